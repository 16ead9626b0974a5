"""history, sequence and xdmf on a file written by the real voussoir-run: the plotted
numbers are checked against the datasets, not only that a PNG exists."""

from __future__ import annotations

import hashlib
import math
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import pytest
from PIL import Image

from conftest import RUN_NML, run_executable

from voussoir_post.plots.history import plot_history
from voussoir_post.analysis.kinematics import block_polygons, default_open_tol_m, joint_openings, joint_states
from voussoir_post.readers.results import read_run
from voussoir_post.plots.sequence import default_frame_times, plot_sequence, write_sequence_gif
from voussoir_post.plots.xdmf import check_xdmf, write_xdmf


def assert_png(path, min_width=400):
    with Image.open(path) as im:
        assert im.format == "PNG"
        assert im.size[0] >= min_width and im.size[1] >= 200


def world_vertices(run, sample, body):
    """Vertices straight from the datasets: centroid + R(theta) * local vertex."""
    x, y, th = run.body_position[sample, body]
    local = run.vertices_local_m[body, : run.n_vertices[body]]
    rot = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
    return np.array([x, y]) + local @ rot.T


def area_centroid(xy):
    x, y = xy[:, 0], xy[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    w = x * yn - xn * y
    return np.array([((x + xn) * w).sum(), ((y + yn) * w).sum()]) / (3.0 * w.sum())


def test_history_plots_the_file_series(run_file, tmp_path, drawn_figures):
    from figure_text import text_clashes

    run = read_run(run_file)
    data = plot_history(run, tmp_path / "history.png")
    assert_png(data.png_path)
    assert text_clashes(drawn_figures[0]) == []  # no text box over another, none cut
    assert np.array_equal(data.time_s, run.time_s)
    assert np.allclose(data.table_x_mm, 1e3 * run.table_x_m)
    assert np.array_equal(data.table_v_m_s, run.table_v_m_s)
    assert np.array_equal(data.table_a_m_s2, run.table_a_m_s2)
    assert np.allclose(data.crown_dx_mm, 1e3 * run.crown_dx_m)
    assert np.allclose(data.crown_dy_mm, 1e3 * run.crown_dy_m)
    assert np.array_equal(data.step_iterations, run.step_iterations)
    assert np.array_equal(data.contact_count, run.contact_count)
    assert data.collapse_time_s == run.collapse_time_s
    # the commanded afd motion: 50 mm peak, peak acceleration close to A (2 pi f)^2
    assert np.abs(data.table_x_mm).max() == pytest.approx(50.0, rel=0.02)
    assert np.abs(data.table_a_m_s2).max() == pytest.approx(0.05 * (2 * math.pi * 2.5) ** 2, rel=0.1)
    summary = {row[0]: row for row in data.summary.rows}
    assert summary["nlgs_iterations"][3] == run.max_iterations
    assert summary["crown_dy_mm"][1] == pytest.approx(1e3 * run.crown_dy_m.min())
    assert len(data.samples_table().rows) == run.n_samples
    assert len(data.steps_table().rows) == run.n_steps


def test_sequence_frames_and_polygons(run_file, tmp_path):
    run = read_run(run_file)
    data = plot_sequence(run, tmp_path / "seq.png", n_frames=5)
    assert_png(data.png_path)
    times = default_frame_times(run, 5)
    assert times[-1] == pytest.approx(min(run.time_s[-1], 1.15 * run.collapse_time_s))
    assert [f.sample for f in data.frames] == [int(np.argmin(abs(run.time_s - t))) for t in times]
    for frame in data.frames:
        assert len(frame.polygons_m) == run.n_bodies
        for b in range(run.n_bodies):
            assert np.allclose(frame.polygons_m[b], world_vertices(run, frame.sample, b), atol=1e-12)
    # the first frame is the reference arch: every voussoir touches its joint points
    intr = run.arch.joint_intrados_xy_m
    assert np.allclose(data.frames[0].polygons_m[0][:2], intr[:2])
    assert data.frames[0].open_joints == []
    assert data.table.column("sample") == [f.sample for f in data.frames]


def test_sequence_frames_show_distinct_states(run_file, tmp_path):
    """No two frames of the default strip show the same still arch: the first is the
    start, the others run from the first opening of a joint, each a state other than the
    one before (another set of open joints, or openings changed by more than the
    tolerance)."""
    run = read_run(run_file)
    tol = default_open_tol_m(run)
    data = plot_sequence(run, tmp_path / "seq.png", n_frames=6)
    assert data.frames[0].sample == 0 and data.frames[0].open_joints == []
    first_open = next(k for k in range(run.n_samples) if joint_openings(run, k).max() > tol)
    assert data.frames[1].sample == first_open and data.frames[1].open_joints
    for before, after in zip(data.frames, data.frames[1:]):
        change = np.abs(joint_openings(run, after.sample) - joint_openings(run, before.sample)).max()
        assert before.hinge_labels() != after.hinge_labels() or change > tol, (before.time_s, after.time_s)


def test_sequence_amplification(run_file, tmp_path):
    run = read_run(run_file)
    k = int(np.argmin(abs(run.time_s - 0.6 * run.collapse_time_s)))
    t = float(run.time_s[k])
    one = plot_sequence(run, tmp_path / "a1.png", times_s=[t], amplify=1.0).frames[0]
    five = plot_sequence(run, tmp_path / "a5.png", times_s=[t], amplify=5.0).frames[0]
    ref = block_polygons(run, 0)
    shift = np.array([run.table_x_m[k] - run.table_x_m[0], 0.0])
    for b in range(run.n_bodies):
        c_ref = area_centroid(ref[b]) + shift
        c1, c5 = area_centroid(one.polygons_m[b]), area_centroid(five.polygons_m[b])
        assert np.allclose(c5 - c_ref, 5.0 * (c1 - c_ref), atol=1e-9)
        if run.body_role[b] == 2:  # foundations move with the table, drawn true
            assert np.allclose(c5, c1, atol=1e-4)
    # edge direction of a voussoir rotates by 5 theta
    b = 3
    e1 = one.polygons_m[b][1] - one.polygons_m[b][0]
    e5 = five.polygons_m[b][1] - five.polygons_m[b][0]
    e0 = ref[b][1] - ref[b][0]
    ang = lambda v: math.atan2(v[1], v[0])
    assert ang(e5) - ang(e0) == pytest.approx(5.0 * (ang(e1) - ang(e0)), abs=1e-9)


def test_open_hinges_agree_with_hinge_events(run_file):
    """Geometric hinges before collapse are the last /hinges event at that joint, with the
    same side; at collapse a mechanism (at least three hinges) is open."""
    run = read_run(run_file)
    tol = default_open_tol_m(run)
    # The driver's hinge gap: &output hinge_gap_m, or 1 % of the thickness when it is 0
    # (automatic, docs/results_format.md).
    gap = run.config["output"]["hinge_gap_m"] or 0.01 * run.config["arch"]["thickness_m"]
    assert tol == pytest.approx(gap)
    names = run.hinge_side_names
    checked = 0
    for k in np.nonzero(run.time_s <= run.collapse_time_s)[0]:
        t = run.time_s[k]
        last = {}
        for te, j, side in zip(run.hinge_time_s, run.hinge_joint, run.hinge_side):
            if te <= t + 1e-9:
                last[int(j)] = names[int(side)]
        for s in joint_states(run, int(k)):
            if s.state == "separated" or s.opening_m < 1.5 * tol:
                continue
            assert last.get(s.joint) == s.state, (t, s.joint, s.state, last)
            checked += 1
    assert checked > 0
    k = int(np.argmin(abs(run.time_s - run.collapse_time_s)))
    hinges = [s for s in joint_states(run, k) if s.state != "separated"]
    assert len(hinges) >= 3
    # openings are measured, not invented: nothing is open in the reference configuration
    assert np.allclose(joint_openings(run, 0), 0.0, atol=1e-12)


def test_sequence_gif(run_file, tmp_path):
    run = read_run(run_file)
    gif, samples = write_sequence_gif(run, tmp_path / "seq.gif", max_frames=20)
    assert len(samples) == 20 and samples[0] == 0
    with Image.open(gif) as im:
        assert im.format == "GIF" and im.n_frames == 20


def test_xdmf_export(run_copy):
    digest = hashlib.sha256(run_copy.read_bytes()).hexdigest()
    run = read_run(run_copy)
    data = write_xdmf(run)
    assert data.xmf_path == str(run_copy.with_suffix(".xmf"))
    assert data.h5_path == str(run_copy.parent / (run_copy.stem + ".vtk.h5"))
    assert hashlib.sha256(run_copy.read_bytes()).hexdigest() == digest  # the run file is untouched
    items = check_xdmf(data.xmf_path)
    with_contacts = int(np.count_nonzero(run.contact_count))
    assert len(items) == run.n_samples * 6 + with_contacts * 7
    assert data.n_contact_points == int(run.contact_count.sum())

    root = ET.parse(data.xmf_path).getroot()
    assert root.get("Version") == "3.0"
    series = root.find("Domain/Grid")
    assert series.get("CollectionType") == "Temporal"
    grids = series.findall("Grid")
    assert len(grids) == run.n_samples
    assert [float(g.find("Time").get("Value")) for g in grids] == pytest.approx(list(run.time_s))
    k = run.n_samples // 2
    assert grids[k].get("CollectionType") == "Spatial"
    assert [g.get("Name") for g in grids[k].findall("Grid")] == ["blocks", "contacts"]
    geom = grids[k].find("Grid[@Name='blocks']/Geometry/DataItem").text.strip().split(":", 1)[1]
    with h5py.File(data.h5_path, "r") as h5:
        xyz = h5[geom][()]
        conn = h5["topology/mixed"][()]
    nv = int(run.n_vertices.sum())
    assert xyz.shape == (nv, 3) and np.all(xyz[:, 2] == 0.0)
    expected = np.vstack([world_vertices(run, k, b) for b in range(run.n_bodies)])
    assert np.allclose(xyz[:, :2], expected, atol=1e-12)
    assert conn[:6].tolist() == [3, 4, 0, 1, 2, 3]
    assert grids[k].find("Grid[@Name='blocks']/Topology").get("NumberOfElements") == str(run.n_bodies)


def test_check_xdmf_detects_wrong_dimensions(run_copy):
    data = write_xdmf(read_run(run_copy))
    text = open(data.xmf_path).read().replace(f'Dimensions="{data.n_vertices_total} 3"',
                                              f'Dimensions="{data.n_vertices_total + 1} 3"', 1)
    bad = run_copy.parent / "bad.xmf"
    bad.write_text(text)
    with pytest.raises(ValueError, match="XML says"):
        check_xdmf(bad)


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

BLOCKS = """\
# a slender block (b/h = 0.2) on a table-driven base
block driven
-1.0 -0.2
 1.0 -0.2
 1.0  0.0
-1.0  0.0
block free
-0.1 0.0
 0.1 0.0
 0.1 1.0
-0.1 1.0
"""


def test_polygon_assembly_run(voussoir_run_exe, tmp_path):
    """A polygon-file assembly has no /arch: sequence draws it without hinges, xdmf exports it."""
    (tmp_path / "blocks.txt").write_text(BLOCKS)
    h5 = tmp_path / "block.h5"
    (tmp_path / "block.nml").write_text(BLOCK_NML.format(blocks=tmp_path / "blocks.txt", file=h5))
    run_executable([voussoir_run_exe, tmp_path / "block.nml"], tmp_path)
    run = read_run(h5)
    assert run.arch is None and run.n_bodies == 2
    assert sorted(run.body_role.tolist()) == [1, 2]
    data = plot_sequence(run, tmp_path / "seq.png", n_frames=3)
    assert all(f.open_joints == [] for f in data.frames)
    free = int(np.nonzero(run.body_role == 1)[0][0])
    assert np.allclose(data.frames[0].polygons_m[free], [[-0.1, 0.0], [0.1, 0.0], [0.1, 1.0], [-0.1, 1.0]],
                       atol=1e-9)
    assert check_xdmf(write_xdmf(run).xmf_path)


def test_run_that_stands(voussoir_run_exe, tmp_path):
    """0.5 mm at 2.5 Hz: the arch stands, no hinge event, frames spread to the end."""
    h5 = tmp_path / "stands.h5"
    nml = tmp_path / "stands.nml"
    nml.write_text(RUN_NML.format(file=h5).replace("amplitude_m = 0.05", "amplitude_m = 0.0005"))
    run_executable([voussoir_run_exe, nml], tmp_path)
    run = read_run(h5)
    assert not run.collapsed and math.isnan(run.collapse_time_s)
    assert run.hinge_time_s.shape == (0,)
    history = plot_history(run, tmp_path / "h.png")
    assert math.isnan(history.collapse_time_s)
    data = plot_sequence(run, tmp_path / "s.png", n_frames=4)
    assert data.frames[-1].time_s == pytest.approx(run.time_s[-1])
    assert all(f.open_joints == [] for f in data.frames)


def test_sequence_true_scale_colours_and_text(run_file, tmp_path, drawn_figures):
    """The main job's six frames: true scale said in the title; a hinge on the intrados,
    one on the extrados and a separated joint have one colour each, the legend's, and
    red (the collapse's) marks none of them; no text box over another or cut by the
    edge. One frame exaggerated 5 times: the title says so, and its text fits too."""
    from figure_text import text_clashes

    run = read_run(run_file)
    data = plot_sequence(run, tmp_path / "seq.png", n_frames=6)
    plot_sequence(run, tmp_path / "x5.png", n_frames=1, amplify=5.0)
    fig, x5_fig = drawn_figures
    assert "true scale" in fig._suptitle.get_text() and "exaggerated" not in fig._suptitle.get_text()
    assert all("x5" not in ax.get_title() for ax in fig.axes)
    assert "exaggerated x5" in x5_fig._suptitle.get_text()
    legend = {t.get_text().split(":")[0]: h.get_color() for t, h in
              zip(fig.legends[0].get_texts(), fig.legends[0].legend_handles)}
    colours = {"intrados": legend["hinge (i)"], "extrados": legend["hinge (e)"],
               "separated": legend["separated joint (s)"]}
    assert len(set(colours.values())) == 3 and "tab:red" not in colours.values()
    seen = 0
    for ax, frame in zip(fig.axes, data.frames):
        marks = [line for line in ax.get_lines() if line.get_marker() == "o" and len(line.get_xdata())]
        assert len(marks) == len(frame.open_joints)
        for line, state in zip(marks, frame.open_joints):
            assert line.get_color() == colours[state.state]
            seen += 1
    assert seen > 0
    assert text_clashes(fig) == []
    assert text_clashes(x5_fig) == []
