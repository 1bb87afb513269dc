"""Hairline outlines (raster.pixels.hairline): the joined outline has the
winding number of the union of its pieces (segment rectangles, bevel and
miter triangles, square caps), checked against those pieces built one by
one here."""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.geometry.flattening import Polylines
from raster.pixels.hairline import hairline_outline
from raster.pixels.scan import coverage

R = 0.5


def _pieces(points, closed, capped, mitered, limit):
    """The separate pieces of one polyline's hairline, as closed polygons
    (lists of vertices, negative signed area), one Python step per segment
    (a reference, not the fast path)."""
    pts = [np.asarray(p, float) for p in points]
    segs = [(pts[i], pts[i + 1]) for i in range(len(pts) - 1)]
    if closed:
        segs.append((pts[-1], pts[0]))
    segs = [(p, q) for p, q in segs if math.hypot(*(q - p)) > 1e-9]
    out = []
    if not segs:
        return out
    us = [(q - p) / math.hypot(*(q - p)) for p, q in segs]
    ns = [R * np.array([-u[1], u[0]]) for u in us]
    m = len(segs)
    for i, ((p, q), u, nv) in enumerate(zip(segs, us, ns)):
        if capped and not closed:
            if i == 0:
                p = p - u * R
            if i == m - 1:
                q = q + u * R
        out.append([p + nv, q + nv, q - nv, p - nv])
    joins = [(i, i + 1) for i in range(m - 1)] + ([(m - 1, 0)] if closed else [])
    for i, k in joins:
        v = segs[i][1]
        cr = us[i][0] * us[k][1] - us[i][1] * us[k][0]
        side = -1.0 if cr > 0 else 1.0
        p1, p2 = v + side * ns[i], v + side * ns[k]
        out.append(_negative([v, p1, p2]))
        cos_t = min(1.0, max(-1.0, float(us[i] @ us[k])))
        half = math.sqrt(max((1.0 + cos_t) / 2.0, 0.0))
        if mitered and half > 1e-12 and 1.0 <= limit * half and cos_t < 1.0 - 1e-12:
            bis = side * (ns[i] + ns[k])
            tip = v + bis / max(math.hypot(*bis), 1e-300) * (R / half)
            out.append(_negative([p1, tip, p2]))
    return out


def _negative(tri):
    (px, py), (qx, qy), (sx, sy) = tri
    if (qx - px) * (sy - py) - (qy - py) * (sx - px) > 0:
        return [tri[0], tri[2], tri[1]]
    return tri


def _edges(polygons):
    e = [[poly[k], poly[(k + 1) % len(poly)]] for poly in polygons for k in range(len(poly))]
    return np.array(e, float).reshape(-1, 2, 2)


def _polylines(rng, k):
    pts, starts, closed = [], [], []
    for _ in range(k):
        starts.append(len(pts))
        n = int(rng.integers(1, 9))
        walk = rng.uniform(4, 28, 2) + np.cumsum(rng.normal(0, 2.5, (n, 2)), 0)
        if n > 2 and rng.random() < 0.3:
            walk[2] = walk[1]                                   # a zero-length segment
        if n > 3 and rng.random() < 0.3:
            walk[3] = walk[1] + 1e-3 * (walk[3] - walk[1])      # a U-turn
        pts.extend(np.clip(walk, 1, 31).tolist())
        closed.append(bool(rng.random() < 0.5))
    return Polylines(pts, starts, closed)


@pytest.mark.parametrize('seed', range(12))
@pytest.mark.parametrize('exact', [False, True])
def test_outline_has_the_winding_of_its_pieces(seed, exact):
    """Invariance: coverage of the joined outline equals coverage of the
    separate pieces, summed (exact=False) and as their union (exact=True)."""
    rng = np.random.default_rng(seed)
    pl = _polylines(rng, 4)
    capped = rng.random(len(pl)) < 0.5
    mitered = rng.random(len(pl)) < 0.5
    limit = rng.uniform(1.0, 6.0, len(pl))
    e, own, dots = hairline_outline(pl, capped, mitered, limit)
    ref = []
    for i, (p, c) in enumerate(pl):
        ref += _pieces(p, c, capped[i], mitered[i], limit[i])
    if not ref:
        assert len(e) == 0
        return
    a = coverage(e, 32, 32, exact=exact)
    b = coverage(_edges(ref), 32, 32, exact=exact)
    fa = a.full(32, 32) if a is not None else np.zeros((32, 32), np.float32)
    fb = b.full(32, 32) if b is not None else np.zeros((32, 32), np.float32)
    assert np.abs(fa - fb).max() < 1e-5
    assert np.all(np.diff(own) >= 0)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2 ** 32 - 1), st.booleans(), st.booleans())
def test_outline_is_closed_loops_of_fewer_edges(seed, capped, mitered):
    """Every edge ends where the next one of its loop starts (each
    polyline's outline is closed), and the outline has at most 5 edges per
    segment plus 1 per miter join (the pieces: 7 and 3 more)."""
    rng = np.random.default_rng(seed)
    pl = _polylines(rng, 3)
    k = len(pl)
    e, own, _ = hairline_outline(pl, np.full(k, capped), np.full(k, mitered), np.full(k, 4.0))
    ref = []
    for p, c in pl:
        ref += _pieces(p, c, capped, mitered, 4.0)
    n_ref = sum(len(p) for p in ref)
    assert len(e) <= n_ref
    # per polyline, the end points and start points are the same multiset
    for i in range(k):
        mine = e[own == i]
        s = sorted(map(tuple, mine[:, 0].tolist()))
        t = sorted(map(tuple, mine[:, 1].tolist()))
        assert s == t


def test_straight_run_outline_is_its_rectangle_with_inner_spikes():
    """A straight open polyline of 3 collinear segments (x = 2..8 at
    y = 5): coverage is the 6 x 1 rectangle; rows 4 and 5 half covered."""
    pl = Polylines([[2, 5], [4, 5], [6, 5], [8, 5]], [0], [False])
    e, _, _ = hairline_outline(pl, np.array([False]), np.array([False]), np.array([4.0]))
    m = coverage(e, 10, 10, exact=False).full(10, 10)
    want = np.zeros((10, 10), np.float32)
    want[4:6, 2:8] = 0.5
    assert np.abs(m - want).max() < 1e-6
    assert len(e) == 3 * 5 - 1
