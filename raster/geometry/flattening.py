"""Adaptive flattening of Bezier curves into polylines.

Two entry points:

* :func:`flatten_beziers` -- ``S`` Bezier curves of one degree ``n >= 1``
  (any dimension ``D``) to polylines, vectorized over all curves;
* :func:`flatten` -- a :class:`~raster.geometry.path.Path` (optionally transformed to
  device space) to :class:`Polylines`.

The guarantee
-------------
Every returned polyline is within ``tolerance`` of its curve in the
Hausdorff sense (both directions): every curve point is within
``tolerance`` of the polyline and every polyline point is within
``tolerance`` of the curve.  Polyline vertices lie on the curve (they are
curve points at increasing parameters; the end points are copied exactly).

How it works
------------
The curve parameter range is cut into pieces ``[a, b]``.  For a piece, its
own control points ``Q_0 .. Q_n`` are computed from the *original* control
points by blossoming (a de Casteljau scheme with ``a`` and ``b`` as
arguments: stable, no accumulated error).  The piece is accepted when a
rigorous bound on its Hausdorff distance to the chord ``Q_0 Q_n`` is
``<= tolerance``:

* for planar quadratics and cubics, exactly: the signed offset of the curve
  from the chord line and its position along the chord are Bernstein
  polynomials of degree <= 3 whose extrema come from a quadratic equation;
  the bound is ``sqrt(offset**2 + overshoot**2)``, ``overshoot`` being how
  far the curve's projection leaves the chord's ends (usually 0);
* for higher degrees (or ``D != 2``) the same with Bernstein bounds: the
  offset is at most ``(1 - 2**(1-n)) * max_i |offset(Q_i)|`` (it vanishes at
  both ends) and the projection stays within the control points' range;
* in every case at most the convex-hull bound: the largest distance of a
  control point to the chord *segment* (to the point ``Q_0`` when the chord
  has zero length).

Each bound also covers the other direction (every chord point is within
the bound of the curve): the curve joins the chord's ends, so it crosses the
perpendicular to the chord through any chord point, at a point whose
distance is an offset.

A rejected piece is cut into several pieces at once, not halved: the chord
deviation over a short parameter step ``h`` is about ``kappa h**2 / 8``
(``kappa = |B' x B''| / |B'|``), so the piece is cut where the integral of
``sqrt(kappa / (8 tolerance))`` (midpoint rule on 16 cells) passes whole
numbers, i.e. into pieces of roughly equal error just under the tolerance
(a uniform split into ``ceil(sqrt(e / tolerance))`` pieces when that
estimate is useless, e.g. along a straight line that folds back).  The new
pieces are tested again in the next round.  Rounds are a Python loop; each
round is vectorized over all pieces of all curves.  On 40 random cubics
the total piece count measured 1.05x (tolerance 0.01), 1.09x (0.25) and
1.10x (2) that of a greedy near-minimal reference on 3000 curve samples
(with the density sampled on 32 cells; 16 cells, the present choice, give
0.1-2% more pieces on 10,000 random cubics and plan 1.5-2.5x faster).

Straddled polylines
-------------------
With ``straddle=True`` (planar curves; what the renderer uses) a polyline
no longer cuts every convex bulge from inside.  Each accepted piece's
chord is moved along its normal to the middle of the piece's signed
offset range (exact for quadratics and cubics), and each interior vertex
goes where the two moved chords of its pieces meet, at most
``tolerance / 2`` from the curve point it started at (it stays on the
curve where the chords turn by more than 90 degrees: cusps, tight
loops).  The end pieces of a curve, whose outer vertex stays on the
curve, are accepted at ``tolerance / 2`` instead; :func:`flatten` also
straddles the vertex between two segments that meet with one tangent
(and then keeps the full tolerance there), while corners and the ends of
open contours stay where they are.  On a smooth curve the polyline then
deviates about ``tolerance / 2`` on both sides instead of ``tolerance``
on one side: for a circle of radius 300 px the edge error of a fill
drawn at tolerance 0.05 is 7.6/255 in alpha with 184 edges, where
vertices on the curve need tolerance 0.02 (about 290 edges) for the same.
The Hausdorff guarantee above still holds for straddled polylines, with
the measured ratio at most 0.99 of ``tolerance`` over 12,000 random
quadratics and cubics with integer coordinates, a quarter of them with
cusps (tests/geometry/test_flatten.py checks random and cusped curves);
the vertices are no longer on the curve.

Repeated contours
-----------------
Text draws the same glyph many times at one size, and markers and
symbols repeat one shape: in device space such contours are translates
of one another.  :func:`flatten_joined` (what the renderer calls) looks
for them when a call holds at least :data:`REPEAT_MIN_CONTOURS`
contours: contours with the same segments, degrees and closing whose
control points relative to their start agree on a grid of
:data:`REPEAT_GRID` (2**-20 px) are found by a hash and confirmed point
by point (:func:`repeated_contours`).  Each distinct contour is flattened
once and its polyline moved to every copy's start, so a copy's polyline
is within ``tolerance + REPEAT_GRID`` of its curve; a
:class:`ContourCache` passed to successive calls (the renderer keeps one
per render) carries the distinct contours' polylines from call to call.
A quick look at
every contour (segment count, closing, where its first and last segments
end) leaves the call as it was when most contours are unlike any other
(maps).  A page of 12 px text (7,900 glyphs, 60 lines): 0.16 -> 0.05 s
of flattening in one process.

Conventions: coordinates are float64 user units (x right, y down);
``tolerance`` is in the same units (device pixels after a transform).
Tolerances below the floating-point resolution of the coordinates
(``~1e-14`` times their magnitude) are raised to that floor, so the
subdivision always terminates.

>>> import numpy as np
>>> quad = np.array([[[0.0, 0.0], [50.0, 100.0], [100.0, 0.0]]])
>>> pts, counts = flatten_beziers(quad, tolerance=0.25)
>>> counts.tolist(), pts[0].tolist(), pts[-1].tolist()
([14], [0.0, 0.0], [100.0, 0.0])
"""

from __future__ import annotations

import math

from typing import List, Optional, Sequence, TYPE_CHECKING, Tuple, Union

import numpy as np
if TYPE_CHECKING:              # numpy.typing costs 1 ms of every start-up
    from numpy.typing import ArrayLike

from ..errors import PathError, LimitError
from .. import limits
from .bezier import bernstein, bernstein_range, blossom_pieces, derivative
from .path import CLOSE, CUBIC, LINE, MOVE, QUAD, Path, segment_arrays
from .rows import concat_ranges, pairs, put_rows, take_rows
from .transform import AffineLike, apply_each, as_affine

__all__ = ['flatten', 'flatten_many', 'flatten_joined', 'flatten_beziers', 'Polylines',
           'DEFAULT_TOLERANCE']

#: Default flattening tolerance in device pixels.
DEFAULT_TOLERANCE = 0.25

# Pieces are tested in chunks of this many to bound temporary memory (the
# test, the split plan and the blossoms of the children take some 200 bytes
# a piece: 2^14 keeps them near 3 MB; 2^16 let a 65,000-quadratic stroke
# peak at 67 instead of 37 MB, at the same speed).
_CHUNK = 1 << 14
# After this many rounds every remaining piece is accepted (never reached
# for finite input: parameter intervals shrink geometrically).
_MAX_ROUNDS = 200
# Accept a piece whose deviation is at rounding-noise level.
_NOISE = 64 * np.finfo(np.float64).eps
# Largest coordinate magnitude accepted (squares must not overflow).
_HUGE = 1e150


def _check_tolerance(tolerance):
    try:
        tol = float(tolerance)
    except (TypeError, ValueError):
        raise PathError('tolerance must be a number, got %r' % (tolerance,)) from None
    if not (tol > 0 and math.isfinite(tol)):
        raise PathError('tolerance must be a positive finite number, got %r' % (tolerance,))
    return tol


def estimate_points(ctrl, tolerance):
    """Estimated polyline points of :func:`flatten_beziers` for curves
    ``ctrl`` ((S, n+1, D) float64) at ``tolerance`` (a number, or (S,)
    one per curve): Wang's bound, the
    pieces of a uniform subdivision that is certainly within tolerance,
    ``ceil(sqrt(n (n-1) M / (8 tolerance)))`` per curve with ``M`` the
    largest second difference of its control points, plus one point per
    curve.  Adaptive subdivision needs about half as many; the estimate
    costs one pass over the control points, so a budget can refuse a
    hopeless flattening before any work (:mod:`raster.limits`).

    >>> estimate_points(np.array([[[0, 0], [50, 100], [100, 0]]], float), 0.25)
    16.0
    """
    P = np.asarray(ctrl, np.float64)
    S, n1 = P.shape[0], P.shape[1]
    n = n1 - 1
    if S == 0 or n < 2:
        return float(S * max(n, 1) + S)
    d2 = P[:, 2:] - 2.0 * P[:, 1:-1] + P[:, :-2]
    m = np.sqrt(np.einsum('sij,sij->si', d2, d2).max(axis=1))
    with np.errstate(over='ignore', invalid='ignore'):
        pieces = np.ceil(np.sqrt(m * (n * (n - 1) / 8.0) / np.asarray(tolerance, np.float64)))
    return float(np.maximum(pieces, 1.0).sum()) + S


