"""Stage 2 of the diagnosis: the simulation bank, which does not depend on the data.

For each specimen, the collapse thresholds of every model the inference weighs, at every
frequency the campaign tested it at: the nominal model, each effect over its grid, the
pairs of effects over a coarser product grid, and the replicas that measure the
simulator's own spread (the nominal model at dt x 0.97 and x 1.03, and at dt / 2).

Nothing here reads a measured threshold: the search ceiling and tolerance come from the
specimen's limit analysis (the onset of rocking, voussoir-limit), so every noise draw
of a campaign, and every campaign of the same specimens and frequencies, asks the
kernel the same questions and gets the same answers. The bank is cached as JSON, one
file per specimen and frequency, under a key of the executables' bytes (less the version
string they embed: a commit of Python or docs keeps the cache), the specimen, the
frequency and cycles, the time step and the grids: a second diagnosis re-simulates
nothing, and a test at a new frequency simulates that frequency only (`merge` joins a
specimen's frequencies).

The simulator's own spread is measured by replicas (the same model at dt x 0.97 and x
1.03, and for the nominal model also at other scan steps) at the nominal model and at
the two ends of every single effect's grid, so that the spread is known over the
parameter space, not at one point. Where the response is steep, the bank simulates more
nodes: between two neighbouring values of a single effect whose thresholds differ (at
any frequency) by more than `REFINE_SPREADS` times the larger of the pair's replica
spread and 1 %, the midpoint is simulated, for `settings.refine_rounds` rounds (models.py
interpolates between the nodes, so a steep step must be resolved by nodes, not guessed).

Cost, per specimen and tested frequency, in threshold searches (each about 12 runs of
the ramp): 1 nominal + 5 replicas + about 28 single-effect values + about 107 pairs +
about 14 replicas at the effects' ends + the refined nodes.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..readers.campaign import Specimen
from ..runner import Runner, code_hash
from ..units import G_M_S2
from .effects import COMBINED, EFFECTS_BY_ID, RESTRAINTS, Variant, arch_group, nominal_value, restraint_values
from .settings import DiagnosisSettings
from .simulator import Simulator

__all__ = ["BANK_VERSION", "SpecimenBank", "Bank", "variant_key", "key_variant", "bank_variants", "build_bank",
           "load", "save", "load_banks", "onset_amplitudes",
           "REPLICAS", "FINE_DT", "NODE_REPLICAS", "G", "spread_nodes", "refine_values", "replica_groups", "pooled_spread", "merge", "MISSING"]

#: Part of every cache key: 3 since the catalogue's brackets have play (a bank cached by an
#: older catalogue lacks their models).
BANK_VERSION = 3
G = G_M_S2  #: the kernel's gravity [m/s2] (units.py)
#: Time-step factors of the replicas of the nominal model that measure the simulator's
#: own spread (a threshold search near a chaotic boundary answers differently to a
#: change of dt of a few percent); the fine-dt check is at dt / 2.
#: The replicas of the nominal model: (name, dt factor, scan step or None for the
#: bank's). Their spread is the simulator's own: a threshold near a chaotic, non-monotonic
#: band answers differently to a change of dt of a few percent or of the search's path.
REPLICAS = (("dt x0.97", 0.97, None), ("dt x1.03", 1.03, None), ("scan 3 %", 1.0, 0.03),
            ("scan 7 %", 1.0, 0.07))
FINE_DT = ("dt / 2", 0.5, None)  #: the discretisation check of each specimen
#: The replicas made at the ends of every single effect's grid.
NODE_REPLICAS = (("dt x0.97", 0.97, None), ("dt x1.03", 1.03, None))
REFINE_SPREADS = 3.0  #: neighbouring nodes this many spreads apart get a node between them
#: The smallest spacing refinement goes down to, per effect (in its parameter's unit).
REFINE_MIN_STEP = {"contact_edges": 0.00025, "friction": 0.0125, "geometry": 0.015}


def variant_key(v: Variant) -> str:
    """A text key of a variant: 'nominal', 'friction=0.45', 'contact_edges=0.002+friction=0.45'."""
    parts = sorted(v.parts())
    return "+".join(f"{e}={val}" for e, val in parts) if parts else "nominal"


def key_variant(key: str) -> Variant:
    if key == "nominal":
        return Variant()
    parts = []
    for text in key.split("+"):
        e, val = text.split("=")
        parts.append((e, val if val.partition("@")[0] in RESTRAINTS else float(val)))
    return Variant.of(parts)


def _pair_values(spec: Specimen, settings: DiagnosisSettings) -> dict[str, list]:
    """The coarser grid of each effect inside a pair."""
    return {"contact_edges": [e for e in settings.pair_inset_m if e < 0.45 * spec.thickness_m],
            "friction": [round(spec.friction + d, 6) for d in settings.pair_friction_steps
                         if settings.min_friction <= spec.friction + d <= settings.max_friction],
            "geometry": list(settings.pair_thickness_factors),
            "base_restraint": [] if spec.restrained_springings != "none" else list(restraint_values(settings.bracket_gaps_m))}


def bank_variants(spec: Specimen, settings: DiagnosisSettings) -> list[Variant]:
    """Every model simulated for one specimen (the replicas apart)."""
    out = [Variant()]
    for e in ("contact_edges", "friction", "geometry", "base_restraint"):
        out += EFFECTS_BY_ID[e].simulated(spec, settings)
    grid = _pair_values(spec, settings)
    # Every value of a pair's grid alone too: the pair's product table has its edges.
    alone = set(out)
    out += [v for e, values in grid.items() for v in (Variant(e, x) for x in values) if v not in alone]
    ids = sorted(grid)
    for i, a in enumerate(ids):
        for b in ids[i + 1:]:
            out += [Variant(COMBINED, ((a, va), (b, vb))) for va in grid[a] for vb in grid[b]]
    return out


@dataclass
class SpecimenBank:
    """Simulated thresholds [m] of one specimen, per model key, one per frequency."""

    specimen_id: str
    frequencies_hz: list[float]
    cycles: tuple[int, int, int]
    onset_m: list[float]  #: amplitude of the onset of rocking (limit analysis) per frequency
    amp_max_m: float
    amp_tol_m: float
    dt_s: float
    thresholds: dict[str, list[float]] = field(default_factory=dict)
    replicas: dict[str, list[float]] = field(default_factory=dict)  #: 'dt x0.97' ... and 'dt / 2'
    #: Replicas of other models: {variant key: {replica name: thresholds per frequency}}.
    node_replicas: dict[str, dict[str, list[float]]] = field(default_factory=dict)
    searches: int = 0  #: threshold searches made to fill it

    def index(self, frequency_hz: float) -> int:
        """The position of a tested frequency in the bank's lists."""
        k = min(range(len(self.frequencies_hz)), key=lambda i: abs(self.frequencies_hz[i] - frequency_hz))
        if abs(self.frequencies_hz[k] - frequency_hz) > 1e-6:
            raise KeyError(f"{self.specimen_id}: {frequency_hz} Hz is not in the bank")
        return k

    def threshold(self, key: str, frequency_hz: float) -> float:
        return self.thresholds[key][self.index(frequency_hz)]


