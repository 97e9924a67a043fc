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


def oom_round(data, tmp):
    """load, check, plan (with certificates), verify, write, generate."""
    s = unstack.load(data / "cantilever.json")
    assert s.check(method="lp").stable
    p = s.plan(certificates=True)
    assert p.found and p.verify()["ok"]
    p.write(tmp / "p.json")
    s.to_dict()
    assert unstack.generate("arch", voussoirs=5).plan(hands="auto").found


def oom_error(e):
    """An out-of-memory error as the library reports it."""
    return e.code == "nomem"


def test_out_of_memory_sweep(data, tmp_path):
    # every allocation of the round fails in turn: an Error with code nomem,
    # never a crash or a wrong answer, and nothing left allocated
    gc.collect()
    base = unstack._alloc_live()
    codes = set()
    n = 0
    while True:
        unstack._alloc_fail_after(n)
        try:
            oom_round(data, tmp_path)
            done = True
        except unstack.Error as e:
            assert oom_error(e), f"allocation {n}: {e.code}: {e}"
            codes.add(e.code)
            done = False
        finally:
            unstack._alloc_fail_after(-1)
        gc.collect()
        assert unstack._alloc_live() == base, f"leak after failing allocation {n}"
        if done:
            break
        n += 1 if n < 100 else 5  # every one first, then every fifth
    assert n > 100 and "nomem" in codes
