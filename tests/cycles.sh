#!/bin/bash
# Files call one another one way only: inside each folder of the library
# (one archive per concept) and the tool, no two object files call each
# other, directly or round a longer loop. A helper both use belongs in a
# file below them. Edges come from nm: file A -> file B when A uses a
# global symbol B defines; tsort reports any loop.
# Usage: cycles.sh <build dir>
set -u
build=$1
fail=0
check() { # <name> <object files or archives...>
  local name=$1; shift
  local edges
  edges=$(nm -A "$@" 2>/dev/null | awk '
    NF != 3 { next }
    { n = split($1, p, ":"); f = ""
      for (i = 1; i <= n; i++) if (p[i] ~ /\.o$/) f = p[i]
      sub(/.*\//, "", f); sub(/\.c\.o$/, "", f) }
    $2 ~ /^[TDBRCVW]$/ { def[$3] = f; next }
    $2 == "U" { use[f, $3] = 1 }
    END {
      for (k in use) { split(k, q, SUBSEP); if ((q[2] in def) && def[q[2]] != q[1]) print q[1], def[q[2]] }
    }' | sort -u)
  [ -z "$edges" ] && return
  local loop
  loop=$(echo "$edges" | tsort 2>&1 >/dev/null)
  if [ -n "$loop" ]; then
    echo "$name: files that call each other:"; echo "$loop" | sed 's/^/  /'; fail=1
  fi
}
n=0
for a in "$build"/libus_*.a; do check "$(basename "$a" .a)" "$a"; n=$((n + 1)); done
tools=$(find "$build" -path '*unstack_cli.dir/tools/*.o')
[ -n "$tools" ] && { check tools $tools; n=$((n + 1)); }
[ "$n" -lt 5 ] && { echo "only $n folders found under $build"; fail=1; }
echo "$n folders checked"
exit $fail
