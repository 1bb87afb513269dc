"""The fonts of a :class:`~raster.fonts.FontOptions`, and CSS font matching
over them (:class:`FontDB`).

Matching follows CSS Fonts level 4 (section 5.2, the font matching
algorithm) in this form:

1. The families of a ``font-family`` list are tried in order.  A generic
   keyword (``serif``, ``sans-serif``, ``monospace``, ``cursive``,
   ``fantasy``, ``system-ui``, ``emoji``, ``math`` and the ``ui-*``
   keywords) resolves to the overriding family of the options, else to
   the first installed family of its preference list
   (:data:`GENERIC_PREFERENCES`, fontconfig's defaults extended with the
   common macOS and Windows families), else to an installed family whose
   faces are of that class (fixed pitch for ``monospace``; PANOSE, the IBM
   class and the name for the others).  A named family that is not
   installed may be replaced by a metric-compatible one
   (:data:`METRIC_ALIASES`: Arial and Helvetica by Liberation Sans or
   Arimo, Times New Roman by Liberation Serif or Tinos, Courier New by
   Liberation Mono or Cousine, ...).
2. When no family of the list is available: the generic class of the
   first family of the list whose class is known (``Fira Code`` is
   monospace, ``Arial`` sans-serif), then the default family, then
   ``serif``, then any face.
3. Within the chosen family: the closest stretch, then the style (italic,
   else oblique, else normal; oblique prefers oblique, then italic), then
   the weight by the CSS rule (400 looks at 500 first, 500 at 400, lighter
   weights look lighter first, heavier ones heavier first).

Characters the chosen face has no glyph for are taken from another face
(:meth:`FontDB.fallback_face`): faces of the same generic class first,
then all others, in scan order, skipping faces whose style, weight and
stretch all differ from the base face (usvg's rule).

When no usable font exists at all, the bundled Noto Sans (ASCII only,
SIL Open Font License; ``raster/fonts/NotoSans-Regular-ASCII.ttf``) is the
one face (:attr:`FontDB.bundled_only`), so text is never left blank.
"""

import os
import re
import time

from .discovery import ScanCache, font_files, system_font_dirs, warn_bad_fonts
from .files import FontFace, scan_faces
from .options import FontOptions

__all__ = ['FontDB', 'GENERIC_PREFERENCES', 'METRIC_ALIASES', 'FAMILY_CLASSES',
           'BUNDLED_FONT', 'parse_font_family', 'generic_keyword', 'cached']

#: The bundled fallback font (SIL OFL 1.1, its licence beside it).
BUNDLED_FONT = os.path.join(os.path.dirname(os.path.abspath(__file__)),
                            'NotoSans-Regular-ASCII.ttf')

_SERIF = ('DejaVu Serif', 'Noto Serif', 'Liberation Serif', 'Tinos', 'Times New Roman', 'Times',
          'Nimbus Roman', 'Nimbus Roman No9 L', 'TeX Gyre Termes', 'FreeSerif', 'Georgia',
          'Bitstream Vera Serif', 'Cambria', 'Source Serif 4', 'Source Serif Pro',
          'Droid Serif', 'Noto Serif CJK SC', 'Noto Serif CJK JP')
_SANS = ('DejaVu Sans', 'Noto Sans', 'Liberation Sans', 'Arimo', 'Arial', 'Helvetica',
         'Helvetica Neue', 'Nimbus Sans', 'Nimbus Sans L', 'TeX Gyre Heros', 'FreeSans',
         'Verdana', 'Bitstream Vera Sans', 'Segoe UI', 'Roboto', 'Open Sans', 'Cantarell',
         'Ubuntu', 'Source Sans 3', 'Source Sans Pro', 'Droid Sans', 'Tahoma',
         'Noto Sans CJK SC', 'Noto Sans CJK JP')
_MONO = ('DejaVu Sans Mono', 'Noto Sans Mono', 'Noto Mono', 'Liberation Mono', 'Cousine',
         'Courier New', 'Menlo', 'Monaco', 'Consolas', 'SF Mono', 'Nimbus Mono PS',
         'Nimbus Mono L', 'TeX Gyre Cursor', 'FreeMono', 'Bitstream Vera Sans Mono',
         'Ubuntu Mono', 'Source Code Pro', 'Fira Mono', 'Fira Code', 'JetBrains Mono',
         'Cascadia Mono', 'Inconsolata', 'Droid Sans Mono', 'Courier',
         'Noto Sans Mono CJK SC')

