"""Where documents come from: local paths, ``file:`` URLs and file objects.

raster reads documents from local files, ``bytes`` and file objects; it
never fetches a URL.  The front door (:func:`raster.render`,
:func:`raster.load_svg`, :func:`raster.svg2png`, the commands) passes every
path through :func:`local_path` and reads it with :func:`read_file`, so that

* a ``file:`` URL names a local file (``file:///tmp/a%20b.svg`` is
  ``/tmp/a b.svg``);
* any other URL (``http:``, ``https:``, ``ftp:``, a ``data:`` URL holding
  the whole document ...) is refused with a one-line
  :class:`~raster.errors.RasterIOError`;
* a file that is missing or cannot be read raises
  :class:`~raster.errors.RasterIOError`, which is both a
  :class:`~raster.errors.RasterError` and an :class:`OSError` (``errno``,
  ``strerror`` and ``filename`` as the operating system reported them).

>>> local_path('file:///tmp/a%20b.svg')
'/tmp/a b.svg'
>>> local_path('drawing.svg')
'drawing.svg'
>>> local_path('https://example.com/a.svg')
Traceback (most recent call last):
...
raster.errors.RasterIOError: https://example.com/a.svg: URLs are not fetched (only local paths and file: URLs are read)
"""

from __future__ import annotations

import os
import re

from .errors import RasterIOError, SVGError

__all__ = ['url_scheme', 'local_path', 'read_file', 'read_stream']

# A URL scheme has two or more characters, so ``C:\\x.svg`` is a path.
_SCHEME = re.compile(r'([A-Za-z][A-Za-z0-9+.\-]+):')


def _short(s: str, n: int = 80) -> str:
    s = ' '.join(s.split())
    return s if len(s) <= n else s[:n - 3] + '...'


def url_scheme(s: str) -> str | None:
    """The lower-case URL scheme ``s`` starts with (``'http'``, ``'file'``,
    ``'data'`` ...), or None for a plain path.

    >>> url_scheme('HTTPS://x/y.svg'), url_scheme('data:image/svg+xml,<svg/>')
    ('https', 'data')
    >>> url_scheme('/tmp/x.svg'), url_scheme('C:\\\\x.svg'), url_scheme('x.svg')
    (None, None, None)
    """
    m = _SCHEME.match(s)
    return m.group(1).lower() if m else None


def local_path(source: str | os.PathLike) -> str:
    """The local file path that a path or a ``file:`` URL names.

    Parameters
    ----------
    source : str or os.PathLike
        A file path, or a ``file:`` URL (``file:///abs/path``,
        ``file:relative``, ``file://localhost/abs``; percent escapes are
        decoded).

    Returns
    -------
    str
        The path (not checked for existence).

    Raises
    ------
    raster.errors.RasterIOError
        Any other URL (raster never fetches one), or a ``file:`` URL naming
        another host.  A path that merely looks like a URL (``a:b.svg``) is
        taken as a path when such a file exists.
    """
    path = os.fspath(source)
    if isinstance(path, bytes):
        path = os.fsdecode(path)
    scheme = url_scheme(path)
    if scheme is None:
        return path
    if scheme == 'file':
        # (imported here: urllib.request pulls in http, email and ssl, a
        # fifth of a command's start-up, for a plain path)
        import urllib.parse
        import urllib.request
        parts = urllib.parse.urlsplit(path)
        if parts.netloc not in ('', 'localhost'):
            raise RasterIOError('%s: file URL on another host (only local files are read)'
                                % _short(path))
        return urllib.request.url2pathname(parts.path)
    if os.path.exists(path):
        return path
    raise RasterIOError('%s: URLs are not fetched (only local paths and file: URLs are read)'
                        % _short(path))


def _io_error(e: OSError, path: str) -> RasterIOError:
    return RasterIOError(e.errno, e.strerror or str(e),
                         e.filename if e.filename is not None else path)


def read_file(path: str | os.PathLike, max_bytes: int) -> bytes:
    """Bytes of a local file (or ``file:`` URL), at most ``max_bytes``.

    Raises
    ------
    raster.errors.RasterIOError
        A URL, or the file cannot be opened or read (missing, a directory,
        no permission ...).
    raster.errors.SVGError
        The file is larger than ``max_bytes``.
    """
    p = local_path(path)
    try:
        with open(p, 'rb') as f:
            data = f.read(max_bytes + 1)
    except OSError as e:
        raise _io_error(e, p) from e
    if len(data) > max_bytes:
        raise SVGError('document is larger than %d bytes' % max_bytes)
    return data


def read_stream(fileobj, max_bytes: int) -> bytes | str:
    """What ``fileobj.read(max_bytes + 1)`` returns, with a failing read (a
    closed file, an operating-system error) raised as
    :class:`~raster.errors.RasterIOError`."""
    name = getattr(fileobj, 'name', None)
    try:
        return fileobj.read(max_bytes + 1)
    except OSError as e:
        raise _io_error(e, name if isinstance(name, str) else None) from e
    except ValueError as e:              # I/O operation on closed file
        raise RasterIOError('cannot read the file object: %s' % _short(str(e))) from e
