"""The diagnosis's simulations, through the project's one runner: thresholds of every
variant by voussoir-sweep (the bank's ceiling and tolerance, never the data's), single
tests (hinges, crown records) by voussoir-run. Simulations are never re-implemented
here. A batch of searches or runs that lasts prints its progress through settings.log, at
most every PROGRESS_EVERY_S: done of total, time elapsed and an estimate of the time left
(the sweeps' own progress lines are off: the runner keeps their output)."""

from __future__ import annotations

import hashlib
import json
import math
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from ..readers.campaign import Specimen, Test
from ..earthquake.ida import played_record, read_ida
from ..runner import Runner, code_hash
from .crown import peak_m
from .effects import Variant, arch_group, effect
from .settings import DiagnosisSettings

__all__ = ["Simulator", "FALLEN_PEAK_M", "HINGE_GAP_M", "PROGRESS_EVERY_S", "duration_words"]

#: Opening of a joint's other edge at which a hinge counts as open: 1 mm, as a
#: laboratory sees it (and as the test generator counts it).
HINGE_GAP_M = 1.0e-3
#: Least time [s] between two progress lines of a batch.
PROGRESS_EVERY_S = 10.0
#: What a single run that fell is taken to have shown at the crown: a displacement of the
#: size of the arch's collapse (the far tail of the crown records' law, not a reason to
#: drop the run).
FALLEN_PEAK_M = 0.1


def duration_words(seconds: float) -> str:
    """'45 s', '3 min 05 s', '1 h 02 min'."""
    s = int(round(max(seconds, 0.0)))
    if s < 60:
        return f"{s} s"
    if s < 3600:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s // 3600} h {s % 3600 // 60:02d} min"


class _Progress:
    """Items (searches, runs) done of a batch, logged with the time elapsed and the time
    left at the rate of the items simulated so far (items found in the cache cost
    nothing and do not count in the rate), at most every PROGRESS_EVERY_S."""

    def __init__(self, log, what: str, total: int, clock):
        self.log, self.what, self.total, self.clock = log, what, total, clock
        self.done = self.simulated = 0
        self.start = self.last = clock()
        self.lock = threading.Lock()

    def advance(self, n: int, simulated: bool = True, detail: str = "") -> None:
        with self.lock:
            self.done += n
            self.simulated += n if simulated else 0
            now = self.clock()
            if now - self.last < PROGRESS_EVERY_S:
                return
            self.last = now
            elapsed = now - self.start
            left = (f"about {duration_words(elapsed / self.simulated * (self.total - self.done))} left"
                    if self.simulated else "no estimate yet")
            self.log(f"{self.what}: {self.done} of {self.total}{detail}, {duration_words(elapsed)} elapsed, {left}")


