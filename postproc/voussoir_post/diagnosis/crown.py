"""Crown records as evidence: the peak crown displacement of a test that stood below the
threshold, set against each model's simulation of the same test at the same fraction of
that model's own threshold (docs/diagnosis.md, "Crown records in the probabilities").

The law was measured across codes before it entered the probabilities
(bench/lmgc90/crown_records.py: LMGC90's records of its truths against Voussoir's runs of
their own models, held at 0.9, 0.95 and 0.98 of the threshold):

- the feature is the peak |crown_dx_m| of the record (relative to the table). A simulated
  peak is floored at FLOOR_M (0.5 mm, a displacement transducer's noise), as the bench
  floored both; a measured peak below it is censored: its likelihood is P(peak <
  FLOOR_M) under the law below (one law: the censored mass and the density above it sum
  to 1);
- the error log(measured / simulated) is a Student t of T_DOF = 3 degrees of freedom
  (a normal law was confidently wrong on two truths of eight), of scale
  `crown_scale(r)` at that fraction r of the threshold, calibrated to the coverage of the
  bench's cross-code errors (SCALE_KNOTS: 0.16 at 0.9, 0.22 at 0.95, 0.47 at 0.98);
- the test's fraction is its amplitude over the pair's measured threshold (the bracket's
  midpoint), and the law's scale is taken there;
- each model is simulated at the same fraction of its own threshold at a parameter draw
  (the simulated threshold at that grid point, the table following the command: a
  table gain scales the threshold and the test alike, and drops out), for DRAWS
  stratified draws of its threshold posterior (next_test.draw_indices); and, because the
  crown can grow tenfold within a few per cent of amplitude near the threshold (W118 at
  3 Hz: 1 mm at 0.88 of its threshold, 25 mm at 0.95), over the uncertainties of that
  fraction: the specimen's threshold lies anywhere in its bracket (uniform in log
  between the largest stand and the smallest collapse); the model knows its own
  threshold for the specimen as built to within the simulator's spread and the build
  tolerance's (normal in log); and where, below its threshold, a code's crown starts to
  grow differs between codes by a few per cent of the threshold (CLIFF_SPREAD, normal
  in log: a discrepancy of the pair, integrated over its scale); `pair_spread` joins
  the last three. The model's amplitude is the test's
  amplitude times (its threshold / the specimen's), whose log is their difference: the
  runs are at NODES equal-weight nodes of that sum's law (`threshold_nodes`), and the
  factor is p(records | model, thresholds) = the mean over the draws of the product over
  the tests of the nodes' mixture.

Only records that can say something enter: tests that stood, of a certain pair with a
stand below its collapse, at a fraction of R_MIN to R_MAX; one per pair (the narrowest
law, then the highest fraction), because the codes differ by pair more than by test: a
second record of the same pair shares the first one's error, and counting both as
independent would overstate them; at most MAX_TESTS pairs (the narrowest laws first). A
model the thresholds already put below MIN_PROBABILITY is not simulated: it gets the
least factor of those that were, so records cannot revive it.

They are weighed only with DiagnosisSettings.crown_records (voussoir-diagnose run
--crown-records): against LMGC90 they are calibrated on twenty-one truths but leave a
truth whose collapse is not monotone in amplitude confidently wrong (docs/diagnosis.md).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy.special import logsumexp
from scipy.optimize import brentq
from scipy.stats import norm
from scipy.stats import t as student_t

from ..readers.campaign import Campaign, Test
from .effects import Variant
from .observations import PairObservation

__all__ = ["FLOOR_M", "T_DOF", "SCALE_KNOTS", "CrownTest", "crown_scale", "crown_tests", "peak_m", "bracket",
           "log_terms", "pair_spread", "threshold_nodes", "amplitudes", "mixture_log_term", "crown_log_factors",
           "with_crown", "DRAWS", "NODES", "CLIFF_SPREAD", "variant_at"]

FLOOR_M = 5.0e-4
T_DOF = 3
#: (fraction of the threshold, scale of the log error), calibrated to coverage: at each
#: fraction, the largest over the leave-one-truth-out sets of the bench's records of the
#: 90th percentile of |log LMGC90 / own| over the t's 95th percentile (2.353), so that the
#: law's 90 % interval holds at least 90 % of the cross-code errors of every such set
#: (docs/diagnosis.md, "Crown records across codes": 630 records of twenty-one truths,
#: eight of them with pivots set in, at ten pairs, 0.75 to 4 Hz, each model at a fraction
#: of its own threshold at the pair; the tests where LMGC90 and the own model both stood).
#: The rule gives 0.151, 0.217 and 0.461.
SCALE_KNOTS = ((0.90, 0.16), (0.95, 0.22), (0.98, 0.47))
R_MIN, R_MAX = 0.80, 0.99
MAX_TESTS = 8
DRAWS = 3
MIN_PROBABILITY = 1.0e-4
#: The cross-code discrepancy of the fraction of its threshold at which a code's crown
#: reaches a given peak (normal in log): the largest over the leave-one-truth-out sets of
#: the stored records (bench/lmgc90/crown_records.py) of the 90th percentile of that
#: shift between LMGC90 and Voussoir's own model, over 1.645: 0.0218 (docs/diagnosis.md;
#: test_diagnosis_crown.py works it from the records), taken as 0.022.
CLIFF_SPREAD = 0.022
#: Equal-weight nodes of the law of the model's amplitude relative to the test's
#: (module docstring, `threshold_nodes`).
NODES = 5


@dataclass(frozen=True)
class CrownTest:
    test: Test
    pair: int  #: index of its pair in the posterior's pairs
    fraction: float  #: amplitude over the pair's measured threshold
    scale: float  #: of the log error
    peak_m: float  #: measured peak |crown_dx|
    centre: float  #: amplitude over the bracket's geometric centre (`bracket`)
    width: float  #: of the bracket in log (`bracket`)


def crown_scale(r: float) -> float:
    """The scale of the log error at a fraction `r` of the threshold (the knots' values,
    linear between them, constant outside)."""
    xs, ys = zip(*SCALE_KNOTS)
    return float(np.interp(r, xs, ys))


def peak_m(crown_dx_m) -> float:
    return float(np.max(np.abs(np.asarray(crown_dx_m, float)))) if len(crown_dx_m) else math.nan


def crown_tests(campaign: Campaign, pairs: list[PairObservation]) -> list[CrownTest]:
    """The records that enter the probabilities (module docstring)."""
    out = []
    for tid, rec in campaign.records.items():
        t = campaign.tests.get(tid)
        if rec.crown_dx_m is None or t is None or t.collapsed or t.waveform != "afd" or not t.amplitude_m:
            continue
        j = next((k for k, p in enumerate(pairs) if p.specimen_id == t.specimen_id
                  and abs(p.frequency_hz - t.frequency_hz) < 1e-6), None)
        if j is None or not pairs[j].closed:
            continue
        r = t.amplitude_m / pairs[j].threshold_m
        if not R_MIN <= r <= R_MAX:
            continue
        out.append(CrownTest(t, j, r, crown_scale(r), peak_m(rec.crown_dx_m), *bracket(pairs[j], t.amplitude_m)))
    # One record per pair: the narrowest law, then the highest fraction (the arch rocks most).
    best = {}
    for c in sorted(out, key=lambda c: (c.scale, -c.fraction, c.test.test_id)):
        best.setdefault(c.pair, c)
    return sorted(best.values(), key=lambda c: (c.scale, c.width, c.test.test_id))[:MAX_TESTS]


def bracket(pair: PairObservation, amplitude_m: float) -> tuple[float, float]:
    """(amplitude over the bracket's geometric centre sqrt(low high), the bracket's width
    in log, log(high / low)) of a test of a pair with a stand below its collapse: what
    `amplitudes` takes."""
    return amplitude_m / math.sqrt(pair.low_m * pair.high_m), math.log(pair.high_m / pair.low_m)


def log_terms(measured_peak_m: float, simulated_peaks_m, scale: float) -> np.ndarray:
    """log p(measured peak | simulated peak) for each simulated peak (module docstring)."""
    loc = np.log(np.maximum(np.asarray(simulated_peaks_m, float), FLOOR_M))
    if measured_peak_m < FLOOR_M:
        return student_t.logcdf((math.log(FLOOR_M) - loc) / scale, T_DOF)
    z = (math.log(measured_peak_m) - loc) / scale
    return student_t.logpdf(z, T_DOF) - math.log(scale)


def variant_at(grid, i: int) -> Variant:
    """The simulated variant of grid point i (a table gain needs no simulation)."""
    columns = [(n, v) for n, v in zip(grid.names, grid.values) if n != "table_motion"]
    return Variant.of((n, str(v[i]) if v.dtype == object else round(float(v[i]), 6)) for n, v in columns)


def pair_spread(scales, j: int) -> float:
    """The spread (log) of a model's fraction of its own threshold at pair j when the
    laboratory held at a known fraction of its specimen's: the simulator's spread, the
    build tolerance's and CLIFF_SPREAD."""
    return math.hypot(float(scales.sigma_sim[j]), float(scales.sigma_tol[j]), CLIFF_SPREAD)


