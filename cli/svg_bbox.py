"""svg-bbox: exact bounding boxes of an SVG document and its elements.

    svg-bbox in.svg [--id ID] [--stroke] [font options]

Prints JSON ``{"units": "user", "document": [xmin, ymin, xmax, ymax],
"elements": {id: [xmin, ymin, xmax, ymax], ...}}``.  Boxes are in the root
``<svg>`` element's user units (its ``viewBox`` coordinates, or CSS px
without one), x right and y down.  ``document`` is the union of every drawn
shape; ``elements`` holds every element with an id that draws something
(the union of its shapes; null when it draws nothing).  Boxes are of the
geometry (fill area) unless ``--stroke`` is given, which includes the
stroke outlines (joins, caps, dashes).  ``--id`` reports only that element
(an unknown id is an error).  Text elements have the exact boxes of their
glyph outlines, laid out with the system's fonts and the font options of
``rasterize`` (``--font-dir``, ``--font-file``, ``--no-system-fonts``,
``--serif-family`` ..., ``--list-fonts``).
"""

import json
import sys

from ._common import (LimitError, Parser, add_font_options, add_languages, add_limit_options,
                      add_version, base_dir_of, font_options, languages_of, left_out, list_fonts,
                      metered, read_source, run, user_to_doc, write_text)

PROG = 'svg-bbox'

#: Tolerance (user units) of stroke outlines when an exact stroke box is not
#: available.
STROKE_TOLERANCE = 1e-4


def shape_box(node, t, with_stroke=False):
    """Box (x0, y0, x1, y1) of one PathNode under ``t``, or None."""
    from raster.errors import RasterError
    path = node.path
    if path is None or len(path.verbs) == 0:
        return None
    boxes = []
    if node.fill is not None or not with_stroke or node.stroke is None:
        boxes.append(_path_box(path, t))
    if with_stroke and node.stroke is not None:
        from raster.geometry.stroking import stroke
        style = node.stroke.style
        box = None
        try:
            from raster.geometry.bounds import bbox as exact
            box = tuple(float(v) for v in exact(path, transform=t, stroke=style,
                                                tolerance=STROKE_TOLERANCE))
        except (ImportError, TypeError, RasterError, AttributeError):
            out = stroke(path, style, transform=t, tolerance=STROKE_TOLERANCE)
            if len(out.points):
                box = out.control_box()
        if box is not None:
            boxes.append(box)
        elif node.fill is None:
            boxes.append(_path_box(path, t))
    return _union_all(boxes)


def _path_box(path, t):
    from raster.errors import RasterError
    try:
        from raster.geometry.bounds import bbox as exact
        return tuple(float(v) for v in exact(path, transform=t))
    except (ImportError, TypeError, AttributeError):
        pass
    except RasterError:
        return None
    from raster.geometry.flattening import flatten
    pts = flatten(path, 1e-6, transform=t).points
    if len(pts) == 0:
        return None
    lo, hi = pts.min(0), pts.max(0)
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def _union_all(boxes):
    boxes = [b for b in boxes if b is not None]
    if not boxes:
        return None
    return (min(b[0] for b in boxes), min(b[1] for b in boxes),
            max(b[2] for b in boxes), max(b[3] for b in boxes))


def boxes(tree, with_stroke=False, only_id=None):
    """``{'units': 'user', 'document': box, 'elements': {id: box}}`` in the
    root's user units; boxes are ``[x0, y0, x1, y1]`` lists or None.

    One pass over the tree: each drawn shape's box is computed once and
    united into the boxes of the nodes above it (children before parents),
    so nested elements with ids cost no more than the shapes themselves.
    A shape over a budget of :mod:`raster.limits` is left out with one
    warning."""
    from raster.errors import SVGError
    from raster.tree import Group, PathNode
    from raster.geometry.transform import IDENTITY
    to_user = user_to_doc(tree).inverse()
    ids = dict(tree.ids) if isinstance(tree.ids, dict) else {}
    if only_id is not None:
        if only_id not in ids:
            raise SVGError('no element with id %r' % (only_id,))
        ids = {only_id: ids[only_id]}
    # pre-order list of (node, transform of its coordinates, parent index)
    order = []
    where = {}                          # id(node) -> its last index (as node_transforms)
    stack = [(tree.root, IDENTITY, -1)]
    while stack:
        n, t, parent = stack.pop()
        k = len(order)
        order.append((n, t, parent))
        where[id(n)] = k
        if isinstance(n, Group):
            t2 = t @ n.transform
            stack.extend((c, t2, k) for c in reversed(n.children))
        elif isinstance(n, PathNode) and n.markers is not None:
            stack.append((n.markers, t, k))
    box = [None] * len(order)
    warned = False
    with metered(tree):
        for k in range(len(order) - 1, -1, -1):          # children before parents
            n, t, parent = order[k]
            if (isinstance(n, PathNode) and n.path is not None
                    and (n.fill is not None or n.stroke is not None)):
                try:
                    b = shape_box(n, to_user @ t, with_stroke)
                except LimitError as e:
                    if not warned:
                        warned = True
                        left_out(e)
                    b = None
                box[k] = _union_all([box[k], b])
            if parent >= 0 and box[k] is not None:
                box[parent] = _union_all([box[parent], box[k]])
    elements = {}
    for key in sorted(ids):
        k = where.get(id(ids[key]))
        elements[key] = None if k is None else _fmt(box[k])
    return {'units': 'user', 'document': _fmt(box[0]) if box else None, 'elements': elements}


def _fmt(b):
    if b is None:
        return None
    return [round(float(v), 9) + 0.0 for v in b]


def build_parser():
    ap = Parser(prog=PROG, description='Exact bounding boxes of an SVG document and of its '
                'elements with an id, in the root user units, as JSON.')
    ap.add_argument('input', nargs='?', help='SVG or SVGZ file, or - for stdin')
    ap.add_argument('--id', metavar='ID', help='report only this element')
    ap.add_argument('--stroke', action='store_true', help='include stroke outlines')
    ap.add_argument('-o', '--output', default='-', help='output file (default: stdout)')
    add_font_options(ap)
    add_languages(ap)
    add_limit_options(ap)
    add_version(ap)
    return ap


def _body(args):
    from raster.svg import load_svg
    if list_fonts(args):
        return 0
    data = read_source(args.input)
    tree = load_svg(data, base_dir=base_dir_of(args.input), fonts=font_options(args),
                    languages=languages_of(args))
    result = boxes(tree, args.stroke, args.id)
    write_text(args.output, json.dumps(result, indent=1) + '\n')
    return 0


def main(argv=None):
    return run(PROG, _body, build_parser(), argv)


if __name__ == '__main__':
    sys.exit(main())
