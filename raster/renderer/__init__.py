"""The renderer: a resolved :class:`raster.tree.Tree` onto a canvas.

Coordinates: the tree's root group maps user space to *document pixels*
(the natural size ``tree.width x tree.height``); :func:`output_size`
chooses the output size in device pixels and the scale from document to
device pixels.

Modules: :mod:`.draw` (the loop over the tree), :mod:`.batch` (masks of
many paths at once), :mod:`.bounds` (device boxes of nodes),
:mod:`.paint` (gradients, patterns' sampling, raster images),
:mod:`.filters` (filter primitives on a layer).  The renderer imports the
tree, the geometry kernel and the pixel layer; never the parser.

>>> from raster.geometry.path import Path
>>> from raster.tree import Tree, Group, PathNode, Fill, SolidPaint
>>> sq = Path.polygon([(2, 2), (8, 2), (8, 8), (2, 8)])
>>> tree = Tree(10, 10, Group(children=[PathNode(path=sq, fill=Fill(SolidPaint((1, 0, 0, 1))))]))
>>> img = render_tree(tree).to_rgba8()
>>> img.shape, img[5, 5].tolist(), img[0, 0].tolist()
((10, 10, 4), [255, 0, 0, 255], [0, 0, 0, 0])
"""

import math
from typing import NamedTuple, Optional, Tuple

from .. import limits
from ..errors import CanvasError, SVGError
from ..pixels.canvas import Canvas
from ..geometry.transform import IDENTITY, Affine
from ..tree import Group, Tree
from ..tree.extent import drawn_box
from .draw import Renderer

__all__ = ['render_tree', 'output_size', 'output_geometry', 'OutputGeometry', 'find_node', 'DEFAULT_TOLERANCE',
           'Renderer']

#: Default flattening tolerance in device pixels.  The renderer flattens
#: into straddled polylines (:func:`raster.geometry.flattening.flatten`
#: with ``straddle=True``): at 0.05 the drawn edge of a smooth curve lies
#: within about 1/40 px of it, on both sides, so a curved edge's coverage
#: is within about 8/255 of the exact area (bench/bench_coverage.py).
DEFAULT_TOLERANCE = 0.05


def _positive(name, v):
    try:
        f = float(v)
    except (TypeError, ValueError):
        raise CanvasError('%s must be a number, got %r' % (name, v)) from None
    if not math.isfinite(f) or f <= 0:
        raise CanvasError('%s must be positive and finite, got %r' % (name, v))
    return f


def output_size(doc_width: float, doc_height: float, width: Optional[int] = None,
                height: Optional[int] = None,
                zoom: Optional[float] = None) -> Tuple[int, int, float, float]:
    """Output size in pixels and the document-to-device scale.

    Parameters
    ----------
    doc_width, doc_height : float
        The document's natural size in px (> 0).
    width, height : int or None
        Requested output size.  Only ``width``: the height keeps the aspect
        ratio of the natural pixel size (rounded half up), the scaled side
        rounded up; only ``height``: likewise for the width; both:
        non-uniform scale.
    zoom : float or None
        Scale factor of the natural size (not with ``width``/``height``).

    Returns
    -------
    (w, h, sx, sy)
        Integer output size and the scales mapping document px to device
        px (``w / doc_width``, ``h / doc_height``).

    Raises
    ------
    CanvasError
        A size or zoom that is not positive and finite, both zoom and a
        size, or an output of more than :data:`raster.limits.MAX_PIXELS`
        pixels or a side above :data:`raster.limits.MAX_SIDE`.

    >>> output_size(100, 50)
    (100, 50, 1.0, 1.0)
    >>> output_size(100, 50, width=300)
    (300, 150, 3.0, 3.0)
    >>> output_size(100, 50, zoom=1.5)
    (150, 75, 1.5, 1.5)
    >>> output_size(10.5, 10, width=20)[:2]          # natural pixel size 11 x 10
    (20, 19)
    """
    dw = _positive('document width', doc_width)
    dh = _positive('document height', doc_height)
    if zoom is not None and (width is not None or height is not None):
        raise CanvasError('give a zoom or an output size, not both')
    # natural pixel size: rounded half up, as resvg does (1000 x 507.224 ->
    # 1000 x 507; 10.5 x 10 -> 11 x 10)
    nw, nh = max(1, math.floor(dw + 0.5)), max(1, math.floor(dh + 0.5))
    if zoom is not None:
        z = _positive('zoom', zoom)
        w, h = math.ceil(nw * z), math.ceil(nh * z)
    elif width is not None and height is not None:
        w, h = _positive('width', width), _positive('height', height)
    elif width is not None:
        w = _positive('width', width)
        h = math.ceil(w * nh / nw)
    elif height is not None:
        h = _positive('height', height)
        w = math.ceil(h * nw / nh)
    else:
        w, h = nw, nh
    if w != int(w) or h != int(h):
        raise CanvasError('output size must be whole pixels, got %r x %r' % (w, h))
    w, h = int(w), int(h)
    if w > limits.MAX_SIDE or h > limits.MAX_SIDE or w * h > limits.MAX_PIXELS:
        raise CanvasError('output size %d x %d exceeds the limit (%d px per side, %d pixels)'
                          % (w, h, limits.MAX_SIDE, limits.MAX_PIXELS))
    return w, h, w / dw, h / dh


