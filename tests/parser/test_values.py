"""Tests of raster.parser.values: colours, paints, lengths, transforms, viewBox."""

import glob
import math
import os
import re

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.errors import RasterError, SVGError
from raster.geometry.transform import Affine
from raster.parser import values as V
from raster.parser.values import (
    CURRENT_COLOR, PAINT_NONE, LengthContext, Paint, parse_angle, parse_color,
    parse_font_size, parse_length, parse_length_list, parse_number,
    parse_number_list, parse_opacity, parse_paint, parse_preserve_aspect_ratio,
    parse_transform, parse_transform_origin, parse_url, parse_viewbox, resolve_viewbox,
    ZERO_VIEWBOX,
    viewbox_transform)

from _shared import SUITE_TESTS as SUITE


def close(a, b, tol=1e-12):
    return all(abs(x - y) <= tol for x, y in zip(a, b)) and len(a) == len(b)


def aff_close(t, expected, tol=1e-9):
    assert t is not None
    assert close(tuple(t), tuple(expected), tol), (t, expected)


# --------------------------------------------------------------------------
# colours
# --------------------------------------------------------------------------

def test_named_colours_match_pillow_table():
    # Pillow's CSS colour table is an independent source for the 147 SVG
    # names plus rebeccapurple (CSS Color 4).
    from PIL import ImageColor
    assert len(V.NAMED_COLORS) == 148
    assert set(V.NAMED_COLORS) == set(ImageColor.colormap)
    for name, rgb in V.NAMED_COLORS.items():
        assert ImageColor.getrgb(name)[:3] == rgb, name
        c = parse_color(name.upper())
        assert close(c, (rgb[0] / 255, rgb[1] / 255, rgb[2] / 255, 1.0))


@pytest.mark.parametrize('s, expected', [
    ('#f00', (1, 0, 0, 1)),
    ('#F00', (1, 0, 0, 1)),
    ('#abcd', (0xaa / 255, 0xbb / 255, 0xcc / 255, 0xdd / 255)),
    ('#008000', (0, 128 / 255, 0, 1)),
    ('#00800080', (0, 128 / 255, 0, 128 / 255)),
    ('  green\n ', (0, 128 / 255, 0, 1)),
    ('GreeN', (0, 128 / 255, 0, 1)),
    ('transparent', (0, 0, 0, 0)),
    ('rgb(0, 128, 0)', (0, 128 / 255, 0, 1)),
    (' rgb( 0 , 128 , 0 ) ', (0, 128 / 255, 0, 1)),
    ('RGB(0,128,0)', (0, 128 / 255, 0, 1)),
    ('rgb(0.8, 127.5, 14.2)', (0.8 / 255, 0.5, 14.2 / 255, 1)),
    ('rgb(0%, 45.5%, 0%)', (0, 0.455, 0, 1)),
    ('rgb(300, -5, 0)', (1, 0, 0, 1)),                 # clamped
    ('rgb(300 -5 50%)', (1, 0, 0.5, 1)),               # clamped, modern mixing
    ('rgb(120%, -10%, 50%)', (1, 0, 0.5, 1)),
    ('rgba(0, 127, 0, 0.5)', (0, 127 / 255, 0, 0.5)),
    ('rgb(0, 127, 0, 0.5)', (0, 127 / 255, 0, 0.5)),  # CSS 4: rgb takes alpha
    ('rgba(0, 127, 0, -1)', (0, 127 / 255, 0, 0)),
    ('rgba(0, 127, 0, 2)', (0, 127 / 255, 0, 1)),
    ('rgba(0%, 50%, 0%, 0.5)', (0, 0.5, 0, 0.5)),
    ('rgb(0 127 0 / 0.25)', (0, 127 / 255, 0, 0.25)),
    ('rgb(0 127 0 / 25%)', (0, 127 / 255, 0, 0.25)),
    ('hsl(120, 100%, 50%)', (0, 1, 0, 1)),
    ('hsl(120, 100%, 25%)', (0, 0.5, 0, 1)),
    ('hsl(120, 200%, 25%)', (0, 0.5, 0, 1)),           # saturation clamped
    ('hsl(360, 100%, 25%)', (0.5, 0, 0, 1)),
    ('hsl(-240, 100%, 50%)', (0, 1, 0, 1)),
    ('hsl(120, 100%, 25%, 0.5)', (0, 0.5, 0, 0.5)),
    ('hsla(240, 100%, 50%, 0.5)', (0, 0, 1, 0.5)),
    ('hsl(0.5turn 100% 50%)', (0, 1, 1, 1)),
    ('hsl(200grad 100% 50%)', (0, 1, 1, 1)),
    ('hsl(180deg 0% 50% / 10%)', (0.5, 0.5, 0.5, 0.1)),
    ('hsl(0, 0%, 100%)', (1, 1, 1, 1)),
])
def test_colour_syntaxes(s, expected):
    assert close(parse_color(s), expected, 1e-12), (s, parse_color(s))


