# unstack classify: the classes of generated and fixture structures (text
# and JSON), ids that need escaping, the top-down probe's limit, usage and
# input errors (exit 2). Reference values: the column, the cantilever
# fixture and the arch as in tests/test_plan_classify.c; the leaning
# fixture's mu* by hand statics (its _note): with the left slab's centre
# c_x = 1.6825 / 3.075, mu* = (c_x - 0.3) / 2.25 = 0.76 / 6.91875 =
# 0.1098464...; the overhang tips at any mu.
. "$(dirname "$0")/lib.sh"

# json_is FILE JQ-EXPR DESCRIPTION: the output parses and the expression holds
json_is() {
  if command -v jq >/dev/null; then
    if jq -e "$2" "$1" >/dev/null 2>&1; then ok "$3"; else bad "$3 ($2)"; sed 's/^/    /' "$1" | head -5; fi
  elif command -v python3 >/dev/null; then
    if python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$1"; then ok "$3 (parsed only)"; else bad "$3: not JSON"; fi
  else
    ok "$3 (skipped: no jq or python3)"
  fi
}

expect 0 "classify --help" -- "$CLI" classify --help
contains "$T/out" "usage: unstack classify" "classify help text"
expect 0 "unstack --help lists classify" -- "$CLI" --help
contains "$T/out" "classify FILE" "usage names classify"

# a column: top-down, frictionless, K = 1
"$CLI" generate column --blocks 5 -o "$T/c5.json" >/dev/null
expect 0 "classify column" -- "$CLI" classify "$T/c5.json"
contains "$T/out" "stands: yes" "column stands"
contains "$T/out" "friction: stands frictionless (mu* = 0" "column needs no friction"
contains "$T/out" "frictionless: strong = weak (Gauss's principle)" "column: strong = weak"
contains "$T/out" "top-down: yes" "column is top-down"
contains "$T/out" "sequence: yes" "column has a sequence"
contains "$T/out" "group: smallest K = 1" "column: K = 1"
contains "$T/out" "count: 6 connected" "column: count 6"
contains "$T/out" "equality constraints: no, it stands already" "column: no equality class"
[ "$(wc -l <"$T/out")" -eq 10 ] && ok "one line per class and a time line" || bad "$(wc -l <"$T/out") lines"

# the cantilever: highest first fails, the DFS finds an order
expect 0 "classify cantilever" -- "$CLI" classify "$DATA/cantilever.json"
contains "$T/out" "top-down: no, needs backtracking in the source's DFS (found after 1 rejected move" "cantilever needs backtracking"
contains "$T/out" "sequence: yes" "cantilever has a sequence"
expect 0 "cantilever, probe cut after the rejection" -- "$CLI" classify "$DATA/cantilever.json" --max-tests 3
contains "$T/out" "top-down: no, highest first fails" "a rejection before the limit decides"
"$CLI" generate column --blocks 30 -o "$T/c30.json" >/dev/null
expect 0 "column, probe cut early" -- "$CLI" classify "$T/c30.json" --max-tests 5
contains "$T/out" "top-down: unknown (limit" "limit before any failure: unknown"
contains "$T/out" "group: smallest K = 1" "the other classes have no limit"

# two slabs leaning on each other: friction, no sequence, K = 2
expect 0 "classify leaning" -- "$CLI" classify "$DATA/leaning.json"
contains "$T/out" "stands only with friction, mu* = 0.109846" "leaning: mu* by hand statics"
contains "$T/out" 'sequence: none; blocked: "left", "right"' "leaning: both slabs blocked"
contains "$T/out" "group: smallest K = 2" "leaning: K = 2"
contains "$T/out" "not frictionless: they may differ" "leaning: no strong = weak claim with friction"
expect 0 "classify leaning --json" -- "$CLI" classify "$DATA/leaning.json" --json
json_is "$T/out" '.stands and (.stands_frictionless | not) and .min_group == 2 and .sequence == false and .blocked == ["left", "right"] and .count == "4" and .mu_critical == 0.109846' "leaning: JSON classes"
expect 0 "classify leaning with the LCP" -- "$CLI" classify "$DATA/leaning.json" --method lcp-reuse
contains "$T/out" "group: smallest K = 2" "lcp-reuse: K = 2"

