"""`voussoir-post vtk`: the .pvd/.vtu export of runs written by the real voussoir-run,
read back with meshio and checked against the run file's own datasets: one polygon per
block, bodies numbered from 1, the arch's joints 0..n with their opening and the hinge
state the sequence figures draw, and the loaded contacts as points with their forces."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest

from conftest import run_executable

from voussoir_post.analysis.kinematics import joint_openings, joint_states
from voussoir_post.cli import post
from voussoir_post.readers.results import read_run

HINGE_CODE = {"intrados": 1, "extrados": 2, "separated": 3}


def world_vertices(run, sample, body):
    """Vertices straight from the datasets: centroid + R(theta) * local vertex."""
    x, y, th = run.body_position[sample, body]
    local = run.vertices_local_m[body, : run.n_vertices[body]]
    rot = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
    return np.array([x, y]) + local @ rot.T


def pvd_entries(path):
    """[(time, part, file)] of a .pvd collection, files as written (relative)."""
    root = ET.parse(path).getroot()
    assert root.get("type") == "Collection"
    return [(float(d.get("timestep")), int(d.get("part")), d.get("file")) for d in root.iter("DataSet")]


def cell_values(mesh, name):
    return np.concatenate(mesh.cell_data[name])


@pytest.fixture(scope="module")
def export(run_file, tmp_path_factory):
    """The session's collapsing arch run exported by the command line."""
    out = tmp_path_factory.mktemp("vtk")
    assert post.main(["vtk", str(run_file), "--out", str(out)]) == 0
    return read_run(run_file), out


def test_pvd_lists_every_sample_and_part(export):
    run, out = export
    stem = "arch156"
    entries = pvd_entries(out / f"{stem}.pvd")
    assert len(entries) == 3 * run.n_samples
    assert [t for t, part, _ in entries if part == 0] == pytest.approx(list(run.time_s))
    assert sorted({part for _, part, _ in entries}) == [0, 1, 2]
    assert all((out / f).is_file() for _, _, f in entries)
    for part, name in enumerate(("blocks", "joints", "contacts")):
        alone = pvd_entries(out / f"{stem}_{name}.pvd")
        assert [f for _, _, f in alone] == [f for _, p, f in entries if p == part]
        assert all(f"/{name}_" in f for _, _, f in alone)


