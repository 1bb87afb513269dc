"""Exact-area anti-aliased scan conversion of polygon edges to coverage masks.

The input is a set of line segments (edges) in device pixels, ``(E, 2, 2)``
float64: ``edges[e] = [[x0, y0], [x1, y1]]``, x to the right, y down.  Pixel
(row ``i``, column ``j``) covers the square ``[j, j+1] x [i, i+1]``.  The
edges must form a union of closed polygons (the caller includes the closing
edge of every contour); the orientation of each polygon is free.

How it works
------------
1. Every edge is split at all integer grid lines it crosses, first at the
   horizontal lines (so each piece lies in one pixel row), then each piece at
   the vertical lines (so each piece lies in one pixel).  Both splits produce
   their crossings already in travel order, so no sort is needed.
2. For each piece in cell (row ``r``, column ``c``) with vertical extent
   ``dy`` and mean x offset ``fx`` inside the cell, ``cover[r, c] += dy`` and
   ``partial[r, c] += dy * fx``.  The winding number ``w(x, y)`` integrated
   over a cell is then exactly
   ``sum(cover[r, :c+1]) - partial[r, c]`` (a running sum along the row).
   This is linear in the edges, so it is exact for any set of polygons.
   When the pieces are few for the size of the box (fewer than one per
   ``_SPARSE_RATIO`` cells) the sums are kept for the touched cells only.
3. The fill rule ``f`` (nonzero: ``min(1, |w|)``; evenodd: distance of ``w``
   to the nearest even integer) is applied to that integral.  This equals the
   integral of ``f(w)`` -- the true coverage -- whenever ``w`` takes at most
   two adjacent integer values inside the cell, because ``f`` is linear
   between adjacent integers.  The cells where that might fail (where
   separate chains of edges meet) get their exact coverage from the faces
   the chains cut them into (:func:`_faces`), or, where the chains are not
   simple enough for that, are recomputed on their own sets of horizontal
   sample lines (see :func:`coverage`).  In a dense box (dense hatching),
   a row crossed only by segments that run from its top to its bottom and
   keep their order (none crosses another) is settled first: each segment
   is weighted by the change of ``f`` across it instead of its direction,
   and the running sums of those weights are the coverage of every cell of
   the row, none flagged (:func:`_row_weights`).
4. The output is assembled from the cells holding pieces: along a row the
   coverage is constant between them, so the running sum runs over those
   cells only and the mask is written with one ``np.repeat``.

>>> import numpy as np
>>> square = np.array([[[1, 1], [3, 1]], [[3, 1], [3, 3]],
...                    [[3, 3], [1, 3]], [[1, 3], [1, 1]]], float)
>>> m = coverage(square + 0.5, 5, 5)
>>> m.box
(1, 1, 4, 4)
>>> m.data
array([[0.25, 0.5 , 0.25],
       [0.5 , 1.  , 0.5 ],
       [0.25, 0.5 , 0.25]], dtype=float32)
"""

import math

import numpy as np

from .. import limits
from ..errors import CanvasError, LimitError, PathError
from ..geometry.flattening import flatten
from ..geometry.rows import concat_ranges, distinct_values
from ..geometry.rules import FillRule

__all__ = ['Mask', 'coverage', 'coverage_many', 'coverage_batch', 'path_coverage', 'check_canvas_size']

# Coverage below this is float64 rounding residue and is set to 0.
_RESIDUE = 1e-9
# Most pieces generated at once; larger boxes are processed in row bands.
# About 30 float64 arrays of this length are live in a batch's band: 2^17
# held a 2000 px map (batik_mapWaadt) to 106 MB peak RSS against 124 MB at
# 2^18.  2^16 (the faces of crossing cells made the bands' other work
# cheaper): the stroked random cubics at 2000 px peak at 92 MB against 97
# (whole process, largest process), the jittered polygon at 79 against 85,
# while splom, the world map, batik_mapWaadt and the cubics take the same
# time within noise (paired runs, CPU ratios 0.97-1.09).
_CHUNK_PIECES = 1 << 16
# Most pieces of a sub-batch of shapes scan converted together (shapes
# above _CHUNK_PIECES go alone, in bands).  The batch's arrays per piece
# are live together: 2^16 holds the icon sheet at 2000 px to 68 MB peak
# RSS against 79 MB at 2^17 (batik_mapWaadt 90 against 104).
_BATCH_PIECES = 1 << 16
# Boxes with more than this many cells per piece accumulate cover and
# partial sums over the touched cells only (sorting the pieces' cells
# costs less than sweeping the whole box).
_SPARSE_RATIO = 8
# Bands holding at least this many pieces per cell on average try to settle
# their rows by edge weights (see _row_weights): dense hatching.
_DENSE_BAND = 4.0
# Longest run checked for monotonicity along some direction.
_STRETCH_MAX = 256
# Cells of several simple runs holding at most this many runs and pieces
# get their coverage from their faces (see _faces); busier cells are
# recomputed.
_FACES_RUNS = 32
_FACES_PIECES = 64
# ... and cells of chords alone (runs of one piece) at most this many,
# whose chords cross nowhere (dense hatching: many parallel lines through
# a pixel); where they cross, cells of more than _FACES_PIECES are
# recomputed.
_FACES_CHORDS = 4096
# Cells of chords are checked for crossings (_chords_cross) and tested
# pair by pair only where some cross when some cell of a call holds more
# chords than this (cells of a few chords, most with some crossing, cost
# about as much to check as to test).
_CHORDS_TESTED = 16
# Most work items (sample crossings) per batch of recomputed cells.
_CHUNK_WORK = 1 << 20
# Most work (four per run plus one per pair of pieces of a cell, one per
# chord of a cell checked by _chords_cross) per call of _faces (see
# _flag), and most pairs per slice of its pair tests (_crossings).
_FACES_WORK = 1 << 16

# Fewest cells of single-piece runs worth a _faces call of their own beside
# the other cells (the shorter treatment saves about a third of a
# microsecond a cell, 1.3 against 1.6; a call costs about 0.4 ms).
_FACES_SINGLE_MIN = 1024
# Cells with more pieces than this are refined on a _REFINE x _REFINE grid
# instead of being sampled at all critical heights, while their distinct
# pieces times _REFINE ** depth is at most _REFINE_WORK (the pieces met per
# pixel side at that level: a bundle of lines that refinement cannot part
# would otherwise cost 4x more at every level); busier cells are sampled
# on _SAMPLE_LINES evenly spaced lines.  A fuzzer's document of strokes
# a thousand pixels wide over a 64-pixel canvas took 75 s with the old
# limit (5 levels), 6 s with 1024, 2 s with 256, but 300 lines through
# one point are then 2.3/255 off (0.1/255 with 1024: the refinement parts
# them); the corpus and the crossing benchmarks render identically.
_EXACT_PIECES = 12
_REFINE = 4
_REFINE_WORK = 1024
_SAMPLE_LINES = 16
# Flag every cell holding pieces (see _flag; for checking the flags).
_FLAG_EVERYTHING = False
# Most cells (sum of the shapes' box areas) per batch of coverage_batch.
_BATCH_CELLS = 1 << 24
# Most cells per batch of aliased shapes (about 32 bytes of temporaries a
# cell: the crossings' sums, their running sums, windings and masks):
# 2^18 holds the terminal screenshot (textual_dolphie) at 2000 px to
# 105 MB peak RSS against 124 MB at 2^24.
_ALIASED_CELLS = 1 << 18


class Mask:
    """A coverage mask: a window of a canvas.

    Attributes
    ----------
    data : (h, w) float32 ndarray
        Coverage in [0, 1]; ``data[i, j]`` belongs to canvas pixel
        (row ``y0 + i``, column ``x0 + j``).
    x0, y0 : int
        Canvas position of ``data[0, 0]``.

    >>> m = Mask(np.ones((2, 3), np.float32), 4, 5)
    >>> m.box, m.shape
    ((4, 5, 7, 7), (2, 3))
    """

    __slots__ = ('data', 'x0', 'y0')

    def __init__(self, data, x0, y0):
        self.data = data
        self.x0 = int(x0)
        self.y0 = int(y0)

    @property
    def shape(self):
        """(h, w) of :attr:`data`."""
        return self.data.shape

    @property
    def box(self):
        """(x0, y0, x1, y1): the pixel rectangle covered by :attr:`data`
        (x1, y1 exclusive)."""
        h, w = self.data.shape
        return (self.x0, self.y0, self.x0 + w, self.y0 + h)

    def full(self, width, height):
        """The mask pasted into a zero (height, width) float32 array."""
        out = np.zeros((height, width), np.float32)
        x0, y0, x1, y1 = self.box
        cx0, cy0 = max(x0, 0), max(y0, 0)
        cx1, cy1 = min(x1, width), min(y1, height)
        if cx1 > cx0 and cy1 > cy0:
            out[cy0:cy1, cx0:cx1] = self.data[cy0 - y0:cy1 - y0, cx0 - x0:cx1 - x0]
        return out

    def __repr__(self):
        return 'Mask(box=%r)' % (self.box,)


def check_canvas_size(width, height):
    """Validate a canvas size and return it as two Python ints.

    Raises :class:`~raster.errors.CanvasError` for sizes that are not
    integers (integral floats are accepted), not positive, larger than
    ``max_side`` or with more than
    ``max_pixels`` pixels (:mod:`raster.limits`).

    >>> check_canvas_size(10.0, 3)
    (10, 3)
    """
    out = []
    lim = limits.current()
    for name, v in (('width', width), ('height', height)):
        try:
            f = float(v)
        except (TypeError, ValueError):
            raise CanvasError('canvas %s must be a number, got %r' % (name, v)) from None
        if not np.isfinite(f) or f != int(f):
            raise CanvasError('canvas %s must be a whole number, got %r' % (name, v))
        i = int(f)
        if i <= 0:
            raise CanvasError('canvas %s must be positive, got %d' % (name, i))
        if i > lim.max_side:
            raise CanvasError('canvas %s %d exceeds max_side %d' % (name, i, lim.max_side))
        out.append(i)
    if out[0] * out[1] > lim.max_pixels:
        raise CanvasError('canvas %dx%d exceeds max_pixels %d'
                          % (out[0], out[1], lim.max_pixels))
    return out[0], out[1]


def _check_edges(edges):
    try:
        e = np.asarray(edges, dtype=np.float64)
    except (TypeError, ValueError):
        raise PathError('edges must be an (E, 2, 2) array of numbers') from None
    if e.size == 0:
        return np.zeros((0, 2, 2))
    if e.ndim == 2 and e.shape[1] == 4:
        e = e.reshape(-1, 2, 2)
    if e.ndim != 3 or e.shape[1:] != (2, 2):
        raise PathError('edges must have shape (E, 2, 2), got %r' % (e.shape,))
    if not np.all(np.isfinite(e)):
        raise PathError('edges have non-finite coordinates (NaN or infinity)')
    limits.check_coord(float(np.abs(e).max()), 'edge')
    return e


def _window(width, height, clip):
    """The pixel rectangle (x0, y0, x1, y1) where work may happen: the
    canvas, cut by ``clip`` rounded outward to whole pixels (it may come
    out empty).  Raises CanvasError for a malformed ``clip``."""
    if clip is None:
        return 0, 0, width, height
    try:
        c = [float(v) for v in clip]
    except (TypeError, ValueError):
        raise CanvasError('clip must be four numbers (x0, y0, x1, y1)') from None
    if len(c) != 4 or not all(np.isfinite(c)):
        raise CanvasError('clip must be four finite numbers (x0, y0, x1, y1)')
    return (max(0, math.floor(c[0])), max(0, math.floor(c[1])),
            min(width, math.ceil(c[2])), min(height, math.ceil(c[3])))


def _box(e, width, height, clip, antialias):
    """Integer pixel box [X0, X1) x [Y0, Y1) where work happens, or None."""
    xs, ys = e[:, :, 0], e[:, :, 1]
    if antialias:
        X0, X1 = np.floor(xs.min()), np.ceil(xs.max())
        Y0, Y1 = np.floor(ys.min()), np.ceil(ys.max())
    else:   # pixels whose centre may be inside: min < centre <= max
        X0, X1 = np.floor(xs.min() + 0.5), np.floor(xs.max() + 0.5)
        Y0, Y1 = np.floor(ys.min() + 0.5), np.floor(ys.max() + 0.5)
    wx0, wy0, wx1, wy1 = _window(width, height, clip)
    X0, Y0 = max(int(X0), wx0), max(int(Y0), wy0)
    X1, Y1 = min(int(X1), wx1), min(int(Y1), wy1)
    if X1 <= X0 or Y1 <= Y0:
        return None
    return X0, Y0, X1, Y1