def test_hsl_rad_and_999():
    assert close(parse_color('hsl(3.14159265358979rad, 100%, 50%)'), (0, 1, 1, 1), 1e-9)
    # 999 deg = 279 deg: between blue (240) and magenta (300)
    r, g, b, a = parse_color('hsl(999, 100%, 25%)')
    assert close((r, g, b), ((279 - 240) / 60 * 0.5, 0, 0.5), 1e-12)


@pytest.mark.parametrize('s', [
    '', '   ', '#', '#qqq', '#aaz', '#12345', '#1234567', 'qwe13212', 'ButtonFace',
    'rgb(1, 2)', 'rgb(1, 2, 3, 4, 5)', 'rgb(1 2 3 4)', 'rgb(1,, 2, 3)',
    'rgb(1, 2, 3',
    # resvg's painting/fill tests: legacy syntax does not mix numbers and
    # percentages, and takes no percentage alpha
    'rgba(0, 50%, 0, 0.5)', 'rgb(300, -5, 50%)', 'rgba(0, 127, 0, 50%)',
    'rgb(1, 2, 3 / 0.5)', 'rgb(1px, 2, 3)', 'hsl(120, 100%)', 'hsl(1x, 1%, 1%)',
    'foo(1, 2, 3)', 'green icc-color(acmecmyk, 0.11, 0.48, 0.83, 0.00)',
    'red blue', 'currentColour',
])
def test_invalid_colours(s):
    assert parse_color(s) is None


def test_current_color_sentinel():
    for s in ('currentColor', 'currentcolor', ' CURRENTCOLOR '):
        assert parse_color(s) is CURRENT_COLOR
    assert repr(CURRENT_COLOR) == 'CURRENT_COLOR'
    import pickle
    assert pickle.loads(pickle.dumps(CURRENT_COLOR)) is CURRENT_COLOR


def test_colour_type_error():
    with pytest.raises(SVGError):
        parse_color(None)
    with pytest.raises(RasterError):
        parse_length(3.0)


@settings(max_examples=100, deadline=None)
@given(st.tuples(st.integers(0, 255), st.integers(0, 255), st.integers(0, 255),
                 st.integers(0, 255)))
def test_hex_rgb_roundtrip(rgba):
    r, g, b, a = rgba
    expected = (r / 255, g / 255, b / 255, a / 255)
    assert parse_color('#%02x%02x%02x%02x' % rgba) == expected
    assert parse_color('#%02X%02X%02X' % rgba[:3]) == expected[:3] + (1.0,)
    assert close(parse_color('rgba(%d, %d, %d, %r)' % (r, g, b, a / 255)), expected)
    assert close(parse_color('rgb(%d %d %d / %r%%)' % (r, g, b, a / 2.55)), expected, 1e-12)


@settings(max_examples=100, deadline=None)
@given(st.floats(-720, 720), st.floats(0, 100), st.floats(0, 100))
def test_hsl_properties(h, s, l):
    c = parse_color('hsl(%r, %r%%, %r%%)' % (h, s, l))
    assert c is not None and all(0 <= v <= 1 for v in c)
    # lightness is the mean of the largest and the smallest channel
    assert abs((max(c[:3]) + min(c[:3])) / 2 - l / 100) < 1e-9
    # hue periodicity
    c2 = parse_color('hsl(%r, %r%%, %r%%)' % (h + 360, s, l))
    assert close(c, c2, 1e-9)
    # zero saturation is grey
    g = parse_color('hsl(%r, 0%%, %r%%)' % (h, l))
    assert close(g[:3], (l / 100,) * 3, 1e-12)


# --------------------------------------------------------------------------
# paint
# --------------------------------------------------------------------------

