"""Tests of raster.pixels.canvas: premultiplied compositing, conversion, PNG."""

import io

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from PIL import Image

from raster.pixels.canvas import DEFAULT_COMPRESS_LEVEL, Canvas
from raster.errors import CanvasError
from raster.pixels.scan import Mask, coverage


def mask(values, x0=0, y0=0):
    return Mask(np.asarray(values, np.float32).reshape(np.shape(values)), x0, y0)


def test_background_is_premultiplied():
    c = Canvas(2, 3, background=(1.0, 0.5, 0.0, 0.5))
    assert c.data.shape == (3, 2, 4) and c.data.dtype == np.float32
    assert np.allclose(c.data, [0.5, 0.25, 0.0, 0.5])
    assert np.all(Canvas(4, 4).data == 0)


def test_source_over_known_values():
    # 50% red over opaque blue: (0.5, 0, 0.5, 1)
    c = Canvas(1, 1, background=(0, 0, 1))
    c.fill(mask([[1.0]]), (1, 0, 0, 0.5))
    assert np.allclose(c.data[0, 0], [0.5, 0.0, 0.5, 1.0])
    # 50% green over 50% red on transparent: a = 0.5 + 0.5 * 0.5 = 0.75
    c = Canvas(1, 1)
    c.fill(mask([[1.0]]), (1, 0, 0, 0.5))
    c.fill(mask([[1.0]]), (0, 1, 0, 0.5))
    assert np.allclose(c.data[0, 0], [0.25, 0.5, 0.0, 0.75])
    # straight colour of the result: red 1/3, green 2/3
    assert c.to_rgba8()[0, 0].tolist() == [85, 170, 0, 191]


def test_coverage_and_opacity_multiply():
    c = Canvas(3, 1)
    c.fill(mask([[1.0, 0.5, 0.25]]), (0, 0, 1, 0.8), opacity=0.5)
    assert np.allclose(c.data[0, :, 3], [0.4, 0.2, 0.1])
    assert np.allclose(c.data[0, :, 2], [0.4, 0.2, 0.1])
    c.fill(mask([[1.0, 1.0, 1.0]]), (1, 1, 1), opacity=0.0)   # no-op
    assert np.allclose(c.data[0, :, 3], [0.4, 0.2, 0.1])


def test_opaque_fill_replaces():
    c = Canvas(2, 2, background=(0.2, 0.4, 0.6, 0.7))
    c.fill(mask(np.ones((2, 2))), (1, 0, 0))
    assert np.array_equal(c.data, np.tile(np.array([1, 0, 0, 1], np.float32), (2, 2, 1)))


def test_mask_clipped_at_canvas_edges():
    c = Canvas(4, 3)
    m = mask(np.ones((3, 3)), x0=-1, y0=2)       # only row 2, columns 0..1 land
    c.fill(m, (1, 1, 1))
    alpha = c.data[..., 3]
    assert alpha.sum() == 2 and alpha[2, 0] == 1 and alpha[2, 1] == 1
    c.fill(mask(np.ones((2, 2)), x0=10, y0=0), (1, 1, 1))   # fully outside
    c.fill(mask(np.ones((2, 2)), x0=-5, y0=-5), (1, 1, 1))
    c.fill(None, (1, 1, 1))
    assert c.data[..., 3].sum() == 2


def test_fill_only_touches_mask_box():
    c = Canvas(10, 10, background=(0, 1, 0, 0.5))
    before = c.data.copy()
    c.fill(mask(np.full((2, 3), 0.5), x0=4, y0=5), (1, 0, 0))
    changed = np.any(c.data != before, axis=2)
    assert changed.sum() == 6 and changed[5:7, 4:7].all()


