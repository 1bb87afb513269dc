"""Image comparison for conformance testing.

The pass criterion is the one the project's conformance scorer uses against
the resvg test suite (see ``shared/conformance/README.md``), implemented here
independently so the library can judge its own renders:

1. Both images are turned into premultiplied 8-bit RGBA
   (``c' = (c * a + 127) // 255`` per colour channel, alpha unchanged).
2. For every pixel of either image we take the other image's per-channel
   ``[min, max]`` over the ``(2r+1) x (2r+1)`` neighbourhood of the same
   position (edges replicated) and measure how far the pixel lies outside
   that range (0 inside).  The cost of a pixel position is the maximum over
   the four channels and over both directions.
3. The images pass when their sizes match and

   * coarse check (``r = 2``): at most :data:`CRITERION` ``['F']`` percent of
     the pixels cost more than ``['T']`` (0.05 % over 24), and
   * fine check (``r = 1``): at most ``['F2']`` percent of the pixels cost
     more than ``['T2']`` (1.5 % over 32).

Anti-aliased edge pixels always lie between the extremes of a window that
straddles the edge, so coverage differences and edges moved by a pixel or two
cost nothing, while missing, extra or recoloured content costs its full
difference.

Images are ``(H, W, 4) uint8`` arrays of *straight* (not premultiplied) RGBA,
row 0 at the top.

>>> import numpy as np
>>> a = np.zeros((20, 20, 4), np.uint8); a[5:15, 5:15] = 255
>>> b = np.roll(a, 1, axis=1)                  # the square moved by 1 px
>>> compare_images(a, b).passed
True
>>> c = a.copy(); c[5:15, 5:15, :3] = (255, 0, 0)   # recoloured
>>> r = compare_images(a, c)
>>> r.passed, r.max_diff
(False, 255)
"""

from typing import NamedTuple, Optional, Tuple

import numpy as np

from .errors import RasterError

__all__ = ['CRITERION', 'COARSE_RADIUS', 'FINE_RADIUS', 'Comparison', 'ComparisonError',
           'compare_images', 'premultiply8', 'range_diff', 'diff_strip', 'over_white',
           'SUITE_GENERIC_FAMILIES', 'SUITE_DEFAULT_FAMILY', 'suite_fonts']

#: Pass thresholds: ``T``/``F`` for the coarse check (costs beyond a 5x5
#: window above ``T`` on at most ``F`` percent of the pixels), ``T2``/``F2``
#: for the fine check (3x3 window).
CRITERION = {'T': 24, 'F': 0.05, 'T2': 32, 'F2': 1.5}

#: Neighbourhood radius of the coarse check (5x5 window).
COARSE_RADIUS = 2
#: Neighbourhood radius of the fine check (3x3 window).
FINE_RADIUS = 1


#: The generic families of resvg's test harness (its fontconfig mapping
#: over the resvg suite's fonts), and the family of text without a
#: ``font-family`` (usvg's default): what the conformance harness and the
#: golden text cases render with, so that their references are reproducible.
SUITE_GENERIC_FAMILIES = {'serif': 'Noto Serif', 'sans-serif': 'Noto Sans',
                          'cursive': 'Yellowtail', 'fantasy': 'Sedgwick Ave Display',
                          'monospace': 'Noto Mono'}
SUITE_DEFAULT_FAMILY = 'Times New Roman'


def suite_fonts(fonts_dir):
    """The :class:`raster.FontOptions` of the resvg suite's fonts only (the
    folder ``fonts_dir``, no system fonts) with the harness's generic
    families (:data:`SUITE_GENERIC_FAMILIES`) and default family."""
    from .fonts import FontOptions
    g = SUITE_GENERIC_FAMILIES
    return FontOptions(dirs=(fonts_dir,), system=False, serif_family=g['serif'],
                       sans_serif_family=g['sans-serif'], monospace_family=g['monospace'],
                       cursive_family=g['cursive'], fantasy_family=g['fantasy'],
                       default_family=SUITE_DEFAULT_FAMILY)


