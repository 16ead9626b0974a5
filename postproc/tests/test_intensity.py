"""The intensity measures of a record (voussoir_post.earthquake.intensity) against
closed forms: the Arias intensity and CAV of a sine over whole cycles, PGV and PGD of a
known motion and of a hand-integrated piecewise-linear acceleration, Sa of a lightly
damped oscillator driven at and off resonance (the steady-state amplitude), Sa of a
record of zeros, how each measure grows with the record's scale, and that none
changes with its sign."""

from __future__ import annotations

import math

import numpy as np
import pytest

from voussoir_post.earthquake import intensity as im
from voussoir_post.errors import InputError

G = 9.81  # the kernel's g (src/core/kinds.f90), which the Arias intensity divides by


def sine(a0, period_s, cycles, per_cycle):
    """a0 sin(2 pi t / T) over whole cycles, ``per_cycle`` samples a cycle (the last
    sample closing the last cycle)."""
    dt = period_s / per_cycle
    t = np.arange(cycles * per_cycle + 1) * dt
    return a0 * np.sin(2.0 * math.pi * t / period_s), dt


def test_arias_of_a_sine_over_whole_cycles():
    """Integral of a0^2 sin^2 over a duration D of whole cycles = a0^2 D / 2, so
    I_A = pi / (2 g) a0^2 D / 2; the linear interpolant of 2000 samples a cycle is
    within (2 pi / 2000)^2 of it, relative."""
    a, dt = sine(3.0, 0.4, 5, 2000)
    duration = 5 * 0.4
    assert im.arias_intensity(a, dt) == pytest.approx(math.pi / (2.0 * G) * 3.0 ** 2 * duration / 2.0, rel=1e-5)


def test_cav_of_a_sine_over_whole_cycles():
    """Integral of |a0 sin| over a duration D of whole cycles = (2 / pi) a0 D."""
    a, dt = sine(2.5, 0.7, 4, 2000)
    assert im.cav(a, dt) == pytest.approx(2.0 / math.pi * 2.5 * 4 * 0.7, rel=1e-5)


def test_cav_of_one_sign_change_is_two_triangles():
    """a from 1 to -3 over dt = 2 s: zero at t = 0.5 s, areas 1 x 0.5 / 2 and 3 x 1.5 / 2."""
    assert im.cav([1.0, -3.0], 2.0) == pytest.approx(0.25 + 2.25, rel=1e-14)


def test_pgv_and_pgd_of_a_known_displacement():
    """d(t) = D (1 - cos wt) / 2 from rest: v = D w sin(wt) / 2, a = D w^2 cos(wt) / 2; over
    one period PGD = D (at T/2) and PGV = D w / 2 (at T/4)."""
    disp, period = 0.12, 1.6
    w = 2.0 * math.pi / period
    n = 4001  # an odd number of samples a period: T/2 falls inside an interval
    dt = period / n
    t = np.arange(n + 1) * dt
    a = disp * w * w * np.cos(w * t) / 2.0
    assert im.peak_displacement(a, dt) == pytest.approx(disp, rel=1e-5)
    assert im.peak_velocity(a, dt) == pytest.approx(disp * w / 2.0, rel=1e-5)


def test_peaks_inside_an_interval_by_hand():
    """a = 1, 1, -5 m/s2 at dt = 1 s: v(1) = 1, d(1) = 0.5; then a = 1 - 6 tau, v = 1 + tau
    - 3 tau^2, zero at tau* = (1 + sqrt 13) / 6 where d = 0.5 + tau* + tau*^2 / 2 - tau*^3
    (above d(2) = 1); PGV: v has its top where a = 0, tau = 1/6: 1 + 1/12."""
    a = [1.0, 1.0, -5.0]
    tau = (1.0 + math.sqrt(13.0)) / 6.0
    assert im.peak_displacement(a, 1.0) == pytest.approx(0.5 + tau + tau ** 2 / 2.0 - tau ** 3, rel=1e-12)
    assert im.peak_velocity(a, 1.0) == pytest.approx(1.0 + 1.0 / 12.0, rel=1e-12)


