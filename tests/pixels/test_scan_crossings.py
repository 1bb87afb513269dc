"""Crossing-heavy geometry (issue 11): many overlapping, self-intersecting
contours and self-overlapping strokes against an exact-area reference
(raster.testing.span_coverage), at small sizes; the exact recompute must
stay within 1/255 of the true area."""

import contextlib

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st, HealthCheck

import raster
from raster.geometry.flattening import flatten_beziers
from raster.pixels.scan import coverage
from raster.testing import capsule_spans, polygon_spans, span_coverage

NS = 'http://www.w3.org/2000/svg'


def edges_of(polys):
    return np.concatenate([np.stack([p, np.roll(p, -1, axis=0)], axis=1) for p in polys])


def walk(rng, n, size, step):
    """A closed random walk of n vertices (crossing itself), inside the box."""
    p = np.cumsum(rng.normal(0, step, (n, 2)), axis=0)
    p -= p.mean(axis=0)
    p += rng.uniform(0.3 * size, 0.7 * size, 2)
    return np.clip(p, 0.2, size - 0.2)


def check(polys, size, rule, bound=1.0):
    got = coverage(edges_of(polys), size, size, fill_rule=rule).full(size, size)
    ref = span_coverage(polygon_spans(polys, rule), size, size, lines=1024)
    err = 255 * np.abs(got - ref).max()
    assert err <= bound, err
    return got


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1), st.integers(1, 6), st.integers(3, 40),
       st.floats(0.2, 4.0), st.sampled_from(['nonzero', 'evenodd']))
def test_property_many_self_intersecting_contours(seed, k, n, step, rule):
    rng = np.random.default_rng(seed)
    size = 14
    polys = [walk(rng, n, size, step) for _ in range(k)]
    check(polys, size, rule)


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1), st.integers(2, 12), st.sampled_from(['nonzero', 'evenodd']))
def test_property_stacked_copies_and_reversed_contours(seed, k, rule):
    # the same contour many times, some reversed, some shifted by a hair:
    # windings far from 0 and 1 in one cell, cancelling or adding up
    rng = np.random.default_rng(seed)
    base = walk(rng, 9, 10, 2.0)
    polys = []
    for i in range(k):
        p = base + rng.normal(0, 1e-3, 2) * (i % 3 == 0)
        polys.append(p[::-1] if rng.uniform() < 0.4 else p)
    check(polys, 10, rule)


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
def test_jittered_polygon_small(rule):
    # the crossing-heavy benchmark's polygon at small size: 3,000 vertices
    # with +-1.5 px radial jitter on a 60x60 canvas
    rng = np.random.default_rng(3)
    th = np.sort(rng.uniform(0, 2 * np.pi, 3000))
    r = 25 + 3 * np.cos(5 * th) + rng.uniform(-1.5, 1.5, len(th))
    p = np.c_[30 + r * np.cos(th), 30 + r * np.sin(th)]
    got = check([p], 60, rule)
    # invariance: the same polygon reversed, and transposed
    assert np.allclose(coverage(edges_of([p[::-1]]), 60, 60, fill_rule=rule).full(60, 60),
                       got, atol=1e-6)
    tp = coverage(edges_of([p[:, ::-1]]), 60, 60, fill_rule=rule).full(60, 60)
    assert np.allclose(tp.T, got, atol=1e-6)


def test_map_of_shared_borders():
    # a grid of cells whose borders are shared (each border drawn twice,
    # in opposite directions) with wobbly common edges, nonzero: the union
    # is the whole square
    rng = np.random.default_rng(5)
    n, s = 6, 5.0
    xs = np.arange(n + 1) * s + 1.0
    wob = rng.uniform(-1.2, 1.2, (n + 1, n + 1, 2))
    wob[[0, -1], :, 1] = 0          # V[i, j] = (x_j, y_i): the outer sides stay straight
    wob[:, [0, -1], 0] = 0
    V = np.stack(np.meshgrid(xs, xs, indexing='xy'), -1) + wob
    polys = [np.array([V[i, j], V[i, j + 1], V[i + 1, j + 1], V[i + 1, j]])
             for i in range(n) for j in range(n)]
    got = check(polys, 33, 'nonzero')
    outer = np.array([V[0, 0], V[0, n], V[n, n], V[n, 0]])
    ref = span_coverage(polygon_spans([outer]), 33, 33, lines=1024)
    assert 255 * np.abs(got - ref).max() <= 1.0


