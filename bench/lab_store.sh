#!/bin/bash
# The lab store benchmark (bench_lab_store) against a throwaway PostgreSQL server with fsync on
# (pg_virtualenv turns it off for tests; a lab server keeps it on). Usage: bench/lab_store.sh BUILD_DIR
set -eu
build=${1:-build}
[ -f "${TMPDIR:-/tmp}/palprig_bench_1M_trials.db" ] || "$build/bin/bench_stats" --benchmark_filter=BM_StatsTrials_1M_ByCondition/
exec pg_virtualenv -t -o fsync=on -o synchronous_commit=on "$build/bin/bench_lab_store" "${@:2}"
