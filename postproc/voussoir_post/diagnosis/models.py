"""Stage 3a of the diagnosis: each model's predicted thresholds over its parameter prior.

A model is `none` (the nominal model), one effect, or two effects together (ids joined by
`+` in alphabetical order, as docs/measured_data.md writes them). Each has a prior over
its parameters, stated here and in the report, evaluated on a fine grid:

- contact_edges: inset uniform on 1 mm .. the largest simulated inset (10 mm; 8 mm in a
  pair);
- friction: coefficient uniform on nominal - 0.25 .. nominal + 0.25 (within 0.15 .. 0.9;
  nominal - 0.2 .. nominal + 0.1 in a pair), at least 0.05 from nominal;
- geometry: thickness factor uniform on 0.76 .. 1.12 (0.82 .. 1.06 in a pair), at least
  0.04 from 1;
- base_restraint: left, right or both, 1/3 each;
- table_motion: with table records, each pair's gain is the one its records measure
  (the records' own likelihood, in likelihood.py, weighs it); without them one gain for
  the campaign, uniform on 0.7 .. 1.4.

Between the simulated values the log threshold is emulated (emulator.py: a Gaussian
process through the bank's nodes, whose nugget is the simulator's own spread measured by
the replicas): at a node the prediction is what the bank simulated there, the nominal
node is the mean of the nominal search and its replicas, and between nodes the
emulator's variance goes with the prediction (likelihood.py). The leave-one-node-out
residuals measure the emulator's lack of fit; they are reported, not taken for noise.
A search that found no collapse below its ceiling counts as twice the ceiling.
A table gain g divides any model's threshold exactly (rigid blocks): nothing to simulate.

Only material points enter a prior: a parameter at least MATERIAL from nominal whose
effect moves at least one of the campaign's tested thresholds by its material threshold
(MATERIAL_EFFECT, and twice what a specimen's build tolerance moves that pair by:
effect_sizes, material_threshold). Smaller effects are the nominal model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .bank import FINE_DT, MISSING, Bank, SpecimenBank, key_variant, pooled_spread
from .emulator import emulate
from .effects import RESTRAINTS, RESTRAINT_VALUES, nominal_value
from .observations import Observations

__all__ = ["EFFECT_IDS", "MODEL_IDS", "CANDIDATES", "ModelGrid", "model_grid", "model_prior", "members", "nominal_log",
           "sim_spread", "tolerance_spread", "BUILD_TOLERANCE", "SIM_FLOOR", "MATERIAL", "MATERIAL_EFFECT", "material",
           "effect_sizes", "material_threshold", "pair_tolerance"]

EFFECT_IDS = ("base_restraint", "contact_edges", "friction", "geometry", "table_motion")
MODEL_IDS = ("none",) + EFFECT_IDS + tuple(f"{a}+{b}" for i, a in enumerate(EFFECT_IDS) for b in EFFECT_IDS[i + 1:])
#: The models of diagnosis.json's `candidates`, in order.
CANDIDATES = MODEL_IDS[1:]
#: Gain range of the table_motion prior without records.
GAIN_RANGE = (0.7, 1.4)
#: The smallest change of each continuous parameter from its nominal value that counts as
#: a cause (docs/measured_data.md: an effect is a cause only where it is needed). Below it
#: the model would be the nominal one, or the other effect of a pair, under another name:
#: the models' priors leave these bands out, so that no two models hold the same
#: hypothesis and no model's probability is another's in disguise.
MATERIAL = {"contact_edges": 0.001, "friction": 0.05, "geometry": 0.04}
#: The smallest change of a tested threshold an effect must make to count as a cause: at
#: each grid point, each simulated effect of the model must move the log threshold of at
#: least one of the campaign's tested pairs by this much from the model without it (the
#: nominal model, or the pair's other effect alone), by the emulators. A smaller change is
#: within what the campaign discrepancy (up to 4 %) and a transducer's bias (1-2 %) make
#: by themselves (likelihood.py): no data of these tests could tell it from no effect, so
#: the priors leave it out, as they leave out the parameter bands of MATERIAL. It is
#: computed on the campaign's tested pairs (its design, not its outcomes), once per model.
MATERIAL_EFFECT = 0.05
FINE_1D = 81  #: grid points of a continuous parameter alone
FINE_2D = 21  #: grid points of each continuous parameter of a pair
SIM_FLOOR = 0.003  #: the smallest simulator spread assumed (relative)
#: A laboratory's specimen is never built to its nominal size: its ring's thickness is off
#: by about this much (relative standard deviation; the LMGC90 truths' specimens are built
#: with 1.5 %, a joiner's or mason's tolerance on a 25-40 mm ring is about the same). Too
#: small to be a cause (MATERIAL), but near a change of mechanism it moves a threshold by
#: far more than the replicas' spread: tolerance_spread measures by how much, pair by pair.
BUILD_TOLERANCE = 0.015


def members(model_id: str) -> tuple[str, ...]:
    return () if model_id == "none" else tuple(model_id.split("+"))


def model_prior(model_id: str) -> float:
    """Prior probability of a model: 1/4 for `none`, 1/2 shared by the five single
    effects, 1/4 shared by the ten pairs."""
    n = len(members(model_id))
    return 0.25 if n == 0 else (0.5 / 5 if n == 1 else 0.25 / 10)


@dataclass
class ModelGrid:
    """A model's parameter grid and its predictions."""

    model_id: str
    names: tuple[str, ...]  #: parameter names (effect ids), one per axis
    values: list[np.ndarray]  #: each parameter's value at every grid point (flattened)
    log_prior: np.ndarray  #: (n_points,) log prior weight of each point (sums to 1)
    mu: np.ndarray  #: (n_points, n_pairs) predicted log threshold, table gain 1 [log m]
    gain_per_pair: bool  #: table_motion with records: each pair's measured gain divides it
    log_gain: np.ndarray | None = None  #: (n_points,) log of a campaign gain (table_motion, no records)
    emu_var: np.ndarray | None = None  #: (n_points, n_pairs) the emulator's variance of mu
    loo_z: list | None = None  #: per pair, the emulator's standardised leave-one-node-out residuals

    @property
    def n(self) -> int:
        return self.mu.shape[0]


