"""Nothing the library allocates outlives the Python objects: the library's
live-allocation count returns to its baseline after many calls, errors
included, whether objects are closed or only dropped."""

import gc

import pytest

import unstack


def session(data, k):
    s = unstack.load(data / "cantilever.json")
    r = s.check(method=("lp", "lcp", "lp-lcp")[k % 3])
    assert r.stable
    p = s.plan(certificates=k % 2 == 0)
    assert p.found and p.verify()["ok"]
    p.certificates()
    if k % 2:  # half closed explicitly, half left to the collector
        p.close()
        s.close()
    a = unstack.generate("arch", voussoirs=7)
    assert a.plan(hands="auto").found
    d = unstack.generate("stacker", rows=4, width=4, seed=k).to_dict()
    assert unstack.load(d).check().verdict in ("stable", "unstable")


def errors(data, tmp):
    s = unstack.generate("column", blocks=3)
    calls = [lambda: unstack.load({"bodies": [{"id": "a", "polygon": [[0, 0], [1, 0]]}]}),
             lambda: unstack.load(data / "bad" / "3d_coplanar.json"),
             lambda: unstack.load(tmp / "missing.json"),
             lambda: s.check(method="nope"),
             lambda: s.plan(hands=99),
             lambda: s.plan().write(tmp / "no" / "dir.json"),
             lambda: unstack.generate("jenga", remove=[(1, 9)]),
             lambda: unstack.generate("arch", radius=-1)]
    for call in calls:
        with pytest.raises(unstack.Error):
            call()


def test_alloc_live_returns_to_baseline(data, tmp_path):
    gc.collect()
    base = unstack._alloc_live()
    s = unstack.generate("pyramid", rows=3)
    assert unstack._alloc_live() > base  # the count sees the structure
    s.close()
    assert unstack._alloc_live() == base
    for k in range(40):
        session(data, k)
        errors(data, tmp_path)
    gc.collect()
    assert unstack._alloc_live() == base


def test_plan_keeps_its_structure_alive():
    gc.collect()
    base = unstack._alloc_live()
    p = unstack.generate("column", blocks=4).plan()  # the Structure is dropped at once
    assert p.verify()["ok"]  # the plan's handle still holds it
    del p
    gc.collect()
    assert unstack._alloc_live() == base
