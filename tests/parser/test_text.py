"""Tests of raster.parser.text: SVG text laid out as glyph outlines."""
import os
import warnings

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from PIL import Image

from raster.geometry.bounds import bbox
from raster.errors import RasterWarning
from raster.fonts import Font, FontDB, FontOptions
from raster.geometry.path import Path
from raster.svg import load_svg, render
from raster.parser.text import collapse_whitespace
from raster.tree import PathNode, walk
from raster.testing import compare_images

from _shared import SUITE_FONTS as FONTS, SUITE_ROOT as SUITE
NS = 'xmlns="http://www.w3.org/2000/svg"'
#: The suite's fonts only (no system fonts: the tests do not depend on the
#: machine).
SUITE_FONTS = FontOptions(dirs=FONTS, system=False)


def doc(body, extra=''):
    return ('<svg %s width="400" height="200" %s>%s</svg>' % (NS, extra, body)).encode()


def text_paths(body, fonts=SUITE_FONTS):
    """(path, abs transform, node) of every PathNode of a document."""
    tree = load_svg(doc(body), fonts=fonts)
    return [(n.path.transform(t), n) for n, t in walk(tree.root) if isinstance(n, PathNode)]


def ink(body):
    ps = text_paths(body)
    assert ps, 'no text drawn'
    return bbox(Path.concat([p for p, _ in ps]))


@pytest.fixture(scope='module')
def noto():
    return Font.load(FontDB([FONTS]).match(['Noto Sans']))


def advance(font, text, size):
    return sum(g[2] for g in font.shape(text)) * size / font.upem


# -- whitespace ---------------------------------------------------------------

def test_collapse_whitespace_default_and_preserve():
    assert collapse_whitespace('\n  Hello \t  world\n ') == ('Hello world ', True)
    assert collapse_whitespace('a  b', prev_space=False) == ('a b', False)
    assert collapse_whitespace('  x ', preserve=True) == ('  x ', True)
    assert collapse_whitespace('a\tb\nc', preserve=True) == ('a b c', False)


def test_collapsed_text_draws_like_single_spaces():
    a = text_paths('<text x="10" y="50" font-family="Noto Sans">A B</text>')
    b = text_paths('<text x="10" y="50" font-family="Noto Sans">\n   A  \n  B   </text>')
    assert len(a) == len(b) == 1
    assert a[0][0] == b[0][0]


# -- positions ------------------------------------------------------------------

def test_glyph_origin_and_advance_of_known_string(noto):
    """'Hilmn' in Noto Sans 50px: the ink box lies in [x, x + advance],
    the advance being the hmtx sum (no kerning among these letters); the
    'H' stem sits on the baseline y."""
    x, y, size = 20.0, 100.0, 50.0
    x0, y0, x1, y1 = ink('<text x="%g" y="%g" font-family="Noto Sans" font-size="%g">'
                         'Hilmn</text>' % (x, y, size))
    adv = advance(noto, 'Hilmn', size)
    assert x < x0 < x + 0.2 * size
    assert x + adv - 0.2 * size < x1 < x + adv
    assert y1 == pytest.approx(y)          # no descenders: bottom is the baseline
    assert y0 < y - noto.cap_height * size / noto.upem + 0.5     # 'l' rises above 'H'


@pytest.mark.parametrize('anchor, frac', [('start', 0.0), ('middle', 0.5), ('end', 1.0)])
def test_text_anchor_shifts_by_advance_fraction(noto, anchor, frac):
    base = ink('<text x="200" y="80" font-family="Noto Sans" font-size="40">Hello</text>')
    box = ink('<text x="200" y="80" font-family="Noto Sans" font-size="40" '
              'text-anchor="%s">Hello</text>' % anchor)
    w = advance(noto, 'Hello', 40)
    np.testing.assert_allclose(np.subtract(box, base), [-frac * w, 0, -frac * w, 0], atol=1e-9)


def test_text_anchor_middle_centres_symmetric_ink_box():
    """'HOH' is nearly mirror-symmetric: with text-anchor=middle its ink
    box is centred on x within half a pixel."""
    x0, _, x1, _ = ink('<text x="200" y="80" font-family="Noto Sans" font-size="40" '
                       'text-anchor="middle">HOH</text>')
    assert abs((x0 + x1) / 2 - 200) < 0.5