# the arch: the crown must go at once (--strong off: the arch's strong
# stability MIP runs to its own 10 s limit undecided, and is not what
# these lines check)
"$CLI" generate arch -o "$T/arch.json" >/dev/null
expect 0 "classify arch" -- "$CLI" classify "$T/arch.json" --strong off
contains "$T/out" 'sequence: none; blocked: "b3", "b4", "b5", "b6", "b7", "b8"' "arch: crown blocked"
contains "$T/out" "group: smallest K = 6" "arch: K = 6"
contains "$T/out" "top-down: no" "arch: not top-down"
# 30 voussoirs need K = 20, found by the cut in about 0.05 s: the time
# limit is only a ceiling, hundreds of times the normal time
"$CLI" generate arch --voussoirs 30 -o "$T/arch30.json" >/dev/null
expect 0 "classify arch30" -- "$CLI" classify "$T/arch30.json" --time-limit 30 --strong off
contains "$T/out" "sequence: none; blocked:" "arch30: K = 1 decided"
contains "$T/out" "group: smallest K = 20" "arch30: the middle 20 voussoirs go at once"
# the bevelled dome: one voussoir at a time is none, proven by the cut in
# 50 tests (decided by a test budget, not a clock: no time limit here)
"$CLI" generate dome --courses 5 --segments 8 -o "$T/dome58.json" >/dev/null
expect 1 "dome: one voussoir at a time is none" -- "$CLI" plan "$T/dome58.json" --max-group 1
contains "$T/out" "cannot be removed with steps of up to 1 body" "dome: K = 1 decided"
# with a time limit of 1 s: the group search (K >= 7 runs for minutes) is
# cut; the sequence search and the friction bisection may or may not end
# in time on a busy machine, so only what holds either way is asserted
expect 0 "classify a dome with a time limit" -- "$CLI" classify "$T/dome58.json" --time-limit 1
contains "$T/out" "group: unknown (time limit of 1 s" "dome: K unknown at the limit"
if grep -q "^sequence: none; blocked:" "$T/out"; then
  contains "$T/out" "group: unknown (time limit of 1 s; K > " "dome: K = 1 decided in time, so a bound is given"
else
  contains "$T/out" "sequence: unknown (time limit of 1 s" "dome: the sequence search cut too"
fi
if grep -q "^friction: unknown" "$T/out"; then
  contains "$T/out" "friction: unknown (time limit of 1 s" "dome: the friction bisection stops at the limit"
else
  contains "$T/out" "friction: stands only with friction" "dome: the friction bisection ended in time"
fi
expect 0 "classify the dome --json with a time limit" -- "$CLI" classify "$T/dome58.json" --time-limit 1 --json
json_is "$T/out" '.min_group == null and .group_status == "limit" and ((.sequence == false and .sequence_status == "none" and .group_bound >= 1) or (.sequence_status == "limit" and .group_bound == 0))' "dome: JSON limit"

# a plank that tips: no K at all
cat >"$T/overhang.json" <<'EOF'
{"friction": 0.5, "bodies": [
  {"id": "pier", "polygon": [[0, 0], [1, 0], [1, 1], [0, 1]]},
  {"id": "plank", "polygon": [[0.2, 1], [2.7, 1], [2.7, 1.2], [0.2, 1.2]]}]}
EOF
expect 0 "classify overhang" -- "$CLI" classify "$T/overhang.json"
contains "$T/out" 'stands: no (lp: body "plank" cannot be held)' "overhang: the plank named"
contains "$T/out" "stands for no mu up to 1000" "overhang: no mu"
contains "$T/out" "group: no sequence for any K: the full structure does not stand" "overhang: no K"
# stands only with equality constraints: the joint at x = 0.2 can pull
# (tests/test_plan_classify.c, equality_known_answers)
contains "$T/out" "equality constraints: yes, stands only with equality constraints" "overhang: joints hold it"
expect 0 "classify overhang --json" -- "$CLI" classify "$T/overhang.json" --json
json_is "$T/out" '.stands == false and .unstable_body == "plank" and .mu_critical == null and .min_group == null and .group_status == "unstable" and .topdown == false' "overhang: JSON"
json_is "$T/out" '.equality == true and .stands_bilateral == true and .equality_reason == null' "overhang: JSON equality"

