"""Single runs for the report: hinges and crown records of the tests as they were run,
simulated with the nominal model and the reported one. They do not enter the
probabilities (docs/diagnosis.md says why: a hinge's opening near collapse is as chaotic
as the threshold, and its error model is not yet calibrated)."""

from __future__ import annotations

import math

import numpy as np

from ..readers.campaign import Campaign
from .effects import Variant
from .simulator import Simulator

__all__ = ["hinge_matches", "crown_comparison"]


def hinge_matches(campaign: Campaign, sim: Simulator, models: dict[str, tuple[Variant, dict]]) -> dict:
    """hinge_match of each model: the fraction of observed hinges (joint and side) it
    opens in the same test, up to the collapse (one window for the test and the model)."""
    tests = [campaign.tests[tid] for tid, h in campaign.hinges.items()
             if h and campaign.tests[tid].waveform == "afd" and campaign.tests[tid].amplitude_m is not None]
    if not tests:
        return {name: None for name in models}
    observed = {t.test_id: {(h.joint, h.side) for h in campaign.hinges[t.test_id]} for t in tests}
    total = sum(len(o) for o in observed.values())
    out = {}
    for name, (variant, motion) in models.items():
        runs = sim.run_tests([(campaign.specimens[t.specimen_id], t, variant, motion) for t in tests])
        hit = sum(len(observed[t.test_id] & r["hinges"]) for t, r in zip(tests, runs))
        out[name] = hit / total if total else None
    return out


def crown_comparison(campaign: Campaign, sim: Simulator, models: dict[str, tuple[Variant, dict]],
                     max_tests: int = 24) -> dict:
    """Measured crown motion against the simulated one, per model, on the tests that
    stood and whose records have crown_dx_m (at most `max_tests`, the largest amplitudes
    first: near the threshold the arch rocks most). The compared feature is the peak
    horizontal crown displacement relative to the table, floored at 0.5 mm (the noise of
    a displacement sensor). Returns, per model, the mean of |log(simulated peak /
    measured peak)| and the per-test values."""
    floor_m = 5e-4
    tests = [campaign.tests[tid] for tid, r in campaign.records.items()
             if r.crown_dx_m is not None and campaign.tests[tid].waveform == "afd"
             and campaign.tests[tid].amplitude_m is not None and not campaign.tests[tid].collapsed]
    if not tests:
        return {}
    tests.sort(key=lambda t: -t.amplitude_m)
    tests = tests[:max_tests]
    out = {"tests": [t.test_id for t in tests], "models": {}}
    for name, (variant, motion) in models.items():
        runs = sim.run_tests([(campaign.specimens[t.specimen_id], t, variant, motion) for t in tests])
        errors = []
        for t, r in zip(tests, runs):
            measured = max(floor_m, float(np.abs(campaign.records[t.test_id].crown_dx_m).max()))
            simulated = max(floor_m, float(np.abs(r["crown_dx_m"]).max())) if not r["collapsed"] else 1.0
            errors.append(abs(math.log(simulated / measured)))
        out["models"][name] = {"mean": float(np.mean(errors)), "per_test": errors}
    return out
