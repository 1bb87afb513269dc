"""The command-line tools: rasterize, svg-flatten, svg-bbox.

Each runs in-process (``main(argv)``) for most checks and as a subprocess
for the console-script wiring, stdin/stdout and the no-traceback rule.
"""

import csv
import gzip
import io
import json
import os
import subprocess
import sys
import sysconfig

import numpy as np
import pytest
from PIL import Image

from raster_cli import rasterize, svg_bbox, svg_flatten

SQUARE = (b'<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10">'
          b'<rect id="r" x="2" y="2" width="6" height="6" fill="red"/>'
          b'<g id="g" transform="translate(10 0)"><rect id="b" x="2" y="2" width="4" height="4" '
          b'fill="blue"/></g></svg>')
CIRCLE = (b'<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">'
          b'<circle id="c" cx="50" cy="50" r="10" fill="none" stroke="black" stroke-width="4"/>'
          b'</svg>')
VIEWBOX = (b'<svg xmlns="http://www.w3.org/2000/svg" width="200" height="100" viewBox="0 0 20 10">'
           b'<rect id="r" x="1" y="1" width="4" height="2" fill="#00ff00" stroke="#000" '
           b'stroke-width="0.5"/></svg>')


def write(tmp_path, name, data):
    p = tmp_path / name
    p.write_bytes(data)
    return str(p)


def png(path):
    return np.asarray(Image.open(path).convert('RGBA'))


def script(name):
    """Path of console script ``name`` installed beside this interpreter (the
    environment the tests run in, activated or not; never a copy on PATH)."""
    path = os.path.join(sysconfig.get_path('scripts'), name)
    assert os.path.exists(path), '%s is not installed in %s' % (name, sys.prefix)
    return path


def cli(name, *args, stdin=None):
    """Run a console script of this environment as a subprocess:
    (returncode, stdout bytes, stderr str)."""
    p = subprocess.run([script(name)] + list(args), input=stdin, capture_output=True,
                       timeout=60)
    return p.returncode, p.stdout, p.stderr.decode('utf-8', 'replace')


def one_error_line(err, prog):
    lines = err.strip().splitlines()
    return len(lines) == 1 and lines[0].startswith(prog + ': error: ') and 'Traceback' not in err


# -- builder-independent parts ------------------------------------------------------------

def _circle_tree(with_fill=False, transform=None):
    from raster.tree import Fill, Group, PathNode, SolidPaint, Stroke, Tree
    from raster.geometry.transform import Affine
    from _geometry import kappa_circle
    black = SolidPaint((0, 0, 0, 1))
    node = PathNode(id='c', path=kappa_circle(50.0, 50.0, 10.0), stroke=Stroke.of(black, width=4),
                    fill=Fill(black) if with_fill else None)
    root = Group(transform=transform or Affine(), children=[node])
    return Tree(100, 100, root, ids={'c': node})


def test_boxes_on_resolved_tree():
    """Circle r = 10 at (50, 50), stroke width 4: fill box [40, 40, 60, 60],
    stroke box [38, 38, 62, 62]; a root scale (viewBox) does not change user
    units."""
    from raster.geometry.transform import Affine
    for t in (None, Affine.scale(3)):
        res = svg_bbox.boxes(_circle_tree(transform=t))
        assert res['document'] == pytest.approx([40, 40, 60, 60], abs=1e-6)
        res = svg_bbox.boxes(_circle_tree(transform=t), with_stroke=True)
        assert res['elements']['c'] == pytest.approx([38, 38, 62, 62], abs=1e-3)


def test_collect_on_resolved_tree():
    from raster.geometry.transform import Affine
    (s,) = svg_flatten.collect(_circle_tree(with_fill=True, transform=Affine.scale(2)), 0.05)
    assert s['id'] == 'c' and s['fill'] == '#000000' and s['stroke_width'] == 4
    pts = np.array(s['polylines'][0]['points'])
    assert np.abs(np.hypot(*(pts - 50).T) - 10).max() < 0.003
    (s,) = svg_flatten.collect(_circle_tree(transform=Affine.scale(2)), 0.05, pixels=True)
    pts = np.array(s['polylines'][0]['points'])
    assert np.abs(np.hypot(*(pts - 100).T) - 20).max() < 0.006 and s['stroke_width'] == 8
    fill_shape, outline = svg_flatten.collect(_circle_tree(with_fill=True), 0.05,
                                              outline_strokes=True)
    assert fill_shape['stroke'] is None and outline['fill'] == '#000000'
    assert outline['fill_rule'] == 'nonzero'


