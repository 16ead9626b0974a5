#!/usr/bin/env python3
"""The seed paper's campaign (data/seed_2013) through the diagnosis, as it is
declared (A180's brackets; A180 and A118 with an uncertain set-up), and the paper's own
LMGC90 errors beside it. Writes docs/seed_2013/.

    .venv/bin/python scripts/seed_2013_analysis.py [--np 2]

Nothing is analysed by hand here: the diagnosis's report.md and diagnosis.json are the
result; paper_comparison.json adds only the paper's published thresholds (Table 2, read
from data/seed_2013/paper_dem_results.csv) against the measured ones.
"""

from __future__ import annotations

import argparse
import csv
import json
import shutil
import sys
from pathlib import Path
from typing import Callable, TypeVar

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "postproc"))

from voussoir_post.readers.campaign import measured_thresholds, read_campaign  # noqa: E402
from voussoir_post.diagnosis.pipeline import DiagnosisSettings, diagnose  # noqa: E402

SEED = ROOT / "data" / "seed_2013"
OUT = ROOT / "docs" / "seed_2013"
STAGING = ROOT / "build" / "seed_2013.new"  #: where the output is made before it replaces OUT
T = TypeVar("T")


def paper_comparison() -> list[dict]:
    """Measured thresholds against the paper's LMGC90 columns, where the paper's
    frequency is the test's."""
    campaign = read_campaign(SEED)
    measured = {m.specimen_id: m for m in measured_thresholds(campaign)}
    rows = []
    with open(SEED / "paper_dem_results.csv") as fh:
        for r in csv.DictReader(line for line in fh if not line.startswith("#")):
            m = measured[r["specimen_id"]]
            same_frequency = abs(float(r["frequency_hz"]) - m.frequency_hz) < 1e-9
            rows.append({"specimen": r["specimen_id"], "model": r["model"], "frequency_hz": float(r["frequency_hz"]),
                         "paper_threshold_m": float(r["amplitude_m"]), "measured_threshold_m": m.threshold_m,
                         "error_pct": (100 * (float(r["amplitude_m"]) - m.threshold_m) / m.threshold_m
                                       if same_frequency else None)})
    return rows


def write_output(out: Path, settings: DiagnosisSettings, rows: list[dict]) -> dict:
    """The diagnosis of the seed campaign and the paper's comparison, written into ``out``."""
    result = diagnose(SEED, out, settings)
    shutil.rmtree(out / "work", ignore_errors=True)
    (out / "paper_comparison.json").write_text(json.dumps(rows, indent=2) + "\n")
    return result


def replace_when_made(out: Path, staging: Path, make: Callable[[Path], T]) -> T:
    """``make(staging)`` writes the output into a fresh folder ``staging`` (untracked, under
    build/), which then takes the place of ``out``. While the figures are drawn the tracked
    files of ``out`` are as committed, so the stamp of each figure (plots/drawing.py,
    save_png: the commit, and 'modified' when a tracked file differs from it) tells the state
    of the code that drew it, not that of the folder being written: deleting ``out`` first
    made every figure read 'modified tree'. A failed ``make`` leaves ``out`` as it was.
    Returns what ``make`` returns."""
    if staging.exists():
        shutil.rmtree(staging)
    staging.mkdir(parents=True)
    made = make(staging)
    if out.exists():
        shutil.rmtree(out)
    shutil.move(str(staging), str(out))
    return made


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--np", type=int, default=2)
    parser.add_argument("--bin-dir", default=str(ROOT / "build" / "drivers"))
    args = parser.parse_args()
    # The simulation bank is cached under build/ (not beside docs/): a rerun simulates nothing.
    settings = DiagnosisSettings(bin_dir=Path(args.bin_dir).resolve(), n_ranks=args.np,
                                 bank_dir=ROOT / "build" / "voussoir-bank")
    rows = paper_comparison()
    result = replace_when_made(OUT, STAGING, lambda out: write_output(out, settings, rows))
    print(f"verdict: {result['verdict']}; rivals {result['rivals']}; next test {result['next_test']}")
    print("probabilities: " + ", ".join(f"{m} {p:.3f}" for m, p in sorted(result["probabilities"].items(),
                                                                          key=lambda kv: -kv[1]) if p >= 0.005))
    for r in rows:
        err = "-" if r["error_pct"] is None else f"{r['error_pct']:+.1f} %"
        print(f"{r['specimen']} {r['model']:>12} {r['frequency_hz']:.2f} Hz: {1e3 * r['paper_threshold_m']:.0f} mm "
              f"vs measured {1e3 * r['measured_threshold_m']:.0f} mm ({err})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
