"""The JSON written by ``voussoir-limit --json`` (docs/results_format.md)."""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field

import numpy as np

from ..namelist import parse_namelist
from ..units import G_M_S2
from .results_common import SIDE_NAMES, ResultsError

__all__ = ["LimitResult", "LpInterfaceForce", "LpInterfaceMode", "AssemblyBlock", "PlacedLoad", "read_limit_json"]


@dataclass(frozen=True)
class LpInterfaceForce:
    """One interface of the LP's static field (the JSON's ``contact_forces``): the force on
    block b from block a is (N1 + N2) n + S t, t the normal turned +90 degrees, N1 at end 1,
    N2 at end 2 [N]."""

    blocks: tuple[int, int]  #: a, b as in the JSON (1-based: voussoirs 1..n, foundations n+1 left, n+2 right)
    joint: int | None  #: the arch joint 0..n, None elsewhere
    ends_xy_m: np.ndarray  #: (2, 2)
    normal: np.ndarray  #: (2,) unit, from block a into block b
    normal_n: np.ndarray  #: (2,) N1, N2 >= 0
    shear_n: float  #: S


@dataclass(frozen=True)
class LpInterfaceMode:
    """One interface of the LP's mechanism (the JSON's ``mechanism``)."""

    blocks: tuple[int, int]  #: a, b (1-based, entries of ``blocks``)
    joint: int | None  #: the arch joint 0..n, None elsewhere
    mode: str  #: 'closed', 'hinge', 'sliding' or 'open'
    hinge_side: str | None  #: 'intrados' or 'extrados' for an arch joint's hinge, else None
    hinge_xy_m: np.ndarray | None  #: (2,) the point a hinge turns about, else None


@dataclass(frozen=True)
class AssemblyBlock:
    """One block of the assembly as analysed (the JSON's ``blocks``)."""

    vertices_xy_m: np.ndarray  #: (n, 2) counter-clockwise
    driven: bool  #: a fixed support
    name: str = ""  #: a bridge's name of the block ('span 1 voussoir 3', 'pier 1'); '' elsewhere


@dataclass(frozen=True)
class PlacedLoad:
    """One point load of ``&load`` as placed (the JSON's ``point_loads``)."""

    load: int  #: its index j in &load
    block: int  #: the block that carries it (1-based)
    xy_m: np.ndarray  #: (2,)
    force_n: np.ndarray  #: (2,) a live load at load factor 1
    live: bool


