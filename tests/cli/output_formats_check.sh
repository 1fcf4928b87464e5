#!/usr/bin/env bash
# --format and --stream: `--format csv` has a header and one line per record of the JSON answer (a sweep's
# cells, a solve's trace, the work-precision points with global_error), `--format table` one line per record
# plus its header, aligned; `--stream` prints one JSON record per line, ending with the result, whose records are
# the JSON answer's (the trace, the cells); a render's --format is still its picture's; wrong uses exit 2.
set -euo pipefail
bin=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "$*"; exit 1; }
sweep=(sweep --problem paper-linear --differential exact --methods newton-group,fixed-point --n 3,4 --h 0.5,2 --threads 1)
"$bin" "${sweep[@]}" < /dev/null > "$dir/sweep.json"
"$bin" "${sweep[@]}" --format csv < /dev/null > "$dir/sweep.csv"
[[ $(head -1 "$dir/sweep.csv") == "h,iterations,method,n,rate,reason,residual,status" ]] || fail "sweep csv header: $(head -1 "$dir/sweep.csv")"
[[ $(($(wc -l < "$dir/sweep.csv") - 1)) -eq $(jq '.cells | length' "$dir/sweep.json") ]] || fail "sweep csv: not one line per cell"
# The CSV's iterations column is the JSON's, cell by cell (reason holds commas: read it with a CSV reader).
python3 - "$dir/sweep.csv" "$dir/sweep.json" <<'PY' || fail "sweep csv values differ from the JSON"
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1])))
cells = json.load(open(sys.argv[2]))["cells"]
assert [int(r["iterations"]) for r in rows] == [c["iterations"] for c in cells]
assert [r["rate"] == "" for r in rows] == [c["rate"] is None for c in cells]
PY
"$bin" solve --n 4 --h 0.5 < /dev/null > "$dir/solve.json"
"$bin" solve --n 4 --h 0.5 --format table < /dev/null > "$dir/solve.txt"
[[ $(($(wc -l < "$dir/solve.txt") - 1)) -eq $(jq '.trace | length' "$dir/solve.json") ]] || fail "solve table: not one line per iteration"
head -1 "$dir/solve.txt" | grep -q 'iteration.*residual' || fail "solve table header: $(head -1 "$dir/solve.txt")"
"$bin" work-precision --problem rigid-body --choices '[{"integrator":"dirk-cg2"}]' --h 0.25,0.125 --t-end 0.5 --format csv \
  < /dev/null > "$dir/wp.csv"
head -1 "$dir/wp.csv" | grep -q '^integrator,method,differential,.*global_error' || fail "work-precision csv header: $(head -1 "$dir/wp.csv")"
[[ $(wc -l < "$dir/wp.csv") -eq 3 ]] || fail "work-precision csv: not one line per point"
# --stream: the records as they come, then the result; the iteration records are the result's trace.
"$bin" solve --n 4 --h 0.5 --stream < /dev/null > "$dir/solve.ndjson"
[[ $(tail -1 "$dir/solve.ndjson" | jq -r .type) == result ]] || fail "solve stream does not end with its result"
[[ $(jq -c 'select(.type == "iteration") | del(.type, .seconds, .cpu_seconds)' "$dir/solve.ndjson" | wc -l) -eq $(jq '.trace | length' "$dir/solve.json") ]] \
  || fail "solve stream: not one iteration record per trace entry"
cmp <(jq -c 'select(.type == "iteration") | del(.type, .seconds, .cpu_seconds)' "$dir/solve.ndjson") \
    <(tail -1 "$dir/solve.ndjson" | jq -c '.trace[] | del(.seconds, .cpu_seconds)') || fail "solve stream records differ from its trace"
"$bin" "${sweep[@]}" --stream < /dev/null > "$dir/sweep.ndjson"
[[ $(jq -c 'select(.type == "cell")' "$dir/sweep.ndjson" | wc -l) -eq $(jq '.cells | length' "$dir/sweep.json") ]] || fail "sweep stream: not one record per cell"
"$bin" basins --size 4 --methods newton-group --stream < /dev/null | jq -r .type | tr '\n' ' ' > "$dir/basin-types"
[[ $(cat "$dir/basin-types") == "grid row row row row result " ]] || fail "basin stream: $(cat "$dir/basin-types")"
# A render's --format is the picture's.
"$bin" render residuals --n 3 --h 0.5 --methods newton-group --format svg < /dev/null > "$dir/residuals.svg"
head -c 200 "$dir/residuals.svg" | grep -q '<svg' || fail "render --format svg"
expect_usage() {
  local status=0
  "$bin" "$@" < /dev/null > /dev/null 2> "$dir/err" || status=$?
  [[ $status -eq 2 && $(jq -r .error.code "$dir/err") == usage ]] || fail "lienewton $*: status $status, $(cat "$dir/err")"
}
expect_usage solve --format xml
expect_usage solve --stream --out "$dir/x.json"
expect_usage solve --stream --format csv
expect_usage render frames --stream
echo "output formats: ok"
