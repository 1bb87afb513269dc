"""SVG 2 ``meshgradient`` elements to :class:`raster.tree.MeshGradient`.

A mesh is ``meshrow`` elements of ``meshpatch`` elements of ``stop``
elements.  Each stop's ``path`` (one ``l``, ``L``, ``c`` or ``C`` command,
relative commands from the end of the previous edge) is one edge of a
patch, and its ``stop-color``/``stop-opacity`` the colour of the corner
where that edge starts.  Patches share edges and corners with their
neighbours, so later patches leave them out:

* the first patch of the mesh has four stops (top, right, bottom, left
  edges, starting at the mesh's ``x``/``y``);
* the other patches of the first row have three (top, right, bottom: the
  left edge is the previous patch's right edge);
* the first patch of every later row has three (right, bottom, left: the
  top edge is the bottom edge of the patch above);
* every other patch has two (right, bottom).

The colour of a shared corner comes from the patch that first defines it;
the last edge of a patch may leave out its end point (the corner it must
reach is known).  ``gradientUnits`` (default ``objectBoundingBox``),
``gradientTransform`` and ``type`` (``bilinear``, ``bicubic``) apply;
``href`` inherits them and the rows from another mesh gradient.  A
malformed mesh (a missing or bad ``path``, rows of different lengths)
cannot paint: the fill's fallback colour is used, as for a gradient without
stops.
"""

import re

import numpy as np

from ..geometry.transform import IDENTITY
from ..tree.servers import MeshGradient, MeshInterpolation
from .document import chain_attr
from .refs import href_chain
from .style import local_name, stop_color
from .values import parse_length, parse_number, parse_transform

__all__ = ['mesh_gradient']

_COMMAND = re.compile(r'\s*([lLcC])\s*(.*)$', re.S)
_NUMBER = re.compile(r'[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?')
_TYPES = {m.value: m for m in MeshInterpolation}


class _Bad(Exception):
    """A malformed mesh (caught by :func:`mesh_gradient`)."""


def _children(el, name):
    return [c for c in el if local_name(c) == name]


def _edge(path, start, end=None):
    """The 4 control points ((4, 2) float64) of the edge a stop's ``path``
    describes from ``start``; ``end``, when known, is where it must arrive
    (an end point left out of the path is taken from it)."""
    m = _COMMAND.match(path or '')
    if m is None:
        raise _Bad()
    cmd, rest = m.group(1), m.group(2)
    nums = [float(v) for v in _NUMBER.findall(rest)]
    rel = cmd in 'lc'
    pts = np.array(nums, np.float64).reshape(-1, 2) if len(nums) % 2 == 0 else None
    if pts is None or not np.all(np.isfinite(pts)):
        raise _Bad()
    if rel:
        pts = pts + start
    if cmd in 'lL':
        if len(pts) == 0 and end is not None:
            stop = end
        elif len(pts) == 1:
            stop = pts[0] if end is None else end
        else:
            raise _Bad()
        return np.array([start, start + (stop - start) / 3.0,
                         start + (stop - start) * 2.0 / 3.0, stop])
    if len(pts) == 3:
        stop = pts[2] if end is None else end
    elif len(pts) == 2 and end is not None:
        stop = end
    else:
        raise _Bad()
    return np.array([start, pts[0], pts[1], stop])


