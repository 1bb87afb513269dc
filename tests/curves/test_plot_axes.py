"""Readable plots: axes with ticks and a grid in the curve's coordinates,
labelled control and sample points, tangent arrows, the blending-function
panel, joints marked with their continuity, SVG output."""

import io

import numpy as np
import pytest
import resvg_py
from PIL import Image

from raster.curves import Bezier, CatmullRom, CurveError, FunctionSpline, circle_arc
from raster.curves.axes import AXIS_COLORS, nice_step, nice_ticks, tick_text
from raster.curves.plot import PALETTE, Plot, plot_curve, text_width

CUBIC = [[1, 1], [2, 3], [4, 3], [6, 4]]
STEPS = np.arange(0, 1.01, 0.2)


def px(img, xy):
    x, y = xy
    return img[int(y), int(x), :3].astype(int)


@pytest.mark.parametrize('lo,hi,target,want', [
    (0.8, 6.2, 6, [1, 2, 3, 4, 5, 6]), (0, 1, 5, [0, 0.2, 0.4, 0.6, 0.8, 1]),
    (-0.07, 0.31, 4, [0, 0.1, 0.2, 0.3]), (1000, 1600, 3, [1000, 1200, 1400, 1600]),
    (-3, 3, 6, [-3, -2, -1, 0, 1, 2, 3])])
def test_nice_ticks(lo, hi, target, want):
    np.testing.assert_allclose(nice_ticks(lo, hi, target), want)
    assert tick_text(0.30000000000000004, 0.1) == '0.3'
    assert nice_step(7.3, 8) == 1.0 and nice_step(7.3, 7) == 2.0


def test_axes_grid_and_tick_labels_in_curve_coordinates():
    plot = Plot(Bezier(CUBIC), [], width=640, labels=False)
    img = plot.render()
    T = plot.transform
    # the grid line x = 5 at y = 1.5 (off the hull and the curve)
    X, Y = T.apply(np.array([[5.0, 1.5]]))[0]
    # a 1 px line at a fractional position: between the grid colour and white
    c = px(img, (X, Y))
    assert np.all(c <= 255 * np.array(AXIS_COLORS['grid']) + 12) and np.all(c < 240)
    np.testing.assert_array_equal(px(img, (X + 6, Y)), [255, 255, 255])
    # tick labels: dark glyph pixels under the frame at x = 1 .. 6
    left, top, w, h = plot.panel.rect
    for v in range(1, 7):
        X = T.apply(np.array([[v, 0.0]]))[0, 0]
        strip = img[int(top + h + 8):int(top + h + 20), int(X - 5):int(X + 5), :3]
        assert strip.min() < 120, v
    # the data range shown covers the control points with a margin
    (x0, x1), (y0, y1) = plot.panel.xlim, plot.panel.ylim
    assert x0 < 1 and x1 > 6 and y0 < 1 and y1 > 4


def test_labels_name_points_and_do_not_overlap():
    plot = Plot(Bezier(CUBIC), STEPS, tangents=True)
    texts = [t for t, _, _ in plot.point_labels]
    for want in ('P0 (1, 1)', 'P3 (6, 4)', 't=0.2', '(1.712, 1.984)', '(4.808, 3.496)'):
        assert want in texts, want
    boxes = []
    for t, x, y in plot.point_labels:
        size = 12 if t.startswith('t=') else 11
        boxes.append((x, y - size * 0.75, x + text_width(t, size), y))
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            ow = min(a[2], b[2]) - max(a[0], b[0])
            oh = min(a[3], b[3]) - max(a[1], b[1])
            assert ow <= 0 or oh <= 0, (a, b)


def test_tangent_arrows_point_along_the_tangent():
    b = Bezier(CUBIC)
    plot = Plot(b, [0.0], tangents=True, labels=False)
    img = plot.render()
    T = plot.transform
    p = b.eval(0.0)
    d = b.tangent(0.0) / np.linalg.norm(b.tangent(0.0))
    # 3/4 along the arrow: the tangent colour (the arrow is 14% of the span)
    q = T.apply((p + 0.75 * 0.14 * 5 * d).reshape(1, 2))[0]
    c = px(img, q)
    assert c[1] > c[0] + 40 and c[1] > c[2], c


def test_blend_panel_shows_the_bernstein_functions():
    b = Bezier(CUBIC)
    plot = Plot(b, [0.25], blend=True)
    assert plot.height > Plot(b, [0.25]).height + 150
    img = plot.render()
    P = plot.blend_panel
    # B3,0(t) = (1-t)^3 at t = 0.1: the first palette colour
    X, Y = P.device([[0.1, 0.9 ** 3]])[0]
    c = px(img, (X, Y))
    np.testing.assert_allclose(c, 255 * np.array(PALETTE[0]), atol=60)
    with pytest.raises(CurveError, match='no blending functions'):
        Plot(FunctionSpline([0, 1, 2], [0, 1, 0]), [], blend=True)


def test_joints_are_marked_with_their_continuity():
    plot = Plot(CatmullRom([[0, 0], [1, 2], [3, 2], [4, 0]]), [0.5])
    assert [t for t, _, _ in plot.point_labels].count('C1') == 2
    arc = Plot(circle_arc([0, 0], 1, 0, np.pi))
    assert 'C1 G2' in [t for t, _, _ in arc.point_labels]


@pytest.mark.parametrize('kw', [dict(tangents=True, blend=True), dict(axes=False)])
def test_svg_matches_the_png(kw):
    plot = Plot(Bezier(CUBIC), STEPS, **kw)
    ours = plot.render().astype(float)
    ref = np.asarray(Image.open(io.BytesIO(bytes(resvg_py.svg_to_bytes(
        svg_string=plot.to_svg())))).convert('RGBA')).astype(float)
    assert ref.shape == ours.shape
    diff = np.abs(ours - ref)
    assert diff.mean() < 0.6
    assert np.percentile(diff, 99.9) < 60


def test_plot_files(tmp_path):
    plot_curve(Bezier(CUBIC), tmp_path / 'a.svg', STEPS, blend=True, title='A B C D')
    s = (tmp_path / 'a.svg').read_text()
    assert s.startswith('<svg') and s.count('<path') > 50
    plot_curve(circle_arc([0, 0], 2, 0, 2 * np.pi), tmp_path / 'c.png', [0.25])
    assert Image.open(tmp_path / 'c.png').size[0] == 640
