"""The path model (raster.geometry.path): validation, immutability,
segment arrays, SVG output."""

import numpy as np
import pytest

from raster import parse_path
from raster.errors import PathError
from raster.geometry.path import CLOSE, CUBIC, LINE, MOVE, QUAD, Path, segment_arrays


# -- validation ----------------------------------------------------------------

@pytest.mark.parametrize('verbs, n', [([LINE], 1), ([MOVE, CLOSE, LINE], 2), ([7], 1)])
def test_from_arrays_validates_structure(verbs, n):
    with pytest.raises(PathError):
        Path.from_arrays(verbs, np.zeros((n, 2)))


@pytest.mark.parametrize('bad', [np.nan, np.inf, -np.inf])
def test_non_finite_points_are_refused(bad):
    with pytest.raises(PathError, match='non-finite'):
        Path.from_arrays([MOVE, LINE], [[0, 0], [bad, 1]])


def test_path_is_immutable():
    p = parse_path('M0 0 L1 1')
    with pytest.raises(AttributeError):
        p.verbs = None
    with pytest.raises(ValueError):
        p.points[0, 0] = 3.0


def test_path_pickles_and_copies_as_an_immutable_path():
    import copy
    import pickle
    p = parse_path('M0 0 L10 0 Q20 0 20 10 Z M30 30 C31 31 32 32 33 30')
    p.segments()                                   # (a filled cache is not carried)
    for q in (pickle.loads(pickle.dumps(p)), copy.copy(p), copy.deepcopy(p)):
        assert type(q) is Path and q == p and q.verbs.dtype == p.verbs.dtype
        assert q.segments().ctrl.tolist() == p.segments().ctrl.tolist()
        with pytest.raises(AttributeError):
            q.verbs = None
        with pytest.raises(ValueError):
            q.points[0, 0] = 3.0


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


def test_segment_arrays_of_concatenated_paths():
    """Paths concatenated verb for verb (every path starts with a move) give
    the segments of each, contour numbers running on."""
    a = parse_path('M0 0 L10 0 Q20 0 20 10 Z M 3 3')
    b = parse_path('M5 5 C 6 6 7 7 8 5 L 0 0')
    both = segment_arrays(np.concatenate([a.verbs, b.verbs]), np.concatenate([a.points, b.points]))
    sa, sb = a.segments(), b.segments()
    assert np.array_equal(both.ctrl, np.concatenate([sa.ctrl, sb.ctrl]))
    assert both.degree.tolist() == sa.degree.tolist() + sb.degree.tolist()
    assert both.contour.tolist() == sa.contour.tolist() + (sb.contour + 2).tolist()
    assert both.contour_nseg.tolist() == [2, 0, 2]
    assert both.contour_closed.tolist() == [True, False, False]


def test_draw_replays_every_verb():
    p = parse_path('M0 0 L10 0 Q20 0 20 10 C 1 2 3 4 5 6 Z M 7 7')

    class Log:
        def __init__(self):
            self.calls = []

        def __getattr__(self, name):
            return lambda *pts: self.calls.append((name, [tuple(map(float, q)) for q in pts]))

    log = Log()
    p.draw(log)
    assert log.calls == [('moveTo', [(0, 0)]), ('lineTo', [(10, 0)]),
                         ('qCurveTo', [(20, 0), (20, 10)]),
                         ('curveTo', [(1, 2), (3, 4), (5, 6)]), ('closePath', []),
                         ('moveTo', [(7, 7)])]
    verbs = [MOVE, LINE, QUAD, CUBIC, CLOSE, MOVE]
    assert p.verbs.tolist() == verbs


@pytest.mark.parametrize('n', [1, 2, 5, 32, 33, 200])
def test_control_box_is_the_points_min_and_max(n):
    # small paths take the box with Python's min and max, larger ones with
    # numpy's: either way exactly the extreme coordinates, as floats
    rng = np.random.default_rng(n)
    pts = rng.normal(0, 50, (n, 2)) * rng.choice([1e-300, 1.0, 1e200], (n, 1))
    p = Path(np.array([MOVE] + [LINE] * (n - 1), np.uint8), pts)
    box = p.control_box()
    assert box == (pts[:, 0].min(), pts[:, 1].min(), pts[:, 0].max(), pts[:, 1].max())
    assert all(type(v) is float for v in box)
