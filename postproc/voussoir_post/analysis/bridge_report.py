"""A bridge assessed by ``voussoir-limit --json`` told as an assessor reads it: the
geometry (spans, rises, the ring, the fill over each crown), the loads (the ring's and
the piers' weight, the fill's, the live load and its spread through the fill, the fill's
horizontal pressure), the load factor and its critical position; and the same bridge
without the fill's passive pressure beside it (:func:`check_pair`). Everything is read
from the JSON: its ``config_nml`` (the &bridge and &load groups as analysed), its blocks
and its placed loads. :func:`report_markdown` writes the report's text around the
figures that ``voussoir-post bridge-report`` draws.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..readers.limit_results import LimitResult

__all__ = ["SpanGeometry", "BridgeSummary", "bridge_summary", "check_pair", "report_markdown", "numbered_setting",
           "vehicle_words"]

#: The &bridge variables that may differ between the two files of a pair: the passive pressure only.
_PAIR_MAY_DIFFER = ("passive_mobilisation",)


@dataclass(frozen=True)
class SpanGeometry:
    """One span as built."""

    span_m: float  #: clear span between its intrados springings
    rise_m: float  #: of its intrados above the springings
    x_left_m: float  #: its left intrados springing
    crown_extrados_m: float  #: the highest corner of its voussoirs above the springings
    voussoir_area_m2: float  #: its ring's area in elevation


@dataclass
class BridgeSummary:
    """What the report says of one JSON."""

    limit: LimitResult
    shape: str
    spans: list[SpanGeometry]
    ring_thickness_m: float
    n_voussoirs: int
    n_rings: int  #: concentric rings sharing the depth (1: one); friction between two: frictions['ring_joint']
    width_m: float
    pier_width_m: float
    pier_height_m: float
    abutment_width_m: float
    ring_density_kg_m3: float
    pier_density_kg_m3: float
    frictions: dict[str, float]
    ring_weight_n: float
    pier_weight_n: float
    n_piers: int
    fill_density_kg_m3: float
    fill_level_m: float
    fill_weight_n: float  #: on the free blocks (the fill over the abutments goes to the supports)
    dispersion_angle_deg: float
    fill_friction_deg: float
    passive_mobilisation: float
    live_loads_n: list[float]  #: each live load of &load at load factor 1
    live_total_n: float
    axle_spacing_m: float
    #: With &vehicle: the vehicle in words, and its whole axles' load [N] (before the
    #: strip's share width_m/effective_width_m); '' and 0 without one.
    vehicle: str = ""
    vehicle_total_n: float = 0.0
    dispersion: str = "angle"  #: &bridge dispersion: 'angle' or 'boussinesq'
    spread_x_m: list[tuple[float, float]] = field(default_factory=list)  #: at the critical position
    pressure_at_collapse_n: float = math.nan  #: sum of the faces' horizontal pressures, each's magnitude
    pressure_active_n: float = math.nan  #: the same, every face at its active bound
    pressure_passive_n: float = math.nan  #: every face at its mobilised passive bound
    faces_passive: int = 0  #: faces at their passive bound at collapse (above the active one)
    n_faces: int = 0
    #: Masonry backing (&bridge backing_level_m; docs/bridges.md, "Backing"): its top [m], its
    #: blocks, their weight [N], density, friction and courses; 0 blocks without backing.
    backing_level_m: float = 0.0
    backing_blocks: int = 0
    backing_weight_n: float = 0.0
    backing_density_kg_m3: float = 0.0
    backing_friction: float = math.nan
    backing_course_m: float = math.nan
    #: Each part's compressive strength for the LP [Pa] (0: rigid), where given.
    strengths_pa: dict = field(default_factory=dict)

    @property
    def load_factor(self) -> float:
        return self.limit.load_factor

    @property
    def k_active(self) -> float:
        """Rankine's active coefficient tan^2(45 - phi/2) (NaN without a friction angle)."""
        phi = self.fill_friction_deg
        return math.tan(math.radians(45.0 - phi / 2.0)) ** 2 if phi > 0 else math.nan

    @property
    def k_passive(self) -> float:
        """Rankine's passive coefficient tan^2(45 + phi/2)."""
        phi = self.fill_friction_deg
        return math.tan(math.radians(45.0 + phi / 2.0)) ** 2 if phi > 0 else math.nan

    @property
    def fill_unit_weight_kn_m3(self) -> float:
        return self.fill_density_kg_m3 * self.limit.g_m_s2 / 1e3

    def fill_depth_over_crown_m(self, span: SpanGeometry) -> float:
        return self.fill_level_m - span.crown_extrados_m if self.fill_density_kg_m3 > 0 else math.nan


