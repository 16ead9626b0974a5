"""Hazard readers (voussoir_post.earthquake.hazard) on small files written here in the
exact formats of the USGS hazard service (nshmp-haz-ws HazardService: response list,
metadata.imt.value, metadata.xvalues, data[component 'Total'].yvalues) and of OpenQuake's
hazard-curve CSV export (a comment line with kind, investigation_time and imt; columns
lon, lat, depth, poe-<level>).

The expected values are the curves the files were made from: the annual rates written
into the JSON, and for OpenQuake the rates a power law gives, turned into probabilities
of exceedance in T years here by the Poisson law PoE = 1 - exp(-lambda T), which the reader
must invert.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from voussoir_post.earthquake.hazard import normalise_measure, read_hazard, read_hazard_set
from voussoir_post.errors import InputError

LEVELS = [0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0]
#: OpenQuake's levels here: from 0.05 g, where the PoE in 50 years of these hazards is below 1
OQ = LEVELS[3:]


def _imt(value, display, ordinal):
    return {"id": ordinal, "value": value, "display": display, "displayorder": ordinal}


def usgs_json(path, curves, status="success"):
    """A file as the USGS hazard service writes it; `curves`: {imt: (xvalues, total yvalues)}."""
    response = []
    for k, (imt, (x, y)) in enumerate(curves.items()):
        display = "Peak Ground Acceleration" if imt == "PGA" else f"{imt} Second Spectral Acceleration"
        response.append({
            "metadata": {
                "edition": {"id": 1, "value": "E2014", "version": "v4.1.1",
                            "display": "Dynamic: Conterminous U.S. 2014", "displayorder": 0},
                "region": {"id": 0, "value": "WUS", "display": "Western US", "displayorder": 0},
                "latitude": 34.05, "longitude": -118.25,
                "imt": _imt(imt, display, k), "vs30": {"id": 4, "value": "760", "display": "760 m/s (B/C boundary)",
                                                       "displayorder": 4},
                "xlabel": "Ground Motion (g)", "ylabel": "Annual Frequency of Exceedence", "xvalues": list(x)},
            "data": [{"component": "Total", "yvalues": list(y)},
                     {"component": "Fault", "yvalues": [0.6 * v for v in y]},
                     {"component": "Grid", "yvalues": [0.4 * v for v in y]}]})
    url = "https://earthquake.usgs.gov/nshmp-haz-ws/hazard/E2014/WUS/-118.25/34.05/any/760"
    path.write_text(json.dumps({"status": status, "date": "2026-11-29T08:00:00-07:00", "url": url,
                                "server": {"threads": 1}, "response": response}, indent=2))
    return path


def openquake_csv(path, rates_by_site, years=50.0, kind="mean", imt="PGA", levels=OQ, old_comment=False):
    """A file as OpenQuake exports it: probabilities of exceedance in `years` of the given annual rates."""
    if old_comment:
        head = f"# source_model_tree_path=('b1',), gsim_tree_path=('b1',), investigation_time={years},imt=\"{imt}\"\n"
    else:
        head = (f"#,,,,,\"generated_by='OpenQuake engine 3.18.0', start_date='2026-11-29T08:00:00', "
                f"checksum=2107362341, kind='{kind}', investigation_time={years}, imt='{imt}'\"\n")
    rows = ["lon,lat,depth," + ",".join(f"poe-{x:.7f}" for x in levels)]
    for s, rates in enumerate(rates_by_site):
        poe = [-math.expm1(-r * years) for r in rates]
        rows.append(f"{10 + 0.1 * s:.5f},45.00000,-0.10000," + ",".join(f"{p:.6E}" for p in poe))
    path.write_text(head + "\n".join(rows) + "\n")
    return path


def power(k0, k, levels=LEVELS):
    return [k0 * x ** -k for x in levels]


def test_usgs_json_gives_the_total_curve_of_the_measure_asked(tmp_path):
    y_pga, y_sa = power(1e-4, 2.5), power(5e-5, 2.0)
    path = usgs_json(tmp_path / "usgs.json", {"PGA": (LEVELS, y_pga), "SA1P0": (LEVELS, y_sa)})
    pga = read_hazard(path)
    assert pga.measure == "PGA" and pga.kind == "mean"
    assert np.allclose(pga.pga_g, LEVELS) and np.allclose(pga.annual_rate, y_pga, rtol=1e-12)
    sa = read_hazard(path, measure="SA(1.0)")
    assert sa.measure == "SA(1)" and np.allclose(sa.annual_rate, y_sa, rtol=1e-12)
    with pytest.raises(InputError, match=r"Sa\(0.2 s\).*PGA, SA1P0"):
        read_hazard(path, measure="SA(0.2)")


def test_usgs_json_refuses_rising_negative_and_failed_answers(tmp_path):
    y = power(1e-4, 2.5)
    rising = list(y)
    rising[4] = rising[3] * 1.5
    with pytest.raises(InputError, match="rises with the intensity"):
        read_hazard(usgs_json(tmp_path / "a.json", {"PGA": (LEVELS, rising)}))
    negative = list(y)
    negative[-1] = -1e-9
    with pytest.raises(InputError, match="negative"):
        read_hazard(usgs_json(tmp_path / "b.json", {"PGA": (LEVELS, negative)}))
    with pytest.raises(InputError, match="status 'error'"):
        read_hazard(usgs_json(tmp_path / "c.json", {"PGA": (LEVELS, y)}, status="error"))
    zero_top = list(y)
    zero_top[-2:] = [0.0, 0.0]
    curve = read_hazard(usgs_json(tmp_path / "d.json", {"PGA": (LEVELS, zero_top)}))
    assert curve.pga_g.size == len(LEVELS) - 2 and any("2 point(s) of zero" in n for n in curve.notes)


def test_openquake_probabilities_in_t_years_become_annual_rates(tmp_path):
    rates = power(2e-5, 2.2, OQ)
    curve = read_hazard(openquake_csv(tmp_path / "hazard_curve-mean-PGA_7.csv", [rates], years=50.0))
    assert curve.kind == "mean" and curve.fractile is None
    assert np.allclose(curve.annual_rate, rates, rtol=1e-5)  # the CSV keeps 7 significant digits
    # The same hazard written for another investigation time reads the same.
    again = read_hazard(openquake_csv(tmp_path / "hazard_curve-mean-PGA_8.csv", [rates], years=1.0))
    assert np.allclose(again.annual_rate, rates, rtol=1e-5)


def test_openquake_quantiles_the_older_comment_and_several_sites(tmp_path):
    q16 = openquake_csv(tmp_path / "quantile_curve-0.16-PGA_7.csv", [power(1e-5, 2.2, OQ)], kind="quantile-0.16")
    old = openquake_csv(tmp_path / "quantile_curve-0.84-PGA_7.csv", [power(4e-5, 2.2, OQ)], old_comment=True)
    mean = openquake_csv(tmp_path / "hazard_curve-mean-PGA_7.csv", [power(2e-5, 2.2, OQ)])
    hs = read_hazard_set([mean, q16, old])
    assert sorted(hs.fractiles) == [0.16, 0.84]
    assert np.allclose(hs.fractiles[0.84].annual_rate, power(4e-5, 2.2, OQ), rtol=1e-5)
    two = openquake_csv(tmp_path / "hazard_curve-mean-PGA_9.csv", [power(2e-5, 2.2, OQ), power(3e-5, 2.2, OQ)])
    with pytest.raises(InputError, match="2 sites; choose one with --site"):
        read_hazard(two)
    assert np.allclose(read_hazard(two, site=1).annual_rate, power(3e-5, 2.2, OQ), rtol=1e-5)
    with pytest.raises(InputError, match="one mean hazard curve is needed"):
        read_hazard_set([q16, old])
    with pytest.raises(InputError, match="0.16 fractile given twice"):
        read_hazard_set([mean, q16, q16])


def test_openquake_refuses_another_measure_rising_curves_and_probabilities_above_one(tmp_path):
    sa = openquake_csv(tmp_path / "hazard_curve-mean-SA(1.0)_7.csv", [power(2e-5, 2.2, OQ)], imt="SA(1.0)")
    with pytest.raises(InputError, match=r"hazard is for SA\(1.0\), but the fragility is in PGA"):
        read_hazard(sa)
    assert read_hazard(sa, measure="SA(1)").measure == "SA(1)"
    path = openquake_csv(tmp_path / "hazard_curve-mean-PGA_7.csv", [power(2e-5, 2.2, OQ)])
    text = path.read_text().splitlines()
    cells = text[2].split(",")
    cells[6], cells[7] = cells[7], cells[6]  # two probabilities swapped: the curve rises
    path.write_text("\n".join(text[:2] + [",".join(cells)]) + "\n")
    with pytest.raises(InputError, match="rises with the intensity"):
        read_hazard(path)
    cells[6] = "1.2E+00"
    path.write_text("\n".join(text[:2] + [",".join(cells)]) + "\n")
    with pytest.raises(InputError, match=r"outside \[0, 1\]"):
        read_hazard(path)


def test_openquake_probabilities_of_one_and_zero_are_dropped_and_said(tmp_path):
    path = openquake_csv(tmp_path / "hazard_curve-mean-PGA_7.csv", [power(2e-5, 2.2, OQ)], years=50.0)
    lines = path.read_text().splitlines()
    cells = lines[2].split(",")
    cells[3] = "1.000000E+00"
    cells[-1] = "0.000000E+00"
    path.write_text("\n".join(lines[:2] + [",".join(cells)]) + "\n")
    curve = read_hazard(path)
    assert np.allclose(curve.pga_g, OQ[1:-1])
    assert any("PoE 1 at the bottom dropped" in n for n in curve.notes)
    assert any("zero annual rate at the top dropped" in n for n in curve.notes)


def test_plain_csv_with_fractile_columns_and_measure_names(tmp_path):
    rows = "\n".join(f"{x},{a},{b},{c}" for x, a, b, c in zip(LEVELS, power(2e-4, 2), power(1e-4, 2), power(4e-4, 2)))
    path = tmp_path / "site.csv"
    path.write_text("pga_g,annual_rate,annual_rate_q0.16,annual_rate_q0.84\n" + rows + "\n")
    hs = read_hazard_set(path)
    assert sorted(hs.fractiles) == [0.16, 0.84] and np.allclose(hs.mean.annual_rate, power(2e-4, 2))
    with pytest.raises(InputError, match="gives PGA"):
        read_hazard(path, measure="SA(1.0)")
    assert normalise_measure("SA0P2") == normalise_measure("Sa(0.20)") == "SA(0.2)"
    with pytest.raises(InputError, match="not an intensity measure"):
        normalise_measure("CAV")
