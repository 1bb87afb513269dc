"""Corpus benchmark: raster against resvg-py and cairosvg on real SVG files.

Run from the repository root::

    python bench/bench_corpus.py [--mode process|inprocess|both] [--repeat N]
                                 [--files PATTERN] [--widths natural,2000,8000]
                                 [--renderers raster,resvg,cairosvg] [--timeout S]
                                 [--python VENV/bin/python] [--rasterize CMD]
                                 [--markdown OUT.md] [--json OUT.json] [--save DIR]

Every file of the corpus (default ``../shared/corpus/*.svg`` relative to the
repository root, ``--corpus`` to change) is rendered by every renderer, at its
natural size and at 2000 px width, to PNG bytes, so every renderer pays its
own PNG encode:

* raster: ``raster.render(path, width)`` then raster's PNG encode
  (:func:`raster.pixels.png.encode_png` at ``raster.pixels.canvas.DEFAULT_COMPRESS_LEVEL``,
  what ``Canvas.save_png`` and the ``rasterize`` command do);
  the time without the encode is reported as well ("render-only");
* resvg-py: ``resvg_py.svg_to_bytes`` with the options of
  ``shared/conformance/score.py``'s ResvgRenderer (dpi=96, font_size=12,
  languages=['en'], resources_dir = the file's directory) and the *system
  fonts* (the corpus has text), except that the default and generic font
  families name installed DejaVu fonts (see :data:`RESVG_FONTS`: with
  score.py's 'Times New Roman' and resvg's default generic families, which
  are not installed here, resvg renders no text at all);
* cairosvg: ``cairosvg.svg2png(bytestring=..., url=path, unsafe=False,
  output_width=W)`` (``output_width`` omitted at natural size).

Whole-process mode (``--mode process``, and ``both``, the default): what a
user running one renderer per file gets.  Every render is a fresh process:
``rasterize in.svg out.png [--width W] --font-dir ...`` for raster, and
``python -c`` programs (:data:`RESVG_PROGRAM`, :data:`CAIROSVG_PROGRAM`)
that import the peer, render the file with the options above and write the
PNG.  Each (file, width) runs ``--repeat`` rounds, each renderer once per
round in a rotated order, so load from elsewhere falls on all alike.
Reported: the medians of the wall-clock time seen by this driver, of the
process's user + system time (``wait4``) and of its peak RSS (``/usr/bin/time
-f %M``; ``ru_maxrss`` from ``wait4``, the same number, without it: the
largest single process's), and from one more, untimed run per renderer
the peak of the summed proportional set sizes of the process and every
process it forks (``rasterize`` draws images from 1 million pixels in
strips over forked copies of itself); raster over the faster peer,
raster's RSS and all-process memory over resvg's, and per width the
geometric mean and the files beyond the targets of issue 17 (1.5x the
faster peer's time, 2x resvg's peak RSS).  ``--python`` names the
interpreter of the peers and of the in-process workers, and ``rasterize``
beside it is raster's command: time an installed copy (``pip install .``
into a venv compiles the bytecode; an editable install under
``PYTHONDONTWRITEBYTECODE`` recompiles raster at every start).

In-process method.  Each (file, width, renderer) cell runs in a fresh worker process
(this script with ``--worker``): it imports the renderer, renders a tiny
warm-up document through the same code path (this loads lazily imported
modules and Pillow's PNG plugin), resets the kernel's peak-RSS mark
(writing '5' to /proc/self/clear_refs) and notes its current RSS, then renders
the file ``--repeat`` times.  Reported: the median wall time of the repeats,
and the peak memory = ``getrusage(RUSAGE_SELF).ru_maxrss`` after the renders
minus the RSS before them, i.e. what a render needs on top of an idle
interpreter with the same imports (without the reset the baseline falls back
to the peak so far).  Cells run file by file with the renderers interleaved,
so load from other users of the machine affects all renderers alike; CPU
times are recorded in the JSON output too.  A renderer that raises or
exceeds the timeout shows ``error`` with a one-line reason and the run goes
on.

The ratios are raster's time over the peer's (below 1: raster is faster);
the geometric mean is over the files where both renderers succeeded.
"""

import argparse
import fnmatch
import glob
import json
import math
import os
import platform
import signal
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DEFAULT_CORPUS = os.path.normpath(os.path.join(ROOT, '..', 'shared', 'corpus'))
RENDERERS = ('raster', 'resvg', 'cairosvg')
#: resvg-py font options.  score.py passes font_family='Times New Roman' and
#: leaves the generic families at resvg's defaults (Times New Roman, Arial,
#: Courier New, ...); a family that is not installed makes resvg drop the
#: text, so with only DejaVu installed the corpus text would vanish and resvg
#: would skip the cost of text.  The benchmark therefore names installed
#: DejaVu fonts for the default and the generic families (system fonts are
#: loaded too); cairosvg finds the same fonts through fontconfig.
RESVG_FONTS = dict(font_family='DejaVu Serif', serif_family='DejaVu Serif',
                   sans_serif_family='DejaVu Sans', monospace_family='DejaVu Sans Mono',
                   cursive_family='DejaVu Serif', fantasy_family='DejaVu Serif')
#: raster gets the same installed fonts (its font matching falls back from
#: the generic families to the faces found here), so every renderer pays for
#: the corpus text.
RASTER_FONT_DIRS = [d for d in ('/usr/share/fonts/truetype/dejavu',) if os.path.isdir(d)]
WARMUP_SVG = (b'<svg xmlns="http://www.w3.org/2000/svg" width="8" height="8">'
              b'<path d="M1 1h6v6z" fill="red" stroke="blue"/></svg>')


