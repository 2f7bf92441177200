#!/usr/bin/env bash
# Regression check for refactorings (not a test: it needs a second build). Renders 3 frames of each
# shipped cluster config with the programs in OLD_BIN (cupola-loopback, cupola-master, cupola-slave
# of an earlier build) and with build/bin, then compares every channel frame file with idiff
# (any pixel that differs at all fails) and the master's snapshot hashes.
#   scripts/compare_renders.sh OLD_BIN [out-dir=out/compare]
set -uo pipefail
cd "$(dirname "$0")/.."
old="${1:?usage: scripts/compare_renders.sh OLD_BIN [out-dir]}"
out="${2:-out/compare}"
unset DISPLAY WAYLAND_DISPLAY
status=0
for cfg in dome-4ch eclipse-2006-dome descent-1ch wall-3ch; do
  for v in old new; do
    bin="$old"; [ "$v" = new ] && bin=build/bin
    rm -rf "$out/$cfg-$v" && mkdir -p "$out/$cfg-$v"
    CUPOLA_CACHE_DIR="$out/cache-$v" "$bin/cupola-loopback" --config "configs/$cfg.json" --frames 3 \
      --out "$out/$cfg-$v" --no-stitch >"$out/$cfg-$v.log" 2>&1 || { echo "$cfg: the $v loopback failed"; status=1; }
  done
  same=0; differ=0
  for f in $(cd "$out/$cfg-old" && find . -name 'frame_*.exr' -o -name 'frame_*.png' | sort); do
    if idiff -fail 0 -failpercent 0 "$out/$cfg-old/$f" "$out/$cfg-new/$f" >/dev/null 2>&1; then same=$((same + 1));
    else differ=$((differ + 1)); echo "$cfg: $f differs"; status=1; fi
  done
  hashes() { grep -o '"hash":"[0-9a-f]*"' "$out/$cfg-$1/logs/events.jsonl"; }
  if diff <(hashes old) <(hashes new) >/dev/null; then h="snapshot hashes equal"; else h="snapshot hashes DIFFER"; status=1; fi
  echo "$cfg: $same frame files identical, $differ differ; $h"
done
exit $status
