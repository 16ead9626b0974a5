"""`voussoir-post fragility` on IDA files written by hand in this file (they are the
fit's input, not simulated data; test_ida_sweep.py runs the real sweep): how each row
enters the fit (a bracket, censored at scale_max, a failed search censored at its last
stand or left out), the clusters of the band, the split of beta by model sample, the
per-row disclosure in the points CSV, the comparison of two files (--compare), and
refusals that name the file, line and column. The fit itself: test_fragility.py.
"""

from __future__ import annotations

import csv
import json
import math

import h5py
import numpy as np
import pytest
from scipy import optimize, stats

from voussoir_post.cli.post import main
from voussoir_post.earthquake.fragility import fit_intervals
from voussoir_post.earthquake.ida import (FIT_BRACKET, FIT_CENSORED, FIT_FAILED, FIT_FAILED_COLLAPSED, FIT_LEFT_OUT,
                                          read_ida)
from voussoir_post.readers.results import ResultsError

G = 9.81
RECORDS = ["rec/ELC180.AT2", "rec/CLS000.AT2", "rec/PUL164.AT2"]
EVENTS = ["Imperial Valley 1940", "Loma Prieta 1989", "San Fernando 1971"]
PGA = np.array([2.75, 6.33, 11.96])  # unscaled record PGA [m/s2]
PGV = np.array([0.31, 0.56, 1.14])
SCALES = np.array([[1.2, 0.61, 0.33], [1.5, 0.55, 0.29]])  # thresholds: 2 model samples x 3 records


def csv_fixture(path, scales, censored=None, stood=0.97, non_monotonic=None, events=None):
    """An IDA CSV: scale_stood = stood x scale_threshold (scale_max on both where
    censored); an `event` column when `events` (one per record) is given."""
    censored = np.zeros(scales.shape, bool) if censored is None else censored
    non_monotonic = np.zeros(scales.shape, bool) if non_monotonic is None else non_monotonic
    lines = ["# an IDA written by hand", "record,param_set,friction,scale_stood,scale_threshold,"
             "pga_threshold_m_s2,pgv_threshold_m_s,censored,non_monotonic,n_runs" + (",event" if events else "")]
    for s in range(scales.shape[0]):
        for r in range(scales.shape[1]):
            k = float(scales[s, r])
            below = k if censored[s, r] else stood * k
            lines.append(f"{RECORDS[r]},{s},{0.5 + 0.1 * s},{below!r},{k!r},{k * float(PGA[r])!r},"
                         f"{k * float(PGV[r])!r},{int(censored[s, r])},{int(non_monotonic[s, r])},7"
                         + (f",{events[r]}" if events else ""))
    path.write_text("\n".join(lines) + "\n")
    return path


