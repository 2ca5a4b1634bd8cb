"""The build's helper process (`python -m crankgen.engine.helper ITEM ...`, started by build.py):
compiles the items it is given, from the back of the list, beside the process that started it.

It imports the modules that register the engine's entry points (batch, shooting) before
build runs them, so that build.py itself imports none of them."""

import sys

from . import batch, shooting  # noqa: F401  (each registers its entry point with build.entry_point)
from .build import main

if __name__ == "__main__":
    sys.exit(main())
