#!/usr/bin/env bash
# Checks that the Dockerfile's runtime stage installs exactly the Debian packages that provide the shared
# libraries lienewton and lienewton-server are linked against (NEEDED entries, resolved with ldd) and the one the
# renderer opens when it first draws (OSMesa, found by the build), minus what
# debian:bookworm-slim already has. CI: scripts/check_runtime_libs.sh [build-dir]   (exit 1 on a mismatch)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
base_image_packages="libc6 libstdc++6 libgcc-s1"
declared="$(sed -n 's/^ARG RUNTIME_LIBS="\(.*\)"$/\1/p' "$root/Dockerfile" | tr ' ' '\n' | sort -u)"
[ -n "$declared" ] || { echo "check_runtime_libs: no ARG RUNTIME_LIBS line in the Dockerfile" >&2; exit 1; }
needed=""
for bin in "$build/bin/lienewton" "$build/bin/lienewton-server"; do
  [ -x "$bin" ] || { echo "check_runtime_libs: build $bin first" >&2; exit 1; }
  if ldd "$bin" | grep -q "not found"; then ldd "$bin" | grep "not found" >&2; exit 1; fi
  for lib in $(readelf -d "$bin" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p'); do
    case "$lib" in ld-linux*) continue ;; esac  # the dynamic loader: libc6's, named by its path in ldd's list
    path="$(ldd "$bin" | awk -v l="$lib" '$1 == l { print $3 }')"
    [ -n "$path" ] || { echo "check_runtime_libs: $lib of $bin does not resolve" >&2; exit 1; }
    pkg="$(dpkg -S "$path" 2>/dev/null || dpkg -S "$(readlink -f "$path")" 2>/dev/null || dpkg -S "/usr$path" 2>/dev/null || true)"
    pkg="${pkg%%:*}"
    [ -n "$pkg" ] || { echo "check_runtime_libs: no Debian package owns $path" >&2; exit 1; }
    needed+="$pkg"$'\n'
  done
done
# Opened at run time, not linked (render/osmesa_context.cpp): the library the build found, by its package.
opened="$(sed -n 's/^LIENEWTON_OSMESA_PATH:FILEPATH=//p' "$build/CMakeCache.txt")"
if [ -n "$opened" ]; then
  pkg="$(dpkg -S "$(readlink -f "$opened")" 2>/dev/null || true)"
  pkg="${pkg%%:*}"
  [ -n "$pkg" ] || { echo "check_runtime_libs: no Debian package owns $(readlink -f "$opened")" >&2; exit 1; }
  needed+="$pkg"$'\n'
fi
needed="$(echo "$needed" | grep -v '^$' | sort -u | grep -vxF -f <(tr ' ' '\n' <<<"$base_image_packages") || true)"
if [ "$needed" != "$declared" ]; then
  echo "check_runtime_libs: Dockerfile RUNTIME_LIBS does not match the binaries" >&2
  diff <(echo "$declared") <(echo "$needed") | sed 's/^</  only in Dockerfile:/; s/^>/  needed by ldd:     /' >&2 || true
  exit 1
fi
echo "check_runtime_libs: OK ($(echo $needed))"