class ComparisonError(RasterError, ValueError):
    """An image given to :func:`compare_images` or :func:`diff_strip` is not
    an ``(H, W, 4)`` uint8 RGBA array."""


class Comparison(NamedTuple):
    """Result of :func:`compare_images`.

    Attributes
    ----------
    passed : bool
        True when the sizes match and both checks hold.
    bad_pct : float
        Percentage of pixels failing the coarse check (rounded to 4
        decimals); 100.0 when the sizes differ.
    fine_bad_pct : float
        Percentage of pixels failing the fine check (rounded to 4 decimals);
        100.0 when the sizes differ.
    max_diff : int
        Largest plain per-channel difference of the premultiplied images
        (0..255); 255 when the sizes differ.
    reason : str or None
        Why the comparison failed (None when it passed).
    maps : tuple of three (H, W) int16 ndarrays, or None
        ``(plain, fine, coarse)`` per-pixel costs: the plain premultiplied
        difference, the ``r = 1`` and the ``r = 2`` range costs.  None when
        the sizes differ.
    """
    passed: bool
    bad_pct: float
    fine_bad_pct: float
    max_diff: int
    reason: Optional[str]
    maps: Optional[Tuple[np.ndarray, np.ndarray, np.ndarray]]


def _as_rgba8(img, name):
    if hasattr(img, 'mode') and hasattr(img, 'convert'):      # a PIL image
        img = np.asarray(img.convert('RGBA'))
    arr = np.asarray(img)
    if arr.dtype != np.uint8 or arr.ndim != 3 or arr.shape[2] != 4:
        raise ComparisonError('%s image must be an (H, W, 4) uint8 RGBA array, got %s %s'
                              % (name, arr.dtype, arr.shape))
    return arr


def premultiply8(rgba):
    """Straight RGBA8 to premultiplied RGBA8, rounding half up.

    Parameters
    ----------
    rgba : (H, W, 4) uint8 ndarray
        Straight-alpha colours.

    Returns
    -------
    (H, W, 4) uint8 ndarray
        ``(c * a + 127) // 255`` for R, G, B; alpha unchanged.

    >>> premultiply8(np.array([[[255, 128, 0, 128]]], np.uint8)).tolist()
    [[[128, 64, 0, 128]]]
    """
    x = np.asarray(rgba, dtype=np.uint16)
    out = np.empty(x.shape, np.uint8)
    a = x[..., 3:4]
    out[..., :3] = (x[..., :3] * a + 127) // 255
    out[..., 3] = x[..., 3]
    return out


def _window_extremes(x, r):
    """Per-channel min and max over the (2r+1)^2 window, edge-replicated.

    ``x`` is (H, W, C) uint8; the filter is separable (rows, then columns)."""
    h, w = x.shape[:2]
    p = np.pad(x, ((r, r), (0, 0), (0, 0)), mode='edge')
    lo = p[0:h].copy()
    hi = lo.copy()
    for k in range(1, 2 * r + 1):
        np.minimum(lo, p[k:k + h], out=lo)
        np.maximum(hi, p[k:k + h], out=hi)
    plo = np.pad(lo, ((0, 0), (r, r), (0, 0)), mode='edge')
    phi = np.pad(hi, ((0, 0), (r, r), (0, 0)), mode='edge')
    lo = plo[:, 0:w].copy()
    hi = phi[:, 0:w].copy()
    for k in range(1, 2 * r + 1):
        np.minimum(lo, plo[:, k:k + w], out=lo)
        np.maximum(hi, phi[:, k:k + w], out=hi)
    return lo, hi


def _outside(src, lo, hi):
    s = src.astype(np.int16)
    over = s - hi.astype(np.int16)
    under = lo.astype(np.int16) - s
    return np.maximum(np.maximum(over, under), 0).max(-1)


