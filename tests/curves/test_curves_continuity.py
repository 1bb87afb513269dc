"""Tests of raster.curves.continuity on joints built by hand."""

import numpy as np
import pytest

from raster.curves import (PiecewiseBezier, BSpline, BetaSpline, KochanekBartels, continuity,
                           format_joints, CurveError)


def chain(*segs, breaks=None):
    return PiecewiseBezier(np.array(segs, float), breaks)


def test_c2_cubic_bspline_joints():
    j = BSpline(np.random.default_rng(0).normal(size=(6, 2)), 3).continuity()
    assert [(x.C, x.G) for x in j] == [(2, 2), (2, 2)]


def test_collinear_lines_different_speed_are_g2_c0():
    # (0,0)->(1,0) then (1,0)->(3,0): tangent (1,0) vs (2,0): same direction
    j = continuity(chain([[0, 0], [1, 0]], [[1, 0], [3, 0]]))[0]
    assert (j.C, j.G) == (0, 2)
    assert j.angle == pytest.approx(0.0)
    # the same joint with the second segment on a parameter interval of length 2 is C2
    j = continuity(chain([[0, 0], [1, 0]], [[1, 0], [3, 0]], breaks=[0, 1, 3]))[0]
    assert (j.C, j.G) == (2, 2)


def test_c1_not_g2_cubic_into_line():
    # cubic (0,0),(2,0),(1,1),(3,1): end velocity 3(P3-P2) = (6, 0), end
    # acceleration 6(P3 - 2P2 + P1) = (18, -6), curvature != 0;
    # the line (3,1)->(9,1) as a cubic starts with velocity (6, 0) and no curvature
    j = continuity(chain([[0, 0], [2, 0], [1, 1], [3, 1]], [[3, 1], [5, 1], [7, 1], [9, 1]]))[0]
    assert (j.C, j.G) == (1, 1)
    assert j.curvature_jump > 0.1


def test_corner_and_gap():
    j = continuity(chain([[0, 0], [1, 0]], [[1, 0], [1, 1]]))[0]
    assert (j.C, j.G) == (0, 0)
    assert j.angle == pytest.approx(np.pi / 2)
    j = continuity(chain([[0, 0], [1, 0]], [[1, 0.5], [1, 1]]))[0]
    assert (j.C, j.G) == (-1, -1)
    assert j.gap == pytest.approx(0.5)


def test_beta_spline_is_g2_but_not_c1():
    j = BetaSpline(np.random.default_rng(3).normal(size=(6, 2)), beta1=2.0, beta2=1.0).continuity()
    assert all((x.C, x.G) == (0, 2) for x in j)


def test_tolerance_is_honoured():
    pb = chain([[0, 0], [1, 0]], [[1 + 1e-6, 0], [2, 0]])
    assert continuity(pb, 1e-9)[0].G == -1
    assert continuity(pb, 1e-5)[0].G >= 0


def test_closed_joint_and_format():
    pb = chain([[0, 0], [1, 0]], [[1, 0], [0, 1]], [[0, 1], [0, 0]])
    assert len(continuity(pb)) == 2
    j = continuity(pb, closed=True)
    assert len(j) == 3 and j[-1].index == 2 and j[-1].C == 0
    text = format_joints(j)
    assert text.count('\n') == 3 and 'C0' in text
    assert format_joints([]) == 'no joints (single segment)'


def test_kb_continuity_parameter_breaks_tangent_continuity():
    p = [[0, 0], [1, 2], [3, 2], [4, 0]]
    smooth = KochanekBartels(p).continuity()
    kinked = KochanekBartels(p, continuity=0.8).continuity()
    assert all(j.C >= 1 for j in smooth)
    assert all(j.C == 0 and j.G == 0 for j in kinked)


def test_bad_tolerance():
    with pytest.raises(CurveError):
        continuity(chain([[0, 0], [1, 0]], [[1, 0], [2, 0]]), tolerance=-1)
