"""Tests of raster.geometry.pathdata: SVG path data, arcs and basic shapes."""

import math
import sys

import numpy as np
import pytest
import svgelements
from hypothesis import HealthCheck, assume, example, given, settings, strategies as st

import raster
from raster.geometry import pathdata as svgpath
from raster.errors import LimitError, PathError, RasterError
from raster.geometry.path import CLOSE, CUBIC, LINE, MOVE, Path
from raster.geometry.pens import PathBuilder
from raster.geometry.pathdata import (_arc_batch, _build_loop, _build_vector, _lex, arc_to_cubics,
                                      circle_path, ellipse_path, line_path, parse_path,
                                      parse_points, polyline_path, rect_path)

from _shared import CORPUS

SETTINGS = settings(max_examples=150, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])
FEWER = settings(SETTINGS, max_examples=80)


def svg(d, **kw):
    return parse_path(d, **kw).to_svg()


def bezier_points(path, n=64):
    """(S, n, 2) points sampled on every drawing segment of ``path``."""
    seg = path.segments()
    t = np.linspace(0, 1, n)[None, :, None]
    c = seg.ctrl
    deg = seg.degree[:, None, None]
    p0, p1, p2, p3 = (c[:, k][:, None, :] for k in range(4))
    lin = p0 + (p3 - p0) * t
    quad = (1 - t) ** 2 * p0 + 2 * (1 - t) * t * p1 + t ** 2 * p2
    cub = ((1 - t) ** 3 * p0 + 3 * (1 - t) ** 2 * t * p1 + 3 * (1 - t) * t ** 2 * p2
           + t ** 3 * p3)
    return np.where(deg == 1, lin, np.where(deg == 2, quad, cub))


def cubic_samples(p0, ctrl, n=201):
    """Points sampled densely on the cubics of ``arc_to_cubics``."""
    starts = np.concatenate([np.asarray(p0, float)[None], ctrl[:-1, 2]])
    t = np.linspace(0, 1, n)[None, :, None]
    P = [starts[:, None]] + [ctrl[:, k][:, None] for k in range(3)]
    return ((1 - t) ** 3 * P[0] + 3 * (1 - t) ** 2 * t * P[1]
            + 3 * (1 - t) * t ** 2 * P[2] + t ** 3 * P[3]).reshape(-1, 2)


# -- commands ------------------------------------------------------------------------
@pytest.mark.parametrize('d, expected', [
    ('M1 2', 'M 1 2'),
    ('m1 2', 'M 1 2'),
    ('M1 2 L3 4', 'M 1 2 L 3 4'),
    ('M1 2 l3 4', 'M 1 2 L 4 6'),
    ('M1 2 H5', 'M 1 2 L 5 2'),
    ('M1 2 h5', 'M 1 2 L 6 2'),
    ('M1 2 V5', 'M 1 2 L 1 5'),
    ('M1 2 v5', 'M 1 2 L 1 7'),
    ('M1 2 C3 4 5 6 7 8', 'M 1 2 C 3 4 5 6 7 8'),
    ('M1 2 c3 4 5 6 7 8', 'M 1 2 C 4 6 6 8 8 10'),
    ('M1 2 Q3 4 5 6', 'M 1 2 Q 3 4 5 6'),
    ('M1 2 q3 4 5 6', 'M 1 2 Q 4 6 6 8'),
    ('M1 2 S5 6 7 8', 'M 1 2 C 1 2 5 6 7 8'),
    ('M1 2 s5 6 7 8', 'M 1 2 C 1 2 6 8 8 10'),
    ('M1 2 T5 6', 'M 1 2 Q 1 2 5 6'),
    ('M1 2 t5 6', 'M 1 2 Q 1 2 6 8'),
    ('M1 2 L3 4 Z', 'M 1 2 L 3 4 Z'),
    ('M1 2 L3 4 z', 'M 1 2 L 3 4 Z'),
    ('M1 2 A0 0 0 0 1 5 6', 'M 1 2 L 5 6'),
    ('M1 2 a0 5 0 0 1 5 6', 'M 1 2 L 6 8'),
])
def test_every_command_absolute_and_relative(d, expected):
    assert svg(d) == expected


@pytest.mark.parametrize('d, expected', [
    ('M0 0 1 1 2 2', 'M 0 0 L 1 1 L 2 2'),               # implicit L after M
    ('m1 1 1 1 2 2', 'M 1 1 L 2 2 L 4 4'),               # implicit l after m
    ('M0 0 L1 1 2 2 3 3', 'M 0 0 L 1 1 L 2 2 L 3 3'),
    ('M0 0 h1 2 3', 'M 0 0 L 1 0 L 3 0 L 6 0'),
    ('M0 0 V1 2', 'M 0 0 L 0 1 L 0 2'),
    ('M0 0 c1 1 2 2 3 3 1 1 2 2 3 3', 'M 0 0 C 1 1 2 2 3 3 C 4 4 5 5 6 6'),
    ('M0 0 q1 1 2 0 1 1 2 0', 'M 0 0 Q 1 1 2 0 Q 3 1 4 0'),
    ('M0 0 M5 5 m1 1 2 2', 'M 0 0 M 5 5 M 6 6 L 8 8'),
])
def test_implicit_repeats(d, expected):
    assert svg(d) == expected


@pytest.mark.parametrize('d, c1', [
    ('M0 0 C1 2 3 4 5 5 S 8 8 9 9', [7, 6]),       # after C: reflect (3,4) about (5,5)
    ('M0 0 C1 2 3 4 5 5 S 8 8 9 9 S 0 0 1 1', [10, 10]),  # after S: reflect (8,8) about (9,9)
    ('M0 0 c1 2 3 4 5 5 s 3 3 4 4', [7, 6]),
    ('M0 0 L5 5 S 8 8 9 9', [5, 5]),               # after L: current point
    ('M0 0 Q1 2 5 5 S 8 8 9 9', [5, 5]),           # after Q: no reflection for S
    ('M0 0 C1 2 3 4 5 5 Z S 8 8 9 9', [0, 0]),      # after Z: current point
])
def test_smooth_cubic_reflection(d, c1):
    p = parse_path(d)
    last = p.points[-3]
    assert last.tolist() == c1


@pytest.mark.parametrize('d, ctrl', [
    ('M0 0 Q1 2 5 5 T 9 9', [9, 8]),               # after Q: reflect (1,2) about (5,5)
    ('M0 0 Q1 2 5 5 T 9 9 T 10 10', [9, 10]),      # after T: reflect (9,8) about (9,9)
    ('M0 0 Q1 2 5 5 T 9 9 T 10 10 t 1 1', [11, 10]),
    ('M0 0 L5 5 T 9 9', [5, 5]),                   # after L: current point
    ('M0 0 C1 2 3 4 5 5 T 9 9', [5, 5]),           # after C: no reflection for T
    ('M0 0 L5 5 T 9 9 T 10 10', [13, 13]),         # chain started at the point
    ('M0 0 Q1 2 5 5 Z T 9 9', [0, 0]),
])
def test_smooth_quadratic_reflection(d, ctrl):
    p = parse_path(d)
    assert p.points[-2].tolist() == ctrl


@pytest.mark.parametrize('small', [10**9, 0])
def test_long_t_chain_matches_sequential_rule(small, monkeypatch):
    # the vectorized builder solves the T recurrence with a cumulative sum
    monkeypatch.setattr(svgpath, 'SMALL_PATH_TOKENS', small)
    rng = np.random.default_rng(1)
    pts = rng.uniform(-50, 50, (600, 2)).round(3)
    d = 'M0 0 Q 3 7 1 1 ' + ' '.join('T %r %r' % (float(x), float(y)) for x, y in pts)
    p = parse_path(d)
    ctrl, cur = np.array([3.0, 7.0]), np.array([1.0, 1.0])
    for i, q in enumerate(pts):
        ctrl = 2 * cur - ctrl
        cur = q
        assert np.allclose(p.points[3 + 2 * i], ctrl, atol=1e-9)


