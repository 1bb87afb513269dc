"""Tests of the start-up benchmark (bench/bench_startup.py): the program
list and one round of real processes."""

import sys

import pytest

from _shared import load_bench


@pytest.fixture(scope='module')
def bs():
    return load_bench('bench_startup')


def test_programs_substitute_also(bs):
    progs = bs.programs('py', 'rz', 'in.svg', 'o.png', ['old=/x/rasterize {svg} {out} --width 5'])
    assert list(progs)[0].startswith('python -c')            # the yardstick first
    assert progs['rasterize min.svg out.png'] == ['rz', 'in.svg', 'o.png']
    assert progs['old'] == ['/x/rasterize', 'in.svg', 'o.png', '--width', '5']


def test_measure_and_table(bs):
    res, loads = bs.measure({'yard': [sys.executable, '-c', 'import numpy'],
                             'same': [sys.executable, '-c', 'import numpy, lxml.etree']}, 2)
    assert len(loads) == 2
    assert all(len(v['wall']) == 2 and min(v['rss_mb']) > 5 for v in res.values())
    lines = bs.table(res, loads)
    assert lines[2].startswith('| yard |') and '| 1.00 |' in lines[2]
    assert 'Medians of 2 interleaved rounds' in lines[-1]
    with pytest.raises(SystemExit):
        bs.measure({'bad': [sys.executable, '-c', 'raise SystemExit(3)']}, 1)
