# --time-limit counts from the command's start, reading and finalizing the
# file included (issue 24, point 2): a limit that runs out while loading
# answers undecided (exit 3) with a message saying so, and writes nothing.
# The limit 1e-9 s has always run out when the clock is first read, and
# loading reads it every 1024 bodies, hull points or contact pairs (and
# every MB of text), so these outcomes do not depend on the machine.
. "$(dirname "$0")/lib.sh"
# a 3D body of 5,000 points on a sphere (all hull vertices), resting on z = 0
awk 'BEGIN { srand(7); printf "{\"dimension\": 3, \"bodies\": [{\"id\": \"ball\", \"vertices\": [[0, 0, 0]";
  for (i = 0; i < 5000; i++) { z = 2 * rand() - 1; t = 6.283185307 * rand(); r = sqrt(1 - z * z);
    printf ", [%.12f, %.12f, %.12f]", r * cos(t), r * sin(t), z + 1 }
  print "]}]}" }' >"$T/ball.json"
expect 3 "check: the hull cut by the limit" -- "$CLI" check "$T/ball.json" --time-limit 1e-9
contains "$T/out" "undecided: loading was cut by the time limit" "check: says loading was cut"
contains "$T/out" "convex hull of body 'ball'" "check: names the hull and the body"
"$CLI" check "$T/ball.json" --time-limit 600 >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] || [ $rc -eq 1 ] && ok "check: with room, a verdict (exit $rc)" || bad "check with room: exit $rc"
# contact detection (990 bricks: 2,889 pairs) and reading (10,000 bodies)
"$CLI" generate wall --rows 30 --cols 33 -o "$T/wall.json" >/dev/null
"$CLI" generate wall --rows 100 --cols 100 -o "$T/big.json" >/dev/null
expect 3 "plan: contact detection cut by the limit" -- "$CLI" plan "$T/wall.json" --time-limit 1e-9 -o "$T/p.json"
contains "$T/out" "contact detection" "plan: names contact detection"
[ -e "$T/p.json" ] && bad "plan: wrote a plan file" || ok "plan: no plan file"
expect 3 "check: reading cut by the limit" -- "$CLI" check "$T/big.json" --time-limit 1e-9
contains "$T/out" "loading was cut by the time limit" "check big: says loading was cut"
expect 3 "verify: loading cut by the limit" -- "$CLI" verify "$T/big.json" "$T/wall.json" --time-limit 1e-9
expect 3 "render: loading cut by the limit" -- "$CLI" render "$T/wall.json" --time-limit 1e-9 -o "$T/w.svg"
[ -e "$T/w.svg" ] && bad "render: wrote a picture" || ok "render: no picture"
# generate --time-limit (random3d reads the clock before every drop)
expect 3 "generate random3d: stopped by the limit" -- "$CLI" generate random3d --blocks 50 --time-limit 1e-9 -o "$T/r.json"
contains "$T/out" "random3d: time limit reached" "generate: says it stopped"
[ -e "$T/r.json" ] && bad "generate: wrote a file" || ok "generate: nothing written"
# stacker and random read it between row attempts (and their stability
# tests stop at it); the other kinds while finding contacts
for kind in "stacker --rows 80 --width 40" "random --rows 40 --width 8" "wall --rows 300 --cols 300"; do
  k=${kind%% *}
  expect 3 "generate $k: stopped by the limit" -- "$CLI" generate $kind --time-limit 1e-9 -o "$T/g.json"
  contains "$T/out" "time limit" "generate $k: says it stopped"
  [ -e "$T/g.json" ] && bad "generate $k: wrote a file" || ok "generate $k: nothing written"
done
expect 0 "generate stacker with room" -- "$CLI" generate stacker --rows 6 --width 6 --time-limit 600 -o "$T/g.json"
expect 0 "generate random3d with room" -- "$CLI" generate random3d --blocks 3 --time-limit 600 -o "$T/r.json"
expect 2 "generate --time-limit 0" -- "$CLI" generate random3d --time-limit 0 -o "$T/r0.json"
finish
