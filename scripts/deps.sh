#!/usr/bin/env bash
# Install the Debian 12 packages unstack needs, only when some are missing.
# usage: deps.sh [fuzz]
set -euo pipefail
pkgs=(build-essential cmake pkg-config coinor-libclp-dev coinor-libcbc-dev liblpsolve55-dev
      libsuitesparse-dev
      libjansson-dev libxml2-dev libcairo2-dev libassimp-dev libsiconos-numerics-dev python3
      python3-dev python3-pytest libopenmpi-dev openmpi-bin
      groff-base) # groff-base: the man page's check (tests/cli/manpage.sh)
# `deps.sh fuzz` (make fuzz): also clang with libFuzzer and its sanitizers
[ "${1:-}" = fuzz ] && pkgs+=(clang libclang-rt-14-dev)
# `deps.sh demo` (make demo): what building the tool needs, without the
# packages only the tests use (below: the browser test's too)
test_only=" libsiconos-numerics-dev python3 python3-pytest groff-base libopenmpi-dev openmpi-bin "
missing=()
for p in "${pkgs[@]}"; do
  [ "${1:-}" = demo ] && [[ $test_only == *" $p "* ]] && continue
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# The browser test of the HTML viewer (tests/browser): Debian's chromium,
# and node with npm for playwright-core. Node and npm are judged by their
# commands: a node from another source (nodesource) bundles npm, and
# Debian's npm package would conflict with it.
if [ "${1:-}" != demo ]; then
  command -v chromium >/dev/null 2>&1 || missing+=(chromium)
  command -v node >/dev/null 2>&1 || missing+=(nodejs)
  command -v npm >/dev/null 2>&1 || missing+=(npm)
fi
[ ${#missing[@]} -eq 0 ] && exit 0
echo "installing: ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
