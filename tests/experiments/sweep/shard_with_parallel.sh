#!/bin/sh
# Runs tests/regression/energy_drift.json as 3 shards with GNU parallel into 3 folders (as 3
# machines would), merges them, and checks that the merged table equals an unsharded run's.
# Usage: shard_with_parallel.sh DRAPELAB SOURCE_DIR WORK_DIR. Exit 77 (skipped) without
# GNU parallel or without the experiment commands.
set -eu
drapelab=$1 src=$2 work=$3
python=${DRAPE_PYTHON:-/usr/bin/python3}
command -v parallel >/dev/null 2>&1 || { echo "GNU parallel not found: skipped"; exit 77; }
"$drapelab" experiment --help >/dev/null 2>&1 || { echo "drapelab has no experiment command: skipped"; exit 77; }
exp=$src/tests/regression/energy_drift.json
rm -rf "$work"
mkdir -p "$work"

"$drapelab" experiment "$exp" --out "$work/whole" --jobs 1
parallel --halt now,fail=1 "$drapelab" experiment "$exp" --out "$work/machine{}" --shard {}/3 --jobs 1 ::: 1 2 3
"$drapelab" merge "$work/merged" "$work/machine1" "$work/machine2" "$work/machine3"

"$python" - "$work/whole/results.json" "$work/merged/results.json" <<'PY'
import json, sys
def rows(path):
    doc = json.load(open(path))
    for row in doc["runs"]:
        row.pop("wall_seconds")
        row.pop("cpu_seconds")
        row.pop("date")  # when the run ran (provenance): differs between executions
    return doc["runs"]
whole, merged = rows(sys.argv[1]), rows(sys.argv[2])
assert whole == merged, "merged shards differ from the unsharded run"
print(f"{len(merged)} runs: merged shards equal the unsharded results")
PY
