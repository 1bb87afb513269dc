"""The path model (raster.path) and affine transforms (raster.transform):
the builder's guarantees, segment arrays, pens, transform algebra."""

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from raster import parse_path
from raster.errors import PathError, TransformError
from raster.path import (CLOSE, CUBIC, LINE, MOVE, QUAD, Path, PathBuilder, RecordingPen,
                         TransformPen)
from raster.transform import IDENTITY, Affine, as_affine


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
    with pytest.raises(PathError, match='non-finite'):
        Path.from_arrays([MOVE, LINE], [[0, 0], [bad, 1]])


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


@pytest.mark.parametrize('verbs, n', [([LINE], 1), ([MOVE, CLOSE, LINE], 2), ([7], 1)])
def test_from_arrays_validates_structure(verbs, n):
    with pytest.raises(PathError):
        Path.from_arrays(verbs, np.zeros((n, 2)))


def test_path_is_immutable():
    p = parse_path('M0 0 L1 1')
    with pytest.raises(AttributeError):
        p.verbs = None
    with pytest.raises(ValueError):
        p.points[0, 0] = 3.0


# -- segments -------------------------------------------------------------------

def test_segments_arrays():
    p = parse_path('M0 0 L10 0 Q20 0 20 10 Z M30 30 C31 31 32 32 33 30 M50 50')
    s = p.segments()
    assert s.degree.tolist() == [1, 2, 3]
    assert s.contour.tolist() == [0, 0, 1]
    assert s.contour_closed.tolist() == [True, False, False]
    assert s.contour_nseg.tolist() == [2, 1, 0]
    # start point first, unused slots repeat the end point
    assert s.ctrl[0].tolist() == [[0, 0], [10, 0], [10, 0], [10, 0]]
    assert s.ctrl[1].tolist() == [[10, 0], [20, 0], [20, 10], [20, 10]]
    assert s.contour_end.tolist() == [[20, 10], [33, 30], [50, 50]]


def test_svg_round_trip_and_empty_path():
    d = 'M0 0 L10 0 Q20 0 20 10 C 1 2 3 4 5 6 Z'
    p = parse_path(d)
    assert parse_path(p.to_svg()) == p
    assert Path.empty().is_empty and Path.empty().to_svg() == ''
    assert parse_path('M1 1').is_empty


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
