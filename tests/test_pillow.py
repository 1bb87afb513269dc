"""raster.pillow: the Pillow plugin.  Image.open gives the same pixels as
raster.render (paths, .svgz, file objects, content sniffing), draft() and
raster.pillow.open() choose the size, and nothing is registered until the
user asks."""

import gzip
import io
import os
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image, UnidentifiedImageError

import raster
import raster.pillow
from raster.errors import CanvasError, RasterIOError, SVGError

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BADGE = os.path.join(REPO, 'examples', 'badge.svg')
NS = b'xmlns="http://www.w3.org/2000/svg"'
INCH = b'<svg ' + NS + b' width="1in" height="0.5in"><circle cx="48" cy="24" r="20" fill="red"/></svg>'


@pytest.fixture
def registered(pillow_registry):
    """The plugin registered (with its built-in options) for one test."""
    raster.pillow.register()
    yield
    raster.pillow.register()


def pixels(im):
    return np.asarray(im)


def test_registering_is_opt_in():
    """``import raster`` (and ``import raster.pillow``) leaves Pillow alone;
    register() or ``import raster.pillow.auto`` registers the plugin."""
    code = '''
import io, raster, raster.svg, raster.pillow
from PIL import Image
Image.init()
assert 'SVG' not in Image.OPEN and '.svg' not in Image.EXTENSION
doc = b'<svg xmlns="http://www.w3.org/2000/svg" width="3" height="2"/>'
try:
    Image.open(io.BytesIO(doc))
    raise SystemExit('opened before registering')
except Image.UnidentifiedImageError:
    pass
import raster.pillow.auto
assert Image.OPEN['SVG'][0] is raster.pillow.SvgImageFile
assert Image.EXTENSION['.svg'] == Image.EXTENSION['.svgz'] == 'SVG'
assert Image.MIME['SVG'] == 'image/svg+xml'
assert Image.open(io.BytesIO(doc)).size == (3, 2)
'''
    p = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr


def test_image_open_path_gives_render_pixels(registered):
    im = Image.open(BADGE)
    assert (im.format, im.mode, im.size) == ('SVG', 'RGBA', (320, 200))
    assert im.info['dpi'] == (96.0, 96.0)
    assert np.array_equal(pixels(im), raster.render(BADGE))


def test_svgz_file_objects_and_sniffing(registered, tmp_path):
    want = raster.render(BADGE)
    data = open(BADGE, 'rb').read()
    z = tmp_path / 'b.svgz'
    z.write_bytes(gzip.compress(data))
    assert np.array_equal(pixels(Image.open(z)), want)
    assert np.array_equal(pixels(Image.open(io.BytesIO(data))), want)             # no name
    assert np.array_equal(pixels(Image.open(io.BytesIO(gzip.compress(data)))), want)
    odd = tmp_path / 'drawing.dat'                                              # no hint in the name
    odd.write_bytes(b'\xef\xbb\xbf\n  ' + data)                                 # BOM and blanks first
    assert np.array_equal(pixels(Image.open(odd)), want)
    assert Image.open(io.BytesIO(data), formats=['SVG']).format == 'SVG'
    with pytest.raises(UnidentifiedImageError):
        Image.open(io.BytesIO(data), formats=['PNG'])


def test_other_formats_and_other_xml_are_not_taken(registered, tmp_path):
    png = tmp_path / 'a.png'
    Image.new('RGBA', (3, 3), (1, 2, 3, 4)).save(png)
    assert Image.open(png).format == 'PNG'
    for data in (b'<html xmlns="http://www.w3.org/1999/xhtml"/>', b'<svg broken',
                 gzip.compress(b'not xml at all'), b'<?xml version="1.0"?><a/>'):
        with pytest.raises(UnidentifiedImageError):
            Image.open(io.BytesIO(data))


def test_svg_that_cannot_be_drawn_says_why(registered):
    with pytest.raises(SVGError, match='invalid document size'):
        Image.open(io.BytesIO(b'<svg ' + NS + b' width="0" height="10"/>'))


def test_draft_draws_at_the_requested_size(registered):
    im = Image.open(BADGE)
    mode, box = im.draft(None, (640, 100))        # at least 640 x 100, aspect 320:200
    assert mode == 'RGBA' and im.size == (640, 400) and box == (0, 0, 640, 400)
    assert im.info['dpi'] == (192.0, 192.0)
    assert np.array_equal(pixels(im), raster.render(BADGE, zoom=2))
    assert im.draft(None, (10, 10)) is None       # loaded: no effect
    small = Image.open(BADGE)
    small.draft(None, (32, 32))                   # 32 / 200 of the height would be too low
    assert small.size == (52, 32)
    assert np.array_equal(pixels(small), raster.render(BADGE, zoom=small.size[1] / 200))