def test_tspan_dx_dy_shift_following_glyphs():
    plain = text_paths('<text x="10" y="50" font-family="Noto Sans">A<tspan>B</tspan></text>')
    moved = text_paths('<text x="10" y="50" font-family="Noto Sans">'
                       'A<tspan dx="7" dy="-3">B</tspan></text>')
    assert len(plain) == len(moved) == 2
    np.testing.assert_allclose(moved[0][0].points, plain[0][0].points)
    np.testing.assert_allclose(moved[1][0].points, plain[1][0].points + [7, -3])


def test_dx_list_applies_per_character():
    plain = text_paths('<text x="10" y="50" font-family="Noto Sans">ABC</text>')[0][0]
    moved = text_paths('<text x="10" y="50" dx="1 2 3" font-family="Noto Sans">ABC</text>')[0][0]
    # A moves 1, B 1+2, C 1+2+3: the difference takes exactly those values
    d = np.unique(np.round(moved.points[:, 0] - plain.points[:, 0], 9))
    assert d.tolist() == [1.0, 3.0, 6.0]


def test_absolute_x_list_starts_chunks():
    """Every absolute x starts a new chunk: one PathNode per 'I', each
    starting just right of its x (the left side bearing)."""
    ps = text_paths('<text x="10 100 200" y="50" font-family="Noto Sans">III</text>')
    lefts = [bbox(p)[0] for p, _ in ps]
    assert len(lefts) == 3
    np.testing.assert_allclose(np.subtract(lefts, [10, 100, 200]), lefts[0] - 10)
    assert 0 < lefts[0] - 10 < 5


def test_letter_and_word_spacing_widen_by_count(noto):
    a = ink('<text x="10" y="50" font-family="Noto Sans" font-size="20">HI HI</text>')
    b = ink('<text x="10" y="50" font-family="Noto Sans" font-size="20" '
            'letter-spacing="3" word-spacing="5">HI HI</text>')
    # last glyph 'I' is preceded by 4 characters (3 letter gaps + 1 space gap)
    assert b[2] - a[2] == pytest.approx(4 * 3 + 5)
    assert b[0] == pytest.approx(a[0])


@given(st.floats(-500, 500), st.floats(-500, 500))
@settings(max_examples=30, deadline=None)
def test_translation_invariance(tx, ty):
    a = text_paths('<text x="10" y="50" font-family="Noto Sans">Ag</text>')[0][0]
    b = text_paths('<text x="%r" y="%r" font-family="Noto Sans">Ag</text>'
                   % (10 + tx, 50 + ty))[0][0]
    np.testing.assert_allclose(b.points, a.points + [tx, ty], atol=1e-9)


def test_font_size_scales_outline_about_origin():
    a = text_paths('<text x="0" y="0" font-family="Noto Sans" font-size="10">g</text>')[0][0]
    b = text_paths('<text x="0" y="0" font-family="Noto Sans" font-size="30">g</text>')[0][0]
    np.testing.assert_allclose(b.points, a.points * 3, atol=1e-9)


def test_baseline_shift_super_and_length():
    base = ink('<text x="10" y="100" font-family="Noto Sans" font-size="20">'
               'x<tspan>x</tspan></text>')
    up = text_paths('<text x="10" y="100" font-family="Noto Sans" font-size="20">'
                    'x<tspan baseline-shift="7">x</tspan></text>')
    assert bbox(up[1][0])[3] == pytest.approx(base[3] - 7)


# -- paint ----------------------------------------------------------------------

def test_fill_stroke_and_opacity_resolved_per_span():
    ps = text_paths('<text x="10" y="50" font-family="Noto Sans" fill="red" '
                    'stroke="blue" stroke-width="2">A<tspan fill="#00ff00">B</tspan></text>')
    (_, a), (_, b) = ps
    assert a.fill.paint.color == (1.0, 0.0, 0.0, 1.0)
    assert b.fill.paint.color == (0.0, 1.0, 0.0, 1.0)
    assert a.stroke.width == 2 and b.stroke.paint.color == (0.0, 0.0, 1.0, 1.0)


def test_underline_adds_a_rectangle_below_baseline(noto):
    ps = text_paths('<text x="10" y="50" font-family="Noto Sans" font-size="20" '
                    'text-decoration="underline">HI</text>')
    assert len(ps) == 2                     # underline first, then glyphs
    ux0, uy0, ux1, uy1 = bbox(ps[0][0])
    s = 20 / noto.upem
    assert ux0 == pytest.approx(10) and ux1 == pytest.approx(10 + advance(noto, 'HI', 20))
    assert (uy0 + uy1) / 2 == pytest.approx(50 - noto.underline_position * s)
    assert uy1 - uy0 == pytest.approx(noto.underline_thickness * s)


