#!/usr/bin/env python3
"""A session with the unstack Python package (docs/python.md): load or
generate structures, test them, plan, verify and write plans.

    PYTHONPATH=build/python python3 examples/plan.py [OUTDIR]

Exits non-zero when an answer is not the known one (tests/cli/examples.sh
runs it)."""

import os
import sys
import tempfile

import unstack


def main(outdir):
    # a structure from a dict in the JSON structure format (docs/format.md)
    column = unstack.load({"bodies": [
        {"id": "base", "polygon": [[0, 0], [1, 0], [1, 1], [0, 1]]},
        {"id": "top", "polygon": [[0, 1], [1, 1], [1, 2], [0, 2]]}]})
    r = column.check()
    print(f"{column}: {r.verdict}; the ground carries "
          f"{sum(f['normal_force'] for f in r.forces if f['a'] == 'ground'):.3f}")
    plan = column.plan()
    print(f"  plan {plan.status}: {plan.order}")

    # a generated arch: one voussoir at a time is impossible ...
    with unstack.generate("arch", voussoirs=9) as arch:
        one = arch.plan()
        print(f"arch, one body at a time: {one.status}; blocked {sum(one.blocked, [])}")
        # ... but with two hands (place, grab, release) it can be built
        two = arch.plan(hands="auto", certificates=True)
        print(f"arch with hands: {two.status} with {two.hands} hands, "
              f"{len(two.actions)} actions, first {two.actions[:3]}")
        report = two.verify()
        print(f"  verified: {report['ok']} ({report['steps_checked']} tests re-checked)")
        arch.write(os.path.join(outdir, "arch.json"))
        two.write(os.path.join(outdir, "arch_plan.json"))

    # a bigger random stack, planned with a time budget
    stack = unstack.generate("stacker", rows=10, width=8, seed=7)
    p = stack.plan(time_limit=30)
    print(f"stacker ({len(stack)} blocks): {p.status} in {p.stats['tests']} tests, "
          f"{p.stats['time_total']:.3f} s; verified {p.verify()['ok']}")

    # errors carry the library's message
    try:
        stack.plan(method="simplex")
    except unstack.Error as e:
        print(f"error ({e.code}): {e}")

    ok = (r.stable and plan.order == [["top"], ["base"]] and one.status == "none"
          and two.hands == 2 and report["ok"] and p.status == "found")
    print("all as expected" if ok else "UNEXPECTED ANSWER")
    return 0 if ok else 1


if __name__ == "__main__":
    if len(sys.argv) > 1:
        sys.exit(main(sys.argv[1]))
    with tempfile.TemporaryDirectory() as d:
        sys.exit(main(d))
