#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the loopback dome demo (master + one
# slave process per channel on this machine), then stitches a domemaster PNG and says where.
#   scripts/demo.sh [config] [frames] [out-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
CONFIG="${1:-configs/dome-4ch.json}"
FRAMES="${2:-10}"
OUT="${3:-out/demo}"
scripts/setup.sh
scripts/build.sh cupola-loopback   # with cupola-master and cupola-slave, which it starts; no tests
unset DISPLAY WAYLAND_DISPLAY   # headless: EGL only
build/bin/cupola-loopback --config "$CONFIG" --frames "$FRAMES" --out "$OUT"
echo "demo: channel frames in $OUT/<channel>/, domemasters in $OUT/dome/"
