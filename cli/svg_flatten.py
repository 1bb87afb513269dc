"""svg-flatten: every drawn shape of an SVG document as polylines.

    svg-flatten in.svg [-o OUT] [--tolerance T] [--format svg|json|csv]
                [--pixels] [--outline-strokes] [--dpi DPI] [font options]

Text is converted to its glyph outlines (as ``rasterize`` draws it: the
system's fonts, and the font options of ``rasterize``: ``--font-dir``,
``--font-file``, ``--no-system-fonts``, ``--serif-family`` ...,
``--list-fonts``).

The document is resolved first (``use``, transforms, viewBox, CSS), so the
output holds each painted path once, flattened into straight segments.

Units: by default coordinates are in the root ``<svg>`` element's user units
(the coordinate system of its ``viewBox``, or CSS px without one);
``--pixels`` gives document pixels instead (the natural-size raster, the
one ``rasterize`` makes without a size option).  ``--tolerance`` (default
0.25) is the largest distance between a curve and its polyline, in the
output units.

Formats:

* ``svg``: one ``<path>`` per shape, polylines as ``M .. L .. Z``, with the
  id, fill, fill-rule, stroke and stroke-width of the shape (solid colours;
  other paints are written as ``none`` with a ``data-fill-paint`` /
  ``data-stroke-paint`` attribute naming the paint kind);
* ``json``: a list of ``{id, fill, fill_opacity, fill_rule, stroke,
  stroke_opacity, stroke_width, polylines: [{points, closed}]}``; colours are
  ``#rrggbb`` strings or null (no paint) or ``{"type": kind}`` (non-solid);
* ``csv``: ``shape_index,id,polyline_index,point_index,x,y,closed``.

``--outline-strokes`` replaces each stroke by the polygons of its outline
(see :func:`raster.geometry.stroking.stroke`), emitted as a separate filled shape
(nonzero rule) after the shape's fill.
"""

import argparse
import csv
import io
import json
import math
import sys

from ._common import (LimitError, Parser, add_font_options, add_languages, add_limit_options,
                      add_version, base_dir_of, drawn_shapes, font_options, hex_color,
                      languages_of, left_out, list_fonts, metered, read_source, run, user_to_doc,
                      write_text)

PROG = 'svg-flatten'


def build_parser():
    ap = Parser(prog=PROG, description='Flatten every drawn shape of an SVG document '
                'into polylines.')
    ap.add_argument('input', nargs='?', help='SVG or SVGZ file, or - for stdin')
    ap.add_argument('-o', '--output', default='-', help='output file (default: stdout)')
    ap.add_argument('--tolerance', type=float, default=0.25,
                    help='largest curve-to-polyline distance in output units (default 0.25)')
    ap.add_argument('--format', choices=('svg', 'json', 'csv'), default='svg')
    ap.add_argument('--pixels', action='store_true',
                    help='output document pixels instead of root user units')
    ap.add_argument('--outline-strokes', action='store_true',
                    help='replace strokes by their outline polygons')
    ap.add_argument('--dpi', type=float, default=96.0, help=argparse.SUPPRESS)
    add_font_options(ap)
    add_languages(ap)
    add_limit_options(ap)
    add_version(ap)
    return ap


def _paint_value(paint):
    from raster.tree import SolidPaint
    if paint is None:
        return None, 1.0
    if isinstance(paint, SolidPaint):
        return hex_color(paint.color), float(paint.color[3])
    return {'type': type(paint).__name__[0].lower() + type(paint).__name__[1:]}, 1.0


def collect(tree, tolerance=0.25, pixels=False, outline_strokes=False):
    """The shapes of ``tree`` as dicts (the JSON format's records).

    Parameters
    ----------
    tree : raster.tree.Tree
    tolerance : float
        In output units.
    pixels : bool
        Document pixels instead of root user units.
    outline_strokes : bool
        Emit stroke outlines as filled shapes.

    Returns
    -------
    list of dict
    """
    from raster.errors import RasterError
    if not (math.isfinite(tolerance) and tolerance > 0):
        raise RasterError('--tolerance must be positive, got %g' % tolerance)
    to_out = None
    if not pixels:
        to_out = user_to_doc(tree).inverse()
    shapes = []
    with metered(tree):
        for node, t in drawn_shapes(tree):
            try:
                shapes.extend(_shape(node, t if to_out is None else to_out @ t, tolerance,
                                     outline_strokes))
            except LimitError as e:      # a budget of raster.limits: this shape left out
                left_out(e)
    return shapes