def test_composite_layer():
    c = Canvas(3, 3, background=(0, 0, 1))
    layer = np.zeros((2, 2, 4), np.float32)
    layer[...] = (0.5, 0, 0, 0.5)
    c.composite(layer, 2, 2, opacity=0.5)       # one pixel lands, at (2, 2)
    assert np.allclose(c.data[2, 2], [0.25, 0, 0.75, 1.0])
    assert np.allclose(c.data[0, 0], [0, 0, 1, 1])
    c.composite(layer, -5, 0)
    assert np.allclose(c.data[0, 0], [0, 0, 1, 1])
    with pytest.raises(CanvasError):
        c.composite(np.zeros((2, 2, 3)), 0, 0)


def test_fill_equals_composite_of_premultiplied_layer():
    rng = np.random.default_rng(1)
    cov = rng.uniform(0, 1, (5, 6)).astype(np.float32)
    a = Canvas(8, 8, background=(0.3, 0.2, 0.1, 0.6))
    b = Canvas(8, 8, background=(0.3, 0.2, 0.1, 0.6))
    a.fill(Mask(cov, 1, 2), (0.9, 0.5, 0.2, 0.7), opacity=0.8)
    layer = cov[..., None] * np.float32(0.7 * 0.8) * np.array([0.9, 0.5, 0.2, 1.0], np.float32)
    b.composite(layer, 1, 2)
    assert np.abs(a.data - b.data).max() < 1e-6


def test_to_rgba8_rounding_and_transparent():
    c = Canvas(4, 1)
    c.data[0, 0] = (0.1, 0.2, 0.3, 0.5)          # straight (0.2, 0.4, 0.6)
    c.data[0, 1] = (0.5 / 255, 0, 0, 1.0 / 255)  # alpha rounds to 1
    c.data[0, 2] = (0.001, 0.001, 0.001, 0.001)  # alpha rounds to 0
    c.data[0, 3] = (0.5, 0.5, 0.5, 1.0)          # 127.5 rounds half up
    out = c.to_rgba8()
    assert out.dtype == np.uint8
    assert out[0, 0].tolist() == [51, 102, 153, 128]
    assert out[0, 1].tolist() == [128, 0, 0, 1]
    assert out[0, 2].tolist() == [0, 0, 0, 0]
    assert out[0, 3].tolist() == [128, 128, 128, 255]
    pre = c.to_rgba8(premultiplied=True)
    assert pre[0, 0].tolist() == [26, 51, 77, 128]


@settings(max_examples=100, deadline=None)
@given(st.lists(st.floats(0, 1), min_size=4, max_size=4), st.floats(0.004, 1))
def test_property_rgba8_round_trip(rgb_a, cov):
    # a straight colour filled at full coverage comes back within rounding
    r, g, b, a = rgb_a
    a = max(a, 0.05)
    c = Canvas(1, 1)
    c.fill(mask([[1.0]]), (r, g, b, a))
    px = c.to_rgba8()[0, 0].astype(int)
    assert abs(px[3] - a * 255) <= 0.5 + 1e-3
    # demultiplying an 8-bit-rounded alpha can move colour by 255 * 0.5 / a8
    tol = 0.5 + 1e-3
    assert np.all(np.abs(px[:3] - np.array([r, g, b]) * 255) <= tol)
    # partial coverage keeps colour, scales alpha
    c = Canvas(1, 1)
    c.fill(mask([[cov]]), (r, g, b))
    assert abs(float(c.data[0, 0, 3]) - cov) < 1e-6


def test_png_round_trip(tmp_path):
    c = Canvas(5, 4, background=(1, 1, 1, 0.25))
    edges = np.array([[[1, 1], [4, 1]], [[4, 1], [4, 3]], [[4, 3], [1, 3]], [[1, 3], [1, 1]]], float)
    c.fill(coverage(edges + 0.5, 5, 4), (0.0, 0.5, 1.0))
    p = tmp_path / 'a.png'
    c.save_png(p)
    back = np.asarray(Image.open(p))
    assert back.shape == (4, 5, 4) and np.array_equal(back, c.to_rgba8())
    buf = io.BytesIO()
    c.save_png(buf, compress_level=9)
    assert np.array_equal(np.asarray(Image.open(io.BytesIO(buf.getvalue()))), back)
    assert c.to_image().mode == 'RGBA'
    assert 0 <= DEFAULT_COMPRESS_LEVEL <= 9
    with pytest.raises(CanvasError):
        c.save_png(buf, compress_level=11)


