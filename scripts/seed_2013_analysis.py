#!/usr/bin/env python3
"""The seed paper's campaign (shared/data/seed_2013) through the diagnosis, and what the
model says about the 180-degree arch and its brackets. Writes docs/seed_2013/.

    .venv/bin/python scripts/seed_2013_analysis.py [--np 2]

Steps: (1) voussoir-diagnose run on the campaign as it is (the diagnosis is told nothing
of the brackets: the campaign format has no place for them); (2) with what the paper
says beside the data, the 180-degree arch with its brackets (restrained springings) and
contact insets fitted on the three arches that had none; (3) a side-by-side with the
paper's own LMGC90 results, uncalibrated and calibrated (thickness x 0.82).
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "postproc"))

from voussoir_post.campaign import measured_thresholds, read_campaign  # noqa: E402
from voussoir_post.diagnosis import DiagnosisSettings, diagnose  # noqa: E402
from voussoir_post.runner import Runner  # noqa: E402

SEED = ROOT.parent / "shared" / "data" / "seed_2013"
OUT = ROOT / "docs" / "seed_2013"


def sweep_thresholds(spec, frequency_hz: float, inset_list_m: list[float], restrained: str, thickness_m: float,
                     work: Path, name: str, n_ranks: int, bin_dir: Path) -> list[float]:
    """Threshold [m] of one specimen at one frequency for each inset, by voussoir-sweep."""
    groups = {"arch": {"embrace_deg": float(spec.embrace_deg), "n_voussoirs": spec.n_voussoirs,
                       "r_ext_m": float(spec.r_ext_m), "thickness_m": float(thickness_m),
                       "width_m": float(spec.width_m), "density_kg_m3": float(spec.density_kg_m3),
                       "friction": float(spec.friction), "restrained_springings": restrained},
              "motion": {"waveform": "afd", "n_attack": 1, "n_full": 1, "n_decay": 1, "rest_s": 1.0},
              "solver": {"allow_nonconvergence": True},
              "sweep": {"mode": "threshold", "frequencies_hz": float(frequency_hz), "amp_tol_m": 2.5e-4,
                        "amp_max_m": 0.5, "progress_every_s": 1.0e9,
                        "contact_inset_list_m": [float(x) for x in inset_list_m]}}
    _, rows = Runner(bin_dir, work, n_ranks=n_ranks).run_sweep(groups, name, reuse=False)
    rows.sort(key=lambda r: int(r["param_set"]))
    return [float(r["threshold_m"]) for r in rows]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--np", type=int, default=2)
    parser.add_argument("--bin-dir", default=str(ROOT / "build" / "drivers"))
    args = parser.parse_args()
    bin_dir = Path(args.bin_dir).resolve()
    if OUT.exists():
        shutil.rmtree(OUT)
    OUT.mkdir(parents=True)
    work = Path(os.environ.get("TMPDIR", "/tmp")) / "voussoir_seed_2013"
    work.mkdir(parents=True, exist_ok=True)

    # (1) The diagnosis, told nothing.
    result = diagnose(SEED, OUT, DiagnosisSettings(bin_dir=bin_dir, n_ranks=args.np))
    shutil.rmtree(OUT / "work", ignore_errors=True)

    # (2) The brackets of the 180-degree arch, and insets fitted on the others.
    campaign = read_campaign(SEED)
    measured = {m.specimen_id: m for m in measured_thresholds(campaign)}
    insets = [0.0, 0.001, 0.002, 0.003, 0.004, 0.005, 0.006, 0.008, 0.010, 0.012]
    curves = {}
    for sid, spec in campaign.specimens.items():
        m = measured[sid]
        restrained = "both" if sid == "A180" else "none"
        curves[sid] = sweep_thresholds(spec, m.frequency_hz, insets, restrained, spec.thickness_m, work,
                                       f"seed_{sid}_{restrained}", args.np, bin_dir)
    a180 = campaign.specimens["A180"]
    free180 = sweep_thresholds(a180, measured["A180"].frequency_hz, insets, "none", a180.thickness_m, work,
                               "seed_A180_free", args.np, bin_dir)

    def interp(curve, e):
        import numpy as np
        return float(np.interp(e, insets, curve))

    def inset_for(sid):  # the inset that reproduces a specimen's measured threshold
        import numpy as np
        c = np.array(curves[sid])
        target = measured[sid].threshold_m
        grid = np.linspace(0, insets[-1], 1201)
        vals = np.interp(grid, insets, c)
        return float(grid[np.argmin(abs(vals - target))])

    per_specimen = {sid: inset_for(sid) for sid in campaign.specimens}
    clean = ["A156", "A132", "A118"]
    import numpy as np
    grid = np.linspace(0, insets[-1], 1201)
    err = [np.mean([abs(interp(curves[s], e) - measured[s].threshold_m) / measured[s].threshold_m for s in clean])
           for e in grid]
    e_clean = float(grid[int(np.argmin(err))])

    # (3) Side by side with the paper.
    paper = {}
    with open(SEED / "paper_dem_results.csv") as fh:
        for r in csv.DictReader(line for line in fh if not line.startswith("#")):
            paper[(r["specimen_id"], r["model"])] = r
    rows = []
    for sid in campaign.specimens:
        m = measured[sid]
        t = campaign.tests[m.test_ids[0]]
        nominal = curves[sid][0] if sid != "A180" else free180[0]
        rows.append({
            "specimen": sid, "frequency_hz": m.frequency_hz, "measured_mm": 1e3 * m.threshold_m,
            "measured_peak_accel_m_s2": t.peak_accel_m_s2,
            "paper_uncalibrated_mm": float(paper[(sid, "uncalibrated")]["amplitude_m"]) * 1e3,
            "paper_uncalibrated_hz": float(paper[(sid, "uncalibrated")]["frequency_hz"]),
            "paper_calibrated_mm": float(paper[(sid, "calibrated")]["amplitude_m"]) * 1e3,
            "paper_calibrated_hz": float(paper[(sid, "calibrated")]["frequency_hz"]),
            "voussoir_nominal_mm": 1e3 * nominal,
            "voussoir_brackets_mm": 1e3 * curves["A180"][0] if sid == "A180" else None,
            "voussoir_inset_fitted_on_others_mm": 1e3 * (interp(curves[sid], e_clean)),
            "inset_reproducing_this_arch_mm": 1e3 * per_specimen[sid],
        })
    summary = {"diagnosis_verdict": result["verdict"], "inset_fitted_on_A156_A132_A118_m": e_clean,
               "inset_per_specimen_m": per_specimen, "a180_free_thresholds_m": dict(zip(insets, free180)),
               "a180_bracket_thresholds_m": dict(zip(insets, curves["A180"])), "rows": rows}
    (OUT / "analysis.json").write_text(json.dumps(summary, indent=2) + "\n")
    for r in rows:
        print(r)
    print(f"inset fitted on A156, A132, A118: {1e3 * e_clean:.1f} mm")
    return 0


if __name__ == "__main__":
    sys.exit(main())
