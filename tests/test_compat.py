"""raster.svg2png against CairoSVG's svg2png on the same documents, one
parameter at a time: output sizes (rounding included), scale, dpi, parent
sizes, background, the three inputs and both kinds of write_to; pixels of
simple shapes compared with raster.testing.compare_images."""

import io
import os
import pathlib

import cairosvg
import numpy as np
import pytest
from PIL import Image

import raster
from raster.errors import CanvasError, RasterError, RasterIOError, SVGError
from raster.testing import compare_images

NS = b'xmlns="http://www.w3.org/2000/svg"'
DOCS = {
    # px size, a blue rectangle
    'plain': b'<svg ' + NS + b' width="40" height="30"><rect x="5" y="5" width="20" '
             b'height="10" fill="blue"/></svg>',
    # fractional size: CairoSVG rounds half to even (10.5 -> 10, 7.5 -> 8)
    'fractional': b'<svg ' + NS + b' width="10.5" height="7.5"><rect width="5" height="5" '
                  b'fill="blue"/></svg>',
    # viewBox scaled 10x into the size
    'viewbox': b'<svg ' + NS + b' width="40" height="30" viewBox="0 0 4 3"><rect width="2" '
               b'height="1" fill="#00ff00"/></svg>',
    # percentage size: of the parent box, else the viewBox size
    'percent': b'<svg ' + NS + b' width="50%" height="25%" viewBox="0 0 4 3"><rect width="2" '
               b'height="1" fill="blue"/></svg>',
    # no size at all: the viewBox size, or 100 % of the parent box
    'nosize': b'<svg ' + NS + b' viewBox="0 0 40 30"><circle cx="20" cy="15" r="9" '
              b'fill="red"/></svg>',
    # physical units: 10 mm = 37.8 px at 96 dpi
    'mm': b'<svg ' + NS + b' width="10mm" height="5mm" viewBox="0 0 10 5"><rect x="1" y="1" '
          b'width="4" height="3" fill="blue"/></svg>',
    # an aspect ratio to keep or not
    'stretch': b'<svg ' + NS + b' width="40" height="20" viewBox="0 0 40 20" '
               b'preserveAspectRatio="none"><rect x="10" y="5" width="20" height="10" '
               b'fill="blue"/></svg>',
}

OPTIONS = [
    {}, {'scale': 2.5}, {'scale': 0.333}, {'output_width': 100}, {'output_height': 45},
    {'output_width': 100, 'output_height': 30}, {'output_width': 100, 'scale': 3},
    {'dpi': 300}, {'dpi': 50}, {'parent_width': 200, 'parent_height': 100},
    {'parent_width': 64}, {'background_color': 'red'},
    {'background_color': 'rgba(0, 128, 0, 0.5)', 'scale': 1.5},
]


def decode(png):
    im = Image.open(io.BytesIO(png))
    assert im.format == 'PNG'
    return np.asarray(im.convert('RGBA'))


def ids(o):
    return ','.join('%s=%s' % kv for kv in o.items()) or 'defaults'


@pytest.mark.parametrize('opts', OPTIONS, ids=ids)
@pytest.mark.parametrize('name', sorted(DOCS))
def test_same_size_and_pixels_as_cairosvg(name, opts):
    want = decode(cairosvg.svg2png(DOCS[name], **opts))
    got = decode(raster.svg2png(DOCS[name], **opts))
    assert got.shape == want.shape
    cmp = compare_images(want, got)
    assert cmp.passed, cmp.reason


def test_sizes_named_for_the_record():
    """The analytic sizes behind the comparison: 37.8 x 18.9 px at 96 dpi
    (10 mm = 10 / 25.4 in), 118.1 x 59.1 at 300 dpi; half to even."""
    size = lambda doc, **o: decode(raster.svg2png(doc, **o)).shape[1::-1]
    assert size(DOCS['mm']) == (38, 19)
    assert size(DOCS['mm'], dpi=300) == (118, 59)
    assert size(DOCS['fractional']) == (10, 8)
    assert size(DOCS['percent'], parent_width=200, parent_height=100) == (100, 25)
    assert size(DOCS['nosize'], parent_width=64) == (64, 30)
    assert size(DOCS['plain'], output_width=100, scale=3) == (100, 75)     # scale ignored


def test_both_output_sizes_fit_by_preserve_aspect_ratio():
    """40 x 30 into 100 x 30: uniform scale 1, centred (x from 30), as
    CairoSVG does; with preserveAspectRatio="none" the content stretches."""
    a = decode(raster.svg2png(DOCS['plain'], output_width=100, output_height=30))
    cols = np.flatnonzero(a[10, :, 3] > 128)
    assert (cols.min(), cols.max()) == (35, 54)
    b = decode(raster.svg2png(DOCS['stretch'], output_width=80, output_height=20))
    cols = np.flatnonzero(b[10, :, 3] > 128)
    assert (cols.min(), cols.max()) == (20, 59)


def test_background_covers_the_unrounded_box():
    """10.5 x 7.5 rounds to 10 x 8: the background covers rows 0-6 and half
    of row 7, as CairoSVG paints it."""
    a = decode(raster.svg2png(DOCS['fractional'], background_color='red'))
    assert (a[:7, :, 3] == 255).all() and (abs(a[7, :, 3].astype(int) - 128) <= 1).all()
    b = decode(cairosvg.svg2png(DOCS['fractional'], background_color='red'))
    assert np.array_equal(a[..., 3], b[..., 3])


