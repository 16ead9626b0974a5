"""What the LMGC90 campaigns can say at best: the diagnosis on noise-free data.

    python bench/diagnosis_identifiability.py OUT_DIR [--draws D] [--truths DIR]

The power goal of issue 33 asks the nominal arch and every single effect that moves the
thresholds by 10 % or more to be named at 0.9 in 80 % of their laboratory draws. Whether
any method can do that on these campaigns (three arches, two frequencies each) depends
on what the data hold, so this bench measures it twice, for every stored LMGC90 truth
inside the catalogue (postproc/tests/data/lmgc90):

1. **Best fits, no inference.** For every model, the grid point whose predicted
   thresholds (Voussoir's bank, the emulators of models.py) lie closest to LMGC90's
   noise-free thresholds: the RMS of the log residuals over the six pairs, raw, after
   one offset for the campaign (what two codes differ by everywhere, a transducer's
   calibration), and after one offset per specimen (a specimen built a little off). The
   truth's own model does not fit exactly (the two codes differ): a rival that fits as
   closely cannot be told from it by any inference on these thresholds.
2. **The oracle campaign.** The diagnosis run on the finest brackets the generator
   knows (LMGC90's own bisection: its last stand and first collapse, 0.5 % apart), the
   table following the command exactly, no transducer bias, no campaign offset, every
   row kept: a laboratory with no faults at all. Its P(truth) bounds what this design
   can give under the diagnosis's noise model (the inter-code discrepancy it must allow).

Then the laboratory draws (lmgc90_campaigns.draw_campaign, the calibration's faults) of
the power truths, and their naming rate, split by whether the oracle names the truth.
Prints a table and writes OUT_DIR/identifiability.json. Runs neither LMGC90 nor the
kernel (about a minute).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "postproc"), str(ROOT / "postproc" / "tests")]

from voussoir_post.diagnosis.bank import load_banks  # noqa: E402
from voussoir_post.diagnosis.models import MODEL_IDS, model_grid, model_prior  # noqa: E402
from voussoir_post.diagnosis.rates import covers, outcome  # noqa: E402
from voussoir_post.plots.drawing import provenance  # noqa: E402

from lmgc90_campaigns import IDEAL, TRUTH_DIR, draw_campaign, stored_truths, truth_model  # noqa: E402

from diagnosis_calibration import effect_size  # noqa: E402  (bench/, beside this script)

BANK = ROOT / "postproc" / "tests" / "data" / "replay" / "bank"
NAMED = 0.9
POWER_EFFECT = 0.10  #: the done-when's size of a single effect that must be named


def truth_thresholds(truth: dict, obs) -> np.ndarray:
    """LMGC90's noise-free log thresholds at the campaign's pairs (first collapse)."""
    by = {(p["specimen_id"], round(p["frequency_hz"], 9)): p["threshold_m"] for p in truth["pairs"]}
    return np.array([math.log(by[(p.specimen_id, round(p.frequency_hz, 9))]) for p in obs.pairs])


def best_fits(bank, obs, y: np.ndarray) -> dict[str, tuple[float, float, float]]:
    """Per model (table_motion apart: its gains come from the records), the least RMS of
    the log residuals over its grid: raw, less a campaign offset, less a specimen offset."""
    groups = [np.array([k for k, p in enumerate(obs.pairs) if p.specimen_id == s])
              for s in dict.fromkeys(p.specimen_id for p in obs.pairs)]
    out = {}
    for m in MODEL_IDS:
        if "table_motion" in m:
            continue
        g = model_grid(m, bank, obs)
        if g.n == 0 or not np.isfinite(g.log_prior).any():
            continue
        r = g.mu - y[None, :]
        ok = np.isfinite(g.log_prior)
        rc = r - r.mean(axis=1, keepdims=True)
        rs = r.copy()
        for idx in groups:
            rs[:, idx] -= r[:, idx].mean(axis=1, keepdims=True)
        rms = [float(np.sqrt((x[ok] ** 2).mean(axis=1)).min()) for x in (r, rc, rs)]
        out[m] = tuple(rms)
    return out


def oracle_observations(truth: dict, obs):
    """The campaign's pairs with LMGC90's own brackets and exact gains."""
    by = {(p["specimen_id"], round(p["frequency_hz"], 9)): p for p in truth["pairs"]}
    pairs = []
    for p in obs.pairs:
        t = by[(p.specimen_id, round(p.frequency_hz, 9))]
        low = t["last_stand_m"] if t["last_stand_m"] and t["last_stand_m"] < t["threshold_m"] else 0.0
        pairs.append(dataclasses.replace(p, low_m=low, high_m=t["threshold_m"],
                                         gains=tuple(t["table_gain"] for _ in p.gains)))
    return dataclasses.replace(obs, pairs=pairs)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--draws", type=int, default=10, help="laboratory draws of each power truth")
    ap.add_argument("--truths", type=Path, default=TRUTH_DIR)
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    bank = load_banks(BANK)
    rows, outside = [], []
    print(f"{'truth':46s} {'model':26s} {'effect':>6s}  {'own fit %':>15s}  {'closest rival (fit %)':40s} "
          f"{'oracle P':>8s}")
    print(f"{'':46s} {'':26s} {'':6s}  {'raw/camp/spec':>15s}")
    for t in stored_truths(args.truths):
        obs, _ = draw_campaign(t, np.random.default_rng([2026, t["truth"]["index"], 0]), IDEAL)
        if not obs.pairs:
            continue
        model = truth_model(t, bank, obs)
        if model == "outside":
            o = outcome(bank, oracle_observations(t, obs), model)
            fit = min(v[1] for v in best_fits(bank, obs, truth_thresholds(t, obs)).values())
            outside.append({"slug": t["slug"], "closest_fit": fit, "oracle_p_value": o["p_value"],
                            "oracle_inadequate": not o["adequate"], "oracle_named": o["named"]})
            continue
        y = truth_thresholds(t, obs)
        fits = best_fits(bank, obs, y)
        own = min((v for m, v in fits.items() if covers(m, model)), default=(math.nan,) * 3, key=lambda v: v[1])
        rivals = sorted((v[1], m, v) for m, v in fits.items() if not covers(m, model))
        oracle = outcome(bank, oracle_observations(t, obs), model)
        size = effect_size(t, bank)
        power = model == "none" or ("+" not in model and size >= POWER_EFFECT)
        row = {"slug": t["slug"], "model": model, "effect": size, "power_truth": power,
               "own_fit": own, "rival": rivals[0][1] if rivals else None,
               "rival_fit": rivals[0][2] if rivals else None,
               "oracle_p_truth": oracle["p_truth"], "oracle_top": oracle["top"], "oracle_p_top": oracle["p_top"],
               "oracle_named_right": bool(oracle["named"] and oracle["right_named"])}
        rows.append(row)
        riv = f"{row['rival']} ({'/'.join(f'{100 * x:.1f}' for x in row['rival_fit'])})" if rivals else "-"
        print(f"{t['slug'][:46]:46s} {model[:26]:26s} {100 * size:5.1f}%  "
              f"{'/'.join(f'{100 * x:.1f}' for x in own):>15s}  {riv:40s} {oracle['p_truth']:8.2f}"
              f"{'  named' if row['oracle_named_right'] else ''}{'  *' if power else ''}", flush=True)

    print("\ntruths outside the catalogue, the oracle campaign: the closest fit of any catalogue model (campaign "
          "offset removed) and the adequacy check")
    for r in outside:
        print(f"  {r['slug'][:46]:46s} closest fit {100 * r['closest_fit']:4.1f} %  adequacy p {r['oracle_p_value']:.3f}"
              f"{'  inadequate' if r['oracle_inadequate'] else ''}{'  NAMED' if r['oracle_named'] else ''}")
    print(f"  flagged inadequate: {sum(r['oracle_inadequate'] for r in outside)} of {len(outside)}; named: "
          f"{sum(r['oracle_named'] for r in outside)}")

    power_rows = [r for r in rows if r["power_truth"]]
    print(f"\n* power truths (the nominal arch, single effects moving a threshold by {100 * POWER_EFFECT:.0f} % "
          f"or more): {len(power_rows)}")
    closer = [r for r in power_rows if r["rival_fit"] and r["rival_fit"][1] <= r["own_fit"][1]]
    print(f"  a rival fits LMGC90's noise-free thresholds as closely as the truth's own model "
          f"(campaign offset removed): {len(closer)} of {len(power_rows)}")
    oracle_named = [r for r in power_rows if r["oracle_named_right"]]
    print(f"  named at {NAMED} by the oracle campaign (no laboratory faults): {len(oracle_named)} of "
          f"{len(power_rows)}; mean oracle P(truth) {np.mean([r['oracle_p_truth'] for r in power_rows]):.2f}")

    by_slug = {t["slug"]: t for t in stored_truths(args.truths)}
    draws = []
    for r in power_rows:
        t = by_slug[r["slug"]]
        for k in range(args.draws):  # the calibration's draws (test_diagnosis_lmgc90.outcomes' seeds)
            obs, drawn = draw_campaign(t, np.random.default_rng([2026, t["truth"]["index"], k]))
            if not obs.pairs:
                continue
            o = outcome(bank, obs, r["model"])
            width = float(np.median([math.log(p.high_m / p.low_m) if p.low_m > 0 else math.inf for p in obs.pairs]))
            draws.append({"slug": r["slug"], "oracle_named": r["oracle_named_right"], "width": width,
                          "collapses_only": drawn["collapses_only"], "named_right": bool(o["right_named"]),
                          "p_truth": o["p_truth"]})
    print(f"  laboratory draws of the power truths ({args.draws} each, the calibration's faults), named right at "
          f"{NAMED}:")
    print(f"    {'':34s} {'all':>12s} {'brackets < 5 %':>16s} {'brackets >= 5 %':>16s} {'collapses only':>16s}")
    for label, flag in (("truths the oracle names", True), ("truths the oracle does not name", False)):
        sel = [d for d in draws if d["oracle_named"] == flag]
        cells = []
        for sub in (sel, [d for d in sel if d["width"] < 0.05], [d for d in sel if 0.05 <= d["width"] < math.inf],
                    [d for d in sel if d["collapses_only"]]):
            k = sum(d["named_right"] for d in sub)
            cells.append(f"{k}/{len(sub)}" + (f" ({k / len(sub):.2f})" if sub else ""))
        print(f"    {label:34s} " + " ".join(f"{c:>16s}" for c in cells))
    print("    (brackets: the median over the pairs of log(first collapse / last stand); collapses only: no stand "
          "row, every bracket open below)")
    summary = {"provenance": provenance("bench/diagnosis_identifiability.py", f"{len(rows)} LMGC90 truths"),
               "seconds": time.time() - t0, "draws": args.draws, "truths": rows, "outside": outside, "lab_draws": draws, "prior": {m: model_prior(m) for m in MODEL_IDS}}
    (args.out / "identifiability.json").write_text(json.dumps(summary, indent=1))
    print(f"\n{len(rows)} truths inside the catalogue, {time.time() - t0:.0f} s; {args.out / 'identifiability.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
