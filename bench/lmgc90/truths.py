"""Calibration truths of the diagnosis, made by LMGC90 (a bench, never a CI dependency).

The diagnosis (postproc/voussoir_post/diagnosis) must be calibrated and tested on
campaigns made by another code than the one it fits. This script draws truths from the
diagnosis's own prior (plus truths outside its catalogue), bakes into each a
laboratory's faults, and finds with LMGC90 3.0.0rc1 (pylmgc90) the collapse threshold
of each (arch, frequency) pair of independent_campaigns.ARCHES. One JSON per truth in
postproc/tests/data/lmgc90/<slug>.json; the tests replay them without LMGC90.

Run with the project's Python (/work/main/.venv/bin/python) and PYTHONPATH at postproc;
each LMGC90 run is a subprocess of /usr/bin/python3 (the Python pylmgc90 was built for)
with PYTHONPATH at the LMGC90 build folder, one model per process, under `nice -n 5`,
one at a time:

    python bench/lmgc90/truths.py --lmgc90-build DIR [--truths N] [--seed S] [--out DIR]
    python bench/lmgc90/truths.py --lmgc90-build DIR --check   # nominal W156 at 1.25 Hz, LMGC90 vs Voussoir
    python bench/lmgc90/truths.py --summary                    # the stored truths (no LMGC90 needed)
    python bench/lmgc90/truths.py --lmgc90-build DIR --without EFFECT SLUG [SLUG ...]

--without makes a truth's counterfactual: the same specimens with the same faults, less
one effect (an effect id of a catalogue truth's model, or `outside` for the effect of a
truth outside the catalogue, whose counterfactual is the nominal arch). It is stored in
<out>/counterfactual/<slug>_without_<effect>.json, and says by how much that effect moves
each pair's threshold in LMGC90's own physics: the calibration's labels then judge
whether it is a cause (lmgc90_campaigns.truth_model) by the generator, not by an
emulator that may not hold it (the catalogue's brackets have no play).

Resumable: truth k is drawn from numpy's default_rng([S, k]) alone, and a truth whose
file (t<k>_*.json) is already in --out is skipped. docs/lmgc90.md says how the truths
are made.

The truths (`draw_truth`):
- with probability 1/6 a truth OUTSIDE the catalogue, one of four kinds with equal odds:
  `intrados_gap` (the intrados corners of every voussoir cut at 45 degrees, leg 3-6 mm,
  the extrados corners sharp), `brackets_one_specimen` (brackets on one specimen only,
  side left/right/both, gap 0-0.5 mm), `heavy_crown` (the keystone, or both middle
  voussoirs of an even ring, 1.5-2.5 times denser), `spreading_support` (the right
  foundation drifts outward at a constant rate during the motion, 1-3 mm in all);
- otherwise a model of the diagnosis's catalogue with the prior of models.model_prior
  (`none` 1/4, each single effect 1/10, each pair 1/40) and its parameters uniform on
  the ranges of models.py's docstring (pairs: the narrower ranges):
  contact_edges: a 45-degree chamfer of every voussoir corner, leg c uniform on
  0.5-10 mm (0.5-8 mm in a pair). The chamfer cuts c off both faces at the corner, so an
  opening joint pivots on the chamfer's end, c from the face's original edge along the
  face: the equivalent `inset_m` is c (stored as both);
  friction: 0.25-0.75 (pairs 0.30-0.60); geometry: thickness factor about the mean
  radius 0.76-1.12 (pairs 0.82-1.06); base_restraint: brackets (driven blocks carried by
  the table) beside the bottom voussoir(s), side left/right/both, gap 0-0.5 mm;
  table_motion: a second-order actuator x'' + 2 z w x' + w^2 x = w^2 u (natural
  frequency 4-12 Hz, damping 0.1-0.4) whose velocity is the table's; its steady gain at
  each test frequency is stored per pair.
- laboratory faults per specimen, baked into its geometry: thickness x (1 + N(0, 0.015)),
  extrados radius x (1 + N(0, 0.005)), the right foundation set outward by U(0, 0.5) mm;
  every run starts with 0.5 s at rest in which the arch settles under gravity.

The threshold search (`search`), in COMMANDED amplitude: from 0.3 x the nominal arch's
onset of rocking (voussoir-limit's lambda g / (2 pi f)^2) upward by steps of x 1.06 to
the first collapse (cap 8 x onset), bisection between the last stand and the first
collapse down to 0.5 % of the onset, then three probes at +2, +4, +8 % above the
threshold found. Every probe is stored.
"""

