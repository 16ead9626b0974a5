"""Readers of the result files, on a file written by the real voussoir-run."""

from __future__ import annotations

import math

import h5py
import numpy as np
import pytest

from voussoir_post.namelist import parse_namelist
from voussoir_post.readers.results import ResultsError, read_limit_json, read_run, read_sweep


def test_run_file_layout(run_file):
    run = read_run(run_file)
    nt, nb = run.n_samples, run.n_bodies
    assert nb == 13 + 2  # 13 voussoirs and two foundations
    assert list(run.body_role) == [1] * 13 + [2, 2]
    assert run.body_position.shape == (nt, nb, 3)
    assert run.vertices_local_m.shape[0] == nb and run.vertices_local_m.shape[2] == 2
    assert np.all(run.n_vertices == 4)
    for arr in (run.table_x_m, run.table_v_m_s, run.table_a_m_s2, run.crown_dx_m, run.crown_dy_m,
                run.contact_count):
        assert arr.shape == (nt,)
    assert run.time_s[0] == 0.0 and np.all(np.diff(run.time_s) > 0)
    assert run.step_time_s.shape == run.step_iterations.shape == run.step_norm.shape == (run.n_steps,)
    assert run.step_iterations.max() == run.max_iterations
    assert run.step_iterations.mean() == pytest.approx(run.mean_iterations)
    assert run.hinge_time_s.shape == run.hinge_joint.shape == run.hinge_side.shape
    assert set(run.hinge_side) <= {0, 1} and run.hinge_side_names == ("intrados", "extrados")
    assert run.hinge_joint.min() >= 0 and run.hinge_joint.max() <= 13
    assert run.code_version.startswith("voussoir ")
    assert run.collapsed and math.isfinite(run.collapse_time_s)
    assert 0.0 < run.collapse_time_s <= run.time_s[-1]


def test_run_config_matches_namelist(run_file):
    run = read_run(run_file)
    arch, motion = run.config["arch"], run.config["motion"]
    assert (arch["embrace_deg"], arch["n_voussoirs"], arch["thickness_m"]) == (156.0, 13, 0.071)
    assert (motion["waveform"], motion["frequency_hz"], motion["amplitude_m"]) == ("afd", 2.5, 0.05)
    nml = parse_namelist(run.config_nml)
    for group, values in run.config.items():
        for name, value in values.items():
            parsed = nml[group][name]
            if isinstance(value, float):
                assert parsed == pytest.approx(value), (group, name)
            elif isinstance(parsed, bool):
                assert int(parsed) == value, (group, name)
            else:
                assert parsed == value, (group, name)


def test_arch_geometry_and_reference_configuration(run_file):
    """The first sample is the reference: voussoir j is the quadrilateral of joints j-1, j."""
    run = read_run(run_file)
    a = run.arch
    assert (a.n_voussoirs, a.thickness_m, a.r_ext_m, a.embrace_deg) == (13, 0.071, 0.508, 156.0)
    assert np.allclose(np.hypot(*a.joint_extrados_xy_m.T), 0.508)
    assert np.allclose(np.hypot(*a.joint_intrados_xy_m.T), 0.508 - 0.071)
    assert np.all(run.body_position[0, :, 2] == 0.0)
    intr, extr = a.joint_intrados_xy_m, a.joint_extrados_xy_m
    for j in range(1, 14):
        verts = run.body_position[0, j - 1, :2] + run.vertices_local_m[j - 1, :4]
        expected = np.array([intr[j - 1], intr[j], extr[j], extr[j - 1]])
        assert np.allclose(verts, expected, atol=1e-12), j


def test_crown_is_keystone_relative_to_table(run_file):
    run = read_run(run_file)
    key = 6  # voussoir 7 of 13
    dx = run.body_position[:, key, 0] - run.body_position[0, key, 0] - (run.table_x_m - run.table_x_m[0])
    dy = run.body_position[:, key, 1] - run.body_position[0, key, 1]
    # the driven bodies integrate the table velocity: a few micrometres from the exact x(t)
    assert np.allclose(dx, run.crown_dx_m, atol=2e-5)
    assert np.allclose(dy, run.crown_dy_m, atol=1e-9)
    assert np.hypot(run.crown_dx_m, run.crown_dy_m).max() == pytest.approx(run.peak_crown_disp_m)


def test_missing_file(tmp_path):
    with pytest.raises(ResultsError) as info:
        read_run(tmp_path / "none.h5")
    assert str(info.value) == f"{tmp_path / 'none.h5'}: no such file"


def test_not_hdf5(tmp_path):
    path = tmp_path / "run.h5"
    path.write_text("&arch /\n")
    with pytest.raises(ResultsError, match=r"run\.h5: not an HDF5 file"):
        read_run(path)


def test_wrong_producer(run_file):
    with pytest.raises(ResultsError) as info:
        read_sweep(run_file)
    assert str(info.value) == (f"{run_file}: written by 'voussoir-run', but this command reads "
                               "'voussoir-sweep' files")


def test_missing_dataset_and_attribute(run_copy):
    with h5py.File(run_copy, "a") as h5:
        del h5["crown/dy_m"]
    with pytest.raises(ResultsError) as info:
        read_run(run_copy)
    assert str(info.value) == f"{run_copy}: missing dataset 'crown/dy_m'"
    with h5py.File(run_copy, "a") as h5:
        h5["crown/dy_m"] = np.zeros(h5["time_s"].shape)
        del h5["result"].attrs["n_steps"]
    with pytest.raises(ResultsError, match="missing attribute 'n_steps' of /result"):
        read_run(run_copy)


def test_wrong_shape(run_copy):
    with h5py.File(run_copy, "a") as h5:
        n = h5["time_s"].shape[0]
        del h5["table/v_m_s"]
        h5["table/v_m_s"] = np.zeros(n + 1)
    with pytest.raises(ResultsError, match=rf"'/table/v_m_s' has shape \({n + 1},\), expected \({n}\)"):
        read_run(run_copy)


def test_limit_json_errors(tmp_path):
    with pytest.raises(ResultsError, match="no such file"):
        read_limit_json(tmp_path / "x.json")
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    with pytest.raises(ResultsError, match="not a JSON file"):
        read_limit_json(bad)
    partial = tmp_path / "partial.json"
    partial.write_text('{"lambda_pos": 0.3}')
    with pytest.raises(ResultsError, match="missing key 'arch'"):
        read_limit_json(partial)


def test_parse_namelist_formats():
    text = ("&ARCH\n EMBRACE_DEG=  156.0 ,\n N_VOUSSOIRS=13,\n NAME='a/b, c',\n F= 3*0.5, FLAG=T,\n /\n"
            "&motion waveform = \"afd\", frequency_hz = 2.5d0 /\n&solver allow = .false. /\n")
    nml = parse_namelist(text)
    assert nml["arch"] == {"embrace_deg": 156.0, "n_voussoirs": 13, "name": "a/b, c",
                           "f": [0.5, 0.5, 0.5], "flag": True}
    assert nml["motion"] == {"waveform": "afd", "frequency_hz": 2.5}
    assert nml["solver"] == {"allow": False}