def _deviation(Q):
    """Rigorous bound of the Hausdorff distance between Bezier pieces and
    their chord segments.

    Parameters
    ----------
    Q : (n+1, D, m) float64 ndarray
        Control points of ``m`` pieces (the point-major layout of
        :func:`~raster.geometry.bezier.blossom_pieces`).

    Returns
    -------
    (m,) float64 ndarray
        For planar quadratics and cubics whose projection stays within the
        chord the bound is the exact distance (up to rounding).
    """
    n1, D, m = Q.shape
    n = n1 - 1
    if n < 2:
        return np.zeros(m)
    if D == 2:
        return _deviation_planar(Q)
    A = Q[0]
    d = Q[n] - A                                      # (D, m) chord
    L2 = (d * d).sum(axis=0)
    nz = L2 > 0
    L2s = np.where(nz, L2, 1.0)
    L = np.sqrt(L2s)
    rel = Q[1:n] - A                                  # (n-1, D, m)
    u = (rel * d).sum(axis=1) / L2s                   # (n-1, m) chord parameter
    uc = np.clip(u, 0.0, 1.0)
    h = rel - uc[:, None] * d
    hull = np.sqrt((h * h).sum(axis=1).max(axis=0))   # convex-hull bound
    # (planar pieces went to _deviation_planar, with the exact offsets of
    # quadratics and cubics)
    p = rel - u[:, None] * d
    perp = (1.0 - 2.0 ** (1 - n)) * np.sqrt((p * p).sum(axis=1).max(axis=0))
    ulo, uhi = u.min(axis=0), u.max(axis=0)
    over = np.maximum(np.maximum(-ulo, uhi - 1.0), 0.0) * L
    e = np.minimum(np.sqrt(perp * perp + over * over), hull)
    return np.where(nz, e, hull)


def _deviation_planar(Q, shift=False):
    """:func:`_deviation` for planar pieces (D = 2), written with
    coordinate arrays and few numpy calls (the pieces are often few, so the
    cost per call matters).  Same bound, same formulas.  With ``shift``
    (quadratics and cubics only) also the (3, m) columns of
    :func:`_straddle_shift`, from the same offset range: ``(e, rows)``."""
    n1, _, m = Q.shape
    n = n1 - 1
    ax, ay = Q[0, 0], Q[0, 1]
    dx, dy = Q[n, 0] - ax, Q[n, 1] - ay              # chord
    L2 = dx * dx + dy * dy
    nz = L2 > 0
    L2s = L2 + ~nz                                    # 1 where the chord is a point
    L = np.sqrt(L2s)
    rx, ry = Q[1:n, 0] - ax, Q[1:n, 1] - ay           # (n-1, m)
    u = (rx * dx + ry * dy) / L2s                     # chord parameter
    uc = np.minimum(np.maximum(u, 0.0), 1.0)
    hx, hy = rx - uc * dx, ry - uc * dy
    hull = np.sqrt((hx * hx + hy * hy).max(axis=0))   # convex-hull bound
    if n <= 3:
        # signed offsets from the chord line; offset and chord parameter
        # are Bernstein polynomials (0, .., 0) and (0, .., 1): exact extrema
        off = (dx * ry - dy * rx) / L
        if n == 3:
            olo, ohi = _cubic_range0(off[0], off[1], 0.0)
            ulo, uhi = _cubic_range0(u[0], u[1], 1.0)
        else:
            c = np.zeros((n1, 2 * m))
            c[1:n, :m] = off
            c[1:n, m:] = u
            c[n, m:] = 1.0
            lo, hi = bernstein_range(c, normalize=False)     # |c| < 1e150: exact as is
            olo, ohi, ulo, uhi = lo[:m], hi[:m], lo[m:], hi[m:]
        perp = np.maximum(-olo, ohi)
        if shift:
            rows = np.empty((3, m))
            rows[0] = np.where(nz, 0.5 * (olo + ohi), 0.0)
            rows[1] = -dy / L
            rows[2] = dx / L
    else:
        px, py = rx - u * dx, ry - u * dy
        perp = (1.0 - 2.0 ** (1 - n)) * np.sqrt((px * px + py * py).max(axis=0))
        ulo, uhi = u.min(axis=0), u.max(axis=0)
    over = np.maximum(np.maximum(-ulo, uhi - 1.0), 0.0) * L
    e = np.minimum(np.sqrt(perp * perp + over * over), hull)
    e[~nz] = hull[~nz]
    return (e, rows) if shift else e


def _cubic_range0(c1, c2, end):
    """Minimum and maximum over [0, 1] of the cubic Bernstein polynomials
    with coefficients ``(0, c1, c2, end)`` (``c1``, ``c2``: (m,) float64
    arrays of magnitude below 1e150; ``end``: 0.0 or 1.0), as
    :func:`raster.geometry.bezier.bernstein_range` computes them with
    ``normalize=False``: the same floating-point operations on every
    value that can matter (the terms of the constant coefficients 0 and 1
    are left out, which can only turn a -0.0 into 0.0), the candidate
    parameters being the derivative's roots inside (0, 1) (the order of
    the two roots does not matter to a minimum and maximum)."""
    a = 3.0 * (c1 - c2)
    if end:
        a = end + a
    b = 2.0 * (c2 - 2.0 * c1)
    with np.errstate(all='ignore'):
        disc = b * b - 4.0 * a * c1
        sq = np.sqrt(disc)                            # NaN: no root
        q = -0.5 * (b + np.where(b >= 0, sq, -sq))
        t = np.stack([q / a, c1 / q])
    t = np.where((t > 0.0) & (t < 1.0), t, 0.0)      # (NaN, inf: an end)
    s = 1.0 - t
    v = 3.0 * s * t * (s * c1 + t * c2)
    if end:
        v += t * t * t * end
    lo = np.minimum(np.minimum(v[0], v[1]), min(0.0, end))
    hi = np.maximum(np.maximum(v[0], v[1]), max(0.0, end))
    return lo, hi


# Local parameters where the deviation density is sampled (midpoint rule)
# when planning how to split a rejected piece.
_G = 16
# Pieces planned at once by _plan_split (bounds its temporaries to ~2 MB).
_PLAN_BLOCK = 1 << 12
_SG = (np.arange(_G) + 0.5) / _G


_SAMPLE_BASES = {}


def _sample_basis(n):
    """Bernstein basis of degree ``n`` at the samples ``_SG`` (cached)."""
    B = _SAMPLE_BASES.get(n)
    if B is None:
        B = _SAMPLE_BASES[n] = bernstein(n, _SG)
    return B


def _plan_split(Q, e, tol):
    """How to cut rejected pieces: piece counts and a deviation CDF.

    Taken in blocks of ``_PLAN_BLOCK`` pieces (the pieces are independent):
    about twenty ``(_G, m)`` temporaries live at once, which for a whole
    ``_CHUNK`` of pieces was tens of megabytes.

    The deviation of a chord over a short parameter step ``h`` at ``s`` is
    about ``kappa(s) h**2 / 8`` with ``kappa = |B' x B''| / |B'|`` (the
    normal component of the second derivative), so cutting where the
    integral of ``sqrt(kappa / (8 tol))`` grows by at most 1 makes every
    piece just flat enough.  The integral is taken by the midpoint rule on
    ``_G`` cells.

    Parameters
    ----------
    Q : (n+1, D, m) float64 ndarray
        Control points of the rejected pieces (local parameter ``s``;
        transposed layout).
    e : (m,) float64 ndarray
        Their deviation bounds (``> tol``).
    tol : float

    Returns
    -------
    k : (m,) float64 ndarray
        Number of pieces to cut each into (``>= 2``, integral values).
    cdf : (m, _G + 1) float64 ndarray or None
        Normalised cumulative density at ``s = 0, 1/_G, .., 1``; rows that
        are all NaN ask for a uniform split.
    """
    m = Q.shape[2]
    if m <= _PLAN_BLOCK:
        return _plan_block(Q, e, tol)
    parts = [_plan_block(Q[:, :, i:i + _PLAN_BLOCK], e[i:i + _PLAN_BLOCK], tol)
             for i in range(0, m, _PLAN_BLOCK)]
    k = np.concatenate([p[0] for p in parts])
    if parts[0][1] is None:
        return k, None
    return k, np.concatenate([p[1] for p in parts])


