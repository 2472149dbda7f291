# Sourced by scripts/setup.sh: run jobs as sessions of their own, stopped with everything they
# started when the script that started them ends, however it ends.
#
# `stop_groups` (the caller's EXIT trap) stops the sessions listed in $groups and waits for
# them, on an error, SIGINT or SIGTERM: each session's shell waits for its job to end before it
# does. A SIGKILL of the caller (or of make's process group) cannot be trapped and does not
# reach sessions of their own: each session therefore holds a watcher that stops it within a
# second once its shell's parent, the caller, is gone (reaped or not). Job control off: a
# background job is then never a group leader, so setsid does not fork and $! is the new
# session's process group.
# shellcheck shell=bash
set +m
groups=""
stop_groups() {
  local group
  for group in $groups; do kill -- -"$group" 2>/dev/null || true; done
  wait 2>/dev/null || true
}
session() {  # `session CMD... &`: CMD as a session of its own, ended when this script is gone
  # (exec: $! is then the session, its process group). The session's shell runs CMD and a
  # watcher; a SIGTERM to the session ends both and the shell waits for CMD; when CMD is done,
  # the shell ends the rest of its session (the watcher, anything CMD left).
  if [ "$BASHPID" = "$$" ]; then
    echo "session: run it in the background (session CMD... &)" >&2
    return 2
  fi
  # shellcheck disable=SC2016  # expanded by the session's shell
  exec setsid bash -c '
    parent=$1; shift
    trap : TERM
    "$@" &
    job=$!
    (while read -r _ _ _ ppid _ < /proc/$$/stat && [ "$ppid" = "$parent" ]; do sleep 1; done
     kill -- -$$) 2>/dev/null &
    rc=0; wait "$job" || rc=$?
    while kill -0 "$job" 2>/dev/null; do rc=0; wait "$job" || rc=$?; done  # after a TERM
    trap "" TERM; kill -- -$$ 2>/dev/null
    exit "$rc"' session "$$" "$@"
}
in_background() {  # run "$@" as a session of its own; wait for it (its exit status)
  local pid rc=0
  session "$@" &
  pid=$!
  groups="$groups $pid"
  wait "$pid" || rc=$?
  groups=${groups% "$pid"}  # done: its number may be another process's later
  return "$rc"
}
