"""The lognormal fragility fit and `voussoir-post fragility` on hand-written IDA files.

The fit is checked against the closed form (uncensored data), against known lognormal
populations sampled here (with and without censoring, within the sampling error that
the observed information gives), and the IDA readers on CSV and HDF5 fixtures written
by hand in this file (they are the fit's input, not simulated data).
"""

from __future__ import annotations

import json
import math

import h5py
import numpy as np
import pytest

from voussoir_post.cli.post import main
from voussoir_post.earthquake.fragility import (FitError, bootstrap_band, empirical_collapse_fraction,
                                                fit_lognormal, fragility, log_likelihood, max_likelihood)
from voussoir_post.earthquake.ida import read_ida
from voussoir_post.readers.results import ResultsError

G = 9.81


def standard_errors(ln_x, censored, mu, beta):
    """Standard errors of (mu, beta) from the observed information: the inverse of the
    negative Hessian of the log-likelihood at the fit (central differences)."""
    h = 1e-4

    def ll(p):
        return log_likelihood(p[0], p[1], ln_x, censored)

    p0 = np.array([mu, beta])
    hess = np.zeros((2, 2))
    for i in range(2):
        for j in range(2):
            e_i, e_j = np.eye(2)[i] * h, np.eye(2)[j] * h
            hess[i, j] = (ll(p0 + e_i + e_j) - ll(p0 + e_i - e_j) - ll(p0 - e_i + e_j) + ll(p0 - e_i - e_j)) / (4 * h * h)
    return np.sqrt(np.diag(np.linalg.inv(-hess)))


def test_uncensored_fit_is_the_closed_form():
    im = np.array([2.1, 3.7, 2.9, 5.2, 1.8, 4.4, 3.3])
    fit = fit_lognormal(im)
    assert fit.median == math.exp(np.mean(np.log(im)))
    assert fit.beta == np.std(np.log(im), ddof=0)
    assert fit.n == 7 and fit.n_censored == 0
    # The numerical maximiser used with censoring finds the same maximum.
    mu, beta, _ = max_likelihood(np.log(im), np.zeros(im.size, bool))
    assert math.exp(mu) == pytest.approx(fit.median, rel=1e-7)
    assert beta == pytest.approx(fit.beta, rel=1e-7)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_fit_recovers_a_known_lognormal(seed):
    median, beta, n = 3.5, 0.45, 400
    im = np.exp(np.random.default_rng(seed).normal(math.log(median), beta, n))
    fit = fit_lognormal(im)
    # Sampling error of the maximum-likelihood estimates of a normal sample.
    assert abs(math.log(fit.median) - math.log(median)) < 3.5 * beta / math.sqrt(n)
    assert abs(fit.beta - beta) < 3.5 * beta / math.sqrt(2 * n)


@pytest.mark.parametrize("seed", [4, 5, 6])
def test_fit_with_censoring_recovers_a_known_lognormal(seed):
    median, beta, n = 0.35 * G, 0.4, 400
    capacity = np.exp(np.random.default_rng(seed).normal(math.log(median), beta, n))
    # Records scaled only up to a bound: capacities above it are not seen (30 % of them).
    bound = median * math.exp(beta * 0.5244)  # the 70th percentile
    censored = capacity > bound
    im = np.where(censored, bound, capacity)
    assert 0.2 < censored.mean() < 0.4
    fit = fit_lognormal(im, censored)
    se_mu, se_beta = standard_errors(np.log(im), censored, math.log(fit.median), fit.beta)
    assert abs(math.log(fit.median) - math.log(median)) < 3.5 * se_mu
    assert abs(fit.beta - beta) < 3.5 * se_beta
    # Treating the lower bounds as collapses is biased beyond that error: the censoring
    # is what makes the fit right.
    naive = fit_lognormal(im)
    assert abs(naive.beta - beta) > 3.5 * se_beta


def test_bootstrap_band_holds_the_fit_and_narrows_as_one_over_root_n():
    population = np.exp(np.random.default_rng(7).normal(math.log(3.0), 0.4, 480))
    widths = {}
    for n in (120, 480):
        im = np.minimum(population[:n], 5.0)
        censored = population[:n] > 5.0
        fit = fit_lognormal(im, censored)
        grid = np.linspace(0.5, 8.0, 60)
        band = bootstrap_band(im, censored, grid, n_resamples=200)
        p = fragility(grid, fit.median, fit.beta)
        inside = (p > 0.02) & (p < 0.98)
        assert np.all(band.low[inside] <= p[inside]) and np.all(p[inside] <= band.high[inside])
        assert band.median_low < fit.median < band.median_high and band.n_resamples == 200
        widths[n] = math.log(band.median_high / band.median_low)
    # Four times the rows: half the width (the sampling error of a median), give or take.
    assert 1.5 < widths[120] / widths[480] < 2.7, widths