# --------------------------------------------------------------------------
# Worker side: one renderer, one file, one width
# --------------------------------------------------------------------------

def _make_renderer(name):
    """Return fn(svg_path, width_or_None) -> (png_bytes, render_times), where
    render_times is None or (wall, cpu) seconds spent before the PNG encode."""
    if name == 'raster':
        import io

        import raster
        import raster.svg  # noqa: F401
        from raster.pixels.canvas import DEFAULT_COMPRESS_LEVEL
        from raster.pixels.png import encode_png

        def fn(path, width):
            c0 = time.process_time()
            t0 = time.perf_counter()
            arr = raster.render(path, width, font_dirs=RASTER_FONT_DIRS)
            t1 = time.perf_counter()
            c1 = time.process_time()
            buf = io.BytesIO()
            buf.write(encode_png(arr, DEFAULT_COMPRESS_LEVEL))
            return buf.getvalue(), (t1 - t0, c1 - c0)
        return fn
    if name == 'resvg':
        import re

        import resvg_py
        strings = {}

        def prepare(path):
            """resvg_py reads ``svg_path`` as UTF-8 only; a file in another
            encoding (declared in its XML declaration) is decoded here, once,
            outside the timed renders, and passed as ``svg_string``."""
            with open(path, 'rb') as f:
                data = f.read()
            try:
                data.decode('utf-8')
                return None
            except UnicodeDecodeError:
                m = re.match(rb'<\?xml[^>]*encoding=["\']([A-Za-z0-9._-]+)["\']', data)
                enc = m.group(1).decode('ascii') if m else 'latin-1'
                text = data.decode(enc)
                text = re.sub(r'(<\?xml[^>]*encoding=["\'])[A-Za-z0-9._-]+', r'\g<1>utf-8', text,
                              count=1)
                strings[path] = text
                return 'resvg_py reads files as UTF-8 only: transcoded from %s, passed as svg_string' % enc

        def fn(path, width):
            kw = dict(resources_dir=os.path.dirname(os.path.abspath(path)),
                      dpi=96.0, font_size=12.0, languages=['en'], **RESVG_FONTS)
            if path in strings:
                kw['svg_string'] = strings[path]
            else:
                kw['svg_path'] = path
            if width is not None:
                kw['width'] = int(width)
            return bytes(resvg_py.svg_to_bytes(**kw)), None
        fn.prepare = prepare
        return fn
    if name == 'cairosvg':
        import cairosvg

        def fn(path, width):
            with open(path, 'rb') as f:
                data = f.read()
            kw = dict(bytestring=data, url=path, unsafe=False)
            if width is not None:
                kw['output_width'] = int(width)
            return cairosvg.svg2png(**kw), None
        return fn
    raise ValueError('unknown renderer %r' % name)


def _png_size(png):
    """(width, height) from a PNG's IHDR chunk."""
    if len(png) < 24 or png[:8] != b'\x89PNG\r\n\x1a\n':
        raise ValueError('output is not a PNG')
    return int.from_bytes(png[16:20], 'big'), int.from_bytes(png[20:24], 'big')


def _one_line(exc):
    import traceback
    tb = traceback.extract_tb(exc.__traceback__)
    where = ''
    if tb:
        fr = tb[-1]
        where = ' [%s:%d %s]' % (os.path.relpath(fr.filename, ROOT) if fr.filename.startswith(ROOT)
                                 else os.path.basename(fr.filename), fr.lineno, fr.name)
    msg = str(exc).strip().splitlines()[0] if str(exc).strip() else ''
    return ('%s: %s%s' % (type(exc).__name__, msg, where))[:300]


def _rss_baseline():
    """Current RSS in KiB after resetting the peak-RSS mark, and whether the
    reset worked.  Linux resets the high-water mark (VmHWM, which
    ``ru_maxrss`` reports) when '5' is written to /proc/self/clear_refs; then
    the later ``ru_maxrss`` minus this value is the render's own peak.  Without
    the reset the baseline is the peak so far (imports + warm-up), and a render
    smaller than that peak shows 0."""
    import resource
    try:
        with open('/proc/self/clear_refs', 'w') as f:
            f.write('5')
        with open('/proc/self/status') as f:
            for line in f:
                if line.startswith('VmRSS:'):
                    return int(line.split()[1]), True
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, False


