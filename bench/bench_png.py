"""PNG encoders on the corpus outputs: raster's own against Pillow's.

    python bench/bench_png.py [--width 2000] [--repeat 3] [--levels 1,6] [--files PATTERN]

Every ``../shared/corpus`` file is rendered once by raster at ``--width``
(an 8-bit RGBA picture, as ``rasterize`` writes it); that picture is then
encoded once untimed and ``--repeat`` times timed by :func:`raster.pixels.png.encode_png` at
:data:`raster.pixels.canvas.DEFAULT_COMPRESS_LEVEL` (what the commands use)
and by Pillow's PNG plugin at each of ``--levels`` (Pillow's default is 6).
Reported per file: the median encode time (``time.process_time``, CPU of
this process) and the size of each encoding; below the table the totals
and, for each Pillow level, on how many files raster's encoder was faster
and no larger.  Issue 17 keeps whichever encoder is faster at equal or
smaller size.
"""
import argparse
import fnmatch
import glob
import io
import os
import statistics
import sys
import time

DEFAULT_CORPUS = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'shared',
                              'corpus')


def _median_cpu(fn, repeat):
    """(median CPU seconds of ``repeat`` calls of fn after one untimed
    warm-up call, its last result)."""
    times, out = [], fn()
    for _ in range(repeat):
        t = time.process_time()
        out = fn()
        times.append(time.process_time() - t)
    return statistics.median(times), out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--corpus', default=DEFAULT_CORPUS)
    ap.add_argument('--files', default=None, metavar='PATTERN',
                    help='comma-separated fnmatch patterns or substrings of file names')
    ap.add_argument('--width', type=int, default=2000)
    ap.add_argument('--repeat', type=int, default=3)
    ap.add_argument('--levels', default='1,6', help="Pillow's compress_level values to compare")
    args = ap.parse_args(argv)
    import numpy as np
    from PIL import Image

    import raster
    from raster.pixels.canvas import DEFAULT_COMPRESS_LEVEL
    from raster.pixels.png import encode_png

    levels = [int(x) for x in args.levels.split(',') if x.strip()]
    files = sorted(glob.glob(os.path.join(args.corpus, '*.svg')))
    if args.files:
        pats = [p.strip() for p in args.files.split(',') if p.strip()]
        files = [f for f in files if any(fnmatch.fnmatch(os.path.basename(f), p)
                                         or p in os.path.basename(f) for p in pats)]
    if not files:
        ap.error('no .svg files in %s match' % args.corpus)
    head = ['file', 'size (px)', 'raster ms', 'raster KB']
    for lv in levels:
        head += ['Pillow %d ms' % lv, 'Pillow %d KB' % lv]
    lines = ['| ' + ' | '.join(head) + ' |', '|' + '---|' * len(head)]
    tot = {'raster': [0.0, 0]}
    wins = {lv: 0 for lv in levels}
    for lv in levels:
        tot[lv] = [0.0, 0]
    for path in files:
        rgba = np.ascontiguousarray(raster.render(path, args.width))
        h, w = rgba.shape[:2]
        t, png = _median_cpu(lambda: encode_png(rgba, DEFAULT_COMPRESS_LEVEL), args.repeat)
        row = [os.path.basename(path), '%dx%d' % (w, h), '%.1f' % (t * 1e3),
               '%.0f' % (len(png) / 1024)]
        tot['raster'][0] += t
        tot['raster'][1] += len(png)
        img = Image.fromarray(rgba, 'RGBA')
        for lv in levels:
            def pil(lv=lv):
                b = io.BytesIO()
                img.save(b, format='PNG', compress_level=lv)
                return b.getvalue()
            tp, pp = _median_cpu(pil, args.repeat)
            row += ['%.1f' % (tp * 1e3), '%.0f' % (len(pp) / 1024)]
            tot[lv][0] += tp
            tot[lv][1] += len(pp)
            wins[lv] += t <= tp and len(png) <= len(pp)
        lines.append('| ' + ' | '.join(row) + ' |')
        print(lines[-1], flush=True)
    total = ['**total**', '', '%.0f' % (tot['raster'][0] * 1e3), '%.0f' % (tot['raster'][1] / 1024)]
    for lv in levels:
        total += ['%.0f' % (tot[lv][0] * 1e3), '%.0f' % (tot[lv][1] / 1024)]
    lines.append('| ' + ' | '.join(total) + ' |')
    print('\n'.join(lines[:2] + lines[-1:]))
    print('raster level %d, median CPU of %d encodes, width %d px' % (
        DEFAULT_COMPRESS_LEVEL, args.repeat, args.width))
    for lv in levels:
        print('against Pillow compress_level=%d: raster faster and no larger on %d of %d files'
              % (lv, wins[lv], len(files)))
    return 0


if __name__ == '__main__':
    sys.exit(main())