def _node(bank: SpecimenBank, key: str, k: int) -> tuple[float, int]:
    """(log threshold, number of searches averaged) of a node at frequency index k: the
    mean of its search and its replicas (the nominal model's at the bank's dt scale)."""
    values = [bank.thresholds[key][k]]
    if key == "nominal":
        values += [v[k] for name, v in bank.replicas.items() if name != FINE_DT[0]]
    else:
        values += [v[k] for v in bank.node_replicas.get(key, {}).values()]
    logs = [math.log(v if math.isfinite(v) else 2.0 * bank.amp_max_m) for v in values
            if not (math.isfinite(v) and v <= 0)]
    return float(np.mean(logs)), len(logs)


def nominal_log(bank: SpecimenBank, f: float) -> float:
    """The nominal model's log threshold: the mean over its search and the replicas at
    the same dt scale (dt x 0.97, x 1.03, other scan steps), which the chaotic band
    scatters."""
    return _node(bank, "nominal", bank.index(f))[0]


def sim_spread(bank: SpecimenBank, f: float) -> float:
    """The simulator's own spread (relative) at one frequency: the replicas' pooled
    standard deviation, at least SIM_FLOOR."""
    s, _ = pooled_spread(bank, bank.index(f))
    return max(SIM_FLOOR, s if math.isfinite(s) else SIM_FLOOR)


def tolerance_spread(bank: SpecimenBank, spec, f: float, tolerance: float = BUILD_TOLERANCE) -> float:
    """How far the specimen's build tolerance moves its nominal threshold at frequency f
    (relative): the root mean square, over a thickness factor 1 + e with e ~ N(0,
    tolerance^2) (Gauss-Hermite, 9 points), of the geometry emulator's change from
    its value at 1 (its mean: the emulator's variance goes with each model's own
    prediction). 0 where the bank has no geometry nodes."""
    if tolerance <= 0.0:
        return 0.0
    nodes, weights = np.polynomial.hermite_e.hermegauss(9)
    try:
        mean, _, _ = _predict(bank, spec, ("geometry",), f, [np.append(1.0 + tolerance * nodes, 1.0)], False)
    except (ValueError, IndexError, np.linalg.LinAlgError):
        return 0.0
    change = mean[:-1] - mean[-1]
    return float(np.sqrt(np.sum(weights * change ** 2) / np.sum(weights)))


