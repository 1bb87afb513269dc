r"""Continuity at the joints of a chain of curve segments.

For consecutive segments ``A`` (ending at a joint) and ``B`` (starting there)
with derivatives taken with respect to the chain's global parameter:

* parametric order ``C^k``: ``A^{(j)} = B^{(j)}`` for all ``j <= k``;
* geometric order: ``G0`` = the ends meet; ``G1`` = also the unit tangents
  agree; ``G2`` = also the curvature vectors
  ``kappa N = (a - (a.v / |v|^2) v) / |v|^2`` agree (``v``, ``a``: first and
  second derivatives).  Geometric continuity does not depend on the
  parameterization; ``C^k`` with non-vanishing tangent implies ``G^k``.

Comparisons use ``|p - q| <= tolerance * max(1, |p|, |q|)``.  An order of
``-1`` means not even the positions agree.

>>> from raster.curves.bezier import PiecewiseBezier
>>> pb = PiecewiseBezier([[[0, 0], [1, 0]], [[1, 0], [3, 0]]])
>>> j = continuity(pb)[0]
>>> (j.C, j.G)
(0, 2)
"""

from typing import NamedTuple

import numpy as np

from .checks import as_scalar


class Joint(NamedTuple):
    """Continuity at one joint.

    Attributes
    ----------
    index : int
        The joint is between segment ``index`` and the next one.
    t : float
        Global parameter of the joint.
    C : int
        Highest parametric order (-1, 0, 1 or 2).
    G : int
        Highest geometric order (-1, 0, 1 or 2).
    gap : float
        Distance between the end of one segment and the start of the next.
    angle : float
        Angle between the tangents in radians (``nan`` if one vanishes).
    curvature_jump : float
        ``|kappa N_A - kappa N_B|`` (``nan`` if a tangent vanishes).
    """
    index: int
    t: float
    C: int
    G: int
    gap: float
    angle: float
    curvature_jump: float


def _close(p, q, tol):
    scale = np.maximum(1.0, np.maximum(np.linalg.norm(p, axis=-1), np.linalg.norm(q, axis=-1)))
    return np.linalg.norm(p - q, axis=-1) <= tol * scale


def _curvature_vector(v, a):
    vv = np.einsum('kd,kd->k', v, v)
    with np.errstate(divide='ignore', invalid='ignore'):
        return (a - (np.einsum('kd,kd->k', a, v) / vv)[:, None] * v) / vv[:, None]


def continuity(curve, tolerance=1e-9, closed=False):
    """Continuity orders at every joint of a piecewise curve.

    Parameters
    ----------
    curve : PiecewiseBezier or any curve with ``to_beziers()``
    tolerance : float
        Relative tolerance of the comparisons (default 1e-9).
    closed : bool
        Also check the joint from the last segment back to the first.

    Returns
    -------
    list of :class:`Joint`
    """
    pb = curve.to_beziers()
    tol = as_scalar(tolerance, 'tolerance', 0.0)
    S = len(pb)
    if S < 2 and not closed:
        return []
    left = np.arange(S - 1) if not closed else np.arange(S)
    right = (left + 1) % S
    d = [pb] + [pb.deriv(k) for k in (1, 2)]
    ends = [x.ctrl[left, -1] for x in d]
    starts = [x.ctrl[right, 0] for x in d]
    eq = [_close(ends[k], starts[k], tol) for k in range(3)]
    C = np.full(len(left), -1)
    ok = np.ones(len(left), bool)
    for k in range(3):
        ok &= eq[k]
        C[ok] = k
    va, vb = ends[1], starts[1]
    na, nb = np.linalg.norm(va, axis=1), np.linalg.norm(vb, axis=1)
    scale = np.maximum(1.0, np.maximum(np.abs(ends[0]).max(1), np.abs(starts[0]).max(1)))
    live = (na > tol * scale) & (nb > tol * scale)
    with np.errstate(divide='ignore', invalid='ignore'):
        ua, ub = va / na[:, None], vb / nb[:, None]
        cosang = np.clip(np.einsum('kd,kd->k', ua, ub), -1.0, 1.0)
        angle = np.where(live, np.arccos(cosang), np.nan)
        # robust small angles: use the chord of the unit vectors
        chord = np.linalg.norm(ua - ub, axis=1)
        angle = np.where(live, 2 * np.arcsin(np.clip(chord / 2, 0, 1)), angle)
    ka, kb = _curvature_vector(va, ends[2]), _curvature_vector(vb, starts[2])
    kjump = np.where(live, np.linalg.norm(ka - kb, axis=1), np.nan)
    G = np.where(eq[0], 0, -1)
    g1 = eq[0] & ((live & (chord <= tol)) | (C >= 1))
    G[g1] = 1
    g2 = g1 & ((live & _close(np.nan_to_num(ka), np.nan_to_num(kb), tol)) | (C >= 2))
    G[g2] = 2
    gap = np.linalg.norm(ends[0] - starts[0], axis=1)
    tj = pb.breaks[left + 1]
    return [Joint(int(i), float(t), int(c), int(g), float(gp), float(an), float(kj))
            for i, t, c, g, gp, an, kj in zip(left, tj, C, G, gap, angle, kjump)]


def format_joints(joints):
    """Human-readable table of :func:`continuity` results (str)."""
    if not joints:
        return 'no joints (single segment)'
    lines = ['joint        t  C  G          gap    angle(deg)  curvature jump']
    for j in joints:
        cs = 'C%d' % j.C if j.C >= 0 else '--'
        gs = 'G%d' % j.G if j.G >= 0 else '--'
        lines.append('%5d %8.4g %s %s %12.4g %12.6g %14.6g'
                     % (j.index, j.t, cs, gs, j.gap, np.degrees(j.angle), j.curvature_jump))
    return '\n'.join(lines)

