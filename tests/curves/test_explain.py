"""raster.curves.explain: the worked solutions in the three formats, for
every family."""

import re

import numpy as np
import pytest

from raster.curves import (BetaSpline, Bezier, BSpline, CardinalSpline, CatmullRom, CurveError,
                           FunctionSpline, Hermite, HermiteSpline, KochanekBartels, NaturalSpline,
                           NURBS, RationalBezier, explain)

FAMILIES = [
    (Bezier([[1, 1], [2, 3], [4, 3], [6, 4]]), [0.2, 0.8]),
    (Hermite([0, 0], [1, 0], [0, 3], [0, -3]), [0.5]),
    (HermiteSpline([[0, 0], [1, 1], [2, 0]], [[1, 0], [1, 0]], [[1, 0], [1, 0]]), [0.5, 1.5]),
    (CatmullRom([[0, 0], [1, 2], [3, 2], [4, 0]]), [1.5]),
    (CardinalSpline([[0, 0], [1, 2], [3, 2], [4, 0]], 0.5), [0.5]),
    (KochanekBartels([[0, 0], [1, 2], [3, 2], [4, 0]], 0.2, 0.5, 0.1), [2.5]),
    (BSpline([[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]], 2), [0.5]),
    (BetaSpline([[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]], 2, 1), [0.5]),
    (FunctionSpline([0, 1, 2, 3], [0, 1, 0, 1], [1, -1]), [0.5]),
    (NaturalSpline([[0, 0], [1, 1], [2, 0]]), [0.25]),
    (RationalBezier([[1, 0], [1, 1], [0, 1]], [1, 2 ** -0.5, 1]), [0.5]),
    (NURBS([[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]], [1, 2, 1, 2, 1], 2), [0.3]),
]


def numbers_after(text, label):
    """The last number on the line that starts with ``label``."""
    for line in text.splitlines():
        if line.strip().startswith(label):
            return float(re.findall(r'-?[\d.]+(?:e-?\d+)?', line)[-1])
    raise AssertionError('no line %r' % label)


@pytest.mark.parametrize('curve,ts', FAMILIES, ids=lambda x: type(x).__name__)
def test_every_family_explains_with_its_own_values(curve, ts):
    text = explain(curve, ts)
    # the substituted results are the curve's points (6 significant digits)
    for t in ts:
        want = np.atleast_1d(curve.eval(t))
        if isinstance(curve, (FunctionSpline, NaturalSpline)):
            # the table of values
            for v in want[1:] if isinstance(curve, FunctionSpline) else want:
                assert '%.6g' % v in text
            continue
        got = [numbers_after(text, '%s(%s) =' % (a, ('%.6g' % t))) for a in 'xy'] \
            if not isinstance(curve, (HermiteSpline,)) or isinstance(curve, Hermite) else None
        if got is not None:
            np.testing.assert_allclose(got, want[:2], rtol=1e-5, atol=1e-5)
    for fmt in ('markdown', 'latex'):
        assert explain(curve, ts, fmt)


def test_formats():
    b = Bezier([[2, 6], [6, 8], [9, 12]])
    plain = explain(b, [0.8])
    md = explain(b, [0.8], 'markdown')
    tex = explain(b, [0.8], 'latex')
    assert 'Blending functions for n = 2\n----------------------------' in plain
    assert '### Blending functions for n = 2' in md and '\\begin{aligned}' in md
    assert '| $t$ | $x(t)$ | $y(t)$ |' in md and '| 0.8 | 7.76 | 10.48 |' in md
    assert '\\subsection*{Blending functions for n = 2}' in tex
    assert '\\begin{align*}' in tex and '\\begin{tabular}{rrr}' in tex
    assert 'B_{2,1}(t) &= \\frac{2!}{1!\\,1!} t^{1} (1-t)^{1} = 2t(1-t)' in tex
    # braces balance in every LaTeX line
    for line in tex.splitlines():
        assert line.count('{') == line.count('}'), line
    with pytest.raises(CurveError, match='format'):
        explain(b, [0.5], 'html')
    with pytest.raises(CurveError, match='outside the domain'):
        explain(b, [1.5])


def test_natural_spline_clamped_rows_and_solution():
    # clamped ends s0 = 1, s3 = -1 on (0,0),(1,1),(2,0),(3,1): first row
    # 2 M0 + M1 = 6((1 - 0)/1 - 1) = 0, last M2 + 2 M3 = 6(-1 - 1) = -12
    f = FunctionSpline([0, 1, 2, 3], [0, 1, 0, 1], [1, -1])
    text = explain(f, [])
    assert '2 M0 + 1 M1 = 0' in text and '1 M2 + 2 M3 = -12' in text
    M = f.second_derivatives()
    assert 'M0 = %s' % ('%.6g' % M[0]) in text
    # the interior rows hold for the solution printed
    h = 1.0
    assert M[0] * h + 4 * M[1] + M[2] == pytest.approx(-12)


def test_hermite_spline_lists_every_segment():
    hs = HermiteSpline([[0, 0], [1, 1], [2, 0]], [[1, 0], [1, 0]], [[1, 0], [1, 0]])
    text = explain(hs, [0.5, 1.5])
    assert 'Segment 0 (t in [0, 1])' in text and 'Segment 1 (t in [1, 2])' in text
    assert 'At t = 1.5, u = 0.5:' in text


def test_continuity_section_only_with_joints():
    assert 'Continuity at the joints' not in explain(Bezier([[0, 0], [1, 1]]), [0.5])
    text = explain(BSpline([[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]], 2), [])
    assert text.count('joint ') >= 2 and 'C1, G1' in text
