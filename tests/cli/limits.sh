# Time limits hold inside the solvers (check, verify, plan): a limit that
# runs out answers undecided / limit, never an error and never a verdict;
# the progress line shows only on a terminal.
. "$(dirname "$0")/lib.sh"
"$CLI" generate wall --rows 30 --cols 33 -o "$T/wall.json" >/dev/null
"$CLI" plan "$T/wall.json" -o "$T/plan.json" >/dev/null
expect 3 "check with a time limit that runs out" -- "$CLI" check "$T/wall.json" --local off --time-limit 0.001
contains "$T/out" "undecided" "check: undecided"
contains "$T/out" "time limit" "check: says why"
# (verify walks a plan in microseconds per step since the plumb lines are
# memoised: a 10,000-block wall, so that the 1 ms floor of a limit runs out)
"$CLI" generate wall --rows 100 --cols 100 -o "$T/big.json" >/dev/null
"$CLI" plan "$T/big.json" -o "$T/big-plan.json" >/dev/null
expect 3 "verify with a time limit that runs out" -- "$CLI" verify "$T/big.json" "$T/big-plan.json" --time-limit 0.001
contains "$T/out" "time limit" "verify: says why"
# (the limit counts from the start, so it may run out while the file is
# loading: undecided, exit 3; in the search: limit, exit 1)
"$CLI" plan "$T/wall.json" --search dfs --time-limit 0.001 -o "$T/p2.json" >"$T/out" 2>"$T/err"
rc=$?
case $rc in
  1) ok "plan with a time limit that runs out: limit" ;;
  3) contains "$T/out" "loading was cut by the time limit" "plan with a time limit that runs out while loading" ;;
  *) bad "plan with a time limit that runs out: exit $rc" ;;
esac
contains "$T/out" "limit" "plan: status limit"
expect 0 "check with room" -- "$CLI" check "$T/wall.json" --time-limit 60
expect 0 "verify with room" -- "$CLI" verify "$T/wall.json" "$T/plan.json" --time-limit 60
for v in 0 -1 abc inf; do
  expect 2 "check --time-limit $v" -- "$CLI" check "$T/wall.json" --time-limit "$v"
  contains "$T/err" "positive number of seconds" "check --time-limit $v: says what it needs"
done
expect 2 "verify --time-limit without a value" -- "$CLI" verify "$T/wall.json" "$T/plan.json" --time-limit

# progress: silent when stderr is not a terminal, a line when it is
expect 0 "plan, stderr a file" -- "$CLI" plan "$T/wall.json" -o "$T/p3.json"
if [ -s "$T/err" ]; then bad "plan wrote to stderr"; sed 's/^/    /' "$T/err" | head -3; else ok "plan: stderr silent"; fi
expect 0 "verify, stderr a file" -- "$CLI" verify "$T/wall.json" "$T/plan.json"
if [ -s "$T/err" ]; then bad "verify wrote to stderr"; else ok "verify: stderr silent"; fi
script -qec "'$CLI' plan '$T/wall.json' -o '$T/p4.json'" /dev/null >"$T/tty" 2>&1
contains "$T/tty" "tests/s" "plan on a terminal: a progress line"
script -qec "'$CLI' verify '$T/wall.json' '$T/plan.json'" /dev/null >"$T/tty" 2>&1
contains "$T/tty" "verify: " "verify on a terminal: a progress line"
finish
