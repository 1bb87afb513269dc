"""Batched geometry in the renderer (flatten_many / coverage_many) gives
the same pixels as drawing every path on its own."""

import numpy as np
import pytest

import importlib
from raster.renderer import batch as batch_mod
from raster.geometry.path import Path
from raster.tree import Fill, Group, PathNode, SolidPaint, Stroke, Tree
from raster.renderer import render_tree
from raster.geometry.transform import Affine
from _geometry import kappa_circle as circle



def scene(seed):
    """Overlapping translucent discs and squares in nested groups with
    transforms, thin (hairline) and thick strokes, one layered group, and
    a shape shared by two parents."""
    rng = np.random.default_rng(seed)
    kids = []
    shared = PathNode(path=circle(0, 0, 3), fill=Fill(SolidPaint((0, 0.5, 0, 0.7))))
    for i in range(60):
        cx, cy = rng.uniform(0, 64, 2)
        col = tuple(rng.uniform(0, 1, 3)) + (float(rng.uniform(0.3, 1)),)
        p = circle(cx, cy, rng.uniform(0.5, 9)) if i % 3 else Path.polygon(
            [[cx, cy], [cx + 7, cy + 1], [cx + 6, cy + 8], [cx - 1, cy + 5]])
        stroke = None
        if i % 4 == 0:
            stroke = Stroke.of(SolidPaint((0, 0, 0, 1)), width=float(rng.choice([0.3, 2.0])))
        kids.append(PathNode(path=p, fill=Fill(SolidPaint(col),
                                               rule=('nonzero', 'evenodd')[i % 2]),
                             stroke=stroke))
    inner = Group(transform=Affine.rotate(20, 32, 32), children=kids[20:40] + [shared])
    layered = Group(opacity=0.5, children=kids[40:50])
    root = Group(children=kids[:20] + [inner, layered, shared] + kids[50:],
                 transform=Affine.scale(1.5))
    return Tree(100, 100, root)


@pytest.mark.parametrize('seed', range(4))
def test_batched_render_equals_unbatched(seed, monkeypatch):
    batched = render_tree(scene(seed)).data.copy()
    monkeypatch.setattr(batch_mod.Masks, 'plan', lambda self, *a, **k: None)
    single = render_tree(scene(seed)).data
    assert np.array_equal(batched, single)


def test_small_batches_change_nothing(monkeypatch):
    ref = render_tree(scene(9)).data.copy()
    monkeypatch.setattr(batch_mod, 'BATCH_VERBS', 7)
    monkeypatch.setattr(batch_mod, 'BATCH_AREA', 400)
    assert np.array_equal(render_tree(scene(9)).data, ref)


def test_filled_hairline_over_a_large_box_is_drawn_apart(monkeypatch):
    # a filled path with a hairline stroke whose box is above BATCH_AREA
    # keeps only its fill in the batch (two box-sized masks are never held
    # together); its hairline is drawn on its own, and the pixels are those
    # of the batched hairline
    big = PathNode(path=Path.polygon([[2.3, 1.7], [97.6, 2.2], [96.8, 98.1], [1.9, 97.4]]),
                   fill=Fill(SolidPaint((0.9, 0.8, 0.1, 1.0))),
                   stroke=Stroke.of(SolidPaint((0.1, 0.1, 0.6, 1.0)), width=0.4))
    small = scene(3).root
    tree = Tree(100, 100, Group(children=[big, small]))
    ref = render_tree(tree).data.copy()
    seen = []
    orig = batch_mod.Masks.plan

    def plan(self, *a, **k):
        orig(self, *a, **k)
        seen.extend(v[5] for v in self._geo_pending.values() if v[0] is big)
    monkeypatch.setattr(batch_mod.Masks, 'plan', plan)
    monkeypatch.setattr(batch_mod, 'BATCH_AREA', 5000)
    got = render_tree(tree).data
    assert seen == [False]                 # the fill queued, not the hairline
    assert np.array_equal(got, ref)


def stroke_scene(seed):
    """Stroked discs, some dashed, under transforms of different scales (so
    stroke_many's shared user-space outlines round differently)."""
    rng = np.random.default_rng(seed)
    kids = []
    for i in range(40):
        cx, cy = rng.uniform(5, 60, 2)
        dash = (3.0, 2.0) if i % 3 == 0 else None
        st = Stroke.of(SolidPaint((0.1, 0.2, 0.9, 0.8)), width=float(rng.uniform(1.2, 4)), dash=dash)
        node = PathNode(path=circle(cx, cy, rng.uniform(1, 8)), stroke=st)
        kids.append(Group(transform=Affine.scale(float(rng.choice([0.8, 1.0, 1.3]))),
                          children=[node]))
    return Tree(100, 100, Group(children=kids))


