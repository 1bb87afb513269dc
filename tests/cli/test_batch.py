"""rasterize at scale: many files (--out-dir, folders, --recursive,
--out-pattern, --skip-existing, --jobs, one line per failed file, the
summary, exit status), large PNG output in strips (--memory-budget, strips
over --jobs workers equal to the one-piece render) and XYZ map tiles."""

import json
import os

import numpy as np
import pytest
from PIL import Image

import raster
from raster_cli import rasterize
from test_cli import cli, one_error_line, png, write

DOC = ('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d">'
       '<defs><filter id="f" x="-20%%" y="-20%%" width="140%%" height="140%%">'
       '<feGaussianBlur stdDeviation="4"/></filter>'
       '<linearGradient id="g"><stop offset="0" stop-color="red"/>'
       '<stop offset="1" stop-color="blue"/></linearGradient></defs>'
       '<rect x="10%%" y="10%%" width="80%%" height="80%%" fill="url(#g)" filter="url(#f)"/>'
       '<circle cx="50%%" cy="50%%" r="%d" fill="%s" stroke="black" stroke-width="3"/></svg>')


def doc(w=60, h=40, r=12, colour='green'):
    return (DOC % (w, h, r, colour)).encode()


def folder(tmp_path, n=5):
    d = tmp_path / 'in'
    d.mkdir()
    for i in range(n):
        (d / ('icon%d.svg' % i)).write_bytes(doc(30 + 7 * i, 20 + 5 * i, 4 + i))
    return d


def summary(err):
    lines = [ln for ln in err.strip().splitlines() if 'files converted' in ln]
    assert len(lines) == 1, err
    return lines[0]


@pytest.mark.parametrize('jobs', ['1', '2'])
def test_a_folder_to_an_out_dir(tmp_path, capsys, jobs):
    d = folder(tmp_path)
    out = tmp_path / 'out'
    assert rasterize.main([str(d), '--out-dir', str(out), '--jobs', jobs]) == 0
    names = sorted(os.listdir(out))
    assert names == ['icon%d.png' % i for i in range(5)]
    for i in range(5):
        img = png(out / ('icon%d.png' % i))
        assert np.array_equal(img, raster.render(str(d / ('icon%d.svg' % i))))
    assert '5 of 5 files converted, 0 skipped, 0 failed' in summary(capsys.readouterr().err)


def test_one_bad_file_gets_its_line_and_the_rest_go_on(tmp_path, capsys):
    d = folder(tmp_path, 3)
    (d / 'broken.svg').write_bytes(b'<svg')
    (d / 'notes.txt').write_bytes(b'not an input')
    out = tmp_path / 'out'
    assert rasterize.main([str(d), '--out-dir', str(out), '--jobs', '2']) == 1
    err = capsys.readouterr().err
    errors = [ln for ln in err.splitlines() if ': error: ' in ln]
    assert len(errors) == 1 and 'broken.svg' in errors[0] and 'Traceback' not in err
    assert sorted(os.listdir(out)) == ['icon0.png', 'icon1.png', 'icon2.png']
    assert '3 of 4 files converted, 0 skipped, 1 failed' in summary(err)


def test_recursive_keeps_subfolders_and_the_pattern_names_files(tmp_path, capsys):
    d = folder(tmp_path, 2)
    sub = d / 'sub'
    sub.mkdir()
    (sub / 'deep.SVGZ').write_bytes(__import__('gzip').compress(doc()))
    out = tmp_path / 'out'
    assert rasterize.main([str(d), '--out-dir', str(out), '--jobs', '1']) == 0
    assert sorted(os.listdir(out)) == ['icon0.png', 'icon1.png']          # not recursive
    out2 = tmp_path / 'out2'
    assert rasterize.main([str(d), '--out-dir', str(out2), '--recursive',
                           '--out-pattern', 'x-{stem}.{ext}', '--format', 'webp']) == 0
    found = sorted(os.path.relpath(os.path.join(r, f), out2)
                   for r, _, fs in os.walk(out2) for f in fs)
    assert found == ['sub/x-deep.webp', 'x-icon0.webp', 'x-icon1.webp']
    assert Image.open(out2 / 'sub' / 'x-deep.webp').format == 'WEBP'


def test_skip_existing_and_a_folder_as_the_last_argument(tmp_path, capsys):
    d = folder(tmp_path, 3)
    out = tmp_path / 'out'
    out.mkdir()
    (out / 'icon1.png').write_bytes(b'keep me')
    files = [str(d / ('icon%d.svg' % i)) for i in range(3)]
    assert rasterize.main(files + [str(out), '--skip-existing']) == 0
    assert (out / 'icon1.png').read_bytes() == b'keep me'
    assert png(out / 'icon2.png').shape == (30, 44, 4)
    assert '2 of 3 files converted, 1 skipped, 0 failed' in summary(capsys.readouterr().err)


