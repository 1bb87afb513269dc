"""Tests of the PNG encoder comparison (bench/bench_png.py): one small run
on a temporary corpus, its table and totals."""

import pytest

from _shared import load_bench


@pytest.fixture(scope='module')
def bp():
    return load_bench('bench_png')


def test_table_rows_sizes_and_totals(bp, tmp_path, capsys):
    corpus = tmp_path / 'corpus'
    corpus.mkdir()
    for name, colour in (('a.svg', 'f00'), ('b.svg', '0a0')):
        (corpus / name).write_text(
            '<svg xmlns="http://www.w3.org/2000/svg" width="40" height="20">'
            '<circle cx="20" cy="10" r="8" fill="#%s"/></svg>' % colour)
    assert bp.main(['--corpus', str(corpus), '--width', '400', '--repeat', '1',
                    '--levels', '1,9']) == 0
    out = capsys.readouterr().out
    rows = [line for line in out.splitlines() if line.startswith('| a.svg') or
            line.startswith('| b.svg')]
    assert len(rows) == 2
    cells = rows[0].strip('| ').split(' | ')
    assert cells[1] == '400x200' and len(cells) == 8          # raster, Pillow 1, Pillow 9
    times, sizes = cells[2::2], cells[3::2]
    assert all(float(t) >= 0 for t in times) and all(float(k) > 0 for k in sizes)
    assert out.count('against Pillow compress_level=') == 2
    with pytest.raises(SystemExit):
        bp.main(['--corpus', str(corpus), '--files', 'nothing-matches'])
