"""Stage 3b of the diagnosis: the likelihood of what was observed, for every grid point.

A pair's rows bracket its collapse threshold t (in commanded amplitude): low < t <= high.
Under a model at parameter theta,

    log t = mu(theta) - log g + delta_c + delta_s + eps,

- mu: the emulated threshold (models.py), with the emulator's variance v(theta);
- g: the table gain of the pair (1 when the model says the table followed the command;
  the pair's measured gain under table_motion with records), with a spread of
  ACTUATOR_SPREAD |log g| for what a gain leaves out of an actuator's dynamics;
- eps ~ N(0, s^2), s^2 = sigma_sim^2 + sigma_tol^2 + v(theta) + sigma_gain^2 + tau_p^2 (+
  the standard error of a measured gain): the simulator's own spread at that pair (the
  bank's replicas, pooled over the models that have them), what the specimens' build
  tolerance moves the pair's threshold by (models.tolerance_spread), the emulator's, the
  test-to-test scatter of the table gain that the records measure (1 % when there are
  none; at least 3 % when read from peak accelerations), and a discrepancy of each pair of its own: how
  far another code's threshold, or a laboratory's, lies from this kernel's at the same
  parameters (a chaotic band answers to every detail of a model; LMGC90's nominal
  thresholds of the test arches lie -4 to +10 % from Voussoir's at most pairs, up to
  +22 % at W118 and 3 Hz), tau_p integrated over TAU_PAIR (equal weights);
- delta_s ~ N(0, tau_s^2), shared by the pairs of a specimen: how far that specimen's
  build and set-up lie from its nominal model (a thickness or span a little off, a
  support offset), with tau_s^2 = tau0^2 + d_s^2, d_s the change of the specimen's nominal
  thresholds from dt to dt / 2, and tau0 integrated over TAU_SPECIMEN (equal weights);
- delta_c ~ N(0, tau_c^2), shared by every pair of the campaign: what any two codes or a
  code and a laboratory differ by over the whole campaign (and, for a model that divides
  by the measured gains, the transducer's calibration), tau_c integrated over
  TAU_CAMPAIGN (equal weights).

The two discrepancies are integrated on a grid of log shifts (SHIFTS): each specimen's
likelihood is tabulated against its total shift, convolved with delta_s's density and
then, over the specimens, with delta_c's. A cause is therefore named only where its
effect on the thresholds exceeds what these can make.

In a campaign of collapse rows only (no `stand` row anywhere), each pair's smallest
collapse, high, is read as what such a campaign is (docs/measured_data.md: "a campaign usually
ramps the amplitude ... until the arch falls"): the first collapse of a ramp whose stands were not
reported, of an unknown relative step r, log-uniform over ONE_SIDED_STEPS (1 % to 300 % of
the collapse amplitude). Given r, the threshold lies in (high / (1 + r), high] and high
has the density 1 / log(1 + r) in log over it (the ramp's phase is arbitrary), so the
pair's term is the mean over r of P(high / (1 + r) < t <= high) / log(1 + r). Read as a
bare upper bound (P(t <= high), as before), the data favour every model that predicts a
lower threshold, by as much as it predicts lower: on LMGC90's campaigns with collapse rows
only the 90 % sets held the truth in 0.76 of the draws (0.95 with stands; docs/diagnosis.md).
Where the campaign reports stands elsewhere, a pair without one fell at its ramp's first
test, and its bracket stays the upper bound P(t <= high).

Each pair's probability is mixed with an outlier model (probability 0.05: log t uniform
within a factor 3 of mu), so one odd pair cannot carry a verdict (the adequacy check of
posterior.py has no outliers: an odd pair makes it fail).

A two-sided bracket is a ramp's first collapse, and rocking is not monotone in amplitude:
a ramp finer than a threshold search can fall in a narrow window of collapse below the
threshold the search finds (early), or step over a window the search found and fall a
ramp step or more above it (late). LMGC90 in the laboratory loop: W156 at 3 Hz fell at 12.1
and 12.2 mm, stood from 12.3 to 14.9 mm and fell from 15.0 mm. The bracket's term is
(1 - e - l) P(low < t <= high) + e P(early) + l P(late), the early collapse at log t - u
(u uniform on (0, EARLY_SPAN)), the late one at log t + v (v uniform on (0, LATE_SPAN)),
each a closed form (_end_ramps); e and l by the pair's class, from the kernel's own fine
scan of it (early.py, which states where the constants come from). Without it, one early
collapse named a thinner ring on a truth of a stiff actuator at 0.91 (docs/diagnosis.md,
"Early collapses").

The table records add their own factor. Each test's measured gain reads the table
through its transducer, whose calibration may be off by a common factor 1 + b,
b ~ N(0, gain_sd^2) with gain_sd from table.csv (`displacement_gain_sd`, 1 % by
default): when the table followed the command, the gains are N(1 + b, s_g^2) with b
integrated out; under table_motion each pair has its own gain, uniform on 0.7 .. 1.4
(Laplace: the records pin it), and the bias is part of it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.special import log_ndtr, logsumexp, ndtr

from .bank import FINE_DT, Bank
from .early import EARLY_SPAN, LATE_SPAN, early_key, pair_early_prob
from .models import GAIN_RANGE, SIM_FLOOR, ModelGrid, pair_tolerance, sim_spread
from .observations import Observations, PairObservation

__all__ = ["Scales", "scales", "adjusted_mu", "pair_variance", "log_likelihood", "records_log_factor",
           "TAU_PAIR", "TAU_SPECIMEN", "TAU_CAMPAIGN", "SHIFTS", "OUTLIER_PROB", "OUTLIER_FACTOR", "GAIN_SD_DEFAULT",
           "ONE_SIDED_STEPS", "bracket_terms"]

TAU_PAIR = (0.01, 0.03, 0.06, 0.12)  #: discrepancy of each pair (relative), integrated with equal weights
TAU_SPECIMEN = (0.01, 0.03, 0.06)  #: discrepancy of a specimen (relative), integrated with equal weights
TAU_CAMPAIGN = (0.005, 0.01, 0.02, 0.04)  #: discrepancy of the campaign (relative), integrated with equal weights
SHIFTS = np.linspace(-0.45, 0.45, 61)  #: grid of log shifts on which the discrepancies are integrated
OUTLIER_PROB = 0.05
OUTLIER_FACTOR = 3.0  #: an outlier's threshold lies within this factor of the prediction
#: Nodes of the unreported relative ramp step r of a pair with collapse rows only,
#: log-uniform from 1 % to 300 % (equal weights in log r): at 300 % the unreported last stand
#: was a quarter of the collapse amplitude.
ONE_SIDED_STEPS = np.geomspace(0.01, 3.0, 11)
GAIN_SCATTER_DEFAULT = 0.01  #: test-to-test gain scatter assumed without records
GAIN_SCATTER_FLOOR = 0.003
PEAK_SCATTER_FLOOR = 0.03  #: scatter of a gain read from measured peak accelerations (no records)
GAIN_SD_DEFAULT = 0.01  #: the transducer's calibration without table.csv (docs/measured_data.md)
#: Under table_motion, the relative spread of a threshold about nominal / gain per unit of
#: |log gain|: a gain fitted to the displacement record does not carry the acceleration of
#: an actuator that rings near its resonance, and the further the table is from following
#: the command, the more of its motion a gain leaves out (LMGC90 truths of a lightly damped
#: 4.6 Hz actuator: thresholds 10 to 20 % below nominal / gain where the gain is 1.2 to 1.7).
ACTUATOR_SPREAD = 0.5


@dataclass
class Scales:
    """The scales of the likelihood, from the bank, the records and table.csv."""

    sigma_sim: np.ndarray  #: simulator spread of each pair (relative)
    sigma_gain: float  #: test-to-test table gain scatter (relative)
    d_fine: dict[str, float]  #: per specimen: RMS change of log threshold from dt to dt / 2
    gain_mean: np.ndarray  #: measured gain of each pair (1 without records)
    gain_se: np.ndarray  #: its standard error
    sigma_tol: np.ndarray  #: what the specimens' build tolerance moves each pair by (relative)
    #: (n_pairs, 2): each pair's P(its ramp's first collapse is early), P(late) (early.py,
    #: by the class of the kernel's scan of it)
    early_prob: np.ndarray
    gain_bias_sd: float = GAIN_SD_DEFAULT  #: the transducer's calibration (relative)


def scales(bank: Bank, obs: Observations, pairs: list[PairObservation]) -> Scales:
    fine = {}
    for sid, sb in bank.specimens.items():
        base = np.log(np.asarray(sb.thresholds["nominal"], dtype=float))
        half = np.log(np.asarray(sb.replicas.get(FINE_DT[0], sb.thresholds["nominal"]), dtype=float)) - base
        half = half[np.isfinite(half)]
        fine[sid] = float(np.sqrt(np.mean(half ** 2))) if half.size else 0.0
    sigma_sim = np.array([sim_spread(bank.specimens[p.specimen_id], p.frequency_hz) if p.specimen_id in bank.specimens
                          else SIM_FLOOR for p in pairs])
    within = [np.asarray(p.gains) - np.mean(p.gains) for p in pairs if len(p.gains) > 1]
    dof = sum(w.size - 1 for w in within)
    sigma_gain = (max(GAIN_SCATTER_FLOOR, float(np.sqrt(sum(float(w @ w) for w in within) / dof)))
                  if dof > 0 else GAIN_SCATTER_DEFAULT)
    if obs.gain_source == "peak_accel":  # the peak of a noisy record overstates the table's
        sigma_gain = max(sigma_gain, PEAK_SCATTER_FLOOR)
    gm = np.array([np.mean(p.gains) if p.gains else 1.0 for p in pairs])
    gse = np.array([sigma_gain / math.sqrt(len(p.gains)) if p.gains else 0.0 for p in pairs])
    sigma_tol = np.array([pair_tolerance(bank, obs, p) for p in pairs])
    early = np.array([pair_early_prob(bank.early.get(early_key(p.specimen_id, p.frequency_hz))) for p in pairs],
                     dtype=float).reshape(len(pairs), 2)
    return Scales(sigma_sim, sigma_gain, fine, gm, gse, sigma_tol, early, obs.gain_bias_sd)


def _log_bracket(lo: np.ndarray, hi: np.ndarray, m: np.ndarray, s: np.ndarray) -> np.ndarray:
    """log P(lo < x <= hi), x ~ N(m, s^2), stably (lo may be -inf)."""
    a = (lo - m) / s
    b = (hi - m) / s
    # P = Phi(b) - Phi(a) = Phi(-a) - Phi(-b); take the side away from the tails.
    sign = np.where(a > 0, -1.0, 1.0)
    la, lb = log_ndtr(sign * a), log_ndtr(sign * b)
    upper = sign < 0
    big, small = np.where(upper, la, lb), np.where(upper, lb, la)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = big + np.log1p(-np.exp(np.minimum(small - big, -1e-300)))
    return np.where(np.isfinite(big), out, -np.inf)


def _outlier_mass(lo, hi, m: np.ndarray) -> np.ndarray:
    """P(lo < log t <= hi) under the outlier model: log t uniform within a factor
    OUTLIER_FACTOR of the prediction m."""
    half = math.log(OUTLIER_FACTOR)
    return np.clip(np.minimum(hi, m + half) - np.maximum(lo, m - half), 0.0, None) / (2 * half)


def _log_outlier(lo: np.ndarray, hi: np.ndarray, m: np.ndarray) -> np.ndarray:
    return np.log(np.maximum(_outlier_mass(lo, hi, m), 1e-300))


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


def pair_variance(grid: ModelGrid, sc: Scales) -> np.ndarray:
    """(n_points, n_pairs) variance of eps: simulator, build tolerance, emulator and table scatter, and
    under table_motion the actuator's dynamics that a gain does not carry."""
    var = sc.sigma_sim[None, :] ** 2 + sc.sigma_tol[None, :] ** 2 + sc.sigma_gain ** 2 + grid.emu_var
    if grid.gain_per_pair:
        var = var + ((sc.gain_se / sc.gain_mean) ** 2)[None, :]
        var = var + (ACTUATOR_SPREAD * np.log(sc.gain_mean))[None, :] ** 2
    if grid.log_gain is not None:
        var = var + (ACTUATOR_SPREAD * grid.log_gain)[:, None] ** 2
    return var


