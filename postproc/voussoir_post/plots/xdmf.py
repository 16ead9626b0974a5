"""XDMF 3 export of a run for ParaView.

The run file stores rigid polygons as reference vertices plus a position and rotation
per sample, which XDMF cannot express. :func:`write_xdmf` computes the vertex
coordinates of every sample and writes them into a companion HDF5 file
``RUN.vtk.h5`` (the run file is not modified), then ``RUN.xmf``: a temporal collection
of uniform grids, one per output sample, with a Mixed topology of one polygon per body
(XDMF cell type 3, followed by its vertex count and vertex ids) and XYZ geometry (z = 0).

Companion file layout:

    /topology/mixed          (n_conn,) int64   3, nv_0, ids..., 3, nv_1, ids...
    /time_s                  (nt,)
    /cells/body              (nb,) int32       0-based body index
    /cells/role              (nb,) int32       1 voussoir, 2 foundation, 3 bracket
    /samples/NNNNNN/xyz_m    (nv_total, 3)     vertex coordinates at sample NNNNNN
    /samples/NNNNNN/rotation_rad      (nb,)    cell data
    /samples/NNNNNN/displacement_m    (nb, 3)  centroid displacement from t = 0 (z = 0)
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

    def table(self, run_path: str, n_checked: int) -> ReportTable:
        """What was written, and how many HDF5 items :func:`check_xdmf` checked."""
        return ReportTable(["samples", "bodies", "vertices", "hdf_items_checked"],
                           [(self.n_samples, self.n_bodies, self.n_vertices_total, n_checked)],
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
        h5["cells/body"] = np.arange(nb, dtype=np.int32)
        h5["cells/role"] = run.body_role.astype(np.int32)
        ref = run.body_position[0, :, :2]
        for k in samples:
            g = h5.create_group(f"samples/{k:06d}")
            g["xyz_m"] = _vertex_coordinates(run, k)
            g["rotation_rad"] = run.body_position[k, :, 2]
            disp = run.body_position[k, :, :2] - ref
            g["displacement_m"] = np.column_stack([disp, np.zeros(nb)])

    root = ET.Element("Xdmf", Version="3.0")
    domain = ET.SubElement(root, "Domain")
    series = ET.SubElement(domain, "Grid", Name=os.path.basename(stem), GridType="Collection",
                           CollectionType="Temporal")
    for k in samples:
        grid = ET.SubElement(series, "Grid", Name=f"sample_{k:06d}", GridType="Uniform")
        ET.SubElement(grid, "Time", Value=repr(float(run.time_s[k])))
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
    ET.indent(root)
    with open(xmf_path, "w", encoding="utf-8") as f:
        f.write('<?xml version="1.0" ?>\n<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>\n')
        f.write(ET.tostring(root, encoding="unicode"))
        f.write("\n")
    return XdmfData(xmf_path, h5_path, len(samples), nb, nv_total, conn)


def check_xdmf(xmf_path: str | os.PathLike) -> list[tuple[str, str, tuple[int, ...]]]:
    """Parse an XDMF file and check that every HDF DataItem names an existing dataset of
    the stated dimensions, that Mixed topologies hold NumberOfElements polygons whose
    vertex ids are inside the geometry. Returns (file, dataset, dims) of every item;
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
