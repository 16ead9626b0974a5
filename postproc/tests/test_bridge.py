"""&bridge (issue 37) through the executables: voussoir-run takes the bridge (each part's
mass, the effective &bridge recorded in the result file; the fill as mass the voussoirs
carry, its pressure and a vehicle as constant forces) and the mechanism figure of the
two-span bridge of input/ is the load case's."""

from __future__ import annotations

import numpy as np
import pytest

from hand_geometry import segmental_ring
from conftest import REPO_ROOT, run_executable
from figure_text import text_clashes
from voussoir_post.cli import post
from voussoir_post.plots.drawing import bridge_caption, run_caption
from voussoir_post.plots.mechanism import plot_mechanism
from voussoir_post.plots.reactions import free_weight_n
from voussoir_post.readers.results import read_limit_json, read_run

BRIDGE = """\
&bridge shape = 'segmental', span_m = 10.0, 10.0, rise_m = 2.5, 2.5, ring_thickness_m = 0.45,
  n_voussoirs = 12, pier_width_m = 1.5, pier_height_m = 3.0, abutment_width_m = 2.0,
  ring_density_kg_m3 = 2200, pier_density_kg_m3 = 2400 /
&motion waveform = 'afd', amplitude_m = 0.0, frequency_hz = 1.0, n_full = 0, rest_s = 0.0 /
&output file = 'bridge.h5' /
"""


def test_a_bridge_stands_in_voussoir_run(voussoir_run_exe, tmp_path):
    """At rest a two-span bridge stands (its blocks move by round-off only), and the
    result file records the &bridge group as run, so the figures can say what was run."""
    nml = tmp_path / "bridge.nml"
    nml.write_text(BRIDGE)
    out = run_executable([voussoir_run_exe, nml], tmp_path).stdout
    assert out.startswith("stood;")
    run = read_run(tmp_path / "bridge.h5")
    bridge = run.config["bridge"]
    assert bridge["shape"] == "segmental" and float(bridge["pier_density_kg_m3"]) == 2400.0
    assert float(bridge["span_m(2)"]) == 10.0
    # At rest the supports hold up the free blocks' weight, each part at its own density
    # (the piers 2400 kg/m3, the ring 2200): the reactions figure's reference line.
    c = run.contacts
    rows = c.rows(-1)
    driven = run.body_role != 1
    a, b = c.body[rows, 0], c.body[rows, 1]
    force = c.force_on_a_n()[rows]
    on_free = np.where((driven[a] & ~driven[b])[:, None], -force, force)[driven[a] ^ driven[b]]
    weight = free_weight_n(run)
    assert abs(float(on_free[:, 1].sum()) - weight) <= 1e-6 * weight
    caption = run_caption(run)
    assert caption.startswith("bridge of 2 segmental spans of 10, 10 m (rise 2.5, 2.5 m), ring 450 mm of 12 voussoirs")


def test_mechanism_of_the_two_span_bridge(voussoir_limit_exe, tmp_path, drawn_figures):
    """input/bridge_two_spans.nml: one panel (a load case), titled by the live load with the
    vehicle's critical x, in the bridge's frame (x from the left springing), four hinges,
    the live load drawn at the critical position; no text overlapping or cut."""
    path = tmp_path / "bridge_two_spans.json"
    path.write_text(run_executable([voussoir_limit_exe, REPO_ROOT / "input" / "bridge_two_spans.nml", "--json"],
                                   tmp_path).stdout)
    assert post.main(["mechanism", str(path), "--out", str(tmp_path / "m.png")]) == 0
    (fig,) = drawn_figures
    assert text_clashes(fig) == []
    assert fig.axes[0].get_xlabel() == "x [m] from the left springing of span 1"
    limit = read_limit_json(path)
    data = plot_mechanism(limit, tmp_path / "again.png")
    (panel,) = data.panels
    assert len(panel.hinges) == 4 and panel.load_factor == pytest.approx(limit.load_factor, rel=1e-12)
    assert "span 1 voussoir 20 / pier 1" in data.table.column("blocks")  # the hinge on the pier, by name
    (load,) = limit.point_loads
    assert load.xy_m[0] == pytest.approx(limit.critical_x_m, abs=1e-12)
    assert any("bridge of 44 blocks (&bridge)" in t.get_text() for t in fig.texts)  # the suptitle
    assert np.isfinite(data.force_scale_m_per_n)


