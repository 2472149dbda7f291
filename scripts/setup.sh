#!/usr/bin/env bash
# Bring a Debian 12 machine up to date for floatfoam: apt packages and a pinned .venv.
# Idempotent and quick when already done (checks before installing). Run as root.
set -eu
cd "$(dirname "$0")/.."

# OpenFOAM v1912 (ESI) from Debian, MPI, the headless GL/X libraries that the gmsh and vtk
# wheels load, python3-venv for the venv, shellcheck for the lint, g++ and bzip2 to rebuild
# interFoam from Debian's source package (scripts/build_solver.sh), Slurm's daemons, client and
# munge for the cluster tests' one-node Slurm (scripts/slurm_local.sh; none is started here).
APT_PACKAGES="openfoam openmpi-bin libglu1-mesa libgl1 libxcursor1 libxft2 libxinerama1
libgomp1 libegl1 libgl1-mesa-dri python3-venv shellcheck g++ bzip2 dpkg-dev
munge slurmctld slurmd slurm-client"

missing=""
for pkg in $APT_PACKAGES; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "ok installed" || missing="$missing $pkg"
done
if [ -n "$missing" ]; then
  echo "setup: installing apt packages:$missing"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  # shellcheck disable=SC2086  # word splitting of the package list is intended
  apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi

# interFoam rebuilt without the GCC 12 vectoriser bug of Debian's binary (docs/openfoam-v1912.md),
# beside the Python install: one core compiles (and downloads and unpacks the sources) while the
# other unpacks the wheels. Each runs in a session of its own (scripts/sessions.sh), so that an
# error, SIGINT or SIGTERM here stops both, with everything they started, and waits for them
# before this script ends (a failed build is seen at its final wait, after pip); a SIGKILL here
# ends them within a second.
# shellcheck source=scripts/sessions.sh
. scripts/sessions.sh
trap stop_groups EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

session bash scripts/build_solver.sh &
solver=$!
groups="$solver"

PYTHON=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  echo "setup: creating .venv"
  "$PYTHON" -m venv .venv || { rm -rf .venv; /usr/bin/python3 -m venv .venv; }
fi
stamp=.venv/.floatfoam-deps
want=$(sha256sum pyproject.toml | cut -d' ' -f1)
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
  echo "setup: installing Python dependencies (pinned in pyproject.toml)"
  in_background .venv/bin/python -m pip install -q --upgrade pip
  in_background .venv/bin/python -m pip install -q -e ".[dev]"
  echo "$want" > "$stamp"
fi

wait "$solver"
trap - EXIT
