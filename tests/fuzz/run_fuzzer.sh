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
    # A fixed seed (GEOCEAN_FUZZ_SEED, default 1; 0 = random): a given
    # commit fuzzes the same inputs on every machine, so CI's verdict is
    # reproducible and a finding replays with the same seed. Random-seed
    # campaigns are run by hand (docs/RELIABILITY.md).
    seed=${GEOCEAN_FUZZ_SEED:-1}
    # One process (one core); -timeout: an input slower than 10 s is a hang;
    # -rss_limit_mb: a raster that allocates without bound is a bug.
    rc=0
    "$fuzzer" "$work/corpus" -seed="$seed" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2560 \
      -artifact_prefix="$work/artifacts/" -print_final_stats=1 -print_pcs=0 || rc=$?
    # The finding's bytes last, where a truncated log still shows them.
    for a in "$work"/artifacts/*; do
      [ -f "$a" ] || continue
      echo "FUZZ FINDING $(basename "$fuzzer") seed $seed $(basename "$a"): $(base64 -w0 "$a" | head -c 8000)"
    done
    exit "$rc"
    ;;
  *)
    echo "usage: $0 replay|fuzz ..." >&2
    exit 2
    ;;
esac
