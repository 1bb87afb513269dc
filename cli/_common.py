"""Shared plumbing of the command-line tools.

* :func:`run` wraps a command's body: a :class:`~raster.errors.RasterError`,
  an :class:`OSError` (or any other failure) becomes one line
  ``<prog>: error: <message>`` on stderr and exit status 1, never a
  traceback; usage errors from :mod:`argparse` exit with status 2.
* :func:`read_source` names what to read for a file or ``-`` (stdin): the
  parser reads it a piece at a time within the budgets of
  :mod:`raster.limits` (gzip, ``.svgz``, by content);
* :func:`add_limit_options` gives a command ``--unlimited`` and one
  ``--max-...`` option per budget, applied by :func:`run`.
* :func:`write_output` writes bytes to a regular file atomically (a
  temporary file in the target directory, renamed into place, removed on
  failure, so a failed run never leaves a partial file at the output path);
  anything else that exists (a character device such as ``/dev/null``, a
  FIFO, a socket, ``/dev/stdout``) is opened and written directly, never
  replaced; ``-`` is stdout.
"""

import argparse
import contextlib
import errno
import gc
import os
import re
import stat
import sys
import warnings

from raster.errors import LimitError, RasterError, RasterWarning, SVGError  # noqa: F401 (re-exported)
from raster.sources import local_path


class UsageError(Exception):
    """Bad combination of arguments found after parsing (exit status 2)."""


def _help_formatter(prog):
    """argparse's help formatter at the terminal's width (``COLUMNS``, else
    the width of the terminal on stdout, else 80), found as
    ``shutil.get_terminal_size`` does but without importing :mod:`shutil`,
    which loads bz2 and lzma: argparse builds a formatter for every
    ``add_argument``."""
    try:
        cols = int(os.environ.get('COLUMNS', ''))
    except ValueError:
        cols = 0
    if cols <= 0:
        try:
            cols = os.get_terminal_size(sys.__stdout__.fileno()).columns
        except (AttributeError, ValueError, OSError):
            cols = 0
    return argparse.HelpFormatter(prog, width=(cols or 80) - 2)