def _plan_block(Q, e, tol):
    """:func:`_plan_split` of one block of pieces (same parameters)."""
    n1, D, m = Q.shape
    n = n1 - 1
    # uniform estimate: deviation falls like 1/k**2
    k_uni = np.maximum(np.ceil(np.sqrt(e / tol)), 2.0)
    if n < 2:
        return k_uni, None
    d1 = derivative(Q, axis=0)                        # (n, D, m)
    d2 = derivative(d1, axis=0)                       # (n-1, D, m)
    v = np.tensordot(_sample_basis(n - 1), d1, axes=1)   # (_G, D, m): B'
    w = np.tensordot(_sample_basis(n - 2), d2, axes=1)   # (_G, D, m): B''
    vv = (v * v).sum(axis=1)
    ww = (w * w).sum(axis=1)
    vw = (v * w).sum(axis=1)
    with np.errstate(all='ignore'):
        cross = np.sqrt(np.maximum(vv * ww - vw * vw, 0.0))
        kappa = cross / np.sqrt(vv)
        dens = np.sqrt(kappa / (8.0 * tol))
    dens = np.where(np.isfinite(dens), dens, 0.0)    # (_G, m)
    F = np.zeros((m, _G + 1))
    # (the running sums along the samples, taken on the contiguous (_G, m)
    # layout: the same additions in the same order)
    F[:, 1:] = np.cumsum(dens / _G, axis=0).T
    total = F[:, -1]
    k_den = np.ceil(total * _SAFETY)
    use = np.isfinite(total) & (total > 0) & (k_den >= 2)
    k = np.where(use, np.maximum(k_den, 2.0), k_uni)
    with np.errstate(all='ignore'):
        cdf = F / total[:, None]
    cdf[~use] = np.nan
    return k, cdf


# Margin on the estimated piece count (the density model is approximate).
_SAFETY = 1.05


def _split_points(k, cdf):
    """Local parameters of the ends of the cut pieces.

    Parameters
    ----------
    k : (m,) int64 ndarray
        Pieces per parent.
    cdf : (m, _G + 1) float64 ndarray or None

    Returns
    -------
    rep : (sum k,) int64 ndarray
        Parent of each new piece.
    s_end : (sum k,) float64 ndarray
        Local parameter in (0, 1] of each new piece's end (the last one of a
        parent is replaced by the exact parent end by the caller).
    """
    tot = int(k.sum())
    first = np.cumsum(k) - k
    rep = np.repeat(np.arange(len(k)), k)
    j = np.arange(tot) - first[rep] + 1               # 1 .. k
    frac = j / k[rep].astype(np.float64)
    s_end = frac.copy()                               # uniform split
    if cdf is not None:
        rows = np.flatnonzero(~np.isnan(cdf[:, 0]))
        if len(rows):
            # invert each piecewise-linear CDF.  The cell of target j / k is
            # the number of CDF values c with c k < j; count them by marking,
            # for every CDF value, the first target above it (O(m _G + tot),
            # and independent of the other rows)
            G1 = cdf.shape[1]
            kr = k[rows]
            f = np.floor(cdf[rows] * kr[:, None]).astype(np.int64) + 1   # (r, G1)
            ok = f <= kr[:, None]
            pos = (first[rows][:, None] + f - 1)[ok]
            cs = np.cumsum(np.bincount(pos, minlength=tot))
            before = np.concatenate([[0], cs])[first]          # count before each row
            sel = ~np.isnan(cdf[rep, 0])
            idx = np.clip(cs[sel] - before[rep[sel]], 1, G1 - 1)
            rsel = rep[sel]
            f0, f1 = cdf[rsel, idx - 1], cdf[rsel, idx]
            target = frac[sel]
            with np.errstate(all='ignore'):
                r = np.where(f1 > f0, (target - f0) / (f1 - f0), 1.0)
            s_end[sel] = np.clip((idx - 1 + np.clip(r, 0.0, 1.0)) / (G1 - 1), 0.0, 1.0)
    return rep, s_end


# Straddled end chords are accepted at this fraction of the tolerance.
_STRADDLE_END = 0.5


def _straddle_shift(Q):
    """Half the signed offset range of planar pieces from their chord lines
    and the chords' unit left normals.

    Parameters
    ----------
    Q : (n+1, 2, m) float64 ndarray
        Control points of ``m`` pieces (point-major layout).

    Returns
    -------
    (3, m) float64 ndarray
        ``d, nx, ny``: moving the chord by ``d`` along ``(nx, ny)`` puts it
        in the middle of the curve's offsets (0 for a chord of zero
        length).  Quadratics and cubics: the exact offset range; higher
        degrees: the range of the control points' offsets (it contains the
        curve's).
    """
    n1, _, m = Q.shape
    n = n1 - 1
    ax, ay = Q[0, 0], Q[0, 1]
    dx, dy = Q[n, 0] - ax, Q[n, 1] - ay
    L = np.hypot(dx, dy)
    nz = L > 0
    Ls = np.where(nz, L, 1.0)
    nx, ny = -dy / Ls, dx / Ls
    c = np.zeros((n1, m))
    c[1:n] = (Q[1:n, 0] - ax) * nx + (Q[1:n, 1] - ay) * ny
    if n <= 3:
        lo, hi = bernstein_range(c, normalize=False)
    else:
        lo, hi = c.min(axis=0), c.max(axis=0)
    d = np.where(nz, 0.5 * (lo + hi), 0.0)
    return np.stack([d, nx, ny])


def _vertex_shift(a, b, tol):
    """Displacement (k, 2) of the vertices between pieces ``a`` and ``b``
    ((3, k) columns of :func:`_straddle_shift`): the intersection of the two
    moved chord lines, ``(d_a n_a + d_b n_b) / (1 + n_a . n_b)`` (exact
    when both move alike, a blend otherwise), at most ``tol / 2`` long.
    Where the chords turn by more than 90 degrees (the tip of a cusp or
    of a tight loop) the vertex stays on the curve: the moved chords
    meet far from it there, and any blend of the two shifts can pull the
    vertex off the tip by more than the tolerance allows."""
    c = a[1] * b[1] + a[2] * b[2]
    den = np.maximum(1.0 + c, 1.0)
    v = np.stack([a[0] * a[1] + b[0] * b[1],
                  a[0] * a[2] + b[0] * b[2]], axis=1) / den[:, None]
    v[c < 0.0] = 0.0
    ln = np.hypot(v[:, 0], v[:, 1])
    cap = 0.5 * tol
    big = ln > cap
    if big.any():
        v[big] *= (cap / ln[big])[:, None]
    return v


def flatten_beziers(ctrl: ArrayLike, tolerance: float = DEFAULT_TOLERANCE,
                    straddle: bool = False) -> Tuple[np.ndarray, np.ndarray]:
    """Flatten Bezier curves of one degree into polylines.

    Parameters
    ----------
    ctrl : (S, n+1, D) array_like of float
        Control points of ``S`` Bezier curves of degree ``n >= 1`` in ``D``
        dimensions (usually 2 or 3).
    tolerance : float, optional
        Largest allowed Hausdorff distance between each curve and its
        polyline, in the units of ``ctrl`` (default 0.25).
    straddle : bool, optional
        False (default): the vertices lie on the curve (see the module
        docstring).  True (planar curves only): the interior vertices are
        moved off the curve so that the polyline straddles it instead of
        cutting every convex bulge from inside; see *Straddled polylines*
        in the module docstring for the placement and its bounds.

    Returns
    -------
    points : (N, D) float64 ndarray
        The polylines of all curves concatenated in curve order.  Curve
        ``i`` contributes ``counts[i]`` points: its start point, then the end
        of every piece in increasing parameter order (the last one is the
        curve's end point, copied exactly).
    counts : (S,) int64 ndarray
        Number of points of each curve (``>= 2``).

    Raises
    ------
    PathError
        Non-finite control points, wrong array shape, bad tolerance.
    LimitError
        More than :data:`raster.limits.MAX_FLATTEN_POINTS` points needed, or
        coordinates beyond 1e150.

    Examples
    --------
    A straight cubic needs no subdivision:

    >>> line = [[[0, 0], [1, 1], [2, 2], [3, 3]]]
    >>> pts, counts = flatten_beziers(line)
    >>> pts.tolist(), counts.tolist()
    ([[0.0, 0.0], [3.0, 3.0]], [2])

    A quarter circle (radius 100, as a cubic) at tolerance 0.25: straddled,
    the interior vertices lie outside the circle and the whole polyline
    within 0.14 of it (vertices on the curve: chords up to 0.25 inside):

    >>> k = 0.5522847498 * 100
    >>> arc = [[[100, 0], [100, k], [k, 100], [0, 100]]]
    >>> pts, counts = flatten_beziers(arc, 0.25, straddle=True)
    >>> r = np.hypot(*pts[1:-1].T)
    >>> mid = np.hypot(*((pts[1:] + pts[:-1]) / 2).T)
    >>> bool(np.all(r > 100)), bool(np.abs(np.r_[r, mid] - 100).max() < 0.14)
    (True, True)
    """
    return _flatten(ctrl, tolerance, straddle)[:2]


