"""raster: a vector-graphics rasterizer, SVG toolchain and curve toolkit.

The front door (see README.md):

* :func:`parse_path` -- SVG path data to an immutable :class:`Path`;
* :func:`flatten` -- a path to polylines within a tolerance in device pixels;
* :func:`bbox` -- exact bounding box of a path;
* :func:`render` / :func:`render_image` -- an SVG document to an RGBA array or
  a PIL image;
* :func:`svg2png` -- CairoSVG's ``svg2png`` (PNG bytes or a file), see
  :mod:`raster.compat`.

The Pillow plugin (``Image.open('x.svg')``) is :mod:`raster.pillow`; it is
registered by ``raster.pillow.register()`` or ``import raster.pillow.auto``,
never by ``import raster``.

Names are imported lazily so that ``import raster`` stays fast.
"""

from .errors import (RasterError, PathError, TransformError, CanvasError,  # noqa: F401
                     LimitError, SVGError, FormatError, RasterIOError)
from .path import Path, PathBuilder, TransformPen, RecordingPen  # noqa: F401
from .transform import Affine  # noqa: F401

__version__ = '0.1.0'

_LAZY = {
    'parse_path': 'raster.svgpath',
    'StrokeStyle': 'raster.stroke',
    'coverage': 'raster.scan',
    'path_coverage': 'raster.scan',
    'Canvas': 'raster.canvas',
    'render': 'raster.svg',
    'render_image': 'raster.svg',
    'load_svg': 'raster.svg',
    'svg2png': 'raster.compat',
}


def __getattr__(name):
    mod = _LAZY.get(name)
    if mod is None:
        raise AttributeError('module raster has no attribute %r' % name)
    import importlib
    value = getattr(importlib.import_module(mod), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


# `flatten` and `bbox` name both a public function and its submodule.  Bind
# the functions now: importing a submodule binds the package attribute to the
# module, which would otherwise shadow the lazy name (raster.flatten(path)
# failing after `from raster.flatten import ...`).  Both modules need only
# numpy.
from .flatten import flatten, Polylines  # noqa: E402,F401
from .bbox import bbox  # noqa: E402,F401