def test_text_in_clip_path_clips():
    img = render(doc('<clipPath id="c"><text x="0" y="150" font-size="200" '
                     'font-family="Noto Sans">I</text></clipPath>'
                     '<rect width="400" height="200" fill="blue" clip-path="url(#c)"/>'),
                 fonts=SUITE_FONTS)
    assert img[100, 2, 3] == 0 and img[100, 300, 3] == 0
    assert (img[:, :, 3] == 255).sum() > 1000


# -- robustness -------------------------------------------------------------------

def test_no_usable_font_draws_with_the_bundled_font_and_warns_once(tmp_path):
    body = ('<rect width="10" height="10" fill="red"/><text x="20" y="50">Hi</text>'
            '<text x="20" y="80">there</text>')
    fonts = FontOptions(dirs=str(tmp_path / 'missing'), system=False)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter('always')
        img = render(doc(body), fonts=fonts)
    msgs = [str(x.message) for x in w if issubclass(x.category, RasterWarning)]
    assert len(msgs) == 1 and 'bundled' in msgs[0]
    assert tuple(img[5, 5]) == (255, 0, 0, 255)
    assert img[30:55, 15:].max() > 0         # "Hi" is drawn


@pytest.mark.parametrize('body', [
    '<text x="a" y="b" font-size="-3">x</text>',
    '<text font-size="0">x</text>',
    '<text x="1e308" y="1e308" font-size="1e300">xyz</text>',
    '<text font-family="">\ue000\ud7ff\U0010fff0</text>',
    '<text><textPath href="#p">on a path</textPath></text>',
    '<text rotate="30">r</text>',
    '<text letter-spacing="1e308">ab</text>',
    '<text><tspan><tspan><tspan dx="1 2 3 4 5 6 7">deep</tspan></tspan></tspan></text>',
])
def test_bad_or_unsupported_text_never_raises(body):
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')
        img = render(doc('<rect width="5" height="5"/>' + body), fonts=SUITE_FONTS)
    assert img[2, 2, 3] == 255


# -- suite cases ------------------------------------------------------------------

PASSING = [
    'text/text/simple-case', 'text/text/nested', 'text/text/xml-space', 'text/text/transform',
    'text/text/x-and-y-with-multiple-values', 'text/text/dx-and-dy-with-multiple-values',
    'text/text/x-and-y-with-multiple-values-and-tspan', 'text/text/zalgo',
    'text/tspan/mixed', 'text/tspan/nested', 'text/tspan/with-dy', 'text/tspan/xml-space-2',
    'text/font-size/simple-case', 'text/font-size/percent-value', 'text/font-family/serif',
    'text/font-family/sans-serif', 'text/font-family/cursive', 'text/font-weight/700',
    'text/font-style/italic', 'text/text-anchor/end-on-text', 'text/text-anchor/on-tspan',
    'text/letter-spacing/1mm', 'text/word-spacing/10', 'text/baseline-shift/sub',
    'text/baseline-shift/nested-super', 'text/text-decoration/line-through',
    'text/text-decoration/overline', 'text/text-decoration/tspan-decoration',
]


@pytest.mark.parametrize('case', PASSING)
def test_suite_case_matches_resvg_reference(case):
    svg = os.path.join(SUITE, 'tests', case + '.svg')
    ref = np.asarray(Image.open(svg[:-4] + '.png').convert('RGBA'))
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')
        img = render(svg, width=ref.shape[1], fonts=SUITE_FONTS)
    r = compare_images(ref, img)
    assert r.passed, r.reason


# -- textPath, textLength, variations --------------------------------------------

def test_text_on_straight_horizontal_path_equals_plain_text():
    """On the line M 10 50 H 390 a glyph's middle sits at arc length
    x + advance/2, so the text lands exactly where x=10 y=50 puts it."""
    plain = text_paths('<text x="10" y="50" font-family="Noto Sans">Ab c</text>')[0][0]
    on = text_paths('<path id="p" d="M 10 50 H 390"/><text font-family="Noto Sans">'
                    '<textPath href="#p">Ab c</textPath></text>')
    on = [p for p, n in on if n.fill is not None and len(p.points) > 10][0]
    np.testing.assert_allclose(on.points, plain.points, atol=1e-9)


