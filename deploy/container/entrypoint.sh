#!/usr/bin/env bash
# The image's command, under tini: nginx on $LIENEWTON_HOST:$LIENEWTON_PORT (0.0.0.0:8080) in front of one
# lienewton-server on 127.0.0.1:$LIENEWTON_BACKEND_PORT (8081), the supported deployment
# (deploy/nginx/lienewton.conf) in one container. /metrics is served to the addresses in
# LIENEWTON_METRICS_ALLOW (default loopback only).
#
# A server killed by a signal (a crash, the kernel's OOM killer) is started again, after 1 s, doubling up to
# 16 s while it keeps dying within 30 s of its start; meanwhile nginx answers 502 in the service's JSON
# format. A server that exits by itself (status 0 after draining, 1 cannot listen, 2 bad flags) ends the
# container with its status, and so does nginx exiting.
# SIGTERM (or SIGINT) drains both: the server finishes or ends its open work within its shutdown grace while
# nginx stops accepting and lets the requests in flight finish; then both exit.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
host=${LIENEWTON_HOST:-0.0.0.0}
port=${LIENEWTON_PORT:-8080}
backend=${LIENEWTON_BACKEND_PORT:-8081}
run=$(mktemp -d)
chmod 755 "$run"  # when started as root, nginx's workers (user nobody) create their temp files below it
"$here/../nginx/make_conf.sh" "$run" "$host:$port" "127.0.0.1:$backend" || exit 1

log() { echo "entrypoint: $*" >&2; }
start_server() {
  LIENEWTON_HOST=127.0.0.1 LIENEWTON_PORT=$backend LIENEWTON_TRUSTED_FRONT=127.0.0.1 "$here/lienewton-server" "$@" &
  server=$! alive=1 started=$SECONDS
}
stop() {
  [ "$alive" = 1 ] && kill -TERM "$server" 2>/dev/null
  kill -QUIT "$front" 2>/dev/null  # graceful: in-flight requests finish
}
asked=0 alive=0 front=""
trap 'asked=1; stop' TERM INT

start_server "$@"
nginx -e "$run/error.log" -p "$run" -c "$run/nginx.conf" &
front=$!
delay=1 rc=0
while [ "$asked" = 0 ]; do
  ended=""
  wait -n -p ended "$server" "$front"  # a child exited, or a signal interrupted the wait (the trap has run)
  status=$?
  [ "$asked" = 1 ] && break
  if [ "$ended" = "$front" ]; then
    log "nginx exited with status $status; stopping"
    break
  fi
  alive=0 rc=$status
  if [ "$rc" -le 128 ]; then
    log "lienewton-server exited with status $rc; stopping"
    break
  fi
  [ $((SECONDS - started)) -ge 30 ] && delay=1
  log "lienewton-server ended by signal $((rc - 128)); starting it again in $delay s"
  sleep "$delay" &
  wait $!  # a SIGTERM meanwhile runs the trap and ends this wait
  if [ "$asked" = 1 ]; then
    kill "$!" 2>/dev/null
    rc=0
    break
  fi
  start_server "$@"
  delay=$((delay < 16 ? delay * 2 : 16))
done
stop
if [ "$alive" = 1 ]; then
  wait "$server"
  rc=$?
fi
wait "$front"
exit "$rc"
