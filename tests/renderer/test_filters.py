"""Filter effects: the pixel operations (raster.pixels.effects,
raster.pixels.compositing), their resolution (raster.parser.filters) and
application (raster.renderer.filters), and rendering."""

import math
import os
import warnings

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from PIL import Image

import raster
from raster.errors import RasterError
from raster.errors import CanvasError
from raster.parser import filters as P
from raster.pixels import compositing as C
from raster.pixels import effects as F
from raster.renderer.filters import apply_filters
from raster.tree import filter as T
from raster.geometry.transform import Affine
from raster.testing import compare_images

from _shared import SUITE_ROOT as SUITE


def _img(h, w, seed=0):
    """Random premultiplied RGBA image (colour <= alpha)."""
    rng = np.random.default_rng(seed)
    a = rng.random((h, w, 1), dtype=np.float32)
    c = rng.random((h, w, 3), dtype=np.float32) * a
    return np.concatenate([c, a], -1).astype(np.float32)


# ---------------------------------------------------------------------------
# Gaussian blur
# ---------------------------------------------------------------------------

@pytest.mark.parametrize('sigma', [0.7, 1.5, 3.0, 6.0])
def test_blur_of_constant_image_is_constant_inside(sigma):
    img = np.zeros((80, 80, 4), np.float32)
    img[...] = (0.2, 0.3, 0.1, 0.5)
    out = F.gaussian_blur(img, sigma)
    r = int(4 * sigma) + 3
    inner = out[r:-r, r:-r]
    assert np.allclose(inner, (0.2, 0.3, 0.1, 0.5), atol=1e-5)
    # at the border transparency leaks in
    assert out[0, 40, 3] < 0.5 - 0.05


@pytest.mark.parametrize('sigma', [0.8, 1.9, 2.5, 7.0])
def test_blur_conserves_total_alpha_away_from_edges(sigma):
    img = np.zeros((101, 101, 4), np.float32)
    img[45:56, 40:60] = 1.0
    out = F.gaussian_blur(img, sigma, sigma * 0.5)
    assert abs(out[..., 3].sum() - img[..., 3].sum()) < 1e-3 * img[..., 3].sum()


def test_blur_of_a_point_matches_the_gaussian_variance():
    # the variance of the blurred delta equals sigma^2 (exact kernel) and
    # is close to it for the box approximation (3 boxes of width d:
    # variance 3 (d^2 - 1) / 12)
    img = np.zeros((1, 201, 4), np.float32)
    img[0, 100] = 1
    x = np.arange(201) - 100.0
    for s in (1.0, 1.5):
        out = F.gaussian_blur(img, s, 0)[0, :, 3]
        assert abs((out * x * x).sum() - s * s) < 0.02 * s * s
    out = F.gaussian_blur(img, 10.0, 0, tolerance=None)[0, :, 3]
    d = int(np.floor(10 * 3 * np.sqrt(2 * np.pi) / 4 + 0.5))
    assert d == 19
    assert abs((out * x * x).sum() - 3 * (d * d - 1) / 12) < 1e-3


def test_blur_tolerance_is_honoured():
    # the blur of a delta has the variance of the kernel; with the default
    # tolerance its standard deviation is within 0.25 px of sigma (box
    # blurs allowed), with a tight tolerance the exact kernel is used and
    # the centre value is the Gaussian's 1 / (sqrt(2 pi) sigma)
    img = np.zeros((1, 201, 4), np.float32)
    img[0, 100] = 1
    x = np.arange(201) - 100.0
    for s in np.linspace(1.0, 12.0, 23):
        for tol in (0.25, 0.1, 0.02):
            out = F.gaussian_blur(img, s, 0, tolerance=tol)[0, :, 3]
            assert abs(np.sqrt((out * x * x).sum()) - s) <= tol + 0.01
    s = 3.0
    exact = F.gaussian_blur(img, s, 0, tolerance=0.01)[0, 100, 3]
    assert abs(exact - 1 / (np.sqrt(2 * np.pi) * s)) < 1e-3


@settings(max_examples=80, deadline=None)
@given(st.integers(1, 20), st.integers(1, 45), st.data())
def test_box_sums_match_direct_window_sums(n, d, data):
    left = data.draw(st.integers(0, d - 1))
    a = np.random.default_rng(n * 100 + d).random((n, 3)).astype(np.float32)
    out = F._box_axis(a, d, left, 0)
    ref = np.array([a[max(i - left, 0):max(min(i - left + d, n), 0)].sum(0)
                    for i in range(n)]) / d
    assert np.allclose(out, ref, atol=1e-6)


def _direct_box(x, d, left):
    """Reference box sum along axis 0 by explicit windows (test oracle)."""
    n = x.shape[0]
    return np.array([x[min(max(i - left, 0), n):min(max(i - left + d, 0), n)].sum(0)
                     for i in range(n)]).reshape(x.shape)


@settings(max_examples=80, deadline=None)
@given(st.integers(1, 30), st.integers(1, 4), st.lists(
    st.tuples(st.integers(1, 70), st.integers(-80, 80)), min_size=1, max_size=3),
    st.integers(0, 10_000))
def test_box_passes_match_successive_direct_sums(n, m, boxes, seed):
    # any window position, including windows wider than the array and
    # windows entirely before or after the pixel
    x = np.random.default_rng(seed).random((n, m, 2)).astype(np.float32)
    ref = x.astype(np.float64)
    for d, left in boxes:
        ref = _direct_box(ref, d, left) / d
    out = F._box_passes(x, boxes)
    assert out.shape == x.shape and out.dtype == np.float32
    assert np.allclose(out, ref, rtol=1e-5, atol=1e-6)


def test_box_passes_blocks_and_strides_do_not_change_the_result(monkeypatch):
    x = _img(37, 53, seed=3)
    boxes = ((9, 4), (9, 4), (10, 5))
    whole = F._box_passes(np.moveaxis(x, 1, 0), boxes)
    monkeypatch.setattr(F, '_BLOCK_BYTES', 64)          # one column per block
    assert np.array_equal(F._box_passes(np.moveaxis(x, 1, 0), boxes), whole)
    assert np.array_equal(F._box_passes(np.ascontiguousarray(np.moveaxis(x, 1, 0)), boxes),
                          whole)


