"""The 8-bit canvas (``Canvas(..., dtype=np.uint8)``): every operation is
the float32 canvas's, rounded to the nearest of 256 levels; so each one
lands within half a level of the exact result, and a sequence of them
within one level per operation.  The strips of rows an encoder reads give
the whole image's bytes."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.errors import CanvasError
from raster.pixels.canvas import Canvas
from raster.pixels.encode import encode, encode_canvas
from raster.pixels.png import encode_png, encode_png_strips
from raster.pixels.scan import Mask
from raster.pixels.views import ClipRect
from raster.pixels import views

BG = (0.1, 0.6, 0.9, 0.8)


def levels(c):
    """Premultiplied levels of a canvas as exact floats (0..255)."""
    return c.data.astype(np.float64) if c.dtype == np.uint8 else c.data * 255.0


def pair(w=40, h=30, bg=BG):
    return Canvas(w, h, bg), Canvas(w, h, bg, dtype=np.uint8)


def random_mask(rng, h, w, x0=0, y0=0, full=0.4, empty=0.2):
    k = rng.random((h, w)).astype(np.float32)
    k[k > 1 - full] = 1.0
    k[k < empty] = 0.0
    return Mask(k, x0, y0)


def test_storage_and_background_levels():
    c = Canvas(3, 2, (1.0, 0.5, 0.0, 0.5), dtype=np.uint8)
    assert c.data.dtype == np.uint8 and c.nbytes == 3 * 2 * 4 and c.dtype == np.uint8
    # premultiplied (0.5, 0.25, 0, 0.5) * 255 = (127.5, 63.75, 0, 127.5), rounded half up
    assert c.data[1, 2].tolist() == [128, 64, 0, 128]
    assert Canvas(3, 2).nbytes == 4 * Canvas(3, 2, dtype='uint8').nbytes
    with pytest.raises(CanvasError):
        Canvas(3, 2, dtype=np.float64)
    with pytest.raises(CanvasError):
        Canvas(3, 2, dtype='not a type')


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2 ** 32 - 1), opacity=st.sampled_from([1.0, 0.7, 0.2]),
       color=st.tuples(*[st.floats(0, 1)] * 4), small=st.booleans())
def test_one_fill_is_the_float_fill_rounded(seed, opacity, color, small):
    """Each fill path (small window, sparse, opaque, blocked) of an 8-bit
    canvas stores the float result rounded: within half a level (plus the
    float32 error of the sum)."""
    rng = np.random.default_rng(seed)
    f, e = pair()
    # start both from the same levels
    f.data[...] = e.data / np.float32(255)
    h, w = (6, 5) if small else (25, 33)
    m = random_mask(rng, h, w, int(rng.integers(-3, 10)), int(rng.integers(-3, 8)),
                    full=float(rng.random()), empty=float(rng.random()) * 0.9)
    f.fill(m, color, opacity)
    e.fill(m, color, opacity)
    assert np.abs(levels(f) - levels(e)).max() <= 0.5 + 1e-3


def test_many_fills_stay_within_a_level_per_fill():
    rng = np.random.default_rng(5)
    f, e = pair(60, 50)
    n = 12
    for i in range(n):
        m = random_mask(rng, 30, 40, int(rng.integers(0, 20)), int(rng.integers(0, 20)))
        col = tuple(rng.random(4))
        f.fill(m, col, 0.8)
        e.fill(m, col, 0.8)
    d = np.abs(levels(f) - levels(e))
    assert d.max() <= n * 0.5 + 1e-3
    assert d.mean() < 0.5


@pytest.mark.parametrize('opacity', [1.0, 0.35])
@pytest.mark.parametrize('src_levels', [False, True])
def test_composite_is_the_float_composite_rounded(opacity, src_levels):
    rng = np.random.default_rng(3)
    f, e = pair()
    f.data[...] = e.data / np.float32(255)
    a = rng.random((20, 25, 1)).astype(np.float32)
    layer = (rng.random((20, 25, 4)).astype(np.float32) * a)
    layer[..., 3:] = a
    if src_levels:             # an 8-bit layer: uint8 levels
        layer8 = np.floor(layer * 255 + 0.5).astype(np.uint8)
        f.composite(layer8 / np.float32(255), 7, 4, opacity)
        e.composite(layer8, 7, 4, opacity)
    else:
        f.composite(layer, 7, 4, opacity)
        e.composite(layer, 7, 4, opacity)
    assert np.abs(levels(f) - levels(e)).max() <= 0.5 + 1e-3


def test_store_read_round_trip_and_scale():
    c = Canvas(4, 3, dtype=np.uint8)
    px = np.linspace(0, 1, 4 * 3 * 4, dtype=np.float32).reshape(3, 4, 4)
    c.store(0, 3, 0, 4, px)
    assert np.abs(c.read(0, 3, 0, 4) - px).max() <= 0.5 / 255 + 1e-7
    assert c.read(0, 3, 0, 4).dtype == np.float32
    # read gives a copy
    r = c.read(0, 1, 0, 1)
    r[...] = 0
    assert c.data[0, 0].any() or px[0, 0].max() < 0.5 / 255
    before = c.data.astype(np.float64)
    f = np.full((3, 4), 0.5, np.float32)
    c.scale(f)
    assert np.abs(c.data - before * 0.5).max() <= 0.5 + 1e-6
    with pytest.raises(CanvasError):
        c.scale(np.ones((4, 3), np.float32))


def test_combine_weights_channels():
    c = Canvas(2, 2, (0.2, 0.4, 0.6, 1.0), dtype=np.uint8)
    lum = c.combine((0.2125, 0.7154, 0.0721, 0.0))
    r, g, b, _ = c.data[0, 0] / 255.0
    assert lum.shape == (2, 2) and lum.dtype == np.float32
    assert lum[1, 1] == pytest.approx(0.2125 * r + 0.7154 * g + 0.0721 * b, rel=1e-6)
    f = Canvas(2, 2, (0.2, 0.4, 0.6, 0.5))
    assert f.combine((0, 0, 0, 1)).tolist() == [[0.5, 0.5], [0.5, 0.5]]


def test_to_rgba8_demultiplies_levels():
    c = Canvas(4, 1, dtype=np.uint8)
    c.data[0] = [[64, 0, 0, 128], [10, 20, 30, 255], [5, 5, 5, 0], [1, 0, 0, 3]]
    out = c.to_rgba8()
    # 64 * 255 / 128 = 127.5 -> 128; opaque unchanged; alpha 0 -> all 0;
    # 1 * 255 / 3 = 85
    assert out[0].tolist() == [[128, 0, 0, 128], [10, 20, 30, 255], [0, 0, 0, 0], [85, 0, 0, 3]]
    assert c.to_rgba8(premultiplied=True)[0, 3].tolist() == [1, 0, 0, 3]
    # a colour above its alpha (never made by the operations) is clamped
    c.data[0, 0] = [200, 0, 0, 100]
    assert c.to_rgba8()[0, 0, 0] == 255


def test_demultiplied_in_blocks_is_the_same(monkeypatch):
    # an 8-bit canvas is demultiplied in blocks of pixels: tiny blocks
    # (not dividing the pixel count) give the same bytes, and every pixel
    # is round(c * 255 / a) clamped to 255, 0 where alpha is 0
    import raster.pixels.canvas as canvas
    rng = np.random.default_rng(4)
    c = Canvas(37, 29, dtype=np.uint8)
    a = rng.integers(0, 256, (29, 37, 1))
    a[rng.random((29, 37)) < 0.3] = 255
    a[rng.random((29, 37)) < 0.1] = 0
    c.data[:] = np.concatenate([rng.integers(0, 256, (29, 37, 3)) * a // 255, a], 2)
    whole = c.to_rgba8()
    monkeypatch.setattr(canvas, '_DEMULTIPLY_BLOCK', 100)
    assert np.array_equal(c.to_rgba8(), whole)
    d = c.data.astype(np.float64)
    with np.errstate(all='ignore'):
        want = np.minimum(np.floor(d[..., :3] * 255 / d[..., 3:] + 0.5), 255)
    want = np.where(d[..., 3:] == 0, 0, np.where(d[..., 3:] == 255, d[..., :3], want))
    assert np.array_equal(whole[..., :3], want)
    assert np.array_equal(whole[..., 3], c.data[..., 3])


@pytest.mark.parametrize('dtype', [np.float32, np.uint8])
def test_rows_are_slices_of_the_image(dtype):
    rng = np.random.default_rng(9)
    c = Canvas(23, 17, BG, dtype=dtype)
    for i in range(4):
        c.fill(random_mask(rng, 10, 12, i * 3, i * 2), tuple(rng.random(4)), 0.9)
    full = c.to_rgba8()
    for y0, y1 in [(0, 17), (0, 1), (5, 9), (16, 17), (10, 30)]:
        assert np.array_equal(c.rgba8_rows(y0, y1), full[y0:y1])
        assert np.array_equal(c.rgba8_rows(y0, y1, True), c.to_rgba8(True)[y0:y1])


def test_png_strips_are_the_whole_image_bytes():
    rng = np.random.default_rng(2)
    img = rng.integers(0, 256, (37, 29, 4), dtype=np.uint8)
    img[10:20] = 7                       # runs, so the compressor has something to do
    whole = encode_png(img, 1, 96)
    for cuts in ([37], [1, 36], [5, 5, 5, 22], [36, 1]):
        ys = np.cumsum([0] + cuts)
        strips = [img[a:b] for a, b in zip(ys[:-1], ys[1:])]
        assert encode_png_strips(29, 37, strips, 1, 96) == whole
    with pytest.raises(CanvasError):
        encode_png_strips(29, 37, [img[:10]])               # too few rows
    with pytest.raises(CanvasError):
        encode_png_strips(29, 36, [img])                    # too many rows
    with pytest.raises(CanvasError):
        encode_png_strips(28, 37, [img])                    # wrong width


@pytest.mark.parametrize('dtype', [np.float32, np.uint8])
@pytest.mark.parametrize('fmt', ['png', 'webp', 'bmp'])
def test_encode_canvas_is_encode_of_its_image(monkeypatch, dtype, fmt):
    import raster.pixels.encode as enc
    monkeypatch.setattr(enc, 'STRIP_PIXELS', 50)         # several strips
    rng = np.random.default_rng(4)
    c = Canvas(31, 19, BG, dtype=dtype)
    c.fill(random_mask(rng, 15, 20, 3, 2), (1, 0, 0.5, 0.7))
    assert encode_canvas(c, fmt, dpi=150) == encode(c.to_rgba8(), fmt, dpi=150)


def test_clip_rect_composites_an_8bit_layer(monkeypatch):
    """Through a ClipRect, an 8-bit layer's levels count as levels (divided
    by 255), in strips of rows."""
    monkeypatch.setattr(views, 'STRIP_PIXELS', 16)
    rng = np.random.default_rng(8)
    a = rng.random((12, 10, 1)).astype(np.float32)
    layer = rng.random((12, 10, 4)).astype(np.float32) * a
    layer[..., 3:] = a
    layer8 = np.floor(layer * 255 + 0.5).astype(np.uint8)
    box = (2.5, 1.25, 9.5, 11.0)
    f, e = pair(14, 13)
    f.data[...] = e.data / np.float32(255)
    ClipRect(f, box).composite(layer8 / np.float32(255), 1, 0, 0.9)
    ClipRect(e, box).composite(layer8, 1, 0, 0.9)
    assert np.abs(levels(f) - levels(e)).max() <= 0.5 + 1e-3
    # and the same through fill (coverage times the rectangle's)
    m = random_mask(rng, 12, 10, 1, 0)
    ClipRect(f, box).fill(m, (0, 1, 0, 1))
    ClipRect(e, box).fill(m, (0, 1, 0, 1))
    assert np.abs(levels(f) - levels(e)).max() <= 1.0 + 1e-3
