# The API of geocean.Ocean: shapes, dtypes, the outputs' relations, no
# copies of contiguous float64 inputs, pickling.
import pickle

import numpy as np
import pytest

import geocean
from conftest import mixed_points


def test_surface_names_and_codes():
    assert geocean.SURFACE_NAMES == ("ocean", "land", "lake")
    assert geocean.SURFACE_NAMES[geocean.SURFACE_LAKE] == "lake"


def test_query_shapes_and_dtypes(world):
    lat, lon = mixed_points(1000)
    r = world.query(lat, lon, t=3.0)
    assert sorted(r) == ["elevation_m", "normal_enu", "sea_height_m", "surface", "vertical_velocity_mps"]
    assert r["surface"].dtype == np.uint8 and r["surface"].shape == (1000,)
    assert r["elevation_m"].dtype == np.float32
    assert r["normal_enu"].shape == (1000, 3)
    # All three classes occur, so the NaN rules below are exercised.
    assert set(np.unique(r["surface"])) == {0, 1, 2}
    ocean = r["surface"] == geocean.SURFACE_OCEAN
    assert np.all(np.isfinite(r["sea_height_m"][ocean]))
    assert np.all(np.isnan(r["sea_height_m"][~ocean]))
    assert np.all(np.isnan(r["normal_enu"][~ocean]))
    assert np.all(np.isnan(r["vertical_velocity_mps"][~ocean]))
    # Unit normals: the kernel normalises in double (1e-12 is ~5000 ulp of slack).
    assert np.allclose(np.linalg.norm(r["normal_enu"][ocean], axis=1), 1.0, rtol=0, atol=1e-12)


def test_n_dimensional_inputs_keep_their_shape(world):
    lat, lon = mixed_points(600)
    flat = world.query(lat, lon, 1.0)
    grid = world.query(lat.reshape(20, 30), lon.reshape(20, 30), 1.0)
    assert grid["surface"].shape == (20, 30)
    assert grid["normal_enu"].shape == (20, 30, 3)
    for k in flat:
        np.testing.assert_array_equal(grid[k].reshape(flat[k].shape), flat[k])


def test_per_point_times_equal_scalar_time(world):
    lat, lon = mixed_points(3000)
    a = world.query(lat, lon, 12.5)
    b = world.query(lat, lon, np.full(lat.shape, 12.5))
    for k in a:
        np.testing.assert_array_equal(a[k], b[k])
    # and per-point times do select per-point surfaces
    t = np.linspace(0.0, 30.0, lat.size)
    c = world.query(lat, lon, t)
    for i in (0, 1500, 2999):
        one = world.query(lat[i:i + 1], lon[i:i + 1], t[i])
        np.testing.assert_array_equal(one["sea_height_m"], c["sea_height_m"][i:i + 1])


def test_classify_and_elevation_agree_with_query(world):
    lat, lon = mixed_points(2000)
    r = world.query(lat, lon)
    np.testing.assert_array_equal(world.classify(lat, lon), r["surface"])
    np.testing.assert_array_equal(world.elevation(lat, lon), r["elevation_m"])


def test_known_places(world):
    # Mid-Atlantic, Paris, Lake Superior (the CLI demo's places).
    s = world.classify(np.array([0.0, 48.86, 47.7]), np.array([-30.0, 2.35, -87.5]))
    assert [geocean.SURFACE_NAMES[c] for c in s] == ["ocean", "land", "lake"]
    e = world.elevation(np.array([11.35]), np.array([142.2]))  # Mariana Trench, 20' ETOPO cell mean
    assert e[0] < -5000.0


def test_contiguous_float64_is_not_copied():
    a = np.linspace(-10.0, 10.0, 100)
    assert geocean._geocean._data_address(a) == a.ctypes.data
    # A strided view or another dtype must be converted (else the check above proves nothing).
    assert geocean._geocean._data_address(a[::2]) != a.ctypes.data
    assert geocean._geocean._data_address(a.astype(np.float32)) != a.ctypes.data


def test_lists_and_other_dtypes_are_accepted(world):
    r1 = world.query([36.0, 0.0], [-5.6, -30.0], 2)
    r2 = world.query(np.array([36.0, 0.0], np.float64), np.array([-5.6, -30.0]), 2.0)
    for k in r1:
        np.testing.assert_array_equal(r1[k], r2[k])


def test_waves_none_gives_classes_and_nan_sea():
    o = geocean.Ocean(waves="none")
    r = o.query(np.array([0.0, 48.86]), np.array([-30.0, 2.35]))
    assert list(r["surface"]) == [0, 1]
    assert np.all(np.isnan(r["sea_height_m"])) and np.all(np.isnan(r["normal_enu"]))
    with pytest.raises(geocean.NotReadyError, match="no sea state"):
        o.significant_wave_height_m


