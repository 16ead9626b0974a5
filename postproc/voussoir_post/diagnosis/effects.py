"""The candidate causes of docs/measured_data.md, as changes of the kernel's model.

An effect knows how it is simulated: the values of its parameter that the bank
simulates for a specimen, how a value changes the specimen's &arch group, and the &sweep
list that carries many values in one sweep. Its prior and its place in the posterior are
models.py's; a table gain needs no simulation (it divides any threshold).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..readers.campaign import Specimen
from .settings import DiagnosisSettings

__all__ = ["COMBINED", "Variant", "Effect", "ContactEdges", "TableMotion", "BaseRestraint", "Friction", "Geometry",
           "EFFECTS", "EFFECTS_BY_ID", "RESTRAINTS", "BRACKET_GAPS_M", "RESTRAINT_VALUES", "restraint_value",
           "restraint_values", "restraint_parts", "effect", "arch_group", "nominal_value"]

RESTRAINTS = ("left", "right", "both")
#: The play of a bracket the bank simulates by default [m] (DiagnosisSettings
#: bracket_gaps_m): in contact, and off its voussoir by a quarter and a half of a
#: millimetre. A laboratory's brackets are set by hand against a ring that settles and
#: moves, and LMGC90's truths have them 0 to 0.5 mm off: a play of 0.43 mm takes away most
#: of their effect at some pairs and reverses it at others (bench/lmgc90/bracket_play.py,
#: docs/lmgc90.md), which brackets in contact cannot show.
BRACKET_GAPS_M = DiagnosisSettings.bracket_gaps_m


def restraint_value(side: str, gap_m: float) -> str:
    """The value of base_restraint: the side, and '@' the play [m] where there is one
    ('left', 'left@0.00025')."""
    return side if gap_m == 0 else f"{side}@{gap_m:g}"


def restraint_parts(value: str) -> tuple[str, float]:
    """(side, play [m]) of a base_restraint value."""
    side, _, gap = str(value).partition("@")
    return side, float(gap) if gap else 0.0


def restraint_values(gaps_m=BRACKET_GAPS_M) -> tuple[str, ...]:
    """Every value of base_restraint: each side with each play (a categorical parameter)."""
    return tuple(restraint_value(s, g) for s in RESTRAINTS for g in gaps_m)


#: The values of base_restraint with the default plays.
RESTRAINT_VALUES = restraint_values()
#: The Variant effect of two effects acting together.
COMBINED = "combined"


@dataclass(frozen=True)
class Variant:
    """One simulated model: the nominal one (effect None), one effect at one value, or two
    effects together (effect COMBINED, value ((id1, value1), (id2, value2)))."""

    effect: str | None = None
    value: float | str | tuple | None = None

    def parts(self) -> tuple:
        """The (effect id, value) of each effect of the variant."""
        if self.effect is None:
            return ()
        return tuple(self.value) if self.effect == COMBINED else ((self.effect, self.value),)

    @classmethod
    def of(cls, parts) -> Variant:
        """The variant of these (effect id, value) parts: the inverse of `parts`."""
        parts = tuple(parts)
        if not parts:
            return cls()
        return cls(*parts[0]) if len(parts) == 1 else cls(COMBINED, parts)


def nominal_value(effect_id: str, spec: Specimen) -> float | None:
    """The value of an effect's parameter at which it is absent (no inset, the specimen's
    friction, thickness factor 1, table gain 1); None for a restraint (categorical)."""
    return {"contact_edges": 0.0, "friction": float(spec.friction), "geometry": 1.0,
            "table_motion": 1.0}.get(effect_id)


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

    def simulated(self, spec: Specimen, settings: DiagnosisSettings) -> list[Variant]:
        """The variants the bank simulates for this effect alone on one specimen."""
        return []

    def arch_changes(self, value, spec: Specimen) -> dict:
        return {}


class ContactEdges(Effect):
    id = "contact_edges"
    sweep_list = "contact_inset_list_m"

    def simulated(self, spec, settings):
        return [Variant(self.id, e) for e in settings.inset_grid_m if e < 0.45 * spec.thickness_m]

    def arch_changes(self, value, spec):
        return {"contact_inset_m": float(value)}


class Friction(Effect):
    """The joints' Coulomb coefficient, lower or higher than nominal."""

    id = "friction"
    sweep_list = "friction_list"

    def simulated(self, spec, settings):
        low = max(settings.min_friction, spec.friction - max(settings.friction_steps))
        high = min(settings.max_friction, spec.friction + max(settings.friction_steps))
        values = [spec.friction + s * d for d in settings.friction_steps for s in (-1.0, 1.0)]
        return [Variant(self.id, round(v, 6)) for v in sorted(values) if low - 1e-12 <= v <= high + 1e-12]

    def arch_changes(self, value, spec):
        return {"friction": float(value)}


class BaseRestraint(Effect):
    """Brackets not declared in specimens.csv; a specimen whose brackets are declared
    (its `restrained_springings`) is not changed by this effect."""

    id = "base_restraint"

    def simulated(self, spec, settings):
        return [] if spec.restrained_springings != "none" else [Variant(self.id, r) for r in restraint_values(settings.bracket_gaps_m)]

    def arch_changes(self, value, spec):
        if spec.restrained_springings != "none":
            return {}
        side, gap = restraint_parts(value)
        return {"restrained_springings": side, **({"bracket_gap_m": gap} if gap else {})}


class TableMotion(Effect):
    """A table gain g scales the threshold in commanded amplitude exactly by 1/g (rigid
    blocks); a pure delay of a motion that starts from rest does not change it: nothing
    to simulate. Single runs play it as &motion table_gain and table_delay_s."""

    id = "table_motion"


class Geometry(Effect):
    """The ring effectively thinner or thicker than nominal, about its mean radius (the
    seed paper's calibration: thickness x 0.82): thickness f t, extrados R_mean + f t / 2."""

    id = "geometry"

    def simulated(self, spec, settings):
        return [Variant(self.id, f) for f in settings.thickness_factors]

    def arch_changes(self, value, spec):
        r_mean = spec.r_ext_m - 0.5 * spec.thickness_m
        return {"thickness_m": float(value) * spec.thickness_m,
                "r_ext_m": r_mean + 0.5 * float(value) * spec.thickness_m}


#: The candidates.
EFFECTS_BY_ID: dict[str, Effect] = {e.id: e for e in (ContactEdges(), TableMotion(), BaseRestraint(), Friction(),
                                                      Geometry())}
EFFECTS = tuple(EFFECTS_BY_ID)


def effect(effect_id: str) -> Effect:
    return EFFECTS_BY_ID[effect_id]
