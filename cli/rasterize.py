"""rasterize: render SVG documents to PNG, JPEG, WebP, TIFF or BMP files.

    rasterize in.svg out.png [--width W | --height H | --zoom Z] [--dpi DPI]
              [--background COLOR] [--id ID [--id-page]] [--allow-dir DIR]
              [--format FMT] [--quality Q] [--compress-level N]
              [--jobs N] [--memory-budget MB]
              [--font-dir DIR ...] [--font-file FILE ...] [--no-system-fonts]
              [--serif-family NAME] [--sans-serif-family NAME] [--monospace-family NAME]
              [--cursive-family NAME] [--fantasy-family NAME] [--default-family NAME]
    rasterize A.svg B.svg DIR ... --out-dir OUT [--recursive] [--out-pattern PAT]
              [--skip-existing] [--jobs N] [any option above]
    rasterize A.svg B.svg ... OUT/        (a last argument that is a folder)
    rasterize map.svg --tiles DIR [--min-zoom Z] [--max-zoom Z]
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

Large PNG output is rendered in strips of rows (windows of the whole
render, equal to it) and written as the strips finish, so memory stays
within ``--memory-budget`` (MB of strip pixels per process, default 256)
whatever the size, up to 4 000 million pixels; ``--jobs`` spreads the
strips of one large image over worker processes (a few strips a worker,
of about equal work, taken as workers finish).  A PNG of 65,536 pixels
or more within the budget is drawn as one strip per job (default: the
number of CPUs) at the same time: this process draws the first while
forked copies of it draw the others (where the system cannot fork, from
1 million pixels, by workers started afresh).  The pixels are the same whatever
the number of jobs, except that a resampled raster image may differ by
one level on the rows where two strips meet (Pillow's resampling
coefficients depend on where the window starts).  Other formats are
encoded by Pillow from the whole image (at most 100 million pixels).

Many files: every input (folders are walked for ``.svg``/``.svgz``,
their subfolders too with ``--recursive``, kept below ``--out-dir``) is
converted with the same options to ``--out-dir``/``--out-pattern``
(default ``{stem}.{ext}``; fields ``{stem}``, ``{name}``, ``{ext}``) by
``--jobs`` worker processes (default: the number of CPUs), each paying
the start-up once.  On a terminal a progress bar (tqdm) shows on stderr.
A file that fails gets its one-line error and the others go on;
``--skip-existing`` leaves outputs that exist alone; a summary line ends
the run, with exit status 1 if any file failed.

``--tiles DIR`` writes an XYZ pyramid of 256 px PNG tiles,
``DIR/z/x/y.png``: at zoom z the document's longer side is 256 * 2**z px
(zoom levels ``--min-zoom`` to ``--max-zoom``, default 0 to the first
level at the natural size), with ``DIR/tiles.json`` describing the levels
and the bounds.

Errors are one line on stderr with exit status 1 (2 for usage errors); a
failed run leaves no file at the output path.
"""

import argparse
import os
import sys
import time

from ._common import (Parser, UsageError, add_font_options, add_languages, add_limit_options,
                      add_version, base_dir_of, collect_inputs, cpu_count, error_message,
                      font_options, install_warnings, languages_of, list_fonts, open_output,
                      output_name, process_pool, read_source, run, write_output)

PROG = 'rasterize'

FORMAT_CHOICES = ('png', 'jpeg', 'jpg', 'webp', 'tiff', 'tif', 'bmp')
_EXT = {'png': 'png', 'jpeg': 'jpg', 'webp': 'webp', 'tiff': 'tif', 'bmp': 'bmp'}

#: One image spreads its strips over forked copies of the command from
#: this many pixels on.  Measured on the corpus at its natural sizes (120k
#: to 810k pixels) and on crossing-heavy 400x400 cases, a forked strip
#: costs about 3-10 ms and saves up to a third of the wall time wherever
#: the scan or the pixels cost more than that; a small icon has nothing to
#: share.
PARALLEL_PIXELS = 65_536
#: The same where the system cannot fork: workers started afresh each pay
#: an import of raster, worth it for large images only.
SPAWN_PARALLEL_PIXELS = 1_000_000