def _uncropped_blur(img, plan_x, plan_y):
    """The blur of every pixel (no bounding box), float64 oracle."""
    out = img.astype(np.float64)
    for axis, plan in ((1, plan_x), (0, plan_y)):
        if plan is None:
            continue
        a = np.moveaxis(out, axis, 0)
        if plan[0] == 'box':
            for d, left in plan[1]:
                a = _direct_box(a, d, left) / d
        else:
            a = F._gauss_axis(a.astype(np.float32), plan[1], 0).astype(np.float64)
        out = np.moveaxis(a, 0, axis)
    return out


@pytest.mark.parametrize('sx, sy', [(3.0, 3.0), (6.5, 0.0), (0.0, 2.2), (1.2, 4.0), (0.6, 0.9)])
@pytest.mark.parametrize('where', ['middle', 'corner', 'edge'])
def test_blur_restricted_to_the_content_box_equals_the_whole_blur(sx, sy, where):
    img = np.zeros((60, 70, 4), np.float32)
    patch = _img(6, 9, seed=5)
    y, x = {'middle': (27, 30), 'corner': (0, 61), 'edge': (54, 20)}[where]
    img[y:y + 6, x:x + 9] = patch
    plans = F.blur_plans(sx, sy, None)
    ref = _uncropped_blur(img, *plans)
    out = F.gaussian_blur(img, sx, sy)
    assert np.abs(out - ref).max() <= 1e-6
    # beyond the blur's reach the result is exactly transparent
    (bx, ax), (by, ay) = F._reach(plans[0]), F._reach(plans[1])
    keep = np.zeros((60, 70), bool)
    keep[max(y - by, 0):y + 6 + ay, max(x - bx, 0):x + 9 + ax] = True
    assert not out[~keep].any()


def test_blur_of_a_transparent_image_is_transparent():
    img = np.zeros((12, 9, 4), np.float32)
    out = F.gaussian_blur(img, 3.0)
    assert out.shape == img.shape and not out.any()


def test_nonzero_box_hand_computed():
    img = np.zeros((10, 12, 4), np.float32)
    assert F.nonzero_box(img) is None
    img[2, 7, 1] = 0.5                   # a colour channel alone counts
    img[6, 3, 3] = 0.25
    assert F.nonzero_box(img) == (2, 7, 3, 8)
    assert F.nonzero_box(img[..., 3]) == (6, 7, 3, 4)


def test_solid_colour_is_recognised_and_rejected():
    rng = np.random.default_rng(7)
    a = rng.random((40, 50), dtype=np.float32)
    c = np.array([0.2, 0.7, 1.0], np.float32)
    img = F.solid_image(a, c)
    assert np.allclose(F.solid_colour(img), c, atol=1e-6)
    assert F.solid_colour(np.zeros((5, 5, 4), np.float32)).tolist() == [0.0, 0.0, 0.0]
    off = img.copy()
    off[3, 5, 1] += 1e-3                 # off the sampling grid
    assert F.solid_colour(off) is None
    near = img.copy()
    near[3, 5, 1] += 1e-6                # float32 rounding of compositing
    assert F.solid_colour(near) is not None
    assert F.solid_colour(_img(40, 50, seed=2)) is None


@pytest.mark.parametrize('c', [(0.0, 0.0, 0.0), (1.0, 1.0, 1.0), (0.3, 0.05, 0.9)])
def test_solid_blur_equals_four_channel_blur(c):
    a = np.zeros((50, 60), np.float32)
    a[10:30, 15:50] = np.random.default_rng(1).random((20, 35), dtype=np.float32)
    img = F.solid_image(a, np.array(c, np.float32))
    plans = F.blur_plans(4.0, 1.5, None)
    solid = F.FilterImage.of(img)
    assert solid.solid
    fast = F.blur_image(solid, *plans).data
    general = F.blur_image(F.FilterImage(img), *plans).data
    assert np.abs(fast - general).max() <= 1e-6


def _input_image(solid, shape, box, seed, colour, img_seed):
    """A filter input: a solid colour through random alpha over ``box``
    (y0, y1, x0, x1) of ``shape``, or (not ``solid``) a general image."""
    if not solid:
        return _img(*shape, seed=img_seed)
    y0, y1, x0, x1 = box
    a = np.zeros(shape, np.float32)
    a[y0:y1, x0:x1] = np.random.default_rng(seed).random((y1 - y0, x1 - x0), dtype=np.float32)
    return F.solid_image(a, np.array(colour, np.float32))


def _chain_filter():
    src, res = T.Source, T.Result
    return T.Filter(region=(2.0, 3.0, 56.0, 40.0), primitives=[
        T.GaussianBlur(inputs=(src.GRAPHIC,), result='b', std_dev=(2.5, 1.5)),
        T.Offset(inputs=(res('b'),), result='o', dx=3.0, dy=-2.0),
        T.Flood(result='fl', subregion=(10.0, 8.0, 20.0, 15.0), color=(0.2, 0.4, 0.9, 0.5)),
        T.GaussianBlur(inputs=(src.ALPHA,), result='sa', linear=False, std_dev=(1.0, 1.0)),
        T.Merge(inputs=(res('fl'), res('o'), res('sa'), src.GRAPHIC)),
    ])


@pytest.mark.parametrize('solid', [True, False])
def test_apply_filters_solid_fast_path_matches_the_general_path(monkeypatch, solid):
    data = _input_image(solid, (50, 64), (12, 35, 10, 40), 4, (0.9, 0.3, 0.1), 8)
    t = Affine.identity()
    fast = apply_filters([_chain_filter()], data, t)
    monkeypatch.setattr(F, 'solid_colour', lambda img, tol=None: None)
    general = apply_filters([_chain_filter()], data, t)
    assert np.abs(fast - general).max() <= 2e-6
    assert not fast[:3].any() and not fast[43:].any()      # outside the region


def test_apply_filters_returns_a_new_array():
    data = _img(20, 20, seed=1)
    # a disabled blur passes its input on (resvg): the layer must be copied
    f = T.Filter(region=(-5.0, -5.0, 30.0, 30.0), primitives=[
        T.GaussianBlur(inputs=(T.Source.GRAPHIC,), linear=False, std_dev=(0.0, 0.0))])
    out = apply_filters([f], data, Affine.identity())
    assert np.array_equal(out, data) and not np.shares_memory(out, data)


