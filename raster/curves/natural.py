r"""Natural (and clamped) cubic spline interpolation.

Through samples ``(x_i, y_i)`` with ``h_i = x_{i+1} - x_i > 0`` the cubic
spline's second derivatives ``M_i`` solve the tridiagonal system

.. math:: h_{i-1} M_{i-1} + 2(h_{i-1} + h_i) M_i + h_i M_{i+1}
          = 6 \left(\frac{y_{i+1} - y_i}{h_i} - \frac{y_i - y_{i-1}}{h_{i-1}}\right)

with natural ends ``M_0 = M_{N-1} = 0`` or clamped ends (given end slopes
``s_0, s_N``: ``2 h_0 M_0 + h_0 M_1 = 6((y_1 - y_0)/h_0 - s_0)`` and the
mirror row).  The system is strictly diagonally dominant and is solved by
parallel cyclic reduction (``ceil(log2 N)`` vectorized sweeps).

:class:`FunctionSpline` interpolates a function ``y(x)``;
:class:`NaturalSpline` interpolates a 2-D/3-D point sequence, each coordinate
a spline of a parameter ``t in [0, 1]`` chosen by ``parameterization``:
``'uniform'`` (equal steps), ``'chord'`` (proportional to the distances) or
``'centripetal'`` (to their square roots).

>>> f = FunctionSpline([0, 1, 2], [0, 1, 0])
>>> float(f.value(0.5))
0.6875
"""

import numpy as np

from .base import CurveMixin
from .checks import CurveError, as_params, as_points, shape_out
from .bezier import PiecewiseBezier

PARAMETERIZATIONS = ('uniform', 'chord', 'centripetal')


def solve_tridiagonal(a, b, c, d):
    """Solve a tridiagonal system by parallel cyclic reduction.

    Parameters
    ----------
    a : (N,) array_like of float
        Sub-diagonal (``a[0]`` ignored).
    b : (N,) array_like of float
        Diagonal.
    c : (N,) array_like of float
        Super-diagonal (``c[-1]`` ignored).
    d : (N,) or (N, K) array_like of float
        Right-hand side(s).

    Returns
    -------
    (N,) or (N, K) float64 ndarray

    Stable for diagonally dominant systems (the only kind used here).

    >>> solve_tridiagonal([0, 1, 1], [4, 4, 4], [1, 1, 0], [5, 6, 5]).tolist()
    [1.0, 1.0, 1.0]
    """
    a = np.array(a, dtype=np.float64)
    b = np.array(b, dtype=np.float64)
    c = np.array(c, dtype=np.float64)
    d = np.array(d, dtype=np.float64)
    vec = d.ndim == 1
    if vec:
        d = d[:, None]
    N = len(b)
    a[0] = 0.0
    c[-1] = 0.0
    i = np.arange(N)
    s = 1
    while s < N:
        im, ip = i - s, i + s
        lo, hi = im >= 0, ip < N
        imc, ipc = np.clip(im, 0, N - 1), np.clip(ip, 0, N - 1)
        a_m = np.where(lo, a[imc], 0.0); b_m = np.where(lo, b[imc], 1.0)
        c_m = np.where(lo, c[imc], 0.0); d_m = np.where(lo[:, None], d[imc], 0.0)
        a_p = np.where(hi, a[ipc], 0.0); b_p = np.where(hi, b[ipc], 1.0)
        c_p = np.where(hi, c[ipc], 0.0); d_p = np.where(hi[:, None], d[ipc], 0.0)
        k1 = a / b_m
        k2 = c / b_p
        a, b, c = -a_m * k1, b - c_m * k1 - a_p * k2, -c_p * k2
        d = d - d_m * k1[:, None] - d_p * k2[:, None]
        s *= 2
    x = d / b[:, None]
    return x[:, 0] if vec else x


