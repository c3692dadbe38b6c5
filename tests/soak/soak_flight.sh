#!/usr/bin/env bash
# Soak of the viewer (issue 17 item 3): one scripted flight from orbit to
# 2 m over the middle of the Strait of Gibraltar (35.96 N, 5.5 W: open water
# 5 km from either coast, where the boats spawn) with everything on (terrain and its tile
# pool, the ocean through the plugin ABI, reflections and refraction, the
# HUD and its sea query, BOATS floating boats simulated by the plugin),
# FRAMES frames in a SIZE window under Xvfb (llvmpipe), then glibc's malloc
# bytes in use per frame (mallinfo2, `geocean view --stats`) checked:
#   flat = from frame WARM = FRAMES/10 on (shaders compiled, grow-only
#   buffers at their size) heap in use stays within BOUND_KIB (1024) of the
#   first window after it (details below), no trend over 100 B per frame.
# Usage: tests/soak/soak_flight.sh BUILD_DIR [FRAMES=10000] [SIZE=160x90] [BOATS=20]
# KEEP_CSV=FILE keeps the per-frame stats.
# Prints one line of figures; exit 0 = flat, 1 = not, 2 = could not run.
set -euo pipefail
build=${1:?usage: soak_flight.sh BUILD_DIR [FRAMES] [SIZE] [BOATS]}
frames=${2:-10000}
size=${3:-160x90}
boats=${4:-20}
warm=$((frames / 10))
bound_kib=${BOUND_KIB:-1024}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
stats=$dir/flight.csv
t0=$SECONDS
if ! xvfb-run -a -s '-screen 0 640x480x24' "$build/geocean" view --size "$size" --fly-to 35.96,-5.5 \
     --frames "$frames" --boats "$boats" --stats "$stats" >"$dir/out" 2>"$dir/err"; then
  echo "soak_flight: geocean view failed:" >&2
  cat "$dir/err" >&2
  exit 2
fi
wall=$((SECONDS - t0))
[ -n "${KEEP_CSV:-}" ] && cp "$stats" "$KEEP_CSV"
# stats: frame,wall_s,lat,lon,alt_m,sea_height_m,fps,rss_kb,heap_in_use_kb,heap_held_kb,tiles,tiles_built
# A frame's sample may catch a transient block in use (measured: +3 MB that
# comes and goes from frame to frame), so the check is on windows of
# frames/20: each window's minimum (the heap between transients) and
# maximum after the warm-up must stay within BOUND_KIB of the first such
# window's, and the minima's least-squares slope under 100 B per frame.
awk -F, -v warm="$warm" -v frames="$frames" -v bound="$bound_kib" -v wall="$wall" -v boats="$boats" -v size="$size" '
NR == 1 { next }
{
  n++; f = $1; h = $9; r = $8
  if (n == 1) { h0 = h; r0 = r; alt0 = $5 }
  if (f >= warm) {
    w = int((f - warm) / win)
    if (!(w in lo) || h < lo[w]) lo[w] = h
    if (!(w in hi) || h > hi[w]) hi[w] = h
    if (r > rmax) rmax = r
    if (w > nw) nw = w
  }
  hl = h; rl = r; altl = $5; tiles = $12
}
BEGIN { win = int(frames / 20) }
END {
  up = 0; upHi = 0; down = 0
  for (w = 0; w <= nw; w++) {
    if (lo[w] - lo[0] > up) up = lo[w] - lo[0]
    if (lo[0] - lo[w] > down) down = lo[0] - lo[w]
    if (hi[w] - hi[0] > upHi) upHi = hi[w] - hi[0]
    x = warm + (w + 0.5) * win; m++; sx += x; sy += lo[w]; sxx += x * x; sxy += x * lo[w]
  }
  slope = (m * sxy - sx * sy) / (m * sxx - sx * sx) * 1024  # bytes per frame
  ok = n == frames && up <= bound && down <= bound && upHi <= bound && slope < 100 && slope > -100
  printf "soak_flight: %d frames (%s, %d boats, altitude %.0f m -> %.1f m, %d terrain tiles made) in %d s; " \
         "malloc in use: first %d kB; %d windows of %d frames from frame %d: minimum %d kB in the first, " \
         "then within %+d / %+d kB of it, maximum %d kB in the first, then at most %+d kB; slope of the minima " \
         "%.1f B/frame; last %d kB; resident: first %d kB, max after frame %d %d kB, last %d kB: %s\n",
         n, size, boats, alt0, altl, tiles, wall, h0, nw + 1, win, warm, lo[0], -down, up, hi[0], upHi, slope,
         hl, r0, warm, rmax, rl, ok ? "flat" : "NOT FLAT"
  exit ok ? 0 : 1
}' "$stats"