def test_text_on_vertical_path_is_rotated_quarter_turn():
    """On the line M 50 10 V 390 (pointing down, +90 degrees) every glyph
    point (x, y) of the plain text at origin (0, 0) maps to
    (50 - y, 10 + x)."""
    plain = text_paths('<text x="0" y="0" font-family="Noto Sans">Hi</text>')[0][0]
    on = text_paths('<path id="p" d="M 50 10 V 390"/><text font-family="Noto Sans">'
                    '<textPath href="#p">Hi</textPath></text>')
    on = [p for p, n in on if len(p.points) > 10][0]
    x, y = plain.points.T
    np.testing.assert_allclose(on.points, np.c_[50 - y, 10 + x], atol=1e-9)


def test_text_path_drops_glyphs_past_the_end_and_bad_links():
    short = text_paths('<defs><path id="p" d="M 10 50 H 25"/></defs><text font-family='
                       '"Noto Sans" font-size="16"><textPath href="#p">HHHHHH</textPath></text>')
    # the H advance is ~11.9 px at 16px: only the first middle (~16) is within 25
    assert len(short) == 1
    box = bbox(short[0][0])
    assert 10 < box[0] and box[2] < 10 + 12
    assert text_paths('<text><textPath href="#nope">x</textPath></text>') == []


def test_text_length_spreads_characters(noto):
    """textLength=300 on 'HHHH' (advance A each): the natural length 4A
    grows by 3 equal gaps, so the last 'H' starts at x + 300 - A."""
    x0, _, x1, _ = ink('<text x="10" y="50" font-family="Noto Sans" textLength="300">'
                       'HHHH</text>')
    a = ink('<text x="10" y="50" font-family="Noto Sans">H</text>')
    A = advance(noto, 'H', 12)
    assert x0 == pytest.approx(a[0])
    assert x1 == pytest.approx(a[2] + 300 - A)


def test_font_variation_settings_change_outline():
    thin = ink('<text x="10" y="50" font-family="Roboto Flex" '
               'style="font-variation-settings: \'wght\' 100">H</text>')
    bold = ink('<text x="10" y="50" font-family="Roboto Flex" '
               'style="font-variation-settings: \'wght\' 900">H</text>')
    assert bold[2] - bold[0] > thin[2] - thin[0]


def test_vertical_writing_mode_is_quarter_turn_of_central_baseline_text():
    """writing-mode=tb at the origin: every point (x, y) of the same Latin
    text laid out horizontally on its central baseline maps to (-y, x)
    (rotated characters: no upright one in "Hi")."""
    plain = text_paths('<text font-family="Noto Sans" dominant-baseline="central">Hi</text>')
    vert = text_paths('<text font-family="Noto Sans" writing-mode="tb">Hi</text>')
    x, y = plain[0][0].points.T
    np.testing.assert_allclose(vert[0][0].points, np.c_[-y, x], atol=1e-9)


def test_bitmap_only_font_draws_its_bitmaps_and_falls_back_for_the_rest(tmp_path):
    """A bitmap-only (CBDT) font has no outlines: its emoji is an image,
    the letter it lacks comes from another face of the directory."""
    import shutil
    from raster.tree import ImageNode
    for fn in ('NotoColorEmojiCBDT.subset.ttf', 'NotoSans-Regular.ttf'):
        shutil.copy(os.path.join(FONTS, fn), tmp_path / fn)
    fonts = FontOptions(dirs=str(tmp_path), system=False)
    tree = load_svg(doc('<text x="10" y="50" font-family="Noto Color Emoji">A\U0001F600</text>'),
                    fonts=fonts)
    paths = [(n.path.transform(t), n) for n, t in walk(tree.root) if isinstance(n, PathNode)]
    images = [n for n, _ in walk(tree.root) if isinstance(n, ImageNode)]
    ref = text_paths('<text x="10" y="50" font-family="Noto Sans">A</text>')
    assert len(paths) == 1 and paths[0][0] == ref[0][0]
    assert len(images) == 1 and images[0].pixels.shape == (128, 136, 4)


_XML_CHARS = st.characters(blacklist_categories=('Cs', 'Cc'), blacklist_characters='<&>')


@given(st.text(_XML_CHARS, max_size=12),
       st.lists(st.floats(-50, 50, allow_nan=False), max_size=5),
       st.sampled_from(['start', 'middle', 'end']),
       st.sampled_from(['Noto Sans', 'serif', 'Amiri', 'Nope', 'monospace']))
