"""Building a tree leaves no reference cycles behind (issue 17): the
commands pause the garbage collector, so whatever a cycle holds (a text
element's spans, the lxml elements they name) would stay until the
process ends."""

import gc

import raster
from _shared import SUITE_FONTS

FONTS = raster.FontOptions(dirs=[SUITE_FONTS], system=False)

DOC = b'''<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink"
     width="60" height="30">
  <defs><g id="a"><rect width="4" height="4"/><use xlink:href="#b" x="5"/></g>
        <circle id="b" r="2" cx="2" cy="2"/></defs>
  <text x="2" y="12" font-family="Noto Sans" font-size="9">Hi <tspan dy="2">there</tspan>
    <tspan x="30 34 38" rotate="5">abc</tspan></text>
  <use xlink:href="#a" y="16"/><use xlink:href="#a" x="20" y="16"/>
</svg>'''


def _garbage(fn):
    """The objects of the cycles ``fn()`` leaves (collected with the
    collector saving them), the collector's state restored."""
    was = gc.isenabled()
    gc.disable()
    gc.collect()
    gc.set_debug(gc.DEBUG_SAVEALL)
    try:
        fn()
        gc.collect()
        return list(gc.garbage)
    finally:
        gc.set_debug(0)
        gc.garbage.clear()
        if was:
            gc.enable()


def test_text_and_use_leave_no_cycles():
    raster.load_svg(DOC, fonts=FONTS)          # modules and fonts loaded once
    left = _garbage(lambda: raster.load_svg(DOC, fonts=FONTS))
    names = sorted({type(o).__name__ for o in left})
    # (one small cycle per document remains: the CSS @import loader, which
    # calls itself for nested imports, with the options it reads)
    assert not [o for o in left if type(o).__name__ in ('_Span', '_Element')], names
    assert len(left) < 40, names


LEAVES = b'''<svg xmlns="http://www.w3.org/2000/svg" width="60" height="40">
  <text x="2" y="12" font-family="Noto Sans" font-size="9">first</text>
  <text x="2" y="24" font-family="Noto Sans" font-size="9">leaf</text>
  <text x="2" y="36" font-family="Noto Sans" font-size="9" fill="red">texts</text>
</svg>'''


def test_leaf_texts_leave_no_cycles():
    # text elements with character data only take the leaf path, whose
    # styles are remembered in the document's cache with a fallback
    # function using that cache: the memo tables are released with the
    # build, so neither the cache nor the lxml elements outlive it
    from raster.parser.context import Cache
    raster.load_svg(LEAVES, fonts=FONTS)
    left = _garbage(lambda: raster.load_svg(LEAVES, fonts=FONTS))
    names = sorted({type(o).__name__ for o in left})
    assert not [o for o in left if isinstance(o, Cache)], names
    assert not [o for o in left if type(o).__name__ in ('_LeafStyle', '_Element')], names
    assert len(left) < 40, names
