"""Hairline outlines: strokes thinner than one device pixel are drawn one
pixel wide (their coverage scaled by their width, as resvg does); this
outlines them from device-space polylines in one vectorized pass, without
offset curves.  Meant for :func:`raster.pixels.scan.coverage` with
``exact=False`` (the pieces' areas summed per pixel, clipped to 1)."""

import numpy as np

from ..geometry.rows import pairs

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
    drawn bevelled (at most 0.04 px^2 less per join).  The pieces have one
    orientation (negative signed area) and are meant for the nonzero rule;
    :func:`raster.pixels.scan.coverage` with ``exact=False`` sums their
    areas per pixel (clipped to 1), which counts the small overlaps of
    consecutive rectangles inside a turn twice, as a hairline renderer
    drawing one segment at a time does.

    The edges are not those of the separate pieces: where two pieces share
    an edge (a rectangle's end and its join triangle, a bevel and its miter
    triangle) the two copies run in opposite directions and cancel, so they
    are left out.  What remains is one closed outline per open polyline
    (two per closed one): the left offsets with the outer joins, the end
    cap, the right offsets back, the start cap; on the inner side of a turn
    the outline runs in to the vertex and out again.  The winding number,
    hence the coverage under either rule and either ``exact``, is that of
    the separate pieces (up to rounding), with 5 edges per segment (one
    more per miter) instead of 7 (10).  One vectorized pass for all
    polylines: no offset curves and no per-vertex Python work.

    Parameters
    ----------
    pl : raster.geometry.flattening.Polylines
        K polylines, device pixels.
    capped, mitered : (K,) bool ndarray
    miterlimit : (K,) float64 ndarray

    Returns
    -------
    edges : (E, 2, 2) float64 ndarray
        Polyline after polyline, each polyline's outline as closed loops of
        consecutive edges.
    owner : (E,) int64 ndarray
        The polyline of each edge (non-decreasing).
    dots : (K,) bool ndarray
        Capped polylines of one distinct point: they draw a dot, which
        this outline leaves out (the general stroker draws it).
    """
    r = 0.5
    # (rows of points are gathered and scattered as complex128 views,
    # several times faster than (N, 2) fancy indexing; the arithmetic is
    # done on float64 as before, so the edges are the same bit for bit)
    P = np.ascontiguousarray(pl.points, np.float64)
    n = len(P)
    K = len(pl)
    none = (np.zeros((0, 2, 2)), np.zeros(0, np.int64), np.zeros(K, bool))
    if n == 0:
        return none
    Pc = _pairs(P)
    starts, ends, closed = pl.starts, pl.ends, pl.closed
    nxt = np.arange(1, n + 1)
    nxt[ends - 1] = np.where(closed, starts, -1)
    a_idx = np.flatnonzero(nxt >= 0)
    ac, bc = Pc[a_idx], Pc[nxt[a_idx]]
    dc = bc - ac                                # (componentwise: b - a)
    d = _floats(dc)
    length = np.hypot(d[:, 0], d[:, 1])
    keep = length > 1e-9
    if not keep.all():
        ki = np.flatnonzero(keep)
        a_idx, ac, bc, dc, length = a_idx[ki], ac[ki], bc[ki], dc[ki], length[ki]
        d = _floats(dc)
    poly = np.searchsorted(starts, a_idx, side='right') - 1
    counts = np.bincount(poly, minlength=K)
    dots = capped & (counts == 0)
    S = len(ac)
    if S == 0:
        return none[0], none[1], dots
    u = d / length[:, None]
    nv = np.stack([-u[:, 1], u[:, 0]], 1) * r
    uc, nvc = _pairs(u), _pairs(nv)
    j = np.arange(S)
    first = np.ones(S, bool)
    first[1:] = poly[1:] != poly[:-1]
    last = np.ones(S, bool)
    last[:-1] = poly[1:] != poly[:-1]
    pclosed = closed[poly]
    op = capped[poly] & ~pclosed
    if op.any():
        # square (and round, drawn square) caps on open polylines
        ac = _pairs(_floats(ac) - (u * r) * (first & op)[:, None])
        bc = _pairs(_floats(bc) + (u * r) * (last & op)[:, None])
    # joins: each segment with the next one of its polyline (closed: wrap)
    head = np.maximum.accumulate(np.where(first, j, 0))
    nseg = np.where(~last, j + 1, np.where(pclosed, head, -1))
    has_join = nseg >= 0
    i1 = np.flatnonzero(has_join)
    i2 = nseg[i1]
    vc = Pc[nxt[a_idx[i1]]]
    u1, u2 = _floats(uc[i1]), _floats(uc[i2])
    cr = u1[:, 0] * u2[:, 1] - u1[:, 1] * u2[:, 0]
    outer_left = cr <= 0                        # the outer side is +n
    within = np.zeros(len(i1), bool)
    tipc = None
    if len(i1):
        # turning angle (the dot product as the sum of its two products)
        cos_t = np.minimum(np.maximum(u1[:, 0] * u2[:, 0] + u1[:, 1] * u2[:, 1], -1.0), 1.0)
        # miter length / stroke width = 1 / sin(phi / 2), phi the angle
        # between the segments = pi - turning angle: 1 / cos(turn / 2)
        half = np.sqrt(np.maximum((1.0 + cos_t) / 2.0, 0.0))
        pi1 = poly[i1]
        within = (mitered[pi1] & (half > 1e-12) & (1.0 <= miterlimit[pi1] * half)
                  & (cos_t < 1.0 - 1e-12))
        if within.any():
            w = np.flatnonzero(within)
            side = np.where(outer_left[w], 1.0, -1.0)[:, None]
            bis = side * _floats(nvc[i1[w]] + nvc[i2[w]])
            bl = np.hypot(bis[:, 0], bis[:, 1])[:, None]
            tip = _floats(vc[w]) + bis / np.maximum(bl, 1e-300) * (r / half[w][:, None])
            tipc = _pairs(tip)
    # vertices: per segment a block on the left chain (a + n, b + n, then
    # the join after it: the vertex itself when the turn's inside is on the
    # left, the miter tip when it is outside) and one on the right chain
    # (the join after it as seen from there, b - n, a - n); the right
    # chain runs backwards.  An open polyline is one loop (left chain,
    # right chain); a closed one two loops.
    xl = np.zeros(S, np.int64)
    xr = np.zeros(S, np.int64)
    xl[i1] = (~outer_left | within).astype(np.int64)
    xr[i1] = (outer_left | within).astype(np.int64)
    cl = 2 + xl
    cr_ = 2 + xr
    L = np.bincount(poly, weights=cl, minlength=K).astype(np.int64)
    R = np.bincount(poly, weights=cr_, minlength=K).astype(np.int64)
    tot = L + R
    vs = np.cumsum(tot) - tot                   # each polyline's first vertex
    ccl = np.cumsum(cl) - cl
    ccr = np.cumsum(cr_)                        # inclusive
    fs = np.flatnonzero(first)                  # first segment of each polyline
    pfirst = np.zeros(K, np.int64)
    pfirst[poly[fs]] = fs
    vsp = vs[poly]
    lo = vsp + ccl - ccl[pfirst[poly]]
    # right blocks in reverse segment order: after the blocks of the later
    # segments of the polyline
    seg_end = np.zeros(K, np.int64)
    seg_end[poly[last]] = ccr[last]
    ro = vsp + L[poly] + (seg_end[poly] - ccr)
    nvert = int(tot.sum())
    Vc = np.empty(nvert, np.complex128)
    Vc[lo] = ac + nvc                           # (componentwise sums)
    Vc[lo + 1] = bc + nvc
    rx = ro + xr
    Vc[rx] = bc - nvc
    Vc[rx + 1] = ac - nvc
    if len(i1):
        inner_l = np.flatnonzero(~outer_left)
        Vc[lo[i1[inner_l]] + 2] = vc[inner_l]
        inner_r = np.flatnonzero(outer_left)
        Vc[ro[i1[inner_r]]] = vc[inner_r]
        if tipc is not None:
            w = np.flatnonzero(within)
            tl = outer_left[w]
            Vc[lo[i1[w[tl]]] + 2] = tipc[tl]
            Vc[ro[i1[w[~tl]]]] = tipc[~tl]
    # edges: each vertex to the next one of its loop
    pk = closed & (counts > 0)
    loop_end = np.where(pk, vs + L, vs + tot)   # end of each polyline's first loop
    # (the next vertex is the following one but at the end of a loop,
    # where it is the loop's first)
    has = counts > 0
    oc = np.empty((nvert, 2), np.complex128)
    oc[:, 0] = Vc
    oc[:-1, 1] = Vc[1:]
    oc[-1:, 1] = Vc[:1]
    oc[loop_end[has] - 1, 1] = Vc[vs[has]]
    oc[(vs + tot)[pk] - 1, 1] = Vc[(vs + L)[pk]]
    return oc.view(np.float64).reshape(nvert, 2, 2), np.repeat(np.arange(K), tot), dots


def _pairs(a):
    """(N, 2) float64 as (N,) complex128 (a view when ``a`` is
    C-contiguous, else a copy): rows move as single elements."""
    c = pairs(a)
    return pairs(np.ascontiguousarray(a)) if c is None else c


def _floats(c):
    """(N,) complex128 as (N, 2) float64 (a view)."""
    return c.view(np.float64).reshape(-1, 2)