def test_stroked_random_cubics_small():
    # the benchmark's self-overlapping stroke at small size: one path of 40
    # random cubics across a 64x64 canvas, 1.5 px wide, round joins and caps
    # (so the exact stroke is the union of discs along the curve, i.e. of
    # the capsules of a very fine polyline of it)
    rng = np.random.default_rng(2)
    n, size = 40, 64
    p = rng.uniform(2, size - 2, (3 * n + 1, 2))
    d = 'M%.6f %.6f' % tuple(p[0]) + ''.join('C%.6f %.6f %.6f %.6f %.6f %.6f' % tuple(p[1 + 3 * i:4 + 3 * i].ravel())
                                         for i in range(n))
    doc = ('<svg xmlns="%s" width="%d" height="%d"><path fill="none" stroke="#000" '
           'stroke-width="1.5" stroke-linejoin="round" stroke-linecap="round" d="%s"/></svg>'
           % (NS, size, size, d)).encode()
    ctrl = np.stack([p[3 * i:3 * i + 4] for i in range(n)])
    pts, cnt = flatten_beziers(ctrl, 1e-3)
    ref = 255 * span_coverage(capsule_spans(pts, 0.75), size, size, lines=256)
    # flattened finely, what is left is the scan conversion of the
    # self-overlapping outline: within 2/255 (1/255 of it the reference's)
    fine = raster.render(doc, tolerance=0.002)[..., 3].astype(np.float64)
    assert np.abs(fine - ref).max() <= 2.0
    # at the default most pixels are within the accuracy target (the
    # outline of a turn tighter than the half width is flattened on the
    # inner side of the offset curve: a few pixels miss it)
    a = raster.render(doc)[..., 3].astype(np.float64)
    err = np.abs(a - ref)
    assert (err > 8.0).sum() <= 0.003 * (err > 0.5).sum() + 2 and err.max() <= 16.0


