"""What a document makes raster import (issue 17): the modules behind text,
filters, images and the other element families load with the first
element that needs them, so a plain document renders without fontTools,
uharfbuzz, the filter machinery or Pillow, and the commands import nothing
heavy (not even numpy) before they have parsed their arguments.

Each check runs in a fresh interpreter and lists the modules it ended with;
the positive checks (a filter loads the filter modules, text loads the
fonts, an image loads Pillow) show that the listing sees them."""

import base64
import io
import json
import os
import subprocess
import sys
import textwrap

import pytest
from PIL import Image

from _shared import SUITE_FONTS

#: The paint servers' classes (tree and parser): loaded by the first url() paint.
SERVERS = ('raster.tree.servers', 'raster.parser.servers')
MESH = ('raster.parser.mesh', 'raster.pixels.mesh', 'raster.geometry.patches')
FILTERS = ('raster.parser.filters', 'raster.renderer.filters', 'raster.pixels.effects',
           'raster.tree.filter')
#: Loaded only by documents that need them.
HEAVY = ('fontTools', 'uharfbuzz', 'PIL', 'raster.fonts.font', 'raster.fonts.matching',
         'raster.fonts.discovery', 'raster.fonts.color', 'raster.parser.text',
         'raster.parser.fontface', 'raster.parser.images', 'raster.parser.imageload',
         'raster.parser.markers', 'raster.parser.clipmask',
         'raster.fonts.files') + FILTERS + MESH + SERVERS
#: Modules of numpy and the standard library a plain document does not need.
LIGHT_EXTRAS = ('numpy.ma', 'numpy.typing', 'logging', 'threading', 'hashlib', '_hashlib',
                'tempfile', 'shutil')

SVG = '<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10">%s</svg>'
RECT = '<rect x="2" y="2" width="6" height="6" fill="red" stroke="blue"/>'


def modules_after(code):
    """Sorted names in ``sys.modules`` after running ``code`` in a fresh
    interpreter (which prints nothing else)."""
    prog = code + '\nimport sys, json\nprint(json.dumps(sorted(sys.modules)))\n'
    out = subprocess.run([sys.executable, '-c', prog], capture_output=True, text=True,
                         check=True, cwd=os.path.dirname(os.path.abspath(__file__)))
    return set(json.loads(out.stdout.strip().splitlines()[-1]))


def loaded(mods, names):
    """The entries of ``names`` that are modules (or packages) in ``mods``."""
    return sorted(n for n in names if any(m == n or m.startswith(n + '.') for m in mods))


def render_code(doc, **kw):
    return textwrap.dedent('''
        import raster
        img = raster.render(%r%s)
        assert img.shape[2] == 4
    ''') % (doc.encode(), ''.join(', %s=%r' % kv for kv in kw.items()))


def test_import_raster_loads_no_numpy():
    mods = modules_after('import raster, raster.errors')
    assert 'numpy' not in mods
    assert loaded(mods, ('raster.geometry', 'raster.parser', 'raster.renderer')) == []


def test_a_plain_document_loads_nothing_heavy():
    mods = modules_after(render_code(SVG % (RECT + '<g opacity="0.5">%s</g>' % RECT)))
    assert 'raster.renderer.draw' in mods and 'lxml.etree' in mods
    assert loaded(mods, HEAVY) == []
    # nor what only some documents need from numpy and the standard library:
    # masked arrays (np.unique imports them), numpy.typing (annotations
    # only), logging (fontTools' log lines become warnings), threading
    # (thread pools of large renders), OpenSSL's hashes (@font-face data)
    assert loaded(mods, LIGHT_EXTRAS) == []


def test_the_command_on_a_plain_document_loads_nothing_heavy(tmp_path):
    src = tmp_path / 'in.svg'
    src.write_text(SVG % RECT)
    mods = modules_after(textwrap.dedent('''
        from raster_cli.rasterize import main
        assert main([%r, %r]) == 0
    ''') % (str(src), str(tmp_path / 'out.png')))
    assert 'raster.renderer.draw' in mods
    # nor the network and temporary-file modules of the standard library
    assert loaded(mods, HEAVY + LIGHT_EXTRAS + ('urllib.request', 'http', 'email')) == []
    assert (tmp_path / 'out.png').read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'


@pytest.mark.parametrize('argv', [['--version'], ['--help'], [], ['in.svg']])
def test_the_command_imports_no_numpy_before_its_arguments_are_read(argv):
    mods = modules_after(textwrap.dedent('''
        import contextlib, io
        from raster_cli.rasterize import main
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            try:
                main(%r)
            except SystemExit:
                pass
    ''') % (argv,))
    assert loaded(mods, ('numpy', 'lxml', 'raster.parser', 'raster.renderer')) == []


