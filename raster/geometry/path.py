"""The path model: an immutable list of verbs and points.

Coordinates are float64 user units (x right, y down, as in SVG).

Verbs and the points each one consumes:

=========  =====  =====================================================
verb       value  points
=========  =====  =====================================================
``MOVE``   0      1: the contour's first point
``LINE``   1      1: end point
``QUAD``   2      2: control point, end point
``CUBIC``  3      3: two control points, end point
``CLOSE``  4      0: closes the contour back to its first point
=========  =====  =====================================================

Guarantees of a :class:`Path` (enforced by
:class:`~raster.geometry.pens.PathBuilder` and by :meth:`Path.from_arrays`):

* every point is finite;
* every contour starts with ``MOVE``; a drawing verb after ``CLOSE`` follows a
  ``MOVE`` to the closed contour's first point (SVG's rule), inserted by the
  builder, so the point before any drawing verb is always its start point;
* ``CLOSE`` only follows a contour that was started by ``MOVE``.

A contour may consist of a lone ``MOVE`` (or ``MOVE CLOSE``): it draws no
fill, but ``MOVE CLOSE`` and zero-length segments still get stroke caps.

The pens that make and consume paths are in :mod:`raster.geometry.pens`;
:meth:`Path.draw` replays a path into any pen.

>>> p = Path.from_arrays([MOVE, LINE, CUBIC, CLOSE],
...                      [[0, 0], [10, 0], [10, 5], [5, 10], [0, 10]])
>>> p.to_svg()
'M 0 0 L 10 0 C 10 5 5 10 0 10 Z'
"""

from __future__ import annotations

from typing import Any, Iterable, NamedTuple, Optional, TYPE_CHECKING, Tuple

import numpy as np
if TYPE_CHECKING:              # numpy.typing costs 1 ms of every start-up
    from numpy.typing import ArrayLike

from ..errors import PathError
from .transform import AffineLike, as_affine

MOVE, LINE, QUAD, CUBIC, CLOSE = 0, 1, 2, 3, 4

VERB_NAMES = ('M', 'L', 'Q', 'C', 'Z')
_NPTS = np.array([1, 1, 2, 3, 0], dtype=np.int64)

# Most points whose control box is taken with Python's min and max.
_SMALL_BOX = 32


class Segments(NamedTuple):
    """All drawing segments of a path as arrays (closing lines not included).

    Attributes
    ----------
    ctrl : (S, 4, 2) float64 ndarray
        Control points, start point first.  A segment of degree ``k`` uses
        ``ctrl[:, :k+1]``; the unused slots repeat its end point.
    degree : (S,) int8 ndarray
        1 (line), 2 (quadratic) or 3 (cubic).
    contour : (S,) int64 ndarray
        Index of the contour each segment belongs to.
    contour_start : (C, 2) float64 ndarray
        First point of each contour.
    contour_end : (C, 2) float64 ndarray
        Last point of each contour before any close.
    contour_closed : (C,) bool ndarray
        Whether the contour ends with ``CLOSE``.
    contour_nseg : (C,) int64 ndarray
        Number of segments of each contour.
    """
    ctrl: np.ndarray
    degree: np.ndarray
    contour: np.ndarray
    contour_start: np.ndarray
    contour_end: np.ndarray
    contour_closed: np.ndarray
    contour_nseg: np.ndarray

    @property
    def end(self) -> np.ndarray:
        """(S, 2) end points."""
        return self.ctrl[:, 3]


