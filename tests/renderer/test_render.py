"""raster.renderer on hand-built resolved trees (no SVG parsing involved)."""

import importlib
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.errors import CanvasError, SVGError
from raster.geometry.path import Path
from raster.geometry.pens import PathBuilder
from raster.geometry.transform import Affine
from raster.renderer import output_size, render_tree
from raster.renderer import paint as paint_mod
from raster.tree import (ClipPath, Fill, GradientStop, Group, ImageNode, LinearGradient, Mask,
                             PathNode, Pattern, RadialGradient, SolidPaint, Stroke, Tree)
from _geometry import kappa_circle as circle

import raster.renderer as renderer_pkg
from raster.renderer import batch as batch_mod, draw as draw_mod
from raster.pixels.hairline import hairline_edges
from raster.geometry.flattening import flatten

RED = SolidPaint((1.0, 0.0, 0.0, 1.0))
BLUE = SolidPaint((0.0, 0.0, 1.0, 1.0))
WHITE = SolidPaint((1.0, 1.0, 1.0, 1.0))


def rect(x, y, w, h):
    return Path.polygon([(x, y), (x + w, y), (x + w, y + h), (x, y + h)])



def filled(path, paint=RED, **kw):
    return PathNode(path=path, fill=Fill(paint, **kw))


def tree(*children, w=20, h=20, **group):
    return Tree(w, h, Group(children=list(children), **group))


def alpha(canvas):
    return canvas.data[..., 3].astype(np.float64)


# -- output size -------------------------------------------------------------------

@pytest.mark.parametrize('kw,size', [({}, (40, 20)), ({'width': 80}, (80, 40)),
                                     ({'height': 10}, (20, 10)),
                                     ({'width': 10, 'height': 30}, (10, 30)),
                                     ({'zoom': 0.5}, (20, 10))])
def test_output_sizes(kw, size):
    c = render_tree(tree(w=40, h=20), **kw)
    assert (c.width, c.height) == size and c.data.shape == (size[1], size[0], 4)


def test_natural_size_rounds_half_up():
    # resvg's natural size (see tests/test_output_size.py)
    assert output_size(10.2, 4.5)[:2] == (10, 5)


@pytest.mark.parametrize('kw', [{'width': 0}, {'height': -5}, {'zoom': 0}, {'zoom': float('nan')},
                                {'width': 10, 'zoom': 2}, {'width': 200_000},
                                {'width': 20_000, 'height': 20_000}, {'tolerance': 0},
                                {'width': 2.5}])
def test_bad_sizes_raise_canvas_error(kw):
    with pytest.raises(CanvasError):
        render_tree(tree(), **kw)


def test_not_a_tree():
    with pytest.raises(SVGError):
        render_tree('<svg/>')


# -- fills ------------------------------------------------------------------------------

def test_pixel_aligned_square_is_exact():
    c = render_tree(tree(filled(rect(5, 5, 10, 10))))
    img = c.data
    assert np.all(img[5:15, 5:15] == np.float32([1, 0, 0, 1]))
    assert alpha(c).sum() == 100.0


def test_square_scaled_to_width():
    """Rendering at 3x maps the 10x10 square onto a 30x30 block."""
    c = render_tree(tree(filled(rect(5, 5, 10, 10))), width=60)
    assert alpha(c).sum() == pytest.approx(900.0)
    assert c.data[15:45, 15:45, 3].min() == 1.0


@pytest.mark.parametrize('tol', [0.5, 0.1, 0.01])
def test_circle_area_within_tolerance(tol):
    """Area of a circle r = 8: the flattening error moves the boundary by at
    most ``tol`` px, so the area is within perimeter * tol of pi r^2 (the
    four-cubic circle itself differs from a true circle by < 0.03 %)."""
    r = 8.0
    c = render_tree(tree(filled(circle(10, 10, r))), tolerance=tol)
    area = alpha(c).sum()
    assert abs(area - math.pi * r * r) <= 2 * math.pi * r * tol + 0.02 * r * r * 0.03 + 0.05


def test_integer_translation_invariance():
    base = tree(filled(circle(8.3, 7.7, 5.1)))
    moved = tree(Group(transform=Affine.translate(3, 2), children=[filled(circle(8.3, 7.7, 5.1))]))
    a = render_tree(base).data
    b = render_tree(moved).data
    assert np.allclose(b[2:, 3:], a[:-2, :-3], atol=1e-6)


def test_fill_rules_on_doubled_square():
    """A square traced twice in the same direction: nonzero fills it,
    evenodd leaves it empty."""
    sq = rect(4, 4, 8, 8)
    twice = Path.concat([sq, sq])
    nz = render_tree(tree(filled(twice, rule='nonzero')))
    eo = render_tree(tree(filled(twice, rule='evenodd')))
    assert alpha(nz).sum() == pytest.approx(64.0)
    assert alpha(eo).sum() == pytest.approx(0.0)


