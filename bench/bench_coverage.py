"""Coverage benchmark: edge accuracy and crossing-heavy geometry (issue 11).

    python bench/bench_coverage.py [--part accuracy,crossing] [--mode process|inprocess|both]
                                   [--repeat 3] [--cases jitter,cubics,scribble,hatching,crosshatch]
                                   [--rasterize PATH] [--python PATH]
                                   [--json OUT.json] [--markdown OUT.md]

Two parts, raster side by side with resvg-py and CairoSVG in one run:

*accuracy* -- shapes whose exact coverage is known (a large circle, small
circles of radius 0.5 to 3 px at sub-pixel positions, a thin rotated bar,
a pentagram for both fill rules, a stroked circle, a pixel-aligned
rectangle).  Each renderer draws the SVG at its default settings, opaque
black on transparent; the error of a pixel is ``|alpha - 255 * ref|`` with
``ref`` computed here by :func:`raster.testing.span_coverage` (256 sample
lines per pixel row, the covered length of each line exact).  The table
gives the largest error per case and renderer (in /255), the count of
pixels off by more than 3/255, and raster's edge count at its default
(straddled polylines at ``DEFAULT_TOLERANCE``) against the flattening it
used before (vertices on the curve at 0.25 px).

*crossing* -- inputs where many edges cross inside pixels: a 100,000-vertex
even-odd polygon with +-5 px radial jitter at 2000x2000, one path of 2,000
random cubics across a 2000x2000 canvas stroked 1.5 px wide, and a dense
hand-drawn-like scribble (one path of 20,000 smooth quadratic pieces of a
random walk, stroked 2 px, on 1000x1000), dense hatching (3,000 thin
parallel stripes 0.1 px apart on 400x400: about 20 edges through every
pixel, none crossing) and a cross-hatch (1,000 stripes 0.3 px apart, half
leaning each way: each crosses hundreds of the others).  Modes:

* ``process`` (how users run it): every render is a fresh process --
  raster's ``rasterize in.svg out.png`` command, the peers through
  ``python -c`` writing a PNG -- interleaved in rounds, each timed by
  ``/usr/bin/time -f '%e %U %S %M'``; the median wall time, CPU time and
  peak RSS of ``--repeat`` rounds.  Time an installed copy (``pip install
  .`` into a separate venv compiles the bytecode) with ``--rasterize``.
* ``inprocess``: one fresh worker process per renderer and case imports
  the renderer, renders once to warm up, then times ``--repeat`` renders
  (parse and render to PNG bytes; median wall time) and reports its peak
  RSS (VmHWM).

Inputs are generated with seeded RNGs into a temporary folder.  The machine
(CPU, cores, load average, versions) is printed with the tables.
"""

import argparse
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

RENDERERS = ('raster', 'resvg', 'cairosvg')
SVG_NS = 'http://www.w3.org/2000/svg'


# -- accuracy cases -------------------------------------------------------------

def _svg(w, h, body):
    return ('<svg xmlns="%s" width="%d" height="%d" viewBox="0 0 %d %d">%s</svg>'
            % (SVG_NS, w, h, w, h, body))


def pentagram(cx, cy, r, rot=0.0):
    a = rot + np.pi / 2 + np.arange(5) * 4 * np.pi / 5
    return np.c_[cx + r * np.cos(a), cy - r * np.sin(a)]


