"""Affine transforms (raster.geometry.transform): composition order, exact
right angles, inverses, singular values, the accepted spellings."""

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from raster.errors import TransformError
from raster.geometry.transform import IDENTITY, Affine, as_affine


# -- transforms -------------------------------------------------------------------

def test_composition_order_matches_svg_transform_lists():
    """transform="translate(10 0) scale(2)" maps (1, 1) to (12, 2)."""
    t = Affine.translate(10, 0) @ Affine.scale(2)
    assert t.apply([[1.0, 1.0]]).tolist() == [[12.0, 2.0]]


def test_rotate_about_a_centre_and_exact_right_angles():
    t = Affine.rotate(90, 10, 10)
    assert t.apply([[20.0, 10.0]]).tolist() == [[10.0, 20.0]]
    assert tuple(Affine.rotate(180)) == (-1, 0, 0, -1, 0, 0)


def test_skews():
    assert Affine.skew_x(45).apply([[0.0, 1.0]])[0].tolist() == pytest.approx([1.0, 1.0])
    assert Affine.skew_y(45).apply([[1.0, 0.0]])[0].tolist() == pytest.approx([1.0, 1.0])


finite = st.floats(-100, 100, allow_nan=False)


@settings(max_examples=100, deadline=None)
@given(st.tuples(finite, finite, finite, finite, finite, finite))
def test_inverse_round_trip(vals):
    t = Affine(*vals)
    assume(abs(t.determinant) > 1e-3)
    pts = np.array([[1.0, 2.0], [-3.0, 0.5]])
    assert np.allclose((t.inverse() @ t).apply(pts), pts, atol=1e-6)


@settings(max_examples=100, deadline=None)
@given(st.tuples(finite, finite, finite, finite))
def test_singular_values_bound_every_stretch(abcd):
    """min_scale <= |T v| / |v| <= max_scale for every direction v."""
    t = Affine(*abcd, 0, 0)
    ang = np.linspace(0, 2 * np.pi, 361)
    v = np.stack([np.cos(ang), np.sin(ang)], 1)
    lens = np.hypot(*t.apply_vector(v).T)
    assert lens.max() <= t.max_scale() * (1 + 1e-9) + 1e-9
    assert lens.min() >= t.min_scale() * (1 - 1e-9) - 1e-9
    assert t.mean_scale() == pytest.approx(math.sqrt(t.max_scale() * t.min_scale()), abs=1e-6)


def test_as_affine_accepts_common_spellings_and_refuses_others():
    assert as_affine(None) is IDENTITY
    assert as_affine((2, 0, 0, 2, 1, 1)) == Affine(2, 0, 0, 2, 1, 1)
    assert as_affine([[2, 0, 1], [0, 2, 1]]) == Affine(2, 0, 0, 2, 1, 1)
    for bad in ('abc', [1, 2, 3], [[1, 2], [3, 4]]):
        with pytest.raises(TransformError):
            as_affine(bad)
    with pytest.raises(TransformError):
        Affine(math.nan)
    for bad in ('a', None, [1, 2]):
        with pytest.raises(TransformError, match='must be numbers'):
            Affine(1, bad)
    with pytest.raises(TransformError):
        Affine.scale(0).inverse()


@pytest.mark.parametrize('k', range(6))
@pytest.mark.parametrize('bad', [math.inf, -math.inf, math.nan])
def test_every_non_finite_value_is_refused(k, bad):
    vals = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0]
    vals[k] = bad
    with pytest.raises(TransformError, match='non-finite'):
        Affine(*vals)
    # a product that overflows is refused too, one that is large is not
    big = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0]
    big[k] = 1e300
    with pytest.raises(TransformError, match='non-finite'):
        Affine(1e300, 1e300, 1e300, 1e300, 1e300, 1e300) @ Affine(*big)
    t = Affine(*big) @ Affine(2, 0, 0, 2, 0, 0)
    assert max(map(abs, t)) == pytest.approx(2e300 if k < 4 else 1e300)


def test_max_scale_has_no_cancellation_near_equal_singular_values():
    """(0 12; 12 eps): singular values 12 +- eps/2; the old s^2/4 - det^2
    formula lost every digit of the difference."""
    t = Affine(0.0, 12.0, 12.0, 1.192092896e-07, 0, 0)
    v = np.array([[math.sqrt(0.5), math.sqrt(0.5)]])
    assert np.hypot(*t.apply_vector(v).T)[0] <= t.max_scale() * (1 + 1e-12)


def test_affine_pickles_and_hashes_by_value():
    import pickle
    t = Affine(1.5, 0.25, -2.0, 3.0, 4.0, -5.0)
    u = pickle.loads(pickle.dumps(t))
    assert u == t and hash(u) == hash(t) and u is not t
    assert Affine(0.0, 0, 0, 1, 0, 0) == Affine(-0.0, 0, 0, 1, 0, 0)
    assert len({t, u, Affine(1.5, 0.25, -2.0, 3.0, 4.0, -5.5)}) == 2
