"""Core benchmark: flatten + exact-area scan conversion + canvas fill.

Run as ``python bench/bench_core.py`` (``--repeats N`` to change the number
of timed repeats; the median is reported).  Rows:

(a) fill a 100,000-segment random star-shaped polygon (seed 0) into a
    2000x2000 canvas: flatten + coverage + fill.  Two variants: a smooth
    random radius (sum of 40 random harmonics), and the same radius with
    +-0.5 px random jitter per vertex, whose zig-zag boundary makes every
    boundary pixel hold a tangled chain (recomputed exactly).
(b) flatten 10,000 random cubics at tolerance 0.25.
(c) stroke a 10,000-segment dashed polyline (raster.stroke) and fill it.
(d) PNG encode time of the 2000x2000 result at zlib levels 1, 3, 6 with
    the default and the run-length (Z_RLE) strategies, and Canvas.save_png.

For each row: median wall time, segments per second through
flatten + scan conversion (the canvas fill is timed separately), and the
tracemalloc peak of one run relative to the canvas buffer
(2000 * 2000 * 4 channels * 4 bytes = 64 MB).
"""

import argparse
import io
import statistics
import time
import tracemalloc

import numpy as np

from raster.pixels.canvas import Canvas
from raster.geometry.path import Path
from raster.pixels.scan import coverage

W = H = 2000
CANVAS_BYTES = W * H * 4 * 4


def star_polygon(n, jitter, seed=0):
    rng = np.random.default_rng(seed)
    th = np.sort(rng.uniform(0, 2 * np.pi, n))
    k = np.arange(1, 41)[:, None]
    amp = rng.normal(size=(40, 1)) * 60.0 / k
    ph = rng.uniform(0, 2 * np.pi, (40, 1))
    r = 900.0 + (amp * np.cos(k * th[None, :] + ph)).sum(0)
    if jitter:
        r = r + rng.uniform(-jitter, jitter, n)
    return np.c_[1000.0 + r * np.cos(th), 1000.0 + r * np.sin(th)]


CPU = {}
BEST = {}


def timed(fn, repeats):
    """Median wall time of ``repeats`` calls (the median CPU time of this
    process goes to CPU[fn.__name__]: the machine may be shared)."""
    times, cpu = [], []
    out = None
    for _ in range(repeats):
        c0 = time.process_time()
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    CPU[fn.__name__] = statistics.median(cpu)
    BEST[fn.__name__] = min(times)
    return statistics.median(times), out


def peak_of(fn):
    tracemalloc.start()
    tracemalloc.reset_peak()
    fn()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak


def edges_of(path, tolerance=0.25):
    from raster.geometry.flattening import flatten
    return flatten(path, tolerance=tolerance).edges(close_all=True)


def row(name, nseg, t_scan, t_fill, peak):
    rate = nseg / t_scan if t_scan > 0 else float('inf')
    cpu = CPU.get('scan', 0.0)
    best = BEST.get('scan', t_scan)
    print('%-28s %6d seg  flatten+scan %6.1f ms (best %6.1f, cpu %6.1f)  %5.2f Mseg/s'
          ' (best %5.2f)  fill %5.1f ms  peak %4.2fx canvas'
          % (name, nseg, t_scan * 1e3, best * 1e3, cpu * 1e3, rate / 1e6,
             nseg / best / 1e6, t_fill * 1e3, peak / CANVAS_BYTES))


def bench_polygon(repeats, jitter):
    path = Path.polygon(star_polygon(100_000, jitter))

    def scan():
        return coverage(edges_of(path), W, H)

    edges = edges_of(path)

    def flat():
        return edges_of(path)

    def scan_only():
        return coverage(edges, W, H)
    t_flat, _ = timed(flat, repeats)
    t_cov, _ = timed(scan_only, repeats)
    t_scan, mask = timed(scan, repeats)
    canvas = Canvas(W, H, background=(1, 1, 1))
    t_fill, _ = timed(lambda: canvas.fill(mask, (0.2, 0.4, 0.8, 0.9)), repeats)

    def whole():
        c = Canvas(W, H, background=(1, 1, 1))
        c.fill(scan(), (0.2, 0.4, 0.8, 0.9))
    peak = peak_of(whole)
    label = '(a) 100k-gon %s' % ('jitter 0.5px' if jitter else 'smooth')
    row(label, 100_000, t_scan, t_fill, peak)
    print('    of which flatten %.1f ms (best %.1f), coverage %.1f ms (best %.1f, cpu %.1f)'
          % (t_flat * 1e3, BEST['flat'] * 1e3, t_cov * 1e3, BEST['scan_only'] * 1e3,
             CPU['scan_only'] * 1e3))
    return canvas