def coverage(edges, width, height, fill_rule='nonzero', antialias=True, clip=None, exact=True):
    """Coverage of the region enclosed by ``edges`` on a width x height canvas.

    Parameters
    ----------
    edges : (E, 2, 2) array_like of float
        Line segments ``[[x0, y0], [x1, y1]]`` in device pixels (x right,
        y down), forming closed polygons (closing edges included).  Edges
        outside the canvas still count: the part left of the canvas still
        changes the winding of the pixels to its right.
    width, height : int
        Canvas size in pixels.
    fill_rule : FillRule or {'nonzero', 'evenodd'}
    antialias : bool
        True: exact area coverage of every pixel.  False
        (``shape-rendering: crispEdges``): a pixel is 1 when its centre is
        inside under the fill rule, else 0.
    clip : (x0, y0, x1, y1) or None
        Restrict work and output to this pixel rectangle (rounded outward
        to whole pixels).
    exact : bool
        True (default): exact area coverage, see Notes.  False: every
        pixel gets ``f(integral of the winding number over the pixel)``
        (``f`` the fill rule) without the exact recompute of pixels where
        separate chains of edges meet.  That is exact wherever the winding
        takes at most two adjacent values in a pixel; elsewhere, for the
        nonzero rule and pieces of one orientation (a union of overlapping
        polygons, as a hairline outline is), it is the sum of the pieces'
        areas in the pixel clipped to 1: never less than the true coverage,
        more by at most the overlapping area.

    Returns
    -------
    Mask or None
        ``data`` is (h, w) float32 in [0, 1] covering the edges' pixel
        bounding box clipped to the canvas (and ``clip``); None when no
        pixel is covered.

    Raises
    ------
    PathError
        Edges not of shape (E, 2, 2), non-finite coordinates, unknown
        fill rule.
    LimitError
        A coordinate larger in magnitude than ``max_coord`` (:mod:`raster.limits`).
    CanvasError
        Zero, negative or too large canvas size; malformed ``clip``.

    Notes
    -----
    Antialiased coverage is exact up to float64 rounding, for any
    overlaps, crossings and coincident edges.  The running-sum pass is
    exact in every pixel where the winding number takes at most two
    adjacent values.  A pixel can hold more only where separate chains
    meet: a *chain* is a run of pieces in the pixel, each starting exactly
    where the previous one (in edge order) ends.  A chain that does not
    cross itself cuts the pixel into two sides whose windings differ by
    one; a chain of at most two pieces, or monotone in x or in y, cannot
    cross itself (the two pieces at a closed contour's start vertex count
    as one chain).  A pixel holding several such chains, each from its
    side to its side, is cut into faces of constant winding: its coverage
    is the sum of the faces' areas times the fill rule of their windings,
    each area a shoelace sum over the pixel's boundary and the chains'
    pieces between their crossing points (see :func:`_faces`).  The other
    pixels (a chain crossing itself or ending inside, touching chains,
    more than 32 chains or 64 pieces) are recomputed by the midpoint rule:
    the covered width of a horizontal line through the pixel is linear in
    its height between the piece end points and pairwise intersections
    (see :func:`_exact`); pixels of more than 12 distinct pieces are
    refined on a 4 x 4 grid, recursively while their distinct pieces
    times 4 ** level stay within 1024; beyond that (many pieces that
    refinement cannot part, such as nearly coincident lines) the midpoint
    rule runs on 16 evenly spaced lines of the cell, each line exact: a
    bound on the work per pixel.

    >>> tri = np.array([[[0, 0], [4, 0]], [[4, 0], [0, 4]], [[0, 4], [0, 0]]], float)
    >>> float(coverage(tri, 8, 8).data.sum())
    8.0
    >>> coverage(tri, 8, 8, antialias=False).data.astype(int)
    array([[1, 1, 1, 1],
           [1, 1, 1, 0],
           [1, 1, 0, 0],
           [1, 0, 0, 0]])
    >>> coverage(tri + 100, 8, 8) is None
    True
    """
    width, height = check_canvas_size(width, height)
    evenodd = _is_evenodd(fill_rule)
    e = _check_edges(edges)
    if len(e) == 0:
        return None
    box = _box(e, width, height, clip, antialias)
    if box is None:
        return None
    X0, Y0, X1, Y1 = box
    w, h = X1 - X0, Y1 - Y0
    local = e - np.array([X0, Y0], np.float64)
    if antialias:
        data = _area_coverage(local, w, h, evenodd, exact)
    else:
        data = _centre_coverage(local, w, h, evenodd)
    if data is None or not data.any():
        return None
    return Mask(data, X0, Y0)


def path_coverage(path, width, height, fill_rule='nonzero', antialias=True, clip=None,
                  tolerance=0.25, transform=None, straddle=False):
    """Coverage of a :class:`~raster.geometry.path.Path` filled on a canvas.

    The path is flattened with :func:`raster.geometry.flattening.flatten` (every contour
    closed) and scan converted with :func:`coverage`.

    Parameters
    ----------
    path : raster.geometry.path.Path
    width, height, fill_rule, antialias, clip
        As for :func:`coverage`.
    tolerance : float
        Largest distance in device pixels between a curve and its flattened
        polyline (default 0.25); the scan conversion itself is exact.
    transform : raster.geometry.transform.Affine or None
        User space to device space.
    straddle : bool
        Flatten into straddled polylines (see
        :func:`raster.geometry.flattening.flatten`): the edges of curves
        then lie about half as far from the curves, on both sides.

    Returns
    -------
    Mask or None

    >>> from raster.geometry.path import Path
    >>> m = path_coverage(Path.polygon([(1, 1), (3, 1), (3, 2)]), 4, 4)
    >>> m.box, float(m.data.sum())
    ((1, 1, 3, 2), 1.0)
    """
    edges = flatten(path, tolerance=tolerance, transform=transform,
                    straddle=straddle).edges(close_all=True)
    return coverage(edges, width, height, fill_rule=fill_rule, antialias=antialias, clip=clip)


# -- exact area ---------------------------------------------------------------

def _split(ua, va, ub, vb, hi, tag=None):
    """Split segments (u, v) at every integer u = k with 0 <= k <= hi that lies
    strictly inside the segment (``hi`` a number or one per segment).

    Returns the pieces (ua, va, ub, vb), each lying between two consecutive
    integer u lines (or entirely below 0 / above hi), in travel order.  A
    split point is stored once, so consecutive pieces share it bitwise.
    With ``tag`` (one value per segment) the pieces' tags come fifth.
    """
    n_in = len(ua)
    umin = np.minimum(ua, ub)
    kmin = np.floor(umin, out=umin)
    kmin += 1.0
    np.maximum(kmin, 0.0, out=kmin)
    umax = np.maximum(ua, ub)
    kmax = np.ceil(umax, out=umax)
    kmax -= 1.0
    np.minimum(kmax, hi, out=kmax)
    d = kmax - kmin
    d += 1.0
    n = d.astype(np.int64)
    np.maximum(n, 0, out=n)
    ends = np.cumsum(n)
    m_total = int(ends[-1]) if n_in else 0
    if m_total == 0:
        return (ua, va, ub, vb) if tag is None else (ua, va, ub, vb, tag)
    cb = ends - n                                # crossings before each segment
    n_pieces = n_in + m_total                    # n + 1 per segment
    # the pieces' end points are written in place: segment i's first piece
    # (pstart) starts at its start, its last piece ends at its end, and
    # crossing m ends piece pstart + m and starts piece pstart + m + 1 (one
    # computed value for both, so consecutive pieces share it bitwise)
    UA = np.empty(n_pieces)
    VA = np.empty(n_pieces)
    UB = np.empty(n_pieces)
    VB = np.empty(n_pieces)
    pstart = cb + np.arange(n_in)
    UA[pstart] = ua
    VA[pstart] = va
    last = pstart + n
    UB[last] = ub
    VB[last] = vb
    # crossing j (of all) is crossing m = j - cb of segment owner: the line
    # kmin + m going up, kmax - m going down, that is kb + sg * j with
    # per-segment kb and sg (whole numbers: exact).  Per-segment values are
    # spread over the crossings by np.repeat (sequential, where indexing by
    # owner gathers)
    up = ub > ua
    sg = np.where(up, 1.0, -1.0)
    kb = np.where(up, kmin, kmax)
    kb -= sg * cb
    j = np.arange(m_total)
    k = np.repeat(sg, n)
    k *= j
    k += np.repeat(kb, n)
    t = k - np.repeat(ua, n)
    t /= np.repeat(ub - ua, n)
    v = np.repeat(vb - va, n)
    v *= t
    v += np.repeat(va, n)
    pos = j + np.repeat(np.arange(n_in), n)      # the piece the crossing ends
    UB[pos] = k
    VB[pos] = v
    pos += 1
    UA[pos] = k
    VA[pos] = v
    if tag is not None:
        return UA, VA, UB, VB, np.repeat(tag, n + 1)
    return UA, VA, UB, VB


def _pieces(loc, w, h, evenodd=None):
    """Cell pieces of local edges ``loc`` ((E, 2, 2), box origin at 0).

    Returns xa, ya, xb, yb (float64) and col, row (int64) for every piece
    inside the box rows.  The part of an edge left of the box goes to a
    virtual column -1 (x set to -0.5): it changes the winding of every cell
    to its right like a vertical edge.  The part right of the box is
    dropped.  Consecutive pieces share their split points bitwise.

    With ``evenodd`` (the fill rule, for the exact coverage) a dense box
    also has rows settled by edge weights (:func:`_row_weights`): the
    seventh value is then ``(weight, settled)``, the weight of every piece
    and which rows are settled ((h,) bool), else None.
    """
    xa, ya = loc[:, 0, 0], loc[:, 0, 1]
    xb, yb = loc[:, 1, 0], loc[:, 1, 1]
    # split in y (u = y, v = x)
    ya, xa, yb, xb = _split(ya, xa, yb, xb, h)
    ym = 0.5 * (ya + yb)
    keep = (ym >= 0) & (ym < h)
    if not keep.all():
        xa, ya, xb, yb = xa[keep], ya[keep], xb[keep], yb[keep]
    if len(xa) == 0:
        return None
    weights = None
    if evenodd is not None and len(xa) + np.abs(xb - xa).sum() >= _DENSE_BAND * w * h:
        weights = _row_weights(xa, ya, xb, yb, h, evenodd)
    # split in x (u = x, v = y)
    if weights is None:
        xa, ya, xb, yb = _split(xa, ya, xb, yb, w)
    else:
        xa, ya, xb, yb, wt = _split(xa, ya, xb, yb, w, tag=weights[0])
    xm = 0.5 * (xa + xb)
    keep = xm < w
    if not keep.all():
        xa, ya, xb, yb, xm = xa[keep], ya[keep], xb[keep], yb[keep], xm[keep]
        if weights is not None:
            wt = wt[keep]
    if len(xa) == 0:
        return None
    col = np.floor(xm).astype(np.int64)
    np.clip(col, -1, w - 1, out=col)
    left = col < 0
    if left.any():      # (new arrays: xa, xb may be views of loc)
        xa = np.where(left, -0.5, xa)
        xb = np.where(left, -0.5, xb)
    row = np.floor(0.5 * (ya + yb)).astype(np.int64)
    np.clip(row, 0, h - 1, out=row)
    return xa, ya, xb, yb, col, row, None if weights is None else (wt, weights[1])


