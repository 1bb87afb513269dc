"""Where fonts are found, and the persistent scan cache.

Font folders, in order: the ``dirs`` a caller names, the system's font
folders (unless ``system=False``): the usual Linux, macOS and Windows
locations and every ``<dir>`` of the fontconfig configuration when one
exists (``/etc/fonts/fonts.conf`` and the files it includes); individual
``files`` are added after the folders.  Folders are walked recursively in
sorted order; every file whose name ends in one of
:data:`~raster.fonts.files.FONT_EXTENSIONS` is a candidate.

The scan cache remembers what :func:`~raster.fonts.files.scan_faces`
found in each file, keyed by the file's path, size and modification time,
so a one-shot command does not parse hundreds of fonts every run.  It is
two JSON files in the user cache folder (``$XDG_CACHE_HOME/raster`` on
Linux, the platform's equivalent elsewhere, through platformdirs; the
environment variable ``RASTER_CACHE_DIR`` names another folder):
``fonts-v1.json`` (the faces, read on every run) and
``font-coverage-v1.json`` (character coverage, read only when a character
needs a fallback font).  Writes go to a temporary file in the same folder
renamed over the old one (:func:`os.replace`), so concurrent processes
never see a partial file; a corrupt, foreign or stale cache is ignored
and rebuilt.  A cache folder that cannot be written is not an error: the
scan is simply not remembered.
"""

import json
import os
import re
import sys
import warnings

from ..errors import RasterWarning
from .files import FONT_EXTENSIONS, FontError, FontFace, scan_faces

__all__ = ['system_font_dirs', 'fontconfig_dirs', 'font_files', 'ScanCache', 'cache_dir']

_FORMAT = 1
_FACES_FILE = 'fonts-v%d.json' % _FORMAT
_COVERAGE_FILE = 'font-coverage-v%d.json' % _FORMAT


def _platform_dirs():
    home = os.path.expanduser('~')
    if sys.platform == 'darwin':
        return ['/System/Library/Fonts', '/Library/Fonts', os.path.join(home, 'Library/Fonts'),
                '/Network/Library/Fonts']
    if sys.platform.startswith('win'):
        windir = os.environ.get('WINDIR', 'C:\\Windows')
        local = os.environ.get('LOCALAPPDATA', os.path.join(home, 'AppData', 'Local'))
        return [os.path.join(windir, 'Fonts'), os.path.join(local, 'Microsoft', 'Windows', 'Fonts')]
    data_home = os.environ.get('XDG_DATA_HOME') or os.path.join(home, '.local', 'share')
    data_dirs = (os.environ.get('XDG_DATA_DIRS') or '/usr/local/share:/usr/share').split(':')
    out = [os.path.join(data_home, 'fonts'), os.path.join(home, '.fonts')]
    out += [os.path.join(d, 'fonts') for d in data_dirs if d]
    return out


_DIR_RE = re.compile(r'<dir\b([^>]*)>\s*([^<]*?)\s*</dir>', re.S)
_INCLUDE_RE = re.compile(r'<include\b([^>]*)>\s*([^<]*?)\s*</include>', re.S)


def _fc_path(attrs, text, base):
    text = text.strip()
    if not text:
        return None
    if 'prefix="xdg"' in attrs:
        data_home = os.environ.get('XDG_DATA_HOME') or os.path.join(os.path.expanduser('~'),
                                                                   '.local', 'share')
        return os.path.join(data_home, text)
    if text.startswith('~'):
        return os.path.expanduser(text)
    if 'prefix="relative"' in attrs or not os.path.isabs(text):
        return os.path.join(base, text)
    return text


