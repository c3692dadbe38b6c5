"""Geocean from Python: land/sea classes, terrain elevation and the wave
surface of a WGS84 digital-earth ocean, for numpy arrays of any size.

    import numpy as np, geocean
    ocean = geocean.Ocean(waves="gerstner", wind_mps=12.0)
    r = ocean.query(np.array([36.0, 48.9]), np.array([-5.6, 2.35]), t=10.0)

Units everywhere: degrees (geodetic WGS84 latitude/longitude), metres
(heights above the WGS84 ellipsoid, terrain elevation with ocean depth
negative, ECEF coordinates), seconds (simulation time), m/s (velocities).

The numbers come from the same C++ code as ``geocean query`` (the ocean
façade, plugin/ocean/Ocean.h), through a pybind11 module: contiguous
float64 inputs are read in place, and the GIL is released while a batch
runs (on all cores). See docs/PYTHON.md.
"""

import os as _os

from . import _config
from ._geocean import NotReadyError, RasterError, SURFACE_NAMES
from ._geocean import Core as _Core
from ._geocean import _beaufort_wind_mps

__all__ = ["Ocean", "SURFACE_NAMES", "SURFACE_OCEAN", "SURFACE_LAND", "SURFACE_LAKE",
           "RasterError", "NotReadyError", "default_world_dir"]
__version__ = _config.VERSION

#: Codes of the ``surface`` arrays: ``SURFACE_NAMES[code]`` is the CLI's name.
SURFACE_OCEAN, SURFACE_LAND, SURFACE_LAKE = 0, 1, 2

def default_world_dir():
    """The directory of the bundled world (``landmask_5m.tif``, 5' mask;
    ``etopo_20m.tif``, 20' ETOPO relief): ``$GEOCEAN_DATA`` if set, else
    the data this package was built or installed with."""
    env = _os.environ.get("GEOCEAN_DATA")
    if env:
        return env
    return _os.path.normpath(_os.path.join(_os.path.dirname(__file__), _config.DATA_DIR))


def _layer(value, bundled_name, what):
    # None: the bundled world's layer; False: no such layer; else a path.
    if value is None:
        return _os.path.join(default_world_dir(), bundled_name)
    if value is False:
        return None
    if isinstance(value, (str, _os.PathLike)):
        return _os.fspath(value)
    raise TypeError(f"{what} = {value!r}: expected a file path, None (bundled world) or False (none)")