def _row_weights(xa, ya, xb, yb, h, evenodd):
    """Rows of a box that the running sums get exactly, with edge weights.

    A row of pixels whose segments (edges cut at the rows, ``(xa, ya) ->
    (xb, yb)``) all run from its top to its bottom, and keep their order
    from top to bottom (no two cross), is cut by them into strips of
    constant winding: counted from the left, the winding right of the
    ``i``-th segment is the sum of the directions (+1 down, -1 up) of the
    first ``i``.  The fill rule is then a step function across the row,
    changing by ``fill(w right) - fill(w left)`` at each segment (0 where
    both sides are filled, as between two overlapping stripes under
    nonzero).  Giving each segment that weight instead of its direction,
    the running sums add up the filled area itself, exact in every cell
    of the row whatever the number of segments in it: dense hatching needs
    no recompute.

    Returns ``(weight, settled)``: the weight of every segment, as a factor
    of its direction (1 in rows not settled), and which rows are settled
    ((h,) bool); None when none is.
    """
    top = np.minimum(ya, yb)
    full = np.abs(yb - ya) == 1.0
    # the middle row first: where segments spanning it cross (a
    # cross-hatch), the other rows are not tried
    probe = np.flatnonzero(full & (top == float(h // 2)))
    pd = ya[probe] < yb[probe]
    xt = np.where(pd, xa[probe], xb[probe])
    xd = np.where(pd, xb[probe], xa[probe])
    if (np.diff(xd[np.lexsort((xd, xt))]) < 0).any():
        return None
    row = np.floor(0.5 * (ya + yb)).astype(np.int64)
    down = ya < yb
    spans = full & (top == row)
    ok = np.bincount(row[~spans], minlength=h) == 0
    if not ok.any():
        return None
    sel = np.flatnonzero(ok[row])
    r = row[sel]
    xt = np.where(down[sel], xa[sel], xb[sel])       # x on the row's top line
    xd = np.where(down[sel], xb[sel], xa[sel])       # ... and on its bottom line
    o = _row_order(r, xt, xd)
    r, xt, xd = r[o], xt[o], xd[o]
    first = np.ones(len(r), bool)
    first[1:] = r[1:] != r[:-1]
    # two segments cross where the later one (by the top) ends left of the
    # earlier one at the bottom (or, out of order by the top, are taken to)
    crossed = ~first[1:] & ((xd[1:] < xd[:-1]) | (xt[1:] < xt[:-1]))
    ok[r[1:][crossed]] = False
    if not ok.any():
        return None
    d = np.where(down[sel][o], 1.0, -1.0)
    cs = np.cumsum(d)
    after = cs - np.repeat((cs - d)[first], _run_lengths(np.flatnonzero(first), len(r)))
    before = after - d
    if evenodd:
        step = np.abs(np.remainder(after, 2.0)) - np.abs(np.remainder(before, 2.0))
    else:
        step = np.minimum(np.abs(after), 1.0) - np.minimum(np.abs(before), 1.0)
    weight = np.ones(len(ya))
    weight[sel[o]] = np.where(ok[r], step * d, 1.0)
    return weight, ok


def _row_order(r, xt, xd):
    """An order of segments by row ``r`` (int64 >= 0), then by ``xt``, then
    by ``xd`` (float64): ``np.lexsort((xd, xt, r))``, in one sort of a
    float key ``r * span + xt`` (the segments of equal ``r`` and ``xt``
    then sorted by ``xd``).  Where the key's rounding merges two values of
    ``xt`` of one row their order may come out reversed: the caller checks
    ``xt`` along each row."""
    n = len(r)
    if n == 0:
        return np.zeros(0, np.int64)
    lo = float(xt.min())
    key = r * (float(xt.max()) - lo + 1.0)
    key += xt - lo
    o = np.argsort(key, kind='stable')
    rs, ts = r[o], xt[o]
    tie = (rs[1:] == rs[:-1]) & (ts[1:] == ts[:-1])
    if tie.any():
        # (rare: segments from one point on a row's top line) each run of
        # ties holds consecutive places: sorted together by (r, xt, xd),
        # they keep those places
        at = np.zeros(n, bool)
        at[:-1] |= tie
        at[1:] |= tie
        k = np.flatnonzero(at)
        sub = o[k]
        o[k] = sub[np.lexsort((xd[sub], xt[sub], r[sub]))]
    return o


def _bands(loc, w, h):
    """Row bands ``[(r0, r1), ...]`` covering rows 0..h whose pieces number
    about :data:`_CHUNK_PIECES` at most (a single row may hold more).

    Every cell's pieces lie in one band, so a band is scan converted on its
    own, the exact recompute included.  The pieces of an edge are estimated
    as one plus the rows and columns it spans, spread evenly over its rows.
    """
    n_e = len(loc)
    d = np.abs(loc[:, 1] - loc[:, 0])
    if 3 * n_e + d.sum() <= _CHUNK_PIECES:     # cheap upper bound
        return [(0, h)]
    xs, ys = loc[:, :, 0], loc[:, :, 1]
    r0 = np.clip(np.floor(ys.min(1)), 0, h).astype(np.int64)
    r1 = np.clip(np.ceil(ys.max(1)), 0, h).astype(np.int64)
    nx = np.clip(np.ceil(xs.max(1)), 0, w) - np.clip(np.floor(xs.min(1)), 0, w)
    ny = r1 - r0
    est = 1.0 + ny + nx
    if est.sum() <= _CHUNK_PIECES:
        return [(0, h)]
    dens = est / np.maximum(ny, 1)
    r1e = np.maximum(r1, np.minimum(r0 + 1, h))     # one row at least (clipped)
    per_row = np.cumsum(np.bincount(r0, dens, h + 1) - np.bincount(r1e, dens, h + 1))[:h]
    cum = np.cumsum(per_row)
    bounds = [0]
    while bounds[-1] < h:
        lo = bounds[-1]
        base = cum[lo - 1] if lo else 0.0
        hi = int(np.searchsorted(cum, base + _CHUNK_PIECES, side='right'))
        bounds.append(min(max(hi, lo + 1), h))
    return list(zip(bounds[:-1], bounds[1:]))


def _stable_order(key):
    """``np.argsort(key, kind='stable')`` for a 1-D array of integers >= 0.

    numpy sorts 8- and 16-bit integers stably by radix, in linear time,
    where wider keys take a merge sort: keys below 2**48 are sorted here
    16 bits at a time, least significant digit first, each pass stable
    (the order of equal keys is the input's)."""
    n = len(key)
    top = int(key.max()) if n else 0
    if top < 1 << 16:
        return np.argsort(key.astype(np.uint16), kind='stable')
    if top >= 1 << 48:
        return np.argsort(key, kind='stable')
    order = np.argsort((key & 0xFFFF).astype(np.uint16), kind='stable')
    shift = 16
    while top >> shift:
        digit = ((key[order] >> shift) & 0xFFFF).astype(np.uint16)
        order = order[np.argsort(digit, kind='stable')]
        shift += 16
    return order


def _group_starts(key):
    """Indices where a run of equal values of ``key`` (1-D, non-empty)
    starts."""
    new = np.empty(len(key), bool)
    new[0] = True
    np.not_equal(key[1:], key[:-1], out=new[1:])
    return np.flatnonzero(new)


def _run_lengths(starts, n):
    """Lengths of the runs starting at ``starts`` (increasing) in 0..n-1."""
    out = np.empty_like(starts)
    out[:-1] = starts[1:] - starts[:-1]
    out[-1:] = n - starts[-1:]
    return out


# -- which cells need the exact recompute -------------------------------------
#
# A cell's running-sum value f(integral of w) is exact when the winding w
# takes at most two adjacent values in it (the fill rule f is linear
# between adjacent integers; for nonzero also whenever w stays >= 1, <= -1,
# in [0, 1] or in [-1, 0]).  The pieces of a cell form *runs*: maximal
# sequences of pieces in path order each starting exactly where the
# previous one ends.  A *simple* run does not cross itself: at most two
# pieces, or its directions fit in an open half-plane (it is monotone along
# some direction).  One simple run cuts the cell into two sides whose
# windings differ by one, so a cell of one simple run needs nothing more.
# Simple runs from side to side cut a cell into faces of constant winding
# whose areas are sums over their boundaries: _faces gets the coverage of
# those cells directly (in closed form when the windings' bound already
# makes the fill rule linear).  Every other cell is flagged.

def _flag(xa, ya, xb, yb, col, row, cell, brk, left_of, evenodd, everything=None):
    """Cells whose coverage needs the exact recompute, and the coverage of
    the cells of several runs that :func:`_faces` gives directly.

    Parameters
    ----------
    xa, ya, xb, yb : (P,) float64 ndarray
        Pieces in path order (box coordinates; pixel (row, col) is the
        square [col, col + 1] x [row, row + 1]).
    col, row : (P,) int64 ndarray
        The cell of each piece.
    cell : (P,) int64 ndarray
        Flat cell key of each piece, < 0 for pieces that are in no cell
        (the virtual column left of the box, or shapes not recomputed).
    brk : (P,) bool ndarray or None
        Pieces that never continue the previous one (a new shape).
    left_of : callable
        ``left_of(keys)``: the winding integrated over the left side of
        each cell (float64), from the running sums.
    evenodd : bool or (P,) bool ndarray
        The fill rule (per piece when shapes differ).
    everything : bool or None
        True flags every cell holding a piece (the running sum is then
        used nowhere: a check of the tests above); None reads
        ``_FLAG_EVERYTHING``.

    Returns
    -------
    flagged : (F,) int64 ndarray
        The flagged cell keys, sorted.
    pieces : (Q,) int64 ndarray
        The pieces of the flagged cells, cell after cell.
    counts : (F,) int64 ndarray
        Pieces per flagged cell.
    direct : ((D,) int64 ndarray, (D,) float64 ndarray)
        Cell keys and their coverage (fill rule applied), for cells
        neither flagged nor left to the running sum.
    """
    n = len(cell)
    empty = (np.zeros(0, np.int64),) * 3
    nothing = empty + ((empty[0], np.zeros(0)),)
    if n == 0:
        return nothing
    conn = np.zeros(n, bool)
    conn[1:] = (xa[1:] == xb[:-1]) & (ya[1:] == yb[:-1])
    if brk is not None:
        conn &= ~brk
    start = ~conn
    start[1:] |= cell[1:] != cell[:-1]
    ridx = np.flatnonzero(start)
    rlen = _run_lengths(ridx, n)
    dx = xb - xa
    dy = yb - ya
    bits = ((dy > 0).astype(np.uint8) | ((dy < 0).astype(np.uint8) << 1)
            | ((dx > 0).astype(np.uint8) << 2) | ((dx < 0).astype(np.uint8) << 3))
    rbits = np.bitwise_or.reduceat(bits, ridx)
    # a merged run is a closed chain's end followed by its start (one cell):
    # its own start ridx is the tail part's, hstart/hlen the head part's
    merged = np.zeros(len(ridx), bool)
    hstart = np.zeros(len(ridx), np.int64)
    hlen = np.zeros(len(ridx), np.int64)
    heads = np.flatnonzero(~conn)
    tails = np.empty_like(heads)
    tails[:-1] = heads[1:] - 1
    tails[-1] = n - 1
    cyc = ((xa[heads] == xb[tails]) & (ya[heads] == yb[tails])
           & (cell[heads] == cell[tails]))
    if cyc.any():
        run_id = np.cumsum(start) - 1
        rh, rt = run_id[heads[cyc]], run_id[tails[cyc]]
        two = rh != rt
        rh, rt = rh[two], rt[two]
        rbits[rt] |= rbits[rh]
        hstart[rt] = ridx[rh]
        hlen[rt] = rlen[rh]
        rlen[rt] += rlen[rh]
        merged[rt] = True
        keep = np.ones(len(ridx), bool)
        keep[rh] = False
        ridx, rlen, rbits, merged = ridx[keep], rlen[keep], rbits[keep], merged[keep]
        hstart, hlen = hstart[keep], hlen[keep]
    rcell = cell[ridx]
    inside = rcell >= 0
    if not inside.all():
        ridx, rlen, rbits, merged, rcell, hstart, hlen = (
            ridx[inside], rlen[inside], rbits[inside], merged[inside], rcell[inside],
            hstart[inside], hlen[inside])
    if len(ridx) == 0:
        return nothing
    simple = (rlen <= 2) | ((rbits & 3) != 3) | ((rbits & 12) != 12)
    hp = np.flatnonzero(~simple & (rlen <= _STRETCH_MAX))
    if len(hp):
        simple[hp] = _half_plane(dx, dy, ridx[hp], rlen[hp], merged[hp], hstart[hp], hlen[hp])
    # runs grouped by cell (in path order within a cell)
    order = _stable_order(rcell)
    ridx, rlen, merged, rcell, hstart, hlen, simple = (
        ridx[order], rlen[order], merged[order], rcell[order], hstart[order], hlen[order],
        simple[order])
    gstart = _group_starts(rcell)
    gcnt = _run_lengths(gstart, len(rcell))
    cells = rcell[gstart]
    gsimple = np.logical_and.reduceat(simple, gstart)
    every = _FLAG_EVERYTHING if everything is None else everything
    ok = (gcnt == 1) & gsimple & (not every)
    npc = np.add.reduceat(rlen, gstart)
    # (cells of chords alone, one piece a run, may hold many more: those
    # whose chords cross nowhere cost the sort of their ends, see
    # _chords_cross)
    chords = npc == gcnt
    faces = ((not every) & (gcnt >= 2) & gsimple
             & (((gcnt <= _FACES_RUNS) & (npc <= _FACES_PIECES))
                | (chords & (npc <= _FACES_CHORDS))))
    wi = np.flatnonzero(faces)
    d_cells, d_vals = [], []
    if len(wi):
        runs = (ridx, rlen, merged, hstart, hlen)
        eo = evenodd if np.ndim(evenodd) == 0 else evenodd[ridx[gstart[wi]]]
        eo = np.broadcast_to(np.asarray(eo, bool), (len(wi),))
        lw = left_of(cells[wi])
        # cells whose runs are single pieces (most, where strokes cross) go
        # apart when they are all or enough to pay for a call of their own:
        # their pieces are their runs.  Each part in slices of cells of
        # bounded work: the arrays (per run, per pair of pieces of a cell)
        # stay within a few MB
        p = npc[wi]
        one = chords[wi]
        if not one.all() and np.count_nonzero(one) < _FACES_SINGLE_MIN:
            one = p > _FACES_PIECES             # (only single runs test their crossings first)
        for single in (True, False):
            part = np.flatnonzero(one == single)
            # (cells of many chords test their pairs only where some
            # cross, and then in slices of their own)
            q = p[part]
            pair_work = np.where(single & (q > _CHORDS_TESTED), q, q * (q - 1) // 2)
            for sl in _slices(4 * gcnt[wi[part]] + pair_work, _FACES_WORK):
                k = part[sl]
                w = wi[k]
                lin, good, val = _faces(xa, ya, xb, yb, col, row, dx, dy, runs, gstart[w], gcnt[w],
                                        lw[k], eo[k], single)
                ok[w] = good
                dv = np.flatnonzero(good & ~lin)
                d_cells.append(cells[w[dv]])
                d_vals.append(val[dv])
    if d_cells:
        direct = (np.concatenate(d_cells), np.concatenate(d_vals))
    else:
        direct = (empty[0], np.zeros(0))
    fg = np.flatnonzero(~ok)
    rr = concat_ranges(gstart[fg], gcnt[fg])
    pieces, _ = _run_pieces(ridx[rr], rlen[rr], merged[rr], hstart[rr], hlen[rr])
    counts = np.add.reduceat(rlen[rr], np.cumsum(gcnt[fg]) - gcnt[fg]) if len(fg) else gcnt[:0]
    return cells[fg], pieces, counts, direct


def _run_pieces(ridx, rlen, merged, hstart, hlen):
    """Piece indices of runs, run after run (a merged run: tail part, then
    head part), and the offset of each run's first one."""
    tail = np.where(merged, rlen - hlen, rlen)
    both = np.concatenate([ridx, hstart[merged]])
    lens = np.concatenate([tail, hlen[merged]])
    # order: each run's tail part then, for merged runs, its head part
    slot = np.concatenate([2 * np.arange(len(ridx)), 2 * np.flatnonzero(merged) + 1])
    o = np.argsort(slot)                 # (distinct keys)
    idx = concat_ranges(both[o], lens[o])
    return idx, np.cumsum(rlen) - rlen


def _half_plane(dx, dy, ridx, rlen, merged, hstart, hlen):
    """Whether the directions of each run's pieces fit in an open half-plane
    (the run is then monotone along some direction, so it cannot cross
    itself); zero-length pieces are ignored.  Sorted by angle, some
    circular gap between consecutive directions must exceed pi."""
    idx, _ = _run_pieces(ridx, rlen, merged, hstart, hlen)
    owner = np.repeat(np.arange(len(ridx)), rlen)
    pdx, pdy = dx[idx], dy[idx]
    moving = (pdx != 0) | (pdy != 0)
    owner = owner[moving]
    good = np.ones(len(ridx), bool)
    if len(owner) == 0:
        return good
    ang = np.arctan2(pdy[moving], pdx[moving]) + np.pi          # [0, 2 pi]
    ang = np.sort(owner * 8.0 + ang) - owner * 8.0               # sorted per run
    m = len(ang)
    gfirst = _group_starts(owner)
    glast = gfirst + _run_lengths(gfirst, m) - 1
    gap = np.empty(m)
    gap[1:] = ang[1:] - ang[:-1]
    gap[gfirst] = ang[gfirst] + 2 * np.pi - ang[glast]
    good[owner[gfirst]] = np.maximum.reduceat(gap, gfirst) > np.pi * (1 + 1e-9)
    return good


def _perimeter(u, v, dx, dy):
    """Where a run's end point (u, v) (cell units) lies on the cell's
    boundary and how the winding changes there.

    The boundary is walked clockwise on screen (y down) from the top-left
    corner: top side left to right (t = u), right side downwards
    (t = 1 + v), bottom right to left (t = 3 - u), left side upwards
    (t = 4 - v).  Walking just inside the boundary across a piece of
    direction (dx, dy) changes the winding by the sign of the cross product
    of the walking direction and (dx, dy) (a downward piece adds one to its
    right).  Returns (t, change, ok); ok is False off the boundary, at the
    top-left corner, for a piece along the side (no change) and at a
    corner where the two sides disagree.
    """
    top, right, bottom, lside = v == 0, u == 1, v == 1, u == 0
    t = np.where(top, u, np.where(right, 1.0 + v, np.where(bottom, 3.0 - u, 4.0 - v)))
    s_t, s_r = np.sign(dy), -np.sign(dx)
    s_b, s_l = -s_t, -s_r
    d = np.where(top, s_t, np.where(right, s_r, np.where(bottom, s_b, s_l)))
    ok = (top | right | bottom | lside) & (d != 0) & ~(top & lside)
    ok &= ~(top & right) | (s_t == s_r)
    ok &= ~(right & bottom) | (s_r == s_b)
    ok &= ~(bottom & lside) | (s_b == s_l)
    return t, d, ok


def _faces(xa, ya, xb, yb, col, row, dx, dy, runs, gstart, gcnt, left, evenodd, single=False):
    """Coverage of cells holding several simple runs, each from the cell's
    boundary to its boundary, exactly and directly.

    The runs cut the cell into faces of constant winding, so the coverage
    is ``sum(f(w_F) area(F))`` over the faces F, and by the shoelace
    formula each face's area is a sum over its boundary: stretches of the
    cell's boundary and stretches of pieces.  Gathered by what they lie
    on:

    * a stretch of the cell's boundary between consecutive run ends (in
      the boundary parameter t of :func:`_perimeter`) borders one face,
      whose winding is ``w0`` plus the changes of the ends before it; it
      adds ``f(w) (G(t1) - G(t0))`` (:func:`_boundary_integral`);
    * a stretch of a piece ``P + tau E`` borders two faces, whose windings
      differ by one: ``w`` on the side of ``(E_y, -E_x)`` and ``w - 1`` on
      the side of ``(-E_y, E_x)``; it adds ``(f(w - 1) - f(w)) cross(P, E)
      / 2`` per unit of tau.  Along a run, ``w`` starts at the winding
      after the run's first end on the boundary and changes only where the
      run crosses another run: by ``sign(cross(E, E'))`` crossing a piece
      of direction E'.

    The crossings come from segment tests over the pairs of pieces of
    different runs of a cell; touching or overlapping pieces (and pieces
    along a side, run ends meeting) leave the cell to the general method.

    The winding at the cell's top-left corner, ``w0``, is ``left`` (the
    winding integrated along the left side) corrected by the run ends on
    the left side; a run's winding change ``sigma`` where the boundary walk
    first meets it bounds the windings to ``w0 + sum(sigma < 0)`` ..
    ``w0 + sum(sigma > 0)``: where the fill rule is linear on that range,
    the running sum is exact and the crossings are not looked for.

    Parameters
    ----------
    xa, ya, xb, yb, col, row, dx, dy : (P,) ndarray
        All pieces (as for :func:`_flag`), their cells and directions.
    runs : tuple of (R,) ndarray
        ``(ridx, rlen, merged, hstart, hlen)``: the runs grouped by cell
        (see :func:`_flag` and :func:`_run_pieces`).
    gstart, gcnt : (G,) int64 ndarray
        First run and number of runs of each cell.
    left : (G,) float64 ndarray
        The winding integrated over each cell's left side.
    evenodd : bool or (G,) bool ndarray
    single : bool
        Every run of these cells is one piece (not merged): a run's end
        points and its piece are read once.

    Returns
    -------
    linear : (G,) bool ndarray
        The running sum is exact (no value computed).
    good : (G,) bool ndarray
        The cell is decided: linear, or ``value`` holds its coverage.
    value : (G,) float64 ndarray
        Coverage where ``good & ~linear``.
    """
    ridx, rlen, merged, hstart, hlen = runs
    G = len(gstart)
    rr = concat_ranges(gstart, gcnt)                # runs, group after group
    gid = np.repeat(np.arange(G), gcnt)
    r_idx = f = ridx[rr]
    if single:
        last = f
    else:
        r_len, r_m, r_hs, r_hl = rlen[rr], merged[rr], hstart[rr], hlen[rr]
        last = np.where(r_m, r_hs + r_hl - 1, r_idx + r_len - 1)
    cx = col[f].astype(np.float64)
    cy = row[f].astype(np.float64)
    u0, v0 = xa[f] - cx, ya[f] - cy
    u1, v1 = xb[last] - cx, yb[last] - cy
    if single:
        # (u0 = xa - cx is exact for a point of cell cx (Sterbenz), so
        # u1 - u0 is the piece's dx itself)
        fdx, fdy = u1 - u0, v1 - v0
        ldx, ldy = fdx, fdy
    else:
        fdx, fdy = dx[f], dy[f]
        ldx, ldy = dx[last], dy[last]
    t0, d0, ok0 = _perimeter(u0, v0, fdx, fdy)
    t1, d1, ok1 = _perimeter(u1, v1, ldx, ldy)
    # (an end outside the cell by rounding, or at the top-left corner's
    # t = 0 or 4, is not on the boundary as the walk reads it)
    ends_in = ((np.minimum(np.minimum(u0, v0), np.minimum(u1, v1)) >= 0)
               & (np.maximum(np.maximum(u0, v0), np.maximum(u1, v1)) <= 1)
               & (t0 > 0) & (t0 < 4) & (t1 > 0) & (t1 < 4))
    bad = np.zeros(G, bool)
    bad[gid[~(ok0 & ok1 & ends_in)]] = True
    onl0 = (u0 == 0) & (v0 > 0) & (v0 < 1)
    onl1 = (u1 == 0) & (v1 > 0) & (v1 < 1)
    w0 = left + np.bincount(gid, weights=np.where(onl0, d0 * (1.0 - v0), 0.0)
                            + np.where(onl1, d1 * (1.0 - v1), 0.0), minlength=G)
    w0r = np.rint(w0)
    bad |= np.abs(w0 - w0r) > 1e-6
    eo = np.broadcast_to(np.asarray(evenodd, bool), (G,))
    # one fill rule for all the cells (the usual case): a scalar from here on
    rule = bool(eo[0]) if G and (eo.all() or not eo.any()) else None
    sig = np.where(t0 < t1, d0, d1)
    b_lo = w0r + np.bincount(gid, weights=np.minimum(sig, 0.0), minlength=G)
    b_hi = w0r + np.bincount(gid, weights=np.maximum(sig, 0.0), minlength=G)
    linear = ~bad & _linear_on(b_lo, b_hi, eo if rule is None else rule)
    value = np.zeros(G)
    todo = ~bad & ~linear
    if not todo.any():
        return linear, ~bad, value
    kr = np.flatnonzero(todo[gid])                  # runs of the cells to compute
    rg = gid[kr]
    # -- the boundary: run ends in order, the windings between them ---------
    nk = len(kr)
    # (each run's two ends side by side: a cell's ends are together before
    # the sort, which then has less to do)
    eg = np.repeat(rg, 2)
    et = np.empty(2 * nk)
    et[0::2], et[1::2] = t0[kr], t1[kr]
    ed = np.empty(2 * nk)
    ed[0::2], ed[1::2] = d0[kr], d1[kr]
    o = np.argsort(eg * 8.0 + et, kind='stable')  # (tied keys flag their cell below)
    eg, et, ed = eg[o], et[o], ed[o]
    same = (eg[1:] == eg[:-1]) & (et[1:] == et[:-1])
    bad[eg[1:][same]] = True
    cs = np.cumsum(ed)
    efirst = _group_starts(eg)
    elen = _run_lengths(efirst, len(eg))
    w_after = w0r[eg] + cs - np.repeat((cs - ed)[efirst], elen)     # after each end
    t_next = np.empty_like(et)
    t_next[:-1] = et[1:]
    t_next[efirst[1:] - 1] = 4.0
    t_next[-1] = 4.0
    Gb = _boundary_integral
    value += np.bincount(eg, weights=_fill_of(w_after, eo[eg] if rule is None else rule)
                         * (Gb(t_next) - Gb(et)),
                         minlength=G)
    ug = eg[efirst]
    value[ug] += _fill_of(w0r[ug], eo[ug] if rule is None else rule) * Gb(et[efirst])
    pos = np.empty(len(o), np.int64)
    pos[o] = np.arange(len(o))
    p0, p1 = pos[0::2], pos[1::2]                   # where each run's ends are
    w_start = w_after[p0]                           # the winding after each run's start
    # -- the pieces of those runs ------------------------------------------
    if single:
        npc = nk
        prun = np.arange(nk)
        pg = rg
        ax, ay, bx, by = u0[kr], v0[kr], u1[kr], v1[kr]
    else:
        pidx, poff = _run_pieces(r_idx[kr], r_len[kr], r_m[kr], r_hs[kr], r_hl[kr])
        npc = len(pidx)
        prun = np.repeat(np.arange(nk), r_len[kr])  # run (of kr) of each piece
        pg = rg[prun]
        ox, oy = cx[kr][prun], cy[kr][prun]
        ax, ay = xa[pidx] - ox, ya[pidx] - oy
        bx, by = xb[pidx] - ox, yb[pidx] - oy
    # pieces along a side, or with an end outside the cell (by rounding):
    # the faces' boundaries would not be what the run ends say (a run of
    # one piece was checked with its ends: inside the cell, and a piece
    # along a side changes no winding there, which _perimeter refuses)
    if not single:
        along = (((ax == 0) & (bx == 0)) | ((ax == 1) & (bx == 1))
                 | ((ay == 0) & (by == 0)) | ((ay == 1) & (by == 1))
                 | (np.minimum(np.minimum(ax, ay), np.minimum(bx, by)) < 0)
                 | (np.maximum(np.maximum(ax, ay), np.maximum(bx, by)) > 1))
        bad[pg[along]] = True
    pex, pey = bx - ax, by - ay
    K = 0.5 * (ax * pey - ay * pex)
    # -- crossings of pieces of different runs of a cell --------------------
    cstart = _group_starts(pg)                      # pieces of a cell are consecutive
    cend = cstart + _run_lengths(cstart, npc)
    pend = np.repeat(cend, cend - cstart)           # each piece's cell end
    # each piece against the later pieces of its cell (chords: only in
    # cells where some of them cross, see _chords_cross)
    nb = pend - np.arange(npc) - 1
    if single and (gcnt > _CHORDS_TESTED).any():
        crossed = _chords_cross(p0, p1, rg, G)
        # (cells of many chords that cross are left to the general method)
        wide = crossed & (gcnt > _FACES_PIECES)
        bad |= wide
        nb[~(crossed & ~wide)[pg]] = 0
    # (in slices of pieces of bounded pair work: the pair arrays stay small
    # whatever the cells; the crossings they find are few beside them)
    ends = None
    if single:
        # (chords: two cross exactly when their ends interleave along the
        # boundary, see _chords_cross; only those pairs are measured)
        ends = (np.minimum(p0, p1), np.maximum(p0, p1))
    found = [_crossings(ax, ay, bx, by, pex, pey, nb, None if single else prun, sl, ends)
             for sl in _slices(nb, _FACES_WORK)]
    for touch, _, _, _, _, _ in found:
        bad[pg[touch]] = True
    qa, qb, ta, tb, turn = (found[0][i] if len(found) == 1 else
                            np.concatenate([f[i] for f in found]) for i in range(1, 6))
    del found
    # events along the pieces: (piece, tau, change of w on the right)
    ev_p = np.concatenate([qa, qb])
    ev_t = np.concatenate([ta, tb])
    ev_d = np.concatenate([turn, -turn])
    eo_p = eo[pg] if rule is None else rule
    # the windings at each piece's start: the run's start plus the changes
    # on its earlier pieces
    if single:
        w_p = w_start
    else:
        dsum = np.bincount(ev_p, weights=ev_d, minlength=npc)
        cd = np.cumsum(dsum)
        w_p = w_start[prun] + (cd - dsum) - np.repeat((cd - dsum)[poff], r_len[kr])

    def h(w, ev):
        return _fill_of(w - 1.0, ev) - _fill_of(w, ev)
    contrib = K * h(w_p, eo_p)
    if len(ev_p):
        # by piece, then along it (tau < 1: the key keeps them apart)
        so = np.argsort(ev_p + 0.5 * ev_t, kind='stable')
        ev_p, ev_t, ev_d = ev_p[so], ev_t[so], ev_d[so]
        c = np.cumsum(ev_d)
        gs = _group_starts(ev_p)
        before = w_p[ev_p] + (c - ev_d) - np.repeat((c - ev_d)[gs], _run_lengths(gs, len(ev_p)))
        after = before + ev_d
        ev_eo = eo_p[ev_p] if rule is None else rule
        contrib += np.bincount(ev_p, weights=K[ev_p] * (1.0 - ev_t)
                               * (h(after, ev_eo) - h(before, ev_eo)), minlength=npc)
    value += np.bincount(pg, weights=contrib, minlength=G)
    good = ~bad
    np.clip(value, 0.0, 1.0, out=value)
    value[value < _RESIDUE] = 0.0
    return linear & good, good, value


def _crossings(ax, ay, bx, by, ex, ey, nb, run, sl, ends=None):
    """The pair tests of :func:`_faces` for pieces ``sl`` (a slice), each
    against the ``nb`` pieces that follow it (in its cell), pieces of one
    run (``run``; None: every piece is its own run) excepted.  ``ends``:
    for chords of a cell (straight pieces from its boundary to its
    boundary, no two ends at one point), the positions ``(first, last)``
    of each chord's ends in boundary order; the pairs whose ends do not
    interleave cannot meet and are not measured.

    Returns ``(touch, qa, qb, ta, tb, turn)``: pieces of pairs that meet
    other than by a proper crossing (touching, overlapping, or too close
    to tell), and for every proper crossing the two pieces (qa before qb),
    where it lies along each (``tau`` in (0, 1)) and ``sign(cross(E_qa,
    E_qb))`` for their directions ``E = (ex, ey)``.
    """
    nbs = nb[sl]
    ia = np.repeat(np.arange(sl.start, sl.stop), nbs)
    ib = ia + 1 + (np.arange(len(ia)) - np.repeat(np.cumsum(nbs) - nbs, nbs))
    if run is not None:
        other = run[ia] != run[ib]
        ia, ib = ia[other], ib[other]
    if ends is not None:
        first, last = ends
        fa, la = first[ia], last[ia]
        fb, lb = first[ib], last[ib]
        meet = ((fa < fb) & (fb < la)) != ((fa < lb) & (lb < la))
        ia, ib = ia[meet], ib[meet]
    o1, o2, o3, o4 = _orientations(ax[ia], ay[ia], bx[ia], by[ia], ax[ib], ay[ib], bx[ib], by[ib])
    e = _MEET_EPS
    mi = np.flatnonzero(~_apart(o1, o2, o3, o4))
    a1, a2, a3, a4 = o1[mi], o2[mi], o3[mi], o4[mi]
    proper = ((np.minimum(np.abs(a1), np.abs(a2)) > e) & (np.minimum(np.abs(a3), np.abs(a4)) > e)
              & (a1 * a2 < 0) & (a3 * a4 < 0))
    xi = mi[proper]
    qa, qb = ia[xi], ib[xi]
    ta = a1[proper] / (a1[proper] - a2[proper])      # along qa
    tb = a3[proper] / (a3[proper] - a4[proper])      # along qb
    turn = np.sign(ex[qa] * ey[qb] - ey[qa] * ex[qb])
    return ia[mi[~proper]], qa, qb, ta, tb, turn


def _chords_cross(first, second, cell, G):
    """Which cells hold two chords that cross.

    Chords are straight pieces from a cell's boundary to its boundary
    (each end ``t`` as :func:`_perimeter` walks it, no two ends of a cell
    at the same ``t``).  Two chords of a convex cell cross if and only if
    their ends interleave along its boundary.  Read along the boundary,
    each chord's first end an opening bracket and its other end a closing
    one, a cell's chords cross nowhere exactly when its brackets nest, and
    they nest exactly when every chord's opening bracket leaves the depth
    at the value its closing bracket finds (the brackets of one depth then
    alternate, opening and closing, and a chord can only be closed by the
    closing bracket right after its opening one): ``O(k)`` for ``k``
    chords once the ends are in order, where testing every pair costs
    ``O(k**2)``.

    Parameters
    ----------
    first, second : (K,) int64 ndarray
        Where each chord's two ends are in boundary order: the 2K ends
        cell after cell, each cell's by ``t``.
    cell : (K,) int64 ndarray
        The cell (0..G-1) of each chord.
    G : int
        Number of cells.

    Returns
    -------
    (G,) bool ndarray
        True for the cells where two chords cross.
    """
    opening = np.minimum(first, second)
    closing = np.maximum(first, second)
    step = np.zeros(2 * len(first), np.int32)
    step[opening] = 1
    step[closing] = -1
    # (each cell's brackets balance: the depth is 0 between cells)
    depth = np.cumsum(step)
    out = np.zeros(G, bool)
    out[cell[depth[opening] != depth[closing] + 1]] = True
    return out


def _slices(work, limit=_CHUNK_WORK // 8):
    """Consecutive slices of items whose summed ``work`` stays about
    ``limit`` (one item at least)."""
    c = np.cumsum(work)
    out = []
    lo = 0
    n = len(c)
    while lo < n:
        base = c[lo - 1] if lo else 0
        hi = min(max(int(np.searchsorted(c, base + limit, side='right')), lo + 1), n)
        out.append(slice(lo, hi))
        lo = hi
    return out


def _fill_of(w, evenodd):
    """The fill rule of integer windings ``w`` (int64, or float64 holding
    whole numbers): 1.0 where odd (``evenodd`` True) or nonzero, else 0.0;
    ``evenodd`` broadcasts against ``w``."""
    if w.dtype.kind == 'f':
        w = w.astype(np.int64)
    if np.ndim(evenodd) == 0:
        return ((w & 1) if evenodd else (w != 0)).astype(np.float64)
    return np.where(evenodd, w & 1, w != 0).astype(np.float64)


def _linear_on(mn, mx, eo):
    """Whether the fill rule is linear on the integers mn..mx (evenodd:
    two adjacent values; nonzero: within [0, 1], [-1, 0], >= 1 or <= -1)."""
    if np.ndim(eo) == 0 and eo:
        return mx - mn <= 1
    nonzero = ((mn >= 0) & (mx <= 1)) | (mn >= 1) | ((mx <= 0) & (mn >= -1)) | (mx <= -1)
    return nonzero if np.ndim(eo) == 0 else np.where(eo, mx - mn <= 1, nonzero)


#: Rounding margin of the orientation tests of :func:`_apart`.
_MEET_EPS = 1e-12


def _orientations(ax, ay, bx, by, cx, cy, dx, dy):
    """Cross products ``(o1, o2, o3, o4)``: the sides of a and b relative
    to line cd (o1, o2) and of c and d relative to line ab (o3, o4)."""
    ux, uy = bx - ax, by - ay
    vx, vy = dx - cx, dy - cy
    return (vx * (ay - cy) - vy * (ax - cx), vx * (by - cy) - vy * (bx - cx),
            ux * (cy - ay) - uy * (cx - ax), ux * (dy - ay) - uy * (dx - ax))


def _apart(o1, o2, o3, o4, eps=_MEET_EPS):
    """Where one segment lies strictly on one side of the other's line (by
    more than ``eps``): the pairs that cannot meet."""
    return (((o1 > eps) & (o2 > eps)) | ((o1 < -eps) & (o2 < -eps))
            | ((o3 > eps) & (o4 > eps)) | ((o3 < -eps) & (o4 < -eps)))


# -- the exact recompute --------------------------------------------------------

def _exact(xa, ya, xb, yb, col, row, pieces, counts, left, evenodd, depth):
    """Exact coverage of the flagged cells.

    In a cell, the covered length ``g(y)`` of the horizontal line at height
    ``y`` is linear in ``y`` between *critical heights*: the cell's top and
    bottom, the end points of its pieces and the heights where two of its
    pieces intersect; the midpoint rule on those intervals is therefore
    exact.  On a sample line, the winding just left of the cell is
    ``A(y) = C + sum(s_e [y > y_e])``: every chain crossing the cell's left
    side does so where one of the cell's own pieces starts (``s = -1``) or
    ends (``s = +1``) on that side, and the constant ``C`` is fitted to the
    running sum ``left`` (the integral of ``A``).  Crossings inside the
    cell are sorted and the fill rule is applied span by span.  Cells with
    more than ``_EXACT_PIECES`` distinct pieces (equal pieces merged with a
    multiplicity) are refined instead: their pieces, scaled to a
    ``_REFINE`` x ``_REFINE`` grid with ``A`` as edges left of it, are scan
    converted by the same kernel (recursively), as long as their distinct
    pieces times ``_REFINE ** depth`` stay within ``_REFINE_WORK``.  The
    others, cells of many pieces that do not part (nearly coincident
    lines, hundreds of crossings in one pixel), take the midpoint rule on
    ``_SAMPLE_LINES`` evenly spaced lines, each line exact: ``O(k log k)``
    per line for ``k`` pieces.  Its error comes from the strips holding a
    piece's end or a crossing; a single nearly horizontal edge misplaced by
    half a strip costs at most 1/32 of the cell's area.  Such cells hold
    more than 1024 pieces at the pixel level, more than 256 in a quarter
    pixel, 64 in a sixteenth, 16 in a 64th.

    Parameters
    ----------
    xa, ya, xb, yb, col, row :
        All pieces of the box, as for :func:`_flag`.
    pieces, counts : int64 ndarray
        The pieces of the flagged cells, cell after cell, and their number
        per cell (as :func:`_flag` returns them).
    left : (F,) float64 ndarray
        The winding integrated over each flagged cell's left side.
    evenodd : bool or (F,) bool ndarray
    depth : int
        Refinement level (0 for the canvas).

    Returns
    -------
    (F,) float64 ndarray
        Coverage in [0, 1] (rounding residue set to 0).
    """
    F = len(counts)
    k = counts
    cx = col[pieces].astype(np.float64)
    cy = row[pieces].astype(np.float64)
    ua, va = xa[pieces] - cx, ya[pieces] - cy
    ub, vb = xb[pieces] - cx, yb[pieces] - cy
    fi = np.repeat(np.arange(F), k)
    # left-side events: a piece starting on the left side (s = -1) or
    # ending on it (s = +1)
    # (<= 0: rounding may leave an end a hair left of the side)
    la, lb = ua <= 0, ub <= 0
    C = np.rint(left - np.bincount(fi, weights=np.where(lb, 1.0 - vb, 0.0)
                                   - np.where(la, 1.0 - va, 0.0), minlength=F))
    eo = np.broadcast_to(np.asarray(evenodd, bool), (F,))
    out = np.zeros(F)
    first = np.cumsum(k) - k
    small = k <= _EXACT_PIECES
    # (pieces, cells, padded piece arrays, first piece and count of each cell)
    groups = []
    kb = _PIECE_BINS[np.minimum(np.searchsorted(_PIECE_BINS, k), len(_PIECE_BINS) - 1)]
    kb[small] = _coarsen(kb[small], _piece_work)
    if small.any():
        pad = _pad((ua, va, ub, vb, np.ones(len(ua))))
        for kk in distinct_values(kb[small]).tolist():
            c = np.flatnonzero(small & (kb == kk))
            groups.append((kk, c, pad, first[c], k[c]))
    big = np.flatnonzero(~small)
    crowded = big
    sampled = None
    if len(big):
        # equal pieces merged (opposite ones cancel): stacked copies of one
        # outline are few distinct pieces
        ix = concat_ranges(first[big], k[big])
        d_f, d_p, d_m = _merge_pieces(np.repeat(np.arange(len(big)), k[big]),
                                      [ua[ix], va[ix], ub[ix], vb[ix]], np.ones(len(ix)))
        dpad = _pad(tuple(d_p) + (d_m,))
        kd = np.bincount(d_f, minlength=len(big))
        dfirst = np.cumsum(kd) - kd
        fits = kd <= _EXACT_PIECES
        kdb = _PIECE_BINS[np.minimum(np.searchsorted(_PIECE_BINS, kd), len(_PIECE_BINS) - 1)]
        kdb[fits] = _coarsen(kdb[fits], _piece_work)
        for kk in distinct_values(kdb[fits]).tolist():
            sel = np.flatnonzero(fits & (kdb == kk))
            groups.append((kk, big[sel], dpad, dfirst[sel], kd[sel]))
        crowded = big[~fits]
        part = kd[~fits] * _REFINE ** depth <= _REFINE_WORK
        if not part.all():
            sel = np.flatnonzero(~fits)[~part]
            sampled = (big[sel], dpad, dfirst[sel], kd[sel])
            crowded = crowded[part]
    for kk, cells_k, pad, pf, pk in groups:
        S = 1 + 2 * kk + kk * (kk - 1) // 2
        step = max(1, _CHUNK_WORK // (S * max(kk, 1)))
        for lo in range(0, len(cells_k), step):
            c = cells_k[lo:lo + step]
            pu, pv, qu, qv, pm = _padded(pad, pf[lo:lo + step], pk[lo:lo + step], kk)
            out[c] = _exact_small(pu, pv, qu, qv, pm, C[c], eo[c])
    if sampled is not None:
        c, pad, pf, pk = sampled
        out[c] = _sampled(pad, pf, pk, C[c], eo[c])
    if len(crowded):
        ix = concat_ranges(first[crowded], k[crowded])
        out[crowded] = _refine(ua[ix], va[ix], ub[ix], vb[ix], k[crowded], C[crowded],
                               eo[crowded], depth)
    np.clip(out, 0.0, 1.0, out=out)
    out[out < _RESIDUE] = 0.0
    return out


def _pad(arrays):
    """Piece arrays ``(ua, va, ub, vb, m)`` with one padding piece
    appended: a point below the cell (no crossing, no event, no
    intersection) of multiplicity 0, for :func:`_padded`."""
    return tuple(np.append(a, v) for a, v in zip(arrays, (2.0, 2.0, 2.0, 2.0, 0.0)))


def _padded(pad, pf, pk, kk):
    """The pieces of cells as five (n, kk) arrays: cell i's ``pk[i]``
    pieces from ``pf[i]`` on (in the arrays of :func:`_pad`), then the
    padding piece."""
    r = np.arange(kk)
    ix = np.where(r < pk[:, None], pf[:, None] + r, len(pad[0]) - 1)
    return tuple(a[ix] for a in pad)


def _sampled(pad, pf, pk, C, eo, lines=_SAMPLE_LINES):
    """Coverage of cells by the midpoint rule on ``lines`` evenly spaced
    lines (see :func:`_exact`).

    Parameters
    ----------
    pad : tuple of five (P + 1,) float64 ndarrays
        Piece ends ``ua, va, ub, vb`` in cell units and multiplicities,
        padded (:func:`_pad`).
    pf, pk : (F,) int64 ndarray
        First piece and number of pieces of each cell.
    C : (F,) float64 ndarray
        Winding just left of each cell before its events.
    eo : (F,) bool ndarray
        Fill rules.

    Returns
    -------
    (F,) float64 ndarray
    """
    F = len(pk)
    out = np.zeros(F)
    # cells padded to powers of two of pieces, batches of bounded work
    kb = 1 << np.ceil(np.log2(np.maximum(pk, 1))).astype(np.int64)
    H = np.linspace(0.0, 1.0, lines + 1)
    for kk in distinct_values(kb).tolist():
        cells = np.flatnonzero(kb == kk)
        step = max(1, _CHUNK_WORK // (lines * kk))
        for lo in range(0, len(cells), step):
            c = cells[lo:lo + step]
            pu, pv, qu, qv, pm = _padded(pad, pf[c], pk[c], kk)
            out[c] = _sample_lines(np.broadcast_to(H, (len(c), lines + 1)), pu, pv, qu, qv, pm,
                                   C[c], eo[c])
    return out


def _boundary_integral(t):
    """``G(t)``: the integral of ``(u dv - v du) / 2`` along the cell's
    boundary, walked as in :func:`_perimeter` from the top-left corner to
    ``t`` (0 along the top, rising by 1/2 along the right side and along the
    bottom, 0 along the left side; ``G(4) = 1``, the cell's area)."""
    return np.clip(t - 1.0, 0.0, 2.0) * 0.5


def _merge_pieces(g, p, m):
    """Pieces (group g, end points p = [ua, va, ub, vb], multiplicity m)
    with equal group and end points merged, a piece and its reverse
    cancelling (each is first directed from its lexicographically smaller
    end, its multiplicity negated when turned); zero multiplicities are
    dropped, the result is sorted by group."""
    if len(g) == 0:
        return g, p, m
    turn = (p[0] > p[2]) | ((p[0] == p[2]) & (p[1] > p[3]))
    p = [np.where(turn, p[2], p[0]), np.where(turn, p[3], p[1]),
         np.where(turn, p[0], p[2]), np.where(turn, p[1], p[3])]
    m = np.where(turn, -m, m)
    o = np.lexsort((p[3], p[2], p[1], p[0], g))
    g, m = g[o], m[o]
    p = [a[o] for a in p]
    new = np.ones(len(g), bool)
    new[1:] = ((g[1:] != g[:-1]) | (p[0][1:] != p[0][:-1]) | (p[1][1:] != p[1][:-1])
               | (p[2][1:] != p[2][:-1]) | (p[3][1:] != p[3][:-1]))
    st = np.flatnonzero(new)
    tot = np.add.reduceat(m, st)
    keep = st[tot != 0]
    return g[keep], [a[keep] for a in p], tot[tot != 0]


# Work (in elements of the arrays of _sample_lines) that costs about as
# much as one more call of it: classes of cells are merged into the next
# larger class (padded) while the padding costs less than this.
_CLASS_WORK = 3000


def _piece_work(kk):
    """Work per cell of :func:`_exact_small` with ``kk`` pieces: sample
    heights times pieces."""
    return (1 + 2 * kk + kk * (kk - 1) // 2) * max(kk, 1)


def _coarsen(b, work, budget=_CLASS_WORK):
    """Class sizes ``b`` (int array, one per cell) with small classes
    merged upwards: from the smallest class on, a class joins the next
    larger one when its cells padded to that size cost at most ``budget``
    more work (``work(size)`` per cell).  Fewer, larger batches where the
    cells are few; the same classes where they are many."""
    if len(b) == 0:
        return b
    u, cnt = np.unique(b, return_counts=True)
    if len(u) == 1:
        return b
    u = u.tolist()
    cnt = cnt.tolist()
    to = list(u)
    acc = 0
    for i in range(len(u) - 1):
        acc += cnt[i]
        if acc * (work(u[i + 1]) - work(u[i])) <= budget:
            for j in range(i + 1):
                if to[j] == u[i]:
                    to[j] = u[i + 1]
        else:
            acc = 0
    if to == u:
        return b
    return np.asarray(to, dtype=b.dtype)[np.searchsorted(u, b)]


# x positions are sorted as integer keys: x * 2**36 (x in [0, 1]) shifted
# left by 20 bits, plus the crossing's signed multiplicity + 2**19
_XSCALE = float(1 << 36)
_MBITS = 20
_MOFF = 1 << (_MBITS - 1)
_NOKEY = ((1 << 38) << _MBITS) + _MOFF       # no crossing: x = 4, multiplicity 0
# numbers of sample heights cells are padded to (fewer, larger batches)
_HEIGHT_BINS = np.array([4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128])
# numbers of pieces cells are padded to
_PIECE_BINS = np.array([1, 2, 3, 4, 6, 8, 12])


def _exact_small(ua, va, ub, vb, m, C, eo):
    """:func:`_exact` for F cells of k pieces each.

    Parameters
    ----------
    ua, va, ub, vb, m : (F, k) float64 ndarray
        Piece ends in cell units and multiplicities (a piece counts ``m``
        times).  A piece starting on the left side (``ua <= 0``) is a
        left-side event of sign ``-m`` at ``va``, one ending there ``+m``
        at ``vb``.  Padding pieces lie below the cell.
    C : (F,) float64 ndarray
        The winding just left of the cell before the events.
    eo : (F,) bool ndarray
        Fill rules.

    Returns
    -------
    (F,) float64 ndarray
        Coverage.
    """
    F, k = ua.shape
    P = k * (k - 1) // 2
    H = np.empty((F, 2 + 2 * k + P))
    H[:, 0] = 0.0
    H[:, 1] = 1.0
    H[:, 2:2 + k] = va
    H[:, 2 + k:2 + 2 * k] = vb
    if P:
        i, j = np.triu_indices(k, 1)
        ax, ay = ua[:, i], va[:, i]
        ux, uy = ub[:, i] - ax, vb[:, i] - ay
        vx, vy = ub[:, j] - ua[:, j], vb[:, j] - va[:, j]
        qx, qy = ua[:, j] - ax, va[:, j] - ay
        den = ux * vy - uy * vx
        with np.errstate(all='ignore'):
            t = (qx * vy - qy * vx) / den
            u = (qx * uy - qy * ux) / den
        eps = 1e-9
        hit = (den != 0) & (t >= -eps) & (t <= 1 + eps) & (u >= -eps) & (u <= 1 + eps)
        H[:, 2 + 2 * k:] = np.where(hit, ay + np.where(hit, t, 0.0) * uy, 0.0)
    np.clip(H, 0.0, 1.0, out=H)
    H.sort(axis=1)
    # distinct heights only: cells grouped by their number of them
    new = np.empty(H.shape, bool)
    new[:, 0] = True
    np.not_equal(H[:, 1:], H[:, :-1], out=new[:, 1:])
    nd = new.sum(1)
    # a few width classes (padded with the bottom height: empty intervals)
    width = np.searchsorted(_HEIGHT_BINS, nd)
    width = np.where(width < len(_HEIGHT_BINS), _HEIGHT_BINS[np.minimum(width, len(_HEIGHT_BINS) - 1)],
                     H.shape[1])
    width = np.minimum(width, H.shape[1])
    width = _coarsen(width, lambda q: q * k)
    out = np.zeros(F)
    for q in distinct_values(width).tolist():
        rows = np.flatnonzero(width == q)
        sub = new[rows]
        rank = np.cumsum(sub, axis=1) - 1
        Hq = np.ones((len(rows), q))
        ri, ci = np.nonzero(sub)
        Hq[ri, rank[ri, ci]] = H[rows[ri], ci]
        out[rows] = _sample_lines(Hq, ua[rows], va[rows], ub[rows], vb[rows], m[rows], C[rows],
                                  eo[rows])
    return out


_NETWORKS = {}


def _network(n):
    """Comparators (i, j), i < j, of Batcher's odd-even merge sort of n
    elements (those of the next power of two that touch only the first n:
    the missing elements act as +infinity)."""
    net = _NETWORKS.get(n)
    if net is None:
        m = 1
        while m < n:
            m *= 2
        net = []
        p = 1
        while p < m:
            k = p
            while k >= 1:
                for j in range(k % p, m - k, 2 * k):
                    for i in range(min(k, m - j - k)):
                        if (i + j) // (2 * p) == (i + j + k) // (2 * p):
                            net.append((i + j, i + j + k))
                k //= 2
            p *= 2
        net = _NETWORKS[n] = [(a, b) for a, b in net if b < n]
    return net


def _sort_last(a):
    """``np.sort(a, axis=-1)`` for a short last axis, by a sorting network
    (elementwise minima and maxima are much faster than one sort call per
    row of a few elements)."""
    n = a.shape[-1]
    if n > 16:
        return np.sort(a, axis=-1)
    cols = [a[..., i] for i in range(n)]
    for i, j in _network(n):
        lo = np.minimum(cols[i], cols[j])
        cols[j] = np.maximum(cols[i], cols[j])
        cols[i] = lo
    return np.stack(cols, axis=-1)


def _sample_lines(H, ua, va, ub, vb, m, C, eo):
    """The midpoint rule of :func:`_exact_small` on the sorted distinct
    critical heights H (F, q) of each cell."""
    ys = 0.5 * (H[:, 1:] + H[:, :-1])               # (F, S) sample heights
    wt = H[:, 1:] - H[:, :-1]
    y3 = ys[:, :, None]
    ea = np.where(ua <= 0, -m, 0.0)[:, None, :]
    eb = np.where(ub <= 0, m, 0.0)[:, None, :]
    A = C[:, None] + (np.where(y3 > va[:, None, :], ea, 0.0)
                      + np.where(y3 > vb[:, None, :], eb, 0.0)).sum(2)
    A = np.rint(A).astype(np.int64)
    fA = _fill_of(A, eo[:, None])
    dv = vb - va
    mi = (np.clip(np.sign(dv) * m, 1 - _MOFF, _MOFF - 1).astype(np.int64) + _MOFF)[:, None, :]
    with np.errstate(all='ignore'):                 # horizontal pieces never span
        inv = 1.0 / dv
        tq = (y3 - va[:, None, :]) * inv[:, None, :]    # position along the piece
        span = (tq > 0) & (tq < 1)
        xc = ua[:, None, :] + tq * (ub - ua)[:, None, :]
        np.clip(xc, 0.0, 1.0, out=xc)
        xc[~span] = 0.0
    key = _sort_last(np.where(span, ((xc * _XSCALE).astype(np.int64) << _MBITS) + mi, _NOKEY))
    s = (key & ((1 << _MBITS) - 1)) - _MOFF
    x = (key >> _MBITS).astype(np.float64) * (1.0 / _XSCALE)
    w = A[:, :, None] + np.cumsum(s, axis=2)
    f = _fill_of(w, eo[:, None, None])
    prev = np.concatenate([fA[:, :, None], f[:, :, :-1]], axis=2)
    g = fA + ((f - prev) * (1.0 - x)).sum(2)
    return (g * wt).sum(1)


def _refine(ua, va, ub, vb, k, C, eo, depth):
    """Coverage of crowded cells by scan converting each on a _REFINE x
    _REFINE grid: its pieces (cell units, cell after cell, ``k`` each)
    scaled up, plus vertical edges left of the grid carrying the left-side
    winding ``A(y)`` (see :func:`_exact`)."""
    n = len(k)
    M = float(_REFINE)
    cid = np.repeat(np.arange(n), k)
    own = np.stack([np.stack([ua, va], 1), np.stack([ub, vb], 1)], 1) * M
    # events: s = +1 at y is an edge down from y to the bottom, -1 one up
    ev = np.flatnonzero(ua <= 0)
    eb = np.flatnonzero(ub <= 0)
    ey = np.concatenate([va[ev], vb[eb]]) * M
    es = np.concatenate([-np.ones(len(ev)), np.ones(len(eb))])
    ecid = np.concatenate([cid[ev], cid[eb]])
    nev = np.bincount(ecid, minlength=n)
    Cw = np.where(eo, np.abs(C) % 2, np.abs(C)).astype(np.int64)
    full = ~eo & (np.abs(C) > k + nev)            # |w| > 0 everywhere: covered
    Cw[full] = 0
    cs = np.repeat(np.where(C > 0, 1.0, -1.0), Cw)
    ccid = np.repeat(np.arange(n), Cw)
    vx = np.full(len(ey) + len(cs), -1.0)
    y0 = np.concatenate([np.where(es > 0, ey, M), np.where(cs > 0, 0.0, M)])
    y1 = np.concatenate([np.where(es > 0, M, ey), np.where(cs > 0, M, 0.0)])
    virt = np.stack([np.stack([vx, y0], 1), np.stack([vx, y1], 1)], 1)
    vcid = np.concatenate([ecid, ccid])
    # two points (zero-length edges) left of the grid's top-left corner and
    # right of its bottom-right one: the mask box is the whole grid (the
    # covered region of open chains reaches the grid's sides)
    pts = np.array([[[-1.0, 0.0], [-1.0, 0.0]], [[M + 1, M], [M + 1, M]]])
    virt = np.concatenate([virt, np.tile(pts, (n, 1, 1))])
    vcid = np.concatenate([vcid, np.repeat(np.arange(n), 2)])
    # per cell: its own pieces (path order), then the virtual edges
    allc = np.concatenate([cid, vcid])
    edges = np.concatenate([own, virt])
    if full.any():
        m = ~full[allc]
        allc, edges = allc[m], edges[m]
    o = _stable_order(allc)
    edges = edges[o]
    counts = np.bincount(allc, minlength=n)
    out = np.zeros(n)
    masks = _batch(edges, counts, _REFINE, _REFINE, eo, np.ones(n, bool), np.ones(n, bool),
                   (0, 0, _REFINE, _REFINE), depth + 1)
    for i, m in enumerate(masks):
        if m is not None:
            out[i] = float(m.data.sum(dtype=np.float64)) / (M * M)
    out[full] = 1.0
    return out


def _left_lookup(touched, run, w, vrow):
    """``left_of(keys)`` for :func:`_flag` and :func:`_exact`: the winding
    integrated over the left side of cells ``keys`` is the running sum
    ``run`` of the last touched cell before it in its row (0 if none); in
    column 0 it is the sum ``vrow`` of the row's pieces left of the box
    (those are accumulated into column 0 itself)."""
    def left_of(keys):
        p = np.searchsorted(touched, keys, side='left') - 1
        pc = np.maximum(p, 0)
        r = keys // w
        same = (p >= 0) & (touched[pc] // w == r) if len(touched) else np.zeros(len(keys), bool)
        out = np.where(same, run[pc] if len(run) else 0.0, 0.0)
        c0 = keys % w == 0
        if vrow is not None and c0.any():
            out[c0] += vrow[r[c0]]
        return out
    return left_of


def _area_coverage(loc, w, h, evenodd, exact=True, depth=0):
    """Coverage (h, w) float32 of local edges ``loc`` (box origin at 0), or
    None without pieces; the box is processed in row bands (see
    :func:`_bands`)."""
    bands = _bands(loc, w, h)
    if len(bands) == 1:
        return _band(loc, w, h, evenodd, exact, depth)
    data = None
    # an edge reaches band rows r0..r1 (whole numbers) where its lowest y
    # is below r1 and its highest above r0: floor(lowest) < r1 and
    # ceil(highest) > r0, the same test on int32 rows (half the memory)
    ys = loc[:, :, 1]
    ylo = np.floor(ys.min(1)).clip(-1, h + 1).astype(np.int32)
    yhi = np.ceil(ys.max(1)).clip(-1, h + 1).astype(np.int32)
    for r0, r1 in bands:
        sel = np.flatnonzero((yhi > r0) & (ylo < r1))
        if len(sel) == 0:
            continue
        sub = loc[sel]
        sub[:, :, 1] -= r0
        d = _band(sub, w, r1 - r0, evenodd, exact, depth)
        del sub
        if d is None:
            continue
        if data is None:
            data = np.zeros((h, w), np.float32)
        data[r0:r1] = d
    return data


def _band(loc, w, h, evenodd, exact, depth):
    """:func:`_area_coverage` of one band: pieces, running sums, then the
    exact recompute of the flagged cells."""
    pc = _pieces(loc, w, h, bool(evenodd) if exact else None)
    if pc is None:
        return None
    xa, ya, xb, yb, col, row, settled = pc
    real = col >= 0
    cell = row * w + np.maximum(col, 0)
    dy = yb - ya
    if settled is not None:
        # rows settled by edge weights: their sums are the coverage
        dy *= settled[0]
    # mean x offset inside the cell; virtual pieces act as if at x = 0
    fx = np.where(real, 0.5 * (xa + xb) - col, 0.0)
    ncell = w * h
    if len(cell) * _SPARSE_RATIO < ncell:
        # few pieces in a large box: accumulate over the touched cells
        # only (the same sums, in the same order, as the dense bincount)
        cells, inv = np.unique(cell, return_inverse=True)
        cv = np.bincount(inv, weights=dy, minlength=len(cells))
        pv = np.bincount(inv, weights=dy * fx, minlength=len(cells))
        nz = (cv != 0) | (pv != 0)
        touched, cv, pv = cells[nz], cv[nz], pv[nz]
        del inv
    else:
        cover = np.bincount(cell, weights=dy, minlength=ncell)
        partial = np.bincount(cell, weights=dy * fx, minlength=ncell)
        touched = np.flatnonzero((cover != 0) | (partial != 0))
        cv, pv = cover[touched], partial[touched]
        del cover, partial
    data, run = _resolve_cells(touched, cv, pv, w, h, evenodd)
    if not exact:
        return data
    virt = ~real
    vrow = np.bincount(row[virt], weights=dy[virt], minlength=h) if virt.any() else None
    left_of = _left_lookup(touched, run, w, vrow)
    fcell = np.where(real if settled is None else real & ~settled[1][row], cell, -1)
    flagged, fp, fc, (dc, dv) = _flag(xa, ya, xb, yb, col, row, fcell, None, left_of, evenodd)
    data.reshape(-1)[dc] = dv
    if len(flagged):
        data.reshape(-1)[flagged] = _exact(xa, ya, xb, yb, col, row, fp, fc, left_of(flagged),
                                           evenodd, depth)
    return data


def _rule(v, evenodd):
    """Fill rule applied to winding integrals (float64 array, in place)."""
    if evenodd:
        # distance to the nearest even integer
        v *= 0.5
        v -= np.rint(v)
        np.abs(v, out=v)
        v *= 2.0
    else:
        np.abs(v, out=v)
        np.minimum(v, 1.0, out=v)
    v[v < _RESIDUE] = 0.0
    return v


def _resolve_cells(touched, cv, pv, w, h, evenodd):
    """Coverage (h, w) float32 from the touched cells only: ``touched``
    (sorted flat indices) and their cover ``cv`` and partial ``pv`` sums.

    Only cells holding pieces have cover or partial terms; along a row the
    winding is constant between them.  So the running sum is taken over
    those cells only, and the output is assembled with one ``np.repeat`` of
    runs in flat order: for every touched cell, the cell itself, then the
    rest of its row up to the next touched cell at the winding after it,
    then (when the row ends first) zeros up to the next touched cell.

    Returns the coverage and ``run`` (float64, per touched cell): the
    winding integrated along the cell's right side.
    """
    n = w * h
    if len(touched) == 0:
        return np.zeros((h, w), np.float32), np.zeros(0)
    tr = touched // w
    cs = np.cumsum(cv)
    first = np.empty(len(touched), bool)
    first[0] = True
    first[1:] = tr[1:] != tr[:-1]
    base = (cs - cv)[first][np.cumsum(first) - 1]
    run = cs - base                           # winding right of the cell
    cell = run - pv                           # winding integral over the cell
    row_end = (tr + 1) * w
    nxt = np.append(touched[1:], n)
    gap = np.minimum(nxt, row_end) - touched - 1
    zeros = np.maximum(nxt - row_end, 0)
    vals = np.zeros(3 * len(touched) + 1)
    lens = np.empty(3 * len(touched) + 1, np.int64)
    lens[0] = touched[0]
    vals[1::3] = cell
    lens[1::3] = 1
    vals[2::3] = run
    lens[2::3] = gap
    lens[3::3] = zeros
    _rule(vals, evenodd)
    return np.repeat(vals.astype(np.float32), lens).reshape(h, w), run


# -- pixel centres ----------------------------------------------------------

def _centre_crossings(xa, ya, xb, yb, h, w):
    """Crossings of the scanlines y = i + 0.5 (0 <= i < h) by the edges
    (xa, ya) -> (xb, yb), half-open (an edge crosses when min(y) < y_c <=
    max(y)): with the columns, a centre on the right or bottom edge of a
    shape is inside and one on its left or top edge is not, the sampling of
    Skia's (and resvg's) aliased scan converter, which rounds edge ends to
    the nearest scanline.  ``h`` and ``w`` (the box height and width) are
    numbers or one per edge.

    Returns None without crossings, else ``(owner, i, j, sign)``: the edge,
    the scanline and the first pixel column whose centre (j + 0.5 > the
    crossing) the crossing changes the winding of (-1 <= j - 1 < w), and
    +1 or -1 (float64) for the edge's direction.
    """
    i_lo = np.clip(np.floor(np.minimum(ya, yb) - 0.5) + 1.0, 0, h)
    i_hi = np.clip(np.floor(np.maximum(ya, yb) - 0.5) + 1.0, 0, h)
    n = (i_hi - i_lo).astype(np.int64)
    total = int(n.sum())
    if total == 0:
        return None
    if total > limits.current().max_flatten_points:
        raise LimitError('too many scanline crossings (%d, max_flatten_points)' % total)
    owner = np.repeat(np.arange(len(xa)), n)
    m = np.arange(total) - np.repeat(np.cumsum(n) - n, n)
    i = i_lo[owner].astype(np.int64) + m
    a_y, a_x = ya[owner], xa[owner]
    dyo = yb[owner] - a_y
    xc = a_x + (i + 0.5 - a_y) * ((xb[owner] - a_x) / dyo)
    last = float(w - 1) if np.ndim(w) == 0 else (w[owner] - 1).astype(np.float64)
    j = np.floor(np.clip(xc - 0.5, -1.0, last)).astype(np.int64) + 1
    return owner, i, j, np.where(dyo > 0, 1.0, -1.0)


def _centre_coverage(loc, w, h, evenodd):
    """1 where the pixel centre is inside, from the crossings of the
    scanlines through the centres (:func:`_centre_crossings`)."""
    cr = _centre_crossings(loc[:, 0, 0], loc[:, 0, 1], loc[:, 1, 0], loc[:, 1, 1], h, w)
    if cr is None:
        return None
    _, i, j, sign = cr
    wsum = np.bincount(i * (w + 1) + j, weights=sign, minlength=h * (w + 1))
    wind = np.cumsum(wsum.reshape(h, w + 1)[:, :w], axis=1)
    wind = np.rint(wind).astype(np.int64)
    if evenodd:
        return (wind & 1).astype(np.float32)
    return (wind != 0).astype(np.float32)


# ---------------------------------------------------------------------------
# Many shapes at once
# ---------------------------------------------------------------------------

def _per_shape(value, n, name, kinds):
    """One value per shape: ``value`` itself when it is a single value of
    ``kinds``, else a sequence of n values."""
    if isinstance(value, kinds):
        return [value] * n
    vals = list(value)
    if len(vals) != n:
        raise PathError('coverage_many needs one %s per shape (%d shapes, %d given)'
                        % (name, n, len(vals)))
    return vals


def _is_evenodd(rule):
    """True for the even-odd rule, False for nonzero (a
    :class:`~raster.geometry.rules.FillRule` or its keyword)."""
    r = FillRule.lookup(rule)
    if r is None:
        raise PathError("fill_rule must be 'nonzero' or 'evenodd', got %r" % (rule,))
    return r is FillRule.EVENODD


def _rules_evenodd(rules):
    eo = {r: _is_evenodd(r) for r in set(rules)}
    return np.array([eo[r] for r in rules], bool)


def coverage_many(edge_arrays, width, height, fill_rules='nonzero', antialias=True, clip=None,
                  exact=True):
    """Coverage of many shapes at once, each as :func:`coverage` would give it.

    Drawing thousands of small shapes one :func:`coverage` call at a time
    costs mostly the fixed overhead of a call.  Here the split, accumulate,
    resolve and exact-recompute stages run once for a whole batch of
    shapes: their boxes are stacked vertically into one tall virtual canvas
    (shape ``s`` owns rows ``roff[s] .. roff[s] + h_s``), so a cell key
    ``row * W + col`` also names the shape, and every per-cell sum is taken
    over the same pieces in the same order as for the shape alone.

    Parameters
    ----------
    edge_arrays : sequence of (E_i, 2, 2) array_like of float
        The edges of each shape, device pixels, as for :func:`coverage`.
    width, height : int
        Canvas size in pixels.
    fill_rules : FillRule, {'nonzero', 'evenodd'} or a sequence of them
        One rule for all shapes, or one per shape.
    antialias : bool or sequence of bool
        One flag for all shapes, or one per shape.
    clip : (x0, y0, x1, y1) or None
        Applied to every shape, as for :func:`coverage`.
    exact : bool or sequence of bool
        One flag for all shapes, or one per shape, as for :func:`coverage`.

    Returns
    -------
    list of (Mask or None)
        ``result[i]`` equals ``coverage(edge_arrays[i], width, height,
        fill_rules[i], antialias[i], clip, exact[i])``.

    Raises
    ------
    PathError, LimitError, CanvasError
        As :func:`coverage` (for the first bad shape), or mismatched
        lengths of ``fill_rules`` / ``antialias`` / ``exact``.

    See Also
    --------
    coverage_batch : the same with all edges in one array.

    >>> tri = np.array([[[0, 0], [4, 0]], [[4, 0], [0, 4]], [[0, 4], [0, 0]]], float)
    >>> a, b, c = coverage_many([tri, tri + 2, tri + 100], 8, 8)
    >>> float(a.data.sum()), b.box, c is None
    (8.0, (2, 2, 6, 6), True)
    """
    width, height = check_canvas_size(width, height)
    arrays = [_check_edges(e) for e in edge_arrays]
    counts = np.array([len(e) for e in arrays], np.int64)
    edges = np.concatenate(arrays) if len(arrays) and counts.sum() else np.zeros((0, 2, 2))
    return coverage_batch(edges, counts, width, height, fill_rules, antialias, clip, exact)


def coverage_batch(edges, counts, width, height, fill_rules='nonzero', antialias=True,
                   clip=None, exact=True, overwrite=False):
    """:func:`coverage_many` with the shapes' edges in one array.

    Parameters
    ----------
    edges : (E, 2, 2) array_like of float
        The edges of all shapes, shape after shape (device pixels).
    counts : (n,) array_like of int
        Number of edges of each shape (``sum(counts) == E``; 0 allowed).
    width, height, fill_rules, antialias, clip, exact
        As for :func:`coverage_many`.
    overwrite : bool
        The caller gives ``edges`` up: a float64 array is moved into the
        shapes' boxes in place (its values are then undefined) instead of
        being copied, which saves one copy of the edges at the peak.

    Returns
    -------
    list of (Mask or None)
        One entry per shape, as :func:`coverage_many`.

    Raises
    ------
    PathError, LimitError, CanvasError
        As :func:`coverage_many`; also counts that do not add up to E.

    >>> sq = np.array([[[0, 0], [2, 0]], [[2, 0], [2, 2]], [[2, 2], [0, 2]], [[0, 2], [0, 0]]], float)
    >>> a, b, c = coverage_batch(np.concatenate([sq, sq + 3]), [4, 0, 4], 8, 8)
    >>> a.box, b, c.box
    ((0, 0, 2, 2), None, (3, 3, 5, 5))
    """
    width, height = check_canvas_size(width, height)
    e = _check_edges(edges)
    try:
        counts = np.asarray(counts, np.int64).reshape(-1)
    except (TypeError, ValueError):
        raise PathError('counts must be integers') from None
    n = len(counts)
    if (counts < 0).any() or int(counts.sum()) != len(e):
        raise PathError('counts must be >= 0 and add up to the number of edges (%d)' % len(e))
    eo = _rules_evenodd(_per_shape(fill_rules, n, 'fill rule', str))
    aa = np.array(_per_shape(antialias, n, 'antialias flag', (bool, np.bool_, int)), bool)
    ex = np.array(_per_shape(exact, n, 'exact flag', (bool, np.bool_, int)), bool)
    return _batch(e, counts, width, height, eo, aa, ex, _window(width, height, clip), 0,
                  overwrite and e is edges)


def _batch(e, counts, width, height, eo, aa, ex, win, depth, overwrite=False):
    """:func:`coverage_batch` on checked arguments: edges ``e`` (E, 2, 2),
    ``counts`` (n,), evenodd / antialias / exact flags (n,) bool, the work
    window ``win`` and the refinement level ``depth`` (see :func:`_exact`);
    ``overwrite``: ``e`` may be moved in place (each shape's edges are read
    once)."""
    n = len(counts)
    out = [None] * n
    if n == 0 or len(e) == 0:
        return out
    first = np.cumsum(counts) - counts
    if (~aa & (counts > 0)).any():
        _aliased_batch(e, counts, first, ~aa & (counts > 0), eo, win, out)
    idx = np.flatnonzero(aa & (counts > 0))
    if len(idx) == 0:
        return out
    X0, Y0, X1, Y1 = _shape_boxes(e, counts, first, idx, win, True)
    full = np.flatnonzero(counts > 0)
    f = first[full]
    pick = np.searchsorted(full, idx)
    xa, ya, xb, yb = e[:, 0, 0], e[:, 0, 1], e[:, 1, 0], e[:, 1, 1]
    est = 3 * counts[idx] + np.add.reduceat(np.abs(xb - xa) + np.abs(yb - ya), f)[pick]
    live = (X1 > X0) & (Y1 > Y0)
    alone = live & (est > _CHUNK_PIECES)
    for j in np.flatnonzero(alone).tolist():
        i = int(idx[j])
        x0, y0, w, h = int(X0[j]), int(Y0[j]), int(X1[j] - X0[j]), int(Y1[j] - Y0[j])
        loc = e[first[i]:first[i] + counts[i]]
        if overwrite:
            loc -= np.array([x0, y0], np.float64)
        else:
            loc = loc - np.array([x0, y0], np.float64)
        data = _area_coverage(loc, w, h, bool(eo[i]), bool(ex[i]), depth)
        del loc
        if data is not None and data.any():
            out[i] = Mask(data, x0, y0)
    sel = np.flatnonzero(live & ~alone)
    if len(sel) == 0:
        return out
    idx, X0, Y0, sw, sh, est = idx[sel], X0[sel], Y0[sel], (X1 - X0)[sel], (Y1 - Y0)[sel], est[sel]
    ne = counts[idx]
    if int(ne.sum()) == len(e):          # every edge is in a live shape
        loc = e if overwrite else e.copy()
    else:
        take = np.zeros(n, bool)
        take[idx] = True
        loc = e[np.repeat(take, counts)]
    loc[:, :, 0] -= np.repeat(X0.astype(np.float64), ne)[:, None]
    loc[:, :, 1] -= np.repeat(Y0.astype(np.float64), ne)[:, None]
    # sub-batches bounded in pieces and in cells
    cest = np.cumsum(est)
    carea = np.cumsum(sw * sh)
    eoff = np.concatenate([[0], np.cumsum(ne)])
    m = len(idx)
    lo = 0
    while lo < m:
        b_est = cest[lo - 1] if lo else 0
        b_area = carea[lo - 1] if lo else 0
        hi = min(int(np.searchsorted(cest, b_est + _BATCH_PIECES, side='right')),
                 int(np.searchsorted(carea, b_area + _BATCH_CELLS, side='right')))
        hi = min(max(hi, lo + 1), m)
        s = slice(lo, hi)
        _many_batch(loc[eoff[lo]:eoff[hi]], ne[s], X0[s], Y0[s], sw[s], sh[s], eo[idx[s]],
                    ex[idx[s]], idx[s], out, depth)
        lo = hi
    return out


def _shape_boxes(e, counts, first, idx, win, antialias):
    """Integer pixel boxes (X0, Y0, X1, Y1), int64 arrays, of the shapes
    ``idx`` (with edges; boxes as :func:`_box` makes them, inside the
    :func:`_window` ``win``)."""
    full = np.flatnonzero(counts > 0)
    f = first[full]
    pick = np.searchsorted(full, idx)
    xa, ya, xb, yb = e[:, 0, 0], e[:, 0, 1], e[:, 1, 0], e[:, 1, 1]
    # (two-way np.minimum: a reduction along a length-2 axis is slow)
    lo_x = np.minimum.reduceat(np.minimum(xa, xb), f)[pick]
    hi_x = np.maximum.reduceat(np.maximum(xa, xb), f)[pick]
    lo_y = np.minimum.reduceat(np.minimum(ya, yb), f)[pick]
    hi_y = np.maximum.reduceat(np.maximum(ya, yb), f)[pick]
    if antialias:
        x0, x1, y0, y1 = np.floor(lo_x), np.ceil(hi_x), np.floor(lo_y), np.ceil(hi_y)
    else:       # pixels whose centre may be inside: min < centre <= max
        x0, x1 = np.floor(lo_x + 0.5), np.floor(hi_x + 0.5)
        y0, y1 = np.floor(lo_y + 0.5), np.floor(hi_y + 0.5)
    cx0, cy0, cx1, cy1 = win
    return (np.maximum(x0, cx0).astype(np.int64), np.maximum(y0, cy0).astype(np.int64),
            np.minimum(x1, cx1).astype(np.int64), np.minimum(y1, cy1).astype(np.int64))


def _aliased_batch(e, counts, first, sel, eo, win, out):
    """Aliased masks (as :func:`_centre_coverage`) of the shapes ``sel``
    (bool per shape) into ``out``: the crossings of all shapes' scanlines
    are summed into one flat array of the shapes' boxes (one extra column
    each), and the windings are running sums along its rows."""
    idx = np.flatnonzero(sel)
    X0, Y0, X1, Y1 = _shape_boxes(e, counts, first, idx, win, False)
    live = (X1 > X0) & (Y1 > Y0)
    idx, X0, Y0, sw, sh = idx[live], X0[live], Y0[live], (X1 - X0)[live], (Y1 - Y0)[live]
    if len(idx) == 0:
        return
    size = sh * (sw + 1)
    csize = np.cumsum(size)
    lo = 0
    while lo < len(idx):
        base = csize[lo - 1] if lo else 0
        hi = int(np.searchsorted(csize, base + _ALIASED_CELLS, side='right'))
        hi = min(max(hi, lo + 1), len(idx))
        _aliased_run(e, counts, first, idx[lo:hi], X0[lo:hi], Y0[lo:hi], sw[lo:hi], sh[lo:hi],
                     eo, out)
        lo = hi


def _aliased_run(e, counts, first, idx, X0, Y0, sw, sh, eo, out):
    """Aliased masks of the shapes ``idx`` (boxes X0, Y0, sw, sh; evenodd
    flags ``eo`` per shape of the batch) into ``out``; see
    :func:`_aliased_batch`."""
    ne = counts[idx]
    mark = np.zeros(len(counts), bool)
    mark[idx] = True                     # idx increasing: edges stay in shape order
    take = np.repeat(mark, counts)
    sid = np.repeat(np.arange(len(idx)), ne)
    loc = e[take]
    xa = loc[:, 0, 0] - X0[sid]
    ya = loc[:, 0, 1] - Y0[sid]
    xb = loc[:, 1, 0] - X0[sid]
    yb = loc[:, 1, 1] - Y0[sid]
    cr = _centre_crossings(xa, ya, xb, yb, sh[sid].astype(np.float64), sw[sid])
    if cr is None:
        return
    owner, i, j, sign = cr
    so = sid[owner]
    size = sh * (sw + 1)
    off = np.cumsum(size) - size
    cell = off[so] + i * (sw[so] + 1) + j
    acc = np.bincount(cell, weights=sign, minlength=int(size.sum()))
    # running sums along each row: a global running sum minus its value
    # before the row's first cell
    cs = np.cumsum(acc)
    row_len = np.repeat(sw + 1, sh)
    row_start = np.cumsum(row_len) - row_len
    before = np.where(row_start > 0, cs[np.maximum(row_start - 1, 0)], 0.0)
    wind = np.rint(cs - np.repeat(before, row_len)).astype(np.int64)
    shape_eo = np.repeat(eo[idx], size)
    val = np.where(shape_eo, (wind & 1) != 0, wind != 0).astype(np.float32)
    offl, swl, shl = off.tolist(), sw.tolist(), sh.tolist()
    for s_, i_ in enumerate(idx.tolist()):
        w, h = swl[s_], shl[s_]
        data = val[offl[s_]:offl[s_] + h * (w + 1)].reshape(h, w + 1)[:, :w]
        if data.any():
            out[i_] = Mask(np.ascontiguousarray(data), int(X0[s_]), int(Y0[s_]))


def _many_batch(loc, ne, X0, Y0, sw, sh, seo, sex, ids, out, depth=0):
    """Masks of a batch of k shapes into ``out[ids[s]]``; see
    :func:`coverage_many`.  ``loc`` (E, 2, 2): the shapes' edges, shape
    after shape (``ne`` edges each), relative to each shape's box origin
    (X0, Y0); (sw, sh) box sizes; seo: evenodd; sex: exact."""
    k = len(ne)
    roff = np.cumsum(sh) - sh
    W = int(sw.max())
    sid = np.repeat(np.arange(k, dtype=np.int32), ne)      # (int32: cheaper to repeat)
    # -- pieces (as _pieces, with each shape's own box) -----------------------
    xa, ya = loc[:, 0, 0], loc[:, 0, 1]
    xb, yb = loc[:, 1, 0], loc[:, 1, 1]
    ya, xa, yb, xb, sid = _split(ya, xa, yb, xb, sh[sid].astype(np.float64), tag=sid)
    ym = 0.5 * (ya + yb)
    keep = (ym >= 0) & (ym < sh[sid])
    if not keep.all():
        xa, ya, xb, yb, sid = xa[keep], ya[keep], xb[keep], yb[keep], sid[keep]
    if len(xa) == 0:
        return
    del ym, keep        # (the batch's per-piece arrays are freed once used)
    xa, ya, xb, yb, sid = _split(xa, ya, xb, yb, sw[sid].astype(np.float64), tag=sid)
    xm = 0.5 * (xa + xb)
    swp = sw[sid]                               # each piece's box width
    keep = xm < swp
    if not keep.all():
        xa, ya, xb, yb, xm, sid, swp = (xa[keep], ya[keep], xb[keep], yb[keep], xm[keep],
                                        sid[keep], swp[keep])
    if len(xa) == 0:
        return
    col = np.floor(xm).astype(np.int64)
    del xm, keep
    col = np.minimum(np.maximum(col, -1), swp - 1)
    left = col < 0
    if left.any():
        xa = np.where(left, -0.5, xa)
        xb = np.where(left, -0.5, xb)
    row = np.floor(0.5 * (ya + yb)).astype(np.int64)
    row = np.minimum(np.maximum(row, 0), sh[sid] - 1)
    del left
    # -- accumulate over the touched cells of the stacked boxes ---------------
    real = col >= 0
    grow = row + roff[sid]
    cell = grow * W + np.maximum(col, 0)
    dy = yb - ya
    fx = np.where(real, 0.5 * (xa + xb) - col, 0.0)
    cells, inv = _distinct_cells(cell, sid, row, np.maximum(col, 0), swp, sw, sh)
    del swp
    cv = np.bincount(inv, weights=dy, minlength=len(cells))
    pv = np.bincount(inv, weights=dy * fx, minlength=len(cells))
    nz = (cv != 0) | (pv != 0)
    T, cv, pv = cells[nz], cv[nz], pv[nz]
    del fx, inv, cells, nz
    # -- resolve (as _resolve_cells, running sums restarted per shape) --------
    if len(T) == 0 and not sex.any():
        return
    tg = T // W
    tcol = T % W
    tsid = np.searchsorted(roff, tg, side='right') - 1
    # shapes without rows (h = 0) never hold cells, so searchsorted is exact
    lrow = tg - roff[tsid]
    cs = _segmented_cumsum(cv, tsid, k)
    first = np.empty(len(T), bool)
    first[:1] = True
    first[1:] = tg[1:] != tg[:-1]
    base = (cs - cv)[first][np.cumsum(first) - 1]
    run = cs - base
    # cells to recompute exactly, among the pieces of exact shapes only
    flagged = dc = np.zeros(0, np.int64)
    dv = np.zeros(0)
    if sex.any():
        virt = ~real
        vrow = (np.bincount(grow[virt], weights=dy[virt], minlength=int(sh.sum()))
                if virt.any() else None)
        left_of = _left_lookup(T, run, W, vrow)
        if sex.all():
            brk = np.zeros(len(sid), bool)
            brk[1:] = sid[1:] != sid[:-1]
            flagged, fp, fc, (dc, dv) = _flag(xa, ya, xb, yb, col, row, np.where(real, cell, -1),
                                              brk, left_of, seo[sid])
        else:
            # only the pieces of exact shapes are looked at (hairlines are
            # not: their runs need no test)
            ep = np.flatnonzero(sex[sid])
            es = sid[ep]
            brk = np.zeros(len(ep), bool)
            brk[1:] = es[1:] != es[:-1]
            flagged, fp, fc, (dc, dv) = _flag(xa[ep], ya[ep], xb[ep], yb[ep], col[ep], row[ep],
                                              np.where(real[ep], cell[ep], -1), brk, left_of,
                                              seo[es])
            fp = ep[fp]
    del real, cell, dy, grow
    if len(T) == 0 and len(flagged) == 0 and len(dc) == 0:
        return
    cellv = run - pv
    tw = sw[tsid]
    li = lrow * tw + tcol                       # index in the shape's own box
    nsz = tw * sh[tsid]
    last = np.empty(len(T), bool)
    last[-1:] = True
    last[:-1] = tsid[1:] != tsid[:-1]
    shape_first = np.empty(len(T), bool)
    shape_first[:1] = True
    shape_first[1:] = last[:-1]
    nxt = np.where(last, nsz, np.append(li[1:], 0))
    row_end = (lrow + 1) * tw
    m = len(T)
    vals = np.zeros(4 * m)
    lens = np.zeros(4 * m, np.int64)
    lens[0::4] = np.where(shape_first, li, 0)
    vals[1::4] = cellv
    lens[1::4] = 1
    vals[2::4] = run
    lens[2::4] = np.minimum(nxt, row_end) - li - 1
    lens[3::4] = np.maximum(nxt - row_end, 0)
    eo = np.repeat(seo[tsid], 4)
    if eo.any():
        v_eo = _rule(vals.copy(), True)
        vals = np.where(eo, v_eo, _rule(vals, False))
    else:
        vals = _rule(vals, False)
    has = np.zeros(k, bool)
    has[tsid] = True
    # (cells recomputed exactly, then cells whose coverage _flag gave)
    xsid = np.searchsorted(roff, np.concatenate([flagged, dc]) // W, side='right') - 1
    fsid = xsid[:len(flagged)]
    tail = 0
    if len(xsid) and not has[xsid].all():
        # shapes with flagged cells but no cover terms get zero images (as
        # _resolve_cells gives them): their sizes are added to the leading
        # zeros of the next shape with cover terms (or appended)
        only = np.zeros(k, bool)
        only[xsid] = True
        only &= ~has
        osz = np.where(only, sw * sh, 0)
        cum = np.cumsum(osz)
        hs = np.flatnonzero(has)
        before = cum[hs] - osz[hs]                  # flagged-only sizes before shape
        gap = np.diff(np.concatenate([[0], before]))
        lens[0::4] += np.where(shape_first, gap[np.searchsorted(hs, tsid)], 0)
        tail = int(cum[-1] - (before[-1] if len(hs) else 0))
        has |= only
    vals = vals.astype(np.float32)
    # nonzero pixels per shape (only the cell and run entries hold values)
    nnz = np.bincount(tsid, weights=np.where(vals[1::4] != 0, lens[1::4], 0)
                      + np.where(vals[2::4] != 0, lens[2::4], 0),
                      minlength=k).astype(np.float64, copy=False)   # (int64 when empty)
    flat = np.repeat(vals, lens)
    if tail:
        flat = np.concatenate([flat, np.zeros(tail, np.float32)])
    size = np.where(has, sw * sh, 0)
    ooff = np.cumsum(size) - size
    # -- exact recompute of the flagged cells ---------------------------------
    if len(flagged) or len(dc):
        v = _exact(xa, ya, xb, yb, col, row, fp, fc, left_of(flagged), seo[fsid], depth)
        fl = np.concatenate([flagged, dc])
        fs = np.concatenate([fsid, xsid[len(flagged):]])
        v = np.concatenate([v, dv]).astype(np.float32)
        fr = fl // W - roff[fs]
        pos = ooff[fs] + fr * sw[fs] + fl % W
        nnz += np.bincount(fs, weights=(v != 0).astype(np.float64) - (flat[pos] != 0),
                           minlength=k)
        flat[pos] = v
    X0l, Y0l, swl, shl, offl, idl = (X0.tolist(), Y0.tolist(), sw.tolist(), sh.tolist(),
                                      ooff.tolist(), ids.tolist())
    for s in np.flatnonzero(has & (nnz > 0.5)).tolist():
        w, h = swl[s], shl[s]
        out[idl[s]] = Mask(flat[offl[s]:offl[s] + w * h].reshape(h, w), X0l[s], Y0l[s])


def _distinct_cells(cell, sid, row, col, swp, sw, sh):
    """``np.unique(cell, return_inverse=True)`` for the pieces of a batch:
    ``cell`` (int64) their keys in the stacked boxes, ``sid`` their shape,
    ``row`` / ``col`` (>= 0) their cell in the shape's own box, ``swp``
    that box's width; ``sw``, ``sh`` the (k,) box sizes.

    When the boxes' total area is small for the number of pieces the cells
    are marked in a dense map of the boxes laid end to end (same order as
    the stacked keys), which avoids sorting the pieces.

    Returns
    -------
    cells : (U,) int64 ndarray
        The sorted distinct keys.
    inv : (P,) int64 ndarray
        Each piece's index into ``cells``.
    """
    area = sw * sh
    total = int(area.sum())
    if total > _SPARSE_RATIO * len(cell):
        return np.unique(cell, return_inverse=True)
    off = np.cumsum(area) - area
    key = off[sid] + row * swp + col
    mark = np.zeros(total, bool)
    mark[key] = True
    rank = np.cumsum(mark, dtype=np.int64 if total >= 1 << 31 else np.int32)
    inv = rank[key].astype(np.int64)
    inv -= 1
    cells = np.empty(int(rank[-1]), np.int64)
    cells[inv] = cell
    return cells, inv


def _segmented_cumsum(v, seg, k):
    """Running sums of ``v`` restarted at every new value of ``seg`` (sorted
    ints in 0..k-1), bitwise equal to ``np.cumsum`` of each segment alone:
    the segments are laid out as rows of zero-padded 2-D arrays (one per
    length class, four classes per power of two, each as wide as its
    longest segment) and summed along the rows."""
    cnt = np.bincount(seg, minlength=k)
    start = np.cumsum(cnt) - cnt
    cls = np.ceil(np.log2(np.maximum(cnt, 1)) * 4).astype(np.int16)
    ce = cls[seg]
    order = np.argsort(ce, kind='stable')          # elements by class, in order
    ccount = np.bincount(ce)
    cstart = np.cumsum(ccount) - ccount
    # the segments with elements by class (increasing within a class) and
    # each one's row in its class's array
    live = np.flatnonzero(cnt)
    lcls = cls[live]
    so = live[np.argsort(lcls, kind='stable')]
    scount = np.bincount(lcls, minlength=len(ccount))
    sstart = np.cumsum(scount) - scount
    row_of = np.zeros(k, np.int64)
    row_of[so] = np.arange(len(so)) - np.repeat(sstart, scount)
    out = np.empty(len(v))
    for c in np.flatnonzero(ccount).tolist():
        el = order[cstart[c]:cstart[c] + ccount[c]]
        if c == 0:                      # segments of one element
            out[el] = v[el]
            continue
        sg = seg[el]
        members = so[sstart[c]:sstart[c] + scount[c]]
        slot = row_of[sg]
        pos = el - start[sg]
        M = np.zeros((len(members), int(cnt[members].max())))
        M[slot, pos] = v[el]
        np.cumsum(M, axis=1, out=M)
        out[el] = M[slot, pos]
    return out