def render_tree(tree: Tree, width: Optional[int] = None, height: Optional[int] = None,
                zoom: Optional[float] = None,
                background: Optional[Tuple[float, float, float, float]] = None,
                node_id: Optional[str] = None, tolerance: float = DEFAULT_TOLERANCE,
                crop: bool = False, dtype='float32') -> Canvas:
    """Render a resolved tree.

    Parameters
    ----------
    tree : raster.tree.Tree
    width, height, zoom :
        Output size, see :func:`output_size` (default: the natural size).
    background : RGBA tuple of floats in [0, 1] (straight alpha) or None
        Canvas background (None: transparent).
    node_id : str or None
        Render only the subtree of the node with this id, with the
        transforms of its ancestors.
    tolerance : float
        Flattening tolerance in device pixels (> 0).
    crop : bool
        With ``node_id``: the output is the node's exact drawn box
        (:func:`raster.tree.extent.drawn_box`: strokes, markers and filter
        regions included, clip paths and masks applied) instead of the
        page, and ``width``/``height``/``zoom`` size that box (resvg's
        ``--export-id``).
    dtype : 'float32' or 'uint8' (or the numpy types)
        Storage of the output canvas: float32 (16 bytes a pixel), or 8-bit
        (4 bytes a pixel, each composite onto it rounded to 1/255 as in
        resvg; what :func:`raster.svg.render` and the ``rasterize`` command
        use).  Group layers, clip paths and masks are float32 either way.

    Returns
    -------
    raster.pixels.canvas.Canvas
        Premultiplied RGBA canvas of the output size.

    Raises
    ------
    CanvasError
        Bad output size (see :func:`output_size`) or tolerance.
    SVGError
        ``tree`` is not a Tree, ``node_id`` names no node of it, or the
        node to crop to draws nothing.
    """
    if not isinstance(tree, Tree):
        raise SVGError('render_tree needs a raster.tree.Tree, got %s' % type(tree).__name__)
    tol = _positive('tolerance', tolerance)
    g = output_geometry(tree, width, height, zoom, node_id, crop)
    canvas = Canvas(g.width, g.height, background, dtype)
    Renderer(tol, canvas.dtype).draw(g.node, g.transform, canvas)
    return canvas


class OutputGeometry(NamedTuple):
    """What :func:`render_tree` draws and where: ``node``, the output size
    ``width`` x ``height`` in pixels, ``transform`` (the node's parent
    coordinates to device pixels) and ``scale``, the (x, y) scale of the
    output over document px (over the cropped box's size when cropping)."""
    node: object
    width: int
    height: int
    transform: Affine
    scale: Tuple[float, float]


def output_geometry(tree: Tree, width: Optional[int] = None, height: Optional[int] = None,
                    zoom: Optional[float] = None, node_id: Optional[str] = None,
                    crop: bool = False) -> OutputGeometry:
    """The :class:`OutputGeometry` of a render (arguments as for
    :func:`render_tree`)."""
    if node_id is None:
        node, t = tree.root, IDENTITY
    else:
        node, t = find_node(tree, node_id)
    if crop and node_id is not None:
        box = drawn_box(node, t, tolerance=0.01)
        if box is None or not (box[2] > box[0] and box[3] > box[1]):
            raise SVGError('element %r draws nothing to crop to' % (node_id,))
        w, h, sx, sy = output_size(box[2] - box[0], box[3] - box[1], width, height, zoom)
        t = Affine.translate(-box[0], -box[1]) @ t
    else:
        w, h, sx, sy = output_size(tree.width, tree.height, width, height, zoom)
    return OutputGeometry(node, w, h, Affine.scale(sx, sy) @ t, (sx, sy))


def find_node(tree: Tree, node_id: str):
    """The node with ``node_id`` and the transform of its ancestors (root
    transform included) mapping its coordinates to document px.

    Raises
    ------
    SVGError
        No node has that id.
    """
    target = tree.ids.get(node_id) if isinstance(tree.ids, dict) else None
    stack = [(tree.root, IDENTITY)]
    while stack:
        n, t = stack.pop()
        if n is target or (target is None and getattr(n, 'id', '') == node_id and node_id):
            return n, t
        if isinstance(n, Group):
            t2 = t @ n.transform
            stack.extend((c, t2) for c in reversed(n.children))
    raise SVGError('no element with id %r' % (node_id,))
