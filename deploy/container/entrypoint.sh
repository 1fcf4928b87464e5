#!/usr/bin/env bash
# The image's command, under tini: nginx on 0.0.0.0:$LIENEWTON_PORT (8080) in front of one lienewton-server on
# 127.0.0.1:$LIENEWTON_BACKEND_PORT (8081), the supported deployment (deploy/nginx/lienewton.conf) in one
# container. SIGTERM (or SIGINT) drains both: the server finishes or ends its open work within its shutdown
# grace while nginx stops accepting and lets the requests in flight finish; then both exit. If either exits on
# its own, the other is stopped and the container exits with the server's status.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
port=${LIENEWTON_PORT:-8080}
backend=${LIENEWTON_BACKEND_PORT:-8081}
run=$(mktemp -d)
"$here/../nginx/make_conf.sh" "$run" "0.0.0.0:$port" "127.0.0.1:$backend" || exit 1
LIENEWTON_HOST=127.0.0.1 LIENEWTON_PORT=$backend LIENEWTON_TRUSTED_FRONT=127.0.0.1 "$here/lienewton-server" "$@" &
server=$!
nginx -e "$run/error.log" -p "$run" -c "$run/nginx.conf" &
front=$!
stop() {
  kill -TERM "$server" 2>/dev/null
  kill -QUIT "$front" 2>/dev/null  # graceful: in-flight requests finish
}
trap stop TERM INT
wait -n "$server" "$front"  # a child exited, or a signal interrupted the wait (the trap has run)
stop
wait "$server"
rc=$?
wait "$front"
exit "$rc"
