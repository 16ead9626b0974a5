"""`&motion lead_s` and `rest_s` on the real executable (issue 26): the table is still
for `lead_s` before the motion and for `rest_s` after it, for every waveform.

The times are dyadic (the solver step 2^-10 s, the record step 2^-6 s, the lead 2^-4 s)
so that the motion's start and end fall on steps exactly. The expected tables are
written here: the record's samples by hand and their integrals by the trapezoid rule
(exact for the velocity of a linear acceleration, and the displacement of a constant
velocity after the record), the afd command by voussoir_post.analysis.afd.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from conftest import run_executable
from voussoir_post.analysis.afd import afd_command
from voussoir_post.readers.results import read_run

DT_S = 2.0 ** -10       # solver step [s]
RECORD_DT_S = 2.0 ** -6  # record step [s]
LEAD_S = 2.0 ** -4      # 64 solver steps
# A pulse in m/s2 whose velocity does not return to zero: the table ends the record moving.
SAMPLES = np.array([1.0, 2.0, 0.5, -0.5, 0.25, 0.0])
BLOCK = """\
# A squat block (b/h = 1: it neither rocks nor slides under these pulses) on a table slab.
block free
-0.1 0.0
 0.1 0.0
 0.1 0.2
-0.1 0.2
block driven
-1.0 -0.2
 1.0 -0.2
 1.0  0.0
-1.0  0.0
"""


def run_block(exe, folder: Path, motion: str, name: str):
    """voussoir-run of the block under `motion` (the &motion variables), every step kept."""
    (folder / "block.txt").write_text(BLOCK)
    (folder / "record.csv").write_text("t_s,accel_m_s2\n" + "".join(
        f"{k * RECORD_DT_S!r},{float(a)!r}\n" for k, a in enumerate(SAMPLES)))
    (folder / "table.csv").write_text("t_s,table_x_m\n" + "".join(
        f"{k * RECORD_DT_S!r},{float(0.001 * np.sin(k / 4.0))!r}\n" for k in range(40)))
    nml = folder / f"{name}.nml"
    nml.write_text(f"""&arch
  polygon_file = 'block.txt', thickness_m = 0.2, width_m = 0.2, density_kg_m3 = 2000, friction = 0.7
/
&motion
  {motion}
/
&solver
  dt_s = {DT_S!r}
/
&output
  file = '{name}.h5', every = 1, stop_after_collapse_s = -1.0
/
""")
    run_executable([exe, nml], folder)
    return read_run(folder / f"{name}.h5")


SUB = 1024  # trapezoids per record step


def record_tables(t_after_start: np.ndarray):
    """The table's x, v, a at times after the record's first sample: the samples linear
    between them, then no acceleration; velocity and displacement integrated here on a
    grid of 1/SUB of the record step (trapezoids: exact for the velocity)."""
    end = (SAMPLES.size - 1) * RECORD_DT_S
    fine = np.arange(0.0, t_after_start.max() + RECORD_DT_S, RECORD_DT_S / SUB)
    a = np.interp(fine, np.arange(SAMPLES.size) * RECORD_DT_S, SAMPLES, right=0.0)
    a[fine > end] = 0.0
    h = fine[1] - fine[0]
    v = np.concatenate([[0.0], np.cumsum(0.5 * h * (a[1:] + a[:-1]))])
    x = np.concatenate([[0.0], np.cumsum(0.5 * h * (v[1:] + v[:-1]))])
    return np.interp(t_after_start, fine, x), np.interp(t_after_start, fine, v), np.interp(t_after_start, fine, a)


def x_tolerance(t_span_s: float) -> float:
    """The trapezoids' error bound on the displacement: (h^2 / 12) max|v''| per unit time."""
    h = RECORD_DT_S / SUB
    return t_span_s * h * h / 12.0 * np.abs(np.diff(SAMPLES)).max() / RECORD_DT_S


def test_lead_s_starts_the_record_lead_s_later(voussoir_run_exe, tmp_path):
    run = run_block(voussoir_run_exe, tmp_path, f"waveform = 'accelerogram', record_file = 'record.csv', lead_s = {LEAD_S!r}, "
                              "rest_s = 0.0", "lead")
    t = run.time_s
    before = t < LEAD_S
    assert before.sum() == 64  # t = 0 .. 63 steps
    # Still until lead_s: no displacement, velocity or acceleration.
    assert np.all(run.table_x_m[before] == 0.0) and np.all(run.table_v_m_s[before] == 0.0)
    assert np.all(run.table_a_m_s2[before] == 0.0)
    # The record's first sample at lead_s, then the record played from there.
    k = int(np.flatnonzero(t == LEAD_S)[0])
    assert run.table_a_m_s2[k] == SAMPLES[0]
    x, v, a = record_tables(t[~before] - LEAD_S)
    np.testing.assert_allclose(run.table_a_m_s2[~before], a, rtol=0, atol=1e-12)
    np.testing.assert_allclose(run.table_v_m_s[~before], v, rtol=0, atol=1e-12)
    np.testing.assert_allclose(run.table_x_m[~before], x, rtol=0, atol=x_tolerance(t[-1]))
    # The run ends with the record (rest_s = 0): lead + record.
    assert t[-1] == pytest.approx(LEAD_S + (SAMPLES.size - 1) * RECORD_DT_S, rel=1e-12)
    assert run.record.start_s == LEAD_S