def range_diff(p8, q8, r):
    """Neighbourhood-tolerant cost of two premultiplied images.

    Parameters
    ----------
    p8, q8 : (H, W, 4) uint8 ndarray
        Premultiplied RGBA images of the same size.
    r : int
        Window radius (the window is ``(2r+1) x (2r+1)`` pixels).

    Returns
    -------
    (H, W) int16 ndarray
        For each position, how far (0..255) either image's pixel lies outside
        the other image's per-channel window range, maximised over channels
        and directions.

    >>> a = np.zeros((3, 3, 4), np.uint8); b = a.copy(); b[1, 1] = 200
    >>> int(range_diff(a, b, 1)[1, 1]), int(range_diff(a, b, 1)[0, 0])
    (200, 0)
    """
    plo, phi = _window_extremes(p8, r)
    qlo, qhi = _window_extremes(q8, r)
    return np.maximum(_outside(p8, qlo, qhi), _outside(q8, plo, phi))


def compare_images(expected_rgba8, actual_rgba8, criterion=None):
    """Judge a render against a reference image.

    Parameters
    ----------
    expected_rgba8, actual_rgba8 : (H, W, 4) uint8 ndarray (or PIL images)
        Straight-alpha RGBA, row 0 at the top.
    criterion : dict, optional
        Overrides for :data:`CRITERION` (keys ``T``, ``F``, ``T2``, ``F2``).

    Returns
    -------
    Comparison

    Raises
    ------
    ComparisonError
        If an input is not an (H, W, 4) uint8 image.

    >>> z = np.zeros((4, 4, 4), np.uint8)
    >>> compare_images(z, z).passed
    True
    >>> compare_images(z, np.zeros((4, 5, 4), np.uint8)).reason
    'size 5x4 != expected 4x4'
    """
    crit = dict(CRITERION)
    if criterion:
        crit.update(criterion)
    e = _as_rgba8(expected_rgba8, 'expected')
    a = _as_rgba8(actual_rgba8, 'actual')
    if e.shape != a.shape:
        return Comparison(False, 100.0, 100.0, 255,
                          'size %dx%d != expected %dx%d' % (a.shape[1], a.shape[0],
                                                            e.shape[1], e.shape[0]), None)
    pe, pa = premultiply8(e), premultiply8(a)
    plain = np.abs(pe.astype(np.int16) - pa.astype(np.int16)).max(-1)
    npx = plain.size
    if npx == 0:
        return Comparison(True, 0.0, 0.0, 0, None, (plain, plain, plain))
    if plain.any():
        fine = range_diff(pe, pa, FINE_RADIUS)
        coarse = range_diff(pe, pa, COARSE_RADIUS)
    else:
        fine = coarse = plain
    bad = round(100.0 * int(np.count_nonzero(coarse > crit['T'])) / npx, 4)
    fine_bad = round(100.0 * int(np.count_nonzero(fine > crit['T2'])) / npx, 4)
    why = []
    if bad > crit['F']:
        why.append('%.3f%% px off by >%d beyond 2px (limit %g%%)' % (bad, crit['T'], crit['F']))
    if fine_bad > crit['F2']:
        why.append('%.2f%% px off by >%d beyond 1px (limit %g%%)'
                   % (fine_bad, crit['T2'], crit['F2']))
    return Comparison(not why, bad, fine_bad, int(plain.max()), '; '.join(why) or None,
                      (plain, fine, coarse))


def over_white(rgba8):
    """Straight RGBA8 composited over white: (H, W, 3) uint8.

    >>> over_white(np.array([[[0, 0, 0, 0], [0, 0, 0, 255]]], np.uint8)).tolist()
    [[[255, 255, 255], [0, 0, 0]]]
    """
    x = np.asarray(rgba8, dtype=np.float32)
    al = x[..., 3:4] / 255.0
    return np.clip(x[..., :3] * al + 255.0 * (1.0 - al) + 0.5, 0, 255).astype(np.uint8)


#: Diff panel colours: coarse failure, fine-only failure, tolerated difference.
DIFF_COLOURS = {'coarse': (230, 0, 0), 'fine': (255, 150, 0), 'tolerated': (110, 160, 255)}


