"""``voussoir-post bridge-report`` (issue 37, item 4) on the bridge of input/bridge_passive.nml
run by voussoir-limit twice, with a third of the fill's passive pressure mobilised and
without it: the report's numbers against the two JSONs read here with ``json`` alone, the
critical position against the curve's points, the figures as PNG files, and the refusals
of a pair that is not one bridge with and without the passive pressure."""

from __future__ import annotations

import json
import math
import re

import pytest

from conftest import REPO_ROOT, run_executable
from figure_text import text_clashes
from voussoir_post.cli import post

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


@pytest.fixture
def pair(voussoir_limit_exe, tmp_path):
    """The two JSONs (with, without the passive pressure) and their raw dicts."""
    text = (REPO_ROOT / "input" / "bridge_passive.nml").read_text()
    assert "passive_mobilisation = 0.33" in text
    paths = {}
    for key, nml_text in (("with", text), ("without", text.replace("passive_mobilisation = 0.33",
                                                                     "passive_mobilisation = 0"))):
        nml = tmp_path / f"bridge_{key}.nml"
        nml.write_text(nml_text)
        paths[key] = tmp_path / f"bridge_{key}.json"
        paths[key].write_text(run_executable([voussoir_limit_exe, nml, "--json"], tmp_path).stdout)
    raw = {k: json.loads(p.read_text()) for k, p in paths.items()}
    return paths, raw


def _table(report: str, heading: str) -> list[list[str]]:
    """The rows (cells) of the first table under ``## heading``."""
    section = report.split(f"## {heading}\n", 1)[1].split("\n## ", 1)[0]
    rows = [line for line in section.splitlines() if line.startswith("|")]
    return [[c.strip() for c in row.strip("|").split("|")] for row in rows[2:]]


def test_bridge_report_with_and_without_passive(pair, tmp_path, drawn_figures):
    paths, raw = pair
    out = tmp_path / "report"
    assert post.main(["bridge-report", str(paths["with"]), "--without-passive", str(paths["without"]),
                      "--out", str(out)]) == 0
    report = (out / "report.md").read_text()
    lam = {k: raw[k]["load_factor"] for k in raw}
    # The passive pressure cannot lower the load factor (it only widens the LP's bounds).
    assert lam["with"] >= lam["without"] > 0
    assert lam["with"] > 1.2 * lam["without"]   # and here it matters (measured 2.131 against 1.585)
    # The report's load factors are the JSONs', as printed (4 decimals), in that order.
    rows = _table(report, "Load factor")
    assert [r[0] for r in rows] == ["with the fill's passive pressure (mobilisation 0.33)",
                                    "without the fill's passive pressure (active only)"]
    for row, key in zip(rows, ("with", "without")):
        assert float(row[1]) == pytest.approx(lam[key], abs=5.1e-5)
        assert float(row[3]) == pytest.approx(lam[key] * 100.0, rel=1e-3)      # kN of a 100 kN live load
        assert float(row[4]) == pytest.approx(raw[key]["critical_position"]["x_m"], abs=5e-4)
    ratio = re.search(r"raises the load factor by ([\d.]+) %", report)
    assert float(ratio.group(1)) == pytest.approx(100 * (lam["with"] / lam["without"] - 1), abs=0.051)
    # The critical position is the least of the curve's points (the JSON's, read here), and a point of it.
    for key in raw:
        curve = raw[key]["load_factor_curve"]
        critical = raw[key]["critical_position"]
        assert critical["load_factor"] == lam[key]
        assert critical["load_factor"] <= min(c["load_factor"] for c in curve) * (1 + 1e-9)
        assert any(c["x_m"] == critical["x_m"] and c["at_joint"] for c in curve)   # refined at a joint
        assert min(c["load_factor"] for c in curve if not c["at_joint"]) > critical["load_factor"] * (1 + 1e-3)
    # ... and the report's curve table says so: one critical row a case, the least of its rows.
    curve_rows = _table(report, "Load factor against the vehicle's position")
    assert len(curve_rows) == sum(len(raw[k]["load_factor_curve"]) for k in raw)
    for case in {r[0] for r in curve_rows}:
        mine = [r for r in curve_rows if r[0] == case]
        (critical,) = [r for r in mine if r[4] == "**critical**"]
        assert float(critical[2]) == min(float(r[2]) for r in mine)
        assert critical[3] == "yes"
    # The figures: PNG files, named in the report; the load-position figure's text clear.
    for name in ("mechanism.png", "mechanism_without_passive.png", "load_position.png"):
        assert (out / name).read_bytes()[:8] == PNG_MAGIC
        assert f"]({name})" in report
    curve_fig = drawn_figures[-1]
    assert text_clashes(curve_fig) == []
    assert "vehicle position x [m]" in curve_fig.axes[0].get_xlabel()
    # The geometry and the loads, in metres and kN, from the input file's numbers.
    (span,) = _table(report, "Geometry")
    assert span[1:5] == ["segmental", "10", "2.5", "4"]
    assert float(span[7]) == pytest.approx(0.5, abs=1e-9 + 5e-4)   # 3.45 m surface over a 2.95 m crown extrados
    loads = {r[0]: r[1] for r in _table(report, "Loads")}
    assert float(loads["the live load (load factor 1)"]) == 100.0
    fill_n = -sum(e["force_n"][1] for e in raw["with"]["fill_loads"])
    assert float(loads["the fill's weight on the ring"]) == pytest.approx(fill_n / 1e3, rel=1e-3)


