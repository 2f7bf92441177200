#!/usr/bin/env bash
# Configures and builds Cupola into build/ (Release with debug info). Used by demo.sh and test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS="${JOBS:-$(nproc)}"
cmake -S . -B build -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-RelWithDebInfo}" >/dev/null
cmake --build build -j "$JOBS"
# Git checks files out world-readable; the nodes warn about a key every user can read.
chmod 600 configs/keys/*.key
