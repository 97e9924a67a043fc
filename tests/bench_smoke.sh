#!/bin/bash
# The benchmark's own programs run (not timed here): bench_fig4 writes one
# CSV row per test of a small column, bench_plot draws them and fits a slope.
# Usage: bench_smoke.sh BUILD_DIR
set -u
B=$1
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
"$B/unstack" generate column --blocks 12 -o "$T/c.json" >/dev/null || exit 1
"$B/bench_fig4" "$T/c.json" col12 auto 10 >"$T/f.csv" || { echo "bench_fig4 failed"; exit 1; }
rows=$(grep -c '^col12,auto,' "$T/f.csv")
[ "$rows" -eq 12 ] || { echo "expected 12 rows, got $rows"; exit 1; }
awk -F, '{print $2, $3, $4}' "$T/f.csv" | "$B/bench_plot" "$T/f.svg" t x y >"$T/fit" || { echo "plot failed"; exit 1; }
grep -q '<svg' "$T/f.svg" || { echo "no SVG written"; exit 1; }
grep -q '^auto [0-9.-]* 12$' "$T/fit" || { echo "no fit: $(cat "$T/fit")"; exit 1; }
echo "bench programs ok"
