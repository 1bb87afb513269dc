"""@font-face: the rules found in style sheets, src lists, local files
(relative to the document, allowed directories only), data: URIs with
TrueType, WOFF and WOFF2, local() faces, descriptors, and what is skipped
or warned about."""
import base64
import io
import os
import shutil
import warnings

import numpy as np
import pytest
from fontTools.ttLib import TTFont
from lxml import etree

from raster.errors import RasterWarning
from raster.fonts import FontOptions
from raster.parser.css import font_face_rules
from raster.parser.fontface import parse_src
from raster.svg import load_svg
from raster.tree import PathNode, walk

from _shared import SUITE_FONTS

NS = 'xmlns="http://www.w3.org/2000/svg"'
SUITE = FontOptions(dirs=SUITE_FONTS, system=False)
YELLOWTAIL = os.path.join(SUITE_FONTS, 'Yellowtail-Regular.ttf')


def paths(svg, fonts=SUITE, path=None):
    """The glyph paths (user space) of a document given as text, parsed
    from ``path`` when given (relative references resolve against it)."""
    if path is not None:
        with open(path, 'w') as f:
            f.write(svg)
        tree = load_svg(str(path), fonts=fonts)
    else:
        tree = load_svg(svg.encode(), fonts=fonts)
    return [n.path.transform(t) for n, t in walk(tree.root) if isinstance(n, PathNode)]


def doc(rules, family, text='Hello'):
    return ('<svg %s width="300" height="100"><style>%s</style><text x="10" y="60" '
            'font-size="30" font-family="%s">%s</text></svg>' % (NS, rules, family, text))


@pytest.fixture(scope='module')
def yellowtail():
    """Glyph paths of 'Hello' drawn with Yellowtail as an installed font."""
    return paths(doc('', 'Yellowtail'))


def flavoured(flavor):
    tt = TTFont(YELLOWTAIL)
    tt.flavor = flavor
    buf = io.BytesIO()
    tt.save(buf)
    return buf.getvalue()


def data_uri(data, mime='font/ttf'):
    return 'data:%s;base64,%s' % (mime, base64.b64encode(data).decode())


# -- parsing ----------------------------------------------------------------------

def test_font_face_rules_in_document_order():
    root = etree.fromstring(
        '<svg %s><style>/* @font-face { font-family: X } */ @font-face { font-family: A; '
        'src: url(a.ttf); font-family: B } text { fill: red } @media print { @font-face '
        '{ font-family: C } } @font-face{font-family:"D E";src:local(D)}</style>'
        '<style type="text/other">@font-face { font-family: F }</style></svg>' % NS)
    assert font_face_rules(root) == [{'font-family': 'B', 'src': 'url(a.ttf)'},
                                     {'font-family': '"D E"', 'src': 'local(D)'}]


def test_parse_src_entries():
    assert parse_src("local( 'A B' ), url( 'x y.woff' ) format('woff', 'woff2'),"
                     "url(data:font/woff2;base64,AA==) format(woff2), bogus(1), url()") == [
        ('local', 'A B'), ('url', 'x y.woff', ('woff', 'woff2')),
        ('url', 'data:font/woff2;base64,AA==', ('woff2',))]
    assert parse_src('') == [] and parse_src(None) == []


# -- sources -----------------------------------------------------------------------

def test_relative_file_next_to_the_document(tmp_path, yellowtail):
    shutil.copy(YELLOWTAIL, tmp_path / 'script.ttf')
    got = paths(doc('@font-face { font-family: "My Script"; src: url(script.ttf) }',
                    'My Script'), path=tmp_path / 'd.svg')
    assert got == yellowtail


@pytest.mark.parametrize('flavor, mime', [(None, 'font/ttf'), ('woff', 'font/woff'),
                                          ('woff2', 'font/woff2')])
def test_data_uri_fonts(flavor, mime, yellowtail):
    rule = '@font-face { font-family: Inline; src: url(%s) }' % data_uri(flavoured(flavor),
                                                                         mime)
    assert paths(doc(rule, 'Inline')) == yellowtail