@pytest.mark.parametrize('seed', range(3))
def test_batched_strokes_match_single_strokes(seed, monkeypatch):
    """Batched stroke outlines equal single ones up to float rounding: the
    8-bit images agree within 1 level everywhere."""
    batched = render_tree(stroke_scene(seed)).to_rgba8().astype(int)
    monkeypatch.setattr(batch_mod.Masks, 'plan', lambda self, *a, **k: None)
    single = render_tree(stroke_scene(seed)).to_rgba8().astype(int)
    assert batched.max() > 0
    assert np.abs(batched - single).max() <= 1


# -- rectangles covering the canvas (backgrounds) ------------------------------

from hypothesis import given, settings, strategies as st  # noqa: E402

from raster import limits  # noqa: E402
from raster.geometry.pathdata import rect_path  # noqa: E402
from raster.pixels.scan import path_coverage  # noqa: E402


@settings(max_examples=150, deadline=None)
@given(st.integers(2, 120), st.integers(2, 120), st.floats(0, 40), st.floats(0, 40),
       st.floats(0, 40), st.floats(0, 40), st.floats(0.1, 4), st.floats(0.1, 4),
       st.sampled_from(['nonzero', 'evenodd']), st.booleans())
def test_a_rectangle_covering_the_canvas_is_covered_everywhere(w, h, l, t, r, b, sx, sy,
                                                               rule, aa):
    # a user-space rectangle from the origin mapped by a scale and a
    # translation (-l, -t) to about [-l, w + r] x [-t, h + b]; the canvas
    # is cut at the whole pixels it reaches: the scan converter's exact
    # coverage is 1 at every pixel, which the batch's shortcut gives
    # without scan converting it
    m = Affine(sx, 0, 0, sy, -l, -t)
    p = rect_path(0, 0, (w + r + l) / sx, (h + b + t) / sy)
    x1, y1 = m.apply(p.points[2:3])[0]
    cw, ch = int(np.floor(x1)), int(np.floor(y1))
    assert batch_mod.covers_canvas(p, m, cw, ch)
    assert not batch_mod.covers_canvas(p, m, cw + 1, ch) or x1 >= cw + 1
    scanned = path_coverage(p, cw, ch, rule, aa, transform=m, straddle=True).full(cw, ch)
    shortcut = batch_mod.full_mask(cw, ch).full(cw, ch)
    np.testing.assert_array_equal(scanned, shortcut)


def test_what_does_not_cover_the_canvas_is_scan_converted():
    w, h = 20, 10
    ident = Affine(1, 0, 0, 1, 0, 0)
    assert batch_mod.covers_canvas(rect_path(0, 0, 20, 10), ident, w, h)
    assert not batch_mod.covers_canvas(rect_path(0, 0, 19.5, 10), ident, w, h)   # a column short
    assert not batch_mod.covers_canvas(rect_path(0.1, 0, 20, 10), ident, w, h)   # edge inside
    assert not batch_mod.covers_canvas(rect_path(0, 0, 20, 10),
                                       Affine.rotate(0.1), w, h)                  # not axis-aligned
    assert not batch_mod.covers_canvas(rect_path(-5, -5, 30, 20, rx=2), ident, w, h)  # rounded
    bowtie = Path(np.array([0, 1, 1, 1, 4], np.uint8),
                  np.array([[-1, -1], [30, -1], [-1, 20], [30, 20]], float))
    assert not batch_mod.covers_canvas(bowtie, ident, w, h)                      # sides cross
    with limits.applied(limits.Limits(max_coord=25)):
        # beyond max_coord the scan converter refuses it: so does the shortcut
        assert not batch_mod.covers_canvas(rect_path(-30, -30, 60, 60), ident, w, h)
    # a window's canvas lying at (ox, oy) in its frame: covered when the
    # rectangle contains that part of the frame, whatever lies outside it
    assert batch_mod.covers_canvas(rect_path(30, 5, 20, 10), ident, w, h, 30, 5)
    assert not batch_mod.covers_canvas(rect_path(30, 5, 20, 10), ident, w, h, 31, 5)
    assert not batch_mod.covers_canvas(rect_path(30, 5, 20, 10), ident, w, h, 30, 4)
    assert not batch_mod.covers_canvas(rect_path(30, 5, 20, 10), ident, w, h)