def test_missing_input_and_bad_gzip_exit_1(tmp_path, capsys):
    for main, prog in ((rasterize.main, 'rasterize'), (svg_bbox.main, 'svg-bbox'),
                       (svg_flatten.main, 'svg-flatten')):
        argv = [str(tmp_path / 'missing.svg')] + ([str(tmp_path / 'o.png')] if prog == 'rasterize'
                                                   else [])
        assert main(argv) == 1
        assert one_error_line(capsys.readouterr().err, prog)
    bad = write(tmp_path, 'bad.svgz', b'\x1f\x8b\x08\x00garbage')
    assert rasterize.main([bad, str(tmp_path / 'o.png')]) == 1
    err = capsys.readouterr().err
    assert one_error_line(err, 'rasterize') and 'gzip' in err
    assert not (tmp_path / 'o.png').exists()


@pytest.mark.parametrize('argv', [[], ['only-one'], ['a', 'b', '--width', 'x'],
                                  ['a', 'b', '--zoom', '2', '--width', '3'], ['a', 'b', '--bogus']])
def test_rasterize_usage_errors_exit_2(argv, capsys):
    assert rasterize.main(argv) == 2
    assert 'usage:' in capsys.readouterr().err


@pytest.mark.parametrize('main,argv', [(svg_flatten.main, ['a.svg', '--format', 'pdf']),
                                       (svg_flatten.main, []),
                                       (svg_bbox.main, ['a.svg', '--what'])])
def test_other_usage_errors_exit_2(main, argv, capsys):
    assert main(argv) == 2
    assert 'usage:' in capsys.readouterr().err


def test_console_scripts_installed():
    rc, so, se = cli('rasterize', '--help')
    assert rc == 0 and b'usage: rasterize' in so
    rc, so, se = cli('svg-bbox', '--zzz')
    assert rc == 2 and 'Traceback' not in se


# -- rasterize ---------------------------------------------------------------------------

def test_rasterize_natural_size_and_pixels(tmp_path):
    src = write(tmp_path, 'a.svg', SQUARE)
    out = str(tmp_path / 'a.png')
    assert rasterize.main([src, out]) == 0
    img = png(out)
    assert img.shape == (10, 20, 4)
    assert img[5, 5].tolist() == [255, 0, 0, 255]
    assert img[4, 14].tolist() == [0, 0, 255, 255]
    assert img[0, 0].tolist() == [0, 0, 0, 0]
    assert [f for f in os.listdir(tmp_path) if f.endswith('.tmp')] == []


@pytest.mark.parametrize('opts,size', [(['--width', '40'], (20, 40)), (['--height', '5'], (5, 10)),
                                       (['--width', '30', '--height', '30'], (30, 30)),
                                       (['--zoom', '3'], (30, 60))])
def test_rasterize_sizes(tmp_path, opts, size):
    src = write(tmp_path, 'a.svg', SQUARE)
    out = str(tmp_path / 'a.png')
    assert rasterize.main([src, out] + opts) == 0
    assert png(out).shape[:2] == size


def test_rasterize_background_and_id(tmp_path):
    src = write(tmp_path, 'a.svg', SQUARE)
    out = str(tmp_path / 'a.png')
    assert rasterize.main([src, out, '--background', 'rgb(0, 255, 0)', '--id', 'b',
                           '--id-page']) == 0
    img = png(out)
    assert img[0, 0].tolist() == [0, 255, 0, 255]
    assert img[5, 5].tolist() == [0, 255, 0, 255]          # red rect not rendered
    assert img[4, 14].tolist() == [0, 0, 255, 255]         # with its group's translate
    # without --id-page: the 4 x 4 blue square alone
    assert rasterize.main([src, out, '--background', 'rgb(0, 255, 0)', '--id', 'b']) == 0
    img = png(out)
    assert img.shape == (4, 4, 4) and (img == (0, 0, 255, 255)).all()