def _ramped_sine(a0, period_s, dt, ramp_cycles, steady_cycles):
    """a0 sin(wt) whose amplitude rises linearly over ``ramp_cycles``, holds, and falls
    as it rose: the oscillator follows its steady state, without the transient of a
    sudden start or the free vibration of a sudden stop (which, driven above its own
    frequency, would swing up to w / w_n times the steady amplitude)."""
    t = np.arange(int(round((2 * ramp_cycles + steady_cycles) * period_s / dt)) + 1) * dt
    ramp = ramp_cycles * period_s
    envelope = np.minimum(np.minimum(t / ramp, 1.0), (t[-1] - t) / ramp)
    return a0 * envelope * np.sin(2.0 * math.pi * t / period_s)


@pytest.mark.parametrize("zeta", [0.02, 0.05])
def test_sa_at_resonance_is_the_steady_amplitude(zeta):
    """Driven at its own period, u'' + 2 zeta w u' + w^2 u = -a0 sin(wt) settles at |u| =
    a0 / (2 zeta w^2), so Sa = w^2 max |u| = a0 / (2 zeta)."""
    period, a0 = 0.5, 1.3
    a = _ramped_sine(a0, period, period / 200, 60, 60)
    sa = im.spectral_acceleration(a, period / 200, [period], damping=zeta)[0]
    assert sa == pytest.approx(a0 / (2.0 * zeta), rel=1e-2)


@pytest.mark.parametrize("ratio", [0.6, 1.5])
def test_sa_off_resonance_is_the_steady_amplitude(ratio):
    """Driven at w = ratio x w_n: the steady amplitude |u| = a0 / sqrt((w_n^2 - w^2)^2 +
    (2 zeta w_n w)^2), and Sa = w_n^2 |u|."""
    period_n, a0, zeta = 0.8, 2.0, 0.05
    w_n = 2.0 * math.pi / period_n
    w = ratio * w_n
    period = 2.0 * math.pi / w
    a = _ramped_sine(a0, period, period / 200, 60, 60)
    expected = w_n ** 2 * a0 / math.sqrt((w_n ** 2 - w ** 2) ** 2 + (2.0 * zeta * w_n * w) ** 2)
    assert im.spectral_acceleration(a, period / 200, [period_n], zeta)[0] == pytest.approx(expected, rel=1e-2)


def test_sa_of_a_record_of_zeros_is_zero():
    zeros = np.zeros(500)
    assert im.spectral_acceleration(zeros, 0.01, [0.2, 1.0, 3.0]).tolist() == [0.0, 0.0, 0.0]
    assert im.avg_sa(zeros, 0.01, im.avg_sa_periods(0.2, 3.0)) == 0.0
    rec = im.record_intensity(zeros, 0.01, 1.0, im.avg_sa_periods(0.2, 3.0))
    assert (rec.pga_m_s2, rec.pgv_m_s, rec.pgd_m, rec.arias_m_s, rec.cav_m_s, rec.sa_m_s2, rec.avgsa_m_s2) == \
        (0.0,) * 7


def test_avgsa_periods_and_mean():
    """Ten periods evenly spread in ln T from 0.2 to 3 s; AvgSa is the geometric mean of Sa."""
    periods = im.avg_sa_periods(0.2, 3.0)
    assert periods.size == 10 and periods[0] == pytest.approx(0.2) and periods[-1] == pytest.approx(3.0)
    assert np.allclose(np.diff(np.log(periods)), math.log(15.0) / 9.0)
    rng = np.random.default_rng(3)
    a = rng.normal(0.0, 1.0, 3000)
    sa = im.spectral_acceleration(a, 0.01, periods)
    assert im.avg_sa(a, 0.01, periods) == pytest.approx(float(np.prod(sa)) ** (1.0 / 10.0), rel=1e-12)


