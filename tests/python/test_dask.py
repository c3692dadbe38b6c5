# geocean.dask.query: lazy, one query per chunk, and on a LocalCluster of 2
# worker processes bit-identical to the in-process query.
import dask
import dask.array as da
import numpy as np
import pytest

import geocean
import geocean.dask as gd
from conftest import mixed_points

ARGS = dict(waves="gerstner", wind_mps=13.0, seed=4)


@pytest.fixture(scope="module")
def points():
    lat, lon = mixed_points(60000, seed=21)
    t = np.linspace(0.0, 120.0, lat.size)
    return lat, lon, t


def check_equal(res, ref):
    assert sorted(res) == sorted(ref)
    for k in ref:
        assert res[k].dtype == ref[k].dtype and res[k].shape == ref[k].shape, k
        assert np.ascontiguousarray(res[k]).tobytes() == ref[k].tobytes(), k


def test_threaded_scheduler_matches_in_process(points):
    lat, lon, t = points
    ref = geocean.Ocean(**ARGS).query(lat, lon, t)
    r = gd.query(da.from_array(lat, chunks=7000), da.from_array(lon, chunks=7000),
                 da.from_array(t, chunks=7000), **ARGS)
    assert r["normal_enu"].chunks[1] == (3,)
    check_equal(dict(zip(r, dask.compute(*r.values(), scheduler="threads"))), ref)


def test_one_query_task_per_chunk(points):
    lat, lon, _ = points
    r = gd.query(da.from_array(lat, chunks=20000), da.from_array(lon, chunks=20000), 3.0, **ARGS)
    graph = dict(dask.base.collections_to_dsk(list(r.values())))
    queries = [k for k in graph if isinstance(k, tuple) and k[0].startswith("geocean-query-")]
    assert len(queries) == 3  # 60000 / 20000, shared by all five outputs


def test_mismatched_chunks_are_unified(points):
    lat, lon, _ = points
    ref = geocean.Ocean(**ARGS).query(lat, lon, 1.0)
    r = gd.query(da.from_array(lat, chunks=9000), da.from_array(lon, chunks=25000), 1.0, **ARGS)
    check_equal(dict(zip(r, dask.compute(*r.values(), scheduler="sync"))), ref)


def test_bad_shapes():
    with pytest.raises(ValueError, match="lat has shape"):
        gd.query(da.zeros(3), da.zeros(4))
    with pytest.raises(ValueError, match="t has shape"):
        gd.query(da.zeros(3), da.zeros(3), t=da.zeros(2))


def _builds():
    return gd._builds


def test_local_cluster_of_two_processes_is_bit_identical(points):
    import distributed  # python3-distributed is a build dependency (quickstart.sh): no skip
    lat, lon, t = points
    ref = geocean.Ocean(**ARGS).query(lat, lon, t)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None, silence_logs=40) as cluster, \
            distributed.Client(cluster) as client:
        r = gd.query(da.from_array(lat, chunks=5000), da.from_array(lon, chunks=5000),
                     da.from_array(t, chunks=5000), **ARGS)
        res = dict(zip(r, client.compute(list(r.values()), sync=True)))
        builds = client.run(_builds)
        pids = client.run(__import__("os").getpid)
    check_equal(res, ref)
    # Two distinct worker processes; each that ran chunks built its Ocean
    # once for all of them (12 chunks).
    assert len(set(pids.values())) == 2
    assert set(builds.values()) <= {0, 1} and 1 in builds.values(), builds
