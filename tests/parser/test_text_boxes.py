"""The object bounding box of text (issue 14): every span's
objectBoundingBox paint uses the box of the whole <text> element, and
text that draws nothing still counts in its parents' boxes."""

import warnings

import numpy as np
import pytest

import raster
from raster.errors import RasterWarning
from raster.parser import build_tree
from raster.parser.document import load_document
from raster.tree import PathNode, walk

SVG = '<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d">%s</svg>'


def tree(body, w=200, h=100):
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', RasterWarning)
        return build_tree(load_document((SVG % (w, h, body)).encode()))


def test_gradient_on_tspans_uses_the_whole_text_box():
    """A gradient in objectBoundingBox units on the text, on a tspan and on
    a tspan that starts a new chunk (x, y) resolves to one transform: the
    box of the whole text element."""
    t = tree('<linearGradient id="g"><stop offset="0" stop-color="red"/><stop offset="1" '
             'stop-color="blue"/></linearGradient><text x="10" y="50" font-size="30" '
             'fill="url(#g)">AB<tspan fill="url(#g)">CD</tspan><tspan x="10" y="90" '
             'fill="url(#g)">E</tspan></text>')
    grads = [n.fill.paint for n, _ in walk(t.root) if isinstance(n, PathNode) and n.fill]
    assert len(grads) == 3
    assert len({g.transform for g in grads}) == 1
    tr = grads[0].transform
    # the box spans both lines: from above the first baseline to below the second
    assert tr.e == pytest.approx(10.0) and tr.f < 50 - 15 and tr.f + tr.d > 90


@pytest.mark.parametrize('attrs', ['visibility="hidden"', 'fill="none"',
                                   'fill="none" stroke="none"'])
def test_text_that_draws_nothing_counts_in_the_group_box(attrs):
    """A clip path in objectBoundingBox units on a group whose only other
    content is a square at the left: hidden or unpainted text far to the
    right widens the group's box, so the clip's left half (0 <= x < 0.5 of
    the box) reaches past the square's right edge and the whole square is
    drawn.  Without the text the clip would cut the square in half."""
    body = ('<clipPath id="c" clipPathUnits="objectBoundingBox"><rect width="0.5" height="1"/>'
            '</clipPath><g clip-path="url(#c)"><rect x="10" y="10" width="40" height="40"/>'
            '<text x="150" y="40" font-size="30" %s>WW</text></g>')
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', RasterWarning)
        img = np.asarray(raster.render((SVG % (200, 60, body % attrs)).encode()))
        alone = np.asarray(raster.render((SVG % (200, 60, body.replace(
            '<text x="150" y="40" font-size="30" %s>WW</text>', ''))).encode()))
    assert img[30, 45, 3] == 255 and img[30, 15, 3] == 255      # the square whole
    assert alone[30, 45, 3] == 0 and alone[30, 15, 3] == 255    # cut at x = 30
    assert img[:, 100:, 3].max() == 0                           # the text draws nothing
