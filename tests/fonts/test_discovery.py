"""Font discovery, the persistent scan cache, safe reading of bad fonts, and
matching rules on a temporary font folder of renamed faces."""
import io
import json
import os
import shutil
import struct
import warnings

import pytest
from fontTools.ttLib import TTFont

from raster.errors import RasterWarning
from raster.fonts import FontDB, FontError, FontOptions, BUNDLED_FONT
from raster.fonts import discovery, files
from raster.fonts.files import check_font_data, scan_faces

from _shared import SUITE_FONTS as FONTS


def renamed(src, dst, family, mono=None, weight=None, italic=None):
    """Copy font ``src`` to ``dst`` with another family name (and fixed
    pitch flag, weight, italic bit)."""
    tt = TTFont(os.path.join(FONTS, src))
    name = tt['name']
    for rec in list(name.names):
        if rec.nameID in (1, 4, 6, 16):
            name.removeNames(nameID=rec.nameID)
    name.setName(family, 1, 3, 1, 0x409)
    name.setName(family, 4, 3, 1, 0x409)
    name.setName(family.replace(' ', ''), 6, 3, 1, 0x409)
    if mono is not None:
        tt['post'].isFixedPitch = int(mono)
    if weight is not None:
        tt['OS/2'].usWeightClass = weight
    if italic:
        tt['OS/2'].fsSelection |= 1
    tt.save(str(dst))
    return str(dst)


@pytest.fixture
def folder(tmp_path):
    d = tmp_path / 'fonts'
    d.mkdir()
    return d


# -- the scan cache -------------------------------------------------------------------

def test_cache_is_written_atomically_and_reused(folder, tmp_path, monkeypatch):
    monkeypatch.setenv('RASTER_CACHE_DIR', str(tmp_path / 'cache'))
    shutil.copy(os.path.join(FONTS, 'NotoSans-Regular.ttf'), folder)
    a = discovery.ScanCache()
    faces, errors = a.faces([str(folder / 'NotoSans-Regular.ttf')])
    assert [f.family for f in faces] == ['Noto Sans'] and errors == []
    cached = json.load(open(tmp_path / 'cache' / 'fonts-v1.json'))
    assert cached['format'] == 1 and str(folder / 'NotoSans-Regular.ttf') in cached['files']
    assert not [n for n in os.listdir(tmp_path / 'cache') if n.endswith('.tmp')]
    # a second process reads the cache: no scan
    calls = []
    monkeypatch.setattr(discovery, 'scan_faces', lambda p: calls.append(p) or scan_faces(p))
    b = discovery.ScanCache()
    assert b.faces([str(folder / 'NotoSans-Regular.ttf')])[0] == faces
    assert calls == []
    assert b.coverage(faces[0])[:2] == [32, 126] or b.coverage(faces[0])[0] <= 32


def test_changed_file_is_scanned_again(folder, tmp_path, monkeypatch):
    """The key is path, size and modification time."""
    monkeypatch.setenv('RASTER_CACHE_DIR', str(tmp_path / 'cache'))
    p = renamed('NotoSans-Regular.ttf', folder / 'x.ttf', 'First Family')
    assert discovery.ScanCache().faces([p])[0][0].family == 'First Family'
    renamed('NotoSans-Regular.ttf', folder / 'x.ttf', 'Second Family Longer')
    os.utime(p, ns=(1, 10 ** 9))
    assert discovery.ScanCache().faces([p])[0][0].family == 'Second Family Longer'


@pytest.mark.parametrize('content', [b'', b'{', b'[]', b'{"format": 1, "files": {"x": 3}}',
                                     b'{"format": 99, "files": {}}', b'\xff\xfe'])
def test_corrupt_or_foreign_cache_is_ignored(folder, tmp_path, monkeypatch, content):
    monkeypatch.setenv('RASTER_CACHE_DIR', str(tmp_path / 'cache'))
    os.makedirs(tmp_path / 'cache')
    (tmp_path / 'cache' / 'fonts-v1.json').write_bytes(content)
    p = str(shutil.copy(os.path.join(FONTS, 'NotoMono-Regular.ttf'), folder))
    faces, _ = discovery.ScanCache().faces([p])
    assert faces[0].family == 'Noto Mono' and faces[0].generic == 'monospace'
    # and it was rewritten valid
    assert json.load(open(tmp_path / 'cache' / 'fonts-v1.json'))['format'] == 1


