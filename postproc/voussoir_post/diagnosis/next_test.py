"""The test the laboratory should run next: the one whose outcome is expected to say most
about which rival is the cause.

For an `inconclusive` verdict each candidate test is an afd ramp of one specimen at one
frequency: every tested (specimen, frequency) pair again, and every new frequency of
`DiagnosisSettings.probe_frequencies_hz` (at least 0.05 Hz from the tested ones) on each
specimen with a certain set-up. Its outcome is the bracket the ramp would give: the
threshold's bin on a ramp of step `RAMP_STEP` (relative), the ramp's first collapse
early or late as the likelihood reads it (by the pair's class, early.py; a new frequency
is of the unknown class). Each rival predicts the threshold as a normal law of its log:
at a tested pair its posterior predictive (the parameters' posterior spread, the simulator, emulator, table and discrepancies);
at a new frequency a mixture over DRAWS_AT_NEW draws of its parameters' posterior
(`posterior_draws`: stratified, so a posterior that a new frequency would spread is
spread there), each draw's threshold simulated, with the tested pairs' predictive spread
less the parameters' own (which the draws carry). A rival's table gain divides its
threshold.

The score is the expected information gain of the test about the cause, in bits: the
mutual information I(M; Y) = H(Y) - sum_m p_m H(Y | m) between the rival M (weights
their posterior probabilities, renormalised) and the ramp's bin Y. A repeat of a tested
pair is scored by the likelihood's own terms: its rows join the pair's, whose bracket
(largest stand below, smallest collapse) the threshold is already known to lie in, so
its outcome is the bin of that bracket the new ramp puts it in, each rival's predictive
conditioned on the bracket (truncated to it), and the ramp spans the bracket only. A
repeat of a narrow bracket tells little, and its gain says so; a repeat of a one-sided
bracket (collapse rows only) can tell much.

A test held below the threshold with its crown recorded (kind `hold_crown`) is a
candidate at every tested pair with a stand below its collapse: one amplitude, at
HOLD_FRACTIONS of the pair's measured threshold and at or below its largest stand (so
expected to stand). Its outcome is the bin of the measured peak crown displacement
(crown.py's law: censored below the transducer's floor, a Student t above it); each
rival's law is the mixture over DRAWS draws of its posterior, each simulated at the same
fraction of its own threshold at crown.threshold_nodes (that threshold's spread and the
bracket's). Its
gain's standard error is the jackknife over the draws. Advised only with
DiagnosisSettings.crown_records.

Every candidate is within the table's limits (table.csv, or its defaults): the ramp's
largest amplitude A (the largest rival prediction plus two predictive spreads) must have
A <= stroke, A 2 pi f <= peak velocity and A (2 pi f)^2 <= peak acceleration.
"""

from __future__ import annotations

import hashlib
import json
import math
from pathlib import Path

import numpy as np
from scipy.special import ndtr
from scipy.stats import t as student_t

from ..readers.campaign import Test
from .bank import onset_amplitudes, variant_key
from .crown import DRAWS, FLOOR_M, R_MIN, T_DOF, amplitudes, bracket, crown_scale, pair_spread, variant_at
from .effects import Variant, arch_group
from .early import EARLY_SPAN, LATE_SPAN, pair_early_prob
from .likelihood import predictive_sd, ramp_g
from .models import members
from .observations import Observations
from .posterior import Posterior, predicted_log
from .pulses import (PULSE_S, RATIO_SCALE, PulsePair, grid_log_ratio, one_sided, pulse_thresholds, pulse_variants,
                     reach_m, unit_pulse)
from .settings import DiagnosisSettings
from .simulator import Simulator

__all__ = ["next_test", "hold_gain_bits", "draw_indices", "HOLD_FRACTIONS", "expected_gain_bits", "gain_spread_bits", "gain_jackknife_se_bits", "ramp", "within_limits", "posterior_draws", "RAMP_STEP",
           "DRAWS_AT_NEW"]