@pytest.mark.parametrize('d, expected', [
    ('M10 10 Z', 'M 10 10 Z'),                      # kept (caps)
    ('M10 10 L10 10', 'M 10 10 L 10 10'),           # zero length kept
    ('M10 10 L20 10 Z l5 5', 'M 10 10 L 20 10 Z M 10 10 L 15 15'),
    ('M10 10 L20 10 z m5 5 l1 0', 'M 10 10 L 20 10 Z M 15 15 L 16 15'),
    ('M10 10 L20 10 Z Z', 'M 10 10 L 20 10 Z'),
    ('M1 1 L2 2 Z L3 3 Z h1', 'M 1 1 L 2 2 Z M 1 1 L 3 3 Z M 1 1 L 2 1'),
    ('m1 1 z m1 1 z m1 1 z', 'M 1 1 Z M 2 2 Z M 3 3 Z'),
    ('M0 0 L5 0 M1 1 L6 6 Z v1', 'M 0 0 L 5 0 M 1 1 L 6 6 Z M 1 1 L 1 2'),
])
def test_close_and_subpaths(d, expected):
    assert svg(d) == expected


def test_relative_after_close_chain():
    # each m is relative to the start of the previous (closed) contour
    d = 'M0 0 ' + ' '.join('L7 7 Z m1 2' for _ in range(300)) + ' l1 1'
    p = parse_path(d)
    starts = p.segments().contour_start
    assert np.allclose(starts[1:301], np.arange(1, 301)[:, None] * [1, 2])
    assert p.points[-1].tolist() == [301, 601]


@pytest.mark.parametrize('d', ['', '   ', '\n\t ', ' \r\f'])
def test_empty(d):
    p = parse_path(d)
    assert len(p) == 0 and p.is_empty
    assert len(parse_path(d, strict=False)) == 0


# -- numbers -----------------------------------------------------------------------------------
@pytest.mark.parametrize('d, pts', [
    ('M1.5.5', [[1.5, 0.5]]),
    ('M-1-2', [[-1, -2]]),
    ('M1e-3 2E2', [[0.001, 200]]),
    ('M.5 +1', [[0.5, 1]]),
    ('M1e+2-.5e1', [[100, -5]]),
    ('M1.e2 3.', [[100, 3]]),
    ('M0.5.5.5.5', [[0.5, 0.5], [0.5, 0.5]]),
    ('M 1 , 2', [[1, 2]]),
    ('M1,2,3,4', [[1, 2], [3, 4]]),
    ('M1-.5-.5+2', [[1, -0.5], [-0.5, 2]]),
    ('\tM\n1\r2\f', [[1, 2]]),
    ('M007 08', [[7, 8]]),
    ('M1e-400 2', [[0, 2]]),                        # underflow is fine
])
def test_number_grammar(d, pts):
    assert parse_path(d).points.tolist() == pts


# -- errors ------------------------------------------------------------------------------------
@pytest.mark.parametrize('d, pos, msg', [
    ('M0 0 L1 1 2', 11, 'expected number'),
    ('L1 1', 0, 'expected moveto'),
    ('1 1', 0, 'expected moveto'),
    ('M', 1, 'expected number'),
    ('M1', 2, 'expected number'),
    ('M1 2 L', 6, 'expected number'),
    ('M1 2 L M3 4', 7, 'expected number'),
    ('M1,2,3', 6, 'expected number'),
    ('M1 2 x3', 5, "unexpected character 'x'"),
    ('M1 2 L 3 4 ,', 12, 'expected number'),
    ('M1 2 L,3 4', 6, 'unexpected comma'),
    ('M1 2 L3,,4', 8, 'unexpected comma'),
    ('M1 2 Z 3', 7, 'expected command'),
    ('M1 2 Z,', 6, 'unexpected comma'),
    ('M 1e999 2', 2, 'number out of range'),
    ('M 1 2 L 3 -1e400', 10, 'number out of range'),
    ('M 1,2 L3,1e999', 9, 'number out of range'),
    ('M1 2 A 1 1 0 2 0 5 5', 13, 'expected arc flag'),
    ('M1 2 A 1 1 0 0 1 5 5 1 1 0 0 1 5', 32, 'expected number'),
    ('M1 2 A 1 1 0 0', 14, 'expected arc flag'),
    ('M1 2 A 1 1 00 1 5 5', 16, 'expected arc flag'),   # "00" is the rotation
    ('M1 2 A 1 1 0 1.5 5 5', 14, 'expected arc flag'),
    ('M1 2e', 4, "unexpected character 'e'"),
    ('M1 2 L3 4 #', 10, "unexpected character '#'"),
    ('M1 2 \u00e9', 5, "unexpected character '\u00e9'"),
    ('M1 2\x00', 4, 'unexpected character'),
    ('M1 2 \v', 5, 'unexpected character'),
])
def test_error_positions(d, pos, msg):
    with pytest.raises(PathError, match='^path data error at %d: %s' % (pos, msg)):
        parse_path(d)


@pytest.mark.parametrize('d, expected', [
    ('M0 0 L10 0 L', 'M 0 0 L 10 0'),
    ('M0 0 L10 0 20', 'M 0 0 L 10 0'),
    ('M0 0 L10 0 20 30 40', 'M 0 0 L 10 0 L 20 30'),
    ('M0 0 C1 1 2 2 3 3 4 4', 'M 0 0 C 1 1 2 2 3 3'),
    ('M0 0 L1 1 x L2 2', 'M 0 0 L 1 1'),
    ('M0 0 L1 1 Z 5', 'M 0 0 L 1 1 Z'),
    ('L1 1', ''),
    ('x', ''),
    ('M1', ''),
    ('M1 2 L 3 1e999', 'M 1 2'),
    ('M1 2 A1 1 0 0 1 3 2 A 1 1 0 2 0 5 5', None),
    ('M0 0 L1 1,', 'M 0 0 L 1 1'),
])
def test_non_strict_prefix(d, expected):
    p = parse_path(d, strict=False)
    if expected is None:                       # the first arc survives
        assert p.verbs.tolist()[:2] == [MOVE, CUBIC] and p.points[-1].tolist() == [3, 2]
    else:
        assert p.to_svg() == expected
    with pytest.raises(PathError):
        parse_path(d)


def test_errors_are_raster_errors():
    for bad in [dict(d=3), dict(d='M0 0', tolerance=0), dict(d='M0 0', tolerance=float('nan')),
                dict(d='M0 0', tolerance='x'), dict(d='M0 0', tolerance=-1)]:
        with pytest.raises(RasterError):
            parse_path(**bad)


def test_overflowing_coordinates():
    with pytest.raises(PathError, match='overflow'):
        parse_path('M1e308 0 l1e308 0')


@SETTINGS
@given(st.text(alphabet='MmLlHhVvCcSsQqTtAaZz0123456789.,-+eE x#\t', max_size=40))
def test_fuzz_never_crashes(d):
    # any string: either a Path or a PathError, and non-strict never raises
    try:
        p = parse_path(d)
        Path(p.verbs, p.points)                  # passes full validation
    except PathError as e:
        assert str(e).startswith('path data error at ')
        pos = int(str(e).split()[4].rstrip(':'))
        assert 0 <= pos <= len(d)
        q = parse_path(d, strict=False)
        # the non-strict result is a prefix: it parses strictly from its svg
        assert parse_path(q.to_svg()) == q
    else:
        assert parse_path(d, strict=False) == p


