"""Conformance harness: render the resvg test suite and judge every case.

Usage::

    python -m raster_cli.conformance [--suite DIR] [--jobs N] [--filter PAT ...]
                                     [--timeout S] [--diffs DIR] [--json OUT]
                                     [--check | --update [--force]]
                                     [--renderer raster|resvg]

Every ``<suite>/tests/<area>/<feature>/<case>.svg`` is rendered at 300 px
width and compared with the reference ``<case>.png`` beside it using
:func:`raster.testing.compare_images` (the project's pass criterion).  Each
case runs in a forked worker process; a case that hangs past ``--timeout``
or crashes its worker loses only that case (the worker is replaced).

Ratchet: ``tests/conformance_ratchet.json`` records the pass count of every
area.  ``--check`` exits 1 when an area passes fewer cases than recorded;
``--update`` raises the recorded counts to the current ones (``--force``
also lowers them).  Both need the whole suite (no ``--filter``).

``--renderer resvg`` renders with resvg-py (the reference renderer, with the
options the project's scorer uses) to validate the harness itself.
"""

import argparse
import fnmatch
import json
import multiprocessing as mp
import os
import sys
import time
from collections import Counter
from multiprocessing import connection as mpconn

import numpy as np

from raster.testing import SUITE_GENERIC_FAMILIES

from ._common import add_version

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_SUITE = os.path.normpath(os.path.join(REPO_ROOT, '..', 'shared', 'resvg-suite'))
DEFAULT_RATCHET = os.path.join(REPO_ROOT, 'tests', 'conformance_ratchet.json')
WIDTH = 300
STATUSES = ('pass', 'fail', 'error', 'timeout')
# Generic font families the suite's references were made with (resvg harness).
GENERIC_FAMILIES = SUITE_GENERIC_FAMILIES


class HarnessError(Exception):
    """A harness usage problem (missing suite, unreadable ratchet file)."""


# ---------------------------------------------------------------------------
# Discovery
# ---------------------------------------------------------------------------

def matches(pattern, name):
    """Substring match, or glob match when the pattern has ``* ? [``
    (a glob may match anywhere in the name)."""
    if pattern.endswith('.svg'):
        pattern = pattern[:-4]
    if any(ch in pattern for ch in '*?['):
        return fnmatch.fnmatchcase(name, pattern) or fnmatch.fnmatchcase(name, '*' + pattern + '*')
    return pattern in name


def discover(suite, filters=()):
    """Cases of the suite as dicts ``{name, svg, png, area, feature}``,
    sorted by name.  ``name`` is the path below ``tests/`` without ``.svg``;
    ``feature`` is ``area/feature`` (the area itself for a case directly in
    an area directory)."""
    root = os.path.join(suite, 'tests')
    if not os.path.isdir(root):
        raise HarnessError('no test suite at %s (expected a tests/ directory; use --suite)' % suite)
    cases = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames.sort()
        for fn in filenames:
            if not fn.endswith('.svg'):
                continue
            full = os.path.join(dirpath, fn)
            name = os.path.relpath(full, root).replace(os.sep, '/')[:-4]
            if filters and not any(matches(p, name) for p in filters):
                continue
            parts = name.split('/')
            cases.append({'name': name, 'svg': full, 'png': full[:-4] + '.png',
                          'area': parts[0],
                          'feature': '/'.join(parts[:2]) if len(parts) > 2 else parts[0]})
    cases.sort(key=lambda c: c['name'])
    return cases


# ---------------------------------------------------------------------------
# Renderers (constructed and run inside worker processes); each returns an
# (H, W, 4) uint8 straight-alpha array.
# ---------------------------------------------------------------------------

class RasterRenderer:
    def __init__(self, cfg):
        from raster.svg import render
        self.render_fn = render
        self.cfg = cfg

    def render(self, case):
        return self.render_fn(case['svg'], width=self.cfg['width'], fonts=self.fonts,
                              resources_dir=self.cfg['resources_dir'], languages=('en',))

    @property
    def fonts(self):
        """The suite's fonts only, with resvg's harness mapping (no system
        fonts, so the numbers stay comparable between machines)."""
        from raster.testing import suite_fonts
        return suite_fonts(self.cfg['fonts_dir'])


