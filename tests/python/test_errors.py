# Bad input raises Python exceptions whose message names the argument, the
# index and the value (the C++ message).
import numpy as np
import pytest

import geocean


@pytest.mark.parametrize("lat,lon,msg", [
    ([10.0, 91.0], [0.0, 0.0], r"lat\[1\] = 91 is outside \[-90, 90\] degrees"),
    ([10.0, -90.5], [0.0, 0.0], r"lat\[1\] = -90.5 is outside"),
    ([np.nan, 0.0], [0.0, 0.0], r"lat\[0\] = nan is not a number"),
    ([0.0, 0.0, 0.0], [0.0, 0.0, 400.0], r"lon\[2\] = 400 is outside \[-180, 360\] degrees"),
    ([0.0], [np.inf], r"lon\[0\] = inf is outside"),
])
def test_bad_coordinates(world, lat, lon, msg):
    for call in (lambda: world.query(lat, lon), lambda: world.classify(lat, lon),
                 lambda: world.elevation(lat, lon)):
        with pytest.raises(ValueError, match=msg):
            call()


def test_bad_coordinate_index_is_in_the_callers_shape(world):
    lat = np.zeros((3, 4))
    lat[2, 1] = 95.0
    with pytest.raises(ValueError, match=r"lat\[2, 1\] = 95 is outside"):
        world.query(lat, np.zeros((3, 4)))


def test_bad_times(world):
    with pytest.raises(ValueError, match=r"t = nan s is not finite"):
        world.query([0.0], [0.0], np.nan)
    with pytest.raises(ValueError, match=r"t\[1\] = inf s is not finite"):
        world.query([0.0, 1.0], [0.0, 1.0], [0.0, np.inf])
    # Beyond the sea's time bound (plugin/waves/TimeRange.h): the phase w t
    # has no precision left; Unix-epoch seconds (~1.8e9) are well inside.
    with pytest.raises(ValueError, match=r"t\[1\] = 1e\+33 s is outside -1e12 \.\. 1e12 s"):
        world.query([0.0, 1.0], [0.0, 1.0], [0.0, 1e33])
    with pytest.raises(ValueError, match=r"t = -2e\+12 s is outside"):
        world.query([0.0], [0.0], -2e12)
    assert np.isfinite(world.query([0.0], [-150.0], 1e12)["sea_height_m"]).all()


def test_wrong_shapes(world):
    with pytest.raises(ValueError, match=r"lat has shape \(3,\) but lon has shape \(2,\)"):
        world.query(np.zeros(3), np.zeros(2))
    with pytest.raises(ValueError, match=r"t has shape \(2,\): expected a scalar or lat's shape \(3,\)"):
        world.query(np.zeros(3), np.zeros(3), np.zeros(2))
    with pytest.raises(ValueError, match=r"origins has shape \(2, 2\): expected \(n, 3\)"):
        world.pick(np.zeros((2, 2)), np.zeros((2, 2)))
    with pytest.raises(ValueError, match=r"directions has shape \(1, 3\) but origins has shape \(2, 3\)"):
        world.pick(np.zeros((2, 3)), np.ones((1, 3)))


def test_bad_rays(world):
    o = np.array([[7e6, 0.0, 0.0]])
    with pytest.raises(ValueError, match=r"directions\[0\] is zero"):
        world.pick(o, np.zeros((1, 3)))
    with pytest.raises(ValueError, match=r"origins\[0, 1\] = nan is not finite"):
        world.pick(np.array([[7e6, np.nan, 0.0]]), -o)


def test_missing_raster_file(tmp_path):
    missing = tmp_path / "no_such_mask.tif"
    with pytest.raises(geocean.RasterError, match="no_such_mask.tif: no such file") as e:
        geocean.Ocean(mask=missing)
    assert isinstance(e.value, OSError)
    with pytest.raises(geocean.RasterError, match="etopo_nope.tif"):
        geocean.Ocean(elevation=str(tmp_path / "etopo_nope.tif"))


def test_unreadable_raster_file(tmp_path):
    bad = tmp_path / "garbage.tif"
    bad.write_bytes(b"not a tiff at all")
    with pytest.raises(geocean.RasterError, match="garbage.tif"):
        geocean.Ocean(mask=bad)


@pytest.mark.parametrize("kw,msg", [
    (dict(waves="tsunami"), r"waves = 'tsunami' is not a wave model"),
    (dict(wind_mps=100.0), r"windSpeedMps = 100 is invalid \(expected 0.2 .. 60 m/s\)"),
    (dict(beaufort=13), r"beaufort = 13 is not a Beaufort number 0 .. 12"),
    (dict(beaufort=2.5), r"beaufort = 2.5 is not a Beaufort number"),
    (dict(seed=-1), r"seed = -1 is not an integer"),
    (dict(georef="utm"), r"georef = 'utm' is neither 'file' nor 'global'"),
    (dict(mask_encoding="0=sea"), r"mask encoding class 'sea' is not ocean, land or lake"),
    (dict(anchor=(95.0, 0.0)), r"anchor = \(95, 0\) is outside"),
    (dict(waves="gerstner", gerstner_components=0), r"gerstnerComponents = 0"),
])
def test_bad_ocean_arguments(kw, msg):
    with pytest.raises(ValueError, match=msg):
        geocean.Ocean(**kw)


def test_bad_layer_type():
    with pytest.raises(TypeError, match=r"mask = 3: expected a file path"):
        geocean.Ocean(mask=3)


def test_queries_without_rasters():
    o = geocean.Ocean(mask=False, elevation=False)
    with pytest.raises(geocean.NotReadyError, match=r"Ocean.classify: no mask or elevation raster"):
        o.classify([0.0], [0.0])
    with pytest.raises(geocean.NotReadyError, match=r"Ocean.elevation: no elevation raster"):
        o.elevation([0.0], [0.0])
    # The sea surface needs no raster: deep ocean everywhere.
    r = o.query([48.86], [2.35])
    assert r["surface"][0] == geocean.SURFACE_OCEAN and np.isfinite(r["sea_height_m"][0])
    assert np.isnan(r["elevation_m"][0])