def test_row_blocks_do_not_change_pixel_maps(monkeypatch):
    img = _img(23, 31, seed=6)
    m = P._saturate_matrix(0.3)
    funcs = {0: ('gamma', (1.0, 2.0, 0.0)), 3: ('table', (0.0, 0.5, 1.0))}
    whole = (F.color_matrix(img, m), F.component_transfer(img, funcs),
             F._convert_pixels(img, F.srgb_to_linear))
    monkeypatch.setattr(F, '_BLOCK_BYTES', 1)            # one row per block
    for a, b in zip(whole, (F.color_matrix(img, m), F.component_transfer(img, funcs),
                            F._convert_pixels(img, F.srgb_to_linear))):
        assert np.array_equal(a, b)


def test_zero_sigma_is_identity():
    img = _img(10, 12)
    assert np.array_equal(F.gaussian_blur(img, 0, 0), img)


@settings(max_examples=40, deadline=None)
@given(st.floats(0.3, 12.0), st.integers(0, 10_000))
def test_blur_keeps_premultiplied_invariants(sigma, seed):
    out = F.gaussian_blur(_img(24, 30, seed), sigma)
    assert out.dtype == np.float32 and out.shape == (24, 30, 4)
    assert (out >= -1e-6).all() and (out <= 1 + 1e-5).all()
    assert (out[..., :3] <= out[..., 3:4] + 1e-5).all()


def test_blur_bad_input_raises():
    with pytest.raises(F.FilterError):
        F.gaussian_blur(np.zeros((4, 4)), 1.0)
    with pytest.raises(RasterError):
        F.gaussian_blur(np.zeros((4, 4, 4), np.float32), float('nan'))
    with pytest.raises(F.FilterError):
        F.gaussian_blur(np.zeros((4, 4, 4), np.float32), 1.0, tolerance=0)
    with pytest.raises(F.FilterError):
        F.offset(np.zeros((4, 4, 4), np.float32), float('inf'), 0)


# ---------------------------------------------------------------------------
# Offset, flood, composite, colour
# ---------------------------------------------------------------------------

@settings(max_examples=60, deadline=None)
@given(st.integers(-12, 12), st.integers(-12, 12))
def test_offset_shifts_by_whole_pixels(dx, dy):
    img = _img(20, 20, 3)
    out = F.offset(img, dx, dy)
    h, w = img.shape[:2]
    for i, j in [(5, 5), (10, 3), (0, 19), (19, 0)]:
        ii, jj = i + dy, j + dx
        if 0 <= ii < h and 0 <= jj < w:
            assert np.array_equal(out[ii, jj], img[i, j])
    # what moved in from outside is transparent
    if dx > 0:
        assert not out[:, :dx].any()
    if dy < 0:
        assert not out[h + dy:].any()


def test_offset_inverse_restores_inside():
    img = _img(16, 16, 4)
    back = F.offset(F.offset(img, 3, -2), -3, 2)
    assert np.array_equal(back[2:, :13], img[2:, :13])


# premultiplied (r, g, b, a) for a = half-transparent red over b = opaque blue
A = np.array([[[0.5, 0.0, 0.0, 0.5]]], np.float32)
B = np.array([[[0.0, 0.0, 1.0, 1.0]]], np.float32)


@pytest.mark.parametrize('op,expected', [
    ('over', [0.5, 0.0, 0.5, 1.0]),        # A + B (1 - Aa)
    ('in', [0.5, 0.0, 0.0, 0.5]),          # A Ba
    ('out', [0.0, 0.0, 0.0, 0.0]),         # A (1 - Ba)
    ('atop', [0.5, 0.0, 0.5, 1.0]),        # A Ba + B (1 - Aa)
    ('xor', [0.0, 0.0, 0.5, 0.5]),         # A (1 - Ba) + B (1 - Aa)
])
def test_composite_operators_hand_computed(op, expected):
    assert np.allclose(C.composite(A, B, op)[0, 0], expected)


def test_composite_arithmetic_hand_computed():
    # k1 A B + k2 A + k3 B + k4 = 0.5 A + 0.5 B, then colour <= alpha
    out = C.composite(A, B, 'arithmetic', (0, 0.5, 0.5, 0))[0, 0]
    assert np.allclose(out, [0.25, 0.0, 0.5, 0.75])
    # k4 alone: a flat grey, clamped
    out = C.composite(A, B, 'arithmetic', (0, 0, 0, 2))[0, 0]
    assert np.allclose(out, [1, 1, 1, 1])
    # k1 A B only: product
    out = C.composite(A, B, 'arithmetic', (1, 0, 0, 0))[0, 0]
    assert np.allclose(out, [0, 0, 0, 0.5])


def test_composite_bad_operator_and_shapes():
    with pytest.raises(CanvasError):
        C.composite(A, B, 'plus')
    with pytest.raises(CanvasError):
        C.composite(A, np.zeros((2, 2, 4), np.float32))


def test_blend_normal_is_over_and_multiply_hand_computed():
    img1, img2 = _img(6, 7, 1), _img(6, 7, 2)
    assert np.allclose(C.blend(img1, img2, 'normal'), C.composite(img1, img2, 'over'),
                       atol=1e-6)
    # opaque colours: multiply is the product of the colours
    a = np.array([[[0.5, 1.0, 0.2, 1.0]]], np.float32)
    b = np.array([[[0.4, 0.5, 1.0, 1.0]]], np.float32)
    assert np.allclose(C.blend(a, b, 'multiply')[0, 0], [0.2, 0.5, 0.2, 1.0])


def test_color_matrix_identity_and_luminance_to_alpha():
    img = _img(9, 11, 5)
    ident = P._color_matrix_of('matrix', None)
    assert np.allclose(F.color_matrix(img, ident), img, atol=1e-6)
    # saturate 1 and hueRotate 0 are the identity too
    for kind, v in (('saturate', '1'), ('hueRotate', '0')):
        m = P._color_matrix_of(kind, v)
        assert np.allclose(F.color_matrix(img, m), img, atol=2e-3)
    m = P._color_matrix_of('luminanceToAlpha', None)
    white = np.ones((1, 1, 4), np.float32)
    assert np.allclose(F.color_matrix(white, m)[0, 0], [0, 0, 0, 1.0], atol=1e-4)
    with pytest.raises(F.FilterError):
        F.color_matrix(img, np.eye(4))


