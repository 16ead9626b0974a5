"""A pulse one way and the other (diagnosis/pulses.py; next_test.py, kind pulse_pair): the
pulse against its definition, the reading of record tests against hand-made campaigns,
the ratio's term against numerical integration, the kernel's two ways against mirror
symmetry, and the evidence against another code's thresholds (LMGC90, stored by
bench/lmgc90/pulse.py)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.stats import norm

from conftest import bin_dir
from lmgc90_campaigns import truth_variant
from voussoir_post.diagnosis import pulses
from voussoir_post.diagnosis.effects import Variant
from voussoir_post.diagnosis.next_test import pulse_ramp
from voussoir_post.diagnosis.pulses import (OUTLIER_FACTOR, OUTLIER_PROB, RATIO_SCALE, PulsePair, PulseRamp,
                                            log_ratio_terms, read_pulse_pairs, table_demand, unit_pulse)
from voussoir_post.diagnosis.observations import from_campaign
from voussoir_post.diagnosis.settings import DiagnosisSettings
from voussoir_post.readers.campaign import read_campaign
from voussoir_post.readers.campaign import Specimen

STORED = Path(__file__).parent / "data" / "lmgc90" / "pulse_thresholds.json"
TRUTHS = Path(__file__).parent / "data" / "lmgc90"
W156 = Specimen("W156", 156.0, 13, 0.508, 0.071, 0.145, 700.0, 0.5)


# ---------------------------------------------------------------- the pulse


def test_the_unit_pulse_is_its_two_half_sines_integrated():
    """Travel 1 m from -0.5 to +0.5, the table at rest at both ends, and the displacement
    the double integral (trapezoids, by hand) of the acceleration its definition gives."""
    t, x, acc = unit_pulse()
    tp, td, _ = pulses.PULSE_S
    # The definition, scaled to unit travel by the closed form: travel per m/s2 of peak.
    travel = tp * tp / math.pi + 2 * tp / math.pi * td - (tp / td) * td * td / math.pi
    a = np.where(t < tp, np.sin(np.pi * t / tp), np.where(t < tp + td, -(tp / td) * np.sin(np.pi * (t - tp) / td), 0.0))
    assert np.allclose(acc, a / travel, atol=1e-12)
    dt = t[1] - t[0]
    v = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * dt)])
    d = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * dt)])
    # Trapezoids err by about (dt w)^2 / 12 = 4e-5 of the peak at dt = 1 ms, w = pi / 0.15 s.
    assert abs(v[-1]) < 1e-4 * v.max()
    assert np.allclose(x, d / travel - 0.5, atol=2e-4)
    assert x[0] == pytest.approx(-0.5) and x[-1] == pytest.approx(0.5)
    half, vmax, amax = table_demand(t, x)
    assert half == pytest.approx(0.5, rel=1e-9)
    assert vmax == pytest.approx(v.max() / travel, rel=0.01)
    assert amax == pytest.approx(1.0 / travel, rel=0.02)


def test_a_pulse_ramp_stays_within_the_tables_limits():
    """Unit demand (half travel 0.5 m, 2.67 m/s, 27.9 m/s2 a metre of travel): the default
    table (0.15 m, 1 m/s, 20 m/s2) reaches 0.30 m of travel, by its stroke."""
    table = SimpleNamespace(stroke_m=0.15, max_velocity_m_s=1.0, max_accel_m_s2=20.0)
    amps = pulse_ramp([0.25, 0.27], table)
    assert amps[0] == pytest.approx(0.2, abs=5e-4)
    assert amps[1] <= 0.30 and amps[1] == pytest.approx(0.2995, abs=1e-9)
    assert amps[2] == pytest.approx(0.005, abs=5e-4)
    # A specimen whose thresholds lie beyond the stroke gets no pulse advice.
    assert pulse_ramp([0.28, 0.31], table) is None
    assert pulse_ramp([0.1, 0.12], table)[1] == pytest.approx(0.15, abs=5e-4)


# ---------------------------------------------------------------- reading a campaign


def _campaign(folder: Path, rows, specimens=("W156",)) -> Path:
    """A campaign folder: one afd pair a specimen, then record tests (test id, specimen,
    record (t, x), collapsed)."""
    (folder / "records").mkdir(parents=True)
    (folder / "specimens.csv").write_text(
        "specimen_id,embrace_deg,n_voussoirs,r_ext_m,thickness_m,width_m,density_kg_m3,friction\n"
        + "".join(f"{s},156,13,0.508,0.071,0.145,700,0.5\n" for s in specimens))
    lines = ["test_id,specimen_id,waveform,frequency_hz,amplitude_m,outcome"]
    for s in specimens:
        lines += [f"{s}_a1,{s},afd,1.25,0.050,stand", f"{s}_a2,{s},afd,1.25,0.055,collapse"]
    for tid, sid, (t, x), fell in rows:
        lines.append(f"{tid},{sid},record,,,{'collapse' if fell else 'stand'}")
        (folder / "records" / f"{tid}.csv").write_text(
            "t_s,table_x_m\n" + "".join(f"{a:.4f},{b:.8e}\n" for a, b in zip(t, x)))
    (folder / "tests.csv").write_text("\n".join(lines) + "\n")
    return folder


def test_record_tests_of_one_shape_both_ways_are_a_pulse_pair(tmp_path):
    """Records of the unit pulse at hand-chosen travels, its own way and reversed, with a
    start offset and a little noise: each way's bracket is the largest stand below the
    smallest collapse, in metres of travel; another shape and a one-way group are not
    read."""
    t, x, _ = unit_pulse()
    t, x = t[::5], x[::5]  # a 200 Hz record
    rng = np.random.default_rng(3)
    noisy = lambda travel, sign: 0.02 + sign * travel * x + 2e-5 * rng.standard_normal(x.size)
    rows = [(f"p{k}", "W156", (t, noisy(a, 1)), fell) for k, (a, fell) in
            enumerate([(0.20, False), (0.22, False), (0.24, True)])]
    rows += [(f"m{k}", "W156", (t, noisy(a, -1)), fell) for k, (a, fell) in
             enumerate([(0.18, False), (0.20, True), (0.21, True)])]
    sine = (t, 0.01 * np.sin(2 * np.pi * 2.0 * t))
    rows += [("sine", "W156", sine, False), ("lone", "W132", (t, noisy(0.3, 1)), True)]
    campaign = read_campaign(_campaign(tmp_path / "c", rows, ("W156", "W132")))
    pairs = read_pulse_pairs(campaign)
    unread = from_campaign(campaign)[0].unread
    assert len(pairs) == 1
    pp = pairs[0]
    assert pp.specimen_id == "W156" and pp.usable
    assert (pp.ramps[1].low, pp.ramps[1].high) == pytest.approx((0.22, 0.24), rel=2e-3)
    assert (pp.ramps[-1].low, pp.ramps[-1].high) == pytest.approx((0.18, 0.20), rel=2e-3)
    assert set(pp.ramps[1].test_ids) == {"p0", "p1", "p2"} and set(pp.ramps[-1].test_ids) == {"m0", "m1", "m2"}
    assert set(unread) == {"sine", "lone"}
    # The shape is the pulse's, to unit travel about its centre.
    assert np.max(np.abs(pp.shape - x)) < 2e-3


# ---------------------------------------------------------------- the ratio's term


def _term_by_quadrature(pair: PulsePair, rho: float) -> float:
    """The term of pulses.py's docstring by brute force: the level uniform over the closed
    bracket (own way), the other way's log threshold level + rho + e, e normal or (with
    OUTLIER_PROB) uniform within log(OUTLIER_FACTOR); P(in the other way's bracket)."""
    own, other = pair.ramps[1], pair.ramps[-1]
    a = np.linspace(math.log(own.low), math.log(own.high), 4001)
    lo = math.log(other.low) if other.low > 0 else -np.inf
    hi = math.log(other.high) if math.isfinite(other.high) else np.inf
    normal = norm.cdf((hi - a - rho) / RATIO_SCALE) - norm.cdf((lo - a - rho) / RATIO_SCALE)
    h = math.log(OUTLIER_FACTOR)
    uniform = np.clip(np.minimum(hi, a + rho + h) - np.maximum(lo, a + rho - h), 0, None) / (2 * h)
    return float(np.mean((1 - OUTLIER_PROB) * normal + OUTLIER_PROB * uniform))


@pytest.mark.parametrize("other", [(0.25, 0.26), (0.0, 0.26), (0.25, math.inf)])
def test_the_ratio_term_is_the_brackets_probability_by_quadrature(other):
    pair = PulsePair("W156", np.zeros(2), np.zeros(2), {1: PulseRamp(1, 0.29, 0.30), -1: PulseRamp(-1, *other)})
    rho = np.array([-0.4, -0.2, -0.15, -0.1, -0.03, 0.0, 0.05, 0.2])
    got = np.exp(log_ratio_terms(pair, rho))
    want = [_term_by_quadrature(pair, r) for r in rho]
    assert got == pytest.approx(want, rel=2e-3, abs=1e-7)


def test_the_ratio_term_conditions_on_the_way_that_is_closed():
    """Only the other way closed: the term is the same as with the ways' roles exchanged
    and the ratio's sign turned."""
    a = PulsePair("W156", np.zeros(2), np.zeros(2), {1: PulseRamp(1, 0.0, 0.30), -1: PulseRamp(-1, 0.25, 0.26)})
    b = PulsePair("W156", np.zeros(2), np.zeros(2), {1: PulseRamp(1, 0.25, 0.26), -1: PulseRamp(-1, 0.0, 0.30)})
    rho = np.linspace(-0.3, 0.3, 13)
    assert log_ratio_terms(a, rho) == pytest.approx(log_ratio_terms(b, -rho), rel=1e-12)


# ---------------------------------------------------------------- the kernel, both ways


@pytest.fixture(scope="module")
def kernel_ratios(tmp_path_factory):
    """The kernel's thresholds of the unit pulse both ways (IDA sweep), W156: the nominal
    arch, brackets with 0.5 mm of play on either side, and the stored LMGC90 truths' own
    models."""
    stored = json.loads(STORED.read_text())["truths"]
    variants = {"nominal": Variant(), "left": Variant("base_restraint", "left@0.0005"),
                "right": Variant("base_restraint", "right@0.0005")}
    for slug in stored:
        variants[slug] = truth_variant(json.loads((TRUTHS / f"{slug}.json").read_text()))
    work = tmp_path_factory.mktemp("pulse")
    t, x, _ = unit_pulse()
    pair = PulsePair("W156", t, x)
    settings = DiagnosisSettings(bin_dir=bin_dir(), n_ranks=2, log=lambda m: None)
    got = pulses.pulse_thresholds(W156, pair, list(dict.fromkeys(variants.values())), settings, work / "cache",
                                  work / "run")
    from voussoir_post.diagnosis.bank import variant_key
    return {name: got[variant_key(v)] for name, v in variants.items()}, stored


def test_the_kernel_falls_alike_both_ways_where_the_arch_is_its_own_mirror_image(kernel_ratios):
    """Mirror symmetry, independent of the kernel: the nominal arch falls at the same
    pulse each way, and brackets on the left under the pulse one way are brackets on the
    right under the other (to the IDA's 1 % tolerance)."""
    k, _ = kernel_ratios
    plus, minus = k["nominal"]
    assert minus == pytest.approx(plus, rel=0.011)
    assert k["left"][0] == pytest.approx(k["right"][1], rel=0.011)
    assert k["left"][1] == pytest.approx(k["right"][0], rel=0.011)
    # And brackets on one side do make the two ways differ (else the test parts nothing).
    assert abs(math.log(k["left"][1] / k["left"][0])) > 5 * RATIO_SCALE


def test_lmgc90s_pulses_favour_each_truths_own_side(kernel_ratios):
    """Another code's thresholds (LMGC90, nine stored truths): under the ratio's term, each
    truth's own model (its brackets' side, its other effect) is favoured over the
    mirror-symmetric arch when it has brackets on one side and over brackets on either
    side when it has none, by at least a factor 10, and against its own model the term
    is never below e^-3 of its best value."""
    k, stored = kernel_ratios
    rho = {name: math.log(m / p) for name, (p, m) in k.items()}
    for slug, row in stored.items():
        pair = PulsePair("W156", np.zeros(2), np.zeros(2),
                         {1: PulseRamp(1, row["lmgc90_plus_m_s2"] / 1.01, row["lmgc90_plus_m_s2"]),
                          -1: PulseRamp(-1, row["lmgc90_minus_m_s2"] / 1.01, row["lmgc90_minus_m_s2"])})
        own, symmetric = (log_ratio_terms(pair, np.array([rho[slug], 0.0])))
        best = float(np.max(log_ratio_terms(pair, np.linspace(-0.5, 0.5, 1001))))
        assert own > best - 3.0, slug
        if "base_restraint" in slug:
            assert own > symmetric + math.log(10.0), slug
        else:
            sides = log_ratio_terms(pair, np.array([rho["left"], rho["right"]]))
            assert own > float(np.max(sides)) + math.log(10.0), slug


# ---------------------------------------------------------------- the advice


def _advice(monkeypatch, tmp_path, ratios: dict, rivals=("none", "base_restraint"), stroke_m=0.15):
    """next_test's pulse candidates for two rivals of equal probability on W156: `none`,
    and brackets left or right (equal weights), with the kernel replaced by hand-given
    thresholds both ways [m of travel] per variant key."""
    from voussoir_post.diagnosis import next_test
    from voussoir_post.diagnosis.observations import PairObservation
    grids = {"none": SimpleNamespace(names=(), values=[], n=1),
             "friction": SimpleNamespace(names=("friction",), values=[np.array([0.4, 0.6])], n=2),
             "base_restraint": SimpleNamespace(names=("base_restraint",), n=2,
                                               values=[np.array(["left@0.0005", "right@0.0005"], dtype=object)])}
    models = {m: SimpleNamespace(grid=grids[m], weights=np.full(grids[m].n, 1.0 / grids[m].n)) for m in rivals}
    post = SimpleNamespace(models=models, bank=SimpleNamespace(specimens={"W156": SimpleNamespace(
        thresholds={k: [0.05] for k in ratios})}))
    obs = SimpleNamespace(pairs=[PairObservation("W156", 1.25, 0.05, 0.055)], specimens={"W156": W156},
                          pulse_pairs=[])
    asked = []

    def kernel(spec, pair, variants, settings, cache, work):
        from voussoir_post.diagnosis.bank import variant_key
        asked.extend(variant_key(v) for v in variants)
        return {variant_key(v): ratios[variant_key(v)] for v in variants}

    monkeypatch.setattr(next_test, "pulse_thresholds", kernel)
    table = SimpleNamespace(stroke_m=stroke_m, max_velocity_m_s=1.0, max_accel_m_s2=20.0)
    return next_test._pulse_candidates(post, obs, list(rivals), [0.5, 0.5], None, tmp_path, table), asked


def test_a_pulse_pair_is_advised_by_what_the_rivals_predict_for_its_ratio(monkeypatch, tmp_path):
    """Brackets that move the ratio by 15 % (5 of the law's spreads) against a symmetric
    arch: the outcome nearly tells them apart, so the gain is close to the rivals' whole
    entropy, 1 bit; brackets that move it by 1 % are hardly told apart (a fraction of the
    law's spread); and with no rival with brackets nothing is simulated or advised."""
    base = {"nominal": (0.25, 0.25)}
    strong = base | {"base_restraint=left@0.0005": (0.27, 0.27 * 0.85),
                     "base_restraint=right@0.0005": (0.24, 0.24 * 1.15)}
    weak = base | {"base_restraint=left@0.0005": (0.25, 0.25 * 0.99),
                   "base_restraint=right@0.0005": (0.25, 0.25 * 1.01)}
    (c,), _ = _advice(monkeypatch, tmp_path, strong)
    assert c["kind"] == "pulse_pair" and c["specimen_id"] == "W156"
    assert 0.85 < c["expected_gain_bits"] <= 1.0
    assert c["predicted_ratio"]["none"] == pytest.approx(1.0)
    assert c["predicted_ratio"]["base_restraint"] == pytest.approx(math.sqrt(0.85 * 1.15), rel=1e-9)
    # Within the table: from 0.8 x the least threshold to 1.25 x the largest, cut at the stroke.
    assert c["amplitudes_m"][0] == pytest.approx(0.8 * 0.27 * 0.85, abs=5e-4) and c["amplitudes_m"][1] <= 0.30
    (w,), _ = _advice(monkeypatch, tmp_path, weak)
    assert w["expected_gain_bits"] < 0.1
    none, asked = _advice(monkeypatch, tmp_path, strong, rivals=("none", "friction"))
    assert none == [] and asked == []
    # A table whose stroke cannot reach past the thresholds: nothing advised.
    short, _ = _advice(monkeypatch, tmp_path, strong, stroke_m=0.1)
    assert short == []
    # The bank's other models (brackets in contact, far beyond the stroke one way) do not
    # stop the advice: the ramp spans what the rivals' draws predict, and one way of each
    # draw falls within the table's reach (0.30 m).
    (c2,), _ = _advice(monkeypatch, tmp_path, strong | {"base_restraint=left": (0.45, 0.25)})
    assert c2["expected_gain_bits"] == pytest.approx(c["expected_gain_bits"])
    # A draw that stands both ways at the table's limit cannot give a ratio: no advice.
    beyond = strong | {"base_restraint=left@0.0005": (0.45, 0.40)}
    assert _advice(monkeypatch, tmp_path, beyond)[0] == []


def test_the_ratios_scale_is_the_coverage_rule_on_lmgc90s_truths(kernel_ratios):
    """RATIO_SCALE is worked out, not chosen: the 90th percentile over the stored truths of
    |log LMGC90's ratio - log the diagnosis's ratio of the truth's own model| (1 for a
    mirror-symmetric model, else the kernel's IDA), over the normal's 1.645."""
    k, stored = kernel_ratios
    diffs = []
    for slug, row in stored.items():
        own = k[slug][1] / k[slug][0] if "base_restraint" in slug else 1.0
        diffs.append(abs(math.log(row["lmgc90_minus_m_s2"] / row["lmgc90_plus_m_s2"]) - math.log(own)))
    assert float(np.percentile(diffs, 90)) / 1.645 == pytest.approx(RATIO_SCALE, abs=0.002)


def test_the_report_says_how_to_run_a_pulse_pair_and_what_each_rival_predicts():
    from voussoir_post.diagnosis.report import _advice_text, _next_test_lines
    nt = {"specimen_id": "W156", "frequency_hz": 3.3333, "new": True, "kind": "pulse_pair",
          "amplitudes_m": [0.2, 0.2995, 0.005], "expected_gain_bits": 0.8, "gain_spread_bits": 0.3, "gain_se_bits": 0.0,
          "predicted_m": {"none": 0.25, "base_restraint": 0.27},
          "predicted_ratio": {"none": 1.0, "base_restraint": 0.85}, "alternatives": []}
    text = _advice_text(nt, "The next test")
    assert "next_test_pulse.csv" in text and "from 200.0 to 299.5 mm of travel by 5.0 mm, each way" in text
    assert "none 1.000, base_restraint 0.850" in text
    table = "\n".join(_next_test_lines(nt))
    assert "| 1 | W156 | (a pulse) | pulse each way, travel 200.0 to 299.5 by 5.0 | 0.80 | 0.30 | ratio 1.000 | ratio 0.850 |" in table
