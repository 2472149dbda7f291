"""``python -m floatfoam.cli``: the same as the ``floatfoam`` console script."""

import sys

from floatfoam.cli import main

sys.exit(main())
