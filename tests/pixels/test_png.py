"""raster.pixels.png: PNG files that Pillow reads back bit for bit."""

import io

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from PIL import Image

from raster.errors import CanvasError
from raster.pixels.png import _filtered, encode_png, write_png


def decode(data):
    im = Image.open(io.BytesIO(data))
    assert im.mode == 'RGBA'
    return np.asarray(im)


@settings(max_examples=40, deadline=None)
@given(st.integers(1, 40), st.integers(1, 40), st.integers(0, 2 ** 32 - 1),
       st.sampled_from([0, 1, 3, 6, 9]))
def test_round_trip(h, w, seed, level):
    rng = np.random.default_rng(seed)
    kind = seed % 3
    if kind == 0:                       # noise
        img = rng.integers(0, 256, (h, w, 4), dtype=np.uint8)
    elif kind == 1:                     # flat areas with edges
        img = np.zeros((h, w, 4), np.uint8)
        img[: h // 2] = rng.integers(0, 256, 4)
        img[:, w // 3:] = rng.integers(0, 256, 4)
    else:                               # smooth ramps
        x = np.linspace(0, 255, w)[None, :, None]
        y = np.linspace(0, 255, h)[:, None, None]
        img = ((x + y + np.arange(4) * 40) % 256).astype(np.uint8)
    assert np.array_equal(decode(encode_png(img, level)), img)


def test_filters_choose_per_row_and_undo_exactly():
    rng = np.random.default_rng(1)
    raw = np.repeat(rng.integers(0, 256, (1, 40), dtype=np.uint8), 6, axis=0)   # Up wins
    raw[3] = np.tile(rng.integers(0, 256, 4, dtype=np.uint8), 10)              # Sub wins
    raw[0] = 0                                                                  # None wins
    f = _filtered(raw)
    assert f[0, 0] == 0 and f[2, 0] == 2 and f[3, 0] == 1
    assert f[5, 0] == 2 and not f[5, 1:].any()  # Up of a repeated row is zero


def test_large_image_spans_several_idat_chunks(tmp_path):
    rng = np.random.default_rng(2)
    img = rng.integers(0, 256, (700, 600, 4), dtype=np.uint8)     # ~1.7 MB compressed
    data = encode_png(img)
    assert data.count(b'IDAT') >= 2
    p = tmp_path / 'a.png'
    write_png(p, img)
    assert np.array_equal(np.asarray(Image.open(p)), img)
    buf = io.BytesIO()
    write_png(buf, img, 3)
    assert np.array_equal(decode(buf.getvalue()), img)


def test_rendered_picture_is_compact():
    """A flat picture with anti-aliased edges compresses to a small fraction
    of its raw size."""
    yy, xx = np.mgrid[:300, :300]
    d = np.hypot(xx - 150, yy - 150)
    a = np.clip(100.5 - d, 0, 1)
    img = np.zeros((300, 300, 4), np.uint8)
    img[..., 0] = 200
    img[..., 3] = np.round(a * 255).astype(np.uint8)
    assert len(encode_png(img)) < 300 * 300 * 4 / 50


@pytest.mark.parametrize('bad', [np.zeros((2, 2, 3), np.uint8), np.zeros((2, 2, 4), np.float32),
                                 np.zeros((0, 2, 4), np.uint8), np.zeros((4, 4), np.uint8)])
def test_bad_arrays(bad):
    with pytest.raises(CanvasError):
        encode_png(bad)


def test_bad_level():
    with pytest.raises(CanvasError):
        encode_png(np.zeros((1, 1, 4), np.uint8), 10)
    with pytest.raises(CanvasError):
        encode_png(np.zeros((1, 1, 4), np.uint8), 'x')