@pytest.mark.parametrize('w, h', [(0, 1), (-3, 4), (1.5, 2), ('x', 2), (100_001, 1), (20000, 20000)])
def test_bad_sizes(w, h):
    with pytest.raises(CanvasError):
        Canvas(w, h)


def test_bad_colours():
    c = Canvas(2, 2)
    m = mask(np.ones((2, 2)))
    for bad in [(1, 0), (1, 2, 3, 4, 5), ('a', 0, 0), (np.nan, 0, 0), None]:
        with pytest.raises(CanvasError):
            c.fill(m, bad)
    with pytest.raises(CanvasError):
        c.fill(m, (1, 0, 0), opacity=float('nan'))
    with pytest.raises(CanvasError):
        Canvas(2, 2, background=(1, 1))


# -- fast paths: bitwise equal to the direct float32 formulas -----------------

def _ref_fill(data, k, x0, y0, rgba):
    """The defining formula, pixel-wise: dst += k a (vec - dst) in float32."""
    out = data.copy()
    r, g, b, a = rgba
    vec = np.array([r, g, b, 1.0], np.float32)
    h, w = k.shape
    H, W = data.shape[:2]
    for i in range(h):
        for j in range(w):
            y, x = y0 + i, x0 + j
            if 0 <= y < H and 0 <= x < W and k[i, j] != 0:
                kk = k[i, j] * np.float32(a) if a != 1.0 else k[i, j]
                out[y, x] += (vec - out[y, x]) * kk
    return out


def _ref_rgba8(data, premultiplied=False):
    d = np.clip(data, 0.0, 1.0)
    a8 = np.floor(d[..., 3] * np.float32(255.0) + np.float32(0.5))
    if premultiplied:
        return np.floor(d * np.float32(255.0) + np.float32(0.5)).astype(np.uint8)
    alpha = d[..., 3:4]
    with np.errstate(all='ignore'):
        rgb = np.where(alpha > 0, d[..., :3] / alpha, np.float32(0.0))
    rgb8 = np.floor(np.clip(rgb, 0.0, 1.0) * np.float32(255.0) + np.float32(0.5))
    rgb8[a8 == 0] = 0
    return np.concatenate([rgb8, a8[..., None]], -1).astype(np.uint8)


@pytest.mark.parametrize('block', [16, 1 << 14])
@pytest.mark.parametrize('seed', [0, 1])
def test_fill_blocks_and_crops_match_the_formula(monkeypatch, block, seed):
    # a sparse mask (empty rows and columns, exact 0 and 1, partial values)
    # placed partly off a translucent canvas, with translucent and opaque
    # colours: the blocked, cropped, lane-spread fill equals the formula
    import raster.pixels.canvas as canvas_mod
    monkeypatch.setattr(canvas_mod, '_BLOCK', block)
    rng = np.random.default_rng(seed)
    k = rng.choice([0.0, 0.0, 1.0, 0.25, 0.7], (23, 31)).astype(np.float32)
    k[:4] = 0
    k[:, 20:] = 0
    for rgba in [(0.2, 0.4, 0.8, 1.0), (0.9, 0.1, 0.3, 0.6)]:
        c = Canvas(29, 19, background=(0.5, 0.25, 0.0, 0.5))
        c.data += rng.uniform(0, 0.1, c.data.shape).astype(np.float32)
        ref = _ref_fill(c.data, k, -3, 2, rgba)
        c.fill(Mask(k, -3, 2), rgba)
        assert np.array_equal(c.data, ref)


