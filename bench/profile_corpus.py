"""Where does raster's SVG pipeline spend its time?  Per-stage profile.

Run from the repository root::

    python bench/profile_corpus.py [FILES ...] [--width 2000] [--top 25] [--repeat 3]

FILES are corpus file names or substrings (default: every file of
``../shared/corpus``).  For each file two measurements are made:

1. *Stage times, no profiler*: the public stages are timed one after
   the other, in wall-clock and in process CPU time (median of
   ``--repeat`` runs each): XML parse
   (``raster.parser.document.load_document``), tree build incl. CSS cascade
   (``raster.parser.build_tree``), rendering (``render_tree``: path
   parse, flatten, stroke, scan conversion, compositing), conversion to
   8-bit (``Canvas.to_rgba8``) and PNG encode (:func:`raster.pixels.png.encode_png`, at
   ``raster.pixels.canvas.DEFAULT_COMPRESS_LEVEL``).
2. *cProfile attribution*: one run under cProfile.  Every function's own
   time is assigned to a stage by the module it lives in (``raster/scan.py``
   -> scan conversion, ...).  Time spent in code outside raster (numpy,
   builtins, ``re``) is handed up to its callers in proportion to the time
   each caller spent in it, until it reaches raster code, so
   ``np.add.at`` called from ``scan.py`` counts as scan conversion.  lxml
   counts as XML parse and zlib (called from raster/png.py) as PNG encode.  The profiler inflates
   Python-heavy stages relative to numpy-heavy ones; read the percentages
   with the stage wall times of (1) beside them.

The top functions by own time (after the same hand-up) are listed too.

``--cost-model`` prints instead the fixed CPU cost of one call of each stage
on a small shape and the CPU cost per pixel on a 2000x2000 square: with
thousands of small shapes per document, the fixed costs decide the speed.
"""

import argparse
import cProfile
import glob
import io
import os
import pstats
import statistics
import sys
import time
from collections import defaultdict

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DEFAULT_CORPUS = os.path.normpath(os.path.join(ROOT, '..', 'shared', 'corpus'))

# module file (relative to raster/) -> stage
STAGES = [
    ('svg/document.py', 'XML parse'),
    ('svg/css.py', 'CSS cascade'),
    ('svg/build.py', 'tree build'),
    ('svg/tree.py', 'tree build'),
    ('svg/properties.py', 'tree build'),
    ('svg/values.py', 'tree build'),
    ('svgpath.py', 'path parse'),
    ('path.py', 'path model'),
    ('transform.py', 'path model'),
    ('flatten.py', 'flatten'),
    ('stroke.py', 'stroke'),
    ('scan.py', 'scan conversion'),
    ('canvas.py', 'compositing'),
    ('png.py', 'PNG encode'),
    ('svg/text', 'text'),
    ('svg/filters', 'filters'),
    ('svg/paint', 'paint servers'),
    ('svg/gradient', 'paint servers'),
    ('svg/render.py', 'render (orchestration)'),
]


def stage_of(func):
    """Stage of a pstats function key (filename, line, name), or None for
    code outside raster whose time is handed up to the callers."""
    fn = func[0].replace(os.sep, '/')
    i = fn.rfind('/raster/')
    if i >= 0:
        rel = fn[i + len('/raster/'):]
        for prefix, stage in STAGES:
            if rel.startswith(prefix):
                return stage
        return 'raster other (%s)' % rel
    if '/lxml/' in fn or 'lxml.etree' in func[2]:
        return 'XML parse'
    if fn.endswith('bench/profile_corpus.py'):
        return 'driver'
    return None


def attribute(stats):
    """(stage -> seconds, function -> seconds) from a pstats.Stats object,
    handing own time of non-raster functions up to their callers."""
    raw = stats.stats
    by_stage = defaultdict(float)
    by_func = defaultdict(float)

    def give(func, seconds, depth=0):
        st = stage_of(func)
        if st is not None or depth > 40:
            by_stage[st or 'unattributed'] += seconds
            by_func[func] += seconds
            return
        callers = raw[func][4] if func in raw else {}
        weights = {c: v[2] + 1e-12 for c, v in callers.items() if c != func}
        tot = sum(weights.values())
        if not weights:
            by_stage['unattributed'] += seconds
            by_func[func] += seconds
            return
        for c, w in weights.items():
            give(c, seconds * w / tot, depth + 1)

    for func, (_, _, tt, _, _) in raw.items():
        if tt > 0:
            give(func, tt)
    return by_stage, by_func


