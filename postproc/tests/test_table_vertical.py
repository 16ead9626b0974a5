"""The table's vertical component and a record's polarity on the real executable
(`&motion vertical_ratio`, `record_vertical_file`, `record_polarity`).

Expected answers are the closed form of a block's tipping (it tips when
a_h > (b/h)(g + a_v)) and the mirror symmetry of a symmetric arch: the mirror image of a
motion is a motion of the mirrored problem, so the arch under the reversed record moves
as the mirror image of the arch under the record (crown x reversed, crown y the same),
up to the contact solve's tolerance.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from conftest import run_executable
from voussoir_post.readers.results import read_run

G = 9.81  # the kernel's gravity
BLOCK = """\
# A 0.2 m x 1.0 m block on a table slab (coordinates in m): b/h = 0.2.
block free
-0.1 0.0
 0.1 0.0
 0.1 1.0
-0.1 1.0
block driven
-1.0 -0.2
 1.0 -0.2
 1.0  0.0
-1.0  0.0
"""
SLENDERNESS = 0.2  # b/h of BLOCK


def constant_record(path: Path, accel_m_s2: float, ramp_s=0.1, hold_s=1.2, dt_s=0.01) -> Path:
    """A CSV accelerogram: a linear ramp to `accel_m_s2`, then that value held."""
    t = np.arange(round((ramp_s + hold_s) / dt_s) + 1) * dt_s
    a = accel_m_s2 * np.minimum(t / ramp_s, 1.0)
    path.write_text("t_s,accel_m_s2\n" + "".join(f"{ti!r},{ai!r}\n" for ti, ai in zip(t.tolist(), a.tolist())))
    return path


def block_run(exe: Path, folder: Path, name: str, motion_extra: str) -> Path:
    (folder / "block.txt").write_text(BLOCK)
    nml = folder / f"{name}.nml"
    nml.write_text(f"""&arch
  polygon_file = 'block.txt', thickness_m = 0.2, width_m = 0.2, density_kg_m3 = 2000, friction = 0.7
/
&motion
  waveform = 'accelerogram', record_file = 'horizontal.csv', rest_s = 0.0, {motion_extra}
/
&solver
  dt_s = 1.0e-3, tol = 1.0e-8
/
&output
  file = '{name}.h5', every = 10, stop_after_collapse_s = -1.0
/
""")
    run_executable([exe, nml], folder)
    return folder / f"{name}.h5"


def test_a_downward_vertical_component_tips_a_block_that_stands_without_it(voussoir_run_exe, tmp_path):
    # a_h = 0.9 (b/h) g: below the onset (b/h) g without vertical acceleration; with
    # a_v = -a_h (vertical_ratio = -1) the onset is (b/h)(g + a_v) = 0.164 g < 0.18 g.
    a_h = 0.9 * SLENDERNESS * G
    assert a_h < SLENDERNESS * G and a_h > SLENDERNESS * (G - a_h)
    constant_record(tmp_path / "horizontal.csv", a_h)
    constant_record(tmp_path / "vertical.csv", -a_h)
    alone = read_run(block_run(voussoir_run_exe, tmp_path, "alone", "record_scale = 1.0"))
    ratio = read_run(block_run(voussoir_run_exe, tmp_path, "ratio", "vertical_ratio = -1.0"))
    own = read_run(block_run(voussoir_run_exe, tmp_path, "own", "record_vertical_file = 'vertical.csv'"))
    assert np.abs(alone.crown_dx_m).max() < 1e-6
    assert np.abs(ratio.crown_dx_m).max() > 1e-3
    assert alone.table_y_m is None and ratio.table_y_m is not None  # stored only with a vertical motion
    # The ratio and the vertical record of the same samples are one motion.
    np.testing.assert_array_equal(own.crown_dx_m, ratio.crown_dx_m)
    np.testing.assert_array_equal(own.crown_dy_m, ratio.crown_dy_m)


def arch_runs(exe: Path, folder: Path, tol: float):
    record = Path(__file__).resolve().parents[2] / "input" / "records" / "sine_pulse_0.3g.csv"
    runs = []
    for polarity in (1, -1):
        name = f"arch_{polarity}_{tol:g}"
        nml = folder / f"{name}.nml"
        nml.write_text(f"""&arch
  embrace_deg = 156, n_voussoirs = 13