RAMP_STEP = 0.025  #: relative step of the advised ramp (a bin of the outcome)
ALTERNATIVES = 3
#: Draws of each rival's parameters simulated at a new frequency (its predictive there is
#: their mixture).
DRAWS_AT_NEW = 3
#: Fractions of a tested pair's measured threshold at which a test may be held with its
#: crown recorded (kind `hold_crown`), and the outcome's bin in scales of the crown law.
HOLD_FRACTIONS = (0.9, 0.95)
CROWN_BIN = 0.5


def draw_indices(mp, k: int = DRAWS_AT_NEW) -> list[int]:
    """k grid points of a model drawn from its posterior by stratified (systematic)
    resampling: the points at cumulative posterior mass (i + 1/2) / k in the grid's order,
    which for one parameter are its quantiles of 1/(2k), 3/(2k), ..."""
    cdf = np.cumsum(mp.weights)
    return [min(int(np.searchsorted(cdf, (i + 0.5) / k * cdf[-1])), cdf.size - 1) for i in range(k)]


def posterior_draws(mp, k: int = DRAWS_AT_NEW) -> list[Variant]:
    """k draws of a model's simulated parameters from its posterior over its grid
    (draw_indices); the nominal variant for `none` and a table gain alone (a gain needs no
    simulation: it divides the threshold)."""
    return [variant_at(mp.grid, i) for i in draw_indices(mp, k)]


def _ramp_cdf(x: np.ndarray, mu: np.ndarray, sd: np.ndarray, early) -> np.ndarray:
    """P(a ramp's first collapse <= x), log t ~ N(mu, sd^2), early with probability e (at
    log t - u, u uniform on (0, EARLY_SPAN)) and late with l (at log t + v, v uniform on
    (0, LATE_SPAN)), early = (e, l): the likelihood's story of a two-sided bracket
    (likelihood.py), each part the mean of Phi over the shift, sd (G(z + span / sd) - G(z)) /
    span with z the standardised x. Infinite x: 0 or 1."""
    e, late = early
    finite = np.isfinite(x)
    z = (np.where(finite, x, 0.0) - mu) / sd
    cdf = (1.0 - e - late) * ndtr(z)
    if e > 0:
        cdf = cdf + e * sd * (ramp_g(z + EARLY_SPAN / sd) - ramp_g(z)) / EARLY_SPAN
    if late > 0:
        cdf = cdf + late * sd * (ramp_g(z) - ramp_g(z - LATE_SPAN / sd)) / LATE_SPAN
    return np.where(finite, np.clip(cdf, 0.0, 1.0), np.where(x > 0, 1.0, 0.0))


def _outcome_laws(probabilities, means, sds, step, within, early=(0.0, 0.0)):
    """(p, py_m): the rivals' normalised probabilities and each rival's law of the ramp's
    bin (rival, bin), for expected_gain_bits and gain_spread_bits (which see); None when
    the bracket `within` leaves no bin. `early`: the pair's (e, l) (_ramp_cdf)."""
    p = np.asarray(probabilities, float)
    p = p / p.sum()
    comps = [np.atleast_1d(np.asarray(m, float)) for m in means]
    comp_sd = [np.broadcast_to(np.atleast_1d(np.asarray(s_, float)), c.shape) for c, s_ in zip(comps, sds)]
    owner = np.concatenate([np.full(c.size, i) for i, c in enumerate(comps)])
    mu, sd = np.concatenate(comps), np.concatenate(comp_sd)
    width = math.log1p(step)
    lo = float(np.min(mu - 6 * sd)) - (EARLY_SPAN if early[0] > 0 else 0.0)
    reach = float(np.max(mu + 6 * sd)) + (LATE_SPAN if early[1] > 0 else 0.0)
    if within is None:
        edges = lo + width * np.arange(int(math.ceil((reach - lo) / width)) + 2)
    else:
        lo = max(lo, within[0])
        hi = within[1]
        if not hi > lo:
            return None
        # Above a lower bound the bins run to where the rivals reach, then one more to infinity.
        top = hi if math.isfinite(hi) else max(reach, lo + width)
        edges = np.append(lo + width * np.arange(max(1, int(math.ceil((top - lo) / width - 1e-9)))), top)
        if not math.isfinite(hi):
            edges = np.append(edges, hi)
    cdf = _ramp_cdf(edges[None, :], mu[:, None], sd[:, None], early)
    py_c = np.clip(np.diff(cdf, axis=1), 0.0, None)  # (component, bin)
    py_m = np.stack([py_c[owner == i].mean(axis=0) for i in range(len(comps))])  # (rival, bin)
    if within is not None:
        mass = py_m.sum(axis=1, keepdims=True)
        py_m = np.where(mass > 1e-300, py_m / np.maximum(mass, 1e-300), 1.0 / py_m.shape[1])
    return p, py_m


