"""VTK export of a run for ParaView: a ``.pvd`` time collection of ``.vtu`` files.

The ``.vtu`` files (VTK XML unstructured grids) are written by meshio; the ``.pvd``
collection, a short XML list of (time, part, file) that meshio does not write, by hand.
Three parts per output sample, each a ``.vtu`` in ``<stem>_vtu/``:

- ``blocks``: one polygon cell per body, cell data ``body`` (1..nb, as /bodies and the
  text outputs number them), ``role``, ``rotation_rad``, ``displacement_m`` and
  ``velocity_m_s`` (centroid, z = 0) and ``angular_velocity_rad_s``. The run file holds
  positions only: the velocities are their central differences over the neighbouring
  output samples (one-sided at the first and last), an estimate over ``every`` steps.
- ``joints``: one line cell per joint, drawn midway between the copies of its two ends
  carried by the blocks on either side. For an arch, the joints of
  shared/MEASURED_DATA.md (``joint`` 0..n, 0 the left springing, between voussoirs j and
  j + 1; ends intrados and extrados); for any other assembly the faces where two blocks
  touch at t = 0 (:func:`~voussoir_post.analysis.assembly_joints.find_joints`, ``joint``
  = -1 as in /contacts). Cell data: ``body_a``, ``body_b`` (from 1), the opening of each
  end and the larger one ``opening_m``, the sliding at the middle ``sliding_m``
  (:func:`~voussoir_post.analysis.assembly_joints.joint_series`), ``hinge`` (0 closed,
  1 a hinge on the intrados / first end: that end stays closed, 2 on the extrados / second
  end, 3 separated: both ends open, by more than the opening tolerance; the rule of
  :func:`~voussoir_post.analysis.kinematics.joint_states`), and the forces the two blocks
  exchange, ``normal_force_n`` and ``shear_force_n`` (|T|), where the run recorded them.
- ``contacts``: one vertex per loaded contact point (none at t = 0), point data
  ``force_n`` (the mean force over the step on body a, which presses into it; body b
  receives the opposite), ``normal``, ``normal_force_n``, ``tangent_force_n``,
  ``body_a``, ``body_b`` (from 1) and ``joint`` (0..n, -1 none): the glyph data.

``<stem>.pvd`` lists all three parts (ParaView opens it as a multiblock), and
``<stem>_blocks.pvd``, ``<stem>_joints.pvd``, ``<stem>_contacts.pvd`` one part each
(the contacts alone are what the Glyph filter wants).
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

import numpy as np

from ..analysis.assembly_joints import Joint, carried_points, find_joints, joint_series
from ..analysis.contact_forces import pair_forces
from ..analysis.kinematics import default_open_tol_m, joint_bodies, rotation_matrix
from ..errors import InputError
from ..readers.results import RunResult
from ..tables import ReportTable

__all__ = ["VtuExport", "write_vtu", "run_joints_for_export", "hinge_codes", "PARTS",
           "HINGE_CLOSED", "HINGE_FIRST_END", "HINGE_SECOND_END", "HINGE_SEPARATED"]

PARTS = ("blocks", "joints", "contacts")  #: the part names, in the order of the .pvd's part numbers
HINGE_CLOSED, HINGE_FIRST_END, HINGE_SECOND_END, HINGE_SEPARATED = 0, 1, 2, 3


@dataclass
class VtuExport:
    """What :func:`write_vtu` wrote."""

    pvd_path: str  #: all parts
    part_pvd_paths: dict  #: {part: .pvd of that part alone}
    vtu_folder: str
    samples: list  #: the run's output samples written (0-based, as /time_s)
    n_bodies: int
    n_joints: int
    arch_joints: bool  #: the joints are an arch's 0..n (else the faces found at t = 0)
    open_tol_m: float
    n_contact_points: int = 0  #: over all samples written
    files: dict = field(default_factory=dict)  #: {part: [.vtu path per sample]}

    def table(self, run_path: str) -> ReportTable:
        return ReportTable(["samples", "bodies", "joints", "joint_numbering", "open_tol_mm", "contact_points"],
                           [(len(self.samples), self.n_bodies, self.n_joints,
                             "arch 0..n" if self.arch_joints else "faces (joint -1)", 1e3 * self.open_tol_m,
                             self.n_contact_points)],
                           title=f"ParaView export of {run_path} (bodies numbered from 1)")


def run_joints_for_export(run: RunResult, tol_m: float = 1e-4) -> tuple[list[Joint], np.ndarray, bool]:
    """The joints of the run's assembly and their numbers: an arch's joints 0..n
    (MEASURED_DATA.md, ends intrados then extrados), or the faces where two blocks touch at
    t = 0 (numbered -1). The third value says which."""
    if run.arch is not None:
        try:
            bodies = joint_bodies(run)
        except InputError:
            bodies = None
        if bodies is not None:
            joints = []
            for j, (left, right) in enumerate(bodies):
                ends = np.array([run.arch.joint_intrados_xy_m[j], run.arch.joint_extrados_xy_m[j]])
                along = ends[1] - ends[0]
                normal = np.array([along[1], -along[0]]) / np.linalg.norm(along)  # from left to right
                joints.append(Joint(int(left), int(right), ends, normal))
            return joints, np.arange(len(joints)), True
    vertices = [run.vertices_local_m[b, : run.n_vertices[b]] for b in range(run.n_bodies)]
    joints = find_joints(run.body_position[0, :, :2], vertices, tol_m)
    return joints, np.full(len(joints), -1), False


def hinge_codes(openings_m: np.ndarray, open_tol_m: float) -> np.ndarray:
    """The hinge state (...,) of joints whose two ends opened by ``openings_m`` (..., 2):
    0 closed, 1 a hinge on the first end (it stays within the tolerance, the other opens),
    2 on the second end, 3 both ends open."""
    largest, smallest = openings_m.max(axis=-1), openings_m.min(axis=-1)
    pivot = np.where(openings_m[..., 0] < openings_m[..., 1], HINGE_FIRST_END, HINGE_SECOND_END)
    return np.where(largest <= open_tol_m, HINGE_CLOSED,
                    np.where(smallest <= open_tol_m, pivot, HINGE_SEPARATED)).astype(np.int32)


def _vertex_coordinates(run: RunResult, sample: int) -> np.ndarray:
    pos = run.body_position[sample]
    rot = rotation_matrix(pos[:, 2])
    parts = [pos[b, :2] + run.vertices_local_m[b, : run.n_vertices[b]] @ rot[b].T for b in range(run.n_bodies)]
    return _xyz(np.vstack(parts))


def _xyz(xy: np.ndarray) -> np.ndarray:
    return np.column_stack([xy, np.zeros(xy.shape[0])])


def _polygon_cells(n_vertices: np.ndarray) -> list:
    """meshio cell blocks in body order: one block per run of bodies with equal vertex counts."""
    blocks, start, b = [], 0, 0
    while b < n_vertices.size:
        e = b
        while e < n_vertices.size and n_vertices[e] == n_vertices[b]:
            e += 1
        nv = int(n_vertices[b])
        blocks.append(("polygon", start + np.arange((e - b) * nv, dtype=np.int64).reshape(e - b, nv)))
        start += (e - b) * nv
        b = e
    return blocks


def _split(values: np.ndarray, cells: list) -> list:
    """Per-cell values split as the cell blocks are."""
    out, k = [], 0
    for _, conn in cells:
        out.append(values[k: k + len(conn)])
        k += len(conn)
    return out


def _body_velocities(run: RunResult) -> np.ndarray:
    """(nt, nb, 3) d/dt of x, y, rotation over the output samples."""
    if run.n_samples < 2:
        return np.zeros_like(run.body_position)
    return np.gradient(run.body_position, run.time_s, axis=0)


@dataclass
class _JointFields:
    """Every joint's drawing and fields at every output sample of the run."""

    joints: list  #: Joint, as run_joints_for_export gives them
    numbers: np.ndarray  #: (nj,) arch joint 0..n or -1
    arch: bool
    openings_m: np.ndarray  #: (nt, nj, 2) at each end
    sliding_m: np.ndarray  #: (nt, nj)
    hinge: np.ndarray  #: (nt, nj) hinge_codes
    drawn_m: np.ndarray  #: (nt, nj, 2 ends, 2): each end midway between its copies on either block