/
&motion
  waveform = 'accelerogram', record_file = '{record}', record_scale = 1.5, lead_s = 0.2,
  duration_s = 1.5, record_polarity = {polarity}
/
&solver
  tol = {tol!r}, max_iter = 100000
/
&output
  file = '{name}.h5', every = 5, stop_after_collapse_s = -1.0
/
""")
        run_executable([exe, nml], folder)
        runs.append(read_run(folder / f"{name}.h5"))
    return runs


def test_the_reversed_record_mirrors_a_symmetric_arch(voussoir_run_exe, tmp_path):
    # The 156-degree arch (symmetric about x = 0) under a 0.45 g sine pulse, which brings
    # it down: a large motion, the same mechanism mirrored.
    errors, lags = {}, {}
    for tol in (1e-4, 1e-5):
        forward, reversed_ = arch_runs(voussoir_run_exe, tmp_path, tol)
        np.testing.assert_array_equal(reversed_.table_x_m, -forward.table_x_m)
        # Both collapse; compared until then (the debris's fall after the collapse is no
        # longer the mechanism).
        assert forward.collapsed and reversed_.collapsed
        lags[tol] = abs(forward.collapse_time_s - reversed_.collapse_time_s)
        until = forward.time_s <= forward.collapse_time_s
        peak = np.abs(forward.crown_dx_m[until]).max()
        assert peak > 0.01  # the crown moves by a seventh of the ring's thickness
        errors[tol] = max(np.abs(reversed_.crown_dx_m + forward.crown_dx_m)[until].max(),
                          np.abs(reversed_.crown_dy_m - forward.crown_dy_m)[until].max()) / peak
    # Mirrored to the solve's tolerance: within 1 % of the motion at tol = 1e-5, and the
    # departure shrinks with the tolerance (the contact solve's order is not mirrored):
    # measured 1.8 % at 1e-4 and 0.38 % at 1e-5 (2026-11-26).
    assert lags[1e-5] <= 1.5e-3, lags  # the same collapse time to a step (dt_s = 1e-3)
    assert errors[1e-5] < 0.01, errors
    assert errors[1e-5] < errors[1e-4] / 3, errors


def dense_integrals(accel: np.ndarray, dt: float, sub: int = 64):
    """The linearly interpolated acceleration on a grid `sub` times finer, and its
    velocity and displacement from rest by cumulative trapezoids (a second-order
    quadrature, not the closed form the program uses)."""
    t = np.arange((accel.size - 1) * sub + 1) * (dt / sub)
    a = np.interp(t, np.arange(accel.size) * dt, accel)
    h = dt / sub
    v = np.concatenate([[0.0], np.cumsum(0.5 * h * (a[1:] + a[:-1]))])
    x = np.concatenate([[0.0], np.cumsum(0.5 * h * (v[1:] + v[:-1]))])
    return t, v, x


def rise(run) -> np.ndarray:
    """The table slab's (body 2 of BLOCK) rise [m] from its place at the first sample (t = 0)."""
    return run.body_position[:, 1, 1] - run.body_position[0, 1, 1]


def test_the_driven_blocks_follow_the_vertical_record(voussoir_run_exe, tmp_path):
    # Horizontal: a constant 0.1 g after a ramp; vertical: one cycle of a 4 Hz sine of
    # 0.2 g, then rest. The table (the driven block) rises by the vertical record's
    # double integral, computed here by quadrature.
    dt, n = 0.01, 131
    constant_record(tmp_path / "horizontal.csv", 0.1 * G)
    t = np.arange(n) * dt
    a_v = np.where(t < 0.25, 0.2 * G * np.sin(2 * np.pi * 4.0 * t), 0.0)
    (tmp_path / "vertical.csv").write_text(
        "t_s,accel_m_s2\n" + "".join(f"{ti!r},{ai!r}\n" for ti, ai in zip(t.tolist(), a_v.tolist())))
    run = read_run(block_run(voussoir_run_exe, tmp_path, "own_v", "record_vertical_file = 'vertical.csv'"))
    assert run.time_s[0] == 0.0
    table_y = rise(run)
    td, _, yd = dense_integrals(a_v, dt)
    inside = run.time_s <= t[-1]
    np.testing.assert_allclose(table_y[inside], np.interp(run.time_s[inside], td, yd),
                               rtol=0, atol=1e-6 * np.abs(yd).max())
    assert np.abs(yd).max() > 1e-3  # the table does move vertically
    # The file's vertical table record: the record played, and the slab on it.
    np.testing.assert_allclose(run.table_ay_m_s2[inside], np.interp(run.time_s[inside], t, a_v), rtol=0,
                               atol=1e-9 * np.abs(a_v).max())
    np.testing.assert_allclose(run.table_y_m, table_y, rtol=0, atol=1e-12)