def _entropy_bits(q) -> float:
    q = np.asarray(q, float)
    q = q[q > 0]
    return float(-(q * np.log2(q)).sum())


def _information(laws) -> tuple[float, float]:
    """(expected gain, spread) in bits from `_outcome_laws`: I(M; Y), and the standard
    deviation over the outcomes y of the information H(p) - H(p | y) each delivers."""
    if laws is None:
        return 0.0, 0.0
    p, py_m = laws
    py = p @ py_m
    gain = max(0.0, _entropy_bits(py) - sum(pm * _entropy_bits(row) for pm, row in zip(p, py_m)))
    seen = py > 0
    post = (p[:, None] * py_m[:, seen]) / py[seen]
    delivered = _entropy_bits(p) - np.array([_entropy_bits(post[:, k]) for k in range(post.shape[1])])
    mean = float(py[seen] @ delivered)
    return gain, float(math.sqrt(max(0.0, py[seen] @ (delivered - mean) ** 2)))


def expected_gain_bits(probabilities: list[float], means: list, sds: list,
                       step: float = RAMP_STEP, within: tuple[float, float] | None = None, early=(0.0, 0.0)) -> float:
    """I(M; Y) in bits for rivals of probabilities p_m predicting log threshold
    N(mean_m, sd_m^2), Y the bin of width log(1 + step) the threshold falls in. A rival's
    mean may be a list: an equal mixture of normals of those means (its sd one, or one
    per component). `within` (log low, log high): the threshold is already known to lie
    there (a tested pair's bracket; -inf for no stand below): each rival's law is
    truncated to it, and the bins cover it only. `early` (e, l): the ramp's first collapse
    may be early or late (_ramp_cdf), as the likelihood reads the pair's bracket."""
    return _information(_outcome_laws(probabilities, means, sds, step, within, early))[0]


def gain_spread_bits(probabilities: list[float], means: list, sds: list,
                     step: float = RAMP_STEP, within: tuple[float, float] | None = None) -> float:
    """The standard deviation, over the test's outcomes, of the information it delivers
    (bits): outcome y gives H(p) - H(p | y), the rivals' entropy before less after
    Bayes' rule, whose mean over y (drawn from the rivals' mixture) is expected_gain_bits.
    What one run of the test may give about that mean: a test expected to give 0.3 bits
    with a spread of 0.4 often gives nothing and sometimes a bit. Arguments as
    expected_gain_bits."""
    return _information(_outcome_laws(probabilities, means, sds, step, within))[1]


def gain_jackknife_se_bits(probabilities: list[float], means: list, sds: list, step: float = RAMP_STEP,
                           early=(0.0, 0.0)) -> float:
    """The Monte Carlo standard error of expected_gain_bits at a new frequency, whose rivals'
    laws are mixtures over k draws of their parameters, each a simulated threshold (with
    its own chaotic jitter): the jackknife over the draws, every rival's draw i left out
    together, sqrt((k - 1)/k sum_i (g_(i) - mean g)^2). 0 with fewer than 3 draws."""
    comps = [np.atleast_1d(np.asarray(m, float)) for m in means]
    k = min(c.size for c in comps)
    if k < 3:
        return 0.0
    g = np.array([expected_gain_bits(probabilities, [np.delete(c, i) if c.size == k else c for c in comps], sds, step,
                                     early=early)
                  for i in range(k)])
    return float(math.sqrt((k - 1) / k * np.sum((g - g.mean()) ** 2)))


def within_limits(amplitude_m: float, frequency_hz: float, table) -> bool:
    w = 2 * math.pi * frequency_hz
    return (amplitude_m <= table.stroke_m and amplitude_m * w <= table.max_velocity_m_s
            and amplitude_m * w * w <= table.max_accel_m_s2)


