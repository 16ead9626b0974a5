"""`voussoir-post dtcheck` on two IDAs made by the built `voussoir-sweep` on 2 MPI ranks:
the seed's 156-degree arch, one Latin hypercube sample, two one-off sine pulses (CSV
records written here, 2 and 5 Hz: different collapse PGAs), at dt_s = 1e-3 and 5e-4 s.

No bound on the ratio of the medians follows from the physics alone (how far a
threshold moves with the step is what the check measures), so this checks the output's
form, its pairing against the two CSVs read here, and one consequence that does follow:
when no bracket moved, both fits take the same brackets, so the ratio is exactly 1 and
the beta change exactly 0. The statistics: test_dt_check.py.
"""

from __future__ import annotations

import csv
import json
import math
import os
import subprocess

import numpy as np

from voussoir_post.cli.post import main

ARCH = "&arch embrace_deg = 156, n_voussoirs = 13 /\n&motion rest_s = 0.5 /\n"
KEYS = {"median_pga_g_a", "median_pga_g_b", "median_ratio", "median_ratio_band", "beta_a", "beta_b", "beta_change",
        "beta_change_band", "n_rows", "rows_moved", "dt_s_a", "dt_s_b", "band_cluster"}


def mpi_env() -> dict:
    env = dict(os.environ)
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    return env


def sine_pulse(path, frequency_hz: float, cycles: int = 1) -> None:
    """A record of `cycles` sine cycles of 1 m/s2 at `frequency_hz`, then zero to 1 s."""
    t = np.arange(0.0, 1.0 + 1e-9, 0.005)
    a = np.where(t <= cycles / frequency_hz, np.sin(2.0 * math.pi * frequency_hz * t), 0.0)
    path.write_text("t_s,accel_m_s2\n" + "\n".join(f"{x:.6f},{y:.9e}" for x, y in zip(t, a)) + "\n")


def run_ida(exe, folder, dt_s: float) -> list[dict]:
    name = f"ida_dt{dt_s:g}"
    (folder / f"{name}.nml").write_text(
        ARCH + f"&solver dt_s = {dt_s!r} /\n"
        "&sweep mode = 'ida', record_files = 'pulse_2hz.csv', 'pulse_5hz.csv', scale_tol = 0.05, scale_max = 20,\n"
        "  n_samples = 1, sample_seed = 3, friction_range = 0.5, 0.6, progress_every_s = 0 /\n"
        f"&output file = '{name}.h5' /\n")
    proc = subprocess.run(["mpirun", "--oversubscribe", "-np", "2", str(exe), f"{name}.nml"], cwd=folder,
                          capture_output=True, text=True, env=mpi_env(), timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    with open(folder / f"{name}.csv", newline="") as f:
        return list(csv.DictReader(f))


def test_dtcheck_of_an_ida_at_half_its_step(voussoir_sweep_exe, tmp_path, capsys):
    sine_pulse(tmp_path / "pulse_2hz.csv", 2.0)
    sine_pulse(tmp_path / "pulse_5hz.csv", 5.0, cycles=2)
    rows_a = run_ida(voussoir_sweep_exe, tmp_path, 1e-3)
    rows_b = run_ida(voussoir_sweep_exe, tmp_path, 5e-4)
    assert main(["dtcheck", str(tmp_path / "ida_dt0.001.h5"), str(tmp_path / "ida_dt0.0005.h5"), "--json",
                 "--bootstrap", "200"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert KEYS <= set(out)
    assert (out["dt_s_a"], out["dt_s_b"]) == (1e-3, 5e-4)
    assert out["n_rows"] == 2 and out["band_cluster"] == "record"
    by_row = {(r["record"], r["param_set"]): r for r in rows_a}
    moved = 0
    for r in rows_b:
        a = by_row[(r["record"], r["param_set"])]
        moved += any(float(a[c]) != float(r[c]) for c in ("scale_stood", "scale_threshold", "censored"))
    assert out["rows_moved"] == moved
    for name in ("median_pga_g_a", "median_pga_g_b", "beta_a", "beta_b"):
        assert math.isfinite(out[name]) and out[name] > 0.0, name
    low, high = out["median_ratio_band"]
    assert 0.0 < low <= out["median_ratio"] <= high
    low, high = out["beta_change_band"]
    assert low <= out["beta_change"] <= high
    if moved == 0:
        assert out["median_ratio"] == 1.0 and out["beta_change"] == 0.0
    assert main(["dtcheck", str(tmp_path / "ida_dt0.001.h5"), str(tmp_path / "ida_dt0.0005.h5"),
                 "--bootstrap", "50"]) == 0
    text = capsys.readouterr().out
    assert "median PGA [g]" in text and "dt_s = 0.0005 s" in text and f"brackets moved: {moved} of 2 rows" in text
