#!/usr/bin/env bash
# Runs every fuzz target of a PALPRIG_FUZZ build for SECONDS each (FUZZ_JOBS at a time, one per
# core), starting from the seeds (the shipped data files and test fixtures that reader takes, plus
# fuzz/seeds/<target>), and prints one line per target: executions, time, new corpus units, crashes. Exit 1 if any target
# crashed, leaked, timed out or ran out of memory; its input is kept in BUILD/fuzz-artifacts.
#   fuzz/run_fuzz.sh BUILD_DIR SECONDS [TARGET...]
set -euo pipefail
build=${1:?build dir (cmake -DPALPRIG_FUZZ=ON)}
seconds=${2:?seconds per target}
shift 2
src=$(cd "$(dirname "$0")/.." && pwd)
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in "$src"/fuzz/fuzz_*.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi

# The shipped files each reader takes (globs relative to the source tree).
seeds_for() {
  case $1 in
    fuzz_rig_file) echo "data/rigs/*.json" ;;
    fuzz_scene_file) echo "data/scenes/*.json" ;;
    fuzz_calibration_file) echo "data/calibration/*.json" ;;
    fuzz_protocol) echo "data/protocols/discrimination_*.json data/protocols/localisation_*.json" ;;
    fuzz_threshold_protocol) echo "data/protocols/threshold_*.json" ;;
    fuzz_pulse_protocol) echo "data/protocols/pulse_*.json" ;;
    fuzz_curriculum) echo "data/curricula/*.json" ;;
    fuzz_trace_csv) echo "data/traces/*.csv" ;;
    fuzz_map_csv) echo "" ;;
    fuzz_pgm) echo "data/scenes/*.pgm" ;;
    fuzz_evemu) echo "tests/fixtures/evemu/*.evemu" ;;
    fuzz_telemetry_bin) echo "" ;;
    fuzz_stats_csv) echo "data/calibration/*.csv data/traces/*.csv" ;;
    fuzz_waveform_csv) echo "data/waveforms/*.csv" ;;
    fuzz_psychometric_csv) echo "" ;;
    fuzz_calibration_csv) echo "data/calibration/*.csv" ;;
    fuzz_tracking_file) echo "data/tracking/*.json" ;;
    fuzz_pose_recording) echo "data/tracking/*.csv" ;;
    fuzz_igtl_stream) echo "" ;;
    fuzz_fe_fingertip) echo "data/fe/fingertip_*.json" ;;
    fuzz_fe_tissue) echo "data/fe/soft_tissue_*.json" ;;
    fuzz_fe_actuator) echo "data/fe/actuator_*.json" ;;
    fuzz_fe_results) echo "data/fe/stress_model_*.json data/fe/stress_table_*.json" ;;
  esac
}

work=$(mktemp -d "${TMPDIR:-/tmp}/palprig-fuzz.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$build/fuzz-artifacts"

# One target: its row of the table in $work/$t.row, its failure (with its log's telling lines) in
# $work/$t.failed.
fuzz_one() {
  local t=$1 exe="$build/bin/$1"
  [ -x "$exe" ] || exe="$build/fuzz/$t"
  [ -x "$exe" ] || { echo "$t: not built in $build" >"$work/$t.failed"; return; }
  mkdir -p "$work/$t/seeds" "$work/$t/new"
  (cd "$src" && for f in $(seeds_for "$t"); do [ -f "$f" ] && cp "$f" "$work/$t/seeds/"; done; true)
  [ -d "$src/fuzz/seeds/$t" ] && cp "$src/fuzz/seeds/$t"/* "$work/$t/seeds/" 2>/dev/null || true
  local log="$work/$t.log" start end execs corpus crashes=0 status=0
  start=$(date +%s.%N)
  "$exe" "$work/$t/new" "$work/$t/seeds" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$t-" >"$log" 2>&1 || status=$?
  end=$(date +%s.%N)
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  corpus=$(find "$work/$t/new" "$work/$t/seeds" -type f | wc -l)
  if [ "$status" -ne 0 ]; then
    crashes=1
    { echo "---- $t failed (exit $status); its log:"
      grep -E "ERROR|SUMMARY|Test unit written|terminate|what\(\)" "$log" | head -20; } >"$work/$t.failed"
  fi
  printf '%-22s %12s %8.1f %8s %8s\n' "$t" "${execs:-?}" "$(awk "BEGIN {print $end - $start}")" "$corpus" "$crashes" \
    >"$work/$t.row"
}

# FUZZ_JOBS targets at a time (default: one per core): libFuzzer runs one process per target, so on
# two cores two targets run in the time of one (make test's second per target: 23 targets in about
# 26 s rather than 51 s). Each still gets its SECONDS; the table keeps the targets' order.
jobs_max=${FUZZ_JOBS:-$(nproc)}
for t in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do wait -n || true; done
  fuzz_one "$t" &
done
wait
failed=0
printf '%-22s %12s %8s %8s %8s\n' target executions time_s corpus crashes
for t in "${targets[@]}"; do
  [ -f "$work/$t.row" ] && cat "$work/$t.row"
  if [ -f "$work/$t.failed" ]; then
    cat "$work/$t.failed" >&2
    failed=1
  fi
done
exit $failed