def second_derivatives(x, y, end_slopes=None):
    """Spline second derivatives ``M`` at the samples.

    Parameters
    ----------
    x : (N,) float64, strictly increasing
    y : (N, D) float64
    end_slopes : None or pair of (D,) arrays
        None: natural ends; else the clamped end derivatives ``dy/dx``.

    Returns
    -------
    (N, D) float64
    """
    N = len(x)
    h = np.diff(x)
    dy = np.diff(y, axis=0) / h[:, None]
    a = np.zeros(N); b = np.ones(N); c = np.zeros(N); r = np.zeros_like(y)
    a[1:-1] = h[:-1]
    b[1:-1] = 2 * (h[:-1] + h[1:])
    c[1:-1] = h[1:]
    r[1:-1] = 6 * (dy[1:] - dy[:-1])
    if end_slopes is not None:
        s0, s1 = end_slopes
        b[0], c[0], r[0] = 2 * h[0], h[0], 6 * (dy[0] - s0)
        a[-1], b[-1], r[-1] = h[-1], 2 * h[-1], 6 * (s1 - dy[-1])
    return solve_tridiagonal(a, b, c, r)


class _Cubic:
    """Interpolating cubic spline of (N, D) values over knots x (N,)."""

    def __init__(self, x, y, end_slopes):
        self.x, self.y = x, y
        with np.errstate(over='ignore', invalid='ignore', divide='ignore'):
            self.m = second_derivatives(x, y, end_slopes)
        if not np.all(np.isfinite(self.m)):
            raise CurveError('the spline overflows: samples or end slopes too large')

    def eval(self, xs, order=0):
        x, y, m = self.x, self.y, self.m
        i = np.clip(np.searchsorted(x, xs, side='right') - 1, 0, len(x) - 2)
        h = (x[i + 1] - x[i])[:, None]
        A = (x[i + 1][:, None] - xs[:, None])
        B = (xs[:, None] - x[i][:, None])
        mi, mj, yi, yj = m[i], m[i + 1], y[i], y[i + 1]
        if order == 0:
            return (mi * A ** 3 + mj * B ** 3) / (6 * h) + (yi / h - mi * h / 6) * A \
                + (yj / h - mj * h / 6) * B
        if order == 1:
            return (-mi * A ** 2 + mj * B ** 2) / (2 * h) + (yj - yi) / h - (mj - mi) * h / 6
        if order == 2:
            return (mi * A + mj * B) / h
        if order == 3:
            return np.broadcast_to((mj - mi) / h, A.shape[:1] + mi.shape[1:]).copy()
        return np.zeros(A.shape[:1] + mi.shape[1:])

    def bezier_ctrl(self):
        """(S, 4, D) cubic Bezier control points in the local parameter."""
        x, y, m = self.x, self.y, self.m
        h = np.diff(x)[:, None]
        dy = np.diff(y, axis=0) / h
        s0 = dy - h * (2 * m[:-1] + m[1:]) / 6          # y'(x_i+)
        s1 = dy + h * (m[:-1] + 2 * m[1:]) / 6          # y'(x_{i+1}-)
        return np.stack([y[:-1], y[:-1] + h * s0 / 3, y[1:] - h * s1 / 3, y[1:]], axis=1)


def _end_pair(v, D, name):
    if v is None:
        return None
    try:
        a = np.array(v, dtype=np.float64).reshape(2, D)
    except (TypeError, ValueError):
        raise CurveError('%s must be two %d-vectors' % (name, D)) from None
    if not np.all(np.isfinite(a)):
        raise CurveError('%s must be finite' % name)
    return a[0], a[1]