def test_paints():
    assert parse_paint('none') is PAINT_NONE
    assert parse_paint(' None ') is PAINT_NONE
    assert parse_paint('currentColor').kind == 'current'
    assert parse_paint('context-fill') == Paint('context-fill')
    assert parse_paint('context-stroke') == Paint('context-stroke')
    assert parse_paint('#ff0000') == Paint('color', (1.0, 0.0, 0.0, 1.0))
    assert parse_paint('url(#lg1)') == Paint('url', url='lg1')
    p = parse_paint('url(#lg1) green')
    assert p.kind == 'url' and p.url == 'lg1'
    assert p.fallback == Paint('color', (0.0, 128 / 255, 0.0, 1.0))
    assert parse_paint('url(#lg1) none').fallback is PAINT_NONE
    assert parse_paint('url(#lg1) currentColor').fallback.kind == 'current'
    assert parse_paint("url('#a b')").url == 'a b'
    assert parse_paint('url( "#q" )').url == 'q'
    assert parse_paint('URL(#x)').url == 'x'


@pytest.mark.parametrize('s', [
    'inherit', 'url(#a', 'url()', 'url(#a) url(#b)', 'url(#a) qwe', 'red url(#a)',
    'url(#a) green icc-color(acmecmyk, 0.11, 0.48, 0.83, 0.00)', '', 'nonee',
    'url(#a) context-fill',
])
def test_invalid_paints(s):
    assert parse_paint(s) is None


def test_parse_url():
    assert parse_url('url(#a)') == ('a', '')
    assert parse_url('url(a.svg#b) x') == ('a.svg#b', 'x')
    assert parse_url('#a') is None


# --------------------------------------------------------------------------
# numbers, lengths, angles, opacity, font-size
# --------------------------------------------------------------------------

@pytest.mark.parametrize('s, v', [
    ('0', 0.0), ('-1', -1.0), ('+.5', 0.5), ('1.', 1.0), ('1e3', 1000.0),
    ('1E-2', 0.01), (' 7 ', 7.0), ('-0.0', 0.0)])
def test_numbers(s, v):
    assert parse_number(s) == v


@pytest.mark.parametrize('s', ['', '.', '1e', '1px', '1 2', 'e3', '--1', '1e999', 'nan', 'inf'])
def test_invalid_numbers(s):
    assert parse_number(s) is None


def test_number_lists():
    assert parse_number_list('') == []
    assert parse_number_list('  ') == []
    assert parse_number_list('1,2 3\t,\n4') == [1, 2, 3, 4]
    assert parse_number_list('1-2-3') == [1, -2, -3]
    assert parse_number_list('0.5.5') == [0.5, 0.5]
    assert parse_number_list('1e2-1e-1') == [100, -0.1]
    for bad in (',1', '1,', '1,,2', '1 x 2', '1;2', '1e', ', ', '1, ,2'):
        assert parse_number_list(bad) is None, bad
    # points: numbers before the first error
    assert parse_number_list('10 20 30 x 40', strict=False) == [10, 20, 30]
    assert parse_number_list('10,20,', strict=False) == [10, 20]
    assert parse_number_list('x', strict=False) == []


@settings(max_examples=100, deadline=None)
@given(st.lists(st.floats(-1e6, 1e6, allow_nan=False), max_size=20),
       st.sampled_from([' ', ',', ', ', ' ,\n']))
def test_number_list_roundtrip(nums, sep):
    s = sep.join(repr(x) for x in nums)
    assert parse_number_list(s) == nums


CTX = LengthContext(font_size=20.0, width=300.0, height=400.0)


@pytest.mark.parametrize('s, axis, v', [
    ('10', 'x', 10.0), ('10px', 'x', 10.0), ('1in', 'x', 96.0),
    ('2.54cm', 'x', 96.0), ('25.4mm', 'x', 96.0), ('72pt', 'x', 96.0),
    ('3pt', 'x', 4.0), ('6pc', 'x', 96.0), ('1pc', 'x', 16.0),
    ('2em', 'x', 40.0), ('2ex', 'x', 20.0), ('1EM', 'x', 20.0),
    ('50%', 'x', 150.0), ('50%', 'y', 200.0),
    ('100%', 'other', math.sqrt((300 ** 2 + 400 ** 2) / 2)),
    (' -1.5e1px ', 'x', -15.0), ('+.5in', 'y', 48.0),
])
def test_lengths(s, axis, v):
    assert parse_length(s, axis, CTX) == pytest.approx(v, rel=1e-12)


