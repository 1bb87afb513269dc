"""Plots of surfaces, drawn by raster: a shaded surface (one light,
Lambert shading, front and back faces in two colours), an isoparametric
wireframe, the control net and labelled sample points, in an orthographic
or a perspective view.

The surface is sampled on a grid of quads; quads are sorted by depth and
painted back to front (the painter's algorithm), each followed by the
wireframe edges lying on it, so nearer parts hide farther lines.  The
control net and the sample points are drawn on top.  PNG goes through
raster's scan converter and canvas (all quads scan converted in one batch);
SVG writes the same polygons as paths.

The camera looks at the middle of the control net's bounding box from the
direction given by ``azimuth`` (degrees, from +x towards +y) and
``elevation`` (degrees above the x-y plane); ``z`` is up.
"""

import math
import os

import numpy as np

from ..geometry.path import Path
from ..geometry.pens import PathBuilder
from ..geometry.pathdata import circle_path
from .checks import CurveError
from .plot import (COLORS, MAX_PLOT_SIDE, fmt_number as _fmt, layers_to_svg, place_label,
                   text_path, text_width)

__all__ = ['SurfacePlot', 'plot_surface', 'camera', 'SURFACE_COLORS', 'VIEWS']

VIEWS = ('perspective', 'ortho', 'both')

#: Colours (straight RGB in [0, 1]) of the surface plot layers.
SURFACE_COLORS = {
    'front': (0.35, 0.55, 0.85),
    'back': (0.9, 0.6, 0.3),
    'wire': (0.1, 0.15, 0.3),
    'net': (0.45, 0.45, 0.45),
    'net_point': (0.2, 0.2, 0.2),
}


def camera(center, radius: float, azimuth: float, elevation: float, perspective: bool):
    """A view: a function mapping (N, 3) points to ((N, 2) screen points,
    (N,) depths), and the unit vectors (right, up, forward)."""
    a, e = math.radians(azimuth), math.radians(elevation)
    d = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
    f = -d
    up0 = np.array([0.0, 0.0, 1.0])
    r = np.cross(f, up0)
    if np.linalg.norm(r) < 1e-9:                       # looking straight down or up
        r = np.array([1.0, 0.0, 0.0]) if f[2] < 0 else np.array([-1.0, 0.0, 0.0])
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    c = np.asarray(center, dtype=np.float64)
    R = max(float(radius), 1e-12)
    eye = c + 3.2 * R * d

    def project(p):
        p = np.asarray(p, dtype=np.float64).reshape(-1, 3)
        if perspective:
            q = p - eye
            z = q @ f
            z = np.maximum(z, 1e-6 * R)
            return np.stack([(q @ r) / z, (q @ u) / z], 1) * (3.2 * R), z
        q = p - c
        return np.stack([q @ r, q @ u], 1), q @ f

    return project, (r, u, f)


def _as3(p):
    p = np.asarray(p, dtype=np.float64)
    if p.shape[-1] == 3:
        return p
    if p.shape[-1] == 2:
        return np.concatenate([p, np.zeros(p.shape[:-1] + (1,))], -1)
    raise CurveError('surface plots need 2-D or 3-D surfaces')


