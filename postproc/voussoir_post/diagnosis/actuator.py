"""The table's motion: what the records (or the measured peak accelerations) say of how
the table followed the afd command of docs/measured_data.md (analysis/afd.py).

Every record of an `afd` test is fitted as gain x command(t - delay) by least squares,
which measures the actuator's gain and lag test by test (and so their scatter); without
records, the measured peak accelerations are compared with the commanded motion's own
peak: the attack and decay envelopes add their derivatives to the full cycles' A (2 pi
f)^2, so a table that follows the command exactly peaks 1.049 times above it (1-1-1
cycles; analysis/afd.py), and that is not the actuator's gain.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..analysis.afd import afd_command, afd_peak_accel_per_m
from ..readers.campaign import Campaign, Test

__all__ = ["fit_actuator", "peak_gain", "TableEvidence", "table_evidence"]


def fit_actuator(t_s: np.ndarray, table_x_m: np.ndarray, test: Test, max_delay_s: float = 0.2
                 ) -> tuple[float, float, float]:
    """Least-squares gain and delay of a table record against its command:
    table_x(t) ~ gain command(t - delay). Returns (gain, delay_s, relative rms residual)."""
    x = np.asarray(table_x_m, float) - float(table_x_m[0])
    dt = float(t_s[1] - t_s[0])
    best = (math.inf, 1.0, 0.0)
    delays = np.arange(-0.05, max_delay_s + 1e-12, dt / 4.0)
    for d in delays:
        c = afd_command(t_s - d, test.frequency_hz, test.amplitude_m, test.n_attack, test.n_full, test.n_decay)
        cc = float(c @ c)
        if cc <= 0:
            continue
        g = float(x @ c) / cc
        r = float(((x - g * c) ** 2).sum())
        if r < best[0]:
            best = (r, g, float(d))
    rms = math.sqrt(best[0] / x.size) / max(1e-12, float(np.abs(x).max()))
    return best[1], best[2], rms


def peak_gain(test: Test) -> float | None:
    """Measured peak table acceleration over the commanded motion's true peak (not over
    A (2 pi f)^2): the actuator's gain as a test without a record tells it; None when
    the test does not say."""
    if not (test.peak_accel_m_s2 and test.waveform == "afd" and test.frequency_hz and test.amplitude_m):
        return None
    command = test.amplitude_m * afd_peak_accel_per_m(test.frequency_hz, test.n_attack, test.n_full, test.n_decay)
    return test.peak_accel_m_s2 / command


@dataclass
class TableEvidence:
    """What the records (or the peak accelerations) say of the table."""

    source: str  #: 'records', 'peak_accel' or 'none'
    n: int = 0
    gain: float = 1.0
    gain_se: float = math.nan
    gain_sd: float = math.nan
    delay_s: float = 0.0
    delay_se: float = math.nan
    per_test: list = field(default_factory=list)  #: (test_id, gain, delay_s, rms); delay and rms NaN from peaks

    @property
    def deviates(self) -> bool:
        """Whether the table measurably did not follow the command."""
        if self.source == "none" or self.n == 0:
            return False
        margin = max(0.02, 3.0 * (self.gain_se if math.isfinite(self.gain_se) else 0.0))
        return abs(self.gain - 1.0) > margin


def table_evidence(campaign: Campaign) -> TableEvidence:
    fits = []
    for tid, rec in campaign.records.items():
        test = campaign.tests[tid]
        if test.waveform != "afd" or test.frequency_hz is None or test.amplitude_m is None:
            continue
        g, d, rms = fit_actuator(rec.t_s - rec.t_s[0], rec.table_x_m, test)
        fits.append((tid, g, d, rms))
    if fits:
        gains = np.array([f[1] for f in fits])
        delays = np.array([f[2] for f in fits])
        n = len(fits)
        sd = float(gains.std(ddof=1)) if n > 1 else math.nan
        dsd = float(delays.std(ddof=1)) if n > 1 else math.nan
        return TableEvidence("records", n, float(gains.mean()), sd / math.sqrt(n) if n > 1 else math.nan, sd,
                             float(delays.mean()), dsd / math.sqrt(n) if n > 1 else math.nan, fits)
    ratios = [(tid, g) for tid, g in ((tid, peak_gain(t)) for tid, t in campaign.tests.items()) if g is not None]
    if ratios:
        r = np.array([g for _, g in ratios])
        n = r.size
        sd = float(r.std(ddof=1)) if n > 1 else math.nan
        return TableEvidence("peak_accel", n, float(np.median(r)), sd / math.sqrt(n) if n > 1 else math.nan, sd,
                             per_test=[(tid, float(g), math.nan, math.nan) for tid, g in ratios])
    return TableEvidence("none")

