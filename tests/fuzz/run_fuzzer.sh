#!/bin/sh
# ctest's driver for the libFuzzer targets (tests/fuzz/CMakeLists.txt).
#   run_fuzzer.sh replay <fuzzer> <seed dir> <regression dir>
#       runs every seed and every regression input once (no mutation)
#   run_fuzzer.sh fuzz <fuzzer> <seed dir> <work dir> <seconds>
#       fuzzes for <seconds> from a copy of the seeds (the repository's
#       corpus is never written); a crash leaves its input in
#       <work dir>/artifacts/ and fails the test.
set -eu
mode=$1 fuzzer=$2 seeds=$3
case "$mode" in
  replay)
    dirs="$seeds"
    [ -d "$4" ] && dirs="$dirs $4"
    # -runs=0: execute the given inputs, nothing else.
    exec "$fuzzer" -runs=0 $dirs
    ;;
  fuzz)
    work=$4 seconds=$5
    rm -rf "$work"
    mkdir -p "$work/corpus" "$work/artifacts"
    cp "$seeds"/* "$work/corpus/"
    # One process (one core); -timeout: an input slower than 10 s is a hang;
    # -rss_limit_mb: a raster that allocates without bound is a bug.
    exec "$fuzzer" "$work/corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2560 \
      -artifact_prefix="$work/artifacts/" -print_final_stats=1 -print_pcs=0
    ;;
  *)
    echo "usage: $0 replay|fuzz ..." >&2
    exit 2
    ;;
esac
