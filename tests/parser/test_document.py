"""Tests of raster.parser.document.load_document: sources, gzip, XML errors,
entities (internal ones work, billion laughs is refused), the root check."""

import gzip
import io

import pytest

from raster.errors import SVGError
from raster.parser.document import SVG_NS, load_document

SVG = b'<svg xmlns="http://www.w3.org/2000/svg" width="10" height="20"><rect width="1" height="1"/></svg>'
ROOT = '{%s}svg' % SVG_NS


def test_bytes_str_and_file_object():
    for src in (SVG, SVG.decode(), io.BytesIO(SVG), bytearray(SVG)):
        root = load_document(src)
        assert root.tag == ROOT and root.get('height') == '20'


def test_path_and_pathlike(tmp_path):
    p = tmp_path / 'a.svg'
    p.write_bytes(SVG)
    assert load_document(str(p)).tag == ROOT
    assert load_document(p).tag == ROOT


def test_svgz_by_magic_and_extension(tmp_path):
    p = tmp_path / 'a.svgz'
    p.write_bytes(gzip.compress(SVG))
    assert load_document(p).get('width') == '10'
    assert load_document(gzip.compress(SVG)).get('width') == '10'


def test_gzip_bomb_refused():
    big = gzip.compress(b'<svg xmlns="http://www.w3.org/2000/svg">' + b' ' * 5_000_000 + b'</svg>')
    assert len(big) < 10_000
    with pytest.raises(SVGError, match='larger than'):
        load_document(big, max_bytes=1_000_000)


def test_corrupt_gzip():
    with pytest.raises(SVGError, match='gzip'):
        load_document(gzip.compress(SVG)[:30])


def test_size_cap_plain():
    with pytest.raises(SVGError, match='larger than'):
        load_document(io.BytesIO(SVG), max_bytes=10)
    with pytest.raises(SVGError, match='larger than'):
        load_document(gzip.compress(SVG), max_bytes=20)


def test_xml_error_has_line():
    with pytest.raises(SVGError) as e:
        load_document(b'<svg xmlns="http://www.w3.org/2000/svg">\n<g>\n<rect></g></svg>')
    msg = str(e.value)
    assert msg.startswith('XML error at line 3') and '\n' not in msg


def test_empty_document():
    with pytest.raises(SVGError, match='empty'):
        load_document(b'   ')


def test_not_svg_root():
    with pytest.raises(SVGError, match=r'root element is <html>'):
        load_document(b'<html><body/></html>')
    with pytest.raises(SVGError, match=r'root element is <svg>'):
        load_document(b'<svg xmlns="http://example.org/other"/>')


def test_no_namespace_svg_root_is_adopted():
    root = load_document(b'<svg width="5"><g><rect/></g></svg>')
    assert root.tag == ROOT
    assert [el.tag for el in root.iter()] == [ROOT, '{%s}g' % SVG_NS, '{%s}rect' % SVG_NS]


def test_prefixed_svg_namespace():
    root = load_document(b'<s:svg xmlns:s="http://www.w3.org/2000/svg"><s:rect/></s:svg>')
    assert root.tag == ROOT and root[0].tag == '{%s}rect' % SVG_NS


def test_internal_entities_expand():
    doc = b'''<!DOCTYPE svg [
  <!ENTITY fill_value "green">
  <!ENTITY Rect "<rect id='r' width='3' height='3'/>">
]>
<svg xmlns="http://www.w3.org/2000/svg"><g fill="&fill_value;">&Rect;</g></svg>'''
    root = load_document(doc)
    g = root[0]
    assert g.get('fill') == 'green'
    assert g[0].get('id') == 'r'
    assert g[0].tag == '{%s}rect' % SVG_NS      # entity content joins the SVG namespace


def test_billion_laughs_refused():
    ents = ['<!ENTITY a "%s">' % ('x' * 50)]
    for i, n in enumerate('bcdefghij'):
        prev = 'abcdefghij'[i]
        ents.append('<!ENTITY %s "%s">' % (n, ('&%s;' % prev) * 10))
    doc = '<!DOCTYPE svg [%s]><svg xmlns="http://www.w3.org/2000/svg"><text>&j;</text></svg>' % ''.join(ents)
    with pytest.raises(SVGError, match='XML error'):
        load_document(doc.encode())


def test_external_entity_not_loaded(tmp_path):
    secret = tmp_path / 'secret.txt'
    secret.write_text('TOPSECRET')
    doc = ('<!DOCTYPE svg [<!ENTITY x SYSTEM "file://%s">]>'
           '<svg xmlns="http://www.w3.org/2000/svg"><text>&x;</text></svg>' % secret)
    try:
        root = load_document(doc.encode())
    except SVGError:
        return
    assert 'TOPSECRET' not in ''.join(root.itertext())


def test_comments_and_pis_removed():
    root = load_document(b'<svg xmlns="http://www.w3.org/2000/svg"><!-- c --><?pi x?><g/></svg>')
    assert len(root) == 1


def test_bad_source_type():
    with pytest.raises(SVGError, match='cannot read'):
        load_document(12)


def test_missing_file():
    with pytest.raises(OSError):
        load_document('/nonexistent/file.svg')


def test_xlink_href_inside_an_entity_is_accepted():
    # libxml2 parses entity text without the root's xmlns:xlink in scope;
    # the document is retried with plain href inside the DTD only
    doc = (b'<!DOCTYPE svg [<!ENTITY R "<rect id=\'r\' width=\'2\' height=\'2\'/>'
           b'<use xlink:href=\'#r\' x=\'3\'/>">]>'
           b'<svg xmlns="http://www.w3.org/2000/svg" '
           b'xmlns:xlink="http://www.w3.org/1999/xlink">&R;</svg>')
    root = load_document(doc)
    use = root.find('{%s}use' % SVG_NS)
    assert use is not None and use.get('href') == '#r'


def test_other_namespace_errors_still_fail():
    with pytest.raises(SVGError, match='Namespace prefix foo'):
        load_document(b'<svg xmlns="http://www.w3.org/2000/svg"><rect foo:x="1"/></svg>')