class Parser(argparse.ArgumentParser):
    """ArgumentParser that raises :class:`SystemExit` (2) with its usual
    message; :func:`run` turns that into a return value.  Help is
    formatted at the terminal's width (see :func:`_help_formatter`)."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault('formatter_class', _help_formatter)
        super().__init__(*args, **kwargs)


def add_font_options(parser):
    """Give ``parser`` the font options shared by the commands:
    ``--font-dir DIR`` and ``--font-file FILE`` (repeatable),
    ``--no-system-fonts``, ``--serif-family`` ... ``--fantasy-family`` (as
    resvg names them), ``--default-family`` and ``--list-fonts``; see
    :func:`font_options` and :func:`list_fonts`."""
    g = parser.add_argument_group('fonts')
    g.add_argument('--font-dir', action='append', default=[], metavar='DIR',
                   help='folder of fonts for text, searched before the system fonts (repeatable)')
    g.add_argument('--font-file', action='append', default=[], metavar='FILE',
                   help='a font file for text (repeatable)')
    g.add_argument('--no-system-fonts', action='store_true',
                   help="use only --font-dir and --font-file fonts, not the system's")
    for generic in ('serif', 'sans-serif', 'monospace', 'cursive', 'fantasy'):
        g.add_argument('--%s-family' % generic, metavar='NAME',
                       help='family the %s generic family resolves to' % generic)
    g.add_argument('--default-family', metavar='NAME',
                   help='family of text whose font-family names nothing available '
                        '(default: serif)')
    g.add_argument('--list-fonts', action='store_true',
                   help='print the fonts found and what each generic family resolves to, '
                        'then exit')


def font_options(args):
    """The :class:`raster.FontOptions` of parsed :func:`add_font_options`
    arguments."""
    from raster.fonts import FontOptions
    return FontOptions(dirs=tuple(args.font_dir), files=tuple(args.font_file),
                       system=not args.no_system_fonts, serif_family=args.serif_family,
                       sans_serif_family=args.sans_serif_family,
                       monospace_family=args.monospace_family,
                       cursive_family=args.cursive_family, fantasy_family=args.fantasy_family,
                       default_family=args.default_family)


def list_fonts(args, required=('input',)):
    """``--list-fonts``: print the font list (stdout) and return True; else
    check that the positional arguments ``required`` were given (a usage
    error otherwise) and return False."""
    if args.list_fonts:
        from raster.fonts import FontDB
        db = FontDB.for_options(font_options(args))
        sys.stdout.write('\n'.join(db.describe()) + '\n')
        return True
    missing = [n for n in required if getattr(args, n, None) is None]
    if missing:
        raise UsageError('the following arguments are required: %s' % ', '.join(missing))
    return False


def add_version(parser):
    """Give ``parser`` a ``--version`` option printing ``<prog> <version>``
    (the version of the installed ``raster`` package)."""
    from raster import __version__
    parser.add_argument('--version', action='version',
                        version='%s %s' % (parser.prog, __version__))


def _one_line(msg):
    msg = ' '.join(str(msg).split())
    return msg or 'unknown error'


_REPR = re.compile(r'<[^<>]*? at 0x[0-9A-Fa-f]+>')


def _no_reprs(msg):
    """``msg`` without object reprs (``<_io.BytesIO object at 0x...>``):
    heap addresses mean nothing to the user."""
    return _REPR.sub('', msg)


def error_message(exc):
    """One-line description of an exception for the user (no object
    reprs)."""
    return _no_reprs(_error_message(exc))


def _error_message(exc):
    if isinstance(exc, OSError):
        parts = [exc.strerror or str(exc)]
        if exc.filename:
            parts.append(str(exc.filename))
        return _one_line(': '.join(parts[::-1]) if exc.filename else parts[0])
    if isinstance(exc, MemoryError):
        return 'out of memory'
    if isinstance(exc, RasterError):
        return _one_line(exc)
    return _one_line('internal error: %s: %s' % (type(exc).__name__, exc))


def _budget_value(text):
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError('must be a positive number or inf, got %r' % text)
    if not v > 0:
        raise argparse.ArgumentTypeError('must be a positive number or inf, got %r' % text)
    return v


def add_limit_options(parser):
    """Give ``parser`` the budgets of :mod:`raster.limits`: ``--unlimited``
    and one ``--max-...`` option per budget (``--max-pixel-work 2048``);
    :func:`run` applies them around the command's body."""
    from raster.limits import Limits
    g = parser.add_argument_group(
        'limits', 'budgets that bound the time and memory a document may cost; over one, '
        'the element is left out with a warning (see raster.limits)')
    g.add_argument('--unlimited', action='store_true',
                   help='lift every budget (trusted input only)')
    for name, default, unit, doc in Limits.describe():
        g.add_argument('--' + name.replace('_', '-'), type=_budget_value, metavar='N',
                       dest='limit_' + name,
                       help='%s (%s; default %s)' % (doc, unit, _fmt_default(default)))


def _fmt_default(v):
    return ('%d' % v) if float(v).is_integer() and abs(v) < 1e15 else ('%g' % v)


def limits_of(args):
    """The :class:`raster.limits.Limits` the options of
    :func:`add_limit_options` ask for (None when the parser has none)."""
    if not hasattr(args, 'unlimited'):
        return None
    from raster import limits
    base = limits.UNLIMITED if args.unlimited else limits.current()
    changes = {k[len('limit_'):]: v for k, v in vars(args).items()
               if k.startswith('limit_') and v is not None}
    return base.replace(**changes) if changes else base


def install_warnings(prog):
    """Print every warning (an element skipped, no fonts for text, a
    numpy floating-point warning that escaped...) as one line
    ``<prog>: warning: <message>``, each distinct message once."""
    seen = set()

    def show(message, category, filename, lineno, file=None, line=None):
        msg = _one_line(_no_reprs(str(message)))
        if msg not in seen:
            seen.add(msg)
            print('%s: warning: %s' % (prog, msg), file=sys.stderr)
    warnings.showwarning = show


@contextlib.contextmanager
def collector_paused(freeze=False):
    """Python's cyclic garbage collector paused for the duration, then
    restored as it was.

    A command is a short process that builds tens of thousands of
    long-lived objects (the document's tree), which the collector would
    keep rescanning: a sixth of a chart's tree building.  The commands opt
    in through :func:`run`; the library itself never changes the
    collector's state.

    With ``freeze`` (a command's own process, which ends after the block)
    every object the collector tracks is moved to its permanent
    generation (:func:`gc.freeze`) before the collector is enabled again:
    otherwise the first allocation after the block scans everything the
    block made (the modules it imported included) and the interpreter's
    final collection scans it all again, 20 ms of a minimal document's
    40 ms beyond the interpreter importing numpy and lxml."""
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            if freeze:
                gc.freeze()
            gc.enable()


