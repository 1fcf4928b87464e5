#!/usr/bin/env bash
# Writes DIR/nginx.conf (a self-contained nginx main config whose pid, logs and temp files stay in DIR) and
# DIR/lienewton.conf: the shipped deploy/nginx/lienewton.conf with its listen address and upstream servers
# replaced, and /metrics allowed from the addresses in LIENEWTON_METRICS_ALLOW (space-separated addresses or
# CIDR ranges; default: the shipped loopback 127.0.0.1 and ::1). Used by deploy/run_local.sh and by the
# container's entrypoint.
#   deploy/nginx/make_conf.sh DIR LISTEN UPSTREAM...      e.g. make_conf.sh /tmp/x 127.0.0.1:8080 127.0.0.1:8081
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
dir=$1 listen=$2
shift 2
upstreams=""
for u in "$@"; do upstreams+="    server $u max_fails=3 fail_timeout=5s;\n"; done
allowed=""
for a in ${LIENEWTON_METRICS_ALLOW:-127.0.0.1 ::1}; do
  [[ $a =~ ^[0-9A-Fa-f.:/]+$ ]] || { echo "make_conf: LIENEWTON_METRICS_ALLOW: not an address: $a" >&2; exit 2; }
  allowed+="        allow $a;\n"
done
sed -e "s/^\(\s*listen\) [^;]*;/\1 $listen;/" \
    -e "/^\s*server 127\.0\.0\.1:[0-9]*.*;/d" \
    -e "s/^\(\s*least_conn;.*\)$/\1\n$upstreams/" \
    -e "/^\s*allow .*;/d" \
    -e "s|^\(\s*\)deny all;|$allowed\1deny all;|" \
    "$here/lienewton.conf" >"$dir/lienewton.conf"
cat >"$dir/nginx.conf" <<CONF
daemon off;
worker_processes 2;
pid $dir/nginx.pid;
error_log $dir/error.log warn;
events { worker_connections 4096; }
http {
  access_log off;
  client_body_temp_path $dir/client_body;
  proxy_temp_path $dir/proxy;
  fastcgi_temp_path $dir/fastcgi;
  uwsgi_temp_path $dir/uwsgi;
  scgi_temp_path $dir/scgi;
  include $dir/lienewton.conf;
}
CONF