def test_fill_opacity_and_background():
    c = render_tree(tree(filled(rect(0, 0, 10, 20), opacity=0.5)), background=(1, 1, 1, 1))
    assert np.allclose(c.data[5, 5], [1.0, 0.5, 0.5, 1.0])
    assert np.allclose(c.data[5, 15], [1, 1, 1, 1])


def test_antialias_off_gives_binary_coverage():
    n = PathNode(path=circle(10, 10, 6.3), fill=Fill(RED), antialias=False)
    a = alpha(render_tree(tree(n)))
    assert set(np.unique(a)) <= {0.0, 1.0}


# -- strokes ------------------------------------------------------------------------

def line(x0, y0, x1, y1):
    return Path.polygon([(x0, y0), (x1, y1)], closed=False)


def test_butt_stroke_area():
    """A 16 px line stroked 2 wide with butt caps covers 32 px^2."""
    n = PathNode(path=line(2, 10, 18, 10), stroke=Stroke.of(RED, width=2))
    assert alpha(render_tree(tree(n))).sum() == pytest.approx(32.0)


def test_stroke_width_scales_with_transform():
    n = PathNode(path=line(1, 5, 9, 5), stroke=Stroke.of(RED, width=1))
    t = tree(Group(transform=Affine.scale(2), children=[n]))
    assert alpha(render_tree(t)).sum() == pytest.approx(16 * 2)


@pytest.mark.parametrize('width', [0.5, 0.25])
def test_hairline_keeps_average_darkness(width):
    """A stroke thinner than a pixel is drawn 1 px wide with coverage scaled
    by its width: the total coverage still equals length * width."""
    n = PathNode(path=line(2, 10.5, 18, 10.5), stroke=Stroke.of(RED, width=width))
    a = alpha(render_tree(tree(n)))
    assert a.sum() == pytest.approx(16 * width, rel=1e-5)
    assert a.max() == pytest.approx(width)          # one row, never broken up


def test_paint_order():
    """The stroke's inner half shows the stroke colour when the stroke is
    painted last, the fill colour when the fill is painted last."""
    sq = rect(5, 5, 10, 10)
    normal = PathNode(path=sq, fill=Fill(BLUE), stroke=Stroke.of(RED, width=4))
    reverse = PathNode(path=sq, fill=Fill(BLUE), stroke=Stroke.of(RED, width=4),
                       paint_order=('stroke', 'fill', 'markers'))
    a = render_tree(tree(normal)).data
    b = render_tree(tree(reverse)).data
    assert np.allclose(a[10, 6], [1, 0, 0, 1]) and np.allclose(b[10, 6], [0, 0, 1, 1])
    assert np.allclose(a[10, 4], [1, 0, 0, 1]) and np.allclose(b[10, 4], [1, 0, 0, 1])


def test_markers_group_drawn_with_node():
    dot = filled(rect(0, 0, 2, 2), BLUE)
    n = PathNode(path=line(2, 10, 18, 10), stroke=Stroke.of(RED, width=1),
                 markers=Group(transform=Affine.translate(17, 9), children=[dot]))
    c = render_tree(tree(n)).data
    assert np.allclose(c[9, 17], [0, 0, 1, 1])


# -- hairlines (device width < 1 px: drawn 1 px wide, coverage scaled) --------------

def _l_path():
    b = PathBuilder()
    b.moveTo((2, 5))
    b.lineTo((15, 5))
    b.lineTo((15, 15))
    return b.path()


@pytest.mark.parametrize('join,cap,area', [
    # 1 px wide L: rectangles of 13 and 10 px^2, + 0.25 outer miter square
    # (miter) or + 0.125 bevel triangle; square caps add 2 x 0.5 x 1.  The
    # 0.25 px^2 where the rectangles overlap inside the turn counts twice:
    # hairline coverage is the sum of the pieces' areas per pixel, clipped
    # to 1 (as a renderer drawing one segment at a time blends it twice)
    ('miter', 'butt', 23.25), ('bevel', 'butt', 23.125),
    ('miter', 'square', 24.25), ('bevel', 'square', 24.125)])
def test_hairline_l_shape_area(join, cap, area):
    n = PathNode(path=_l_path(), stroke=Stroke.of(RED, width=0.5, join=join, cap=cap))
    a = alpha(render_tree(tree(n)))
    assert a.sum() == pytest.approx(0.5 * area, abs=1e-6)
    assert a[5, 8] == pytest.approx(0.25)          # row 4.5..5.5 half in row 5


def test_hairline_miter_limit_falls_back_to_bevel():
    """The L turns by 90 degrees: miter ratio sqrt(2) > limit 1.2: bevel."""
    n = PathNode(path=_l_path(), stroke=Stroke.of(RED, width=0.5, miterlimit=1.2))
    assert alpha(render_tree(tree(n))).sum() == pytest.approx(0.5 * 23.125, abs=1e-6)


