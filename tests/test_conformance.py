"""The conformance harness itself (raster_cli.conformance) on a fake suite.

The full suite runs from CI (``python -m raster_cli.conformance --check``);
here we check discovery, the worker pool (timeouts, crashes), scoring and the
ratchet logic with a fake renderer (workers are forked, so a renderer
registered in this process is visible to them).
"""

import json
import os
import time

import numpy as np
import pytest
from PIL import Image

from raster_cli import conformance as cf


class FakeRenderer:
    """Returns the reference (pass), a blank image ('bad'), hangs ('hang'),
    kills its process ('crash') or raises ('raise')."""

    def __init__(self, cfg):
        self.cfg = cfg

    def render(self, case):
        name = case['name']
        if 'hang' in name:
            time.sleep(60)
        if 'crash' in name:
            os._exit(3)
        if 'raise' in name:
            raise ValueError('boom\nsecond line')
        ref = cf.load_png(case['png'])
        if 'bad' in name:
            return np.zeros_like(ref)
        return ref


@pytest.fixture(autouse=True)
def fake_renderer(monkeypatch):
    monkeypatch.setitem(cf.RENDERERS, 'fake', FakeRenderer)


def make_suite(root, names):
    """A suite with one 10x10 red-square reference per case name."""
    img = np.zeros((10, 10, 4), np.uint8)
    img[2:8, 2:8] = (255, 0, 0, 255)
    for name in names:
        p = root / 'tests' / (name + '.svg')
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text('<svg xmlns="http://www.w3.org/2000/svg"/>')
        Image.fromarray(img).save(str(p)[:-4] + '.png')
    (root / 'fonts').mkdir(exist_ok=True)
    (root / 'resources').mkdir(exist_ok=True)
    return root


NAMES = ['shapes/rect/simple', 'shapes/rect/bad-case', 'shapes/circle/simple',
         'painting/stroke/simple', 'painting/stroke/bad-width', 'structure/top-level']


def test_matches_substring_and_glob():
    assert cf.matches('rect', 'shapes/rect/simple')
    assert cf.matches('shapes/*/simple', 'shapes/rect/simple')
    assert cf.matches('rect/simple.svg', 'shapes/rect/simple')
    assert not cf.matches('circle', 'shapes/rect/simple')
    assert cf.matches('r?ct', 'shapes/rect/simple')


def test_discover_areas_and_features(tmp_path):
    make_suite(tmp_path, NAMES)
    cases = cf.discover(str(tmp_path))
    assert [c['name'] for c in cases] == sorted(NAMES)
    by = {c['name']: c for c in cases}
    assert by['shapes/rect/simple']['area'] == 'shapes'
    assert by['shapes/rect/simple']['feature'] == 'shapes/rect'
    assert by['structure/top-level']['feature'] == 'structure'
    assert [c['name'] for c in cf.discover(str(tmp_path), ['stroke'])] == \
        ['painting/stroke/bad-width', 'painting/stroke/simple']


def test_missing_suite_is_a_clear_error(tmp_path, capsys):
    with pytest.raises(cf.HarnessError):
        cf.discover(str(tmp_path / 'nowhere'))
    assert cf.main(['--suite', str(tmp_path / 'nowhere')]) == 1
    err = capsys.readouterr().err
    assert err.count('\n') == 1 and 'no test suite' in err and 'Traceback' not in err


def run_fake(tmp_path, *extra):
    return cf.main(['--suite', str(tmp_path), '--renderer', 'fake', '--no-features',
                    '--ratchet', str(tmp_path / 'ratchet.json'), *extra])


def test_scores_and_reports(tmp_path, capsys):
    make_suite(tmp_path, NAMES)
    out = tmp_path / 'res.json'
    diffs = tmp_path / 'diffs'
    assert run_fake(tmp_path, '--jobs', '2', '--json', str(out), '--diffs', str(diffs)) == 0
    data = json.loads(out.read_text())
    st = {c['name']: c['status'] for c in data['cases']}
    assert st == {n: ('fail' if 'bad' in n else 'pass') for n in NAMES}
    assert data['pass_counts'] == {'painting': 1, 'shapes': 2, 'structure': 1}
    assert sorted(os.listdir(diffs)) == ['painting__stroke__bad-width.png',
                                         'shapes__rect__bad-case.png']
    strip = np.asarray(Image.open(diffs / 'shapes__rect__bad-case.png'))
    assert strip.shape[1] == 3 * 10 + 8
    text = capsys.readouterr().out
    assert 'shapes' in text and '2/3' in text and 'TOTAL' in text and 'wall time' in text


