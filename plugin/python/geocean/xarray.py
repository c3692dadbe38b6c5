"""Geocean queries on xarray Datasets.

    import xarray as xr, geocean.xarray
    ds = xr.Dataset(coords={"lat": lats, "lon": lons, "time": times})
    out = geocean.xarray.query(ds, waves="gerstner")

lat/lon (and time) are found among the Dataset's coordinates or data
variables and broadcast against each other (a grid lat(y) x lon(x) gives a
y x x result). Times may be numbers (seconds of simulation time) or
numpy datetime64 (seconds since ``time_origin``, by default
1970-01-01T00:00:00; the simulation's t = 0 is then the Unix epoch).
Dask-backed inputs give dask-backed outputs through geocean.dask.
"""

import numpy as np
import xarray as xr

import geocean

_ATTRS = {
    "surface": {"long_name": "surface class", "flag_values": np.array([0, 1, 2], np.uint8),
                "flag_meanings": " ".join(geocean.SURFACE_NAMES)},
    "elevation_m": {"long_name": "terrain elevation (ocean depth negative)", "units": "m"},
    "sea_height_m": {"long_name": "sea surface height above the WGS84 ellipsoid", "units": "m"},
    "normal_enu": {"long_name": "unit normal of the sea surface, east-north-up", "units": "1"},
    "vertical_velocity_mps": {"long_name": "d(sea_height_m)/dt", "units": "m s-1"},
    "horizontal_velocity_en_mps": {"long_name": "surface particle velocity, east-north", "units": "m s-1"},
}
_EXTRA_DIM = {"normal_enu": ("enu", ["e", "n", "u"]), "horizontal_velocity_en_mps": ("en", ["e", "n"])}


def _find(ds, name, required):
    if name in ds.variables:
        return ds[name]
    if required:
        raise KeyError(f"the Dataset has no coordinate or variable '{name}' "
                       f"(it has {sorted(map(str, ds.variables))}); pass {name}=... to name it")
    return None


def seconds(time, time_origin="1970-01-01T00:00:00"):
    """Simulation time in seconds (float64) from numbers (taken as seconds),
    timedelta64 or datetime64 (since ``time_origin``)."""
    v = np.asarray(time)
    if np.issubdtype(v.dtype, np.datetime64):
        return (v - np.datetime64(time_origin, "ns")) / np.timedelta64(1, "s")
    if np.issubdtype(v.dtype, np.timedelta64):
        return v / np.timedelta64(1, "s")
    return v.astype(np.float64)


def query(ds, ocean=None, *, lat="lat", lon="lon", time="time", t=None,
          time_origin="1970-01-01T00:00:00", horizontal_velocity=False, **ocean_args):
    """``Ocean.query`` on a Dataset; returns a Dataset of the outputs.

    ds : xarray.Dataset with ``lat``/``lon`` (degrees) and optionally
        ``time`` as coordinates or variables (names changeable).
    ocean : a geocean.Ocean, or None to build one from ``ocean_args``.
    t : seconds for every point when the Dataset has no time.

    The result has one variable per output of ``Ocean.query`` (units in
    their attrs; ``normal_enu`` gains a dimension ``enu``), on the
    broadcast dimensions of lat, lon and time, with ds's coordinates on
    those dimensions kept.
    """
    la, lo = _find(ds, lat, True), _find(ds, lon, True)
    tm = _find(ds, time, False) if t is None else None
    arrays = [la, lo] + ([tm] if tm is not None else [])
    arrays = xr.broadcast(*arrays)
    dims = arrays[0].dims
    lazy = any(a.chunks is not None for a in arrays)
    tv = t if t is not None else 0.0
    if lazy:
        import dask.array as da
        import geocean.dask as gd
        if ocean is not None:
            ocean_args = ocean.args
        data = [a.data if a.chunks is not None else da.asarray(a.values) for a in arrays]
        if tm is not None:
            data[2] = data[2].map_blocks(seconds, time_origin, dtype=np.float64)
            tv = data[2]
        res = gd.query(data[0], data[1], tv, horizontal_velocity=horizontal_velocity, **ocean_args)
    else:
        if ocean is None:
            ocean = geocean.Ocean(**ocean_args)
        elif ocean_args:
            raise TypeError(f"give either ocean= or Ocean arguments, not both ({sorted(ocean_args)})")
        if tm is not None:
            tv = seconds(arrays[2].values, time_origin)
        res = ocean.query(arrays[0].values, arrays[1].values, tv, horizontal_velocity=horizontal_velocity)
    coords = {k: c for k, c in arrays[0].coords.items() if set(c.dims) <= set(dims)}
    for k, c in ds.coords.items():
        if set(c.dims) <= set(dims) and k not in coords:
            coords[k] = c
    out = {}
    for name, v in res.items():
        vd = dims
        if name in _EXTRA_DIM:
            d, labels = _EXTRA_DIM[name]
            vd = dims + (d,)
            coords.setdefault(d, labels)
        out[name] = xr.Variable(vd, v, attrs=_ATTRS.get(name, {}))
    return xr.Dataset(out, coords=coords)
