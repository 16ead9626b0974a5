"""XDMF 3 export of a run for ParaView.

The run file stores rigid polygons as reference vertices plus a position and rotation
per sample, which XDMF cannot express. :func:`write_xdmf` computes the vertex
coordinates of every sample and writes them into a companion HDF5 file
``RUN.vtk.h5`` (the run file is not modified), then ``RUN.xmf``: a temporal collection
of spatial collections, one per output sample, each holding the grid ``blocks`` (a Mixed
topology of one polygon per body: XDMF cell type 3, followed by its vertex count and
vertex ids, and XYZ geometry, z = 0) and, when the sample has loaded contacts and the run
recorded them, the grid ``contacts``: one point per contact (Polyvertex) with the contact
force as a point vector, so that ParaView draws the forces with its Glyph filter (Glyph
Type Arrow, Orientation Array ``force_n``, Scale Array ``force_n``, scale factor in m/N).
The vector is the mean force over the step on the contact's body a, which points into
that body (its compression); body b receives the opposite.

Companion file layout:

    /topology/mixed          (n_conn,) int64   3, nv_0, ids..., 3, nv_1, ids...
    /time_s                  (nt,)
    /cells/body              (nb,) int32       body number, from 1 (as /bodies and the text outputs)
    /cells/role              (nb,) int32       1 voussoir, 2 foundation, 3 bracket
    /samples/NNNNNN/xyz_m    (nv_total, 3)     vertex coordinates at sample NNNNNN
    /samples/NNNNNN/rotation_rad      (nb,)    cell data
    /samples/NNNNNN/displacement_m    (nb, 3)  centroid displacement from t = 0 (z = 0)
    /samples/NNNNNN/contacts/xyz_m    (nc, 3)  contact points (z = 0); point data:
    /samples/NNNNNN/contacts/force_n  (nc, 3)  force on body a [N] (z = 0)
    /samples/NNNNNN/contacts/normal_force_n, tangent_force_n (nc,)  its components [N]
    /samples/NNNNNN/contacts/body_a, body_b, joint (nc,) int32  bodies from 1, arch joint 0..n or -1
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass

import h5py
import numpy as np

from ..analysis.kinematics import rotation_matrix
from ..errors import CheckError
from ..readers.results import RunResult
from ..tables import ReportTable

__all__ = ["XdmfData", "write_xdmf", "check_xdmf", "XDMF_POLYGON"]

XDMF_POLYGON = 3  #: XDMF cell type id of a polygon in a Mixed topology


@dataclass
class XdmfData:
    """What :func:`write_xdmf` wrote."""

    xmf_path: str
    h5_path: str
    n_samples: int
    n_bodies: int
    n_vertices_total: int
    connectivity: np.ndarray
    n_contact_points: int = 0  #: contact points written, over all samples

    def table(self, run_path: str, n_checked: int) -> ReportTable:
        """What was written, and how many HDF5 items :func:`check_xdmf` checked."""
        return ReportTable(["samples", "bodies", "vertices", "contact_points", "hdf_items_checked"],
                           [(self.n_samples, self.n_bodies, self.n_vertices_total, self.n_contact_points,
                             n_checked)],
                           title=f"XDMF of {run_path}")


def _vertex_coordinates(run: RunResult, sample: int) -> np.ndarray:
    """(nv_total, 3) world coordinates of every vertex of every body at ``sample``."""
    pos = run.body_position[sample]
    rot = rotation_matrix(pos[:, 2])
    parts = []
    for b in range(run.n_bodies):
        local = run.vertices_local_m[b, : run.n_vertices[b]]
        parts.append(pos[b, :2] + local @ rot[b].T)
    xy = np.vstack(parts)
    return np.column_stack([xy, np.zeros(xy.shape[0])])


def _connectivity(n_vertices: np.ndarray) -> np.ndarray:
    conn, start = [], 0
    for nv in n_vertices:
        conn += [XDMF_POLYGON, int(nv)] + list(range(start, start + int(nv)))
        start += int(nv)
    return np.asarray(conn, dtype=np.int64)


def _data_item(parent, dims, number_type, precision, h5_name, dataset):
    item = ET.SubElement(parent, "DataItem", Dimensions=" ".join(str(d) for d in dims), Format="HDF",
                         NumberType=number_type, Precision=str(precision))
    item.text = f"{h5_name}:{dataset}"
    return item


def write_xdmf(run: RunResult, xmf_path: str | os.PathLike | None = None,
               every: int = 1) -> XdmfData:
    """Write ``RUN.vtk.h5`` and ``RUN.xmf`` beside the run (or at ``xmf_path``), one grid
    per ``every``-th output sample. Returns the paths and sizes written."""
    stem = os.path.splitext(run.path)[0]
    xmf_path = os.fspath(xmf_path) if xmf_path is not None else stem + ".xmf"
    h5_path = os.path.splitext(xmf_path)[0] + ".vtk.h5"
    os.makedirs(os.path.dirname(os.path.abspath(xmf_path)), exist_ok=True)
    h5_name = os.path.basename(h5_path)  # referenced relative to the .xmf
    samples = list(range(0, run.n_samples, max(int(every), 1)))
    conn = _connectivity(run.n_vertices)
    nv_total = int(run.n_vertices.sum())
    nb = run.n_bodies

    with h5py.File(h5_path, "w") as h5:
        h5.attrs["source_run"] = os.path.abspath(run.path)
        h5["topology/mixed"] = conn
        h5["time_s"] = run.time_s[samples]
        h5["cells/body"] = np.arange(1, nb + 1, dtype=np.int32)
        h5["cells/role"] = run.body_role.astype(np.int32)
        ref = run.body_position[0, :, :2]
        contacts = run.contacts
        forces = contacts.force_on_a_n() if contacts is not None else None
        n_contacts = {}
        for k in samples:
            g = h5.create_group(f"samples/{k:06d}")
            g["xyz_m"] = _vertex_coordinates(run, k)
            g["rotation_rad"] = run.body_position[k, :, 2]
            disp = run.body_position[k, :, :2] - ref
            g["displacement_m"] = np.column_stack([disp, np.zeros(nb)])
            if contacts is None:
                continue
            rows = contacts.rows(k)
            n_contacts[k] = rows.stop - rows.start
            if n_contacts[k] == 0:
                continue
            zero = np.zeros((n_contacts[k], 1))
            c = g.create_group("contacts")
            c["xyz_m"] = np.hstack([contacts.point_m[rows], zero])
            c["force_n"] = np.hstack([forces[rows], zero])
            c["normal_force_n"] = contacts.normal_force_n[rows]
            c["tangent_force_n"] = contacts.tangent_force_n[rows]
            c["body_a"] = (contacts.body[rows, 0] + 1).astype(np.int32)
            c["body_b"] = (contacts.body[rows, 1] + 1).astype(np.int32)
            c["joint"] = contacts.joint[rows].astype(np.int32)

    root = ET.Element("Xdmf", Version="3.0")
    domain = ET.SubElement(root, "Domain")
    series = ET.SubElement(domain, "Grid", Name=os.path.basename(stem), GridType="Collection",
                           CollectionType="Temporal")
    for k in samples:
        sample = ET.SubElement(series, "Grid", Name=f"sample_{k:06d}", GridType="Collection",
                               CollectionType="Spatial")
        ET.SubElement(sample, "Time", Value=repr(float(run.time_s[k])))
        grid = ET.SubElement(sample, "Grid", Name="blocks", GridType="Uniform")
        topo = ET.SubElement(grid, "Topology", TopologyType="Mixed", NumberOfElements=str(nb))
        _data_item(topo, (conn.size,), "Int", 8, h5_name, "/topology/mixed")
        geom = ET.SubElement(grid, "Geometry", GeometryType="XYZ")
        _data_item(geom, (nv_total, 3), "Float", 8, h5_name, f"/samples/{k:06d}/xyz_m")
        for name, dims, ntype, prec, dset in (
            ("body", (nb,), "Int", 4, "/cells/body"),
            ("role", (nb,), "Int", 4, "/cells/role"),
            ("rotation_rad", (nb,), "Float", 8, f"/samples/{k:06d}/rotation_rad"),
        ):
            attr = ET.SubElement(grid, "Attribute", Name=name, AttributeType="Scalar", Center="Cell")
            _data_item(attr, dims, ntype, prec, h5_name, dset)
        attr = ET.SubElement(grid, "Attribute", Name="displacement_m", AttributeType="Vector", Center="Cell")
        _data_item(attr, (nb, 3), "Float", 8, h5_name, f"/samples/{k:06d}/displacement_m")
        if n_contacts.get(k, 0) > 0:
            _contacts_grid(sample, n_contacts[k], h5_name, f"/samples/{k:06d}/contacts")
    ET.indent(root)
    with open(xmf_path, "w", encoding="utf-8") as f:
        f.write('<?xml version="1.0" ?>\n<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>\n')
        f.write(ET.tostring(root, encoding="unicode"))
        f.write("\n")
    return XdmfData(xmf_path, h5_path, len(samples), nb, nv_total, conn, sum(n_contacts.values()))


def _contacts_grid(parent, nc: int, h5_name: str, group: str) -> None:
    """The grid of a sample's `nc` contact points with their forces as point data."""
    grid = ET.SubElement(parent, "Grid", Name="contacts", GridType="Uniform")
    ET.SubElement(grid, "Topology", TopologyType="Polyvertex", NumberOfElements=str(nc), NodesPerElement="1")
    geom = ET.SubElement(grid, "Geometry", GeometryType="XYZ")
    _data_item(geom, (nc, 3), "Float", 8, h5_name, f"{group}/xyz_m")
    attr = ET.SubElement(grid, "Attribute", Name="force_n", AttributeType="Vector", Center="Node")
    _data_item(attr, (nc, 3), "Float", 8, h5_name, f"{group}/force_n")
    for name, ntype, prec in (("normal_force_n", "Float", 8), ("tangent_force_n", "Float", 8),
                              ("body_a", "Int", 4), ("body_b", "Int", 4), ("joint", "Int", 4)):
        attr = ET.SubElement(grid, "Attribute", Name=name, AttributeType="Scalar", Center="Node")
        _data_item(attr, (nc,), ntype, prec, h5_name, f"{group}/{name}")


