# verify rejects a wrong order and names the step that fails.
. "$(dirname "$0")/lib.sh"
"$CLI" generate column --blocks 4 -o "$T/col.json" >/dev/null
cat >"$T/wrong.json" <<'PLAN'
{"format": "unstack-plan", "version": 1, "status": "found", "order": ["b4", "b1", "b2", "b3"]}
PLAN
expect 1 "wrong order rejected" -- "$CLI" verify "$T/col.json" "$T/wrong.json"
contains "$T/out" "step 2" "names step 2"
contains "$T/out" "'b1'" "names the body removed"
cat >"$T/short.json" <<'PLAN'
{"format": "unstack-plan", "version": 1, "status": "found", "order": ["b4", "b3"]}
PLAN
expect 1 "incomplete order rejected" -- "$CLI" verify "$T/col.json" "$T/short.json"
contains "$T/out" "incomplete" "says incomplete"
cat >"$T/right.json" <<'PLAN'
{"format": "unstack-plan", "version": 1, "status": "found", "order": ["b4", "b3", "b2", "b1"]}
PLAN
expect 0 "right order accepted" -- "$CLI" verify "$T/col.json" "$T/right.json"
cat >"$T/unknown.json" <<'PLAN'
{"format": "unstack-plan", "version": 1, "status": "found", "order": ["b4", "b9"]}
PLAN
expect 2 "unknown id in plan" -- "$CLI" verify "$T/col.json" "$T/unknown.json"
contains "$T/err" "b9" "message names the unknown id"
cat >"$T/undecided.json" <<'PLAN'
{"format": "unstack-plan", "version": 1, "status": "undecided", "order": []}
PLAN
expect 3 "a plan with status undecided is undecided (exit 3), not invalid" -- "$CLI" verify "$T/col.json" "$T/undecided.json"
contains "$T/out" "undecided" "says undecided"
printf '{"status": "found", "order": [' >"$T/broken.json"
expect 2 "malformed plan" -- "$CLI" verify "$T/col.json" "$T/broken.json"
contains "$T/err" "broken.json" "message names the plan file"
finish
