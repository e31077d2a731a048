#!/usr/bin/env bash
# Time every compile and link of a build (docs/developing.md, "Build time").
#   tools/build_time.sh step LOG CMD...   (the launcher) run CMD, append "cpu_s wall_s output" to LOG
#   tools/build_time.sh report LOG [N]    CPU and wall summed per target, and the N (15) costliest steps
# Used as CMake's launcher in front of ccache:
#   cmake -B build-timed -DCMAKE_CXX_COMPILER_LAUNCHER="$PWD/tools/build_time.sh;step;$PWD/t.log;ccache" \
#         -DCMAKE_CXX_LINKER_LAUNCHER="$PWD/tools/build_time.sh;step;$PWD/t.log"
#   CCACHE_DISABLE=1 cmake --build build-timed -j2      (cold: ccache neither read nor written)
set -euo pipefail
mode=${1:-}
case "$mode" in
  step)
    log=$2; shift 2
    out=""; prev=""
    for a in "$@"; do
      [ "$prev" = "-o" ] && out=$a
      prev=$a
    done
    t=$(mktemp)
    status=0
    /usr/bin/time -f "%U %S %e" -o "$t" "$@" || status=$?
    read -r user sys wall < <(tail -n 1 "$t") || true
    rm -f "$t"
    echo "$(awk -v u="${user:-0}" -v s="${sys:-0}" 'BEGIN{printf "%.2f", u+s}') ${wall:-0} $PWD/$out" >>"$log"
    exit $status
    ;;
  report)
    log=$2; n=${3:-15}
    # A step run again (an interrupted build resumed) counts once, its last run.
    awk -v n="$n" '
      { last[$3]=$0 }
      END { for (o in last) print last[o] }' "$log" | awk -v n="$n" '
      { cpu=$1; wall=$2; out=$3
        t=out
        if (match(out, /CMakeFiles\/[^\/]+\.dir\//)) { t=substr(out, RSTART+11, RLENGTH-16) }
        else { sub(/.*\//, "", t); t=t " (link)" }
        cpu_t[t]+=cpu; n_t[t]++; total+=cpu; steps++ }
      END {
        printf "%d steps, %.0f s CPU in all (%.1f min)\n", steps, total, total/60
        for (t in cpu_t) printf "%8.1f s %5d  %s\n", cpu_t[t], n_t[t], t | "sort -rn"
      }'
    echo "costliest steps:"
    sort -rn "$log" | head -n "$n" | awk '{ printf "%8.1f s  %s\n", $1, $3 }'
    ;;
  *)
    sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
    ;;
esac
