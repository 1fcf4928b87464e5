#!/usr/bin/env bash
# MPI P = 1 vs P = 2 on the paper's full experiment: `lienewton figures DIFF` (paper-linear and
# paper-sine, 3 methods, N = 2..15, h = 2^-10..2^10: 1764 cells) under `mpirun -n 1` and `mpirun -n 2`, and the
# plain process on all cores (threads) as the reference, interleaved REPEATS times so that all three meet the
# same machine load. Prints each run's wall seconds, the medians and their ratios, and checks that every output
# equals the plain one (seconds masked). Needs a -DLIENEWTON_MPI=ON build.
#   bench/mpi_sweep.sh build/bin/lienewton [exact|finite-difference] [REPEATS]
set -euo pipefail
bin=$1
differential=${2:-exact}
repeats=${3:-3}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export OMPI_MCA_btl_vader_single_copy_mechanism=none
masked() { sed -E 's/cells in [0-9.e+-]+ s/cells in _ s/' "$1"; }
run() {  # label, command...: wall seconds on stdout, output in $dir/<label>.md
  local label=$1; shift
  local start end
  start=$(date +%s.%N)
  "$@" figures "$differential" > "$dir/$label.md"
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN {printf "%.2f", b - a}'
}
mpi=(mpirun --allow-run-as-root)
declare -A times
for ((r = 1; r <= repeats; r++)); do
  times[threads]+="$(run threads "$bin") "
  times[p1]+="$(run p1 "${mpi[@]}" -n 1 "$bin") "
  times[p2]+="$(run p2 "${mpi[@]}" -n 2 "$bin") "
  for label in p1 p2; do
    cmp -s <(masked "$dir/threads.md") <(masked "$dir/$label.md") || { echo "$label output differs"; exit 1; }
  done
done
median() { tr ' ' '\n' <<< "$1" | grep . | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
echo "lienewton figures $differential (1764 cells), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), wall seconds:"
for label in threads p1 p2; do echo "  $label: ${times[$label]}-> median $(median "${times[$label]}")"; done
p1=$(median "${times[p1]}"); p2=$(median "${times[p2]}"); th=$(median "${times[threads]}")
awk -v p1="$p1" -v p2="$p2" -v th="$th" 'BEGIN {
  printf "  MPI P=1 / P=2: %.2fx (parallel efficiency %.0f %%)\n", p1 / p2, 50 * p1 / p2
  printf "  one process on all cores (threads) / MPI P=2: %.2fx\n", th / p2 }'
echo "outputs identical (seconds masked)"
