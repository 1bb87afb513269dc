"""Plots of curves, drawn by raster itself: axes with ticks and a grid in the
curve's own coordinates, the curve, its control polygon, the convex hull of
the control points, control points labelled with their names and
coordinates, sample points labelled with their parameter and coordinates,
optional tangent arrows, the joints between segments marked with their
continuity, and optionally a second panel with the family's blending
functions.

PNG output goes through raster's core (:func:`raster.geometry.stroking.stroke`,
:func:`raster.geometry.flattening.flatten`, :func:`raster.pixels.scan.coverage`,
:class:`raster.pixels.canvas.Canvas`); SVG output is written as text with the same
geometry (labels as glyph outlines, so the file needs no font).  Labels are
set in Noto Sans (SIL Open Font License, ``NotoSans-LICENSE-OFL.txt``),
subset to ASCII and shipped next to this module.

The plot uses the mathematical orientation by default (y up); 3-D curves are
projected onto their x, y coordinates.
"""

import os

import numpy as np

from ..geometry.hull import convex_hull
from ..geometry.path import Path
from ..geometry.pens import PathBuilder, TransformPen
from ..geometry.pathdata import circle_path
from ..geometry.transform import Affine
from .checks import CurveError

# the bundled OFL font (one copy, shipped with raster.fonts as its fallback
# face); a file path, not an import: the curve toolkit does not use raster.fonts
FONT_FILE = os.path.join(os.path.dirname(os.path.dirname(__file__)), 'fonts',
                         'NotoSans-Regular-ASCII.ttf')

#: Colours (straight RGB in [0, 1]) of the plot layers.
COLORS = {
    'background': (1.0, 1.0, 1.0),
    'hull': (0.55, 0.75, 0.95, 0.35),
    'hull_edge': (0.35, 0.55, 0.85),
    'polygon': (0.55, 0.55, 0.55),
    'control': (0.35, 0.35, 0.35),
    'curve': (0.05, 0.2, 0.6),
    'point': (0.85, 0.1, 0.1),
    'label': (0.0, 0.0, 0.0),
    'point_label': (0.55, 0.08, 0.08),
    'control_label': (0.3, 0.3, 0.3),
    'joint': (0.45, 0.1, 0.55),
    'tangent': (0.0, 0.5, 0.25),
}

_FONT = None

#: Largest plot side in pixels (keeps the float32 canvas under 256 MB).
MAX_PLOT_SIDE = 4000


def _font():
    global _FONT
    if _FONT is None:
        from fontTools.ttLib import TTFont
        f = TTFont(FONT_FILE)
        _FONT = (f.getGlyphSet(), f.getBestCmap(), f['head'].unitsPerEm)
    return _FONT


def text_path(text, x, y, size=12.0):
    """Glyph outlines of ``text`` as a :class:`~raster.geometry.path.Path` in device
    space (y down), baseline starting at ``(x, y)``, ``size`` px per em.

    >>> p = text_path('t=1', 0, 20)
    >>> p.is_empty, p.control_box()[3] <= 20.5
    (False, True)
    """
    glyphs, cmap, upem = _font()
    s = size / upem
    b = PathBuilder()
    pen_x = 0.0
    for ch in text:
        name = cmap.get(ord(ch)) or cmap.get(ord('?'))
        g = glyphs[name]
        g.draw(TransformPen(b, Affine(s, 0, 0, -s, x + pen_x * s, y)))
        pen_x += g.width
    return b.path()


def text_width(text, size=12.0):
    glyphs, cmap, upem = _font()
    return sum(glyphs[cmap.get(ord(c)) or cmap.get(ord('?'))].width for c in text) * size / upem


def _square(cx, cy, r):
    return Path.polygon([(cx - r, cy - r), (cx + r, cy - r), (cx + r, cy + r), (cx - r, cy + r)])


