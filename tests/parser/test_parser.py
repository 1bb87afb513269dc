"""Tests of raster.parser.build_tree: the resolved tree of small inline
documents (inheritance, CSS, units, use/symbol/nested svg, switch,
display/visibility, opacity, group dropping) and a sweep over the resvg
suite's structure/shapes/painting documents."""

import glob
import math
import os
import warnings

import numpy as np
import pytest
from hypothesis import given, settings, strategies as hs

import raster
from raster.errors import RasterWarning, SVGError
from raster.parser import build_tree
from raster.parser.document import load_document
from raster.tree import ClipPath, Group, PathNode, SolidPaint, walk
from raster.geometry.transform import Affine

from _shared import SUITE_TESTS as SUITE
GREEN = (0.0, 128 / 255, 0.0, 1.0)


def tree_of(body, attrs='width="200" height="200"', **kw):
    doc = ('<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
           '%s>%s</svg>' % (attrs, body))
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', RasterWarning)
        return build_tree(load_document(doc.encode()), **kw)


def paths(tree):
    """[(PathNode, absolute transform)] in document order."""
    return [(n, t) for n, t in walk(tree.root) if isinstance(n, PathNode)]


def only_path(tree):
    ps = paths(tree)
    assert len(ps) == 1, ps
    return ps[0]


def box(node, t=Affine()):
    pts = t.apply(node.path.points)
    return tuple(np.round(np.concatenate([pts.min(0), pts.max(0)]), 6).tolist())


# -- document size ------------------------------------------------------------

def test_size_from_width_height_and_units():
    t = tree_of('', 'width="1in" height="10mm"')
    assert t.width == 96 and t.height == pytest.approx(960 / 25.4)


def test_size_from_viewbox_and_percent():
    t = tree_of('', 'viewBox="0 0 30 40"')
    assert (t.width, t.height) == (30, 40)
    t = tree_of('', 'width="50%" height="10" viewBox="0 0 30 40"')
    assert (t.width, t.height) == (15, 10)


def test_no_size_reaches_the_content_from_the_origin():
    # no width, height or viewBox: the far edges of the content, which is
    # not moved (resvg does the same; the origin stays the viewport's corner)
    t = tree_of('<rect x="10" y="20" width="30" height="40"/>', '')
    assert (t.width, t.height) == (40, 60)
    n, m = only_path(t)
    assert box(n, m) == (10, 20, 40, 60)
    # strokes count: nothing drawn is cut off
    t = tree_of('<rect x="10" y="20" width="30" height="40" stroke="black" stroke-width="4"/>',
                'width="auto"')
    assert (t.width, t.height) == (42, 62)
    # content left of or above the origin only: the 100 px default
    t = tree_of('<rect x="-50" y="-50" width="30" height="40"/>', '')
    assert (t.width, t.height) == (100, 100)


@pytest.mark.parametrize('attrs, size', [
    ('width="80" viewBox="0 0 40 20"', (80, 40)),            # the ratio gives the height
    ('height="80" viewBox="0 0 40 20"', (160, 80)),
    ('width="80" height="auto" viewBox="0 0 40 20"', (80, 40)),
    ('width="auto" height="auto" viewBox="0 0 40 20"', (40, 20)),
    ('width="50%" viewBox="0 0 40 20"', (20, 10)),            # percent of the viewBox
    ('width="80" height="50%" viewBox="0 0 40 20"', (80, 10)),
    ('width="80" viewBox="0 0 40 20" preserveAspectRatio="none"', (80, 40)),
    ('width="80"', (80, 25)),                  # no viewBox: the other side from the content
    ('height="auto" width="30"', (30, 25)),
])
def test_a_missing_side_follows_the_ratio_or_the_content(attrs, size):
    t = tree_of('<rect x="5" y="5" width="20" height="20"/>', attrs)
    assert (t.width, t.height) == pytest.approx(size)


def test_display_none_on_the_root_draws_nothing_at_its_size():
    t = tree_of('<rect width="20" height="20"/>', 'width="50" height="40" display="none"')
    assert (t.width, t.height) == (50, 40)
    assert [n for n, _ in walk(t.root) if isinstance(n, PathNode)] == []
    t = tree_of('<rect width="20" height="20"/>', 'width="50" height="40" style="display: none"')
    assert [n for n, _ in walk(t.root) if isinstance(n, PathNode)] == []


@pytest.mark.parametrize('attrs', ['width="-50" height="10"', 'width="0" height="10"',
                                   'width="abc" height="10"'])
def test_invalid_size_raises(attrs):
    with pytest.raises(SVGError, match='invalid document size'):
        tree_of('', attrs)


def test_root_preserve_aspect_ratio():
    # viewBox 100x50 in 200x200: meet scales by 2 and centres vertically
    t = tree_of('<rect width="100" height="50"/>',
                'width="200" height="200" viewBox="0 0 100 50"')
    assert box(*only_path(t)) == (0, 50, 200, 150)
    t = tree_of('<rect width="100" height="50"/>',
                'width="200" height="200" viewBox="0 0 100 50" preserveAspectRatio="xMinYMax meet"')
    assert box(*only_path(t)) == (0, 100, 200, 200)
    t = tree_of('<rect width="100" height="50"/>',
                'width="200" height="200" viewBox="0 0 100 50" preserveAspectRatio="none"')
    assert box(*only_path(t)) == (0, 0, 200, 200)


# -- inheritance and CSS ---------------------------------------------------------

def test_inheritance_and_inherit_keyword():
    t = tree_of('<g fill="green" stroke="blue" opacity="0.5">'
                '<g fill="red"><rect fill="inherit" width="1" height="1"/></g>'
                '<rect opacity="inherit" width="1" height="1"/></g>')
    (a, _), (b, _) = paths(t)
    assert a.fill.paint.color == (1.0, 0.0, 0.0, 1.0)
    assert a.stroke.paint.color == (0.0, 0.0, 1.0, 1.0)
    assert b.fill.paint.color == GREEN
    # opacity is not inherited, but inherit copies the parent's 0.5
    groups = [n for n, _ in walk(t.root) if isinstance(n, Group) and n.opacity == 0.5]
    assert len(groups) == 2


def test_current_color_uses_own_color():
    t = tree_of('<g color="red"><rect fill="currentColor" stroke="currentColor" '
                'color="green" width="1" height="1"/>'
                '<rect fill="currentColor" width="1" height="1"/></g>')
    (a, _), (b, _) = paths(t)
    assert a.fill.paint.color == GREEN and a.stroke.paint.color == GREEN
    assert b.fill.paint.color == (1.0, 0.0, 0.0, 1.0)


def test_css_precedence_end_to_end():
    t = tree_of('<style>#r{fill:blue} rect{fill:red !important} .c{stroke:green}</style>'
                '<rect id="r" class="c" fill="yellow" stroke="black" style="stroke-width:3"'
                ' width="1" height="1"/>'
                '<rect style="fill:lime !important" width="1" height="1"/>')
    (a, _), (b, _) = paths(t)
    assert a.fill.paint.color == (1.0, 0.0, 0.0, 1.0)
    assert a.stroke.paint.color == GREEN and a.stroke.width == 3
    assert b.fill.paint.color == (0.0, 1.0, 0.0, 1.0)


