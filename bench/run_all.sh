#!/usr/bin/env bash
# bench/run_all.sh [BUILD_DIR]: run every benchmark program BUILD_DIR/bin/bench_* (make bench)
# and print the tables the figures of docs/benchmarks.md come from, headed by the machine and its
# load, since on a shared machine the load decides the tails.
#
# Google Benchmark programs run with --benchmark_min_time (default 0.5 s per case, set
# PALPRIG_BENCH_MIN_TIME; cases that fix their own time or iterations keep them) and their
# counters as a table. Other programs (bench_pulse_correlation) print their own table. Each
# program is stopped after PALPRIG_BENCH_TIMEOUT seconds (default 600). Exit status: the number
# of programs that failed or ran out of time (0 when all ran).
set -u

build=${1:-build}
min_time=${PALPRIG_BENCH_MIN_TIME:-0.5}
limit_s=${PALPRIG_BENCH_TIMEOUT:-600}

shopt -s nullglob
programs=("$build"/bin/bench_*)
if [ ${#programs[@]} -eq 0 ]; then
  echo "bench/run_all.sh: no benchmark programs in $build/bin (configure with -DPALPRIG_BENCH=ON and build)" >&2
  exit 2
fi

machine() {
  local cpu cores mem
  cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
  cores=$(nproc)
  mem=$(awk '/^MemTotal/ { printf "%.0f GiB", $2 / 1048576 }' /proc/meminfo)
  echo "$cpu, $cores cores, $mem, $(uname -sr)$(systemd-detect-virt -q 2>/dev/null && echo ", virtual machine ($(systemd-detect-virt))")"
}
load() { cut -d' ' -f1-3 /proc/loadavg; }

echo "palprig benchmarks, $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "machine: $(machine)"
echo "load average (1/5/15 min) at start: $(load)"
echo "build: $build ($(sed -n 's/^CMAKE_BUILD_TYPE:STRING=//p' "$build/CMakeCache.txt" 2>/dev/null || echo unknown))"

failed=0
for program in "${programs[@]}"; do
  [ -x "$program" ] || continue
  name=$(basename "$program")
  echo
  echo "## $name (load $(load))"
  start=$(date +%s)
  if readelf -d "$program" 2>/dev/null | grep -q 'libbenchmark'; then
    timeout --signal=INT --kill-after=10 "$limit_s" "$program" --benchmark_min_time="$min_time" \
      --benchmark_counters_tabular=true --benchmark_color=false
  else
    timeout --signal=INT --kill-after=10 "$limit_s" "$program"
  fi
  status=$?
  if [ $status -eq 124 ]; then
    echo "$name: stopped after ${limit_s} s (PALPRIG_BENCH_TIMEOUT)" >&2
    failed=$((failed + 1))
  elif [ $status -ne 0 ]; then
    echo "$name: exit status $status" >&2
    failed=$((failed + 1))
  fi
  echo "($name took $(( $(date +%s) - start )) s)"
done

# The command end to end, as the user waits for it (bench_stats above made its store).
if [ -x "$build/bin/palprig" ]; then
  echo
  echo "## stats_command.sh (load $(load))"
  if ! "$(dirname "$0")/stats_command.sh" "$build" 5; then
    echo "stats_command.sh: failed" >&2
    failed=$((failed + 1))
  fi
fi

echo
echo "load average at end: $(load)"
if [ $failed -ne 0 ]; then
  echo "bench/run_all.sh: $failed of ${#programs[@]} benchmark programs failed" >&2
fi
exit $failed