def bench_cubics(repeats):
    try:
        from raster.geometry.flattening import flatten_beziers
    except ImportError:
        print('(b) skipped: raster.geometry.flattening.flatten_beziers not available')
        return
    rng = np.random.default_rng(0)
    p0 = rng.uniform(0, W, (10_000, 1, 2))
    ctrl = p0 + rng.normal(0, 60, (10_000, 4, 2))
    ctrl[:, 0] = p0[:, 0]
    t, (pts, counts) = timed(lambda: flatten_beziers(ctrl, 0.25), repeats)
    nseg = int((counts - 1).sum())
    print('%-34s %9d cubics -> %d segments  %8.1f ms  %6.2f Mseg/s out'
          % ('(b) flatten 10k cubics tol 0.25', 10_000, nseg, t * 1e3, nseg / t / 1e6))


def bench_stroke(repeats):
    try:
        from raster.geometry.stroking import stroke
    except ImportError:
        print('(c) skipped: raster.stroke not available yet')
        return
    rng = np.random.default_rng(0)
    # a random walk of 10,000 segments, 2-8 px steps, kept on the canvas
    ang = np.cumsum(rng.normal(0, 0.5, 10_000))
    step = rng.uniform(2, 8, 10_000)
    pts = np.cumsum(np.c_[np.cos(ang), np.sin(ang)] * step[:, None], axis=0)
    pts = np.abs((pts + 1000.0) % 3800.0 - 1900.0) + 50.0        # fold into [50, 1950]
    pts = np.vstack([[[1000.0, 1000.0]], pts])
    path = Path.polygon(pts, closed=False)

    def outline():
        return stroke(path, width=3.0, dash=[12.0, 6.0], join='round', cap='round')

    t_stroke, out = timed(outline, max(1, repeats // 2))
    edges = edges_of(out)
    def scan():
        return coverage(edges, W, H)
    t_scan, mask = timed(scan, repeats)
    canvas = Canvas(W, H, background=(1, 1, 1))
    t_fill, _ = timed(lambda: canvas.fill(mask, (0, 0, 0)), repeats)

    def whole():
        c = Canvas(W, H, background=(1, 1, 1))
        c.fill(coverage(edges_of(stroke(path, width=3.0, dash=[12.0, 6.0],
                                        join='round', cap='round')), W, H), (0, 0, 0))
    peak = peak_of(whole)
    print('(c) stroke 10k-segment dashed walk: stroke %.1f ms -> %d outline edges'
          % (t_stroke * 1e3, len(edges)))
    row('(c) scan stroke outline', len(edges), t_scan, t_fill, peak)


def bench_png(canvas):
    img = canvas.to_image()
    for level in (1, 3, 6):
        for strategy, name in ((-1, 'default'), (3, 'Z_RLE')):
            def enc():
                b = io.BytesIO()
                img.save(b, format='PNG', compress_level=level, compress_type=strategy)
                return len(b.getvalue())
            t, size = timed(enc, 3)
            print('(d) PNG 2000x2000 level %d %-7s: %7.1f ms (cpu %6.1f)  %8d bytes'
                  % (level, name, t * 1e3, CPU['enc'] * 1e3, size))

    def save():
        b = io.BytesIO()
        canvas.save_png(b)
        return len(b.getvalue())
    t, size = timed(save, 3)
    print('(d) Canvas.save_png default (to_rgba8 + encode): %7.1f ms (cpu %6.1f)  %8d bytes'
          % (t * 1e3, CPU['save'] * 1e3, size))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--repeats', type=int, default=5)
    args = ap.parse_args()
    import os
    print('canvas %dx%d = %.0f MB premultiplied float32; median of %d repeats; '
          'load average %.1f on %d CPUs'
          % (W, H, CANVAS_BYTES / 2**20, args.repeats, os.getloadavg()[0], os.cpu_count()))
    canvas = bench_polygon(args.repeats, 0.0)
    bench_polygon(args.repeats, 0.5)
    bench_cubics(args.repeats)
    bench_stroke(args.repeats)
    bench_png(canvas)


if __name__ == '__main__':
    main()
