#!/usr/bin/env bash
# bench/stats_command.sh [BUILD_DIR] [RUNS]: `palprig stats trials` on the 1,000,000-trial store,
# timed as the user waits for it: the whole process, from exec to exit (issue 23 goal: < 1 s).
#
# The store is bench_stats' ($TMPDIR/palprig_bench_1M_trials.db; BUILD_DIR/bin/bench_stats makes
# it, about a minute, when it is missing). Two figures, each the median (and min, max) of RUNS
# runs (default 5) after one warm-up run:
#   first read   the first reader of this state of the file: PRAGMA quick_check runs (the
#                integrity cache, store/integrity_check_cache.hpp, is pointed at an empty
#                folder before each run)
#   later reads  the same state read again: the check remembered in the user's cache is skipped
# Wall time from date +%s%N around each run; the file's pages are in the page cache (the warm-up
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

# Milliseconds of one run of "$@" (its output thrown away; a failure stops the script).
time_ms() {
  local start end
  start=$(date +%s%N)
  "$@" >/dev/null
  end=$(date +%s%N)
  echo $(( (end - start) / 1000000 ))
}

# "median min max" of the numbers on stdin.
summary() { sort -n | awk '{ v[NR] = $1 } END { printf "%d ms (min %d, max %d)", v[int((NR + 1) / 2)], v[1], v[NR] }'; }

first_read() {
  rm -rf "$cache/first" && mkdir "$cache/first"
  XDG_CACHE_HOME=$cache/first time_ms "$palprig" stats trials "$db"
}
later_read() { XDG_CACHE_HOME=$cache/later time_ms "$palprig" stats trials "$db"; }

echo "palprig stats trials $db ($(du -h "$db" | cut -f1)), $runs runs each, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "machine: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1), $(nproc) cores"
first_read >/dev/null   # warm-up: the pages into the page cache
later_read >/dev/null   # and the state into the later reads' cache
echo "first read of a file state (quick_check): $(for _ in $(seq "$runs"); do first_read; done | summary)"
echo "later reads of the same state:            $(for _ in $(seq "$runs"); do later_read; done | summary)"
echo "goal: < 1000 ms"
