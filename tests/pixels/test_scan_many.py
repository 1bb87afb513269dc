"""Tests of raster.pixels.scan.coverage_many: identical to per-shape coverage."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st, HealthCheck

from raster.errors import CanvasError, LimitError, PathError
from raster.pixels.scan import coverage, coverage_many


def polygon_edges(pts):
    pts = np.asarray(pts, float)
    return np.stack([pts, np.roll(pts, -1, axis=0)], axis=1)


def random_shapes(rng, n, size=100):
    """Random polygons (self-intersecting ones included), some partly or
    wholly off canvas, some tiny, some with several contours."""
    out = []
    for _ in range(n):
        parts = []
        for _ in range(rng.integers(1, 3)):
            k = rng.integers(3, 12)
            c = rng.uniform(-0.2 * size, 1.2 * size, 2)
            r = rng.uniform(0.2, 0.3 * size)
            parts.append(polygon_edges(c + rng.uniform(-r, r, (k, 2))))
        out.append(np.concatenate(parts))
    return out


def same(a, b):
    if a is None or b is None:
        return a is None and b is None
    return a.box == b.box and np.array_equal(a.data, b.data)


@pytest.mark.parametrize('seed', range(6))
def test_identical_to_coverage_on_random_polygons(seed):
    rng = np.random.default_rng(seed)
    shapes = random_shapes(rng, 150)
    rules = [('nonzero', 'evenodd')[int(b)] for b in rng.random(len(shapes)) < 0.5]
    got = coverage_many(shapes, 100, 90, rules)
    assert len(got) == len(shapes)
    assert all(same(g, coverage(e, 100, 90, r)) for e, r, g in zip(shapes, rules, got))


def test_identical_on_suite_like_scene():
    """A map-like scene: a grid of adjacent cells sharing edges (like county
    outlines), circles (scatter marks) and a large background."""
    shapes = []
    for i in range(12):
        for j in range(10):
            x, y = 5 + 15.3 * i, 4 + 17.1 * j
            shapes.append(polygon_edges([[x, y], [x + 15.3, y + 0.7], [x + 15.0, y + 17.1],
                                         [x - 0.4, y + 16.8]]))
    th = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    rng = np.random.default_rng(7)
    for c in rng.uniform(0, 200, (60, 2)):
        shapes.append(polygon_edges(c + 2.5 * np.stack([np.cos(th), np.sin(th)], 1)))
    shapes.append(polygon_edges([[-10, -10], [210, -10], [210, 210], [-10, 210]]))
    got = coverage_many(shapes, 200, 200)
    assert all(same(g, coverage(e, 200, 200)) for e, g in zip(shapes, got))


def test_unit_square_and_disc_areas():
    """Analytic areas: an axis-aligned 7.5 x 3.25 rectangle, a disc of
    radius 20 (polygon of 720 sides: area r^2 * 360 sin(pi / 360) * 2)."""
    rect = polygon_edges([[1.25, 2.5], [8.75, 2.5], [8.75, 5.75], [1.25, 5.75]])
    th = np.linspace(0, 2 * np.pi, 720, endpoint=False)
    disc = polygon_edges(np.stack([50 + 20 * np.cos(th), 50 + 20 * np.sin(th)], 1))
    a, b = coverage_many([rect, disc], 100, 100)
    assert float(a.data.sum(dtype=np.float64)) == pytest.approx(7.5 * 3.25, abs=1e-5)
    poly_area = 0.5 * 720 * 400 * np.sin(2 * np.pi / 720)
    assert float(b.data.sum(dtype=np.float64)) == pytest.approx(poly_area, abs=1e-3)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1), st.integers(1, 20), st.booleans())
def test_order_and_grouping_invariance(seed, n, evenodd):
    """Shapes give the same masks alone, in a batch, or in reversed order."""
    rng = np.random.default_rng(seed)
    shapes = random_shapes(rng, n, 40)
    rule = 'evenodd' if evenodd else 'nonzero'
    got = coverage_many(shapes, 40, 40, rule)
    rev = coverage_many(shapes[::-1], 40, 40, rule)[::-1]
    for e, g, r in zip(shapes, got, rev):
        assert same(g, r) and same(g, coverage(e, 40, 40, rule))


def test_translation_invariance():
    """Moving every shape by whole pixels moves each mask and keeps its data."""
    rng = np.random.default_rng(3)
    shapes = random_shapes(rng, 30, 60)
    shapes = [np.clip(e, 1, 59) for e in shapes]
    a = coverage_many(shapes, 100, 100)
    b = coverage_many([e + [17, 9] for e in shapes], 100, 100)
    for m, k in zip(a, b):
        assert (m is None) == (k is None)
        if m is not None:
            assert k.box == (m.x0 + 17, m.y0 + 9, m.box[2] + 17, m.box[3] + 9)
            assert np.allclose(m.data, k.data, atol=1e-6)


def test_aliased_clip_and_empty_shapes():
    rng = np.random.default_rng(11)
    shapes = random_shapes(rng, 20, 50) + [np.zeros((0, 2, 2))]
    aas = [bool(b) for b in rng.random(len(shapes)) < 0.7]
    got = coverage_many(shapes, 50, 50, 'nonzero', aas, clip=(5, 5, 40, 45))
    for e, a, g in zip(shapes, aas, got):
        assert same(g, coverage(e, 50, 50, 'nonzero', a, clip=(5, 5, 40, 45)))
    assert got[-1] is None and coverage_many([], 10, 10) == []


def test_errors():
    sq = polygon_edges([[0, 0], [1, 0], [1, 1]])
    with pytest.raises(PathError):
        coverage_many([sq], 10, 10, 'winding')
    with pytest.raises(PathError):
        coverage_many([sq, sq], 10, 10, ['nonzero'])
    with pytest.raises(PathError):
        coverage_many([sq, [[np.nan, 0], [1, 1]]], 10, 10)
    with pytest.raises(LimitError):
        coverage_many([sq * 1e12], 10, 10)
    with pytest.raises(CanvasError):
        coverage_many([sq], 0, 10)


def test_small_batches_and_large_shapes(monkeypatch):
    """With a tiny piece budget the shapes are cut into many batches and the
    large ones drawn alone: the masks do not change."""
    import raster.pixels.scan as scan
    rng = np.random.default_rng(5)
    shapes = random_shapes(rng, 40, 80)
    ref = [coverage(e, 80, 80) for e in shapes]
    monkeypatch.setattr(scan, '_CHUNK_PIECES', 120)
    monkeypatch.setattr(scan, '_BATCH_PIECES', 120)
    got = coverage_many(shapes, 80, 80)
    assert all(same(g, r) for g, r in zip(got, ref))
    # sub-batches smaller than the size above which a shape goes alone
    monkeypatch.setattr(scan, '_BATCH_PIECES', 50)
    got = coverage_many(shapes, 80, 80)
    assert all(same(g, r) for g, r in zip(got, ref))


def test_zero_area_shape_with_flagged_cells():
    """A zigzag traced there and back (zero area, its cell flagged for the
    exact recompute but without cover terms) must not leak into the next
    shape's mask; alone or first in a batch it draws nothing."""
    z = np.array([[3.2, 3.2], [3.8, 3.5], [3.2, 3.8], [3.8, 3.9]])
    zig = np.concatenate([np.stack([z[:-1], z[1:]], 1), np.stack([z[:0:-1], z[-2::-1]], 1)])
    sq = polygon_edges([[2.5, 2.5], [6.5, 2.5], [6.5, 6.5], [2.5, 6.5]])
    for shapes in ([zig, sq], [zig], [sq, zig, sq], [zig, zig + 1, sq, zig, sq + 1, zig + 2],
                   [sq, zig, zig + 1]):
        got = coverage_many(shapes, 10, 10)
        assert all(same(g, coverage(e, 10, 10)) for e, g in zip(shapes, got))
    assert coverage_many([zig], 10, 10) == [None]


