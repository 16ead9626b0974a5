"""envelope and compare on files written by the real voussoir-sweep.

Skipped while voussoir-sweep does not exist. The ``&sweep`` group below follows
docs/sweep.md.
"""

from __future__ import annotations

import csv
import math
import os
import shutil

import numpy as np
import pytest

from conftest import run_executable
from voussoir_post.cli import post
from voussoir_post.readers.campaign import read_campaign
from voussoir_post.plots.compare import compare_thresholds, match_specimens, mean_error_lines, plot_compare
from voussoir_post.plots.envelope import plot_envelope
from voussoir_post.readers.results import read_sweep

FREQUENCIES_HZ = (1.25, 2.5)

SWEEP_NML = """\
&arch
  embrace_deg = 156.0, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071,
  width_m = 0.145, density_kg_m3 = 700.0, friction = 0.5
/
&motion
  waveform = 'afd', n_attack = 1, n_full = 1, n_decay = 1, rest_s = 0.5
/
&solver
  dt_s = 2.0e-3, theta = 0.5, tol = 1.0e-4, allow_nonconvergence = .true.
/
&output
  file = '{file}', every = 50
/
&sweep
  mode = '{mode}', frequencies_hz = 1.25, 2.5,
  {amplitudes}
/
"""

#: The mode-specific &sweep variables (docs/sweep.md).
SWEEP_AMPLITUDES = {"threshold": "amp_max_m = 0.10, amp_tol_m = 0.005",
                    "grid": "amplitudes_m = 0.02, 0.04, 0.06, 0.08"}


def sweep_command(exe, nml):
    """Run the sweep on 2 MPI ranks when mpirun exists (as tests/run_input.sh does)."""
    mpirun = shutil.which("mpirun")
    if mpirun:
        return [mpirun, "--oversubscribe", "-np", "2", exe, nml]
    return [exe, nml]


def make_sweep(exe, folder, mode):
    h5 = folder / f"sweep_{mode}.h5"
    nml = folder / f"sweep_{mode}.nml"
    nml.write_text(SWEEP_NML.format(file=h5, mode=mode, amplitudes=SWEEP_AMPLITUDES[mode]))
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    run_executable(sweep_command(exe, nml), folder, timeout_s=1800, env=env)
    return h5


@pytest.fixture(scope="module")
def threshold_sweep(voussoir_sweep_exe, tmp_path_factory):
    return make_sweep(voussoir_sweep_exe, tmp_path_factory.mktemp("sweep_t"), "threshold")


@pytest.fixture(scope="module")
def grid_sweep(voussoir_sweep_exe, tmp_path_factory):
    return make_sweep(voussoir_sweep_exe, tmp_path_factory.mktemp("sweep_g"), "grid")


def test_threshold_sweep_file(threshold_sweep):
    sweep = read_sweep(threshold_sweep)
    assert sweep.mode == "threshold" and sweep.n_sets == 1 and sweep.parameter_names == []
    res = sweep.results
    assert sorted(res["job"]) == list(range(sweep.n_rows)) and sweep.n_rows == sweep.n_jobs
    assert sorted(res["frequency_hz"]) == pytest.approx(sorted(FREQUENCIES_HZ))
    finite = np.isfinite(res["threshold_m"])
    assert np.allclose(res["full_cycle_accel_m_s2"][finite],
                       res["threshold_m"][finite] * (2 * np.pi * res["frequency_hz"][finite]) ** 2)
    # The true peak of the 1-1-1 afd motion at the threshold: by second differences of the
    # closed-form displacement x = A e(t) sin(2 pi f t) on a fine grid.
    for thr, f, peak in zip(res["threshold_m"][finite], res["frequency_hz"][finite],
                            res["peak_accel_m_s2"][finite]):
        t = np.linspace(0.0, 3.0 / f, 600001)
        e = np.where(t < 1.0 / f, np.sin(0.5 * np.pi * f * t) ** 2,
                     np.where(t < 2.0 / f, 1.0, np.cos(0.5 * np.pi * (f * t - 2.0)) ** 2))
        x = thr * e * np.sin(2 * np.pi * f * t)
        assert peak == pytest.approx(np.abs(np.diff(x, 2)).max() / (t[1] - t[0]) ** 2, rel=1e-4)
    assert sweep.config["arch"]["embrace_deg"] == 156.0


