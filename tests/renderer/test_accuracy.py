"""Edge accuracy of the renderer at its default settings (issue 11): the
alpha of curved shapes against an exact-area reference
(raster.testing.span_coverage, 256 sample lines per pixel row)."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st, HealthCheck

import raster
from raster.testing import disc_spans, polygon_spans, span_coverage

NS = 'http://www.w3.org/2000/svg'
# the target: within 8/255 of the exact area at default settings
BOUND = 8.0


def svg(w, h, body):
    return ('<svg xmlns="%s" width="%d" height="%d">%s</svg>' % (NS, w, h, body)).encode()


def alpha(doc, **kw):
    return raster.render(doc, **kw)[..., 3].astype(np.float64)


def ellipse_spans(cx, cy, rx, ry, angle):
    """Spans of an ellipse with semi-axes rx, ry rotated by ``angle``: on a
    horizontal line, the quadratic in x of the ellipse's equation."""
    c, s = np.cos(angle), np.sin(angle)

    def fn(ys):
        dy = ys - cy
        # ((x c + y s) / rx)^2 + ((-x s + y c) / ry)^2 = 1 in centred coordinates
        A = (c / rx) ** 2 + (s / ry) ** 2
        B = 2 * dy * (c * s / rx ** 2 - s * c / ry ** 2)
        C = dy ** 2 * ((s / rx) ** 2 + (c / ry) ** 2) - 1
        disc = B * B - 4 * A * C
        li = np.flatnonzero(disc > 0)
        r = np.sqrt(disc[li])
        return li, cx + (-B[li] - r) / (2 * A), cx + (-B[li] + r) / (2 * A)
    return fn


@pytest.mark.parametrize('r', [0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 7.5, 30.0, 120.0])
def test_circles_of_many_radii_within_bound(r):
    rng = np.random.default_rng(int(r * 100))
    size = int(2 * r + 6)
    for _ in range(3):
        cx, cy = size / 2 + rng.uniform(-0.5, 0.5, 2)
        a = alpha(svg(size, size, '<circle cx="%.5f" cy="%.5f" r="%g"/>' % (cx, cy, r)))
        ref = 255 * span_coverage(disc_spans([(cx, cy, r)]), size, size, lines=256)
        assert np.abs(a - ref).max() <= BOUND, (r, cx, cy)


def test_tiny_hole_stays_round():
    # a hole of radius 0.5 px (evenodd) is a disc, not a square: its pixels
    # keep the exact area within the bound
    body = ('<path fill-rule="evenodd" d="M2 2h12v12h-12z M8.3 8.1 m-0.5 0 '
            'a0.5 0.5 0 1 0 1 0 a0.5 0.5 0 1 0 -1 0z"/>')
    a = alpha(svg(16, 16, body))
    ref = 255 * (span_coverage(polygon_spans([[(2, 2), (14, 2), (14, 14), (2, 14)]]), 16, 16, 256)
                 - span_coverage(disc_spans([(8.3, 8.1, 0.5)]), 16, 16, 256))
    assert np.abs(a - ref).max() <= BOUND


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.floats(2.0, 40.0), st.floats(0.2, 1.0), st.floats(0.0, np.pi),
       st.floats(0, 1), st.floats(0, 1))
def test_rotated_ellipses_within_bound(rx, ratio, angle, fx, fy):
    ry = rx * ratio
    size = int(2 * rx + 6)
    cx, cy = size / 2 + fx, size / 2 + fy
    body = ('<ellipse cx="0" cy="0" rx="%.9f" ry="%.9f" '
            'transform="translate(%.9f %.9f) rotate(%.9f)"/>'
            % (rx, ry, cx, cy, np.degrees(angle)))
    a = alpha(svg(size + 1, size + 1, body))
    ref = 255 * span_coverage(ellipse_spans(cx, cy, rx, ry, angle), size + 1, size + 1, 256)
    assert np.abs(a - ref).max() <= BOUND


@pytest.mark.parametrize("zoom", [0.37, 1.0, 4.5, 20.0])
def test_accuracy_holds_under_zoom(zoom):
    # the bound is in device pixels whatever the document-to-device scale
    doc = svg(40, 40, '<circle cx="20.3" cy="19.6" r="15"/>')
    a = alpha(doc, zoom=zoom)
    h, w = a.shape
    ref = 255 * span_coverage(disc_spans([(20.3 * w / 40, 19.6 * h / 40, 15 * w / 40)]),
                              w, h, lines=256)
    assert np.abs(a - ref).max() <= BOUND


def test_stroked_circle_within_bound():
    doc = svg(60, 60, '<circle cx="30.2" cy="29.7" r="20" fill="none" stroke="#000" '
                      'stroke-width="3"/>')
    a = alpha(doc)
    ref = 255 * (span_coverage(disc_spans([(30.2, 29.7, 21.5)]), 60, 60, 256)
                 - span_coverage(disc_spans([(30.2, 29.7, 18.5)]), 60, 60, 256))
    assert np.abs(a - ref).max() <= BOUND


def test_clip_path_circle_within_bound():
    doc = svg(50, 50, '<clipPath id="c"><circle cx="25.4" cy="24.8" r="18"/></clipPath>'
                      '<rect width="50" height="50" clip-path="url(#c)"/>')
    ref = 255 * span_coverage(disc_spans([(25.4, 24.8, 18)]), 50, 50, 256)
    assert np.abs(alpha(doc) - ref).max() <= BOUND


def test_pixel_aligned_rectangles_exactly_binary():
    a = alpha(svg(30, 30, '<rect x="3" y="4" width="20" height="11"/>'
                          '<rect x="5" y="17" width="7" height="9" rx="0"/>'))
    assert set(np.unique(a).tolist()) <= {0.0, 255.0}
    assert (a == 255).sum() == 20 * 11 + 7 * 9


def test_finer_tolerance_than_default_is_not_worse():
    doc = svg(72, 72, '<circle cx="36.3" cy="35.7" r="30"/>')
    ref = 255 * span_coverage(disc_spans([(36.3, 35.7, 30)]), 72, 72, 256)
    e_def = np.abs(alpha(doc) - ref).max()
    e_fine = np.abs(alpha(doc, tolerance=0.005) - ref).max()
    e_coarse = np.abs(alpha(doc, tolerance=0.5) - ref).max()
    assert e_fine <= e_def <= BOUND < e_coarse