@pytest.mark.parametrize('seed', range(6))
@pytest.mark.parametrize('join', ['miter', 'bevel'])
def test_hairline_matches_general_stroker_on_convex_polygons(seed, join):
    """Invariance: on a convex polygon (no spikes) the hairline outline
    (union of segment rectangles and join triangles) covers exactly what the
    general stroker's 1 px wide outline covers."""
    from raster.geometry.hull import convex_hull
    from raster.pixels.scan import coverage, path_coverage
    from raster.geometry.stroking import StrokeStyle, stroke as stroke_outline
    rng = np.random.default_rng(seed)
    pts = np.asarray(convex_hull(rng.uniform(3, 37, (12, 2))))
    path = Path.polygon(pts)
    pl = flatten(path, 0.25)
    e = hairline_edges(pl, 'butt', join, 4.0)
    a = coverage(e, 40, 40).full(40, 40)
    o = stroke_outline(path, StrokeStyle(width=1.0, join=join, miterlimit=4.0))
    b = path_coverage(o, 40, 40, 'nonzero', True, tolerance=0.25).full(40, 40)
    assert np.abs(a - b).max() < 1e-6


@pytest.mark.parametrize('tol', [0.02, 0.1, 0.5])
def test_hairline_circle_area_within_tolerance(tol):
    """Hairline (width 0.5) on the circle r = 8: the 1 px annulus has area
    2 pi r; the flattened circle is within ``tol`` of it, so the area is
    within (perimeter x tol) of it; coverage is scaled by 0.5."""
    n = PathNode(path=circle(10, 10, 8), stroke=Stroke.of(RED, width=0.5))
    a = alpha(render_tree(tree(n), tolerance=tol)).sum()
    assert abs(a - 0.5 * 2 * math.pi * 8) <= 0.5 * 2 * math.pi * 8.5 * tol + 1e-3


@pytest.mark.parametrize('cap,area', [('butt', 0.0), ('round', math.pi / 4), ('square', 1.0)])
def test_hairline_zero_length_subpath_dot(cap, area):
    """A zero-length subpath draws a cap-shaped dot (disc of diameter 1 px,
    or a 1 px square) at the hairline's coverage factor 0.5; butt: nothing."""
    b = PathBuilder()
    b.moveTo((5, 5))
    b.lineTo((5, 5))
    n = PathNode(path=b.path(), stroke=Stroke.of(RED, width=0.5, cap=cap))
    assert alpha(render_tree(tree(n))).sum() == pytest.approx(0.5 * area, abs=2e-3)


def test_filled_hairline_path_is_flattened_once(monkeypatch):
    calls = []
    orig = batch_mod.flatten
    monkeypatch.setattr(batch_mod, 'flatten', lambda *a, **k: calls.append(1) or orig(*a, **k))
    # the renderer may flatten in batches: a batch call counts once per path
    orig_joined = batch_mod.flatten_joined
    monkeypatch.setattr(batch_mod, 'flatten_joined',
                        lambda paths, *a, **k: calls.extend([1] * len(paths))
                        or orig_joined(paths, *a, **k))
    n = PathNode(path=circle(10, 10, 8), fill=Fill(BLUE), stroke=Stroke.of(RED, width=0.5))
    c = render_tree(tree(n)).data
    assert len(calls) == 1 and c[10, 10, 2] == pytest.approx(1.0)


# -- groups and layers --------------------------------------------------------------

def test_group_opacity_uses_a_layer():
    """Two overlapping opaque squares in a group of opacity 0.5: the overlap
    is 0.5 alpha (a layer), not 0.75 (per-shape opacity)."""
    g = Group(opacity=0.5, children=[filled(rect(2, 2, 10, 10)), filled(rect(6, 6, 10, 10), BLUE)])
    c = render_tree(tree(g)).data
    assert c[8, 8, 3] == pytest.approx(0.5)
    assert np.allclose(c[8, 8], [0, 0, 0.5, 0.5])
    assert c[3, 3, 3] == pytest.approx(0.5)


def test_layer_covers_only_the_group_box(monkeypatch):
    sizes = []
    orig = draw_mod.Canvas

    def spy(w, h, *a, **k):
        sizes.append((w, h))
        return orig(w, h, *a, **k)
    monkeypatch.setattr(draw_mod, 'Canvas', spy)
    monkeypatch.setattr(renderer_pkg, 'Canvas', draw_mod.Canvas)
    g = Group(opacity=0.5, children=[filled(rect(100, 100, 10, 5))])
    render_tree(Tree(400, 400, Group(children=[g])))
    assert sizes[0] == (400, 400)
    assert all(w <= 12 and h <= 7 for w, h in sizes[1:]) and len(sizes) == 2


def test_group_outside_canvas_allocates_nothing(monkeypatch):
    sizes = []
    orig = draw_mod.Canvas
    monkeypatch.setattr(draw_mod, 'Canvas', lambda w, h, *a, **k: sizes.append((w, h)) or
                        orig(w, h, *a, **k))
    monkeypatch.setattr(renderer_pkg, 'Canvas', draw_mod.Canvas)
    g = Group(opacity=0.5, children=[filled(rect(-50, -50, 10, 10))])
    c = render_tree(tree(g))
    assert len(sizes) == 1 and alpha(c).sum() == 0