def ramp(means: list[float], sds: list[float]) -> list[float]:
    """[from, to, by] [m] of an afd ramp that brackets every rival's threshold: from the
    smallest prediction less two spreads to the largest plus two, by RAMP_STEP of the
    smallest, in 0.5 mm."""
    lo = min(math.exp(float(np.min(m)) - 2 * float(np.max(s))) for m, s in zip(means, sds))
    hi = max(math.exp(float(np.max(m)) + 2 * float(np.max(s))) for m, s in zip(means, sds))
    return [_snap(lo), _snap(hi), _snap(RAMP_STEP * lo)]


def _snap(x: float) -> float:
    """An amplitude [m] a laboratory commands: a multiple of 0.5 mm, at least 0.5 mm,
    written without float noise (0.051, not 0.051000000000000004)."""
    return round(max(5e-4, round(x / 5e-4) * 5e-4), 6)


def _new_frequencies(obs: Observations, sid: str, settings: DiagnosisSettings) -> list[float]:
    tested = [p.frequency_hz for p in obs.of(sid)]
    return [f for f in settings.probe_frequencies_hz if min(abs(f - t) for t in tested) > 0.05]


def _candidate(sid: str, f: float, new: bool, rivals: list[str], probs: list[float], means: list[float],
               sds: list[float], table, bracket: tuple[float, float] | None = None, early=(0.0, 0.0)) -> dict | None:
    """One candidate test; `bracket` (low, high) [m] of a tested pair: the repeat's ramp
    spans it (from its stand, or from the ramp's start without one, to its collapse);
    `early` the pair's (e, l) of early and late first collapses (likelihood.py)."""
    amps = ramp(means, sds)
    within = None
    if bracket is not None and not math.isfinite(bracket[1]):  # every test stood: ramp on from the stand
        low = bracket[0]
        within = (math.log(low), math.inf)
        amps = [_snap(low), _snap(max(amps[1], (1.0 + RAMP_STEP) * low)), _snap(RAMP_STEP * low)]
    elif bracket is not None:
        low, high = bracket
        within = (math.log(low) if low > 0 else -math.inf, math.log(high))
        start = low if low > 0 else min(amps[0], 0.9 * high)
        amps = [_snap(start), _snap(high), _snap(RAMP_STEP * start)]
    if not within_limits(amps[1], f, table):
        return None
    gain, spread = _information(_outcome_laws(probs, means, sds, RAMP_STEP, within, early))   # one law, both figures
    return {"specimen_id": sid, "frequency_hz": f, "new": new, "kind": "afd_ramp", "amplitudes_m": amps,
            "expected_gain_bits": gain, "gain_spread_bits": spread,
            "gain_se_bits": gain_jackknife_se_bits(probs, means, sds, early=early) if new else 0.0,
            "predicted_m": {m: math.exp(float(np.mean(v))) for m, v in zip(rivals, means)},
            "spread": {m: float(np.sqrt(np.mean(np.square(s_)) + np.var(v))) for m, s_, v in zip(rivals, sds, means)}}


def _hold_laws(probabilities, peaks, scale: float):
    """(p, py_m) of a test held below the threshold with its crown recorded: its outcome
    is the measured peak's bin (the censored one below FLOOR_M, then bins of CROWN_BIN
    scales), each rival's law the mixture over its draws (and, where a draw is a row of
    peaks, over crown.threshold_nodes of its threshold) of the crown law (crown.py)
    about each simulated peak."""
    p = np.asarray(probabilities, float)
    p = p / p.sum()
    locs = [np.log(np.maximum(np.asarray(v, float).reshape(len(v), -1), FLOOR_M)) for v in peaks]  # (draw, node)
    top = max(float(np.max(v)) for v in locs) + 12 * scale
    lo = math.log(FLOOR_M)
    edges = np.append(lo + CROWN_BIN * scale * np.arange(int(math.ceil((top - lo) / (CROWN_BIN * scale))) + 1), np.inf)
    py_m = []
    for v in locs:
        cdf = student_t.cdf((edges[None, None, :] - v[:, :, None]) / scale, T_DOF)  # (draw, node, edge)
        per = np.concatenate([cdf[:, :, :1], np.diff(cdf, axis=2)], axis=2)
        py_m.append(per.mean(axis=(0, 1)))  # the nodes are equal-weight, and so are the draws
    return p, np.clip(np.array(py_m), 0.0, None)


