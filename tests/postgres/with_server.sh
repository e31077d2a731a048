#!/bin/bash
# Runs one PostgreSQL test program (or one of its tests) against a throwaway server:
# pg_virtualenv (postgresql-common) creates a cluster in a temporary directory (-t, also as
# root), sets PGHOST, PGPORT, PGUSER, PGPASSWORD, PGDATABASE, runs the command and drops the
# cluster. ctest uses this script as the test program's emulator.
#
# Where no server can be started (no PostgreSQL installed, cluster creation failed), the test
# still runs, with PALPRIG_PG_SKIP set to the reason: the tests skip and print it.
# Listing the tests (gtest discovery) needs no server.
#
# PALPRIG_PG_REQUIRED=1 (set it on a machine that must have a server) turns that skip into a failure with the same
# reason: on a machine that must have a server, a skipped lab-store test is a broken set-up.
set -u
no_server() {  # no_server REASON COMMAND...
  local reason=$1
  shift
  if [ "${PALPRIG_PG_REQUIRED:-0}" = 1 ]; then
    echo "with_server.sh: PALPRIG_PG_REQUIRED=1 but $reason" >&2
    exit 1
  fi
  PALPRIG_PG_SKIP="$reason" exec "$@"
}
for arg in "$@"; do
  if [ "$arg" = "--gtest_list_tests" ]; then exec "$@"; fi
done

if ! command -v pg_virtualenv >/dev/null 2>&1; then
  no_server "pg_virtualenv not found (install postgresql and postgresql-common)" "$@"
fi

started=$(mktemp -t palprig-pg-started.XXXXXX)
rm -f "$started"
log=$(mktemp -t palprig-pg-log.XXXXXX)
inner=$(mktemp -t palprig-pg-inner.XXXXXX)
trap 'rm -f "$started" "$log" "$inner"' EXIT
# Inside the environment: note that the server came up, let the next test create its cluster
# (pg_createcluster picks "the next free port" without a lock of its own), run the test.
cat >"$inner" <<'INNER'
#!/bin/bash
touch "$1"; shift
flock -u 9
exec "$@"
INNER
chmod +x "$inner"

attempt=0
while :; do
  attempt=$((attempt + 1))
  (
    flock 9
    exec pg_virtualenv -t "$inner" "$started" "$@"
  ) 9>"${TMPDIR:-/tmp}/palprig-pg-virtualenv.lock" >"$log" 2>&1
  rc=$?
  if [ -e "$started" ]; then
    # The test ran: its output (and pg_virtualenv's server log when it failed) is in $log.
    cat "$log"
    exit $rc
  fi
  [ $attempt -lt 2 ] || break
done
reason=$(grep -v '^\s*$' "$log" | tail -3 | tr '\n' ' ')
no_server "no PostgreSQL server could be started by pg_virtualenv: ${reason}" "$@"