def diff_strip(expected, actual, comparison, gap=4):
    """A side-by-side picture ``expected | diff | actual`` for eyeballing.

    Both images are shown over white.  The middle panel is a faded copy of
    the expected image with pixels failing the coarse check in red, pixels
    failing only the fine check in orange and pixels that differ (plain
    difference > 2) but are tolerated in blue.  When the sizes differ (no
    maps) the middle panel is solid red.  Panels are separated by ``gap``
    columns of grey.

    Parameters
    ----------
    expected, actual : (H, W, 4) uint8 ndarray
        Straight RGBA; ``actual`` may be None (render failed).
    comparison : Comparison or None
        From :func:`compare_images` on the same images.

    Returns
    -------
    (max(He, Ha), 3 * max(We, Wa) + 2 * gap, 3) uint8 ndarray

    >>> z = np.zeros((5, 6, 4), np.uint8)
    >>> diff_strip(z, z, compare_images(z, z)).shape
    (5, 26, 3)
    """
    e = _as_rgba8(expected, 'expected')
    a = None if actual is None else _as_rgba8(actual, 'actual')
    he, we = e.shape[:2]
    ha, wa = a.shape[:2] if a is not None else (he, we)
    h, w = max(he, ha), max(we, wa)
    out = np.full((h, 3 * w + 2 * gap, 3), 96, np.uint8)
    out[:he, :we] = over_white(e)
    if a is not None:
        x = 2 * (w + gap)
        out[:ha, x:x + wa] = over_white(a)
    panel = np.empty((h, w, 3), np.uint8)
    panel[:] = DIFF_COLOURS['coarse']
    maps = comparison.maps if comparison is not None else None
    if maps is not None and a is not None and e.shape == a.shape:
        plain, fine, coarse = maps
        g = over_white(e).astype(np.float32).mean(-1, keepdims=True)
        sub = np.repeat((255.0 - (255.0 - g) * 0.25).astype(np.uint8), 3, -1)
        crit = CRITERION
        sub[plain > 2] = DIFF_COLOURS['tolerated']
        sub[fine > crit['T2']] = DIFF_COLOURS['fine']
        sub[coarse > crit['T']] = DIFF_COLOURS['coarse']
        panel[:he, :we] = sub
    out[:, w + gap:2 * w + gap] = panel
    return out


# -- reference coverage --------------------------------------------------------
# Coverage of shapes known exactly (discs, polygons, round-capped strokes of
# polylines), for measuring a rasterizer's edge error: each pixel row is cut
# by ``lines`` horizontal sample lines (midpoint rule in y) and the covered
# length of every line inside every pixel is computed exactly.  The error is
# that of the midpoint rule in y: O(1 / lines**2) per pixel for smooth
# edges, at most about one line's share (1 / lines) where a vertex or a
# horizontal edge sits inside the pixel.