def test_invalid_paint_falls_back_to_inherited():
    t = tree_of('<g fill="green"><rect fill="not-a-colour" width="1" height="1"/></g>')
    assert only_path(t)[0].fill.paint.color == GREEN


# -- units --------------------------------------------------------------------------

def test_units_em_ex_percent_mm():
    t = tree_of('<g font-size="20"><rect x="1em" y="2ex" width="50%" height="10mm"/></g>',
                'width="400" height="300"')
    n, m = only_path(t)
    assert box(n, m) == pytest.approx((20, 20, 220, 20 + 96 / 2.54))


def test_font_size_relative_chain():
    t = tree_of('<g font-size="10"><g font-size="200%"><g font-size="2em">'
                '<circle r="1em"/></g></g></g>')
    n, m = only_path(t)
    assert box(n, m) == pytest.approx((-40, -40, 40, 40))


def test_percent_uses_nearest_viewport():
    t = tree_of('<svg x="0" y="0" width="50" height="50" viewBox="0 0 10 20">'
                '<rect width="100%" height="100%"/></svg>', 'width="200" height="100"')
    n, _ = only_path(t)
    assert box(n) == (0, 0, 10, 20)


def test_stroke_width_percent_and_dasharray():
    t = tree_of('<rect width="1" height="1" stroke="red" stroke-width="10%" '
                'stroke-dasharray="5, 10%, 1" stroke-dashoffset="1mm"/>',
                'width="300" height="400" viewBox="0 0 300 400"')
    s = only_path(t)[0].stroke.style
    diag = math.sqrt((300 ** 2 + 400 ** 2) / 2)
    assert s.width == pytest.approx(diag / 10)
    assert s.dash == pytest.approx((5, diag / 10, 1, 5, diag / 10, 1))
    assert s.dash_offset == pytest.approx(96 / 25.4)


@pytest.mark.parametrize('da', ['none', '0 0', '5 -1', '5,,5', ''])
def test_dasharray_solid_cases(da):
    t = tree_of('<rect width="1" height="1" stroke="red" stroke-dasharray="%s"/>' % da)
    assert only_path(t)[0].stroke.style.dash is None


def test_stroke_properties():
    t = tree_of('<line x2="10" stroke="red" stroke-linejoin="round" stroke-linecap="square" '
                'stroke-miterlimit="0.5" stroke-opacity="2" fill-opacity="-1"/>'
                '<line x2="10" stroke="red" stroke-width="0"/>')
    n, _ = paths(t)[0]
    s = n.stroke
    assert (s.style.join, s.style.cap, s.style.miterlimit, s.opacity) == \
        ('round', 'square', 4.0, 1.0)
    assert n.fill.opacity == 0.0
    assert paths(t)[1][0].stroke is None


@pytest.mark.parametrize('po,expect', [
    ('normal', ('fill', 'stroke', 'markers')),
    ('stroke', ('stroke', 'fill', 'markers')),
    ('markers fill', ('markers', 'fill', 'stroke')),
    ('fill fill', ('fill', 'stroke', 'markers')),
])
def test_paint_order(po, expect):
    t = tree_of('<rect width="1" height="1" paint-order="%s"/>' % po)
    assert only_path(t)[0].paint_order == expect


def test_shape_rendering_antialias():
    t = tree_of('<g shape-rendering="crispEdges"><rect width="1" height="1"/>'
                '<rect shape-rendering="geometricPrecision" width="1" height="1"/></g>'
                '<rect shape-rendering="optimizeSpeed" width="1" height="1"/>')
    assert [n.antialias for n, _ in paths(t)] == [False, True, False]


def test_fill_rule_and_url_fallbacks():
    t = tree_of('<rect fill="url(#missing) green" fill-rule="evenodd" width="1" height="1"/>'
                '<rect fill="url(#missing)" stroke="red" width="1" height="1"/>')
    (a, _), (b, _) = paths(t)
    assert a.fill.paint.color == GREEN and a.fill.rule == 'evenodd'
    assert b.fill is None


# -- shapes -------------------------------------------------------------------------

def test_shapes_geometry():
    t = tree_of('<rect x="1" y="2" width="3" height="4"/>'
                '<circle cx="10" cy="10" r="5"/>'
                '<ellipse cx="10" cy="10" rx="5"/>'
                '<line x1="1" y1="2" x2="3" y2="4" stroke="red"/>'
                '<polygon points="0,0 4,0 4,4"/>'
                '<path d="M 0 0 L 5 5 L oops 9"/>')
    boxes = [box(n) for n, _ in paths(t)]
    assert boxes[0] == (1, 2, 4, 6)
    assert boxes[1] == pytest.approx((5, 5, 15, 15))
    assert boxes[2] == pytest.approx((5, 5, 15, 15))      # ry auto = rx
    assert boxes[3] == (1, 2, 3, 4)
    assert boxes[4] == (0, 0, 4, 4)
    assert boxes[5] == (0, 0, 5, 5)                       # prefix before the error


@pytest.mark.parametrize('shape', ['<rect width="0" height="5"/>', '<rect width="5"/>',
                                   '<circle r="-1"/>', '<ellipse/>', '<polygon points=""/>',
                                   '<path d="L 1 1"/>', '<rect width="-5" height="5"/>'])
def test_invalid_shapes_not_rendered(shape):
    assert paths(tree_of(shape)) == []


def test_circle_arc_tolerance():
    # the circle's cubics stay within tolerance/10 of the true circle at natural size
    t = tree_of('<circle cx="0" cy="0" r="1"/>', 'width="1000" height="1000" viewBox="-1 -1 2 2"',
                tolerance=0.1)
    n, m = only_path(t)
    seg = n.path.segments()
    tt = np.linspace(0, 1, 33)[:, None]
    c = seg.ctrl[:, None]
    pts = ((1 - tt) ** 3 * c[:, :, 0] + 3 * (1 - tt) ** 2 * tt * c[:, :, 1]
           + 3 * (1 - tt) * tt ** 2 * c[:, :, 2] + tt ** 3 * c[:, :, 3])
    err_px = np.abs(np.hypot(pts[..., 0], pts[..., 1]) - 1).max() * 500
    assert err_px <= 0.01 + 1e-9


# -- structure ----------------------------------------------------------------------

def test_trivial_groups_dropped():
    t = tree_of('<g><g><rect width="1" height="1"/></g></g>')
    assert isinstance(t.root.children[0], PathNode)


def test_group_with_id_or_transform_kept():
    t = tree_of('<g id="a"><g transform="translate(5 6)"><rect width="1" height="1"/></g></g>')
    g = t.root.children[0]
    assert isinstance(g, Group) and g.id == 'a' and t.ids['a'] is g
    assert g.children[0].transform == Affine.translate(5, 6)


def test_opacity_wraps_shape():
    # filled and stroked: a layer is needed (a single paint is folded, see
    # test_group_opacity_over_one_paint_is_folded_into_the_paint)
    t = tree_of('<rect id="r" opacity="50%" width="1" height="1" stroke="red"/>')
    g = t.root.children[0]
    assert isinstance(g, Group) and g.opacity == 0.5 and isinstance(g.children[0], PathNode)
    assert t.ids['r'] is g


def test_transform_origin():
    t = tree_of('<rect width="10" height="10" transform="rotate(90)" transform-origin="5 5"/>')
    n, m = only_path(t)
    assert box(n, m) == pytest.approx((0, 0, 10, 10))


