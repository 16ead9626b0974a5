"""The early and late constants of diagnosis/early.py, worked out from LMGC90's fine
amplitude scans (bench/lmgc90/collapse_scan.py, stored) sorted by the kernel's own scans
of the same pairs.

Each LMGC90 scan is read by early.ramp_depths (the search at its phases against ramps of
3, 4.5 and 6 % at theirs). A pair is rough when the kernel's scan of its nominal arch has
an early ramp, smooth when it has none. Each class's early and late rates are the mean of
its scans' fractions (each scan weighed alike), the unknown rates those of every scan, and
the spans the EARLY_QUANTILE of every early depth and every late height (log).
"""

from __future__ import annotations

import numpy as np

from voussoir_post.diagnosis.early import early_key, ramp_depths

EARLY_QUANTILE = 0.95


def early_rule(scan: dict, kernel: dict) -> dict:
    """The constants from a collapse_scan.py result and the kernel's early fraction of each
    pair, keyed by early.early_key (None: its scan brackets nothing)."""
    classes = {"rough": [], "smooth": []}
    depths, heights, unusable = [], [], 0
    for row in scan["rows"]:
        n, early, late = ramp_depths(row["collapsed"], scan["step"])
        if n == 0:
            unusable += 1
            continue
        k = kernel[early_key(row["specimen_id"], row["frequency_hz"])]
        classes["rough" if k else "smooth"].append((len(early) / n, len(late) / n))
        depths += early
        heights += late
    mean = {c: np.mean(v, axis=0) for c, v in classes.items()}
    every = np.mean(classes["rough"] + classes["smooth"], axis=0)
    return {"early": {"rough": float(mean["rough"][0]), "smooth": float(mean["smooth"][0]), "unknown": float(every[0])},
            "late": {"rough": float(mean["rough"][1]), "smooth": float(mean["smooth"][1]), "unknown": float(every[1])},
            "early_span": float(np.quantile(depths, EARLY_QUANTILE)),
            "late_span": float(np.quantile(heights, EARLY_QUANTILE)),
            "pairs": {c: len(v) for c, v in classes.items()},
            "with_early": {c: int(sum(e > 0 for e, _ in v)) for c, v in classes.items()}, "unusable": unusable}
