"""2-D affine transforms.

An :class:`Affine` is the SVG matrix ``(a, b, c, d, e, f)``, mapping a point
``(x, y)`` to ``(a*x + c*y + e, b*x + d*y + f)``.  Coordinates follow SVG and
image conventions: x grows to the right, y grows downward.

Composition reads like SVG transform lists: ``A @ B`` applies ``B`` first,
then ``A`` (so ``transform="translate(..) scale(..)"`` is
``translate @ scale``).

>>> t = Affine.translate(10, 0) @ Affine.scale(2)
>>> t.apply([[1.0, 1.0]]).tolist()
[[12.0, 2.0]]
"""

from __future__ import annotations

import math
from typing import Optional, Sequence, TYPE_CHECKING, Union

import numpy as np
if TYPE_CHECKING:              # numpy.typing costs 1 ms of every start-up
    from numpy.typing import ArrayLike

from ..errors import TransformError

#: What :func:`as_affine` accepts: an :class:`Affine`, six numbers
#: ``a b c d e f``, a 2x3 or 3x3 matrix, or None (the identity).
AffineLike = Union['Affine', Sequence[float], np.ndarray, None]


class Affine:
    """Immutable 2x3 affine transform ``(a, b, c, d, e, f)`` as in SVG."""

    __slots__ = ('a', 'b', 'c', 'd', 'e', 'f', '_hash')

    def __init__(self, a: float = 1.0, b: float = 0.0, c: float = 0.0, d: float = 1.0,
                 e: float = 0.0, f: float = 0.0) -> None:
        if not (type(a) is float and type(b) is float and type(c) is float
                and type(d) is float and type(e) is float and type(f) is float):
            try:
                a, b, c, d, e, f = float(a), float(b), float(c), float(d), float(e), float(f)
            except (TypeError, ValueError):
                raise TransformError('transform values must be numbers, got %r'
                                     % ((a, b, c, d, e, f),)) from None
        _fill(self, a, b, c, d, e, f)

    def __setattr__(self, name, value):
        raise AttributeError('Affine is immutable')

    # -- constructors -----------------------------------------------------
    @classmethod
    def identity(cls) -> 'Affine':
        return cls()

    @classmethod
    def translate(cls, tx: float, ty: float = 0.0) -> 'Affine':
        return cls(1, 0, 0, 1, tx, ty)

    @classmethod
    def scale(cls, sx: float, sy: Optional[float] = None) -> 'Affine':
        return cls(sx, 0, 0, sx if sy is None else sy, 0, 0)

    @classmethod
    def rotate(cls, degrees: float, cx: float = 0.0, cy: float = 0.0) -> 'Affine':
        r = math.radians(degrees)
        co, si = math.cos(r), math.sin(r)
        # snap tiny values so 90-degree rotations are exact
        co = 0.0 if abs(co) < 1e-15 else co
        si = 0.0 if abs(si) < 1e-15 else si
        rot = cls(co, si, -si, co, 0, 0)
        if cx or cy:
            return cls.translate(cx, cy) @ rot @ cls.translate(-cx, -cy)
        return rot

    @classmethod
    def skew_x(cls, degrees: float) -> 'Affine':
        return cls(1, 0, math.tan(math.radians(degrees)), 1, 0, 0)

    @classmethod
    def skew_y(cls, degrees: float) -> 'Affine':
        return cls(1, math.tan(math.radians(degrees)), 0, 1, 0, 0)

    @classmethod
    def from_matrix(cls, m: ArrayLike) -> 'Affine':
        """From a (2, 3) or (3, 3) array ``[[a, c, e], [b, d, f]]``."""
        m = np.asarray(m, dtype=np.float64)
        return cls(m[0, 0], m[1, 0], m[0, 1], m[1, 1], m[0, 2], m[1, 2])

    # -- algebra -----------------------------------------------------------
    def __matmul__(self, other):
        if not isinstance(other, Affine):
            return NotImplemented
        a, b, c, d, e, f = self.a, self.b, self.c, self.d, self.e, self.f
        A, B, C, D, E, F = other.a, other.b, other.c, other.d, other.e, other.f
        if A == 1.0 and B == 0.0 and C == 0.0 and D == 1.0 and E == 0.0 and F == 0.0:
            return self
        if a == 1.0 and b == 0.0 and c == 0.0 and d == 1.0 and e == 0.0 and f == 0.0:
            return other
        t = object.__new__(Affine)
        _fill(t, a * A + c * B, b * A + d * B, a * C + c * D, b * C + d * D,
              a * E + c * F + e, b * E + d * F + f)
        return t

    def inverse(self) -> 'Affine':
        det = self.determinant
        if det == 0 or not math.isfinite(1.0 / det):
            raise TransformError('transform is not invertible')
        a, b, c, d, e, f = self.a, self.b, self.c, self.d, self.e, self.f
        ia, ib, ic, id_ = d / det, -b / det, -c / det, a / det
        return Affine(ia, ib, ic, id_, -(ia * e + ic * f), -(ib * e + id_ * f))

    # -- properties --------------------------------------------------------
    @property
    def determinant(self) -> float:
        return self.a * self.d - self.b * self.c

    @property
    def matrix(self) -> np.ndarray:
        """(2, 3) float64 ndarray ``[[a, c, e], [b, d, f]]``."""
        return np.array([[self.a, self.c, self.e], [self.b, self.d, self.f]])

    @property
    def is_identity(self) -> bool:
        return (self.a == 1.0 and self.b == 0.0 and self.c == 0.0 and self.d == 1.0
                and self.e == 0.0 and self.f == 0.0)

    @property
    def is_translation(self) -> bool:
        return self.a == 1.0 and self.b == 0.0 and self.c == 0.0 and self.d == 1.0

    def max_scale(self) -> float:
        """Largest singular value: the most any length can grow."""
        a, b, c, d = self.a, self.b, self.c, self.d
        # (|q| + |r|) / 2 with q, r the conformal and anti-conformal parts:
        # no cancellation (s^2 / 4 - det^2 loses all digits when the
        # singular values are close)
        return 0.5 * (math.hypot(a + d, c - b) + math.hypot(a - d, b + c))

    def min_scale(self) -> float:
        """Smallest singular value: the least any length can grow
        (|det| / max_scale, which stays accurate for nearly singular
        transforms)."""
        big = self.max_scale()
        return abs(self.determinant) / big if big > 0 else 0.0

    def mean_scale(self) -> float:
        """sqrt(|det|): the factor a stroke width scales by on average."""
        return math.sqrt(abs(self.determinant))

    # -- application -------------------------------------------------------
    def apply(self, points: ArrayLike) -> np.ndarray:
        """Transform points.

        Parameters
        ----------
        points : (..., 2) array_like of float

        Returns
        -------
        (..., 2) float64 ndarray
        """
        p = np.asarray(points, dtype=np.float64)
        x, y = p[..., 0], p[..., 1]
        out = np.empty(p.shape, dtype=np.float64)
        out[..., 0] = self.a * x + self.c * y + self.e
        out[..., 1] = self.b * x + self.d * y + self.f
        return out

    def apply_vector(self, vectors: ArrayLike) -> np.ndarray:
        """Transform direction vectors (no translation)."""
        p = np.asarray(vectors, dtype=np.float64)
        x, y = p[..., 0], p[..., 1]
        out = np.empty(p.shape, dtype=np.float64)
        out[..., 0] = self.a * x + self.c * y
        out[..., 1] = self.b * x + self.d * y
        return out

    def __iter__(self):
        return iter((self.a, self.b, self.c, self.d, self.e, self.f))

    def __eq__(self, other):
        if self is other:
            return True
        return (isinstance(other, Affine) and self._hash == other._hash
                and self.a == other.a and self.b == other.b and self.c == other.c
                and self.d == other.d and self.e == other.e and self.f == other.f)

    def __hash__(self):
        return self._hash

    def __reduce__(self):
        return (Affine, tuple(self))

    def __repr__(self):
        return 'Affine(%g, %g, %g, %g, %g, %g)' % tuple(self)


