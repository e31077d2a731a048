#!/usr/bin/env bash
# bench/stats_command.sh [BUILD_DIR] [RUNS]: `palprig stats trials` on the 1,000,000-trial store,
# timed as the user waits for it: the whole process, from exec to exit (goal: < 1 s).
#
# The store is bench_stats' ($TMPDIR/palprig_bench_1M_trials.db; BUILD_DIR/bin/bench_stats makes
# it, about a minute, when it is missing). Two figures, each the median (and min, max) of RUNS
# runs (default 5) after one warm-up run:
#   first read   the first reader of this state of the file: PRAGMA quick_check runs (the
#                integrity cache, store/integrity_check_cache.hpp, is pointed at an empty
#                folder before each run)
#   later reads  the same state read again: the check remembered in the user's cache is skipped
# Wall and CPU (user + system) time of the process from GNU time; the file's pages are in the page cache (the warm-up
# read them), as after the session that wrote them.
set -euo pipefail

build=${1:-build}
runs=${2:-5}
db=${TMPDIR:-/tmp}/palprig_bench_1M_trials.db
palprig=$build/bin/palprig

if [ ! -f "$db" ]; then
  echo "making $db with $build/bin/bench_stats ..." >&2
  "$build/bin/bench_stats" --benchmark_filter=BM_StatsTrials_1M_ByCondition/ >/dev/null
fi

cache=$(mktemp -d)
trap 'rm -rf "$cache"' EXIT

# "wall_ms cpu_ms" of one run of "$@" (its output thrown away; a failure stops the script): GNU
# time's elapsed and user + system seconds of the process.
time_ms() {
  local out
  out=$(mktemp)
  /usr/bin/time -f '%e %U %S' -o "$out" "$@" >/dev/null
  awk '{ printf "%d %d\n", $1 * 1000, ($2 + $3) * 1000 }' "$out"
  rm -f "$out"
}

# "median (min, max)" of the numbers in column $1 of stdin.
summary() {
  awk -v c="$1" '{ print $c }' | sort -n |
    awk '{ v[NR] = $1 } END { printf "%d ms (min %d, max %d)", v[int((NR + 1) / 2)], v[1], v[NR] }'
}

report() {
  local runs_out
  runs_out=$(for _ in $(seq "$runs"); do "$1"; done)
  echo "wall $(echo "$runs_out" | summary 1), CPU $(echo "$runs_out" | summary 2)"
}

first_read() {
  rm -rf "$cache/first" && mkdir "$cache/first"
  XDG_CACHE_HOME=$cache/first time_ms "$palprig" stats trials "$db"
}
later_read() { XDG_CACHE_HOME=$cache/later time_ms "$palprig" stats trials "$db"; }

echo "palprig stats trials $db ($(du -h "$db" | cut -f1)), $runs runs each, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "machine: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1), $(nproc) cores"
first_read >/dev/null   # warm-up: the pages into the page cache
later_read >/dev/null   # and the state into the later reads' cache
echo "first read of a file state (quick_check): $(report first_read)"
echo "later reads of the same state:            $(report later_read)"
echo "goal: < 1000 ms"
