"""`voussoir-post fragility --axis pga-lambda-g`: the fragility against PGA / (lambda g),
each row's PGA over the static capacity of its own model sample.

The IDA rows are made here from a known lognormal in the ratio: each row's collapse ratio
x = exp(ln MEDIAN + BETA z), z standard normal, times its model's capacity c_s gives its
PGA threshold, and the bracket is (0.97 x, x] c_s. The fit must recover MEDIAN and BETA
within their sampling error, and the points, curve and figure must be drawn in the ratio;
on PGA the same rows spread much wider (the capacities differ by a factor 2.5). A file
without the capacity column (older sweeps) is refused with a message saying so.
"""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest

from voussoir_post.cli.post import main

G = 9.81
MEDIAN, BETA = 1.45, 0.15  #: the law of the collapse ratio PGA / (lambda g)
CAPACITIES = np.array([1.2, 2.0, 2.6, 3.0])  #: lambda g of the 4 model samples [m/s2]
N_RECORDS = 60
STOOD = 0.97  #: scale_stood / scale_threshold of every row


def ratio_fixture(path, capacities=CAPACITIES, seed=5, capacity_column=True, written=None):
    """An IDA CSV of len(capacities) x N_RECORDS rows from the law above (the column
    static_capacity_m_s2 says `written`, default the capacities); returns the path and
    the ratio at the collapse of each row (file order)."""
    written = capacities if written is None else written
    rng = np.random.default_rng(seed)
    record_pga = rng.uniform(1.0, 8.0, N_RECORDS)  # unscaled PGA of each record [m/s2]
    header = ("record,param_set,scale_stood,scale_threshold,pga_threshold_m_s2,pgv_threshold_m_s,censored"
              + (",static_capacity_m_s2" if capacity_column else ""))
    lines, ratios = ["# an IDA written by hand", header], []
    for s, (capacity, said) in enumerate(zip(capacities, written)):
        for r in range(N_RECORDS):
            ratio = MEDIAN * math.exp(BETA * rng.standard_normal())
            pga = float(ratio * capacity)
            scale = float(pga / record_pga[r])
            lines.append(f"rec/R{r:02d}.AT2,{s},{STOOD * scale!r},{scale!r},{pga!r},{0.1 * scale!r},0"
                         + (f",{float(said)!r}" if capacity_column else ""))
            ratios.append(ratio)
    path.write_text("\n".join(lines) + "\n")
    return path, np.array(ratios)


