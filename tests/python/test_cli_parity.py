# Python results are bit-identical to `geocean query --format json` (and
# `geocean pick`) on the same points: both run the same façade batch, and
# the CLI prints shortest round-trip decimals (std::to_chars), so parsing
# them back gives the very doubles (floats for elevation_m).
import json

import numpy as np
import pytest

import geocean
from conftest import mixed_points, run_cli


def cli_rows(exe, lat, lon, t, args, tmp_path):
    pts = tmp_path / "points.csv"
    with open(pts, "w") as f:
        f.write("lat,lon,time\n")
        for a, b, c in zip(lat, lon, t):
            f.write(f"{a!r},{b!r},{c!r}\n")  # repr: the exact double
    out = run_cli(exe, ["query", "--points", str(pts), "--format", "json"] + args)
    return [json.loads(line) for line in out.splitlines()]


def as_array(rows, key, dtype=np.float64):
    return np.array([np.nan if r[key] is None else r[key] for r in rows], dtype=dtype)


def bits_equal(a, b):
    a, b = np.ascontiguousarray(a), np.ascontiguousarray(b)
    return a.shape == b.shape and a.tobytes() == b.tobytes()


@pytest.mark.parametrize("waves,args,kw", [
    ("noise", [], {}),
    ("gerstner", ["--wind", "14", "--wind-dir", "200", "--seed", "5"],
     dict(wind_mps=14.0, wind_from_deg=200.0, seed=5)),
    ("fft", ["--fetch", "80000", "--anchor", "36,-5"], dict(fetch_m=80000.0, anchor=(36.0, -5.0))),
    ("gerstner", ["--beaufort", "7"], dict(beaufort=7)),
])
def test_query_matches_cli_bit_for_bit(geocean_exe, tmp_path, waves, args, kw):
    lat, lon = mixed_points(3000, seed=11)
    # Per-point times, a few distinct ones so FFT's per-time tables repeat and differ.
    t = np.round(np.random.default_rng(3).uniform(0.0, 600.0, lat.size) / 37.0) * 37.0
    rows = cli_rows(geocean_exe, lat, lon, t, ["--waves", waves] + args, tmp_path)
    assert len(rows) == lat.size
    r = geocean.Ocean(waves=waves, **kw).query(lat, lon, t)
    names = [geocean.SURFACE_NAMES[c] for c in r["surface"]]
    assert names == [row["surface"] for row in rows]
    assert bits_equal(r["elevation_m"], as_array(rows, "elevation_m", np.float32))
    assert bits_equal(r["sea_height_m"], as_array(rows, "sea_height_m"))
    assert bits_equal(r["vertical_velocity_mps"], as_array(rows, "vertical_velocity_mps"))
    normal = np.array([[np.nan] * 3 if row["normal"] is None else row["normal"] for row in rows])
    assert bits_equal(r["normal_enu"], normal)
    st = geocean.Ocean(waves=waves, **kw).sea_state(lat, lon)
    for key in ("hs_m", "peak_period_s", "peak_wavelength_m", "wave_from_deg"):
        assert bits_equal(st[key], as_array(rows, key)), key
    # The comparison covers all classes and real waves.
    assert {"ocean", "land", "lake"} <= set(names)
    assert np.nanstd(r["sea_height_m"]) > 0.1


def test_scalar_time_matches_cli_time_option(geocean_exe, tmp_path):
    lat, lon = mixed_points(500, seed=2)
    pts = tmp_path / "p.csv"
    pts.write_text("".join(f"{a!r},{b!r}\n" for a, b in zip(lat, lon)))
    out = run_cli(geocean_exe, ["query", "--points", str(pts), "--format", "json", "--time", "42.5"])
    rows = [json.loads(x) for x in out.splitlines()]
    r = geocean.Ocean().query(lat, lon, 42.5)
    assert bits_equal(r["sea_height_m"], as_array(rows, "sea_height_m"))


def test_pick_matches_cli_bit_for_bit(geocean_exe, world):
    # Rays from 2 km over Gibraltar at a slant (terrain and sea), one from orbit, one missing.
    rays = [
        (5.1e6, -0.5e6, 3.8e6, -1.0, 0.1, -0.7),
        (5.17e6, -0.51e6, 3.73e6, -0.2, 0.9, -0.6),
        (2e7, 0.0, 0.0, -1.0, 0.0, 0.0),
        (2e7, 0.0, 0.0, 1.0, 0.0, 0.0),
    ]
    kinds = set()
    for ray in rays:
        cli = json.loads(run_cli(geocean_exe, ["pick", "--ray", ",".join(repr(v) for v in ray),
                                               "--format", "json"]))
        r = world.pick(np.array([ray[:3]]), np.array([ray[3:]]))
        assert bool(r["hit"][0]) == cli["hit"]
        if not cli["hit"]:
            continue
        kinds.add(int(r["kind"][0]))
        assert geocean.SURFACE_NAMES[r["surface"][0]] == cli["surface"]
        for k in ("lat", "lon", "height_m", "distance_m"):
            assert r[k][0] == cli[k], k  # exact: same doubles
    assert kinds == {1, 2}, "the rays must hit both sea and terrain"
