"""Early collapses: where a ramp's first collapse may lie below the threshold a search finds.

Rocking is not monotone in amplitude. A laboratory's ramp, finer than the bank's threshold
search (up by x 1.06 to the first collapse, then bisection), can fall in a narrow window of
collapse below the threshold the search finds, where the search stepped over: LMGC90 in
the laboratory loop fell on a W156 ramp at 3 Hz at 12.1 and 12.2 mm, stood from 12.3 to
14.9 mm and fell from 15.0 mm (docs/diagnosis.md, "Early collapses").

The other way round too: where the search landed in a window, a ramp may step over it
and first fall a ramp step or more above the threshold the search found (late).

Whether a pair has such windows is a property of the arch at that frequency, and the
kernel sees it as the other code does: the kernel's nominal arch, run at every amplitude
from SCAN_LO to SCAN_HI times its threshold by steps of SCAN_STEP, has early ramps at W118
3 Hz, W132 2.5 Hz, W156 3 Hz and W118 4 Hz and none at the other six pairs of the test
arches, and LMGC90's scans of eight truths show early windows in 17 of the 28 scans of the
first pairs and 2 of the 40 of the others. So each pair's scan (`early_fractions`, cached
beside the bank) sorts it: rough where some ramp of the kernel's scan falls early, smooth
where none does. The likelihood (likelihood.py) reads a two-sided bracket as a ramp's
first collapse: early with probability EARLY_PROB_ROUGH or EARLY_PROB_SMOOTH by the pair's
class (EARLY_PROB_UNKNOWN, the pooled rate, for a bank without scans), anywhere up to
EARLY_SPAN (log) below the threshold; late with LATE_PROB_*, up to LATE_SPAN above. The
constants are the rule of `ramp_depths` on LMGC90's scans (bench/lmgc90/collapse_scan.py),
sorted by the kernel's: the rates of each class (each scan weighed alike) and the 95th
percentiles of the depths and heights, rounded up to a step of the likelihood's shift grid
(0.015: the likelihood reads a story's shift as whole columns of that grid;
tests/collapse_windows.py works them out again).

The rule, on a scan of grid step `step`: the search is played at each of its SEARCH_STEP
phases (up by SEARCH_STEP grid steps to the first collapse, bisection between it and the
last stand), a ramp at each step of RAMP_STEPS (3, 4.5 and 6 %) and each phase; a ramp is
early against a search when its first collapse lies below the search's threshold, late
when it lies a ramp step or more above it.
"""

from __future__ import annotations

import hashlib
import json
import math
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from ..readers.campaign import Specimen
from ..runner import Runner, code_hash
from .effects import Variant, arch_group

__all__ = ["EARLY_PROB_ROUGH", "EARLY_PROB_SMOOTH", "EARLY_PROB_UNKNOWN", "EARLY_SPAN", "LATE_PROB_ROUGH", "LATE_PROB_SMOOTH", "LATE_PROB_UNKNOWN", "LATE_SPAN", "SCAN_LO", "SCAN_HI",
           "SCAN_STEP", "SEARCH_STEP", "RAMP_STEPS", "scan_grid", "first_collapse", "search_index", "ramp_depths",
           "early_fraction", "early_fractions", "pair_early_prob", "early_key", "add_early_scans"]

#: P(a ramp's first collapse is early) at a pair whose kernel scan has early ramps, at one
#: whose scan has none, and without a scan (the pooled rate); EARLY_SPAN: how far below the
#: search's threshold an early collapse may lie (log), the 95th percentile of LMGC90's
#: (0.179) rounded up to a multiple of SPAN_STEP.
EARLY_PROB_ROUGH = 0.15
EARLY_PROB_SMOOTH = 0.01
EARLY_PROB_UNKNOWN = 0.07
EARLY_SPAN = 0.18
#: P(a ramp's first collapse is late: past a window the search found, by more than the
#: ramp's step) by the same classes, and how far above (log).
LATE_PROB_ROUGH = 0.07
LATE_PROB_SMOOTH = 0.01
LATE_PROB_UNKNOWN = 0.03
LATE_SPAN = 0.225  #: the 95th percentile (0.222) rounded up to a multiple of SPAN_STEP
#: The step the spans are rounded up to: that of likelihood.SHIFTS.
SPAN_STEP = 0.015
SCAN_LO, SCAN_HI, SCAN_STEP = 0.7, 1.35, 0.015
SEARCH_STEP = 4  #: the search's scan step in grid steps (x 1.06 on a 1.5 % grid)
RAMP_STEPS = (2, 3, 4)  #: a laboratory ramp's step in grid steps (3, 4.5 and 6 %)
EARLY_VERSION = 1  #: part of the scans' cache key


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


def ramp_depths(collapsed, step: float = SCAN_STEP, ramp_steps=RAMP_STEPS) -> tuple[int, list[float], list[float]]:
    """(number of (search, ramp) couples, log depths of the early ones, log heights of the
    late ones) on one scan: every search phase against every ramp step at every phase. A
    ramp is early when its first collapse lies below the search's threshold, late when it
    lies a ramp step or more above it (it stepped over a window the search found); depths
    and heights are (difference in grid steps) x log(1 + step). A scan whose first
    amplitude fell or whose last stood brackets nothing: (0, [], [])."""
    collapsed = list(collapsed)
    if not collapsed or collapsed[0] or not collapsed[-1]:
        return 0, [], []
    n, early, late = 0, [], []
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
                    early.append((found - first) * math.log1p(step))
                elif first >= found + k:
                    late.append((first - found) * math.log1p(step))
    return n, early, late


def early_fraction(collapsed) -> float | None:
    """The fraction of early (search, ramp) couples of a scan; None when it brackets nothing."""
    n, early, _ = ramp_depths(collapsed)
    return len(early) / n if n else None


def pair_early_prob(fraction: float | None) -> tuple[float, float]:
    """A pair's (early, late) probabilities from its kernel scan's early fraction (None: no
    scan)."""
    if fraction is None:
        return EARLY_PROB_UNKNOWN, LATE_PROB_UNKNOWN
    return (EARLY_PROB_ROUGH, LATE_PROB_ROUGH) if fraction > 0 else (EARLY_PROB_SMOOTH, LATE_PROB_SMOOTH)


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
        key = hashlib.sha256(json.dumps([EARLY_VERSION, code, settings.dt_s, round(f, 6), list(cycles), f"{ref:.9g}",
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


def early_key(specimen_id: str, frequency_hz: float) -> tuple[str, float]:
    """The key of a pair's scan in bank.early."""
    return specimen_id, round(frequency_hz, 6)


def add_early_scans(bank, obs, settings, cache: Path, work: Path) -> int:
    """Scan (or read from `cache`) every afd pair's nominal arch into bank.early; returns the
    number of pairs scanned or read."""
    n = 0
    for sid in obs.specimens:
        freqs = sorted({p.frequency_hz for p in obs.pairs if p.specimen_id == sid})
        sb = bank.specimens.get(sid)
        if not freqs or sb is None:
            continue
        found = early_fractions(obs.specimens[sid], freqs, [sb.threshold("nominal", f) for f in freqs],
                                obs.cycles[sid], settings, cache, Path(work) / sid)
        for f, d in found.items():
            bank.early[early_key(sid, f)] = d["fraction"]
            n += 1
    settings.log(f"[diagnose] early collapses: the kernel's fine scan of {n} pairs' nominal arch (cached in "
                 f"{cache}); early windows at " + (", ".join(f"{s} {f:g} Hz" for (s, f), x in bank.early.items()
                                                            if x) or "none"))
    return n