def test_a_filter_loads_the_filter_modules():
    doc = SVG % ('<filter id="f"><feGaussianBlur stdDeviation="1"/></filter>'
                 '<rect width="6" height="6" filter="url(#f)"/>')
    mods = modules_after(render_code(doc))
    assert loaded(mods, FILTERS) == sorted(FILTERS)
    assert loaded(mods, ('fontTools', 'uharfbuzz', 'PIL')) == []


def test_a_mesh_gradient_loads_the_mesh_modules():
    patch = ''.join('<stop stop-color="%s" path="%s"/>' % sp for sp in (
        ('red', 'l 8,0'), ('blue', 'l 0,6'), ('lime', 'l -8,0'), ('black', 'l 0,-6')))
    doc = SVG % ('<meshgradient id="m" gradientUnits="userSpaceOnUse" x="1" y="1">'
                 '<meshrow><meshpatch>%s</meshpatch></meshrow></meshgradient>'
                 '<rect width="10" height="8" fill="url(#m) lime"/>' % patch)
    mods = modules_after(render_code(doc))
    assert loaded(mods, MESH) == sorted(MESH)
    assert loaded(mods, FILTERS + ('raster.fonts.files', 'fontTools', 'PIL')) == []


def test_text_loads_the_fonts():
    doc = SVG % '<text x="1" y="8" font-family="Noto Sans" font-size="8">Hi</text>'
    mods = modules_after(render_code(doc, font_dirs=[SUITE_FONTS]))
    # (fontTools only if this run scanned the fonts: the scan cache may be cold)
    assert loaded(mods, ('uharfbuzz', 'raster.fonts', 'raster.parser.text')) == [
        'raster.fonts', 'raster.parser.text', 'uharfbuzz']
    assert loaded(mods, FILTERS) == []
    # colour glyphs and the image loading of @font-face sources load with
    # the first colour font and the first rule
    assert loaded(mods, ('raster.fonts.color', 'raster.parser.imageload', 'PIL')) == []
    # text without @font-face data maps no OpenSSL (hashlib's 3 MB of RSS);
    # the font scan cache, once written, is read without tempfile
    assert loaded(mods, ('hashlib', '_hashlib')) == []
    mods = modules_after(render_code(doc, font_dirs=[SUITE_FONTS]))
    assert loaded(mods, ('hashlib', '_hashlib', 'tempfile', 'shutil')) == []
    # nor logging: fontTools, whose records the text converter turns into
    # warnings, is not loaded (raster.errors.log_warnings)
    assert 'logging' not in mods
    # with the scan cached, plain text (TrueType outlines, no colour
    # tables) is shaped, measured and drawn by HarfBuzz alone
    assert 'uharfbuzz' in mods and loaded(mods, ('fontTools',)) == []


@pytest.mark.parametrize('family', ['Source Sans Pro', 'Roboto Flex', 'Sedgwick Ave Display'])
def test_plain_text_does_not_load_fonttools(family):
    # CFF outlines (Source Sans Pro is a .ttf here: the .otf of the suite
    # holds sbix too), a variable font at another weight, TrueType
    doc = SVG % ('<text x="1" y="8" font-family="%s" font-weight="700" font-size="8" '
                 'stroke="red" text-decoration="underline">Hi 12</text>' % family)
    modules_after(render_code(doc, font_dirs=[SUITE_FONTS]))       # (the scan cache)
    mods = modules_after(render_code(doc, font_dirs=[SUITE_FONTS]))
    assert 'raster.parser.text' in mods and 'uharfbuzz' in mods
    assert loaded(mods, ('fontTools', 'raster.fonts.color')) == []


def test_a_colour_font_loads_fonttools():
    doc = SVG % ('<text x="1" y="8" font-family="Noto Color Emoji" font-size="8">'
                 '\U0001F600</text>')
    modules_after(render_code(doc, font_dirs=[SUITE_FONTS]))
    mods = modules_after(render_code(doc, font_dirs=[SUITE_FONTS]))
    assert loaded(mods, ('fontTools', 'raster.fonts.color')) == ['fontTools', 'raster.fonts.color']


def test_text_finds_the_font_cache_folder_without_platformdirs_on_linux(tmp_path):
    # the user cache folder ($XDG_CACHE_HOME here, not the suite's
    # RASTER_CACHE_DIR) found as platformdirs would, without importing it
    doc = SVG % '<text x="1" y="8" font-family="Noto Sans" font-size="8">Hi</text>'
    code = ('import os\nos.environ.pop("RASTER_CACHE_DIR", None)\n'
            'os.environ["XDG_CACHE_HOME"] = %r\n' % str(tmp_path))
    mods = modules_after(code + render_code(doc, font_dirs=[SUITE_FONTS]))
    assert 'raster.fonts.discovery' in mods
    assert (tmp_path / 'raster').is_dir()               # the scan cache went there
    assert loaded(mods, ('platformdirs',)) == ([] if sys.platform.startswith('linux')
                                              else ['platformdirs'])