def test_mechanism_with_the_fill(voussoir_limit_exe, tmp_path, drawn_figures):
    """input/bridge_fill.nml: the live load drawn where it stands, on the fill's surface
    (not on the extrados), the fill's surface and the load's spread in the legend with the
    fill's weight (the JSON's fill loads summed); no text overlapping or cut."""
    path = tmp_path / "bridge_fill.json"
    path.write_text(run_executable([voussoir_limit_exe, REPO_ROOT / "input" / "bridge_fill.nml", "--json"],
                                   tmp_path).stdout)
    assert post.main(["mechanism", str(path), "--out", str(tmp_path / "m.png")]) == 0
    (fig,) = drawn_figures
    assert text_clashes(fig) == []
    limit = read_limit_json(path)
    (surface,) = limit.surface_loads
    assert surface.xy_m[1] == 3.45 and surface.xy_m[0] == pytest.approx(limit.critical_x_m, abs=1e-12)
    fill_kn = sum(-f.force_n[1] for f in limit.fill_loads) / 1e3
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert any("fill surface, y = 3.45 m" in t and f"{fill_kn:.4g} kN" in t for t in labels)
    assert any("100 kN at factor 1" in t for t in labels)


def test_mechanism_with_the_fill_pressure(voussoir_limit_exe, tmp_path, drawn_figures):
    """input/bridge_fill.nml with the fill's horizontal pressure (phi 35 deg, a third of the
    passive mobilised): the pressures drawn with their own key, their total at collapse the
    JSON's; no text overlapping or cut."""
    nml = tmp_path / "bridge_pressure.nml"
    nml.write_text((REPO_ROOT / "input" / "bridge_fill.nml").read_text().replace(
        "dispersion_angle_deg = 30", "dispersion_angle_deg = 30, fill_friction_deg = 35, passive_mobilisation = 0.33"))
    path = tmp_path / "bridge_pressure.json"
    path.write_text(run_executable([voussoir_limit_exe, nml, "--json"], tmp_path).stdout)
    assert post.main(["mechanism", str(path), "--out", str(tmp_path / "m.png")]) == 0
    (fig,) = drawn_figures
    assert text_clashes(fig) == []
    limit = read_limit_json(path)
    total_kn = sum(abs(p.force_n[0]) for p in limit.fill_pressures) / 1e3
    labels = [t.get_text().replace("\n", " ") for t in fig.legends[0].get_texts()]
    assert any("horizontal pressure" in t and f"{total_kn:.4g} kN in all" in t for t in labels)


def test_mechanism_with_boussinesq(voussoir_limit_exe, tmp_path, drawn_figures):
    """input/bridge_fill.nml with dispersion = 'boussinesq': no dotted lines bound the
    spread (it has no ends of its own); the pressure on the extrados is drawn as a filled
    profile over the spread, its peak in the legend the JSON's greatest strip load over
    its length (read with json alone); no text overlapping or cut."""
    import json

    nml = tmp_path / "bridge_boussinesq.nml"
    nml.write_text((REPO_ROOT / "input" / "bridge_fill.nml").read_text().replace(
        "dispersion_angle_deg = 30", "dispersion = 'boussinesq'"))
    path = tmp_path / "bridge_boussinesq.json"
    path.write_text(run_executable([voussoir_limit_exe, nml, "--json"], tmp_path).stdout)
    assert post.main(["mechanism", str(path), "--out", str(tmp_path / "m.png")]) == 0
    (fig,) = drawn_figures
    assert text_clashes(fig) == []
    (surface,) = json.loads(path.read_text())["surface_loads"]
    edges, loads = surface["strip_edges_x_m"], surface["strip_load_n"]
    peak_kn = max(q / (b - a) for q, a, b in zip(loads, edges, edges[1:])) / 1e3
    labels = [t.get_text().replace("\n", " ") for t in fig.legends[0].get_texts()]
    assert any(t.startswith("Boussinesq") and f"peak {peak_kn:.4g} kN/m" in t and f"{surface['retained']:.3g}" in t
               for t in labels)
    assert not any("dotted lines" in t for t in labels)
    ax = fig.axes[0]
    assert not any(line.get_linestyle() == ":" for line in ax.get_lines())
    (profile,) = [c for c in ax.collections if c.get_gid() == "boussinesq_pressure"]
    xs = profile.get_paths()[0].vertices[:, 0]
    assert min(xs) == pytest.approx(edges[0], abs=1e-9) and max(xs) == pytest.approx(edges[-1], abs=1e-9)


FILL_RUN = """\
&bridge shape = 'segmental', span_m(1) = 10.0, rise_m(1) = 2.5, ring_thickness_m = 0.45, n_voussoirs = 12,
  pier_height_m = 3.0, abutment_width_m = 2.0, width_m = 1.0, ring_density_kg_m3 = 2200,
  fill_density_kg_m3 = 2000, fill_level_m = 3.45, dispersion_angle_deg = 30, fill_friction_deg = 35 /
&load path_x0_m = 2.0, path_x1_m = 8.0, path_points = 3 /
&vehicle axle_load_kn = 100, 100, axle_spacing_m = 1.5, first_axle_x_m = 3.0 /
&motion waveform = 'afd', amplitude_m = 0.0, frequency_hz = 1.0, n_full = 0, rest_s = 0.0 /
&solver tol = 1e-8 /
&output file = 'fill.h5' /
"""


