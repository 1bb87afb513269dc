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
   between adjacent integers.  The few cells where that might fail (where
   separate chains of edges meet) are recomputed exactly, each on its own
   set of horizontal sample lines (see :func:`coverage`).
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
from ..geometry.rules import FillRule

__all__ = ['Mask', 'coverage', 'coverage_many', 'coverage_batch', 'path_coverage', 'check_canvas_size', 'SUBSCANLINES']

#: Evenly spaced sample lines per pixel used in pixels crowded with more
#: than ``_PAIR_LIMIT`` pieces (the only non-exact case).
SUBSCANLINES = 32

# Coverage below this is float64 rounding residue and is set to 0.
_RESIDUE = 1e-9
# Most pieces generated at once; longer inputs are processed in chunks.
_CHUNK_PIECES = 1 << 21
# Largest box (cells) for which flagged cells are found through a dense
# int32 map rather than a binary search.
_CELLMAP_MAX = 1 << 25
# Boxes with more than this many cells per piece accumulate cover and
# partial sums over the touched cells only (sorting the pieces' cells
# costs less than sweeping the whole box).
_SPARSE_RATIO = 8
# The dense cell map of _exact_cells is used when the box has at most this
# many cells per piece (else a binary search over the flagged cells).
_CELLMAP_RATIO = 16
# Longest stretch of a chain checked for monotonicity when it visits one
# cell several times.
_STRETCH_MAX = 256
# Most work items (pairs, pieces, heights) per batch of recomputed cells.
_CHUNK_WORK = 1 << 21
# Cells with more pieces than this are sampled on a fixed grid of
# SUBSCANLINES heights instead of at all end points and intersections.
_PAIR_LIMIT = 32
# Most cells (sum of the shapes' box areas) per batch of coverage_batch.
_BATCH_CELLS = 1 << 24


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
    as one chain).  So every pixel holding two or more chains, or one chain
    of three or more pieces monotone in neither axis, is recomputed by an
    exact method (see :func:`_exact_cells`): the covered width of a
    horizontal line through the pixel is linear in its height between the
    piece end points and pairwise intersections, so the midpoint rule over
    those heights is exact.  Only pixels holding more than ``_PAIR_LIMIT``
    (32) pieces skip the pairwise intersections, and if they have many
    distinct end point heights are sampled at :data:`SUBSCANLINES` evenly
    spaced heights instead (close, not exact; it bounds the work per
    pixel).

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
                  tolerance=0.25, transform=None):
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

    Returns
    -------
    Mask or None

    >>> from raster.geometry.path import Path
    >>> m = path_coverage(Path.polygon([(1, 1), (3, 1), (3, 2)]), 4, 4)
    >>> m.box, float(m.data.sum())
    ((1, 1, 3, 2), 1.0)
    """
    edges = flatten(path, tolerance=tolerance, transform=transform).edges(close_all=True)
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
    # kmin + m going up, kmax - m going down
    owner = np.repeat(np.arange(n_in), n)
    j = np.arange(m_total)
    m = j - cb[owner]
    a_u = ua[owner]
    b_u = ub[owner]
    k = np.where(b_u > a_u, kmin[owner] + m, kmax[owner] - m)
    a_v = va[owner]
    t = (k - a_u) / (b_u - a_u)
    v = a_v + t * (vb[owner] - a_v)
    pos = j + owner                              # the piece the crossing ends
    UB[pos] = k
    VB[pos] = v
    pos += 1
    UA[pos] = k
    VA[pos] = v
    if tag is not None:
        return UA, VA, UB, VB, np.repeat(tag, n + 1)
    return UA, VA, UB, VB


def _pieces(loc, w, h):
    """Cell pieces of local edges ``loc`` ((E, 2, 2), box origin at 0).

    Returns xa, ya, xb, yb (float64) and col, row (int64) for every piece
    inside the box rows.  The part of an edge left of the box goes to a
    virtual column -1 (x set to -0.5): it changes the winding of every cell
    to its right like a vertical edge.  The part right of the box is
    dropped.  Consecutive pieces share their split points bitwise.
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
    # split in x (u = x, v = y)
    xa, ya, xb, yb = _split(xa, ya, xb, yb, w)
    xm = 0.5 * (xa + xb)
    keep = xm < w
    if not keep.all():
        xa, ya, xb, yb, xm = xa[keep], ya[keep], xb[keep], yb[keep], xm[keep]
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
    return xa, ya, xb, yb, col, row


