"""Start-up of the commands on a minimal document, against the interpreter
importing numpy and lxml.

    python bench/bench_startup.py [--python VENV/bin/python] [--rounds 21] \
        [--also LABEL=CMD ...] [--markdown OUT.md]

A 100x100 document with one rectangle is written to a temporary folder and
rendered to PNG by fresh processes, the programs interleaved (the order
rotated each round):

- ``python -c "import numpy, lxml.etree"`` (issue 17's yardstick: raster's
  ``rasterize`` should take at most 1.3x its wall time);
- ``rasterize min.svg out.png`` (the ``rasterize`` beside ``--python``);
- resvg-py and CairoSVG rendering the same file through ``python -c``;
- any ``--also LABEL=CMD`` (``{svg}`` and ``{out}`` in CMD are replaced),
  e.g. an older installed copy's ``rasterize``.

Reported per program: median wall-clock time, median CPU time (user +
system) and median peak RSS (``/usr/bin/time -f %M``), and the ratios of
the time medians to the yardstick's; the load average seen is printed.
Time an installed copy (``pip install .`` into a venv): an editable
install under ``PYTHONDONTWRITEBYTECODE`` recompiles raster at every start.
"""
import argparse
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

MINIMAL_SVG = ('<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">'
               '<rect x="10" y="10" width="80" height="80" fill="teal"/></svg>\n')


def programs(python, rasterize, svg, out, also=()):
    """Ordered {label: argv} of the programs to compare."""
    progs = {
        'python -c "import numpy, lxml.etree"': [python, '-c', 'import numpy, lxml.etree'],
        'rasterize min.svg out.png': [rasterize, svg, out],
        'resvg-py (python -c)': [python, '-c', 'import sys, resvg_py; open(sys.argv[2], "wb").write('
                                 'bytes(resvg_py.svg_to_bytes(svg_path=sys.argv[1])))', svg, out],
        'CairoSVG (python -c)': [python, '-c', 'import sys, cairosvg; '
                                 'cairosvg.svg2png(url=sys.argv[1], write_to=sys.argv[2])', svg, out],
    }
    for item in also:
        label, _, cmd = item.partition('=')
        progs[label] = [a.replace('{svg}', svg).replace('{out}', out) for a in shlex.split(cmd)]
    return progs


def measure(progs, rounds):
    """{label: {'wall': [...], 'cpu': [...], 'rss_mb': [...]}} and the
    1-minute load averages seen before each round."""
    res = {k: {'wall': [], 'cpu': [], 'rss_mb': []} for k in progs}
    keys = list(progs)
    loads = []
    for i in range(rounds):
        loads.append(os.getloadavg()[0])
        for k in keys[i % len(keys):] + keys[:i % len(keys)]:
            t = time.perf_counter()
            p = subprocess.run(['/usr/bin/time', '-f', '%M %U %S'] + progs[k],
                               capture_output=True, text=True, cwd=tempfile.gettempdir())
            wall = time.perf_counter() - t
            if p.returncode != 0:
                raise SystemExit('%s failed: %s' % (k, (p.stderr.strip().splitlines() or ['?'])[-1]))
            m, u, s = p.stderr.strip().splitlines()[-1].split()
            res[k]['wall'].append(wall)
            res[k]['cpu'].append(float(u) + float(s))
            res[k]['rss_mb'].append(int(m) / 1024)
    return res, loads


def table(res, loads):
    keys = list(res)
    med = {k: {m: statistics.median(v) for m, v in res[k].items()} for k in keys}
    ref = med[keys[0]]
    lines = ['| program | wall ms | / yardstick | CPU ms | / yardstick | peak RSS MB |',
             '|---|---|---|---|---|---|']
    for k in keys:
        r = med[k]
        lines.append('| %s | %.0f | %.2f | %.0f | %.2f | %.0f |' % (
            k, r['wall'] * 1e3, r['wall'] / ref['wall'], r['cpu'] * 1e3,
            r['cpu'] / ref['cpu'] if ref['cpu'] else float('nan'), r['rss_mb']))
    lines.append('')
    lines.append('Medians of %d interleaved rounds; load average (1 min) %.1f to %.1f.'
                 % (len(loads), min(loads), max(loads)))
    return lines


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--python', default=sys.executable)
    ap.add_argument('--rasterize', default=None, help='default: rasterize beside --python')
    ap.add_argument('--rounds', type=int, default=21)
    ap.add_argument('--also', action='append', default=[], metavar='LABEL=CMD')
    ap.add_argument('--markdown', metavar='OUT.md')
    args = ap.parse_args(argv)
    if args.rounds < 1:
        ap.error('--rounds must be >= 1')
    rasterize = args.rasterize or os.path.join(os.path.dirname(args.python), 'rasterize')
    with tempfile.TemporaryDirectory(prefix='bench_startup_') as tmp:
        svg = os.path.join(tmp, 'min.svg')
        with open(svg, 'w') as f:
            f.write(MINIMAL_SVG)
        res, loads = measure(programs(args.python, rasterize, svg, os.path.join(tmp, 'out.png'),
                                      args.also), args.rounds)
    lines = table(res, loads)
    print('\n'.join(lines))
    if args.markdown:
        with open(args.markdown, 'w') as f:
            f.write('\n'.join(lines) + '\n')
    return 0


if __name__ == '__main__':
    sys.exit(main())