#: Generic family keyword -> installed families tried in order.
GENERIC_PREFERENCES = {
    'serif': _SERIF,
    'sans-serif': _SANS,
    'monospace': _MONO,
    'cursive': ('Comic Sans MS', 'Comic Neue', 'TeX Gyre Chorus', 'Z003', 'URW Chancery L',
                'Apple Chancery', 'Brush Script MT', 'Segoe Script', 'Purisa', 'Yellowtail'),
    'fantasy': ('Impact', 'Papyrus', 'Copperplate', 'Luminari', 'Chalkduster', 'Jokerman',
                'Sedgwick Ave Display'),
    'system-ui': ('Cantarell', 'Segoe UI', 'System Font', '.SF NS', 'San Francisco', 'Ubuntu',
                  'Noto Sans', 'DejaVu Sans') + _SANS,
    'emoji': ('Noto Color Emoji', 'Apple Color Emoji', 'Segoe UI Emoji', 'Twemoji',
              'Twitter Color Emoji', 'JoyPixels', 'EmojiOne Color', 'Symbola'),
    'math': ('DejaVu Math TeX Gyre', 'STIX Two Math', 'Cambria Math', 'Latin Modern Math',
             'TeX Gyre Termes Math', 'Noto Sans Math'),
    'ui-serif': _SERIF, 'ui-sans-serif': _SANS, 'ui-monospace': _MONO,
    'ui-rounded': _SANS,
}
# the class whose faces a generic keyword falls back to
_GENERIC_CLASS = {'system-ui': 'sans-serif', 'ui-serif': 'serif', 'ui-sans-serif': 'sans-serif',
                  'ui-monospace': 'monospace', 'ui-rounded': 'sans-serif', 'math': 'serif'}

#: Named family (lower case) -> metric-compatible substitutes.
METRIC_ALIASES = {
    'arial': ('Liberation Sans', 'Arimo'),
    'helvetica': ('Liberation Sans', 'Arimo', 'Nimbus Sans', 'Nimbus Sans L', 'TeX Gyre Heros'),
    'helvetica neue': ('Liberation Sans', 'Arimo', 'Nimbus Sans'),
    'arial narrow': ('Liberation Sans Narrow', 'Nimbus Sans Narrow'),
    'times new roman': ('Liberation Serif', 'Tinos'),
    'times': ('Liberation Serif', 'Tinos', 'Nimbus Roman', 'Nimbus Roman No9 L',
              'TeX Gyre Termes'),
    'courier new': ('Liberation Mono', 'Cousine'),
    'courier': ('Liberation Mono', 'Cousine', 'Nimbus Mono PS', 'Nimbus Mono L',
                'TeX Gyre Cursor'),
    'calibri': ('Carlito',),
    'cambria': ('Caladea',),
    'georgia': ('Gelasio',),
    'palatino': ('TeX Gyre Pagella', 'P052', 'URW Palladio L'),
    'palatino linotype': ('TeX Gyre Pagella', 'P052'),
    'book antiqua': ('TeX Gyre Pagella', 'P052'),
    'century schoolbook': ('TeX Gyre Schola', 'C059'),
    'bookman': ('TeX Gyre Bonum', 'URW Bookman'),
    'zapf chancery': ('TeX Gyre Chorus', 'Z003'),
}

