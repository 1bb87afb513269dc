"""raster.pixels.encode and the PNG pHYs chunk: every format decodes (by
Pillow) to the pixels given -- exactly for the lossless ones, within a few
levels for JPEG -- JPEG and BMP flattened on the matte, resolutions
recorded, options a format does not take refused."""

import io
import struct
import zlib

import numpy as np
import pytest
from PIL import Image

from raster.errors import CanvasError, FormatError, RasterError
from raster.pixels.encode import (EXTENSIONS, FORMATS, encode, flatten, format_name,
                                  format_of_path)
from raster.pixels.png import encode_png, phys_chunk


def picture(seed=3, h=23, w=31):
    """Random straight-alpha RGBA with fully transparent, opaque and
    partial pixels; RGB zeroed where alpha is 0 (as the canvas gives)."""
    rng = np.random.default_rng(seed)
    a = rng.integers(0, 256, (h, w, 4), dtype=np.uint8)
    a[rng.random((h, w)) < 0.2, 3] = 0
    a[rng.random((h, w)) < 0.3, 3] = 255
    a[a[..., 3] == 0, :3] = 0
    return a


def decode(data):
    im = Image.open(io.BytesIO(data))
    im.load()
    return im


def chunks(png):
    """[(type, payload)] of a PNG stream, CRCs checked."""
    out, i = [], 8
    while i < len(png):
        n, = struct.unpack('>I', png[i:i + 4])
        kind, payload = png[i + 4:i + 8], png[i + 8:i + 8 + n]
        crc, = struct.unpack('>I', png[i + 8 + n:i + 12 + n])
        assert crc == zlib.crc32(payload, zlib.crc32(kind)) & 0xFFFFFFFF
        out.append((kind, payload))
        i += 12 + n
    return out


# -- names and extensions ----------------------------------------------------------------

def test_format_names_and_extensions():
    assert [format_name(n) for n in ('PNG', 'jpg', 'JPEG', 'tif', 'Tiff', 'webp', 'bmp')] == \
        ['png', 'jpeg', 'jpeg', 'tiff', 'tiff', 'webp', 'bmp']
    assert set(EXTENSIONS.values()) == set(FORMATS)
    assert format_of_path('a/b.c/out.TIFF') == 'tiff'
    assert format_of_path('out.jpe') == 'jpeg'
    assert format_of_path('a.dir/out') is None and format_of_path('-') is None
    for bad in ('out.pdf', 'out.gif', 'out.svg', 'x.png.tmp'):
        with pytest.raises(FormatError, match='cannot write'):
            format_of_path(bad)
    with pytest.raises(FormatError, match='unknown output format'):
        format_name('pdf')
    assert issubclass(FormatError, RasterError)


# -- flatten -----------------------------------------------------------------------------

def test_flatten_is_the_over_operator_rounded():
    a = picture()
    m = np.array([0.2, 0.6, 1.0])
    got = flatten(a, m).astype(np.float64)
    al = a[..., 3:4] / 255.0
    want = a[..., :3] * al + np.round(m * 255) * (1 - al)
    assert np.abs(got - want).max() <= 0.5 + 1e-9
    assert np.array_equal(flatten(a)[a[..., 3] == 0], np.full(((a[..., 3] == 0).sum(), 3), 255))
    opaque = a[..., 3] == 255
    assert np.array_equal(flatten(a)[opaque], a[opaque][:, :3])


@pytest.mark.parametrize('matte', [(1, 1), (0, 0, 2), 'white', None])
def test_flatten_refuses_a_bad_matte(matte):
    with pytest.raises(FormatError, match='matte'):
        flatten(picture(), matte)


# -- each format -------------------------------------------------------------------------

@pytest.mark.parametrize('fmt', ['png', 'webp', 'tiff'])
def test_lossless_formats_with_alpha_round_trip_exactly(fmt):
    a = picture()
    im = decode(encode(a, fmt))
    assert im.format == {'png': 'PNG', 'webp': 'WEBP', 'tiff': 'TIFF'}[fmt]
    assert im.mode == 'RGBA' and im.size == (a.shape[1], a.shape[0])
    assert np.array_equal(np.asarray(im), a)


def test_bmp_is_flattened_exactly():
    a = picture()
    im = decode(encode(a, 'bmp', matte=(0, 0.5, 1)))
    assert im.format == 'BMP' and im.mode == 'RGB'
    assert np.array_equal(np.asarray(im), flatten(a, (0, 0.5, 1)))


