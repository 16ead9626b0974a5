"""Intensity measures of a ground-motion record, computed once on the unscaled record.

The acceleration a [m/s2] is linear between samples ``dt_s`` apart, as the table plays
it (docs/earthquakes.md), and its velocity and displacement are its exact integrals
from rest, with no filter and no baseline correction (src/motion/ground_record.f90
integrates the same way):

- PGA = max |a| [m/s2]; PGV = max |v| [m/s] and PGD = max |d| [m], each with its
  extremum inside a sample interval;
- Arias intensity I_A = pi / (2 g) * integral of a^2 dt [m/s] (g = 9.81 m/s2, the
  kernel's); CAV = integral of |a| dt [m/s]; both exact for linear segments;
- Sa(T): the 5 %-damped pseudo-spectral acceleration omega^2 max |u| [m/s2] of a
  linear oscillator of period T, computed by pyRotd (:data:`PYROTD_VERSION`,
  ``calc_oscillator_resp``: the oscillator's transfer function on the record's Fourier
  spectrum), the record padded with zeros first so that the oscillator's free vibration
  dies out before the discrete transform wraps it round to the start;
- AvgSa(T_low..T_high): the geometric mean of Sa over periods spaced evenly in ln T;
- RotD50(T): of a record that is one horizontal component of a pair, the median over
  the rotation angles 0, 1, ..., 179 deg of the peak pseudo-spectral acceleration of the
  pair rotated by the angle, cos(theta) a_1 + sin(theta) a_2 (Boore 2010; the measure
  of NGA-West2 ground-motion models and so of hazard curves), computed by pyRotd
  (``calc_rotated_oscillator_resp``, every time step: ``method='rigorous'``) on the two
  components padded alike. Both components are scaled by the record's scale, so the
  pair's RotD50 scales with it.

A record scaled by s has s times PGA, PGV, PGD, CAV, Sa and RotD50, and s^2 times the
Arias intensity (:data:`SCALE_POWER`).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..units import G_M_S2

__all__ = ["G_M_S2", "DAMPING", "PYROTD_VERSION", "SCALE_POWER", "RecordIntensity", "velocity_displacement",
           "peak_velocity", "peak_displacement", "arias_intensity", "cav", "spectral_acceleration",
           "avg_sa_periods", "avg_sa", "rotd50", "ROTD_ANGLES_DEG", "record_intensity", "scaled"]

DAMPING = 0.05  #: of the oscillators of Sa and AvgSa
PYROTD_VERSION = "0.6.1"  #: the pyRotd the spectra are computed with (scripts/setup.sh installs it)
#: How each measure grows with the record's scale s: IM(s a) = s^power IM(a).
SCALE_POWER = {"pga": 1, "pgv": 1, "pgd": 1, "arias": 2, "cav": 1, "sa": 1, "avgsa": 1, "rotd50": 1}
#: The rotation angles of RotD50 [deg] (pyRotd's default, Boore 2010's 1 deg steps).
ROTD_ANGLES_DEG = np.arange(0.0, 180.0, 1.0)
#: Free vibration left after the record, in units of 1 / (zeta omega): e^-12 of its amplitude.
_DECAY_TIMES = 12.0


@dataclass(frozen=True)
class RecordIntensity:
    """The intensity measures of one unscaled record."""

    pga_m_s2: float
    pgv_m_s: float
    pgd_m: float
    arias_m_s: float
    cav_m_s: float
    sa_m_s2: float  #: at sa_period_s, 5 % damping
    avgsa_m_s2: float  #: geometric mean of Sa at avgsa_periods_s
    sa_period_s: float
    avgsa_periods_s: tuple[float, ...]
    #: RotD50 of the record's pair at sa_period_s, 5 % damping; NaN: not computed (no pair)
    rotd50_m_s2: float = math.nan

    def value(self, measure: str) -> float:
        """The measure by its name in :data:`SCALE_POWER`."""
        return {"pga": self.pga_m_s2, "pgv": self.pgv_m_s, "pgd": self.pgd_m, "arias": self.arias_m_s,
                "cav": self.cav_m_s, "sa": self.sa_m_s2, "avgsa": self.avgsa_m_s2,
                "rotd50": self.rotd50_m_s2}[measure]


def _check(accel_m_s2, dt_s: float) -> np.ndarray:
    a = np.asarray(accel_m_s2, dtype=float)
    if a.ndim != 1 or a.size < 2 or not np.all(np.isfinite(a)):
        raise InputError("a record needs at least two finite acceleration samples")
    if not (math.isfinite(dt_s) and dt_s > 0.0):
        raise InputError(f"the time step of a record must be > 0 s (got {dt_s!r})")
    return a


def velocity_displacement(accel_m_s2, dt_s: float) -> tuple[np.ndarray, np.ndarray]:
    """(v [m/s], d [m]) at the samples: the exact integrals from rest of the acceleration,
    linear between samples."""
    a = _check(accel_m_s2, dt_s)
    v = np.concatenate(([0.0], np.cumsum(0.5 * dt_s * (a[:-1] + a[1:]))))
    step = dt_s * v[:-1] + dt_s * dt_s * (2.0 * a[:-1] + a[1:]) / 6.0
    return v, np.concatenate(([0.0], np.cumsum(step)))


def peak_velocity(accel_m_s2, dt_s: float) -> float:
    """PGV [m/s]: max |v|, at the samples and where a changes sign inside an interval."""
    a = _check(accel_m_s2, dt_s)
    v, _ = velocity_displacement(a, dt_s)
    peak = float(np.max(np.abs(v)))
    k = np.flatnonzero(a[:-1] * a[1:] < 0.0)
    if k.size:
        tau = dt_s * a[k] / (a[k] - a[k + 1])
        slope = (a[k + 1] - a[k]) / dt_s
        peak = max(peak, float(np.max(np.abs(v[k] + a[k] * tau + 0.5 * slope * tau * tau))))
    return peak


def peak_displacement(accel_m_s2, dt_s: float) -> float:
    """PGD [m]: max |d|, at the samples and where v (quadratic in an interval) is zero
    inside one."""
    a = _check(accel_m_s2, dt_s)
    v, d = velocity_displacement(a, dt_s)
    peak = float(np.max(np.abs(d)))
    k = np.arange(a.size - 1)
    s = (a[1:] - a[:-1]) / dt_s
    # v(tau) = v_k + a_k tau + s_k tau^2 / 2 on (0, dt): its roots there (both of the quadratic, or the linear one)
    with np.errstate(invalid="ignore", divide="ignore"):
        root = np.sqrt(a[:-1] ** 2 - 2.0 * s * v[:-1])
        taus = [np.where(s != 0.0, (-a[:-1] + root) / s, -v[:-1] / a[:-1]),
                np.where(s != 0.0, (-a[:-1] - root) / s, np.nan)]
    for tau in taus:
        inside = np.isfinite(tau) & (tau > 0.0) & (tau < dt_s)
        if inside.any():
            t, j = tau[inside], k[inside]
            x = d[j] + v[j] * t + 0.5 * a[j] * t ** 2 + s[j] * t ** 3 / 6.0
            peak = max(peak, float(np.max(np.abs(x))))
    return peak


def arias_intensity(accel_m_s2, dt_s: float) -> float:
    """I_A = pi / (2 g) * integral of a^2 dt [m/s], exact for a linear between samples."""
    a = _check(accel_m_s2, dt_s)
    return math.pi / (2.0 * G_M_S2) * float(np.sum(dt_s * (a[:-1] ** 2 + a[:-1] * a[1:] + a[1:] ** 2) / 3.0))


def cav(accel_m_s2, dt_s: float) -> float:
    """Cumulative absolute velocity, integral of |a| dt [m/s], exact for a linear
    between samples (an interval where a changes sign is two triangles)."""
    a = _check(accel_m_s2, dt_s)
    lo, hi = np.abs(a[:-1]), np.abs(a[1:])
    same = a[:-1] * a[1:] >= 0.0
    with np.errstate(invalid="ignore", divide="ignore"):
        crossing = (lo ** 2 + hi ** 2) / (2.0 * (lo + hi))
    return float(np.sum(dt_s * np.where(same, 0.5 * (lo + hi), crossing)))


def _pyrotd():
    """The pyRotd module, checked to be :data:`PYROTD_VERSION`; imported where used (the
    rest of the package does without it)."""
    try:
        with warnings.catch_warnings():  # pyRotd imports pkg_resources, which newer setuptools warn about
            warnings.simplefilter("ignore")
            import pyrotd  # noqa: PLC0415
    except ImportError as exc:
        raise InputError(f"the response spectra (Sa, AvgSa) need the PyPI package pyRotd=={PYROTD_VERSION} and "
                         f"setuptools<82 ({exc}; bash scripts/setup.sh installs them)") from exc
    if pyrotd.__version__ != PYROTD_VERSION:
        raise InputError(f"the response spectra are those of pyRotd {PYROTD_VERSION}, but {pyrotd.__version__} is "
                         f"installed (pip install --no-deps pyrotd=={PYROTD_VERSION})")
    return pyrotd


def _periods(periods_s, dt_s: float, damping: float) -> np.ndarray:
    """The periods of a spectrum, checked (finite, above 2 dt), and the damping (in (0, 1))."""
    periods = np.atleast_1d(np.asarray(periods_s, dtype=float))
    if not np.all(np.isfinite(periods) & (periods > 2.0 * dt_s)):
        raise InputError(f"a period of Sa must be finite and above twice the record's time step {dt_s:g} s "
                         f"(got {', '.join(f'{p:g}' for p in periods)} s)")
    if not 0.0 < damping < 1.0:
        raise InputError(f"the damping of Sa must be in (0, 1) (got {damping!r})")
    return periods


def _padded_spectra(records, dt_s: float, longest_period_s: float, damping: float) -> tuple[np.ndarray, list]:
    """(frequencies [Hz], the Fourier spectrum of each record of ``records``), each padded
    with zeros to one even length: the longest record and the free vibration of the
    oscillator of ``longest_period_s`` after it."""
    pad = _DECAY_TIMES * longest_period_s / (2.0 * math.pi * damping)
    n = max(a.size for a in records) + int(math.ceil(pad / dt_s))
    n += n % 2  # an even length: pyRotd's frequencies linspace(0, 1 / (2 dt)) are then the FFT's
    fourier = [np.fft.rfft(np.concatenate((a, np.zeros(n - a.size)))) for a in records]
    return np.linspace(0.0, 1.0 / (2.0 * dt_s), num=fourier[0].size), fourier


def spectral_acceleration(accel_m_s2, dt_s: float, periods_s, damping: float = DAMPING) -> np.ndarray:
    """Sa(T) [m/s2] at each period of ``periods_s``: omega^2 max |u| of the linear
    oscillator of period T and ``damping`` (pyRotd's pseudo-spectral acceleration), the
    record padded with zeros for the oscillator's free vibration to die out."""
    pyrotd = _pyrotd()
    a = _check(accel_m_s2, dt_s)
    periods = _periods(periods_s, dt_s, damping)
    freq_hz, (fourier,) = _padded_spectra([a], dt_s, float(np.max(periods)), damping)
    return np.array([pyrotd.calc_oscillator_resp(freq_hz, fourier, damping, 1.0 / t, peak_resp_only=True,
                                                 osc_type="psa") for t in periods], dtype=float)


def avg_sa_periods(low_s: float, high_s: float, n: int = 10) -> np.ndarray:
    """``n`` periods from ``low_s`` to ``high_s``, evenly spaced in ln T."""
    if not (math.isfinite(low_s) and math.isfinite(high_s) and 0.0 < low_s < high_s) or n < 2:
        raise InputError(f"the periods of AvgSa run from a low to a higher period > 0 s, at least two of them "
                         f"(got {low_s!r} to {high_s!r} s, {n})")
    return np.exp(np.linspace(math.log(low_s), math.log(high_s), n))


def avg_sa(accel_m_s2, dt_s: float, periods_s, damping: float = DAMPING) -> float:
    """AvgSa [m/s2]: the geometric mean of Sa at ``periods_s``."""
    sa = spectral_acceleration(accel_m_s2, dt_s, periods_s, damping)
    return float(np.exp(np.mean(np.log(sa)))) if np.all(sa > 0.0) else 0.0


def rotd50(accel_a_m_s2, accel_b_m_s2, dt_s: float, periods_s, damping: float = DAMPING,
           padded_for_s: float = 0.0) -> np.ndarray:
    """RotD50 [m/s2] at each period of ``periods_s`` of the pair of horizontal components
    ``accel_a_m_s2`` and ``accel_b_m_s2`` (orthogonal, sampled at one ``dt_s``; a shorter
    one is at rest after its end): the median over :data:`ROTD_ANGLES_DEG` of the peak
    pseudo-spectral acceleration of cos(theta) a + sin(theta) b (pyRotd's percentile,
    linear between the sorted peaks), the oscillator's responses rotated at every time
    step. The pair is padded for the free vibration of the longest of ``periods_s`` and
    ``padded_for_s`` (:func:`record_intensity` pads as for its Sa and AvgSa, so that the
    record's Sa and RotD50 are of one padded record)."""
    pyrotd = _pyrotd()
    a, b = _check(accel_a_m_s2, dt_s), _check(accel_b_m_s2, dt_s)
    periods = _periods(periods_s, dt_s, damping)
    freq_hz, fourier = _padded_spectra([a, b], dt_s, max(float(np.max(periods)), padded_for_s), damping)
    out = []
    for t in periods:
        ((_, _, value, _),) = pyrotd.calc_rotated_oscillator_resp(ROTD_ANGLES_DEG, [50.0], freq_hz, fourier, damping,
                                                                  1.0 / t, osc_type="psa", method="rigorous")
        out.append(value)
    return np.array(out, dtype=float)


def record_intensity(accel_m_s2, dt_s: float, sa_period_s: float, avgsa_periods_s,
                     pair_accel_m_s2=None) -> RecordIntensity:
    """Every measure of one unscaled record (acceleration in m/s2); with
    ``pair_accel_m_s2``, the other horizontal component of its pair (same dt), also
    RotD50 at ``sa_period_s`` (else NaN)."""
    a = _check(accel_m_s2, dt_s)
    periods = np.asarray(avgsa_periods_s, dtype=float)
    sa = spectral_acceleration(a, dt_s, np.concatenate(([sa_period_s], periods)))
    avg = float(np.exp(np.mean(np.log(sa[1:])))) if np.all(sa[1:] > 0.0) else 0.0
    return RecordIntensity(pga_m_s2=float(np.max(np.abs(a))), pgv_m_s=peak_velocity(a, dt_s),
                           pgd_m=peak_displacement(a, dt_s), arias_m_s=arias_intensity(a, dt_s), cav_m_s=cav(a, dt_s),
                           sa_m_s2=float(sa[0]), avgsa_m_s2=avg, sa_period_s=float(sa_period_s),
                           avgsa_periods_s=tuple(float(t) for t in periods),
                           rotd50_m_s2=math.nan if pair_accel_m_s2 is None else
                           float(rotd50(a, pair_accel_m_s2, dt_s, [sa_period_s],
                                        padded_for_s=float(np.max(np.concatenate(([sa_period_s], periods)))))[0]))


def scaled(measure: str, value, scale):
    """The measure of the record scaled by ``scale``: value * scale^power (:data:`SCALE_POWER`)."""
    if measure not in SCALE_POWER:
        raise InputError(f"no intensity measure '{measure}' (known: {', '.join(SCALE_POWER)})")
    return np.asarray(value, dtype=float) * np.asarray(scale, dtype=float) ** SCALE_POWER[measure]