def hold_gain_bits(probabilities, peaks, scale: float) -> tuple[float, float, float]:
    """(expected gain, spread, jackknife standard error over the draws) in bits of a hold
    test whose rivals' draws simulate these peaks [m] (a list per rival: a peak per draw,
    or a row of crown.threshold_nodes's peaks per draw)."""
    gain, spread = _information(_hold_laws(probabilities, peaks, scale))
    k = min(len(v) for v in peaks)
    if k < 3:
        return gain, spread, 0.0
    g = np.array([_information(_hold_laws(probabilities, [np.delete(np.asarray(v, float), i, axis=0) for v in peaks],
                                          scale))[0] for i in range(k)])
    return gain, spread, float(math.sqrt((k - 1) / k * np.sum((g - g.mean()) ** 2)))


def _hold_candidates(post: Posterior, obs: Observations, rivals: list[str], probs: list[float], predicted: dict,
                     settings: DiagnosisSettings, work: Path, table, recorded) -> list[dict]:
    """Tests held at HOLD_FRACTIONS of a tested pair's measured threshold (at or below its
    largest stand, so expected to stand), with the crown recorded: each rival's draws
    simulated at the same fraction of their own thresholds (crown.py). A pair whose crown
    record is already in the probabilities is not asked again (one record a pair counts)."""
    plans, jobs = [], {}
    for j, p in enumerate(post.pairs):
        if not p.closed:
            continue
        for h in HOLD_FRACTIONS:
            amp = _snap(h * p.threshold_m)
            r = amp / p.threshold_m
            centre, width = bracket(p, amp)
            if (amp > p.low_m or r < R_MIN or not within_limits(amp, p.frequency_hz, table)
                    or any(c.pair == j for c in recorded)):
                continue
            draws = {}
            for m in rivals:
                mp = post.models[m]
                draws[m] = [(variant_at(mp.grid, i),
                             amplitudes(centre, float(mp.grid.mu[i, j]), pair_spread(post.scales, j), width))
                            for i in draw_indices(mp, DRAWS)]
                for v, nodes in draws[m]:
                    for a in nodes:
                        jobs.setdefault((p.specimen_id, p.frequency_hz, v, a), len(jobs))
            plans.append((j, p, amp, r, draws))
    if not plans:
        return []
    sim = Simulator(settings, Path(work) / "hold")
    peaks = sim.peaks([(obs.specimens[sid], Test(f"hold_{k:04d}", sid, "afd", "stand", frequency_hz=f,
                                                 amplitude_m=a, n_attack=obs.cycles[sid][0],
                                                 n_full=obs.cycles[sid][1], n_decay=obs.cycles[sid][2]), v, {})
                       for k, (sid, f, v, a) in enumerate(jobs)], Path(work) / "crown-runs")
    out = []
    for j, p, amp, r, draws in plans:
        sims = [[[peaks[jobs[(p.specimen_id, p.frequency_hz, v, a)]] for a in nodes] for v, nodes in draws[m]]
                for m in rivals]
        scale = crown_scale(r)
        gain, spread, se = hold_gain_bits(probs, sims, scale)
        out.append({"specimen_id": p.specimen_id, "frequency_hz": p.frequency_hz, "new": False, "kind": "hold_crown",
                    "amplitudes_m": [amp], "fraction": round(r, 4), "expected_gain_bits": gain,
                    "gain_spread_bits": spread, "gain_se_bits": se,
                    "predicted_m": {m: float(predicted[m][j]) for m in rivals},
                    "predicted_crown_m": {m: float(np.exp(np.mean(np.log(np.maximum(np.asarray(v)[:, len(v[0]) // 2],
                                                                                   FLOOR_M)))))
                                          for m, v in zip(rivals, sims)}})
    return out


#: Posterior draws of each rival whose pulse ratio makes its law for a pulse pair (no
#: simulation per draw: the ratios are the pulse bank's).
PULSE_DRAWS = 12
#: The advised pulse ramp: from PULSE_RANGE[0] times the smallest simulated threshold (either
#: way, of the nominal model and the models with brackets on one side) to PULSE_RANGE[1]
#: times the largest.
PULSE_RANGE = (0.8, 1.25)


def pulse_ramp(thresholds: list[float], table, must_reach: float | None = None) -> list[float] | None:
    """[from, to, by] [m of travel] of a pulse ramp both ways (PULSE_RANGE of the
    thresholds), `to` cut to the table's reach (pulses.reach_m); None when the table
    cannot reach 1.05 times `must_reach` (default: the largest threshold)."""
    lo = PULSE_RANGE[0] * min(thresholds)
    hi = PULSE_RANGE[1] * max(thresholds)
    reach = reach_m(table)
    if reach < 1.05 * (max(thresholds) if must_reach is None else must_reach):
        return None
    return [_snap(lo), _snap(min(hi, reach - 5e-4)), _snap(RAMP_STEP * lo)]


def _pulse_candidates(post: Posterior, obs: Observations, rivals: list[str], probs: list[float],
                      settings: DiagnosisSettings, work: Path, table) -> list[dict]:
    """A pair of pulse ramps, one way and the other (pulses.py), on each certain specimen
    that has none yet, when a rival has brackets. Its outcome is the bin (of the ramps'
    step) of the log ratio of the two ways' thresholds; each rival's law the mixture over
    PULSE_DRAWS posterior draws of its ratio (0 for a mirror-symmetric model) with the codes'
    disagreement (pulses.RATIO_SCALE) and the two ramps' bins."""
    if not any("base_restraint" in members(m) for m in rivals):
        return []
    t, x, _ = unit_pulse()
    sd = math.sqrt(RATIO_SCALE ** 2 + math.log1p(RAMP_STEP) ** 2 / 6.0)
    out = []
    pulsed = {pp.specimen_id for pp in obs.pulse_pairs}
    for sid in sorted({p.specimen_id for p in obs.pairs} - pulsed):
        spec = obs.specimens[sid]
        pp = PulsePair(sid, t, x)
        cache, folder = Path(work) / "pulse-bank", Path(work) / f"pulse-{sid}"
        nominal = pulse_thresholds(spec, pp, [Variant()], settings, cache, folder)["nominal"]
        if pulse_ramp(list(nominal), table) is None:
            continue
        bank_keys = post.bank.specimens[sid].thresholds if post.bank is not None else {}
        ratios = pulse_thresholds(spec, pp, pulse_variants(bank_keys), settings, cache, folder)

        def both_ways(v: Variant) -> tuple[float, float]:
            """A draw's thresholds both ways: its own where simulated, else its brackets
            alone's (a pair's other effect at a value between the bank's nodes), else the
            nominal arch's (mirror-symmetric)."""
            side = one_sided(v)
            return ratios.get(variant_key(v), ratios.get(f"base_restraint={side}", nominal) if side else nominal)

        means, level, ratio, ways = [], {}, {}, []
        for m in rivals:
            mp = post.models[m]
            idx = draw_indices(mp, PULSE_DRAWS)
            rho = grid_log_ratio(mp.grid, ratios, spec)[idx]
            means.append(list(rho))
            drawn = [both_ways(variant_at(mp.grid, i)) for i in idx]
            ways += drawn
            own = [d[0] for d in drawn if math.isfinite(d[0])]   # inf: stood at the IDA's ceiling
            level[m] = float(np.exp(np.mean(np.log(own)))) if own else None
            ratio[m] = float(np.exp(np.mean(rho)))
        # The ramps span the draws' thresholds both ways; each draw must fall one way
        # within the table's reach (a way that stands at the table's limit is a lower bound).
        finite = [v for d in ways for v in d if math.isfinite(v)]
        amps = pulse_ramp(finite, table, must_reach=max(min(d) for d in ways))
        if amps is None:
            continue
        gain, spread = _information(_outcome_laws(probs, means, [sd] * len(rivals), RAMP_STEP, None))
        out.append({"specimen_id": sid, "frequency_hz": round(1.0 / (2.0 * PULSE_S[0]), 4), "new": True,
                    "kind": "pulse_pair", "amplitudes_m": amps, "expected_gain_bits": gain,
                    "gain_spread_bits": spread, "gain_se_bits": 0.0, "predicted_m": level,
                    "predicted_ratio": ratio})
    return out


def next_test(post: Posterior, obs: Observations, rivals: list[str], settings: DiagnosisSettings,
              work: Path, table, recorded=(), holds: bool = True) -> dict | None:
    """The best test (specimen_id, frequency_hz, new, kind, amplitudes_m,
    expected_gain_bits, predicted_m per rival, alternatives: the next best), or None with
    fewer than two rivals or no test within the table's limits. `holds`: tests held below
    a threshold with the crown recorded are candidates too (`recorded`: the campaign's
    crown records already in the probabilities, crown.crown_tests)."""
    if len(rivals) < 2:
        return None
    sc = post.scales
    probs = [post.probabilities[m] for m in rivals]
    candidates = []
    # Tested pairs: each rival's posterior predictive (mean, and the spread of its mixture).
    stats, noise_sd = {}, {}
    for m in rivals:
        mp = post.models[m]
        mu = mp.adjusted_mu(sc)
        mean = predicted_log(mp, sc)
        sd = predictive_sd(mp.grid, sc, post.pairs)
        var = mp.weights @ (sd ** 2 + (mu - mean[None, :]) ** 2)
        stats[m] = (mean, np.sqrt(var))
        # At a new frequency the draws carry the parameters' spread; the rest is the tested
        # pairs' predictive spread at a given parameter.
        noise_sd[m] = float(np.sqrt(np.mean(mp.weights @ sd ** 2)))
    draws = {m: posterior_draws(post.models[m]) for m in rivals}
    for j, p in enumerate(post.pairs):
        c = _candidate(p.specimen_id, p.frequency_hz, False, rivals, probs, [stats[m][0][j] for m in rivals],
                       [stats[m][1][j] for m in rivals], table, (p.low_m, p.high_m),
                       tuple(sc.early_prob[j]))
        if c:
            candidates.append(c)
    gain = float(np.mean(sc.gain_mean)) if obs.gain_source != "none" else 1.0
    for sid in sorted({p.specimen_id for p in obs.pairs}):
        spec, freqs = obs.specimens[sid], _new_frequencies(obs, sid, settings)
        if not freqs:
            continue
        variants = sorted({v for m in rivals for v in draws[m]}, key=variant_key)
        # A folder per question (specimen, frequencies, models): a rerun reuses its sweeps,
        # another question never meets them.
        key = json.dumps([[arch_group(spec, v) for v in variants], freqs, settings.dt_s], sort_keys=True)
        sim = Simulator(settings, Path(work) / hashlib.sha256(key.encode()).hexdigest()[:16])
        onset = onset_amplitudes(sim.runner, spec, freqs)
        found = sim.thresholds_at(spec, freqs, obs.cycles[sid], variants, settings.ceiling_factor * max(onset),
                                  settings.amp_tol_fraction * min(onset))
        for f in freqs:
            pred = {m: [found.get((v, f), math.nan) / (gain if "table_motion" in members(m) else 1.0)
                        for v in draws[m]] for m in rivals}
            if not all(math.isfinite(v) and v > 0 for vs in pred.values() for v in vs):
                continue
            c = _candidate(sid, f, True, rivals, probs, [list(np.log(pred[m])) for m in rivals],
                           [noise_sd[m] for m in rivals], table, early=pair_early_prob(None))
            if c:
                candidates.append(c)
    candidates += _pulse_candidates(post, obs, rivals, probs, settings, work, table)
    if holds:
        predicted = {m: np.exp(stats[m][0]) for m in rivals}
        candidates += _hold_candidates(post, obs, rivals, probs, predicted, settings, work, table, recorded)
    if not candidates:
        return None
    candidates.sort(key=lambda c: -c["expected_gain_bits"])
    best = dict(candidates[0])
    best["alternatives"] = [{k: c[k] for k in ("specimen_id", "frequency_hz", "new", "kind", "amplitudes_m",
                                               "expected_gain_bits", "gain_spread_bits", "gain_se_bits", "predicted_m",
                                               "predicted_crown_m", "predicted_ratio") if k in c}
                            for c in candidates[1:1 + ALTERNATIVES]]
    return best