def test_vertical_ratio_of_an_afd_and_of_a_reversed_record(voussoir_run_exe, tmp_path):
    (tmp_path / "block.txt").write_text(BLOCK)
    afd = tmp_path / "afd.nml"
    afd.write_text("""&arch
  polygon_file = 'block.txt', thickness_m = 0.2, width_m = 0.2, density_kg_m3 = 2000, friction = 0.7
/
&motion
  waveform = 'afd', frequency_hz = 2.0, amplitude_m = 0.01, vertical_ratio = 0.5, rest_s = 0.2
/
&output
  file = 'afd.h5', every = 5
/
""")
    run_executable([voussoir_run_exe, afd], tmp_path)
    run = read_run(tmp_path / "afd.h5")
    # The table moves along the line y = 0.5 x.
    assert run.time_s[0] == 0.0
    np.testing.assert_allclose(rise(run), 0.5 * run.table_x_m, rtol=0, atol=1e-12)
    assert np.abs(run.table_x_m).max() > 0.005
    # A record reversed with a ratio: the horizontal flips, the vertical stays that of the
    # record as recorded (the mirror image leaves it as it is).
    constant_record(tmp_path / "horizontal.csv", 0.1 * G)
    forward = read_run(block_run(voussoir_run_exe, tmp_path, "fwd", "vertical_ratio = -0.5"))
    reverse = read_run(block_run(voussoir_run_exe, tmp_path, "rev", "vertical_ratio = -0.5, record_polarity = -1"))
    np.testing.assert_array_equal(reverse.table_x_m, -forward.table_x_m)
    np.testing.assert_array_equal(rise(reverse), rise(forward))
    np.testing.assert_allclose(rise(forward), -0.5 * forward.table_x_m, rtol=1e-12, atol=1e-15)


def test_an_esm_file_in_cm_s2_drives_the_table_as_its_csv_in_m_s2(voussoir_run_exe, tmp_path):
    # The same acceleration as an ESM/ITACA file in cm/s^2 (the header says so) and as a
    # CSV in m/s2: the table plays the same record.
    dt, n = 0.01, 101
    t = np.arange(n) * dt
    a = 0.15 * G * np.sin(2 * np.pi * 3.0 * t) * np.exp(-t)
    (tmp_path / "horizontal.csv").write_text(
        "t_s,accel_m_s2\n" + "".join(f"{ti!r},{ai!r}\n" for ti, ai in zip(t.tolist(), a.tolist())))
    header = ["EVENT_NAME: TEST", "EVENT_ID: T-1", "NETWORK: IT", "STATION_CODE: AMT", "STREAM: HNE",
              f"SAMPLING_INTERVAL_S: {dt}", f"NDATA: {n}", "DATA_TYPE: ACCELERATION", "UNITS: cm/s^2",
              "USER1:", "USER2:", "USER3:", "USER4:", "USER5:"]
    (tmp_path / "record.ASC").write_text("\n".join(header + [f"{100.0 * ai!r}" for ai in a.tolist()]) + "\n")
    csv_run = read_run(block_run(voussoir_run_exe, tmp_path, "csv", "record_scale = 1.0"))
    (tmp_path / "horizontal.csv").rename(tmp_path / "horizontal_m_s2.csv")
    (tmp_path / "record.ASC").rename(tmp_path / "horizontal.ASC")
    nml = (tmp_path / "csv.nml").read_text().replace("horizontal.csv", "horizontal.ASC").replace("csv.h5", "esm.h5")
    (tmp_path / "esm.nml").write_text(nml)
    run_executable([voussoir_run_exe, tmp_path / "esm.nml"], tmp_path)
    esm_run = read_run(tmp_path / "esm.h5")
    np.testing.assert_allclose(esm_run.table_a_m_s2, csv_run.table_a_m_s2, rtol=1e-12, atol=1e-12)
    assert np.abs(esm_run.table_a_m_s2).max() > 0.5
    assert "TEST" in esm_run.record.description and "AMT" in esm_run.record.description
