"""floatfoam: oscillation and stability of floating bodies (Le Barbier 1817 to CFD)."""

from __future__ import annotations


def package_version() -> str:
    """floatfoam's version: the installed package's (importlib.metadata), else, in a source
    tree that was never installed, pyproject.toml's — the one place the number is written."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("floatfoam")
    except PackageNotFoundError:
        import tomllib
        from pathlib import Path

        pyproject = Path(__file__).resolve().parents[2] / "pyproject.toml"
        with open(pyproject, "rb") as handle:
            return tomllib.load(handle)["project"]["version"]


#: the public API: each name and the module it lives in, imported when first asked for (so
#: that ``import floatfoam`` stays light and the command line loads only what it uses).
#: The command line (:mod:`floatfoam.cli`) is a layer over these; the generated
#: docs/reference/api.md (`make docs`) lists them with an example.
API = {
    # a case: the body, its mass, the fluid, the release, the tank and the run's settings
    "Case": "floatfoam.case",
    "load_case": "floatfoam.case",
    "with_overrides": "floatfoam.case",
    "InputError": "floatfoam.errors",
    # theory: exact hydrostatics, equilibrium, stability, linear periods, GZ
    "equilibrium": "floatfoam.hydrostatics.theory",
    "theory_summary": "floatfoam.hydrostatics.theory",
    "gz_curve": "floatfoam.hydrostatics.gz",
    # potential flow: added mass, radiation damping, periods with added inertia, decay models
    "radiation_coefficients": "floatfoam.potential.radiation",
    "potential_summary": "floatfoam.potential.radiation",
    "decay_series": "floatfoam.potential.models",
    # the CFD run, its record and its analysis
    "run_case": "floatfoam.foam.driver",
    "read_motion": "floatfoam.motion",
    "analyse_decay": "floatfoam.analysis.decay",
    # the convergence study and the report
    "run_study": "floatfoam.workflow",
    "validate_case": "floatfoam.analysis.validation",
    "build_report": "floatfoam.analysis.report",
}
__all__ = [*API, "package_version", "__version__"]


def __getattr__(name: str):
    """A name of the public API (:data:`API`) or ``floatfoam.__version__``, looked up when
    asked for (not on every import)."""
    if name == "__version__":
        return package_version()
    if name in API:
        import importlib

        value = getattr(importlib.import_module(API[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'floatfoam' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