@dataclass
class LimitResult:
    """The JSON written by ``voussoir-limit --json``."""

    path: str
    lambda_pos: float
    lambda_neg: float
    hinges_pos: list[tuple[int, str]]  #: (joint, side) from the left
    hinges_neg: list[tuple[int, str]]
    min_thickness_ratio_ext: float
    min_thickness_ratio_mean: float
    n_voussoirs: int
    embrace_deg: float
    r_ext_m: float
    thickness_m: float
    contact_inset_m: float
    joint_intrados_xy_m: np.ndarray  #: (n+1, 2)
    joint_extrados_xy_m: np.ndarray  #: (n+1, 2)
    sliding: list  #: joints where friction does not carry the collapse thrust
    sliding_pos: list | None = None  #: the same per direction, when the JSON has it
    sliding_neg: list | None = None
    friction: float = math.nan
    g_m_s2: float = 9.81  #: gravity used for lambda (JSON 'g_m_s2', else the kernel's 9.81)
    code_version: str = ""
    #: Where the collapse thrust crosses each joint 0..n (0 intrados pivot, 1 extrados
    #: pivot), per direction, when the JSON has it (NaN where there is none).
    thrust_fraction_pos: np.ndarray | None = None
    thrust_fraction_neg: np.ndarray | None = None
    input_file: str = ""
    #: The LP's load factor (associative friction, load towards +x; NaN when the JSON has none)
    #: and its static field at collapse, one entry per interface (empty when there is none).
    load_factor: float = math.nan
    contact_forces: list[LpInterfaceForce] = field(default_factory=list)
    #: What was analysed: 'arch', 'restrained arch', 'wall', 'polygon file' or 'bridge'.
    assembly: str = "arch"
    #: The live load in words (the JSON's ``live_load``); '' when the JSON has none.
    live_load: str = ""
    blocks: list[AssemblyBlock] = field(default_factory=list)  #: empty in JSON files older than the key
    point_loads: list[PlacedLoad] = field(default_factory=list)
    mechanism: list[LpInterfaceMode] = field(default_factory=list)  #: the LP's, associative, live load as given
    load_factor_nonassociative: float = math.nan
    critical_x_m: float = math.nan  #: the vehicle's critical position on a path (NaN without one)
    load_factor_curve: list[tuple[float, float]] = field(default_factory=list)  #: (x_m, lambda or NaN)
    #: Per point of the curve: a live load stands over a joint's end there (refined), not a grid point.
    curve_at_joint: list[bool] = field(default_factory=list)
    #: Every setting as analysed, as namelist text (the JSON's ``config_nml``; '' in older files).
    config_nml: str = ""
    #: The LP with the horizontal acceleration turned round (towards -x), where it applies.
    #: With a &bridge fill: each live load on the fill's surface (``point_loads`` then holds
    #: none of them: they enter as strips) with the x it spreads over, and the fill's weight
    #: on each top face of a free block.
    surface_loads: list[PlacedLoad] = field(default_factory=list)
    surface_spread_x_m: list[tuple[float, float]] = field(default_factory=list)
    #: Per surface load spread by Boussinesq (``&bridge dispersion = 'boussinesq'``): its
    #: strips' ends along x [m], each strip's load [N, down, at load factor 1] and the
    #: fraction of the load Flamant's stress gave them before they were scaled to it; None
    #: for a load spread at an angle (empty list: no surface loads).
    surface_strips: list[tuple[np.ndarray, np.ndarray, float] | None] = field(default_factory=list)
    fill_loads: list[PlacedLoad] = field(default_factory=list)
    #: With its horizontal pressure: each face's force at collapse (horizontal, into the ring).
    fill_pressures: list[PlacedLoad] = field(default_factory=list)
    #: Each face's bounds of that pressure (Rankine's active, the mobilised passive) [N].
    fill_pressure_bounds_n: list[tuple[float, float]] = field(default_factory=list)
    load_factor_neg: float = math.nan
    contact_forces_neg: list[LpInterfaceForce] = field(default_factory=list)
    mechanism_neg: list[LpInterfaceMode] = field(default_factory=list)
    #: With &load_cases: each case as the JSON's ``load_cases`` gives it (name, gamma_q,
    #: gamma_g, factored_live_load_n, load_factor, ...), and the governing one (from 1);
    #: the LP keys above are the governing case's.
    load_cases: list[dict] = field(default_factory=list)
    #: Without a fill: each live patch (``patch_loads``) at its centre on the top surface,
    #: the whole patch's force (it enters the LP as strips, not in ``point_loads``).
    patch_loads: list[PlacedLoad] = field(default_factory=list)
    governing_load_case: int | None = None

    @property
    def config(self) -> dict[str, dict[str, object]]:
        """``config_nml`` as ``{group: {variable: value}}`` (empty in older files)."""
        return parse_namelist(self.config_nml)

    @property
    def has_arch(self) -> bool:
        """The JSON has an ``arch`` object (joints numbered 0..n)."""
        return self.n_voussoirs > 0

    def static_capacity_m_s2(self) -> float:
        """The static horizontal capacity [m/s2], the weaker direction: the four-hinge
        analysis's for an arch, the LP's for any other assembly. ResultsError where the
        JSON's load factor is of live point loads, not of an acceleration."""
        if math.isfinite(self.lambda_pos) or math.isfinite(self.lambda_neg):
            return min(self.lambda_pos, self.lambda_neg) * self.g_m_s2
        if not self.live_is_acceleration:
            raise ResultsError(self.path, "its load factor multiplies the live point loads of &load, not a "
                                          "horizontal acceleration: run voussoir-limit without live point loads "
                                          "for a static capacity in m/s2")
        factors = [f for f in (self.load_factor, self.load_factor_neg) if math.isfinite(f)]
        if not factors:
            raise ResultsError(self.path, "no load factor (the LP had no answer: see load_factor_note)")
        return min(factors) * self.g_m_s2

    @property
    def live_is_acceleration(self) -> bool:
        """The live load is the horizontal acceleration (no live point loads in &load)."""
        return not self.live_load or self.live_load.startswith("horizontal acceleration")


def _json_float(value) -> float:
    return math.nan if value is None else float(value)