@pytest.mark.parametrize('s', ['', 'px', '1 px', '10qq', '10Q', '1vw', '1rem', '44mmx',
                               '1e999', '1%%', '1,', '5vmin'])
def test_invalid_lengths(s):
    # resvg renders nothing for SVG 2 units (vw, rem ...): invalid here too
    assert parse_length(s, 'x', CTX) is None


@given(st.text(alphabet='0123456789.+-eE', min_size=1, max_size=12), st.sampled_from(['', ' ']))
def test_unitless_lengths_follow_the_number_grammar(s, pad):
    # strings of digits, points, signs and exponents take a shorter path
    # (float()); they are lengths exactly when they are SVG numbers, with
    # or without the spaces the grammar allows around them
    m = re.fullmatch(V.NUMBER, s)
    want = None
    if m is not None:
        v = float(s)
        want = v if math.isfinite(v) else None
    assert parse_length(pad + s + pad, 'x', CTX) == want
    for bad in ('1_0', 'inf', 'nan', '1e', 'e1', '+-1', '1..2', '--1', '.', '1.2.3'):
        assert parse_length(bad, 'x', CTX) is None


def test_length_dpi_and_defaults():
    assert parse_length('1in', 'x', LengthContext(dpi=72)) == 72.0
    assert parse_length('1em') == 12.0  # resvg's default font size
    assert parse_length('10%') == 10.0


def test_length_lists():
    assert parse_length_list('5mm, 2%  1em', 'other', CTX) == pytest.approx(
        [5 * 96 / 25.4, 0.02 * math.sqrt((300 ** 2 + 400 ** 2) / 2), 20.0])
    assert parse_length_list('', 'x', CTX) == []
    assert parse_length_list('1,,2') is None
    assert parse_length_list('1 2qq') is None
    assert parse_length_list('none') is None


@pytest.mark.parametrize('s, deg', [
    ('90', 90.0), ('90deg', 90.0), ('0.25turn', 90.0), ('100grad', 90.0),
    ('-1rad', -180 / math.pi), (' 45DEG ', 45.0)])
def test_angles(s, deg):
    assert parse_angle(s) == pytest.approx(deg, rel=1e-12)


def test_invalid_angles():
    for s in ('', 'deg', '1 deg', '1px', '1e999'):
        assert parse_angle(s) is None


def test_opacity():
    # resvg's painting/opacity tests: 50% is 0.5, '0.1mm' is ignored
    assert parse_opacity('0.5') == 0.5
    assert parse_opacity('50%') == 0.5
    assert parse_opacity('-1') == 0.0
    assert parse_opacity('3') == 1.0
    assert parse_opacity('0.1mm') is None
    assert parse_opacity('') is None


def test_font_size_keywords():
    # measured on resvg's text/font-size/named-value test: medium = 12 and a
    # factor of 1.2 per step; larger/smaller scale the parent by 1.2
    expected = {'xx-small': 12 / 1.728, 'x-small': 12 / 1.44, 'small': 10.0,
                'medium': 12.0, 'large': 14.4, 'x-large': 17.28, 'xx-large': 20.736}
    for k, v in expected.items():
        assert parse_font_size(k, 30.0) == pytest.approx(v, rel=1e-12)
    assert parse_font_size('larger', 10) == pytest.approx(12.0)
    assert parse_font_size('smaller', 12) == pytest.approx(10.0)
    assert parse_font_size('50%', 12) == 6.0
    assert parse_font_size('2em', 12) == 24.0
    assert parse_font_size('2ex', 12) == 12.0
    assert parse_font_size('12pt', 99) == 16.0
    assert parse_font_size('-1', 12) is None
    assert parse_font_size('big', 12) is None


# --------------------------------------------------------------------------
# transforms
# --------------------------------------------------------------------------

T45 = math.tan(math.radians(45))


