#!/usr/bin/env bash
# The hands workloads (plan --hands auto, docs/planning.md "Hands"): arches
# of 6 to 30 voussoirs and, in the full run, the default dome. Per row:
# the H found, whether it is proven minimal (hands_lower == hands), the
# tests, the plan's time, and verify's verdict on the plan. Writes
# OUT/hands-TAG.csv and prints a markdown table.
# Usage: bench/hands.sh BUILD_DIR OUT TAG   (env QUICK=1, BENCH_LIMIT=s)
set -uo pipefail
B=$1 OUT=$2 TAG=$3
CLI=$B/unstack
LIMIT=${BENCH_LIMIT:-120}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
CSV=$OUT/hands-$TAG.csv
echo "structure,bodies,status,hands,proven,tests,plan_s,verify" >"$CSV"

# row NAME FILE BODIES: plan --hands auto, then verify the plan
row() {
  local name=$1 f=$2 n=$3
  timeout $((LIMIT + 30)) "$CLI" plan "$f" --hands auto --stats -o "$W/p.json" >"$W/log" 2>&1
  local status tests total hands lower ver
  status=$(head -1 "$W/log" | sed 's/[:,].*//')
  tests=$(sed -n 's/^  tests \([0-9]*\).*/\1/p' "$W/log")
  total=$(sed -n 's/.*time: total \([0-9.]*\) s.*/\1/p' "$W/log")
  hands=$(sed -n 's/^  "hands": \([0-9]*\),/\1/p' "$W/p.json" 2>/dev/null)
  lower=$(sed -n 's/^  "hands_lower": \([0-9]*\),/\1/p' "$W/p.json" 2>/dev/null)
  ver=$("$CLI" verify "$f" "$W/p.json" 2>&1 | head -1 | sed 's/:.*//')
  local proven=no
  [ -n "$hands" ] && [ "$hands" = "$lower" ] && proven=yes
  echo "$name,$n,${status:-timeout},${hands:--},$proven,${tests:-0},${total:-nan},${ver:-error}" >>"$CSV"
}

sizes="6 7 8 10 12 16 20 24 30"
[ "${QUICK:-0}" = 1 ] && sizes="6 12 30"
for n in $sizes; do
  "$CLI" generate arch --voussoirs "$n" -o "$W/arch.json" >/dev/null
  row "arch $n" "$W/arch.json" "$n"
done
if [ "${QUICK:-0}" != 1 ]; then
  "$CLI" generate dome -o "$W/dome.json" >/dev/null
  row "dome (default)" "$W/dome.json" 120
fi
echo "| structure | bodies | status | H | proven minimal | tests | plan s | verify |"
echo "|---|---|---|---|---|---|---|---|"
tail -n +2 "$CSV" | awk -F, '{printf "| %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6, $7, $8}'
