"""The laboratory loop against another code (issue 35 item 4; a bench, never run by CI).

LMGC90 is the laboratory. For each stored LMGC90 truth inside the catalogue
(postproc/tests/data/lmgc90, made by truths.py), the loop starts from the truth's
campaign replayed with a laboratory's faults (lmgc90_campaigns.draw_campaign), writes it
as a campaign folder (docs/measured_data.md: specimens.csv, tests.csv, table.csv, a table
record per test) and then, up to MAX_TESTS times:

1. diagnoses it (pipeline.diagnose, the `voussoir-diagnose run` pipeline) with one bank
   folder shared by every truth, design and step, so the bank grows test by test;
2. chooses the next test: `advised` reads diagnosis.json's next_test (specimen,
   frequency, an afd ramp from/to/by, or an afd test held at one amplitude with the crown
   recorded, kind hold_crown; DiagnosisSettings.crown_records on: the records weighed);
   `ramps` the same advice with held tests left out (crown_records off, the default of
   voussoir-diagnose; its own step 0); `recorded` is `advised` with the crown recorded
   in every test, as a laboratory with a crown transducer has it (a ramp's stands near
   the threshold then bring their records too); `naive` takes the next frequency up (of
   DiagnosisSettings.probe_frequencies_hz, not yet tested) on the specimen of the most
   recent test, within the table's limits, else a seeded random untested (specimen,
   frequency), ramped as the laboratory ramps (lmgc90_campaigns.LabFaults: a start of
   0.5 to 0.9 times the nominal onset, steps of 1 to 5 mm);
3. runs it in LMGC90 on the same hidden truth (the truth's parameters and its specimens'
   build faults; truths.Lmgc90Specimen, one subprocess per run): the ramp's amplitudes
   one after the other until the first collapse (past the advised `to` by the same step
   while within the table's limits; when the first amplitude already falls, down by the
   step until it stands, at most 10 tests), each run with the laboratory's faults of
   the campaign (each test's table gain scattered by 1 %, the campaign-wide offset, the
   transducer's bias on the measured gain, as draw_campaign draws them);
   A held test is one LMGC90 run at that amplitude (with the same faults), its crown
   recorded as a transducer gives it (truth_case.py, relative to the table, with 0.05 mm
   of noise; in `recorded`, every test's);
4. appends the rows and their table records (and a held test's crown record) to the
   campaign folder, and diagnoses again.

It stops early when a cause (or `none`) is named at 0.9 or more. The step 0 diagnosis
(the replayed campaign) is shared by the designs that weigh the same evidence. After each diagnosis the loop asserts
that the bank gained at most the file of the (specimen, frequency) pair just tested,
counts its threshold searches, and that every advised ramp is within the table's limits.

Resumable: one JSON per truth and design in OUT/results (finished ones are skipped; an
unfinished one goes on from its last finished step). Run with the project's Python and
PYTHONPATH at postproc (loop.sh does that):

    python bench/lmgc90/loop.py --lmgc90-build DIR --out OUT [--truths N | --slugs S1,S2] \
        [--designs advised,ramps,recorded,naive]
    python bench/lmgc90/loop.py --out OUT --summary      # the table of what is finished

The summary also labels each truth as the calibration does (lmgc90_campaigns.truth_model
with the bank and the campaign at step 0 and at the last step: an effect that moves none
of the tested thresholds by its material threshold is no cause), beside the generator's
label.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import os
import shutil
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path.insert(0, str(ROOT / "postproc"))
sys.path.insert(0, str(ROOT / "postproc" / "tests"))
sys.path.insert(0, str(HERE))

from independent_campaigns import ARCHES  # noqa: E402
from lmgc90_campaigns import SNAP_M, LabFaults, draw_campaign, stored_truths, truth_model  # noqa: E402
from voussoir_post.diagnosis.bank import build_bank  # noqa: E402
from voussoir_post.diagnosis.observations import from_campaign  # noqa: E402
from truths import Lmgc90Specimen, actuator_gain, onset_m  # noqa: E402
from voussoir_post.analysis.afd import afd_command  # noqa: E402
from voussoir_post.diagnosis import pipeline  # noqa: E402
from voussoir_post.diagnosis.next_test import within_limits  # noqa: E402
from voussoir_post.diagnosis.pulses import LEAD_S as PULSE_LEAD_S, reach_m, unit_pulse  # noqa: E402
from voussoir_post.diagnosis.settings import DiagnosisSettings  # noqa: E402
from voussoir_post.readers.campaign import read_campaign  # noqa: E402

MAX_TESTS = 3
NAMED_AT = 0.9
CONFIDENT_AGAINST = 0.01  #: a final P(truth) at or below this is confidently against the truth
SEED = 35
FAULTS = LabFaults()
#: ramps: the advice without tests held for the crown; recorded: the crown recorded in every test
DESIGNS = ("advised", "naive", "ramps", "recorded")
RECORD_HZ = 200.0
CROWN_NOISE_M = 5.0e-5   #: a displacement transducer's noise on the crown record
STEP_DOWN_MAX = 10
ARCH = {a.specimen_id: a for a in ARCHES}


def log(msg: str) -> None:
    print(f"{time.strftime('%H:%M:%S')} {msg}", flush=True)


# ---------------------------------------------------------------- the campaign folder


def replayed_tests(truth: dict, seed: int) -> tuple[list[dict], dict]:
    """The tests of the truth's campaign replayed with a laboratory's faults
    (draw_campaign), as rows; and the campaign's faults (transducer bias, offset,
    collapse rows only)."""
    rng = np.random.default_rng([seed, truth["truth"]["index"]])
    obs, faults = draw_campaign(truth, rng, FAULTS)
    rows = []
    for p in obs.pairs:
        # draw_campaign's test ids are <specimen>_f<frequency>_A<mm>; its ramps stop at the
        # first collapse, so the pair's last test is its collapse (its only one when the
        # campaign keeps collapse rows only).
        for k, (tid, gain) in enumerate(zip(p.test_ids, p.gains)):
            amp = float(tid.rsplit("_A", 1)[1]) * 1e-3
            rows.append({"test_id": tid, "specimen_id": p.specimen_id, "frequency_hz": p.frequency_hz,
                         "amplitude_m": round(amp / SNAP_M) * SNAP_M, "collapsed": k == len(p.test_ids) - 1,
                         "collapse_time_s": None, "gain": gain, "step": 0})
    return rows, faults


def write_campaign(folder: Path, rows: list[dict]) -> None:
    """specimens.csv (the nominal arches, as the laboratory declares them), tests.csv,
    table.csv (the contract's default limits) and records/<test>.csv: the table's
    displacement, the measured gain times the afd command (no delay: the replay's
    laboratory measures a gain only)."""
    if folder.exists():
        shutil.rmtree(folder)
    (folder / "records").mkdir(parents=True)
    used = list(dict.fromkeys(r["specimen_id"] for r in rows))
    spec = ["specimen_id,embrace_deg,n_voussoirs,r_ext_m,thickness_m,width_m,density_kg_m3,friction"]
    spec += [f"{a.specimen_id},{a.embrace_deg:g},{a.n_voussoirs},{a.r_ext_m:g},{a.thickness_m:g},{a.width_m:g},"
             f"{a.density_kg_m3:g},{a.friction:g}" for a in ARCHES if a.specimen_id in used]
    (folder / "specimens.csv").write_text("\n".join(spec) + "\n")
    (folder / "table.csv").write_text("stroke_m,max_velocity_m_s,max_accel_m_s2,displacement_gain_sd\n"
                                      "0.15,1.0,20,0.01\n")
    lines = ["test_id,specimen_id,waveform,frequency_hz,amplitude_m,n_attack,n_full,n_decay,outcome,collapse_time_s"]
    t_pulse, x_pulse, _ = unit_pulse()
    for r in rows:
        tc = "" if r["collapse_time_s"] is None else f"{r['collapse_time_s']:.3f}"
        outcome = "collapse" if r["collapsed"] else "stand"
        if r.get("kind") == "pulse":   # a record test: the table's record says what drove it
            lines.append(f"{r['test_id']},{r['specimen_id']},record,,,,,,{outcome},{tc}")
            t = np.arange(0.0, t_pulse[-1] + 1e-9, 1.0 / RECORD_HZ)
            x = r["gain"] * r["polarity"] * r["amplitude_m"] * np.interp(t, t_pulse, x_pulse)
            text = "t_s,table_x_m\n" + "\n".join(f"{a:.4f},{b:.7e}" for a, b in zip(t, x))
            (folder / "records" / f"{r['test_id']}.csv").write_text(text + "\n")
            continue
        lines.append(f"{r['test_id']},{r['specimen_id']},afd,{r['frequency_hz']:g},{r['amplitude_m']:.4f},1,1,1,"
                     f"{outcome},{tc}")
        t = np.arange(0.0, 3.0 / r["frequency_hz"] + 0.5, 1.0 / RECORD_HZ)
        x = r["gain"] * afd_command(t, r["frequency_hz"], r["amplitude_m"])
        if r.get("crown"):
            dx = np.interp(t, r["crown"]["t_s"], r["crown"]["dx_m"])
            text = "t_s,table_x_m,crown_dx_m\n" + "\n".join(f"{a:.4f},{b:.7e},{c:.7e}" for a, b, c in zip(t, x, dx))
        else:
            text = "t_s,table_x_m\n" + "\n".join(f"{a:.4f},{b:.7e}" for a, b in zip(t, x))
        (folder / "records" / f"{r['test_id']}.csv").write_text(text + "\n")
    (folder / "tests.csv").write_text("\n".join(lines) + "\n")
    (folder / "README.md").write_text("A campaign of the LMGC90 laboratory loop (bench/lmgc90/loop.py).\n")


# ---------------------------------------------------------------- the laboratory: LMGC90 on the truth


class Laboratory:
    """LMGC90 on one hidden truth, with the campaign's faults; one model folder per specimen."""

    def __init__(self, truth: dict, faults: dict, build: str, work: Path, bin_dir: Path):
        self.truth = {"parameters": truth["truth"]["parameters"], "faults": truth["faults"]}
        self.faults, self.build, self.work, self.bin_dir = faults, build, work, bin_dir
        self.models: dict[str, Lmgc90Specimen] = {}
        self.runs, self.seconds = 0, 0.0

    def specimen(self, sid: str) -> Lmgc90Specimen:
        if sid not in self.models:
            par = self.truth["parameters"]
            friction = par.get("friction", {}).get("friction", ARCH[sid].friction)
            self.models[sid] = Lmgc90Specimen(self.build, self.work / sid, ARCH[sid], self.truth, friction,
                                              record_crown=True)
        return self.models[sid]

    def gain(self, f: float) -> float:
        q = self.truth["parameters"].get("table_motion")
        return 1.0 if q is None else actuator_gain(f, q["actuator_hz"], q["actuator_damping"])

    def test(self, sid: str, f: float, amp: float, rng: np.random.Generator, step: int, hold: bool = False) -> dict:
        """One test: the table's real gain scatters about the actuator's, the campaign's
        offset applies (as draw_campaign's), the transducer reads the gain with its bias.
        `hold`: a test held below the threshold, whose crown is recorded too."""
        scatter = 1.0 + FAULTS.gain_scatter * rng.standard_normal()
        measured = self.gain(f) * scatter * (1.0 + self.faults["transducer_bias"]) * (
            1.0 + FAULTS.gain_noise * rng.standard_normal())
        t0 = time.time()
        model = self.specimen(sid)
        fell, tc, _ = model.run(f, amp * scatter * self.faults["offset"])
        self.seconds += time.time() - t0
        self.runs += 1
        row = {"test_id": f"{sid}_f{f:g}_s{step}_A{1e3 * amp:.1f}", "specimen_id": sid, "frequency_hz": f,
               "amplitude_m": amp, "collapsed": bool(fell), "collapse_time_s": tc, "gain": measured, "step": step}
        if hold:   # the crown's transducer: LMGC90's record with a displacement sensor's noise
            dx = np.asarray(model.last["crown_dx_m"], float)
            row["crown"] = {"t_s": model.last["crown_t_s"],
                            "dx_m": (dx + CROWN_NOISE_M * rng.standard_normal(dx.size)).tolist()}
        return row

    def pulse(self, sid: str, travel: float, polarity: int, rng: np.random.Generator, step: int) -> dict:
        """One pulse test (pulses.unit_pulse scaled to `travel` [m], `polarity` +1 or -1),
        with the campaign's faults as an afd test has them: the table's travel scattered
        and offset, the transducer reading it with its bias."""
        scatter = 1.0 + FAULTS.gain_scatter * rng.standard_normal()
        measured = scatter * (1.0 + self.faults["transducer_bias"]) * (1.0 + FAULTS.gain_noise * rng.standard_normal())
        t, x, _ = unit_pulse()
        vel = np.gradient(x, t[1] - t[0]) * polarity * travel * scatter * self.faults["offset"]
        t0 = time.time()
        fell = self.specimen(sid).run_table(vel, int(round(PULSE_LEAD_S / (t[1] - t[0]))))
        self.seconds += time.time() - t0
        self.runs += 1
        return {"test_id": f"{sid}_pulse{'p' if polarity > 0 else 'm'}_s{step}_T{1e3 * travel:.1f}",
                "specimen_id": sid, "kind": "pulse", "polarity": polarity, "frequency_hz": None,
                "amplitude_m": travel, "collapsed": bool(fell), "collapse_time_s": None, "gain": measured,
                "step": step}

    def pulse_ramps(self, sid: str, start: float, by: float, table, rng, step: int) -> list[dict]:
        """A pulse ramp each way (`ramp_rows`), in metres of travel, within the table's limits."""
        reach = reach_m(table)
        return [r for pol in (1, -1) for r in ramp_rows(lambda a, pol=pol: self.pulse(sid, a, pol, rng, step),
                                                         start, by, lambda a: a <= reach)]

    def ramp(self, sid: str, f: float, start: float, by: float, table, rng, step: int, record: bool = False
             ) -> list[dict]:
        """An afd ramp (`ramp_rows`) within the table's limits. `record`: every test's crown too."""
        return ramp_rows(lambda a: self.test(sid, f, a, rng, step, hold=record), start, by,
                         lambda a: within_limits(a, f, table))


def ramp_rows(run, start: float, by: float, ok, max_tests: int = 40) -> list[dict]:
    """Up from `start` by `by` to the first collapse while `ok(amplitude)`; when the first
    test falls, down by `by` until one stands (at most STEP_DOWN_MAX). `run(amplitude)`
    gives a test's row."""
    snap = lambda a: round(round(a / SNAP_M) * SNAP_M, 7)
    by = max(SNAP_M, snap(by))
    rows, amp = [], max(SNAP_M, snap(start))
    while len(rows) < max_tests and ok(amp):
        rows.append(run(amp))
        if rows[-1]["collapsed"]:
            break
        amp = snap(amp + by)
    if len(rows) == 1 and rows[0]["collapsed"]:
        amp = snap(rows[0]["amplitude_m"] - by)
        while amp >= SNAP_M and len(rows) <= STEP_DOWN_MAX:
            rows.append(run(amp))
            if not rows[-1]["collapsed"]:
                break
            amp = snap(amp - by)
    return rows


# ---------------------------------------------------------------- one truth, one design


def bank_files(bank: Path) -> dict[str, int]:
    """The bank's files (one per specimen and frequency) and their searches."""
    return {p.name: json.loads(p.read_text()).get("searches", 0) for p in sorted(bank.glob("*.json"))}


def named_model(result: dict) -> str | None:
    v = result["verdict"]
    if v == "inconclusive":
        return None
    return "+".join(sorted(result["effects"])) if v == "combined" else v


def diagnose_step(campaign: Path, out: Path, settings: DiagnosisSettings, advise: bool, label: str,
                  tested: list[tuple[str, float]]) -> dict:
    """One diagnosis; returns its summary with the bank's growth and the times."""
    bank = Path(settings.bank_dir)
    before = bank_files(bank)
    times = {"bank_s": 0.0, "next_test_s": 0.0}
    real_bank, real_next = pipeline.build_bank, pipeline.next_test

    def timed_bank(*a, **k):
        t0 = time.time()
        try:
            return real_bank(*a, **k)
        finally:
            times["bank_s"] += time.time() - t0

    def timed_next(*a, **k):
        if not advise:  # the naive design never reads the advice: not computed
            return None
        t0 = time.time()
        try:
            return real_next(*a, **k)
        finally:
            times["next_test_s"] += time.time() - t0

    pipeline.build_bank, pipeline.next_test = timed_bank, timed_next
    t0 = time.time()
    try:
        result = pipeline.diagnose(campaign, out, settings)
    finally:
        pipeline.build_bank, pipeline.next_test = real_bank, real_next
    elapsed = time.time() - t0
    shutil.rmtree(out / "work", ignore_errors=True)
    after = bank_files(bank)
    new = {k: v for k, v in after.items() if k not in before}
    # A new test adds only its own simulations to the bank: the file of its (specimen,
    # frequency), if that pair was not simulated before (by this truth or another).
    allowed = {f"{sid}-{f:g}Hz-" for sid, f in tested}
    stray = [k for k in new if not any(k.startswith(a) for a in allowed)]
    assert not stray, f"the bank gained files of pairs other than {tested}: {stray}"
    p = result["probabilities"]
    named = named_model(result)
    return {"verdict": result["verdict"], "named": named, "named_right": None if named is None else named == label,
            "p_truth": p.get(label, 0.0), "top": sorted(p.items(), key=lambda kv: -kv[1])[:4],
            "rivals": result["rivals"], "adequate": result["adequate"], "flags": result["flags"],
            "next_test": result["next_test"], "diagnose_s": round(elapsed, 1), "bank_s": round(times["bank_s"], 1),
            "next_test_s": round(times["next_test_s"], 1), "bank_new_files": sorted(new),
            "bank_new_searches": int(sum(new.values()))}


def naive_choice(rows: list[dict], table, settings: DiagnosisSettings, rng: np.random.Generator
                 ) -> tuple[str, float] | None:
    """The next frequency up on the specimen of the most recent test (untested, within the
    table's limits at the start of a ramp), else a random untested (specimen, frequency)."""
    tested = {(r["specimen_id"], r["frequency_hz"]) for r in rows}

    def fresh(sid, f):
        return (all(abs(f - t) > 0.05 for s, t in tested if s == sid)
                and within_limits(FAULTS.start_fraction[1] * onset_m(ARCH[sid], f, settings.bin_dir), f, table))
    last = rows[-1]
    ups = [f for f in sorted(settings.probe_frequencies_hz) if f > last["frequency_hz"] + 0.05
           and fresh(last["specimen_id"], f)]
    if ups:
        return last["specimen_id"], ups[0]
    pool = [(a.specimen_id, f) for a in ARCHES for f in settings.probe_frequencies_hz if fresh(a.specimen_id, f)]
    return pool[int(rng.integers(len(pool)))] if pool else None


def run_truth(truth: dict, design: str, args, settings: DiagnosisSettings, out_root: Path) -> dict:
    settings_of = lambda d: dataclasses.replace(settings, crown_records=d != "ramps")
    slug = truth["slug"]
    label = truth_model(truth)
    res_path = out_root / "results" / f"{slug}__{design}.json"
    state = json.loads(res_path.read_text()) if res_path.exists() else None
    if state and state.get("finished"):
        return state
    base = out_root / "runs" / slug
    rows0, faults = replayed_tests(truth, args.seed)
    if state is None:
        state = {"truth": slug, "label": label, "design": design, "seed": args.seed, "faults": faults,
                 "steps": [], "rows": rows0, "finished": False}
    rows = state["rows"]
    table = None
    lab = Laboratory(truth, faults, args.lmgc90_build, base / design / "lmgc90", settings.bin_dir)
    while True:
        k = len(state["steps"])
        campaign = base / design / "campaign"
        write_campaign(campaign, rows)
        table = read_campaign(campaign).table
        if k == 0:
            # Step 0 is the replayed campaign: diagnosed once, shared by the designs.
            shared = base / ("step0_ramps.json" if design == "ramps" else "step0.json")
            if shared.exists():
                step = json.loads(shared.read_text())
            else:
                log(f"{slug} ({label}): step 0, the replayed campaign ({len(rows)} tests)")
                step = diagnose_step(campaign, base / shared.stem, settings_of(design), True, label,
                                     sorted({(r["specimen_id"], r["frequency_hz"]) for r in rows}))
                step |= {"step": 0, "tests_used": 0, "chosen": None}
                shared.write_text(json.dumps(step, indent=1))
        else:
            prev = state["steps"][-1]
            rng = np.random.default_rng([args.seed, truth["truth"]["index"], DESIGNS.index(design), k])
            if design in ("advised", "ramps", "recorded"):
                nt = prev["next_test"]
                chosen = {"specimen_id": nt["specimen_id"], "frequency_hz": nt["frequency_hz"], "kind": nt["kind"],
                          "amplitudes_m": nt["amplitudes_m"], "expected_gain_bits": nt["expected_gain_bits"],
                          "predictions": nt["predictions"], **({"predicted_crown_m": nt["predicted_crown_m"]}
                                                               if "predicted_crown_m" in nt else {})}
                assert nt["kind"] in ("afd_ramp", "hold_crown", "pulse_pair"), nt
                a_to = max(nt["amplitudes_m"][:2])
                if nt["kind"] == "pulse_pair":
                    assert a_to <= reach_m(table), f"advice beyond the table's limits: {nt}"
                else:
                    assert within_limits(a_to, nt["frequency_hz"], table), f"advice beyond the table's limits: {nt}"
                sid, f = nt["specimen_id"], nt["frequency_hz"]
                if nt["kind"] in ("afd_ramp", "pulse_pair"):
                    a_from, a_to, a_by = nt["amplitudes_m"]
            else:
                pick = naive_choice(rows, table, settings, rng)
                if pick is None:
                    state["stopped"] = "no untested pair within the table's limits"
                    break
                sid, f = pick
                onset = onset_m(ARCH[sid], f, settings.bin_dir)
                a_from = rng.uniform(*FAULTS.start_fraction) * onset
                a_by = rng.uniform(*FAULTS.step_mm) * 1e-3
                chosen = {"specimen_id": sid, "frequency_hz": f, "kind": "afd_ramp",
                          "amplitudes_m": [round(round(a_from / SNAP_M) * SNAP_M, 7), None,
                                           round(max(SNAP_M, round(a_by / SNAP_M) * SNAP_M), 7)]}
            runs0, secs0 = lab.runs, lab.seconds
            log(f"{slug} [{design}] test {k}: {sid} at {f:g} Hz, "
                + {"hold_crown": "held", "pulse_pair": "pulses each way"}.get(chosen["kind"], "ramp") + f" {chosen['amplitudes_m']} in LMGC90")
            if chosen["kind"] == "hold_crown":
                new = [lab.test(sid, f, chosen["amplitudes_m"][0], rng, k, hold=True)]
            elif chosen["kind"] == "pulse_pair":
                new = lab.pulse_ramps(sid, a_from, a_by, table, rng, k)
            else:
                new = lab.ramp(sid, f, a_from, a_by, table, rng, k, record=design == "recorded")
            lmgc = {"runs": lab.runs - runs0, "seconds": round(lab.seconds - secs0, 1),
                    "rows": [[r.get("polarity", 1) * r["amplitude_m"], int(r["collapsed"])] for r in new]}
            if chosen["kind"] == "hold_crown":
                lmgc["crown_peak_mm"] = [1e3 * float(np.max(np.abs(r["crown"]["dx_m"]))) for r in new]
            log(f"  {lmgc['runs']} LMGC90 runs, {lmgc['seconds']:.0f} s: "
                + " ".join(f"{1e3 * a:.1f}{'C' if c else 's'}" for a, c in lmgc["rows"]))
            rows.extend(new)
            write_campaign(campaign, rows)
            step = diagnose_step(campaign, base / design / f"step{k}", settings_of(design), design != "naive", label,
                                 [(sid, f)])
            step |= {"step": k, "tests_used": k, "chosen": chosen, "lmgc90": lmgc}
        state["steps"].append(step)
        log(f"{slug} [{design}] step {k}: {step['verdict']}, P(truth={label}) {step['p_truth']:.3f}; top "
            + ", ".join(f"{m} {p:.2f}" for m, p in step["top"][:3])
            + f"; diagnosis {step['diagnose_s']:.0f} s (bank {step['bank_s']:.0f} s, "
              f"{step['bank_new_searches']} new searches in {len(step['bank_new_files'])} files; "
              f"next test {step['next_test_s']:.0f} s)")
        res_path.parent.mkdir(parents=True, exist_ok=True)
        res_path.write_text(json.dumps(state, indent=1))
        if step["named"] is not None:
            state["stopped"] = "named"
            break
        if k >= MAX_TESTS:
            state["stopped"] = "three tests"
            break
        if design != "naive" and not step["next_test"]:
            state["stopped"] = "no advice"
            break
    last = state["steps"][-1]
    state |= {"finished": True, "tests_used": last["tests_used"], "named": last["named"],
              "named_right": last["named_right"], "p_truth_initial": state["steps"][0]["p_truth"],
              "p_truth_final": last["p_truth"],
              "named_at_step": last["step"] if last["named"] is not None else None}
    res_path.write_text(json.dumps(state, indent=1))
    return state


# ---------------------------------------------------------------- the summary


def sign_test_p(wins: int, losses: int) -> float:
    """Two-sided exact sign test over the non-tied pairs."""
    n = wins + losses
    if n == 0:
        return 1.0
    k = min(wins, losses)
    tail = sum(math.comb(n, i) for i in range(k + 1)) / 2.0 ** n
    return min(1.0, 2.0 * tail)


def judged_label(truth: dict, rows: list[dict], settings: DiagnosisSettings, work: Path) -> str:
    """The truth's label as the calibration gives it (lmgc90_campaigns.truth_model with the
    bank and the campaign): less any effect that moves none of the campaign's tested
    thresholds by its material threshold. Reads the loop's bank (every pair of these rows
    is in it)."""
    write_campaign(work, rows)
    obs, _ = from_campaign(read_campaign(work))
    bank = build_bank(obs.specimens, {sid: obs.frequencies(sid) for sid in obs.specimens}, obs.cycles, settings,
                      Path(settings.bank_dir), work / "work")
    assert bank.searches == 0, "judged_label: the bank lacks a pair of these rows"
    shutil.rmtree(work, ignore_errors=True)
    return truth_model(truth, bank, obs)


def judge(res: dict, settings: DiagnosisSettings, out_root: Path) -> None:
    """Adds to each result the calibration's labels of the truth at step 0 and at its last
    step, whether the named model is right by the last one, and P(truth) by them."""
    truths = {t["slug"]: t for t in stored_truths()}
    for (t, d), s in res.items():
        last = s["steps"][-1]["step"]
        cache = out_root / "results" / f"{t}__{d}.judged.json"
        if cache.exists():
            s.update(json.loads(cache.read_text()))
            continue
        labels = [judged_label(truths[t], [r for r in s["rows"] if r["step"] <= k], settings, out_root / "judge")
                  for k in (0, last)]
        p = [json.loads((out_root / "runs" / t / (("step0_ramps" if d == "ramps" else "step0") if k == 0
                                                  else f"{d}/step{k}") / "diagnosis.json").read_text())["probabilities"]
             for k in (0, last)]
        j = {"label_judged": labels, "p_truth_initial_judged": p[0].get(labels[0], 0.0),
             "p_truth_final_judged": p[1].get(labels[1], 0.0),
             "named_right_judged": None if s["named"] is None else s["named"] == labels[1]}
        cache.write_text(json.dumps(j))
        s.update(j)


def summary(out_root: Path, settings: DiagnosisSettings | None = None) -> dict:
    res = {}
    for p in sorted((out_root / "results").glob("*__*.json")):
        if p.name.endswith(".judged.json"):
            continue
        s = json.loads(p.read_text())
        if s.get("finished"):
            res[(s["truth"], s["design"])] = s
    if settings is not None:
        judge(res, settings, out_root)
    truths = sorted({t for t, _ in res}, key=lambda t: int(t[1:].split("_")[0]))
    print(f"{'truth':52s} {'label':28s} design   tests verdict                    P(truth) by step")
    for t in truths:
        for d in DESIGNS:
            s = res.get((t, d))
            if s is None:
                continue
            ps = " ".join(f"{st['p_truth']:.2f}" for st in s["steps"])
            chosen = "; ".join(f"{st['chosen']['specimen_id']}@{st['chosen']['frequency_hz']:g}"
                               + {"hold_crown": " hold", "pulse_pair": " pulses"}.get(st["chosen"]["kind"], "")
                               for st in s["steps"][1:])
            verdict = s["steps"][-1]["verdict"] + ("" if s["named"] is None else (" (right)" if s["named_right"]
                                                                                    else " (WRONG)"))
            print(f"{t:52s} {s['label']:28s} {d:8s} {s['tests_used']:5d} {verdict:26s} {ps:24s} {chosen}")
    out = {}
    for d in DESIGNS:
        done = [res[(t, d)] for t in truths if (t, d) in res]
        if not done:
            continue
        named = [s for s in done if s["named"] is not None]
        right = sum(bool(s["named_right"]) for s in named)
        out[d] = {"truths": len(done), "named": len(named), "right": right, "wrong": len(named) - right,
                  "mean_tests": float(np.mean([s["tests_used"] for s in done])),
                  "mean_p_truth_final": float(np.mean([s["p_truth_final"] for s in done]))}
        out[d]["named_after_tests"] = {k: sum(s["named_at_step"] == k for s in named) for k in range(MAX_TESTS + 1)}
        out[d]["stopped"] = {r: sum(s["stopped"] == r for s in done) for r in sorted({s["stopped"] for s in done})}
        # Confidently against the truth: a wrong naming (by the calibration's labels where
        # judged) or the truth's probability at the end at CONFIDENT_AGAINST or below.
        against = [s["truth"] for s in done
                   if s["p_truth_final"] <= CONFIDENT_AGAINST
                   or (s["named"] is not None and not s.get("named_right_judged", s["named_right"]))]
        out[d]["confidently_against"] = against
        if all("named_right_judged" in s for s in done):
            rj = sum(bool(s["named_right_judged"]) for s in named)
            out[d] |= {"right_judged": rj, "wrong_judged": len(named) - rj,
                       "labels_changed": [s["truth"] for s in done if s["label_judged"][-1] != s["label"]]}
            print(f"{d}, labelled as the calibration labels (an effect that moves no tested threshold by its "
                  f"material threshold is no cause): {rj} right, {len(named) - rj} wrong; labels changed: "
                  + (", ".join(f"{s['truth']} {s['label']} -> {s['label_judged'][-1]}" for s in done
                               if s["label_judged"][-1] != s["label"]) or "none"))
        print(f"{d}: named at {NAMED_AT} within {MAX_TESTS} tests in {len(named)} of {len(done)} truths "
              f"({right} right, {len(named) - right} wrong; after 0/1/2/3 tests: "
              + "/".join(str(v) for v in out[d]["named_after_tests"].values())
              + f"); mean tests {out[d]['mean_tests']:.2f}; mean final P(truth) {out[d]['mean_p_truth_final']:.3f}; "
              f"stopped: {out[d]['stopped']}; confidently against the truth (named wrongly, or P(truth) <= "
              f"{CONFIDENT_AGAINST} at the end): {len(against)}" + (f" ({', '.join(against)})" if against else ""))
    for a, b in (("advised", "naive"), ("advised", "ramps"), ("ramps", "naive"), ("recorded", "ramps"),
                 ("recorded", "advised")):
        paired = [t for t in truths if (t, a) in res and (t, b) in res]
        if not paired:
            continue
        gain = {d: [res[(t, d)]["p_truth_final"] - res[(t, d)]["p_truth_initial"] for t in paired] for d in (a, b)}
        diff = np.array(gain[a]) - np.array(gain[b])
        wins, losses = int((diff > 1e-3).sum()), int((diff < -1e-3).sum())
        ties = len(paired) - wins - losses
        p = sign_test_p(wins, losses)
        out[f"paired_{a}_{b}"] = {"truths": len(paired), "wins": wins, "ties": ties, "losses": losses,
                                  "sign_test_p": p, f"mean_gain_{a}": float(np.mean(gain[a])),
                                  f"mean_gain_{b}": float(np.mean(gain[b]))}
        print(f"{a} vs {b}, gain in P(truth) over {len(paired)} truths (ties within 0.001): {wins} wins, "
              f"{ties} ties, {losses} losses; sign test p = {p:.3g}; mean gain {np.mean(gain[a]):+.3f} "
              f"({a}) vs {np.mean(gain[b]):+.3f} ({b})")
    # The advice's expected gain against what its test gave: the entropy of the rivals
    # (renormalised) before the test less after it, in bits.
    expected, realised = [], []
    for (t, d), s in res.items():
        if d == "naive":
            continue
        for k in range(1, len(s["steps"])):
            nt = s["steps"][k - 1]["next_test"]
            first = "step0_ramps" if d == "ramps" else "step0"
            before = out_root / "runs" / t / (first if k == 1 else f"{d}/step{k - 1}") / "diagnosis.json"
            after = out_root / "runs" / t / f"{d}/step{k}" / "diagnosis.json"
            if not (nt and before.exists() and after.exists()):
                continue
            rivals = list(nt["predictions"])

            def h(path):
                q = np.array([json.loads(path.read_text())["probabilities"][m] for m in rivals])
                q = q[q > 0] / q.sum()
                return float(-(q * np.log2(q)).sum())
            expected.append(nt["expected_gain_bits"])
            realised.append(h(before) - h(after))
    if expected:
        out["information"] = {"tests": len(expected), "expected_bits": float(np.mean(expected)),
                              "realised_bits": float(np.mean(realised)),
                              "realised_per_test": [round(x, 3) for x in realised],
                              "expected_per_test": [round(x, 3) for x in expected]}
        print(f"advised tests (every advising design): expected gain {np.mean(expected):.2f} bits a test, realised "
              f"(entropy of the rivals before less after) {np.mean(realised):.2f} bits ({len(expected)} tests)")
    steps = [st for s in res.values() for st in s["steps"][1:]]
    if steps:
        fresh = [st for st in steps if st["bank_new_searches"] > 0]
        out["times"] = {
            "steps": len(steps),
            "lmgc90_runs_per_step": float(np.mean([st["lmgc90"]["runs"] for st in steps])),
            "lmgc90_s_per_step": float(np.mean([st["lmgc90"]["seconds"] for st in steps])),
            "lmgc90_s_per_run": float(sum(st["lmgc90"]["seconds"] for st in steps)
                                      / max(1, sum(st["lmgc90"]["runs"] for st in steps))),
            "diagnose_s_per_step": float(np.mean([st["diagnose_s"] for st in steps])),
            "bank_growth_steps": len(fresh),
            "bank_growth_s": float(np.mean([st["bank_s"] for st in fresh])) if fresh else 0.0,
            "bank_growth_searches": float(np.mean([st["bank_new_searches"] for st in fresh])) if fresh else 0.0,
            "next_test_s_advised": float(np.mean([st["next_test_s"] for s in res.values() if s["design"] == "advised"
                                                  for st in s["steps"]] or [0.0])),
        }
        t = out["times"]
        print(f"times over {t['steps']} tests: LMGC90 {t['lmgc90_runs_per_step']:.1f} runs, "
              f"{t['lmgc90_s_per_step']:.0f} s a test ({t['lmgc90_s_per_run']:.2f} s a run); diagnosis "
              f"{t['diagnose_s_per_step']:.0f} s a step; bank growth at a new pair ({t['bank_growth_steps']} steps) "
              f"{t['bank_growth_s']:.0f} s, {t['bank_growth_searches']:.0f} searches; next_test "
              f"{t['next_test_s_advised']:.0f} s a diagnosis (advised)")
    (out_root / "summary.json").write_text(json.dumps(out, indent=1) + "\n")
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lmgc90-build", help="LMGC90 build folder (holds pylmgc90)")
    ap.add_argument("--out", required=True, help="output folder (results/, runs/, bank/)")
    ap.add_argument("--truths", type=int, default=12, help="the first N stored truths inside the catalogue, by index")
    ap.add_argument("--slugs", help="comma-separated truths to run instead of the first N (their file names' stems)")
    ap.add_argument("--designs", default=",".join(DESIGNS))
    ap.add_argument("--seed", type=int, default=SEED)
    ap.add_argument("--np", type=int, default=2, help="MPI ranks of the sweeps")
    ap.add_argument("--bin-dir", default=os.environ.get("VOUSSOIR_BIN_DIR", str(ROOT / "build" / "drivers")))
    ap.add_argument("--bank", help="bank folder (default OUT/bank)")
    ap.add_argument("--summary", action="store_true", help="print the table of the finished truths and stop")
    args = ap.parse_args(argv)
    out_root = Path(args.out)
    if args.summary:
        summary(out_root, DiagnosisSettings(bin_dir=Path(args.bin_dir).resolve(), n_ranks=args.np,
                                            bank_dir=Path(args.bank or out_root / "bank").resolve(),
                                            log=lambda m: None))
        return 0
    build = os.path.abspath(args.lmgc90_build or ".")
    if not (Path(build) / "pylmgc90").is_dir():
        sys.exit(f"loop.py: no pylmgc90 in {build} (give the LMGC90 build folder)")
    args.lmgc90_build = build
    settings = DiagnosisSettings(bin_dir=Path(args.bin_dir).resolve(), n_ranks=args.np,
                                 bank_dir=Path(args.bank or out_root / "bank").resolve(),
                                 log=lambda m: print(m, flush=True) if not m.startswith("[bank]") or "cached" not in m
                                 else None)
    truths = [t for t in stored_truths() if truth_model(t) != "outside"]
    if args.slugs:
        wanted = args.slugs.split(",")
        missing = set(wanted) - {t["slug"] for t in truths}
        if missing:
            sys.exit(f"loop.py: --slugs: no stored truth inside the catalogue named {', '.join(sorted(missing))}")
        truths = [t for t in truths if t["slug"] in wanted]
    else:
        truths = truths[:args.truths]
    designs = [d for d in args.designs.split(",") if d]
    log(f"{len(truths)} truths inside the catalogue: " + ", ".join(t["slug"] for t in truths))
    t_all = time.time()
    for truth in truths:
        for d in designs:
            t0 = time.time()
            s = run_truth(truth, d, args, settings, out_root)
            log(f"== {truth['slug']} [{d}]: {s['stopped']} after {s['tests_used']} tests, named {s['named']} "
                f"({'right' if s['named_right'] else 'wrong' if s['named'] else '-'}), P(truth) "
                f"{s['p_truth_initial']:.3f} -> {s['p_truth_final']:.3f} ({time.time() - t0:.0f} s)")
    log(f"all done in {time.time() - t_all:.0f} s")
    summary(out_root, settings)
    return 0


if __name__ == "__main__":
    sys.exit(main())