def span_coverage(spans, width: int, height: int, lines: int = 64,
                  rows: int = 64) -> np.ndarray:
    """Reference coverage from covered intervals along sample lines.

    Parameters
    ----------
    spans : callable
        ``spans(ys)`` with ``ys`` a (L,) float64 ndarray of sample heights
        returns ``(line, x0, x1)``: (K,) int64 indices into ``ys`` and
        (K,) float64 ends of covered x-intervals on those lines.  The
        intervals of one line must not overlap (they are added).
    width, height : int
        The canvas in pixels.
    lines : int
        Sample lines per pixel row (>= 1).
    rows : int
        Pixel rows computed at once (memory: ``rows * lines * width``
        float64).

    Returns
    -------
    (height, width) float64 ndarray
        Coverage in [0, 1].

    >>> cov = span_coverage(disc_spans([(2.0, 2.0, 1.0)]), 4, 4, lines=256)
    >>> round(float(cov.sum()), 3)       # pi r**2
    3.142
    """
    out = np.zeros((height, width))
    for r0 in range(0, height, rows):
        r1 = min(height, r0 + rows)
        ys = r0 + (np.arange((r1 - r0) * lines) + 0.5) / lines
        li, a, b = spans(ys)
        a = np.clip(np.asarray(a, np.float64), 0, width)
        b = np.clip(np.asarray(b, np.float64), 0, width)
        ok = b > a
        li, a, b = np.asarray(li, np.int64)[ok], a[ok], b[ok]
        n = len(ys)
        cov = np.zeros((n, width + 2))
        ja = np.minimum(np.floor(a).astype(np.int64), width - 1)
        jb = np.minimum(np.floor(b).astype(np.int64), width)
        same = ja == jb
        np.add.at(cov, (li[same], ja[same]), b[same] - a[same])
        d = ~same
        np.add.at(cov, (li[d], ja[d]), ja[d] + 1 - a[d])
        np.add.at(cov, (li[d], jb[d]), b[d] - jb[d])
        full = np.zeros((n, width + 2))
        np.add.at(full, (li[d], ja[d] + 1), 1.0)
        np.add.at(full, (li[d], jb[d]), -1.0)
        cov += np.cumsum(full, axis=1)
        out[r0:r1] = cov[:, :width].reshape(r1 - r0, lines, width).mean(axis=1)
    return np.clip(out, 0.0, 1.0)


def disc_spans(discs):
    """``spans`` of :func:`span_coverage` for the union of disjoint discs
    ``(cx, cy, r)``."""
    d = np.asarray(discs, np.float64).reshape(-1, 3)

    def fn(ys):
        dy = ys[None, :] - d[:, 1:2]
        m = np.abs(dy) < d[:, 2:3]
        k, li = np.nonzero(m)
        hw = np.sqrt(d[k, 2] ** 2 - dy[k, li] ** 2)
        return li, d[k, 0] - hw, d[k, 0] + hw
    return fn


def _crossings(edges, ys):
    """Crossings of edges ((E, 2, 2)) with horizontal lines ys (sorted):
    (line, x, direction) with each edge half-open in y."""
    x0, y0, x1, y1 = edges[:, 0, 0], edges[:, 0, 1], edges[:, 1, 0], edges[:, 1, 1]
    lo, hi = np.minimum(y0, y1), np.maximum(y0, y1)
    i0 = np.searchsorted(ys, lo, 'left')
    i1 = np.searchsorted(ys, hi, 'left')
    cnt = i1 - i0
    own = np.repeat(np.arange(len(edges)), cnt)
    li = np.repeat(i0, cnt) + np.arange(int(cnt.sum())) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    y = ys[li]
    xe = x0[own] + (y - y0[own]) * (x1[own] - x0[own]) / (y1[own] - y0[own])
    s = np.where(y1[own] > y0[own], 1, -1)
    return li, xe, s


def polygon_spans(polygons, rule: str = 'nonzero'):
    """``spans`` of :func:`span_coverage` for closed polygons ((n_i, 2)
    vertex arrays, any orientation, crossing themselves and each other)
    filled with ``rule`` ('nonzero' or 'evenodd') as one shape."""
    e = np.concatenate([np.stack([p, np.roll(p, -1, axis=0)], axis=1)
                        for p in (np.asarray(q, np.float64) for q in polygons)])
    e = e[e[:, 0, 1] != e[:, 1, 1]]

    def fn(ys):
        li, xc, s = _crossings(e, ys)
        o = np.lexsort((xc, li))
        li, xc, s = li[o], xc[o], s[o]
        cs = np.cumsum(s)
        first = np.r_[True, li[1:] != li[:-1]] if len(li) else np.zeros(0, bool)
        base = (cs - s)[first][np.cumsum(first) - 1]
        wnd = cs - base
        inside = (wnd != 0) if rule == 'nonzero' else (wnd % 2 != 0)
        same = np.r_[li[1:] == li[:-1], False]
        m = inside & same
        nxt = np.r_[xc[1:], 0.0]
        return li[m], xc[m], nxt[m]
    return fn


