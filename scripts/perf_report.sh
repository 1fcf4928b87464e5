#!/usr/bin/env bash
# Reproduces docs/performance.md's figures: builds lienewton-bench and lienewton-perf-plot, runs the benchmark
# with 5 repetitions (medians) and JSON output, measures peak RSS of the large-N solves one process each, and
# draws docs/time_per_iteration.png with the project's renderer.
#   scripts/perf_report.sh                 # everything (~15-25 min on 2 cores)
#   FILTER='PerIteration' scripts/perf_report.sh   # only some benchmarks (the plot needs PerIteration)
# Environment: BUILD (default build-perf), OUT (default $BUILD/perf), REPS (default 5), FILTER (default all),
# SKIP_BUILD=1, SKIP_RSS=1.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${BUILD:-$ROOT/build-perf}"
OUT="${OUT:-$BUILD/perf}"
REPS="${REPS:-5}"
FILTER="${FILTER:-.}"
mkdir -p "$OUT"

if [[ "${SKIP_BUILD:-0}" != 1 ]]; then
  cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$BUILD" --target lienewton-bench lienewton-perf-plot -j"$(nproc)"
fi
BENCH="$(find "$BUILD" -name lienewton-bench -type f -perm -u+x | head -1)"
PLOT="$(find "$BUILD" -name lienewton-perf-plot -type f -perm -u+x | head -1)"

echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)" | tee "$OUT/load.txt"
"$BENCH" --benchmark_filter="$FILTER" --benchmark_repetitions="$REPS" --benchmark_report_aggregates_only=true \
  --benchmark_out="$OUT/bench.json" --benchmark_out_format=json | tee "$OUT/bench.txt"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$OUT/load.txt"

# Peak RSS (ru_maxrss, counter peak_rss_MB) of one large-N solve per process: dense vs matrix-free.
if [[ "${SKIP_RSS:-0}" != 1 ]]; then
  : >"$OUT/rss.txt"
  for b in 'LargeN_Solve/lu/32/' 'LargeN_Solve/gmres/32/' 'LargeN_Solve/lu/64/' 'LargeN_Solve/gmres/64/' \
           'LargeN_Solve/gmres/100/'; do
    "$BENCH" --benchmark_filter="^$b" --benchmark_min_time=0.01 --benchmark_format=json 2>/dev/null |
      python3 -c 'import json,sys; b=json.load(sys.stdin)["benchmarks"][0]; print(b["name"], "peak_rss_MB", round(b["peak_rss_MB"],1))' |
      tee -a "$OUT/rss.txt"
  done
fi

if grep -q '"PerIteration/' "$OUT/bench.json"; then
  "$PLOT" "$OUT/bench.json" "$ROOT/docs/time_per_iteration.png" 16 | tee "$OUT/fit.txt"
fi