def test_each_measure_scales_with_the_record():
    """A record scaled by s: PGA, PGV, PGD, CAV, Sa, AvgSa times s, Arias times s^2."""
    rng = np.random.default_rng(11)
    a = rng.normal(0.0, 2.0, 2000) * np.hanning(2000)
    periods = im.avg_sa_periods(0.2, 2.0)
    one = im.record_intensity(a, 0.01, 0.5, periods)
    s = 2.7
    big = im.record_intensity(s * a, 0.01, 0.5, periods)
    for name, power in (("pga", 1), ("pgv", 1), ("pgd", 1), ("arias", 2), ("cav", 1), ("sa", 1), ("avgsa", 1)):
        assert big.value(name) == pytest.approx(s ** power * one.value(name), rel=1e-12), name
        assert im.scaled(name, one.value(name), s) == pytest.approx(big.value(name), rel=1e-12), name
    with pytest.raises(InputError, match="no intensity measure 'pgx'"):
        im.scaled("pgx", 1.0, 2.0)


def test_every_measure_is_blind_to_the_sign_of_the_record():
    """A record played reversed (&sweep record_polarity, -a, its pair -b too) has every
    measure of the record: what voussoir-post fragility --im gives a reversed row."""
    rng = np.random.default_rng(13)
    a, b = rng.normal(0.0, 2.0, 1500) * np.hanning(1500), rng.normal(0.0, 1.0, 1500) * np.hanning(1500)
    periods = im.avg_sa_periods(0.2, 2.0)
    one = im.record_intensity(a, 0.01, 0.5, periods, b)
    flipped = im.record_intensity(-a, 0.01, 0.5, periods, -b)
    assert one.pga_m_s2 == np.max(np.abs(a))
    for name in im.SCALE_POWER:
        assert flipped.value(name) == pytest.approx(one.value(name), rel=1e-12), name


def test_bad_records_and_periods_are_refused():
    with pytest.raises(InputError, match="at least two finite"):
        im.arias_intensity([1.0, math.nan], 0.01)
    with pytest.raises(InputError, match="time step"):
        im.cav([1.0, 2.0], 0.0)
    with pytest.raises(InputError, match="above twice the record's time step"):
        im.spectral_acceleration(np.ones(10), 0.01, [0.01])
    with pytest.raises(InputError, match="the periods of AvgSa"):
        im.avg_sa_periods(3.0, 0.2)


# ------------------------------------------------------------------ RotD50 of a pair

def burst(rng, n, dt=0.01, centre_s=6.0, width_s=3.0):
    """A random record of n samples in a Gaussian envelope (zero at both ends)."""
    t = np.arange(n) * dt
    return rng.normal(0.0, 1.0, n) * np.exp(-((t - centre_s) / width_s) ** 2)


def test_rotd50_of_a_component_and_zero_is_cos_45_of_its_sa():
    """b = 0: the oscillator rotated by theta responds cos(theta) u_a(t) (it is linear), its
    peak |cos theta| Sa_a; over theta = 0, 1, ..., 179 deg, 89 angles give less than
    cos 45 deg, 89 more, and 45 and 135 deg exactly it: the median is cos 45 deg Sa_a."""
    a = burst(np.random.default_rng(21), 2000)
    periods = [0.2, 0.5, 1.0, 2.0]
    sa = im.spectral_acceleration(a, 0.01, periods)
    assert im.rotd50(a, np.zeros_like(a), 0.01, periods) == pytest.approx(math.cos(math.pi / 4) * sa, rel=1e-9)
    # and the pair the other way round: the same by symmetry (|sin theta| has the same median)
    assert im.rotd50(np.zeros_like(a), a, 0.01, periods) == pytest.approx(math.cos(math.pi / 4) * sa, rel=1e-9)


