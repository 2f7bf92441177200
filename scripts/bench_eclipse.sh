#!/usr/bin/env bash
# Benchmark (not a test): what the eclipse shadows cost in a whole frame. The 4-channel
# eclipse dome (configs/eclipse-2006-dome.json) at totality, SIZE^2 per channel, once per shadow
# mode (the scene's default mode switched), reporting per-channel ms/frame.
#   scripts/bench_eclipse.sh [frames=10] [size=256]
set -euo pipefail
cd "$(dirname "$0")/.."
FRAMES="${1:-10}"
SIZE="${2:-256}"
unset DISPLAY WAYLAND_DISPLAY
for mode in off fast lut exact illustrative; do
  dir="out/bench/eclipse-$mode"
  rm -rf "$dir" && mkdir -p "$dir"
  python3 - "$SIZE" "$mode" "$dir" <<'PY'
import json, os, sys
size, mode, out = int(sys.argv[1]), sys.argv[2], os.path.abspath(sys.argv[3])
scene = json.load(open("configs/scenes/earth-physical.json"))
scene["shadows"]["mode"] = mode
scene["stars"]["catalog"] = os.path.abspath("data/stars/bright_stars.csv")
json.dump(scene, open(out + "/scene.json", "w"), indent=2)
show = json.load(open("configs/shows/eclipse-2006-ground.json"))
show["keyframes"] = [dict(show["keyframes"][-1], at_s=0)]  # totality, held
json.dump(show, open(out + "/show.json", "w"), indent=2)
c = json.load(open("configs/eclipse-2006-dome.json"))
c["key_file"] = os.path.abspath("configs/keys/loopback.key")
c["scene"], c["show"] = out + "/scene.json", out + "/show.json"
c["output"].update({"width": size, "height": size, "formats": ["png"]})
c["network"]["channel_timeout_ms"] = 60000
json.dump(c, open(out + "/cluster.json", "w"), indent=2)
PY
  echo "== shadows $mode, 4 channels at ${SIZE}x${SIZE}, $FRAMES frames (totality)"
  build/bin/cupola-loopback --config "$dir/cluster.json" --frames "$FRAMES" --out "$dir/run" --no-stitch >/dev/null
  python3 tools/loopback_stats.py "$dir/run/logs/events.jsonl" | grep -i "ms\|frame" | head -7
done