@settings(max_examples=40, deadline=None)
def test_arbitrary_text_builds_and_stays_finite(text, dxs, anchor, family):
    """Any characters, dx lists, anchors and families: the tree builds
    without an exception and every glyph point is finite."""
    dx = ' '.join('%r' % v for v in dxs)
    body = ('<text x="20" y="60" text-anchor="%s" font-family="%s" %s>%s'
            '<tspan dy="3">%s</tspan></text>'
            % (anchor, family, 'dx="%s"' % dx if dx else '', text, text[::-1]))
    with warnings.catch_warnings():
        warnings.simplefilter('error', RasterWarning)
        try:
            ps = text_paths(body)
        except RasterWarning as w:      # only the documented kinds
            assert any(k in str(w) for k in ('vertical', 'not usable', 'no font has a glyph')), \
                str(w)
            return
    for p, _ in ps:
        assert np.isfinite(p.points).all()


def test_letter_spacing_skips_cursive_arabic_letters():
    """Arabic letters join: letter-spacing is applied to the spaces only,
    so two Arabic words grow by exactly one spacing (right-to-left run)."""
    words = '\u0628\u0639\u0636 \u0627\u0644\u0646\u0635'
    a = ink('<text x="20" y="60" font-family="Amiri" font-size="20">%s</text>' % words)
    b = ink('<text x="20" y="60" font-family="Amiri" font-size="20" '
            'letter-spacing="10">%s</text>' % words)
    assert (b[2] - b[0]) - (a[2] - a[0]) == pytest.approx(10)


# -- the vectorized glyph paths against a per-glyph construction -------------------

def per_glyph_reference(spans, x, y, ls=0.0, ws=0.0, dx=(), rotate=()):
    """Glyph outlines of one chunk built glyph by glyph, as a reference.

    ``spans``: (text, family, font size) of the text element and its
    tspans, in order; runs of one font are shaped together, every glyph is
    scaled by the size of its own span, ``dx``/``rotate`` apply per
    character (the last angle repeating), letter/word spacing after every
    character/space.  Returns one (verbs, points) per run of consecutive
    glyphs of one span.  Left-to-right text without spaces at the ends of
    font runs and without fallback fonts only.
    """
    import math
    db = FontDB([FONTS])
    chars, owner, fonts = [], [], []
    for si, (text, family, _) in enumerate(spans):
        f = Font.load(db.match([family]))
        for ch in text:
            chars.append(ch)
            owner.append(si)
            fonts.append(f)
    n = len(chars)
    dxs = list(dx) + [0.0] * n
    rots = (list(rotate) + [rotate[-1]] * n) if rotate else [0.0] * n
    before, sum_dx, sum_extra = [], 0.0, 0.0
    for k, ch in enumerate(chars):
        sum_dx += dxs[k]
        before.append(sum_dx + sum_extra)
        sum_extra += ls + (ws if ch == ' ' else 0.0)
    pieces = []         # (span, verbs, points) per glyph
    pen, k = 0.0, 0
    while k < n:
        e = k + 1
        while e < n and fonts[e] is fonts[k]:
            e += 1
        f = fonts[k]
        for gid, cluster, xa, _, xo, yo in f.shape(''.join(chars[k:e])):
            j = k + cluster
            s = spans[owner[j]][2] / f.upem
            outline = f.outline(gid)
            th = math.radians(rots[j])
            X, Y = outline.points[:, 0] * s, -outline.points[:, 1] * s
            X, Y = math.cos(th) * X - math.sin(th) * Y, math.sin(th) * X + math.cos(th) * Y
            origin = (x + pen + before[j] + xo * s, y - yo * s)
            pieces.append((owner[j], outline.verbs, np.c_[X + origin[0], Y + origin[1]]))
            pen += xa * s
        k = e
    out = []
    for si, verbs, pts in pieces:
        if out and out[-1][0] == si:
            out[-1][1].append(verbs)
            out[-1][2].append(pts)
        else:
            out.append((si, [verbs], [pts]))
    return [(np.concatenate(v), np.concatenate(p)) for _, v, p in out]


