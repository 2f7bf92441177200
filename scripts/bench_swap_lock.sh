#!/usr/bin/env bash
# Benchmark (not a test): the swap lock's present skew (docs/SWAP_LOCK.md). A master and four slaves
# on 127.0.0.1 run FRAMES frames with network.swap_lock on, then off; each slave logs when it was
# ready and when it showed each frame (--present-log, CLOCK_MONOTONIC: one clock on one host).
# Prints per run: frames/s, present skew (latest - earliest present of a frame, over the four),
# release (earliest present - latest ready: what the lock's round trip costs) and wait (a
# channel's present - its own ready), median / p99 / max in ms, plus the master's --stats figures.
# Run it under flock /tmp/cupola-ctest.lock when other runs share the machine's ports.
#   scripts/bench_swap_lock.sh [frames=300] [size=64]
set -euo pipefail
cd "$(dirname "$0")/.."
FRAMES="${1:-300}"
SIZE="${2:-64}"
unset DISPLAY WAYLAND_DISPLAY
for lock in true false; do
  dir="out/bench/swap-lock-$lock"
  rm -rf "$dir" && mkdir -p "$dir"
  python3 - "$SIZE" "$lock" "$dir/cluster.json" <<'PY'
import json, os, sys
size, lock, out = int(sys.argv[1]), sys.argv[2] == "true", sys.argv[3]
c = json.load(open("configs/dome-4ch.json"))
for k in ("key_file", "scene", "show"):
    c[k] = os.path.abspath(os.path.join("configs", c[k]))
c["frame_rate_hz"] = 0
c["output"].update({"width": size, "height": size, "formats": ["png"], "domemaster_size": 2 * size})
c["network"].update({"snapshot_port": 47920, "report_port": 47921, "multicast_group": "239.255.77.121",
                     "channel_timeout_ms": 60000, "swap_lock": lock})
json.dump(c, open(out, "w"), indent=2)
PY
  chans=$(python3 -c 'import json,sys; print(" ".join(c["name"] for c in json.load(open(sys.argv[1]))["channels"]))' "$dir/cluster.json")
  pids=()
  for ch in $chans; do
    build/bin/cupola-slave --config "$dir/cluster.json" --channel "$ch" --out "$dir/$ch" --idle-timeout 60 \
      --present-log "$dir/$ch.present.jsonl" -q 2>"$dir/$ch.log" &
    pids+=($!)
  done
  build/bin/cupola-master --config "$dir/cluster.json" --frames "$FRAMES" --events "$dir/events.jsonl" \
    --stats "$dir/master.stats.json" -q 2>"$dir/master.log"
  for p in "${pids[@]}"; do wait "$p"; done
  echo "== swap_lock $lock: 4 channels at ${SIZE}x${SIZE}, $FRAMES frames"
  python3 - "$dir" $chans <<'PY'
import json, math, sys
d, chans = sys.argv[1], sys.argv[2:]
logs = {c: {e["frame"]: e for e in map(json.loads, open(f"{d}/{c}.present.jsonl"))} for c in chans}
frames = sorted(set.intersection(*(set(l) for l in logs.values())))
def summary(v):
    v = sorted(v)
    r = lambda p: v[min(len(v), max(1, math.ceil(p * len(v)))) - 1]  # nearest rank
    return f"median {r(0.5):.3f}  p99 {r(0.99):.3f}  max {v[-1]:.3f}"
skew, release, wait = [], [], []
for f in frames:
    pres = [logs[c][f]["present_ns"] for c in chans]
    ready = [logs[c][f]["ready_ns"] for c in chans]
    skew.append((max(pres) - min(pres)) / 1e6)
    release.append((min(pres) - max(ready)) / 1e6)
    wait += [(logs[c][f]["present_ns"] - logs[c][f]["ready_ns"]) / 1e6 for c in chans]
end = [json.loads(l) for l in open(f"{d}/events.jsonl") if '"event":"end"' in l][0]
print(f"frames/s {end['frames'] / end['seconds']:.1f} ({len(frames)} frames shown by all four)")
print(f"present skew ms : {summary(skew)}")
print(f"release ms      : {summary(release)}   (earliest present - latest ready; < 0: shown before all were ready)")
print(f"wait ms         : {summary(wait)}")
print("master --stats  :", json.dumps(json.load(open(f"{d}/master.stats.json"))["presentation"]["skew_ms"]))
PY
done
