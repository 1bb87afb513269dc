"""Exact bounding boxes of paths and Bezier curves.

The box of a Bezier curve is spanned by its end points and by the curve
points where a coordinate's derivative vanishes
(:func:`raster.geometry.bezier.bounds`: closed form up to degree 3, for all
segments of a path at once).  :class:`~raster.geometry.pens.BoundsPen`
takes the same boxes segment by segment.

Coordinates are float64 user units (x right, y down); a ``transform`` is
applied to the control points *before* the box is taken (the box of a
transformed curve, not the transformed box).
"""

from __future__ import annotations

from typing import Any, TYPE_CHECKING, Tuple

import numpy as np
if TYPE_CHECKING:              # numpy.typing costs 1 ms of every start-up
    from numpy.typing import ArrayLike

from ..errors import PathError
from .bezier import bounds, segment_bounds
from .stroking import stroke as _stroke
from .path import Path
from .transform import AffineLike, as_affine

__all__ = ['bbox', 'bezier_bbox']

Box = Tuple[float, float, float, float]


def bezier_bbox(ctrl: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
    """Exact bounding box of one Bezier curve of any degree.

    Parameters
    ----------
    ctrl : (n+1, D) array_like of float
        Control points, ``n >= 0``.

    Returns
    -------
    lo, hi : (D,) float64 ndarray

    Raises
    ------
    PathError
        Control points that are not a finite ``(n+1, D)`` array.

    Notes
    -----
    See :func:`raster.geometry.bezier.bounds` (degrees up to 3 in closed
    form, higher degrees by the real roots of the derivative in (0, 1)).

    Examples
    --------
    >>> lo, hi = bezier_bbox([[0, 0], [1, 2], [2, 0]])
    >>> lo.tolist(), hi.tolist()
    ([0.0, 0.0], [2.0, 1.0])
    """
    try:
        P = np.asarray(ctrl, dtype=np.float64)
    except (TypeError, ValueError):
        raise PathError('control points must be an (n+1, D) array of numbers') from None
    if P.ndim != 2 or len(P) < 1:
        raise PathError('control points must have shape (n+1, D), got %r' % (P.shape,))
    if not np.all(np.isfinite(P)):
        raise PathError('control points must be finite (NaN or infinity found)')
    return bounds(P)


def bbox(path: Path, transform: AffineLike = None, stroke: Any = None,
         tolerance: float = 0.25) -> Box:
    """Exact bounding box of a path.

    Parameters
    ----------
    path : raster.geometry.path.Path
    transform : raster.geometry.transform.Affine or None, optional
        Applied to the control points first: the result is the exact box of
        the transformed path (not the transformed box).
    stroke : StrokeStyle, dict or None, optional
        When given, the box of the *stroke* instead of the fill: the path is
        stroked with :func:`raster.geometry.stroking.stroke` (a dict is passed as
        keyword arguments, anything else as the style) in device space and
        the exact box of that outline is returned.  The outline itself is
        within ``tolerance`` of the true stroke, so this box is too.  A
        stroke that draws nothing (zero width) gives the fill box.
    tolerance : float, optional
        Device-pixel tolerance of the stroke outline (only with ``stroke``).

    Returns
    -------
    (xmin, ymin, xmax, ymax) : tuple of float

    Raises
    ------
    PathError
        Not a path, or coordinates non-finite after the transform, or the
        path draws nothing: no segment and no closed lone point
        (``M x y Z`` counts as its point; a lone ``M x y`` is ignored, as in
        :func:`raster.flatten`).

    Examples
    --------
    >>> from raster.geometry.pathdata import parse_path
    >>> bbox(parse_path('M 0 0 C 0 4 4 4 4 0'))
    (0.0, 0.0, 4.0, 3.0)
    """
    if stroke is not None:
        if isinstance(stroke, dict):
            outline = _stroke(path, transform=transform, tolerance=tolerance, **stroke)
        else:
            outline = _stroke(path, stroke, transform=transform, tolerance=tolerance)
        if not outline.is_empty:
            return bbox(outline)
    if not callable(getattr(path, 'segments', None)):
        raise PathError('bbox needs a raster.Path, got %s' % type(path).__name__)
    seg = path.segments()
    t = as_affine(transform)
    ctrl = seg.ctrl
    lone = seg.contour_start[(seg.contour_nseg == 0) & seg.contour_closed]
    if not t.is_identity:
        ctrl = t.apply(ctrl)
        lone = t.apply(lone)
        if not (np.all(np.isfinite(ctrl)) and np.all(np.isfinite(lone))):
            raise PathError('transformed path has non-finite coordinates')
    if len(ctrl) == 0 and len(lone) == 0:
        raise PathError('path draws nothing: it has no bounding box')
    los, his = [lone], [lone]
    if len(ctrl):
        lo, hi = segment_bounds(ctrl, seg.degree)
        los.append(lo)
        his.append(hi)
    lo = np.concatenate(los).min(axis=0)
    hi = np.concatenate(his).max(axis=0)
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))
