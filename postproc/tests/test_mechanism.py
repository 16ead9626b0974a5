"""mechanism on the JSON of the real voussoir-limit."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from conftest import run_executable
from voussoir_post.cli import post
from voussoir_post.plots.mechanism import plot_mechanism, voussoir_polygons
from voussoir_post.readers.results import ResultsError, read_limit_json

LIMIT_NML = """\
&arch
  embrace_deg = 156.0, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071,
  width_m = 0.145, density_kg_m3 = 700.0, friction = 0.5, contact_inset_m = 0.0
/
"""


@pytest.fixture(scope="module")
def limit_json(voussoir_limit_exe, tmp_path_factory):
    folder = tmp_path_factory.mktemp("limit")
    nml = folder / "limit_156.nml"
    nml.write_text(LIMIT_NML)
    proc = run_executable([voussoir_limit_exe, nml, "--json"], folder)
    path = folder / "limit_156.json"
    path.write_text(proc.stdout)
    json.loads(proc.stdout)
    return path


def test_mechanism_draws_the_json_hinges(limit_json, tmp_path):
    limit = read_limit_json(limit_json)
    assert limit.n_voussoirs == 13 and limit.joint_intrados_xy_m.shape == (14, 2)
    data = plot_mechanism(limit, tmp_path / "mech.png")
    assert [p.direction for p in data.panels] == ["+x", "-x"]
    # docs/limit_analysis.md: 156/13 without inset, lambda 0.376, 0i 5e 10i 13e / 0e 3i 8e 13i
    pos, neg = data.panels
    assert pos.load_factor == pytest.approx(0.376019, abs=1e-5)
    assert pos.hinges == [(0, "intrados"), (5, "extrados"), (10, "intrados"), (13, "extrados")]
    assert neg.hinges == [(13 - j, s) for j, s in reversed(pos.hinges)]
    for panel in data.panels:
        for (j, side), xy in zip(panel.hinges, panel.hinge_xy_m):
            end = limit.joint_intrados_xy_m[j] if side == "intrados" else limit.joint_extrados_xy_m[j]
            assert np.array_equal(xy, end)
    polys = voussoir_polygons(limit.joint_intrados_xy_m, limit.joint_extrados_xy_m)
    assert len(data.voussoirs_m) == 13 and np.array_equal(data.voussoirs_m[6], polys[6])
    assert len(data.table.rows) == 8
    assert pos.sliding_joints == [] and neg.sliding_joints == []  # hinging governs at friction 0.5
    assert pos.accel_m_s2 == pytest.approx(0.376019 * 9.81, rel=1e-5)


def test_mechanism_sliding_joints_of_the_118_arch(voussoir_limit_exe, tmp_path):
    """docs/limit_analysis.md: at friction 0.5 the 118-degree arch slides at joints 0 and 10."""
    nml = tmp_path / "limit_118.nml"
    nml.write_text(LIMIT_NML.replace("embrace_deg = 156.0, n_voussoirs = 13",
                                     "embrace_deg = 118.0, n_voussoirs = 10"))
    path = tmp_path / "limit_118.json"
    path.write_text(run_executable([voussoir_limit_exe, nml, "--json"], tmp_path).stdout)
    data = plot_mechanism(read_limit_json(path), tmp_path / "m.png")
    assert [p.sliding_joints for p in data.panels] == [[0, 10], [0, 10]]
    assert [row[-1] for row in data.table.rows] == [True, False, False, True] * 2


def test_limit_json_from_another_producer(limit_json, tmp_path):
    data = json.loads(limit_json.read_text())
    data["producer"] = "voussoir-run"
    other = tmp_path / "other.json"
    other.write_text(json.dumps(data))
    with pytest.raises(ResultsError, match="written by 'voussoir-run', but this command reads 'voussoir-limit'"):
        read_limit_json(other)


def test_mechanism_cli(limit_json, tmp_path, capsys):
    assert post.main(["mechanism", str(limit_json), "--out", str(tmp_path / "m.png"), "--csv"]) == 0
    assert (tmp_path / "m.png").is_file() and (tmp_path / "m.csv").is_file()
    assert "extrados" in capsys.readouterr().out


def test_mechanism_thrust_line_and_forces_of_the_lp(limit_json, tmp_path):
    """Towards +x the thrust line is the LP's centres of pressure: at the four hinges of the
    exact analysis it passes through the hinge (the joint's end, no inset), elsewhere inside
    the joint; the arrows' forces keep every voussoir in equilibrium under its weight
    (trapezoid, closed form) and the inertial load lambda times it."""
    limit = read_limit_json(limit_json)
    data = plot_mechanism(limit, tmp_path / "mech.png")
    pos = data.panels[0]
    lp = pos.lp_forces
    assert lp is not None and data.panels[1].lp_forces is None
    for (j, side), xy in zip(pos.hinges, pos.hinge_xy_m):
        assert np.allclose(pos.thrust_xy_m[j], xy, atol=1e-9)
    intr, extr = limit.joint_intrados_xy_m, limit.joint_extrados_xy_m
    length = np.hypot(*(extr - intr).T)
    assert np.allclose(np.hypot(*(pos.thrust_xy_m - intr).T) + np.hypot(*(pos.thrust_xy_m - extr).T), length,
                       atol=1e-9)
    r_int, dphi = 0.508 - 0.071, math.radians(156.0) / 13
    w = 0.5 * (0.508**2 - r_int**2) * math.sin(dphi) * 0.145 * 700.0 * 9.81
    lam = limit.load_factor
    assert lam == pytest.approx(0.376019, abs=1e-5)
    assert np.allclose(np.diff(lp.force_n, axis=0), [lam * w, -w], rtol=0, atol=1e-6 * w)
    # The arrows' key: a round force, drawn at the figure's scale.
    assert data.force_key_n in (10.0, 20.0, 50.0) and data.force_scale_m_per_n > 0


def test_mechanism_axes_from_the_springings_and_capacity_words(limit_json, tmp_path):
    """y = 0 at the springings: the JSON's origin is the circle's centre, the intrados
    springing r_int sin(12 deg) above it for a 156-degree arch."""
    from voussoir_post.plots.mechanism import _capacity_text
    limit = read_limit_json(limit_json)
    data = plot_mechanism(limit, tmp_path / "mech.png")
    assert data.springing_y_m == pytest.approx((0.508 - 0.071) * math.sin(math.radians(12.0)), rel=1e-9)
    rows = {(r[0], r[3]): r for r in data.table.rows}
    assert "y_above_springings_m" in data.table.columns
    assert rows[("+x", 0)][6] == pytest.approx(0.0, abs=1e-12)  # the hinge at the intrados springing
    text = _capacity_text(data.panels[0])
    assert "collapse load factor λ = 0.376" in text
    assert "horizontal acceleration 3.69 m/s² = 0.376 g" in text


# --- A load case and any assembly (issue 37): the LP's own mechanism, forces and loads. ---

from conftest import REPO_ROOT  # noqa: E402
from figure_text import text_clashes  # noqa: E402


def _limit_json(exe, nml, folder):
    path = folder / (nml.stem + ".json")
    path.write_text(run_executable([exe, nml, "--json"], folder).stdout)
    return path


def _figure_words(fig) -> str:
    words = [t.get_text() for t in fig.texts] + [ax.get_title() for ax in fig.axes]
    for legend in fig.legends:
        words += [t.get_text() for t in legend.get_texts()]
    return "\n".join(words)


def test_mechanism_of_a_load_case(voussoir_limit_exe, tmp_path, drawn_figures):
    """input/limit_arch_point_load.nml (1 kN along a path): the figure is the load case's.
    Its titles name the live load, not a horizontal acceleration; its hinges are the LP's at
    the critical position (joints 3i 7e 12i 16e, docs/limit_analysis.md), not the weights'
    acceleration mechanism; its legend claims no sliding (nothing slides) and compares the
    load factor with nothing; its arrows keep every voussoir in equilibrium under its weight
    (polygon area x 2000 kg/m3 x 1 m x g) and lambda x the drawn live load (1e-6 of a weight)."""
    path = _limit_json(voussoir_limit_exe, REPO_ROOT / "input" / "limit_arch_point_load.nml", tmp_path)
    limit = read_limit_json(path)
    assert post.main(["mechanism", str(path), "--out", str(tmp_path / "m.png")]) == 0
    (fig,) = drawn_figures
    words = _figure_words(fig)
    # The critical position, refined at the joints: a micrometre left of joint 7's extrados end.
    x_crit = limit.critical_x_m
    assert x_crit == pytest.approx(-math.sin(math.radians(11.25)) - 1e-6, abs=1e-12)
    assert "horizontal acceleration" not in words and "live load" in words and f"x = {x_crit:.3g} m" in words
    assert "slid" not in words and "four-hinge" not in words
    assert text_clashes(fig) == []
    data = plot_mechanism(limit, tmp_path / "again.png")
    (panel,) = data.panels
    assert panel.load_factor == pytest.approx(1.432999, abs=1e-6)
    assert [(m.joint, m.hinge_side) for m in panel.hinges] == [(3, "intrados"), (7, "extrados"), (12, "intrados"),
                                                               (16, "extrados")]
    assert [j for j, _ in limit.hinges_pos] != [m.joint for m in panel.hinges]  # the weights' case differs
    assert panel.sliding == []
    (load,) = limit.point_loads
    assert load.xy_m[0] == pytest.approx(x_crit, abs=1e-12) and load.live
    g = limit.g_m_s2
    for b, block in enumerate(limit.blocks, start=1):
        if block.driven:
            continue
        xy = block.vertices_xy_m
        area = 0.5 * abs(np.dot(xy[:, 0], np.roll(xy[:, 1], -1)) - np.dot(xy[:, 1], np.roll(xy[:, 0], -1)))
        weight = area * 2000.0 * 1.0 * g
        total = np.array([0.0, -weight])
        for f, resultant in zip(limit.contact_forces, panel.force_n):
            total += resultant if f.blocks[1] == b else -resultant if f.blocks[0] == b else 0.0
        if load.block == b:
            total += panel.load_factor * load.force_n
        assert np.allclose(total, 0.0, atol=1e-6 * weight), (b, total)


def test_mechanism_of_a_polygon_file(voussoir_limit_exe, tmp_path, drawn_figures):
    """input/rocking_block.nml (arch null in the JSON): the blocks are drawn, no traceback;
    the block (0.2 x 1.0 m) tips at b/h = 0.2 about its +x corner (0.1, 0) towards +x and its
    -x corner towards -x."""
    path = _limit_json(voussoir_limit_exe, REPO_ROOT / "input" / "rocking_block.nml", tmp_path)
    assert json.loads(path.read_text())["arch"] is None
    assert post.main(["mechanism", str(path), "--out", str(tmp_path / "m.png")]) == 0
    (fig,) = drawn_figures
    assert text_clashes(fig) == [] and "polygon file" in _figure_words(fig)
    data = plot_mechanism(read_limit_json(path), tmp_path / "again.png")
    assert len(data.voussoirs_m) == 2 and [p.direction for p in data.panels] == ["+x", "-x"]
    for panel, corner in zip(data.panels, ([0.1, 0.0], [-0.1, 0.0])):
        assert panel.load_factor == pytest.approx(0.2, rel=1e-9)
        (hinge,) = panel.hinges
        assert np.allclose(hinge.hinge_xy_m, corner, atol=1e-12)


def test_input_without_fill_does_not_claim_an_assessment():
    """The bare ring of input/limit_arch_point_load.nml says what it is not."""
    text = (REPO_ROOT / "input" / "limit_arch_point_load.nml").read_text()
    assert "daily work" not in text and "bare semicircular arch ring" in text


def test_static_capacity_of_any_assembly(voussoir_limit_exe, tmp_path):
    """The envelope's static capacity (voussoir-post envelope --limit) from any JSON: the
    polygon block's LP, b/h g = 0.2 g both ways (it was NaN: the four-hinge keys are null);
    a load case's factor is not an acceleration and is refused, naming the file."""
    block = read_limit_json(_limit_json(voussoir_limit_exe, REPO_ROOT / "input" / "rocking_block.nml", tmp_path))
    assert block.static_capacity_m_s2() == pytest.approx(0.2 * block.g_m_s2, rel=1e-9)
    case = read_limit_json(_limit_json(voussoir_limit_exe, REPO_ROOT / "input" / "bridge_two_spans.nml", tmp_path))
    with pytest.raises(ResultsError, match="bridge_two_spans.json.*live point loads of &load, not a horizontal"):
        case.static_capacity_m_s2()