def test_jpeg_is_flattened_on_white_within_a_few_levels():
    """A smooth picture (JPEG's own error is small on it): transparent areas
    come out white, half-transparent blue as (127, 127, 255)."""
    h, w = 32, 48
    a = np.zeros((h, w, 4), np.uint8)
    a[:, :16] = (0, 0, 255, 128)
    a[:, 16:32] = (200, 60, 20, 255)
    im = decode(encode(a, 'jpeg'))
    assert im.format == 'JPEG' and im.mode == 'RGB'
    got = np.asarray(im).astype(int)
    assert np.abs(got[4:-4, 4:12] - (127, 127, 255)).max() <= 3
    assert np.abs(got[4:-4, 20:28] - (200, 60, 20)).max() <= 3
    assert np.abs(got[4:-4, 36:44] - 255).max() <= 3
    assert np.abs(got.astype(float) - flatten(a)).mean() < 1.5


def test_jpeg_quality_changes_size_and_error():
    a = picture(h=64, w=64)
    lo, hi = encode(a, 'jpeg', quality=10), encode(a, 'jpeg', quality=100)
    err = lambda d: np.abs(np.asarray(decode(d)).astype(int) - flatten(a)).mean()
    assert len(lo) < len(hi) and err(lo) > err(hi)
    assert encode(a, 'jpeg') == encode(a, 'jpeg', quality=90)


def test_webp_quality_makes_it_lossy():
    a = picture(h=64, w=64)
    lossy = decode(encode(a, 'webp', quality=50))
    assert not np.array_equal(np.asarray(lossy), a)
    assert len(encode(a, 'webp', quality=50)) < len(encode(a, 'webp'))


@pytest.mark.parametrize('fmt', ['png', 'jpeg', 'tiff', 'bmp'])
def test_resolution_is_recorded(fmt):
    im = decode(encode(picture(), fmt, dpi=(300, 150)))
    x, y = im.info['dpi']
    # PNG and BMP store whole pixels per metre, JPEG whole dots per inch
    assert abs(x - 300) < 0.02 and abs(y - 150) < 0.02
    plain = decode(encode(picture(), fmt)).info.get('dpi')
    if fmt == 'tiff':               # a TIFF always has one: the CSS pixel's
        assert plain == (96, 96)
    elif fmt == 'png':              # no pHYs chunk
        assert plain is None


def test_webp_has_no_resolution_and_ignores_it():
    assert encode(picture(), 'webp', dpi=300) == encode(picture(), 'webp')


def test_png_compress_level():
    a = picture(h=80, w=80)
    stored, best = encode(a, 'png', compress_level=0), encode(a, 'png', compress_level=9)
    assert len(stored) > len(best)
    assert np.array_equal(np.asarray(decode(stored)), a)
    assert encode(a) == encode_png(a)


@pytest.mark.parametrize('fmt, kw, msg', [
    ('png', {'quality': 80}, 'quality applies to JPEG and WebP'),
    ('tiff', {'quality': 80}, 'quality applies'),
    ('jpeg', {'compress_level': 3}, 'compression level applies to PNG'),
    ('jpeg', {'quality': 0}, 'quality must be a whole number 1-100'),
    ('jpeg', {'quality': 101}, 'quality must be'),
    ('jpeg', {'quality': 50.5}, 'quality must be'),
    ('png', {'compress_level': 10}, 'compression level must be'),
    ('png', {'dpi': 0}, 'dpi must be a positive number'),
    ('png', {'dpi': (1, 2, 3)}, 'dpi must be'),
    ('tiff', {'dpi': 'high'}, 'dpi must be'),
    ('gif', {}, 'unknown output format'),
])
def test_bad_options_are_format_errors(fmt, kw, msg):
    with pytest.raises(FormatError, match=msg):
        encode(picture(), fmt, **kw)


@pytest.mark.parametrize('bad', [np.zeros((4, 4, 3), np.uint8), np.zeros((4, 4, 4), np.float32),
                                 np.zeros((0, 4, 4), np.uint8)])
def test_bad_images_are_refused(bad):
    with pytest.raises(FormatError, match='needs an'):
        encode(bad, 'tiff')


# -- PNG pHYs ----------------------------------------------------------------------------

def test_phys_chunk_follows_ihdr_with_pixels_per_metre():
    data = encode_png(picture(), dpi=(72, 254))
    kinds = [k for k, _ in chunks(data)]
    assert kinds[:2] == [b'IHDR', b'pHYs'] and kinds[-1] == b'IEND'
    payload = dict(chunks(data))[b'pHYs']
    # 72 dpi = 2834.6 px/m -> 2835; 254 dpi = 10000 px/m exactly; unit 1 = metre
    assert struct.unpack('>IIB', payload) == (2835, 10000, 1)
    assert b'pHYs' not in [k for k, _ in chunks(encode_png(picture()))]


@pytest.mark.parametrize('dpi', [0, -1, float('inf'), float('nan'), 1e-6, 'x', (1,), 1e12])
def test_phys_chunk_refuses_bad_resolutions(dpi):
    with pytest.raises(CanvasError, match='resolution'):
        phys_chunk(dpi)
