"""JSON as floatfoam writes it: NaN and inf as null (JSON has neither), indented."""

from __future__ import annotations

import json
import math


def dump_json(data) -> str:
    """JSON with NaN/inf written as null (JSON has neither)."""
    def clean(x):
        if isinstance(x, float) and not math.isfinite(x):
            return None
        if isinstance(x, dict):
            return {k: clean(v) for k, v in x.items()}
        if isinstance(x, (list, tuple)):
            return [clean(v) for v in x]
        return x

    return json.dumps(clean(data), indent=2, allow_nan=False)