@dataclass
class Bank:
    """The banks of every specimen of a campaign."""

    specimens: dict[str, SpecimenBank]
    code: str  #: hash of the executables that made it
    reused: int = 0  #: specimens found in the cache
    searches: int = 0  #: threshold searches made now (0 when everything was cached)
    #: Model grids already made from this bank (models.model_grid), by model and pairs.
    grids: dict = field(default_factory=dict, repr=False, compare=False)
    #: Pulse pairs' thresholds (pulses.py): {"<specimen>:<shape key>": {variant key: (+, -) [m]}}.
    pulses: dict = field(default_factory=dict)
    #: The kernel's scan of each afd pair (early.py): {early.early_key(specimen, f): early fraction or None}.
    early: dict = field(default_factory=dict)


def _cache_key(code: str, spec: Specimen, freqs: list[float], cycles, settings: DiagnosisSettings) -> str:
    group = arch_group(spec, Variant())
    grids = {k: v for k, v in dataclasses.asdict(settings).items()
             if k in ("dt_s", "amp_tol_fraction", "inset_grid_m", "friction_steps", "min_friction", "max_friction",
                      "thickness_factors", "scan_step", "pair_inset_m", "pair_friction_steps", "pair_thickness_factors",
                      "ceiling_factor", "bracket_gaps_m", "refine_rounds")}
    text = json.dumps({"version": BANK_VERSION, "code": code, "arch": group, "freqs": [round(f, 6) for f in freqs],
                       "cycles": list(cycles), "grids": grids}, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _clean(x: float):
    return None if not math.isfinite(x) else float(f"{x:.9g}")


def save(bank: SpecimenBank, path: Path) -> None:
    d = dataclasses.asdict(bank)
    d["thresholds"] = {k: [_clean(x) for x in v] for k, v in bank.thresholds.items()}
    d["replicas"] = {k: [_clean(x) for x in v] for k, v in bank.replicas.items()}
    d["node_replicas"] = {k: {n: [_clean(x) for x in v] for n, v in r.items()} for k, r in bank.node_replicas.items()}
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(d, separators=(",", ":")) + "\n")