class Simulator:
    """Runs the Fortran executables for the diagnosis, in a work folder."""

    def __init__(self, settings: DiagnosisSettings, work_dir: Path):
        self.s = settings
        self.runner = Runner(settings.bin_dir, work_dir, n_ranks=settings.n_ranks)
        self.n_sweeps = 0
        self.n_runs = 0
        self.code_version = ""  #: of the executables, from the first sweep file
        self._count = 0
        self.clock = time.monotonic  #: of the progress lines

    def _solver(self) -> dict:
        return {"dt_s": float(self.s.dt_s), "allow_nonconvergence": True}

    def thresholds_at(self, spec: Specimen, freqs: list[float], cycles: tuple[int, int, int],
                      variants: list[Variant], amp_max: float, amp_tol: float) -> dict[tuple[Variant, float], float]:
        """Simulated threshold [m] of every (variant, frequency), searched up to `amp_max`
        to `amp_tol` [m]."""
        out: dict[tuple[Variant, float], float] = {}
        freqs = sorted(freqs)
        # Variants whose first effect has a &sweep list go in one sweep per value of the
        # rest (the fixed part, in the &arch group); every other variant is a sweep.
        groups: dict[tuple, list[Variant]] = {}
        for v in variants:
            parts = v.parts()
            # The listed part goes first: a pair with one listed effect is one sweep per
            # value of the other.
            listed_first = sorted(parts, key=lambda part: effect(part[0]).sweep_list is None)
            listed = bool(parts) and effect(listed_first[0][0]).sweep_list is not None
            key = (listed_first[0][0], tuple(listed_first[1:])) if listed else ("single", v)
            groups.setdefault(key, []).append(v)
        progress = _Progress(self.s.log, f"[thresholds] {spec.specimen_id}: searches", len(variants) * len(freqs),
                             self.clock)
        for n_sweep, (key, vs) in enumerate(groups.items(), start=1):
            self._count += 1
            name = f"sweep_{self._count:03d}_{spec.specimen_id}"
            sweep = {"mode": "threshold", "frequencies_hz": [float(f) for f in freqs], "amp_tol_m": float(amp_tol),
                     "amp_max_m": float(amp_max), "scan_step": float(self.s.scan_step),
                     "progress_every_s": 1.0e9}
            listed = key[0] != "single"
            if listed:
                base = Variant(*key[1][0]) if key[1] else Variant()
                sweep[effect(key[0]).sweep_list] = [float(dict(v.parts())[key[0]]) for v in vs]
            else:
                base = vs[0]
            groups_nml = {"arch": arch_group(spec, base),
                          "motion": {"waveform": "afd", "n_attack": cycles[0], "n_full": cycles[1],
                                     "n_decay": cycles[2], "rest_s": 1.0},
                          "solver": self._solver(), "output": {}, "sweep": sweep}
            before = self.runner.reused
            result, rows = self.runner.run_sweep(groups_nml, name)
            if self.runner.reused == before:
                self.n_sweeps += 1
            progress.advance(len(vs) * len(freqs), simulated=self.runner.reused == before,
                             detail=f" ({n_sweep} of {len(groups)} sweeps)")
            if not self.code_version:
                self.code_version = result.code_version
            for row in rows:
                v = vs[int(row["param_set"])] if listed else vs[0]
                f = min(freqs, key=lambda x: abs(x - float(row["frequency_hz"])))
                text = row["threshold_m"].strip()
                out[(v, f)] = math.nan if text in ("", "nan", "NaN") else float(text)
        return out

    def record_thresholds(self, spec: Specimen, record: Path, variants: list[Variant], lead_s: float, rest_s: float,
                          scale_max: float = 20.0, scale_tol: float = 0.01) -> dict[Variant, tuple[float, float]]:
        """Each variant's collapse scale of an accelerogram (CSV t_s, accel_m_s2) as given and
        reversed, by the kernel's IDA sweep (`record_polarity = 'both'`), to `scale_tol`;
        inf where it stood at `scale_max`. One sweep a variant."""
        out = {}
        progress = _Progress(self.s.log, f"[pulse] {spec.specimen_id}: searches both ways", len(variants), self.clock)
        for v in variants:
            groups = {"arch": arch_group(spec, v), "motion": {"lead_s": float(lead_s), "rest_s": float(rest_s)},
                      "solver": self._solver(), "output": {},
                      "sweep": {"mode": "ida", "record_files": [str(record)], "record_polarity": "both",
                                "scale_max": float(scale_max), "scale_tol": float(scale_tol),
                                "scan_step": float(self.s.scan_step), "progress_every_s": 1.0e9}}
            before = self.runner.reused
            # Named by its input: another batch in the same folder never meets a sweep of other content.
            name = hashlib.sha256(json.dumps(groups, sort_keys=True, default=str).encode()).hexdigest()[:12]
            ida = read_ida(self.runner.run_sweep_file(groups, f"ida_{spec.specimen_id}_{name}"))
            if self.runner.reused == before:
                self.n_sweeps += 1
            found = {played_record(rec).polarity: math.inf if censored else float(scale)
                     for rec, scale, censored in zip(ida.record, ida.scale_threshold, ida.censored)}
            out[v] = (found[1], found[-1])
            progress.advance(1)
        return out

    def run_tests(self, jobs: list[tuple[Specimen, Test, Variant, dict]]) -> list[dict]:
        """Simulate single tests as they were run (voussoir-run, in parallel). Each job's
        dict may add &motion settings (e.g. the table gain and delay). Returns for each
        job: collapsed, collapse_time_s, hinges {(joint, side)}, and the crown time series."""
        self._count += 1
        batch = self._count
        progress = _Progress(self.s.log, "[runs] single tests", len(jobs), self.clock)

        def one(k_job):
            k, (spec, test, variant, motion) = k_job
            groups = {"arch": arch_group(spec, variant),
                      "motion": {"waveform": "afd", "frequency_hz": float(test.frequency_hz),
                                 "amplitude_m": float(test.amplitude_m), "n_attack": test.n_attack,
                                 "n_full": test.n_full, "n_decay": test.n_decay, "rest_s": 1.0,
                                 **{key: float(val) for key, val in motion.items()}},
                      "solver": self._solver(),
                      "output": {"every": max(1, round(0.005 / self.s.dt_s)), "stop_after_collapse_s": 0.3,
                                 "hinge_gap_m": HINGE_GAP_M}}
            r = self.runner.run_single(groups, f"run_{batch:03d}_{k:04d}", keep=False)
            progress.advance(1)
            return {"collapsed": r.collapsed, "collapse_time_s": r.collapse_time_s,
                    # One window for the model and the laboratory: hinges up to the collapse.
                    "hinges": {(int(j), r.hinge_side_names[int(s)])
                               for t, j, s in zip(r.hinge_time_s, r.hinge_joint, r.hinge_side)
                               if not r.collapsed or t <= r.collapse_time_s},
                    "t_s": r.time_s, "crown_dx_m": r.crown_dx_m, "crown_dy_m": r.crown_dy_m}

        with ThreadPoolExecutor(max_workers=max(1, self.s.n_ranks)) as pool:
            results = list(pool.map(one, enumerate(jobs)))
        self.n_runs += len(jobs)
        return results

    def peaks(self, jobs: list[tuple[Specimen, Test, Variant, dict]], cache: Path | None = None) -> list[float]:
        """The peak |crown dx| [m] of each single test (FALLEN_PEAK_M where it fell), for the
        crown records' likelihood and the tests held for them. With `cache` (a folder), each
        run's result is kept there under the hash of its input and the executables, so a
        second diagnosis runs none of them again."""
        keys = [hashlib.sha256(json.dumps([self.code_hash(), self.s.dt_s, arch_group(spec, v), test.frequency_hz,
                                           test.amplitude_m, test.n_attack, test.n_full, test.n_decay,
                                           sorted(motion.items())], sort_keys=True, default=str).encode()
                                ).hexdigest()[:20] for spec, test, v, motion in jobs]
        found = {}
        if cache is not None:
            for k in set(keys):
                path = Path(cache) / f"{k}.json"
                if path.exists():
                    found[k] = json.loads(path.read_text())["peak_m"]
        todo = [(k, job) for k, job in zip(keys, jobs) if k not in found]
        todo = list({k: job for k, job in todo}.items())
        for (k, _), r in zip(todo, self.run_tests([job for _, job in todo]) if todo else []):
            found[k] = FALLEN_PEAK_M if r["collapsed"] else peak_m(r["crown_dx_m"])
            if cache is not None:
                Path(cache).mkdir(parents=True, exist_ok=True)
                (Path(cache) / f"{k}.json").write_text(json.dumps({"peak_m": found[k]}) + "\n")
        return [found[k] for k in keys]

    def code_hash(self) -> str:
        """The executables' hash (voussoir-run's), for the single runs' cache."""
        if not hasattr(self, "_code_hash"):
            self._code_hash = code_hash(self.s.bin_dir, ("voussoir-run",))
        return self._code_hash