def fmt_number(v: float) -> str:
    """A coordinate for a label: 4 significant digits, short exponents."""
    return ('%.4g' % v).replace('e+0', 'e').replace('e-0', 'e-')


_fmt = fmt_number


#: Colours of the blending functions in the ``blend`` panel (cycled).
PALETTE = [(0.12, 0.35, 0.75), (0.85, 0.35, 0.05), (0.15, 0.6, 0.25), (0.75, 0.1, 0.45),
           (0.45, 0.3, 0.7), (0.0, 0.55, 0.6), (0.6, 0.45, 0.1), (0.35, 0.35, 0.35)]


def blend_functions(curve, samples: int = 241) -> dict:
    """The blending functions of a curve's family, sampled for plotting.

    Returns
    -------
    dict
        ``names`` (F labels), ``x`` ((K,) parameters), ``values`` ((K, F)),
        ``var`` (``'t'`` or ``'u'``: global or per-segment parameter) and
        ``title``.

    Raises
    ------
    CurveError
        The family has no blending functions (natural splines interpolate
        globally; piecewise rational chains have one basis per segment).
    """
    from .bezier import Bezier
    from .hermite import HermiteSpline, hermite_blend
    from .cardinal import CardinalSpline, cardinal_matrix
    from .bspline import BSpline
    from .beta import BetaSpline, beta_blend
    from .rational import RationalBezier
    from .nurbs import NURBS
    u = np.linspace(0.0, 1.0, samples)
    pw = np.stack([u ** 3, u ** 2, u, np.ones_like(u)], axis=1)
    if isinstance(curve, Bezier):
        n = curve.degree
        return {'names': ['B%d,%d' % (n, i) for i in range(n + 1)], 'x': u,
                'values': curve.blending(u), 'var': 't',
                'title': 'Bernstein blending functions B%d,i(t)' % n}
    if isinstance(curve, RationalBezier):
        return {'names': ['R%d' % i for i in range(curve.degree + 1)], 'x': u,
                'values': curve.blending(u), 'var': 't',
                'title': 'rational basis R_i(t) = w_i B_i / sum w_j B_j'}
    if isinstance(curve, (BSpline, NURBS)):
        lo, hi = curve.domain
        t = np.linspace(lo, hi, samples)
        vals = curve.basis(t)
        pre = 'N' if isinstance(curve, BSpline) else 'R'
        return {'names': ['%s%d' % (pre, i) for i in range(vals.shape[1])], 'x': t,
                'values': vals, 'var': 't',
                'title': ('B-spline basis N_i,%d(t)' if pre == 'N' else 'NURBS basis R_i,%d(t)')
                % curve.degree}
    if isinstance(curve, BetaSpline):
        return {'names': ['b-2', 'b-1', 'b0', 'b1'], 'x': u,
                'values': beta_blend(u, curve.beta1, curve.beta2), 'var': 'u',
                'title': 'Beta-spline blending b_r(u) on a segment'}
    if isinstance(curve, CardinalSpline):
        return {'names': ['P(i-1)', 'P(i)', 'P(i+1)', 'P(i+2)'], 'x': u,
                'values': pw @ cardinal_matrix(curve.tension), 'var': 'u',
                'title': 'cardinal blending (tension %g) on a segment' % curve.tension}
    if isinstance(curve, HermiteSpline):
        return {'names': ['h00', 'h01', 'h10', 'h11'], 'x': u, 'values': hermite_blend(u),
                'var': 'u', 'title': 'Hermite blending functions on a segment'}
    raise CurveError('%s has no blending functions to plot' % type(curve).__name__)


def _curve_data(curve, tolerance):
    """(control points (N, 2), polynomial chain or None, path builder fn,
    bounding box, joints) of any toolkit curve."""
    ctrl = np.asarray(curve.control_points() if hasattr(curve, 'control_points')
                      else curve.to_beziers().points)
    if ctrl.ndim != 2 or ctrl.shape[1] < 2:
        raise CurveError('plots need curves of dimension 2 or 3')
    lo, hi = curve.bounding_box()
    if len(lo) < 2:
        raise CurveError('plots need curves of dimension 2 or 3')
    return ctrl[:, :2], (lo[:2], hi[:2])