#: Named family (lower case) -> its generic class, for families that are
#: not installed (step 2 of the matching).
FAMILY_CLASSES = {
    **{f.lower(): 'serif' for f in _SERIF}, **{f.lower(): 'sans-serif' for f in _SANS},
    **{f.lower(): 'monospace' for f in _MONO},
    'arial narrow': 'sans-serif', 'calibri': 'sans-serif', 'trebuchet ms': 'sans-serif',
    'lucida grande': 'sans-serif', 'lucida sans unicode': 'sans-serif', 'inter': 'sans-serif',
    'lato': 'sans-serif', 'montserrat': 'sans-serif', 'fira sans': 'sans-serif',
    'palatino': 'serif', 'palatino linotype': 'serif', 'book antiqua': 'serif',
    'garamond': 'serif', 'baskerville': 'serif', 'century schoolbook': 'serif',
    'bookman': 'serif',
    'lucida console': 'monospace', 'andale mono': 'monospace', 'cascadia code': 'monospace',
    'hack': 'monospace', 'iosevka': 'monospace',
    'comic sans ms': 'cursive', 'zapf chancery': 'cursive', 'impact': 'fantasy',
    **{f: 'sans-serif' for f in ('myriad', 'myriad pro', 'frutiger', 'humnst777 bt',
                                 'humanist 777', 'futura', 'gill sans', 'gill sans mt', 'optima',
                                 'univers', 'avenir', 'avenir next', 'franklin gothic',
                                 'century gothic', 'lucida sans', 'segoe ui', 'sf pro',
                                 'source sans pro', 'noto sans', 'pt sans', 'istok web')},
    **{f: 'serif' for f in ('minion', 'minion pro', 'caslon', 'bodoni', 'didot', 'rockwell',
                            'pt serif', 'charter', 'constantia', 'cochin')},
}

_STRETCH = {'ultra-condensed': 1, 'extra-condensed': 2, 'condensed': 3,
            'semi-condensed': 4, 'normal': 5, 'semi-expanded': 6, 'expanded': 7,
            'extra-expanded': 8, 'ultra-expanded': 9}

#: Font descriptions matched remembered per :class:`FontDB`.
_MATCH_LIMIT = 4096
#: How often (seconds) a process-wide FontDB checks its folders for changes.
_REVALIDATE_S = 2.0


def cached(cache, key, make, limit):
    """``cache[key]``, made by ``make()`` when missing; the dict is emptied
    once it holds more than ``limit`` entries (a bound, not an LRU)."""
    value = cache.get(key)
    if value is None:
        value = make()
        if len(cache) > limit:
            cache.clear()
        cache[key] = value
    return value


def parse_font_family(value):
    """Split a CSS ``font-family`` value into a list of names.

    Quoted names keep their inner spaces; unquoted names have runs of
    whitespace collapsed.  Empty entries are dropped.  Generic keywords
    stay as written (unquoted); a quoted keyword is a family name and
    keeps its quotes' meaning by being returned with a leading ``"``
    removed only when it is not a keyword.

    >>> parse_font_family("'Times New Roman',  Noto   Serif, monospace")
    ['Times New Roman', 'Noto Serif', 'monospace']
    """
    out = []
    for m in re.finditer(r'\s*(?:"([^"]*)"|\'([^\']*)\'|([^,]*))\s*(?:,|$)', value or ''):
        q = m.group(1) if m.group(1) is not None else m.group(2)
        if q is not None:
            name = q.strip()
        else:
            name = ' '.join((m.group(3) or '').split())
        if name:
            out.append(name)
    return out


def generic_keyword(name):
    """The generic keyword ``name`` is (lower case), or None."""
    low = name.lower()
    return low if low in GENERIC_PREFERENCES else None


def _class_of_name(name):
    low = name.lower()
    if low in GENERIC_PREFERENCES:
        return _GENERIC_CLASS.get(low, low)
    c = FAMILY_CLASSES.get(low)
    if c is not None:
        return c
    if re.search(r'\b(mono|code|courier|consol)', low):
        return 'monospace'
    if re.search(r'\b(sans|gothic|grotesk|grotesque|humnst|humanist|myriad)', low):
        return 'sans-serif'
    if re.search(r'\bserif\b', low):
        return 'serif'
    return None


