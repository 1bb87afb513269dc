"""Tests of raster.curves.plot and ``curve --plot``: pixels where the plot
puts things, and the PNG (raster) against resvg's rendering of the SVG."""

import io
import json

import numpy as np
import pytest
import resvg_py
from PIL import Image

from raster.curves import Bezier, CatmullRom, BSpline, CurveError
from raster.curves.plot import COLORS, Plot, plot_curve, text_path
from raster_cli.curve import main

CUBIC = [[1, 1], [2, 3], [4, 3], [6, 4]]


def pixel(img, xy):
    x, y = xy
    return img[int(y), int(x)].astype(int)


def device(plot, p):
    return plot.transform.apply(np.asarray(p, float)[:2].reshape(1, 2))[0]


def test_pixels_of_points_curve_and_background():
    b = Bezier(CUBIC)
    plot = Plot(b, params=[0.5])
    img = plot.render()
    assert img.shape == (plot.height, plot.width, 4)
    red = pixel(img, device(plot, b.eval(0.5)))
    assert red[0] > 200 and red[1] < 80 and red[2] < 80            # the sample point disc
    blue = pixel(img, device(plot, b.eval(0.1)))
    assert blue[2] > 100 and blue[0] < 60                          # the curve stroke
    np.testing.assert_array_equal(img[0, 0], [255, 255, 255, 255])  # background
    # y up: the start (1,1) is below the end (6,4) on the image
    assert device(plot, CUBIC[0])[1] > device(plot, CUBIC[-1])[1]


def test_hull_layer_is_drawn():
    # control polygon of the cubic: hull is the triangle (1,1), (6,4), (2,3);
    # its centroid (3, 8/3) lies off the curve and off the labels (no axes:
    # the grid line x = 3 would cross it)
    b = Bezier(CUBIC)
    plot = Plot(b, params=[], axes=False, labels=False)
    img = plot.render().astype(int)
    c = pixel(img, device(plot, [3.0, 8.0 / 3.0]))
    hull_rgb = np.array(COLORS['hull'][:3]) * COLORS['hull'][3] + (1 - COLORS['hull'][3])
    np.testing.assert_allclose(c[:3], 255 * hull_rgb, atol=2)
    outside = pixel(img, device(plot, [5.5, 1.2]))
    np.testing.assert_array_equal(outside, [255, 255, 255, 255])


def test_label_is_drawn_next_to_its_point():
    b = Bezier(CUBIC)
    plot = Plot(b, params=[0.5])
    (label, lx, ly), = plot.labels
    assert label == 't=0.5'
    img = plot.render()[..., :3].astype(int)
    box = img[int(ly) - 10:int(ly) + 1, int(lx):int(lx) + 30]
    assert box.min() < 60                       # dark glyph pixels in the label box


def test_text_path_cap_height():
    # Noto Sans cap height is 714 units of 1000: 'I' at 100 px is 71.4 px tall
    x0, y0, x1, y1 = text_path('I', 0, 200, 100).control_box()
    assert y1 == pytest.approx(200, abs=0.01)
    assert y1 - y0 == pytest.approx(71.4, abs=0.05)


@pytest.mark.parametrize('curve,params', [
    (Bezier(CUBIC), [0, 0.25, 0.5, 0.75, 1]),
    (CatmullRom([[0, 0], [1, 2], [3, 2], [4, 0]]), [0, 1, 2, 3]),
    (Bezier([[0, 0, 0], [1, 0, 1], [1, 1, 2]]), [0.5]),
])
def test_png_matches_resvg_rendering_of_svg(curve, params):
    plot = Plot(curve, params)
    ours = plot.render().astype(float)
    png = resvg_py.svg_to_bytes(svg_string=plot.to_svg())
    ref = np.asarray(Image.open(io.BytesIO(bytes(png))).convert('RGBA')).astype(float)
    assert ref.shape == ours.shape
    diff = np.abs(ours - ref)
    assert diff.mean() < 0.5                    # measured 0.05-0.10 (of 255)
    assert np.percentile(diff, 99.9) < 40


def test_plot_file_types(tmp_path):
    b = BSpline([[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]], 3)
    plot_curve(b, tmp_path / 'a.png', params=[0.5], width=300)
    im = Image.open(tmp_path / 'a.png')
    assert im.size[0] == 300
    plot_curve(b, tmp_path / 'a.svg', params=[0.5])
    assert (tmp_path / 'a.svg').read_text().startswith('<svg')
    with pytest.raises(CurveError):
        plot_curve(b, tmp_path / 'a.gif')


def test_cli_plot(tmp_path, capsys):
    out = tmp_path / 'c.png'
    code = main(['catmull-rom', '0,0 1,2 3,2 4,0', '--step', '1', '--plot', str(out),
                 '--json', '--size', '320'])
    obj = json.loads(capsys.readouterr().out)
    assert code == 0 and obj['plot'] == str(out)
    assert Image.open(out).size[0] == 320
    code = main(['bezier', '0,0 1,1', '--plot', str(tmp_path / 'x.png'), '--size', '3'])
    assert code == 2 and 'size' in capsys.readouterr().err


def test_layer_colours_documented():
    plot = Plot(Bezier(CUBIC), [0.5])
    kinds = [st['color'] for _, _, st in plot.layers]
    assert COLORS['curve'] in kinds and COLORS['point'] in kinds and COLORS['label'] in kinds