def test_kaplan_meier_fraction_by_hand():
    # 4 records: collapse at 1, censored at 2, collapses at 3 and 4. At 1: 1 - 3/4; the
    # censored record leaves the risk set; at 3: 1 - (3/4)(1/2); at 4: everyone.
    x, p = empirical_collapse_fraction([3.0, 2.0, 1.0, 4.0], [False, True, False, False])
    np.testing.assert_allclose(x, [1.0, 3.0, 4.0])
    np.testing.assert_allclose(p, [0.25, 0.625, 1.0])


def test_no_fit_without_two_collapses():
    with pytest.raises(FitError, match="at least two"):
        fit_lognormal([1.0, 2.0, 3.0], [True, True, False])


# ------------------------------------------------------------------ IDA files by hand

RECORDS = ["rec/ELC180.AT2", "rec/CLS000.AT2", "rec/PUL164.AT2"]
PGA = np.array([2.75, 6.33, 11.96])  # unscaled record PGA [m/s2]
PGV = np.array([0.31, 0.56, 1.14])


def csv_fixture(path, scales, censored=None):
    censored = np.zeros(scales.shape, bool) if censored is None else censored
    lines = ["# an IDA written by hand", "record,param_set,friction,scale_stood,scale_threshold,"
             "pga_threshold_m_s2,pgv_threshold_m_s,censored,non_monotonic,n_runs"]
    for s in range(scales.shape[0]):
        for r in range(scales.shape[1]):
            k = float(scales[s, r])
            lines.append(f"{RECORDS[r]},{s},{0.5 + 0.1 * s},{0.97 * k!r},{k!r},{k * float(PGA[r])!r},"
                         f"{k * float(PGV[r])!r},"
                         f"{int(censored[s, r])},0,7")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_cli_fits_the_csv_of_an_uncensored_ida(tmp_path, capsys):
    scales = np.array([[1.2, 0.61, 0.33], [1.5, 0.55, 0.29]])
    path = csv_fixture(tmp_path / "ida.csv", scales)
    assert main(["fragility", str(path), "--json", "--bootstrap", "50"]) == 0
    out = json.loads(capsys.readouterr().out)
    pga = (scales * PGA).reshape(-1)
    pgv = (scales * PGV).reshape(-1)
    assert out["median_pga_g"] == pytest.approx(math.exp(np.mean(np.log(pga))) / G, rel=1e-12)
    assert out["beta"] == pytest.approx(np.std(np.log(pga)), rel=1e-12)
    assert out["median_pgv_m_s"] == pytest.approx(math.exp(np.mean(np.log(pgv))), rel=1e-12)
    assert out["beta_pgv"] == pytest.approx(np.std(np.log(pgv)), rel=1e-12)
    assert out["n_rows"] == 6 and out["n_censored"] == 0
    assert (tmp_path / "ida_fragility.png").stat().st_size > 10000
    assert (tmp_path / "ida_fragility.csv").is_file() and (tmp_path / "ida_fragility_points.csv").is_file()


def test_failed_rows_are_left_out_and_said(tmp_path, capsys):
    """A search ended by a failed run is neither a collapse nor a censored row: the fit
    leaves it out (the same fit as without it) and the command says so."""
    scales = np.array([[1.2, 0.61, 0.33], [1.5, 0.55, 0.29]])
    path = csv_fixture(tmp_path / "ida.csv", scales)
    lines = path.read_text().splitlines()
    lines[1] += ",failed"
    lines[2:] = [line + ",0" for line in lines[2:]]
    lines.append(f"{RECORDS[0]},1,0.6,nan,nan,nan,nan,0,0,1,1")
    path.write_text("\n".join(lines) + "\n")
    ida = read_ida(str(path))
    assert ida.n_failed == 1 and ida.n_rows == 6 and "failed" not in ida.parameters
    assert main(["fragility", str(path), "--json", "--bootstrap", "20"]) == 0
    captured = capsys.readouterr()
    assert json.loads(captured.out)["n_rows"] == 6
    assert "1 rows left out" in captured.err


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
    expected = fit_lognormal(ida.pga_m_s2, ida.censored)
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


@pytest.mark.parametrize("edit, words", [
    (lambda t: t.replace(",censored,", ",flag,"), "line 2: the header lacks the column(s) censored"),
    (lambda t: t.replace(",0,0,7\n", ",2,0,7\n", 1), "line 3, column censored: '2' is not 0 or 1"),
    (lambda t: t.replace("rec/CLS000.AT2,0,0.5,", "rec/CLS000.AT2,0,0.5,x", 1), "line 4, column scale_stood"),
])
def test_bad_ida_csv_is_refused_with_line_and_column(tmp_path, capsys, edit, words):
    path = csv_fixture(tmp_path / "ida.csv", np.array([[1.2, 0.61, 0.33], [1.5, 0.55, 0.29]]))
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
