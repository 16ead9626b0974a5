"""The test the laboratory should run next: where the rivals disagree most.

For an `inconclusive` verdict, every tested (specimen, frequency) pair and every new
frequency of `DiagnosisSettings.probe_frequencies_hz` (at least 0.05 Hz from the tested
ones) on each specimen with a certain set-up is scored by how differently the rivals
predict its threshold: the sum over pairs of rivals of p_a p_b (m_a - m_b)^2 / (v_a + v_b)
(m the log threshold, v its predictive variance). At a tested pair the rivals' posteriors
give m and v (posterior.tested_separation); at a new frequency each rival is simulated
at its posterior mean (ceiling and tolerance from the limit analysis, as the bank's), so
v there is the predictive spread alone, without the parameters' (stated in the report).
A rival's table gain divides its threshold at a new frequency by the campaign's mean
measured gain.
"""

from __future__ import annotations

import hashlib
import json
import math
from pathlib import Path

import numpy as np

from .bank import onset_amplitudes, variant_key
from .effects import arch_group
from .likelihood import TAU_CAMPAIGN, TAU_SPECIMEN
from .models import members
from .observations import Observations
from .posterior import Posterior, tested_separation
from .settings import DiagnosisSettings
from .simulator import Simulator

__all__ = ["next_test"]


def _new_frequencies(obs: Observations, sid: str, settings: DiagnosisSettings) -> list[float]:
    tested = [p.frequency_hz for p in obs.of(sid)]
    return [f for f in settings.probe_frequencies_hz if min(abs(f - t) for t in tested) > 0.05]


def next_test(post: Posterior, obs: Observations, rivals: list[str], runs: dict, settings: DiagnosisSettings,
              work: Path) -> dict | None:
    """{'specimen_id', 'frequency_hz', 'new', 'predicted_m': {rival: threshold}} of the
    best test, or None with fewer than two rivals. `runs` gives each rival's (variant,
    &motion settings) at its posterior mean (pipeline.model_run)."""
    if len(rivals) < 2:
        return None
    tested = tested_separation(post, rivals)
    j = int(np.argmax(tested))
    best = {"specimen_id": post.pairs[j].specimen_id, "frequency_hz": post.pairs[j].frequency_hz, "new": False,
            "score": float(tested[j]), "predicted_m": {}}
    sc = post.scales
    var = float(np.mean(sc.sigma_sim ** 2)) + sc.sigma_gain ** 2 + TAU_SPECIMEN[1] ** 2 + TAU_CAMPAIGN[1] ** 2
    gain = float(np.mean(sc.gain_mean)) if obs.gain_source != "none" else 1.0
    for sid in sorted({p.specimen_id for p in obs.pairs}):
        spec, freqs = obs.specimens[sid], _new_frequencies(obs, sid, settings)
        if not freqs:
            continue
        variants = sorted({runs[m][0] for m in rivals}, key=variant_key)
        # A folder per question (specimen, frequencies, models): a rerun reuses its sweeps,
        # another question never meets them.
        key = json.dumps([[arch_group(spec, v) for v in variants], freqs, settings.dt_s], sort_keys=True)
        sim = Simulator(settings, Path(work) / hashlib.sha256(key.encode()).hexdigest()[:16])
        onset = onset_amplitudes(sim.runner, spec, freqs)
        found = sim.thresholds_at(spec, freqs, obs.cycles[sid], variants, settings.ceiling_factor * max(onset),
                                  settings.amp_tol_fraction * min(onset))
        for f in freqs:
            pred = {m: found.get((runs[m][0], f), math.nan) / (gain if "table_motion" in members(m) else 1.0)
                    for m in rivals}
            if not all(math.isfinite(v) and v > 0 for v in pred.values()):
                continue
            score = sum(post.probabilities[a] * post.probabilities[b] * math.log(pred[a] / pred[b]) ** 2 / (2 * var)
                        for i, a in enumerate(rivals) for b in rivals[i + 1:])
            if score > best["score"]:
                best = {"specimen_id": sid, "frequency_hz": f, "new": True, "score": score, "predicted_m": pred}
    return best