def test_horizontal_velocity():
    lat, lon = np.array([0.0, 10.0, 48.86]), np.array([-30.0, -40.0, 2.35])
    noise = geocean.Ocean().query(lat, lon, 1.0, horizontal_velocity=True)["horizontal_velocity_en_mps"]
    # The noise models move particles vertically only (plugin/ocean/Ocean.cpp).
    np.testing.assert_array_equal(noise[:2], 0.0)
    assert np.all(np.isnan(noise[2]))
    g = geocean.Ocean(waves="gerstner").query(lat, lon, 1.0, horizontal_velocity=True)
    assert g["horizontal_velocity_en_mps"].shape == (3, 2)
    assert np.all(np.abs(g["horizontal_velocity_en_mps"][:2]) > 0.0)


def test_pickle_rebuilds_the_same_ocean():
    o = geocean.Ocean(waves="gerstner", wind_mps=14.0, seed=9, wind_from_deg=200.0)
    o2 = pickle.loads(pickle.dumps(o))
    assert o2.args == o.args
    lat, lon = mixed_points(500)
    a, b = o.query(lat, lon, 4.0), o2.query(lat, lon, 4.0)
    for k in a:
        np.testing.assert_array_equal(a[k], b[k])


def test_sea_state_parameters_change_the_sea():
    lat, lon = np.array([0.0]), np.array([-30.0])
    base = geocean.Ocean(waves="gerstner").query(lat, lon, 5.0)["sea_height_m"]
    for kw in (dict(seed=2), dict(wind_mps=15.0), dict(wind_from_deg=0.0), dict(fetch_m=50e3)):
        assert geocean.Ocean(waves="gerstner", **kw).query(lat, lon, 5.0)["sea_height_m"] != base, kw


def test_significant_wave_height_grows_with_wind():
    # Pierson-Moskowitz: Hs ~ 0.21 U^2 / g, so doubling U multiplies Hs by ~4 (3.5 .. 4.5 allows the
    # spectrum's discretisation; the exact factor is 4 for the continuous spectrum).
    h1 = geocean.Ocean(wind_mps=8.0).significant_wave_height_m
    h2 = geocean.Ocean(wind_mps=16.0).significant_wave_height_m
    assert 3.5 < h2 / h1 < 4.5


def test_pick_down_onto_the_sea_and_land(world):
    # Straight down from 1000 km over the mid-Atlantic and over the Sahara.
    import math
    def ecef(lat, lon, h):
        a, f = 6378137.0, 1 / 298.257223563
        e2 = f * (2 - f)
        la, lo = math.radians(lat), math.radians(lon)
        n = a / math.sqrt(1 - e2 * math.sin(la) ** 2)
        return np.array([(n + h) * math.cos(la) * math.cos(lo), (n + h) * math.cos(la) * math.sin(lo),
                         (n * (1 - e2) + h) * math.sin(la)])
    o = np.array([ecef(0.0, -30.0, 1e6), ecef(23.0, 10.0, 1e6)])
    d = np.array([ecef(0.0, -30.0, 0.0), ecef(23.0, 10.0, 0.0)]) - o
    r = world.pick(o, d)
    assert list(r["hit"]) == [True, True]
    assert list(r["kind"]) == [1, 2]
    assert [geocean.SURFACE_NAMES[s] for s in r["surface"]] == ["ocean", "land"]
    # The vertical ray hits the ellipsoid 1000 km down (double refinement: mm, see plugin/pick/Picker.h).
    assert abs(r["distance_m"][0] - 1e6) < 1e-3 and abs(r["height_m"][0]) < 1e-3
    assert abs(r["lat"][0]) < 1e-9 and abs(r["lon"][0] + 30.0) < 1e-9
    # Sahara terrain is above the sea: hit before 1000 km.
    assert r["height_m"][1] > 0.0 and r["distance_m"][1] < 1e6
    # A ray pointing away from the Earth misses.
    miss = world.pick(o[:1], -d[:1])
    assert not miss["hit"][0] and miss["surface"][0] == 255 and np.isnan(miss["distance_m"][0])


def test_sea_state_is_pierson_moskowitz_in_deep_water_and_nan_on_land(world):
    # Pierson-Moskowitz: Hs = 4 sqrt(0.0081 / 5) g / wp^2, wp = 0.877 g / U
    # (the spectrum is integrated from 0.2 to 20 wp: 0.2 %).
    lat, lon = mixed_points(400)
    r = world.sea_state(lat, lon)
    assert sorted(r) == ["hs_m", "peak_period_s", "peak_wavelength_m", "wave_from_deg"]
    ocean = world.classify(lat, lon) == geocean.SURFACE_OCEAN
    g, u = 9.80665, 10.0
    wp = 0.877 * g / u
    hs = 4.0 * np.sqrt(0.0081 / 5.0) * g / wp**2
    assert np.allclose(r["hs_m"][ocean], hs, rtol=2e-3, atol=0)
    assert np.allclose(r["peak_period_s"][ocean], 2 * np.pi / wp, rtol=1e-12, atol=0)
    for v in r.values():
        assert np.all(np.isnan(v[~ocean]))
    assert np.all((r["wave_from_deg"][ocean] >= 0) & (r["wave_from_deg"][ocean] < 360))