# -- coverage_batch and exact=False ------------------------------------------

from raster.errors import PathError as _PathError  # noqa: E402
from raster.pixels.scan import coverage_batch  # noqa: E402


@pytest.mark.parametrize('seed', range(4))
def test_batch_equals_many_with_mixed_flags(seed):
    rng = np.random.default_rng(100 + seed)
    shapes = random_shapes(rng, 30, 60) + [np.zeros((0, 2, 2))]
    rng.shuffle(shapes)
    n = len(shapes)
    rules = [('evenodd' if b else 'nonzero') for b in rng.random(n) < 0.4]
    aas = [bool(b) for b in rng.random(n) < 0.8]
    ex = [bool(b) for b in rng.random(n) < 0.5]
    counts = [len(s) for s in shapes]
    got = coverage_batch(np.concatenate(shapes), counts, 60, 50, rules, aas, exact=ex)
    many = coverage_many(shapes, 60, 50, rules, aas, exact=ex)
    for s, r, a, x, g, m in zip(shapes, rules, aas, ex, got, many):
        want = coverage(s, 60, 50, r, a, exact=x)
        assert same(g, want) and same(m, want)


def clockwise_square(x0, y0, size):
    pts = np.array([[x0, y0], [x0, y0 + size], [x0 + size, y0 + size], [x0 + size, y0]])
    return polygon_edges(pts)