def test_the_fit_recovers_the_ratio_law_within_its_sampling_error(tmp_path, capsys):
    """240 rows. The maximum-likelihood ln median has standard error beta / sqrt(n) and
    beta about beta / sqrt(2 n) (the brackets, 3 % wide, cost little): each within 4 of
    them. On PGA the same rows mix capacities 1.2-3 m/s2: beta is far larger."""
    path, ratios = ratio_fixture(tmp_path / "ida.csv")
    n = ratios.size
    assert main(["fragility", str(path), "--axis", "pga-lambda-g", "--json", "--bootstrap", "40"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert abs(math.log(out["median_pga_lambda_g"] / MEDIAN)) < 4 * BETA / math.sqrt(n)
    assert abs(out["beta_pga_lambda_g"] - BETA) < 4 * BETA / math.sqrt(2 * n)
    low, high = out["median_pga_lambda_g_band"]
    assert low < out["median_pga_lambda_g"] < high
    assert out["beta_pga"] > 2 * BETA  # PGA: the capacities' spread is in it
    # the existing keys are kept beside the new ones
    assert {"median_pga_g", "beta_pga", "median_pga_g_band", "gof_p_value", "beta_record", "beta_model"} <= set(out)
    assert out["static_capacities_m_s2"] == pytest.approx(sorted(CAPACITIES), rel=1e-9)
    # each sample alone: its median in the ratio is MEDIAN (the capacity taken out)
    for median in out["median_pga_lambda_g_by_sample"]:
        assert abs(math.log(median / MEDIAN)) < 4 * BETA / math.sqrt(N_RECORDS)


def test_points_curve_and_figure_are_in_the_ratio(tmp_path, capsys, drawn_figures):
    path, ratios = ratio_fixture(tmp_path / "ida.csv", seed=9)
    assert main(["fragility", str(path), "--axis", "pga-lambda-g", "--bootstrap", "20", "--out", str(tmp_path)]) == 0
    text = capsys.readouterr().out
    assert "PGA / (lambda g): median" in text
    png = tmp_path / "ida_fragility_pga_lambda_g.png"
    assert png.exists()
    with open(tmp_path / "ida_fragility_pga_lambda_g_points.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert np.allclose([float(r["pga_lambda_g_threshold"]) for r in rows], ratios, rtol=1e-9)
    assert np.allclose([float(r["pga_lambda_g_stood"]) for r in rows], STOOD * ratios, rtol=1e-9)
    with open(tmp_path / "ida_fragility_pga_lambda_g.csv", newline="") as f:
        curve = list(csv.DictReader(f))
    x = np.array([float(r["pga_lambda_g"]) for r in curve])
    p = np.array([float(r["p_collapse"]) for r in curve])
    assert x.max() == pytest.approx(1.15 * ratios.max(), rel=1e-9)
    assert abs(np.interp(0.5, p, x) / MEDIAN - 1.0) < 4 * BETA / math.sqrt(ratios.size)  # the curve is in the ratio
    fig, _ = drawn_figures  # the fragility, then the record table
    (ax,) = fig.axes
    assert "λ g" in ax.get_xlabel() and "static capacity = 1" in ax.get_xlabel()
    verticals = [line for line in ax.lines if np.ptp(line.get_xdata()) == 0 and len(line.get_xdata()) == 2]
    assert any(float(line.get_xdata()[0]) == 1.0 for line in verticals)  # the static capacity at 1
    # the points at the geometric middle of their brackets (STOOD x, x], each with a bar over its bracket
    points = [line for line in ax.lines if line.get_marker() == "o"]
    assert len(points) == 1 and set(np.round(points[0].get_xdata(), 9)) <= set(np.round(math.sqrt(STOOD) * ratios, 9))
    (bars,) = ax.collections[1:]  # after the band
    for (x0, _), (x1, _) in (segment for segment in bars.get_segments()):
        assert np.isclose(x1 * STOOD, x0, rtol=1e-9) and np.round(x1, 9) in set(np.round(ratios, 9))
    # the x-range fitted to the data: from just below the static capacity 1 (or the lowest bracket) to just
    # beyond the last point
    left, right = ax.get_xlim()
    lowest = min(1.0, STOOD * ratios.min())
    assert lowest - 0.1 * (right - lowest) < left < lowest and ratios.max() < right < 1.1 * ratios.max()
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert any(label.startswith("static capacity: PGA = λ g") for label in labels)


def test_compare_puts_both_models_on_the_one_ratio_axis(tmp_path, capsys):
    """Two files of the same ratio law on different capacities (the second model about
    half as strong): in the ratio their medians agree within the sampling error of
    both, while in PGA they differ by the capacities."""
    a, _ = ratio_fixture(tmp_path / "a.csv", seed=1)
    b, _ = ratio_fixture(tmp_path / "b.csv", CAPACITIES * 0.5, seed=2)
    assert main(["fragility", str(a), "--compare", str(b), "--axis", "pga-lambda-g", "--json", "--bootstrap", "20",
                 "--out", str(tmp_path)]) == 0
    out = json.loads(capsys.readouterr().out)
    n = CAPACITIES.size * N_RECORDS
    for fit in out["fits"]:
        assert abs(math.log(fit["median_pga_lambda_g"] / MEDIAN)) < 4 * BETA / math.sqrt(n)
    assert abs(math.log(out["median_pga_lambda_g_ratio"])) < 4 * BETA * math.sqrt(2.0 / n)
    assert abs(math.log(out["median_pga_ratio"] / 0.5)) < 4 * BETA * math.sqrt(2.0 / n) + 0.1
    assert (tmp_path / "a_compare_fragility_pga_lambda_g.png").exists()
    with open(tmp_path / "a_compare_fragility_pga_lambda_g.csv", newline="") as f:
        assert list(csv.DictReader(f))[0].keys() >= {"pga_lambda_g", "p_collapse_a", "p_collapse_b"}


def test_a_file_without_the_capacity_is_refused(tmp_path, capsys):
    old, _ = ratio_fixture(tmp_path / "old.csv", capacity_column=False)
    new, _ = ratio_fixture(tmp_path / "new.csv")
    assert main(["fragility", str(old), "--axis", "pga-lambda-g", "--bootstrap", "20"]) == 2
    err = capsys.readouterr().err
    assert "old.csv: the rows do not give static_capacity_m_s2" in err and "run the IDA again" in err
    assert main(["fragility", str(new), "--compare", str(old), "--axis", "pga-lambda-g", "--bootstrap", "20"]) == 2
    assert "old.csv: the rows do not give static_capacity_m_s2" in capsys.readouterr().err
    # without --axis the old file is fitted as before
    assert main(["fragility", str(old), "--json", "--bootstrap", "20"]) == 0
    assert "median_pga_lambda_g" not in json.loads(capsys.readouterr().out)


def test_a_capacity_of_zero_is_refused(tmp_path, capsys):
    path, _ = ratio_fixture(tmp_path / "ida.csv", capacities=np.array([2.0, 2.0]), written=[2.0, 0.0])
    assert main(["fragility", str(path), "--axis", "pga-lambda-g", "--bootstrap", "20"]) == 2
    assert f"row {N_RECORDS + 1} (record rec/R00.AT2, param_set 1): static_capacity_m_s2 = 0.0" in \
        capsys.readouterr().err


def test_the_pga_fit_says_what_its_tail_puts_below_the_static_capacity(tmp_path, capsys):
    """No rigid model collapses below its own static capacity, but the PGA lognormal has
    a tail there: the report gives the lowest capacity and the fit's probability at it,
    which must be the lognormal's cdf there (scipy's, from the reported median and beta);
    a file without capacities gives none."""
    from scipy.stats import norm

    path, _ = ratio_fixture(tmp_path / "ida.csv", seed=3)
    assert main(["fragility", str(path), "--json", "--bootstrap", "20"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["pga_floor_m_s2"] == pytest.approx(CAPACITIES.min(), rel=1e-12)
    expected = norm.cdf(math.log(CAPACITIES.min() / out["median_pga_m_s2"]) / out["beta_pga"])
    assert out["p_collapse_at_floor"] == pytest.approx(expected, rel=1e-9)
    assert 0.0 < out["p_collapse_at_floor"] < 0.5
    assert main(["fragility", str(path), "--bootstrap", "20", "--out", str(tmp_path)]) == 0
    assert (f"floor: no rigid model moves below its static capacity (the lowest here {CAPACITIES.min() / G:.3g} g)"
            in capsys.readouterr().out)
    old, _ = ratio_fixture(tmp_path / "old.csv", capacity_column=False)
    assert main(["fragility", str(old), "--json", "--bootstrap", "20"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["pga_floor_m_s2"] is None and out["p_collapse_at_floor"] is None
