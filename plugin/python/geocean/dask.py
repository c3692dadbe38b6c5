"""Geocean queries on Dask arrays, on any scheduler (threads, processes,
``dask.distributed`` clusters of any number of machines).

    import dask.array as da, geocean.dask
    lat = da.random.uniform(-80, 80, 10**8, chunks=10**6)
    lon = da.random.uniform(-180, 180, 10**8, chunks=10**6)
    r = geocean.dask.query(lat, lon, t=0.0, waves="gerstner", wind_mps=12.0)
    mean_height = da.nanmean(r["sea_height_m"]).compute()

Each chunk is one ``Ocean.query``. The graph carries only the keyword
arguments of ``geocean.Ocean`` (strings and numbers), never an Ocean: each
worker process builds its Ocean from them once, at its first chunk, and
reuses it for every later chunk (``_ocean_for``). So every worker needs the
``geocean`` package and the raster files at the paths given (with
``mask=None``/``elevation=None``: the bundled world where its geocean finds
it, or under ``$GEOCEAN_DATA``). See docs/PYTHON.md.
"""

import itertools
import threading

import numpy as np
import dask.array as da
from dask.base import tokenize
from dask.highlevelgraph import HighLevelGraph

import geocean

# name -> (dtype, trailing axis length or 0). The same names as Ocean.query.
_FIELDS = {
    "surface": (np.uint8, 0),
    "elevation_m": (np.float32, 0),
    "sea_height_m": (np.float64, 0),
    "normal_enu": (np.float64, 3),
    "vertical_velocity_mps": (np.float64, 0),
}

_oceans = {}
_oceans_lock = threading.Lock()
_builds = 0  # Oceans this process built (tests check a worker builds one)


def _key(ocean_args):
    return tuple(sorted((k, repr(v)) for k, v in ocean_args.items()))


def _ocean_for(ocean_args):
    """This process's Ocean for these arguments, built at the first call."""
    key = _key(ocean_args)
    with _oceans_lock:  # threads of one worker share one Ocean (thread-safe queries)
        ocean = _oceans.get(key)
        if ocean is None:
            global _builds
            ocean = _oceans[key] = geocean.Ocean(**ocean_args)
            _builds += 1
        return ocean


def _query_chunk(lat, lon, t, ocean_args, horizontal_velocity):
    return _ocean_for(ocean_args).query(lat, lon, t, horizontal_velocity=horizontal_velocity)


def _field(result, name):
    return result[name]


def query(lat, lon, t=0.0, *, horizontal_velocity=False, **ocean_args):
    """``Ocean(**ocean_args).query(lat, lon, t)`` chunk by chunk, lazily.

    lat, lon : dask or numpy arrays of the same shape (degrees, as
        ``Ocean.query``); numpy inputs become one chunk.
    t : float (seconds, for all points) or an array of lat's shape.
    ocean_args : keyword arguments of ``geocean.Ocean`` (plain values:
        they travel to the workers).

    Returns a dict of dask arrays named as ``Ocean.query``'s outputs, with
    lat's chunks (``normal_enu`` has a trailing axis of 3, one chunk). All
    outputs of one chunk come from one query task: computing several
    outputs together (``dask.compute(*r.values())``) queries each chunk once.
    """
    if "t" in ocean_args:
        raise TypeError("t is a query argument, not an Ocean argument")
    lat = da.asarray(lat)
    lon = da.asarray(lon)
    if lat.shape != lon.shape:
        raise ValueError(f"lat has shape {lat.shape} but lon has shape {lon.shape}")
    per_point = np.ndim(t) != 0
    if per_point:
        t = da.asarray(t)
        if t.shape != lat.shape:
            raise ValueError(f"t has shape {t.shape}: expected a scalar or lat's shape {lat.shape}")
        _, (lat, lon, t) = da.unify_chunks(lat, _idx(lat), lon, _idx(lat), t, _idx(lat))
    else:
        t = float(t)
        _, (lat, lon) = da.unify_chunks(lat, _idx(lat), lon, _idx(lat))
    fields = dict(_FIELDS)
    if horizontal_velocity:
        fields["horizontal_velocity_en_mps"] = (np.float64, 2)
    token = tokenize(lat, lon, t, _key(ocean_args), horizontal_velocity)
    qname = "geocean-query-" + token
    blocks = list(itertools.product(*(range(len(c)) for c in lat.chunks)))
    qdsk = {}
    for b in blocks:
        tb = (t.name,) + b if per_point else t
        qdsk[(qname,) + b] = (_query_chunk, (lat.name,) + b, (lon.name,) + b, tb, ocean_args, horizontal_velocity)
    deps = [lat, lon] + ([t] if per_point else [])
    out = {}
    for name, (dtype, trailing) in fields.items():
        fname = f"geocean-{name}-{token}"
        extra = (0,) if trailing else ()
        dsk = dict(qdsk)
        for b in blocks:
            dsk[(fname,) + b + extra] = (_field, (qname,) + b, name)
        graph = HighLevelGraph.from_collections(fname, dsk, dependencies=deps)
        chunks = lat.chunks + (((trailing,),) if trailing else ())
        out[name] = da.Array(graph, fname, chunks, dtype=dtype)
    return out


def _idx(a):
    return "".join(chr(ord("i") + k) for k in range(a.ndim))