@pytest.mark.parametrize('spans, attrs', [
    ([('Hello, World', 'Noto Sans', 40)], {}),
    ([('AVAWAY orbit', 'Noto Serif', 23.5)], {'letter-spacing': 2.5, 'word-spacing': 4}),
    # 'B' only: the font's 'A' is an sbix bitmap (drawn as an image)
    ([('BB', 'CFF Outlines and SBIX', 50), ('B B', 'CFF Outlines and SBIX', 25)], {}),
    ([('Ab', 'Noto Sans', 30), ('cd', 'Noto Sans', 15), ('ef', 'Noto Serif', 20)],
     {'dx': [1, 2, 3], 'rotate': [15, -30, 45]}),
    ([('The quick brown fox jumps over the lazy dog 0123456789', 'Source Sans Pro', 12)],
     {'rotate': [5], 'letter-spacing': -0.5}),
])
def test_glyph_paths_equal_per_glyph_construction(spans, attrs):
    """The glyph outlines of a text (shaping and outlines cached, positions
    and outline transforms computed on whole arrays) equal those built
    glyph by glyph, to 1e-9."""
    x, y = 13.25, 71.5
    extra = ''.join(' %s="%s"' % (k, ' '.join(map(str, v)) if isinstance(v, list) else v)
                    for k, v in attrs.items())
    (t0, f0, s0), rest = spans[0], spans[1:]
    body = ('<text x="%r" y="%r" font-family="%s" font-size="%r"%s>%s%s</text>'
            % (x, y, f0, s0, extra, t0, ''.join(
                '<tspan font-family="%s" font-size="%r">%s</tspan>' % (f, s, t)
                for t, f, s in rest)))
    for _ in range(2):          # built twice: the second time from the caches
        got = text_paths(body)
        ref = per_glyph_reference(spans, x, y, attrs.get('letter-spacing', 0.0),
                                  attrs.get('word-spacing', 0.0), attrs.get('dx', ()),
                                  attrs.get('rotate', ()))
        assert len(got) == len(ref)
        for (p, _), (verbs, pts) in zip(got, ref):
            np.testing.assert_array_equal(p.verbs, verbs)
            np.testing.assert_allclose(p.points, pts, rtol=0, atol=1e-9)


def test_letter_spacing_is_per_cluster_as_usvg():
    """A ligature is one cluster: letter-spacing is added once after it
    (usvg's rule), and never after the chunk's last cluster."""
    serif = Font.load(FontDB([FONTS]).match(['Noto Serif']))
    assert len(serif.shape('ffi')) == 1            # Noto Serif has an ffi ligature
    a = ink('<text x="10" y="50" font-family="Noto Serif" font-size="40">ffio</text>')
    b = ink('<text x="10" y="50" font-family="Noto Serif" font-size="40" '
            'letter-spacing="7">ffio</text>')
    assert b[2] - a[2] == pytest.approx(7.0, abs=1e-6)      # one gap: ffi|o


def test_shaping_memo_is_bounded_and_shared():
    """Chunks are shaped once per font and text in a document; the memo
    table is emptied beyond its bound and shapes again the same."""
    from raster.parser import textlayout as L
    font = Font.load(FontDB([FONTS]).match(['Noto Sans']))
    memo = {}
    runs = [(0, 3, False)]
    r = L._shape_runs(font, 'AVA', runs, None, memo)
    assert L._shape_runs(font, 'AVA', runs, None, memo) is r
    assert r[0].tolist() == [g[0] for g in font.shape('AVA')]
    nok = L._shape_runs(font, 'AVA', runs, {'kern': 0}, memo)
    assert nok[2].tolist() != r[2].tolist()         # kerning changes the advances
    for i in range(5000):
        w = 'w%d' % i
        L._shape_runs(font, w, [(0, len(w), False)], None, memo)
        assert len(memo) <= 4097
    again = L._shape_runs(font, 'AVA', runs, None, memo)
    assert [a.tolist() for a in again] == [a.tolist() for a in r]


def test_same_string_in_other_fonts_of_one_document():
    """Repeated strings of one document share shaping only within one
    font: each text equals the same text built alone."""
    texts = ['<text x="10" y="%d" font-family="%s"%s>AVA</text>' % (30 + 20 * i, fam, kern)
             for i, (fam, kern) in enumerate([('Noto Sans', ''), ('Noto Serif', ''),
                                              ('Noto Sans', ' font-kerning="none"'),
                                              ('Noto Sans', '')])]
    together = text_paths(''.join(texts))
    alone = [text_paths(t)[0] for t in texts]
    assert len(together) == 4
    for (p, _), (q, _) in zip(together, alone):
        assert p == q
    np.testing.assert_allclose(together[3][0].points, together[0][0].points + [0, 60], atol=1e-9)
    assert together[0][0] != together[2][0]


# -- characters without a glyph -------------------------------------------------

