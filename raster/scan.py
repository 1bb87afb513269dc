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
3. The fill rule ``f`` (nonzero: ``min(1, |w|)``; evenodd: distance of ``w``
   to the nearest even integer) is applied to that integral.  This equals the
   integral of ``f(w)`` -- the true coverage -- whenever ``w`` takes at most
   two adjacent integer values inside the cell, because ``f`` is linear
   between adjacent integers.  Cells where that might fail are recomputed
   exactly along 32 sub-scanlines per pixel (see :func:`coverage`).

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

import numpy as np

from . import limits
from .errors import CanvasError, LimitError, PathError

__all__ = ['Mask', 'coverage', 'check_canvas_size', 'SUBSCANLINES']

#: Sub-scanlines per pixel used to recompute the cells where edges of
#: different chains meet (crossings, overlaps, coincident edges).
SUBSCANLINES = 32

# Coverage below this is float64 rounding residue and is set to 0.
_RESIDUE = 1e-9
# Most pieces generated at once; longer inputs are processed in chunks.
_CHUNK_PIECES = 1 << 21
# Most sub-scanline events sorted at once in the recompute pass.
_CHUNK_EVENTS = 1 << 22


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
    :data:`raster.limits.MAX_SIDE` or with more than
    :data:`raster.limits.MAX_PIXELS` pixels.

    >>> check_canvas_size(10.0, 3)
    (10, 3)
    """
    out = []
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
        if i > limits.MAX_SIDE:
            raise CanvasError('canvas %s %d exceeds MAX_SIDE %d' % (name, i, limits.MAX_SIDE))
        out.append(i)
    if out[0] * out[1] > limits.MAX_PIXELS:
        raise CanvasError('canvas %dx%d exceeds MAX_PIXELS %d'
                          % (out[0], out[1], limits.MAX_PIXELS))
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
    if np.abs(e).max() > limits.MAX_COORD:
        raise LimitError('edge coordinate magnitude exceeds MAX_COORD %g' % limits.MAX_COORD)
    return e


def _box(e, width, height, clip, antialias):
    """Integer pixel box [X0, X1) x [Y0, Y1) where work happens, or None."""
    xs, ys = e[:, :, 0], e[:, :, 1]
    if antialias:
        X0, X1 = np.floor(xs.min()), np.ceil(xs.max())
        Y0, Y1 = np.floor(ys.min()), np.ceil(ys.max())
    else:   # pixels whose centre may be inside
        X0, X1 = np.floor(xs.min() + 0.5), np.ceil(xs.max() - 0.5)
        Y0, Y1 = np.floor(ys.min() + 0.5), np.ceil(ys.max() - 0.5)
    X0, Y0 = max(int(X0), 0), max(int(Y0), 0)
    X1, Y1 = min(int(X1), width), min(int(Y1), height)
    if clip is not None:
        try:
            c = [float(v) for v in clip]
        except (TypeError, ValueError):
            raise CanvasError('clip must be four numbers (x0, y0, x1, y1)') from None
        if len(c) != 4 or not all(np.isfinite(c)):
            raise CanvasError('clip must be four finite numbers (x0, y0, x1, y1)')
        X0, Y0 = max(X0, int(np.floor(c[0]))), max(Y0, int(np.floor(c[1])))
        X1, Y1 = min(X1, int(np.ceil(c[2]))), min(Y1, int(np.ceil(c[3])))
    if X1 <= X0 or Y1 <= Y0:
        return None
    return X0, Y0, X1, Y1


def coverage(edges, width, height, fill_rule='nonzero', antialias=True, clip=None):
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
    fill_rule : {'nonzero', 'evenodd'}
    antialias : bool
        True: exact area coverage of every pixel.  False
        (``shape-rendering: crispEdges``): a pixel is 1 when its centre is
        inside under the fill rule, else 0.
    clip : (x0, y0, x1, y1) or None
        Restrict work and output to this pixel rectangle (rounded outward
        to whole pixels).

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
        A coordinate larger in magnitude than :data:`raster.limits.MAX_COORD`.
    CanvasError
        Zero, negative or too large canvas size; malformed ``clip``.

    Notes
    -----
    Antialiased coverage is exact (up to float64 rounding) in every pixel
    where the winding number takes at most two adjacent values.  A pixel
    can hold more only where edges of different chains meet: a *chain* is
    a run of consecutive pieces of consecutive edges (edge ``e`` ends where
    edge ``e+1`` starts) inside that pixel.  A single chain that does not
    cross itself cuts the pixel into two sides whose windings differ by one;
    a chain with at most two pieces, or monotone in x or in y, cannot cross
    itself.  So every pixel that holds two or more chains, or one chain of
    three or more pieces that is monotone in neither axis, is recomputed
    exactly along :data:`SUBSCANLINES` horizontal sub-scanlines: for each
    sub-scanline the crossings of all edges left of and in the pixel are
    sorted, the winding is accumulated left to right and the fill rule is
    applied to each span.  The remaining error is that of the midpoint rule
    in y, at most ``1 / (2 * SUBSCANLINES)`` per pixel at a horizontal edge
    and far less elsewhere.

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
    if fill_rule not in ('nonzero', 'evenodd'):
        raise PathError("fill_rule must be 'nonzero' or 'evenodd', got %r" % (fill_rule,))
    evenodd = fill_rule == 'evenodd'
    e = _check_edges(edges)
    # edges with no vertical extent never change any winding number
    if len(e) == 0:
        return None
    box = _box(e, width, height, clip, antialias)
    if box is None:
        return None
    X0, Y0, X1, Y1 = box
    w, h = X1 - X0, Y1 - Y0
    local = e - np.array([X0, Y0], np.float64)
    if antialias:
        data = _area_coverage(e, local, w, h, evenodd)
    else:
        data = _centre_coverage(local, w, h, evenodd)
    if data is None or not data.any():
        return None
    return Mask(data, X0, Y0)


# -- exact area ---------------------------------------------------------------

def _split(ua, va, ub, vb, hi):
    """Split segments (u, v) at every integer u = k with 0 <= k <= hi that lies
    strictly inside the segment.

    Returns the pieces (ua, va, ub, vb), each lying between two consecutive
    integer u lines (or entirely below 0 / above hi), in travel order.  A
    split point is stored once, so consecutive pieces share it bitwise.
    """
    n_in = len(ua)
    umin = np.minimum(ua, ub)
    umax = np.maximum(ua, ub)
    kmin = np.maximum(np.floor(umin) + 1.0, 0.0)
    kmax = np.minimum(np.ceil(umax) - 1.0, float(hi))
    n = np.maximum(kmax - kmin + 1.0, 0.0).astype(np.int64)
    m_total = int(n.sum())
    if m_total == 0:
        return ua, va, ub, vb
    npc = n + 1                                  # pieces per segment
    ends = np.cumsum(npc)
    pstart = ends - npc                          # first piece of each segment
    n_pieces = int(ends[-1])
    # point sequence: segment i owns points pstart[i] + i ... + n[i] + 1
    off = pstart + np.arange(n_in)
    U = np.empty(n_pieces + n_in)
    V = np.empty(n_pieces + n_in)
    U[off] = ua
    V[off] = va
    U[off + n + 1] = ub
    V[off + n + 1] = vb
    owner = np.repeat(np.arange(n_in), n)
    first = np.cumsum(n) - n
    m = np.arange(m_total) - first[owner]
    a_u, b_u = ua[owner], ub[owner]
    k = np.where(b_u > a_u, kmin[owner] + m, kmax[owner] - m)
    t = (k - a_u) / (b_u - a_u)
    a_v = va[owner]
    pos = off[owner] + 1 + m
    U[pos] = k
    V[pos] = a_v + t * (vb[owner] - a_v)
    # piece j starts at point j + (segment index of piece j)
    piece_owner = np.repeat(np.arange(n_in), npc)
    idx = np.arange(n_pieces) + piece_owner
    return U[idx], V[idx], U[idx + 1], V[idx + 1]


def _pieces(loc, w, h):
    """Cell pieces of local edges ``loc`` ((E, 2, 2), box origin at 0).

    Returns xa, ya, xb, yb (float64) and col, row (int64) for
    every piece inside the box rows, with x clamped to >= 0 (the part of an
    edge left of the box acts as a vertical edge on its left side) and the
    part right of the box dropped.
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
    np.maximum(xa, 0.0, out=xa)
    np.maximum(xb, 0.0, out=xb)
    col = np.floor(xm).astype(np.int64)
    np.clip(col, 0, w - 1, out=col)
    row = np.floor(0.5 * (ya + yb)).astype(np.int64)
    np.clip(row, 0, h - 1, out=row)
    return xa, ya, xb, yb, col, row