def one_blas_thread():
    """Ask numpy's BLAS for one thread (``OPENBLAS_NUM_THREADS=1``) when the
    user has not set it and numpy is not imported yet.

    numpy starts a BLAS thread pool as it is imported, a third of its
    import time on this project's machine (40 ms of a command's start-up);
    raster's arrays never need BLAS threads.  Only a command run from the
    command line does this (:func:`run` with ``argv`` None): it is the
    command's own process."""
    if 'numpy' not in sys.modules and 'OPENBLAS_NUM_THREADS' not in os.environ:
        os.environ['OPENBLAS_NUM_THREADS'] = '1'


#: glibc malloc thresholds of a command's own process (:func:`steady_heap`):
#: blocks up to this size come from the heap ...
HEAP_MMAP_THRESHOLD = 4 << 20
#: ... and the heap's free top is given back to the system beyond this.
HEAP_TRIM_THRESHOLD = 32 << 20


def steady_heap():
    """Fix glibc's malloc thresholds for this process (``mallopt``:
    :data:`HEAP_MMAP_THRESHOLD`, :data:`HEAP_TRIM_THRESHOLD`); returns
    whether it did.

    glibc adapts both thresholds to the largest block freed so far, so a
    render's speed depended on what came before it: after parsing a long
    path the scan's temporaries came from the heap, after the same polygon
    as ``points`` they were mapped, faulted in and given back band after
    band (a 100,000-vertex polygon at 2000 px: 123,000 page faults instead
    of 31,000 and 1.3 times the wall time, whole process, paired runs).
    Fixed thresholds keep freed blocks for reuse whatever the document.  Only a
    command run from the command line does this (:func:`run` with ``argv``
    None: the command's own process, which ends with the command), and not
    when the user set ``MALLOC_*`` or ``GLIBC_TUNABLES``, nor on other C
    libraries; the library never does."""
    if any(k.startswith('MALLOC_') or k == 'GLIBC_TUNABLES' for k in os.environ):
        return False
    try:
        if not os.confstr('CS_GNU_LIBC_VERSION'):
            return False
        import ctypes
        mallopt = ctypes.CDLL(None).mallopt
    except (ValueError, OSError, AttributeError):
        return False
    mallopt.argtypes = [ctypes.c_int, ctypes.c_int]
    # M_MMAP_THRESHOLD = -3, M_TRIM_THRESHOLD = -1 (malloc.h)
    return bool(mallopt(-3, HEAP_MMAP_THRESHOLD)) and bool(mallopt(-1, HEAP_TRIM_THRESHOLD))


