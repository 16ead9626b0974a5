"""Brackets on one specimen only: a set-up fault of that specimen, weighed on its own data.

A restraint of one specimen alone is not a cause of the campaign, and the campaign's
posterior cannot see it for what it is. Each specimen with a certain set-up, no declared
brackets and two or more tested frequencies is therefore also given its own posterior,
on its own pairs alone; where base_restraint reaches 0.9 there while the campaign's
verdict is not base_restraint, the report says so and asks for the set-up to be checked.
The screen never changes the verdict.
"""

from __future__ import annotations

from .bank import Bank
from .decision import NAME_AT, Decision
from .observations import Observations
from .posterior import infer

__all__ = ["specimen_screen"]


def specimen_screen(bank: Bank, obs: Observations, decision: Decision) -> list[dict]:
    found = []
    if "base_restraint" in decision.effects:
        return found
    for sid, spec in obs.specimens.items():
        pairs = obs.of(sid)
        if len(pairs) < 2 or spec.restrained_springings != "none" or not spec.setup_certain:
            continue
        p = infer(bank, obs, pairs).probabilities
        mass = sum(v for m, v in p.items() if "base_restraint" in m.split("+"))
        if mass >= NAME_AT:
            found.append({"specimen": sid, "probability": mass, "sentence": (
                f"On its own data, specimen {sid} behaves as if its springings were restrained (probability "
                f"{mass:.2f} on its {len(pairs)} frequencies alone): check that specimen's set-up (brackets, a "
                f"support against the bottom voussoirs) and declare it in specimens.csv (restrained_springings).")})
    return found
