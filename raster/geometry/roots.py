r"""Real roots of polynomials: the one place for the root solvers of the
kernel and of the curve toolkit.

* :func:`solve_quadratic` -- ``a t**2 + b t + c = 0``, elementwise over
  arrays of coefficients, in the cancellation-free form;
* :func:`solve_cubic` -- ``a t**3 + b t**2 + c t + d = 0``, elementwise, in
  closed form (trigonometric for three real roots, Cardano's with the
  cancellation-free choice of cube root for one) followed by Newton steps on
  the given polynomial;
* :func:`unit_interval_roots` -- the real roots in (0, 1) of many
  polynomials of one degree (any degree) at once, as Bezier extrema need.

Coefficients are float64; a root that does not exist (negative
discriminant, a degenerate polynomial) is NaN.  Roots are invariant under
scaling all coefficients of one polynomial, which the solvers use to keep
squares and cubes of coefficients away from overflow and underflow.

>>> solve_quadratic(1.0, -3.0, 2.0).tolist()
[1.0, 2.0]
>>> [round(r, 12) for r in solve_cubic(1.0, -6.0, 11.0, -6.0).tolist()]
[1.0, 2.0, 3.0]
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Tuple

import numpy as np
if TYPE_CHECKING:              # numpy.typing costs 1 ms of every start-up
    from numpy.typing import ArrayLike

__all__ = ['solve_quadratic', 'solve_cubic', 'unit_interval_roots']

# A cubic whose leading coefficient is below this fraction of its largest
# coefficient is solved as a quadratic: its remaining root lies beyond
# 1e60 (relative to the other coefficients), and powers of the normalised
# coefficients up to the fourth must stay finite.
_CUBIC_LEAD = 1e-60
_EPS = np.finfo(np.float64).eps


def _normalised(*coefs):
    """Coefficient arrays broadcast to one shape and scaled, per polynomial,
    by the power of two that brings the largest magnitude into [0.5, 1).
    Scaling by a power of two is exact, so the roots (and every rounding
    step of the solvers) are those of the unscaled coefficients, short of
    the overflow or underflow it avoids."""
    cs = np.broadcast_arrays(*(np.asarray(v, dtype=np.float64) for v in coefs))
    m = np.abs(cs[0])
    for v in cs[1:]:
        m = np.maximum(m, np.abs(v))
    _, e = np.frexp(m)
    return [np.ldexp(v, -e) for v in cs]


def solve_quadratic(a: ArrayLike, b: ArrayLike, c: ArrayLike, *,
                    normalize: bool = True) -> np.ndarray:
    """Real roots of ``a t**2 + b t + c = 0``, elementwise.

    With ``q = -(b + sign(b) sqrt(b**2 - 4 a c)) / 2`` the roots are
    ``q / a`` and ``c / q``: no subtraction of nearly equal numbers, so
    both roots keep full relative precision even when ``b**2 >> |4 a c|``.
    A zero (or tiny) ``a`` degrades gracefully to the linear root
    ``-c / b``; ``q / a`` is then infinite or huge.

    Parameters
    ----------
    a, b, c : array_like of float, broadcastable to one shape ``(...)``
    normalize : bool, optional
        Scale each polynomial's coefficients by a power of two first (exact)
        so that the largest has magnitude in [0.5, 1) and ``b**2`` and
        ``4 a c`` can neither overflow nor underflow (default).  The result
        is the same bit for bit without it for coefficients within about
        ``1e-150 .. 1e150``: callers that know theirs are may skip it.

    Returns
    -------
    (2, ...) float64 ndarray
        The two roots, ascending, NaN where there is none: both NaN for a
        negative discriminant or ``a = b = 0``, the second NaN for a linear
        polynomial (``a = 0``).  A double root appears twice.

    Examples
    --------
    >>> solve_quadratic(0.0, 2.0, -1.0).tolist()         # linear: 2 t - 1
    [0.5, nan]
    >>> solve_quadratic([1.0, 1.0], [0.0, 2.0], [1.0, 1.0]).tolist()
    [[nan, -1.0], [nan, -1.0]]
    """
    if normalize:
        a, b, c = _normalised(a, b, c)
    else:
        a, b, c = _broadcast(a, b, c)
    return _quadratic(a, b, c, False)


def _broadcast(*coefs):
    """float64 arrays of one shape (the inputs themselves when they are)."""
    if all(type(v) is np.ndarray and v.dtype == np.float64 for v in coefs) and \
            all(v.shape == coefs[0].shape for v in coefs):
        return coefs
    return np.broadcast_arrays(*(np.asarray(v, dtype=np.float64) for v in coefs))


def _quadratic(a, b, c, keep_double):
    """:func:`solve_quadratic` of float64 arrays of one shape; with
    ``keep_double`` a negative discriminant within ``1024 eps (b**2 +
    4 |a c|)`` counts as zero (the quadratics left by deflating a cubic
    carry the rounding of the deflation), so that a double root is
    reported twice rather than lost to the sign of rounding noise."""
    out = np.empty((2,) + a.shape)
    with np.errstate(all='ignore'):
        disc = b * b - 4.0 * a * c
        if keep_double:
            noise = (disc < 0) & (disc >= -1024.0 * _EPS * (b * b + np.abs(4.0 * a * c)))
            disc = np.where(noise, 0.0, disc)
        sq = np.sqrt(disc)                             # NaN for a negative discriminant
        q = -0.5 * (b + np.where(b >= 0, sq, -sq))
        r1, r2 = out[0, ...], out[1, ...]           # views, also for 0-d input
        np.divide(q, a, out=r1)
        np.divide(c, q, out=r2)
    zq = q == 0
    if zq.any():
        # b = 0 and a c = 0: with a != 0 the root is 0 (c = 0, or a c
        # underflowed), with a = b = 0 there is none
        r2[zq] = np.where(a[zq] != 0, 0.0, np.nan)
    # no root: NaN or infinite (a = 0, overflow).  Sort with those as +inf,
    # so that they come last, then make them NaN.
    out[~np.isfinite(out)] = np.inf
    lo = np.minimum(r1, r2)
    np.maximum(r1, r2, out=r2)
    r1[...] = lo
    out[out == np.inf] = np.nan
    return out


def _horner(coefs, x):
    """Value and derivative of the polynomial with coefficients ``coefs``
    (highest order first, arrays broadcasting with ``x``) at ``x``."""
    val = np.zeros_like(x)
    der = np.zeros_like(x)
    for cf in coefs:
        der = der * x + val
        val = val * x + cf
    return val, der


def _polish(coefs, x, steps):
    """Newton steps on the polynomial ``coefs`` (highest first) from the
    estimates ``x`` (NaN entries stay NaN); a step is taken only where it
    makes the residual smaller, so a converged root is never moved off."""
    with np.errstate(all='ignore'):
        f, df = _horner(coefs, x)
        for _ in range(steps):
            step = f / df
            nx = x - step
            nf, ndf = _horner(coefs, nx)
            better = np.isfinite(nx) & (np.abs(nf) < np.abs(f))
            x = np.where(better, nx, x)
            f = np.where(better, nf, f)
            df = np.where(better, ndf, df)
    return x


def solve_cubic(a: ArrayLike, b: ArrayLike, c: ArrayLike, d: ArrayLike) -> np.ndarray:
    """Real roots of ``a t**3 + b t**2 + c t + d = 0``, elementwise.

    Each cubic is scaled by a power of two (largest coefficient magnitude
    in [0.5, 1)), made monic, ``t**3 + 3 p t**2 + 3 r t + s``, and its
    variable scaled by a power of two of the size of its roots (all exact
    steps, so no square or product of coefficients under- or overflows).
    With ``e = r - p**2``, ``f = s - r p`` and ``g = p s - r**2`` the
    discriminant is ``4 e g - f**2`` (positive: three distinct real roots)
    and the shift ``t = y - p`` leaves ``y**3 + 3 e y + (f - 2 p e)``.  Of the closed-form
    roots (trigonometric for three real roots, with the angle from
    ``atan2`` rather than ``arccos`` of a rounded ratio; Cardano's formula
    with the cube root on the side that does not cancel for one) only the
    one of largest magnitude is kept: the shift by ``p`` costs the others
    their accuracy when the roots differ much in size.  It is refined by
    Newton steps and divided out (from the constant term when it is larger
    than the geometric mean of the roots' magnitudes, else from the leading
    term: the stable direction of each), and the remaining quadratic is
    solved by :func:`solve_quadratic`.  Two Newton steps on the normalised
    cubic, taken only where they lower the residual, finish all roots.

    Parameters
    ----------
    a, b, c, d : array_like of float, broadcastable to one shape ``(...)``

    Returns
    -------
    (3, ...) float64 ndarray
        The real roots ascending, NaN-padded: three when the discriminant is
        positive or zero within its rounding error (a double root appears
        twice, a triple root three times), otherwise one.  A leading
        coefficient below ``1e-60`` of the largest one (zero included) is
        treated as zero: the roots of the quadratic ``b t**2 + c t + d`` are
        returned (a root beyond ``1e60`` times the others' scale is left
        out).

    Notes
    -----
    A root of multiplicity ``k`` is ill-conditioned: rounding the
    coefficients by ``eps`` moves it by about ``eps**(1/k)``.  A pair of
    roots closer than about ``1e-6`` of their magnitude (a complex pair with
    such an imaginary part included) is reported as a double real root; a
    triple root may be reported once.

    Examples
    --------
    >>> r = solve_cubic(1.0, 0.0, -3.0, 2.0)              # (t - 1)**2 (t + 2)
    >>> np.allclose(r, [-2, 1, 1])
    True
    >>> solve_cubic(0.0, 1.0, -3.0, 2.0).tolist()         # a quadratic
    [1.0, 2.0, nan]
    >>> r = solve_cubic(1e-30, 1.0, -1.0, 0.21)           # 0.3, 0.7 and about -1e30
    >>> np.allclose(r, [-1e30, 0.3, 0.7], rtol=1e-14, atol=0)
    True
    """
    a, b, c, d = _normalised(a, b, c, d)
    shape = a.shape
    out = np.full((3,) + shape, np.nan)
    cub = np.abs(a) >= _CUBIC_LEAD
    if not cub.all():
        q = ~cub
        out[:2, q] = _quadratic(b[q], c[q], d[q], True)
    if not cub.any():
        return out
    A, B, C, D = a[cub], b[cub], c[cub], d[cub]
    with np.errstate(all='ignore'):
        p = B / (3.0 * A)
        r = C / (3.0 * A)
        s = D / A
        # t = sigma x with sigma a power of two of the size of the roots
        # (exact): x**3 + 3 p x**2 + 3 r x + s has coefficients of order 1,
        # whose squares and products cannot underflow or overflow
        size = np.maximum(np.maximum(np.abs(p), np.sqrt(np.abs(r))), np.cbrt(np.abs(s)))
        k = np.frexp(size)[1]
        p, r, s = np.ldexp(p, -k), np.ldexp(r, -2 * k), np.ldexp(s, -3 * k)
        e = r - p * p
        f = s - r * p
        g = p * s - r * r
        disc = 4.0 * e * g - f * f
        h = f - 2.0 * p * e                      # y**3 + 3 e y + h = 0
        three = disc >= 0
        # three real roots: 2 sqrt(-e) cos(phi / 3 + 2 pi k / 3), k = 0, 1, 2;
        # the one of largest magnitude is k = 0 for h <= 0, k = 1 for h > 0
        phi = np.arctan2(np.sqrt(np.where(disc > 0, disc, 0.0)), -h) / 3.0   # +0.0, never -0.0
        rad = 2.0 * np.sqrt(np.maximum(-e, 0.0))
        y3 = rad * np.cos(np.where(h <= 0, phi, phi + 2.0 * np.pi / 3.0))
        # one real root: u**3 = -h/2 - sign(h) sqrt(-disc / 4), y = u - e / u
        w = np.sqrt(np.where(three, 0.0, -0.25 * disc))
        u = np.cbrt(-0.5 * h - np.where(h >= 0, w, -w))
        y1 = np.where(u != 0, u - e / u, 0.0)
        x1 = np.ldexp(np.where(three, y3, y1) - p, k)
    coefs = (A, B, C, D)
    x1 = _polish(coefs, x1, 3)
    with np.errstate(all='ignore'):
        back = np.abs(x1) ** 3 * np.abs(A) > np.abs(D)
        xs = np.where(back, x1, 1.0)
        q0b = -D / xs
        q1b = (q0b - C) / xs
        q1f = B + A * x1
        q0f = C + q1f * x1
        q1 = np.where(back, q1b, q1f)
        q0 = np.where(back, q0b, q0f)
    rest = _quadratic(*_normalised(A, q1, q0), True)
    roots = _polish(coefs, np.concatenate([x1[None], rest]), 2)
    roots[~np.isfinite(roots)] = np.nan
    out[:, cub] = np.sort(roots, axis=0)
    return out


def unit_interval_roots(coef: ArrayLike,
                        margin: float = 1e-12) -> Tuple[np.ndarray, np.ndarray]:
    """Real roots in the open interval (0, 1) of many polynomials.

    Parameters
    ----------
    coef : (K, m+1) array_like of float
        Power-form coefficients, lowest order first: row ``k`` is
        ``coef[k, 0] + coef[k, 1] u + ... + coef[k, m] u**m``.
    margin : float, optional
        Roots within ``margin`` of 0 or 1 are left out (the ends of the
        interval are candidates of every bound anyway, and rounding puts
        roots at the ends on either side).

    Returns
    -------
    roots : (R,) float64 ndarray
    owner : (R,) int64 ndarray
        The row of each root.  Rows are scanned in order; the roots of one
        row are not sorted.

    Notes
    -----
    Each row is scaled by a power of two first (roots do not depend on
    scale); all-zero rows have no roots.  Degrees up to 2 use :func:`solve_quadratic`,
    degree 3 :func:`solve_cubic`, higher degrees the eigenvalues of the
    companion matrices of all rows at once (one batched LAPACK call)
    polished by Newton steps, and :func:`numpy.roots` for rows whose
    leading coefficient nearly vanishes.

    Examples
    --------
    >>> r, k = unit_interval_roots([[0.25, -1.0, 1.0], [1.0, 1.0, 0.0]])
    >>> r.tolist(), k.tolist()                           # (u - 1/2)**2; 1 + u
    ([0.5, 0.5], [0, 0])
    """
    coef = np.asarray(coef, dtype=np.float64)
    K, m1 = coef.shape
    m = m1 - 1
    scale = np.abs(coef).max(axis=1) if m1 else np.zeros(K)
    live = scale > 0
    coef = np.ldexp(coef, -np.frexp(scale)[1][:, None])    # exact: largest in [0.5, 1)
    lo, hi = margin, 1.0 - margin
    if m < 1:
        return np.zeros(0), np.zeros(0, np.int64)
    if m <= 3:
        c = [coef[:, k] for k in range(m, -1, -1)]          # highest first
        if m == 1:
            c = [np.zeros(K)] + c
        r = solve_cubic(*c) if m == 3 else solve_quadratic(*c, normalize=False)
        ok = (r > lo) & (r < hi) & live
        owner = np.broadcast_to(np.arange(K), r.shape)
        # row-major over (row, root): transpose so that rows come in order
        return r.T[ok.T], owner.T[ok.T].astype(np.int64)
    roots, owner = [], []
    lead = coef[:, m]
    batch = live & (np.abs(lead) > 1e-8)
    rows = np.nonzero(batch)[0]
    if len(rows):
        # companion matrices of all well-conditioned rows, one batched eigvals
        comp = np.zeros((len(rows), m, m))
        comp[:, 0, :] = -coef[rows, m - 1::-1] / lead[rows, None]
        comp[:, np.arange(1, m), np.arange(m - 1)] = 1.0
        ev = np.linalg.eigvals(comp)
        ok = np.abs(ev.imag) <= 1e-7 * np.maximum(1.0, np.abs(ev.real))
        r = ev.real[ok]
        own = np.repeat(rows, m).reshape(-1, m)[ok]
        near = (r > -1e-6) & (r < 1 + 1e-6)
        r, own = r[near], own[near]
        c = coef[own]
        for _ in range(3):                  # Newton polish
            val = np.zeros_like(r)
            der = np.zeros_like(r)
            for k in range(m, -1, -1):
                der = der * r + val
                val = val * r + c[:, k]
            step = np.where(der != 0, val / np.where(der != 0, der, 1.0), 0.0)
            r = np.where(np.abs(step) < 1e-3, r - step, r)
        sel = (r > lo) & (r < hi)
        roots.append(r[sel])
        owner.append(own[sel])
    for k in np.nonzero(live & ~batch)[0].tolist():     # nearly degenerate rows
        c = coef[k].copy()
        c[np.abs(c) < 1e-14] = 0.0
        nz = np.nonzero(c)[0]
        if len(nz) == 0 or nz[-1] == 0:
            continue
        r = np.roots(c[:nz[-1] + 1][::-1])
        r = r[np.abs(r.imag) <= 1e-9 * np.maximum(1.0, np.abs(r.real))].real
        r = r[(r > lo) & (r < hi)]
        roots.append(r)
        owner.append(np.full(len(r), k))
    if not roots:
        return np.zeros(0), np.zeros(0, np.int64)
    order = np.argsort(np.concatenate(owner), kind='stable')
    return np.concatenate(roots)[order], np.concatenate(owner).astype(np.int64)[order]
