"""Paths cut down to what reaches a box: the segments of a path that a
fill or stroke drawn in a rectangle of device space needs.

A window of a large render (a strip, a tile, a zoomed-in crop) needs only
the segments near it.  Both functions below look at each segment's
*device control box* (the box of its control points under the transform:
a Bezier lies in the hull of its control points, so the curve lies in the
box) and keep every segment whose box meets the window grown by a
margin unchanged, point for point, so what is drawn inside the window is
flattened and stroked exactly as from the whole path:

* :func:`cull_fill` replaces each run of other segments lying beyond one
  side of the grown window by one line joining the run's ends.  A line
  between two points beyond a side stays beyond it, and a curve and its
  chord cross every horizontal line the same net number of times, so the
  winding number at every point of the window is unchanged (fill
  coverage, either rule); anything drawn along the path within the margin
  of its segments (a hairline) is unchanged inside the window too.  The
  straddled flattening (:mod:`raster.geometry.flattening`) of a segment
  reads the end pieces of its neighbours, and theirs the tangents of the
  next, so two segments each side of a kept one are kept too: the kept
  segments flatten to the same polylines as in the whole path.
* :func:`cull_stroke` drops them, cutting contours where they were into
  open contours (a closed contour cut somewhere is rotated so the piece
  across its start stays one piece).  The stroker flattens each segment
  on its own, and the caps at the cuts lie at ends of dropped segments,
  beyond the margin: a stroke that reaches at most the margin from its
  path draws the same inside the window.  An open contour that ends
  where it started is kept whole (the stroker may seal it into a ring).  Dashes follow the arc length
  from a contour's start, so a dashed stroke must be culled after
  dashing, not before: the stroker does it (the ``window`` of
  :func:`raster.geometry.stroking.stroke`).

Both return the path itself when nothing is left out.

A square with ten segments on each of its top and bottom sides, filled
and stroked in a strip across its middle (the fill's closing line is
implied, not a segment):

>>> from raster.geometry.path import Path
>>> top = [(10.0 * i, 0.0) for i in range(11)]
>>> p = Path.polygon(top + [(100.0 - x, 100.0) for x, _ in top])
>>> cull_fill(p, None, (0, 40, 100, 60), margin=1).to_svg()
'M 0 0 L 80 0 L 90 0 L 100 0 L 100 100 L 90 100 L 80 100 L 0 100 Z'
>>> cull_stroke(p, None, (0, 40, 100, 60), reach=1).to_svg()
'M 0 100 L 0 0 M 100 0 L 100 100'

Only the top side far from the box: the rest of the stroke stays one
piece, across the contour's start:

>>> cull_stroke(p, None, (0, 40, 100, 110), reach=1).to_svg()
'M 100 0 L 100 100 L 90 100 L 80 100 L 70 100 L 60 100 L 50 100 L 40 100 L 30 100 L 20 100 L 10 100 L 0 100 L 0 0'
"""

from __future__ import annotations

from typing import Tuple

import numpy as np

from .path import CLOSE, CUBIC, LINE, MOVE, Path
from .rows import concat_ranges
from .transform import AffineLike, as_affine

__all__ = ['cull_fill', 'cull_stroke']

Box = Tuple[float, float, float, float]

# points each verb consumes (MOVE LINE QUAD CUBIC CLOSE)
_POINTS = np.array([1, 1, 2, 3, 0], np.int64)


def _device_points(path, transform):
    t = as_affine(transform)
    return path.points if t.is_identity else t.apply(path.points)


def _inside(dev, box, m):
    """Whether every device point ``dev`` lies in
    ``box`` grown by ``m``: then no segment can be left out."""
    x0, y0, x1, y1 = box
    if len(dev) <= 64:
        xs, ys = dev.T.tolist()
        return (min(xs) >= x0 - m and max(xs) <= x1 + m and min(ys) >= y0 - m
                and max(ys) <= y1 + m)
    return bool(dev[:, 0].min() >= x0 - m and dev[:, 0].max() <= x1 + m
                and dev[:, 1].min() >= y0 - m and dev[:, 1].max() <= y1 + m)


def _boxes(dev, first, last):
    """Device control boxes ``(x0, y0, x1, y1)`` of segments whose points
    are ``dev[first..last]`` (2 to 4 consecutive points each)."""
    xs, ys = dev[:, 0], dev[:, 1]
    x0, y0 = xs[first], ys[first]          # (copies: indexed)
    x1, y1 = x0.copy(), y0.copy()
    for k in range(1, 4):
        idx = np.minimum(first + k, last)
        xk, yk = xs[idx], ys[idx]
        np.minimum(x0, xk, out=x0)
        np.maximum(x1, xk, out=x1)
        np.minimum(y0, yk, out=y0)
        np.maximum(y1, yk, out=y1)
    return x0, y0, x1, y1