def read_limit_json(path: str | os.PathLike) -> LimitResult:
    """Read the ``voussoir-limit --json`` output; ResultsError on a missing file, bad JSON
    or a missing key."""
    path = os.fspath(path)
    if not os.path.exists(path):
        raise ResultsError(path, "no such file")
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise ResultsError(path, f"not a JSON file: {exc}") from exc
    if not isinstance(data, dict):
        raise ResultsError(path, "expected one JSON object")
    producer = data.get("producer", "voussoir-limit")
    if producer != "voussoir-limit":
        raise ResultsError(path, f"written by '{producer}', but this command reads 'voussoir-limit' files")

    def need(obj, key, where=""):
        if key not in obj:
            raise ResultsError(path, f"missing key '{where}{key}'")
        return obj[key]

    def hinges(key):
        out = []
        for k, h in enumerate(need(data, key)):
            try:
                side = str(h["side"])
                joint = int(h["joint"])
            except (KeyError, TypeError, ValueError) as exc:
                raise ResultsError(path, f"'{key}[{k}]' must be {{\"joint\": j, \"side\": ...}}") from exc
            if side not in SIDE_NAMES:
                raise ResultsError(path, f"'{key}[{k}].side' is '{side}', expected intrados or extrados")
            out.append((joint, side))
        return out

    # A wall, a polygon file or a bridge has no "arch" object (null): no numbered joints.
    arch = need(data, "arch")
    if arch is None:
        arch = {"n_voussoirs": 0, "embrace_deg": math.nan, "r_ext_m": math.nan, "thickness_m": math.nan,
                "joint_intrados_xy_m": np.zeros((0, 2)), "joint_extrados_xy_m": np.zeros((0, 2))}
        n = -1
    else:
        n = int(need(arch, "n_voussoirs", "arch."))
    intr = np.asarray(need(arch, "joint_intrados_xy_m", "arch."), dtype=float).reshape(-1, 2)
    extr = np.asarray(need(arch, "joint_extrados_xy_m", "arch."), dtype=float).reshape(-1, 2)
    for name, arr in (("joint_intrados_xy_m", intr), ("joint_extrados_xy_m", extr)):
        if arr.shape != (n + 1, 2):
            raise ResultsError(path, f"'arch.{name}' has shape {arr.shape}, expected ({n + 1}, 2)")
    n = max(n, 0)
    critical = data.get("critical_position")
    return LimitResult(
        path=path,
        lambda_pos=_json_float(need(data, "lambda_pos")),
        lambda_neg=_json_float(need(data, "lambda_neg")),
        hinges_pos=hinges("hinges_pos"),
        hinges_neg=hinges("hinges_neg"),
        min_thickness_ratio_ext=_json_float(data.get("min_thickness_ratio_ext")),
        min_thickness_ratio_mean=_json_float(data.get("min_thickness_ratio_mean")),
        n_voussoirs=n,
        embrace_deg=float(need(arch, "embrace_deg", "arch.")),
        r_ext_m=float(need(arch, "r_ext_m", "arch.")),
        thickness_m=float(need(arch, "thickness_m", "arch.")),
        contact_inset_m=float(arch.get("contact_inset_m", 0.0) or 0.0),
        joint_intrados_xy_m=intr,
        joint_extrados_xy_m=extr,
        sliding=list(data.get("sliding", []) or []),
        sliding_pos=list(data["sliding_pos"]) if data.get("sliding_pos") is not None else None,
        sliding_neg=list(data["sliding_neg"]) if data.get("sliding_neg") is not None else None,
        friction=_json_float(data.get("friction")),
        g_m_s2=_json_float(data.get("g_m_s2", G_M_S2)),
        code_version=str(data.get("code_version", "")),
        thrust_fraction_pos=_fractions(data.get("thrust_fraction_pos")),
        thrust_fraction_neg=_fractions(data.get("thrust_fraction_neg")),
        input_file=str(data.get("input_file", "")),
        load_factor=_json_float(data.get("load_factor")),
        contact_forces=_interface_forces(path, data.get("contact_forces") or []),
        assembly=str(data.get("assembly", "arch")),
        live_load=str(data.get("live_load") or ""),
        blocks=_blocks(path, data.get("blocks") or []),
        point_loads=_point_loads(path, data.get("point_loads") or []),
        mechanism=_modes(path, "mechanism", data.get("mechanism") or []),
        load_factor_nonassociative=_json_float(data.get("load_factor_nonassociative")),
        critical_x_m=_json_float(critical.get("x_m")) if isinstance(critical, dict) else math.nan,
        load_factor_curve=[(float(c["x_m"]), _json_float(c.get("load_factor")))
                           for c in data.get("load_factor_curve") or []],
        curve_at_joint=[bool(c.get("at_joint", False)) for c in data.get("load_factor_curve") or []],
        config_nml=str(data.get("config_nml") or ""),
        surface_loads=[PlacedLoad(int(e["load"]), 0, np.asarray(e["xy_m"], dtype=float), np.asarray(e["force_n"], dtype=float),
                                  True) for e in data.get("surface_loads") or []],
        surface_spread_x_m=[(float(e["spread_x_m"][0]), float(e["spread_x_m"][1])) for e in data.get("surface_loads") or []],
        surface_strips=[(np.asarray(e["strip_edges_x_m"], dtype=float), np.asarray(e["strip_load_n"], dtype=float),
                         float(e["retained"])) if e.get("dispersion") == "boussinesq" else None
                        for e in data.get("surface_loads") or []],
        fill_loads=[PlacedLoad(0, int(e["block"]), np.asarray(e["xy_m"], dtype=float), np.asarray(e["force_n"], dtype=float),
                               False) for e in data.get("fill_loads") or []],
        fill_pressures=[PlacedLoad(0, int(e["block"]), np.asarray(e["xy_m"], dtype=float),
                                   _json_float(e.get("at_collapse_n")) * np.asarray(e["direction"], dtype=float), False)
                        for e in data.get("fill_pressures") or []],
        fill_pressure_bounds_n=[(_json_float(e.get("active_n")), _json_float(e.get("passive_n")))
                                for e in data.get("fill_pressures") or []],
        load_factor_neg=_json_float(data.get("load_factor_neg")),
        contact_forces_neg=_interface_forces(path, data.get("contact_forces_neg") or []),
        mechanism_neg=_modes(path, "mechanism_neg", data.get("mechanism_neg") or []),
        load_cases=list(data.get("load_cases") or []),
        patch_loads=[PlacedLoad(int(e["load"]), 0, np.asarray(e["xy_m"], dtype=float),
                                np.asarray(e["force_n"], dtype=float), True) for e in data.get("patch_loads") or []],
        governing_load_case=data.get("governing_load_case"),
    )