def test_rasterize_svgz_and_dpi(tmp_path):
    doc = (b'<svg xmlns="http://www.w3.org/2000/svg" width="1in" height="0.5in">'
           b'<rect width="100%" height="100%" fill="black"/></svg>')
    src = write(tmp_path, 'a.svgz', gzip.compress(doc))
    out = str(tmp_path / 'a.png')
    assert rasterize.main([src, out]) == 0
    assert png(out).shape[:2] == (48, 96)
    assert rasterize.main([src, out, '--dpi', '192']) == 0
    assert png(out).shape[:2] == (96, 192)


def test_rasterize_stdin_stdout_subprocess():
    rc, so, se = cli('rasterize', '-', '-', '--width', '40', stdin=SQUARE)
    assert rc == 0, se
    img = np.asarray(Image.open(io.BytesIO(so)).convert('RGBA'))
    assert img.shape == (20, 40, 4) and img[10, 10].tolist() == [255, 0, 0, 255]


BAD_INPUTS = {
    'missing': None,
    'not-xml': b'<svg xmlns="http://www.w3.org/2000/svg" <<<',
    'not-svg': b'<html xmlns="http://www.w3.org/1999/xhtml"><body/></html>',
    'zero-size': b'<svg xmlns="http://www.w3.org/2000/svg" width="0" height="10"/>',
    'negative-size': b'<svg xmlns="http://www.w3.org/2000/svg" width="-5" height="10"/>',
    'bad-gzip': b'\x1f\x8b\x08\x00garbage',
}


@pytest.mark.parametrize('kind', sorted(BAD_INPUTS))
def test_rasterize_bad_input_exit_1_no_output(tmp_path, capsys, kind):
    data = BAD_INPUTS[kind]
    src = str(tmp_path / 'in.svg') if data is None else write(tmp_path, 'in.svg', data)
    out = tmp_path / 'out.png'
    assert rasterize.main([src, str(out)]) == 1
    err = capsys.readouterr().err
    assert one_error_line(err, 'rasterize'), err
    assert not out.exists()
    assert os.listdir(tmp_path) == ([] if data is None else ['in.svg'])


@pytest.mark.parametrize('opts', [['--width', '0'], ['--width', '-3'], ['--zoom', '0'],
                                  ['--width', '200000'], ['--width', '70000', '--height', '70000'],
                                  ['--width', '20000', '--height', '20000', '--format', 'jpeg'],
                                  ['--background', 'notacolour'], ['--id', 'nope'],
                                  ['--dpi', '0']])
def test_rasterize_bad_options_exit_1(tmp_path, capsys, opts):
    src = write(tmp_path, 'a.svg', SQUARE)
    out = tmp_path / 'a.png'
    assert rasterize.main([src, str(out)] + opts) == 1
    assert one_error_line(capsys.readouterr().err, 'rasterize')
    assert not out.exists()


def test_rasterize_failure_keeps_existing_output(tmp_path):
    out = tmp_path / 'a.png'
    out.write_bytes(b'previous')
    src = write(tmp_path, 'bad.svg', b'<nope')
    assert rasterize.main([src, str(out)]) == 1
    assert out.read_bytes() == b'previous'


def test_rasterize_unwritable_output(tmp_path, capsys):
    src = write(tmp_path, 'a.svg', SQUARE)
    assert rasterize.main([src, str(tmp_path / 'no' / 'dir' / 'a.png')]) == 1
    assert one_error_line(capsys.readouterr().err, 'rasterize')


def test_subprocess_errors_have_no_traceback(tmp_path):
    rc, so, se = cli('rasterize', str(tmp_path / 'missing.svg'), str(tmp_path / 'o.png'))
    assert rc == 1 and one_error_line(se, 'rasterize')
    rc, so, se = cli('svg-bbox', '-', stdin=b'<svg')
    assert rc == 1 and one_error_line(se, 'svg-bbox')
    rc, so, se = cli('svg-flatten', '--format', 'pdf', 'x.svg')
    assert rc == 2 and 'Traceback' not in se


# -- svg-flatten ----------------------------------------------------------------------------

