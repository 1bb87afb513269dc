"""raster.dask against a real distributed.LocalCluster of two worker
processes (one thread each): chunks of render_array rendered on the
workers equal the single render, reductions and slices compute only what
they need, and render_files converts a batch with one record per file."""

import os

import numpy as np
import pytest

import raster
from raster.errors import SVGError

distributed = pytest.importorskip('distributed')
da = pytest.importorskip('dask.array')

from raster.dask import render_array, render_files  # noqa: E402

DOC = (b'<svg xmlns="http://www.w3.org/2000/svg" width="200" height="130">'
       b'<defs><filter id="f" x="-30%" y="-30%" width="160%" height="160%">'
       b'<feGaussianBlur stdDeviation="5"/><feOffset dx="6" dy="4"/></filter>'
       b'<pattern id="p" width="11" height="7" patternUnits="userSpaceOnUse">'
       b'<circle cx="4" cy="3" r="3" fill="navy"/></pattern>'
       b'<mask id="m"><circle cx="100" cy="65" r="50" fill="white"/></mask></defs>'
       b'<rect x="20" y="15" width="160" height="100" fill="url(#p)" mask="url(#m)"/>'
       b'<rect x="40" y="40" width="70" height="50" fill="crimson" filter="url(#f)"/></svg>')


@pytest.fixture(scope='module')
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=40)
    c = distributed.Client(cluster)
    try:
        yield c
    finally:
        c.close()
        cluster.close()


def test_chunks_rendered_on_workers_equal_the_single_render(client):
    arr = render_array(DOC, width=400, chunks=(70, 90))
    assert arr.shape == (260, 400, 4) and arr.dtype == np.uint8
    assert arr.chunks[0] == (70, 70, 70, 50) and arr.chunks[1] == (90, 90, 90, 90, 40)
    img = arr.compute()
    whole = raster.render(DOC, 400)
    assert int(np.abs(img.astype(int) - whole).max()) <= 1
    # the chunks were rendered in the worker processes, not here
    pids = set(client.run(os.getpid).values())
    assert len(pids) == 2 and os.getpid() not in pids


def test_stored_to_zarr_on_the_cluster_and_read_back(client, tmp_path):
    # the use: a lazy render stored to zarr, chunk by chunk on the
    # workers (each chunk a window written by the worker that rendered it),
    # read back equal to the single render
    zarr = pytest.importorskip('zarr')
    arr = render_array(DOC, width=333, chunks=(64, 100))
    path = str(tmp_path / 'map.zarr')
    arr.to_zarr(path, compute=True)
    z = zarr.open_array(path, mode='r')
    assert z.shape == (217, 333, 4) and z.dtype == np.uint8 and z.chunks == (64, 100, 4)
    whole = raster.render(DOC, 333)
    assert int(np.abs(z[...].astype(int) - whole).max()) <= 1
    back = da.from_zarr(path)
    assert np.array_equal(back[100:200, 50:300].compute(), z[100:200, 50:300])


def test_reductions_and_slices(client):
    arr = render_array(DOC, chunks=64, background='white')
    whole = raster.render(DOC, background='white')
    assert np.array_equal(arr[30:90, 50:170].compute(), whole[30:90, 50:170])
    means = arr.mean(axis=(0, 1)).compute()
    assert np.allclose(means, whole.reshape(-1, 4).mean(0), atol=0.5)


def test_a_slice_renders_only_the_chunks_it_needs(monkeypatch):
    import raster.dask as rd
    windows = []
    real = rd._render_chunk

    def counting(data, spec, window):
        windows.append(window)
        return real(data, spec, window)
    monkeypatch.setattr(rd, '_render_chunk', counting)
    arr = render_array(DOC, chunks=64)
    part = arr[70:100, 10:60].compute(scheduler='sync')
    assert windows == [(0, 64, 64, 128)]
    assert np.array_equal(part, raster.render(DOC)[70:100, 10:60])


def test_bad_documents_fail_before_any_chunk():
    with pytest.raises(SVGError):
        render_array(b'<svg')
    with pytest.raises(TypeError):
        render_array(DOC, colour='red')
    with pytest.raises(SVGError):
        render_array(DOC, chunks=0)


def test_render_files_on_the_cluster(client, tmp_path):
    good = []
    for i in range(4):
        p = tmp_path / ('d%d.svg' % i)
        p.write_bytes(DOC.replace(b'crimson', b'#%02x8040' % (60 * i)))
        good.append(str(p))
    bad = tmp_path / 'bad.svg'
    bad.write_bytes(b'<svg')
    missing = str(tmp_path / 'missing.svg')
    out = tmp_path / 'out'
    recs = render_files(good + [str(bad), missing], str(out), client=client, width=100)
    assert [r['input'] for r in recs] == good + [str(bad), missing]
    for r, src in zip(recs[:4], good):
        assert r['error'] is None and os.path.exists(r['output'])
        from PIL import Image
        assert np.array_equal(np.asarray(Image.open(r['output'])), raster.render(src, 100))
    assert recs[4]['output'] is None and 'XML' in recs[4]['error']
    assert recs[5]['output'] is None and 'missing.svg' in recs[5]['error']
    assert '\n' not in recs[4]['error'] + recs[5]['error']
    assert sorted(os.listdir(out)) == ['d0.png', 'd1.png', 'd2.png', 'd3.png']
