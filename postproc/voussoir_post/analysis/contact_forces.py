"""Statics of a run from its contact forces (/contacts, docs/results_format.md).

Every loaded contact of a sample carries the mean force of the step that ends there
(impulse / dt) on its body a, and the opposite on its body b. From them:

- the **reactions of the supports** (the driven bodies: the springings' foundations, the
  brackets, a wall's base or a polygon file's fixed blocks): the force each support
  exerts on the blocks it carries, Fx and Fy [N]; under gravity alone the vertical
  reactions sum to the weight of the free blocks;
- the **thrust line of an arch**: at each joint the resultant of its contact forces
  (normal N, shear S) and its point of application, the centre of pressure
  sum(N_i p_i) / sum(N_i) of its contact points, as a point [m] and as the fraction of
  the joint from the intrados (0) to the extrados (1) in the present configuration; NaN
  where the joint carries nothing (fully open).

The same centre of pressure for the static field of the limit analysis (the JSON's
``contact_forces``): :func:`lp_joint_resultants`.

Nothing here is physics the kernel does not already do: sums of recorded forces.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..readers.limit_results import LimitResult
from ..readers.results import ContactRecord, RunResult
from ..tables import ReportTable
from .kinematics import ROLE_BACKING, ROLE_FILL, ROLE_VOUSSOIR, body_transforms, joint_bodies, rotation_matrix

__all__ = ["Reactions", "ThrustLine", "LpJointResultants", "contact_record", "reactions", "thrust_line",
           "reactions_table", "lp_joint_resultants", "pair_forces"]


@dataclass(frozen=True)
class Reactions:
    """The force each support (driven body) exerts on the blocks it carries, per sample."""

    time_s: np.ndarray  #: (nt,)
    bodies: np.ndarray  #: (nd,) the driven bodies, 0-based, left to right by reference x
    role: np.ndarray  #: (nd,) 2 foundation, 3 restraint bracket
    force_n: np.ndarray  #: (nt, nd, 2) Fx, Fy [N]

    @property
    def total_n(self) -> np.ndarray:
        """(nt, 2) the sum over the supports [N]."""
        return self.force_n.sum(axis=1)


@dataclass(frozen=True)
class ThrustLine:
    """The resultant of every joint of an arch, per sample."""

    time_s: np.ndarray  #: (nt,)
    point_m: np.ndarray  #: (nt, n+1, 2) centre of pressure; NaN where the joint carries nothing
    fraction: np.ndarray  #: (nt, n+1) its place from the intrados (0) to the extrados (1); NaN likewise
    normal_n: np.ndarray  #: (nt, n+1) N: the sum of the normal forces across the joint [N]
    shear_n: np.ndarray  #: (nt, n+1) S: the sum of the tangential forces [N], signed along the joint
    #: (nt, n+1, 2) the resultant force on the joint's right-hand body (x, y) [N]
    force_n: np.ndarray


def contact_record(run: RunResult) -> ContactRecord:
    """The run's contacts, or an InputError for a file written before they were recorded."""
    if run.contacts is None:
        raise InputError(f"{run.path}: no /contacts/start: the file was written before runs recorded "
                         "their contact forces; run it again with this voussoir-run")
    return run.contacts


def _sample_of_row(c: ContactRecord) -> np.ndarray:
    return np.repeat(np.arange(c.start.shape[0] - 1), np.diff(c.start))


def pair_forces(run: RunResult, sample: int = -1) -> dict[tuple[int, int], tuple[float, float]]:
    """The normal force N and the magnitude of the tangential force |T| [N] between every
    pair of bodies in contact at `sample` (keys: 0-based body pairs, the smaller first).
    The points of one pair share their normal, so their tangential forces add along it."""
    c = contact_record(run)
    sums: dict[tuple[int, int], list[float]] = {}
    rows = c.rows(sample)
    for a, b, n, t in zip(c.body[rows, 0], c.body[rows, 1], c.normal_force_n[rows], c.tangent_force_n[rows]):
        entry = sums.setdefault((int(min(a, b)), int(max(a, b))), [0.0, 0.0])
        entry[0] += float(n)
        entry[1] += float(t)
    return {pair: (n, abs(t)) for pair, (n, t) in sums.items()}


def reactions(run: RunResult) -> Reactions:
    """The reactions of every driven body (role 2 or 3: not a voussoir nor a fill particle) at every sample."""
    c = contact_record(run)
    driven = np.nonzero(~np.isin(run.body_role, (ROLE_VOUSSOIR, ROLE_FILL, ROLE_BACKING)))[0]
    driven = driven[np.argsort(run.body_position[0, driven, 0], kind="stable")]
    column = np.full(run.n_bodies, -1)
    column[driven] = np.arange(driven.size)
    force = np.zeros((run.n_samples, driven.size, 2))
    sample = _sample_of_row(c)
    on_a = c.force_on_a_n()
    # A support is body b of a row: it pushes body a with the row's force. As body a it
    # receives the force, and pushes body b with the opposite.
    for side, sign in ((1, 1.0), (0, -1.0)):
        col = column[c.body[:, side]]
        rows = col >= 0
        np.add.at(force, (sample[rows], col[rows]), sign * on_a[rows])
    return Reactions(time_s=run.time_s, bodies=driven, role=run.body_role[driven], force_n=force)