# -- arcs -------------------------------------------------------------------------------------
def test_arc_flags_without_separators():
    a = parse_path('M0 0 a1 1 0 00 1 1')
    b = parse_path('M0 0 a1 1 0 0 0 1 1')
    assert a == b and len(a) > 1
    c = parse_path('M0 0 a1 1 0 0110 10')              # flags 0 1, end (10, 10)
    d = parse_path('M0 0 a1 1 0 0 1 10 10')
    assert c == d
    e = parse_path('M0 0a5,5,0,1,1,10,0')
    assert np.allclose(e.points[-1], [10, 0])


def test_arc_radii_correction_half_circle():
    # radius 1 cannot span 10 units: scaled up to 5, half circle about (5, 0)
    p = parse_path('M0 0 A1 1 0 0 1 10 0', tolerance=0.001)
    q = bezier_points(p, 200).reshape(-1, 2)
    r = np.hypot(q[:, 0] - 5, q[:, 1])
    assert np.abs(r - 5).max() <= 0.001
    assert q[:, 1].min() < -4.99 and q[:, 1].max() <= 1e-12     # sweep 1: above
    p2 = parse_path('M0 0 A1 1 0 0 0 10 0')
    assert bezier_points(p2).reshape(-1, 2)[:, 1].max() > 4.99   # sweep 0: below


def test_arc_zero_radius_and_same_endpoints():
    assert svg('M0 0 A0 5 0 1 1 10 0') == 'M 0 0 L 10 0'
    assert svg('M0 0 A5 0 0 1 1 10 0') == 'M 0 0 L 10 0'
    assert svg('M3 4 A5 5 0 1 1 3 4') == 'M 3 4'
    assert svg('M3 4 A5 5 0 1 1 3 4 L 5 5') == 'M 3 4 L 5 5'
    assert arc_to_cubics((1, 1), 3, 3, 0, 1, 1, (1, 1)).shape == (0, 3, 2)
    line = arc_to_cubics((0, 0), 0, 3, 0, 1, 1, (3, 6))
    assert np.allclose(line, [[[1, 2], [2, 4], [3, 6]]])


def test_arc_negative_radii_use_absolute_value():
    assert parse_path('M0 0 A-5 -5 0 0 1 10 0') == parse_path('M0 0 A5 5 0 0 1 10 0')


@pytest.mark.parametrize('large, sweep, centre_y, far', [
    (0, 0, -8, False), (0, 1, 8, False), (1, 0, 8, True), (1, 1, -8, True)])
def test_arc_flag_combinations(large, sweep, centre_y, far):
    # circle of radius 10 through (0,0) and (16,0): centres (8, +-6)
    p = parse_path('M0 0 A10 10 0 %d %d 16 0' % (large, sweep), tolerance=1e-4)
    q = bezier_points(p, 100).reshape(-1, 2)
    cy = 6 if centre_y > 0 else -6
    assert np.abs(np.hypot(q[:, 0] - 8, q[:, 1] - cy) - 10).max() <= 1e-4
    span = q[:, 1].max() - q[:, 1].min()
    assert (span > 10) == far                        # the large arc goes round


def test_arc_rotation():
    # an ellipse rotated by 90 degrees is the swapped ellipse
    a = parse_path('M0 0 A4 2 90 0 1 0 4')
    b = parse_path('M0 0 A2 4 0 0 1 0 4')
    assert np.allclose(a.points, b.points, atol=1e-12)
    c = parse_path('M0 0 A4 2 450 0 1 0 4')          # 450 = 90 mod 360
    assert np.allclose(c.points, b.points, atol=1e-12)


def _svg_centre(x1, y1, rx, ry, phi, fa, fs, x2, y2):
    """Lambda, and the centre and corrected radii, straight from the SVG
    implementation notes' formulas (an independent, scalar implementation)."""
    rx, ry = abs(rx), abs(ry)
    co, si = math.cos(math.radians(phi)), math.sin(math.radians(phi))
    dx, dy = (x1 - x2) / 2, (y1 - y2) / 2
    x1p, y1p = co * dx + si * dy, -si * dx + co * dy
    lam = x1p ** 2 / rx ** 2 + y1p ** 2 / ry ** 2
    if lam > 1:
        rx, ry = rx * math.sqrt(lam), ry * math.sqrt(lam)
    num = rx ** 2 * ry ** 2 - rx ** 2 * y1p ** 2 - ry ** 2 * x1p ** 2
    den = rx ** 2 * y1p ** 2 + ry ** 2 * x1p ** 2
    k = 0.0 if lam > 1 else math.sqrt(max(0.0, num / den)) * (1 if fa != fs else -1)
    cxp, cyp = k * rx * y1p / ry, -k * ry * x1p / rx
    centre = np.array([co * cxp - si * cyp + (x1 + x2) / 2,
                       si * cxp + co * cyp + (y1 + y2) / 2])
    return lam, (centre, rx, ry)


@SETTINGS
@given(x0=st.floats(-100, 100), y0=st.floats(-100, 100), x1=st.floats(-100, 100),
       y1=st.floats(-100, 100), rx=st.floats(0.01, 200), ry=st.floats(0.01, 200),
       phi=st.floats(-360, 360), large=st.booleans(), sweep=st.booleans(),
       tol=st.sampled_from([1e-4, 1e-3, 0.01, 0.25, 2.0]))
def test_arc_accuracy_against_exact_ellipse(x0, y0, x1, y1, rx, ry, phi, large, sweep, tol):
    assume(math.hypot(x1 - x0, y1 - y0) > 1e-6)
    ctrl = arc_to_cubics((x0, y0), rx, ry, phi, large, sweep, (x1, y1), tol)
    assert ctrl.shape[1:] == (3, 2) and len(ctrl) >= 1
    assert ctrl[-1, 2].tolist() == [x1, y1]
    # the vectorized batch conversion (long paths) gives the same cubics
    kind, count, batch = _arc_batch(np.array([[x0, y0]]), np.array([[x1, y1]]),
                                    np.array([rx]), np.array([ry]), np.array([phi]),
                                    np.array([large]), np.array([sweep]), tol)
    assert kind.tolist() == [2] and count.tolist() == [len(ctrl)]
    assert np.allclose(batch, ctrl, rtol=1e-12, atol=1e-9)
    # exact ellipse from the SVG implementation notes (F.6.5, F.6.6)
    lam, (c, rx2, ry2) = _svg_centre(x0, y0, rx, ry, phi, large, sweep, x1, y1)
    assume(not 1 - 1e-6 < lam <= 1)     # centre ill-conditioned (sqrt of ~0)
    t = math.radians(phi)
    u = np.array([math.cos(t), math.sin(t)])
    v = np.array([-math.sin(t), math.cos(t)])
    q = cubic_samples((x0, y0), ctrl) - c
    radial = np.hypot(q @ u / rx2, q @ v / ry2)
    scale = max(rx2, ry2)
    # float64 resolution of this check: coordinates |q| carry eps * |q|
    # absolute error, i.e. up to eps * |q| / min(rx, ry) in ``radial``
    slack = 8 * 2.2e-16 * np.abs(q).max() / min(rx2, ry2) * scale
    assert np.abs(radial - 1).max() * scale <= tol + slack
    arc = svgelements.Path('M%r %r A%r %r %r %d %d %r %r' % (
        x0, y0, rx, ry, phi, large, sweep, x1, y1))[1]
    # at most 90 degrees per piece
    assert len(ctrl) >= math.ceil(abs(arc.sweep) / (math.pi / 2) - 1e-6)
    # the arc goes the same way round: its midpoint lies on our cubics
    mid = np.array(arc.point(0.5)) - c
    assert np.hypot(*(q - mid).T).min() <= tol + 0.01 * scale