def test_a_stale_entry_with_the_same_key_shape_is_rescanned(folder, tmp_path, monkeypatch):
    monkeypatch.setenv('RASTER_CACHE_DIR', str(tmp_path / 'cache'))
    p = str(shutil.copy(os.path.join(FONTS, 'NotoMono-Regular.ttf'), folder))
    st = os.stat(p)
    os.makedirs(tmp_path / 'cache')
    bad = {'format': 1, 'files': {p: [st.st_size, st.st_mtime_ns, [['garbage']], None]}}
    (tmp_path / 'cache' / 'fonts-v1.json').write_text(json.dumps(bad))
    assert discovery.ScanCache().faces([p])[0][0].family == 'Noto Mono'


def test_unwritable_cache_folder_is_not_an_error(folder, tmp_path, monkeypatch):
    blocker = tmp_path / 'file'
    blocker.write_text('x')
    monkeypatch.setenv('RASTER_CACHE_DIR', str(blocker / 'cache'))
    p = str(shutil.copy(os.path.join(FONTS, 'NotoMono-Regular.ttf'), folder))
    assert discovery.ScanCache().faces([p])[0][0].family == 'Noto Mono'


def test_concurrent_writers_leave_a_valid_cache(folder, tmp_path):
    """Processes scanning at once each replace the file whole."""
    import subprocess
    import sys
    for fn in ('NotoSans-Regular.ttf', 'NotoSerif-Regular.ttf', 'NotoMono-Regular.ttf'):
        shutil.copy(os.path.join(FONTS, fn), folder)
    env = dict(os.environ, RASTER_CACHE_DIR=str(tmp_path / 'cache'))
    code = ('from raster.fonts import FontDB; import sys; '
            'print(len(FontDB([sys.argv[1]], cache=True).faces))')
    procs = [subprocess.Popen([sys.executable, '-c', code, str(folder)], env=env,
                              stdout=subprocess.PIPE) for _ in range(4)]
    outs = [p.communicate(timeout=120)[0].strip() for p in procs]
    assert outs == [b'3'] * 4
    d = json.load(open(tmp_path / 'cache' / 'fonts-v1.json'))
    assert len(d['files']) == 3


def test_fontconfig_dirs_follow_includes(tmp_path, monkeypatch):
    monkeypatch.setenv('XDG_DATA_HOME', str(tmp_path / 'data'))
    conf = tmp_path / 'fonts.conf'
    (tmp_path / 'conf.d').mkdir()
    conf.write_text('<fontconfig><dir>/opt/fonts-a</dir><!-- <dir>/not</dir> -->'
                    '<dir prefix="xdg">fonts</dir><include>conf.d</include></fontconfig>')
    (tmp_path / 'conf.d' / '10-x.conf').write_text('<fontconfig><dir>~/myfonts</dir>'
                                                   '</fontconfig>')
    dirs = discovery.fontconfig_dirs(str(conf))
    assert dirs == ['/opt/fonts-a', str(tmp_path / 'data' / 'fonts'),
                    os.path.expanduser('~/myfonts')]


# -- bad fonts -------------------------------------------------------------------------

def _woff2_bomb():
    """A WOFF2 header declaring a 1 KB font whose Brotli stream inflates to
    64 MB."""
    import brotli
    payload = brotli.compress(b'\0' * (64 << 20))
    tables = bytes([1]) + bytes([0x88, 0x00])       # tag index 1 (head), length 1024
    head = struct.pack('>4s4sIHHIIHHIIIII', b'wOF2', b'\x00\x01\x00\x00', 0, 1, 0, 1024,
                       len(payload), 1, 0, 0, 0, 0, 0, 0)
    data = head + tables + payload
    return data[:8] + struct.pack('>I', len(data)) + data[12:]