class ResvgRenderer:
    """resvg-py with the options the project's scorer uses (usvg defaults:
    dpi 96, font size 12, language en, suite fonts only)."""

    def __init__(self, cfg):
        import resvg_py
        self.mod = resvg_py
        self.cfg = cfg

    def render(self, case):
        import io
        from PIL import Image
        png = self.mod.svg_to_bytes(
            svg_path=case['svg'], width=self.cfg['width'],
            resources_dir=os.path.dirname(case['svg']), dpi=96.0, font_size=12.0,
            languages=['en'], font_family='Times New Roman', skip_system_fonts=True,
            font_dirs=[self.cfg['fonts_dir']],
            serif_family=GENERIC_FAMILIES['serif'],
            sans_serif_family=GENERIC_FAMILIES['sans-serif'],
            cursive_family=GENERIC_FAMILIES['cursive'],
            fantasy_family=GENERIC_FAMILIES['fantasy'],
            monospace_family=GENERIC_FAMILIES['monospace'])
        im = Image.open(io.BytesIO(bytes(png)))
        return np.asarray(im.convert('RGBA'))


RENDERERS = {'raster': RasterRenderer, 'resvg': ResvgRenderer}


def load_png(path):
    from PIL import Image
    with Image.open(path) as im:
        im.load()
        if im.mode in ('I;16', 'I;16B', 'I;16L', 'I'):
            g = np.clip(np.round(np.asarray(im).astype(np.float64) / 257.0), 0, 255)
            g = g.astype(np.uint8)
            return np.dstack([g, g, g, np.full_like(g, 255)])
        return np.asarray(im.convert('RGBA'))


# ---------------------------------------------------------------------------
# One case, in a worker
# ---------------------------------------------------------------------------

def run_case(case, renderer, init_error, cfg):
    """Render and judge one case; returns a JSON-able record."""
    from raster.testing import compare_images
    rec = {'name': case['name'], 'area': case['area'], 'feature': case['feature']}
    try:
        expected = load_png(case['png'])
    except Exception as e:  # missing or unreadable reference
        rec.update(status='error', reason='cannot read reference: %s' % (e,), seconds=0.0)
        return rec
    if init_error:
        rec.update(status='error', reason=init_error, seconds=0.0)
        return rec
    t0 = time.perf_counter()
    try:
        actual = renderer.render(case)
    except Exception as e:
        rec.update(status='error', seconds=round(time.perf_counter() - t0, 4),
                   reason=('%s: %s' % (type(e).__name__, e)).splitlines()[0][:300])
        _write_diff(cfg, case, expected, None, None, 'ERROR ' + rec['reason'])
        return rec
    rec['seconds'] = round(time.perf_counter() - t0, 4)
    if rec['seconds'] > cfg['timeout']:
        rec.update(status='timeout', reason='render took %.1f s > %g s'
                   % (rec['seconds'], cfg['timeout']))
        return rec
    try:
        cmp = compare_images(expected, actual)
    except Exception as e:
        rec.update(status='error', reason='unusable output: %s' % (e,))
        return rec
    rec.update(status='pass' if cmp.passed else 'fail', reason=cmp.reason,
               bad_pct=cmp.bad_pct, fine_bad_pct=cmp.fine_bad_pct, max_diff=cmp.max_diff)
    if not cmp.passed:
        _write_diff(cfg, case, expected, actual, cmp, 'FAIL ' + (cmp.reason or ''))
    return rec


def _write_diff(cfg, case, expected, actual, cmp, title):
    if not cfg.get('diffs'):
        return
    from PIL import Image, ImageDraw
    from raster.testing import diff_strip
    strip = diff_strip(expected, actual, cmp)
    head = 14
    img = np.full((strip.shape[0] + head, strip.shape[1], 3), 40, np.uint8)
    img[head:] = strip
    im = Image.fromarray(img)
    ImageDraw.Draw(im).text((2, 1), '%s  %s' % (case['name'], title), fill=(255, 255, 255))
    os.makedirs(cfg['diffs'], exist_ok=True)
    im.save(os.path.join(cfg['diffs'], case['name'].replace('/', '__') + '.png'))