def _flatten(ctrl, tolerance, straddle=False, smooth=None):
    """:func:`flatten_beziers`, also returning for straddled polylines the
    shift rows (see :func:`_straddle_shift`) of each curve's first and last
    piece, (S, 2, 3) float64 (None otherwise).  ``smooth`` ((S, 2) bool or
    None) marks curve ends whose vertex the caller moves as well (the path
    goes on there with the same tangent): their end pieces need not be
    flatter."""
    tol = _check_tolerance(tolerance)
    try:
        P = np.asarray(ctrl, dtype=np.float64)
    except (TypeError, ValueError):
        raise PathError('control points must be an (S, n+1, D) array of numbers') from None
    if P.ndim != 3 or P.shape[1] < 2 or P.shape[2] < 1:
        raise PathError('control points must have shape (S, n+1, D) with n >= 1, got %r'
                        % (P.shape,))
    S, n1, D = P.shape
    if not np.all(np.isfinite(P)):
        raise PathError('control points must be finite (NaN or infinity found)')
    straddle = bool(straddle) and n1 > 2
    if straddle and D != 2:
        raise PathError('straddled polylines need planar curves (D = 2), got D = %d' % D)
    if S == 0:
        return np.zeros((0, D)), np.zeros(0, np.int64)
    n = n1 - 1
    scale = np.abs(P).reshape(S, -1).max(axis=1)
    if scale.max() > _HUGE:
        raise LimitError('control points beyond %g cannot be flattened '
                         '(squared distances would overflow)' % _HUGE)
    floor = _NOISE * scale                            # per-curve noise level
    # the work budget, before any subdivision (raster.limits)
    limits.spend_points(estimate_points(P, np.maximum(tol, floor)), 'flattening')
    max_points = limits.current().max_flatten_points

    # active pieces: curve index and parameter interval
    PT = np.ascontiguousarray(P.transpose(1, 2, 0))   # (n+1, D, S)
    cur = np.arange(S, dtype=np.int64)
    a = np.zeros(S)
    b = np.ones(S)
    acc_cur, acc_t, acc_pt, acc_sh = [], [], [], []
    n_acc = 0
    for rnd in range(_MAX_ROUNDS + 1):
        if len(cur) == 0:
            break
        new_cur, new_a, new_b = [], [], []
        n_new = 0
        for lo in range(0, len(cur), _CHUNK):
            c = cur[lo:lo + _CHUNK]
            ca, cb = a[lo:lo + _CHUNK], b[lo:lo + _CHUNK]
            # first round: the pieces are the whole curves (Q = P exactly)
            Q = PT[:, :, c] if rnd == 0 else blossom_pieces(PT[:, :, c], ca, cb)
            if straddle and n <= 3:
                # the straddle shifts come from the same offset range
                e, sh = _deviation_planar(Q, shift=True)
            else:
                e, sh = _deviation(Q), None
            lim = tol
            if straddle:
                # a curve's end stays on it, so its end chords are straddled
                # from one side only: they are made flatter (unless the
                # caller moves that end too)
                fixed = (ca == 0.0) | (cb == 1.0)
                if smooth is not None:
                    fixed = ((ca == 0.0) & ~smooth[c, 0]) | ((cb == 1.0) & ~smooth[c, 1])
                lim = np.where(fixed, tol * _STRADDLE_END, tol)
            ok = (e <= np.maximum(lim, floor[c])) | (rnd == _MAX_ROUNDS)
            if np.any(ok):
                acc_cur.append(c[ok])
                acc_t.append(cb[ok])
                acc_pt.append(Q[n][:, ok])
                if straddle:
                    acc_sh.append(_straddle_shift(Q[:, :, ok]) if sh is None else sh[:, ok])
                n_acc += int(ok.sum())
            bad = ~ok
            if not np.any(bad):
                continue
            # (planned for the plain tolerance: a piece's children are
            # shorter and may be allowed less than the piece)
            kf, cdf = _plan_split(Q[:, :, bad], e[bad], tol)
            total = float(kf.sum())
            if n_acc + n_new + len(cur) - lo + total + S > max_points:
                raise LimitError('flattening would produce more than %d points '
                                 '(max_flatten_points; tolerance %g too small?)'
                                 % (max_points, tol))
            k = kf.astype(np.int64)
            ba, bb = ca[bad], cb[bad]
            rep, s_end = _split_points(k, cdf)
            last = np.zeros(len(rep), bool)
            last[np.cumsum(k) - 1] = True
            h = (bb - ba)[rep]
            t1 = np.where(last, bb[rep], ba[rep] + h * s_end)
            t0 = np.empty_like(t1)
            t0[1:] = t1[:-1]
            t0[np.cumsum(k) - k] = ba
            tot = len(rep)
            new_cur.append(c[bad][rep])
            new_a.append(t0)
            new_b.append(t1)
            n_new += tot
        if new_cur:
            cur = np.concatenate(new_cur)
            a = np.concatenate(new_a)
            b = np.concatenate(new_b)
        else:
            cur = cur[:0]

    if n_acc == S and not straddle:
        # nothing was split: each curve is its chord
        out = np.empty((S, 2, D))
        out[:, 0] = P[:, 0]
        out[:, 1] = P[:, n]
        return out.reshape(2 * S, D), np.full(S, 2, np.int64), None
    ac = np.concatenate(acc_cur)
    at = np.concatenate(acc_t)
    del acc_cur, acc_t          # (each stage's arrays are freed once used)
    # every round appends runs already in (curve, t) order; a stable sort of
    # the complex key curve + i t (lexicographic) merges them quickly
    order = np.argsort(ac.astype(np.float64) + 1j * at, kind='stable')
    del at
    ac = ac[order]
    # (piece ends and shifts are kept as coordinate rows, (D, pieces) and
    # (3, pieces): gathered a row at a time, which is much faster than
    # fancy indexing of (pieces, D) arrays; planar points move as complex128)
    apT = np.concatenate(acc_pt, axis=1)[:, order]    # (D, pieces)
    del acc_pt
    per = np.bincount(ac, minlength=S).astype(np.int64)
    counts = per + 1
    off = np.cumsum(counts) - counts                  # start of each curve
    out = np.empty((int(counts.sum()), D))
    out[off] = P[:, 0]
    rank = np.arange(len(ac)) - (np.cumsum(per) - per)[ac]
    dest = off[ac] + 1 + rank
    if D != 2:
        out[dest] = apT.T
        return out, counts, None
    ap = np.empty((len(ac), 2))
    ap[:, 0] = apT[0]
    ap[:, 1] = apT[1]
    del apT
    apc = pairs(ap)
    ends = None
    if straddle:
        sh = np.concatenate(acc_sh, axis=1)[:, order]     # (3, pieces): shift, normal
        del acc_sh, order
        inner = np.flatnonzero(rank < per[ac] - 1)    # piece ends inside the curve
        for lo in range(0, len(inner), _CHUNK):      # (bounded temporaries)
            i = inner[lo:lo + _CHUNK]
            apc[i] += pairs(_vertex_shift(sh[:, i], sh[:, i + 1], tol))
        del inner
        pfirst = np.cumsum(per) - per
        ends = np.empty((S, 2, 3))
        ends[:, 0] = sh[:, pfirst].T
        ends[:, 1] = sh[:, pfirst + per - 1].T
    pairs(out)[dest] = apc
    return out, counts, ends