def capsule_spans(points, r: float):
    """``spans`` of :func:`span_coverage` for the stroke of a polyline
    ((n, 2) points) of width ``2 r`` with round joins and caps: the union
    of the capsules (points within ``r`` of a segment) of its segments."""
    p = np.asarray(points, np.float64)
    a, b = p[:-1], p[1:]

    def fn(ys):
        # the lines each segment's capsule can reach
        y0 = np.minimum(a[:, 1], b[:, 1]) - r
        y1 = np.maximum(a[:, 1], b[:, 1]) + r
        i0 = np.searchsorted(ys, y0, 'left')
        cnt = np.searchsorted(ys, y1, 'right') - i0
        seg = np.repeat(np.arange(len(a)), cnt)
        li = np.repeat(i0, cnt) + np.arange(int(cnt.sum())) - np.repeat(np.cumsum(cnt) - cnt, cnt)
        y = ys[li]
        ax, ay, bx, by = a[seg, 0], a[seg, 1], b[seg, 0], b[seg, 1]
        lo = np.full(len(seg), np.inf)
        hi = np.full(len(seg), -np.inf)
        for cx, cy in ((ax, ay), (bx, by)):           # the two end discs
            dy = y - cy
            m = np.abs(dy) < r
            hw = np.sqrt(np.maximum(r * r - dy * dy, 0.0))
            lo = np.where(m, np.minimum(lo, cx - hw), lo)
            hi = np.where(m, np.maximum(hi, cx + hw), hi)
        # the rectangle: |cross| <= r L and 0 <= dot <= L^2, linear in x
        dx, dyv = bx - ax, by - ay
        L2 = dx * dx + dyv * dyv
        Ln = np.sqrt(L2)
        with np.errstate(all='ignore'):
            # cross(x) = dx (y - ay) - dy (x - ax), dot(x) = dx (x - ax) + dy (y - ay)
            c0 = dx * (y - ay) + dyv * ax            # cross = c0 - dy x
            d0 = -dx * ax + dyv * (y - ay)           # dot = d0 + dx x
            xl = np.full(len(seg), -np.inf)
            xh = np.full(len(seg), np.inf)
            for coef, const, lo_v, hi_v in ((-dyv, c0, -r * Ln, r * Ln), (dx, d0, 0.0, L2)):
                pos, neg, zero = coef > 0, coef < 0, coef == 0
                t1 = (lo_v - const) / coef
                t2 = (hi_v - const) / coef
                xl = np.where(pos, np.maximum(xl, t1), np.where(neg, np.maximum(xl, t2), xl))
                xh = np.where(pos, np.minimum(xh, t2), np.where(neg, np.minimum(xh, t1), xh))
                bad = zero & ((const < lo_v) | (const > hi_v))
                xh = np.where(bad, -np.inf, xh)
        rect = (xh > xl) & (L2 > 0)
        lo = np.where(rect, np.minimum(lo, xl), lo)
        hi = np.where(rect, np.maximum(hi, xh), hi)
        m = hi > lo
        li, lo, hi = li[m], lo[m], hi[m]
        # union of the intervals of each line
        o = np.lexsort((lo, li))
        li, lo, hi = li[o], lo[o], hi[o]
        if len(li) == 0:
            return li, lo, hi
        first = np.r_[True, li[1:] != li[:-1]]
        grp = np.cumsum(first) - 1
        # running maximum of hi within each line: lines lifted apart by more
        # than any interval's extent
        lift = grp * (hi.max() - lo.min() + 1.0)
        run_hi = np.maximum.accumulate(hi + lift) - lift
        new = first.copy()
        new[1:] |= lo[1:] > run_hi[:-1]
        k = np.cumsum(new) - 1
        out_lo = lo[new]
        out_hi = np.full(int(new.sum()), -np.inf)
        np.maximum.at(out_hi, k, hi)
        return li[new], out_lo, out_hi
    return fn
