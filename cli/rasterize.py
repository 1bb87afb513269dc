"""rasterize: render an SVG document to a PNG, JPEG, WebP, TIFF or BMP file.

    rasterize in.svg out.png [--width W | --height H | --zoom Z] [--dpi DPI]
              [--background COLOR] [--id ID [--id-page]] [--allow-dir DIR]
              [--format FMT] [--quality Q] [--compress-level N]
              [--font-dir DIR ...] [--font-file FILE ...] [--no-system-fonts]
              [--serif-family NAME] [--sans-serif-family NAME] [--monospace-family NAME]
              [--cursive-family NAME] [--fantasy-family NAME] [--default-family NAME]
    rasterize --list-fonts [font options]

Text is drawn with the system's fonts (and the ``--font-dir`` folders and
``--font-file`` files, searched first); ``--no-system-fonts`` uses only
those.  ``--list-fonts`` prints the faces found and what each generic
family resolves to.

``-`` reads the document from stdin or writes the image to stdout.
Compressed ``.svgz`` input is recognised by its content.  With only
``--width`` or only ``--height`` the other side keeps the aspect ratio;
both stretch.

The output format comes from ``--format``, else from the output's
extension (``.png``, ``.jpg``/``.jpeg``, ``.webp``, ``.tif``/``.tiff``,
``.bmp``); a name without an extension (``-``, a FIFO, ``/dev/stdout``) is
PNG, an unknown extension is a usage error.  JPEG and BMP have no alpha:
the image is flattened on ``--background``, on white where that is not
given or not opaque.  With ``--dpi`` the resolution is recorded in the file
(PNG ``pHYs``, JPEG, TIFF, BMP): ``--dpi`` times the output's scale of the
natural size, so the document keeps its physical size.

Errors are one line on stderr with exit status 1 (2 for usage errors); a
failed run leaves no file at the output path.
"""

import argparse
import sys

from ._common import (Parser, UsageError, add_font_options, add_languages, add_version,
                      base_dir_of, font_options, languages_of, list_fonts, read_source, run,
                      write_output)

PROG = 'rasterize'

FORMAT_CHOICES = ('png', 'jpeg', 'jpg', 'webp', 'tiff', 'tif', 'bmp')


def build_parser():
    ap = Parser(prog=PROG, description='Render an SVG document to a PNG, JPEG, WebP, TIFF or '
                'BMP image.')
    ap.add_argument('input', nargs='?', help='SVG or SVGZ file, or - for stdin')
    ap.add_argument('output', nargs='?', help='image file to write, or - for stdout')
    ap.add_argument('--width', type=int, metavar='PX', help='output width in pixels')
    ap.add_argument('--height', type=int, metavar='PX', help='output height in pixels')
    ap.add_argument('--zoom', type=float, metavar='F', help='scale factor of the natural size')
    ap.add_argument('--dpi', type=float, help='resolution for in/mm/pt units (default 96); '
                    'also recorded in the output file')
    ap.add_argument('--background', metavar='COLOR', help='background colour (any CSS colour)')
    ap.add_argument('--id', metavar='ID',
                    help='render only the element with this id, cropped to what it draws '
                         '(strokes, markers and filters included); --width/--height/--zoom '
                         'size that box')
    ap.add_argument('--id-page', action='store_true',
                    help='with --id: keep the whole page (the other elements hidden)')
    ap.add_argument('--allow-dir', metavar='DIR',
                    help='directory external files (images) may be read from')
    ap.add_argument('--format', choices=FORMAT_CHOICES, type=str.lower,
                    help='output format (default: from the extension; PNG without one)')
    ap.add_argument('--quality', type=int, metavar='Q',
                    help='JPEG quality 1-100 (default 90); WebP: lossy at Q (default lossless)')
    ap.add_argument('--compress-level', type=int, metavar='N',
                    help='PNG zlib level 0-9 (default 1)')
    ap.add_argument('--tolerance', type=float, default=None, help=argparse.SUPPRESS)
    add_font_options(ap)
    add_languages(ap)
    add_version(ap)
    return ap


def output_format(args):
    """The format to write and its checked options, before any work: a
    usage error for an unknown extension or an option of another format."""
    from raster.errors import FormatError
    from raster.pixels.encode import format_name, format_of_path
    try:
        if args.format is not None:
            fmt = format_name(args.format)
        else:
            fmt = ('png' if args.output == '-' else format_of_path(args.output)) or 'png'
    except FormatError as e:
        raise UsageError('%s; give --format' % e) from None
    if args.quality is not None:
        if fmt not in ('jpeg', 'webp'):
            raise UsageError('--quality applies to JPEG and WebP output, not %s' % fmt.upper())
        if not 1 <= args.quality <= 100:
            raise UsageError('--quality must be 1-100, got %d' % args.quality)
    if args.compress_level is not None:
        if fmt != 'png':
            raise UsageError('--compress-level applies to PNG output, not %s' % fmt.upper())
        if not 0 <= args.compress_level <= 9:
            raise UsageError('--compress-level must be 0-9, got %d' % args.compress_level)
    return fmt


def _body(args):
    import math
    from raster.errors import CanvasError
    if list_fonts(args, ('input', 'output')):
        return 0
    if args.zoom is not None and (args.width is not None or args.height is not None):
        raise UsageError('--zoom cannot be combined with --width/--height')
    dpi = 96.0 if args.dpi is None else args.dpi
    if not (math.isfinite(dpi) and dpi > 0):
        raise CanvasError('--dpi must be positive and finite, got %g' % dpi)
    fmt = output_format(args)
    from raster.svg import DEFAULT_TOLERANCE, load_svg, parse_background, render_tree
    tol = DEFAULT_TOLERANCE if args.tolerance is None else args.tolerance
    bg = parse_background(args.background)       # a bad colour fails before any work
    data = read_source(args.input)
    tree = load_svg(data, dpi=dpi, fonts=font_options(args),
                    resources_dir=args.allow_dir, base_dir=base_dir_of(args.input),
                    languages=languages_of(args))
    crop = args.id is not None and not args.id_page
    canvas = render_tree(tree, width=args.width, height=args.height, zoom=args.zoom,
                         background=bg, node_id=args.id, tolerance=tol, crop=crop,
                         dtype='uint8')
    res = None
    if args.dpi is not None:
        # the resolution at which the document keeps its physical size
        from raster.renderer import output_geometry
        sx, sy = output_geometry(tree, args.width, args.height, args.zoom, args.id,
                                 crop).scale
        res = (dpi * sx, dpi * sy)
    from raster.pixels.encode import encode_canvas
    write_output(args.output, encode_canvas(canvas, fmt, dpi=res, quality=args.quality,
                                            compress_level=args.compress_level))
    return 0


def main(argv=None):
    return run(PROG, _body, build_parser(), argv)


if __name__ == '__main__':
    sys.exit(main())
