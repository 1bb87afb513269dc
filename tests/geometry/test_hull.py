"""Tests of raster.geometry.hull.convex_hull."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.spatial import ConvexHull

from raster.errors import PathError
from raster.geometry.hull import convex_hull


def signed_area(H):
    x, y = H[:, 0], H[:, 1]
    return 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)


def check_hull(P, H):
    P = np.asarray(P, float)
    # vertices are input points
    pts = {tuple(p) for p in P.tolist()}
    assert all(tuple(h) in pts for h in H.tolist())
    assert len({tuple(h) for h in H.tolist()}) == len(H)
    if len(H) >= 3:
        A, B = H, np.roll(H, -1, axis=0)
        e = B - A
        # strict left turns at every vertex (no collinear vertices), CCW y-up
        C = np.roll(e, -1, axis=0)
        assert np.all(e[:, 0] * C[:, 1] - e[:, 1] * C[:, 0] > 0)
        assert signed_area(H) > 0
        # every point is on the inner side of every edge
        cross = (e[:, None, 0] * (P[None, :, 1] - A[:, None, 1])
                 - e[:, None, 1] * (P[None, :, 0] - A[:, None, 0]))
        scale = np.abs(P).max() ** 2 + 1
        assert cross.min() >= -1e-12 * scale
        # starts at the lexicographically smallest point
        assert tuple(H[0]) == min(pts)


def test_square_with_interior_and_edge_points():
    P = [[0, 0], [1, 0], [2, 0], [2, 1], [2, 2], [1, 2], [0, 2], [0, 1], [1, 1], [0.5, 0.5]]
    H = convex_hull(P)
    assert H.tolist() == [[0, 0], [2, 0], [2, 2], [0, 2]]
    assert signed_area(H) == 4.0


def test_triangle():
    H = convex_hull([[3, 1], [0, 0], [1, 2], [1.5, 1], [3, 1]])
    assert H.tolist() == [[0, 0], [3, 1], [1, 2]]
    assert signed_area(H) == pytest.approx(2.5)   # |(3,1) x (1,2)| / 2


def test_small_and_degenerate_inputs():
    assert convex_hull([]).shape == (0, 2)
    assert convex_hull(np.zeros((0, 2))).shape == (0, 2)
    assert convex_hull([[1, 2]]).tolist() == [[1, 2]]
    assert convex_hull([[1, 2], [1, 2], [1, 2]]).tolist() == [[1, 2]]
    assert convex_hull([[3, 4], [1, 2]]).tolist() == [[1, 2], [3, 4]]
    # collinear: the two extreme points
    t = np.arange(65) / 64          # dyadic: exactly collinear in floating point
    assert convex_hull(np.c_[t * 2, t * 3 + 1][::-1]).tolist() == [[0, 1], [2, 4]]
    assert convex_hull(np.c_[np.zeros(100), np.arange(100)]).tolist() == [[0, 0], [0, 99]]


def test_duplicates():
    rng = np.random.default_rng(0)
    P = rng.integers(0, 5, (300, 2)).astype(float)
    H = convex_hull(P)
    check_hull(P, H)
    assert H.tolist() == [[0, 0], [4, 0], [4, 4], [0, 4]]


@pytest.mark.parametrize('kind', ['square', 'normal', 'circle', 'integer-grid'])
def test_matches_scipy(kind):
    rng = np.random.default_rng(1)
    if kind == 'square':
        P = rng.uniform(-100, 100, (20000, 2))
    elif kind == 'normal':
        P = rng.normal(size=(20000, 2)) * [3, 1]
    elif kind == 'circle':
        a = rng.uniform(0, 2 * np.pi, 3000)
        P = np.c_[np.cos(a), np.sin(a)] * 50 + rng.uniform(-1e-3, 1e-3, (3000, 2))
    else:
        P = rng.integers(-30, 30, (5000, 2)).astype(float)
    H = convex_hull(P)
    check_hull(P, H)
    ref = {tuple(p) for p in P[ConvexHull(P).vertices].tolist()}
    assert {tuple(h) for h in H.tolist()} == ref


@settings(max_examples=150, deadline=None)
@given(st.lists(st.tuples(st.integers(-50, 50), st.integers(-50, 50)), min_size=0, max_size=120))
def test_hull_properties_random_integer_points(pts):
    P = np.array(pts, float).reshape(-1, 2)
    H = convex_hull(P)
    check_hull(P, H)
    # invariance: hull of the hull is the hull; order of input does not matter
    assert np.array_equal(convex_hull(H), H)
    assert np.array_equal(convex_hull(P[::-1]), H)
    if len(np.unique(P, axis=0)) >= 3 and len(H) >= 3:
        ref = {tuple(p) for p in P[ConvexHull(P).vertices].tolist()}
        assert {tuple(h) for h in H.tolist()} == ref


def test_translation_and_mirror():
    rng = np.random.default_rng(2)
    P = rng.integers(0, 1000, (500, 2)).astype(float)
    H = convex_hull(P)
    assert np.array_equal(convex_hull(P + [64, -128]), H + [64, -128])
    # mirroring x flips orientation; the hull as a set is mirrored
    Hm = convex_hull(P * [-1, 1])
    assert {tuple(h) for h in Hm.tolist()} == {tuple(h) for h in (H * [-1, 1]).tolist()}


@pytest.mark.parametrize('bad', [[[0, np.nan]], [[np.inf, 0], [1, 1]], [[1, 2, 3]],
                                 [['a', 'b']], np.zeros((3, 3))])
def test_bad_input(bad):
    with pytest.raises(PathError):
        convex_hull(bad)


def test_sequential_fallback_agrees(monkeypatch):
    import raster.geometry.hull as hull
    rng = np.random.default_rng(3)
    P = rng.normal(size=(3000, 2))
    H = convex_hull(P)
    monkeypatch.setattr(hull, '_MAX_PASSES', 1)
    assert np.array_equal(convex_hull(P), H)
    a = np.linspace(0, 2 * np.pi, 500, endpoint=False)
    C = np.c_[np.cos(a), np.sin(a)]
    H2 = convex_hull(C)
    check_hull(C, H2)
    assert len(H2) == 500
