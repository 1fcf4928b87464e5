#!/usr/bin/env bash
# MPI: `mpirun -n 3 lienewton sweep|basins|figures` prints the single-process output byte for byte,
# apart from wall-clock seconds. Three ranks on two cores (--oversubscribe): rank 0 hands out items and computes,
# two ranks compute. A rank that ran the command on its own would print a second copy, and a lost, repeated or
# misfiled cell, row or root would change the output: each comparison fails then.
set -euo pipefail
bin=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
# Containers (CI's fresh Debian) may forbid the cross-process memory copy of Open MPI's shared-memory transport;
# the messages here are small, so plain copies through shared memory are as fast.
export OMPI_MCA_btl_vader_single_copy_mechanism=none
mpi() { mpirun --oversubscribe --allow-run-as-root -n 3 "$bin" "$@"; }
without_seconds() { sed -E -e 's/"seconds":[^,}]*//g' -e 's/cells in [0-9.e+-]+ s/cells in _ s/' "$1"; }
same() {  # name, serial file, MPI file
  if ! cmp <(without_seconds "$2") <(without_seconds "$3"); then
    echo "$1: the MPI output differs from the single-process output"
    diff <(without_seconds "$2") <(without_seconds "$3") | head -20
    exit 1
  fi
  echo "$1: same output ($(wc -c < "$3") bytes)"
}

sweep='{"problem":"paper-sine","n":[2,3,5,8],"h":[0.25,1,4,64]}'  # finite differences, 48 cells
echo "$sweep" | "$bin" sweep > "$dir/sweep.json"
echo "$sweep" | mpi sweep > "$dir/sweep-mpi.json"
[[ $(grep -o '"method":' "$dir/sweep-mpi.json" | wc -l) -eq 48 ]] || { echo "sweep: not 48 cells"; exit 1; }
same sweep "$dir/sweep.json" "$dir/sweep-mpi.json"

# Dozens of roots (how many is rounding's: 59 to 70 across builds), whose ids depend on classifying rows in order
basins='{"problem":"paper-sine","n":4,"h":8,"size":12}'
echo "$basins" | "$bin" basins > "$dir/basins.json"
echo "$basins" | mpi basins > "$dir/basins-mpi.json"
grep -q '"id":19' "$dir/basins-mpi.json" || { echo "basins: fewer than 20 roots, too few to number out of order"; exit 1; }
same basins "$dir/basins.json" "$dir/basins-mpi.json"

"$bin" figures exact > "$dir/figures.md"
mpi figures exact > "$dir/figures-mpi.md"
same figures "$dir/figures.md" "$dir/figures-mpi.md"

# An invalid request: every rank meets the error, rank 0 alone reports it, and the job exits with status 2.
status=0
echo '{"h":-1}' | mpi sweep > "$dir/out" 2> "$dir/err" || status=$?
[[ $status -eq 2 && ! -s "$dir/out" && $(grep -c '"field":"h"' "$dir/err") -eq 1 ]] ||
  { echo "invalid request: status $status"; cat "$dir/err"; exit 1; }
echo "invalid request: one error naming h, status 2"