def test_inputs_bytes_str_file_obj_path_and_file_url(tmp_path):
    doc = DOCS['viewbox']
    p = tmp_path / 'd.svg'
    p.write_bytes(doc)
    want = raster.svg2png(doc)
    assert raster.svg2png(doc.decode()) == want
    assert raster.svg2png(file_obj=io.BytesIO(doc)) == want
    with open(p, 'rb') as f:
        assert raster.svg2png(file_obj=f) == want
    assert raster.svg2png(url=str(p)) == want
    assert raster.svg2png(url=p) == want
    assert raster.svg2png(url=p.as_uri()) == want
    assert decode(want).shape == decode(cairosvg.svg2png(url=str(p))).shape
    # the order CairoSVG takes them in: bytestring, then file_obj, then url
    assert raster.svg2png(doc, file_obj=io.BytesIO(DOCS['plain'])) == want
    assert raster.svg2png(file_obj=io.BytesIO(doc), url=str(tmp_path / 'absent.svg')) == want


def test_write_to_a_path_and_a_file_object(tmp_path):
    want = raster.svg2png(DOCS['plain'])
    out = tmp_path / 'o.png'
    assert raster.svg2png(DOCS['plain'], write_to=str(out)) is None
    assert out.read_bytes() == want
    out2 = tmp_path / 'o2.png'
    assert raster.svg2png(DOCS['plain'], write_to=out2) is None
    assert out2.read_bytes() == want
    buf = io.BytesIO()
    assert raster.svg2png(DOCS['plain'], write_to=buf) is None
    assert buf.getvalue() == want
    # CairoSVG behaves the same way: None returned, the PNG in the target
    cbuf = io.BytesIO()
    assert cairosvg.svg2png(DOCS['plain'], write_to=cbuf) is None
    assert decode(cbuf.getvalue()).shape == decode(want).shape
    with pytest.raises(RasterIOError):
        raster.svg2png(DOCS['plain'], write_to=str(tmp_path / 'no' / 'such' / 'dir.png'))


def image_doc(tmp_path):
    Image.new('RGBA', (4, 4), (0, 255, 0, 255)).save(tmp_path / 'green.png')
    p = tmp_path / 'img.svg'
    p.write_bytes(b'<svg ' + NS + b' width="8" height="8"><image href="green.png" '
                  b'width="8" height="8"/></svg>')
    return p


def test_unsafe_allows_image_files_otherwise_none(tmp_path, recwarn):
    """CairoSVG reads no external file unless unsafe (both draw nothing for
    the image then); with unsafe the image file is drawn."""
    p = image_doc(tmp_path)
    safe = decode(raster.svg2png(url=str(p)))
    assert not safe[..., 3].any()
    assert not decode(cairosvg.svg2png(url=str(p)))[..., 3].any()
    unsafe = decode(raster.svg2png(url=str(p), unsafe=True))
    assert unsafe[4, 4].tolist() == [0, 255, 0, 255]
    # CairoSVG fades the image's outer pixel row (its filter samples past the
    # edge); the inside is the same
    theirs = decode(cairosvg.svg2png(url=str(p), unsafe=True))
    assert np.array_equal(theirs[2:-2, 2:-2], unsafe[2:-2, 2:-2])


def test_data_uri_images_need_no_unsafe():
    import base64
    buf = io.BytesIO()
    Image.new('RGBA', (2, 2), (255, 0, 0, 255)).save(buf, 'PNG')
    href = b'data:image/png;base64,' + base64.b64encode(buf.getvalue())
    doc = b'<svg ' + NS + b' width="6" height="6"><image href="' + href + \
          b'" width="6" height="6"/></svg>'
    assert decode(raster.svg2png(doc))[3, 3].tolist() == [255, 0, 0, 255]


@pytest.mark.parametrize('url', ['https://example.com/a.svg', 'http://localhost/a.svg',
                                 'ftp://example.com/a.svg'])
def test_network_urls_are_refused(url):
    with pytest.raises(RasterIOError, match='not fetched'):
        raster.svg2png(url=url)


@pytest.mark.parametrize('kw, exc, msg', [
    ({}, SVGError, 'no input'),
    ({'bytestring': 12}, SVGError, 'bytes or str'),
    ({'bytestring': DOCS['plain'], 'scale': 0}, CanvasError, 'scale must be positive'),
    ({'bytestring': DOCS['plain'], 'scale': 'big'}, CanvasError, 'scale must be a number'),
    ({'bytestring': DOCS['plain'], 'scale': 0.001}, CanvasError, 'rounds to zero'),
    ({'bytestring': DOCS['plain'], 'output_width': -5}, CanvasError, 'output_width'),
    ({'bytestring': DOCS['percent'], 'parent_width': float('nan')}, CanvasError, 'parent_width'),
    ({'bytestring': DOCS['plain'], 'dpi': 0}, SVGError, 'dpi'),
    ({'bytestring': DOCS['plain'], 'background_color': 'nope'}, SVGError, 'background'),
    ({'bytestring': b'<html/>'}, SVGError, 'not an SVG'),
    ({'url': '/nonexistent/a.svg'}, RasterIOError, 'No such file'),
])
def test_errors_are_raster_errors(kw, exc, msg):
    with pytest.raises(exc, match=msg) as ei:
        raster.svg2png(**kw)
    assert isinstance(ei.value, RasterError)


def test_exported_lazily_from_raster():
    import subprocess
    import sys
    code = ('import sys, raster; assert "raster.compat" not in sys.modules; '
            'f = raster.svg2png; assert "raster.compat" in sys.modules; '
            'assert f is __import__("raster.compat").compat.svg2png')
    subprocess.run([sys.executable, '-c', code], check=True, timeout=60)
