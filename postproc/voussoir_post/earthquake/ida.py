"""Reader of incremental dynamic analysis (IDA) results: ``voussoir-sweep`` in
``&sweep mode = 'ida'`` writes an HDF5 file and a CSV beside it, one row per record and
parameter set (docs/results_format.md, docs/earthquakes.md).

A row is the collapse intensity of one record on one model: the smallest scale of the
record that brought the arch down (``scale_threshold``), the largest below it that
stood (``scale_stood``), and the record's PGA and PGV at ``scale_threshold``. A record
that never brought it down up to ``scale_max`` is *censored*: its threshold columns
then hold the values at ``scale_max``, a lower bound of the unknown threshold.

Both files are accepted; an error names the file and, for the CSV, the line and column
(the CSV is read by :func:`voussoir_post.readers.csv_table.read_csv_table`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import h5py
import numpy as np

from ..errors import ResultsError
from ..namelist import parse_namelist
from ..readers.csv_table import read_csv_table

__all__ = ["IdaResult", "IDA_COLUMNS", "read_ida"]

#: The columns every IDA CSV has (others, e.g. the sampled parameters, are kept apart).
IDA_COLUMNS = ("record", "param_set", "scale_stood", "scale_threshold", "pga_threshold_m_s2",
               "pgv_threshold_m_s", "censored")
_OPTIONAL_INT = ("non_monotonic", "n_runs", "failed")


@dataclass
class IdaResult:
    """The rows of an IDA sweep, in file order."""

    path: str
    record: list[str]  #: the record file of each row (the path given to the sweep)
    param_set: np.ndarray  #: int
    scale_stood: np.ndarray
    scale_threshold: np.ndarray  #: at scale_max for a censored row
    pga_m_s2: np.ndarray  #: PGA at scale_threshold (a lower bound where censored)
    pgv_m_s: np.ndarray
    censored: np.ndarray  #: bool
    non_monotonic: np.ndarray | None = None  #: bool, when the file has it
    n_runs: np.ndarray | None = None
    parameters: dict[str, np.ndarray] = field(default_factory=dict)  #: sampled model parameters per row
    config: dict = field(default_factory=dict)  #: the base case {group: {var: value}} when known
    #: Rows left out because their search ended by a run that failed (no threshold, not
    #: a censored one either: a numerical failure tells nothing of the arch).
    n_failed: int = 0
    code_version: str = ""  #: the version of voussoir-sweep that wrote the file (HDF5 only)

    @property
    def n_rows(self) -> int:
        return len(self.record)

    @property
    def records(self) -> list[str]:
        """The distinct records, in order of first appearance."""
        return list(dict.fromkeys(self.record))

    @property
    def n_sets(self) -> int:
        return len(set(self.param_set.tolist()))

    def check(self) -> "IdaResult":
        """Check the rows against the rules of the format; ResultsError otherwise."""
        for name in ("scale_stood", "scale_threshold", "pga_m_s2", "pgv_m_s"):
            values = getattr(self, name)
            bad = ~(np.isfinite(values) & (values >= 0.0))
            if name != "scale_stood":
                bad |= values <= 0.0
            if bad.any():
                k = int(np.argmax(bad))
                raise ResultsError(self.path, f"row {k + 1} (record {self.record[k]}): {name} = {values[k]!r} "
                                              f"is not a finite number > 0")
        bad = self.scale_stood > self.scale_threshold * (1 + 1e-12)
        if bad.any():
            k = int(np.argmax(bad))
            raise ResultsError(self.path, f"row {k + 1} (record {self.record[k]}): scale_stood = "
                                          f"{self.scale_stood[k]!r} above scale_threshold = {self.scale_threshold[k]!r}")
        return self


def read_ida(path: str | os.PathLike) -> IdaResult:
    """The IDA rows of ``path``: the sweep's HDF5 file or its CSV summary."""
    path = os.fspath(path)
    if not os.path.exists(path):
        raise ResultsError(path, "no such file")
    if path.lower().endswith(".csv"):
        return _read_csv(path).check()
    return _read_h5(path).check()


