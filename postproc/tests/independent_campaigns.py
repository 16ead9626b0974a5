"""Test campaigns made by a path independent of the diagnosis's models.

The diagnosis models its candidates as parameters of the kernel's arch builder
(`&arch contact_inset_m`, `friction`, `thickness_m`, `restrained_springings`,
`&motion table_gain`). A test campaign made through those same parameters, on the same
grid and time step, is an inverse crime: it can only confirm the code's own
assumptions. The campaigns here are made another way:

- the arch is a polygon file written by this module's own geometry (`ring_blocks`):
  contact edges are *chamfers* cut off the voussoirs' corners, a thinner ring is a ring
  of thinner polygons, brackets are driven blocks standing off the bottom voussoirs by a
  gap, and a gap at the intrados (an effect outside every candidate) is a cut of the
  intrados corners alone;
- a table with an actuator is a second-order system driven by the command, integrated
  here and played to the kernel as an accelerogram;
- the time step is finer than the diagnosis's (5e-4 s against 1e-3 s), truth values lie
  off the diagnosis's grids, and the noise has its own seed;
- hinges are found here from the blocks' motion, not by the kernel's hinge monitor.

Only the kernel's contact dynamics is shared: that is what the diagnosis is about.
Nothing in the files written says what the truth was.
"""

from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from voussoir_post.analysis.afd import afd_command
from voussoir_post.readers.campaign import Specimen
from voussoir_post.runner import Runner

G = 9.81


@dataclass(frozen=True)
class Arch:
    """A specimen in the units of specimens.csv, and the frequencies it is ramped at."""

    specimen_id: str
    embrace_deg: float
    n_voussoirs: int
    frequencies_hz: tuple[float, ...]
    r_ext_m: float = 0.508
    thickness_m: float = 0.071
    width_m: float = 0.145
    density_kg_m3: float = 700.0
    friction: float = 0.5

    def specimen(self) -> Specimen:
        """The arch as a campaign's specimens.csv declares it (the nominal specimen)."""
        return Specimen(self.specimen_id, self.embrace_deg, self.n_voussoirs, self.r_ext_m, self.thickness_m,
                        self.width_m, self.density_kg_m3, self.friction)


ARCHES = (Arch("W156", 156.0, 13, (1.25, 2.0)),
          Arch("W132", 132.0, 11, (1.6, 2.5)),
          Arch("W118", 118.0, 10, (2.0, 3.0)))


@dataclass(frozen=True)
class Truth:
    """What really happens, in terms of the generated blocks and table (never written)."""

    chamfer_m: float = 0.0  #: 45-degree chamfer of every voussoir corner (leg length)
    intrados_cut_m: float = 0.0  #: chamfer of the intrados corners only (outside the catalogue)
    thickness_factor: float = 1.0  #: ring thickness about its mean radius
    friction: float | None = None  #: true Coulomb coefficient (None: nominal)
    bracket_gap_m: float | None = None  #: driven brackets beside both bottom voussoirs, this far off
    bracket_specimens: tuple[str, ...] | None = None  #: the specimens that have them (None: all)
    actuator_hz: float | None = None  #: natural frequency of a second-order actuator
    actuator_damping: float = 0.2  #: its damping ratio


# ---------------------------------------------------------------- geometry


def _polar(r: float, a_deg: float) -> np.ndarray:
    a = math.radians(a_deg)
    return np.array([r * math.cos(a), r * math.sin(a)])


def _cut_corners(poly: list[np.ndarray], cuts: list[float]) -> list[np.ndarray]:
    """Cut corner k of a convex polygon by `cuts[k]` along both of its edges."""
    out = []
    n = len(poly)
    for k in range(n):
        c = cuts[k]
        if c <= 0.0:
            out.append(poly[k])
            continue
        prev, here, nxt = poly[k - 1], poly[k], poly[(k + 1) % n]
        out.append(here + c * (prev - here) / np.linalg.norm(prev - here))
        out.append(here + c * (nxt - here) / np.linalg.norm(nxt - here))
    return out


