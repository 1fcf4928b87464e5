#!/usr/bin/env bash
# Runs the attack battery (tests/attack/attacks.py) against lienewton-server on a free loopback port.
#   tests/attack/run_attacks.sh [--via-nginx] [SERVER_BIN]     (default build/bin/lienewton-server)
# Direct: one server with 3 s request and sweep deadlines. --via-nginx: deploy/run_local.sh starts nginx with
# deploy/nginx/lienewton.conf in front of 2 replicas, and the same battery runs through nginx.
# Loopback only; the whole run is bounded (timeout below). LIENEWTON_ATTACK_STACK_KIB: see the direct server below.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
mode=direct
[ "${1:-}" = --via-nginx ] && { mode=nginx; shift; }
server_bin="$(realpath "${1:-$root/build/bin/lienewton-server}")"
[ -x "$server_bin" ] || { echo "run_attacks: no $server_bin (build the lienewton-server target)"; exit 1; }
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])')
log=$(mktemp -d)
pid=""
cleanup() { [ -n "$pid" ] && kill "$pid" 2>/dev/null; wait 2>/dev/null; rm -rf "$log"; }
trap cleanup EXIT
if [ "$mode" = nginx ]; then
  LIENEWTON_REQUEST_TIMEOUT=3 LIENEWTON_SWEEP_TIMEOUT=3 "$root/deploy/run_local.sh" --port "$port" --replicas 2 --server-bin "$server_bin" \
    >"$log/front.log" 2>&1 &
else
  # LIENEWTON_ATTACK_STACK_KIB: the server's stack limit (its threads' too), e.g. 1024: no program may need more.
  (if [ -n "${LIENEWTON_ATTACK_STACK_KIB:-}" ]; then ulimit -s "$LIENEWTON_ATTACK_STACK_KIB"; fi
   exec "$server_bin" --host 127.0.0.1 --port "$port" --request-timeout 3 --sweep-timeout 3 --web-root "$root/web") \
    >"$log/server.log" 2>&1 &
fi
pid=$!
for _ in $(seq 100); do curl -sf -m 1 "http://127.0.0.1:$port/livez" >/dev/null && break; sleep 0.1; done
curl -sf -m 2 "http://127.0.0.1:$port/livez" >/dev/null || { cat "$log"/*.log; echo "run_attacks: no /livez"; exit 1; }
set +e
timeout 300 python3 "$root/tests/attack/attacks.py" --base "http://127.0.0.1:$port" --mode "$mode" ${ATTACK_ONLY:+--only "$ATTACK_ONLY"} \
  --server-bin "$server_bin"
rc=$?
set -e
[ "$rc" -ne 0 ] && tail -n 30 "$log"/*.log
exit "$rc"