def test_component_transfer_functions():
    img = np.array([[[0.25, 0.5, 0.75, 1.0]]], np.float32)
    out = F.component_transfer(img, {0: ('linear', (2.0, 0.1)),        # 0.6
                                     1: ('table', (0.0, 1.0, 0.0)),     # 1.0 at the middle
                                     2: ('discrete', (0.2, 0.4)),       # 0.4
                                     3: ('gamma', (0.5, 1.0, 0.0))})    # 0.5
    a = 0.5
    assert np.allclose(out[0, 0], [0.6 * a, 1.0 * a, 0.4 * a, a], atol=1e-6)


@settings(max_examples=50, deadline=None)
@given(st.floats(0, 1), st.floats(0, 1), st.floats(0, 1))
def test_linear_rgb_round_trip(r, g, b):
    c = np.array([r, g, b], np.float32)
    back = F.linear_to_srgb(F.srgb_to_linear(c))
    assert np.allclose(back, c, atol=2e-5)


def test_colour_conversions_match_the_float64_formulas():
    x = np.linspace(0.0, 1.0, 200_001)
    lin = np.where(x <= 0.04045, x / 12.92, ((x + 0.055) / 1.055) ** 2.4)
    srgb = np.where(x <= 0.0031308, x * 12.92, 1.055 * x ** (1 / 2.4) - 0.055)
    assert np.abs(F.srgb_to_linear(x) - lin).max() <= 1e-6
    assert np.abs(F.linear_to_srgb(x) - srgb).max() <= 1e-6
    assert F.srgb_to_linear(np.zeros((2, 3, 3))).shape == (2, 3, 3)
    assert F.linear_to_srgb(0.25).shape == ()


def test_convert_pixels_of_a_sparse_image_matches_every_pixel_conversion():
    img = np.zeros((30, 40, 4), np.float32)
    img[5:12, 20:33] = _img(7, 13, seed=9)
    img[25, 2, :3] = 0.5                 # colour without alpha: transparent
    out = F._convert_pixels(img, F.srgb_to_linear)
    a = img[..., 3:4].astype(np.float64)
    c = np.where(a > 0, img[..., :3] / np.where(a > 0, a, 1.0), 0.0)
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    assert np.abs(out[..., :3] - lin * a).max() <= 2e-6
    assert np.array_equal(out[..., 3], img[..., 3]) and not out[25, 2].any()


def test_srgb_to_linear_known_values():
    # sRGB 0.5 is 21.4 % linear light; the curve is monotone
    assert abs(float(F.srgb_to_linear(0.5)) - 0.21404) < 1e-4
    x = np.linspace(0, 1, 101)
    assert (np.diff(F.srgb_to_linear(x)) > 0).all()


def test_convolve_identity_and_shift_kernels():
    img = _img(7, 9, 6)
    ident = np.zeros((3, 3)); ident[1, 1] = 1
    for edge in ('duplicate', 'wrap', 'none'):
        assert np.allclose(F.convolve(img, ident, edge=edge), img, atol=1e-6)
    # the kernel is applied rotated by 180 degrees: K[1, 2] takes the
    # left neighbour; with wrap the left column comes from the right edge
    k = np.zeros((3, 3)); k[1, 2] = 1
    out = F.convolve(img, k, edge='wrap')
    assert np.allclose(out, np.roll(img, 1, axis=1), atol=1e-6)


def test_convolve_box_kernel_hand_computed_and_errors():
    img = np.zeros((3, 3, 4), np.float32)
    img[1, 1] = (0.9, 0.0, 0.0, 0.9)
    out = F.convolve(img, np.ones((3, 3)), edge='none')     # divisor 9
    assert np.allclose(out[0, 0], [0.1, 0, 0, 0.1], atol=1e-6)
    with pytest.raises(F.FilterError):
        F.convolve(img, np.ones((3, 3)), divisor=0)
    with pytest.raises(F.FilterError):
        F.convolve(img, np.ones((3, 3)), edge='mirror')
    # a kernel of the wrong size makes the primitive transparent
    defs = ('<filter id="f"><feConvolveMatrix order="3" kernelMatrix="1 2 3"/></filter>')
    img = _render(_svg(defs, '<rect x="5" y="5" width="20" height="20" filter="url(#f)"/>'))
    assert not img[..., 3].any()


def test_diffuse_lighting_of_a_flat_surface_is_lambert():
    # a flat bump map has the normal (0, 0, 1): N.L = sin(elevation)
    a = np.ones((6, 6), np.float32)
    for el in (90.0, 30.0):
        out = F.lighting(a, ('distant', (0.0, el)), (1.0, 0.5, 0.0), 3.0, 0.8, 1.0, False)
        assert np.allclose(out[..., 0], 0.8 * np.sin(np.radians(el)), atol=1e-6)
        assert np.allclose(out[..., 1], 0.4 * np.sin(np.radians(el)), atol=1e-6)
        assert np.allclose(out[..., 3], 1.0)


def test_specular_lighting_of_a_flat_surface_and_a_slope():
    a = np.ones((5, 5), np.float32)
    # light from straight above: H = (0, 0, 1), N.H = 1
    out = F.lighting(a, ('distant', (0.0, 90.0)), (1.0, 1.0, 1.0), 1.0, 0.5, 4.0, True)
    assert np.allclose(out[..., :3], 0.5) and np.allclose(out[..., 3], 0.5)
    # a ramp rising to the right (alpha = x / 10, surfaceScale 10): the
    # Sobel gradient is -10 / 4 * (4 * 0.2) = -2, the normal (-2, 0, 1) /
    # sqrt 5; a distant light along it (azimuth 180, elevation atan(1/2))
    # gives N.L = 1, one at elevation 90 gives 1 / sqrt 5
    ramp = np.tile(np.arange(8, dtype=np.float32) / 10.0, (8, 1))
    el = np.degrees(np.arctan(0.5))
    out = F.lighting(ramp, ('distant', (180.0, el)), (1, 1, 1), 10.0, 1.0, 1.0, False)
    assert np.allclose(out[1:-1, 1:-1, 0], 1.0, atol=1e-5)
    out = F.lighting(ramp, ('distant', (0.0, 90.0)), (1, 1, 1), 10.0, 1.0, 1.0, False)
    assert np.allclose(out[1:-1, 1:-1, 0], 1 / np.sqrt(5), atol=1e-5)


