"""Budgets: how much input, memory and work one document may cost.

Every stage that a few bytes of input could drive into unbounded work
estimates that work *before* doing it and compares the estimate with a
budget of :class:`Limits`.  The budgets, their defaults and units:

========================  ==============  =========================================
name                      default         what it bounds
========================  ==============  =========================================
``max_input_bytes``       200 MiB         bytes of a document read (file, stdin,
                                          ``bytes``, file object) and after gzip
``max_xml_elements``      250,000         elements parsed (XML)
``max_xml_text_bytes``    10,000,000      longest text or attribute value (a
                                          ``data:`` image): libxml2's limits
                                          up to 10 MB (and 256 levels deep);
                                          above, its huge mode
``max_elements``          100,000         render-tree nodes built (``use``
                                          copies included)
``max_use_depth``         64              ``use`` nesting followed
``max_layers``            2,000           group layers built (a clip path,
                                          mask, filter, blend mode, a group
                                          opacity), ``use`` copies included
``max_css_matches``       1,000,000       selector tests of the CSS cascade
                                          (candidate rules x elements)
``max_path_bytes``        2,000,000       path data of one element (``d``,
                                          ``points``)
``max_glyphs``            20,000          characters of text laid out
``max_image_bytes``       64 MiB          encoded size of one image
``max_image_pixels``      89,478,485      decoded size of one raster image
``max_pixels``            100,000,000     pixels of a canvas or layer
``max_side``              100,000         pixels of a canvas side
``max_coord``             1e9             device-pixel coordinate magnitude
``max_flatten_points``    4,000,000       polyline points of one flattening
                                          (one path or one batch)
``max_render_points``     10,000,000      curve points flattened by one render
``max_pixel_work``        512             pixel work of one render (layers,
                                          masks, clip paths, pattern tiles,
                                          images, filter primitives, fills)
                                          in array passes over the output's
                                          pixels (at least 2**19 of them)
========================  ==============  =========================================

Over a budget, the stage raises :class:`~raster.errors.LimitError` (or
:class:`~raster.errors.CanvasError` for sizes) before allocating; the
parser and the renderer turn that into one
:class:`~raster.errors.RasterWarning` and leave the one element out
(``use`` copies, filtered groups, paths, stylesheets), so the rest of the
document is drawn.  Whole-document budgets (input size, XML elements) fail
the document.

The budgets in force are :func:`current`: :data:`DEFAULT` unless a caller
raised them for a block with :func:`applied` (a context variable: other
threads and the rest of the process keep theirs).  The front doors take
them too::

    raster.render('big.svg', limits={'max_xml_text_bytes': 50_000_000})
    raster.render('trusted.svg', limits='unlimited')
    with raster.limits.applied(max_pixel_work=256):
        ...

and the commands have ``--unlimited`` and one option per budget
(``--max-pixel-work 256``).  ``'unlimited'`` (:data:`UNLIMITED`) lifts
every budget: only the memory of the machine and the kernel's own
numerical bounds remain.

>>> current().max_elements
100000
>>> with applied(max_elements=10):
...     current().max_elements
10
>>> resolve({'max_pixels': 4e8}).max_pixels
400000000
"""

from __future__ import annotations

import contextlib
import contextvars
import dataclasses
import math
from dataclasses import dataclass, field
from typing import Iterator, Mapping, Optional, Union

from .errors import LimitError

__all__ = ['Limits', 'DEFAULT', 'UNLIMITED', 'current', 'applied', 'resolve', 'Meter',
           'metering', 'meter', 'check_points', 'spend_points', 'spend_work', 'check_coord',
           'WORK_FLOOR', 'LimitsSpec']


def _budget(default, unit, doc):
    return field(default=default, metadata={'unit': unit, 'doc': doc})


