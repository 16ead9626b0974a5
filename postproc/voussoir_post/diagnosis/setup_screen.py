"""Brackets on one specimen only: a set-up fault of that specimen, screened on its own data.

The candidates of the decision carry one value for the whole campaign, and they are
judged leaving one specimen out: a restraint on one specimen alone can never be
predicted for a specimen held out, so as a candidate it would always score like the
nominal model. Its honest test is within the specimen: leaving one of its frequencies
out, the restraint (none, left, right or both) that fits its other frequencies predicts
the one held out. A specimen is said to behave as if restrained only when those
held-out predictions beat, by strong evidence, every other story of that specimen: the
nominal model, the campaign's model (fitted on every specimen, this one included), and
each other effect of the catalogue fitted to this specimen alone the same way (a
specimen that is merely off, e.g. one whose thresholds the campaign's friction does not
suit, is not taken for one with brackets). The table's gain is not among them: one
table carries every specimen. The screen never changes the verdict (one specimen's fault
is not the campaign's cause) and needs two or more frequencies of the specimen.
"""

from __future__ import annotations

import math

from .actuator import TableEvidence
from .effects import RESTRAINTS, Variant, effect
from .nested import mean_relative_error
from .selection import CandidateResult, PairData, clearly_better, evaluate_candidate, predictions_loss
from .settings import DiagnosisSettings

__all__ = ["specimen_restraints", "RIVAL_STORIES"]

#: The effects fitted to one specimen alone that the restraint must beat.
RIVAL_STORIES = ("contact_edges", "friction", "geometry")


def specimen_restraints(pairs: list[PairData], model: CandidateResult | None, settings: DiagnosisSettings,
                        table: TableEvidence) -> list[dict]:
    """The specimens (certain set-up, no declared brackets, two or more frequencies) whose
    own thresholds a restraint of that specimen alone predicts better, by strong
    evidence, than any other story of it (module docstring), with the numbers."""
    eff = effect("base_restraint")

    def restrained(p: PairData, r) -> float:
        return p.simulated.get(Variant(), math.nan) if r is None else eff.predict(p, r)

    by_specimen: dict[str, list[PairData]] = {}
    for p in pairs:
        by_specimen.setdefault(p.spec.specimen_id, []).append(p)
    found = []
    for sid, ps in by_specimen.items():
        if len(ps) < 2 or ps[0].spec.restrained_springings != "none":
            continue
        # The restraint of this specimen alone, leaving one of its frequencies out (none
        # first: of equal fits, the smaller change).
        held, chosen = [], []
        for i in range(len(ps)):
            train = [q for j, q in enumerate(ps) if j != i]
            best = min([None, *RESTRAINTS], key=lambda r: predictions_loss([restrained(q, r) for q in train], train))
            chosen.append(best)
            held.append(restrained(ps[i], best))
        if any(not math.isfinite(x) for x in held):
            continue
        stories = {"the nominal model": [restrained(p, None) for p in ps]}
        if model is not None:
            stories[f"the campaign's model ({model.effect}, fitted on all specimens)"] = \
                [model.eff.predict(p, model.value) for p in ps]
        for e in RIVAL_STORIES:  # one specimen: its folds leave one pair out
            stories[f"{e} fitted to it alone"] = evaluate_candidate(ps, effect(e), settings, table).per_pair
        loss = predictions_loss(held, ps)
        if not all(clearly_better(loss, predictions_loss(preds, ps)) for preds in stories.values()):
            continue
        fitted = min(RESTRAINTS, key=lambda r: predictions_loss([restrained(q, r) for q in ps], ps))
        errors = {name: mean_relative_error(preds, ps) for name, preds in stories.items()}
        best_other = min(errors, key=lambda k: errors[k] if math.isfinite(errors[k]) else math.inf)
        sentence = (f"On its own data, specimen {sid} behaves as if its springings were restrained ({fitted}): fitted "
                    f"on its other frequencies, that restraint predicts each of its {len(ps)} tested frequencies within "
                    f"{100 * mean_relative_error(held, ps):.1f} % on average, better by strong evidence than any other story "
                    f"of it (the best, {best_other}, {100 * errors[best_other]:.1f} %). Check that specimen's set-up "
                    f"(brackets, a support against the bottom voussoirs) and declare it in specimens.csv "
                    f"(restrained_springings).")
        found.append({"specimen": sid, "restraint": fitted, "fold_choices": chosen,
                      "held_out_error": mean_relative_error(held, ps), "other_errors": errors, "sentence": sentence})
    return found
