"""Do crown records part the rivals that the thresholds confuse, across codes? A bench
(issues 33 and 35: "the records and hinges where the causes part physically"); runs
LMGC90 and the kernel, never a test.

    python bench/lmgc90/crown_records.py --lmgc90-build DIR OUT [--slugs S1,S2]
        [--fractions 0.9,0.95,0.98] [--pair-thresholds] [--extra-pairs W118:4,W156:3]
        [--extra-only] [--thresholds-from JSON] [--truths-dir DIR] [--bin-dir DIR]
    python bench/lmgc90/crown_records.py --lmgc90-build DIR OUT --from-json OUT/crown_records.json

The thresholds of a campaign (three arches, two frequencies) cannot part a thinner ring
from inset pivots, nor the nominal arch from a pair of small effects
(bench/diagnosis_identifiability.py): the closest rival fits LMGC90's noise-free thresholds
as closely as the truth's own model. Within Voussoir, a test that stands just below the
threshold does part them by its crown record (bench/diagnosis_crown.py: 3 mm apart
against 0.5 mm of spread). Whether that holds against another code is what a crown record
would have to show before it can enter the likelihood: here, for each stored LMGC90
truth with the table following the command (the nominal arch, a ring, a friction; no
actuator), at each of its six (arch, frequency) pairs:

- LMGC90 runs the truth's own specimens (its faults baked in) at each of `fractions` x
  its threshold (commanded amplitude), recording the crown relative to the table
  (truth_case.py: the keystone, or the mean of the two middle voussoirs);
- Voussoir runs (the nominal specimens) the truth's own model and its closest rival, each
  at its grid point closest to LMGC90's thresholds after one campaign offset (as the
  identifiability bench finds them; the own model of a truth with brackets among the
  points with brackets on its side, which the thresholds do not tell), at the same
  fraction of that model's own threshold
  (with --pair-thresholds, its threshold searched at the pair, as the bank searches it
  and as the diagnosis uses it; without, the amplitude times the model's campaign
  offset, which takes the fit's misfit at the pair for cross-code error), at dt x 0.97, 1
  and 1.03 (the simulator's spread);
- with --extra-pairs, the same at pairs beyond the campaign's six, LMGC90's threshold
  there found by the truths' own scan and bisection (or read from --thresholds-from) and
  the models always at their own threshold at the pair. The stored file of the tests
  (postproc/tests/data/lmgc90/crown_records.json) is this bench with --pair-thresholds
  --extra-pairs W118:4,W132:4,W156:3,W156:4 on the nine DEFAULT_SLUGS and t107, t109,
  t206 and t207, and with --truths-dir postproc/tests/data/lmgc90/crown_truths on the
  eight truths with pivots set in stored there (truths.py --first K --truths K+1 for K
  in 26, 27, 46, 47, 89, 110, 153, 158: picked by hand among the calibration seed's
  draws past its stored truths whose model has contact_edges and no actuator, for a
  spread of chamfers, 1.1 to 7.5 mm, alone and beside a ring, brackets or a friction;
  kept apart from the calibration's truths because they were chosen by model);
  postproc/tests/data/lmgc90/crown_records_ramp.json is this bench with --pair-thresholds
  --ramp-brackets on the same twenty-one truths (LMGC90 at fractions of a ramp's bracket);
- the peak horizontal crown displacement of each: LMGC90's measured peak against the two
  models' predictions.

Prints a row per pair and fraction: the peaks [mm], the cross-code error of the truth's
own model (log LMGC90 / own), the rivals' difference (log rival / own), the replicas'
spread, and which model LMGC90's peak lies closer to. A row where every peak stays below
FLOOR_M (0.5 mm, the floor of the diagnosis's crown comparison: a transducer's noise) is
a test that did not rock, and says nothing; a row where a run fell is left out. Then,
over the rows that rocked: the share where LMGC90's peak is closer to the truth's own
model, and the median |cross-code error| against the median |rivals' difference|; and at
each fraction, per truth, the log likelihood ratio of its records between its own model
and the rival, the error model's spread taken from the other truths' records (`evidence`).
For a truth outside the catalogue (no own model) the "own" model is the closest of the
catalogue by thresholds and the "rival" the next: its records' misfit against that model is
set beside the inside truths' against their own (would a check on the records flag it?).
Writes OUT/crown_records.json.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.stats import t as student_t

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path[:0] = [str(ROOT / "postproc"), str(ROOT / "postproc" / "tests"), str(ROOT / "bench"), str(HERE)]

from voussoir_post.diagnosis.bank import load_banks, variant_key  # noqa: E402
from voussoir_post.diagnosis.crown import peak_m, variant_at  # noqa: E402
from voussoir_post.diagnosis.effects import Variant, restraint_parts  # noqa: E402
from voussoir_post.diagnosis.models import MODEL_IDS, model_grid  # noqa: E402
from voussoir_post.diagnosis.rates import covers  # noqa: E402
from voussoir_post.diagnosis.settings import DiagnosisSettings  # noqa: E402
from voussoir_post.diagnosis.simulator import Simulator  # noqa: E402
from voussoir_post.readers.campaign import Test  # noqa: E402

from independent_campaigns import ARCHES  # noqa: E402
from lmgc90_campaigns import IDEAL, TRUTH_DIR, draw_campaign, stored_truths, truth_model  # noqa: E402
from truths import Lmgc90Specimen, onset_m, search  # noqa: E402

BANK = ROOT / "postproc" / "tests" / "data" / "replay" / "bank"
DT_FACTORS = (0.97, 1.0, 1.03)
DEFAULTS = DiagnosisSettings(bin_dir=ROOT / "build" / "drivers")  #: the bank's search settings
T_DOF = 3  #: degrees of freedom of the records' error law (Student t)
FLOOR_M = 5.0e-4  #: peaks below this are a transducer's noise (single_runs.crown_comparison's floor)
#: The truths whose table follows the command and whose model is a power truth of the
#: identifiability bench (the nominal arch, a ring, a friction).
DEFAULT_SLUGS = ("t03_none", "t04_none", "t07_none", "t00_geometry_0.928", "t06_geometry_0.880",
                 "t18_geometry_0.807", "t23_geometry_1.079", "t13_friction_0.422", "t103_friction_0.268")


def closest(bank, obs, y: np.ndarray, model: str, side: str | None = None) -> tuple[Variant, float, float]:
    """The grid point of `model` whose log thresholds lie closest to y after one campaign
    offset: its variant, its RMS and the offset (log, model less LMGC90). With `side`, among
    the points whose brackets are on that side only."""
    g = model_grid(model, bank, obs)
    r = g.mu - y[None, :]
    ok = np.isfinite(g.log_prior)
    if side is not None and "base_restraint" in g.names:
        column = g.values[list(g.names).index("base_restraint")]
        ok &= np.array([restraint_parts(v)[0] == side for v in column])
    rc = r - r.mean(axis=1, keepdims=True)
    rms = np.where(ok, np.sqrt((rc ** 2).mean(axis=1)), np.inf)
    j = int(np.argmin(rms))
    return variant_at(g, j), float(rms[j]), float(r[j].mean())


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lmgc90-build", required=True)
    ap.add_argument("out", type=Path)
    ap.add_argument("--slugs", default=",".join(DEFAULT_SLUGS))
    ap.add_argument("--fractions", default="0.9,0.95,0.98", help="of each threshold, where the tests stand")
    ap.add_argument("--extra-pairs", default="",
                    help="pairs beyond the campaign's six, as W118:4,W156:3: LMGC90's threshold found there by the "
                         "truths' own search (truths.search), then the records as at the others")
    ap.add_argument("--extra-only", action="store_true", help="the extra pairs only")
    ap.add_argument("--pair-thresholds", action="store_true",
                    help="at the campaign's pairs too, run Voussoir's models at a fraction of their own threshold "
                         "searched at the pair (as at the extra pairs and in the diagnosis), not of LMGC90's times "
                         "the campaign's offset")
    ap.add_argument("--thresholds-from", type=Path,
                    help="a crown_records.json whose rows give LMGC90's thresholds at the extra pairs (amplitude / "
                         "fraction): no search again (LMGC90 repeats itself to 5e-5 mm)")
    ap.add_argument("--ramp-brackets", action="store_true",
                    help="at the campaign's pairs, hold LMGC90 at fractions of the midpoint of the bracket a "
                         "laboratory's ramp finds (the campaign of lmgc90_campaigns.IDEAL: 2 mm steps from 0.7 x the "
                         "onset, through the windows where the truth stands above its first collapse), as the "
                         "diagnosis reads a record's fraction, not of the search's first collapse")
    ap.add_argument("--truths-dir", type=Path, default=TRUTH_DIR,
                    help="folder of the LMGC90 truths (bench/lmgc90/truths.py --out; default the calibration's)")
    ap.add_argument("--bin-dir", type=Path, default=ROOT / "build" / "drivers")
    ap.add_argument("--from-json", type=Path, help="summarise a stored crown_records.json instead of running")
    args = ap.parse_args()
    if args.ramp_brackets and (args.extra_pairs or args.extra_only):
        ap.error("--ramp-brackets: the campaign's pairs only (the extra pairs have no stored probes to ramp through)")
    args.out.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    if args.from_json:
        stored = json.loads(args.from_json.read_text())
        summarise(stored["rows"], stored["fractions"], args.out, 0.0)
        return 0
    bank = load_banks(BANK)
    truths = {t["slug"]: t for t in stored_truths(args.truths_dir)}
    unknown = [s for s in args.slugs.split(",") if s and s not in truths]
    if unknown:
        ap.error(f"--slugs: no stored truth {', '.join(unknown)} in {args.truths_dir}")
    sims = {f: Simulator(DiagnosisSettings(bin_dir=args.bin_dir, dt_s=1.0e-3 * f, log=lambda *_: None),
                         args.out / f"voussoir_dt_{f}") for f in DT_FACTORS}
    arches = {a.specimen_id: a for a in ARCHES}
    rows = []
    fractions = [float(x) for x in args.fractions.split(",") if x]
    extra = []
    for x in (x for x in args.extra_pairs.split(",") if x):
        sid, _, f = x.partition(":")
        try:
            extra.append((sid, float(f)))
        except ValueError:
            ap.error(f"--extra-pairs: {x!r} is not SPECIMEN:FREQUENCY_HZ (as W118:4)")
        if sid not in arches or not extra[-1][1] > 0:
            ap.error(f"--extra-pairs: {x!r}: the specimens are {', '.join(sorted(arches))}, the frequency in Hz > 0")
    known = {}
    if args.thresholds_from:
        given = json.loads(args.thresholds_from.read_text())["rows"]
        if any("amplitude_m" not in r for r in given):
            ap.error(f"--thresholds-from {args.thresholds_from}: its rows have no amplitude_m (a file this bench "
                     "wrote, not the tests' stored file, which keeps only what the tests read)")
        known = {(r["slug"], r["specimen_id"], round(r["frequency_hz"], 9)): r["amplitude_m"] / r["fraction"]
                 for r in given}
    print(f"{'truth':22s} {'pair':9s} {'frac':4s} {'own':26s} {'rival':34s} {'LMGC90':>6s} {'own':>6s} {'rival':>6s} "
          f"{'spread':>6s} {'err':>6s} {'diff':>6s}  closer   (peak crown dx, mm; err = log LMGC90/own, "
          f"diff = log rival/own)")
    for slug in [s for s in args.slugs.split(",") if s]:
        t = truths[slug]
        obs, _ = draw_campaign(t, np.random.default_rng([2026, t["truth"]["index"], 0]), IDEAL)
        model = truth_model(t, bank, obs)
        by = {(p["specimen_id"], round(p["frequency_hz"], 9)): p for p in t["pairs"]}
        y = np.array([math.log(by[(p.specimen_id, round(p.frequency_hz, 9))]["threshold_m"]) for p in obs.pairs])
        fits = {m: closest(bank, obs, y, m) for m in MODEL_IDS if "table_motion" not in m}
        if model == "outside":   # no own model: the closest of the catalogue, and the next closest
            ranked = sorted(fits, key=lambda m: fits[m][1])
            own_id, rival_id = ranked[0], ranked[1]
        else:
            own_id = min((m for m in fits if covers(m, model)), key=lambda m: fits[m][1])
            side = t["truth"]["parameters"].get("base_restraint", {}).get("side")
            if side is not None and "base_restraint" in own_id:
                # The thresholds do not tell the brackets' side (a side's mirror fits them
                # about as well) and the diagnosis keeps both; the truth's own model is on
                # its side (t158: its left-side mirror rocked 0.2 to 3 in log more).
                fits[own_id] = closest(bank, obs, y, own_id, side)
            rival_id = min((m for m in fits if not covers(m, model)), key=lambda m: fits[m][1])
        own, rival = fits[own_id], fits[rival_id]
        specimens = {}

        def specimen(sid):
            if sid not in specimens:   # as truths.make_truth builds the truth's specimens
                drawn = dict(t["truth"], faults=t["faults"])
                friction = drawn["parameters"].get("friction", {}).get("friction", arches[sid].friction)
                specimens[sid] = Lmgc90Specimen(args.lmgc90_build, args.out / "lmgc90" / slug / sid, arches[sid],
                                                drawn, friction, record_crown=True)
            return specimens[sid]

        def own_offsets(sid, f, thr, onset, how):
            """Voussoir's own and rival thresholds at the pair (as the bank searches them):
            their log offsets from LMGC90's, so that the models run at a fraction of their
            own threshold at the pair, as the diagnosis runs them."""
            found = sims[1.0].thresholds_at(obs.specimens[sid], [f], (1, 1, 1), [own[0], rival[0]],
                                            DEFAULTS.ceiling_factor * onset, DEFAULTS.amp_tol_fraction * onset)
            print(f"{slug[:22]:22s} {sid} {f:4.2f} LMGC90 threshold {1e3 * thr:.2f} mm ({how}); Voussoir's own "
                  f"{1e3 * found[(own[0], f)]:.2f} mm, rival {1e3 * found[(rival[0], f)]:.2f} mm", flush=True)
            return {name: math.log(found[(v[0], f)] / thr) for name, v in (("own", own), ("rival", rival))}

        thresholds = []   # (specimen, frequency, LMGC90's threshold, the models' offsets at the pair or None)
        for p in ([] if args.extra_only else obs.pairs):   # LMGC90's stored threshold
            sid, f = p.specimen_id, p.frequency_hz
            thr, how = by[(sid, round(f, 9))]["threshold_m"], "stored"
            if args.ramp_brackets:
                if p.low_m <= 0:
                    print(f"{slug[:22]:22s} {sid} {f:4.2f} no stand below the ramp's collapse: left out", flush=True)
                    continue
                thr, how = p.threshold_m, (f"ramp bracket {1e3 * p.low_m:.2f}-{1e3 * p.high_m:.2f} mm; "
                                           f"bisection {1e3 * thr:.2f} mm")
            offsets = (own_offsets(sid, f, thr, onset_m(arches[sid], f, args.bin_dir), how)
                       if args.pair_thresholds else None)
            thresholds.append((sid, f, thr, offsets))
        for sid, f in extra:   # pairs beyond the campaign's: LMGC90's threshold by the truths' own search
            if sid not in obs.specimens:
                print(f"{slug[:22]:22s} {sid} {f:4.2f} not in this truth's campaign: left out", flush=True)
                continue
            onset = onset_m(arches[sid], f, args.bin_dir)
            if (slug, sid, round(f, 9)) in known:
                thr, how = known[(slug, sid, round(f, 9))], "stored"
            else:
                lm = specimen(sid)
                found = search(lambda a, f=f, lm=lm: lm.run(f, a)[:2], onset)
                thr, how = found["threshold_m"], f"{len(found['probes'])} runs"
            if thr is None:
                print(f"{slug[:22]:22s} {sid} {f:4.2f} LMGC90 threshold none ({how})", flush=True)
                continue
            # Not the campaign's offset: carried from the other frequencies it differs from
            # the pair's own by several per cent (docs/diagnosis.md).
            thresholds.append((sid, f, thr, own_offsets(sid, f, thr, onset, how)))
        for sid, f, threshold, offsets in thresholds:
            campaign_pair = (sid, round(f, 9)) in by
            for fraction in fractions:
                amp = fraction * threshold
                lm = specimen(sid)
                collapsed, _, _ = lm.run(f, amp)
                lm_mm = 1e3 * peak_m(lm.last["crown_dx_m"])
                spec = obs.specimens[sid]
                pred = {}
                for name, (variant, _, offset) in (("own", own), ("rival", rival)):
                    offset = offsets[name] if offsets else offset   # else the campaign's
                    test = Test(f"{slug}_{sid}_{f}_{fraction}_{name}", sid, "afd", "stand", frequency_hz=f,
                                amplitude_m=amp * math.exp(offset), n_attack=1, n_full=1, n_decay=1)
                    runs = [sim.run_tests([(spec, test, variant, {})])[0] for sim in sims.values()]
                    pred[name] = ([1e3 * float(np.max(np.abs(r["crown_dx_m"]))) for r in runs],
                                  any(r["collapsed"] for r in runs))
                o, r_ = float(np.mean(pred["own"][0])), float(np.mean(pred["rival"][0]))
                spread = float(np.std(np.log(pred["own"][0])))  # the own model's replicas (dt)
                fell = collapsed or pred["own"][1] or pred["rival"][1]
                rocked = max(lm_mm, o, r_) >= 1e3 * FLOOR_M
                floor = 1e3 * FLOOR_M
                lo, oo, ro = max(lm_mm, floor), max(o, floor), max(r_, floor)
                err, diff = math.log(lo / oo), math.log(ro / oo)
                closer = "own" if abs(math.log(lo / oo)) < abs(math.log(lo / ro)) else \
                    ("tie" if abs(math.log(lo / oo)) == abs(math.log(lo / ro)) else "rival")
                row = {"slug": slug, "model": model, "own": variant_key(own[0]), "own_fit": own[1],
                       "own_offset": own[2], "rival": variant_key(rival[0]), "rival_fit": rival[1],
                       "rival_offset": rival[2], "specimen_id": sid, "frequency_hz": f, "fraction": fraction,
                       "amplitude_m": amp, "lmgc90_collapsed": collapsed, "lmgc90_peak_mm": lm_mm,
                       "own_peaks_mm": pred["own"][0], "own_collapsed": pred["own"][1],
                       "rival_peaks_mm": pred["rival"][0], "rival_collapsed": pred["rival"][1],
                       "campaign_pair": campaign_pair,
                       "held_at": "ramp bracket" if args.ramp_brackets and campaign_pair else "threshold",
                       "own_threshold_offset": offsets["own"] if offsets else own[2],
                       "rocked": rocked, "fell": fell, "log_err": err, "log_diff": diff, "log_spread": spread,
                       "closer": closer}
                rows.append(row)
                note = " fell: " + ",".join(n for n, c in (("LMGC90", collapsed), ("own", pred["own"][1]),
                                                           ("rival", pred["rival"][1])) if c) if fell else \
                    ("" if rocked else " (no rocking)")
                print(f"{slug[:22]:22s} {sid} {f:4.2f} {fraction:4.2f} {variant_key(own[0])[:26]:26s} "
                      f"{variant_key(rival[0])[:34]:34s} {lm_mm:6.2f} {o:6.2f} {r_:6.2f} {spread:6.3f} {err:+6.2f} "
                      f"{diff:+6.2f}  {closer}{note}", flush=True)
    summarise(rows, fractions, args.out, time.time() - t0)
    return 0


def evidence(rows: list[dict], fraction: float) -> list[dict]:
    """Per truth, what its crown records at `fraction` of each threshold would say between
    its own model and its closest rival: the log likelihood ratio sum_i [log f(e_i) -
    log f(e_i - d_i)] (e_i = log LMGC90 / own, d_i = log rival / own; positive favours the
    truth) for an error law f of scale sigma, the robust spread (1.4826 x the median
    absolute deviation) of the cross-code errors of the OTHER truths' records (leave one
    truth out: the error model is never fitted to the truth it judges): a Student t of 3
    degrees of freedom (`llr`, heavy tails: a record the codes disagree on by several
    spreads costs little), and a normal law for comparison (`llr_normal`); P(own) from even
    odds under the t. The rows of a truth share specimens and are taken as independent: an
    upper bound on the evidence."""
    use = [r for r in rows if r["rocked"] and not r["fell"] and abs(r["fraction"] - fraction) < 1e-9
           and r["model"] != "outside"]
    out = []
    for slug in dict.fromkeys(r["slug"] for r in use):
        mine = [r for r in use if r["slug"] == slug]
        others = np.array([r["log_err"] for r in use if r["slug"] != slug])
        if not mine or others.size < 5:
            continue
        sigma = max(1.4826 * float(np.median(np.abs(others - np.median(others)))), 0.02)
        e = np.array([r["log_err"] for r in mine])
        d = np.array([r["log_diff"] for r in mine])
        llr_normal = float(np.sum(((e - d) ** 2 - e ** 2) / (2 * sigma ** 2)))
        llr = float(np.sum(student_t.logpdf(e, T_DOF, scale=sigma) - student_t.logpdf(e - d, T_DOF, scale=sigma)))
        out.append({"slug": slug, "rival": mine[0]["rival"], "tests": len(mine), "sigma": sigma, "llr": llr,
                    "llr_normal": llr_normal, "p_own": 1.0 / (1.0 + math.exp(-max(-700.0, min(700.0, llr))))})
    return out


def summarise(rows: list[dict], fractions: list[float], out_dir: Path, seconds: float) -> None:
    outside = [r for r in rows if r["rocked"] and not r["fell"] and r["model"] == "outside"]
    ok = [r for r in rows if r["rocked"] and not r["fell"] and r["model"] != "outside"]
    share = sum(r["closer"] == "own" for r in ok) / max(1, len(ok))
    med_err = float(np.median([abs(r["log_err"]) for r in ok])) if ok else math.nan
    med_diff = float(np.median([abs(r["log_diff"]) for r in ok])) if ok else math.nan
    n_inside = sum(r["model"] != "outside" for r in rows)
    print(f"\n{len(ok)} of {n_inside} tests of truths inside the catalogue rocked and stood in every run: LMGC90's peak closer to the truth's own model in "
          f"{share:.2f} of them; median |log LMGC90/own| {med_err:.2f}, median |log rival/own| {med_diff:.2f}; "
          f"{seconds:.0f} s")
    misfit = {}
    if outside:
        print("\ntruths outside the catalogue: LMGC90's records against the closest catalogue model by thresholds "
              "(median |log LMGC90/closest| per truth; the truths inside the catalogue against their own model beside)")
        for fraction in fractions:
            inside = [abs(r["log_err"]) for r in ok if abs(r["fraction"] - fraction) < 1e-9]
            per = {}
            for r in outside:
                if abs(r["fraction"] - fraction) < 1e-9:
                    per.setdefault(r["slug"], []).append(abs(r["log_err"]))
            misfit[str(fraction)] = {k: float(np.median(v)) for k, v in per.items()}
            q90 = float(np.quantile(inside, 0.9)) if inside else math.nan
            print(f"  at {fraction}: inside median {np.median(inside) if inside else math.nan:.2f} (90th percentile "
                  f"{q90:.2f}); outside: " + ", ".join(f"{k[:24]} {v:.2f}" for k, v in misfit[str(fraction)].items())
                  + f"; above the inside 90th percentile: {sum(v > q90 for v in misfit[str(fraction)].values())} of "
                  f"{len(per)}")
    by_fraction = {}
    for fraction in fractions:
        ev = evidence(rows, fraction)
        by_fraction[str(fraction)] = ev
        print(f"\nthe records at {fraction} of each threshold as evidence, own model against the closest rival "
              f"(sigma from the other truths' records):")
        for e in ev:
            print(f"  {e['slug'][:22]:22s} against {e['rival'][:40]:40s} {e['tests']:2d} tests  sigma {e['sigma']:.3f}  "
                  f"log LR (t3) {e['llr']:+7.1f}  (normal {e['llr_normal']:+8.1f})  P(own) {e['p_own']:.3f}")
        if ev:
            print(f"  favours the truth in {sum(e['llr'] > 0 for e in ev)} of {len(ev)} truths under the t "
                  f"({sum(e['llr_normal'] > 0 for e in ev)} under the normal law)")
    (out_dir / "crown_records.json").write_text(json.dumps({"fractions": fractions, "rows": rows,
                                                            "share_closer_own": share, "median_abs_log_err": med_err,
                                                            "median_abs_log_diff": med_diff,
                                                            "evidence": by_fraction, "outside_misfit": misfit},
                                                           indent=1))


if __name__ == "__main__":
    raise SystemExit(main())