def test_spread4_repeats_bits():
    from raster.pixels.canvas import _spread4
    rng = np.random.default_rng(3)
    k = rng.normal(size=(5, 40)).astype(np.float32)
    k[0, :3] = [-0.0, np.inf, 1e-45]
    lanes = np.empty((k.size, 2), np.uint64)
    s = _spread4(k[:, 7:30], lanes)
    assert np.array_equal(s.view(np.uint32), np.repeat(k[:, 7:30], 4, axis=1).view(np.uint32))


@pytest.mark.parametrize('opaque_share', [0.0, 0.9, 1.0])
def test_to_rgba8_matches_the_formula(opaque_share):
    # blocks that are mostly opaque divide only their translucent pixels,
    # mostly translucent ones divide everything: both equal the formula,
    # including alphas that round to 0, tiny and out-of-range values
    rng = np.random.default_rng(5)
    d = rng.uniform(-0.2, 1.2, (70, 130, 4)).astype(np.float32)
    kind = rng.random((70, 130))
    d[..., 3] = np.where(kind < opaque_share, 1.0, d[..., 3])
    d[kind > 0.97, 3] = 0.0
    d[(kind > 0.94) & (kind <= 0.97), 3] = 1e-3
    d[0, :5, 3] = [1e-39, 0.5 / 255, 1.0 / 255, 0.0, 2.0]
    c = Canvas(130, 70)
    c.data = d
    assert np.array_equal(c.to_rgba8(), _ref_rgba8(d))
    assert np.array_equal(c.to_rgba8(premultiplied=True), _ref_rgba8(d, True))


@pytest.mark.parametrize('opacity', [1.0, 0.35])
def test_composite_matches_the_formula(opacity):
    rng = np.random.default_rng(9)
    base = rng.uniform(0, 1, (17, 21, 4)).astype(np.float32)
    layer = rng.uniform(0, 1, (9, 30, 4)).astype(np.float32)
    c = Canvas(21, 17)
    c.data = base.copy()
    c.composite(layer, -4, 11, opacity)
    s = layer[:6, 4:25] * np.float32(opacity) if opacity != 1.0 else layer[:6, 4:25]
    ref = base.copy()
    ref[11:17, 0:21] = ref[11:17, 0:21] * (np.float32(1.0) - s[..., 3:4]) + s
    assert np.array_equal(c.data, ref)


@pytest.mark.parametrize('level', [0, 1, 3, 6, 9])
def test_png_levels_round_trip_identically(level):
    # levels 1-3 use zlib's run-length strategy, the others the default:
    # the decoded pixels are the same
    rng = np.random.default_rng(2)
    c = Canvas(40, 30, background=(1, 1, 1))
    c.fill(Mask(rng.random((20, 25)).astype(np.float32), 5, 4), (0.1, 0.5, 0.9, 0.8))
    buf = io.BytesIO()
    c.save_png(buf, compress_level=level)
    assert np.array_equal(np.asarray(Image.open(io.BytesIO(buf.getvalue()))), c.to_rgba8())


@pytest.mark.parametrize('contiguous', [True, False])
def test_sparse_fill_matches_the_formula(contiguous):
    # few covered pixels (a thin diagonal line): gathered and scattered
    rng = np.random.default_rng(4)
    k = np.zeros((40, 60), np.float32)
    i = np.arange(40)
    k[i, i + 7] = rng.uniform(0.1, 1.0, 40)
    k[i[::3], i[::3] + 8] = 1.0
    if not contiguous:
        k = np.asfortranarray(k)
    assert np.count_nonzero(k) * 8 <= k.size
    for rgba in [(0.3, 0.6, 0.9, 1.0), (1.0, 0.5, 0.0, 0.4)]:
        c = Canvas(50, 45, background=(0.1, 0.2, 0.3, 0.6))
        ref = _ref_fill(c.data, k, -5, 9, rgba)
        c.fill(Mask(k, -5, 9), rgba)
        assert np.array_equal(c.data, ref)


