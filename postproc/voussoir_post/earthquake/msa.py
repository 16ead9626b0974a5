"""Reader of multiple-stripe analysis (MSA) results: ``voussoir-sweep`` in ``&sweep mode
= 'msa'`` writes an HDF5 file and a CSV beside it, one row per run: a record on a model
sample, scaled so that its PGA is one of the levels ``msa_levels_g`` [g], and whether
the arch collapsed (docs/earthquakes.md, docs/sweep.md).

A run that stopped with an error (``failed`` = 1) says nothing of the outcome: it is
kept in the rows and left out of the stripes. :meth:`MsaResult.stripes` gives what
Baker's binomial fit (:mod:`voussoir_post.earthquake.stripes_fit`) takes; the runs of
one record are one bootstrap cluster, under its event when the file names events.

Each run also keeps its largest joint opening and the crown's residual drift at its end
(mm): :meth:`MsaResult.exceeded` turns them into the outcome of a limit state short of
collapse (hinge onset: an opening above about 1 mm; a residual drift above a stated
value), so that their fragilities come from the same stripes. A run that collapsed
exceeds every limit state.

Both files are accepted; an error names the file and, for the CSV, the line and column.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import h5py
import numpy as np

from ..errors import ResultsError
from ..readers.csv_table import read_csv_table
from .ida import RECORD_COLUMNS, _events, _text, read_sweep_rows, record_columns

__all__ = ["MsaResult", "MSA_COLUMNS", "LIMIT_STATES", "read_msa", "is_msa"]

#: The columns every MSA CSV has (others, e.g. the sampled parameters, are kept apart).
MSA_COLUMNS = ("record", "param_set", "level_g", "scale", "collapsed", "failed")
_TEXT = ("record", "event")
_FLAGS = ("collapsed", "failed")
#: Optional numbers of each row: its record's magnitude, distance [km] and own PGA [m/s2],
#: the run's collapse time [s], peak crown displacement [m] and mean NLGS iterations, and
#: lambda g of its model [m/s2]; its record's Vs30, pulse and pulse period (RECORD_COLUMNS).
_OPTIONAL_REAL = ("magnitude", "distance_km", "pga_m_s2", "collapse_time_s", "peak_crown_disp_m", "mean_iterations",
                  "static_capacity_m_s2", "max_joint_opening_mm", "residual_drift_mm") + RECORD_COLUMNS
#: The limit states a run's outcome can be read against: its column (None: collapsed) and
#: what exceeding it means.
LIMIT_STATES = {"collapse": (None, "collapse"),
                "hinge-onset": ("max_joint_opening_mm", "a joint opened by more than {mm:g} mm (or collapse)"),
                "residual-drift": ("residual_drift_mm", "a residual crown drift above {mm:g} mm (or collapse)")}


@dataclass
class MsaResult:
    """The runs of an MSA sweep, in file order."""

    path: str
    record: list[str]  #: the record of each run (the file given to the sweep, or the set's name)
    param_set: np.ndarray  #: int
    level_g: np.ndarray  #: the PGA the record was scaled to [g]
    scale: np.ndarray  #: the record's scale factor
    collapsed: np.ndarray  #: bool
    failed: np.ndarray  #: bool: the run stopped with an error (no outcome)
    event: list[str] | None = None  #: the earthquake of each run's record, when the file names it
    pga_m_s2: np.ndarray | None = None  #: the record's own PGA at scale 1 [m/s2]
    static_capacity_m_s2: np.ndarray | None = None  #: lambda g of the run's model [m/s2]
    parameters: dict[str, np.ndarray] = field(default_factory=dict)  #: sampled model parameters per run
    config: dict = field(default_factory=dict)  #: the base case {group: {var: value}} when known
    code_version: str = ""
    record_set: str = ""
    max_joint_opening_mm: np.ndarray | None = None  #: the run's largest joint opening [mm]
    residual_drift_mm: np.ndarray | None = None  #: the crown's horizontal drift from the table at the end [mm]
    vs30_m_s: np.ndarray | None = None  #: the site's Vs30 of the run's record (NaN: unknown), when the file has it
    pulse: np.ndarray | None = None  #: float: 1 a pulse, 0 none, NaN not classified; when the file has it
    pulse_period_s: np.ndarray | None = None  #: Tp of the record's pulse (NaN: none or unknown), when the file has it

    @property
    def n_rows(self) -> int:
        return len(self.record)

    def exceeded(self, limit_state: str = "collapse", threshold_mm: float | None = None) -> tuple[np.ndarray, str]:
        """(bool per row, the limit state in words): whether each run exceeded
        ``limit_state`` (a key of LIMIT_STATES): collapsed, or collapsed or its column
        above ``threshold_mm`` (|residual drift|). ResultsError when the file lacks the
        column; ValueError for an unknown limit state or a threshold not > 0."""
        if limit_state not in LIMIT_STATES:
            raise ValueError(f"limit state '{limit_state}': one of {', '.join(LIMIT_STATES)}")
        column, words = LIMIT_STATES[limit_state]
        if column is None:
            return self.collapsed.copy(), words
        if threshold_mm is None or not (math.isfinite(threshold_mm) and threshold_mm > 0.0):
            raise ValueError(f"limit state '{limit_state}' needs a threshold > 0 mm, got {threshold_mm!r}")
        values = getattr(self, column)
        if values is None:
            raise ResultsError(self.path, f"no column {column}: the file was written before voussoir-sweep kept it")
        with np.errstate(invalid="ignore"):
            beyond = np.abs(values) > threshold_mm
        return self.collapsed | beyond, words.format(mm=threshold_mm)

    @property
    def n_failed(self) -> int:
        return int(np.sum(self.failed))

    @property
    def records(self) -> list[str]:
        """The distinct records, in order of first appearance."""
        return list(dict.fromkeys(self.record))

    @property
    def n_sets(self) -> int:
        return len(set(self.param_set.tolist()))

    @property
    def used(self) -> np.ndarray:
        """bool per row: its run gave an outcome (it did not fail)."""
        return ~self.failed

    def stripes(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(levels [g], runs, collapses) per level, increasing, over the runs that gave
        an outcome."""
        from .stripes_fit import stripes_of
        return stripes_of(self.level_g[self.used], self.collapsed[self.used])

    def bootstrap_clusters(self) -> tuple[list[str], list[str] | None, str]:
        """(cluster of each row, event of each row or None, what a resample draws): the
        runs of one record (every level, every model sample) are one cluster; with
        events, the records of one event are grouped under it."""
        if self.event is not None:
            return list(self.record), list(self.event), "event"
        return list(self.record), None, "record"

    def check(self) -> "MsaResult":
        """The rules of the format; ResultsError otherwise."""
        for name in ("level_g", "scale"):
            values = getattr(self, name)
            bad = ~(np.isfinite(values) & (values > 0.0))
            if bad.any():
                k = int(np.argmax(bad))
                raise ResultsError(self.path, f"row {k + 1} (record {self.record[k]}): {name} = {values[k]!r} "
                                              "is not a finite number > 0")
        return self


