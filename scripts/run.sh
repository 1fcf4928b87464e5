#!/usr/bin/env bash
# Quick start, step 1: installs what is missing, builds a Release build and starts the service on
# http://127.0.0.1:8080 (override with LIENEWTON_HOST / LIENEWTON_PORT or flags passed through).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/deps.sh build
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target lienewton lienewton-server
exec build/bin/lienewton-server --web-root web "$@"
