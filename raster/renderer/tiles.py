"""Large outputs a piece at a time: strips of rows within a memory budget,
and the levels of an XYZ map-tile pyramid.

Every piece is a window of the whole render
(:func:`raster.renderer.render_tree` with ``window``), which equals that
part of the whole image, so pieces can be rendered in any order and in
other processes.

>>> strip_spans(10, 3)
[(0, 3), (3, 6), (6, 9), (9, 10)]
>>> [lv.zoom for lv in xyz_levels(1000, 507, 0, 2)], xyz_levels(1000, 507, 2, 2)[0][1:]
([0, 1, 2], (1024, 520, 4, 3))
"""

import math
from typing import List, NamedTuple, Tuple

import numpy as np

from ..errors import CanvasError
from ..tree import ImageNode, PathNode, walk
from .bounds import device_box

__all__ = ['DEFAULT_BUDGET', 'BYTES_PER_PIXEL', 'TILE_SIZE', 'strip_rows', 'strip_spans',
           'row_work', 'balanced_spans', 'XYZLevel', 'xyz_levels', 'default_max_zoom']

#: Default memory budget (bytes) of the pixels of one piece being rendered.
DEFAULT_BUDGET = 256 * 1024 * 1024

#: Bytes a pixel of a strip costs while it is drawn and encoded (the 8-bit
#: canvas, coverage batches, the straight 8-bit copy, the PNG filter's work
#: space), an estimate measured on the corpus; group and filter layers
#: come on top of it where a document has them.
BYTES_PER_PIXEL = 24

#: Side of a map tile in pixels.
TILE_SIZE = 256


