"""Fonts: discovery, the scan cache, CSS matching, loading, colour glyphs.

* :mod:`raster.fonts.options` -- :class:`FontOptions`, where fonts come
  from (the system's fonts by default, folders, files) and how generic
  families resolve;
* :mod:`raster.fonts.discovery` -- the system's font folders (Linux,
  macOS, Windows, fontconfig) and the persistent scan cache;
* :mod:`raster.fonts.files` -- reading font files safely (limits, WOFF and
  WOFF2 inflated with bounds) and what a scan records about a face;
* :mod:`raster.fonts.matching` -- :class:`FontDB`: generic families,
  metric-compatible aliases, CSS weight/style/stretch matching, per
  character fallback, the bundled fallback font;
* :mod:`raster.fonts.font` -- :class:`Font`: shaping, metrics and packed
  glyph outlines (HarfBuzz);
* :mod:`raster.fonts.color` -- colour glyphs (COLRv0, COLRv1, sbix,
  CBDT/CBLC, SVG) as neutral layer descriptions.

>>> from raster.fonts import parse_font_family       # a lazy name: not a global yet
>>> parse_font_family('"Noto Sans", Arial ,serif')
['Noto Sans', 'Arial', 'serif']
"""

import importlib

from .options import FontOptions

#: Names of the heavier submodules, imported on first use (a document
#: without text loads only :mod:`raster.fonts.options`).
_LAZY = {'FONT_EXTENSIONS': 'files', 'FontError': 'files', 'FontFace': 'files',
         'Font': 'font', 'Shaped': 'font', 'register_memory_font': 'font',
         'BUNDLED_FONT': 'matching', 'FAMILY_CLASSES': 'matching',
         'GENERIC_PREFERENCES': 'matching', 'METRIC_ALIASES': 'matching', 'FontDB': 'matching',
         'cached': 'matching', 'generic_keyword': 'matching', 'parse_font_family': 'matching'}


def __getattr__(name):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError('module %r has no attribute %r' % (__name__, name))
    value = getattr(importlib.import_module('.' + module, __name__), name)
    globals()[name] = value
    return value


__all__ = ['FontError', 'FontFace', 'FontDB', 'Font', 'Shaped', 'FontOptions',
           'parse_font_family', 'generic_keyword', 'cached', 'register_memory_font',
           'GENERIC_PREFERENCES', 'METRIC_ALIASES', 'FAMILY_CLASSES', 'BUNDLED_FONT',
           'FONT_EXTENSIONS', 'DEFAULT_FAMILY']

#: The family usvg (and so the conformance harness) gives text without a
#: ``font-family``; raster's own default is the ``serif`` generic family.
DEFAULT_FAMILY = 'Times New Roman'
