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


def write_vtu(run: RunResult, out_dir: str | os.PathLike | None = None, every: int = 1,
              open_tol_m: float | None = None, joint_tol_m: float = 1e-4) -> VtuExport:
    """Write the .vtu files of every ``every``-th output sample (and the last) and the
    .pvd collections into ``out_dir`` (default: the run's folder). ``open_tol_m``: the
    opening that counts as open (default: the run's ``&output hinge_gap_m``, else 1 % of
    the ring thickness); ``joint_tol_m``: faces closer than this at t = 0 touch (not arches)."""
    import meshio

    stem = os.path.splitext(os.path.basename(run.path))[0]
    out_dir = os.path.dirname(os.path.abspath(run.path)) if out_dir is None else os.fspath(out_dir)
    folder_name = f"{stem}_vtu"
    folder = os.path.join(out_dir, folder_name)
    os.makedirs(folder, exist_ok=True)
    for name in os.listdir(folder):  # an earlier export's samples, which the new .pvd would not list
        if re.fullmatch(r"(blocks|joints|contacts)_\d{6}\.vtu", name):
            os.remove(os.path.join(folder, name))
    samples = list(range(0, run.n_samples, max(int(every), 1)))
    if samples[-1] != run.n_samples - 1:
        samples.append(run.n_samples - 1)
    tol = default_open_tol_m(run) if open_tol_m is None else float(open_tol_m)

    nb = run.n_bodies
    body_cells = _polygon_cells(run.n_vertices)
    velocity = _body_velocities(run)
    ref = run.body_position[0]
    joints, numbers, arch_joints = run_joints_for_export(run, joint_tol_m)
    series = [joint_series(j, run.body_position) for j in joints]
    openings = np.stack([s[0] for s in series], axis=1) if joints else np.zeros((run.n_samples, 0, 2))
    sliding = np.stack([s[1] for s in series], axis=1) if joints else np.zeros((run.n_samples, 0))
    hinge = hinge_codes(openings, tol)
    # Each end carried by both blocks, drawn midway: (nt, n_joints, 2 ends, 2).
    drawn = np.stack([0.5 * (carried_points(run.body_position, j.a, j.ends_m)
                             + carried_points(run.body_position, j.b, j.ends_m)) for j in joints], axis=1) \
        if joints else np.zeros((run.n_samples, 0, 2, 2))
    end_names = ("opening_intrados_m", "opening_extrados_m") if arch_joints else ("opening_end1_m", "opening_end2_m")
    contacts = run.contacts
    forces = contacts.force_on_a_n() if contacts is not None else None
    parts = PARTS if contacts is not None else PARTS[:2]
    files = {p: [] for p in parts}
    n_contact_points = 0

    for k in samples:
        # Blocks
        disp = run.body_position[k, :, :2] - ref[:, :2]
        cell_data = {
            "body": np.arange(1, nb + 1, dtype=np.int32),
            "role": run.body_role.astype(np.int32),
            "rotation_rad": run.body_position[k, :, 2],
            "displacement_m": _xyz(disp),
            "velocity_m_s": _xyz(velocity[k, :, :2]),
            "angular_velocity_rad_s": velocity[k, :, 2],
        }
        mesh = meshio.Mesh(_vertex_coordinates(run, k), body_cells,
                           cell_data={name: _split(v, body_cells) for name, v in cell_data.items()})
        files["blocks"].append(_write(meshio, mesh, folder, "blocks", k))

        # Joints
        nj = len(joints)
        if contacts is not None:
            pair = pair_forces(run, k)
            n_s = np.array([pair.get((min(j.a, j.b), max(j.a, j.b)), (0.0, 0.0)) for j in joints]).reshape(nj, 2)
        else:
            n_s = np.full((nj, 2), np.nan)
        joint_data = {
            "joint": numbers.astype(np.int32),
            "body_a": np.array([j.a + 1 for j in joints], dtype=np.int32),
            "body_b": np.array([j.b + 1 for j in joints], dtype=np.int32),
            end_names[0]: openings[k, :, 0],
            end_names[1]: openings[k, :, 1],
            "opening_m": openings[k].max(axis=-1) if nj else np.zeros(0),
            "sliding_m": sliding[k],
            "hinge": hinge[k],
            "normal_force_n": n_s[:, 0],
            "shear_force_n": n_s[:, 1],
        }
        lines = [("line", np.arange(2 * nj, dtype=np.int64).reshape(nj, 2))]
        mesh = meshio.Mesh(_xyz(drawn[k].reshape(-1, 2)), lines, cell_data={n: [v] for n, v in joint_data.items()})
        files["joints"].append(_write(meshio, mesh, folder, "joints", k))

        # Contacts
        if contacts is None:
            continue
        rows = contacts.rows(k)
        nc = rows.stop - rows.start
        n_contact_points += nc
        point_data = {
            "force_n": _xyz(forces[rows]),
            "normal": _xyz(contacts.normal[rows]),
            "normal_force_n": contacts.normal_force_n[rows],
            "tangent_force_n": contacts.tangent_force_n[rows],
            "body_a": (contacts.body[rows, 0] + 1).astype(np.int32),
            "body_b": (contacts.body[rows, 1] + 1).astype(np.int32),
            "joint": contacts.joint[rows].astype(np.int32),
        }
        mesh = meshio.Mesh(_xyz(contacts.point_m[rows]), [("vertex", np.arange(nc, dtype=np.int64)[:, None])],
                           point_data=point_data)
        files["contacts"].append(_write(meshio, mesh, folder, "contacts", k))

    times = [float(run.time_s[k]) for k in samples]
    pvd = os.path.join(out_dir, f"{stem}.pvd")
    _write_pvd(pvd, times, [(i, files[p]) for i, p in enumerate(parts)])
    part_pvds = {}
    for p in parts:
        part_pvds[p] = os.path.join(out_dir, f"{stem}_{p}.pvd")
        _write_pvd(part_pvds[p], times, [(0, files[p])])
    return VtuExport(pvd, part_pvds, folder, samples, nb, len(joints), arch_joints, tol, n_contact_points, files)


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