def run(prog, body, parser, argv):
    """Parse ``argv`` with ``parser`` and call ``body(args)`` with the
    garbage collector paused (:func:`collector_paused`); from the command
    line (``argv`` None) numpy gets one BLAS thread (:func:`one_blas_thread`),
    malloc fixed thresholds (:func:`steady_heap`) and the objects of the
    run are frozen for the rest of the process
    (``collector_paused(freeze=True)``).

    Returns the exit status: ``body``'s return value (default 0), 1 after an
    error (one line on stderr), 2 for usage errors."""
    if argv is None:
        one_blas_thread()
        steady_heap()
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else 2
    install_warnings(prog)
    try:
        lim = limits_of(args)
        with collector_paused(freeze=argv is None):
            if lim is None:
                rc = body(args)
            else:
                from raster.limits import applied
                with applied(lim):
                    rc = body(args)
    except UsageError as e:
        parser.print_usage(sys.stderr)
        print('%s: error: %s' % (prog, _one_line(e)), file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print('%s: error: interrupted' % prog, file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 1
    except Exception as e:      # never a traceback: one line, status 1
        print('%s: error: %s' % (prog, error_message(e)), file=sys.stderr)
        return 1
    return 0 if rc is None else int(rc)


def read_source(path):
    """What :func:`raster.svg.load_svg` should read for the command-line
    input ``path``: stdin's binary stream for ``-``, else the local path
    (``file:`` URLs resolved, other URLs refused).  The document is then
    read a piece at a time while it is parsed, so input beyond
    ``max_input_bytes`` or ``max_xml_elements`` (:mod:`raster.limits`;
    files, stdin and gzip alike) fails before it is read in full, and a
    regular file's size is checked before anything is read.

    Raises
    ------
    raster.errors.RasterIOError
        ``path`` is a URL other than ``file:``.
    """
    if path == '-':
        return sys.stdin.buffer
    return local_path(path)


def metered(tree):
    """The whole-render budgets of :mod:`raster.limits` (flattened points)
    for a command that works on ``tree`` without rendering it (svg-bbox,
    svg-flatten), as a context manager."""
    from raster import limits
    return limits.metering(limits.Meter(limits.current(),
                                        int(min(tree.width * tree.height, 1e15))))


def left_out(e):
    """One shape beyond a budget (:class:`raster.errors.LimitError`) is
    left out with a warning; the rest of the document is processed."""
    warnings.warn('shape left out: %s' % e, RasterWarning, stacklevel=2)


def base_dir_of(path):
    """Directory against which a document's relative references resolve."""
    if path == '-':
        return os.getcwd()
    return os.path.dirname(os.path.abspath(local_path(path)))


def write_output(path, data):
    """Write ``data`` (bytes) to ``path``, or to stdout for ``-``.

    A regular file (or a path that does not exist yet) is written
    atomically: a temporary file beside it, renamed over it.  Any other
    existing file (a device, a FIFO, a socket, a link to one) is opened and
    written directly: renaming over it would replace the device node."""
    with open_output(path) as f:
        f.write(data)


@contextlib.contextmanager
def open_output(path):
    """A binary file to write ``path`` through, by the rules of
    :func:`write_output`: ``-`` is stdout; a regular file (or a new path)
    is a temporary file beside it, renamed into place when the block ends
    without an error and removed otherwise, so a failed or interrupted
    write never leaves a partial file at ``path``; an existing device,
    FIFO or socket is opened and written directly.  What streams its
    output (a PNG written strip by strip) writes through this."""
    if path == '-':
        yield sys.stdout.buffer
        sys.stdout.buffer.flush()
        return
    try:
        st = os.stat(path)
    except FileNotFoundError:
        st = None
    if st is not None and not stat.S_ISREG(st.st_mode):
        if stat.S_ISDIR(st.st_mode):
            raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), path)
        with open(path, 'wb') as f:
            yield f
        return
    # a link to a regular file: replace the file it names, not the link
    target = os.path.realpath(path)
    try:
        fd, tmp = _temporary_beside(target)
    except OSError as e:
        raise _about(e, path) from None
    try:
        with os.fdopen(fd, 'wb') as f:
            yield f
        # created 0600; give the file the mode a plain open() would
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, target)
    except BaseException as e:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(e, OSError):      # about the output, not the temporary file
            raise _about(e, path) from None
        raise


#: File name endings batch conversion picks up in folders.
SVG_SUFFIXES = ('.svg', '.svgz')


def collect_inputs(paths, recursive=False):
    """The documents of a batch: ``[(input path, folder relative to the
    walked root)]`` in the order given, folders walked for
    :data:`SVG_SUFFIXES` files (case-insensitive, sorted by name; with
    ``recursive`` their subfolders too, whose relative folder is kept);
    a file given by name is taken whatever its name, with folder ``''``.

    Raises
    ------
    raster.errors.RasterIOError
        A path that does not exist."""
    from raster.errors import RasterIOError
    out = []
    for p in paths:
        if p != '-' and os.path.isdir(p):
            for d, dirs, files in os.walk(p):
                dirs.sort()
                if not recursive:
                    dirs[:] = []
                rel = os.path.relpath(d, p)
                rel = '' if rel == '.' else rel
                out.extend((os.path.join(d, f), rel) for f in sorted(files)
                           if f.lower().endswith(SVG_SUFFIXES))
        elif p == '-' or os.path.exists(p):
            out.append((p, ''))
        else:
            raise RasterIOError(errno.ENOENT, 'No such file or directory', p)
    return out


def output_name(path, rel, out_dir, pattern, ext):
    """Output path of batch input ``path`` found in folder ``rel`` (see
    :func:`collect_inputs`): ``out_dir/rel/<pattern>`` where ``pattern``
    names the file with the fields ``{stem}`` (the input's name without
    ``.svg``/``.svgz``), ``{name}`` (its whole name) and ``{ext}`` (the
    output format's extension, ``png``...).

    >>> output_name('in/a/logo.svgz', 'a', 'out', '{stem}.{ext}', 'png')
    'out/a/logo.png'
    """
    name = os.path.basename(path)
    stem = name
    for suf in SVG_SUFFIXES:
        if stem.lower().endswith(suf):
            stem = stem[:-len(suf)]
            break
    try:
        fname = pattern.format(stem=stem, name=name, ext=ext)
    except (KeyError, IndexError, ValueError) as e:
        raise UsageError('--out-pattern %r: unknown field or bad format (%s); fields: '
                         '{stem} {name} {ext}' % (pattern, e)) from None
    return os.path.join(out_dir, rel, fname) if rel else os.path.join(out_dir, fname)


