# Shared fixtures. ctest sets PYTHONPATH=<build>/python and GEOCEAN_EXE
# (tests/python/CMakeLists.txt); run by hand the same way.
import os
import subprocess

import numpy as np
import pytest

import geocean


@pytest.fixture(scope="session")
def world():
    """The bundled world with the default sea state (noise, 10 m/s from 270)."""
    return geocean.Ocean()


@pytest.fixture(scope="session")
def geocean_exe():
    exe = os.environ.get("GEOCEAN_EXE")
    if not exe:
        pytest.fail("GEOCEAN_EXE is not set (the geocean executable, for the CLI comparisons)")
    return exe


def run_cli(exe, args, stdin=None):
    p = subprocess.run([exe] + args, input=stdin, capture_output=True, text=True, check=False)
    assert p.returncode == 0, f"{exe} {' '.join(args)}: exit {p.returncode}: {p.stderr}"
    return p.stdout


def mixed_points(n, seed=7):
    """Points over the whole globe plus coastal ones (Gibraltar, the Baltic,
    the Great Lakes) so that ocean, land and lake all occur."""
    rng = np.random.default_rng(seed)
    lat = rng.uniform(-85.0, 85.0, n)
    lon = rng.uniform(-180.0, 180.0, n)
    k = n // 4
    lat[:k] = rng.uniform(35.0, 37.0, k)
    lon[:k] = rng.uniform(-7.0, -4.0, k)
    lat[k:2 * k] = rng.uniform(41.0, 49.0, k)
    lon[k:2 * k] = rng.uniform(-92.0, -76.0, k)
    return lat, lon