def stage_times(path, width, repeat, cpu=False):
    """Median wall (or, with ``cpu``, process CPU) time of each public stage,
    without profiler."""

    from raster.pixels.canvas import DEFAULT_COMPRESS_LEVEL
    from raster.pixels.png import encode_png
    from raster.svg import load_svg  # noqa: F401
    from raster.parser import build_tree
    from raster.parser.document import load_document
    from raster.renderer import render_tree
    rows = defaultdict(list)
    clock = time.process_time if cpu else time.perf_counter
    for _ in range(repeat):
        t0 = clock()
        root = load_document(path)
        t1 = clock()
        tree = build_tree(root, base_dir=os.path.dirname(os.path.abspath(path)), dpi=96)
        t2 = clock()
        canvas = render_tree(tree, width=width)
        t3 = clock()
        arr = canvas.to_rgba8()
        t4 = clock()
        buf = io.BytesIO()
        buf.write(encode_png(arr, DEFAULT_COMPRESS_LEVEL))
        t5 = clock()
        for k, v in (('XML parse', t1 - t0), ('tree build + CSS', t2 - t1),
                     ('render_tree', t3 - t2), ('to_rgba8', t4 - t3), ('PNG encode', t5 - t4)):
            rows[k].append(v)
    return {k: statistics.median(v) for k, v in rows.items()}, arr.shape


def render_png(path, width):

    import raster
    from raster.pixels.canvas import DEFAULT_COMPRESS_LEVEL
    from raster.pixels.png import encode_png
    arr = raster.render(path, width)
    buf = io.BytesIO()
    buf.write(encode_png(arr, DEFAULT_COMPRESS_LEVEL))
    return buf.getvalue()


def fmt_func(func):
    fn, line, name = func
    i = fn.replace(os.sep, '/').rfind('/raster/')
    if i >= 0:
        fn = fn[i + 1:]
    elif fn != '~':
        fn = os.path.basename(fn)
    return '%s:%d(%s)' % (fn, line, name) if fn != '~' else name


def profile_file(path, width, top, repeat):
    print('=' * 78)
    print('%s at width %s' % (os.path.basename(path), width))
    try:
        render_png(path, width)            # warm-up (imports, caches)
        st, shape = stage_times(path, width, repeat)
        st_cpu, _ = stage_times(path, width, repeat, cpu=True)
    except Exception as exc:
        print('  error: %s: %s' % (type(exc).__name__, str(exc).splitlines()[0] if str(exc) else ''))
        return None
    total = sum(st.values())
    total_cpu = sum(st_cpu.values())
    print('Stage times (median of %d, no profiler), output %dx%d, total %.0f ms wall, '
          '%.0f ms CPU:' % (repeat, shape[1], shape[0], total * 1000, total_cpu * 1000))
    for k, v in st.items():
        print('  %-22s %8.1f ms  %5.1f %%   CPU %8.1f ms  %5.1f %%'
              % (k, v * 1000, 100 * v / total, st_cpu[k] * 1000, 100 * st_cpu[k] / total_cpu))
    prof = cProfile.Profile()
    prof.enable()
    render_png(path, width)
    prof.disable()
    stats = pstats.Stats(prof)
    by_stage, by_func = attribute(stats)
    ptotal = sum(by_stage.values())
    print('cProfile attribution (total %.0f ms under the profiler):' % (ptotal * 1000))
    for k, v in sorted(by_stage.items(), key=lambda kv: -kv[1]):
        print('  %-28s %8.1f ms  %5.1f %%' % (k, v * 1000, 100 * v / ptotal))
    print('Top %d functions by own time (non-raster time handed up to raster callers):' % top)
    raw = stats.stats
    for func, v in sorted(by_func.items(), key=lambda kv: -kv[1])[:top]:
        ncalls = raw[func][1] if func in raw else 0
        cum = raw[func][3] if func in raw else 0.0
        print('  %8.1f ms %5.1f %%  calls %7d  cum %8.1f ms  %s'
              % (v * 1000, 100 * v / ptotal, ncalls, cum * 1000, fmt_func(func)))
    return st, by_stage


