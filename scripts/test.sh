#!/usr/bin/env bash
# Quick start, step 2: installs what the tests need too (Chromium, nginx, npm packages from the lockfile),
# builds and runs the whole suite through ctest.
#   scripts/test.sh              Release build in build/ (with -DLIENEWTON_MPI=ON)
#   scripts/test.sh --sanitize   the same tests in an ASan + UBSan (incl. float-cast-overflow) build in build-asan/
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/deps.sh test
if [ "${1:-}" = --sanitize ]; then
  dir=build-asan
  # -g1: line tables are all a sanitizer report needs. -O1: the build is CI's longest stage, and -O1 compiles a
  # solver test in 46 s where -O2 takes 65 s; for lienewton_core, 397 s of CPU against 534 s at -O2, and the
  # suite ran no slower (ctest 280 s against 295 s).
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DLIENEWTON_SANITIZE=ON -DLIENEWTON_BENCH=OFF
else
  dir=build
  # The CLI with MPI (ctest mpi_check runs it under mpirun); the sanitizer build stays without.
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DLIENEWTON_MPI=ON
fi
cmake --build "$dir" -j"$(nproc)"
ctest --test-dir "$dir" --output-on-failure -j"$(nproc)"
