#!/usr/bin/env bash
# The chart figures of docs/analysing.md ("Figures") and docs/rig.md, remade with palprig's own
# --plot from simulated sessions and a simulated calibration (seeded: the same pictures on any
# machine), into docs/figures/, as palprig writes them (PNG at print size, 2100 x 1320 at 300
# dpi; a page shows them scaled to its width).
#   tools/docs_charts.sh [BUILD]   (default build; about a minute)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
palprig="$(cd "$build" && pwd)/bin/palprig"
[ -x "$palprig" ] || { echo "docs_charts: no $palprig (build first)" >&2; exit 1; }
work="$(mktemp -d /tmp/palprig-charts.XXXXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
ln -s "$here/data" data
run() { "$palprig" experiment run --quiet --protocol "data/protocols/$1" --participant "$2" --db "$3" >/dev/null; }

# Paper 002's discrimination study (the two participants of docs/analysing.md), a localisation
# study, a threshold session and pulse localisation, each exported with its figures.
run discrimination_002.json sim:7 disc.db
run discrimination_002.json sim:8 disc.db
for i in 1 2 3; do run localisation_002.json "sim:$i" loc.db; done
run threshold_1up3down.json sim:1 threshold.db
for i in 1 2; do run pulse_localisation_000.json "sim:$i" pulse.db; done
for db in disc loc threshold pulse; do "$palprig" export "$db.db" --out "csv_$db" --plot "plots_$db" >/dev/null; done
# The calibration of docs/rig.md: sweep, fit and evaluate on the default simulated rig.
"$palprig" calibrate sweep --rig data/rigs/simulated.json --excitation staircase,random,sine --out sweep.csv --quiet \
  >/dev/null 2>&1
"$palprig" calibrate fit sweep.csv --out cal.json --plot plots_cal >/dev/null 2>&1
"$palprig" calibrate evaluate --rig data/rigs/simulated.json --cal cal.json --channels 1 --plot plots_cal --quiet \
  >/dev/null

out="$here/docs/figures"
mkdir -p "$out"
for f in plots_disc/measures_by_condition.png plots_disc/measures_by_finger.png plots_loc/sensitivity_by_tumor.png \
         plots_threshold/psychometric_one_finger.png plots_threshold/track_session1.png \
         plots_pulse/pulse_hits_by_condition.png plots_pulse/pulse_distance_by_condition.png \
         plots_cal/channel_1_regulator.png plots_cal/channel_1_hysteresis.png \
         plots_cal/evaluate_channel_1_error.png plots_cal/evaluate_channel_1_loops.png; do
  cp "$f" "$out/"
  echo "$out/$(basename "$f")"
done
