"""Scale benchmark (issue 12): many small files, one very large image, one
and two workers -- whole processes, as users run them.

    python bench/bench_scale.py --rasterize VENV/bin/rasterize --python VENV/bin/python
        [--sections icons,map] [--repeat 3] [--loop-files 50]
        [--widths 8000,16000,32000] [--json OUT.json] [--markdown OUT.md]

Every measurement is one fresh process (``rasterize`` of an installed copy,
the peers through ``python -c`` as in ``bench_corpus.py --mode process``)
under ``/usr/bin/time -f %M`` (peak RSS); the commands of one round run
one after the other, rounds repeat ``--repeat`` times (interleaved: every
command once per round), and the tables give medians.

* icons: the 200 single-icon documents of ``make_icons.py`` converted by
  ``rasterize DIR --out-dir OUT`` with ``--jobs 1`` and ``--jobs 2``, and by
  shell loops (``sh -c 'for f in ...; do ...; done'``, one process per
  file) of ``rasterize``, of resvg-py and of CairoSVG's ``cairosvg``
  command over the first ``--loop-files`` documents; seconds per file.
* map: the corpus world map at ``--widths`` px by ``rasterize`` (``--jobs
  1`` and ``--jobs 2``, the default memory budget: PNG in strips) and by
  resvg-py; time and peak RSS.  The RSS of ``--jobs 2`` is that of the
  largest process (the parent or a worker; ``/usr/bin/time`` reports the
  peak of one process).
"""

import argparse
import json
import os
import shlex
import statistics
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import bench_corpus as bc          # noqa: E402  (run_process, the peers' programs, machine_info)
import make_icons                  # noqa: E402

WORLD = os.path.join(HERE, '..', '..', 'shared', 'corpus', 'world_states_provinces.svg')


def icon_commands(args, icons, loop_files, out):
    """{name: argv} of the icon section."""
    rz = shlex.quote(args.rasterize)
    py = shlex.quote(args.python)
    cairo = shlex.quote(os.path.join(os.path.dirname(args.python), 'cairosvg'))
    files = ' '.join(shlex.quote(os.path.join(icons, f)) for f in loop_files)
    resvg = shlex.quote(RESVG_ONE)
    loop = 'for f in %s; do %%s; done' % files
    o = shlex.quote(out)
    return {
        'raster --jobs 1': [args.rasterize, icons, '--out-dir', out + '/j1', '--jobs', '1'],
        'raster --jobs 2': [args.rasterize, icons, '--out-dir', out + '/j2', '--jobs', '2'],
        'loop: rasterize': ['sh', '-c', loop % ('%s "$f" %s/r_$(basename "$f" .svg).png'
                                                % (rz, o))],
        'loop: resvg-py': ['sh', '-c', loop % ('%s -c %s "$f" %s/v_$(basename "$f" .svg).png'
                                               % (py, resvg, o))],
        'loop: cairosvg': ['sh', '-c', loop % ('%s "$f" -o %s/c_$(basename "$f" .svg).png'
                                               % (cairo, o))],
    }


#: resvg-py on one file (argv: svg, png), system fonts as in bench_corpus.
RESVG_ONE = """\
import sys, resvg_py
with open(sys.argv[2], 'wb') as f:
    f.write(bytes(resvg_py.svg_to_bytes(svg_path=sys.argv[1], dpi=96.0)))
"""


def map_commands(args, width, out):
    spec = dict(svg=WORLD, out=os.path.join(out, 'resvg.png'), width=width,
                resources=os.path.dirname(WORLD), fonts=bc.RESVG_FONTS)
    return {
        'raster --jobs 1': [args.rasterize, WORLD, os.path.join(out, 'r1.png'), '--width',
                            str(width), '--jobs', '1'],
        'raster --jobs 2': [args.rasterize, WORLD, os.path.join(out, 'r2.png'), '--width',
                            str(width), '--jobs', '2'],
        'resvg-py': [args.python, '-c', bc.RESVG_PROGRAM, json.dumps(spec)],
    }


def measure(groups, repeat, timeout, tmpdir, log):
    """{group: {name: [result per round]}}: every command of every group
    once per round, rounds ``repeat`` times."""
    res = {g: {n: [] for n in cmds} for g, cmds in groups.items()}
    for r in range(repeat):
        for g, cmds in groups.items():
            for n, cmd in cmds.items():
                m = bc.run_process(cmd, timeout, tmpdir)
                res[g][n].append(m)
                log('round %d %s %s: %s' % (r + 1, g, n, m))
    return res


def med(rs, key):
    xs = [r[key] for r in rs if key in r]
    return statistics.median(xs) if xs else None


