"""rasterize's output formats (by extension or --format; JPEG flattened on
the background; --quality, --compress-level; resolution from --dpi) and
--version on every command."""

import io
import os
import struct

import numpy as np
import pytest
from PIL import Image

import raster
from raster_cli import conformance, curve, rasterize, svg_bbox, svg_flatten

# 20 x 10: a red square on the left half, the right half transparent (column
# 18 lies in an 8 x 8 JPEG block of its own, away from the square's edges)
DOC = (b'<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10">'
       b'<rect x="1" y="1" width="8" height="8" fill="#ff0000"/></svg>')


@pytest.fixture
def src(tmp_path):
    p = tmp_path / 'in.svg'
    p.write_bytes(DOC)
    return str(p)


def run_ok(*argv):
    rc = rasterize.main([str(a) for a in argv])
    assert rc == 0
    return rc


def opened(path):
    im = Image.open(path)
    im.load()
    return im


@pytest.mark.parametrize('name, fmt, mode', [
    ('o.png', 'PNG', 'RGBA'), ('o.PNG', 'PNG', 'RGBA'), ('o.jpg', 'JPEG', 'RGB'),
    ('o.jpeg', 'JPEG', 'RGB'), ('o.webp', 'WEBP', 'RGBA'), ('o.tif', 'TIFF', 'RGBA'),
    ('o.tiff', 'TIFF', 'RGBA'), ('o.bmp', 'BMP', 'RGB'), ('o', 'PNG', 'RGBA')])
def test_format_from_the_extension(tmp_path, src, name, fmt, mode):
    out = tmp_path / name
    run_ok(src, out)
    im = opened(out)
    assert (im.format, im.mode, im.size) == (fmt, mode, (20, 10))
    px = np.asarray(im.convert('RGBA'))
    assert np.abs(px[5, 5].astype(int) - (255, 0, 0, 255)).max() <= 2     # inside the square
    if mode == 'RGBA':
        assert px[5, 18, 3] == 0                                # transparent half kept
    else:
        assert np.abs(px[5, 18].astype(int) - 255).max() <= 2   # flattened on white


def test_lossless_outputs_agree_pixel_for_pixel(tmp_path, src):
    run_ok(src, tmp_path / 'a.png')
    run_ok(src, tmp_path / 'a.tiff')
    run_ok(src, tmp_path / 'a.webp')
    a = np.asarray(opened(tmp_path / 'a.png'))
    assert np.array_equal(np.asarray(opened(tmp_path / 'a.tiff')), a)
    w = np.asarray(opened(tmp_path / 'a.webp'))
    assert np.array_equal(w[..., 3], a[..., 3]) and np.array_equal(w[a[..., 3] > 0], a[a[..., 3] > 0])


def test_format_option_wins_over_the_extension(tmp_path, src):
    out = tmp_path / 'really-a-jpeg.png'
    run_ok(src, out, '--format', 'JPG')
    assert opened(out).format == 'JPEG'


def test_jpeg_is_flattened_on_the_background(tmp_path, src):
    out = tmp_path / 'o.jpg'
    run_ok(src, out, '--background', '#0000ff')
    px = np.asarray(opened(out)).astype(int)
    assert np.abs(px[5, 18] - (0, 0, 255)).max() <= 3
    run_ok(src, out, '--background', 'rgba(0, 0, 255, 0.5)')     # half blue, then white
    px = np.asarray(opened(out)).astype(int)
    assert np.abs(px[5, 18] - (127, 127, 255)).max() <= 3


def test_quality_and_compress_level(tmp_path, src):
    run_ok(src, tmp_path / 'lo.jpg', '--width', '200', '--quality', '5')
    run_ok(src, tmp_path / 'hi.jpg', '--width', '200', '--quality', '100')
    assert os.path.getsize(tmp_path / 'lo.jpg') < os.path.getsize(tmp_path / 'hi.jpg')
    run_ok(src, tmp_path / 'lossy.webp', '--width', '200', '--quality', '40')
    run_ok(src, tmp_path / 'c0.png', '--width', '200', '--compress-level', '0')
    run_ok(src, tmp_path / 'c9.png', '--width', '200', '--compress-level', '9')
    assert os.path.getsize(tmp_path / 'c0.png') > os.path.getsize(tmp_path / 'c9.png')
    assert np.array_equal(np.asarray(opened(tmp_path / 'c0.png')),
                          np.asarray(opened(tmp_path / 'c9.png')))