@pytest.mark.parametrize('block', [64, 1 << 14])
@pytest.mark.parametrize('rgba', [(0.2, 0.4, 0.8, 1.0), (0.9, 0.1, 0.3, 0.6)])
def test_large_dense_fill_matches_the_formula(monkeypatch, block, rgba):
    # a mask above the small-mask size, mostly covered (no gather): opaque
    # paint copies the colour into fully covered pixels and blends the
    # edges, translucent paint blends in blocks; both equal the formula
    # within float32 rounding, and full coverage of opaque paint gives the
    # colour exactly
    import raster.pixels.canvas as canvas_mod
    monkeypatch.setattr(canvas_mod, '_BLOCK', block)
    monkeypatch.setattr(canvas_mod, '_SMALL', 1024)
    rng = np.random.default_rng(11)
    k = rng.choice([0.0, 1.0, 1.0, 1.0, 0.3, 0.85], (60, 45)).astype(np.float32)
    k[:3] = 0
    assert k.size > canvas_mod._SMALL and np.count_nonzero(k) * 8 > k.size
    c = Canvas(50, 70, background=(0.5, 0.25, 0.0, 0.5))
    c.data += rng.uniform(0, 0.1, c.data.shape).astype(np.float32)
    ref = _ref_fill(c.data, k, -4, 6, rgba)
    c.fill(Mask(k, -4, 6), rgba)
    assert np.abs(c.data - ref).max() <= 1e-6
    changed = np.zeros((70, 50), bool)
    changed[6:66, 0:41] = k[:, 4:] != 0
    assert np.array_equal(np.any(c.data != ref, axis=2) | changed, changed)
    if rgba[3] == 1.0:
        full = np.zeros((70, 50), bool)
        full[6:66, 0:41] = k[:, 4:] == 1
        assert np.all(c.data[full] == np.float32([0.2, 0.4, 0.8, 1.0]))


@pytest.mark.parametrize('rgba', [(0.2, 0.4, 0.8, 1.0), (0.9, 0.1, 0.3, 0.6)])
@pytest.mark.parametrize('share', [0.05, 0.5, 1.0])
def test_eight_bit_fill_same_in_one_pass_and_by_covered_pixels(monkeypatch, rgba, share):
    # an 8-bit canvas gets the same levels whether a mask is filled in one
    # pass over its window (small masks) or through its covered and full
    # pixels (sparse gather, opaque copy, blocks): the size threshold
    # between them is a matter of speed only
    import raster.pixels.canvas as canvas_mod
    rng = np.random.default_rng(int(share * 100))
    k = rng.choice([0.0, 1.0, 0.3, 0.85, 0.02], (48, 71)).astype(np.float32)
    k[rng.uniform(size=k.shape) > share] = 0
    back = rng.integers(0, 256, (60, 80, 4), dtype=np.uint8)
    out = []
    for small in (0, 1 << 20):
        monkeypatch.setattr(canvas_mod, '_SMALL', small)
        c = Canvas(80, 60, dtype=np.uint8)
        c.data[...] = back
        c.fill(Mask(k, 3, -2), rgba)
        out.append(c.data.copy())
    assert np.array_equal(out[0], out[1])
    assert not np.array_equal(out[0], back)


def test_fill_paints_repeat_and_still_validate():
    # the same colour as tuple and list, several opacities and row widths
    # (remembered paints and colour rows) give the formula every time
    rng = np.random.default_rng(12)
    c = Canvas(300, 8, background=(0.1, 0.2, 0.3, 0.4))
    ref = c.data.copy()
    for color, op, w in [((0.3, 0.6, 0.9), 1.0, 3), ([0.3, 0.6, 0.9], 0.5, 290),
                         ((0.3, 0.6, 0.9), 0.5, 7), ((0.9, 0.6, 0.3, 0.5), 1.0, 300),
                         ((0.3, 0.6, 0.9), 1.0, 300)]:
        k = rng.uniform(0, 1, (3, w)).astype(np.float32)
        ref = _ref_fill(ref, k, 0, 2, tuple(color[:3]) + ((color[3] if len(color) == 4 else 1.0) * op,))
        c.fill(Mask(k, 0, 2), color, op)
        assert np.abs(c.data - ref).max() <= 1e-6
    for _ in range(2):
        with pytest.raises(CanvasError):
            c.fill(Mask(np.ones((1, 1), np.float32), 0, 0), (float('nan'), 0, 0))
        with pytest.raises(CanvasError):
            c.fill(Mask(np.ones((1, 1), np.float32), 0, 0), (0.1, 0.2, 0.3), float('inf'))