class FontDB:
    """The faces of some font folders and files, and CSS matching over them.

    Parameters
    ----------
    dirs : sequence of str
        Folders scanned recursively (missing ones are skipped).
    system : bool
        Also scan the system's font folders (see
        :func:`~raster.fonts.discovery.system_font_dirs`).
    generic : dict, optional
        Generic keyword -> family name overriding the preference lists.
    files : sequence of str
        Individual font files.
    default_family : str or None
        Family for text whose list names nothing available (None: serif).
    cache : bool
        Use the persistent scan cache (False: scan in this process only).

    Attributes
    ----------
    faces : list of FontFace
        Every usable face, in scan order.
    bundled_only : bool
        No usable font was found: ``faces`` is the bundled Noto Sans.
    errors : list of (str, str)
        Font files that were skipped and why (each also warned once).

    >>> FontDB(['/nonexistent'], cache=False).bundled_only
    True
    """

    def __init__(self, dirs=(), system=False, generic=None, files=(), default_family=None,
                 cache=False):
        self.generic = {k.lower(): v for k, v in (generic or {}).items()}
        self.default_family = default_family
        roots = [os.fspath(d) for d in (dirs or ())]
        if system:
            roots += system_font_dirs()
        self._scan = ScanCache(persistent=cache)
        paths, self._walked = font_files(roots, files or ())
        self._stamp = self._dir_stamp()
        self._checked = time.monotonic()
        faces, self.errors = self._scan.faces(paths)
        warn_bad_fonts(self.errors, set())
        self.bundled_only = not faces
        if not faces:
            faces, _ = scan_faces(BUNDLED_FONT)
        self._set_faces(faces)

    def _set_faces(self, faces):
        self.faces = list(faces)
        self._by_family = {}
        self._matches = {}
        self._fallbacks = {}
        self._coverage = {}
        self._generic_memo = {}
        for f in self.faces:
            for fam in f.families:
                lst = self._by_family.setdefault(fam.lower(), [])
                if f not in lst:
                    lst.append(f)

    @classmethod
    def for_options(cls, options):
        """The process-wide FontDB of a :class:`~raster.fonts.FontOptions`
        (made on first use; its folders are checked for changes at most
        every few seconds)."""
        options = FontOptions.coerce(options)
        db = _DBS.get(options)
        if db is not None:
            now = time.monotonic()
            if now - db._checked < _REVALIDATE_S:
                return db
            db._checked = now
            if db._dir_stamp() == db._stamp:
                return db
        db = cls(options.dirs, options.system, options.generic_overrides(), options.files,
                 options.default_family, options.cache)
        if len(_DBS) > 16:
            _DBS.clear()
        _DBS[options] = db
        return db

    def _dir_stamp(self):
        out = []
        for d in self._walked:
            try:
                out.append(os.stat(d).st_mtime_ns)
            except OSError:
                out.append(None)
        return out

    # -- families ---------------------------------------------------------------

    def family_faces(self, family):
        """Faces of one family name (a generic keyword resolved), maybe
        empty."""
        g = generic_keyword(family)
        if g is not None:
            family = self.resolve_generic(g)
            if family is None:
                return []
        return self._by_family.get(family.lower(), [])

    def resolve_generic(self, keyword):
        """The installed family a generic keyword resolves to, or None."""
        keyword = keyword.lower()
        memo = self._generic_memo
        if keyword in memo:
            return memo[keyword]
        r = None
        over = self.generic.get(keyword)
        if over is not None:
            r = over if over.lower() in self._by_family else None
            if r is None and generic_keyword(over) and generic_keyword(over) != keyword:
                r = self.resolve_generic(over)
        if r is None and over is None:
            for fam in GENERIC_PREFERENCES.get(keyword, ()):
                if fam.lower() in self._by_family:
                    r = fam
                    break
            if r is None:
                r = self._family_of_class(_GENERIC_CLASS.get(keyword, keyword))
            if r is None and keyword in ('cursive', 'fantasy', 'system-ui', 'emoji'):
                r = self.resolve_generic('sans-serif') if keyword != 'emoji' else None
        memo[keyword] = r
        return r

    def _family_of_class(self, cls):
        """The installed family with faces of generic class ``cls`` whose
        face is closest to a regular one, or None."""
        best = None
        for f in self.faces:
            if f.generic != cls:
                continue
            key = (f.style != 'normal', abs(f.weight - 400), abs(f.stretch - 5), f.family.lower())
            if best is None or key < best[0]:
                best = (key, f.family)
        return None if best is None else best[1]

    def _named(self, fam):
        cands = self._by_family.get(fam.lower())
        if cands:
            return cands
        for alt in METRIC_ALIASES.get(fam.lower(), ()):
            cands = self._by_family.get(alt.lower())
            if cands:
                return cands
        return None

    # -- matching -----------------------------------------------------------------

    def match(self, families, weight=400, style='normal', stretch='normal'):
        """The best :class:`FontFace` for a CSS font description.

        Parameters
        ----------
        families : sequence of str
            ``font-family`` list (see :func:`parse_font_family`).
        weight : int
            1..1000.
        style : str
            'normal', 'italic' or 'oblique'.
        stretch : str or int
            CSS keyword or 1..9.

        Returns
        -------
        FontFace
            Never None: some face always matches (the bundled one at
            worst).
        """
        if isinstance(stretch, str):
            stretch = _STRETCH.get(stretch, 5)
        key = (tuple(families), int(weight), style, int(stretch))
        return cached(self._matches, key, lambda: self._match(*key), _MATCH_LIMIT)

    def match_family(self, families):
        """The faces of the first available family of a list (step 1 of the
        matching), or None."""
        for fam in families:
            g = generic_keyword(fam)
            cands = self.family_faces(fam) if g is not None else self._named(fam)
            if cands:
                return cands
        return None

    def _match(self, families, weight, style, stretch):
        cands = self.match_family(families)
        if cands is None:
            for fam in families:
                cls = _class_of_name(fam)
                if cls is not None:
                    cands = self.family_faces(cls)
                    break
        if not cands and self.default_family:
            cands = self.match_family([self.default_family])
            if not cands:
                cls = _class_of_name(self.default_family)
                cands = self.family_faces(cls) if cls else None
        if not cands:
            cands = self.family_faces('serif')
        if not cands:
            cands = self.faces
        return best_face(cands, weight, style, stretch)

    # -- per-character fallback -----------------------------------------------------

    def coverage(self, face):
        """The characters ``face`` maps, as a sorted (2K,) int64 array of
        inclusive ranges ``lo0, hi0, lo1, hi1, ...`` (from the scan cache,
        else from the font itself; empty when it cannot be read)."""
        ranges = self._coverage.get(face)
        if ranges is None:
            import numpy as np
            ranges = self._scan.coverage(face)
            if ranges is None:
                try:
                    _, cover = scan_faces(face.path)
                    ranges = cover[face.index] if face.index < len(cover) else []
                except Exception:       # unreadable now: covers nothing
                    ranges = []
            ranges = self._coverage[face] = np.asarray(ranges, np.int64)
        return ranges

    def has_char(self, face, cp):
        """True when ``face`` maps codepoint ``cp`` (see :meth:`coverage`)."""
        ranges = self.coverage(face)
        if not len(ranges):
            return False
        import numpy as np
        i = int(np.searchsorted(ranges, cp, 'right'))
        return i % 2 == 1 or (i > 0 and ranges[i - 1] == cp)

    def fallback_face(self, face, ch):
        """Another face with a glyph for character ``ch`` when ``face`` has
        none, or None: faces of ``face``'s generic class first, then the
        rest, in scan order; faces whose style, weight and stretch all
        differ from ``face`` are skipped."""
        key = (face, ch)
        if key in self._fallbacks:
            return self._fallbacks[key]
        cp = ord(ch)
        r = None
        for same in (True, False):
            for f in self.faces:
                if f == face or (f.generic == face.generic) != same:
                    continue
                if f.style != face.style and f.weight != face.weight and \
                        f.stretch != face.stretch:
                    continue
                if self.has_char(f, cp):
                    r = f
                    break
            if r is not None:
                break
        if len(self._fallbacks) > 10000:
            self._fallbacks.clear()
        self._fallbacks[key] = r
        return r

    def fallback_faces(self, face):
        """Other faces, in the order :meth:`fallback_face` tries them."""
        same = [f for f in self.faces if f != face and f.generic == face.generic]
        return same + [f for f in self.faces if f != face and f.generic != face.generic]

    # -- document fonts --------------------------------------------------------------

    def local_face(self, name):
        """The face whose full name or PostScript name is ``name`` (case
        insensitive; ``@font-face`` ``local()``), or None."""
        table = self.__dict__.get('_local')
        if table is None:
            table = {}
            for f in self.faces:
                for n in (f.full_name, f.postscript_name):
                    if n and n.lower() not in table:
                        table[n.lower()] = f
            self._local = table
        return table.get(name.strip().lower())

    def with_faces(self, faces, coverage):
        """This FontDB with more faces: a document's ``@font-face`` fonts.

        Parameters
        ----------
        faces : sequence of FontFace
            Their families hide installed families of the same name (CSS
            Fonts: the document's faces come first); per-character fallback
            tries them after the installed faces.  The faces of a family
            any of which has a ``unicode_range`` are listed last first.
        coverage : sequence of list of int
            Each face's characters as flat inclusive ranges
            (:func:`~raster.fonts.files.coverage_ranges`).

        Returns
        -------
        FontDB
            ``self`` for no faces; otherwise a derived FontDB, the same one
            for the same faces (remembered, a few per FontDB).
        """
        import copy
        import numpy as np
        key = tuple(faces)
        if not key:
            return self
        memo = self.__dict__.setdefault('_derived', {})
        db = memo.get(key)
        if db is None:
            db = copy.copy(self)
            db._derived = {}
            db._local = None
            db._set_faces(self.faces + [f for f in key if f not in self.faces])
            own = {}
            for f in key:
                for fam in f.families:
                    lst = own.setdefault(fam.lower(), [])
                    if f not in lst:
                        lst.append(f)
            for fam, lst in own.items():
                if any(f.unicode_range for f in lst):
                    # a family split by unicode-range: the last rule is
                    # checked first for a character (CSS Fonts 4, 4.5)
                    lst.reverse()
            db._by_family.update(own)
            db._coverage = dict(self._coverage)
            for f, ranges in zip(key, coverage):
                db._coverage[f] = np.asarray(ranges, np.int64)
            if len(memo) > 16:
                memo.clear()
            memo[key] = db
        return db

    # -- listing ----------------------------------------------------------------------

    def describe(self):
        """Lines for ``--list-fonts``: every face (family, style, weight,
        stretch, class, file) and what each generic keyword resolves to."""
        lines = []
        if self.bundled_only:
            lines.append('no usable fonts found: text uses the bundled Noto Sans (ASCII only)')
        lines.append('%d faces:' % len(self.faces))
        for f in sorted(self.faces, key=lambda f: (f.family.lower(), f.weight, f.style,
                                                   f.stretch)):
            lines.append('  %s | %s %d %s | %s | %s%s' % (
                f.family, f.style, f.weight, _STRETCH_NAME[f.stretch], f.generic or '-',
                f.path, '' if not f.index else ' #%d' % f.index))
        lines.append('generic families:')
        for g in ('serif', 'sans-serif', 'monospace', 'cursive', 'fantasy', 'system-ui',
                  'emoji', 'math'):
            face = self.match([g])
            fam = self.resolve_generic(g)
            lines.append('  %-10s -> %s (%s)' % (g, fam or face.family, face.path))
        face = self.match([])
        lines.append('  %-10s -> %s (%s)' % ('default', face.family, face.path))
        return lines


