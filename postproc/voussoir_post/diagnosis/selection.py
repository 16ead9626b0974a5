"""Fitting and judging the candidate effects on the measured thresholds.

Each candidate's parameter is fitted by leave-one-specimen-out cross-validation
(leave-one-pair-out with a single specimen): the error that counts is the error on the
specimens held out of the fit. Models are compared by the likelihood of the measured
thresholds under their held-out predictions, with Student-t errors (heavy tails, so that
one odd pair cannot carry a verdict alone).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..readers.campaign import MeasuredThreshold, Specimen
from .actuator import TableEvidence
from .effects import Effect, Variant
from .settings import DiagnosisSettings

__all__ = ["PairData", "CandidateResult", "T_DOF", "STRONG_EVIDENCE", "neg_log_likelihood", "predictions",
           "errors", "mean_error", "fit", "predictions_loss", "held_out_loss", "clearly_better", "evaluate_candidate", "folds"]

#: Degrees of freedom of the Student-t likelihood of a threshold: heavy tails, so that
#: one odd pair (a safe island, a chaotic run) cannot carry the verdict alone.
T_DOF = 3.0
#: Twice the log-likelihood ratio that counts as strong evidence (Kass and Raftery 1995).
STRONG_EVIDENCE = 6.0


@dataclass
class PairData:
    """A measured pair with the simulated thresholds of every variant."""

    measured: MeasuredThreshold
    spec: Specimen
    resolution: float  #: relative half-width of the bracket (or the default)
    sigma: float = 0.05  #: relative uncertainty of the measured threshold (resolution and floor)
    simulated: dict = field(default_factory=dict)  #: Variant -> threshold [m]
    #: The table gain measured on this pair's own records over the campaign's mean gain
    #: (1 without records): an actuator's gain depends on the frequency.
    gain_shape: float = 1.0


@dataclass
class CandidateResult:
    effect: str  #: an effect id, or "id1+id2" for two effects together
    value: object  #: fitted on all pairs
    low: object
    high: object
    cv_error: float  #: mean held-out relative error
    in_sample_error: float
    fold_values: list
    admissible: bool = True
    reason: str = ""
    hinge_match: float | None = None  #: fraction of the observed hinges reproduced
    hinge_score: float | None = None  #: F1 of observed and simulated hinges (false ones count)
    per_pair: list = field(default_factory=list)  #: held-out predictions [m]
    eff: Effect | None = None  #: the effect (or pair of effects) the result is of

    @property
    def members(self) -> tuple[str, ...]:
        """The effect ids: one, or two for a pair."""
        return tuple(self.effect.split("+"))


def rel_error(pred_m: float, meas_m: float) -> float:
    return abs(pred_m - meas_m) / meas_m


def neg_log_likelihood(pred_m, meas_m, sigma) -> float:
    """Student-t negative log-likelihood of a predicted threshold, up to a constant."""
    if not math.isfinite(pred_m):
        pred_m = 10.0 * meas_m  # no collapse found: as bad as a prediction ten times off
    z = (pred_m - meas_m) / (meas_m * sigma)
    return 0.5 * (T_DOF + 1.0) * math.log1p(z * z / T_DOF)


def predictions(pairs: list[PairData], eff: Effect | None, value) -> list[float]:
    """Threshold [m] of every pair under one model (effect None: the nominal one)."""
    if eff is None:
        return [p.simulated[Variant()] for p in pairs]
    return [eff.predict(p, value) for p in pairs]


def errors(preds: list[float], pairs: list[PairData]) -> list[float]:
    """Relative threshold errors (a prediction without collapse counts 1)."""
    return [rel_error(pred, p.measured.threshold_m) if math.isfinite(pred) else 1.0 for pred, p in zip(preds, pairs)]


def mean_error(pairs: list[PairData], eff: Effect | None, value) -> float:
    """Mean relative threshold error of one model."""
    errs = errors(predictions(pairs, eff, value), pairs)
    return float(np.mean(errs)) if errs else math.nan


def predictions_loss(preds: list[float], pairs: list[PairData]) -> float:
    """Negative log-likelihood of the measured thresholds under predictions `preds` [m]."""
    total = 0.0
    for pred, p in zip(preds, pairs):
        total += neg_log_likelihood(pred, p.measured.threshold_m, p.sigma)
    return total


def loss(pairs: list[PairData], eff: Effect | None, value) -> float:
    """Negative log-likelihood of the measured thresholds under one model."""
    return predictions_loss(predictions(pairs, eff, value), pairs)


def fit(pairs: list[PairData], e: Effect, settings: DiagnosisSettings, fixed=None):
    """Best parameter on `pairs` (or `fixed`, measured elsewhere) and the near-optimal
    set. Ties are broken towards the nominal model (the smallest change that explains
    the data)."""
    if fixed is not None:
        return fixed, [fixed]
    values = e.candidate_values(pairs, settings)
    losses = np.array([loss(pairs, e, v) for v in values])
    best = float(np.nanmin(losses))
    # Parsimony: among the values within a hair of the best, the one closest to nominal.
    choice = e.choose([v for v, x in zip(values, losses) if x <= best + 1e-6], pairs)
    # The values the data cannot tell from the best (log-likelihood within 1/2: about
    # one standard deviation).
    near = [v for v, x in zip(values, losses) if x <= best + 0.5]
    return choice, near


def folds(pairs: list[PairData], by_pair: bool = False) -> list[tuple[list[int], list[int]]]:
    """Leave one specimen out; with one specimen (or `by_pair`), leave one pair out; with
    one pair, no hold-out (train = test)."""
    specimens = sorted({p.spec.specimen_id for p in pairs})
    if len(specimens) > 1 and not by_pair:
        return [([i for i, p in enumerate(pairs) if p.spec.specimen_id != s],
                 [i for i, p in enumerate(pairs) if p.spec.specimen_id == s]) for s in specimens]
    if len(pairs) > 1:
        return [([j for j in range(len(pairs)) if j != i], [i]) for i in range(len(pairs))]
    return [([0], [0])]


def evaluate_candidate(pairs: list[PairData], e: Effect, settings: DiagnosisSettings,
                       table: TableEvidence, by_pair: bool = False) -> CandidateResult:
    """Fit one effect (or pair) in every fold and predict the pairs held out of it."""
    fixed = e.fixed_value(table)
    held = [math.nan] * len(pairs)
    fold_values = []
    for train, test in folds(pairs, by_pair):
        value, _ = fit([pairs[i] for i in train], e, settings, fixed)
        fold_values.append(value)
        for i in test:
            held[i] = e.predict(pairs[i], value)
    value, near = fit(pairs, e, settings, fixed)
    cv = float(np.mean(errors(held, pairs)))
    low, high = e.interval(value, fold_values, near, table)
    return CandidateResult(e.id, value, low, high, cv, mean_error(pairs, e, value), fold_values,
                           per_pair=held, eff=e)


def held_out_loss(c: CandidateResult | None, pairs: list[PairData]) -> float:
    """Negative log-likelihood of the measured thresholds under a candidate's held-out
    predictions (None: the nominal model)."""
    preds = [p.simulated.get(Variant(), math.nan) for p in pairs] if c is None else c.per_pair
    return predictions_loss(preds, pairs)


def clearly_better(better: float, worse: float) -> bool:
    """Whether held-out negative log-likelihood `better` beats `worse` by strong evidence."""
    return 2.0 * (worse - better) > STRONG_EVIDENCE