def accuracy_cases():
    """name -> (svg, width, height, spans) with spans for span_coverage."""
    from raster.testing import disc_spans, polygon_spans
    rng = np.random.default_rng(11)
    cases = {}
    cases['circle r=300'] = (_svg(620, 620, '<circle cx="310.2" cy="309.6" r="300"/>'),
                             620, 620, disc_spans([(310.2, 309.6, 300.0)]))
    cases['circle r=30'] = (_svg(72, 72, '<circle cx="36.3" cy="35.7" r="30"/>'),
                            72, 72, disc_spans([(36.3, 35.7, 30.0)]))
    small = [(4 + 8 * j + rng.uniform(0, 1), 4 + 8 * i + rng.uniform(0, 1), r)
             for i, r in enumerate([0.5, 0.75, 1.0, 1.5, 2.0, 3.0]) for j in range(4)]
    body = ''.join('<circle cx="%.4f" cy="%.4f" r="%g"/>' % c for c in small)
    cases['small circles r=0.5..3'] = (_svg(36, 52, body), 36, 52, disc_spans(small))
    # a bar 0.7 px wide, 60 px long, rotated by 17 degrees about its centre
    th = np.radians(17.0)
    u, v = np.array([np.cos(th), np.sin(th)]), np.array([-np.sin(th), np.cos(th)])
    c = np.array([40.3, 30.6])
    bar = np.array([c - 30 * u - 0.35 * v, c + 30 * u - 0.35 * v,
                    c + 30 * u + 0.35 * v, c - 30 * u + 0.35 * v])
    d = 'M' + ' L'.join('%.6f %.6f' % tuple(p) for p in bar) + 'Z'
    cases['thin bar 0.7 px, 17 deg'] = (_svg(80, 62, '<path d="%s"/>' % d), 80, 62,
                                       polygon_spans([bar], 'nonzero'))
    star = pentagram(40.4, 41.3, 36.0, 0.1)
    d = 'M' + ' L'.join('%.6f %.6f' % tuple(p) for p in star) + 'Z'
    for rule in ('nonzero', 'evenodd'):
        cases['star %s' % rule] = (_svg(82, 82, '<path fill-rule="%s" d="%s"/>' % (rule, d)),
                                   82, 82, polygon_spans([star], rule))
    # a stroked circle: the ring between radii 18.5 and 21.5
    cases['stroked circle r=20 w=3'] = (
        _svg(82, 82, '<circle cx="40.2" cy="40.7" r="20" fill="none" stroke="#000" '
                     'stroke-width="3"/>'), 82, 82, _ring_spans(40.2, 40.7, 18.5, 21.5))
    cases['aligned rect'] = (_svg(40, 40, '<rect x="10" y="10" width="20" height="20"/>'),
                             40, 40, polygon_spans([[(10, 10), (30, 10), (30, 30), (10, 30)]]))
    return cases


def _ring_spans(cx, cy, r0, r1):
    """spans of the ring r0 <= |p - c| <= r1: one or two intervals a line."""
    def fn(ys):
        dy = ys - cy
        m1 = np.abs(dy) < r1
        li = np.flatnonzero(m1)
        ho = np.sqrt(r1 * r1 - dy[li] ** 2)
        inner = np.abs(dy[li]) < r0
        hi_ = np.sqrt(np.maximum(r0 * r0 - dy[li] ** 2, 0.0))
        a = np.where(inner, cx + hi_, cx - ho)          # right piece (or the whole chord)
        b = cx + ho
        la, aa, bb = [li], [a], [b]
        k = inner
        la.append(li[k]); aa.append(cx - ho[k]); bb.append(cx - hi_[k])
        return np.concatenate(la), np.concatenate(aa), np.concatenate(bb)
    return fn


def _alpha_png(png):
    import io
    from PIL import Image
    im = Image.open(io.BytesIO(png)).convert('RGBA')
    return np.asarray(im)[..., 3].astype(np.float64)


def render_alpha(renderer, svg):
    """(H, W) float64 alpha 0..255 of ``svg`` by ``renderer`` at its
    defaults."""
    data = svg.encode()
    if renderer == 'raster':
        import raster
        return raster.render(data)[..., 3].astype(np.float64)
    if renderer == 'resvg':
        import resvg_py
        return _alpha_png(bytes(resvg_py.svg_to_bytes(svg_string=svg)))
    import cairosvg
    return _alpha_png(cairosvg.svg2png(bytestring=data))