def test_transform_only_group_composes():
    g = Group(transform=Affine.translate(5, 0) @ Affine.scale(2),
              children=[filled(rect(0, 0, 2, 2))])
    a = alpha(render_tree(tree(g)))
    assert a.sum() == 16 and a[0:4, 5:9].min() == 1.0


def test_clip_path_halves_square():
    clip = ClipPath(root=Group(children=[filled(rect(0, 0, 10, 20), SolidPaint((0, 1, 0, 1)))]))
    g = Group(clip_path=clip, children=[filled(rect(5, 5, 10, 10))])
    c = render_tree(tree(g))
    assert alpha(c).sum() == pytest.approx(50.0)
    assert np.allclose(c.data[7, 7], [1, 0, 0, 1])          # clip colour is irrelevant


def test_clip_path_transform_and_nested_clip():
    inner = ClipPath(root=Group(children=[filled(rect(0, 0, 20, 8))]))
    clip = ClipPath(root=Group(children=[filled(rect(0, 0, 5, 20))]),
                    transform=Affine.scale(2), clip_path=inner)
    g = Group(clip_path=clip, children=[filled(rect(0, 0, 20, 20))])
    assert alpha(render_tree(tree(g))).sum() == pytest.approx(10 * 8)


@pytest.mark.parametrize('kind,paint,expect', [
    ('luminance', WHITE, 1.0), ('luminance', SolidPaint((0, 0, 0, 1)), 0.0),
    ('luminance', SolidPaint((1, 1, 1, 0.5)), 0.5), ('alpha', SolidPaint((0, 0, 0, 0.25)), 0.25)])
def test_mask_kinds(kind, paint, expect):
    m = Mask(rect=(0, 0, 20, 20), root=Group(children=[filled(rect(0, 0, 20, 20), paint)]),
             kind=kind)
    g = Group(mask=m, children=[filled(rect(5, 5, 10, 10))])
    c = render_tree(tree(g)).data
    assert c[10, 10, 3] == pytest.approx(expect, abs=1e-6)


def test_mask_rect_limits_the_mask():
    m = Mask(rect=(0, 0, 10, 20), root=Group(children=[filled(rect(0, 0, 20, 20), WHITE)]))
    g = Group(mask=m, children=[filled(rect(0, 0, 20, 20))])
    assert alpha(render_tree(tree(g))).sum() == pytest.approx(200.0)


# -- node_id -------------------------------------------------------------------------

def test_node_id_renders_subtree_with_ancestor_transforms():
    a = filled(rect(0, 0, 4, 4)); a.id = 'a'
    b = filled(rect(10, 10, 4, 4), BLUE); b.id = 'b'
    g = Group(transform=Affine.translate(2, 3), children=[a, b])
    t = Tree(20, 20, Group(children=[g]), ids={'a': a, 'b': b})
    c = render_tree(t, node_id='a').data
    assert c[..., 3].sum() == 16 and c[3:7, 2:6, 3].min() == 1.0
    with pytest.raises(SVGError):
        render_tree(t, node_id='nope')


# -- paints ---------------------------------------------------------------------------

def test_linear_gradient_user_space():
    grad = LinearGradient(0, 0, 20, 0, [GradientStop(0, (1, 0, 0, 1)), GradientStop(1, (0, 0, 1, 1))])
    c = render_tree(tree(filled(rect(0, 0, 20, 20), grad))).data
    # pixel centre x = 10.5 -> t = 0.525
    assert np.allclose(c[3, 10], [0.475, 0, 0.525, 1], atol=1e-5)
    assert np.allclose(c[3, 0], [0.975, 0, 0.025, 1], atol=1e-5)


def _svg_tree(body, w=20, h=20):
    from raster.svg import load_svg
    return load_svg(('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d">%s</svg>'
                     % (w, h, body)).encode())


def test_linear_gradient_bbox_units_and_pad():
    t = _svg_tree('<linearGradient id="g" x1="0.25" x2="0.75"><stop stop-color="red"/>'
                  '<stop offset="1" stop-color="blue"/></linearGradient>'
                  '<rect width="20" height="20" fill="url(#g)"/>')
    c = render_tree(t).data
    assert np.allclose(c[5, 1], [1, 0, 0, 1]) and np.allclose(c[5, 18], [0, 0, 1, 1])


@pytest.mark.parametrize('spread,expect', [('pad', 1.0), ('repeat', 0.25), ('reflect', 0.75)])
def test_gradient_spread(spread, expect):
    """Stops 0 -> 1 of the blue channel over x in [0, 8]; the pixel centred
    at x = 10 (s = 1.25) gets blue 1 (pad), 0.25 (repeat), 0.75 (reflect)."""
    grad = LinearGradient(-0.5, 0, 7.5, 0, [GradientStop(0, (0, 0, 0, 1)), GradientStop(1, (0, 0, 1, 1))],
                          spread=spread)
    c = render_tree(tree(filled(rect(0, 0, 20, 20), grad))).data
    assert c[2, 9, 2] == pytest.approx(expect, abs=1e-5)


