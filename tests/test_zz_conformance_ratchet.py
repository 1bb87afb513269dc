"""The resvg-suite conformance ratchet: the whole suite in
../shared/resvg-suite is rendered by raster and scored with raster.testing's
criterion (the same as ../shared/conformance/score.py); the test fails when
any area passes fewer cases than tests/conformance_ratchet.json records.

Named test_zz_* so that it runs last in a serial run (it is the slowest
test); under pytest-xdist tests/conftest.py starts it first instead."""

import os
import subprocess
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def conformance_jobs(cpus, xdist_workers):
    """Worker processes for the conformance run: the CPUs left per pytest
    process (an xdist run has ``xdist_workers`` of them busy with the other
    tests meanwhile), at least 1 and at most 4."""
    return max(1, min(4, cpus // max(1, xdist_workers)))


def available_cpus():
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:       # not Linux
        return os.cpu_count() or 1


def test_conformance_jobs_share_the_cpus_with_xdist_workers():
    assert conformance_jobs(2, 0) == 2          # serial run on two cores
    assert conformance_jobs(2, 2) == 1          # -n 2: one core per pytest worker
    assert conformance_jobs(8, 2) == 4
    assert conformance_jobs(3, 2) == 1
    assert conformance_jobs(1, 0) == 1
    assert conformance_jobs(64, 0) == 4


@pytest.mark.conformance
def test_no_area_below_its_ratchet():
    workers = int(os.environ.get('PYTEST_XDIST_WORKER_COUNT', '0') or 0)
    jobs = str(conformance_jobs(available_cpus(), workers))
    proc = subprocess.run(
        [sys.executable, '-m', 'raster_cli.conformance', '--jobs', jobs, '--check', '--no-features'],
        cwd=REPO, capture_output=True, text=True, timeout=1800)
    print(proc.stdout[-3000:])
    print(proc.stderr[-2000:], file=sys.stderr)
    assert proc.returncode == 0, 'conformance below ratchet:\n' + proc.stdout[-3000:]
