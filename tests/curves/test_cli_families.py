"""The ``curve`` command for rational Bezier curves, NURBS, arcs and
surfaces, ``--explain`` and the plot options."""

import json
import math

import numpy as np
import pytest
from PIL import Image

from raster_cli.curve import main

QUAD = '0,0,0 1,0,1 2,0,0 ; 0,1,1 1,1,2 2,1,1 ; 0,2,0 1,2,1 2,2,0'


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def js(capsys, *argv):
    code, out, err = run(capsys, *argv, '--json')
    assert code == 0, err
    return json.loads(out)


def test_rational_bezier_quarter_circle(capsys):
    obj = js(capsys, 'rational-bezier', '1,0 1,1 0,1', '--weights', '1,%r' % 2 ** -0.5 + ',1',
             '--at', '0.5', '--poly', '--blend')
    np.testing.assert_allclose(obj['points'][0]['point'], [2 ** -0.5] * 2, atol=1e-15)
    assert obj['weights'][1] == pytest.approx(2 ** -0.5)
    poly = obj['polynomial'][0]
    # numerator w(t) x(t) and denominator w(t) in the power basis
    s = 2 ** -0.5
    np.testing.assert_allclose(poly['denominator'], [1, 2 * (s - 1), 2 - 2 * s], atol=1e-14)
    np.testing.assert_allclose(np.sum(obj['points'][0]['blend']), 1.0)


def test_nurbs_with_knots_and_weights(capsys):
    obj = js(capsys, 'nurbs', '0,0 1,2 3,2 4,0 5,1', '--weights', '1,2,1,2,1', '--degree', '2',
             '--knots', '0,0,0,1,3,4,4,4', '--at', '0,4', '--continuity')
    assert obj['domain'] == [0, 4] and obj['knots'][3] == 1
    np.testing.assert_allclose([p['point'] for p in obj['points']], [[0, 0], [5, 1]])
    assert [j['t'] for j in obj['joints']] == [1, 3] and all(j['C'] >= 0 for j in obj['joints'])


def test_arc_at_angles_is_exact(capsys):
    obj = js(capsys, 'arc', '1,2', '--radius', '3', '--angles', '0,90', '--at-angle', '30,60')
    want = [[1 + 3 * math.cos(math.radians(a)), 2 + 3 * math.sin(math.radians(a))]
            for a in (30, 60)]
    np.testing.assert_allclose([p['point'] for p in obj['points']], want, atol=1e-14)
    e = js(capsys, 'arc', '0,0', '--radius', '3,1', '--rotation', '90', '--at', '0')
    np.testing.assert_allclose(e['points'][0]['point'], [0, 3], atol=1e-15)


def test_explain_formats_and_json(capsys):
    code, out, _ = run(capsys, 'bezier', '2,6 6,8 9,12', '--at', '0.8', '--explain',
                       '--format', 'markdown')
    assert code == 0 and '### Substituting the parameter values' in out and '$$' in out
    code, out, _ = run(capsys, 'bezier', '2,6 6,8 9,12', '--at', '0.8', '--explain',
                       '--format', 'latex')
    assert '\\begin{align*}' in out
    obj = js(capsys, 'rational-bezier', '1,0 1,1 0,1', '--weights', '1,0.7071,1', '--at', '0.5',
             '--explain')
    assert 'R_i(t) = w_i B_2,i(t)' in obj['explanation']


def test_plot_options(capsys, tmp_path):
    out = tmp_path / 'p.png'
    code, _, err = run(capsys, 'bezier', '1,1 2,3 4,3 6,4', '--step', '0.2', '--plot', str(out),
                       '--plot-blend', '--plot-tangents', '--title', 'A B C D')
    assert code == 0, err
    im = Image.open(out)
    assert im.size[0] == 640 and im.size[1] > 600
    code, _, _ = run(capsys, 'bezier', '1,1 2,3', '--plot', str(tmp_path / 'q.svg'), '--no-axes',
                     '--no-labels')
    assert code == 0 and (tmp_path / 'q.svg').read_text().startswith('<svg')


