"""Collapse risk at a site (voussoir-post risk) against closed forms.

For a power-law hazard lambda(im) = k0 im^-k and a lognormal fragility (median m, beta),
the mean annual frequency of collapse is k0 m^-k exp(k^2 beta^2 / 2) (Cornell et al.
2002), and the density of that rate over ln im is a normal of mean ln m - k beta^2: its
mode lies at m exp(-k beta^2). Both are derived by hand, apart from the code.
"""

from __future__ import annotations

import argparse
import json
import math

import numpy as np
import pytest
from scipy.stats import norm

from voussoir_post.cli.post import main
from voussoir_post.cli.risk import cmd_risk
from voussoir_post.earthquake.risk import (FragilityDraws, HazardCurve, collapse_risk, model_form, power_law_rate,
                                          read_hazard, read_hazard_set, risk_band)
from voussoir_post.errors import InputError


def _power_law_file(path, k0=1e-4, k=2.5, lo=0.01, hi=5.0, n=30):
    rows = [f"{a:.9g},{k0 * a ** -k:.9g}" for a in np.geomspace(lo, hi, n)]
    path.write_text("# a power-law hazard\npga_g,annual_rate\n" + "\n".join(rows) + "\n")
    return path


@pytest.mark.parametrize("k0,k,m,beta", [(1e-4, 2.5, 0.3, 0.283), (5e-5, 3.2, 0.52, 0.15), (2e-3, 1.8, 0.2, 0.45)])
def test_the_rate_of_collapse_is_the_closed_form_of_a_power_law_hazard(tmp_path, k0, k, m, beta):
    hazard = read_hazard(_power_law_file(tmp_path / "h.csv", k0, k))
    r = collapse_risk(hazard, m, beta, mce_g=0.5)
    exact = k0 * m ** (-k) * math.exp(0.5 * (k * beta) ** 2)
    assert abs(r.annual_rate / exact - 1) < 1e-3
    assert abs(r.p_50yr - (1 - math.exp(-50 * exact))) < 1e-3 * r.p_50yr
    assert abs(r.margin_ratio - m / 0.5) < 1e-12
    mode = float(r.pga_g[np.argmax(r.density * r.pga_g)])
    assert abs(math.log(mode) - (math.log(m) - k * beta * beta)) < 0.01


def test_a_hazard_file_must_decrease_and_name_its_columns(tmp_path):
    (tmp_path / "a.csv").write_text("pga_g,annual_rate\n0.1,0.01\n0.2,0.02\n")
    with pytest.raises(InputError, match="rises with the intensity"):
        read_hazard(tmp_path / "a.csv")
    (tmp_path / "b.csv").write_text("pga,rate\n0.1,0.01\n0.2,0.001\n")
    with pytest.raises(InputError, match="missing column 'pga_g'"):
        read_hazard(tmp_path / "b.csv")
    (tmp_path / "c.csv").write_text("pga_g,annual_rate\n0.1,-1\n0.2,0.001\n")
    with pytest.raises(InputError, match=r"c.csv:2: .*positive"):
        read_hazard(tmp_path / "c.csv")


def test_beyond_the_files_range_the_end_power_laws_are_extended_and_counted():
    hazard = HazardCurve(np.array([0.1, 0.2]), np.array([1e-2, 1e-2 * 2 ** -3]))
    r = collapse_risk(hazard, 0.3, 0.3)
    assert abs(r.annual_rate / (1e-2 * (0.3 / 0.1) ** -3 * math.exp(0.5 * (3 * 0.3) ** 2)) - 1) < 1e-3
    # The rate's density over ln PGA is a normal of mean ln 0.3 - 3 (0.3)^2 and sd 0.3: the
    # share outside [0.1, 0.2] g in closed form.
    mu = math.log(0.3) - 3 * 0.3 ** 2
    outside = norm.cdf((math.log(0.1) - mu) / 0.3) + norm.sf((math.log(0.2) - mu) / 0.3)
    assert abs(r.beyond_fraction - outside) < 1e-3


def test_the_command_prints_writes_json_and_a_pdf(tmp_path, capsys):
    path = _power_law_file(tmp_path / "site.csv")
    frag = tmp_path / "frag.json"
    frag.write_text(json.dumps({"median_pga_g": 0.3, "beta_pga": 0.283}))
    assert main(["risk", str(path), "--fragility-json", str(frag), "--json", "--out", str(tmp_path / "r.pdf")]) == 0
    out = json.loads(capsys.readouterr().out)
    assert abs(out["annual_rate_of_collapse"] / (1e-4 * 0.3 ** -2.5 * math.exp(0.5 * (2.5 * 0.283) ** 2)) - 1) < 1e-3
    assert (tmp_path / "r.pdf").read_bytes()[:4] == b"%PDF"
    with pytest.raises(InputError, match="--median-g and --beta"):
        cmd_risk(argparse.Namespace(hazard=str(path), fragility_json=None, median_g=0.3, beta=None, years=50.0,
                                    mce_g=None, json=False, out=None, format=None))