def test_bridge_report_refuses_a_pair_that_is_not_one_bridge(pair, tmp_path, capsys):
    """The files the wrong way round, and a second file of another bridge: exit 2, a message
    naming the file and why."""
    paths, raw = pair
    assert post.main(["bridge-report", str(paths["without"]), "--without-passive", str(paths["with"]),
                      "--out", str(tmp_path / "r1")]) == 2
    assert "passive_mobilisation is 0.33, not 0" in capsys.readouterr().err
    other = raw["without"]
    other["config_nml"] = other["config_nml"].replace("ring_thickness_m = 4.5000000000000001E-01",
                                                      "ring_thickness_m = 0.5")
    assert "ring_thickness_m = 0.5" in other["config_nml"]
    (tmp_path / "other.json").write_text(json.dumps(other))
    assert post.main(["bridge-report", str(paths["with"]), "--without-passive", str(tmp_path / "other.json"),
                      "--out", str(tmp_path / "r2")]) == 2
    assert "&bridge differs in ring_thickness_m" in capsys.readouterr().err


def test_bridge_report_of_two_spans_without_fill(voussoir_limit_exe, tmp_path, drawn_figures):
    """input/bridge_two_spans.nml alone: two spans on a pier, no fill; the positions over the
    pier where the LP finds no collapse (null in the JSON) are said so, not drawn as numbers;
    the critical position is still the least of the finite points."""
    path = tmp_path / "two.json"
    path.write_text(run_executable([voussoir_limit_exe, REPO_ROOT / "input" / "bridge_two_spans.nml", "--json"],
                                   tmp_path).stdout)
    raw = json.loads(path.read_text())
    assert post.main(["bridge-report", str(path), "--out", str(tmp_path / "r")]) == 0
    report = (tmp_path / "r" / "report.md").read_text()
    (row,) = _table(report, "Load factor")
    assert float(row[1]) == pytest.approx(raw["load_factor"], abs=5.1e-5)
    spans = _table(report, "Geometry")
    assert [s[5] for s in spans] == ["0", "11.5"]            # span 2 springs from beyond the 1.5 m pier
    assert "Piers: 1, 1.5 m wide" in report and "No fill." in report
    curve = raw["load_factor_curve"]
    finite = [c["load_factor"] for c in curve if c["load_factor"] is not None]
    assert len(finite) < len(curve)                           # over the pier: no collapse
    assert raw["critical_position"]["load_factor"] <= min(finite) * (1 + 1e-9)
    rows = _table(report, "Load factor against the vehicle's position")
    assert sum(r[2] == "none (the LP found no collapse)" for r in rows) == len(curve) - len(finite)
    assert (tmp_path / "r" / "load_position.png").read_bytes()[:8] == PNG_MAGIC
    assert text_clashes(drawn_figures[-1]) == []
    assert not (tmp_path / "r" / "mechanism_without_passive.png").exists()


