"""Contact forces of a run written by the real voussoir-run, against statics worked out by
hand: an arch at rest under its own weight is carried by its springings (vertical
reactions summing to its weight, horizontal ones equal and opposite, each pushing the
ring inwards), and its thrust line lies inside the ring at every joint."""

from __future__ import annotations

import math

import numpy as np
import pytest

from conftest import run_executable

from voussoir_post.analysis.contact_forces import reactions, reactions_table, thrust_line
from voussoir_post.errors import InputError
from voussoir_post.plots.xdmf import check_xdmf, write_xdmf
from voussoir_post.readers.results import read_run

#: The seed's 156-degree arch at rest for 1 s, solved tightly so that the forces balance
#: the weight to far better than 1e-6 once the first steps have settled it.
REST_NML = """\
&arch
  embrace_deg = 156.0, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071,
  width_m = 0.145, density_kg_m3 = 700.0, friction = 0.6, contact_inset_m = 0.0
/
&motion
  waveform = 'afd', frequency_hz = 2.5, amplitude_m = 0.0, rest_s = 1.0
/
&solver
  dt_s = 1.0e-3, tol = 1.0e-9, max_iter = 20000
/
&output
  file = '{file}', every = 50
/
"""


@pytest.fixture(scope="module")
def rest_run(voussoir_run_exe, tmp_path_factory):
    folder = tmp_path_factory.mktemp("rest")
    h5 = folder / "rest.h5"
    (folder / "rest.nml").write_text(REST_NML.format(file=h5))
    run_executable([voussoir_run_exe, folder / "rest.nml"], folder)
    return read_run(h5)


def ring_weight_n(embrace_deg, n, r_ext_m, thickness_m, width_m, density_kg_m3, g=9.81):
    """n voussoirs with straight (chord) faces: each a trapezoid of area
    (r_ext^2 - r_int^2) sin(dphi) / 2."""
    r_int = r_ext_m - thickness_m
    dphi = math.radians(embrace_deg) / n
    return n * 0.5 * (r_ext_m**2 - r_int**2) * math.sin(dphi) * width_m * density_kg_m3 * g


def test_contacts_are_recorded(rest_run):
    c = rest_run.contacts
    assert c is not None and c.start.shape == (rest_run.n_samples + 1,)
    assert np.array_equal(np.diff(c.start), rest_run.contact_count)
    last = c.rows(-1)
    # Every one of the 14 joints shut: two loaded points each.
    assert rest_run.contact_count[-1] == 2 * 14
    assert sorted(c.joint[last].tolist()) == sorted(list(range(14)) * 2)
    assert np.all(c.normal_force_n[last] > 0.0)
    assert np.allclose(c.normal_force_n, c.normal_impulse_n_s / 1.0e-3, rtol=1e-12)
    assert np.allclose(np.hypot(*c.normal.T), 1.0, atol=1e-12)
    assert np.all(np.abs(c.tangent_force_n) <= 0.6 * c.normal_force_n * (1 + 1e-9))


def test_springing_reactions_of_an_arch_at_rest(rest_run):
    weight = ring_weight_n(156.0, 13, 0.508, 0.071, 0.145, 700.0)
    r = reactions(rest_run)
    assert r.role.tolist() == [2, 2]
    left, right = r.force_n[-1]
    assert r.total_n[-1, 1] == pytest.approx(weight, rel=1e-6)
    # (How the weight is shared between the springings is not fixed by statics: the ring
    # is hyperstatic; only the sums are.)
    # The thrust: the left springing pushes the ring towards +x, the right one towards -x, equally.
    assert left[0] > 0.05 * weight and right[0] < 0.0
    assert left[0] + right[0] == pytest.approx(0.0, abs=1e-6 * left[0])
    table = reactions_table(r)
    assert table.columns[0] == "time_s" and len(table.rows) == rest_run.n_samples
    assert table.rows[-1][2] == pytest.approx(left[1])


