"""Repeated shapes benchmark: pages of text and scatter plots, whole process.

    python bench/bench_repeated.py [--repeat 3] [--cases text12,text5,scatter]
                                   [--rasterize PATH] [--python PATH] [--markdown OUT.md]

Documents that draw one shape many times at one size: a page of text
draws each glyph of its font hundreds of times, a scatter plot one marker
at every data point.  raster flattens such contours once and moves the
polyline to each copy (``raster.geometry.flattening``, *Repeated
contours*) and strokes such paths once (``stroke_many``).  Cases,
generated with seeded RNGs into a temporary folder:

* ``text12`` -- 60 lines of 12 px DejaVu Sans on 1000x860 (about 7,900
  glyphs);
* ``text5`` -- 70 lines of 5 px DejaVu Sans on 600x430 (about 17,500
  glyphs: small labels, where the glyphs' curves are most of the work);
* ``scatter`` -- 5,000 ``<circle>`` of radius 3 at random centres on
  1000x1000, filled half transparent and stroked 1 px.

Every render is a fresh process (raster's ``rasterize in.svg out.png``,
the peers through ``python -c`` at their defaults writing a PNG),
interleaved in rounds and timed by ``/usr/bin/time``; the table gives the
median wall time, CPU time and peak RSS of ``--repeat`` rounds and raster's
ratio to the faster peer.  Time an installed copy (``pip install .`` into
a separate venv compiles the bytecode) with ``--rasterize``; ``--python``
runs the peers.  The machine is printed with the table.  The fonts are
the system's (DejaVu Sans must be installed for the text cases to draw
the same glyphs in every renderer).
"""

import argparse
import os
import platform
import shutil
import statistics
import sys
import tempfile

import numpy as np

# (the peers' programs, the timing of one process and the table cells are
# the coverage benchmark's)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_coverage import PEER_CODE, process_cells, timed  # noqa: E402

RENDERERS = ('raster', 'resvg', 'cairosvg')
SVG_NS = 'http://www.w3.org/2000/svg'

_WORDS = ('the quick brown fox jumps over a lazy dog while raster renders every glyph '
          'exactly').split()


def text_page(lines, words, size, width, height, seed=1):
    """``lines`` lines of ``words`` random words each at ``size`` px."""
    rng = np.random.default_rng(seed)
    body = []
    for i in range(lines):
        t = ' '.join(_WORDS[k] for k in rng.integers(0, len(_WORDS), words))
        body.append('<text x="4" y="%g" font-size="%g" font-family="DejaVu Sans">%s</text>'
                    % (size * 1.2 + i * size * 1.2, size, t))
    return ('<svg xmlns="%s" width="%d" height="%d">%s</svg>'
            % (SVG_NS, width, height, ''.join(body)))


def scatter(n=5000, seed=1, size=1000):
    """``n`` stroked, half transparent circles of radius 3 at random centres."""
    rng = np.random.default_rng(seed)
    xy = rng.uniform(10, size - 10, (n, 2))
    body = ''.join('<circle cx="%.2f" cy="%.2f" r="3" fill="steelblue" fill-opacity="0.5" '
                   'stroke="#123" stroke-width="1"/>' % (x, y) for x, y in xy)
    return '<svg xmlns="%s" width="%d" height="%d">%s</svg>' % (SVG_NS, size, size, body)


CASES = {
    'text12': ('60 lines of 12 px text, 1000x860', lambda: text_page(60, 22, 12, 1000, 860)),
    'text5': ('70 lines of 5 px text, 600x430', lambda: text_page(70, 40, 5, 600, 430)),
    'scatter': ('5,000 stroked circles, 1000x1000', scatter),
}


def run(names, renderers, repeat, rasterize, python, tmp):
    files = {}
    for name in names:
        files[name] = os.path.join(tmp, name + '.svg')
        with open(files[name], 'w') as f:
            f.write(CASES[name][1]())
    res = {}
    for name in names:
        for _ in range(repeat):
            for r in renderers:
                out = os.path.join(tmp, '%s_%s.png' % (name, r))
                cmd = ([rasterize, files[name], out] if r == 'raster'
                       else [python, '-c', PEER_CODE[r], files[name], out])
                res.setdefault((name, r), []).append(timed(cmd))
        print('  %-8s ' % name + '  '.join(
            '%s %.2f s' % (r, statistics.median(x[0] for x in res[(name, r)]))
            for r in renderers), flush=True)
    return res


def markdown(res, names, renderers, repeat):
    out = ['Machine: %s, %s, %d cores, load %s' % (platform.python_version(), platform.platform(),
                                                    os.cpu_count() or 0,
                                                    ' '.join('%.2f' % x for x in os.getloadavg())),
           '', 'Whole process (fresh process each, interleaved, median of %d): wall s / CPU s / '
           'peak RSS MB' % repeat, '',
           '| case | ' + ' | '.join(renderers) + ' | raster / faster peer (wall) |',
           '|---|' + '---|' * len(renderers) + '---|']
    for name in names:
        cells, vals, fast = process_cells({r: res[(name, r)] for r in renderers}, renderers)
        ratio = ''
        if fast is not None:
            ratio = '%.2fx %s' % (vals['raster'][0] / vals[fast][0], fast)
        out.append('| %s | %s | %s |' % (name, ' | '.join(cells), ratio))
    out += ['', 'Cases: ' + '; '.join('%s: %s' % (n, CASES[n][0]) for n in names), '']
    return '\n'.join(out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--repeat', type=int, default=3)
    ap.add_argument('--cases', default=','.join(CASES))
    ap.add_argument('--renderers', default=','.join(RENDERERS))
    ap.add_argument('--rasterize', default=None,
                    help='the rasterize command to time (default: beside this Python)')
    ap.add_argument('--python', default=sys.executable, help='Python that runs the peers')
    ap.add_argument('--markdown', default=None)
    args = ap.parse_args(argv)
    names = [c for c in args.cases.split(',') if c]
    bad = [c for c in names if c not in CASES]
    if bad:
        ap.error('unknown case(s): %s (known: %s)' % (', '.join(bad), ', '.join(CASES)))
    renderers = [r for r in args.renderers.split(',') if r]
    rasterize = args.rasterize or os.path.join(os.path.dirname(sys.executable), 'rasterize')
    tmp = tempfile.mkdtemp(prefix='bench_repeated_')
    try:
        res = run(names, renderers, args.repeat, rasterize, args.python, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    text = markdown(res, names, renderers, args.repeat)
    print(text)
    if args.markdown:
        with open(args.markdown, 'w') as f:
            f.write(text)
    return 0


if __name__ == '__main__':
    sys.exit(main())