def test_to_rgba8_blocks_of_different_kinds(monkeypatch):
    # many small blocks: all opaque, all transparent, mostly translucent,
    # out of range, transparent with colour: each equals the formula
    import raster.pixels.canvas as canvas_mod
    monkeypatch.setattr(canvas_mod, '_BLOCK', 24)
    rng = np.random.default_rng(13)
    d = rng.uniform(0, 1, (60, 9, 4)).astype(np.float32)
    d[:10, :, 3] = 1.0
    d[10:20] = 0.0
    d[20:25, :, :3] = 0.3                       # transparent, with colour
    d[20:25, :, 3] = 0.0
    d[30:35] = rng.uniform(-0.5, 1.5, (5, 9, 4))
    d[40:45, :, 3] = rng.choice([1.0, 1e-4, 0.3], (5, 9))
    c = Canvas(9, 60)
    c.data = d
    assert np.array_equal(c.to_rgba8(), _ref_rgba8(d))
    assert np.array_equal(c.to_rgba8(premultiplied=True), _ref_rgba8(d, True))


def test_fill_on_a_non_contiguous_canvas_matches_the_formula():
    # canvas data replaced by a Fortran-ordered array: small, sparse and
    # dense masks still follow the formula (no row reshapes)
    rng = np.random.default_rng(14)
    base = np.asfortranarray(rng.uniform(0, 1, (40, 50, 4)).astype(np.float32))
    for shape in [(5, 6), (30, 40)]:
        k = rng.choice([0.0, 1.0, 0.4], shape).astype(np.float32)
        for rgba in [(0.2, 0.4, 0.8, 1.0), (0.9, 0.1, 0.3, 0.6)]:
            c = Canvas(50, 40)
            c.data = base.copy(order='F')
            ref = _ref_fill(base, k, 3, 2, rgba)
            c.fill(Mask(k, 3, 2), rgba)
            assert np.abs(c.data - ref).max() <= 1e-6


@pytest.mark.parametrize('dtype', [np.float32, np.uint8])
@pytest.mark.parametrize('rgba', [(0.2, 0.4, 0.8, 1.0), (0.9, 0.1, 0.3, 0.6)])
def test_fill_in_windows_of_rows_equals_one_window(monkeypatch, dtype, rgba):
    # a mask above _FILL_ROWS pixels is filled in windows of rows, each
    # window taking its own way (gathered pixels, opaque copy, blocks): the
    # pixels are those of one window, bit for bit, also where the mask
    # reaches off the canvas
    import raster.pixels.canvas as canvas_mod
    rng = np.random.default_rng(3)
    k = rng.choice([0.0, 1.0, 1.0, 0.3, 0.85], (90, 70)).astype(np.float32)
    k[10:40] = 0                                 # sparse rows: gathered
    k[40:50, 5:] = 0
    k[60:70] = 1.0                               # full rows: copied
    out = []
    for rows in (1 << 30, 700, 64):
        monkeypatch.setattr(canvas_mod, '_FILL_ROWS', rows)
        c = Canvas(60, 80, background=(0.5, 0.25, 0.0, 0.5), dtype=dtype)
        c.fill(Mask(k, -5, -7), rgba)
        c.fill(Mask(k[::-1].copy(), 3, 2), rgba, opacity=0.5)
        out.append(c.data.copy())
    assert np.array_equal(out[0], out[1]) and np.array_equal(out[0], out[2])