def test_usage_errors_of_batches(tmp_path, capsys):
    d = folder(tmp_path, 1)
    other = tmp_path / 'other'
    other.mkdir()
    (other / 'icon0.svg').write_bytes(doc())
    out = str(tmp_path / 'out')
    # two inputs writing one output
    assert rasterize.main([str(d), str(other), '--out-dir', out]) == 2
    assert 'would both write' in capsys.readouterr().err
    # many inputs and no output folder
    assert rasterize.main([str(d / 'icon0.svg')] * 3) == 2
    assert '--out-dir' in capsys.readouterr().err
    assert rasterize.main([str(d), '--out-dir', out, '--out-pattern', '{nope}.png']) == 2
    assert 'unknown field' in capsys.readouterr().err
    assert rasterize.main([str(d), '--out-dir', out, '--jobs', '0']) == 2
    capsys.readouterr()
    # a missing input: one line, status 1
    assert rasterize.main([str(tmp_path / 'missing.svg'), '--out-dir', out]) == 1
    assert one_error_line(capsys.readouterr().err, 'rasterize')


def test_the_command_converts_a_batch_in_worker_processes(tmp_path):
    # end to end: the installed command, two workers, no terminal (no bar)
    d = folder(tmp_path, 4)
    out = tmp_path / 'out'
    rc, stdout, err = cli('rasterize', str(d), '--out-dir', str(out), '--jobs', '2')
    assert rc == 0 and stdout == b'' and '\r' not in err
    assert summary(err).startswith('rasterize: 4 of 4 files converted')
    assert len(os.listdir(out)) == 4


# -- large images in strips ---------------------------------------------------------------

@pytest.mark.parametrize('jobs', ['1', '2'])
def test_png_in_strips_equals_the_one_piece_render(tmp_path, capsys, jobs):
    src = write(tmp_path, 'big.svg', doc(300, 200, 60, 'orange'))
    whole = raster.render(src, 700)
    out = tmp_path / 'strips.png'
    # 0.2 MB for pixels: strips of 16 rows (BYTES_PER_PIXEL 24 a pixel)
    assert rasterize.main([src, str(out), '--width', '700', '--memory-budget', '0.2',
                           '--jobs', jobs]) == 0
    assert np.array_equal(png(out), whole)


def test_strips_reach_outputs_beyond_max_pixels(tmp_path):
    # with the max_pixels budget lowered, an output above it still renders
    # as PNG in strips (and is refused for a format encoded in one piece)
    src = write(tmp_path, 'big.svg', doc(300, 200, 60, 'orange'))
    out = tmp_path / 'big.png'
    assert rasterize.main([src, str(out), '--width', '300', '--memory-budget', '0.1',
                           '--jobs', '1', '--max-pixels', '20000']) == 0
    assert np.array_equal(png(out), raster.render(src))
    assert rasterize.main([src, str(tmp_path / 'big.jpg'), '--width', '300',
                           '--max-pixels', '20000']) == 1
    assert not (tmp_path / 'big.jpg').exists()


def test_a_failed_strip_render_leaves_no_file(tmp_path, capsys, monkeypatch):
    src = write(tmp_path, 'big.svg', doc(300, 200, 60, 'orange'))
    out = tmp_path / 'big.png'
    calls = []

    def broken(job, span):
        calls.append(span)
        if len(calls) == 3:
            raise MemoryError
        return real(job, span)
    real = rasterize._compress_strip
    monkeypatch.setattr(rasterize, '_compress_strip', broken)
    assert rasterize.main([src, str(out), '--memory-budget', '0.1', '--jobs', '1']) == 1
    assert one_error_line(capsys.readouterr().err, 'rasterize')
    assert os.listdir(tmp_path) == ['big.svg']


needs_fork = pytest.mark.skipif(not hasattr(os, 'fork'), reason='strips in forked copies need fork')


