"""Does an arch fall at every amplitude above its first collapse? A fine scan in LMGC90.

    python bench/lmgc90/collapse_scan.py --lmgc90-build DIR --slugs t101_none,t104_none \
        --pairs W156:3:14.45,W118:3:32.44 [--lo 0.7 --hi 1.35 --step 0.015] [--out FILE]

A laboratory ramps a test's amplitude until the arch falls and reads the first collapse
as the threshold. Rocking is not monotone in amplitude: the threshold searches of the
stored LMGC90 truths found a stand above the first collapse (within +8 %, the last probe)
at 60 of 258 pairs, and in the laboratory loop a W156 ramp at 3 Hz fell at 12.1 mm in a
window two probes wide, then stood from 12.3 to 14.5 mm and fell again from 15 mm
(truth t24). This bench runs each afd pair of each stored truth
(postproc/tests/data/lmgc90/<slug>.json: parameters and faults, the model of truths.py,
an actuator included) at every amplitude of a geometric grid from `lo` to `hi` times the
reference amplitude given for the pair (Voussoir's nominal threshold, say), and writes the
outcomes (JSON: one row a truth and pair). postproc/tests/collapse_windows.py reads them
(docs/diagnosis.md, "Early collapses"): how often a ramp's first collapse lies below the
threshold a search finds, and how far, where the kernel's own scan has early ramps and
where it has none.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path


HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent)]

import truths as T  # noqa: E402  (puts postproc/ and postproc/tests/ on the path)
from independent_campaigns import ARCHES  # noqa: E402
from voussoir_post.diagnosis.early import SCAN_HI, SCAN_LO, SCAN_STEP, scan_grid  # noqa: E402

ARCH = {a.specimen_id: a for a in ARCHES}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lmgc90-build", required=True)
    ap.add_argument("--slugs", required=True, help="comma-separated stored truths (file stems)")
    ap.add_argument("--pairs", required=True, help="comma-separated specimen:frequency_hz:reference_mm")
    ap.add_argument("--lo", type=float, default=SCAN_LO, help="first amplitude / reference")
    ap.add_argument("--hi", type=float, default=SCAN_HI, help="last amplitude / reference")
    ap.add_argument("--step", type=float, default=SCAN_STEP, help="relative step of the grid")
    ap.add_argument("--work", type=Path, default=Path("lmgc90_scan_work"))
    ap.add_argument("--out", type=Path, default=Path("collapse_scan.json"))
    args = ap.parse_args()
    try:
        pairs = [(s, float(f), float(r) * 1e-3) for s, f, r in (p.split(":") for p in args.pairs.split(","))]
    except ValueError:
        ap.error(f"--pairs {args.pairs!r}: give specimen:frequency_hz:reference_mm, comma-separated "
                 "(e.g. W156:3:14.45,W118:3:32.44)")
    unknown = sorted({s for s, _, _ in pairs} - set(ARCH))
    if unknown or not all(f > 0 and r > 0 for _, f, r in pairs):
        ap.error(f"--pairs {args.pairs!r}: specimens are {', '.join(ARCH)}; frequency and reference must be > 0")
    grid = scan_grid(args.lo, args.hi, args.step)
    rows = json.loads(args.out.read_text())["rows"] if args.out.exists() else []
    done = {(r["slug"], r["specimen_id"], r["frequency_hz"]) for r in rows}
    for slug in args.slugs.split(","):
        stored = json.loads((T.ROOT / "postproc" / "tests" / "data" / "lmgc90" / f"{slug}.json").read_text())
        truth = {"parameters": stored["truth"]["parameters"], "faults": stored["faults"]}
        friction = truth["parameters"].get("friction", {})
        models = {}
        for sid, f, ref in pairs:
            if (slug, sid, f) in done:
                continue
            if sid not in models:
                models[sid] = T.Lmgc90Specimen(args.lmgc90_build, args.work / slug / sid, ARCH[sid], truth,
                                               friction.get("friction", ARCH[sid].friction))
            t0 = time.time()
            amps = [round(float(ref * x), 7) for x in grid]
            fell = [bool(models[sid].run(f, a)[0]) for a in amps]
            rows.append({"slug": slug, "model": stored["truth"]["model"], "specimen_id": sid, "frequency_hz": f,
                         "reference_m": ref, "amplitudes_m": amps, "collapsed": fell})
            print(f"{slug} {sid} {f:g} Hz: " + "".join("C" if c else "." for c in fell)
                  + f" ({time.time() - t0:.0f} s)", flush=True)
            args.out.write_text(json.dumps({
                "made_by": "bench/lmgc90/collapse_scan.py", "lo": args.lo, "hi": args.hi, "step": args.step,
                "rows": rows}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
