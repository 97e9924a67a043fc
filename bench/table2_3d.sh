#!/usr/bin/env bash
# The 3D counterpart of the source's Table 2 (issue 23): plan on pyramid3d
# (6 rows, 91 boxes), wall3d (6 x 6), a jittered tower (12 boxes turned up
# to 30 degrees) and random3d (30 boxes), mu = 0.5, with every method and
# both directions (assemble: bodies join; dfs: bodies leave), one row each:
# status, tests, LCP pivots, LP fallbacks (tests the LP decided for an LCP
# method), reused tests, seconds. CSV on stdout; the lcp / lcp-reuse time
# ratio per workload and direction on stderr.
# Usage: bench/table2_3d.sh BUILD_DIR   (env T3_LIMIT=s per plan, default 300)
set -uo pipefail
B=${1:-build}
CLI=$B/unstack
LIMIT=${T3_LIMIT:-300}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
export OPENBLAS_NUM_THREADS=1

gen() { "$CLI" generate "$@" --friction 0.5 >/dev/null || echo "generate $* failed" >&2; }
gen pyramid3d --rows 6 -o "$W/pyramid3d-6.json"
gen wall3d --rows 6 --cols 6 -o "$W/wall3d-6x6.json"
gen tower --blocks 12 --jitter 30 --seed 3 -o "$W/tower-12j.json"
gen random3d --blocks 30 --width 4 --seed 2 -o "$W/random3d-30.json"

echo "workload,search,method,status,tests,pivots,lp_fallbacks,reused,seconds"
for wl in pyramid3d-6 wall3d-6x6 tower-12j random3d-30; do
  for search in assemble dfs; do
    for m in lp lpsolve lcp lcp-reuse lp-lcp; do
      log=$W/log
      "$CLI" plan "$W/$wl.json" --method "$m" --search "$search" --stats --time-limit "$LIMIT" \
        >"$log" 2>&1
      status=$(head -1 "$log" | sed 's/[:,].*//')
      tests=$(sed -n 's/^  tests \([0-9]*\).*/\1/p' "$log")
      piv=$(sed -n 's/^  LCP pivots \([0-9]*\),.*/\1/p' "$log")
      fb=$(sed -n 's/.*LP fallbacks \([0-9]*\) .*/\1/p' "$log")
      re=$(sed -n 's/.*), reused \([0-9]*\);.*/\1/p' "$log")
      secs=$(sed -n 's/.*time: total \([0-9.]*\) s.*/\1/p' "$log")
      echo "$wl,$search,$m,${status:-error},${tests:-0},${piv:-0},${fb:-0},${re:-0},${secs:-nan}"
      [ "$m" = lcp ] && t_lcp=${secs:-nan}
      [ "$m" = lcp-reuse ] && echo "$wl $search: lcp / lcp-reuse = $(python3 -c "print('%.1f' % ($t_lcp / max(${secs:-1}, 1e-9)))" 2>/dev/null)x" >&2
    done
  done
done
