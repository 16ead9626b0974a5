"""The diagnosis's long batches say how far they are: the threshold searches of the bank
(and the single runs) log done of total, the time elapsed and an estimate of the time
left, through settings.log, at most every PROGRESS_EVERY_S. A runner that answers at
once and a clock that the test moves stand in for voussoir-sweep and the time: what is
checked is the counting, the estimate and the pace of the lines, not a simulation."""

from __future__ import annotations

import re
from pathlib import Path
from types import SimpleNamespace

import pytest

from voussoir_post.diagnosis import simulator
from voussoir_post.diagnosis.effects import Variant
from voussoir_post.diagnosis.settings import DiagnosisSettings
from voussoir_post.readers.campaign import Specimen

SPEC = Specimen("A156", 156.0, 13, 0.508, 0.071, 0.145, 700.0)
FREQS = [1.25, 2.5]
COST_S = 4.0  #: simulated time of one search


class Clock:
    def __init__(self):
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


class FakeRunner:
    """run_sweep as the Runner's: (result, rows), one row per parameter set and frequency;
    each search costs COST_S on the clock, none when the sweep is `cached`."""

    def __init__(self, clock: Clock, cached: set[int] = frozenset()):
        self.clock, self.cached, self.reused, self.calls = clock, cached, 0, 0

    def run_sweep(self, groups, name):
        self.calls += 1
        sweep = groups["sweep"]
        n_sets = len(sweep.get("friction_list", sweep.get("contact_inset_list_m", [None])))
        if self.calls in self.cached:
            self.reused += 1
        else:
            self.clock.now += COST_S * n_sets * len(sweep["frequencies_hz"])
        rows = [{"param_set": str(p), "frequency_hz": str(f), "threshold_m": "0.05"}
                for p in range(n_sets) for f in sweep["frequencies_hz"]]
        return SimpleNamespace(code_version="test"), rows


def _simulator(tmp_path, lines, cached=frozenset()):
    sim = simulator.Simulator(DiagnosisSettings(bin_dir=Path(tmp_path), log=lines.append), tmp_path)
    clock = Clock()
    sim.runner, sim.clock = FakeRunner(clock, cached), clock
    return sim


#: 12 one-value sweeps (geometry) and one of two frictions: 14 models, 28 searches.
VARIANTS = ([Variant("geometry", 0.80 + 0.02 * k) for k in range(12)]
            + [Variant("friction", 0.4), Variant("friction", 0.5)])
LINE = re.compile(r"\[thresholds\] A156: searches: (\d+) of 28 \((\d+) of 13 sweeps\), (.+) elapsed, about (.+) left$")


def _seconds(words: str) -> float:
    parts = dict((unit, int(value)) for value, unit in re.findall(r"(\d+) (h|min|s)", words))
    return 3600 * parts.get("h", 0) + 60 * parts.get("min", 0) + parts.get("s", 0)


def test_the_searches_log_done_of_total_elapsed_and_time_left(tmp_path):
    lines = []
    sim = _simulator(tmp_path, lines)
    found = sim.thresholds_at(SPEC, FREQS, (1, 1, 1), VARIANTS, 0.5, 0.001)
    assert len(found) == 28
    parsed = [LINE.match(line) for line in lines]
    assert parsed and all(parsed), lines
    previous_elapsed = -simulator.PROGRESS_EVERY_S
    for m in parsed:
        done, elapsed, left = int(m[1]), _seconds(m[3]), _seconds(m[4])
        assert elapsed == COST_S * done  # every search costs the same here
        assert left == COST_S * (28 - done)  # so the estimate is exact
        assert elapsed - previous_elapsed >= simulator.PROGRESS_EVERY_S  # at most every 10 s
        previous_elapsed = elapsed
    # 8 s a sweep of one model, 16 s the last of two: a line every second sweep (16 s), not one per sweep
    assert len(lines) == 7


def test_cached_sweeps_do_not_count_in_the_rate(tmp_path):
    """The first six sweeps come from the cache (no time): the time left is estimated on
    the searches simulated, not on all those done."""
    lines = []
    sim = _simulator(tmp_path, lines, cached=set(range(1, 7)))
    sim.thresholds_at(SPEC, FREQS, (1, 1, 1), VARIANTS, 0.5, 0.001)
    for m in map(LINE.match, lines):
        done, elapsed, left = int(m[1]), _seconds(m[3]), _seconds(m[4])
        simulated = done - 12
        assert elapsed == COST_S * simulated and left == pytest.approx(COST_S * (28 - done), abs=1)


def test_durations_in_words():
    assert simulator.duration_words(45.2) == "45 s"
    assert simulator.duration_words(185) == "3 min 05 s"
    assert simulator.duration_words(3720) == "1 h 02 min"


def test_the_single_runs_log_their_progress(tmp_path):
    """run_tests (voussoir-run, in parallel threads): done of total, at most every 10 s."""
    from voussoir_post.readers.campaign import Test as CampaignTest

    lines = []
    sim = _simulator(tmp_path, lines)
    lock = __import__("threading").Lock()

    def run_single(groups, name, keep=True):
        with lock:
            sim.clock.now += 6.0
        return SimpleNamespace(collapsed=False, collapse_time_s=float("nan"), hinge_time_s=[], hinge_joint=[],
                               hinge_side=[], hinge_side_names=[], time_s=[0.0], crown_dx_m=[0.0], crown_dy_m=[0.0])

    sim.runner.run_single = run_single
    test = CampaignTest("T1", "A156", "afd", "stand", 1.25, 0.02)
    assert len(sim.run_tests([(SPEC, test, Variant(), {})] * 10)) == 10
    counts = [int(re.match(r"\[runs\] single tests: (\d+) of 10, ", line)[1]) for line in lines]
    assert counts and counts == sorted(counts) and counts[-1] <= 10
    assert len(lines) <= 60.0 // simulator.PROGRESS_EVERY_S  # 10 runs of 6 s: at most one line per 10 s
