"""Structure.render: the same pictures and page as `unstack render` on the
plan file the package wrote, errors before any file is written."""

import subprocess

import pytest

import unstack


def cli_render(cli, structure, plan, out, *opts):
    subprocess.run([cli, "render", str(structure), "--plan", str(plan), *opts, "-o", str(out)],
                   check=True, capture_output=True)
    return out.read_bytes()


@pytest.mark.parametrize("name", ["cantilever", "leaning"])
def test_svg_and_html_as_the_cli(name, data, cli, tmp_path):
    sf = data / f"{name}.json"
    s = unstack.load(sf)
    p = s.plan(certificates=True)
    p.write(tmp_path / "plan.json")
    want = cli_render(cli, sf, tmp_path / "plan.json", tmp_path / "cli.svg")
    # the CLI's title line: file name, bodies, the plan's status and steps
    what = (f"plan found, {len(p.order)} steps" if p.found else
            f"plan status {p.status}, {len(sum(p.blocked, []))} bodies cannot be removed")
    title = f"{name}.json \u2014 {len(s)} bodies, {what}"
    s.render(tmp_path / "py.svg", p, title=title)
    assert (tmp_path / "py.svg").read_bytes() == want
    if p.found:
        want = cli_render(cli, sf, tmp_path / "plan.json", tmp_path / "cli.html", "--html")
        s.render(tmp_path / "py.html", p, title=f"{name}.json")
        assert (tmp_path / "py.html").read_bytes() == want


def test_forces_drawn_from_the_certificates(data, tmp_path):
    # forces are not unique: the picture draws the plan's own certificate
    s = unstack.load(data / "cantilever.json")
    p = s.plan(certificates=True)
    s.render(tmp_path / "f.svg", p, forces=True)
    s.render(tmp_path / "n.svg", p)
    arrows = (tmp_path / "f.svg").read_text().count('marker-end="url(#arrow)"')
    nonzero = sum(1 for f in p.certificates()[0] if abs(f["normal_force"]) > 1e-9)
    assert arrows >= nonzero > 0
    assert (tmp_path / "n.svg").read_text().count('marker-end="url(#arrow)"') == 0


def test_png_and_hands_page(tmp_path):
    a = unstack.generate("arch", voussoirs=7)
    h = a.plan(hands="auto")
    a.render(tmp_path / "a.png", h)
    assert (tmp_path / "a.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    a.render(tmp_path / "a.html", h)
    page = (tmp_path / "a.html").read_text()
    assert '"hands":2' in page.replace(" ", "") and "<canvas" in page


def test_render_errors_write_nothing(tmp_path):
    s = unstack.generate("column", blocks=2)
    other = unstack.generate("column", blocks=3).plan()
    with pytest.raises(unstack.Error, match=r"\.svg, \.png or \.html"):
        s.render(tmp_path / "x.pdf")
    with pytest.raises(unstack.Error, match="another structure"):
        s.render(tmp_path / "x.svg", other)
    with pytest.raises(unstack.Error) as e:
        s.render(tmp_path / "no" / "x.svg")
    assert e.value.code == "io"
    assert list(tmp_path.iterdir()) == []