def test_envelope_threshold_plots_the_results(threshold_sweep, seed_campaign, tmp_path):
    sweep = read_sweep(threshold_sweep)
    campaign = read_campaign(seed_campaign)
    data = plot_envelope(sweep, tmp_path / "env.png", campaign, ["A156"])
    assert os.path.getsize(data.png_path) > 0
    (curve,) = data.curves
    order = np.argsort(sweep.results["frequency_hz"])
    assert np.array_equal(curve.frequency_hz, sweep.results["frequency_hz"][order])
    assert np.array_equal(curve.threshold_m, sweep.results["threshold_m"][order], equal_nan=True)
    assert [ov.specimen_id for ov in data.measured] == ["A156"]
    assert data.measured[0].thresholds[0].threshold_m == 0.046
    mm = [row[3] for row in data.table.rows]
    assert np.allclose(mm, 1e3 * curve.threshold_m, equal_nan=True)
    # The right panel is the true peak of the motion (the file's column), not A (2 pi f)^2.
    assert np.array_equal(curve.peak_accel_m_s2, sweep.results["peak_accel_m_s2"][order], equal_nan=True)
    assert np.all(curve.peak_accel_m_s2[np.isfinite(curve.peak_accel_m_s2)]
                  > 1.04 * curve.full_cycle_accel_m_s2[np.isfinite(curve.peak_accel_m_s2)])


