"""The resvg-suite conformance ratchet: the whole suite in
../shared/resvg-suite is rendered by raster and scored with raster.testing's
criterion (the same as ../shared/conformance/score.py); the test fails when
any area passes fewer cases than tests/conformance_ratchet.json records.

Named test_zz_* so that it runs last (it takes a few minutes)."""

import os
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def test_no_area_below_its_ratchet():
    jobs = str(max(1, min(4, os.cpu_count() or 1)))
    proc = subprocess.run(
        [sys.executable, '-m', 'raster_cli.conformance', '--jobs', jobs, '--check', '--no-features'],
        cwd=REPO, capture_output=True, text=True, timeout=1800)
    print(proc.stdout[-3000:])
    print(proc.stderr[-2000:], file=sys.stderr)
    assert proc.returncode == 0, 'conformance below ratchet:\n' + proc.stdout[-3000:]