def _chunks(loc, w, h):
    """Edge index ranges whose pieces number about _CHUNK_PIECES at most."""
    n_e = len(loc)
    d = np.abs(loc[:, 1] - loc[:, 0])
    if 3 * n_e + d.sum() <= _CHUNK_PIECES:     # cheap upper bound
        return [(0, n_e)]
    xs, ys = loc[:, :, 0], loc[:, :, 1]
    ny = np.clip(np.ceil(ys.max(1)), 0, h) - np.clip(np.floor(ys.min(1)), 0, h)
    nx = np.clip(np.ceil(xs.max(1)), 0, w) - np.clip(np.floor(xs.min(1)), 0, w)
    est = np.cumsum(1.0 + ny + nx)
    if est[-1] <= _CHUNK_PIECES:
        return [(0, n_e)]
    bounds = [0]
    while bounds[-1] < n_e:
        lo = bounds[-1]
        base = est[lo - 1] if lo else 0.0
        hi = int(np.searchsorted(est, base + _CHUNK_PIECES, side='right'))
        bounds.append(min(max(hi, lo + 1), n_e))
    return list(zip(bounds[:-1], bounds[1:]))


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


def _flag_cells(xa, ya, xb, yb, cell, brk=None):
    """Cells whose winding may take more than two adjacent values.

    Parameters are the pieces of one chunk in path order; ``cell`` is < 0
    for pieces outside the box.  Returns (cells touched, cells flagged),
    both sorted int64 arrays of flat cell indices.  ``brk`` (bool, optional)
    marks pieces that never continue the previous one (a new shape).

    A piece *continues* the previous piece of the array when it starts
    exactly where that one ends (split points and shared polygon vertices
    are bitwise equal); a *run* is a maximal sequence of continuing pieces
    in one cell (a closed chain whose first and last pieces meet in one
    cell has those two runs merged).  A cell is left alone (it is exact)
    when all its pieces lie on one curve that is strictly monotone along
    some direction ``d``: for any two points p, q of the cell, the
    crossings of the segment pq with such a curve are consecutive along it
    (their order along d is their order along pq), so their signs
    alternate and the winding changes by at most one.  Tested here:

    * one run of at most two pieces, or monotone in x or in y;
    * otherwise, the directions of all pieces from the cell's first piece
      to its last one in path order (at most _STRETCH_MAX pieces, no break
      of the chain, possibly leaving and re-entering the cell) lie in an
      open half-plane (zero-length pieces are ignored).
    """
    n = len(cell)
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
    merged = np.zeros(len(ridx), bool)
    # for a merged run: start and length of its head part (the pieces at
    # the start of the chain); its own start ridx is the tail part's
    hstart = np.zeros(len(ridx), np.int64)
    hlen = np.zeros(len(ridx), np.int64)
    # closed chains: merge the run at the chain's start into the run at its end
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
    if not inside.any():
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    ridx, rlen, rbits, merged, rcell, hstart, hlen = (
        ridx[inside], rlen[inside], rbits[inside], merged[inside], rcell[inside],
        hstart[inside], hlen[inside])
    # group the runs by cell (runs of a cell stay in path order)
    order = np.argsort(rcell, kind='stable')
    ridx, rlen, rbits, merged, rcell, hstart, hlen = (
        ridx[order], rlen[order], rbits[order], merged[order], rcell[order],
        hstart[order], hlen[order])
    gstart = _group_starts(rcell)
    gcnt = _run_lengths(gstart, len(rcell))
    cells = rcell[gstart]
    single = gcnt == 1
    axis_ok = (rlen[gstart] <= 2) | ((rbits[gstart] & 3) != 3) | ((rbits[gstart] & 12) != 12)
    ok = single & axis_ok
    # the rest (no merged run involved): monotone along the chord?
    has_merged = np.logical_or.reduceat(merged, gstart)
    glast = gstart + gcnt - 1
    s_first = ridx[gstart]
    s_last = np.minimum(ridx[glast] + rlen[glast] - 1, n - 1)   # (merged runs wrap)
    breaks = np.cumsum(~conn)
    cand = (~ok & ~has_merged & (s_last - s_first < _STRETCH_MAX)
            & (breaks[s_last] == breaks[s_first]))
    # a cell holding one merged run (a closed chain's end and start) holds
    # one unbroken chain too: its tail part, then its head part
    cand_m = ~ok & single & merged[gstart] & (rlen[gstart] <= _STRETCH_MAX)
    ci = np.flatnonzero(cand)
    cm = np.flatnonzero(cand_m)
    if len(ci) or len(cm):
        # the piece directions fit in an open half-plane iff, sorted by
        # angle, some circular gap between consecutive ones exceeds pi.
        # Stretches of pieces: (first piece, count, candidate)
        gm = gstart[cm]
        sf = np.concatenate([s_first[ci], ridx[gm], hstart[gm]])
        L = np.concatenate([s_last[ci] - s_first[ci] + 1, rlen[gm] - hlen[gm], hlen[gm]])
        cand_of = np.concatenate([np.arange(len(ci)), len(ci) + np.arange(len(cm)),
                                  len(ci) + np.arange(len(cm))])
        ci = np.concatenate([ci, cm])
        owner = np.repeat(cand_of, L)
        idx = np.repeat(sf, L) + (np.arange(len(owner)) - np.repeat(np.cumsum(L) - L, L))
        srt = np.argsort(owner, kind='stable')
        owner, idx = owner[srt], idx[srt]
        pdx, pdy = dx[idx], dy[idx]
        moving = (pdx != 0) | (pdy != 0)
        owner = owner[moving]
        ang = np.arctan2(pdy[moving], pdx[moving]) + np.pi          # [0, 2 pi]
        ang = np.sort(owner * 8.0 + ang) - owner * 8.0               # sorted per stretch
        m = len(ang)
        if m:
            gfirst = _group_starts(owner)
            glast = gfirst + _run_lengths(gfirst, m) - 1
            gap = np.empty(m)
            gap[1:] = ang[1:] - ang[:-1]
            gap[gfirst] = ang[gfirst] + 2 * np.pi - ang[glast]
            fits = np.maximum.reduceat(gap, gfirst) > np.pi * (1 + 1e-9)
            good = np.ones(len(ci), bool)          # stretches of points only
            good[owner[gfirst]] = fits
        else:
            good = np.ones(len(ci), bool)
        ok[ci] = good
    return cells, cells[~ok]