# ------------------------------------------------------------------ bands, model-form betas

def _power_set(tmp_path, k0s: dict, k=2.5):
    """A plain hazard CSV with the mean (k0s['mean']) and fractile columns, all k0 x^-k."""
    xs = np.geomspace(0.01, 5.0, 40)
    names = [n for n in k0s if n != "mean"]
    header = "pga_g,annual_rate" + "".join(f",annual_rate_q{q:g}" for q in names)
    rows = [f"{x:.9g},{k0s['mean'] * x ** -k:.9g}" + "".join(f",{k0s[q] * x ** -k:.9g}" for q in names) for x in xs]
    path = tmp_path / "site.csv"
    path.write_text(header + "\n" + "\n".join(rows) + "\n")
    return path


def test_the_band_on_fractile_hazards_is_the_closed_form_at_each_fractiles_k0(tmp_path):
    """Fractile hazards of one slope k: lambda_c on each is k0_q m^-k exp(k^2 beta^2 / 2)."""
    k, m, beta = 2.5, 0.3, 0.3
    k0 = {"mean": 1.2e-4, 0.16: 0.6e-4, 0.5: 1.0e-4, 0.84: 1.8e-4}
    band = risk_band(read_hazard_set(_power_set(tmp_path, k0, k)), m, beta)
    for q in (0.16, 0.5, 0.84):
        assert band.hazard_fractiles[q] == pytest.approx(power_law_rate(k0[q], k, m, beta), rel=1e-2)
    assert band.point.annual_rate == pytest.approx(power_law_rate(k0["mean"], k, m, beta), rel=1e-2)
    # beta_H from the 0.16 / 0.84 pair: ln(1.8 / 0.6) / (2 z_0.84)
    assert band.beta_hazard == pytest.approx(math.log(1.8 / 0.6) / (2 * norm.ppf(0.84)), rel=1e-3)


def test_the_combined_band_of_lognormal_hazard_and_medians_is_lognormal(tmp_path):
    """Hazard fractiles lognormal about k0_50 with dispersion bH; fragility draws of one beta
    and medians m exp(s z_j), z_j the normal's quantiles: on a power law lambda_c = C m^-k,
    so ln lambda_c is normal with sd sqrt(bH^2 + k^2 s^2) about ln lambda_c(k0_50, m)."""
    k, m, beta, b_h, s = 2.0, 0.3, 0.3, 0.5, 0.15
    z84 = norm.ppf(0.84)
    k0 = {"mean": 1e-4, 0.16: 1e-4 * math.exp(-b_h * z84), 0.5: 1e-4, 0.84: 1e-4 * math.exp(b_h * z84)}
    n = 400
    z = norm.ppf((np.arange(n) + 0.5) / n)
    draws = [FragilityDraws("bootstrap", m * np.exp(s * z), np.full(n, beta))]
    band = risk_band(read_hazard_set(_power_set(tmp_path, k0, k)), m, beta, draws)
    centre = power_law_rate(1e-4, k, m, beta)
    sd = math.hypot(b_h, k * s)
    for q in (0.05, 0.16, 0.5, 0.84, 0.95):
        assert band.combined[q] == pytest.approx(centre * math.exp(norm.ppf(q) * sd), rel=1e-2)
    # the fragility-only band: the draws' quantiles, lambda_c falling as the median rises
    frag = band.fragility["bootstrap"]["quantiles"]
    assert frag[0.16] == pytest.approx(centre * math.exp(-k * s * norm.ppf(0.84)), rel=1e-2)


def test_model_samples_mixture_is_the_mean_of_the_samples_rates(tmp_path):
    """The mixture fragility (the mean of the samples' curves) integrates to the mean of the
    samples' closed forms; the margin ratio's band is the medians over the MCE."""
    k, k0 = 2.2, 1e-4
    medians, betas = np.array([0.197, 0.33, 0.35, 0.37]), np.array([0.25, 0.3, 0.28, 0.22])
    band = risk_band(read_hazard_set(_power_set(tmp_path, {"mean": k0}, k)), 0.3, 0.3,
                     [FragilityDraws("model samples", medians, betas)], mce_g=0.5)
    expected = np.mean([power_law_rate(k0, k, mm, bb) for mm, bb in zip(medians, betas)])
    assert band.fragility["model samples"]["mean"] == pytest.approx(expected, rel=1e-2)
    assert band.fragility["model samples"]["margin_quantiles"][0.5] == pytest.approx(np.median(medians) / 0.5)
    assert band.combined == {}  # no hazard fractiles: no combined band


