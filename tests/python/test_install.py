# `cmake --install` gives a working package: installed into a fresh prefix,
# imported from there (not the build tree), it finds the installed world
# and answers as the build tree does.
import os
import subprocess
import sys

import numpy as np

import geocean

SCRIPT = """
import sys, numpy as np, geocean
assert geocean.__file__.startswith(sys.argv[1]), geocean.__file__
print(repr(float(geocean.Ocean().query(np.array([0.0]), np.array([-30.0]), 7.0)["sea_height_m"][0])))
print(geocean.default_world_dir())
"""


def test_installed_package(tmp_path):
    build, cmake = os.environ["GEOCEAN_BUILD_DIR"], os.environ["CMAKE_COMMAND"]
    prefix = tmp_path / "prefix"
    for comp in ("python", "plugin"):  # the package, and the world it loads by default
        subprocess.run([cmake, "--install", build, "--prefix", str(prefix), "--component", comp],
                       check=True, capture_output=True)
    site = [p for p in prefix.glob("lib/python*/dist-packages")]
    assert len(site) == 1, list(prefix.rglob("*"))
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "GEOCEAN_DATA")}
    env["PYTHONPATH"] = str(site[0])
    p = subprocess.run([sys.executable, "-c", SCRIPT, str(site[0])], env=env, cwd=tmp_path,
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    height, data_dir = p.stdout.split()
    assert os.path.realpath(data_dir) == os.path.realpath(prefix / "share" / "geocean" / "data")
    assert float(height) == geocean.Ocean().query(np.array([0.0]), np.array([-30.0]), 7.0)["sea_height_m"][0]
