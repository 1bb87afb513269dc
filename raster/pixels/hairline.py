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
    pclosed = closed[poly]
    op = capped[poly] & ~pclosed
    if op.any():
        # square (and round, drawn square) caps on open polylines
        a = a - (u * r) * (first & op)[:, None]
        b = b + (u * r) * (last & op)[:, None]
    # joins: each segment with the next one of its polyline (closed: wrap)
    head = np.maximum.accumulate(np.where(first, j, 0))
    nseg = np.where(~last, j + 1, np.where(pclosed, head, -1))
    has_join = nseg >= 0
    i1 = np.flatnonzero(has_join)
    i2 = nseg[i1]
    v = P[nxt[a_idx[i1]]]
    cr = u[i1, 0] * u[i2, 1] - u[i1, 1] * u[i2, 0]
    outer_left = cr <= 0                        # the outer side is +n
    within = np.zeros(len(i1), bool)
    tip = None
    if len(i1):
        cos_t = np.clip((u[i1] * u[i2]).sum(1), -1.0, 1.0)   # turning angle
        # miter length / stroke width = 1 / sin(phi / 2), phi the angle
        # between the segments = pi - turning angle: 1 / cos(turn / 2)
        half = np.sqrt(np.maximum((1.0 + cos_t) / 2.0, 0.0))
        within = (mitered[poly[i1]] & (half > 1e-12) & (1.0 <= miterlimit[poly[i1]] * half)
                  & (cos_t < 1.0 - 1e-12))
        if within.any():
            w = np.flatnonzero(within)
            side = np.where(outer_left[w], 1.0, -1.0)[:, None]
            bis = side * (nv[i1[w]] + nv[i2[w]])
            bl = np.hypot(bis[:, 0], bis[:, 1])[:, None]
            tip = v[w] + bis / np.maximum(bl, 1e-300) * (r / half[w][:, None])
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
    lo = vs[poly] + ccl - ccl[pfirst[poly]]
    # right blocks in reverse segment order: after the blocks of the later
    # segments of the polyline
    seg_end = np.zeros(K, np.int64)
    seg_end[poly[last]] = ccr[last]
    ro = vs[poly] + L[poly] + (seg_end[poly] - ccr)
    nvert = int(tot.sum())
    V = np.empty((nvert, 2))
    V[lo] = a + nv
    V[lo + 1] = b + nv
    V[ro + xr] = b - nv
    V[ro + xr + 1] = a - nv
    if len(i1):
        inner_l = np.flatnonzero(~outer_left)
        V[lo[i1[inner_l]] + 2] = v[inner_l]
        inner_r = np.flatnonzero(outer_left)
        V[ro[i1[inner_r]]] = v[inner_r]
        if tip is not None:
            w = np.flatnonzero(within)
            tl = outer_left[w]
            V[lo[i1[w[tl]]] + 2] = tip[tl]
            V[ro[i1[w[~tl]]]] = tip[~tl]
    # edges: each vertex to the next one of its loop
    pk = closed & (counts > 0)
    loop_end = np.where(pk, vs + L, vs + tot)   # end of each polyline's first loop
    # (the next vertex is the following one but at the end of a loop,
    # where it is the loop's first)
    has = counts > 0
    out = np.empty((nvert, 2, 2))
    out[:, 0] = V
    out[:-1, 1] = V[1:]
    out[-1:, 1] = V[:1]
    out[loop_end[has] - 1, 1] = V[vs[has]]
    out[(vs + tot)[pk] - 1, 1] = V[(vs + L)[pk]]
    return out, np.repeat(np.arange(K), tot), dots