def test_inexact_coverage_is_the_clipped_sum_of_piece_areas():
    # two squares of one orientation inside pixel (1, 1), overlapping in
    # [1.5, 1.75]^2: union 0.25 + 0.16 - 0.0625, sum 0.41
    e = np.concatenate([clockwise_square(1.25, 1.25, 0.5), clockwise_square(1.5, 1.5, 0.4)])
    exact = coverage(e, 4, 4).full(4, 4)
    rough = coverage(e, 4, 4, exact=False).full(4, 4)
    assert np.isclose(exact[1, 1], 0.3475) and np.isclose(rough[1, 1], 0.41)
    # a pixel covered twice over is clipped to 1
    big = np.concatenate([clockwise_square(0, 0, 3), clockwise_square(0.5, 0.5, 2)])
    r = coverage(big, 4, 4, exact=False).full(4, 4)
    assert np.allclose(r, coverage(big, 4, 4).full(4, 4))
    assert np.allclose(r[:3, :3], 1.0)


def test_inexact_equals_exact_without_meeting_chains():
    rng = np.random.default_rng(5)
    for _ in range(5):
        c = rng.uniform(5, 35, 2)
        ang = np.sort(rng.uniform(0, 2 * np.pi, 12))
        pts = c + np.stack([np.cos(ang), np.sin(ang)], 1) * rng.uniform(3, 10)
        e = polygon_edges(pts)              # a convex polygon: one chain per pixel
        a, b = coverage(e, 40, 40), coverage(e, 40, 40, exact=False)
        assert a.box == b.box and np.allclose(a.data, b.data, atol=1e-6)


def test_batch_count_errors():
    sq = polygon_edges(np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]]))
    with pytest.raises(_PathError):
        coverage_batch(sq, [2], 10, 10)
    with pytest.raises(_PathError):
        coverage_batch(sq, [4, -1], 10, 10)
    with pytest.raises(_PathError):
        coverage_batch(sq, [3], 10, 10, exact=[True, False])


