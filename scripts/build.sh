#!/usr/bin/env bash
# Configures and builds Cupola into build/ (Release with debug info). Used by demo.sh and test.sh.
#   scripts/build.sh              everything (programs, tests, benchmarks, fuzzers)
#   scripts/build.sh TARGET...    only these targets and what they need (demo.sh: cupola-loopback)
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS="${JOBS:-$(nproc)}"
cmake -S . -B build -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-RelWithDebInfo}" >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build build -j "$JOBS" "${targets[@]}"
# Git checks files out world-readable; the nodes warn about a key every user can read.
chmod 600 configs/keys/*.key