def test_thrust_line_of_an_arch_at_rest_is_inside_the_ring(rest_run):
    t = thrust_line(rest_run)
    assert t.fraction.shape == (rest_run.n_samples, 14)
    assert np.all(np.isnan(t.fraction[0]))  # t = 0: no step made, no force yet
    later = t.fraction[1:]
    assert np.all(np.isfinite(later))
    assert np.all((later >= 0.0) & (later <= 1.0))
    # The centre of pressure lies on the joint: between its two ends in the reference configuration.
    arch = rest_run.arch
    ends_dist = np.hypot(*(arch.joint_extrados_xy_m - arch.joint_intrados_xy_m).T)
    d_int = np.hypot(*(t.point_m[-1] - arch.joint_intrados_xy_m).T)
    d_ext = np.hypot(*(t.point_m[-1] - arch.joint_extrados_xy_m).T)
    assert np.allclose(d_int + d_ext, ends_dist, atol=1e-6)
    # Each voussoir in equilibrium: from one joint to the next the resultant on the right-hand
    # block drops by the voussoir's weight and keeps its horizontal component (the thrust H).
    weight = ring_weight_n(156.0, 13, 0.508, 0.071, 0.145, 700.0)
    f = t.force_n[-1]
    assert np.allclose(np.diff(f[:, 1]), -weight / 13, rtol=0, atol=1e-6 * weight)
    assert np.allclose(f[:, 0], f[0, 0], rtol=0, atol=1e-6 * weight)
    # Joint 0's resultant on voussoir 1 is the left springing's reaction.
    assert np.allclose(f[0], reactions(rest_run).force_n[-1, 0], atol=1e-9 * weight)


def test_no_thrust_line_without_an_arch(rest_run):
    from dataclasses import replace
    with pytest.raises(InputError, match="no /arch"):
        thrust_line(replace(rest_run, arch=None))
    with pytest.raises(InputError, match="before runs recorded"):
        reactions(replace(rest_run, contacts=None))


def test_xdmf_draws_the_contact_forces(rest_run, tmp_path):
    """The contacts grid of the last sample: one point per loaded contact, at the recorded
    point, with the force on body a; its forces on the voussoirs from the foundations
    sum to the vertical reactions."""
    import xml.etree.ElementTree as ET
    import h5py
    data = write_xdmf(rest_run, tmp_path / "rest.xmf")
    check_xdmf(data.xmf_path)
    assert data.n_contact_points == int(rest_run.contact_count.sum())
    last = ET.parse(data.xmf_path).getroot().find("Domain/Grid").findall("Grid")[-1]
    grid = last.find("Grid[@Name='contacts']")
    assert grid.find("Topology").get("TopologyType") == "Polyvertex"
    assert grid.find("Topology").get("NumberOfElements") == str(rest_run.contact_count[-1])
    force_attr = grid.find("Attribute[@Name='force_n']")
    assert force_attr.get("AttributeType") == "Vector" and force_attr.get("Center") == "Node"
    c = rest_run.contacts
    rows = c.rows(-1)
    with h5py.File(data.h5_path, "r") as h5:
        g = h5[f"samples/{rest_run.n_samples - 1:06d}/contacts"]
        xyz, force, a = g["xyz_m"][()], g["force_n"][()], g["body_a"][()]
        b = g["body_b"][()]
        cell_body = h5["cells/body"][()]
    # One numbering with the text outputs and figures: bodies from 1.
    assert cell_body.tolist() == list(range(1, rest_run.n_bodies + 1))
    assert np.array_equal(a, c.body[rows, 0] + 1) and np.array_equal(b, c.body[rows, 1] + 1)
    assert np.array_equal(xyz[:, :2], c.point_m[rows]) and np.all(xyz[:, 2] == 0.0)
    # Independent of the reader's force_on_a_n: N n + T t with t = n turned +90 degrees.
    n = c.normal[rows]
    expected = c.normal_force_n[rows, None] * n + c.tangent_force_n[rows, None] * np.column_stack([-n[:, 1], n[:, 0]])
    assert np.allclose(force[:, :2], expected, rtol=1e-12, atol=0)
    driven = np.nonzero(rest_run.body_role == 2)[0] + 1  # the export numbers bodies from 1
    on_ring = np.where(np.isin(b, driven), force[:, 1], 0.0) - np.where(np.isin(a, driven), force[:, 1], 0.0)
    assert on_ring.sum() == pytest.approx(ring_weight_n(156.0, 13, 0.508, 0.071, 0.145, 700.0), rel=1e-6)


