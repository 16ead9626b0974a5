"""Reader of a shaking-table campaign folder, exactly per docs/measured_data.md.

A campaign is a folder with ``specimens.csv``, ``tests.csv`` and optionally
``records/<test_id>.csv`` and ``hinges/<test_id>.csv``. :func:`read_campaign` accepts
every valid folder and rejects an invalid one with a :class:`CampaignError` whose message
names the file, the line and the column:

    <file>:<line>:<column index>: column '<column name>': <what is wrong>

Line numbers are 1-based and count every physical line of the file (comments, blank
lines and the lines inside a quoted multi-line field included); the column index is the
1-based position of the column in that file's header. When a required column is absent
from the header, the location is the header line and the column name alone.

CSV rules: UTF-8 (a byte order mark is accepted), comma separated, fields may be quoted,
LF or CRLF line ends, one header row, lines starting with ``#`` are comments anywhere
(outside a quoted field), blank lines are skipped, cells are stripped of surrounding
spaces. Column order is free; unknown columns are ignored with a
:class:`CampaignWarning` (also collected in :attr:`Campaign.warnings`). Extra files are
ignored; a records/ or hinges/ file whose name is not a test id is ignored with a warning.

The first error found is raised (files in the order specimens, tests, records, hinges;
rows in file order; within a row the leftmost column).
"""

from __future__ import annotations

import math
import os
import re
import warnings
from dataclasses import dataclass, field

import numpy as np

from .campaign_csv import CampaignError, CampaignWarning, Cells, check_columns, read_table

__all__ = [
    "CampaignError",
    "CampaignWarning",
    "Specimen",
    "Test",
    "Record",
    "HingeObservation",
    "Campaign",
    "TableLimits",
    "MeasuredThreshold",
    "read_campaign",
    "measured_thresholds",
    "DEFAULT_FRICTION",
    "DEFAULT_CYCLES",
    "RESTRAINTS",
]

DEFAULT_FRICTION = 0.5  #: friction of a specimen whose `friction` cell or column is absent
DEFAULT_CYCLES = 1  #: default of n_attack, n_full and n_decay
#: Allowed deviation of a record's time step from its median step, as a fraction of it; one
#: unit of the last printed decimal of t_s (at most half a step) is allowed on top, for
#: the rounding of printed times.
SAMPLING_TOLERANCE = 0.01

WAVEFORMS = ("afd", "record")
#: Values of specimens.csv `restrained_springings`: brackets fixed to the table against the
#: outer face of the bottom voussoir(s), a known part of the specimen's set-up.
RESTRAINTS = ("none", "left", "right", "both")
DEFAULT_RESTRAINT = "none"
OUTCOMES = ("stand", "collapse")
SIDES = ("intrados", "extrados")



@dataclass
class Specimen:
    """One row of specimens.csv."""

    specimen_id: str
    embrace_deg: float
    n_voussoirs: int
    r_ext_m: float
    thickness_m: float
    width_m: float
    density_kg_m3: float
    friction: float = DEFAULT_FRICTION
    restrained_springings: str = DEFAULT_RESTRAINT  #: known brackets: none, left, right or both
    setup_certain: bool = True  #: False: simulated and reported apart, never fitted nor scored
    line: int = 0  #: line of specimens.csv

    @property
    def thickness_ratio_mean(self) -> float:
        """t / R_mean, the usual slenderness of an arch ring."""
        return self.thickness_m / (self.r_ext_m - 0.5 * self.thickness_m)


@dataclass
class Test:
    """One row of tests.csv (None where an optional cell is empty)."""

    test_id: str
    specimen_id: str
    waveform: str
    outcome: str
    frequency_hz: float | None = None
    amplitude_m: float | None = None
    n_attack: int = DEFAULT_CYCLES
    n_full: int = DEFAULT_CYCLES
    n_decay: int = DEFAULT_CYCLES
    collapse_time_s: float | None = None
    peak_accel_m_s2: float | None = None
    line: int = 0  #: line of tests.csv

    @property
    def collapsed(self) -> bool:
        return self.outcome == "collapse"

    @property
    def commanded_peak_accel_m_s2(self) -> float | None:
        """A (2 pi f)^2 of the full cycles, when frequency and amplitude are given."""
        if self.frequency_hz is None or self.amplitude_m is None:
            return None
        return self.amplitude_m * (2.0 * math.pi * self.frequency_hz) ** 2


