"""Which kinds of test could part the rivals that the LMGC90 loop leaves unnamed?

    python bench/diagnosis_test_types.py OUT_DIR [--truths N] [--bin-dir DIR]

Issue 35 lists the candidates of `next_test`: afd ramps at every frequency within the
table's limits (built), tests held below the threshold with the crown recorded (built),
cycle counts, and a record-driven test such as a slow ramp, which measures the static
capacity. This bench asks, before anything is built, whether the last two could part
what the first two cannot. For the first N stored LMGC90 truths inside the catalogue (the
loop's twenty by default, bench/lmgc90/loop.py) it takes:

- the truth's own model at the truth's parameters ("truth"), and at the parameters that
  fit LMGC90's noise-free thresholds best ("own fit": the same model, as the diagnosis
  would fit it);
- the three rival models that fit those thresholds best (campaign offset removed, as in
  bench/diagnosis_identifiability.py), each at its best grid point;

and for each of them, on each of the campaign's three arches, with Voussoir's kernel:

1. **Static capacity both ways** (voussoir-limit, the LP, non-associative friction):
   lambda towards +x and towards -x. A slow ramp would measure the weaker; a pulse one
   way, the capacity in its direction.
2. **Cycle counts**: the collapse threshold of the campaign's two frequencies with six
   full cycles (1-6-1) against one (1-1-1), with voussoir-sweep.

It prints, per truth, each model's change of these against the truth's own model at the
truth's parameters, in per cent, beside the afd fit residual. A rival that a test type
leaves within the own fit's own distance of the truth is not parted by it: two codes
differ by that much already (docs/diagnosis.md, "Crown records across codes").

Then the table: the longest time a default table (table.csv's defaults: stroke 0.15 m,
1 m/s) can hold each arch's static capacity lambda g from rest (end to end of its stroke,
or up to its largest velocity), against the arch's own time scale sqrt(R / g), R its mean
radius (its mechanism's free motion takes a few of them): a ramp is quasi-static only
when it lasts many of them.

Writes OUT_DIR/test_types.json. Runs the kernel, not LMGC90 (about 20 minutes on two
cores for twenty truths).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "postproc"), str(ROOT / "postproc" / "tests"), str(ROOT / "bench"),
                str(ROOT / "bench" / "lmgc90")]

from voussoir_post.diagnosis.bank import load_banks  # noqa: E402
from voussoir_post.diagnosis.effects import Variant, arch_group  # noqa: E402
from voussoir_post.diagnosis.models import MODEL_IDS  # noqa: E402
from voussoir_post.diagnosis.rates import covers  # noqa: E402
from voussoir_post.plots.drawing import provenance  # noqa: E402
from voussoir_post.readers.campaign import TableLimits  # noqa: E402
from voussoir_post.runner import Runner  # noqa: E402
from voussoir_post.units import G_M_S2  # noqa: E402

from lmgc90_campaigns import IDEAL, draw_campaign, stored_truths, truth_model, truth_variant  # noqa: E402

from crown_records import closest  # noqa: E402  (bench/lmgc90: a model's best grid point)
from diagnosis_identifiability import BANK, truth_thresholds  # noqa: E402

CYCLES = (1, 6)  #: full cycles of the afd motion compared (attack and decay one each)


def closest_fits(bank, obs, y: np.ndarray, model: str) -> tuple[tuple, list[tuple]]:
    """(own fit, three closest rivals): (rms of the log residuals less a campaign offset,
    model id, variant at the best grid point), each model's by crown_records.closest."""
    fits = []
    for m in MODEL_IDS:
        if "table_motion" in m:
            continue
        v, rms, _ = closest(bank, obs, y, m)
        fits.append((rms, m, v))
    fits.sort(key=lambda x: x[0])
    own = [f for f in fits if covers(f[1], model)]
    return (own[0] if own else None), [f for f in fits if not covers(f[1], model)][:3]


