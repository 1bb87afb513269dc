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
import stat
from typing import Iterator

from .errors import InputLimitError, RasterIOError

__all__ = ['url_scheme', 'local_path', 'read_file', 'read_stream', 'file_chunks',
           'stream_chunks', 'too_large', 'CHUNK']

#: Bytes read at a time by :func:`file_chunks` and :func:`stream_chunks`.
CHUNK = 1 << 16

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


def too_large(max_bytes: float, what: str = 'document') -> InputLimitError:
    """The error for input beyond ``max_bytes``
    (:attr:`raster.limits.Limits.max_input_bytes`)."""
    return InputLimitError('%s is larger than %d bytes (max_input_bytes)' % (what, max_bytes))


def _read_size(max_bytes) -> int:
    """What to ask ``read()`` for: ``max_bytes + 1`` (room to see "too
    big"), or everything (-1) without a limit."""
    return -1 if max_bytes == float('inf') else int(max_bytes) + 1


def read_file(path: str | os.PathLike, max_bytes: float) -> bytes:
    """Bytes of a local file (or ``file:`` URL), at most ``max_bytes``.

    A regular file's size is checked before anything is read; a device or a
    FIFO is read up to ``max_bytes + 1`` bytes.

    Raises
    ------
    raster.errors.RasterIOError
        A URL, or the file cannot be opened or read (missing, a directory,
        no permission ...).
    raster.errors.InputLimitError
        The file is larger than ``max_bytes`` (an :class:`~raster.errors.SVGError`).
    """
    return b''.join(file_chunks(path, max_bytes, _read_size(max_bytes)))


def file_chunks(path: str | os.PathLike, max_bytes: float, chunk: int = CHUNK) -> Iterator[bytes]:
    """The bytes of a local file (or ``file:`` URL) in pieces of at most
    ``chunk`` bytes (-1: one piece), read as they are consumed, at most
    ``max_bytes`` in all; a regular file larger than that fails before
    anything is read.

    Raises
    ------
    raster.errors.RasterIOError
        A URL, or the file cannot be opened or read.
    raster.errors.InputLimitError
        More than ``max_bytes`` bytes.
    """
    p = local_path(path)
    try:
        f = open(p, 'rb')
    except OSError as e:
        raise _io_error(e, p) from e
    with f:
        try:
            st = os.fstat(f.fileno())
        except OSError as e:
            raise _io_error(e, p) from e
        if stat.S_ISREG(st.st_mode) and st.st_size > max_bytes:
            raise too_large(max_bytes)
        # (a failing read names the file: f.name is the path opened)
        yield from stream_chunks(f, max_bytes, chunk)


def read_stream(fileobj, max_bytes: float) -> bytes | str:
    """What ``fileobj.read(max_bytes + 1)`` returns, with a failing read (a
    closed file, an operating-system error) raised as
    :class:`~raster.errors.RasterIOError`."""
    return _read(fileobj, _read_size(max_bytes))


def _read(fileobj, n):
    name = getattr(fileobj, 'name', None)
    try:
        return fileobj.read(n)
    except OSError as e:
        raise _io_error(e, name if isinstance(name, str) else None) from e
    except ValueError as e:              # I/O operation on closed file
        raise RasterIOError('cannot read the file object: %s' % _short(str(e))) from e


def stream_chunks(fileobj, max_bytes: float, chunk: int = CHUNK) -> Iterator[bytes | str]:
    """What a file object's ``read(chunk)`` returns, piece after piece,
    at most ``max_bytes`` in all (a ``str`` piece counts its characters).

    Raises
    ------
    raster.errors.RasterIOError
        A failing read.
    raster.errors.InputLimitError
        More than ``max_bytes``.
    """
    total = 0
    while True:
        data = _read(fileobj, chunk)
        if not data:
            return
        total += len(data)
        if total > max_bytes:
            raise too_large(max_bytes)
        yield data