def recorded_coverage(monkeypatch, e, rule, name, arg, patches):
    """Coverage of edges ``e`` on a 24x24 canvas with the module values
    ``patches`` (name -> value) of raster.pixels.scan set and every call
    of ``scan.<name>`` recorded by its argument number ``arg``: (coverage,
    the recorded arguments)."""
    from raster.pixels import scan
    calls = []
    real = getattr(scan, name)

    def recording(*a):
        calls.append(a[arg])
        return real(*a)
    monkeypatch.setattr(scan, name, recording)
    for k, v in patches.items():
        monkeypatch.setattr(scan, k, v)
    return coverage(e, 24, 24, fill_rule=rule).full(24, 24), calls


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
def test_faces_in_slices_are_the_same(monkeypatch, rule):
    # the cells of several runs are resolved (scan._faces) over slices of
    # cells of bounded work: tiny slices (one cell each, nearly) give the
    # same coverage bit for bit
    rng = np.random.default_rng(11)
    polys = [walk(rng, 30, 24, 2.5) for _ in range(6)]
    e = edges_of(polys)
    whole = coverage(e, 24, 24, fill_rule=rule).full(24, 24)
    sliced, cells = recorded_coverage(monkeypatch, e, rule, '_faces', 9, {'_FACES_WORK': 8})
    calls = [len(c) for c in cells]
    assert len(calls) > 10 and max(calls) < sum(calls)
    assert np.array_equal(sliced, whole)
    ref = span_coverage(polygon_spans(polys, rule), 24, 24, lines=1024)
    assert 255 * np.abs(sliced - ref).max() <= 1.0


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
@pytest.mark.parametrize('seed', range(3))
def test_faces_of_single_piece_runs_are_the_same(monkeypatch, rule, seed):
    """Cells whose runs are all one piece (long steps: a piece crosses a
    cell whole) take a shorter treatment in _faces calls of their own;
    the general treatment of the same cells gives the same coverage bit
    for bit, and both are exact."""
    from raster.pixels import scan
    rng = np.random.default_rng(20 + seed)
    polys = [walk(rng, 80, 24, 4.0) for _ in range(4)] + [walk(rng, 200, 24, 0.4)]
    e = edges_of(polys)
    seen = []
    real = scan._faces

    def recording(*a):
        seen.append((a[13] if len(a) > 13 else False, len(a[9])))
        return real(*a)

    def general(*a):
        return real(*a[:13])
    monkeypatch.setattr(scan, '_FACES_SINGLE_MIN', 0)
    monkeypatch.setattr(scan, '_faces', recording)
    apart = coverage(e, 24, 24, fill_rule=rule).full(24, 24)
    assert sum(n for one, n in seen if one) > 100 and sum(n for one, n in seen if not one) > 10
    monkeypatch.setattr(scan, '_faces', general)
    assert np.array_equal(apart, coverage(e, 24, 24, fill_rule=rule).full(24, 24))
    ref = span_coverage(polygon_spans(polys, rule), 24, 24, lines=1024)
    assert 255 * np.abs(apart - ref).max() <= 1.0


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
@pytest.mark.parametrize('seed', range(4))
def test_faces_agree_with_the_midpoint_rule(monkeypatch, rule, seed):
    """The coverage of cells of several runs from their faces equals the
    midpoint rule's over the critical heights (every such cell flagged
    instead: _FACES_RUNS = 1), on self-crossing walks of long and of short
    steps (runs of one piece and of many)."""
    from raster.pixels import scan
    rng = np.random.default_rng(seed)
    polys = [walk(rng, 60, 24, 3.0) for _ in range(3)] + [walk(rng, 300, 24, 0.4)]
    e = edges_of(polys)
    direct, cells = recorded_coverage(monkeypatch, e, rule, '_faces', 9, {})
    assert sum(len(c) for c in cells) > 50
    monkeypatch.setattr(scan, '_FACES_RUNS', 1)
    midpoint = coverage(e, 24, 24, fill_rule=rule).full(24, 24)
    assert np.abs(direct - midpoint).max() < 1e-6


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
def test_run_along_the_left_side_of_its_cell(rule):
    """A run that leaves its cell's interior, follows the cell's left side
    for a stretch and comes back (a polygon with a vertical edge on a
    pixel boundary), among other polygons crossing that cell: the stretch
    bounds no face, so the faces' windings and the running sum stay right,
    whether the cell is decided by the windings' bound or by its faces."""
    rng = np.random.default_rng(1)
    for _ in range(40):
        a, b = rng.uniform(0.05, 0.45), rng.uniform(0.55, 0.95)
        x = rng.uniform(1.2, 1.95)
        p = np.array([(x, 2.0), (1.0, 2.0 + a), (1.0, 2.0 + b), (x, 3.0), (4, 5), (5, 1)])
        polys = [p if rng.uniform() < 0.5 else p[::-1]]
        polys += [rng.uniform(0.3, 5.7, (rng.integers(3, 7), 2)) for _ in range(rng.integers(1, 4))]
        check(polys, 6, rule)


