"""The Gaussian pass of the blur in blocks of columns (issue 17: the padded
copy and the products are block-sized, not layer-sized)."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import raster.pixels.effects as fx


def _reference(a, s, axis):
    """The truncated, renormalised Gaussian of deviation ``s`` along
    ``axis`` with zeros outside, in float64 (np.convolve per line)."""
    r = max(1, int(np.ceil(4.0 * s)))
    x = np.arange(-r, r + 1, dtype=np.float64)
    k = np.exp(-0.5 * (x / s) ** 2)
    k /= k.sum()
    return np.apply_along_axis(lambda v: np.convolve(v, k, mode='same'), axis,
                               a.astype(np.float64))


@pytest.mark.parametrize('shape, axis', [((40,), 0), ((23, 31), 0), ((23, 31), 1),
                                         ((17, 29, 4), 0), ((17, 29, 4), 1)])
def test_gauss_axis_is_the_truncated_gaussian(shape, axis):
    rng = np.random.default_rng(7)
    a = rng.random(shape, np.float32)
    got = fx._gauss_axis(a, 1.3, axis)
    assert got.dtype == np.float32 and got.shape == a.shape
    np.testing.assert_allclose(got, _reference(a, 1.3, axis), rtol=0, atol=1e-5)


@settings(max_examples=40, deadline=None)
@given(st.integers(1, 40), st.integers(1, 40), st.sampled_from([1, 4]),
       st.floats(0.3, 3.0), st.integers(0, 1), st.integers(64, 4096), st.integers(0, 2**31))
def test_gauss_axis_does_not_depend_on_the_blocks(h, w, c, s, axis, block, seed):
    # every output is the same float32 sum in the same order whatever the
    # block size: the blocked pass equals one block holding everything
    a = np.random.default_rng(seed).random((h, w, c), np.float32)
    old = fx._BLOCK_BYTES
    try:
        fx._BLOCK_BYTES = block
        small = fx._gauss_axis(a, s, axis)
        fx._BLOCK_BYTES = 1 << 40
        whole = fx._gauss_axis(a, s, axis)
    finally:
        fx._BLOCK_BYTES = old
    np.testing.assert_array_equal(small, whole)
