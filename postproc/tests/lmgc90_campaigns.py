"""Campaigns made by another code: LMGC90's thresholds of hidden truths, replayed as a laboratory.

bench/lmgc90/truths.py draws truths from the diagnosis's own prior (and truths outside
its catalogue), builds each specimen as it really is in LMGC90 (chamfered polygons, a
thinner ring, brackets with play, an actuator, a heavier crown, a spreading support; each
specimen a little off its nominal size), and finds each (arch, frequency) pair's collapse
threshold in commanded amplitude by a scan and a bisection. The stored truths
(data/lmgc90/*.json) hold those searches' probes; they are made once, with LMGC90, and
replayed here without it.

A replay (`draw_campaign`) plays a laboratory over a truth, with the faults of real ones
drawn per campaign (`LabFaults`):

- a ramp per pair of 1 to 5 mm steps (snapped to 0.5 mm), from a start between 0.5 and
  0.9 times the nominal onset of rocking, up to the first collapse;
- each test's real table gain scatters (1 % by default) about the actuator's gain;
- the table transducer reads every gain off by a common factor (up to +-2 %);
- a campaign-wide offset of the thresholds, of the size two codes differ by (normal,
  1 % by default);
- in some campaigns only the collapse rows are kept (the seed paper's tables), so every
  bracket is an upper bound.

A test's outcome is the truth's at the amplitude the table really made (command x gain x
offset): stand below the stored threshold; at or above it, the outcome of the nearest
probe the search made above it (a window of standing beyond the first collapse, kept as
the search saw it), and collapse past the last probe.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from replay_maps import bracket, ramp_observations
from voussoir_post.diagnosis.effects import BRACKET_GAPS_M, RESTRAINT_VALUES, Variant, restraint_value
from voussoir_post.diagnosis.models import MATERIAL, effect_sizes, material_threshold, members
from voussoir_post.diagnosis.observations import Observations

__all__ = ["TRUTH_DIR", "LabFaults", "load_truth", "stored_truths", "draw_campaign", "truth_model", "truth_values",
           "generator_effect_size", "SNAP_M"]

TRUTH_DIR = Path(__file__).resolve().parent / "data" / "lmgc90"
SNAP_M = 5e-4  #: amplitudes a laboratory commands are multiples of this


@dataclass(frozen=True)
class LabFaults:
    """How a laboratory's campaign departs from an ideal one (ranges drawn per campaign)."""

    step_mm: tuple[float, float] = (1.0, 5.0)  #: ramp step, uniform [mm]
    start_fraction: tuple[float, float] = (0.5, 0.9)  #: first amplitude, times the nominal onset
    gain_scatter: float = 0.01  #: test-to-test table gain scatter (relative)
    transducer_bias: float = 0.02  #: the transducer's common gain error, uniform within +-
    gain_noise: float = 0.002  #: noise of one measured gain (relative)
    offset_sd: float = 0.01  #: campaign-wide offset of the thresholds (relative, normal)
    collapses_only_p: float = 0.2  #: probability that a campaign keeps only its collapse rows
    max_tests: int = 40


#: Ideal campaigns: the faults off (a check that the faults matter, and a baseline).
IDEAL = LabFaults(step_mm=(2.0, 2.0), start_fraction=(0.7, 0.7), transducer_bias=0.0, offset_sd=0.0,
                  collapses_only_p=0.0)


def load_truth(path: Path) -> dict:
    return json.loads(Path(path).read_text())


def truth_variant(truth: dict) -> Variant:
    """The catalogue variant of a truth at its own parameters (its table motion apart: it
    changes no static capacity and no kernel threshold of the commanded motion); the
    brackets' play the simulated one nearest."""
    parts = []
    for e, p in sorted(truth["truth"].get("parameters", {}).items()):
        if e in TRUTH_PARAMETERS:
            parts.append((e, p[TRUTH_PARAMETERS[e][0]]))
        elif e == "base_restraint":
            parts.append((e, RESTRAINT_VALUES[int(restraint_index(p))]))
    return Variant.of(parts)


def stored_truths(folder: Path = TRUTH_DIR) -> list[dict]:
    """Every stored truth, by index, with its stored counterfactuals (bench/lmgc90/truths.py
    --without: the same specimens less one effect) under "counterfactuals", by effect."""
    out = []
    for p in sorted(Path(folder).glob("t*.json")):
        cfs = {c.stem.rsplit("_without_", 1)[1]: load_truth(c)
               for c in sorted((Path(folder) / "counterfactual").glob(f"{p.stem}_without_*.json"))}
        out.append(load_truth(p) | {"slug": p.stem, "counterfactuals": cfs})
    return sorted(out, key=lambda t: t["truth"]["index"])


def generator_effect_size(truth: dict, effect: str, bank, obs: Observations) -> float | None:
    """How far an effect moves the campaign's tested thresholds in the generator's own
    physics: the largest |change of log threshold| between the truth and its stored
    counterfactual without that effect, in units of the pair's material threshold
    (models.material_threshold, as models.effect_sizes); None without a counterfactual."""
    cf = truth.get("counterfactuals", {}).get(effect)
    if cf is None:
        return None
    def thresholds(rec):
        return {(p["specimen_id"], round(p["frequency_hz"], 9)): p["threshold_m"] for p in rec["pairs"]}
    with_it, without = thresholds(truth), thresholds(cf)
    size = 0.0
    for p in obs.pairs:
        key = (p.specimen_id, round(p.frequency_hz, 9))
        a, b = with_it.get(key), without.get(key)
        if a is None and b is None:
            continue
        if a is None or b is None:
            return math.inf  # one of them never fell within the search's cap
        size = max(size, abs(math.log(a / b)) / material_threshold(bank, obs, p))
    return size