def ring_blocks(arch: Arch, truth: Truth) -> tuple[list[tuple[str, list[np.ndarray]]], list[dict]]:
    """The blocks of an arch as it really is, and its joints for the hinge watch.

    Voussoir j (1..n, from the left springing) spans the angles from 90 + e/2 - (j-1) d
    to 90 + e/2 - j d (e the embrace, d = e / n); its corners are on circles about the
    mean radius. Returns [(role, vertices)], roles 'free' or 'driven', and per joint
    (0..n) the bodies on each side (indices into the blocks) and its intrados and
    extrados points.
    """
    t = truth.thickness_factor * arch.thickness_m
    r_mean = arch.r_ext_m - 0.5 * arch.thickness_m
    r_in, r_out = r_mean - 0.5 * t, r_mean + 0.5 * t
    n = arch.n_voussoirs
    d = arch.embrace_deg / n
    angles = [90.0 + 0.5 * arch.embrace_deg - j * d for j in range(n + 1)]
    inner = [_polar(r_in, a) for a in angles]
    outer = [_polar(r_out, a) for a in angles]
    blocks: list[tuple[str, list[np.ndarray]]] = []
    for j in range(1, n + 1):
        # corners: inner left, inner right, outer right, outer left (counter-clockwise
        # for a voussoir seen from the centre is clockwise; the reader reorients)
        poly = [inner[j - 1], inner[j], outer[j], outer[j - 1]]
        cuts = [truth.chamfer_m + truth.intrados_cut_m, truth.chamfer_m + truth.intrados_cut_m,
                truth.chamfer_m, truth.chamfer_m]
        blocks.append(("free", _cut_corners(poly, cuts)))
    # Foundations: a block of depth t below each springing face, along the ring's tangent.
    for k, (p_in, p_out, sign) in enumerate(((inner[0], outer[0], 1.0), (inner[n], outer[n], -1.0))):
        a = math.radians(angles[0] if k == 0 else angles[n])
        tangent = sign * np.array([-math.sin(a), math.cos(a)])  # away from the ring
        depth = max(t, 0.1)
        blocks.append(("driven", [p_in, p_out, p_out + depth * tangent, p_in + depth * tangent]))
    if truth.bracket_gap_m is not None and (truth.bracket_specimens is None
                                            or arch.specimen_id in truth.bracket_specimens):
        # Brackets carried by the table, standing off the extrados of each bottom
        # voussoir by the gap, over its outer half.
        for j, k0, k1 in ((1, 0, 1), (n, n, n - 1)):
            a0, a1 = outer[k0], outer[k1]
            mid = 0.5 * (a0 + a1)
            normal = mid / np.linalg.norm(mid)
            p0 = a0 + truth.bracket_gap_m * normal
            p1 = mid + truth.bracket_gap_m * normal
            blocks.append(("driven", [p0, p1, p1 + 0.05 * normal, p0 + 0.05 * normal]))
    joints = []
    for j in range(n + 1):
        left = j - 1 if j > 0 else n  # block index of voussoir j (or the left foundation)
        right = j if j < n else n + 1
        joints.append({"bodies": (left, right), "intrados": inner[j], "extrados": outer[j]})
    return blocks, joints


def write_polygon_file(path: Path, blocks) -> None:
    lines = ["# Voussoirs and table blocks of a test arch (m)."]
    for role, poly in blocks:
        lines.append(f"block {role}")
        lines += [f"{p[0]:.9f} {p[1]:.9f}" for p in poly]
    path.write_text("\n".join(lines) + "\n")


# ---------------------------------------------------------------- the table


