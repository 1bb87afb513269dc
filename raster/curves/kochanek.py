r"""Kochanek-Bartels (TCB) splines: interpolating piecewise cubic Hermite
curves with a tension ``T``, continuity ``C`` and bias ``B`` per key.

At key ``P_i`` the tangent leaving the key (start of segment ``i``) and the
tangent arriving at it (end of segment ``i - 1``) are

.. math::

    D^{out}_i = \frac{(1-T)(1+B)(1-C)}{2}(P_i - P_{i-1})
              + \frac{(1-T)(1-B)(1+C)}{2}(P_{i+1} - P_i)

    D^{in}_i  = \frac{(1-T)(1+B)(1+C)}{2}(P_i - P_{i-1})
              + \frac{(1-T)(1-B)(1-C)}{2}(P_{i+1} - P_i)

With ``T = C = B = 0`` both are the Catmull-Rom tangent; ``C != 0`` makes them
differ (a corner, C0 but not C1 at the key).  Parameterization and end
handling are those of :mod:`raster.curves.cardinal`.

>>> kb = KochanekBartels([[0, 0], [1, 1], [2, 0]])
>>> kb.eval(1.0).tolist()
[1.0, 1.0]
"""


from .checks import as_points, per_key
from .cardinal import neighbours
from .hermite import HermiteSpline


class KochanekBartels(HermiteSpline):
    """Kochanek-Bartels spline through ``points``.

    Parameters
    ----------
    points : (N, D) array_like of float
    tension, continuity, bias : float or (N,) array_like of float
        One value for all keys or one per input point.
    ends : {'duplicate', 'interior', 'closed'}
        See :mod:`raster.curves.cardinal`.
    """

    def __init__(self, points, tension=0.0, continuity=0.0, bias=0.0, ends='duplicate'):
        p = as_points(points, 2, dims=None)
        N = len(p)
        self.tension = per_key(tension, N, 'tension')
        self.continuity_param = per_key(continuity, N, 'continuity')
        self.bias = per_key(bias, N, 'bias')
        self.ends = ends
        prev, key, nxt, idx = neighbours(p, ends)
        T, C, B = (self.tension[idx][:, None], self.continuity_param[idx][:, None],
                   self.bias[idx][:, None])
        a, b = key - prev, nxt - key
        d_out = (1 - T) * (1 + B) * (1 - C) / 2 * a + (1 - T) * (1 - B) * (1 + C) / 2 * b
        d_in = (1 - T) * (1 + B) * (1 + C) / 2 * a + (1 - T) * (1 - B) * (1 - C) / 2 * b
        super().__init__(key, d_out[:-1], d_in[1:])
        self.keys = key
        self.source_points = p