def read_points(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_rows_of_no_width_are_exact_and_give_the_closed_form(tmp_path, capsys):
    """scale_stood = scale_threshold on a row that collapsed: an exact intensity, and
    with only such rows the fit is the closed form (divisor n)."""
    path = csv_fixture(tmp_path / "ida.csv", SCALES, stood=1.0)
    assert main(["fragility", str(path), "--json", "--bootstrap", "50"]) == 0
    out = json.loads(capsys.readouterr().out)
    pga = (SCALES * PGA).reshape(-1)
    pgv = (SCALES * PGV).reshape(-1)
    assert out["median_pga_g"] == pytest.approx(math.exp(np.mean(np.log(pga))) / G, rel=1e-12)
    assert out["beta"] == pytest.approx(np.std(np.log(pga), ddof=0), rel=1e-12)
    assert out["median_pgv_m_s"] == pytest.approx(math.exp(np.mean(np.log(pgv))), rel=1e-12)
    assert out["beta_pgv"] == pytest.approx(np.std(np.log(pgv), ddof=0), rel=1e-12)
    assert out["n_rows"] == 6 and out["n_censored"] == 0 and out["n_interval"] == 0
    assert "not n - 1" in out["beta_convention"]
    assert (tmp_path / "ida_fragility.png").stat().st_size > 10000
    assert (tmp_path / "ida_fragility.csv").is_file() and (tmp_path / "ida_fragility_points.csv").is_file()


def test_beta_split_of_exact_rows_by_hand(tmp_path, capsys):
    """Rows of no width on 2 model samples x 3 records: each sample's fit is the closed
    form, so beta_RTR = sqrt(mean of the two samples' std ln IM) and beta_model = the
    standard deviation (divisor 1) of their mean ln IM, computed here from the scales;
    the same for PGV. The dashed curve's median is the low end of the median's band."""
    path = csv_fixture(tmp_path / "ida.csv", SCALES, stood=1.0)
    assert main(["fragility", str(path), "--json", "--bootstrap", "50"]) == 0
    out = json.loads(capsys.readouterr().out)
    for measure, unit, scale, intensities in (("pga", "g", G, PGA), ("pgv", "m_s", 1.0, PGV)):
        ln_im = np.log(SCALES * intensities)  # (model sample, record)
        assert out[f"beta_{measure}_rtr"] == pytest.approx(math.sqrt(np.mean(np.var(ln_im, axis=1))), rel=1e-12)
        assert out[f"beta_{measure}_model"] == pytest.approx(np.std(np.mean(ln_im, axis=1), ddof=1), rel=1e-12)
        assert out[f"beta_{measure}_srss"] == pytest.approx(math.hypot(out[f"beta_{measure}_rtr"],
                                                                       out[f"beta_{measure}_model"]), rel=1e-12)
        np.testing.assert_allclose(out[f"median_{measure}_{unit}_by_sample"],
                                   np.exp(np.mean(ln_im, axis=1)) / scale, rtol=1e-12)
        np.testing.assert_allclose(out[f"beta_{measure}_by_sample"], np.std(ln_im, axis=1), rtol=1e-12)
    assert out["model_samples"] == [0, 1] and "divisor m - 1" in out["beta_split"]
    # the interface keys of issue 24: PGA's split under its plain names, the fit and the band
    ln_pga = np.log(SCALES * PGA)
    assert out["beta_record"] == pytest.approx(math.sqrt(np.mean(np.var(ln_pga, axis=1))), rel=1e-12)
    assert out["beta_model"] == pytest.approx(np.std(np.mean(ln_pga, axis=1), ddof=1), rel=1e-12)
    assert out["beta_pga"] == out["beta"] and out["fit"] == "interval" and out["band_cluster"] == "record"
    assert out["gof_p_value"] == out["ks_p_pga"] and 0.0 <= out["gof_p_value"] <= 1.0
    low_g, high_g = out["median_pga_g_band"]
    assert low_g < out["median_pga_g"] < high_g and out["band_level"] == 0.9
    assert out["median_pga_g_conf"] == out["median_pga_g_band"][0] and out["conf_level"] == 0.95
    # Each resample's fit is listed (what voussoir-post risk carries into its band): the
    # band's ends are their 5th and 95th percentiles (ln median, as the band takes them).
    medians, betas = np.array(out["bootstrap_median_pga_g"]), np.array(out["bootstrap_beta_pga"])
    assert medians.size == betas.size == out["n_bootstrap"]
    np.testing.assert_allclose(np.exp(np.percentile(np.log(medians), [5, 95])), out["median_pga_g_band"], rtol=1e-12)
    np.testing.assert_allclose(np.percentile(betas, [5, 95]), out["beta_pga_band"], rtol=1e-12)
    assert out["median_pgv_m_s_conf"] == out["median_pgv_m_s_band"][0]
    assert main(["fragility", str(path), "--bootstrap", "50"]) == 0
    text = capsys.readouterr().out
    assert "PGA beta split over 2 model samples: record-to-record" in text and "lower 5 % bound" in text
    curve = read_points(tmp_path / "ida_fragility.csv")
    median_conf = out["median_pga_g_conf"] * G
    p_conf = [stats.norm.cdf(math.log(float(c["pga_m_s2"]) / median_conf) / out["beta"]) for c in curve]
    np.testing.assert_allclose([float(c["p_conf"]) for c in curve], p_conf, rtol=1e-9, atol=1e-12)


def test_one_model_sample_has_no_model_part(tmp_path, capsys):
    path = csv_fixture(tmp_path / "ida.csv", SCALES[:1], stood=0.97)
    assert main(["fragility", str(path), "--json", "--bootstrap", "30"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["beta_pga_model"] is None and out["beta_pga_srss"] is None and out["model_samples"] == [0]
    assert out["beta_model"] is None and out["beta_record"] == pytest.approx(out["beta"], rel=1e-12)
    assert out["beta_pga_rtr"] == pytest.approx(out["beta"], rel=1e-12)
    assert main(["fragility", str(path), "--bootstrap", "30"]) == 0
    assert "one model sample" in capsys.readouterr().out


def test_cli_fits_the_brackets_and_discloses_each_row(tmp_path, capsys):
    """Each row's PGA at collapse lies in (0.97, 1] x its PGA at scale_threshold: the
    command's fit is the maximum of that interval likelihood, maximised here by
    Nelder-Mead on a likelihood written from scipy.stats.norm; it lies between the fits
    of the bottoms and of the tops. The points CSV says per row how it was fitted, its
    bracket, its non_monotonic flag (two rows set here) and its PIT, within F of its
    bracket; the band draws the 3 records."""
    non_monotonic = np.array([[False, True, False], [False, False, True]])
    path = csv_fixture(tmp_path / "ida.csv", SCALES, non_monotonic=non_monotonic)
    assert main(["fragility", str(path), "--json", "--bootstrap", "60"]) == 0
    out = json.loads(capsys.readouterr().out)
    top = (SCALES * PGA).reshape(-1)
    low, high = 0.97 * top, top

    def cost(p):
        return -np.sum(np.log(stats.norm.cdf((np.log(high) - p[0]) / p[1])
                              - stats.norm.cdf((np.log(low) - p[0]) / p[1])))

    best = optimize.minimize(cost, [np.mean(np.log(top)), np.std(np.log(top))], method="Nelder-Mead",
                             options={"xatol": 1e-11, "fatol": 1e-14, "maxiter": 20000})
    assert out["median_pga_g"] == pytest.approx(math.exp(best.x[0]) / G, rel=1e-7)
    assert out["beta"] == pytest.approx(best.x[1], rel=1e-6)
    assert 0.97 * math.exp(np.mean(np.log(top))) / G < out["median_pga_g"] < math.exp(np.mean(np.log(top))) / G
    assert out["n_rows"] == 6 and out["n_interval"] == 6 and out["n_censored"] == 0
    assert out["n_non_monotonic"] == 2
    assert out["cluster_by"] == "record" and out["n_clusters"] == 3 and out["n_bootstrap"] == 60
    assert 0.0 <= out["ks_p_pga"] <= 1.0 and 0.0 <= out["ks_d_pga"] <= 1.0
    points = read_points(tmp_path / "ida_fragility_points.csv")
    assert [p["non_monotonic"] for p in points] == [str(int(v)) for v in non_monotonic.reshape(-1)]
    assert all(p["fit_as"] == FIT_BRACKET and p["failed"] == "0" for p in points)
    np.testing.assert_allclose([float(p["pga_stood_g"]) for p in points], low / G, rtol=1e-12)
    median, beta = out["median_pga_m_s2"], out["beta"]
    pit = np.array([float(p["pit_pga"]) for p in points])
    f_low, f_high = (stats.norm.cdf(np.log(b / median) / beta) for b in (low, high))
    assert np.all((f_low <= pit + 1e-12) & (pit <= f_high + 1e-12))
    assert main(["fragility", str(path), "--bootstrap", "60"]) == 0
    text = capsys.readouterr().out
    assert "clustered by record" in text and "2 non-monotonic" in text and "Kolmogorov-Smirnov" in text


def test_an_event_column_makes_the_band_draw_events(tmp_path, capsys):
    path = csv_fixture(tmp_path / "ida.csv", SCALES, events=[EVENTS[0], EVENTS[0], EVENTS[2]])
    ida = read_ida(path)
    assert ida.event[:3] == [EVENTS[0], EVENTS[0], EVENTS[2]] and "event" not in ida.parameters
    assert main(["fragility", str(path), "--json", "--bootstrap", "60"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["cluster_by"] == "event" and out["band_cluster"] == "event" and out["n_clusters"] == 2
    assert read_points(tmp_path / "ida_fragility_points.csv")[2]["event"] == EVENTS[2]


def with_failed_row(path, stood):
    """Append a failed search of record 0 on model 1 to the CSV at `path`, its
    scale_stood `stood` (NaN: as voussoir-sweep writes it, the last stand unknown)."""
    lines = path.read_text().splitlines()
    lines[1] += ",failed"
    lines[2:] = [line + ",0" for line in lines[2:]]
    lines.append(f"{RECORDS[0]},1,0.6,{stood!r},nan,nan,nan,0,0,1,1")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_a_failed_row_without_its_last_stand_is_left_out_and_said(tmp_path, capsys):
    path = with_failed_row(csv_fixture(tmp_path / "ida.csv", SCALES), math.nan)
    ida = read_ida(str(path))
    assert ida.n_failed == 1 and ida.n_rows == 7 and "failed" not in ida.parameters
    assert ida.fit_as[-1] == FIT_LEFT_OUT and ida.fit_as[:-1] == [FIT_BRACKET] * 6
    assert main(["fragility", str(path), "--json", "--bootstrap", "20"]) == 0
    captured = capsys.readouterr()
    out = json.loads(captured.out)
    assert out["n_rows"] == 6 and out["n_failed_left_out"] == 1 and out["n_failed_censored"] == 0
    assert "1 rows left out" in captured.err and "last stand" in captured.err


def test_a_failed_row_is_right_censored_at_its_last_stand(tmp_path, capsys):
    """A failed search of El Centro that stood up to scale 2.0 (above the record's
    thresholds, 1.2 and 1.5): its PGA at collapse exceeds 2.0 x the record's PGA (taken
    from the record's other rows). It enters the fit so, and raises the median above
    the fit without it."""
    plain = csv_fixture(tmp_path / "plain.csv", SCALES)
    path = with_failed_row(csv_fixture(tmp_path / "ida.csv", SCALES), 2.0)
    ida = read_ida(str(path))
    assert ida.fit_as[-1] == FIT_FAILED
    low, high = ida.intensity_brackets("pga")
    assert low[-1] == pytest.approx(2.0 * PGA[0], rel=1e-12) and high[-1] == math.inf
    assert main(["fragility", str(path), "--json", "--bootstrap", "20"]) == 0
    captured = capsys.readouterr()
    out = json.loads(captured.out)
    assert out["n_rows"] == 7 and out["n_failed_censored"] == 1 and out["n_failed_left_out"] == 0
    assert "1 fitted as right-censored at their last stand" in captured.err
    top = (SCALES * PGA).reshape(-1)
    expected = fit_intervals(np.append(0.97 * top, 2.0 * PGA[0]), np.append(top, math.inf))
    assert out["median_pga_m_s2"] == pytest.approx(expected.median, rel=1e-9)
    assert main(["fragility", str(plain), "--json", "--bootstrap", "20"]) == 0
    assert out["median_pga_m_s2"] > json.loads(capsys.readouterr().out)["median_pga_m_s2"]
    assert read_points(tmp_path / "ida_fragility_points.csv")[-1]["fit_as"] == FIT_FAILED


def h5_fixture(path, scales, censored, scale_max):
    """An IDA sweep file as docs/results_format.md describes it."""
    n_sets, n_rec = scales.shape
    with h5py.File(path, "w") as h5:
        h5.attrs["producer"] = "voussoir-sweep"
        h5.attrs["mode"] = "ida"
        h5.attrs["code_version"] = "voussoir 9.9.9+test"
        h5.attrs["record_files"] = "\n".join(RECORDS)
        h5.attrs["parameter_names"] = "friction,thickness_m"
        h5.attrs["config_nml"] = "&arch\n  embrace_deg = 156.0\n  n_voussoirs = 13\n  r_ext_m = 0.508\n" \
                                 "  thickness_m = 0.071\n/\n"
        h5["parameters/values"] = np.array([[0.5 + 0.05 * s, 0.07 + 0.001 * s] for s in range(n_sets)])
        h5["sweep/record_pga_m_s2"] = PGA
        h5["sweep/record_pgv_m_s"] = PGV
        sets, recs = np.meshgrid(np.arange(n_sets), np.arange(n_rec), indexing="ij")
        k = np.where(censored, scale_max, scales)
        h5["results/job"] = np.arange(n_sets * n_rec)
        h5["results/param_set"] = sets.reshape(-1)
        h5["results/record"] = recs.reshape(-1)
        h5["results/scale_stood"] = np.where(censored, scale_max, 0.96 * scales).reshape(-1)
        h5["results/scale_threshold"] = k.reshape(-1)
        h5["results/pga_threshold_m_s2"] = (k * PGA).reshape(-1)
        h5["results/pgv_threshold_m_s"] = (k * PGV).reshape(-1)
        h5["results/censored"] = censored.reshape(-1).astype(int)
        h5["results/non_monotonic"] = np.zeros(n_sets * n_rec, int)
        h5["results/n_runs"] = np.full(n_sets * n_rec, 9)
    return path


def test_hdf5_ida_with_censored_rows(tmp_path, capsys):
    rng = np.random.default_rng(11)
    scales = np.exp(rng.normal(0.0, 0.4, (8, 3))) * 3.9 / PGA  # capacities around 3.9 m/s2
    scale_max = 1.6
    censored = scales > scale_max
    assert censored.any() and (~censored).sum() >= 2
    path = h5_fixture(tmp_path / "ida.h5", scales, censored, scale_max)
    ida = read_ida(path)
    assert ida.n_rows == 24 and ida.records == RECORDS and ida.n_sets == 8
    assert ida.record[4] == RECORDS[1] and ida.param_set[4] == 1
    assert ida.code_version == "voussoir 9.9.9+test"  # the figure's small print names it
    np.testing.assert_allclose(ida.parameters["friction"][3:6], 0.55)
    np.testing.assert_array_equal(ida.censored, censored.reshape(-1))
    # The brackets as the format defines them: (0.96, 1] x the threshold's PGA, or
    # above the PGA at scale_max.
    low = np.where(censored, scale_max, 0.96 * scales) * PGA
    high = np.where(censored, np.inf, scales * PGA)
    got_low, got_high = ida.intensity_brackets("pga")
    np.testing.assert_allclose(got_low, low.reshape(-1), rtol=1e-12)
    np.testing.assert_array_equal(np.isinf(got_high), censored.reshape(-1))
    np.testing.assert_allclose(got_high[~censored.reshape(-1)], high[~censored], rtol=1e-12)
    assert [k for k, c in zip(ida.fit_as, censored.reshape(-1)) if c] == [FIT_CENSORED] * int(censored.sum())
    expected = fit_intervals(low.reshape(-1), high.reshape(-1))
    assert main(["fragility", str(path), "--json", "--bootstrap", "50"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["n_censored"] == int(censored.sum())
    assert out["median_pga_g"] == pytest.approx(expected.median / G, rel=1e-9)
    assert out["beta"] == pytest.approx(expected.beta, rel=1e-9)
    lo, hi = out["median_pga_g_band"]
    assert lo < out["median_pga_g"] < hi
    assert main(["fragility", str(path), "--bootstrap", "50"]) == 0
    text = capsys.readouterr().out
    assert "PGA: median" in text and f"{int(censored.sum())} censored" in text


def test_hdf5_failed_search_after_a_collapse_is_bracketed_by_the_runs(tmp_path, capsys):
    """The sweep writes NaN in the /results row of a failed search; its runs in /runs say
    how far it got: stands at 0.9 and 1.0, a collapse at 1.1, a stand at 1.2 (above the
    collapse: not a lower bound of the first collapse), then the failed run at 1.05. Its
    last stand is 1.0 and it collapsed at 1.1: its collapse lies in (1.0, 1.1] x the record's
    PGA (/sweep/record_pga_m_s2), not merely above 1.0 (issue 36); counted as a collapse at
    its failed run, in (1.0, 1.05]."""
    scales = np.exp(np.random.default_rng(15).normal(0.0, 0.3, (4, 3))) * 3.9 / PGA
    path = h5_fixture(tmp_path / "ida.h5", scales, np.zeros(scales.shape, bool), 10.0)
    job = 4  # model 1, record 1
    with h5py.File(path, "a") as h5:
        for name in ("scale_stood", "scale_threshold", "pga_threshold_m_s2", "pgv_threshold_m_s"):
            values = h5[f"results/{name}"][()]
            values[job] = np.nan
            h5[f"results/{name}"][...] = values
        failed = np.zeros(12, int)
        failed[job] = 1
        h5["results/failed"] = failed
        h5["runs/job"] = [3, 4, 4, 4, 4, 4, 5]
        h5["runs/scale"] = [1.0, 0.9, 1.0, 1.1, 1.2, 1.05, 1.0]
        h5["runs/collapsed"] = [1, 0, 0, 1, 0, 0, 1]
        h5["runs/failed"] = [0, 0, 0, 0, 0, 1, 0]
    ida = read_ida(path)
    assert ida.n_failed == 1 and ida.fit_as[job] == FIT_FAILED_COLLAPSED and ida.scale_stood[job] == 1.0
    low, high = ida.intensity_brackets("pgv")
    assert low[job] == pytest.approx(1.0 * PGV[1], rel=1e-12) and high[job] == pytest.approx(1.1 * PGV[1], rel=1e-12)
    low, high = ida.scale_brackets(failures_as_collapses=True)
    assert (low[job], high[job]) == (1.0, 1.05)
    assert main(["fragility", str(path), "--json", "--bootstrap", "30"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["n_rows"] == 12 and out["n_failed_censored"] == 0 and out["n_failed_after_collapse"] == 1
    assert out["n_interval"] == 12 and out["failures_as_collapses"]["n_counted"] == 1


def test_failures_read_two_ways_on_a_set_whose_intervals_are_known(tmp_path, capsys):
    """Six searches on one model: three plain brackets, a failed search that had collapsed
    (stands to 1.0, collapse at 1.3, failed at 1.15), one that failed without a collapse
    (stands to 0.8, failed at 0.9) and one that failed before any stand (failed at 0.5).
    The right reading: (1.0, 1.3], (0.8, inf) and left out; every failure a collapse:
    (1.0, 1.15], (0.8, 0.9] and (0, 0.5]. Both fits are the interval fits of those brackets,
    written here by hand."""
    records = RECORDS + ["rec/A.AT2", "rec/B.AT2", "rec/C.AT2"]
    unit_pga = np.array([2.0, 3.0, 4.0, 2.5, 3.5, 5.0])
    stood = np.array([1.2, 0.7, 0.45, 1.0, 0.8, np.nan])
    threshold = np.array([1.3, 0.75, 0.5, np.nan, np.nan, np.nan])
    failed = np.array([0, 0, 0, 1, 1, 1])
    path = tmp_path / "ida.h5"
    with h5py.File(path, "w") as h5:
        h5.attrs["producer"], h5.attrs["mode"] = "voussoir-sweep", "ida"
        h5.attrs["record_files"] = "\n".join(records)
        h5["sweep/record_pga_m_s2"] = unit_pga
        h5["sweep/record_pgv_m_s"] = unit_pga / 9.0
        h5["results/job"] = np.arange(6)
        h5["results/param_set"] = np.zeros(6, int)
        h5["results/record"] = np.arange(6)
        h5["results/scale_stood"] = stood
        h5["results/scale_threshold"] = threshold
        h5["results/pga_threshold_m_s2"] = threshold * unit_pga
        h5["results/pgv_threshold_m_s"] = threshold * unit_pga / 9.0
        h5["results/censored"] = np.zeros(6, int)
        h5["results/failed"] = failed
        h5["runs/job"] = [0, 0, 1, 1, 2, 2, 3, 3, 3, 4, 4, 5]
        h5["runs/scale"] = [1.2, 1.3, 0.7, 0.75, 0.45, 0.5, 1.0, 1.3, 1.15, 0.8, 0.9, 0.5]
        h5["runs/collapsed"] = [0, 1, 0, 1, 0, 1, 0, 1, 0, 0, 0, 0]
        h5["runs/failed"] = [0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 1, 1]
    ida = read_ida(path)
    assert ida.fit_as[3:] == [FIT_FAILED_COLLAPSED, FIT_FAILED, FIT_LEFT_OUT]
    right_low = np.array([1.2, 0.7, 0.45, 1.0, 0.8]) * unit_pga[:5]
    right_high = np.array([1.3, 0.75, 0.5, 1.3, math.inf]) * unit_pga[:5]
    all_low = np.array([1.2, 0.7, 0.45, 1.0, 0.8, 0.0]) * unit_pga
    all_high = np.array([1.3, 0.75, 0.5, 1.15, 0.9, 0.5]) * unit_pga
    for flag, (lo, hi) in ((False, (right_low, right_high)), (True, (all_low, all_high))):
        low, high = ida.intensity_brackets("pga", failures_as_collapses=flag)
        used = np.isfinite(low)
        np.testing.assert_allclose(low[used], lo, rtol=1e-12)
        np.testing.assert_allclose(high[used], hi, rtol=1e-12)
    right, every = fit_intervals(right_low, right_high), fit_intervals(all_low, all_high)
    assert main(["fragility", str(path), "--json", "--bootstrap", "20"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["median_pga_g"] == pytest.approx(right.median / G, rel=1e-9)
    second = out["failures_as_collapses"]
    assert second["n_counted"] == 3 and out["n_failed"] == 3
    assert second["median_pga_g"] == pytest.approx(every.median / G, rel=1e-9)
    assert second["beta_pga"] == pytest.approx(every.beta, rel=1e-9)
    assert second["median_ratio"] == pytest.approx(every.median / right.median, rel=1e-9)
    assert main(["fragility", str(path), "--bootstrap", "20"]) == 0
    assert "failed searches: 3 (1 had collapsed before failing" in capsys.readouterr().out


@pytest.mark.parametrize("edit, words", [
    (lambda t: t.replace(",censored,", ",flag,"), "line 2: the header lacks the column(s) censored"),
    (lambda t: t.replace(",0,0,7\n", ",2,0,7\n", 1), "line 3, column censored: '2' is not 0 or 1"),
    (lambda t: t.replace("rec/CLS000.AT2,0,0.5,", "rec/CLS000.AT2,0,0.5,x", 1), "line 4, column scale_stood"),
])
def test_bad_ida_csv_is_refused_with_line_and_column(tmp_path, capsys, edit, words):
    path = csv_fixture(tmp_path / "ida.csv", SCALES)
    path.write_text(edit(path.read_text()))
    assert main(["fragility", str(path)]) == 2
    err = capsys.readouterr().err
    assert str(path) in err and words in err, err


def test_all_censored_and_wrong_files_are_refused(tmp_path, capsys):
    scales = np.full((2, 3), 2.0)
    path = csv_fixture(tmp_path / "ida.csv", scales, censored=np.ones((2, 3), bool))
    assert main(["fragility", str(path)]) == 2
    assert "at least two different collapse intensities" in capsys.readouterr().err
    other = tmp_path / "threshold.h5"
    with h5py.File(other, "w") as h5:
        h5.attrs["producer"] = "voussoir-sweep"
        h5.attrs["mode"] = "threshold"
    with pytest.raises(ResultsError, match="a 'threshold' sweep, not an IDA"):
        read_ida(other)


def test_compare_two_files_in_one_figure(tmp_path, capsys):
    """B is A with every record's thresholds at 0.7 times the scale: every bracket is 0.7
    times A's, so (the fit is equivariant in the scale of IM) B's medians are 0.7 times
    A's and its betas, split included, are A's. Each file's fit is the one `fragility`
    gives it alone; the figure is written with the curves of both on one grid."""
    a = csv_fixture(tmp_path / "nominal.csv", SCALES)
    b = csv_fixture(tmp_path / "calibrated.csv", 0.7 * SCALES)
    assert main(["fragility", str(a), "--json", "--bootstrap", "40"]) == 0
    alone = json.loads(capsys.readouterr().out)
    assert main(["fragility", str(a), "--compare", str(b), "--labels", "nominal model", "as tested", "--json",
                 "--bootstrap", "40"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["labels"] == ["nominal model", "as tested"] and out["files"] == [str(a), str(b)]
    assert out["same_records"] is True
    fit_a, fit_b = out["fits"]
    for key in ("median_pga_g", "beta", "beta_pga_rtr", "beta_pga_model", "median_pgv_m_s", "beta_pgv",
                "median_pga_g_band", "median_pga_g_conf", "ks_p_pga"):
        assert fit_a[key] == pytest.approx(alone[key], rel=1e-12), key
    assert out["median_pga_ratio"] == pytest.approx(0.7, rel=1e-7)
    assert out["median_pgv_ratio"] == pytest.approx(0.7, rel=1e-7)
    assert fit_b["median_pga_g_conf"] == pytest.approx(0.7 * fit_a["median_pga_g_conf"], rel=1e-7)
    for key in ("beta", "beta_pgv", "beta_pga_rtr", "beta_pga_model", "beta_pgv_model"):
        assert fit_b[key] == pytest.approx(fit_a[key], rel=1e-6), key
    png = tmp_path / "nominal_compare_fragility.png"
    assert png.stat().st_size > 10000
    curve = read_points(tmp_path / "nominal_compare_fragility.csv")
    assert {"pga_g", "p_collapse_a", "p_conf_a", "p_low_b", "p_conf_b"} <= set(curve[0])
    # One grid: at any PGA, B (weaker) is at least as likely to collapse as A.
    assert all(float(c["p_collapse_b"]) >= float(c["p_collapse_a"]) - 1e-15 for c in curve)
    assert main(["fragility", str(a), "--compare", str(b), "--bootstrap", "40", "--out", str(tmp_path / "f.png")]) == 0
    text = capsys.readouterr().out
    assert "== nominal: " in text and "== calibrated: " in text  # the stems by default
    assert "== calibrated against nominal" in text and "(x 0.700)" in text
    assert "PGA beta split over 2 model samples" in text and (tmp_path / "f.png").is_file()


def test_labels_without_compare_are_refused(tmp_path, capsys):
    path = csv_fixture(tmp_path / "ida.csv", SCALES)
    assert main(["fragility", str(path), "--labels", "a", "b"]) == 2
    assert "--labels names the two files of --compare" in capsys.readouterr().err
