"""The two accelerations of an afd motion, named apart: the true peak against dense
sampling of the closed-form displacement (differentiated twice here, by second
differences), and the full-cycle A (2 pi f)^2."""

from __future__ import annotations

import math

import numpy as np
import pytest

from voussoir_post.analysis.afd import afd_peak_accel_m_s2, afd_peak_accel_per_m, full_cycle_accel_m_s2


def _dense_peak(amp_m, f_hz, n_attack, n_full, n_decay, per_cycle=200000):
    """Largest |x''| of x = A e(t) sin(2 pi f t) (docs/measured_data.md's envelopes),
    x'' by second differences on a grid of `per_cycle` points a cycle."""
    ta, tf, td = n_attack / f_hz, n_full / f_hz, n_decay / f_hz
    t = np.linspace(0.0, ta + tf + td, per_cycle * (n_attack + n_full + n_decay) + 1)
    h = t[1] - t[0]
    e = np.ones_like(t)
    if n_attack:
        e = np.where(t < ta, np.sin(math.pi * t / (2 * ta)) ** 2, e)
    if n_decay:
        e = np.where(t >= ta + tf, np.cos(math.pi * (t - ta - tf) / (2 * td)) ** 2, e)
    x = amp_m * e * np.sin(2 * math.pi * f_hz * t)
    return float(np.abs((x[2:] - 2 * x[1:-1] + x[:-2]) / h ** 2).max())


@pytest.mark.parametrize("amp_m, f_hz, cycles", [(0.046, 1.25, (1, 1, 1)), (0.010, 3.0, (2, 3, 1)),
                                                  (0.020, 0.75, (1, 0, 1))])
def test_true_peak_against_dense_sampling(amp_m, f_hz, cycles):
    expected = _dense_peak(amp_m, f_hz, *cycles)
    assert afd_peak_accel_m_s2(amp_m, f_hz, *cycles) == pytest.approx(expected, rel=1e-5)


def test_seed_run_peak_is_above_the_full_cycle_acceleration():
    # seed_156.nml: 46 mm at 1.25 Hz, 1-1-1 cycles; A (2 pi f)^2 = 2.838 m/s2, and the run's
    # table printed a largest sample of 2.975 m/s2 (issue 26).
    full = 0.046 * (2 * math.pi * 1.25) ** 2
    assert float(full_cycle_accel_m_s2(0.046, 1.25)) == pytest.approx(full, rel=1e-15)
    peak = afd_peak_accel_m_s2(0.046, 1.25)
    assert 2.975 <= peak <= 2.975 * 1.002
    assert peak / full == pytest.approx(_dense_peak(1.0, 1.25, 1, 1, 1) / (2 * math.pi * 1.25) ** 2, rel=1e-5)


def test_ratio_depends_on_the_cycles_not_the_frequency():
    r = [afd_peak_accel_per_m(f) / (2 * math.pi * f) ** 2 for f in (0.5, 1.25, 4.0)]
    assert max(r) - min(r) < 1e-9
    arr = afd_peak_accel_m_s2(np.array([0.01, 0.02]), np.array([1.0, 2.0]))
    assert arr == pytest.approx([0.01 * afd_peak_accel_per_m(1.0), 0.02 * afd_peak_accel_per_m(2.0)])
