"""Tests of the corpus benchmark driver (bench/bench_corpus.py): its pure
helpers, the table builder, and one small end-to-end run with the peers."""

import io
import json
import math

import numpy as np
import pytest
from PIL import Image

from _shared import load_bench


@pytest.fixture(scope='module')
def bc():
    return load_bench('bench_corpus')


def test_geomean_analytic(bc):
    assert math.isclose(bc.geomean([2.0, 8.0]), 4.0)
    assert math.isclose(bc.geomean([0.5, 2.0, 1.0]), 1.0)
    assert bc.geomean([]) is None
    # missing / zero ratios are skipped, not turned into 0 or an exception
    assert math.isclose(bc.geomean([None, 9.0, 0, 1.0]), 3.0)


def test_png_size_reads_ihdr(bc):
    buf = io.BytesIO()
    Image.new('RGBA', (37, 11)).save(buf, format='PNG')
    assert bc._png_size(buf.getvalue()) == (37, 11)
    with pytest.raises(ValueError):
        bc._png_size(b'GIF89a' + bytes(30))


def _cell(times, size=(10, 10), peak=1.0, **kw):
    d = dict(wall=list(times), cpu=[t / 2 for t in times], size=list(size), peak_mb=peak)
    d.update(kw)
    return d


def test_tables_ratios_errors_and_target(bc):
    files = ['/c/a.svg', '/c/b.svg']
    res = {
        ('a.svg', 2000, 'raster'): _cell([1.0, 3.0, 2.0], render_only=[1.5, 1.5, 1.5],
                                          render_only_cpu=[0.7, 0.7, 0.7]),
        ('a.svg', 2000, 'resvg'): _cell([0.5, 0.5, 0.5]),
        ('a.svg', 2000, 'cairosvg'): _cell([4.0, 4.0, 4.0]),
        ('b.svg', 2000, 'raster'): _cell([1.0, 1.0, 1.0]),
        ('b.svg', 2000, 'resvg'): {'error': 'ValueError: broken'},
        ('b.svg', 2000, 'cairosvg'): _cell([2.0, 2.0, 2.0]),
    }
    lines, summary = bc.build_tables(res, files, [2000], list(bc.RENDERERS), 3, 'wall')
    text = '\n'.join(lines)
    row_a = next(line for line in lines if line.startswith('| a.svg'))
    # median 2.0 s -> 2000 ms; ratios 2.0 / 0.5 = 4.00 and 2.0 / 4.0 = 0.50
    assert '| 2000 | 1500 | 500 | 4000 | 4.00 | 0.50 |' in row_a
    row_b = next(line for line in lines if line.startswith('| b.svg'))
    assert '| error |' in row_b
    assert 'b.svg / 2000 / resvg: ValueError: broken' in text
    # geometric means: resvg over a only (4.0), cairosvg over a and b (0.5, 0.5)
    assert math.isclose(summary[(2000, 'resvg')][0], 4.0)
    assert summary[(2000, 'resvg')][1] == 1
    assert math.isclose(summary[(2000, 'cairosvg')][0], 0.5)
    # a is 4x slower than its faster peer (resvg): listed; b (0.5x) is not
    assert 'a.svg (4.0x)' in text and 'b.svg (' not in text
    # the CPU-time table uses the cpu lists
    lines_cpu, summary_cpu = bc.build_tables(res, files, [2000], list(bc.RENDERERS), 3, 'cpu')
    row_a = next(line for line in lines_cpu if line.startswith('| a.svg'))
    assert '| 1000 | 700 | 250 | 2000 | 4.00 | 0.50 |' in row_a


def test_table_flags_fewer_runs_and_size_mismatch(bc):
    res = {('a.svg', 'natural', 'raster'): _cell([70.0], size=(10, 11)),
           ('a.svg', 'natural', 'resvg'): _cell([1.0, 1.0, 1.0])}
    lines, _ = bc.build_tables(res, ['a.svg'], [None], ['raster', 'resvg'], 3, 'wall')
    row = next(line for line in lines if line.startswith('| a.svg'))
    assert '(1 run)' in row
    assert '10x10 vs 10x11' in row


SVG = ('<svg xmlns="http://www.w3.org/2000/svg" width="40" height="20">'
       '<rect x="5" y="5" width="30" height="10" fill="#%s"/></svg>')


def test_end_to_end_peers(bc, tmp_path):
    corpus = tmp_path / 'corpus'
    corpus.mkdir()
    (corpus / 'ok.svg').write_text(SVG % 'f00')
    (corpus / 'broken.svg').write_text('<svg xmlns="http://www.w3.org/2000/svg" width="4"')
    # ISO-8859-1 file: resvg_py's svg_path only reads UTF-8, the driver transcodes
    latin = ('<?xml version="1.0" encoding="iso-8859-1"?>\n'
             + (SVG % '00f').replace('<rect', '<!-- caf\xe9 --><rect'))
    (corpus / 'latin.svg').write_bytes(latin.encode('iso-8859-1'))
    out = tmp_path / 'r.json'
    md = tmp_path / 'r.md'
    save = tmp_path / 'png'
    rc = bc.main(['--corpus', str(corpus), '--renderers', 'resvg,cairosvg', '--repeat', '1',
                  '--widths', 'natural,80', '--json', str(out), '--markdown', str(md),
                  '--save', str(save), '--timeout', '30'])
    assert rc == 0
    res = {(r['file'], r['width'], r['renderer']): r for r in json.load(open(out))['results']}
    for r in ('resvg', 'cairosvg'):
        assert tuple(res[('ok.svg', 'natural', r)]['size']) == (40, 20)
        assert tuple(res[('ok.svg', 80, r)]['size']) == (80, 40)
        assert 'error' in res[('broken.svg', 'natural', r)]
        assert res[('ok.svg', 80, r)]['peak_mb'] >= 0
    assert 'transcoded from iso-8859-1' in res[('latin.svg', 80, 'resvg')]['note']
    # the saved PNG shows the rectangle's colour at its centre
    img = np.asarray(Image.open(save / 'latin_80_resvg.png').convert('RGBA'))
    assert tuple(img[20, 40]) == (0, 0, 255, 255)
    assert '| ok.svg |' in md.read_text()