def test_singular_transform_not_rendered():
    assert paths(tree_of('<rect width="1" height="1" transform="scale(0)"/>')) == []


def test_display_and_visibility():
    t = tree_of('<g display="none"><rect id="a" width="1" height="1"/></g>'
                '<g visibility="hidden"><rect id="b" width="1" height="1"/>'
                '<rect id="c" visibility="visible" width="1" height="1"/></g>'
                '<rect id="d" visibility="collapse" width="1" height="1"/>')
    painted = [n.id for n, _ in paths(t) if n.fill is not None or n.stroke is not None]
    assert painted == ['c']
    # invisible shapes stay in the tree unpainted (they count in bounding boxes)
    assert [n.id for n, _ in paths(t)] == ['b', 'c', 'd']


def test_hidden_shape_counts_in_object_bounding_box():
    t = tree_of('<clipPath id="c" clipPathUnits="objectBoundingBox"><rect width="1" height="1"/>'
                '</clipPath><g id="g" clip-path="url(#c)">'
                '<rect x="20" y="20" width="160" height="160" visibility="hidden"/>'
                '<rect x="40" y="40" width="120" height="120"/></g>')
    cp = t.ids['g'].clip_path
    assert cp.transform == Affine(160, 0, 0, 160, 20, 20)


def test_use_inherits_from_use_and_translates():
    t = tree_of('<defs><rect id="r" width="10" height="10"/></defs>'
                '<use href="#r" x="5" y="6" fill="green"/>')
    n, m = only_path(t)
    assert n.fill.paint.color == GREEN and box(n, m) == (5, 6, 15, 16)


def test_use_href_precedence_and_display_none():
    t = tree_of('<defs><rect id="a" width="1" height="1" fill="green"/>'
                '<rect id="b" width="1" height="1" fill="red"/></defs>'
                '<use href="#a" xlink:href="#b"/><use href="#a" display="none"/>')
    assert [n.fill.paint.color for n, _ in paths(t)] == [GREEN]


@pytest.mark.parametrize('body', [
    '<use id="u1" href="#u2"/><use id="u2" href="#u1"/>',
    '<g id="g"><use href="#g"/><rect width="1" height="1"/></g>',
    '<use id="u" href="#u"/>',
    '<use id="u1" href="#u2"><use id="u2" href="#u1"/></use>',
])
def test_use_cycles_refused(body):
    doc = ('<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10">%s</svg>' % body)
    with pytest.warns(RasterWarning, match='recursive'):
        t = build_tree(load_document(doc.encode()))
    # only the non-recursive rect itself (if any) is drawn
    assert len(paths(t)) <= 1


def test_use_bomb_capped():
    body = ['<defs><rect id="a0" width="1" height="1"/>']
    for i in range(1, 12):
        body.append('<g id="a%d">%s</g>' % (i, ''.join('<use href="#a%d"/>' % (i - 1)
                                                      for _ in range(10))))
    body.append('</defs><use href="#a11"/>')
    doc = '<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10">%s</svg>' % ''.join(body)
    # the fan-out of 10**11 copies is refused before any of it is built
    with pytest.warns(RasterWarning, match='left of max_elements'):
        t = build_tree(load_document(doc.encode()), max_elements=2000)
    assert len(paths(t)) == 0


