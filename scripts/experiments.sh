#!/usr/bin/env bash
# Regenerates the measured tables of docs/experiments.md. Each section runs the `lienewton` CLI on the requests its
# table is made of and prints the table as Markdown, headed by the date, the commit and the machine's load, so a
# table pasted into the docs says where it came from.
#   scripts/experiments.sh [--bin DIR] [SECTION...]
# DIR holds the `lienewton` binary (default build/bin). SECTION, any of (default: all, in this order):
#   figures       the paper's experiment: every method, N = 2..15, h = 2^-10..2^10, both differentials   (~1 min CPU)
#   grid          Version 1 plain, with line search / trust region, with and without the watchdog         (~3 min)
#   basins        the share of starts that converge, paper-linear N = 3, 128 x 128, h = 0.5, 4, 32       (~3 min)
#   predictors    integration iterations without and with the Lie-Euler predictor                        (seconds)
#   branches      which root: Version 1 plain and continued on the paper's grid, by branch and status; the
#                 path's cost per continued solve (median path points, CPU)                            (~3 min)
# Counts are exact for the binary that produced them; long erratic runs of ≥ 16 iterations change class with the
# last bits of rounding (another compiler, -DLIENEWTON_NATIVE=OFF, another CPU), so another build may differ.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bin=build/bin
if [ "${1:-}" = --bin ]; then bin=$2; shift 2; fi
lienewton="$bin/lienewton"
[ -x "$lienewton" ] || { echo "experiments: no $lienewton (build the lienewton target, or pass --bin DIR)" >&2; exit 2; }
command -v jq >/dev/null || { echo "experiments: jq is needed (apt-get install jq)" >&2; exit 2; }
sections=("$@")
[ ${#sections[@]} -gt 0 ] || sections=(figures grid basins predictors branches)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

header() {  # title
  echo
  echo "### $1"
  echo
  echo "<!-- scripts/experiments.sh $section: $(date -u +%F), commit $(git rev-parse --short HEAD 2>/dev/null || echo ?)," \
       "load $(cut -d' ' -f1 /proc/loadavg) -->"
  echo
}

# A status's one-letter code, as `lienewton figures` prints it.
jq_codes='def code: {"max_iterations":"M","diverged":"D","non_finite":"F","left_log_domain":"L",
  "singular_differential":"X","stagnated":"S","off_branch":"B","local_minimum":"P","no_descent":"N",
  "fold":"T","cancelled":"-"}[.];
def failures: [.[] | select(.status != "converged") | .status] | group_by(.) | map("\(.[0] | code) \(length)")
  | join(", ");
def converged: map(select(.status == "converged")) | length;'

sweep() {  # out-file request-json
  echo "$2" | nice -n 10 "$lienewton" sweep > "$1"
}

# "231 (M 63; rows < plain: 6, 7, 10; 12.3 s)": converged cells of a Version 1 sweep, the classes of the rest, the
# N whose row converges on fewer cells than in the plain sweep $2, and the sweep's wall seconds.
cell_vs_plain() {  # sweep-file plain-file
  jq -r --slurpfile plain "$2" "$jq_codes"'
    def per_n: group_by(.n) | map({key: (.[0].n | tostring), value: converged}) | from_entries;
    ($plain[0].cells | per_n) as $p
    | (.cells | per_n) as $q
    | [$q | to_entries[] | select(.value < $p[.key]) | .key | tonumber] as $below
    | (.cells | failures) as $f
    | "\(.cells | converged) (" + ([if $f == "" then empty else $f end,
         if ($below | length) > 0 then "rows < plain: \($below | map(tostring) | join(", "))" else empty end,
         "\(.seconds * 10 | round / 10) s"] | join("; ")) + ")"' "$1"
}

problems=(paper-linear paper-sine)
# LIENEWTON_DIFFERENTIALS="exact" limits the grid sections to one differential (finite differences cost ~5x more).
read -ra differentials <<< "${LIENEWTON_DIFFERENTIALS:-exact finite-difference}"

figures() {
  header "The paper's experiment: converged cells of 294 per method (N = 3…6, of 84, in parentheses)"
  echo "| problem | differential | fixed point (1.2) | Version 1 (3.5) | Version 2 (3.20) | sweep wall time |"
  echo "|---|---|---|---|---|---|"
  for p in "${problems[@]}"; do
    for d in "${differentials[@]}"; do
      sweep "$tmp/f.json" "{\"problem\":\"$p\",\"differential\":\"$d\"}"
      jq -r --arg p "$p" --arg d "$d" "$jq_codes"'
        def col($m): [.cells[] | select(.method == $m)] as $c
          | "\($c | converged) (\([$c[] | select(.n >= 3 and .n <= 6)] | converged))"
            + (($c | failures) as $f | if $f == "" then "" else "; \($f)" end);
        "| `\($p)` | \($d) | \(col("fixed-point")) | \(col("newton-group")) | \(col("newton-algebra")) | \(.seconds * 10 | round / 10) s |"' \
        "$tmp/f.json"
    done
  done
}

# Version 1 sweeps of one problem and differential, one column per variant (extra request fields), against plain.
variant_rows() {  # variant-json...
  local p d v i
  for p in "${problems[@]}"; do
    for d in "${differentials[@]}"; do
      local base="\"problem\":\"$p\",\"differential\":\"$d\",\"methods\":[\"newton-group\"]"
      sweep "$tmp/plain.json" "{$base}"
      local row="| \`$p\` | $d | $(cell_vs_plain "$tmp/plain.json" "$tmp/plain.json")"
      i=0
      for v in "$@"; do
        sweep "$tmp/v$i.json" "{$base,$v}"
        row+=" | $(cell_vs_plain "$tmp/v$i.json" "$tmp/plain.json")"
        i=$((i + 1))
      done
      echo "$row |"
    done
  done
}

grid() {
  header "Globalised Version 1 on the paper's grid: converged cells of 294"
  echo "| problem | differential | plain | line search | line search + watchdog | trust region | trust region + watchdog |"
  echo "|---|---|---|---|---|---|---|"
  variant_rows '"globalization":"line-search"' '"globalization":"line-search","watchdog":true' \
    '"globalization":"trust-region"' '"globalization":"trust-region","watchdog":true'
}

branches() {
  header "Which root, Version 1 (exact) on the paper's grid (N = 2..15, h = 2^-10..2^10, seed 1): cells by branch and status"
  echo "| problem | search | cells | continued | other | unchecked | by status | median path points | median CPU per solve |"
  echo "|---|---|---|---|---|---|---|---|---|"
  local problem search n k
  for problem in paper-linear paper-sine; do
    for search in plain continuation; do
      local cont=false
      [ "$search" = continuation ] && cont=true
      : > "$tmp/cells.ndjson"
      for n in $(seq 2 15); do
        for k in $(seq -10 10); do
          echo "{\"problem\":\"$problem\",\"n\":$n,\"h\":$(awk "BEGIN{print 2^$k}"),\"differential\":\"exact\",\"continuation\":$cont}" |
            nice -n 10 "$lienewton" solve |
            jq -c '{status, branch, cpu: .cpu_seconds, points: ((.continuation.stages // []) | map(select(.kind == "path")) | length)}' \
              >> "$tmp/cells.ndjson"
        done
      done
      jq -rs --arg p "$problem" --arg s "$search" '
        def median: sort | if length == 0 then 0 else .[length / 2 | floor] end;
        def count(b): map(select(.branch == b)) | length;
        "| \($p) | \($s) | \(length) | \(count("continued")) | \(count("other")) | \(count("unchecked")) | " +
        (group_by(.status) | map("\(.[0].status) \(length)") | join(", ")) +
        " | \(map(.points) | median) | \(map(.cpu) | median * 1e6 | round) µs |"' "$tmp/cells.ndjson"
    done
  done
}

basins() {
  header "Share of 128 × 128 starts that converge, paper-linear N = 3, seed 1, exact, r = π"
  # Column: label, variant fields, method.
  local cols=("V1|newton-group|" "V1 line search|newton-group|\"globalization\":\"line-search\","
    "V1 line search + watchdog|newton-group|\"globalization\":\"line-search\",\"watchdog\":true,"
    "V1 trust region|newton-group|\"globalization\":\"trust-region\","
    "V1 trust region + watchdog|newton-group|\"globalization\":\"trust-region\",\"watchdog\":true,"
    "V2|newton-algebra|" "V2 line search|newton-algebra|\"globalization\":\"line-search\","
    "fixed point|fixed-point|")
  local line="| h" rule="|---" c h
  for c in "${cols[@]}"; do line+=" | ${c%%|*}"; rule+="|---"; done
  echo "$line |"
  echo "$rule|"
  for h in 0.5 4 32; do
    line="| $h"
    for c in "${cols[@]}"; do
      local rest=${c#*|}
      local method=${rest%%|*} fields=${rest#*|}
      echo "{\"problem\":\"paper-linear\",\"n\":3,\"h\":$h,\"differential\":\"exact\",\"size\":128,$fields\"methods\":[\"$method\"]}" |
        nice -n 10 "$lienewton" basins > "$tmp/b.json"
      line+=" | $(jq -r '.methods[0].converged_fraction * 1000 | round / 10 | "\(.) %"' "$tmp/b.json")"
    done
    echo "$line |"
  done
}

predictors() {
  header "Integration over t ∈ [0, 1], exact differential: total iterations, predictor none → lie-euler (global error)"
  echo "| problem | integrator | h = 1/32 | h = 1/16 | h = 1/8 |"
  echo "|---|---|---|---|---|"
  local spec integrator h pred
  for spec in 'rigid-body|"problem":"rigid-body"' 'paper-linear N = 5|"problem":"paper-linear","n":5' \
              'paper-sine N = 5|"problem":"paper-sine","n":5'; do
    for integrator in implicit-euler dirk-cg2; do
      local row="| ${spec%%|*} | $integrator"
      for h in 0.03125 0.0625 0.125; do
        local it=() err=()
        for pred in none lie-euler; do
          echo "{${spec#*|},\"integrator\":\"$integrator\",\"h\":$h,\"t_end\":1,\"differential\":\"exact\",\"predictor\":\"$pred\"}" |
            nice -n 10 "$lienewton" integrate > "$tmp/i.json"
          it+=("$(jq -r .total_iterations "$tmp/i.json")")
          err+=("$(printf '%.2g' "$(jq -r .global_error "$tmp/i.json")")")
        done
        row+=" | ${it[0]} → ${it[1]} (${err[0]} → ${err[1]})"
      done
      echo "$row |"
    done
  done
}

for section in "${sections[@]}"; do
  case "$section" in
    figures | grid | basins | predictors | branches) "$section" ;;
    *) echo "experiments: unknown section $section" >&2; exit 2 ;;
  esac
done
