"""Stage 5 of the diagnosis: the verdict of docs/measured_data.md (version 3) from the
posterior probabilities.

- a cause (one effect, or `combined` for a pair) is named when its probability is at
  least 0.9 and the most probable model is adequate (posterior predictive check);
- `none` when the nominal model's probability is at least 0.9;
- otherwise `inconclusive`, with `rivals` the most probable models, best first, whose
  probabilities first reach 0.9 together (empty when no model is adequate).

No margin and no cut-off on a score decides: 0.9 is the contract's, and the calibration
study (bench/diagnosis_calibration.sh, docs/diagnosis.md) checks that causes named at
0.9 are right at least as often as that.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .models import members
from .posterior import ADEQUATE_P, Posterior, adequacy

__all__ = ["NAME_AT", "Decision", "decide", "credible_set"]

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
