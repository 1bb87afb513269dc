"""raster_cli._malloc, the command's opt-in allocator tuning: freed large
numpy temporaries are reused, not re-faulted."""

import subprocess
import sys
import textwrap

import pytest

SCRIPT = textwrap.dedent('''
    import resource, sys
    import numpy as np
    import raster_cli._malloc as m
    applied = m.tune()
    def faults():
        return resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    for _ in range(2):                        # warm up the heap
        a = np.ones(8 << 20); del a
    f0 = faults()
    for _ in range(20):                       # 20 x 64 MB temporaries
        a = np.ones(8 << 20); del a
    print(int(applied), faults() - f0, int(m.tune()))
''')


def run(env_value):
    env = {'PATH': '/usr/bin:/bin'}
    if env_value is not None:
        env['RASTER_MALLOC_TUNING'] = env_value
    out = subprocess.run([sys.executable, '-c', SCRIPT], capture_output=True, text=True,
                         env=env, check=True).stdout.split()
    return [int(v) for v in out]


@pytest.mark.skipif(not sys.platform.startswith('linux'), reason='glibc tuning is Linux only')
def test_tuned_allocator_reuses_freed_blocks():
    applied, faults, again = run(None)
    assert applied == 1 and again == 0          # applied once per process
    off_applied, off_faults, _ = run('0')
    assert off_applied == 0
    # untuned, every 64 MB temporary is a fresh mapping faulted page by page
    # (huge pages make that fewer faults: about 10,000 seen here); tuned,
    # the freed block is reused from the heap
    assert off_faults > 2000 and faults < off_faults / 20
