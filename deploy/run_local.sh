#!/usr/bin/env bash
# Runs the shipped deployment on loopback: N lienewton-server replicas behind nginx with
# deploy/nginx/lienewton.conf (only the listen and upstream ports rewritten). Stays in the foreground; Ctrl-C
# (or SIGTERM) stops nginx and the replicas.
#   deploy/run_local.sh [--port 8080] [--replicas 3] [--server-bin build/bin/lienewton-server]
# The replicas read the usual LIENEWTON_* variables (e.g. LIENEWTON_REQUEST_TIMEOUT).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
port=8080 replicas=3 server_bin="$root/build/bin/lienewton-server"
while [ $# -gt 0 ]; do
  case "$1" in
    --port) port=$2; shift 2 ;;
    --replicas) replicas=$2; shift 2 ;;
    --server-bin) server_bin=$2; shift 2 ;;
    *) echo "usage: $0 [--port P] [--replicas N] [--server-bin PATH]"; exit 2 ;;
  esac
done
nginx_bin=$(command -v nginx || echo /usr/sbin/nginx)
[ -x "$nginx_bin" ] || { echo "run_local: nginx is not installed (apt-get install nginx)"; exit 1; }
[ -x "$server_bin" ] || { echo "run_local: no $server_bin (build lienewton-server first)"; exit 1; }

dir=$(mktemp -d)
chmod 755 "$dir"  # nginx's workers (user nobody) create their temp files below it
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$dir"
}
trap cleanup EXIT
trap 'exit 0' INT TERM

free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
upstreams=()
for i in $(seq "$replicas"); do
  p=$(free_port)
  # Every connection comes from nginx: its X-Real-IP names the client (long-work slots per client address).
  "$server_bin" --host 127.0.0.1 --port "$p" --web-root "$root/web" --trusted-front 127.0.0.1 \
    >"$dir/replica-$i.log" 2>&1 &
  pids+=($!)
  upstreams+=("127.0.0.1:$p")
  echo "run_local: replica $i on 127.0.0.1:$p (log $dir/replica-$i.log)"
done
"$root/deploy/nginx/make_conf.sh" "$dir" "127.0.0.1:$port" "${upstreams[@]}"
"$nginx_bin" -t -q -e "$dir/error.log" -p "$dir" -c "$dir/nginx.conf"
echo "run_local: nginx on http://127.0.0.1:$port/ in front of $replicas replicas (config $dir/lienewton.conf)"
"$nginx_bin" -e "$dir/error.log" -p "$dir" -c "$dir/nginx.conf" &
pids+=($!)
wait -n "${pids[@]}"
echo "run_local: a process exited; stopping"
tail -n 20 "$dir"/*.log
exit 1
