#!/usr/bin/env bash
# Benchmarks (make bench): plan the source's structures and larger ones with
# every backend and print a table of wall-clock times, tests and memory.
# Timings live here, never in the tests. Usage: bench/run.sh BUILD_DIR [OUT.md]
set -euo pipefail
B=${1:-build}
OUT=${2:-bench/results/latest.md}
CLI=$B/unstack
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
LIMIT=${BENCH_TIME_LIMIT:-300}

$CLI generate pyramid --rows 13 -o "$W/pyramid91.json" >/dev/null
$CLI generate column --blocks 1000 -o "$W/column1000.json" >/dev/null
$CLI generate wall --rows 25 --cols 40 -o "$W/wall1012.json" >/dev/null
$CLI generate wall --rows 20 --cols 20 -o "$W/wall400.json" >/dev/null
$CLI generate wall --rows 30 --cols 30 -o "$W/wall915.json" >/dev/null
$CLI generate wall --rows 30 --cols 30 --friction 0 -o "$W/wall915f0.json" >/dev/null
$CLI generate arch --voussoirs 15 -o "$W/arch15.json" >/dev/null

row() { # STRUCTURE METHOD [extra plan args]
  local name=$1 m=$2
  shift 2
  local line rss
  line=$( { /usr/bin/time -f "RSS %M" "$CLI" plan "$W/$name.json" --method "$m" --time-limit "$LIMIT" \
            --stats "$@" -o "$W/plan.json" || true; } 2>&1)
  local summary tests solve total
  summary=$(echo "$line" | head -1)
  tests=$(echo "$line" | sed -n 's/^  tests \([0-9]*\).*/\1/p')
  total=$(echo "$line" | sed -n 's/.*time: total \([0-9.]*\) s.*/\1/p')
  solve=$(echo "$line" | sed -n 's/.*in solver \([0-9.]*\) s.*/\1/p')
  rss=$(echo "$line" | sed -n 's/^RSS \([0-9]*\)/\1/p')
  local fb
  fb=$(echo "$line" | sed -n 's/.*LP fallbacks \([0-9]*\) (re-seeded \([0-9]*\), LCP skipped \([0-9]*\)).*/\1 (\3 skipped)/p')
  local per
  per=$(awk -v s="$solve" -v t="$tests" 'BEGIN{ if (t > 0) printf "%.3f", 1000 * s / t; else print "-" }')
  printf '| %s | %s %s | %s | %s | %s | %s | %s | %s |\n' "$name" "$m" "$*" "${summary%%,*}" "$tests" "$total" "$per" \
    "${fb:--}" "$((rss / 1024))" | tee -a "$OUT.tmp"
}

{
  echo "# unstack benchmarks"
  echo
  echo "$(date -u +%Y-%m-%d), $(uname -m), $(nproc) cores; $(gcc --version | head -1); Release build."
  echo
  echo "| structure | method | result | tests | total s | solver ms/test | LP fallbacks | max RSS MiB |"
  echo "|---|---|---|---|---|---|---|---|"
} >"$OUT.tmp"
cat "$OUT.tmp"
# the source's Table 2 structure, every backend: the default assemble
# search, and the source's DFS in both directions
for m in lpsolve lp lcp lcp-reuse; do row pyramid91 $m; done
for d in down up; do
  for m in lpsolve lp lcp lcp-reuse; do row pyramid91 $m --search dfs --direction $d; done
done
row column1000 lp
row column1000 lcp-reuse
row column1000 lpsolve --max-tests 100
row column1000 lcp --max-tests 100
row wall1012 lp
row wall1012 lpsolve --max-tests 40
row wall1012 lcp-reuse
row wall1012 lcp --max-tests 3
row wall400 lp
row wall400 lcp-reuse
row wall400 lcp --max-tests 5
row wall400 lpsolve --max-tests 40
# 30 x 30: the scratch LCP reaches its pivot limit; lcp-reuse goes on from
# the LP's forces (frictionless: reuses every test; with friction: backs off)
row wall915 lp
row wall915 lcp-reuse
row wall915f0 lcp-reuse
row arch15 lp
row arch15 lcp-reuse
for b in "$B"/bench_*; do
  [ -x "$b" ] || continue
  printf '\n## %s\n\n```\n' "$(basename "$b")" >>"$OUT.tmp"
  "$b" 2>&1 | tee -a "$OUT.tmp"
  printf '```\n' >>"$OUT.tmp"
done
mv "$OUT.tmp" "$OUT"
echo "wrote $OUT"
