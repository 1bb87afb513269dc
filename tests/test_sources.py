"""Document sources (raster.sources) and the errors of the front door: a URL
is refused with a RasterIOError, a missing or unreadable file raises an
error that is both a RasterError and an OSError, file: URLs are local files,
and bad option values are RasterErrors."""

import errno
import io
import os
import pathlib

import numpy as np
import pytest

import raster
from raster.errors import RasterError, RasterIOError, SVGError
from raster.sources import file_chunks, local_path, read_file, read_stream, url_scheme
from raster.parser.document import load_document

DOC = (b'<svg xmlns="http://www.w3.org/2000/svg" width="4" height="2">'
       b'<rect width="2" height="2" fill="blue"/></svg>')


def test_rasterioerror_is_both_kinds():
    assert issubclass(RasterIOError, RasterError) and issubclass(RasterIOError, OSError)


@pytest.mark.parametrize('url', [
    'http://example.com/a.svg', 'https://example.com/a.svg', 'HTTPS://EXAMPLE.COM/A.SVG',
    'ftp://example.com/a.svg', 'data:image/svg+xml;base64,PHN2Zy8+',
    'data:image/svg+xml,%3Csvg%20xmlns=%22http://www.w3.org/2000/svg%22/%3E',
    'javascript:alert(1)', 'file://otherhost/tmp/a.svg'])
@pytest.mark.parametrize('entry', ['render', 'load_svg', 'load_document'])
def test_urls_are_refused_with_one_line(url, entry):
    fn = {'render': raster.render, 'load_svg': raster.load_svg,
          'load_document': load_document}[entry]
    with pytest.raises(RasterIOError) as ei:
        fn(url)
    msg = str(ei.value)
    assert '\n' not in msg and ('not fetched' in msg or 'another host' in msg)
    assert len(msg) < 200                     # a long data: URL is shortened


def test_missing_file_is_rasterioerror_with_os_fields(tmp_path):
    p = tmp_path / 'absent.svg'
    for fn in (raster.render, raster.load_svg, load_document):
        with pytest.raises(RasterIOError) as ei:
            fn(str(p))
        e = ei.value
        assert isinstance(e, OSError) and isinstance(e, RasterError)
        assert e.errno == errno.ENOENT and e.filename == str(p) and e.strerror
    try:                                       # old code that caught OSError still works
        raster.render(p)
    except OSError as e:
        assert isinstance(e, RasterIOError)


def test_directory_and_unreadable_file(tmp_path):
    with pytest.raises(RasterIOError) as ei:
        raster.render(str(tmp_path))
    assert ei.value.errno == errno.EISDIR
    p = tmp_path / 'locked.svg'
    p.write_bytes(DOC)
    p.chmod(0)
    try:
        if os.access(p, os.R_OK):              # root reads anything: nothing to test
            return
        with pytest.raises(RasterIOError) as ei:
            raster.render(str(p))
        assert ei.value.errno == errno.EACCES
    finally:
        p.chmod(0o644)


def test_file_urls_name_local_files(tmp_path):
    d = tmp_path / 'a dir'
    d.mkdir()
    p = d / 'doc.svg'
    p.write_bytes(DOC)
    want = raster.render(str(p))
    url = pathlib.Path(p).as_uri()                       # file:///.../a%20dir/doc.svg
    assert '%20' in url
    assert np.array_equal(raster.render(url), want)
    assert np.array_equal(raster.render('file://localhost' + url[len('file://'):]), want)
    assert local_path(url) == str(p)


def test_file_url_resolves_relative_images_against_its_directory(tmp_path):
    from PIL import Image
    Image.new('RGBA', (2, 2), (0, 255, 0, 255)).save(tmp_path / 'g.png')
    p = tmp_path / 'img.svg'
    p.write_bytes(b'<svg xmlns="http://www.w3.org/2000/svg" width="2" height="2">'
                  b'<image href="g.png" width="2" height="2"/></svg>')
    img = raster.render(p.as_uri())
    assert img[1, 1].tolist() == [0, 255, 0, 255]


def test_path_that_looks_like_a_url_is_a_path(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / 'ab:c.svg').write_bytes(DOC)
    assert url_scheme('ab:c.svg') == 'ab'
    assert raster.render('ab:c.svg').shape == (2, 4, 4)
    with pytest.raises(RasterIOError, match='not fetched'):
        raster.render('ab:missing.svg')


