#!/usr/bin/env bash
# A ccache store that builds inside containers reach over HTTP (ccache's http storage; nginx's WebDAV PUT), kept on
# this machine between CI runs: the fresh-debian stage builds from nothing in a throwaway container and the
# container stage in a Dockerfile, and without a shared cache each recompiled the whole tree (the fresh-debian stage
# alone took 45 of CI's 76 minutes). A developer's Release build that sets the variables `env` prints fills the
# store, so the CI run after it compiles only what changed since.
#   .ci/compile_cache.sh start   serves the store on 127.0.0.1 (idempotent), trims it to its size cap
#   .ci/compile_cache.sh env     the variables a build sets to read and fill the store (for eval or a command prefix)
#   .ci/compile_cache.sh stop
# A cache miss or an unreachable store only costs time: ccache compiles and goes on.
set -euo pipefail
store=${LIENEWTON_COMPILE_CACHE_DIR:-$HOME/.cache/lienewton-compile-cache}
port=${LIENEWTON_COMPILE_CACHE_PORT:-18731}
cap_mb=${LIENEWTON_COMPILE_CACHE_MB:-6000}
run_dir=$store.nginx

# A result is keyed by the compiler's mtime and size (a package's, the same in a fresh container of the same
# Debian) and by paths relative to CCACHE_BASEDIR (the source tree: /src in the container, the checkout here),
# never by the build folder, and by LANG (set; the LC_ variables are unset in .ci/run). Ninja on both sides: it
# compiles from the build folder, where make compiles from each subfolder (other relative paths, other keys).
# Reshare: a result this machine's own cache already held goes to the store too.
print_env() {
  echo "CCACHE_REMOTE_STORAGE=http://127.0.0.1:$port/ CCACHE_RESHARE=true CCACHE_NOHASHDIR=true" \
       "CMAKE_CXX_COMPILER_LAUNCHER=ccache CMAKE_GENERATOR=Ninja LANG=C.UTF-8"
}

trim() {  # oldest results first, until the store is under its cap
  local used_mb
  used_mb=$(du -sm "$store" | cut -f1)
  ((used_mb > cap_mb)) || return 0
  find "$store" -type f -printf '%T@ %s %p\n' | sort -n |
    awk -v excess=$(((used_mb - cap_mb * 3 / 4) * 1024 * 1024)) '{ if (freed >= excess) exit; freed += $2; print $3 }' |
    xargs -r rm -f
}

start() {
  mkdir -p "$store" "$run_dir"
  if [ "$(curl -s -o /dev/null -w '%{http_code}' "http://127.0.0.1:$port/" || true)" != 000 ]; then
    return 0  # already serving
  fi
  trim
  cat >"$run_dir/nginx.conf" <<EOF
user root root;
worker_processes 2;
pid $run_dir/nginx.pid;
error_log $run_dir/error.log warn;
events { worker_connections 256; }
http {
  access_log off;
  client_body_temp_path $run_dir/body;
  server {
    listen 127.0.0.1:$port;
    root $store;
    location / {
      dav_methods PUT DELETE;
      create_full_put_path on;
      client_max_body_size 512m;
    }
  }
}
EOF
  nginx -p "$run_dir" -c "$run_dir/nginx.conf"
}

stop() {
  [ -f "$run_dir/nginx.pid" ] && kill "$(cat "$run_dir/nginx.pid")" 2>/dev/null || true
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  env) print_env ;;
  *) echo "usage: $0 start|env|stop" >&2; exit 2 ;;
esac
