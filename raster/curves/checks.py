"""Input checking of the curve toolkit: its error type and the validators
every curve family uses (no curve maths here, so that every module of
:mod:`raster.curves` can import it)."""

import numpy as np

from ..errors import RasterError

#: Most control points / samples a curve call accepts (guards memory and time).
MAX_CURVE_POINTS = 10_000_000

#: Largest coordinate magnitude accepted: cubes of coordinates and of
#: parameters stay far from float64 overflow.
MAX_CURVE_COORD = 1e100


class CurveError(RasterError, ValueError):
    """Invalid curve input: too few or non-finite control points, a parameter
    outside the curve's domain, a knot vector that is not non-decreasing, a
    degree that does not fit the points, an unknown option."""


def as_points(points, min_points=1, name='control points', dims=(2, 3)):
    """Validate control points.

    Parameters
    ----------
    points : (N, D) array_like of float
    min_points : int
    dims : tuple of int or None
        Allowed dimensions ``D`` (``None``: any D >= 1).

    Returns
    -------
    (N, D) float64 ndarray (a fresh copy).
    """
    try:
        p = np.array(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise CurveError('%s must be numbers' % name) from None
    if p.ndim != 2:
        raise CurveError('%s must be an (N, D) array, got shape %s' % (name, p.shape))
    if dims is not None and p.shape[1] not in dims:
        raise CurveError('%s must be %s-dimensional, got D=%d'
                         % (name, ' or '.join(map(str, dims)), p.shape[1]))
    if p.shape[1] < 1:
        raise CurveError('%s need at least one coordinate' % name)
    if len(p) < min_points:
        raise CurveError('need at least %d %s, got %d' % (min_points, name, len(p)))
    if len(p) > MAX_CURVE_POINTS:
        raise CurveError('too many %s (%d)' % (name, len(p)))
    if not np.all(np.isfinite(p)):
        raise CurveError('%s must be finite' % name)
    if p.size and np.abs(p).max() > MAX_CURVE_COORD:
        raise CurveError('%s exceed the coordinate limit %g' % (name, MAX_CURVE_COORD))
    return p


def as_params(t, lo, hi, name='t', slack=1e-12):
    """Validate parameter values against the domain ``[lo, hi]``.

    Returns ``(values, scalar)``: a (M,) float64 ndarray (clipped to the
    domain after a relative slack of ``slack``) and whether the input was a
    scalar.
    """
    try:
        a = np.asarray(t, dtype=np.float64)
    except (TypeError, ValueError):
        raise CurveError('%s must be numbers' % name) from None
    scalar = a.ndim == 0
    a = a.reshape(-1)
    if a.size > MAX_CURVE_POINTS:
        raise CurveError('too many %s values (%d)' % (name, a.size))
    if not np.all(np.isfinite(a)):
        raise CurveError('%s must be finite' % name)
    if a.size and np.abs(a).max() > MAX_CURVE_COORD:
        raise CurveError('%s exceeds the limit %g' % (name, MAX_CURVE_COORD))
    eps = slack * max(1.0, abs(lo), abs(hi))
    if a.size and (a.min() < lo - eps or a.max() > hi + eps):
        bad = a[(a < lo - eps) | (a > hi + eps)][0]
        raise CurveError('%s=%g is outside the domain [%g, %g]' % (name, bad, lo, hi))
    return np.clip(a, lo, hi), scalar


def as_scalar(v, name, lo=-np.inf, hi=np.inf):
    """A finite float in [lo, hi] or :class:`CurveError`."""
    try:
        f = float(v)
    except (TypeError, ValueError):
        raise CurveError('%s must be a number, got %r' % (name, v)) from None
    if not np.isfinite(f) or f < lo or f > hi:
        raise CurveError('%s=%r is out of range [%g, %g]' % (name, v, lo, hi))
    return f


def per_key(v, n, name):
    """A scalar or a length-``n`` sequence as an (n,) float64 ndarray."""
    try:
        a = np.asarray(v, dtype=np.float64)
    except (TypeError, ValueError):
        raise CurveError('%s must be numbers' % name) from None
    if a.ndim == 0:
        a = np.full(n, float(a))
    a = a.reshape(-1)
    if a.shape != (n,):
        raise CurveError('%s needs 1 or %d values, got %d' % (name, n, a.size))
    if not np.all(np.isfinite(a)):
        raise CurveError('%s must be finite' % name)
    return a


def shape_out(values, scalar):
    """Return ``values[0]`` for a scalar parameter, else ``values``."""
    return values[0] if scalar else values


#: Highest Bezier degree accepted (Bernstein recurrences are O(n^2) per parameter).
MAX_DEGREE = 200


def as_degree(n):
    """A polynomial degree: an int in ``0 .. MAX_DEGREE`` or :class:`CurveError`."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise CurveError('degree must be a non-negative integer, got %r' % (n,))
    if n > MAX_DEGREE:
        raise CurveError('degree %d exceeds the limit %d' % (n, MAX_DEGREE))
    return int(n)
