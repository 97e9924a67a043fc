# plan --hands: the arch's proven minimum, H - 1 none, the plan file's
# actions accepted by verify; verify rejects bad action lists naming the
# action's index (exit 2) and a release that falls (exit 1); an old plan
# verifies as before; classify names the buttressing class; with
# --certificates the independent Python checker replays the actions and
# rejects corrupted ones.
. "$(dirname "$0")/lib.sh"
"$CLI" generate arch --voussoirs 7 -o "$T/arch.json" >/dev/null
expect 0 "arch: --hands auto finds a plan" -- "$CLI" plan "$T/arch.json" --hands auto -o "$T/auto.json"
contains "$T/out" "2 hands: the minimum (proven)" "the minimum is 2, proven"
contains "$T/auto.json" '"hands": 2' "plan file: hands"
contains "$T/auto.json" '["place", "b1"]' "plan file: actions"
expect 0 "verify accepts the action plan" -- "$CLI" verify "$T/arch.json" "$T/auto.json"
contains "$T/out" "at most 2 hands" "verify names the hands"
expect 1 "arch: one hand is none" -- "$CLI" plan "$T/arch.json" --hands 1
contains "$T/out" "none" "says none"
expect 0 "arch: --hands 2" -- "$CLI" plan "$T/arch.json" --hands=2 -o "$T/two.json"
expect 0 "verify accepts it" -- "$CLI" verify "$T/arch.json" "$T/two.json"
expect 2 "--hands 0 is a usage error" -- "$CLI" plan "$T/arch.json" --hands 0
expect 2 "--hands x is a usage error" -- "$CLI" plan "$T/arch.json" --hands x

expect 0 "classify the arch" -- "$CLI" classify "$T/arch.json" --strong off
contains "$T/out" "buttressing: needed: the smallest number of hands holding bodies still is 2 (proven" "classify: needs buttressing, 2 hands, proven"

"$CLI" generate column --blocks 3 -o "$T/col.json" >/dev/null
expect 0 "old plan verifies as before" -- "$CLI" plan "$T/col.json" -o "$T/old.json"
expect 0 "old plan verify" -- "$CLI" verify "$T/col.json" "$T/old.json"
contains "$T/out" "valid: 3 removals" "old report unchanged"
expect 0 "classify the column" -- "$CLI" classify "$T/col.json"
if grep -q buttressing "$T/out"; then bad "a column needs no buttressing line"; else ok "no buttressing line for a column"; fi

plan() { # plan HANDS ACTIONS ORDER
  printf '{"status": "found", "hands": %s, "order": [%s], "actions": [%s]}\n' "$1" "$3" "$2"
}
plan 1 '["place", "b1"], ["place", "b1"], ["release", "b1"]' '"b1"' >"$T/twice.json"
expect 2 "a body placed twice" -- "$CLI" verify "$T/col.json" "$T/twice.json"
contains "$T/err" "action 1" "names the action's index"
plan 2 '["place", "b1"], ["release", "b2"]' '"b1"' >"$T/unheld.json"
expect 2 "a release of a body not held" -- "$CLI" verify "$T/col.json" "$T/unheld.json"
contains "$T/err" "action 1" "names the action's index"
plan 1 '["place", "b1"], ["place", "b2"], ["release", "b1"], ["release", "b2"], ["place", "b3"], ["release", "b3"]' '"b3", "b2", "b1"' >"$T/many.json"
expect 2 "more than H held" -- "$CLI" verify "$T/col.json" "$T/many.json"
contains "$T/err" "action 1" "names the action's index"
plan 1 '["put", "b1"]' '"b1"' >"$T/verb.json"
expect 2 "an unknown verb" -- "$CLI" verify "$T/col.json" "$T/verb.json"
contains "$T/err" "actions[0]" "names the entry"
plan 1 '["place", "b2"], ["release", "b2"], ["place", "b1"], ["release", "b1"], ["place", "b3"], ["release", "b3"]' '"b3", "b1", "b2"' >"$T/falls.json"
expect 1 "a release that falls" -- "$CLI" verify "$T/col.json" "$T/falls.json"
contains "$T/out" "action 1" "names the release"
plan 1 '["place", "b1"], ["release", "b1"], ["place", "b2"], ["release", "b2"], ["place", "b3"], ["release", "b3"]' '"b1", "b2", "b3"' >"$T/order.json"
expect 2 "order not the placements reversed" -- "$CLI" verify "$T/col.json" "$T/order.json"
# the independent Python checker replays action plans with certificates
CHECK="python3 $(cd "$(dirname "$0")/.." && pwd)/independent/check_plan.py"
expect 0 "arch: --hands auto --certificates" -- "$CLI" plan "$T/arch.json" --hands auto --certificates -o "$T/cert.json"
contains "$T/cert.json" '"release_certificates"' "plan file: release certificates"
expect 0 "the independent checker passes the action plan" -- $CHECK "$T/arch.json" "$T/cert.json" --quiet
contains "$T/out" "7 releases checked" "every release checked"
"$CLI" generate pyramid3d --rows 3 -o "$T/p3.json" >/dev/null
expect 0 "3D: --hands auto --certificates" -- "$CLI" plan "$T/p3.json" --hands auto --certificates -o "$T/p3c.json"
expect 0 "3D: the independent checker passes" -- $CHECK "$T/p3.json" "$T/p3c.json" --quiet
for seed in 1 2 3 4 5; do
  "$CLI" generate stacker --rows 4 --width 5 --seed $seed -o "$T/st$seed.json" >/dev/null
  "$CLI" plan "$T/st$seed.json" --hands auto --certificates -o "$T/st$seed-plan.json" >"$T/out" 2>&1
  if [ $? -eq 0 ]; then
    expect 0 "stacker seed $seed: the checker passes the action plan" -- $CHECK "$T/st$seed.json" "$T/st$seed-plan.json" --quiet
  else
    bad "stacker seed $seed: plan --hands auto found nothing"; sed 's/^/    /' "$T/out" | head -5
  fi
done
# corrupted: a force scaled by 1.5, a held body dropped, one hand too few
python3 - "$T/cert.json" "$T" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
q = json.loads(json.dumps(p))
c = q["release_certificates"][1]["contacts"][0]
c["force"] = [1.5 * v for v in c["force"]]
c["force_xyz"] = [1.5 * v for v in c["force_xyz"]]
json.dump(q, open(sys.argv[2] + "/scaled.json", "w"))
q = json.loads(json.dumps(p))
q["release_certificates"][1]["held"] = []
json.dump(q, open(sys.argv[2] + "/unheld.json", "w"))
q = json.loads(json.dumps(p))
q["hands"] = 1
json.dump(q, open(sys.argv[2] + "/onehand.json", "w"))
PY
expect 1 "checker: a scaled force fails" -- $CHECK "$T/arch.json" "$T/scaled.json" --quiet
expect 1 "checker: a held body left out of the certificate fails" -- $CHECK "$T/arch.json" "$T/unheld.json" --quiet
expect 1 "checker: more bodies held than hands fails" -- $CHECK "$T/arch.json" "$T/onehand.json" --quiet
contains "$T/out" "more than 1 hands" "names the hands"
finish