def test_arc_tolerance_controls_piece_count():
    counts = [len(arc_to_cubics((0, 0), 100, 100, 0, 0, 1, (200, 0), tol))
              for tol in (10, 1, 0.1, 0.01, 0.001, 1e-4)]
    assert counts[0] == 2                                  # 90-degree cap
    assert counts == sorted(counts) and counts[-1] > counts[0]
    with pytest.raises(LimitError):
        arc_to_cubics((0, 0), 1e8, 1e8, 0, 1, 1, (1e8, 1e8), 1e-300)
    with pytest.raises(PathError):
        arc_to_cubics((0, 0), float('inf'), 1, 0, 0, 1, (1, 1))


def test_arc_tolerance_in_parse_path():
    coarse = parse_path('M0 0 A100 100 0 0 1 200 0', tolerance=1)
    fine = parse_path('M0 0 A100 100 0 0 1 200 0', tolerance=1e-4)
    for p, tol in ((coarse, 1), (fine, 1e-4)):
        q = bezier_points(p, 300).reshape(-1, 2)
        assert np.abs(np.hypot(q[:, 0] - 100, q[:, 1]) - 100).max() <= tol
    assert len(fine) > len(coarse)


# -- builders agree; svgelements agrees ------------------------------------------------------
_CMD_ARGS = {'M': 2, 'L': 2, 'H': 1, 'V': 1, 'C': 6, 'S': 4, 'Q': 4, 'T': 2, 'A': 7, 'Z': 0}


@st.composite
def path_strings(draw, arcs=True, svgelements_reflections=False):
    """Path data of every command.  With ``svgelements_reflections`` an S
    never follows a Q or T and a T never follows a C or S: svgelements
    reflects the control point of a Bezier of the other degree there, where
    SVG reflects none (tested on its own below)."""
    letters = 'MLHVCSQTZ' + ('A' if arcs else '')
    n = draw(st.integers(1, 25))
    parts = ['M %d %d' % (draw(st.integers(-50, 50)), draw(st.integers(-50, 50)))]
    prev = 'M'
    for _ in range(n):
        c = draw(st.sampled_from(letters))
        if svgelements_reflections and (c == 'S' and prev in 'QT' or c == 'T' and prev in 'CS'):
            c = 'L'
        prev = c
        if draw(st.booleans()):
            c = c.lower()
        k = _CMD_ARGS[c.upper()]
        reps = 1 if k == 0 else draw(st.integers(1, 3))
        nums = []
        for _ in range(reps):
            g = [draw(st.integers(-40, 40)) for _ in range(k)]
            if c in 'Aa':
                g[0], g[1] = abs(g[0]) + 1, abs(g[1]) + 1
                g[3], g[4] = draw(st.integers(0, 1)), draw(st.integers(0, 1))
            nums += g
        parts.append(c + ' '.join(map(str, nums)))
    return ' '.join(parts)


@FEWER
@given(path_strings())
def test_loop_and_vector_builders_agree(d):
    _, nums, kb = _lex(d)
    kinds = kb.replace(b',', b'')
    vals = [float(x) for x in nums]
    a = _build_loop(kinds, vals, 0.01)
    b = _build_vector(kinds, np.array(vals), 0.01)
    Path(b.verbs, b.points)                      # passes full validation
    assert a.verbs.tolist() == b.verbs.tolist()
    assert np.allclose(a.points, b.points, rtol=0, atol=1e-9)


def test_long_path_uses_vector_builder_and_agrees():
    rng = np.random.default_rng(7)
    parts = ['M 0 0']
    for i in range(3000):
        c = 'lcsqtLhvZmaA'[rng.integers(12)]
        k = _CMD_ARGS[c.upper()]
        nums = rng.integers(-30, 30, k).tolist()
        if c in 'aA':
            nums[0], nums[1], nums[3], nums[4] = abs(nums[0]) + 1, 3, 1, i % 2
        parts.append(c + ' '.join(map(str, nums)))
    d = ' '.join(parts)
    _, nums, kinds = _lex(d)                 # no commas in d
    assert len(kinds) > svgpath.SMALL_PATH_TOKENS
    vals = [float(x) for x in nums]
    a = _build_loop(kinds, vals, 0.01)
    b = parse_path(d)                        # vectorized builder
    assert a.verbs.tolist() == b.verbs.tolist()
    assert np.allclose(a.points, b.points, rtol=1e-12, atol=1e-9)


@FEWER
@given(path_strings(), st.sampled_from([9, 10, 13, 40]))
def test_vector_builder_in_parts_is_the_one_pass_result(d, size):
    # long token strings are built in parts of about _BUILD_TOKENS tokens,
    # cut between command groups (inside runs of implicit repeats too),
    # each starting from the state the previous left (current point,
    # contour start, last command and control point for S / T): with
    # integer coordinates every sum is exact, so the same numbers (up to
    # the sign of a zero: the T recurrence alternates signs by index)
    _, nums, kb = _lex(d)
    kinds = kb.replace(b',', b'')
    vals = np.array([float(x) for x in nums])
    whole = _build_vector(kinds, vals, 0.01)
    saved = svgpath._BUILD_TOKENS
    svgpath._BUILD_TOKENS = size
    try:
        parts = _build_vector(kinds, vals, 0.01)
    finally:
        svgpath._BUILD_TOKENS = saved
    assert parts.verbs.tobytes() == whole.verbs.tobytes()
    assert np.array_equal(parts.points, whole.points)


@FEWER
@given(st.lists(path_strings(), min_size=2, max_size=8), st.sampled_from([9, 17, 50]))
@example(['M 0 0 M0 0', 'M 1 35 A2 9 1 0 0 1 0'], 9)    # (the arc's tan: one ulp apart)
def test_many_paths_built_in_parts_are_each_path(ds, size):
    # parse_paths builds all strings in one pass, which is cut into parts
    # regardless of where the strings start: bit for bit the one pass (the
    # coordinates are exact), and each path as parse_path builds it alone.
    # (Short paths alone take the loop builder, whose arcs use math's
    # tan and atan2: numpy's differ from them in the last bit of a few
    # arguments, as in test_loop_and_vector_builders_agree.)
    one = [parse_path(d, strict=False) for d in ds]
    whole = svgpath.parse_paths(ds)
    saved = svgpath._BUILD_TOKENS
    svgpath._BUILD_TOKENS = size
    try:
        many = svgpath.parse_paths(ds)
    finally:
        svgpath._BUILD_TOKENS = saved
    for a, w, b in zip(one, whole, many):
        assert a.verbs.tolist() == w.verbs.tolist() == b.verbs.tolist()
        assert np.array_equal(w.points, b.points)
        assert np.allclose(a.points, b.points, rtol=0, atol=1e-9)


def test_parts_of_a_run_of_implicit_repeats():
    # one moveto and 3000 implicit relative linetos: parts cut inside the
    # run continue it as 'l' (not as another moveto)
    d = 'm5 5 ' + ' '.join('%d %d' % (k % 7 - 3, k % 5 - 2) for k in range(3000)) + ' z'
    _, nums, kb = _lex(d)
    cuts = list(svgpath._parts(kb, 100))
    assert len(cuts) > 50 and {lead for _, _, lead in cuts[1:]} == {b'l'}
    saved = svgpath._BUILD_TOKENS
    svgpath._BUILD_TOKENS = 100
    try:
        p = parse_path(d)
    finally:
        svgpath._BUILD_TOKENS = saved
    assert p.verbs.tolist() == [MOVE] + [LINE] * 3000 + [CLOSE]
    steps = np.array([(k % 7 - 3, k % 5 - 2) for k in range(3000)], float)
    assert np.array_equal(p.points, np.cumsum(np.vstack([[5.0, 5.0], steps]), axis=0))