def test_faces_decide_the_crossings_of_a_stroke():
    """In a self-overlapping stroke nearly every cell where the outline
    crosses itself is resolved from its faces; few are left to the
    general recompute (each a run ending inside the cell, touching
    pieces, ...)."""
    from raster.pixels import scan
    rng = np.random.default_rng(4)
    p = rng.uniform(2, 62, (3 * 30 + 1, 2))
    d = 'M%.6f %.6f' % tuple(p[0]) + ''.join(
        'C%.6f %.6f %.6f %.6f %.6f %.6f' % tuple(p[1 + 3 * i:4 + 3 * i].ravel())
        for i in range(30))
    doc = ('<svg xmlns="%s" width="64" height="64"><path fill="none" stroke="#000" '
           'stroke-width="1.5" d="%s"/></svg>' % (NS, d)).encode()
    counts = {'faces': 0, 'exact': 0}
    real_faces, real_exact = scan._faces, scan._exact

    def faces(*a):
        linear, good, value = real_faces(*a)
        counts['faces'] += int((good & ~linear).sum())
        return linear, good, value

    def exact(*a):
        counts['exact'] += len(a[7])
        return real_exact(*a)
    mp = pytest.MonkeyPatch()
    try:
        mp.setattr(scan, '_faces', faces)
        mp.setattr(scan, '_exact', exact)
        raster.render(doc)
    finally:
        mp.undo()
    assert counts['faces'] > 200
    assert counts['exact'] < 0.1 * counts['faces']


# -- cells of many chords (dense hatching) ------------------------------------

def _boundary_point(t):
    """The point of the unit cell's boundary at parameter t (the walk of
    scan._perimeter: top left to right, right side down, bottom right to
    left, left side up)."""
    side, f = np.floor(t).astype(int), t - np.floor(t)
    x = np.choose(side, [f, np.ones_like(f), 1 - f, np.zeros_like(f)])
    y = np.choose(side, [np.zeros_like(f), f, np.ones_like(f), 1 - f])
    return x, y


def _segments_cross(p, q, r, s):
    """Whether segments pq and rs cross at one point inside both."""
    def orient(a, b, c):
        return np.sign((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    return (orient(p, q, r) * orient(p, q, s) < 0) and (orient(r, s, p) * orient(r, s, q) < 0)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 6), st.integers(1, 40))
def test_chords_cross_exactly_where_two_chords_cross(seed, cells, most):
    """scan._chords_cross tells, from the order of chord ends along each
    cell's boundary alone, the cells where two chords cross: the same
    answer as testing every pair of segments (random chords between
    different sides, nested, parallel or crossing; many cells at once)."""
    from raster.pixels import scan
    rng = np.random.default_rng(seed)
    k = rng.integers(1, most + 1, cells)
    g = np.repeat(np.arange(cells), k)
    K = len(g)
    # distinct parameters, the two ends of a chord on different sides
    t0 = rng.uniform(0.001, 3.999, K)
    t1 = (np.floor(t0) + rng.integers(1, 4, K) + rng.uniform(0.001, 0.999, K)) % 4.0
    if rng.uniform() < 0.5:         # parallel chords (nested brackets) in some cells
        par = rng.uniform(size=cells)[g] < 0.5
        t0[par] = rng.uniform(0.001, 0.999, par.sum())
        t1[par] = 3.0 - t0[par] + rng.normal(0, 0.01, par.sum()).clip(-0.0009, 0.0009)
    ends_g = np.concatenate([g, g])
    ends_t = np.concatenate([t0, t1])
    o = np.lexsort((ends_t, ends_g))
    pos = np.empty(2 * K, np.int64)
    pos[o] = np.arange(2 * K)
    got = scan._chords_cross(pos[:K], pos[K:], g, cells)
    x0, y0 = _boundary_point(t0)
    x1, y1 = _boundary_point(t1)
    want = np.zeros(cells, bool)
    for c in range(cells):
        idx = np.flatnonzero(g == c)
        for i, a in enumerate(idx):
            for b in idx[i + 1:]:
                if _segments_cross((x0[a], y0[a]), (x1[a], y1[a]), (x0[b], y0[b]), (x1[b], y1[b])):
                    want[c] = True
    assert np.array_equal(got, want)