def actuator_record(frequency_hz: float, amplitude_m: float, gain: float, truth: Truth, dt_s: float = 5e-4,
                    tail_s: float = 3.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Table displacement and acceleration of a second-order actuator
    x'' + 2 z w x' + w^2 x = w^2 u(t), u the afd command (times a test gain), from rest;
    integrated by the exact discrete solution of a linear system (matrix exponential of
    the 2x2 state matrix, the input linear within each step)."""
    w = 2.0 * math.pi * truth.actuator_hz
    z = truth.actuator_damping
    t = np.arange(0.0, 3.0 / frequency_hz + tail_s, dt_s)
    u = gain * afd_command(t, frequency_hz, amplitude_m)
    a_mat = np.array([[0.0, 1.0], [-w * w, -2.0 * z * w]])
    vals, vecs = np.linalg.eig(a_mat)  # distinct eigenvalues for z < 1
    h = dt_s
    phi = (vecs @ np.diag(np.exp(vals * h)) @ np.linalg.inv(vecs)).real  # exp(A h)
    inv = np.linalg.inv(a_mat)
    gam0 = inv @ (phi - np.eye(2))  # int_0^h exp(A r) dr
    gam1 = inv @ (h * phi - gam0)  # int_0^h exp(A r) r dr
    b = np.array([0.0, w * w])
    # x(h) = phi x(0) + int_0^h exp(A (h - s)) b (u0 + du s) ds
    b0, b1 = gam0 @ b, (h * gam0 - gam1) @ b
    state = np.zeros(2)
    x = np.zeros_like(t)
    v = np.zeros_like(t)
    for k in range(1, t.size):
        state = phi @ state + b0 * u[k - 1] + b1 * (u[k] - u[k - 1]) / h
        x[k], v[k] = state
    acc = w * w * (u - x) - 2.0 * z * w * v
    return t, x, acc


# ---------------------------------------------------------------- hinges from the motion


def hinges_from_motion(run, joints: list[dict], open_m: float = 1.0e-3) -> list[tuple[float, int, str]]:
    """(time, joint, side) at which each joint first pivots on one edge: the other edge
    opened by more than `open_m` while this one stays within half of it. The edges are
    carried by each body's rigid motion from the recorded centroid and rotation."""
    pos = run.body_position  # (nt, nb, 3)
    ref = pos[0]
    seen = {}
    for j, jt in enumerate(joints):
        a, b = jt["bodies"]
        for k in range(pos.shape[0]):
            gaps = []
            for point in (jt["intrados"], jt["extrados"]):
                carried = []
                for body in (a, b):
                    th = pos[k, body, 2] - ref[body, 2]
                    c, s = math.cos(th), math.sin(th)
                    rel = point - ref[body, :2]
                    carried.append(np.array([c * rel[0] - s * rel[1], s * rel[0] + c * rel[1]]) + pos[k, body, :2])
                gaps.append(float(np.linalg.norm(carried[0] - carried[1])))
            for side, here, other in (("intrados", gaps[0], gaps[1]), ("extrados", gaps[1], gaps[0])):
                if other > open_m and here < 0.5 * open_m and (j, side) not in seen:
                    seen[(j, side)] = float(run.time_s[k])
    return sorted((tt, j, side) for (j, side), tt in seen.items())


# ---------------------------------------------------------------- the campaign


def _onset_amplitude_m(runner: Runner, arch: Arch, frequency_hz: float) -> float:
    limit = runner.run_limit({"arch": {"embrace_deg": arch.embrace_deg, "n_voussoirs": arch.n_voussoirs,
                                       "r_ext_m": arch.r_ext_m, "thickness_m": arch.thickness_m}},
                             f"limit_{arch.specimen_id}")
    return limit.lambda_pos * G / (2.0 * math.pi * frequency_hz) ** 2


def run_groups(arch: Arch, poly_file: Path, friction: float, motion: dict, dt_s: float) -> dict:
    """The input groups of one test of a campaign (the arch as its polygon file)."""
    return {"arch": {"polygon_file": str(poly_file), "width_m": arch.width_m,
                     "density_kg_m3": arch.density_kg_m3, "friction": friction},
            "motion": motion,
            "solver": {"dt_s": dt_s, "allow_nonconvergence": True},
            "output": {"every": int(round(0.005 / dt_s)), "stop_after_collapse_s": 0.3,
                       "collapse_drop_m": 0.5 * arch.thickness_m}}


def write_campaign(folder: Path, truth: Truth, bin_dir: Path, arches=ARCHES, seed: int = 11, dt_s: float = 5e-4,
                   step_fraction: float = 0.05, start_fraction: float = 0.8, max_steps: int = 30,
                   hinges: bool = True) -> dict:
    """Ramp every (arch, frequency) in amplitude steps until it falls, under `truth`,
    and write the campaign in the format of docs/measured_data.md."""
    folder = Path(folder)
    (folder / "records").mkdir(parents=True, exist_ok=True)
    (folder / "hinges").mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    spec_rows, test_rows, summary = [], [], {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        runner = Runner(bin_dir, tmp)
        for arch in arches:
            blocks, joints = ring_blocks(arch, truth)
            poly_file = tmp / f"{arch.specimen_id}.txt"
            write_polygon_file(poly_file, blocks)
            spec_rows.append(f"{arch.specimen_id},{arch.embrace_deg:g},{arch.n_voussoirs},{arch.r_ext_m:g},"
                             f"{arch.thickness_m:g},{arch.width_m:g},{arch.density_kg_m3:g},{arch.friction:g}")
            friction = arch.friction if truth.friction is None else truth.friction
            for f in arch.frequencies_hz:
                onset = _onset_amplitude_m(runner, arch, f)
                step = max(5e-4, round(step_fraction * onset / 5e-4) * 5e-4)
                amp = max(step, round(start_fraction * onset / 5e-4) * 5e-4)
                written = 0
                for _ in range(max_steps):
                    test_id = f"{arch.specimen_id}_f{f:g}_A{1e3 * amp:.1f}"
                    gain = 1.0 + 0.01 * rng.standard_normal()
                    motion, t0 = _motion(tmp, test_id, f, amp, gain, truth, dt_s)
                    run = runner.run_single(run_groups(arch, poly_file, friction, motion, dt_s), test_id,
                                            keep=False)
                    row = _write_test(folder, arch, test_id, f, amp, run, t0, joints, rng, hinges)
                    test_rows.append(row)
                    written += 1
                    if run.collapsed:
                        break
                    amp = round((amp + step) / 5e-4) * 5e-4
                summary[(arch.specimen_id, f)] = written
    (folder / "specimens.csv").write_text(
        "# Arches of a shaking-table campaign.\n"
        "specimen_id,embrace_deg,n_voussoirs,r_ext_m,thickness_m,width_m,density_kg_m3,friction\n"
        + "\n".join(spec_rows) + "\n")
    (folder / "tests.csv").write_text(
        "# Amplitude ramps at fixed frequencies until collapse.\n"
        "test_id,specimen_id,waveform,frequency_hz,amplitude_m,n_attack,n_full,n_decay,outcome,"
        "collapse_time_s,peak_accel_m_s2\n" + "\n".join(test_rows) + "\n")
    (folder / "README.md").write_text("Shaking-table campaign: ring arches of 12-degree voussoirs under\n"
                                      "sinusoidal attack-full-decay motion ramped in amplitude until collapse.\n")
    return summary


def _motion(tmp: Path, test_id: str, f: float, amp: float, gain: float, truth: Truth, dt_s: float
            ) -> tuple[dict, float]:
    """The &motion group of one test and the time [s] at which its motion starts."""
    if truth.actuator_hz is None:
        return {"waveform": "afd", "frequency_hz": f, "amplitude_m": amp, "n_attack": 1, "n_full": 1,
                "n_decay": 1, "rest_s": 1.0, "table_gain": gain}, 0.0
    t, _, acc = actuator_record(f, amp, gain, truth)
    path = tmp / f"{test_id}_table.csv"
    path.write_text("t_s,accel_m_s2\n" + "\n".join(f"{a:.6f},{b:.9e}" for a, b in zip(t, acc)) + "\n")
    return {"waveform": "accelerogram", "record_file": str(path), "lead_s": 1.0, "rest_s": 0.0}, 1.0


def _write_test(folder: Path, arch: Arch, test_id: str, f: float, amp: float, run, t0: float, joints, rng,
                hinges: bool) -> str:
    fs = 200.0
    ts = np.arange(0.0, run.time_s[-1] - t0, 1.0 / fs)
    table = np.interp(ts + t0, run.time_s, run.table_x_m)
    x = table + 3e-5 * rng.standard_normal(ts.size)
    acc = np.interp(ts + t0, run.time_s, run.table_a_m_s2) + 0.05 * rng.standard_normal(ts.size)
    dx = np.interp(ts + t0, run.time_s, run.crown_dx_m) + 2e-4 * rng.standard_normal(ts.size)
    dy = np.interp(ts + t0, run.time_s, run.crown_dy_m) + 2e-4 * rng.standard_normal(ts.size)
    lines = ["t_s,table_x_m,crown_dx_m,crown_dy_m"]
    lines += [f"{a:.4f},{b:.6e},{c:.6e},{d:.6e}" for a, b, c, d in zip(ts, x, dx, dy)]
    (folder / "records" / f"{test_id}.csv").write_text("\n".join(lines) + "\n")
    if hinges:
        end = run.collapse_time_s if run.collapsed else math.inf
        found = [(tt - t0, j, s) for tt, j, s in hinges_from_motion(run, joints) if tt <= end and tt >= t0]
        if found:
            rows = ["t_s,joint,side"] + [f"{max(0.0, tt + 0.01 * rng.standard_normal()):.3f},{j},{s}"
                                         for tt, j, s in found]
            (folder / "hinges" / f"{test_id}.csv").write_text("\n".join(rows) + "\n")
    outcome = "collapse" if run.collapsed else "stand"
    tc = f"{run.collapse_time_s - t0:.3f}" if run.collapsed else ""
    return (f"{test_id},{arch.specimen_id},afd,{f:g},{amp:.4f},1,1,1,{outcome},{tc},"
            f"{float(np.abs(acc).max()):.3f}")