def _overlap(a, b):
    """Overlap area of boxes (x0, y0, x1, y1)."""
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    return w * h if w > 0 and h > 0 else 0.0


def place_label(anchor, w: float, h: float, taken: list, bounds, prefer=(1, -1)):
    """Top-left corner of a ``w x h`` label box near ``anchor`` that overlaps
    the boxes in ``taken`` least (greedy; the box is then appended).

    ``prefer`` = (sx, sy): the preferred side (+1 right / below)."""
    x, y = anchor
    sx, sy = prefer
    cands = [(sx, sy), (-sx, sy), (sx, -sy), (-sx, -sy), (sx, 0), (-sx, 0), (0, sy), (0, -sy)]
    best, best_cost = None, None
    for k, (cx, cy) in enumerate(cands):
        gx = 7.0 if cx > 0 else (-7.0 - w if cx < 0 else -w / 2)
        gy = 6.0 if cy > 0 else (-6.0 - h if cy < 0 else -h / 2)
        box = (x + gx, y + gy, x + gx + w, y + gy + h)
        cost = sum(_overlap(box, t) for t in taken)
        x0, y0, x1, y1 = bounds
        cost += 50.0 * (max(0, x0 - box[0]) + max(0, box[2] - x1) + max(0, y0 - box[1])
                        + max(0, box[3] - y1)) * h
        cost += 0.01 * k
        if best_cost is None or cost < best_cost:
            best, best_cost = box, cost
        if cost < 1:
            break
    taken.append(best)
    return best[0], best[1]


def _fmt_pt(p):
    return '(%s)' % ', '.join(_fmt(v) for v in p)


def _arrow(tail, head, width=1.6, size=7.0):
    """A stroke path for the shaft and a filled head triangle."""
    tail, head = np.asarray(tail, float), np.asarray(head, float)
    d = head - tail
    L = float(np.hypot(*d))
    b = PathBuilder()
    if L < 1e-9:
        return b.path(), b.path()
    u = d / L
    n = np.array([-u[1], u[0]])
    size = min(size, 0.6 * L)
    base = head - size * u
    b.moveTo(tuple(tail))
    b.lineTo(tuple(base))
    b.endPath()
    shaft = b.path()
    tri = Path.polygon([head, base + 0.45 * size * n, base - 0.45 * size * n])
    return shaft, tri


class Plot:
    """The device-space geometry of a curve plot (shared by PNG and SVG).

    Parameters
    ----------
    curve : any curve of :mod:`raster.curves`
    params : (M,) array_like of float, optional
        Parameters of the labelled sample points.
    width : int
        Image width in pixels (100 to :data:`MAX_PLOT_SIDE`); the height
        follows the data's aspect ratio (equal scales on both axes).
    label_var : str
        Name printed in the labels (``t=0.5``).
    y_up : bool
        Mathematical orientation (default); False keeps raster's y-down.
    tolerance : float
        Flattening tolerance of the drawn curve, device pixels.
    axes : bool
        Axes with ticks, tick labels and a grid in the curve's coordinates.
    labels : bool
        Label the control points with their names and coordinates, and the
        sample points with their parameter and coordinates.
    tangents : bool
        Tangent arrows at the sample points (one scale for all, so their
        lengths compare).
    blend : bool
        A second panel below with the family's blending functions
        (:func:`blend_functions`) and the sample parameters marked.
    joints : bool
        Mark the joints between segments with their continuity (``C1``,
        ``C1 G2``, ...).
    title : str, optional
        Text above the plot.

    Attributes
    ----------
    width, height : int
    transform : raster.geometry.transform.Affine
        Curve coordinates to device pixels.
    layers : list of (kind, Path, style dict)
        Paths in device space, drawn in order; ``kind`` is ``'fill'`` or
        ``'stroke'``.
    labels : list of (text, x, y)
        The sample-point labels (first line: ``t=0.5``), baseline start.
    point_labels : list of (text, x, y)
        Every text label drawn over the data (control points, samples,
        joints).
    """

    def __init__(self, curve, params=None, width=640, label_var='t', y_up=True,
                 tolerance=0.1, axes=True, labels=True, tangents=False, blend=False,
                 joints=True, title=None):
        from .axes import Panel
        ctrl, (lo, hi) = _curve_data(curve, tolerance)
        t = np.zeros(0) if params is None else np.asarray(params, dtype=np.float64).reshape(-1)
        pts = np.atleast_2d(curve.eval(t))[:, :2] if len(t) else np.zeros((0, 2))
        self.width = int(width)
        if not 100 <= self.width <= MAX_PLOT_SIDE:
            raise CurveError('plot width must be between 100 and %d pixels' % MAX_PLOT_SIDE)
        allp = np.concatenate([ctrl, pts, [lo, hi]])
        xmin, ymin = allp.min(0)
        xmax, ymax = allp.max(0)
        span = max(xmax - xmin, ymax - ymin)
        if not span > 1e-9 * max(1.0, np.abs(allp).max()):
            span = 1.0                  # a curve of a single point: a unit frame
            xmin, xmax, ymin, ymax = xmin - 0.5, xmax + 0.5, ymin - 0.5, ymax + 0.5
        small = self.width < 300
        if axes:
            left, right, top, bottom = (44, 14, 24, 40) if small else (58, 22, 30, 46)
        else:
            left = right = top = bottom = 36
        aw = self.width - left - right
        ratio = max(ymax - ymin, 1e-3 * span) / max(xmax - xmin, 1e-3 * span)
        ah = float(np.clip(aw * ratio, 0.3 * aw, 1.5 * aw))
        ah = min(ah, MAX_PLOT_SIDE - top - bottom - (0.5 * aw + 90 if blend else 0))
        ah = max(ah, 16.0)
        panel = Panel((xmin, xmax, ymin, ymax), (left, top, aw, ah), y_up=y_up, equal=True,
                      pad=0.08 if axes else 0.0)
        if not axes:
            # the old framing: the data fills the area exactly along its long side
            panel = Panel((xmin, xmax, ymin, ymax), (left, top, aw, ah), y_up=y_up, equal=True,
                          pad=0.0)
        self.panel = panel
        T = self.transform = panel.transform
        s = panel.scale
        dev = panel.device
        height = top + ah + bottom
        self.layers = []
        self.labels = []
        self.point_labels = []
        texts = []                      # (text, x, y, size, colour) drawn last, with halos
        if axes:
            self.layers += panel.layers(text_path, text_width, xlabel='x', ylabel='y',
                                        title=title, font=10.0 if small else 11.0,
                                        target=max(3, int(max(aw, ah) / 70)))
        elif title:
            texts.append((title, left, top - 10, 13.0, COLORS['label']))
        if len(ctrl) >= 3:
            hull = convex_hull(ctrl)
            if len(hull) >= 3:
                hp = Path.polygon(dev(hull))
                self.layers.append(('fill', hp, {'color': COLORS['hull']}))
                self.layers.append(('stroke', hp, {'color': COLORS['hull_edge'], 'width': 1.0}))
        cp = dev(ctrl)
        self.layers.append(('stroke', Path.polygon(cp, closed=False),
                            {'color': COLORS['polygon'], 'width': 1.0, 'dash': (4.0, 3.0)}))
        for x, y in cp:
            self.layers.append(('fill', _square(x, y, 2.5), {'color': COLORS['control']}))
        self.curve_path = curve.to_path(tolerance / s if np.isfinite(s) else tolerance) \
            .transform(T)
        self.layers.append(('stroke', self.curve_path,
                            {'color': COLORS['curve'], 'width': 2.0, 'join': 'round',
                             'cap': 'round'}))
        fs = 10.0 if small else 11.0
        centre = cp.mean(axis=0)
        requests = []                   # (anchor, [(text, size, colour)], prefer, kind)
        if labels:
            names = _control_names(curve, len(ctrl))
            seen = {}
            for k, p in enumerate(ctrl):            # coinciding points share a label
                seen.setdefault(tuple(np.round(p, 12)), []).append(k)
            for ks in seen.values():
                (x, y), p = cp[ks[0]], ctrl[ks[0]]
                prefer = (1 if x >= centre[0] else -1, 1 if y >= centre[1] else -1)
                requests.append(((x, y), [('%s %s' % ('='.join(names[k] for k in ks),
                                                      _fmt_pt(p)), fs,
                                           COLORS['control_label'])], prefer, 'control'))
        if joints:
            jl = _joint_list(curve)
            for (x, y), txt in zip(dev(jl[0]) if len(jl[0]) else [], jl[1]):
                ring = circle_path(x, y, 3.0)
                self.layers.append(('fill', ring, {'color': COLORS['background']}))
                self.layers.append(('stroke', ring, {'color': COLORS['joint'], 'width': 1.3}))
                if labels:
                    requests.append(((x, y), [(txt, fs - 1, COLORS['joint'])], (1, 1), 'joint'))
        arrows = []
        if tangents and len(t):
            d = np.atleast_2d(curve.tangent(t))[:, :2]
            norms = np.linalg.norm(d, axis=1)
            if norms.size and norms.max() > 0:
                k = 0.14 * span / float(norms.max())
                for p0, v in zip(pts, d):
                    a0, a1 = dev(p0)[0], dev(p0 + k * v)[0]
                    arrows.append(np.stack([a0, a1]))
                    shaft, head = _arrow(a0, a1)
                    if not shaft.is_empty:
                        self.layers.append(('stroke', shaft, {'color': COLORS['tangent'],
                                                              'width': 1.6, 'cap': 'round'}))
                        self.layers.append(('fill', head, {'color': COLORS['tangent']}))
        for tv, (x, y), p in zip(t, dev(pts), pts):
            self.layers.append(('fill', circle_path(x, y, 3.5), {'color': COLORS['point']}))
            lines = [('%s=%s' % (label_var, _fmt(tv)), 12.0, COLORS['label'])]
            if labels:
                lines.append((_fmt_pt(p), fs, COLORS['point_label']))
            requests.insert(0, ((x, y), lines, (1, -1), 'sample'))
        # place the labels: sample points first, then control points, joints
        taken = [(x - 4, y - 4, x + 4, y + 4) for x, y in np.concatenate([cp, dev(pts)])]
        # the curve and the arrows are obstacles too (boxes along them)
        from ..geometry.flattening import flatten
        lines_dev = [pl for pl, _ in flatten(self.curve_path, 0.5)] + arrows
        for pl in lines_dev:
            pl = np.asarray(pl)
            if len(pl) < 2:
                continue
            seg = np.linalg.norm(np.diff(pl, axis=0), axis=1)
            arc = np.concatenate([[0], np.cumsum(seg)])
            at = np.linspace(0, arc[-1], max(2, int(arc[-1] / 6) + 1))
            qx, qy = np.interp(at, arc, pl[:, 0]), np.interp(at, arc, pl[:, 1])
            taken += [(x - 2, y - 2, x + 2, y + 2) for x, y in zip(qx, qy)]
        bounds = (2.0, 2.0, self.width - 2.0, top + ah + bottom - 2.0)
        for anchor, lines, prefer, kind in requests:
            w = max(text_width(txt, size) for txt, size, _ in lines)
            h = sum(size + 3 for _, size, _ in lines)
            bx, by = place_label(anchor, w + 2, h + 2, taken, bounds, prefer)
            yy = by + 1
            for n, (txt, size, col) in enumerate(lines):
                yy += size
                texts.append((txt, bx + 1, yy - 1, size, col))
                if kind == 'sample' and n == 0:
                    self.labels.append((txt, bx + 1, yy - 1))
                yy += 3
        self.height = int(np.clip(np.ceil(height), 16, MAX_PLOT_SIDE))
        if blend:
            self._blend_panel(curve, t, left, right, aw, fs, small)
        for txt, x, y, size, col in texts:
            glyphs = text_path(txt, x, y, size)
            self.point_labels.append((txt, x, y))
            self.layers.append(('stroke', glyphs, {'color': COLORS['background'], 'width': 3.0,
                                                   'join': 'round'}))
            self.layers.append(('fill', glyphs, {'color': col}))

    def _blend_panel(self, curve, t, left, right, aw, fs, small):
        from .axes import Panel
        bf = blend_functions(curve)
        top = self.height + 52
        bh = max(80.0, 0.42 * aw)
        x = bf['x']
        vals = bf['values']
        ylo, yhi = min(0.0, float(vals.min())), max(1.0, float(vals.max()))
        panel = Panel((x[0], x[-1], ylo, yhi), (left, top, aw, bh), y_up=True, equal=False,
                      pad=0.03)
        self.blend_panel = panel
        self.layers += panel.layers(text_path, text_width, xlabel=bf['var'], ylabel='',
                                    title=None, font=10.0 if small else 11.0,
                                    target=max(3, int(aw / 70)))
        tt = text_path(bf['title'], left, top - fs - 16, fs + 2)
        self.layers.append(('fill', tt, {'color': COLORS['label']}))
        dev = panel.device
        if len(t):
            (lo, hi) = curve.domain
            marks = t if bf['var'] == 't' else t - np.clip(np.floor(t), 0, max(hi - 1, 0))
            for tv in np.unique(np.clip(marks, x[0], x[-1])):
                X = dev([[tv, 0.0]])[0, 0]
                line = Path.polygon([(X, top), (X, top + bh)], closed=False)
                self.layers.append(('stroke', line, {'color': COLORS['point'], 'width': 1.0,
                                                     'dash': (3.0, 3.0)}))
        F = vals.shape[1]
        for f in range(F):
            col = PALETTE[f % len(PALETTE)]
            poly = dev(np.stack([x, vals[:, f]], 1))
            self.layers.append(('stroke', Path.polygon(poly, closed=False),
                                {'color': col, 'width': 1.8, 'join': 'round', 'cap': 'round'}))
        # legend: names in a row between the panel title and the frame
        lx, ly = left + 2.0, top - 6
        for f, name in enumerate(bf['names']):
            col = PALETTE[f % len(PALETTE)]
            sw = Path.polygon([(lx, ly - 4), (lx + 14, ly - 4)], closed=False)
            self.layers.append(('stroke', sw, {'color': col, 'width': 2.5}))
            g = text_path(name, lx + 17, ly, fs)
            self.layers.append(('stroke', g, {'color': COLORS['background'], 'width': 3.0,
                                              'join': 'round'}))
            self.layers.append(('fill', g, {'color': col}))
            lx += 17 + text_width(name, fs) + 12
        self.height = int(np.clip(np.ceil(top + bh + 44), 16, MAX_PLOT_SIDE))

    def render(self):
        """Rasterize with raster's core: (height, width, 4) uint8 RGBA."""
        return self.canvas().to_rgba8()

    def canvas(self):
        from ..pixels.canvas import Canvas
        from ..geometry.flattening import flatten
        from ..pixels.scan import coverage
        from ..geometry.stroking import stroke
        c = Canvas(self.width, self.height, background=COLORS['background'])
        for kind, path, st in self.layers:
            if path.is_empty:
                continue
            if kind == 'stroke':
                kw = {k: v for k, v in st.items() if k not in ('color', 'layer')}
                path = stroke(path, tolerance=0.1, **kw)
            edges = flatten(path, 0.1).edges()
            if len(edges):
                c.fill(coverage(edges, self.width, self.height), st['color'])
        return c

    def to_svg(self):
        """The plot as an SVG document (str)."""
        return layers_to_svg(self.width, self.height, self.layers)


def layers_to_svg(width: int, height: int, layers: list) -> str:
    """Plot layers ``(kind, Path, style)`` as an SVG document (str): fills
    and strokes with the styles' colours, dashes, joins and caps."""
    def rgb(col):
        return 'rgb(%d,%d,%d)' % tuple(int(round(255 * v)) for v in col[:3])

    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
           'viewBox="0 0 %d %d">' % (width, height, width, height),
           '<rect width="100%%" height="100%%" fill="%s"/>' % rgb(COLORS['background'])]
    for kind, path, st in layers:
        if path.is_empty:
            continue
        d = path.to_svg(precision=3)
        col = st['color']
        op = ' fill-opacity="%g"' % col[3] if len(col) == 4 else ''
        if kind == 'fill':
            out.append('<path d="%s" fill="%s"%s/>' % (d, rgb(col), op))
        else:
            extra = ''
            if 'dash' in st:
                extra += ' stroke-dasharray="%s"' % ' '.join('%g' % v for v in st['dash'])
            if 'join' in st:
                extra += ' stroke-linejoin="%s"' % st['join']
            if 'cap' in st:
                extra += ' stroke-linecap="%s"' % st['cap']
            out.append('<path d="%s" fill="none" stroke="%s" stroke-width="%g"%s/>'
                       % (d, rgb(col), st['width'], extra))
    out.append('</svg>')
    return '\n'.join(out) + '\n'


def _control_names(curve, n):
    """Names of the control points: P0..; V0.. for Beta-splines."""
    from .beta import BetaSpline
    pre = 'V' if isinstance(curve, BetaSpline) else 'P'
    return ['%s%d' % (pre, i) for i in range(n)]


def _joint_list(curve):
    """Joint positions (K, 2) and their continuity labels."""
    try:
        js = curve.continuity(1e-9)
    except (CurveError, AttributeError):
        return np.zeros((0, 2)), []
    if not js:
        return np.zeros((0, 2)), []
    ts = np.array([min(j.t, curve.domain[1]) for j in js])
    pos = np.atleast_2d(curve.eval(ts))[:, :2]
    labels = []
    for j in js:
        c = 'C%d' % j.C if j.C >= 0 else 'gap'
        g = 'G%d' % j.G if j.G >= 0 else ''
        labels.append(c if (j.C == j.G or j.C < 0) else '%s %s' % (c, g))
    return pos, labels


def plot_curve(curve, filename, params=None, width=640, label_var='t', y_up=True, **options):
    """Draw ``curve`` to ``filename`` (``.png`` rendered by raster, or
    ``.svg`` text) and return the :class:`Plot`; ``options`` are those of
    :class:`Plot` (``axes``, ``labels``, ``tangents``, ``blend``,
    ``joints``, ``title``).

    Raises
    ------
    CurveError
        Unknown file extension or a curve of dimension 1.
    OSError
        The file cannot be written.
    """
    ext = os.path.splitext(str(filename))[1].lower()
    if ext not in ('.png', '.svg'):
        raise CurveError('plot file must end in .png or .svg, got %r' % str(filename))
    plot = Plot(curve, params, width, label_var, y_up, **options)
    if ext == '.svg':
        with open(filename, 'w', encoding='utf-8') as f:
            f.write(plot.to_svg())
    else:
        plot.canvas().save_png(filename)
    return plot
