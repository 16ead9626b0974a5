"""The verdict of shared/MEASURED_DATA.md from the candidates' held-out predictions.

`none` when the nominal model already agrees within the measurement resolution;
otherwise the candidate with the best held-out likelihood, provided it beats the nominal
model by strong evidence and no other candidate comes within strong evidence of it,
unless the records or the hinges separate them; else `inconclusive`, naming the rivals.
"""

from __future__ import annotations

from dataclasses import dataclass

from .actuator import TableEvidence
from .selection import CandidateResult, PairData, clearly_better, held_out_loss, mean_error

__all__ = ["Decision", "decide", "hinge_match"]


@dataclass
class Decision:
    verdict: str
    chosen: CandidateResult | None
    rivals: list[str]  #: for `inconclusive`: the effects the data cannot separate, best first
    notes: str
    best_rival: CandidateResult | None = None  #: the first of the rivals (its held-out result is `extended`)


def hinge_match(observed: dict[str, set], simulated: dict[str, set]) -> float | None:
    total = sum(len(o) for o in observed.values())
    if total == 0:
        return None
    hit = sum(len(o & simulated.get(tid, set())) for tid, o in observed.items())
    return hit / total


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
    allowed = {e: c for e, c in cands.items() if c.admissible}
    if not allowed:
        return Decision("inconclusive", None, [], "No candidate effect is compatible with the evidence.")
    loss = {e: held_out_loss(c, pairs) for e, c in allowed.items()}
    loss0 = held_out_loss(None, pairs)
    best = min(allowed.values(), key=lambda c: loss[c.effect])
    if not clearly_better(loss[best.effect], loss0):
        verdict = "none" if baseline_error <= 2.0 * resolution else "inconclusive"
        return Decision(verdict, None, [], (
            f"The nominal model is off by {pct(baseline_error)} on average (resolution {pct(resolution)}), "
            f"and no candidate effect predicts the held-out thresholds better by strong evidence: the best, "
            f"{best.effect}, leaves {pct(best.cv_error)}."))
    rivals = [c for c in allowed.values() if c is not best and not clearly_better(loss[best.effect], loss[c.effect])]
    # Evidence beyond the thresholds: a table measured to deviate, and the hinges.
    if rivals and best.effect == "table_motion" and table.source == "records" and table.deviates:
        rivals = []
    if rivals and best.hinge_match is not None:
        group = [best] + rivals
        top = max(group, key=lambda c: -1.0 if c.hinge_match is None else c.hinge_match)
        if all(c is top or (c.hinge_match is not None and c.hinge_match <= top.hinge_match - 0.15) for c in group):
            best, rivals = top, []
    if rivals:
        group = sorted([best] + rivals, key=lambda c: loss[c.effect])
        names = ", ".join(c.effect for c in group)
        return Decision("inconclusive", None, [c.effect for c in group], (
            f"The nominal model is off by {pct(baseline_error)}; {names} each bring the held-out error down "
            f"({', '.join(f'{c.effect} {pct(c.cv_error)}' for c in group)}), none of them is preferred to the "
            f"others by strong evidence, and neither the records nor the hinges separate them: the data cannot "
            f"tell which it is."), group[0])
    return Decision(best.effect, best, [], "")
