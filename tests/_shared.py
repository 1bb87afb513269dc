"""Where the shared test material lies: ../shared beside the repository
(the resvg suite with its fonts and resources, and the corpus).  CI always
has it; tests that read it fail, rather than skip, when it is missing."""

import os

SHARED = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                       '..', '..', 'shared'))
SUITE_ROOT = os.path.join(SHARED, 'resvg-suite')
SUITE_TESTS = os.path.join(SUITE_ROOT, 'tests')
SUITE_FONTS = os.path.join(SUITE_ROOT, 'fonts')
SUITE_RESOURCES = os.path.join(SUITE_ROOT, 'resources')
CORPUS = os.path.join(SHARED, 'corpus')
