"""Calibration of the diagnosis's probabilities (issue 23): are causes named at 0.9 right
at least 85 % of the time, and is the truth in the 90 % set at least 85 % of the time?

    python bench/diagnosis_calibration.py BIN_DIR OUT_DIR [--truths N] [--draws D] [--seed S]

Truths are drawn from a prior over the catalogue, with values off every grid and in both
directions, pairs, and truths outside it (a gap at the intrados, brackets on one specimen
only); each truth is made by the independent generator (postproc/tests/replay_maps.py
outcome maps: polygon blocks, chamfers, an integrated actuator, dt 5e-4 s) and diagnosed
in D noise draws on the stored simulation bank of the test arches
(postproc/tests/data/replay/bank). Prints the table of rates and writes
OUT_DIR/calibration.json and the reliability figure OUT_DIR/diagnosis_reliability.png
(stated probability of the most probable model against how often it is the truth).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np
from scipy.stats import binomtest

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "postproc"), str(ROOT / "postproc" / "tests")]

from voussoir_post.diagnosis.bank import Bank, load_banks  # noqa: E402
from voussoir_post.diagnosis.rates import draw_outcomes  # noqa: E402
from voussoir_post.diagnosis.figures import reliability_figure  # noqa: E402
from voussoir_post.plots.drawing import provenance  # noqa: E402

from independent_campaigns import ARCHES, Truth  # noqa: E402
from replay_maps import draw_observations, outcome_map, save_map, load_map  # noqa: E402

DATA = ROOT / "postproc" / "tests" / "data" / "replay"


def draw_truth(rng: np.random.Generator) -> tuple[str, Truth]:
    """One truth from the calibration prior (equal weight per kind)."""
    kind = rng.choice(["none", "edges", "friction", "geometry", "actuator", "brackets", "edges+friction",
                       "geometry+friction", "intrados gap", "brackets on one"])
    u = lambda a, b: float(np.round(rng.uniform(a, b), 4))
    low_or_high = lambda lo, hi: lo if rng.random() < 0.7 else hi
    if kind == "none":
        return kind, Truth()
    if kind == "edges":
        return kind, Truth(chamfer_m=u(0.001, 0.007))
    if kind == "friction":
        return kind, Truth(friction=low_or_high(u(0.30, 0.46), u(0.55, 0.70)))
    if kind == "geometry":
        return kind, Truth(thickness_factor=low_or_high(u(0.78, 0.95), u(1.05, 1.10)))
    if kind == "actuator":
        return kind, Truth(actuator_hz=u(4.0, 10.0), actuator_damping=u(0.1, 0.4))
    if kind == "brackets":
        return kind, Truth(bracket_gap_m=u(0.0, 0.0005))
    if kind == "edges+friction":
        return kind, Truth(chamfer_m=u(0.002, 0.006), friction=u(0.32, 0.45))
    if kind == "geometry+friction":
        return kind, Truth(thickness_factor=u(0.80, 0.92), friction=u(0.32, 0.45))
    if kind == "intrados gap":
        return kind, Truth(intrados_cut_m=u(0.003, 0.008))
    return kind, Truth(bracket_gap_m=u(0.0, 0.0005), bracket_specimens=(str(rng.choice([a.specimen_id for a in ARCHES])),))


def stored_bank() -> Bank:
    return load_banks(DATA / "bank")


def reliability(outcomes: list[dict], out: Path, note: str) -> list[tuple]:
    stated = np.array([o["p_top"] for o in outcomes if o["truth"] != "outside"])
    right = np.array([o["top_right"] for o in outcomes if o["truth"] != "outside"])
    edges = np.array([0.0, 0.2, 0.4, 0.6, 0.8, 0.9, 1.0001])
    rows = []
    for a, b in zip(edges[:-1], edges[1:]):
        sel = (stated >= a) & (stated < b)
        if sel.any():
            rows.append((a, min(b, 1.0), int(sel.sum()), float(stated[sel].mean()), float(right[sel].mean())))
    bins = []
    for a, b, n, s, r in rows:
        ci = binomtest(int(round(r * n)), n).proportion_ci(0.95, method="wilson")
        bins.append((a, b, n, s, r, ci.low, ci.high))
    reliability_figure(out, bins, note)
    return rows


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("bin_dir", type=Path)
    ap.add_argument("out", type=Path)
    ap.add_argument("--truths", type=int, default=20)
    ap.add_argument("--draws", type=int, default=10)
    ap.add_argument("--seed", type=int, default=23)
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(args.seed)
    bank = stored_bank()
    outcomes, per_truth = [], []
    t0 = time.time()
    for k in range(args.truths):
        kind, truth = draw_truth(rng)
        path = args.out / "maps" / f"truth_{k:03d}.json"
        if path.exists():
            omap = load_map(path)
        else:
            omap = outcome_map(truth, args.bin_dir, log=lambda m: None)
            path.parent.mkdir(parents=True, exist_ok=True)
            save_map(omap, path)
        got = draw_outcomes(bank, omap, args.draws, draw_observations, seed=1000 + k)
        outcomes += got
        per_truth.append({"kind": kind, "truth": str(truth), "model": omap["truth_model"],
                          "in_set": sum(o["in_set"] for o in got), "named_right": sum(o["right_named"] for o in got),
                          "named_wrong": sum(o["wrong_named"] for o in got), "draws": len(got)})
        r = per_truth[-1]
        print(f"[{time.time() - t0:6.0f} s] truth {k:2d} {kind:18s} {r['model']:28s} in set {r['in_set']:2d}/{r['draws']}"
              f"  named right {r['named_right']:2d}  named wrong {r['named_wrong']:2d}   ({truth})", flush=True)
    inside = [o for o in outcomes if o["truth"] != "outside"]
    named = [o for o in inside if o["named"]]
    outside_named = sum(o["named"] for o in outcomes if o["truth"] == "outside")
    table = {
        "draws": len(outcomes), "truths": args.truths,
        "named_at_0.9": len(named),
        "named_right_fraction": (sum(o["right_named"] for o in named) / len(named)) if named else None,
        "truth_in_90pct_set_fraction": sum(o["in_set"] for o in inside) / len(inside) if inside else None,
        "outside_named": outside_named,
        "outside_draws": sum(o["truth"] == "outside" for o in outcomes),
    }
    note = provenance("bench/diagnosis_calibration.sh",
                      f"{args.truths} truths x {args.draws} noise draws, seed {args.seed}; the test arches' bank")
    rows = reliability(outcomes, args.out, note)
    print()
    print(f"draws {table['draws']} ({args.truths} truths x {args.draws})")
    print(f"causes named at >= 0.9: {table['named_at_0.9']}, right {table['named_right_fraction']}  (goal >= 0.85)")
    print(f"truth in the 90 % set: {table['truth_in_90pct_set_fraction']}  (goal >= 0.85)")
    print(f"out-of-catalogue truths named at >= 0.9: {outside_named} of {table['outside_draws']}  (goal 0)")
    print("reliability (stated bin, draws, mean stated, observed):")
    for a, b, n, s, r in rows:
        print(f"  {a:.1f}-{b:.1f}  {n:4d}  {s:.2f}  {r:.2f}")
    (args.out / "calibration.json").write_text(json.dumps({"table": table, "per_truth": per_truth,
                                                           "reliability": rows}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
