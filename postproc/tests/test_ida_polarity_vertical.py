"""`&sweep mode = 'ida'` with `record_polarity = 'both'` and `&motion vertical_ratio`, on 2
MPI ranks, checked by voussoir-run.

The seed's 156-degree arch under the first 6 s of El Centro 180, its vertical component
half the horizontal one (vertical_ratio = 0.5, scaled with the record): the sweep plays
the record and, as a row of its own, the record reversed. Each row's scale_stood must
stand and scale_threshold collapse when run alone by voussoir-run with the same
vertical_ratio and the row's polarity (an independent path: its own input file, its own
reading of the record). The arch is symmetric about its crown, so the reversed record is
the mirrored motion and must bring it down at the same scale, to a bracket's width.
"""

from __future__ import annotations

import csv
import os
import subprocess

import pytest

from conftest import run_executable
from voussoir_post.earthquake.ida import read_ida
from voussoir_post.earthquake.records import record_path
from voussoir_post.readers.results import read_run

SCALE_TOL, SCALE_MAX = 0.05, 3.0
RATIO = 0.5
ARCH = "&arch embrace_deg = 156, n_voussoirs = 13 /\n"
MOTION = f"&motion lead_s = 0.5, duration_s = 6.0, vertical_ratio = {RATIO} /\n"


@pytest.fixture(scope="module")
def ida(voussoir_sweep_exe, tmp_path_factory):
    folder = tmp_path_factory.mktemp("ida_polarity")
    record = record_path("ELC180")
    (folder / "ida.nml").write_text(
        ARCH + MOTION + f"&sweep mode = 'ida', record_files = '{record}', record_polarity = 'both', "
        f"scale_tol = {SCALE_TOL}, scale_max = {SCALE_MAX} /\n&output file = 'ida.h5' /\n")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    proc = subprocess.run(["mpirun", "--oversubscribe", "-np", "2", str(voussoir_sweep_exe), "ida.nml"],
                          cwd=folder, capture_output=True, text=True, env=env, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    with open(folder / "ida.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return folder, rows, record


def test_the_reversed_record_is_a_row_of_its_own(ida):
    folder, rows, record = ida
    assert [r["record"] for r in rows] == [str(record), f"{record} (reversed)"]
    assert all(r["censored"] == "0" for r in rows)
    # The HDF5 file names the rows alike, and the record's intensity is that of |a|.
    data = read_ida(folder / "ida.h5")
    assert list(data.record) == [str(record), f"{record} (reversed)"]
    assert rows[0]["pga_m_s2"] == rows[1]["pga_m_s2"]


def run_alone(exe, folder, record, polarity, scale, name):
    nml = folder / f"{name}.nml"
    nml.write_text(ARCH + MOTION.replace(" /", f", waveform = 'accelerogram', record_file = '{record}', "
                                                f"record_scale = {scale!r}, record_polarity = {polarity} /") +
                   f"&output file = '{name}.h5', every = 100 /\n")
    run_executable([exe, nml], folder)
    return read_run(folder / f"{name}.h5")


def test_each_row_brackets_its_collapse_with_the_vertical_component(ida, voussoir_run_exe):
    folder, rows, record = ida
    for k, (row, polarity) in enumerate(zip(rows, (1, -1))):
        stood, threshold = float(row["scale_stood"]), float(row["scale_threshold"])
        assert 0.0 < threshold - stood <= SCALE_TOL * threshold * (1 + 1e-12)
        low = run_alone(voussoir_run_exe, folder, record, polarity, stood, f"row{k}_stood")
        high = run_alone(voussoir_run_exe, folder, record, polarity, threshold, f"row{k}_threshold")
        assert not low.collapsed, f"row {k}: scale_stood = {stood} collapsed when run alone"
        assert high.collapsed, f"row {k}: scale_threshold = {threshold} stood when run alone"


def test_the_vertical_component_is_played(ida, voussoir_run_exe):
    # Without the vertical component the row's own bracket is not the same runs: at least
    # one of its two scales ends otherwise (else vertical_ratio would not reach the runs).
    folder, rows, record = ida
    row = rows[0]
    outcomes = []
    for scale, name in ((float(row["scale_stood"]), "plain_stood"), (float(row["scale_threshold"]), "plain_thr")):
        nml = folder / f"{name}.nml"
        nml.write_text(ARCH + f"&motion lead_s = 0.5, duration_s = 6.0, waveform = 'accelerogram', "
                       f"record_file = '{record}', record_scale = {scale!r} /\n"
                       f"&output file = '{name}.h5', every = 100 /\n")
        run_executable([voussoir_run_exe, nml], folder)
        outcomes.append(read_run(folder / f"{name}.h5"))
    with_vertical = [run_alone(voussoir_run_exe, folder, record, 1, float(row[c]), f"v_{c}")
                     for c in ("scale_stood", "scale_threshold")]
    assert any(abs(a.peak_crown_disp_m - b.peak_crown_disp_m) > 1e-6
               for a, b in zip(outcomes, with_vertical))


def test_the_reversed_record_collapses_the_symmetric_arch_at_the_same_scale(ida):
    _, rows, _ = ida
    forward, reversed_ = (float(r["scale_threshold"]) for r in rows)
    assert abs(forward - reversed_) <= SCALE_TOL * max(forward, reversed_) * (1 + 1e-12)
