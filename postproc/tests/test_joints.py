"""Joints of any assembly (voussoir-post joints): found from the blocks' shapes, their
opening and sliding against hand kinematics and against the closed form of a block
sliding under a growing load."""

from __future__ import annotations

import math

import numpy as np
import pytest

from voussoir_post.analysis.assembly_joints import find_joints, joint_motion
from voussoir_post.cli.post import main

from conftest import run_executable

SQUARE = np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]])


def _stack(offset_x: float = 0.0):
    """Two unit squares, the upper one shifted by `offset_x`: centroids and local vertices."""
    return np.array([[0.0, 0.5], [offset_x, 1.5]]), [SQUARE, SQUARE]


def test_faces_that_touch_are_found_with_their_overlap():
    joints = find_joints(*_stack())
    assert len(joints) == 1 and (joints[0].a, joints[0].b) == (0, 1)
    assert np.linalg.norm(joints[0].ends_m[1] - joints[0].ends_m[0]) == pytest.approx(1.0)
    assert np.allclose(joints[0].normal, [0.0, 1.0])
    half = find_joints(*_stack(0.5))
    assert np.linalg.norm(half[0].ends_m[1] - half[0].ends_m[0]) == pytest.approx(0.5)
    # Apart by 1 mm, or side by side with no overlap: no joint.
    assert find_joints(np.array([[0.0, 0.5], [0.0, 1.501]]), [SQUARE, SQUARE]) == []
    assert find_joints(*_stack(1.0)) == []


def test_sliding_and_opening_by_hand():
    centroids, vertices = _stack()
    joint = find_joints(centroids, vertices)[0]
    # The upper block slides 10 mm to the right: sliding 10 mm, no opening.
    slide = np.zeros((2, 2, 3))
    slide[:, :, :2] = centroids
    slide[1, 1, 0] += 0.010
    m = joint_motion(joint, slide)
    assert abs(m.final_sliding_m) == pytest.approx(0.010) and m.max_sliding_m == pytest.approx(0.010)
    assert m.max_opening_m == pytest.approx(0.0, abs=1e-12)
    # It rocks clockwise by |theta| about its bottom right corner (0.5, 1): its bottom
    # left corner lifts by sin|theta| times the 1 m base; the right end stays shut.
    theta = -0.02
    rock = np.zeros((2, 2, 3))
    rock[:, :, :2] = centroids
    c = np.array([0.5, 1.0]) + np.array([[math.cos(theta), -math.sin(theta)],
                                         [math.sin(theta), math.cos(theta)]]) @ (centroids[1] - [0.5, 1.0])
    rock[1, 1] = [c[0], c[1], theta]
    m = joint_motion(joint, rock)
    assert m.max_opening_m == pytest.approx(math.sin(-theta), rel=1e-9)
    assert m.final_opening_m == pytest.approx(math.sin(-theta), rel=1e-9)


def test_a_slab_slides_as_the_closed_form_says(voussoir_run_exe, tmp_path, capsys):
    """A wide slab on a driven foundation under a load acceleration growing at R: it slides
    once R t exceeds mu g, by R (T - t0)^3 / 6 at time T, t0 = mu g / R (rigid blocks, Coulomb)."""
    mu, rate, duration = 0.3, 1.0, 3.5
    (tmp_path / "slab.txt").write_text("block driven\n-1 -0.1\n1 -0.1\n1 0\n-1 0\n"
                                       "block free\n-0.2 0\n0.2 0\n0.2 0.1\n-0.2 0.1\n")
    (tmp_path / "slab.nml").write_text(
        f"&arch polygon_file = 'slab.txt', friction = {mu}, width_m = 0.1, density_kg_m3 = 2000 /\n"
        f"&motion waveform = 'ramp', ramp_rate_m_s3 = {rate}, duration_s = {duration} /\n"
        "&solver dt_s = 1e-3 /\n&output file = 'slab.h5', every = 10 /\n")
    run_executable([voussoir_run_exe, "slab.nml"], tmp_path)
    assert main(["joints", str(tmp_path / "slab.h5"), "--csv"]) == 0
    out = capsys.readouterr().out
    rows = (tmp_path / "slab_joints.csv").read_text().splitlines()
    assert len(rows) == 2 and rows[0].startswith("body_a,body_b,length_mm") and "1 faces" in out
    cells = dict(zip(rows[0].split(","), rows[1].split(",")))
    expected_mm = 1e3 * rate * (duration - mu * 9.81 / rate) ** 3 / 6.0
    assert abs(float(cells["final_sliding_mm"])) == pytest.approx(expected_mm, rel=0.01)
    assert float(cells["length_mm"]) == pytest.approx(400.0)
    assert abs(float(cells["max_opening_mm"])) < 0.01  # it slides flat, it does not tip
    # Sliding at the end: the base carries the slab's weight m g, and Coulomb's mu m g along it
    # (to the contact solve's default tolerance, 1e-4: the run leaves &solver tol alone).
    weight = 2000 * 0.1 * 0.4 * 0.1 * 9.81
    assert float(cells["final_normal_n"]) == pytest.approx(weight, rel=1e-4)
    assert float(cells["final_shear_n"]) == pytest.approx(mu * weight, rel=1e-4)


def test_no_joint_is_refused_clearly(voussoir_run_exe, tmp_path, capsys):
    (tmp_path / "apart.txt").write_text("block driven\n-1 -0.1\n1 -0.1\n1 0\n-1 0\n"
                                        "block free\n-0.2 0.01\n0.2 0.01\n0.2 0.11\n-0.2 0.11\n")
    (tmp_path / "apart.nml").write_text("&arch polygon_file = 'apart.txt' /\n&motion amplitude_m = 0 /\n"
                                        "&output file = 'apart.h5' /\n")
    run_executable([voussoir_run_exe, "apart.nml"], tmp_path)
    assert main(["joints", str(tmp_path / "apart.h5"), "--tol-mm", "0.1"]) == 2
    assert "no two blocks touch" in capsys.readouterr().err
    assert main(["joints", str(tmp_path / "apart.h5"), "--tol-mm", "-1"]) == 2
    assert "--tol-mm -1: the touching tolerance must be > 0 mm" in capsys.readouterr().err