def bracket_terms(pair: PairObservation, stands_unreported: bool) -> list[tuple[float, float, float]]:
    """(log low, log high, log weight) of the brackets a pair's term mixes: its own, or,
    in a campaign of collapse rows only, one per unreported ramp step r of
    ONE_SIDED_STEPS, weighted by 1 / log(1 + r) (module docstring)."""
    hi = math.log(pair.high_m)
    if pair.low_m > 0:
        return [(math.log(pair.low_m), hi, 0.0)]
    if not stands_unreported:  # its ramp fell at its first test: an upper bound
        return [(-math.inf, hi, 0.0)]
    widths = np.log1p(ONE_SIDED_STEPS)
    return [(hi - w, hi, -math.log(w) - math.log(widths.size)) for w in widths]


@lru_cache(maxsize=64)
def _shift_weights(tau: float) -> np.ndarray:
    """(shift, shift) matrix: the normalised density of one shift about another."""
    d = SHIFTS[:, None] - SHIFTS[None, :]
    w = np.exp(-0.5 * (d / tau) ** 2)
    return w / w.sum(axis=0, keepdims=True)


def _campaign_taus(grid: ModelGrid, sc: Scales) -> list[float]:
    extra = sc.gain_bias_sd ** 2 if grid.gain_per_pair else 0.0
    return [math.sqrt(t * t + extra) for t in TAU_CAMPAIGN]


