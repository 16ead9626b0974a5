"""&bridge fill_model = 'particles' (issue 37, item 2(b)) in voussoir-run: the fill as free
blocks that stand at rest on the ring and the abutments, every support holding up the
ring and the whole fill (over the abutments too), computed here from the geometry alone."""

from __future__ import annotations

from conftest import run_executable
from hand_geometry import segmental_ring
from voussoir_post.cli import post
from voussoir_post.analysis.contact_forces import reactions
from voussoir_post.plots.reactions import free_weight_n
from voussoir_post.readers.results import read_run

PARTICLES_AT_REST = """\
&bridge shape = 'segmental', span_m(1) = 10.0, rise_m(1) = 2.5, ring_thickness_m = 0.45, n_voussoirs = 12,
  pier_height_m = 3.0, abutment_width_m = 2.0, width_m = 1.0, ring_density_kg_m3 = 2200,
  fill_density_kg_m3 = 2000, fill_level_m = 3.45, fill_model = 'particles', fill_particle_size_m = 0.5,
  fill_particle_friction = 0.6 /
&motion waveform = 'afd', amplitude_m = 0.0, frequency_hz = 1.0, n_full = 0, rest_s = 0.0 /
&solver tol = 1e-6 /
&output file = 'particles.h5' /
"""


def test_the_particles_stand_on_the_ring_at_rest(voussoir_run_exe, tmp_path):
    """At rest the supports (the two abutments) hold up the ring and every particle: the
    ring's voussoirs (segmental: R = (L^2/4 + r^2)/(2r), each a quadrilateral of area
    (R_e^2 - R_i^2) sin(dphi)/2) at 2200 kg/m3 and the fill, the region between the
    abutments' level tops, the extrados chords and the level, from the back of one abutment
    to the back of the other (shoelace), at 2000 kg/m3. No particle is watched for collapse
    nor taken for the crown. The NLGS runs to tol = 1e-6: at 1e-8 it does not converge in
    10000 iterations on the second step (the particles' many contacts); the supports' sum
    is then within 1e-5 of the weight (measured 5.7e-6: 598936.1 N against 598939.5 N)."""
    nml = tmp_path / "particles.nml"
    nml.write_text(PARTICLES_AT_REST)
    out = run_executable([voussoir_run_exe, nml], tmp_path).stdout
    assert out.startswith("stood;")
    run = read_run(tmp_path / "particles.h5")
    assert run.config["bridge"]["fill_model"] == "particles"
    span, rise, t, n, level, w, g = 10.0, 2.5, 0.45, 12, 3.45, 2.0, 9.81
    ring_area, ex, ey = segmental_ring(span, rise, t, n)
    region = [(-w, ey[0]), *zip(ex, ey), (span + w, ey[-1]), (span + w, level), (-w, level)]
    fill_area = 0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(region, region[1:] + region[:1]))
    expected = (2200 * ring_area + 2000 * fill_area) * g * 1.0
    particles = run.body_role == 4
    assert n + particles.sum() + 2 == run.n_bodies and particles.sum() > 50
    r = reactions(run)
    assert sorted(r.bodies.tolist()) == [n, n + 1]          # the abutments alone are supports
    held = float(r.force_n[-1, :, 1].sum())
    assert abs(held - expected) <= 1e-5 * expected, (held, expected)
    assert abs(float(r.force_n[-1, :, 0].sum())) <= 1e-5 * expected
    # The reactions figure's weight line counts the particles at the fill's density.
    assert abs(free_weight_n(run) - expected) <= 1e-9 * expected


def test_a_vehicle_stands_on_the_particles_at_rest(voussoir_run_exe, tmp_path):
    """A standing 2-axle vehicle (100 kN each, first axle at x = 3 m) on the particles at the
    surface: the abutments hold up the ring, the fill and the axles (the same geometry by
    hand as above, + 200 kN). At NLGS tol 1e-6 the run did not converge within 10000
    sweeps at step 164; at 1e-5 the supports' sum is within 1e-4 of the load (measured
    3.4e-5: 798966.7 N against 798939.5 N)."""
    nml = tmp_path / "vehicle.nml"
    nml.write_text(PARTICLES_AT_REST.replace("tol = 1e-6", "tol = 1e-5").replace(
        "&solver", "&load path_x0_m = 2.0, path_x1_m = 8.0, path_points = 3 /\n"
                   "&vehicle axle_load_kn = 100, 100, axle_spacing_m = 1.5, first_axle_x_m = 3.0 /\n&solver"))
    out = run_executable([voussoir_run_exe, nml], tmp_path).stdout
    assert out.startswith("stood;")
    run = read_run(tmp_path / "particles.h5")
    r = reactions(run)
    span, rise, t, n, level, w, g = 10.0, 2.5, 0.45, 12, 3.45, 2.0, 9.81
    ring_area, ex, ey = segmental_ring(span, rise, t, n)
    region = [(-w, ey[0]), *zip(ex, ey), (span + w, ey[-1]), (span + w, level), (-w, level)]
    fill_area = 0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(region, region[1:] + region[:1]))
    expected = (2200 * ring_area + 2000 * fill_area) * g * 1.0 + 2 * 100e3
    held = float(r.force_n[-1, :, 1].sum())
    assert abs(held - expected) <= 1e-4 * expected, (held, expected)


def test_the_bridge_report_refuses_particles(voussoir_limit_exe, tmp_path, capsys):
    """The bridge report tells the engineers' columns (the fill's weight on the ring, the
    spread, the pressures): on a bridge whose fill is particles it would report no fill on
    the ring and a spread of 0 degrees, so it refuses (exit 2), naming the file and why.
    (1 m particles and one load position: a few seconds of LP.)"""
    nml = tmp_path / "coarse.nml"
    nml.write_text(PARTICLES_AT_REST.split("&motion")[0].replace("fill_particle_size_m = 0.5", "fill_particle_size_m = 1.0")
                   + "&load point_load_n(1) = 100000, point_load_x_m(1) = 3.0, point_load_y_m(1) = 3.45 /\n")
    out = run_executable([voussoir_limit_exe, nml, "--json"], tmp_path).stdout
    (tmp_path / "coarse.json").write_text(out)
    assert post.main(["bridge-report", str(tmp_path / "coarse.json"), "--out", str(tmp_path / "report")]) == 2
    err = capsys.readouterr().err
    assert "coarse.json: its fill is particles" in err and not (tmp_path / "report" / "report.md").exists()