class FunctionSpline(CurveMixin):
    """Cubic spline interpolant of a function ``y(x)``.

    Parameters
    ----------
    x : (N,) array_like of float
        Strictly increasing sample abscissae, N >= 2.
    y : (N,) array_like of float
    end_slopes : (2,) array_like of float, optional
        Clamped end conditions ``y'(x_0), y'(x_{N-1})``; default natural.

    ``eval(x)`` returns graph points ``(x, y(x))`` ((M, 2)), the shared
    vocabulary's point form; :meth:`value` returns ``y(x)``.
    """

    def __init__(self, x, y, end_slopes=None):
        pts = as_points(np.column_stack([np.ravel(x), np.ravel(y)])
                        if np.size(x) == np.size(y) else [[np.nan, np.nan]], 2, 'samples')
        xs = pts[:, 0]
        if np.any(np.diff(xs) <= 0):
            raise CurveError('x values must be strictly increasing')
        self.points = pts
        ends = _end_pair(end_slopes, 1, 'end slopes')
        #: None (natural ends) or the clamped end slopes (y'(x0), y'(xN)).
        self.end_slopes = None if ends is None else (float(ends[0][0]), float(ends[1][0]))
        self._c = _Cubic(xs, pts[:, 1:], ends)

    @property
    def domain(self):
        return (float(self.points[0, 0]), float(self.points[-1, 0]))

    def value(self, x, order=0):
        """``y(x)`` or its ``order``-th derivative: float or (M,) float64."""
        xa, scalar = as_params(x, *self.domain, name='x')
        return shape_out(self._c.eval(xa, order)[:, 0], scalar)

    __call__ = value

    def eval(self, x):
        """Graph points ``(x, y(x))``: (2,) or (M, 2) float64."""
        xa, scalar = as_params(x, *self.domain, name='x')
        return shape_out(np.column_stack([xa, self._c.eval(xa)[:, 0]]), scalar)

    def second_derivatives(self):
        """(N,) float64 ``M_i = y''(x_i)``."""
        return self._c.m[:, 0].copy()

    def to_beziers(self):
        """Exact cubic Bezier segments of the graph (x is linear in each)."""
        x = self._c.x
        yc = self._c.bezier_ctrl()[:, :, 0]
        xc = x[:-1, None] + np.diff(x)[:, None] * (np.arange(4) / 3.0)[None, :]
        return PiecewiseBezier(np.stack([xc, yc], axis=2), x)


def parameterize(points, kind='chord'):
    """Parameter values in [0, 1] for a point sequence: (N,) float64,
    strictly increasing (``'uniform'``, ``'chord'`` or ``'centripetal'``)."""
    if kind not in PARAMETERIZATIONS:
        raise CurveError('parameterization must be one of %s, got %r'
                         % (', '.join(PARAMETERIZATIONS), kind))
    n = len(points)
    if kind == 'uniform':
        return np.linspace(0.0, 1.0, n)
    d = np.linalg.norm(np.diff(points, axis=0), axis=1)
    if np.any(d == 0):
        raise CurveError('consecutive points coincide; %s parameterization needs distinct points'
                         % kind)
    if kind == 'centripetal':
        d = np.sqrt(d)
    t = np.concatenate([[0.0], np.cumsum(d)])
    t /= t[-1]
    t[-1] = 1.0
    if np.any(np.diff(t) <= 0):
        raise CurveError('parameter steps underflow; points too close together')
    return t


class NaturalSpline(CurveMixin):
    """Parametric cubic spline through a 2-D/3-D point sequence.

    Parameters
    ----------
    points : (N, D) array_like of float
        N >= 2 points to interpolate.
    parameterization : {'chord', 'uniform', 'centripetal'}
    end_tangents : (2, D) array_like of float, optional
        Clamped end derivatives ``C'(0), C'(1)``; default natural ends.

    The curve passes through ``points[i]`` at ``t = params[i]``, t in [0, 1].
    """

    def __init__(self, points, parameterization='chord', end_tangents=None):
        p = as_points(points, 2, dims=None)
        self.points = p
        self.parameterization = parameterization
        self.params = parameterize(p, parameterization)
        ends = _end_pair(end_tangents, p.shape[1], 'end tangents')
        #: None (natural ends) or the clamped end derivatives, (2, D) float64.
        self.end_tangents = None if ends is None else np.stack(ends)
        self._c = _Cubic(self.params, p, ends)

    domain = (0.0, 1.0)

    def eval(self, t, order=0):
        """Point(s) (or ``order``-th derivative) at ``t``: (D,) or (M, D)."""
        ta, scalar = as_params(t, 0.0, 1.0)
        return shape_out(self._c.eval(ta, order), scalar)

    __call__ = eval

    def to_beziers(self):
        """Exact cubic Bezier segments with breaks at :attr:`params`."""
        return PiecewiseBezier(self._c.bezier_ctrl(), self.params)