@pytest.mark.parametrize('cells', [None, 1, 500])
@pytest.mark.parametrize('seed', range(3))
def test_aliased_shapes_in_one_batch_equal_one_by_one(monkeypatch, seed, cells):
    # (cells: batches of at most that many cells, one shape at least)
    import raster.pixels.scan as scan
    if cells is not None:
        monkeypatch.setattr(scan, '_ALIASED_CELLS', cells)
    rng = np.random.default_rng(300 + seed)
    shapes = random_shapes(rng, 40, 70)
    rules = [('evenodd' if b else 'nonzero') for b in rng.random(len(shapes)) < 0.5]
    clip = (3.5, 2, 60, 66.5) if seed == 2 else None
    got = coverage_many(shapes, 70, 68, rules, False, clip=clip)
    for e, r, g in zip(shapes, rules, got):
        assert same(g, coverage(e, 70, 68, r, False, clip=clip))


# -- internals of the batched path ---------------------------------------------

def jaggy_contour(rng, c, r, n, amp):
    """A closed walk of n short steps around c (radius r, radial noise amp):
    map-like outlines that re-enter pixels often."""
    th = 2 * np.pi * (np.arange(n) + rng.uniform(0, 1, n)) / n
    rr = r + rng.uniform(-amp, amp, n)
    return c + np.stack([rr * np.cos(th), rr * np.sin(th)], 1)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1), st.booleans(), st.sampled_from([0, 1, 10**9]))
def test_exact_cells_of_batches_on_left_edge_crossings_and_holes(seed, evenodd, ratio):
    """Shapes straddling the canvas' left side (virtual column), crossing
    themselves (bow ties, stars), nested contours of either orientation and
    jaggy outlines, batched with the cell index built either way: every
    mask equals the shape drawn alone, bit for bit."""
    import raster.pixels.scan as scan
    rng = np.random.default_rng(seed)
    shapes = []
    for _ in range(12):
        c = rng.uniform(-3, 25, 2)
        kind = rng.integers(0, 4)
        if kind == 0:       # bow tie crossing near the left side
            x = rng.uniform(-0.5, 1.5)
            y = c[1]
            d = rng.uniform(0.3, 6, 2)
            pts = [[x - d[0], y - d[1]], [x + d[0], y + d[1]], [x + d[0], y - d[1]],
                   [x - d[0], y + d[1]]]
            shapes.append(polygon_edges(pts))
        elif kind == 1:     # pentagram
            a = np.pi / 2 + 4 * np.pi / 5 * np.arange(5)
            shapes.append(polygon_edges(c + rng.uniform(1, 8) * np.stack([np.cos(a), np.sin(a)], 1)))
        elif kind == 2:     # nested jaggy contours, random orientations
            r = rng.uniform(2, 9)
            parts = []
            for f in (1.0, 0.6, 0.3):
                p = jaggy_contour(rng, c, r * f, int(40 * f) + 4, 0.4)
                parts.append(polygon_edges(p if rng.random() < 0.5 else p[::-1]))
            shapes.append(np.concatenate(parts))
        else:               # one jaggy outline crossing itself
            p = jaggy_contour(rng, c, rng.uniform(2, 9), 60, 1.5)
            shapes.append(polygon_edges(np.concatenate([p, p[::7] + 0.3])))
    rule = 'evenodd' if evenodd else 'nonzero'
    ref = [coverage(e, 30, 28, rule) for e in shapes]
    orig = scan._SPARSE_RATIO
    try:
        scan._SPARSE_RATIO = ratio
        got = coverage_many(shapes, 30, 28, rule)
    finally:
        scan._SPARSE_RATIO = orig
    assert all(same(g, r) for g, r in zip(got, ref))