def test_the_fill_and_a_vehicle_stand_in_voussoir_run(voussoir_run_exe, tmp_path):
    """voussoir-run carries a bridge's fill as mass that each voussoir carries (its weight
    comes from gravity on that mass), its active pressure as constant forces, and a vehicle
    standing at first_axle_x_m: at rest the abutments hold up the
    ring's weight, the fill over the ring and the axles, computed here from the geometry
    alone (segmental ring: R = (L^2/4 + r^2)/(2r), voussoir k between angles phi_k and
    phi_k+1, each a quadrilateral of area (R_e^2 - R_i^2) sin(dphi)/2; the fill the area
    between the extrados chords and the level), and the active pressures balance (the
    span is symmetric). The NLGS runs to tol = 1e-8: with the fill as mass (heavier,
    top-heavy voussoirs) its default Quad norm of 1e-4 left the ring ringing by micrometres
    and the supports' sum 3e-4 off the weight (measured: -204 N .. +381 N in 594 kN over
    the run's samples), the solver's error, not the statics'."""
    nml = tmp_path / "fill.nml"
    nml.write_text(FILL_RUN)
    out = run_executable([voussoir_run_exe, nml], tmp_path).stdout
    assert out.startswith("stood;")
    run = read_run(tmp_path / "fill.h5")
    assert float(run.config["vehicle"]["axle_load_kn(2)"]) == 100.0
    span, rise, t, n, level, g = 10.0, 2.5, 0.45, 12, 3.45, 9.81
    # The extrados ends of the joints (the centre at (L/2, r - R)), and the fill above their chords.
    ring_area, ex, ey = segmental_ring(span, rise, t, n)
    fill_area = sum((ex[k + 1] - ex[k]) * (level - 0.5 * (ey[k] + ey[k + 1])) for k in range(n))
    expected = (2200 * ring_area + 2000 * fill_area) * g * 1.0 + 2 * 100e3
    c = run.contacts
    rows = c.rows(-1)
    driven = run.body_role != 1
    force = c.force_on_a_n()[rows]
    a, b = c.body[rows, 0], c.body[rows, 1]
    # The force on the free block of every free-driven contact (a's force, or minus it when a is driven).
    on_free = np.where((driven[a] & ~driven[b])[:, None], -force, force)[driven[a] ^ driven[b]]
    lifted = float(on_free[:, 1].sum())
    # (measured: 594295.0850 N against 594295.0850 N, of which the fill 278134 N)
    assert abs(lifted - expected) <= 1e-6 * expected, (lifted, expected)
    assert abs(float(on_free[:, 0].sum())) <= 1e-6 * expected
    # The left half of the ring (voussoirs 1..6) in horizontal equilibrium: the fill's active
    # pressure on its extrados faces, into the ring (+x), sums over the contiguous faces from
    # the springing's extrados end (y_0) to the crown's (y_6) to K_a w_f ((F - y_0)^2 - (F - y_6)^2)/2,
    # with K_a = tan^2(45 - phi/2) (Rankine); the contacts (abutment, voussoir 7) hold it.
    k_a = np.tan(np.radians(45 - 35 / 2)) ** 2
    pressure = k_a * 2000 * g * 1.0 * ((level - ey[0]) ** 2 - (level - ey[n // 2]) ** 2) / 2
    half = np.zeros(len(run.body_role), dtype=bool)
    half[: n // 2] = True
    across = half[a] ^ half[b]
    on_half = np.where((half[b] & ~half[a])[:, None], -force, force)[across]
    assert pressure > 0.05 * 2000 * g * fill_area / 2       # not negligible: a check that can fail
    # (the sum of the contacts' x-forces, each up to 2e5 N, to the solver's round-off: 1e-6 of the largest;
    # measured 0.046 N in 26218 N)
    scale = float(np.abs(on_half[:, 0]).max())
    assert abs(float(on_half[:, 0].sum()) + pressure) <= 1e-6 * scale, (float(on_half[:, 0].sum()), pressure)
    caption = run_caption(run)
    assert "fill to 3.45 m (2000 kg/m³) as mass the ring carries, its active pressure as forces" in caption
    assert "vehicle (axles 100 + 100 kN, 1.5 m apart) standing from x = 3 m" in caption and "arch of" not in caption


def test_a_multi_ring_bridge_in_words():
    """&bridge n_rings > 1 in a figure's caption (a run file's /config keys); one ring as before."""
    bridge = {"shape": "segmental", "span_m(1)": 6.0, "rise_m(1)": 1.5, "ring_thickness_m": 0.45, "n_voussoirs": 12}
    assert bridge_caption(bridge) == "bridge of 1 segmental span of 6 m (rise 1.5 m), ring 450 mm of 12 voussoirs"
    assert bridge_caption({**bridge, "n_rings": 4}) == ("bridge of 1 segmental span of 6 m (rise 1.5 m), ring 450 mm "
                                                       "in 4 rings of 12 voussoirs")
