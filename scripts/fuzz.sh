#!/usr/bin/env bash
# Builds (if needed) and runs the wire-protocol fuzzer cupola-fuzz-wire (fuzz/) for longer than the
# ctest fuzz_wire_bounded does, then prints the number of executions, the rate and the coverage
# (for BENCHMARKS.md). It runs on a scratch copy of fuzz/corpus/wire plus freshly generated seeds
# under $BUILD_DIR/fuzz/scratch-bench; nothing is written into the source tree. Inputs that crash,
# leak or hit UB are left in $BUILD_DIR/fuzz/scratch-bench/artifacts and make this script fail.
#
#   scripts/fuzz.sh                 300 seconds
#   scripts/fuzz.sh 3600            an hour
#   scripts/fuzz.sh -runs=10000000  a fixed number of inputs
#   scripts/fuzz.sh 600 -jobs=4     further arguments go to libFuzzer as they are
# Environment: BUILD_DIR (default build), JOBS (build parallelism, default nproc).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${BUILD_DIR:-build}"
JOBS="${JOBS:-$(nproc)}"

limit="${1:-300}"
shift || true
case "$limit" in
  -runs=*) limit_def="-DRUNS=${limit#-runs=}" ;;
  ''|*[!0-9]*) echo "usage: $0 [SECONDS | -runs=N] [libFuzzer arguments...]" >&2; exit 2 ;;
  *) limit_def="-DSECONDS=$limit" ;;
esac

if [ ! -f "$BUILD_DIR/CMakeCache.txt" ]; then
  echo "fuzz: configuring $BUILD_DIR"
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-RelWithDebInfo}" >/dev/null
else
  cmake -S . -B "$BUILD_DIR" >/dev/null  # picks up fuzz/ in a build dir configured before it existed
fi
if ! grep -q '^CUPOLA_FUZZ_ENABLED:INTERNAL=ON' "$BUILD_DIR/CMakeCache.txt"; then
  echo "fuzz: $BUILD_DIR does not build the fuzzer (CUPOLA_BUILD_FUZZ=OFF, or clang++ / libclang-rt-14-dev" \
       "missing: see the CMake warning and scripts/setup.sh)" >&2
  exit 1
fi
cmake --build "$BUILD_DIR" --target cupola-fuzz-wire -j "$JOBS"

bin="$(cd "$BUILD_DIR" && pwd)/bin"
scratch="$(cd "$BUILD_DIR" && pwd)/fuzz/scratch-bench"
log="$(cd "$BUILD_DIR" && pwd)/fuzz/fuzz-bench.log"
extra=""
if [ $# -gt 0 ]; then extra="$(IFS=';'; echo "$*")"; fi

rc=0
cmake -DFUZZER="$bin/cupola-fuzz-wire" -DCORPUS_GEN="$bin/cupola-fuzz-wire-corpus" \
      -DSEEDS="$PWD/fuzz/corpus/wire" -DSCRATCH="$scratch" "$limit_def" -DEXTRA="$extra" \
      -P fuzz/run_fuzz.cmake 2>&1 | tee "$log" || rc=$?

stat() { sed -n "s/^stat::$1: *//p" "$log" | tail -1; }
echo
echo "fuzz: ---- summary (log: $log) ----"
sed -n 's/^Done \([0-9]*\) runs in \([0-9]*\) second.*/fuzz: executions: \1 in \2 s/p' "$log" | tail -1
echo "fuzz: executions (stat): $(stat number_of_executed_units), exec/s: $(stat average_exec_per_sec)," \
     "peak RSS: $(stat peak_rss_mb) MB, new units: $(stat new_units_added)"
grep -E '^#[0-9]+[[:space:]]+(DONE|pulse|NEW|REDUCE)' "$log" | tail -1 | sed 's/^/fuzz: last status: /' || true
if [ "$rc" -ne 0 ]; then
  echo "fuzz: FAILED (see $scratch/artifacts)" >&2
fi
exit "$rc"
