"""Stage 3b of the diagnosis: the likelihood of what was observed, for every grid point.

A pair's rows bracket its collapse threshold t (in commanded amplitude): low < t <= high.
Under a model at parameter theta,

    log t = mu(theta) - log g + delta_s + eps,

- mu: the simulated threshold (models.py);
- g: the table gain of the pair (1 when the model says the table followed the command;
  the pair's measured gain under table_motion with records);
- eps ~ N(0, s^2), s^2 = sigma_sim^2 + sigma_gain^2 (+ the standard error of a measured
  gain): the simulator's own spread at that pair, pooled from the bank's replicas of the
  nominal model (dt x 0.97 and x 1.03, scan steps of 3 and 7 %) and the jitter of every
  model's simulated values about its smooth fit (models.py), at least 1 %; and the test-to-test scatter of the table gain that the records
  measure (1 % when there are none; at least 3 % when read from peak accelerations);
- delta_s ~ N(0, tau_s^2), shared by the pairs of a specimen: a discrepancy of the model
  that no parameter carries, tau_s^2 = tau0^2 + d_s^2 with d_s the change of the
  specimen's nominal thresholds from dt to dt / 2 and tau0 integrated over 1, 3 and 6 %
  (equal weights); integrated by Gauss-Hermite quadrature.

Each pair's probability is mixed with an outlier model (probability 0.05: log t uniform
within a factor 3 of mu), so one odd pair cannot carry a verdict. The table records add
their own factor: each test's measured gain is N(1, s_g^2) when the table followed the
command, or N(g_pair, s_g^2) with g_pair uniform on 0.7 .. 1.4 under table_motion.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import log_ndtr, logsumexp

from .bank import FINE_DT, Bank
from .models import GAIN_RANGE, ModelGrid, roughness
from .observations import Observations, PairObservation

__all__ = ["Scales", "scales", "adjusted_mu", "log_likelihood", "records_log_factor", "TAU0", "OUTLIER_PROB", "OUTLIER_FACTOR"]

TAU0 = (0.01, 0.03, 0.06)  #: model discrepancy per specimen (relative), integrated with equal weights
OUTLIER_PROB = 0.05
OUTLIER_FACTOR = 3.0  #: an outlier's threshold lies within this factor of the prediction
SIM_FLOOR = 0.01  #: the smallest simulator spread assumed (relative)
GAIN_SCATTER_DEFAULT = 0.01  #: test-to-test gain scatter assumed without records
GAIN_SCATTER_FLOOR = 0.003
PEAK_SCATTER_FLOOR = 0.03  #: scatter of a gain read from measured peak accelerations (no records)
_GH_X, _GH_W = np.polynomial.hermite_e.hermegauss(9)
_GH_LOGW = np.log(_GH_W / _GH_W.sum())


@dataclass
class Scales:
    """The scales of the likelihood, from the bank and the records."""

    sigma_sim: np.ndarray  #: simulator spread of each pair (relative)
    sigma_gain: float  #: test-to-test table gain scatter (relative)
    d_fine: dict[str, float]  #: per specimen: RMS change of log threshold from dt to dt / 2
    gain_mean: np.ndarray  #: measured gain of each pair (1 without records)
    gain_se: np.ndarray  #: its standard error


def scales(bank: Bank, obs: Observations, pairs: list[PairObservation]) -> Scales:
    fine = {}
    for sid, sb in bank.specimens.items():
        base = np.log(np.asarray(sb.thresholds["nominal"], dtype=float))
        half = np.log(np.asarray(sb.replicas.get(FINE_DT[0], sb.thresholds["nominal"]), dtype=float)) - base
        half = half[np.isfinite(half)]
        fine[sid] = float(np.sqrt(np.mean(half ** 2))) if half.size else 0.0
    sigma_sim = np.full(len(pairs), SIM_FLOOR)
    if bank.specimens:
        # Per pair: the spread of the nominal model's replicas and the jitter of every
        # model's simulated values about its smooth fit, pooled.
        ss, dof = roughness(bank, obs, pairs)
        for j, p in enumerate(pairs):
            sb = bank.specimens[p.specimen_id]
            k = sb.index(p.frequency_hz)
            reps = np.log([sb.thresholds["nominal"][k]] + [v[k] for name, v in sb.replicas.items()
                                                           if name != FINE_DT[0]])
            reps = reps[np.isfinite(reps)]
            rep_ss = float(np.sum((reps - reps.mean()) ** 2)) if reps.size > 1 else 0.0
            total_dof = dof[j] + max(0, reps.size - 1)
            if total_dof > 0:
                sigma_sim[j] = max(SIM_FLOOR, math.sqrt((ss[j] + rep_ss) / total_dof))
    within = [np.asarray(p.gains) - np.mean(p.gains) for p in pairs if len(p.gains) > 1]
    dof = sum(w.size - 1 for w in within)
    sigma_gain = (max(GAIN_SCATTER_FLOOR, float(np.sqrt(sum(float(w @ w) for w in within) / dof)))
                  if dof > 0 else GAIN_SCATTER_DEFAULT)
    if obs.gain_source == "peak_accel":  # the peak of a noisy record overstates the table's
        sigma_gain = max(sigma_gain, PEAK_SCATTER_FLOOR)
    gm = np.array([np.mean(p.gains) if p.gains else 1.0 for p in pairs])
    gse = np.array([sigma_gain / math.sqrt(len(p.gains)) if p.gains else 0.0 for p in pairs])
    return Scales(sigma_sim, sigma_gain, fine, gm, gse)


def _log_bracket(lo: np.ndarray, hi: np.ndarray, m: np.ndarray, s: np.ndarray) -> np.ndarray:
    """log P(lo < x <= hi), x ~ N(m, s^2), stably (lo may be -inf)."""
    a = (lo - m) / s
    b = (hi - m) / s
    # P = Phi(b) - Phi(a) = Phi(-a) - Phi(-b); take the side away from the tails.
    upper = a > 0
    la = np.where(upper, log_ndtr(-a), log_ndtr(a))
    lb = np.where(upper, log_ndtr(-b), log_ndtr(b))
    big, small = np.where(upper, la, lb), np.where(upper, lb, la)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = big + np.log1p(-np.exp(np.minimum(small - big, -1e-300)))
    return np.where(np.isfinite(big), out, -np.inf)


def _log_outlier(lo: np.ndarray, hi: np.ndarray, m: np.ndarray) -> np.ndarray:
    half = math.log(OUTLIER_FACTOR)
    inside = np.clip(np.minimum(hi, m + half) - np.maximum(lo, m - half), 0.0, None)
    return np.log(np.maximum(inside / (2 * half), 1e-300))


def adjusted_mu(grid: ModelGrid, sc: Scales) -> np.ndarray:
    """A model's predicted log threshold in commanded amplitude at each grid point, per
    pair: the simulated one divided by the table gain the model says (the pair's measured
    gain under table_motion with records, the grid's gain without)."""
    mu = grid.mu.copy()
    if grid.gain_per_pair:
        mu -= np.log(sc.gain_mean)[None, :]
    if grid.log_gain is not None:
        mu -= grid.log_gain[:, None]
    return mu


def log_likelihood(grid: ModelGrid, obs: Observations, pairs: list[PairObservation], sc: Scales) -> np.ndarray:
    """log p(brackets | model, theta) at every grid point (records apart)."""
    lo = np.log(np.array([p.low_m if p.low_m > 0 else 0.0 for p in pairs]) + 1e-300)
    lo = np.where(np.array([p.low_m > 0 for p in pairs]), lo, -np.inf)
    hi = np.log(np.array([p.high_m for p in pairs]))
    mu = adjusted_mu(grid, sc)
    var = np.full(len(pairs), sc.sigma_sim ** 2 + sc.sigma_gain ** 2)
    if grid.gain_per_pair:
        var += (sc.gain_se / sc.gain_mean) ** 2
    s = np.sqrt(var)[None, :]
    specimens = sorted({p.specimen_id for p in pairs})
    total = np.zeros((len(TAU0), grid.n))
    for sid in specimens:
        j = [k for k, p in enumerate(pairs) if p.specimen_id == sid]
        # Every (tau0, Gauss-Hermite node) at once: shift (n_tau, n_nodes, 1, 1).
        tau = np.sqrt(np.asarray(TAU0) ** 2 + sc.d_fine.get(sid, 0.0) ** 2)
        shift = (tau[:, None] * _GH_X[None, :])[:, :, None, None]
        m = mu[None, None, :, j] + shift
        normal = _log_bracket(lo[j], hi[j], m, s[:, j])
        mixed = np.logaddexp(math.log1p(-OUTLIER_PROB) + normal,
                             math.log(OUTLIER_PROB) + _log_outlier(lo[j], hi[j], m))
        total += logsumexp(_GH_LOGW[None, :, None] + mixed.sum(axis=3), axis=1)
    return logsumexp(total, axis=0) - math.log(len(TAU0))


def records_log_factor(table_motion: bool, obs: Observations, pairs: list[PairObservation], sc: Scales) -> float:
    """log p(measured gains | model): the table followed the command (gain 1), or each pair
    has its own gain, uniform on 0.7 .. 1.4, integrated (Laplace: the records pin it)."""
    if obs.gain_source == "none":
        return 0.0
    s = sc.sigma_gain
    total = 0.0
    width = GAIN_RANGE[1] - GAIN_RANGE[0]
    for p in pairs:
        g = np.asarray(p.gains, dtype=float)
        if g.size == 0:
            continue
        centre = float(g.mean()) if table_motion else 1.0
        total += float(np.sum(-0.5 * ((g - centre) / s) ** 2 - math.log(s * math.sqrt(2 * math.pi))))
        if table_motion:
            total += math.log(s * math.sqrt(2 * math.pi / g.size) / width)
    return total


def predictive_scale(sc: Scales, j: int, sid: str) -> float:
    """Standard deviation of pair j's log threshold about a model's prediction (tau0 at its
    middle value): for the posterior predictive check and the next test."""
    return math.sqrt(sc.sigma_sim[j] ** 2 + sc.sigma_gain ** 2 + TAU0[1] ** 2 + sc.d_fine.get(sid, 0.0) ** 2)