@pytest.mark.parametrize('s, expected', [
    ('', Affine()),
    ('   ', Affine()),
    ('matrix(1 2 3 4 5 6)', Affine(1, 2, 3, 4, 5, 6)),
    ('matrix(0.7569, 0.2097, -0.588, 0.7239, 81, 2.76)',
     Affine(0.7569, 0.2097, -0.588, 0.7239, 81, 2.76)),
    ('  matrix  (  0.7569  0.2097 -0.588  0.7239 81 2.76  )   ',
     Affine(0.7569, 0.2097, -0.588, 0.7239, 81, 2.76)),
    (' matrix (\t1\r0\n0 1 0 0)', Affine()),
    ('translate(20 30)', Affine.translate(20, 30)),
    ('translate(20)', Affine.translate(20, 0)),
    ('scale(2)', Affine.scale(2, 2)),
    ('scale(0.5, 0.5)', Affine.scale(0.5)),
    ('scale(1,2)', Affine.scale(1, 2)),
    ('rotate(90)', Affine(0, 1, -1, 0, 0, 0)),
    ('rotate(90 10 10)', Affine(0, 1, -1, 0, 20, 0)),
    ('skewX(45)', Affine(1, 0, T45, 1, 0, 0)),
    ('skewY(45)', Affine(1, T45, 0, 1, 0, 0)),
    ('matrix(0, 0, 0, 0, 0, 0)', Affine(0, 0, 0, 0, 0, 0)),
    # composition: the rightmost function applies first
    ('translate(10,0) scale(2)', Affine(2, 0, 0, 2, 10, 0)),
    ('scale(2)translate(10,0)', Affine(2, 0, 0, 2, 20, 0)),
    ('scale(2),translate(10,0)', Affine(2, 0, 0, 2, 20, 0)),
    ('scale(2) , translate(10-5)', Affine(2, 0, 0, 2, 20, -10)),
])
def test_transforms(s, expected):
    aff_close(parse_transform(s), expected)


@pytest.mark.parametrize('s', [
    'qwe', 'scale', 'scale()', 'scale(1 2 3)', 'rotate(1 2)', 'matrix(1 2 3 4 5)',
    'translate(1,,2)', 'scale(2) qwe', 'scale(2),', ',scale(2)', 'Scale(2)',
    'scale(2px)', 'skewX(1 2)', 'translate(1 2', 'scale(2) , , scale(2)',
    'scale(1e308) scale(1e308)',
])
def test_invalid_transforms(s):
    # any error discards the whole attribute (resvg structure/transform)
    assert parse_transform(s) is None


@settings(max_examples=100, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(['translate', 'scale', 'rotate', 'skewX', 'skewY']),
                          st.floats(-50, 50), st.floats(-3, 3)), min_size=1, max_size=5))
def test_transform_list_is_product(items):
    parts, expected = [], Affine()
    for name, a, b in items:
        if name == 'translate':
            parts.append('translate(%r %r)' % (a, b))
            t = Affine.translate(a, b)
        elif name == 'scale':
            parts.append('scale(%r,%r)' % (b, a))
            t = Affine.scale(b, a)
        elif name == 'rotate':
            parts.append('rotate(%r, %r, %r)' % (a * 7, a, b))
            t = Affine.rotate(a * 7, a, b)
        elif name == 'skewX':
            parts.append('skewX(%r)' % a)
            t = Affine.skew_x(a)
        else:
            parts.append('skewY(%r)' % a)
            t = Affine.skew_y(a)
        expected = expected @ t
    got = parse_transform(' '.join(parts))
    aff_close(got, expected, 1e-9 * (1 + max(abs(v) for v in expected)))
    # the same list with commas and no separators parses identically
    assert parse_transform(','.join(parts)) == got
    assert parse_transform(''.join(parts)) == got


def test_rotate_about_centre_fixes_centre():
    t = parse_transform('rotate(37, 100, 50)')
    assert np.allclose(t.apply([[100.0, 50.0]]), [[100.0, 50.0]])


@st.composite
def translate_strings(draw):
    """translate(...) with every kind of argument text and separator."""
    ws = st.sampled_from(['', ' ', '\t', '\n', '\f', '\r', '  '])
    num = st.one_of(st.floats(-1e6, 1e6, allow_nan=False).map(repr),
                    st.sampled_from(['-0', '+1', '.5', '1.', '1e3', '1e999', '-.5e-2', '1.5.5',
                                     '1-2', 'x', '', '1,', ',1', '1,,2', '1 2 3']))
    sep = st.sampled_from([' ', ',', ' , ', ', ', ' ,', '', '\f', ',,'])
    args = draw(num) + (draw(sep) + draw(num) if draw(st.booleans()) else '')
    return draw(ws) + 'translate' + draw(ws) + '(' + draw(ws) + args + draw(ws) + ')' + draw(ws)


