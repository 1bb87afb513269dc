"""Tests of raster.geometry.pens: the builder's guarantees, the pens built
on BasePen, and BasePen's decomposition of the pen protocol (TrueType
implied on-curve points, the None end of an all-off-curve contour,
super-Beziers) against fontTools' own BasePen on the same input."""

import math

import numpy as np
import pytest
from fontTools.pens.basePen import BasePen as FontToolsBasePen
from hypothesis import given, settings, strategies as st

from raster import parse_path
from raster.errors import PathError
from raster.geometry.path import CLOSE, CUBIC, LINE, MOVE, QUAD
from raster.geometry.pens import BasePen, PathBuilder, RecordingPen, TransformPen
from raster.geometry.transform import Affine


# -- builder guarantees --------------------------------------------------------

def test_builder_makes_verbs_and_points():
    b = PathBuilder()
    b.moveTo((0, 0))
    b.lineTo((10, 0))
    b.qCurveTo((10, 10), (0, 10))
    b.curveTo((-5, 10), (-5, 0), (0, 0))
    b.closePath()
    p = b.path()
    assert p.verbs.tolist() == [MOVE, LINE, QUAD, CUBIC, CLOSE]
    assert p.points.shape == (7, 2) and p.points.dtype == np.float64


@pytest.mark.parametrize('call', ['lineTo', 'qCurveTo', 'curveTo'])
def test_drawing_without_a_move_is_refused(call):
    b = PathBuilder()
    args = {'lineTo': [(1, 1)], 'qCurveTo': [(1, 1), (2, 2)],
            'curveTo': [(1, 1), (2, 2), (3, 3)]}[call]
    with pytest.raises(PathError, match='no current point'):
        getattr(b, call)(*args)


@pytest.mark.parametrize('bad', [math.nan, math.inf, -math.inf])
def test_non_finite_points_are_refused(bad):
    b = PathBuilder()
    with pytest.raises(PathError, match='non-finite'):
        b.moveTo((bad, 0))
    b.moveTo((0, 0))
    with pytest.raises(PathError, match='non-finite'):
        b.curveTo((1, 1), (bad, 2), (3, 3))


def test_drawing_after_close_starts_at_the_contour_start():
    """SVG: after Z the current point is the subpath's first point."""
    b = PathBuilder()
    b.moveTo((5, 5))
    b.lineTo((10, 5))
    b.closePath()
    b.lineTo((7, 9))
    p = b.path()
    assert p.verbs.tolist() == [MOVE, LINE, CLOSE, MOVE, LINE]
    assert p.points[2].tolist() == [5, 5]


def test_end_path_requires_a_new_move():
    b = PathBuilder()
    b.moveTo((0, 0))
    b.lineTo((1, 0))
    b.endPath()
    with pytest.raises(PathError):
        b.lineTo((2, 2))


def test_truetype_implied_on_curve_points():
    """qCurveTo with two off-curve points: the on-curve point between them
    is their midpoint (TrueType rule)."""
    b = PathBuilder()
    b.moveTo((0, 0))
    b.qCurveTo((0, 10), (10, 10), (10, 0))
    p = b.path()
    assert p.verbs.tolist() == [MOVE, QUAD, QUAD]
    assert p.points.tolist() == [[0, 0], [0, 10], [5, 10], [10, 10], [10, 0]]


# -- pens -------------------------------------------------------------------------

def test_recording_pen_replays_into_a_builder():
    p = parse_path('M0 0 L10 0 Q20 0 20 10 C 1 2 3 4 5 6 Z')
    rec = RecordingPen()
    p.draw(rec)
    assert [name for name, _ in rec.value] == ['moveTo', 'lineTo', 'qCurveTo', 'curveTo',
                                               'closePath']
    b = PathBuilder()
    rec.replay(b)
    assert b.path() == p


def test_transform_pen_equals_path_transform():
    p = parse_path('M0 0 L10 0 Q20 0 20 10 C 1 2 3 4 5 6 Z')
    t = Affine.rotate(30, 5, 5) @ Affine.scale(2, 0.5)
    b = PathBuilder()
    p.draw(TransformPen(b, t))
    assert np.allclose(b.path().points, p.transform(t).points)
    assert b.path().verbs.tolist() == p.verbs.tolist()


