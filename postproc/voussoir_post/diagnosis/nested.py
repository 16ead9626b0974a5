"""The reported gain, by nested cross-validation.

The held-out error of the candidate that the decision chose would still be measured on
the data that chose it (among several candidates, the one whose held-out error happens to
be lowest is favoured). So the whole procedure is cross-validated: in each outer fold
(leave one specimen out) the candidates are fitted and judged, and the verdict decided,
on the other specimens alone, with their own inner folds (leave one pair out: a choice
made from two specimens by leaving one of them out would rest on fits to a single
arch), and the model with the best inner held-out likelihood (the nominal one among them; a pair only where it beats each
of its members by strong evidence, as in the decision), fitted on those specimens,
predicts the specimen held out. The mean error of those predictions is the extended
model's `threshold_error_pct`: the gain of choosing a cause and fitting it, measured on
data that took part in neither. (The strong-evidence bar of the verdict is not applied
inside: it decides what may be *named*, not which model predicts best.) Hinges weigh in
the outer decision only; the table evidence in both.
"""

from __future__ import annotations

import math

import numpy as np

from .actuator import TableEvidence
from .effects import Effect, Variant
from .selection import PairData, clearly_better, errors, evaluate_candidate, folds, held_out_loss
from .settings import DiagnosisSettings

__all__ = ["nested_held_out", "admissibility", "mean_relative_error"]


def admissibility(cands: dict, table: TableEvidence) -> None:
    """Exclude the table's effect where the table evidence contradicts it (in place)."""
    c = cands.get("table_motion")
    if c is None:
        return
    if table.source == "records" and not table.deviates:
        c.admissible = False
        c.reason = (f"the records show the table followed the command (gain {table.gain:.3f}"
                    f" +- {2 * table.gain_se:.3f})")
    if table.source == "peak_accel":
        tol = max(0.05, 3.0 * (table.gain_se if math.isfinite(table.gain_se) else 0.0))
        if abs(float(c.value) - table.gain) > tol:
            c.admissible = False
            c.reason = (f"it needs a gain of {float(c.value):.2f}, but the measured peak accelerations are "
                        f"{table.gain:.2f} times the commanded ones")


def nested_held_out(pairs: list[PairData], effects: list[Effect], settings: DiagnosisSettings,
                    table: TableEvidence) -> tuple[list[float], list[str]]:
    """Outer held-out predictions [m] of every pair by the whole procedure, and the
    model each outer fold chose."""
    held = [math.nan] * len(pairs)
    verdicts = []
    for train, test in folds(pairs):
        if train == test:  # one pair: nothing to hold out
            return [p.simulated.get(Variant(), math.nan) for p in pairs], []
        sub = [pairs[i] for i in train]
        cands = {e.id: evaluate_candidate(sub, e, settings, table, by_pair=True) for e in effects}
        admissibility(cands, table)
        loss = {k: held_out_loss(c, sub) for k, c in cands.items()}
        allowed = [c for k, c in cands.items() if c.admissible and (
            len(c.members) == 1 or all(m in cands and clearly_better(loss[k], loss[m]) for m in c.members))]
        model = min(allowed, key=lambda c: loss[c.effect], default=None)
        if model is not None and loss[model.effect] >= held_out_loss(None, sub):
            model = None
        verdicts.append("nominal" if model is None else model.effect)
        for i in test:
            held[i] = pairs[i].simulated.get(Variant(), math.nan) if model is None else \
                model.eff.predict(pairs[i], model.value)
    return held, verdicts


def mean_relative_error(held: list[float], pairs: list[PairData]) -> float:
    return float(np.mean(errors(held, pairs)))
