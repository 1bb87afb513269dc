"""Which fonts text is drawn with: :class:`FontOptions`, the one way the
library, the commands and the conformance harness say it."""

import os
from dataclasses import dataclass, fields
from typing import Optional, Tuple

__all__ = ['FontOptions', 'GENERIC_NAMES']

#: Generic family keywords of CSS that :class:`FontOptions` can override.
GENERIC_NAMES = ('serif', 'sans-serif', 'monospace', 'cursive', 'fantasy')


def _font_error(message):
    """:class:`raster.fonts.files.FontError` with ``message``, its module
    imported only now: options are made for every document, fonts read
    only for text."""
    from .files import FontError
    return FontError(message)


def _paths(name, value):
    if value is None:
        return ()
    if isinstance(value, (str, os.PathLike)):
        value = (value,)                 # one path, not its characters
    try:
        out = tuple(os.fspath(v) for v in value)
    except TypeError:
        raise _font_error('%s must be a path or a sequence of paths, got %r'
                          % (name, value)) from None
    return out


@dataclass(frozen=True)
class FontOptions:
    """Where fonts come from and how generic families resolve.

    Attributes
    ----------
    dirs : tuple of str
        Font folders, searched first (recursively).
    files : tuple of str
        Individual font files (``.ttf``, ``.otf``, ``.ttc``, ``.otc``,
        ``.woff``, ``.woff2``).
    system : bool
        Also use the system's fonts (the platform's font folders and
        fontconfig's); False for output that does not depend on the
        machine.
    serif_family, sans_serif_family, monospace_family, cursive_family, fantasy_family : str or None
        The family a generic family keyword resolves to, overriding the
        built-in preference lists (:data:`raster.fonts.GENERIC_PREFERENCES`).
    default_family : str or None
        The family of text whose ``font-family`` names nothing available
        (None: the ``serif`` generic family, as browsers do).
    cache : bool
        Remember font scans across processes in the user cache folder
        (see :mod:`raster.fonts.discovery`).

    A str or path given for ``dirs`` or ``files`` is one entry.

    >>> FontOptions(dirs='fonts', system=False).dirs
    ('fonts',)
    >>> FontOptions(monospace_family='Fira Code').generic_overrides()
    {'monospace': 'Fira Code'}
    """
    dirs: Tuple[str, ...] = ()
    files: Tuple[str, ...] = ()
    system: bool = True
    serif_family: Optional[str] = None
    sans_serif_family: Optional[str] = None
    monospace_family: Optional[str] = None
    cursive_family: Optional[str] = None
    fantasy_family: Optional[str] = None
    default_family: Optional[str] = None
    cache: bool = True

    def __post_init__(self):
        object.__setattr__(self, 'dirs', _paths('dirs', self.dirs))
        object.__setattr__(self, 'files', _paths('files', self.files))
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name.endswith('_family') and v is not None:
                if not isinstance(v, str) or not v.strip():
                    raise _font_error('%s must be a non-empty family name, got %r' % (f.name, v))
                object.__setattr__(self, f.name, v.strip())
        object.__setattr__(self, 'system', bool(self.system))
        object.__setattr__(self, 'cache', bool(self.cache))

    def generic_overrides(self):
        """``{generic keyword: family}`` of the overridden generic families."""
        out = {}
        for g in GENERIC_NAMES:
            v = getattr(self, g.replace('-', '_') + '_family')
            if v is not None:
                out[g] = v
        return out

    @classmethod
    def coerce(cls, value):
        """``value`` as FontOptions: a FontOptions, None (the defaults) or a
        dict of its fields.  Raises :class:`FontError` otherwise."""
        if value is None:
            return cls()
        if isinstance(value, cls):
            return value
        if isinstance(value, dict):
            try:
                return cls(**value)
            except TypeError as e:
                raise _font_error('bad font options: %s' % e) from None
        raise _font_error('fonts must be a raster.FontOptions, a dict or None, got %s'
                          % type(value).__name__)