def _joint_fields(run: RunResult, open_tol_m: float, joint_tol_m: float) -> _JointFields:
    joints, numbers, arch = run_joints_for_export(run, joint_tol_m)
    nt, q = run.n_samples, run.body_position
    if not joints:
        return _JointFields([], numbers, arch, np.zeros((nt, 0, 2)), np.zeros((nt, 0)), np.zeros((nt, 0), np.int32),
                            np.zeros((nt, 0, 2, 2)))
    series = [joint_series(j, q) for j in joints]
    openings = np.stack([o for o, _ in series], axis=1)
    drawn = np.stack([0.5 * (carried_points(q, j.a, j.ends_m) + carried_points(q, j.b, j.ends_m)) for j in joints],
                     axis=1)
    return _JointFields(joints, numbers, arch, openings, np.stack([s for _, s in series], axis=1),
                        hinge_codes(openings, open_tol_m), drawn)


def _blocks_mesh(meshio, run: RunResult, k: int, cells: list, velocity: np.ndarray):
    disp = run.body_position[k, :, :2] - run.body_position[0, :, :2]
    cell_data = {
        "body": np.arange(1, run.n_bodies + 1, dtype=np.int32),
        "role": run.body_role.astype(np.int32),
        "rotation_rad": run.body_position[k, :, 2],
        "displacement_m": _xyz(disp),
        "velocity_m_s": _xyz(velocity[k, :, :2]),
        "angular_velocity_rad_s": velocity[k, :, 2],
    }
    return meshio.Mesh(_vertex_coordinates(run, k), cells,
                       cell_data={name: _split(v, cells) for name, v in cell_data.items()})