class Kernel:
    """Static capacities and afd thresholds of one variant on one specimen, cached."""

    def __init__(self, bin_dir: Path, work: Path):
        self.runner = Runner(bin_dir, work)
        self.cache: dict[str, object] = {}
        self.n = 0

    def _key(self, *parts) -> str:
        return json.dumps(parts, sort_keys=True, default=str)

    def capacity(self, spec, v: Variant) -> tuple[float, float]:
        """(lambda towards +x, towards -x): the LP's, friction non-associative."""
        key = self._key("lp", arch_group(spec, v))
        if key not in self.cache:
            self.n += 1
            nml = self.runner.write({"arch": arch_group(spec, v)}, f"lp_{self.n}")
            d = json.loads(self.runner.execute("voussoir-limit", nml, "--json").stdout)
            self.cache[key] = (float(d["load_factor_nonassociative"]), float(d["load_factor_nonassociative_neg"]))
        return self.cache[key]

    def thresholds(self, spec, v: Variant, freqs: list[float], n_full: int) -> list[float]:
        """Collapse thresholds [m] of the afd motion (1-n_full-1 cycles) at `freqs`."""
        key = self._key("afd", arch_group(spec, v), freqs, n_full)
        if key not in self.cache:
            self.n += 1
            groups = {"arch": arch_group(spec, v),
                      "motion": {"waveform": "afd", "n_attack": 1, "n_full": n_full, "n_decay": 1, "rest_s": 1.0},
                      "solver": {"dt_s": 1.0e-3, "theta": 0.5, "tol": 1.0e-4},
                      "sweep": {"mode": "threshold", "frequencies_hz": list(freqs), "amp_tol_m": 1.0e-4,
                                "amp_max_m": 0.3, "scan_step": 0.05}}
            result = self.runner.run_sweep(groups, f"afd_{self.n}")[0]
            self.cache[key] = [float(x) for x in result.results["threshold_m"]]
        return self.cache[key]


def describe(kernel: Kernel, obs, v: Variant) -> dict:
    """A variant's static capacities and thresholds at 1 and 6 full cycles, per specimen."""
    out = {}
    for sid, spec in obs.specimens.items():
        freqs = sorted({p.frequency_hz for p in obs.pairs if p.specimen_id == sid})
        lam = kernel.capacity(spec, v)
        out[sid] = {"lambda_pos": lam[0], "lambda_neg": lam[1], "frequencies_hz": freqs,
                    **{f"threshold_m_{c}": kernel.thresholds(spec, v, freqs, c) for c in CYCLES}}
    return out


def changes(a: dict, ref: dict) -> dict:
    """Per cent changes of a's quantities against ref's, over the specimens: the static
    capacity each way, the thresholds at one and at six full cycles, and the change of the
    six-cycle threshold relative to the one-cycle one (what a cycle count adds)."""
    def pct(x, y):
        return [100.0 * (p / q - 1.0) for p, q in zip(x, y)]
    lam_pos, lam_neg, one, six, added = [], [], [], [], []
    for sid in ref:
        lam_pos += pct([a[sid]["lambda_pos"]], [ref[sid]["lambda_pos"]])
        lam_neg += pct([a[sid]["lambda_neg"]], [ref[sid]["lambda_neg"]])
        one += pct(a[sid]["threshold_m_1"], ref[sid]["threshold_m_1"])
        six += pct(a[sid]["threshold_m_6"], ref[sid]["threshold_m_6"])
        added += [100.0 * (math.log(a6 / a1) - math.log(r6 / r1)) for a1, a6, r1, r6 in
                  zip(a[sid]["threshold_m_1"], a[sid]["threshold_m_6"], ref[sid]["threshold_m_1"],
                      ref[sid]["threshold_m_6"])]
    return {"lambda_pos": lam_pos, "lambda_neg": lam_neg, "afd_1": one, "afd_6": six, "cycles_added": added}


def largest(x: list[float]) -> float:
    finite = [abs(v) for v in x if math.isfinite(v)]
    return max(finite) if finite else math.nan


