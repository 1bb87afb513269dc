"""The render tree's types: enums equal to their SVG keywords, Group
layers, Stroke carrying the kernel's stroke style, walk order, and the
parser's promise that no objectBoundingBox units reach the tree."""

import dataclasses

import pytest

from raster.parser import build_tree
from raster.parser.document import load_document
from raster.geometry.stroking import StrokeStyle
from raster.geometry.transform import Affine
from raster.tree import (BlendMode, Fill, FillRule, Group, LinearGradient, MaskType, PaintItem,
                         PathNode, Pattern, RadialGradient, SolidPaint, SpreadMethod, Stroke,
                         walk)
from raster.tree import filter as F

RED = SolidPaint((1.0, 0.0, 0.0, 1.0))


@pytest.mark.parametrize('enum,word', [(BlendMode.COLOR_DODGE, 'color-dodge'),
                                       (MaskType.ALPHA, 'alpha'), (SpreadMethod.REFLECT, 'reflect'),
                                       (PaintItem.MARKERS, 'markers'), (FillRule.EVENODD, 'evenodd'),
                                       (F.CompositeOperator.ARITHMETIC, 'arithmetic'),
                                       (F.Source.ALPHA, 'SourceAlpha')])
def test_enums_equal_their_keywords(enum, word):
    assert enum == word and type(enum)(word) is enum and hash(enum) == hash(word)


def test_sixteen_blend_modes():
    assert len(BlendMode) == 16


def test_group_needs_a_layer_only_for_effects():
    assert not Group(transform=Affine.scale(2)).needs_layer
    for g in (Group(opacity=0.5), Group(blend_mode=BlendMode.MULTIPLY), Group(isolate=True),
              Group(filters=(F.Filter(None, []),))):
        assert g.needs_layer


def test_stroke_carries_the_kernels_style():
    s = Stroke.of(RED, width=3, join='round', dash=(1, 2))
    assert isinstance(s.style, StrokeStyle) and s.width == 3 and s.style.dash == (1.0, 2.0)
    assert s == Stroke(RED, StrokeStyle(width=3, join='round', dash=(1, 2)))


def test_paints_are_immutable():
    g = LinearGradient(0, 0, 1, 0, ())
    with pytest.raises(dataclasses.FrozenInstanceError):
        g.x1 = 3


def test_walk_is_document_order_with_transforms():
    a, b, c = (PathNode(id=i) for i in 'abc')
    inner = Group(id='g', transform=Affine.translate(5, 0), children=[b])
    root = Group(transform=Affine.scale(2), children=[a, inner, c])
    order = [(n.id, t) for n, t in walk(root)]
    assert [i for i, _ in order] == ['', 'a', 'g', 'b', 'c']
    assert dict(order)['b'] == Affine.scale(2) @ Affine.translate(5, 0)


def _paints(tree):
    for n, _ in walk(tree.root):
        if isinstance(n, PathNode):
            for f in (n.fill, n.stroke):
                if f is not None:
                    yield f.paint


@pytest.mark.parametrize('units', ['objectBoundingBox', 'userSpaceOnUse'])
def test_the_parser_resolves_bounding_box_units(units):
    """Whatever the units, the tree's gradients and patterns paint in the
    node's user space: the same gradient drawn on boxes of two sizes gets
    two transforms for objectBoundingBox units, one for user space."""
    doc = ('<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">'
           '<linearGradient id="g" gradientUnits="%s"><stop/><stop offset="1"/></linearGradient>'
           '<pattern id="p" width="0.5" height="0.5" patternUnits="%s"><rect width="1" height="1"/>'
           '</pattern><rect width="10" height="10" fill="url(#g)" stroke="url(#p)"/>'
           '<rect x="20" width="40" height="20" fill="url(#g)" stroke="url(#p)"/></svg>'
           % (units, units))
    paints = list(_paints(build_tree(load_document(doc.encode()))))
    assert len(paints) == 4
    assert all(isinstance(p, (LinearGradient, RadialGradient, Pattern, SolidPaint))
               for p in paints)
    assert not any(hasattr(p, 'units') for p in paints)
    g1, p1, g2, p2 = paints
    if units == 'objectBoundingBox':
        assert g1.transform == Affine(10, 0, 0, 10, 0, 0)
        assert g2.transform == Affine(40, 0, 0, 20, 20, 0)
        assert p1.rect == (0, 0, 5, 5) and p2.rect == (20, 0, 20, 10)
    else:
        assert g1.transform == g2.transform == Affine()
        assert p1.rect == p2.rect == (0, 0, 0.5, 0.5)


def test_filter_primitives_are_typed_and_inputs_resolved():
    doc = (b'<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10">'
           b'<filter id="f"><feGaussianBlur stdDeviation="2 3" result="b"/>'
           b'<feOffset in="b" dx="1" result="o"/><feBlend in="nope" in2="SourceAlpha" mode="screen"/>'
           b'<feComposite operator="xor" in2="o"/><feConvolveMatrix order="0"/></filter>'
           b'<rect width="5" height="5" filter="url(#f)"/></svg>')
    (g,) = build_tree(load_document(doc)).root.children
    (f,) = g.filters
    blur, off, blend, comp, bad = f.primitives
    assert isinstance(blur, F.GaussianBlur) and blur.std_dev == (2.0, 3.0)
    assert blur.inputs == (F.Source.GRAPHIC,)
    assert isinstance(off, F.Offset) and off.inputs == (F.Result('b'),)
    assert isinstance(blend, F.Blend) and blend.mode is BlendMode.SCREEN
    assert blend.inputs == (F.PREVIOUS, F.Source.ALPHA)      # 'nope' names no result
    assert comp.operator is F.CompositeOperator.XOR and comp.inputs == (F.PREVIOUS, F.Result('o'))
    assert isinstance(bad, F.Flood) and bad.color == F.TRANSPARENT      # in error


def test_a_tree_pickles_and_renders_the_same():
    # what a worker started afresh (no fork) would be sent: every node,
    # paint, effect and path of the tree travels by pickle
    import pickle

    import numpy as np

    from raster.renderer import render_tree
    from raster.svg import load_svg
    doc = b'''<svg xmlns="http://www.w3.org/2000/svg" width="40" height="30">
      <linearGradient id="g"><stop offset="0" stop-color="red"/><stop offset="1"/></linearGradient>
      <radialGradient id="r"><stop offset="0" stop-color="lime"/><stop offset="1"/></radialGradient>
      <pattern id="p" width="4" height="4" patternUnits="userSpaceOnUse">
        <rect width="2" height="2" fill="url(#g)"/></pattern>
      <clipPath id="c"><circle cx="20" cy="15" r="14"/></clipPath>
      <mask id="m"><rect width="40" height="30" fill="white" opacity="0.7"/></mask>
      <filter id="f"><feGaussianBlur stdDeviation="1"/></filter>
      <g clip-path="url(#c)" mask="url(#m)">
        <rect width="20" height="30" fill="url(#g)" stroke="url(#r)" stroke-dasharray="3 1"/>
        <rect x="20" width="20" height="30" fill="url(#p)" filter="url(#f)"/>
      </g>
    </svg>'''
    tree = load_svg(doc)
    copy = pickle.loads(pickle.dumps(tree))
    assert [type(n) for n, _ in walk(copy.root)] == [type(n) for n, _ in walk(tree.root)]
    a = render_tree(tree, dtype='uint8').to_rgba8()
    b = render_tree(copy, dtype='uint8').to_rgba8()
    assert a[..., 3].any() and np.array_equal(a, b)
