#!/usr/bin/env bash
# Shards: a sweep run as 3 shards (in any order, one thread each) and joined by `lienewton merge` prints
# the unsharded sweep's output byte for byte, apart from the top-level "seconds" (wall time, summed over the parts);
# every part holds cells, the parts are disjoint; a missing or repeated shard is refused with exit status 2.
# The same for a basin map run as 3 shards of rows (paper-linear h = 4: two roots, which two of the parts meet in
# the other order, so the merge renumbers them); a part of another map is refused.
set -euo pipefail
bin=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
grid='"problem":"paper-sine","differential":"exact","n":[2,3,5,8],"h":[0.25,1,4,64]'
echo "{$grid}" | "$bin" sweep > "$dir/all.json"
for i in 0 1 2; do
  echo "{$grid,\"shard\":{\"index\":$i,\"count\":3},\"threads\":1}" | "$bin" sweep > "$dir/part$i.json"
done
"$bin" merge "$dir/part2.json" "$dir/part0.json" "$dir/part1.json" > "$dir/merged.json"
without_seconds() { sed -E 's/"seconds":[^,}]*//' "$1"; }
if ! cmp <(without_seconds "$dir/all.json") <(without_seconds "$dir/merged.json"); then
  echo "merged shards differ from the unsharded sweep"
  exit 1
fi
cells() { grep -o '"method":' "$1" | wc -l; }
total=$(cells "$dir/all.json")
parts=$(( $(cells "$dir/part0.json") + $(cells "$dir/part1.json") + $(cells "$dir/part2.json") ))
[[ $total -eq 48 && $parts -eq 48 ]] || { echo "cells: $total unsharded, $parts in the parts (expected 48)"; exit 1; }
for i in 0 1 2; do
  [[ $(cells "$dir/part$i.json") -eq 16 ]] || { echo "part $i does not hold 16 cells"; exit 1; }
done
status=0
"$bin" merge "$dir/part0.json" "$dir/part1.json" 2> "$dir/err" > /dev/null || status=$?
[[ $status -eq 2 ]] && grep -q 'shard 2 of 3 is missing' "$dir/err" || { echo "missing shard: status $status"; cat "$dir/err"; exit 1; }
status=0
"$bin" merge "$dir/part0.json" "$dir/part1.json" "$dir/part1.json" "$dir/part2.json" 2> "$dir/err" > /dev/null || status=$?
[[ $status -eq 2 ]] && grep -q 'shard 1 is given twice' "$dir/err" || { echo "repeated shard: status $status"; cat "$dir/err"; exit 1; }

basin='"problem":"paper-linear","n":3,"h":4,"differential":"exact","size":21'
echo "{$basin}" | "$bin" basins > "$dir/basins.json"
for i in 0 1 2; do
  echo "{$basin,\"shard\":{\"index\":$i,\"count\":3}}" | "$bin" basins > "$dir/basins$i.json"
  grep -q "\"shard\":{\"count\":3,\"index\":$i,\"request\":{[^}]*},\"rows\":\[$i,$((i + 3)),$((i + 6)),$((i + 9)),$((i + 12)),$((i + 15)),$((i + 18))\]}" \
    "$dir/basins$i.json" || { echo "basin part $i does not say it holds rows $i, $((i + 3)), ..."; exit 1; }
done
"$bin" merge "$dir/basins1.json" "$dir/basins2.json" "$dir/basins0.json" > "$dir/basins-merged.json"
if ! cmp <(without_seconds "$dir/basins.json") <(without_seconds "$dir/basins-merged.json"); then
  echo "merged basin shards differ from the unsharded basin map"
  exit 1
fi
roots=$(grep -o '"hg_angle":' "$dir/basins.json" | wc -l)
[[ $roots -eq 2 ]] || { echo "expected two roots, found $roots"; exit 1; }
echo "{${basin/\"h\":4/\"h\":0.5},\"shard\":{\"index\":2,\"count\":3}}" | "$bin" basins > "$dir/foreign.json"
status=0
"$bin" merge "$dir/basins0.json" "$dir/basins1.json" "$dir/foreign.json" 2> "$dir/err" > /dev/null || status=$?
[[ $status -eq 2 ]] && grep -q '"field":"shard"' "$dir/err" || { echo "foreign basin part: status $status"; cat "$dir/err"; exit 1; }
status=0
"$bin" merge "$dir/basins0.json" "$dir/basins2.json" 2> "$dir/err" > /dev/null || status=$?
[[ $status -eq 2 ]] && grep -q 'shard 1 of 3 is missing' "$dir/err" || { echo "missing basin shard: status $status"; cat "$dir/err"; exit 1; }
echo "shards merge to the unsharded sweep ($total cells) and basin map (21 x 21)"
