#!/usr/bin/env bash
# Quick start, step 2: installs what the tests need too (Chromium, nginx, npm packages from the lockfile),
# builds and runs the whole suite through ctest.
#   scripts/test.sh              Release build in build/ (with -DLIENEWTON_MPI=ON)
#   scripts/test.sh --sanitize   the same tests in an ASan + UBSan (incl. float-cast-overflow) build in build-asan/,
#                                compiled with clang, with the libFuzzer harnesses (tests/fuzz, ctest label fuzz)
#   Further arguments go to ctest: CI's sanitize stage passes -LE 'attack|browser|fuzz' (its attack stage runs the
#   battery against this build's server, its fuzz stage passes -L fuzz, and the browser tests, which check the page,
#   run in the Release suite); its fresh-debian stage runs the Release suite with -LE attack.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/deps.sh test
if [ "${1:-}" = --sanitize ]; then
  shift
  scripts/deps.sh fuzz
  dir=build-asan
  # The sanitizer build is CI's longest stage, and the fuzzers' build too (one build, not two). clang: it compiles
  # the solver instances under ASan + UBSan faster than GCC 12 (docs/development.md). -g1: line tables are all a
  # sanitizer report needs. -O1: it compiles faster than -O2, and the suite runs no slower. NDEBUG: without it
  # (Eigen's range checks on) the attack battery's programs on many bodies met the ASan server's deadline.
  cmake -S . -B "$dir" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DLIENEWTON_SANITIZE=ON -DLIENEWTON_FUZZ=ON -DLIENEWTON_BENCH=OFF
else
  dir=build
  # The CLI with MPI (ctest mpi_check runs it under mpirun); the sanitizer build stays without.
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DLIENEWTON_MPI=ON
fi
cmake --build "$dir" -j"$(nproc)"
ctest --test-dir "$dir" --output-on-failure -j"$(nproc)" "$@"