@needs_fork
def test_an_image_over_parallel_pixels_is_drawn_in_forked_strips(tmp_path, monkeypatch):
    # within the memory budget and from PARALLEL_PIXELS on, one strip per
    # worker: this process draws the first, forked copies the others; the
    # pixels are the one-piece render's
    src = write(tmp_path, 'big.svg', doc(300, 200, 60, 'orange'))
    whole = raster.render(src, 600)
    monkeypatch.setattr(rasterize, 'PARALLEL_PIXELS', 10_000)
    spans, pids = [], set()
    real = rasterize._compress_strip

    def seen(job, span, keep=True):
        spans.append((span, keep))
        pids.add(os.getpid())
        return real(job, span, keep)
    monkeypatch.setattr(rasterize, '_compress_strip', seen)
    out = tmp_path / 'par.png'
    assert rasterize.main([src, str(out), '--width', '600', '--jobs', '3']) == 0
    assert np.array_equal(png(out), whole)
    # (a copy's calls are not seen here: only the first strip is; a
    # process drawing one strip keeps no outlines for others)
    assert len(spans) == 1 and spans[0][0][0] == 0 and pids == {os.getpid()}
    assert spans[0][1] is False
    with pytest.raises(ChildProcessError):
        os.waitpid(-1, os.WNOHANG)                 # every copy was reaped


@needs_fork
def test_a_small_image_forks_from_parallel_pixels_on(tmp_path, monkeypatch):
    # by default a 300 x 300 image (above PARALLEL_PIXELS, far below the
    # old million) is shared with a forked copy; one below it is not; where
    # the system cannot fork, no pool of fresh workers is started for it
    assert 90_000 >= rasterize.PARALLEL_PIXELS > 100 * 100
    assert rasterize.SPAWN_PARALLEL_PIXELS > 90_000
    src = write(tmp_path, 'mid.svg', doc(300, 300, 100, 'orange'))
    whole = raster.render(src, 300)
    forked, pooled = [], []
    real_forked, real_pool = rasterize._forked_strips, rasterize._pool

    def spy_forked(job, spans):
        forked.append(len(spans))
        return real_forked(job, spans)

    def spy_pool(*a, **k):
        pooled.append(1)
        return real_pool(*a, **k)
    monkeypatch.setattr(rasterize, '_forked_strips', spy_forked)
    monkeypatch.setattr(rasterize, '_pool', spy_pool)
    out = tmp_path / 'mid.png'
    assert rasterize.main([src, str(out), '--jobs', '2']) == 0
    assert np.array_equal(png(out), whole) and forked == [2]
    small = write(tmp_path, 'small.svg', doc(100, 100, 30, 'orange'))
    assert rasterize.main([small, str(tmp_path / 'small.png'), '--jobs', '2']) == 0
    assert forked == [2]
    monkeypatch.delattr(os, 'fork')
    assert rasterize.main([src, str(tmp_path / 'nofork.png'), '--jobs', '2']) == 0
    assert np.array_equal(png(tmp_path / 'nofork.png'), whole)
    assert forked == [2] and pooled == []


def _raise_in_copy(job, span, keep):
    raise raster.LimitError('strip budget spent')


def _die_in_copy(job, span, keep):
    import signal
    os.kill(os.getpid(), signal.SIGKILL)


@needs_fork
@pytest.mark.parametrize('failure, message', [(_raise_in_copy, 'strip budget spent'),
                                              (_die_in_copy, 'killed by signal 9')])
def test_a_failed_forked_strip_is_one_line_and_leaves_no_file(tmp_path, capsys, monkeypatch,
                                                               failure, message):
    # an exception in a forked copy is raised here; a copy that dies
    # without its strip is an error naming the signal
    src = write(tmp_path, 'big.svg', doc(300, 200, 60, 'orange'))
    monkeypatch.setattr(rasterize, 'PARALLEL_PIXELS', 10_000)
    parent = os.getpid()
    real = rasterize._compress_strip

    def broken(job, span, keep=True):
        if os.getpid() != parent:
            failure(job, span, keep)
        return real(job, span, keep)
    monkeypatch.setattr(rasterize, '_compress_strip', broken)
    out = tmp_path / 'par.png'
    assert rasterize.main([src, str(out), '--width', '600', '--jobs', '2']) == 1
    err = capsys.readouterr().err
    assert one_error_line(err, 'rasterize') and message in err
    assert os.listdir(tmp_path) == ['big.svg']
    with pytest.raises(ChildProcessError):
        os.waitpid(-1, os.WNOHANG)


# -- map tiles ------------------------------------------------------------------------------

