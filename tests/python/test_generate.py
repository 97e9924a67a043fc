"""Every generator kind: the same structure as `unstack generate` with the
same options (fingerprints equal), and a round trip through to_dict() and
load() that keeps the fingerprint, the size and the verdict."""

import subprocess

import pytest

import unstack

# one small case per kind, with the options that kind takes
CASES = {
    "column": dict(blocks=4, block_height=0.7),
    "pyramid": dict(rows=3, friction=0.6),
    "wall": dict(rows=3, cols=4, block_width=1.2),
    "arch": dict(voussoirs=7, radius=2.5, thickness=0.4, loose=2),
    "random": dict(rows=4, width=4, seed=3),
    "stacker": dict(rows=6, width=6, seed=2),
    "tower": dict(blocks=3, jitter=10, seed=2, block_depth=0.8),
    "pyramid3d": dict(rows=2, density=2),
    "wall3d": dict(rows=2, cols=4, thickness=0.4, returns=2),
    "dome": dict(courses=3, segments=6, radius=2, thickness=0.4, oculus=30, cap=True, chamfer=0),
    "jenga": dict(levels=3, remove=[(2, 1)]),
    "random3d": dict(blocks=5, width=3, seed=1, max_tries=50),
}


def cli_args(params):
    args = []
    for k, v in params.items():
        opt = "--" + k.replace("_", "-")
        if v is True:
            args.append(opt)
        elif k == "remove":
            args += [opt, ",".join(f"{a}:{b}" for a, b in v)]
        else:
            args += [opt, str(v)]
    return args


def test_every_kind_has_a_case():
    # the kinds are listed by the unknown-kind error
    with pytest.raises(unstack.Error) as e:
        unstack.generate("?")
    listed = str(e.value).split("(")[1].rstrip(")").split(", ")
    assert sorted(listed) == sorted(CASES)


@pytest.mark.parametrize("kind", sorted(CASES))
def test_same_as_the_cli(kind, cli, tmp_path):
    f = tmp_path / f"{kind}.json"
    subprocess.run([cli, "generate", kind, *cli_args(CASES[kind]), "-o", str(f)], check=True,
                   capture_output=True)
    with unstack.load(f) as want, unstack.generate(kind, **CASES[kind]) as got:
        assert got.fingerprint == want.fingerprint
        assert len(got) == len(want) and got.dim == want.dim


@pytest.mark.parametrize("kind", sorted(CASES))
def test_round_trip(kind, tmp_path):
    s = unstack.generate(kind, **CASES[kind])
    d = s.to_dict()
    assert len(d["bodies"]) == len(s) and d.get("dimension", 2) == s.dim
    t = unstack.load(d)
    assert t.fingerprint == s.fingerprint
    assert t.ids == s.ids and t.ncontacts == s.ncontacts
    assert t.check().verdict == s.check().verdict
    s.write(tmp_path / "s.json")
    assert unstack.load(tmp_path / "s.json").fingerprint == s.fingerprint


def test_defaults_follow_the_cli(cli, tmp_path):
    # no parameters at all: the CLI's defaults (stacker width 12, jenga height)
    for kind in ("stacker", "jenga", "column"):
        f = tmp_path / f"{kind}.json"
        subprocess.run([cli, "generate", kind, "-o", str(f)], check=True, capture_output=True)
        assert unstack.generate(kind).fingerprint == unstack.load(f).fingerprint
