#!/usr/bin/env bash
# The outputs a refactoring must leave byte for byte: the demo's table, a simulated session of
# every shipped protocol (its stored rows, `stats trials`, the long CSV, BIDS and the plot),
# and `stats psychometric` on a threshold store. Run it with the palprig of two builds and
# compare the folders:
#   tools/study_fingerprint.sh build-before/bin/palprig /tmp/before
#   tools/study_fingerprint.sh build/bin/palprig /tmp/after
#   diff -r /tmp/before /tmp/after && echo identical
# Wall-clock columns (completed_utc, started_utc, created_utc, since_utc) and the demo's timing
# lines are masked; everything else is compared as written.
set -euo pipefail
bin=$(realpath "$1")
out=$2
here=$(cd "$(dirname "$0")/.." && pwd)
binsrc=$(cd "$(dirname "$bin")/../.." && pwd)  # the source tree the binary was built from (its data/)
rm -rf "$out"
mkdir -p "$out"
cd "$out"
"$bin" demo | grep -v -E 'ticks/s|latency|wall|elapsed|us\b' > demo.txt
dump() {  # every table of a store as text, wall-clock columns masked
  sqlite3 "$1" .dump | sed -E 's/[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z/<utc>/g; s#'"$here"'#<src>#g; s#'"$binsrc"'#<src>#g; s#'"$out"'#<out>#g'
}
for protocol in "$here"/data/protocols/*.json; do
  name=$(basename "$protocol" .json)
  "$bin" experiment run --protocol "$protocol" --participant sim:3 --db "$name.db" --quiet > "$name.run.txt" 2>&1 || echo "exit $?" >> "$name.run.txt"
  dump "$name.db" > "$name.sql"
  "$bin" stats trials "$name.db" --json > "$name.stats.json" 2>&1 || echo "exit $?" >> "$name.stats.json"
  "$bin" export "$name.db" --format csv --out "$name.csv" > "$name.export.txt" 2>&1 || echo "exit $?" >> "$name.export.txt"
  "$bin" export "$name.db" --format bids --out "$name.bids" >> "$name.export.txt" 2>&1 || echo "exit $?" >> "$name.export.txt"
  "$bin" export "$name.db" --format csv --out "$name.plot" --plot "$name.plot" >> "$name.export.txt" 2>&1 || echo "exit $?" >> "$name.export.txt"
done
"$bin" stats psychometric threshold_1up3down.db --by track_name --json > psychometric.json 2>&1 || echo "exit $?" >> psychometric.json
# The database files themselves hold wall-clock stamps; their dumps above are compared instead.
rm -f ./*.db ./*.db-wal ./*.db-shm
sed -i -E "s#$out#<out>#g; s#$here#<src>#g; s#$binsrc#<src>#g" ./*.txt ./*.json
# Wall-clock stamps in every written file (completed_utc columns) and the fits' own timings.
find . -type f \( -name '*.csv' -o -name '*.tsv' -o -name '*.json' -o -name '*.txt' \) -print0 |
  xargs -0 sed -i -E 's/[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z/<utc>/g; s/("[a-z_]*seconds": )[0-9.e+-]+/\1<s>/g'
