#!/usr/bin/env bash
# The benchmark (make bench; make bench QUICK=1 for a subset under a
# minute). Release build, timings never in the tests. It records, side by
# side, in bench/results/ (CSV, SVG plots drawn by bench/plot.c with cairo,
# and a markdown summary with the machine's CPU and core count):
#   table2.csv    the source's Table 2 workloads (random 10, column 50,
#                 column 80, random 84 from the stacker, pyramid 91), every
#                 method and search direction, the source's own figures,
#                 and the ratio to lpsolve;
#   table2-3d.csv the 3D Table 2 (bench/table2_3d.sh: pyramid3d, wall3d,
#                 a jittered tower, random3d; every method, both directions);
#   table2-source.csv  the same workloads in the source's set-up:
#                 frictionless, its DFS down from the top, no culling;
#   fig4-*.csv    the source's Figure 4: seconds per stability test against
#                 the bodies in the tested sub-assembly, per method, on the
#                 91-block pyramid and a 1,000-block wall (bench_fig4),
#                 and on the frictionless pyramid taken apart (the source's);
#                 in 3D on pyramid3d 6 rows and wall3d 8 x 8 (lp, lcp, lcp-reuse);
#   startup.csv   whole commands timed from fork to exit: /bin/true, check
#                 on a 5-block column, plan on the pyramid with lp and
#                 lpsolve (bench/startup.c); startup-ratios.csv the two
#                 ratios of issue 24;
#   scaling.csv   walls and pyramids from 100 to 100,000 blocks, the
#                 stacker's random stacks from 100 to about 9,000: plan and verify time, tests, peak memory,
#                 and the fitted exponent from 1,000 blocks up;
#   decisions.csv per scaling workload, the default plan's tests settled
#                 by plumb lines, by levers, by region LPs (with the region
#                 sizes) and by the full system;
#   hands-*.csv   plan --hands auto on arches of 6 to 30 voussoirs and the
#                 default dome (bench/hands.sh): H, proven or not, time;
#   batch-*.csv   unstack batch on 400 small structures (1 and 2 jobs, MPI,
#                 one process per file) and a large set (bench/batch.sh).
# Usage: bench/run.sh BUILD_DIR   (env QUICK=1, BENCH_OUT=dir, BENCH_LIMIT=s)
set -uo pipefail
B=${1:-build}
QUICK=${QUICK:-0}
OUT=${BENCH_OUT:-bench/results}
LIMIT=${BENCH_LIMIT:-120}
CLI=$B/unstack
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=1 # CLP links OpenBLAS; its thread pool only spins here
tag=$([ "$QUICK" = 1 ] && echo quick || echo full)
MD=$OUT/c-$tag.md
T2=$OUT/table2-$tag.csv
SC=$OUT/scaling-$tag.csv
START=$(date +%s)

say() { echo "$@" | tee -a "$MD"; }

# plan FILE [args]: prints "status tests total_s rss_kb" (status "timeout"
# when the wall-clock guard fired)
plan_row() {
  local f=$1
  shift
  local log=$W/plan.log
  /usr/bin/time -f "RSS %M" timeout $((LIMIT + 30)) "$CLI" plan "$f" --stats --time-limit "$LIMIT" \
    -o "$W/plan.json" "$@" >"$log" 2>&1
  local status tests total rss
  status=$(head -1 "$log" | sed 's/[:,].*//')
  tests=$(sed -n 's/^  tests \([0-9]*\).*/\1/p' "$log")
  total=$(sed -n 's/.*time: total \([0-9.]*\) s.*/\1/p' "$log")
  rss=$(sed -n 's/^RSS \([0-9]*\)/\1/p' "$log")
  [ -n "$total" ] || status=timeout
  echo "${status:-error} ${tests:-0} ${total:-nan} ${rss:-0}"
  cp "$log" "$W/last-plan.log"
  cat "$log" >>"$W/all-plans.log"
}

gen() { "$CLI" generate "$@" >/dev/null; }

# ------------------------------------------------------------------ header
{
  echo "# unstack benchmark ($tag)"
  echo
  echo "$(date -u +%Y-%m-%d), $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(uname -m);"
  echo "$(gcc --version | head -1); Release build; OPENBLAS_NUM_THREADS=1."
  echo
} >"$MD"
cat "$MD"

