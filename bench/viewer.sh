#!/usr/bin/env bash
# The HTML viewer's load and slider times on a big wall (issue 24 point 15;
# targets: load under 2 s, a slider move under 100 ms). Not a test: it
# prints timings. Makes a running-bond wall of ROWS x COLS (default 100 x
# 100: 10,050 blocks), plans it (--certificates with CERTS=1, so the page
# carries every step's forces), renders the page and opens it in headless
# Chromium through playwright-core (installed by the browser test into
# BUILD/browser; bench/viewer.js).
# Usage: bench/viewer.sh BUILD_DIR [ROWS COLS]   (env CERTS=1, US_CHROMIUM)
set -euo pipefail
B=${1:-build}
ROWS=${2:-100}
COLS=${3:-100}
CLI=$B/unstack
PW=$B/browser
CHROME=${US_CHROMIUM:-/usr/bin/chromium}
[ -f "$PW/node_modules/playwright-core/package.json" ] ||
  { echo "run 'ctest -L browser' once first (it installs playwright-core into $PW)"; exit 2; }
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
"$CLI" generate wall --rows "$ROWS" --cols "$COLS" -o "$W/wall.json"
certs=$([ "${CERTS:-0}" = 1 ] && echo --certificates || true)
t0=$(date +%s.%N)
"$CLI" plan "$W/wall.json" $certs -o "$W/plan.json" >/dev/null
t1=$(date +%s.%N)
"$CLI" render "$W/wall.json" --plan "$W/plan.json" --html -o "$W/wall.html"
t2=$(date +%s.%N)
echo "plan $(echo "$t1 - $t0" | bc) s, render --html $(echo "$t2 - $t1" | bc) s, page $(du -k "$W/wall.html" | cut -f1) kB"
node "$(dirname "$0")/viewer.js" "$PW" "$CHROME" "$W/wall.html" 20