def is_msa(path: str | os.PathLike) -> bool:
    """Whether ``path`` is an MSA sweep's file: its HDF5 root attribute mode = 'msa', or a
    CSV whose header has level_g."""
    path = os.fspath(path)
    if not os.path.isfile(path):
        return False
    if path.lower().endswith(".csv"):
        with open(path, encoding="utf-8-sig", errors="replace") as f:
            for line in f:
                if line.strip() and not line.lstrip().startswith("#"):
                    return "level_g" in [c.strip() for c in line.split(",")]
        return False
    if not h5py.is_hdf5(path):
        return False
    with h5py.File(path, "r") as h5:
        return _text(h5.attrs.get("mode", "")) == "msa"


def read_msa(path: str | os.PathLike) -> MsaResult:
    """The MSA runs of ``path``: the sweep's HDF5 file or its CSV summary."""
    path = os.fspath(path)
    if not os.path.exists(path):
        raise ResultsError(path, "no such file")
    if path.lower().endswith(".csv"):
        return _read_csv(path).check()
    return _read_h5(path).check()


def _read_csv(path: str) -> MsaResult:
    table = read_csv_table(path, expected="a header row with " + ", ".join(MSA_COLUMNS))
    header = table.columns
    missing = [c for c in MSA_COLUMNS if c not in header]
    if missing:
        raise ResultsError(path, f"line {table.header_line}: the header lacks the column(s) {', '.join(missing)} "
                                 f"(an MSA CSV has {', '.join(MSA_COLUMNS)})")
    extra = [h for h in header if h not in MSA_COLUMNS + _TEXT + _OPTIONAL_REAL]
    data: dict[str, list] = {name: [] for name in header}
    for row in table.rows:
        if row.n_fields < len(header):
            raise ResultsError(path, f"line {row.line}: {row.n_fields} cells, the header has {len(header)}")
        for name in header:
            text = row.cells[name]
            if name in _TEXT:
                if not text and name == "record":
                    raise ResultsError(path, f"line {row.line}, column record: empty")
                data[name].append(text)
                continue
            try:
                value = float(text)
            except ValueError:
                raise ResultsError(path, f"line {row.line}, column {name}: '{text}' is not a number") from None
            if name in _FLAGS and value not in (0.0, 1.0):
                raise ResultsError(path, f"line {row.line}, column {name}: '{text}' is not 0 or 1")
            if name == "param_set" and (value != int(value) or value < 0):
                raise ResultsError(path, f"line {row.line}, column param_set: '{text}' is not an integer >= 0")
            data[name].append(value)
    if not table.rows:
        raise ResultsError(path, "no data rows")
    arr = {name: np.asarray(v, dtype=float) for name, v in data.items() if name not in _TEXT}
    return MsaResult(path=path, record=data["record"], param_set=arr["param_set"].astype(int),
                     level_g=arr["level_g"], scale=arr["scale"], collapsed=arr["collapsed"].astype(bool),
                     failed=arr["failed"].astype(bool), event=_events(data.get("event"), data["record"]),
                     pga_m_s2=arr.get("pga_m_s2"), static_capacity_m_s2=arr.get("static_capacity_m_s2"),
                     max_joint_opening_mm=arr.get("max_joint_opening_mm"), residual_drift_mm=arr.get("residual_drift_mm"),
                     **record_columns(arr), parameters={name: arr[name] for name in extra})


