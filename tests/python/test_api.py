"""The package's API on known answers: verdicts, plan statuses and orders,
the objects' data and their life cycle."""

import subprocess

import pytest

import unstack
from conftest import ROOT


def test_column_top_down_found():
    with unstack.generate("column", blocks=5) as s:
        assert (len(s), s.dim, s.ids) == (5, 2, ["b1", "b2", "b3", "b4", "b5"])
        for search in ("assemble", "dfs", "bfs"):
            p = s.plan(search=search)
            assert p.status == "found" and p.found
            assert p.order == [["b5"], ["b4"], ["b3"], ["b2"], ["b1"]]
            assert p.actions is None
            assert p.verify()["ok"]
            assert p.stats["tests"] > 0


def test_cantilever_order(data):
    s = unstack.load(data / "cantilever.json")
    p = s.plan()
    assert p.status == "found"
    # the plank must go first (docs of the fixture); then all the others once
    assert p.order[0] == ["L"]
    assert sorted(sum(p.order, [])) == ["B", "C", "L", "P"]
    rep = p.verify()
    assert rep["ok"] and rep["failed_step"] is None and rep["steps_checked"] == 5


def test_arch_none_then_hands():
    s = unstack.generate("arch")
    p = s.plan()
    assert p.status == "none"
    assert p.order == [] and p.blocked  # the voussoirs the greedy cannot reach
    assert set(sum(p.blocked, [])) <= set(s.ids)
    with pytest.raises(unstack.Error, match="no order"):
        p.verify()
    h = s.plan(hands="auto")
    assert h.status == "found"
    assert h.hands == 2 and h.hands_lower == 2  # 1 hand is proven impossible
    verbs = {v for v, _ in h.actions}
    assert verbs <= {"place", "grab", "release"}
    assert sorted(b for v, b in h.actions if v == "place") == sorted(s.ids)
    assert h.verify()["ok"]


def test_leaning_slabs_none(data):
    p = unstack.load(data / "leaning.json").plan()
    assert p.status == "none"
    assert sorted(sum(p.blocked, [])) == ["left", "right"]


def test_max_group_auto_arch():
    # steps of several voussoirs: the smallest group size that gives an order
    p = unstack.generate("arch").plan(max_group="auto")
    assert p.status == "found" and p.max_group >= 2
    assert max(len(step) for step in p.order) == p.max_group
    assert p.verify()["ok"]


def test_check_stable_forces(data):
    s = unstack.load(data / "lean_wall.json")
    r = s.check()
    assert r.stable and r.verdict == "stable" and bool(r)
    assert r.certificate["ok"]
    assert r.forces and r.mechanism is None
    ids = set(s.ids) | {"ground"}
    for f in r.forces:
        assert f["a"] in ids and f["b"] in ids
        assert len(f["point"]) == 2 and len(f["normal"]) == 2 and len(f["friction"]) == 2
        assert f["normal_force"] >= -1e-9


def test_check_unstable_mechanism(data):
    s = unstack.load(data / "lean_wall_mu0.json")
    for method in ("auto", "lp", "lpsolve", "lcp", "lcp-reuse", "lp-lcp"):
        r = s.check(method=method)
        assert r.verdict == "unstable" and not r.stable and r.forces is None
    m = s.check(method="lp").mechanism
    assert m is not None and m["ok"] and m["bodies"]
    assert all(len(v) == 3 for v in m["velocities"])


def test_check_3d_tower():
    s = unstack.generate("tower", blocks=3, jitter=10, seed=2)
    assert s.dim == 3
    r = s.check()
    assert r.stable
    assert all(len(f["point"]) == 3 and len(f["tangential"]) == 2 for f in r.forces)
    p = s.plan()
    assert p.order == [["b3"], ["b2"], ["b1"]]


def test_certificates_per_step():
    p = unstack.generate("column", blocks=3).plan(certificates=True)
    c = p.certificates()
    assert len(c) == len(p.order) + 1 and c[-1] == []
    assert {f["b"] for f in c[0]} == {"b1", "b2", "b3"}
    assert unstack.generate("column", blocks=3).plan().certificates() is None


def test_close_and_context_manager(data):
    with unstack.load(data / "column3.json") as s:
        p = s.plan()
    assert s.closed
    with pytest.raises(unstack.Error, match="closed"):
        s.check()
    with pytest.raises(unstack.Error, match="closed"):
        p.verify()  # the plan's structure is gone
    p.close()
    p.close()  # idempotent
    with pytest.raises(unstack.Error, match="closed"):
        p.write("never.json")


def test_limit_status():
    s = unstack.generate("arch")
    p = s.plan(search="dfs", max_tests=3)
    assert p.status == "limit"


def test_version():
    assert unstack.__version__.count(".") == 2


def test_bodies_and_contacts(data):
    s = unstack.load(data / "cantilever.json")
    plank = next(b for b in s.bodies if b["id"] == "L")
    assert plank["fixed"] is False
    assert plank["mass"] == pytest.approx(3.2 * 0.2)  # density 1 times the area
    assert plank["com"] == pytest.approx([1.4, 1.1])
    assert len(s.contacts) == s.ncontacts
    pairs = {frozenset((c["a"], c["b"])) for c in s.contacts}
    assert frozenset(("L", "C")) in pairs and frozenset(("ground", "P")) in pairs
    assert all(c["mu"] == pytest.approx(0.5) for c in s.contacts)


def test_import_svg_as_the_cli(cli, tmp_path):
    for name, status in (("arch", "none"), ("cantilever", "found"), ("column", "found")):
        svg = ROOT / "examples" / f"{name}.svg"
        f = tmp_path / f"{name}.json"
        subprocess.run([cli, "import-svg", str(svg), "-o", str(f)], check=True, capture_output=True)
        s = unstack.import_svg(svg)
        assert s.fingerprint == unstack.load(f).fingerprint
        assert s.plan().status == status
    with pytest.raises(unstack.Error) as e:
        unstack.import_svg(ROOT / "README.md")
    assert e.value.code == "parse" and "README.md:1" in str(e.value)


def test_threads_plan_at_once():
    # the GIL is released while the library works; answers do not depend on it
    import threading
    kinds = [("stacker", dict(rows=8, width=6, seed=k)) for k in range(1, 7)]
    want = [unstack.generate(k, **p).plan().order for k, p in kinds]
    got = [None] * len(kinds)

    def run(i):
        got[i] = unstack.generate(kinds[i][0], **kinds[i][1]).plan().order

    threads = [threading.Thread(target=run, args=(i,)) for i in range(len(kinds))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert got == want and all(want)
