"""Plans made through the package, written with plan.write() and re-checked
by the independent checker tests/independent/check_plan.py (no code shared
with the library): every step's certificate balances every present body."""

import json
import subprocess
import sys

import pytest

import unstack
from conftest import CHECKER

CASES = [
    ("column", dict(blocks=6), {}),
    ("pyramid", dict(rows=4), {}),
    ("wall", dict(rows=3, cols=4), dict(search="dfs")),
    ("stacker", dict(rows=8, width=6, seed=5), {}),
    ("random", dict(rows=5, width=4, seed=2), dict(method="lcp-reuse")),
    ("arch", dict(), dict(hands="auto")),
    ("arch", dict(voussoirs=7), dict(max_group="auto")),
    ("tower", dict(blocks=3, jitter=15, seed=4), {}),
    ("pyramid3d", dict(rows=2), {}),
]


def independent(structure, plan, tmp_path):
    sf, pf = tmp_path / "s.json", tmp_path / "p.json"
    structure.write(sf)
    plan.write(pf)
    r = subprocess.run([sys.executable, str(CHECKER), str(sf), str(pf), "--quiet"],
                       capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


@pytest.mark.parametrize("kind,params,settings", CASES)
def test_generated_plans_pass_the_checker(kind, params, settings, tmp_path):
    s = unstack.generate(kind, **params)
    p = s.plan(certificates=True, **settings)
    assert p.status == "found"
    code, out = independent(s, p, tmp_path)
    assert code == 0, out
    assert "PASSED" in out


def test_cantilever_and_a_none_plan(data, tmp_path):
    s = unstack.load(data / "cantilever.json")
    code, out = independent(s, s.plan(certificates=True), tmp_path)
    assert code == 0, out
    s = unstack.load(data / "leaning.json")
    p = s.plan(certificates=True)
    assert p.status == "none"
    code, out = independent(s, p, tmp_path)
    assert code == 0 and "status none" in out, out


def test_the_checker_refuses_a_wrong_certificate(data, tmp_path):
    # the control: the same plan with the first step's forces halved
    s = unstack.load(data / "cantilever.json")
    p = s.plan(certificates=True)
    sf, pf = tmp_path / "s.json", tmp_path / "p.json"
    s.write(sf)
    p.write(pf)
    plan = json.loads(pf.read_text())
    for c in plan["steps"][0]["certificate"]["contacts"]:
        c["force"] = [x / 2 for x in c["force"]]
        c["force_xyz"] = [x / 2 for x in c["force_xyz"]]
    pf.write_text(json.dumps(plan))
    r = subprocess.run([sys.executable, str(CHECKER), str(sf), str(pf), "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode == 1 and "step 1" in r.stdout, r.stdout + r.stderr
