"""Benchmarks of the geocean package (figures in docs/PERFORMANCE.md).

    PYTHONPATH=build/python /usr/bin/python3 plugin/python/bench/bench_python.py [--quick]

1. Ocean.query on 10^6 points against the C++ façade batch on the same
   arrays and snapshot in the same process (Core._time_facade_batch: the
   same Snapshot::querySurface into C++ vectors, no Python; with outputs
   allocated per call as query() does, and reused); best of N,
   interleaved so machine noise hits all three.
2. geocean.dask.query on a LocalCluster of 2 worker processes against
   in-process Ocean.query on the same arrays, split into where the time goes.
3. 10^8 points through Dask with the points made on the workers and reduced
   there: peak RSS per worker against the chunk size.
"""
import argparse
import os
import time

import numpy as np

import geocean


def best(f, n):
    ts = []
    for _ in range(n):
        t0 = time.perf_counter()
        f()
        ts.append(time.perf_counter() - t0)
    return min(ts)


def points(n, seed=1):
    rng = np.random.default_rng(seed)
    return rng.uniform(-80.0, 80.0, n), rng.uniform(-180.0, 180.0, n)


def bench_python_vs_cpp(repeats):
    lat, lon = points(10**6)
    print("## 1. Ocean.query vs the C++ facade batch, 10^6 points, t = 10 s")
    for waves in ("noise", "gerstner", "fft"):
        o = geocean.Ocean(waves=waves)
        o.query(lat[:1000], lon[:1000], 10.0)  # warm: tables, TBB threads
        py, cpp, cpp_kept = [], [], []
        for _ in range(repeats):
            py.append(best(lambda: o.query(lat, lon, 10.0), 1))
            cpp.append(o._core._time_facade_batch(lat, lon, 10.0, 1, True))
            cpp_kept.append(o._core._time_facade_batch(lat, lon, 10.0, 1, False))
        p, c, k = min(py), min(cpp), min(cpp_kept)
        print(f"{waves:9s} python {p * 1e3:7.1f} ms ({1e6 / p / 1e6:5.2f} M/s)   C++ fresh outputs "
              f"{c * 1e3:7.1f} ms (ratio {p / c:5.3f})   C++ reused outputs {k * 1e3:7.1f} ms (ratio {p / k:5.3f})")


def worker_rss():
    with open("/proc/self/status") as f:
        s = dict(line.split(":", 1) for line in f)
    return int(s["VmHWM"].split()[0]) * 1024, int(s["VmRSS"].split()[0]) * 1024


def bench_dask(n, chunk, big_n, big_chunk):
    import dask
    import dask.array as da
    import distributed
    import geocean.dask as gd

    args = dict(waves="gerstner")
    lat, lon = points(n, seed=2)
    o = geocean.Ocean(**args)
    o.query(lat[:1000], lon[:1000], 0.0)
    inproc = best(lambda: o.query(lat, lon, 0.0), 3)
    print(f"\n## 2. Dask, {n:.0e} points, chunks of {chunk:.0e}, Gerstner")
    print(f"in-process Ocean.query            {inproc:7.3f} s  ({n / inproc / 1e6:5.2f} M/s)")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None, silence_logs=40) as cluster, \
            distributed.Client(cluster) as client:
        # Warm the workers (import, Ocean build) so the figures are steady state.
        w = gd.query(da.from_array(lat[:10], chunks=5), da.from_array(lon[:10], chunks=5), 0.0, **args)
        dask.compute(*w.values())

        def numpy_in_results_back():
            r = gd.query(da.from_array(lat, chunks=chunk), da.from_array(lon, chunks=chunk), 0.0, **args)
            return client.compute(list(r.values()), sync=True)
        res = numpy_in_results_back()
        ref = o.query(lat, lon, 0.0)
        same = all(np.ascontiguousarray(a).tobytes() == ref[k].tobytes() for a, k in zip(res, ref))
        full = best(numpy_in_results_back, 3)

        # Points made on the workers, one float reduced per chunk: no transfer.
        def on_workers():
            la = da.random.RandomState(5).uniform(-80, 80, n, chunks=chunk)
            lo = da.random.RandomState(6).uniform(-180, 180, n, chunks=chunk)
            r = gd.query(la, lo, 0.0, **args)
            return client.compute(da.nansum(r["sea_height_m"]), sync=True)
        on_workers()
        compute_only = best(on_workers, 3)
        # The same graph without the query: making the points and the scheduler.
        def no_query():
            la = da.random.RandomState(5).uniform(-80, 80, n, chunks=chunk)
            lo = da.random.RandomState(6).uniform(-180, 180, n, chunks=chunk)
            return client.compute(da.nansum(la + lo), sync=True)
        overhead = best(no_query, 3)
        print(f"dask 2 workers, numpy in, all outputs back {full:7.3f} s  ratio {full / inproc:5.2f}"
              f"  bit-identical: {same}")
        print(f"dask 2 workers, points made on workers, reduced {compute_only:7.3f} s  ratio "
              f"{compute_only / inproc:5.2f}")
        print(f"  of which making points + scheduling (same graph, no query) {overhead:7.3f} s")
        out_bytes = sum(a.nbytes for a in res)
        print(f"  transfer: {2 * lat.nbytes / 1e6:.0f} MB in, {out_bytes / 1e6:.0f} MB out: "
              f"{full - compute_only:6.3f} s more than the reduced run")

        # 3. Memory for 10^8 points.
        client.restart()
        t0 = time.perf_counter()
        la = da.random.RandomState(7).uniform(-80, 80, big_n, chunks=big_chunk)
        lo = da.random.RandomState(8).uniform(-180, 180, big_n, chunks=big_chunk)
        r = gd.query(la, lo, 0.0, **args)
        ocean = r["surface"] == 0
        mean_h, n_ocean = dask.compute(da.nanmean(r["sea_height_m"]), ocean.sum())
        dt = time.perf_counter() - t0
        rss = client.run(worker_rss)
        print(f"\n## 3. {big_n:.0e} points, chunks of {big_chunk:.0e}, 2 workers: {dt:6.1f} s "
              f"({big_n / dt / 1e6:5.2f} M/s), mean sea height {mean_h:+.4f} m over {n_ocean} ocean points")
        per_chunk = big_chunk * (2 * 8 + 1 + 4 + 8 + 24 + 8)  # inputs + the five outputs
        for addr, (hwm, now) in sorted(rss.items()):
            print(f"  worker peak RSS {hwm / 2**20:6.0f} MiB (now {now / 2**20:6.0f} MiB); "
                  f"one chunk's inputs + outputs {per_chunk / 2**20:.0f} MiB")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="small sizes, to check the script runs")
    a = ap.parse_args()
    print(f"geocean {geocean.__version__}, {os.cpu_count()} CPUs")
    if a.quick:
        bench_python_vs_cpp(2)
        bench_dask(10**5, 2 * 10**4, 10**6, 10**5)
    else:
        bench_python_vs_cpp(7)
        bench_dask(4 * 10**6, 5 * 10**5, 10**8, 10**6)


if __name__ == "__main__":
    main()
