"""Tests of raster.geometry.stroking.stroke_many: batch stroking gives, path by path, the
outline stroke() gives for each path alone."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.errors import LimitError, RasterError
from raster.geometry.path import Path
from raster.geometry.pens import PathBuilder
from raster.geometry.stroking import StrokeError, StrokeStyle, stroke, stroke_many
from raster.geometry.pathdata import parse_path
from raster.geometry.transform import Affine


def random_path(rng, kind=None):
    """A random path of 1-3 contours of lines, quadratics and cubics (some
    closed, some of zero length, some lone moves)."""
    b = PathBuilder()
    kind = kind if kind is not None else int(rng.integers(0, 6))
    if kind == 0:
        return Path.empty()
    for _ in range(int(rng.integers(1, 4))):
        b.moveTo(rng.uniform(0, 50, 2))
        if rng.random() < 0.1:
            continue                                     # lone move
        for _ in range(int(rng.integers(1, 5))):
            v = rng.integers(1, 4)
            if v == 1:
                b.lineTo(rng.uniform(0, 50, 2))
            elif v == 2:
                b.qCurveTo(rng.uniform(0, 50, 2), rng.uniform(0, 50, 2))
            else:
                b.curveTo(rng.uniform(0, 50, 2), rng.uniform(0, 50, 2), rng.uniform(0, 50, 2))
        if rng.random() < 0.5:
            b.closePath()
    return b.path()


def polygons_only(rng, n):
    return [Path.polygon(rng.uniform(0, 100, (int(rng.integers(2, 7)), 2)),
                         closed=bool(rng.random() < 0.5)) for _ in range(n)]


def assert_same(batch, single, exact=False):
    """Same outlines: bit for bit when ``exact`` (paths of lines), else to
    rounding (flatten_beziers rounds a curve differently in a batch)."""
    assert len(batch) == len(single)
    for a, b in zip(batch, single):
        assert np.array_equal(a.verbs, b.verbs)
        if exact:
            assert np.array_equal(a.points, b.points)
        else:
            assert np.allclose(a.points, b.points, rtol=0, atol=1e-9)


def winding(path, pts):
    """Nonzero winding number of the outline ``path`` at points (P, 2)."""
    segs = path.segments()
    a = np.concatenate([segs.ctrl[:, 0], segs.contour_end[segs.contour_closed]])
    b = np.concatenate([segs.ctrl[:, 3], segs.contour_start[segs.contour_closed]])
    x, y = pts[:, 0:1], pts[:, 1:2]
    up = (a[:, 1] <= y) & (b[:, 1] > y)
    down = (b[:, 1] <= y) & (a[:, 1] > y)
    side = (b[:, 0] - a[:, 0]) * (y - a[:, 1]) - (x - a[:, 0]) * (b[:, 1] - a[:, 1])
    return (up & (side > 0)).sum(1) - (down & (side < 0)).sum(1)


def boundary_distance(path, pts):
    segs = path.segments()
    a = np.concatenate([segs.ctrl[:, 0], segs.contour_end[segs.contour_closed]])
    b = np.concatenate([segs.ctrl[:, 3], segs.contour_start[segs.contour_closed]])
    d = b - a
    L2 = np.maximum((d ** 2).sum(1), 1e-300)
    rel = pts[:, None, :] - a[None]
    t = np.clip((rel * d[None]).sum(2) / L2, 0, 1)
    q = a[None] + t[..., None] * d[None]
    return np.sqrt(((pts[:, None, :] - q) ** 2).sum(2)).min(1)


@pytest.mark.parametrize('join', ['miter', 'miter-clip', 'round', 'bevel'])
@pytest.mark.parametrize('cap', ['butt', 'round', 'square'])
def test_mixed_paths_equal_single_strokes(join, cap):
    rng = np.random.default_rng(7)
    paths = [random_path(rng) for _ in range(40)]
    style = StrokeStyle(width=float(rng.uniform(0.5, 8)), join=join, cap=cap, miterlimit=3)
    t = Affine.rotate(30) @ Affine.scale(2.5, 1.5)
    assert_same(stroke_many(paths, style, transforms=t, tolerance=0.1),
                [stroke(p, style, transform=t, tolerance=0.1) for p in paths])


def test_per_path_translations_equal_single_strokes():
    # translations do not change the scale: one tolerance for all paths
    rng = np.random.default_rng(3)
    paths = [random_path(rng, kind=1) for _ in range(30)]
    ts = [Affine.translate(*rng.uniform(-100, 100, 2)) @ Affine.scale(3) for _ in paths]
    style = StrokeStyle(width=1.5, join='round')
    assert_same(stroke_many(paths, style, transforms=ts),
                [stroke(p, style, transform=t) for p, t in zip(paths, ts)])


def test_power_of_two_scales_equal_single_strokes():
    # per-path tolerances that differ by powers of two scale exactly
    rng = np.random.default_rng(11)
    paths = [random_path(rng, kind=1) for _ in range(24)]
    ts = [Affine.scale(2.0 ** int(rng.integers(-2, 4))) for _ in paths]
    style = StrokeStyle(width=3, cap='square')
    assert_same(stroke_many(paths, style, transforms=ts, tolerance=0.2),
                [stroke(p, style, transform=t, tolerance=0.2) for p, t in zip(paths, ts)])
    polys = polygons_only(rng, 20)
    assert_same(stroke_many(polys, style, transforms=ts[:20]),
                [stroke(p, style, transform=t) for p, t in zip(polys, ts)], exact=True)


def test_mixed_scales_fill_the_same_region_within_tolerance():
    # a circle of 4 cubics under scales 1, 3 and 7: the outlines may differ
    # only by rounding, so the fill agrees away from the boundary
    circle = parse_path('M10 0 C15.5 0 20 4.5 20 10 C20 15.5 15.5 20 10 20 '
                        'C4.5 20 0 15.5 0 10 C0 4.5 4.5 0 10 0 Z')
    paths = [circle, circle, circle]
    ts = [Affine.scale(1), Affine.scale(3), Affine.scale(7)]
    style = StrokeStyle(width=4)
    tol = 0.25
    batch = stroke_many(paths, style, transforms=ts, tolerance=tol)
    rng = np.random.default_rng(5)
    for a, p, t in zip(batch, paths, ts):
        b = stroke(p, style, transform=t, tolerance=tol)
        x0, y0, x1, y1 = b.control_box()
        pts = rng.uniform((x0 - 1, y0 - 1), (x1 + 1, y1 + 1), (3000, 2))
        far = boundary_distance(b, pts) > 1e-6
        assert np.array_equal(winding(a, pts[far]) != 0, winding(b, pts[far]) != 0)
        # and the two outlines are close vertex by vertex where they match
        if len(a.points) == len(b.points):
            assert np.allclose(a.points, b.points, atol=1e-9 * max(x1, y1))


@pytest.mark.parametrize('seed', [0, 1])
def test_dashed_paths_equal_single_strokes_to_rounding(seed):
    rng = np.random.default_rng(seed)
    paths = [random_path(rng) for _ in range(30)]
    style = StrokeStyle(width=2, dash=(3.0, 1.5, 0.0, 2.0), dash_offset=1.25, cap='round')
    batch = stroke_many(paths, style, tolerance=0.25)
    for a, p in zip(batch, paths):
        b = stroke(p, style, tolerance=0.25)
        assert np.array_equal(a.verbs, b.verbs)
        assert np.allclose(a.points, b.points, rtol=0, atol=1e-9)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2 ** 32 - 1), st.integers(1, 12),
       st.sampled_from(['miter', 'bevel', 'round']), st.sampled_from(['butt', 'square', 'round']))
def test_polygon_batches_equal_single_strokes(seed, n, join, cap):
    rng = np.random.default_rng(seed)
    paths = polygons_only(rng, n)
    style = StrokeStyle(width=float(rng.uniform(0.1, 20)), join=join, cap=cap)
    t = Affine(*rng.uniform(-2, 2, 4), 5, 7)
    assert_same(stroke_many(paths, style, transforms=[t] * n),
                [stroke(p, style, transform=t) for p in paths], exact=True)


def test_outline_is_split_per_path():
    # two unit-spaced lines: each result holds exactly its own rectangle
    a = Path.polygon([(0, 0), (10, 0)], closed=False)
    b = Path.polygon([(0, 5), (0, 15)], closed=False)
    ra, rb = stroke_many([a, b], StrokeStyle(width=2))
    assert ra.control_box() == (0.0, -1.0, 10.0, 1.0)
    assert rb.control_box() == (-1.0, 5.0, 1.0, 15.0)


def test_degenerate_inputs_give_empty_paths():
    line = Path.polygon([(0, 0), (10, 0)], closed=False)
    assert stroke_many([]) == []
    assert all(p.is_empty for p in stroke_many([line, line], StrokeStyle(width=0)))
    out = stroke_many([line, Path.empty(), line],
                      transforms=[Affine.scale(0), Affine(), Affine.scale(2)])
    assert [len(p.verbs) for p in out] == [0, 0, 5]
    assert out[2] == stroke(line, transform=Affine.scale(2))
    # a lone move draws nothing, alone or in a batch
    lone = parse_path('M 5 5')
    assert [len(p.verbs) for p in stroke_many([lone, line, lone])] == [0, 5, 0]


def test_bad_arguments_raise_stroke_error():
    line = Path.polygon([(0, 0), (10, 0)], closed=False)
    with pytest.raises(StrokeError):
        stroke_many([line, 'M 0 0 L 1 1'])
    with pytest.raises(StrokeError):
        stroke_many([line, line], transforms=[Affine()])
    with pytest.raises(StrokeError):
        stroke_many([line], tolerance=0)
    with pytest.raises(StrokeError):
        stroke_many([line], tolerance=float('nan'))
    with pytest.raises(StrokeError):
        stroke_many([line], style={'width': 2})
    with pytest.raises(RasterError):
        stroke_many([line], transforms=['not a transform'])
    with pytest.raises(LimitError):
        stroke_many([line], transforms=[Affine.scale(1e300)])


@pytest.mark.parametrize('tol', [0.01, 0.1, 1.0])
def test_round_caps_in_batch_honour_tolerance(tol):
    # a round-capped line: the outline's distance from its segment is
    # within tol of the half width (the round cap, a named exact shape)
    rng = np.random.default_rng(2)
    paths = [Path.polygon([p, p + (20, 0)], closed=False) for p in rng.uniform(0, 50, (5, 2))]
    outs = stroke_many(paths, StrokeStyle(width=10, cap='round'), tolerance=tol)
    for p, o in zip(paths, outs):
        a, b = p.points
        q = o.points
        t = np.clip((q[:, 0] - a[0]) / 20.0, 0, 1)
        d = np.hypot(q[:, 0] - (a[0] + 20 * t), q[:, 1] - a[1])
        assert np.all(np.abs(d - 5) <= tol)
        assert np.max(d) > 5 - tol                  # not a degenerate outline


# -- repeated paths: one user-space outline per (path, scale) --------------

def no_sharing(monkeypatch):
    """Disable the grouping of repeated paths (the general path: every path
    gets its own user-space outline)."""
    import raster.geometry.stroking as S

    def distinct(paths, use, scales, translates=True):
        return use, np.arange(len(use)), np.zeros((len(use), 2))
    monkeypatch.setattr(S, '_distinct', distinct)


def repeated_batch(rng, n):
    """``n`` paths drawn from a few random ones (the same objects and equal
    copies) under random transforms sharing few largest scales: translations,
    rotations and reflections of a few scales, one general transform."""
    base = [random_path(rng, kind=int(k)) for k in rng.integers(1, 6, 4)]
    lin = [Affine.scale(2), Affine.rotate(30) @ Affine.scale(2), Affine.scale(-2, 2),
           Affine.scale(3, 1), Affine(*rng.uniform(-2, 2, 4), 0, 0)]
    paths, ts = [], []
    for _ in range(n):
        p = base[int(rng.integers(len(base)))]
        if rng.random() < 0.3:
            p = Path(p.verbs.copy(), p.points.copy(), _checked=True)      # equal copy
        paths.append(p)
        ts.append(Affine.translate(*rng.uniform(-500, 500, 2)) @ lin[int(rng.integers(len(lin)))])
    return paths, ts


@pytest.mark.parametrize('seed', range(4))
@pytest.mark.parametrize('style', [StrokeStyle(width=2), StrokeStyle(width=3, join='round', cap='round'),
                                   StrokeStyle(width=1.5, join='miter-clip', cap='square'),
                                   StrokeStyle(width=2, dash=(3.0, 1.0), cap='round')])
def test_repeated_paths_equal_the_general_path(seed, style, monkeypatch):
    # sharing the user-space outline of equal paths (same largest scale)
    # and mapping it by each path's transform is what the general path
    # computes for each of them, to rounding (flatten_beziers may round a
    # curve differently in another batch); paths of lines: bit for bit
    rng = np.random.default_rng(seed)
    paths, ts = repeated_batch(rng, 60)
    fast = stroke_many(paths, style, transforms=ts, tolerance=0.2)
    one = [Affine.translate(*t.apply(np.zeros((1, 2)))[0]) @ Affine.scale(2) for t in ts]
    fast_one = stroke_many(paths, style, transforms=one, tolerance=0.2)
    with monkeypatch.context() as mp:
        no_sharing(mp)
        assert_same(fast, stroke_many(paths, style, transforms=ts, tolerance=0.2))
        assert_same(fast_one, stroke_many(paths, style, transforms=one, tolerance=0.2))
    polys = [Path.polygon(p.points) if len(p.points) else p for p in paths]
    fast_polys = stroke_many(polys, style, transforms=ts, tolerance=0.2)
    no_sharing(monkeypatch)
    assert_same(fast_polys, stroke_many(polys, style, transforms=ts, tolerance=0.2),
                exact=style.dash is None)
    # and each is the stroke of its path alone
    assert_same(fast, [stroke(p, style, transform=t, tolerance=0.2) for p, t in zip(paths, ts)])


def test_repeated_circle_outline_is_translated_exactly():
    # a circle of 4 cubics stroked at many translations (a scatter plot): each
    # outline is the first one moved by the difference of the offsets, to
    # the rounding of the additions
    circle = parse_path('M2.7 0 C2.7 1.5 1.5 2.7 0 2.7 C-1.5 2.7 -2.7 1.5 -2.7 0 '
                        'C-2.7 -1.5 -1.5 -2.7 0 -2.7 C1.5 -2.7 2.7 -1.5 2.7 0 Z')
    rng = np.random.default_rng(9)
    off = rng.uniform(0, 2000, (500, 2))
    ts = [Affine.translate(*o) @ Affine.scale(2.03) for o in off]
    outs = stroke_many([circle] * len(ts), StrokeStyle(width=2), transforms=ts)
    ref = stroke(circle, width=2, transform=Affine.scale(2.03))
    assert len(ref.verbs) > 20
    for o, d in zip(outs, off):
        assert o.verbs is outs[0].verbs                 # shared, read-only
        assert np.array_equal(o.verbs, ref.verbs)
        assert np.allclose(o.points - d, ref.points, rtol=0, atol=1e-9)
        assert o.points.flags.writeable is False
        assert o == stroke(circle, width=2, transform=Affine.translate(*d) @ Affine.scale(2.03))


def test_distinct_groups_by_content_and_scale():
    from raster.geometry.stroking import _distinct
    a = parse_path('M0 0 L10 0')
    a2 = parse_path('M0 0 L10 0')
    b = parse_path('M0 0 L10 1')
    paths = [a, Path.empty(), a2, b, a, a, b]
    scales = np.array([2.0, 2.0, 2.0, 2.0, 3.0, 2.0, 2.0])
    use = np.array([0, 2, 3, 4, 5, 6])
    rep, inv, shift = _distinct(paths, use, scales)
    assert rep.tolist() == [0, 3, 4]                   # first of each group, in order
    assert inv.tolist() == [0, 0, 1, 2, 0, 1]
    assert not shift.any()
    rep, inv, _ = _distinct([a, b], np.array([0, 1]), np.array([1.0, 1.0]))
    assert rep.tolist() == [0, 1] and inv.tolist() == [0, 1]


def test_distinct_groups_translates():
    # the same shape at other places (a scatter plot's markers) is one
    # group, each with its shift from the first; a shape moved by more than
    # the grid (2**-20 device px) at one point is not
    from raster.geometry.flattening import REPEAT_GRID
    from raster.geometry.stroking import _distinct
    d = 'M{0} {1} C{2} {1} {3} {4} {0} {4} Z'
    paths = [parse_path(d.format(x, y, x + 2.5, x + 3, y + 1.75))
             for x, y in ((0.1, 0.2), (10.37, -4.91), (1e3 / 7, 1e3 / 3), (5.5, 6.5))]
    paths.append(Path(paths[0].verbs, paths[0].points + [0.3, 0.0], _checked=True))
    far = paths[1].points.copy()
    far[2, 0] += 4 * REPEAT_GRID / 2.0                 # 4 grid steps in device px (scale 2)
    paths.append(Path(paths[1].verbs, far, _checked=True))
    use = np.arange(len(paths))
    rep, inv, shift = _distinct(paths, use, np.full(len(paths), 2.0))
    assert rep.tolist() == [0, 5] and inv.tolist() == [0, 0, 0, 0, 0, 1]
    for k in range(5):
        assert np.allclose(shift[k], paths[k].points[0] - paths[0].points[0], rtol=0,
                           atol=1e-12)
    assert not shift[5].any()
    # translates off (dashes cut to a window): equal paths only
    rep, inv, shift = _distinct(paths + [paths[0]], np.arange(len(paths) + 1),
                                np.full(len(paths) + 1, 2.0), translates=False)
    assert rep.tolist() == list(range(len(paths))) and inv[-1] == 0 and not shift.any()


def test_scatter_of_translated_circles_strokes_like_each_alone():
    # circles of one radius at many centres, as the parser builds them:
    # one outline, moved; each within the grid of its own stroke
    from raster.geometry.flattening import REPEAT_GRID
    from raster.geometry.pathdata import ellipse_path
    rng = np.random.default_rng(3)
    cs = rng.uniform(0, 500, (200, 2))
    paths = [ellipse_path(x, y, 3.0, 3.0) for x, y in cs]
    t = Affine.scale(1.7)
    outs = stroke_many(paths, StrokeStyle(width=1.2), transforms=[t] * len(paths))
    assert all(o.verbs is outs[0].verbs for o in outs)
    for p, o in zip(paths, outs):
        alone = stroke(p, StrokeStyle(width=1.2), transform=t)
        assert np.array_equal(o.verbs, alone.verbs)
        assert np.allclose(o.points, alone.points, rtol=0, atol=2 * REPEAT_GRID)


def test_max_scales_are_the_methods_values():
    from raster.geometry.stroking import _max_scales
    rng = np.random.default_rng(4)
    ts = [Affine(*rng.uniform(-3, 3, 6)) for _ in range(50)]
    ts += [Affine.rotate(float(a)) @ Affine.scale(1.7) for a in rng.uniform(0, 360, 20)]
    for group in (ts, ts[:1] * 5, []):
        m = np.array([tuple(t) for t in group]).reshape(-1, 6)
        assert _max_scales(m).tolist() == [t.max_scale() for t in group]


def test_outline_items_drop_empty_runs_and_pool_is_read_once():
    # joins that add no point (most joins inside a flattened curve) are not
    # kept as items; the polygons are the same as with them
    from raster.geometry import stroking
    items = stroking._Items()
    start = items.put(np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]]))
    items.add(np.array([0, 0, 0]), np.array([0, 1, 2]), np.array([start, start, start + 2]),
              np.array([2, 0, 2]))
    assert items.cols[0].shape == (5, 2)
    pts, counts, ids = items.polygons()
    assert counts.tolist() == [4] and ids.tolist() == [0]
    # reversed (positive area, y down): the same four points
    assert sorted(map(tuple, pts.tolist())) == [(0.0, 0.0), (0.0, 3.0), (4.0, 0.0), (4.0, 3.0)]
    assert items.pool == [] and items.npool == 0