def build_parser():
    ap = Parser(prog=PROG, description='Render SVG documents to PNG, JPEG, WebP, TIFF or '
                'BMP images: one file, many files (--out-dir), or map tiles (--tiles).')
    ap.add_argument('paths', nargs='*', metavar='PATH',
                    help='INPUT OUTPUT for one file (- for stdin/stdout); with --out-dir, or '
                         'a last argument that is a folder, every PATH is an input (folders '
                         'are walked for .svg/.svgz)')
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
    g = ap.add_argument_group('many files, large images, map tiles')
    g.add_argument('--out-dir', metavar='DIR',
                   help='convert every PATH into this folder (created if needed)')
    g.add_argument('--recursive', action='store_true',
                   help='walk the subfolders of input folders too (kept below --out-dir)')
    g.add_argument('--out-pattern', metavar='PAT', default=None,
                   help='output file name: fields {stem} {name} {ext} (default {stem}.{ext})')
    g.add_argument('--skip-existing', action='store_true',
                   help='leave inputs whose output exists alone')
    g.add_argument('--jobs', '-j', type=int, metavar='N',
                   help='worker processes for many files, the strips of a large image or '
                        'tiles (default: the number of CPUs)')
    g.add_argument('--memory-budget', type=float, metavar='MB', default=256.0,
                   help='memory for the pixels a process renders at once, in MB (default '
                        '256): larger PNG output is rendered and written in strips')
    g.add_argument('--tiles', metavar='DIR',
                   help='write an XYZ pyramid of 256 px PNG tiles DIR/z/x/y.png and '
                        'DIR/tiles.json instead of one image')
    g.add_argument('--min-zoom', type=int, default=0, metavar='Z',
                   help='with --tiles: first zoom level (default 0)')
    g.add_argument('--max-zoom', type=int, metavar='Z',
                   help='with --tiles: last zoom level (default: where the longer side '
                        'reaches the natural size)')
    g.add_argument('--all-tiles', action='store_true',
                   help='with --tiles: write fully transparent tiles too (by default they '
                        'are left out: map clients draw a missing tile as blank)')
    add_font_options(ap)
    add_languages(ap)
    add_limit_options(ap)
    add_version(ap)
    return ap


def output_format(args, output=None):
    """The format to write and its checked options, before any work: a
    usage error for an unknown extension or an option of another format."""
    from raster.errors import FormatError
    from raster.pixels.encode import format_name, format_of_path
    try:
        if args.format is not None:
            fmt = format_name(args.format)
        elif output is None:
            fmt = 'png'
        else:
            fmt = ('png' if output == '-' else format_of_path(output)) or 'png'
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


def _check_common(args):
    """Options every mode checks before any work: returns the dpi."""
    import math
    from raster.errors import CanvasError
    if args.zoom is not None and (args.width is not None or args.height is not None):
        raise UsageError('--zoom cannot be combined with --width/--height')
    dpi = 96.0 if args.dpi is None else args.dpi
    if not (math.isfinite(dpi) and dpi > 0):
        raise CanvasError('--dpi must be positive and finite, got %g' % dpi)
    if args.jobs is not None and args.jobs < 1:
        raise UsageError('--jobs must be at least 1, got %d' % args.jobs)
    if not (args.memory_budget > 0 and math.isfinite(args.memory_budget)):
        raise UsageError('--memory-budget must be a positive number of MB')
    return dpi


def _budget(args):
    return max(1, int(args.memory_budget * 1024 * 1024))


def _jobs(args):
    return cpu_count() if args.jobs is None else args.jobs


