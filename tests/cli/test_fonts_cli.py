"""The font options of the commands (one argparse helper in
raster_cli._common): --list-fonts, --font-dir/--font-file,
--no-system-fonts, the generic family overrides; text drawn, flattened and
boxed with them."""
import json
import os

import numpy as np
from PIL import Image

from raster_cli import rasterize, svg_bbox, svg_flatten

from _shared import SUITE_FONTS as FONTS

DOC = ('<svg xmlns="http://www.w3.org/2000/svg" width="200" height="60">'
       '<text id="t" x="10" y="40" font-size="30" font-family="monospace">Hi</text></svg>')


def test_list_fonts_prints_faces_and_generic_resolution(capsys):
    assert rasterize.main(['--list-fonts', '--no-system-fonts', '--font-dir', FONTS,
                           '--monospace-family', 'Noto Sans']) == 0
    out = capsys.readouterr().out
    assert 'Noto Serif | normal 400 normal | serif' in out
    assert 'monospace  -> Noto Sans' in out


def test_list_fonts_without_fonts_names_the_bundled_face(tmp_path, capsys):
    assert svg_bbox.main(['--list-fonts', '--no-system-fonts', '--font-dir',
                          str(tmp_path)]) == 0
    assert 'bundled Noto Sans' in capsys.readouterr().out


def test_missing_positionals_are_a_usage_error(capsys):
    assert rasterize.main([]) == 2
    assert 'required: input, output' in capsys.readouterr().err


def test_font_file_and_override_change_the_face(tmp_path):
    svg = tmp_path / 'a.svg'
    svg.write_text(DOC)
    out = [tmp_path / 'a.png', tmp_path / 'b.png']
    base = ['--no-system-fonts', '--font-file', os.path.join(FONTS, 'NotoMono-Regular.ttf'),
            '--font-file', os.path.join(FONTS, 'NotoSerif-Regular.ttf')]
    assert rasterize.main([str(svg), str(out[0])] + base) == 0
    assert rasterize.main([str(svg), str(out[1])] + base + ['--monospace-family',
                                                            'Noto Serif']) == 0
    a, b = (np.asarray(Image.open(p)) for p in out)
    assert a[..., 3].any() and b[..., 3].any() and not np.array_equal(a, b)


def test_svg_flatten_and_svg_bbox_see_text(tmp_path, capsys):
    svg = tmp_path / 'a.svg'
    svg.write_text(DOC)
    opts = ['--no-system-fonts', '--font-dir', FONTS]
    assert svg_flatten.main([str(svg), '--format', 'json'] + opts) == 0
    shapes = json.loads(capsys.readouterr().out)
    assert shapes and all(s['polylines'] for s in shapes)
    assert svg_bbox.main([str(svg)] + opts) == 0
    box = json.loads(capsys.readouterr().out)['elements']['t']
    # the glyph outlines of "Hi" at 30 px from x=10 on the baseline y=40
    assert 10 <= box[0] < 14 and box[2] < 10 + 2 * 0.6 * 30 + 1
    assert 15 < box[1] < 20 and box[3] == 40