def _read_csv(path: str) -> IdaResult:
    table = read_csv_table(path, expected="a header row with " + ", ".join(IDA_COLUMNS))
    header, header_line = table.columns, table.header_line
    missing = [c for c in IDA_COLUMNS if c not in header]
    if missing:
        raise ResultsError(path, f"line {header_line}: the header lacks the column(s) {', '.join(missing)} "
                                 f"(an IDA CSV has {', '.join(IDA_COLUMNS)})")
    extra = [h for h in header if h not in IDA_COLUMNS and h not in _OPTIONAL_INT]
    data: dict[str, list] = {name: [] for name in header}
    for row in table.rows:
        line_no = row.line
        if row.n_fields < len(header):
            raise ResultsError(path, f"line {line_no}: {row.n_fields} cells, the header has {len(header)}")
        for name in header:
            text = row.cells[name]
            if name == "record":
                if not text:
                    raise ResultsError(path, f"line {line_no}, column record: empty")
                data[name].append(text)
                continue
            try:
                value = float(text)
            except ValueError:
                raise ResultsError(path, f"line {line_no}, column {name}: '{text}' is not a number") from None
            if name in ("param_set", "censored") + _OPTIONAL_INT:
                flags = ("censored", "non_monotonic", "failed")
                if value != int(value) or value < 0 or (name in flags and value > 1):
                    allowed = "0 or 1" if name in flags else "an integer >= 0"
                    raise ResultsError(path, f"line {line_no}, column {name}: '{text}' is not {allowed}")
            data[name].append(value)
    if not table.rows:
        raise ResultsError(path, "no data rows")
    arr = {name: np.asarray(v, dtype=float) for name, v in data.items() if name != "record"}
    keep = arr["failed"] == 0 if "failed" in arr else np.ones(len(data["record"]), bool)
    arr = {name: v[keep] for name, v in arr.items()}
    data["record"] = [r for r, k in zip(data["record"], keep) if k]
    return IdaResult(
        n_failed=int((~keep).sum()), path=path, record=data["record"], param_set=arr["param_set"].astype(int),
        scale_stood=arr["scale_stood"], scale_threshold=arr["scale_threshold"],
        pga_m_s2=arr["pga_threshold_m_s2"], pgv_m_s=arr["pgv_threshold_m_s"],
        censored=arr["censored"].astype(bool),
        non_monotonic=arr["non_monotonic"].astype(bool) if "non_monotonic" in arr else None,
        n_runs=arr["n_runs"].astype(int) if "n_runs" in arr else None,
        parameters={name: arr[name] for name in extra})


def _read_h5(path: str) -> IdaResult:
    if not h5py.is_hdf5(path):
        raise ResultsError(path, "not an HDF5 file (nor a .csv)")
    with h5py.File(path, "r") as h5:
        producer = _text(h5.attrs.get("producer", ""))
        if producer != "voussoir-sweep":
            raise ResultsError(path, f"written by '{producer}', but an IDA comes from 'voussoir-sweep'")
        mode = _text(h5.attrs.get("mode", ""))
        if mode != "ida":
            raise ResultsError(path, f"a '{mode}' sweep, not an IDA (&sweep mode = 'ida')")
        if "record_files" not in h5.attrs:
            raise ResultsError(path, "missing root attribute 'record_files'")
        files = [f for f in _text(h5.attrs["record_files"]).split("\n") if f.strip()]
        columns = {}
        for name in ("param_set", "record", "scale_stood", "scale_threshold", "pga_threshold_m_s2",
                     "pgv_threshold_m_s", "censored") + _OPTIONAL_INT:
            key = f"results/{name}"
            if key not in h5:
                if name in _OPTIONAL_INT:
                    continue
                raise ResultsError(path, f"missing dataset '/{key}'")
            columns[name] = np.asarray(h5[key][()]).reshape(-1)
        n = columns["param_set"].shape[0]
        for name, values in columns.items():
            if values.shape[0] != n:
                raise ResultsError(path, f"'/results/{name}' has {values.shape[0]} rows, '/results/param_set' {n}")
        if "failed" in columns:
            keep = columns["failed"] == 0
            n_failed = int((~keep).sum())
            columns = {name: v[keep] for name, v in columns.items()}
            n = int(keep.sum())
        else:
            n_failed = 0
        index = columns["record"].astype(int)
        if n and (index.min() < 0 or index.max() >= len(files)):
            raise ResultsError(path, f"'/results/record' refers to a record that 'record_files' "
                                     f"({len(files)} files) does not have")
        names = [s.strip() for s in _text(h5.attrs.get("parameter_names", "")).split(",") if s.strip()]
        parameters = {}
        if names:
            values = np.asarray(h5["parameters/values"][()], dtype=float).reshape(-1, len(names))
            sets = columns["param_set"].astype(int)
            parameters = {name: values[sets, k] for k, name in enumerate(names)}
        config = parse_namelist(_text(h5.attrs.get("config_nml", "")))
        code_version = _text(h5.attrs.get("code_version", ""))
    return IdaResult(
        path=path, record=[files[i] for i in index], param_set=columns["param_set"].astype(int),
        scale_stood=columns["scale_stood"].astype(float), scale_threshold=columns["scale_threshold"].astype(float),
        pga_m_s2=columns["pga_threshold_m_s2"].astype(float), pgv_m_s=columns["pgv_threshold_m_s"].astype(float),
        censored=columns["censored"].astype(bool),
        non_monotonic=columns["non_monotonic"].astype(bool) if "non_monotonic" in columns else None,
        n_runs=columns["n_runs"].astype(int) if "n_runs" in columns else None,
        parameters=parameters, config=config, n_failed=n_failed, code_version=code_version)


def _text(value) -> str:
    if isinstance(value, np.ndarray):
        value = value.reshape(-1)[0] if value.size else ""
    if isinstance(value, (bytes, np.bytes_)):
        value = bytes(value).decode("utf-8", errors="replace")
    return str(value).rstrip("\x00").strip()
