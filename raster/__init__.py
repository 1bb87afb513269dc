"""raster: a vector-graphics rasterizer, SVG toolchain and curve toolkit.

The front door (see README.md):

* :func:`parse_path` -- SVG path data to an immutable :class:`Path`;
* :func:`flatten` -- a path to polylines within a tolerance in device pixels;
* :func:`bbox` -- exact bounding box of a path;
* :func:`stroke` -- the outline of a path's stroke (a :class:`StrokeStyle`);
* :func:`render` / :func:`render_image` -- an SVG document to an RGBA array or
  a PIL image;
* :func:`svg2png` -- CairoSVG's ``svg2png`` (PNG bytes or a file), see
  :mod:`raster.compat`;
* :class:`FontOptions` -- the fonts of text, for every function above that
  takes ``fonts=`` (default: the system's fonts), see :mod:`raster.fonts`.

The Pillow plugin (``Image.open('x.svg')``) is :mod:`raster.pillow`; it is
registered by ``raster.pillow.register()`` or ``import raster.pillow.auto``,
never by ``import raster``.

The geometry behind them is the kernel :mod:`raster.geometry`.  Names are
imported lazily: ``import raster`` loads only :mod:`raster.errors` (no
numpy), so that it stays fast.
"""

from .errors import (RasterError, PathError, TransformError, CanvasError,  # noqa: F401
                     LimitError, InputLimitError, SVGError, FormatError, RasterIOError)

__version__ = '0.1.0'

# Everything else is imported on first use: ``import raster`` (and so
# ``import raster.errors`` in a command that has not parsed its arguments
# yet) loads neither numpy nor any other module of the package.
_LAZY = {
    'Path': 'raster.geometry.path',
    'PathBuilder': 'raster.geometry.pens',
    'TransformPen': 'raster.geometry.pens',
    'RecordingPen': 'raster.geometry.pens',
    'Affine': 'raster.geometry.transform',
    'parse_path': 'raster.geometry.pathdata',
    'flatten': 'raster.geometry.flattening',
    'Polylines': 'raster.geometry.flattening',
    'bbox': 'raster.geometry.bounds',
    'BoundsPen': 'raster.geometry.pens',
    'stroke': 'raster.geometry.stroking',
    'StrokeStyle': 'raster.geometry.stroking',
    'LineJoin': 'raster.geometry.stroking',
    'LineCap': 'raster.geometry.stroking',
    'FillRule': 'raster.geometry.rules',
    'coverage': 'raster.pixels.scan',
    'path_coverage': 'raster.pixels.scan',
    'Canvas': 'raster.pixels.canvas',
    'render': 'raster.svg',
    'render_image': 'raster.svg',
    'load_svg': 'raster.svg',
    'svg2png': 'raster.compat',
    'FontOptions': 'raster.fonts',
    'FontError': 'raster.fonts',
    'Limits': 'raster.limits',
}


def __getattr__(name):
    import importlib
    if name == 'limits':                # the budgets (raster.limits), a module
        return importlib.import_module('raster.limits')
    mod = _LAZY.get(name)
    if mod is None:
        raise AttributeError('module raster has no attribute %r' % name)
    value = getattr(importlib.import_module(mod), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY) | {'limits'})
