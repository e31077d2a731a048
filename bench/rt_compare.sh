#!/usr/bin/env bash
# Wake-up latency of palprig's real-time loop beside cyclictest (Debian's rt-tests), run
# alternately in the same minutes at the same SCHED_FIFO priority and rate, idle and with every
# core loaded by ordinary-priority stress-ng workers. Three programs per case:
#   cyclictest          cyclictest -m -p PRIO -i PERIOD_US -t 1 (holds /dev/cpu_dma_latency at 0)
#   palprig             palprig run --realtime --priority PRIO (the loop users run: phantom
#                       scene, raster sweep, simulated rig; holds the PM QoS request)
#   palprig --no-pm-qos the same without the PM QoS request (what the request gives)
# Percentiles come from 1-us histograms for both programs (upper bin edge, as palprig's own
# summary); "overruns" are, for cyclictest, wake-ups at least one period late, and for palprig,
# ticks that ended after the next deadline (its own count; wake-up plus ~5 us of tick and I/O).
#   bench/rt_compare.sh [BUILD_DIR] [SECONDS_PER_RUN=10] [ROUNDS=3] [RATE_HZ=1000] [PRIORITY=80]
# Needs root (or an rtprio limit) for SCHED_FIFO. Prints every run, then per case the median
# over rounds of each figure and palprig's p99 minus cyclictest's (goal: within 10 us).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
seconds="${2:-10}"
rounds="${3:-3}"
rate="${4:-1000}"
prio="${5:-80}"
bin="$build/bin/palprig"
period_us=$(python3 -c "print(round(1e6 / $rate))")
loops=$(python3 -c "print(round($seconds * $rate))")
for tool in cyclictest stress-ng python3; do
  command -v "$tool" >/dev/null || { echo "rt_compare: $tool not found (apt-get install rt-tests stress-ng python3)" >&2; exit 2; }
done
work="$(mktemp -d)"
stress_pid=""
cleanup() { [ -n "$stress_pid" ] && kill "$stress_pid" 2>/dev/null; wait 2>/dev/null; rm -rf "$work"; }
trap cleanup EXIT

run_cyclictest() {  # $1: output file
  cyclictest -m -p "$prio" -i "$period_us" -l "$loops" -t 1 -h 20000 -q >"$1" 2>&1
}
run_palprig() {  # $1: output file, $2...: extra options
  local out="$1"; shift
  "$bin" run --scene "$here/data/scenes/phantom_abc.json" --input sweep --realtime --rate-hz "$rate" \
    --duration-s "$seconds" --priority "$prio" --json "$@" >"$out"
}

echo "rt_compare: $(nproc) CPUs, $(uname -r) ($(uname -v)), load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "rt_compare: $rounds round(s) x {idle, loaded} x {cyclictest, palprig, palprig --no-pm-qos}, $seconds s each at $rate Hz, FIFO $prio"
for round in $(seq 1 "$rounds"); do
  for load in idle loaded; do
    if [ "$load" = loaded ]; then
      stress-ng --cpu "$(nproc)" --timeout "$((seconds * 4))s" --quiet >/dev/null 2>&1 &
      stress_pid=$!
      sleep 1
    fi
    # Alternate the order from round to round so neither program always runs first.
    if [ $((round % 2)) -eq 1 ]; then order="cyclictest palprig palprig_noqos"; else order="palprig_noqos palprig cyclictest"; fi
    for prog in $order; do
      f="$work/r${round}_${load}_${prog}"
      case "$prog" in
        cyclictest) run_cyclictest "$f" ;;
        palprig) run_palprig "$f" ;;
        palprig_noqos) run_palprig "$f" --no-pm-qos ;;
      esac
    done
    if [ -n "$stress_pid" ]; then kill "$stress_pid" 2>/dev/null || true; wait "$stress_pid" 2>/dev/null || true; stress_pid=""; fi
  done
done

python3 - "$work" "$rounds" "$period_us" <<'PY'
import json, math, os, statistics, sys
work, rounds, period_us = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])