#: A truth's parameter, as the diagnosis's MATERIAL measures it (its nominal value: the test
#: arches' friction 0.5, no inset, thickness factor 1).
TRUTH_PARAMETERS = {"contact_edges": ("inset_m", 0.0), "friction": ("friction", 0.5),
                    "geometry": ("thickness_factor", 1.0)}


def restraint_index(brackets: dict) -> float:
    """The grid index (models.RESTRAINTS_ARRAY) of a truth's brackets: its side, with the
    simulated play nearest its own."""
    gap = min(BRACKET_GAPS_M, key=lambda g: abs(g - brackets.get("gap_m", 0.0)))
    return float(RESTRAINT_VALUES.index(restraint_value(brackets["side"], gap)))


def truth_values(truth: dict) -> dict:
    """The truth's value of each continuous parameter, by the effect ids the diagnosis's
    grids are named by (for its simulation-based calibration)."""
    params = truth["truth"].get("parameters", {})
    return {e: params[e][key] for e, (key, _) in TRUTH_PARAMETERS.items() if e in params}


def truth_model(truth: dict, bank=None, obs: Observations | None = None) -> str:
    """The model id the diagnosis should name ('outside' for a truth outside the
    catalogue): the generator's, less any effect that is no cause by the diagnosis's
    definitions: a parameter within MATERIAL of nominal (a friction of 0.52 is the
    nominal arch) or, given the bank and a campaign's observations, an effect that moves
    none of the campaign's tested thresholds by its material threshold (dropped one effect
    at a time, the smallest first). How far an effect moves them is the generator's own
    where the truth has a stored counterfactual without it (generator_effect_size: brackets
    with play, which the catalogue's rigid brackets cannot hold; an effect outside the
    catalogue, whose truth is then the nominal arch when it moves nothing), else the
    diagnosis's emulators' (models.effect_sizes, at the truth's parameter values: a
    friction of 0.56 on arches that rock and never slide)."""
    model = truth["truth"]["model"]
    judged = bank is not None and obs is not None and bool(obs.pairs)
    if model == "outside":
        size = generator_effect_size(truth, "outside", bank, obs) if judged else None
        return "none" if size is not None and size < 1.0 else model
    params = truth["truth"].get("parameters", {})
    kept = [e for e in members(model)
            if e not in MATERIAL or abs(params[e][TRUTH_PARAMETERS[e][0]] - TRUTH_PARAMETERS[e][1])
            >= MATERIAL[e] - 1e-12]
    whole = list(members(model))
    while judged:
        simulated = [e for e in kept if e != "table_motion"]
        if not simulated:
            break
        points = [np.array([restraint_index(params[e]) if e == "base_restraint"
                            else params[e][TRUTH_PARAMETERS[e][0]]]) for e in simulated]
        sizes = effect_sizes(bank, obs, tuple(simulated), points)[0]
        if kept == whole:  # a counterfactual is the whole truth less one effect
            for i, e in enumerate(simulated):
                size = generator_effect_size(truth, e, bank, obs)
                sizes[i] = sizes[i] if size is None else size
        if sizes.min() >= 1.0:
            break
        kept.remove(simulated[int(np.argmin(sizes))])
    return "+".join(sorted(kept)) or "none"


def _collapsed(pair: dict, amp_m: float) -> bool:
    """The truth's outcome at a real amplitude (see the module docstring)."""
    thr = pair["threshold_m"]
    if thr is None or amp_m < thr:
        return False
    above = [(a, c) for a, c, *_ in pair["probes"] if a >= thr]
    if not above or amp_m > max(a for a, _ in above):
        return True  # past what the search probed: it falls (a window of standing is narrow)
    return bool(min(above, key=lambda ac: abs(ac[0] - amp_m))[1])


def draw_campaign(truth: dict, rng: np.random.Generator, faults: LabFaults = LabFaults(),
                  name: str = "lmgc90") -> tuple[Observations, dict]:
    """One campaign over a stored truth; returns its observations and the drawn faults."""
    bias = rng.uniform(-faults.transducer_bias, faults.transducer_bias) if faults.transducer_bias else 0.0
    offset = math.exp(faults.offset_sd * rng.standard_normal()) if faults.offset_sd else 1.0
    collapses_only = bool(rng.random() < faults.collapses_only_p)
    pairs = []
    for pair in truth["pairs"]:
        step = max(SNAP_M, round(rng.uniform(*faults.step_mm) * 1e-3 / SNAP_M) * SNAP_M)
        amp = max(SNAP_M, round(rng.uniform(*faults.start_fraction) * pair["onset_m"] / SNAP_M) * SNAP_M)
        tests = []
        for _ in range(faults.max_tests):
            g = pair["table_gain"] * (1.0 + faults.gain_scatter * rng.standard_normal())
            measured = g * (1.0 + bias) * (1.0 + faults.gain_noise * rng.standard_normal())
            fell = _collapsed(pair, amp * g / pair["table_gain"] * offset)
            tests.append((amp, fell, measured, f"{pair['specimen_id']}_f{pair['frequency_hz']:g}_A{1e3 * amp:.1f}"))
            if fell:
                break
            amp = round((amp + step) / SNAP_M) * SNAP_M
        if not tests[-1][1]:
            continue
        if collapses_only:
            tests = [t for t in tests if t[1]]
        pairs.append(bracket(pair["specimen_id"], pair["frequency_hz"], tests))
    obs = ramp_observations(name, pairs)
    return obs, {"transducer_bias": bias, "offset": offset, "collapses_only": collapses_only}