@dataclass(frozen=True)
class Limits:
    """The budgets of one document (see the module docstring for each).

    Every field is a positive number; ``math.inf`` means no limit.  Make
    variants with :meth:`replace`; :data:`DEFAULT` is ``Limits()``.
    """
    max_input_bytes: float = _budget(
        200 * 1024 * 1024, 'bytes',
        'bytes of a document read from a file, stdin, bytes or a file object, and after '
        'gzip decompression')
    max_xml_elements: float = _budget(
        250_000, 'elements', 'XML elements parsed; a larger document fails')
    max_xml_text_bytes: float = _budget(
        10_000_000, 'bytes',
        'longest XML text or attribute value (a data: image): up to 10 MB libxml2\'s limits '
        'apply (nesting 256 deep too); above, its huge mode, bounded by max_input_bytes')
    max_elements: float = _budget(
        100_000, 'nodes', 'render-tree nodes built, use copies included; the rest is left out')
    max_use_depth: float = _budget(64, 'levels', 'use nesting followed')
    max_layers: float = _budget(
        2_000, 'elements', 'group layers built (a clip path, mask, filter, blend mode or a '
        'group opacity), use copies included; the rest is left out')
    max_css_matches: float = _budget(
        1_000_000, 'tests',
        'selector tests of the CSS cascade (candidate rules x elements); over it the '
        'stylesheets are ignored')
    max_path_bytes: float = _budget(
        2_000_000, 'bytes', 'path data of one element (d, points); a longer one is left out')
    max_glyphs: float = _budget(
        20_000, 'characters', 'characters of text laid out; a text element that would go '
        'over it is left out')
    max_image_bytes: float = _budget(64 * 1024 * 1024, 'bytes', 'encoded size of one image')
    max_image_pixels: float = _budget(89_478_485, 'pixels', 'decoded size of one raster image')
    max_pixels: float = _budget(100_000_000, 'pixels', 'pixels of the canvas or of one layer')
    max_side: float = _budget(100_000, 'pixels', 'pixels of a canvas side')
    max_coord: float = _budget(1e9, 'pixels', 'device coordinate magnitude of geometry')
    max_flatten_points: float = _budget(
        4_000_000, 'points', 'polyline points of one flattening (a path or a batch of paths), '
        'estimated before flattening')
    max_render_points: float = _budget(
        10_000_000, 'points', 'curve points flattened by one render (estimated, as for '
        'max_flatten_points)')
    max_pixel_work: float = _budget(
        512, 'passes',
        'pixel work of one render (layers, masks, clip paths, pattern tiles, images, filter '
        'primitives, fills) in array passes over the output\'s pixels (at least 2**19 of them)')

    def __post_init__(self):
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            try:
                ok = not isinstance(v, bool) and float(v) > 0 and not math.isnan(float(v))
            except (TypeError, ValueError):
                ok = False
            if not ok:
                raise LimitError('limit %s must be a positive number, got %r' % (f.name, v))
            if isinstance(v, float) and v.is_integer() and f.name != 'max_coord':
                object.__setattr__(self, f.name, int(v))

    def replace(self, **changes) -> 'Limits':
        """A copy with some budgets changed (``math.inf``: no limit).

        Raises
        ------
        raster.errors.LimitError
            An unknown name or a value that is not a positive number.
        """
        names = {f.name for f in dataclasses.fields(self)}
        bad = sorted(set(changes) - names)
        if bad:
            raise LimitError('unknown limit %s (known: %s)' % (bad[0], ', '.join(sorted(names))))
        return dataclasses.replace(self, **changes)

    @classmethod
    def names(cls):
        """The budget names, in declaration order."""
        return [f.name for f in dataclasses.fields(cls)]

    @classmethod
    def describe(cls):
        """``[(name, default, unit, description)]`` of every budget."""
        return [(f.name, f.default, f.metadata['unit'], f.metadata['doc'])
                for f in dataclasses.fields(cls)]


#: The budgets in force unless raised.
DEFAULT = Limits()

#: No budget at all (``--unlimited``, ``limits='unlimited'``).
UNLIMITED = Limits(**{name: math.inf for name in Limits.names()})

# The defaults under their historical names.
MAX_PIXELS = DEFAULT.max_pixels
MAX_SIDE = DEFAULT.max_side
MAX_COORD = DEFAULT.max_coord
MAX_FLATTEN_POINTS = DEFAULT.max_flatten_points
MAX_USE_DEPTH = DEFAULT.max_use_depth
MAX_ELEMENTS = DEFAULT.max_elements

#: Smallest output (pixels) :attr:`Limits.max_pixel_work` is counted against.
WORK_FLOOR = 1 << 19

#: What :func:`resolve` accepts.
LimitsSpec = Union[None, Limits, Mapping[str, float], str, bool]

_CURRENT: contextvars.ContextVar = contextvars.ContextVar('raster_limits', default=DEFAULT)
_METER: contextvars.ContextVar = contextvars.ContextVar('raster_meter', default=None)


def current() -> Limits:
    """The budgets in force in this context (thread, task)."""
    return _CURRENT.get()


