# unstack count: exact counts on generated and fixture structures, JSON,
# refusals at the limits (exit 1), usage and input errors (exit 2).
# Reference values: a column of n blocks has n + 1; the pyramids and walls
# are the brute-force values pinned in tests/test_analysis_count.c
# (generator_scenes_pinned); pyramid 9 is where deletion-contraction and
# the frontier programme, two independent methods, are compared here.
. "$(dirname "$0")/lib.sh"

count_is() { # WANT DESCRIPTION FILE [options...]
  local want=$1 what=$2
  shift 2
  # a generous time limit: the values are checked here, not the speed (the
  # sanitizer build on a loaded machine is many times slower)
  expect 0 "count $what" -- "$CLI" count --time-limit 600 "$@"
  contains "$T/out" "count: $want connected sub-assemblies containing the ground" "$what = $want"
}

expect 0 "count --help" -- "$CLI" count --help
contains "$T/out" "usage: unstack count" "count help text"
expect 0 "unstack --help lists count" -- "$CLI" --help
contains "$T/out" "count FILE" "usage names count"

"$CLI" generate column --blocks 5 -o "$T/c5.json" >/dev/null
count_is 6 "column of 5 (a path)" "$T/c5.json"
contains "$T/out" "(tree, 5 bodies, 5 edges" "column: tree formula, 5 edges"
count_is 6 "column of 5, frontier" "$T/c5.json" --method frontier
count_is 6 "column of 5, contraction" "$T/c5.json" --method contract
"$CLI" generate column --blocks 1000 -o "$T/c1000.json" >/dev/null
count_is 1001 "column of 1000" "$T/c1000.json"

"$CLI" generate pyramid --rows 3 -o "$T/p3.json" >/dev/null
count_is 46 "pyramid of 3 rows" "$T/p3.json"
contains "$T/out" "frontier" "pyramid: frontier programme"
"$CLI" generate pyramid --rows 4 -o "$T/p4.json" >/dev/null
count_is 596 "pyramid of 4 rows" "$T/p4.json"
"$CLI" generate wall --rows 3 --cols 3 -o "$T/w33.json" >/dev/null
count_is 554 "wall 3 x 3" "$T/w33.json"
"$CLI" generate wall --rows 4 --cols 4 -o "$T/w44.json" >/dev/null
count_is 88841 "wall 4 x 4" "$T/w44.json"
count_is 88841 "wall 4 x 4, contraction" "$T/w44.json" --method contract
"$CLI" generate pyramid --rows 9 -o "$T/p9.json" >/dev/null
count_is 6495641491094 "pyramid of 9 rows" "$T/p9.json"
count_is 6495641491094 "pyramid of 9 rows, contraction" "$T/p9.json" --method contract
count_is 4 "column3 fixture" "$DATA/column3.json"

expect 0 "count --json" -- "$CLI" count "$T/p4.json" --json
contains "$T/out" '"count": "596"' "json: the count as a string"
contains "$T/out" '"status": "exact"' "json: status exact"
contains "$T/out" '"method": "frontier"' "json: method"
contains "$T/out" '"bodies": 10' "json: bodies"

# refusals are outcomes: exit 1 with a message on stdout
# (a wall of 869 contact pairs: loading reads no clock below 1024, so the
# limit, counted from the start, runs out in the count)
"$CLI" generate wall --rows 12 --cols 25 -o "$T/w1225.json" >/dev/null
expect 1 "wall 12 x 25 past a short time limit" -- "$CLI" count "$T/w1225.json" --time-limit 0.05
contains "$T/out" "refused, time limit" "time refusal says so"
expect 1 "past --max-bodies" -- "$CLI" count "$T/p4.json" --max-bodies 9
contains "$T/out" "refused, 10 bodies connected to the ground" "size refusal says so"
expect 1 "refused, json" -- "$CLI" count "$T/p4.json" --max-bodies 9 --json
contains "$T/out" '"count": null' "json: no count when refused"
contains "$T/out" '"status": "refused-size"' "json: refused status"

# usage and input errors: exit 2
expect 2 "count without file" -- "$CLI" count
expect 2 "count missing file" -- "$CLI" count "$T/nope.json"
contains "$T/err" "nope.json" "names the missing file"
expect 2 "count bad input" -- "$CLI" count "$DATA/bad/overlap.json"
contains "$T/err" "overlap.json" "names the bad file"
expect 2 "count unknown option" -- "$CLI" count "$T/c5.json" --frob
expect 2 "count bad time limit" -- "$CLI" count "$T/c5.json" --time-limit soon
expect 2 "count negative time limit" -- "$CLI" count "$T/c5.json" --time-limit -1
expect 2 "count bad max-bodies" -- "$CLI" count "$T/c5.json" --max-bodies 0
expect 2 "count unknown method" -- "$CLI" count "$T/c5.json" --method magic
expect 2 "count tree method on a pyramid" -- "$CLI" count "$T/p3.json" --method tree
contains "$T/err" "tree" "tree refusal of a cycle is explained"
expect 2 "count two files" -- "$CLI" count "$T/c5.json" "$T/p3.json"
finish