def test_csv_summary_beside_the_sweep(threshold_sweep):
    sweep = read_sweep(threshold_sweep)
    summary = threshold_sweep.with_suffix(".csv")
    with open(summary, newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == sweep.n_rows
    got = [float(r["threshold_m"]) if r["threshold_m"] not in ("", "nan", "NaN") else math.nan for r in rows]
    assert np.allclose(got, sweep.results["threshold_m"], equal_nan=True, rtol=1e-6)


def test_compare_matches_a156_by_geometry(threshold_sweep, seed_campaign, tmp_path, capsys):
    sweep = read_sweep(threshold_sweep)
    campaign = read_campaign(seed_campaign)
    assert match_specimens(sweep, campaign) == {0: ["A156"]}
    rows, _ = compare_thresholds(sweep, campaign)
    (row,) = rows  # A156 was tested at 1.25 Hz only
    assert row.specimen_id == "A156" and row.frequency_hz == 1.25 and row.measured_m == 0.046
    sim = float(sweep.results["threshold_m"][np.isclose(sweep.results["frequency_hz"], 1.25)][0])
    assert row.simulated_m == sim
    assert row.error_pct == pytest.approx(100 * (sim - 0.046) / 0.046)
    data = plot_compare(sweep, campaign, tmp_path / "cmp.png")
    assert data.mean_abs_error_pct[0] == pytest.approx(abs(row.error_pct))
    assert post.main(["compare", str(threshold_sweep), str(seed_campaign), "--out", str(tmp_path),
                      "--csv"]) == 0
    assert "A156" in capsys.readouterr().out


def test_envelope_grid(grid_sweep, seed_campaign, tmp_path, drawn_figures):
    from figure_text import text_clashes

    sweep = read_sweep(grid_sweep)
    assert sweep.mode == "grid"
    plot_envelope(sweep, tmp_path / "grid_measured.png", read_campaign(seed_campaign), ["A156"])
    assert text_clashes(drawn_figures[0]) == []
    data = plot_envelope(sweep, tmp_path / "grid.png")
    (gm,) = data.maps
    res = sweep.results
    for f, env in zip(gm.envelope_frequency_hz, gm.envelope_amplitude_m):
        sel = (res["frequency_hz"] == f) & (res["collapsed"] == 1)
        expected = res["amplitude_m"][sel].min() if sel.any() else math.nan
        assert env == expected or (math.isnan(env) and math.isnan(expected))
    assert len(gm.amplitude_m) == sweep.n_rows


def test_envelope_figure_reads_for_a_report(threshold_sweep, seed_campaign, voussoir_limit_exe, tmp_path,
                                            drawn_figures):
    """Log frequency axis; the static capacity of voussoir-limit's JSON drawn where it is;
    the measured test drawn over (not under) the threshold marker; the right axis in g;
    no text box over another."""
    from conftest import run_executable
    from figure_text import text_clashes
    from voussoir_post.readers.results import read_limit_json

    limit_nml = tmp_path / "limit.nml"
    limit_nml.write_text(SWEEP_NML.split("&motion")[0])
    proc = run_executable([voussoir_limit_exe, limit_nml, "--json"], tmp_path)
    (tmp_path / "limit.json").write_text(proc.stdout)
    limit = read_limit_json(tmp_path / "limit.json")
    capacity = min(limit.lambda_pos, limit.lambda_neg) * limit.g_m_s2
    assert post.main(["envelope", str(threshold_sweep), "--campaign", str(seed_campaign), "--specimen", "A156",
                      "--limit", str(tmp_path / "limit.json"), "--out", str(tmp_path)]) == 0
    (fig,) = drawn_figures
    ax_a, ax_g = [ax for ax in fig.axes if ax.get_xlabel()]
    assert ax_a.get_xscale() == "log" and ax_g.get_xscale() == "log"
    dashed = [line for line in ax_g.get_lines() if line.get_linestyle() == "--"]
    assert len(dashed) == 1 and np.allclose(dashed[0].get_ydata(), capacity)
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    assert any(f"{capacity:.2f} m/s²" in t and f"{capacity / 9.81:.3f} g" in t for t in legend)
    (right,) = ax_g.child_axes
    assert "[g]" in right.get_ylabel() and "[m/s²]" in ax_g.get_ylabel()
    for ax in (ax_a, ax_g):  # the 46 mm test is drawn above the gold threshold and smaller
        gold = [ln for ln in ax.get_lines() if ln.get_color() == "gold"]
        tests = [ln for ln in ax.get_lines() if ln.get_color() == "black" and len(ln.get_xdata())
                 and ln.get_marker() == "o" and ln.get_linestyle() == "None"]
        assert gold and tests
        assert all(t.get_zorder() > g.get_zorder() and t.get_markersize() < g.get_markersize()
                   for t in tests for g in gold)
    assert text_clashes(fig) == []


def test_parameters_in_words():
    from voussoir_post.plots.drawing import parameters_in_words

    assert parameters_in_words({"embrace_deg": 156.0, "n_voussoirs": 13.0}) == "156°, 13 voussoirs"
    assert parameters_in_words({"arch.thickness_m": 0.065, "friction": 0.45}) == "t = 65 mm, friction 0.45"


def _measured_marks(ax):
    arrows = [a for a in ax.texts if getattr(a, "arrow_patch", None) is not None]
    bars = [c for c in ax.containers if type(c).__name__ == "ErrorbarContainer" and len(c.lines[0].get_xdata())]
    return arrows, bars


def test_compare_draws_a_bracket_open_below_as_a_one_sided_bound(threshold_sweep, seed_campaign, tmp_path,
                                                                  drawn_figures):
    """The seed's A156 bracket is open below (no test stood below 46 mm): an arrow down
    from 46 mm, no error bar, its error marked as a lower bound; with a stand at 40 mm
    added, a closed bracket 40-46 mm about its 43 mm midpoint, no arrow."""
    from figure_text import text_clashes

    sweep = read_sweep(threshold_sweep)
    data = plot_compare(sweep, read_campaign(seed_campaign), tmp_path / "open.png")
    (fig,) = drawn_figures
    ax_a, ax_e = fig.axes
    arrows, bars = _measured_marks(ax_a)
    assert bars == [] and len(arrows) == 1
    (arrow,) = arrows
    assert arrow.xyann[1] == pytest.approx(46.0) and arrow.xy[1] < 46.0  # from the first collapse, down
    assert any(t.get_text().startswith("≥ ") for t in ax_e.texts)
    err_label, bound_label = [t.get_text() for t in ax_e.get_legend().get_texts()]
    assert "lower bound" in bound_label
    assert "(one pair)" in err_label and "mean" not in err_label
    assert "embrace_deg" not in " ".join(t.get_text() for t in ax_a.get_legend().get_texts())
    assert text_clashes(fig) == []
    assert "over 1 pair" in mean_error_lines(data, sweep)[0]

    closed = tmp_path / "campaign"
    shutil.copytree(seed_campaign, closed)
    with open(closed / "tests.csv", "a") as f:
        f.write("A156_f1.25_stand,A156,afd,1.25,0.040,1,1,1,stand,\n")
    data = plot_compare(sweep, read_campaign(closed), tmp_path / "closed.png")
    ax_a, ax_e = drawn_figures[1].axes
    arrows, bars = _measured_marks(ax_a)
    assert arrows == [] and len(bars) == 1
    (bar,) = bars
    low, high = sorted(seg[:, 1].tolist() for seg in bar.lines[2][0].get_segments())[0]
    assert (low, high) == pytest.approx((40.0, 46.0))
    assert not any(t.get_text().startswith("≥") for t in ax_e.texts)
    assert text_clashes(drawn_figures[1]) == []
