"""&bridge backing_level_m (issue 37) in voussoir-run: the masonry backing as free blocks in
courses that stand at rest on the abutments and the haunches, the fill's columns standing on
them, every support holding up the ring, the backing and the whole fill, computed here from
the geometry alone."""

from __future__ import annotations

import re
from pathlib import Path

from conftest import run_executable
from hand_geometry import backed_area, segmental_ring
from voussoir_post.cli import post
from voussoir_post.analysis.contact_forces import reactions
from voussoir_post.analysis.kinematics import ROLE_BACKING
from voussoir_post.plots.reactions import free_weight_n
from voussoir_post.readers.results import read_run

BACKING_AT_REST = """\
&bridge shape = 'segmental', span_m(1) = 10.0, rise_m(1) = 2.5, ring_thickness_m = 0.45, n_voussoirs = 12,
  pier_height_m = 3.0, abutment_width_m = 2.0, width_m = 1.0, ring_density_kg_m3 = 2200,
  fill_density_kg_m3 = 2000, fill_level_m = 3.45,
  backing_level_m = 1.5, backing_course_m = 0.3, backing_density_kg_m3 = 2100 /
&motion waveform = 'afd', amplitude_m = 0.0, frequency_hz = 1.0, n_full = 0, rest_s = 0.0 /
&solver tol = 1e-5 /
&output file = 'backing.h5' /
"""


def test_the_backing_and_the_fill_stand_on_the_ring_at_rest(voussoir_run_exe, tmp_path):
    """At rest the two abutments hold up the ring (segmental: R = (L^2/4 + r^2)/(2r), each
    voussoir a quadrilateral of area (R_e^2 - R_i^2) sin(dphi)/2) at 2200 kg/m3, the backing
    (the trapezoids between its level and the abutments' tops and the extrado chords wholly
    below it) at 2100 kg/m3 and the fill (between the extrados, the abutments' tops and its
    level, less the backing) at 2000 kg/m3, carried as the mass of the blocks beneath it.
    No backing block is watched for collapse nor taken for the crown; the reactions
    figure's weight counts the backing at its own density. The NLGS runs to tol = 1e-5:
    at 1e-6 it stops at 10000 iterations on the sixth step (norm 1.2e-6)."""
    nml = tmp_path / "backing.nml"
    nml.write_text(BACKING_AT_REST)
    out = run_executable([voussoir_run_exe, nml], tmp_path).stdout
    assert out.startswith("stood;")
    run = read_run(tmp_path / "backing.h5")
    span, rise, t, n, level, back, w, g = 10.0, 2.5, 0.45, 12, 3.45, 1.5, 2.0, 9.81
    ring_area, ex, ey = segmental_ring(span, rise, t, n)
    bottom = [(-w, ey[0]), *zip(ex, ey), (span + w, ey[-1])]
    backing_area = backed_area(bottom, back)
    fill_area = sum((x1 - x0) * (level - (y0 + y1) / 2) for (x0, y0), (x1, y1) in zip(bottom, bottom[1:])) \
        - backing_area
    expected = (2200 * ring_area + 2100 * backing_area + 2000 * fill_area) * g * 1.0
    backing = run.body_role == ROLE_BACKING
    assert backing.sum() >= 8 and n + backing.sum() + 2 == run.n_bodies
    r = reactions(run)
    assert sorted(r.bodies.tolist()) == [n, n + 1]          # the abutments alone are supports
    held = float(r.force_n[-1, :, 1].sum())
    assert abs(held - expected) <= 1e-5 * expected, (held, expected)
    assert abs(float(r.force_n[-1, :, 0].sum())) <= 1e-5 * expected
    ring_and_backing = (2200 * ring_area + 2100 * backing_area) * g
    assert abs(free_weight_n(run) - ring_and_backing) <= 1e-9 * ring_and_backing


def test_the_bridge_report_lists_the_backing_and_its_weight(voussoir_limit_exe, tmp_path):
    """voussoir-post bridge-report on input/bridge_backing.nml: the geometry says where the
    backing stands and how it is laid, and its weight is 2200 kg/m3 x g x the trapezoids
    between its level and the abutments' tops and the extrados chords wholly below it,
    computed here from the segmental geometry (to the report's 4 digits); the fill's row
    says it stands on the backing too."""
    nml = Path(__file__).resolve().parents[2] / "input" / "bridge_backing.nml"
    out = run_executable([voussoir_limit_exe, nml, "--json"], tmp_path).stdout
    (tmp_path / "backing.json").write_text(out)
    assert post.main(["bridge-report", str(tmp_path / "backing.json"), "--out", str(tmp_path / "report")]) == 0
    text = (tmp_path / "report" / "report.md").read_text()
    span, rise, t, n, back, w, g = 10.0, 2.5, 0.45, 20, 1.5, 2.0, 9.81
    _, ex, ey = segmental_ring(span, rise, t, n)
    area = backed_area([(-w, ey[0]), *zip(ex, ey), (span + w, ey[-1])], back)
    row = re.search(r"\| the backing's weight \| ([0-9.]+) \|", text)
    assert row and abs(float(row.group(1)) - 2200 * g * area / 1e3) <= 0.05, (row, 2200 * g * area / 1e3)
    assert "- Backing: masonry over the haunches up to 1.5 m above the springings" in text
    assert "courses of 0.3 m" in text and "| the fill's weight on the ring and the backing |" in text