# ------------------------------------------------------------------ Table 2
# the workloads, with friction 0.5 and frictionless (-f0: the source's set-up)
table2_gen() { # SUFFIX [generate options]
  local x=$1
  shift
  gen random --rows 6 --width 4 --seed 2 "$@" -o "$W/random10$x.json"
  gen column --blocks 50 "$@" -o "$W/column50$x.json"
  gen column --blocks 80 "$@" -o "$W/column80$x.json"
  gen stacker --rows 16 --width 12 --seed 15 "$@" -o "$W/random84$x.json" # 84 blocks
  gen pyramid --rows 13 "$@" -o "$W/pyramid91$x.json"
}
table2_gen ""
table2_gen -f0 --friction 0
# bodies of a generated file (one "id" per body; no solve, so 100,000 is cheap)
bodies() { grep -o '"id"' "$1" | wc -l; }
# the source's Table 2 (seconds, whole plan, frictionless, its DFS taking
# the structure down from the top; averages of 100 runs on a 1.5 GHz
# PowerBook G4, Java)
source_s() {
  case "$1/$2" in
  random10/lpsolve) echo 0.017 ;;
  random10/lcp) echo 0.024 ;;
  random10/lcp-reuse) echo 0.010 ;;
  column50/lpsolve) echo 0.483 ;;
  column50/lcp) echo 2.987 ;;
  column50/lcp-reuse) echo 0.469 ;;
  column80/lpsolve) echo 2.880 ;;
  column80/lcp) echo 20.997 ;;
  column80/lcp-reuse) echo 2.005 ;;
  random84/lpsolve) echo 9.396 ;;
  random84/lcp) echo 72.099 ;;
  random84/lcp-reuse) echo 5.532 ;;
  pyramid91/lpsolve) echo 5.260 ;;
  pyramid91/lcp) echo 38.825 ;;
  pyramid91/lcp-reuse) echo 3.074 ;;
  *) echo "" ;;
  esac
}
workloads="random10 column50 column80 random84 pyramid91"
methods="lpsolve lp lcp lcp-reuse lp-lcp auto"
[ "$QUICK" = 1 ] && workloads="random10 column50 pyramid91"
echo "workload,bodies,method,search,status,tests,total_s,ms_per_test,rss_kb,source_s,speedup_vs_lpsolve" >"$T2"
say "## Table 2: the source's workloads"
say ""
say "Whole plans, seconds (tests); \`assemble\` is the default search, \`dfs down\` the source's (its figures are for its own machine and Java prototype)."
say ""
say "| workload | bodies | search | lpsolve | lp | lcp | lcp-reuse | lp-lcp | auto | auto vs lpsolve | source (lpsolve / lcp / lcp-reuse) |"
say "|---|---|---|---|---|---|---|---|---|---|---|"
for wl in $workloads; do
  n=$(bodies "$W/$wl.json")
  for search in "assemble" "dfs down" "dfs up"; do
    set -- $search
    args=(--search "$1")
    [ $# -gt 1 ] && args+=(--direction "$2")
    line="| $wl | $n | $search |"
    declare -A tot=()
    for m in $methods; do
      read -r status tests total rss < <(plan_row "$W/$wl.json" --method "$m" "${args[@]}")
      tot[$m]=$total
      per=$(awk -v t="$total" -v n="$tests" 'BEGIN{ if (n > 0 && t != "nan") printf "%.4f", 1000 * t / n; else print "" }')
      src=$([ "$search" = "dfs down" ] && source_s "$wl" "$m")
      sp=$(awk -v a="${tot[lpsolve]:-nan}" -v b="$total" 'BEGIN{ if (a != "nan" && b > 0) printf "%.1f", a / b; else print "" }')
      echo "$wl,$n,$m,$search,$status,$tests,$total,$per,$rss,$src,$sp" >>"$T2"
      line="$line $(awk -v t="$total" 'BEGIN{ if (t == "nan") print "-"; else printf "%.3g", t }') ($tests)$([ "$status" = found ] || echo " $status") |"
    done
    sp=$(awk -v a="${tot[lpsolve]}" -v b="${tot[auto]}" 'BEGIN{ if (b > 0 && a != "nan") printf "%.0fx", a / b; else print "-" }')
    srcs="$(source_s "$wl" lpsolve) / $(source_s "$wl" lcp) / $(source_s "$wl" lcp-reuse)"
    [ "$search" = "dfs down" ] || srcs=""
    say "$line $sp | $srcs |"
    unset tot
  done
done
say ""

# The source's own set-up: frictionless copies, its depth-first search down
# from the top (highest first), no culling rules; the source's seconds
# beside ours (its machine: a 1.5 GHz PowerBook G4, Java).
T2S=$OUT/table2-source-$tag.csv
echo "workload,bodies,method,status,tests,unstable,total_s,source_s" >"$T2S"
say "## Table 2 in the source's set-up"
say ""
say "Frictionless, \`--search dfs --direction down --order highest --rules none\`: seconds (tests), and the source's seconds."
say ""
say "| workload | bodies | lpsolve | lcp | lcp-reuse | lp | auto | source lpsolve / lcp / lcp-reuse |"
say "|---|---|---|---|---|---|---|---|"
for wl in $workloads; do
  f=$W/$wl-f0.json
  n=$(bodies "$f")
  line="| $wl | $n |"
  for m in lpsolve lcp lcp-reuse lp auto; do
    read -r status tests total rss < <(plan_row "$f" --method "$m" --search dfs --direction down \
      --order highest --rules none)
    unst=$(sed -n 's/^  tests [0-9]* (stable [0-9]*, unstable \([0-9]*\).*/\1/p' "$W/plan.log")
    echo "$wl,$n,$m,$status,$tests,${unst:-},$total,$(source_s "$wl" "$m")" >>"$T2S"
    line="$line $(awk -v t="$total" 'BEGIN{ if (t == "nan") print "-"; else printf "%.3g", t }') ($tests)$([ "$status" = found ] || echo " $status") |"
  done
  say "$line $(source_s "$wl" lpsolve) / $(source_s "$wl" lcp) / $(source_s "$wl" lcp-reuse) |"
done
say ""

# --------------------------------------------------- Table 2 in 3D (issue 23)
if [ "$QUICK" != 1 ]; then
  say "## Table 2 in 3D: [data](table2-3d-$tag.csv) (bench/table2_3d.sh)"
  say ""
  bench/table2_3d.sh "$B" >"$OUT/table2-3d-$tag.csv" 2>>"$MD"
  say ""
fi

# ----------------------------------------------------------------- Figure 4
say "## Figure 4: one stability test against the sub-assembly's size"
say ""
gen wall --rows 25 --cols 40 -o "$W/wall1000.json"
budget=$([ "$QUICK" = 1 ] && echo 0.5 || echo 15)
for wl in pyramid91 wall1000; do
  f4=$OUT/fig4-$wl-$tag.csv
  echo "structure,method,bodies,seconds" >"$f4"
  for m in $methods; do
    [ "$QUICK" = 1 ] && [ "$wl" = wall1000 ] && [ "$m" != auto ] && [ "$m" != lp ] && continue
    "$B/bench_fig4" "$W/$wl.json" "$wl" "$m" "$budget" >>"$f4" 2>>"$W/fig4.err"
  done
  fits=$(tail -n +2 "$f4" | awk -F, '{print $2, $3, $4}' |
    "$B/bench_plot" "$OUT/fig4-$wl-$tag.svg" "Figure 4: $wl, one stability test" \
      "bodies in the sub-assembly" "seconds per test")
  say "$wl ([plot](fig4-$wl-$tag.svg), [data](fig4-$wl-$tag.csv)); median ms per test, and the slope of log time against log size:"
  say ""
  say "| method | tests timed | median ms | largest size timed | slope |"
  say "|---|---|---|---|---|"
  for m in $methods; do
    stats=$(awk -F, -v m="$m" '$2 == m {print $4 * 1000, $3}' "$f4" | sort -n |
      awk '{v[NR] = $1; if ($2 > mx) mx = $2} END { if (NR) printf "%d | %.4f | %d", NR, v[int((NR + 1) / 2)], mx }')
    [ -n "$stats" ] || continue
    say "| $m | $stats | $(echo "$fits" | awk -v m="$m" '$1 == m {print $2}') |"
  done
  say ""
done
# The source's Figure 4: frictionless pyramid, taken apart along its DFS
# from the top (bench_fig4 ... down), sizes from 91 down.
wl=pyramid91-f0
f4=$OUT/fig4-$wl-$tag.csv
echo "structure,method,bodies,seconds" >"$f4"
for m in lpsolve lcp lcp-reuse lp auto; do
  "$B/bench_fig4" "$W/$wl.json" "$wl" "$m" "$budget" down >>"$f4" 2>>"$W/fig4.err"
done
fits=$(tail -n +2 "$f4" | awk -F, '{print $2, $3, $4}' |
  "$B/bench_plot" "$OUT/fig4-$wl-$tag.svg" "Figure 4 (source set-up): frictionless pyramid, taken apart" \
    "bodies in the sub-assembly" "seconds per test")
say "$wl, the source's set-up (frictionless, taken apart along its DFS from the top; [plot](fig4-$wl-$tag.svg), [data](fig4-$wl-$tag.csv)):"
say ""
say "| method | tests timed | median ms | sizes timed | slope |"
say "|---|---|---|---|---|"
for m in lpsolve lcp lcp-reuse lp auto; do
  stats=$(awk -F, -v m="$m" '$2 == m {print $4 * 1000, $3}' "$f4" | sort -n |
    awk 'NR == 1 {mn = $2} {v[NR] = $1; if ($2 > mx) mx = $2; if ($2 < mn) mn = $2}
      END { if (NR) printf "%d | %.4f | %d-%d", NR, v[int((NR + 1) / 2)], mn, mx }')
  [ -n "$stats" ] || continue
  say "| $m | $stats | $(echo "$fits" | awk -v m="$m" '$1 == m {print $2}') |"
done
say ""
# Figure 4 in 3D (issue 23): pyramid3d (6 rows, 91 boxes) and wall3d
# (8 x 8), built up along the plan; lp against the 3D LCP methods.
gen pyramid3d --rows 6 -o "$W/pyramid3d-6.json"
gen wall3d --rows 8 --cols 8 -o "$W/wall3d-8x8.json"
for wl in pyramid3d-6 wall3d-8x8; do
  [ "$QUICK" = 1 ] && [ "$wl" = wall3d-8x8 ] && continue
  f4=$OUT/fig4-$wl-$tag.csv
  echo "structure,method,bodies,seconds" >"$f4"
  for m in lp lcp lcp-reuse; do
    "$B/bench_fig4" "$W/$wl.json" "$wl" "$m" "$budget" >>"$f4" 2>>"$W/fig4.err"
  done
  fits=$(tail -n +2 "$f4" | awk -F, '{print $2, $3, $4}' |
    "$B/bench_plot" "$OUT/fig4-$wl-$tag.svg" "Figure 4 in 3D: $wl, one stability test" \
      "bodies in the sub-assembly" "seconds per test")
  say "$wl, 3D ([plot](fig4-$wl-$tag.svg), [data](fig4-$wl-$tag.csv)):"
  say ""
  say "| method | tests timed | median ms | largest size timed | slope |"
  say "|---|---|---|---|---|"
  for m in lp lcp lcp-reuse; do
    stats=$(awk -F, -v m="$m" '$2 == m {print $4 * 1000, $3}' "$f4" | sort -n |
      awk '{v[NR] = $1; if ($2 > mx) mx = $2} END { if (NR) printf "%d | %.4f | %d", NR, v[int((NR + 1) / 2)], mx }')
    [ -n "$stats" ] || continue
    say "| $m | $stats | $(echo "$fits" | awk -v m="$m" '$1 == m {print $2}') |"
  done
  say ""
done

# ------------------------------------------------------------------ start-up
# Whole commands as a user runs them (bench_startup: fork to exit, median
# of many runs): the price of loading the executable and its libraries
# (docs/modules.md). Targets (issue 24): check on a 5-block column at most
# 4x /bin/true; plan on the pyramid at least 20x faster than with lpsolve.
say "## Start-up: whole commands"
say ""
ST=$OUT/startup-$tag.csv
RUNS=$([ "$QUICK" = 1 ] && echo 31 || echo 101)
SLOW=$([ "$QUICK" = 1 ] && echo 11 || echo 31)
gen column --blocks 5 -o "$W/column5.json"
echo "command,runs,median_ms,min_ms,objects" >"$ST"
# objects COMMAND...: the shared objects one run maps
objects() { LD_DEBUG=files "$@" 2>&1 >/dev/null | grep -c 'generating link map'; }
# the fast three take turns (bench_startup), so the load falls on all alike
fast=$("$B/bench_startup" "$RUNS" /bin/true -- "$CLI" check "$W/column5.json" \
  -- "$CLI" plan "$W/pyramid91.json" -o "$W/sp.json")
slow=$("$B/bench_startup" "$SLOW" "$CLI" plan "$W/pyramid91.json" --method lpsolve -o "$W/sp.json")
# shellcheck disable=SC2086 # the numbers, one word each
read -r t_true m_true t_check m_check t_plan m_plan < <(echo $fast)
read -r t_lps m_lps <<<"$slow"
{
  echo "true,$RUNS,$t_true,$m_true,$(objects /bin/true)"
  echo "check column5,$RUNS,$t_check,$m_check,$(objects "$CLI" check "$W/column5.json")"
  echo "plan pyramid91,$RUNS,$t_plan,$m_plan,$(objects "$CLI" plan "$W/pyramid91.json" -o "$W/sp.json")"
  echo "plan pyramid91 --method lpsolve,$SLOW,$t_lps,$m_lps,$(objects "$CLI" plan "$W/pyramid91.json" \
    --method lpsolve -o "$W/sp.json")"
} >>"$ST"
say "| command | runs | median ms | min ms | shared objects loaded |"
say "|---|---|---|---|---|"
tail -n +2 "$ST" | awk -F, '{printf "| %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5}' | tee -a "$MD"
say ""
say "$(awk -v c="$t_check" -v t="$t_true" -v p="$t_plan" -v l="$t_lps" 'BEGIN {
  printf "check column5 / true: %.2f (target at most 4); plan pyramid91 lpsolve / lp: %.1f (target at least 20)", c / t, l / p }')"
awk -v c="$t_check" -v t="$t_true" -v p="$t_plan" -v l="$t_lps" 'BEGIN {
  print "ratio,value,target"
  printf "check column5 / true,%.3f,at most 4\n", c / t
  printf "plan pyramid91 lpsolve / lp,%.3f,at least 20\n", l / p }' >"$OUT/startup-ratios-$tag.csv"