def test_a_background_renders_as_scan_converted():
    # the same document with the background scan converted (a rectangle a
    # hair inside the canvas on the right is not covering: drawn by the
    # scan converter; the covering one by the shortcut) gives the same pixels
    # where both cover
    def doc(width):
        bg = PathNode(path=rect_path(0, 0, width, 30), fill=Fill(SolidPaint((0.2, 0.4, 0.6, 0.8))))
        disc = PathNode(path=circle(20, 15, 9), fill=Fill(SolidPaint((1, 0, 0, 0.5))))
        return Tree(40, 30, Group(children=[bg, disc]))
    a = render_tree(doc(40), dtype='uint8').to_rgba8()
    old = batch_mod.covers_canvas
    try:
        batch_mod.covers_canvas = lambda *args: False
        b = render_tree(doc(40), dtype='uint8').to_rgba8()
    finally:
        batch_mod.covers_canvas = old
    np.testing.assert_array_equal(a, b)


@settings(max_examples=150, deadline=None)
@given(st.lists(st.sampled_from([-3.0, -0.5, 0.0, 7.0, 8.0, 8.25, 12.0]), min_size=8, max_size=8),
       st.sampled_from([(1, 0, 0, 1), (0, 1, 1, 0), (-1, 0, 0, 2), (0.5, 0, 0, -1)]),
       st.sampled_from([0.0, 0.5, 4.0]))
def test_property_the_shortcut_claims_only_full_coverage(xy, abcd, shift):
    # four corners from a few values (many axis-aligned, some crossed or
    # degenerate) under axis-preserving maps: where the batch's shortcut
    # claims the canvas covered, the exact coverage is 1 everywhere, and an
    # axis-aligned rectangle whose coverage is 1 everywhere is claimed
    pts = np.array(xy, float).reshape(4, 2)
    p = Path(np.array([0, 1, 1, 1, 4], np.uint8), pts)
    m = Affine(*abcd, shift, -shift)
    w, h = 6, 5
    claimed = batch_mod.covers_canvas(p, m, w, h)
    mask = path_coverage(p, w, h, 'nonzero', True, transform=m)
    full = mask is not None and mask.box == (0, 0, w, h) and bool((mask.data == 1).all())
    if claimed:
        assert full
    q = m.apply(pts)
    rect = all((q[i, 0] == q[i - 3, 0]) != (q[i, 1] == q[i - 3, 1]) for i in range(4)) and \
        len(set(q[:, 0])) == 2 and len(set(q[:, 1])) == 2
    if rect and full:
        assert claimed


# -- solid fills composited together (Renderer.settle, Canvas.fill_many) --------
from raster.renderer import draw as draw_mod  # noqa: E402
from raster.svg import load_svg  # noqa: E402


def fills_svg(seed, n=160):
    """Overlapping translucent and opaque polygons (both fill rules, some
    self-intersecting), some stroked, some in groups clipped by a
    rectangle (ClipRect views) or by a circle (a layer), and a gradient
    between them."""
    rng = np.random.default_rng(seed)
    parts = ['<svg xmlns="http://www.w3.org/2000/svg" width="160" height="120">',
             '<defs><clipPath id="r">'
             '<rect x="20.3" y="15.7" width="90.5" height="70.2"/></clipPath>',
             '<clipPath id="c"><circle cx="80" cy="60" r="45"/></clipPath>',
             '<linearGradient id="g"><stop offset="0" stop-color="red"/>'
             '<stop offset="1" stop-color="blue"/></linearGradient></defs>']
    for i in range(n):
        if i % 40 == 0:
            parts.append('<g clip-path="url(#%s)">' % ('r' if i % 80 == 0 else 'c'))
        pts = rng.random((int(rng.integers(3, 7)), 2)) * (40, 30) + rng.random(2) * (150, 110) - 10
        d = 'M' + 'L'.join('%.2f,%.2f' % tuple(p) for p in pts) + 'Z'
        fill = 'url(#g)' if i % 37 == 5 else 'rgb(%d,%d,%d)' % tuple(rng.integers(0, 256, 3))
        extra = (' stroke="black" stroke-width="%.2f"' % (0.3 + 2 * rng.random())
                 if i % 3 == 0 else '')
        parts.append('<path d="%s" fill="%s" fill-opacity="%.2f" fill-rule="%s"%s/>'
                     % (d, fill, rng.choice([1.0, 0.5, 0.8]),
                        'evenodd' if i % 2 else 'nonzero', extra))
        if i % 40 == 39:
            parts.append('</g>')
    parts.append('</svg>')
    return ''.join(parts).encode()