def _shape(node, ot, tolerance, outline_strokes):
    """The records of one drawn shape under ``ot`` (node to output units)."""
    from raster.geometry.flattening import flatten
    from raster.geometry.stroking import stroke
    shapes = []
    fill, fill_a = _paint_value(node.fill.paint if node.fill else None)
    strk, strk_a = _paint_value(node.stroke.paint if node.stroke else None)
    rec = {'id': node.id or None,
           'fill': fill,
           'fill_opacity': round(fill_a * node.fill.opacity, 6) if node.fill else None,
           'fill_rule': node.fill.rule if node.fill else None,
           'stroke': strk,
           'stroke_opacity': round(strk_a * node.stroke.opacity, 6) if node.stroke else None,
           'stroke_width': (node.stroke.width * ot.mean_scale()) if node.stroke else 0.0}
    outline = None
    if outline_strokes and node.stroke is not None:
        op = stroke(node.path, node.stroke.style, transform=ot, tolerance=tolerance)
        outline = dict(rec, fill=strk, fill_opacity=rec['stroke_opacity'],
                       fill_rule='nonzero', stroke=None, stroke_opacity=None,
                       stroke_width=0.0, polylines=_polylines(flatten(op, tolerance)))
        rec.update(stroke=None, stroke_opacity=None, stroke_width=0.0)
    if rec['fill'] is not None or rec['stroke'] is not None:
        rec['polylines'] = _polylines(flatten(node.path, tolerance, transform=ot))
        shapes.append(rec)
    if outline is not None and outline['polylines']:
        shapes.append(outline)
    return shapes


def _polylines(pl):
    return [{'points': pts.tolist(), 'closed': bool(closed)} for pts, closed in pl]


def _num(v):
    r = round(float(v), 6)
    return ('%.6f' % r).rstrip('0').rstrip('.') if r != int(r) else str(int(r))


def to_svg(shapes, view_box):
    x0, y0, w, h = view_box
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           '<svg xmlns="http://www.w3.org/2000/svg" width="%s" height="%s" viewBox="%s %s %s %s">'
           % (_num(w), _num(h), _num(x0), _num(y0), _num(w), _num(h))]
    for s in shapes:
        d = []
        for p in s['polylines']:
            pts = p['points']
            if not pts:
                continue
            d.append('M%s %s' % (_num(pts[0][0]), _num(pts[0][1])))
            d.extend('L%s %s' % (_num(x), _num(y)) for x, y in pts[1:])
            if p['closed']:
                d.append('Z')
        attrs = []
        if s['id']:
            attrs.append('id="%s"' % _xml(s['id']))
        for key in ('fill', 'stroke'):
            v = s[key]
            if v is None:
                attrs.append('%s="none"' % key)
            elif isinstance(v, dict):
                attrs.append('%s="none" data-%s-paint="%s"' % (key, key, _xml(v['type'])))
            else:
                attrs.append('%s="%s"' % (key, v))
                op = s[key + '_opacity']
                if op is not None and op < 1:
                    attrs.append('%s-opacity="%s"' % (key, _num(op)))
        if s['fill_rule'] == 'evenodd':
            attrs.append('fill-rule="evenodd"')
        if s['stroke'] is not None:
            attrs.append('stroke-width="%s"' % _num(s['stroke_width']))
        out.append('<path %s d="%s"/>' % (' '.join(attrs), ' '.join(d)))
    out.append('</svg>')
    return '\n'.join(out) + '\n'


def _xml(s):
    return (str(s).replace('&', '&amp;').replace('<', '&lt;').replace('>', '&gt;')
            .replace('"', '&quot;'))


def to_csv(shapes):
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator='\n')
    w.writerow(['shape_index', 'id', 'polyline_index', 'point_index', 'x', 'y', 'closed'])
    for si, s in enumerate(shapes):
        for pi, p in enumerate(s['polylines']):
            c = 1 if p['closed'] else 0
            for k, (x, y) in enumerate(p['points']):
                w.writerow([si, s['id'] or '', pi, k, repr(float(x)), repr(float(y)), c])
    return buf.getvalue()


def _body(args):
    from raster.svg import load_svg
    if list_fonts(args):
        return 0
    data = read_source(args.input)
    tree = load_svg(data, dpi=args.dpi, base_dir=base_dir_of(args.input),
                    fonts=font_options(args),
                    languages=languages_of(args))
    shapes = collect(tree, args.tolerance, args.pixels, args.outline_strokes)
    if args.format == 'json':
        text = json.dumps(shapes, indent=1) + '\n'
    elif args.format == 'csv':
        text = to_csv(shapes)
    else:
        if args.pixels:
            vb = (0.0, 0.0, tree.width, tree.height)
        else:
            inv = user_to_doc(tree).inverse()
            c = inv.apply([[0, 0], [tree.width, tree.height]])
            vb = (min(c[:, 0]), min(c[:, 1]), abs(c[1, 0] - c[0, 0]), abs(c[1, 1] - c[0, 1]))
        text = to_svg(shapes, vb)
    write_text(args.output, text)
    return 0


def main(argv=None):
    return run(PROG, _body, build_parser(), argv)


if __name__ == '__main__':
    sys.exit(main())