def test_url_scheme_is_not_a_drive_letter():
    assert url_scheme('C:\\drawings\\a.svg') is None
    assert url_scheme('c:/a.svg') is None
    assert url_scheme('svn+ssh://h/x') == 'svn+ssh'


def test_read_file_limit_and_errors(tmp_path):
    p = tmp_path / 'x.svg'
    p.write_bytes(b'x' * 100)
    assert read_file(str(p), 100) == b'x' * 100
    with pytest.raises(SVGError, match='larger than 99 bytes'):
        read_file(str(p), 99)
    with pytest.raises(RasterIOError):
        read_file(str(tmp_path / 'nope'), 100)


class _FailingFile:
    name = '/some/where.svg'

    def read(self, n=-1):
        raise OSError(errno.EIO, 'Input/output error')


def test_failing_and_closed_file_objects():
    with pytest.raises(RasterIOError) as ei:
        raster.render(_FailingFile())
    assert ei.value.errno == errno.EIO and ei.value.filename == '/some/where.svg'
    f = io.BytesIO(DOC)
    f.close()
    with pytest.raises(RasterIOError, match='closed file'):
        raster.render(f)
    assert read_stream(io.BytesIO(b'abc'), 1) == b'ab'     # max_bytes + 1: room to see "too big"


@pytest.mark.parametrize('dpi', [0, -96, float('nan'), float('inf'), 'abc', None])
def test_bad_dpi_is_an_svgerror(dpi):
    with pytest.raises(SVGError, match='dpi must be a positive number'):
        raster.render(DOC, dpi=dpi)


def test_dpi_scales_physical_units():
    """1in at 200 dpi is 200 px; numeric strings and numpy scalars are numbers."""
    doc = b'<svg xmlns="http://www.w3.org/2000/svg" width="1in" height="0.5in"/>'
    assert raster.load_svg(doc, dpi=200).width == pytest.approx(200)
    assert raster.load_svg(doc, dpi=np.float32(300)).width == pytest.approx(300)
    assert raster.load_svg(doc, dpi='72').height == pytest.approx(36)


def test_one_font_dir_as_a_string(tmp_path):
    """``FontOptions(dirs='dir')`` and the deprecated ``font_dirs='dir'`` are
    one directory, not a sequence of characters."""
    from raster.fonts import __file__ as fonts_init
    fonts = os.path.dirname(fonts_init)        # holds the bundled Noto Sans subset
    doc = (b'<svg xmlns="http://www.w3.org/2000/svg" width="60" height="30">'
           b'<text x="2" y="24" font-size="24" font-family="Noto Sans">Hi</text></svg>')
    a = raster.render(doc, fonts=raster.FontOptions(dirs=fonts, system=False))
    b = raster.render(doc, fonts={'dirs': [fonts], 'system': False})
    with pytest.deprecated_call():
        c = raster.render(doc, font_dirs=fonts)
    assert np.array_equal(a, b) and np.array_equal(a, c) and a[..., 3].any()


def test_cli_refuses_a_url_in_one_line(tmp_path):
    from raster_cli import rasterize
    out = tmp_path / 'o.png'
    import contextlib
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        rc = rasterize.main(['https://example.com/x.svg', str(out)])
    assert rc == 1 and not out.exists()
    lines = err.getvalue().strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith('rasterize: error: ') and 'not fetched' in lines[0]


def test_cli_reads_a_file_url(tmp_path):
    from raster_cli import rasterize
    p = tmp_path / 'd.svg'
    p.write_bytes(DOC)
    out = tmp_path / 'o.png'
    assert rasterize.main([p.as_uri(), str(out)]) == 0
    from PIL import Image
    assert Image.open(out).size == (4, 2)


@pytest.mark.skipif(not os.path.exists('/proc/self/mem'), reason='needs Linux /proc')
def test_a_failing_read_of_a_file_names_the_file():
    # /proc/self/mem opens but its first read fails (EIO): the error is a
    # RasterIOError naming the path, whether read whole or in pieces
    for chunk in (-1, 16):
        with pytest.raises(RasterIOError) as info:
            list(file_chunks('/proc/self/mem', 1000, chunk))
        assert '/proc/self/mem' in str(info.value)