def test_network_source_skipped_silently_for_the_next(yellowtail):
    rule = ('@font-face { font-family: Inline; src: url(https://example.com/a.woff2) '
            'format("woff2"), url("%s") }' % data_uri(flavoured(None)))
    with warnings.catch_warnings():
        warnings.simplefilter('error')
        assert paths(doc(rule, 'Inline')) == yellowtail


def test_unsupported_formats_are_skipped(yellowtail):
    rule = ('@font-face { font-family: Inline; src: url("%s") format("embedded-opentype"), '
            'url("%s") format("truetype") }' % (data_uri(b'junk'), data_uri(flavoured(None))))
    with warnings.catch_warnings():
        warnings.simplefilter('error')
        assert paths(doc(rule, 'Inline')) == yellowtail


def test_local_by_full_and_postscript_name(yellowtail):
    tt = TTFont(YELLOWTAIL)
    full, ps = tt['name'].getDebugName(4), tt['name'].getDebugName(6)
    for name in (full, ps, ps.upper()):
        rule = '@font-face { font-family: Alias; src: local("Nope"), local("%s") }' % name
        assert paths(doc(rule, 'Alias')) == yellowtail


def test_file_outside_the_allowed_directories_is_refused(tmp_path):
    inside = tmp_path / 'doc'
    inside.mkdir()
    shutil.copy(YELLOWTAIL, tmp_path / 'outside.ttf')
    rule = '@font-face { font-family: Out; src: url(../outside.ttf) }'
    with pytest.warns(RasterWarning, match='outside the allowed directories'):
        got = paths(doc(rule, 'Out, Noto Sans'), path=inside / 'd.svg')
    assert got == paths(doc('', 'Noto Sans'))


@pytest.mark.parametrize('payload, message', [
    (b'not a font at all', 'not a font'),
    (flavoured('woff2')[:200], 'WOFF2'),
])
def test_bad_font_data_warns_once_and_falls_back(payload, message):
    rule = '@font-face { font-family: Broken; src: url("%s") }' % data_uri(payload)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter('always')
        got = paths(doc(rule, 'Broken, Noto Sans') + '')
    msgs = [str(x.message) for x in w if issubclass(x.category, RasterWarning)]
    assert len(msgs) == 1 and 'Broken' in msgs[0] and message in msgs[0]
    assert got == paths(doc('', 'Noto Sans'))


# -- matching ----------------------------------------------------------------------

def test_document_family_hides_an_installed_family(yellowtail):
    rule = '@font-face { font-family: "Noto Sans"; src: url("%s") }' % data_uri(
        flavoured(None))
    assert paths(doc(rule, 'Noto Sans')) == yellowtail


def test_weight_descriptors_choose_the_face(yellowtail):
    sans = open(os.path.join(SUITE_FONTS, 'NotoSans-Regular.ttf'), 'rb').read()
    rules = ('@font-face { font-family: Two; src: url("%s"); font-weight: 400 }'
             '@font-face { font-family: Two; src: url("%s"); font-weight: bold }'
             % (data_uri(sans), data_uri(flavoured(None))))
    assert paths(doc(rules, 'Two').replace('font-size', 'font-weight="bold" font-size')) \
        == yellowtail
    assert paths(doc(rules, 'Two')) == paths(doc('', 'Noto Sans'))


def test_generic_family_names_cannot_be_declared():
    rule = '@font-face { font-family: serif; src: url("%s") }' % data_uri(flavoured(None))
    assert paths(doc(rule, 'serif')) == paths(doc('', 'serif'))


# -- unicode-range ----------------------------------------------------------------------

def glyphs(svg):
    """The glyph outlines of a document as a multiset of points: the
    sorted (P, 2) points of all its paths (the same glyphs in other
    pieces or another order give the same array)."""
    pts = np.concatenate([p.points for p in paths(svg)])
    return pts[np.lexsort(pts.T[::-1])]


def same(a, b, atol=0.0):
    return a.shape == b.shape and np.allclose(a, b, rtol=0, atol=atol)


