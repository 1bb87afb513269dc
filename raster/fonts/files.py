"""Reading font files safely: the container formats, their limits, and what
one scan of a file records about each face.

A font file is checked before fontTools parses it:

* its size is at most :data:`MAX_FONT_BYTES`;
* an sfnt (TrueType ``.ttf``, OpenType ``.otf``, collections ``.ttc`` /
  ``.otc``) has a table directory whose tables lie inside the file;
* a WOFF file's tables inflate (zlib, with a bounded output) to exactly
  their declared sizes, and those add up to at most
  :data:`MAX_SFNT_BYTES`;
* a WOFF2 file's one Brotli stream inflates, with a bounded output, to
  exactly the size its table directory declares (at most
  :data:`MAX_SFNT_BYTES`): a "Brotli bomb" stops at the bound instead of
  filling memory.

Anything else (not a font, a truncated file, a table beyond the end)
raises :class:`FontError` with a one-line message.  fontTools' own log
records during a read are captured (:func:`quiet_fonttools`) and become
part of that message or are dropped; nothing is printed to stderr.

:func:`scan_faces` reads what matching needs about every face of a file:
:class:`FontFace` (families, names, weight, style, stretch, the generic
class it belongs to) and its character coverage as ranges.
"""

import contextlib
import io
import os
import struct
import zlib
from dataclasses import dataclass, field

from ..errors import RasterError

__all__ = ['FontError', 'FontFace', 'MAX_FONT_BYTES', 'MAX_SFNT_BYTES', 'FONT_EXTENSIONS',
           'read_font_bytes', 'check_font_data', 'scan_faces', 'sfnt_bytes', 'quiet_fonttools',
           'coverage_ranges']

#: Largest font file read (bytes); larger files are skipped with a warning.
MAX_FONT_BYTES = 128 * 1024 * 1024
#: Largest decompressed font (WOFF, WOFF2) accepted (bytes).
MAX_SFNT_BYTES = 128 * 1024 * 1024
#: File name endings scanned for fonts (lower case).
FONT_EXTENSIONS = ('.ttf', '.otf', '.ttc', '.otc', '.woff', '.woff2')


class FontError(RasterError):
    """A font file cannot be read or used (not a font, truncated, beyond a
    limit, no outlines)."""


@dataclass(frozen=True)
class FontFace:
    """One face of a font file (what matching needs; no font data).

    Attributes
    ----------
    path : str
        File path, or a ``memory:`` key for a font given as bytes
        (``@font-face`` with a ``data:`` URI).
    index : int
        Face index inside a collection (0 for plain files).
    families : tuple of str
        Family names: the typographic family (name ID 16) first, then the
        legacy family (name ID 1), then any other languages' names.
    weight : int
        ``OS/2.usWeightClass`` (1..1000; 400 normal, 700 bold).
    style : str
        ``'normal'``, ``'italic'`` or ``'oblique'``.
    stretch : int
        ``OS/2.usWidthClass`` (1 ultra-condensed .. 5 normal .. 9 ultra-expanded).
    full_name, postscript_name : str
        Name IDs 4 and 6 (``@font-face`` ``local()`` matches either).
    generic : str
        The generic class the face belongs to: ``'monospace'`` (fixed
        pitch), ``'serif'``, ``'sans-serif'``, ``'cursive'``, ``'fantasy'``,
        ``'emoji'`` or ``''`` (unknown), from the ``post`` and ``OS/2``
        tables (``isFixedPitch``, PANOSE, the IBM font class) and the name.
    color : bool
        The face has colour glyphs (COLR, sbix, CBDT or SVG tables).
    unicode_range : tuple of int
        The code points the face may be used for (``@font-face``
        ``unicode-range``) as flat sorted inclusive ranges ``lo0, hi0, lo1,
        hi1, ...``; empty: every code point (faces of font files).
    """
    path: str
    index: int
    families: tuple
    weight: int = 400
    style: str = 'normal'
    stretch: int = 5
    full_name: str = ''
    postscript_name: str = ''
    generic: str = ''
    color: bool = field(default=False)
    unicode_range: tuple = ()

    @property
    def family(self):
        """The first family name."""
        return self.families[0] if self.families else ''

    def to_json(self):
        return [self.index, list(self.families), self.weight, self.style, self.stretch,
                self.full_name, self.postscript_name, self.generic, self.color]

    @classmethod
    def from_json(cls, path, rec):
        index, fams, weight, style, stretch, full, ps, generic, color = rec
        return cls(path, int(index), tuple(str(f) for f in fams), int(weight), str(style),
                   int(stretch), str(full), str(ps), str(generic), bool(color))


_CAPTURE_CLASS = None