@pytest.mark.parametrize('seed', range(3))
@pytest.mark.parametrize('dtype', ['float32', 'uint8'])
def test_fills_composited_together_equal_one_by_one(seed, dtype, monkeypatch):
    tree = load_svg(fills_svg(seed))
    together = render_tree(tree, width=320, dtype=dtype).data
    monkeypatch.setattr(draw_mod, 'MANY_MASK_PIXELS', -1)     # nothing held
    alone = render_tree(tree, width=320, dtype=dtype).data
    assert np.array_equal(together, alone)


@pytest.mark.parametrize('window', [None, (0, 0, 100, 60)])
def test_a_layer_between_paths_keeps_the_later_paths_batched(monkeypatch, window):
    # a layered group drawn between paths of the output has its own queue:
    # flushing it leaves the output's later paths queued, so they are
    # scan converted in a batch, not one by one (same pixels either way)
    def square(x, y, s, colour):
        return PathNode(path=Path.polygon([[x, y], [x + s, y + 0.3], [x + s, y + s],
                                           [x, y + s]]),
                        fill=Fill(SolidPaint(colour)),
                        stroke=Stroke.of(SolidPaint((0.2, 0.2, 0.2, 1.0)), width=2.5))
    before = [square(5 + 9 * i, 5, 7.5, (0.9, 0.2, 0.1, 1.0)) for i in range(3)]
    layer = Group(children=[square(40.5, 30.5, 20, (0.1, 0.5, 0.9, 1.0))], opacity=0.5)
    after = [square(5 + 9 * i, 50.2, 7.5, (0.1, 0.8, 0.3, 1.0)) for i in range(8)]
    tree = Tree(100, 100, Group(children=before + [layer] + after))
    ref = render_tree(tree, window=window).data.copy()
    single = []
    one = batch_mod.coverage

    def counted(*a, **k):
        single.append(1)
        return one(*a, **k)
    monkeypatch.setattr(batch_mod, 'coverage', counted)
    # (batches of a few paths: the output's later paths are still queued
    # when the layer is drawn)
    monkeypatch.setattr(batch_mod, 'BATCH_VERBS', 12)
    got = render_tree(tree, window=window).data
    assert single == []
    assert np.array_equal(got, ref)
    # and each path drawn on its own gives the same pixels
    monkeypatch.setattr(batch_mod, 'BATCH_VERBS', 1)
    monkeypatch.setattr(batch_mod, 'BATCH_AREA', 1)
    assert np.abs(render_tree(tree, window=window).data - ref).max() <= 1e-6


def test_a_long_stroke_is_scan_converted_with_only_its_edges_live(monkeypatch):
    """A path of 200 random cubics stroked 1.5 px (its outline crosses
    itself everywhere): when the batch's coverage starts, what the render
    holds beyond the canvas is the edges (the outline, its polylines and
    the per-edge owners are gone)."""
    import tracemalloc
    from raster.svg import load_svg
    rng = np.random.default_rng(0)
    w = 500
    d = 'M250 250' + ''.join('C%.2f %.2f %.2f %.2f %.2f %.2f' % tuple(q)
                             for q in rng.uniform(0, w, (200, 6)))
    tree = load_svg(('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d">'
                     '<path fill="none" stroke="#000" stroke-width="1.5" d="%s"/></svg>'
                     % (w, w, d)).encode())
    seen = []
    real = batch_mod.coverage_batch

    def probe(e, counts, *args, **kw):
        seen.append((tracemalloc.get_traced_memory()[0], e.nbytes))
        return real(e, counts, *args, **kw)
    monkeypatch.setattr(batch_mod, 'coverage_batch', probe)
    render_tree(tree, dtype='uint8')                # (warm)
    seen.clear()
    tracemalloc.start()
    try:
        base = tracemalloc.get_traced_memory()[0]
        render_tree(tree, dtype='uint8')
    finally:
        tracemalloc.stop()
    assert len(seen) == 1
    live, edge_bytes = seen[0]
    assert edge_bytes > 400_000
    assert live - base - 4 * w * w - edge_bytes <= 0.1 * edge_bytes + 32_000
