#!/usr/bin/env bash
# Benchmark (not a test) for a render node with an NVIDIA GPU, headless (EGL device, no display),
# in one go: builds Release (only the programs it runs), then
#   1. benchmarks/frame_cost at 1024^2 and 2048^2 (one earth-moon channel by day, at sunset and
#      from orbit: per-pass ms, the whole frame, a trivial pass; one JSON line per view), once
#      without and once with the read-back a files sink needs;
#   2. a 4-channel loopback (configs/dome-4ch.json at 2048^2 per channel, PNG files, no stitch),
#      summarised by tools/loopback_stats.py (render ms per channel, dome frames/s).
# Prints the figures and keeps them, with the machine's description, under the results folder.
# Stops with exit 3 and says why when no NVIDIA GPU or no EGL device on it is found.
#   scripts/gpu_bench.sh [--results DIR] [--build-dir DIR] [--no-build] [--egl-device N]
#                        [--frames N] [--loopback-frames N]
#   scripts/gpu_bench.sh --cpu     the same steps on whatever EGL gives (llvmpipe here), at 128^2
#                                  and 256^2 and a 4 x 128^2 loopback: to check the script itself
set -euo pipefail
cd "$(dirname "$0")/.."

CPU=0
BUILD=1
BUILD_DIR="build-release"
RESULTS=""
EGL_DEVICE=-1
FRAMES=20
LOOPBACK_FRAMES=30
usage() { sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; }
while [ $# -gt 0 ]; do
  case "$1" in
    --cpu) CPU=1 ;;
    --no-build) BUILD=0 ;;
    --build-dir) BUILD_DIR="$2"; shift ;;
    --results) RESULTS="$2"; shift ;;
    --egl-device) EGL_DEVICE="$2"; shift ;;
    --frames) FRAMES="$2"; shift ;;
    --loopback-frames) LOOPBACK_FRAMES="$2"; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "gpu_bench: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
  shift
done
if [ "$CPU" = 1 ]; then
  SIZES="128 256"; LOOPBACK_SIZE=128
  FRAMES=$(( FRAMES < 3 ? FRAMES : 3 )); LOOPBACK_FRAMES=$(( LOOPBACK_FRAMES < 6 ? LOOPBACK_FRAMES : 6 ))
else
  SIZES="1024 2048"; LOOPBACK_SIZE=2048
fi
RESULTS="${RESULTS:-out/gpu-bench/$(date -u +%Y%m%dT%H%M%SZ)}"
mkdir -p "$RESULTS"
RESULTS="$(cd "$RESULTS" && pwd)"
fail() { echo "gpu_bench: $*" >&2; exit 3; }
unset DISPLAY WAYLAND_DISPLAY

# --- the GPU, before anything is built
if [ "$CPU" = 0 ]; then
  command -v nvidia-smi >/dev/null || fail "no NVIDIA GPU: nvidia-smi is not installed (for a check on llvmpipe: --cpu)"
  nvidia-smi -L >"$RESULTS/gpus.txt" 2>&1 || fail "nvidia-smi finds no GPU: $(head -n 3 "$RESULTS/gpus.txt")"
  grep -q '^GPU ' "$RESULTS/gpus.txt" || fail "nvidia-smi lists no GPU: $(head -n 3 "$RESULTS/gpus.txt")"
  # Only NVIDIA's EGL vendor library, so that EGL cannot fall back to Mesa's software renderer.
  if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ]; then
    for f in /usr/share/glvnd/egl_vendor.d/10_nvidia.json /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json; do
      if [ -f "$f" ]; then export __EGL_VENDOR_LIBRARY_FILENAMES="$f"; break; fi
    done
  fi
fi
{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "host: $(uname -srm), $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2 / 1048576}' /proc/meminfo)"
  echo "cpu: $(awk -F': ' '/model name/ {print $2; exit}' /proc/cpuinfo)"
  echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD 2>/dev/null || echo ' (with local changes)')"
  if [ "$CPU" = 0 ]; then
    nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | sed 's/^/gpu: /'
  fi
  echo "egl vendor libraries: ${__EGL_VENDOR_LIBRARY_FILENAMES:-(the default search)}"
} | tee "$RESULTS/machine.txt"

# --- build (Release, only the programs run below)
BIN="$BUILD_DIR/bin"
if [ "$BUILD" = 1 ]; then
  for tool in cmake c++ pkg-config; do
    command -v "$tool" >/dev/null || fail "$tool is not installed (scripts/setup.sh installs the build dependencies)"
  done
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  echo "== build ($BUILD_DIR, Release)"
  start=$(date +%s)
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DCUPOLA_BUILD_TESTS=OFF -DCUPOLA_BUILD_FUZZ=OFF \
        "${launcher[@]}" >"$RESULTS/build.log" 2>&1 || { tail -n 30 "$RESULTS/build.log" >&2; fail "cmake configure failed"; }
  cmake --build "$BUILD_DIR" -j "$(nproc)" --target frame_cost cupola-loopback cupola-master cupola-slave \
        >>"$RESULTS/build.log" 2>&1 || { tail -n 30 "$RESULTS/build.log" >&2; fail "the build failed"; }
  echo "built in $(( $(date +%s) - start )) s"