def edge_counts(svg):
    """Edges raster's renderer scan converts for the fills and strokes of
    ``svg``: (now, before) -- straddled at DEFAULT_TOLERANCE, and vertices
    on the curve at 0.25 px."""
    from raster.geometry.flattening import flatten
    from raster.geometry.stroking import stroke
    from raster.renderer import DEFAULT_TOLERANCE
    from raster.svg import load_svg
    from raster.tree import PathNode, walk
    tree = load_svg(svg.encode())
    out = []
    for tol, st in ((DEFAULT_TOLERANCE, True), (0.25, False)):
        n = 0
        for node, t in walk(tree.root):
            if not isinstance(node, PathNode) or node.path is None:
                continue
            if node.fill is not None:
                n += len(flatten(node.path, tol, transform=t, straddle=st).edges(close_all=True))
            if node.stroke is not None:
                o = stroke(node.path, node.stroke.style, transform=t, tolerance=tol,
                           straddle=st)
                n += len(flatten(o, tol).edges(close_all=True))
        out.append(n)
    return tuple(out)


def run_accuracy(renderers):
    from raster.testing import span_coverage
    rows = []
    for name, (svg, w, h, spans) in accuracy_cases().items():
        ref = 255.0 * span_coverage(spans, w, h, lines=256)
        row = {'case': name, 'size': '%dx%d' % (w, h)}
        for r in renderers:
            try:
                a = render_alpha(r, svg)
            except Exception as e:              # a peer failing shows as such
                row[r] = {'error': str(e).splitlines()[0][:80]}
                continue
            err = np.abs(a - ref)
            row[r] = {'max': float(err.max()), 'over3': int((err > 3).sum())}
            if name == 'aligned rect':
                row[r]['binary'] = bool(np.all((a == 0) | (a == 255)))
        row['edges'] = edge_counts(svg)
        rows.append(row)
        print('  %-26s ' % name + '  '.join(
            '%s %s' % (r, ('%.1f' % row[r]['max']) if 'max' in row[r] else 'error')
            for r in renderers), flush=True)
    return rows


# -- crossing-heavy cases ---------------------------------------------------------

def jitter_polygon(n=100_000, jitter=5.0, seed=0, size=2000):
    rng = np.random.default_rng(seed)
    th = np.sort(rng.uniform(0, 2 * np.pi, n))
    k = np.arange(1, 41)[:, None]
    amp = rng.normal(size=(40, 1)) * 60.0 / k
    ph = rng.uniform(0, 2 * np.pi, (40, 1))
    r = 0.45 * size + (amp * np.cos(k * th[None, :] + ph)).sum(0) + rng.uniform(-jitter, jitter, n)
    p = np.c_[size / 2 + r * np.cos(th), size / 2 + r * np.sin(th)]
    d = 'M' + ' '.join('%.3f %.3f' % tuple(q) for q in p) + 'Z'
    return _svg(size, size, '<path fill-rule="evenodd" fill="#203060" d="%s"/>' % d)


def random_cubics(n=2000, seed=0, width=1.5, size=2000):
    rng = np.random.default_rng(seed)
    p = rng.uniform(0, size, (3 * n + 1, 2))
    d = 'M%.3f %.3f' % tuple(p[0]) + ''.join(
        'C%.3f %.3f %.3f %.3f %.3f %.3f' % tuple(p[1 + 3 * i:4 + 3 * i].ravel()) for i in range(n))
    return _svg(size, size, '<path fill="none" stroke="#000" stroke-width="%g" d="%s"/>'
                % (width, d))


def scribble(n=20_000, seed=0, width=2.0, size=1000):
    """A hand-drawn-like scribble: a smooth random walk (heading that drifts,
    steps of 3-9 px, kept inside the canvas) drawn as quadratic pieces
    through the midpoints of its steps."""
    rng = np.random.default_rng(seed)
    turn = np.cumsum(rng.normal(0, 0.35, n + 1))
    step = rng.uniform(3, 9, n + 1)
    z = np.cumsum(step * np.exp(1j * turn))
    # fold into the canvas (reflect at the borders)
    m = 0.05 * size
    span = size - 2 * m

    def fold(v):
        v = np.mod(v, 2 * span)
        return m + np.where(v > span, 2 * span - v, v)
    x, y = fold(z.real + size / 2), fold(z.imag + size / 2)
    mx, my = (x[1:] + x[:-1]) / 2, (y[1:] + y[:-1]) / 2
    d = 'M%.2f %.2f' % (mx[0], my[0]) + ''.join(
        'Q%.2f %.2f %.2f %.2f' % (x[i], y[i], mx[i], my[i]) for i in range(1, n))
    return _svg(size, size, '<path fill="none" stroke="#553322" stroke-width="%g" '
                            'stroke-linecap="round" stroke-linejoin="round" d="%s"/>'
                % (width, d))


