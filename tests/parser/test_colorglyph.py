"""Colour glyphs drawn: COLRv0/v1 layers, gradients, composite modes, the
foreground colour, SVG glyphs and bitmaps, checked by pixels of synthetic
fonts (tests/_colorfonts.py: units per em 1000, glyph 'sq' the unit
square, 'lo' its lower half, 'left' its left half).

Every document draws one glyph at font size 100 with its origin at
(20, 120): the glyph square covers user x in [20, 120] and y in [20, 120]
(y down), so glyph-space point (u, v) is at (20 + u / 10, 120 - v / 10).
"""
import os

import numpy as np
import pytest
from fontTools.ttLib.tables.otTables import PaintFormat

from raster.fonts import FontOptions
from raster.svg import load_svg, render
from raster.tree import Group, ImageNode, PathNode, walk

from _colorfonts import SEQUENCES, colr_font, glyph, solid, stops, svg_font
from _shared import SUITE_FONTS

NS = 'xmlns="http://www.w3.org/2000/svg"'
RED, BLUE, GREEN = (255, 0, 0, 255), (0, 0, 255, 255), (0, 255, 0, 255)
CLEAR = (0, 0, 0, 0)


def draw(path, text='A', extra='', family=None, size=(140, 140)):
    fam = family or 'Test Colour'
    svg = ('<svg %s width="%d" height="%d"><text x="20" y="120" font-size="100" '
           'font-family="%s" %s>%s</text></svg>' % (NS, size[0], size[1], fam, extra, text))
    return render(svg.encode(), fonts=FontOptions(files=[path], system=False))


def at(img, u, v):
    """The pixel at glyph-space point (u, v)."""
    x, y = 20 + u / 10.0, 120 - v / 10.0
    return tuple(int(c) for c in img[int(y), int(x)])


def close(a, b, tol=3):
    return all(abs(p - q) <= tol for p, q in zip(a, b))


def test_colrv0_layers_paint_in_order(tmp_path):
    f = colr_font(tmp_path / 'f.ttf', {'A': [('lo', 0), ('left', 1)]})
    img = draw(f)
    assert at(img, 750, 250) == RED            # lower right: 'lo' only
    assert at(img, 250, 250) == BLUE           # lower left: 'left' drawn over 'lo'
    assert at(img, 250, 750) == BLUE
    assert at(img, 750, 750) == CLEAR


@pytest.mark.parametrize('t', [0.25, 0.5, 0.8])
def test_linear_gradient_along_x(tmp_path, t):
    """Red at u = 0 to blue at u = 1000: at u = 1000 t the colour is
    (1 - t) red + t blue (sRGB interpolation)."""
    g = {'Format': PaintFormat.PaintLinearGradient, 'ColorLine': stops((0, 0), (1, 1)),
         'x0': 0, 'y0': 0, 'x1': 1000, 'y1': 0, 'x2': 0, 'y2': 1000}
    img = draw(colr_font(tmp_path / 'f.ttf', {'A': glyph('sq', g)}))
    u = 1000 * t + 5           # the pixel centre lies 0.5 px = 5 units right
    assert close(at(img, 1000 * t, 500), (round(255 * (1 - u / 1000)), 0,
                                          round(255 * u / 1000), 255))


def test_linear_gradient_stops_beyond_the_unit_interval(tmp_path):
    """Stops at offsets -1 and 1.5 over p0 = 0, p1 = 1000: red at
    u = -1000, blue at u = 1500, so at u the blue share is
    (u + 1000) / 2500."""
    g = {'Format': PaintFormat.PaintLinearGradient, 'ColorLine': stops((-1, 0), (1.5, 1)),
         'x0': 0, 'y0': 0, 'x1': 1000, 'y1': 0, 'x2': 0, 'y2': 1000}
    img = draw(colr_font(tmp_path / 'f.ttf', {'A': glyph('sq', g)}))
    s = (495 + 1000) / 2500            # the pixel centre at u = 495
    assert close(at(img, 495, 500), (round(255 * (1 - s)), 0, round(255 * s), 255))


