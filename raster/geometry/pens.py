"""Pens: the one sink for everything that makes Bezier segments.

The pen protocol is fontTools': ``moveTo(pt)``, ``lineTo(pt)``,
``curveTo(*pts)``, ``qCurveTo(*pts)``, ``closePath()``, ``endPath()`` (and
``addComponent``, refused here).  :class:`BasePen` decomposes the
multi-point calls once, for every pen, with fontTools' semantics:

* ``curveTo`` with ``n`` points: ``n = 3`` one cubic; ``n = 2`` the same as
  ``qCurveTo``; ``n = 1`` a line; ``n > 3`` a *super-Bezier*: the ``n - 1``
  off-curve points are the control polygon of a chain of ``n - 2`` cubics,
  its legs cut at halves (first and last leg) and thirds (the others), the
  cubics meeting at the midpoints of consecutive cut points;
* ``qCurveTo`` with ``n`` points: ``n - 1`` off-curve points and an on-curve
  end point, with an implied on-curve point halfway between consecutive
  off-curve points (TrueType); ``n = 1`` a line.  A last point ``None``
  closes a contour of off-curve points only: the implied point between the
  last and the first off-curve point starts the contour (a ``moveTo``) and
  ends it.

Subclasses implement ``_moveTo(pt)``, ``_lineTo(pt)``,
``_curveToOne(pt1, pt2, pt3)``, and optionally ``_qCurveToOne(pt1, pt2)``
(default: the exact cubic), ``_closePath()`` and ``_endPath()``.  Points
reach them as tuples of two finite floats; :attr:`BasePen.current_point`
is the current point.

After ``closePath`` the current point is the contour's first point (SVG's
rule: :class:`PathBuilder` starts a new contour there when drawing goes on);
after ``endPath`` there is none, and drawing needs a ``moveTo``.

>>> rec = RecordingPen()
>>> rec.moveTo((0, 0)); rec.qCurveTo((0, 10), (10, 10), (10, 0)); rec.closePath()
>>> rec.value
[('moveTo', ((0.0, 0.0),)), ('qCurveTo', ((0.0, 10.0), (5.0, 10.0))), ('qCurveTo', ((10.0, 10.0), (10.0, 0.0))), ('closePath', ())]
"""

from typing import Any, List, Optional, Sequence, Tuple

import numpy as np

from ..errors import PathError
from .bezier import bounds
from .path import CLOSE, CUBIC, LINE, MOVE, QUAD, Path
from .transform import AffineLike, as_affine

__all__ = ['BasePen', 'PathBuilder', 'TransformPen', 'RecordingPen', 'BoundsPen']

Point = Tuple[float, float]


def _point(p) -> Point:
    try:
        x, y = float(p[0]), float(p[1])
    except (TypeError, ValueError, IndexError):
        raise PathError('point must be two numbers, got %r' % (p,)) from None
    if not (np.isfinite(x) and np.isfinite(y)):
        raise PathError('non-finite coordinate (%r, %r)' % (x, y))
    return (x, y)


def _mid(p: Point, q: Point) -> Point:
    return ((p[0] + q[0]) * 0.5, (p[1] + q[1]) * 0.5)


def _implied_quadratics(pts: Sequence[Point]) -> List[Tuple[Point, Point]]:
    """(control, end) of each quadratic of a TrueType run: off-curve
    points ``pts[:-1]``, on-curve end ``pts[-1]``, on-curve points implied
    halfway between consecutive off-curve points."""
    offs = pts[:-1]
    ends = [_mid(offs[i], offs[i + 1]) for i in range(len(offs) - 1)] + [pts[-1]]
    return list(zip(offs, ends))


def _super_bezier(pts: Sequence[Point]) -> List[Tuple[Point, Point, Point]]:
    """The cubics of a super-Bezier run: off-curve points ``pts[:-1]``
    (three or more), on-curve end ``pts[-1]``.

    Leg ``k`` of the off-curve polygon (``pts[k]`` to ``pts[k + 1]``) is
    cut at its half when it is the first or the last leg and at its thirds
    otherwise, giving an even number of cut points ``C``.  Cubic ``j`` has
    the inner controls ``C[2j - 1], C[2j]`` (``pts[0]`` instead of
    ``C[-1]`` for the first) and ends halfway between ``C[2j]`` and
    ``C[2j + 1]``; the last cubic has the controls ``C[-1], pts[-2]`` and
    ends at ``pts[-1]``.
    """
    offs = pts[:-1]
    legs = len(offs) - 1
    cuts = []
    for k in range(legs):
        (x0, y0), (x1, y1) = offs[k], offs[k + 1]
        parts = 2 if k in (0, legs - 1) else 3
        for j in range(1, parts):
            f = j / parts
            cuts.append((x0 + f * (x1 - x0), y0 + f * (y1 - y0)))
    out = []
    c1 = offs[0]
    for j in range(0, len(cuts), 2):
        c2, nxt = cuts[j], cuts[j + 1]
        joint = _mid(c2, nxt)
        out.append((c1, c2, joint))
        c1 = nxt
    out.append((c1, offs[-1], pts[-1]))
    return out