def tables(res, n_icons, n_loop, widths):
    lines = []
    if 'icons' in res:
        ic = res['icons']
        lines += ['### %d small icon documents' % n_icons, '',
                  '| command | files | wall s (median) | CPU s | s per file | peak RSS MB |',
                  '|---|---|---|---|---|---|']
        per = {}
        for n, rs in ic.items():
            k = n_icons if n.startswith('raster') else n_loop
            w, c, m = med(rs, 'wall'), med(rs, 'cpu'), med(rs, 'rss_mb')
            if w is None:
                lines.append('| %s | %d | failed: %s | | | |' % (n, k, rs[0].get('error')))
                continue
            per[n] = w / k
            lines.append('| %s | %d | %.2f | %.2f | %.4f | %.0f |' % (n, k, w, c, w / k, m))
        lines.append('')
        if 'loop: rasterize' in per:
            for n in ('raster --jobs 1', 'raster --jobs 2'):
                if n in per:
                    lines.append('- per file, `%s` is %.1fx faster than the shell loop of '
                                 '`rasterize`' % (n, per['loop: rasterize'] / per[n]))
        if 'raster --jobs 1' in per and 'raster --jobs 2' in per:
            lines.append('- batch speed-up from one to two workers: %.2fx'
                         % (per['raster --jobs 1'] / per['raster --jobs 2']))
        lines.append('')
    for w in widths:
        g = 'map %d' % w
        if g not in res:
            continue
        lines += ['### World map at %d px width' % w, '',
                  '| renderer | wall s (median) | CPU s | peak RSS MB |', '|---|---|---|---|']
        walls = {}
        for n, rs in res[g].items():
            wall, c, m = med(rs, 'wall'), med(rs, 'cpu'), med(rs, 'rss_mb')
            if wall is None:
                lines.append('| %s | failed: %s | | |' % (n, rs[0].get('error')))
                continue
            walls[n] = wall
            lines.append('| %s | %.1f | %.1f | %.0f |' % (n, wall, c, m))
        lines.append('')
        if 'resvg-py' in walls:
            for n in ('raster --jobs 1', 'raster --jobs 2'):
                if n in walls:
                    lines.append('- `%s` / resvg: %.2fx the time' % (n, walls[n] / walls['resvg-py']))
        if 'raster --jobs 1' in walls and 'raster --jobs 2' in walls:
            lines.append('- speed-up from one to two workers: %.2fx'
                         % (walls['raster --jobs 1'] / walls['raster --jobs 2']))
        lines.append('')
    return lines


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--rasterize', required=True, help='rasterize of an installed copy')
    ap.add_argument('--python', required=True, help='python with resvg-py and CairoSVG')
    ap.add_argument('--sections', default='icons,map')
    ap.add_argument('--repeat', type=int, default=3)
    ap.add_argument('--icons', type=int, default=200)
    ap.add_argument('--loop-files', type=int, default=50)
    ap.add_argument('--widths', default='8000,16000,32000')
    ap.add_argument('--timeout', type=float, default=900)
    ap.add_argument('--json')
    ap.add_argument('--markdown')
    args = ap.parse_args(argv)
    sections = set(args.sections.split(','))
    widths = [int(w) for w in args.widths.split(',') if w]
    info = bc.machine_info(args.python)
    for line in info:
        print(line, flush=True)
    with tempfile.TemporaryDirectory(prefix='bench_scale_') as tmp:
        icons = os.path.join(tmp, 'icons')
        os.makedirs(icons)
        docs = make_icons.documents(args.icons)
        for name, data in docs:
            with open(os.path.join(icons, name), 'wb') as f:
                f.write(data)
        groups = {}
        if 'icons' in sections:
            out = os.path.join(tmp, 'icons_out')
            os.makedirs(out)
            loop = sorted(os.listdir(icons))[:args.loop_files]
            groups['icons'] = icon_commands(args, icons, loop, out)
        if 'map' in sections:
            for w in widths:
                out = os.path.join(tmp, 'map_%d' % w)
                os.makedirs(out)
                groups['map %d' % w] = map_commands(args, w, out)
        res = measure(groups, args.repeat, args.timeout, tmp, lambda s: print(s, flush=True))
    lines = ['Machine: ' + info[0]] + info[1:] + [''] + tables(
        res, args.icons, min(args.loop_files, args.icons), widths)
    text = '\n'.join(lines) + '\n'
    print(text)
    if args.markdown:
        with open(args.markdown, 'w') as f:
            f.write(text)
    if args.json:
        with open(args.json, 'w') as f:
            json.dump({'machine': info, 'results': res}, f, indent=1)
    return 0


if __name__ == '__main__':
    sys.exit(main())
