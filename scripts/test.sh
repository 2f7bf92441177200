#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
unset DISPLAY WAYLAND_DISPLAY
ctest --test-dir build --output-on-failure -j "${CTEST_JOBS:-2}" --timeout 600
