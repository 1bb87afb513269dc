"""Tests of raster.geometry.flattening.flatten_many: equal to per-path flatten."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st, HealthCheck

from raster import parse_path
from raster.errors import PathError, TransformError
from raster.geometry.flattening import flatten, flatten_many
from raster.geometry.path import Path
from raster.geometry.transform import Affine


def same(a, b):
    """Same polylines: identical structure, vertices equal up to float64
    rounding (flatten_beziers evaluates pieces with array products whose
    rounding depends on the batch size, ~1e-14 here)."""
    return (a.points.shape == b.points.shape and np.array_equal(a.starts, b.starts)
            and np.array_equal(a.closed, b.closed)
            and np.allclose(a.points, b.points, rtol=0, atol=1e-9))


def random_path(rng):
    """A path of a few contours mixing lines, quadratics, cubics, closes and
    lone moves."""
    parts = []
    for _ in range(rng.integers(0, 4)):
        parts.append('M %f %f' % tuple(rng.uniform(-50, 50, 2)))
        for _ in range(rng.integers(0, 5)):
            k = rng.integers(0, 3)
            pts = rng.uniform(-50, 50, 2 * (k + 1))
            parts.append('LQC'[k] + ' ' + ' '.join('%f' % v for v in pts))
        if rng.random() < 0.5:
            parts.append('Z')
    return parse_path(' '.join(parts)) if parts else Path.empty()


def random_affine(rng):
    if rng.random() < 0.3:
        return None
    if rng.random() < 0.2:
        return Affine.identity()
    return Affine(*rng.uniform(-3, 3, 6))


@pytest.mark.parametrize('seed', range(8))
def test_equals_per_path_flatten(seed):
    rng = np.random.default_rng(seed)
    paths = [random_path(rng) for _ in range(25)]
    ts = [random_affine(rng) for _ in paths]
    for tol in (0.05, 0.25, 2.0):
        got = flatten_many(paths, ts, tol)
        assert len(got) == len(paths)
        for p, t, g in zip(paths, ts, got):
            assert same(g, flatten(p, tol, transform=t))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1), st.integers(1, 12))
def test_batching_is_invisible(seed, n):
    """Splitting a batch anywhere gives the same polylines."""
    rng = np.random.default_rng(seed)
    paths = [random_path(rng) for _ in range(n)]
    ts = [random_affine(rng) for _ in paths]
    whole = flatten_many(paths, ts)
    k = int(rng.integers(0, n + 1))
    parts = flatten_many(paths[:k], ts[:k]) + flatten_many(paths[k:], ts[k:])
    assert all(same(a, b) for a, b in zip(whole, parts))


def test_circle_vertices_on_circle_within_tolerance():
    """Unit circle arcs scaled by 100: every vertex lies on the circle (up to
    the cubic's own error, 2.7e-4 radii) and every chord midpoint within
    the tolerance plus that error."""
    circ = parse_path('M 1 0 A 1 1 0 0 1 -1 0 A 1 1 0 0 1 1 0 Z')
    for tol in (0.01, 0.25, 1.0):
        pl, = flatten_many([circ], [Affine.scale(100)], tol)
        r = np.hypot(*pl.points.T)
        assert np.all(np.abs(r - 100) <= 0.03)
        mid = 0.5 * (pl.points + np.roll(pl.points, -1, axis=0))
        assert np.all(100 - np.hypot(*mid.T) <= tol + 0.03)


def test_empty_inputs():
    assert flatten_many([]) == []
    a, b = flatten_many([Path.empty(), parse_path('M 1 1')])
    assert len(a) == 0 and len(b) == 0 and len(a.points) == 0


def test_errors():
    sq = Path.polygon([[0, 0], [1, 0], [1, 1]])
    with pytest.raises(PathError):
        flatten_many([sq], [None, None])
    with pytest.raises(PathError):
        flatten_many(['M 0 0 L 1 1'])
    with pytest.raises(PathError):
        flatten_many([sq], [(1e308, 0, 0, 1e308, 1e308, 0)])
    with pytest.raises(PathError):
        flatten_many([sq], tolerance=0)
    with pytest.raises(TransformError):
        flatten_many([sq], [(1, 2, 3)])


@pytest.mark.parametrize('seed', range(4))
def test_joined_ranges_hold_each_paths_polylines(seed):
    from raster.geometry.flattening import flatten_joined
    rng = np.random.default_rng(50 + seed)
    paths = [random_path(rng) for _ in range(30)]
    ts = [random_affine(rng) for _ in paths]
    pl, first = flatten_joined(paths, ts, 0.25)
    assert first[0] == 0 and first[-1] == len(pl) and np.all(np.diff(first) >= 0)
    ends = pl.ends
    for i, (p, t) in enumerate(zip(paths, ts)):
        want = flatten(p, 0.25, transform=t)
        k0, k1 = first[i], first[i + 1]
        assert k1 - k0 == len(want)
        if k1 > k0:
            pts = pl.points[pl.starts[k0]:ends[k1 - 1]]
            assert np.allclose(pts, want.points, rtol=0, atol=1e-9)
            assert np.array_equal(pl.closed[k0:k1], want.closed)
            assert np.array_equal(pl.starts[k0:k1] - pl.starts[k0], want.starts)


def _line_paths(rng, n):
    out = []
    for _ in range(n):
        d = []
        for _ in range(int(rng.integers(0, 4))):
            k = int(rng.integers(0, 6))
            pts = rng.normal(0, 30, (k + 1, 2)).round(int(rng.integers(0, 3)))
            d.append('M%.17g %.17g' % tuple(pts[0])
                     + ''.join(' L%.17g %.17g' % tuple(p) for p in pts[1:]))
            if rng.random() < 0.5:
                d.append('Z')
        out.append(parse_path(' '.join(d)))
    return out


@pytest.mark.parametrize('straddle', [False, True])
@pytest.mark.parametrize('seed', range(12))
def test_joined_lines_equal_the_general_flattening(seed, straddle, monkeypatch):
    # paths of lines only take a short way (their points are the polylines):
    # the same polylines, bit for bit, as through the segment arrays
    from raster.geometry import flattening
    from raster.geometry.flattening import flatten_joined
    rng = np.random.default_rng(seed)
    paths = _line_paths(rng, int(rng.integers(1, 12)))
    ts = [None if rng.random() < 0.3 else Affine(*rng.normal(0, 2, 6)) for _ in paths]
    called = []
    fast = flattening._joined_lines

    def seen(*a):
        called.append(1)
        return fast(*a)
    monkeypatch.setattr(flattening, '_joined_lines', seen)
    got, first = flatten_joined(paths, ts, 0.1, straddle)
    assert called or sum(len(p.verbs) for p in paths) == 0
    monkeypatch.setattr(flattening, '_lines_only', lambda verbs: False)
    want, wfirst = flatten_joined(paths, ts, 0.1, straddle)
    if straddle:         # (straddling adds a zero shift: 0.0 for -0.0 at most)
        assert np.array_equal(got.points, want.points)
    else:
        assert got.points.tobytes() == want.points.tobytes()
    assert got.starts.tolist() == want.starts.tolist()
    assert got.closed.tolist() == want.closed.tolist()
    assert first.tolist() == wfirst.tolist()
    for i, p in enumerate(paths):                      # and each path on its own
        one = flatten(p, 0.1, transform=ts[i], straddle=straddle)
        sl = got.points[got.starts[first[i]]:] if first[i] < len(got.starts) else got.points[:0]
        assert len(one.points) == (0 if first[i] == first[i + 1] else
                                   (got.starts[first[i + 1]] if first[i + 1] < len(got.starts)
                                    else len(got.points)) - got.starts[first[i]])
        assert np.array_equal(sl[:len(one.points)], one.points)