def numbered_setting(group: dict, name: str) -> list[float]:
    """The entries name(1), name(2), ... of a group's effective settings, in order: a list
    (a namelist parsed by voussoir_post.namelist) or keys 'name(k)' (a run file's /config)."""
    if name in group:
        value = group[name]
        return [float(v) for v in (value if isinstance(value, list) else [value]) if v is not None]
    found = {int(k[len(name) + 1:-1]): float(v) for k, v in group.items() if k.startswith(name + "(")}
    return [found[k] for k in sorted(found)]


def vehicle_words(vehicle: dict) -> str:
    """A &vehicle group in words: "vehicle 'lm1_tandem_lane1' (axles 300 + 300 kN, 1.2 m
    apart, each over an effective width of 3 m)"."""
    name = str(vehicle.get("name", "")).strip()
    loads, gaps = numbered_setting(vehicle, "axle_load_kn"), numbered_setting(vehicle, "axle_spacing_m")
    text = f"vehicle{' ' + repr(name) if name else ''} (axle{'s' if len(loads) > 1 else ''} " \
           f"{' + '.join(f'{p:g}' for p in loads)} kN"
    if gaps:
        text += ", " + ", ".join(f"{g:g}" for g in gaps) + " m apart"
    width = float(vehicle.get("effective_width_m", 0.0) or 0.0)
    return text + (f", each over an effective width of {width:g} m)" if width > 0 else ")")


def _area(poly: np.ndarray) -> float:
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def _listed(value) -> list:
    if value is None:
        return []
    return [v for v in (value if isinstance(value, list) else [value]) if v is not None]