def stripes(n, x0, pitch, width, lean, top, bottom):
    """n thin parallelograms (stripes) ``width`` wide, ``pitch`` apart,
    from ``x0`` on, leaning ``lean`` to the right between ``top`` and
    ``bottom``: dense hatching, whose edges cross nowhere."""
    xs = x0 + pitch * np.arange(n)
    return [np.array([(x, top), (x + width, top), (x + width + lean, bottom), (x + lean, bottom)])
            for x in xs]


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
@pytest.mark.parametrize('pitch', [0.25, 0.02])
def test_dense_hatching_is_exact_and_decided_by_faces(monkeypatch, rule, pitch):
    """Hatching of 8 to 100 edges a pixel (thin stripes, none crossing
    another) is exact.  Cells of up to _FACES_CHORDS chords that cross
    nowhere are decided from their faces, whatever their number of chords:
    only the cells where the stripes end (first and last rows) are left to
    the exact recompute, and the chords of cells of more than
    _CHORDS_TESTED are not tested pair by pair."""
    from raster.pixels import scan
    # (rows of stripes alone are settled by edge weights before any cell
    # is flagged: see test_rows_of_stripes_are_settled_by_edge_weights)
    monkeypatch.setattr(scan, '_DENSE_BAND', np.inf)
    n = int(round(5.0 / pitch))
    # (no edge through a cell's corner: such cells go to the exact recompute)
    polys = stripes(n, 1.3137, pitch, 0.4 * pitch, 3.7219, 0.6173, 11.4291)
    rows, pairs = [], []
    real_exact, real_crossings = scan._exact, scan._crossings

    def exact(*a):
        xa, ya, xb, yb, col, row, pieces, counts = a[:8]
        if a[-1] == 0:
            rows.extend(row[pieces[np.cumsum(counts) - counts]].tolist())
        return real_exact(*a)

    def crossings(*a):
        if a[7] is None:                    # cells of chords alone
            pairs.append(int(a[6][a[8]].max(initial=0)))
        return real_crossings(*a)
    monkeypatch.setattr(scan, '_exact', exact)
    monkeypatch.setattr(scan, '_crossings', crossings)
    got = check(polys, 12, rule)
    assert set(rows) <= {0, 11} and len(rows) > 0
    # (a chord is tested against the later ones of its cell: fewer than
    # _CHORDS_TESTED, in cells tested directly)
    assert max(pairs, default=0) < scan._CHORDS_TESTED
    # the same coverage when every cell is left to the general methods
    monkeypatch.setattr(scan, '_FACES_CHORDS', 0)
    monkeypatch.setattr(scan, '_FACES_PIECES', 0)
    assert np.allclose(coverage(edges_of(polys), 12, 12, fill_rule=rule).full(12, 12), got,
                       atol=1e-9)


def spy_rows(monkeypatch):
    """Record the rows :func:`_row_weights` settles, and the rows of the
    cells flagged for _faces or the exact recompute (a list each); every
    box is tried for weights, however sparse (_DENSE_BAND 0)."""
    from raster.pixels import scan
    monkeypatch.setattr(scan, '_DENSE_BAND', 0.0)
    settled, flagged, depth = [], [], []
    real_weights, real_flag = scan._row_weights, scan._flag
    real_band, real_batch = scan._band, scan._batch

    def band(*a):
        depth.append(a[-1])
        try:
            return real_band(*a)
        finally:
            depth.pop()

    def batch(*a, **k):         # (the refinement of recomputed cells)
        depth.append(a[8])
        try:
            return real_batch(*a, **k)
        finally:
            depth.pop()

    def weights(*a):
        r = real_weights(*a)
        if r is not None and depth[-1] == 0:
            settled.extend(np.flatnonzero(r[1]).tolist())
        return r

    def flag(xa, ya, xb, yb, col, row, cell, *a, **k):
        r = real_flag(xa, ya, xb, yb, col, row, cell, *a, **k)
        if depth[-1] == 0:      # (not the refinement of a recomputed cell)
            at = np.concatenate([r[0], r[3][0]])
            flagged.extend(np.unique(row[np.isin(cell, at)]).tolist())
        return r
    monkeypatch.setattr(scan, '_band', band)
    monkeypatch.setattr(scan, '_batch', batch)
    monkeypatch.setattr(scan, '_row_weights', weights)
    monkeypatch.setattr(scan, '_flag', flag)
    return settled, flagged


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
@pytest.mark.parametrize('pitch, width', [(0.25, 0.1), (0.02, 0.008), (0.05, 0.12)])
def test_rows_of_stripes_are_settled_by_edge_weights(monkeypatch, rule, pitch, width):
    """Rows crossed only by stripe edges that span them and cross nowhere
    are settled by edge weights (the change of the fill rule across each
    edge): exact, and no cell of theirs is flagged, whatever the number of
    edges in a pixel (up to 100 here).  Stripes wider than their pitch
    overlap (windings up to 3: nonzero fills the overlaps, evenodd
    alternates).  Rows where the stripes end are left to the cells."""
    from raster.pixels import scan
    settled, flagged = spy_rows(monkeypatch)
    n = int(round(5.0 / pitch))
    polys = stripes(n, 1.3137, pitch, width, 3.7219, 0.6173, 11.4291)
    got = check(polys, 12, rule)
    assert set(settled) == set(range(1, 11))
    assert set(flagged) <= {0, 11}
    # the same coverage without the weights (cells flagged and recomputed)
    monkeypatch.setattr(scan, '_DENSE_BAND', np.inf)
    assert np.allclose(coverage(edges_of(polys), 12, 12, fill_rule=rule).full(12, 12), got,
                       atol=1e-9)


