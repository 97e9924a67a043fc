# Plans re-checked by an independent implementation (issue 11):
# tests/independent/check_plan.py, Python standard library only, no code
# shared with the C library, recomputes every body's mass and centre of mass
# from the structure file and checks every step's certificate (equilibrium of
# every present movable body, sign and Coulomb cone of every force, contacts
# that the geometry allows, between present bodies; a found plan removes
# every movable body once). Generated 2D and 3D structures of tens of bodies
# are planned with --certificates and must pass; corrupted plans (a force
# scaled by 1.5, a flipped normal, a point moved off the surfaces, a missing
# step, a contact with a removed body, a friction coefficient below the one
# the forces need) must fail with exit 1, unreadable input exit 2.
# docs/independent_check.md.
. "$(dirname "$0")/lib.sh"
CHECK="python3 $(cd "$(dirname "$0")/.." && pwd)/independent/check_plan.py"

# plan_and_check NAME [plan options...]: $T/NAME.json must plan (found) and pass
plan_and_check() {
  local name=$1
  shift
  expect 0 "$name: plan --certificates" -- "$CLI" plan "$T/$name.json" --certificates "$@" -o "$T/$name-plan.json"
  expect 0 "$name: the independent check passes" -- $CHECK "$T/$name.json" "$T/$name-plan.json" --quiet
  grep -E '^  worst (force|torque|cone) ' "$T/out" | sed 's/^/    /'
}

# gen NAME generate-arguments...
gen() {
  local name=$1
  shift
  "$CLI" generate "$@" -o "$T/$name.json" >"$T/out" 2>&1 || { bad "$name: generate $*"; cat "$T/out"; }
}

# 2D
gen column column --blocks 10 && plan_and_check column
gen pyramid pyramid --rows 6 && plan_and_check pyramid
gen wall wall --rows 5 --cols 5 && plan_and_check wall
gen arch arch --voussoirs 9 --loose 4
expect 1 "arch: one at a time is none" -- "$CLI" plan "$T/arch.json" --certificates -o "$T/arch-none.json"
expect 0 "arch: the none plan's claims pass" -- $CHECK "$T/arch.json" "$T/arch-none.json" --quiet
plan_and_check arch --max-group auto
gen stacker stacker --rows 10 --width 8 --seed 3 && plan_and_check stacker
cp "$T/stacker.json" "$T/stacker-dfs.json" && plan_and_check stacker-dfs --search dfs --method lpsolve
gen random random --rows 6 --width 4 --seed 2 && plan_and_check random
cp "$DATA/explicit.json" "$T/explicit.json" && plan_and_check explicit

# 3D
gen tower tower --blocks 12 --jitter 30 --seed 4 && plan_and_check tower
gen pyramid3d pyramid3d --rows 3 && plan_and_check pyramid3d
gen wall3d wall3d --rows 3 --cols 4 && plan_and_check wall3d
if "$CLI" generate --help 2>&1 | grep -q -- --returns; then
  gen wall3d-returns wall3d --rows 3 --cols 3 --returns 2 && plan_and_check wall3d-returns
fi
gen jenga jenga --levels 6 --remove 2:2,4:1,4:3 && plan_and_check jenga
gen random3d random3d --blocks 20 --width 3 --seed 5 && plan_and_check random3d
gen dome dome --courses 3 --segments 8 --oculus 30 --cap --chamfer 0 && plan_and_check dome
# boxes on a fixed plank tilted 41 degrees about a tilted axis (as in
# plank3d.sh), friction 1e-5 above tan(41 deg): forces at the cone's edge;
# and a compound body (box + wedge) under a box turned by a quaternion
python3 - "$T" <<'EOF'
import json, math, sys
T = sys.argv[1]
th, az = 41.0, -130.0
t, a = math.radians(th), math.radians(az)
n = (math.cos(a) * math.sin(t), math.sin(a) * math.sin(t), math.cos(t))
c0 = (0.3, -0.2, 2.0)
def plank(mu):
    return {"dimension": 3, "ground": False, "friction": mu, "bodies": [
        {"id": "plank", "fixed": True, "box": {"center": list(c0), "size": [4, 3, 0.2], "euler": [0, th, az]}},
        {"id": "block", "mass": 0.1, "box": {"center": [c0[i] + 0.2 * n[i] for i in range(3)],
                                             "size": [0.5, 0.7, 0.2], "euler": [0, th, az]}},
        {"id": "top", "box": {"center": [c0[i] + 0.5 * n[i] for i in range(3)],
                                            "size": [0.4, 0.5, 0.4], "euler": [0, th, az]}}]}
json.dump(plank(math.tan(t) * (1 + 1e-5)), open(T + "/plank.json", "w"))
json.dump(plank(math.tan(t) * (1 - 1e-4)), open(T + "/plank-lowmu.json", "w"))
c, s = math.cos(math.radians(15)), math.sin(math.radians(15))
json.dump({"dimension": 3, "bodies": [
    {"id": "base", "box": {"center": [0.5, 0.5, 0.25], "size": [1, 1, 0.5]}},
    {"id": "top", "box": {"center": [0.5, 0.5, 0.75], "size": [1, 1, 0.5], "euler": [0, 0, 45]}},
    {"id": "ell", "mass": 3, "parts": [
        {"box": {"center": [3, 0.5, 0.5], "size": [1, 1, 1]}},
        {"vertices": [[3.5, 0, 0], [5, 0, 0], [3.5, 1, 0], [5, 1, 0], [3.5, 0, 0.5], [3.5, 1, 0.5]]}]},
    {"id": "cap", "density": 2.5, "friction": 0.9,
     "box": {"center": [3, 0.5, 1.2], "size": [0.6, 0.6, 0.4], "rotation": [2 * c, 0, 0, 2 * s]}}]},
    open(T + "/compound.json", "w"))
