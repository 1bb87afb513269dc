"""rasterize: render an SVG document to a PNG file.

    rasterize in.svg out.png [--width W | --height H | --zoom Z] [--dpi DPI]
              [--background COLOR] [--font-dir DIR ...] [--id ID] [--allow-dir DIR]

``-`` reads the document from stdin or writes the PNG to stdout.  Compressed
``.svgz`` input is recognised by its content.  With only ``--width`` or only
``--height`` the other side keeps the aspect ratio; both stretch.  Errors are
one line on stderr with exit status 1 (2 for usage errors); a failed run
leaves no file at the output path.
"""

import argparse
import sys

from ._common import Parser, UsageError, base_dir_of, read_source, run, write_output

PROG = 'rasterize'


def build_parser():
    ap = Parser(prog=PROG, description='Render an SVG document to a PNG image.')
    ap.add_argument('input', help='SVG or SVGZ file, or - for stdin')
    ap.add_argument('output', help='PNG file to write, or - for stdout')
    ap.add_argument('--width', type=int, metavar='PX', help='output width in pixels')
    ap.add_argument('--height', type=int, metavar='PX', help='output height in pixels')
    ap.add_argument('--zoom', type=float, metavar='F', help='scale factor of the natural size')
    ap.add_argument('--dpi', type=float, default=96.0, help='resolution for in/mm/pt units '
                    '(default %(default)s)')
    ap.add_argument('--background', metavar='COLOR', help='background colour (any CSS colour)')
    ap.add_argument('--font-dir', action='append', default=[], metavar='DIR',
                    help='directory of fonts for text (repeatable)')
    ap.add_argument('--id', metavar='ID', help='render only the element with this id')
    ap.add_argument('--allow-dir', metavar='DIR',
                    help='directory external files (images) may be read from')
    ap.add_argument('--tolerance', type=float, default=0.25, help=argparse.SUPPRESS)
    return ap


def _body(args):
    import math
    from raster.errors import CanvasError
    if args.zoom is not None and (args.width is not None or args.height is not None):
        raise UsageError('--zoom cannot be combined with --width/--height')
    if not (math.isfinite(args.dpi) and args.dpi > 0):
        raise CanvasError('--dpi must be positive and finite, got %g' % args.dpi)
    from raster.svg import load_svg, parse_background
    from raster.svg.render import render_tree
    bg = parse_background(args.background)            # a bad colour fails before any work
    data = read_source(args.input)
    tree = load_svg(data, dpi=args.dpi, font_dirs=args.font_dir,
                    resources_dir=args.allow_dir, base_dir=base_dir_of(args.input))
    canvas = render_tree(tree, width=args.width, height=args.height, zoom=args.zoom,
                         background=bg, node_id=args.id, tolerance=args.tolerance)
    from raster.png import encode_png
    write_output(args.output, encode_png(canvas.to_rgba8()))
    return 0


def main(argv=None):
    return run(PROG, _body, build_parser(), argv)


if __name__ == '__main__':
    sys.exit(main())