say ""

# ------------------------------------------------------------------ scaling
say "## Scaling: whole plan (and verify) time against the number of blocks"
say ""
echo "family,bodies,method,status,tests,plan_s,verify_s,rss_kb" >"$SC"
DC=$OUT/decisions-$tag.csv
echo "family,bodies,local_tests,plumb_pct,lever_pct,region_pct,full_pct,region_lps,mean_region,settled_by_region_size" >"$DC"
if [ "$QUICK" = 1 ]; then
  walls="10 17 32"; pyrs="14 24 45"; stacks="18:12"
else
  walls="10 17 32 55 100 173 316"; pyrs="14 24 45 77 141 245 447"; stacks="18:12 50:24 160:48 250:75 80:400 100:560"
fi
scale_row() { # family file method-words max-bodies
  local fam=$1 f=$2 m=$3 cap=$4 n
  n=$(bodies "$f")
  [ "$n" -le "$cap" ] || return 0
  read -r status tests total rss < <(plan_row "$f" $m)
  local vt=""
  if [ "$status" = found ]; then
    local t0 t1
    t0=$(date +%s.%N)
    timeout $((LIMIT + 30)) "$CLI" verify "$f" "$W/plan.json" $m >/dev/null 2>&1 && t1=$(date +%s.%N) &&
      vt=$(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.3f", b - a}')
  fi
  local label
  label=$(echo "$m" | sed 's/--method //; s/ --local off/-nolocal/')
  echo "$fam,$n,$label,$status,$tests,$total,$vt,$rss" | tee -a "$SC"
  [ "$label" = auto ] && decision_row "$fam" "$n" "$W/last-plan.log"
}
# Who decided the local tests of a plan (its --stats log): shares of the
# tests settled by plumb lines, by region LPs (stable or unstable, with the
# region sizes' histogram) and by the full system (docs/local.md).
decision_row() { # family bodies log
  sed -n 's/.*local tests: \([0-9]*\) stable (\([0-9]*\) by plumb lines, \([0-9]*\) by levers), \([0-9]*\) unstable, \([0-9]*\) on the full system[^;]*; \([0-9]*\) region LPs, mean region \([0-9.]*\) bodies.*/\1 \2 \3 \4 \5 \6 \7/p' "$3" |
    awk -v fam="$1" -v n="$2" -v sizes="$(sed -n 's/.*settled by region size: //p' "$3" | tr ',' ';')" \
      '{t = $1 + $4 + $5; if (t == 0) next
        printf "%s,%s,%d,%.2f,%.2f,%.2f,%.2f,%d,%s,%s\n", fam, n, t, 100 * $2 / t, 100 * $3 / t,
          100 * ($1 - $2 - $3 + $4) / t, 100 * $5 / t, $6, $7, sizes}' >>"$DC"
}
# One regular family: generate each size, then the methods that reach it
# (lcp-reuse up to lcp_cap bodies, lpsolve up to 350).
scale_family() { # family generator-words-fn sizes lcp_cap
  local fam=$1 args=$2 sizes=$3 lcp_cap=$4 r f
  for r in $sizes; do
    f="$W/$fam$r.json"
    # shellcheck disable=SC2046
    gen "$fam" $($args "$r") -o "$f"
    scale_row "$fam" "$f" "--method auto" 1000000
    scale_row "$fam" "$f" "--method lp --local off" $([ "$QUICK" = 1 ] && echo 400 || echo 3500)
    [ "$QUICK" = 1 ] && continue
    scale_row "$fam" "$f" "--method lcp-reuse" "$lcp_cap"
    scale_row "$fam" "$f" "--method lpsolve" 350
  done
}
wall_args() { echo "--rows $1 --cols $1"; }
pyramid_args() { echo "--rows $1"; }
scale_family wall wall_args "$walls" 400
scale_family pyramid pyramid_args "$pyrs" 1100
for rw in $stacks; do
  gen stacker --rows "${rw%:*}" --width "${rw#*:}" --seed 1 -o "$W/stack$rw.json"
  scale_row stacker "$W/stack$rw.json" "--method auto" 100000
  [ "$QUICK" = 1 ] || scale_row stacker "$W/stack$rw.json" "--method lp --local off" 3500
