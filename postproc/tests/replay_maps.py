"""Outcome maps: stored single runs of the independent generator, replayed as campaigns.

A test of the diagnosis has to assert *rates* (how often the right cause is named) over
many noise draws, and a campaign written by `independent_campaigns.write_campaign` costs
a ramp of runs per (arch, frequency). The runs do not depend on the noise, so they are
made once and stored:

- an *outcome map* of a truth (`outcome_map`) is, for each arch of `ARCHES` and each of
  its frequencies, the onset amplitude write_campaign starts from and whether the arch
  collapsed at amplitudes a_k = onset (lo + k step), k = 0, 1, ..., from below the
  start of write_campaign's ramps to some way past the first collapse. Each run is made
  exactly as write_campaign makes its tests (the arch as a polygon file of its own
  geometry, the true friction, the table as write_campaign plays it, dt 5e-4 s), with the
  table gain 1: a test of command A and gain g is the run of command A g;
- a *replay* (`draw_observations`) walks write_campaign's ramp over a map: each test
  draws its table gain, takes the outcome of the map amplitude nearest to A g and adds
  the noise of a measured gain. Its result is the `Observations` the diagnosis reads
  from a campaign folder. Past a map's last amplitude its last outcome is assumed (a
  ramp that misses a narrow collapse window may walk off the map), and an amplitude
  between map points takes the nearer one's outcome (exact to a map step, 1 % of the
  onset).

A replay is a noise draw over stored runs of the independent generator (polygon blocks,
chamfers, brackets as driven blocks, an integrated actuator, dt 5e-4 s), not over the
diagnosis's own model: the maps keep the tests free of the inverse crime that
independent_campaigns.py is there to avoid. The maps of `MAP_TRUTHS` are stored in
`data/replay/maps/<slug>.json` and remade by running this file (see ``--help``); the
time each map took is printed.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from independent_campaigns import (ARCHES, Arch, Truth, _motion, _onset_amplitude_m, ring_blocks, run_groups,
                                   write_polygon_file)
from voussoir_post.diagnosis.observations import Observations, PairObservation
from voussoir_post.runner import Runner, find_bin_dir

__all__ = ["MAP_DIR", "MAP_TRUTHS", "truth_model", "table_gain", "outcome_map", "first_collapse_ratio",
           "draw_observations", "save_map", "load_map", "load_stored_map"]

MAP_DIR = Path(__file__).resolve().parent / "data" / "replay" / "maps"  #: the stored maps

#: The truths whose maps are stored, by file name (slug).
MAP_TRUTHS: dict[str, Truth] = {
    "nothing": Truth(),
    "friction_0.43": Truth(friction=0.43),
    "chamfer_3mm": Truth(chamfer_m=0.003),
    "ring_0.85": Truth(thickness_factor=0.85),
    "chamfer_4mm_friction_0.42": Truth(chamfer_m=0.004, friction=0.42),
    "intrados_gap_5mm": Truth(intrados_cut_m=0.005),
    "actuator_6hz": Truth(actuator_hz=6.0, actuator_damping=0.2),
    "brackets_0.3mm": Truth(bracket_gap_m=0.0003),
}

SNAP_M = 5e-4  #: write_campaign's amplitudes are multiples of this


# ---------------------------------------------------------------- the truth, as the diagnosis names it


def truth_model(truth: Truth, arches=ARCHES) -> str:
    """The diagnosis's model id of a truth: 'none'; one of 'base_restraint',
    'contact_edges', 'friction', 'geometry', 'table_motion'; two of these joined by
    '+' in alphabetical order; or 'outside' (an intrados gap, brackets on some of the
    specimens only, or more than two effects: nothing the catalogue's models hold)."""
    with_brackets = {a.specimen_id for a in arches if truth.bracket_gap_m is not None
                     and (truth.bracket_specimens is None or a.specimen_id in truth.bracket_specimens)}
    if truth.intrados_cut_m > 0.0 or 0 < len(with_brackets) < len(arches):
        return "outside"
    parts = []
    if with_brackets:
        parts.append("base_restraint")
    if truth.chamfer_m > 0.0:
        parts.append("contact_edges")
    if truth.friction is not None and any(truth.friction != a.friction for a in arches):
        parts.append("friction")
    if truth.thickness_factor != 1.0:
        parts.append("geometry")
    if truth.actuator_hz is not None:
        parts.append("table_motion")
    if len(parts) > 2:
        return "outside"
    return "+".join(sorted(parts)) or "none"


def table_gain(truth: Truth, frequency_hz: float) -> float:
    """The table's steady amplitude over the command's at a frequency: 1, or for an
    actuator |H(f)| = 1 / hypot(1 - r^2, 2 zeta r), r = f / f_actuator."""
    if truth.actuator_hz is None:
        return 1.0
    r = frequency_hz / truth.actuator_hz
    return 1.0 / math.hypot(1.0 - r * r, 2.0 * truth.actuator_damping * r)


# ---------------------------------------------------------------- making a map


def _ramp_pair(runner: Runner, tmp: Path, arch: Arch, poly_file: Path, frequency_hz: float, onset_m: float,
               truth: Truth, dt_s: float, lo: float, step: float, after: int, max_factor: float) -> dict:
    """The runs of one (arch, frequency) at a_k = onset (lo + k step), one after the
    other, until the last `after` points all collapsed (past the first collapse) or past
    max_factor onset."""
    friction = arch.friction if truth.friction is None else truth.friction
    amplitudes_m, collapsed = [], []
    first = None
    k = 0
    while True:
        amp_m = onset_m * (lo + k * step)
        if amp_m > max_factor * onset_m:
            break
        run_id = f"{arch.specimen_id}_f{frequency_hz:g}_k{k:03d}"
        motion, _ = _motion(tmp, run_id, frequency_hz, amp_m, 1.0, truth, dt_s)
        # The groups of write_campaign's tests, the table gain aside.
        run = runner.run_single(run_groups(arch, poly_file, friction, motion, dt_s), run_id, keep=False)
        (tmp / f"{run_id}_table.csv").unlink(missing_ok=True)
        amplitudes_m.append(amp_m)
        collapsed.append(bool(run.collapsed))
        if first is None and run.collapsed:
            first = k
        # Collapse is not monotonic in amplitude: the map ends only on `after` collapses
        # in a row, so that a ramp that walks past a window of collapse finds the next.
        if first is not None and k - first >= after and all(collapsed[-after:]):
            break
        k += 1
    return {"specimen_id": arch.specimen_id, "frequency_hz": frequency_hz, "onset_m": onset_m,
            "table_gain": table_gain(truth, frequency_hz), "amplitudes_m": amplitudes_m, "collapsed": collapsed}


def first_collapse_ratio(pair: dict) -> float:
    """The first collapse amplitude of a map pair over its onset (nan: none)."""
    for a, c in zip(pair["amplitudes_m"], pair["collapsed"]):
        if c:
            return a / pair["onset_m"]
    return math.nan


def outcome_map(truth: Truth, bin_dir, arches=ARCHES, dt_s: float = 5e-4, lo: float = 0.7, step: float = 0.01,
                after: int = 10, max_factor: float = 3.5, log=print) -> dict:
    """The outcome map of a truth (see the module's docstring): for every arch and
    frequency, the onset amplitude [m] of write_campaign and whether the arch collapsed
    at each amplitude a_k = onset (lo + k step) [m], run as write_campaign runs its
    tests with the table gain 1, from k = 0 until `after` collapses in a row past the first collapse
    or until a_k > max_factor onset. Two runs at a time (one pair per thread). Returns a
    JSON-able dict: truth, truth_model, dt_s, and pairs (specimen_id, frequency_hz,
    onset_m, table_gain, amplitudes_m, collapsed)."""
    started = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        runner = Runner(bin_dir, tmp)
        jobs = []
        for arch in arches:
            poly_file = tmp / f"{arch.specimen_id}.txt"
            write_polygon_file(poly_file, ring_blocks(arch, truth)[0])
            for f in arch.frequencies_hz:
                jobs.append((arch, poly_file, f, _onset_amplitude_m(runner, arch, f)))

        def one(job):
            arch, poly_file, f, onset_m = job
            t0 = time.perf_counter()
            pair = _ramp_pair(runner, tmp, arch, poly_file, f, onset_m, truth, dt_s, lo, step, after, max_factor)
            log(f"  {arch.specimen_id} {f:g} Hz: onset {1e3 * onset_m:.2f} mm, {len(pair['collapsed'])} runs, "
                f"first collapse at {first_collapse_ratio(pair):.2f} onset ({time.perf_counter() - t0:.0f} s)")
            return pair

        with ThreadPoolExecutor(max_workers=2) as pool:
            pairs = list(pool.map(one, jobs))
    log(f"  {sum(len(p['collapsed']) for p in pairs)} runs in {time.perf_counter() - started:.0f} s")
    return {"truth": dataclasses.asdict(truth), "truth_model": truth_model(truth, arches), "dt_s": dt_s,
            "pairs": pairs}


# ---------------------------------------------------------------- replaying a map


def _outcome(amplitudes_m: np.ndarray, collapsed: np.ndarray, amp_m: float) -> bool:
    """The map's outcome at an amplitude: that of the nearest map amplitude; past the
    last, the last one's; below the first, stand."""
    if amp_m > amplitudes_m[-1]:
        return bool(collapsed[-1])
    if amp_m < amplitudes_m[0]:
        return False
    return bool(collapsed[int(np.argmin(np.abs(amplitudes_m - amp_m)))])


def draw_observations(omap: dict, rng: np.random.Generator, arches=ARCHES, gain_sd: float = 0.01,
                      gain_meas_sd: float = 0.002, step_fraction: float = 0.05, start_fraction: float = 0.8,
                      max_steps: int = 30, name: str = "replay") -> Observations:
    """One campaign drawn over a map: write_campaign's ramp of every pair (start and step
    snapped to 0.5 mm, up to the first collapse or max_steps tests), each test with a
    table gain g = 1 + gain_sd N(0, 1) and the map's outcome at amplitude x g, and a
    measured gain table_gain g (1 + gain_meas_sd N(0, 1)). Pairs without a collapse are
    left out."""
    pairs = []
    for pair in omap["pairs"]:
        amplitudes_m = np.asarray(pair["amplitudes_m"], dtype=float)
        collapsed = np.asarray(pair["collapsed"], dtype=bool)
        onset_m, f = pair["onset_m"], pair["frequency_hz"]
        step_m = max(SNAP_M, round(step_fraction * onset_m / SNAP_M) * SNAP_M)
        amp_m = max(step_m, round(start_fraction * onset_m / SNAP_M) * SNAP_M)
        tests = []  # (commanded amplitude [m], collapsed, measured gain, test id)
        for _ in range(max_steps):
            g = 1.0 + gain_sd * rng.standard_normal()
            measured = pair["table_gain"] * g * (1.0 + gain_meas_sd * rng.standard_normal())
            fell = _outcome(amplitudes_m, collapsed, amp_m * g)
            tests.append((amp_m, fell, measured, f"{pair['specimen_id']}_f{f:g}_A{1e3 * amp_m:.1f}"))
            if fell:
                break
            amp_m = round((amp_m + step_m) / SNAP_M) * SNAP_M
        if any(fell for _, fell, _, _ in tests):
            pairs.append(bracket(pair["specimen_id"], f, tests))
    # The maps' specimens are the kernel's own polygons at their stated sizes.
    return ramp_observations(name, pairs, arches, build_tolerance=0.0)


def bracket(specimen_id: str, frequency_hz: float, tests: list[tuple]) -> PairObservation:
    """The bracket of one ramp's tests (commanded amplitude [m], collapsed, measured gain,
    test id), which hold a collapse: the smallest collapse and the largest stand below it."""
    high_m = min(a for a, fell, _, _ in tests if fell)
    low_m = max((a for a, fell, _, _ in tests if not fell and a < high_m), default=0.0)
    return PairObservation(specimen_id, float(frequency_hz), float(low_m), float(high_m),
                           tuple(float(t[2]) for t in tests), tuple(t[3] for t in tests))


def ramp_observations(name: str, pairs: list[PairObservation], arches=ARCHES,
                      build_tolerance: float = 0.015) -> Observations:
    """The observations of a replayed campaign: its pairs on the nominal arches (as the
    laboratory declares them), records of every test, afd 1-1-1 cycles, and the build
    tolerance of the generator's specimens (the laboratory states it, as it states its
    transducer's calibration: 1.5 % for LMGC90's truths, 0 for the maps)."""
    by_id = {a.specimen_id: a for a in arches}
    ids = list(dict.fromkeys(p.specimen_id for p in pairs))
    specimens = {sid: by_id[sid].specimen() for sid in ids}
    return Observations(name, specimens, pairs, {sid: (1, 1, 1) for sid in ids}, gain_source="records",
                        build_tolerance=build_tolerance)


# ---------------------------------------------------------------- files


def _rounded(value):
    """Floats to 6 significant digits and booleans to 0/1, all through a JSON-able value."""
    if isinstance(value, bool):
        return int(value)
    if isinstance(value, float):
        return float(f"{value:.6g}")
    if isinstance(value, dict):
        return {k: _rounded(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_rounded(v) for v in value]
    return value


def save_map(omap: dict, path) -> None:
    """Write a map as JSON (floats to 6 significant digits, collapsed as 0/1), one pair
    a line."""
    data = _rounded(omap)
    head = {k: v for k, v in data.items() if k != "pairs"}
    lines = [f"  {json.dumps(k)}: {json.dumps(v)}," for k, v in head.items()]
    lines.append('  "pairs": [\n' + ",\n".join(f"    {json.dumps(p)}" for p in data["pairs"]) + "\n  ]")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("{\n" + "\n".join(lines) + "\n}\n")


def load_map(path) -> dict:
    """A map written by `save_map` (collapsed back to booleans)."""
    omap = json.loads(Path(path).read_text())
    for pair in omap["pairs"]:
        pair["collapsed"] = [bool(c) for c in pair["collapsed"]]
    return omap


def load_stored_map(slug: str) -> dict:
    """The stored map of one of `MAP_TRUTHS`."""
    return load_map(MAP_DIR / f"{slug}.json")


# ---------------------------------------------------------------- remaking the stored maps


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description="(Re)make the stored outcome maps of the replay tests.")
    parser.add_argument("--out", type=Path, default=MAP_DIR, help=f"folder of the maps (default {MAP_DIR})")
    parser.add_argument("--bin-dir", help="folder of voussoir-run and voussoir-limit (default: as the runner finds it)")
    parser.add_argument("--only", action="append", choices=sorted(MAP_TRUTHS), metavar="SLUG",
                        help=f"only this map (repeatable): {', '.join(MAP_TRUTHS)}")
    args = parser.parse_args(argv)
    bin_dir = find_bin_dir(args.bin_dir, programs=("voussoir-run", "voussoir-limit"))
    for slug in args.only or list(MAP_TRUTHS):
        print(f"{slug}: {MAP_TRUTHS[slug]}")
        t0 = time.perf_counter()
        omap = outcome_map(MAP_TRUTHS[slug], bin_dir)
        save_map(omap, args.out / f"{slug}.json")
        print(f"{slug}: {omap['truth_model']}, {time.perf_counter() - t0:.0f} s -> {args.out / f'{slug}.json'}")


if __name__ == "__main__":
    main()
