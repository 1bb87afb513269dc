"""Exact bounding boxes of paths and Bezier curves.

The box of a Bezier curve is spanned by its end points and by the curve
points where a coordinate's derivative vanishes.  For quadratics and cubics
that derivative is a polynomial of degree 1 or 2 per axis, solved in closed
form (:func:`quadratic_roots`) for all segments at once.

Coordinates are float64 user units (x right, y down); a ``transform`` is
applied to the control points *before* the box is taken (the box of a
transformed curve, not the transformed box).
"""

import numpy as np

from .errors import PathError

__all__ = ['quadratic_roots']


def quadratic_roots(a, b, c):
    """Real roots of ``a t**2 + b t + c = 0``, elementwise.

    Uses the cancellation-free form ``q = -(b + sign(b) sqrt(b**2 - 4ac)) / 2``,
    roots ``q / a`` and ``c / q``.  A zero (or tiny) ``a`` degrades
    gracefully to the linear root ``-c / b``; ``q / a`` is then infinite or
    huge.

    Parameters
    ----------
    a, b, c : array_like of float, broadcastable to one shape ``(...)``

    Returns
    -------
    (..., 2) float64 ndarray
        The two roots; NaN where there is no real root (negative
        discriminant, or ``a = b = 0``).  A double root appears twice.

    Examples
    --------
    >>> quadratic_roots(1.0, -3.0, 2.0).tolist()
    [2.0, 1.0]
    >>> quadratic_roots(0.0, 2.0, -1.0).tolist()
    [nan, 0.5]
    """
    a, b, c = np.broadcast_arrays(*(np.asarray(v, dtype=np.float64) for v in (a, b, c)))
    with np.errstate(all='ignore'):
        disc = b * b - 4.0 * a * c
        sq = np.sqrt(np.where(disc >= 0, disc, np.nan))
        q = -0.5 * (b + np.where(b >= 0, sq, -sq))
        r1 = np.where(a != 0, q / a, np.nan)
        r2 = np.where(q != 0, c / q, np.where(a != 0, 0.0, np.nan))
    r1 = np.where(np.isfinite(r1), r1, np.nan)
    r2 = np.where(np.isfinite(r2), r2, np.nan)
    return np.stack([r1, r2], axis=-1)
