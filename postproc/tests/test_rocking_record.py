"""A rigid block under a real record against Housner's rocking equation integrated here.

The 0.2 m x 1.0 m block (half-width b = 0.1 m, half-height h = 0.5 m) stands on the
table under El Centro 1940 (180), unscaled: peak 0.28 g, above its uplift threshold
g b/h = 0.2 g. The program's NSCD answer (two contact points, Signorini and Coulomb,
no restitution) must follow the classical model of Housner (1963), written and
integrated in this file only:

    theta'' = -p^2 [ s sin(alpha - s theta) - (a_g / g) cos(alpha - s theta) ],
    s = sign(theta), p^2 = 3 g / (4 R), R = sqrt(b^2 + h^2), alpha = atan(b / h),

(theta > 0 counter-clockwise, pivoting on the left corner, driven by a table
acceleration a_g > 0 to the right), at rest until |a_g| first exceeds g tan(alpha),
each impact (theta crossing 0) located by bisection and followed by
theta'+ = eta theta'-, eta = 1 - 1.5 sin^2(alpha) (angular momentum about the new
corner). RK4 with a step that divides the record's 0.01 s, so the piecewise-linear
acceleration is smooth inside every step.

DESIGN.md: rocking is sensitive to the time step (the program departs from Housner after
a few seconds at dt = 1e-4 s, and still at 2e-5 s); at dt = 1e-5 s it must agree over
the first 5.4 s of rocking (14 impacts) within 10 % of the peak rotation (6 % when this
test was written), and the disagreement must shrink at dt = 5e-6 s (it is the program's
discretisation error, not a different model).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from conftest import run_executable
from test_accelerogram import block_nml, read_at2_here
from voussoir_post.earthquake.records import record_path
from voussoir_post.readers.results import read_run

G = 9.81
B, H = 0.1, 0.5
LEAD_S = 0.5  # the table is still before the first sample
END_S = 8.0  # compared window: [0, END_S] of simulated time


def housner_rocking(accel: np.ndarray, dt_rec: float, start_s: float, end_s: float, step_s: float):
    """theta(t) on the grid k step_s of Housner's rocking block (see the module doc)."""
    n_sub = round(dt_rec / step_s)
    assert abs(n_sub * step_s - dt_rec) < 1e-12 and abs(round(start_s / step_s) * step_s - start_s) < 1e-12
    radius, alpha = math.hypot(B, H), math.atan2(B, H)
    p2 = 3.0 * G / (4.0 * radius)
    eta = 1.0 - 1.5 * math.sin(alpha) ** 2
    uplift = G * math.tan(alpha)

    def a_g(t):
        u = (t - start_s) / dt_rec
        if u < 0.0 or u > accel.size - 1:
            return 0.0
        i = min(int(u), accel.size - 2)
        return accel[i] + (u - i) * (accel[i + 1] - accel[i])

    def rhs(t, th, w, s):
        return w, -p2 * (s * math.sin(alpha - s * th) - a_g(t) / G * math.cos(alpha - s * th))

    def rk4(t, th, w, s, dt):
        k1 = rhs(t, th, w, s)
        k2 = rhs(t + dt / 2, th + dt / 2 * k1[0], w + dt / 2 * k1[1], s)
        k3 = rhs(t + dt / 2, th + dt / 2 * k2[0], w + dt / 2 * k2[1], s)
        k4 = rhs(t + dt, th + dt * k3[0], w + dt * k3[1], s)
        return (th + dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]),
                w + dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]))

    n = round(end_s / step_s)
    theta = np.zeros(n + 1)
    th, w, s = 0.0, 0.0, 0  # s = 0: at rest on both corners
    for k in range(n):
        t0 = k * step_s
        left = step_s
        while left > 0.0:
            t = t0 + step_s - left
            if s == 0:
                a0, a1 = a_g(t), a_g(t + left)  # linear inside the step
                if abs(a0) > uplift:
                    tc = t
                elif abs(a1) > uplift:
                    target = math.copysign(uplift, a1)
                    tc = t + (target - a0) / (a1 - a0) * left
                else:
                    break
                s = 1 if a_g(tc) > 0 else -1
                left -= tc - t
                th, w = 0.0, 0.0
                continue
            th1, w1 = rk4(t, th, w, s, left)
            if s * th1 > 0.0:
                th, w, left = th1, w1, 0.0
                continue
            lo, hi = 0.0, left  # impact inside: bisection on the length of the sub-step
            for _ in range(80):
                mid = 0.5 * (lo + hi)
                if s * rk4(t, th, w, s, mid)[0] > 0.0:
                    lo = mid
                else:
                    hi = mid
            tau = 0.5 * (lo + hi)
            w_before = rk4(t, th, w, s, tau)[1]
            th, w, s = 0.0, eta * w_before, -s
            left -= tau
            if abs(w) < 1e-9 or tau == 0.0:  # impacts accumulating: the block comes to rest
                th, w, s = 0.0, 0.0, 0
        theta[k + 1] = th
    return np.arange(n + 1) * step_s, theta