def test_use_copies_past_the_node_budget_are_left_out():
    # 30 copies of a group of 10 rects: those that fit in 100 nodes are built
    doc = ('<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10"><defs><g id="g">%s'
           '</g></defs>%s</svg>' % ('<rect width="1" height="1"/>' * 10,
                                    '<use href="#g"/>' * 30))
    with pytest.warns(RasterWarning, match='left of max_elements'):
        t = build_tree(load_document(doc.encode()), max_elements=100)
    # each copy: the use, its group and 10 rects (12 nodes), within 100
    assert len(paths(t)) == 10 * (100 // 12)


def test_use_depth_limit():
    body = ['<rect id="a0" width="1" height="1"/>']
    body += ['<use id="a%d" href="#a%d"/>' % (i, i - 1) for i in range(1, 20)]
    doc = '<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10"><defs>%s</defs>' \
          '<use href="#a19"/></svg>' % ''.join(body)
    with pytest.warns(RasterWarning):
        t = build_tree(load_document(doc.encode()), max_use_depth=5)
    assert paths(t) == []
    t = build_tree(load_document(doc.encode()), max_use_depth=64)
    assert len(paths(t)) == 1


def test_symbol_with_viewbox():
    t = tree_of('<symbol id="s" viewBox="0 0 10 10"><rect width="10" height="10"/></symbol>'
                '<use href="#s" x="20" y="30" width="100" height="50"/>')
    n, m = only_path(t)
    assert box(n, m) == (45, 30, 95, 80)
    clips = [g.clip_path for g, _ in walk(t.root) if isinstance(g, Group) and g.clip_path]
    assert len(clips) == 1 and box(clips[0].root.children[0]) == (20, 30, 120, 80)


def test_symbol_not_rendered_directly():
    assert paths(tree_of('<symbol><rect width="1" height="1"/></symbol>')) == []


def test_nested_svg_viewport_and_clip():
    t = tree_of('<svg x="10" y="20" width="50" height="60"><circle r="100"/></svg>'
                '<svg x="10" y="20" width="50" height="60" overflow="visible">'
                '<circle r="100"/></svg>')
    groups = [g for g in t.root.children if isinstance(g, Group)]
    assert isinstance(groups[0].clip_path, ClipPath)
    assert box(groups[0].clip_path.root.children[0]) == (10, 20, 60, 80)
    assert groups[1].clip_path is None
    (_, m1), (_, m2) = paths(t)
    assert m1.apply([[0.0, 0.0]]).tolist() == [[10, 20]] == m2.apply([[0.0, 0.0]]).tolist()


def test_switch_and_system_language():
    t = tree_of('<switch><rect id="a" requiredExtensions="x" width="1" height="1"/>'
                '<foo id="f"/>'
                '<rect id="b" systemLanguage="ru" width="1" height="1"/>'
                '<rect id="c" systemLanguage="fr, en-GB" width="1" height="1"/>'
                '<rect id="d" width="1" height="1"/></switch>')
    assert [n.id for n, _ in paths(t)] == ['c']
    t = tree_of('<switch><rect id="b" systemLanguage="ru" width="1" height="1"/>'
                '<rect id="d" width="1" height="1"/></switch>', languages=('ru-RU',))
    assert [n.id for n, _ in paths(t)] == ['b']


def test_unknown_and_unsupported_elements_skipped():
    t = build_tree(load_document(
        b'<svg xmlns="http://www.w3.org/2000/svg" width="5" height="5">'
        b'<foo><rect width="1" height="1"/></foo><rect id="k" width="1" height="1"/></svg>'))
    assert [n.id for n, _ in paths(t)] == ['k']


# -- properties -------------------------------------------------------------------------

@settings(max_examples=60, deadline=None)
@given(tx=hs.floats(-100, 100), ty=hs.floats(-100, 100), s=hs.floats(0.1, 10))
def test_transform_invariance(tx, ty, s):
    """Wrapping content in <g transform> maps the resolved geometry by the
    same affine (a rect and a circle)."""
    inner = '<rect x="1" y="2" width="3" height="4"/><circle cx="5" cy="5" r="2"/>'
    a = tree_of(inner)
    b = tree_of('<g transform="translate(%r %r) scale(%r)">%s</g>' % (tx, ty, s, inner))
    T = Affine.translate(tx, ty) @ Affine.scale(s)
    for (na, ma), (nb, mb) in zip(paths(a), paths(b)):
        pa = T.apply(ma.apply(na.path.points))
        pb = mb.apply(nb.path.points)
        if pa.shape == pb.shape:
            assert np.allclose(pa, pb, atol=1e-6 * (1 + abs(tx) + abs(ty)))
        else:   # a finer arc subdivision at a larger scale: compare the boxes
            assert np.allclose(pa.min(0), pb.min(0), atol=1e-2 * s)


# -- the resvg suite -------------------------------------------------------------------

def _suite_files():
    out = []
    for area in ('structure', 'shapes', 'painting'):
        out += sorted(glob.glob(os.path.join(SUITE, area, '**', '*.svg'), recursive=True))
    return out


def test_resvg_suite_builds():
    files = _suite_files()
    assert len(files) > 500
    errors = []
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', RasterWarning)
        for f in files:
            try:
                build_tree(load_document(f))
            except SVGError:
                pass     # refused documents (negative size, XML errors) are fine
            except Exception as e:  # noqa: BLE001
                errors.append('%s: %s: %s' % (os.path.relpath(f, SUITE), type(e).__name__, e))
    assert errors == []


# -- gradients (issue 4) ----------------------------------------------------------------

def _fill_of(body, **kw):
    return only_path(tree_of(body + '<rect width="10" height="10" fill="url(#g)"/>', **kw))[0].fill.paint


def test_linear_gradient_defaults_and_stops():
    from raster.tree import LinearGradient
    p = _fill_of('<linearGradient id="g"><stop offset="-1" stop-color="red"/>'
                 '<stop offset="50%" stop-color="lime" stop-opacity="0.5"/>'
                 '<stop offset="0.2" stop-color="blue"/><stop offset="7"/></linearGradient>')
    assert isinstance(p, LinearGradient)
    assert (p.x1, p.y1, p.x2, p.y2, p.spread) == (0, 0, 1, 0, 'pad')
    # objectBoundingBox units resolved: the box of the 10 x 10 rect
    assert p.transform == Affine(10, 0, 0, 10, 0, 0)
    # offsets clamped to [0, 1] and made non-decreasing
    assert [s.offset for s in p.stops] == [0, 0.5, 0.5, 1]
    assert p.stops[1].color == (0, 1, 0, 0.5)
    assert p.stops[3].color == (0, 0, 0, 1)


def test_gradient_href_chain_and_cycle():
    from raster.tree import LinearGradient, RadialGradient
    p = _fill_of('<radialGradient id="base" y2="1" spreadMethod="reflect" cx="0.2">'
                 '<stop offset="0" stop-color="red"/><stop offset="1" stop-color="blue"/>'
                 '</radialGradient>'
                 '<linearGradient id="g" href="#mid" x2="0.7"/>'
                 '<linearGradient id="mid" href="#base" y1="0.3" gradientTransform="rotate(90)"/>')
    assert isinstance(p, LinearGradient)
    # x2 own, y1 from the linear parent, y2 of the radial gradient ignored
    assert (p.x1, p.y1, p.x2, p.y2) == (0, 0.3, 0.7, 0)
    assert p.spread == 'reflect' and p.transform == Affine.scale(10) @ Affine.rotate(90)
    assert [s.color for s in p.stops] == [(1, 0, 0, 1), (0, 0, 1, 1)]
    # a cycle of hrefs terminates; no stops anywhere paints nothing
    t = tree_of('<linearGradient id="g" href="#h"/><linearGradient id="h" href="#g"/>'
                '<rect width="1" height="1" fill="url(#g)" stroke="red"/>')
    assert only_path(t)[0].fill is None
    p = _fill_of('<radialGradient id="g" fx="0.1" r="-1"><stop offset="0"/>'
                 '<stop offset="1" stop-color="red"/></radialGradient>')
    assert isinstance(p, RadialGradient) and (p.cx, p.cy, p.fx, p.fy, p.r) == (0.5, 0.5, 0.1, 0.5, 0)


def test_gradient_user_space_units_and_single_stop():
    p = _fill_of('<linearGradient id="g" gradientUnits="userSpaceOnUse" x1="10%" x2="1in">'
                 '<stop offset="0"/><stop offset="1"/></linearGradient>',
                 attrs='width="200" height="100"')
    assert (p.x1, p.x2, p.transform) == (20, 96, Affine())
    p = _fill_of('<linearGradient id="g"><stop offset="0.3" stop-color="currentColor" '
                 'color="lime" style="stop-opacity:0.25"/></linearGradient>')
    assert isinstance(p, SolidPaint) and p.color == (0, 1, 0, 0.25)


def test_stop_current_color_inherits_from_document_parents():
    p = _fill_of('<g color="blue"><linearGradient id="g"><stop stop-color="currentColor"/>'
                 '<stop offset="1" stop-color="red"/></linearGradient></g>')
    assert p.stops[0].color == (0, 0, 1, 1)


# -- clip paths and masks -------------------------------------------------------------

def test_clip_path_user_space_and_clip_rule():
    t = tree_of('<clipPath id="c" transform="translate(1 2)" clip-rule="evenodd">'
                '<rect width="5" height="5" fill="none" stroke="red" opacity="0.1"/>'
                '<g><rect width="9" height="9"/></g></clipPath>'
                '<rect id="r" width="10" height="10" fill="green" clip-path="url(#c)"/>')
    g = t.ids['r']
    cp = g.clip_path
    assert isinstance(g, Group) and isinstance(cp, ClipPath)
    assert cp.transform == Affine.translate(1, 2)
    (n,) = cp.root.children             # the <g> child is not valid in a clipPath
    assert isinstance(n, PathNode) and n.fill.rule == 'evenodd' and n.stroke is None
    assert box(n) == (0, 0, 5, 5)


def test_clip_path_object_bounding_box():
    t = tree_of('<clipPath id="c" clipPathUnits="objectBoundingBox">'
                '<rect x="0.25" width="0.5" height="1"/></clipPath>'
                '<g id="g" clip-path="url(#c)"><rect x="10" y="20" width="40" height="10"/></g>')
    cp = t.ids['g'].clip_path
    (n,) = cp.root.children
    assert box(n, cp.transform) == (20, 20, 40, 30)


def test_clip_path_missing_recursive_and_empty():
    # missing reference: ignored; self-recursive reference: ignored; empty clip: not drawn
    t = tree_of('<clipPath id="self" clip-path="url(#self)"><rect width="1" height="1"/></clipPath>'
                '<clipPath id="empty"/>'
                '<rect id="a" width="1" height="1" clip-path="url(#nothing)"/>'
                '<rect id="b" width="1" height="1" clip-path="url(#self)"/>'
                '<rect id="c" width="1" height="1" clip-path="url(#empty)"/>')
    assert isinstance(t.ids['a'], PathNode)
    assert t.ids['b'].clip_path.clip_path is None
    assert [n.id for n, _ in paths(t)] == ['a', 'b']


def test_mask_defaults_and_content_units():
    t = tree_of('<mask id="m" maskContentUnits="objectBoundingBox" style="mask-type:alpha">'
                '<rect width="0.5" height="1" fill="white"/></mask>'
                '<rect id="r" x="10" y="10" width="100" height="50" mask="url(#m)"/>')
    m = t.ids['r'].mask
    assert m.kind == 'alpha'
    assert m.rect == pytest.approx((0, 5, 120, 60))      # -10%, 120% of the bbox
    (n, tt), = [(n, tt) for n, tt in walk(m.root) if isinstance(n, PathNode)]
    assert box(n, tt) == (10, 10, 60, 60)


def test_mask_recursion_dropped():
    t = tree_of('<mask id="m1" mask="url(#m2)"><rect width="5" height="5" fill="white"/></mask>'
                '<mask id="m2" mask="url(#m1)"><rect width="5" height="5" fill="white"/></mask>'
                '<rect id="r" width="1" height="1" mask="url(#m2)"/>')
    m = t.ids['r'].mask
    assert m.id == 'm2' and m.mask is None


def test_gradient_fallbacks():
    # no stops: the fallback colour; objectBoundingBox on a line (zero-height box): fallback
    t = tree_of('<linearGradient id="g0"/><linearGradient id="g">'
                '<stop offset="0"/><stop offset="1" stop-color="red"/></linearGradient>'
                '<rect width="1" height="1" fill="url(#g0) green"/>'
                '<line x2="10" stroke="url(#g) green"/><line x2="10" stroke="url(#g)"/>')
    (a, _), (b, _), (c, _) = paths(t)
    assert a.fill.paint.color == GREEN and b.stroke.paint.color == GREEN
    assert c.stroke is None


def test_pattern_resolved():
    from raster.tree import Pattern
    t = tree_of('<pattern id="base" width="20" height="10" patternUnits="userSpaceOnUse" '
                'viewBox="0 0 2 1" patternTransform="scale(2)"><rect width="1" height="1"/></pattern>'
                '<pattern id="p" href="#base" x="5" fill="green"/>'
                '<rect width="100" height="100" fill="url(#p)"/>')
    p = only_path(t)[0].fill.paint
    assert isinstance(p, Pattern)
    assert p.rect == (5, 0, 20, 10)
    assert p.transform == Affine.scale(2) and p.content_transform == Affine.scale(10)
    (n,) = p.root.children
    assert box(n) == (0, 0, 1, 1)
    # content inherits from the pattern's document ancestors, not from the painted shape
    assert n.fill.paint.color == (0, 0, 0, 1)


def test_pattern_self_reference_terminates():
    t = tree_of('<pattern id="p" href="#p" width="10" height="10" patternUnits="userSpaceOnUse">'
                '<rect width="5" height="5" fill="url(#p)" stroke="green"/></pattern>'
                '<rect width="100" height="100" fill="url(#p)"/>')
    p = only_path(t)[0].fill.paint
    (inner,) = p.root.children
    assert inner.fill is None and inner.stroke.paint.color == GREEN


# -- context paints (markers: tests/test_svg_markers.py) ---------------------------------------------------------

def test_context_fill_in_use():
    t = tree_of('<defs><rect id="r" width="1" height="1" fill="context-stroke" '
                'stroke="context-fill"/></defs><use href="#r" fill="green" stroke="red"/>'
                '<rect width="1" height="1" fill="context-fill" stroke="blue"/>')
    (a, _), (b, _) = paths(t)
    assert a.fill.paint.color == (1, 0, 0, 1) and a.stroke.paint.color == GREEN
    assert b.fill is None      # no context element


def test_gradient_transform_origin():
    p = _fill_of('<radialGradient id="g" gradientTransform="scale(2)" transform-origin="0.5 0.5">'
                 '<stop offset="0"/><stop offset="1"/></radialGradient>')
    assert p.transform == Affine.scale(10) @ Affine(2, 0, 0, 2, -0.5, -0.5)


# -- robustness -------------------------------------------------------------------------

_VALUES = ['', ' ', '-1', '0', '1e400', 'NaN', 'inf', '50%', '-50%', '1em', '2ex', '3mm', 'auto',
           'none', 'inherit', 'url(#a)', 'url(#b) red', 'url(#c)', 'currentColor', 'red',
           'rotate(45)', 'scale(0)', 'matrix(1 0 0 1 1e308 0)', '0 0 10 10', '0 0 -1 1',
           'M 0 0 L 10 10 A 5 5 0 1 1 1e6 3', 'xMinYMin slice', '1,2,3', '#a', 'evenodd']
_ATTRS = ['x', 'y', 'width', 'height', 'r', 'rx', 'ry', 'd', 'points', 'fill', 'stroke',
          'stroke-width', 'stroke-dasharray', 'opacity', 'transform', 'viewBox', 'href',
          'clip-path', 'mask', 'font-size', 'preserveAspectRatio', 'offset', 'stop-color',
          'gradientTransform', 'transform-origin', 'display', 'marker-mid', 'patternUnits']
_TAGS = ['g', 'rect', 'circle', 'ellipse', 'path', 'polygon', 'use', 'svg', 'symbol',
         'clipPath', 'mask', 'linearGradient', 'radialGradient', 'stop', 'pattern', 'switch',
         'marker', 'line']


@settings(max_examples=40, deadline=None)
@given(hs.data())
def test_random_documents_never_crash(data):
    """Random trees of elements with hostile attribute values build without
    an exception other than SVGError (seeded by hypothesis)."""
    ids = ['a', 'b', 'c']

    def element(depth):
        tag = data.draw(hs.sampled_from(_TAGS))
        attrs = data.draw(hs.dictionaries(hs.sampled_from(_ATTRS), hs.sampled_from(_VALUES),
                                          max_size=5))
        if data.draw(hs.booleans()):
            attrs['id'] = data.draw(hs.sampled_from(ids))
        a = ''.join(' %s="%s"' % kv for kv in attrs.items())
        kids = ''
        if depth < 3:
            kids = ''.join(element(depth + 1) for _ in range(data.draw(hs.integers(0, 3))))
        return '<%s%s>%s</%s>' % (tag, a, kids, tag)
    body = ''.join(element(0) for _ in range(data.draw(hs.integers(1, 3))))
    try:
        t = tree_of(body, max_elements=5000)
    except SVGError:
        return
    for n, m in walk(t.root):
        if isinstance(n, PathNode):
            assert np.all(np.isfinite(n.path.points))


def test_bad_tolerance_and_root():
    root = load_document(b'<svg xmlns="http://www.w3.org/2000/svg" width="5" height="5"/>')
    for bad in (0, -1, float('nan'), 'x'):
        with pytest.raises(SVGError, match='tolerance'):
            build_tree(root, tolerance=bad)
    with pytest.raises(SVGError, match='root element'):
        build_tree(root[0] if len(root) else load_document(
            b'<svg xmlns="http://www.w3.org/2000/svg"><g/></svg>')[0])


def test_overflowing_numbers_skip_only_that_element():
    for inner in (b'<rect id="a" transform="scale(1e200)" width="1" height="1"/>',
                  b'<use id="a" href="#b" transform="scale(1e200)"/>',
                  b'<svg id="a" viewBox="0 0 1e-200 1e-200"><rect width="1" height="1"/></svg>'):
        with warnings.catch_warnings():
            warnings.simplefilter('ignore', RasterWarning)
            t = build_tree(load_document(
                b'<svg xmlns="http://www.w3.org/2000/svg" width="5" height="5">'
                b'<g transform="scale(1e200)">' + inner + b'</g>'
                b'<rect id="b" width="1" height="1"/></svg>'))
        assert [n.id for n, _ in paths(t)] == ['b']


# -- context paints rebased to the use element; path sharing --------------------------------
def test_context_gradient_in_use_spans_the_use_bounding_box():
    # objectBoundingBox gradient through context-fill: the box is the use
    # element's (both rects together: x 0..50 and, scaled about x=10,
    # 30..55), not each rect's own
    t = build_tree(load_document(
        b'<svg xmlns="http://www.w3.org/2000/svg" width="100" height="10">'
        b'<linearGradient id="lg"><stop offset="0" stop-color="red"/>'
        b'<stop offset="1" stop-color="blue"/></linearGradient>'
        b'<defs><g id="g"><rect width="50" height="10" fill="context-fill"/>'
        b'<rect x="50" width="50" height="10" fill="context-fill" '
        b'transform="translate(10 0) scale(0.5 1) translate(-10 0)"/></g></defs>'
        b'<use href="#g" fill="url(#lg)" x="0"/></svg>'))
    ps = paths(t)
    assert len(ps) == 2
    for n, m in ps:
        g = n.fill.paint
        assert type(g).__name__ == 'LinearGradient'
        # the gradient's x axis, mapped to the document, runs 0 -> 55
        gm = m @ g.transform
        assert gm.apply([[g.x1, g.y1], [g.x2, g.y2]])[:, 0].tolist() == \
            pytest.approx([0.0, 55.0])


def test_context_pattern_ignores_transforms_inside_use_content():
    # a user-space pattern painted through context-fill stays in the use's
    # user space although the shape is rotated inside the referenced group
    t = build_tree(load_document(
        b'<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">'
        b'<pattern id="p" patternUnits="userSpaceOnUse" width="10" height="10">'
        b'<rect width="5" height="5"/></pattern>'
        b'<defs><g id="g" transform="rotate(30)"><rect width="50" height="50" '
        b'fill="context-fill"/></g></defs>'
        b'<use href="#g" fill="url(#p)" transform="translate(5 5)"/></svg>'))
    (n, m), = paths(t)
    p = n.fill.paint
    assert np.allclose(list(m @ p.transform), list(Affine.translate(5, 5)))


def test_identical_path_data_share_one_path():
    d = b'M0 0 A 5 5 0 1 1 10 0 A 5 5 0 1 1 0 0'
    body = b''.join(b'<path d="%s" transform="translate(%d 0)"/>' % (d, i) for i in range(5))
    t = build_tree(load_document(b'<svg xmlns="http://www.w3.org/2000/svg" width="100" '
                                 b'height="100">' + body + b'</svg>'))
    ps = paths(t)
    assert len(ps) == 5 and all(n.path is ps[0][0].path for n, _ in ps)


def test_many_paths_batch_parsed_like_one_by_one():
    from raster.geometry.pathdata import parse_path
    rng = np.random.default_rng(11)
    ds = ['M%d,%d' % tuple(rng.integers(0, 90, 2)) +
          ''.join('l%d,%d' % tuple(rng.integers(-5, 6, 2)) for _ in range(5)) + 'z'
          for _ in range(60)]
    ds[7] = 'M 1 1 L 2'                  # malformed: its valid prefix is kept
    body = ''.join('<path d="%s"/>' % d for d in ds).encode()
    t = build_tree(load_document(b'<svg xmlns="http://www.w3.org/2000/svg" width="100" '
                                 b'height="100">' + body + b'</svg>'))
    got = [n.path for n, _ in paths(t)]
    want = [parse_path(d, strict=False) for d in ds]
    want = [p for p in want if len(p.verbs)]
    assert len(got) == len(want)
    for a, b in zip(got, want):
        assert a.verbs.tolist() == b.verbs.tolist()
        assert np.allclose(a.points, b.points, rtol=0, atol=1e-9)


def test_root_background_color_fills_the_whole_viewport():
    # viewBox 0 0 10 10 shown in 40 x 20 px (meet: centred, 2 px per unit);
    # the background covers the whole 40 x 20 viewport, under the content
    t = build_tree(load_document(
        b'<svg xmlns="http://www.w3.org/2000/svg" width="40" height="20" viewBox="0 0 10 10" '
        b'style="background-color: #0000ff80"><rect width="1" height="1"/></svg>'))
    (bg, m), (rect, _) = paths(t)
    assert bg.fill.paint.color == pytest.approx((0.0, 0.0, 1.0, 128 / 255))
    x0, y0, x1, y1 = bg.path.control_box()
    corners = m.apply([[x0, y0], [x1, y1]])
    assert corners.ravel().tolist() == pytest.approx([0.0, 0.0, 40.0, 20.0])
    plain = build_tree(load_document(
        b'<svg xmlns="http://www.w3.org/2000/svg" width="4" height="2" '
        b'style="background-color: transparent"><rect width="1" height="1"/></svg>'))
    assert len(paths(plain)) == 1


def test_mask_cycle_through_children_is_cut_at_the_back_reference():
    # mask1's rect references mask2, whose rect references mask1 again: the
    # back reference (rect in mask2) is dropped for the whole document, so
    # mask2 applied anywhere has an unmasked rect, and mask1's rect keeps
    # mask2 (resvg's choice: painting order decides nothing here)
    t = build_tree(load_document(
        b'<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10">'
        b'<mask id="m1"><rect id="r1" width="10" height="10" fill="white" mask="url(#m2)"/></mask>'
        b'<mask id="m2"><rect id="r2" width="10" height="10" fill="white" mask="url(#m1)"/></mask>'
        b'<rect id="a" width="10" height="5" mask="url(#m1)"/>'
        b'<rect id="b" y="5" width="10" height="5" mask="url(#m2)"/></svg>'))
    groups = {n.id: n for n, _ in walk(t.root) if isinstance(n, Group) and n.id}
    m1, m2 = groups['a'].mask, groups['b'].mask
    inner1 = [n for n, _ in walk(m1.root) if isinstance(n, Group) and n.mask is not None]
    assert len(inner1) == 1 and inner1[0].mask.id == 'm2'          # r1 keeps mask2
    assert not [n for n, _ in walk(m2.root) if isinstance(n, Group) and n.mask is not None]


def test_group_opacity_over_one_paint_is_folded_into_the_paint():
    """opacity on a shape painted once needs no layer: the builder folds it
    into fill-opacity (or stroke-opacity); with both fill and stroke the
    layer stays, since the stroke must not show the fill through it."""
    import numpy as np
    import raster
    from raster.tree import Group, PathNode, walk
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="40" height="20">'
           '<circle cx="10" cy="10" r="8" fill="red" fill-opacity="0.5" opacity="0.5"/>'
           '<circle cx="30" cy="10" r="8" fill="blue" stroke="black" opacity="0.5"/></svg>')
    tree = raster.load_svg(svg.encode())
    paths = [n for n, _ in walk(tree.root) if isinstance(n, PathNode)]
    groups = [n for n, _ in walk(tree.root) if isinstance(n, Group) and n.opacity < 1]
    assert paths[0].fill.opacity == 0.25
    assert len(groups) == 1 and groups[0].children[0] is paths[1]
    img = raster.render(svg.encode(), premultiplied=True)
    # red at 25 % over transparent, in the circle's interior
    assert abs(int(img[10, 10, 0]) - 64) <= 1 and abs(int(img[10, 10, 3]) - 64) <= 1