def resolve(spec: LimitsSpec = None) -> Limits:
    """Budgets from a specification.

    Parameters
    ----------
    spec : None, Limits, mapping, ``'unlimited'`` or bool
        None or False: :func:`current`; a :class:`Limits`: itself; a
        mapping ``{name: value}``: :func:`current` with those budgets
        replaced; ``'unlimited'`` or True: :data:`UNLIMITED`.

    Raises
    ------
    raster.errors.LimitError
        Anything else, unknown names or bad values.
    """
    if spec is None or spec is False:
        return current()
    if spec is True or (isinstance(spec, str) and spec.strip().lower() == 'unlimited'):
        return UNLIMITED
    if isinstance(spec, Limits):
        return spec
    if isinstance(spec, Mapping):
        return current().replace(**dict(spec))
    raise LimitError("limits must be a raster.limits.Limits, a mapping of budgets or "
                     "'unlimited', got %s" % type(spec).__name__)


@contextlib.contextmanager
def applied(spec: LimitsSpec = None, **changes) -> Iterator[Limits]:
    """Run a block under other budgets: ``with applied(max_elements=10**6):``
    or ``with applied('unlimited'):`` (see :func:`resolve`); yields them."""
    lim = resolve(spec)
    if changes:
        lim = lim.replace(**changes)
    token = _CURRENT.set(lim)
    try:
        yield lim
    finally:
        _CURRENT.reset(token)


def _amount(x):
    return '%.3g' % x if x >= 1e6 else '%d' % x


class Meter:
    """What one render may still spend of the budgets counted over the
    whole render (:attr:`Limits.max_pixel_work`,
    :attr:`Limits.max_render_points`).

    Parameters
    ----------
    limits : Limits
    pixels : int
        The output's pixel count (the unit of ``max_pixel_work``, at least
        :data:`WORK_FLOOR`).
    """
    __slots__ = ('limits', 'work_left', 'points_left', 'work_spent', 'points_spent')

    def __init__(self, limits: Limits, pixels: int):
        self.limits = limits
        self.work_left = limits.max_pixel_work * max(int(pixels), WORK_FLOOR)
        self.points_left = limits.max_render_points
        self.work_spent = self.points_spent = 0.0

    def spend_work(self, amount: float, what: str) -> None:
        """Take ``amount`` pixel operations for ``what`` (a short noun
        phrase), or raise :class:`~raster.errors.LimitError` (nothing
        taken)."""
        if amount > self.work_left:
            raise LimitError('%s needs %s pixel operations, more than the %s left of '
                             'max_pixel_work' % (what, _amount(amount),
                                                 _amount(max(self.work_left, 0))))
        self.work_left -= amount
        self.work_spent += amount

    def spend_points(self, n: float, what: str) -> None:
        """Take ``n`` polyline points, or raise
        :class:`~raster.errors.LimitError` (nothing taken)."""
        if n > self.points_left:
            raise LimitError('%s needs %s points, more than the %s left of max_render_points'
                             % (what, _amount(n), _amount(max(self.points_left, 0))))
        self.points_left -= n
        self.points_spent += n


@contextlib.contextmanager
def metering(m: Meter) -> Iterator[Meter]:
    """Count the whole-render budgets of a block on ``m``."""
    token = _METER.set(m)
    try:
        yield m
    finally:
        _METER.reset(token)


def meter() -> Optional[Meter]:
    """The meter of the render in progress, or None outside one."""
    return _METER.get()


def check_points(n: float, what: str = 'flattening') -> None:
    """Raise :class:`~raster.errors.LimitError` when one flattening needs
    more than :attr:`Limits.max_flatten_points` points."""
    lim = _CURRENT.get().max_flatten_points
    if n > lim:
        raise LimitError('%s would produce %s points, more than max_flatten_points %s'
                         % (what, _amount(n), _amount(lim)))


def spend_points(n: float, what: str = 'flattening') -> None:
    """:func:`check_points`, then take ``n`` points from the render in
    progress (if any)."""
    check_points(n, what)
    m = _METER.get()
    if m is not None:
        m.spend_points(n, what)


def spend_work(amount: float, what: str) -> None:
    """Take ``amount`` pixel operations from the render in progress (if
    any), or raise :class:`~raster.errors.LimitError`."""
    m = _METER.get()
    if m is not None:
        m.spend_work(amount, what)


def check_coord(magnitude: float, what: str = 'geometry') -> None:
    """Raise :class:`~raster.errors.LimitError` when a device coordinate
    magnitude exceeds :attr:`Limits.max_coord` (or is not finite)."""
    lim = _CURRENT.get().max_coord
    if not magnitude <= lim:
        raise LimitError('%s coordinate magnitude %.3g exceeds max_coord %.3g'
                         % (what, magnitude, lim))