@pytest.fixture(scope="module")
def elcentro():
    accel_g, dt = read_at2_here(record_path("ELC180"))
    return record_path("ELC180"), G * accel_g, dt


@pytest.fixture(scope="module")
def housner(elcentro):
    _, accel, dt = elcentro
    t, theta = housner_rocking(accel, dt, LEAD_S, END_S, 5.0e-5)
    # The reference is converged: halving its step changes it by far less than the
    # tolerance of the comparison below.
    t2, theta2 = housner_rocking(accel, dt, LEAD_S, END_S, 1.0e-4)
    assert np.abs(np.interp(t2, t, theta) - theta2).max() < 1e-3 * np.abs(theta).max()
    return t, theta


def simulated_rotation(exe, folder, record, dt_s):
    nml = block_nml(folder, record, f"elcentro_dt{dt_s:g}.h5", lead_s=LEAD_S, duration_s=END_S, dt_s=dt_s,
                    every=max(1, round(1.0e-4 / dt_s)))
    run_executable([exe, nml], folder)
    run = read_run(folder / f"elcentro_dt{dt_s:g}.h5")
    free = int(np.flatnonzero(run.body_role == 1)[0])
    return run.time_s, run.body_position[:, free, 2]


def test_block_under_el_centro_follows_housner(voussoir_run_exe, tmp_path, elcentro, housner):
    record, _, _ = elcentro
    t_ref, theta_ref = housner
    peak = np.abs(theta_ref).max()
    impacts = np.count_nonzero(np.diff(np.sign(theta_ref[np.abs(theta_ref) > 0])) != 0)
    assert peak > 0.05 and impacts >= 10  # the window holds real rocking, not a wobble
    errors = {}
    for dt_s in (1.0e-5, 5.0e-6):
        t, theta = simulated_rotation(voussoir_run_exe, tmp_path, record, dt_s)
        assert t[-1] == pytest.approx(END_S, abs=1e-6)
        errors[dt_s] = np.abs(theta - np.interp(t, t_ref, theta_ref)).max()
    assert errors[1.0e-5] < 0.10 * peak, f"max |theta - theta_Housner| = {errors[1.0e-5]:.4f} rad, peak {peak:.4f}"
    assert errors[5.0e-6] < 0.75 * errors[1.0e-5], errors  # converging towards Housner with the step


def test_uplift_starts_when_the_record_first_exceeds_g_b_over_h(voussoir_run_exe, tmp_path, elcentro, housner):
    record, accel, dt = elcentro
    # First time |a_g| > g b/h, on the linear interpolation of the record.
    threshold = G * B / H
    i = int(np.argmax(np.abs(accel) > threshold))
    a0, a1 = accel[i - 1], accel[i]
    target = math.copysign(threshold, a1)
    t_star = LEAD_S + (i - 1 + (target - a0) / (a1 - a0)) * dt
    t, theta = simulated_rotation(voussoir_run_exe, tmp_path, record, 1.0e-5)
    assert np.abs(theta[t < t_star]).max() < 1e-7, "the block moved before the record reached g b/h"
    # Rotation grows from zero like (t - t*)^3: compare the time it reaches 1e-5 rad
    # with Housner's (which starts exactly at t*).
    t_ref, theta_ref = housner
    t_sim = t[np.argmax(np.abs(theta) > 1e-5)]
    t_hou = t_ref[np.argmax(np.abs(theta_ref) > 1e-5)]
    assert t_star < t_sim and t_sim - t_star < 0.05
    assert t_sim == pytest.approx(t_hou, abs=2e-3)
    # theta > 0 is counter-clockwise: the block tips towards -x when the table pushes to +x.
    assert np.sign(theta[np.argmax(np.abs(theta) > 1e-5)]) == np.sign(a1)