@pytest.mark.parametrize('angle', [30, 135, 200, 315])
def test_sweep_gradient_counter_clockwise_in_glyph_space(tmp_path, angle):
    """A sweep from 0 to 360 degrees about the square's centre: the colour
    at angle a (counter-clockwise from +x, y up) is offset a / 360, here
    measured at the pixel centre nearest to radius 300 at that angle."""
    g = {'Format': PaintFormat.PaintSweepGradient, 'ColorLine': stops((0, 0), (1, 1)),
         'centerX': 500, 'centerY': 500, 'startAngle': 0, 'endAngle': 360}
    img = draw(colr_font(tmp_path / 'f.ttf', {'A': glyph('sq', g)}))
    r = np.radians(angle)
    x, y = int(20 + (500 + 300 * np.cos(r)) / 10), int(120 - (500 + 300 * np.sin(r)) / 10)
    u, v = (x + 0.5 - 20) * 10, (120 - y - 0.5) * 10
    s = (np.degrees(np.arctan2(v - 500, u - 500)) % 360) / 360
    assert close(tuple(int(c) for c in img[y, x]), (round(255 * (1 - s)), 0, round(255 * s), 255))


@pytest.mark.parametrize('mode, expect', [
    # (lower-left, lower-right, upper-left, upper-right) quadrants;
    # source 'lo' red, backdrop 'left' blue
    ('SRC_OVER', (RED, RED, BLUE, CLEAR)),
    ('DEST_OVER', (BLUE, RED, BLUE, CLEAR)),
    ('SRC', (RED, RED, CLEAR, CLEAR)),
    ('DEST', (BLUE, CLEAR, BLUE, CLEAR)),
    ('CLEAR', (CLEAR, CLEAR, CLEAR, CLEAR)),
    ('SRC_IN', (RED, CLEAR, CLEAR, CLEAR)),
    ('DEST_IN', (BLUE, CLEAR, CLEAR, CLEAR)),
    ('SRC_OUT', (CLEAR, RED, CLEAR, CLEAR)),
    ('DEST_OUT', (CLEAR, CLEAR, BLUE, CLEAR)),
    ('SRC_ATOP', (RED, CLEAR, BLUE, CLEAR)),
    ('DEST_ATOP', (BLUE, RED, CLEAR, CLEAR)),
    ('XOR', (CLEAR, RED, BLUE, CLEAR)),
    ('PLUS', ((255, 0, 255, 255), RED, BLUE, CLEAR)),
    ('MULTIPLY', ((0, 0, 0, 255), RED, BLUE, CLEAR)),
    ('SCREEN', ((255, 0, 255, 255), RED, BLUE, CLEAR)),
    ('DARKEN', ((0, 0, 0, 255), RED, BLUE, CLEAR)),
])
def test_composite_modes(tmp_path, mode, expect):
    comp = {'Format': PaintFormat.PaintComposite, 'CompositeMode': mode,
            'SourcePaint': glyph('lo', solid(0)), 'BackdropPaint': glyph('left', solid(1))}
    img = draw(colr_font(tmp_path / 'f.ttf', {'A': comp}, clip_boxes={'A': (0, 0, 1000, 1000)}))
    got = (at(img, 250, 250), at(img, 750, 250), at(img, 250, 750), at(img, 750, 750))
    assert all(close(g, e) for g, e in zip(got, expect)), got


def test_foreground_palette_index_takes_the_fill_colour(tmp_path):
    f = colr_font(tmp_path / 'f.ttf', {'A': glyph('sq', solid(0xFFFF)),
                                       'B': glyph('sq', solid(0xFFFF, 0.5))})
    assert at(draw(f, extra='fill="#00ff00"'), 500, 500) == GREEN
    assert close(at(draw(f, 'B', extra='fill="#00ff00"'), 500, 500), (0, 255, 0, 128))
    assert at(draw(f), 500, 500) == (0, 0, 0, 255)      # default fill: black


def test_transformed_glyph_in_colr_glyph_reference(tmp_path):
    """PaintColrGlyph of a base glyph translated by half the square."""
    paints = {'B': glyph('lo', solid(1)),
              'A': {'Format': PaintFormat.PaintTranslate, 'dx': 0, 'dy': 500,
                    'Paint': {'Format': PaintFormat.PaintColrGlyph, 'Glyph': 'B'}}}
    img = draw(colr_font(tmp_path / 'f.ttf', paints))
    assert at(img, 500, 750) == BLUE and at(img, 500, 250) == CLEAR


def test_colour_glyph_in_a_clip_path_clips_by_its_outline(tmp_path):
    f = colr_font(tmp_path / 'f.ttf', {'A': [('lo', 0)]})
    svg = ('<svg %s width="140" height="140"><clipPath id="c"><text x="20" y="120" '
           'font-size="100" font-family="Test Colour">A</text></clipPath>'
           '<rect width="140" height="140" fill="#00f" clip-path="url(#c)"/></svg>' % NS)
    img = render(svg.encode(), fonts=FontOptions(files=[f], system=False))
    assert at(img, 500, 750) == BLUE            # the outline is the whole square
    assert img[10, 10, 3] == 0


