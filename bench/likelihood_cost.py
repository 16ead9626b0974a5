"""What the likelihood costs, and what its early and late first collapses add to it.

    python bench/likelihood_cost.py [--truths N] [--repeat R]

Diagnoses one laboratory campaign drawn from each of the first N stored LMGC90 truths
(postproc/tests/data/lmgc90, the faults of test_diagnosis_lmgc90.py) on the stored bank
of the test arches, three ways: as it is (G(z) = z Phi(z) + phi(z) read from the table of
likelihood.py), with G from ndtr and exp (the exact form the table replaces), and with
every pair's early and late probabilities 0 (the stories' terms still computed). Prints
the best of R timings of each, and the cost per element of G both ways and of log_ndtr.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.special import log_ndtr, ndtr

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "postproc"), str(ROOT / "postproc" / "tests")]

from voussoir_post.diagnosis import likelihood as L  # noqa: E402
from voussoir_post.diagnosis.rates import outcome  # noqa: E402

from lmgc90_campaigns import LabFaults, draw_campaign, stored_truths, truth_model, truth_values  # noqa: E402
from test_diagnosis import stored_bank  # noqa: E402


def exact_g(z: np.ndarray) -> np.ndarray:
    return z * ndtr(z) + np.exp(-0.5 * z * z) / math.sqrt(2.0 * math.pi)


def per_element_ns(f, z: np.ndarray, repeat: int) -> float:
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(10):
            f(z)
        best = min(best, (time.perf_counter() - t0) / 10)
    return best / z.size * 1e9


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--truths", type=int, default=8, help="stored LMGC90 truths, one campaign each (default 8)")
    ap.add_argument("--repeat", type=int, default=3, help="timings of each way, the best kept (default 3)")
    args = ap.parse_args()
    if args.truths < 1 or args.repeat < 1:
        ap.error("--truths and --repeat must be at least 1")
    bank = stored_bank()
    campaigns = []
    for t in stored_truths()[:args.truths]:
        obs, _ = draw_campaign(t, np.random.default_rng([2026, t["truth"]["index"], 0]), LabFaults())
        if obs.pairs:
            campaigns.append((t, obs))

    def run() -> float:
        t0 = time.perf_counter()
        for t, obs in campaigns:
            outcome(bank, obs, truth_model(t, bank, obs), truth_values(t))
        return time.perf_counter() - t0

    table_g, classes = L.ramp_g, L.pair_early_prob
    ways = {}
    run()  # the emulators' and models' caches
    ways["as it is (G from the table)"] = min(run() for _ in range(args.repeat))
    L.ramp_g = exact_g
    ways["G from ndtr and exp"] = min(run() for _ in range(args.repeat))
    L.ramp_g, L.pair_early_prob = table_g, lambda fraction: (0.0, 0.0)
    ways["early and late probabilities 0"] = min(run() for _ in range(args.repeat))
    L.pair_early_prob = classes
    print(f"{len(campaigns)} campaigns of stored LMGC90 truths, diagnosed on the stored bank (best of {args.repeat}):")
    for name, s in ways.items():
        print(f"  {name:<34} {s:6.2f} s  ({s / len(campaigns) * 1e3:6.0f} ms a campaign)")
    z = np.random.default_rng(1).normal(0.0, 3.0, (2000, 61))
    print("per element of a (2000, 61) array, z ~ N(0, 9):")
    print(f"  G from the table   {per_element_ns(L.ramp_g, z, args.repeat):6.1f} ns")
    print(f"  G from ndtr, exp   {per_element_ns(exact_g, z, args.repeat):6.1f} ns")
    print(f"  log_ndtr           {per_element_ns(log_ndtr, z, args.repeat):6.1f} ns")
    print(f"  table's largest error on z in (-10, 10): "
          f"{np.max(np.abs(L.ramp_g(np.linspace(-10, 10, 200001)) - exact_g(np.linspace(-10, 10, 200001)))):.1e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