from __future__ import annotations

import argparse
import dataclasses
import glob
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path.insert(0, str(ROOT / "postproc"))
sys.path.insert(0, str(ROOT / "postproc" / "tests"))

from independent_campaigns import ARCHES, Arch, Truth, ring_blocks  # noqa: E402
from voussoir_post.analysis.afd import _envelope  # noqa: E402
from voussoir_post.diagnosis.effects import RESTRAINTS  # noqa: E402
from voussoir_post.diagnosis.models import MODEL_IDS, members, model_prior  # noqa: E402

GENERATOR = "LMGC90 3.0.0rc1 via pylmgc90"
G = 9.81
DT_S = 1.0e-3
THETA = 0.5
TOL = 1.0e-4
LEAD_S = 0.5  #: at rest before the motion: the arch settles under gravity
REST_S = 1.0  #: at rest after the afd motion (1-1-1 cycles)
SCAN_START = 0.3  #: x onset
SCAN_STEP = 1.06
BISECT_TOL = 0.005  #: x onset
ABOVE = (1.02, 1.04, 1.08)
CAP = 8.0  #: x onset
OUTSIDE_P = 1.0 / 6.0
OUTSIDE_KINDS = ("intrados_gap", "brackets_one_specimen", "heavy_crown", "spreading_support")
DEFAULT_OUT = ROOT / "postproc" / "tests" / "data" / "lmgc90"
VOUSSOIR_NOMINAL_W156_125_M = 0.0642  #: docs/lmgc90.md, docs/sweep.md: Voussoir's nominal threshold


# ---------------------------------------------------------------- drawing a truth


def _draw_effect(rng: np.random.Generator, effect: str, in_pair: bool) -> dict:
    u = rng.uniform
    if effect == "contact_edges":
        c = u(0.5e-3, 8e-3 if in_pair else 10e-3)
        return {"chamfer_leg_m": c, "inset_m": c}
    if effect == "friction":
        return {"friction": u(0.30, 0.60) if in_pair else u(0.25, 0.75)}
    if effect == "geometry":
        return {"thickness_factor": u(0.82, 1.06) if in_pair else u(0.76, 1.12)}
    if effect == "base_restraint":
        return {"side": str(RESTRAINTS[rng.integers(len(RESTRAINTS))]), "gap_m": u(0.0, 0.5e-3)}
    if effect == "table_motion":
        return {"actuator_hz": u(4.0, 12.0), "actuator_damping": u(0.1, 0.4)}
    raise ValueError(effect)


def draw_truth(seed: int, k: int) -> dict:
    """Truth k of seed S: the model (as the diagnosis names it, or 'outside'), its
    parameters, and the laboratory faults of each specimen; a function of (S, k) alone."""
    rng = np.random.default_rng([seed, k])
    truth = {"index": k, "seed": seed}
    if rng.random() < OUTSIDE_P:
        kind = OUTSIDE_KINDS[rng.integers(len(OUTSIDE_KINDS))]
        truth["model"], truth["outside_kind"] = "outside", kind
        if kind == "intrados_gap":
            params = {"intrados_cut_m": rng.uniform(3e-3, 6e-3)}
        elif kind == "brackets_one_specimen":
            params = {"specimen_id": ARCHES[rng.integers(len(ARCHES))].specimen_id,
                      "side": str(RESTRAINTS[rng.integers(len(RESTRAINTS))]), "gap_m": rng.uniform(0.0, 0.5e-3)}
        elif kind == "heavy_crown":
            params = {"crown_density_factor": rng.uniform(1.5, 2.5)}
        else:
            params = {"right_drift_m": rng.uniform(1e-3, 3e-3)}
        truth["parameters"] = {kind: params}
    else:
        p = np.array([model_prior(m) for m in MODEL_IDS])
        model = MODEL_IDS[rng.choice(len(MODEL_IDS), p=p / p.sum())]
        effects = members(model)
        truth["model"] = model
        truth["parameters"] = {e: _draw_effect(rng, e, len(effects) == 2) for e in effects}
    truth["faults"] = {a.specimen_id: {"thickness_factor": 1.0 + 0.015 * rng.standard_normal(),
                                       "r_ext_factor": 1.0 + 0.005 * rng.standard_normal(),
                                       "right_support_offset_m": rng.uniform(0.0, 0.5e-3)} for a in ARCHES}
    return truth


