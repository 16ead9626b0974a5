"""Stage 5 of the diagnosis: the verdict of docs/measured_data.md (version 4) from the
posterior probabilities, and the flags a reader must know before trusting the numbers.

- a cause (one effect, or `combined` for a pair) is named when its probability is at
  least 0.9 and the most probable model is adequate (posterior.adequacy, a check that
  can fail);
- `none` when the nominal model's probability is at least 0.9;
- otherwise `inconclusive`, with `rivals` the most probable models, best first, whose
  probabilities first reach 0.9 together (empty when no model is adequate).

No margin and no cut-off on a score decides: 0.9 is the contract's, and the calibration
study (bench/diagnosis_calibration.sh, docs/diagnosis.md) checks that causes named at
0.9 are right at least as often as that.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .models import members
from .posterior import ADEQUATE_P, Posterior, adequacy

__all__ = ["NAME_AT", "Decision", "decide", "credible_set", "to_separate", "flags", "prior_bound", "EDGE_FRACTION",
           "EDGE_MASS"]

EDGE_FRACTION = 0.05  #: the outer part of a prior's range that counts as its edge
EDGE_MASS = 0.15  #: posterior mass there (three times the prior's) that flags the parameter
#: A common gain offset of the records within this many transducer calibrations is a
#: possible sensor bias (docs/measured_data.md).
BIAS_CALIBRATIONS = 3.0

NAME_AT = 0.9  #: probability at which a cause is named, and mass of the rivals' set


@dataclass
class Decision:
    verdict: str
    effects: list[str]  #: of the named cause
    rivals: list[str]  #: model ids, best first (inconclusive)
    adequate: bool
    p_value: float  #: posterior predictive p-value of the most probable model
    top: str  #: the most probable model
    probabilities: dict[str, float] = field(default_factory=dict)

    @property
    def shown(self) -> str | None:
        """The model whose parameters and held-out error are reported (None: the nominal)."""
        return None if self.top == "none" or not self.adequate else self.top


def credible_set(probabilities: dict[str, float], mass: float = NAME_AT) -> list[str]:
    """The most probable models, best first, whose probabilities first reach `mass`."""
    out, total = [], 0.0
    for m in sorted(probabilities, key=lambda k: -probabilities[k]):
        out.append(m)
        total += probabilities[m]
        if total >= mass - 1e-12:
            break
    return out


def decide(post: Posterior) -> Decision:
    probs = post.probabilities
    top = max(probs, key=lambda m: probs[m])
    p = adequacy(post, top)
    adequate = p >= ADEQUATE_P
    if not adequate:
        return Decision("inconclusive", [], [], False, p, top, probs)
    if probs[top] >= NAME_AT:
        eff = list(members(top))
        verdict = "none" if not eff else (eff[0] if len(eff) == 1 else "combined")
        return Decision(verdict, eff, [], True, p, top, probs)
    return Decision("inconclusive", [], credible_set(probs), True, p, top, probs)


def to_separate(decision: Decision) -> list[str]:
    """The models the next test is to separate: the rivals of an inconclusive verdict;
    when the most probable model fails its check (no rivals: nothing in the catalogue
    explains the campaign), the models whose credible set the rivals would have been, so
    that the test says which of them comes nearest and whether the misfit repeats; none
    when a cause (or `none`) is named."""
    if decision.verdict != "inconclusive":
        return []
    return decision.rivals if decision.adequate else credible_set(decision.probabilities)


#: The name of each effect's parameter in diagnosis.json.
PARAMETER_NAMES = {"contact_edges": "inset_m", "friction": "friction", "geometry": "thickness_factor",
                   "table_motion": "accel_gain"}


def prior_bound(post: Posterior, model_id: str) -> list[str]:
    """The parameters of a model whose posterior lies against an edge of its prior: more
    than EDGE_MASS of the posterior in the outer EDGE_FRACTION of the range at one end."""
    mp = post.models[model_id]
    out = []
    for name, v in zip(mp.grid.names, mp.grid.values):
        if v.dtype == object:
            continue
        lo, hi = float(v.min()), float(v.max())
        edge = EDGE_FRACTION * (hi - lo)
        if mp.weights[v <= lo + edge].sum() > EDGE_MASS or mp.weights[v >= hi - edge].sum() > EDGE_MASS:
            out.append(PARAMETER_NAMES[name])
    return out


def flags(post: Posterior, decision: Decision, reported: str | None) -> list[str]:
    """diagnosis.json's `flags` (docs/measured_data.md version 4)."""
    out = []
    if any(p.low_m <= 0 for p in post.pairs):
        out.append("one_sided")
    if reported and reported != "none":
        out += [f"prior_bound:{name}" for name in prior_bound(post, reported)]
    gains = np.concatenate([np.asarray(p.gains, float) for p in post.pairs]) if post.pairs else np.zeros(0)
    sc = post.scales
    if gains.size > 1 and "table_motion" not in decision.effects:
        offset = float(gains.mean() - 1.0)
        se = sc.sigma_gain / math.sqrt(gains.size)
        if abs(offset) > 2.0 * se and abs(offset) <= BIAS_CALIBRATIONS * sc.gain_bias_sd:
            out.append("sensor_bias")
    if not decision.adequate:
        out.append("inadequate")
    return out
