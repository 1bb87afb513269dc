"""Hostile-input benchmark: each case of issue 16 as users meet it.

Run from the repository root, with a Python that has numpy and Pillow (the
generators need them)::

    python bench/bench_hostile.py --bin BEFORE_VENV/bin --bin AFTER_VENV/bin
                                  [--repeat 3] [--timeout 60] [--memory-mb 4000]
                                  [--huge] [--cases PATTERN] [--markdown OUT.md]

Every case is a whole process of a command (``rasterize``, ``svg-bbox``,
``svg-flatten``) of each ``--bin`` directory (an installed copy: ``pip
install .`` into a separate venv compiles the bytecode), started fresh
under ``/usr/bin/time -f '%e %M %U %S'``: the wall time, the CPU time
(user + system) and the peak RSS of the process.  Runs are interleaved (case by case, the installs alternating),
and the median of ``--repeat`` runs is reported with the first line of
stderr and the number of stderr lines.  A process over ``--timeout``
seconds is killed and shown as ``> T s``; one over ``--memory-mb`` of
address space fails with the command's own out-of-memory message.

The inputs are the generators of ``tests/hostile/_hostile_generate.py``
and the files of ``tests/hostile/cases`` (the same documents the test suite
checks), plus ``/dev/zero`` as a file and as stdin; ``--huge`` adds the
199 MB document of 6.8 million rects (written to a temporary directory).
"""

import argparse
import fnmatch
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CASES = os.path.join(ROOT, 'tests', 'hostile', 'cases')
sys.path.insert(0, os.path.join(ROOT, 'tests', 'hostile'))

import _hostile_generate as gen  # noqa: E402

#: (name, command, input: a file of cases/, 'gen:<function>', '/dev/zero',
#: 'stdin-zeros' or 'huge-rects', extra arguments)
TABLE = [
    ('feTurbulence numOctaves=1e9', 'rasterize', 'turbulence_octaves.svg', []),
    ('feConvolveMatrix order=1000', 'rasterize', 'gen:convolve_order_1000', []),
    ('viewBox 1e-9 with one cubic', 'rasterize', 'tiny_viewbox.svg', []),
    ('60-byte path to 6.7e21', 'rasterize', 'huge_quadratic.svg', []),
    ('10^4 use copies of an opacity layer', 'rasterize', 'gen:use_opacity_copies', []),
    ('10^4 use copies of a blurred rect', 'rasterize', 'gen:use_blur_copies', []),
    ('10^8 use fan-out', 'rasterize', 'use_fanout.svg', []),
    ('10^8 use fan-out, svg-bbox', 'svg-bbox', 'use_fanout.svg', []),
    ('10^8 use fan-out, svg-flatten', 'svg-flatten', 'use_fanout.svg', []),
    ('7.5 MB path of 3.75M segments', 'rasterize', 'gen:long_path', []),
    ('2 MB path of 998k segments (at max_path_bytes)', 'rasterize', 'gen:path_at_the_limit', []),
    ('300k rects (8.4 MB)', 'rasterize', 'gen:many_elements', []),
    ('199 MB of 6.8M rects', 'rasterize', 'huge-rects', []),
    ('20,000 rules x 4,000 elements', 'rasterize', 'gen:css_rules', []),
    ('/dev/zero as the input', 'rasterize', '/dev/zero', []),
    ('3 GB of zeros on stdin', 'rasterize', 'stdin-zeros', []),
    ('broken hmtx/head font', 'rasterize', 'gen:broken_font', []),
    ('12 MB data: image, default', 'rasterize', 'gen:big_image', []),
    ('12 MB data: image, --max-xml-text-bytes', 'rasterize', 'gen:big_image',
     ['--max-xml-text-bytes', '20000000']),
    ('20,000 markers of 50 circles', 'rasterize', 'markers_many.svg', []),
    ('dashes of 0.001 on a 1e8 line', 'rasterize', 'dash_storm.svg', []),
    ('dashes of 1e-6 on a 1e8 line', 'rasterize', 'dash_storm_visible.svg', []),
    ('stroke-width 1e12', 'rasterize', 'stroke_huge_width.svg', []),
    ('text stroked 240in wide, dashed, as a mask', 'rasterize', 'fuzz_crowded_cells.svg', []),
    ('457,300 dashes of a line to 1e9, 64x48', 'rasterize', 'fuzz_far_dashes.svg', []),
    ('254 nested svg', 'rasterize', 'deep_svg.svg', []),
    ('svgz bomb (300 MB of spaces)', 'rasterize', 'svgz_bomb.svgz', []),
    ('billion laughs', 'rasterize', 'billion_laughs.svg', []),
]


