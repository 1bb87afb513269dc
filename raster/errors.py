"""Exceptions raised by raster.

Every error the library raises on bad input derives from :class:`RasterError`,
so callers can catch one type.  The command-line tools turn these into a
one-line message and a non-zero exit status.

A document that cannot be read (a missing or unreadable file, a URL, which
raster never fetches) raises :class:`RasterIOError`, which is also an
:class:`OSError`, so code written as ``except OSError`` keeps working.

Other libraries' diagnostics become ours: :func:`log_warnings` turns what
a library logs (fontTools on broken fonts) into one-line
:class:`RasterWarning` s while raster's code runs.
"""

import contextlib
import contextvars
import sys
import _thread
import warnings


class RasterError(Exception):
    """Base class of every error raised by raster for bad input or limits."""


class PathError(RasterError, ValueError):
    """Invalid path data: non-finite coordinates, a drawing command with no
    current point, unparsable SVG path syntax."""


class TransformError(RasterError, ValueError):
    """A transform that cannot be used (non-finite, or singular where an
    inverse is needed)."""


class CanvasError(RasterError, ValueError):
    """A canvas or output size that is zero, negative, non-finite or larger
    than :data:`raster.limits.MAX_PIXELS`."""


class LimitError(RasterError):
    """A budget of :mod:`raster.limits` was exceeded (too many points,
    ``use`` nesting, pixel work, ...).  The message names the budget."""


class SVGError(RasterError):
    """The document cannot be rendered: unreadable XML, not SVG, invalid size."""


class InputLimitError(LimitError, SVGError):
    """A document beyond a whole-document budget of :mod:`raster.limits`
    (``max_input_bytes``, ``max_xml_elements``): nothing is rendered.
    Both a :class:`LimitError` and an :class:`SVGError`."""


class FormatError(RasterError, ValueError):
    """An output format that raster cannot write (an unknown name or file
    extension), or an encoder option the format does not take."""


class RasterIOError(RasterError, OSError):
    """A document source that cannot be read: a missing, unreadable or
    non-regular file, a failing file object, or a URL (``http:``,
    ``data:`` ...; only local paths and ``file:`` URLs are read).

    Raised with ``(errno, strerror, filename)`` when an operating-system
    error is behind it, so ``errno``, ``strerror`` and ``filename`` are set
    as on the :class:`OSError` it replaces; ``str()`` is one line."""


class RasterWarning(UserWarning):
    """Something in the input was ignored or not supported (issued with
    :func:`warnings.warn`; the result is still usable)."""


def one_line(msg: object) -> str:
    """``msg`` as one line: whitespace runs (newlines included) become one
    space."""
    return ' '.join(str(msg).split())


#: The log_warnings blocks this context is in: [logger name, attached] each.
_BLOCKS: contextvars.ContextVar = contextvars.ContextVar('raster_log_blocks', default=())
_LOCK = _thread.allocate_lock()     # threading.Lock, without importing threading (0.6 ms)
_HANDLERS: dict = {}


def _to_warnings():
    """A new logging handler turning the records of the contexts capturing
    them into warnings (:mod:`logging` is imported on first use: most
    documents never capture a library's log)."""
    import logging

    class _ToWarnings(logging.Handler):

        def __init__(self):
            super().__init__(logging.WARNING)
            self.users = 0

        def emit(self, record):
            if not any(record.name == b[0] or record.name.startswith(b[0] + '.')
                       for b in _BLOCKS.get()):
                return
            try:
                msg = record.getMessage()
            except Exception:               # a broken format: the template
                msg = str(record.msg)
            warnings.warn('%s: %s' % (record.name.split('.')[0], one_line(msg)), RasterWarning,
                          stacklevel=2)

    return _ToWarnings()


@contextlib.contextmanager
def log_warnings(name: str = 'fontTools'):
    """While the block runs, what the logger ``name`` (and its children)
    logs at WARNING or above in this context becomes a one-line
    :class:`RasterWarning` ``'<library>: <message>'`` instead of raw lines
    on stderr.

    A handler is attached to the logger for the block only (shared by
    nested and concurrent blocks); records of other threads and tasks pass
    it untouched, and records still propagate to the application's own
    handlers, if it configured any.  The text converter wraps font loading
    and layout in it; font code may call it directly::

        with log_warnings('fontTools'):
            font = TTFont(path)

    A library that is not imported yet cannot log, so the handler (and
    :mod:`logging` itself) waits until code in the block imports it and
    calls :func:`library_loaded` (the plain text of most documents never
    imports fontTools, nor then :mod:`logging`).
    """
    block = [name, False]          # (the logger, whether this block attached)
    token = _BLOCKS.set(_BLOCKS.get() + (block,))
    try:
        if name.partition('.')[0] in sys.modules:
            _attach(block)
        yield
    finally:
        _BLOCKS.reset(token)
        if block[1]:
            _detach(name)


def library_loaded(name: str = 'fontTools') -> None:
    """Say that library ``name`` was just imported: the :func:`log_warnings`
    blocks for it that this context is in, entered before the library was
    loaded, attach their handler now (for the rest of each block)."""
    for block in _BLOCKS.get():
        if block[0] == name and not block[1]:
            _attach(block)


def _attach(block):
    import logging
    name = block[0]
    with _LOCK:
        h = _HANDLERS.get(name)
        if h is None:
            h = _HANDLERS[name] = _to_warnings()
        if h.users == 0:
            logging.getLogger(name).addHandler(h)
        h.users += 1
    block[1] = True


def _detach(name):
    import logging
    with _LOCK:
        h = _HANDLERS[name]
        h.users -= 1
        if h.users == 0:
            logging.getLogger(name).removeHandler(h)
