#!/usr/bin/env bash
# Benchmark (not a test): speed against error of every atmosphere model at SIZE^2 (default 1024),
# with table build time and memory. Writes out/bench/atmosphere.csv and
# docs/atmosphere-speed-vs-error.png (matplotlib from Debian's python3-matplotlib).
#   scripts/bench_atmosphere.sh [size=1024] [frames=5]
set -euo pipefail
cd "$(dirname "$0")/.."
SIZE="${1:-1024}"
FRAMES="${2:-5}"
if ! /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get install -y -qq --no-install-recommends python3-matplotlib
fi
bash scripts/build.sh >/dev/null
mkdir -p out/bench
build/bin/atmosphere_speed_vs_error --size "$SIZE" --frames "$FRAMES" --csv out/bench/atmosphere.csv
/usr/bin/python3 tools/plot_speed_vs_error.py out/bench/atmosphere.csv docs/atmosphere-speed-vs-error.png \
  "Cupola atmosphere: speed vs error (${SIZE}x${SIZE}, $(nproc) cores)"
