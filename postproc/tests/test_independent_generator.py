"""The independent generator of test campaigns (independent_campaigns.py) is what it says:
its actuator has the gain of its transfer function, its uncut polygon ring is the
kernel's arch, and the actuator fit of the diagnosis recovers a known gain and delay."""

from __future__ import annotations

import math

import numpy as np

from voussoir_post.analysis.afd import afd_command
from voussoir_post.diagnosis.actuator import fit_actuator

from conftest import bin_dir
from independent_campaigns import ARCHES, Truth, actuator_record, ring_blocks, write_polygon_file


def _amplitude_ratio(f_hz: float, truth: Truth) -> float:
    """|H(f)| of the second-order actuator: the gain its records must show at f."""
    r = f_hz / truth.actuator_hz
    return 1.0 / math.hypot(1.0 - r * r, 2.0 * truth.actuator_damping * r)


def test_actuator_record_has_the_gain_of_its_transfer_function():
    """The actuator's steady response to a sine has the closed-form amplitude |H(f)|."""
    truth = Truth(actuator_hz=6.0, actuator_damping=0.2)
    f = 2.0
    t, x, acc = actuator_record(f, 0.01, 1.0, truth, tail_s=0.0)
    full = (t > 1.0 / f + 0.3) & (t < 2.0 / f)  # the full-amplitude cycle, after the transient
    assert abs(np.abs(x[full]).max() / 0.01 - _amplitude_ratio(f, truth)) < 0.02
    # The acceleration is the second derivative of the displacement.
    dt = t[1] - t[0]
    fd = (x[2:] - 2 * x[1:-1] + x[:-2]) / dt ** 2
    assert np.abs(fd - acc[1:-1]).max() < 1e-3 * np.abs(acc).max() + 1e-6


def test_polygon_ring_is_the_nominal_arch(voussoir_run_exe, tmp_path):
    """The independent ring, uncut, has the arch's voussoir areas and, shaken, falls
    where the kernel's own arch falls: the test data's geometry is the spec's."""
    from voussoir_post.runner import Runner
    arch = ARCHES[0]
    blocks, joints = ring_blocks(arch, Truth())
    area = [0.5 * abs(sum(p[0] * q[1] - q[0] * p[1] for p, q in zip(poly, poly[1:] + poly[:1])))
            for role, poly in blocks if role == "free"]
    r_in = arch.r_ext_m - arch.thickness_m
    sector = math.radians(arch.embrace_deg / arch.n_voussoirs)
    chord_area = 0.5 * math.sin(sector) * (arch.r_ext_m ** 2 - r_in ** 2)  # two triangles from the centre
    assert len(area) == arch.n_voussoirs and max(abs(a - chord_area) for a in area) < 1e-9
    write_polygon_file(tmp_path / "ring.txt", blocks)
    runner = Runner(bin_dir(), tmp_path)
    motion = {"waveform": "afd", "frequency_hz": 2.0, "rest_s": 1.0}
    solver = {"dt_s": 5e-4}
    out = {"stop_after_collapse_s": 0.1, "collapse_drop_m": 0.5 * arch.thickness_m}
    for amp, falls in ((0.0235, False), (0.0285, True)):  # about 10 % either side of the kernel's threshold
        poly = runner.run_single({"arch": {"polygon_file": str(tmp_path / "ring.txt"), "width_m": arch.width_m,
                                           "density_kg_m3": arch.density_kg_m3},
                                  "motion": {**motion, "amplitude_m": amp}, "solver": solver, "output": out},
                                 "poly", keep=False)
        built = runner.run_single({"arch": {"embrace_deg": arch.embrace_deg, "n_voussoirs": arch.n_voussoirs,
                                            "r_ext_m": arch.r_ext_m, "thickness_m": arch.thickness_m,
                                            "width_m": arch.width_m, "density_kg_m3": arch.density_kg_m3},
                                   "motion": {**motion, "amplitude_m": amp}, "solver": solver, "output": out},
                                  "built", keep=False)
        assert poly.collapsed == built.collapsed == falls, amp


# ------------------------------------------------------------------ fast unit checks


def test_actuator_fit_recovers_gain_and_delay():
    class T:  # the fields of a campaign test that the fit reads
        frequency_hz, amplitude_m, n_attack, n_full, n_decay = 1.6, 0.03, 1, 1, 1
    t = np.arange(0.0, 3.0, 0.005)
    rng = np.random.default_rng(3)
    x = 1.07 * afd_command(t - 0.031, 1.6, 0.03) + 5e-5 * rng.standard_normal(t.size)
    gain, delay, rms = fit_actuator(t, x, T)
    assert abs(gain - 1.07) < 0.005
    assert abs(delay - 0.031) < 0.002
    assert rms < 0.01