@settings(max_examples=300, deadline=None)
@given(translate_strings())
def test_translate_fast_path_equals_the_general_parser(s):
    fast = V._TF_TRANSLATE_RE.fullmatch(s)
    got = V._parse_transform.__wrapped__(s, False)
    want = V._transform_list(s, False)
    if want is None:
        assert got is None
        return
    assert got is not None and tuple(got) == tuple(want), s
    if fast is not None:
        assert got.is_translation


def test_transform_origin():
    c = LengthContext(width=200, height=100)
    cases = {
        'center': (100, 50), 'top': (100, 0), 'bottom': (100, 100),
        'left': (0, 50), 'right': (200, 50), 'bottom right': (200, 100),
        'right bottom': (200, 100), 'top left': (0, 0), '25% top': (50, 0),
        '50% 50%': (100, 50), '100px 100px': (100, 100), '0.5 0.5': (0.5, 0.5),
        'left 10': (0, 10), '10%': (20, 50), '1 2 3': (1, 2), '1in 0': (96, 0),
    }
    for s, v in cases.items():
        assert parse_transform_origin(s, c) == pytest.approx(v), s
    for s in ('', 'top 10', 'left right', 'top bottom', 'x', '1 2 3 4', '1 2 3%',
              'center 10 10%'):
        assert parse_transform_origin(s, c) is None, s


# --------------------------------------------------------------------------
# viewBox and preserveAspectRatio
# --------------------------------------------------------------------------

def test_viewbox():
    assert parse_viewbox('0 0 100 50') == (0, 0, 100, 50)
    assert parse_viewbox(' -10,-20 , 1e2 50 ') == (-10, -20, 100, 50)
    for s in ('0 0 0 50', '0 0 100 -1', '0 0 100', '0 0 100 50 1', 'a b c d', ''):
        assert parse_viewbox(s) is None, s


def test_resolve_viewbox_ignores_invalid_and_disables_zero():
    # SVG 2: an invalid value (syntax, count, negative side) invalidates the
    # attribute; a zero side disables rendering of the element
    assert resolve_viewbox(None) is None
    assert resolve_viewbox('-10,-20 , 1e2 50') == (-10, -20, 100, 50)
    for s in ('0 0 100 -1', '0 0 -1 0', '0 0 100', '0 0 100 50 1', 'a b c d', ''):
        assert resolve_viewbox(s) is None, s
    for s in ('0 0 0 50', '0 0 100 0', '1 1 0 0'):
        assert resolve_viewbox(s) is ZERO_VIEWBOX, s


def test_preserve_aspect_ratio_parse():
    assert parse_preserve_aspect_ratio('none') == ('none', 'meet')
    assert parse_preserve_aspect_ratio('xMaxYMax slice') == ('xMaxYMax', 'slice')
    assert parse_preserve_aspect_ratio('defer xMinYMid meet') == ('xMinYMid', 'meet')
    for s in ('', 'xmidymid', 'xMidYMid cover', 'slice', 'xMidYMid meet slice', 'defer'):
        assert parse_preserve_aspect_ratio(s) is None, s


# Hand-computed: a 100x50 viewBox into a 200x200 viewport.  x scale 2,
# y scale 4.  meet -> s = 2, the content is 200x100, 100 px of vertical
# slack: yMin 0, yMid 50, yMax 100.  slice -> s = 4, the content is 400x200,
# 200 px of horizontal overflow: xMin 0, xMid -100, xMax -200.
PAR_EXPECTED = {
    ('xMinYMin', 'meet'): (2, 0, 0, 2, 0, 0),
    ('xMidYMin', 'meet'): (2, 0, 0, 2, 0, 0),
    ('xMaxYMin', 'meet'): (2, 0, 0, 2, 0, 0),
    ('xMinYMid', 'meet'): (2, 0, 0, 2, 0, 50),
    ('xMidYMid', 'meet'): (2, 0, 0, 2, 0, 50),
    ('xMaxYMid', 'meet'): (2, 0, 0, 2, 0, 50),
    ('xMinYMax', 'meet'): (2, 0, 0, 2, 0, 100),
    ('xMidYMax', 'meet'): (2, 0, 0, 2, 0, 100),
    ('xMaxYMax', 'meet'): (2, 0, 0, 2, 0, 100),
    ('xMinYMin', 'slice'): (4, 0, 0, 4, 0, 0),
    ('xMidYMin', 'slice'): (4, 0, 0, 4, -100, 0),
    ('xMaxYMin', 'slice'): (4, 0, 0, 4, -200, 0),
    ('xMinYMid', 'slice'): (4, 0, 0, 4, 0, 0),
    ('xMidYMid', 'slice'): (4, 0, 0, 4, -100, 0),
    ('xMaxYMid', 'slice'): (4, 0, 0, 4, -200, 0),
    ('xMinYMax', 'slice'): (4, 0, 0, 4, 0, 0),
    ('xMidYMax', 'slice'): (4, 0, 0, 4, -100, 0),
    ('xMaxYMax', 'slice'): (4, 0, 0, 4, -200, 0),
    ('none', 'meet'): (2, 0, 0, 4, 0, 0),
    ('none', 'slice'): (2, 0, 0, 4, 0, 0),
}


