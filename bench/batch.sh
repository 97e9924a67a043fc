#!/usr/bin/env bash
# unstack batch (docs/batch.md): 400 small structures (the random stacker,
# 8 rows on 5 blocks, about 20 blocks each) planned by batch with 1 and 2
# jobs, by mpirun -n 3 (2 working ranks) when this build has MPI, and by
# one `unstack plan` process per file (one after another, and two at a
# time with xargs -P 2); then a large labelled set (BATCH_BIG files,
# 100,000 by default, 2,000 with QUICK=1; hard links to the 400) with 2 jobs: inputs per second
# and the extrapolated time for a million. Wall and CPU seconds, best of
# BATCH_REPS runs (3). Writes OUT/batch-TAG.csv and prints a markdown table.
# BATCH_GEN picks the 400 (default "random --rows 8 --width 5"; e.g.
# "random", "random --rows 12 --width 4", "stacker --rows 6 --width 6").
# Usage: bench/batch.sh BUILD_DIR OUT TAG   (env QUICK=1, BATCH_BIG=n, BATCH_REPS=n, BATCH_GEN=...)
set -uo pipefail
B=$1 OUT=$2 TAG=$3
CLI=$(cd "$(dirname "$B/unstack")" && pwd)/unstack
QUICK=${QUICK:-0}
BIG=${BATCH_BIG:-$([ "$QUICK" = 1 ] && echo 2000 || echo 100000)}
REPS=${BATCH_REPS:-3}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
export OPENBLAS_NUM_THREADS=1
CSV=$OUT/batch-$TAG.csv
echo "run,inputs,wall_s,cpu_s,per_s" >"$CSV"

# timed NAME N command...: best wall of REPS runs (with that run's CPU:
# user + sys of the command and its children), into the CSV
timed() {
  local name=$1 n=$2 best="" cpu="" r
  shift 2
  for ((r = 0; r < REPS; r++)); do
    /usr/bin/time -f "%e %U %S" -o "$W/t" "$@" >/dev/null 2>&1
    read -r wall u s < <(tail -n 1 "$W/t") # after "Command exited with non-zero status"
    if [ -z "$best" ] || awk "BEGIN{exit !($wall < $best)}"; then
      best=$wall cpu=$(awk "BEGIN{print $u + $s}"); fi
  done
  echo "$name,$n,$best,$cpu,$(awk "BEGIN{printf \"%.1f\", $n / ($best > 0 ? $best : 0.01)}")" >>"$CSV"
}

GEN=${BATCH_GEN:-random --rows 8 --width 5}
# shellcheck disable=SC2086 # the generator's kind and options, split
"$CLI" generate $GEN --count 400 -o "$W/s400/" >/dev/null
timed "batch --jobs 1" 400 "$CLI" batch "$W/s400" -o "$W/o1.jsonl" --jobs 1
timed "batch --jobs 2" 400 "$CLI" batch "$W/s400" -o "$W/o2.jsonl" --jobs 2
if "$CLI" --version | grep -q '^mpi: yes' && command -v mpirun >/dev/null; then
  asroot=""
  [ "$(id -u)" -eq 0 ] && asroot=--allow-run-as-root
  timed "mpirun -n 3 batch" 400 mpirun -n 3 $asroot --oversubscribe "$CLI" batch "$W/s400" -o "$W/om.jsonl"
fi
ls "$W"/s400/*.json >"$W/list"
timed "plan per file" 400 bash -c 'while read -r f; do "$0" plan "$f"; done <"$1"' "$CLI" "$W/list"
timed "plan per file xargs -P 2" 400 xargs -a "$W/list" -P 2 -n 1 "$CLI" plan

# the large set: the 400 structures again and again as hard links (the
# random stacker needs about 10 ms a structure to generate; labelling
# does the same work on a copy), labelled once with 2 jobs
python3 -c '
import os, sys
src, dst, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
os.makedirs(dst)
names = sorted(f for f in os.listdir(src) if f.endswith(".json"))
for i in range(n):
    os.link("%s/%s" % (src, names[i % len(names)]), "%s/s%07d.json" % (dst, i))
' "$W/s400" "$W/big" "$BIG"
REPS=1 timed "batch --jobs 2 large set" "$BIG" "$CLI" batch "$W/big" -o "$W/big.jsonl" --jobs 2
lines=$(wc -l <"$W/big.jsonl")

col() { awk -F, -v r="$1" -v c="$2" '$1 == r {print $c}' "$CSV"; }
ratio() { awk "BEGIN{a = $1; b = $2; printf \"%.2f\", (b > 0 ? a / b : 0)}"; }
echo "| run | inputs | wall s | CPU s | inputs/s |"
echo "|---|---|---|---|---|"
tail -n +2 "$CSV" | awk -F, '{printf "| %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5}'
echo ""
echo "- 2 jobs vs 1 (wall): $(ratio "$(col 'batch --jobs 1' 3)" "$(col 'batch --jobs 2' 3)")x"
echo "- batch --jobs 1 vs one plan process per file (wall): $(ratio "$(col 'plan per file' 3)" "$(col 'batch --jobs 1' 3)")x, (CPU): $(ratio "$(col 'plan per file' 4)" "$(col 'batch --jobs 1' 4)")x"
echo "- batch --jobs 2 vs one plan process per file (wall, issue 25's 15x): $(ratio "$(col 'plan per file' 3)" "$(col 'batch --jobs 2' 3)")x"
echo "- batch --jobs 2 vs two plan processes at a time (wall): $(ratio "$(col 'plan per file xargs -P 2' 3)" "$(col 'batch --jobs 2' 3)")x"
big_s=$(col 'batch --jobs 2 large set' 3)
echo "- large set: $lines lines for $BIG structures (hard links to the 400), $(col 'batch --jobs 2 large set' 5) inputs/s; a million at that rate: $(awk "BEGIN{printf \"%.0f\", 1e6 / $BIG * $big_s}") s (extrapolated)"
echo "- inputs: generate $GEN --count 400"
echo "- machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg) at the end"