def _zones(boxes, box, m):
    """(S,) int8: 0 for a segment whose box meets ``box`` grown by ``m``,
    else the side it lies beyond (1 above, 2 below, 3 left, 4 right; the
    first that holds)."""
    x0, y0, x1, y1 = boxes
    bx0, by0, bx1, by1 = box
    z = np.zeros(len(x0), np.int8)
    for code, beyond in ((4, x0 > bx1 + m), (3, x1 < bx0 - m), (2, y0 > by1 + m),
                         (1, y1 < by0 - m)):
        z[beyond] = code
    return z


def _layout(verbs):
    npts = _POINTS[verbs]
    off = np.cumsum(npts) - npts
    draw = (verbs >= LINE) & (verbs <= CUBIC)
    return npts, off, draw


def cull_fill(path: Path, transform: AffineLike, box: Box, margin: float = 0.0) -> Path:
    """``path`` with the segments far from ``box`` replaced by lines, for
    filling (see the module docstring).

    Parameters
    ----------
    path : Path
        In user units.
    transform : Affine or None
        User space to device space.
    box : (x0, y0, x1, y1) floats
        The device rectangle drawn (infinite sides allowed).
    margin : float
        Device distance: every segment whose device control box comes
        within ``margin`` of ``box`` is kept as it is.

    Returns
    -------
    Path
        In user units; its winding number under ``transform`` equals
        ``path``'s at every point of ``box``, and its segments within
        ``margin`` of ``box`` are ``path``'s own.  ``path`` itself when
        every point lies within ``margin`` of ``box``.
    """
    dev = _device_points(path, transform)
    if len(dev) == 0 or _inside(dev, box, margin):
        return path
    verbs = path.verbs
    npts, off, draw = _layout(verbs)
    di = np.flatnonzero(draw)
    z = _zones(_boxes(dev, off[di] - 1, off[di] + npts[di] - 1), box, margin)
    if not z.any():
        return path
    # the straddled flattening of a segment reads the end pieces of its
    # neighbours, and theirs the tangents of the next: two more segments
    # each side of every kept one stay as they are
    contour_of = np.cumsum(verbs == MOVE) - 1
    dc = contour_of[di]
    nc = int(contour_of[-1]) + 1
    nseg = np.bincount(dc, minlength=nc)
    first = np.cumsum(nseg) - nseg
    closed = np.zeros(nc, bool)
    closed[contour_of[verbs == CLOSE]] = True
    last = off[di] + npts[di] - 1
    ring = closed.copy()
    has = nseg > 0
    ring[has] |= np.all(path.points[last[first[has] + nseg[has] - 1]]
                        == path.points[off[verbs == MOVE][has]], axis=1)
    z[_guard(z == 0, dc, np.arange(len(di)) - first[dc], nseg, first, ring)] = 0
    if not z.any():
        return path
    zone = np.zeros(len(verbs), np.int8)
    zone[di] = z
    nxt = np.empty_like(zone)
    nxt[:-1] = zone[1:]
    nxt[-1] = 0
    # a run of segments beyond one side becomes one line to its last end
    # (MOVE and CLOSE have zone 0, so runs never cross contours)
    run_end = (zone > 0) & (nxt != zone)
    emit = (zone == 0) | run_end
    out_verbs = np.where(run_end, np.uint8(LINE), verbs)[emit]
    counts = np.where(run_end, 1, npts)[emit]
    starts = np.where(run_end, off + npts - 1, off)[emit]
    return Path(out_verbs.astype(np.uint8), path.points[concat_ranges(starts, counts)],
                _checked=True)


def _guard(near, contour, pos, size, first, ring, width=2):
    """``near`` (elements in contour order: ``contour``, ``pos`` within
    it) grown by ``width`` elements each way along each contour, around
    the contours marked ``ring``."""
    out = near.copy()
    L = size[contour]
    base = first[contour]
    cyc = ring[contour]
    for k in range(1, width + 1):
        for step in (k, -k):
            q = pos + step
            ok = cyc | ((q >= 0) & (q < L))
            idx = base + q % np.maximum(L, 1)
            out |= ok & near[np.where(ok, idx, 0)]
    return out