@pytest.mark.parametrize('par', sorted(PAR_EXPECTED))
def test_viewbox_transform_all_aligns(par):
    text = '%s %s' % par
    assert parse_preserve_aspect_ratio(text) == par
    aff_close(viewbox_transform((0, 0, 100, 50), par, 200, 200), PAR_EXPECTED[par])
    # a viewBox origin shifts by -origin * scale; a viewport origin adds
    a, b, c, d, e, f = PAR_EXPECTED[par]
    aff_close(viewbox_transform((10, -20, 100, 50), par, 200, 200, x=5, y=7),
              (a, b, c, d, e - 10 * a + 5, f + 20 * d + 7))


def test_viewbox_transform_default_and_errors():
    aff_close(viewbox_transform((0, 0, 100, 50), None, 200, 200), (2, 0, 0, 2, 0, 50))
    with pytest.raises(SVGError):
        viewbox_transform((0, 0, 0, 50), None, 200, 200)
    with pytest.raises(SVGError):
        viewbox_transform((0, 0, 10, 50), ('xMidYmid', 'meet'), 200, 200)


@settings(max_examples=100, deadline=None)
@given(st.floats(1, 500), st.floats(1, 500), st.floats(1, 500), st.floats(1, 500),
       st.sampled_from(sorted(PAR_EXPECTED)))
def test_viewbox_meet_fits_and_slice_covers(vw, vh, w, h, par):
    t = viewbox_transform((3.0, -4.0, vw, vh), par, w, h)
    (x0, y0), (x1, y1) = t.apply([[3.0, -4.0], [3.0 + vw, -4.0 + vh]])
    eps = 1e-9 * (w + h)
    if par[0] == 'none':
        assert abs(x0) < eps and abs(y0) < eps and abs(x1 - w) < eps and abs(y1 - h) < eps
    elif par[1] == 'meet':
        # inside the viewport, touching it on both sides of one axis
        assert x0 > -eps and y0 > -eps and x1 < w + eps and y1 < h + eps
        assert (abs(x0) < eps and abs(x1 - w) < eps) or (abs(y0) < eps and abs(y1 - h) < eps)
    else:
        assert x0 < eps and y0 < eps and x1 > w - eps and y1 > h - eps
    if par[0] != 'none':
        assert t.a == t.d


# --------------------------------------------------------------------------
# the resvg suite
# --------------------------------------------------------------------------

def _suite_files(sub):
    return sorted(glob.glob(os.path.join(SUITE, sub, '*.svg')))