def fontconfig_dirs(conf='/etc/fonts/fonts.conf'):
    """The ``<dir>`` folders of a fontconfig configuration (following its
    ``<include>`` files and folders, at most 200 files); empty when there
    is no configuration."""
    out, seen, todo = [], set(), [conf]
    while todo and len(seen) < 200:
        p = todo.pop(0)
        if p in seen:
            continue
        seen.add(p)
        if os.path.isdir(p):
            try:
                todo[:0] = [os.path.join(p, f) for f in sorted(os.listdir(p)) if f.endswith('.conf')]
            except OSError:
                pass
            continue
        try:
            with open(p, encoding='utf-8', errors='replace') as fh:
                text = fh.read(1 << 20)
        except OSError:
            continue
        base = os.path.dirname(p)
        text = re.sub(r'<!--.*?-->', '', text, flags=re.S)
        for attrs, body in _DIR_RE.findall(text):
            d = _fc_path(attrs, body, base)
            if d and d not in out:
                out.append(d)
        for attrs, body in _INCLUDE_RE.findall(text):
            d = _fc_path(attrs, body, base)
            if d:
                todo.append(d)
    return out


def system_font_dirs():
    """The system's font folders that exist: the platform's usual
    locations and fontconfig's configured ones, without duplicates (a
    folder inside another listed one is dropped)."""
    dirs = []
    for d in _platform_dirs() + fontconfig_dirs():
        d = os.path.normpath(d)
        if d not in dirs and os.path.isdir(d):
            dirs.append(d)
    real = [os.path.realpath(d) for d in dirs]
    keep = []
    for d, r in zip(dirs, real):
        if any(r != o and r.startswith(o.rstrip(os.sep) + os.sep) for o in real):
            continue
        if r in [os.path.realpath(k) for k in keep]:
            continue
        keep.append(d)
    return keep


def font_files(dirs, files=()):
    """``(font files, folders walked)``: every font file below ``dirs``
    (walked recursively, sorted, symlinked folders followed once) and the
    given ``files``, without duplicates."""
    out, seen, walked = [], set(), []
    visited = set()
    for root in dirs:
        root = os.fspath(root)
        if not os.path.isdir(root):
            continue
        for dirpath, dirnames, filenames in os.walk(root, followlinks=True):
            try:
                key = os.stat(dirpath).st_ino, os.stat(dirpath).st_dev
            except OSError:
                dirnames[:] = []
                continue
            if key in visited:
                dirnames[:] = []
                continue
            visited.add(key)
            walked.append(dirpath)
            dirnames.sort()
            for fn in sorted(filenames):
                if fn.lower().endswith(FONT_EXTENSIONS):
                    p = os.path.join(dirpath, fn)
                    if p not in seen:
                        seen.add(p)
                        out.append(p)
    for f in files:
        p = os.path.abspath(os.fspath(f))
        if p not in seen:
            seen.add(p)
            out.append(p)
    return out, walked


def cache_dir():
    """The folder of the persistent scan cache: ``$RASTER_CACHE_DIR``, else
    the user cache folder of platformdirs (``$XDG_CACHE_HOME/raster``,
    ``~/Library/Caches/raster``, ``%LOCALAPPDATA%\\raster\\Cache``)."""
    d = os.environ.get('RASTER_CACHE_DIR')
    if d:
        return d
    if sys.platform.startswith('linux') and 'ANDROID_DATA' not in os.environ:
        # platformdirs' answer on Linux, without importing it: its unix
        # module imports tempfile (and shutil, bz2, lzma), 7 ms of start-up
        base = os.environ.get('XDG_CACHE_HOME', '').strip() or \
            os.path.join(os.path.expanduser('~'), '.cache')
        return os.path.join(base, 'raster')
    try:
        import platformdirs
        return platformdirs.user_cache_dir('raster', appauthor=False)
    except ImportError:         # platformdirs is a dependency; stay usable without it
        base = os.environ.get('XDG_CACHE_HOME') or os.path.join(os.path.expanduser('~'),
                                                                '.cache')
        return os.path.join(base, 'raster')


def _load_json(path):
    try:
        with open(path, encoding='utf-8') as fh:
            d = json.load(fh)
    except (OSError, ValueError, UnicodeDecodeError):
        return {}
    if not isinstance(d, dict) or d.get('format') != _FORMAT or \
            not isinstance(d.get('files'), dict):
        return {}
    return d['files']


def _write_json(folder, name, files):
    """Write ``{'format', 'files'}`` atomically; False when the folder
    cannot be written (not an error)."""
    import tempfile             # (and shutil, bz2, lzma): only when the cache is written
    try:
        os.makedirs(folder, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix='.' + name + '.', suffix='.tmp', dir=folder)
    except OSError:
        return False
    try:
        with os.fdopen(fd, 'w', encoding='utf-8') as fh:
            json.dump({'format': _FORMAT, 'files': files}, fh, separators=(',', ':'))
        os.replace(tmp, os.path.join(folder, name))
        return True
    except OSError:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        return False


