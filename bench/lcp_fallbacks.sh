#!/usr/bin/env bash
# LP fallbacks of the LCP backends per workload (issue 10): for each
# workload, search and method, the plan's stability tests, how many of them
# the LP decided (us_StabilityInfo.lp_fallbacks, from --stats), their share,
# lcp-reuse's re-seeds and skipped friction LCPs (lcp_seeds, lcp_skips;
# issue 23) and the plan's time; and whether the plan's summary (removals, tests,
# unstable tests) is the one --method lp gives. Markdown on stdout.
# Workloads: the benchmark's Table 2 structures (random 10, columns 50 and
# 80, the stacker's random stacks, seeds 1-5 with seed 3 the benchmark's,
# pyramid 91) and walls 10 x 10 and 25 x 40, mu = 0.5 (the generators'
# default friction is 0.5 too, so both requests are the same files).
# Usage: bench/lcp_fallbacks.sh BUILD_DIR   (env LCPFB_LIMIT=s per plan,
# default 120; LCPFB_QUICK=1 leaves out the 25 x 40 wall)
set -uo pipefail
B=${1:-build}
CLI=$B/unstack
LIMIT=${LCPFB_LIMIT:-120}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
export OPENBLAS_NUM_THREADS=1

gen() { "$CLI" generate "$@" --friction 0.5 >/dev/null || echo "generate $* failed" >&2; }
gen random --rows 6 --width 4 --seed 2 -o "$W/random10.json"
gen column --blocks 50 -o "$W/column50.json"
gen column --blocks 80 -o "$W/column80.json"
for s in 1 2 3 4 5; do gen stacker --rows 15 --width 12 --seed "$s" -o "$W/random84-s$s.json"; done
gen pyramid --rows 13 -o "$W/pyramid91.json"
gen wall --rows 10 --cols 10 -o "$W/wall10x10.json"
workloads="random10 column50 column80 random84-s1 random84-s2 random84-s3 random84-s4 random84-s5 pyramid91 wall10x10"
if [ "${LCPFB_QUICK:-0}" != 1 ]; then
  gen wall --rows 25 --cols 40 -o "$W/wall25x40.json"
  workloads="$workloads wall25x40"
fi

# plan FILE METHOD SEARCH-ARGS...: "summary|tests|fallbacks|seeds|skips|seconds"
plan() {
  local f=$1 m=$2
  shift 2
  local log=$W/log
  "$CLI" plan "$f" --method "$m" --stats --time-limit "$LIMIT" "$@" >"$log" 2>&1
  local sum tests fb seeds skips secs
  sum=$(head -1 "$log" | sed 's/, [0-9.]* s \[.*//')
  tests=$(sed -n 's/^  tests \([0-9]*\).*/\1/p' "$log")
  fb=$(sed -n 's/.*LP fallbacks \([0-9]*\).*/\1/p' "$log")
  seeds=$(sed -n 's/.*re-seeded \([0-9]*\).*/\1/p' "$log")
  skips=$(sed -n 's/.*LCP skipped \([0-9]*\).*/\1/p' "$log")
  secs=$(sed -n 's/.*time: total \([0-9.]*\) s.*/\1/p' "$log")
  echo "$sum|${tests:-0}|${fb:-0}|${seeds:-0}|${skips:-0}|${secs:-nan}"
}

echo "$(date -u +%Y-%m-%d), $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; Release build."
echo
echo "| workload | bodies | search | method | tests | lp_fallbacks | % | re-seeds | skipped | time (s) | same plan as lp |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for wl in $workloads; do
  f=$W/$wl.json
  n=$("$CLI" check "$f" --local off 2>/dev/null | sed -n 's/^[a-z]*: \([0-9]*\) bodies.*/\1/p')
  for search in "assemble" "dfs down"; do
    set -- $search
    args=(--search "$1")
    [ $# -gt 1 ] && args+=(--direction "$2")
    IFS='|' read -r lpsum _ <<<"$(plan "$f" lp "${args[@]}")"
    for m in lcp lcp-reuse; do
      # the LCP from scratch needs seconds per test on the 25 x 40 wall
      [ "$wl" = wall25x40 ] && [ "$m" = lcp ] && continue
      IFS='|' read -r sum tests fb seeds skips secs <<<"$(plan "$f" "$m" "${args[@]}")"
      pct=$(awk -v a="$fb" -v b="$tests" 'BEGIN{ if (b > 0) printf "%.1f", 100 * a / b; else print "-" }')
      same=$([ "$sum" = "$lpsum" ] && echo yes || echo "NO: $sum vs $lpsum")
      echo "| $wl | $n | $search | $m | $tests | $fb | $pct | $seeds | $skips | $secs | $same |"
    done
  done
done