def pct(bins, total, mx, q):
    # palprig's LatencyHistogram::percentile_us: upper edge of the 1-us bin holding rank ceil(q n).
    rank = max(1, math.ceil(q * total)); seen = 0
    for b in sorted(bins):
        seen += bins[b]
        if seen >= rank: return min(b + 1.0, mx)
    return mx

def cyclictest(path):
    bins, total, mx, over = {}, 0, 0.0, 0
    for line in open(path):
        if line.startswith("#"):
            if line.startswith("# Max Latencies:"): mx = float(line.split(":")[1])
            if line.startswith("# Histogram Overflows:"): over = int(line.split(":")[1])
            continue
        parts = line.split()
        if len(parts) == 2 and parts[0].isdigit():
            b, n = int(parts[0]), int(parts[1])
            if n: bins[b] = bins.get(b, 0) + n; total += n
    late = sum(n for b, n in bins.items() if b >= period_us) + over
    total += over
    if over: bins[10**9] = over  # beyond the histogram: counted at the maximum
    return dict(p50=pct(bins, total, mx, .5), p99=pct(bins, total, mx, .99), p999=pct(bins, total, mx, .999),
                max=mx, overruns=late, n=total)

def palprig(path):
    s = json.load(open(path)); w = s["wake_latency"]
    return dict(p50=w["p50_us"], p99=w["p99_us"], p999=w["p999_us"], max=w["max_us"], overruns=s["overruns"],
                n=s["ticks"], practices=s.get("realtime_practices", ""), note=s.get("realtime_note", ""))

names = {"cyclictest": "cyclictest", "palprig": "palprig", "palprig_noqos": "palprig --no-pm-qos"}
res = {}
for load in ("idle", "loaded"):
    for prog in names:
        for r in range(1, rounds + 1):
            f = os.path.join(work, f"r{r}_{load}_{prog}")
            res.setdefault((load, prog), []).append(cyclictest(f) if prog == "cyclictest" else palprig(f))

fmt = "{:<7} {:<20} {:>5} {:>8} {:>8} {:>8} {:>9} {:>8} {:>7}"
print(fmt.format("load", "program", "round", "p50 us", "p99 us", "p99.9 us", "max us", "overruns", "samples"))
for (load, prog), runs in res.items():
    for i, x in enumerate(runs, 1):
        print(fmt.format(load, names[prog], i, f"{x['p50']:.0f}", f"{x['p99']:.0f}", f"{x['p999']:.0f}", f"{x['max']:.0f}", x["overruns"], x["n"]))
print()
print("median over rounds (overruns: sum over rounds)")
print(fmt.format("load", "program", "", "p50 us", "p99 us", "p99.9 us", "max us", "overruns", ""))
med = {}
for (load, prog), runs in res.items():
    m = {k: statistics.median(x[k] for x in runs) for k in ("p50", "p99", "p999", "max")}
    m["overruns"] = sum(x["overruns"] for x in runs)
    med[(load, prog)] = m
    print(fmt.format(load, names[prog], "", f"{m['p50']:.0f}", f"{m['p99']:.0f}", f"{m['p999']:.0f}", f"{m['max']:.0f}", m["overruns"], ""))
print()
for load in ("idle", "loaded"):
    c, p, q = med[(load, "cyclictest")], med[(load, "palprig")], med[(load, "palprig_noqos")]
    d = p["p99"] - c["p99"]
    ok = d <= 10 and (c["overruns"] > 0 or p["overruns"] == 0)
    print(f"{load:<7} palprig - cyclictest: p50 {p['p50']-c['p50']:+.0f} us, p99 {d:+.0f} us, p99.9 {p['p999']-c['p999']:+.0f} us, "
          f"overruns {p['overruns']} vs {c['overruns']} -> {'within goal' if ok else 'OUTSIDE goal'} (p99 within 10 us; "
          f"no overruns when cyclictest has none); without PM QoS palprig p99 {q['p99']:.0f} us, overruns {q['overruns']}")
first = res[("idle", "palprig")][0]
print(f"palprig real time: {first['practices']}" + (f"; note: {first['note']}" if first['note'] else ""))
PY
