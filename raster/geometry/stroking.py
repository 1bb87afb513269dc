"""Stroke outlines: offsets, joins, caps and dashes.

:func:`stroke` turns a :class:`~raster.geometry.path.Path` and a :class:`StrokeStyle`
into a new path of closed polygons (``MOVE``/``LINE``/``CLOSE`` only) whose
**nonzero** fill is the stroked region.

How the outline is built
------------------------
The geometry is computed in the path's *user space*, so that a non-uniform
scale or a skew in ``transform`` turns round caps into ellipses and widens a
stroke along the stretched axis, as SVG requires; the finished outline is then
mapped by ``transform``.  Curves are flattened and arcs are polygonized with
``tolerance / transform.max_scale()`` user units, so the error measured in
device pixels stays within ``tolerance``.

The outline is the boundary of a *union of convex pieces*:

* one rectangle per segment (the segment swept by the pen's width);
* one wedge per join, on the outer side of the turn: a triangle (bevel), a
  quadrilateral (miter), a pentagon (clipped miter) or a fan (round);
* one piece per cap (a rectangle for ``square``, a half-disc for
  ``round``), and a disc or a square for a subpath of zero length.

All pieces have the same orientation, so the winding number of a point is
the number of pieces covering it and the nonzero rule fills exactly their
union: overlapping joins, inner corners, cusps and self-overlapping strokes
need no special case.  The pieces are not emitted one by one: adding their
boundaries as cycles, the edges shared by neighbours cancel, and what is left
is traced directly (all subpaths at once, as numpy arrays) as one polygon
per open subpath -- left offsets forward with the outer join points, end
cap, right offsets backward, start cap -- and two loops per closed subpath.
At an inner join the cycle sum passes through the vertex (the "pivot").
Where the neighbouring rectangles both cover the triangle the pivot spans,
it is left out, which changes the winding only where it is at least two;
for turns up to 90 degrees the two inner offset lines then end where they
cross (same argument).  Only at sharp inner corners of short segments does
the outline keep a pivot or a small crossed loop, which the nonzero rule
fills correctly.  The winding is positive (positive shoelace area in user
space, negative after a mirroring transform).

Joins *inside* a flattened curve (between the chords of one Bezier segment)
are always round, whatever the join style, so curves stay smooth; a round
join whose miter stays within the tolerance of it is drawn as that miter
(one outline point instead of an arc).  Round joins,
caps and dots are polygonized with their vertices at the area-preserving
radius ``r * sqrt(a / sin a)`` (``a`` the angle step), so round caps are not
systematically too small.  Where two segments meet with one tangent (the
cubics of a circle, the arcs and sides of a rounded rectangle) the meeting
point is such a smooth vertex too: the exact stroke has no corner there.
For butt and square caps and sharp joins on fat strokes, the flattening is
refined near the other curve ends so that the end chords leave the curve
along its tangent (see :func:`_refine_ends`).  An undashed open contour of
curves that ends exactly at its start with the same tangent (a circle
written without ``Z``, as vega writes its symbols) is stroked as the closed
ring when the caps are butt: the two caps coincide, and the ring's
outline (two loops, a smooth join at the seam) does not cross itself there.

Batches
-------
All of the above works on arrays of contours, so :func:`stroke_many` strokes
many paths with one style in one pass: their contours are concatenated and
numbered by path, the tolerance (user units) and the merge distance are
kept per contour, each point of the outline is mapped by the transform of
its path and the outline is split back per path.  A call of :func:`stroke`
costs a fixed ~0.2 ms of numpy overhead (more with curves); in a batch this
is paid once.  The user-space outline depends only on the path and the
tolerance in user units, ``tolerance / max_scale``, so a path repeated in a
batch (the same object, or equal verbs and points) under transforms of the
same largest scale -- the markers of a scatter plot, translated copies of
one circle -- is outlined once and that outline is mapped by each copy's
transform: the same arithmetic as for separate copies, so the result
differs at most by the rounding of the flattening in another batch (none on
the corpus' scatter plots, see ``tests/test_stroke_many.py``).

Dashes
------
:func:`dash_polylines` cuts the flattened polylines (user space) at the dash
boundaries, with cumulative arc length and :func:`numpy.searchsorted`, for
all subpaths at once.  The pattern restarts at the start of every subpath.  A
closed subpath is dashed as one line from its start point around to the same
point (closing segment included); when a dash reaches that point and another
dash leaves it, the two are one dash, joined there (as resvg does).  A closed
subpath covered by a single dash stays closed (no caps).  Zero-length dashes
are kept: they draw a dot (round cap) or a square oriented along the path
(square cap).  Dash positions follow the arc length of the flattened curve,
which is shorter than the curve's by up to about ``e / 3`` per radian of
turning for a flattening within ``e`` (chords of sagitta ``e`` on a circle of
radius ``R`` lose ``e / (3 R)`` of its length); dashed paths are therefore
flattened within ``tolerance / 4``.

Coordinates are float64, x right and y down, as everywhere in raster.

>>> from raster.geometry.path import Path
>>> out = stroke(Path.polygon([(0, 0), (10, 0)], closed=False), width=2)
>>> out.verbs.tolist()                       # one rectangle: M L L L Z
[0, 1, 1, 1, 4]
>>> out.control_box()
(0.0, -1.0, 10.0, 1.0)
"""

import dataclasses
import math
from typing import Any, List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from ..errors import LimitError, RasterError
from .. import limits
from .bezier import evaluate
from .flattening import REPEAT_GRID, flatten_beziers
from .path import CLOSE, CUBIC, LINE, MOVE, QUAD, Path
from .rules import StrChoice
from .transform import Affine, AffineLike, apply_each, as_affine

__all__ = ['StrokeStyle', 'Stroke', 'StrokeError', 'LineJoin', 'LineCap', 'stroke', 'stroke_many',
           'dash_polylines', 'dash_pattern', 'hairline_scale', 'stroke_reach', 'DashedLines']


class LineJoin(StrChoice):
    """SVG ``stroke-linejoin``.  ``ARCS`` (SVG 2) is drawn as ``MITER``, as
    in browsers; ``MITER_CLIP`` clips an over-long miter at
    ``miterlimit * width / 2`` from the vertex instead of bevelling it."""

    MITER = 'miter'
    MITER_CLIP = 'miter-clip'
    ROUND = 'round'
    BEVEL = 'bevel'
    ARCS = 'arcs'


class LineCap(StrChoice):
    """SVG ``stroke-linecap``."""

    BUTT = 'butt'
    ROUND = 'round'
    SQUARE = 'square'


#: Relative size (of the largest coordinate) below which two consecutive
#: points are treated as one and a segment has no direction.
_EPS_REL = 1e-12


class StrokeError(RasterError, ValueError):
    """Invalid stroke parameters: negative or non-finite width, unknown join
    or cap, miter limit below 1, non-finite dash values or tolerance, a path
    argument that is not a :class:`~raster.geometry.path.Path`."""


# ---------------------------------------------------------------------------
# style
# ---------------------------------------------------------------------------

def _finite(name, v):
    try:
        f = float(v)
    except (TypeError, ValueError):
        raise StrokeError('%s must be a number, got %r' % (name, v)) from None
    if not math.isfinite(f):
        raise StrokeError('%s must be finite, got %r' % (name, v))
    return f


@dataclasses.dataclass(frozen=True)
class StrokeStyle:
    """How to stroke a path (SVG ``stroke-*`` properties).

    Parameters
    ----------
    width : float
        Stroke width in user units, >= 0 (0 draws nothing).
    join : LineJoin or {'miter', 'miter-clip', 'round', 'bevel', 'arcs'}
        Line join, stored as a :class:`LineJoin` (equal to its keyword).
        ``'arcs'`` (SVG 2) falls back to ``'miter'``, as in browsers.
        ``'miter-clip'`` clips an over-long miter at
        ``miterlimit * width / 2`` from the vertex instead of bevelling it.
    cap : LineCap or {'butt', 'round', 'square'}
        Line cap at the ends of open subpaths and of dashes, stored as a
        :class:`LineCap`.
    miterlimit : float
        Limit of the ratio miter length / width, >= 1.
    dash : sequence of float or None
        Dash array in user units (see :func:`dash_pattern` for how invalid
        arrays fall back to a solid stroke).  Stored as a tuple.
    dash_offset : float
        Distance into the dash pattern at which each subpath starts; any
        finite value (it wraps around the pattern length).

    Raises
    ------
    StrokeError
        For a negative or non-finite width, an unknown join or cap, a miter
        limit below 1 or non-finite, non-finite dash values or offset.

    A style is immutable and hashable (a key for batching strokes):

    >>> s = StrokeStyle(width=2, join='round', dash=[1, 2, 3])
    >>> s.dash, s.join is LineJoin.ROUND, s == StrokeStyle(2, LineJoin.ROUND, dash=(1, 2, 3))
    ((1.0, 2.0, 3.0), True, True)
    >>> hash(s) == hash(StrokeStyle(2, 'round', dash=[1.0, 2.0, 3.0]))
    True
    >>> StrokeStyle(miterlimit=0.5)
    Traceback (most recent call last):
    ...
    raster.geometry.stroking.StrokeError: miterlimit must be >= 1, got 0.5
    """

    width: float = 1.0
    join: LineJoin = LineJoin.MITER
    cap: LineCap = LineCap.BUTT
    miterlimit: float = 4.0
    dash: Optional[Tuple[float, ...]] = None
    dash_offset: float = 0.0

    def __post_init__(self):
        w = _finite('stroke width', self.width)
        if w < 0:
            raise StrokeError('stroke width must be >= 0, got %r' % (self.width,))
        join = LineJoin.lookup(self.join)
        if join is None:
            raise StrokeError('unknown line join %r (expected one of %s)'
                              % (self.join, ', '.join(LineJoin.values())))
        cap = LineCap.lookup(self.cap)
        if cap is None:
            raise StrokeError('unknown line cap %r (expected one of %s)'
                              % (self.cap, ', '.join(LineCap.values())))
        ml = _finite('miterlimit', self.miterlimit)
        if ml < 1:
            raise StrokeError('miterlimit must be >= 1, got %r' % (self.miterlimit,))
        dash = self.dash
        if dash is not None:
            if isinstance(dash, (str, bytes)):
                raise StrokeError('dash must be a sequence of numbers, got %r' % (dash,))
            try:
                dash = tuple(_finite('dash value', v) for v in dash)
            except TypeError:
                raise StrokeError('dash must be a sequence of numbers, got %r'
                                  % (dash,)) from None
        object.__setattr__(self, 'width', w)
        object.__setattr__(self, 'join', join)
        object.__setattr__(self, 'cap', cap)
        object.__setattr__(self, 'miterlimit', ml)
        object.__setattr__(self, 'dash', dash)
        object.__setattr__(self, 'dash_offset', _finite('dash offset', self.dash_offset))


_STYLE_FIELDS = frozenset(f.name for f in dataclasses.fields(StrokeStyle))