def test_flatten_json_user_units(tmp_path, capsys):
    src = write(tmp_path, 'v.svg', VIEWBOX)
    assert svg_flatten.main([src, '--format', 'json']) == 0
    shapes = json.loads(capsys.readouterr().out)
    assert len(shapes) == 1
    s = shapes[0]
    assert s['id'] == 'r' and s['fill'] == '#00ff00' and s['stroke'] == '#000000'
    assert s['stroke_width'] == pytest.approx(0.5)
    (pl,) = s['polylines']
    assert pl['closed'] is True
    pts = np.array(pl['points'])
    assert pts.min(0).tolist() == [1, 1] and pts.max(0).tolist() == [5, 3]


def test_flatten_pixels_scale(tmp_path, capsys):
    src = write(tmp_path, 'v.svg', VIEWBOX)
    assert svg_flatten.main([src, '--format', 'json', '--pixels']) == 0
    (s,) = json.loads(capsys.readouterr().out)
    pts = np.array(s['polylines'][0]['points'])
    assert pts.min(0).tolist() == [10, 10] and pts.max(0).tolist() == [50, 30]
    assert s['stroke_width'] == pytest.approx(5.0)


@pytest.mark.parametrize('tol', [1.0, 0.1, 0.01])
def test_flatten_tolerance_honoured_on_circle(tmp_path, capsys, tol):
    """Every vertex lies on the circle r = 10 (the four-cubic circle deviates
    from a true circle by < 0.003) and every chord midpoint within tol."""
    src = write(tmp_path, 'c.svg', CIRCLE)
    assert svg_flatten.main([src, '--format', 'json', '--tolerance', str(tol)]) == 0
    (s,) = json.loads(capsys.readouterr().out)
    pts = np.array(s['polylines'][0]['points'])
    r = np.hypot(pts[:, 0] - 50, pts[:, 1] - 50)
    assert np.all(np.abs(r - 10) < 0.003)
    mids = (pts + np.roll(pts, -1, 0)) / 2
    rm = np.hypot(mids[:, 0] - 50, mids[:, 1] - 50)
    assert np.all(10 - rm <= tol + 0.003)


def test_flatten_csv_and_svg_outputs_parse(tmp_path):
    src = write(tmp_path, 'a.svg', SQUARE)
    out_csv = str(tmp_path / 'o.csv')
    out_svg = str(tmp_path / 'o.svg')
    assert svg_flatten.main([src, '--format', 'csv', '-o', out_csv]) == 0
    rows = list(csv.DictReader(open(out_csv)))
    assert set(r['id'] for r in rows) == {'r', 'b'}
    xs = [float(r['x']) for r in rows if r['id'] == 'b']
    assert min(xs) == 12 and max(xs) == 16
    assert svg_flatten.main([src, '-o', out_svg]) == 0
    # the flattened SVG renders like the original
    a = str(tmp_path / 'a.png')
    b = str(tmp_path / 'b.png')
    assert rasterize.main([src, a]) == 0 and rasterize.main([out_svg, b]) == 0
    assert np.array_equal(png(a), png(b))


def test_flatten_outline_strokes(tmp_path, capsys):
    src = write(tmp_path, 'c.svg', CIRCLE)
    assert svg_flatten.main([src, '--format', 'json', '--outline-strokes']) == 0
    shapes = json.loads(capsys.readouterr().out)
    assert len(shapes) == 1
    s = shapes[0]
    assert s['stroke'] is None and s['fill'] == '#000000'
    pts = np.concatenate([np.array(p['points']) for p in s['polylines']])
    r = np.hypot(pts[:, 0] - 50, pts[:, 1] - 50)
    assert r.min() >= 8 - 0.26 and r.max() <= 12 + 0.26


def test_flatten_errors(tmp_path, capsys):
    assert svg_flatten.main([str(tmp_path / 'missing.svg')]) == 1
    assert one_error_line(capsys.readouterr().err, 'svg-flatten')
    src = write(tmp_path, 'a.svg', SQUARE)
    assert svg_flatten.main([src, '--tolerance', '0']) == 1
    assert one_error_line(capsys.readouterr().err, 'svg-flatten')


# -- svg-bbox ----------------------------------------------------------------------------------