class Polylines:
    """Polylines made by :func:`flatten`: one per kept contour.

    Attributes
    ----------
    points : (N, 2) float64 ndarray
        All vertices, polyline after polyline.
    starts : (K,) int64 ndarray
        Index into ``points`` of each polyline's first vertex (increasing).
    closed : (K,) bool ndarray
        Whether the contour was closed (``Z``).

    ``len(polylines)`` is ``K``; iterating yields ``(points_k, closed_k)``
    pairs, ``points_k`` being an ``(N_k, 2)`` view.  A closed polyline does
    not repeat its first vertex at the end unless the path itself returned
    there explicitly.

    >>> pl = Polylines([[0, 0], [1, 0], [1, 1], [5, 5]], [0, 3], [True, False])
    >>> len(pl), [(p.shape, c) for p, c in pl]
    (2, [((3, 2), True), ((1, 2), False)])
    >>> pl.edges().shape
    (3, 2, 2)
    """

    __slots__ = ('points', 'starts', 'closed')

    def __init__(self, points: ArrayLike, starts: ArrayLike, closed: ArrayLike) -> None:
        self.points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        self.starts = np.asarray(starts, dtype=np.int64).reshape(-1)
        self.closed = np.asarray(closed, dtype=bool).reshape(-1)
        if len(self.starts) != len(self.closed):
            raise PathError('starts and closed must have the same length')

    @property
    def ends(self) -> np.ndarray:
        """(K,) int64: one past the last vertex index of each polyline."""
        return np.append(self.starts[1:], len(self.points)).astype(np.int64)

    @property
    def sizes(self) -> np.ndarray:
        """(K,) int64: number of vertices of each polyline."""
        return self.ends - self.starts

    def __len__(self):
        return len(self.starts)

    def __getitem__(self, k):
        s, e = int(self.starts[k]), int(self.ends[k])
        return self.points[s:e], bool(self.closed[k])

    def __iter__(self):
        ends = self.ends
        for s, e, c in zip(self.starts.tolist(), ends.tolist(), self.closed.tolist()):
            yield self.points[s:e], c

    def __repr__(self):
        return 'Polylines(%d polylines, %d points)' % (len(self), len(self.points))

    def take(self, idx: ArrayLike) -> 'Polylines':
        """The polylines ``idx`` ((M,) int array, in the order given) as a
        new :class:`Polylines`.

        >>> pl = Polylines([[0, 0], [1, 0], [5, 5], [6, 5], [7, 7]], [0, 2, 4], [True, False, True])
        >>> sub = pl.take([2, 0])
        >>> sub.points.tolist(), sub.starts.tolist(), sub.closed.tolist()
        ([[7.0, 7.0], [0.0, 0.0], [1.0, 0.0]], [0, 1], [True, True])
        """
        idx = np.asarray(idx, np.int64).reshape(-1)
        sizes = self.sizes[idx]
        starts = np.cumsum(sizes) - sizes
        src = np.repeat(self.starts[idx] - starts, sizes) + np.arange(int(sizes.sum()))
        return Polylines(take_rows(self.points, src), starts, self.closed[idx])

    def to_path(self) -> Path:
        """The polylines as a :class:`~raster.geometry.path.Path` of line segments
        (``M L .. L`` plus ``Z`` for the closed ones).

        >>> Polylines([[0, 0], [1, 0], [1, 1]], [0], [True]).to_path().to_svg()
        'M 0 0 L 1 0 L 1 1 Z'
        """
        K, N = len(self.starts), len(self.points)
        if K == 0:
            return Path.empty()
        # verb slot of vertex i: i + number of closes of earlier polylines
        ncl = np.cumsum(self.closed) - self.closed
        verbs = np.full(N + int(self.closed.sum()), LINE, np.uint8)
        verbs[self.starts + ncl] = MOVE
        verbs[(self.ends + ncl)[self.closed]] = CLOSE
        return Path(verbs, self.points.copy(), _checked=True)

    def edges(self, close_all: bool = True,
              owners: bool = False) -> Union[np.ndarray, Tuple[np.ndarray, np.ndarray]]:
        """Line segments of all polylines.

        Parameters
        ----------
        close_all : bool, optional
            Add the closing edge (last vertex to first) of every polyline, as
            a fill needs (default); with False only of the closed ones.
        owners : bool, optional
            Also return the index of the polyline of every edge.

        Returns
        -------
        edges : (E, 2, 2) float64 ndarray
            ``edges[e] = [[x0, y0], [x1, y1]]``, in polyline order, each
            polyline's edges in order followed by its closing edge.  Closing
            edges of zero length (the polyline already ends at its start,
            or has a single vertex) are left out.
        owner : (E,) int64 ndarray
            Only with ``owners``: the polyline of each edge (increasing).
        """
        P = self.points
        if len(P) == 0:
            return (np.zeros((0, 2, 2)), np.zeros(0, np.int64)) if owners else np.zeros((0, 2, 2))
        starts, ends = self.starts, self.ends
        sizes = ends - starts
        live = sizes > 0
        s, last = starts[live], ends[live] - 1
        want = np.ones(len(starts), bool) if close_all else self.closed.copy()
        want &= live
        want[live] &= np.any(P[s] != P[last], axis=1)      # zero length: left out
        ne = np.where(live, sizes - 1 + want, 0)            # edges per polyline
        nedge = int(ne.sum())
        # vertex i starts the edge to the next vertex, or at a polyline's
        # last vertex the closing edge to its first (if wanted).  Points
        # move as complex128 (one element per point); the temporaries are
        # one point array and one flag per vertex
        Pc = pairs(np.ascontiguousarray(P))
        nxt = np.empty_like(Pc)
        nxt[:-1] = Pc[1:]
        nxt[last] = Pc[s]
        oc = np.empty((nedge, 2), np.complex128)
        if nedge == len(P):                                 # every vertex starts an edge
            oc[:, 0] = Pc
            oc[:, 1] = nxt
        else:
            opens = np.ones(len(P), bool)
            opens[last] = want[live]
            np.compress(opens, Pc, out=oc[:, 0])
            np.compress(opens, nxt, out=oc[:, 1])
        del nxt
        out = oc.view(np.float64).reshape(nedge, 2, 2)
        if owners:
            return out, np.repeat(np.arange(len(starts)), ne)
        return out


def flatten(path: Path, tolerance: float = DEFAULT_TOLERANCE,
            transform: AffineLike = None, straddle: bool = False) -> Polylines:
    """Flatten a path into polylines.

    Parameters
    ----------
    path : raster.geometry.path.Path
    tolerance : float, optional
        Largest Hausdorff distance between each curve and its polyline, in
        device pixels (the units after ``transform``); default 0.25.
    transform : raster.geometry.transform.Affine or None, optional
        Applied to the control points first (user to device space).
    straddle : bool, optional
        False (default): every vertex lies on the path.  True: the polylines
        straddle the curves (see *Straddled polylines* in the module
        docstring): vertices inside a curve, and where two segments meet
        with one tangent, move off the path by up to ``tolerance / 2``;
        corners and the ends of open contours stay.

    Returns
    -------
    Polylines
        One polyline per contour: the contour's start point, then the
        points of its segments in order (each segment's start is not
        repeated).  Contours made of a lone move followed by a close
        (``M x y Z``) give a 1-point closed polyline, kept because strokes
        draw caps for them; a lone move without close (``M x y``) draws
        nothing and is dropped.

    Raises
    ------
    PathError
        Not a path, bad tolerance, or coordinates that become non-finite
        after the transform.
    TransformError
        A transform that cannot be interpreted.
    LimitError
        More than :data:`raster.limits.MAX_FLATTEN_POINTS` points needed.

    Examples
    --------
    >>> from raster.geometry.path import Path
    >>> pl = flatten(Path.polygon([[0, 0], [4, 0], [4, 3]]), transform=(2, 0, 0, 2, 0, 0))
    >>> pl.points.tolist(), pl.starts.tolist(), pl.closed.tolist()
    ([[0.0, 0.0], [8.0, 0.0], [8.0, 6.0]], [0], [True])
    """
    tol = _check_tolerance(tolerance)
    if not callable(getattr(path, 'segments', None)):
        raise PathError('flatten needs a raster.Path, got %s' % type(path).__name__)
    seg = path.segments()
    t = as_affine(transform)
    ctrl = seg.ctrl
    cstart = seg.contour_start
    if not t.is_identity:
        with np.errstate(over='ignore', invalid='ignore'):     # checked just below
            ctrl = t.apply(ctrl)
            cstart = t.apply(cstart)
        if not (np.all(np.isfinite(ctrl)) and np.all(np.isfinite(cstart))):
            raise PathError('transformed path has non-finite coordinates')
    out, starts, keep_c, _ = _assemble(ctrl, cstart, seg.degree, seg.contour,
                                       seg.contour_nseg, seg.contour_closed, tol, straddle)
    return Polylines(out, starts, seg.contour_closed[keep_c])


