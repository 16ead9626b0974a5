"""Reader of incremental dynamic analysis (IDA) results: ``voussoir-sweep`` in
``&sweep mode = 'ida'`` writes an HDF5 file and a CSV beside it, one row per record and
parameter set (docs/results_format.md, docs/earthquakes.md).

A row is the collapse intensity of one record on one model: the smallest scale of the
record that brought the arch down (``scale_threshold``), the largest below it that
stood (``scale_stood``), and the record's PGA and PGV at ``scale_threshold``. A record
that never brought it down up to ``scale_max`` is *censored*: its threshold columns
then hold the values at ``scale_max``, a lower bound of the unknown threshold. A search
that ended by a run that failed (``failed`` = 1) has no threshold: it is kept, with the
largest scale that stood before the failure as ``scale_stood`` (voussoir-sweep writes it;
NaN when nothing stood; in a file of an older version, NaN there is read from the HDF5
file's ``/runs``), a lower bound too. With a packaged record set (``&sweep record_set``),
each row also carries its record's event, magnitude, distance, own PGA, site Vs30, pulse
classification and pulse period (:data:`RECORD_COLUMNS`; NaN where the set does not tell
and for record files; absent from files of versions before them).

:meth:`IdaResult.intensity_brackets` turns the rows into what the fragility fit takes:
each row's collapse intensity between the intensity at ``scale_stood`` and that at
``scale_threshold`` (the intensities scale linearly with the record's scale). A failed
search that had collapsed before it failed (the HDF5 file's ``/runs`` tell) gives (last
stand, smallest collapse seen]: its collapse at or below that scale is certain
(:data:`FIT_FAILED_COLLAPSED`); the CSV does not tell, and its failed rows stay censored at
their last stand. ``failures_as_collapses=True`` gives a second reading, every failed search
a collapse at the run that failed (or at its collapse seen, if lower): how much the
failures matter is the distance between the two fits.

Both files are accepted; an error names the file and, for the CSV, the line and column
(the CSV is read by :func:`voussoir_post.readers.csv_table.read_csv_table`).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import h5py
import numpy as np

from ..errors import ResultsError
from ..namelist import parse_namelist
from ..readers.csv_table import read_csv_table

__all__ = ["IdaResult", "IDA_COLUMNS", "RECORD_COLUMNS", "read_ida", "FIT_BRACKET", "FIT_CENSORED", "FIT_FAILED",
           "FIT_FAILED_COLLAPSED", "FIT_LEFT_OUT", "REVERSED_SUFFIX", "PlayedRecord", "played_record"]

#: The columns every IDA CSV has (others, e.g. the sampled parameters, are kept apart).
IDA_COLUMNS = ("record", "param_set", "scale_stood", "scale_threshold", "pga_threshold_m_s2",
               "pgv_threshold_m_s", "censored")
_OPTIONAL_INT = ("non_monotonic", "n_runs", "failed")
#: An optional text column of the CSV: the earthquake of each record (voussoir-sweep writes
#: it for a packaged set, empty for record files; with it the bootstrap draws events, then
#: records).
_OPTIONAL_TEXT = ("event",)
#: Optional numbers of each row's record (voussoir-sweep writes them): moment magnitude,
#: closest distance to the rupture [km] (NaN unknown), and its own PGA at scale 1 [m/s2].
#: Optional numbers of each row's record from its set's index, after the others
#: (voussoir-sweep writes them, NaN unknown and for record files): the site's Vs30 [m/s],
#: the pulse classification (1 a pulse, 0 none, NaN not classified) and the pulse period
#: Tp [s] (Shahi & Baker 2014; NaN without a pulse or not published). Files of older
#: versions lack them.
RECORD_COLUMNS = ("vs30_m_s", "pulse", "pulse_period_s")
_OPTIONAL_REAL = ("magnitude", "distance_km", "pga_m_s2", "static_capacity_m_s2") + RECORD_COLUMNS

#: What voussoir-sweep puts after a record's name in a row that played it reversed
#: (``&sweep record_polarity = 'reversed'`` or ``'both'``; src/sweep/sweep_ida.f90).
REVERSED_SUFFIX = " (reversed)"


@dataclass(frozen=True)
class PlayedRecord:
    """A row's record as the sweep played it: which record, and its polarity."""

    record: str  #: the record as given to the sweep (its file, or its name in the set)
    polarity: int  #: 1 as recorded, -1 reversed (the horizontal acceleration's sign flipped)


