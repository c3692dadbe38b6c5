#!/usr/bin/env bash
# Geocean quick start on Debian 12 (run as root, or with sudo available).
#   ./quickstart.sh        install dependencies, build, run the main job on the default world
#   ./quickstart.sh test   install dependencies, build, run every test (what CI runs)
set -euo pipefail
cd "$(dirname "$0")"
mode="${1:-run}"

packages=(
  build-essential cmake pkg-config git
  libgeographiclib-dev geographiclib-tools libglm-dev libglfw3-dev
  libopenimageio-dev openimageio-tools libtiff-dev libdeflate-dev libpng-dev libembree-dev libtbb-dev
  libepoxy-dev libegl-dev libegl-mesa0 libgl1-mesa-dri libcli11-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev
  proj-bin gmt gmt-gshhg-low xvfb xauth
  libkissfft-dev libhwy-dev libimgui-dev
  pybind11-dev python3-numpy python3-xarray python3-dask python3-distributed python3-pytest
  libbullet-dev clang libclang-rt-14-dev gmt-gshhg-full xdotool
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi

jobs=$(nproc)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$jobs"

case "$mode" in
  test)
    cd build
    ctest --output-on-failure -j"$jobs" --timeout 900
    ;;
  run)
    ./build/geocean demo
    # (a) The globe: a window on a display, otherwise a rendered flight from
    # orbit to 2 m above the Strait of Gibraltar as PNG frames.
    if [ -n "${DISPLAY:-}" ]; then
      ./build/geocean view --fly-to 36.0,-5.6
    else
      ./build/geocean fly --to 36.0,-5.6 --frames 90 --size 960x540 --out out/flight
      echo "wrote out/flight/frame_*.png and out/flight/timings.csv (no display: geocean view needs one)"
    fi
    ;;
  *)
    echo "usage: $0 [run|test]" >&2
    exit 2
    ;;
esac
