"""Joints of any block assembly: where two blocks touch, how far they opened and slid.

An arch has numbered joints; a wall or any polygon assembly does not. Its joints are
found here from the geometry of the reference configuration (the first sample): two
edges of two different blocks that face each other (opposite outward normals), lie on
one line within `tol_m`, and overlap over more than `tol_m`. Each joint is the overlap
segment, carried by the block on one side (a) and the other (b).

Over the run, both ends of the segment are moved with each block; at each end the
opening is the distance from a's copy to b's copy along a's outward normal (turned with
a), positive when apart; the sliding is their distance along a's edge direction (at the
middle of the segment). Residual values are those of the last sample. No monitor of the
run is needed: /bodies has every block's motion and shape (docs/results_format.md).
When the run recorded its contact forces, each joint also gets the normal force N and the
tangential force |T| its two blocks exchange at the last sample (|T| = friction x N while
the joint slides).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..readers.results import RunResult
from ..tables import ReportTable
from .contact_forces import pair_forces
from .kinematics import rotation_matrix

__all__ = ["Joint", "JointMotion", "find_joints", "carried_points", "joint_series", "joint_motion", "run_joints", "joints_table"]


@dataclass(frozen=True)
class Joint:
    a: int  #: body index (0-based) on one side
    b: int  #: body index on the other
    ends_m: np.ndarray  #: (2, 2) the two ends of the contact segment, reference configuration
    normal: np.ndarray  #: (2,) outward normal of a's edge, reference configuration


@dataclass(frozen=True)
class JointMotion:
    joint: Joint
    max_opening_m: float  #: the largest opening of either end over the run
    final_opening_m: float  #: the larger opening of the two ends at the last sample
    final_sliding_m: float  #: relative tangential displacement at the middle, last sample (signed)
    max_sliding_m: float  #: its largest magnitude over the run
    final_normal_n: float = float("nan")  #: N between the two blocks at the last sample (NaN: no forces in the file)
    final_shear_n: float = float("nan")  #: |T| between them at the last sample


def _polygons(centroids: np.ndarray, vertices: list[np.ndarray]) -> list[np.ndarray]:
    return [c + v for c, v in zip(centroids, vertices)]


def _edges(poly: np.ndarray) -> list[tuple]:
    """(start, end, unit outward normal, unit direction) of each edge of a convex polygon."""
    centre = poly.mean(axis=0)
    edges = []
    for k in range(len(poly)):
        p, q = poly[k], poly[(k + 1) % len(poly)]
        d = q - p
        length = float(np.hypot(*d))
        if length == 0.0:
            continue
        t = d / length
        n = np.array([t[1], -t[0]])
        if np.dot(n, 0.5 * (p + q) - centre) < 0.0:
            n = -n
        edges.append((p, q, n, t))
    return edges


def find_joints(centroids_m: np.ndarray, vertices_local_m: list[np.ndarray], tol_m: float = 1e-4) -> list[Joint]:
    """The faces where two blocks touch in the reference configuration (centroids (nb, 2),
    vertices relative to each centroid)."""
    polys = _polygons(centroids_m, vertices_local_m)
    lo = np.array([p.min(axis=0) for p in polys]) - tol_m
    hi = np.array([p.max(axis=0) for p in polys]) + tol_m
    edges = [_edges(p) for p in polys]
    joints = []
    for a in range(len(polys)):
        near = np.nonzero(np.all(lo[a + 1:] <= hi[a], axis=1) & np.all(hi[a + 1:] >= lo[a], axis=1))[0] + a + 1
        for b in near:
            for p, q, n, t in edges[a]:
                for r, s, m, _ in edges[b]:
                    if np.dot(n, m) > -1.0 + 1e-6:
                        continue
                    if abs(np.dot(r - p, n)) > tol_m or abs(np.dot(s - p, n)) > tol_m:
                        continue
                    start = max(0.0, min(np.dot(r - p, t), np.dot(s - p, t)))
                    end = min(float(np.dot(q - p, t)), max(np.dot(r - p, t), np.dot(s - p, t)))
                    if end - start > tol_m:
                        joints.append(Joint(a, int(b), np.array([p + start * t, p + end * t]), n))
    return joints


def carried_points(positions: np.ndarray, body: int, points_m: np.ndarray) -> np.ndarray:
    """(nt, p, 2): the points (p, 2) of the reference configuration moved with `body` to
    every sample of `positions` (as :func:`joint_series`)."""
    rot = rotation_matrix(positions[:, body, 2] - positions[0, body, 2])
    return positions[:, body, None, :2] + np.einsum("kij,pj->kpi", rot, points_m - positions[0, body, :2])


def joint_series(joint: Joint, positions: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The opening (nt, 2) of each end of `joint` [m] (positive apart, negative
    interpenetration) and the sliding (nt,) at its middle [m, signed] at every sample of
    `positions` (nt, nb, 3): centroid x, y [m] and rotation [rad] from the reference
    (sample 0)."""
    tangent = np.array([-joint.normal[1], joint.normal[0]])
    points = np.vstack([joint.ends_m, joint.ends_m.mean(axis=0)])  # the two ends and the middle
    rot_a = rotation_matrix(positions[:, joint.a, 2] - positions[0, joint.a, 2])
    n = rot_a @ joint.normal
    t = rot_a @ tangent
    rel = carried_points(positions, joint.b, points) - carried_points(positions, joint.a, points)
    openings = np.einsum("kpi,ki->kp", rel[:, :2], n)
    slidings = np.einsum("ki,ki->k", rel[:, 2], t)
    return openings, slidings


