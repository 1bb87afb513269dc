"""Hairline outlines: strokes thinner than one device pixel are drawn one
pixel wide (their coverage scaled by their width, as resvg does); this
outlines them from device-space polylines in one vectorized pass, without
offset curves.  Meant for :func:`raster.pixels.scan.coverage` with
``exact=False`` (the pieces' areas summed per pixel, clipped to 1)."""

import numpy as np

__all__ = ['hairline_edges', 'hairline_outline']


def hairline_edges(pl, cap, join, miterlimit):
    """Outline edges of a 1 device pixel wide stroke along device-space
    polylines ``pl`` (:class:`raster.geometry.flattening.Polylines`), for hairlines:
    :func:`hairline_outline` with one cap, join and miter limit.

    Returns
    -------
    (E, 2, 2) float64 ndarray, or None when the general stroker must be used
    (a polyline of one distinct point with a non-butt cap: a dot).
    """
    k = len(pl)
    edges, _, dots = hairline_outline(pl, np.full(k, cap != 'butt'),
                                       np.full(k, join in ('miter', 'miter-clip', 'arcs')),
                                       np.full(k, float(miterlimit)))
    return None if dots.any() else edges


def hairline_outline(pl, capped, mitered, miterlimit):
    """Outline edges of 1 device pixel wide strokes along device-space
    polylines ``pl`` (:class:`raster.geometry.flattening.Polylines`), for hairlines.

    The stroke of a polyline is the union of a 1 px wide rectangle per
    segment, a bevel triangle at each vertex between two segments (plus the
    miter triangle where the polyline is ``mitered`` and the join within
    its ``miterlimit``) and, for ``capped`` polylines (square and round
    caps), a half-pixel extension at the ends of open polylines (a round
    cap is drawn square: at most 0.054 px^2 more per end).  Round joins are
    drawn bevelled (at most 0.04 px^2 less per join).  The pieces are
    separate polygons of one orientation (negative signed area), meant for
    the nonzero rule; :func:`raster.pixels.scan.coverage` with ``exact=False``
    sums their areas per pixel (clipped to 1), which counts the small
    overlaps of consecutive rectangles inside a turn twice, as a hairline
    renderer drawing one segment at a time does.  One vectorized pass for
    all polylines: no offset curves and no per-vertex Python work.

    Parameters
    ----------
    pl : raster.geometry.flattening.Polylines
        K polylines, device pixels.
    capped, mitered : (K,) bool ndarray
    miterlimit : (K,) float64 ndarray

    Returns
    -------
    edges : (E, 2, 2) float64 ndarray
        Polyline after polyline; each segment's rectangle, then the join
        after it.
    owner : (E,) int64 ndarray
        The polyline of each edge (non-decreasing).
    dots : (K,) bool ndarray
        Capped polylines of one distinct point: they draw a dot, which
        this outline leaves out (the general stroker draws it).
    """
    r = 0.5
    P = pl.points
    n = len(P)
    K = len(pl)
    none = (np.zeros((0, 2, 2)), np.zeros(0, np.int64), np.zeros(K, bool))
    if n == 0:
        return none
    starts, ends, closed = pl.starts, pl.ends, pl.closed
    nxt = np.arange(1, n + 1)
    nxt[ends - 1] = np.where(closed, starts, -1)
    a_idx = np.flatnonzero(nxt >= 0)
    a, b = P[a_idx], P[nxt[a_idx]]
    d = b - a
    length = np.hypot(d[:, 0], d[:, 1])
    keep = length > 1e-9
    a_idx, a, b, d, length = a_idx[keep], a[keep], b[keep], d[keep], length[keep]
    poly = np.searchsorted(starts, a_idx, side='right') - 1
    counts = np.bincount(poly, minlength=K)
    dots = capped & (counts == 0)
    S = len(a)
    if S == 0:
        return none[0], none[1], dots
    u = d / length[:, None]
    nv = np.stack([-u[:, 1], u[:, 0]], 1) * r
    j = np.arange(S)
    first = np.ones(S, bool)
    first[1:] = poly[1:] != poly[:-1]
    last = np.ones(S, bool)
    last[:-1] = poly[1:] != poly[:-1]
    op = capped[poly] & ~closed[poly]
    if op.any():
        # square (and round, drawn square) caps on open polylines
        a = a - (u * r) * (first & op)[:, None]
        b = b + (u * r) * (last & op)[:, None]
    # joins: each segment with the next one of its polyline (closed: wrap)
    head = np.maximum.accumulate(np.where(first, j, 0))
    nseg = np.where(~last, j + 1, np.where(closed[poly], head, -1))
    has_join = nseg >= 0
    i1 = np.flatnonzero(has_join)
    i2 = nseg[i1]
    v = P[nxt[a_idx[i1]]]
    cr = u[i1, 0] * u[i2, 1] - u[i1, 1] * u[i2, 0]
    side = np.where(cr > 0, -1.0, 1.0)[:, None]          # the outer side
    p1, p2 = v + side * nv[i1], v + side * nv[i2]
    within = np.zeros(S, bool)
    if len(i1):
        cos_t = np.clip((u[i1] * u[i2]).sum(1), -1.0, 1.0)   # turning angle
        # miter length / stroke width = 1 / sin(phi / 2), phi the angle
        # between the segments = pi - turning angle: 1 / cos(turn / 2)
        half = np.sqrt(np.maximum((1.0 + cos_t) / 2.0, 0.0))
        w_j = (mitered[poly[i1]] & (half > 1e-12) & (1.0 <= miterlimit[poly[i1]] * half)
               & (cos_t < 1.0 - 1e-12))
        within[i1] = w_j
    # edge slots: 4 per rectangle, 3 per bevel, 3 per miter triangle
    cnt = 4 + 3 * has_join + 3 * within
    off = np.cumsum(cnt) - cnt
    out = np.empty((int(cnt.sum()), 2, 2))
    # a + n, b + n, b - n, a - n with n = r (-uy, ux): negative signed area
    quad = np.stack([a + nv, b + nv, b - nv, a - nv], 1)
    for k in range(4):
        out[off + k, 0] = quad[:, k]
        out[off + k, 1] = quad[:, (k + 1) % 4]
    if len(i1):
        _put_triangles(out, off[i1] + 4, v, p1, p2)
        if w_j.any():
            bis = side[w_j] * (nv[i1][w_j] + nv[i2][w_j])
            bl = np.hypot(bis[:, 0], bis[:, 1])[:, None]
            tip = v[w_j] + bis / np.maximum(bl, 1e-300) * (r / half[w_j][:, None])
            _put_triangles(out, off[i1[w_j]] + 7, p1[w_j], tip, p2[w_j])
    return out, np.repeat(poly, cnt), dots


def _put_triangles(out, at, p, q, s):
    """Write the triangles (p, q, s) ((M, 2) each) as 3 edges each at
    ``out[at .. at + 2]``, turned to negative signed area."""
    flip = ((q[:, 0] - p[:, 0]) * (s[:, 1] - p[:, 1])
            - (q[:, 1] - p[:, 1]) * (s[:, 0] - p[:, 0])) > 0
    if flip.any():
        q, s = np.where(flip[:, None], s, q), np.where(flip[:, None], q, s)
    for k, (x, y) in enumerate(((p, q), (q, s), (s, p))):
        out[at + k, 0] = x
        out[at + k, 1] = y
