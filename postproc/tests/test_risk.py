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
from voussoir_post.earthquake.risk import HazardCurve, collapse_risk, read_hazard
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