def test_reactions_figure_of_a_shaken_arch(run_file, tmp_path, capsys):
    """The conftest run (156-degree arch, 2.5 Hz, 50 mm): until the table's acceleration
    first reaches the arch's static capacity (0.376 g, docs/limit_analysis.md) no mechanism
    can open, the ring moves with the table, and Newton gives the supports' horizontal
    reactions summing to its mass times the table's acceleration over the step (at its
    middle: the samples interpolated), the vertical ones to its weight. The figure and
    its CSV through `voussoir-post reactions`."""
    from voussoir_post.cli import post
    from voussoir_post.plots.reactions import free_weight_n, support_names
    run = read_run(run_file)
    r = reactions(run)
    assert support_names(r) == ["left springing (body 14)", "right springing (body 15)"]
    weight = ring_weight_n(156.0, 13, 0.508, 0.071, 0.145, 700.0)
    assert free_weight_n(run) == pytest.approx(weight, rel=1e-9)
    t, a = run.time_s, run.table_a_m_s2
    first_over = int(np.argmax(np.abs(a) >= 0.376 * 9.81))
    assert first_over > 5
    rigid = slice(1, first_over)
    mass = weight / 9.81
    a_mid = np.interp(t - 0.5 * 2.0e-3, t, a)
    assert np.allclose(r.total_n[rigid, 0], mass * a_mid[rigid], rtol=0, atol=0.02 * mass * 0.376 * 9.81)
    assert np.allclose(r.total_n[rigid, 1], weight, rtol=0, atol=0.002 * weight)

    assert post.main(["reactions", str(run_file), "--out", str(tmp_path / "r.png"), "--csv"]) == 0
    out = capsys.readouterr().out
    assert "left springing (body 14)" in out and f"weight of the free blocks {weight:.6g} N" in out
    from PIL import Image
    with Image.open(tmp_path / "r.png") as im:
        assert im.format == "PNG" and im.size[0] >= 800
    lines = (tmp_path / "r.csv").read_text().splitlines()
    assert lines[0] == ("time_s,support1_body14_fx_n,support1_body14_fy_n,support2_body15_fx_n,"
                        "support2_body15_fy_n")
    assert len(lines) == run.n_samples + 1


def test_thrust_line_sits_on_the_hinges_the_kinematics_found(run_file, tmp_path):
    """The conftest run: every hinge the monitors saw open before the collapse (from the
    blocks' positions: one end of the joint apart, the other shut) has its joint's force
    at the edge it pivots on, at the first sample after it opened: the centre of
    pressure within a tenth of the joint of the intrados (0) or the extrados (1)."""
    run = read_run(run_file)
    t = thrust_line(run)
    checked = 0
    for time, joint, side in zip(run.hinge_time_s, run.hinge_joint, run.hinge_side):
        if time >= run.collapse_time_s:
            continue
        k = int(np.searchsorted(run.time_s, time))
        assert t.normal_n[k, joint] > 0.0
        assert abs(t.fraction[k, joint] - float(side)) < 0.1, (time, joint, side, t.fraction[k, joint])
        checked += 1
    assert checked >= 4
    from voussoir_post.cli import post
    assert post.main(["thrust", str(run_file), "--out", str(tmp_path / "t.png"), "--csv"]) == 0
    lines = (tmp_path / "t.csv").read_text().splitlines()
    assert lines[0].startswith("time_s,joint0_fraction,") and len(lines) == run.n_samples + 1
    assert (tmp_path / "t.png").is_file()