def test_builder_none_end_closes_an_off_curve_contour():
    """qCurveTo(..., None): the contour starts and ends at the implied point
    between the last and the first off-curve point."""
    b = PathBuilder()
    b.qCurveTo((0, 0), (10, 0), (10, 10), (0, 10), None)
    b.closePath()
    p = b.path()
    assert p.verbs.tolist() == [MOVE, QUAD, QUAD, QUAD, QUAD, CLOSE]
    assert p.points.tolist() == [[0, 5], [0, 0], [5, 0], [10, 0], [10, 5], [10, 10], [5, 10],
                                 [0, 10], [0, 5]]


def test_builder_curve_to_with_one_and_two_points():
    b = PathBuilder()
    b.moveTo((0, 0))
    b.curveTo((1, 1))                    # a line
    b.curveTo((2, 3), (4, 1))            # a quadratic
    assert b.path().verbs.tolist() == [MOVE, LINE, QUAD]
    with pytest.raises(PathError):
        b.curveTo()
    with pytest.raises(PathError):
        b.qCurveTo()
    with pytest.raises(PathError):
        b.qCurveTo(None)


def test_builder_super_bezier_is_smooth_and_ends_on_its_point():
    """curveTo with four off-curve points: three cubics, joined with one
    tangent, from the current point to the last point."""
    b = PathBuilder()
    b.moveTo((0, 0))
    b.curveTo((0, 10), (10, 20), (20, 20), (30, 10), (30, 0))
    seg = b.path().segments()
    assert seg.degree.tolist() == [3, 3, 3]
    assert seg.ctrl[-1, 3].tolist() == [30, 0]
    # G1 joints: the controls on both sides are collinear with the joint
    for k in range(2):
        a = seg.ctrl[k, 3] - seg.ctrl[k, 2]
        c = seg.ctrl[k + 1, 1] - seg.ctrl[k + 1, 0]
        assert abs(a[0] * c[1] - a[1] * c[0]) < 1e-9 and np.dot(a, c) > 0


# -- BasePen against fontTools' BasePen -----------------------------------------------------

class _Log:
    """The calls of a pen's segment hooks, points as float tuples."""

    def _log(self, name, *pts):
        self.calls.append((name, tuple((float(p[0]), float(p[1])) for p in pts)))

    def _moveTo(self, pt):
        self._log('move', pt)

    def _lineTo(self, pt):
        self._log('line', pt)

    def _curveToOne(self, a, b, c):
        self._log('cubic', a, b, c)

    def _qCurveToOne(self, a, b):
        self._log('quad', a, b)

    def _closePath(self):
        self._log('close')

    def _endPath(self):
        self._log('end')


class OurLog(_Log, BasePen):
    def __init__(self):
        BasePen.__init__(self)
        self.calls = []


class TheirLog(_Log, FontToolsBasePen):
    def __init__(self):
        FontToolsBasePen.__init__(self, glyphSet=None)
        self.calls = []


coord = st.one_of(st.integers(-1000, 1000), st.floats(-1000, 1000, allow_nan=False))
point = st.tuples(coord, coord)


@st.composite
def pen_programs(draw):
    """Pen calls that are valid for both pens: every contour starts with a
    moveTo or an all-off-curve qCurveTo(..., None)."""
    ops = []
    for _ in range(draw(st.integers(1, 6))):
        if draw(st.booleans()):
            ops.append(('moveTo', (draw(point),)))
        else:
            ops.append(('qCurveTo', tuple(draw(st.lists(point, min_size=1, max_size=6))) + (None,)))
        for _ in range(draw(st.integers(0, 5))):
            name = draw(st.sampled_from(['lineTo', 'curveTo', 'qCurveTo']))
            n = 1 if name == 'lineTo' else draw(st.integers(1, 8))
            ops.append((name, tuple(draw(st.lists(point, min_size=n, max_size=n)))))
        ops.append((draw(st.sampled_from(['closePath', 'endPath'])), ()))
    return ops


