"""Early collapses: does a ramp fall below the threshold a search finds, and where?

Rocking is not monotone in amplitude. A laboratory's ramp, finer than the threshold search
(up by x 1.06 to the first collapse, then bisection), can fall in a narrow window of
collapse below the threshold the search finds, where the search stepped over: LMGC90 in the
laboratory loop fell on a W156 ramp at 3 Hz at 12.1 and 12.2 mm, stood from 12.3 to
14.9 mm and fell from 15.0 mm (truth t24; docs/diagnosis.md, "Early collapses").

The rule, on a scan (a pair run at every amplitude of a geometric grid of step `step`):
the search is played at each of its SEARCH_STEP phases (up by SEARCH_STEP grid steps to the
first collapse, bisection between it and the last stand), a ramp at each step of
RAMP_STEPS (3, 4.5 and 6 %) and each phase; a ramp is early against a search when its first
collapse lies below the search's threshold. `early_fractions` runs the kernel's nominal arch
over the same grid as bench/lmgc90/collapse_scan.py runs LMGC90's truths; `early_rule`
sorts LMGC90's scans by the kernel's (rough: the kernel's scan of the pair has an early
ramp) and gives each class's early rate and the depth of the early ones.
"""

from __future__ import annotations

import hashlib
import json
import math
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from voussoir_post.diagnosis.effects import Variant, arch_group
from voussoir_post.readers.campaign import Specimen
from voussoir_post.runner import Runner, code_hash

EARLY_QUANTILE = 0.95
SCAN_LO, SCAN_HI, SCAN_STEP = 0.7, 1.35, 0.015
SEARCH_STEP = 4  #: the search's scan step in grid steps (x 1.06 on a 1.5 % grid)
RAMP_STEPS = (2, 3, 4)  #: a laboratory ramp's step in grid steps (3, 4.5 and 6 %)


def scan_grid(lo: float = SCAN_LO, hi: float = SCAN_HI, step: float = SCAN_STEP) -> np.ndarray:
    """A scan's amplitudes over the reference threshold: from lo up to hi by the relative
    step (the kernel's scans and bench/lmgc90/collapse_scan.py's)."""
    n = int(math.floor(math.log(hi / lo) / math.log1p(step))) + 1
    return lo * (1.0 + step) ** np.arange(n)


def first_collapse(collapsed, phase: int, k: int) -> int | None:
    """Grid index of the first collapse of a ramp over every k-th amplitude from `phase`."""
    return next((i for i in range(phase, len(collapsed), k) if collapsed[i]), None)


def search_index(collapsed, phase: int, k: int = SEARCH_STEP) -> int | None:
    """Grid index of the threshold a search finds (up by k grid steps from `phase` to the
    first collapse, then bisection between it and the last stand); None when that first
    collapse has no stand below it in the scan."""
    hi = first_collapse(collapsed, phase, k)
    if hi is None or hi - k < 0:
        return None
    lo = hi - k
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if collapsed[mid] else (mid, hi)
    return hi


def early_depths(collapsed, step: float = SCAN_STEP, ramp_steps=RAMP_STEPS) -> tuple[int, list[float]]:
    """(number of (search, ramp) couples, log depths of the early ones) on one scan: every
    search phase against every ramp step at every phase; a ramp is early when its first
    collapse lies below the search's threshold, by (difference in grid steps) x
    log(1 + step). A scan whose first amplitude fell or whose last stood brackets nothing:
    (0, [])."""
    collapsed = list(collapsed)
    if not collapsed or collapsed[0] or not collapsed[-1]:
        return 0, []
    n, depths = 0, []
    for sp in range(SEARCH_STEP):
        found = search_index(collapsed, sp)
        if found is None:
            continue
        for k in ramp_steps:
            for phase in range(k):
                first = first_collapse(collapsed, phase, k)
                if first is None:
                    continue
                n += 1
                if first < found:
                    depths.append((found - first) * math.log1p(step))
    return n, depths