def test_bridge_report_of_two_spans_with_fill_and_a_vehicle(voussoir_limit_exe, tmp_path, drawn_figures):
    """input/bridge_two_spans_vehicle.nml (two spans, fill with passive pressure, EN 1991-2's
    tandem over an effective width of 3 m) with and without the passive pressure: the live
    load on the strip is each axle x width_m/effective_width_m = 300 x 1/3 = 100 kN, so the
    collapse load on the strip is lambda x 200 kN and, in whole vehicles, lambda x 600 kN;
    the vehicle is named in the report and the figures' titles; the critical position is
    the least of the curve."""
    text = (REPO_ROOT / "input" / "bridge_two_spans_vehicle.nml").read_text()
    assert "passive_mobilisation = 0.33" in text and "name = 'lm1_tandem_lane1', effective_width_m = 3.0" in text
    paths = {}
    for key, nml_text in (("with", text), ("without", text.replace("passive_mobilisation = 0.33",
                                                                     "passive_mobilisation = 0"))):
        nml = tmp_path / f"vehicle_{key}.nml"
        nml.write_text(nml_text)
        paths[key] = tmp_path / f"vehicle_{key}.json"
        paths[key].write_text(run_executable([voussoir_limit_exe, nml, "--json"], tmp_path).stdout)
    raw = {k: json.loads(p.read_text()) for k, p in paths.items()}
    out = tmp_path / "report"
    n_drawn = len(drawn_figures)
    assert post.main(["bridge-report", str(paths["with"]), "--without-passive", str(paths["without"]),
                      "--out", str(out)]) == 0
    report = (out / "report.md").read_text()
    lam = {k: raw[k]["load_factor"] for k in raw}
    assert lam["with"] > lam["without"] > 0
    rows = _table(report, "Load factor")
    for row, key in zip(rows, ("with", "without")):
        assert float(row[1]) == pytest.approx(lam[key], abs=5.1e-5)
        assert float(row[3]) == pytest.approx(lam[key] * 200.0, rel=1e-3)     # kN on the strip
    loads = {r[0]: r for r in _table(report, "Loads")}
    assert loads["the live load (load factor 1)"][1] == "200"
    assert "vehicle 'lm1_tandem_lane1' (axles 300 + 300 kN, 1.2 m apart, each over an effective width of 3 m)" \
        in loads["the live load (load factor 1)"][2]
    assert "100 + 100 kN on the strip" in loads["the live load (load factor 1)"][2]
    whole = re.search(r"weighs 600 kN on its axles; λ = ([0-9.]+) is ([0-9.]+) kN of such axles at collapse "
                      r"\(without the passive pressure, ([0-9.]+) kN\)", report)
    assert whole and float(whole.group(2)) == pytest.approx(600.0 * lam["with"], rel=1e-3)
    assert float(whole.group(3)) == pytest.approx(600.0 * lam["without"], rel=1e-3)
    for key in raw:
        finite = [c["load_factor"] for c in raw[key]["load_factor_curve"] if c["load_factor"] is not None]
        assert raw[key]["critical_position"]["load_factor"] <= min(finite) * (1 + 1e-9)
        # the axles (100 kN each on the strip) stand on the fill's surface, 1.2 m apart
        xs = sorted(q["xy_m"][0] for q in raw[key]["surface_loads"])
        assert len(xs) == 2 and xs[1] - xs[0] == pytest.approx(1.2, abs=1e-12)
        assert all(q["force_n"][1] == pytest.approx(-100e3, rel=1e-14) for q in raw[key]["surface_loads"])
    titles = [t for fig in drawn_figures[n_drawn:] for t in [fig._suptitle.get_text() if fig._suptitle else ""]
              + [ax.get_title() for ax in fig.axes]]
    assert any("vehicle 'lm1_tandem_lane1'" in t for t in titles)
    for name in ("mechanism.png", "mechanism_without_passive.png", "load_position.png"):
        assert (out / name).read_bytes()[:8] == PNG_MAGIC
    for fig in drawn_figures[n_drawn:]:
        assert text_clashes(fig) == []