def slug(truth: dict) -> str:
    k, model, par = truth["index"], truth["model"], truth["parameters"]
    head = f"t{k:02d}_"
    if model == "none":
        return head + "none"
    if model == "outside":
        kind = truth["outside_kind"]
        v = {"intrados_gap": lambda q: f"{1e3 * q['intrados_cut_m']:.1f}mm",
             "brackets_one_specimen": lambda q: f"{q['specimen_id']}_{q['side']}",
             "heavy_crown": lambda q: f"x{q['crown_density_factor']:.2f}",
             "spreading_support": lambda q: f"{1e3 * q['right_drift_m']:.1f}mm"}[kind](par[kind])
        return head + f"outside_{kind}_{v}"
    short = {"contact_edges": lambda q: f"{1e3 * q['chamfer_leg_m']:.1f}mm",
             "friction": lambda q: f"{q['friction']:.3f}",
             "geometry": lambda q: f"{q['thickness_factor']:.3f}",
             "base_restraint": lambda q: f"{q['side']}_{1e3 * q['gap_m']:.2f}mm",
             "table_motion": lambda q: f"{q['actuator_hz']:.1f}hz"}
    return head + "_".join(f"{e}_{short[e](par[e])}" for e in members(model))


def _rounded(x):
    if isinstance(x, float):
        return float(f"{x:.6g}")
    if isinstance(x, dict):
        return {k: _rounded(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_rounded(v) for v in x]
    return x


# ---------------------------------------------------------------- the specimen as built


def specimen_bodies(arch: Arch, truth: dict) -> tuple[list[dict], dict]:
    """The bodies of one specimen under a truth and its faults: [{role, polygon (absolute,
    counter-clockwise), density, evolution}] and a few facts (alert distance)."""
    par, fault = truth["parameters"], truth["faults"][arch.specimen_id]
    built = dataclasses.replace(arch, thickness_m=arch.thickness_m * fault["thickness_factor"],
                                r_ext_m=arch.r_ext_m * fault["r_ext_factor"])
    brackets = None
    if "base_restraint" in par:
        brackets = par["base_restraint"]
    if par.get("brackets_one_specimen", {}).get("specimen_id") == arch.specimen_id:
        brackets = par["brackets_one_specimen"]
    t = Truth(chamfer_m=par.get("contact_edges", {}).get("chamfer_leg_m", 0.0),
              intrados_cut_m=par.get("intrados_gap", {}).get("intrados_cut_m", 0.0),
              thickness_factor=par.get("geometry", {}).get("thickness_factor", 1.0),
              bracket_gap_m=None if brackets is None else brackets["gap_m"])
    blocks, _ = ring_blocks(built, t)
    n = arch.n_voussoirs
    polys = [np.array(p, float) for _, p in blocks]
    roles = [1 if r == "free" else 2 for r, _ in blocks]
    # ring_blocks: voussoirs 0..n-1 from the left, left foundation n, right foundation n+1,
    # then (with brackets) the left bracket n+2 and the right one n+3.
    keep = list(range(n + 2))
    if brackets is not None:
        keep += {"left": [n + 2], "right": [n + 3], "both": [n + 2, n + 3]}[brackets["side"]]
    polys[n + 1] = polys[n + 1] + np.array([fault["right_support_offset_m"], 0.0])
    density = [arch.density_kg_m3] * len(polys)
    if "heavy_crown" in par:
        for j in ([(n - 1) // 2] if n % 2 else [n // 2 - 1, n // 2]):
            density[j] *= par["heavy_crown"]["crown_density_factor"]
    bodies = []
    for i in keep:
        p = polys[i]
        x, y = p[:, 0], p[:, 1]
        xn, yn = np.roll(x, -1), np.roll(y, -1)
        cross = x * yn - xn * y
        area = 0.5 * cross.sum()
        c = np.array([((x + xn) * cross).sum(), ((y + yn) * cross).sum()]) / (6.0 * area)
        if area < 0:
            p = p[::-1]
        bodies.append({"role": roles[i], "polygon": p, "centroid": c, "density_kg_m3": density[i],
                       "evolution": None if roles[i] == 1 else ("right_vx.dat" if i == n + 1 else "table_vx.dat")})
    radius = min(float(np.max(np.linalg.norm(b["polygon"] - b["centroid"], axis=1))) for b in bodies
                 if b["role"] == 1)
    return bodies, {"alert_m": 0.04 * radius}


# ---------------------------------------------------------------- the table


def command_velocity(t: np.ndarray, f: float, amp: float) -> np.ndarray:
    """Velocity of the afd command (1-1-1 cycles) A e(t) sin(2 pi f t), exact."""
    e, de, _ = _envelope(t, f, 1, 1, 1)
    w = 2.0 * math.pi * f
    return amp * (de * np.sin(w * t) + e * w * np.cos(w * t))


def actuator_velocity(t: np.ndarray, f: float, amp: float, fn: float, zeta: float) -> np.ndarray:
    """Table velocity of a second-order actuator x'' + 2 z w x' + w^2 x = w^2 u(t), u the
    afd command, from rest, on a uniform grid t (the exact discrete solution with u linear
    within a step, as independent_campaigns.actuator_record)."""
    from independent_campaigns import afd_command

    w = 2.0 * math.pi * fn
    u = afd_command(t, f, amp)
    a_mat = np.array([[0.0, 1.0], [-w * w, -2.0 * zeta * w]])
    vals, vecs = np.linalg.eig(a_mat)
    h = float(t[1] - t[0])
    phi = (vecs @ np.diag(np.exp(vals * h)) @ np.linalg.inv(vecs)).real
    inv = np.linalg.inv(a_mat)
    gam0 = inv @ (phi - np.eye(2))
    gam1 = inv @ (h * phi - gam0)
    b = np.array([0.0, w * w])
    b0, b1 = gam0 @ b, (h * gam0 - gam1) @ b
    state = np.zeros(2)
    v = np.zeros_like(t)
    for k in range(1, t.size):
        state = phi @ state + b0 * u[k - 1] + b1 * (u[k] - u[k - 1]) / h
        v[k] = state[1]
    return v


def actuator_gain(f: float, fn: float, zeta: float) -> float:
    r = f / fn
    return 1.0 / math.hypot(1.0 - r * r, 2.0 * zeta * r)


def evolutions(truth: dict, f: float, amp: float) -> tuple[dict[str, np.ndarray], int, int]:
    """The velocity files of one run (time, vx columns) and its numbers of steps (all, lead)."""
    lead = int(round(LEAD_S / DT_S))
    n_steps = lead + int(round((3.0 / f + REST_S) / DT_S))
    t = np.arange(n_steps + 3) * DT_S
    tm = np.arange(n_steps + 3 - lead) * DT_S  # time from the start of the motion
    par = truth["parameters"]
    if "table_motion" in par:
        q = par["table_motion"]
        vm = actuator_velocity(tm, f, amp, q["actuator_hz"], q["actuator_damping"])
    else:
        vm = command_velocity(tm, f, amp)
    v = np.concatenate([np.zeros(lead), vm])
    right = v.copy()
    if "spreading_support" in par:
        duration = 3.0 / f
        rate = par["spreading_support"]["right_drift_m"] / duration
        right[(t >= LEAD_S - 1e-12) & (t < LEAD_S + duration - 1e-12)] += rate
    return {"table_vx.dat": np.column_stack([t, v]), "right_vx.dat": np.column_stack([t, right])}, n_steps, lead


# ---------------------------------------------------------------- LMGC90 runs


class Lmgc90Specimen:
    """One specimen's LMGC90 model in its own folder: DATBOX written once, then one
    subprocess per run with that run's evolution files."""

    def __init__(self, build: str, folder: Path, arch: Arch, truth: dict, friction: float, record_crown: bool = False):
        self.folder = folder
        self.truth = truth
        self.env = dict(os.environ, PYTHONPATH=build)
        bodies, facts = specimen_bodies(arch, truth)
        self.alert_m = facts["alert_m"]
        model = {"dt_s": DT_S, "theta": THETA, "tol": TOL, "friction": friction, "alert_m": self.alert_m,
                 "gravity_m_s2": G, "collapse_drop_m": 0.5 * arch.thickness_m, "collapse_rotation_rad": 0.5,
                 "every": 10,
                 "bodies": [{"role": b["role"], "centroid": b["centroid"].tolist(),
                             "vertices": (b["polygon"] - b["centroid"]).tolist(),
                             "density_kg_m3": b["density_kg_m3"], "evolution": b["evolution"]} for b in bodies]}
        if record_crown:   # the bodies: voussoirs 1..n from the left, then the left foundation (the table's)
            n = arch.n_voussoirs
            model["crown_bodies"] = [(n + 1) // 2] if n % 2 else [n // 2, n // 2 + 1]
            model["table_body"] = n + 1
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "model.json").write_text(json.dumps(model))
        self._call(["gen", "model.json"])
        self.lmgc_loop_s = 0.0
        self.runs = 0

    def _call(self, args):
        p = subprocess.run(["nice", "-n", "5", "/usr/bin/python3", str(HERE / "truth_case.py")] + args,
                           cwd=self.folder, env=self.env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if p.returncode != 0:
            raise RuntimeError(f"LMGC90 {' '.join(args)} in {self.folder} failed:\n{p.stderr[-3000:]}")

    def run(self, f: float, amp: float) -> tuple[bool, float | None, float]:
        files, n_steps, lead = evolutions(self.truth, f, amp)
        r = self.run_files(files, n_steps, lead)
        return bool(r["collapsed"]), (r["collapse_time_s"] if r["collapsed"] else None), r["settle_max_drop_m"]

    def run_files(self, files: dict[str, np.ndarray], n_steps: int, lead: int) -> dict:
        """One run with these evolution files (name -> (time, vx) columns): OUT.json's dict."""
        for name, arr in files.items():
            np.savetxt(self.folder / "DATBOX" / name, arr, fmt="%.10e")
        (self.folder / "run.json").write_text(json.dumps({"n_steps": n_steps, "lead_steps": lead}))
        out = self.folder / "out.json"
        out.unlink(missing_ok=True)
        self._call(["run", "model.json", "run.json", "out.json"])
        r = json.loads(out.read_text())
        self.lmgc_loop_s += r["loop_s"]
        self.runs += 1
        self.last = r
        return r

    def run_table(self, table_vx: np.ndarray, lead: int) -> bool:
        """One run whose table (and both foundations) move at `table_vx` [m/s] per step of
        DT_S after `lead` steps at rest: whether it collapsed."""
        n_steps = lead + table_vx.size
        t = np.arange(n_steps + 3) * DT_S
        v = np.concatenate([np.zeros(lead), table_vx, np.zeros(3)])
        files = {name: np.column_stack([t, v]) for name in ("table_vx.dat", "right_vx.dat")}
        return bool(self.run_files(files, n_steps, lead)["collapsed"])


# ---------------------------------------------------------------- the threshold search


def fixed_table_truth(slug: str, bench: str) -> tuple[dict, dict]:
    """(the stored truth postproc/tests/data/lmgc90/<slug>.json, its {parameters, faults}
    as Lmgc90Specimen takes them), for a bench that drives the table itself: a table
    motion or a spreading support is refused in `bench`'s name."""
    stored = json.loads((ROOT / "postproc" / "tests" / "data" / "lmgc90" / f"{slug}.json").read_text())
    par = stored["truth"]["parameters"]
    if "table_motion" in par or "spreading_support" in par:
        sys.exit(f"{bench}: {slug}: a table motion or a spreading support is not handled here")
    return stored, {"parameters": par, "faults": stored["faults"]}


def bisect(collapses, lo: float, hi: float, rel_tol: float) -> float:
    """The smallest amplitude that collapses, between a stand at `lo` and a collapse at
    `hi`, to `rel_tol` of it (geometric midpoints): the collapse end of the last bracket."""
    while hi - lo > rel_tol * hi:
        mid = math.sqrt(lo * hi) if lo > 0 else 0.5 * hi
        if collapses(mid):
            hi = mid
        else:
            lo = mid
    return hi


def search(run, onset: float) -> dict:
    """Threshold of one pair in commanded amplitude; `run(amp)` -> (collapsed, time)."""
    probes: dict[float, tuple[bool, float | None]] = {}

    def probe(a: float) -> bool:
        a = round(a, 7)
        if a not in probes:
            probes[a] = run(a)
        return probes[a][0]

    out = {"threshold_m": None, "last_stand_m": None, "never_collapsed": False, "stands_at_rest": True}
    a = SCAN_START * onset
    lo = hi = None
    if probe(a):
        if probe(0.0):
            out["stands_at_rest"] = False
        else:
            lo, hi = 0.0, a
    else:
        while True:
            nxt = a * SCAN_STEP
            if nxt > CAP * onset:
                nxt = CAP * onset
                if nxt <= a * (1 + 1e-9):
                    break
            if probe(nxt):
                lo, hi = a, nxt
                break
            a = nxt
            if a >= CAP * onset * (1 - 1e-9):
                break
        if hi is None:
            out["never_collapsed"] = True
    if hi is not None:
        while hi - lo > BISECT_TOL * onset:
            mid = 0.5 * (lo + hi)
            if probe(mid):
                hi = mid
            else:
                lo = mid
        out["threshold_m"], out["last_stand_m"] = round(hi, 7), round(lo, 7)
        for r in ABOVE:
            probe(hi * r)
    out["probes"] = [[a, int(c), None if t is None else round(t, 3)] for a, (c, t) in sorted(probes.items())]
    return out


# ---------------------------------------------------------------- a truth


_ONSETS: dict[tuple[str, float], float] = {}


def onset_m(arch: Arch, f: float, bin_dir: Path) -> float:
    """The nominal arch's onset of rocking: voussoir-limit's lambda g / (2 pi f)^2."""
    key = (arch.specimen_id, f)
    if key not in _ONSETS:
        from independent_campaigns import _onset_amplitude_m
        from voussoir_post.runner import Runner

        with tempfile.TemporaryDirectory() as d:
            _ONSETS[key] = _onset_amplitude_m(Runner(bin_dir, Path(d)), arch, f)
    return _ONSETS[key]


def make_truth(truth: dict, build: str, bin_dir: Path, work: Path, log=print) -> dict:
    t_start = time.time()
    par = truth["parameters"]
    pairs = []
    runs = 0
    for arch in ARCHES:
        friction = par.get("friction", {}).get("friction", arch.friction)
        spec = Lmgc90Specimen(build, work / arch.specimen_id, arch, truth, friction)
        for f in arch.frequencies_hz:
            t0 = time.time()
            onset = onset_m(arch, f, bin_dir)
            settle = []

            def run(a, f=f):
                c, tc, s = spec.run(f, a)
                settle.append(s)
                return c, tc

            res = search(run, onset)
            gain = 1.0
            if "table_motion" in par:
                q = par["table_motion"]
                gain = actuator_gain(f, q["actuator_hz"], q["actuator_damping"])
            pair = {"specimen_id": arch.specimen_id, "frequency_hz": f, "onset_m": round(onset, 7),
                    "table_gain": round(gain, 5), "threshold_m": res["threshold_m"],
                    "last_stand_m": res["last_stand_m"], "never_collapsed": res["never_collapsed"],
                    "stands_at_rest": res["stands_at_rest"], "alert_m": round(spec.alert_m, 7),
                    "settle_max_drop_m": round(float(np.nanmax(settle)), 7) if settle else None,
                    "n_runs": len(res["probes"]), "seconds": round(time.time() - t0, 1),
                    "probe_fields": ["amplitude_m", "collapsed", "collapse_time_s"], "probes": res["probes"]}
            runs += len(res["probes"])
            pairs.append(pair)
            thr = "none" if res["threshold_m"] is None else f"{1e3 * res['threshold_m']:.2f} mm"
            log(f"  {arch.specimen_id} {f:g} Hz: threshold {thr} (onset {1e3 * onset:.2f} mm, gain {gain:.3f}), "
                f"{len(res['probes'])} runs, {pair['seconds']:.0f} s")
    return {"generator": GENERATOR, "dt_s": DT_S, "theta": THETA, "tol": TOL, "lead_s": LEAD_S, "rest_s": REST_S,
            "motion": "afd 1-1-1 cycles, commanded amplitude; table velocity = command (or actuator response)",
            "collapse": "a voussoir dropped > half the nominal thickness or turned > 0.5 rad; time from motion start",
            "search": {"scan_start_x_onset": SCAN_START, "scan_step": SCAN_STEP, "bisect_tol_x_onset": BISECT_TOL,
                       "above": list(ABOVE), "cap_x_onset": CAP},
            "truth": {k: truth[k] for k in ("index", "seed", "model", "outside_kind", "parameters") if k in truth},
            "faults": truth["faults"], "pairs": pairs, "n_runs": runs, "seconds": round(time.time() - t_start, 1)}


def counterfactual(rec: dict, effect: str) -> dict:
    """The truth of a stored record less one effect (module docstring: --without)."""
    t = rec["truth"]
    model = t["model"]
    if effect == "outside" and model == "outside":
        kept: tuple[str, ...] = ()
    elif model != "outside" and effect in members(model):
        kept = tuple(e for e in members(model) if e != effect)
    else:
        raise SystemExit(f"truths.py: --without {effect}: not an effect of {model}")
    truth = {"index": t["index"], "seed": t["seed"], "model": "+".join(kept) or "none",
             "parameters": {e: t["parameters"][e] for e in kept}, "faults": rec["faults"]}
    return truth


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lmgc90-build", help="LMGC90 build folder (holds pylmgc90)")
    ap.add_argument("--truths", type=int, default=10, help="truths 0 .. N-1 (those stored are skipped)")
    ap.add_argument("--first", type=int, default=0, help="first truth index")
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--out", default=str(DEFAULT_OUT))
    ap.add_argument("--bin-dir", default=os.environ.get("VOUSSOIR_BIN_DIR", str(ROOT / "build" / "drivers")),
                    help="voussoir drivers (voussoir-limit for the onsets; voussoir-run for --check)")
    ap.add_argument("--check", action="store_true", help="nominal W156 at 1.25 Hz: LMGC90 against Voussoir")
    ap.add_argument("--summary", action="store_true", help="list the stored truths (no LMGC90 needed)")
    ap.add_argument("--without", nargs="+", metavar=("EFFECT", "SLUG"),
                    help="counterfactuals of stored truths less EFFECT (module docstring)")
    args = ap.parse_args(argv)
    if args.summary:
        return summary(Path(args.out))
    build = os.path.abspath(args.lmgc90_build or ".")
    if not args.lmgc90_build or not (Path(build) / "pylmgc90").is_dir():
        sys.exit(f"truths.py: no pylmgc90 in {build} (give the LMGC90 build folder)")
    bin_dir = Path(args.bin_dir)
    if not (bin_dir / "voussoir-limit").exists():
        fallback = Path("/work/main/build/drivers")
        if not (fallback / "voussoir-limit").exists():
            sys.exit(f"truths.py: no voussoir-limit in {bin_dir} (--bin-dir)")
        bin_dir = fallback
    if args.check:
        return check(build, bin_dir)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.without:
        effect, slugs = args.without[0], args.without[1:]
        (out / "counterfactual").mkdir(exist_ok=True)
        for name in slugs:
            target = out / "counterfactual" / f"{name}_without_{effect}.json"
            if target.exists():
                continue
            source = out / f"{name}.json"
            if not source.exists():
                sys.exit(f"truths.py: --without: no stored truth {source}")
            rec0 = json.loads(source.read_text())
            truth = counterfactual(rec0, effect)
            print(f"{time.strftime('%H:%M:%S')} {name} without {effect}: {truth['model']}", flush=True)
            with tempfile.TemporaryDirectory(prefix="lmgc-cf-") as d:
                rec = make_truth(truth, build, bin_dir, Path(d), log=lambda s: print(s, flush=True))
            rec["counterfactual_of"], rec["without"] = name, effect
            target.write_text(json.dumps(_rounded(rec), separators=(",", ":")) + "\n")
            print(f"{time.strftime('%H:%M:%S')} stored {target.name}: {rec['n_runs']} runs, {rec['seconds']:.0f} s",
                  flush=True)
        return 0
    for k in range(args.first, args.truths):
        if glob.glob(str(out / f"t{k:02d}_*.json")):
            continue
        truth = draw_truth(args.seed, k)
        name = slug(truth)
        print(f"{time.strftime('%H:%M:%S')} truth {k}: {name}", flush=True)
        with tempfile.TemporaryDirectory(prefix="lmgc-truth-") as d:
            rec = make_truth(truth, build, bin_dir, Path(d), log=lambda s: print(s, flush=True))
        (out / f"{name}.json").write_text(json.dumps(_rounded(rec), separators=(",", ":")) + "\n")
        print(f"{time.strftime('%H:%M:%S')} truth {k} stored: {rec['n_runs']} runs, {rec['seconds']:.0f} s "
              f"({rec['seconds'] / max(rec['n_runs'], 1):.2f} s a run)", flush=True)
    return 0


def summary(out: Path) -> int:
    """One line per stored truth: its model, each pair's threshold over the nominal arch's
    onset, its runs and seconds; then the count per model and the mean time per truth."""
    files = sorted(out.glob("t*_*.json"), key=lambda p: int(p.name[1:].split("_")[0]))
    counts: dict[str, int] = {}
    secs = []
    print(f"{'truth':58s} threshold / onset: " + " ".join(f"{a.specimen_id}@{f:g}" for a in ARCHES
                                                         for f in a.frequencies_hz))
    for path in files:
        rec = json.loads(path.read_text())
        model = rec["truth"]["model"] + (f" ({rec['truth']['outside_kind']})" if "outside_kind" in rec["truth"] else "")
        counts[model] = counts.get(model, 0) + 1
        secs.append(rec["seconds"])
        ratios = " ".join("  -  " if p["threshold_m"] is None else f"{p['threshold_m'] / p['onset_m']:.2f}"
                          for p in rec["pairs"])
        print(f"{path.stem:58s} {ratios}  {rec['n_runs']:4d} runs {rec['seconds']:5.0f} s")
    if secs:
        print(f"{len(files)} truths; " + ", ".join(f"{m}: {n}" for m, n in sorted(counts.items()))
              + f"; {np.mean(secs):.0f} s a truth (min {min(secs):.0f}, max {max(secs):.0f})")
    return 0


def check(build: str, bin_dir: Path) -> int:
    """The nominal W156 at 1.25 Hz (no effect, no faults) by this script's search, in LMGC90
    and in Voussoir (voussoir-run, the same motion, lead and criteria)."""
    from voussoir_post.runner import Runner

    arch = ARCHES[0]
    f = arch.frequencies_hz[0]
    truth = {"index": -1, "seed": -1, "model": "none", "parameters": {},
             "faults": {a.specimen_id: {"thickness_factor": 1.0, "r_ext_factor": 1.0, "right_support_offset_m": 0.0}
                        for a in ARCHES}}
    onset = onset_m(arch, f, bin_dir)
    with tempfile.TemporaryDirectory(prefix="lmgc-check-") as d:
        d = Path(d)
        t0 = time.time()
        spec = Lmgc90Specimen(build, d / "lmgc", arch, truth, arch.friction)
        lm = search(lambda a: spec.run(f, a)[:2], onset)
        t_lm = time.time() - t0
        runner = Runner(bin_dir, d)
        t0 = time.time()

        def vrun(a):
            groups = {"arch": {"embrace_deg": arch.embrace_deg, "n_voussoirs": arch.n_voussoirs,
                               "r_ext_m": arch.r_ext_m, "thickness_m": arch.thickness_m, "width_m": arch.width_m,
                               "density_kg_m3": arch.density_kg_m3, "friction": arch.friction},
                      "motion": {"waveform": "afd", "frequency_hz": f, "amplitude_m": a, "n_attack": 1,
                                 "n_full": 1, "n_decay": 1, "rest_s": REST_S, "table_delay_s": LEAD_S},
                      "solver": {"dt_s": DT_S, "theta": THETA, "tol": TOL, "allow_nonconvergence": True},
                      "output": {"every": 10, "collapse_drop_m": 0.5 * arch.thickness_m, "stop_after_collapse_s": 0.0}}
            r = runner.run_single(groups, f"v{len(os.listdir(d))}", keep=False)
            return bool(r.collapsed), (float(r.collapse_time_s) - LEAD_S if r.collapsed else None)

        vo = search(vrun, onset)
        t_vo = time.time() - t0
    print(f"nominal W156 at {f} Hz, dt {DT_S} s, onset {1e3 * onset:.2f} mm")
    for name, res, secs in (("LMGC90", lm, t_lm), ("Voussoir", vo, t_vo)):
        thr = res["threshold_m"]
        print(f"  {name:8s}: threshold {1e3 * thr:.2f} mm (last stand {1e3 * res['last_stand_m']:.2f} mm), "
              f"{len(res['probes'])} runs, {secs:.0f} s; collapsed above at "
              + ", ".join(f"{1e3 * a:.2f}:{'C' if c else 's'}" for a, c, _ in res["probes"] if a > thr))
    print(f"  Voussoir's quoted nominal threshold (docs/lmgc90.md): {1e3 * VOUSSOIR_NOMINAL_W156_125_M:.1f} mm")
    rel = lm["threshold_m"] / vo["threshold_m"] - 1.0
    print(f"  LMGC90 / Voussoir - 1 = {100 * rel:+.2f} %")
    return 0 if abs(rel) < 0.03 else 1


if __name__ == "__main__":
    sys.exit(main())