def _pcell(times, rss, size=(10, 10), tree=None):
    c = dict(wall=list(times), cpu=[t / 2 for t in times], rss_mb=list(rss), size=list(size))
    if tree is not None:
        c['tree_mb'] = tree
    return c


def test_process_tables_against_the_targets(bc):
    files = ['/c/a.svg', '/c/b.svg']
    res = {
        ('a.svg', 2000, 'raster'): _pcell([3.0, 1.0, 2.0], [90, 100, 110], tree=150),
        ('a.svg', 2000, 'resvg'): _pcell([1.0, 1.0, 1.0], [40, 40, 40], tree=30),
        ('a.svg', 2000, 'cairosvg'): _pcell([4.0, 4.0, 4.0], [60, 60, 60]),
        ('b.svg', 2000, 'raster'): _pcell([1.0, 1.0, 1.0], [50, 50, 50]),
        ('b.svg', 2000, 'resvg'): {'error': 'exit status 1: boom'},
        ('b.svg', 2000, 'cairosvg'): _pcell([2.0, 2.0, 2.0], [30, 30, 30]),
    }
    inproc = {('a.svg', 2000, 'raster'): {'wall': [0.5]}}
    lines, summary = bc.build_process_tables(res, files, [2000], list(bc.RENDERERS), 3, inproc)
    text = '\n'.join(lines)
    row_a = next(line for line in lines if line.startswith('| a.svg'))
    # medians 2000 / 1000 / 4000 ms; 2.0x the faster peer; RSS 100 / 40 = 2.5
    # all processes: 150 / 30 MB (5.0x), cairosvg's not sampled
    assert ('| 2000 | 1000 | 4000 | 2.00 | 100 / 40 / 60 | 2.50 | 150 / 30 / - | 5.00 '
            '| 500 / - / - |') in row_a
    row_b = next(line for line in lines if line.startswith('| b.svg'))
    assert '| error |' in row_b and '| 0.50 |' in row_b          # cairosvg is the faster peer
    assert 'b.svg / 2000 / resvg: exit status 1: boom' in text
    g, n = summary[(2000, 'faster_peer')]
    assert n == 2 and math.isclose(g, 1.0)                      # sqrt(2.0 * 0.5)
    assert 'a.svg (2.00x)' in text and 'b.svg (0.50x)' not in text
    g, n, worst = summary[(2000, 'rss_resvg')]
    assert n == 1 and math.isclose(worst, 2.5) and 'a.svg (2.5x)' in text
    g, n, worst = summary[(2000, 'tree_resvg')]
    assert n == 1 and math.isclose(worst, 5.0) and 'a.svg (5.0x)' in text


def test_end_to_end_whole_processes(bc, tmp_path):
    corpus = tmp_path / 'corpus'
    corpus.mkdir()
    (corpus / 'ok.svg').write_text(SVG % '0f0')
    out = tmp_path / 'p.json'
    rc = bc.main(['--corpus', str(corpus), '--renderers', 'raster,resvg', '--repeat', '2',
                  '--widths', 'natural,60', '--mode', 'process', '--json', str(out),
                  '--timeout', '60'])
    assert rc == 0
    data = json.load(open(out))
    assert data['results'] == []                              # no in-process cells
    res = {(r['file'], r['width'], r['renderer']): r for r in data['process']}
    for r in ('raster', 'resvg'):
        c = res[('ok.svg', 60, r)]
        assert tuple(c['size']) == (60, 30) and len(c['wall']) == 2
        assert all(m > 5 for m in c['rss_mb']) and all(t > 0 for t in c['cpu'])
        # the untimed run of the process tree: about the process's own size
        assert 2 < c['tree_mb'] < 3 * max(c['rss_mb'])
        assert tuple(res[('ok.svg', 'natural', r)]['size']) == (40, 20)


def test_inprocess_widths_subset(bc, tmp_path):
    """--inprocess-widths: the whole-process cells at every width, the
    in-process cells only at the widths named; a width outside --widths is
    refused with a usage error."""
    corpus = tmp_path / 'corpus'
    corpus.mkdir()
    (corpus / 'ok.svg').write_text(SVG % '00f')
    out = tmp_path / 'b.json'
    md = tmp_path / 'b.md'
    rc = bc.main(['--corpus', str(corpus), '--renderers', 'raster', '--repeat', '1',
                  '--widths', 'natural,60', '--inprocess-widths', 'natural', '--json', str(out),
                  '--markdown', str(md), '--timeout', '60'])
    assert rc == 0
    data = json.load(open(out))
    assert sorted(str(r['width']) for r in data['process']) == ['60', 'natural']
    assert [r['width'] for r in data['results']] == ['natural']
    text = md.read_text()
    assert 'Whole process, width 60 px' in text
    assert 'Width: natural size' in text and 'Width: 60 px' not in text
    with pytest.raises(SystemExit):
        bc.main(['--corpus', str(corpus), '--widths', 'natural', '--inprocess-widths', '2000'])