def test_characters_without_a_glyph_warn_once_per_document():
    """U+E000 (private use) and U+0378 (unassigned) are in none of the
    suite's fonts: one warning naming them, however many elements hold
    such characters; the boxes are still drawn."""
    body = ('<text x="10" y="50" font-family="Noto Sans">a\ue000b\u0378</text>'
            '<text x="10" y="90">\ue001</text>')
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter('always')
        ps = text_paths(body)
    msgs = [str(x.message) for x in w if issubclass(x.category, RasterWarning)]
    assert len(msgs) == 1 and 'U+E000 U+0378' in msgs[0] and 'boxes' in msgs[0]
    assert len(ps) == 2


@pytest.mark.parametrize('text', ['a b', 'a\u200db', 'a\ufe0fb', '\u4e2d', 'a\u00a0b\tc'])
def test_no_warning_when_every_character_has_a_glyph(text):
    """Spaces, default-ignorable characters and characters another face
    has (CJK from the fallback) do not warn."""
    with warnings.catch_warnings():
        warnings.simplefilter('error')
        assert text_paths('<text x="10" y="50" font-family="Noto Sans">%s</text>' % text)


def test_fallback_tries_the_font_family_list_first():
    """CSS Fonts' order: a character the first family lacks comes from the
    next family of the list that has it (Twitter Color Emoji: an SVG
    glyph), not from the first face of the folder that has it (Noto Color
    Emoji: a bitmap)."""
    from raster.tree import ImageNode
    def images(family):
        tree = load_svg(doc('<text x="10" y="50" font-family="%s">a\U0001F600</text>' % family),
                        fonts=SUITE_FONTS)
        return [n for n, _ in walk(tree.root) if isinstance(n, ImageNode)]
    assert images('Noto Sans, Twitter Color Emoji') == []
    assert len(images('Noto Sans, Noto Color Emoji')) == 1


# -- the leaf path (text elements of character data only) ------------------------

_LEAF_STYLES = st.sampled_from([
    '', 'text-anchor="middle"', 'text-anchor="end"', 'textLength="120"',
    'textLength="90" lengthAdjust="spacingAndGlyphs"', 'text-decoration="underline"',
    'letter-spacing="3" word-spacing="5"', 'dominant-baseline="central"',
    'writing-mode="tb"', 'font-weight="bold" fill="red"', 'style="font-size:30px"',
    'font-family="Noto Sans, Noto Serif"', 'xml:space="preserve"'])


@settings(max_examples=40, deadline=None)
@given(text=st.text(st.sampled_from('ab W.\u00e9\u05d0\u4e2d'), min_size=0, max_size=8),
       attrs=_LEAF_STYLES, x=st.sampled_from(['0', '12.5', '10 20 30', '-40', '5%']),
       y=st.floats(-50, 200))
def test_leaf_text_equals_the_general_path(text, attrs, x, y):
    """Text elements of character data only (the leaf path, their layout
    shared per style) draw what the general path draws for them."""
    from raster.parser import text as text_module
    body = ('<g text-decoration="overline"><text x="%s" y="%r" %s>%s</text>'
            '<text y="%s" %s>%s</text><text %s>%s</text></g>'
            % (x, y, attrs, text, x, attrs, text[::-1], attrs, text))
    real = text_module._leaf
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')
        leaf = text_paths(body)
        text_module._leaf = lambda *a: False
        try:
            general = text_paths(body)
        finally:
            text_module._leaf = real
    assert len(leaf) == len(general)
    for (p, n), (q, m) in zip(leaf, general):
        assert p == q
        assert n.fill == m.fill and n.stroke == m.stroke


def test_leaf_texts_differing_in_clip_paths_share_one_style_set_up():
    """A terminal screenshot's rows: many leaf text elements of a few
    classes, each row with its own clip path.  The spans are set up once
    per class (the clip path does not reach the layout), every element is
    placed at its own position and keeps its own clip path."""
    from raster.parser import build_tree
    from raster.parser.document import load_document
    from raster.parser import text as text_module
    rows = ''.join('<clipPath id="c%d"><rect y="%d" width="400" height="20"/></clipPath>'
                   % (i, 20 * i) for i in range(5))
    texts = ''.join('<text class="%s" x="%d" y="%d" clip-path="url(#c%d)">%s</text>'
                    % ('ab'[i % 2], 7 * j, 20 * i + 15, i, 'xyz'[j % 3])
                    for i in range(5) for j in range(8))
    src = ('<svg %s width="400" height="200"><style>.a {fill: red; font-family: Noto Sans}'
           '.b {fill: blue; font-family: Noto Sans; font-weight: bold}</style>%s%s</svg>'
           % (NS, rows, texts)).encode()
    calls = []
    real = text_module._leaf_style

    def counting(*a):
        calls.append(1)
        return real(*a)
    text_module._leaf_style = counting
    try:
        tree = build_tree(load_document(src), fonts=SUITE_FONTS)
    finally:
        text_module._leaf_style = real
    assert len(calls) <= 2          # one per class (the first element takes the general path)
    groups = [n for n in tree.root.children]
    assert len(groups) == 40
    lefts = [bbox(g.children[0].path)[0] for g in groups]
    for i in range(5):
        row = lefts[8 * i:8 * i + 8]
        assert all(b > a for a, b in zip(row, row[1:]))     # each at its own x
    clips = [g.clip_path for g in groups]
    assert len({id(c) for c in clips}) == 5                 # one per row, shared


