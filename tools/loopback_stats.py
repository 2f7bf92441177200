#!/usr/bin/env python3
"""Summarise a master events file (cupola-master --events) for BENCHMARKS.md.

Prints per-channel render ms/frame (median, p90), write ms, dome frames/s and the master->slave
snapshot latency (median, p99) measured on one host with CLOCK_MONOTONIC.
    tools/loopback_stats.py out/bench/logs/events.jsonl [--skip 2]
"""
import json
import statistics
import sys


def pct(values, p):
    v = sorted(values)
    if not v:
        return float("nan")
    k = (len(v) - 1) * p / 100.0
    lo, hi = int(k), min(int(k) + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (k - lo)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    skip = int(sys.argv[sys.argv.index("--skip") + 1]) if "--skip" in sys.argv else 2
    frames = []
    with open(sys.argv[1]) as f:
        for line_no, line in enumerate(f, 1):
            try:
                e = json.loads(line)
            except json.JSONDecodeError as err:
                sys.exit(f"{sys.argv[1]}:{line_no}: not JSON: {err}")
            if e.get("event") == "frame":
                frames.append(e)
    frames = frames[skip:]  # warm-up: first frames include shader compilation and table uploads
    if not frames:
        sys.exit(f"{sys.argv[1]}: no frame events after skipping {skip}")
    render, write, latency = {}, {}, []
    for e in frames:
        for ch, r in e["channels"].items():
            render.setdefault(ch, []).append(r["render_ms"])
            write.setdefault(ch, []).append(r["write_ms"])
            if r["latency_ms"] > 0:
                latency.append(r["latency_ms"])
    frame_ms = [e["frame_ms"] for e in frames]
    print(f"frames measured: {len(frames)} (first {skip} skipped)")
    for ch in sorted(render, key=int):
        print(f"channel {ch}: render ms/frame median {statistics.median(render[ch]):.1f} p90 {pct(render[ch], 90):.1f}; "
              f"write ms median {statistics.median(write[ch]):.1f}")
    all_render = [v for vs in render.values() for v in vs]
    print(f"all channels: render ms/frame median {statistics.median(all_render):.1f}")
    print(f"dome frame (barrier to barrier) ms median {statistics.median(frame_ms):.1f} -> "
          f"{1000.0 / statistics.median(frame_ms):.2f} dome frames/s")
    if latency:
        print(f"snapshot latency master->slave ms: median {statistics.median(latency):.3f} "
              f"p99 {pct(latency, 99):.3f} (n={len(latency)})")


if __name__ == "__main__":
    main()