def _worker(conn, cfg):
    if cfg.get('mem_limit_mb'):
        try:
            import resource
            lim = cfg['mem_limit_mb'] * 1024 * 1024
            resource.setrlimit(resource.RLIMIT_AS, (lim, lim))
        except (ImportError, ValueError, OSError):
            pass
    renderer, init_error = None, None
    try:
        renderer = RENDERERS[cfg['renderer']](cfg)
    except Exception as e:
        init_error = 'renderer unavailable: %s: %s' % (type(e).__name__, e)
    while True:
        try:
            msg = conn.recv()
        except (EOFError, OSError):
            return
        if msg is None:
            return
        idx, case = msg
        conn.send((idx, run_case(case, renderer, init_error, cfg)))


# ---------------------------------------------------------------------------
# Process pool with per-case timeouts
# ---------------------------------------------------------------------------

class _Slot:
    def __init__(self, ctx, cfg):
        parent, child = ctx.Pipe()
        self.proc = ctx.Process(target=_worker, args=(child, cfg), daemon=True)
        self.proc.start()
        child.close()
        self.conn = parent
        self.task = None
        self.started = 0.0

    def kill(self):
        try:
            self.proc.kill()
        except Exception:
            pass
        self.proc.join(5)
        self.conn.close()


def run_cases(cases, cfg, jobs=1, progress=None):
    """Run every case in ``jobs`` forked workers; returns the records in
    case order.  A worker exceeding ``cfg['timeout']`` (+1 s for loading and
    comparing) is killed and the case recorded as a timeout; a worker that
    dies records an error.  ``progress(done, total)`` is called after each."""
    ctx = mp.get_context('fork')
    slots = [_Slot(ctx, cfg) for _ in range(max(1, min(jobs, len(cases) or 1)))]
    todo = list(range(len(cases)))[::-1]
    results = [None] * len(cases)
    limit = cfg['timeout'] + 1.0
    done = 0

    def finish(slot, rec):
        nonlocal done
        results[slot.task] = rec
        slot.task = None
        done += 1
        if progress:
            progress(done, len(cases))

    try:
        while todo or any(s.task is not None for s in slots):
            for s in slots:
                if s.task is None and todo:
                    s.task = todo.pop()
                    s.started = time.perf_counter()
                    s.conn.send((s.task, cases[s.task]))
            busy = [s for s in slots if s.task is not None]
            now = time.perf_counter()
            wait = max(0.0, min(s.started + limit - now for s in busy))
            ready = mpconn.wait([s.conn for s in busy], timeout=wait)
            now = time.perf_counter()
            for i, s in enumerate(slots):
                if s.task is None:
                    continue
                case = cases[s.task]
                stub = {'name': case['name'], 'area': case['area'], 'feature': case['feature'],
                        'seconds': round(now - s.started, 4)}
                if s.conn in ready:
                    try:
                        _, rec = s.conn.recv()
                    except (EOFError, OSError):
                        s.proc.join(1)
                        stub.update(status='error', reason='worker crashed (exit code %s)'
                                    % s.proc.exitcode)
                        rec = stub
                        task = s.task
                        s.kill()
                        slots[i] = _Slot(ctx, cfg)
                        slots[i].task = task
                        s = slots[i]
                    finish(s, rec)
                elif now - s.started > limit:
                    stub.update(status='timeout', reason='no result after %g s (worker killed)'
                                % cfg['timeout'])
                    task = s.task
                    s.kill()
                    slots[i] = _Slot(ctx, cfg)
                    slots[i].task = task
                    finish(slots[i], stub)
    finally:
        for s in slots:
            try:
                s.conn.send(None)
            except Exception:
                pass
        for s in slots:
            s.proc.join(5)
            if s.proc.is_alive():
                s.kill()
    return results