def thrust_line(run: RunResult) -> ThrustLine:
    """The centre of pressure and resultant of every joint of an arch at every sample."""
    c = contact_record(run)
    if run.arch is None:
        raise InputError(f"{run.path}: no /arch group: a thrust line is drawn through the joints of an arch")
    bodies = joint_bodies(run)
    nt, nj = run.n_samples, bodies.shape[0]
    sample = _sample_of_row(c)
    rows = c.joint >= 0
    s, j = sample[rows], c.joint[rows]
    on_a = c.force_on_a_n()[rows]
    # The force on the joint's right-hand body: rows whose body a is the left one push the right one back.
    sign = np.where(c.body[rows, 0] == bodies[j, 1], 1.0, -1.0)
    normal = np.zeros((nt, nj))
    moment = np.zeros((nt, nj, 2))
    force = np.zeros((nt, nj, 2))
    np.add.at(normal, (s, j), c.normal_force_n[rows])
    np.add.at(moment, (s, j), c.normal_force_n[rows, None] * c.point_m[rows])
    np.add.at(force, (s, j), sign[:, None] * on_a)
    carried = normal > 0.0
    point = np.full((nt, nj, 2), np.nan)
    point[carried] = moment[carried] / normal[carried][:, None]

    # The joint's ends moved with its voussoir (the right body of joint 0, else the left).
    voussoir = np.where(run.body_role[bodies[:, 0]] == ROLE_VOUSSOIR, bodies[:, 0], bodies[:, 1])
    ends_ref = np.stack([run.arch.joint_intrados_xy_m, run.arch.joint_extrados_xy_m], axis=1)  # (nj, 2, 2)
    fraction = np.full((nt, nj), np.nan)
    shear = np.zeros((nt, nj))
    for k in range(nt):
        centroid, rotation = body_transforms(run, k)
        rot = rotation_matrix(rotation[voussoir])  # (nj, 2, 2)
        rel = ends_ref - run.body_position[0, voussoir, None, :2]
        ends = centroid[voussoir, None, :] + np.einsum("jab,jeb->jea", rot, rel)
        along = ends[:, 1] - ends[:, 0]
        length2 = np.einsum("ja,ja->j", along, along)
        fraction[k] = np.einsum("ja,ja->j", point[k] - ends[:, 0], along) / length2
        shear[k] = np.einsum("ja,ja->j", force[k], along) / np.sqrt(length2)
    return ThrustLine(time_s=run.time_s, point_m=point, fraction=fraction, normal_n=normal,
                      shear_n=shear, force_n=force)


def reactions_table(r: Reactions) -> ReportTable:
    """One row per sample: time and each support's Fx, Fy [N]."""
    columns = ["time_s"]
    for k, (b, role) in enumerate(zip(r.bodies, r.role)):
        name = f"support{k + 1}_body{b + 1}"
        columns += [f"{name}_fx_n", f"{name}_fy_n"]
    rows = []
    for t, f in zip(r.time_s, r.force_n):
        rows.append(tuple([float(t)] + [float(v) for v in f.reshape(-1)]))
    return ReportTable(columns=columns, rows=rows)


@dataclass(frozen=True)
class LpJointResultants:
    """The joints of an arch in the LP's static field at collapse (``voussoir-limit --json``)."""

    joint: np.ndarray  #: (n+1,) 0..n
    point_m: np.ndarray  #: (n+1, 2) centre of pressure, the JSON's frame; NaN where N = 0
    force_n: np.ndarray  #: (n+1, 2) the force of the part left of the joint on the part right of it [N]
    normal_n: np.ndarray  #: (n+1,) N = N1 + N2


def lp_joint_resultants(limit: LimitResult) -> LpJointResultants | None:
    """Centre of pressure (N1 e1 + N2 e2) / (N1 + N2) and resultant of every arch joint in
    the LP's contact forces; None when the JSON has no LP field for every joint. The
    right-hand block of joint j is voussoir j + 1, and of joint n the right foundation n + 2."""
    n = limit.n_voussoirs
    by_joint = {f.joint: f for f in limit.contact_forces if f.joint is not None}
    if sorted(by_joint) != list(range(n + 1)):
        return None
    point = np.full((n + 1, 2), np.nan)
    force = np.zeros((n + 1, 2))
    normal = np.zeros(n + 1)
    for j in range(n + 1):
        f = by_joint[j]
        total = float(f.normal_n.sum())
        tangent = np.array([-f.normal[1], f.normal[0]])
        on_b = total * f.normal + f.shear_n * tangent
        right = j + 1 if j < n else n + 2
        force[j] = on_b if f.blocks[1] == right else -on_b
        normal[j] = total
        if total > 0.0:
            point[j] = (f.normal_n[0] * f.ends_xy_m[0] + f.normal_n[1] * f.ends_xy_m[1]) / total
    return LpJointResultants(np.arange(n + 1), point, force, normal)
