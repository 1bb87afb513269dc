"""transform-origin and transform-box (CSS Transforms 1): the reference box
of the origin is the viewport (view-box, the default) or the element's own
fill or stroke box; transforms on text content children are ignored."""

import math
import warnings

import numpy as np
import pytest

from raster.errors import RasterWarning
from raster.geometry.bounds import bbox
from raster.parser import build_tree
from raster.parser.document import load_document
from raster.parser.values import LengthContext, parse_transform_origin
from raster.tree import PathNode, walk


def tree(body, size=200):
    doc = '<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d">%s</svg>' % (size, size, body)
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', RasterWarning)
        return build_tree(load_document(doc.encode()))


def device_boxes(t):
    """(K, 4) float64: the device box of every path of the tree."""
    return np.array([bbox(n.path, m) for n, m in walk(t.root) if isinstance(n, PathNode)])


@pytest.mark.parametrize('value, box, want', [
    ('center', (10, 20, 40, 60), (30.0, 50.0)),
    ('right bottom', (10, 20, 40, 60), (50.0, 80.0)),
    ('bottom right', (10, 20, 40, 60), (50.0, 80.0)),
    ('25% 75%', (10, 20, 40, 60), (20.0, 65.0)),
    ('5px 10', (10, 20, 40, 60), (15.0, 30.0)),        # lengths start at the box corner
    ('left 50%', (-10, -10, 20, 20), (-10.0, 0.0)),
    ('top', (0, 0, 40, 60), (20.0, 0.0)),
    ('25% top', None, (50.0, 0.0)),                     # view-box: the viewport
])
def test_origin_in_a_reference_box(value, box, want):
    ctx = LengthContext(width=200, height=100)
    assert parse_transform_origin(value, ctx, box) == pytest.approx(want)


@pytest.mark.parametrize('cls, style', [('fill-box', 'fill-box'), ('content-box', 'fill-box'),
                                        ('stroke-box', 'stroke-box'), ('border-box', 'stroke-box')])
def test_shape_origin_in_its_own_box(cls, style):
    """rotate(30) about the centre of the shape's own box equals
    rotate(30 cx cy); the stroke box is the fill box widened by half the
    stroke width (content-box and border-box stand for fill-box and
    stroke-box on SVG elements)."""
    got = tree('<rect x="20" y="30" width="40" height="60" stroke="red" stroke-width="10" '
               'transform="rotate(30)" transform-origin="left top" style="transform-box: %s"/>'
               % cls)
    o = (20, 30) if style == 'fill-box' else (15, 25)
    want = tree('<rect x="20" y="30" width="40" height="60" stroke="red" stroke-width="10" '
                'transform="rotate(30 %g %g)"/>' % o)
    np.testing.assert_allclose(device_boxes(got), device_boxes(want), atol=1e-9)


def test_group_origin_in_its_content_box():
    got = tree('<g transform="scale(0.5)" transform-origin="center" style="transform-box: fill-box">'
               '<rect x="20" y="20" width="40" height="40"/><circle cx="100" cy="100" r="20"/></g>')
    # content box (20, 20)-(120, 120): centre (70, 70)
    want = tree('<g transform="translate(70 70) scale(0.5) translate(-70 -70)">'
                '<rect x="20" y="20" width="40" height="40"/><circle cx="100" cy="100" r="20"/></g>')
    np.testing.assert_allclose(device_boxes(got), device_boxes(want), atol=1e-9)
    np.testing.assert_allclose(device_boxes(got)[0], (45.0, 45.0, 65.0, 65.0), atol=1e-9)


def test_view_box_is_the_default_and_the_attribute_is_not_transform_box():
    """transform-box is a property, not a presentation attribute: the
    attribute is ignored and the origin stays in the viewport."""
    a = tree('<rect x="20" y="20" width="40" height="40" transform="rotate(90)" '
             'transform-origin="50% 50%" transform-box="fill-box"/>')
    b = tree('<rect x="20" y="20" width="40" height="40" transform="rotate(90 100 100)"/>')
    np.testing.assert_allclose(device_boxes(a), device_boxes(b), atol=1e-9)


def test_fill_box_without_transform_changes_nothing():
    a = tree('<rect x="20" y="20" width="40" height="40" transform-origin="center" '
             'style="transform-box: fill-box"/>')
    np.testing.assert_allclose(device_boxes(a), [(20.0, 20.0, 60.0, 60.0)])


def test_transforms_inside_text_are_ignored():
    """tspan, textPath and a inside text are not transformable (SVG 2 text
    content children; resvg ignores them too): a transform and an origin on
    them move nothing; the text element's own origin applies."""
    plain = tree('<text x="20" y="60" font-size="30">AB<a>CD</a><tspan>EF</tspan></text>')
    moved = tree('<text x="20" y="60" font-size="30">AB<a transform="translate(0 60)" '
                 'transform-origin="50 50">CD</a><tspan transform="rotate(30)" '
                 'transform-origin="center">EF</tspan></text>')
    np.testing.assert_array_equal(device_boxes(moved), device_boxes(plain))
    a = tree('<text x="20" y="60" font-size="30" transform="rotate(10)" '
             'transform-origin="20 60">GH</text>')
    b = tree('<text x="20" y="60" font-size="30" transform="rotate(10 20 60)">GH</text>')
    np.testing.assert_allclose(device_boxes(a), device_boxes(b), atol=1e-9)