# not even with joints: a block touching nothing, a block on one vertex
cat >"$T/cloud.json" <<'EOF'
{"friction": 0.5, "bodies": [
  {"id": "pier", "polygon": [[0, 0], [1, 0], [1, 1], [0, 1]]},
  {"id": "cloud", "polygon": [[3, 3], [4, 3], [4, 4], [3, 4]]}]}
EOF
expect 0 "classify a loose block" -- "$CLI" classify "$T/cloud.json"
contains "$T/out" 'equality constraints: no, it does not stand even with bilateral joints: body "cloud" touches nothing' "loose: named"
expect 0 "classify a loose block --json" -- "$CLI" classify "$T/cloud.json" --json
json_is "$T/out" '.equality == false and .stands_bilateral == false and .equality_reason == "loose body" and .bilateral_body == "cloud"' "loose: JSON"
cat >"$T/vertex.json" <<'EOF'
{"friction": 0.5, "bodies": [{"id": "d", "polygon": [[0, 0], [1, 1], [0.2, 2], [-1.3, 1]]}]}
EOF
expect 0 "classify a block on a vertex" -- "$CLI" classify "$T/vertex.json" --json
json_is "$T/out" '.equality == false and .equality_reason == "mechanism" and .stands == false' "vertex: a mechanism even with joints"
expect 0 "classify leaning --json: stands, so no" -- "$CLI" classify "$DATA/leaning.json" --json
json_is "$T/out" '.equality == false and .stands_bilateral == null and .equality_reason == "stands"' "leaning: stands already"

# ids with quotes, backslashes and control characters are escaped
cat >"$T/weird.json" <<'EOF'
{"friction": 0.5, "bodies": [
 {"id": "le\"ft\\", "polygon": [[0, 0], [0.3, 0], [1, 1.75], [1, 2.25]]},
 {"id": "ri\u0001g\nht\t\u00e9", "polygon": [[2, 0], [1, 2.25], [1, 1.75], [1.7, 0]]}]}
EOF
expect 0 "classify odd ids" -- "$CLI" classify "$T/weird.json"
contains "$T/out" 'blocked: "le\"ft\\", "ri\u0001g\u000aht\u0009' "text: ids escaped"
[ "$(wc -l <"$T/out")" -eq 11 ] && ok "no raw newline from an id" || bad "an id broke a line"
expect 0 "classify odd ids --json" -- "$CLI" classify "$T/weird.json" --json
json_is "$T/out" '.blocked == ["le\"ft\\", "ri\u0001g\nht\t\u00e9"]' "json: ids round-trip"

# usage and input errors: exit 2
expect 2 "classify without file" -- "$CLI" classify
expect 2 "classify missing file" -- "$CLI" classify "$T/nope.json"
contains "$T/err" "nope.json" "names the missing file"
expect 2 "classify bad input" -- "$CLI" classify "$DATA/bad/overlap.json"
contains "$T/err" "overlap.json" "names the bad file"
expect 2 "classify unknown option" -- "$CLI" classify "$T/c5.json" --frob
expect 2 "classify bad max-tests" -- "$CLI" classify "$T/c5.json" --max-tests ten
expect 2 "classify negative max-tests" -- "$CLI" classify "$T/c5.json" --max-tests -1
expect 2 "classify bad time limit" -- "$CLI" classify "$T/c5.json" --time-limit soon
expect 2 "classify negative time limit" -- "$CLI" classify "$T/c5.json" --time-limit -1
expect 2 "classify unknown method" -- "$CLI" classify "$T/c5.json" --method simplex
expect 2 "classify bad tolerance" -- "$CLI" classify "$T/c5.json" --contact-tol 0
expect 2 "classify two files" -- "$CLI" classify "$T/c5.json" "$T/arch.json"
finish