def test_rotd50_of_two_identical_components_is_their_sa():
    """b = a: the rotated response is (cos theta + sin theta) u_a = sqrt(2) sin(theta + 45 deg)
    u_a, its peak sqrt(2) |sin(theta + 45 deg)| Sa_a; theta + 45 deg runs over 180
    consecutive whole degrees, a full period of |sin|, whose median is sin 45 deg: RotD50 =
    sqrt(2) sin 45 deg Sa_a = Sa_a."""
    a = burst(np.random.default_rng(22), 2000)
    periods = [0.3, 1.0]
    assert im.rotd50(a, a, 0.01, periods) == pytest.approx(im.spectral_acceleration(a, 0.01, periods), rel=1e-9)


def test_rotd50_of_two_components_apart_in_time_is_the_median_of_the_larger_peak():
    """a shakes first, b (of Sa 0.8 times a's) 60 s later, when a's oscillator (T = 0.3 s, 5 %: decay time 0.95 s)
    has died out (e^-60): at angle theta the peak is max(|cos theta| Sa_a, |sin theta| Sa_b),
    each from its own component's Sa; RotD50 is the median of it over the 180 whole
    degrees (numpy's median of the closed form, not pyRotd's rotation)."""
    rng = np.random.default_rng(23)
    a_alone, b_alone = burst(rng, 1200), burst(rng, 1200)
    sa_0 = [float(im.spectral_acceleration(x, 0.01, [0.3])[0]) for x in (a_alone, b_alone)]
    b_alone *= 0.8 * sa_0[0] / sa_0[1]
    gap = np.zeros(6000)
    a = np.concatenate((a_alone, gap, np.zeros(1200)))
    b = np.concatenate((np.zeros(1200), gap, b_alone))
    sa_a = float(im.spectral_acceleration(a_alone, 0.01, [0.3])[0])
    sa_b = float(im.spectral_acceleration(b_alone, 0.01, [0.3])[0])
    theta = np.radians(np.arange(180.0))
    expected = float(np.median(np.maximum(np.abs(np.cos(theta)) * sa_a, np.abs(np.sin(theta)) * sa_b)))
    # the pair's answer is neither component's alone (cos 45 deg Sa of the larger)
    assert expected > 1.05 * math.cos(math.pi / 4) * max(sa_a, sa_b)
    assert im.rotd50(a, b, 0.01, [0.3])[0] == pytest.approx(expected, rel=1e-6)


def test_rotd50_scales_with_the_pair_and_needs_a_pair_of_one_time_step():
    """Both components scaled by s: RotD50 times s (the IDA's scale applies to the pair);
    a shorter second component is at rest after its end (the same as padded with zeros);
    record_intensity gives RotD50 with a pair, NaN without."""
    rng = np.random.default_rng(24)
    a, b = burst(rng, 2000), burst(rng, 1500)
    one = im.rotd50(a, b, 0.01, [0.4, 1.2])
    assert im.rotd50(2.7 * a, 2.7 * b, 0.01, [0.4, 1.2]) == pytest.approx(2.7 * one, rel=1e-12)
    assert im.rotd50(a, np.concatenate((b, np.zeros(500))), 0.01, [0.4, 1.2]) == pytest.approx(one, rel=1e-12)
    periods = im.avg_sa_periods(0.2, 2.0)
    # record_intensity pads as for its longest period (2 s), as its Sa is
    at_04 = float(im.rotd50(a, b, 0.01, [0.4], padded_for_s=2.0)[0])
    assert at_04 == pytest.approx(one[0], rel=1e-5)  # the padding's wrap-round: e^-12 of the free vibration
    assert im.record_intensity(a, 0.01, 0.4, periods, b).value("rotd50") == pytest.approx(at_04, rel=1e-12)
    assert math.isnan(im.record_intensity(a, 0.01, 0.4, periods).value("rotd50"))
    assert im.SCALE_POWER["rotd50"] == 1
    with pytest.raises(InputError, match="above twice the record's time step"):
        im.rotd50(a, b, 0.01, [0.01])
