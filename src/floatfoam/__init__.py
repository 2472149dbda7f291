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


def __getattr__(name: str):
    """``floatfoam.__version__``, looked up when asked for (not on every import)."""
    if name == "__version__":
        return package_version()
    raise AttributeError(f"module 'floatfoam' has no attribute {name!r}")