class Ocean:
    """One ocean: rasters (mask, elevation) and a sea state, queried in batches.

    Parameters
    ----------
    mask : path, None or False
        Land/sea/lake mask raster (GeoTIFF or any image OpenImageIO reads;
        values 0 ocean, 1 land, 2 lake unless ``mask_encoding`` says
        otherwise). None (default): the bundled 5' world mask. False: no
        mask (classes then come from the elevation: below 0 m is ocean).
    elevation : path, None or False
        Terrain elevation raster in metres, ocean depth negative (sets the
        water depth of the Gerstner model). None: the bundled 20' ETOPO
        relief. False: none (deep water everywhere).
    waves : str
        Wave model: "noise" (default), "noise-paper", "gerstner", "fft", or
        "none" (classes and elevation only; sea outputs are NaN).
    wind_mps : float
        Wind speed at 19.5 m, m/s, 0.2 .. 60.
    wind_from_deg : float
        Direction the wind blows from, degrees clockwise from north.
    fetch_m : float
        Fetch, metres; 0 = fully developed sea (Pierson-Moskowitz), > 0 JONSWAP.
    seed : int
        Random seed of the wave field, 0 .. 2**32 - 1.
    beaufort : int or None
        If given (0 .. 12), replaces ``wind_mps`` by the middle of that
        Beaufort class (WMO, converted to 19.5 m).
    gerstner_components, noise_octaves : int
        1 .. 64 and 1 .. 12.
    anchor : (lat_deg, lon_deg)
        Where the wind direction holds exactly (Gerstner).
    reference_depth_m : float
        Depth (m) that sets the Gerstner wave numbers; default deep water.
    mask_encoding : str or None
        How mask values map to classes, e.g. "0=ocean,1=land,2=lake,3=land".
    georef : "file" or "global"
        Georeferencing from the file (GeoTIFF tags, world file) or "whole
        Earth, north up, column 0 at -180 degrees".
    few_lookups : bool
        Read only the tiles lookups touch (tiled TIFFs), for a handful of
        points; default: decode rasters into memory (fast batches).

    Errors: ``RasterError`` (an OSError) names the file and the field;
    ``ValueError`` names the parameter and the value.

    An Ocean is thread-safe (queries from any number of threads) and
    picklable: it pickles as its constructor arguments, so the receiver
    (e.g. a Dask worker) rebuilds it from the same files.
    """

    def __init__(self, mask=None, elevation=None, waves="noise", wind_mps=10.0,
                 wind_from_deg=270.0, fetch_m=0.0, seed=1, *, beaufort=None,
                 gerstner_components=16, noise_octaves=8, anchor=(0.0, 0.0),
                 reference_depth_m=1e30, mask_encoding=None, georef="file",
                 few_lookups=False):
        self._args = dict(mask=mask, elevation=elevation, waves=waves, wind_mps=wind_mps,
                          wind_from_deg=wind_from_deg, fetch_m=fetch_m, seed=seed,
                          beaufort=beaufort, gerstner_components=gerstner_components,
                          noise_octaves=noise_octaves, anchor=tuple(anchor),
                          reference_depth_m=reference_depth_m, mask_encoding=mask_encoding,
                          georef=georef, few_lookups=few_lookups)
        if beaufort is not None:
            if isinstance(beaufort, bool) or int(beaufort) != beaufort:
                raise ValueError(f"beaufort = {beaufort!r} is not a Beaufort number 0 .. 12")
            wind_mps = _beaufort_wind_mps(int(beaufort))  # ValueError outside 0 .. 12
        if len(self._args["anchor"]) != 2:
            raise ValueError(f"anchor = {anchor!r}: expected (lat_deg, lon_deg)")
        if not 0 <= int(seed) <= 0xFFFFFFFF or int(seed) != seed:
            raise ValueError(f"seed = {seed!r} is not an integer 0 .. 4294967295")
        self._core = _Core(
            mask=_layer(mask, "landmask_5m.tif", "mask"),
            elevation=_layer(elevation, "etopo_20m.tif", "elevation"),
            georef=georef, few_lookups=bool(few_lookups), mask_encoding=mask_encoding,
            waves=waves, wind_mps=float(wind_mps), wind_from_deg=float(wind_from_deg),
            fetch_m=float(fetch_m), seed=int(seed), gerstner_components=int(gerstner_components),
            noise_octaves=int(noise_octaves), anchor_lat_deg=float(anchor[0]),
            anchor_lon_deg=float(anchor[1]), reference_depth_m=float(reference_depth_m))

    def __reduce__(self):
        return (_rebuild, (self._args,))

    def __repr__(self):
        shown = ", ".join(f"{k}={v!r}" for k, v in self._args.items())
        return f"geocean.Ocean({shown})"

    @property
    def args(self):
        """The constructor arguments (a copy), as keyword arguments."""
        return dict(self._args)

    def query(self, lat, lon, t=0.0, *, horizontal_velocity=False):
        """Class, elevation and the sea surface at points.

        Parameters
        ----------
        lat, lon : array_like of float, same shape (any number of dimensions)
            Geodetic WGS84 latitude in [-90, 90] and longitude in
            [-180, 360], degrees. C-contiguous float64 arrays are read in
            place; anything else is converted (copied) once.
        t : float or array_like of float
            Simulation time, seconds: one for all points, or one per point
            (lat's shape), within -1e12 .. 1e12 s (Unix-epoch seconds fit;
            beyond, a wave's phase has no precision left: ValueError).
            The same t always gives the same surface.
        horizontal_velocity : bool
            Also return ``horizontal_velocity_en_mps`` (costs a second
            surface evaluation per ocean point).

        Returns
        -------
        dict of numpy arrays, named as ``geocean query --format json``'s fields:
            ``surface`` (uint8, lat's shape): 0 ocean, 1 land, 2 lake
            (``SURFACE_NAMES[code]``).
            ``elevation_m`` (float32): terrain elevation, m, ocean depth
            negative (bilinear); NaN without elevation data.
            ``sea_height_m`` (float64): height above the WGS84 ellipsoid, m,
            of the sea surface exactly above the point (the waves'
            horizontal displacement is inverted); NaN on land and lakes.
            ``normal_enu`` (float64, shape + (3,)): unit normal, east, north,
            up at the point; NaN on land and lakes.
            ``vertical_velocity_mps`` (float64): d(sea_height_m)/dt, m/s; NaN
            on land and lakes.
            ``horizontal_velocity_en_mps`` (float64, shape + (2,), only if
            asked): east/north velocity, m/s, of the water particle now at
            the surface above the point.

        Raises
        ------
        ValueError
            lat/lon/t out of range or not finite (the message names the
            index and the value), shapes that differ.
        """
        return self._core.query(lat, lon, t, horizontal_velocity)

    def sea_state(self, lat, lon):
        """The sea state at points, as wave models and buoys report it.

        Returns a dict of float64 arrays of lat's shape, named as ``geocean
        query``'s columns: ``hs_m`` (significant wave height, m),
        ``peak_period_s``, ``peak_wavelength_m`` (of the peak frequency at
        the depth that sets the waves' phase, m) and ``wave_from_deg``
        (direction the waves come FROM, degrees clockwise from north); NaN on
        land and lakes. Independent of time.

        Raises
        ------
        ValueError
            lat/lon out of range or not finite, shapes that differ.
        geocean.NotReadyError
            waves='none'.
        """
        return self._core.sea_state(lat, lon)

    def classify(self, lat, lon):
        """Surface class (uint8 codes, see ``SURFACE_NAMES``) at points,
        nearest mask cell. lat, lon in degrees as in :meth:`query`.
        Raises NotReadyError without mask and elevation (both False)."""
        return self._core.classify(lat, lon)

    def elevation(self, lat, lon):
        """Terrain elevation (float32, metres, ocean depth negative,
        bilinear; NaN where the raster has no data or outside a regional
        raster) at points, degrees as in :meth:`query`. Raises
        NotReadyError with ``elevation=False``."""
        return self._core.elevation(lat, lon)

    def pick(self, origins, directions):
        """First hit of rays on terrain or the mean sea surface (WGS84
        ellipsoid where the mask says ocean), Embree refined in double.

        Parameters
        ----------
        origins : array_like, shape (n, 3)
            Ray origins, ECEF metres.
        directions : array_like, shape (n, 3)
            Ray directions, ECEF, any length > 0.

        Returns
        -------
        dict of numpy arrays of length n (the fields of ``geocean pick
        --format json``, NaN where there is no hit):
            ``hit`` (bool); ``kind`` (uint8: 0 none, 1 sea, 2 terrain);
            ``surface`` (uint8 code of the surface hit, 255 for none);
            ``lat``, ``lon`` (degrees), ``height_m`` (above the ellipsoid),
            ``distance_m`` (from the origin, metres); ``point_ecef_m`` (n, 3).

        Up to 16 rays build a scene of only the terrain cells they cross
        (as ``geocean pick --ray`` does); larger batches build the whole
        elevation raster's scene once (about 1 s for the bundled world) and
        reuse it.
        """
        return self._core.pick(origins, directions)

    @property
    def significant_wave_height_m(self):
        """Significant wave height Hs = 4 sqrt(m0), metres, of the sea state's spectrum."""
        return self._core.significant_wave_height_m()


def _rebuild(args):
    return Ocean(**args)