def _joints_mesh(meshio, run: RunResult, k: int, f: _JointFields):
    nj = len(f.joints)
    if run.contacts is not None:
        pair = pair_forces(run, k)
        forces = np.array([pair.get((min(j.a, j.b), max(j.a, j.b)), (0.0, 0.0)) for j in f.joints]).reshape(nj, 2)
    else:
        forces = np.full((nj, 2), np.nan)
    ends = ("opening_intrados_m", "opening_extrados_m") if f.arch else ("opening_end1_m", "opening_end2_m")
    cell_data = {
        "joint": f.numbers.astype(np.int32),
        "body_a": np.array([j.a + 1 for j in f.joints], dtype=np.int32),
        "body_b": np.array([j.b + 1 for j in f.joints], dtype=np.int32),
        ends[0]: f.openings_m[k, :, 0],
        ends[1]: f.openings_m[k, :, 1],
        "opening_m": f.openings_m[k].max(axis=-1, initial=-np.inf),
        "sliding_m": f.sliding_m[k],
        "hinge": f.hinge[k],
        "normal_force_n": forces[:, 0],
        "shear_force_n": forces[:, 1],
    }
    lines = [("line", np.arange(2 * nj, dtype=np.int64).reshape(nj, 2))]
    return meshio.Mesh(_xyz(f.drawn_m[k].reshape(-1, 2)), lines, cell_data={n: [v] for n, v in cell_data.items()})


def _contacts_mesh(meshio, run: RunResult, k: int, force_on_a_n: np.ndarray):
    c = run.contacts
    rows = c.rows(k)
    point_data = {
        "force_n": _xyz(force_on_a_n[rows]),
        "normal": _xyz(c.normal[rows]),
        "normal_force_n": c.normal_force_n[rows],
        "tangent_force_n": c.tangent_force_n[rows],
        "body_a": (c.body[rows, 0] + 1).astype(np.int32),
        "body_b": (c.body[rows, 1] + 1).astype(np.int32),
        "joint": c.joint[rows].astype(np.int32),
    }
    nc = rows.stop - rows.start
    return meshio.Mesh(_xyz(c.point_m[rows]), [("vertex", np.arange(nc, dtype=np.int64)[:, None])],
                       point_data=point_data)