class BasePen:
    """A pen that decomposes the pen protocol into single segments.

    Subclasses implement the ``_``-prefixed hooks (see the module
    docstring).  Every public call validates its points
    (:class:`~raster.errors.PathError` for points that are not two finite
    numbers) and refuses drawing with no current point.
    """

    def __init__(self) -> None:
        self._current: Optional[Point] = None
        self._start: Optional[Point] = None

    @property
    def current_point(self) -> Optional[Point]:
        """The current point (the contour's start after ``closePath``), or
        None before any ``moveTo`` and after ``endPath``."""
        return self._current

    # -- hooks ------------------------------------------------------------------
    def _moveTo(self, pt: Point) -> None:
        raise NotImplementedError('%s does not implement _moveTo' % type(self).__name__)

    def _lineTo(self, pt: Point) -> None:
        raise NotImplementedError('%s does not implement _lineTo' % type(self).__name__)

    def _curveToOne(self, pt1: Point, pt2: Point, pt3: Point) -> None:
        raise NotImplementedError('%s does not implement _curveToOne' % type(self).__name__)

    def _qCurveToOne(self, pt1: Point, pt2: Point) -> None:
        """Default: the cubic with the same curve (degree elevation)."""
        (x0, y0), (x1, y1), (x2, y2) = self._current, pt1, pt2
        self._curveToOne((x0 + 2.0 / 3.0 * (x1 - x0), y0 + 2.0 / 3.0 * (y1 - y0)),
                         (x2 + 2.0 / 3.0 * (x1 - x2), y2 + 2.0 / 3.0 * (y1 - y2)), pt2)

    def _closePath(self) -> None:
        pass

    def _endPath(self) -> None:
        pass

    # -- protocol ---------------------------------------------------------------
    def _need_current(self) -> None:
        if self._current is None:
            raise PathError('drawing command with no current point (missing move)')

    def moveTo(self, pt: Sequence[float]) -> None:
        p = _point(pt)
        self._moveTo(p)
        self._start = self._current = p

    def lineTo(self, pt: Sequence[float]) -> None:
        p = _point(pt)
        self._need_current()
        self._lineTo(p)
        self._current = p

    def curveTo(self, *pts: Sequence[float]) -> None:
        """One cubic (3 points), or a super-Bezier (more), a quadratic (2)
        or a line (1): see the module docstring."""
        n = len(pts)
        if n == 0:
            raise PathError('curveTo needs at least one point')
        if n == 1:
            self.lineTo(pts[0])
            return
        if n == 2:
            self.qCurveTo(*pts)
            return
        P = [_point(p) for p in pts]
        self._need_current()
        for c1, c2, end in ([P] if n == 3 else _super_bezier(P)):
            self._curveToOne(c1, c2, end)
            self._current = end

    def qCurveTo(self, *pts: Optional[Sequence[float]]) -> None:
        """Quadratic(s) with implied on-curve points (TrueType), a line for
        one point; a last point ``None`` closes an all-off-curve contour."""
        if len(pts) == 0:
            raise PathError('qCurveTo needs at least one point')
        if pts[-1] is None:
            if len(pts) < 2:
                raise PathError('qCurveTo with a None end point needs off-curve points')
            P = [_point(p) for p in pts[:-1]]
            implied = _mid(P[-1], P[0])
            self._moveTo(implied)
            self._start = self._current = implied
            P.append(implied)
        else:
            P = [_point(p) for p in pts]
            self._need_current()
            if len(P) == 1:
                self._lineTo(P[0])
                self._current = P[0]
                return
        for c, on in _implied_quadratics(P):
            self._qCurveToOne(c, on)
            self._current = on

    def closePath(self) -> None:
        self._closePath()
        self._current = self._start

    def endPath(self) -> None:
        self._endPath()
        self._current = self._start = None

    def addComponent(self, glyphName: str, transformation: Any) -> None:  # fontTools pen API
        raise PathError('components are not supported by %s' % type(self).__name__)


class PathBuilder(BasePen):
    """A pen that builds an immutable :class:`~raster.geometry.path.Path`.

    Raises :class:`~raster.errors.PathError` for non-finite coordinates and
    for drawing with no current point.  After ``closePath`` a drawing call
    starts a new contour at the closed contour's first point (SVG rule).

    >>> b = PathBuilder()
    >>> b.moveTo((0, 0)); b.lineTo((10, 0)); b.curveTo((10, 5), (5, 10), (0, 10)); b.closePath()
    >>> p = b.path()
    >>> p.verbs.tolist(), p.points.shape
    ([0, 1, 3, 4], (5, 2))
    """

    def __init__(self) -> None:
        super().__init__()
        self._verbs: List[int] = []
        self._pts: List[Point] = []
        self._open = False      # a contour is in progress (not closed)

    def _moveTo(self, pt):
        self._verbs.append(MOVE)
        self._pts.append(pt)
        self._open = True

    def _begin(self):
        if not self._open:
            # drawing after closePath: implicit move to the contour start
            self._moveTo(self._start)

    def _lineTo(self, pt):
        self._begin()
        self._verbs.append(LINE)
        self._pts.append(pt)

    def _qCurveToOne(self, pt1, pt2):
        self._begin()
        self._verbs.append(QUAD)
        self._pts.extend((pt1, pt2))

    def _curveToOne(self, pt1, pt2, pt3):
        self._begin()
        self._verbs.append(CUBIC)
        self._pts.extend((pt1, pt2, pt3))

    def _closePath(self):
        if self._start is None:
            raise PathError('closePath with no current contour')
        if self._open:
            self._verbs.append(CLOSE)
            self._open = False

    def _endPath(self):
        self._open = False

    def path(self) -> Path:
        """The :class:`~raster.geometry.path.Path` built so far."""
        verbs = np.array(self._verbs, dtype=np.uint8)
        pts = np.array(self._pts, dtype=np.float64).reshape(-1, 2)
        return Path(verbs, pts, _checked=True)