def rms(x: list[float]) -> float:
    """The RMS over the pairs: a kernel threshold jitters by 2-8 % near chaotic bands
    (docs/diagnosis.md), so the largest of six differences says more of the jitter."""
    finite = [v for v in x if math.isfinite(v)]
    return math.sqrt(sum(v * v for v in finite) / len(finite)) if finite else math.nan


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--truths", type=int, default=20, help="the first N stored truths inside the catalogue")
    ap.add_argument("--bin-dir", type=Path, default=ROOT / "build" / "drivers")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    bank = load_banks(BANK)
    kernel = Kernel(args.bin_dir, args.out / "work")
    rows = []
    chosen = [t for t in stored_truths() if truth_model(t) != "outside"][:args.truths]
    print("per cent against the truth's own model at its parameters: lambda +x/-x, the largest over the "
          "three arches; afd threshold 1-1-1 / 1-6-1 and what six cycles add, RMS over the six pairs")
    for t in chosen:
        obs, _ = draw_campaign(t, np.random.default_rng([2026, t["truth"]["index"], 0]), IDEAL)
        model = truth_model(t, bank, obs)
        own, rivals = closest_fits(bank, obs, truth_thresholds(t, obs), model)
        ref = describe(kernel, obs, truth_variant(t))
        row = {"slug": t["slug"], "model": model, "truth": ref, "fits": []}
        print(f"{t['slug'][:44]:44s} {model}", flush=True)
        for tag, fit in [("own fit", own)] + [("rival", r) for r in rivals]:
            if fit is None:
                continue
            fit_rms, m, v = fit
            d = changes(describe(kernel, obs, v), ref)
            row["fits"].append({"kind": tag, "model": m, "variant": [list(p) for p in v.parts()], "afd_fit_rms": fit_rms,
                                "changes_pct": d})
            print(f"    {tag:7s} {m:30s} fit {100 * fit_rms:4.1f}%   lambda {largest(d['lambda_pos']):5.1f}/"
                  f"{largest(d['lambda_neg']):5.1f}   afd {rms(d['afd_1']):5.1f}/{rms(d['afd_6']):5.1f}   "
                  f"cycles add {rms(d['cycles_added']):5.1f}   {v.parts()}", flush=True)
        rows.append(row)
    # A rival is parted by a test type when it moves that type's quantity further from the
    # truth than the own fit does (the distance two codes and a best fit already put between
    # the same model and the truth), by a margin of 2 % (a table's calibration, the scatter).
    print("\nrivals parted (beyond the own fit's own distance + 2 %), of those the afd ramps leave within "
          "the own fit's residual + 0.5 %:")
    tally = {"close": 0, "lambda_pos": 0, "lambda_both": 0, "cycles": 0}
    for row in rows:
        own = next((f for f in row["fits"] if f["kind"] == "own fit"), None)
        if own is None:
            continue
        for f in row["fits"]:
            if f["kind"] != "rival" or f["afd_fit_rms"] > own["afd_fit_rms"] + 0.005:
                continue
            tally["close"] += 1
            c, o = f["changes_pct"], own["changes_pct"]
            tally["lambda_pos"] += largest(c["lambda_pos"]) > largest(o["lambda_pos"]) + 2.0
            tally["lambda_both"] += max(largest(c["lambda_pos"]), largest(c["lambda_neg"])) > \
                max(largest(o["lambda_pos"]), largest(o["lambda_neg"])) + 2.0
            tally["cycles"] += rms(c["cycles_added"]) > rms(o["cycles_added"]) + 2.0
    print(f"  close rivals {tally['close']}: parted by the static capacity one way {tally['lambda_pos']}, "
          f"either way {tally['lambda_both']}, by six full cycles {tally['cycles']}")
    limits = TableLimits()
    table = []
    print(f"\nthe default table (stroke {limits.stroke_m} m, {limits.max_velocity_m_s} m/s): the longest hold of "
          f"lambda g from rest, against the arch's time scale sqrt(R / g)")
    for sid, spec in obs.specimens.items():
        lam = min(kernel.capacity(spec, Variant()))
        a = lam * G_M_S2
        # From rest at one end of the stroke to the other (2 x the amplitude), or up to the
        # largest velocity, whichever comes first.
        hold = min(math.sqrt(2.0 * 2.0 * limits.stroke_m / a), limits.max_velocity_m_s / a)
        r_mean = spec.r_ext_m - 0.5 * spec.thickness_m
        scale = math.sqrt(r_mean / G_M_S2)
        table.append({"specimen_id": sid, "lambda": lam, "hold_s": hold, "time_scale_s": scale})
        print(f"  {sid}: lambda {lam:.3f}, lambda g {a:.2f} m/s2: held {hold:.2f} s at most; sqrt(R / g) "
              f"{scale:.2f} s")
    summary = {"provenance": provenance("bench/diagnosis_test_types.py", f"{len(rows)} LMGC90 truths"),
               "seconds": time.time() - t0, "cycles": CYCLES, "truths": rows, "tally": tally, "table": table}
    (args.out / "test_types.json").write_text(json.dumps(summary, indent=1))
    print(f"\n{len(rows)} truths, {time.time() - t0:.0f} s; {args.out / 'test_types.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