def _fill(t, a, b, c, d, e, f, _set=object.__setattr__):
    """Set the six floats of a new Affine ``t`` (and its hash); a
    TransformError when one of them is not finite (``x * 0.0`` is 0.0 for
    every finite ``x``, NaN for infinities and NaN)."""
    if a * 0.0 + b * 0.0 + c * 0.0 + d * 0.0 + e * 0.0 + f * 0.0 != 0.0:
        raise TransformError('transform has non-finite values: %r' % ((a, b, c, d, e, f),))
    _set(t, 'a', a)
    _set(t, 'b', b)
    _set(t, 'c', c)
    _set(t, 'd', d)
    _set(t, 'e', e)
    _set(t, 'f', f)
    _set(t, '_hash', hash((a, b, c, d, e, f)))


IDENTITY = Affine()


def as_affine(t: AffineLike) -> Affine:
    """Accept None, an :class:`Affine`, 6 numbers (a..f) or a (2,3)/(3,3) array."""
    if t is None:
        return IDENTITY
    if isinstance(t, Affine):
        return t
    try:
        arr = np.asarray(t, dtype=np.float64)
    except (TypeError, ValueError):
        raise TransformError('cannot interpret %r as an affine transform' % (t,)) from None
    if arr.shape == (6,):
        return Affine(*arr)
    if arr.shape in ((2, 3), (3, 3)):
        return Affine.from_matrix(arr)
    raise TransformError('cannot interpret %r as an affine transform' % (t,))


def apply_each(m: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Map each item of ``pts`` by its own affine transform.

    Parameters
    ----------
    m : (N, 6) float64 ndarray
        One transform ``(a, b, c, d, e, f)`` per item.
    pts : (N, ..., 2) float64 ndarray
        Item ``k`` holds points (x right, y down) mapped by ``m[k]``.

    Returns
    -------
    (N, ..., 2) float64 ndarray
        ``(a x + c y + e, b x + d y + f)``: the arithmetic of
        :meth:`Affine.apply`.  Overflow is not checked (callers test the
        result for finiteness).

    >>> apply_each(np.array([[2, 0, 0, 2, 1, 0], [1, 0, 0, 1, 0, 5]], float),
    ...            np.array([[1.0, 1.0], [1.0, 1.0]])).tolist()
    [[3.0, 2.0], [1.0, 6.0]]
    """
    shape = (-1,) + (1,) * (pts.ndim - 2)
    a, b, c, d, e, f = (m[:, k].reshape(shape) for k in range(6))
    x, y = pts[..., 0], pts[..., 1]
    out = np.empty(pts.shape)
    with np.errstate(over='ignore', invalid='ignore'):
        out[..., 0] = a * x + c * y + e
        out[..., 1] = b * x + d * y + f
    return out