def test_unicode_range_face_draws_only_its_characters():
    """Digits from the face declared for U+30-39, everything else (the
    spaces too) from the next family: the same outlines as tspans in the
    two installed families."""
    rule = ('@font-face { font-family: Digits; src: local("NotoSerif-Regular"); '
            'unicode-range: U+30-39 }')
    got = glyphs(doc(rule, 'Digits, Noto Sans', 'Ab 2024 x9'))
    want = glyphs(doc('', 'Noto Sans', 'Ab <tspan font-family="Noto Serif">2024</tspan> '
                                       'x<tspan font-family="Noto Serif">9</tspan>'))
    assert same(got, want)
    assert not same(got, glyphs(doc('', 'Noto Sans', 'Ab 2024 x9')))


def test_unicode_range_missing_every_character_leaves_the_face_unused():
    rule = ('@font-face { font-family: Cyr; src: local("NotoSerif-Regular"); '
            'unicode-range: U+4?? }')
    assert same(glyphs(doc(rule, 'Cyr, Noto Sans', 'Hello')), glyphs(doc('', 'Noto Sans', 'Hello')))
    # and the Cyrillic letters are the face's
    assert same(glyphs(doc(rule, 'Cyr, Noto Sans', 'Мир')), glyphs(doc('', 'Noto Serif', 'Мир')))


@pytest.mark.parametrize('value', ['U+00FF-0025', 'U+41, U+4?4', 'U+110000', 'U+0-10FFFF',
                                   'bogus'])
def test_invalid_or_full_unicode_range_means_every_character(value):
    rule = ('@font-face { font-family: Whole; src: local("NotoSerif-Regular"); '
            'unicode-range: %s }' % value)
    assert same(glyphs(doc(rule, 'Whole, Noto Sans', 'Ab 2024')),
                glyphs(doc('', 'Noto Serif', 'Ab 2024')))


def test_family_split_by_unicode_range_checks_the_last_rule_first():
    """Two faces of one family whose ranges overlap on the capitals: the
    rule defined last wins there (CSS Fonts 4, 4.5); swapping the rules
    swaps the faces."""
    sans = '@font-face { font-family: Split; src: local("NotoSans-Regular"); unicode-range: U+0-7F }'
    serif = ('@font-face { font-family: Split; src: local("NotoSerif-Regular"); '
             'unicode-range: U+41-5A }')
    got = glyphs(doc(sans + serif, 'Split', 'Hello World'))
    want = glyphs(doc('', 'Noto Sans', '<tspan font-family="Noto Serif">H</tspan>ello '
                                       '<tspan font-family="Noto Serif">W</tspan>orld'))
    assert got.shape == want.shape
    # the faces' pieces as tspans of the two families would draw them, but
    # for kerning: the Sans face shapes the whole text (capitals included)
    assert not same(got, glyphs(doc('', 'Noto Sans', 'Hello World')), atol=1.0)
    # serif defined last for U+0-7F: every character is serif
    serif_all = ('@font-face { font-family: Split; src: local("NotoSerif-Regular"); '
                 'unicode-range: U+0-7F }')
    sans_caps = ('@font-face { font-family: Split; src: local("NotoSans-Regular"); '
                 'unicode-range: U+41-5A }')
    got = glyphs(doc(sans_caps + serif_all, 'Split', 'Hello'))
    assert same(got, glyphs(doc('', 'Noto Serif', 'Hello')))


def test_font_of_a_unicode_range_face_has_only_its_characters():
    import dataclasses
    from raster.fonts import Font, FontDB
    face = FontDB([SUITE_FONTS]).match(['Noto Sans'])
    whole = Font.load(face)
    part = Font.load(dataclasses.replace(face, unicode_range=(0x30, 0x39)))
    assert part is not whole
    assert whole.has_char('A') and whole.has_char('5')
    assert part.has_char('5') and not part.has_char('A')
    shaped = part.shape_arrays('A5 ')
    assert shaped.gid.tolist()[1] == whole.shape_arrays('A5 ').gid.tolist()[1]
    assert shaped.gid.tolist()[0] == 0 and shaped.gid.tolist()[2] == 0