def test_blocks_are_polygons_numbered_from_1(export):
    run, out = export
    for k in (0, run.n_samples // 2, run.n_samples - 1):
        mesh = meshio.read(out / "arch156_vtu" / f"blocks_{k:06d}.vtu")
        assert [c.type for c in mesh.cells] == ["polygon"] * len(mesh.cells)
        assert sum(len(c.data) for c in mesh.cells) == run.n_bodies
        assert cell_values(mesh, "body").tolist() == list(range(1, run.n_bodies + 1))
        assert cell_values(mesh, "role").tolist() == run.body_role.tolist()
        assert np.allclose(cell_values(mesh, "rotation_rad"), run.body_position[k, :, 2], rtol=0, atol=1e-15)
        # The polygon of body b (cell b - 1) has the vertices of body b in the run file.
        conn = np.vstack([c.data for c in mesh.cells])
        for b in (0, run.n_bodies // 2, run.n_bodies - 1):
            assert np.allclose(mesh.points[conn[b], :2], world_vertices(run, k, b), atol=1e-12)
        velocity = np.vstack(mesh.cell_data["velocity_m_s"])
        assert velocity.shape == (run.n_bodies, 3) and np.all(velocity[:, 2] == 0.0)
    # An interior sample: the central difference of the sampled positions.
    k = run.n_samples // 2
    mesh = meshio.read(out / "arch156_vtu" / f"blocks_{k:06d}.vtu")
    h_back, h_next = run.time_s[k] - run.time_s[k - 1], run.time_s[k + 1] - run.time_s[k]
    assert math.isclose(h_back, h_next)  # every = 5 steps: evenly spaced samples
    expected = (run.body_position[k + 1, :, :2] - run.body_position[k - 1, :, :2]) / (h_back + h_next)
    assert np.allclose(np.vstack(mesh.cell_data["velocity_m_s"])[:, :2], expected, rtol=1e-9, atol=1e-12)


def test_joints_are_the_arch_joints_with_opening_and_hinge(export):
    """Joint j between voussoir j and j + 1 (bodies from 1; 0 and n the springings), its
    openings those of kinematics.joint_openings and its hinge state that of the sequence
    figures (kinematics.joint_states) at every sample."""
    run, out = export
    n = run.arch.n_voussoirs
    hinged = 0
    for k in range(run.n_samples):
        mesh = meshio.read(out / "arch156_vtu" / f"joints_{k:06d}.vtu")
        assert [c.type for c in mesh.cells] == ["line"] and len(mesh.cells[0].data) == n + 1
        assert cell_values(mesh, "joint").tolist() == list(range(n + 1))
        a, b = cell_values(mesh, "body_a"), cell_values(mesh, "body_b")
        assert a[1:].tolist() == list(range(1, n + 1)) and b[:-1].tolist() == list(range(1, n + 1))
        assert run.body_role[a[0] - 1] == 2 and run.body_role[b[-1] - 1] == 2
        openings = np.column_stack([cell_values(mesh, "opening_intrados_m"), cell_values(mesh, "opening_extrados_m")])
        assert np.allclose(openings, joint_openings(run, k), rtol=0, atol=1e-9)
        expected = np.zeros(n + 1, dtype=int)
        for state in joint_states(run, k):
            expected[state.joint] = HINGE_CODE[state.state]
        assert cell_values(mesh, "hinge").tolist() == expected.tolist(), f"sample {k}"
        hinged += int(np.count_nonzero(expected))
        for name in ("opening_m", "sliding_m", "normal_force_n", "shear_force_n"):
            assert cell_values(mesh, name).shape == (n + 1,)
    assert hinged > 0  # the run collapses: hinges open


def test_contacts_are_points_with_their_forces(export):
    run, out = export
    c = run.contacts
    first = (out / "arch156_vtu" / "contacts_000000.vtu").read_text()
    assert 'NumberOfPoints="0"' in first  # no step made, no contact loaded
    for k in range(1, run.n_samples):
        rows = c.rows(k)
        mesh = meshio.read(out / "arch156_vtu" / f"contacts_{k:06d}.vtu")
        assert len(mesh.points) == run.contact_count[k] > 0
        assert np.array_equal(mesh.points[:, :2], c.point_m[rows]) and np.all(mesh.points[:, 2] == 0.0)
        n = c.normal[rows]
        expected = c.normal_force_n[rows, None] * n + c.tangent_force_n[rows, None] * np.column_stack([-n[:, 1],
                                                                                                       n[:, 0]])
        assert np.allclose(mesh.point_data["force_n"][:, :2], expected, rtol=1e-12, atol=0)
        assert np.array_equal(mesh.point_data["body_a"], c.body[rows, 0] + 1)
        assert np.array_equal(mesh.point_data["body_b"], c.body[rows, 1] + 1)
        assert np.array_equal(mesh.point_data["joint"], c.joint[rows])
        assert mesh.point_data["body_a"].min() >= 1 and mesh.point_data["body_b"].max() <= run.n_bodies


BLOCK_NML = """\
&arch
  polygon_file = '{blocks}', thickness_m = 0.2, width_m = 0.2, density_kg_m3 = 2000, friction = 0.7
/
&motion
  waveform = 'afd', frequency_hz = 2.0, amplitude_m = 0.02, rest_s = 0.2
/
&solver
  dt_s = 2.0e-3
/
&output
  file = '{file}', every = 10
/
"""

#: Two blocks stacked on a driven base: two faces where blocks touch, no arch numbering.
BLOCKS = """\
block driven
-1.0 -0.2
 1.0 -0.2
 1.0  0.0
-1.0  0.0
block free
-0.1 0.0
 0.1 0.0
 0.1 0.5
-0.1 0.5
block free
-0.1 0.5
 0.1 0.5
 0.1 1.0
-0.1 1.0
"""


def test_polygon_assembly_joints_are_the_touching_faces(voussoir_run_exe, tmp_path):
    (tmp_path / "blocks.txt").write_text(BLOCKS)
    h5 = tmp_path / "stack.h5"
    (tmp_path / "stack.nml").write_text(BLOCK_NML.format(blocks=tmp_path / "blocks.txt", file=h5))
    run_executable([voussoir_run_exe, tmp_path / "stack.nml"], tmp_path)
    assert post.main(["vtk", str(h5)]) == 0
    assert post.main(["vtk", str(h5), "--every", "4"]) == 0  # again, sparser: the other samples' files go
    run = read_run(h5)
    entries = pvd_entries(tmp_path / "stack.pvd")
    written = list(range(0, run.n_samples, 4)) + ([run.n_samples - 1] if (run.n_samples - 1) % 4 else [])
    assert [t for t, part, _ in entries if part == 0] == pytest.approx(list(run.time_s[written]))
    assert sorted(p.name for p in (tmp_path / "stack_vtu").iterdir()) == sorted(
        f"{part}_{k:06d}.vtu" for k in written for part in ("blocks", "joints", "contacts"))
    last = written[-1]
    blocks = meshio.read(tmp_path / "stack_vtu" / f"blocks_{last:06d}.vtu")
    assert cell_values(blocks, "body").tolist() == [1, 2, 3]
    joints = meshio.read(tmp_path / "stack_vtu" / f"joints_{last:06d}.vtu")
    assert cell_values(joints, "joint").tolist() == [-1, -1]
    assert sorted(zip(cell_values(joints, "body_a").tolist(), cell_values(joints, "body_b").tolist())) == \
        [(1, 2), (2, 3)]
    assert "opening_end1_m" in joints.cell_data and "hinge" in joints.cell_data