def threshold_nodes(spread: float, width: float, k: int = NODES) -> np.ndarray:
    """The k equal-weight nodes (the quantiles at (i + 1/2) / k) of N(0, spread^2) +
    U(-width / 2, width / 2): the log of a model's threshold over the specimen's, the
    first known to within `spread`, the second anywhere in a bracket `width` wide (both
    in log)."""
    q = (np.arange(k) + 0.5) / k
    if width <= 1e-12:
        return spread * norm.ppf(q)
    if spread <= 1e-12:
        return width * (q - 0.5)
    h = 0.5 * width

    def g(z):  # the integral of the normal cdf
        return z * norm.cdf(z) + norm.pdf(z)

    def cdf(x):
        return spread / width * (g((x + h) / spread) - g((x - h) / spread))

    lim = h + 10.0 * spread
    return np.array([brentq(lambda x: cdf(x) - qi, -lim, lim, xtol=1e-12) for qi in q])


def amplitudes(centre: float, log_threshold: float, spread: float, width: float = 0.0) -> list[float]:
    """The amplitudes [m] of a model's runs for a test held at `centre` times the
    bracket's geometric centre, the model's threshold exp(log_threshold) known to within
    `spread`, the specimen's anywhere in a bracket `width` wide (log): `threshold_nodes`."""
    return [round(centre * math.exp(log_threshold + x), 7) for x in threshold_nodes(spread, width)]