def test_hard_stop():
    grad = LinearGradient(0, 0, 20, 0, [GradientStop(0, (1, 0, 0, 1)), GradientStop(0.5, (1, 0, 0, 1)),
                                        GradientStop(0.5, (0, 0, 1, 1)), GradientStop(1, (0, 0, 1, 1))])
    c = render_tree(tree(filled(rect(0, 0, 20, 20), grad))).data
    assert np.allclose(c[1, 9], [1, 0, 0, 1]) and np.allclose(c[1, 10], [0, 0, 1, 1])


def test_radial_gradient_is_radial():
    """Centred radial gradient: colour depends on the distance only; at
    distance d the blue channel is d / r."""
    grad = RadialGradient(10, 10, 8, 10, 10, [GradientStop(0, (0, 0, 0, 1)),
                                              GradientStop(1, (0, 0, 1, 1))])
    c = render_tree(tree(filled(rect(0, 0, 20, 20), grad))).data
    d = math.hypot(13.5 - 10, 10.5 - 10)
    assert c[10, 13, 2] == pytest.approx(d / 8, abs=1e-5)
    assert c[13, 10, 2] == pytest.approx(c[10, 13, 2], abs=1e-6)
    assert c[0, 0, 2] == pytest.approx(1.0)


def test_unsupported_paint_is_skipped():
    c = render_tree(tree(filled(rect(0, 0, 20, 20), object()), filled(rect(0, 0, 5, 5))))
    assert alpha(c).sum() == 25


def test_pattern_tiles_user_space():
    """4x4 tiles each holding a 2x2 red square: a quarter of the area, and
    the square repeats every 4 px."""
    pat = Pattern(rect=(0, 0, 4, 4), root=Group(children=[filled(rect(0, 0, 2, 2))]))
    c = render_tree(tree(filled(rect(0, 0, 20, 20), pat)))
    a = alpha(c)
    assert a.sum() == pytest.approx(100.0, abs=0.5)
    assert np.allclose(c.data[9, 9], [1, 0, 0, 1], atol=1e-3)       # tile (2, 2) at 8..10
    assert a[10, 10] == pytest.approx(0.0, abs=1e-3)


def test_pattern_bbox_units():
    """Tile = a quarter of the bbox in each direction (objectBoundingBox)."""
    c = render_tree(_svg_tree('<pattern id="p" width="0.25" height="0.25">'
                              '<rect width="2.5" height="2.5" fill="red"/></pattern>'
                              '<rect width="20" height="20" fill="url(#p)"/>'))
    assert alpha(c).sum() == pytest.approx(100.0, abs=0.5)
    assert c.data[1, 6, 3] == pytest.approx(1.0, abs=1e-3) and c.data[3, 3, 3] == pytest.approx(0)


@pytest.mark.parametrize('mode,src,expect', [
    ('multiply', (0, 0, 1, 1), (0, 0, 0.5)), ('screen', (0, 0, 1, 1), (0.5, 0.5, 1)),
    ('difference', (1, 1, 1, 1), (0.5, 0.5, 0.5)), ('darken', (1, 1, 0, 1), (0.5, 0.5, 0)),
    ('lighten', (1, 1, 0, 1), (1, 1, 0.5)), ('luminosity', (1, 1, 1, 1), (1, 1, 1)),
    ('normal', (0, 0, 1, 1), (0, 0, 1))])
def test_blend_modes_over_grey(mode, src, expect):
    g = Group(blend_mode=mode, children=[filled(rect(0, 0, 20, 20), SolidPaint(src))])
    c = render_tree(tree(g), background=(0.5, 0.5, 0.5, 1)).data
    assert np.allclose(c[5, 5], list(expect) + [1], atol=1e-5)


@pytest.mark.parametrize('par,area,red_at,empty_at', [
    (None, 100.0, (5, 10), (5, 2)),                     # xMidYMid meet: x 5..15
    (('none', 'meet'), 200.0, (5, 2), None),             # stretched over the tile
    (('xMinYMin', 'meet'), 100.0, (5, 2), (5, 15)),      # x 0..10
    (('xMaxYMax', 'meet'), 100.0, (5, 15), (5, 2)),      # x 10..20
    (('xMinYMin', 'slice'), 200.0, (5, 2), None)])       # scale 2, cropped
def test_pattern_bbox_units_viewbox_aspect_ratio(par, area, red_at, empty_at):
    """objectBoundingBox tile = the whole 20 x 10 bbox; a 10 x 10 viewBox
    holding a full red square is mapped onto it per preserveAspectRatio."""
    attr = '' if par is None else ' preserveAspectRatio="%s %s"' % par
    c = render_tree(_svg_tree('<pattern id="p" width="1" height="1" viewBox="0 0 10 10"%s>'
                              '<rect width="10" height="10" fill="red"/></pattern>'
                              '<rect width="20" height="10" fill="url(#p)"/>' % attr, 20, 10))
    assert alpha(c).sum() == pytest.approx(area, abs=0.5)
    assert c.data[red_at][3] == pytest.approx(1.0, abs=1e-3)
    if empty_at is not None:
        assert c.data[empty_at][3] == pytest.approx(0.0, abs=1e-3)


