#!/usr/bin/env bash
# Whole commands at 100,000 blocks (issue 26): the 2 x 50,007 wall
# (100,015 blocks) and the 316 x 316 wall (100,014) checked, planned and
# verified; CPU (user + sys), wall seconds and peak memory, best CPU of
# LOAD_REPS runs (3). Loading (JSON, validation, contact detection) is
# most of check; plan and verify add the search. Writes OUT/load-TAG.csv
# and prints a markdown table.
# Usage: bench/load.sh BUILD_DIR OUT TAG   (env QUICK=1: the 2-row wall only)
set -uo pipefail
B=$1 OUT=$2 TAG=$3
CLI=$(cd "$(dirname "$B/unstack")" && pwd)/unstack
REPS=${LOAD_REPS:-3}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
CSV=$OUT/load-$TAG.csv
echo "wall,command,cpu_s,wall_s,peak_mb" >"$CSV"

# timed WALL NAME command...: the run of least CPU of REPS, into the CSV
timed() {
  local wall=$1 name=$2 best="" el="" mem="" r
  shift 2
  for ((r = 0; r < REPS; r++)); do
    /usr/bin/time -f "%e %U %S %M" -o "$W/t" "$@" >/dev/null 2>&1
    read -r e u s m < <(tail -n 1 "$W/t")
    c=$(awk "BEGIN{print $u + $s}")
    if [ -z "$best" ] || awk "BEGIN{exit !($c < $best)}"; then best=$c el=$e mem=$((m / 1024)); fi
  done
  echo "$wall,$name,$best,$el,$mem" >>"$CSV"
}

walls="2x50007"
[ "${QUICK:-0}" = 1 ] || walls="$walls 316x316"
for w in $walls; do
  "$CLI" generate wall --rows "${w%x*}" --cols "${w#*x}" -o "$W/w.json" >/dev/null
  timed "$w" check "$CLI" check "$W/w.json"
  timed "$w" plan "$CLI" plan "$W/w.json" -o "$W/p.json"
  timed "$w" verify "$CLI" verify "$W/w.json" "$W/p.json"
done
echo "| wall | command | CPU s | wall s | peak MB |"
echo "|---|---|---|---|---|"
tail -n +2 "$CSV" | awk -F, '{printf "| %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5}'
