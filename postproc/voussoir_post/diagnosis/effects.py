"""The candidate causes of shared/MEASURED_DATA.md, one class per effect.

An effect knows its parameter: the values simulated by sweeps (and how they change a
specimen's &arch group), the values tried in a fit, how a pair's threshold follows from
the simulated ones, the model a fitted value describes for single runs, and how the
value is written in diagnosis.json and in plain words. Adding an effect is adding one
class here and its instance to EFFECTS_BY_ID; nothing else branches on effect names.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..readers.campaign import Specimen
from .actuator import TableEvidence
from .settings import DiagnosisSettings

__all__ = ["COMBINED", "Variant", "Effect", "ContactEdges", "TableMotion", "BaseRestraint", "Friction", "Geometry", "EFFECTS",
           "EFFECTS_BY_ID", "RESTRAINTS", "effect", "arch_group"]

RESTRAINTS = ("left", "right", "both")
#: The Variant effect of two effects acting together.
COMBINED = "combined"


@dataclass(frozen=True)
class Variant:
    """One simulated model: the nominal one (effect None), one effect at one value, or two
    effects together (effect COMBINED, value ((id1, value1), (id2, value2)))."""

    effect: str | None = None
    value: float | str | tuple | None = None

    @property
    def label(self) -> str:
        if self.effect is None:
            return "nominal"
        if self.effect == COMBINED:
            return " + ".join(EFFECTS_BY_ID[e].label(v) for e, v in self.value)
        return EFFECTS_BY_ID[self.effect].label(self.value)

    def parts(self) -> tuple:
        """The (effect id, value) of each effect of the variant."""
        if self.effect is None:
            return ()
        return tuple(self.value) if self.effect == COMBINED else ((self.effect, self.value),)


def arch_group(spec: Specimen, variant: Variant) -> dict:
    """The &arch group of a specimen under a variant; the specimen's declared set-up
    (brackets) is part of its nominal model."""
    group = {"embrace_deg": float(spec.embrace_deg), "n_voussoirs": int(spec.n_voussoirs),
             "r_ext_m": float(spec.r_ext_m), "thickness_m": float(spec.thickness_m), "width_m": float(spec.width_m),
             "density_kg_m3": float(spec.density_kg_m3), "friction": float(spec.friction), "contact_inset_m": 0.0,
             "restrained_springings": spec.restrained_springings}
    for effect_id, value in variant.parts():
        group.update(EFFECTS_BY_ID[effect_id].arch_changes(value, spec))
    return group


class Effect:
    """A candidate cause. Subclasses set `id` and override what differs."""

    id: str = ""
    #: &sweep list that carries several values of the parameter in one sweep (None: one
    #: sweep per simulated value).
    sweep_list: str | None = None
    #: (panel position, scale, axis label) of the parameter in the candidates figure
    #: (None: not drawn).
    figure_axis: tuple[int, float, str] | None = None

    def simulated(self, spec: Specimen, settings: DiagnosisSettings) -> list[Variant]:
        """The variants simulated for this effect on one specimen."""
        return []

    def arch_changes(self, value, spec: Specimen) -> dict:
        return {}

    def nominal(self, spec: Specimen):
        """The parameter value of the nominal model (None: no nominal point on the curve)."""
        return None

    def candidate_values(self, pairs, settings: DiagnosisSettings) -> list:
        raise NotImplementedError

    def predict(self, pair, value) -> float:
        """Threshold [m] of one pair at `value`: interpolated between the simulated ones,
        the nominal point included."""
        pts = [(float(self.nominal(pair.spec)), pair.simulated[Variant()])]
        pts += [(float(v.value), t) for v, t in pair.simulated.items() if v.effect == self.id]
        pts.sort()
        x = np.array([p[0] for p in pts])
        y = np.array([p[1] for p in pts])
        good = np.isfinite(y)
        if not good.any():
            return math.nan
        return float(np.interp(value, x[good], y[good]))

    def choose(self, close: list, pairs):
        """Among values the data cannot tell apart, the smallest change from the nominal
        model of `pairs`."""
        nominal = self.nominal(pairs[0].spec)
        return close[0] if nominal is None else min(close, key=lambda v: abs(float(v) - float(nominal)))

    def fixed_value(self, table: TableEvidence):
        """A value measured elsewhere (not fitted), or None."""
        return None

    def interval(self, value, fold_values: list, near: list, table: TableEvidence) -> tuple:
        vals = [float(v) for v in fold_values] + [float(v) for v in near]
        return min(vals), max(vals)

    #: Whether the effect combines with another exactly, with nothing to simulate (a
    #: table gain divides any model's threshold).
    exact_in_combination: bool = False
    #: A change of the parameter that counts as one unit when changes of two effects are
    #: weighed against each other (parsimony of a pair); None: categorical.
    change_scale: float | None = None

    def pair_values(self, pairs, settings: DiagnosisSettings, table: TableEvidence) -> list:
        """The values tried for this effect inside a pair of effects: the fit's values, at
        most about 25 of them (a pair's grid is their product)."""
        fixed = self.fixed_value(table)
        if fixed is not None:
            return [fixed]
        values = self.candidate_values(pairs, settings)
        step = max(1, len(values) // 24)
        picked = values[::step]
        return picked if picked[-1] == values[-1] else picked + [values[-1]]

    def simulated_values(self, spec: Specimen, settings: DiagnosisSettings) -> list:
        """The values simulated for one specimen, the nominal one included (sorted)."""
        values = {float(v.value) for v in self.simulated(spec, settings)}
        if self.nominal(spec) is not None:
            values.add(float(self.nominal(spec)))
        return sorted(values)

    def model(self, value, table: TableEvidence) -> tuple[Variant, dict]:
        """The model (variant, extra &motion settings) that a fitted value describes."""
        return Variant(self.id, value), {}

    def parameters(self, c, table: TableEvidence) -> dict:
        raise NotImplementedError

    def label(self, value) -> str:
        raise NotImplementedError

    def value_text(self, c) -> str:
        """The fitted value and its interval, for the report."""
        raise NotImplementedError

    def sentence(self, c, table: TableEvidence) -> str:
        """What the fitted value means, to follow "The data are best explained if"."""
        raise NotImplementedError


class ContactEdges(Effect):
    id = "contact_edges"
    change_scale = 0.01
    sweep_list = "contact_inset_list_m"
    figure_axis = (0, 1e3, "contact inset [mm]")

    def simulated(self, spec, settings):
        return [Variant(self.id, e) for e in settings.inset_grid_m if e < 0.45 * spec.thickness_m]

    def arch_changes(self, value, spec):
        return {"contact_inset_m": float(value)}

    def nominal(self, spec):
        return 0.0

    def candidate_values(self, pairs, settings):
        top = max(settings.inset_grid_m)
        return list(np.linspace(0.0, top, int(round(top / 1e-4)) + 1))

    def parameters(self, c, table):
        return {"inset_m": {"value": float(c.value), "low": float(c.low), "high": float(c.high), "unit": "m"}}

    def label(self, value):
        return f"inset {1e3 * value:g} mm"

    def value_text(self, c):
        return f"inset {1e3 * float(c.value):.1f} mm ({1e3 * float(c.low):.1f} to {1e3 * float(c.high):.1f})"

    def sentence(self, c, table):
        return f"the joints pivot {1e3 * float(c.value):.1f} mm inside the block edges"


class Friction(Effect):
    """The joints' Coulomb coefficient, lower or higher than nominal."""

    id = "friction"
    change_scale = 0.25
    sweep_list = "friction_list"
    figure_axis = (1, 1.0, "friction coefficient")

    @staticmethod
    def _range(spec, settings) -> tuple[float, float]:
        return (max(settings.min_friction, spec.friction - max(settings.friction_steps)),
                min(settings.max_friction, spec.friction + max(settings.friction_steps)))

    def simulated(self, spec, settings):
        low, high = self._range(spec, settings)
        values = [spec.friction + s * d for d in settings.friction_steps for s in (-1.0, 1.0)]
        return [Variant(self.id, round(v, 6)) for v in sorted(values) if low - 1e-12 <= v <= high + 1e-12]

    def arch_changes(self, value, spec):
        return {"friction": float(value)}

    def nominal(self, spec):
        return spec.friction

    def candidate_values(self, pairs, settings):
        low, high = self._range(pairs[0].spec, settings)
        return list(np.linspace(low, high, int(round((high - low) / 0.005)) + 1))


    def parameters(self, c, table):
        return {"friction": {"value": float(c.value), "low": float(c.low), "high": float(c.high), "unit": ""}}

    def label(self, value):
        return f"friction {value:g}"

    def value_text(self, c):
        return f"friction {float(c.value):.3f} ({float(c.low):.3f} to {float(c.high):.3f})"

    def sentence(self, c, table):
        return f"the joints slide with a friction coefficient of {float(c.value):.2f}"


class BaseRestraint(Effect):
    """Brackets not declared in specimens.csv; a specimen whose brackets are declared
    (its `restrained_springings`) is not changed by this effect."""

    id = "base_restraint"

    def simulated(self, spec, settings):
        return [] if spec.restrained_springings != "none" else [Variant(self.id, r) for r in RESTRAINTS]

    def arch_changes(self, value, spec):
        # Declared brackets are the specimen's own: this effect leaves them as they are.
        return {} if spec.restrained_springings != "none" else {"restrained_springings": str(value)}

    def candidate_values(self, pairs, settings):
        return list(RESTRAINTS)

    def predict(self, pair, value):
        if pair.spec.restrained_springings != "none":
            return pair.simulated[Variant()]
        return pair.simulated.get(Variant(self.id, value), math.nan)

    def choose(self, close, pairs):
        order = {"left": 1, "right": 1, "both": 2}  # one bracket is the smaller change
        return min(close, key=lambda v: order[v])

    def interval(self, value, fold_values, near, table):
        return value, value

    def pair_values(self, pairs, settings, table):
        return list(RESTRAINTS)

    def simulated_values(self, spec, settings):
        return [] if spec.restrained_springings != "none" else list(RESTRAINTS)

    def parameters(self, c, table):
        sides = ["left", "right"] if c.value == "both" else [str(c.value)]
        return {"restrained_springings": {"value": sides, "low": sides, "high": sides, "unit": ""}}

    def label(self, value):
        return f"restrained {value}"

    def value_text(self, c):
        if c.value in ("left", "right"):
            return f"restrained: {c.value} (or its mirror image: an arch is symmetric, the afd motion too)"
        return f"restrained: {c.value}"

    def sentence(self, c, table):
        if c.value == "both":
            return "rotation at both springings is blocked"
        return (f"rotation at one springing is blocked (named {c.value}; the other side would do the same, "
                f"the arch and its motion being symmetric)")


class TableMotion(Effect):
    """A table gain g scales the threshold in commanded amplitude exactly by 1/g (rigid
    blocks); a pure delay does not change it: nothing to simulate. With records, each
    pair's own measured gain relative to the campaign's mean (its `gain_shape`) scales
    the fitted one: an actuator's gain changes with the frequency."""

    id = "table_motion"
    exact_in_combination = True
    change_scale = 0.3
    figure_axis = (2, 1.0, "table gain (measured / commanded)")

    def nominal(self, spec):
        return 1.0

    def candidate_values(self, pairs, settings):
        return list(np.linspace(0.7, 1.4, 141))

    def predict(self, pair, value):
        return pair.simulated[Variant()] / (float(value) * pair.gain_shape)

    def fixed_value(self, table):
        return table.gain if table.source == "records" else None

    def interval(self, value, fold_values, near, table):
        if table.source == "records":
            se = table.gain_se if math.isfinite(table.gain_se) else 0.0
            return value - 2 * se, value + 2 * se
        return super().interval(value, fold_values, near, table)

    def model(self, value, table):
        delay = table.delay_s if table.source == "records" else 0.0
        return Variant(), {"table_gain": float(value), "table_delay_s": max(0.0, float(delay))}

    def parameters(self, c, table):
        out = {"accel_gain": {"value": float(c.value), "low": float(c.low), "high": float(c.high), "unit": ""}}
        if table.source == "records":
            se = table.delay_se if math.isfinite(table.delay_se) else 0.0
            out["delay_s"] = {"value": table.delay_s, "low": table.delay_s - 2 * se,
                              "high": table.delay_s + 2 * se, "unit": "s"}
        return out

    def label(self, value):
        return f"table gain {value:.3f}"

    def value_text(self, c):
        return f"gain {float(c.value):.3f} ({float(c.low):.3f} to {float(c.high):.3f})"

    def sentence(self, c, table):
        return (f"the table moved {float(c.value):.3f} times the command"
                + (f", {1e3 * table.delay_s:.0f} ms late" if table.source == "records" else ""))


class Geometry(Effect):
    """The ring effectively thinner or thicker than nominal, about its mean radius (the
    seed paper's calibration: thickness x 0.82): thickness f t, extrados R_mean + f t / 2."""

    id = "geometry"
    change_scale = 0.24
    figure_axis = (3, 1.0, "thickness factor")

    def simulated(self, spec, settings):
        return [Variant(self.id, f) for f in settings.thickness_factors]

    def arch_changes(self, value, spec):
        r_mean = spec.r_ext_m - 0.5 * spec.thickness_m
        return {"thickness_m": float(value) * spec.thickness_m,
                "r_ext_m": r_mean + 0.5 * float(value) * spec.thickness_m}

    def nominal(self, spec):
        return 1.0

    def candidate_values(self, pairs, settings):
        low, high = min(settings.thickness_factors), max(settings.thickness_factors)
        return list(np.linspace(low, high, int(round((high - low) / 0.005)) + 1))

    def parameters(self, c, table):
        return {"thickness_factor": {"value": float(c.value), "low": float(c.low), "high": float(c.high),
                                     "unit": ""}}

    def label(self, value):
        return f"thickness x {float(value):.3g}"

    def value_text(self, c):
        return f"thickness x {float(c.value):.3f} ({float(c.low):.3f} to {float(c.high):.3f})"

    def sentence(self, c, table):
        return (f"the ring acts as if {float(c.value):.2f} times as thick as nominal (about its mean radius)")


#: The candidates, in the order of diagnosis.json's `candidates`.
EFFECTS_BY_ID: dict[str, Effect] = {e.id: e for e in (ContactEdges(), TableMotion(), BaseRestraint(), Friction(),
                                                      Geometry())}
EFFECTS = tuple(EFFECTS_BY_ID)


def effect(effect_id: str) -> Effect:
    return EFFECTS_BY_ID[effect_id]