def test_turbulence_is_deterministic_bounded_and_seed_dependent():
    y, x = np.mgrid[0:16, 0:16].astype(np.float64)
    a = F.turbulence(x, y, (0.1, 0.1), 3, 7, False)
    assert a.shape == (16, 16, 4) and a.dtype == np.float32
    assert np.array_equal(a, F.turbulence(x, y, (0.1, 0.1), 3, 7, False))
    assert (a >= 0).all() and (a <= 1).all() and a.std() > 0.01
    assert not np.array_equal(a, F.turbulence(x, y, (0.1, 0.1), 3, 8, False))
    # Perlin noise vanishes on the lattice: integer points of frequency 1
    z = F.turbulence(x, y, (1.0, 1.0), 1, 7, False)
    assert np.allclose(z, 0.0, atol=1e-9)
    f = F.turbulence(x, y, (1.0, 1.0), 1, 7, True)
    assert np.allclose(f, 0.5, atol=1e-6)


# The turbulence of Filter Effects 1 (section 9.21), transcribed point by point
# from the specification's description, as the oracle of the vectorized one.

_REF_TABLES = {}


def _ref_tables(seed):
    if seed in _REF_TABLES:
        return _REF_TABLES[seed]
    m, a, q, r = 2147483647, 16807, 127773, 2836

    def rnd(s):
        s = a * (s % q) - r * int(s / q)
        return s + m if s <= 0 else s
    if seed <= 0:
        seed = -(abs(seed) % (m - 1)) + 1 if seed < 0 else 1
    seed = min(seed, m - 1)
    lat = list(range(256)) + [0] * 258
    grad = [[[0.0, 0.0] for _ in range(514)] for _ in range(4)]
    for k in range(4):
        for i in range(256):
            for j in range(2):
                seed = rnd(seed)
                grad[k][i][j] = ((seed % 512) - 256) / 256.0
            n = (grad[k][i][0] ** 2 + grad[k][i][1] ** 2) ** 0.5
            grad[k][i] = [grad[k][i][0] / n, grad[k][i][1] / n]
    for i in range(255, 0, -1):
        seed = rnd(seed)
        j = seed % 256
        lat[i], lat[j] = lat[j], lat[i]
    for i in range(258):
        lat[256 + i] = lat[i]
        for k in range(4):
            grad[k][256 + i] = list(grad[k][i])
    _REF_TABLES[seed] = lat, grad
    return lat, grad


def _ref_noise(lat, grad, ch, vx, vy, st):
    def s_curve(t):
        return t * t * (3 - 2 * t)
    t = vx + 4096
    bx0 = int(t)
    bx1, rx0 = bx0 + 1, t - int(t)
    t = vy + 4096
    by0 = int(t)
    by1, ry0 = by0 + 1, t - int(t)
    if st is not None:
        if bx0 >= st['wx']:
            bx0 -= st['w']
        if bx1 >= st['wx']:
            bx1 -= st['w']
        if by0 >= st['wy']:
            by0 -= st['h']
        if by1 >= st['wy']:
            by1 -= st['h']
    bx0, bx1, by0, by1 = bx0 & 255, bx1 & 255, by0 & 255, by1 & 255
    i, j = lat[bx0], lat[bx1]
    b00, b10, b01, b11 = lat[i + by0], lat[j + by0], lat[i + by1], lat[j + by1]
    rx1, ry1 = rx0 - 1, ry0 - 1
    sx, sy = s_curve(rx0), s_curve(ry0)
    g = grad[ch]
    u, v = rx0 * g[b00][0] + ry0 * g[b00][1], rx1 * g[b10][0] + ry0 * g[b10][1]
    aa = u + sx * (v - u)
    u, v = rx0 * g[b01][0] + ry1 * g[b01][1], rx1 * g[b11][0] + ry1 * g[b11][1]
    bb = u + sx * (v - u)
    return aa + sy * (bb - aa)


def _ref_turbulence(x, y, fx, fy, octaves, seed, fractal, tile):
    lat, grad = _ref_tables(seed)
    out = []
    for ch in range(4):
        f1, f2, st = fx, fy, None
        if tile is not None:
            tx, ty, tw, th = tile
            if f1 != 0:
                lo, hi = math.floor(tw * f1) / tw, math.ceil(tw * f1) / tw
                f1 = lo if lo > 0 and f1 / lo < hi / f1 else hi
            if f2 != 0:
                lo, hi = math.floor(th * f2) / th, math.ceil(th * f2) / th
                f2 = lo if lo > 0 and f2 / lo < hi / f2 else hi
            st = {'w': int(tw * f1 + 0.5), 'h': int(th * f2 + 0.5)}
            st['wx'] = int(tx * f1 + 4096 + st['w'])
            st['wy'] = int(ty * f2 + 4096 + st['h'])
        total, vx, vy, ratio = 0.0, x * f1, y * f2, 1.0
        for _ in range(octaves):
            n = _ref_noise(lat, grad, ch, vx, vy, st)
            total += (n if fractal else abs(n)) / ratio
            vx, vy, ratio = vx * 2, vy * 2, ratio * 2
            if st is not None:
                st = {'w': 2 * st['w'], 'h': 2 * st['h'], 'wx': 2 * st['wx'] - 4096,
                      'wy': 2 * st['wy'] - 4096}
        if fractal:
            total = (total + 1) / 2
        out.append(min(max(total, 0.0), 1.0))
    return out


@pytest.mark.parametrize('stitch', [False, True])
@pytest.mark.parametrize('fractal', [False, True])
def test_turbulence_matches_the_specification_point_by_point(stitch, fractal):
    rng = np.random.default_rng(5)
    x = rng.uniform(10, 60, (4, 5))
    y = rng.uniform(-5, 40, (4, 5))
    tile = (10.0, -5.0, 37.0, 29.0) if stitch else None
    got = F.turbulence(x, y, (0.047, 0.11), 3, 17, fractal, tile)
    for i in range(4):
        for j in range(5):
            want = _ref_turbulence(x[i, j], y[i, j], 0.047, 0.11, 3, 17, fractal, tile)
            assert got[i, j] == pytest.approx(want, abs=1e-5)


@settings(max_examples=30, deadline=None)
@given(st.integers(-3, 3), st.integers(-3, 3), st.floats(8, 120), st.floats(8, 120),
       st.floats(0.01, 0.3), st.floats(0.01, 0.3), st.integers(1, 4), st.integers(0, 20))
