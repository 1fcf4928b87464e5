#!/usr/bin/env bash
# Reproduces docs/performance.md's figures: builds lienewton-bench and lienewton-perf-plot, runs the benchmark
# with 5 repetitions (medians) and JSON output, measures peak RSS of the large-N solves one process each, and
# draws docs/time_per_iteration.png with the project's renderer.
#   scripts/perf_report.sh                 # everything (~15-25 min on 2 cores)
#   FILTER='PerIteration' scripts/perf_report.sh   # only some benchmarks (the plot needs PerIteration)
# Environment: BUILD (default build-perf), OUT (default $BUILD/perf), REPS (default 5), FILTER (default all),
# SKIP_BUILD=1, SKIP_RUN=1 (reuse $OUT/bench.json), SKIP_RSS=1.
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

if [[ "${SKIP_RUN:-0}" != 1 ]]; then
  echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)" | tee "$OUT/load.txt"
  # The binary's exit status is reported, not fatal: the JSON is complete once the last benchmark ran (a crash
  # at process exit, after the render benchmarks, has been seen; see docs/performance.md).
  status=0
  "$BENCH" --benchmark_filter="$FILTER" --benchmark_repetitions="$REPS" --benchmark_report_aggregates_only=true \
    --benchmark_out="$OUT/bench.json" --benchmark_out_format=json >"$OUT/bench.txt" || status=$?
  cat "$OUT/bench.txt"
  echo "lienewton-bench exit status: $status" | tee -a "$OUT/load.txt"
  echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$OUT/load.txt"
fi

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

# The target ratios from the medians, as Markdown (docs/performance.md quotes them).
python3 - "$OUT/bench.json" <<'PY' | tee "$OUT/summary.md"
import json, sys
doc = json.load(open(sys.argv[1]))
med = {}
for b in doc["benchmarks"]:
    if b.get("error_occurred"):
        print("ERROR:", b["name"], b.get("error_message")); continue
    if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median": continue
    med[b["run_name"]] = b
def t(name):  # seconds: wall time for the /real_time (multi-threaded or long) benchmarks, else CPU time of
    b = med[name]  # the single-threaded micro-benchmarks (robust against other processes on a shared machine)
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
    return b["real_time" if name.endswith("real_time") else "cpu_time"] * scale
def fmt(s):
    for unit, f in (("s", 1), ("ms", 1e-3), ("us", 1e-6), ("ns", 1e-9)):
        if s >= f: return f"{s / f:.3g} {unit}"
    return f"{s * 1e9:.3g} ns"
def have(*names): return all(n in med for n in names)
print("| target | measured (medians) | ratio | goal |\n|---|---|---|---|")
for p in ("rigid_body", "paper_linear"):
    a, b = f"Solve_Baseline/{p}", f"Solve_Lienewton/{p}"
    if have(a, b): print(f"| SO(3) solve {p} | baseline {fmt(t(a))}, lienewton {fmt(t(b))} | {t(a)/t(b):.1f}x | >= 30x |")
parts = ["SO3_Exp", "SO3_Log", "SO3_DexpinvMatrix", "SO3_LUSolve3"]
if have("SO3_NewtonIteration", *parts):
    s = sum(t(x) for x in parts)
    print(f"| SO(3) iteration vs parts | iteration {fmt(t('SO3_NewtonIteration'))}, parts {fmt(s)} "
          f"({' + '.join(fmt(t(x)) for x in parts)}) | {t('SO3_NewtonIteration')/s:.2f}x | <= 2x |")
base = "Sweep_Baseline/subset/iterations:1/real_time"
fd, ex = "Sweep_Lienewton/fd/full/iterations:1/real_time", "Sweep_Lienewton/exact/full/iterations:1/real_time"
fds, exs = "Sweep_Lienewton/fd/subset/iterations:1/real_time", "Sweep_Lienewton/exact/subset/iterations:1/real_time"
if have(base, fd, ex):
    est = t(base) * 21 / 5
    print(f"| sweep, fd vs baseline | baseline subset {fmt(t(base))} (x 21/5 = {fmt(est)} extrapolated), fd full {fmt(t(fd))} | {est/t(fd):.1f}x | >= 20x |")
    print(f"| sweep, exact vs fd | exact full {fmt(t(ex))} | {t(fd)/t(ex):.1f}x | >= 10x |")
if have(base, fds, exs):
    print(f"| sweep subset (same grid, no extrapolation) | baseline {fmt(t(base))}, fd {fmt(t(fds))}, exact {fmt(t(exs))} | fd {t(base)/t(fds):.1f}x, exact/fd {t(fds)/t(exs):.1f}x | |")
for n in (8, 12, 16, 24, 32, 64):
    lu, gm = f"LargeN_Solve/lu/{n}/real_time", f"LargeN_Solve/gmres/{n}/real_time"
    if have(lu, gm):
        print(f"| N = {n}: lu vs gmres (exact) | lu {fmt(t(lu))} ({med[lu]['iterations']:.0f} it, {fmt(med[lu]['per_iteration'])}/it), "
              f"gmres {fmt(t(gm))} ({med[gm]['iterations']:.0f} it, {fmt(med[gm]['per_iteration'])}/it) | {t(lu)/t(gm):.1f}x | >= 5x at 64 |")
g100 = "LargeN_Solve/gmres/100/real_time"
if have(g100):
    b = med[g100]
    print(f"| N = 100 gmres | {fmt(t(g100))}, {b['iterations']:.0f} iterations, residual {b['residual']:.2e} | | converged |")
PY