def _assemble(ctrl, cstart, degree, contour, contour_nseg, contour_closed, tol, straddle=False):
    """Flatten segment arrays (device space) and lay out the polyline
    vertices: returns ``(points, starts, keep_c, item_n)``; ``keep_c`` marks
    the contours kept, ``item_n`` the vertex count of each item (contour
    start or segment, in path order).  With ``straddle`` the curves are
    straddled, and so are the vertices where two segments meet with one
    tangent (see :func:`_smooth_joints`)."""
    seg_contour = contour
    S = len(ctrl)
    C = len(cstart)
    if S:
        # device coordinates (raster.limits.max_coord), before any work
        limits.check_coord(max(float(np.abs(ctrl).max()), float(np.abs(cstart).max())))
    deg = degree.astype(np.int64)
    joint = nxt = None
    smooth = np.zeros((S, 2), bool)
    if straddle and S:
        joint, nxt = _smooth_joints(ctrl, deg, contour, contour_nseg, cstart)
        smooth[:, 1] = joint
        smooth[nxt[joint], 0] = True
    # points each segment contributes (its start excluded)
    seg_n = np.ones(S, np.int64)
    seg_pts = [None] * 4
    rows = np.zeros((S, 2, 3)) if straddle else None
    for d in (2, 3):
        idx = np.flatnonzero(deg == d)
        if len(idx):
            pts, counts, ends = _flatten(ctrl[idx, :d + 1], tol, straddle, smooth[idx])
            keep = np.ones(len(pts), bool)
            keep[np.cumsum(counts) - counts] = False
            seg_n[idx] = counts - 1
            seg_pts[d] = (idx, take_rows(pts, keep), counts - 1)
            if straddle:
                rows[idx] = ends
    keep_c = (contour_nseg > 0) | contour_closed
    # item order: contour start j, then its segments; item index of start j
    # is j + (segments before contour j), of segment s is contour[s] + 1 + s
    nseg_before = np.cumsum(contour_nseg) - contour_nseg
    item_n = np.zeros(C + S, np.int64)
    start_item = np.arange(C) + nseg_before
    seg_item = seg_contour + 1 + np.arange(S)
    item_n[start_item] = keep_c
    item_n[seg_item] = seg_n
    item_off = np.cumsum(item_n) - item_n
    total = int(item_n.sum())
    limits.check_points(total, 'flattening')
    # (rows of points move as complex128: see raster.geometry.rows)
    out = np.empty((total, 2))
    starts = item_off[start_item][keep_c]
    put_rows(out, starts, take_rows(np.ascontiguousarray(cstart), keep_c))
    lines = np.flatnonzero(deg == 1)
    cc = pairs(ctrl)
    put_rows(out, item_off[seg_item[lines]],
             ctrl[lines, 1] if cc is None else cc[lines, 1].view(np.float64).reshape(-1, 2))
    for d in (2, 3):
        if seg_pts[d] is not None:
            idx, pts, cnt = seg_pts[d]
            base = np.repeat(item_off[seg_item[idx]], cnt)
            within = np.arange(len(pts)) - np.repeat(np.cumsum(cnt) - cnt, cnt)
            put_rows(out, base + within, pts)
    if joint is not None and joint.any():
        # lines: no offset, their own normal
        dl = ctrl[lines, 1] - ctrl[lines, 0]
        ll = np.hypot(dl[:, 0], dl[:, 1])
        ll[ll == 0] = 1.0
        rows[lines, :, 1] = (-dl[:, 1] / ll)[:, None]
        rows[lines, :, 2] = (dl[:, 0] / ll)[:, None]
        js = np.flatnonzero(joint)
        v = _vertex_shift(rows[js, 1].T, rows[nxt[js], 0].T, tol)
        endv = item_off[seg_item[js]] + seg_n[js] - 1         # vertex ending segment js
        out[endv] += v
        # a joint at a contour's start: the contour's first vertex too
        wrap = nxt[js] < js
        out[item_off[start_item[contour[js[wrap]]]]] += v[wrap]
    return out, starts, keep_c, item_n


def _smooth_joints(ctrl, deg, contour, contour_nseg, cstart):
    """Where consecutive segments of a contour meet: ``(joint, next)``,
    ``joint[s]`` True when segment ``s`` goes on into segment ``next[s]``
    (the following one, or the contour's first when ``s`` ends the contour
    exactly at its start) and both have a tangent there.  Such a vertex is
    straddled like those inside a curve (two lines leave it in place; a
    corner moves by at most half the tolerance)."""
    S = len(ctrl)
    ar = np.arange(S)
    # a tangent exists at an end unless all control points sit on it
    t0 = np.any(ctrl[:, 1:] != ctrl[:, :1], axis=(1, 2))
    t1 = np.any(ctrl[:, :3] != ctrl[:, 3:4], axis=(1, 2))
    nxt = ar + 1
    first = np.cumsum(contour_nseg) - contour_nseg
    last_of = first + contour_nseg - 1
    is_last = ar == last_of[contour]
    nxt[is_last] = first[contour[is_last]]
    closes = is_last & np.all(ctrl[:, 3] == cstart[contour], axis=1)
    ok = (~is_last | closes) & t1
    nn = np.where(ok, nxt, 0)
    ok &= t0[nn] & (nn != ar)
    return ok, nxt


def flatten_joined(paths: Sequence[Path], transforms: Optional[Sequence[AffineLike]] = None,
                   tolerance: float = DEFAULT_TOLERANCE,
                   straddle: bool = False,
                   cache: Optional['ContourCache'] = None) -> Tuple[Polylines, np.ndarray]:
    """Flatten many paths at once into one :class:`Polylines`.

    The verbs and points of all paths are read as one array (every path
    starts with a move, so no contour spans two paths), transformed with
    each path's transform and flattened with one :func:`flatten_beziers`
    call per degree: no per-path work beyond gathering the arrays.

    Parameters
    ----------
    paths : sequence of raster.geometry.path.Path
    transforms : sequence of Affine (or None entries), or None, optional
        One transform per path (user to device space); None: identity.
    tolerance, straddle : optional
        As for :func:`flatten` (device pixels, default 0.25; on the path).
    cache : ContourCache or None, optional
        Distinct contours flattened by earlier calls, taken from it and
        added to it (see *Repeated contours* above).

    Returns
    -------
    polylines : Polylines
        The polylines of all paths, path after path.
    first : (n + 1,) int64 ndarray
        Path ``i`` owns polylines ``first[i]:first[i + 1]``, those of
        ``flatten(paths[i], tolerance, transforms[i], straddle)``: the
        same, or, for a contour that repeats an earlier one of the call up
        to a translation (see *Repeated contours* above), the earlier one's
        moved to its start, within :data:`REPEAT_GRID` of them.

    Raises
    ------
    As :func:`flatten_many`.

    >>> from raster.geometry.path import Path
    >>> sq = Path.polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    >>> pl, first = flatten_joined([sq, Path.empty(), sq], [None, None, (2, 0, 0, 2, 5, 0)])
    >>> first.tolist(), pl.starts.tolist(), pl.points[4:].tolist()
    ([0, 1, 1, 2], [0, 4], [[5.0, 0.0], [7.0, 0.0], [7.0, 2.0], [5.0, 2.0]])
    """
    tol = _check_tolerance(tolerance)
    paths = list(paths)
    n = len(paths)
    if transforms is None:
        transforms = [None] * n
    transforms = list(transforms)
    if len(transforms) != n:
        raise PathError('flatten_many needs one transform per path (%d paths, %d transforms)'
                        % (n, len(transforms)))
    for p in paths:
        if not (hasattr(p, 'verbs') and callable(getattr(p, 'segments', None))):
            raise PathError('flatten_many needs raster.Path objects, got %s'
                            % type(p).__name__)
    if n == 0:
        return Polylines(np.zeros((0, 2)), [], []), np.zeros(1, np.int64)
    nverb = np.array([len(p.verbs) for p in paths], np.int64)
    if nverb.sum() == 0:
        return Polylines(np.zeros((0, 2)), [], []), np.zeros(n + 1, np.int64)
    verbs = np.concatenate([p.verbs for p in paths])
    points = np.concatenate([p.points for p in paths])
    aff = [as_affine(t) for t in transforms]
    ident = np.array([a.is_identity for a in aff], bool)
    if _lines_only(verbs):
        return _joined_lines(verbs, points, nverb, aff, ident)
    seg = segment_arrays(verbs, points)
    ctrl, cstart = seg.ctrl, seg.contour_start
    nc = np.bincount(np.repeat(np.arange(n), nverb)[verbs == MOVE], minlength=n)
    if not ident.all():
        M = np.array([tuple(a) for a in aff], np.float64)          # (n, 6)
        c_path = np.repeat(np.arange(n), nc)                       # path of each contour
        ctrl = _transform_owned(ctrl, c_path[seg.contour], M, ident)
        cstart = _transform_owned(cstart, c_path, M, ident)
        if not (np.all(np.isfinite(ctrl)) and np.all(np.isfinite(cstart))):
            raise PathError('transformed path has non-finite coordinates')
    out, starts, keep_c = _assemble_repeated(ctrl, cstart, seg.degree, seg.contour,
                                             seg.contour_nseg, seg.contour_closed, tol,
                                             straddle, cache)
    per_path = np.bincount(np.repeat(np.arange(n), nc), weights=keep_c,
                           minlength=n).astype(np.int64)
    first = np.concatenate([[0], np.cumsum(per_path)])
    return Polylines(out, starts, seg.contour_closed[keep_c]), first


