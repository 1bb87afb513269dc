"""Exceptions raised by raster.

Every error the library raises on bad input derives from :class:`RasterError`,
so callers can catch one type.  The command-line tools turn these into a
one-line message and a non-zero exit status.

A document that cannot be read (a missing or unreadable file, a URL, which
raster never fetches) raises :class:`RasterIOError`, which is also an
:class:`OSError`, so code written as ``except OSError`` keeps working.
"""


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