def _capture():
    """A new logging handler collecting messages (:mod:`logging` is
    imported with the first font read, not with the package; the class
    is made once)."""
    global _CAPTURE_CLASS
    if _CAPTURE_CLASS is None:
        import logging

        class _Capture(logging.Handler):
            def __init__(self):
                super().__init__(logging.WARNING)
                self.messages = []

            def emit(self, record):
                try:
                    self.messages.append(record.getMessage())
                except Exception:       # a record that cannot be formatted
                    self.messages.append(str(record.msg))

        _CAPTURE_CLASS = _Capture
    return _CAPTURE_CLASS()


@contextlib.contextmanager
def quiet_fonttools():
    """While reading a font: fontTools' log records (warnings about odd
    tables, ...) are collected instead of reaching the host's handlers
    or stderr.  Yields the list of captured messages.  The ``fontTools``
    logger's handlers and ``propagate`` flag are restored afterwards."""
    import logging
    logger = logging.getLogger('fontTools')
    cap = _capture()
    old_prop = logger.propagate
    logger.addHandler(cap)
    logger.propagate = False
    try:
        yield cap.messages
    finally:
        logger.removeHandler(cap)
        logger.propagate = old_prop


def read_font_bytes(path):
    """The bytes of a font file, checked by :func:`check_font_data`.

    Raises
    ------
    FontError
        Unreadable, larger than :data:`MAX_FONT_BYTES` or not a usable
        font container.
    """
    try:
        size = os.path.getsize(path)
        if size > MAX_FONT_BYTES:
            raise FontError('font file is larger than %d bytes' % MAX_FONT_BYTES)
        with open(path, 'rb') as fh:
            # read what the file holds, not a buffer of the limit (a file
            # that grew since is still read only up to the limit)
            data = fh.read(size + 1)
            if len(data) > size:
                data += fh.read(MAX_FONT_BYTES + 1 - len(data))
    except OSError as e:
        raise FontError('cannot read font file: %s' % (e.strerror or e)) from None
    check_font_data(data)
    return data


def check_font_data(data):
    """Check the container of font ``data`` (bytes) without parsing the
    tables; returns the kind: ``'sfnt'``, ``'ttc'``, ``'woff'`` or
    ``'woff2'``.

    Raises
    ------
    FontError
        Not a font, truncated, a table outside the file, or a compressed
        font inflating beyond :data:`MAX_SFNT_BYTES` or to another size
        than it declares.
    """
    if len(data) > MAX_FONT_BYTES:
        raise FontError('font data is larger than %d bytes' % MAX_FONT_BYTES)
    if len(data) < 12:
        raise FontError('not a font file (too short)')
    tag = data[:4]
    if tag in (b'\x00\x01\x00\x00', b'OTTO', b'true', b'typ1'):
        _check_sfnt(data, 0)
        return 'sfnt'
    if tag == b'ttcf':
        (n,) = struct.unpack_from('>I', data, 8)
        if n == 0 or 12 + 4 * n > len(data) or n > 10000:
            raise FontError('truncated font collection header')
        for off in struct.unpack_from('>%dI' % n, data, 12):
            _check_sfnt(data, off)
        return 'ttc'
    if tag == b'wOFF':
        _check_woff(data)
        return 'woff'
    if tag == b'wOF2':
        _check_woff2(data)
        return 'woff2'
    raise FontError('not a font file (unknown signature %r)' % (bytes(tag),))


def _check_sfnt(data, off):
    if off + 12 > len(data):
        raise FontError('truncated font file (no table directory)')
    (num,) = struct.unpack_from('>H', data, off + 4)
    end = off + 12 + 16 * num
    if num == 0 or end > len(data):
        raise FontError('truncated font file (table directory)')
    for k in range(num):
        tag, _, t_off, t_len = struct.unpack_from('>4sIII', data, off + 12 + 16 * k)
        if t_off + t_len > len(data):
            raise FontError('truncated font file (table %r ends beyond the file)'
                            % tag.decode('latin-1'))


def _check_woff(data):
    if len(data) < 44:
        raise FontError('truncated WOFF header')
    _, _, length, num, _, total = struct.unpack_from('>4s4sIHHI', data, 0)
    if total > MAX_SFNT_BYTES:
        raise FontError('WOFF font declares %d bytes uncompressed (limit %d)'
                        % (total, MAX_SFNT_BYTES))
    if 44 + 20 * num > len(data):
        raise FontError('truncated WOFF table directory')
    out = 0
    for k in range(num):
        tag, t_off, comp, orig, _ = struct.unpack_from('>4sIIII', data, 44 + 20 * k)
        if t_off + comp > len(data):
            raise FontError('truncated WOFF file (table %r)' % tag.decode('latin-1'))
        out += orig
        if out > MAX_SFNT_BYTES:
            raise FontError('WOFF tables inflate beyond %d bytes' % MAX_SFNT_BYTES)
        if comp < orig:
            d = zlib.decompressobj()
            try:
                raw = d.decompress(data[t_off:t_off + comp], orig + 1)
            except zlib.error as e:
                raise FontError('corrupt WOFF table %r: %s' % (tag.decode('latin-1'), e)) \
                    from None
            if len(raw) != orig:
                raise FontError('WOFF table %r inflates to another size than declared'
                                % tag.decode('latin-1'))


