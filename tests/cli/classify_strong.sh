# unstack classify, strong stability with friction (docs/classify.md):
# hand-derived answers. The pinched box (tests/data/pinched.json, its
# _note): stands, not strongly (free fall with no force at either wall is
# a solution), by both methods, the witness in JSON moving the box down;
# the same box resting on the ground between the walls: every admissible
# motion raises it, strong yes; a frictionless column: yes by the theorem;
# a box sliding on a slope steeper than its friction: no; --strong off and
# a bad --strong word.
. "$(dirname "$0")/lib.sh"

json_is() {
  if command -v jq >/dev/null; then
    if jq -e "$2" "$1" >/dev/null 2>&1; then ok "$3"; else bad "$3 ($2)"; sed 's/^/    /' "$1" | head -5; fi
  else
    ok "$3 (skipped: no jq)"
  fi
}

for m in mip enum; do
  expect 0 "classify pinched --strong $m" -- "$CLI" classify "$DATA/pinched.json" --strong $m
  contains "$T/out" "stands: yes" "pinched stands ($m)"
  contains "$T/out" "strong: no (a motion the dynamics allow (checked)" "pinched: not strongly stable ($m)"
  expect 0 "classify pinched --json --strong $m" -- "$CLI" classify "$DATA/pinched.json" --json --strong $m
  json_is "$T/out" '.stands == true and .strong == false and .strong_witness.bodies[0].id == "box" and .strong_witness.bodies[0].a[1] < 0' "pinched: the witness moves the box down ($m)"
done

cat >"$T/seated.json" <<'EOF2'
{"friction": 0.5, "bodies": [
 {"id": "left", "fixed": true, "polygon": [[0, 0], [1, 0], [1, 3], [0, 3]]},
 {"id": "right", "fixed": true, "polygon": [[2, 0], [3, 0], [3, 3], [2, 3]]},
 {"id": "box", "polygon": [[1, 0], [2, 0], [2, 1], [1, 1]]}]}
EOF2
expect 0 "classify seated box" -- "$CLI" classify "$T/seated.json" --json
json_is "$T/out" '.stands == true and .strong == true and .strong_witness == null' "seated box: strongly stable"

"$CLI" generate column --blocks 3 -o "$T/c3.json" >/dev/null
expect 0 "classify column" -- "$CLI" classify "$T/c3.json"
contains "$T/out" "strong: yes (frictionless: strong = weak (Gauss's principle))" "column: yes by the theorem"

cat >"$T/slope.json" <<'EOF2'
{"friction": 0.5, "gravity": [6.867, -9.81], "bodies": [
 {"id": "box", "polygon": [[0, 0], [1, 0], [1, 1], [0, 1]]}]}
EOF2
expect 0 "classify a box on a steep slope" -- "$CLI" classify "$T/slope.json" --json
json_is "$T/out" '.stands == false and .strong == false' "steep slope: neither weak nor strong"

expect 0 "classify --strong off" -- "$CLI" classify "$DATA/pinched.json" --strong off --json
json_is "$T/out" '.strong == null and .strong_note == "not asked"' "--strong off: not asked"
expect 2 "classify --strong bad" -- "$CLI" classify "$DATA/pinched.json" --strong maybe
contains "$T/err" "--strong takes auto, mip, enum or off" "bad --strong word named"
finish
