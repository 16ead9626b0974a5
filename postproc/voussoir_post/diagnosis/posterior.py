"""Stage 4 of the diagnosis: posterior probabilities of the models, and what follows.

Each model's evidence is its likelihood integrated over its parameter prior (models.py),
times the records' factor; with the models' prior probabilities (models.model_prior)
that gives the posterior probability of `none`, of each effect and of each pair. Then:

- each model's parameters: posterior mean and 90 % credible interval;
- `adequate`: a check of the most probable model that can fail (`adequacy`): each
  specimen's brackets are predicted by the model fitted without that specimen (without
  the pair itself when there is one specimen); the probability integral transform of
  each bracket's midpoint under that prediction is uniform when the model is right, so
  the largest |Phi^-1(PIT)| of the J pairs is compared with its null distribution
  (Sidak: p = 1 - (1 - 2 Phi(-T))^J, exact for independent pairs and conservative for
  the positively dependent ones a shared discrepancy makes). No outlier process in it:
  an odd pair fails the check. Adequate when p >= 0.01;
- the held-out error of a model, leave one specimen out (one pair out with a single
  specimen), with its standard error over the pairs;
- the prior sensitivity: the probabilities with every continuous range scaled about its
  nominal value.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.special import logsumexp, ndtr, ndtri

from .bank import Bank
from .effects import nominal_value
from .likelihood import Scales, adjusted_mu, log_likelihood, predictive_sd, records_log_factor, scales
from .models import MODEL_IDS, ModelGrid, members, model_grid, model_prior
from .observations import Observations, PairObservation
from .pulses import pulse_log_likelihood

__all__ = ["ModelPosterior", "weighted_summary", "Posterior", "infer", "held_out", "relative_errors", "predicted_log",
           "ADEQUATE_P", "adequacy", "pit_values", "loso_folds", "prior_sensitivity", "SENSITIVITY_FACTORS"]

ADEQUATE_P = 0.01


@dataclass
class ModelPosterior:
    model_id: str
    grid: ModelGrid
    log_evidence: float  #: log of the likelihood integrated over the prior, records included
    weights: np.ndarray  #: posterior weight of each grid point
    probability: float = 0.0
    log_lik: np.ndarray | None = field(default=None, repr=False)  #: log likelihood of each grid point, records in

    def adjusted_mu(self, sc: Scales) -> np.ndarray:
        """Predicted log threshold in commanded amplitude at each grid point, per pair."""
        return adjusted_mu(self.grid, sc)

    def summary(self, name: str) -> tuple:
        """(posterior mean or mode, 5 %, 95 %) of one parameter."""
        v = self.grid.values[self.grid.names.index(name)]
        if v.dtype == object:
            cats = sorted(set(v))
            mass = {c: float(self.weights[v == c].sum()) for c in cats}
            mode = max(cats, key=lambda c: mass[c])
            return mode, mode, mode
        return weighted_summary(v, self.weights)


def weighted_summary(values: np.ndarray, weights: np.ndarray) -> tuple[float, float, float]:
    """(mean, 5 %, 95 %) of a parameter's values at grid points of these weights (summing
    to 1)."""
    order = np.argsort(values)
    cdf = np.cumsum(weights[order])
    q = lambda x: float(values[order][min(np.searchsorted(cdf, x), values.size - 1)])
    return float(weights @ values), q(0.05), q(0.95)


@dataclass
class Posterior:
    models: dict[str, ModelPosterior]
    scales: Scales
    pairs: list[PairObservation]
    probabilities: dict[str, float] = field(default_factory=dict)
    bank: Bank | None = field(default=None, repr=False)
    obs: Observations | None = field(default=None, repr=False)
    #: log factor of the crown records of each model (crown.py; empty without them)
    crown: dict[str, float] = field(default_factory=dict)

    def ranked(self) -> list[str]:
        return sorted(self.probabilities, key=lambda m: -self.probabilities[m])


def infer(bank: Bank, obs: Observations, pairs: list[PairObservation] | None = None,
          model_ids=MODEL_IDS) -> Posterior:
    """Posterior probabilities of the models given the pairs (default: every certain pair)."""
    pairs = obs.pairs if pairs is None else pairs
    sc = scales(bank, obs, pairs)
    models = {}
    for m in model_ids:
        grid = model_grid(m, bank, obs, pairs)
        lik = log_likelihood(grid, obs, pairs, sc)
        if obs.pulse_pairs and bank.pulses:
            lik = lik + pulse_log_likelihood(grid, obs.pulse_pairs, bank.pulses, obs.specimens)
        ll = lik + grid.log_prior
        z = float(logsumexp(ll))
        w = np.exp(ll - z) if math.isfinite(z) else np.full(grid.n, 1.0 / grid.n)
        records = records_log_factor("table_motion" in members(m), obs, pairs, sc)
        models[m] = ModelPosterior(m, grid, z + records, w, log_lik=lik + records)
    logs = np.array([math.log(model_prior(m)) + mp.log_evidence for m, mp in models.items()])
    probs = np.exp(logs - logsumexp(logs))
    for (m, mp), p in zip(models.items(), probs):
        mp.probability = float(p)
    return Posterior(models, sc, pairs, {m: mp.probability for m, mp in models.items()}, bank, obs)


def predicted_log(mp: ModelPosterior, sc: Scales) -> np.ndarray:
    """Posterior mean of each pair's predicted log threshold."""
    return mp.weights @ mp.adjusted_mu(sc)