def hatching(n=3000, pitch=0.1, width=0.04, lean=40.0, cross=False, size=400):
    """Dense hatching: ``n`` thin parallelograms (stripes) ``width`` px
    wide, ``pitch`` px apart, leaning ``lean`` px over the canvas's height:
    about 2 / pitch edges through every pixel, none crossing another (as
    in an engraving or a plotter's fill drawn small).  ``cross``: half of
    them lean the other way, so each crosses hundreds of the others."""
    rng = np.random.default_rng(1)
    x = 0.1 * size + pitch * np.arange(n) + rng.uniform(-0.2, 0.2, n) * pitch
    t = np.full(n, lean)
    if cross:
        t[1::2] = -lean
        x[1::2] += lean
    top, bottom = 0.05 * size, 0.95 * size
    d = ''.join('M%.4f %.4fh%.4fl%.4f %.4fh%.4fZ' % (a, top, width, b, bottom - top, -width)
                for a, b in zip(x.tolist(), t.tolist()))
    return _svg(size, size, '<path fill="#102030" d="%s"/>' % d)


CROSSING = {
    'jitter': ('100,000-vertex even-odd polygon, +-5 px jitter, 2000x2000', jitter_polygon),
    'cubics': ('2,000 random cubics stroked 1.5 px, 2000x2000', random_cubics),
    'scribble': ('scribble of 20,000 quadratics stroked 2 px, 1000x1000', scribble),
    'hatching': ('3,000 parallel stripes 0.1 px apart, 400x400', hatching),
    'crosshatch': ('1,000 stripes 0.3 px apart, half leaning each way, 400x400',
                   lambda: hatching(1000, 0.3, 0.1, 40.0, True)),
}

#: The peers' whole-process programs: ``python -c CODE in.svg out.png``.
PEER_CODE = {
    'resvg': ('import resvg_py, sys\n'
              'open(sys.argv[2], "wb").write(bytes(resvg_py.svg_to_bytes(svg_path=sys.argv[1])))'),
    'cairosvg': ('import cairosvg, sys\n'
                 'cairosvg.svg2png(url=sys.argv[1], write_to=sys.argv[2], unsafe=False)'),
}

_WORKER = r'''
import json, resource, statistics, sys, time
renderer, path, repeat = sys.argv[1], sys.argv[2], int(sys.argv[3])
data = open(path, 'rb').read()
if renderer == 'raster':
    import raster
    from raster.svg import load_svg, render_tree
    from raster.pixels.encode import encode_canvas
    def fn():
        c = render_tree(load_svg(data), dtype='uint8')
        return encode_canvas(c, 'png')
elif renderer == 'resvg':
    import resvg_py
    def fn():
        return bytes(resvg_py.svg_to_bytes(svg_path=path))
else:
    import cairosvg
    def fn():
        return cairosvg.svg2png(bytestring=data, unsafe=False)
fn()
ts = []
for _ in range(repeat):
    t0 = time.perf_counter()
    fn()
    ts.append(time.perf_counter() - t0)
# VmHWM: this process's own peak (ru_maxrss would carry the parent's peak
# over the exec on Linux)
hwm = [l for l in open('/proc/self/status') if l.startswith('VmHWM')]
rss = (int(hwm[0].split()[1]) if hwm
       else resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)
print(json.dumps({'wall': statistics.median(ts), 'rss_mb': rss / 1024}))
'''