def test_bbox_circle_fill_and_stroke(tmp_path, capsys):
    src = write(tmp_path, 'c.svg', CIRCLE)
    assert svg_bbox.main([src]) == 0
    res = json.loads(capsys.readouterr().out)
    assert res['units'] == 'user'
    assert res['document'] == pytest.approx([40, 40, 60, 60], abs=1e-9)
    assert res['elements']['c'] == pytest.approx([40, 40, 60, 60], abs=1e-9)
    assert svg_bbox.main([src, '--stroke']) == 0
    res = json.loads(capsys.readouterr().out)
    assert res['document'] == pytest.approx([38, 38, 62, 62], abs=1e-3)


def test_bbox_viewbox_user_units_and_groups(tmp_path, capsys):
    src = write(tmp_path, 'a.svg', SQUARE)
    assert svg_bbox.main([src]) == 0
    res = json.loads(capsys.readouterr().out)
    assert res['document'] == [2, 2, 16, 8]
    assert res['elements']['g'] == [12, 2, 16, 6]
    assert res['elements']['r'] == [2, 2, 8, 8]
    src = write(tmp_path, 'v.svg', VIEWBOX)
    assert svg_bbox.main([src, '--id', 'r', '--stroke']) == 0
    res = json.loads(capsys.readouterr().out)
    assert list(res['elements']) == ['r']
    assert res['elements']['r'] == pytest.approx([0.75, 0.75, 5.25, 3.25], abs=1e-3)


def test_bbox_unknown_id(tmp_path, capsys):
    src = write(tmp_path, 'a.svg', SQUARE)
    assert svg_bbox.main([src, '--id', 'zz']) == 1
    assert one_error_line(capsys.readouterr().err, 'svg-bbox')


def test_bbox_stdin_subprocess():
    rc, so, se = cli('svg-bbox', '-', stdin=CIRCLE)
    assert rc == 0, se
    assert json.loads(so)['document'] == pytest.approx([40, 40, 60, 60])


def test_output_file_gets_the_usual_permissions(tmp_path):
    """The atomic write (temp file + rename) must not leave mkstemp's 0600."""
    import os
    import stat
    from raster_cli import rasterize as rz
    src = tmp_path / 'in.svg'
    src.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="4" height="4"/>')
    out = tmp_path / 'out.png'
    old = os.umask(0o022)
    try:
        assert rz.main([str(src), str(out)]) in (0, None)
    finally:
        os.umask(old)
    assert stat.S_IMODE(out.stat().st_mode) == 0o644


def test_rasterize_skips_an_element_beyond_a_limit_with_a_one_line_warning(tmp_path):
    src = tmp_path / 'dashes.svg'
    src.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">'
                   '<rect width="50" height="50" fill="green"/>'
                   # (5 million dashes where the canvas sees the line: over
                   # the dash budget of 4 million)
                   '<path d="M 0 50 L 1e8 50" stroke="red" stroke-dasharray="1e-5 1e-5"/>'
                   '</svg>')
    out = tmp_path / 'out.png'
    rc, _, err = cli('rasterize', str(src), str(out))
    assert rc == 0 and out.exists()
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith('rasterize: warning: element not drawn')
    img = np.asarray(Image.open(out))
    assert img[25, 25].tolist() == [0, 128, 0, 255]


# -- output onto special files -------------------------------------------------------------

def _reader(path, out):
    """Thread body: read everything from ``path`` into ``out`` (a list)."""
    with open(path, 'rb') as f:
        out.append(f.read())


def test_output_to_a_fifo_is_written_into_the_fifo(tmp_path):
    """``mkfifo p; rasterize in.svg p``: the reader gets the PNG and the FIFO
    stays a FIFO (an atomic rename would have replaced it by a file)."""
    import stat
    import threading
    src = write(tmp_path, 'in.svg', SQUARE)
    fifo = tmp_path / 'p'
    os.mkfifo(fifo)
    got = []
    t = threading.Thread(target=_reader, args=(str(fifo), got))
    t.start()
    rc = rasterize.main([src, str(fifo)])
    t.join(30)
    assert rc == 0
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert got and got[0][:8] == b'\x89PNG\r\n\x1a\n'
    assert np.asarray(Image.open(io.BytesIO(got[0]))).shape == (10, 20, 4)
    assert sorted(p.name for p in tmp_path.iterdir()) == ['in.svg', 'p']