# ---------------------------------------------------------------------------
# Summaries and the ratchet
# ---------------------------------------------------------------------------

def tally(records, key):
    """``{key value: Counter(status -> n)}`` for ``key`` 'area' or 'feature'."""
    out = {}
    for r in records:
        out.setdefault(r[key], Counter())[r['status']] += 1
    return dict(sorted(out.items()))


def pass_counts(records):
    """``{area: number of passing cases}`` (areas with no pass included)."""
    return {area: c['pass'] for area, c in tally(records, 'area').items()}


def load_ratchet(path):
    """The recorded ``{area: count}``; an absent file is an empty ratchet."""
    if not os.path.exists(path):
        return {}
    try:
        with open(path) as f:
            data = json.load(f)
        areas = data['areas']
        return {str(k): int(v) for k, v in areas.items()}
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as e:
        raise HarnessError('cannot read ratchet file %s: %s' % (path, e)) from None


def check_ratchet(counts, recorded):
    """Areas passing fewer cases than recorded: list of ``(area, now, recorded)``.
    An area missing from ``counts`` counts as 0 passes."""
    return [(area, counts.get(area, 0), need) for area, need in sorted(recorded.items())
            if counts.get(area, 0) < need]


def updated_ratchet(counts, recorded, force=False):
    """New ``{area: count}``: the maximum of recorded and current counts, or
    the current counts when ``force``."""
    if force:
        return dict(sorted(counts.items()))
    new = dict(recorded)
    for area, n in counts.items():
        new[area] = max(n, new.get(area, 0))
    return dict(sorted(new.items()))


def save_ratchet(path, areas, meta=None):
    data = {'comment': 'pass counts per area of the resvg suite; raise with '
                       'python -m raster_cli.conformance --update',
            'areas': areas, 'total': sum(areas.values())}
    if meta:
        data['measured'] = meta
    tmp = path + '.tmp'
    with open(tmp, 'w') as f:
        json.dump(data, f, indent=1, sort_keys=False)
        f.write('\n')
    os.replace(tmp, path)


def report(records, wall, jobs, out=None, features=True):
    out = out if out is not None else sys.stdout
    p = lambda *a: print(*a, file=out)
    def table(title, groups):
        p('%-38s %11s %7s %5s %6s %8s' % (title, 'pass/total', '%', 'fail', 'error', 'timeout'))
        for k, c in groups.items():
            n = sum(c[s] for s in STATUSES)
            p('%-38s %11s %6.1f%% %5d %6d %8d' % (k, '%d/%d' % (c['pass'], n),
                                                100.0 * c['pass'] / n if n else 0.0,
                                                c['fail'], c['error'], c['timeout']))
    if features:
        table('feature', tally(records, 'feature'))
        p('')
    table('area', tally(records, 'area'))
    tot = Counter(r['status'] for r in records)
    n = len(records)
    p('%-38s %11s %6.1f%%' % ('TOTAL', '%d/%d' % (tot['pass'], n),
                              100.0 * tot['pass'] / n if n else 0.0))
    render_s = sum(r.get('seconds') or 0.0 for r in records)
    p('wall time %.1f s with --jobs %d (render time summed %.1f s, mean %.0f ms)'
      % (wall, jobs, render_s, 1000.0 * render_s / max(n, 1)))


# ---------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------

