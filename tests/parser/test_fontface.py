"""@font-face: the rules found in style sheets, src lists, local files
(relative to the document, allowed directories only), data: URIs with
TrueType, WOFF and WOFF2, local() faces, descriptors, and what is skipped
or warned about."""
import base64
import io
import os
import shutil
import warnings

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
