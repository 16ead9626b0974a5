"""Rigid-block kinematics of a run: block polygons at a sample and joint openings.

Conventions (docs/results_format.md): ``/bodies/position[k, b]`` is the centroid x, y [m]
and the rotation [rad] from the reference configuration of body b at sample k;
``/bodies/vertices_local_m[b]`` are the vertices relative to the centroid in the reference
configuration. The reference centroid of each body is taken from the first sample
(t = 0), where the drivers write the initial, reference configuration.

Amplification by K draws each block at ``c_ref + x_table(t) e_x + K (c(t) - c_ref -
x_table(t) e_x)`` rotated by ``K theta(t)``: the displacement and rotation relative to the
reference configuration carried by the table are multiplied by K, the table motion
itself is drawn true (so K = 1 is the computed configuration and driven blocks are never
distorted).

Open hinges are computed from the geometry (not from the /hinges events): at each joint
j the two ends of the joint (intrados and extrados, from /arch) are moved with the block
on each side, and the normal opening of each end is measured along the joint normal of
the block on the left. A joint is open when its larger opening exceeds ``open_tol_m``;
it is a hinge on the side whose end stays closed (opening below ``open_tol_m``) -- the
edge that stays in contact, as MEASURED_DATA.md defines the side -- and "separated"
when both ends are open. The default ``open_tol_m`` is the run's ``&output hinge_gap_m``
when /config has it (so the drawing agrees with the /hinges events), else 1 % of the
ring thickness.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..readers.results import RunResult

__all__ = [
    "ROLE_VOUSSOIR",
    "ROLE_FOUNDATION",
    "ROLE_RESTRAINT",
    "rotation_matrix",
    "body_transforms",
    "block_polygons",
    "joint_bodies",
    "joint_openings",
    "JointState",
    "joint_states",
    "default_open_tol_m",
]

ROLE_VOUSSOIR = 1
ROLE_FOUNDATION = 2
ROLE_RESTRAINT = 3
ROLE_FILL = 4  #: a free particle of a bridge's fill (&bridge fill_model = 'particles')
ROLE_BACKING = 5  #: a free block of a bridge's masonry backing (&bridge backing_level_m)


def rotation_matrix(angle_rad: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 2, 2) for counter-clockwise angles (...)."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


def body_transforms(run: RunResult, sample: int, amplify: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Centroids (nb, 2) [m] and rotations (nb,) [rad] to draw at ``sample``, amplified.

    See the module docstring for the amplification rule.
    """
    ref = run.body_position[0, :, :2]
    carried = ref + np.array([run.table_x_m[sample] - run.table_x_m[0], 0.0])
    centroid = carried + amplify * (run.body_position[sample, :, :2] - carried)
    rotation = amplify * run.body_position[sample, :, 2]
    return centroid, rotation


def block_polygons(run: RunResult, sample: int, amplify: float = 1.0) -> list[np.ndarray]:
    """Vertices (nv_b, 2) [m] of every body at ``sample``, amplified by ``amplify``."""
    centroid, rotation = body_transforms(run, sample, amplify)
    rot = rotation_matrix(rotation)
    polygons = []
    for b in range(run.n_bodies):
        local = run.vertices_local_m[b, : run.n_vertices[b]]
        polygons.append(centroid[b] + local @ rot[b].T)
    return polygons