def test_surface_points_and_normals(capsys):
    obj = js(capsys, 'surface', QUAD, '--at', '0.5,0.5;0,1')
    assert obj['surface'] == 'bezier' and obj['degree'] == [2, 2]
    p = obj['points']
    assert (p[0]['u'], p[0]['v']) == (0.5, 0.5)
    # S(1/2, 1/2) = sum B_i B_j P_ij with B = (1/4, 1/2, 1/4): (1, 1, 1)
    np.testing.assert_allclose(p[0]['point'], [1, 1, 1])
    # corner (0, 1) = P_02 = (2, 0, 0); S_u = 2 (P_12 - P_02) = (0, 2, 2),
    # S_v = 2 (P_02 - P_01) = (2, 0, -2): n = (-1, 1, -1) / sqrt 3
    np.testing.assert_allclose(p[1]['point'], [2, 0, 0])
    np.testing.assert_allclose(p[1]['normal'], np.array([-1, 1, -1]) / math.sqrt(3), atol=1e-15)
    code, out, _ = run(capsys, 'surface', QUAD)               # default 3 x 3 (u, v) grid
    assert code == 0 and len(out.splitlines()) == 2 + 9


def test_surface_bspline_nurbs_and_json_file(capsys, tmp_path):
    net = '0,0,0 1,0,0 2,0,0 3,0,0 ; 0,1,1 1,1,1 2,1,1 3,1,1 ; 0,2,0 1,2,0 2,2,0 3,2,0'
    obj = js(capsys, 'surface', net, '--degree', '2,2', '--at', '0,0;1,1')
    assert obj['surface'] == 'bspline' and obj['degree'] == [2, 2]
    np.testing.assert_allclose([q['point'] for q in obj['points']], [[0, 0, 0], [3, 2, 0]])
    w = '1 1 1 1 ; 1 3 3 1 ; 1 1 1 1'
    nu = js(capsys, 'surface', net, '--degree', '2', '--weights', w, '--at', '0.5,0.5')
    assert nu['surface'] == 'nurbs' and nu['weights'][1][1] == 3
    f = tmp_path / 'net.json'
    f.write_text(json.dumps({'points': [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]]}))
    obj = js(capsys, 'surface', str(f), '--at', '0.3,0.7')
    np.testing.assert_allclose(obj['points'][0]['point'], [0.3, 0.7, 0.21])
    np.testing.assert_allclose(obj['points'][0]['normal'],
                               np.array([-0.7, -0.3, 1]) / math.sqrt(1.58), atol=1e-14)


def test_surface_plot(capsys, tmp_path):
    out = tmp_path / 's.png'
    code, _, err = run(capsys, 'surface', QUAD, '--plot', str(out), '--view', 'both',
                       '--size', '800')
    assert code == 0, err
    assert Image.open(out).size[0] == 800


@pytest.mark.parametrize('argv,needle', [
    (['rational-bezier', '0,0 1,1', '--weights', '1,2,3'], 'one weight per control point'),
    (['rational-bezier', '0,0 1,1', '--weights', '1,-2'], 'positive'),
    (['nurbs', '0,0 1,1 2,0', '--degree', '3'], 'at least 4'),
    (['arc', '0,0'], '--radius'),
    (['arc', '0,0 1,1', '--radius', '1'], 'one 2-D centre'),
    (['arc', '0,0', '--radius', '1', '--angles', '0,0'], 'sweep'),
    (['bezier', '0,0 1,1', '--at-angle', '30'], 'does not apply'),
    (['bezier', '0,0 1,1', '--weights', '1,1'], 'does not apply'),
    (['bezier', '0,0 1,1', '--view', 'ortho'], 'surface only'),
    (['bezier', '0,0 1,1', '--explain', '--format', 'html'], 'invalid choice'),
    (['natural', '0,0 1,1 2,0', '--plot', '/tmp/x.png', '--plot-blend'], 'blending'),
    (['surface', '0,0,0 1,0,0 ; 0,1,0'], 'same number of points'),
    (['surface', QUAD, '--at', '0.5'], 'u,v pairs'),
    (['surface', QUAD, '--at', '1.5,0'], 'outside the domain'),
    (['surface', QUAD, '--weights', '1 1 ; 1 1'], '3 rows of 3 weights'),
    (['surface', QUAD, '--knots', '0,0,1,1'], 'u knots;v knots'),
    (['surface', QUAD, '--explain'], 'does not apply to surface'),
    (['surface', QUAD, '--step', '0.1'], 'does not apply'),
    (['surface', '/nonexistent/net.json'], 'No such file'),
])
def test_bad_input_one_line(capsys, argv, needle):
    code, out, err = run(capsys, *argv)
    assert code in (1, 2)
    assert err.count('\n') == 1 and err.startswith('curve: error:')
    assert needle in err, err
