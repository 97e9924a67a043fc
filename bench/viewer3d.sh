#!/usr/bin/env bash
# The 3D viewer's page size, load and redraw times (issue 22 point 4; not a
# test: it prints figures). Makes a 3D pyramid of ROWS courses (default 6:
# 91 boxes) planned with --certificates, and a dome of COURSES x SEGMENTS
# voussoirs (default 10 x 12 = 120) shown with the full structure's forces
# (--forces) and with its plan (status none: the buildable part taken
# apart), renders the pages and times them in headless Chromium with
# bench/viewer.js (load to the page's ready mark; a slider move redraws the
# canvas synchronously in its handler: the whole 3D frame, faces culled,
# projected and sorted, as an orbit step does).
# Usage: bench/viewer3d.sh BUILD_DIR [ROWS COURSES SEGMENTS]   (env US_CHROMIUM)
set -euo pipefail
B=${1:-build}
ROWS=${2:-6}
COURSES=${3:-10}
SEGMENTS=${4:-12}
CLI=$B/unstack
PW=$B/browser
CHROME=${US_CHROMIUM:-/usr/bin/chromium}
[ -f "$PW/node_modules/playwright-core/package.json" ] ||
  { echo "run 'ctest -L browser' once first (it installs playwright-core into $PW)"; exit 2; }
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
page() { # NAME RENDER-ARGS...: render, print the time and size, time it in the browser
  local name=$1; shift
  local t0 t1
  t0=$(date +%s.%N)
  "$CLI" render "$@" --html -o "$W/$name.html" >/dev/null 2>&1 || [ $? -eq 1 ]
  t1=$(date +%s.%N)
  echo "$name: render --html $(echo "$t1 - $t0" | bc) s, page $(du -k "$W/$name.html" | cut -f1) kB"
  node "$(dirname "$0")/viewer.js" "$PW" "$CHROME" "$W/$name.html" 20
}
"$CLI" generate pyramid3d --rows "$ROWS" -o "$W/pyr.json" >/dev/null
"$CLI" plan "$W/pyr.json" --certificates -o "$W/pyr-plan.json" >/dev/null
"$CLI" plan "$W/pyr.json" -o "$W/pyr-plain.json" >/dev/null
page pyramid3d-certs "$W/pyr.json" --plan "$W/pyr-plan.json"
page pyramid3d-plain "$W/pyr.json" --plan "$W/pyr-plain.json"
"$CLI" generate dome --courses "$COURSES" --segments "$SEGMENTS" -o "$W/dome.json" >/dev/null
"$CLI" plan "$W/dome.json" -o "$W/dome-plan.json" >/dev/null 2>&1 || true
page dome-forces "$W/dome.json" --forces
page dome-plan "$W/dome.json" --plan "$W/dome-plan.json"