# -- what the builder shares and memoizes ---------------------------------------

def test_folded_opacity_stays_with_its_own_shape():
    # siblings with one computed style share the style work, not the paints:
    # folding one shape's opacity into its fill leaves the others alone
    t = tree_of('<g fill="red" stroke="none">'
                '<rect width="1" height="1"/><rect width="1" height="1" opacity="0.5"/>'
                '<rect width="1" height="1"/><path d="M0 0h1v1z" opacity="0.25"/>'
                '<path d="M0 0h1v1z"/></g>')
    fills = [n.fill for n, _ in paths(t)]
    assert [f.opacity for f in fills] == [1.0, 0.5, 1.0, 0.25, 1.0]
    assert len({id(f) for f in fills}) == 5
    assert all(f.paint.color == (1.0, 0.0, 0.0, 1.0) for f in fills)


def test_identical_shapes_share_one_path_and_lengths_follow_their_viewport():
    t = tree_of('<rect x="10%" width="5" height="5"/><rect x="10%" width="5" height="5"/>'
                '<svg x="0" width="100" height="100"><rect x="10%" width="5" height="5"/></svg>'
                '<circle r="3"/><circle r="3" transform="scale(100)"/>')
    (a, _), (b, _), (c, _), (d, _), (e, _) = paths(t)
    assert a.path is b.path and box(a) == (20.0, 0.0, 25.0, 5.0)
    assert box(c) == (10.0, 0.0, 15.0, 5.0)          # 10 % of the nested viewport
    # the scaled circle is flattened finer: not the same path
    assert d.path is not e.path and len(e.path.verbs) > len(d.path.verbs)