def _body(args):
    if list_fonts(args, ()):
        return 0
    dpi = _check_common(args)
    paths = list(args.paths)
    if args.tiles is not None:
        if len(paths) != 1 or args.out_dir is not None:
            raise UsageError('--tiles takes one input document')
        if args.format not in (None, 'png') or args.quality is not None:
            raise UsageError('--tiles writes PNG tiles')
        return _tiles(args, dpi, paths[0])
    out_dir = args.out_dir
    if out_dir is None and len(paths) >= 2 and (
            paths[-1].endswith(('/', os.sep)) or os.path.isdir(paths[-1])):
        out_dir = paths.pop()
    if out_dir is None and len(paths) == 2 and not os.path.isdir(paths[0]):
        if args.recursive or args.out_pattern is not None or args.skip_existing:
            raise UsageError('--recursive, --out-pattern and --skip-existing go with --out-dir')
        return _single(args, dpi, paths[0], paths[1])
    if out_dir is None:
        if len(paths) < 2:
            raise UsageError('the following arguments are required: %s (or inputs and '
                             '--out-dir DIR)' % ('input, output' if not paths else 'output'))
        raise UsageError('many inputs need --out-dir DIR (or a folder as the last argument)')
    if not paths:
        raise UsageError('no input documents given')
    return _batch(args, dpi, paths, out_dir)


# -- one document -----------------------------------------------------------------------

def _load(args, dpi, path):
    from raster.svg import load_svg
    data = read_source(path)
    return load_svg(data, dpi=dpi, fonts=font_options(args), resources_dir=args.allow_dir,
                    base_dir=base_dir_of(path), languages=languages_of(args))


def _tolerance(args):
    """The flattening tolerance: --tolerance, else the renderer's default."""
    if args.tolerance is not None:
        return args.tolerance
    from raster.renderer import DEFAULT_TOLERANCE
    return DEFAULT_TOLERANCE


def _render_kw(args, bg):
    crop = args.id is not None and not args.id_page
    return dict(width=args.width, height=args.height, zoom=args.zoom, background=bg,
                node_id=args.id, tolerance=_tolerance(args), crop=crop)


def _single(args, dpi, inp, out):
    fmt = output_format(args, out)
    from raster.svg import parse_background
    bg = parse_background(args.background)       # a bad colour fails before any work
    convert(args, dpi, fmt, bg, inp, out, _jobs(args))
    return 0


def convert(args, dpi, fmt, bg, inp, out, jobs=1):
    """Render document ``inp`` to ``out`` in format ``fmt``: in one piece,
    or as PNG in strips (over ``jobs`` workers) when the image is beyond
    the memory budget or large enough for the workers to pay."""
    from raster import limits
    from raster.errors import CanvasError
    from raster.renderer import MAX_WINDOWED_PIXELS, output_geometry, render_tree
    from raster.renderer.tiles import (BYTES_PER_PIXEL, balanced_spans, row_work, strip_rows,
                                       strip_spans)
    tree = _load(args, dpi, inp)
    kw = _render_kw(args, bg)
    g = output_geometry(tree, kw['width'], kw['height'], kw['zoom'], kw['node_id'], kw['crop'],
                        max_pixels=MAX_WINDOWED_PIXELS)
    res = None if args.dpi is None else (dpi * g.scale[0], dpi * g.scale[1])
    budget = _budget(args)
    pixels = g.width * g.height
    big = pixels * BYTES_PER_PIXEL > budget
    share = PARALLEL_PIXELS if hasattr(os, 'fork') else SPAWN_PARALLEL_PIXELS
    if fmt == 'png' and (big or (jobs > 1 and pixels >= share)):
        from raster.pixels.png import DEFAULT_LEVEL, PNGWriter
        level = DEFAULT_LEVEL if args.compress_level is None else args.compress_level
        workers = max(1, jobs)
        # the budget is per process.  The strips are of about equal
        # estimated work (row_work: where the paths are), at least
        # MIN_STRIPS of them, whatever the number of workers (so is the
        # file); workers take them in order as each finishes one, so none
        # waits long for the last.  A process keeps the outlines crossing
        # into its next strips (EdgeStore): the strips cost about the whole
        # render's flattening.  An image within the budget drawn in strips
        # only to use the workers gets STRIPS_PER_WORKER a worker.
        rows = strip_rows(g.width, budget)
        count = max(len(strip_spans(g.height, rows)),
                    MIN_STRIPS if big else STRIPS_PER_WORKER * workers)
        spans = balanced_spans(row_work(g.node, g.transform, g.width, g.height), count, rows)
        job = (tree, kw, level)
        with open_output(out) as f:
            png = PNGWriter(f, g.width, g.height, level, dpi=res)
            if not big and 1 < len(spans) <= workers and hasattr(os, 'fork'):
                # one strip each: this process draws the first while forked
                # copies draw the others (no pool to start or feed)
                for piece in _forked_strips(job, spans):
                    png.write_compressed(piece)
            elif workers > 1 and len(spans) > 1:
                global _JOB
                _JOB = job
                try:
                    with _pool(min(workers, len(spans)), '_JOB', job) as pool:
                        for piece in pool.imap(_strip_piece, spans):
                            png.write_compressed(piece)
                finally:
                    _JOB = None
            else:
                try:
                    for span in spans:
                        png.write_compressed(_compress_strip(job, span))
                finally:
                    _forget_store()
            png.close()
        return
    if pixels > limits.current().max_pixels:
        raise CanvasError('output size %d x %d exceeds %d pixels for %s output (PNG is '
                          'written in strips up to %d pixels)'
                          % (g.width, g.height, limits.current().max_pixels, fmt.upper(),
                             MAX_WINDOWED_PIXELS))
    canvas = render_tree(tree, dtype='uint8', **kw)
    from raster.pixels.encode import encode_canvas
    write_output(out, encode_canvas(canvas, fmt, dpi=res, quality=args.quality,
                                    compress_level=args.compress_level))