def cull_stroke(path: Path, transform: AffineLike, box: Box, reach: float = 0.0) -> Path:
    """``path`` without the segments far from ``box``, for stroking (see
    the module docstring).

    Parameters
    ----------
    path : Path
        In user units.
    transform : Affine or None
        User space to device space.
    box : (x0, y0, x1, y1) floats
        The device rectangle drawn (infinite sides allowed).
    reach : float
        Device distance: every segment (and closing line) whose device
        control box comes within ``reach`` of ``box`` is kept as it is.

    Returns
    -------
    Path
        In user units: the kept segments in their order, contours cut where
        segments were left out (open from there; a contour cut anywhere
        loses its ``CLOSE``, its closing line becoming a line when kept).
        An undashed stroke reaching at most ``reach`` from the path under
        ``transform`` draws the same inside ``box``.  Contours without
        segments (a lone move, a dot) are kept.  ``path`` itself when every
        point lies within ``reach`` of ``box``.
    """
    dev = _device_points(path, transform)
    if len(dev) == 0 or _inside(dev, box, reach):
        return path
    verbs = path.verbs
    npts, off, draw = _layout(verbs)
    contour_of = np.cumsum(verbs == MOVE) - 1
    nc = int(contour_of[-1]) + 1
    move_pt = off[verbs == MOVE]
    closed = np.zeros(nc, bool)
    closed[contour_of[verbs == CLOSE]] = True
    di = np.flatnonzero(draw)
    dc = contour_of[di]
    nseg = np.bincount(dc, minlength=nc)
    # the closing line of a closed contour with segments (unless it has no
    # length): an element like the segments, drawn from the contour's last
    # point back to its move point
    last_pt = np.zeros(nc, np.int64)
    last_pt[dc] = off[di] + npts[di] - 1            # (the last write wins)
    cc = np.flatnonzero(closed & (nseg > 0))
    cc = cc[np.any(path.points[last_pt[cc]] != path.points[move_pt[cc]], axis=1)]
    # elements: (contour, position, verb, first point, point count, start point)
    e_c = np.concatenate([dc, cc])
    pos_seg = np.arange(len(di)) - (np.cumsum(nseg) - nseg)[dc]
    e_pos = np.concatenate([pos_seg, nseg[cc]])
    e_verb = np.concatenate([verbs[di], np.full(len(cc), LINE, np.uint8)])
    e_first = np.concatenate([off[di], move_pt[cc]])
    e_np = np.concatenate([npts[di], np.ones(len(cc), np.int64)])
    e_start = np.concatenate([off[di] - 1, last_pt[cc]])
    seg_boxes = _boxes(dev, off[di] - 1, off[di] + npts[di] - 1)
    a, b = dev[last_pt[cc]], dev[move_pt[cc]]
    close_boxes = (np.minimum(a[:, 0], b[:, 0]), np.minimum(a[:, 1], b[:, 1]),
                   np.maximum(a[:, 0], b[:, 0]), np.maximum(a[:, 1], b[:, 1]))
    boxes = tuple(np.concatenate([a, b]) for a, b in zip(seg_boxes, close_boxes))
    drop = _zones(boxes, box, reach) > 0
    # an open contour ending where it started may be stroked as a ring
    # (undashed butt caps: the stroker seals it): it stays whole
    sealed = ~closed & (nseg > 0)
    sealed[sealed] = np.all(path.points[last_pt[sealed]] == path.points[move_pt[sealed]], axis=1)
    drop &= ~sealed[e_c]
    if not drop.any():
        return path
    size = np.bincount(e_c, minlength=nc)
    ndrop = np.bincount(e_c, weights=drop, minlength=nc).astype(np.int64)
    whole = ndrop == 0
    # a closed contour kept whole stays as it was (its closing line implied)
    e_keep = ~(whole[e_c] & closed[e_c] & (e_pos == nseg[e_c]))
    # a closed contour cut somewhere starts after its last cut: the piece
    # across its start stays one open piece
    last_drop = np.full(nc, -1, np.int64)
    np.maximum.at(last_drop, e_c[drop], e_pos[drop])
    rot = closed & ~whole
    r = np.where(rot[e_c], (e_pos - last_drop[e_c] - 1) % np.maximum(size[e_c], 1), e_pos)
    order = np.lexsort((r, e_c))
    order = order[e_keep[order]]
    kept = ~drop[order]
    oc = e_c[order]
    prev = np.zeros(len(order), bool)
    prev[1:] = kept[:-1] & (oc[1:] == oc[:-1])
    starts_run = kept & ~prev
    # items: a move before each piece, the kept elements, CLOSE after a
    # closed contour kept whole, contours without segments as they were
    n_items = len(order)
    rank = np.arange(n_items)
    parts_c = [oc[starts_run], oc[kept]]
    parts_s = [2 * rank[starts_run], 2 * rank[kept] + 1]
    parts_v = [np.full(int(starts_run.sum()), MOVE, np.uint8), e_verb[order][kept]]
    parts_f = [e_start[order][starts_run], e_first[order][kept]]
    parts_n = [np.ones(int(starts_run.sum()), np.int64), e_np[order][kept]]
    wc = np.flatnonzero(whole & closed & (nseg > 0))
    parts_c.append(wc)
    parts_s.append(np.full(len(wc), 2 * n_items + 2, np.int64))
    parts_v.append(np.full(len(wc), CLOSE, np.uint8))
    parts_f.append(np.zeros(len(wc), np.int64))
    parts_n.append(np.zeros(len(wc), np.int64))
    bare = np.flatnonzero(nseg[contour_of] == 0)        # verbs of contours without segments
    parts_c.append(contour_of[bare])
    parts_s.append(np.arange(len(bare), dtype=np.int64))
    parts_v.append(verbs[bare])
    parts_f.append(off[bare])
    parts_n.append(npts[bare])
    ic = np.concatenate(parts_c)
    if len(ic) == 0:
        return Path.empty()
    final = np.lexsort((np.concatenate(parts_s), ic))
    out_verbs = np.concatenate(parts_v)[final]
    pts = path.points[concat_ranges(np.concatenate(parts_f)[final],
                                    np.concatenate(parts_n)[final])]
    return Path(out_verbs.astype(np.uint8), pts, _checked=True)