# Non-separable modes (Compositing 1, section 10.2), worked by hand with
# Lum = 0.3 R + 0.59 G + 0.11 B.  Backdrop Cb = (0.2, 0.4, 0.6): Lum 0.362,
# Sat 0.4.
#   hue        SetLum(SetSat(Cs, Sat(Cb)), Lum(Cb)), Cs red: SetSat -> (0.4, 0, 0),
#              Lum 0.12, + 0.242 -> (0.642, 0.242, 0.242)
#   saturation SetLum(SetSat(Cb, Sat(Cs)), Lum(Cb)), Cs (0.5, 0.5, 0.6), Sat 0.1:
#              SetSat -> (0, 0.05, 0.1), Lum 0.0405, + 0.3215
#   color      SetLum(Cs, Lum(Cb)), Cs red: (1.062, 0.062, 0.062) is above 1, so
#              ClipColor: L + (C - L)(1 - L)/(max - L) -> (1, 0.08857..., 0.08857...)
#   luminosity SetLum(Cb, Lum(Cs)), Cs grey 0.5: + 0.138
CB = (0.2, 0.4, 0.6, 1)


@pytest.mark.parametrize('mode,src,expect', [
    ('hue', (1, 0, 0, 1), (0.642, 0.242, 0.242)),
    ('saturation', (0.5, 0.5, 0.6, 1), (0.3215, 0.3715, 0.4215)),
    ('color', (1, 0, 0, 1), (1.0, 0.362 - 0.3 * 0.638 / 0.7, 0.362 - 0.3 * 0.638 / 0.7)),
    ('luminosity', (0.5, 0.5, 0.5, 1), (0.338, 0.538, 0.738))])
def test_non_separable_modes_known_values(mode, src, expect):
    g = Group(blend_mode=mode, children=[filled(rect(0, 0, 20, 20), SolidPaint(src))])
    c = render_tree(tree(g), background=CB).data
    assert np.allclose(c[5, 5], list(expect) + [1], atol=2e-6)


def test_non_separable_negative_channel_clamps_like_resvg():
    """Saturation of green (0, 0.5, 0) with saturated yellow: SetSat gives
    (0, 1, 0), SetLum to Lum 0.295 gives (-0.295, 0.705, -0.295).  The
    specification's ClipColor would scale that to (0, 0.5, 0); resvg clamps
    the negative channels and keeps G = 0.705 (its suite's references
    painting/mix-blend-mode/saturation and color are drawn this way)."""
    g = Group(blend_mode='saturation',
              children=[filled(rect(0, 0, 20, 20), SolidPaint((1, 1, 0, 1)))])
    c = render_tree(tree(g), background=(0, 0.5, 0, 1)).data
    assert np.allclose(c[5, 5], [0, 0.705, 0, 1], atol=2e-6)


def test_non_separable_with_partial_alphas():
    """Source-over with a blend: Co = Cs Sa (1 - Ba) + Cb Ba (1 - Sa) + Sa Ba B
    (premultiplied result); luminosity of grey 0.5 over Cb, both at alpha 0.5."""
    g = Group(blend_mode='luminosity',
              children=[filled(rect(0, 0, 20, 20), SolidPaint((0.5, 0.5, 0.5, 0.5)))])
    c = render_tree(tree(g), background=(0.2, 0.4, 0.6, 0.5)).data
    b = np.array([0.338, 0.538, 0.738])
    want = 0.5 * 0.5 * 0.5 + np.array([0.2, 0.4, 0.6]) * 0.5 * 0.5 + 0.25 * b
    assert np.allclose(c[5, 5, :3], want, atol=2e-6) and c[5, 5, 3] == pytest.approx(0.75)


def test_blend_with_transparent_backdrop_is_source():
    g = Group(blend_mode='multiply', children=[filled(rect(0, 0, 10, 10), BLUE)])
    c = render_tree(tree(g)).data
    assert np.allclose(c[5, 5], [0, 0, 1, 1])


# -- images ---------------------------------------------------------------------------

def test_image_nearest_scaling():
    pix = np.array([[[255, 0, 0, 255], [0, 0, 255, 255]],
                    [[0, 255, 0, 255], [0, 0, 0, 0]]], np.uint8)
    n = ImageNode(view_rect=(0, 0, 10, 10), transform=Affine.scale(5), pixels=pix, smooth=False)
    c = render_tree(tree(n)).data
    assert np.allclose(c[2, 2], [1, 0, 0, 1]) and np.allclose(c[2, 7], [0, 0, 1, 1])
    assert np.allclose(c[7, 2], [0, 1, 0, 1]) and np.allclose(c[7, 7], 0)
    assert alpha(render_tree(tree(n))).sum() == pytest.approx(75)


def test_image_clip_and_opacity():
    pix = np.full((4, 4, 4), 255, np.uint8)
    n = ImageNode(view_rect=(0, 0, 8, 8), transform=Affine.scale(2), pixels=pix,
                  clip=(0, 0, 8, 4), opacity=0.5)
    assert alpha(render_tree(tree(n))).sum() == pytest.approx(32 * 0.5)


