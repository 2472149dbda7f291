"""The packages' layering: the theory and the potential flow stand below the meshers and the
run, so they import neither (their shared pieces, the tank and poses and the gmsh session,
live below all of them: floatfoam.tank, floatfoam.gmshio)."""

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "floatfoam"


def imported(path: Path) -> set[str]:
    """Every module ``path`` imports, at its top or inside a function."""
    names = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names |= {node.module, *(f"{node.module}.{alias.name}" for alias in node.names)}
    return names


@pytest.mark.parametrize("package", ["hydrostatics", "potential"])
def test_theory_and_potential_flow_import_no_mesher_and_no_run(package):
    files = sorted((SRC / package).glob("*.py"))
    assert files
    for path in files:
        above = {name for name in imported(path)
                 if name.startswith(("floatfoam.meshing", "floatfoam.foam"))}
        assert not above, f"{path.relative_to(SRC)} imports {sorted(above)}"