def _chunks(loc, w, h):
    """Edge index ranges whose pieces number about _CHUNK_PIECES at most."""
    n_e = len(loc)
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


def _run_summary(xa, ya, xb, yb, cell):
    """Cells of chain runs, and which runs may cross themselves.

    A piece *continues* the previous piece of the array when it starts
    exactly where that one ends (split points and shared polygon vertices
    are bitwise equal).  A run is a maximal sequence of continuing pieces in
    one cell; a closed chain whose first and last pieces meet in one cell
    has those two runs merged.  Returns the cell of every run and whether
    the run has three or more pieces and is monotone in neither x nor y.
    """
    n = len(cell)
    conn = np.zeros(n, bool)
    conn[1:] = (xa[1:] == xb[:-1]) & (ya[1:] == yb[:-1])
    start = ~conn
    start[1:] |= cell[1:] != cell[:-1]
    ridx = np.flatnonzero(start)
    dx = xb - xa
    dy = yb - ya
    bits = ((dy > 0).astype(np.uint8) | ((dy < 0).astype(np.uint8) << 1)
            | ((dx > 0).astype(np.uint8) << 2) | ((dx < 0).astype(np.uint8) << 3))
    rbits = np.bitwise_or.reduceat(bits, ridx)
    rlen = np.diff(np.append(ridx, n))
    # closed chains: merge the run at the chain's start into the run at its end
    heads = np.flatnonzero(~conn)
    tails = np.append(heads[1:], n) - 1
    cyc = ((xa[heads] == xb[tails]) & (ya[heads] == yb[tails])
           & (cell[heads] == cell[tails]))
    if cyc.any():
        run_id = np.cumsum(start) - 1
        rh, rt = run_id[heads[cyc]], run_id[tails[cyc]]
        two = rh != rt
        rh, rt = rh[two], rt[two]
        rbits[rt] |= rbits[rh]
        rlen[rt] += rlen[rh]
        keep = np.ones(len(ridx), bool)
        keep[rh] = False
        ridx, rbits, rlen = ridx[keep], rbits[keep], rlen[keep]
    tangled = (rlen >= 3) & ((rbits & 3) == 3) & ((rbits & 12) == 12)
    return cell[ridx], tangled


