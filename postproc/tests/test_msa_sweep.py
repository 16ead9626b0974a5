"""`voussoir-sweep` in `&sweep mode = 'msa'` on 2 MPI ranks, checked by the static
capacity, by voussoir-run and by an independent fit.

The seed's 156-degree arch (static capacity lambda g from voussoir-limit, limit
analysis: an independent path through the program) under short sine pulses written
here (3 cycles, PGA 1 m/s2). Below lambda g no mechanism can open, so no run at a level
of half the capacity may collapse; at ten times the capacity a 2 or 3 Hz pulse moves the
table back and forth by more than the ring's thickness (a / (2 pi f)^2 = 0.10 m at
3 Hz against 0.071 m), so every run there must collapse. A second sweep, over four
pulses at 2 to 8 Hz whose stripes overlap, is fitted by `voussoir-post fragility` and
checked against the binomial likelihood maximised by a plain grid search here; its
limit states short of collapse (hinge onset, residual drift) are checked against the
rows and, for one run, against voussoir-run's own crown record.
"""

from __future__ import annotations

import csv
import json
import math
import os
import subprocess

import h5py
import numpy as np
import pytest
from scipy.stats import norm

from voussoir_post.cli.post import main
from voussoir_post.earthquake.msa import read_msa
from voussoir_post.readers.results import read_run

G_M_S2 = 9.81  # the kernel's g, in which the levels are given
ARCH = "&arch embrace_deg = 156, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071 /\n"
BASE = ARCH + "&motion lead_s = 0.5, rest_s = 0.0 /\n&solver dt_s = 2.0e-3 /\n"


def mpi_env() -> dict:
    env = dict(os.environ)
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    return env


def write_pulse(path, freq_hz: float, dt_s: float = 0.005) -> float:
    """Three cycles of a sine at `freq_hz`, peak 1 m/s2, then 0.5 s at rest; returns the
    PGA of the samples as written [m/s2]."""
    n = int(round(3.0 / freq_hz / dt_s))
    accel = [f"{math.sin(2 * math.pi * freq_hz * dt_s * k) if k <= n else 0.0:.6f}" for k in range(n + 101)]
    with open(path, "w") as f:
        f.write("t_s,accel_m_s2\n" + "".join(f"{dt_s * k:.3f},{a}\n" for k, a in enumerate(accel)))
    return max(abs(float(a)) for a in accel)


