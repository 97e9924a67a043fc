# unstack render --action K of a plan with hands: at every action of an
# arch's plan the SVG has one hand mark (class "held") per body held after
# that action, counted here from the plan's actions, and the title names
# the count; the whole plan's title names H and its proof; a 3D dome
# planned with 2 hands draws its marks (SVG and PNG); bad --action values
# and --action without a plan of hands are exit 2 with nothing written.
. "$(dirname "$0")/lib.sh"
"$CLI" generate arch --voussoirs 9 -o "$T/arch.json" >/dev/null || bad "generate arch"
"$CLI" plan "$T/arch.json" --hands auto -o "$T/plan.json" >/dev/null || bad "plan --hands auto"
# held after each action K = 0..N, from the actions alone
python3 - "$T/plan.json" >"$T/held" <<'PY' || bad "read the plan's actions"
import json, sys
p = json.load(open(sys.argv[1]))
held = set()
print(0, 0, p["hands"])
for k, (verb, body) in enumerate(p["actions"], 1):
    if verb == "release": held.discard(body)
    else: held.add(body)
    print(k, len(held), p["hands"])
PY
N=$(($(wc -l <"$T/held") - 1))
[ "$N" -gt 2 ] && ok "the arch's plan has $N actions" || bad "the arch's plan has $N actions"
maxheld=0
while read -r k h H; do
  "$CLI" render "$T/arch.json" --plan "$T/plan.json" --action "$k" -o "$T/a.svg" 2>"$T/err" ||
    { bad "render --action $k"; continue; }
  got=$(grep -o 'class="held"' "$T/a.svg" | wc -l)
  [ "$got" -eq "$h" ] || bad "action $k: $got hand marks, $h held"
  grep -qF "action $k of $N" "$T/a.svg" && grep -qF "$h of H=$H hands held" "$T/a.svg" ||
    bad "action $k: the title does not say '$h of H=$H hands held'"
  [ "$h" -gt "$maxheld" ] && maxheld=$h
done <"$T/held"
ok "every action's hand marks and title match the actions (at most $maxheld held)"
[ "$maxheld" -ge 2 ] && ok "some action holds 2 bodies" || bad "no action holds 2 bodies"
expect 0 "render the whole hands plan" -- "$CLI" render "$T/arch.json" --plan "$T/plan.json" -o "$T/w.svg"
contains "$T/w.svg" "hands: 2 (proven minimal)" "the title names H and its proof"
[ "$(grep -c 'class="held"' "$T/w.svg")" -eq 0 ] && ok "no hand marks without --action" ||
  bad "hand marks without --action"
expect 0 "render --action as PNG" -- "$CLI" render "$T/arch.json" --plan "$T/plan.json" --action 3 -o "$T/a.png"

# actions that let the arch fall (one hand, each voussoir released at
# once): exit 1, the picture written, the title names the failing action
python3 - "$T/plan.json" "$T/fall.json" <<'PY' || bad "write the falling plan"
import json, sys
p = json.load(open(sys.argv[1]))
placed = [b for v, b in p["actions"] if v == "place"]
p["hands"], p["hands_lower"] = 1, 1
p["actions"] = [a for b in placed for a in (["place", b], ["release", b])]
json.dump(p, open(sys.argv[2], "w"))
PY
expect 1 "render of actions that let the arch fall" -- "$CLI" render "$T/arch.json" --plan "$T/fall.json" -o "$T/fall.svg"
contains "$T/fall.svg" "the actions fail at action" "the title names the failing action"
contains "$T/err" "the actions are invalid" "stderr says the actions are invalid"

# the viewer page of a hands plan carries H and the actions
expect 0 "render --html of a hands plan" -- "$CLI" render "$T/arch.json" --plan "$T/plan.json" -o "$T/h.html"
contains "$T/h.html" '"actions":[["place",' "the page carries the actions"

# 3D: a dome planned with 2 hands
"$CLI" generate dome --courses 2 --segments 6 -o "$T/dome.json" >/dev/null || bad "generate dome"
"$CLI" plan "$T/dome.json" --hands 2 -o "$T/dplan.json" >/dev/null || bad "plan dome --hands 2"
k=$(python3 -c "
import json,sys; a=json.load(open(sys.argv[1]))['actions']; h=set()
for k,(v,b) in enumerate(a,1):
    (h.discard if v=='release' else h.add)(b)
    if h: print(k, len(h)); break" "$T/dplan.json")
set -- $k
expect 0 "3D render --action $1" -- "$CLI" render "$T/dome.json" --plan "$T/dplan.json" --action "$1" -o "$T/d.svg"
[ "$(grep -o 'class="held"' "$T/d.svg" | wc -l)" -eq "$2" ] && ok "3D: $2 hand marks" || bad "3D: hand marks"
"$CLI" render "$T/dome.json" --plan "$T/dplan.json" --action 0 -o "$T/d0.svg" || bad "3D --action 0"
[ "$(grep -c '<polygon' "$T/d0.svg")" -eq 0 ] && ok "3D: nothing placed, no faces drawn" ||
  bad "3D: faces drawn before anything is placed"
[ "$(grep -c '<polygon' "$T/d.svg")" -gt 0 ] && ok "3D: the placed bodies' faces drawn" || bad "3D: no faces"
expect 0 "3D render --action as PNG" -- "$CLI" render "$T/dome.json" --plan "$T/dplan.json" --action "$1" -o "$T/d.png"

# bad --action values: exit 2, nothing written
"$CLI" plan "$T/arch.json" --max-group auto -o "$T/group.json" >/dev/null
for v in -1 x 1.5 "" $((N + 1)); do
  expect 2 "--action '$v'" -- "$CLI" render "$T/arch.json" --plan "$T/plan.json" --action "$v" -o "$T/bad.svg"
done
expect 2 "--action without --plan" -- "$CLI" render "$T/arch.json" --action 1 -o "$T/bad.svg"
expect 2 "--action with a plan without actions" -- "$CLI" render "$T/arch.json" --plan "$T/group.json" --action 1 -o "$T/bad.svg"
contains "$T/err" "needs a plan with actions" "the message says why"
expect 2 "--action with --html" -- "$CLI" render "$T/arch.json" --plan "$T/plan.json" --action 1 -o "$T/bad.html"
[ -e "$T/bad.svg" ] || [ -e "$T/bad.html" ] && bad "a bad --action wrote a file" || ok "a bad --action writes nothing"
finish
