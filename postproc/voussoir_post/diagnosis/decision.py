"""The verdict of shared/MEASURED_DATA.md from the candidates' held-out predictions.

`none` when the nominal model already agrees within the measurement resolution;
otherwise the candidate with the best held-out likelihood, provided it beats the nominal
model by strong evidence and no other candidate comes within strong evidence of it,
unless the records or the hinges separate them; else `inconclusive`, naming the rivals.
A pair of effects is a candidate only where it beats each of its members alone by strong
evidence: otherwise the simpler story wins.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .actuator import TableEvidence
from .selection import CandidateResult, PairData, clearly_better, held_out_loss, mean_error

#: A named cause must leave a mean held-out error within this many times the mean
#: relative uncertainty of a measured threshold (sigma: resolution, search tolerance and
#: the 3 % floor): about the 95 % band of a single threshold.
ADEQUATE_SIGMAS = 2.0
#: Rivals are separated by their hinges when one's hinge F1 beats every other's by this.
HINGE_F1_MARGIN = 0.15

__all__ = ["ADEQUATE_SIGMAS", "HINGE_F1_MARGIN", "Decision", "decide", "hinge_match", "hinge_score", "verdict_of"]


@dataclass
class Decision:
    verdict: str
    chosen: CandidateResult | None
    rivals: list[str]  #: for `inconclusive`: the effects the data cannot separate, best first
    notes: str
    best_rival: CandidateResult | None = None  #: the first of the rivals (its held-out result is `extended`)
    rival_results: list = field(default_factory=list)  #: the rivals' candidates, best first (a pair is one)
    #: For a named cause that the thresholds alone did not separate from others: what did.
    separation: str = ""


def hinge_match(observed: dict[str, set], simulated: dict[str, set]) -> float | None:
    """The spec's `hinge_match`: the fraction of observed hinges (joint and side) that
    the model opens in the same test (recall: a model opening every hinge scores 1)."""
    total = sum(len(o) for o in observed.values())
    if total == 0:
        return None
    hit = sum(len(o & simulated.get(tid, set())) for tid, o in observed.items())
    return hit / total


def hinge_score(observed: dict[str, set], simulated: dict[str, set]) -> float | None:
    """F1 of the hinges, over all tests with observed hinges: 2 |O & S| / (|O| + |S|).
    A missed hinge and a false one (opened by the model, not seen) cost the same; this,
    not the recall, is what separates candidates."""
    total = sum(len(o) + len(simulated.get(tid, set())) for tid, o in observed.items())
    if not any(observed.values()):
        return None
    hit = sum(len(o & simulated.get(tid, set())) for tid, o in observed.items())
    return 2.0 * hit / total


def verdict_of(c: CandidateResult) -> str:
    """The verdict that names a candidate: its effect, or `combined` for a pair."""
    return "combined" if len(c.members) > 1 else c.effect


def _rival_ids(group: list[CandidateResult]) -> list[str]:
    """The effect ids of a list of rivals, best first, a pair giving both of its own."""
    out: list[str] = []
    for c in group:
        out += [e for e in c.members if e not in out]
    return out


def _shared(group: list[CandidateResult]) -> str:
    """What every rival has in common: that part of the story the data do establish."""
    common = set(group[0].members).intersection(*(set(c.members) for c in group[1:]))
    if not common:
        return ""
    names = " and ".join(sorted(common))
    return (f" Every rival includes {names}: that cause is established; what acts with it is not.")


def _partial(best: CandidateResult, resolution: float) -> str:
    """A warning when even the best candidate leaves more than twice the resolution."""
    if best.cv_error <= 2.0 * resolution:
        return ""
    return (f" Even the best of them leaves {100 * best.cv_error:.1f} % held out, more than twice the "
            f"resolution: it explains part of the gap only, and the cause may lie outside the catalogue or be "
            f"several at once.")


def decide(pairs: list[PairData], resolution: float, cands: dict[str, CandidateResult],
           table: TableEvidence) -> Decision:
    """The verdict of shared/MEASURED_DATA.md from the held-out predictions and the evidence.

    Models are compared by the likelihood of the measured thresholds under their
    held-out predictions (Student-t errors of scale sigma per pair); one model is
    preferred to another only on strong evidence (twice the log-likelihood ratio above
    STRONG_EVIDENCE), never on a small difference of mean errors.
    """
    pct = lambda x: f"{100 * x:.1f} %"
    baseline_error = mean_error(pairs, None, None)
    if baseline_error <= resolution:
        return Decision("none", None, [], (
            f"The nominal model predicts the measured thresholds within {pct(baseline_error)} on average, "
            f"inside the measurement resolution of {pct(resolution)} (half the amplitude steps plus the "
            f"search tolerance), so there is nothing for an extension to explain."))
    loss = {e: held_out_loss(c, pairs) for e, c in cands.items()}
    allowed = {e: c for e, c in cands.items() if c.admissible and (
        len(c.members) == 1 or all(m in cands and cands[m].admissible and clearly_better(loss[e], loss[m])
                                   for m in c.members))}
    if not allowed:
        return Decision("inconclusive", None, [], "No candidate effect is compatible with the evidence.")
    loss0 = held_out_loss(None, pairs)
    best = min(allowed.values(), key=lambda c: loss[c.effect])
    if not clearly_better(loss[best.effect], loss0):
        verdict = "none" if baseline_error <= 2.0 * resolution else "inconclusive"
        return Decision(verdict, None, [], (
            f"The nominal model is off by {pct(baseline_error)} on average (resolution {pct(resolution)}), "
            f"and no candidate effect predicts the held-out thresholds better by strong evidence: the best, "
            f"{best.effect}, leaves {pct(best.cv_error)}."))
    # Adequacy: a cause is named only if it explains the data to within their uncertainty,
    # not merely better than the others (a truth outside the catalogue is often
    # approached by some candidate, or pair, that still misses by far).
    sigma = float(np.mean([p.sigma for p in pairs]))
    if best.cv_error > ADEQUATE_SIGMAS * sigma:
        return Decision("inconclusive", None, [], (
            f"The nominal model is off by {pct(baseline_error)}; the best candidate, {best.effect} "
            f"({best.eff.label(best.value) if best.eff else best.effect}), brings the held-out error down to "
            f"{pct(best.cv_error)} only, more than {ADEQUATE_SIGMAS:g} times the uncertainty of a measured "
            f"threshold ({pct(sigma)}): no candidate of the catalogue explains the data, and the cause is "
            f"likely outside it (or several at once)."), best)
    rivals = [c for c in allowed.values() if c is not best and not clearly_better(loss[best.effect], loss[c.effect])]
    # Evidence beyond the thresholds: a table measured to deviate, and the hinges.
    separation = ""
    if rivals and best.effect == "table_motion" and table.source == "records" and table.deviates:
        separation = (f"The thresholds alone do not tell it from {', '.join(c.effect for c in rivals)}; the table "
                      f"records do: they show the table did not follow the command.")
        rivals = []
    if rivals and best.hinge_score is not None:
        group = [best] + rivals
        top = max(group, key=lambda c: -1.0 if c.hinge_score is None else c.hinge_score)
        if all(c is top or (c.hinge_score is not None and c.hinge_score <= top.hinge_score - HINGE_F1_MARGIN)
               for c in group):
            others = [c for c in group if c is not top]
            separation = (f"The thresholds alone do not tell it from {', '.join(c.effect for c in others)} (not by "
                          f"strong evidence); the observed hinges do: hinge F1 {top.hinge_score:.2f} against "
                          f"{', '.join(f'{c.effect} {c.hinge_score:.2f}' for c in others)}, a margin of "
                          f"{HINGE_F1_MARGIN:g} or more.")
            best, rivals = top, []
    if rivals:
        group = sorted([best] + rivals, key=lambda c: loss[c.effect])
        names = ", ".join(c.effect for c in group)
        return Decision("inconclusive", None, _rival_ids(group), (
            f"The nominal model is off by {pct(baseline_error)}; {names} each bring the held-out error down "
            f"({', '.join(f'{c.effect} {pct(c.cv_error)}' for c in group)}), none of them is preferred to the "
            f"others by strong evidence, and neither the records nor the hinges separate them: the data cannot "
            f"tell which it is." + _shared(group) + _partial(group[0], resolution)), group[0], group)
    return Decision(verdict_of(best), best, [], "", separation=separation)