def huge_rects(d):
    p = os.path.join(d, 'huge_rects.svg')
    with open(p, 'w') as f:
        f.write('<svg xmlns="http://www.w3.org/2000/svg" width="200" height="200">')
        r = '<rect width="1" height="1"/>' * 100_000
        for _ in range(68):
            f.write(r)
        f.write('</svg>')
    return p


def prepare(spec, d):
    """(input argument, extra arguments, stdin file or None) of a case."""
    if spec.startswith('gen:'):
        made = getattr(gen, spec[4:])(d)
        return (made[0], made[1], None) if isinstance(made, tuple) else (made, [], None)
    if spec == 'huge-rects':
        return huge_rects(d), [], None
    if spec == 'stdin-zeros':
        return '-', [], 'zeros'
    if spec.startswith('/'):
        return spec, [], None
    return os.path.join(CASES, spec), [], None


def run_once(bindir, command, src, args, stdin, out, timeout, memory_mb):
    """(seconds or None, peak RSS kB or None, stderr lines, CPU seconds or None)
    of one process."""
    exe = os.path.join(bindir, command)
    target = [out] if command == 'rasterize' else ['-o', out]
    inner = [exe, src] + target + args
    script = 'ulimit -v %d; ' % (memory_mb * 1024)
    if stdin == 'zeros':
        script += 'head -c 3000000000 /dev/zero | exec "$@"'
    else:
        script += 'exec "$@"'
    cmd = ['/usr/bin/time', '-f', 'TIME %e %M %U %S', 'timeout', str(timeout), 'bash', '-c', script,
           '_'] + inner
    p = subprocess.run(cmd, capture_output=True, text=True, errors='replace')
    lines = p.stderr.splitlines()
    stat = [ln for ln in lines if ln.startswith('TIME ')]
    msgs = [ln for ln in lines if not ln.startswith('TIME ') and 'Command exited' not in ln
            and 'Command terminated' not in ln]
    if p.returncode == 124 or not stat:
        return None, None, msgs, None
    _, t, m, u, s = stat[-1].split()
    return float(t), int(m), msgs, float(u) + float(s)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--bin', action='append', required=True,
                    help='bin directory of an installed copy (repeat to compare)')
    ap.add_argument('--repeat', type=int, default=3)
    ap.add_argument('--timeout', type=int, default=60)
    ap.add_argument('--memory-mb', type=int, default=4000)
    ap.add_argument('--huge', action='store_true', help='include the 199 MB document')
    ap.add_argument('--cases', default='*',
                    help='fnmatch patterns of case names, separated by commas')
    ap.add_argument('--markdown', help='write the table here too')
    args = ap.parse_args(argv)
    rows = []
    tmp = tempfile.mkdtemp(prefix='bench_hostile_')
    try:
        for name, command, spec, extra in TABLE:
            if (not any(fnmatch.fnmatch(name, p) for p in args.cases.split(','))
                    or (spec == 'huge-rects' and not args.huge)):
                continue
            src, more, stdin = prepare(spec, tmp)
            runs = {b: [] for b in args.bin}
            for _ in range(args.repeat):
                for b in args.bin:                    # interleaved
                    runs[b].append(run_once(b, command, src, more + extra, stdin,
                                            os.path.join(tmp, 'out.png'), args.timeout,
                                            args.memory_mb))
            cells = []
            for b in args.bin:
                ts = [r[0] for r in runs[b]]
                ms = [r[1] for r in runs[b] if r[1] is not None]
                msgs = runs[b][-1][2]
                t = ('> %d s' % args.timeout if any(x is None for x in ts)
                     else '%.2f s (CPU %.2f s)' % (statistics.median(ts),
                                                  statistics.median(r[3] for r in runs[b])))
                m = '%d MB' % (statistics.median(ms) // 1024) if ms else '-'
                first = msgs[0] if msgs else '(no message)'
                if len(first) > 110:
                    first = first[:107] + '...'
                cells.append('%s, %s, %d line%s: %s' % (t, m, len(msgs), '' if len(msgs) == 1
                                                        else 's', first))
            rows.append((name, cells))
            print('%-40s %s' % (name, ' || '.join(cells)), flush=True)
            if spec == 'huge-rects':
                os.unlink(src)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    head = '| case | ' + ' | '.join(args.bin) + ' |\n|---|' + '---|' * len(args.bin) + '\n'
    table = head + ''.join('| %s | %s |\n' % (n, ' | '.join(c.replace('|', '/') for c in cells))
                           for n, cells in rows)
    if args.markdown:
        with open(args.markdown, 'w') as f:
            f.write(table)
    print()
    print(table)


if __name__ == '__main__':
    main()