def played_record(row_record: str) -> PlayedRecord:
    """The record and polarity of a row from its ``record`` cell: ``'X'`` is X as
    recorded, ``'X (reversed)'`` X reversed. Every place that matches rows to records
    (reads a row's record, looks it up in its set) goes through this."""
    if row_record.endswith(REVERSED_SUFFIX):
        return PlayedRecord(row_record[:-len(REVERSED_SUFFIX)], -1)
    return PlayedRecord(row_record, 1)


#: How a row enters the fragility fit (:attr:`IdaResult.fit_as`).
FIT_BRACKET = "bracket"  #: IM_c in (IM at scale_stood, IM at scale_threshold]
FIT_CENSORED = "censored at scale_max"  #: IM_c > IM at scale_max
FIT_FAILED = "failed: censored at last stand"  #: IM_c > IM at the last scale that stood
FIT_LEFT_OUT = "failed: no stand known"  #: nothing known: left out
#: IM_c in (IM at the last stand (0 if none), IM at the smallest scale that had collapsed before the failure]
FIT_FAILED_COLLAPSED = "failed after a collapse: in (last stand, collapse seen]"


@dataclass
class IdaResult:
    """The rows of an IDA sweep, in file order."""

    path: str
    record: list[str]  #: the record file of each row (the path given to the sweep)
    param_set: np.ndarray  #: int
    scale_stood: np.ndarray  #: of a failed row: the last scale that stood, NaN if unknown
    scale_threshold: np.ndarray  #: at scale_max for a censored row; NaN for a failed one
    pga_m_s2: np.ndarray  #: PGA at scale_threshold (a lower bound where censored; NaN where failed)
    pgv_m_s: np.ndarray
    censored: np.ndarray  #: bool: no collapse up to scale_max
    non_monotonic: np.ndarray | None = None  #: bool, when the file has it
    n_runs: np.ndarray | None = None
    parameters: dict[str, np.ndarray] = field(default_factory=dict)  #: sampled model parameters per row
    config: dict = field(default_factory=dict)  #: the base case {group: {var: value}} when known
    code_version: str = ""  #: the version of voussoir-sweep that wrote the file (HDF5 only)
    #: bool: the search ended by a run that failed (no threshold); all False when the
    #: file has no such column
    failed: np.ndarray | None = None
    event: list[str] | None = None  #: the earthquake of each row's record, when the file has it
    #: Each row's record at scale 1: PGA [m/s2] and PGV [m/s] (the HDF5 file's
    #: /sweep/record_*, else from the record's rows; NaN when neither tells)
    unit_pga_m_s2: np.ndarray | None = None
    unit_pgv_m_s: np.ndarray | None = None
    magnitude: np.ndarray | None = None  #: of each row's record's earthquake (NaN: unknown), when the file has it
    distance_km: np.ndarray | None = None  #: closest distance to the rupture (NaN: unknown), when the file has it
    record_set: str = ""  #: the packaged set the records came from ('' : record files, or unknown)
    #: lambda g of each row's model by limit analysis [m/s2], where its search started (when the file has it)
    static_capacity_m_s2: np.ndarray | None = None
    vs30_m_s: np.ndarray | None = None  #: the site's Vs30 of each row's record (NaN: unknown), when the file has it
    pulse: np.ndarray | None = None  #: float: 1 a pulse, 0 none, NaN not classified; when the file has it
    pulse_period_s: np.ndarray | None = None  #: Tp of the record's pulse (NaN: none or unknown), when the file has it
    #: of a failed row: the smallest scale whose run had collapsed before the failure (NaN: none, or
    #: not known: a CSV); all NaN when the file cannot tell
    scale_collapse_seen: np.ndarray | None = None
    #: of a failed row: the scale of the run that failed (NaN: not known); all NaN when the file cannot tell
    scale_failed_run: np.ndarray | None = None

    def __post_init__(self):
        if self.failed is None:
            self.failed = np.zeros(len(self.record), bool)
        for name in ("scale_collapse_seen", "scale_failed_run"):
            if getattr(self, name) is None:
                setattr(self, name, np.full(len(self.record), np.nan))
        for name, column in (("unit_pga_m_s2", self.pga_m_s2), ("unit_pgv_m_s", self.pgv_m_s)):
            if getattr(self, name) is None:
                setattr(self, name, _unit_intensity(self.record, column, self.scale_threshold, self.failed))

    @property
    def n_rows(self) -> int:
        return len(self.record)

    @property
    def n_failed(self) -> int:
        """Rows whose search ended by a run that failed."""
        return int(np.sum(self.failed))

    @property
    def fit_as(self) -> list[str]:
        """How each row enters the fit: FIT_BRACKET, FIT_CENSORED, FIT_FAILED, FIT_FAILED_COLLAPSED
        or FIT_LEFT_OUT."""
        return self._fit_as(False)

    def _fit_as(self, failures_as_collapses: bool) -> list[str]:
        units = np.isfinite(self.unit_pga_m_s2) & np.isfinite(self.unit_pgv_m_s)
        known = np.isfinite(self.scale_stood) & units
        top = self._failure_top(failures_as_collapses)
        with np.errstate(invalid="ignore"):  # a collapse seen above the last stand bounds it (NaN: none)
            seen = np.isfinite(top) & units & ~(top <= self.scale_stood)
        return [FIT_FAILED_COLLAPSED if f and s else FIT_LEFT_OUT if f and not k else FIT_FAILED if f else
                FIT_CENSORED if c else FIT_BRACKET
                for f, k, s, c in zip(self.failed.tolist(), known.tolist(), seen.tolist(), self.censored.tolist())]

    def _failure_top(self, failures_as_collapses: bool) -> np.ndarray:
        """Per row, the scale at or below which a failed search's collapse lies (NaN: none known):
        its collapse seen; with `failures_as_collapses`, the lower of that and the failed run."""
        if not failures_as_collapses:
            return self.scale_collapse_seen
        return np.fmin(self.scale_collapse_seen, self.scale_failed_run)

    @property
    def n_failed_collapsed(self) -> int:
        """Failed searches that had collapsed before they failed (their collapse is bounded above)."""
        return sum(1 for k in self.fit_as if k == FIT_FAILED_COLLAPSED)

    def n_failures_as_collapses(self) -> int:
        """Failed rows the second reading counts as collapses (the failed run's scale, or a
        collapse seen, known)."""
        return sum(1 for k in self._fit_as(True) if k == FIT_FAILED_COLLAPSED)

    def intensity_brackets(self, measure: str, failures_as_collapses: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """(low, high) per row: the collapse intensity ``measure`` ('pga' in m/s2 or 'pgv'
        in m/s) lies in (low, high]. A bracket: low the intensity at scale_stood
        (intensity at scale_threshold x scale_stood / scale_threshold), high that at
        scale_threshold; censored at scale_max: low the intensity there, high = inf; a
        failed search: low the intensity at its last stand, high = inf, or, when it had
        collapsed before failing, high the intensity at its smallest collapse (low 0 without
        a stand); NaN for a row left out. ``failures_as_collapses``: every failed search whose
        failed run's scale is known collapses at or below it (the second reading)."""
        if measure not in ("pga", "pgv"):
            raise ValueError(f"measure '{measure}': 'pga' or 'pgv'")
        at_threshold = self.pga_m_s2 if measure == "pga" else self.pgv_m_s
        unit = self.unit_pga_m_s2 if measure == "pga" else self.unit_pgv_m_s
        low = np.full(self.n_rows, np.nan)
        high = np.full(self.n_rows, np.nan)
        top = self._failure_top(failures_as_collapses)
        for k, how in enumerate(self._fit_as(failures_as_collapses)):
            if how == FIT_FAILED_COLLAPSED:
                stood = self.scale_stood[k] if np.isfinite(self.scale_stood[k]) else 0.0
                low[k], high[k] = unit[k] * stood, unit[k] * top[k]
            elif how == FIT_BRACKET:
                high[k] = at_threshold[k]
                low[k] = at_threshold[k] * (self.scale_stood[k] / self.scale_threshold[k])
                if self.scale_stood[k] == self.scale_threshold[k]:
                    low[k] = high[k]  # a bracket of no width: an exact intensity
            elif how == FIT_CENSORED:
                low[k], high[k] = at_threshold[k], np.inf
            elif how == FIT_FAILED:
                low[k], high[k] = unit[k] * self.scale_stood[k], np.inf
        return low, high

    def scale_brackets(self, failures_as_collapses: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """(low, high) per row: the record scale at the collapse lies in (low, high], as
        :meth:`intensity_brackets` has it for an intensity (scale_stood and
        scale_threshold; scale_max and inf where censored; the last stand and inf where a
        search failed, the last stand (or 0) and the collapse seen where it had collapsed
        before; NaN for a row left out). Any measure of the record at scale 1
        times these (to the measure's power) is that measure's bracket."""
        low = np.full(self.n_rows, np.nan)
        high = np.full(self.n_rows, np.nan)
        top = self._failure_top(failures_as_collapses)
        for k, how in enumerate(self._fit_as(failures_as_collapses)):
            if how == FIT_FAILED_COLLAPSED:
                low[k] = self.scale_stood[k] if np.isfinite(self.scale_stood[k]) else 0.0
                high[k] = top[k]
            elif how == FIT_BRACKET:
                low[k], high[k] = self.scale_stood[k], self.scale_threshold[k]
            elif how == FIT_CENSORED:
                low[k], high[k] = self.scale_threshold[k], np.inf
            elif how == FIT_FAILED:
                low[k], high[k] = self.scale_stood[k], np.inf
        return low, high

    def bootstrap_clusters(self) -> tuple[list[str], list[str] | None, str]:
        """(cluster of each row, event of each row or None, what a resample draws): the
        rows of one record over the model samples are one cluster (they share the
        record, so they are not independent); with an event column, the records of one
        event are grouped under it ('event'), else the records are drawn ('record')."""
        if self.event is not None:
            return list(self.record), list(self.event), "event"
        return list(self.record), None, "record"

    @property
    def records(self) -> list[str]:
        """The distinct records, in order of first appearance (a record and its reversal two)."""
        return list(dict.fromkeys(self.record))

    @property
    def played(self) -> list[PlayedRecord]:
        """Each row's record and polarity (:func:`played_record`)."""
        return [played_record(r) for r in self.record]

    @property
    def played_records(self) -> list[str]:
        """The distinct records the rows played, each once whatever its polarity, in
        order of first appearance."""
        return list(dict.fromkeys(p.record for p in self.played))

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
            # a failed search has no threshold, and its last stand may be unknown (NaN)
            bad &= ~self.failed
            if name == "scale_stood":
                bad |= self.failed & ~(np.isnan(values) | (np.isfinite(values) & (values >= 0.0)))
            if bad.any():
                k = int(np.argmax(bad))
                raise ResultsError(self.path, f"row {k + 1} (record {self.record[k]}): {name} = {values[k]!r} "
                                              f"is not a finite number > 0")
        bad = (self.scale_stood > self.scale_threshold * (1 + 1e-12)) & ~self.failed
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
    extra = [h for h in header if h not in IDA_COLUMNS + _OPTIONAL_INT + _OPTIONAL_TEXT + _OPTIONAL_REAL]
    data: dict[str, list] = {name: [] for name in header}
    for row in table.rows:
        line_no = row.line
        if row.n_fields < len(header):
            raise ResultsError(path, f"line {line_no}: {row.n_fields} cells, the header has {len(header)}")
        for name in header:
            text = row.cells[name]
            if name in ("record",) + _OPTIONAL_TEXT:
                if not text and name == "record":
                    raise ResultsError(path, f"line {line_no}, column {name}: empty")
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
    arr = {name: np.asarray(v, dtype=float) for name, v in data.items() if name not in ("record",) + _OPTIONAL_TEXT}
    return IdaResult(
        failed=arr["failed"].astype(bool) if "failed" in arr else None, event=_events(data.get("event"), data["record"]),
        magnitude=arr.get("magnitude"), distance_km=arr.get("distance_km"), unit_pga_m_s2=arr.get("pga_m_s2"),
        static_capacity_m_s2=arr.get("static_capacity_m_s2"), **record_columns(arr),
        path=path, record=data["record"], param_set=arr["param_set"].astype(int),
        scale_stood=arr["scale_stood"], scale_threshold=arr["scale_threshold"],
        pga_m_s2=arr["pga_threshold_m_s2"], pgv_m_s=arr["pgv_threshold_m_s"],
        censored=arr["censored"].astype(bool),
        non_monotonic=arr["non_monotonic"].astype(bool) if "non_monotonic" in arr else None,
        n_runs=arr["n_runs"].astype(int) if "n_runs" in arr else None,
        parameters={name: arr[name] for name in extra})


def record_columns(columns: dict) -> dict[str, np.ndarray | None]:
    """The RECORD_COLUMNS of ``columns`` as float arrays, None where a file lacks one."""
    return {name: None if columns.get(name) is None else np.asarray(columns[name], dtype=float)
            for name in RECORD_COLUMNS}


@dataclass
class SweepRows:
    """What an IDA and an MSA file share, read by :func:`read_sweep_rows`: the record
    files, the /results columns (with RECORD_COLUMNS where the file has them), each row's
    record index, its model sample's parameters, its event, and the file's configuration."""

    files: list[str]
    columns: dict[str, np.ndarray]
    index: np.ndarray
    parameters: dict[str, np.ndarray]
    events: list[str] | None
    config: dict
    code_version: str
    record_set: str


def read_sweep_rows(h5: h5py.File, path: str, mode: str, label: str, required: tuple[str, ...],
                    optional: tuple[str, ...]) -> SweepRows:
    """The rows of a voussoir-sweep file of `mode` ('ida', 'msa'; `label` names it in
    messages, 'IDA'): the /results columns `required` (each refused when missing) and
    `optional` (left out when missing) and RECORD_COLUMNS (left out when missing), of
    one length, their records among the file's."""
    producer = _text(h5.attrs.get("producer", ""))
    if producer != "voussoir-sweep":
        raise ResultsError(path, f"written by '{producer}', but an {label} comes from 'voussoir-sweep'")
    found = _text(h5.attrs.get("mode", ""))
    if found != mode:
        raise ResultsError(path, f"a '{found}' sweep, not an {label} (&sweep mode = '{mode}')")
    if "record_files" not in h5.attrs:
        raise ResultsError(path, "missing root attribute 'record_files'")
    files = [f for f in _text(h5.attrs["record_files"]).split("\n") if f.strip()]
    columns = {}
    optional = optional + tuple(name for name in RECORD_COLUMNS if name not in optional)
    for name in required + optional:
        key = f"results/{name}"
        if key not in h5:
            if name in optional:
                continue
            raise ResultsError(path, f"missing dataset '/{key}'")
        columns[name] = np.asarray(h5[key][()]).reshape(-1)
    n = columns["param_set"].shape[0]
    for name, values in columns.items():
        if values.shape[0] != n:
            raise ResultsError(path, f"'/results/{name}' has {values.shape[0]} rows, '/results/param_set' {n}")
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
    events = None
    if "record_events" in h5.attrs:
        event_names = _text(h5.attrs["record_events"]).split("\n")
        if len(event_names) == len(files):
            events = _events([event_names[i].strip() for i in index], [files[i] for i in index])
    return SweepRows(files=files, columns=columns, index=index, parameters=parameters, events=events,
                     config=parse_namelist(_text(h5.attrs.get("config_nml", ""))),
                     code_version=_text(h5.attrs.get("code_version", "")),
                     record_set=_text(h5.attrs.get("record_set", "")))


def _read_h5(path: str) -> IdaResult:
    if not h5py.is_hdf5(path):
        raise ResultsError(path, "not an HDF5 file (nor a .csv)")
    with h5py.File(path, "r") as h5:
        rows = read_sweep_rows(h5, path, "ida", "IDA",
                               ("param_set", "record", "scale_stood", "scale_threshold", "pga_threshold_m_s2",
                                "pgv_threshold_m_s", "censored"), _OPTIONAL_INT + ("static_capacity_m_s2",))
        columns, index, files = rows.columns, rows.index, rows.files
        n = columns["param_set"].shape[0]
        failed = columns["failed"].astype(bool) if "failed" in columns else np.zeros(n, bool)
        stood = columns["scale_stood"].astype(float)
        seen, failed_run = np.full(n, np.nan), np.full(n, np.nan)
        if failed.any() and "results/job" in h5:
            jobs = np.asarray(h5["results/job"][()]).reshape(-1).astype(int)
            for k in np.flatnonzero(failed & np.isnan(stood)):  # older versions wrote NaN there
                stood[k] = _last_stand(h5, jobs[k])
            for k in np.flatnonzero(failed):
                seen[k], failed_run[k] = _failed_search_scales(h5, jobs[k])
        units = {}
        for name in ("record_pga_m_s2", "record_pgv_m_s", "record_magnitude", "record_distance_km"):
            if f"sweep/{name}" in h5:
                values = np.asarray(h5[f"sweep/{name}"][()], dtype=float).reshape(-1)
                if values.size == len(files):
                    units[name] = values[index]
    return IdaResult(
        failed=failed, unit_pga_m_s2=units.get("record_pga_m_s2"), unit_pgv_m_s=units.get("record_pgv_m_s"),
        magnitude=units.get("record_magnitude"), distance_km=units.get("record_distance_km"), event=rows.events,
        record_set=rows.record_set, static_capacity_m_s2=columns.get("static_capacity_m_s2"),
        **record_columns(columns),
        path=path, record=[files[i] for i in index], param_set=columns["param_set"].astype(int),
        scale_stood=stood, scale_threshold=columns["scale_threshold"].astype(float),
        pga_m_s2=columns["pga_threshold_m_s2"].astype(float), pgv_m_s=columns["pgv_threshold_m_s"].astype(float),
        censored=columns["censored"].astype(bool),
        non_monotonic=columns["non_monotonic"].astype(bool) if "non_monotonic" in columns else None,
        n_runs=columns["n_runs"].astype(int) if "n_runs" in columns else None,
        parameters=rows.parameters, config=rows.config, code_version=rows.code_version,
        scale_collapse_seen=seen, scale_failed_run=failed_run)


def _events(events: list[str] | None, records: list[str]) -> list[str] | None:
    """The event column, None when no row names its event (record files: the bootstrap then
    draws records); a record without an event among records with one is an event of its
    own."""
    if events is None or not any(events):
        return None
    return [e if e else f"{r} (event not given)" for e, r in zip(events, records)]


def _last_stand(h5: h5py.File, job: int) -> float:
    """The largest scale that stood in the runs of search ``job`` before it failed, below
    its smallest collapse if it had one (the search's scale_stood, as far as it got);
    NaN when the file has no /runs or the search had no stand."""
    if not all(f"runs/{c}" in h5 for c in ("job", "scale", "collapsed")):
        return float("nan")
    mine = np.asarray(h5["runs/job"][()]).reshape(-1).astype(int) == job
    scale = np.asarray(h5["runs/scale"][()], dtype=float).reshape(-1)[mine]
    collapsed = np.asarray(h5["runs/collapsed"][()]).reshape(-1)[mine] != 0
    ok = np.asarray(h5["runs/failed"][()]).reshape(-1)[mine] == 0 if "runs/failed" in h5 else np.ones(scale.size, bool)
    below = scale < np.min(scale[ok & collapsed], initial=np.inf)
    stands = scale[ok & ~collapsed & below]
    return float(stands.max()) if stands.size else float("nan")


def _failed_search_scales(h5: h5py.File, job: int) -> tuple[float, float]:
    """(the smallest scale whose run collapsed, the smallest scale whose run failed) among
    the runs of search ``job``; NaN where there is none or the file has no /runs."""
    if not all(f"runs/{c}" in h5 for c in ("job", "scale", "collapsed")):
        return float("nan"), float("nan")
    mine = np.asarray(h5["runs/job"][()]).reshape(-1).astype(int) == job
    scale = np.asarray(h5["runs/scale"][()], dtype=float).reshape(-1)[mine]
    collapsed = np.asarray(h5["runs/collapsed"][()]).reshape(-1)[mine] != 0
    bad = (np.asarray(h5["runs/failed"][()]).reshape(-1)[mine] != 0 if "runs/failed" in h5
           else np.zeros(scale.size, bool))
    seen = scale[collapsed & ~bad]
    return (float(seen.min()) if seen.size else float("nan"),
            float(scale[bad].min()) if bad.any() else float("nan"))


def _unit_intensity(record: list[str], at_threshold: np.ndarray, scale_threshold: np.ndarray,
                    failed: np.ndarray) -> np.ndarray:
    """Each row's record at scale 1 from the rows of that record that have a threshold
    (intensity / scale; the same for all of them); NaN for a record without such a row."""
    ratio = np.where(failed, np.nan, np.asarray(at_threshold, float) / np.asarray(scale_threshold, float))
    by_record: dict[str, float] = {}
    for name, r in zip(record, ratio.tolist()):
        if math.isfinite(r) and name not in by_record:
            by_record[name] = r
    return np.array([by_record.get(name, np.nan) for name in record], dtype=float)


def _text(value) -> str:
    if isinstance(value, np.ndarray):
        value = value.reshape(-1)[0] if value.size else ""
    if isinstance(value, (bytes, np.bytes_)):
        value = bytes(value).decode("utf-8", errors="replace")
    return str(value).rstrip("\x00").strip()
