#!/usr/bin/env bash
# Builds the request-parsing and user-program fuzzers with clang (libFuzzer + ASan + UBSan) in build-fuzz/ and
# runs each for a bounded number of inputs over the committed seed corpus. CI: tests/fuzz/run_fuzzer.sh [runs]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
runs="${1:-50000}"
build="${LIENEWTON_FUZZ_BUILD:-$root/build-fuzz}"
"$root/scripts/deps.sh" fuzz
# Every project file is instrumented (LIENEWTON_FUZZ); -O1 and line tables keep that build short. No NDEBUG: Eigen's
# own range checks stay on, so an out-of-range read inside Eigen (an empty SVD's first singular value) aborts here
# even where it reads mapped memory that ASan does not see.
cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" -DLIENEWTON_FUZZ=ON \
  -DLIENEWTON_NATIVE=OFF -DLIENEWTON_BENCH=OFF -DLIENEWTON_TESTS=ON >/dev/null
cmake --build "$build" -j"$(nproc)" --target lienewton_fuzz_request lienewton_fuzz_program lienewton_fuzz_program_grammar
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
mkdir "$scratch/request" "$scratch/program" "$scratch/grammar"
"$build/tests/fuzz/../../bin/lienewton_fuzz_request" -runs="$runs" -max_len=4096 -timeout=10 "$scratch/request" "$root/tests/fuzz/corpus"
# The program language: its inputs are cheap, so a fifth of the runs covers it.
"$build/tests/fuzz/../../bin/lienewton_fuzz_program" -runs="$(( runs / 5 ))" -max_len=2048 -timeout=10 "$scratch/program" \
  "$root/tests/fuzz/program_corpus"
# The same language, programs written from its grammar (fuzz_program_grammar.cpp): slower inputs (each runs a
# Newton step), so a tenth of the runs.
"$build/tests/fuzz/../../bin/lienewton_fuzz_program_grammar" -runs="$(( runs / 10 ))" -max_len=512 -timeout=10 \
  "$scratch/grammar" "$root/tests/fuzz/program_grammar_corpus"
