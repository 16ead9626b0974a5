"""Does any afd test on the table part a thinner ring from pivots set in, at frequencies
beyond the ones the diagnosis probes?

    python bench/ring_pivots.py [--rings 0.93,0.88,0.81] [--freqs 1.25,2,3,4,5,6,8]
        [--bin-dir DIR] [--work DIR]

A ring thinned to a factor f of its thickness t and a ring of full thickness whose joints
pivot `inset` = (1 - f) t / 2 in from each face thin the arch's line of thrust alike (the
inset is this geometric rule, not a fit). For each ring, on each of the campaigns' three
arches (independent_campaigns.ARCHES) and at each frequency whose thresholds stay within
the default table's limits, the kernel finds both models' afd threshold (one cycle up,
one full, one down, as the campaigns run them) and, held at 0.9 and 0.95 of each model's
own threshold, the peak horizontal crown displacement relative to the table (the record
`hold_crown` tests read). It prints each pair's thresholds and crowns and their log
ratios (pivots over ring), and, per ring, the median and largest |log ratio| over the
pairs where both models rock (crown above crown.FLOOR_M) and neither falls, beside what parts two models
across codes: the crown law's scale at 0.9 (crown.crown_scale) and the thresholds'
cross-code spread (docs/diagnosis.md). Runs the kernel only (about 1 minute for the
defaults on two cores).
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "postproc"), str(ROOT / "postproc" / "tests")]

from voussoir_post.diagnosis.bank import onset_amplitudes  # noqa: E402
from voussoir_post.diagnosis.crown import FLOOR_M, crown_scale  # noqa: E402
from voussoir_post.diagnosis.effects import Variant  # noqa: E402
from voussoir_post.diagnosis.next_test import within_limits  # noqa: E402
from voussoir_post.diagnosis.settings import DiagnosisSettings  # noqa: E402
from voussoir_post.diagnosis.simulator import FALLEN_PEAK_M, Simulator  # noqa: E402
from voussoir_post.readers.campaign import TableLimits, Test  # noqa: E402

from independent_campaigns import ARCHES  # noqa: E402

HOLDS = (0.9, 0.95)
CYCLES = (1, 1, 1)


def floats(text: str) -> list[float]:
    try:
        values = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a comma-separated list of numbers: {text!r}") from None
    if not values or any(not (v > 0) for v in values):
        raise argparse.ArgumentTypeError(f"expected positive numbers: {text!r}")
    return values


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rings", type=floats, default=[0.93, 0.88, 0.81], help="thickness factors of the ring")
    ap.add_argument("--freqs", type=floats, default=[1.25, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0], help="frequencies [Hz]")
    ap.add_argument("--bin-dir", type=Path, default=ROOT / "build" / "drivers")
    ap.add_argument("--work", type=Path, default=Path("/tmp/voussoir_ring_pivots"))
    args = ap.parse_args()
    if any(f >= 1.0 for f in args.rings):
        ap.error("--rings: a thinner ring has a factor below 1")
    if not (args.bin_dir / "voussoir-run").exists():
        ap.error(f"no voussoir-run in {args.bin_dir}: build the project first (README)")
    settings = DiagnosisSettings(bin_dir=args.bin_dir)
    table = TableLimits()
    t0 = time.time()
    print("pair | threshold ring / pivots [mm] (log) | crown at 0.9 [mm] (log) | crown at 0.95 [mm] (log)")
    for f_ring in args.rings:
        thr_logs, crown_logs = [], []
        for arch in ARCHES:
            spec = arch.specimen()
            inset = (1.0 - f_ring) * spec.thickness_m / 2.0
            ring, pivots = Variant("geometry", f_ring), Variant("contact_edges", round(inset, 6))
            sim = Simulator(settings, args.work / f"{arch.specimen_id}-{f_ring:g}")
            onset = onset_amplitudes(sim.runner, spec, args.freqs)
            found = sim.thresholds_at(spec, args.freqs, CYCLES, [ring, pivots], settings.ceiling_factor * max(onset),
                                      settings.amp_tol_fraction * min(onset))
            freqs = [f for f in args.freqs if all(math.isfinite(found.get((v, f), math.nan))
                                                  and within_limits(found[(v, f)], f, table) for v in (ring, pivots))]
            jobs = [(spec, Test(f"hold_{k}", spec.specimen_id, "afd", "stand", frequency_hz=f,
                                amplitude_m=h * found[(v, f)], n_attack=CYCLES[0], n_full=CYCLES[1],
                                n_decay=CYCLES[2]), v, {})
                    for k, (f, v, h) in enumerate((f, v, h) for f in freqs for v in (ring, pivots) for h in HOLDS)]
            peaks = iter(sim.peaks(jobs, None))
            for f in freqs:
                a, b = found[(ring, f)], found[(pivots, f)]
                crowns = {v: [next(peaks) for _ in HOLDS] for v in (ring, pivots)}
                thr_logs.append(abs(math.log(b / a)))
                cells = []
                for i, h in enumerate(HOLDS):
                    c, d = crowns[ring][i], crowns[pivots][i]
                    fell = FALLEN_PEAK_M in (c, d)
                    rocks = not fell and c > FLOOR_M and d > FLOOR_M
                    if rocks and h == HOLDS[0]:
                        crown_logs.append(abs(math.log(d / c)))
                    shown = lambda x: "fell" if x == FALLEN_PEAK_M else f"{1e3 * x:.2f}"
                    cells.append(f"{shown(c)} / {shown(d)}" + (f" ({math.log(d / c):+.3f})" if rocks else
                                                               "" if fell else " (below the floor)"))
                print(f"ring {f_ring:g} vs pivots {1e3 * inset:.2f} mm, {arch.specimen_id} {f:g} Hz | "
                      f"{1e3 * a:6.2f} / {1e3 * b:6.2f} ({math.log(b / a):+.3f}) | " + " | ".join(cells), flush=True)
        print(f"ring {f_ring:g}: |log ratio| pivots / ring of the thresholds median {statistics.median(thr_logs):.3f}, largest "
              f"{max(thr_logs):.3f} over {len(thr_logs)} pairs; of the crowns at 0.9 where both rock and stand "
              + (f"median {statistics.median(crown_logs):.3f}, largest {max(crown_logs):.3f} over {len(crown_logs)}"
                 if crown_logs else "none rocks")
              + f" (the crown law's scale at 0.9: {crown_scale(0.9):.2f})", flush=True)
    print(f"{time.time() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