def test_exact_cells_of_batches_are_used_at_column_zero(monkeypatch):
    """A bow tie crossing in column 0 with its left half off canvas: the
    crossing cell's coverage comes from its faces in the batch (its left
    side's winding from the pieces left of the box) and the area is the
    analytic one."""
    import raster.pixels.scan as scan
    calls = []
    real = scan._faces

    def spy(xa, ya, xb, yb, col, row, dx, dy, runs, gstart, *a):
        linear, good, value = real(xa, ya, xb, yb, col, row, dx, dy, runs, gstart, *a)
        calls.append(col[runs[0][gstart]][good & ~linear])
        return linear, good, value
    monkeypatch.setattr(scan, '_faces', spy)
    # crossing at (0.5, 5.5); triangles of half-width 4, height 3 each side
    bow = polygon_edges([[-3.5, 2.5], [4.5, 8.5], [4.5, 2.5], [-3.5, 8.5]])
    got = coverage_many([bow, bow + [0, 10]], 8, 20)
    assert calls and any((c == 0).any() for c in calls)
    for g, e in zip(got, (bow, bow + [0, 10])):
        assert same(g, coverage(e, 8, 20))
        # right triangle (apex (0.5, 5.5), side 6 at x = 4.5): 12; of the left
        # one only x in [0, 0.5] is on canvas: apex 0.5 wide, side 0.75
        want = 12.0 + 0.5 * 0.5 * 0.75
        assert abs(float(g.data.sum(dtype=np.float64)) - want) < 1e-5     # (float32 data)


def test_distinct_cells_equals_unique():
    import raster.pixels.scan as scan
    rng = np.random.default_rng(3)
    k = 50
    sw = rng.integers(1, 9, k)
    sh = rng.integers(1, 7, k)
    roff = np.cumsum(sh) - sh
    W = int(sw.max())
    sid = np.sort(rng.integers(0, k, 400)).astype(np.int32)
    row = rng.integers(0, 100, 400) % sh[sid]
    col = rng.integers(0, 100, 400) % sw[sid]
    cell = (row + roff[sid]) * W + col
    want = np.unique(cell, return_inverse=True)
    for ratio in (0, 10**9):
        orig = scan._SPARSE_RATIO
        try:
            scan._SPARSE_RATIO = ratio
            got = scan._distinct_cells(cell, sid, row, col, sw[sid], sw, sh)
        finally:
            scan._SPARSE_RATIO = orig
        assert np.array_equal(got[0], want[0]) and np.array_equal(got[1], want[1])


def test_segmented_cumsum_is_bitwise_per_segment():
    import raster.pixels.scan as scan
    rng = np.random.default_rng(4)
    k = 300
    cnt = np.concatenate([[0, 1, 2, 3, 5, 8, 9, 1000, 1023, 1024, 1025, 0],
                          rng.integers(0, 70, k - 12)])
    seg = np.repeat(np.arange(k), cnt)
    v = rng.normal(size=len(seg)) * 10.0 ** rng.integers(-8, 8, len(seg))
    got = scan._segmented_cumsum(v, seg, k)
    start = np.cumsum(cnt) - cnt
    want = np.concatenate([np.cumsum(v[s:s + c]) for s, c in zip(start, cnt)])
    assert got.tobytes() == want.tobytes()
    assert len(scan._segmented_cumsum(np.zeros(0), np.zeros(0, np.int64), 3)) == 0


@pytest.mark.parametrize('chunk', [1 << 17, 40])
def test_batch_overwriting_its_edges_gives_the_same_masks(monkeypatch, chunk):
    # overwrite=True moves the caller's edges in place instead of copying
    # them (shapes drawn alone, above _CHUNK_PIECES, and in sub-batches)
    from raster.pixels import scan
    from raster.pixels.scan import coverage_batch
    monkeypatch.setattr(scan, '_CHUNK_PIECES', chunk)
    rng = np.random.default_rng(11)
    shapes = [s for s in random_shapes(rng, 60)                 # (all on the canvas)
              if (s.min(axis=(0, 1)) < 99).all() and (s.max(axis=(0, 1)) > 1).all()]
    e = np.concatenate(shapes)
    counts = [len(s) for s in shapes]
    want = coverage_batch(e, counts, 100, 100)
    mine = e.copy()
    got = coverage_batch(mine, counts, 100, 100, overwrite=True)
    assert not np.array_equal(mine, e)          # moved, not copied
    for a, b in zip(got, want):
        assert same(a, b)