def load(path: Path) -> SpecimenBank:
    d = json.loads(Path(path).read_text())
    nan = lambda v: [math.nan if x is None else float(x) for x in v]
    d["thresholds"] = {k: nan(v) for k, v in d["thresholds"].items()}
    d["replicas"] = {k: nan(v) for k, v in d["replicas"].items()}
    d["node_replicas"] = {k: {n: nan(v) for n, v in r.items()} for k, r in d.get("node_replicas", {}).items()}
    d["cycles"] = tuple(d["cycles"])
    return SpecimenBank(**d)


def onset_amplitudes(runner: Runner, spec: Specimen, freqs: list[float]) -> list[float]:
    """Amplitude [m] of the onset of rocking at each frequency, from the limit analysis of
    the nominal ring: the scale of every search, known before any test."""
    group = {k: v for k, v in arch_group(spec, Variant()).items()
             if k in ("embrace_deg", "n_voussoirs", "r_ext_m", "thickness_m")}
    lam = runner.run_limit({"arch": group}, f"limit_{spec.specimen_id}").lambda_pos
    return [lam * G / (2.0 * math.pi * f) ** 2 for f in freqs]


def spread_nodes(spec: Specimen, settings: DiagnosisSettings) -> list[Variant]:
    """The models whose replicas measure the simulator's spread beside the nominal one's:
    the two ends of every single effect's grid (and brackets at both springings)."""
    out = []
    for e in ("contact_edges", "friction", "geometry", "base_restraint"):
        values = EFFECTS_BY_ID[e].simulated(spec, settings)
        if e == "base_restraint":
            out += [v for v in values if v.value == "both"]
        elif values:
            out += [values[0], values[-1]]
    return out


def replica_groups(bank: SpecimenBank, k: int) -> list[np.ndarray]:
    """The log thresholds at frequency index k of every model that has replicas: its own
    search and its replicas (the nominal model's without the dt / 2 check)."""
    groups = [[bank.thresholds["nominal"][k]] + [v[k] for n, v in bank.replicas.items() if n != FINE_DT[0]]]
    groups += [[bank.thresholds[key][k]] + [v[k] for v in reps.values()]
               for key, reps in bank.node_replicas.items() if key in bank.thresholds]
    out = []
    for g in groups:
        vals = np.array([x for x in g if math.isfinite(x) and x > 0])
        if vals.size > 1:
            out.append(np.log(vals))
    return out