@dataclass
class Record:
    """records/<test_id>.csv: measured motion, uniformly sampled."""

    test_id: str
    path: str
    t_s: np.ndarray
    table_x_m: np.ndarray
    crown_dx_m: np.ndarray | None = None
    crown_dy_m: np.ndarray | None = None

    @property
    def dt_s(self) -> float:
        """Sampling step [s]."""
        return float((self.t_s[-1] - self.t_s[0]) / (self.t_s.size - 1))

    @property
    def duration_s(self) -> float:
        return float(self.t_s[-1] - self.t_s[0])


@dataclass
class HingeObservation:
    """One row of hinges/<test_id>.csv."""

    t_s: float
    joint: int
    side: str
    line: int = 0


@dataclass(frozen=True)
class TableLimits:
    """table.csv (version 4): what the table can do and how well its transducer is known;
    the defaults of docs/measured_data.md without the file."""

    stroke_m: float = 0.15  #: largest displacement amplitude the table can command
    max_velocity_m_s: float = 1.0
    max_accel_m_s2: float = 20.0
    displacement_gain_sd: float = 0.01  #: the transducer's calibration, relative standard deviation
    from_file: bool = False


@dataclass
class Campaign:
    """A validated campaign folder."""

    path: str
    specimens: dict[str, Specimen]
    tests: dict[str, Test]
    records: dict[str, Record] = field(default_factory=dict)
    hinges: dict[str, list[HingeObservation]] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    table: TableLimits = field(default_factory=TableLimits)

    @property
    def name(self) -> str:
        return os.path.basename(os.path.normpath(self.path))

    def tests_of(self, specimen_id: str) -> list[Test]:
        """Tests of one specimen in file order."""
        return [t for t in self.tests.values() if t.specimen_id == specimen_id]


@dataclass
class MeasuredThreshold:
    """The measured collapse threshold of one (specimen, frequency) pair.

    ``threshold_m`` is the midpoint between the smallest collapse amplitude
    (``high_m``) and the largest stand amplitude below it (``low_m``); with no stand row
    below, the smallest collapse amplitude (and ``low_m`` is NaN). With no collapse at
    all, ``threshold_m`` and ``high_m`` are NaN and ``low_m`` is the largest stand
    amplitude.
    """

    specimen_id: str
    frequency_hz: float
    threshold_m: float
    low_m: float
    high_m: float
    n_stand: int
    n_collapse: int
    non_monotonic: bool  #: a stand row above the smallest collapse amplitude
    test_ids: list[str]

    @property
    def has_collapse(self) -> bool:
        return self.n_collapse > 0

    @property
    def threshold_accel_m_s2(self) -> float:
        """Commanded peak acceleration A (2 pi f)^2 at the threshold amplitude."""
        return self.threshold_m * (2.0 * math.pi * self.frequency_hz) ** 2


# ---------------------------------------------------------------------- the files

_SPECIMEN_REQUIRED = ("specimen_id", "embrace_deg", "n_voussoirs", "r_ext_m", "thickness_m",
                      "width_m", "density_kg_m3")
_SPECIMEN_KNOWN = _SPECIMEN_REQUIRED + ("friction", "restrained_springings", "setup_certain")
_TEST_REQUIRED = ("test_id", "specimen_id", "waveform", "outcome")
_TEST_KNOWN = _TEST_REQUIRED + ("frequency_hz", "amplitude_m", "n_attack", "n_full", "n_decay",
                                "collapse_time_s", "peak_accel_m_s2")
_RECORD_REQUIRED = ("t_s", "table_x_m")
_RECORD_KNOWN = _RECORD_REQUIRED + ("crown_dx_m", "crown_dy_m")
_HINGE_REQUIRED = ("t_s", "joint", "side")