def test_xyz_tiles(tmp_path, capsys):
    src = write(tmp_path, 'map.svg', doc(600, 300, 80, 'teal'))
    d = tmp_path / 'tiles'
    assert rasterize.main([src, '--tiles', str(d), '--jobs', '2']) == 0
    meta = json.loads((d / 'tiles.json').read_text())
    assert meta['tile_size'] == 256 and (meta['minzoom'], meta['maxzoom']) == (0, 2)
    assert meta['bounds'] == [0.0, 0.0, 600.0, 300.0]
    for lv in meta['levels']:
        z = lv['zoom']
        assert lv['width'] == 256 * 2 ** z and lv['height'] == 128 * 2 ** z
        whole = raster.render(src, lv['width'])
        got = sorted(os.listdir(d / str(z)))
        assert got == [str(x) for x in range(lv['columns'])]
        for x in range(lv['columns']):
            assert sorted(os.listdir(d / str(z) / str(x))) == sorted(
                '%d.png' % y for y in range(lv['rows']))
            for y in range(lv['rows']):
                tile = png(d / str(z) / str(x) / ('%d.png' % y))
                assert tile.shape == (256, 256, 4)
                part = whole[256 * y:256 * (y + 1), 256 * x:256 * (x + 1)]
                assert np.array_equal(tile[:part.shape[0], :part.shape[1]], part)
                assert not tile[part.shape[0]:].any()          # padding is transparent
    assert '11 tiles, zoom 0-2' in capsys.readouterr().err    # 1 + 2 + 8


SPARSE = ('<svg xmlns="http://www.w3.org/2000/svg" width="1000" height="500">'
          '<circle cx="860" cy="90" r="40" fill="navy"/>'
          '<rect x="100" y="380" width="30" height="20" fill="orange" opacity="0.5"/></svg>')


@pytest.mark.parametrize('jobs', ['1', '2'])
def test_xyz_tiles_leave_out_empty_tiles(tmp_path, capsys, jobs):
    # a sparse map: only tiles with a drawn pixel are written, as web map
    # tile generators do (a client draws a missing tile blank); tiles.json
    # says so and counts them; every omitted tile is blank in the render
    src = write(tmp_path, 'sparse.svg', SPARSE.encode())
    d = tmp_path / 'tiles'
    assert rasterize.main([src, '--tiles', str(d), '--max-zoom', '3', '--jobs', jobs]) == 0
    meta = json.loads((d / 'tiles.json').read_text())
    assert meta['empty_tiles'] == 'omitted'
    total = sum(lv['columns'] * lv['rows'] for lv in meta['levels'])
    assert meta['tiles_written'] + meta['tiles_omitted'] == total
    assert meta['tiles_omitted'] > meta['tiles_written'] > 0
    written = 0
    for lv in meta['levels']:
        z = lv['zoom']
        whole = raster.render(src, lv['width'])
        for x in range(lv['columns']):
            for y in range(lv['rows']):
                part = whole[256 * y:256 * (y + 1), 256 * x:256 * (x + 1)]
                f = d / str(z) / str(x) / ('%d.png' % y)
                assert f.exists() == bool(part[..., 3].any()), (z, x, y)
                if f.exists():
                    written += 1
                    assert np.array_equal(png(f)[:part.shape[0], :part.shape[1]], part)
    assert written == meta['tiles_written']
    err = capsys.readouterr().err
    assert '%d tiles' % written in err and '%d empty tiles omitted' % meta['tiles_omitted'] in err


def test_xyz_tiles_all_tiles_writes_the_empty_ones(tmp_path, capsys):
    src = write(tmp_path, 'sparse.svg', SPARSE.encode())
    d = tmp_path / 'tiles'
    assert rasterize.main([src, '--tiles', str(d), '--max-zoom', '2', '--all-tiles']) == 0
    meta = json.loads((d / 'tiles.json').read_text())
    assert meta['empty_tiles'] == 'written' and meta['tiles_omitted'] == 0
    total = sum(lv['columns'] * lv['rows'] for lv in meta['levels'])
    assert meta['tiles_written'] == total
    blank = png(d / '2' / '0' / '0.png')
    assert blank.shape == (256, 256, 4) and not blank.any()


def test_tiles_usage_errors(tmp_path, capsys):
    src = write(tmp_path, 'map.svg', doc())
    d = str(tmp_path / 't')
    assert rasterize.main([src, src, '--tiles', d]) == 2
    assert rasterize.main([src, '--tiles', d, '--width', '100']) == 2
    assert rasterize.main([src, '--tiles', d, '--min-zoom', '3', '--max-zoom', '1']) == 2
    assert rasterize.main([src, '--tiles', d, '--max-zoom', '30']) == 1
    assert not os.path.exists(d)


