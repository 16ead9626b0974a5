"""Brackets on one specimen only: a set-up fault of that specimen, screened on its own data.

The candidates of the decision carry one value for the whole campaign, and they are
judged leaving one specimen out: a restraint on one specimen alone can never be
predicted for a specimen held out, so as a candidate it would always score like the
nominal model. Its honest test is within the specimen: leaving one of its frequencies
out, the restraint (left, right, both or none) that fits its other frequencies predicts
the one held out. Where those held-out predictions beat the campaign's model on the
specimen by strong evidence, the report says so and asks the laboratory to check the
specimen's set-up (and to declare it in specimens.csv). It never changes the verdict:
one specimen's fault is not the campaign's cause, and the screen needs at least two
frequencies of the specimen.
"""

from __future__ import annotations

import math

from .effects import RESTRAINTS, Variant, effect
from .selection import CandidateResult, PairData, clearly_better, neg_log_likelihood

__all__ = ["specimen_restraints"]


def _loss(preds: list[float], ps: list[PairData]) -> float:
    return sum(neg_log_likelihood(x, p.measured.threshold_m, p.sigma) for x, p in zip(preds, ps))


def _mean_error(preds: list[float], ps: list[PairData]) -> float:
    errs = [abs(x - p.measured.threshold_m) / p.measured.threshold_m for x, p in zip(preds, ps) if math.isfinite(x)]
    return sum(errs) / len(errs) if errs else math.nan


def specimen_restraints(pairs: list[PairData], model: CandidateResult | None) -> list[dict]:
    """For each specimen without declared brackets and with two or more frequencies, the
    restraint of that specimen alone, fitted leaving one of its frequencies out, against
    the campaign's `model` (its held-out predictions; None: the nominal model). Returns
    the specimens where the restraint wins by strong evidence."""
    eff = effect("base_restraint")
    by_specimen: dict[str, list[int]] = {}
    for k, p in enumerate(pairs):
        by_specimen.setdefault(p.spec.specimen_id, []).append(k)
    found = []
    for sid, idx in by_specimen.items():
        ps = [pairs[k] for k in idx]
        if len(ps) < 2 or ps[0].spec.restrained_springings != "none":
            continue
        options = [None, *RESTRAINTS]

        def predict(p: PairData, r) -> float:
            return p.simulated.get(Variant(), math.nan) if r is None else eff.predict(p, r)

        held, chosen = [], []
        for i in range(len(ps)):
            train = [q for j, q in enumerate(ps) if j != i]
            best = min(options, key=lambda r: (_loss([predict(q, r) for q in train], train), r is not None))
            chosen.append(best)
            held.append(predict(ps[i], best))
        reference = [p.simulated.get(Variant(), math.nan) if model is None else model.per_pair[k]
                     for k, p in zip(idx, ps)]
        if any(not math.isfinite(x) for x in held) or not clearly_better(_loss(held, ps), _loss(reference, ps)):
            continue
        fitted = min(RESTRAINTS, key=lambda r: _loss([predict(q, r) for q in ps], ps))
        name = "the nominal model" if model is None else f"the campaign's model ({model.effect})"
        sentence = (f"On its own data, specimen {sid} behaves as if its springings were restrained ({fitted}): fitted on its "
                    f"other frequencies, that restraint predicts each of its {len(ps)} tested frequencies within "
                    f"{100 * _mean_error(held, ps):.1f} % on average, against {100 * _mean_error(reference, ps):.1f} % "
                    f"for {name}. Check that specimen's set-up (brackets, a support against the bottom voussoirs) "
                    f"and declare it in specimens.csv (restrained_springings).")
        found.append({"specimen": sid, "restraint": fitted, "fold_choices": chosen,
                      "held_out_error": _mean_error(held, ps), "reference_error": _mean_error(reference, ps),
                      "sentence": sentence})
    return found