def joint_motion(joint: Joint, positions: np.ndarray) -> JointMotion:
    """Opening and sliding of `joint` over the samples of `positions` (as
    :func:`joint_series`): the largest and the final ones."""
    openings, slidings = joint_series(joint, positions)
    return JointMotion(joint, float(openings.max()), float(openings[-1].max()), float(slidings[-1]),
                       float(np.abs(slidings).max()))


def run_joints(run: RunResult, tol_m: float = 1e-4) -> list[JointMotion]:
    """Every joint of a run's assembly with its opening and sliding, the largest residual
    sliding first."""
    vertices = [run.vertices_local_m[b, : run.n_vertices[b]] for b in range(run.n_bodies)]
    joints = find_joints(run.body_position[0, :, :2], vertices, tol_m)
    motions = [joint_motion(j, run.body_position) for j in joints]
    if run.contacts is not None:
        forces = pair_forces(run, -1)
        motions = [replace(m, final_normal_n=forces.get((m.joint.a, m.joint.b), (0.0, 0.0))[0],
                           final_shear_n=forces.get((m.joint.a, m.joint.b), (0.0, 0.0))[1]) for m in motions]
    return sorted(motions, key=lambda m: (-abs(m.final_sliding_m), -m.max_opening_m))


def joints_table(motions: list[JointMotion], run_name: str) -> ReportTable:
    """One row per joint (bodies numbered from 1, lengths in mm), in the order of
    ``motions``."""
    columns = ["body_a", "body_b", "length_mm", "max_opening_mm", "final_opening_mm", "max_sliding_mm",
               "final_sliding_mm", "final_normal_n", "final_shear_n"]
    rows = [(m.joint.a + 1, m.joint.b + 1, 1e3 * float(np.linalg.norm(m.joint.ends_m[1] - m.joint.ends_m[0])),
             1e3 * m.max_opening_m, 1e3 * m.final_opening_m, 1e3 * m.max_sliding_m, 1e3 * m.final_sliding_m,
             m.final_normal_n, m.final_shear_n)
            for m in motions]
    title = (f"joints of {run_name}: {len(motions)} faces where two blocks touch at t = 0 "
             f"(bodies numbered as in /bodies, from 1), the largest final sliding first")
    return ReportTable(columns, rows, title)