@pytest.mark.parametrize('smooth', [True, False])
def test_image_window_sampling_matches_full_image(smooth):
    """A 64 x 64 random image scaled by 3 and shifted so that the 40 x 30
    canvas sees an interior window: the renderer samples only the source
    pixels it needs, and must give what sampling the whole (premultiplied)
    image at the pixel centres gives: exactly for nearest sampling, within
    2/255 for smooth sampling (resampled in 8 bits by Pillow)."""
    rng = np.random.default_rng(7)
    pix = rng.integers(0, 256, (64, 64, 4), dtype=np.uint8)
    tf = Affine.translate(-50, -60) @ Affine.scale(3)
    img = ImageNode(view_rect=(-50, -60, 192, 192), transform=tf, pixels=pix, smooth=smooth)
    c = render_tree(Tree(40, 30, Group(children=[img]))).data
    p = pix.astype(np.float32) / 255
    pm = np.concatenate([p[..., :3] * p[..., 3:], p[..., 3:]], -1)
    jj, ii = np.meshgrid(np.arange(40) + 0.5, np.arange(30) + 0.5)
    uv = tf.inverse().apply(np.stack([jj, ii], -1))
    want = paint_mod.sample(pm, uv[..., 0], uv[..., 1], smooth=smooth)
    assert np.allclose(c, want, atol=2 / 255 if smooth else 1e-5)


def test_svg_image_renders_nested_tree():
    inner = Tree(4, 4, Group(children=[filled(rect(0, 0, 4, 4), BLUE)]))
    n = ImageNode(view_rect=(2, 2, 8, 8), transform=Affine.translate(2, 2) @ Affine.scale(2),
                  tree=inner, clip=(2, 2, 8, 8))
    c = render_tree(tree(n)).data
    assert c[..., 3].sum() == pytest.approx(64) and np.allclose(c[5, 5], [0, 0, 1, 1])


# -- properties ----------------------------------------------------------------------

@settings(max_examples=40, deadline=None)
@given(x=st.floats(-5, 25), y=st.floats(-5, 25), w=st.floats(0.1, 15), h=st.floats(0.1, 15))
def test_rect_coverage_is_its_visible_area(x, y, w, h):
    """A rectangle anywhere (also partly outside the canvas) covers its area
    inside the canvas, up to the scan converter's documented sub-scanline
    error (1/64 px per pixel holding a whole small contour or corner)."""
    c = render_tree(tree(filled(rect(x, y, w, h))))
    vis = max(0, min(x + w, 20) - max(x, 0)) * max(0, min(y + h, 20) - max(y, 0))
    assert alpha(c).sum() == pytest.approx(vis, abs=1e-3 + (2 * (w + h) + 4) / 64)
    assert c.data.min() >= 0 and c.data.max() <= 1 + 1e-6


@settings(max_examples=25, deadline=None)
@given(op=st.floats(0.05, 1.0), seed=st.integers(0, 1000))
def test_group_opacity_scales_single_shape(op, seed):
    """A group holding a single shape with opacity o is the same as the shape
    with fill-opacity o."""
    rng = np.random.default_rng(seed)
    cx, cy, r = rng.uniform(4, 16, 3) * (1, 1, 0.5)
    a = render_tree(tree(Group(opacity=op, children=[filled(circle(cx, cy, r))]))).data
    b = render_tree(tree(filled(circle(cx, cy, r), opacity=op))).data
    assert np.allclose(a, b, atol=1e-5)


# -- library entry points (raster.render, render_image, load_svg) ----------------------

DOC = (b'<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10">'
       b'<rect id="r" width="5" height="10" fill="red" fill-opacity="0.5"/></svg>')


def test_render_straight_and_premultiplied():
    import raster
    img = raster.render(DOC)
    assert img.dtype == np.uint8 and img.shape == (10, 10, 4)
    assert img[5, 2].tolist() == [255, 0, 0, 128]
    pre = raster.render(DOC, premultiplied=True)
    assert pre[5, 2].tolist() == [128, 0, 0, 128]


def test_render_image_background_and_size():
    import raster
    im = raster.render_image(DOC, 20, background='white')
    assert im.mode == 'RGBA' and im.size == (20, 20)
    assert im.getpixel((5, 5)) == (255, 128, 128, 255)      # 0.5 of white: 127.5 rounds up
    assert im.getpixel((15, 5)) == (255, 255, 255, 255)


def test_load_svg_gives_tree():
    import raster
    t = raster.load_svg(DOC)
    assert isinstance(t, Tree) and (t.width, t.height) == (10, 10) and 'r' in t.ids


@pytest.mark.parametrize('kw,err', [({'width': 0}, CanvasError), ({'height': -1}, CanvasError),
                                    ({'width': 10**6}, CanvasError), ({'id': 'nope'}, SVGError),
                                    ({'background': 'nocolour'}, SVGError),
                                    ({'background': (2, 0, 0, 1)}, SVGError)])
