"""The mixin that gives every curve family the common vocabulary by way of
its Bezier segments.

Every curve object implements ``eval(t)`` and ``to_beziers()`` (a
:class:`~raster.curves.bezier.PiecewiseBezier`); :class:`CurveMixin` derives
``extrema``, ``bounding_box``, ``flatten``, ``to_path``, ``to_svg``, ``draw``
and ``continuity`` from its :meth:`CurveMixin.segments`: the Bezier form, or
for rational families (NURBS, rational Bezier) their exact rational chain.
"""

import numpy as np

from .checks import CurveError
from .continuity import continuity as _continuity


class CurveMixin:
    """The shared vocabulary, derived from :meth:`to_beziers`.

    Subclasses provide ``eval(t)``, ``to_beziers()`` and ``domain``.
    """

    __slots__ = ()

    def segments(self):
        """The piecewise form the vocabulary is derived from (default:
        :meth:`to_beziers`; rational families return their rational chain)."""
        return self.to_beziers()

    @property
    def dim(self):
        """Dimension D of the curve's points (2 or 3)."""
        return self.segments().dim

    def deriv(self, order=1):
        """Derivative (hodograph) with respect to the curve's parameter, as a
        :class:`~raster.curves.bezier.PiecewiseBezier`."""
        return self.segments().deriv(order)

    def tangent(self, t):
        """First derivative at ``t``: (D,) or (M, D) float64."""
        return self.segments().tangent(t)

    def slope(self, t):
        """dy/dx = y'(t) / x'(t) (``+-inf`` where x' = 0, ``nan`` where both
        vanish): float or (M,) float64.  Needs D >= 2."""
        if self.dim < 2:
            raise CurveError('slope needs a curve of dimension >= 2')
        d = np.atleast_2d(self.tangent(t))
        with np.errstate(divide='ignore', invalid='ignore'):
            s = d[:, 1] / d[:, 0]
        return float(s[0]) if np.ndim(t) == 0 else s

    def subsegment(self, t0, t1):
        """The piece between parameters ``t0`` and ``t1`` (PiecewiseBezier)."""
        return self.segments().subsegment(t0, t1)

    def extrema(self):
        """Parameters (sorted (K,) float64) where some coordinate has a local
        extremum inside the domain."""
        return self.segments().extrema()

    def bounding_box(self):
        """Exact bounding box ``(lo, hi)``, two (D,) float64 arrays."""
        return self.segments().bounding_box()

    def flatten(self, tolerance=0.25):
        """Polyline within ``tolerance`` of the curve: (K, D) float64."""
        return self.segments().flatten(tolerance)

    def to_path(self, tolerance=0.25):
        """A :class:`raster.geometry.path.Path` (x, y only); see
        :meth:`PiecewiseBezier.to_path`."""
        return self.segments().to_path(tolerance)

    def to_svg(self, tolerance=0.25, precision=None):
        """SVG path data of :meth:`to_path`."""
        return self.to_path(tolerance).to_svg(precision)

    def draw(self, pen, tolerance=0.25):
        """Send the curve to a pen (fontTools protocol)."""
        self.segments().draw(pen, tolerance)

    def continuity(self, tolerance=1e-9):
        """Continuity at each joint; see :func:`raster.curves.continuity.continuity`."""
        closed = bool(getattr(self, 'closed', False)) or getattr(self, 'ends', None) == 'closed'
        return _continuity(self.to_beziers(), tolerance, closed=closed)

    def control_points(self):
        """The points that define the curve ((N, D) float64)."""
        return self.points.copy()
