# Queries from several Python threads at once give the single-threaded
# answers, and a batch releases the GIL (other Python code runs meanwhile).
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import geocean
from conftest import mixed_points


def test_concurrent_queries_match_serial(world):
    lat, lon = mixed_points(40000, seed=5)
    parts = np.array_split(np.arange(lat.size), 16)
    times = [float(i) for i in range(len(parts))]
    serial = [world.query(lat[p], lon[p], t) for p, t in zip(parts, times)]
    cls = [world.classify(lat[p], lon[p]) for p in parts]
    with ThreadPoolExecutor(max_workers=8) as ex:
        futs = [ex.submit(world.query, lat[p], lon[p], t) for p, t in zip(parts, times)]
        futs += [ex.submit(world.classify, lat[p], lon[p]) for p in parts]
        results = [f.result() for f in futs]
    for a, b in zip(serial, results[:len(parts)]):
        for k in a:
            np.testing.assert_array_equal(a[k], b[k])
    for a, b in zip(cls, results[len(parts):]):
        np.testing.assert_array_equal(a, b)


def test_concurrent_picks_and_oceans():
    # Distinct Oceans built and queried on threads (construction is thread-safe too).
    lat, lon = mixed_points(2000, seed=8)
    def work(seed):
        o = geocean.Ocean(waves="gerstner", seed=seed)
        return o.query(lat, lon, 2.0)["sea_height_m"]
    with ThreadPoolExecutor(max_workers=4) as ex:
        par = list(ex.map(work, range(4)))
    for seed, h in enumerate(par):
        np.testing.assert_array_equal(h, work(seed))


def gaps_while(call):
    """Runs call() on a thread and spins on this one meanwhile; returns the
    call's duration and the longest time this thread could not run."""
    done = threading.Event()

    def work():
        call()
        done.set()

    th = threading.Thread(target=work)
    t0 = last = time.perf_counter()
    longest = 0.0
    th.start()
    while not done.is_set():
        now = time.perf_counter()
        longest = max(longest, now - last)
        last = now
    elapsed = time.perf_counter() - t0
    th.join()
    return elapsed, longest


def test_batch_releases_the_gil(world):
    lat, lon = mixed_points(2_000_000, seed=9)
    elapsed, longest = gaps_while(lambda: world.query(lat, lon, 1.0))
    # Held for the batch, this thread would stop for the whole call (all but
    # the first switch interval, 5 ms); released, it stops only for OS time
    # slices and GIL hand-overs (ms). Half the call separates the two with
    # a wide margin either way (a GIL-holding C call fails it: checked with
    # pickle.dumps of a large list, whose C code keeps the GIL).
    assert elapsed > 0.2, f"the batch took {elapsed:.3f} s: too short to tell"
    assert longest < 0.5 * elapsed, f"this thread stalled {longest:.3f} s of {elapsed:.3f} s: the GIL was held"