EOF
plan_and_check plank
plan_and_check compound

# The check must be able to fail. corrupt IN OUT KIND: edit a plan
python3 - "$T" <<'EOF'
import json, sys
T = sys.argv[1]
def load(n): return json.load(open("%s/%s" % (T, n)))
def save(p, n): json.dump(p, open("%s/%s" % (T, n), "w"))
def loaded(step, ground=True):  # the contact carrying the largest force
    cs = [c for c in step["certificate"]["contacts"] if ground or c["a"] != "ground"]
    return max(cs, key=lambda c: sum(x * x for x in c["force_xyz"]))
for src in ("stacker", "random3d"):
    # one force scaled by 1.5 (both forms, so only equilibrium can see it)
    p = load(src + "-plan.json")
    c = loaded(p["steps"][2])
    c["force"] = [1.5 * x for x in c["force"]]
    c["force_xyz"] = [1.5 * x for x in c["force_xyz"]]
    save(p, src + "-scaled.json")
    # a normal flipped: the force now pulls
    p = load(src + "-plan.json")
    c = loaded(p["steps"][1], ground=False)
    c["normal"] = [-x for x in c["normal"]]
    save(p, src + "-flipped.json")
    # a contact point moved off both bodies (by a tenth of a block, sideways and up)
    p = load(src + "-plan.json")
    c = loaded(p["steps"][0], ground=False)
    c["point"] = [x + 0.1 for x in c["point"]]
    save(p, src + "-moved.json")
    # the last removal left out
    p = load(src + "-plan.json")
    p["order"].pop()
    p["steps"].pop()
    save(p, src + "-short.json")
    # a contact of the body removed in step 1 kept, with no force, in step 2
    p = load(src + "-plan.json")
    gone = p["steps"][0]["remove"]
    c = [c for c in p["steps"][0]["certificate"]["contacts"] if gone in (c["a"], c["b"])][0]
    c = dict(c, force=[0.0] * len(c["force"]), force_xyz=[0.0] * len(c["force"]))
    p["steps"][1]["certificate"]["contacts"].append(c)
    save(p, src + "-removed.json")
    # the two forms of one force disagree
    p = load(src + "-plan.json")
    c = loaded(p["steps"][0])
    c["force"][1] += 0.5 * abs(c["force"][0])
    save(p, src + "-frame.json")
EOF
for src in stacker random3d; do
  expect 1 "$src: a force scaled by 1.5 fails" -- $CHECK "$T/$src.json" "$T/$src-scaled.json" --quiet
  contains "$T/out" "step 3" "and the message names step 3"
  contains "$T/out" "force residual" "and the force residual"
  expect 1 "$src: a flipped normal fails" -- $CHECK "$T/$src.json" "$T/$src-flipped.json" --quiet
  contains "$T/out" "is not a contact normal" "and says the normal is wrong"
  expect 1 "$src: a point moved off the bodies fails" -- $CHECK "$T/$src.json" "$T/$src-moved.json" --quiet
  contains "$T/out" "from the surface of" "and says it is off a surface"
  expect 1 "$src: a found plan that leaves a body fails" -- $CHECK "$T/$src.json" "$T/$src-short.json" --quiet
  contains "$T/out" "never removed" "and says a body is never removed"
  expect 1 "$src: a contact with a removed body fails" -- $CHECK "$T/$src.json" "$T/$src-removed.json" --quiet
  contains "$T/out" "which an earlier step removed" "and names the removed body"
  expect 1 "$src: force and force_xyz that disagree fail" -- $CHECK "$T/$src.json" "$T/$src-frame.json" --quiet
  contains "$T/out" "is not force_xyz" "and says so"
done
expect 1 "plank: the same forces with friction 1e-4 below tan fail" -- $CHECK "$T/plank-lowmu.json" "$T/plank-plan.json" --quiet
contains "$T/out" "outside the friction cone" "and name the cone"
# a body the brute-force hull does not take (40 points): skipped, exit 3
python3 -c '
import json, math, sys
ring = lambda z: [[math.cos(k * math.pi / 10), math.sin(k * math.pi / 10), z] for k in range(20)]
json.dump({"dimension": 3, "bodies": [{"id": "cyl", "vertices": ring(0) + ring(1)},
           {"id": "lid", "box": {"center": [0, 0, 1.25], "size": [1, 1, 0.5]}}]}, open(sys.argv[1], "w"))' "$T/cyl.json"
expect 0 "a 40-point prism: plan" -- "$CLI" plan "$T/cyl.json" --certificates -o "$T/cyl-plan.json"
expect 3 "the checker skips its body: incomplete, exit 3" -- $CHECK "$T/cyl.json" "$T/cyl-plan.json" --quiet
contains "$T/out" "SKIP body 'cyl'" "and names it"
# unreadable input
head -c 200 "$T/tower-plan.json" >"$T/truncated.json"
expect 2 "a truncated plan is unreadable" -- $CHECK "$T/tower.json" "$T/truncated.json"
expect 2 "a missing structure is unreadable" -- $CHECK "$T/nonexistent.json" "$T/tower-plan.json"
finish
