"""Rates of the diagnosis over noise draws: what the replay tests assert and the
calibration study reports, and the paired test that judges a change of the simulations.

A draw is right or wrong against its truth's model id (`outside` for a truth outside the
catalogue, which no verdict can name rightly):

- named: the verdict names a model (a cause, a pair, or `none`) at probability 0.9 or more;
- in the set: the truth is the named model or one of the rivals (the 90 % set);
- wrong: a model other than the truth is named.

Brackets standing off by a gap (the generator's) are weaker than the catalogue's rigid
ones: for a truth `base_restraint`, a pair of base_restraint with another effect (which
weakens the rigid brackets) names it too.
"""

from __future__ import annotations

from typing import Callable

import numpy as np
from scipy.stats import binomtest

from .bank import Bank
from .decision import decide, flags
from .models import MODEL_IDS, members, model_prior
from .posterior import infer

__all__ = ["covers", "outcome", "draw_outcomes", "mcnemar", "truth_prior", "parameter_cdf", "power"]


def covers(model_id: str, truth: str) -> bool:
    """Whether naming `model_id` names the truth (module docstring)."""
    return model_id == truth or (truth == "base_restraint" and "base_restraint" in members(model_id))


def truth_prior(truth: str) -> float:
    """The prior probability of what `covers` counts as the truth (0 outside the catalogue)."""
    return sum(model_prior(m) for m in MODEL_IDS if covers(m, truth))


def parameter_cdf(post, truth: str, values: dict) -> dict[str, float]:
    """The posterior CDF, under the truth's model, of each continuous parameter at its true
    value (a simulation-based calibration: uniform over draws when the posterior is right)."""
    if truth not in post.models:
        return {}
    mp = post.models[truth]
    out = {}
    for name, v in zip(mp.grid.names, mp.grid.values):
        if v.dtype == object or name not in values:
            continue
        below = float(mp.weights[v < values[name]].sum())
        at = float(mp.weights[v == values[name]].sum())
        out[name] = below + 0.5 * at
    return out


def outcome(bank: Bank, obs, truth: str, truth_values: dict | None = None) -> dict:
    post = infer(bank, obs)
    d = decide(post)
    named = d.verdict != "inconclusive"
    chosen = [d.top] if named else d.rivals
    right = covers(d.top, truth)
    return {"truth": truth, "verdict": d.verdict, "top": d.top, "p_top": post.probabilities[d.top],
            "p_truth": sum(p for m, p in post.probabilities.items() if covers(m, truth)),
            "prior_truth": truth_prior(truth),
            "top_right": right, "adequate": d.adequate, "p_value": d.p_value, "named": named,
            "in_set": any(covers(m, truth) for m in chosen), "set": list(chosen), "set_size": len(chosen),
            "right_named": named and right,
            "wrong_named": named and not right, "probabilities": post.probabilities,
            "flags": flags(post, d, d.shown), "cdf": parameter_cdf(post, truth, truth_values or {})}


def draw_outcomes(bank: Bank, omap: dict, draws: int, draw: Callable, seed: int = 2026) -> list[dict]:
    """The outcome of each of `draws` noise draws of one stored truth (draw(omap, rng)
    makes the observations of one draw; the seeds are fixed, so two banks meet the same
    draws)."""
    out = []
    for k in range(draws):
        obs = draw(omap, np.random.default_rng([seed, k]))
        out.append(outcome(bank, obs, omap["truth_model"]))
    return out


def mcnemar(before: list[bool], after: list[bool]) -> dict:
    """Exact McNemar test of paired draws: `better` draws right only after the change,
    `worse` right only before; p-value of the two-sided binomial test of the discordant
    draws."""
    a, b = np.asarray(before, bool), np.asarray(after, bool)
    worse = int(np.sum(a & ~b))
    better = int(np.sum(~a & b))
    n = worse + better
    p = 1.0 if n == 0 else float(binomtest(better, n, 0.5).pvalue)
    return {"better": better, "worse": worse, "p_value": p}


def power(outcomes: list[dict]) -> float:
    """The mean of log P(truth) - log prior(truth) over draws of truths in the catalogue:
    0 for a diagnosis that ignores the data, positive when the data move it toward the
    truth (an information gain, in nats)."""
    inside = [o for o in outcomes if o["prior_truth"] > 0]
    return float(np.mean([np.log(max(o["p_truth"], 1e-300)) - np.log(o["prior_truth"]) for o in inside]))