def _mesh(rows, x, y, cache):
    """``(patches (P, 12, 2), colors (P, 4, 4), (rows, cols))`` of the
    ``meshrow`` elements ``rows`` starting at (x, y)."""
    patch_rows = [_children(r, 'meshpatch') for r in rows]
    nr = len(patch_rows)
    nc = len(patch_rows[0]) if nr else 0
    if nr == 0 or nc == 0 or any(len(r) != nc for r in patch_rows):
        raise _Bad()
    corner = np.full((nr + 1, nc + 1, 2), np.nan)
    color = np.zeros((nr + 1, nc + 1, 4))
    top = np.zeros((nr + 1, nc, 4, 2))      # horizontal edges, left to right
    side = np.zeros((nr, nc + 1, 4, 2))     # vertical edges, top to bottom
    corner[0, 0] = (x, y)
    for r in range(nr):
        for c in range(nc):
            stops = [s for s in _children(patch_rows[r][c], 'stop')]
            need = 4 if r == 0 and c == 0 else 3 if (r == 0 or c == 0) else 2
            if len(stops) < need:
                raise _Bad()
            stops = stops[:need]
            # the edges this patch defines, in its stop order: (kind,
            # from corner, to corner); 'top'/'side' edges are stored in
            # their left-to-right / top-to-bottom direction
            edges = []
            if r == 0:
                edges.append(('top', (0, c), (0, c + 1)))
            edges.append(('side', (r, c + 1), (r + 1, c + 1)))
            edges.append(('top', (r + 1, c + 1), (r + 1, c)))
            if c == 0:
                edges.append(('side', (r + 1, 0), (r, 0)))
            for k, ((kind, a, b), stop) in enumerate(zip(edges, stops)):
                start = corner[a]
                if np.isnan(start).any():
                    raise _Bad()
                known = corner[b] if not np.isnan(corner[b]).any() else None
                pts = _edge(stop.get('path'), start, known)
                corner[b] = pts[3]
                # a stop colours the corner its edge starts at, unless an
                # earlier patch did (the first stop of every patch but the
                # mesh's first starts at a shared corner)
                if k > 0 or (r == 0 and c == 0):
                    color[a] = stop_color(stop, cache)
                if kind == 'top':
                    if b[1] < a[1]:
                        pts = pts[::-1]
                    top[a[0], min(a[1], b[1])] = pts
                else:
                    if b[0] < a[0]:
                        pts = pts[::-1]
                    side[min(a[0], b[0]), a[1]] = pts
    P = nr * nc
    patches = np.empty((P, 12, 2))
    colors = np.empty((P, 4, 4))
    for r in range(nr):
        for c in range(nc):
            i = r * nc + c
            t, rt, bt, lt = top[r, c], side[r, c + 1], top[r + 1, c][::-1], side[r, c][::-1]
            patches[i, 0:4] = t
            patches[i, 4:7] = rt[1:]
            patches[i, 7:10] = bt[1:]
            patches[i, 10:12] = lt[1:3]
            colors[i] = (color[r, c], color[r, c + 1], color[r + 1, c + 1], color[r + 1, c])
    return patches, colors, (nr, nc)


def mesh_gradient(el, ctx, cache):
    """A ``meshgradient`` element to ``(MeshGradient, obb)`` (``obb``: the
    mesh is in objectBoundingBox units), or None when it cannot paint."""
    chain = href_chain(el, ('meshgradient',), cache)
    rows = None
    for e in chain:
        rows = _children(e, 'meshrow')
        if rows:
            break
    if not rows:
        return None
    obb = chain_attr(chain, 'gradientUnits') != 'userSpaceOnUse'

    def coord(name, axis):
        v = chain_attr(chain, name)
        if v is None:
            return 0.0
        if obb:
            n = parse_number(v.strip()[:-1]) / 100.0 if v.strip().endswith('%') and \
                parse_number(v.strip()[:-1]) is not None else parse_number(v)
        else:
            n = parse_length(v, axis, ctx)
        return 0.0 if n is None else float(n)
    try:
        patches, colors, shape = _mesh(rows, coord('x', 'x'), coord('y', 'y'), cache)
    except _Bad:
        return None
    tf = IDENTITY
    ts = chain_attr(chain, 'gradientTransform')
    if ts is not None:
        t = parse_transform(ts)
        if t is not None and t.determinant != 0:
            tf = t
    kind = _TYPES.get((chain_attr(chain, 'type') or 'bilinear').strip(),
                      MeshInterpolation.BILINEAR)
    patches.setflags(write=False)
    colors.setflags(write=False)
    return MeshGradient(patches, colors, shape, kind, tf, el.get('id') or ''), obb