def timed(cmd):
    """Run ``cmd`` under /usr/bin/time: (wall s, cpu s, peak RSS MB, ok);
    ok is False when the command failed or its times cannot be read."""
    p = subprocess.run(['/usr/bin/time', '-f', '%e %U %S %M'] + cmd,
                       capture_output=True, text=True)
    lines = p.stderr.strip().splitlines()
    try:
        last = lines[-1].split()
        wall, usr, sys_, rss = float(last[0]), float(last[1]), float(last[2]), int(last[3])
    except (IndexError, ValueError):
        return 0.0, 0.0, 0.0, False
    return wall, usr + sys_, rss / 1024.0, p.returncode == 0


def process_cells(runs, renderers):
    """One table row of whole-process runs: ``runs`` maps each renderer to
    its :func:`timed` results.  Returns ``(cells, vals, fast)``: the cells
    ('wall / CPU / RSS' medians, or 'error' for a renderer that failed in
    any round), the medians by renderer, and the faster peer (None when
    raster or every peer failed)."""
    vals = {r: [_med([x[i] for x in runs[r]]) for i in range(3)]
            for r in renderers if all(x[3] for x in runs[r])}
    cells = ['%.2f / %.2f / %.0f' % tuple(vals[r]) if r in vals else 'error' for r in renderers]
    peers = [r for r in renderers if r != 'raster' and r in vals]
    fast = min(peers, key=lambda r: vals[r][0]) if 'raster' in vals and peers else None
    return cells, vals, fast


def run_crossing(names, renderers, modes, repeat, rasterize, python, tmp):
    files = {}
    for name in names:
        path = os.path.join(tmp, name + '.svg')
        with open(path, 'w') as f:
            f.write(CROSSING[name][1]())
        files[name] = path
    res = {}
    if 'process' in modes:
        for name in names:
            for rnd in range(repeat):
                for r in renderers:
                    out = os.path.join(tmp, '%s_%s.png' % (name, r))
                    if r == 'raster':
                        cmd = [rasterize, files[name], out]
                    else:
                        cmd = [python, '-c', PEER_CODE[r], files[name], out]
                    res.setdefault((name, r, 'process'), []).append(timed(cmd))
            print('  process %-9s ' % name + '  '.join(
                '%s %.2f s %.0f MB' % (r, _med([x[0] for x in res[(name, r, 'process')]]),
                                       _med([x[2] for x in res[(name, r, 'process')]]))
                if all(x[3] for x in res[(name, r, 'process')]) else '%s error' % r
                for r in renderers), flush=True)
    if 'inprocess' in modes:
        for name in names:
            for r in renderers:
                py = sys.executable if r == 'raster' else python
                p = subprocess.run([py, '-c', _WORKER, r, files[name], str(repeat)],
                                   capture_output=True, text=True)
                try:
                    d = json.loads(p.stdout.strip().splitlines()[-1])
                except (IndexError, ValueError):
                    d = {'error': (p.stderr.strip().splitlines() or ['?'])[-1][:80]}
                res[(name, r, 'inprocess')] = d
            print('  inprocess %-9s ' % name + '  '.join(
                '%s %s' % (r, '%.2f s %.0f MB' % (res[(name, r, 'inprocess')]['wall'],
                                                  res[(name, r, 'inprocess')]['rss_mb'])
                           if 'wall' in res[(name, r, 'inprocess')] else 'error')
                for r in renderers), flush=True)
    return res


def _med(xs):
    return statistics.median(xs) if xs else float('nan')


# -- report -----------------------------------------------------------------------

