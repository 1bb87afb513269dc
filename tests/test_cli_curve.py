"""Tests of the ``curve`` command (raster_cli.curve)."""

import json
import subprocess
import sys

import numpy as np
import pytest

from raster_cli.curve import main, parse_points

CUBIC = '1,1 2,3 4,3 6,4'


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def table(out):
    """Numeric rows of the first table (skips the header lines)."""
    rows = []
    for line in out.splitlines()[2:]:
        try:
            rows.append([float(v) for v in line.split()])
        except ValueError:
            break
    return np.array(rows)


def test_bezier_table_hand_values(capsys):
    # B(t) = (1-t)^3 (1,1) + 3t(1-t)^2 (2,3) + 3t^2(1-t) (4,3) + t^3 (6,4)
    # t = 0.5: ((1 + 6 + 12 + 6) / 8, (1 + 9 + 9 + 4) / 8) = (3.125, 2.875)
    code, out, err = run(capsys, 'bezier', CUBIC, '--at', '0,0.25,0.5,0.75,1')
    assert code == 0 and err == ''
    rows = table(out)
    assert rows.shape == (5, 3)
    np.testing.assert_allclose(rows[2], [0.5, 3.125, 2.875])
    np.testing.assert_allclose(rows[[0, -1], 1:], [[1, 1], [6, 4]])


def test_bezier_json_with_tangents(capsys):
    code, out, _ = run(capsys, 'bezier', CUBIC, '--at', '0,0.5,1', '--tangent', '--json')
    assert code == 0
    obj = json.loads(out)
    assert [p['t'] for p in obj['points']] == [0, 0.5, 1]
    assert obj['points'][1]['point'] == [3.125, 2.875]
    # end tangents 3 (P1 - P0) = (3, 6) and 3 (P3 - P2) = (6, 3)
    assert obj['points'][0]['tangent'] == [3, 6]
    assert obj['points'][2]['tangent'] == [6, 3]
    assert obj['points'][0]['slope'] == 2.0


def test_step_and_3d(capsys):
    code, out, _ = run(capsys, 'bezier', '0,0,0 1,0,1 1,1,2', '--step', '0.2', '--json')
    obj = json.loads(out)
    assert code == 0 and obj['dimension'] == 3
    np.testing.assert_allclose([p['t'] for p in obj['points']], [0, .2, .4, .6, .8, 1])
    np.testing.assert_allclose(obj['points'][-1]['point'], [1, 1, 2])


def test_poly_and_blend(capsys):
    code, out, _ = run(capsys, 'bezier', CUBIC, '--at', '0.5', '--poly', '--blend')
    assert code == 0
    # x(t) = 1 + 3t + 3t^2 - t^3, y(t) = 1 + 6t - 6t^2 + 3t^3
    assert 'x(u) = 1 + 3*u + 3*u^2 - u^3' in out
    assert 'y(u) = 1 + 6*u - 6*u^2 + 3*u^3' in out
    np.testing.assert_allclose(table(out)[0, 3:], [0.125, 0.375, 0.375, 0.125])


def test_hermite(capsys):
    code, out, _ = run(capsys, 'hermite', '0,0 1,0', '--tangents', '0,3 0,-3', '--at', '0.5',
                       '--json', '--blend')
    obj = json.loads(out)
    assert code == 0
    assert obj['points'][0]['point'] == [0.5, 0.75]
    assert obj['points'][0]['blend'] == [0.5, 0.5, 0.125, -0.125]


@pytest.mark.parametrize('family,extra', [
    ('cardinal', ['--tension', '0.5']),
    ('catmull-rom', []),
    ('kochanek-bartels', ['--tension', '0.1', '--continuity', '0.2', '--bias', '-0.3']),
])
def test_interpolating_families_pass_through_keys(capsys, family, extra):
    code, out, _ = run(capsys, family, '0,0 1,2 3,2 4,0', '--step', '1', '--json', *extra)
    obj = json.loads(out)
    assert code == 0 and obj['domain'] == [0, 3]
    np.testing.assert_allclose([p['point'] for p in obj['points']],
                               [[0, 0], [1, 2], [3, 2], [4, 0]], atol=1e-12)


def test_kb_continuity_value_vs_joint_report(capsys):
    code, out, _ = run(capsys, 'kochanek-bartels', '0,0 1,2 3,2 4,0', '--continuity', '0.5',
                       '--joints', '--json')
    obj = json.loads(out)
    assert [j['C'] for j in obj['joints']] == [0, 0]
    code, out, _ = run(capsys, 'catmull-rom', '0,0 1,2 3,2 4,0', '--continuity')
    assert code == 0 and 'C1 G1' in out