def test_identity_transforms_add_no_group():
    t = tree_of('<rect transform="translate(0,0)" width="1" height="1"/>'
                '<rect transform="scale(1) rotate(0)" width="1" height="1"/>'
                '<rect transform="translate(-0)" width="1" height="1" id="r"/>')
    assert all(isinstance(n, PathNode) for n in t.root.children)
    assert len(t.root.children) == 3 and t.ids['r'] is t.root.children[2]


def test_the_garbage_collector_is_left_alone(monkeypatch):
    """The library never changes the application's collector state (the
    commands pause it themselves: tests/cli/test_process.py)."""
    import gc
    calls = []
    for name in ('disable', 'enable', 'freeze', 'unfreeze', 'set_threshold', 'collect'):
        monkeypatch.setattr(gc, name, lambda *a, _n=name: calls.append(_n))
    t = tree_of('<rect width="1" height="1"/><text>x</text><g opacity="0.5"><circle r="2"/></g>')
    raster.render(b'<svg xmlns="http://www.w3.org/2000/svg" width="4" height="4">'
                  b'<rect width="2" height="2"/></svg>')
    assert calls == [] and len(t.root.children) == 3     # rect, text (bundled font), g


def test_conditional_attributes_found_in_one_pass():
    t = tree_of('<g systemLanguage="fr"><rect width="1" height="1"/></g>'
                '<rect id="x" requiredExtensions="" width="2" height="2"/>'
                '<rect id="en" systemLanguage="en-US" width="3" height="3"/>'
                '<switch><rect systemLanguage="de" width="4" height="4"/>'
                '<rect id="y" width="5" height="5"/></switch>')
    assert [box(n) for n, _ in paths(t)] == [(0.0, 0.0, 3.0, 3.0), (0.0, 0.0, 5.0, 5.0)]


