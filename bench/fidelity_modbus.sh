#!/usr/bin/env bash
# Haptic fidelity with the plant on the far side of a fieldbus: `palprig sim-rig` serves the
# simulated plant (the WAGO 750-559 rig file's plant section) as a real Modbus TCP server on
# loopback, the rig is calibrated over that link in real time by the documented recipe
# (calibrate sweep --excitation staircase,random,sine,step,chirp, then calibrate fit), and the
# demo pass runs over it in real time without and with lag compensation; bench_fidelity
# measures each run's telemetry as it measures the in-process runs (RMS(monitor - target) for
# fingers 1 and 2, monitor/target over tumors, overshoot over soft tissue, largest setpoint).
#
#   bench/fidelity_modbus.sh [BUILD [PLANT_RIG]]   (BUILD: the build folder, default build)
#   PALPRIG_KEEP=DIR bench/fidelity_modbus.sh   keeps the rig, sweep, calibration and telemetry in DIR
#
# PLANT_RIG: a rig file whose plant section the server simulates instead of the WAGO file's own,
# e.g. data/rigs/simulated_asymmetric.json (the asymmetric regulator of docs/rig.md); its safety
# section's p_max_kPa, slew limit and max_lost_time_s come with it, so the bench judges setpoints
# by that rig and, like that simulated rig, rides out a stall of a shared virtual machine (0.5 s
# of lost periods: a simulated regulator holds no air) instead of venting at the hardware
# files' 0.05 s; the overruns are printed beside each run.
#
# About 3 minutes, most of it the real-time sweep. Prints the machine, the load, the identified
# dynamics (which include the bus's transport) and one table row per run.
set -euo pipefail
build=${1:-build}
plant_rig=${2:-}
bin=$(cd "$build/bin" && pwd)
src=$(cd "$(dirname "$0")/.." && pwd)
work=${PALPRIG_KEEP:-$(mktemp -d)}
mkdir -p "$work"
sim=
cleanup() {
  [[ -n $sim ]] && kill "$sim" 2>/dev/null && wait "$sim" 2>/dev/null
  [[ -n ${PALPRIG_KEEP:-} ]] || rm -rf "$work"
}
trap cleanup EXIT

echo "Machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load average $(cut -d' ' -f1-3 /proc/loadavg)"

# The WAGO rig file, with the plant (and safety limits) of PLANT_RIG when one is given.
python3 - "$src/data/rigs/wago_750_559.json" "$work/served.json" "$plant_rig" <<'EOF'
import json, sys
rig = json.load(open(sys.argv[1]))
if sys.argv[3]:
    other = json.load(open(sys.argv[3]))
    rig["plant"] = other["plant"]
    for key in ("p_max_kPa", "slew_kPa_per_s", "max_lost_time_s"):
        if key in other.get("safety", {}):
            rig["safety"][key] = other["safety"][key]
json.dump(rig, open(sys.argv[2], "w"), indent=2)
EOF
[[ -n $plant_rig ]] && echo "Plant: the plant section of $plant_rig, served over Modbus TCP"

# The server on a free port, then a copy of the rig file pointing at it.
"$bin/palprig" sim-rig --rig "$work/served.json" --listen 127.0.0.1:0 --duration-s 900 \
  > "$work/sim.txt" 2>&1 &
sim=$!
for _ in $(seq 100); do
  port=$(sed -n 's/.*listening on 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$work/sim.txt")
  [[ -n $port ]] && break
  sleep 0.1
done
[[ -n ${port:-} ]] || { echo "sim-rig did not start:"; cat "$work/sim.txt"; exit 1; }
python3 - "$work/served.json" "$work/rig.json" "$port" <<'EOF'
import json, sys
rig = json.load(open(sys.argv[1]))
rig["modbus"]["links"][0]["tcp"]["port"] = int(sys.argv[3])
json.dump(rig, open(sys.argv[2], "w"), indent=2)
EOF

"$bin/palprig" calibrate sweep --rig "$work/rig.json" --channels 1,2,3 \
  --excitation staircase,random,sine,step,chirp --quiet --out "$work/sweep.csv" > "$work/sweep.txt" 2>&1 ||
  { echo "the sweep over the link failed:"; cat "$work/sweep.txt"; exit 1; }
grep -E 'holds|redone' "$work/sweep.txt" || true
"$bin/palprig" calibrate fit "$work/sweep.csv" --out "$work/cal.json" > "$work/fit.txt" 2>&1 ||
  { echo "the fit failed:"; cat "$work/fit.txt"; exit 1; }
sed -n '/^Regulator dynamics/,/^Actuator/p' "$work/fit.txt" | sed '$d'

status=0
for mode in off on; do
  flag=--no-compensate-lag
  [[ $mode == on ]] && flag=--compensate-lag
  echo "load average before the run with compensation $mode: $(cut -d' ' -f1-3 /proc/loadavg)"
  if ! "$bin/palprig" run --rig "$work/rig.json" --cal "$work/cal.json" --scene "$src/data/scenes/phantom_abc.json" \
      --input "trace:$src/data/traces/phantom_abc_pass.csv" $flag --telemetry "$work/$mode.csv" > "$work/run_$mode.txt" 2>&1; then
    echo "the run with compensation $mode ended with a fault:"; tail -3 "$work/run_$mode.txt"; status=1
  fi
  grep -E 'modbus:|overruns' "$work/run_$mode.txt" || true
  "$bin/bench_fidelity" --telemetry "$work/$mode.csv" --rig "$work/rig.json" --label "Modbus TCP loopback, real time, compensation $mode"
done
exit $status
