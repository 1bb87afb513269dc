"""Test-suite setup: the helper modules of tests/ (``_shared``,
``_geometry``) are importable from test files in any sub-folder (the suite
mirrors the package layout: tests/geometry, tests/parser, ...)."""

import os
import sys

_HERE = os.path.dirname(os.path.abspath(__file__))
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)