@pytest.mark.parametrize('pitch, tried', [(0.02, True), (1.5, False)])
def test_only_dense_boxes_are_tried_for_edge_weights(monkeypatch, pitch, tried):
    # hatching of about 100 edges a pixel is tried (and settled) at the
    # default density; stripes 1.5 px apart are left to the cells
    from raster.pixels import scan
    calls = []
    real = scan._row_weights
    monkeypatch.setattr(scan, '_row_weights', lambda *a: calls.append(1) or real(*a))
    polys = stripes(int(round(8.0 / pitch)), 1.3137, pitch, 0.4 * pitch, 3.7219, 0.6173,
                    11.4291)
    check(polys, 12, 'nonzero')
    assert bool(calls) == tried


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
def test_rows_with_crossings_or_vertices_are_not_settled(monkeypatch, rule):
    """Rows where two edges cross, or an edge ends, keep the flags: a
    cross-hatch settles no row (its first sorted row tells), a stripe
    crossing a hatch in its top rows leaves those, and stripes bent in the
    middle rows settle only the others."""
    settled, flagged = spy_rows(monkeypatch)
    cross = stripes(60, 0.5, 0.15, 0.05, 4.0, 0.5, 11.5) + stripes(60, 5.0, 0.15, 0.05, -4.0, 0.5, 11.5)
    check(cross, 12, rule)
    assert settled == [] and len(flagged) > 0
    # a shallow stripe crossing a vertical hatch in rows 0-2 only: the row
    # sorted first (the middle one) has no crossing, the top rows do
    hatch = stripes(10, 1.0, 0.2, 0.05, 0.0, 0.5, 11.5)
    shallow = [np.array([(0.5, 0.5), (0.6, 0.5), (12.1, 11.5), (12.0, 11.5)])]
    settled.clear()
    check(hatch + shallow, 12, rule)
    assert set(settled) == set(range(3, 11))
    # chevrons: every stripe turns at y = 6.5, inside row 6
    bent = [np.array([(x, 0.5), (x + 0.06, 0.5), (x + 3.06, 6.5), (x + 0.06, 11.5),
                      (x, 11.5), (x + 3.0, 6.5)]) for x in 1.3 + 0.15 * np.arange(40)]
    settled.clear()
    check(bent, 12, rule)
    assert 6 not in settled and set(settled) == set(range(1, 11)) - {6}


@contextlib.contextmanager
def dense_band(value):
    """``scan._DENSE_BAND`` set to ``value`` in the block (0: every box
    tried for edge weights, inf: none), for the Hypothesis tests, which
    cannot take pytest's monkeypatch."""
    from raster.pixels import scan
    saved = scan._DENSE_BAND
    scan._DENSE_BAND = value
    try:
        yield
    finally:
        scan._DENSE_BAND = saved


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1), st.integers(20, 120), st.floats(0.01, 0.6),
       st.floats(-6.0, 6.0), st.floats(0.0, 0.6), st.sampled_from(['nonzero', 'evenodd']))