def write_vtu(run: RunResult, out_dir: str | os.PathLike | None = None, every: int = 1,
              open_tol_m: float | None = None, joint_tol_m: float = 1e-4) -> VtuExport:
    """Write the .vtu files of every ``every``-th output sample (and the last) and the
    .pvd collections into ``out_dir`` (default: the run's folder). ``open_tol_m``: the
    opening that counts as open (default: the run's ``&output hinge_gap_m``, else 1 % of
    the ring thickness); ``joint_tol_m``: faces closer than this at t = 0 touch (not arches)."""
    import meshio

    stem = os.path.splitext(os.path.basename(run.path))[0]
    out_dir = os.path.dirname(os.path.abspath(run.path)) if out_dir is None else os.fspath(out_dir)
    folder = os.path.join(out_dir, f"{stem}_vtu")
    os.makedirs(folder, exist_ok=True)
    for name in os.listdir(folder):  # an earlier export's samples, which the new .pvd would not list
        if re.fullmatch(r"(blocks|joints|contacts)_\d{6}\.vtu", name):
            os.remove(os.path.join(folder, name))
    samples = list(range(0, run.n_samples, max(int(every), 1)))
    if samples[-1] != run.n_samples - 1:
        samples.append(run.n_samples - 1)
    tol = default_open_tol_m(run) if open_tol_m is None else float(open_tol_m)

    body_cells = _polygon_cells(run.n_vertices)
    velocity = _body_velocities(run)
    joints = _joint_fields(run, tol, joint_tol_m)
    parts = PARTS if run.contacts is not None else PARTS[:2]
    force_on_a = run.contacts.force_on_a_n() if run.contacts is not None else None
    files = {p: [] for p in parts}
    for k in samples:
        files["blocks"].append(_write(meshio, _blocks_mesh(meshio, run, k, body_cells, velocity), folder, "blocks", k))
        files["joints"].append(_write(meshio, _joints_mesh(meshio, run, k, joints), folder, "joints", k))
        if run.contacts is not None:
            files["contacts"].append(_write(meshio, _contacts_mesh(meshio, run, k, force_on_a), folder, "contacts", k))

    times = [float(run.time_s[k]) for k in samples]
    pvd = os.path.join(out_dir, f"{stem}.pvd")
    _write_pvd(pvd, times, [(i, files[p]) for i, p in enumerate(parts)])
    part_pvds = {}
    for p in parts:
        part_pvds[p] = os.path.join(out_dir, f"{stem}_{p}.pvd")
        _write_pvd(part_pvds[p], times, [(0, files[p])])
    n_contact_points = int(run.contact_count[samples].sum()) if run.contacts is not None else 0
    return VtuExport(pvd, part_pvds, folder, samples, run.n_bodies, len(joints.joints), joints.arch, tol,
                     n_contact_points, files)


def _write(meshio, mesh, folder: str, part: str, sample: int) -> str:
    path = os.path.join(folder, f"{part}_{sample:06d}.vtu")
    if len(mesh.points) > 0:
        meshio.write(path, mesh, file_format="vtu")
        return path
    # An empty grid (the contacts at t = 0) as plain text, with no header of compressed
    # blocks of zero bytes to trip a reader; meshio's warning that ASCII is for debugging
    # does not apply to a file without data.
    with contextlib.redirect_stderr(io.StringIO()):
        meshio.write(path, mesh, file_format="vtu", binary=False)
    return path


def _write_pvd(path: str, times: list, parts: list) -> None:
    """A VTK Collection: one DataSet per time and part, files relative to the .pvd."""
    root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
    collection = ET.SubElement(root, "Collection")
    base = os.path.dirname(os.path.abspath(path))
    for i, t in enumerate(times):
        for part, files in parts:
            ET.SubElement(collection, "DataSet", timestep=repr(t), group="", part=str(part),
                          file=os.path.relpath(files[i], base).replace(os.sep, "/"))
    ET.indent(root)
    with open(path, "w", encoding="utf-8") as f:
        f.write('<?xml version="1.0"?>\n')
        f.write(ET.tostring(root, encoding="unicode"))
        f.write("\n")
