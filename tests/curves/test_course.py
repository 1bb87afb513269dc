"""The worked examples and exercises of the course chapter on curves
(``../shared/course/000_a431c0e315cc02b7.txt``), solved through the
``curve`` command and its ``--json`` / ``--explain`` output, with the right
answers.

Expected values are worked by hand here from the Bernstein form (the
numbers in the comments), never taken from the program's output.

Two printed answers of the course are wrong (called out where they occur):

* the cubic through A(1,1) B(2,3) C(4,3) D(6,4): the table prints
  y(0.8) = 2.496; it is 3.496 (also y(0.6) is printed 3.083 for 3.088);
* the worked example with B0 = (2, 0), B1 = (3, 3), B2 = (6, 3), B3 = (8, 1)
  is evaluated as if B0 were (1, 0): P(0) = [1, 0], P(0.2) = [2.304, 1.448],
  P(0.5) = [4.5, 2.375], P(0.7) = [5.984, ...] are the x values of that
  other curve (also y(0.7) is printed 2.333 for 2.233).
"""

import json

import numpy as np
import pytest

from raster_cli.curve import main


def run_json(capsys, *argv):
    code = main(list(argv) + ['--json'])
    out, err = capsys.readouterr()
    assert code == 0, err
    return json.loads(out)


def points(obj):
    return np.array([p['point'] for p in obj['points']])