def _area_coverage(loc, w, h, evenodd, exact=True):
    ncell = w * h
    cover = None
    partial = None
    touched_cells, bad_cells = [], []
    chunks = _chunks(loc, w, h)
    saved = None
    sparse = None
    for lo, hi in chunks:
        pc = _pieces(loc[lo:hi], w, h)
        if pc is None:
            continue
        xa, ya, xb, yb, col, row = pc
        real = col >= 0
        cacc = np.maximum(col, 0)
        cell = row * w + cacc
        dy = yb - ya
        # mean x offset inside the cell; virtual pieces act as if at x = 0
        fx = np.where(real, 0.5 * (xa + xb) - col, 0.0)
        if len(chunks) == 1 and len(cell) * _SPARSE_RATIO < ncell:
            # few pieces in a large box: accumulate over the touched cells
            # only (the same sums, in the same order, as the dense bincount)
            cells, inv = np.unique(cell, return_inverse=True)
            sparse = (cells, np.bincount(inv, weights=dy, minlength=len(cells)),
                      np.bincount(inv, weights=dy * fx, minlength=len(cells)))
        else:
            c1 = np.bincount(cell, weights=dy, minlength=ncell)
            p1 = np.bincount(cell, weights=dy * fx, minlength=ncell)
            if cover is None:
                cover, partial = c1, p1
            else:
                cover += c1
                partial += p1
        if not exact:
            continue
        # virtual pieces get cell ids < 0 (never flagged)
        touched, bad = _flag_cells(xa, ya, xb, yb, np.where(real, cell, -1))
        touched_cells.append(touched)
        bad_cells.append(bad)
        if len(chunks) == 1:
            saved = (xa, ya, xb, yb, col, row)
    if sparse is not None:
        cells, cv, pv = sparse
        nz = (cv != 0) | (pv != 0)
        data = _resolve_cells(cells[nz], cv[nz], pv[nz], w, h, evenodd)
    elif cover is not None:
        data = _resolve(cover, partial, w, h, evenodd)
        del cover, partial
    else:
        return None

    # flagged cells, and cells touched by pieces of several chunks (a chain
    # cut at a chunk boundary is not followed across it)
    if not exact or not touched_cells:
        return data
    if len(touched_cells) == 1:
        flagged = bad_cells[0]
    else:
        nchunks = np.bincount(np.concatenate(touched_cells), minlength=ncell)
        for tg in bad_cells:
            nchunks[tg] = 2
        flagged = np.flatnonzero(nchunks >= 2)
        del nchunks
    if len(flagged):
        if saved is None:
            saved = _collect_rows(loc, w, h, flagged)
        vals = _exact_cells(saved, flagged, w, h, evenodd)
        np.clip(vals, 0.0, 1.0, out=vals)
        # rounding residue of cancelling edges (a path traced back on itself)
        vals[vals < _RESIDUE] = 0.0
        data.reshape(-1)[flagged] = vals
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