_STRETCH_NAME = {v: k for k, v in _STRETCH.items()}
_DBS = {}


def best_face(cands, weight, style, stretch):
    """The face of ``cands`` (one family's faces) closest to a weight,
    style and stretch by the CSS Fonts rules (see the module docstring)."""
    def sdist(f):
        d = f.stretch - stretch
        if stretch <= 5:
            return (d > 0, abs(d))
        return (d < 0, abs(d))
    best_s = min(sdist(f) for f in cands)
    cands = [f for f in cands if sdist(f) == best_s]
    order = {'italic': ('italic', 'oblique', 'normal'),
             'oblique': ('oblique', 'italic', 'normal')}.get(style, ('normal', 'oblique', 'italic'))
    for s in order:
        sub = [f for f in cands if f.style == s]
        if sub:
            cands = sub
            break

    def wkey(f):
        w = f.weight
        if w == weight:
            return (0, 0)
        if 400 <= weight <= 500 and weight < w <= 500:
            return (1, w - weight)
        if weight < 400 or (weight <= 500 and w < weight):
            # lighter first (descending), then heavier (ascending)
            return (2, weight - w) if w < weight else (3, w - weight)
        # heavier first (ascending), then lighter (descending)
        return (2, w - weight) if w > weight else (3, weight - w)
    return min(cands, key=wkey)


def memory_face(key, data):
    """The faces of a font given as bytes (``@font-face`` data), keyed by
    ``key`` (a ``memory:`` path)."""
    faces, cover = scan_faces(key, data)
    return faces, cover


__all__ += ['best_face', 'FontFace']