#: Short alias of :class:`StrokeStyle`.
Stroke = StrokeStyle


def dash_pattern(dash: Optional[Sequence[float]]) -> Optional[np.ndarray]:
    """The effective dash pattern of an SVG dash array, or None for solid.

    Follows SVG: an odd-length array is repeated to even length; an empty
    array, any negative value or an all-zero sum means a solid stroke.

    Parameters
    ----------
    dash : sequence of float or None

    Returns
    -------
    (2k,) float64 ndarray or None
        Alternating dash and gap lengths.

    Raises
    ------
    StrokeError
        For non-finite values.

    >>> dash_pattern([5, 2, 1]).tolist()
    [5.0, 2.0, 1.0, 5.0, 2.0, 1.0]
    >>> dash_pattern([4, -1]) is None, dash_pattern([0, 0]) is None
    (True, True)
    """
    if dash is None:
        return None
    try:
        d = np.asarray(dash, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        raise StrokeError('dash must be a sequence of numbers, got %r' % (dash,)) from None
    if not np.all(np.isfinite(d)):
        raise StrokeError('dash values must be finite')
    if len(d) == 0 or np.any(d < 0) or not d.sum() > 0:
        return None
    if len(d) % 2:
        d = np.concatenate([d, d])
    return d


def hairline_scale(style: 'StrokeStyle', transform: AffineLike = None) -> Optional[float]:
    """Coverage factor for a stroke thinner than one device pixel.

    A stroke whose device width ``style.width * transform.mean_scale()`` is
    below 1 px is drawn as a 1 px wide stroke (user width
    ``1 / transform.mean_scale()``) whose coverage is multiplied by the
    returned factor, the device width.  This keeps very thin lines visible
    and of the right average darkness instead of letting them break up into
    sub-pixel slivers.

    Parameters
    ----------
    style : StrokeStyle
    transform : Affine or None
        User space to device space.

    Returns
    -------
    float or None
        The factor in (0, 1), or None when no hairline treatment applies
        (device width >= 1 px, or zero: a zero width or a singular transform
        draws nothing).

    >>> from raster.geometry.transform import Affine
    >>> hairline_scale(StrokeStyle(width=0.5), Affine.scale(1.5))
    0.75
    >>> hairline_scale(StrokeStyle(width=2.0)) is None
    True
    """
    w = style.width * as_affine(transform).mean_scale()
    if 0.0 < w < 1.0:
        return float(w)
    return None


# ---------------------------------------------------------------------------
# polylines
# ---------------------------------------------------------------------------

class DashedLines(NamedTuple):
    """Polylines produced by :func:`dash_polylines`, one per dash.

    Attributes
    ----------
    points : (N, 2) float64 ndarray
        All vertices, polyline after polyline.
    starts : (K,) int64 ndarray
        Index of each polyline's first vertex in ``points``.
    closed : (K,) bool ndarray
        False for dashes (open); True only for a closed polyline covered
        entirely by one dash.
    tangent : (K, 2) float64 ndarray
        Unit direction of the path where each dash starts (orients the
        square cap of a zero-length dash).
    """
    points: np.ndarray
    starts: np.ndarray
    closed: np.ndarray
    tangent: np.ndarray

    def __iter__(self):
        bounds = np.append(self.starts, len(self.points))
        for k in range(len(self.starts)):
            yield self.points[bounds[k]:bounds[k + 1]], bool(self.closed[k])


class _Lines(NamedTuple):
    """Internal polyline set (user space)."""
    points: np.ndarray    # (N, 2)
    starts: np.ndarray    # (C,) int64
    counts: np.ndarray    # (C,) int64, >= 1
    closed: np.ndarray    # (C,) bool
    smooth: np.ndarray    # (N,) bool: vertex inside a flattened curve
    tangent: np.ndarray   # (C, 2) direction used for a zero-length square cap


def _starts(counts):
    """Exclusive prefix sums of ``counts``: (K,) int64."""
    out = np.zeros(len(counts), np.int64)
    if len(counts) > 1:
        np.cumsum(counts[:-1], out=out[1:])
    return out


def _ranges(counts):
    """(owner, local) index arrays for consecutive blocks of ``counts``."""
    counts = np.asarray(counts, dtype=np.int64)
    owner = np.repeat(np.arange(len(counts)), counts)
    local = np.arange(len(owner)) - np.repeat(_starts(counts), counts)
    return owner, local


def _check_size(n, what):
    """The budget of :mod:`raster.limits` for ``n`` points (or dashes)
    of a stroke, before they are made."""
    lim = limits.current().max_flatten_points
    if n > lim:
        raise LimitError('stroke needs %.3g %s, more than max_flatten_points %d'
                         % (n, what, lim))


def _refine_ends(ctrl, points, counts, r, tol, ends=None):
    """Refine the flattening of curves near their ends for a pen of
    half-width ``r``, so that butt and square caps and miter or bevel joins
    built on the end chords stay within ``tol`` of the exact stroke.

    A chord turned by ``a`` from the curve's normal at its end pokes its
    rectangle out past the cap (or join) line by about ``r * a`` minus its
    distance from the end along the curve.  Where the first chord turns
    too much (``r * a > tol``), curve points are added at parameters in
    geometric progression towards the end, ``t_a / rho**j``, so that every
    chord near the end satisfies ``r * a <= tol + distance``; ``t_a`` is
    found by halving (a loop over halvings, vectorized over the curves).
    Round caps and joins need none of this: the stroke of the polyline with
    round joins is within ``tol`` of the exact one anyway.

    Parameters
    ----------
    ctrl : (M, k+1, 2) float64 ndarray
    points, counts : as returned by :func:`raster.geometry.flattening.flatten_beziers`.
    r : float
    tol : float or (M,) float64 ndarray
    ends : (M, 2) bool ndarray or None
        Which ends (start, end) may need refining; None: all.  Ends where
        the path continues with the same tangent (see :func:`_g1_ends`) need
        none: the join there is drawn as a smooth vertex.

    Returns
    -------
    points, counts
        Each curve gains at most 64 points at each end.
    """
    M = len(ctrl)
    first = _starts(counts)
    last = first + counts - 1
    scale = np.abs(ctrl).reshape(M, -1).max(axis=1)
    tiny = (_EPS_REL * np.maximum(scale, 1e-300))[:, None]
    ar = np.arange(M)
    ds = ctrl[:, 1:] - ctrl[:, :1]                   # start tangent candidates
    de = ctrl[:, -2::-1] - ctrl[:, -1:]              # end (reversed) candidates
    sides = []
    for side, (q0i, q1i, cand) in enumerate(((first, first + 1, ds), (last, last - 1, de))):
        tan = _unit(cand[ar, np.argmax(np.hypot(cand[..., 0], cand[..., 1]) > tiny, axis=1)])
        q0, ch = points[q0i], points[q1i] - points[q0i]
        c1 = np.hypot(ch[:, 0], ch[:, 1])
        ang = np.arctan2(np.abs(ch[:, 0] * tan[:, 1] - ch[:, 1] * tan[:, 0]),
                         np.einsum('ij,ij->i', ch, tan))
        big = r * ang > tol
        if ends is not None:
            big &= ends[:, side]
        todo = np.flatnonzero(big)
        if side == 0 and len(todo) == 0 and ends is not None and \
                not np.any(ends[:, 1]):
            return points, counts
        ta = np.zeros(M)
        t = np.full(len(todo), 0.5) / np.maximum(counts[todo] - 1, 1)
        for _ in range(60):                          # a parameter short of q1
            if len(todo) == 0:
                break
            v = evaluate(ctrl[todo], t if side == 0 else 1.0 - t) - q0[todo]
            ok = np.hypot(v[:, 0], v[:, 1]) < c1[todo]
            ta[todo[ok]] = t[ok]
            todo, t = todo[~ok], 0.5 * t[~ok]
        need = ta > 0
        with np.errstate(over='ignore'):             # a huge ratio is clamped to 1
            rho = 1.0 + np.minimum(1.0, c1 / np.maximum(r * ang, 1e-300))
        need &= rho > 1.0
        lr = np.log(np.where(need, rho, 2.0))
        J = np.where(need, np.minimum(64, np.ceil(np.log(np.maximum(r * ang / tol, 1.0)) / lr) + 1),
                     0).astype(np.int64)
        cid, j = _ranges(J)
        if side == 0:
            j = J[cid] - 1 - j                        # increasing parameter
        tt = ta[cid] * rho[cid] ** (-j.astype(np.float64))
        pts = evaluate(ctrl[cid], tt if side == 0 else 1.0 - tt)
        sides.append((J, pts))
    (J0, p0), (J1, p1) = sides
    new_counts = counts + J0 + J1
    ns = _starts(new_counts)
    cid, j = _ranges(counts)
    pos = ns[cid] + j + np.where(j >= 1, J0[cid], 0) + np.where(j == counts[cid] - 1, J1[cid], 0)
    out = np.empty((int(new_counts.sum()), 2))
    out[pos] = points
    c0, k0 = _ranges(J0)
    out[ns[c0] + 1 + k0] = p0
    c1_, k1 = _ranges(J1)
    out[(ns + new_counts - 1 - J1)[c1_] + k1] = p1
    return out, new_counts


def _path_lines(path, tol, r=0.0, straddle=False, seal=False):
    """Flatten every segment of ``path`` within ``tol`` (user units) with
    :func:`raster.geometry.flattening.flatten_beziers` (``straddle`` passed
    on), keeping track of which vertices
    lie inside a curve (smooth joins).  ``tol`` is a float or a (C,) array,
    one tolerance per contour (``MOVE``) of ``path``.

    With ``seal`` (undashed strokes with butt caps) an open contour of
    curves that ends exactly at its start point with the tangent it started
    with is returned closed, its start a smooth vertex: the butt caps there
    coincide (with opposite directions) and the stroke of the curve has no
    corner, so the closed ring is the same stroke without the two caps
    crossing the outline (no cells where the outline meets itself).  The
    only difference is at the seam, where the two end chords of the
    flattening may meet at a small angle: the ring's round join fills the
    sliver of outer wedge (at most the tolerance wide) that the open
    contour leaves out.

    Returns ``(lines, keep)``: the polylines of the contours where the (C,)
    bool ``keep`` is True; lone ``MOVE`` contours are dropped (SVG does not
    stroke them)."""
    verbs = path.verbs
    if not len(verbs):
        return _Lines(np.zeros((0, 2)), *(np.zeros(0, np.int64),) * 2, np.zeros(0, bool),
                      np.zeros(0, bool), np.zeros((0, 2))), np.zeros(0, bool)
    if not np.any((verbs == QUAD) | (verbs == CUBIC)):
        return _polygon_lines(verbs, path.points)

    seg = path.segments()
    C = len(seg.contour_start)
    S = len(seg.degree)
    deg = seg.degree
    g1 = None
    if seal:
        cand = (~seg.contour_closed & (seg.contour_nseg > 0)
                & np.all(seg.contour_start == seg.contour_end, axis=1))
        if cand.any():
            g1 = _g1_ends(seg._replace(contour_closed=seg.contour_closed | cand))
            ci = np.flatnonzero(cand)
            sealed = np.zeros(C, bool)
            sealed[ci] = g1[0][_starts(seg.contour_nseg)[ci]]
            if sealed.any():
                seg = seg._replace(contour_closed=seg.contour_closed | sealed)
            g1 = None
    n = np.ones(S, np.int64)                          # pieces per segment
    seg_pts = [None, None, None, None]                # flattened points per degree
    for k in (2, 3):
        sel = deg == k
        if np.any(sel):
            ctrl = seg.ctrl[sel, :k + 1]
            if np.ndim(tol):
                # one tolerance per curve: flatten copies scaled to a common
                # tolerance (exact when all tolerances are equal)
                tc = tol[seg.contour[sel]]
                tmin = float(tc.min())
                if np.all(tc == tmin):
                    p, cnt = flatten_beziers(ctrl, tmin, straddle)
                else:
                    f = tmin / tc
                    p, cnt = flatten_beziers(ctrl * f[:, None, None], tmin, straddle)
                    p = p / np.repeat(f, cnt)[:, None]
                    last = np.cumsum(cnt) - 1     # end points exactly
                    p[last] = ctrl[:, -1]
                    p[last - cnt + 1] = ctrl[:, 0]
            else:
                tc = tol
                p, cnt = flatten_beziers(ctrl, tol, straddle)
            if r > 0:
                if g1 is None:
                    g1 = _g1_ends(seg)
                need = ~np.stack([g1[0][sel], g1[1][sel]], axis=1)
                if need.any():
                    p, cnt = _refine_ends(ctrl, p, cnt, r, tc, need)
            n[sel] = cnt - 1
            first = _starts(cnt)
            keep = np.ones(len(p), bool)
            keep[first] = False                       # start = previous end point
            seg_pts[k] = p[keep]
    _check_size(float(n.sum()) + C, 'flattened points')

    counts = np.bincount(seg.contour, weights=n, minlength=C).astype(np.int64) + 1
    starts = _starts(counts)
    N = int(counts.sum())
    pts = np.empty((N, 2))
    smooth = np.zeros(N, bool)
    pts[starts] = seg.contour_start
    if S:
        sid, j = _ranges(n)
        excl = _starts(n)
        pos = excl[sid] + seg.contour[sid] + j + 1    # one start point per contour before
        smooth[pos] = j < n[sid] - 1
        if g1 is not None:
            # vertices where segments meet with one tangent are smooth
            ends = _starts(n) + n - 1
            smooth[pos[ends[g1[1]]]] = True
            fs = _starts(seg.contour_nseg)
            cs = seg.contour_closed & (seg.contour_nseg > 0)
            sm0 = np.zeros(C, bool)
            sm0[cs] = g1[0][fs[cs]]
            smooth[starts[sm0]] = True
        lin = deg == 1
        pts[pos[lin[sid]]] = seg.ctrl[lin, 1]
        for k in (2, 3):
            if seg_pts[k] is not None:
                pts[pos[(deg == k)[sid]]] = seg_pts[k]
    keep = (seg.contour_nseg > 0) | seg.contour_closed
    tangent = np.zeros((C, 2))
    tangent[:, 0] = 1.0
    lines = _Lines(pts, starts, counts, seg.contour_closed.copy(), smooth, tangent)
    return _select(lines, keep), keep


def _g1_ends(seg):
    """Which segment ends continue smoothly: ``(start, end)``, two (S,) bool
    arrays, True where the path has the same tangent on both sides of the
    segment's start (end) point -- the previous (next) segment of the
    contour, or the closing line of a closed contour, or the other end
    segment across a closing line of zero length.  Open ends and segments
    of zero length are never smooth."""
    ctrl = seg.ctrl
    S = len(ctrl)
    ar = np.arange(S)
    tiny = (_EPS_REL * np.maximum(np.abs(ctrl).reshape(S, -1).max(axis=1), 1e-300))[:, None]

    def first_dir(cand):
        ln = np.hypot(cand[..., 0], cand[..., 1]) > tiny
        return _unit(cand[ar, np.argmax(ln, axis=1)]), ln.any(axis=1)
    tin, vin = first_dir(ctrl[:, 1:] - ctrl[:, :1])
    tout, vout = first_dir(ctrl[:, 3:] - ctrl[:, 2::-1])
    nseg = seg.contour_nseg
    fs = _starts(nseg)
    c = seg.contour
    first = ar == fs[c]
    last = ar == fs[c] + nseg[c] - 1
    closed = seg.contour_closed[c]
    # direction after each segment's end
    nxt, vnx = np.empty((S, 2)), np.zeros(S, bool)
    nxt[:-1], vnx[:-1] = tin[1:], vin[1:]
    gap = seg.contour_start - seg.contour_end
    gl = np.hypot(gap[:, 0], gap[:, 1])
    gv = gl > _EPS_REL * np.maximum(np.abs(seg.contour_start).max(axis=1), 1e-300)
    gu = _unit(gap)
    lc = last & closed
    nxt[lc] = np.where(gv[c[lc]][:, None], gu[c[lc]], tin[fs[c[lc]]])
    vnx[lc] = gv[c[lc]] | vin[fs[c[lc]]]
    vnx[last & ~closed] = False
    # direction before each segment's start
    prv, vpr = np.empty((S, 2)), np.zeros(S, bool)
    prv[1:], vpr[1:] = tout[:-1], vout[:-1]
    fc = first & closed
    lastseg = fs + nseg - 1
    prv[fc] = np.where(gv[c[fc]][:, None], gu[c[fc]], tout[lastseg[c[fc]]])
    vpr[fc] = gv[c[fc]] | vout[lastseg[c[fc]]]
    vpr[first & ~closed] = False

    def same(u, v):
        cr = np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
        return (cr <= 1e-9) & (np.einsum('ij,ij->i', u, v) > 0)
    return vin & vpr & same(prv, tin), vout & vnx & same(tout, nxt)


def _polygon_lines(verbs, points):
    """:func:`_path_lines` for a path of lines only (no flattening): the
    points are the path's own, contour by contour."""
    mv = verbs == MOVE
    cnum = np.cumsum(mv) - 1
    C = int(cnum[-1]) + 1
    cl = verbs == CLOSE
    closed = np.zeros(C, bool)
    closed[cnum[cl]] = True
    counts = np.bincount(cnum[~cl], minlength=C).astype(np.int64)
    keep = (counts > 1) | closed
    tangent = np.zeros((C, 2))
    tangent[:, 0] = 1.0
    lines = _Lines(points, _starts(counts), counts, closed, np.zeros(len(points), bool),
                   tangent)
    return _select(lines, keep), keep


def _select(lines, keep):
    """Keep only the contours where ``keep`` is True."""
    if np.all(keep):
        return lines
    cid = np.repeat(np.arange(len(lines.counts)), lines.counts)
    vk = keep[cid]
    counts = lines.counts[keep]
    return _Lines(lines.points[vk], _starts(counts), counts, lines.closed[keep],
                  lines.smooth[vk], lines.tangent[keep])


def _clean(lines, eps):
    """Merge runs of (nearly) equal consecutive points; for closed contours
    also drop a last run equal to the first point (zero-length closing
    segment).  A merged vertex is smooth only if every point of its run is.
    ``eps`` is a float or a (C,) array, one per contour."""
    P, starts, counts = lines.points, lines.starts, lines.counts
    N = len(P)
    if N == 0:
        return lines
    cid = np.repeat(np.arange(len(counts)), counts) if len(counts) > 1 else np.zeros(N, np.int64)
    first = np.zeros(N, bool)
    first[starts] = True
    step = np.empty(N)
    step[0] = np.inf
    dP = P[1:] - P[:-1]
    step[1:] = np.hypot(dP[:, 0], dP[:, 1])
    head = first | (step > (eps[cid] if np.ndim(eps) else eps))   # first point of each run
    if head.all():
        smooth = lines.smooth
        heads = None
        hc = cid
    else:
        heads = np.flatnonzero(head)
        smooth = np.logical_and.reduceat(lines.smooth, heads)
        hc = cid[heads]
    # closed contours: drop a final run that returns onto the first point
    lastc = np.zeros(len(hc), bool)
    lastc[:-1] = hc[1:] != hc[:-1]
    lastc[-1] = True
    hpts = P if heads is None else P[heads]
    cand = np.flatnonzero(lastc & lines.closed[hc])
    if len(cand):
        d = hpts[cand] - P[starts[hc[cand]]]
        e = eps[hc[cand]] if np.ndim(eps) else eps
        notfirst = ~first[cand] if heads is None else ~first[heads[cand]]
        cand = cand[notfirst & (np.hypot(d[:, 0], d[:, 1]) <= e)]
    if heads is None and not len(cand):
        return lines
    keep = np.ones(len(hc), bool)
    keep[cand] = False
    hc, smooth, hpts = hc[keep], smooth[keep], hpts[keep]
    ncount = np.bincount(hc, minlength=len(counts)).astype(np.int64)
    return _Lines(hpts, _starts(ncount), ncount, lines.closed, smooth, lines.tangent)


def _eps(points):
    if len(points) == 0:
        return 0.0
    return _EPS_REL * max(float(np.abs(points).max()), 1e-300)


def _unit(v):
    """Unit vectors of (M, 2) ``v``; (1, 0) where ``v`` is zero."""
    ln = np.hypot(v[:, 0], v[:, 1])
    ok = ln > 0
    u = np.empty(v.shape)
    u[:, 0], u[:, 1] = 1.0, 0.0
    np.divide(v, ln[:, None], out=u, where=ok[:, None])
    return u


# ---------------------------------------------------------------------------
# dashing
# ---------------------------------------------------------------------------

def _as_lines(polylines):
    """Accept a :class:`raster.geometry.flattening.Polylines`-like object (``points``,
    ``starts``, ``closed``), a :class:`DashedLines` or an internal _Lines."""
    if isinstance(polylines, _Lines):
        return polylines
    try:
        P = np.asarray(polylines.points, dtype=np.float64).reshape(-1, 2)
        starts = np.asarray(polylines.starts, dtype=np.int64).reshape(-1)
        closed = np.asarray(polylines.closed, dtype=bool).reshape(-1)
    except (AttributeError, TypeError, ValueError):
        raise StrokeError('expected polylines with points, starts and closed arrays') from None
    if len(closed) != len(starts) or not np.all(np.isfinite(P)) or \
            np.any(np.diff(np.append(starts, len(P))) < 1) or (len(starts) and starts[0] != 0):
        raise StrokeError('malformed polylines (starts, closed and points disagree)')
    counts = np.diff(np.append(starts, len(P))).astype(np.int64)
    tangent = getattr(polylines, 'tangent', None)
    if tangent is None:
        tangent = np.tile([1.0, 0.0], (len(starts), 1))
    return _Lines(P, starts, counts, closed, np.zeros(len(P), bool),
                  np.asarray(tangent, dtype=np.float64).reshape(-1, 2))


def _dash(lines, pattern, offset, near=None, cp=None):
    """Dash cleaned lines; returns ``(_Lines, source)``: one polyline per
    dash (tangent set per dash) and the (K,) int64 contour each came from.

    A closed contour is unrolled twice around (two laps), so that the dash
    through its start point -- from the last dash start ``a`` to ``L`` and on
    from 0 -- is the single interval ``[a, L + b]``.  A closed contour that
    one dash covers entirely stays closed.

    With ``near`` (a :class:`_Near`; ``cp`` (C,) numbers each contour's
    path) only the periods of the pattern that overlap the arc-length
    spans of the contours lying within reach of the window are made (a
    superset of the dashes that can reach it, in order), and the budget
    counts those: a long, finely dashed line seen through a small window
    costs its few dashes there."""
    P, starts, counts, closed = lines.points, lines.starts, lines.counts, lines.closed
    C = len(counts)
    if C == 0:
        return lines, np.zeros(0, np.int64)
    cl = closed & (counts >= 2)
    ucounts = np.where(cl, 2 * counts + 1, counts)
    ustarts = _starts(ucounts)
    cid, loc = _ranges(ucounts)
    src = starts[cid] + loc % counts[cid]
    U = P[src]
    usmooth = lines.smooth[src]
    ulast = ustarts + ucounts - 1
    # global arc length with a gap of 1 between contours (strictly increasing)
    seglen = np.zeros(len(U))
    seglen[1:] = np.hypot(*(U[1:] - U[:-1]).T)
    seglen[ustarts] = 1.0
    seglen[0] = 0.0
    S = np.cumsum(seglen)
    base = S[ustarts]
    L = S[np.where(cl, ustarts + counts, ulast)] - base      # one lap

    period = float(pattern.sum())
    cum = np.concatenate([[0.0], np.cumsum(pattern)])
    on0, on1 = cum[0:-1:2], cum[1::2]             # dash intervals within a period
    off = float(offset) % period
    if not 0 <= off < period:
        off = 0.0
    with np.errstate(over='ignore', invalid='ignore'):
        Kf = np.floor((L + off) / period) + 1
    # a contour of length zero has no dashes (as Skia's contour measure
    # skips it): dashed, a zero-length subpath draws no dot
    Kf[L <= 0] = 0
    if near is None:
        _check_size(float(Kf.sum()) * len(on0), 'dashes')      # before the int cast (huge)
        K = Kf.astype(np.int64)
        kc, kk = _ranges(K)
    else:
        kc, kk = _near_periods(near, cp[cid], U, S, ulast, base, Kf, period, off, on0, on1)
    a = (kk * period - off)[:, None] + on0[None, :]
    b = (kk * period - off)[:, None] + on1[None, :]
    dc = np.repeat(kc, len(on0))
    a, b = a.reshape(-1), b.reshape(-1)
    Lc = L[dc]
    keep = ((a < Lc) & (b > 0)) | ((a == b) & (a >= 0) & (a <= Lc))
    a, b, dc, Lc = a[keep], b[keep], dc[keep], Lc[keep]
    a = np.clip(a, 0.0, Lc)
    b = np.clip(b, 0.0, Lc)
    # closed contours: the last dash runs on into the first when both touch
    # the start point (intervals are in order, so first/last are run ends)
    whole = np.zeros(len(dc), bool)
    if np.any(cl) and len(dc):
        head = np.flatnonzero(np.r_[True, dc[1:] != dc[:-1]])
        tail = np.r_[head[1:] - 1, len(dc) - 1]
        touch = cl[dc[head]] & (a[head] == 0) & (b[tail] == Lc[tail])
        whole[head[touch & (head == tail)]] = True
        mh, mt = head[touch & (head != tail)], tail[touch & (head != tail)]
        b[mt] = Lc[mt] + b[mh]
        drop = np.zeros(len(dc), bool)
        drop[mh] = True
        a, b, dc, whole = a[~drop], b[~drop], dc[~drop], whole[~drop]
    a = a + base[dc]
    b = b + base[dc]

    lo_i = ustarts[dc]
    hi_i = np.maximum(ulast[dc] - 1, lo_i)

    def at(s):
        i = np.clip(np.searchsorted(S, s, 'right') - 1, lo_i, hi_i)
        j = np.minimum(i + 1, ulast[dc])
        span = S[j] - S[i]
        with np.errstate(invalid='ignore', divide='ignore'):
            t = np.where(span > 0, (s - S[i]) / span, 0.0)
        t = np.clip(t, 0.0, 1.0)[:, None]
        return U[i] + t * (U[j] - U[i]), U[j] - U[i]

    pa, da = at(a)
    pb, _ = at(b)
    j_lo = np.searchsorted(S, a, 'right')
    j_hi = np.searchsorted(S, b, 'left')
    nint = np.maximum(j_hi - j_lo, 0)
    dcounts = nint + 2
    _check_size(float(dcounts.sum()), 'dash points')
    did, dl = _ranges(dcounts)
    dstarts = _starts(dcounts)
    out = np.empty((len(did), 2))
    sm = np.zeros(len(did), bool)
    inner = (dl > 0) & (dl < dcounts[did] - 1)
    vi = j_lo[did[inner]] + dl[inner] - 1
    out[inner] = U[vi]
    sm[inner] = usmooth[vi]
    out[dstarts] = pa
    out[dstarts + dcounts - 1] = pb
    tangent = _unit(da)
    return _Lines(out, dstarts, dcounts, whole, sm, tangent), dc


def _near_periods(near, pc, U, S, ulast, base, Kf, period, off, on0, on1):
    """``(contour, period index)`` pairs, in order, of the periods of the
    dash pattern that overlap the parts of the unrolled contours (points
    ``U``, arc length ``S``, path ``pc`` of each point) within reach of
    ``near``'s window (see :func:`_dash`)."""
    seg = np.ones(len(U), bool)
    seg[ulast] = False                           # segment i runs from U[i] to U[i + 1]
    i = np.flatnonzero(seg)
    cid = np.searchsorted(ulast, i)              # the unrolled contour of each segment
    t0, t1 = near.clip(U[i], U[i + 1], pc[i])
    hit = t0 <= t1
    i, cid, t0, t1 = i[hit], cid[hit], t0[hit], t1[hit]
    span = S[i + 1] - S[i]
    u = S[i] + t0 * span - base[cid]
    v = S[i] + t1 * span - base[cid]
    # periods k with k * period - off + on0[q] <= v and ... + on1[q] >= u
    # for some q, within 0 .. K - 1
    with np.errstate(over='ignore', invalid='ignore'):
        lo = np.maximum(np.ceil((u + off - on1[-1]) / period), 0.0)
        hi = np.minimum(np.floor((v + off - on0[0]) / period), Kf[cid] - 1)
    n = np.maximum(hi - lo + 1, 0.0)
    _check_size(float(n.sum()) * len(on0), 'dashes')          # before the int cast (huge)
    if len(hi) and not float(np.abs(hi).max()) < 2.0 ** 52:
        _check_size(float('inf'), 'dashes')
    n = n.astype(np.int64)
    pair_c = np.repeat(cid, n)
    pair_k = np.repeat(lo.astype(np.int64), n) + _ranges(n)[1]
    # spans of one contour may share periods: each pair once, in order
    o = np.lexsort((pair_k, pair_c))
    pair_c, pair_k = pair_c[o], pair_k[o]
    new = np.ones(len(pair_c), bool)
    new[1:] = (pair_c[1:] != pair_c[:-1]) | (pair_k[1:] != pair_k[:-1])
    return pair_c[new], pair_k[new]


class _Near:
    """A device window for :func:`_geometry`: which dashes (user space) of
    which path (transform rows ``m`` ``a b c d e f``, (P, 6); NaN rows for
    outlines several transforms share, never cut) can reach the box
    ``window`` within ``reach`` (P,) device units."""

    def __init__(self, window, m, reach):
        self.box = window
        self.m = m
        self.reach = reach

    def clip(self, p0, p1, c):
        """The parameter range ``[t0, t1]`` of each user-space segment
        ``p0 -> p1`` ((N, 2)) of path ``c`` that lies within reach of the
        window (t0 > t1: none): the segment clipped to the grown window in
        device space (an affine map keeps the parameter)."""
        m = self.m[c]
        a, b, cc, d = m[:, :4].T
        r = self.reach[c]
        x0, y0, x1, y1 = self.box
        t0 = np.zeros(len(c))
        t1 = np.ones(len(c))
        q = apply_each(m, p0)                   # the start in device space
        with np.errstate(invalid='ignore', divide='ignore', over='ignore'):
            for lo, hi, q0, dq in (
                    (x0 - r, x1 + r, q[:, 0],
                     a * (p1[:, 0] - p0[:, 0]) + cc * (p1[:, 1] - p0[:, 1])),
                    (y0 - r, y1 + r, q[:, 1],
                     b * (p1[:, 0] - p0[:, 0]) + d * (p1[:, 1] - p0[:, 1]))):
                ta, tb = (lo - q0) / dq, (hi - q0) / dq
                flat = dq == 0
                inside = (q0 >= lo) & (q0 <= hi)
                t0 = np.where(flat, np.where(inside, t0, 2.0), np.maximum(t0, np.minimum(ta, tb)))
                t1 = np.where(flat, np.where(inside, t1, -1.0), np.minimum(t1, np.maximum(ta, tb)))
        shared = np.isnan(a)
        t0[shared], t1[shared] = 0.0, 1.0
        return t0, t1

    def __call__(self, lines, cp):
        """True for the contours of ``lines`` (user space; ``cp`` their
        paths) whose device box comes within reach of the window."""
        keep = np.ones(len(lines.counts), bool)
        has = np.flatnonzero(lines.counts > 0)
        if len(has) == 0:
            return keep
        # (each range runs to the next nonempty contour's start: empty
        # contours hold no points)
        st = lines.starts[has]
        lo = np.minimum.reduceat(lines.points, st)
        hi = np.maximum.reduceat(lines.points, st)
        c, h = 0.5 * (lo + hi), 0.5 * (hi - lo)
        m = self.m[cp[has]]
        a, b, cc, d = m[:, :4].T
        r = self.reach[cp[has]]
        x0, y0, x1, y1 = self.box
        dx, dy = apply_each(m, c).T             # the box's centre in device space
        hx = np.abs(a) * h[:, 0] + np.abs(cc) * h[:, 1] + r
        hy = np.abs(b) * h[:, 0] + np.abs(d) * h[:, 1] + r
        with np.errstate(invalid='ignore'):
            far = (dx + hx < x0) | (dx - hx > x1) | (dy + hy < y0) | (dy - hy > y1)
        keep[has] = ~far
        return keep


def dash_polylines(polylines: Any, dash: Optional[Sequence[float]],
                   offset: float = 0.0) -> DashedLines:
    """Cut polylines into dashes.

    Parameters
    ----------
    polylines : Polylines-like
        Any object with ``points`` ((N, 2) float64), ``starts`` ((K,) int64,
        first vertex of each polyline, ``starts[0] == 0``) and ``closed``
        ((K,) bool), e.g. :class:`raster.geometry.flattening.Polylines`, in user units.
    dash : sequence of float
        SVG dash array (see :func:`dash_pattern`).
    offset : float
        Dash offset; negative or larger than the pattern length wraps.

    Returns
    -------
    DashedLines
        Polylines, one per dash, in path order.  The pattern restarts at
        each polyline; a closed polyline is dashed from its start point
        around to the same point, and a dash running through that point is
        one polyline (its last part first).  Dashes are open, except a closed
        polyline covered by one dash, which stays closed.  With a solid
        pattern the polylines are returned unchanged.

    >>> import numpy as np
    >>> lines = DashedLines(np.array([[0., 0], [10, 0]]), np.array([0]),
    ...                     np.array([False]), np.array([[1., 0]]))
    >>> d = dash_polylines(lines, [3, 1])
    >>> [p[:, 0].tolist() for p, c in d]
    [[0.0, 3.0], [4.0, 7.0], [8.0, 10.0]]
    """
    lines = _as_lines(polylines)
    pattern = dash_pattern(dash)
    off = _finite('dash offset', offset)
    if pattern is not None:
        lines = _dash(_clean(lines, _eps(lines.points)), pattern, off)[0]
    return DashedLines(lines.points, lines.starts, lines.closed, lines.tangent)


# ---------------------------------------------------------------------------
# outline pieces
# ---------------------------------------------------------------------------

def _rot90(v):
    """Rotate (.., 2) vectors by +90 degrees: (x, y) -> (-y, x)."""
    out = np.empty(v.shape)
    out[..., 0] = -v[..., 1]
    out[..., 1] = v[..., 0]
    return out


def _arc_step(r, tol):
    """Largest angle step (radians, at most pi/2) for an arc of radius ``r``
    polygonized by :func:`_arcs` within ``tol``.

    The vertices sit at the area-preserving radius ``R = r * sqrt(a / sin a)``
    (``a`` the step), so each fan triangle has exactly the area of its circle
    sector: round caps and dots are not systematically too small.  The
    outward error ``R - r`` is about ``r a^2 / 12`` and the inward error (at
    the chord midpoints) about ``r a^2 / 24``; the factor 0.9 covers the
    higher-order terms up to ``a = pi/2``.
    """
    r = np.asarray(r, dtype=np.float64)
    q = np.full(np.broadcast(r, tol).shape, np.inf)
    np.divide(12.0 * tol, r, out=q, where=r > 0)
    a = 0.9 * np.sqrt(q)
    return np.where(np.isfinite(a), np.minimum(a, np.pi / 2), np.pi / 2)


def _arcs(center, u, sweep, tol, full=False):
    """Polygonized circle arcs, within ``tol``.

    Arc ``f`` has centre ``center[f]``, starts in the direction of ``u[f]``
    (whose length is the radius) and turns by ``sweep[f]`` radians (positive:
    from +x towards +y).  Its vertices sit at the area-preserving radius (see
    :func:`_arc_step`).  Returns ``(points (M, 2), counts (F,))``: ``n + 1``
    points per arc (both ends included), or ``n`` when ``full`` (a whole
    circle, the end point omitted).
    """
    F = len(center)
    if F == 0:
        return np.zeros((0, 2)), np.zeros(0, np.int64)
    r = np.hypot(u[:, 0], u[:, 1])
    nf = np.maximum(np.ceil(np.abs(sweep) / _arc_step(r, tol)), 1.0)
    _check_size(float(nf.sum()) + F, 'arc points')
    n = nf.astype(np.int64)
    a = np.abs(sweep) / nf
    grow = np.ones(F)
    np.sqrt(np.divide(a, np.sin(a), out=grow, where=a > 0), out=grow)
    counts = n if full else n + 1
    fid, k = _ranges(counts)
    ang = sweep[fid] * (k / nf[fid])
    co, si = np.cos(ang), np.sin(ang)
    uu = u[fid] * grow[fid, None]
    pts = center[fid] + np.stack([co * uu[:, 0] - si * uu[:, 1],
                                  si * uu[:, 0] + co * uu[:, 1]], axis=1)
    return pts, counts


class _Items:
    """Runs of outline points ("items"), each destined for one polygon at one
    sort key.  Item points live in a pool; an item may read its run in
    reverse.  :meth:`polygons` sorts the items and gathers the points (once:
    it empties the pool)."""

    def __init__(self):
        self.pool, self.npool = [], 0
        self.cols = []                    # (poly, key, start, count, reverse)

    def put(self, pts):
        """Add (M, 2) points to the pool; returns the start index."""
        start = self.npool
        if len(pts):
            self.pool.append(pts)
            self.npool += len(pts)
        return start

    def add(self, poly, key, start, count, reverse=False):
        # empty items (most joins inside curves add no point) are dropped
        # here rather than in polygons: five int64 per item otherwise
        n = len(poly)
        keep = np.asarray(count) > 0
        if keep.ndim and not keep.all():
            sel = np.flatnonzero(keep)
            n = len(sel)
            poly, key, start, count, reverse = (
                np.broadcast_to(a, keep.shape)[sel] for a in (poly, key, start, count, reverse))
        col = np.empty((5, n), np.int64)
        col[0], col[1], col[2], col[3], col[4] = poly, key, start, count, reverse
        self.cols.append(col)

    def polygons(self):
        """Gather the items: ``(points (M, 2), counts (K,), ids (K,))``, the
        points of each non-empty polygon (reversed, see below), their counts
        and the polygon numbers they came from."""
        if not self.cols:
            return np.zeros((0, 2)), np.zeros(0, np.int64), np.zeros(0, np.int64)
        poly, key, start, cnt, rev = np.concatenate(self.cols, axis=1) \
            if len(self.cols) > 1 else self.cols[0]
        rev = rev.astype(bool)
        keep = cnt > 0
        if not keep.all():
            poly, key, start, cnt, rev = poly[keep], key[keep], start[keep], cnt[keep], rev[keep]
        order = np.lexsort((key, poly))
        poly, start, cnt, rev = poly[order], start[order], cnt[order], rev[order]
        total = int(cnt.sum())
        _check_size(float(total), 'outline points')
        pool = np.concatenate(self.pool) if len(self.pool) > 1 else \
            (self.pool[0] if self.pool else np.zeros((0, 2)))
        iid = np.repeat(np.arange(len(cnt)), cnt)
        k = np.arange(total) - np.repeat(_starts(cnt), cnt)
        src = start[iid] + np.where(rev[iid], cnt[iid] - 1 - k, k)
        # points as complex numbers (x + iy, the same 16 bytes): one compare
        # per point pair, same result as comparing x and y (-0.0 == 0.0)
        pts = np.ascontiguousarray(pool[src], np.float64).view(np.complex128).reshape(-1)
        pid = poly[iid]
        # (the pool is read once: its arrays go now, the gathered points stay)
        self.pool, self.npool = [], 0
        del pool, iid, k, src
        # drop repeated points (collinear vertices, coincident join ends)
        keep = np.ones(total, bool)
        if total > 1:
            keep[1:] = (pid[1:] != pid[:-1]) | (pts[1:] != pts[:-1])
            pts, pid = pts[keep], pid[keep]
        # drop a last point back on the first
        head = np.ones(len(pid), bool)
        head[1:] = pid[1:] != pid[:-1]
        tail = np.ones(len(pid), bool)
        tail[:-1] = head[1:]
        tail &= ~head
        h = np.flatnonzero(head)
        tails = np.flatnonzero(tail)
        if len(tails):
            back = pts[tails] == pts[h[np.searchsorted(h, tails, 'right') - 1]]
            if back.any():
                keep = np.ones(len(pts), bool)
                keep[tails[back]] = False
                pts, pid = pts[keep], pid[keep]
        counts = np.bincount(pid)
        ids = np.flatnonzero(counts)
        counts = counts[ids].astype(np.int64)
        # reverse every polygon: the winding number becomes +1 per covering
        # piece (positive shoelace areas, x right and y down)
        ends = np.cumsum(counts)
        src = np.repeat(ends + _starts(counts) - 1, counts) - np.arange(len(pts))
        return pts[src].view(np.float64).reshape(-1, 2), counts, ids


def _outline(lines, style, tol):
    """Outline polygons of the stroke of cleaned ``lines``: (points, counts,
    contour of each polygon).  ``tol`` is a float or a (C,) array, one
    tolerance per contour of ``lines``.

    Think of the stroke as a union of convex pieces: one rectangle per
    segment, one wedge per join on the outer side of the turn, one piece per
    cap, all with the same orientation (negative shoelace area), so the
    winding number of a point is minus the number of pieces covering it.
    Adding the pieces' boundaries as cycles, the edges shared by neighbours
    cancel, and what remains is, per open subpath, one polygon: the left
    offsets forward (with the outer join points where the left side is
    outer), the end cap, the right offsets backward, the start cap; per
    closed subpath two loops (left and right).  At an inner join the cycle
    sum passes through the vertex itself (the "pivot").  The pivot may be
    skipped when the triangle it spans is covered by both neighbouring
    rectangles (``r * sin(turn) <= both segment lengths``): that changes the
    winding by one only where it is at least two.  So these polygons have
    exactly the winding numbers of the pieces, and nonzero fills the union.
    """
    N = len(lines.points)
    if N <= _OUTLINE_POINTS:
        return _outline_part(lines, style, tol, None)
    # a long outline in parts of about _OUTLINE_POINTS points: the build's
    # arrays (tens of float64 per point) stay a few MB
    parts = []
    for sub, src, bare in _outline_parts(lines):
        pts, pcounts, ids = _outline_part(sub, style, tol[src] if np.ndim(tol) else tol, bare)
        parts.append((pts, pcounts, src[ids]))
    return (np.concatenate([q[0] for q in parts]), np.concatenate([q[1] for q in parts]),
            np.concatenate([q[2] for q in parts]))


#: Points of polylines outlined at once by :func:`_outline`.
_OUTLINE_POINTS = 1 << 14


def _outline_part(lines, style, tol, bare):
    """:func:`_outline` of polylines of at most about ``_OUTLINE_POINTS``
    points (``bare``: see :func:`_outline_items`)."""
    items, npoly = _outline_items(lines, style, tol, bare)
    # (the arrays of the build are gone: only the items' pool is live)
    pts, pcounts, ids = items.polygons()
    if npoly is None:
        return pts, pcounts, ids
    return pts, pcounts, np.repeat(np.arange(len(npoly)), npoly)[ids]


def _outline_parts(lines):
    """The polylines of ``lines`` in parts of about ``_OUTLINE_POINTS``
    points, in order: ``(part, src, bare)`` with ``src`` ((c,) int64) the
    contour of ``lines`` each contour of the part comes from and ``bare``
    as for :func:`_outline_items` (or None).

    Short contours go whole, several to a part.  A longer one is cut into
    open windows of ``B + 2`` vertices, each starting ``B`` vertices after
    the last, so that consecutive windows share one segment: every join
    lies inside one window, and the shared segment's rectangle is covered
    twice (the same sign: the nonzero union is the stroke).  The cut ends
    are bare (no cap).  A closed contour is first unrolled into an open one
    through its first vertex and on to the second (its closing join inside,
    its first segment twice), bare at both ends."""
    B = _OUTLINE_POINTS
    P, starts, counts = lines.points, lines.starts, lines.counts
    C = len(counts)
    long_ = np.flatnonzero(counts > B).tolist()
    c0 = 0
    for c in long_ + [C]:
        if c0 < c:                                   # short contours c0 .. c-1
            end = np.cumsum(counts[c0:c])
            grp = (end - 1) // B
            cuts = np.flatnonzero(np.diff(grp)) + 1
            for g0, g1 in zip([0] + cuts.tolist(), cuts.tolist() + [c - c0]):
                a, b = c0 + g0, c0 + g1
                lo, hi = int(starts[a]), int(starts[b - 1] + counts[b - 1])
                sub = _Lines(P[lo:hi], starts[a:b] - lo, counts[a:b], lines.closed[a:b],
                             lines.smooth[lo:hi], lines.tangent[a:b])
                yield sub, np.arange(a, b), None
        if c == C:
            break
        s0, m = int(starts[c]), int(counts[c])
        ring = bool(lines.closed[c])
        seq = np.arange(s0, s0 + m)
        if ring:
            seq = np.concatenate([seq, seq[:2]])
        L = len(seq)
        for k0 in range(0, L - 1, B):
            w = seq[k0:k0 + B + 2]
            last = k0 + B + 2 >= L
            sub = _Lines(P[w], np.zeros(1, np.int64), np.array([len(w)], np.int64),
                         np.zeros(1, bool), lines.smooth[w], lines.tangent[c:c + 1])
            bare = np.array([[ring or k0 > 0, ring or not last]])
            yield sub, np.array([c], np.int64), bare
            if last:
                break
        c0 = c + 1


def _outline_items(lines, style, tol, bare=None):
    """The items of :func:`_outline` (an :class:`_Items`) and the number of
    polygons per contour (None without points).  ``bare`` ((C, 2) bool or
    None) marks the start and end of open contours that get no cap."""
    P, starts, counts, closed = lines.points, lines.starts, lines.counts, lines.closed
    r = 0.5 * style.width
    N, C = len(P), len(counts)
    items = _Items()
    if N == 0:
        return items, None
    if np.ndim(tol):
        def tol_of(c):
            return tol[c]
    else:
        def tol_of(c):
            return tol
    if C == 1:
        cid, loc = np.zeros(N, np.int64), np.arange(N)
    else:
        cid, loc = _ranges(counts)
    m = counts[cid]
    ring = closed[cid] & (m >= 2)
    has_out = (loc < m - 1) | ring
    has_in = (loc > 0) | ring
    idx = np.arange(N)
    nxt = np.where(loc < m - 1, idx + 1, starts[cid])
    prv = np.where(loc > 0, idx - 1, starts[cid] + m - 1)
    vec = P[nxt] - P
    seglen = np.hypot(vec[:, 0], vec[:, 1])
    d = _unit(vec)                                  # valid where has_out
    nrm = _rot90(d) * r

    is_ring = closed & (counts >= 2)
    is_open = ~closed & (counts >= 2)
    is_dot = (counts == 1) & (style.cap != 'butt')
    npoly = np.where(is_ring, 2, (is_open | is_dot).astype(np.int64))
    pbase = _starts(npoly)
    nseg = np.where(is_ring, counts, counts - 1)

    # segments: left run [a+n, b+n], right run [b-n, a-n]
    s = np.flatnonzero(has_out)
    c, k, S = cid[s], loc[s], nseg[cid[s]]
    a, b, nn = P[s], P[nxt[s]], nrm[s]
    quads = np.empty((len(s), 4, 2))
    quads[:, 0] = a + nn
    quads[:, 1] = b + nn
    quads[:, 2] = b - nn
    quads[:, 3] = a - nn
    quads = quads.reshape(-1, 2)
    base = items.put(quads)                         # (edited in place at inner joins)
    rs = np.arange(len(s)) * 4 + base
    qpos = np.zeros(N, np.int64)                    # vertex -> its segment's row in quads
    qpos[s] = np.arange(len(s)) * 4
    items.add(pbase[c], 4 * k, rs, 2)
    items.add(pbase[c] + is_ring[c], np.where(is_ring[c], 4 * (S - 1 - k), 4 * S + 2 + 4 * (S - 1 - k)),
              rs + 2, 2)

    # joins
    jv = np.flatnonzero(has_in & has_out)
    if len(jv):
        c, l, S = cid[jv], loc[jv], nseg[cid[jv]]
        pj = prv[jv]
        d0, d1, v = d[pj], d[jv], P[jv]
        cross = d0[:, 0] * d1[:, 1] - d0[:, 1] * d1[:, 0]
        dot = np.clip(d0[:, 0] * d1[:, 0] + d0[:, 1] * d1[:, 1], -1.0, 1.0)
        theta = np.arctan2(np.abs(cross), dot)      # turning angle in [0, pi]
        sgn = np.where(cross >= 0, 1.0, -1.0)
        o0 = np.empty((len(jv), 2))                 # outer unit normals
        o0[:, 0], o0[:, 1] = sgn * d0[:, 1], -sgn * d0[:, 0]
        o1 = np.empty((len(jv), 2))
        o1[:, 0], o1[:, 1] = sgn * d1[:, 1], -sgn * d1[:, 0]
        turn = theta > 1e-9
        join = style.join
        left_outer = sgn < 0                         # outer normal = +n
        cos_half = np.sqrt(0.5 * (1.0 + dot))       # 1 / (miter length / width)
        roundish = turn & (lines.smooth[jv] | (join == 'round'))
        # a round join whose miter stays within tol of it is that miter
        mit = roundish & (r * (1.0 - cos_half) <= tol_of(c) * cos_half)
        rnd = roundish & ~mit
        ostart = np.zeros(len(jv), np.int64)        # outer points, from o0 to o1
        ocnt = np.zeros(len(jv), np.int64)
        if join in ('miter', 'miter-clip', 'arcs'):
            sharp = turn & ~roundish
            fits = cos_half * style.miterlimit >= 1.0
            mit |= sharp & fits
            if join == 'miter-clip':
                q = sharp & ~fits
                bis = o0[q] + o1[q]
                bl = np.hypot(bis[:, 0], bis[:, 1])
                bis = np.where((bl > 1e-12)[:, None], bis / np.maximum(bl, 1e-300)[:, None], d0[q])
                t = (style.miterlimit * r - r * np.einsum('ij,ij->i', o0[q], bis)) / \
                    np.maximum(np.einsum('ij,ij->i', d0[q], bis), 1e-300)
                e0 = v[q] + r * o0[q] + t[:, None] * d0[q]
                e1 = v[q] + r * o1[q] - t[:, None] * d1[q]
                ostart[q] = items.put(np.stack([e0, e1], axis=1).reshape(-1, 2)) + \
                    2 * np.arange(int(q.sum()))
                ocnt[q] = 2
        # a miter tip lies on both outer offset lines: it replaces their ends
        # (adding the miter triangle beyond the bevel to the cycle sum); the
        # inner offset lines cross at the mirror image of the tip
        shortest = np.minimum(seglen[pj], seglen[jv])
        pivot = r * np.sin(theta) > shortest
        x = turn & ~pivot & (theta <= 0.5 * np.pi)
        tx = mit | x
        if tx.any():
            h = o0[tx] + o1[tx]
            h *= (r / (1.0 + dot[tx]))[:, None]
            lo = left_outer[tx].astype(np.int64)
            qin, qout = qpos[pj[tx]], qpos[jv[tx]]
            m1, x1 = mit[tx], x[tx]
            tip = v[tx] + h
            quads[(qin + 2 - lo)[m1]] = tip[m1]          # outer end, segment in
            quads[(qout + 3 - 3 * lo)[m1]] = tip[m1]     # outer start, segment out
            X = v[tx] - h
            quads[(qin + 1 + lo)[x1]] = X[x1]            # inner end, segment in
            quads[(qout + 3 * lo)[x1]] = X[x1]           # inner start, segment out
        if np.any(rnd):
            pts, cnt = _arcs(v[rnd], r * o0[rnd], (sgn * theta)[rnd], tol_of(c[rnd]))
            ostart[rnd] = items.put(pts) + _starts(cnt)
            ocnt[rnd] = cnt
        pstart = np.zeros(len(jv), np.int64)
        if pivot.any():
            pstart[pivot] = items.put(v[pivot]) + np.arange(int(pivot.sum()))
        pcnt = pivot.astype(np.int64)
        if pivot.any() or ocnt.any():               # (else the joins add no point)
            lkey = 4 * ((l - 1) % S) + 2
            rkey = np.where(is_ring[c], 4 * (S - 1 - l) + 2, 4 * S + 4 + 4 * (S - 1 - l))
            items.add(pbase[c], lkey, np.where(left_outer, ostart, pstart),
                      np.where(left_outer, ocnt, pcnt))
            items.add(pbase[c] + is_ring[c], rkey, np.where(left_outer, pstart, ostart),
                      np.where(left_outer, pcnt, ocnt), ~left_outer)

    # caps of open subpaths: end cap from b+n to b-n, start cap from a-n to a+n
    # (not at the ends ``bare`` marks: cuts of a long contour, see _outline)
    co = np.flatnonzero(is_open)
    if len(co) and style.cap != 'butt':
        ce = co if bare is None else co[~bare[co, 1]]
        cs = co if bare is None else co[~bare[co, 0]]
        lb, fa = starts[ce] + counts[ce] - 1, starts[cs]
        de, ne = d[lb - 1], nrm[lb - 1]
        ds, ns = d[fa], nrm[fa]
        if style.cap == 'square':
            end = np.stack([P[lb] + ne + r * de, P[lb] - ne + r * de], axis=1)
            beg = np.stack([P[fa] - ns - r * ds, P[fa] + ns - r * ds], axis=1)
            items.add(pbase[ce], 4 * nseg[ce], items.put(end.reshape(-1, 2))
                      + 2 * np.arange(len(ce)), 2)
            items.add(pbase[cs], 8 * nseg[cs] + 2, items.put(beg.reshape(-1, 2))
                      + 2 * np.arange(len(cs)), 2)
        else:
            pts, cnt = _arcs(P[lb], ne, np.full(len(ce), -np.pi), tol_of(ce))
            items.add(pbase[ce], 4 * nseg[ce], items.put(pts) + _starts(cnt), cnt)
            pts, cnt = _arcs(P[fa], -ns, np.full(len(cs), -np.pi), tol_of(cs))
            items.add(pbase[cs], 8 * nseg[cs] + 2, items.put(pts) + _starts(cnt), cnt)

    # subpaths of zero length: a disc or a square oriented by the tangent
    cd = np.flatnonzero(is_dot)
    if len(cd):
        ctr = P[starts[cd]]
        h = _unit(lines.tangent[cd]) * r
        if style.cap == 'square':
            q = _rot90(h)
            sq = np.stack([ctr + h - q, ctr - h - q, ctr - h + q, ctr + h + q], axis=1)
            items.add(pbase[cd], 0, items.put(sq.reshape(-1, 2)) + 4 * np.arange(len(cd)), 4)
        else:
            pts, cnt = _arcs(ctr, h, np.full(len(cd), -2 * np.pi), tol_of(cd), full=True)
            items.add(pbase[cd], 0, items.put(pts) + _starts(cnt), cnt)
    return items, npoly


def _emit(points, counts):
    """Path of closed polygons (M L ... Z per polygon)."""
    if len(counts) == 0:
        return Path.empty()
    return Path(_emit_verbs(counts), np.ascontiguousarray(points), _checked=True)


def _emit_verbs(counts):
    """Verbs of closed polygons of ``counts`` (K,) int64 points each: (V,)
    uint8, ``M L ... L Z`` per polygon, read-only."""
    K = len(counts)
    starts = _starts(counts)
    verbs = np.full(int(np.sum(counts)) + K, LINE, np.uint8)
    ar = np.arange(K)
    verbs[starts + ar] = MOVE
    verbs[starts + counts + ar] = CLOSE
    verbs.flags.writeable = False
    return verbs


# ---------------------------------------------------------------------------
# front door
# ---------------------------------------------------------------------------

def stroke(path: Path, style: Optional[StrokeStyle] = None, *, transform: AffineLike = None,
           tolerance: float = 0.25, straddle: bool = False, window: Optional[Sequence[float]] = None,
           **style_kwargs: Any) -> Path:
    """Outline of the stroke of ``path``, to be filled with the nonzero rule.

    Parameters
    ----------
    path : Path
        In user units.
    style : StrokeStyle or None
        The stroke; keyword arguments (``width``, ``join``, ``cap``,
        ``miterlimit``, ``dash``, ``dash_offset``) build one or override
        fields of ``style``.
    transform : Affine or None
        User space to device space, applied to the finished outline.
    tolerance : float
        Largest distance, in device pixels, between the returned outline and
        the exact stroke (curve flattening and arc polygonization).
    straddle : bool
        Flatten the curves into straddled polylines
        (:func:`raster.geometry.flattening.flatten_beziers`): the outline's
        curved sides then lie on both sides of the exact ones, about half
        as far, instead of all inside or outside them.
    window : (x0, y0, x1, y1) or None
        A device box (bounds may be infinite): the dashes of a dashed
        stroke whose outlines cannot reach it (farther from it than
        :func:`stroke_reach` plus ``tolerance`` plus one pixel) are not
        made, so the outline within the box is unchanged and a long dashed
        line drawn through a small window costs its few visible dashes
        (the ``max_flatten_points`` budget counts those).  Solid strokes
        are not cut (see :mod:`raster.geometry.culling`).

    Returns
    -------
    Path
        Closed polygons only (``MOVE``, ``LINE``, ``CLOSE``) in device
        space: one per open subpath or dash, two (its two sides) per closed
        subpath, one per dot.  Their winding number is never negative
        (never positive after a mirroring transform), so the nonzero rule
        fills the stroke, overlaps included.  Empty for a zero width, an
        empty path or a transform with no scale.

    Raises
    ------
    StrokeError
        Invalid style values, tolerance or window, or ``path`` not a Path.
    LimitError
        When the outline would need more than
        ``max_flatten_points`` (:mod:`raster.limits`) points or dashes.

    Examples
    --------
    A closed 10 x 10 square stroked 2 wide gives two loops, the outer and
    the inner edge of the stroke:

    >>> from raster.geometry.path import Path
    >>> sq = Path.polygon([(0, 0), (10, 0), (10, 10), (0, 10)])
    >>> out = stroke(sq, width=2)
    >>> int((out.verbs == 0).sum()), out.control_box()
    (2, (-1.0, -1.0, 11.0, 11.0))
    """
    if not isinstance(path, Path):
        raise StrokeError('stroke() needs a raster.Path, got %s' % type(path).__name__)
    if style is not None and not isinstance(style, StrokeStyle):
        raise StrokeError('style must be a StrokeStyle, got %s' % type(style).__name__)
    if style_kwargs:
        unknown = set(style_kwargs) - _STYLE_FIELDS
        if unknown:
            raise StrokeError('unknown stroke parameter(s): %s' % ', '.join(sorted(unknown)))
    if style is None:
        style = StrokeStyle(**style_kwargs)
    elif style_kwargs:
        style = dataclasses.replace(style, **style_kwargs)
    tol = _finite('tolerance', tolerance)
    if tol <= 0:
        raise StrokeError('tolerance must be > 0, got %r' % (tolerance,))
    if window is not None:
        window = _window(window)
    t = _affine(transform)
    scale = t.max_scale()
    if not math.isfinite(scale):
        raise LimitError('transform scale is too large (%r)' % (t,))
    if style.width == 0 or len(path.verbs) == 0 or scale == 0:
        return Path.empty()
    with np.errstate(over='ignore', invalid='ignore'):         # checked in _check_early
        dev = path.points if t.is_identity else t.apply(path.points)
    _check_early(dev, style.width * scale)
    near = None
    if window is not None:
        m = np.array([[t.a, t.b, t.c, t.d, t.e, t.f]])
        near = _Near(window, m, np.array([stroke_reach(style) * scale + tol + 1.0]))
    pts, counts, _ = _geometry(path, style, tol / scale, straddle=straddle, near=near)
    if not t.is_identity:
        pts = t.apply(pts)
    _check_device(pts)
    return _emit(pts, counts)


def _geometry(path, style, tol_u, cpath=None, npaths=1, straddle=False, near=None):
    """Outline polygons of the stroke of ``path`` in user space.

    ``tol_u`` is the tolerance in user units: a float, or with ``cpath`` a
    (C,) array, one per contour of ``path``.  ``cpath`` ((C,) int64 or None)
    numbers the input path each contour belongs to (paths concatenated by
    :func:`stroke_many`); everything that depends on a path as a whole (the
    size below which points merge) is then computed per path, so each path
    gets the same outline as on its own.  Returns ``(points, counts,
    owner)``: the polygons and, per polygon, the entry of ``cpath`` (or 0).
    ``straddle`` is passed on to the flattening.  ``near`` (a
    :class:`_Near`), for a dashed stroke: only the dashes that can reach
    its window are made (:func:`_dash`) and outlined.
    """
    pattern = dash_pattern(style.dash)
    # dash positions follow the arc length of the flattening, which falls
    # short of the curve's by up to tol/3 per radian: flatten 4x finer
    tol_f = tol_u if pattern is None else 0.25 * tol_u
    # straight caps and sharp joins rest on the end chords of curves
    all_round = style.cap == 'round' and style.join == 'round'
    lines, keep = _path_lines(path, tol_f, 0.0 if all_round else 0.5 * style.width, straddle,
                              seal=pattern is None and style.cap == 'butt')
    if cpath is None:
        cp = np.zeros(len(lines.counts), np.int64)
        eps = _eps(lines.points)
    else:
        cp, tol_u = cpath[keep], tol_u[keep]
        eps = _eps_per_path(lines, cp, npaths)
    lines = _clean(lines, eps)
    if pattern is not None:
        eps = _eps(lines.points) if cpath is None else _eps_per_path(lines, cp, npaths)
        lines, src = _dash(lines, pattern, style.dash_offset, near, cp)
        cp = cp[src]
        if cpath is not None:
            eps, tol_u = eps[src], tol_u[src]
        if near is not None:
            keep = near(lines, cp)
            if not keep.all():
                lines, cp = _select(lines, keep), cp[keep]
                if cpath is not None:
                    eps, tol_u = eps[keep], tol_u[keep]
        lines = _clean(lines, eps)
    pts, counts, owner = _outline(lines, style, tol_u)
    return pts, counts, cp[owner]


def _affine(t):
    """:func:`~raster.geometry.transform.as_affine`, with a StrokeError (not a numpy
    error) for something that is not a transform."""
    try:
        return as_affine(t)
    except RasterError:
        raise
    except (TypeError, ValueError):
        raise StrokeError('cannot interpret %r as an affine transform' % (t,)) from None


def stroke_reach(style):
    """How far (in user units) a stroke of ``style`` can reach beyond the
    path (half the width, times the miter limit or sqrt 2 for square caps)."""
    r = style.width / 2.0
    k = 1.0
    if style.join in ('miter', 'miter-clip', 'arcs'):
        k = max(k, style.miterlimit)
    if style.cap == 'square':
        k = max(k, math.sqrt(2.0))
    return r * k


def _window(window):
    """``window`` checked: four numbers (infinite allowed, not NaN) with
    x0 <= x1 and y0 <= y1, else a StrokeError."""
    try:
        box = tuple(float(v) for v in window)
    except (TypeError, ValueError):
        box = ()
    if len(box) != 4 or any(math.isnan(v) for v in box) or box[0] > box[2] or box[1] > box[3]:
        raise StrokeError('window must be (x0, y0, x1, y1) with x0 <= x1 and y0 <= y1, got %r'
                          % (window,))
    return box


def _eps_per_path(lines, cp, npaths):
    """(C,) merge distance per contour: :func:`_eps` of the points of the
    contour's path (``cp`` numbers the path of each contour, in order)."""
    C = len(lines.counts)
    if C == 0:
        return np.zeros(0)
    amax = np.abs(lines.points).max(axis=1) if len(lines.points) else np.zeros(0)
    pcount = np.bincount(cp, weights=lines.counts, minlength=npaths).astype(np.int64)
    m = np.zeros(npaths)
    has = pcount > 0
    if len(amax):
        m[has] = np.maximum.reduceat(amax, _starts(pcount)[has])
    return _EPS_REL * np.maximum(m, 1e-300)[cp]


def _check_device(pts):
    """Outline points after the transform: finite and within
    ``max_coord`` (:mod:`raster.limits`) (as scan conversion requires), else
    :class:`~raster.errors.LimitError`."""
    if len(pts) and not (np.all(np.isfinite(pts))
                         and np.abs(pts).max() <= limits.current().max_coord):
        raise LimitError('stroke outline coordinates exceed max_coord %g'
                         % limits.current().max_coord)


def _check_early(pts, width):
    """Before any work: the path's device points ``pts`` within
    ``max_coord``, and a stroke ``width`` (device px) that cannot put the
    outline beyond it for certain (every path point has outline points
    ``width / 2`` away, one coordinate at least ``width / (2 sqrt 2)``
    off)."""
    _check_device(pts)
    if len(pts):
        lim = limits.current().max_coord
        if 0.5 * width / math.sqrt(2.0) - float(np.abs(pts).max()) > lim:
            raise LimitError('stroke outline coordinates exceed max_coord %g' % lim)


def stroke_many(paths: Sequence[Path], style: Optional[StrokeStyle] = None, *,
                transforms: Optional[Sequence[AffineLike]] = None,
                tolerance: float = 0.25, straddle: bool = False,
                window: Optional[Sequence[float]] = None) -> List[Path]:
    """Stroke many paths with one style in one vectorized pass.

    The paths are concatenated (contours numbered by the path they come
    from), their outlines are built together in user space, mapped by each
    path's own transform and split back per path.  Each result is the
    outline :func:`stroke` gives for that path alone: identical for solid
    strokes when the paths' transforms have the same largest scale
    (:meth:`~raster.geometry.transform.Affine.max_scale`); otherwise, and for dashes
    (whose arc lengths are summed over all paths in float64), within a
    rounding error far below ``tolerance``.  Repeated paths (equal verbs,
    and points equal up to a translation within
    :data:`~raster.geometry.flattening.REPEAT_GRID` device pixels: the same
    circle at many centres) whose transforms have the same largest scale
    share one user-space outline, moved to each one's place and mapped by
    its transform (within ``REPEAT_GRID`` plus rounding of its own
    outline); the returned paths of such a group share one read-only
    verbs array.

    Parameters
    ----------
    paths : sequence of Path
        In user units.
    style : StrokeStyle or None
        The stroke of every path (None: the default ``StrokeStyle()``).
    transforms : None, Affine or sequence of Affine
        User space to device space: one for all paths, or one per path
        (each anything :func:`raster.geometry.transform.as_affine` accepts).
    tolerance : float
        Largest distance, in device pixels, between each outline and its
        exact stroke.
    straddle : bool
        As for :func:`stroke`.
    window : (x0, y0, x1, y1) or None
        As for :func:`stroke`: dashes that cannot reach this device box are
        left out (except those of an outline several paths share).

    Returns
    -------
    list of Path
        One outline per input path, in order (see :func:`stroke`); empty for
        an empty path, a zero width or a transform with no scale.

    Raises
    ------
    StrokeError
        Invalid style, tolerance or window, an item that is not a Path, or a
        number of transforms different from the number of paths.
    LimitError
        When the outlines together would need more than
        ``max_flatten_points`` (:mod:`raster.limits`) points or dashes, or an
        outline overflows.

    Examples
    --------
    >>> from raster.geometry.path import Path
    >>> a = Path.polygon([(0, 0), (10, 0)], closed=False)
    >>> b = Path.polygon([(0, 0), (10, 0), (10, 10), (0, 10)])
    >>> outs = stroke_many([a, b], StrokeStyle(width=2))
    >>> outs[0] == stroke(a, width=2), outs[1] == stroke(b, width=2)
    (True, True)
    """
    paths = list(paths)
    for p in paths:
        if not isinstance(p, Path):
            raise StrokeError('stroke_many() needs raster.Path items, got %s'
                              % type(p).__name__)
    if style is None:
        style = StrokeStyle()
    elif not isinstance(style, StrokeStyle):
        raise StrokeError('style must be a StrokeStyle, got %s' % type(style).__name__)
    tol = _finite('tolerance', tolerance)
    if tol <= 0:
        raise StrokeError('tolerance must be > 0, got %r' % (tolerance,))
    if window is not None:
        window = _window(window)
    n = len(paths)
    if transforms is None or isinstance(transforms, Affine):
        ts = [_affine(transforms)] * n
    else:
        if isinstance(transforms, (str, bytes)):
            raise StrokeError('transforms must be Affine objects, got %r' % (transforms,))
        ts = [t if type(t) is Affine else _affine(t) for t in transforms]
        if len(ts) != n:
            raise StrokeError('stroke_many() got %d transforms for %d paths' % (len(ts), n))
    empty = Path.empty()
    out = [empty] * n
    if style.width == 0 or n == 0:
        return out
    m = np.array([(t.a, t.b, t.c, t.d, t.e, t.f) for t in ts], np.float64).reshape(-1, 6)
    scales = _max_scales(m)
    if not np.all(np.isfinite(scales)):
        raise LimitError('transform scale is too large (%r)'
                         % (ts[int(np.flatnonzero(~np.isfinite(scales))[0])],))
    lens = np.array([len(p.verbs) for p in paths], np.int64)
    use = np.flatnonzero((lens > 0) & (scales > 0))
    if len(use) == 0:
        return out
    # the user-space outline depends only on the path and the tolerance in
    # user units (tol / max_scale): build it once per distinct pair and map
    # it by the transform of every path that shares it
    # (dashed strokes cut to a window: translates keep outlines of their
    # own, whose dashes out of reach are left out)
    rep, inv, shift = _distinct(paths, use, scales,
                                translates=window is None or not style.dash)
    sub = [paths[i] for i in rep.tolist()]
    big = Path(np.concatenate([p.verbs for p in sub]),
               np.concatenate([p.points for p in sub]), _checked=True)
    vpath = np.repeat(np.arange(len(rep)), lens[rep])
    cpath = vpath[big.verbs == MOVE]
    tol_u = (tol / scales[rep])[cpath]
    mu = m[use]
    # device coordinates of the paths themselves, before any work
    upts = [paths[i].points for i in use.tolist()]
    vp = np.repeat(np.arange(len(use)), [len(q) for q in upts])
    with np.errstate(over='ignore', invalid='ignore'):         # checked in _check_early
        dev = apply_each(mu[vp], np.concatenate(upts))
    _check_early(dev, style.width * float(scales[use].max()))
    near = None
    if window is not None:
        # the transform of each representative drawn once (NaN: shared)
        mr = np.full((len(rep), 6), np.nan)
        alone = np.flatnonzero(np.bincount(inv, minlength=len(rep))[inv] == 1)
        mr[inv[alone]] = mu[alone]
        near = _Near(window, mr, stroke_reach(style) * scales[rep] + tol + 1.0)
    pts, rcounts, owner = _geometry(big, style, tol_u, cpath, len(rep), straddle, near)
    # polygons come out path by path
    ppath = np.repeat(owner, rcounts)
    npoly = np.bincount(owner, minlength=len(rep))
    npts = np.bincount(ppath, minlength=len(rep))
    if len(rep) < len(use):
        # gather each used path's copy of its representative's polygons,
        # moved to the path's own place (its translation from the
        # representative, in user space)
        ipath, loc = _ranges(npts[inv])
        pts = pts[_starts(npts)[inv][ipath] + loc]
        moved = (shift != 0).any(axis=1)
        if moved.any():
            sel = np.flatnonzero(moved[ipath])
            pts[sel] += shift[ipath[sel]]
    else:
        ipath = ppath
    if len(ipath) and not np.all(mu == (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)):
        pts = apply_each(mu[ipath], pts)
    _check_device(pts)
    pts = np.ascontiguousarray(pts)
    pts.flags.writeable = False
    # verbs per representative, shared (read-only) by the paths using it
    vall = _emit_verbs(rcounts)
    vcut = np.cumsum(npts + npoly).tolist()
    vrep = [vall[a:b] for a, b in zip([0] + vcut[:-1], vcut)]
    pend = np.cumsum(npts[inv]).tolist()
    for i, r, a, b in zip(use.tolist(), inv.tolist(), [0] + pend[:-1], pend):
        if b > a:
            out[i] = Path(vrep[r], pts[a:b], _checked=True)
    return out


def _max_scales(m):
    """(K,) :meth:`~raster.geometry.transform.Affine.max_scale` of transforms ``m``
    ((K, 6) float64, rows ``a b c d e f``), computed once per distinct linear
    part (bit for bit the method's value)."""
    if len(m) == 0:
        return np.zeros(0)
    if np.all(m[:, :4] == m[0, :4]):               # one linear part (common)
        return np.full(len(m), Affine(*m[0, :4].tolist()).max_scale())
    lin, inv = np.unique(m[:, :4], axis=0, return_inverse=True)
    s = np.array([Affine(*row).max_scale() for row in lin.tolist()])
    return s[inv.reshape(-1)]


def _distinct(paths, use, scales, translates=True):
    """Group the paths ``paths[use]`` by (verbs, points up to a
    translation, scale).

    Two paths fall in one group when their verbs are equal, their scales
    too, and their points relative to their first point agree after
    rounding to ``REPEAT_GRID / scale`` user units (so within
    :data:`raster.geometry.flattening.REPEAT_GRID` device pixels of being
    translates; equal paths are in one group).  Without ``translates``
    only equal paths are (their points compared as they are).

    Returns ``(rep, inv, shift)``: ``rep`` (R,) int64, the index (into
    ``paths``) of the first path of each group, in order of first
    occurrence; ``inv`` (len(use),) int64, the group of each used path;
    ``shift`` (len(use), 2) float64, each used path's first point minus
    its group's first path's (0 for equal paths).  Without repeats ``rep``
    is ``use`` and ``inv`` is ``arange(len(use))``.  A path object met
    again is recognized by identity, the others by the bytes of their
    verbs and rounded relative points."""
    used = [paths[i] for i in use.tolist()]
    lens = np.array([len(p.points) for p in used], np.int64)
    starts = np.cumsum(lens) - lens
    pts = np.concatenate([p.points for p in used])
    first_pt = pts[starts]
    if translates:
        own = np.repeat(np.arange(len(used)), lens)
        unit = (scales[use] / REPEAT_GRID)[own][:, None]
        with np.errstate(over='ignore', invalid='ignore'):   # (non-finite: refused later)
            q = np.rint((pts - first_pt[own]) * unit).astype(np.int64).tobytes()
    else:
        q = pts.tobytes()
    by_id, by_content = {}, {}
    for k, p in enumerate(used):
        if id(p) not in by_id:
            a = 16 * int(starts[k])
            key = (p.verbs.tobytes(), q[a:a + 16 * int(lens[k])])
            by_id[id(p)] = by_content.setdefault(key, len(by_content))
    group = np.array([by_id[id(p)] for p in used], np.int64)
    sc_val, sc_id = np.unique(scales[use], return_inverse=True)
    code = group * len(sc_val) + sc_id.reshape(-1)
    _, first, inv = np.unique(code, return_index=True, return_inverse=True)
    # renumber the groups by first occurrence
    order = np.argsort(first, kind='stable')
    rank = np.empty(len(order), np.int64)
    rank[order] = np.arange(len(order))
    inv = rank[inv.reshape(-1)]
    rep_local = first[order]
    shift = first_pt - first_pt[rep_local[inv]] if translates else np.zeros((len(used), 2))
    return use[rep_local], inv, shift