def _area_coverage(e, loc, w, h, evenodd):
    ncell = w * h
    cover = None
    partial = None
    run_cells, tangled_cells = [], []
    chunks = _chunks(loc, w, h)
    saved = None
    for lo, hi in chunks:
        pc = _pieces(loc[lo:hi], w, h)
        if pc is None:
            continue
        xa, ya, xb, yb, col, row = pc
        cell = row * w + col
        dy = yb - ya
        fx = 0.5 * (xa + xb) - col
        c1 = np.bincount(cell, weights=dy, minlength=ncell)
        p1 = np.bincount(cell, weights=dy * fx, minlength=ncell)
        if cover is None:
            cover, partial = c1, p1
        else:
            cover += c1
            partial += p1
        rc, tg = _run_summary(xa, ya, xb, yb, cell)
        run_cells.append(rc)
        tangled_cells.append(rc[tg])
        if len(chunks) == 1:
            saved = (xa, ya, xb, yb, col, row)
    if cover is None:
        return None
    acc = np.cumsum(cover.reshape(h, w), axis=1)
    acc -= partial.reshape(h, w)
    del cover, partial
    if evenodd:
        # distance to the nearest even integer
        acc *= 0.5
        acc -= np.rint(acc)
        np.abs(acc, out=acc)
        acc *= 2.0
    else:
        np.abs(acc, out=acc)
        np.minimum(acc, 1.0, out=acc)
    data = acc.astype(np.float32)
    del acc

    # cells where two or more chains meet, or a chain may cross itself
    rc = np.sort(np.concatenate(run_cells))
    multi = rc[1:][rc[1:] == rc[:-1]]
    flagged = np.unique(np.concatenate([multi] + tangled_cells))
    if len(flagged):
        if saved is None:
            saved = _collect_rows(loc, w, h, flagged)
        vals = _subscan(saved, flagged, w, h, evenodd)
        data.reshape(-1)[flagged] = vals
    np.clip(data, 0.0, 1.0, out=data)
    # rounding residue of cancelling edges (e.g. a path traced back on itself)
    data[data < _RESIDUE] = 0.0
    return data


