"""``@font-face`` rules: a document's own fonts.

:func:`document_font_db` reads the document's ``@font-face`` rules
(:func:`raster.parser.css.font_face_rules`) and returns the FontDB its
text is matched against: the options' fonts plus one face per rule whose
``src`` gives a usable font, under the rule's ``font-family`` (which hides
an installed family of that name) and its ``font-weight``,
``font-style`` and ``font-stretch`` descriptors (the font's own values
where a descriptor is missing or ``auto``; the first value of a range).

``src`` entries are tried in order, the first usable one wins:

* ``local(name)`` -- an installed face by full name or PostScript name;
* ``url(...)`` -- a ``data:`` URI or a file, read by the rules of images
  (:func:`raster.parser.imageload.read_reference`: relative to the
  document, only from the allowed directories, no network); TrueType,
  OpenType, collections (the first face), WOFF and WOFF2 (checked and
  inflated with bounds, :mod:`raster.fonts.files`).  Entries whose
  ``format()`` names only other formats (``embedded-opentype``, ``svg``)
  are skipped.

A network URL or a missing ``local()`` face is skipped silently (a
browser offline does the same: the next source, then the next family of
``font-family``); a refused or missing file or bad font data warns once
per family.

``unicode-range`` (CSS Fonts 4, section 4.5) restricts a face to the code
points of its ranges (:func:`raster.fonts.ranges.parse_unicode_range`; an
invalid value is ignored: every code point): other characters are not
shaped with it and go to the per-character fallback, which tries the
family's other faces with the same weight, style and stretch (the last
rule first, as CSS orders a family's faces that differ in their ranges),
then the next families of ``font-family``, then every face.
"""

import re

from ..fonts import FontError, generic_keyword, parse_font_family, register_memory_font
from ..fonts.files import scan_faces
from ..fonts.font import memory_font_data
from ..fonts.ranges import MAX_CODE_POINT, intersect_ranges, parse_unicode_range
from .css import font_face_rules

__all__ = ['document_font_db', 'parse_src']

_FORMATS = {'woff', 'woff2', 'truetype', 'opentype', 'collection', 'font-collection'}
_STYLE = {'normal': 'normal', 'italic': 'italic', 'oblique': 'oblique'}
_STRETCH = {'ultra-condensed': 1, 'extra-condensed': 2, 'condensed': 3, 'semi-condensed': 4,
            'normal': 5, 'semi-expanded': 6, 'expanded': 7, 'extra-expanded': 8,
            'ultra-expanded': 9}
_ITEM = re.compile(r"""\s*(local|url)\(\s*(?:"([^"]*)"|'([^']*)'|([^)]*?))\s*\)\s*(.*)$""",
                   re.I | re.S)
_FORMAT = re.compile(r"""format\(([^)]*)\)""", re.I)
#: Scans of fonts given as bytes, by their memory key (bounded).
_SCANS = {}


def _split(value):
    """Split a ``src`` value at top-level commas."""
    out, depth, quote, start = [], 0, None, 0
    for i, ch in enumerate(value):
        if quote:
            if ch == quote:
                quote = None
        elif ch in '"\'':
            quote = ch
        elif ch == '(':
            depth += 1
        elif ch == ')':
            depth = max(depth - 1, 0)
        elif ch == ',' and depth == 0:
            out.append(value[start:i])
            start = i + 1
    out.append(value[start:])
    return [s for s in out if s.strip()]


def parse_src(value):
    """The entries of a ``src`` descriptor: ``('local', name)`` or
    ``('url', reference, formats)`` (formats: a tuple of lower-case
    names, empty when not given); entries that do not parse are dropped.

    >>> parse_src('local("Fira Code"), url(a.woff2) format("woff2"), url("b.ttf")')
    [('local', 'Fira Code'), ('url', 'a.woff2', ('woff2',)), ('url', 'b.ttf', ())]
    """
    out = []
    for item in _split(value or ''):
        m = _ITEM.match(item)
        if m is None:
            continue
        arg = next(g for g in m.group(2, 3, 4) if g is not None).strip()
        if m.group(1).lower() == 'local':
            if arg:
                out.append(('local', arg))
            continue
        formats = ()
        f = _FORMAT.search(m.group(5) or '')
        if f is not None:
            formats = tuple(x.strip().strip('"\'').lower() for x in f.group(1).split(','))
        if arg:
            out.append(('url', arg, formats))
    return out