def cpu_count():
    """CPUs this process may run on (its affinity where the system says)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


def process_pool(jobs, initializer=None, initargs=()):
    """A pool of ``jobs`` worker processes for a command.  Where the system
    can fork, the workers are copies of the command's process, so the
    imports (and a document already parsed) are paid for once, not once
    per worker; elsewhere they are started afresh and ``initializer`` runs
    in each."""
    import multiprocessing
    methods = multiprocessing.get_all_start_methods()
    ctx = multiprocessing.get_context('fork' if 'fork' in methods else None)
    return ctx.Pool(jobs, initializer=initializer, initargs=initargs)
def _about(e, path):
    """``e`` (an OSError) told about ``path`` rather than a temporary
    file."""
    return type(e)(e.errno, e.strerror or str(e), path)


def _temporary_beside(target):
    """``(fd, path)`` of a new file ``.<name>.<random>.tmp`` in the
    directory of ``target``, created exclusively with mode 0600 (what
    ``tempfile.mkstemp`` does; :mod:`tempfile` itself imports shutil,
    random and hashlib, a tenth of the command's start-up)."""
    d, name = os.path.split(target)
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, 'O_CLOEXEC', 0)
    for _ in range(100):
        tmp = os.path.join(d, '.%s.%s.tmp' % (name, os.urandom(6).hex()))
        try:
            return os.open(tmp, flags, 0o600), tmp
        except FileExistsError:
            continue
    raise FileExistsError(errno.EEXIST, 'no unused temporary name', os.path.join(d, name))


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_text(path, text):
    write_output(path, text.encode('utf-8'))


def drawn_shapes(tree):
    """Every painted path of a resolved tree in drawing order.

    Yields ``(node, transform)``: a :class:`~raster.tree.PathNode` with a
    fill or a stroke, and the transform mapping its coordinates to the
    tree's document pixels.  Descends into groups and marker instances (not
    into clip paths, masks or patterns, which are not drawn themselves)."""
    from raster.tree import Group, PathNode
    from raster.geometry.transform import IDENTITY
    stack = [(tree.root, IDENTITY)]
    while stack:
        n, t = stack.pop()
        if isinstance(n, Group):
            t2 = t @ n.transform
            stack.extend((c, t2) for c in reversed(n.children))
        elif isinstance(n, PathNode):
            if n.path is not None and (n.fill is not None or n.stroke is not None):
                yield n, t
            if n.markers is not None:
                stack.append((n.markers, t))


def subtree_shapes(node, t):
    """Like :func:`drawn_shapes` for the subtree of one node whose parent
    coordinates map to document px by ``t``."""
    from raster.tree import Group, Tree
    for n, tt in drawn_shapes(Tree(1.0, 1.0, Group(children=[node]))):
        yield n, t @ tt


def node_transforms(tree):
    """``{id(node): transform to document px}`` of every node of the tree,
    markers included (the transform of the node's own coordinates)."""
    from raster.tree import Group, PathNode
    from raster.geometry.transform import IDENTITY
    out = {}
    stack = [(tree.root, IDENTITY)]
    while stack:
        n, t = stack.pop()
        out[id(n)] = t
        if isinstance(n, Group):
            t2 = t @ n.transform
            stack.extend((c, t2) for c in reversed(n.children))
        elif isinstance(n, PathNode) and n.markers is not None:
            stack.append((n.markers, t))
    return out


def user_to_doc(tree):
    """The root's user space to document px (the root group's transform)."""
    return tree.root.transform


def hex_color(rgba):
    """``'#rrggbb'`` of straight RGBA floats (alpha dropped)."""
    r, g, b = (max(0, min(255, int(round(float(v) * 255)))) for v in rgba[:3])
    return '#%02x%02x%02x' % (r, g, b)


def add_languages(parser):
    """Give ``parser`` a ``--languages`` option: the user's languages for
    ``systemLanguage`` (default: the environment's locale, see
    :func:`languages_of`)."""
    parser.add_argument('--languages', metavar='LIST',
                        help="the user's languages for systemLanguage, e.g. en,de-CH "
                             "(default: from LC_ALL / LC_MESSAGES / LANG, else en)")


def languages_of(args):
    """The languages a command parses with: ``--languages``, else those of
    the environment's locale (``LC_ALL``, ``LC_MESSAGES``, ``LANG``; ``en``
    without one).  A malformed list is a usage error."""
    from raster.parser.context import locale_languages, parse_languages
    if args.languages is None:
        return locale_languages()
    try:
        return parse_languages(args.languages)
    except SVGError as e:
        raise UsageError('--languages: %s' % e) from None