#: What forked workers of one image render: (tree, render_tree options, level).
_JOB = None


def _pool(workers, name, value):
    """A pool of ``workers`` processes (:func:`process_pool`) whose workers
    see ``value`` as this module's global ``name``: forked copies inherit
    it; workers started afresh, where the system cannot fork, get it (with
    the limits and the warning lines in force here) from
    :func:`_worker_start`, which needs ``value`` to pickle."""
    from raster import limits
    return process_pool(workers, _worker_start, (name, value, limits.current()))


#: The limits a worker started afresh keeps applied (see :func:`_pool`).
_WORKER_LIMITS = None


def _worker_start(name, value, lim):
    global _WORKER_LIMITS
    if globals()[name] is value:            # a forked copy: it has all of it
        return
    globals()[name] = value
    from raster import limits
    _WORKER_LIMITS = limits.applied(lim)
    _WORKER_LIMITS.__enter__()              # for the life of the worker
    install_warnings(PROG)

#: Fewest strips of an image beyond the memory budget, and strips per
#: worker of one within it spread over workers.
MIN_STRIPS = 4
STRIPS_PER_WORKER = 1

#: The EdgeStore of this process's windows (the strips or tiles of one
#: output at a time; see raster.renderer.EdgeStore).
_STORE = None


def _store():
    global _STORE
    if _STORE is None:
        from raster.renderer import EdgeStore
        _STORE = EdgeStore()
    return _STORE


def _forget_store():
    global _STORE
    _STORE = None


def _compress_strip(job, span, keep=True):
    """The compressed PNG strip of rows ``span`` of ``job``'s image;
    ``keep``: the process draws more strips after it, top to bottom, and
    keeps the outlines reaching into them (the EdgeStore)."""
    from raster.pixels.png import compress_strip
    from raster.renderer import render_tree
    tree, kw, level = job
    y0, y1 = span
    from raster.renderer import MAX_WINDOWED_PIXELS, output_geometry
    g = output_geometry(tree, kw['width'], kw['height'], kw['zoom'], kw['node_id'], kw['crop'],
                        max_pixels=MAX_WINDOWED_PIXELS)
    canvas = render_tree(tree, dtype='uint8', window=(0, y0, g.width, y1),
                         store=_store() if keep else None, **kw)
    rgba = canvas.to_rgba8()
    del canvas
    return compress_strip(rgba, level, first=y0 == 0)