def run_text(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert code == 0, err
    return out


def test_cubic_A_B_C_D_at_quarters(capsys):
    # A(1,1) B(2,3) C(4,3) D(6,4): x = 1 + 3t + 3t^2 - t^3, y = 1 + 6t - 6t^2 + 3t^3
    obj = run_json(capsys, 'bezier', '1,1 2,3 4,3 6,4', '--at', '0,0.25,0.5,0.75,1', '--poly')
    want = [[1, 1], [1.921875, 2.171875], [3.125, 2.875], [4.515625, 3.390625], [6, 4]]
    np.testing.assert_allclose(points(obj), want, atol=1e-12)
    np.testing.assert_allclose(obj['polynomial'][0]['coefficients'],
                               [[1, 3, 3, -1], [1, 6, -6, 3]], atol=1e-12)


def test_cubic_A_B_C_D_table_and_the_printed_mistake(capsys):
    # the course's table for u = 0, 0.2, ..., 1.  PRINTED MISTAKE: y(0.8) is
    # printed 2.496; 1 + 6(0.8) - 6(0.64) + 3(0.512) = 3.496 (and y(0.6) is
    # printed 3.083: 1 + 3.6 - 2.16 + 0.648 = 3.088)
    obj = run_json(capsys, 'bezier', '1,1 2,3 4,3 6,4', '--step', '0.2')
    want = [[1, 1], [1.712, 1.984], [2.616, 2.632], [3.664, 3.088], [4.808, 3.496], [6, 4]]
    np.testing.assert_allclose(points(obj), want, atol=1e-12)
    assert abs(points(obj)[4, 1] - 2.496) > 0.99
    text = run_text(capsys, 'bezier', '1,1 2,3 4,3 6,4', '--step', '0.2', '--explain')
    assert 'y(0.8) = 0.008(1) + 0.096(3) + 0.384(3) + 0.512(4) = ' \
           '0.008 + 0.288 + 1.152 + 2.048 = 3.496' in text
    assert 'x(t) = (1-t)^3 + 6t(1-t)^2 + 12t^2(1-t) + 6t^3' in text      # as in the notes
    assert 'y(t) = (1-t)^3 + 9t(1-t)^2 + 9t^2(1-t) + 4t^3' in text


def test_worked_example_B0_2_0_and_the_printed_mistake(capsys):
    # B0(2,0) B1(3,3) B2(6,3) B3(8,1) at t = 0, 0.2, 0.5, 0.7, 1:
    # t = 0.2: 0.512 (2,0) + 0.384 (3,3) + 0.096 (6,3) + 0.008 (8,1) = (2.816, 1.448)
    # t = 0.5: (2 + 9 + 18 + 8) / 8, (0 + 9 + 9 + 1) / 8 = (4.625, 2.375)
    # t = 0.7: 0.027 (2,0) + 0.189 (3,3) + 0.441 (6,3) + 0.343 (8,1) = (6.011, 2.233)
    obj = run_json(capsys, 'bezier', '2,0 3,3 6,3 8,1', '--at', '0,0.2,0.5,0.7,1')
    want = [[2, 0], [2.816, 1.448], [4.625, 2.375], [6.011, 2.233], [8, 1]]
    np.testing.assert_allclose(points(obj), want, atol=1e-12)
    # PRINTED MISTAKE: the notes' x values 1, 2.304, 4.5, 5.984 are those of
    # the curve with B0 = (1, 0); their y(0.7) = 2.333 is a slip for 2.233
    wrong = run_json(capsys, 'bezier', '1,0 3,3 6,3 8,1', '--at', '0,0.2,0.5,0.7')
    np.testing.assert_allclose(points(wrong)[:, 0], [1, 2.304, 4.5, 5.984], atol=1e-12)


def test_control_points_10_12_at_0_3(capsys):
    # (1-0.3)^3 = 0.343, 3(0.3)(0.49) = 0.441, 3(0.09)(0.7) = 0.189, 0.027
    obj = run_json(capsys, 'bezier', '10,12 15,28 22,35 28,9', '--at', '0.3')
    np.testing.assert_allclose(points(obj), [[14.959, 23.322]], atol=1e-12)


def test_control_points_10_15_at_quarters(capsys):
    # x = 10 + 15t (equally spaced x); y = (15 B0 + 25 B1 + 35 B2 + 15 B3)
    obj = run_json(capsys, 'bezier', '10,15 15,25 20,35 25,15', '--at', '0.25,0.5,0.75')
    np.testing.assert_allclose(points(obj), [[13.75, 1410 / 64], [17.5, 26.25],
                                             [21.25, 1590 / 64]], atol=1e-12)


def test_polynomial_of_0_0_3_1_5_2_8_1(capsys):
    # x(t) = 9t - 3t^2 + 2t^3, y(t) = 3t - 2t^3
    obj = run_json(capsys, 'bezier', '0,0 3,1 5,2 8,1', '--at', '0.25,0.5,0.75', '--poly')
    np.testing.assert_allclose(obj['polynomial'][0]['coefficients'],
                               [[0, 9, -3, 2], [0, 3, 0, -2]], atol=1e-12)
    np.testing.assert_allclose(points(obj), [[2.09375, 0.71875], [4, 1.25],
                                             [5.90625, 1.40625]], atol=1e-12)


def test_3d_bezier_through_origin_and_minus2_1_1(capsys):
    # passes through (0,0,0) and (-2,1,1), controlled by (7,5,2) and (2,0,1)
    # (in that order, as the question gives them; the worked solution's
    # "Given" list swaps them but then substitutes them in this order):
    # x = 21t - 36t^2 + 13t^3, y = 15t - 30t^2 + 16t^3, z = 6t - 9t^2 + 4t^3
    obj = run_json(capsys, 'bezier', '0,0,0 7,5,2 2,0,1 -2,1,1', '--poly', '--at', '0,1')
    np.testing.assert_allclose(obj['polynomial'][0]['coefficients'],
                               [[0, 21, -36, 13], [0, 15, -30, 16], [0, 6, -9, 4]], atol=1e-12)
    np.testing.assert_allclose(points(obj), [[0, 0, 0], [-2, 1, 1]], atol=1e-12)


def test_control_points_10_10_at_quarters(capsys):
    obj = run_json(capsys, 'bezier', '10,10 15,25 20,30 25,5', '--at', '0.25,0.5,0.75')
    np.testing.assert_allclose(points(obj), [[13.75, 1220 / 64], [17.5, 22.5],
                                             [21.25, 1180 / 64]], atol=1e-12)


def test_control_points_2_10_at_quarters_and_plot(capsys, tmp_path):
    obj = run_json(capsys, 'bezier', '2,10 6,20 12,5 16,15', '--at', '0.25,0.5,0.75', '--plot',
                   str(tmp_path / 'c.png'))
    np.testing.assert_allclose(points(obj), [[340 / 64, 870 / 64], [9, 12.5],
                                             [812 / 64, 730 / 64]], atol=1e-12)
    assert (tmp_path / 'c.png').stat().st_size > 1000


def test_control_points_1_1_at_0_2(capsys):
    # 0.512 (1,1) + 0.384 (4,6) + 0.096 (8,-3) + 0.008 (12,2)
    obj = run_json(capsys, 'bezier', '1,1 4,6 8,-3 12,2', '--at', '0.2')
    np.testing.assert_allclose(points(obj), [[2.912, 2.544]], atol=1e-12)


def test_quadratic_2_6_6_8_9_12(capsys):
    # x = 2 + 8t - t^2, y = 6 + 4t + 2t^2; P(0.8) = (7.76, 10.48) as printed
    obj = run_json(capsys, 'bezier', '2,6 6,8 9,12', '--at', '0.8', '--poly')
    np.testing.assert_allclose(points(obj), [[7.76, 10.48]], atol=1e-12)
    np.testing.assert_allclose(obj['polynomial'][0]['coefficients'], [[2, 8, -1], [6, 4, 2]],
                               atol=1e-12)
    text = run_text(capsys, 'bezier', '2,6 6,8 9,12', '--at', '0.8', '--explain')
    assert 'B_2,1(0.8) = 2*(0.8)*(0.2) = 0.32' in text
    assert 'P(0.8) = (7.76, 10.48)' in text


def test_tangent_at_half(capsys):
    # P'(0.5) = 3 [0.25 (2,1) + 0.5 (3,1) + 0.25 (1,-1)] = (6.75, 1.5); dy/dx = 0.222
    obj = run_json(capsys, 'bezier', '0,0 2,1 5,2 6,1', '--at', '0.5', '--tangent')
    p = obj['points'][0]
    np.testing.assert_allclose(p['tangent'], [6.75, 1.5], atol=1e-12)
    assert p['slope'] == pytest.approx(1.5 / 6.75, abs=1e-12)


def test_derive_the_hermite_matrix(capsys):
    # the exercise "Derive Hermite matrix": the conditions, the solved
    # coefficients and M_H, then the blending functions
    text = run_text(capsys, 'hermite', '0,0 1,0', '--tangents', '0,3 0,-3', '--at', '0.5',
                    '--explain')
    for line in ("P'(1) = 3 a3 + 2 a2 + a1", "a2 = -3 P(0) + 3 P(1) - 2 P'(0) - P'(1)",
                 "a3 = 2 P(0) - 2 P(1) + P'(0) + P'(1)", '| -3  3 -2 -1 |',
                 "(t^3 - 2t^2 + t) P'(0) + (t^3 - t^2) P'(1)"):
        assert line in text, line
    # h00(0.5) = h01(0.5) = 0.5, h10 = 0.125, h11 = -0.125; P(0.5) = (0.5, 0.75)
    obj = run_json(capsys, 'hermite', '0,0 1,0', '--tangents', '0,3 0,-3', '--at', '0.5',
                   '--blend')
    assert obj['points'][0]['blend'] == [0.5, 0.5, 0.125, -0.125]
    assert obj['points'][0]['point'] == [0.5, 0.75]


def test_blending_functions_of_the_parametric_cubic(capsys):
    text = run_text(capsys, 'bezier', '1,1 2,3 4,3 6,4', '--explain')
    for line in ('B_3,0(t) = 3!/(0! 3!) t^0 (1-t)^3 = (1-t)^3',
                 'B_3,1(t) = 3!/(1! 2!) t^1 (1-t)^2 = 3t(1-t)^2',
                 'B_3,2(t) = 3!/(2! 1!) t^2 (1-t)^1 = 3t^2(1-t)',
                 'B_3,3(t) = 3!/(3! 0!) t^3 (1-t)^0 = t^3',
                 'P(t) = (1-t)^3 P0 + 3t(1-t)^2 P1 + 3t^2(1-t) P2 + t^3 P3'):
        assert line in text, line


def test_cubic_spline_interpolation_steps(capsys):
    # samples (0,0),(1,1),(2,0),(3,1), h = 1, natural ends: the system
    # 4 M1 + M2 = 6(-1 - 1) = -12, M1 + 4 M2 = 12 gives M1 = -4, M2 = 4
    text = run_text(capsys, 'natural', '0,0 1,1 2,0 3,1', '--function', '--at', '0.5,1.5',
                    '--explain')
    assert '1 M0 + 4 M1 + 1 M2 = -12' in text and '1 M1 + 4 M2 + 1 M3 = 12' in text
    assert 'M0 = 0, M1 = -4, M2 = 4, M3 = 0' in text
    # on [0, 1]: S(x) = x + (5/3 - 1) ... = (5/3) x - (2/3) x^3: S(0.5) = 0.75
    obj = run_json(capsys, 'natural', '0,0 1,1 2,0 3,1', '--function', '--at', '0.5,1.5')
    np.testing.assert_allclose(points(obj), [[0.5, 5 / 6 - 1 / 12], [1.5, 0.5]], atol=1e-12)


def test_order_of_continuity(capsys):
    # Catmull-Rom through 4 keys: C1 at the joints (tangents shared,
    # curvature not); a Kochanek-Bartels continuity of 0.5 breaks C1
    obj = run_json(capsys, 'catmull-rom', '0,0 1,2 3,2 4,0', '--continuity')
    assert [(j['C'], j['G']) for j in obj['joints']] == [(1, 1), (1, 1)]
    text = run_text(capsys, 'catmull-rom', '0,0 1,2 3,2 4,0', '--explain', '--at', '0.5')
    assert "A'(1) = (1.5, 1),  B'(1) = (1.5, 1)" in text
    assert "A''(1) = (1, -6),  B''(1) = (3, -2)" in text
    assert 'joint 0 at t = 1: C1, G1' in text
    obj = run_json(capsys, 'kochanek-bartels', '0,0 1,2 3,2 4,0', '--continuity', '0.5',
                   '--joints')
    assert [j['C'] for j in obj['joints']] == [0, 0]