def _axis(bank: SpecimenBank, effect_id: str, in_pair: bool, spec) -> list:
    """The simulated values of one effect in the bank (alone or inside pairs), with its
    nominal value, sorted (restraints: each side with each play the bank simulated, in the
    order of RESTRAINT_VALUES; the three sides in contact where the specimen's brackets are
    declared and base_restraint leaves them as they are)."""
    # The bank's keys are parsed once per bank (and again when it gains a model).
    parsed = bank.__dict__.get("_parsed_keys")
    if parsed is None or parsed[0] != len(bank.thresholds):
        parsed = bank.__dict__["_parsed_keys"] = (len(bank.thresholds),
                                                  [key_variant(key).parts() for key in bank.thresholds])
    if effect_id == "base_restraint":
        found = {v for parts in parsed[1] for e, v in parts if e == effect_id}
        order = {v: k for k, v in enumerate(RESTRAINT_VALUES)}
        return sorted(found, key=lambda v: (order.get(v, len(order)), v)) or list(RESTRAINTS)
    found = {v for parts in parsed[1] if (len(parts) == 2) == in_pair for e, v in parts if e == effect_id}
    return sorted(found | {nominal_value(effect_id, spec)})


def _key(parts: list[tuple]) -> str:
    parts = [(e, v) for e, v in parts if v is not None]
    return "+".join(f"{e}={v}" for e, v in sorted(parts)) if parts else "nominal"