class Path:
    """Immutable path of verbs and points.

    Parameters
    ----------
    verbs : (V,) uint8 ndarray
    points : (P, 2) float64 ndarray

    Use :class:`PathBuilder`, :func:`raster.parse_path` or
    :meth:`Path.from_arrays` to make one; the constructor trusts its input.
    """

    __slots__ = ('verbs', 'points', '_segments', '_cbox')

    def __init__(self, verbs: np.ndarray, points: np.ndarray, _checked: bool = False) -> None:
        if not _checked:
            verbs, points = _validate(verbs, points)
        verbs.flags.writeable = False
        points.flags.writeable = False
        object.__setattr__(self, 'verbs', verbs)
        object.__setattr__(self, 'points', points)
        object.__setattr__(self, '_segments', None)
        object.__setattr__(self, '_cbox', None)

    def __setattr__(self, name, value):
        raise AttributeError('Path is immutable')

    def __reduce__(self):
        # pickled and copied as its arrays (already checked); the caches
        # are made again on use
        return (type(self), (self.verbs, self.points, True))

    @classmethod
    def from_arrays(cls, verbs: ArrayLike, points: ArrayLike) -> 'Path':
        """Validated construction from verb and point arrays (raises
        :class:`~raster.errors.PathError`)."""
        return cls(verbs, points)

    @classmethod
    def empty(cls) -> 'Path':
        return cls(np.zeros(0, np.uint8), np.zeros((0, 2)), _checked=True)

    @classmethod
    def polygon(cls, points: ArrayLike, closed: bool = True) -> 'Path':
        """Path of one polyline contour through ``points`` ((N, 2))."""
        pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        if len(pts) == 0:
            return cls.empty()
        verbs = np.full(len(pts) + (1 if closed else 0), LINE, np.uint8)
        verbs[0] = MOVE
        if closed:
            verbs[-1] = CLOSE
        return cls(verbs, pts.copy())

    @classmethod
    def concat(cls, paths: Iterable['Path']) -> 'Path':
        paths = [p for p in paths if len(p.verbs)]
        if not paths:
            return cls.empty()
        return cls(np.concatenate([p.verbs for p in paths]),
                   np.concatenate([p.points for p in paths]), _checked=True)

    # -- queries -------------------------------------------------------------
    def __len__(self):
        return len(self.verbs)

    @property
    def is_empty(self) -> bool:
        """True when the path has no drawing segment."""
        return not np.any((self.verbs >= LINE) & (self.verbs <= CUBIC))

    def __eq__(self, other):
        return (isinstance(other, Path) and np.array_equal(self.verbs, other.verbs)
                and np.array_equal(self.points, other.points))

    __hash__ = None

    def __repr__(self):
        return 'Path(%r)' % self.to_svg(precision=6)[:200]

    def segments(self) -> Segments:
        """All drawing segments as arrays: see :class:`Segments`.  Cached."""
        if self._segments is None:
            object.__setattr__(self, '_segments', segment_arrays(self.verbs, self.points))
        return self._segments

    def control_box(self) -> Tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) of all points (a bound, not exact)."""
        if self._cbox is None:
            if len(self.points) == 0:
                raise PathError('empty path has no bounds')
            if len(self.points) <= _SMALL_BOX:
                # (a few points: Python's min and max on lists cost less
                # than numpy's reductions, which documents of many small
                # shapes pay once a shape)
                xs, ys = self.points.T.tolist()
                box = (min(xs), min(ys), max(xs), max(ys))
            else:
                # (one reduction per coordinate column: numpy reduces an
                # (N, 2) array along axis 0 two elements at a time, several
                # times slower)
                xs, ys = self.points[:, 0], self.points[:, 1]
                box = (float(xs.min()), float(ys.min()), float(xs.max()), float(ys.max()))
            object.__setattr__(self, '_cbox', box)
        return self._cbox

    # -- transformations -----------------------------------------------------
    def transform(self, t: AffineLike) -> 'Path':
        """Return the path with every point mapped by the affine ``t``
        (an :class:`~raster.geometry.transform.Affine`, 6 numbers or a 2x3 matrix)."""
        t = as_affine(t)
        if t.is_identity:
            return self
        pts = t.apply(self.points)
        if not np.all(np.isfinite(pts)):
            raise PathError('transformed path has non-finite coordinates')
        return Path(self.verbs.copy(), pts, _checked=True)

    def draw(self, pen: Any) -> None:
        """Replay the path into a pen."""
        pts = self.points
        i = 0
        for v in self.verbs.tolist():
            if v == MOVE:
                pen.moveTo(tuple(pts[i])); i += 1
            elif v == LINE:
                pen.lineTo(tuple(pts[i])); i += 1
            elif v == QUAD:
                pen.qCurveTo(tuple(pts[i]), tuple(pts[i + 1])); i += 2
            elif v == CUBIC:
                pen.curveTo(tuple(pts[i]), tuple(pts[i + 1]), tuple(pts[i + 2])); i += 3
            else:
                pen.closePath()

    def to_svg(self, precision: Optional[int] = None) -> str:
        """SVG path data with absolute commands (``M L Q C Z``).

        ``precision`` rounds to that many decimals (``None``: shortest exact
        repr)."""
        def fmt(v):
            if precision is not None:
                v = round(v, precision)
            if v == int(v) and abs(v) < 1e15:
                return str(int(v))
            return repr(v) if precision is None else ('%.*f' % (precision, v)).rstrip('0').rstrip('.')
        out = []
        pts = self.points.tolist()
        i = 0
        for v in self.verbs.tolist():
            n = int(_NPTS[v])
            coords = ' '.join('%s %s' % (fmt(x), fmt(y)) for x, y in pts[i:i + n])
            out.append(VERB_NAMES[v] + (' ' + coords if coords else ''))
            i += n
        return ' '.join(out)


def _validate(verbs, points):
    verbs = np.ascontiguousarray(verbs, dtype=np.uint8).reshape(-1)
    points = np.ascontiguousarray(points, dtype=np.float64).reshape(-1, 2)
    if np.any(verbs > CLOSE):
        raise PathError('unknown verb value')
    if int(_NPTS[verbs].sum()) != len(points):
        raise PathError('verbs need %d points, got %d' % (int(_NPTS[verbs].sum()), len(points)))
    if not np.all(np.isfinite(points)):
        raise PathError('path has non-finite coordinates (NaN or infinity)')
    if len(verbs):
        if verbs[0] != MOVE:
            raise PathError('path must start with a move')
        prev = np.concatenate([[MOVE], verbs[:-1]])
        if np.any((prev == CLOSE) & (verbs != MOVE)):
            raise PathError('a contour after a close must start with a move')
    return verbs.copy(), points.copy()


def segment_arrays(verbs: np.ndarray, points: np.ndarray) -> Segments:
    """The :class:`Segments` of verb and point arrays (see
    :meth:`Path.segments`, which caches them).

    Parameters
    ----------
    verbs : (V,) uint8 ndarray
    points : (P, 2) float64 ndarray
        A valid path (as :class:`Path` guarantees); several paths
        concatenated are valid too (every path starts with a move).

    Returns
    -------
    Segments
    """
    npts = _NPTS[verbs]
    off = np.cumsum(npts) - npts                 # index of the verb's first point
    contour = np.cumsum(verbs == MOVE) - 1
    ncont = int(contour[-1]) + 1 if len(verbs) else 0
    draw = (verbs >= LINE) & (verbs <= CUBIC)
    dv = verbs[draw].astype(np.int8)
    doff = off[draw]
    S = len(dv)
    ctrl = np.empty((S, 4, 2))
    if S:
        ctrl[:, 0] = points[doff - 1]
        last = doff + dv - 1                      # index of end point
        for k in range(1, 4):
            idx = np.minimum(doff + k - 1, last)
            ctrl[:, k] = points[idx]
    seg_contour = contour[draw].astype(np.int64)
    moves = verbs == MOVE
    cstart = points[off[moves]] if ncont else np.zeros((0, 2))
    closed = np.zeros(ncont, bool)
    closed[contour[verbs == CLOSE]] = True
    nseg = np.bincount(seg_contour, minlength=ncont).astype(np.int64)
    # contour end: the last point of the contour (start if it has no segment)
    cend = cstart.copy()
    if S:
        last_seg = np.zeros(ncont, np.int64) - 1
        np.maximum.at(last_seg, seg_contour, np.arange(S))
        has = last_seg >= 0
        cend[has] = ctrl[last_seg[has], 3]
    return Segments(ctrl, dv, seg_contour, cstart, cend, closed, nseg)
