#!/usr/bin/env python3
"""Body STL of a case at a mesh level, with its discrete volume error: ``meshes/body_surface.py
CASE [--level coarse|medium|fine|all] [--pose body|equilibrium|release] [--out DIR]``.

Same arguments as ``floatfoam mesh body`` (see floatfoam.cli.mesh).
"""

import sys

from floatfoam.cli import mesh

if __name__ == "__main__":
    sys.exit(mesh.script_main("body_surface.py", __doc__, mesh.add_body_arguments,
                              mesh.run_body))