def specimen_log_tables(pairs: list[PairObservation], terms_of: list[list[tuple[float, float, float]]],
                        mu: np.ndarray, var: np.ndarray, outlier: list[np.ndarray | None],
                        tau_pair: float, early_prob) -> dict[str, np.ndarray]:
    """Per specimen, log p(its brackets | theta, total shift) on SHIFTS: (n_points, n_shifts),
    each pair's own discrepancy (scale tau_pair) in its spread. `terms_of` holds each pair's
    bracket_terms, `mu` (n_points, n_pairs) its predictions (shifted over SHIFTS here),
    `outlier` its outlier term where it has one bracket (None where it mixes several:
    _log_ramp_mixture); none of them depends on tau_pair; `early_prob` each pair's
    probabilities (e, l) of an early and a late first collapse."""
    s = np.sqrt(var + tau_pair ** 2)
    out = {}
    for j, (p, terms) in enumerate(zip(pairs, terms_of)):
        if len(terms) == 1:
            (lo, hi, _), = terms
            normal = _log_bracket(np.float64(lo), np.float64(hi), mu[:, j, None] + SHIFTS[None, :], s[:, j, None])
            if math.isfinite(lo):
                normal = _with_early(normal, lo, hi, mu[:, j, None], s[:, j, None], tuple(early_prob[j]))
            mixed = np.logaddexp(math.log1p(-OUTLIER_PROB) + normal, math.log(OUTLIER_PROB) + outlier[j])
        else:
            mixed = _log_ramp_mixture(terms, mu[:, j, None], s[:, j, None], tuple(early_prob[j]))
        out[p.specimen_id] = out.get(p.specimen_id, 0.0) + mixed
    return out


