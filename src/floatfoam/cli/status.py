"""``floatfoam status [JOB ...]``: the jobs submitted with ``floatfoam batch --submit`` and
``floatfoam validate --slurm``, each task's case, run, state, simulated time and ETA (from the
queue and the runs' own logs); ``--summary`` analyses a job's finished runs."""

from __future__ import annotations

from pathlib import Path

from floatfoam.cli.common import dump_json


def register(sub) -> None:
    p = sub.add_parser("status", help="the state of submitted Slurm jobs: each task's run, "
                       "time reached and ETA")
    p.add_argument("jobs", nargs="*", metavar="JOB",
                   help="job ids that batch --submit or validate --slurm printed, or their "
                   "submission folders <build>/slurm/<name>-<n> (default: every job submitted "
                   "from this build folder, newest first)")
    p.add_argument("--summary", action="store_true",
                   help="analyse each task's finished run (damped period and damping ratio of "
                   "the released DoFs) and write summary.md and summary.json in the "
                   "submission's folder")
    p.set_defaults(func=run)


def run(args) -> int:
    from floatfoam import layout
    from floatfoam.cluster import jobs, slurm

    records = jobs.read_records(args.jobs or None)
    if not records:
        print(f"no job submitted from {layout.build_dir()} (floatfoam batch --submit, "
              "floatfoam validate --slurm)")
        return 0
    if args.summary:
        for record in records:
            entries = jobs.summary(record)
            text = jobs.summary_markdown(record, entries)
            base = Path(record["folder"]) / "summary"
            base.with_suffix(".md").write_text(text)
            base.with_suffix(".json").write_text(dump_json(entries) + "\n")
            print(text + f"written: {base}.md, {base}.json")
        return 0
    ids = [r["job"] for r in records] + [r["after"] for r in records if r.get("after")]
    queued = slurm.queue(ids)
    if queued is None:
        print("(Slurm's queue cannot be asked here: states are the runs' own)")
    for n, record in enumerate(records):
        if n:
            print()
        print(f"job {record['job']}: {record['kind']} {record['label']}, submitted "
              f"{record['submitted']} ({record['folder']})")
        print("\n".join("  " + line for line in
                        jobs.table(jobs.task_rows(record, queued))))
        after = jobs.after_state(record, queued)
        if after:
            what = "study" if record["kind"] == "validate" else "summary"
            print(f"  then job {record['after']} ({what}): {after}")
    return 0