def loso_folds(pairs: list[PairObservation]) -> list[list[int]]:
    """Leave one specimen out (one pair out with a single specimen)."""
    sids = sorted({p.specimen_id for p in pairs})
    if len(sids) > 1:
        return [[j for j, p in enumerate(pairs) if p.specimen_id == s] for s in sids]
    return [[j] for j in range(len(pairs))]


def pit_values(bank: Bank, obs: Observations, pairs: list[PairObservation], model_id: str) -> np.ndarray:
    """Each pair's probability integral transform under the model fitted without it (its
    specimen left out): P(log t <= log midpoint) under the held-out predictive, a mixture
    over the parameters' posterior of normals whose spread holds the simulator, emulator,
    table and the discrepancies at their middle values. For a bracket with no stand row
    below, the midpoint of the transform over (0, high]: PIT(high) / 2; for a pair whose
    tests all stood, over (low, inf): (1 + PIT(low)) / 2."""
    pit = np.full(len(pairs), math.nan)
    for test in loso_folds(pairs):
        train = [pairs[j] for j in range(len(pairs)) if j not in test] or [pairs[j] for j in test]
        weights = infer(bank, obs, train, (model_id,)).models[model_id].weights
        held = [pairs[j] for j in test]
        grid = model_grid(model_id, bank, obs, held)
        sc = scales(bank, obs, held)
        mu = adjusted_mu(grid, sc)
        sd = predictive_sd(grid, sc, held)
        for col, j in enumerate(test):
            p = pairs[j]
            if not p.collapsed:  # above the largest stand: the midpoint of the transform over (low, inf)
                cdf = 0.5 * (1.0 + float(weights @ ndtr((math.log(p.low_m) - mu[:, col]) / sd[:, col])))
            elif p.low_m > 0:
                cdf = float(weights @ ndtr((math.log(p.threshold_m) - mu[:, col]) / sd[:, col]))
            else:
                cdf = 0.5 * float(weights @ ndtr((math.log(p.high_m) - mu[:, col]) / sd[:, col]))
            pit[j] = cdf
    return pit


def adequacy(post: Posterior, model_id: str) -> float:
    """p-value of the check of a model (module docstring): Sidak's null of the largest
    |Phi^-1(PIT)| over the pairs."""
    pit = np.clip(pit_values(post.bank, post.obs, post.pairs, model_id), 1e-12, 1 - 1e-12)
    z = np.abs(ndtri(pit))
    t = float(np.max(z))
    return float(-np.expm1(pit.size * np.log1p(-2.0 * ndtr(-t)))) if t > 0 else 1.0


def relative_errors(pred: np.ndarray, pairs: list[PairObservation]) -> np.ndarray:
    """|predicted - measured| / measured threshold of each pair that has one (a pair whose
    tests all stood has no value to miss)."""
    meas = np.array([p.threshold_m for p in pairs])
    fell = np.isfinite(meas)
    return np.abs(pred[fell] - meas[fell]) / meas[fell]


def held_out(bank: Bank, obs: Observations, model_id: str) -> tuple[np.ndarray, float, float]:
    """Each pair's threshold [m] predicted by a model fitted without its specimen (without
    the pair itself when there is one specimen), and the mean relative error and its
    standard error over the pairs."""
    pairs = obs.pairs
    folds = loso_folds(pairs)
    pred = np.full(len(pairs), math.nan)
    for test in folds:
        train = [j for j in range(len(pairs)) if j not in test]
        if not train:
            train = test
        post = infer(bank, obs, [pairs[j] for j in train], (model_id,))
        mp = post.models[model_id]
        held = [pairs[j] for j in test]
        grid = model_grid(model_id, bank, obs, held)
        sc = scales(bank, obs, held)
        other = ModelPosterior(model_id, grid, 0.0, mp.weights)
        pred[test] = np.exp(predicted_log(other, sc))
    err = relative_errors(pred, pairs)
    se = float(np.std(err, ddof=1) / math.sqrt(err.size)) if err.size > 1 else math.nan
    return pred, float(np.mean(err)) if err.size else math.nan, se


#: The factors of the prior-sensitivity table (every continuous range about its nominal value).
SENSITIVITY_FACTORS = (0.6, 1.0, 1.5)


def prior_sensitivity(post: Posterior, factor: float) -> dict[str, float]:
    """The models' probabilities with every continuous parameter's prior range scaled by
    `factor` about its nominal value (friction nominal, inset 0, thickness factor 1, gain
    1). A narrower range keeps the grid points inside it; a wider one dilutes the prior
    over a range the bank did not simulate, whose likelihood is taken as nil there (a
    model whose posterior lies against an edge is then understated: see the flags)."""
    logs = {}
    for m, mp in post.models.items():
        keep = np.ones(mp.grid.n, bool)
        penalty = 0.0
        for name, v in zip(mp.grid.names, mp.grid.values):
            if v.dtype == object:
                continue
            nominal = nominal_value(name, post.obs.specimens[post.pairs[0].specimen_id])
            lo, hi = float(v.min()), float(v.max())
            if factor < 1.0:
                keep &= (v >= nominal - factor * (nominal - lo) - 1e-12) & (v <= nominal + factor * (hi - nominal) + 1e-12)
            else:
                penalty -= math.log(factor)
        if not keep.any():
            keep[:] = True
        logs[m] = math.log(model_prior(m)) + float(logsumexp(mp.log_lik[keep]) - math.log(keep.sum())) + penalty
    values = np.array(list(logs.values()))
    probs = np.exp(values - logsumexp(values))
    return dict(zip(logs, map(float, probs)))