@pytest.mark.parametrize('vb, drawn', [('0 0 10 -10', True), ('0 0 10', True), ('a b c d', True),
                                       ('0 0 0 10', False), ('0 0 10 0', False)])
def test_invalid_viewbox_is_ignored_and_a_zero_one_disables(vb, drawn):
    # SVG 2: an invalid viewBox is as if absent; a zero width or height
    # disables rendering -- on nested svg, symbol instances and markers alike
    for body in ('<svg width="50" height="50" viewBox="%s"><rect width="10" height="10"/></svg>',
                 '<symbol id="s" viewBox="%s"><rect width="10" height="10"/></symbol>'
                 '<use href="#s" width="50" height="50"/>',
                 '<marker id="m" viewBox="%s" markerWidth="4" markerHeight="4">'
                 '<rect width="10" height="10"/></marker>'
                 '<path d="M20 20 H80" fill="none" stroke="red" marker-end="url(#m)"/>'):
        t = tree_of(body % vb)
        nodes = [n for n, _ in walk(t.root)]
        nodes += [m for n in nodes if isinstance(n, PathNode) and n.markers is not None
                  for m, _ in walk(n.markers)]
        filled = [n for n in nodes if isinstance(n, PathNode) and n.fill is not None]
        assert bool(filled) == drawn, body


@pytest.mark.parametrize('pattern, fallback', [
    ('<pattern id="p" width="20" height="20" patternUnits="userSpaceOnUse"/>', True),
    ('<pattern id="q" width="20" height="20" patternUnits="userSpaceOnUse"/>'
     '<pattern id="p" href="#q" height="30"/>', True),
    ('<pattern id="p" width="0" height="20"><rect width="5" height="5"/></pattern>', True),
    ('<pattern id="p" width="10" height="-1"><rect width="5" height="5"/></pattern>', True),
    ('<pattern id="p" width="10" height="10" viewBox="0 0 10 0"><rect width="5" height="5"/>'
     '</pattern>', True),
    # content that draws nothing is a transparent pattern, not a failure
    ('<pattern id="p" width="10" height="10" patternUnits="userSpaceOnUse"><g/></pattern>',
     False),
])
def test_a_pattern_that_cannot_paint_takes_the_fallback(pattern, fallback):
    t = tree_of(pattern + '<rect width="50" height="50" fill="url(#p) #00ff00"/>')
    fills = [n.fill for n, _ in walk(t.root) if isinstance(n, PathNode)]
    if fallback:
        assert len(fills) == 1 and fills[0].paint == SolidPaint((0.0, 1.0, 0.0, 1.0))
    else:
        assert all(f is None or not isinstance(f.paint, SolidPaint) for f in fills)


@pytest.mark.parametrize('units', ['', 'patternUnits="userSpaceOnUse" '
                                       'patternContentUnits="objectBoundingBox"'])
def test_object_bounding_box_pattern_on_a_line_takes_the_fallback(units):
    t = tree_of('<pattern id="p" width="0.5" height="0.5" %s><rect width="5" height="5"/>'
                '</pattern><path d="M10 10 H90" stroke="url(#p) #0000ff"/>' % units)
    (n, _), = [(n, m) for n, m in walk(t.root) if isinstance(n, PathNode)]
    assert n.stroke.paint == SolidPaint((0.0, 0.0, 1.0, 1.0))