def check_xdmf(xmf_path: str | os.PathLike) -> list[tuple[str, str, tuple[int, ...]]]:
    """Parse an XDMF file and check that every HDF DataItem names an existing dataset of
    the stated dimensions, that Mixed topologies hold NumberOfElements polygons whose
    vertex ids are inside the geometry, and that a Polyvertex grid (the contacts) has
    as many points as elements. Returns (file, dataset, dims) of every item;
    raises CheckError (a ValueError) on the first problem."""
    xmf_path = os.fspath(xmf_path)
    base = os.path.dirname(os.path.abspath(xmf_path))
    root = ET.parse(xmf_path).getroot()
    if root.tag != "Xdmf":
        raise CheckError(f"{xmf_path}: root element is <{root.tag}>, expected <Xdmf>")
    items, files = [], {}
    try:
        for item in root.iter("DataItem"):
            if item.get("Format") != "HDF":
                continue
            fname, dset = item.text.strip().split(":", 1)
            dims = tuple(int(d) for d in item.get("Dimensions").split())
            path = os.path.join(base, fname)
            if path not in files:
                if not os.path.exists(path):
                    raise CheckError(f"{xmf_path}: DataItem refers to missing file {fname}")
                files[path] = h5py.File(path, "r")
            h5 = files[path]
            if dset not in h5:
                raise CheckError(f"{xmf_path}: dataset {fname}:{dset} does not exist")
            if h5[dset].shape != dims:
                raise CheckError(f"{xmf_path}: {fname}:{dset} has shape {h5[dset].shape}, XML says {dims}")
            items.append((fname, dset, dims))
        for grid in root.iter("Grid"):
            topo, geom = grid.find("Topology"), grid.find("Geometry")
            if topo is None or geom is None:
                continue
            n_elem = int(topo.get("NumberOfElements"))
            if topo.get("TopologyType") == "Polyvertex":
                n_points = int(geom.find("DataItem").get("Dimensions").split()[0])
                if n_points != n_elem:
                    raise CheckError(f"{xmf_path}: {n_points} points in a Polyvertex grid, NumberOfElements={n_elem}")
                continue
            t_item, g_item = topo.find("DataItem"), geom.find("DataItem")
            tf, td = t_item.text.strip().split(":", 1)
            conn = files[os.path.join(base, tf)][td][()]
            n_points = int(g_item.get("Dimensions").split()[0])
            k, count = 0, 0
            while k < conn.size:
                if conn[k] != XDMF_POLYGON:
                    raise CheckError(f"{xmf_path}: cell type {conn[k]} at {k}, expected {XDMF_POLYGON}")
                nv = int(conn[k + 1])
                ids = conn[k + 2: k + 2 + nv]
                if ids.size != nv or ids.min() < 0 or ids.max() >= n_points:
                    raise CheckError(f"{xmf_path}: polygon {count} has vertex ids outside 0..{n_points - 1}")
                k += 2 + nv
                count += 1
            if count != n_elem:
                raise CheckError(f"{xmf_path}: {count} polygons in the topology, NumberOfElements={n_elem}")
    finally:
        for h5 in files.values():
            h5.close()
    return items
