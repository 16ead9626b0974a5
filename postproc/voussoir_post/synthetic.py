"""Synthetic shaking-table campaigns written by the project's own simulator.

A campaign is run the way a laboratory runs one: for each specimen and frequency the
commanded amplitude is raised in fixed steps from below the static onset until the
arch falls. Each test is simulated with ``voussoir-run`` under a hidden *truth* (one
model effect of shared/MEASURED_DATA.md, or none), and written in the campaign format
with realistic imperfections: the table of each test plays the command with a small
random gain (1 % by default), the records carry sensor noise, the peak acceleration is
measured from the noisy record, the hinge times are jittered. Nothing in the files
says what the truth was: it lives only in the caller (e.g. a test's assertions).

Used by the diagnosis tests; also a tool for planning a campaign.
"""

from __future__ import annotations

import math
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .results import RunResult
from .runner import Runner

__all__ = ["SyntheticSpecimen", "Truth", "write_synthetic_campaign", "SEED_LIKE_SPECIMENS"]


@dataclass
class SyntheticSpecimen:
    """An arch to build and test, in the units of specimens.csv."""

    specimen_id: str
    embrace_deg: float
    n_voussoirs: int
    frequencies_hz: tuple[float, ...]
    r_ext_m: float = 0.508
    thickness_m: float = 0.071
    width_m: float = 0.145
    density_kg_m3: float = 700.0
    friction: float = 0.5  #: nominal friction written to specimens.csv


#: Arches like the seed paper's (12-degree voussoirs) at two frequencies each.
SEED_LIKE_SPECIMENS = (
    SyntheticSpecimen("S156", 156.0, 13, (1.25, 2.0)),
    SyntheticSpecimen("S132", 132.0, 11, (1.6, 2.5)),
    SyntheticSpecimen("S118", 118.0, 10, (2.0, 3.0)),
)


@dataclass
class Truth:
    """The hidden physics of a synthetic campaign: at most one effect."""

    effect: str = "none"  #: none, contact_edges, table_motion, base_restraint, friction
    inset_m: float = 0.0
    accel_gain: float = 1.0
    delay_s: float = 0.0
    restrained_springings: str = "none"  #: none, left, right, both
    friction: float | None = None  #: true friction (None: the nominal one)


@dataclass
class _Noise:
    test_gain_sd: float = 0.01  #: test-to-test scatter of the table gain (fraction)
    record_sd_m: float = 3.0e-5  #: sensor noise of the table record (position transducer) [m]
    crown_sd_m: float = 2.0e-4  #: sensor noise of the crown record [m]
    hinge_time_sd_s: float = 0.01
    sample_hz: float = 200.0


def _groups(spec: SyntheticSpecimen, truth: Truth, frequency_hz: float, amplitude_m: float,
            gain: float, dt_s: float) -> dict:
    friction = spec.friction if truth.friction is None else truth.friction
    return {"arch": {"embrace_deg": float(spec.embrace_deg), "n_voussoirs": spec.n_voussoirs,
                     "r_ext_m": float(spec.r_ext_m), "thickness_m": float(spec.thickness_m),
                     "width_m": float(spec.width_m), "density_kg_m3": float(spec.density_kg_m3),
                     "friction": float(friction), "contact_inset_m": float(truth.inset_m),
                     "restrained_springings": truth.restrained_springings},
            "motion": {"waveform": "afd", "frequency_hz": float(frequency_hz), "amplitude_m": float(amplitude_m),
                       "n_attack": 1, "n_full": 1, "n_decay": 1, "rest_s": 1.0, "table_gain": float(gain),
                       "table_delay_s": float(truth.delay_s)},
            "solver": {"dt_s": float(dt_s), "allow_nonconvergence": True},
            "output": {"every": max(1, int(round(1.0 / (200.0 * dt_s)))), "stop_after_collapse_s": 0.3}}


def _static_onset_m(runner: Runner, spec: SyntheticSpecimen, frequency_hz: float) -> float:
    """Amplitude whose peak acceleration equals the nominal arch's static capacity."""
    limit = runner.run_limit({"arch": {"embrace_deg": float(spec.embrace_deg), "n_voussoirs": spec.n_voussoirs,
                                       "r_ext_m": float(spec.r_ext_m), "thickness_m": float(spec.thickness_m)}},
                             f"limit_{spec.specimen_id}")
    return limit.lambda_pos * 9.81 / (2.0 * math.pi * frequency_hz) ** 2


def _butter_filtfilt(x: np.ndarray, cutoff_hz: float, fs_hz: float) -> np.ndarray:
    """Zero-phase second-order Butterworth low-pass (as the kernel filters records)."""
    k = math.tan(math.pi * cutoff_hz / fs_hz)
    norm = 1.0 / (1.0 + math.sqrt(2.0) * k + k * k)
    b = np.array([k * k, 2 * k * k, k * k]) * norm
    a1, a2 = 2.0 * (k * k - 1.0) * norm, (1.0 - math.sqrt(2.0) * k + k * k) * norm

    def one_pass(y):
        out = np.empty_like(y)
        x1 = x2 = y1 = y2 = 0.0
        for i, x0 in enumerate(y):
            out[i] = b[0] * x0 + b[1] * x1 + b[2] * x2 - a1 * y1 - a2 * y2
            x2, x1, y2, y1 = x1, x0, y1, out[i]
        return out

    y = one_pass(x - x[0]) + x[0]
    return one_pass((y - y[-1])[::-1])[::-1] + y[-1]