def pooled_spread(bank: SpecimenBank, k: int) -> tuple[float, int]:
    """The simulator's own spread at frequency index k: the pooled standard deviation of
    log threshold within the replica groups, and its degrees of freedom."""
    groups = replica_groups(bank, k)
    ss = sum(float(np.sum((g - g.mean()) ** 2)) for g in groups)
    dof = sum(g.size - 1 for g in groups)
    return (math.sqrt(ss / dof) if dof else math.nan), dof


def _replica_spread(bank: SpecimenBank) -> float:
    """The largest pooled spread over the frequencies (the refinement's yardstick)."""
    spreads = [pooled_spread(bank, k)[0] for k in range(len(bank.frequencies_hz))]
    return max([s for s in spreads if math.isfinite(s)], default=0.0)


def refine_values(effect_id: str, values: list[float], thresholds: dict[float, list[float]], spread: float
                  ) -> list[float]:
    """The midpoints to simulate between neighbouring values of one effect whose log
    thresholds differ at any frequency by more than REFINE_SPREADS x max(spread, 1 %)."""
    limit = REFINE_SPREADS * max(spread, 0.01)
    out = []
    xs = sorted(values)
    for a, b in zip(xs[:-1], xs[1:]):
        if b - a < 2 * REFINE_MIN_STEP[effect_id] - 1e-12:
            continue
        ya, yb = np.asarray(thresholds[a], float), np.asarray(thresholds[b], float)
        ok = np.isfinite(ya) & np.isfinite(yb) & (ya > 0) & (yb > 0)
        if np.any(np.abs(np.log(yb[ok]) - np.log(ya[ok])) > limit) or np.any(np.isfinite(ya) != np.isfinite(yb)):
            out.append(round(0.5 * (a + b), 7))
    return out


def _simulate(spec: Specimen, freqs, cycles, settings: DiagnosisSettings, work: Path) -> SpecimenBank:
    sim = Simulator(settings, work)
    onset = onset_amplitudes(sim.runner, spec, freqs)
    amp_max = settings.ceiling_factor * max(onset)
    amp_tol = settings.amp_tol_fraction * min(onset)
    bank = SpecimenBank(spec.specimen_id, list(freqs), tuple(cycles), onset, amp_max, amp_tol, settings.dt_s)
    variants = bank_variants(spec, settings)
    settings.log(f"[bank] {spec.specimen_id}: {len(variants)} models x {len(freqs)} frequencies "
                 f"(+ {len(REPLICAS) + 1} replicas of the nominal model)")
    found = sim.thresholds_at(spec, freqs, cycles, variants, amp_max, amp_tol)
    for v in variants:
        bank.thresholds[variant_key(v)] = [found.get((v, f), math.nan) for f in freqs]
    searches = len(variants)
    for name, dt_factor, scan in REPLICAS + (FINE_DT,):
        other = Simulator(dataclasses.replace(settings, dt_s=settings.dt_s * dt_factor,
                                              scan_step=scan or settings.scan_step), work)
        other._count = 1000 + 10 * len(bank.replicas)
        found = other.thresholds_at(spec, freqs, cycles, [Variant()], amp_max, amp_tol)
        bank.replicas[name] = [found.get((Variant(), f), math.nan) for f in freqs]
        searches += 1
    nodes = spread_nodes(spec, settings)
    for k, (name, dt_factor, scan) in enumerate(NODE_REPLICAS):
        other = Simulator(dataclasses.replace(settings, dt_s=settings.dt_s * dt_factor,
                                              scan_step=scan or settings.scan_step), work)
        other._count = 2000 + 100 * k
        found = other.thresholds_at(spec, freqs, cycles, nodes, amp_max, amp_tol)
        for v in nodes:
            bank.node_replicas.setdefault(variant_key(v), {})[name] = [found.get((v, f), math.nan) for f in freqs]
        searches += len(nodes)
    # Steep responses: more nodes where neighbouring ones differ by more than the spread.
    spread = _replica_spread(bank)
    for round_ in range(settings.refine_rounds):
        new = []
        for e in ("contact_edges", "friction", "geometry"):
            table = {nominal_value(e, spec): bank.thresholds["nominal"]}
            for key, values in bank.thresholds.items():
                parts = key_variant(key).parts()
                if len(parts) == 1 and parts[0][0] == e:
                    table[float(parts[0][1])] = values
            new += [Variant(e, x) for x in refine_values(e, list(table), table, spread)
                    if variant_key(Variant(e, x)) not in bank.thresholds]
        if not new:
            break
        settings.log(f"[bank] {spec.specimen_id}: {len(new)} more nodes where the response is steep "
                     f"(round {round_ + 1})")
        sim._count = 3000 + 100 * round_
        found = sim.thresholds_at(spec, freqs, cycles, new, amp_max, amp_tol)
        for v in new:
            bank.thresholds[variant_key(v)] = [found.get((v, f), math.nan) for f in freqs]
        searches += len(new)
    bank.searches = searches * len(freqs)
    return bank


