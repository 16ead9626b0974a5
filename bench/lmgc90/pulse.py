"""A pulse one way and the other: does it part brackets from a free arch in both codes?

    python bench/lmgc90/pulse.py --lmgc90-build DIR --slugs t03_none,t12_... [--work DIR]

Brackets against one springing make an arch's static capacity differ between the two
directions (bench/diagnosis_test_types.py: 61 to 91 % one way when in contact), which an
afd test, symmetric, hardly sees. This bench drives the W156 specimen of stored LMGC90
truths (postproc/tests/data/lmgc90/<slug>.json: their parameters and faults, the model of
truths.py) and Voussoir's model of the same truth at its own parameters (voussoir-run,
`waveform = 'accelerogram'`, `record_polarity` +1 and -1) with one table pulse, the
diagnosis's (pulses.unit_pulse): a half-sine of acceleration of 0.15 s towards +x, then a
half-sine of 0.6 s the other way that brings the table to rest (the velocity back to
zero), 1.5 s still. For each code and each direction it finds the smallest peak acceleration that brings the
arch down (geometric bisection to 1 %, from 1 to 40 m/s2), and prints the ratio -x / +x:
1 for a symmetric arch, away from 1 with brackets on one side.

Per m/s2 of peak acceleration the pulse moves the table 0.036 m at most and at 0.095 m/s:
at 7 m/s2, 0.25 m of travel (a table of 0.15 m amplitude, from one end) and 0.67 m/s.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent)]

import truths as T  # noqa: E402  (puts postproc/ and postproc/tests/ on the path)
from lmgc90_campaigns import truth_variant  # noqa: E402
from independent_campaigns import ARCHES  # noqa: E402
from voussoir_post.diagnosis import pulses  # noqa: E402
from voussoir_post.diagnosis.effects import arch_group  # noqa: E402
from voussoir_post.runner import Runner  # noqa: E402


DT = 1.0e-3


def unit_pulse() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, acceleration, velocity) of the pulse (the diagnosis's, pulses.unit_pulse) of peak
    acceleration 1 m/s2."""
    t, _, acc = pulses.unit_pulse(DT)
    acc = acc / acc.max()
    vel = np.concatenate([[0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * DT)])
    return t, acc, vel


def lmgc90_collapses(spec: T.Lmgc90Specimen, vel: np.ndarray, scale: float, polarity: int) -> bool:
    return spec.run_table(polarity * scale * vel, int(round(T.LEAD_S / T.DT_S)))


class VoussoirRuns:
    def __init__(self, work: Path, record: Path, bin_dir: Path):
        self.runner, self.record, self.k = Runner(bin_dir, work), record, 0

    def collapses(self, group: dict, scale: float, polarity: int) -> bool:
        self.k += 1
        return self.runner.collapses({
            "arch": group,
            "motion": {"waveform": "accelerogram", "record_file": str(self.record), "record_scale": scale,
                       "record_polarity": polarity, "lead_s": T.LEAD_S, "rest_s": 0.0},
            "solver": {"dt_s": DT}}, f"v{self.k}")


def threshold(collapses, lo: float = 1.0, hi: float = 40.0) -> float:
    """Smallest peak acceleration [m/s2] that brings the arch down, to 1 %."""
    if collapses(lo):
        return math.nan
    if not collapses(hi):
        return math.inf
    return T.bisect(collapses, lo, hi, 0.01)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lmgc90-build", required=True)
    ap.add_argument("--slugs", required=True, help="comma-separated stored truths (file stems)")
    ap.add_argument("--work", type=Path, default=Path("lmgc90_pulse_work"))
    ap.add_argument("--bin-dir", type=Path, default=T.ROOT / "build" / "drivers")
    args = ap.parse_args()
    args.work.mkdir(parents=True, exist_ok=True)
    t, acc, vel = unit_pulse()
    record = args.work / "pulse.csv"
    record.write_text("t_s,accel_m_s2\n" + "".join(f"{a:.4f},{b:.8f}\n" for a, b in zip(t, acc)))
    disp = np.concatenate([[0.0], np.cumsum(0.5 * (vel[1:] + vel[:-1]) * DT)])
    print(f"the pulse per m/s2: peak velocity {vel.max():.3f} m/s, travel {disp.max():.3f} m, final velocity "
          f"{vel[-1]:.1e} m/s")
    voussoir = VoussoirRuns(args.work, record.resolve(), args.bin_dir)
    arch = ARCHES[0]
    spec = arch.specimen()
    for slug in args.slugs.split(","):
        stored, truth = T.fixed_table_truth(slug, "pulse.py")
        par = truth["parameters"]
        lmgc = T.Lmgc90Specimen(args.lmgc90_build, args.work / slug, arch, truth,
                                par.get("friction", {}).get("friction", arch.friction))
        group = arch_group(spec, truth_variant(stored))
        t0 = time.time()
        found = {pol: (threshold(lambda s, pol=pol: lmgc90_collapses(lmgc, vel, s, pol)),
                       threshold(lambda s, pol=pol: voussoir.collapses(group, s, pol))) for pol in (1, -1)}
        print(f"{slug}: +x LMGC90 {found[1][0]:.2f}, Voussoir {found[1][1]:.2f} m/s2; -x LMGC90 {found[-1][0]:.2f}, "
              f"Voussoir {found[-1][1]:.2f} m/s2; -x / +x LMGC90 {found[-1][0] / found[1][0]:.3f}, Voussoir "
              f"{found[-1][1] / found[1][1]:.3f} ({time.time() - t0:.0f} s)", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