def write_synthetic_campaign(folder: str | os.PathLike, truth: Truth, bin_dir: str | os.PathLike,
                             specimens=SEED_LIKE_SPECIMENS, step_fraction: float = 0.05,
                             start_fraction: float = 0.75, max_steps: int = 30, dt_s: float = 1.0e-3,
                             seed: int = 1, records: bool = True, hinges: bool = True,
                             noise: _Noise | None = None) -> dict:
    """Simulate a campaign under `truth` and write it to `folder` in the spec's format.

    Amplitude ladder of each (specimen, frequency): from `start_fraction` of the nominal
    static onset amplitude upwards in steps of `step_fraction` of it (rounded to 0.5 mm),
    until the first collapse. Returns a small summary (tests written per pair) for the
    caller; the truth is not written anywhere.
    """
    folder = Path(folder)
    bin_dir = Path(bin_dir)
    noise = noise or _Noise()
    rng = np.random.default_rng(seed)
    (folder / "records").mkdir(parents=True, exist_ok=True)
    (folder / "hinges").mkdir(parents=True, exist_ok=True)
    summary = {}
    spec_rows, test_rows = [], []
    with tempfile.TemporaryDirectory() as tmp:
        runner = Runner(bin_dir, Path(tmp))
        for spec in specimens:
            spec_rows.append(f"{spec.specimen_id},{spec.embrace_deg:g},{spec.n_voussoirs},{spec.r_ext_m:g},"
                             f"{spec.thickness_m:g},{spec.width_m:g},{spec.density_kg_m3:g},{spec.friction:g}")
            for f in spec.frequencies_hz:
                onset = _static_onset_m(runner, spec, f)
                step = max(5e-4, round(step_fraction * onset / 5e-4) * 5e-4)
                amp = max(step, round(start_fraction * onset / 5e-4) * 5e-4)
                n_written = 0
                for k in range(max_steps):
                    test_id = f"{spec.specimen_id}_f{f:g}_A{1e3 * amp:.1f}"
                    gain = truth.accel_gain * (1.0 + noise.test_gain_sd * rng.standard_normal())
                    run = runner.run_single(_groups(spec, truth, f, amp, gain, dt_s), test_id, keep=False)
                    row = _write_test(folder, spec, test_id, f, amp, run, rng, noise, records, hinges)
                    test_rows.append(row)
                    n_written += 1
                    if row.split(",")[8] == "collapse":
                        break
                    amp = round((amp + step) / 5e-4) * 5e-4
                summary[(spec.specimen_id, f)] = n_written
    (folder / "specimens.csv").write_text(
        "# Arches of a shaking-table campaign (synthetic).\n"
        "specimen_id,embrace_deg,n_voussoirs,r_ext_m,thickness_m,width_m,density_kg_m3,friction\n"
        + "\n".join(spec_rows) + "\n")
    (folder / "tests.csv").write_text(
        "# Amplitude ramps at fixed frequencies until collapse.\n"
        "test_id,specimen_id,waveform,frequency_hz,amplitude_m,n_attack,n_full,n_decay,outcome,"
        "collapse_time_s,peak_accel_m_s2\n" + "\n".join(test_rows) + "\n")
    (folder / "README.md").write_text("Shaking-table campaign: wooden ring arches of 12-degree voussoirs,\n"
                                      "sinusoidal attack-full-decay motion ramped in amplitude until collapse.\n")
    return summary


def _write_test(folder: Path, spec: SyntheticSpecimen, test_id: str, f: float, amp: float, run: RunResult,
                rng, noise: _Noise, records: bool, hinges: bool) -> str:
    collapsed, t_collapse = run.collapsed, run.collapse_time_s
    t, table, crown_dx, crown_dy = run.time_s, run.table_x_m, run.crown_dx_m, run.crown_dy_m
    h_t, h_j, h_s = run.hinge_time_s, run.hinge_joint, run.hinge_side
    fs = noise.sample_hz
    ts = np.arange(0.0, t[-1] + 1e-9, 1.0 / fs)
    x = np.interp(ts, t, table) + noise.record_sd_m * rng.standard_normal(ts.size)
    xf = _butter_filtfilt(x, 20.0, fs)
    acc = np.zeros_like(xf)
    acc[1:-1] = (xf[2:] - 2 * xf[1:-1] + xf[:-2]) * fs * fs
    peak_accel = float(np.abs(acc).max())
    if records:
        dx = np.interp(ts, t, crown_dx) + noise.crown_sd_m * rng.standard_normal(ts.size)
        dy = np.interp(ts, t, crown_dy) + noise.crown_sd_m * rng.standard_normal(ts.size)
        lines = ["t_s,table_x_m,crown_dx_m,crown_dy_m"]
        lines += [f"{a:.4f},{b:.6e},{c:.6e},{d:.6e}" for a, b, c, d in zip(ts, x, dx, dy)]
        (folder / "records" / f"{test_id}.csv").write_text("\n".join(lines) + "\n")
    if hinges and h_t.size:
        end = t_collapse if collapsed else math.inf
        rows = ["t_s,joint,side"]
        for tt, j, s in zip(h_t, h_j, h_s):
            if tt <= end:
                rows.append(f"{max(0.0, tt + noise.hinge_time_sd_s * rng.standard_normal()):.3f},{int(j)},"
                            f"{run.hinge_side_names[int(s)]}")
        if len(rows) > 1:
            (folder / "hinges" / f"{test_id}.csv").write_text("\n".join(rows) + "\n")
    outcome = "collapse" if collapsed else "stand"
    tc = f"{t_collapse:.3f}" if collapsed else ""
    return (f"{test_id},{spec.specimen_id},afd,{f:g},{amp:.4f},1,1,1,{outcome},{tc},{peak_accel:.3f}")