def mixture_log_term(measured_peak_m: float, node_peaks_m, scale: float) -> float:
    """log of the equal-weight mixture of the law over the nodes' simulated peaks."""
    return float(logsumexp(log_terms(measured_peak_m, node_peaks_m, scale)) - math.log(len(node_peaks_m)))


def crown_log_factors(post, obs, tests: list[CrownTest], sim, draw_indices, cache=None) -> dict[str, float]:
    """log p(records | model, thresholds) of every model (module docstring). `sim` gives
    the runs' peaks (Simulator.peaks, with its `cache`); `draw_indices(mp, k)` the
    stratified draws."""
    wanted = [m for m, p in post.probabilities.items() if p >= MIN_PROBABILITY]
    plan = {}  # model -> [(draw's variant, the nodes' amplitudes of each test)]
    jobs: dict[tuple, int] = {}
    for m in wanted:
        mp = post.models[m]
        plan[m] = []
        for i in draw_indices(mp, DRAWS):
            v = variant_at(mp.grid, i)
            amps = [amplitudes(c.centre, float(mp.grid.mu[i, c.pair]), pair_spread(post.scales, c.pair), c.width)
                    for c in tests]
            plan[m].append((v, amps))
            for c, nodes in zip(tests, amps):
                for a in nodes:
                    jobs.setdefault((v, c.test.test_id, a), len(jobs))
    by_id = {c.test.test_id: c for c in tests}
    peaks = sim.peaks([(obs.specimens[by_id[tid].test.specimen_id], dataclasses.replace(by_id[tid].test, amplitude_m=a),
                        v, {}) for (v, tid, a) in jobs], cache)
    out = {}
    for m, draws in plan.items():
        per_draw = [sum(mixture_log_term(c.peak_m, [peaks[jobs[(v, c.test.test_id, a)]] for a in nodes], c.scale)
                        for c, nodes in zip(tests, amps)) for v, amps in draws]
        out[m] = float(logsumexp(per_draw) - math.log(len(per_draw)))
    least = min(out.values()) if out else 0.0
    return {m: out.get(m, least) for m in post.probabilities}


def with_crown(post, factors: dict[str, float]):
    """The posterior with each model's evidence times its records' factor."""
    logs = {}
    for m, mp in post.models.items():
        mp.log_evidence += factors[m]
        if mp.log_lik is not None:
            mp.log_lik = mp.log_lik + factors[m]
        logs[m] = math.log(post.probabilities[m]) + factors[m] if post.probabilities[m] > 0 else -math.inf
    values = np.array(list(logs.values()))
    probs = np.exp(values - logsumexp(values))
    for (m, mp), p in zip(post.models.items(), probs):
        mp.probability = float(p)
    post.probabilities = {m: post.models[m].probability for m in post.models}
    post.crown = factors
    return post