def early_fraction(collapsed) -> float | None:
    """The fraction of early (search, ramp) couples of a scan; None when it brackets nothing."""
    n, depths = early_depths(collapsed)
    return len(depths) / n if n else None


def early_fractions(spec: Specimen, frequencies: list[float], thresholds: list[float], cycles, settings,
                    cache: Path, work: Path) -> dict[float, dict]:
    """The kernel's scan of the nominal arch at each frequency (amplitudes scan_grid() x the
    given reference threshold there), cached in `cache` per specimen, frequency, cycles and
    executables: {frequency: {"collapsed": [...], "fraction": early_fraction}}."""
    code = code_hash(settings.bin_dir, ("voussoir-run",))
    grid = scan_grid()
    group = arch_group(spec, Variant())
    out, todo = {}, []
    for f, ref in zip(frequencies, thresholds):
        if not (ref > 0 and math.isfinite(ref)):
            continue
        key = hashlib.sha256(json.dumps([code, settings.dt_s, round(f, 6), list(cycles), f"{ref:.9g}",
                                         SCAN_LO, SCAN_HI, SCAN_STEP, group],
                                        sort_keys=True).encode()).hexdigest()[:16]
        path = Path(cache) / f"{spec.specimen_id}-{f:g}Hz-scan-{key}.json"
        if path.exists():
            out[f] = json.loads(path.read_text())
        else:
            todo.append((f, ref, path))
    if todo:
        runner = Runner(settings.bin_dir, Path(work))
        jobs = [(f"scan_{spec.specimen_id}_{f:g}_{i}", f, float(ref * x)) for f, ref, _ in todo for i, x in enumerate(grid)]

        def fell_at(job):
            name, f, amp = job
            return runner.collapses({"arch": group,
                                     "motion": {"waveform": "afd", "frequency_hz": f, "amplitude_m": amp,
                                                "n_attack": cycles[0], "n_full": cycles[1], "n_decay": cycles[2],
                                                "rest_s": 1.0},
                                     "solver": {"dt_s": settings.dt_s},
                                     "output": {"stop_after_collapse_s": 0.0}}, name)

        with ThreadPoolExecutor(max_workers=max(1, settings.n_ranks)) as pool:
            fell = list(pool.map(fell_at, jobs))
        for k, (f, ref, path) in enumerate(todo):
            collapsed = [bool(c) for c in fell[k * grid.size:(k + 1) * grid.size]]
            d = {"specimen_id": spec.specimen_id, "frequency_hz": f, "reference_m": ref,
                 "amplitudes_m": [float(ref * x) for x in grid], "collapsed": collapsed,
                 "fraction": early_fraction(collapsed)}
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(json.dumps(d) + "\n")
            out[f] = d
    return out


def early_rule(scan: dict, kernel: dict) -> dict:
    """The constants from a collapse_scan.py result and the kernel's early fraction of each
    (specimen, round(frequency, 6)) (None: its scan brackets nothing)."""
    classes = {"rough": [], "smooth": []}
    depths, unusable = [], 0
    for row in scan["rows"]:
        n, d = early_depths(row["collapsed"], scan["step"])
        if n == 0:
            unusable += 1
            continue
        k = kernel[(row["specimen_id"], round(row["frequency_hz"], 6))]
        classes["rough" if k else "smooth"].append(len(d) / n)
        depths += d
    every = classes["rough"] + classes["smooth"]
    return {"rough": float(np.mean(classes["rough"])), "smooth": float(np.mean(classes["smooth"])),
            "unknown": float(np.mean(every)), "span": float(np.quantile(depths, EARLY_QUANTILE)),
            "pairs": {c: len(v) for c, v in classes.items()},
            "with_early": {c: int(sum(x > 0 for x in v)) for c, v in classes.items()}, "unusable": unusable}