def test_colour_glyphs_keep_their_place_among_outline_glyphs(tmp_path):
    """'BAB': outline, colour, outline: the colour glyph is the second of
    three advances."""
    f = colr_font(tmp_path / 'f.ttf', {'A': [('sq', 0)]})
    img = draw(f, 'BAB', size=(360, 140))
    assert at(img, 500, 500) == (0, 0, 0, 255)
    assert at(img, 1500, 500) == RED
    assert at(img, 2500, 500) == (0, 0, 0, 255)


def test_svg_glyph_whole_document_and_by_id(tmp_path):
    one = ('<svg xmlns="http://www.w3.org/2000/svg"><rect x="0" y="-1000" width="500" '
           'height="1000" fill="#0000ff"/></svg>')
    many = ('<svg xmlns="http://www.w3.org/2000/svg"><rect id="glyph6" x="500" y="-500" '
            'width="500" height="500" fill="#ff0000"/><rect id="glyph7" width="1000" '
            'height="1000" fill="#00ff00"/></svg>')
    f = svg_font(tmp_path / 's.ttf', [(one, 'A', 'A'), (many, 'B', 'C')])
    a = draw(f, family='Test SVG')
    assert at(a, 250, 500) == BLUE and at(a, 750, 500) == CLEAR
    b = draw(f, 'B', family='Test SVG')         # gid 6 = 'B'
    assert at(b, 750, 250) == RED and at(b, 250, 250) == CLEAR


def test_cbdt_glyph_is_an_image_on_the_baseline():
    """Noto Color Emoji's U+1F600 at font size 109 * 2048 / 2048 px per em:
    one image pixel per bitmap pixel; the bitmap's top is 101 px above the
    baseline."""
    fonts = FontOptions(files=[os.path.join(SUITE_FONTS, 'NotoColorEmojiCBDT.subset.ttf')],
                        system=False)
    svg = ('<svg %s width="300" height="300"><text x="10" y="200" font-size="109" '
           'font-family="Noto Color Emoji">\U0001F600</text></svg>' % NS)
    tree = load_svg(svg.encode(), fonts=fonts)
    (img, t), = [(n, t) for n, t in walk(tree.root) if isinstance(n, ImageNode)]
    corners = (t @ img.transform).apply(np.array([[0, 0], [136, 128]], float))
    np.testing.assert_allclose(corners, [[10, 200 - 101], [10 + 136, 200 - 101 + 128]],
                               atol=1e-9)


def test_colour_glyph_nodes_are_groups_in_glyph_space(tmp_path):
    f = colr_font(tmp_path / 'f.ttf', {'A': [('lo', 0)]})
    svg = ('<svg %s width="140" height="140"><text x="20" y="120" font-size="100" '
           'font-family="Test Colour">A</text></svg>' % NS)
    tree = load_svg(svg.encode(), fonts=FontOptions(files=[f], system=False))
    groups = [(n, t) for n, t in walk(tree.root) if isinstance(n, Group) and n.children
              and isinstance(n.children[0], PathNode)]
    (g, t), = groups
    np.testing.assert_allclose(tuple(t), (0.1, 0, 0, -0.1, 20, 120), atol=1e-12)


@pytest.mark.parametrize('seq', [s for s, _ in SEQUENCES], ids=['zwj', 'skin-tone', 'flag'])
@pytest.mark.parametrize('family', ['Test Emoji', 'Noto Sans, Test Emoji'])
def test_emoji_sequences_are_one_glyph(tmp_path, seq, family):
    """A ZWJ sequence, a skin tone modifier and a flag each shape to one
    ligature glyph (red, one advance), also when the first family lacks
    the characters and the emoji font is the fallback that joins them."""
    from _colorfonts import emoji_font
    f = emoji_font(tmp_path / 'e.ttf')
    fonts = FontOptions(files=[f, os.path.join(SUITE_FONTS, 'NotoSans-Regular.ttf')],
                        system=False)
    svg = ('<svg %s width="360" height="140"><text x="20" y="120" font-size="100" '
           'font-family="%s">%s|</text></svg>' % (NS, family, seq))
    img = render(svg.encode(), fonts=fonts)
    assert at(img, 500, 500) == RED
    assert not (img[..., 2] > 128).any()            # no single-character glyph drawn
    # the square covers one advance (x 20..120); the bar after it follows
    ink = np.flatnonzero(img[60, :, 3] > 128)
    assert ink.min() == 20 and ink[ink < 120].size == 100
    bar = ink[ink >= 120]
    assert len(bar) and 120 < bar.min() < 160 and bar.max() < 170