def test_property_dense_stripes_exact_with_and_without_weights(seed, n, width, lean, jitter,
                                                               rule):
    # random stripes (widths, leans and directions jittered: some cross,
    # some overlap, some run backwards) through a 10 x 10 box: the same
    # coverage as the reference, and as without the edge weights
    rng = np.random.default_rng(seed)
    xs = np.sort(rng.uniform(-2.0, 10.0, n))
    polys = []
    for x in xs:
        w = width * rng.uniform(0.5, 1.5)
        ln = lean + jitter * rng.normal()
        p = np.array([(x, 0.3), (x + w, 0.3), (x + w + ln, 9.7), (x + ln, 9.7)])
        polys.append(p[::-1] if rng.random() < 0.3 else p)
    with dense_band(0.0):               # (every box tried for weights)
        got = check(polys, 10, rule)
    with dense_band(np.inf):            # (none)
        plain = coverage(edges_of(polys), 10, 10, fill_rule=rule).full(10, 10)
    assert np.allclose(plain, got, atol=1e-9)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1), st.integers(1, 11), st.integers(1, 11),
       st.sampled_from(['nonzero', 'evenodd']))
def test_property_weights_with_polygons_and_coincident_edges(seed, w, h, rule):
    # stripes spanning whole rows (or starting on a row line, or outside
    # the box), polygons with vertices on row lines, and copies of earlier
    # shapes (coincident edges, some reversed) in small boxes: the same
    # coverage with every box tried for weights as with none
    rng = np.random.default_rng(seed)
    polys = []
    for _ in range(int(rng.integers(1, 30))):
        kind = rng.random()
        if kind < 0.6 or not polys:
            x, wd, ln = rng.uniform(-4, w + 4), rng.uniform(0, 1), rng.uniform(-5, 5) * (rng.random() < 0.7)
            y0 = float(rng.integers(0, h)) if rng.random() < 0.5 else rng.uniform(-1, h)
            y1 = float(h) if rng.random() < 0.5 else rng.uniform(y0, h + 1)
            polys.append(np.array([(x, y0), (x + wd, y0), (x + wd + ln, y1), (x + ln, y1)]))
        elif kind < 0.75:
            # (vertices on row lines: their edges span whole rows too)
            n = int(rng.integers(3, 8))
            polys.append(np.stack([np.round(rng.uniform(-2, w + 2, n) * 2) / 2,
                                   rng.integers(-1, h + 2, n).astype(float)], axis=1))
        else:
            p = polys[int(rng.integers(0, len(polys)))]
            polys.append(p[::-1].copy() if rng.random() < 0.5 else p.copy())
    e = edges_of(polys)
    got = []
    for band in (0.0, np.inf):
        with dense_band(band):
            m = coverage(e, w, h, fill_rule=rule)
            got.append(np.zeros((h, w)) if m is None else m.full(w, h))
    assert np.abs(got[0] - got[1]).max() <= 1e-7


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
def test_crossing_hatches_are_exact_with_bounded_pair_work(monkeypatch, rule):
    """Two hatches leaning opposite ways (every stripe of one crosses many
    of the other): cells of chords that cross are tested pair by pair up
    to _FACES_PIECES chords, in slices of at most _FACES_WORK pairs (and
    one piece's); busier ones go to the exact recompute.  Exact either way,
    and the same with the pair slices a single pair."""
    from raster.pixels import scan
    polys = (stripes(40, 0.5, 0.23, 0.07, 4.0, 0.5, 11.5)
             + stripes(40, 5.0, 0.19, 0.05, -4.0, 0.5, 11.5))
    pairs = []
    real = scan._crossings

    def crossings(*a):
        pairs.append(int(a[6][a[8]].sum()))
        return real(*a)
    monkeypatch.setattr(scan, '_crossings', crossings)
    got = check(polys, 12, rule)
    assert sum(pairs) > 0
    assert max(pairs) <= scan._FACES_WORK + scan._FACES_PIECES
    monkeypatch.setattr(scan, '_FACES_WORK', 1)
    pairs.clear()
    assert np.allclose(coverage(edges_of(polys), 12, 12, fill_rule=rule).full(12, 12), got,
                       atol=1e-12)
    assert max(pairs) <= scan._FACES_PIECES


