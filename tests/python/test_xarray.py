# geocean.xarray.query on Datasets: coordinates kept, grids broadcast,
# datetime64 times as seconds since the origin, dask-backed inputs.
import numpy as np
import pytest
import xarray as xr

import geocean
import geocean.xarray as gx
from conftest import mixed_points


def test_points_dataset_with_datetime_times(world):
    lat, lon = mixed_points(400)
    times = np.datetime64("2024-03-01T12:00:00", "ns") + np.arange(400) * np.timedelta64(1500, "ms")
    ds = xr.Dataset({"lat": ("obs", lat), "lon": ("obs", lon), "time": ("obs", times)},
                    coords={"ship": ("obs", np.arange(400) % 7)})
    out = gx.query(ds)
    t = (times - np.datetime64("1970-01-01", "ns")) / np.timedelta64(1, "s")
    ref = world.query(lat, lon, t)
    for k in ref:
        np.testing.assert_array_equal(out[k].values, ref[k])
    assert out["normal_enu"].dims == ("obs", "enu")
    assert list(out["enu"].values) == ["e", "n", "u"]
    np.testing.assert_array_equal(out["ship"].values, np.arange(400) % 7)
    assert out["sea_height_m"].attrs["units"] == "m"
    assert out["surface"].attrs["flag_meanings"] == "ocean land lake"


def test_time_origin_and_numeric_seconds(world):
    lat, lon = np.array([0.0, 10.0]), np.array([-30.0, -40.0])
    ds = xr.Dataset(coords={"lat": ("p", lat), "lon": ("p", lon),
                            "time": ("p", np.array(["2000-01-01T00:01:00"] * 2, "datetime64[ns]"))})
    a = gx.query(ds, time_origin="2000-01-01")
    b = gx.query(xr.Dataset(coords={"lat": ("p", lat), "lon": ("p", lon), "time": ("p", [60.0, 60.0])}))
    np.testing.assert_array_equal(a["sea_height_m"].values, b["sea_height_m"].values)
    np.testing.assert_array_equal(a["sea_height_m"].values, world.query(lat, lon, 60.0)["sea_height_m"])


def test_grid_broadcasts_lat_and_lon(world):
    ds = xr.Dataset(coords={"lat": np.linspace(30.0, 40.0, 11), "lon": np.linspace(-10.0, 0.0, 21)})
    out = gx.query(ds, t=5.0, waves="gerstner")
    assert out["sea_height_m"].dims == ("lat", "lon") and out["sea_height_m"].shape == (11, 21)
    la, lo = np.meshgrid(ds.lat.values, ds.lon.values, indexing="ij")
    ref = geocean.Ocean(waves="gerstner").query(la, lo, 5.0)
    np.testing.assert_array_equal(out["sea_height_m"].values, ref["sea_height_m"])
    np.testing.assert_array_equal(out["lat"].values, ds.lat.values)


def test_given_ocean_and_other_names(world):
    ds = xr.Dataset({"y": ("n", [0.0]), "x": ("n", [-30.0])})
    out = gx.query(ds, world, lat="y", lon="x", t=1.0)
    assert out["sea_height_m"].values[0] == world.query([0.0], [-30.0], 1.0)["sea_height_m"][0]
    with pytest.raises(KeyError, match="no coordinate or variable 'lat'"):
        gx.query(ds, world)
    with pytest.raises(TypeError, match="either ocean= or Ocean arguments"):
        gx.query(ds, world, lat="y", lon="x", waves="fft")


def test_dask_backed_dataset(world):
    lat, lon = mixed_points(5000)
    ds = xr.Dataset({"lat": ("obs", lat), "lon": ("obs", lon), "time": ("obs", np.linspace(0, 50, 5000))})
    out = gx.query(ds.chunk({"obs": 1000}))
    assert out["sea_height_m"].chunks is not None  # lazy
    ref = world.query(lat, lon, np.linspace(0, 50, 5000))
    np.testing.assert_array_equal(out["sea_height_m"].values, ref["sea_height_m"])
    np.testing.assert_array_equal(out["normal_enu"].values, ref["normal_enu"])
