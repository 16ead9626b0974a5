"""Brackets with play: Voussoir's brackets (`&arch bracket_gap_m`) against LMGC90's.

    python bench/lmgc90/bracket_play.py [--out DIR] [--np N]

The LMGC90 truths with brackets (postproc/tests/data/lmgc90) set them 0 to 0.5 mm off
the springing voussoirs, and the catalogue's base_restraint has them in contact. Where a
truth's counterfactual is stored (the same truth run again in LMGC90 without its
brackets, bench/lmgc90/truths.sh --without), LMGC90's own effect of the brackets is the
ratio of the two thresholds at each tested pair. This bench computes the same ratio with
Voussoir's kernel (threshold searches of voussoir-sweep on the nominal specimens, with the
truth's other effects: contact_edges as `contact_inset_m`) with the brackets in contact
(gap 0, the catalogue's) and at the truth's gap, and prints the three side by side with
the RMS of the log differences. It needs only the project's executables (no LMGC90).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path[:0] = [str(ROOT / "postproc"), str(ROOT / "postproc" / "tests")]

from voussoir_post.runner import Runner  # noqa: E402

from independent_campaigns import ARCHES  # noqa: E402
from lmgc90_campaigns import TRUTH_DIR  # noqa: E402

COUNTERFACTUALS = TRUTH_DIR / "counterfactual"


def bracket_truths() -> list[tuple[dict, dict, dict]]:
    """(truth, counterfactual, brackets {side, gap_m, specimens}) of every stored truth with
    brackets whose counterfactual without them is stored."""
    out = []
    for path in sorted(COUNTERFACTUALS.glob("*_without_*.json")):
        slug = path.stem.split("_without_")[0]
        truth = json.loads((TRUTH_DIR / f"{slug}.json").read_text())
        par = truth["truth"]["parameters"]
        if "base_restraint" in par and path.stem.endswith("_without_base_restraint"):
            b = dict(par["base_restraint"], specimens=None)
        elif "brackets_one_specimen" in par and path.stem.endswith("_without_outside"):
            b = dict(par["brackets_one_specimen"])
            b["specimens"] = [b.pop("specimen_id")]
        else:
            continue
        if "table_motion" in par:  # an actuator: not a threshold search of the arch alone
            continue
        out.append((truth, json.loads(path.read_text()), b))
    return out


def thresholds(runner: Runner, arch, freqs, inset_m: float, side: str, gap_m: float, name: str,
               np_ranks: int) -> dict[float, float]:
    group = {"embrace_deg": arch.embrace_deg, "n_voussoirs": arch.n_voussoirs, "r_ext_m": arch.r_ext_m,
             "thickness_m": arch.thickness_m, "width_m": arch.width_m, "density_kg_m3": arch.density_kg_m3,
             "friction": arch.friction, "contact_inset_m": inset_m, "restrained_springings": side}
    if side != "none":
        group["bracket_gap_m"] = gap_m
    sweep = {"mode": "threshold", "frequencies_hz": list(freqs), "amp_tol_m": 2.5e-4, "amp_max_m": 0.3,
             "scan_step": 0.05, "progress_every_s": 1.0e9}
    _, rows = runner.run_sweep({"arch": group, "motion": {"waveform": "afd", "n_attack": 1, "n_full": 1,
                                                          "n_decay": 1, "rest_s": 1.0},
                                "solver": {"dt_s": 1.0e-3, "allow_nonconvergence": True}, "output": {},
                                "sweep": sweep}, name)
    return {float(r["frequency_hz"]): float(r["threshold_m"]) for r in rows}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, help="work folder (default: a temporary one)")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks of the sweeps")
    ap.add_argument("--bin-dir", default=os.environ.get("VOUSSOIR_BIN_DIR", str(ROOT / "build" / "drivers")))
    args = ap.parse_args()
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    t0 = time.time()
    with tempfile.TemporaryDirectory() as tmp:
        work = args.out or Path(tmp)
        runner = Runner(args.bin_dir, work, n_ranks=args.np)
        by_id = {a.specimen_id: a for a in ARCHES}
        summary = []
        for truth, without, b in bracket_truths():
            par = truth["truth"]["parameters"]
            inset = par.get("contact_edges", {}).get("inset_m", 0.0)
            print(f"{truth['truth']['index']:>4d} brackets {b['side']}, {1e3 * b['gap_m']:.2f} mm off"
                  f"{' on ' + ', '.join(b['specimens']) if b['specimens'] else ''}"
                  f"{f', pivots set in by {1e3 * inset:.1f} mm' if inset else ''}", flush=True)
            lm = {(p["specimen_id"], p["frequency_hz"]): p["threshold_m"] for p in truth["pairs"]}
            lm0 = {(p["specimen_id"], p["frequency_hz"]): p["threshold_m"] for p in without["pairs"]}
            diffs = {"gap 0": [], "gap": []}
            for sid in (b["specimens"] or [a.specimen_id for a in ARCHES]):
                arch = by_id[sid]
                tag = f"t{truth['truth']['index']}_{sid}"
                free = thresholds(runner, arch, arch.frequencies_hz, inset, "none", 0.0, tag + "_free", args.np)
                tight = thresholds(runner, arch, arch.frequencies_hz, inset, b["side"], 0.0, tag + "_gap0", args.np)
                loose = thresholds(runner, arch, arch.frequencies_hz, inset, b["side"], b["gap_m"], tag + "_gap",
                                   args.np)
                for f in arch.frequencies_hz:
                    r_lm = lm[(sid, f)] / lm0[(sid, f)]
                    r0, r1 = tight[f] / free[f], loose[f] / free[f]
                    diffs["gap 0"].append(math.log(r0 / r_lm))
                    diffs["gap"].append(math.log(r1 / r_lm))
                    print(f"     {sid} {f:4g} Hz: LMGC90 x{r_lm:.3f}   Voussoir in contact x{r0:.3f}   "
                          f"Voussoir {1e3 * b['gap_m']:.2f} mm off x{r1:.3f}", flush=True)
            rms = {k: math.sqrt(sum(d * d for d in v) / len(v)) for k, v in diffs.items()}
            print(f"     RMS of log(Voussoir / LMGC90): in contact {100 * rms['gap 0']:.1f} %, with the play "
                  f"{100 * rms['gap']:.1f} %", flush=True)
            summary.append(rms)
    print(f"{len(summary)} truths, {time.time() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
