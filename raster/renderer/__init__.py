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

import numpy as np

from .. import limits
from ..errors import CanvasError, SVGError
from ..pixels.canvas import Canvas
from ..geometry.transform import IDENTITY, Affine
from ..tree import Group, Tree
from ..tree.extent import drawn_box
from .batch import EdgeStore
from .draw import Renderer

__all__ = ['render_tree', 'output_size', 'output_geometry', 'OutputGeometry', 'find_node', 'DEFAULT_TOLERANCE',
           'Renderer', 'check_window', 'MAX_WINDOWED_PIXELS',
           'EdgeStore']

#: Largest whole output (pixels) that is rendered a window at a time
#: (``render_tree(window=...)``, the strips of ``rasterize``, map tiles):
#: each window is still at most :data:`raster.limits.MAX_PIXELS`.
MAX_WINDOWED_PIXELS = 4_000_000_000

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
                zoom: Optional[float] = None,
                max_pixels: Optional[int] = None) -> Tuple[int, int, float, float]:
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
    max_pixels : int or None
        Largest output in pixels (default :data:`raster.limits.MAX_PIXELS`;
        windowed rendering allows :data:`MAX_WINDOWED_PIXELS`).

    Returns
    -------
    (w, h, sx, sy)
        Integer output size and the scales mapping document px to device
        px (``w / doc_width``, ``h / doc_height``).

    Raises
    ------
    CanvasError
        A size or zoom that is not positive and finite, both zoom and a
        size, or an output of more than ``max_pixels`` pixels or a side
        above ``max_side`` (:mod:`raster.limits`).

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
    lim = limits.current()
    # windowed rendering may allow a larger whole output (max_pixels), never
    # less than the budget
    mp = lim.max_pixels if max_pixels is None else max(max_pixels, lim.max_pixels)
    if w > lim.max_side or h > lim.max_side or w * h > mp:
        raise CanvasError('output size %d x %d exceeds the limit (max_side %d px, max_pixels '
                          '%d)' % (w, h, lim.max_side, mp))
    return w, h, w / dw, h / dh


def render_tree(tree: Tree, width: Optional[int] = None, height: Optional[int] = None,
                zoom: Optional[float] = None,
                background: Optional[Tuple[float, float, float, float]] = None,
                node_id: Optional[str] = None, tolerance: float = DEFAULT_TOLERANCE,
                crop: bool = False, dtype='float32',
                window: Optional[Tuple[int, int, int, int]] = None,
                store: Optional[EdgeStore] = None) -> Canvas:
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
    window : (x0, y0, x1, y1) ints or None
        Render only this rectangle of the output (pixel columns x0 to
        x1 - 1, rows y0 to y1 - 1; 0 <= x0 < x1 <= width, likewise for y):
        the canvas is ``(x1 - x0) x (y1 - y0)`` and holds those pixels of
        the whole render.  Filters, masks, clip paths and patterns that
        reach across the window's border are drawn with the margins they
        need, so windows put side by side equal the whole image (to within
        one level of 255 where a blur's sums round differently).  The
        whole output may then be up to :data:`MAX_WINDOWED_PIXELS` pixels;
        the window at most :data:`raster.limits.MAX_PIXELS`.
    store : raster.renderer.EdgeStore or None
        With ``window``: keeps the edges of outlines that reach past this
        window for the next windows of the same output (pass one store to
        all of them, top to bottom): a path crossing several strips or
        tiles is flattened and stroked once.  The pixels are the same
        with or without it.

    Returns
    -------
    raster.pixels.canvas.Canvas
        Premultiplied RGBA canvas of the output size (of the window).

    Raises
    ------
    CanvasError
        Bad output size (see :func:`output_size`) or tolerance.
    SVGError
        ``tree`` is not a Tree, ``node_id`` names no node of it, or the
        node to crop to draws nothing; a window that is not inside the
        output.
    """
    if not isinstance(tree, Tree):
        raise SVGError('render_tree needs a raster.tree.Tree, got %s' % type(tree).__name__)
    tol = _positive('tolerance', tolerance)
    # hostile numbers overflow in transforms and boxes: the results are
    # checked where they are used (finite, max_coord), not warned about
    with np.errstate(over='ignore', invalid='ignore', divide='ignore'):
        g = output_geometry(tree, width, height, zoom, node_id, crop,
                            max_pixels=None if window is None else MAX_WINDOWED_PIXELS)
        if window is None:
            x0, y0, x1, y1 = 0, 0, g.width, g.height
        else:
            x0, y0, x1, y1 = check_window(window, g.width, g.height)
        canvas = Canvas(x1 - x0, y1 - y0, background, dtype)
        # the whole-render budgets (pixel work, flattened points) of raster.limits
        with limits.metering(limits.Meter(limits.current(), canvas.width * canvas.height)):
            # a window is drawn with the whole output's CTM at its place
            if store is not None:
                store.bind(tree, g.transform, tol, y0)
            Renderer(tol, canvas.dtype, store).draw(g.node, g.transform, canvas,
                                                    origin=(x0, y0), size=(g.width, g.height))
    return canvas


def check_window(window, width: int, height: int) -> Tuple[int, int, int, int]:
    """``window`` as four ints ``(x0, y0, x1, y1)`` with
    ``0 <= x0 < x1 <= width`` and ``0 <= y0 < y1 <= height``.

    Raises
    ------
    CanvasError
        Anything else, or a window of more than
        :data:`raster.limits.MAX_PIXELS` pixels.

    >>> check_window((0, 10, 20, 30), 100, 50)
    (0, 10, 20, 30)
    """
    try:
        vals = tuple(window)
        x0, y0, x1, y1 = (int(v) for v in vals)
        if any(int(v) != v for v in vals):
            raise ValueError
    except (TypeError, ValueError):
        raise CanvasError('window must be four whole numbers (x0, y0, x1, y1), got %r'
                          % (window,)) from None
    if not (0 <= x0 < x1 <= width and 0 <= y0 < y1 <= height):
        raise CanvasError('window %r is not inside the %d x %d output' % (window, width, height))
    if (x1 - x0) * (y1 - y0) > limits.current().max_pixels:
        raise CanvasError('window %d x %d exceeds %d pixels'
                          % (x1 - x0, y1 - y0, limits.current().max_pixels))
    return x0, y0, x1, y1


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
                    crop: bool = False, max_pixels: Optional[int] = None) -> OutputGeometry:
    """The :class:`OutputGeometry` of a render (arguments as for
    :func:`render_tree`; ``max_pixels`` as for :func:`output_size`)."""
    if node_id is None:
        node, t = tree.root, IDENTITY
    else:
        node, t = find_node(tree, node_id)
    if crop and node_id is not None:
        box = drawn_box(node, t, tolerance=0.01)
        if box is None or not (box[2] > box[0] and box[3] > box[1]):
            raise SVGError('element %r draws nothing to crop to' % (node_id,))
        w, h, sx, sy = output_size(box[2] - box[0], box[3] - box[1], width, height, zoom,
                                   max_pixels)
        t = Affine.translate(-box[0], -box[1]) @ t
    else:
        w, h, sx, sy = output_size(tree.width, tree.height, width, height, zoom, max_pixels)
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
