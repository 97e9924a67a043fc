#!/bin/bash
# Issue 21's differential test, replayed by the independent checker: the
# random piles of test_hands (minimum_agrees_with_exhaustive_reference,
# where the library's minimum is compared with an exhaustive search over
# (placed, held) states) are written with their `plan --hands auto` plans
# and certificates (US_HANDS_DUMP), and every plan is replayed by
# tests/independent/check_plan.py: at most H held, the actions in order,
# every release's forces balancing the placed bodies with the held ones
# fixed. The checker shares no code with the library.
source "$(dirname "$0")/lib.sh"
CHECKER="$(cd "$(dirname "$0")/.." && pwd)/independent/check_plan.py"
TEST_HANDS="$(dirname "$CLI")/test_hands"
mkdir -p "$T/piles"
expect 0 "test_hands' differential case passes and writes its plans" -- \
  env US_HANDS_DUMP="$T/piles" "$TEST_HANDS" minimum_agrees_with_exhaustive_reference
n=$(ls "$T/piles" | grep -c -- '-plan\.json$')
if [ "$n" -ge 50 ]; then ok "$n plans written"; else bad "only $n plans written"; fi
# one Python process replays them all (the checker's main per pair)
python3 - "$CHECKER" "$T/piles" >"$T/replay" 2>&1 <<'PY'
import glob, importlib.util, io, contextlib, sys
spec = importlib.util.spec_from_file_location("check_plan", sys.argv[1])
cp = importlib.util.module_from_spec(spec)
spec.loader.exec_module(cp)
bad = checked = held2 = 0
for plan in sorted(glob.glob(sys.argv[2] + "/pile-*-plan.json")):
    structure = plan.replace("-plan.json", ".json")
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = cp.main(["check_plan.py", structure, plan, "--quiet"])
    checked += 1
    if '"hands": 2' in open(plan).read():
        held2 += 1
    if code != 0:
        bad += 1
        print("FAILED %s:\n%s" % (plan, out.getvalue()[-600:]))
print("replayed %d plans, %d with 2 hands, %d failed" % (checked, held2, bad))
sys.exit(1 if bad or held2 == 0 else 0)
PY
code=$?
tail -1 "$T/replay"
if [ $code -eq 0 ]; then ok "the independent checker passes every plan (some with 2 hands)"; else
  bad "the independent checker refused a plan"; head -30 "$T/replay" | sed 's/^/    /'; fi
finish
