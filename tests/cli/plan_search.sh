# The planner's searches from the command line: the assemble default, none
# with the blocked bodies named, steps of several bodies, removal
# kinematics checked by verify, every search mode agreeing.
. "$(dirname "$0")/lib.sh"

"$CLI" generate arch --voussoirs 7 -o "$T/arch.json" >/dev/null

# none, with the bodies that cannot be removed named, in the plan and picture
expect 1 "arch: none" -- "$CLI" plan "$T/arch.json" -o "$T/arch-plan.json"
contains "$T/out" "cannot be removed with steps of up to 1 body" "summary names the blocked bodies"
contains "$T/arch-plan.json" '"blocked": [' "plan file lists the blocked bodies"
expect 0 "render a none plan" -- "$CLI" render "$T/arch.json" --plan "$T/arch-plan.json" -o "$T/arch.svg"
contains "$T/arch.svg" "cannot be removed" "picture marks the blocked bodies"
expect 1 "verify refuses a none plan" -- "$CLI" verify "$T/arch.json" "$T/arch-plan.json"

# the smallest group size, written as steps and verified step by step
expect 0 "arch: --max-group auto" -- "$CLI" plan "$T/arch.json" --max-group auto -o "$T/arch-k.json"
contains "$T/out" "steps of up to" "summary gives the group size"
contains "$T/arch-k.json" '"order": [[' "a step of several bodies is an array"
expect 0 "verify the group plan" -- "$CLI" verify "$T/arch.json" "$T/arch-k.json"
contains "$T/out" "steps re-checked" "verify counts steps"
expect 0 "render the group plan" -- "$CLI" render "$T/arch.json" --plan "$T/arch-k.json" -o "$T/arch-k.svg"

# an arch next to loose blocks: none at once, the voussoirs named
expect 0 "generate arch --loose 30" -- "$CLI" generate arch --voussoirs 7 --loose 30 -o "$T/al.json"
contains "$T/out" "37 bodies" "7 voussoirs and 30 loose blocks"
expect 1 "arch + 30 loose: none" -- "$CLI" plan "$T/al.json"
contains "$T/out" "cannot be removed with steps of up to 1 body: b2, b3, b4, b5, b6" "names the voussoirs"
expect 2 "--loose -1" -- "$CLI" generate arch --loose -1 -o "$T/x.json"

# every search mode and direction gives the same answer
"$CLI" generate random --rows 8 --width 6 --seed 3 -o "$T/r.json" >/dev/null
for s in assemble dfs bfs random; do
  for d in down up; do
    expect 0 "random stack: $s $d finds a plan" -- "$CLI" plan "$T/r.json" --search $s --direction $d -o "$T/r-$s-$d.json"
    expect 0 "random stack: $s $d plan verifies" -- "$CLI" verify "$T/r.json" "$T/r-$s-$d.json"
  done
  expect 1 "arch: $s is none" -- "$CLI" plan "$T/arch.json" --search $s
done
expect 0 "rules off still finds" -- "$CLI" plan "$T/r.json" --search dfs --rules memo
expect 0 "rule list" -- "$CLI" plan "$T/r.json" --search dfs --rules memo,ground,union --stats
contains "$T/out" "rules: ground saved" "statistics report the rules"

# removal kinematics: the block under the bridge must wait for the lintel
expect 2 "assemble refuses kinematics" -- "$CLI" plan "$DATA/bridge.json" --removal up
contains "$T/err" "graph search" "the refusal says what to use"
expect 0 "dfs with removal up" -- "$CLI" plan "$DATA/bridge.json" --search dfs --removal up --order lowest -o "$T/b.json"
expect 0 "the plan verifies, kinematics included" -- "$CLI" verify "$DATA/bridge.json" "$T/b.json"
contains "$T/out" "lifted straight up" "verify checked the lifting"
sed 's/"order": \[[^]]*\]/"order": ["b", "lintel", "pr", "pl"]/' "$T/b.json" >"$T/b2.json"
expect 1 "verify catches a blocked lift" -- "$CLI" verify "$DATA/bridge.json" "$T/b2.json"
contains "$T/out" "'lintel' is in the way" "verify names the body in the way"

# where the greedy is stuck the exact decision settles it, within its budget
expect 0 "greedy stuck, exact finds" -- "$CLI" plan "$DATA/greedy_stuck.json" --stats
contains "$T/out" "sets searched exhaustively 1" "the exact decision ran"
expect 1 "a cut exact decision is a limit" -- "$CLI" plan "$DATA/greedy_stuck.json" --exact-tests 3
contains "$T/out" "limit" "status limit"
contains "$T/out" "not reached by the greedy" "the summary says what the greedy left"
expect 2 "--exact-tests -1" -- "$CLI" plan "$DATA/greedy_stuck.json" --exact-tests -1

# bad option values
expect 2 "--max-group 0" -- "$CLI" plan "$T/arch.json" --max-group 0
expect 2 "--max-group x" -- "$CLI" plan "$T/arch.json" --max-group x
expect 2 "--search nope" -- "$CLI" plan "$T/arch.json" --search nope
expect 2 "--removal sideways" -- "$CLI" plan "$T/arch.json" --removal sideways
expect 2 "--rules bogus" -- "$CLI" plan "$T/arch.json" --rules memo,bogus
expect 2 "--seed -1" -- "$CLI" plan "$T/arch.json" --search random --seed -1
expect 2 "groups with dfs" -- "$CLI" plan "$T/arch.json" --search dfs --max-group 2

finish