@settings(max_examples=300, deadline=None)
@given(pen_programs())
def test_decomposition_matches_fonttools_basepen(ops):
    """The same hook calls with the same points, bit for bit: implied
    on-curve points, the None end point, super-Beziers, curveTo with one or
    two points, qCurveTo with one."""
    ours, theirs = OurLog(), TheirLog()
    for name, args in ops:
        getattr(ours, name)(*args)
        getattr(theirs, name)(*args)
    assert ours.calls == theirs.calls


@pytest.mark.parametrize('n', range(3, 10))
def test_super_bezier_matches_fonttools(n):
    rng = np.random.default_rng(n)
    pts = [tuple(p) for p in rng.uniform(-100, 100, (n, 2)).tolist()]
    ours, theirs = OurLog(), TheirLog()
    for pen in (ours, theirs):
        pen.moveTo((0.5, -0.25))
        pen.curveTo(*pts)
    assert ours.calls == theirs.calls
    assert [c[0] for c in ours.calls] == ['move'] + ['cubic'] * (max(n - 2, 1))


def test_glyph_outlines_match_fonttools():
    """Every glyph of a TrueType font drawn into a PathBuilder: the same
    segments as fontTools' BasePen decomposition of the same outline."""
    from fontTools.ttLib import TTFont
    from raster.curves.plot import FONT_FILE
    font = TTFont(FONT_FILE)
    gs = font.getGlyphSet()
    names = font.getGlyphOrder()
    assert len(names) > 50
    for name in names:
        theirs = TheirLog()
        gs[name].draw(theirs)
        b = PathBuilder()
        gs[name].draw(b)
        rec = RecordingPen()
        b.path().draw(rec)
        ours = OurLog()
        rec.replay(ours)
        # the builder's path closes contours (no explicit end) as fontTools' pen saw them
        assert ([c for c in ours.calls if c[0] != 'close']
                == [c for c in theirs.calls if c[0] != 'close']), name


def test_base_pen_default_quadratic_is_the_exact_cubic():
    class Cubics(BasePen):
        def __init__(self):
            super().__init__()
            self.segs = []

        def _moveTo(self, pt):
            pass

        def _curveToOne(self, a, b, c):
            self.segs.append((a, b, c))

    pen = Cubics()
    pen.moveTo((0, 0))
    pen.qCurveTo((3, 6), (6, 0))
    assert pen.segs == [((2.0, 4.0), (4.0, 4.0), (6.0, 0.0))]
    assert pen.current_point == (6.0, 0.0)
    with pytest.raises(NotImplementedError):
        pen.lineTo((1, 1))


def test_current_point_after_close_and_end():
    b = PathBuilder()
    assert b.current_point is None
    b.moveTo((1, 2)); b.lineTo((3, 4))
    assert b.current_point == (3.0, 4.0)
    b.closePath()
    assert b.current_point == (1.0, 2.0)
    b.endPath()
    assert b.current_point is None
    with pytest.raises(PathError, match='components'):
        b.addComponent('a', (1, 0, 0, 1, 0, 0))


def test_recording_pen_records_single_segments():
    rec = RecordingPen()
    rec.moveTo((0, 0))
    rec.qCurveTo((0, 10), (10, 10), (10, 0))
    rec.curveTo((1, 1), (2, 2), (3, 3), (4, 4), (5, 5))
    rec.endPath()
    assert [n for n, _ in rec.value] == ['moveTo', 'qCurveTo', 'qCurveTo', 'curveTo', 'curveTo',
                                         'curveTo', 'endPath']
    assert rec.value[1][1] == ((0.0, 10.0), (5.0, 10.0))


def test_transform_pen_of_truetype_quadratics():
    """Decomposed before the transform: the same path as transforming the
    builder's path (midpoints commute with affine maps, up to rounding)."""
    t = Affine.rotate(20) @ Affine.scale(3, -2)
    b1, b2 = PathBuilder(), PathBuilder()
    for pen in (b1, TransformPen(b2, t)):
        pen.qCurveTo((0, 0), (10, 0), (10, 10), None)
        pen.closePath()
        pen.moveTo((5, 5))
        pen.curveTo((6, 9), (8, 9), (9, 7), (9, 5))
    p1, p2 = b1.path().transform(t), b2.path()
    assert p1.verbs.tolist() == p2.verbs.tolist()
    assert np.allclose(p1.points, p2.points, rtol=0, atol=1e-12)