def static_capacity_m_s2(voussoir_limit_exe, folder) -> float:
    (folder / "limit.nml").write_text(ARCH)
    proc = subprocess.run([str(voussoir_limit_exe), "limit.nml", "--json"], cwd=folder, capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    out = json.loads(proc.stdout)
    return min(out["lambda_pos"], out["lambda_neg"]) * out["g_m_s2"]


def run_sweep(exe, folder, name: str, sweep: str) -> str:
    (folder / f"{name}.nml").write_text(BASE + f"&output file = '{name}.h5' /\n" + sweep)
    proc = subprocess.run(["mpirun", "--oversubscribe", "-np", "2", str(exe), f"{name}.nml"], cwd=folder,
                          capture_output=True, text=True, env=mpi_env(), timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return proc.stdout


@pytest.fixture(scope="module")
def small(voussoir_sweep_exe, voussoir_limit_exe, tmp_path_factory):
    """2 records x 3 levels: half, twice and ten times the static capacity."""
    folder = tmp_path_factory.mktemp("msa")
    pga = {name: write_pulse(folder / name, f) for name, f in (("pulse_2hz.csv", 2.0), ("pulse_3hz.csv", 3.0))}
    capacity_g = static_capacity_m_s2(voussoir_limit_exe, folder) / G_M_S2
    levels_g = [0.5 * capacity_g, 2.0 * capacity_g, 10.0 * capacity_g]
    out = run_sweep(voussoir_sweep_exe, folder, "msa",
                    "&sweep mode = 'msa', record_files = 'pulse_2hz.csv', 'pulse_3hz.csv',\n"
                    f"  msa_levels_g = {', '.join(repr(x) for x in levels_g)} /\n")
    with open(folder / "msa.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return folder, rows, pga, levels_g, out


def test_one_row_per_record_and_level_with_its_scale(small):
    folder, rows, pga, levels_g, out = small
    # the runs that scale their record beyond 4 or below 0.25, warned of before any run
    beyond = sum(not 0.25 <= x * G_M_S2 / a <= 4.0 for x in levels_g for a in pga.values())
    assert (f"msa sweep of 6 jobs (1 model samples x 2 records x 3 levels; warning: {beyond} runs scale their "
            "record beyond 4 or below 0.25)") in out
    assert "estimate: 6 jobs, 6 runs" in out  # the plan's run count, up front
    assert len(rows) == 6
    pairs = sorted((row["record"], float(row["level_g"])) for row in rows)
    assert pairs == sorted((r, x) for r in pga for x in levels_g)
    for row in rows:
        assert float(row["pga_m_s2"]) == pytest.approx(pga[row["record"]], rel=1e-12)
        # the record's PGA scaled to the level: scale = level x g / PGA
        assert float(row["scale"]) == pytest.approx(float(row["level_g"]) * G_M_S2 / pga[row["record"]], rel=1e-12)
        assert row["failed"] == "0"
    with h5py.File(folder / "msa.h5", "r") as h5:
        assert h5.attrs["mode"] in (b"msa", "msa")
        np.testing.assert_array_equal(h5["sweep/msa_levels_g"][()], levels_g)
        assert h5["results/level_g"].shape == (6,)


def test_below_the_static_capacity_stands_far_above_collapses(small):
    _, rows, _, levels_g, out = small
    below = [row for row in rows if float(row["level_g"]) == levels_g[0]]
    above = [row for row in rows if float(row["level_g"]) == levels_g[2]]
    assert len(below) == 2 and all(row["collapsed"] == "0" for row in below), below
    assert len(above) == 2 and all(row["collapsed"] == "1" for row in above), above
    assert "stripes (collapsed / runs): " in out
    # below the capacity the ring does not move: no joint opens, the crown stays put
    for row in below:
        assert float(row["max_joint_opening_mm"]) < 0.05 and abs(float(row["residual_drift_mm"])) < 0.05, row
    # a collapse (a voussoir dropped or turned by 0.5 rad) opens joints by far more than 1 mm
    for row in above:
        assert float(row["max_joint_opening_mm"]) > 1.0, row
    # both records at ten times the capacity are scaled beyond 4: warned of
    assert "warning: " in out and "runs scaled their record beyond 4 or below 0.25" in out


def test_a_rerun_redoes_nothing(small, voussoir_sweep_exe):
    folder = small[0]
    proc = subprocess.run(["mpirun", "--oversubscribe", "-np", "1", str(voussoir_sweep_exe), "msa.nml"], cwd=folder,
                          capture_output=True, text=True, env=mpi_env(), timeout=600)
    assert proc.returncode == 0 and "6 jobs, 0 runs" in proc.stdout, proc.stdout + proc.stderr


def grid_fit(levels, collapsed) -> tuple[float, float]:
    """(median, beta) maximising the binomial likelihood by a plain grid search (the
    test's own: no optimiser), refined twice around the best point."""
    levels, collapsed = np.asarray(levels, float), np.asarray(collapsed, bool)
    ln_t, ln_b = np.linspace(math.log(0.05), math.log(20.0), 301), np.linspace(math.log(0.02), math.log(10.0), 301)
    for _ in range(3):
        t, b = np.meshgrid(ln_t, ln_b, indexing="ij")
        u = (np.log(levels) - t[..., None]) / np.exp(b)[..., None]
        ll = np.sum(np.where(collapsed, norm.logcdf(u), norm.logsf(u)), axis=-1)
        i, j = np.unravel_index(np.argmax(ll), ll.shape)
        dt, db = ln_t[1] - ln_t[0], ln_b[1] - ln_b[0]
        ln_t = np.linspace(ln_t[i] - 2 * dt, ln_t[i] + 2 * dt, 81)
        ln_b = np.linspace(ln_b[j] - 2 * db, ln_b[j] + 2 * db, 81)
    return math.exp(ln_t[40]), math.exp(ln_b[40])


def test_the_fragility_of_overlapping_stripes(stripes, capsys):
    tmp_path, rows, _ = stripes
    levels = [float(row["level_g"]) for row in rows]
    collapsed = [row["collapsed"] == "1" for row in rows]
    stood_above = max(x for x, c in zip(levels, collapsed) if not c)
    assert stood_above > min(x for x, c in zip(levels, collapsed) if c), "the stripes overlap (else no fit)"
    capsys.readouterr()
    assert main(["fragility", str(tmp_path / "stripes.h5"), "--json", "--bootstrap", "60"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["fit"] == "binomial" and out["band_cluster"] == "record" and out["n_clusters"] == 4 and out["n_rows"] == 28
    median, beta = grid_fit(levels, collapsed)
    assert out["median_pga_g"] == pytest.approx(median, rel=2e-3)
    assert out["beta_pga"] == pytest.approx(beta, rel=2e-3)
    low, high = out["median_pga_g_band"]
    assert low <= out["median_pga_g"] <= high
    stripes = {s["level_g"]: (s["n_runs"], s["n_exceeded"]) for s in out["stripes"]}
    for x in set(levels):
        assert stripes[x] == (levels.count(x), sum(c for lx, c in zip(levels, collapsed) if lx == x))
    # the CSV summary gives the same fit
    assert main(["fragility", str(tmp_path / "stripes.csv"), "--json", "--bootstrap", "60"]) == 0
    out_csv = json.loads(capsys.readouterr().out)
    assert out_csv["median_pga_g"] == pytest.approx(out["median_pga_g"], rel=1e-9)
    assert os.path.exists(tmp_path / "stripes_fragility.png")
    assert read_msa(tmp_path / "stripes.h5").n_rows == 28


@pytest.fixture(scope="module")
def stripes(voussoir_sweep_exe, tmp_path_factory):
    """Four pulses at 2 to 8 Hz x seven levels around the capacity: stripes that overlap.
    Every step solved (skip_at_rest = .false.), as voussoir-run solves them, so that a row
    can be compared with voussoir-run's run to the last bit (a run that rides at rest
    before its pulse starts the pulse from the arch as built, not as settled by the
    solver, and a rocking run can then end otherwise: tests/test_rest_window.f90)."""
    folder = tmp_path_factory.mktemp("stripes")
    pga = {name: write_pulse(folder / name, f) for name, f in (("p2.csv", 2.0), ("p4.csv", 4.0), ("p6.csv", 6.0),
                                                                 ("p8.csv", 8.0))}
    run_sweep(voussoir_sweep_exe, folder, "stripes",
              "&sweep mode = 'msa', record_files = 'p2.csv', 'p4.csv', 'p6.csv', 'p8.csv',\n"
              "  msa_levels_g = 0.4, 0.45, 0.5, 0.6, 0.8, 1.0, 1.3, skip_at_rest = .false. /\n")
    with open(folder / "stripes.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return folder, rows, pga


def test_the_scale_warning_is_in_the_legend(stripes, tmp_path, drawn_figures):
    """Pulses of about 1 m/s2 scaled to 0.4-1.3 g: most runs beyond a scale of 4, said in
    the figure's legend (where it is read), not only in its small print."""
    from figure_text import text_clashes

    folder, rows, _ = stripes
    beyond = sum(1 for r in rows if not 0.25 <= float(r["scale"]) <= 4.0)
    assert beyond > 0
    assert main(["fragility", str(folder / "stripes.h5"), "--bootstrap", "20", "--out", str(tmp_path / "f.png")]) == 0
    (fig,) = drawn_figures
    (legend,) = fig.legends
    warned = [t.get_text() for t in legend.get_texts() if t.get_text().startswith("warning: ")]
    assert warned == [f"warning: {beyond} of 28 runs scaled their record beyond 4 or below 0.25 (the record then "
                      f"stands for another earthquake)"]
    assert text_clashes(fig) == []


def test_hinge_onset_fragility_from_the_same_stripes(stripes, capsys):
    folder, rows, _ = stripes
    capsys.readouterr()
    # 1 mm opens in every run just above lambda g (0.376 g) with these pulses: stripes
    # separated between 0.4 and 0.45 g, refused; 5 mm overlaps
    assert main(["fragility", str(folder / "stripes.h5"), "--json", "--limit-state", "hinge-onset"]) == 2
    assert "the stripes are separated: every run stayed short of it at or below 0.4 g" in capsys.readouterr().err
    assert main(["fragility", str(folder / "stripes.h5"), "--json", "--bootstrap", "40", "--limit-state",
                 "hinge-onset", "--opening-mm", "5"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["limit_state"] == "hinge-onset" and out["threshold_mm"] == 5.0 and out["fit"] == "binomial"
    # the test's own count: a run exceeds hinge onset when it collapsed or a joint opened > 5 mm
    for stripe in out["stripes"]:
        mine = [row for row in rows if float(row["level_g"]) == stripe["level_g"]]
        exceeded = sum(row["collapsed"] == "1" or float(row["max_joint_opening_mm"]) > 5.0 for row in mine)
        assert (stripe["n_runs"], stripe["n_exceeded"]) == (len(mine), exceeded)
    assert os.path.exists(folder / "stripes_fragility_hinge_onset.png")
    # hinge onset comes before collapse: its median is lower
    assert main(["fragility", str(folder / "stripes.h5"), "--json", "--bootstrap", "40"]) == 0
    collapse = json.loads(capsys.readouterr().out)
    assert out["median_pga_g"] < collapse["median_pga_g"]
    assert main(["fragility", str(folder / "stripes.h5"), "--limit-state", "residual-drift"]) == 2
    assert "--limit-state residual-drift needs --drift-mm X" in capsys.readouterr().err


def test_residual_drift_is_that_of_voussoir_run(stripes, voussoir_run_exe):
    """A run that rocked and stood (6 Hz at 1.3 g): voussoir-run on its own input ends
    with its crown where the row says."""
    folder, rows, pga = stripes
    (row,) = [r for r in rows if r["record"] == "p6.csv" and float(r["level_g"]) == 1.3]
    assert row["collapsed"] == "0" and abs(float(row["residual_drift_mm"])) > 0.5, row
    scale = 1.3 * G_M_S2 / pga["p6.csv"]
    (folder / "alone.nml").write_text(BASE.replace("&motion lead_s = 0.5, rest_s = 0.0 /", "&motion lead_s = 0.5, rest_s = 0.0, waveform = "
                                                   f"'accelerogram', record_file = 'p6.csv', record_scale = {scale!r} /")
                                      + "&output file = 'alone.h5', every = 1 /\n")
    proc = subprocess.run([str(voussoir_run_exe), "alone.nml"], cwd=folder, capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    run = read_run(folder / "alone.h5")
    assert 1e3 * run.crown_dx_m[-1] == pytest.approx(float(row["residual_drift_mm"]), rel=1e-9, abs=1e-9)
    assert np.max(np.hypot(run.crown_dx_m, run.crown_dy_m)) == pytest.approx(float(row["peak_crown_disp_m"]),
                                                                            rel=1e-9)