def _collect_rows(loc, w, h, flagged):
    """Pieces (of all chunks) in rows holding flagged cells, left of or in the
    rightmost flagged cell of their row."""
    maxcol = np.full(h, -1, np.int64)
    np.maximum.at(maxcol, flagged // w, flagged % w)
    parts = []
    for lo, hi in _chunks(loc, w, h):
        pc = _pieces(loc[lo:hi], w, h)
        if pc is None:
            continue
        xa, ya, xb, yb, col, row = pc
        sel = (col <= maxcol[row]) & (ya != yb)
        parts.append([a[sel] for a in (xa, ya, xb, yb, col, row)])
    return [np.concatenate([p[i] for p in parts]) for i in range(6)]


def _subscan(pieces, flagged, w, h, evenodd):
    """Coverage of the flagged cells (sorted flat indices) by exact horizontal
    coverage on SUBSCANLINES sub-scanlines per pixel."""
    S = SUBSCANLINES
    xa, ya, xb, yb, col, row = pieces
    frow = flagged // w
    fcol = flagged % w
    maxcol = np.full(h, -1, np.int64)
    np.maximum.at(maxcol, frow, fcol)
    sel = (col <= maxcol[row]) & (ya != yb)
    xa, ya, xb, yb, row = xa[sel], ya[sel], xb[sel], yb[sel], row[sel]
    # sub-scanline s of row r is at y = r + (s + 0.5) / S; a piece crosses it
    # when min(ya, yb) <= y < max(ya, yb)
    ylo = (np.minimum(ya, yb) - row) * S - 0.5
    yhi = (np.maximum(ya, yb) - row) * S - 0.5
    s_lo = np.ceil(ylo).astype(np.int64)
    cnt = np.ceil(yhi).astype(np.int64) - s_lo
    np.maximum(cnt, 0, out=cnt)
    # rows in batches so that the sorted event arrays stay bounded
    rows_f, fstart = np.unique(frow, return_index=True)
    ev_row = np.bincount(row, weights=cnt, minlength=h)[rows_f]
    ev_row += 2 * S * np.diff(np.append(fstart, len(flagged)))
    cum = np.cumsum(ev_row)
    out = np.empty(len(flagged), np.float64)
    b0 = 0
    while b0 < len(rows_f):
        base = cum[b0 - 1] if b0 else 0.0
        b1 = int(np.searchsorted(cum, base + _CHUNK_EVENTS, side='right'))
        b1 = min(max(b1, b0 + 1), len(rows_f))
        r_lo, r_hi = rows_f[b0], rows_f[b1 - 1]
        f_lo = fstart[b0]
        f_hi = fstart[b1] if b1 < len(rows_f) else len(flagged)
        ps = (row >= r_lo) & (row <= r_hi)
        out[f_lo:f_hi] = _subscan_batch(
            xa[ps], ya[ps], xb[ps], yb[ps], row[ps], s_lo[ps], cnt[ps],
            frow[f_lo:f_hi], fcol[f_lo:f_hi], r_lo, r_hi, w, evenodd)
        b0 = b1
    return out


def _subscan_batch(xa, ya, xb, yb, row, s_lo, cnt, frow, fcol, r_lo, r_hi, w, evenodd):
    """Sub-scanline coverage of the flagged cells (frow, fcol) of rows
    r_lo..r_hi from the pieces of those rows (float64 (F,))."""
    S = SUBSCANLINES
    span = float(w + 2)                      # key = group * span + x, x in [0, w]
    # crossings of every piece with the sub-scanlines it spans
    m_total = int(cnt.sum())
    nf = len(frow)
    if m_total == 0:
        return np.zeros(nf)
    owner = np.repeat(np.arange(len(xa)), cnt)
    m = np.arange(m_total) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    s = s_lo[owner] + m
    r = row[owner]
    a_y, a_x = ya[owner], xa[owner]
    dyo = yb[owner] - a_y
    xc = a_x + ((r - a_y) + (s + 0.5) / S) * ((xb[owner] - a_x) / dyo)
    np.clip(xc, 0.0, float(w), out=xc)
    grp = (r - r_lo) * S + s
    keys = grp * span + xc
    order = np.argsort(keys)
    keys = keys[order]
    grp = grp[order]
    x = xc[order]
    sign = np.where(dyo[order] > 0, 1, -1).astype(np.int32)
    del owner, m, s, r, a_y, a_x, dyo, xc, order
    # winding after each crossing, restarting at 0 on each sub-scanline
    newg = np.empty(m_total, bool)
    newg[0] = True
    newg[1:] = grp[1:] != grp[:-1]
    gid = np.cumsum(newg) - 1
    gfirst = np.flatnonzero(newg)
    cs = np.cumsum(sign)
    wind = cs - (cs[gfirst] - sign[gfirst])[gid]
    if evenodd:
        f = (wind & 1).astype(np.float64)
    else:
        f = (wind != 0).astype(np.float64)
    # Fc[i]: integral of f(w) dx from the sub-scanline's start to x[i]
    inc = np.zeros(m_total)
    inc[1:] = f[:-1] * (x[1:] - x[:-1])
    inc[newg] = 0.0
    Fc = np.cumsum(inc)
    Fc -= Fc[gfirst][gid]

    def F(q_grp, q_x):
        i = np.searchsorted(keys, q_grp * span + q_x, side='right') - 1
        ic = np.maximum(i, 0)
        ok = (i >= 0) & (grp[ic] == q_grp)
        return np.where(ok, Fc[ic] + f[ic] * (q_x - x[ic]), 0.0)

    qg = (((frow - r_lo) * S)[:, None] + np.arange(S)[None, :]).ravel()
    qx = np.repeat(fcol.astype(np.float64), S)
    val = F(qg, qx + 1.0) - F(qg, qx)
    return val.reshape(nf, S).sum(1) / S


# -- pixel centres ----------------------------------------------------------

def _centre_coverage(loc, w, h, evenodd):
    """1 where the pixel centre is inside, from crossings of the scanlines
    y = i + 0.5 (half-open: an edge crosses when min(y) <= y_c < max(y))."""
    xa, ya = loc[:, 0, 0], loc[:, 0, 1]
    xb, yb = loc[:, 1, 0], loc[:, 1, 1]
    i_lo = np.clip(np.ceil(np.minimum(ya, yb) - 0.5), 0, h)
    i_hi = np.clip(np.ceil(np.maximum(ya, yb) - 0.5), 0, h)
    n = (i_hi - i_lo).astype(np.int64)
    total = int(n.sum())
    if total == 0:
        return None
    if total > limits.MAX_FLATTEN_POINTS:
        raise LimitError('too many scanline crossings (%d)' % total)
    owner = np.repeat(np.arange(len(xa)), n)
    m = np.arange(total) - np.repeat(np.cumsum(n) - n, n)
    i = i_lo[owner].astype(np.int64) + m
    a_y, a_x = ya[owner], xa[owner]
    dyo = yb[owner] - a_y
    xc = a_x + (i + 0.5 - a_y) * ((xb[owner] - a_x) / dyo)
    # the crossing changes the winding of centres j + 0.5 > xc
    j = np.floor(np.clip(xc - 0.5, -1.0, float(w - 1))).astype(np.int64) + 1
    cell = i * (w + 1) + j
    wsum = np.bincount(cell, weights=np.where(dyo > 0, 1.0, -1.0), minlength=h * (w + 1))
    wind = np.cumsum(wsum.reshape(h, w + 1)[:, :w], axis=1)
    wind = np.rint(wind).astype(np.int64)
    if evenodd:
        return (wind & 1).astype(np.float32)
    return (wind != 0).astype(np.float32)
