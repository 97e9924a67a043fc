#!/usr/bin/env bash
# The HTML plan viewer in a real browser (ctest browser.viewer; docs/viewer.md).
# usage: run.sh CLI WORK_DIR
# Makes structures, plans and pages with the built CLI in WORK_DIR, then
# opens them in Debian's headless Chromium through playwright-core
# (viewer.test.js, viewer3d.test.js for 3D). playwright-core is installed with `npm ci` into WORK_DIR
# from this directory's package-lock.json when missing or when the lock
# file changed. Screenshots: WORK_DIR/shots. A missing or broken Chromium,
# node or npm is a failure, never a skip.
set -uo pipefail
CLI=$1
W=$2
HERE=$(cd "$(dirname "$0")" && pwd)
die() { echo "FAIL $*"; exit 1; }
mkdir -p "$W" || die "cannot create $W"

# ---- the tools
CHROME=${US_CHROMIUM:-/usr/bin/chromium}
[ -x "$CHROME" ] || die "Chromium not found at $CHROME (scripts/deps.sh installs Debian's chromium)"
command -v node >/dev/null || die "node not found (scripts/deps.sh installs nodejs)"
if [ ! -f "$W/node_modules/playwright-core/package.json" ] ||
   ! cmp -s "$HERE/package-lock.json" "$W/package-lock.json"; then
  command -v npm >/dev/null || die "npm not found (scripts/deps.sh installs npm)"
  cp "$HERE/package.json" "$HERE/package-lock.json" "$W/" || die "cannot copy the npm manifests"
  echo "npm ci in $W"
  (cd "$W" && npm ci --ignore-scripts --no-audit --no-fund --loglevel=error) ||
    die "npm ci failed: playwright-core could not be installed (is the npm registry reachable?)"
fi

# ---- the pages
run() { "$@" >"$W/cmd.log" 2>&1 || { cat "$W/cmd.log"; die "command failed: $*"; }; }
run "$CLI" generate pyramid --rows 5 -o "$W/pyramid.json"
run "$CLI" plan "$W/pyramid.json" --certificates -o "$W/pyramid-plan.json"
run "$CLI" render "$W/pyramid.json" --plan "$W/pyramid-plan.json" --html -o "$W/pyramid.html"

# the pyramid's plan with its first certificate force made negative
sed -E '0,/"force": \[[^,]*,/s//"force": [-1000,/' "$W/pyramid-plan.json" >"$W/pyramid-neg-plan.json"
run "$CLI" render "$W/pyramid.json" --plan "$W/pyramid-neg-plan.json" --html -o "$W/pyramid-neg.html"

# an arch that cannot be taken apart one block at a time (plan status none)
run "$CLI" generate arch --voussoirs 7 --loose 30 -o "$W/arch.json"
"$CLI" plan "$W/arch.json" -o "$W/arch-plan.json" >"$W/cmd.log" 2>&1
[ $? -eq 1 ] || { cat "$W/cmd.log"; die "the arch's plan should be none (exit 1)"; }
run "$CLI" render "$W/arch.json" --plan "$W/arch-plan.json" --html -o "$W/arch.html"

# the same arch without loose blocks, planned with hands (--hands auto)
run "$CLI" generate arch --voussoirs 7 -o "$W/arch-hands.json"
run "$CLI" plan "$W/arch-hands.json" --hands auto -o "$W/arch-hands-plan.json"
run "$CLI" render "$W/arch-hands.json" --plan "$W/arch-hands-plan.json" --html -o "$W/arch-hands.html"

# a column of three taken apart from the bottom: verify fails after step 1
cat >"$W/column-bad.json" <<'JSON'
{"dimension": 2, "ground": true, "bodies": [
  {"id": "bottom", "polygon": [[0, 0], [1, 0], [1, 1], [0, 1]]},
  {"id": "middle", "polygon": [[0, 1], [1, 1], [1, 2], [0, 2]]},
  {"id": "top", "polygon": [[0, 2], [1, 2], [1, 3], [0, 3]]}]}
JSON
cat >"$W/column-bad-plan.json" <<'JSON'
{"format": "unstack-plan", "version": 1, "status": "found", "order": ["bottom", "middle", "top"]}
JSON
"$CLI" render "$W/column-bad.json" --plan "$W/column-bad-plan.json" -o "$W/column-bad.html" \
  >"$W/cmd.log" 2>&1
rc=$?
[ $rc -eq 1 ] || { cat "$W/cmd.log"; die "render of an invalid plan: exit $rc, wanted 1"; }

# ids that try to end the data's script element or start markup
cat >"$W/ids.json" <<'JSON'
{"dimension": 2, "ground": true, "bodies": [
  {"id": "</script><script>window.pwned=1</script>", "polygon": [[0, 0], [1, 0], [1, 1], [0, 1]]},
  {"id": "<!-- \"q\" & 'a' </SCRIPT >", "polygon": [[0, 1], [1, 1], [1, 2], [0, 2]]},
  {"id": "\u2028<b>bold</b>\\", "polygon": [[0, 2], [1, 2], [1, 3], [0, 3]]}]}
JSON
run "$CLI" plan "$W/ids.json" --certificates -o "$W/ids-plan.json"
run "$CLI" render "$W/ids.json" --plan "$W/ids-plan.json" --html -o "$W/ids.html"

# 3D (viewer3d.test.js): a pyramid of 14 boxes with a plan with
# certificates, the same with one certificate force made negative, planned
# with hands, and a tower of 3 taken apart from the bottom (verify fails)
run "$CLI" generate pyramid3d --rows 3 -o "$W/pyr3.json"
run "$CLI" plan "$W/pyr3.json" --certificates -o "$W/pyr3-plan.json"
run "$CLI" render "$W/pyr3.json" --plan "$W/pyr3-plan.json" --html -o "$W/pyr3.html"
sed -E '0,/"force": \[[^,]*,/s//"force": [-1000,/' "$W/pyr3-plan.json" >"$W/pyr3-neg-plan.json"
run "$CLI" render "$W/pyr3.json" --plan "$W/pyr3-neg-plan.json" --html -o "$W/pyr3-neg.html"
run "$CLI" plan "$W/pyr3.json" --hands auto -o "$W/pyr3-hands-plan.json"
run "$CLI" render "$W/pyr3.json" --plan "$W/pyr3-hands-plan.json" --html -o "$W/pyr3-hands.html"
run "$CLI" generate tower --blocks 3 -o "$W/tower3.json"
set -- $(grep -o '"id": "[^"]*"' "$W/tower3.json" | cut -d'"' -f4)
printf '{"status": "found", "order": ["%s", "%s", "%s"]}\n' "$1" "$2" "$3" >"$W/tower3-bad-plan.json"
"$CLI" render "$W/tower3.json" --plan "$W/tower3-bad-plan.json" -o "$W/tower3-bad.html" >"$W/cmd.log" 2>&1
rc=$?
[ $rc -eq 1 ] || { cat "$W/cmd.log"; die "render of an invalid 3D plan: exit $rc, wanted 1"; }

# ---- the browser: the 2D pages, then the 3D ones
node "$HERE/viewer.test.js" "$W" "$CHROME" "$W"
rc2=$?
node "$HERE/viewer3d.test.js" "$W" "$CHROME" "$W"
rc3=$?
[ $rc2 -eq 0 ] && [ $rc3 -eq 0 ]