#: G(z) = E[max(0, z + x)], x ~ N(0, 1) = z Phi(z) + phi(z), tabulated: G(z) = max(z, 0) +
#: H(|z|) with H(u) = G(-u) = phi(u) - u Phi(-u), linear between nodes G_STEP apart on
#: [0, G_REACH] (error below G_STEP^2 phi(0) / 8 = 5e-8) and 0 beyond (H(8) = 5e-17). A
#: table, not ndtr and exp: the early and late stories take a row of G at each end of every
#: bracket, and the table's few arithmetic passes cost a quarter of theirs (5 ns an element
#: against 21; bench/likelihood_cost.py).
G_STEP, G_REACH = 1.0 / 1024.0, 8.0
_H_NODES = np.arange(int(G_REACH / G_STEP) + 2) * G_STEP
_H_TABLE = np.exp(-0.5 * _H_NODES ** 2) / math.sqrt(2.0 * math.pi) - _H_NODES * ndtr(-_H_NODES)
_H_SLOPE = np.append(np.diff(_H_TABLE), 0.0)


def ramp_g(z: np.ndarray) -> np.ndarray:
    """G(z) = z Phi(z) + phi(z), from the table (see _H_TABLE)."""
    t = np.minimum(np.abs(z), G_REACH) * (1.0 / G_STEP)
    i = t.astype(np.intp)
    return np.maximum(z, 0.0) + _H_TABLE[i] + _H_SLOPE[i] * (t - i)


def _span_columns(span: float) -> int:
    """A story's span in columns of SHIFTS (early.py states the spans on its step)."""
    k = round(span / SHIFT_STEP)
    if abs(k * SHIFT_STEP - span) > 1e-12:
        raise ValueError(f"span {span} is not a multiple of the shift step {SHIFT_STEP}")
    return k


