"""Where the shared test material lies: ../shared beside the repository
(the resvg suite with its fonts and resources, and the corpus).  CI always
has it; tests that read it fail, rather than skip, when it is missing.
Also :func:`load_bench`, the scripts of bench/ as modules for their tests."""

import importlib.util
import os

SHARED = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                       '..', '..', 'shared'))
SUITE_ROOT = os.path.join(SHARED, 'resvg-suite')
SUITE_TESTS = os.path.join(SUITE_ROOT, 'tests')
SUITE_FONTS = os.path.join(SUITE_ROOT, 'fonts')
SUITE_RESOURCES = os.path.join(SUITE_ROOT, 'resources')
CORPUS = os.path.join(SHARED, 'corpus')

BENCH = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'bench')


def load_bench(name):
    """The script ``bench/<name>.py`` loaded as a module (bench/ is not a
    package)."""
    spec = importlib.util.spec_from_file_location(name, os.path.join(BENCH, name + '.py'))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod
