"""Plots of curves, drawn by raster itself: the curve, its control polygon,
the convex hull of the control points, rings at the joints between
segments, and labelled sample points.

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

FONT_FILE = os.path.join(os.path.dirname(__file__), 'NotoSans-Regular-ASCII.ttf')

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


def _fmt(v):
    return ('%.4g' % v).replace('e+0', 'e').replace('e-0', 'e-')


class Plot:
    """The device-space geometry of a curve plot (shared by PNG and SVG).

    Parameters
    ----------
    curve : any curve of :mod:`raster.curves`
    params : (M,) array_like of float, optional
        Parameters of the labelled sample points.
    width : int
        Image width in pixels; the height follows the aspect ratio.
    label_var : str
        Name printed in the labels (``t=0.5``).
    y_up : bool
        Mathematical orientation (default); False keeps raster's y-down.

    Attributes
    ----------
    width, height : int
    layers : list of (kind, Path, style dict)
        Paths in device space, drawn in order; ``kind`` is ``'fill'`` or
        ``'stroke'``.
    """

    def __init__(self, curve, params=None, width=640, label_var='t', y_up=True,
                 tolerance=0.1):
        pb = curve.to_beziers()
        if pb.dim < 2:
            raise CurveError('plots need curves of dimension 2 or 3')
        ctrl = np.asarray(curve.control_points() if hasattr(curve, 'control_points')
                          else pb.points)[:, :2]
        t = np.zeros(0) if params is None else np.asarray(params, dtype=np.float64).reshape(-1)
        pts = np.atleast_2d(curve.eval(t))[:, :2] if len(t) else np.zeros((0, 2))
        lo, hi = pb.bounding_box()
        allp = np.concatenate([ctrl, pts, [lo[:2], hi[:2]]])
        xmin, ymin = allp.min(0)
        xmax, ymax = allp.max(0)
        span = max(xmax - xmin, ymax - ymin)
        if not span > 1e-9 * max(1.0, np.abs(allp).max()):
            span = 1.0                  # a curve of a single point: a unit frame
        if xmax - xmin < 1e-3 * span:
            xmin, xmax = xmin - 0.05 * span, xmax + 0.05 * span
        if ymax - ymin < 1e-3 * span:
            ymin, ymax = ymin - 0.05 * span, ymax + 0.05 * span
        margin = 36.0
        self.width = int(width)
        if not 100 <= self.width <= MAX_PLOT_SIDE:
            raise CurveError('plot width must be between 100 and %d pixels' % MAX_PLOT_SIDE)
        s = (self.width - 2 * margin) / (xmax - xmin)
        if (ymax - ymin) * s + 2 * margin > MAX_PLOT_SIDE:        # tall: fit the height
            s = (MAX_PLOT_SIDE - 2 * margin) / (ymax - ymin)
        self.height = int(np.clip(np.ceil((ymax - ymin) * s + 2 * margin), 16, MAX_PLOT_SIDE))
        if y_up:
            T = Affine(s, 0, 0, -s, margin - xmin * s, margin + ymax * s)
        else:
            T = Affine(s, 0, 0, s, margin - xmin * s, margin - ymin * s)
        self.transform = T
        dev = lambda p: T.apply(np.asarray(p, dtype=np.float64).reshape(-1, 2))  # noqa: E731
        self.layers = []
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
        self.curve_path = pb.to_path(tolerance / s if np.isfinite(s) else tolerance).transform(T)
        self.layers.append(('stroke', self.curve_path,
                            {'color': COLORS['curve'], 'width': 2.0, 'join': 'round',
                             'cap': 'round'}))
        if len(pb) > 1:                 # joints: small rings on the curve
            for x, y in dev(pb.ctrl[1:, 0, :2]):
                ring = circle_path(x, y, 2.5)
                self.layers.append(('fill', ring, {'color': COLORS['background']}))
                self.layers.append(('stroke', ring, {'color': COLORS['curve'], 'width': 1.2}))
        self.labels = []
        for tv, (x, y) in zip(t, dev(pts)):
            self.layers.append(('fill', circle_path(x, y, 3.5), {'color': COLORS['point']}))
            label = '%s=%s' % (label_var, _fmt(tv))
            lx = x + 6 if x + 6 + text_width(label, 12) < self.width else x - 6 - text_width(label)
            ly = y - 6 if y - 18 > 0 else y + 16
            self.labels.append((label, lx, ly))
            glyphs = text_path(label, lx, ly, 12.0)
            self.layers.append(('stroke', glyphs, {'color': COLORS['background'], 'width': 3.0,
                                                   'join': 'round'}))
            self.layers.append(('fill', glyphs, {'color': COLORS['label']}))

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
                kw = {k: v for k, v in st.items() if k != 'color'}
                path = stroke(path, tolerance=0.1, **kw)
            edges = flatten(path, 0.1).edges()
            if len(edges):
                c.fill(coverage(edges, self.width, self.height), st['color'])
        return c

    def to_svg(self):
        """The plot as an SVG document (str)."""
        def rgb(col):
            return 'rgb(%d,%d,%d)' % tuple(int(round(255 * v)) for v in col[:3])
        out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
               'viewBox="0 0 %d %d">' % (self.width, self.height, self.width, self.height),
               '<rect width="100%%" height="100%%" fill="%s"/>' % rgb(COLORS['background'])]
        for kind, path, st in self.layers:
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


def plot_curve(curve, filename, params=None, width=640, label_var='t', y_up=True):
    """Draw ``curve`` to ``filename`` (``.png`` rendered by raster, or
    ``.svg`` text) and return the :class:`Plot`.

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
    plot = Plot(curve, params, width, label_var, y_up)
    if ext == '.svg':
        with open(filename, 'w', encoding='utf-8') as f:
            f.write(plot.to_svg())
    else:
        plot.canvas().save_png(filename)
    return plot