def _base128(data, pos):
    v = 0
    for k in range(5):
        if pos >= len(data):
            raise FontError('truncated WOFF2 table directory')
        b = data[pos]
        pos += 1
        if k == 0 and b == 0x80:
            raise FontError('bad WOFF2 table directory')
        v = (v << 7) | (b & 0x7F)
        if not b & 0x80:
            return v, pos
    raise FontError('bad WOFF2 table directory')


def _check_woff2(data):
    """Walk a WOFF2 table directory (W3C WOFF2, section 5) for the declared
    uncompressed size, then inflate the Brotli stream with that bound."""
    if len(data) < 48:
        raise FontError('truncated WOFF2 header')
    num, = struct.unpack_from('>H', data, 12)
    total_sfnt, = struct.unpack_from('>I', data, 16)
    comp_len, = struct.unpack_from('>I', data, 20)
    if total_sfnt > MAX_SFNT_BYTES:
        raise FontError('WOFF2 font declares %d bytes uncompressed (limit %d)'
                        % (total_sfnt, MAX_SFNT_BYTES))
    pos = 48
    expect = 0
    for _ in range(num):
        if pos >= len(data):
            raise FontError('truncated WOFF2 table directory')
        flags = data[pos]
        pos += 1
        tag_index = flags & 0x3F
        if tag_index == 0x3F:
            tag = data[pos:pos + 4]
            pos += 4
        else:
            tag = None
        version = (flags >> 6) & 3
        orig, pos = _base128(data, pos)
        # glyf/loca are transformed when the version is 0, others when it is not 0
        transformed = (version == 0) if tag_index in (10, 11) else (version != 0)
        length = orig
        if transformed:
            length, pos = _base128(data, pos)
        del tag
        expect += length
        if expect > MAX_SFNT_BYTES:
            raise FontError('WOFF2 tables inflate beyond %d bytes' % MAX_SFNT_BYTES)
    if num > 0 and data[4:8] == b'ttcf':
        raise FontError('WOFF2 font collections are not supported')
    start = pos
    if start + comp_len > len(data):
        raise FontError('truncated WOFF2 file (compressed data)')
    try:
        import brotli
    except ImportError:
        raise FontError('WOFF2 fonts need the brotli package') from None
    d = brotli.Decompressor()
    try:
        out = d.process(bytes(data[start:start + comp_len]), output_buffer_limit=expect + 1)
        got = len(out)
        while got <= expect and not d.is_finished() and not d.can_accept_more_data():
            more = d.process(b'', output_buffer_limit=expect + 1 - got)
            if not more:
                break
            got += len(more)
    except brotli.error as e:
        raise FontError('corrupt WOFF2 data: %s' % e) from None
    if got != expect or not d.is_finished():
        raise FontError('WOFF2 data inflates to another size than its table directory declares')


def sfnt_bytes(data, kind=None):
    """Plain sfnt bytes (for HarfBuzz) of checked font data: WOFF and WOFF2
    are unpacked through fontTools, sfnt data is returned as is."""
    kind = kind or check_font_data(data)
    if kind not in ('woff', 'woff2'):
        return data
    from fontTools.ttLib import TTFont
    with quiet_fonttools():
        try:
            tt = TTFont(io.BytesIO(data))
            tt.flavor = None
            buf = io.BytesIO()
            tt.save(buf, reorderTables=False)
        except Exception as e:      # fontTools raises many kinds on bad data
            raise FontError('cannot unpack %s font: %s' % (kind.upper(), _one_line(e))) from None
    return buf.getvalue()


def _one_line(e):
    return ' '.join(str(e).split()) or type(e).__name__


_MONO_WORDS = ('mono', 'code', 'courier', 'console', 'consolas', 'typewriter', 'fixed')
_SANS_WORDS = ('sans', 'gothic', 'grotesk', 'arial', 'helvetica', 'verdana', 'tahoma',
               'roboto', 'inter', 'segoe', 'ubuntu', 'cantarell')
_SERIF_WORDS = ('serif', 'roman', 'times', 'georgia', 'garamond', 'book', 'mincho',
                'song', 'ming', 'baskerville', 'palatino', 'tinos', 'caladea')
_CURSIVE_WORDS = ('script', 'hand', 'cursive', 'brush', 'comic', 'chancery')


