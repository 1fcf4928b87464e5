#!/usr/bin/env bash
# Bounded load test against a local lienewton-server: N = 3 and N = 15 solves, throughput and p50/p99
# latency, errors must be 0 (exit 1 otherwise). Not a timed test; its figures go into the README.
#   scripts/load_test.sh [build-dir] [connections] [requests-n3] [requests-n15]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
connections="${2:-2}"
requests3="${3:-5000}"
requests15="${4:-1000}"
server="$build/bin/lienewton-server"
client="$build/load_test_client"
[ -x "$server" ] || { echo "load_test: build $server first" >&2; exit 2; }
# The client is one file; build it with the same flags as the service (Debian's compiled cpp-httplib).
if [ ! -x "$client" ] || [ "$root/scripts/load_test.cpp" -nt "$client" ]; then
  g++ -std=c++20 -O2 -o "$client" "$root/scripts/load_test.cpp" $(pkg-config --cflags --libs cpp-httplib) -pthread
fi
port="${LIENEWTON_LOAD_PORT:-18431}"
"$server" --port "$port" --threads 8 --max-streams 6 > "$build/load_test_server.log" &
pid=$!
trap 'kill -TERM "$pid" 2>/dev/null; wait "$pid" 2>/dev/null || true' EXIT
for _ in $(seq 100); do "$server" --port "$port" --healthcheck && break; sleep 0.05; done
n3='{"problem":"paper-linear","n":3,"h":0.5,"method":"newton-group","differential":"exact","seed":1}'
n15='{"problem":"paper-linear","n":15,"h":0.5,"method":"newton-group","differential":"exact","seed":1}'
"$client" 127.0.0.1 "$port" "$connections" 200 warmup "$n3" > /dev/null
"$client" 127.0.0.1 "$port" "$connections" "$requests3" "N=3" "$n3"
"$client" 127.0.0.1 "$port" "$connections" "$requests15" "N=15" "$n15"
