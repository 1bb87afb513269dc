"""raster's curve toolkit: parametric curves for design, teaching and
computation.

Every family shares one vocabulary -- ``eval(t)`` (scalar or array of t),
``deriv()``, ``subsegment(t0, t1)``, ``extrema()``, ``bounding_box()``,
``to_beziers()`` (a :class:`PiecewiseBezier`, iterable as :class:`Bezier`
objects), ``flatten(tolerance)``, ``to_path()``, ``to_svg()``, ``draw(pen)``
and ``continuity()`` -- and converts exactly to Bezier segments, so curves
can be flattened, bounded, stroked, rendered and exported with the rest of
raster.

Parameters: a :class:`Bezier` lives on ``t in [0, 1]`` and its
``subsegment(t0, t1)`` is again a Bezier on [0, 1] (as in kurbo); splines
have a ``domain`` (uniform splines ``[0, S]`` with joints at integers,
B-splines their knot range, natural splines [0, 1] or the x range) and
their ``subsegment`` keeps the global parameter.  ``deriv()`` is the
derivative with respect to that parameter (a Bezier, a B-spline, or a
:class:`PiecewiseBezier`).  ``to_path()`` projects onto (x, y); degrees
above 3 become cubics within ``tolerance`` (an exact error bound, see
:meth:`PiecewiseBezier.to_cubics`).

=====================  ==============================================
module                 classes and functions
=====================  ==============================================
``bezier``             :class:`Bezier`, :class:`PiecewiseBezier`,
                       :func:`bernstein`, :func:`bernstein_matrix`
``hermite``            :class:`Hermite`, :class:`HermiteSpline`,
                       :func:`hermite_blend`, :func:`hermite_basis_matrix`
``cardinal``           :class:`CardinalSpline`, :class:`CatmullRom`,
                       :func:`cardinal_matrix`
``kochanek``           :class:`KochanekBartels`
``bspline``            :class:`BSpline`, :func:`basis_functions`,
                       :func:`clamped_uniform_knots`
``beta``               :class:`BetaSpline`, :func:`beta_basis_matrix`
``natural``            :class:`NaturalSpline`, :class:`FunctionSpline`,
                       :func:`solve_tridiagonal`
``continuity``         :func:`continuity`, :class:`Joint`
``rational``           :class:`RationalBezier`, :class:`PiecewiseRational`
``nurbs``              :class:`NURBS`
``conics``             :func:`conic`, :func:`conic_kind`, :func:`circle_arc`,
                       :func:`ellipse_arc`, :func:`circle`, :func:`ellipse`,
                       :class:`ConicArc`
``surface``            :class:`BezierSurface`, :class:`RationalBezierSurface`,
                       :class:`BSplineSurface`, :class:`NURBSSurface`,
                       :class:`HermitePatch`, :class:`CoonsPatch`
``explain``            :func:`explain` (worked solutions)
``plot``, ``axes``,    plots of curves (axes, labels, blending panel) and
``surfaceplot``        of surfaces (shaded, wireframe, control net)
(``raster.geometry.hull``) :func:`convex_hull` (monotone chain), re-exported
=====================  ==============================================

Rational curves (rational Bezier, NURBS, conic arcs) share the vocabulary
except that ``to_beziers()`` is exact only for equal weights; otherwise
``to_beziers(tolerance)`` gives cubics within the tolerance, and
``flatten``, ``to_path``, ``bounding_box`` (exact) and ``continuity`` work
on the rational form directly.

Errors are :class:`CurveError` (a :class:`raster.errors.RasterError`).

>>> from raster.curves import Bezier
>>> Bezier([[0, 0], [1, 1]]).eval(0.5).tolist()
[0.5, 0.5]
"""

from .checks import CurveError
from .bezier import Bezier, PiecewiseBezier, bernstein, bernstein_matrix
from .hermite import Hermite, HermiteSpline, hermite_blend, hermite_basis_matrix
from .cardinal import CardinalSpline, CatmullRom, cardinal_matrix
from .kochanek import KochanekBartels
from .bspline import BSpline, basis_functions, clamped_uniform_knots
from .beta import BetaSpline, beta_basis_matrix, beta_blend
from .natural import NaturalSpline, FunctionSpline, solve_tridiagonal
from .continuity import continuity, Joint, format_joints
from .rational import RationalBezier, PiecewiseRational
from .nurbs import NURBS
from .conics import ConicArc, conic, conic_kind, circle_arc, ellipse_arc, circle, ellipse
from .surface import (BezierSurface, RationalBezierSurface, BSplineSurface, NURBSSurface,
                      HermitePatch, CoonsPatch)
from .explain import explain
from ..geometry.hull import convex_hull   # re-exported: the hull shared with flattening


__all__ = ['CurveError', 'Bezier', 'PiecewiseBezier', 'bernstein', 'bernstein_matrix',
           'Hermite', 'HermiteSpline', 'hermite_blend', 'hermite_basis_matrix',
           'CardinalSpline', 'CatmullRom', 'cardinal_matrix', 'KochanekBartels', 'BSpline', 'basis_functions',
           'clamped_uniform_knots', 'BetaSpline', 'beta_basis_matrix', 'beta_blend',
           'NaturalSpline', 'FunctionSpline', 'solve_tridiagonal', 'continuity', 'Joint',
           'format_joints', 'convex_hull', 'RationalBezier', 'PiecewiseRational', 'NURBS',
           'ConicArc', 'conic', 'conic_kind', 'circle_arc', 'ellipse_arc', 'circle', 'ellipse',
           'BezierSurface', 'RationalBezierSurface', 'BSplineSurface', 'NURBSSurface',
           'HermitePatch', 'CoonsPatch', 'explain']