#: Fewest contours in one call worth looking for repeated ones.
REPEAT_MIN_CONTOURS = 64
#: Contours equal up to a translation when their control points relative
#: to their start agree on this grid (device pixels): 2**-20, about 1e-6.
REPEAT_GRID = 2.0 ** -20
#: Share the work only where the distinct contours are at most this
#: fraction of all.
_REPEAT_SHARE = 0.5


def _mix64(x):
    """A 64-bit integer mixing step (splitmix64's finalizer), in place on
    a uint64 array: nearby inputs give unrelated outputs."""
    x ^= x >> np.uint64(30)
    x *= np.uint64(0xBF58476D1CE4E5B9)
    x ^= x >> np.uint64(27)
    x *= np.uint64(0x94D049BB133111EB)
    x ^= x >> np.uint64(31)
    return x


def repeated_contours(ctrl, cstart, degree, contour, contour_nseg, contour_closed,
                      grid=REPEAT_GRID):
    """For each contour, an earlier (or the same) contour it repeats up to
    a translation.

    Two contours repeat each other when they have the same segments, of
    the same degrees, in the same order, closed alike, and every control
    point relative to the contour's start agrees after rounding to
    ``grid``: the two are then within ``grid`` of being translates.  Text
    (the same glyph many times at one size), markers and symbols drawn
    many times are made of such contours.

    Parameters
    ----------
    ctrl : (S, 4, 2) float64 ndarray
        Segments' control points (unused slots repeat the end point).
    cstart : (C, 2) float64 ndarray
        Contour start points.
    degree, contour : (S,) ndarray
        Degree and contour of each segment (contours' segments are
        consecutive, in contour order).
    contour_nseg : (C,) int64 ndarray
    contour_closed : (C,) bool ndarray
    grid : float, optional

    Returns
    -------
    (C,) int64 ndarray
        ``rep[c] <= c``, with ``rep[rep[c]] == rep[c]``: the first contour
        of those ``c`` repeats (``c`` itself when none before it).
    """
    return _repeats(*_contour_keys(ctrl, cstart, degree, contour, contour_nseg,
                                   contour_closed, grid), degree, contour_nseg, contour_closed)


def _contour_keys(ctrl, cstart, degree, contour, contour_nseg, contour_closed, grid):
    """``(key, q)``: a 64-bit hash of each contour ((C,) uint64) and the
    rounded control points relative to each segment's contour start
    ((S, 8) int64, in units of ``grid``).  Equal contours (as
    :func:`repeated_contours` reads them) have equal keys."""
    C, S = len(cstart), len(ctrl)
    with np.errstate(over='ignore', invalid='ignore'):
        q = np.rint((ctrl - cstart[contour][:, None, :]) * (1.0 / grid)).astype(np.int64)
    q = q.reshape(S, 8)
    # a hash of each segment (its points, degree and place in its contour),
    # summed over the contour (wrapping uint64 arithmetic)
    first_seg = np.cumsum(contour_nseg) - contour_nseg
    place = np.arange(S) - first_seg[contour]
    h = (degree.astype(np.uint64) + (place.astype(np.uint64) << np.uint64(2)))
    h = _mix64(h)
    with np.errstate(over='ignore'):
        for j in range(8):
            h += q[:, j].view(np.uint64) * np.uint64(
                (0x9E3779B97F4A7C15 ^ (j * 0x632BE59BD9B4E019)) & 0xFFFFFFFFFFFFFFFF)
            h = _mix64(h)
    key = np.zeros(C, np.uint64)
    has = contour_nseg > 0
    with np.errstate(over='ignore'):
        if S:
            key[has] = np.add.reduceat(h, first_seg[has])
        key += contour_nseg.astype(np.uint64) * np.uint64(0xD6E8FEB86659FD93)
        key += contour_closed.astype(np.uint64)
    return _mix64(key), q


def _repeats(key, q, degree, contour_nseg, contour_closed):
    """:func:`repeated_contours` from the contours' keys and rounded points
    (:func:`_contour_keys`): the first contour of each key, confirmed
    point by point (a contour that differs from it stands for itself)."""
    C = len(key)
    _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    rep = first[inverse.reshape(-1)]
    # confirm: same count, closing and degrees, the same rounded points
    other = np.flatnonzero(rep != np.arange(C))
    if len(other):
        first_seg = np.cumsum(contour_nseg) - contour_nseg
        r = rep[other]
        bad = (contour_nseg[other] != contour_nseg[r]) | (contour_closed[other] != contour_closed[r])
        n_o = np.where(bad, 0, contour_nseg[other])
        own = concat_ranges(first_seg[other], n_o)
        theirs = own - np.repeat(first_seg[other] - first_seg[r], n_o)
        differ = (q[own] != q[theirs]).any(axis=1) | (degree[own] != degree[theirs])
        if differ.any():
            bad[np.repeat(np.arange(len(other)), n_o)[differ]] = True
        rep[other[bad]] = other[bad]
    return rep


class ContourCache:
    """Polylines of distinct contours kept across :func:`flatten_joined`
    calls (the renderer keeps one per render: a page of text flattens
    each glyph once, not once per batch).

    An entry is a contour's polyline relative to its start, found by the
    contour's key (tolerance, straddling, hash of :func:`_contour_keys`)
    and taken only when the contour's rounded points, degrees and closing
    (the proof, stored with it) are the same.  At most ``max_bytes`` of
    polylines and proofs are held (default 4 MB); beyond, the cache starts
    afresh.
    """

    def __init__(self, max_bytes=1 << 22):
        self.max_bytes = int(max_bytes)
        self._entries = {}
        self._bytes = 0

    def __len__(self):
        return len(self._entries)

    def get(self, key, proof):
        """``(polyline relative to the start (k, 2), kept)`` or None."""
        e = self._entries.get(key)
        return e[1:] if e is not None and e[0] == proof else None

    def put(self, key, proof, rel, kept):
        size = rel.nbytes + len(proof)
        old = self._entries.pop(key, None)
        if old is not None:
            self._bytes -= old[1].nbytes + len(old[0])
        if self._bytes + size > self.max_bytes:
            self._entries.clear()
            self._bytes = 0
        if size <= self.max_bytes:
            self._entries[key] = (proof, rel, kept)
            self._bytes += size