SHIFT_STEP = float(SHIFTS[1] - SHIFTS[0])
_EARLY_COLUMNS, _LATE_COLUMNS = _span_columns(EARLY_SPAN), _span_columns(LATE_SPAN)
#: SHIFTS widened by the early span below and the late span above: G at a threshold
#: EARLY_SPAN lower is G at the column that many steps to the left, and so on.
_SHIFTS_WIDE = SHIFTS[0] + SHIFT_STEP * np.arange(-_EARLY_COLUMNS, SHIFTS.size + _LATE_COLUMNS)


def _end_ramps(c: float, base: np.ndarray, s: np.ndarray, prob) -> np.ndarray:
    """One end's share, over s, of e P(early in (lo, hi]) + l P(late in (lo, hi]) at the
    predictions base + SHIFTS ((n, 1) each; prob = (e, l)):
    (e / EARLY_SPAN - l / LATE_SPAN) G(z_c) - e / EARLY_SPAN G(z_{c + EARLY_SPAN})
    + l / LATE_SPAN G(z_{c - LATE_SPAN}), z_x = (m - x) / s. The term is the low end's share
    less the high end's: a first collapse at log t + u, u uniform on (a, b), falls in
    (lo, hi] when log t lies in (lo - u, hi - u], a trapezoid in log t, four ramps
    max(0, log t - x) of normal mean s G(z_x). The three G's of an end are one row of G
    over _SHIFTS_WIDE, read at three offsets."""
    e, late = prob
    a, b = e / EARLY_SPAN, late / LATE_SPAN
    g = ramp_g((base + (_SHIFTS_WIDE - c)) / s)
    n = SHIFTS.size
    at, below, above = (g[:, _EARLY_COLUMNS:_EARLY_COLUMNS + n], g[:, :n],
                        g[:, _EARLY_COLUMNS + _LATE_COLUMNS:_EARLY_COLUMNS + _LATE_COLUMNS + n])
    return (a - b) * at - a * below + b * above


def _shifted_term(lo: float, at_hi: np.ndarray, base: np.ndarray, s: np.ndarray, prob) -> np.ndarray:
    """e P(early in (lo, hi]) + l P(late in (lo, hi]), given the high end's _end_ramps."""
    return np.maximum(s * (_end_ramps(lo, base, s, prob) - at_hi), 0.0)


def _with_early(log_normal: np.ndarray, lo: float, hi: float, base: np.ndarray, s: np.ndarray, prob) -> np.ndarray:
    """log[(1 - e - l) P(lo < t <= hi) + e P(early in (lo, hi]) + l P(late in (lo, hi])]:
    a two-sided bracket read as the ramp's first collapse, early with probability e, late
    (past a window the search found) with probability l; prob = (e, l)."""
    e, late = prob
    with np.errstate(divide="ignore"):
        shifted = np.log(_shifted_term(lo, _end_ramps(hi, base, s, prob), base, s, prob))
    return np.logaddexp(math.log1p(-e - late) + log_normal, shifted)


def _log_ramp_mixture(terms: list[tuple[float, float, float]], base: np.ndarray, s: np.ndarray, early_prob
                      ) -> np.ndarray:
    """log of the weighted sum over bracket_terms (one upper end) of each bracket's
    probability mixed with the outlier model, in linear space (one normal tail a term:
    the likelihood's costliest piece when every pair of a campaign has collapse rows only);
    floored at 1e-300, beyond which no grid point's probability matters. `base` (n, 1): the
    predictions, shifted over SHIFTS here."""
    hi = terms[0][1]
    m = base + SHIFTS[None, :]
    b = (hi - m) / s
    below_hi, above_hi = ndtr(b), ndtr(-b)
    total = np.zeros(np.broadcast_shapes(m.shape, s.shape))
    e, late = early_prob
    at_hi = _end_ramps(hi, base, s, early_prob)
    for lo, _, log_w in terms:
        a = (lo - m) / s
        tail = ndtr(-np.abs(a))  # the small side, exactly: S(a) where a > 0, Phi(a) elsewhere
        normal = np.where(a > 0, tail - above_hi, below_hi - tail)
        normal = (1.0 - e - late) * np.clip(normal, 0.0, None) + _shifted_term(lo, at_hi, base, s, early_prob)
        total += math.exp(log_w) * ((1.0 - OUTLIER_PROB) * normal + OUTLIER_PROB * _outlier_mass(lo, hi, m))
    return np.log(np.maximum(total, 1e-300))