@pytest.mark.parametrize('make, why', [
    (lambda: b'not a font at all', 'not a font'),
    (lambda: open(os.path.join(FONTS, 'NotoSans-Regular.ttf'), 'rb').read()[:5000], 'truncated'),
    (lambda: _woff2_bomb(), 'inflates'),
    (lambda: b'wOFF' + b'\0' * 12 + struct.pack('>I', 1 << 31) + b'\0' * 24, 'declares'),
])
def test_bad_font_is_skipped_with_one_warning_each(folder, make, why):
    (folder / 'bad.woff2').write_bytes(make())
    shutil.copy(os.path.join(FONTS, 'NotoSans-Regular.ttf'), folder)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter('always')
        db = FontDB([str(folder)])
    msgs = [str(x.message) for x in w if issubclass(x.category, RasterWarning)]
    assert len(msgs) == 1 and 'bad.woff2' in msgs[0] and why in msgs[0], msgs
    assert [f.family for f in db.faces] == ['Noto Sans']


def test_huge_table_beyond_the_file_is_refused(folder):
    data = bytearray(open(os.path.join(FONTS, 'NotoMono-Regular.ttf'), 'rb').read())
    struct.pack_into('>I', data, 12 + 12, 1 << 30)      # first table's length: 1 GB
    with pytest.raises(FontError, match='beyond'):
        check_font_data(bytes(data))


def test_fonttools_log_records_do_not_reach_stderr(folder, capfd):
    """A font fontTools complains about (a bad checksum adjustment) is read
    with its log captured."""
    import logging
    data = bytearray(open(os.path.join(FONTS, 'NotoMono-Regular.ttf'), 'rb').read())
    struct.pack_into('>I', data, 12 + 4, 0xDEADBEEF)    # a table checksum
    (folder / 'odd.ttf').write_bytes(bytes(data))
    logging.getLogger('fontTools').setLevel(logging.DEBUG)
    try:
        FontDB([str(folder)])
    finally:
        logging.getLogger('fontTools').setLevel(logging.NOTSET)
    assert capfd.readouterr().err == ''
    assert logging.getLogger('fontTools').propagate


def test_woff_and_woff2_load_and_shape(folder):
    from raster.fonts import Font
    tt = TTFont(os.path.join(FONTS, 'NotoSans-Regular.ttf'))
    for flavor in ('woff', 'woff2'):
        tt.flavor = flavor
        tt.save(str(folder / ('n.' + flavor)))
    db = FontDB([str(folder)])
    assert len(db.faces) == 2
    for face in db.faces:
        f = Font.load(face)
        assert [g[0] for g in f.shape('Hi')] == [43, 76] or len(f.shape('Hi')) == 2


# -- matching on a temporary folder ------------------------------------------------------

def test_generic_families_take_installed_preferences_and_classes(folder):
    renamed('NotoSans-Regular.ttf', folder / 'a.ttf', 'Aaa Display')        # alphabetically first
    renamed('NotoSans-Regular.ttf', folder / 'ds.ttf', 'DejaVu Sans')
    renamed('NotoSerif-Regular.ttf', folder / 'dse.ttf', 'Some Book Serif')
    renamed('NotoMono-Regular.ttf', folder / 'm.ttf', 'Zed Typewriter', mono=True)
    db = FontDB([str(folder)])
    assert db.match(['sans-serif']).family == 'DejaVu Sans'          # preference list
    assert db.match(['serif']).family == 'Some Book Serif'            # class from the name
    assert db.match(['monospace']).family == 'Zed Typewriter'         # fixed pitch
    assert db.match(['Fira Code', 'monospace']).family == 'Zed Typewriter'
    # a missing family of known class, at the end of the list: its class
    assert db.match(['Fira Code']).family == 'Zed Typewriter'
    assert db.match(['arial']).family == 'DejaVu Sans'
    assert db.match(['No Such Face']).family == 'Some Book Serif'     # default: serif


