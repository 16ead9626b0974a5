"""LMGC90's collapse thresholds with more full cycles, for stored truths (a bench).

    python bench/lmgc90/cycles.py --lmgc90-build DIR --slugs t03_none,t00_geometry_0.928 [--n-full 6] [--out F]

Issue 35 lists cycle counts among the tests `next_test` could advise. Whether they part
two rival models across codes depends on whether the two codes agree on what more cycles
do. For each stored truth (postproc/tests/data/lmgc90/<slug>.json) and each of its six
(arch, frequency) pairs, this finds LMGC90's first collapse of the afd motion with
1-N-1 cycles (the same specimen, faults and runs as truths.py: one subprocess per run):
an upward scan by x 1.04 from 0.8 times the stored 1-1-1 threshold (down by the same
step when that collapses), then bisection to 0.5 %. It prints the log change against
the stored 1-1-1 threshold, to set beside Voussoir's (bench/diagnosis_test_types.py,
"cycles add"), and writes them to --out (JSON).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import truths as T  # noqa: E402  (puts postproc/ and postproc/tests/ on the path)
from independent_campaigns import ARCHES  # noqa: E402
from voussoir_post.analysis.afd import _envelope  # noqa: E402

STEP = 1.04
TOL = 0.005


def velocity(t: np.ndarray, f: float, amp: float, n_full: int) -> np.ndarray:
    """Velocity of the afd command A e(t) sin(2 pi f t) with 1-n_full-1 cycles, exact."""
    e, de, _ = _envelope(t, f, 1, n_full, 1)
    w = 2.0 * math.pi * f
    return amp * (de * np.sin(w * t) + e * w * np.cos(w * t))


def collapses(spec: T.Lmgc90Specimen, f: float, amp: float, n_full: int) -> bool:
    """One LMGC90 run of the commanded motion (truths.evolutions with n_full cycles; a
    truth with an actuator or a spreading support is not handled here)."""
    lead = int(round(T.LEAD_S / T.DT_S))
    tm = np.arange(int(round(((2 + n_full) / f + T.REST_S) / T.DT_S))) * T.DT_S
    return spec.run_table(velocity(tm, f, amp, n_full), lead)


def threshold(spec: T.Lmgc90Specimen, f: float, start: float, n_full: int) -> float:
    """First collapse [m]: a scan by STEP from `start`, then bisection to TOL."""
    a = start
    if collapses(spec, f, a, n_full):
        hi = a
        while True:
            a /= STEP
            if not collapses(spec, f, a, n_full):
                lo = a
                break
            hi = a
    else:
        lo = a
        for _ in range(40):
            a *= STEP
            if collapses(spec, f, a, n_full):
                hi = a
                break
            lo = a
        else:
            return math.nan
    return T.bisect(lambda a: collapses(spec, f, a, n_full), lo, hi, TOL)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lmgc90-build", required=True)
    ap.add_argument("--slugs", required=True, help="comma-separated stored truths (file stems)")
    ap.add_argument("--n-full", type=int, default=6)
    ap.add_argument("--work", type=Path, default=Path("lmgc90_cycles_work"))
    ap.add_argument("--out", type=Path, default=Path("lmgc90_cycles.json"))
    args = ap.parse_args()
    results = {}
    for slug in args.slugs.split(","):
        stored, truth = T.fixed_table_truth(slug, "cycles.py")
        par = truth["parameters"]
        one = {(p["specimen_id"], p["frequency_hz"]): p["threshold_m"] for p in stored["pairs"]}
        for arch in ARCHES:
            friction = par.get("friction", {}).get("friction", arch.friction)
            spec = T.Lmgc90Specimen(args.lmgc90_build, args.work / slug / arch.specimen_id, arch, truth, friction)
            for f in arch.frequencies_hz:
                t0 = time.time()
                t1 = one[(arch.specimen_id, f)]
                tn = threshold(spec, f, 0.8 * t1, args.n_full)
                results[f"{slug} {arch.specimen_id} {f:g}"] = {"threshold_m_1": t1, f"threshold_m_{args.n_full}": tn}
                print(f"{slug} {arch.specimen_id} {f:g} Hz: 1-1-1 {1e3 * t1:.2f} mm, 1-{args.n_full}-1 "
                      f"{1e3 * tn:.2f} mm, log change {100 * math.log(tn / t1):+.1f} % ({time.time() - t0:.0f} s)",
                      flush=True)
    args.out.write_text(json.dumps({"generator": T.GENERATOR, "n_full": args.n_full, "pairs": results}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