def test_bridge_report_of_load_cases(voussoir_limit_exe, tmp_path):
    """input/bridge_load_cases.nml (two cases with partial factors and patches): the report's
    "Load cases" table is the JSON's ``load_cases`` (read with ``json`` alone), the
    governing case marked and the least; the rest of the report is of that case, its live
    load as factored (gamma_q x 2 x 100 kN)."""
    path = tmp_path / "cases.json"
    path.write_text(run_executable([voussoir_limit_exe, REPO_ROOT / "input" / "bridge_load_cases.nml", "--json"],
                                   tmp_path).stdout)
    raw = json.loads(path.read_text())
    assert post.main(["bridge-report", str(path), "--out", str(tmp_path / "r")]) == 0
    report = (tmp_path / "r" / "report.md").read_text()
    rows = _table(report, "Load cases")
    cases = raw["load_cases"]
    assert len(rows) == len(cases) == 2
    gov = min(range(len(cases)), key=lambda k: cases[k]["load_factor"])
    assert raw["governing_load_case"] == gov + 1
    for k, (row, case) in enumerate(zip(rows, cases)):
        assert row[0] == f"{k + 1} '{case['name']}'"
        assert float(row[1]) == case["gamma_q"] and float(row[2]) == case["gamma_g"]
        assert float(row[3]) == pytest.approx(case["factored_live_load_n"] / 1e3, rel=1e-3)
        assert float(row[4]) == pytest.approx(case["load_factor"], abs=5.1e-5)
        assert float(row[6]) == pytest.approx(case["critical_position"]["x_m"], abs=5e-3)
        assert float(row[7]) == pytest.approx(case["load_factor"] * case["factored_live_load_n"] / 1e3, rel=1e-3)
        assert ("not adequate" in row[8]) == (case["load_factor"] < 1) and ("governs" in row[8]) == (k == gov)
    assert f"governing case, {gov + 1} '{cases[gov]['name']}'" in report
    (row,) = _table(report, "Load factor")
    assert float(row[1]) == pytest.approx(cases[gov]["load_factor"], abs=5.1e-5)
    assert float(row[3]) == pytest.approx(cases[gov]["collapse_live_load_n"] / 1e3, rel=1e-3)
    live = [r for r in _table(report, "Loads") if r[0] == "the live load (load factor 1)"]
    assert float(live[0][1]) == pytest.approx(cases[gov]["factored_live_load_n"] / 1e3, rel=1e-3)


def test_bridge_report_of_a_multi_ring_arch(voussoir_limit_exe, tmp_path):
    """input/bridge_multi_ring.nml (&bridge n_rings = 4): the report counts every ring's
    voussoirs, as the JSON names them (span 1 ring r voussoir j): the ring's weight is the
    density x g x width x the shoelace area of all 48, which is the segmental ring's by hand
    (R = (L^2/4 + r^2)/(2r), half-angle a: (n/2)(R_e^2 - R^2) sin(2a/n)); the crown's extrados
    is rise + depth; the ring is said to be in 4 rings with the friction between them."""
    path = tmp_path / "rings.json"
    path.write_text(run_executable([voussoir_limit_exe, REPO_ROOT / "input" / "bridge_multi_ring.nml", "--json"],
                                   tmp_path).stdout)
    raw = json.loads(path.read_text())
    assert post.main(["bridge-report", str(path), "--out", str(tmp_path / "r")]) == 0
    report = (tmp_path / "r" / "report.md").read_text()
    names = [b["name"] for b in raw["blocks"]]
    assert sum(bool(re.match(r"span 1 ring [1-4] voussoir \d+$", n)) for n in names) == 48
    span, rise, depth, n = 6.0, 1.5, 0.45, 12
    radius = (span ** 2 / 4 + rise ** 2) / (2 * rise)
    half = math.atan2(span / 2, radius - rise)
    area = 0.5 * n * ((radius + depth) ** 2 - radius ** 2) * math.sin(2 * half / n)
    (weight,) = [r for r in _table(report, "Loads") if r[0] == "the ring's weight"]
    assert float(weight[1]) == pytest.approx(2000 * raw["g_m_s2"] * 1.0 * area / 1e3, rel=5e-4)   # 4 digits
    (geometry,) = _table(report, "Geometry")
    assert float(geometry[6]) == pytest.approx(rise + depth, abs=5e-4)
    assert "in 4 rings of 0.1125 m (joints aligned; friction 0.6 between two rings)" in report
