"""`voussoir-sweep` in `&sweep mode = 'ida'` on 2 MPI ranks, checked by voussoir-run.

The seed's 156-degree arch under three real records (the first 5.5 s of El Centro 180
and Corralitos 000, and the weak Sylmar 360 aftershock record, which cannot bring it
down by scale_max: a censored row), two Latin hypercube samples of friction. Every
row's scale_stood must stand and scale_threshold collapse when run on their own by
voussoir-run (an independent path through the program: its own input file, its own
reading of the record), with the record's PGA and PGV of that run times the scale in
the row; the bracket is as narrow as scale_tol asks.
"""

from __future__ import annotations

import csv
import json
import os
import subprocess

import numpy as np
import pytest

from conftest import run_executable
from voussoir_post.cli.post import main
from voussoir_post.earthquake.ida import read_ida
from voussoir_post.earthquake.records import record_path
from voussoir_post.readers.results import read_run

SCALE_TOL, SCALE_MAX = 0.05, 3.0
ARCH = "&arch embrace_deg = 156, n_voussoirs = 13 /\n"
MOTION = "&motion lead_s = 0.5, duration_s = 6.0 /\n"


def mpi_env() -> dict:
    env = dict(os.environ)
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    return env


@pytest.fixture(scope="module")
def ida(voussoir_sweep_exe, tmp_path_factory):
    folder = tmp_path_factory.mktemp("ida")
    records = [record_path(k) for k in ("ELC180", "CLS000", "SYL360")]
    files = ", ".join(f"'{p}'" for p in records)
    (folder / "ida.nml").write_text(
        ARCH + MOTION + f"&sweep mode = 'ida', record_files = {files}, scale_tol = {SCALE_TOL}, "
        f"scale_max = {SCALE_MAX}, n_samples = 2, sample_seed = 5, friction_range = 0.5, 0.6 /\n"
        "&output file = 'ida.h5' /\n")
    proc = subprocess.run(["mpirun", "--oversubscribe", "-np", "2", str(voussoir_sweep_exe), "ida.nml"],
                          cwd=folder, capture_output=True, text=True, env=mpi_env(), timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    with open(folder / "ida.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return folder, rows, records


def test_one_row_per_record_and_sample_with_a_censored_weak_record(ida):
    folder, rows, records = ida
    assert len(rows) == 6
    assert set(rows[0]) >= {"record", "param_set", "friction", "scale_stood", "scale_threshold",
                            "pga_threshold_m_s2", "pgv_threshold_m_s", "censored"}
    assert [r["record"] for r in rows] == [str(p) for p in records] * 2
    frictions = sorted({float(r["friction"]) for r in rows})
    assert len(frictions) == 2 and 0.5 <= frictions[0] < 0.55 <= frictions[1] < 0.6  # one per stratum
    weak = [r for r in rows if r["record"].endswith("SYL360-hor2.AT2")]
    assert all(r["censored"] == "1" and float(r["scale_threshold"]) == SCALE_MAX for r in weak)
    assert all(r["censored"] == "0" for r in rows if r not in weak)


def run_alone(exe, folder, row, scale, name):
    """The row's record on the row's model at `scale`, by voussoir-run."""
    nml = folder / f"{name}.nml"
    nml.write_text(ARCH.replace(" /", f", friction = {row['friction']} /") +
                   MOTION.replace(" /", f", waveform = 'accelerogram', record_file = '{row['record']}', "
                                        f"record_scale = {scale!r} /") +
                   f"&output file = '{name}.h5', every = 100 /\n")
    run_executable([exe, nml], folder)
    return read_run(folder / f"{name}.h5")


def test_scale_stood_stands_and_scale_threshold_collapses(ida, voussoir_run_exe):
    folder, rows, _ = ida
    checked = 0
    for k, row in enumerate(rows):
        if row["censored"] == "1":
            continue
        stood, threshold = float(row["scale_stood"]), float(row["scale_threshold"])
        assert 0.0 < threshold - stood <= SCALE_TOL * threshold * (1 + 1e-12)
        low = run_alone(voussoir_run_exe, folder, row, stood, f"row{k}_stood")
        high = run_alone(voussoir_run_exe, folder, row, threshold, f"row{k}_threshold")
        assert not low.collapsed, f"row {k}: scale_stood = {stood} collapsed when run alone"
        assert high.collapsed, f"row {k}: scale_threshold = {threshold} stood when run alone"
        assert float(row["pga_threshold_m_s2"]) == pytest.approx(high.record.pga_m_s2, rel=1e-12)
        assert float(row["pgv_threshold_m_s"]) == pytest.approx(high.record.pgv_m_s, rel=1e-12)
        checked += 1
    assert checked == 4


def test_the_fragility_of_the_ida(ida, capsys):
    folder, rows, _ = ida
    data = read_ida(folder / "ida.h5")
    assert data.n_rows == 6 and int(data.censored.sum()) == 2
    np.testing.assert_allclose(np.sort(data.pga_m_s2),
                               np.sort([float(r["pga_threshold_m_s2"]) for r in rows]), rtol=1e-15)
    assert main(["fragility", str(folder / "ida.h5"), "--json", "--bootstrap", "50"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["n_censored"] == 2 and out["n_rows"] == 6
    # The arch cannot fall below its static capacity (lambda g = 0.376 g, limit analysis).
    assert out["median_pga_g"] > 0.376


def test_the_same_ida_on_1_and_3_ranks(voussoir_sweep_exe, tmp_path):
    """The searches are deterministic: the rows do not depend on how many ranks ran them."""
    files = ", ".join(f"'{record_path(k)}'" for k in ("ELC270", "PUL254"))
    text = (ARCH + "&motion lead_s = 0.5, duration_s = 4.0 /\n"
            f"&sweep mode = 'ida', record_files = {files}, scale_tol = 0.1, scale_max = {SCALE_MAX}, "
            "n_samples = 2, friction_range = 0.5, 0.6, size_imperfection_range = 0.0, 0.04 /\n"
            "&output file = 'ida.h5' /\n")
    tables = {}
    for n in (1, 3):
        folder = tmp_path / f"ranks{n}"
        folder.mkdir()
        (folder / "ida.nml").write_text(text)
        proc = subprocess.run(["mpirun", "--oversubscribe", "-np", str(n), str(voussoir_sweep_exe), "ida.nml"],
                              cwd=folder, capture_output=True, text=True, env=mpi_env(), timeout=600)
        assert proc.returncode == 0, proc.stdout + proc.stderr
        tables[n] = (folder / "ida.csv").read_text()
    assert tables[1] == tables[3]
    assert tables[1].count("\n") == 5  # header + 2 records x 2 samples