def joint_bodies(run: RunResult) -> np.ndarray:
    """(n+1, 2) body indices (0-based) on the left and right of each joint of an arch.

    Voussoirs are the role-1 bodies in file order (left to right); the foundations are
    the role-2 bodies, the left one being the one with the smaller reference x.
    """
    if run.arch is None:
        raise InputError(f"{run.path}: no /arch group, joints are defined for arches only")
    voussoirs = np.nonzero(run.body_role == ROLE_VOUSSOIR)[0]
    foundations = np.nonzero(run.body_role == ROLE_FOUNDATION)[0]
    n = run.arch.n_voussoirs
    if voussoirs.size != n or foundations.size != 2:
        raise InputError(f"{run.path}: expected {n} voussoirs and 2 foundations, found "
                         f"{voussoirs.size} and {foundations.size}")
    foundations = foundations[np.argsort(run.body_position[0, foundations, 0])]
    bodies = np.empty((n + 1, 2), dtype=int)
    bodies[0] = foundations[0], voussoirs[0]
    for j in range(1, n):
        bodies[j] = voussoirs[j - 1], voussoirs[j]
    bodies[n] = voussoirs[n - 1], foundations[1]
    return bodies


def _move_points(run: RunResult, sample: int, body: int, points_ref: np.ndarray,
                 amplify: float = 1.0) -> np.ndarray:
    """Reference points (k, 2) carried by ``body`` to ``sample`` (amplified)."""
    centroid, rotation = body_transforms(run, sample, amplify)
    ref = run.body_position[0, body, :2]
    return centroid[body] + (points_ref - ref) @ rotation_matrix(rotation[body]).T


def joint_openings(run: RunResult, sample: int) -> np.ndarray:
    """(n+1, 2) normal opening [m] of the intrados (column 0) and extrados (column 1)
    end of every joint at ``sample``; negative values are interpenetration."""
    bodies = joint_bodies(run)
    intr, extr = run.arch.joint_intrados_xy_m, run.arch.joint_extrados_xy_m
    openings = np.zeros((intr.shape[0], 2))
    for j, (left, right) in enumerate(bodies):
        ends = np.array([intr[j], extr[j]])
        on_left = _move_points(run, sample, left, ends)
        on_right = _move_points(run, sample, right, ends)
        along = on_left[1] - on_left[0]
        normal = np.array([along[1], -along[0]]) / np.linalg.norm(along)  # from left to right
        openings[j] = (on_right - on_left) @ normal
    return openings


@dataclass
class JointState:
    """An open joint at one sample: a hinge ('intrados'/'extrados') or 'separated'."""

    joint: int
    state: str
    opening_m: float  #: the larger normal opening of the two ends
    pivot_xy_m: np.ndarray  #: drawn point: the closed end (hinge) or the joint middle


def default_open_tol_m(run: RunResult) -> float:
    """Opening above which a joint counts as open: the run's ``&output hinge_gap_m``
    (the gap at which the driver records a hinge event) when the file has it, else 1 %
    of the ring thickness."""
    gap = run.config.get("output", {}).get("hinge_gap_m")
    if isinstance(gap, (int, float)) and gap > 0:
        return float(gap)
    return 0.01 * run.arch.thickness_m if run.arch is not None else 1e-4


def joint_states(run: RunResult, sample: int, open_tol_m: float | None = None,
                 amplify: float = 1.0) -> list[JointState]:
    """Open joints at ``sample`` (see the module docstring); pivot points are placed in
    the drawing amplified by ``amplify``."""
    if open_tol_m is None:
        open_tol_m = default_open_tol_m(run)
    openings = joint_openings(run, sample)
    bodies = joint_bodies(run)
    intr, extr = run.arch.joint_intrados_xy_m, run.arch.joint_extrados_xy_m
    states = []
    for j, (o_int, o_ext) in enumerate(openings):
        largest = max(o_int, o_ext)
        if largest <= open_tol_m:
            continue
        if min(o_int, o_ext) <= open_tol_m:
            state = "intrados" if o_int < o_ext else "extrados"
            point = intr[j] if state == "intrados" else extr[j]
        else:
            state = "separated"
            point = 0.5 * (intr[j] + extr[j])
        # Draw the pivot on the block that is not the foundation (the moving one).
        left, right = bodies[j]
        body = right if run.body_role[left] != ROLE_VOUSSOIR else left
        drawn = _move_points(run, sample, body, point[None, :], amplify)[0]
        states.append(JointState(j, state, float(largest), drawn))
    return states