def _resolve(cover, partial, w, h, evenodd):
    """Coverage (h, w) float32 from the flat cover / partial accumulators.

    Only cells holding pieces have cover or partial terms; along a row the
    winding is constant between them.  So the running sum is taken over
    those cells only, and the output is assembled with one ``np.repeat`` of
    runs in flat order: for every touched cell, the cell itself, then the
    rest of its row up to the next touched cell at the winding after it,
    then (when the row ends first) zeros up to the next touched cell.
    """
    touched = np.flatnonzero((cover != 0) | (partial != 0))
    return _resolve_cells(touched, cover[touched], partial[touched], w, h, evenodd)


def _resolve_cells(touched, cv, pv, w, h, evenodd):
    """:func:`_resolve` from the touched cells only: ``touched`` (sorted
    flat indices) and their cover ``cv`` and partial ``pv`` sums."""
    n = w * h
    if len(touched) == 0:
        return np.zeros((h, w), np.float32)
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
    return np.repeat(vals.astype(np.float32), lens).reshape(h, w)


def _collect_rows(loc, w, h, flagged):
    """Pieces (of all chunks) in rows holding flagged cells, left of or in the
    rightmost flagged cell of their row."""
    maxcol = np.full(h, -2, np.int64)
    np.maximum.at(maxcol, flagged // w, flagged % w)
    parts = []
    for lo, hi in _chunks(loc, w, h):
        pc = _pieces(loc[lo:hi], w, h)
        if pc is None:
            continue
        col, row = pc[4], pc[5]
        sel = col <= maxcol[row]
        parts.append([a[sel] for a in pc])
    return [np.concatenate([p[i] for p in parts]) for i in range(6)]


def _exact_cells(pieces, flagged, w, h, evenodd, lrow=None, cellidx=None):
    """Exact coverage of the flagged cells (sorted flat indices).

    In a cell, the covered length ``g(y)`` of the horizontal line at height
    ``y`` is linear in ``y`` between *critical heights*: the cell's top and
    bottom, the end points of the pieces in the cell (which include every
    point where an edge crosses the cell's left side) and the heights where
    two pieces in the cell intersect.  The midpoint rule on those intervals
    is therefore exact.  On each sample line the winding at the cell's left
    side is the winding at its top-left corner (signed crossings of the top
    grid line left of the cell) plus the crossings of the left side above the
    sample; crossings inside the cell are sorted and the fill rule is applied
    span by span.  Cells with more than _PAIR_LIMIT pieces skip the pairwise
    intersections (exact only if their pieces do not cross) and, when they
    also have more than SUBSCANLINES + 2 distinct heights, use SUBSCANLINES
    evenly spaced heights instead (the midpoint rule is then approximate).
    ``lrow`` (optional) is each piece's row in its own y coordinates when
    ``row`` is a row of a stack of several boxes (see :func:`coverage_many`).
    ``cellidx`` (optional) is ``(cells, inv)``: the sorted distinct keys
    ``row * w + max(col, 0)`` of all the pieces (``flagged`` among them)
    and each piece's index into ``cells``, int64 ndarrays; with it the
    pieces are matched to the flagged cells through ``inv`` (one gather
    per piece instead of a search) and the corner windings are summed
    per cell.
    """
    xa, ya, xb, yb, col, row = pieces
    if lrow is None:
        lrow = row
    F = len(flagged)
    frow = flagged // w
    fcol = flagged % w
    if cellidx is not None:
        return _exact_cells_indexed(pieces, flagged, w, h, evenodd, lrow, cellidx)

    if h * (w + 1) <= min(_CELLMAP_MAX, _CELLMAP_RATIO * len(xa)):
        # flagged index of every cell, -1 elsewhere (extra column for c = w)
        cellmap = np.full(h * (w + 1), -1, np.int32)
        cellmap[frow * (w + 1) + fcol] = np.arange(F)

        def lookup(r, c):
            i = cellmap[r * (w + 1) + np.maximum(c, 0)]
            ok = (i >= 0) & (c >= 0)
            return i.astype(np.int64), ok
    else:
        def lookup(r, c):
            key = r * w + c
            i = np.searchsorted(flagged, key)
            np.minimum(i, F - 1, out=i)
            return i, (flagged[i] == key) & (c >= 0) & (c < w)

    # -- winding at each flagged cell's top-left corner ------------------------
    # pieces starting on their row's top line (not horizontal) cross it; the
    # crossing counts for cells right of the piece's column
    dy = yb - ya
    ymin = np.minimum(ya, yb)
    top = (ymin == lrow) & (dy != 0)
    tkey = row[top] * (w + 1) + (col[top] + 1)
    torder = np.argsort(tkey, kind='stable')
    tkey = tkey[torder]
    tcs = np.concatenate([[0], np.cumsum(np.sign(dy[top])[torder])])
    qrow = frow * (w + 1)
    corner = (tcs[np.searchsorted(tkey, qrow + fcol + 1, side='left')]
              - tcs[np.searchsorted(tkey, qrow, side='left')])
    fl, okl = lookup(row, col + 1)
    fi, oki = lookup(row, col)
    return _exact_tail(pieces, lrow, fcol, corner, fl, okl, fi, oki, evenodd)


def _exact_cells_indexed(pieces, flagged, w, h, evenodd, lrow, cellidx):
    """:func:`_exact_cells` with the pieces' cell index ``cellidx``.

    Only the pieces in rows holding a flagged cell take part (the cells'
    own pieces, their left neighbours' and the crossings of the rows' top
    lines left of them are all there), kept in their order.
    """
    cells, inv = cellidx
    F = len(flagged)
    fcol = flagged % w
    U = len(cells)
    rows = np.zeros(h, bool)
    rows[flagged // w] = True
    sub = np.flatnonzero(rows[pieces[5]])
    pieces = tuple(a[sub] for a in pieces)
    xa, ya, xb, yb, col, row = pieces
    lrow = lrow[sub]
    inv = inv[sub]
    real = col >= 0
    # flagged index of every distinct cell (-1: not flagged), and of the
    # cell right of it in its row
    uf = np.searchsorted(cells, flagged)            # flagged is among cells
    here = np.full(U, -1, np.int64)
    here[uf] = np.arange(F)
    right = np.full(U, -1, np.int64)
    ul = uf - 1
    nb = np.flatnonzero((fcol > 0) & (ul >= 0))
    nb = nb[cells[ul[nb]] == flagged[nb] - 1]
    right[ul[nb]] = nb
    fi = here[inv]
    # a virtual piece (col -1) shares the key of column 0: its right
    # neighbour is that cell itself
    fl = np.where(real, right[inv], fi)
    oki = (fi >= 0) & real
    okl = fl >= 0
    # -- winding at each flagged cell's top-left corner ------------------------
    # the signed crossings of the row's top line (pieces starting on it)
    # summed per distinct cell, then over the cells of the row left of the
    # flagged cell; virtual pieces in the flagged cell's own key (column 0)
    # are left of it too.  All sums are of small integers (exact).
    dy = yb - ya
    top = np.flatnonzero((np.minimum(ya, yb) == lrow) & (dy != 0))
    tsg = np.sign(dy[top])
    tcell = np.bincount(inv[top], weights=tsg, minlength=U)
    tcs = np.concatenate([[0.0], np.cumsum(tcell)])
    rstart = np.searchsorted(cells, flagged - fcol)
    corner = tcs[uf] - tcs[rstart]
    tv = ~real[top]
    if tv.any():
        vc = np.bincount(inv[top[tv]], weights=tsg[tv], minlength=U)
        corner += vc[uf]
    return _exact_tail(pieces, lrow, fcol, corner, fl, okl, fi, oki, evenodd)


def _exact_tail(pieces, lrow, fcol, corner, fl, okl, fi, oki, evenodd):
    """The rest of :func:`_exact_cells`, given the winding at each flagged
    cell's top-left corner and, for every piece, the flagged cell right of
    it (``fl``, valid where ``okl``) and the one holding it (``fi``, valid
    where ``oki``)."""
    xa, ya, xb, yb, col, row = pieces
    F = len(fcol)
    # -- changes of the left-side winding inside each cell --------------------
    # every piece contributes +1 at its start height and -1 at its end height
    # (for either direction); summed over the pieces left of the cell these
    # cancel except where a chain crosses the cell's left side, so only the
    # pieces of the left neighbour ending on that side (or, for column 0, the
    # virtual column) need to be counted
    # (tested on the pieces left of a flagged cell only, in piece order)
    lp = np.flatnonzero(okl)
    lv = col[lp] < 0
    lc = col[lp] + 1
    s_on = lp[lv | (xa[lp] == lc)]
    e_on = lp[lv | (xb[lp] == lc)]
    ev_f = np.concatenate([fl[s_on], fl[e_on]])
    ev_y = np.concatenate([ya[s_on] - lrow[s_on], yb[e_on] - lrow[e_on]])
    ev_c = np.concatenate([np.ones(len(s_on)), -np.ones(len(e_on))])
    inner = ev_y > 0
    ev_f, ev_y, ev_c = ev_f[inner], ev_y[inner], ev_c[inner]
    eorder = np.argsort(ev_f * 2.0 + ev_y)
    ev_f, ev_y, ev_c = ev_f[eorder], ev_y[eorder], ev_c[eorder]
    ecount = np.bincount(ev_f, minlength=F)
    efirst = np.cumsum(ecount) - ecount

    # -- the pieces inside each flagged cell, grouped by cell -----------------
    sel = np.flatnonzero(oki)
    order = sel[np.argsort(fi[sel], kind='stable')]
    pf = fi[order]
    pxa, pya, pxb, pyb = xa[order], ya[order] - lrow[order], xb[order], yb[order] - lrow[order]
    pc0 = fcol[pf].astype(np.float64)
    pxa = pxa - pc0
    pxb = pxb - pc0
    gcount = np.bincount(pf, minlength=F)
    gfirst = np.cumsum(gcount) - gcount

    # -- cells in batches of bounded work -------------------------------------
    cost = (np.where(gcount <= _PAIR_LIMIT, gcount * (gcount - 1) // 2, SUBSCANLINES * gcount)
            + 4 * gcount + ecount + 4)
    ccum = np.cumsum(cost)
    out = np.empty(F)
    f_lo = 0
    while f_lo < F:
        base = ccum[f_lo - 1] if f_lo else 0
        f_hi = int(np.searchsorted(ccum, base + _CHUNK_WORK, side='right'))
        f_hi = min(max(f_hi, f_lo + 1), F)
        p_lo, p_hi = gfirst[f_lo], gfirst[f_hi - 1] + gcount[f_hi - 1]
        e_lo, e_hi = efirst[f_lo], efirst[f_hi - 1] + ecount[f_hi - 1]
        ps = slice(p_lo, p_hi)
        es = slice(e_lo, e_hi)
        out[f_lo:f_hi] = _exact_batch(
            pf[ps] - f_lo, pxa[ps], pya[ps], pxb[ps], pyb[ps],
            gcount[f_lo:f_hi], gfirst[f_lo:f_hi] - p_lo,
            ev_f[es] - f_lo, ev_y[es], ev_c[es], corner[f_lo:f_hi], evenodd)
        f_lo = f_hi
    return out


def _exact_batch(pf, pxa, pya, pxb, pyb, gcount, gfirst, ev_f, ev_y, ev_c, corner, evenodd):
    """Exact coverage of cells 0..F-1 of a batch (see :func:`_exact_cells`).

    pf : cell of each piece (sorted); pxa.. : piece ends in cell units
    (x - column, y - row); gcount, gfirst : pieces per cell and first piece;
    ev_* : left-side winding changes sorted by (cell, height); corner :
    winding at each cell's top-left corner.
    """
    F = len(gcount)
    # keys cell * 2 + height sort by cell, then height (heights closer than
    # the key's float resolution may tie; such intervals have no weight)
    ev_key = ev_f * 2.0 + ev_y
    ev_cs = np.concatenate([[0.0], np.cumsum(ev_c)])

    # -- critical heights -----------------------------------------------------
    # crowded cells (more than _PAIR_LIMIT pieces) skip the pairwise
    # intersections; if they also have more than SUBSCANLINES distinct end
    # point heights, an even grid replaces those, so crossings stay <= k * S
    crowded = gcount > _PAIR_LIMIT
    k = gcount[pf]
    small = k <= _PAIR_LIMIT
    hf = [np.arange(F), np.arange(F), pf, pf, ev_f]
    hy = [np.zeros(F), np.ones(F), pya, pyb, ev_y]
    pos = np.arange(len(pf)) - gfirst[pf]
    npair = np.where(small, k - 1 - pos, 0)
    n_pairs = int(npair.sum())
    if n_pairs:
        i = np.repeat(np.arange(len(pf)), npair)
        j = i + 1 + (np.arange(n_pairs) - np.repeat(np.cumsum(npair) - npair, npair))
        ax, ay = pxa[i], pya[i]
        ux, uy = pxb[i] - ax, pyb[i] - ay
        vx, vy = pxb[j] - pxa[j], pyb[j] - pya[j]
        qx, qy = pxa[j] - ax, pya[j] - ay
        den = ux * vy - uy * vx
        with np.errstate(all='ignore'):
            t = (qx * vy - qy * vx) / den
            u = (qx * uy - qy * ux) / den
        eps = 1e-9
        hit = (den != 0) & (t >= -eps) & (t <= 1 + eps) & (u >= -eps) & (u <= 1 + eps)
        hf.append(pf[i[hit]])
        hy.append(np.clip(ay[hit] + t[hit] * uy[hit], 0.0, 1.0))
    hf = np.concatenate(hf)
    hy = np.clip(np.concatenate(hy), 0.0, 1.0)
    hkey = np.sort(hf * 2.0 + hy)
    distinct = np.empty(len(hkey), bool)
    distinct[0] = True
    distinct[1:] = hkey[1:] != hkey[:-1]
    hkey = hkey[distinct]
    if crowded.any():
        hid = np.floor(hkey * 0.5).astype(np.int64)
        gridded = crowded & (np.bincount(hid, minlength=F) > SUBSCANLINES + 2)
        big = np.flatnonzero(gridded)
        if len(big):
            grid = np.arange(SUBSCANLINES + 1) / SUBSCANLINES
            extra = (np.repeat(big * 2.0, len(grid)) + np.tile(grid, len(big)))
            hkey = np.sort(np.concatenate([hkey[~gridded[hid]], extra]))
    hid = np.floor(hkey * 0.5).astype(np.int64)
    hy = hkey - 2.0 * hid
    same = hid[1:] == hid[:-1]
    lo, hi = hy[:-1][same], hy[1:][same]
    sfid = hid[:-1][same]
    weight = hi - lo
    keep = weight > 0
    sfid, weight = sfid[keep], weight[keep]
    sy = 0.5 * (lo[keep] + hi[keep])            # sample heights (cell units)
    skey = sfid * 2.0 + sy                      # sorted ascending

    # -- left-side winding at each sample -------------------------------------
    wl = (corner[sfid]
          + ev_cs[np.searchsorted(ev_key, skey, side='right')]
          - ev_cs[np.searchsorted(ev_key, sfid * 2.0, side='left')])
    wl = np.rint(wl).astype(np.int64)

    # -- crossings of the sample lines by the pieces in the cell ---------------
    moving = pya != pyb
    mi = np.flatnonzero(moving)
    pmin = np.minimum(pya[mi], pyb[mi])
    pmax = np.maximum(pya[mi], pyb[mi])
    base = pf[mi] * 2.0
    s_lo = np.searchsorted(skey, base + pmin, side='right')
    s_hi = np.searchsorted(skey, base + pmax, side='left')
    cnt = np.maximum(s_hi - s_lo, 0)
    m_total = int(cnt.sum())
    g = (wl != 0) if not evenodd else (wl & 1).astype(bool)
    g = g.astype(np.float64)                      # covered length per sample
    if m_total:
        owner = np.repeat(mi, cnt)
        smp = np.repeat(s_lo, cnt) + (np.arange(m_total) - np.repeat(np.cumsum(cnt) - cnt, cnt))
        oya = pya[owner]
        oxa = pxa[owner]
        ody = pyb[owner] - oya
        with np.errstate(over='ignore'):
            xc = oxa + (sy[smp] - oya) * ((pxb[owner] - oxa) / ody)
        np.clip(xc, 0.0, 1.0, out=xc)
        sgn = np.where(ody > 0, 1, -1)
        corder = np.argsort(smp * 2.0 + xc, kind='stable')
        smp, xc, sgn = smp[corder], xc[corder], sgn[corder]
        newg = np.empty(m_total, bool)
        newg[0] = True
        newg[1:] = smp[1:] != smp[:-1]
        cs = np.cumsum(sgn)
        gstart = np.flatnonzero(newg)
        before = (cs[gstart] - sgn[gstart])[np.cumsum(newg) - 1]
        w_after = wl[smp] + cs - before
        w_before = w_after - sgn
        if evenodd:
            fa, fb = w_after & 1, w_before & 1
        else:
            fa, fb = (w_after != 0), (w_before != 0)
        # telescoping: each crossing changes f for the rest of the cell
        delta = (fa.astype(np.float64) - fb) * (1.0 - xc)
        g += np.bincount(smp, weights=delta, minlength=len(g))
    return np.bincount(sfid, weights=g * weight, minlength=F)


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
                   clip=None, exact=True):
    """:func:`coverage_many` with the shapes' edges in one array.

    Parameters
    ----------
    edges : (E, 2, 2) array_like of float
        The edges of all shapes, shape after shape (device pixels).
    counts : (n,) array_like of int
        Number of edges of each shape (``sum(counts) == E``; 0 allowed).
    width, height, fill_rules, antialias, clip, exact
        As for :func:`coverage_many`.

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
    win = _window(width, height, clip)
    out = [None] * n
    if n == 0 or len(e) == 0:
        return out
    first = np.cumsum(counts) - counts
    rules = ['evenodd' if v else 'nonzero' for v in eo.tolist()]
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
        out[i] = coverage(e[first[i]:first[i] + counts[i]], width, height, rules[i], True, clip,
                          bool(ex[i]))
    sel = np.flatnonzero(live & ~alone)
    if len(sel) == 0:
        return out
    idx, X0, Y0, sw, sh, est = idx[sel], X0[sel], Y0[sel], (X1 - X0)[sel], (Y1 - Y0)[sel], est[sel]
    ne = counts[idx]
    take = np.zeros(n, bool)
    take[idx] = True
    loc = e[np.repeat(take, counts)]
    loc = loc - np.stack([np.repeat(X0, ne), np.repeat(Y0, ne)], 1)[:, None, :].astype(np.float64)
    # sub-batches bounded in pieces and in cells
    cest = np.cumsum(est)
    carea = np.cumsum(sw * sh)
    eoff = np.concatenate([[0], np.cumsum(ne)])
    m = len(idx)
    lo = 0
    while lo < m:
        b_est = cest[lo - 1] if lo else 0
        b_area = carea[lo - 1] if lo else 0
        hi = min(int(np.searchsorted(cest, b_est + _CHUNK_PIECES, side='right')),
                 int(np.searchsorted(carea, b_area + _BATCH_CELLS, side='right')))
        hi = min(max(hi, lo + 1), m)
        s = slice(lo, hi)
        _many_batch(loc[eoff[lo]:eoff[hi]], ne[s], X0[s], Y0[s], sw[s], sh[s], eo[idx[s]],
                    ex[idx[s]], idx[s], out)
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
        hi = int(np.searchsorted(csize, base + _BATCH_CELLS, side='right'))
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


def _many_batch(loc, ne, X0, Y0, sw, sh, seo, sex, ids, out):
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
    col = np.minimum(np.maximum(col, -1), swp - 1)
    left = col < 0
    if left.any():
        xa = np.where(left, -0.5, xa)
        xb = np.where(left, -0.5, xb)
    row = np.floor(0.5 * (ya + yb)).astype(np.int64)
    row = np.minimum(np.maximum(row, 0), sh[sid] - 1)
    # -- accumulate over the touched cells of the stacked boxes ---------------
    real = col >= 0
    grow = row + roff[sid]
    cell = grow * W + np.maximum(col, 0)
    dy = yb - ya
    fx = np.where(real, 0.5 * (xa + xb) - col, 0.0)
    cells, inv = _distinct_cells(cell, sid, row, np.maximum(col, 0), swp, sw, sh)
    cv = np.bincount(inv, weights=dy, minlength=len(cells))
    pv = np.bincount(inv, weights=dy * fx, minlength=len(cells))
    # cells to recompute exactly, among the pieces of exact shapes only
    if sex.any():
        fcell = np.where(real, cell, -1)
        brk = np.zeros(len(sid), bool)
        brk[1:] = sid[1:] != sid[:-1]
        if sex.all():
            _, flagged = _flag_cells(xa, ya, xb, yb, fcell, brk)
        else:
            ps = sex[sid]
            _, flagged = _flag_cells(xa[ps], ya[ps], xb[ps], yb[ps], fcell[ps], brk[ps])
    else:
        flagged = np.zeros(0, np.int64)
    nz = (cv != 0) | (pv != 0)
    T, cv, pv = cells[nz], cv[nz], pv[nz]
    if len(T) == 0 and len(flagged) == 0:
        return
    # -- resolve (as _resolve_cells, running sums restarted per shape) --------
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
    fsid = np.searchsorted(roff, flagged // W, side='right') - 1
    tail = 0
    if len(fsid) and not has[fsid].all():
        # shapes with flagged cells but no cover terms get zero images (as
        # _resolve_cells gives them): their sizes are added to the leading
        # zeros of the next shape with cover terms (or appended)
        only = np.zeros(k, bool)
        only[fsid] = True
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
    if len(flagged):
        pieces = (xa, ya, xb, yb, col, grow)
        H = int(sh.sum())
        for evenodd in (False, True):
            sel = seo[fsid] == evenodd
            if not sel.any():
                continue
            fl = flagged[sel]
            fs = fsid[sel]
            v = _exact_cells(pieces, fl, W, H, evenodd, lrow=row, cellidx=(cells, inv))
            np.clip(v, 0.0, 1.0, out=v)
            v[v < _RESIDUE] = 0.0
            fr = fl // W - roff[fs]
            pos = ooff[fs] + fr * sw[fs] + fl % W
            v = v.astype(np.float32)
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
    out = np.empty(len(v))
    for c in np.flatnonzero(ccount).tolist():
        el = order[cstart[c]:cstart[c] + ccount[c]]
        sg = seg[el]
        members = np.flatnonzero((cls == c) & (cnt > 0))
        slot = np.searchsorted(members, sg)
        pos = el - start[sg]
        M = np.zeros((len(members), int(cnt[members].max())))
        M[slot, pos] = v[el]
        np.cumsum(M, axis=1, out=M)
        out[el] = M[slot, pos]
    return out