@pytest.mark.parametrize('plain', [False, True])
@pytest.mark.parametrize('d', ['M0 0' + 'l1 2' * 200_000, 'M0 0' + 'h1' * 400_000,
                               'M0 0 ' + ' '.join(['1 2'] * 200_000), 'M0 0Z' * 160_000])
def test_long_path_data_is_parsed_in_bounded_memory(d, plain, monkeypatch):
    # lexed in chunks (also data without separators, cut before letters),
    # its grammar checked in pieces and built in parts: the temporaries were
    # some 300 bytes a command (160 MB for 2 MB of 'L1 2'); now the peak is
    # the result, the values and a few MB.  `plain`: the grammar regex
    # without possessive repeats (Python before 3.11.5), whose backtracking
    # state was another 100 bytes a command in one match
    import re
    import tracemalloc
    if plain:
        monkeypatch.setattr(svgpath, '_VALID', re.compile(svgpath._validity_source(False)))
        monkeypatch.setattr(svgpath, '_VALID_BODY',
                            re.compile(svgpath._validity_source(False, body=True)))
    tracemalloc.start()
    try:
        p = parse_path(d)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    kept = p.points.nbytes + p.verbs.nbytes
    assert peak < 3 * kept + 8e6, (peak, kept)


def test_grammar_checked_in_pieces_agrees_with_one_match():
    # _grammar_ok cuts long token strings before command letters: the first
    # piece must be valid data, the others sequences of commands; the same
    # verdict as one match of the whole, with either form of the regex
    import random
    import re
    rng = random.Random(3)
    toks = [b'M##', b'm####', b'L##', b'l', b'H#', b'V##', b'C######', b'S####', b'Q####',
            b'T##', b'A###\x00\x01##', b'a###\x01\x01##', b'Z', b'z', b'#', b'##', b'x',
            b'\x00', b'A###\x00\x02##']
    forms = [(svgpath._VALID, svgpath._VALID_BODY),
             (re.compile(svgpath._validity_source(False)),
              re.compile(svgpath._validity_source(False, body=True)))]
    saved = svgpath._VALID, svgpath._VALID_BODY, svgpath._VALID_TOKENS
    seen = set()
    try:
        for _ in range(3000):
            k = b''.join(rng.choice(toks) for _ in range(rng.randint(0, 12)))
            if rng.random() < 0.5:
                k = b'M##' + k
            want = forms[1][0].fullmatch(k) is not None
            seen.add(want)
            for whole, body in forms:
                svgpath._VALID, svgpath._VALID_BODY = whole, body
                for size in (1, 2, 3, 5, 8):
                    svgpath._VALID_TOKENS = size
                    assert svgpath._grammar_ok(k) == want, (k, size)
    finally:
        svgpath._VALID, svgpath._VALID_BODY, svgpath._VALID_TOKENS = saved
    assert seen == {True, False}


def _svgelements_ends(d):
    out = []
    for s in svgelements.Path(d):
        if isinstance(s, svgelements.Close):
            continue
        if isinstance(s, svgelements.Arc) and s.start == s.end:
            continue                      # SVG omits it; svgelements keeps it
        out.append((type(s).__name__, (s.end.x, s.end.y)))
    return out


def _our_ends(p):
    """End point of every verb but CLOSE, in order."""
    npts = np.array([1, 1, 2, 3, 0])[p.verbs]
    last = np.cumsum(npts) - 1
    keep = p.verbs != CLOSE
    return p.points[last[keep]]


@FEWER
@given(path_strings())
def test_end_points_match_svgelements(d):
    ours = _our_ends(parse_path(d))
    theirs = _svgelements_ends(d)
    # svgelements' end points are a subsequence of ours: arcs become several
    # cubics here, and drawing after Z starts with an explicit move here
    i = 0
    for name, e in theirs:
        while i < len(ours) and not np.allclose(ours[i], e, atol=1e-6):
            i += 1
        assert i < len(ours), (name, e)
        i += 1
    assert np.allclose(ours[-1], theirs[-1][1], atol=1e-6)


def test_end_points_match_svgelements_on_corpus_sample():
    import lxml.etree as ET
    from pathlib import Path as FsPath
    f = FsPath(CORPUS) / 'tiger.svg'
    if not f.exists():
        pytest.fail('corpus file missing: %s' % f)
    ds = [e.get('d') for e in ET.parse(str(f)).iter() if e.get('d')]
    assert len(ds) > 100
    for d in ds[::7]:
        ends = _our_ends(parse_path(d))
        theirs = np.array([e for _, e in _svgelements_ends(d)])
        assert ends.shape == theirs.shape and np.allclose(ends, theirs, atol=1e-9)


# -- svgelements as the oracle of the geometry ------------------------------------------------
#: Arcs are converted within this tolerance (path units) in the comparison.
ORACLE_TOL = 0.01
#: svgelements keeps arc centres to about 1e-7; lines and Beziers agree to rounding.
ORACLE_EXACT = 1e-9


def _dense(ctrl, n=400):
    """(n, 2) points on one Bezier segment (ctrl (k+1, 2))."""
    t = np.linspace(0, 1, n)
    k = len(ctrl) - 1
    return sum(math.comb(k, i) * ((1 - t) ** (k - i) * t ** i)[:, None] * ctrl[i]
               for i in range(k + 1))


def _max_gap(a, b):
    """Largest distance from a point of ``a`` to the polyline of samples ``b``
    (its vertices: the caller samples ``b`` densely and adds the spacing)."""
    d = np.hypot(a[:, None, 0] - b[None, :, 0], a[:, None, 1] - b[None, :, 1])
    return float(d.min(axis=1).max())


def assert_geometry_matches_svgelements(d, tol=ORACLE_TOL):
    """Walk svgelements' segments of ``d`` and ours side by side: every line
    and Bezier has the same control points (to ``ORACLE_EXACT`` relative),
    every arc is the chain of our cubics up to its end point, within ``tol``
    of svgelements' arc in both directions (sampled on both sides, the
    sampling spacing added to the allowance)."""
    ours = parse_path(d, tolerance=tol).segments()
    ctrl, deg = ours.ctrl, ours.degree
    scale = max(1.0, float(np.abs(ours.ctrl).max()) if len(ctrl) else 1.0)
    i = 0
    for seg in svgelements.Path(d):
        if isinstance(seg, (svgelements.Move, svgelements.Close)):
            continue
        if isinstance(seg, svgelements.Arc) and seg.start == seg.end:
            continue                              # SVG omits it; svgelements keeps it
        if isinstance(seg, svgelements.Arc):
            start = i
            end = np.array([seg.end.x, seg.end.y])
            while not np.allclose(ctrl[i, 3], end, rtol=0, atol=1e-6 * scale):
                assert deg[i] == 3, (d, i)
                i += 1
            assert deg[i] == 3
            i += 1
            theirs = seg.npoint(np.linspace(0, 1, 2000))
            mine = np.concatenate([_dense(ctrl[j]) for j in range(start, i)])
            spacing = max(np.hypot(*np.diff(theirs, axis=0).T).max(),
                          np.hypot(*np.diff(mine, axis=0).T).max())
            allow = tol + spacing + 1e-6 * scale
            assert _max_gap(mine[::7], theirs) <= allow, d
            assert _max_gap(theirs[::7], mine) <= allow, d
            continue
        if isinstance(seg, svgelements.Line):
            want = [seg.start, seg.end]
        elif isinstance(seg, svgelements.QuadraticBezier):
            want = [seg.start, seg.control, seg.end]
        else:
            want = [seg.start, seg.control1, seg.control2, seg.end]
        want = np.array([[q.x, q.y] for q in want])
        k = len(want) - 1
        assert deg[i] == k, (d, i, type(seg).__name__)
        assert np.allclose(ctrl[i, :k + 1], want, rtol=0, atol=ORACLE_EXACT * scale), (d, i)
        i += 1
    assert i == len(ctrl), d                       # nothing left over on our side