class SurfacePlot:
    """The device-space geometry of a surface plot (shared by PNG and SVG).

    Parameters
    ----------
    surface : a surface of :mod:`raster.curves.surface`
    params : (M, 2) array_like of float, optional
        ``(u, v)`` of labelled sample points.
    width : int
        Image width in pixels.
    view : {'perspective', 'ortho', 'both'}
        ``'both'`` puts the two views side by side.
    azimuth, elevation : float
        View direction in degrees.
    grid : int
        Quads per direction of the shaded surface.
    isolines : int
        Isoparametric lines per direction in the wireframe.
    title : str, optional

    Attributes
    ----------
    width, height : int
    layers : list of (kind, Path, style dict)
    """

    def __init__(self, surface, params=None, width=640, view='perspective', azimuth=-60.0,
                 elevation=30.0, grid=32, isolines=8, title=None):
        if view not in VIEWS:
            raise CurveError('view must be one of %s, got %r' % (', '.join(VIEWS), view))
        self.width = int(width)
        if not 100 <= self.width <= MAX_PLOT_SIDE:
            raise CurveError('plot width must be between 100 and %d pixels' % MAX_PLOT_SIDE)
        grid = int(np.clip(grid, 2, 200))
        isolines = int(np.clip(isolines, 1, grid))
        uv = np.zeros((0, 2)) if params is None else np.asarray(params, float).reshape(-1, 2)
        us, vs, P = surface.grid(grid + 1, grid + 1)
        P = _as3(P)
        net = _as3(surface.control_net())
        samp = _as3(np.atleast_2d(surface.eval(uv[:, 0], uv[:, 1]))) if len(uv) else \
            np.zeros((0, 3))
        allp = np.concatenate([net.reshape(-1, 3), P.reshape(-1, 3)])
        lo, hi = allp.min(0), allp.max(0)
        center, radius = 0.5 * (lo + hi), 0.5 * float(np.linalg.norm(hi - lo)) or 1.0
        views = ['perspective', 'ortho'] if view == 'both' else [view]
        pw = self.width / len(views)
        self.layers = []
        #: per view, the depths of the quads in the order they are painted
        self.paint_depths = []
        self.height = 0
        for k, name in enumerate(views):
            h = self._panel(surface, name, k * pw, pw, P, net, samp, uv, center, radius,
                            azimuth, elevation, grid, isolines, title)
            self.height = max(self.height, h)
        self.height = int(np.clip(self.height, 16, MAX_PLOT_SIDE))

    def _panel(self, surface, name, x0, pw, P, net, samp, uv, center, radius, az, el, grid,
               isolines, title):
        project, (r, u, f) = camera(center, radius, az, el, name == 'perspective')
        G = grid + 1
        sp, depth = project(P.reshape(-1, 3))
        sp, depth = sp.reshape(G, G, 2), depth.reshape(G, G)
        npj, _ = project(net.reshape(-1, 3))
        npj = npj.reshape(net.shape[0], net.shape[1], 2)
        spj = project(samp)[0] if len(samp) else np.zeros((0, 2))
        allp = np.concatenate([sp.reshape(-1, 2), npj.reshape(-1, 2)])
        mn, mx = allp.min(0), allp.max(0)
        margin, top = 24.0, 40.0
        aw = pw - 2 * margin
        span = max(mx[0] - mn[0], mx[1] - mn[1], 1e-12)
        s = aw / max(mx[0] - mn[0], 1e-12 * span)
        ah = (mx[1] - mn[1]) * s
        if ah > 1.2 * aw:
            s *= 1.2 * aw / ah
            ah = 1.2 * aw
        ah = max(ah, 0.3 * aw)
        ox = x0 + margin + 0.5 * (aw - (mx[0] - mn[0]) * s)
        oy = top + 0.5 * (ah + (mx[1] - mn[1]) * s)

        def dev(q):
            q = np.asarray(q, dtype=np.float64).reshape(-1, 2)
            return np.stack([ox + (q[:, 0] - mn[0]) * s, oy - (q[:, 1] - mn[1]) * s], 1)

        D = dev(sp.reshape(-1, 2)).reshape(G, G, 2)
        # quads: corners (i, j), (i+1, j), (i+1, j+1), (i, j+1)
        c00, c10, c11, c01 = P[:-1, :-1], P[1:, :-1], P[1:, 1:], P[:-1, 1:]
        n = np.cross(c11 - c00, c01 - c10)
        nl = np.linalg.norm(n, axis=-1, keepdims=True)
        n = np.where(nl > 0, n / np.where(nl > 0, nl, 1), 0.0)
        light = -f + 0.6 * u - 0.35 * r
        light /= np.linalg.norm(light)
        lam = np.abs(n @ light)
        mid = 0.25 * (c00 + c10 + c11 + c01)
        if name == 'perspective':
            eye = center - 3.2 * radius * f
            facing = np.einsum('ijk,ijk->ij', n, eye - mid) > 0
        else:
            facing = (n @ -f) > 0
        qdepth = 0.25 * (depth[:-1, :-1] + depth[1:, :-1] + depth[1:, 1:] + depth[:-1, 1:])
        order = np.argsort(-qdepth.reshape(-1), kind='stable')
        self.paint_depths.append(qdepth.reshape(-1)[order])
        step = max(1, grid // isolines)
        front = np.array(SURFACE_COLORS['front'])
        back = np.array(SURFACE_COLORS['back'])
        for q in order.tolist():
            i, j = divmod(q, grid)
            base = front if facing[i, j] else back
            shade = base * (0.38 + 0.62 * lam[i, j])
            quad = np.array([D[i, j], D[i + 1, j], D[i + 1, j + 1], D[i, j + 1]])
            # grown by 0.4 px so that neighbouring quads overlap (no
            # anti-aliasing seams between them)
            rad = quad - quad.mean(0)
            ln = np.linalg.norm(rad, axis=1, keepdims=True)
            quad = quad + np.where(ln > 0, 0.4 * rad / np.where(ln > 0, ln, 1), 0)
            self.layers.append(('fill', Path.polygon(quad),
                                {'color': tuple(np.clip(shade, 0, 1).tolist())}))
            edges = []
            if i % step == 0:
                edges.append((D[i, j], D[i, j + 1]))
            if (i + 1) % step == 0 or i + 1 == grid:
                edges.append((D[i + 1, j], D[i + 1, j + 1]))
            if j % step == 0:
                edges.append((D[i, j], D[i + 1, j]))
            if (j + 1) % step == 0 or j + 1 == grid:
                edges.append((D[i, j + 1], D[i + 1, j + 1]))
            for a, b in edges:
                self.layers.append(('fill', _bar(a, b, 0.9), {'color': SURFACE_COLORS['wire']}))
        # control net on top
        Nd = dev(npj.reshape(-1, 2)).reshape(npj.shape)
        b = PathBuilder()
        for row in list(Nd) + list(np.swapaxes(Nd, 0, 1)):
            b.moveTo(tuple(row[0]))
            for q in row[1:]:
                b.lineTo(tuple(q))
            b.endPath()
        self.layers.append(('stroke', b.path(), {'color': SURFACE_COLORS['net'], 'width': 1.0,
                                                 'dash': (4.0, 3.0)}))
        for x, y in Nd.reshape(-1, 2):
            self.layers.append(('fill', Path.polygon([(x - 2.2, y - 2.2), (x + 2.2, y - 2.2),
                                                      (x + 2.2, y + 2.2), (x - 2.2, y + 2.2)]),
                                {'color': SURFACE_COLORS['net_point']}))
        taken = [(x - 3, y - 3, x + 3, y + 3) for x, y in Nd.reshape(-1, 2)]
        texts = []
        for (x, y), (a, bb), p in zip(dev(spj), uv, samp):
            self.layers.append(('fill', circle_path(x, y, 3.5), {'color': COLORS['point']}))
            taken.append((x - 4, y - 4, x + 4, y + 4))
        bounds = (x0 + 2, 2.0, x0 + pw - 2, top + ah + 40)
        for (x, y), (a, bb), p in zip(dev(spj), uv, samp):
            lines = ['(u, v) = (%s, %s)' % (_fmt(a), _fmt(bb)), '(%s)' % ', '.join(_fmt(v) for v in
                                                                               p[:surface.dim])]
            w = max(text_width(t_, 11) for t_ in lines)
            lx, ly = place_label((x, y), w + 2, 30, taken, bounds, (1, -1))
            texts.append((lines[0], lx + 1, ly + 12, 11.0, COLORS['label']))
            texts.append((lines[1], lx + 1, ly + 26, 10.0, COLORS['point_label']))
        # axis triad
        ax0 = np.array([x0 + 34.0, top + ah + 22])
        for k, (vec, lab) in enumerate(zip(np.eye(3), 'xyz')):
            d2 = np.array([vec @ r, -(vec @ u)]) * 18
            b = PathBuilder()
            b.moveTo(tuple(ax0))
            b.lineTo(tuple(ax0 + d2))
            b.endPath()
            self.layers.append(('stroke', b.path(), {'color': COLORS['label'], 'width': 1.3}))
            texts.append((lab, *(ax0 + d2 * 1.35 + [-3, 4]), 10.0, COLORS['label']))
        head = '%s view, azimuth %s, elevation %s' % (
            'perspective' if name == 'perspective' else 'orthographic', _fmt(az), _fmt(el))
        if title:
            texts.append((title, x0 + margin, 16.0, 13.0, COLORS['label']))
        texts.append((head, x0 + margin, 33.0, 11.0, COLORS['control_label']))
        for txt, x, y, size, col in texts:
            g = text_path(txt, x, y, size)
            self.layers.append(('stroke', g, {'color': COLORS['background'], 'width': 3.0,
                                              'join': 'round'}))
            self.layers.append(('fill', g, {'color': col}))
        return top + ah + 48

    def render(self):
        """(height, width, 4) uint8 RGBA."""
        return self.canvas().to_rgba8()

    def canvas(self):
        """The plot on a :class:`raster.pixels.canvas.Canvas` (fills scan converted in
        one batch, composited in order)."""
        from ..pixels.canvas import Canvas
        from ..geometry.flattening import flatten
        from ..pixels.scan import coverage_many
        from ..geometry.stroking import stroke
        c = Canvas(self.width, self.height, background=COLORS['background'])
        edges, cols = [], []
        for kind, path, st in self.layers:
            if path.is_empty:
                continue
            if kind == 'stroke':
                kw = {k: v for k, v in st.items() if k != 'color'}
                path = stroke(path, tolerance=0.1, **kw)
            edges.append(flatten(path, 0.1).edges())
            cols.append(st['color'])
        for mask, col in zip(coverage_many(edges, self.width, self.height), cols):
            c.fill(mask, col)
        return c

    def to_svg(self):
        """The plot as an SVG document (str)."""
        return layers_to_svg(self.width, self.height, self.layers)


def _bar(a, b, w):
    """A thin rectangle from a to b, ``w`` pixels wide (a stroke without
    the stroker)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    d = b - a
    L = float(np.hypot(*d))
    if L < 1e-12:
        return Path.polygon([a, a + [w, 0], a + [w, w], a + [0, w]])
    n = np.array([-d[1], d[0]]) / L * (w / 2)
    e = d / L * (w / 2)
    return Path.polygon([a - e + n, b + e + n, b + e - n, a - e - n])


def plot_surface(surface, filename, params=None, width: int = 640,
                 **options) -> 'SurfacePlot':
    """Draw ``surface`` to ``filename`` (``.png`` or ``.svg``) and return the
    :class:`SurfacePlot`; ``options`` as for :class:`SurfacePlot`."""
    ext = os.path.splitext(str(filename))[1].lower()
    if ext not in ('.png', '.svg'):
        raise CurveError('plot file must end in .png or .svg, got %r' % str(filename))
    plot = SurfacePlot(surface, params, width, **options)
    if ext == '.svg':
        with open(filename, 'w', encoding='utf-8') as fh:
            fh.write(plot.to_svg())
    else:
        plot.canvas().save_png(filename)
    return plot