done
points() { tail -n +2 "$SC" | awk -F, '$4 == "found" {print $1 "/" $3, $2, $6}'; }
fits=$(points | "$B/bench_plot" "$OUT/scaling-$tag.svg" "Whole plan time" "blocks" "seconds" --lines --fit-from 900)
fits10=$(points | "$B/bench_plot" "$W/fit10.svg" "" "" "" --fit-from 900 --fit-to 11000)
say "[plot](scaling-$tag.svg), [data](scaling-$tag.csv); fitted exponent of plan time from about 1,000 to 10,000 blocks, and from about 1,000 blocks up:"
say ""
say "| family / method | exponent 1,000-10,000 | points | exponent 1,000 up | points |"
say "|---|---|---|---|---|"
join <(echo "$fits10" | sort) <(echo "$fits" | sort) -a 2 |
  awk '{for (i = 2; i <= NF; i++) if ($i == "nan") $i = "-"} NF == 5 {printf "| %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5} NF == 3 {printf "| %s | | | %s | %s |\n", $1, $2, $3}' | tee -a "$MD"
say ""
say "| family | blocks | method | status | tests | plan s | verify s | max RSS MiB |"
say "|---|---|---|---|---|---|---|---|"
tail -n +2 "$SC" | awk -F, '{printf "| %s | %s | %s | %s | %s | %s | %s | %.0f |\n", $1, $2, $3, $4, $5, $6, $7, $8 / 1024}' | tee -a "$MD"
say ""
say "Who decided the stability tests of the default plan ($(basename "$DC")): plumb lines, levers, region LPs (stable or unstable; the share settled at each region size) and the full system:"
say ""
say "| family | blocks | tests | plumb lines % | levers % | regions % | full system % | region LPs | mean region | settled by region size |"
say "|---|---|---|---|---|---|---|---|---|---|"
tail -n +2 "$DC" | awk -F, '{printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6, $7, $8, $9, $10}' | tee -a "$MD"
if [ "$QUICK" != 1 ]; then # about 5 minutes: the full run only
  say ""
  say "## LP fallbacks of the LCP backends"
  say ""
  LCPFB_LIMIT=60 bash "$(dirname "$0")/lcp_fallbacks.sh" "$B" >"$OUT/lcp-fallbacks-$tag.md"
  say "Per workload, both searches: [table](lcp-fallbacks-$tag.md) (bench/lcp_fallbacks.sh; docs/lcp.md explains the causes)."
fi
say ""
say "## Hands: plan --hands auto (docs/planning.md, \"Hands\")"
say ""
bash "$(dirname "$0")/hands.sh" "$B" "$OUT" "$tag" | tee -a "$MD"
say ""
say "## unstack batch: 400 small structures, and a large labelled set (docs/batch.md)"
say ""
bash "$(dirname "$0")/batch.sh" "$B" "$OUT" "$tag" | tee -a "$MD"
say ""
say "## Whole commands at 100,000 blocks: check, plan, verify (bench/load.sh)"
say ""
bash "$(dirname "$0")/load.sh" "$B" "$OUT" "$tag" | tee -a "$MD"
say ""
say "## Tests by change: per-test time against size (bench_delta; docs/planning.md, \"Tests by change\")"
say ""
"$B/bench_delta" $([ "$QUICK" = 1 ] && echo quick) | tee -a "$MD"
say ""
say "Whole benchmark: $(($(date +%s) - START)) s."
echo "wrote $MD"
