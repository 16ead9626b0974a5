"""Calibration of the diagnosis's probabilities on campaigns made by another code (LMGC90).

    python bench/diagnosis_calibration.py OUT_DIR [--draws D] [--truths DIR] [--faults lab|ideal]

The truths are those LMGC90 made (bench/lmgc90/truths.sh, stored in
postproc/tests/data/lmgc90): drawn from the diagnosis's own prior with values off every
grid, pairs and truths outside the catalogue, each specimen a little off its nominal
size. Each is replayed in D laboratory campaigns with the faults of real laboratories
(postproc/tests/lmgc90_campaigns.py: ramps of 1 to 5 mm, a transducer off by up to 2 %,
a campaign-wide offset, a fifth of the campaigns with collapse rows only) and diagnosed on
the stored simulation bank of the test arches (Voussoir's). Nothing here runs LMGC90 or
the kernel: the bench is fast and can be rerun after any change of the inference.

Prints, and writes into OUT_DIR/calibration.json: the rates of the done-when of issue 33
(causes named at 0.9 right, with a 95 % lower bound by truth from a bootstrap over the
truths; the truth in the 90 % set, by kind of truth; the nominal arch and the single
effects that move the thresholds by 10 % or more named at 0.9; truths outside the
catalogue named and flagged inadequate), the log and Brier scores of the stated
probability of the truth against a diagnosis that returns its prior, the mean size of the
90 % sets, the reliability of the stated probabilities (OUT_DIR/diagnosis_reliability.png)
and a simulation-based calibration of the parameters (the posterior CDF of the truth's
value, uniform when the posteriors are right: its 90 % coverage and a KS test).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.stats import kstest

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "postproc"), str(ROOT / "postproc" / "tests")]

from voussoir_post.diagnosis.bank import load_banks  # noqa: E402
from voussoir_post.diagnosis.figures import reliability_figure  # noqa: E402
from voussoir_post.diagnosis.models import MODEL_IDS, model_prior, nominal_log  # noqa: E402
from voussoir_post.diagnosis.rates import covers  # noqa: E402
from voussoir_post.plots.drawing import provenance  # noqa: E402

from lmgc90_campaigns import IDEAL, TRUTH_DIR, LabFaults, stored_truths, truth_model  # noqa: E402
from test_diagnosis_lmgc90 import outcomes  # noqa: E402

BANK = ROOT / "postproc" / "tests" / "data" / "replay" / "bank"


def kind(model: str) -> str:
    """A truth's kind by the model the diagnosis should name (lmgc90_campaigns.truth_model)."""
    return "outside" if model == "outside" else ("none" if model == "none" else ("pair" if "+" in model else model))


def effect_size(truth: dict, bank) -> float:
    """The largest change of a pair's threshold from the nominal model's (Voussoir's, the
    bank's), in relative terms."""
    sizes = []
    for p in truth["pairs"]:
        if p["threshold_m"] is None:
            continue
        sb = bank.specimens[p["specimen_id"]]
        sizes.append(abs(math.log(p["threshold_m"]) - nominal_log(sb, p["frequency_hz"])))
    return math.expm1(max(sizes)) if sizes else math.inf


def bootstrap_by_truth(outs: list[dict], stat, n: int = 2000, seed: int = 5) -> tuple[float, float]:
    """A statistic of the draws and its 95 % lower bound, resampling truths (not draws)."""
    slugs = sorted({o["slug"] for o in outs})
    by = {s: [o for o in outs if o["slug"] == s] for s in slugs}
    rng = np.random.default_rng(seed)
    values = []
    for _ in range(n):
        pick = rng.choice(len(slugs), len(slugs))
        sample = [o for k in pick for o in by[slugs[k]]]
        v = stat(sample)
        if v is not None:
            values.append(v)
    return stat(outs), float(np.quantile(values, 0.05)) if values else math.nan


def named_right(outs):
    named = [o for o in outs if o["named"] and o["truth"] != "outside"]
    return (sum(o["right_named"] for o in named) / len(named)) if named else None


