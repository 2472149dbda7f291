"""The finished CFD runs of a case under a build folder (:func:`cfd_runs`), those of the
case's settings today (:func:`current_runs`: a run's stamp against the case's digest), and the
note on those left out (:func:`stale_note`)."""

from __future__ import annotations

from pathlib import Path

from floatfoam import layout


def cfd_runs(case_name: str, build_dir: str | Path) -> list[tuple[str, Path]]:
    """(level, motion.csv) of every finished run of the case under ``build_dir``, coarse to
    fine: a level folder whose driver marked it finished (unfinished, diverged and moved-aside
    ``<level>.old-<date>`` runs are left out)."""
    runs = ((level, layout.run_dir(case_name, level, Path(build_dir))) for level in layout.LEVELS)
    return [(level, run / "motion.csv") for level, run in runs
            if (run / "motion.csv").is_file() and layout.is_finished(run)]


def current_runs(case, build_dir: str | Path) -> tuple[list[tuple[str, Path]], list[str]]:
    """:func:`cfd_runs` of ``case`` whose stamp is of the case's settings today (or that have
    none: made by hand), and the levels of those made with other settings (its case file, a
    --set or a default changed since): a run of other settings is not this case's CFD."""
    from floatfoam.plan.stamps import stamped_with

    runs, foreign = [], []
    for level, motion in cfd_runs(case.name, build_dir):
        if stamped_with(case, level, motion.parent) is False:
            foreign.append(level)
        else:
            runs.append((level, motion))
    return runs, foreign


def stale_note(case_name: str, names: list[str], study: bool = False) -> str:
    """The report's line on runs (or the study made of them) left out because the runs were
    made with other settings than the case's today."""
    what = "The grid and time-step study is" if study else "CFD runs are"
    again = f", then `floatfoam validate {case_name}`" if study else ""
    return (f"{what} left out: {', '.join(names)} made with other settings than the case's "
            "today (its case file, a --set, a default or the shared dictionaries changed "
            f"since). Run again with the run's own options and --force (`floatfoam run "
            f"{case_name} --level LEVEL`, with `--dt-divisor K` or `--morphing F` for a "
            f"`-dtK` or `-morphF` run), which sets the old run aside{again}")