def _assemble_repeated(ctrl, cstart, degree, contour, contour_nseg, contour_closed, tol,
                       straddle=False, cache=None):
    """:func:`_assemble` (its first three results), each contour that
    repeats an earlier one (:func:`repeated_contours`), or one of
    ``cache`` (a :class:`ContourCache`), flattened once and moved: its
    polyline is the earlier one's translated to its start point, so
    within ``tol`` plus :data:`REPEAT_GRID` of its curve (rounding aside,
    the polyline flattening it would give)."""
    C = len(cstart)
    if C < REPEAT_MIN_CONTOURS:
        return _assemble(ctrl, cstart, degree, contour, contour_nseg, contour_closed, tol,
                         straddle)[:3]
    # a quick look first (segment count, closing, the first and last
    # segments' ends): contours alone in their look repeat nothing
    first_seg = np.cumsum(contour_nseg) - contour_nseg
    has = contour_nseg > 0
    look = contour_nseg.astype(np.uint64) * np.uint64(0xD6E8FEB86659FD93)
    look += contour_closed.astype(np.uint64)
    for end in (first_seg[has], first_seg[has] + contour_nseg[has] - 1):
        with np.errstate(over='ignore', invalid='ignore'):     # (coordinates: checked below)
            q = np.rint((ctrl[end, 3] - cstart[has]) * (1.0 / REPEAT_GRID)).astype(np.int64)
            look[has] = _mix64(look[has] + q[:, 0].view(np.uint64))
            look[has] = _mix64(look[has] + q[:, 1].view(np.uint64))
    _, inverse, count = np.unique(look, return_inverse=True, return_counts=True)
    if np.count_nonzero(count[inverse.reshape(-1)] == 1) > _REPEAT_SHARE * C:
        return _assemble(ctrl, cstart, degree, contour, contour_nseg, contour_closed, tol,
                         straddle)[:3]
    if len(ctrl):
        # (the limit applies to all of them, as without sharing)
        limits.check_coord(max(float(np.abs(ctrl).max()), float(np.abs(cstart).max())))
    key, q = _contour_keys(ctrl, cstart, degree, contour, contour_nseg, contour_closed,
                           REPEAT_GRID)
    rep = _repeats(key, q, degree, contour_nseg, contour_closed)
    reps = np.flatnonzero(rep == np.arange(C))
    if len(reps) > _REPEAT_SHARE * C:
        return _assemble(ctrl, cstart, degree, contour, contour_nseg, contour_closed, tol,
                         straddle)[:3]
    slot = np.zeros(C, np.int64)
    slot[reps] = np.arange(len(reps))
    # the polyline of each distinct contour: from the cache, or flattened
    # now (the distinct contours alone, renumbered)
    rel, kept, entries, fresh = [None] * len(reps), [False] * len(reps), [], reps
    if cache is not None:
        fs, ns, cl = first_seg.tolist(), contour_nseg.tolist(), contour_closed.tolist()
        for r in reps.tolist():
            a, b = fs[r], fs[r] + ns[r]
            entries.append(((tol, bool(straddle), int(key[r])),
                            q[a:b].tobytes() + degree[a:b].tobytes() + (b'z' if cl[r] else b'o')))
        miss = []
        for j, (k, proof) in enumerate(entries):
            hit = cache.get(k, proof)
            if hit is None:
                miss.append(j)
            else:
                rel[j], kept[j] = hit
        fresh = reps[miss]
    if len(fresh):
        nr = contour_nseg[fresh]
        segs = concat_ranges(first_seg[fresh], nr)
        out_f, starts_f, keep_f, _ = _assemble(ctrl[segs], cstart[fresh], degree[segs],
                                               np.repeat(np.arange(len(fresh)), nr), nr,
                                               contour_closed[fresh], tol, straddle)
        ends_f = np.append(starts_f[1:], len(out_f))
        kf = np.flatnonzero(keep_f)
        where = dict(zip(kf.tolist(), range(len(kf))))
        fresh_slot = slot[fresh].tolist()
        for i, j in enumerate(fresh_slot):
            if i in where:
                w = where[i]
                rel[j] = out_f[starts_f[w]:ends_f[w]] - cstart[fresh[i]]
                kept[j] = True
            else:
                rel[j] = np.zeros((0, 2))
            if cache is not None:
                cache.put(entries[j][0], entries[j][1], rel[j], kept[j])
    keep_r = np.array(kept, bool)
    length = np.array([len(x) for x in rel], np.int64)
    out_r = np.concatenate(rel) if len(rel) else np.zeros((0, 2))
    start_of = np.cumsum(length) - length
    # each contour: its distinct contour's polyline, moved to its start
    k = slot[rep]                                   # distinct contour of each contour
    keep_c = keep_r[k]
    kc = np.flatnonzero(keep_c)
    L = length[k[kc]]
    total = int(L.sum())
    limits.check_points(total, 'flattening')
    starts = np.cumsum(L) - L
    idx = np.repeat(start_of[k[kc]], L) + (np.arange(total) - np.repeat(starts, L))
    out = take_rows(out_r, idx)
    out += np.repeat(cstart[kc], L, axis=0)
    return out, starts, keep_c


def _transform_owned(pts, owner, M, ident):
    """``pts`` (any shape ``(k, ..., 2)``) with row ``i`` mapped by the
    transform ``M[owner[i]]`` (rows ``a b c d e f``) with the arithmetic of
    :meth:`Affine.apply`; rows of identity transforms are copied as they
    are.  Overflow is left for the caller to check (non-finite values)."""
    out = pts.copy()
    move = np.flatnonzero(~ident[owner])
    with np.errstate(over='ignore', invalid='ignore'):
        out[move] = apply_each(M[owner[move]], pts[move])
    return out


def _lines_only(verbs):
    """True when ``verbs`` (concatenated paths) hold no curve and every
    close is followed by a move (or ends them): each contour's polyline is
    then its own points."""
    if np.any((verbs == QUAD) | (verbs == CUBIC)):
        return False
    cl = np.flatnonzero(verbs[:-1] == CLOSE)
    return bool(np.all(verbs[cl + 1] == MOVE))


def _joined_lines(verbs, points, nverb, aff, ident):
    """:func:`flatten_joined` of paths of lines only (see :func:`_lines_only`):
    the points themselves, transformed with the arithmetic of the general
    case, in contours that have a segment or are closed; the same
    polylines as the general case without building segments.  Straddling
    moves no vertex where two lines meet (their shift is zero; the
    general case adds that zero, which can turn a coordinate of -0.0 into
    0.0: the only difference)."""
    n = len(nverb)
    mv = verbs == MOVE
    contour = np.cumsum(mv) - 1
    C = int(contour[-1]) + 1
    line = verbs == LINE
    nline = np.bincount(contour[line], minlength=C)
    closed = np.zeros(C, bool)
    closed[contour[verbs == CLOSE]] = True
    c_path = np.repeat(np.arange(n), nverb)[mv]                    # path of each contour
    pts = points
    if not ident.all():
        M = np.array([tuple(a) for a in aff], np.float64)
        # (each point owned by its contour's path)
        pts = _transform_owned(points, np.repeat(c_path, nline + 1), M, ident)
        if not np.all(np.isfinite(pts)):
            raise PathError('transformed path has non-finite coordinates')
    if len(pts):
        limits.check_coord(float(np.abs(pts).max()))
    keep_c = (nline > 0) | closed
    counts = nline + 1
    if not keep_c.all():
        pts = take_rows(np.ascontiguousarray(pts), np.repeat(keep_c, counts))
        counts = counts[keep_c]
    limits.check_points(int(counts.sum()), 'flattening')
    # (pts is new: the concatenation, its transform or its kept rows)
    per_path = np.bincount(c_path, weights=keep_c, minlength=n).astype(np.int64)
    first = np.concatenate([[0], np.cumsum(per_path)])
    return Polylines(pts, np.cumsum(counts) - counts, closed[keep_c]), first


def flatten_many(paths: Sequence[Path], transforms: Optional[Sequence[AffineLike]] = None,
                 tolerance: float = DEFAULT_TOLERANCE, straddle: bool = False) -> List[Polylines]:
    """Flatten many paths at once: one :func:`flatten_beziers` call per
    degree for all their curves, so a document of thousands of small paths
    does not pay the fixed cost of a flatten call per path.

    Parameters
    ----------
    paths : sequence of raster.geometry.path.Path
    transforms : sequence of Affine (or None entries), or None, optional
        One transform per path (user to device space); None: identity.
    tolerance, straddle : optional
        As for :func:`flatten` (device pixels, default 0.25; on the path).

    Returns
    -------
    list of Polylines
        ``result[i]`` equals ``flatten(paths[i], tolerance, transforms[i],
        straddle)`` exactly (same vertices, starts and closed flags).

    Raises
    ------
    PathError
        Not a path, bad tolerance, mismatched lengths, or coordinates that
        become non-finite after a transform.
    TransformError
        A transform that cannot be interpreted.
    LimitError
        More than :data:`raster.limits.MAX_FLATTEN_POINTS` points needed in
        all.

    Examples
    --------
    >>> from raster.geometry.path import Path
    >>> sq = Path.polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    >>> a, b = flatten_many([sq, sq], [None, (2, 0, 0, 2, 5, 0)])
    >>> b.points.tolist()
    [[5.0, 0.0], [7.0, 0.0], [7.0, 2.0], [5.0, 2.0]]
    """
    pl, first = flatten_joined(paths, transforms, tolerance, straddle)
    out, starts, closed_k = pl.points, pl.starts, pl.closed
    bounds = np.append(starts, len(out))[first]        # point range of each path
    res = []
    kl, bl = first.tolist(), bounds.tolist()
    for i in range(len(kl) - 1):
        k0, k1, a0, a1 = kl[i], kl[i + 1], bl[i], bl[i + 1]
        res.append(Polylines(out[a0:a1], starts[k0:k1] - a0, closed_k[k0:k1]))
    return res