def reliability(outs: list[dict], out: Path, note: str, n_boot: int = 2000, seed: int = 9) -> list[tuple]:
    """Draws binned by the stated probability of the most probable model against how often
    it is the truth; each bin's 95 % interval from a bootstrap over the truths (a truth's
    campaigns are not independent draws)."""
    inside = [o for o in outs if o["truth"] != "outside"]
    edges = np.array([0.0, 0.2, 0.4, 0.6, 0.8, 0.9, 1.0001])
    slugs = sorted({o["slug"] for o in inside})
    by = {s: [o for o in inside if o["slug"] == s] for s in slugs}
    rng = np.random.default_rng(seed)
    samples = [[o for k in rng.choice(len(slugs), len(slugs)) for o in by[slugs[k]]] for _ in range(n_boot)]
    bins = []
    for a, b in zip(edges[:-1], edges[1:]):
        sel = [o for o in inside if a <= o["p_top"] < b]
        if not sel:
            continue
        boot = [np.mean([o["top_right"] for o in smp if a <= o["p_top"] < b]) for smp in samples
                if any(a <= o["p_top"] < b for o in smp)]
        bins.append((float(a), float(min(b, 1.0)), len(sel), float(np.mean([o["p_top"] for o in sel])),
                     float(np.mean([o["top_right"] for o in sel])), float(np.quantile(boot, 0.025)),
                     float(np.quantile(boot, 0.975))))
    reliability_figure(out, bins, note)
    return bins


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--draws", type=int, default=10)
    ap.add_argument("--truths", type=Path, default=TRUTH_DIR)
    ap.add_argument("--faults", choices=("lab", "ideal"), default="lab")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    bank = load_banks(BANK)
    truths = stored_truths(args.truths)
    faults = LabFaults() if args.faults == "lab" else IDEAL
    t0 = time.time()
    outs = []
    for t in truths:
        got = outcomes(bank, [t], args.draws, faults)
        size = effect_size(t, bank)
        generator = truth_model(t)  # the generator's label, less the parameter bands only
        for o in got:
            o["kind"], o["effect_size"] = kind(o["truth"]), size
            o["generator_label"] = generator
            o["right_by_generator"] = o["named"] and covers(o["top"], generator)
            o["in_set_by_generator"] = any(covers(m, generator) for m in o["set"])
        outs += got
        print(f"[{time.time() - t0:5.0f} s] {t['slug']:44s} effect {100 * size:5.1f} %  in set "
              f"{sum(o['in_set'] for o in got):2d}/{len(got)}  named right {sum(o['right_named'] for o in got):2d}  "
              f"wrong {sum(o['wrong_named'] for o in got):2d}  mean P(truth) {np.mean([o['p_truth'] for o in got]):.2f}"
              f"  inadequate {sum(not o['adequate'] for o in got)}", flush=True)
    inside = [o for o in outs if o["truth"] != "outside"]
    outside = [o for o in outs if o["truth"] == "outside"]
    named = [o for o in inside if o["named"]]
    right, right_low = bootstrap_by_truth(outs, named_right)
    log_score = float(np.mean([math.log(max(o["p_truth"], 1e-300)) for o in inside]))
    log_prior = float(np.mean([math.log(o["prior_truth"]) for o in inside]))
    brier = float(np.mean([sum((p - (m == o["truth"])) ** 2 for m, p in o["probabilities"].items()) for o in inside]))
    prior_brier = float(np.mean([sum((model_prior(m) - (m == o["truth"])) ** 2 for m in MODEL_IDS) for o in inside]))
    by_kind = {}
    for k in sorted({o["kind"] for o in outs}):
        sel = [o for o in outs if o["kind"] == k]
        by_kind[k] = {"draws": len(sel), "truths": len({o["slug"] for o in sel}),
                      "in_set": sum(o["in_set"] for o in sel) / len(sel),
                      "named_right": sum(o["right_named"] for o in sel), "named_wrong": sum(o["wrong_named"] for o in sel),
                      "inadequate": sum(not o["adequate"] for o in sel)}
    strong = [o for o in inside if o["kind"] == "none" or (o["kind"] not in ("pair",) and o["effect_size"] >= 0.10)]
    cdfs = np.array([c for o in inside for c in o["cdf"].values()])
    table = {
        "draws": len(outs), "truths": len(truths), "faults": args.faults,
        "named_at_0.9": len(named), "named_right": right, "named_right_95pct_lower_bound_by_truth": right_low,
        "truth_in_90pct_set": sum(o["in_set"] for o in inside) / len(inside),
        "mean_90pct_set_size": float(np.mean([o["set_size"] for o in inside if not o["named"]] or [math.nan])),
        "strong_truths_named_right": (sum(o["right_named"] for o in strong) / len(strong)) if strong else None,
        "strong_draws": len(strong),
        "log_score": log_score, "log_score_of_the_prior": log_prior, "brier": brier, "brier_of_the_prior": prior_brier,
        "outside_named": sum(o["named"] for o in outside), "outside_inadequate": sum(not o["adequate"] for o in outside),
        "outside_draws": len(outside),
        "parameter_cdf_in_90pct": float(np.mean((cdfs >= 0.05) & (cdfs <= 0.95))) if cdfs.size else None,
        "parameter_cdf_ks_p": float(kstest(cdfs, "uniform").pvalue) if cdfs.size > 4 else None,
        "by_kind": by_kind,
    }
    note = provenance("bench/diagnosis_calibration.sh", f"{len(truths)} LMGC90 truths x {args.draws} campaigns "
                      f"({args.faults} faults); the test arches' bank")
    bins = reliability(outs, args.out, note)
    print()
    print(f"{len(outs)} campaigns of {len(truths)} LMGC90 truths ({args.faults} faults), {time.time() - t0:.0f} s")
    print(f"causes named at >= 0.9: {len(named)}, right {right} (95 % lower bound by truth {right_low:.2f}; "
          "goals 0.9 and 0.8)")
    relabelled = [o for o in inside if o["generator_label"] != o["truth"]]
    gen_named = [o for o in outs if o["generator_label"] != "outside" and o["named"]]
    print(f"by the generator's labels (an effect that moves no tested threshold by its material threshold kept "
          f"as a cause; {len({o['slug'] for o in relabelled})} truths relabelled): named right "
          f"{sum(o['right_by_generator'] for o in gen_named)} of {len(gen_named)}, truth in the 90 % set "
          f"{np.mean([o['in_set_by_generator'] for o in inside]):.3f}")
    table["by_generator_labels"] = {"relabelled_truths": sorted({o["slug"] for o in relabelled}),
                                    "named": len(gen_named),
                                    "named_right": sum(o["right_by_generator"] for o in gen_named),
                                    "truth_in_90pct_set": float(np.mean([o["in_set_by_generator"] for o in inside]))}
    print(f"truth in the 90 % set: {table['truth_in_90pct_set']:.3f} (goal 0.85 in every kind); mean size of the "
          f"sets of inconclusive draws {table['mean_90pct_set_size']:.2f}")
    for k, v in by_kind.items():
        print(f"  {k:16s} {v['truths']:3d} truths {v['draws']:4d} draws: in set {v['in_set']:.2f}, named right "
              f"{v['named_right']}, wrong {v['named_wrong']}, inadequate {v['inadequate']}")
    print(f"nominal arch and single effects moving thresholds >= 10 %: named right {table['strong_truths_named_right']}"
          f" of {len(strong)} draws (goal 0.8)")
    print(f"log score {log_score:.2f} against the prior's {log_prior:.2f}; Brier {brier:.3f} against the prior's "
          f"{prior_brier:.3f}")
    print(f"outside the catalogue: named {table['outside_named']} of {len(outside)}, flagged inadequate "
          f"{table['outside_inadequate']} (goal: never named, inadequate in half)")
    print(f"parameters: truth's posterior CDF within 5-95 % in {table['parameter_cdf_in_90pct']} (goal 0.9), "
          f"KS p {table['parameter_cdf_ks_p']}")
    print("reliability (stated bin, draws, mean stated, observed, 95 % interval):")
    for a, b, n, s, r, lo, hi in bins:
        print(f"  {a:.1f}-{b:.1f}  {n:4d}  {s:.2f}  {r:.2f}  [{lo:.2f}, {hi:.2f}]")
    clean = [{k: v for k, v in o.items() if k != "probabilities"} for o in outs]
    (args.out / "calibration.json").write_text(json.dumps({"table": table, "reliability": bins, "draws": clean},
                                                          indent=1, default=str) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