def test_p695_ratings_add_to_beta_by_srss(tmp_path):
    """FEMA P695 quality ratings (superior 0.10, good 0.20, fair 0.35, poor 0.50; Section 7.3.1's
    SRSS): good design requirements, good test data, a fair model on beta 0.3 give
    sqrt(0.3^2 + 0.2^2 + 0.2^2 + 0.35^2), and the rate is the closed form at that beta."""
    k, k0, m, beta = 2.5, 1e-4, 0.3, 0.3
    form = model_form("good", "Good", "fair")
    total = math.sqrt(0.3 ** 2 + 0.2 ** 2 + 0.2 ** 2 + 0.35 ** 2)
    assert form.total(beta) == pytest.approx(total, rel=1e-12)
    band = risk_band(read_hazard_set(_power_set(tmp_path, {"mean": k0}, k)), m, beta, form=form)
    assert band.point.annual_rate == pytest.approx(power_law_rate(k0, k, m, total), rel=1e-2)
    assert band.point_without_model_form.annual_rate == pytest.approx(power_law_rate(k0, k, m, beta), rel=1e-2)
    assert model_form().beta == 0.0 and not model_form().rated
    with pytest.raises(InputError, match="superior, good, fair, poor"):
        model_form("excellent")


def test_the_command_with_openquake_files_bootstrap_and_ratings(tmp_path, capsys):
    """OpenQuake mean and 16/84 % files of one slope, a fragility JSON with bootstrap draws and
    model samples, P695 ratings: the JSON's rates on the fractiles are the closed forms at
    each fractile's k0 with the raised beta."""
    from test_hazard import OQ, openquake_csv
    k, m, beta = 2.2, 0.3, 0.28
    k0 = {"mean": 2e-5, 0.16: 1e-5, 0.84: 3.5e-5}
    files = [openquake_csv(tmp_path / "hazard_curve-mean-PGA_5.csv", [[k0["mean"] * x ** -k for x in OQ]])]
    for q in (0.16, 0.84):
        files.append(openquake_csv(tmp_path / f"quantile_curve-{q}-PGA_5.csv", [[k0[q] * x ** -k for x in OQ]],
                                   kind=f"quantile-{q}"))
    frag = tmp_path / "frag.json"
    rng = np.random.default_rng(1)
    frag.write_text(json.dumps({"median_pga_g": m, "beta_pga": beta,
                                "bootstrap_median_pga_g": list(m * np.exp(0.05 * rng.standard_normal(60))),
                                "bootstrap_beta_pga": list(beta + 0.02 * rng.standard_normal(60)),
                                "median_pga_g_by_sample": [0.28, 0.32], "beta_pga_by_sample": [0.25, 0.27]}))
    args = ["risk", *map(str, files), "--fragility-json", str(frag), "--rating-dr", "good", "--rating-td", "good",
            "--rating-mdl", "fair", "--mce-g", "0.4", "--out", str(tmp_path / "r.png")]
    assert main(args + ["--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    total = math.sqrt(beta ** 2 + 0.2 ** 2 + 0.2 ** 2 + 0.35 ** 2)
    assert out["beta_total"] == pytest.approx(total, rel=1e-12)
    for q in ("0.16", "0.84"):
        assert out["annual_rate_on_hazard_fractiles"][q] == pytest.approx(
            power_law_rate(k0[float(q)], k, m, total), rel=1e-2)
    assert out["annual_rate_of_collapse"] == pytest.approx(power_law_rate(k0["mean"], k, m, total), rel=1e-2)
    assert set(out["fragility_bands"]) == {"bootstrap", "model samples"}
    assert out["combined_band_with"] == "bootstrap" and "0.5" in out["annual_rate_combined_quantiles"]
    assert out["model_form"]["beta_mdl"] == 0.35 and "7.3.1" in out["model_form"]["source"]
    assert out["collapse_margin_ratio"] == pytest.approx(m / 0.4)
    assert (tmp_path / "r.png").read_bytes()[:4] == b"\x89PNG"
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "combined (hazard fractiles x bootstrap)" in text and "model-form: design requirements good (0.20)" in text


def test_the_command_refuses_a_pga_fit_on_another_measure_and_a_bad_rating(tmp_path, capsys):
    """--fragility-json is a PGA fit: with --measure SA(1.0) it is refused before anything is
    read or drawn; a rating outside P695's four is refused by the parser."""
    path = _power_law_file(tmp_path / "site.csv")
    frag = tmp_path / "frag.json"
    frag.write_text(json.dumps({"median_pga_g": 0.3, "beta_pga": 0.283}))
    assert main(["risk", str(path), "--fragility-json", str(frag), "--measure", "SA(1.0)"]) == 2
    assert "gives the PGA fit" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["risk", str(path), "--median-g", "0.3", "--beta", "0.3", "--rating-mdl", "excellent"])
    assert not list(tmp_path.glob("*.png"))