def _generic_of(tt, families, is_color):
    """The generic class of a face (see :attr:`FontFace.generic`)."""
    name = ' '.join(families).lower()
    if is_color and 'emoji' in name:
        return 'emoji'
    post = tt['post'] if 'post' in tt else None
    if post is not None and int(getattr(post, 'isFixedPitch', 0)):
        return 'monospace'
    os2 = tt['OS/2'] if 'OS/2' in tt else None
    panose = getattr(os2, 'panose', None) if os2 is not None else None
    if panose is not None:
        fam = int(getattr(panose, 'bFamilyType', 0))
        if fam == 2 and int(getattr(panose, 'bProportion', 0)) == 9:
            return 'monospace'
        if fam == 3:
            return 'cursive'
        if fam == 4:
            return 'fantasy'
    if any(w in name for w in _MONO_WORDS):
        return 'monospace'
    if any(w in name for w in _SANS_WORDS):
        return 'sans-serif'
    if any(w in name for w in _SERIF_WORDS):
        return 'serif'
    if any(w in name for w in _CURSIVE_WORDS):
        return 'cursive'
    if panose is not None and int(getattr(panose, 'bFamilyType', 0)) == 2:
        style = int(getattr(panose, 'bSerifStyle', 0))
        if 11 <= style <= 13:
            return 'sans-serif'
        if 2 <= style <= 10:
            return 'serif'
    ibm = (int(getattr(os2, 'sFamilyClass', 0)) >> 8) if os2 is not None else 0
    if ibm == 8:
        return 'sans-serif'
    if 1 <= ibm <= 7:
        return 'serif'
    if ibm == 10:
        return 'cursive'
    return ''


def coverage_ranges(codepoints):
    """Sorted codepoints as a flat list of inclusive ranges
    ``[lo0, hi0, lo1, hi1, ...]``.

    >>> coverage_ranges([65, 66, 67, 70, 32])
    [32, 32, 65, 67, 70, 70]
    """
    out = []
    for c in sorted(codepoints):
        if out and c == out[-1] + 1:
            out[-1] = c
        else:
            out += [c, c]
    return out


def _faces_of(path, fonts):
    faces, cover = [], []
    for index, f in enumerate(fonts):
        if 'name' not in f or 'head' not in f:
            continue
        name = f['name']
        fams = []
        for nid in (16, 1):
            rec = name.getDebugName(nid)
            if rec and rec not in fams:
                fams.append(rec)
        for rec in name.names:
            if rec.nameID in (1, 16):
                try:
                    s = rec.toUnicode()
                except Exception:       # undecodable records are skipped
                    continue
                if s and s not in fams:
                    fams.append(s)
        if not fams:
            continue
        weight, style, stretch = 400, 'normal', 5
        if 'OS/2' in f:
            os2 = f['OS/2']
            weight = int(os2.usWeightClass) or 400
            if weight < 10:             # some old fonts store 1..9
                weight *= 100
            weight = min(max(weight, 1), 1000)
            stretch = min(max(int(os2.usWidthClass), 1), 9)
            sel = int(os2.fsSelection)
            if sel & 1:
                style = 'italic'
            elif sel & (1 << 9):
                style = 'oblique'
        elif int(f['head'].macStyle) & 2:
            style = 'italic'
        color = any(t in f for t in ('COLR', 'sbix', 'CBDT', 'SVG '))
        cmap = f.getBestCmap() or {}
        if not cmap and not any(t in f for t in ('glyf', 'CFF ', 'CFF2')):
            continue
        faces.append(FontFace(path, index, tuple(fams), weight, style, stretch,
                              name.getDebugName(4) or '', name.getDebugName(6) or '',
                              _generic_of(f, fams, color), color))
        cover.append(coverage_ranges(cmap.keys()))
    return faces, cover


def scan_faces(path, data=None):
    """``(faces, coverage)`` of a font file (or of its ``data``): a list of
    :class:`FontFace` and, for each, its character coverage as flat
    inclusive ranges (:func:`coverage_ranges`).

    Raises
    ------
    FontError
        The file is not a usable font (see :func:`check_font_data`).
    """
    from fontTools.ttLib import TTCollection, TTFont
    if data is None:
        data = read_font_bytes(path)
    kind = check_font_data(data)
    with quiet_fonttools() as messages:
        try:
            if kind == 'ttc':
                fonts = list(TTCollection(io.BytesIO(data), lazy=True).fonts)
            else:
                fonts = [TTFont(io.BytesIO(data), lazy=True)]
            faces, cover = _faces_of(path, fonts)
        except Exception as e:      # fontTools raises many kinds on bad files
            raise FontError(_one_line(e) if not messages else
                            '%s (%s)' % (_one_line(e), _one_line(messages[-1]))) from None
    if not faces:
        raise FontError('no usable face (no names or no glyphs)')
    return faces, cover
