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


# -- contours repeated up to a translation (text, markers) -------------------

def _copies(rng, bases, n, hair=0.0):
    """``n`` contours, each a base contour (``M`` and curves, closed or
    not) moved by a random translation with a fraction part; with ``hair``
    every third copy has one control point moved by that much or more.  Returns
    the path and, per contour, its base (-1: moved by a hair)."""
    parts, base_of = [], []
    for i in range(n):
        b = int(rng.integers(len(bases)))
        pts, closed = bases[b]
        off = rng.uniform(-400, 400, 2)
        q = pts + off
        moved = hair and i % 3 == 1
        if moved:
            q = q.copy()
            # (by a different amount each: no two of them are translates)
            q[1 + int(rng.integers(len(q) - 1))] += hair * (1 + i)
        d = 'M%.17g %.17g' % tuple(q[0]) + ''.join(
            ' C%.17g %.17g %.17g %.17g %.17g %.17g' % tuple(q[1 + 3 * k:4 + 3 * k].ravel())
            for k in range((len(q) - 1) // 3))
        parts.append(d + (' Z' if closed else ''))
        base_of.append(-1 if moved else b)
    return parse_path(' '.join(parts)), base_of


def _bases(rng, k):
    out = []
    for _ in range(k):
        m = int(rng.integers(1, 4))
        out.append((rng.uniform(-20, 20, (1 + 3 * m, 2)), bool(rng.random() < 0.5)))
    return out


@pytest.mark.parametrize('seed', range(4))
@pytest.mark.parametrize('collide', [False, True])
def test_repeated_contours_are_translates(seed, collide, monkeypatch):
    # copies of a few contours at random offsets are found (the first copy
    # of each base stands for the others); copies with a control point
    # moved by 1e-3 px stand for themselves; with every hash the same
    # (collide), the point by point check alone tells them apart
    from raster.geometry import flattening
    from raster.geometry.path import segment_arrays
    rng = np.random.default_rng(seed)
    bases = _bases(rng, 5)
    path, base_of = _copies(rng, bases, 120, hair=1e-3)
    if collide:
        monkeypatch.setattr(flattening, '_mix64', lambda x: x * np.uint64(0))
    seg = segment_arrays(path.verbs, path.points)
    rep = flattening.repeated_contours(seg.ctrl, seg.contour_start, seg.degree, seg.contour,
                                       seg.contour_nseg, seg.contour_closed)
    assert np.all(rep[rep] == rep) and np.all(rep <= np.arange(len(rep)))
    if collide:
        # every hash equal: the first contour stands for its own copies,
        # the point by point check leaves every other contour to itself
        b0 = base_of[0]
        want = [0 if b0 >= 0 and b == b0 else c for c, b in enumerate(base_of)]
        assert rep.tolist() == want
        return
    first = {}
    for c, b in enumerate(base_of):
        if b < 0:
            assert rep[c] == c
        else:
            first.setdefault(b, c)
            assert rep[c] == first[b]


def spy_assemble(monkeypatch):
    """Record the number of contours of every flattening of distinct
    contours (flattening._assemble); returns the list it fills."""
    from raster.geometry import flattening
    sizes = []
    real = flattening._assemble

    def spy(ctrl, cstart, *a, **k):
        sizes.append(len(cstart))
        return real(ctrl, cstart, *a, **k)
    monkeypatch.setattr(flattening, '_assemble', spy)
    return sizes


@pytest.mark.parametrize('straddle', [False, True])
@pytest.mark.parametrize('seed', range(3))
def test_repeated_contours_flattened_once_and_moved(seed, straddle, monkeypatch):
    # a batch of many copies: the distinct contours alone are flattened,
    # and every polyline is the one flattening each path alone gives
    # (within the grid of REPEAT_GRID and rounding), same structure
    from raster.geometry import flattening
    from raster.geometry.flattening import REPEAT_GRID, flatten_joined
    rng = np.random.default_rng(80 + seed)
    bases = _bases(rng, 4)
    paths = []
    for _ in range(40):
        p, _ = _copies(rng, bases, int(rng.integers(1, 6)))
        paths.append(p)
    ts = [Affine(1.5, 0.3, -0.2, 1.1, 7.25, -3.5) if i % 2 else None
          for i in range(len(paths))]
    real = flattening._assemble
    sizes = spy_assemble(monkeypatch)
    pl, first = flatten_joined(paths, ts, 0.1, straddle)
    total = sum(int(np.count_nonzero(p.verbs == 0)) for p in paths)
    assert total >= flattening.REPEAT_MIN_CONTOURS and sizes == [8]   # 4 bases, 2 transforms
    monkeypatch.setattr(flattening, '_assemble', real)
    for i, (p, t) in enumerate(zip(paths, ts)):
        want = flatten(p, 0.1, transform=t, straddle=straddle)
        k0, k1 = first[i], first[i + 1]
        assert k1 - k0 == len(want)
        pts = pl.points[pl.starts[k0]:pl.ends[k1 - 1]]
        assert np.allclose(pts, want.points, rtol=0, atol=2 * REPEAT_GRID)
        assert np.array_equal(pl.closed[k0:k1], want.closed)
        assert np.array_equal(pl.starts[k0:k1] - pl.starts[k0], want.starts)
    # without repeats enough to pay, everything is flattened as before
    sizes = spy_assemble(monkeypatch)
    flatten_joined(paths[:3], ts[:3], 0.1, straddle)
    assert sizes == [sum(int(np.count_nonzero(p.verbs == 0)) for p in paths[:3])]


def test_repeated_symbols_render_as_without_sharing(monkeypatch):
    # 300 copies of a curved symbol at fractional offsets: the same pixels
    # with the sharing as with every contour flattened (within one level)
    import raster
    from raster.geometry import flattening
    rng = np.random.default_rng(5)
    xy = rng.uniform(0, 190, (300, 2))
    uses = ''.join('<use href="#s" x="%.6f" y="%.6f"/>' % tuple(p) for p in xy)
    doc = ('<svg xmlns="http://www.w3.org/2000/svg" width="200" height="200"><defs>'
           '<path id="s" d="M0 0C3 -2 6 4 9 1Q5 8 0 0Z"/></defs>%s</svg>' % uses).encode()
    shared = raster.render(doc).astype(int)
    monkeypatch.setattr(flattening, 'REPEAT_MIN_CONTOURS', 10**9)
    alone = raster.render(doc).astype(int)
    assert np.abs(shared - alone).max() <= 1


@pytest.mark.parametrize('collide', [False, True])
def test_contour_cache_carries_contours_from_call_to_call(collide, monkeypatch):
    # a second call with the same shapes elsewhere flattens nothing new and
    # gives each path's own flattening within the grid; with every hash the
    # same (collide) the stored points tell contours apart
    from raster.geometry import flattening
    from raster.geometry.flattening import REPEAT_GRID, ContourCache, flatten_joined
    if collide:
        monkeypatch.setattr(flattening, '_mix64', lambda x: x * np.uint64(0))
    rng = np.random.default_rng(11)
    bases = _bases(rng, 6)

    def batch(k):
        return [_copies(rng, bases, k)[0] for _ in range(20)]
    real = flattening._assemble
    flattened = spy_assemble(monkeypatch)
    cache = ContourCache()
    first = batch(5)
    flatten_joined(first, None, 0.1, True, cache=cache)
    # (colliding hashes: the point by point check leaves most contours to
    # themselves, too many to share: all flattened, as without a cache)
    assert (sum(flattened) <= 6 and len(cache) == sum(flattened)) or collide
    flattened.clear()
    second = batch(4)
    pl, starts = flatten_joined(second, None, 0.1, True, cache=cache)
    # (with colliding hashes one key holds one contour at a time: the
    # others are flattened again, never taken for it)
    assert sum(flattened) == 0 or collide
    monkeypatch.setattr(flattening, '_assemble', real)
    for i, p in enumerate(second):
        want = flatten(p, 0.1, straddle=True)
        k0, k1 = starts[i], starts[i + 1]
        assert k1 - k0 == len(want)
        got = pl.points[pl.starts[k0]:pl.ends[k1 - 1]]
        assert np.allclose(got, want.points, rtol=0, atol=2 * REPEAT_GRID)
        assert np.array_equal(pl.starts[k0:k1] - pl.starts[k0], want.starts)
    # a different tolerance or straddling takes nothing from the cache
    flattened = spy_assemble(monkeypatch)
    flatten_joined(second, None, 0.2, True, cache=cache)
    flatten_joined(second, None, 0.1, False, cache=cache)
    assert len(flattened) == 2 and min(flattened) > 0


def test_contour_cache_is_bounded():
    from raster.geometry.flattening import ContourCache
    c = ContourCache(max_bytes=200)                   # polylines of 16 bytes a vertex
    c.put('a', b'1', np.zeros((6, 2)), True)          # 97 bytes
    c.put('b', b'2', np.zeros((3, 2)), True)          # 49
    assert len(c) == 2 and c.get('a', b'1')[1] is True
    assert c.get('a', b'x') is None                   # another contour under that key
    c.put('a', b'1', np.zeros((6, 2)), True)          # the same again: still 146 bytes
    assert len(c) == 2
    c.put('c', b'3', np.zeros((4, 2)), True)          # 65 more: over, starts afresh
    assert len(c) == 1 and c.get('a', b'1') is None and c.get('c', b'3') is not None
    c.put('d', b'4', np.zeros((13, 2)), True)         # larger than the bound: not kept
    assert c.get('d', b'4') is None


def test_contour_cache_checks_points_behind_a_shared_key(monkeypatch):
    # every hash the same: the copies of one shape fill the cache under one
    # key; copies of another shape then meet that key, are told apart by
    # their points and flattened, not drawn as the first shape
    from raster.geometry import flattening
    from raster.geometry.flattening import REPEAT_GRID, ContourCache, flatten_joined
    monkeypatch.setattr(flattening, '_mix64', lambda x: x * np.uint64(0))
    rng = np.random.default_rng(12)
    a, b = _bases(rng, 2)
    cache = ContourCache()
    flatten_joined([_copies(rng, [a], 70)[0]], None, 0.1, True, cache=cache)
    assert len(cache) == 1
    other, _ = _copies(rng, [b], 70)
    pl, _ = flatten_joined([other], None, 0.1, True, cache=cache)
    want = flatten(other, 0.1, straddle=True)
    assert np.array_equal(pl.starts, want.starts)
    assert np.allclose(pl.points, want.points, rtol=0, atol=2 * REPEAT_GRID)


def test_repeated_contours_beyond_the_coordinate_limit_are_refused():
    # many copies far out: the coordinate limit, as without the sharing,
    # and no warning from the rounding of the quick look
    import warnings
    from raster import limits as lim
    from raster.errors import LimitError
    from raster.geometry.flattening import ContourCache, flatten_joined
    d = ' '.join('M%r 0 C%r 1 %r 2 %r 0 Z' % (x, x + 1, x + 2, x + 3)
                 for x in (np.arange(100) * 1e12).tolist())
    with warnings.catch_warnings():
        warnings.simplefilter('error')
        with pytest.raises(LimitError, match='max_coord'):
            flatten_joined([parse_path(d)], None, 0.1, True, cache=ContourCache())
    assert lim.current().max_coord == 1e9