@pytest.mark.parametrize('rule', ['nonzero', 'evenodd'])
def test_only_chords_whose_ends_interleave_are_measured(monkeypatch, rule):
    """In cells of chords alone the pairs whose ends do not interleave
    along the cell's boundary (parallel stripes of one hatch) cannot meet:
    every pair measured (orientation tests) is a crossing found, and the
    coverage is exact."""
    from raster.pixels import scan
    polys = (stripes(30, 0.5, 0.31, 0.07, 4.0, 0.5, 11.5)
             + stripes(30, 5.0, 0.29, 0.05, -4.0, 0.5, 11.5))
    measured, found = [], []
    real_o, real_c = scan._orientations, scan._crossings

    def orientations(*a):
        measured.append(len(a[0]))
        return real_o(*a)

    def crossings(*a):
        out = real_c(*a)
        if a[7] is None:                    # cells of chords alone
            found.append(len(out[1]) + len(out[0]))
        else:
            measured.pop()
        return out
    monkeypatch.setattr(scan, '_orientations', orientations)
    monkeypatch.setattr(scan, '_crossings', crossings)
    check(polys, 12, rule)
    assert sum(found) > 100
    assert measured == found


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 300), st.integers(1, 40),
       st.sampled_from([1.0, 0.5, 1e-3]))
def test_row_order_is_the_lexicographic_order(seed, n, rows, grid):
    """_row_order sorts segments by (row, x at the top, x at the bottom),
    as np.lexsort does, ties in x at the top included (values on a coarse
    grid repeat often)."""
    from raster.pixels.scan import _row_order
    rng = np.random.default_rng(seed)
    r = rng.integers(0, rows, n)
    xt = np.round(rng.uniform(-5, 30, n) / grid) * grid
    xd = np.round(rng.uniform(-5, 30, n) / grid) * grid
    o = _row_order(r, xt, xd)
    assert sorted(o.tolist()) == list(range(n))
    ref = np.lexsort((xd, xt, r))
    got = np.stack([r[o], xt[o], xd[o]])
    assert np.array_equal(got, np.stack([r[ref], xt[ref], xd[ref]]))


def test_row_order_rounding_leaves_crossing_rows_unsettled():
    """Two segments of a far row whose x at the top differ by less than the
    sort key's rounding and which cross in the row: their order may come
    out reversed, and the row is then not settled (an unsettled row has
    weight 1 everywhere)."""
    from raster.pixels.scan import _row_order, _row_weights
    h = 4000
    # 40 stripes spanning row 3990 and crossing nowhere, and two segments
    # 1e-13 apart at the top that cross (one leans right, one left)
    xs = np.linspace(0, 300, 40)
    xa = np.concatenate([xs, [150.00000000001 + 1e-13, 150.00000000001]])
    xb = np.concatenate([xs + 0.5, [149.8, 150.2]])
    ya = np.full(len(xa), 3990.0)
    yb = ya + 1.0
    r = np.full(len(xa), 3990)
    o = _row_order(r, xa, xb)
    i = o.tolist().index(40)
    assert o[i + 1] == 41                           # (reversed: one key)
    for evenodd in (False, True):
        weight, settled = _row_weights(xa, ya, xb, yb, h, evenodd)
        assert not settled[3990] and (weight == 1).all()
    # the same row without the crossing pair is settled
    weight, settled = _row_weights(xa[:40], ya[:40], xb[:40], yb[:40], h, False)
    assert settled[3990]