def test_metric_aliases(folder):
    renamed('NotoSans-Regular.ttf', folder / 'ls.ttf', 'Liberation Sans')
    renamed('NotoSerif-Regular.ttf', folder / 'tinos.ttf', 'Tinos')
    renamed('NotoMono-Regular.ttf', folder / 'cous.ttf', 'Cousine', mono=True)
    db = FontDB([str(folder)])
    for fam, want in (('Arial', 'Liberation Sans'), ('Helvetica', 'Liberation Sans'),
                      ('Times New Roman', 'Tinos'), ('Courier New', 'Cousine')):
        assert db.match([fam]).family == want, fam


def test_overrides_and_default_family(folder):
    renamed('NotoSans-Regular.ttf', folder / 'a.ttf', 'Alpha')
    renamed('NotoSerif-Regular.ttf', folder / 'b.ttf', 'Beta')
    db = FontDB([str(folder)], generic={'monospace': 'Beta'}, default_family='Alpha')
    assert db.match(['monospace']).family == 'Beta'
    assert db.match(['Nope']).family == 'Alpha'


def test_weight_and_style_rules_on_one_family(folder):
    for w in (300, 400, 600, 900):
        renamed('NotoSans-Regular.ttf', folder / ('w%d.ttf' % w), 'Fam', weight=w)
    renamed('NotoSans-Regular.ttf', folder / 'i.ttf', 'Fam', weight=400, italic=True)
    db = FontDB([str(folder)])
    assert db.match(['Fam'], 500).weight == 400          # 500: 400 first (below 500)
    assert db.match(['Fam'], 700).weight == 900          # heavier first
    assert db.match(['Fam'], 350).weight == 300          # lighter first
    assert db.match(['Fam'], 400, 'italic').style == 'italic'
    assert db.match(['Fam'], 400, 'oblique').style == 'italic'


def test_per_character_fallback_prefers_the_same_class(folder):
    renamed('NotoSans-Regular.ttf', folder / 'base.ttf', 'Base Sans')
    renamed('Amiri-Regular.ttf', folder / 'am.ttf', 'Amiri Serif')
    renamed('NotoSansDevanagari-Regular.ttf', folder / 'dv.ttf', 'Deva Sans')
    db = FontDB([str(folder)])
    base = db.match(['Base Sans'])
    assert db.fallback_face(base, '\u0915').family == 'Deva Sans'      # Devanagari KA
    assert db.fallback_face(base, '\u0627').family == 'Amiri Serif'    # Arabic ALEF
    assert db.fallback_face(base, '\U0001F600') is None


def test_no_fonts_gives_the_bundled_face(tmp_path):
    db = FontDB([str(tmp_path)])
    assert db.bundled_only and db.faces[0].path == BUNDLED_FONT
    assert 'bundled' in db.describe()[0]


def test_system_fonts_resolve_generic_classes_by_advance_widths():
    """On this machine's (or CI's) own fonts: monospace has equal advances
    for 'i' and 'W', the sans-serif and serif faces do not."""
    from raster.fonts import Font
    db = FontDB.for_options(FontOptions())
    assert not db.bundled_only, 'the machine has fonts (DejaVu on CI)'
    mono = Font.load(db.match(['monospace']))
    adv = [g[2] for g in mono.shape('iW')]
    assert adv[0] == adv[1]
    for g in ('sans-serif', 'serif'):
        f = Font.load(db.match([g]))
        a = [x[2] for x in f.shape('iW')]
        assert a[0] < a[1], g
    assert db.match(['sans-serif']).generic == 'sans-serif'
    assert db.match(['serif']).generic == 'serif'


@pytest.mark.parametrize('xdg', [None, '', '   ', '/tmp/some cache'])
def test_cache_dir_is_platformdirs_answer_on_linux(monkeypatch, xdg):
    # on Linux computed without importing platformdirs (whose unix module
    # imports tempfile, shutil, bz2 and lzma): the same folder; elsewhere
    # platformdirs' own answer
    import platformdirs
    monkeypatch.delenv('RASTER_CACHE_DIR', raising=False)
    monkeypatch.delenv('ANDROID_DATA', raising=False)
    if xdg is None:
        monkeypatch.delenv('XDG_CACHE_HOME', raising=False)
    else:
        monkeypatch.setenv('XDG_CACHE_HOME', xdg)
    assert discovery.cache_dir() == platformdirs.user_cache_dir('raster', appauthor=False)