# -- spaces at the end of a child (usvg's and Chrome's rule) -----------------------

def test_space_before_a_tail_moves_out_of_a_text_path(noto):
    """'abc ' on a path followed by ' X': the space leaves the path and
    starts the next chunk, so X sits one space advance (Noto Sans: 260
    units) further than without the spaces, and the path's glyphs are the
    same."""
    size = 20.0
    path = '<defs><path id="p" d="M 10 100 L 190 100"/></defs>'

    def body(inner, tail):
        return ('%s<text font-family="Noto Sans" font-size="%g"><textPath href="#p">%s'
                '</textPath>%s<tspan fill="green">X</tspan></text>' % (path, size, inner, tail))
    spaced = text_paths(body('abc ', ' '))
    tight = text_paths(body('abc', ''))
    assert spaced[0][0] == tight[0][0]
    shift = bbox(spaced[1][0])[0] - bbox(tight[1][0])[0]
    assert shift == pytest.approx(advance(noto, ' ', size), abs=1e-6)
    assert advance(noto, ' ', size) == pytest.approx(260 * size / 1000)


def test_space_before_a_tail_belongs_to_the_parent_span():
    """'a <tspan>b </tspan> c' draws the space after b in the text's own
    style: an underline of the tspan ends with b."""
    with_space = text_paths('<text x="10" y="50" font-family="Noto Sans" font-size="30">a '
                            '<tspan text-decoration="underline">b </tspan> c</text>')
    without = text_paths('<text x="10" y="50" font-family="Noto Sans" font-size="30">a '
                         '<tspan text-decoration="underline">b</tspan> c</text>')
    assert [p for p, _ in with_space] == [p for p, _ in without]


def test_text_of_an_invalid_text_path_still_separates_spaces():
    """An invalid textPath draws nothing, but its characters take part in
    the whitespace processing: 'Some <textPath>long</textPath> text' lays
    out as 'Some  text' with both spaces."""
    got = text_paths('<text x="10" y="50" font-family="Noto Sans" font-size="24">Some '
                     '<textPath>long</textPath> text</text>')
    want = text_paths('<text x="10" y="50" font-family="Noto Sans" font-size="24" '
                      'xml:space="preserve">Some  text</text>')
    assert [p for p, _ in got] == [p for p, _ in want]
    blank = text_paths('<text x="10" y="50" font-family="Noto Sans" font-size="24">Some '
                       '<textPath> </textPath> text</text>')
    assert [p for p, _ in blank] == [p for p, _ in text_paths(
        '<text x="10" y="50" font-family="Noto Sans" font-size="24">Some text</text>')]


def test_text_path_is_followed_as_closely_when_scaled_up():
    """Text on a tiny curve scaled up 100 times draws what the same text
    on the curve 100 times larger draws (the path is flattened within
    0.01 device pixels, not only 0.01 user units: the glyphs' positions
    and turns agree within 0.05 pixels)."""
    def body(k, extra):
        return ('<g transform="scale(%g)"><defs><path id="c" d="M %g %g C %g %g %g %g %g %g"/>'
                '</defs><text font-family="Noto Sans" font-size="%g" dy="%g"><textPath href="#c">'
                'Some long text</textPath></text></g>' % (
                    (k,) + tuple(v / k for v in (20, 73, 35, 108, 85, 108, 180, 73, 24, 15))))
    small = text_paths(body(100.0, ''))
    large = text_paths(body(1.0, ''))
    assert len(small) == len(large) == 1
    p, q = small[0][0].points, large[0][0].points
    assert p.shape == q.shape
    assert np.abs(p - q).max() < 0.05
