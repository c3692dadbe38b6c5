#!/usr/bin/env bash
# Soak of the viewer (issue 17 item 3): FRAMES frames of `geocean view`
# under Xvfb (llvmpipe) flying the scripted flight from orbit to 2 m over the
# middle of the Strait of Gibraltar (35.96 N, 5.5 W: open water 5 km from
# either coast, where the boats spawn) FLIGHTS times over, with everything
# on: terrain and its tile pool, the ocean through the plugin ABI,
# reflections and refraction, the HUD and its sea query, BOATS floating
# boats simulated by the plugin. Then glibc's malloc bytes in use per frame
# (mallinfo2, `geocean view --stats`) are checked:
#   flat = the heap between transients does not grow: each flight's
#   minimum of heap in use, from flight 2 on, within BOUND_KIB (1024) of
#   flight 2's (a leak of 175 B per frame fails over 3 x 2,000 frames), and
#   the last flight sets no maximum more than BOUND_KIB above the earlier
#   flights'. Flight 1 is the warm-up: it makes the terrain tiles the poses
#   need, grows the ocean's grow-only
#   buffers to the largest grid (near the sea), compiles the shaders; the
#   later flights draw the same poses, so what they add is a leak. Maxima
#   alone would not do: a transient block (up to 3 MB) comes and goes between
#   frames, and after a restart from 2 m to orbit. Within one flight the heap
#   follows the altitude (measured: +2.3 MB in the last 20 m of the descent,
#   then constant), so a single descent cannot tell a leak from a working set.
# Usage: tests/soak/soak_flight.sh BUILD_DIR [FRAMES=10000] [SIZE=160x90] [BOATS=20] [FLIGHTS=5]
# KEEP_CSV=FILE keeps the per-frame stats.
set -euo pipefail
build=${1:?usage: soak_flight.sh BUILD_DIR [FRAMES] [SIZE] [BOATS]}
frames=${2:-10000}
size=${3:-160x90}
boats=${4:-20}
flights=${5:-5}
bound_kib=${BOUND_KIB:-1024}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
stats=$dir/flight.csv
t0=$SECONDS
if ! xvfb-run -a -s '-screen 0 640x480x24' "$build/geocean" view --size "$size" --fly-to 35.96,-5.5 \
     --frames "$frames" --flight-frames $((frames / flights)) --boats "$boats" --stats "$stats" >"$dir/out" 2>"$dir/err"; then
  echo "soak_flight: geocean view failed:" >&2
  cat "$dir/err" >&2
  exit 2
fi
wall=$((SECONDS - t0))
[ -n "${KEEP_CSV:-}" ] && cp "$stats" "$KEEP_CSV"
# stats: frame,wall_s,lat,lon,alt_m,sea_height_m,fps,rss_kb,heap_in_use_kb,heap_held_kb,tiles,tiles_built
awk -F, -v per=$((frames / flights)) -v frames="$frames" -v bound="$bound_kib" -v wall="$wall" -v boats="$boats" -v size="$size" '
NR == 1 { next }
{
  n++; f = $1; h = $9; r = $8; k = int(f / per)
  if (!(k in lo) || h < lo[k]) lo[k] = h
  if (!(k in hi) || h > hi[k]) hi[k] = h
  if (!(k in rhi) || r > rhi[k]) rhi[k] = r
  if (k > nk) nk = k
  if (f == per - 1) { altEnd = $5; tiles1 = $12 }
  tiles = $12
}
END {
  upLo = 0; downLo = 0; hiBefore = 0
  for (k = 1; k <= nk; k++) {
    if (lo[k] - lo[1] > upLo) upLo = lo[k] - lo[1]
    if (lo[1] - lo[k] > downLo) downLo = lo[1] - lo[k]
    later = later sprintf(" %d..%d", lo[k], hi[k])
  }
  for (k = 0; k < nk; k++) if (hi[k] > hiBefore) hiBefore = hi[k]
  ok = n == frames && nk >= 2 && upLo <= bound && downLo <= bound && hi[nk] - hiBefore <= bound
  printf "soak_flight: %d frames = %d flights of %d (%s, %d boats, orbit -> %.1f m; terrain tiles made %d in flight 1, %d in all) " \
         "in %d s; malloc in use (kB, min..max per flight) flight 1 %d..%d, then%s: minima of flights 2-%d within " \
         "%+d / %+d kB of flight 2, last flight max %+d kB over the earlier flights; resident max flight 1 %d kB, " \
         "last flight %d kB: %s\n",
         n, nk + 1, per, size, boats, altEnd, tiles1, tiles, wall, lo[0], hi[0], later, nk + 1, -downLo, upLo,
         hi[nk] - hiBefore, rhi[0], rhi[nk], ok ? "flat" : "NOT FLAT"
  exit ok ? 0 : 1
}' "$stats"