def test_render_errors(kw, err):
    import raster
    with pytest.raises(err):
        raster.render(DOC, **kw)


# -- groups clipped by one axis-aligned rectangle: drawn without a layer ----------

def _clip_group(children, x, y, w, h, clip_transform=None, **kw):
    clip = ClipPath(root=Group(children=[filled(rect(x, y, w, h))]),
                    transform=clip_transform or Affine())
    return Group(children=children, clip_path=clip, **kw)


@pytest.mark.parametrize('seed', range(4))
def test_rectangle_clip_without_layer_matches_layer(monkeypatch, seed):
    """Disjoint children under a fractional, scaled, translated clip
    rectangle: the same pixels with and without a layer, and no layer is
    allocated."""
    rng = np.random.default_rng(seed)
    kids = [filled(circle(cx, cy, 2.5), paint)
            for (cx, cy), paint in zip([(4, 4), (10, 5), (5, 12), (13, 13)], [RED, BLUE] * 2)]
    x, y = rng.uniform(1, 6, 2)
    w, h = rng.uniform(5, 12, 2)
    g = _clip_group(kids, x, y, w, h, clip_transform=Affine(1.1, 0, 0, 0.9, 0.3, -0.2),
                    transform=Affine.translate(*rng.uniform(-1, 1, 2)))
    t = tree(g)
    sizes = []
    orig = draw_mod.Canvas
    monkeypatch.setattr(draw_mod, 'Canvas', lambda w_, h_, *a, **k: sizes.append((w_, h_))
                        or orig(w_, h_, *a, **k))
    monkeypatch.setattr(renderer_pkg, 'Canvas', draw_mod.Canvas)
    fast = render_tree(t, width=37).data
    assert len(sizes) == 1                      # the output canvas only
    monkeypatch.setattr(draw_mod, 'clip_rect', lambda g, m: None)
    monkeypatch.setattr(batch_mod, 'clip_rect', lambda g, m: None)
    slow = render_tree(t, width=37).data
    assert np.abs(fast - slow).max() < 1e-6
    assert fast[..., 3].sum() > 1.0


def test_rectangle_clip_is_not_taken_for_rotations_and_other_shapes():
    sq = _clip_group([filled(rect(0, 0, 20, 20))], 2, 2, 8, 8)
    assert draw_mod.clip_rect(sq, Affine()) == (2.0, 2.0, 10.0, 10.0)
    assert draw_mod.clip_rect(sq, Affine.rotate(10)) is None
    disc = Group(children=[filled(rect(0, 0, 20, 20))],
                 clip_path=ClipPath(root=Group(children=[filled(circle(5, 5, 3))])))
    assert draw_mod.clip_rect(disc, Affine()) is None
    half = _clip_group([filled(rect(0, 0, 20, 20))], 2, 2, 8, 8, opacity=0.5)
    assert draw_mod.clip_rect(half, Affine()) is None
    # the clipped result: exact area of the rectangle, fractional edges included
    g = _clip_group([filled(rect(0, 0, 20, 20))], 2.25, 3.5, 8.5, 6.25)
    a = alpha(render_tree(tree(g)))
    assert a.sum() == pytest.approx(8.5 * 6.25, abs=1e-5)
    assert a[3, 5] == pytest.approx(0.5) and a[5, 2] == pytest.approx(0.75)


def test_rectangle_clip_of_a_blended_group_lerps_with_coverage():
    """A multiply-blended child group inside a rectangle-clipped group:
    blended pixels are mixed with the backdrop by the clip coverage."""
    inner = Group(children=[filled(rect(0, 0, 20, 20), BLUE)], blend_mode='multiply')
    g = _clip_group([inner], 2.5, 2.5, 10, 10)
    back = filled(rect(0, 0, 20, 20), SolidPaint((1.0, 1.0, 1.0, 1.0)))
    c = render_tree(tree(back, g)).data
    assert np.allclose(c[5, 5], [0, 0, 1, 1], atol=1e-6)      # inside: blue
    assert np.allclose(c[2, 5], [0.5, 0.5, 1, 1], atol=1e-6)   # half covered row
    assert np.allclose(c[0, 0], [1, 1, 1, 1], atol=1e-6)       # outside: white


def test_element_beyond_coordinate_limit_is_left_out_with_a_warning():
    """A stroke 1e12 wide would put outline coordinates above MAX_COORD:
    that element is dropped (one RasterWarning), the others are drawn."""
    from raster.errors import RasterWarning
    huge = PathNode(path=line(2, 2, 18, 18), stroke=Stroke.of(RED, width=1e12))
    far = filled(rect(0, 0, 4e9, 3), BLUE)
    ok = filled(rect(10, 2, 5, 5), BLUE)
    with pytest.warns(RasterWarning, match='not drawn'):
        c = render_tree(tree(filled(rect(0, 10, 5, 5)), huge, far, ok)).data
    assert np.allclose(c[12, 2], [1, 0, 0, 1]) and np.allclose(c[4, 12], [0, 0, 1, 1])
    assert c[18, 18, 3] == 0
