#!/bin/sh
# Loop wake-up latency and overruns at 1 kHz: `palprig run --realtime` alone, then the same
# loop behind `palprig gui` with its window open and its traces drawing (the loop fed by the
# raster sweep so the traces move), one after the other in the same script run. The window runs
# on Xvfb when xvfb-run is installed (a real X server), else on the offscreen platform.
#   bench/gui_vs_run_wakeup.sh [BUILD_DIR] [SECONDS]
set -eu
build=${1:-build}
secs=${2:-20}
bin="$build/bin/palprig"
scene="$(dirname "$0")/../data/scenes/phantom_abc.json"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

summary() {  # label, JSON file
  python3 - "$1" "$2" <<'PY'
import json, sys
label, path = sys.argv[1], sys.argv[2]
text = open(path).read()
j = json.loads(text[text.index("{"):])
w = j["wake_latency"]
print(f"{label:<34} ticks {j['ticks']:>6}  overruns {j['overruns']:>3}  wake-up p50 {w['p50_us']:7.1f} us"
      f"  p99 {w['p99_us']:7.1f} us  max {w['max_us']:8.1f} us")
PY
}

"$bin" run --realtime --scene "$scene" --input sweep --duration-s "$secs" --json > "$out/run.json"
summary "palprig run (no window)" "$out/run.json"

if command -v xvfb-run >/dev/null 2>&1; then
  xvfb-run -a -s '-screen 0 1400x1000x24' env QT_QPA_PLATFORM=xcb \
    "$bin" gui --scene "$scene" --input sweep --json --screenshot "$out/gui.png" --after-s "$secs" > "$out/gui.json"
  summary "palprig gui (Xvfb, traces drawing)" "$out/gui.json"
else
  QT_QPA_PLATFORM=offscreen "$bin" gui --scene "$scene" --input sweep --json --screenshot "$out/gui.png" --after-s "$secs" > "$out/gui.json"
  summary "palprig gui (offscreen, traces)" "$out/gui.json"
fi