def worker(spec):
    """Run one cell; ``spec`` is the JSON job description.  Writes a JSON result."""
    import resource
    res = {'renderer': spec['renderer'], 'file': os.path.basename(spec['svg']),
           'width': spec['width']}
    try:
        fn = _make_renderer(spec['renderer'])
        with tempfile.NamedTemporaryFile(suffix='.svg', delete=False) as f:
            f.write(WARMUP_SVG)
        try:
            fn(f.name, None)
        finally:
            os.unlink(f.name)
        import gc
        gc.collect()
        prep = getattr(fn, 'prepare', None)
        if prep is not None:
            note = prep(spec['svg'])
            if note:
                res['note'] = note
        base_kb, reset = _rss_baseline()
        walls, cpus, renders, renders_cpu = [], [], [], []
        png = None
        t_start = time.perf_counter()
        for _ in range(spec['repeat']):
            c0 = time.process_time()
            t0 = time.perf_counter()
            png, t_render = fn(spec['svg'], spec['width'])
            walls.append(time.perf_counter() - t0)
            cpus.append(time.process_time() - c0)
            if t_render is not None:
                renders.append(t_render[0])
                renders_cpu.append(t_render[1])
            if time.perf_counter() - t_start > spec['soft_limit']:
                break                     # slow file: keep the repeats we have
        peak_kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        res.update(wall=walls, cpu=cpus, render_only=renders or None,
                   render_only_cpu=renders_cpu or None,
                   peak_mb=max(0, peak_kb - base_kb) / 1024.0, hwm_reset=reset,
                   base_mb=base_kb / 1024.0, size=_png_size(png), png_bytes=len(png))
        if spec.get('save'):
            with open(spec['save'], 'wb') as f:
                f.write(png)
    except BaseException as exc:          # report, never crash the run
        res['error'] = _one_line(exc)
    with open(spec['out'], 'w') as f:
        json.dump(res, f)


# --------------------------------------------------------------------------
# Whole-process mode: one fresh process per render, as users run renderers
# --------------------------------------------------------------------------

#: The peers' programs in whole-process mode (``python -c`` with a JSON
#: spec): what a user's one-off script does -- import, render the file,
#: write the PNG.  resvg gets the same options as in the in-process mode.
RESVG_PROGRAM = """\
import json, sys
s = json.loads(sys.argv[1])
import resvg_py
kw = dict(svg_path=s['svg'], resources_dir=s['resources'], dpi=96.0, font_size=12.0,
          languages=['en'], **s['fonts'])
if s['width'] is not None:
    kw['width'] = s['width']
with open(s['out'], 'wb') as f:
    f.write(bytes(resvg_py.svg_to_bytes(**kw)))
"""
CAIROSVG_PROGRAM = """\
import json, sys
s = json.loads(sys.argv[1])
import cairosvg
kw = dict(url=s['svg'], write_to=s['out'], unsafe=False)
if s['width'] is not None:
    kw['output_width'] = s['width']
cairosvg.svg2png(**kw)
"""


def _utf8_copy(svg, tmpdir):
    """``svg`` itself when it is UTF-8, else a UTF-8 copy in ``tmpdir`` and
    a note (resvg_py's ``svg_path`` reads UTF-8 only; the copy is made
    once, outside the timing, as the in-process mode's transcoding)."""
    import re
    with open(svg, 'rb') as f:
        data = f.read()
    try:
        data.decode('utf-8')
        return svg, None
    except UnicodeDecodeError:
        pass
    m = re.match(rb'<\?xml[^>]*encoding=["\']([A-Za-z0-9._-]+)["\']', data)
    enc = m.group(1).decode('ascii') if m else 'latin-1'
    text = re.sub(r'(<\?xml[^>]*encoding=["\'])[A-Za-z0-9._-]+', r'\g<1>utf-8',
                  data.decode(enc), count=1)
    out = os.path.join(tmpdir, 'utf8_' + os.path.basename(svg))
    with open(out, 'w', encoding='utf-8') as f:
        f.write(text)
    return out, ('resvg_py reads files as UTF-8 only: transcoded from %s once, untimed' % enc)


def process_command(renderer, svg, width, out, args, utf8=None):
    """argv of one whole-process render of ``svg`` at ``width`` (None:
    natural size) to the PNG file ``out``."""
    if renderer == 'raster':
        cmd = [args.rasterize, svg, out]
        if width is not None:
            cmd += ['--width', str(int(width))]
        for d in RASTER_FONT_DIRS:
            cmd += ['--font-dir', d]
        return cmd
    spec = dict(svg=svg, out=out, width=None if width is None else int(width))
    if renderer == 'resvg':
        spec.update(svg=utf8 or svg, resources=os.path.dirname(os.path.abspath(svg)),
                    fonts=RESVG_FONTS)
        return [args.python, '-c', RESVG_PROGRAM, json.dumps(spec)]
    if renderer == 'cairosvg':
        return [args.python, '-c', CAIROSVG_PROGRAM, json.dumps(spec)]
    raise ValueError('unknown renderer %r' % renderer)


def _descendants(pid):
    """``pid`` and every process below it (from /proc; [] where it cannot
    be read)."""
    out, i = [pid], 0
    while i < len(out):
        try:
            for t in os.listdir('/proc/%d/task' % out[i]):
                with open('/proc/%d/task/%s/children' % (out[i], t)) as f:
                    out += [int(x) for x in f.read().split()]
        except OSError:
            pass
        i += 1
    return out


def _pss_kb(pid):
    """Proportional set size of process ``pid`` in kB (shared pages split
    among the processes sharing them), 0 where it cannot be read."""
    try:
        with open('/proc/%d/smaps_rollup' % pid) as f:
            for line in f:
                if line.startswith('Pss:'):
                    return int(line.split()[1])
    except (OSError, ValueError):
        pass
    return 0