def test_an_image_loads_pillow():
    buf = io.BytesIO()
    Image.new('RGBA', (2, 2), (0, 255, 0, 255)).save(buf, 'PNG')
    uri = 'data:image/png;base64,' + base64.b64encode(buf.getvalue()).decode()
    doc = SVG % ('<image width="4" height="4" href="%s"/>' % uri)
    mods = modules_after(render_code(doc))
    assert 'PIL' in mods and 'raster.parser.images' in mods
    assert loaded(mods, FILTERS + ('fontTools', 'uharfbuzz')) == []


def test_markers_and_clip_paths_load_their_modules():
    doc = SVG % ('<marker id="m" markerWidth="2" markerHeight="2"><rect width="1" height="1"/>'
                 '</marker><clipPath id="c"><circle cx="5" cy="5" r="4"/></clipPath>'
                 '<path d="M1 1h8v8" stroke="black" marker-end="url(#m)" clip-path="url(#c)"/>')
    mods = modules_after(render_code(doc))
    assert loaded(mods, ('raster.parser.markers', 'raster.parser.clipmask')) == [
        'raster.parser.clipmask', 'raster.parser.markers']
    # solid paints in markers load no paint servers
    assert loaded(mods, SERVERS) == []


@pytest.mark.parametrize('server', [
    '<linearGradient id="p"><stop offset="0" stop-color="red"/><stop offset="1"/></linearGradient>',
    '<radialGradient id="p"><stop offset="0" stop-color="red"/><stop offset="1"/></radialGradient>',
    '<pattern id="p" width="2" height="2" patternUnits="userSpaceOnUse">'
    '<rect width="1" height="1"/></pattern>'])
def test_a_paint_server_loads_the_server_modules(server):
    doc = SVG % (server + '<rect width="10" height="8" stroke="url(#p)" fill="url(#p) lime"/>')
    mods = modules_after(render_code(doc))
    assert loaded(mods, SERVERS) == sorted(SERVERS)
    assert loaded(mods, FILTERS + MESH + ('raster.fonts.files', 'fontTools', 'PIL')) == []


def test_a_url_to_something_else_loads_no_paint_servers():
    # a url() paint whose target is not a paint server uses its fallback
    doc = SVG % '<g id="g"/><rect width="10" height="8" fill="url(#g) red" stroke="url(#none)"/>'
    mods = modules_after(render_code(doc))
    assert 'raster.renderer.draw' in mods and loaded(mods, SERVERS) == []


def test_the_tree_exports_the_server_classes_on_first_use():
    mods = modules_after('import raster.tree')
    assert loaded(mods, SERVERS) == []
    mods = modules_after(textwrap.dedent('''
        import raster.tree, raster.tree.paint, raster.tree.servers as s
        from raster.tree import LinearGradient, Paint
        assert LinearGradient is s.LinearGradient is raster.tree.paint.LinearGradient
        assert Paint is raster.tree.paint.Paint and raster.tree.SpreadMethod is s.SpreadMethod
        assert set(Paint.__args__) == {raster.tree.SolidPaint, LinearGradient, s.RadialGradient,
                                       s.SweepGradient, s.Pattern, s.MeshGradient}
        for name in raster.tree.__all__:
            getattr(raster.tree, name)
        for name in raster.tree.paint.__all__:
            getattr(raster.tree.paint, name)
    '''))
    assert 'raster.tree.servers' in mods and 'raster.parser.servers' not in mods


PATTERNS = textwrap.dedent('''
    import raster.parser.css, raster.parser.document, raster.parser.context
    from raster._regex import LazyPattern
    for m in (raster.parser.css, raster.parser.document, raster.parser.context):
        print(m.__name__, sorted(k for k, v in vars(m).items() if isinstance(v, LazyPattern)))
''')


def test_a_plain_document_compiles_none_of_the_css_patterns():
    out = subprocess.run([sys.executable, '-c', render_code(SVG % RECT) + PATTERNS],
                         capture_output=True, text=True, check=True).stdout
    lines = dict(line.split(' ', 1) for line in out.strip().splitlines())
    assert '_IDENT_RE' in lines['raster.parser.css'] and '_IMPORT_RE' in lines['raster.parser.css']
    assert '_XLINK_HREF_IN_DTD' in lines['raster.parser.document']
    assert '_LANG_TAG' in lines['raster.parser.context']
    # a style sheet with selectors compiles what it uses
    styled = SVG % ('<style>rect.a { fill: blue }</style><rect class="a" width="4" height="4"/>')
    out = subprocess.run([sys.executable, '-c', render_code(styled) + PATTERNS],
                         capture_output=True, text=True, check=True).stdout
    lines = dict(line.split(' ', 1) for line in out.strip().splitlines())
    assert '_IDENT_RE' not in lines['raster.parser.css']