def test_stitched_turbulence_meets_itself_at_the_tile_edges(mx, my, tw, th, fx, fy, octaves,
                                                            seed):
    # stitchTiles="stitch": the noise along the tile's right edge is the
    # noise along its left edge (bottom and top likewise), so tiles placed
    # side by side show no seam.  (The reference algorithm wraps the lattice
    # at whole cells, so this holds for tiles whose origin is on the
    # lattice: here at whole multiples of the tile size.)
    rng = np.random.default_rng(seed)
    tx, ty = mx * tw, my * th
    tile = (tx, ty, tw, th)
    ys = ty + rng.uniform(0, th, 16)[None, :]
    xs = tx + rng.uniform(0, tw, 16)[None, :]
    left = F.turbulence(np.full_like(ys, tx), ys, (fx, fy), octaves, seed, True, tile)
    right = F.turbulence(np.full_like(ys, tx + tw - 1e-7), ys, (fx, fy), octaves, seed, True,
                         tile)
    top = F.turbulence(xs, np.full_like(xs, ty), (fx, fy), octaves, seed, True, tile)
    bottom = F.turbulence(xs, np.full_like(xs, ty + th - 1e-7), (fx, fy), octaves, seed, True,
                          tile)
    assert np.allclose(left, right, atol=1e-4)
    assert np.allclose(top, bottom, atol=1e-4)


def test_displacement_by_a_constant_map_is_an_offset():
    img = _img(10, 12, 9)
    dmap = np.zeros((10, 12, 4), np.float32)
    dmap[..., 0] = 1.0                     # R = 1: x + scale / 2
    dmap[..., 3] = 1.0                     # A = 1: y + scale / 2
    out = F.displace(img, dmap, 4.0, 0, 3)
    assert np.array_equal(out, F.offset(img, -2, -2))


def test_morphology_dilate_and_erode_of_a_square():
    img = np.zeros((21, 21, 4), np.float32)
    img[8:13, 8:13] = 1
    d = F.morphology(img, 2, 1, 'dilate')
    assert d[..., 3].sum() == (5 + 4) * (5 + 2)
    e = F.morphology(img, 1, 1, 'erode')
    assert e[..., 3].sum() == 3 * 3
    assert np.array_equal(F.morphology(d, 2, 1, 'erode')[..., 3], img[..., 3])


# ---------------------------------------------------------------------------
# Documents
# ---------------------------------------------------------------------------

def _svg(defs, body, size=40):
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d">%s%s</svg>'
            % (size, size, defs, body)).encode()


