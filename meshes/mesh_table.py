#!/usr/bin/env python3
"""Mesh levels table (Markdown) of some or all cases: ``meshes/mesh_table.py [CASE ...]
[--domains [--check]] [--json]``.

Same arguments as ``floatfoam mesh table`` (see floatfoam.cli.mesh).
"""

import sys

from floatfoam.cli import mesh

if __name__ == "__main__":
    sys.exit(mesh.script_main("mesh_table.py", __doc__, mesh.add_table_arguments,
                              mesh.run_table))