def _read_specimens(path: str, warn_list: list[str]) -> dict[str, Specimen]:
    table = read_table(path)
    check_columns(table, _SPECIMEN_REQUIRED, _SPECIMEN_KNOWN, warn_list)
    specimens: dict[str, Specimen] = {}
    for row in table.rows:
        c = Cells(table, row)
        sid = c.text("specimen_id")
        if sid is not None and sid in specimens:
            c.error("specimen_id", f"duplicate id '{sid}' (first on line {specimens[sid].line})")
        embrace = c.number("embrace_deg", low=0.0, low_inclusive=False, high=180.0,
                           rule="0 < embrace_deg <= 180")
        n = c.integer("n_voussoirs", low=2, rule="integer >= 2")
        r_ext = c.number("r_ext_m", length=True, low=0.0, low_inclusive=False, rule="r_ext_m > 0")
        thickness = c.number("thickness_m", length=True, low=0.0, low_inclusive=False,
                             rule="0 < thickness_m < r_ext_m")
        width = c.number("width_m", length=True, low=0.0, low_inclusive=False, rule="width_m > 0")
        density = c.number("density_kg_m3", low=0.0, low_inclusive=False, rule="density_kg_m3 > 0")
        friction = c.number("friction", required=False, low=0.0, rule="friction >= 0")
        restrained = c.enum("restrained_springings", RESTRAINTS, required=False)
        certain = c.enum("setup_certain", ("1", "0"), required=False)
        if thickness is not None and r_ext is not None and thickness >= r_ext:
            c.error("thickness_m", f"{row.cells['thickness_m']} is out of range: "
                                   f"0 < thickness_m < r_ext_m = {row.cells['r_ext_m']}")
        elif None not in (embrace, n, r_ext, thickness) and n >= 2 and 0.0 < embrace <= 180.0 and thickness > 0.0:
            # The rule of voussoir-run: every voussoir at least thickness_m/100 long at the
            # intrados (a block a hundred times deeper than long is a sliver).
            length = (r_ext - thickness) * math.radians(embrace) / n
            if length < thickness / 100.0:
                low = math.ceil(100.0 * math.degrees(n * thickness / (100.0 * (r_ext - thickness)))) / 100.0
                c.error("embrace_deg", f"{row.cells['embrace_deg']} is out of range: {low:g} <= embrace_deg "
                                       f"<= 180 for n_voussoirs = {n}, thickness_m = {row.cells['thickness_m']}, "
                                       f"r_ext_m = {row.cells['r_ext_m']} (each voussoir at least thickness_m/100 "
                                       f"long at the intrados; these would be {length:.3g} m)")
        c.raise_first()
        specimens[sid] = Specimen(sid, embrace, n, r_ext, thickness, width, density,
                                  DEFAULT_FRICTION if friction is None else friction,
                                  restrained or DEFAULT_RESTRAINT, certain != "0", row.line)
    return specimens


def _read_tests(path: str, specimens: dict[str, Specimen], folder: str,
                warn_list: list[str]) -> dict[str, Test]:
    table = read_table(path)
    check_columns(table, _TEST_REQUIRED, _TEST_KNOWN, warn_list)
    tests: dict[str, Test] = {}
    for row in table.rows:
        c = Cells(table, row)
        tid = c.text("test_id")
        if tid is not None:
            if tid in tests:
                c.error("test_id", f"duplicate id '{tid}' (first on line {tests[tid].line})")
            elif any(ch in tid for ch in "/\\\0") or tid in (".", ".."):
                c.error("test_id", f"'{tid}' cannot be a file name in records/ and hinges/")
        sid = c.text("specimen_id")
        if sid is not None and sid not in specimens:
            c.error("specimen_id", f"unknown specimen '{sid}' (not in specimens.csv)")
        waveform = c.enum("waveform", WAVEFORMS)
        afd = waveform == "afd"
        frequency = c.number("frequency_hz", required=afd, low=0.0, low_inclusive=False,
                             rule="frequency_hz > 0")
        amplitude = c.number("amplitude_m", required=afd, length=True)
        cycles = {}
        for name in ("n_attack", "n_full", "n_decay"):
            # The attack and decay envelopes last n cycles each: none is no afd at all.
            low = 0 if name == "n_full" else 1
            value = c.integer(name, required=False, low=low, rule=f"integer >= {low}")
            cycles[name] = DEFAULT_CYCLES if value is None else value
        outcome = c.enum("outcome", OUTCOMES)
        collapse_time = c.number("collapse_time_s", required=False, low=0.0, rule="collapse_time_s >= 0")
        peak_accel = c.number("peak_accel_m_s2", required=False, low=0.0, rule="peak_accel_m_s2 >= 0")
        if waveform == "record" and tid is not None:
            record_path = os.path.join(folder, "records", f"{tid}.csv")
            if not os.path.isfile(record_path):
                c.error("waveform", f"a 'record' test needs records/{tid}.csv, which does not exist")
        c.raise_first()
        tests[tid] = Test(tid, sid, waveform, outcome, frequency, amplitude, cycles["n_attack"],
                          cycles["n_full"], cycles["n_decay"], collapse_time, peak_accel, row.line)
    return tests