fi
for p in frame_cost cupola-loopback cupola-master cupola-slave; do
  [ -x "$BIN/$p" ] || fail "$BIN/$p is missing (build it, or drop --no-build)"
done
chmod 600 configs/keys/*.key

# --- the EGL device: the renderer frame_cost's context reports must be the GPU's
"$BIN/frame_cost" --size 16 --frames 1 --warm-up 0 --views day --device "$EGL_DEVICE" \
  >"$RESULTS/egl_probe.jsonl" 2>"$RESULTS/egl_probe.err" ||
  fail "no EGL context for rendering: $(tail -n 3 "$RESULTS/egl_probe.err")"
RENDERER=$(python3 -c 'import json, sys; print(json.loads(open(sys.argv[1]).readline())["renderer"])' "$RESULTS/egl_probe.jsonl")
echo "renderer: $RENDERER" | tee -a "$RESULTS/machine.txt"
if [ "$CPU" = 0 ]; then
  case "$RENDERER" in
    *llvmpipe*|*softpipe*|*swrast*|*"Software"*) fail "EGL gives a software renderer ($RENDERER), not the GPU: no EGL device for it" ;;
  esac
fi

# --- 1. frame cost, one channel
summary() {  # one line per view from frame_cost's JSON
  python3 - "$1" <<'PY'
import json, sys
for line in open(sys.argv[1]):
    j = json.loads(line)
    passes = ", ".join(f"{k} {v:.2f}" for k, v in j["passes"].items())
    print(f"  {j['view']:7s} {j['size']}^2 read-back {'yes' if j['read_back'] else 'no '}: frame {j['frame_ms']:.2f} ms "
          f"(untimed {j['untimed_frame_ms']:.2f}), trivial {j['trivial_ms']:.3f} ms, ratio {j['ratio']:.1f} (of minima {j['ratio_of_minima']:.1f}, of CPU times {j['ratio_cpu']:.1f}) | {passes}"
          + (f", read-back {j['read_back_ms']:.2f}" if j["read_back"] else ""))
PY
}
for s in $SIZES; do
  for rb in "" "--read-back"; do
    name="frame_cost_${s}${rb:+_read_back}"
    echo "== frame_cost ${s}x${s} ${rb:-(no read-back)}, $FRAMES frames"
    # shellcheck disable=SC2086
    "$BIN/frame_cost" --size "$s" --frames "$FRAMES" --device "$EGL_DEVICE" $rb \
      >"$RESULTS/$name.jsonl" 2>"$RESULTS/$name.err" || { cat "$RESULTS/$name.err" >&2; fail "frame_cost at $s failed"; }
    summary "$RESULTS/$name.jsonl" | tee "$RESULTS/$name.txt"
  done
done

# --- 2. four channels at LOOPBACK_SIZE^2 through the real master, slaves and network
dir="$RESULTS/loopback-4x$LOOPBACK_SIZE"
rm -rf "$dir" && mkdir -p "$dir"
python3 - "$LOOPBACK_SIZE" "$EGL_DEVICE" "$dir/cluster.json" <<'PY'
import json, os, sys
size, device, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
c = json.load(open("configs/dome-4ch.json"))
for k in ("key_file", "scene", "show"):
    c[k] = os.path.abspath(os.path.join("configs", c[k]))
c["egl_device"] = device
c["output"].update({"width": size, "height": size, "formats": ["png"], "domemaster_size": 2 * size})
c["network"].update({"snapshot_port": 47910, "report_port": 47911, "channel_timeout_ms": 60000})
json.dump(c, open(out, "w"), indent=2)
PY
echo "== loopback: 4 channels at ${LOOPBACK_SIZE}x${LOOPBACK_SIZE}, $LOOPBACK_FRAMES frames (PNG files, no stitch)"
run_loopback=("$BIN/cupola-loopback" --config "$dir/cluster.json" --frames "$LOOPBACK_FRAMES" --out "$dir/run"
              --no-stitch --timeout 300)
if command -v flock >/dev/null; then run_loopback=(flock /tmp/cupola-ctest.lock "${run_loopback[@]}"); fi
"${run_loopback[@]}" >"$dir/loopback.log" 2>&1 || { tail -n 30 "$dir/loopback.log" >&2; fail "the loopback failed"; }
python3 tools/loopback_stats.py "$dir/run/logs/events.jsonl" | tee "$RESULTS/loopback-4x$LOOPBACK_SIZE.txt"
find "$dir/run" -mindepth 1 -maxdepth 1 ! -name logs -exec rm -rf {} +  # the frames (GiBs at 2048^2), not the logs

echo "== results in $RESULTS"