@FEWER
@given(path_strings(svgelements_reflections=True))
def test_geometry_matches_svgelements(d):
    assert_geometry_matches_svgelements(d)


@pytest.mark.parametrize('d', [
    # compact syntax: signs and dots as separators, exponents, packed arc flags
    'M.5.5-.5-.5l1e1-1E1h-2.5v.25z',
    'M0 0a10 10 0 0110 10a5 5 0 1 0-5 5A20 10 30 1 1 40 40',
    'm10,10 c10,0 20,10 20,20 s-10,20-20,20 q-10-10-10-20 t10-20 Z m5 5 l5 0',
    # reflections: chains, and after commands that have no control point
    'M0 0 C 5 5 10 10 20 0 S 30 10 40 0 S 50 -5 60 0 L 70 0 S 80 10 90 0',
    'M0 0 Q 10 10 20 0 T 40 0 T 60 0 H 70 T 80 5 t 10 0',
    # arcs: tiny radii scaled up, rotated, large, negative rotation, huge sweep
    'M 10 20 A 1 1 0 0 1 50 60 A 30 15 -45 1 0 90 20 a 100 20 170 0 1 -40 -10',
    'M 0 0 A 50 50 0 1 1 0.001 0 Z',
])
def test_geometry_matches_svgelements_on_varied_data(d):
    assert_geometry_matches_svgelements(d)


def test_reflection_after_a_bezier_of_the_other_degree():
    """SVG reflects only the control point of its own kind of Bezier: T
    after a cubic and S after a quadratic start with a control point on the
    current point (svgelements reflects the other kind's, so it is not the
    oracle here)."""
    seg = parse_path('M0 0 S 10 10 20 0 T 30 10 Q 40 20 50 10 S 60 0 70 10').segments()
    assert seg.ctrl[1, :3].tolist() == [[20, 0], [20, 0], [30, 10]]             # T after S
    assert seg.ctrl[3, :4].tolist() == [[50, 10], [50, 10], [60, 0], [70, 10]]  # S after Q


@pytest.mark.parametrize('tol', [1.0, 0.1, 0.001])
def test_arc_tolerance_holds_against_svgelements(tol):
    """The stated arc tolerance, checked with svgelements' own ellipse."""
    assert_geometry_matches_svgelements('M 0 0 A 200 80 25 1 1 150 40 A 60 90 -70 0 0 10 100', tol)


# -- round trip --------------------------------------------------------------------------------
@st.composite
def random_paths(draw):
    b = PathBuilder()
    fl = st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False)
    pt = st.tuples(fl, fl)
    b.moveTo(draw(pt))
    for _ in range(draw(st.integers(0, 12))):
        v = draw(st.sampled_from('MLQCZ'))
        if v == 'M':
            b.moveTo(draw(pt))
        elif v == 'L':
            b.lineTo(draw(pt))
        elif v == 'Q':
            b.qCurveTo(draw(pt), draw(pt))
        elif v == 'C':
            b.curveTo(draw(pt), draw(pt), draw(pt))
        else:
            b.closePath()
    return b.path()


@FEWER
@given(random_paths())
def test_round_trip_to_svg(p):
    assert parse_path(p.to_svg()) == p


def test_round_trip_of_parsed_arcs_and_shapes():
    for p in (parse_path('M0 0 A3 5 20 1 0 7 2 T 3 3 Z m1 1 s 1 2 3 4'),
              rect_path(1, 2, 30, 20, 4, 3), ellipse_path(5, 5, 3, 9)):
        assert parse_path(p.to_svg()) == p


# -- shapes --------------------------------------------------------------------------------------
def test_rect_square_corners():
    p = rect_path(1, 2, 10, 5)
    assert p.to_svg() == 'M 1 2 L 11 2 L 11 7 L 1 7 Z'
    assert rect_path(0, 0, 0, 5).is_empty and len(rect_path(0, 0, 5, -1)) == 0


def test_rect_rounded_corners():
    x, y, w, h, rx, ry = 1.0, 2.0, 30.0, 20.0, 4.0, 3.0
    p = rect_path(x, y, w, h, rx, ry)
    n = (len(p.verbs) - 2 - 4) // 4
    assert p.verbs.tolist() == [MOVE] + ([LINE] + [CUBIC] * n) * 4 + [CLOSE]
    seg = p.segments()
    ends = seg.end[seg.degree == 1]
    assert p.points[0].tolist() == [x + rx, y]
    assert ends.tolist() == [[x + w - rx, y], [x + w, y + h - ry], [x + rx, y + h], [x, y + ry]]
    arc_ends = seg.end[np.flatnonzero(seg.degree == 1) + n]
    assert arc_ends.tolist() == [[x + w, y + ry], [x + w - rx, y + h], [x, y + h - ry],
                                 [x + rx, y]]
    # corner arcs lie on their quarter ellipses within tolerance
    for tol in (0.01, 1e-4):
        p = rect_path(x, y, w, h, 40, 30, tolerance=tol)     # clamped to 15, 10
        assert p.points[0].tolist() == [x + 15, y]
        seg = p.segments()
        q = bezier_points(p, 100)[seg.degree == 3]
        n = len(q) // 4
        centres = np.repeat([[x + w - 15, y + 10], [x + w - 15, y + h - 10],
                             [x + 15, y + h - 10], [x + 15, y + 10]], n, axis=0)
        d = q - centres[:, None]
        assert (np.abs(np.hypot(d[..., 0] / 15, d[..., 1] / 10) - 1) * 15).max() <= tol


def test_rect_auto_radii():
    assert rect_path(0, 0, 10, 10, rx=2) == rect_path(0, 0, 10, 10, 2, 2)
    assert rect_path(0, 0, 10, 10, ry=3) == rect_path(0, 0, 10, 10, 3, 3)
    assert rect_path(0, 0, 10, 4, rx=3) == rect_path(0, 0, 10, 4, 3, 2)   # ry clamped
    assert rect_path(0, 0, 10, 10, rx=-1) == rect_path(0, 0, 10, 10)
    with pytest.raises(PathError):
        rect_path(0, 0, float('nan'), 1)


@pytest.mark.parametrize('tol', [0.5, 0.01, 1e-5])
def test_circle_points_on_circle_and_direction(tol):
    cx, cy, r = 3.0, -2.0, 50.0
    p = circle_path(cx, cy, r, tolerance=tol)
    assert p.points[0].tolist() == [cx + r, cy] and p.verbs[-1] == CLOSE
    q = bezier_points(p, 200)
    assert np.abs(np.hypot(q[..., 0] - cx, q[..., 1] - cy) - r).max() <= tol
    ends = p.segments().end
    n = len(ends) // 4
    assert ends[[n - 1, 2 * n - 1, 3 * n - 1, 4 * n - 1]].tolist() == [
        [cx, cy + r], [cx - r, cy], [cx, cy - r], [cx + r, cy]]
    # positive-angle direction: angles increase along the path (y down)
    ang = np.unwrap(np.arctan2(q[..., 1] - cy, q[..., 0] - cx).reshape(-1))
    assert np.all(np.diff(ang) >= -1e-12) and ang[-1] - ang[0] == pytest.approx(2 * np.pi)