def _read_record(path: str, test_id: str, warn_list: list[str]) -> Record:
    table = read_table(path)
    check_columns(table, _RECORD_REQUIRED, _RECORD_KNOWN, warn_list)
    optional = [n for n in ("crown_dx_m", "crown_dy_m") if table.has(n)]
    columns: dict[str, list[float]] = {n: [] for n in _RECORD_REQUIRED + tuple(optional)}
    previous_t = None
    step_lines: list[int] = []
    decimals = 0  # printed decimals of t_s: rounding to them makes steps jitter by 10**-decimals
    for row in table.rows:
        c = Cells(table, row)
        t = c.number("t_s")
        x = c.number("table_x_m")
        extra = {n: c.number(n, required=False) for n in optional}
        if t is not None and previous_t is not None and t <= previous_t:
            c.error("t_s", f"t_s = {row.cells['t_s']} does not increase (previous sample {previous_t:g} s)")
        c.raise_first()
        previous_t = t
        step_lines.append(row.line)
        m = re.fullmatch(r"[+-]?\d*\.(\d+)", row.cells["t_s"])
        decimals = max(decimals, len(m.group(1)) if m else 0)
        columns["t_s"].append(t)
        columns["table_x_m"].append(x)
        for n in optional:
            columns[n].append(math.nan if extra[n] is None else extra[n])
    if len(columns["t_s"]) < 2:
        raise CampaignError(path, "a record needs at least 2 samples", table.header_line)
    t = np.asarray(columns["t_s"])
    steps = np.diff(t)
    typical = float(np.median(steps))
    allowed = SAMPLING_TOLERANCE * typical + min(10.0 ** -decimals if decimals else 0.0, 0.5 * typical)
    bad = np.nonzero(np.abs(steps - typical) > allowed)[0]
    if bad.size:
        k = int(bad[0]) + 1
        raise CampaignError(path, f"non-uniform sampling: step {steps[k - 1]:.6g} s before this sample, "
                                  f"typical step {typical:.6g} s", step_lines[k], "t_s", table.index("t_s"))
    return Record(
        test_id=test_id,
        path=path,
        t_s=t,
        table_x_m=np.asarray(columns["table_x_m"]),
        crown_dx_m=np.asarray(columns["crown_dx_m"]) if "crown_dx_m" in columns else None,
        crown_dy_m=np.asarray(columns["crown_dy_m"]) if "crown_dy_m" in columns else None,
    )


def _read_hinges(path: str, n_voussoirs: int, warn_list: list[str]) -> list[HingeObservation]:
    table = read_table(path)
    check_columns(table, _HINGE_REQUIRED, _HINGE_REQUIRED, warn_list)
    hinges = []
    for row in table.rows:
        c = Cells(table, row)
        t = c.number("t_s")
        joint = c.integer("joint", low=0, high=n_voussoirs, rule=f"joint index 0..{n_voussoirs}")
        side = c.enum("side", SIDES)
        c.raise_first()
        hinges.append(HingeObservation(t, joint, side, row.line))
    return hinges


_TABLE_COLUMNS = ("stroke_m", "max_velocity_m_s", "max_accel_m_s2", "displacement_gain_sd")


def _read_table_limits(path: str, warn_list: list[str]) -> TableLimits:
    """table.csv: one header row and one data row; every column optional (its default)."""
    table = read_table(path)
    check_columns(table, (), _TABLE_COLUMNS, warn_list)
    if len(table.rows) != 1:
        raise CampaignError(path, f"table.csv must have one data row, it has {len(table.rows)}", table.header_line)
    c = Cells(table, table.rows[0])
    values = {"stroke_m": c.number("stroke_m", required=False, length=True, low=0.0, low_inclusive=False,
                                   rule="stroke_m > 0"),
              "max_velocity_m_s": c.number("max_velocity_m_s", required=False, low=0.0, low_inclusive=False,
                                           rule="max_velocity_m_s > 0"),
              "max_accel_m_s2": c.number("max_accel_m_s2", required=False, low=0.0, low_inclusive=False,
                                         rule="max_accel_m_s2 > 0"),
              "displacement_gain_sd": c.number("displacement_gain_sd", required=False, low=0.0, high=0.5,
                                               rule="0 <= displacement_gain_sd <= 0.5")}
    c.raise_first()
    return TableLimits(**{k: v for k, v in values.items() if v is not None}, from_file=True)


