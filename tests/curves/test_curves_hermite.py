"""Tests of raster.curves.hermite, cardinal (Catmull-Rom) and kochanek."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from raster.curves import (Hermite, HermiteSpline, hermite_blend, hermite_basis_matrix,
                           CardinalSpline, CatmullRom, KochanekBartels, CurveError,
                           cardinal_matrix)

seeds = st.integers(0, 2**32 - 1)


def pts(seed, n, d=2):
    return np.random.default_rng(seed).normal(size=(n, d)) * 5


# -- Hermite ---------------------------------------------------------------
def test_blending_closed_forms():
    t = np.linspace(0, 1, 9)
    expect = np.column_stack([2 * t**3 - 3 * t**2 + 1, -2 * t**3 + 3 * t**2,
                              t**3 - 2 * t**2 + t, t**3 - t**2])
    np.testing.assert_allclose(hermite_blend(t), expect, atol=1e-15)
    np.testing.assert_allclose(hermite_blend(t)[:, :2].sum(1), 1.0)
    pw = np.column_stack([t**3, t**2, t, np.ones_like(t)])
    np.testing.assert_allclose(pw @ hermite_basis_matrix(), expect, atol=1e-15)


def test_hermite_arch_closed_form():
    # P0=(0,0), P1=(1,0), T0=(0,3), T1=(0,-3):
    #   x = -2t^3 + 3t^2 (smoothstep), y = 3t(1 - t)
    h = Hermite([0, 0], [1, 0], [0, 3], [0, -3])
    t = np.linspace(0, 1, 11)
    np.testing.assert_allclose(h.eval(t), np.column_stack([-2 * t**3 + 3 * t**2, 3 * t * (1 - t)]),
                               atol=1e-14)
    np.testing.assert_allclose(h.to_bezier().ctrl, [[0, 0], [0, 1], [1, 1], [1, 0]])
    np.testing.assert_allclose(h.power_coeffs(), [[0, 0], [0, 3], [3, -3], [-2, 0]])
    np.testing.assert_allclose(h.blending(0.5), [0.5, 0.5, 0.125, -0.125])


@settings(max_examples=100, deadline=None)
@given(seeds, st.sampled_from([2, 3]))
def test_hermite_to_bezier_exact_and_end_conditions(seed, d):
    p = pts(seed, 4, d)
    h = Hermite(p[0], p[1], p[2], p[3])
    t = np.linspace(0, 1, 33)
    np.testing.assert_allclose(h.to_bezier().eval(t), h.eval(t), atol=1e-9)
    np.testing.assert_allclose(h.eval([0, 1]), p[:2], atol=1e-12)
    np.testing.assert_allclose(h.tangent([0.0, 1.0]), p[2:], atol=1e-9)


def test_hermite_errors():
    with pytest.raises(CurveError):
        Hermite([0, 0], [1, 1], [0, 0], [1, 1, 1])
    with pytest.raises(CurveError):
        Hermite([0, np.inf], [1, 1], [0, 0], [1, 1])
    with pytest.raises(CurveError):
        Hermite([0, 0], [1, 1], [0, 0], [1, 1]).eval(1.01)
    with pytest.raises(CurveError):
        HermiteSpline([[0, 0], [1, 1], [2, 2]], [[1, 1]], [[1, 1]])


# -- cardinal / Catmull-Rom -------------------------------------------------
def test_catmull_rom_equally_spaced_line_is_linear():
    # interior segment of equally spaced collinear points: x(t) = 1 + t exactly
    c = CatmullRom([[0, 0], [1, 0], [2, 0], [3, 0]], ends='interior')
    t = np.linspace(0, 1, 11)
    np.testing.assert_allclose(c.eval(t), np.column_stack([1 + t, 0 * t]), atol=1e-15)


def test_catmull_rom_tangent_formula_and_interpolation():
    p = np.array([[0, 0], [1, 2], [3, 3], [4, 0], [6, 1]], float)
    c = CatmullRom(p)
    np.testing.assert_allclose(c.eval(np.arange(5.0)), p, atol=1e-12)
    for i in (1, 2, 3):
        np.testing.assert_allclose(c.tangent(float(i)), (p[i + 1] - p[i - 1]) / 2, atol=1e-12)
    # duplicated end neighbours: T0 = (P1 - P0) / 2
    np.testing.assert_allclose(c.tangent(0.0), (p[1] - p[0]) / 2)


@settings(max_examples=60, deadline=None)
@given(seeds, st.integers(2, 9), st.floats(-1, 1), st.sampled_from(['duplicate', 'closed']))
def test_cardinal_properties(seed, n, c, ends):
    if ends == 'closed':
        n = max(n, 3)
    p = pts(seed, n)
    s = CardinalSpline(p, tension=c, ends=ends)
    keys = np.arange(len(s.keys), dtype=float)
    np.testing.assert_allclose(s.eval(keys), s.keys, atol=1e-9)
    t = np.linspace(*s.domain, 97)
    np.testing.assert_allclose(s.to_beziers().eval(t), s.eval(t), atol=1e-9)
    joints = s.continuity(1e-9)
    assert all(j.C >= 1 for j in joints)
    assert len(joints) == (len(s.keys) - 1 if ends == 'closed' else len(s.keys) - 2)
    # the tension scales every tangent by (1 - c) relative to Catmull-Rom
    np.testing.assert_allclose(s.out_tangents, (1 - c) * CatmullRom(p, ends=ends).out_tangents,
                               atol=1e-12)


def test_catmull_rom_matrix_closed_form():
    # the classic Catmull-Rom matrix (1/2)[[-1,3,-3,1],[2,-5,4,-1],[-1,0,1,0],[0,2,0,0]]
    np.testing.assert_allclose(cardinal_matrix(0.0) * 2, [[-1, 3, -3, 1], [2, -5, 4, -1],
                                                          [-1, 0, 1, 0], [0, 2, 0, 0]])


@settings(max_examples=40, deadline=None)
@given(seeds, st.floats(-1, 1))
def test_cardinal_blending_reproduces_curve(seed, c):
    p = pts(seed, 7)
    s = CardinalSpline(p, c, ends='interior')
    t = np.linspace(0, 4, 37)
    w = s.blending(t)
    i = np.clip(np.floor(t), 0, 3).astype(int)
    np.testing.assert_allclose(np.einsum('mk,mkd->md', w, p[i[:, None] + np.arange(4)]),
                               s.eval(t), atol=1e-12)
    np.testing.assert_allclose(w.sum(1), 1.0, atol=1e-12)


def test_tension_one_gives_zero_tangents():
    s = CardinalSpline([[0, 0], [1, 1], [2, 0]], tension=1.0)
    bz = s.to_beziers().ctrl
    np.testing.assert_array_equal(bz[:, 0], bz[:, 1])
    np.testing.assert_array_equal(bz[:, 2], bz[:, 3])


def test_closed_catmull_rom_is_a_loop():
    p = pts(7, 5)
    s = CatmullRom(p, ends='closed')
    assert s.domain == (0.0, 5.0)
    np.testing.assert_allclose(s.eval(0.0), s.eval(5.0))
    np.testing.assert_allclose(s.tangent(0.0), s.tangent(5.0), atol=1e-12)


def test_cardinal_errors():
    with pytest.raises(CurveError):
        CatmullRom([[0, 0], [1, 1], [2, 2]], ends='interior')
    with pytest.raises(CurveError):
        CatmullRom([[0, 0], [1, 1]], ends='sideways')
    with pytest.raises(CurveError):
        CatmullRom([[0, 0]])
    with pytest.raises(CurveError):
        CardinalSpline([[0, 0], [1, 1]], tension='hard')


# -- Kochanek-Bartels ---------------------------------------------------------
@settings(max_examples=60, deadline=None)
@given(seeds, st.integers(2, 8), st.sampled_from(['duplicate', 'interior', 'closed']))
def test_kb_zero_parameters_is_catmull_rom(seed, n, ends):
    n = max(n, 4) if ends == 'interior' else n
    n = max(n, 3) if ends == 'closed' else n
    p = pts(seed, n, 3)
    t = np.linspace(0, len(CatmullRom(p, ends=ends).keys) - 1, 41)
    np.testing.assert_allclose(KochanekBartels(p, ends=ends).eval(t),
                               CatmullRom(p, ends=ends).eval(t), atol=1e-12)


def test_kb_bias_one_uses_incoming_chord():
    # (0,0), (1,1), (2,0) with bias 1: both tangents at the middle key = P1 - P0 = (1, 1)
    kb = KochanekBartels([[0, 0], [1, 1], [2, 0]], bias=[0, 1, 0])
    bz = kb.to_beziers().ctrl
    np.testing.assert_allclose(3 * (bz[0, 3] - bz[0, 2]), [1, 1])
    np.testing.assert_allclose(3 * (bz[1, 1] - bz[1, 0]), [1, 1])


def test_kb_tension_one_and_continuity_corner():
    p = [[0, 0], [1, 1], [2, 0], [3, 1]]
    kb = KochanekBartels(p, tension=1.0)
    np.testing.assert_allclose(kb.out_tangents, 0.0)
    corner = KochanekBartels(p, continuity=[0, -1, 0, 0])
    j = corner.continuity()
    assert j[0].C == 0 and j[0].G == 0 and j[0].angle > 0.1
    assert j[1].C >= 1


@settings(max_examples=60, deadline=None)
@given(seeds, st.integers(3, 8))
def test_kb_per_key_parameters_convert_exactly(seed, n):
    r = np.random.default_rng(seed)
    p = r.normal(size=(n, 2))
    kb = KochanekBartels(p, r.uniform(-1, 1, n), r.uniform(-1, 1, n), r.uniform(-1, 1, n))
    t = np.linspace(0, n - 1, 77)
    np.testing.assert_allclose(kb.to_beziers().eval(t), kb.eval(t), atol=1e-9)
    np.testing.assert_allclose(kb.eval(np.arange(n, dtype=float)), p, atol=1e-12)


def test_kb_errors():
    with pytest.raises(CurveError):
        KochanekBartels([[0, 0], [1, 1], [2, 0]], tension=[0, 1])
    with pytest.raises(CurveError):
        KochanekBartels([[0, 0], [1, 1], [2, 0]], bias=np.nan)