def build_parser():
    ap = argparse.ArgumentParser(prog='python -m raster_cli.conformance',
                                 description='Render the resvg test suite and judge every case.')
    ap.add_argument('--suite', default=DEFAULT_SUITE,
                    help='suite directory holding tests/, fonts/, resources/ (default %(default)s)')
    ap.add_argument('--renderer', choices=sorted(RENDERERS), default='raster')
    ap.add_argument('--filter', action='append', default=[], metavar='PAT',
                    help='substring or glob on case names like "shapes/rect" (repeatable, OR-ed)')
    ap.add_argument('--jobs', type=int, default=1, help='worker processes (default 1)')
    ap.add_argument('--timeout', type=float, default=20.0, help='seconds per case (default 20)')
    ap.add_argument('--width', type=int, default=WIDTH, help=argparse.SUPPRESS)
    ap.add_argument('--diffs', metavar='DIR', help='write expected|diff|actual strips of failures')
    ap.add_argument('--json', metavar='OUT', help='write every case record as JSON')
    ap.add_argument('--ratchet', default=DEFAULT_RATCHET, help='ratchet file (default %(default)s)')
    g = ap.add_mutually_exclusive_group()
    g.add_argument('--check', action='store_true', help='exit 1 when an area is below its ratchet')
    g.add_argument('--update', action='store_true', help='raise the ratchet to the current counts')
    ap.add_argument('--force', action='store_true', help='with --update: also lower counts')
    ap.add_argument('--mem-limit-mb', type=int, default=4096,
                    help='address-space limit per worker (0: none; default %(default)s)')
    ap.add_argument('--no-features', action='store_true', help='print the per-area table only')
    add_version(ap)
    return ap


def main(argv=None):
    ap = build_parser()
    args = ap.parse_args(argv)
    if args.jobs < 1:
        ap.error('--jobs must be at least 1')
    if args.timeout <= 0:
        ap.error('--timeout must be positive')
    if args.force and not args.update:
        ap.error('--force only goes with --update')
    if (args.check or args.update) and args.filter:
        ap.error('--check/--update need the whole suite (no --filter)')
    prog = 'conformance'
    try:
        suite = os.path.abspath(args.suite)
        cases = discover(suite, args.filter)
        if not cases:
            raise HarnessError('no cases matched in %s' % suite)
        recorded = load_ratchet(args.ratchet) if (args.check or args.update) else {}
    except HarnessError as e:
        print('%s: error: %s' % (prog, e), file=sys.stderr)
        return 1
    cfg = {'renderer': args.renderer, 'width': args.width, 'timeout': args.timeout,
           'fonts_dir': os.path.join(suite, 'fonts'),
           'resources_dir': os.path.join(suite, 'resources'),
           'diffs': os.path.abspath(args.diffs) if args.diffs else None,
           'mem_limit_mb': args.mem_limit_mb}
    if args.renderer == 'raster':
        import raster.svg  # noqa: F401  (import once, before forking)

    tty = sys.stderr.isatty()

    def progress(done, total):
        if tty or done % 100 == 0 or done == total:
            print('\r[%d/%d] %.0f s' % (done, total, time.perf_counter() - t0),
                  end='' if tty and done < total else '\n', file=sys.stderr, flush=True)

    t0 = time.perf_counter()
    records = run_cases(cases, cfg, args.jobs, progress)
    wall = time.perf_counter() - t0
    print('renderer: %s, suite: %s, %d cases' % (args.renderer, suite, len(cases)))
    report(records, wall, args.jobs, features=not args.no_features)
    odd = [r for r in records if r['status'] in ('error', 'timeout')]
    if odd:
        print('\nerrors and timeouts (%d):' % len(odd))
        for r in odd[:60]:
            print('  %-58s %s: %s' % (r['name'], r['status'], r.get('reason')))
        if len(odd) > 60:
            print('  ... %d more' % (len(odd) - 60))
    counts = pass_counts(records)
    if args.json:
        with open(args.json, 'w') as f:
            json.dump({'renderer': args.renderer, 'suite': suite, 'jobs': args.jobs,
                       'wall_s': round(wall, 2), 'pass_counts': counts, 'cases': records},
                      f, indent=1)
    if args.update:
        new = updated_ratchet(counts, recorded, args.force)
        save_ratchet(args.ratchet, new, {'renderer': args.renderer,
                                         'wall_s': round(wall, 1), 'jobs': args.jobs})
        print('ratchet %s: %s' % (args.ratchet, ', '.join('%s=%d' % kv for kv in new.items())))
    if args.check:
        below = check_ratchet(counts, recorded)
        if below:
            for area, now, need in below:
                print('ratchet: %s passes %d, recorded %d' % (area, now, need), file=sys.stderr)
            return 1
        print('ratchet: every area at or above its recorded count')
    return 0


if __name__ == '__main__':
    sys.exit(main())