def test_ellipse_path():
    p = ellipse_path(0, 0, 8, 2, tolerance=1e-3)
    q = bezier_points(p, 200).reshape(-1, 2)
    assert np.abs(np.hypot(q[:, 0] / 8, q[:, 1] / 2) - 1).max() * 8 <= 1e-3
    assert ellipse_path(0, 0, 0, 5).is_empty and len(circle_path(1, 1, -1)) == 0
    assert ellipse_path(1, 2, rx=3) == ellipse_path(1, 2, 3, 3) == circle_path(1, 2, 3)
    assert len(ellipse_path(1, 2)) == 0


def test_shapes_share_the_unit_quarter_arcs_but_not_their_points():
    # circles, ellipses and rounded corners of one piece count scale the
    # same cached unit arcs (read-only); every shape gets its own points,
    # equal to those built with the cache empty
    makers = [lambda: circle_path(3, 4, 5, tolerance=0.01),
              lambda: ellipse_path(-2, 7, 5, 3, tolerance=0.01),
              lambda: rect_path(1, 2, 30, 20, 5, 4, tolerance=0.01),
              lambda: circle_path(1e5, -3, 4.5, tolerance=0.01)]
    caches = (svgpath._unit_quarters, svgpath._unit_ellipse, svgpath._quarter_pieces)
    fresh = []
    for make in makers:
        for c in caches:
            c.cache_clear()
        fresh.append(make())
    for c in caches:
        c.cache_clear()
    warm = [make() for make in makers]
    assert svgpath._unit_ellipse.cache_info().hits >= 1
    assert svgpath._quarter_pieces.cache_info().hits >= 1
    assert all(a == b for a, b in zip(fresh, warm))
    assert not any(np.shares_memory(a.points, b.points) for a in warm for b in warm if a is not b)
    u = svgpath._unit_quarters(3, (0, 1, 2, 3))
    assert not u.flags.writeable and u.shape == (12, 3, 2)
    # ellipses of one piece count share their (read-only) verbs
    a, b = warm[0], warm[1]
    assert a.verbs is b.verbs and not a.verbs.flags.writeable
    assert a.verbs.tolist() == [MOVE] + [CUBIC] * (len(a.verbs) - 2) + [CLOSE]
    assert u[[2, 5, 8, 11], 2].tolist() == [[0, 1], [-1, 0], [0, -1], [1, 0]]


def test_line_and_polyline():
    assert line_path(1, 2, 1, 2).to_svg() == 'M 1 2 L 1 2'
    assert polyline_path([[0, 0], [1, 0], [1, 1]]).to_svg() == 'M 0 0 L 1 0 L 1 1'
    assert polyline_path('0,0 1,0 1,1', closed=True).to_svg() == 'M 0 0 L 1 0 L 1 1 Z'
    assert len(polyline_path(np.zeros((0, 2)))) == 0 and len(polyline_path('')) == 0
    with pytest.raises(PathError):
        polyline_path([[0, 0, 0]])
    with pytest.raises(PathError):
        polyline_path([[0, float('inf')]])
    with pytest.raises(PathError):
        polyline_path('0 0', tolerance=0)


@pytest.mark.parametrize('s, pts', [
    ('0,0 10,0 10,10', [[0, 0], [10, 0], [10, 10]]),
    ('1-2-3-4', [[1, -2], [-3, -4]]),
    ('1 2 3', [[1, 2]]),                           # odd count: last dropped
    ('1 2 3 4 x 5 6', [[1, 2], [3, 4]]),           # stop at the error
    ('1 2,,3 4', [[1, 2]]),
    (',1 2', []),
    ('1 2 1e999 4', [[1, 2]]),
    ('  .5.5  ', [[0.5, 0.5]]),
    ('', []),
])
def test_parse_points(s, pts):
    out = parse_points(s)
    assert out.dtype == np.float64 and out.shape == (len(pts), 2)
    assert out.tolist() == pts


def test_public_name():
    assert raster.parse_path is parse_path
    with pytest.raises(PathError):
        parse_points(5)


# -- invariances ---------------------------------------------------------------------------------
@st.composite
def absolute_commands(draw):
    """A list of (letter, absolute args) with integer coordinates."""
    n = draw(st.integers(1, 20))
    coord = st.integers(-60, 60)
    cmds = [('M', [draw(coord), draw(coord)])]
    for _ in range(n):
        c = draw(st.sampled_from('MLHVCSQTAZ'))
        k = _CMD_ARGS[c]
        args = [draw(coord) for _ in range(k)]
        if c == 'A':
            args[0], args[1] = abs(args[0]) + 1, abs(args[1]) + 1
            args[3], args[4] = draw(st.integers(0, 1)), draw(st.integers(0, 1))
        cmds.append((c, args))
    return cmds


def _spell(cmds, relative):
    """SVG text of ``cmds``, with relative commands when asked (the current
    point is tracked here independently of the parser)."""
    x = y = sx = sy = 0
    out = []
    for c, a in cmds:
        a = list(a)
        if relative and c != 'Z':
            if c == 'H':
                a = [a[0] - x]
            elif c == 'V':
                a = [a[0] - y]
            elif c == 'A':
                a[5], a[6] = a[5] - x, a[6] - y
            else:
                a = [v - (x if i % 2 == 0 else y) for i, v in enumerate(a)]
        out.append((c.lower() if relative else c) + ' '.join(map(str, a)))
        # advance the current point
        if c == 'Z':
            x, y = sx, sy
        elif c == 'H':
            x = (a[0] + x) if relative else a[0]
        elif c == 'V':
            y = (a[0] + y) if relative else a[0]
        else:
            ex, ey = a[-2], a[-1]
            x, y = (x + ex, y + ey) if relative else (ex, ey)
            if c == 'M':
                sx, sy = x, y
    return ' '.join(out)


@SETTINGS
@given(absolute_commands())
def test_relative_and_absolute_spellings_agree(cmds):
    a = parse_path(_spell(cmds, False))
    r = parse_path(_spell(cmds, True))
    assert a.verbs.tolist() == r.verbs.tolist()
    assert np.allclose(a.points, r.points, rtol=0, atol=1e-9)


@SETTINGS
@given(path_strings(), st.sampled_from([0.5, 2.0, 4.0]))
def test_scaling_by_powers_of_two_is_exact(d, k):
    # scaling the data by k (exact in binary) with tolerance * k scales the path
    def scaled(tok):
        try:
            return repr(float(tok) * k)
        except ValueError:
            return tok
    # arc rotations and flags are not scaled: walk the tokens
    out, letter, arg = [], 'M', 0
    for tok in d.split(' '):
        head = tok[0] if tok and tok[0].isalpha() else ''
        if head:
            letter, arg, tok = head, 0, tok[1:]
        if tok == '':
            out.append(head)
            continue
        if letter in 'Aa' and arg % 7 in (2, 3, 4):
            out.append(head + tok)
        else:
            out.append(head + scaled(tok))
        arg += 1
    d2 = ' '.join(out)
    p = parse_path(d, tolerance=0.01)
    q = parse_path(d2, tolerance=0.01 * k)
    assert q == p.transform(raster.Affine.scale(k))


