"""Regenerate the golden reference PNGs with resvg (resvg-py, pinned in the
test extra), an independent renderer.  Runs only on request:

    python golden/regenerate.py            # every case
    python golden/regenerate.py stroke-    # cases whose name contains 'stroke-'

The options reproduce resvg's own defaults (usvg::Options), as the
conformance scorer does: dpi 96, font size 12, language 'en'; and the
resvg suite's fonts only (``../shared/resvg-suite/fonts``, no system
fonts) with its harness's generic families, so that text references do
not depend on the machine (``raster.testing.suite_fonts`` gives raster the
same fonts in tests/test_golden.py).

Where resvg does not follow a rule a case pins down (the case's <desc>
says why; ``@font-face``, which usvg ignores, is one), golden/equivalent/NAME.svg
draws what the rule asks for without the feature (for @font-face: the
installed family instead of the document's one), and resvg's rendering of
that equivalent is the reference.
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = os.path.join(HERE, 'cases')
EQUIVALENT = os.path.join(HERE, 'equivalent')
SUITE_FONTS = os.path.normpath(os.path.join(HERE, '..', '..', 'shared', 'resvg-suite', 'fonts'))


def render_reference(svg_path):
    """PNG bytes of resvg's rendering of ``svg_path`` at its natural size."""
    import resvg_py
    sys.path.insert(0, os.path.dirname(HERE))
    from raster.testing import SUITE_DEFAULT_FAMILY, SUITE_GENERIC_FAMILIES as g
    return bytes(resvg_py.svg_to_bytes(
        svg_path=svg_path, resources_dir=os.path.dirname(svg_path),
        dpi=96.0, font_size=12.0, languages=['en'], font_family=SUITE_DEFAULT_FAMILY,
        skip_system_fonts=True, font_dirs=[SUITE_FONTS], serif_family=g['serif'],
        sans_serif_family=g['sans-serif'], cursive_family=g['cursive'],
        fantasy_family=g['fantasy'], monospace_family=g['monospace']))


def main(argv):
    names = sorted(f[:-4] for f in os.listdir(CASES) if f.endswith('.svg'))
    if argv:
        names = [n for n in names if any(a in n for a in argv)]
    for n in names:
        eq = os.path.join(EQUIVALENT, n + '.svg')
        png = render_reference(eq if os.path.exists(eq) else os.path.join(CASES, n + '.svg'))
        with open(os.path.join(CASES, n + '.png'), 'wb') as f:
            f.write(png)
        print('wrote', n + '.png')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