@pytest.mark.parametrize('invisible', [
    '<rect x="0" y="0" width="100" height="80" opacity="0"/>',
    '<rect x="0" y="0" width="100" height="80" fill="none"/>',
    '<rect x="0" y="0" width="100" height="80" fill="url(#nothing)"/>',
    '<rect x="0" y="0" width="100" height="80" visibility="hidden"/>',
    '<g opacity="0"><rect x="0" y="0" width="100" height="80" fill="blue"/></g>',
    '<use href="#r" opacity="0"/>',
    '<image width="100" height="80" opacity="0" preserveAspectRatio="xMinYMin meet" '
    'href="data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAQAAAADCAYAAAC09K7GAAAAKUlEQVR4nGN4'
    'Zun2/+Ovd/9X3Lrz37V67n8GZM4zS7f/DMicj7/e/QcAllEj4JIVAnkAAAAASUVORK5CYII="/>',
])
def test_invisible_children_count_in_the_object_bounding_box(invisible):
    # the clip path's objectBoundingBox rectangle scales with the group's box,
    # which is 0..100 x 0..80 whatever the invisible child paints
    from raster.parser.boxes import object_box
    t = tree_of('<defs><rect id="r" width="100" height="80"/><clipPath id="c" '
                'clipPathUnits="objectBoundingBox"><rect width="1" height="1"/></clipPath></defs>'
                '<g id="g" clip-path="url(#c)">%s<rect x="40" y="30" width="20" height="20" '
                'fill="red"/></g>' % invisible)
    g = t.ids['g']
    assert object_box(g.children) == pytest.approx((0, 0, 100, 80))
    cp = g.clip_path
    (clip_rect_node, m), = [(n, m) for n, m in walk(cp.root, cp.transform)
                            if isinstance(n, PathNode)]
    assert box(clip_rect_node, m) == pytest.approx((0, 0, 100, 80))


def _external_docs(tmp_path):
    lib = tmp_path / 'doc' / 'lib'
    lib.mkdir(parents=True)
    (lib / 'a.svg').write_text(
        '<svg xmlns="http://www.w3.org/2000/svg"><style>.c { fill: #00ff00 }</style>'
        '<rect id="r" class="c" width="10" height="10"/><use id="u" href="b.svg#r2"/>'
        '<use id="loop" href="b.svg#back"/>'
        '<g id="many">%s</g></svg>' % ''.join('<rect width="1" height="1"/>' for _ in range(50)))
    (lib / 'b.svg').write_text('<svg xmlns="http://www.w3.org/2000/svg"><rect id="r2" x="5" '
                               'width="3" height="3" fill="blue"/><use id="back" '
                               'href="a.svg#loop"/></svg>')
    (tmp_path / 'outside.svg').write_text('<svg xmlns="http://www.w3.org/2000/svg"><rect '
                                          'id="o" width="9" height="9"/></svg>')
    return tmp_path / 'doc'


def _filled(t):
    return [n for n, _ in walk(t.root) if isinstance(n, PathNode) and n.fill is not None]


def test_use_of_an_element_in_another_local_file(tmp_path):
    doc = _external_docs(tmp_path)
    root = load_document(b'<svg xmlns="http://www.w3.org/2000/svg"><use href="lib/a.svg#r" '
                         b'x="20"/><use href="lib/a.svg#u"/></svg>')
    t = build_tree(root, base_dir=str(doc))
    (a, ma), (b, mb) = [(n, m) for n, m in walk(t.root) if isinstance(n, PathNode)]
    # styled by the other file's style sheet, placed by the use; chains follow
    assert a.fill.paint == SolidPaint((0.0, 1.0, 0.0, 1.0)) and box(a, ma) == (20, 0, 30, 10)
    assert b.fill.paint == SolidPaint((0.0, 0.0, 1.0, 1.0)) and box(b, mb) == (5, 0, 8, 3)
    assert not t.ids.get('r')               # the other file's ids are not this tree's


@pytest.mark.parametrize('href', ['../outside.svg#o', 'lib/a.svg#missing', 'lib/a.svg#loop',
                                  'http://localhost/a.svg#r', 'lib/nofile.svg#r'])
def test_external_use_references_that_are_not_followed(tmp_path, href):
    doc = _external_docs(tmp_path)
    root = load_document(('<svg xmlns="http://www.w3.org/2000/svg"><use href="%s"/></svg>'
                          % href).encode())
    with pytest.warns(RasterWarning):
        t = build_tree(root, base_dir=str(doc))
    assert _filled(t) == []


def test_external_use_counts_against_the_element_limit(tmp_path):
    doc = _external_docs(tmp_path)
    root = load_document(('<svg xmlns="http://www.w3.org/2000/svg">%s</svg>'
                          % ('<use href="lib/a.svg#many"/>' * 10)).encode())
    with pytest.warns(RasterWarning, match='more than 120 nodes'):
        t = build_tree(root, base_dir=str(doc), max_elements=120)
    assert len(_filled(t)) < 120


def test_external_use_is_refused_inside_svg_images(tmp_path):
    doc = _external_docs(tmp_path)
    root = load_document(b'<svg xmlns="http://www.w3.org/2000/svg"><use href="lib/a.svg#r"/>'
                         b'</svg>')
    with pytest.warns(RasterWarning, match='refused'):
        t = build_tree(root, base_dir=str(doc), image_depth=1)
    assert _filled(t) == []


@pytest.mark.parametrize('user, listed, passes', [
    (('en',), 'en', True), (('en',), 'en-GB', True), (('en',), 'EN-gb', True),
    (('en-GB',), 'en', True), (('en-GB',), 'en-US', True), (('zh',), 'zh-Hant-TW', True),
    (('de', 'en'), 'fr, en', True), (('de',), 'fr, en', False), (('en',), 'eng', False),
])
def test_system_language_compares_primary_subtags(user, listed, passes):
    t = tree_of('<rect systemLanguage="%s" width="5" height="5"/>' % listed, languages=user)
    assert bool([n for n, _ in walk(t.root) if isinstance(n, PathNode)]) == passes


def test_a_user_space_clip_path_is_built_once_and_shared():
    # many elements clipped by one userSpaceOnUse clip path share one
    # ClipPath; objectBoundingBox clip paths still follow each element's box
    body = ('<clipPath id="u"><rect width="50" height="50"/></clipPath>'
            '<clipPath id="o" clipPathUnits="objectBoundingBox">'
            '<rect width="0.5" height="0.5"/></clipPath>'
            + ''.join('<rect x="%d" width="10" height="10" clip-path="url(#u)"/>' % (20 * i)
                      for i in range(4))
            + '<rect width="10" height="10" clip-path="url(#o)"/>'
              '<rect width="40" height="40" clip-path="url(#o)"/>'
              '<g transform="scale(2)"><rect width="10" height="10" clip-path="url(#u)"/></g>')
    t = tree_of(body)
    clips = [n.clip_path for n, _ in walk(t.root)
             if isinstance(n, Group) and n.clip_path is not None]
    user = [c for c in clips if c.id == 'u']
    obb = [c for c in clips if c.id == 'o']
    # one per CTM (arcs are converted for the device size): the four rects
    # share theirs, the scaled one has its own
    assert len(user) == 5 and len({id(c) for c in user[:4]}) == 1 and user[4] is not user[0]
    assert len(obb) == 2 and obb[0].transform != obb[1].transform
    img = raster.render(('<svg xmlns="http://www.w3.org/2000/svg" width="200" height="200">'
                         '%s</svg>' % body).encode())
    # the rects at x = 60 (outside the 50 px clip) draw nothing; x = 40 half
    assert img[5, 45, 3] == 255 and img[5, 65, 3] == 0 and img[5, 55, 3] == 0
