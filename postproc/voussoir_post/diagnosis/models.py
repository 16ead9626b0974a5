"""Stage 3a of the diagnosis: each model's predicted thresholds over its parameter prior.

A model is `none` (the nominal model), one effect, or two effects together (ids joined by
`+` in alphabetical order, as docs/measured_data.md writes them). Each has a prior over
its parameters, stated here and in the report, evaluated on a fine grid:

- contact_edges: inset uniform on 0 .. the largest simulated inset (10 mm; 8 mm in a pair);
- friction: coefficient uniform on nominal - 0.25 .. nominal + 0.25 (within 0.15 .. 0.9;
  nominal - 0.2 .. nominal + 0.1 in a pair);
- geometry: thickness factor uniform on 0.76 .. 1.12 (0.82 .. 1.06 in a pair);
- base_restraint: left, right or both, 1/3 each;
- table_motion: with table records, each pair's gain is the one its records measure
  (the records' own likelihood, in likelihood.py, weighs it); without them one gain for
  the campaign, uniform on 0.7 .. 1.4.

Through the simulated values the log threshold is smoothed by least squares (a cubic
along one parameter, a quadratic x quadratic surface in a pair, one cubic per side for a
restraint with another effect): near a chaotic band a search jitters from one simulated
value to the next, and the residuals of the fit measure that jitter (likelihood.py).
The nominal model is the mean of its search and its replicas. A search that found no
collapse below its ceiling counts as twice the ceiling.
A table gain g divides any model's threshold exactly (rigid blocks): nothing to simulate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .bank import FINE_DT, Bank, SpecimenBank, key_variant
from .effects import RESTRAINTS
from .observations import Observations

__all__ = ["EFFECT_IDS", "MODEL_IDS", "CANDIDATES", "ModelGrid", "model_grid", "model_prior", "members", "roughness", "nominal_log"]

EFFECT_IDS = ("base_restraint", "contact_edges", "friction", "geometry", "table_motion")
MODEL_IDS = ("none",) + EFFECT_IDS + tuple(f"{a}+{b}" for i, a in enumerate(EFFECT_IDS) for b in EFFECT_IDS[i + 1:])
#: The models of diagnosis.json's `candidates`, in order.
CANDIDATES = MODEL_IDS[1:]
#: Gain range of the table_motion prior without records.
GAIN_RANGE = (0.7, 1.4)
FINE = 41  #: grid points of a continuous parameter
SMOOTH_DEGREE = 3  #: of the least-squares fit of log threshold along one parameter


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
    resid_ss: np.ndarray | None = None  #: (n_pairs,) residual sum of squares of the smooth fits
    resid_dof: np.ndarray | None = None  #: (n_pairs,) their degrees of freedom

    @property
    def n(self) -> int:
        return self.mu.shape[0]


def _node_log(bank: SpecimenBank, key: str, f: float) -> float:
    t = bank.threshold(key, f)
    return math.log(t if math.isfinite(t) else 2.0 * bank.amp_max_m)


def nominal_log(bank: SpecimenBank, f: float) -> float:
    """The nominal model's log threshold: the mean over its search and the replicas at
    the same dt scale (dt x 0.97, x 1.03, other scan steps), which the chaotic band
    scatters."""
    keys = [k for k in bank.replicas if k != FINE_DT[0]]
    k = bank.index(f)
    values = [_node_log(bank, "nominal", f)] + [math.log(bank.replicas[r][k]) for r in keys
                                                 if math.isfinite(bank.replicas[r][k])]
    return float(np.mean(values))


def _axis(bank: SpecimenBank, effect_id: str, in_pair: bool, spec) -> list:
    """The simulated values of one effect in the bank (alone or inside pairs), with its
    nominal value, sorted (restraints: the three sides)."""
    if effect_id == "base_restraint":
        return list(RESTRAINTS)
    found = set()
    for key in bank.thresholds:
        parts = key_variant(key).parts()
        if (len(parts) == 2) == in_pair:
            found |= {v for e, v in parts if e == effect_id}
    return sorted(found | {_nominal_value(effect_id, spec)})


def _nominal_value(effect_id: str, spec):
    return {"contact_edges": 0.0, "friction": spec.friction, "geometry": 1.0}.get(effect_id)


def _key(parts: list[tuple]) -> str:
    parts = [(e, v) for e, v in parts if v is not None]
    return "+".join(f"{e}={v}" for e, v in sorted(parts)) if parts else "nominal"


def _table_at(bank: SpecimenBank, spec, effects: tuple[str, ...], axes: list[list], f: float) -> np.ndarray:
    """Log thresholds on the product of the simulated axes of `effects` (nominal value = no part)."""
    shape = [len(a) for a in axes]
    out = np.empty(shape)
    for idx in np.ndindex(*shape):
        parts = []
        for e, a, i in zip(effects, axes, idx):
            v = a[i]
            parts.append((e, None if v == _nominal_value(e, spec) else v))
        key = _key(parts)
        if key not in bank.thresholds:  # declared brackets: base_restraint leaves them as they are
            key = _key([(e, v) for e, v in parts if e != "base_restraint"])
        out[idx] = _node_log(bank, key, f)
    return out


def _fine(effect_id: str, axis: list) -> np.ndarray:
    if effect_id == "base_restraint":
        return np.arange(len(axis), dtype=float)
    return np.linspace(min(axis), max(axis), FINE)


def _basis(x: np.ndarray, degree: int) -> np.ndarray:
    return np.vstack([x ** k for k in range(degree + 1)]).T


def _smooth_1d(nodes: list, y: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, float, int]:
    """Least-squares cubic (fewer terms with few nodes) of log threshold over one axis,
    evaluated at x; the residual sum of squares and its degrees of freedom."""
    lo, hi = min(nodes), max(nodes)
    scale = lambda v: (np.asarray(v, dtype=float) - lo) / (hi - lo) * 2.0 - 1.0
    degree = min(SMOOTH_DEGREE, len(nodes) - 2) if len(nodes) > 2 else len(nodes) - 1
    a = _basis(scale(nodes), degree)
    coef, *_ = np.linalg.lstsq(a, y, rcond=None)
    resid = y - a @ coef
    return _basis(scale(x), degree) @ coef, float(resid @ resid), len(nodes) - degree - 1


def _smooth_2d(axes: list[list], table: np.ndarray, points: list[np.ndarray]) -> tuple[np.ndarray, float, int]:
    """Least-squares quadratic x quadratic surface of log threshold over two axes."""
    scaled = [(np.asarray(a, float) - min(a)) / (max(a) - min(a)) * 2.0 - 1.0 for a in axes]
    gx, gy = np.meshgrid(scaled[0], scaled[1], indexing="ij")
    design = lambda x, y: np.vstack([x ** i * y ** j for i in range(3) for j in range(3)]).T
    a = design(gx.ravel(), gy.ravel())
    coef, *_ = np.linalg.lstsq(a, table.ravel(), rcond=None)
    resid = table.ravel() - a @ coef
    px = (points[0] - min(axes[0])) / (max(axes[0]) - min(axes[0])) * 2.0 - 1.0
    py = (points[1] - min(axes[1])) / (max(axes[1]) - min(axes[1])) * 2.0 - 1.0
    return design(px, py) @ coef, float(resid @ resid), table.size - a.shape[1]


def _predict(bank: SpecimenBank, spec, effects: tuple[str, ...], f: float, points: list[np.ndarray],
             in_pair: bool) -> tuple[np.ndarray, float, int]:
    """Smoothed log threshold at every grid point (one array per effect), with the
    residual sum of squares of the smooth fit through the simulated nodes and its degrees
    of freedom: a search near a chaotic band jitters from node to node, and the fit keeps
    the trend while the residuals measure the jitter."""
    axes = [_axis(bank, e, in_pair, spec) for e in effects]
    table = _table_at(bank, spec, effects, axes, f)
    categorical = [e == "base_restraint" for e in effects]
    if len(effects) == 1:
        if categorical[0]:
            return table[points[0].astype(int)], 0.0, 0
        return _smooth_1d(axes[0], table, points[0])
    if not any(categorical):
        return _smooth_2d(axes, table, points)
    # A restraint (categorical) with a continuous effect: one cubic per side.
    c = categorical.index(True)
    k, x = points[c].astype(int), points[1 - c]
    rows = table if c == 0 else table.T
    out = np.empty_like(x)
    ss, dof = 0.0, 0
    for side in range(rows.shape[0]):
        sel = k == side
        pred, s_side, d_side = _smooth_1d(axes[1 - c], rows[side], x[sel])
        out[sel] = pred
        ss, dof = ss + s_side, dof + d_side
    return out, ss, dof


def roughness(bank: Bank, obs: Observations, pairs) -> tuple[np.ndarray, np.ndarray]:
    """Per pair: the residual sum of squares of every model's smooth fit through its
    simulated nodes, and the degrees of freedom (the simulator's jitter between nearby
    models; likelihood.py pools it with the replicas' spread)."""
    ss, dof = np.zeros(len(pairs)), np.zeros(len(pairs))
    for m in MODEL_IDS:
        grid = model_grid(m, bank, obs, pairs)
        ss += grid.resid_ss
        dof += grid.resid_dof
    return ss, dof


def model_grid(model_id: str, bank: Bank, obs: Observations, pairs=None) -> ModelGrid:
    """The grid of one model over the pairs `pairs` (default: the observations' pairs);
    made once per bank, model and set of pairs (it does not depend on the brackets)."""
    pairs = obs.pairs if pairs is None else pairs
    key = (model_id, obs.pairs[0].specimen_id, obs.gain_source != "none",
           tuple((p.specimen_id, round(p.frequency_hz, 9)) for p in pairs))
    if key not in bank.grids:
        bank.grids[key] = _model_grid(model_id, bank, obs, pairs)
    return bank.grids[key]


def _model_grid(model_id: str, bank: Bank, obs: Observations, pairs) -> ModelGrid:
    effects = members(model_id)
    simulated = tuple(e for e in effects if e != "table_motion")
    in_pair = len(simulated) == 2
    # The grid of each simulated parameter: the same for every subset of pairs (from the
    # campaign's first specimen), so that a posterior on some pairs predicts the others.
    ref = obs.pairs[0].specimen_id
    fine = {e: _fine(e, _axis(bank.specimens[ref], e, in_pair, obs.specimens[ref])) for e in simulated}
    mesh = np.meshgrid(*[fine[e] for e in simulated], indexing="ij") if simulated else []
    points = [m.ravel() for m in mesh]
    n = points[0].size if points else 1
    mu = np.empty((n, len(pairs)))
    resid_ss, resid_dof = np.zeros(len(pairs)), np.zeros(len(pairs))
    for j, p in enumerate(pairs):
        sb, spec = bank.specimens[p.specimen_id], obs.specimens[p.specimen_id]
        if simulated:
            mu[:, j], resid_ss[j], resid_dof[j] = _predict(sb, spec, simulated, p.frequency_hz, points, in_pair)
        else:
            mu[:, j] = nominal_log(sb, p.frequency_hz)
    values = [RESTRAINTS_ARRAY[pt.astype(int)] if e == "base_restraint" else pt for e, pt in zip(simulated, points)]
    names = simulated
    log_gain = None
    gain_per_pair = "table_motion" in effects and obs.gain_source != "none"
    if "table_motion" in effects and not gain_per_pair:
        gains = np.linspace(*GAIN_RANGE, 71)
        mu = np.repeat(mu, gains.size, axis=0)
        log_gain = np.tile(np.log(gains), n)
        values = [np.repeat(v, gains.size) for v in values] + [np.tile(gains, n)]
        names = simulated + ("table_motion",)
        n *= gains.size
    return ModelGrid(model_id, names, values, np.full(n, -math.log(n)), mu, gain_per_pair, log_gain,
                     resid_ss, resid_dof)


RESTRAINTS_ARRAY = np.array(RESTRAINTS, dtype=object)
