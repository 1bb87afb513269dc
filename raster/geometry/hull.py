"""Convex hull of a planar point set (Andrew's monotone chain).

Orientation: the hull is returned counter-clockwise in the mathematical,
y-up sense (positive signed area by the shoelace formula, every turn a
left turn).  raster's device space has y pointing *down*, so on screen the
same polygon runs clockwise.

>>> convex_hull([[0, 0], [2, 0], [1, 1], [2, 2], [0, 2], [1, 0]]).tolist()
[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
if TYPE_CHECKING:              # numpy.typing costs 1 ms of every start-up
    from numpy.typing import ArrayLike

from ..errors import PathError

__all__ = ['convex_hull']

# Elimination passes tried before falling back to the sequential chain.
_MAX_PASSES = 64


def _cross(o, a, b):
    """z of (a - o) x (b - o), elementwise over leading axes."""
    return ((a[..., 0] - o[..., 0]) * (b[..., 1] - o[..., 1])
            - (a[..., 1] - o[..., 1]) * (b[..., 0] - o[..., 0]))


def _prefilter(P):
    """Drop points strictly inside the polygon of the extreme points in 8
    directions (Akl-Toussaint); they cannot be hull vertices."""
    dirs = np.array([[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1]],
                    dtype=np.float64)
    proj = P @ dirs.T                                  # (N, 8)
    V = P[np.argmax(proj, axis=0)]                     # CCW order of directions
    keep = np.ones(len(V), bool)
    keep[1:] = np.any(V[1:] != V[:-1], axis=1)
    V = V[keep]
    if len(V) > 1 and np.all(V[-1] == V[0]):
        V = V[:-1]
    if len(V) < 3:
        return P
    W = np.roll(V, -1, axis=0)
    scale = np.abs(P).max() + 1.0
    margin = 64 * np.finfo(np.float64).eps * scale * scale
    inside = np.ones(len(P), bool)
    for k in range(len(V)):                             # <= 8 edges
        inside &= _cross(V[k], W[k], P) > margin
    return P[~inside]


def _half_chain(P):
    """Lower hull (left to right, strict left turns) of lexicographically
    sorted points ``P`` ((M, 2)), first and last point included."""
    idx = np.arange(len(P))
    for _ in range(_MAX_PASSES):
        if len(idx) < 3:
            return P[idx]
        Q = P[idx]
        turn = _cross(Q[:-2], Q[1:-1], Q[2:])
        bad = turn <= 0
        if not np.any(bad):
            return Q
        keep = np.ones(len(idx), bool)
        keep[1:-1] = ~bad
        idx = idx[keep]
    # sequential monotone chain on what is left
    out = []
    for p in P[idx].tolist():
        while len(out) >= 2 and ((out[-1][0] - out[-2][0]) * (p[1] - out[-2][1])
                                 - (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0])) <= 0:
            out.pop()
        out.append(p)
    return np.array(out, dtype=np.float64)


def convex_hull(points: ArrayLike) -> np.ndarray:
    """Convex hull of 2-D points.

    Parameters
    ----------
    points : (N, 2) array_like of float
        Any order; duplicates allowed.

    Returns
    -------
    (H, 2) float64 ndarray
        Hull vertices, counter-clockwise in the y-up mathematical sense
        (clockwise on a y-down screen), starting at the lexicographically
        smallest point (least x, then least y), without repeating it.
        Collinear points on hull edges are dropped.  Degenerate inputs:
        ``N = 0`` gives ``(0, 2)``; all points equal gives that one point;
        all points on a line gives its two extreme points.

    Raises
    ------
    PathError
        Not an (N, 2) array of numbers, or non-finite coordinates.

    Notes
    -----
    Points strictly inside the polygon of the extreme points in 8 directions
    are discarded first; the survivors are sorted and each monotone half is
    reduced by vectorized passes that drop every vertex that is not a strict
    left turn (a point above the segment of two other points cannot be on
    the lower hull), finishing with the sequential chain if many passes would
    be needed.

    Examples
    --------
    >>> convex_hull([[0, 0], [1, 1], [2, 2]]).tolist()
    [[0.0, 0.0], [2.0, 2.0]]
    >>> convex_hull(np.zeros((0, 2))).shape
    (0, 2)
    """
    try:
        P = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise PathError('points must be an (N, 2) array of numbers') from None
    if P.size == 0:
        return np.zeros((0, 2))
    if P.ndim != 2 or P.shape[1] != 2:
        raise PathError('points must have shape (N, 2), got %r' % (P.shape,))
    if not np.all(np.isfinite(P)):
        raise PathError('points must be finite (NaN or infinity found)')
    if len(P) > 64:
        P = _prefilter(P)
    P = np.unique(P, axis=0)                           # sorted by x, then y
    if len(P) <= 2:
        return P
    lower = _half_chain(P)
    upper = _half_chain(P[::-1])
    return np.concatenate([lower[:-1], upper[:-1]])
