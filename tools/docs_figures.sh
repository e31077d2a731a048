#!/usr/bin/env bash
# The figures the docs quote about the simulated participant, pulse localisation and
# calibration, regenerated with the machine they ran on named. Deterministic (seeded) figures do
# not depend on the machine; the wall times printed do.
#   tools/docs_figures.sh [BUILD]   (default build; about two minutes on 2 cores)
# Sections: machine; paper 002 discrimination over sim:1..60; localisation over sim:1..90;
# pulse localisation (sim:1, sim:2); threshold (sim:1); calibration with and without the
# identification excitations; the pulse stage's correlations; the haptic fidelity with and
# without lag compensation; the demo's per-region table. docs/developing.md, "Figures in the
# docs", says where each figure is quoted.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
palprig="$(cd "$build" && pwd)/bin/palprig"
[ -x "$palprig" ] || { echo "docs_figures: no $palprig (build first)" >&2; exit 1; }
work="$(mktemp -d /tmp/palprig-figures.XXXXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
ln -s "$here/data" data
started=$(date +%s)

echo "== machine"
echo "date:    $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "cpu:     $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores$(grep -q hypervisor /proc/cpuinfo && echo ', virtual machine')"
echo "memory:  $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo)"
echo "system:  $(. /etc/os-release && echo "$PRETTY_NAME"), Linux $(uname -r)"
echo "load:    $(cut -d' ' -f1-3 /proc/loadavg) (1, 5, 15 min) at the start"
echo "palprig: $("$palprig" --version) ($(grep -s CMAKE_BUILD_TYPE:STRING "$build/CMakeCache.txt" | cut -d= -f2))"

echo
echo "== discrimination (data/protocols/discrimination_002.json), sim:1..60, default rig and observer"
t0=$(date +%s.%N)
for i in $(seq 1 60); do
  "$palprig" experiment run --protocol data/protocols/discrimination_002.json --participant "sim:$i" --db disc.db --quiet >/dev/null
done
echo "60 sessions in $(echo "$(date +%s.%N) - $t0" | bc) s wall"
"$palprig" stats trials disc.db --by condition --json > disc.json
python3 - disc.json <<'EOF'
import json, sys
for r in json.load(open(sys.argv[1]))["rows"]:
    a = r["ACC"]
    print(f"{r['condition']}: ACC {100*a['value']:.1f} % [{100*a['lower']:.1f}, {100*a['upper']:.1f}] "
          f"({a['k']}/{a['n']} finger values), RT mean {r['rt_mean_s']:.2f} s (sd {r['rt_sd_s']:.2f})")
EOF
echo "paper 002: three fingers 96.8 %, one finger 93.3 %; RT 4.6 +/- 2.3 s and 8.3 +/- 2.9 s"

echo
echo "== localisation (data/protocols/localisation_002.json), sim:1..90"
for i in $(seq 1 90); do
  "$palprig" experiment run --protocol data/protocols/localisation_002.json --participant "sim:$i" --db loc.db --quiet >/dev/null
done
"$palprig" stats trials loc.db --by tumor
echo "paper 002 (9 participants): A 66.7 %, B 100 %, C 88.9 %"

echo
echo "== pulse localisation"
"$palprig" experiment run --protocol data/protocols/pulse_localisation_000.json --participant sim:1 --db pulse.db --quiet >/dev/null
"$palprig" stats trials pulse.db
"$palprig" experiment run --protocol data/protocols/pulse_generated.json --participant sim:2 --db generated.db --quiet >/dev/null
"$palprig" stats trials generated.db

echo
echo "== threshold (data/protocols/threshold_1up3down.json), sim:1"
"$palprig" experiment run --protocol data/protocols/threshold_1up3down.json --participant sim:1 --db t.db --quiet | tail -2

echo
echo "== calibration of the default simulated rig, with --excitation staircase,random,sine,step,chirp"
"$palprig" calibrate sweep --rig data/rigs/simulated.json --channels 1,2,3 --excitation staircase,random,sine,step,chirp \
  --out sweep.csv 2>/dev/null | sed -n 2p
"$palprig" calibrate fit sweep.csv --out cal.json | grep -E '^ +all +|channel [123]: (from|dead time)|gap|^ +[123] +[0-9.]+ kPa /'
"$palprig" calibrate evaluate --rig data/rigs/simulated.json --cal cal.json | tail -8

echo
echo "== calibration, the plain staircase (no --excitation)"
"$palprig" calibrate sweep --rig data/rigs/simulated.json --channels 1,2,3 --out plain.csv 2>/dev/null | sed -n 2p
"$palprig" calibrate fit plain.csv --out plain_cal.json | grep -E 'channel [123]: from'
"$palprig" calibrate evaluate --rig data/rigs/simulated.json --cal plain_cal.json | tail -1

echo
echo "== pulse on the regulators (bench_pulse_correlation)"
if [ -x "$build/bin/bench_pulse_correlation" ]; then
  "$build/bin/bench_pulse_correlation" | grep -E '^\| (rectangular|saw-tooth|table)' || true
else
  echo "(not built: make bench builds the benchmark programs)"
fi

echo
echo "== haptic fidelity: the demo pass with and without lag compensation (bench_fidelity)"
if [ -x "$build/bin/bench_fidelity" ]; then
  "$build/bin/bench_fidelity" --figure fidelity.png
else
  echo "(not built: make bench builds the benchmark programs)"
fi

echo
echo "== demo"
"$palprig" demo --out demo | tail -7

echo
echo "load:    $(cut -d' ' -f1-3 /proc/loadavg) at the end; $(( $(date +%s) - started )) s in all"