def phys(path):
    data = open(path, 'rb').read()
    i = data.find(b'pHYs')
    return None if i < 0 else struct.unpack('>IIB', data[i + 4:i + 13])


def test_png_resolution_from_dpi_keeps_the_physical_size(tmp_path, tmp_path_factory):
    """A 1in x 0.5in document: at --dpi 300 it is 300 x 150 px and the PNG
    says 300 dpi (11811 px/m); at --dpi 300 --width 600 the same inch is
    600 px, so 600 dpi; without --dpi no pHYs chunk."""
    p = tmp_path / 'inch.svg'
    p.write_bytes(b'<svg xmlns="http://www.w3.org/2000/svg" width="1in" height="0.5in"/>')
    out = tmp_path / 'o.png'
    run_ok(p, out, '--dpi', '300')
    assert opened(out).size == (300, 150) and phys(out) == (11811, 11811, 1)
    run_ok(p, out, '--dpi', '300', '--width', '600')
    assert opened(out).size == (600, 300) and phys(out) == (23622, 23622, 1)
    run_ok(p, out, '--dpi', '300', '--width', '600', '--height', '150')      # stretched
    assert phys(out) == (23622, 11811, 1)
    run_ok(p, out)
    assert phys(out) is None
    run_ok(p, tmp_path / 'o.jpg', '--dpi', '150')
    assert opened(tmp_path / 'o.jpg').info['dpi'] == (150, 150)
    run_ok(p, tmp_path / 'o.tiff', '--dpi', '150', '--zoom', '2')
    assert opened(tmp_path / 'o.tiff').info['dpi'] == pytest.approx((300, 300))


@pytest.mark.parametrize('argv, msg', [
    (['o.pdf'], "cannot write '.pdf' files"),
    (['o.gif'], "cannot write '.gif' files"),
    (['o.png', '--quality', '80'], '--quality applies to JPEG and WebP'),
    (['o.jpg', '--compress-level', '3'], '--compress-level applies to PNG'),
    (['o.jpg', '--quality', '0'], '--quality must be 1-100'),
    (['o.png', '--compress-level', '12'], '--compress-level must be 0-9'),
    (['o.png', '--format', 'pdf'], 'invalid choice'),
])
def test_usage_errors_exit_2_and_write_nothing(tmp_path, src, capsys, argv, msg):
    out = tmp_path / argv[0]
    rc = rasterize.main([src, str(out)] + argv[1:])
    err = capsys.readouterr().err
    assert rc == 2 and msg in err and 'Traceback' not in err
    assert not out.exists()


def test_stdout_is_png_unless_format_says(src, capsysbinary):
    assert rasterize.main([src, '-']) == 0
    assert capsysbinary.readouterr().out[:8] == b'\x89PNG\r\n\x1a\n'
    assert rasterize.main([src, '-', '--format', 'webp']) == 0
    data = capsysbinary.readouterr().out
    assert Image.open(io.BytesIO(data)).format == 'WEBP'


# -- --version ---------------------------------------------------------------------------

@pytest.mark.parametrize('main, prog', [
    (rasterize.main, 'rasterize'), (svg_flatten.main, 'svg-flatten'),
    (svg_bbox.main, 'svg-bbox'), (curve.main, 'curve'),
    (conformance.main, 'python -m raster_cli.conformance')])
def test_every_command_has_version(main, prog, capsys):
    try:
        rc = main(['--version'])
    except SystemExit as e:          # argparse's version action exits
        rc = e.code
    assert rc in (0, None)
    assert capsys.readouterr().out.strip() == '%s %s' % (prog, raster.__version__)