def _strip_piece(span):
    return _compress_strip(_JOB, span)


def _forked_strips(job, spans):
    """The compressed strips of ``spans`` in order (an iterator): the first
    drawn by this process, each other at the same time by a forked copy of
    it, which sends its strip back through a pipe (or its exception, raised
    here; a copy that dies without either is a RasterError).  Copies still
    running when the iterator is left are killed."""
    import pickle
    import signal
    from raster.errors import RasterError
    kids = []
    try:
        for span in spans[1:]:
            r, w = os.pipe()
            pid = os.fork()
            if pid == 0:                                    # the copy
                code = 1
                try:
                    os.close(r)
                    try:
                        data = b'+' + pickle.dumps(_compress_strip(job, span, False), -1)
                        code = 0
                    except BaseException as e:              # noqa: B036 (sent back)
                        try:
                            data = b'!' + pickle.dumps((str(e), e), -1)
                        except Exception:
                            data = b'!' + pickle.dumps((str(e), None), -1)
                    with os.fdopen(w, 'wb') as f:
                        f.write(data)
                finally:
                    os._exit(code)
            os.close(w)
            kids.append([pid, r, span])
        yield _compress_strip(job, spans[0], False)
        for kid in kids:
            with os.fdopen(kid[1], 'rb') as f:
                kid[1] = None
                data = f.read()
            _, status = os.waitpid(kid[0], 0)
            kid[0] = None
            if data[:1] == b'+':
                yield pickle.loads(data[1:])
                continue
            if data[:1] == b'!':
                try:
                    text, exc = pickle.loads(data[1:])
                except Exception:
                    text, exc = 'an error the process could not send back', None
                if isinstance(exc, BaseException):
                    raise exc
                raise RasterError('rows %d-%d: %s' % (kid[2][0], kid[2][1], text))
            how = ('killed by signal %d' % os.WTERMSIG(status) if os.WIFSIGNALED(status)
                   else 'exit status %d' % os.waitstatus_to_exitcode(status))
            raise RasterError('the process drawing rows %d-%d ended without them (%s)'
                              % (kid[2][0], kid[2][1], how))
    finally:
        for pid, r, _ in kids:
            if r is not None:
                os.close(r)
            if pid is not None:
                try:
                    os.kill(pid, signal.SIGKILL)
                    os.waitpid(pid, 0)
                except OSError:
                    pass


# -- many documents ---------------------------------------------------------------------

def _batch(args, dpi, paths, out_dir):
    from raster.svg import parse_background
    if '-' in paths:
        raise UsageError('stdin (-) cannot be one of many inputs')
    fmt = output_format(args)
    bg = parse_background(args.background)
    pattern = args.out_pattern or '{stem}.{ext}'
    ext = _EXT[fmt]
    if args.out_pattern is not None:
        from raster.pixels.encode import format_of_path
        from raster.errors import FormatError
        try:
            pfmt = format_of_path(pattern.replace('{', '').replace('}', ''))
        except FormatError:
            pfmt = None
        if args.format is None and pfmt is not None:
            fmt, ext = pfmt, _EXT[pfmt]
            output_format(args, 'x.' + ext)
    items = collect_inputs(paths, args.recursive)
    tasks, seen = [], {}
    for inp, rel in items:
        out = output_name(inp, rel, out_dir, pattern, ext)
        key = os.path.abspath(out)
        if key in seen:
            raise UsageError('%s and %s would both write %s' % (seen[key], inp, out))
        seen[key] = inp
        tasks.append((inp, out))
    skipped = 0
    if args.skip_existing:
        todo = [t for t in tasks if not os.path.exists(t[1])]
        skipped = len(tasks) - len(todo)
        tasks = todo
    jobs = min(_jobs(args), max(1, len(tasks)))
    start = time.perf_counter()
    global _BATCH
    _BATCH = (args, dpi, fmt, bg, jobs)
    failed = done = 0
    bar = _progress(len(tasks))
    try:
        if jobs > 1:
            with _pool(jobs, '_BATCH', _BATCH) as pool:
                # a few files per hand-over: one round trip per file
                # costs the parent (on the same cores) more than the
                # small imbalance of the last chunks
                results = pool.imap_unordered(_batch_one, tasks, batch_chunk(len(tasks), jobs))
                for r in results:
                    failed += _report(bar, r)
                    done += 1
        else:
            for t in tasks:
                failed += _report(bar, _batch_one(t))
                done += 1
    finally:
        _BATCH = None
        if bar is not None:
            bar.close()
    secs = time.perf_counter() - start
    print('%s: %d of %d files converted, %d skipped, %d failed in %.2f s (%d jobs)'
          % (PROG, done - failed, len(tasks) + skipped, skipped, failed, secs, jobs),
          file=sys.stderr)
    return 1 if failed else 0