def test_bspline_knots_and_domain(capsys):
    # quadratic, knots 0,0,0,1,2,3,3,3: on [0,1] the first span; C(0.5) with
    # N = (0.25, 0.625, 0.125) of P0..P2 = (0,0),(1,2),(3,2) -> (1.0, 1.5)
    code, out, _ = run(capsys, 'bspline', '0,0 1,2 3,2 4,0 5,1', '--degree', '2', '--knots',
                       '0,0,0,1,2,3,3,3', '--at', '0.5,3', '--json')
    obj = json.loads(out)
    assert code == 0 and obj['domain'] == [0, 3]
    np.testing.assert_allclose(obj['points'][0]['point'], [1.0, 1.5])
    np.testing.assert_allclose(obj['points'][1]['point'], [5, 1])


def test_beta_reduces_to_bspline(capsys):
    _, a, _ = run(capsys, 'beta', '0,0 1,2 3,2 4,0 5,1', '--step', '0.25', '--json')
    _, b, _ = run(capsys, 'bspline', '0,0 1,2 3,2 4,0 5,1', '--knots', '0,1,2,3,4,5,6,7,8',
                  '--step', '0.25', '--json')
    pa = [p['point'] for p in json.loads(a)['points']]
    pb = [p['point'] for p in json.loads(b)['points']]
    np.testing.assert_allclose(pa, pb, atol=1e-12)


def test_natural_function_and_parametric(capsys):
    # samples (0,0),(1,1),(2,0): y = -x^3/2 + 3x/2 on [0, 1]
    code, out, _ = run(capsys, 'natural', '0,0 1,1 2,0', '--function', '--at', '0.5',
                       '--tangent', '--json')
    obj = json.loads(out)
    assert code == 0
    assert obj['points'][0]['point'] == [0.5, 0.6875]
    assert obj['points'][0]['slope'] == pytest.approx(-1.5 * 0.25 + 1.5)
    code, out, _ = run(capsys, 'natural', '0,0 1,1 2,0', '--param', 'uniform', '--at', '0.5')
    np.testing.assert_allclose(table(out)[0], [0.5, 1, 1])


@pytest.mark.parametrize('argv,needle', [
    (['bezier', '1,1'], 'at least 2'),
    (['bezier', '1,1 2,x'], "parse coordinate 'x'"),
    (['bezier', '1,1 2,2,2'], 'same number of coordinates'),
    (['bezier', '1,1 2,2', '--at', '1.5'], 'outside the domain'),
    (['bezier', '1,1 2,2', '--at', 'half'], 'cannot parse'),
    (['bezier', '1,1 2,2', '--step', '0'], 'positive'),
    (['bspline', '0,0 1,1 2,2'], 'at least 4'),
    (['bspline', '0,0 1,1 2,2', '--degree', '1', '--knots', '0,0,1,0.5,1'], 'non-decreasing'),
    (['bspline', '0,0 1,1 2,2', '--degree', '1.5'], 'integer'),
    (['hermite', '0,0 1,1'], '--tangents'),
    (['natural', '0,0 1,1'], None),
    (['natural', '0,0 0,0 1,1'], 'coincide'),
    (['natural', '0,0 2,1 1,1', '--function'], 'increasing'),
    (['natural', '0,0 1,1 2,0', '--blend'], 'blending'),
    (['beta', '0,0 1,1 2,0 3,3', '--bias', '0'], 'beta1 > 0'),
    (['bezier', '1,1 2,2', '--tension', '1'], 'does not apply'),
    (['spiral', '1,1 2,2'], 'invalid choice'),
    (['bezier'], 'required'),
])
def test_bad_input_one_line_exit_2(capsys, argv, needle):
    code, out, err = run(capsys, *argv)
    if needle is None:                  # a valid command, for contrast
        assert code == 0
        return
    assert code == 2
    assert err.startswith('curve: error: ') and err.count('\n') == 1
    assert needle in err
    assert 'Traceback' not in err


def test_console_script_exit_status():
    proc = subprocess.run([sys.executable, '-m', 'raster_cli.curve', 'bezier', '1,1 2,2',
                           '--at', '7'], capture_output=True, text=True)
    assert proc.returncode == 2
    assert proc.stderr.strip() == 'curve: error: t=7 is outside the domain [0, 1]'
    assert proc.stdout == ''


def test_negative_numbers_are_values_not_options(capsys):
    code, out, err = run(capsys, 'bspline', '-1,2 3,-4 5,5', '--degree', '1', '--knots',
                         '-1,-1,0,1,1', '--at', '-0.5,0.5', '--json')
    obj = json.loads(out)
    assert code == 0 and err == ''
    assert obj['domain'] == [-1, 1]
    np.testing.assert_allclose([p['point'] for p in obj['points']], [[1, -1], [4, 0.5]])


def test_parse_points_separators():
    np.testing.assert_array_equal(parse_points(' 1,2;3,4\n5,6 '), [[1, 2], [3, 4], [5, 6]])
