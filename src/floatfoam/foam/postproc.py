"""Read OpenFOAM function-object output of a run directory."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def max_speed(run_dir: Path) -> np.ndarray:
    """(time, max |U|) per time step from the ``minmaxU`` fieldMinMax output (tab-separated
    columns: time, field, min, location(min), max, location(max))."""
    files = sorted(Path(run_dir).glob("postProcessing/minmaxU/*/fieldMinMax*.dat"))
    rows = []
    for path in files:
        for line in path.read_text().splitlines():
            if line.startswith("#") or not line.strip():
                continue
            cells = line.split("\t")
            rows.append((float(cells[0]), float(cells[4])))
    return np.array(rows).reshape(-1, 2)
