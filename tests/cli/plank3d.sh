# 3D end to end: a box resting on a fixed plank tilted by theta (both given
# as `box` with Euler angles, contacts found by the 3D detector) stands iff
# tan(theta) <= mu. `check` decides mu = tan(theta) (1 +- 1e-5) both ways,
# `classify` finds the critical friction mu* = tan(theta) to 1e-4, for
# slopes about y and about a tilted axis (Euler angles on two axes, so the
# slope direction falls anywhere in the contact frames); a tower plans and
# verifies; the LCP methods refuse 3D with a message.
. "$(dirname "$0")/lib.sh"

# plank FILE THETA_DEG AZIMUTH_DEG MU: the box's centre 0.2 along the
# plank's normal (half of each thickness), both turned alike
plank() {
  python3 - "$@" <<'EOF'
import json, math, sys
out, th, az, mu = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
t, a = math.radians(th), math.radians(az)
# "euler": [rx, ry, rz], R = Rz Ry Rx (docs/format.md): R = Rz(az) Ry(th); the plank's normal is R (0, 0, 1)
n = (math.cos(a) * math.sin(t), math.sin(a) * math.sin(t), math.cos(t))
c0 = (0.3, -0.2, 2.0)
c1 = [c0[i] + 0.2 * n[i] for i in range(3)]
s = {"dimension": 3, "ground": False, "friction": float(mu), "bodies": [
    {"id": "plank", "fixed": True, "box": {"center": list(c0), "size": [4, 3, 0.2], "euler": [0, th, az]}},
    {"id": "block", "box": {"center": c1, "size": [0.5, 0.7, 0.2], "euler": [0, th, az]}}]}
json.dump(s, open(out, "w"))
EOF
}

for case in "20 0" "35 0" "12 57" "41 -130"; do
  set -- $case
  tan=$(python3 -c "import math; print(repr(math.tan(math.radians($1))))")
  hi=$(python3 -c "print(repr($tan * (1 + 1e-5)))")
  lo=$(python3 -c "print(repr($tan * (1 - 1e-5)))")
  plank "$T/hi.json" "$1" "$2" "$hi"
  plank "$T/lo.json" "$1" "$2" "$lo"
  expect 0 "slope $1 deg, azimuth $2: stands at mu = tan (1 + 1e-5)" -- "$CLI" check "$T/hi.json"
  expect 1 "slope $1 deg, azimuth $2: slides at mu = tan (1 - 1e-5)" -- "$CLI" check "$T/lo.json"
  "$CLI" classify "$T/hi.json" >"$T/cls" 2>&1
  mustar=$(sed -n 's/.*mu\* = \([0-9.e+-]*\).*/\1/p' "$T/cls" | head -1)
  if [ -n "$mustar" ] && python3 -c "import sys; sys.exit(0 if abs($mustar - $tan) <= 1e-4 else 1)"; then
    ok "slope $1 deg: critical friction $mustar = tan $tan to 1e-4"
  else
    bad "slope $1 deg: critical friction '$mustar', wanted $tan"; sed 's/^/    /' "$T/cls"
  fi
done

"$CLI" generate tower --blocks 8 --jitter 25 --seed 4 -o "$T/tower.json" >/dev/null
expect 0 "a jittered tower of boxes plans" -- "$CLI" plan "$T/tower.json" -o "$T/tower-plan.json"
expect 0 "and its plan verifies" -- "$CLI" verify "$T/tower.json" "$T/tower-plan.json"
expect 0 "lp_solve plans it too" -- "$CLI" plan "$T/tower.json" --method lpsolve -o "$T/tower-plan2.json"
for m in lcp lcp-reuse lp-lcp; do
  expect 0 "$m decides the 3D tower: stands" -- "$CLI" check "$T/tower.json" --method $m
  expect 0 "$m plans it" -- "$CLI" plan "$T/tower.json" --method $m -o "$T/tower-$m.json"
  expect 0 "and its plan verifies" -- "$CLI" verify "$T/tower.json" "$T/tower-$m.json"
done
finish
