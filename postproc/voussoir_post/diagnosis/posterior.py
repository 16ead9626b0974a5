"""Stage 4 of the diagnosis: posterior probabilities of the models, and what follows.

Each model's evidence is its likelihood integrated over its parameter prior (models.py),
times the records' factor; with the models' prior probabilities (models.model_prior)
that gives the posterior probability of `none`, of each effect and of each pair. Then:

- each model's parameters: posterior mean and 90 % credible interval;
- `adequate`: a posterior predictive check of the most probable model (replicated
  thresholds drawn from its posterior, compared with the measured ones by their
  standardised squared distance; adequate when p >= 0.01);
- the held-out error of a model, leave one specimen out (one pair out with a single
  specimen), with its standard error over the pairs;
- how differently the rivals predict each tested pair, in units of their predictive
  spread, weighted by their probabilities (next_test.py weighs it against new
  frequencies).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.special import logsumexp

from .bank import Bank
from .likelihood import (OUTLIER_FACTOR, OUTLIER_PROB, TAU0, Scales, adjusted_mu, log_likelihood, predictive_scale,
                         records_log_factor, scales)
from .models import MODEL_IDS, ModelGrid, members, model_grid, model_prior
from .observations import Observations, PairObservation

__all__ = ["ModelPosterior", "Posterior", "infer", "held_out", "tested_separation", "predicted_log", "ADEQUATE_P"]

ADEQUATE_P = 0.01
PPC_DRAWS = 400


@dataclass
class ModelPosterior:
    model_id: str
    grid: ModelGrid
    log_evidence: float  #: log of the likelihood integrated over the prior, records included
    weights: np.ndarray  #: posterior weight of each grid point
    probability: float = 0.0

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
        order = np.argsort(v)
        cdf = np.cumsum(self.weights[order])
        q = lambda x: float(v[order][min(np.searchsorted(cdf, x), v.size - 1)])
        return float(self.weights @ v), q(0.05), q(0.95)


@dataclass
class Posterior:
    models: dict[str, ModelPosterior]
    scales: Scales
    pairs: list[PairObservation]
    probabilities: dict[str, float] = field(default_factory=dict)

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
        ll = log_likelihood(grid, obs, pairs, sc) + grid.log_prior
        z = float(logsumexp(ll))
        w = np.exp(ll - z) if math.isfinite(z) else np.full(grid.n, 1.0 / grid.n)
        z += records_log_factor("table_motion" in members(m), obs, pairs, sc)
        models[m] = ModelPosterior(m, grid, z, w)
    logs = np.array([math.log(model_prior(m)) + mp.log_evidence for m, mp in models.items()])
    probs = np.exp(logs - logsumexp(logs))
    for (m, mp), p in zip(models.items(), probs):
        mp.probability = float(p)
    return Posterior(models, sc, pairs, {m: mp.probability for m, mp in models.items()})


def predicted_log(mp: ModelPosterior, sc: Scales) -> np.ndarray:
    """Posterior mean of each pair's predicted log threshold."""
    return mp.weights @ mp.adjusted_mu(sc)


def adequacy(post: Posterior, model_id: str, seed: int = 0) -> float:
    """Posterior predictive p-value of a model: how often a replicated campaign lies
    farther from the model than the measured one (standardised squared distance of the
    log thresholds, bracket widths included)."""
    mp = post.models[model_id]
    sc = post.scales
    rng = np.random.default_rng(seed)
    mu = mp.adjusted_mu(sc)
    mid = np.log([p.threshold_m for p in post.pairs])
    width = np.array([math.log(p.high_m / p.low_m) if p.low_m > 0 else 0.1 for p in post.pairs])
    sids = [p.specimen_id for p in post.pairs]
    spread = np.array([predictive_scale(sc, j, s) for j, s in enumerate(sids)])
    scale2 = spread ** 2 + width ** 2 / 12
    idx = rng.choice(mp.grid.n, size=PPC_DRAWS, p=mp.weights)
    specimens = sorted(set(sids))
    col = np.array([specimens.index(s) for s in sids])
    m = mu[idx]  # (draws, pairs)
    noise = np.sqrt(sc.sigma_sim ** 2 + sc.sigma_gain ** 2)
    tau = np.array([math.sqrt(TAU0[1] ** 2 + sc.d_fine.get(s, 0.0) ** 2) for s in specimens])
    delta = rng.normal(0.0, 1.0, (PPC_DRAWS, len(specimens))) * tau[None, :]
    rep = (m + delta[:, col] + rng.normal(0.0, 1.0, m.shape) * noise[None, :]
           + width[None, :] * (rng.random(m.shape) - 0.5))
    out = rng.random(m.shape) < OUTLIER_PROB
    rep = np.where(out, m + rng.uniform(-1, 1, m.shape) * math.log(OUTLIER_FACTOR), rep)
    t_obs = np.sum((mid[None, :] - m) ** 2 / scale2[None, :], axis=1)
    t_rep = np.sum((rep - m) ** 2 / scale2[None, :], axis=1)
    return float(np.mean(t_rep >= t_obs))


def held_out(bank: Bank, obs: Observations, model_id: str) -> tuple[np.ndarray, float, float]:
    """Each pair's threshold [m] predicted by a model fitted without its specimen (without
    the pair itself when there is one specimen), and the mean relative error and its
    standard error over the pairs."""
    pairs = obs.pairs
    sids = sorted({p.specimen_id for p in pairs})
    folds = ([[j for j, p in enumerate(pairs) if p.specimen_id == s] for s in sids] if len(sids) > 1
             else [[j] for j in range(len(pairs))])
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
    meas = np.array([p.threshold_m for p in pairs])
    err = np.abs(pred - meas) / meas
    se = float(np.std(err, ddof=1) / math.sqrt(err.size)) if err.size > 1 else math.nan
    return pred, float(np.mean(err)), se


def tested_separation(post: Posterior, rivals: list[str]) -> np.ndarray:
    """How differently the rivals predict each tested pair: the sum over pairs of rivals
    of p_a p_b (m_a - m_b)^2 / (v_a + v_b), m the posterior mean log threshold and v its
    predictive variance (simulator, table, discrepancy and the parameters' own spread)."""
    sc = post.scales
    means = {m: predicted_log(post.models[m], sc) for m in rivals}
    var = {}
    for m in rivals:
        mu = post.models[m].adjusted_mu(sc)
        var[m] = post.models[m].weights @ (mu - means[m][None, :]) ** 2
    base = np.array([predictive_scale(sc, j, p.specimen_id) ** 2 for j, p in enumerate(post.pairs)])
    score = np.zeros(len(post.pairs))
    for i, a in enumerate(rivals):
        for b in rivals[i + 1:]:
            pa, pb = post.probabilities[a], post.probabilities[b]
            score += pa * pb * (means[a] - means[b]) ** 2 / (2 * base + var[a] + var[b])
    return score
