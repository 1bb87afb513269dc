"""Regenerate the golden reference PNGs with resvg (resvg-py, pinned in the
test extra), an independent renderer.  Runs only on request:

    python golden/regenerate.py            # every case
    python golden/regenerate.py stroke-    # cases whose name contains 'stroke-'

The options reproduce resvg's own defaults (usvg::Options), as the
conformance scorer does: dpi 96, font size 12, language 'en'.

Where resvg does not follow a rule a case pins down (the case's <desc>
says why), golden/equivalent/NAME.svg draws what the rule asks for without
the feature, and resvg's rendering of that equivalent is the reference.
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = os.path.join(HERE, 'cases')
EQUIVALENT = os.path.join(HERE, 'equivalent')


def render_reference(svg_path):
    """PNG bytes of resvg's rendering of ``svg_path`` at its natural size."""
    import resvg_py
    return bytes(resvg_py.svg_to_bytes(
        svg_path=svg_path, resources_dir=os.path.dirname(svg_path),
        dpi=96.0, font_size=12.0, languages=['en'], font_family='Times New Roman'))


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