def bridge_summary(limit: LimitResult) -> BridgeSummary:
    """The report's numbers of one JSON; InputError when it is not a bridge's with its
    settings (``config_nml``) or has no load factor of a live load."""
    if limit.assembly != "bridge":
        raise InputError(f"{limit.path}: its assembly is '{limit.assembly}', not a bridge (&bridge): a bridge "
                         "report is of voussoir-limit --json on an input with &bridge")
    config = limit.config
    if "bridge" not in config:
        raise InputError(f"{limit.path}: no 'config_nml' with &bridge (written before voussoir-limit recorded its "
                         "settings): run voussoir-limit --json again")
    if str(config["bridge"].get("fill_model", "columns")).strip("'\" ").lower() == "particles":
        raise InputError(f"{limit.path}: its fill is particles (&bridge fill_model = 'particles'); the bridge "
                         "report tells the engineers' columns (weight, spread, pressure) and does not take "
                         "particles yet: draw its mechanism with voussoir-post mechanism")
    if limit.live_is_acceleration:
        raise InputError(f"{limit.path}: its live load is the horizontal acceleration; a bridge report is of a "
                         "live point load of &load (a vehicle), moved along a path or standing at one place")
    if not math.isfinite(limit.load_factor):
        raise InputError(f"{limit.path}: no load factor (the LP had no answer: see its load_factor_note)")
    b, load = config["bridge"], config.get("load", {})
    spans_m = [float(v) for v in _listed(b.get("span_m"))]
    rises_m = [float(v) for v in _listed(b.get("rise_m"))]
    if len(rises_m) < len(spans_m):   # a semicircle's rise may be left out
        rises_m += [s / 2.0 for s in spans_m[len(rises_m):]]
    pier_w = float(b.get("pier_width_m", 0.0))
    spans, x = [], 0.0
    g, width = limit.g_m_s2, float(b.get("width_m", 1.0))
    ring_area = 0.0
    for k, (span, rise) in enumerate(zip(spans_m, rises_m), start=1):
        # 'span k voussoir j', or with rings 'span k ring r voussoir j': every ring's.
        voussoirs = [blk.vertices_xy_m for blk in limit.blocks
                     if re.match(rf"span {k} (ring \d+ )?voussoir ", blk.name)]
        top = max((float(v[:, 1].max()) for v in voussoirs), default=math.nan)
        area = sum(_area(v) for v in voussoirs)
        ring_area += area
        spans.append(SpanGeometry(span, rise, x, top, area))
        x += span + pier_w
    piers = [blk.vertices_xy_m for blk in limit.blocks if blk.name.startswith("pier ")]
    rho_ring, rho_pier = float(b.get("ring_density_kg_m3", 0.0)), float(b.get("pier_density_kg_m3", 0.0))
    live = [float(v) for v in _listed(load.get("point_load_n"))]
    flags = _listed(load.get("point_load_live"))
    live = [p for p, is_live in zip(live, flags + [True] * len(live)) if is_live]
    if limit.load_cases:   # the governing case's live loads, as factored (the LP keys are its own)
        live = [float(np.hypot(*q.force_n)) for q in
                (limit.surface_loads or [q for q in limit.point_loads if q.live] + limit.patch_loads)]
    vehicle, vehicle_total_n = config.get("vehicle"), 0.0
    if vehicle:
        # The vehicle's axles are the live loads (&load gives only the path): on the strip,
        # axle x width_m/effective_width_m.
        axles_kn = [float(v) for v in _listed(vehicle.get("axle_load_kn"))]
        effective = float(vehicle.get("effective_width_m", 0.0) or 0.0)
        share = width / effective if effective > 0 else 1.0
        # With load cases the live loads above are the governing case's, factored: the
        # vehicle's axles among them, times its gamma_q.
        gamma_q = (float(limit.load_cases[limit.governing_load_case - 1]["gamma_q"])
                   if limit.load_cases and limit.governing_load_case else 1.0)
        if not limit.load_cases:
            live = [1e3 * p * share for p in axles_kn] + live
        vehicle_total_n = 1e3 * sum(axles_kn) * gamma_q
    backing = [blk.vertices_xy_m for blk in limit.blocks if blk.name.startswith("backing ")]
    rho_back = float(b.get("backing_density_kg_m3", 2000.0))
    strengths = {part: float(b.get(f"{part}_compressive_strength_pa", 0.0) or 0.0)
                 for part in ("ring", "pier", "backing")}
    pressures = [abs(float(p.force_n[0])) for p in limit.fill_pressures]
    bounds = limit.fill_pressure_bounds_n
    at_passive = sum(1 for f, (a, p) in zip(pressures, bounds) if p > a * (1 + 1e-9) and abs(f - p) <= 1e-9 * p)
    return BridgeSummary(
        limit=limit, shape=str(b.get("shape", "")), spans=spans,
        ring_thickness_m=float(b.get("ring_thickness_m", math.nan)), n_voussoirs=int(b.get("n_voussoirs", 0)),
        n_rings=int(b.get("n_rings", 1)),
        width_m=width, pier_width_m=pier_w, pier_height_m=float(b.get("pier_height_m", math.nan)),
        abutment_width_m=float(b.get("abutment_width_m", math.nan)),
        ring_density_kg_m3=rho_ring, pier_density_kg_m3=rho_pier,
        frictions={part: float(b.get(f"{part}_friction", math.nan))
                   for part in ("ring", "ring_joint", "pier", "abutment")},
        ring_weight_n=rho_ring * g * width * ring_area,
        pier_weight_n=rho_pier * g * width * sum(_area(p) for p in piers), n_piers=len(piers),
        fill_density_kg_m3=float(b.get("fill_density_kg_m3", 0.0)), fill_level_m=float(b.get("fill_level_m", 0.0)),
        fill_weight_n=-sum(float(p.force_n[1]) for p in limit.fill_loads),
        dispersion_angle_deg=float(b.get("dispersion_angle_deg", 0.0)),
        fill_friction_deg=float(b.get("fill_friction_deg", 0.0)),
        backing_level_m=float(b.get("backing_level_m", 0.0) or 0.0), backing_blocks=len(backing),
        backing_weight_n=rho_back * g * width * sum(_area(v) for v in backing), backing_density_kg_m3=rho_back,
        backing_friction=float(b.get("backing_friction", math.nan)),
        backing_course_m=float(b.get("backing_course_m", math.nan)),
        strengths_pa={k: v for k, v in strengths.items() if v > 0},
        passive_mobilisation=float(b.get("passive_mobilisation", 0.0)),
        live_loads_n=live, live_total_n=sum(float(np.hypot(*p.force_n)) for p in
                                            (limit.surface_loads or [q for q in limit.point_loads if q.live] + limit.patch_loads)),
        axle_spacing_m=float(load.get("axle_spacing_m", 0.0) or 0.0),
        vehicle=vehicle_words(vehicle) if vehicle else "", vehicle_total_n=vehicle_total_n,
        dispersion=str(b.get("dispersion", "angle")).strip("'\" ").lower(),
        spread_x_m=list(limit.surface_spread_x_m),
        pressure_at_collapse_n=sum(pressures) if pressures else math.nan,
        pressure_active_n=sum(a for a, _ in bounds) if bounds else math.nan,
        pressure_passive_n=sum(p for _, p in bounds) if bounds else math.nan,
        faces_passive=at_passive, n_faces=len(pressures))