def _read_h5(path: str) -> MsaResult:
    if not h5py.is_hdf5(path):
        raise ResultsError(path, "not an HDF5 file (nor a .csv)")
    with h5py.File(path, "r") as h5:
        rows = read_sweep_rows(h5, path, "msa", "MSA", ("param_set", "record", "level_g", "scale", "collapsed", "failed"),
                               ("static_capacity_m_s2", "pga_m_s2", "max_joint_opening_mm", "residual_drift_mm"))
    columns = rows.columns
    return MsaResult(path=path, record=[rows.files[i] for i in rows.index], param_set=columns["param_set"].astype(int),
                     level_g=columns["level_g"].astype(float), scale=columns["scale"].astype(float),
                     collapsed=columns["collapsed"].astype(bool), failed=columns["failed"].astype(bool),
                     event=rows.events, pga_m_s2=columns.get("pga_m_s2"),
                     static_capacity_m_s2=columns.get("static_capacity_m_s2"), parameters=rows.parameters,
                     config=rows.config, code_version=rows.code_version, record_set=rows.record_set,
                     max_joint_opening_mm=_real(columns.get("max_joint_opening_mm")),
                     residual_drift_mm=_real(columns.get("residual_drift_mm")), **record_columns(columns))


def _real(values) -> np.ndarray | None:
    return None if values is None else np.asarray(values, dtype=float)