def _blocks(path: str, entries: list) -> list[AssemblyBlock]:
    out = []
    for k, e in enumerate(entries):
        try:
            out.append(AssemblyBlock(np.asarray(e["vertices_xy_m"], dtype=float).reshape(-1, 2), bool(e["driven"]),
                                     str(e.get("name", ""))))
        except (KeyError, TypeError, ValueError) as exc:
            raise ResultsError(path, f"'blocks[{k}]' must have vertices_xy_m (a list of [x, y]) and driven: "
                                     f"{exc}") from exc
    return out


def _point_loads(path: str, entries: list) -> list[PlacedLoad]:
    out = []
    for k, e in enumerate(entries):
        try:
            out.append(PlacedLoad(int(e["load"]), int(e["block"]), np.asarray(e["xy_m"], dtype=float).reshape(2),
                                  np.asarray(e["force_n"], dtype=float).reshape(2), bool(e["live"])))
        except (KeyError, TypeError, ValueError) as exc:
            raise ResultsError(path, f"'point_loads[{k}]' must have load, block, xy_m, force_n and live: "
                                     f"{exc}") from exc
    return out


def _modes(path: str, key: str, entries: list) -> list[LpInterfaceMode]:
    out = []
    for k, e in enumerate(entries):
        try:
            xy = e.get("hinge_xy_m")
            out.append(LpInterfaceMode((int(e["blocks"][0]), int(e["blocks"][1])),
                                       None if e.get("joint") is None else int(e["joint"]), str(e["mode"]),
                                       e.get("hinge_side"),
                                       None if xy is None else np.asarray(xy, dtype=float).reshape(2)))
        except (KeyError, TypeError, ValueError, IndexError) as exc:
            raise ResultsError(path, f"'{key}[{k}]' must have blocks, joint, mode and hinge_xy_m: {exc}") from exc
    return out


def _interface_forces(path: str, entries: list) -> list[LpInterfaceForce]:
    out = []
    for k, e in enumerate(entries):
        try:
            force = LpInterfaceForce(
                blocks=(int(e["blocks"][0]), int(e["blocks"][1])),
                joint=None if e.get("joint") is None else int(e["joint"]),
                ends_xy_m=np.asarray(e["ends_xy_m"], dtype=float).reshape(2, 2),
                normal=np.asarray(e["normal"], dtype=float).reshape(2),
                normal_n=np.asarray(e["normal_n"], dtype=float).reshape(2),
                shear_n=float(e["shear_n"]))
        except (KeyError, TypeError, ValueError, IndexError) as exc:
            raise ResultsError(path, f"'contact_forces[{k}]' must have blocks, joint, ends_xy_m (2 x 2), "
                                     f"normal (2), normal_n (2) and shear_n: {exc}") from exc
        out.append(force)
    return out


def _fractions(values) -> np.ndarray | None:
    if values is None:
        return None
    return np.array([math.nan if v is None else float(v) for v in values])