def _csv_files(folder: str) -> list[str]:
    """Names of the .csv files directly in ``folder`` (sorted), [] when it is absent. An
    entry named like a CSV that is not a file (a folder, a broken link) is refused."""
    if not os.path.isdir(folder):
        return []
    names = sorted(f for f in os.listdir(folder) if f.endswith(".csv"))
    for f in names:
        if not os.path.isfile(os.path.join(folder, f)):
            raise CampaignError(os.path.join(folder, f), "not a readable file (a folder or a broken link): "
                                                         "records/ and hinges/ hold one CSV file per test")
    return names


def read_campaign(folder: str | os.PathLike) -> Campaign:
    """Read and validate a campaign folder (see the module docstring for the rules).

    Raises :class:`CampaignError` on the first error; unknown columns and orphan
    record/hinge files are reported as :class:`CampaignWarning` and in
    :attr:`Campaign.warnings`.
    """
    folder = os.fspath(folder)
    if not os.path.isdir(folder):
        raise CampaignError(folder, "not a campaign folder (no such directory)")
    warn_list: list[str] = []
    for name in ("specimens.csv", "tests.csv"):
        if not os.path.isfile(os.path.join(folder, name)):
            raise CampaignError(os.path.join(folder, name), "missing required file")
    specimens = _read_specimens(os.path.join(folder, "specimens.csv"), warn_list)
    tests = _read_tests(os.path.join(folder, "tests.csv"), specimens, folder, warn_list)

    records: dict[str, Record] = {}
    for fname in _csv_files(os.path.join(folder, "records")):
        test_id, path = fname[:-4], os.path.join(folder, "records", fname)
        if test_id not in tests:
            message = f"{path}: no test '{test_id}' in tests.csv, file ignored"
            warn_list.append(message)
            warnings.warn(message, CampaignWarning, stacklevel=2)
            continue
        records[test_id] = _read_record(path, test_id, warn_list)

    hinges: dict[str, list[HingeObservation]] = {}
    for fname in _csv_files(os.path.join(folder, "hinges")):
        test_id, path = fname[:-4], os.path.join(folder, "hinges", fname)
        if test_id not in tests:
            message = f"{path}: no test '{test_id}' in tests.csv, file ignored"
            warn_list.append(message)
            warnings.warn(message, CampaignWarning, stacklevel=2)
            continue
        n = specimens[tests[test_id].specimen_id].n_voussoirs
        hinges[test_id] = _read_hinges(path, n, warn_list)

    records = {t: records[t] for t in tests if t in records}
    hinges = {t: hinges[t] for t in tests if t in hinges}
    table_path = os.path.join(folder, "table.csv")
    limits = _read_table_limits(table_path, warn_list) if os.path.isfile(table_path) else TableLimits()
    return Campaign(folder, specimens, tests, records, hinges, warn_list, limits)


# ------------------------------------------------------------------- thresholds


def _frequency_key(frequency_hz: float) -> float:
    return round(frequency_hz, 9)


def measured_thresholds(campaign: Campaign, specimen_id: str | None = None) -> list[MeasuredThreshold]:
    """Measured threshold and bracket of every (specimen, frequency) pair.

    Pairs are formed from the tests that give both frequency_hz and amplitude_m (every
    afd test; a record test only if it states them), in the order of specimens.csv
    then increasing frequency. See :class:`MeasuredThreshold` for the definition.
    """
    groups: dict[tuple[str, float], list[Test]] = {}
    for test in campaign.tests.values():
        if test.frequency_hz is None or test.amplitude_m is None:
            continue
        if specimen_id is not None and test.specimen_id != specimen_id:
            continue
        groups.setdefault((test.specimen_id, _frequency_key(test.frequency_hz)), []).append(test)
    order = {sid: k for k, sid in enumerate(campaign.specimens)}
    out = []
    for (sid, freq), tests in sorted(groups.items(), key=lambda kv: (order[kv[0][0]], kv[0][1])):
        collapse = [t.amplitude_m for t in tests if t.collapsed]
        stand = [t.amplitude_m for t in tests if not t.collapsed]
        high = min(collapse) if collapse else math.nan
        if collapse:
            below = [a for a in stand if a < high]
            low = max(below) if below else math.nan
            threshold = 0.5 * (low + high) if below else high
            non_monotonic = any(a >= high for a in stand)
        else:
            low = max(stand) if stand else math.nan
            threshold = math.nan
            non_monotonic = False
        out.append(MeasuredThreshold(sid, tests[0].frequency_hz, threshold, low, high, len(stand),
                                     len(collapse), non_monotonic, [t.test_id for t in tests]))
    return out