def test_resvg_fill_values_parse_as_resvg_renders():
    # For each painting/fill test: a valid colour value must be one resvg
    # rendered; an invalid one gives resvg's black (the initial fill).
    from PIL import Image
    n = 0
    for path in _suite_files('painting/fill'):
        if 'pattern' in path or 'gradient' in path:
            continue
        src = open(path, encoding='utf-8').read()
        m = re.search(r'id="rect1"[^>]*?fill="([^"]*)"', src, re.S)
        if m is None or m.group(1).strip() in ('inherit', 'currentColor', 'none') \
                or 'url(' in m.group(1):
            continue
        im = Image.open(path[:-4] + '.png').convert('RGBA')
        px = np.array(im.getpixel((im.size[0] // 2, im.size[1] // 2))) / 255
        c = parse_color(m.group(1))
        if c is None:
            assert np.allclose(px, (0, 0, 0, 1)), path
        else:
            # the reference PNGs have a transparent page: compare alpha,
            # then the (straight) colour where there is any
            assert abs(px[3] - c[3]) < 2 / 255, path
            if c[3] > 0:
                assert np.allclose(px[:3], c[:3], atol=2.5 / 255), (path, px, c)
        n += 1
    assert n >= 30


@pytest.mark.parametrize('s, expected', [
    ('none', Affine()),
    (' NONE ', Affine()),
    ('scale(2)', Affine.scale(2)),
    ('rotate(90deg)', Affine(0, 1, -1, 0, 0, 0)),
    ('rotate(0.25turn)', Affine(0, 1, -1, 0, 0, 0)),
    ('rotate(100grad)', Affine(0, 1, -1, 0, 0, 0)),
    ('translate(10px, 1in)', Affine.translate(10, 96)),
    ('translateX(2.54cm) translateY(3pt)', Affine.translate(96, 4)),
    ('scaleX(50%) scaleY(3)', Affine.scale(0.5, 3)),
    ('skew(45deg)', Affine(1, 0, T45, 1, 0, 0)),
    ('skew(0, 45deg)', Affine(1, T45, 0, 1, 0, 0)),
    ('skewX(45deg)', Affine(1, 0, T45, 1, 0, 0)),
    ('Translate(10px,0)Scale(2)', Affine(2, 0, 0, 2, 10, 0)),
    ('matrix(1, 2, 3, 4, 5, 6)', Affine(1, 2, 3, 4, 5, 6)),
])
def test_css_transforms(s, expected):
    aff_close(parse_transform(s, css=True), expected)


@pytest.mark.parametrize('s', [
    'translate(10%)', 'rotate(1px)', 'matrix(1, 0, 0, 1, 5px, 0)', 'scale(2px)',
    'translate(1em)', 'perspective(10px)', 'rotate(1deg', 'skew(1deg, 2deg, 3deg)',
    'none scale(2)',
])
def test_invalid_css_transforms(s):
    assert parse_transform(s, css=True) is None


def test_svg_transform_refuses_css_only_syntax():
    for s in ('none', 'rotate(90deg)', 'translateX(1)', 'SCALE(2)'):
        assert parse_transform(s) is None, s


FUZZ_ALPHABET = st.sampled_from(list('0123456789.eE+-,% ()#/\t\nabcdfghilmnoprstuxyzAXY')
                                + ['rgb(', 'hsl(', 'url(#', 'rotate(', 'matrix(', 'deg',
                                   'px', 'none', 'turn', 'currentColor', 'xMidYMid', 'slice'])


@settings(max_examples=100, deadline=None)
@given(st.lists(FUZZ_ALPHABET, max_size=25).map(''.join))
def test_parsers_never_raise_on_text(s):
    # every micro-syntax parser answers None or a value, never an exception
    c = parse_color(s)
    assert c is None or c is CURRENT_COLOR or (len(c) == 4 and all(0 <= v <= 1 for v in c))
    p = parse_paint(s)
    assert p is None or isinstance(p, Paint)
    for f in (parse_number, parse_angle, parse_opacity, parse_length):
        v = f(s)
        assert v is None or math.isfinite(v)
    for css in (False, True):
        t = parse_transform(s, css=css)
        assert t is None or isinstance(t, Affine)
    for f in (parse_number_list, parse_length_list):
        v = f(s)
        assert v is None or all(math.isfinite(x) for x in v)
    assert parse_viewbox(s) is None or len(parse_viewbox(s)) == 4
    assert parse_preserve_aspect_ratio(s) in (None,) or len(parse_preserve_aspect_ratio(s)) == 2
    o = parse_transform_origin(s, CTX)
    assert o is None or len(o) == 2
    fs = parse_font_size(s, 10.0)
    assert fs is None or fs >= 0


def test_single_function_transforms_match_the_general_parser():
    # the fast path for translate/scale/matrix alone agrees with composing
    # the same function after an identity through the general path
    from raster.parser.values import parse_transform
    for s, want in [('translate(3,4)', Affine.translate(3, 4)),
                    ('translate(3)', Affine.translate(3, 0)),
                    (' scale( 2 ) ', Affine.scale(2)), ('scale(2 -1)', Affine.scale(2, -1)),
                    ('matrix(1-2.5.5,3 4 5)', Affine(1, -2.5, 0.5, 3, 4, 5))]:
        assert tuple(parse_transform(s)) == tuple(want)
        assert tuple(parse_transform(s + ' rotate(0)')) == pytest.approx(tuple(want))
    for bad in ('translate(1,2,3)', 'translate(1,)', 'matrix(1 0 0 1 5)', 'scale()',
                'translate(1e999)', 'translate(1,,2)'):
        assert parse_transform(bad) is None
