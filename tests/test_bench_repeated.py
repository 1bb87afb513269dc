"""Tests of the repeated-shapes benchmark driver (bench/bench_repeated.py):
its cases are the documents it describes, and its table shows a renderer
that failed as an error, not as a time."""

import pytest
from lxml import etree

from _shared import load_bench


@pytest.fixture(scope='module')
def br():
    return load_bench('bench_repeated')


def test_cases_are_what_they_say(br):
    ns = '{%s}' % br.SVG_NS
    page = etree.fromstring(br.CASES['text12'][1]().encode())
    texts = page.findall(ns + 'text')
    assert len(texts) == 60 and all(t.get('font-size') == '12' for t in texts)
    assert 7000 < sum(len(t.text) for t in texts) < 9000
    small = etree.fromstring(br.CASES['text5'][1]().encode())
    assert sum(len(t.text) for t in small.findall(ns + 'text')) > 15000
    dots = etree.fromstring(br.CASES['scatter'][1]().encode())
    circles = dots.findall(ns + 'circle')
    assert len(circles) == 5000 and len({(c.get('cx'), c.get('cy')) for c in circles}) == 5000
    # seeded: the same documents every run
    assert br.CASES['scatter'][1]() == br.CASES['scatter'][1]()


def test_table_marks_failures(br):
    res = {('scatter', 'raster'): [(1.0, 1.5, 60.0, True)] * 3,
           ('scatter', 'resvg'): [(0.5, 0.5, 20.0, True)] * 3,
           ('scatter', 'cairosvg'): [(0.0, 0.0, 0.0, False)] * 3}
    text = br.markdown(res, ['scatter'], ['raster', 'resvg', 'cairosvg'], 3)
    row = [ln for ln in text.splitlines() if ln.startswith('| scatter')][0]
    assert '| error |' in row and '2.00x resvg' in row
