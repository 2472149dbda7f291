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


@pytest.mark.parametrize("package", ["hydrostatics", "potential", "analysis", "plan"])
def test_theory_potential_flow_plan_and_analysis_import_no_mesher_and_no_run(package):
    # the analysis reads what a run recorded (its stamp, its info.json) and the plan's rules;
    # it neither meshes nor runs
    files = sorted((SRC / package).glob("*.py"))
    assert files
    for path in files:
        above = {name for name in imported(path)
                 if name.startswith(("floatfoam.meshing", "floatfoam.foam"))}
        assert not above, f"{path.relative_to(SRC)} imports {sorted(above)}"


def module_file(name: str) -> Path | None:
    """The source file of a floatfoam module name (None for a name that is no module)."""
    parts = name.split(".")[1:]
    for path in (SRC.joinpath(*parts).with_suffix(".py"), SRC.joinpath(*parts, "__init__.py")):
        if parts and path.is_file():
            return path
    return None


def reachable(name: str) -> set[str]:
    """Every floatfoam module that importing ``name`` can load, directly or through others,
    at their tops or inside their functions."""
    seen, todo = set(), [name]
    while todo:
        path = module_file(todo.pop())
        if path is None or path in seen:
            continue
        seen.add(path)
        todo += [n for n in imported(path) if n.startswith("floatfoam.")]
    return {str(path.relative_to(SRC)) for path in seen}


@pytest.mark.parametrize("module", ["floatfoam.tank", "floatfoam.gmshio"])
def test_the_shared_pieces_reach_no_stage_above_them(module):
    # not even lazily: a function-level import of the theory from the tank was a loop
    # (hydrostatics → tank → hydrostatics) that the direct check above did not see
    stages = ("hydrostatics/", "potential/", "meshing/", "foam/", "analysis/", "cli/")
    above = sorted(p for p in reachable(module) if p.startswith(stages))
    assert reachable(module) and not above, f"{module} reaches {above}"


def test_the_plan_reaches_no_mesher_no_run_and_no_analysis():
    # a run's plan is resolved before anything is meshed or run; the analysis reads it
    stages = ("meshing/", "foam/", "analysis/", "cli/")
    found = set()
    for path in sorted((SRC / "plan").glob("*.py")):
        found |= reachable("floatfoam.plan." + path.stem)
    above = sorted(p for p in found if p.startswith(stages))
    assert found and not above, f"floatfoam.plan reaches {above}"