def cost_model():
    """Print the fixed per-call CPU cost of each stage on a small shape and
    the per-pixel CPU cost on a 2000x2000 one (min of 3 batches)."""
    from raster.pixels.canvas import Canvas
    from raster.geometry.flattening import flatten
    from raster.geometry.path import Path
    from raster.pixels.scan import coverage
    from raster.geometry.stroking import stroke
    from raster.geometry.pathdata import parse_path

    def cpu(fn, n):
        best = float('inf')
        for _ in range(3):
            c = time.process_time()
            for _ in range(n):
                fn()
            best = min(best, (time.process_time() - c) / n)
        return best

    d = 'M10 10 C 20 0 30 0 40 10 S 60 30 50 40 L 20 45 Q 5 30 10 10 Z'
    p = parse_path(d)
    poly = Path.polygon([(1, 1), (30, 2), (25, 30), (3, 20)])
    pl = flatten(p, 0.25)
    e = pl.edges(close_all=True)
    m = coverage(e, 100, 100)
    c = Canvas(100, 100)
    print('Fixed CPU cost per call, small shape (6 verbs: line, quad, cubics; '
          '%d edges; mask %dx%d):' % (len(e), m.data.shape[1], m.data.shape[0]))
    rows = [('parse_path', lambda: parse_path(d), 200),
            ('flatten (curves)', lambda: flatten(p, 0.25), 100),
            ('flatten (4-gon)', lambda: flatten(poly, 0.25), 200),
            ('Polylines.edges', lambda: pl.edges(close_all=True), 200),
            ('scan.coverage', lambda: coverage(e, 100, 100), 100),
            ('Canvas.fill', lambda: c.fill(m, (1, 0, 0, 1)), 200),
            ('stroke (curves, w=2)', lambda: stroke(p, width=2, tolerance=0.25), 30),
            ('stroke (4-gon, w=2)', lambda: stroke(poly, width=2, tolerance=0.25), 30)]
    for name, fn, n in rows:
        print('  %-22s %8.3f ms' % (name, cpu(fn, n) * 1e3))
    big = Canvas(2000, 2000)
    sq = Path.polygon([(0.5, 0.5), (1999.5, 0.5), (1999.5, 1999.5), (0.5, 1999.5)])
    E = flatten(sq, 0.25).edges(close_all=True)
    M = coverage(E, 2000, 2000)
    print('CPU cost per pixel, 2000x2000 square:')
    for name, fn in (('scan.coverage', lambda: coverage(E, 2000, 2000)),
                     ('Canvas.fill', lambda: big.fill(M, (1, 0, 0, 0.5))),
                     ('Canvas.composite', lambda: big.composite(big.data)),
                     ('Canvas.to_rgba8', lambda: big.to_rgba8())):
        print('  %-22s %8.1f ns' % (name, cpu(fn, 2) * 1e9 / 4e6))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('files', nargs='*', help='corpus file names or substrings')
    ap.add_argument('--corpus', default=DEFAULT_CORPUS)
    ap.add_argument('--width', type=int, default=2000)
    ap.add_argument('--top', type=int, default=25)
    ap.add_argument('--repeat', type=int, default=3)
    ap.add_argument('--cost-model', action='store_true',
                    help='only print per-call and per-pixel costs of the stages')
    args = ap.parse_args(argv)
    if args.cost_model:
        cost_model()
        return 0
    files = sorted(glob.glob(os.path.join(args.corpus, '*.svg')))
    if args.files:
        files = [f for f in files if any(p in os.path.basename(f) for p in args.files)]
    if not files:
        ap.error('no matching .svg files in %s' % args.corpus)
    for f in files:
        profile_file(f, args.width, args.top, args.repeat)
    return 0


if __name__ == '__main__':
    sys.exit(main())