def check_pair(with_passive: BridgeSummary, without: BridgeSummary) -> None:
    """InputError unless the two files are one bridge under one load, the first with the
    fill's passive pressure mobilised and the second without it."""
    a, b = with_passive.limit, without.limit
    ca, cb = a.config, b.config
    differ = sorted(k for k in set(ca["bridge"]) | set(cb["bridge"])
                    if k not in _PAIR_MAY_DIFFER and ca["bridge"].get(k) != cb["bridge"].get(k))
    if differ:
        raise InputError(f"{b.path} is not the bridge of {a.path}: &bridge differs in "
                         + ", ".join(f"{k} ({ca['bridge'].get(k)} against {cb['bridge'].get(k)})" for k in differ)
                         + "; the two files may differ in passive_mobilisation only")
    if ca.get("load") != cb.get("load"):
        raise InputError(f"{b.path} is not under the load of {a.path}: their &load groups differ")
    if without.passive_mobilisation != 0.0:
        raise InputError(f"--without-passive {b.path}: its passive_mobilisation is {without.passive_mobilisation:g}, "
                         "not 0 (the fill's passive pressure is mobilised there)")
    if not with_passive.passive_mobilisation > 0.0:
        raise InputError(f"{a.path}: its passive_mobilisation is 0 (no passive pressure), so there is nothing to "
                         "compare with --without-passive: give the file with the passive pressure first")


def _kn(value_n: float) -> str:
    return f"{value_n / 1e3:.4g}"


def _num(value: float, digits: int = 4) -> str:
    return "-" if value is None or not math.isfinite(value) else f"{value:.{digits}g}"


def _critical_lines(s: BridgeSummary) -> tuple[float, float]:
    lim = s.limit
    x = lim.critical_x_m if math.isfinite(lim.critical_x_m) else math.nan
    return x, lim.load_factor


def _load_case_lines(lim: LimitResult) -> list[str]:
    """With &load_cases: a section listing each case (its partial factors, factored live
    load, load factor = adequacy factor, critical position, collapse live load, verdict);
    the rest of the report is of the governing case. Nothing without cases."""
    if not lim.load_cases:
        return []
    gov = lim.governing_load_case
    out = ["## Load cases", "",
           "Each case's live loads times γ_Q and every permanent load (the blocks' and the fill's weight, its "
           "pressure, the dead loads) times γ_G; λ is the multiple of the factored live loads at collapse, the "
           "factored permanent loads held fixed: the adequacy factor (at least 1: the factored loads are carried).",
           "", "| case | γ_Q | γ_G | factored live load [kN] | λ (adequacy factor) | non-associative | "
           "critical position x [m] | collapse live load [kN] | |", "|---|---|---|---|---|---|---|---|---|"]
    for k, c in enumerate(lim.load_cases, start=1):
        lam = float(c["load_factor"])
        critical = c.get("critical_position")
        verdict = ("adequate" if lam >= 1.0 else "**not adequate**") + (", governs" if k == gov else "")
        out.append(f"| {k} '{c['name']}' | {float(c['gamma_q']):g} | {float(c['gamma_g']):g} | "
                   f"{_kn(float(c['factored_live_load_n']))} | {lam:.4f} | "
                   f"{_num(_json_number(c.get('load_factor_nonassociative')), 5)} | "
                   f"{_num(float(critical['x_m']), 4) if critical else 'no path'} | "
                   f"{_kn(float(c['collapse_live_load_n']))} | {verdict} |")
    if gov is not None:
        name = lim.load_cases[gov - 1]["name"]
        out += ["", f"The rest of this report is of the governing case, {gov} '{name}', its loads as factored."]
    out.append("")
    return out