class TransformPen(BasePen):
    """Pen that maps every point through an affine transform and forwards
    the single segments to another pen.

    Parameters
    ----------
    out : pen
    transform : Affine, 6 numbers or a 2x3 matrix
    """

    def __init__(self, out: Any, transform: AffineLike) -> None:
        super().__init__()
        self.out = out
        self.t = as_affine(transform)

    def _m(self, *pts):
        return [tuple(q) for q in self.t.apply(np.asarray(pts, dtype=np.float64)).tolist()]

    def _moveTo(self, pt):
        self.out.moveTo(self._m(pt)[0])

    def _lineTo(self, pt):
        self.out.lineTo(self._m(pt)[0])

    def _qCurveToOne(self, pt1, pt2):
        self.out.qCurveTo(*self._m(pt1, pt2))

    def _curveToOne(self, pt1, pt2, pt3):
        self.out.curveTo(*self._m(pt1, pt2, pt3))

    def _closePath(self):
        self.out.closePath()

    def _endPath(self):
        self.out.endPath()


class RecordingPen(BasePen):
    """Pen that records the single segments as ``(name, args)`` tuples in
    ``self.value`` (``curveTo`` with 3 points, ``qCurveTo`` with 2);
    :meth:`replay` sends them to another pen."""

    def __init__(self) -> None:
        super().__init__()
        self.value: List[Tuple[str, tuple]] = []

    def _moveTo(self, pt):
        self.value.append(('moveTo', (pt,)))

    def _lineTo(self, pt):
        self.value.append(('lineTo', (pt,)))

    def _qCurveToOne(self, pt1, pt2):
        self.value.append(('qCurveTo', (pt1, pt2)))

    def _curveToOne(self, pt1, pt2, pt3):
        self.value.append(('curveTo', (pt1, pt2, pt3)))

    def _closePath(self):
        self.value.append(('closePath', ()))

    def _endPath(self):
        self.value.append(('endPath', ()))

    def replay(self, pen: Any) -> None:
        for name, args in self.value:
            getattr(pen, name)(*args)


class BoundsPen(BasePen):
    """A pen that accumulates the exact bounds of what is drawn into it.

    Parameters
    ----------
    out : pen or None, optional
        Every single segment is forwarded to this pen as well.

    Attributes
    ----------
    bounds : (xmin, ymin, xmax, ymax) tuple of float, or None
        None until something is drawn.  A ``moveTo`` point counts once a
        segment or a ``closePath`` follows it (as in :func:`raster.bbox`).

    Examples
    --------
    >>> pen = BoundsPen()
    >>> pen.moveTo((0, 0)); pen.qCurveTo((1, 2), (2, 0)); pen.closePath()
    >>> pen.bounds
    (0.0, 0.0, 2.0, 1.0)
    """

    def __init__(self, out: Any = None) -> None:
        super().__init__()
        self.out = out
        self.bounds: Optional[Tuple[float, float, float, float]] = None
        self._pending = False      # the move point is not counted yet

    def _add(self, lo, hi):
        if self.bounds is None:
            self.bounds = (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))
        else:
            b = self.bounds
            self.bounds = (min(b[0], float(lo[0])), min(b[1], float(lo[1])),
                           max(b[2], float(hi[0])), max(b[3], float(hi[1])))

    def _count_move(self):
        if self._pending:
            self._add(self._current, self._current)
            self._pending = False

    def _segment(self, *pts):
        self._count_move()
        lo, hi = bounds(np.array((self._current,) + pts))
        self._add(lo, hi)

    def _moveTo(self, pt):
        self._pending = True
        if self.out is not None:
            self.out.moveTo(pt)

    def _lineTo(self, pt):
        self._segment(pt)
        if self.out is not None:
            self.out.lineTo(pt)

    def _qCurveToOne(self, pt1, pt2):
        self._segment(pt1, pt2)
        if self.out is not None:
            self.out.qCurveTo(pt1, pt2)

    def _curveToOne(self, pt1, pt2, pt3):
        self._segment(pt1, pt2, pt3)
        if self.out is not None:
            self.out.curveTo(pt1, pt2, pt3)

    def _closePath(self):
        if self._current is not None:
            self._count_move()
        if self.out is not None:
            self.out.closePath()

    def _endPath(self):
        self._pending = False
        if self.out is not None:
            self.out.endPath()