def test_rest_s_after_an_accelerogram_extends_the_run_with_the_table_unaccelerated(voussoir_run_exe, tmp_path):
    rest_s = 0.25
    run = run_block(voussoir_run_exe, tmp_path, f"waveform = 'accelerogram', record_file = 'record.csv', rest_s = {rest_s!r}",
                    "rest")
    t = run.time_s
    end = (SAMPLES.size - 1) * RECORD_DT_S
    # No lead (lead_s = 0 by default): the record from t = 0; then rest_s after it.
    assert run.table_a_m_s2[1] == pytest.approx(SAMPLES[0] + (SAMPLES[1] - SAMPLES[0]) * DT_S / RECORD_DT_S,
                                                rel=1e-12)
    assert t[-1] == pytest.approx(end + rest_s, rel=1e-12)
    # After the record the table does not accelerate: it keeps the record's final
    # velocity (the exact integral of a zero acceleration), the velocity an uncorrected
    # record leaves, which rigid blocks do not feel.
    after = t > end
    assert after.sum() == round(rest_s / DT_S)
    v_end = np.sum(0.5 * RECORD_DT_S * (SAMPLES[1:] + SAMPLES[:-1]))  # exact: a is linear
    assert abs(v_end) > 0.01  # the test means something: the table moves after the record
    assert np.all(run.table_a_m_s2[after] == 0.0)
    np.testing.assert_allclose(run.table_v_m_s[after], v_end, rtol=0, atol=1e-12)
    x, _, _ = record_tables(t[after])
    np.testing.assert_allclose(run.table_x_m[after], x, rtol=0, atol=x_tolerance(t[-1]))
    x_end = run.table_x_m[t == end][0]
    np.testing.assert_allclose(run.table_x_m[after], x_end + v_end * (t[after] - end), rtol=0, atol=1e-12)


def test_lead_s_of_an_afd_motion(voussoir_run_exe, tmp_path):
    f_hz, amp_m, rest_s = 4.0, 0.002, 0.125
    run = run_block(voussoir_run_exe, tmp_path, f"waveform = 'afd', frequency_hz = {f_hz!r}, amplitude_m = {amp_m!r}, "
                              f"lead_s = {LEAD_S!r}, rest_s = {rest_s!r}", "afd")
    t = run.time_s
    before = t < LEAD_S
    assert np.all(run.table_x_m[before] == 0.0) and np.all(run.table_a_m_s2[before] == 0.0)
    np.testing.assert_allclose(run.table_x_m[~before], afd_command(t[~before] - LEAD_S, f_hz, amp_m),
                               rtol=0, atol=1e-12)
    assert t[-1] == pytest.approx(LEAD_S + 3 / f_hz + rest_s, rel=1e-12)


def test_lead_s_of_a_ramp(voussoir_run_exe, tmp_path):
    rate = 0.5
    run = run_block(voussoir_run_exe, tmp_path, f"waveform = 'ramp', ramp_rate_m_s3 = {rate!r}, lead_s = {LEAD_S!r}, "
                              "duration_s = 0.5", "ramp")
    t = run.time_s
    np.testing.assert_allclose(run.table_a_m_s2, rate * np.maximum(t - LEAD_S, 0.0), rtol=0, atol=1e-12)
    assert np.all(run.table_a_m_s2[t <= LEAD_S] == 0.0)
    assert t[-1] == pytest.approx(0.5, rel=1e-12)  # a ramp's run lasts duration_s (it has no end)


def test_lead_s_of_a_table_record(voussoir_run_exe, tmp_path):
    run = run_block(voussoir_run_exe, tmp_path, f"waveform = 'record', record_file = 'table.csv', record_cutoff_hz = 0, "
                              f"lead_s = {LEAD_S!r}, rest_s = 0.125", "table")
    t = run.time_s
    before = t <= LEAD_S
    assert np.all(run.table_x_m[before] == 0.0) and np.all(run.table_v_m_s[before] == 0.0)
    # Unfiltered, the table is the record linear between its samples, lead_s later.
    samples = 0.001 * np.sin(np.arange(40) / 4.0)
    np.testing.assert_allclose(run.table_x_m[~before],
                               np.interp(t[~before] - LEAD_S, np.arange(40) * RECORD_DT_S, samples),
                               rtol=0, atol=1e-12)
    assert t[-1] == pytest.approx(LEAD_S + 39 * RECORD_DT_S + 0.125, rel=1e-12)
