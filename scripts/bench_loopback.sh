#!/usr/bin/env bash
# Benchmark (not a test): the 4-channel loopback at 512^2 and 1024^2 per channel.
# Prints per-channel ms/frame, dome frames/s and master->slave snapshot latency.
#   scripts/bench_loopback.sh [frames=20] [sizes="512 1024"]
set -euo pipefail
cd "$(dirname "$0")/.."
FRAMES="${1:-20}"
SIZES="${2:-512 1024}"
unset DISPLAY WAYLAND_DISPLAY
for s in $SIZES; do
  dir="out/bench/dome-4ch-$s"
  rm -rf "$dir" && mkdir -p "$dir"
  python3 - "$s" "$dir/cluster.json" <<'PY'
import json, os, sys
size, out = int(sys.argv[1]), sys.argv[2]
c = json.load(open("configs/dome-4ch.json"))
for k in ("key_file", "scene", "show"):
    c[k] = os.path.abspath(os.path.join("configs", c[k]))
c["output"].update({"width": size, "height": size, "formats": ["png"], "domemaster_size": 2 * size})
c["network"].update({"snapshot_port": 47900, "report_port": 47901, "channel_timeout_ms": 60000})
json.dump(c, open(out, "w"), indent=2)
PY
  echo "== 4 channels at ${s}x${s}, $FRAMES frames"
  build/bin/cupola-loopback --config "$dir/cluster.json" --frames "$FRAMES" --out "$dir/run" --no-stitch >/dev/null
  python3 tools/loopback_stats.py "$dir/run/logs/events.jsonl"
done