def machine_info():
    info = {'python': platform.python_version(), 'platform': platform.platform(),
            'cores': os.cpu_count()}
    try:
        with open('/proc/cpuinfo') as f:
            for line in f:
                if line.startswith('model name'):
                    info['cpu'] = line.split(':', 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        info['load'] = os.getloadavg()
    except OSError:
        pass
    from importlib import metadata
    for dist in ('numpy', 'raster-svg', 'resvg_py', 'CairoSVG'):
        try:
            info[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            info[dist] = None
    return info


def markdown(acc, cross, names, renderers, modes, repeat, info):
    out = ['Machine: %s' % ', '.join('%s %s' % kv for kv in info.items()), '']
    if acc:
        out += ['Maximum alpha error against the reference (/255; pixels over 3/255 in '
                'brackets); raster edges now / before (0.25 px on the curve):', '',
                '| case | size | ' + ' | '.join(renderers) + ' | raster edges |',
                '|---|---|' + '---|' * len(renderers) + '---|']
        for row in acc:
            cells = []
            for r in renderers:
                c = row[r]
                if 'error' in c:
                    cells.append('error')
                else:
                    s = '%.1f (%d)' % (c['max'], c['over3'])
                    if 'binary' in c:
                        s += ' binary' if c['binary'] else ' not binary'
                    cells.append(s)
            out.append('| %s | %s | %s | %d / %d |' % (row['case'], row['size'],
                                                      ' | '.join(cells), *row['edges']))
        out.append('')
    for mode in modes:
        if not cross:
            break
        if mode == 'process':
            out += ['Whole process (fresh process each, interleaved, median of %d): '
                    'wall s / CPU s / peak RSS MB' % repeat, '',
                    '| case | ' + ' | '.join(renderers) + ' | raster / faster peer (wall, RSS) |',
                    '|---|' + '---|' * len(renderers) + '---|']
            for name in names:
                cells, vals, fast = process_cells(
                    {r: cross[(name, r, 'process')] for r in renderers}, renderers)
                ratio = ''
                if fast is not None:
                    ratio = '%.2fx %s, %.2fx' % (vals['raster'][0] / vals[fast][0], fast,
                                                 vals['raster'][2] / vals[fast][2])
                out.append('| %s | %s | %s |' % (name, ' | '.join(cells), ratio))
            out.append('')
        else:
            out += ['In process (warm, median of %d renders to PNG bytes): wall s / '
                    'worker peak RSS MB' % repeat, '',
                    '| case | ' + ' | '.join(renderers) + ' |', '|---|' + '---|' * len(renderers)]
            for name in names:
                cells = []
                for r in renderers:
                    d = cross[(name, r, 'inprocess')]
                    cells.append('%.2f / %.0f' % (d['wall'], d['rss_mb']) if 'wall' in d
                                 else 'error')
                out.append('| %s | %s |' % (name, ' | '.join(cells)))
            out.append('')
    if cross:
        out += ['Cases: ' + '; '.join('%s: %s' % (n, CROSSING[n][0]) for n in names), '']
    return '\n'.join(out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--part', default='accuracy,crossing')
    ap.add_argument('--mode', default='both', choices=('process', 'inprocess', 'both'))
    ap.add_argument('--repeat', type=int, default=3)
    ap.add_argument('--cases', default=','.join(CROSSING))
    ap.add_argument('--renderers', default=','.join(RENDERERS))
    ap.add_argument('--rasterize', default=None,
                    help='the rasterize command to time (default: beside this Python)')
    ap.add_argument('--python', default=sys.executable,
                    help='Python that runs the peers (default: this one)')
    ap.add_argument('--json')
    ap.add_argument('--markdown')
    args = ap.parse_args(argv)
    parts = args.part.split(',')
    renderers = args.renderers.split(',')
    names = [n for n in args.cases.split(',') if n]
    modes = ('process', 'inprocess') if args.mode == 'both' else (args.mode,)
    rasterize = args.rasterize or shutil.which('rasterize', path=os.path.dirname(sys.executable))
    info = machine_info()
    print('machine:', json.dumps(info), flush=True)
    acc = run_accuracy(renderers) if 'accuracy' in parts else []
    cross = {}
    if 'crossing' in parts:
        with tempfile.TemporaryDirectory(prefix='bench_coverage_') as tmp:
            cross = run_crossing(names, renderers, modes, args.repeat, rasterize, args.python,
                                 tmp)
    md = markdown(acc, cross, names, renderers, modes if cross else (), args.repeat, info)
    print(md)
    if args.markdown:
        with open(args.markdown, 'w') as f:
            f.write(md + '\n')
    if args.json:
        with open(args.json, 'w') as f:
            json.dump({'machine': info, 'accuracy': acc,
                       'crossing': {'|'.join(k): v for k, v in cross.items()}}, f, indent=1)
    return 0


if __name__ == '__main__':
    sys.exit(main())
