"""The commanded afd table motion (shared/MEASURED_DATA.md): its displacement and
acceleration over time from one envelope, and two accelerations that a figure or a table
may quote, named apart.

- the *full-cycle acceleration* A (2 pi f)^2: the amplitude of the acceleration in the
  full cycles, what the field usually quotes;
- the *peak acceleration*: the largest |a| of the whole motion. The attack and decay
  envelopes add their own derivatives to it, so it is higher (1.0492 A (2 pi f)^2 for
  1-1-1 cycles, at any frequency: the ratio depends on the numbers of cycles only).

The motion is x(t) = A e(t) sin(2 pi f t), with e = sin^2(pi t / (2 T_a)) in the attack,
1 in the full cycles and cos^2(pi tau / (2 T_d)) in the decay (src/motion/motion.f90).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["full_cycle_accel_m_s2", "afd_command", "afd_accel_per_m", "afd_peak_accel_per_m", "afd_peak_accel_m_s2"]


def full_cycle_accel_m_s2(amplitude_m, frequency_hz):
    """A (2 pi f)^2 [m/s2]: the acceleration amplitude of the full cycles."""
    return np.asarray(amplitude_m, dtype=float) * (2.0 * math.pi * np.asarray(frequency_hz, dtype=float)) ** 2


def _envelope(t: np.ndarray, frequency_hz: float, n_attack: int, n_full: int, n_decay: int
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The envelope e(t) of the afd motion and its first two derivatives (0 before and
    after the motion)."""
    ta, tf, td = n_attack / frequency_hz, n_full / frequency_hz, n_decay / frequency_hz
    e, de, d2e = np.zeros_like(t), np.zeros_like(t), np.zeros_like(t)
    if ta > 0:
        w = math.pi / ta
        m = (t >= 0) & (t < ta)
        e[m], de[m], d2e[m] = (np.sin(np.pi * t[m] / (2 * ta)) ** 2, 0.5 * w * np.sin(w * t[m]),
                               0.5 * w * w * np.cos(w * t[m]))
    m = (t >= ta) & (t < ta + tf)
    e[m] = 1.0
    if td > 0:
        w = math.pi / td
        m = (t >= ta + tf) & (t < ta + tf + td)
        tau = t[m] - ta - tf
        e[m], de[m], d2e[m] = (np.cos(np.pi * tau / (2 * td)) ** 2, -0.5 * w * np.sin(w * tau),
                               -0.5 * w * w * np.cos(w * tau))
    return e, de, d2e


def afd_command(t_s, frequency_hz: float, amplitude_m: float, n_attack: int = 1, n_full: int = 1,
                n_decay: int = 1) -> np.ndarray:
    """The commanded afd displacement [m] of shared/MEASURED_DATA.md at the times ``t_s``."""
    t = np.asarray(t_s, dtype=float)
    e = _envelope(t, frequency_hz, n_attack, n_full, n_decay)[0]
    return amplitude_m * e * np.sin(2 * np.pi * frequency_hz * t)


def afd_accel_per_m(t_s, frequency_hz: float, n_attack: int = 1, n_full: int = 1, n_decay: int = 1) -> np.ndarray:
    """Table acceleration [m/s2 per metre of amplitude] at the times ``t_s`` (exact
    second derivative of the displacement, as src/motion/motion.f90 evaluates it)."""
    t = np.asarray(t_s, dtype=float)
    e, de, d2e = _envelope(t, frequency_hz, n_attack, n_full, n_decay)
    om = 2.0 * math.pi * frequency_hz
    s, c = np.sin(om * t), np.cos(om * t)
    return d2e * s + 2.0 * de * om * c - e * om * om * s


def afd_peak_accel_per_m(frequency_hz: float, n_attack: int = 1, n_full: int = 1, n_decay: int = 1) -> float:
    """The true peak |a| [m/s2 per metre of amplitude] of the afd motion: sampled at
    4000 points a cycle, then refined about the largest sample (to about 1e-12)."""
    if not (frequency_hz > 0):
        return math.nan
    n = n_attack + n_full + n_decay
    t_end = n / frequency_hz
    t = np.linspace(0.0, t_end, 4000 * n + 1)
    a = np.abs(afd_accel_per_m(t, frequency_hz, n_attack, n_full, n_decay))
    k = int(np.argmax(a))
    lo, hi = t[max(k - 1, 0)], t[min(k + 1, t.size - 1)]
    for _ in range(3):
        fine = np.linspace(lo, hi, 2001)
        af = np.abs(afd_accel_per_m(fine, frequency_hz, n_attack, n_full, n_decay))
        j = int(np.argmax(af))
        lo, hi = fine[max(j - 1, 0)], fine[min(j + 1, fine.size - 1)]
    return float(max(af.max(), a.max()))


def afd_peak_accel_m_s2(amplitude_m, frequency_hz, n_attack: int = 1, n_full: int = 1, n_decay: int = 1):
    """The true peak table acceleration [m/s2] of afd motions (arrays broadcast)."""
    amp, freq = np.broadcast_arrays(np.asarray(amplitude_m, dtype=float), np.asarray(frequency_hz, dtype=float))
    per_m = np.array([afd_peak_accel_per_m(float(f), n_attack, n_full, n_decay) if np.isfinite(f) else math.nan
                      for f in freq.reshape(-1)]).reshape(freq.shape)
    out = amp * per_m
    return float(out) if out.ndim == 0 else out