def _log_matmul(log_table: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """log of exp(log_table) @ weights, stably: (n_points, n_columns)."""
    top = np.max(log_table, axis=1, keepdims=True)
    top = np.where(np.isfinite(top), top, 0.0)
    with np.errstate(divide="ignore"):
        return np.log(np.exp(log_table - top) @ weights) + top


def log_likelihood(grid: ModelGrid, obs: Observations, pairs: list[PairObservation], sc: Scales) -> np.ndarray:
    """log p(brackets | model, theta) at every grid point (records apart), the pair,
    specimen and campaign discrepancies integrated."""
    centre = SHIFTS.size // 2
    prior_c = np.column_stack([_shift_weights(t)[:, centre] for t in _campaign_taus(grid, sc)])
    mu = adjusted_mu(grid, sc)
    shifted = [mu[:, j, None] + SHIFTS[None, :] for j in range(len(pairs))]
    terms_of = [bracket_terms(p, obs.stands_unreported) for p in pairs]
    outlier = [_log_outlier(t[0][0], t[0][1], shifted[j]) if len(t) == 1 else None for j, t in enumerate(terms_of)]
    var = pair_variance(grid, sc)
    per_level = []
    for tau_pair in TAU_PAIR:
        total = None
        for sid, table in specimen_log_tables(pairs, terms_of, mu, var, outlier, tau_pair, sc.early_prob).items():
            taus = [round(math.sqrt(t0 * t0 + sc.d_fine.get(sid, 0.0) ** 2), 12) for t0 in TAU_SPECIMEN]
            # Every specimen level at once: (n, shifts x levels).
            conv = _log_matmul(table, np.hstack([_shift_weights(t) for t in taus]))
            total = conv if total is None else total + conv
        per_level += [_log_matmul(total[:, k * SHIFTS.size:(k + 1) * SHIFTS.size], prior_c)
                      for k in range(len(TAU_SPECIMEN))]
    per_level = np.hstack(per_level)
    return logsumexp(per_level, axis=1) - math.log(per_level.shape[1])


def records_log_factor(table_motion: bool, obs: Observations, pairs: list[PairObservation], sc: Scales) -> float:
    """log p(measured gains | model): the table followed the command (every gain
    N(1 + b, s^2), b the transducer's common bias, integrated), or each pair has its own
    gain, uniform on 0.7 .. 1.4, integrated (Laplace: the records pin it)."""
    if obs.gain_source == "none":
        return 0.0
    s = sc.sigma_gain
    g = np.concatenate([np.asarray(p.gains, float) for p in pairs]) if pairs else np.zeros(0)
    if g.size == 0:
        return 0.0
    if not table_motion:
        # N(1 + b, s^2) each, b ~ N(0, beta): covariance s^2 I + beta 1 1^T (Sherman-Morrison).
        r = g - 1.0
        n, beta = g.size, sc.gain_bias_sd ** 2
        return float(-0.5 * n * math.log(2 * math.pi * s * s) - 0.5 * math.log1p(n * beta / (s * s))
                     - 0.5 * (r @ r) / (s * s) + 0.5 * beta * r.sum() ** 2 / (s * s * (s * s + n * beta)))
    total = 0.0
    width = GAIN_RANGE[1] - GAIN_RANGE[0]
    for p in pairs:
        gp = np.asarray(p.gains, dtype=float)
        if gp.size == 0:
            continue
        total += float(np.sum(-0.5 * ((gp - gp.mean()) / s) ** 2 - math.log(s * math.sqrt(2 * math.pi))))
        total += math.log(s * math.sqrt(2 * math.pi / gp.size) / width)
    return total


def predictive_sd(grid: ModelGrid, sc: Scales, pairs: list[PairObservation]) -> np.ndarray:
    """(n_points, n_pairs) standard deviation of a pair's log threshold about a model's
    prediction at each grid point, the discrepancies at their middle values."""
    tau_s = np.array([TAU_SPECIMEN[1] ** 2 + sc.d_fine.get(p.specimen_id, 0.0) ** 2 for p in pairs])
    tau_c = _campaign_taus(grid, sc)[len(TAU_CAMPAIGN) // 2] ** 2
    return np.sqrt(pair_variance(grid, sc) + TAU_PAIR[1] ** 2 + tau_s[None, :] + tau_c)