#: What forked batch workers convert with: (args, dpi, format, background, jobs).
_BATCH = None

#: Hand-overs per worker a batch is cut into at least (more of them keep
#: the workers' loads even when file sizes differ; fewer cost fewer round
#: trips between the processes).
CHUNKS_PER_WORKER = 16


def batch_chunk(files, jobs):
    """Files per hand-over to a worker for a batch of ``files`` over
    ``jobs`` workers: at least 1, and at least ``CHUNKS_PER_WORKER``
    hand-overs per worker."""
    return max(1, files // (max(1, jobs) * CHUNKS_PER_WORKER))


def _batch_one(task):
    """Convert one file of a batch: ``(input, output, error line or None,
    [warning lines])``; never raises for the file's own failures."""
    import warnings
    inp, out = task
    args, dpi, fmt, bg, jobs = _BATCH
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter('always')
        try:
            d = os.path.dirname(out)
            if d:
                os.makedirs(d, exist_ok=True)
            convert(args, dpi, fmt, bg, inp, out, 1)
            err = None
        except KeyboardInterrupt:
            raise
        except Exception as e:
            err = error_message(e)
    return inp, out, err, [' '.join(str(w.message).split()) for w in caught]


def _progress(total):
    """A tqdm bar on stderr when it is a terminal, else None."""
    if total < 2 or not sys.stderr.isatty():
        return None
    from tqdm import tqdm
    return tqdm(total=total, unit='file', file=sys.stderr, dynamic_ncols=True)


def _report(bar, result):
    inp, out, err, warns = result
    lines = ['%s: warning: %s: %s' % (PROG, inp, w) for w in dict.fromkeys(warns)]
    if err is not None:
        lines.append('%s: error: %s: %s' % (PROG, inp, err))
    for line in lines:
        if bar is not None:
            bar.write(line, file=sys.stderr)
        else:
            print(line, file=sys.stderr)
    if bar is not None:
        bar.update(1)
    return 1 if err is not None else 0


# -- map tiles --------------------------------------------------------------------------

def _tiles(args, dpi, inp):
    import json
    from raster.svg import parse_background
    from raster.renderer.tiles import TILE_SIZE, default_max_zoom, xyz_levels
    if args.width is not None or args.height is not None or args.zoom is not None:
        raise UsageError('--tiles sizes each level itself: no --width/--height/--zoom')
    if args.id is not None and args.id_page is False:
        raise UsageError('--tiles renders the page: --id needs --id-page')
    bg = parse_background(args.background)
    tree = _load(args, dpi, inp)
    maxz = default_max_zoom(tree.width, tree.height) if args.max_zoom is None else args.max_zoom
    if args.min_zoom > maxz:
        raise UsageError('--min-zoom %d is above the last zoom level %d' % (args.min_zoom, maxz))
    levels = xyz_levels(tree.width, tree.height, args.min_zoom, maxz)
    level = 1 if args.compress_level is None else args.compress_level
    budget = _budget(args)
    jobs = _jobs(args)
    tasks = []
    for lv in levels:
        # pieces of whole tile rows, as many tiles across as the budget allows
        per = max(1, budget // (24 * TILE_SIZE * TILE_SIZE * max(1, jobs)))
        for row in range(lv.rows):
            for c0 in range(0, lv.columns, per):
                tasks.append((lv, row, c0, min(lv.columns, c0 + per)))
    global _TILES
    _TILES = (tree, bg, args, level, args.tiles)
    count = skipped = 0
    bar = _progress(len(tasks))
    try:
        if jobs > 1 and len(tasks) > 1:
            with _pool(min(jobs, len(tasks)), '_TILES', _TILES) as pool:
                for n, k in pool.imap(_tile_piece, tasks):
                    count += n
                    skipped += k
                    if bar is not None:
                        bar.update(1)
        else:
            for t in tasks:
                n, k = _tile_piece(t)
                count += n
                skipped += k
                if bar is not None:
                    bar.update(1)
    finally:
        _TILES = None
        _forget_store()
        if bar is not None:
            bar.close()
    meta = {'scheme': 'xyz', 'format': 'png', 'tile_size': TILE_SIZE,
            'minzoom': levels[0].zoom, 'maxzoom': levels[-1].zoom,
            'bounds': [0.0, 0.0, float(tree.width), float(tree.height)],
            'bounds_units': 'document px (x right, y down) of level 0 to its width, height',
            'levels': [{'zoom': lv.zoom, 'width': lv.width, 'height': lv.height,
                        'columns': lv.columns, 'rows': lv.rows,
                        'scale': lv.width / tree.width} for lv in levels],
            # as web map tile generators do for sparse maps: a missing tile
            # is a fully transparent one (clients draw it blank)
            'empty_tiles': 'written' if args.all_tiles else 'omitted',
            'tiles_written': count, 'tiles_omitted': skipped}
    os.makedirs(args.tiles, exist_ok=True)
    write_output(os.path.join(args.tiles, 'tiles.json'),
                 (json.dumps(meta, indent=1) + '\n').encode('utf-8'))
    print('%s: %d tiles, zoom %d-%d, in %s%s'
          % (PROG, count, levels[0].zoom, levels[-1].zoom, args.tiles,
             ' (%d empty tiles omitted)' % skipped if skipped else ''), file=sys.stderr)
    return 0


#: What forked tile workers render: (tree, background, args, level, folder).
_TILES = None


def _tile_piece(task):
    """Render tiles ``c0 .. c1 - 1`` of one tile row of a level as one
    window and write them (fully transparent ones only with
    ``--all-tiles``); returns ``(written, omitted)``."""
    import numpy as np
    from raster.pixels.png import encode_png
    from raster.renderer import render_tree
    from raster.renderer.tiles import TILE_SIZE
    lv, row, c0, c1 = task
    tree, bg, args, level, folder = _TILES
    T = TILE_SIZE
    x0, y0 = c0 * T, row * T
    x1, y1 = min(lv.width, c1 * T), min(lv.height, (row + 1) * T)
    side = dict(width=lv.width) if tree.width >= tree.height else dict(height=lv.height)
    canvas = render_tree(tree, background=bg, node_id=args.id, tolerance=_tolerance(args),
                         dtype='uint8', window=(x0, y0, x1, y1), store=_store(), **side)
    rgba = canvas.to_rgba8()
    del canvas
    n = k = 0
    for c in range(c0, c1):
        part = rgba[:, (c - c0) * T:(c - c0 + 1) * T]
        if not args.all_tiles and not part[..., 3].any():
            k += 1
            continue
        tile = np.zeros((T, T, 4), np.uint8)
        tile[:part.shape[0], :part.shape[1]] = part
        d = os.path.join(folder, str(lv.zoom), str(c))
        os.makedirs(d, exist_ok=True)
        write_output(os.path.join(d, '%d.png' % row), encode_png(tile, level))
        n += 1
    return n, k


def main(argv=None):
    return run(PROG, _body, build_parser(), argv)


if __name__ == '__main__':
    sys.exit(main())
