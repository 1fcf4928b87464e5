#!/usr/bin/env bash
# Installs what is missing for lienewton. Shared by scripts/run.sh, scripts/test.sh, .ci/run and the
# Dockerfile so that they cannot drift apart.
#   scripts/deps.sh build   Debian packages to build and run the service
#   scripts/deps.sh test    the above plus what the test suite needs (Chromium, nginx, npm packages)
#   scripts/deps.sh fuzz    build packages plus clang and its libFuzzer runtime (scripts/test.sh --sanitize)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
what="${1:-build}"

package_list() { grep -v '^\s*#' "$here/packages-$1.txt" | grep -v '^\s*$'; }

missing=()
lists=(build)
[ "$what" = build ] || lists+=("$what")
for list in "${lists[@]}"; do
  while read -r pkg; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
  done < <(package_list "$list")
done
if [ "$what" = test ] && ! command -v npm >/dev/null; then missing+=(nodejs npm); fi

if [ "${#missing[@]}" -gt 0 ]; then
  echo "deps: installing ${missing[*]}"
  sudo_cmd=""; [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

if [ "$what" = test ] && [ -f "$here/../package-lock.json" ]; then
  (cd "$here/.." && npm ci --no-audit --no-fund --loglevel=error)
fi