def _weight(value, own):
    v = (value or 'auto').split()
    if not v or v[0] == 'auto':
        return own
    if v[0] == 'normal':
        return 400
    if v[0] == 'bold':
        return 700
    try:
        w = float(v[0])
    except ValueError:
        return own
    return int(w) if 1 <= w <= 1000 else own


def _style(value, own):
    v = (value or 'auto').split()
    return _STYLE.get(v[0].lower(), own) if v else own


def _stretch(value, own):
    v = (value or 'auto').split()
    if not v:
        return own
    k = v[0].lower()
    if k in _STRETCH:
        return _STRETCH[k]
    if k.endswith('%'):
        try:
            pct = float(k[:-1])
        except ValueError:
            return own
        marks = (50, 62.5, 75, 87.5, 100, 112.5, 125, 150, 200)
        return 1 + min(range(9), key=lambda i: abs(marks[i] - pct))
    return own


def _unicode_range(value):
    """The ``unicode_range`` of a rule's face: () for every code point
    (no descriptor, an invalid one, or one covering everything)."""
    if value is None:
        return ()
    ranges = parse_unicode_range(value)
    if ranges is None or ranges == (0, MAX_CODE_POINT):
        return ()
    return ranges


def _scan_bytes(data):
    """``(faces, coverage)`` of font bytes (registered as a memory font)."""
    key = register_memory_font(data)
    r = _SCANS.get(key)
    if r is None:
        r = scan_faces(key, memory_font_data(key))
        if len(_SCANS) > 64:
            _SCANS.clear()
        _SCANS[key] = r
    return r


def _face_of(rule, family, db, cache):
    """``(FontFace, coverage)`` of the first usable source of a rule, or
    None."""
    import dataclasses
    # (imported here: text without @font-face rules loads no image loading)
    from .imageload import ImageError, image_source, is_network_reference, read_reference
    problems = []
    for entry in parse_src(rule.get('src', '')):
        if entry[0] == 'local':
            face = db.local_face(entry[1])
            if face is None:
                continue
            cover = db.coverage(face)
        else:
            href, formats = entry[1], entry[2]
            if formats and not any(f in _FORMATS for f in formats):
                continue
            if is_network_reference(href):
                continue
            try:
                data = read_reference(href, image_source(cache.options), 'font')
                faces, covers = _scan_bytes(data)
            except (ImageError, FontError) as e:
                problems.append(str(e))
                continue
            face, cover = faces[0], covers[0]
        ranges = _unicode_range(rule.get('unicode-range'))
        if ranges:
            cover = intersect_ranges(cover, ranges)
        face = dataclasses.replace(
            face, families=(family,), weight=_weight(rule.get('font-weight'), face.weight),
            style=_style(rule.get('font-style'), face.style),
            stretch=_stretch(rule.get('font-stretch'), face.stretch), unicode_range=ranges)
        return face, cover
    if problems:
        cache.warn('font-face-' + family, '@font-face for %r not used: %s'
                   % (family, problems[-1]))
    return None


def document_font_db(db, cache):
    """The FontDB of a document: ``db`` with the faces of its
    ``@font-face`` rules (see the module docstring); ``db`` itself when
    it has none."""
    rules = font_face_rules(cache.root)
    if not rules:
        return db
    faces, cover = [], []
    for rule in rules:
        fams = parse_font_family(rule.get('font-family', ''))
        if len(fams) != 1 or generic_keyword(fams[0]) is not None:
            continue
        r = _face_of(rule, fams[0], db, cache)
        if r is not None:
            faces.append(r[0])
            cover.append(r[1])
    return db.with_faces(faces, cover)