def _nodes(bank: SpecimenBank, spec, effects: tuple[str, ...], axes: list[list], f: float
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every simulated node on the product of `axes`: (indices (n, d), log thresholds,
    number of searches averaged). A product point the bank lacks is left out."""
    k = bank.index(f)
    idx, ys, counts = [], [], []
    for ii in np.ndindex(*[len(a) for a in axes]):
        parts = [(e, None if a[i] == nominal_value(e, spec) else a[i]) for e, a, i in zip(effects, axes, ii)]
        key = _key(parts)
        if key not in bank.thresholds:  # declared brackets: base_restraint leaves them as they are
            key = _key([(e, v) for e, v in parts if e != "base_restraint"])
        if key not in bank.thresholds or bank.thresholds[key][k] == MISSING:  # simulated at other frequencies
            continue
        y, c = _node(bank, key, k)
        idx.append(ii)
        ys.append(y)
        counts.append(c)
    return np.array(idx, dtype=int), np.array(ys), np.array(counts, dtype=float)


def _fine(effect_id: str, axis: list, in_pair: bool) -> np.ndarray:
    if effect_id == "base_restraint":
        return np.arange(len(axis), dtype=float)
    return np.linspace(min(axis), max(axis), FINE_2D if in_pair else FINE_1D)


def _scaled(values, axis) -> np.ndarray:
    lo, hi = min(axis), max(axis)
    return (np.asarray(values, float) - lo) / (hi - lo)


def _predict(bank: SpecimenBank, spec, effects: tuple[str, ...], f: float, points: list[np.ndarray],
             in_pair: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The emulated log threshold at every grid point (one array per effect), its
    emulator variance, and the standardised leave-one-node-out residuals."""
    axes = [_axis(bank, e, in_pair, spec) for e in effects]
    idx, y, counts = _nodes(bank, spec, effects, axes, f)
    noise = sim_spread(bank, f) ** 2 / counts
    categorical = [e == "base_restraint" for e in effects]
    if all(categorical):  # the restraint alone: the node itself
        k = points[0].astype(int)
        lookup = {int(i[0]): (yy, nn) for i, yy, nn in zip(idx, y, noise)}
        return (np.array([lookup[i][0] for i in k]), np.array([lookup[i][1] for i in k]), np.zeros(0))
    if not any(categorical):
        x = np.column_stack([_scaled(np.asarray(a)[idx[:, c]], a) for c, a in enumerate(axes)])
        at = np.column_stack([_scaled(p, a) for p, a in zip(points, axes)])
        em = emulate(x, y, noise, at)
        return em.mean, em.var, em.loo_z
    # A restraint (categorical) with a continuous effect: one emulator per side.
    c = categorical.index(True)
    side, x = points[c].astype(int), points[1 - c]
    mean, var, loo = np.empty_like(x), np.empty_like(x), []
    for s in range(len(axes[c])):
        on = idx[:, c] == s
        sel = side == s
        cont = axes[1 - c]
        em = emulate(_scaled(np.asarray(cont)[idx[on, 1 - c]], cont)[:, None], y[on], noise[on],
                     _scaled(x[sel], cont)[:, None])
        mean[sel], var[sel] = em.mean, em.var
        loo.append(em.loo_z)
    return mean, var, np.concatenate(loo)


def model_grid(model_id: str, bank: Bank, obs: Observations, pairs=None) -> ModelGrid:
    """The grid of one model over the pairs `pairs` (default: the observations' pairs).
    Each pair's emulation is made once per bank and model (it does not depend on the
    brackets) and kept in bank.grids."""
    pairs = obs.pairs if pairs is None else pairs
    effects = members(model_id)
    simulated = tuple(e for e in effects if e != "table_motion")
    in_pair = len(simulated) == 2
    # The grid of each simulated parameter: the same for every subset of pairs (from the
    # campaign's first specimen), so that a posterior on some pairs predicts the others.
    ref = obs.pairs[0].specimen_id
    fine = {e: _fine(e, _axis(bank.specimens[ref], e, in_pair, obs.specimens[ref]), in_pair) for e in simulated}
    mesh = np.meshgrid(*[fine[e] for e in simulated], indexing="ij") if simulated else []
    points = [m.ravel() for m in mesh]
    n = points[0].size if points else 1
    mu, var, loo = np.empty((n, len(pairs))), np.empty((n, len(pairs))), []
    for j, p in enumerate(pairs):
        key = ("emulation", model_id, ref, p.specimen_id, round(p.frequency_hz, 9))
        if key not in bank.grids:
            sb, spec = bank.specimens[p.specimen_id], obs.specimens[p.specimen_id]
            if simulated:
                bank.grids[key] = _predict(sb, spec, simulated, p.frequency_hz, points, in_pair)
            else:
                y, count = _node(sb, "nominal", sb.index(p.frequency_hz))
                bank.grids[key] = (np.array([y]), np.array([sim_spread(sb, p.frequency_hz) ** 2 / count]),
                                   np.zeros(0))
        mu[:, j], var[:, j], z = bank.grids[key]
        loo.append(z)
    restraints = np.array(_axis(bank.specimens[ref], "base_restraint", in_pair, obs.specimens[ref]), dtype=object)
    values = [restraints[pt.astype(int)] if e == "base_restraint" else pt for e, pt in zip(simulated, points)]
    keep = material(simulated, values, obs.specimens[ref])
    if simulated:
        keep &= _material_response(model_id, bank, obs, points)
    impossible = not keep.any()  # no material point on this design: the model holds no hypothesis
    if impossible:
        keep[:] = True
    mu, var, values = mu[keep], var[keep], [v[keep] for v in values]
    n = int(keep.sum())
    names = simulated
    log_gain = None
    gain_per_pair = "table_motion" in effects and obs.gain_source != "none"
    if "table_motion" in effects and not gain_per_pair:
        gains = np.linspace(*GAIN_RANGE, 36)
        gains = gains[np.abs(np.log(gains)) >= MATERIAL_EFFECT]
        mu, var = np.repeat(mu, gains.size, axis=0), np.repeat(var, gains.size, axis=0)
        log_gain = np.tile(np.log(gains), n)
        values = [np.repeat(v, gains.size) for v in values] + [np.tile(gains, n)]
        names = simulated + ("table_motion",)
        n *= gains.size
    log_prior = np.full(n, -math.inf if impossible else -math.log(n))
    return ModelGrid(model_id, names, values, log_prior, mu, gain_per_pair, log_gain, var, loo)



def material(effects: tuple[str, ...], values: list[np.ndarray], spec) -> np.ndarray:
    """The grid points at which every continuous effect of a model departs from its
    nominal value by at least MATERIAL."""
    keep = np.ones(values[0].size if values else 1, bool)
    for e, v in zip(effects, values):
        if e in MATERIAL:
            keep &= np.abs(v.astype(float) - nominal_value(e, spec)) >= MATERIAL[e] - 1e-12
    return keep


def material_threshold(bank: Bank, obs: Observations, pair) -> float:
    """The smallest change of a pair's log threshold that counts as an effect there: at
    least MATERIAL_EFFECT, and at least twice what the specimens' build tolerance moves
    it by (tolerance_spread: near a change of mechanism a joiner's tolerance alone moves a
    threshold by 10 % or more, and no test of that pair can tell an effect from it)."""
    return max(MATERIAL_EFFECT, 2.0 * pair_tolerance(bank, obs, pair))


def pair_tolerance(bank: Bank, obs: Observations, pair) -> float:
    """tolerance_spread of one pair at the campaign's build tolerance, kept in bank.grids."""
    if pair.specimen_id not in bank.specimens:
        return 0.0
    key = ("tolerance", pair.specimen_id, round(pair.frequency_hz, 9), obs.build_tolerance)
    if key not in bank.grids:
        bank.grids[key] = tolerance_spread(bank.specimens[pair.specimen_id], obs.specimens[pair.specimen_id],
                                           pair.frequency_hz, obs.build_tolerance)
    return bank.grids[key]


def effect_sizes(bank: Bank, obs: Observations, effects: tuple[str, ...], points: list[np.ndarray]) -> np.ndarray:
    """(n_points, n_effects): for each simulated effect of a model at each point, the
    largest change it makes to a tested pair's log threshold, against the model without
    it (the nominal model for a single effect, the other effect alone for a pair, each by
    its own emulator), in units of that pair's material_threshold: 1 or more is a cause.
    Points: one array per effect, as model_grid's (a restraint by its index in
    the bank's restraint axis, _axis)."""
    in_pair = len(effects) == 2
    out = np.zeros((np.asarray(points[0]).size, len(effects)))
    for p in obs.pairs:
        sb, spec, f = bank.specimens[p.specimen_id], obs.specimens[p.specimen_id], p.frequency_hz
        full = _predict(sb, spec, effects, f, points, in_pair)[0]
        least = material_threshold(bank, obs, p)
        for i in range(len(effects)):
            if in_pair:
                other = 1 - i
                without = _predict(sb, spec, (effects[other],), f, [points[other]], False)[0]
            elif effects[i] == "base_restraint":
                without = np.full(full.shape, _node(sb, "nominal", sb.index(f))[0])
            else:  # the same emulator at the nominal value (its nodes hold the nominal one)
                without = _predict(sb, spec, effects, f, [np.array([nominal_value(effects[i], spec)])], False)[0]
            out[:, i] = np.maximum(out[:, i], np.abs(full - without) / least)
    return out


def _material_response(model_id: str, bank: Bank, obs: Observations, points: list[np.ndarray]) -> np.ndarray:
    """The grid points at which every simulated effect of the model moves a tested
    threshold by at least its material_threshold (effect_sizes), kept in bank.grids per
    model, campaign design and build tolerance."""
    key = ("material", model_id, obs.pairs[0].specimen_id, obs.build_tolerance,
           tuple((p.specimen_id, round(p.frequency_hz, 9)) for p in obs.pairs))
    if key not in bank.grids:
        effects = tuple(e for e in members(model_id) if e != "table_motion")
        bank.grids[key] = np.all(effect_sizes(bank, obs, effects, points) >= 1.0, axis=1)
    return bank.grids[key]