def _render(src, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')
        return raster.render(src, **kw)


def test_invalid_filter_reference_is_not_rendered():
    img = _render(_svg('', '<rect width="40" height="40" fill="red" filter="url(#nope)"/>'))
    assert not img[..., 3].any()
    # a reference to something that is not a filter: not rendered either
    img = _render(_svg('<linearGradient id="g"/>',
                       '<rect width="40" height="40" fill="red" filter="url(#g)"/>'))
    assert not img[..., 3].any()


def test_empty_filter_and_zero_region_are_not_rendered():
    for f in ('<filter id="f"/>',
              '<filter id="f" width="-1"><feOffset/></filter>'):
        img = _render(_svg(f, '<rect width="40" height="40" fill="red" filter="url(#f)"/>'))
        assert not img[..., 3].any()


def test_flood_fills_the_subregion():
    defs = ('<filter id="f" filterUnits="userSpaceOnUse" x="0" y="0" width="40" height="40">'
            '<feFlood flood-color="#00ff00" flood-opacity="0.5" x="10" y="5" width="20" '
            'height="10"/></filter>')
    img = _render(_svg(defs, '<rect width="1" height="1" filter="url(#f)"/>'))
    a = img[..., 3]
    assert (a[5:15, 10:30] == 128).all()
    assert a.sum() == 128 * 200
    assert tuple(img[8, 15, :3]) == (0, 255, 0)


def test_offset_in_a_document_moves_by_device_pixels():
    defs = '<filter id="f" x="-1" y="-1" width="3" height="3"><feOffset dx="3" dy="2"/></filter>'
    img = _render(_svg(defs, '<rect x="10" y="10" width="10" height="10" fill="blue" '
                             'filter="url(#f)"/>'), zoom=2)
    a = img[..., 3]
    ys, xs = np.nonzero(a)
    assert (ys.min(), ys.max(), xs.min(), xs.max()) == (24, 43, 26, 45)


def test_filter_region_clips_and_default_region_is_ten_percent():
    # a huge offset moves everything outside the default region (-10%..120%)
    defs = '<filter id="f"><feOffset dx="15"/></filter>'
    img = _render(_svg(defs, '<rect x="10" y="10" width="10" height="10" fill="blue" '
                             'filter="url(#f)"/>'))
    assert not img[..., 3].any()
    defs = '<filter id="f"><feOffset dx="1"/></filter>'
    img = _render(_svg(defs, '<rect x="10" y="10" width="10" height="10" fill="blue" '
                             'filter="url(#f)"/>'))
    ys, xs = np.nonzero(img[..., 3])
    assert (xs.min(), xs.max()) == (11, 20)


def test_blur_in_document_is_translation_invariant():
    defs = '<filter id="f"><feGaussianBlur stdDeviation="2"/></filter>'
    a = _render(_svg(defs, '<rect x="8" y="8" width="10" height="10" fill="teal" '
                           'filter="url(#f)"/>', 60))
    b = _render(_svg(defs, '<rect x="28" y="18" width="10" height="10" fill="teal" '
                           'filter="url(#f)"/>', 60))
    assert np.array_equal(np.roll(a, (10, 20), (0, 1)), b)


def test_unknown_primitive_warns_and_is_skipped():
    defs = '<filter id="f"><feFoo/><feOffset/></filter>'
    with pytest.warns(raster.errors.RasterWarning):
        img = raster.render(_svg(defs, '<rect width="40" height="40" fill="red" '
                                       'filter="url(#f)"/>'
                                       '<rect width="5" height="5" fill="blue"/>'))
    assert img[2, 2, 2] == 255 and tuple(img[20, 20]) == (255, 0, 0, 255)


def test_filter_functions_resolve_to_primitives():
    _functions = P._functions
    assert _functions('url(#a) drop-shadow(rgb(0, 0, 255) 1 2)') == \
        [('url', '#a'), ('drop-shadow', 'rgb(0, 0, 255) 1 2')]
    assert _functions('blur(2') is None


def test_opacity_function_halves_alpha_and_invert_inverts():
    body = '<rect width="40" height="40" fill="#ff0000" filter="opacity(50%)"/>'
    img = _render(_svg('', body))
    assert abs(int(img[20, 20, 3]) - 128) <= 1 and tuple(img[20, 20, :3]) == (255, 0, 0)
    img = _render(_svg('', '<rect width="40" height="40" fill="#ff0000" filter="invert()"/>'))
    assert tuple(img[20, 20]) == (0, 255, 255, 255)


def test_invalid_filter_function_renders_unfiltered():
    img = _render(_svg('', '<rect width="40" height="40" fill="#ff0000" filter="blur(-2)"/>'))
    assert tuple(img[0, 0]) == (255, 0, 0, 255)


def test_filter_on_an_empty_group_can_flood():
    defs = ('<filter id="f" filterUnits="userSpaceOnUse" x="5" y="5" width="10" height="10">'
            '<feFlood flood-color="blue"/></filter>')
    img = _render(_svg(defs, '<g filter="url(#f)"/>'))
    assert img[..., 3].sum() == 255 * 100 and tuple(img[10, 10]) == (0, 0, 255, 255)
    # objectBoundingBox units on an empty group: nothing
    defs = '<filter id="f"><feFlood flood-color="blue"/></filter>'
    assert not _render(_svg(defs, '<g filter="url(#f)"/>'))[..., 3].any()


def test_tile_repeats_the_input_subregion():
    img = np.zeros((8, 8, 4), np.float32)
    img[1, 1] = 1                                    # tile (1..3) x (1..3)
    out = F.tile(img, (1, 1, 3, 3), (0, 0, 8, 8))
    assert out[1::2, 1::2, 3].all() and out[..., 3].sum() == 16


def test_color_interpolation_filters_linear_vs_srgb():
    # a half-transparent flood merged over nothing is the same in both
    # spaces; a blur of a red/blue edge differs (averaging in linear light
    # is brighter)
    def render(cif):
        defs = ('<filter id="f" color-interpolation-filters="%s"><feGaussianBlur '
                'stdDeviation="3"/></filter>' % cif)
        body = ('<g filter="url(#f)"><rect width="20" height="40" fill="red"/>'
                '<rect x="20" width="20" height="40" fill="blue"/></g>')
        return _render(_svg(defs, body)).astype(int)
    lin, srgb = render('linearRGB'), render('sRGB')
    assert lin[20, 20, 0] > srgb[20, 20, 0] + 20


def test_feimage_draws_a_referenced_element_at_the_subregion_origin():
    defs = ('<rect id="r" width="10" height="10" fill="lime"/>'
            '<filter id="f" filterUnits="userSpaceOnUse" x="5" y="20" width="30" height="20">'
            '<feImage href="#r"/></filter>')
    img = _render(_svg('<defs>%s</defs>' % defs, '<rect width="1" height="1" filter="url(#f)"/>'))
    ys, xs = np.nonzero(img[..., 3])
    assert (ys.min(), ys.max(), xs.min(), xs.max()) == (20, 29, 5, 14)


def test_recursive_feimage_drops_the_inner_filter():
    defs = ('<filter id="f"><feImage href="#r"/></filter>'
            '<rect id="r" x="5" y="5" width="10" height="10" fill="lime" filter="url(#f)"/>')
    with pytest.warns(raster.errors.RasterWarning):
        img = raster.render(_svg('<defs>%s</defs>' % defs,
                                 '<rect x="5" y="5" width="10" height="10" filter="url(#f)"/>'))
    assert img[..., 3].any()


# ---------------------------------------------------------------------------
# resvg suite cases
# ---------------------------------------------------------------------------

SUITE_CASES = [
    'filters/filter/simple-case', 'filters/filter/no-children',
    'filters/filter/invalid-FuncIRI', 'filters/filter/in-to-invalid-1',
    'filters/filter/invalid-region', 'filters/filter/negative-subregion',
    'filters/filter/color-interpolation-filters=sRGB',
    'filters/filter/in=SourceAlpha',
    'filters/feGaussianBlur/stdDeviation-with-two-values',
    'filters/feGaussianBlur/huge-stdDeviation',
    'filters/feOffset/only-dx', 'filters/feOffset/with-primitiveUnits=objectBoundingBox',
    'filters/feFlood/partial-subregion', 'filters/feFlood/with-opacity',
    'filters/feComposite/operator=xor', 'filters/feComposite/operator=arithmetic-with-some-k1-4',
    'filters/feBlend/mode=multiply', 'filters/feColorMatrix/type=hueRotate',
    'filters/feColorMatrix/type=luminanceToAlpha',
    'filters/feComponentTransfer/type=table-on-blue', 'filters/feComponentTransfer/mixed-types',
    'filters/feDropShadow/only-stdDeviation', 'filters/feMorphology/radius=10-1',
    'filters/feMerge/color-interpolation-filters=linearRGB',
    'filters/feTile/simple-case', 'filters/filter/subregion-bigger-that-region',
    'filters/filter/on-zero-sized-shape', 'filters/filter/transform-on-shape-with-filter-region',
    'filters/feGaussianBlur/complex-transform', 'filters/feColorMatrix/invalid-type',
    'filters/feMorphology/zero-radius', 'filters/feGaussianBlur/negative-stdDeviation',
    'filters/filter-functions/blur-function', 'filters/filter-functions/drop-shadow-function',
    'filters/filter-functions/drop-shadow-function-em-values',
    'filters/filter-functions/hue-rotate-function-45', 'filters/filter-functions/url-and-grayscale',
    'filters/feImage/link-to-an-element', 'filters/feImage/recursive-links-1',
    'filters/feImage/with-subregion-2', 'filters/feOffset/complex-transform',
    'filters/feConvolveMatrix/order=4-2', 'filters/feConvolveMatrix/edgeMode=none',
    'filters/feDiffuseLighting/single-light-source', 'filters/feSpotLight/custom-attributes',
    'filters/feTurbulence/seed=-20', 'filters/feTurbulence/type=fractalNoise',
    'filters/feSpecularLighting/with-feDistantLight', 'filters/fePointLight/default-attributes',
]


@pytest.mark.parametrize('case', SUITE_CASES)
def test_suite_case(case):
    base = os.path.join(SUITE, 'tests', case)
    expected = np.asarray(Image.open(base + '.png').convert('RGBA'))
    actual = _render(base + '.svg', width=expected.shape[1],
                     resources_dir=os.path.join(SUITE, 'resources'))
    r = compare_images(expected, actual)
    assert r.passed, (case, r)


def _filters_of(doc):
    """The filters of the element with id 'e' in ``doc`` (a body), or
    'not rendered'."""
    from raster.parser import build_tree
    from raster.parser.document import load_document
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')
        t = build_tree(load_document(('<svg xmlns="http://www.w3.org/2000/svg" width="100" '
                                      'height="100">%s</svg>' % doc).encode()))
    n = t.ids.get('e')
    if n is None:
        return 'not rendered'
    return [[type(p).__name__ for p in f.primitives] for f in getattr(n, 'filters', ())]


@pytest.mark.parametrize('value, expected', [
    ('url(#s) url(#missing)', [['Offset']]),          # the unusable reference left out
    ('url(#missing) url(#s)', [['Offset']]),
    ('blur(2) url(#missing)', [['GaussianBlur']]),
    ('url(#missing)', 'not rendered'),                   # nothing usable left
    ('url(#missing) url(#nothing)', 'not rendered'),
    ('url(#s),url(#s)', []),                             # syntax errors: value ignored
    ('url()', []),
    ('url(#s) url(#s)', [['Offset'], ['Offset']]),
])
def test_filter_lists_leave_unusable_references_out(value, expected):
    doc = ('<filter id="s"><feOffset dx="5"/></filter><rect id="e" width="10" height="10" '
           'filter="%s"/>' % value)
    assert _filters_of(doc) == expected


def test_an_element_drawn_by_its_own_feimage_ignores_its_filter():
    doc = ('<filter id="f"><feImage href="#e"/></filter><filter id="g"><feImage href="#e"/>'
           '</filter><rect id="e" width="10" height="10" filter="url(#f)"/>'
           '<rect id="o" width="10" height="10" filter="url(#g)"/>')
    assert _filters_of(doc) == []
    from raster.parser import build_tree
    from raster.parser.document import load_document
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')
        t = build_tree(load_document(('<svg xmlns="http://www.w3.org/2000/svg">%s</svg>'
                                      % doc).encode()))
    (f,) = t.ids['o'].filters
    assert isinstance(f.primitives[0], T.Image) and f.primitives[0].root.children


@pytest.mark.parametrize('given, used', [('0', 0.0), ('0.5', 0.5), ('-2', 1.0), (None, 1.0)])
def test_spot_light_specular_exponent(given, used):
    a = '' if given is None else ' specularExponent="%s"' % given
    doc = ('<filter id="f"><feDiffuseLighting><feSpotLight x="5" y="5" z="9"%s/>'
           '</feDiffuseLighting></filter><rect id="e" width="10" height="10" filter="url(#f)"/>'
           % a)
    from raster.parser import build_tree
    from raster.parser.document import load_document
    t = build_tree(load_document(('<svg xmlns="http://www.w3.org/2000/svg">%s</svg>'
                                  % doc).encode()))
    (f,) = t.ids['e'].filters
    assert f.primitives[0].light.specular_exponent == used


def _reuse_filter():
    """A chain whose buffers are read again after a primitive could have
    overwritten them: SourceGraphic and a named result read twice, a
    disabled blur passing its input on, sRGB and linearRGB steps."""
    src, res = T.Source, T.Result
    return T.Filter(region=(1.0, 2.0, 60.0, 44.0), primitives=[
        T.GaussianBlur(inputs=(src.GRAPHIC,), result='z', std_dev=(0.0, 0.0)),
        T.GaussianBlur(inputs=(res('z'),), result='b', std_dev=(2.5, 1.5)),
        T.GaussianBlur(inputs=(res('b'),), linear=False, std_dev=(1.0, 3.0),
                       subregion=(5.0, 6.0, 40.0, 30.0)),
        T.GaussianBlur(inputs=(T.PREVIOUS,), std_dev=(0.5, 0.5)),
        T.Composite(inputs=(res('b'), src.GRAPHIC), result='c'),
        T.GaussianBlur(inputs=(src.ALPHA,), std_dev=(2.0, 0.0)),
        T.Merge(inputs=(res('c'), T.PREVIOUS, res('z'))),
        T.GaussianBlur(inputs=(T.PREVIOUS,), std_dev=(3.0, 3.0)),
    ])


@pytest.mark.parametrize('solid', [True, False])
def test_reused_buffers_give_the_pixels_of_fresh_copies(monkeypatch, solid):
    import raster.renderer.filters as R
    from raster.pixels.canvas import Canvas
    data = _input_image(solid, (48, 64), (10, 30, 8, 50), 3, (0.2, 0.7, 0.4), 9)
    keep = data.copy()
    t = Affine.scale(1.1)
    got = apply_filters([_reuse_filter()], data, t)
    assert np.array_equal(data, keep)                    # the caller's pixels are left alone
    layer = Canvas(64, 48, dtype=np.float32)
    layer.data[...] = data
    R.filter_layer([_reuse_filter()], layer, t)
    # nothing may be overwritten: every step copies
    monkeypatch.setattr(R, '_shares', lambda img, arrays: True)
    want = apply_filters([_reuse_filter()], data, t)
    assert np.array_equal(got, want)
    ref = Canvas(64, 48, dtype=np.float32)
    ref.data[...] = data
    R.filter_layer([_reuse_filter()], ref, t)
    assert np.array_equal(layer.data, ref.data)


@pytest.mark.parametrize('plans', [(('gauss', 1.3), ('box', ((5, 2),) * 3)),
                                   (None, ('gauss', 2.0)), (('box', ((4, 2), (4, 1), (5, 2))), None)])
def test_blur_array_in_place_equals_a_new_result(plans):
    x = np.zeros((30, 40, 4), np.float32)
    x[5:20, 10:30] = _img(15, 20, seed=2)
    want = F.blur_array(x, *plans)
    y = x.copy()
    out = F.blur_array(y, *plans, in_place=True)
    assert out is y and np.array_equal(out, want)
    c = F._convert_pixels(x, F.srgb_to_linear)
    assert F._convert_pixels(x, F.srgb_to_linear, in_place=True) is x and np.array_equal(x, c)