def test_thumbnail_is_drawn_not_shrunk_from_the_natural_size(registered):
    """thumbnail((64, 64)) asks draft() for 128 x 128 (Pillow's reducing gap
    of 2): the badge is drawn at zoom max(128/320, 128/200) = 0.64, 205 x
    128, and that drawing is resized to 64 x 40."""
    im = Image.open(BADGE)
    im.thumbnail((64, 64))
    assert im.size == (64, 40)
    drawn = Image.fromarray(raster.render(BADGE, zoom=0.64), 'RGBA')
    assert drawn.size == (205, 128)
    want = drawn.resize((64, 40), Image.Resampling.BICUBIC, reducing_gap=2.0)
    assert np.array_equal(pixels(im), np.asarray(want))
    shrunk = Image.fromarray(raster.render(BADGE), 'RGBA')
    shrunk.thumbnail((64, 64))
    assert not np.array_equal(pixels(im), np.asarray(shrunk))


def test_open_with_size_dpi_and_background(tmp_path):
    im = raster.pillow.open(BADGE, width=640)
    assert im.size == (640, 400) and im.info['dpi'] == (192.0, 192.0)
    assert np.array_equal(pixels(im), raster.render(BADGE, width=640))
    assert raster.pillow.open(BADGE, height=100).size == (160, 100)
    assert raster.pillow.open(BADGE, width=50, height=50).size == (50, 50)
    assert raster.pillow.open(BADGE, zoom=0.5).size == (160, 100)
    inch = tmp_path / 'inch.svg'
    inch.write_bytes(INCH)
    im = raster.pillow.open(str(inch), dpi=200)
    assert im.size == (200, 100) and im.info['dpi'] == (200.0, 200.0)
    assert np.array_equal(pixels(im), raster.render(str(inch), dpi=200))
    im = raster.pillow.open(io.BytesIO(INCH), background='white')
    px = pixels(im)
    assert (px[..., 3] == 255).all() and px[0, 0].tolist() == [255, 255, 255, 255]
    assert px[24, 48].tolist() == [255, 0, 0, 255]
    im.save(tmp_path / 'out.png')
    assert np.array_equal(np.asarray(Image.open(tmp_path / 'out.png')), px)


def test_register_sets_the_defaults(registered, tmp_path):
    inch = tmp_path / 'inch.svg'
    inch.write_bytes(INCH)
    raster.pillow.register(dpi=192, background='black')
    im = Image.open(inch)
    assert im.size == (192, 96)
    assert pixels(im)[0, 0].tolist() == [0, 0, 0, 255]
    assert raster.pillow.open(str(inch), dpi=96).size == (96, 48)   # per-call wins


def test_relative_images_resolve_when_opened_by_path(registered, tmp_path):
    Image.new('RGBA', (2, 2), (0, 0, 255, 255)).save(tmp_path / 'blue.png')
    doc = tmp_path / 'img.svg'
    doc.write_bytes(b'<svg ' + NS + b' width="4" height="4"><image href="blue.png" width="4" '
                    b'height="4"/></svg>')
    assert pixels(Image.open(doc))[2, 2].tolist() == [0, 0, 255, 255]
    with open(doc, 'rb') as f:                    # a named file object: its directory
        assert pixels(Image.open(f))[2, 2].tolist() == [0, 0, 255, 255]
    with pytest.warns(raster.errors.RasterWarning):
        blank = pixels(Image.open(io.BytesIO(doc.read_bytes())))   # no directory: refused
    assert not blank[..., 3].any()


@pytest.mark.parametrize('src, exc', [
    ('/nonexistent/x.svg', RasterIOError), ('https://example.com/x.svg', RasterIOError)])
def test_open_errors(src, exc):
    with pytest.raises(exc):
        raster.pillow.open(src)


def test_open_refuses_non_svg_and_bad_options(tmp_path):
    png = tmp_path / 'a.png'
    Image.new('RGB', (2, 2)).save(png)
    with pytest.raises(SVGError, match='XML error'):
        raster.pillow.open(str(png))
    with pytest.raises(SVGError, match='dpi'):
        raster.pillow.open(BADGE, dpi=0)
    with pytest.raises(SVGError, match='background'):
        raster.pillow.open(BADGE, background='nope')
    with pytest.raises(CanvasError):
        raster.pillow.open(BADGE, width=0)
    with pytest.raises(CanvasError):
        raster.pillow.open(BADGE, zoom=2, width=10)