def run_process(cmd, timeout, tmpdir, tree=False):
    """Run ``cmd`` once as a fresh process under ``/usr/bin/time -f %M``.

    Returns ``{'wall': s, 'cpu': s, 'rss_mb': MB}`` (wall-clock time seen by
    this process, the child's user + system time from ``wait4`` and its
    peak RSS as ``/usr/bin/time`` reports it; without ``/usr/bin/time``,
    ``ru_maxrss`` from ``wait4``, the same number), or ``{'error': ...}``.
    That peak is the largest single process's: a renderer that forks
    workers uses more.  With ``tree`` the process and all its descendants
    are sampled every few milliseconds (which costs CPU: not a timed run)
    and ``'tree_mb'``, the largest sum of their proportional set sizes,
    is added."""
    timef = os.path.join(tmpdir, 'time.txt')
    if os.path.exists(timef):
        os.unlink(timef)
    full = (['/usr/bin/time', '-f', '%M', '-o', timef] + cmd if os.path.exists('/usr/bin/time')
            else list(cmd))
    errf = os.path.join(tmpdir, 'stderr.txt')
    with open(errf, 'wb') as err:
        t0 = time.perf_counter()
        p = subprocess.Popen(full, stdout=subprocess.DEVNULL, stderr=err, stdin=subprocess.DEVNULL,
                             start_new_session=True, cwd=ROOT)
        deadline = t0 + timeout
        tree_kb = 0
        while True:
            pid, status, ru = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if tree:
                # (the time command itself excluded: it is not the renderer)
                tree_kb = max(tree_kb, sum(_pss_kb(q) for q in _descendants(p.pid)[1:]))
            if time.perf_counter() > deadline:
                try:
                    os.killpg(p.pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
                os.wait4(p.pid, 0)
                p.returncode = -9
                return {'error': 'timeout: no result after %g s' % timeout}
            time.sleep(0.002)
        wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    if p.returncode != 0:
        with open(errf, 'rb') as f:
            tail = f.read().decode('utf-8', 'replace').strip().splitlines()
        tail = [ln for ln in tail if not ln.startswith('Command exited with')]
        return {'error': ('exit status %d: %s' % (p.returncode, tail[-1] if tail else ''))[:300]}
    rss_kb = ru.ru_maxrss
    try:
        with open(timef) as f:
            rss_kb = int(f.read().split()[-1])
    except (OSError, ValueError, IndexError):
        pass
    res = {'wall': wall, 'cpu': ru.ru_utime + ru.ru_stime, 'rss_mb': rss_kb / 1024.0}
    if tree:
        res['tree_mb'] = tree_kb / 1024.0
    return res


def run_processes(svg, width, renderers, args, tmpdir):
    """Whole-process cells of one (file, width): ``--repeat`` rounds, each
    renderer once per round in a rotated order (interleaved, so load from
    elsewhere falls on all alike).  Returns ``{renderer: cell}`` with lists
    ``wall``, ``cpu``, ``rss_mb``, the output ``size`` and ``png_bytes``."""
    utf8, note = (_utf8_copy(svg, tmpdir) if 'resvg' in renderers else (None, None))
    cells = {r: {'wall': [], 'cpu': [], 'rss_mb': []} for r in renderers}
    if note and 'resvg' in cells:
        cells['resvg']['note'] = note
    for i in range(args.repeat):
        order = renderers[i % len(renderers):] + renderers[:i % len(renderers)]
        for r in order:
            c = cells[r]
            if 'error' in c:
                continue
            out = os.path.join(tmpdir, 'out_%s.png' % r)
            if os.path.exists(out):
                os.unlink(out)
            res = run_process(process_command(r, svg, width, out, args, utf8), args.timeout,
                              tmpdir)
            if 'error' not in res:
                try:
                    with open(out, 'rb') as f:
                        png = f.read()
                    c['size'] = list(_png_size(png))
                    c['png_bytes'] = len(png)
                except (OSError, ValueError) as e:
                    res = {'error': 'no PNG written: %s' % e}
            if 'error' in res:
                c.clear()
                c['error'] = res['error']
                continue
            for k in ('wall', 'cpu', 'rss_mb'):
                c[k].append(res[k])
            if args.save and i == 0:
                import shutil
                shutil.copyfile(out, os.path.join(args.save, '%s_%s_%s.png' % (
                    os.path.splitext(os.path.basename(svg))[0], width or 'natural', r)))
    # one more, untimed run each: the memory of the whole process tree
    if os.path.isdir('/proc/self/task'):
        for r in renderers:
            c = cells[r]
            if 'error' in c:
                continue
            out = os.path.join(tmpdir, 'out_%s.png' % r)
            res = run_process(process_command(r, svg, width, out, args, utf8), args.timeout,
                              tmpdir, tree=True)
            if 'error' not in res:
                c['tree_mb'] = res['tree_mb']
    return cells


def _ratio_cell(row, num, den, limit, ratios, over, label, name):
    """Append ``num / den`` to ``row`` ('-' when either is missing) and to
    ``ratios``; a ratio above ``limit`` is named in ``over`` (``label`` %
    (name, ratio))."""
    if num is None or den is None:
        row.append('-')
        return
    q = num / den
    ratios.append(q)
    if q > limit:
        over.append(label % (name, q))
    row.append('%.2f' % q)


def build_process_tables(results, files, widths, renderers, repeat, inproc=None, metric='wall'):
    """Markdown lines of the whole-process tables (one per width) and a
    summary ``{(width, key): value}``.

    ``results`` maps (file, width, renderer) to whole-process cells;
    ``inproc`` (optional) maps the same keys to in-process cells, shown
    beside them.  Per file: each renderer's median time, raster over the
    faster peer, each process's median peak RSS and raster's RSS over
    resvg's.  Below the table: the geometric mean of raster / faster peer,
    the files above 1.5x, the files whose peak RSS is above 2x resvg's (the
    targets of issue 17)."""
    lines, summary = [], {}
    peers = [r for r in renderers if r != 'raster']
    for width in widths:
        wkey = width or 'natural'
        lines += ['', '### Whole process, width %s (%s time, median of %d)' % (
            'natural size' if width is None else '%d px' % width,
            'wall-clock' if metric == 'wall' else 'CPU', repeat), '']
        head = ['file', 'size (px)'] + ['%s ms' % r for r in renderers]
        if 'raster' in renderers and peers:
            head.append('raster / faster peer')
        head.append('peak RSS MB (%s)' % ' / '.join(renderers))
        if 'raster' in renderers and 'resvg' in renderers:
            head.append('RSS raster / resvg')
        head.append('all processes MB (%s)' % ' / '.join(renderers))
        if 'raster' in renderers and 'resvg' in renderers:
            head.append('all raster / resvg')
        if inproc is not None:
            head.append('in-process ms (%s)' % ' / '.join(renderers))
        lines += ['| ' + ' | '.join(head) + ' |', '|' + '|'.join(['---'] * len(head)) + '|']
        ratios, rss_ratios, over_t, over_m, errors, notes = [], [], [], [], [], []
        tree_ratios, over_tree = [], []
        for svg in files:
            name = os.path.basename(svg)
            cells = {r: results.get((name, wkey, r), {'error': 'not run'}) for r in renderers}
            sizes = {tuple(c['size']) for c in cells.values() if 'size' in c}
            row = [name, ' vs '.join('%dx%d' % s for s in sorted(sizes)) or '-']
            t, m = {}, {}
            for r in renderers:
                c = cells[r]
                if 'error' in c or not c.get(metric):
                    row.append('error')
                    errors.append('%s / %s / %s: %s' % (name, wkey, r, c.get('error', 'no runs')))
                    continue
                t[r], m[r] = _med(c[metric]), _med(c['rss_mb'])
                mark = ''
                if c.get('note'):
                    mark = '*'
                    notes.append('%s / %s / %s: %s' % (name, wkey, r, c['note']))
                if len(c[metric]) < repeat:
                    mark += ' (%d run%s)' % (len(c[metric]), 's' if len(c[metric]) > 1 else '')
                row.append(_ms(t[r]) + mark)
            if 'raster' in renderers and peers:
                pt = [t[p] for p in peers if p in t]
                _ratio_cell(row, t.get('raster'), min(pt) if pt else None, 1.5, ratios, over_t,
                            '%s (%.2fx)', name)
            tm = {r: cells[r]['tree_mb'] for r in renderers if cells[r].get('tree_mb')}
            for mem, qs, over in ((m, rss_ratios, over_m), (tm, tree_ratios, over_tree)):
                # memory per renderer, raster / resvg (2x: the target)
                row.append(' / '.join('%.0f' % mem[r] if r in mem else '-' for r in renderers))
                if 'raster' in renderers and 'resvg' in renderers:
                    _ratio_cell(row, mem.get('raster'), mem.get('resvg'), 2.0, qs, over,
                                '%s (%.1fx)', name)
            if inproc is not None:
                vals = []
                for r in renderers:
                    c = inproc.get((name, wkey, r), {})
                    vals.append(_ms(_med(c[metric])) if c.get(metric) else '-')
                row.append(' / '.join(vals))
            lines.append('| ' + ' | '.join(row) + ' |')
        lines.append('')
        g = geomean(ratios)
        if g is not None:
            summary[(wkey, 'faster_peer')] = (g, len(ratios))
            lines.append('Geometric mean raster / faster peer at %s (whole process, %s time): '
                         '**%.2f** over %d files (target 1.0 at 2000 px); above 1.5x: %s.'
                         % (wkey, metric, g, len(ratios), ', '.join(over_t) or 'none'))
        g = geomean(rss_ratios)
        if g is not None:
            summary[(wkey, 'rss_resvg')] = (g, len(rss_ratios), max(rss_ratios))
            lines.append('Peak RSS raster / resvg at %s: geometric mean %.2f, largest %.2f '
                         '(target at most 2); above 2x: %s.'
                         % (wkey, g, max(rss_ratios), ', '.join(over_m) or 'none'))
        g = geomean(tree_ratios)
        if g is not None:
            summary[(wkey, 'tree_resvg')] = (g, len(tree_ratios), max(tree_ratios))
            lines.append('All processes (peak of the summed proportional set sizes of a '
                         'renderer and the processes it forks, one untimed run) raster / '
                         'resvg at %s: geometric mean %.2f, largest %.2f; above 2x: %s.'
                         % (wkey, g, max(tree_ratios), ', '.join(over_tree) or 'none'))
        for title, items in (('Errors', errors), ('Notes (*)', notes)):
            if items:
                lines += ['', title + ':', ''] + ['- ' + e.replace('|', '/') for e in items]
    return lines, summary


# --------------------------------------------------------------------------
# Parent side
# --------------------------------------------------------------------------

def run_cell(renderer, svg, width, args, tmpdir):
    out = os.path.join(tmpdir, 'result.json')
    if os.path.exists(out):
        os.unlink(out)
    save = None
    if args.save:
        save = os.path.join(args.save, '%s_%s_%s.png' % (
            os.path.splitext(os.path.basename(svg))[0], width or 'natural', renderer))
    spec = dict(renderer=renderer, svg=svg, width=width, repeat=args.repeat,
                soft_limit=args.timeout, out=out, save=save)
    hard = args.timeout * 2 + 30      # first render may start just before soft_limit
    p = subprocess.Popen([args.python, os.path.abspath(__file__), '--worker', json.dumps(spec)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         stdin=subprocess.DEVNULL, start_new_session=True, cwd=ROOT)
    try:
        _, err = p.communicate(timeout=hard)
    except subprocess.TimeoutExpired:
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        p.communicate()
        return {'error': 'timeout: no result after %g s' % hard}
    if not os.path.exists(out):
        tail = err.decode('utf-8', 'replace').strip().splitlines()
        why = tail[-1] if tail else 'no output'
        if p.returncode and p.returncode < 0:
            why = 'killed by signal %d; %s' % (-p.returncode, why)
        return {'error': ('worker died: ' + why)[:300]}
    with open(out) as f:
        return json.load(f)


_VERSIONS_PROGRAM = """\
from importlib import metadata
vers = []
for dist in ('numpy', 'Pillow', 'lxml', 'resvg_py', 'CairoSVG', 'cairocffi', 'raster-svg'):
    try:
        vers.append('%s %s' % (dist, metadata.version(dist)))
    except metadata.PackageNotFoundError:
        vers.append('%s -' % dist)
try:
    import cairocffi
    vers.append('libcairo %s' % cairocffi.cairo_version_string())
except Exception:
    pass
import platform, sys
print('Python %s (%s), %s; %s' % (platform.python_version(), platform.machine(),
                                  platform.platform(), sys.prefix))
print('Libraries: ' + ', '.join(vers))
"""


def machine_info(python=sys.executable):
    """Lines describing the machine and the libraries of ``python`` (the
    interpreter that runs the renderers)."""
    model = '?'
    try:
        with open('/proc/cpuinfo') as f:
            for line in f:
                if line.startswith('model name'):
                    model = line.split(':', 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        avail = len(os.sched_getaffinity(0))
    except AttributeError:
        avail = os.cpu_count()
    try:
        load = ' (load average %.2f %.2f %.2f)' % os.getloadavg()
    except OSError:
        load = ''
    mem = ''
    try:
        with open('/proc/meminfo') as f:
            kb = int(f.readline().split()[1])
        mem = ', %.0f GB RAM' % (kb / 1024 ** 2)
    except (OSError, ValueError, IndexError):
        pass
    try:
        libs = subprocess.run([python, '-c', _VERSIONS_PROGRAM], capture_output=True, text=True,
                              timeout=60).stdout.strip().splitlines()
    except (OSError, subprocess.TimeoutExpired):
        libs = []
    return ['CPU: %s, %d cores available (os.cpu_count()=%s)%s%s'
            % (model, avail, os.cpu_count(), mem, load)] + (libs or ['Python: %s (not run)' % python])


def _med(xs):
    return statistics.median(xs) if xs else None


def _ms(x):
    return '%.0f' % (x * 1000) if x >= 0.0995 else '%.1f' % (x * 1000)


def geomean(xs):
    xs = [x for x in xs if x and x > 0]
    return math.exp(sum(map(math.log, xs)) / len(xs)) if xs else None


def build_tables(results, files, widths, renderers, repeat, metric='wall'):
    """Markdown lines: one table per width plus geometric means.  ``metric``
    is 'wall' (wall-clock time) or 'cpu' (the worker's CPU time, which load
    from other processes disturbs less)."""
    ro_key = 'render_only' if metric == 'wall' else 'render_only_cpu'
    lines = []
    summary = {}
    for width in widths:
        wkey = width or 'natural'
        lines.append('')
        lines.append('### Width: %s (%s time)' % ('natural size' if width is None else '%d px' % width,
                                                  'wall-clock' if metric == 'wall' else 'CPU'))
        lines.append('')
        head = ['file', 'size (px)']
        for r in renderers:
            head.append('%s ms' % r)
            if r == 'raster':
                head.append('raster render-only ms')
        for peer in ('resvg', 'cairosvg'):
            if 'raster' in renderers and peer in renderers:
                head.append('raster/%s' % peer)
        head.append('peak MB (%s)' % ' / '.join(renderers))
        lines.append('| ' + ' | '.join(head) + ' |')
        lines.append('|' + '|'.join(['---'] * len(head)) + '|')
        ratios = {p: [] for p in ('resvg', 'cairosvg')}
        errors, notes = [], []
        for svg in files:
            name = os.path.basename(svg)
            row = [name]
            cells = {r: results.get((name, wkey, r), {'error': 'not run'}) for r in renderers}
            sizes = {tuple(c['size']) for c in cells.values() if 'size' in c}
            row.append(' vs '.join('%dx%d' % s for s in sorted(sizes)) or '-')
            t = {}
            for r in renderers:
                c = cells[r]
                if 'error' in c:
                    row.append('error')
                    errors.append('%s / %s / %s: %s' % (name, wkey, r, c['error']))
                    if r == 'raster':
                        row.append('error')
                    continue
                t[r] = _med(c[metric])
                mark = ''
                if c.get('note'):
                    mark = '*'
                    notes.append('%s / %s / %s: %s' % (name, wkey, r, c['note']))
                if len(c['wall']) < repeat:
                    mark += ' (%d run%s)' % (len(c['wall']), 's' if len(c['wall']) > 1 else '')
                row.append(_ms(t[r]) + mark)
                if r == 'raster':
                    ro = _med(c.get(ro_key) or [])
                    row.append(_ms(ro) if ro is not None else '-')
            for peer in ('resvg', 'cairosvg'):
                if 'raster' in renderers and peer in renderers:
                    if 'raster' in t and peer in t:
                        q = t['raster'] / t[peer]
                        ratios[peer].append(q)
                        row.append('%.2f' % q)
                    else:
                        row.append('-')
            row.append(' / '.join('%.0f' % cells[r]['peak_mb'] if 'peak_mb' in cells[r] else '-'
                                  for r in renderers))
            lines.append('| ' + ' | '.join(row) + ' |')
        lines.append('')
        for peer, qs in ratios.items():
            g = geomean(qs)
            if g is not None:
                summary[(wkey, peer)] = (g, len(qs))
                lines.append('Geometric mean raster/%s at %s (%s time): **%.2f** over %d files.'
                             % (peer, wkey, metric, g, len(qs)))
        # the project target: no file slower than 2x the faster peer
        if 'raster' in renderers:
            over = []
            for svg in files:
                name = os.path.basename(svg)
                c = results.get((name, wkey, 'raster'), {})
                peers = [_med(results[(name, wkey, p)][metric]) for p in ('resvg', 'cairosvg')
                         if metric in results.get((name, wkey, p), {})]
                if metric in c and peers and _med(c[metric]) > 2 * min(peers):
                    over.append('%s (%.1fx)' % (name, _med(c[metric]) / min(peers)))
            if over:
                lines.append('Files where raster is more than 2x slower than the faster peer: '
                             + ', '.join(over) + '.')
        for title, items in (('Errors', errors), ('Notes (*)', notes)):
            if items:
                lines.append('')
                lines.append(title + ':')
                lines.append('')
                for e in items:
                    lines.append('- ' + e.replace('|', '/'))
    return lines, summary


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--corpus', default=DEFAULT_CORPUS, help='folder of .svg files')
    ap.add_argument('--files', default=None, metavar='PATTERN',
                    help='comma-separated fnmatch patterns or substrings of file names')
    ap.add_argument('--widths', default='natural,2000',
                    help="comma-separated output widths; 'natural' = the document's size")
    ap.add_argument('--inprocess-widths', default=None, metavar='WIDTHS',
                    help='widths of the in-process mode when it should run fewer than --widths '
                    '(e.g. natural,2000 beside a whole-process run that includes 8000)')
    ap.add_argument('--renderers', default=','.join(RENDERERS))
    ap.add_argument('--repeat', type=int, default=3, help='timed renders per cell (median)')
    ap.add_argument('--timeout', type=float, default=60.0,
                    help='seconds: stop repeating after this; kill the worker after 2x+30')
    ap.add_argument('--markdown', metavar='OUT.md', help='write the tables as markdown')
    ap.add_argument('--json', metavar='OUT.json', help='write all raw measurements')
    ap.add_argument('--save', metavar='DIR', help='keep each PNG as DIR/<file>_<width>_<renderer>.png')
    ap.add_argument('--metric', choices=('wall', 'cpu', 'both'), default='both',
                    help='time shown in the tables: wall-clock, worker CPU time, or both')
    ap.add_argument('--mode', choices=('process', 'inprocess', 'both'), default='both',
                    help='whole process (each render a fresh process: the command for raster), '
                    'in-process (warm renders in a worker after a warm-up), or both')
    ap.add_argument('--python', default=sys.executable,
                    help='interpreter running the peers and the in-process workers (default: '
                    'this one); time an installed copy (pip install . into a venv) so that '
                    'start-up does not include compiling bytecode')
    ap.add_argument('--rasterize', default=None,
                    help="raster's command in whole-process mode (default: rasterize beside "
                    '--python)')
    ap.add_argument('--retable', metavar='IN.json',
                    help='no rendering: rebuild the tables from a --json file of an earlier run')
    ap.add_argument('--worker', help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        worker(json.loads(args.worker))
        return 0
    if args.repeat < 1:
        ap.error('--repeat must be >= 1')
    renderers = [r.strip() for r in args.renderers.split(',') if r.strip()]
    bad = [r for r in renderers if r not in RENDERERS]
    if bad:
        ap.error('unknown renderer(s): %s' % ', '.join(bad))
    def parse_widths(text):
        out = []
        for w in text.split(','):
            w = w.strip()
            if w == 'natural':
                out.append(None)
            elif w.isdigit() and int(w) > 0:
                out.append(int(w))
            else:
                ap.error('bad width %r' % w)
        return out
    widths = parse_widths(args.widths)
    inproc_widths = widths if args.inprocess_widths is None else parse_widths(args.inprocess_widths)
    bad = [w for w in inproc_widths if w not in widths]
    if bad:
        ap.error('--inprocess-widths must be among --widths')
    if args.rasterize is None:
        args.rasterize = os.path.join(os.path.dirname(args.python), 'rasterize')
    modes = ('process', 'inprocess') if args.mode == 'both' else (args.mode,)
    if args.retable:
        with open(args.retable) as f:
            old = json.load(f)
        inproc = {(r['file'], r['width'], r['renderer']): r for r in old.get('results', [])}
        proc = {(r['file'], r['width'], r['renderer']): r for r in old.get('process', [])}
        keys = set(inproc) | set(proc)
        files = sorted({k[0] for k in keys})
        present = {k[1] for k in keys}
        widths = [w for w in widths if (w or 'natural') in present]
        renderers = [r for r in renderers if r in {k[2] for k in keys}]
        _report(args, argv, old['machine'], proc, inproc, files, widths, renderers,
                old.get('repeat', args.repeat))
        return 0
    files = sorted(glob.glob(os.path.join(args.corpus, '*.svg')))
    if args.files:
        pats = [p.strip() for p in args.files.split(',') if p.strip()]
        files = [f for f in files if any(
            fnmatch.fnmatch(os.path.basename(f), p) or p in os.path.basename(f) for p in pats)]
    if not files:
        ap.error('no .svg files in %s match' % args.corpus)
    if args.save:
        os.makedirs(args.save, exist_ok=True)
    if 'process' in modes and 'raster' in renderers and not os.path.exists(args.rasterize):
        ap.error('no rasterize command at %s (give --rasterize)' % args.rasterize)

    info = machine_info(args.python)
    for line in info:
        print(line)
    print('Corpus: %s (%d files); widths: %s; renderers: %s; repeat %d; mode %s'
          % (args.corpus, len(files), args.widths, ', '.join(renderers), args.repeat, args.mode))
    inproc, proc = {}, {}
    t_all = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix='bench_corpus_') as tmpdir:
        for svg in files:
            name = os.path.basename(svg)
            for width in widths:
                wkey = width or 'natural'
                if 'process' in modes:
                    cells = run_processes(svg, width, renderers, args, tmpdir)
                    for r in renderers:
                        res = proc[(name, wkey, r)] = cells[r]
                        if 'error' in res:
                            msg = 'error: ' + res['error']
                        else:
                            msg = '%8s ms  cpu %8s ms  peak RSS %5.0f MB  %dx%d  (%d runs)' % (
                                _ms(_med(res['wall'])), _ms(_med(res['cpu'])),
                                _med(res['rss_mb']), res['size'][0], res['size'][1],
                                len(res['wall']))
                        print('%-40s %-8s %-9s process    %s' % (name, wkey, r, msg), flush=True)
                if 'inprocess' not in modes or width not in inproc_widths:
                    continue
                for r in renderers:
                    res = run_cell(r, svg, width, args, tmpdir)
                    inproc[(name, wkey, r)] = res
                    if 'error' in res:
                        msg = 'error: ' + res['error']
                    else:
                        msg = '%8s ms  peak %5.0f MB  %dx%d  (%d runs)' % (
                            _ms(_med(res['wall'])), res['peak_mb'], res['size'][0],
                            res['size'][1], len(res['wall']))
                        if res.get('note'):
                            msg += '  [%s]' % res['note']
                        if res.get('render_only'):
                            msg += '  render-only %s ms' % _ms(_med(res['render_only']))
                    print('%-40s %-8s %-9s in-process %s' % (name, wkey, r, msg), flush=True)
    print('Total benchmark time %.0f s' % (time.perf_counter() - t_all))
    if args.json:
        with open(args.json, 'w') as f:
            json.dump({'machine': info, 'repeat': args.repeat, 'mode': args.mode,
                       'results': [dict(v, file=k[0], width=k[1], renderer=k[2])
                                   for k, v in inproc.items()],
                       'process': [dict(v, file=k[0], width=k[1], renderer=k[2])
                                   for k, v in proc.items()]}, f, indent=1)
    _report(args, argv, info, proc, inproc, files, widths, renderers, args.repeat)
    return 0


def _report(args, argv, info, proc, inproc, files, widths, renderers, repeat):
    metrics = ('wall', 'cpu') if args.metric == 'both' else (args.metric,)
    lines = []
    if proc:
        for metric in metrics:
            lines += build_process_tables(proc, files, widths, renderers, repeat,
                                          inproc or None, metric)[0]
    if inproc:
        if proc:
            lines += ['', '## In process (warm renders after a warm-up, one worker per cell)']
        present = {k[1] for k in inproc}
        inproc_widths = [w for w in widths if (w or 'natural') in present]
        for metric in metrics:
            lines += build_tables(inproc, files, inproc_widths, renderers, repeat, metric)[0]
    print('\n'.join(lines))
    if args.markdown:
        with open(args.markdown, 'w') as f:
            f.write('## Corpus benchmark\n\n')
            f.write('Command: `python bench/bench_corpus.py %s`\n\n'
                    % ' '.join(argv if argv is not None else sys.argv[1:]))
            f.write('Machine (tables written %s UTC):\n\n'
                    % time.strftime('%Y-%m-%d %H:%M', time.gmtime()))
            for line in info:
                f.write('- %s\n' % line)
            if proc:
                f.write('\nWhole process: every render is a fresh process (`rasterize in.svg '
                        'out.png [--width W]`; the peers through `python -c` importing them, '
                        'rendering and writing the PNG), the renderers interleaved, %d rounds; '
                        'medians of wall-clock and CPU time, peak RSS of each process '
                        '(`/usr/bin/time -f %%M`: the largest single process); from one more, '
                        'untimed run each, the peak of the summed proportional set sizes of a '
                        'renderer and the processes it forks (all processes).\n' % repeat)
            if inproc:
                f.write('\nIn process: medians of %d renders to PNG bytes (PNG encode '
                        'included), wall-clock and CPU time of the worker process; peak MB = '
                        'peak RSS of the worker during the renders minus its RSS before them '
                        '(after the imports and a warm-up render).\n' % repeat)
            f.write('\n'.join(lines) + '\n')


if __name__ == '__main__':
    sys.exit(main())
