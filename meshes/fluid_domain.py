#!/usr/bin/env python3
"""Fluid domain of a case for gmshToFoam (MSH 2.2): ``meshes/fluid_domain.py CASE
[--level coarse|medium|fine|all] [--kind auto|2d|wedge|3d] [--pose release|equilibrium]
[--out FILE] [--check]``.

Same arguments as ``floatfoam mesh domain`` (see floatfoam.cli.mesh).
"""

import sys

from floatfoam.cli import mesh

if __name__ == "__main__":
    sys.exit(mesh.script_main("fluid_domain.py", __doc__, mesh.add_domain_arguments,
                              mesh.run_domain))