def test_output_to_a_character_device_keeps_the_device(tmp_path):
    """A character device of the test's own (the slave side of a new
    pseudo-terminal, or a node made with mknod when allowed) is written
    directly, never replaced by a regular file."""
    import stat
    import threading
    src = write(tmp_path, 'in.svg', SQUARE)
    master, slave = os.openpty()
    try:
        import tty
        tty.setraw(slave)                # bytes pass unchanged
        dev = os.ttyname(slave)
        got = bytearray()

        def drain():
            while True:
                try:
                    chunk = os.read(master, 65536)
                except OSError:
                    return
                if not chunk:
                    return
                got.extend(chunk)
        t = threading.Thread(target=drain, daemon=True)
        t.start()
        assert stat.S_ISCHR(os.stat(dev).st_mode)
        assert svg_bbox.main([src, '-o', dev]) == 0
        assert stat.S_ISCHR(os.stat(dev).st_mode)
        import time
        deadline = time.time() + 10
        result = None
        while result is None and time.time() < deadline:
            try:
                result = json.loads(bytes(got).decode())
            except ValueError:
                time.sleep(0.05)
        want = json.loads(subprocess.run([script('svg-bbox'), src], capture_output=True,
                                         timeout=60).stdout)
        assert result == want
    finally:
        os.close(slave)
        os.close(master)


def test_output_through_a_link_to_a_device_keeps_the_device(tmp_path):
    """A symbolic link to a FIFO is followed and written, not replaced."""
    import stat
    import threading
    src = write(tmp_path, 'in.svg', SQUARE)
    fifo = tmp_path / 'p'
    os.mkfifo(fifo)
    link = tmp_path / 'link.png'
    link.symlink_to(fifo)
    got = []
    t = threading.Thread(target=_reader, args=(str(fifo), got))
    t.start()
    assert rasterize.main([src, str(link)]) == 0
    t.join(30)
    assert link.is_symlink() and stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert got and got[0][:4] == b'\x89PNG'


def test_output_through_a_link_to_a_file_replaces_the_file(tmp_path):
    src = write(tmp_path, 'in.svg', SQUARE)
    real = tmp_path / 'real.png'
    real.write_bytes(b'old')
    link = tmp_path / 'link.png'
    link.symlink_to(real)
    assert rasterize.main([src, str(link)]) == 0
    assert link.is_symlink() and real.read_bytes()[:4] == b'\x89PNG'


def test_output_to_a_directory_converts_into_it(tmp_path, capsys):
    # a folder as the last argument is the output folder of a batch (it
    # was "Is a directory")
    src = write(tmp_path, 'in.svg', SQUARE)
    d = tmp_path / 'dir'
    d.mkdir()
    assert rasterize.main([src, str(d)]) == 0
    assert [p.name for p in d.iterdir()] == ['in.png']
    assert 'rasterize: 1 of 1 files converted' in capsys.readouterr().err


# -- --id crops to the element ---------------------------------------------------------------

SPRITES = (b'<svg xmlns="http://www.w3.org/2000/svg" width="200" height="100">'
           b'<g transform="translate(10 10)"><rect id="a" x="10" y="10" width="30" height="20" '
           b'fill="red" stroke="black" stroke-width="4"/></g>'
           b'<circle id="b" cx="150" cy="50" r="20" fill="blue"/>'
           b'<g id="c" filter="url(#f)"><rect x="100" y="5" width="10" height="10" fill="green"/></g>'
           b'<filter id="f" x="-0.5" y="-0.5" width="2" height="2">'
           b'<feGaussianBlur stdDeviation="2"/></filter>'
           b'<g id="empty"/><rect id="none" width="5" height="5" fill="none"/></svg>')


@pytest.mark.parametrize('eid,size', [('a', (34, 24)),     # 30 x 20 plus half the 4 px stroke
                                      ('b', (40, 40)),     # the circle's box
                                      ('c', (20, 20))])    # the filter region, not the 10 px rect
def test_id_crops_to_what_the_element_draws(tmp_path, eid, size):
    src = write(tmp_path, 'sprites.svg', SPRITES)
    out = str(tmp_path / 'o.png')
    assert rasterize.main([src, out, '--id', eid]) == 0
    assert Image.open(out).size == size


