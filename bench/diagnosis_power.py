"""How many frequencies per arch a laboratory needs to name a cause (issue 23: the power
at a friction change of 0.07).

    python bench/diagnosis_power.py BIN_DIR OUT_DIR [--draws D]

The three test arches at two frequencies each (the replay tests' design) and at four
(W156: 1, 1.25, 2, 3 Hz; W132: 1.25, 1.6, 2.5, 3.5 Hz; W118: 1.6, 2, 3, 4 Hz). For each
design: the simulation bank (built with BIN_DIR, cached in OUT_DIR/bank) and the outcome
maps of three truths (friction 0.43, chamfers 3 mm, a ring 0.85 as thick; made by the
independent generator, cached in OUT_DIR/maps), then D noise draws each. Prints, per
design and truth, how often the truth is named at 0.9, how often it is in the 90 % set,
the mean probability of the truth and any wrong cause named.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "postproc"), str(ROOT / "postproc" / "tests")]

from voussoir_post.diagnosis.bank import build_bank  # noqa: E402
from voussoir_post.diagnosis.rates import outcome  # noqa: E402
from voussoir_post.diagnosis.settings import DiagnosisSettings  # noqa: E402

from independent_campaigns import ARCHES, Arch, Truth  # noqa: E402
from replay_maps import draw_observations, load_map, outcome_map, save_map  # noqa: E402

FOUR = (Arch("W156", 156.0, 13, (1.0, 1.25, 2.0, 3.0)),
        Arch("W132", 132.0, 11, (1.25, 1.6, 2.5, 3.5)),
        Arch("W118", 118.0, 10, (1.6, 2.0, 3.0, 4.0)))
TRUTHS = {"friction_0.43": Truth(friction=0.43), "chamfer_3mm": Truth(chamfer_m=0.003),
          "ring_0.85": Truth(thickness_factor=0.85)}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("bin_dir", type=Path)
    ap.add_argument("out", type=Path)
    ap.add_argument("--draws", type=int, default=20)
    args = ap.parse_args()
    settings = DiagnosisSettings(bin_dir=args.bin_dir, n_ranks=2, log=print)
    print(f"{'design':16s} {'truth':16s} {'named':>6s} {'in set':>7s} {'P(truth)':>9s} {'wrong':>6s}")
    for design, arches in (("2 per arch", ARCHES), ("4 per arch", FOUR)):
        specs = {a.specimen_id: a.specimen() for a in arches}
        bank = build_bank(specs, {a.specimen_id: list(a.frequencies_hz) for a in arches},
                          {k: (1, 1, 1) for k in specs}, settings, args.out / "bank", args.out / "work")
        for slug, truth in TRUTHS.items():
            path = args.out / "maps" / f"{design.split()[0]}_{slug}.json"
            if not path.exists():
                path.parent.mkdir(parents=True, exist_ok=True)
                save_map(outcome_map(truth, args.bin_dir, arches=arches, log=lambda m: None), path)
            omap = load_map(path)
            got = [outcome(bank, draw_observations(omap, np.random.default_rng([7, k]), arches=arches),
                           omap["truth_model"]) for k in range(args.draws)]
            print(f"{design:16s} {slug:16s} {sum(o['right_named'] for o in got):3d}/{args.draws} "
                  f"{sum(o['in_set'] for o in got):4d}/{args.draws} {np.mean([o['p_truth'] for o in got]):9.2f} "
                  f"{sum(o['wrong_named'] for o in got):6d}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