def test_hang_crash_and_exception_lose_only_their_case(tmp_path):
    names = ['a/x/hang-1', 'a/x/ok-1', 'a/x/crash-1', 'a/x/ok-2', 'a/x/raise-1', 'a/x/ok-3']
    make_suite(tmp_path, names)
    cases = cf.discover(str(tmp_path))
    cfg = {'renderer': 'fake', 'width': 300, 'timeout': 1.0, 'fonts_dir': '', 'resources_dir': '',
           'diffs': None, 'mem_limit_mb': 0}
    recs = cf.run_cases(cases, cfg, jobs=2)
    st = {r['name']: (r['status'], r.get('reason') or '') for r in recs}
    assert st['a/x/hang-1'][0] == 'timeout'
    assert st['a/x/crash-1'][0] == 'error' and 'crashed' in st['a/x/crash-1'][1]
    assert st['a/x/raise-1'] == ('error', 'ValueError: boom')
    assert all(st['a/x/ok-%d' % k][0] == 'pass' for k in (1, 2, 3))


# -- ratchet ------------------------------------------------------------------

def test_ratchet_functions():
    rec = {'shapes': 10, 'text': 5}
    assert cf.check_ratchet({'shapes': 10, 'text': 6}, rec) == []
    assert cf.check_ratchet({'shapes': 9, 'text': 6}, rec) == [('shapes', 9, 10)]
    assert cf.check_ratchet({'shapes': 12}, rec) == [('text', 0, 5)]
    assert cf.updated_ratchet({'shapes': 9, 'text': 7, 'new': 1}, rec) == \
        {'new': 1, 'shapes': 10, 'text': 7}
    assert cf.updated_ratchet({'shapes': 9, 'text': 7}, rec, force=True) == {'shapes': 9, 'text': 7}


def test_ratchet_file_roundtrip_and_errors(tmp_path):
    p = str(tmp_path / 'r.json')
    assert cf.load_ratchet(p) == {}
    cf.save_ratchet(p, {'a': 3, 'b': 0})
    assert cf.load_ratchet(p) == {'a': 3, 'b': 0}
    (tmp_path / 'bad.json').write_text('{"areas": [1, 2')
    with pytest.raises(cf.HarnessError):
        cf.load_ratchet(str(tmp_path / 'bad.json'))
    (tmp_path / 'bad2.json').write_text('{"nothing": 1}')
    with pytest.raises(cf.HarnessError):
        cf.load_ratchet(str(tmp_path / 'bad2.json'))


def test_check_and_update_through_main(tmp_path, capsys):
    make_suite(tmp_path, NAMES)
    ratchet = tmp_path / 'ratchet.json'
    cf.save_ratchet(str(ratchet), {'painting': 1, 'shapes': 3, 'structure': 1})
    assert run_fake(tmp_path, '--check') == 1            # shapes passes 2 < 3
    assert 'shapes passes 2, recorded 3' in capsys.readouterr().err
    assert run_fake(tmp_path, '--update') == 0           # never lowers without --force
    assert cf.load_ratchet(str(ratchet))['shapes'] == 3
    assert run_fake(tmp_path, '--update', '--force') == 0
    assert cf.load_ratchet(str(ratchet)) == {'painting': 1, 'shapes': 2, 'structure': 1}
    assert run_fake(tmp_path, '--check') == 0


@pytest.mark.parametrize('argv', [['--check', '--filter', 'x'], ['--force'], ['--jobs', '0'],
                                  ['--check', '--update'], ['--timeout', '-1']])
def test_usage_errors_exit_2(tmp_path, argv):
    with pytest.raises(SystemExit) as e:
        cf.main(['--suite', str(tmp_path)] + argv)
    assert e.value.code == 2


def test_repo_ratchet_file_is_valid():
    rec = cf.load_ratchet(cf.DEFAULT_RATCHET)
    assert set(rec) <= {'filters', 'masking', 'paint-servers', 'painting', 'shapes',
                        'structure', 'text'}
    assert all(v >= 0 for v in rec.values())
