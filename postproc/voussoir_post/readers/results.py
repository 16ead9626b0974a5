"""Readers of the HDF5 result files written by the Fortran drivers.

The layout is the one of ``docs/results_format.md`` (arrays in the shapes h5py reports).
Every reader checks the ``producer`` root attribute against the file kind it reads and
raises :class:`ResultsError`, whose message names the file and what is wrong, for a
missing file, a file that is not HDF5, a file from another producer and a missing
dataset or attribute.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field

import h5py
import numpy as np

__all__ = [
    "ResultsError",
    "ArchGeometry",
    "GroundMotion",
    "ContactRecord",
    "RunResult",
    "SweepResult",
    "LimitResult",
    "read_run",
    "read_sweep",
    "read_limit_json",
    "SIDE_NAMES",
]

from ..namelist import parse_namelist
from .results_common import SIDE_NAMES, ResultsError


# --------------------------------------------------------------------------- helpers


def _as_str(value) -> str:
    """Text of an HDF5 string attribute (fixed or variable length, bytes or str)."""
    if isinstance(value, np.ndarray):
        if value.size != 1:
            return "\n".join(_as_str(v) for v in value.reshape(-1))
        value = value.reshape(-1)[0]
    if isinstance(value, (bytes, np.bytes_)):
        value = bytes(value).decode("utf-8", errors="replace")
    return str(value).rstrip("\x00").rstrip()


def _as_scalar(value):
    """A Python scalar from an attribute stored as a scalar or a 1-element array."""
    arr = np.asarray(value)
    if arr.dtype.kind in "SUO":
        return _as_str(value)
    if arr.size != 1:
        return arr
    item = arr.reshape(-1)[0].item()
    return item


def _open_h5(path, expected_producer: str) -> h5py.File:
    """Open ``path`` read-only after checking it exists, is HDF5 and comes from
    ``expected_producer``."""
    path = os.fspath(path)
    if not os.path.exists(path):
        raise ResultsError(path, "no such file")
    if os.path.isdir(path):
        raise ResultsError(path, "is a directory, expected an HDF5 result file")
    if not h5py.is_hdf5(path):
        raise ResultsError(path, "not an HDF5 file")
    try:
        h5 = h5py.File(path, "r")
    except OSError as exc:  # pragma: no cover - corrupt file that passes is_hdf5
        raise ResultsError(path, f"cannot open HDF5 file: {exc}") from exc
    if "producer" not in h5.attrs:
        h5.close()
        raise ResultsError(path, f"missing root attribute 'producer' (expected '{expected_producer}')")
    producer = _as_str(h5.attrs["producer"])
    if producer != expected_producer:
        h5.close()
        raise ResultsError(
            path,
            f"written by '{producer}', but this command reads '{expected_producer}' files",
        )
    return h5


def _dataset(h5: h5py.File, name: str, dtype=float) -> np.ndarray:
    """The whole dataset ``name`` as a numpy array; ResultsError when absent."""
    if name not in h5:
        raise ResultsError(h5.filename, f"missing dataset '{name}'")
    obj = h5[name]
    if not isinstance(obj, h5py.Dataset):
        raise ResultsError(h5.filename, f"'{name}' is a group, expected a dataset")
    data = obj[()]
    return np.asarray(data, dtype=dtype) if dtype is not None else np.asarray(data)


def _attr(h5obj, name: str, kind=float):
    """Attribute ``name`` of a file, group or dataset converted by ``kind``."""
    if name not in h5obj.attrs:
        where = h5obj.name if h5obj.name != "/" else "root"
        raise ResultsError(h5obj.file.filename, f"missing attribute '{name}' of {where}")
    value = h5obj.attrs[name]
    if kind is str:
        return _as_str(value)
    return kind(_as_scalar(value))


def _optional_str_attr(h5obj, name: str, default: str = "") -> str:
    return _as_str(h5obj.attrs[name]) if name in h5obj.attrs else default


def _check_shape(path, name: str, array: np.ndarray, shape: tuple) -> None:
    """Check ``array.shape`` against ``shape`` (None = any length)."""
    ok = array.ndim == len(shape) and all(s is None or s == a for s, a in zip(shape, array.shape))
    if not ok:
        want = "(" + ", ".join("?" if s is None else str(s) for s in shape) + ")"
        raise ResultsError(path, f"dataset '{name}' has shape {array.shape}, expected {want}")


def _side_names(h5: h5py.File) -> tuple[str, str]:
    """Names of the hinge side codes 0 and 1 from the ``side_names`` attribute of
    /hinges/side or /hinges ('intrados,extrados' or '0=intrados,1=extrados')."""
    for obj in (h5["hinges/side"], h5["hinges"]):
        if "side_names" not in obj.attrs:
            continue
        names = dict(enumerate(SIDE_NAMES))
        items = [s.strip() for s in re.split(r"[,;\s]+", _as_str(obj.attrs["side_names"])) if s.strip()]
        for k, item in enumerate(items):
            code, _, name = item.rpartition("=")
            names[int(code) if code.strip().isdigit() else k] = name.strip()
        return names[0], names[1]
    return SIDE_NAMES


@dataclass
class ArchGeometry:
    """The ``/arch`` group of a run file: joint end points in the reference configuration."""

    n_voussoirs: int
    thickness_m: float
    r_ext_m: float
    embrace_deg: float
    joint_intrados_xy_m: np.ndarray  #: (n+1, 2)
    joint_extrados_xy_m: np.ndarray  #: (n+1, 2)


@dataclass
class GroundMotion:
    """The ``/record`` group of a run driven by an accelerogram: the record and the
    intensity measures of its acceleration as the table played it (scaled)."""

    name: str  #: file name without folder and extension
    description: str  #: event and station line of a PEER .AT2 file ('' for a CSV)
    file: str  #: the record file as resolved by the program
    scale: float  #: record_scale, the factor on the acceleration
    n_samples: int
    dt_s: float
    start_s: float  #: time of the first sample (&motion lead_s: the table still before it)
    pga_m_s2: float
    pga_g: float
    pgv_m_s: float
    arias_m_s: float
    t5_s: float  #: 5 % of the Arias intensity, from the first sample
    t95_s: float
    significant_duration_s: float  #: t95 - t5


def _ground_motion(h5: h5py.File) -> GroundMotion:
    g = h5["record"]
    return GroundMotion(
        name=_attr(g, "name", str), description=_attr(g, "description", str), file=_attr(g, "file", str),
        scale=_attr(g, "scale"), n_samples=_attr(g, "n_samples", int), dt_s=_attr(g, "dt_s"),
        start_s=_attr(g, "start_s"), pga_m_s2=_attr(g, "pga_m_s2"), pga_g=_attr(g, "pga_g"),
        pgv_m_s=_attr(g, "pgv_m_s"), arias_m_s=_attr(g, "arias_m_s"), t5_s=_attr(g, "t5_s"),
        t95_s=_attr(g, "t95_s"), significant_duration_s=_attr(g, "significant_duration_s"))


@dataclass
class ContactRecord:
    """The loaded contacts of every sample of a run (/contacts, docs/results_format.md):
    one flat list, the rows of sample s being ``start[s]:start[s + 1]``."""

    dt_s: float  #: the time step: force = impulse / dt_s
    start: np.ndarray  #: (nt + 1,) 0-based offsets into the rows
    body: np.ndarray  #: (nc, 2) bodies a, b (0-based, as the rows of RunResult.body_role)
    joint: np.ndarray  #: (nc,) arch joint 0..n, -1 when none
    point_m: np.ndarray  #: (nc, 2) contact point [m]
    normal: np.ndarray  #: (nc, 2) unit normal from b towards a
    normal_impulse_n_s: np.ndarray  #: (nc,) on a, along the normal [N s]
    tangent_impulse_n_s: np.ndarray  #: (nc,) on a, along t = (-n_y, n_x) [N s]
    normal_force_n: np.ndarray  #: (nc,) mean over the step [N]
    tangent_force_n: np.ndarray  #: (nc,) mean over the step [N]

    @property
    def n_rows(self) -> int:
        return int(self.joint.shape[0])

    def rows(self, sample: int) -> slice:
        """The rows of sample `sample` (0-based; negative counts from the end)."""
        n = self.start.shape[0] - 1
        s = sample + n if sample < 0 else sample
        return slice(int(self.start[s]), int(self.start[s + 1]))

    def force_on_a_n(self) -> np.ndarray:
        """(nc, 2) world x, y of the mean force on body a of every row [N]."""
        tangent = np.column_stack([-self.normal[:, 1], self.normal[:, 0]])
        return self.normal_force_n[:, None] * self.normal + self.tangent_force_n[:, None] * tangent


def _contact_record(path: str, h5: h5py.File, nt: int, nb: int) -> ContactRecord | None:
    """/contacts of a run, or None for a file written before contacts were recorded."""
    if "contacts/start" not in h5:
        return None
    start = _dataset(h5, "contacts/start", dtype=int).reshape(-1)
    _check_shape(path, "/contacts/start", start, (nt + 1,))
    nc = int(start[-1]) if nt >= 0 else 0
    if start[0] != 0 or np.any(np.diff(start) < 0):
        raise ResultsError(path, "'/contacts/start' is not a non-decreasing list of offsets from 0")
    arrays = {}
    for name, shape, dtype in (("body", (nc, 2), int), ("joint", (nc,), int), ("point_m", (nc, 2), float),
                               ("normal", (nc, 2), float), ("normal_impulse_n_s", (nc,), float),
                               ("tangent_impulse_n_s", (nc,), float), ("normal_force_n", (nc,), float),
                               ("tangent_force_n", (nc,), float)):
        a = _dataset(h5, "contacts/" + name, dtype=dtype)
        a = a.reshape(shape) if a.size == 0 else a
        _check_shape(path, "/contacts/" + name, a, shape)
        arrays[name] = a
    body = arrays.pop("body") - 1
    if nc and (body.min() < 0 or body.max() >= nb):
        raise ResultsError(path, f"'/contacts/body' out of range 1..{nb}")
    return ContactRecord(dt_s=_attr(h5["contacts"], "dt_s"), start=start, body=body, **arrays)


@dataclass
class RunResult:
    """One ``voussoir-run`` result file (see docs/results_format.md)."""

    path: str
    code_version: str
    created_utc: str
    config_nml: str
    input_file: str
    config: dict  #: {group: {variable: value}} from /config
    # /result attributes
    collapsed: bool
    collapse_time_s: float
    peak_crown_disp_m: float
    mean_iterations: float
    max_iterations: int
    nonconverged_steps: int
    n_steps: int
    wall_time_s: float
    # samples (nt,)
    time_s: np.ndarray
    table_x_m: np.ndarray
    table_v_m_s: np.ndarray
    table_a_m_s2: np.ndarray
    crown_dx_m: np.ndarray
    crown_dy_m: np.ndarray
    contact_count: np.ndarray
    # bodies
    body_position: np.ndarray  #: (nt, nb, 3): centroid x [m], y [m], rotation [rad]
    vertices_local_m: np.ndarray  #: (nb, max_nv, 2), NaN padded
    n_vertices: np.ndarray  #: (nb,)
    body_role: np.ndarray  #: (nb,) 1 voussoir, 2 foundation, 3 restraint bracket
    # steps (ns,)
    step_time_s: np.ndarray
    step_iterations: np.ndarray
    step_norm: np.ndarray
    # hinge events (nh,)
    hinge_time_s: np.ndarray
    hinge_joint: np.ndarray
    hinge_side: np.ndarray  #: 0 intrados, 1 extrados
    hinge_side_names: tuple = SIDE_NAMES
    arch: ArchGeometry | None = None
    record: GroundMotion | None = None  #: runs driven by an accelerogram only
    #: The loaded contacts of every sample (None in files written before they were recorded).
    contacts: ContactRecord | None = None
    #: The signal that stopped the run early (2 SIGINT, 15 SIGTERM; 0: it ran to its end).
    interrupted_by_signal: int = 0
    #: The largest final displacement of a free block relative to the table [m] (NaN in
    #: files written before it was recorded), and that block's body index (1-based).
    max_residual_disp_m: float = float("nan")
    max_residual_body: int = 0
    #: The table's vertical displacement [m], velocity [m/s] and acceleration [m/s2],
    #: upwards (None for a motion without a vertical component).
    table_y_m: np.ndarray | None = None
    table_vy_m_s: np.ndarray | None = None
    table_ay_m_s2: np.ndarray | None = None

    @property
    def n_samples(self) -> int:
        return int(self.time_s.shape[0])

    @property
    def n_bodies(self) -> int:
        return int(self.body_role.shape[0])


def read_run(path: str | os.PathLike) -> RunResult:
    """Read a ``voussoir-run`` HDF5 file into a :class:`RunResult`.

    Raises :class:`ResultsError` for a missing or non-HDF5 file, another producer, a
    missing dataset or attribute, or inconsistent shapes.
    """
    path = os.fspath(path)
    with _open_h5(path, "voussoir-run") as h5:
        config: dict[str, dict[str, object]] = {}
        if "config" in h5:
            for gname, group in h5["config"].items():
                config[gname] = {k: _as_scalar(v) for k, v in group.attrs.items()}
        if "result" not in h5:
            raise ResultsError(path, "missing group '/result'")
        res = h5["result"]

        time_s = _dataset(h5, "time_s")
        nt = time_s.shape[0]
        _check_shape(path, "/time_s", time_s, (None,))
        samples = {}
        for name in ("table/x_m", "table/v_m_s", "table/a_m_s2", "crown/dx_m", "crown/dy_m",
                     "contacts/count"):
            samples[name] = _dataset(h5, name)
            _check_shape(path, "/" + name, samples[name], (nt,))
        for name in ("table/y_m", "table/vy_m_s", "table/ay_m_s2"):
            samples[name] = _dataset(h5, name) if name in h5 else None
            if samples[name] is not None:
                _check_shape(path, "/" + name, samples[name], (nt,))

        role = _dataset(h5, "bodies/role", dtype=int)
        nb = role.shape[0]
        _check_shape(path, "/bodies/role", role, (None,))
        position = _dataset(h5, "bodies/position")
        _check_shape(path, "/bodies/position", position, (nt, nb, 3))
        vertices = _dataset(h5, "bodies/vertices_local_m")
        _check_shape(path, "/bodies/vertices_local_m", vertices, (nb, None, 2))
        n_vertices = _dataset(h5, "bodies/n_vertices", dtype=int)
        _check_shape(path, "/bodies/n_vertices", n_vertices, (nb,))
        if np.any(n_vertices < 3) or np.any(n_vertices > vertices.shape[1]):
            raise ResultsError(path, "'/bodies/n_vertices' out of range 3..max_nv")

        step_time = _dataset(h5, "solver/time_s")
        ns = step_time.shape[0]
        iterations = _dataset(h5, "solver/iterations", dtype=int)
        _check_shape(path, "/solver/iterations", iterations, (ns,))
        norm = _dataset(h5, "solver/norm")
        _check_shape(path, "/solver/norm", norm, (ns,))

        hinge_time = _dataset(h5, "hinges/time_s").reshape(-1)
        nh = hinge_time.shape[0]
        hinge_joint = _dataset(h5, "hinges/joint", dtype=int).reshape(-1)
        _check_shape(path, "/hinges/joint", hinge_joint, (nh,))
        hinge_side = _dataset(h5, "hinges/side", dtype=int).reshape(-1)
        _check_shape(path, "/hinges/side", hinge_side, (nh,))
        side_names = _side_names(h5)

        arch = None
        if "arch" in h5:
            g = h5["arch"]
            n = _attr(g, "n_voussoirs", int)
            intr = _dataset(h5, "arch/joint_intrados_xy_m")
            extr = _dataset(h5, "arch/joint_extrados_xy_m")
            _check_shape(path, "/arch/joint_intrados_xy_m", intr, (n + 1, 2))
            _check_shape(path, "/arch/joint_extrados_xy_m", extr, (n + 1, 2))
            arch = ArchGeometry(
                n_voussoirs=n,
                thickness_m=_attr(g, "thickness_m"),
                r_ext_m=_attr(g, "r_ext_m"),
                embrace_deg=_attr(g, "embrace_deg"),
                joint_intrados_xy_m=intr,
                joint_extrados_xy_m=extr,
            )

        return RunResult(
            path=path,
            code_version=_optional_str_attr(h5, "code_version"),
            created_utc=_optional_str_attr(h5, "created_utc"),
            config_nml=_optional_str_attr(h5, "config_nml"),
            input_file=_optional_str_attr(h5, "input_file"),
            config=config,
            collapsed=bool(_attr(res, "collapsed", int)),
            collapse_time_s=_attr(res, "collapse_time_s"),
            peak_crown_disp_m=_attr(res, "peak_crown_disp_m"),
            mean_iterations=_attr(res, "mean_iterations"),
            max_iterations=_attr(res, "max_iterations", int),
            nonconverged_steps=_attr(res, "nonconverged_steps", int),
            n_steps=_attr(res, "n_steps", int),
            wall_time_s=_attr(res, "wall_time_s"),
            interrupted_by_signal=(_attr(res, "interrupted_by_signal", int)
                                   if "interrupted_by_signal" in res.attrs else 0),
            max_residual_disp_m=(_attr(res, "max_residual_disp_m") if "max_residual_disp_m" in res.attrs
                                 else float("nan")),
            max_residual_body=(_attr(res, "max_residual_body", int) if "max_residual_body" in res.attrs else 0),
            time_s=time_s,
            table_x_m=samples["table/x_m"],
            table_v_m_s=samples["table/v_m_s"],
            table_a_m_s2=samples["table/a_m_s2"],
            crown_dx_m=samples["crown/dx_m"],
            crown_dy_m=samples["crown/dy_m"],
            contact_count=samples["contacts/count"].astype(int),
            body_position=position,
            vertices_local_m=vertices,
            n_vertices=n_vertices,
            body_role=role,
            step_time_s=step_time,
            step_iterations=iterations,
            step_norm=norm,
            hinge_time_s=hinge_time,
            hinge_joint=hinge_joint,
            hinge_side=hinge_side,
            hinge_side_names=side_names,
            arch=arch,
            record=_ground_motion(h5) if "record" in h5 else None,
            contacts=_contact_record(path, h5, nt, nb),
            table_y_m=samples["table/y_m"],
            table_vy_m_s=samples["table/vy_m_s"],
            table_ay_m_s2=samples["table/ay_m_s2"],
        )


# ---------------------------------------------------------------------- sweep files

_THRESHOLD_COLUMNS = ("job", "param_set", "frequency_hz", "mean_iterations", "threshold_m",
                      "peak_accel_m_s2", "non_monotonic", "n_runs")
_GRID_COLUMNS = ("job", "param_set", "frequency_hz", "amplitude_m", "collapsed",
                 "collapse_time_s", "peak_crown_disp_m", "mean_iterations")


@dataclass
class SweepResult:
    """One ``voussoir-sweep`` result file; ``results`` rows sorted by job index."""

    path: str
    mode: str  #: 'threshold' or 'grid'
    sweep_signature: str
    n_jobs: int
    parameter_names: list[str]
    parameter_values: np.ndarray  #: (n_sets, n_params)
    results: dict[str, np.ndarray]  #: column name -> (n_rows,) sorted by job
    code_version: str = ""
    created_utc: str = ""
    config_nml: str = ""
    config: dict = field(default_factory=dict)  #: parsed config_nml {group: {var: value}}

    @property
    def n_sets(self) -> int:
        return int(self.parameter_values.shape[0])

    @property
    def n_rows(self) -> int:
        return int(self.results["job"].shape[0])

    def set_label(self, param_set: int) -> str:
        """Human label of a parameter set: 'name=value, ...' or 'nominal'."""
        if not self.parameter_names:
            return "nominal"
        values = self.parameter_values[param_set]
        return ", ".join(f"{n}={v:.6g}" for n, v in zip(self.parameter_names, values))

    def set_parameters(self, param_set: int) -> dict[str, float]:
        """The swept parameter values of one set as a dict."""
        return {n: float(v) for n, v in zip(self.parameter_names, self.parameter_values[param_set])}


def read_sweep(path: str | os.PathLike) -> SweepResult:
    """Read a ``voussoir-sweep`` HDF5 file into a :class:`SweepResult`.

    Rows of ``/results`` are sorted by the ``job`` column (the file stores them in order
    of completion). A partly finished sweep (fewer rows than ``n_jobs``) is read as it is.
    """
    path = os.fspath(path)
    with _open_h5(path, "voussoir-sweep") as h5:
        mode = _attr(h5, "mode", str)
        if mode not in ("threshold", "grid"):
            raise ResultsError(path, f"root attribute 'mode' is '{mode}', expected 'threshold' or 'grid'")
        names_text = _attr(h5, "parameter_names", str)
        names = [n.strip() for n in names_text.split(",") if n.strip()]
        if names:
            values = _dataset(h5, "parameters/values")
            if values.ndim == 1 and len(names) == 1:
                values = values.reshape(-1, 1)
            _check_shape(path, "/parameters/values", values, (None, len(names)))
        else:
            values = np.zeros((1, 0))
        columns = _THRESHOLD_COLUMNS if mode == "threshold" else _GRID_COLUMNS
        if "results" not in h5:
            raise ResultsError(path, "missing group '/results'")
        results = {}
        for col in columns:
            results[col] = _dataset(h5, f"results/{col}").reshape(-1)
        if mode == "threshold":
            if "full_cycle_accel_m_s2" in h5["results"]:
                results["full_cycle_accel_m_s2"] = _dataset(h5, "results/full_cycle_accel_m_s2").reshape(-1)
            else:
                # Before full_cycle_accel_m_s2 was written, peak_accel_m_s2 held A (2 pi f)^2,
                # not the peak of the motion: it is read under its true name, and the peak
                # is left to the reader of the file (voussoir_post.analysis.afd).
                results["full_cycle_accel_m_s2"] = results.pop("peak_accel_m_s2")
        n_rows = results["job"].shape[0]
        for col in results:
            _check_shape(path, f"/results/{col}", results[col], (n_rows,))
        order = np.argsort(results["job"], kind="stable")
        results = {k: v[order] for k, v in results.items()}
        for col in ("job", "param_set", "collapsed", "non_monotonic", "n_runs"):
            if col in results:
                results[col] = results[col].astype(int)
        if n_rows and (results["param_set"].min() < 0 or results["param_set"].max() >= values.shape[0]):
            raise ResultsError(path, "'/results/param_set' refers to a parameter set that "
                                     f"'/parameters/values' does not have ({values.shape[0]} sets)")
        config_nml = _optional_str_attr(h5, "config_nml")
        return SweepResult(
            path=path,
            mode=mode,
            sweep_signature=_attr(h5, "sweep_signature", str),
            n_jobs=_attr(h5, "n_jobs", int),
            parameter_names=names,
            parameter_values=values,
            results=results,
            code_version=_optional_str_attr(h5, "code_version"),
            created_utc=_optional_str_attr(h5, "created_utc"),
            config_nml=config_nml,
            config=parse_namelist(config_nml),
        )


# The limit JSON reader lives in limit_results.py; its names stay importable from here.
from .limit_results import LimitResult, read_limit_json  # noqa: E402