def load_banks(folder: Path, code: str = "stored") -> Bank:
    """The bank of every specimen stored as JSON in `folder` (one file each)."""
    files = sorted(Path(folder).glob("*.json"))
    return Bank({b.specimen_id: b for b in map(load, files)}, code)


#: A threshold a merged bank does not hold at one frequency (a node refined at another).
MISSING = -1.0


def merge(banks: list[SpecimenBank]) -> SpecimenBank:
    """One specimen's bank over every frequency, from banks of one frequency each (a model
    simulated at some frequencies only, a refined node, holds MISSING at the others)."""
    banks = sorted(banks, key=lambda b: b.frequencies_hz[0])
    if len(banks) == 1:
        return banks[0]
    freqs = [f for b in banks for f in b.frequencies_hz]

    def table(get) -> dict[str, list[float]]:
        keys = sorted(set().union(*(get(b) for b in banks)))
        return {k: [v for b in banks for v in get(b).get(k, [MISSING] * len(b.frequencies_hz))] for k in keys}

    node_keys = sorted(set().union(*(b.node_replicas for b in banks)))
    return SpecimenBank(banks[0].specimen_id, freqs, banks[0].cycles, [o for b in banks for o in b.onset_m],
                        max(b.amp_max_m for b in banks), min(b.amp_tol_m for b in banks), banks[0].dt_s,
                        table(lambda b: b.thresholds), table(lambda b: b.replicas),
                        {k: table(lambda b, k=k: b.node_replicas.get(k, {})) for k in node_keys},
                        sum(b.searches for b in banks))


def build_bank(specimens: dict[str, Specimen], frequencies: dict[str, list[float]], cycles: dict[str, tuple],
               settings: DiagnosisSettings, cache_dir: Path, work_dir: Path) -> Bank:
    """The bank of every specimen, from the cache where it is there. The cache holds one
    file per specimen and frequency (the key says which: executables, specimen, frequency,
    cycles, grids), so a test at a new frequency simulates that frequency only."""
    code = code_hash(settings.bin_dir, ("voussoir-sweep", "voussoir-limit"))
    out, reused, searches = {}, 0, 0
    for sid, spec in specimens.items():
        parts, cached = [], 0
        for f in sorted(frequencies[sid]):
            key = _cache_key(code, spec, [f], cycles[sid], settings)
            path = Path(cache_dir) / f"{sid}-{f:g}Hz-{key}.json"
            if path.exists():
                cached += 1
                settings.log(f"[bank] {sid} at {f:g} Hz: cached ({path})")
            else:
                made = _simulate(spec, [f], cycles[sid], settings, Path(work_dir) / f"{sid}-{f:g}Hz")
                searches += made.searches
                save(made, path)
            # The bank as the cache holds it (thresholds to 9 digits): a second diagnosis
            # reads the same numbers, so it computes the same posterior to the last bit.
            parts.append(load(path))
        reused += cached == len(parts)
        out[sid] = merge(parts)
    return Bank(out, code, reused, searches)
