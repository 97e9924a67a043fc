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
# taken apart (the source's Figure 4): from all 12 bodies down to 1
"$B/bench_fig4" "$T/c.json" col12 lcp-reuse 10 down >"$T/d.csv" || { echo "bench_fig4 down failed"; exit 1; }
[ "$(cut -d, -f3 "$T/d.csv" | tr '\n' ' ')" = "12 11 10 9 8 7 6 5 4 3 2 1 " ] ||
  { echo "down: sizes $(cut -d, -f3 "$T/d.csv" | tr '\n' ' ')"; exit 1; }
# the legend is never cut off: a longer series name makes a wider picture
width() { sed -n 's/.*<svg[^>]* width="\([0-9.]*\)[a-z]*".*/\1/p' "$1" | head -1; }
awk -F, '{print "a", $3, $4}' "$T/f.csv" | "$B/bench_plot" "$T/a.svg" t x y >/dev/null
awk -F, '{print "a-much-longer-series-name/lp-nolocal", $3, $4}' "$T/f.csv" |
  "$B/bench_plot" "$T/b.svg" t x y >/dev/null
wa=$(width "$T/a.svg") wb=$(width "$T/b.svg")
awk -v a="$wa" -v b="$wb" 'BEGIN { exit !(a > 0 && b > a) }' ||
  { echo "legend: widths $wa and $wb"; exit 1; }
echo "bench programs ok"