@SETTINGS
@given(absolute_commands(), st.integers(-1000, 1000), st.integers(-1000, 1000))
def test_translation_invariance(cmds, tx, ty):
    def moved(cmds):
        out = []
        for c, a in cmds:
            a = list(a)
            if c == 'H':
                a = [a[0] + tx]
            elif c == 'V':
                a = [a[0] + ty]
            elif c == 'A':
                a[5], a[6] = a[5] + tx, a[6] + ty
            elif c != 'Z':
                a = [v + (tx if i % 2 == 0 else ty) for i, v in enumerate(a)]
            out.append((c, a))
        return out
    p = parse_path(_spell(cmds, False)).transform(raster.Affine.translate(tx, ty))
    q = parse_path(_spell(moved(cmds), False))
    assert p.verbs.tolist() == q.verbs.tolist()
    assert np.allclose(p.points, q.points, rtol=0, atol=1e-9)


# -- the vectorized lexer ----------------------------------------------------------

@st.composite
def number_runs(draw):
    """Path-like text made of numbers in many spellings (signs, bare and
    trailing dots, leading zeros, '1.5.5' runs, long mantissas), command
    letters, arc flags and separators."""
    pieces = st.one_of(
        st.integers(-10 ** 17, 10 ** 17).map(str),
        st.floats(-1e6, 1e6, allow_nan=False).map(lambda v: '%.*f' % (abs(hash(v)) % 9, v)),
        st.sampled_from(['0', '-0', '+0', '00', '007', '.5', '-.5', '+.5', '1.5.5', '-1-2',
                         '3.', '1..5', '0.' + '0' * 20 + '1', '9' * 16, '.25.125.5']),
        st.sampled_from(list('MmLlHhVvCcSsQqTtAaZz,') + [' ', '  ', '\n', '\t', '-', '+',
                                                         '.', 'x', '\u00e9', '#']))
    return ''.join(draw(st.lists(pieces, max_size=40)))


@SETTINGS
@given(number_runs())
def test_fast_lexer_equals_regex_lexer(d):
    d = svgpath._mark(d)
    fast = svgpath._lex_fast(d)
    nums, kinds = svgpath._split(d)
    if fast is None:            # (only for data the fast lexer leaves alone)
        assert (not d or not d.isascii() or 'e' in d or 'E' in d
                or any(c == '.' and not d[i + 1:i + 2].isdigit() for i, c in enumerate(d))
                or any(c in '+-' and d[i + 1:i + 2] not in tuple('0123456789.')
                       for i, c in enumerate(d)))
        return
    assert fast[0] == kinds
    want = np.array(nums, dtype=np.float64)
    # bit for bit, signed zeros included
    assert fast[1].dtype == np.float64 and fast[1].tobytes() == want.tobytes()


def _parse_outcome(d):
    try:
        p = parse_path(d)
    except PathError as e:
        return 'error', str(e)
    return p.verbs.tobytes(), p.points.tobytes()


@SETTINGS
@given(st.lists(st.sampled_from(['M', 'L1', '2', ' ', ',', '-3.5', '.5', 'c', 'z', 'x',
                                 'A1 1 0 1 0 4 4', '1e2', '7.', '+', '0']), max_size=40),
       st.integers(1, 30))
def test_long_data_lexed_in_chunks_parses_the_same(tokens, chunk):
    # parse_path lexes data longer than _LEX_CHUNK in chunks cut after a
    # space or comma: the same path, or the same error at the same place
    d = ''.join(tokens)
    whole = _parse_outcome(d)
    saved = svgpath._LEX_CHUNK
    svgpath._LEX_CHUNK = chunk
    try:
        cut = _parse_outcome(d)
    finally:
        svgpath._LEX_CHUNK = saved
    assert cut == whole


def test_a_megabyte_of_path_data_is_lexed_in_chunks():
    rng = np.random.default_rng(5)
    d = 'M0 0' + ''.join('L%.3f,%.3f %.2f-%.1f' % (x, y, z, abs(w))
                         for x, y, z, w in rng.normal(0, 50, (40000, 4)))
    assert len(d) > 3 * svgpath._LEX_CHUNK
    nums, kinds = svgpath._split(svgpath._mark(d))
    calls = []
    fast = svgpath._lex_fast

    def counted(part):
        calls.append(len(part))
        return fast(part)
    svgpath._lex_fast = counted
    try:
        k, v = svgpath._lex_values(d)
        p = parse_path(d)
    finally:
        svgpath._lex_fast = fast
    assert k == kinds and v.tobytes() == np.array(nums, np.float64).tobytes()
    assert max(calls) < svgpath._LEX_CHUNK + 64 and len(calls) >= 8
    assert np.array_equal(p.points[1:3], [[float(nums[2]), float(nums[3])],
                                          [float(nums[4]), float(nums[5])]])


def test_fast_lexer_reads_long_and_tiny_numbers_exactly():
    nums = ['123456789012345678', '0.' + '0' * 25 + '7', '-9007199254740993',
            '0.1', '-0', '.1.2.3', '4503599627370497.5']
    d = 'M ' + ' '.join(nums) * 200
    k, v = svgpath._lex_fast(d)
    assert v.tobytes() == np.array(svgpath._split(d)[0], np.float64).tobytes()
    assert np.signbit(v[4]) and v[4] == 0


def test_fast_lexer_is_used_for_long_data_and_agrees(monkeypatch):
    rng = np.random.default_rng(11)
    d = 'M0 0' + ''.join('c%s' % ','.join('%.3f' % x for x in rng.normal(0, 5, 6))
                         for _ in range(2000))
    assert len(d) >= svgpath.FAST_LEX_CHARS and svgpath._lex_fast(svgpath._mark(d)) is not None
    _, nums, kb = _lex(d)
    a = _build_loop(kb.replace(b',', b''), [float(x) for x in nums], 0.01)
    b = parse_path(d)
    assert a.verbs.tolist() == b.verbs.tolist()
    assert np.allclose(a.points, b.points, rtol=1e-12, atol=1e-9)
    # long paths with errors: the messages do not depend on the lexer
    bad = [d + ' L1', d[:5000] + ' x ' + d[5000:], d + ' 1e999 0']
    msgs = []
    for b in bad:
        with pytest.raises(PathError) as e:
            parse_path(b)
        msgs.append(str(e.value))
    monkeypatch.setattr(svgpath, 'FAST_LEX_CHARS', 10 ** 9)
    for b, m in zip(bad, msgs):
        with pytest.raises(PathError) as e:
            parse_path(b)
        assert str(e.value) == m
    assert msgs[0] == 'path data error at %d: expected number' % len(bad[0])


@SETTINGS
@given(st.binary(max_size=12).map(lambda b: bytes(b'#,\x00\x01M |x'[c % 8] for c in b)))
def test_bad_commas_equals_the_regular_expressions(kb):
    want = bool(svgpath._COMMA_AFTER_BAD.search(kb) or svgpath._COMMA_BEFORE_BAD.search(kb))
    assert svgpath._bad_commas(kb) == want


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet='MmLlHhVvCcSsQqTtAaZz#,\x00\x01x', max_size=40))
def test_validity_regex_agrees_with_its_plain_form(kb):
    """The token-validity regex uses possessive repeats where the
    interpreter gets them right (3.11.5+); it must accept exactly what the
    plain-repeat form accepts (a buggy engine once disagreed: gh-106052)."""
    from raster.geometry import pathdata
    data = kb.encode('latin-1')
    plain = pathdata.validity_regex(possessive=False)
    assert pathdata._VALID.match(data).end() == plain.match(data).end()
    if sys.version_info >= (3, 11, 5):
        assert pathdata.validity_regex(True).match(data).end() == plain.match(data).end()