def _json_number(value) -> float:
    return math.nan if value is None else float(value)


def report_markdown(main: BridgeSummary, without: BridgeSummary | None, figures: dict[str, str],
                    curve_rows: list[tuple]) -> str:
    """The report's text; ``figures`` maps 'mechanism', 'mechanism_without_passive',
    'load_position' to file names beside it (left out where absent); ``curve_rows`` the
    load-position figure's table rows (case, x, lambda, at_joint, critical)."""
    lim = main.limit
    out = [f"# Bridge report: {lim.input_file or lim.path}", ""]
    out += [f"Limit analysis by `voussoir-limit` ({lim.code_version}) of the bridge of `{lim.input_file}`, "
            f"read from `{lim.path}`" + (f" and, without the fill's passive pressure, `{without.limit.path}`"
                                         if without else "") + ". A strip of the barrel "
            f"{main.width_m:g} m wide is analysed: every load and weight below is on that strip. Coordinates: x "
            "from the left intrados springing of span 1, y above the springings, in metres.", ""]
    # Geometry
    out += ["## Geometry", "",
            "| span | shape | clear span [m] | rise [m] | span / rise | left springing at x [m] | "
            "crown extrados above the springings [m] | fill over the crown's extrados [m] |",
            "|---|---|---|---|---|---|---|---|"]
    for k, sp in enumerate(main.spans, start=1):
        out.append(f"| {k} | {main.shape} | {sp.span_m:.4g} | {sp.rise_m:.4g} | {sp.span_m / sp.rise_m:.3g} | "
                   f"{sp.x_left_m:.4g} | {sp.crown_extrados_m:.4g} | {_num(main.fill_depth_over_crown_m(sp), 3)} |")
    rings = (f" in {main.n_rings} rings of {main.ring_thickness_m / main.n_rings:g} m (joints aligned; friction "
             f"{main.frictions['ring_joint']:g} between two rings)" if main.n_rings > 1 else "")
    out += ["", f"- Ring: {main.ring_thickness_m:g} m deep (normal to the intrados){rings}, {main.n_voussoirs} voussoirs "
            f"a span, {main.ring_density_kg_m3:g} kg/m³, joint friction {main.frictions['ring']:g}.",
            f"- Abutments: reaching {main.abutment_width_m:g} m back from the outer springings, fixed; friction "
            f"{main.frictions['abutment']:g}. Springings {main.pier_height_m:g} m above the ground."]
    if main.n_piers:
        out.append(f"- Piers: {main.n_piers}, {main.pier_width_m:g} m wide, {main.pier_density_kg_m3:g} kg/m³, free "
                   f"blocks on the ground; friction {main.frictions['pier']:g}.")
    if main.backing_blocks:
        out.append(f"- Backing: masonry over the haunches up to {main.backing_level_m:g} m above the springings, "
                   f"{main.backing_blocks} free blocks in courses of {main.backing_course_m:g} m, "
                   f"{main.backing_density_kg_m3:g} kg/m³, friction {main.backing_friction:g} (no tension).")
    if main.strengths_pa:
        out.append("- Compressive strength (each interface at the lesser of its two blocks'; the others rigid): "
                   + ", ".join(f"{part} {v / 1e6:g} MPa" for part, v in main.strengths_pa.items()) + ".")
    if main.fill_density_kg_m3 > 0:
        out.append(f"- Fill: level surface {main.fill_level_m:g} m above the springings, {main.fill_density_kg_m3:g} "
                   f"kg/m³ ({main.fill_unit_weight_kn_m3:.4g} kN/m³).")
    else:
        out.append("- No fill.")
    # Loads
    out += ["", "## Loads", "", "| load | kN (on the strip) | how |", "|---|---|---|",
            f"| the ring's weight | {_kn(main.ring_weight_n)} | {main.ring_density_kg_m3:g} kg/m³ × g × the "
            f"voussoirs' area × {main.width_m:g} m |"]
    if main.n_piers:
        out.append(f"| the piers' weight | {_kn(main.pier_weight_n)} | {main.pier_density_kg_m3:g} kg/m³ |")
    if main.backing_blocks:
        out.append(f"| the backing's weight | {_kn(main.backing_weight_n)} | {main.backing_density_kg_m3:g} kg/m³ × g × "
                   f"its blocks' area × {main.width_m:g} m |")
    if main.fill_density_kg_m3 > 0 and main.backing_blocks:
        out.append(f"| the fill's weight on the ring and the backing | {_kn(main.fill_weight_n)} | the column of fill "
                   "over each bare voussoir's extrados and each top course of the backing up to the surface, at its "
                   "centroid |")
    elif main.fill_density_kg_m3 > 0:
        out.append(f"| the fill's weight on the ring | {_kn(main.fill_weight_n)} | the column of fill over each "
                   "voussoir's extrados up to the surface, at its centroid (the fill over the abutments goes to "
                   "the supports and is left out) |")
    live_words = " + ".join(_kn(p) for p in main.live_loads_n) or "-"
    spacing = f", axles {main.axle_spacing_m:g} m apart" if main.axle_spacing_m > 0 else ""
    if main.vehicle:
        out.append(f"| the live load (load factor 1) | {_kn(main.live_total_n)} | the {main.vehicle} of &vehicle: "
                   f"{live_words} kN on the strip, straight down, multiplied together by the load factor |")
    else:
        out.append(f"| the live load (load factor 1) | {_kn(main.live_total_n)} | {live_words} kN{spacing}, "
                   "straight down, multiplied together by the load factor |")
    out.append("")
    if main.fill_density_kg_m3 > 0:
        spread = "; ".join(f"x = {a:.3f} to {b:.3f} m ({b - a:.3f} m)" for a, b in main.spread_x_m)
        out.append(f"The live load stands on the fill's surface and spreads through the fill {spread_words(main)}"
                   + (f": at the critical position over {spread}." if spread else "."))
    if main.fill_friction_deg > 0:
        out.append("")
        out.append(f"The fill presses horizontally on the ring (Rankine, angle of friction "
                   f"{main.fill_friction_deg:g}°): between K_a = {main.k_active:.4f} times the vertical stress "
                   f"and {main.passive_mobilisation:g} × K_p = {main.passive_mobilisation:g} × {main.k_passive:.4f}, "
                   "the LP choosing where the ring moves into the fill. "
                   f"On {main.n_faces} faces: {_kn(main.pressure_active_n)} kN in all at the active bound, "
                   f"{_kn(main.pressure_passive_n)} kN at the mobilised passive one; at collapse "
                   f"{_kn(main.pressure_at_collapse_n)} kN, {main.faces_passive} faces at their passive bound.")
    elif main.fill_density_kg_m3 > 0:
        out += ["", "No horizontal pressure of the fill (`fill_friction_deg` = 0)."]
    out.append("")
    # Load factor
    x, lam = _critical_lines(main)
    out += _load_case_lines(lim)
    out += ["## Load factor", ""]
    cases = [("as given" if without is None else
              f"with the fill's passive pressure (mobilisation {main.passive_mobilisation:g})", main)]
    if without is not None:
        cases.append(("without the fill's passive pressure (active only)", without))
    out += ["| case | load factor λ | non-associative | collapse live load [kN] | critical position x [m] |",
            "|---|---|---|---|---|"]
    for label, s in cases:
        cx, cl = _critical_lines(s)
        out.append(f"| {label} | {cl:.4f} | {_num(s.limit.load_factor_nonassociative, 5)} | "
                   f"{_kn(cl * s.live_total_n)} | {_num(cx, 4)} |")
    out.append("")
    if without is not None:
        ratio = main.load_factor / without.load_factor
        out.append(f"The passive pressure raises the load factor by {100 * (ratio - 1):.1f} % ({ratio:.3f} times): "
                   "the number an assessor should quote depends on whether that pressure can be relied on.")
        out.append("")
    for label, s in cases:
        same = [xi for xi, li in s.limit.load_factor_curve
                if math.isfinite(li) and abs(li - s.load_factor) <= 1e-9 * abs(s.load_factor)
                and xi != s.limit.critical_x_m]
        if same:
            out.append(f"- {label}: the same least load factor (to 1e-9) also at x = "
                       + ", ".join(f"{xi:.4f}" for xi in same) + " m (a symmetric bridge's mirror position, the same "
                       "place on an identical span, or the other side of the critical joint).")
    if main.vehicle:
        out += ["", f"In whole vehicles: the {main.vehicle} weighs {_kn(main.vehicle_total_n)} kN on its axles; λ = "
                    f"{main.load_factor:.4f} is {_kn(main.load_factor * main.vehicle_total_n)} kN of such axles "
                    "at collapse" + (f" (without the passive pressure, {_kn(without.load_factor * without.vehicle_total_n)}"
                                     " kN)" if without is not None else "") + "."]
    out += ["", "λ multiplies the live load (every axle together), the dead loads, the fill's weight and its pressure "
            "bounds staying as they are: the bridge collapses under λ times the live load as given (associative "
            "friction; the non-associative column: friction without dilatancy, by the driver's iteration)."]
    out.append("")
    # Mechanism
    out += ["## Mechanism at the critical position", ""]
    if "mechanism" in figures:
        out += [f"![The LP's mechanism at the critical position]({figures['mechanism']})", ""]
    if "mechanism_without_passive" in figures:
        out += [f"![The mechanism without the fill's passive pressure]({figures['mechanism_without_passive']})", ""]
    out += ["| case | hinge or sliding between | mode | x [m] | y [m] |", "|---|---|---|---|---|"]
    for label, s in cases:
        for m in s.limit.mechanism:
            if m.mode not in ("hinge", "sliding"):
                continue
            names = [s.limit.blocks[b - 1].name for b in m.blocks]
            xy = m.hinge_xy_m if m.hinge_xy_m is not None else (math.nan, math.nan)
            out.append(f"| {label} | {' / '.join(names)} | {m.mode} | {_num(xy[0], 4)} | {_num(xy[1], 4)} |")
    out.append("")
    # Load-position curve
    out += ["## Load factor against the vehicle's position", ""]
    if "load_position" in figures:
        out += [f"![Load factor against the vehicle's position]({figures['load_position']})", "",
                "The vehicle is moved along the path of `&load` (grid points) and, besides, set a micrometre to "
                "either side of every position where one of its live loads stands over a joint's extrados end "
                "(refined points): the curve jumps at the joints, so the least of the grid alone is not the "
                "critical position. The critical position is the least of all the points.", "",
                "| case | x [m] | λ | refined at a joint | critical |", "|---|---|---|---|---|"]
        for case, xi, li, joint, critical in curve_rows:
            lam_text = f"{li:.6f}" if math.isfinite(li) else "none (the LP found no collapse)"
            out.append(f"| {case} | {xi:.6f} | {lam_text} | {'yes' if joint else ''} | "
                       f"{'**critical**' if critical else ''} |")
    else:
        out.append(f"No path in `&load`: the load stands at one position, x = {_num(x, 4)} m.")
    out.append("")
    return "\n".join(out)


def spread_words(main: BridgeSummary) -> str:
    """How the live load spreads through the fill, in words (after 'spreads through the fill')."""
    if main.dispersion == "boussinesq":
        return ("by Boussinesq: Flamant's vertical stress under a line load, on the extrados at the fill's depth "
                "there, truncated where it falls below a thousandth of the stress beneath the load (or at the deck's "
                "ends) and scaled to the load")
    return f"at {main.dispersion_angle_deg:g}° from the vertical either side, uniformly, down to the extrados"
