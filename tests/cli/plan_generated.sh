# End to end: generate, check, plan, verify (with a second backend), render.
. "$(dirname "$0")/lib.sh"

gen_plan_verify() { # NAME STATUS GENERATE-ARGS...
  local name=$1 status=$2
  shift 2
  expect 0 "generate $name" -- "$CLI" generate "$@" -o "$T/$name.json"
  local want=0
  [ "$status" = found ] || want=1
  expect $want "plan $name is $status" -- "$CLI" plan "$T/$name.json" -o "$T/$name-plan.json"
  contains "$T/out" "$status" "plan $name summary says $status"
  contains "$T/$name-plan.json" "\"$status\"" "plan file of $name has status $status"
  if [ "$status" = found ]; then
    expect 0 "verify $name (lp)" -- "$CLI" verify "$T/$name.json" "$T/$name-plan.json"
    expect 0 "verify $name (lpsolve)" -- "$CLI" verify "$T/$name.json" "$T/$name-plan.json" --method lpsolve
    expect 0 "render $name" -- "$CLI" render "$T/$name.json" --plan "$T/$name-plan.json" -o "$T/$name.svg"
    contains "$T/$name.svg" "<svg" "svg of $name written"
  fi
}

gen_plan_verify column3 found column --blocks 3
gen_plan_verify column100 found column --blocks 100
gen_plan_verify pyramid found pyramid --rows 13
"$CLI" generate pyramid --rows 13 -o "$T/p13.json" >"$T/gen.out"; contains "$T/gen.out" "91 bodies" "13 rows = the 91-block pyramid"
gen_plan_verify wall found wall --rows 6 --cols 8
gen_plan_verify arch none arch --voussoirs 9 --radius 3 --thickness 0.6
gen_plan_verify random found random --rows 4 --width 5 --seed 7

# the random stacker is reproducible
expect 0 "random again, same seed" -- "$CLI" generate random --rows 4 --width 5 --seed 7 -o "$T/random2.json"
if cmp -s "$T/random.json" "$T/random2.json"; then ok "same seed, same file"; else bad "same seed gave different files"; fi

# the column comes apart top-down
expect 0 "plan column with certificates" -- "$CLI" plan "$T/column3.json" --certificates --stats -o "$T/c3.json"
contains "$T/c3.json" '"order": ["b3", "b2", "b1"]' "column order is top-down"
contains "$T/c3.json" '"certificate"' "certificates written"
contains "$T/out" "statistics" "--stats prints statistics"

# searches and directions agree on the verdict
for v in "--search bfs" "--direction up" "--order lowest" "--order input" "--method lpsolve"; do
  expect 0 "plan pyramid $v" -- "$CLI" plan "$T/column3.json" $v
done

# check: the arch stands whole, one stone less it does not
expect 0 "check arch" -- "$CLI" check "$T/arch.json"
contains "$T/out" "stable" "check prints stable"
expect 0 "check --forces" -- "$CLI" check "$T/column3.json" --forces
contains "$T/out" "fn =" "forces printed"
expect 0 "render forces" -- "$CLI" render "$T/arch.json" --forces -o "$T/arch.svg"

# limits
expect 1 "max-tests limit" -- "$CLI" plan "$T/column100.json" --max-tests 3 -o "$T/lim.json"
contains "$T/lim.json" '"limit"' "limit status written"
finish