def strip_rows(width: int, budget: int = DEFAULT_BUDGET, workers: int = 1) -> int:
    """Rows per strip of a ``width`` px wide output so that ``workers``
    strips drawn at once stay within ``budget`` bytes
    (:data:`BYTES_PER_PIXEL` a pixel); at least 16 rows.

    Raises
    ------
    CanvasError
        A width, budget or worker count below 1.

    >>> strip_rows(32000, 256 * 1024 * 1024)
    349
    """
    width, budget, workers = int(width), int(budget), int(workers)
    if width < 1 or budget < 1 or workers < 1:
        raise CanvasError('strip_rows needs a positive width, budget and worker count')
    return max(16, budget // (BYTES_PER_PIXEL * width * workers))


def strip_spans(height: int, rows: int) -> List[Tuple[int, int]]:
    """``[(y0, y1)]`` strips of ``rows`` rows (the last may be shorter)
    covering ``height`` rows, top to bottom."""
    return [(y, min(height, y + rows)) for y in range(0, int(height), max(1, int(rows)))]


#: Work of a pixel of a path's device box relative to a path verb in
#: :func:`row_work` (masks and compositing against flattening and
#: scanning a segment), and of a pixel of the output (its encoding):
#: fitted to the strips of the world map at 8000 px (about 60 us a verb,
#: 30 ns a box pixel).
BOX_PIXEL_WORK = 1.0 / 2000
PIXEL_WORK = 1.0 / 4000


def row_work(node, transform, width: int, height: int) -> np.ndarray:
    """An estimate of the work of each row of an output: every path under
    ``node`` (with the CTM ``transform`` of the output's pixels, layered
    groups included) spreads its verbs and the pixels of its device box
    evenly over the rows of that box; every pixel of the output adds
    :data:`PIXEL_WORK`.

    Returns
    -------
    (height,) float64 ndarray
        Work per row (arbitrary units, > 0).
    """
    height, width = int(height), int(width)
    d = np.zeros(height + 1)
    y0s, y1s, ws = [], [], []
    pending = [(node, transform)]           # subtrees: the root, markers, SVG images
    while pending:
        root, t0 = pending.pop()
        for n, t in walk(root, t0):
            if isinstance(n, PathNode) and n.path is not None and len(n.path.verbs):
                if n.markers is not None:
                    pending.append((n.markers, t))
                x0, y0, x1, y1 = device_box(n.path, t)
                bx0, bx1 = max(x0, 0.0), min(x1, width)
                by0, by1 = max(y0, 0.0), min(y1, height)
                if not (bx1 > bx0 and by1 > by0) or not math.isfinite(by1 - by0):
                    continue
                y0s.append(by0)
                y1s.append(by1)
                ws.append(len(n.path.verbs) + BOX_PIXEL_WORK * (bx1 - bx0) * (by1 - by0))
            elif isinstance(n, ImageNode) and n.tree is not None:
                pending.append((n.tree.root, t @ n.transform))
    if ws:
        a = np.floor(np.array(y0s)).astype(np.int64)
        b = np.maximum(np.ceil(np.array(y1s)).astype(np.int64), a + 1)
        b = np.minimum(b, height)
        per = np.array(ws) / (b - a)
        np.add.at(d, a, per)
        np.add.at(d, b, -per)
    return np.cumsum(d[:height]) + PIXEL_WORK * width


def balanced_spans(work: np.ndarray, count: int, max_rows: int) -> List[Tuple[int, int]]:
    """``[(y0, y1)]`` strips covering the rows of ``work`` (per-row work,
    :func:`row_work`), top to bottom: ``count`` strips of about equal
    work, those of more than ``max_rows`` rows cut into equal parts.

    >>> balanced_spans(np.array([1.0, 1, 1, 1, 4, 4]), 2, 10)
    [(0, 5), (5, 6)]
    >>> balanced_spans(np.ones(10), 2, 3)
    [(0, 3), (3, 5), (5, 8), (8, 10)]
    """
    work = np.asarray(work, np.float64)
    h = len(work)
    c = np.cumsum(work)
    cuts = np.searchsorted(c, c[-1] * np.arange(1, max(1, int(count))) / max(1, int(count)),
                           side='left') + 1
    edges = sorted(set([0, h] + [int(v) for v in cuts if 0 < v < h]))
    out = []
    rows = max(1, int(max_rows))
    for y0, y1 in zip(edges, edges[1:]):
        k = -(-(y1 - y0) // rows)
        step = -(-(y1 - y0) // k)
        out.extend((y, min(y1, y + step)) for y in range(y0, y1, step))
    return out


class XYZLevel(NamedTuple):
    """One zoom level of a tile pyramid: the document fitted into a square
    of ``TILE_SIZE * 2**zoom`` px by its longer side, an output of
    ``width`` x ``height`` px, cut into ``columns`` x ``rows`` tiles (the
    last ones padded with transparency)."""
    zoom: int
    width: int
    height: int
    columns: int
    rows: int


def default_max_zoom(doc_width: float, doc_height: float, tile: int = TILE_SIZE) -> int:
    """The first zoom level at which the document's longer side reaches its
    natural size (0 for documents no larger than a tile).

    >>> default_max_zoom(1000, 507), default_max_zoom(200, 100)
    (2, 0)
    """
    side = max(float(doc_width), float(doc_height))
    return max(0, int(math.ceil(math.log2(side / tile) - 1e-9))) if side > tile else 0


def xyz_levels(doc_width: float, doc_height: float, min_zoom: int, max_zoom: int,
               tile: int = TILE_SIZE) -> List[XYZLevel]:
    """The levels ``min_zoom`` to ``max_zoom`` of a pyramid of a document
    of natural size ``doc_width`` x ``doc_height`` px; the sizes are those
    of :func:`raster.renderer.output_size` with ``width`` (a landscape
    document) or ``height`` set to ``tile * 2**zoom``.

    Raises
    ------
    CanvasError
        Zoom levels outside 0-24 or ``min_zoom > max_zoom``.
    """
    from . import output_size, MAX_WINDOWED_PIXELS
    if not (0 <= min_zoom <= max_zoom <= 24):
        raise CanvasError('zoom levels must satisfy 0 <= min <= max <= 24, got %r to %r'
                          % (min_zoom, max_zoom))
    out = []
    for z in range(int(min_zoom), int(max_zoom) + 1):
        side = tile * 2 ** z
        if doc_width >= doc_height:
            w, h = output_size(doc_width, doc_height, width=side, max_pixels=MAX_WINDOWED_PIXELS)[:2]
        else:
            w, h = output_size(doc_width, doc_height, height=side, max_pixels=MAX_WINDOWED_PIXELS)[:2]
        out.append(XYZLevel(z, w, h, -(-w // tile), -(-h // tile)))
    return out
