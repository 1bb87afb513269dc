"""The streaming PNG writer (PNGWriter, compress_strip): decoded images
equal what was written whatever the strip cuts, strips compressed apart
(in any order, as worker processes do) give the same bytes as the writer
compressing them itself, the Adler-32 join, and its errors."""

import io
import zlib

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from PIL import Image

from raster.errors import CanvasError
from raster.pixels import png as P
from raster.pixels.png import PNGWriter, compress_strip, encode_png


def picture(rng, h, w):
    """A rendered-looking image: flat areas, a gradient, noise, alpha."""
    img = np.zeros((h, w, 4), np.uint8)
    img[..., 0] = np.linspace(0, 255, w, dtype=np.uint8)[None, :]
    img[h // 3:, :, 1] = 200
    img[..., 2] = rng.integers(0, 256, (h, w), dtype=np.uint8) // 64 * 64
    img[..., 3] = np.where(rng.random((h, w)) < 0.8, 255, rng.integers(0, 256, (h, w)))
    return img


def decode(data):
    return np.asarray(Image.open(io.BytesIO(data)).convert('RGBA'))


def write(img, cuts, level=1, dpi=None):
    out = io.BytesIO()
    with PNGWriter(out, img.shape[1], img.shape[0], level, dpi) as w:
        for a, b in zip([0] + cuts, cuts + [len(img)]):
            w.write(img[a:b])
    return out.getvalue()


@settings(max_examples=25, deadline=None)
@given(h=st.integers(1, 40), w=st.integers(1, 30), seed=st.integers(0, 2 ** 16),
       level=st.sampled_from([0, 1, 6, 9]), data=st.data())
def test_any_strip_cuts_decode_to_the_image(h, w, seed, level, data):
    rng = np.random.default_rng(seed)
    img = picture(rng, h, w)
    cuts = sorted(set(data.draw(st.lists(st.integers(1, max(1, h - 1)), max_size=5))))
    cuts = [c for c in cuts if 0 < c < h]
    assert np.array_equal(decode(write(img, cuts, level)), img)


def test_strips_compressed_apart_give_the_same_bytes():
    rng = np.random.default_rng(7)
    img = picture(rng, 300, 123)
    spans = [(0, 50), (50, 51), (51, 170), (170, 300)]
    pieces = {s: compress_strip(img[s[0]:s[1]], 1, first=s[0] == 0) for s in reversed(spans)}
    out = io.BytesIO()
    w = PNGWriter(out, 123, 300, 1)
    for s in spans:
        w.write_compressed(pieces[s])
    w.close()
    assert out.getvalue() == write(img, [50, 51, 170])
    assert np.array_equal(decode(out.getvalue()), img)


def test_the_first_row_of_a_later_strip_never_uses_up():
    # rows equal to the row above are cheapest with Up; a strip compressed
    # apart cannot know that row, so its first row uses None or Sub
    img = np.full((6, 4, 4), 77, np.uint8)
    a = compress_strip(img[3:], 9, first=False)
    rows = zlib.decompressobj(-15).decompress(a.data)
    kinds = [rows[i * 17] for i in range(3)]
    assert kinds[0] != 2 and kinds[1:] == [2, 2]


@settings(max_examples=50, deadline=None)
@given(st.binary(max_size=3000), st.binary(max_size=3000))
def test_adler_join_is_the_checksum_of_the_joined_bytes(a, b):
    assert P._adler_join(zlib.adler32(a), zlib.adler32(b), len(b)) == zlib.adler32(a + b)


def test_big_strips_join_checksums_beyond_the_modulus():
    a = bytes(range(256)) * 700                # 179200 bytes: s1 and s2 wrap
    b = bytes(reversed(range(256))) * 900
    assert P._adler_join(zlib.adler32(a), zlib.adler32(b), len(b)) == zlib.adler32(a + b)


def test_resolution_and_level_are_written():
    img = picture(np.random.default_rng(1), 20, 10)
    data = write(img, [7], level=9, dpi=300)
    im = Image.open(io.BytesIO(data))
    assert round(im.info['dpi'][0]) == 300
    assert np.array_equal(np.asarray(im), img)
    # the same picture as encode_png's (other filters on strip starts)
    assert np.array_equal(decode(encode_png(img)), decode(data))


def test_errors():
    img = np.zeros((4, 3, 4), np.uint8)
    out = io.BytesIO()
    w = PNGWriter(out, 3, 4)
    with pytest.raises(CanvasError):
        w.write(np.zeros((2, 5, 4), np.uint8))          # another width
    w.write(img[:3])
    with pytest.raises(CanvasError):
        w.close()                                       # one row short
    with pytest.raises(CanvasError):
        w.write(img)                                    # too many rows
    with pytest.raises(CanvasError):
        PNGWriter(io.BytesIO(), 0, 3)
    with pytest.raises(CanvasError):
        PNGWriter(io.BytesIO(), 3, 3, level=11)
    with pytest.raises(CanvasError):
        compress_strip(np.zeros((2, 2, 3), np.uint8))
    other = compress_strip(np.zeros((1, 5, 4), np.uint8), first=True)
    with pytest.raises(CanvasError):
        PNGWriter(io.BytesIO(), 3, 1).write_compressed(other)


def test_a_large_image_is_written_in_idat_chunks_of_bounded_size():
    rng = np.random.default_rng(3)
    img = rng.integers(0, 256, (600, 700, 4), dtype=np.uint8)      # incompressible
    data = write(img, [200, 400])
    pos, sizes = 8, []
    while pos < len(data):
        n = int.from_bytes(data[pos:pos + 4], 'big')
        if data[pos + 4:pos + 8] == b'IDAT':
            sizes.append(n)
        pos += 12 + n
    assert len(sizes) > 1 and max(sizes) <= P._IDAT_MAX
    assert np.array_equal(decode(data), img)