def test_the_file_does_not_depend_on_the_number_of_workers(tmp_path):
    src = write(tmp_path, 'big.svg', doc(300, 200, 60, 'orange'))
    outs = []
    for jobs in ('1', '2'):
        out = tmp_path / ('j%s.png' % jobs)
        assert rasterize.main([src, str(out), '--width', '500', '--memory-budget', '0.5',
                               '--jobs', jobs]) == 0
        outs.append(out.read_bytes())
    assert outs[0] == outs[1]


def test_batch_chunks_cover_every_file_and_keep_workers_busy():
    # at least CHUNKS_PER_WORKER hand-overs per worker, never an empty one
    for files in (1, 2, 31, 32, 33, 200, 1000):
        for jobs in (1, 2, 3, 8):
            k = rasterize.batch_chunk(files, jobs)
            assert k >= 1
            assert k == 1 or -(-files // k) >= jobs * rasterize.CHUNKS_PER_WORKER


def test_a_chunked_batch_reports_a_bad_file_inside_a_chunk(tmp_path, capsys, monkeypatch):
    # files go to the workers several at a time: a bad file in the middle
    # of a hand-over gets its line and the files after it are converted
    monkeypatch.setattr(rasterize, 'CHUNKS_PER_WORKER', 1)
    d = folder(tmp_path, 7)
    (d / 'icon3.svg').write_bytes(b'<svg')
    assert rasterize.batch_chunk(7, 2) == 3
    out = tmp_path / 'out'
    assert rasterize.main([str(d), '--out-dir', str(out), '--jobs', '2']) == 1
    err = capsys.readouterr().err
    assert sorted(os.listdir(out)) == ['icon%d.png' % i for i in range(7) if i != 3]
    assert len([ln for ln in err.splitlines() if 'error' in ln and 'icon3.svg' in ln]) == 1
    assert '6 of 7 files converted, 0 skipped, 1 failed' in summary(err)


# -- workers started afresh (no fork) -------------------------------------------------------

NO_FORK = '''
import multiprocessing, os, sys
del os.fork                                     # as on a system that cannot fork
multiprocessing.get_all_start_methods = lambda: ['spawn']
multiprocessing.set_start_method('spawn')      # (Linux's default is fork)
from raster_cli.rasterize import main
sys.exit(main(sys.argv[1:]))
'''


def _without_fork(*argv):
    import subprocess
    import sys
    return subprocess.run([sys.executable, '-c', NO_FORK] + [str(a) for a in argv],
                          capture_output=True, text=True, timeout=300)


def test_workers_started_afresh_draw_strips_batches_and_tiles(tmp_path):
    # where the system cannot fork, the pools' workers are new processes:
    # what a forked copy inherits (the parsed document, the batch's options,
    # the limits) reaches them through the pool's initializer, so the
    # outputs are the forked workers' (and the one-process render's)
    src = write(tmp_path, 'big.svg', doc(500, 400, 90, 'orange'))
    out = tmp_path / 'strips.png'
    r = _without_fork('--width', 1200, '--jobs', 2, src, out)
    assert r.returncode == 0, r.stderr
    assert np.array_equal(png(out), raster.render(src, 1200))
    d = folder(tmp_path, 3)
    r = _without_fork(d, '--out-dir', tmp_path / 'many', '--jobs', 2)
    assert r.returncode == 0 and '3 of 3 files converted' in r.stderr, r.stderr
    for i in range(3):
        assert np.array_equal(png(tmp_path / 'many' / ('icon%d.png' % i)),
                              raster.render(str(d / ('icon%d.svg' % i))))
    tiles = tmp_path / 'tiles'
    r = _without_fork(src, '--tiles', tiles, '--max-zoom', 1, '--jobs', 2)
    assert r.returncode == 0, r.stderr
    whole = raster.render(src, 512)
    tile = png(tiles / '1' / '1' / '0.png')
    assert np.array_equal(tile, whole[:256, 256:512])
    # the limits of the command line hold in those workers too, and their
    # warnings are the command's one-line ones: the blurred group is left
    # out of every strip, as forked workers leave it out
    r = _without_fork('--width', 1200, '--jobs', 2, '--max-pixel-work', 1, src,
                      tmp_path / 'limited.png')
    assert r.returncode == 0, r.stderr
    lines = r.stderr.strip().splitlines()
    assert lines and all(ln.startswith('rasterize: warning: element not drawn: a group layer')
                         for ln in lines), r.stderr
    assert rasterize.main(['--width', '1200', '--jobs', '2', '--max-pixel-work', '1', src,
                           str(tmp_path / 'forked.png')]) == 0
    limited = png(tmp_path / 'limited.png')
    assert np.array_equal(limited, png(tmp_path / 'forked.png'))
    assert not np.array_equal(limited, png(out))