class ScanCache:
    """The faces of font files, remembered across processes.

    Parameters
    ----------
    folder : str or None
        Cache folder (default :func:`cache_dir`); None or ``False`` with
        ``persistent=False``: in memory only.
    persistent : bool
        Read and write the cache files.

    Entries are ``path -> [size, mtime_ns, faces or None, error or None]``
    in the faces file and ``path -> [size, mtime_ns, [ranges per face]]``
    in the coverage file.  A file whose entry does not match its current
    size and modification time is scanned again.
    """

    def __init__(self, folder=None, persistent=True):
        self.persistent = bool(persistent)
        self.folder = (folder or cache_dir()) if self.persistent else None
        self._faces = _load_json(os.path.join(self.folder, _FACES_FILE)) if self.persistent \
            else {}
        self._coverage = None        # loaded on first use
        self._new_cover = {}
        self._dirty = False

    def faces(self, paths):
        """``(faces, errors)``: the :class:`FontFace` list of every path (in
        order) and ``[(path, message)]`` for files that are not usable
        fonts.  Files changed since they were cached are scanned again,
        and the cache files are rewritten when anything changed."""
        out, errors = [], []
        for p in paths:
            try:
                st = os.stat(p)
            except OSError:
                continue
            size, mt = st.st_size, st.st_mtime_ns
            rec = self._faces.get(p)
            if not (isinstance(rec, list) and len(rec) == 4 and rec[0] == size and rec[1] == mt):
                rec = self._scan(p, size, mt)
            try:
                faces = [FontFace.from_json(p, r) for r in (rec[2] or ())]
            except (TypeError, ValueError):         # a foreign entry: scan again
                rec = self._scan(p, size, mt)
                faces = [FontFace.from_json(p, r) for r in (rec[2] or ())]
            if rec[3]:
                errors.append((p, rec[3]))
            out.extend(faces)
        self.flush()
        return out, errors

    def _scan(self, p, size, mt):
        try:
            faces, cover = scan_faces(p)
            rec = [size, mt, [f.to_json() for f in faces], None]
            self._new_cover[p] = [size, mt, cover]
        except FontError as e:
            rec = [size, mt, None, str(e)]
        self._faces[p] = rec
        self._dirty = True
        return rec

    def coverage(self, face):
        """Character coverage of a face as flat inclusive ranges (see
        :func:`~raster.fonts.files.coverage_ranges`), or None when unknown
        (the caller then reads the font)."""
        rec = self._new_cover.get(face.path)
        if rec is None:
            if self._coverage is None:
                self._coverage = _load_json(os.path.join(self.folder, _COVERAGE_FILE)) \
                    if self.persistent else {}
            rec = self._coverage.get(face.path)
        try:
            st = os.stat(face.path)
            if rec[0] != st.st_size or rec[1] != st.st_mtime_ns:
                return None
            return rec[2][face.index]
        except (OSError, TypeError, IndexError, KeyError):
            return None

    def flush(self):
        """Write the cache files when something changed (entries of files
        that no longer exist are dropped then)."""
        if not self._dirty or not self.persistent:
            self._dirty = False
            return
        self._dirty = False
        faces = {p: r for p, r in self._faces.items() if os.path.exists(p)}
        if not _write_json(self.folder, _FACES_FILE, faces):
            return
        cover = _load_json(os.path.join(self.folder, _COVERAGE_FILE))
        cover.update(self._new_cover)
        cover = {p: r for p, r in cover.items() if p in faces}
        _write_json(self.folder, _COVERAGE_FILE, cover)
        self._coverage = cover


def warn_bad_fonts(errors, seen):
    """One :class:`~raster.errors.RasterWarning` per unusable font file not
    in ``seen`` (a set, updated)."""
    for p, msg in errors:
        if p not in seen:
            seen.add(p)
            warnings.warn('font file %s skipped: %s' % (p, msg), RasterWarning, stacklevel=4)