def test_id_crop_equals_the_page_render_there(tmp_path):
    """The cropped rect (box 18..52 x 18..42 in the page, its group's
    translation included) has the page render's pixels of that window."""
    src = write(tmp_path, 'sprites.svg', SPRITES)
    crop, page = str(tmp_path / 'c.png'), str(tmp_path / 'p.png')
    assert rasterize.main([src, crop, '--id', 'a']) == 0
    assert rasterize.main([src, page, '--id', 'a', '--id-page']) == 0
    c, p = png(crop), png(page)
    assert p.shape == (100, 200, 4) and c.shape == (24, 34, 4)
    assert np.array_equal(c, p[18:42, 18:52])
    assert p[:, 60:].max() == 0                          # the other elements hidden


def test_id_crop_is_scaled_by_zoom_and_width_and_records_the_dpi(tmp_path):
    src = write(tmp_path, 'sprites.svg', SPRITES)
    out = str(tmp_path / 'o.png')
    assert rasterize.main([src, out, '--id', 'b', '--zoom', '2', '--dpi', '96']) == 0
    im = Image.open(out)
    assert im.size == (80, 80) and round(im.info['dpi'][0]) == 192
    assert rasterize.main([src, out, '--id', 'b', '--width', '100']) == 0
    assert Image.open(out).size == (100, 100)


@pytest.mark.parametrize('eid', ['empty', 'none'])
def test_id_of_an_element_that_draws_nothing_is_an_error(tmp_path, capsys, eid):
    src = write(tmp_path, 'sprites.svg', SPRITES)
    out = tmp_path / 'o.png'
    assert rasterize.main([src, str(out), '--id', eid]) == 1
    assert one_error_line(capsys.readouterr().err, 'rasterize') and not out.exists()


LANG_DOC = (b'<svg xmlns="http://www.w3.org/2000/svg" width="30" height="10"><switch>'
            b'<rect systemLanguage="de" width="30" height="10" fill="#0000ff"/>'
            b'<rect systemLanguage="en" width="30" height="10" fill="#00ff00"/>'
            b'<rect width="30" height="10" fill="#ff0000"/></switch></svg>')


@pytest.mark.parametrize('env, opts, colour', [
    ({'LANG': 'de_DE.UTF-8'}, [], (0, 0, 255)),
    ({'LANG': 'en_US.UTF-8'}, [], (0, 255, 0)),
    ({'LC_ALL': 'C'}, [], (0, 255, 0)),                 # C: English
    ({}, [], (0, 255, 0)),                               # nothing set: English
    ({'LANG': 'fr_FR'}, [], (255, 0, 0)),                # neither: the fallback child
    ({'LC_MESSAGES': 'de_AT', 'LANG': 'en_US'}, [], (0, 0, 255)),
    ({'LC_ALL': 'fr_FR', 'LC_MESSAGES': 'de_AT'}, [], (255, 0, 0)),
    ({'LANG': 'de_DE.UTF-8'}, ['--languages', 'en'], (0, 255, 0)),
    ({}, ['--languages', 'de-CH,en'], (0, 0, 255)),      # primary subtags: de-CH is de
    ({}, ['--languages', 'fr, de'], (0, 0, 255)),
])
def test_languages_option_and_locale_default(tmp_path, monkeypatch, env, opts, colour):
    for k in ('LC_ALL', 'LC_MESSAGES', 'LANG'):
        monkeypatch.delenv(k, raising=False)
    for k, v in env.items():
        monkeypatch.setenv(k, v)
    src = write(tmp_path, 'l.svg', LANG_DOC)
    out = str(tmp_path / 'l.png')
    assert rasterize.main([src, out] + opts) == 0
    assert tuple(png(out)[5, 5, :3]) == colour
    res = str(tmp_path / 'l.json')
    assert svg_flatten.main([src, '-o', res, '--format', 'json'] + opts) == 0
    assert svg_bbox.main([src, '-o', res] + opts) == 0


@pytest.mark.parametrize('main', [rasterize.main, svg_flatten.main, svg_bbox.main])
def test_bad_languages_list_is_a_usage_error(tmp_path, main, capsys):
    src = write(tmp_path, 'l.svg', LANG_DOC)
    args = [src, str(tmp_path / 'o.png')] if main is rasterize.main else [src]
    assert main(args + ['--languages', 'de_CH,,x']) == 2
    assert 'languages' in capsys.readouterr().err
