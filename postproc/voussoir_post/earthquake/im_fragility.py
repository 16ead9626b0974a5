"""The fragility of an IDA against every intensity measure, to choose one: efficiency
(the spread beta of the fit, smaller is better) and sufficiency (no trend of the fit's
residuals with the earthquake's magnitude, distance, pulse or frequency content).

Each row's record is read again (a record file, or the record of the packaged set the
IDA played, :func:`record_motions`) and its measures computed once, unscaled
(:mod:`.intensity`). A row that played its record reversed (``&sweep record_polarity``,
named ``'<record> (reversed)'``: :func:`.ida.played_record`) has the record's measures:
every measure here is a peak of |a|, |v|, |d| or of an oscillator's |u|, or an integral
of |a| or a^2, so the sign does not change it (RotD50 flips both components alike, which
flips the rotated response at every angle and keeps its peaks). A row's collapse
intensity in a measure is the measure of its record times the row's scale bracket
(:meth:`.ida.IdaResult.scale_brackets`), to the measure's power (2 for the Arias
intensity). Besides the measures of the record alone:

- RotD50 at the period of Sa(T) (``--sa-period``): of the record's pair, the record and
  the other horizontal component of its event's recording (:func:`.intensity.rotd50`),
  both scaled by the row's scale, as a hazard model's Sa is of both components; only the
  packaged sets know a record's pair (:func:`record_motions`), so it is not available
  for record files;

- PGA / (lambda g): the PGA over the row's static capacity (the column
  ``static_capacity_m_s2``), dimensionless: a model that is twice as strong needs
  twice the PGA, and this measure takes that out of the spread;
- the frequency ratio omega_g / p, not an intensity (a record scaled keeps it) but a
  covariate of the sufficiency: omega_g = PGA / PGV [rad/s], a frequency of the record
  (omega exactly for a harmonic ground velocity v0 sin(omega t)), and p = sqrt(3 g / (4 R)) the frequency
  parameter of a rocking block of half-diagonal R (Housner 1963), here the arch's
  block equivalent with R its mean radius r_ext - t / 2 (after the similarity of the
  rocking block, Dimitrakopoulos & DeJong 2012, and the rocking frame, Makris &
  Vassiliou 2013; De Lorenzis, DeJong & Ochsendorf 2007 for arches under pulses). The
  constant of R is a choice: it shifts ln(omega_g / p) alike on every row of one
  arch and leaves the regression's slope as it is;
- the pulse's frequency ratio omega_p / p, omega_p = 2 pi / Tp with Tp the record's
  pulse period (Shahi & Baker 2014, :mod:`.record_sets`; the rows' pulse_period_s
  column, or in a file written before it the packaged set's): the group that governs a
  rocking block under a pulse (Dimitrakopoulos & DeJong 2012), a covariate of the
  records with a pulse only (the FEMA P695 near-field pulse records; the others have no
  Tp and are left out of its regression).

Each measure is fitted by :func:`.fragility.fit_intervals` (the interval-censored
maximum likelihood of the PGA fragility). Its residuals are ln IM_c - ln median of the
rows that collapsed (IM_c the geometric middle of the row's bracket; censored rows have
none), each regressed alone on each covariate (scipy.stats.linregress): slope, its
standard error and the two-sided p-value of slope = 0. Rows that share a record are not
independent, so these p-values are optimistic (too small); the same line through the
records' mean residuals (one point a record) is given beside them.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy import stats

from ..errors import FitError, InputError, RecordsError
from ..readers.csv_table import read_csv_table
from ..tables import ReportTable
from .fragility import FragilityFit, fit_intervals, resample_clusters
from .ida import IdaResult, played_record
from .intensity import (DAMPING, G_M_S2, PYROTD_VERSION, RecordIntensity, avg_sa_periods,
                        record_intensity)
from .record_sets import read_at2, read_set

__all__ = ["MEASURES", "COVARIATES", "RecordMotion", "Sufficiency", "MeasureFit", "MeasureComparison",
           "parse_measures", "record_motions", "frequency_parameter_rad_s", "sufficiency", "residuals",
           "fit_measure", "bootstrap_efficiency", "compare_measures", "FREQUENCY_WORDS", "row_capacities_m_s2",
           "pga_lambda_g_brackets", "rotd50_refusal", "unpaired_records"]

#: The measures, in the order of the table: (label, unit, power of the scale).
MEASURES = {
    "pga": ("PGA", "m/s2", 1), "pgv": ("PGV", "m/s", 1), "pgd": ("PGD", "m", 1),
    "arias": ("Arias intensity", "m/s", 2), "cav": ("CAV", "m/s", 1), "sa": ("Sa(T)", "m/s2", 1),
    "avgsa": ("AvgSa", "m/s2", 1), "rotd50": ("RotD50 Sa(T)", "m/s2", 1),
    "pga_lambda_g": ("PGA / (lambda g)", "-", 1),
}
#: The covariates of the sufficiency, as far as the rows give them.
COVARIATES = ("magnitude", "distance_km", "pulse", "ln_frequency_ratio", "ln_pulse_frequency_ratio")
FREQUENCY_WORDS = ("ln(omega_g / p): omega_g = PGA / PGV of the record [rad/s], p = sqrt(3 g / (4 R)) with R the "
                   "arch's mean radius r_ext - t/2 (a rocking block's frequency parameter, Housner 1963; the arch's "
                   "block equivalent)")
PULSE_FREQUENCY_WORDS = ("ln(omega_p / p): omega_p = 2 pi / Tp, Tp the record's pulse period (Shahi & Baker 2014, "
                         "the records with a pulse only), p as in frequency_ratio")
_CHECK_RTOL = 1e-6  #: the record read here and the one the sweep played: PGA and PGV to this


def row_capacities_m_s2(ida: IdaResult) -> np.ndarray:
    """Each row's static capacity lambda g [m/s2], that of the row's own model sample
    (the column ``static_capacity_m_s2``), the denominator of PGA / (lambda g);
    InputError naming the file when the rows do not give it (a file of a voussoir-sweep
    from before the column) or a row's is not > 0 (0: the limit analysis does not apply
    to its model, e.g. under &load)."""
    capacity = ida.static_capacity_m_s2
    if capacity is None:
        raise InputError(f"{ida.path}: the rows do not give static_capacity_m_s2 (each row's static capacity "
                         f"lambda g, which PGA / (lambda g) divides by): a file of a voussoir-sweep from before that "
                         f"column; run the IDA again with this code")
    capacity = np.asarray(capacity, float)
    bad = ~(np.isfinite(capacity) & (capacity > 0.0))
    if bad.any():
        k = int(np.argmax(bad))
        raise InputError(f"{ida.path}: row {k + 1} (record {ida.record[k]}, param_set {int(ida.param_set[k])}): "
                         f"static_capacity_m_s2 = {float(capacity[k])!r}, not a capacity > 0 (the limit analysis does not "
                         f"apply to this model, e.g. under &load): PGA / (lambda g) is not defined")
    return capacity


def pga_lambda_g_brackets(ida: IdaResult) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) per row: the collapse intensity in PGA / (lambda g) lies in (low,
    high], the row's PGA bracket (:meth:`.ida.IdaResult.intensity_brackets`) over its
    own model's static capacity (:func:`row_capacities_m_s2`; InputError without it)."""
    capacity = row_capacities_m_s2(ida)
    low, high = ida.intensity_brackets("pga")
    return low / capacity, high / capacity


@dataclass(frozen=True)
class RecordMotion:
    """The acceleration of one record as recorded, unscaled (a row that played it
    reversed has the same measures)."""

    name: str  #: as given to the sweep (the rows' name without ' (reversed)')
    dt_s: float
    accel_m_s2: np.ndarray
    pulse: int | None = None  #: 1 a pulse, 0 none, None not classified
    pulse_period_s: float = math.nan  #: Tp of its pulse; nan: no pulse, or not published
    #: the other horizontal component of its pair [m/s2], sampled at dt_s; None: not known
    pair_accel_m_s2: np.ndarray | None = None
    orientation: str = ""  #: 'fault-normal', 'fault-parallel', 'as recorded' (a packaged set's); '' not known


@dataclass
class Sufficiency:
    """The regression of a measure's residuals on one covariate."""

    covariate: str
    slope: float  #: residual per unit of the covariate
    stderr: float
    p_value: float  #: two-sided, of slope = 0 (optimistic: rows sharing a record are not independent)
    n: int  #: residuals regressed
    #: the same line through each record's mean residual and mean covariate (one point a
    #: record: the rows of a record are not independent); NaN with fewer than 3 records
    slope_records: float = math.nan
    p_value_records: float = math.nan
    n_records: int = 0


@dataclass
class MeasureFit:
    """The fragility in one measure, and its sufficiency."""

    name: str  #: a key of MEASURES
    label: str
    unit: str
    power: int  #: IM(s a) = s^power IM(a)
    fit: FragilityFit
    sufficiency: dict[str, Sufficiency] = field(default_factory=dict)
    unit_values: np.ndarray = field(default_factory=lambda: np.array([]))  #: per row, at scale 1
    low: np.ndarray = field(default_factory=lambda: np.array([]))  #: per row: IM_c in (low, high] (NaN: left out)
    high: np.ndarray = field(default_factory=lambda: np.array([]))
    beta_band: tuple[float, float] = (math.nan, math.nan)  #: 90 % of beta over the bootstrap resamples
    p_best: float = math.nan  #: fraction of the resamples in which its beta / power is the smallest

    @property
    def beta_linear(self) -> float:
        """beta / power: the spread of the measure taken to the power 1 / power (sqrt of
        Arias), which scales like the record, so that the measures compare."""
        return self.fit.beta / self.power


@dataclass
class MeasureComparison:
    """Every measure's fit, the settings and the records' measures."""

    fits: list[MeasureFit]
    records: dict[str, RecordIntensity]
    sa_period_s: float
    avgsa_periods_s: tuple[float, ...]
    skipped: dict[str, str] = field(default_factory=dict)  #: measure or covariate -> why it is not there
    n_bootstrap: int = 0  #: resamples of the efficiency's bootstrap that were fitted
    cluster_by: str = ""  #: what they drew ('record', 'event')

    def ranking(self) -> list[str]:
        """The measures by efficiency, the smallest beta / power first."""
        return [m.name for m in sorted(self.fits, key=lambda m: m.beta_linear)]

    def table(self) -> ReportTable:
        """One row per measure: median, beta, beta / power, the slopes and p-values."""
        names = [c for c in COVARIATES if any(c in m.sufficiency for m in self.fits)]
        rows = []
        for m in self.fits:
            median = f"{m.fit.median:.4g}" + (f" ({m.fit.median / G_M_S2:.3g} g)" if m.unit == "m/s2" else "")
            cells = [m.label, m.unit, median, f"{m.fit.beta:.3f} [{m.beta_band[0]:.3f}, {m.beta_band[1]:.3f}]",
                     f"{m.beta_linear:.3f}", f"{m.p_best:.2f}"]
            for c in names:
                s = m.sufficiency.get(c)
                cells.append("-" if s is None else f"{s.slope:+.3f} +- {s.stderr:.3f} (p {s.p_value:.2g}; "
                             f"{s.n_records} records: p {s.p_value_records:.2g})")
            rows.append(tuple(cells))
        return ReportTable(["measure", "unit", "median", "beta [90 % band]", "beta/power", "P(best)"]
                           + [f"slope on {c}" for c in names],
                           rows, title=f"fragility by intensity measure (Sa and RotD50 at T = "
                                       f"{self.sa_period_s:g} s, AvgSa over {self.avgsa_periods_s[0]:g}-"
                                       f"{self.avgsa_periods_s[-1]:g} s, "
                                       f"{100 * DAMPING:g} % damping, pyRotd {PYROTD_VERSION})")

    def summary(self) -> dict:
        """For --json: ``intensity_measures`` and the settings."""
        return {
            "intensity_measures": {m.name: {
                "label": m.label, "median": m.fit.median, "beta": m.fit.beta, "beta_linear": m.beta_linear,
                "beta_band": [_number(b) for b in m.beta_band], "p_best": _number(m.p_best),
                "unit": m.unit, "scale_power": m.power, "n_rows": m.fit.n, "n_censored": m.fit.n_censored,
                "sufficiency": {c: {"slope": s.slope, "stderr": s.stderr, "p_value": s.p_value, "n": s.n,
                                    "slope_records": _number(s.slope_records),
                                    "p_value_records": _number(s.p_value_records), "n_records": s.n_records}
                                for c, s in m.sufficiency.items()}} for m in self.fits},
            "intensity_efficiency_rank": self.ranking(),
            "intensity_bootstrap": {"n_resamples": self.n_bootstrap, "cluster_by": self.cluster_by, "band_level": 0.90,
                                    "p_best": "fraction of the resamples (the same for every measure) in which the "
                                              "measure's beta / power is the smallest"},
            "intensity_settings": {
                "sa_period_s": self.sa_period_s, "avgsa_periods_s": list(self.avgsa_periods_s),
                "damping": DAMPING, "spectra": f"pyRotd {PYROTD_VERSION} (pseudo-spectral acceleration)",
                "g_m_s2": G_M_S2, "frequency_ratio": FREQUENCY_WORDS,
                "pulse_frequency_ratio": PULSE_FREQUENCY_WORDS,
                "residual": "ln IM_c - ln median, IM_c the geometric middle of a collapsed row's bracket "
                            "(censored rows left out); each covariate regressed alone (scipy.stats.linregress), "
                            "over the rows and over the records' mean residuals (_records)",
                "not_available": dict(self.skipped)},
            "record_intensities": {name: {"pga_m_s2": r.pga_m_s2, "pgv_m_s": r.pgv_m_s, "pgd_m": r.pgd_m,
                                          "arias_m_s": r.arias_m_s, "cav_m_s": r.cav_m_s, "sa_m_s2": r.sa_m_s2,
                                          "avgsa_m_s2": r.avgsa_m_s2, "rotd50_m_s2": _number(r.rotd50_m_s2)}
                                   for name, r in self.records.items()},
        }


def _number(x: float) -> float | None:
    """A float for JSON, None for NaN."""
    return x if math.isfinite(x) else None


def parse_measures(text: str) -> list[str]:
    """'all' or a comma-separated list of MEASURES' keys; InputError naming the known ones."""
    names = [t.strip().lower() for t in text.split(",") if t.strip()]
    if names == ["all"]:
        return list(MEASURES)
    unknown = [n for n in names if n not in MEASURES]
    if unknown or not names:
        raise InputError(f"--im {text!r}: 'all' or a comma-separated list of {', '.join(MEASURES)}")
    return list(dict.fromkeys(names))


# ------------------------------------------------------------------ the records

def _read_record_file(path: Path) -> tuple[float, np.ndarray]:
    """(dt [s], a [m/s2]) of a record file as the kernel reads it: .AT2 in g, or a CSV
    with t_s and accel_m_s2."""
    if path.suffix.lower() == ".csv":
        table = read_csv_table(path, expected="a header row with t_s and accel_m_s2")
        if not (table.has("t_s") and table.has("accel_m_s2")):
            raise RecordsError(f"{path}: a record CSV needs the columns t_s and accel_m_s2")
        values = []
        for row in table.rows:
            try:
                values.append((float(row.cells["t_s"]), float(row.cells["accel_m_s2"])))
            except ValueError:
                raise RecordsError(f"{path}:{row.line}: t_s or accel_m_s2 is not a number") from None
        if len(values) < 2:
            raise RecordsError(f"{path}: fewer than two samples")
        t, a = np.array(values).T
        return float(t[1] - t[0]), a
    dt, accel_g = read_at2(path)
    return dt, accel_g * G_M_S2


def record_motions(ida: IdaResult) -> dict[str, RecordMotion]:
    """The acceleration of each record of the rows, by the record's name as given to the
    sweep (a record played forward and reversed once: :attr:`.ida.IdaResult.played_records`):
    from the packaged set the IDA played (``ida.record_set``), else each row's record file
    (absolute, or relative to the IDA file's folder or the working folder). RecordsError
    naming the record when it cannot be found."""
    names = ida.played_records
    if ida.record_set:
        by_name: dict[str, list] = {}
        by_pair: dict[int, list] = {}
        for r in read_set(ida.record_set):
            by_name.setdefault(r.record, []).append(r)
            by_pair.setdefault(r.pair, []).append(r)
        out = {}
        for name in names:
            found = by_name.get(name, [])
            if len(found) != 1:
                raise RecordsError(f"{ida.path}: record '{name}' is {'not' if not found else 'twice'} in the set "
                                   f"{ida.record_set}")
            r = found[0]
            others = [o for o in by_pair[r.pair] if o is not r]
            pair = others[0].accel_g * G_M_S2 if len(others) == 1 and others[0].dt_s == r.dt_s else None
            out[name] = RecordMotion(name, r.dt_s, r.accel_g * G_M_S2, r.pulse, r.pulse_period_s, pair, r.orientation)
        return out
    out = {}
    for name in names:
        candidates = [Path(name)] if os.path.isabs(name) else [Path(os.path.dirname(os.path.abspath(ida.path))) / name,
                                                                Path(name)]
        path = next((p for p in candidates if p.is_file()), None)
        if path is None:
            raise RecordsError(f"{ida.path}: record file '{name}' not found (looked at "
                               f"{', '.join(str(p) for p in candidates)}); a CSV of a packaged set does not name "
                               f"its set: give the HDF5 file")
        dt, accel = _read_record_file(path)
        out[name] = RecordMotion(name, dt, accel)
    return out


def _check_records(ida: IdaResult, records: dict[str, RecordIntensity]) -> None:
    """RecordsError when a record read here is not the one the sweep played (its PGA or
    PGV at scale 1 differs from the file's; those of a reversed row are its record's)."""
    for k, name in enumerate(ida.record):
        r = records[played_record(name).record]
        for what, mine, theirs in (("PGA", r.pga_m_s2, ida.unit_pga_m_s2[k]), ("PGV", r.pgv_m_s, ida.unit_pgv_m_s[k])):
            if math.isfinite(theirs) and abs(mine - theirs) > _CHECK_RTOL * abs(theirs):
                raise RecordsError(f"{ida.path}: record '{name}' read here has {what} {mine:.6g}, the IDA file "
                                   f"{theirs:.6g}: not the record the sweep played")


def frequency_parameter_rad_s(ida: IdaResult) -> np.ndarray | None:
    """p = sqrt(3 g / (4 R)) of each row's arch [rad/s], R = r_ext - t / 2 (the sampled
    values where the row's model has them); None when the file does not give the arch."""
    arch = ida.config.get("arch", {})
    r_ext = ida.parameters.get("r_ext_m", np.full(ida.n_rows, float(arch.get("r_ext_m", math.nan))))
    thickness = ida.parameters.get("thickness_m", np.full(ida.n_rows, float(arch.get("thickness_m", math.nan))))
    radius = np.asarray(r_ext, float) - 0.5 * np.asarray(thickness, float)
    if not np.all(np.isfinite(radius) & (radius > 0.0)):
        return None
    return np.sqrt(3.0 * G_M_S2 / (4.0 * radius))


# ------------------------------------------------------------------ fit and sufficiency

def residuals(low, high, fit: FragilityFit) -> np.ndarray:
    """ln IM_c - ln median per row, IM_c the geometric middle of a bracket (the value of
    an exact row); NaN for a censored row or one left out."""
    low, high = np.asarray(low, float), np.asarray(high, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        middle = 0.5 * (np.log(low) + np.log(high))
    return np.where(np.isfinite(middle), middle - math.log(fit.median), np.nan)


def sufficiency(residual, covariate, name: str, records=None) -> Sufficiency | None:
    """The least-squares line of ``residual`` on ``covariate`` over the rows where both
    are finite; None with fewer than 3 such rows or one value of the covariate. With
    ``records`` (one label per row), also the line through the records' means."""
    r, x = np.asarray(residual, float), np.asarray(covariate, float)
    used = np.isfinite(r) & np.isfinite(x)
    if used.sum() < 3 or np.unique(x[used]).size < 2:
        return None
    line = stats.linregress(x[used], r[used])
    out = Sufficiency(name, float(line.slope), float(line.stderr), float(line.pvalue), int(used.sum()))
    if records is not None:
        labels = np.asarray(records)[used]
        names = list(dict.fromkeys(labels.tolist()))
        x_mean = np.array([x[used][labels == n].mean() for n in names])
        r_mean = np.array([r[used][labels == n].mean() for n in names])
        if len(names) >= 3 and np.unique(x_mean).size >= 2:
            by_record = stats.linregress(x_mean, r_mean)
            out.slope_records, out.p_value_records = float(by_record.slope), float(by_record.pvalue)
            out.n_records = len(names)
    return out


def fit_measure(name: str, unit_values, scale_low, scale_high, covariates: dict[str, np.ndarray],
                records=None) -> MeasureFit:
    """The fit of one measure from its value at scale 1 per row and the rows' scale
    brackets, and the regression of its residuals on each covariate (per row; and over
    the records' means with ``records``, the record of each row)."""
    label, unit, power = MEASURES[name]
    unit_values = np.asarray(unit_values, float)
    low, high = unit_values * np.asarray(scale_low, float) ** power, unit_values * np.asarray(scale_high, float) ** power
    used = np.isfinite(low)
    fit = fit_intervals(low[used], high[used])
    res = residuals(low, high, fit)
    found = {c: sufficiency(res, x, c, records) for c, x in covariates.items()}
    return MeasureFit(name, label, unit, power, fit, {c: s for c, s in found.items() if s is not None}, unit_values,
                      low, high)


def bootstrap_efficiency(fits: list[MeasureFit], clusters, events=None, n_resamples: int = 200,
                         seed: int = 20261124) -> int:
    """Each fit's 90 % band of beta and the fraction of resamples in which its beta /
    power is the smallest (``beta_band``, ``p_best``), from one set of clustered
    resamples shared by all the measures (:func:`.fragility.resample_clusters`: records,
    or events then records), each measure refitted on the same rows; resamples in which a
    measure cannot be fitted are left out for all. Returns the resamples used."""
    rng = np.random.default_rng(seed)
    used = np.isfinite(fits[0].low)
    for m in fits:
        used &= np.isfinite(m.low)
    clusters = np.asarray(clusters)[used]
    events = None if events is None else np.asarray(events)[used]
    betas = []
    for _ in range(n_resamples):
        pick = resample_clusters(rng, clusters, events)
        try:
            betas.append([fit_intervals(m.low[used][pick], m.high[used][pick], tol=1e-9).beta / m.power
                          for m in fits])
        except FitError:
            continue
    if len(betas) < 10:
        return len(betas)
    betas = np.array(betas)
    best = np.argmin(betas, axis=1)
    for j, m in enumerate(fits):
        low, high = np.percentile(betas[:, j] * m.power, [5.0, 95.0])
        m.beta_band = (float(low), float(high))
        m.p_best = float(np.mean(best == j))
    return len(betas)


def unpaired_records(ida: IdaResult, motions: dict[str, RecordMotion]) -> list[str]:
    """The records of the rows (:func:`record_motions`) with no second horizontal
    component known: RotD50 cannot be had for them. Reads nothing, computes nothing."""
    return [name for name in ida.played_records if motions[name].pair_accel_m_s2 is None]


def rotd50_refusal(ida: IdaResult, unpaired: list[str]) -> str:
    """Why RotD50 cannot be had for the records ``unpaired`` of ``ida``: no second
    horizontal component known."""
    where = (f"the set {ida.record_set} has no other component of one time step in its pair" if ida.record_set else
             "a record file does not say which file is the other component of its event's recording (only the "
             "packaged sets, played with &sweep record_set, pair the components)")
    more = f" (and {len(unpaired) - 1} other records)" if len(unpaired) > 1 else ""
    return (f"RotD50 is of the two horizontal components of a record's pair, but record '{unpaired[0]}'{more} has no "
            f"second component: {where}")


def record_pulses(ida: IdaResult, motions: dict[str, RecordMotion]) -> tuple[np.ndarray, np.ndarray]:
    """(pulse, Tp [s]) per row: the rows' own pulse and pulse_period_s columns (written by
    voussoir-sweep from its set's index), each where the file has it; in a file written
    before them, the record's (:class:`RecordMotion`, from the packaged set). NaN: not
    classified, no pulse, or no period published."""
    played = [motions[p.record] for p in ida.played]
    pulse = ida.pulse
    if pulse is None:
        pulse = [math.nan if m.pulse is None else float(m.pulse) for m in played]
    tp = ida.pulse_period_s
    if tp is None:
        tp = [m.pulse_period_s for m in played]
    return np.asarray(pulse, float), np.asarray(tp, float)


def compare_measures(ida: IdaResult, measures: list[str], sa_period_s: float = 1.0,
                     avgsa_range_s: tuple[float, float] = (0.2, 3.0),
                     motions: dict[str, RecordMotion] | None = None, n_bootstrap: int = 200,
                     seed: int = 20261124) -> MeasureComparison:
    """The fit and sufficiency of each of ``measures`` (keys of MEASURES) on the rows of
    ``ida``; Sa at ``sa_period_s``, AvgSa over 10 periods spread in ln T over
    ``avgsa_range_s``; ``motions``: the records (default :func:`record_motions`); the
    efficiency's bootstrap (:func:`bootstrap_efficiency`) of ``n_bootstrap`` resamples
    clustered as the PGA band is (0: none)."""
    periods = avg_sa_periods(*avgsa_range_s)
    motions = record_motions(ida) if motions is None else motions
    skipped = {}
    unpaired = unpaired_records(ida, motions)
    if "rotd50" in measures and unpaired:
        skipped["rotd50"] = rotd50_refusal(ida, unpaired)
    pairs = "rotd50" in measures and not unpaired
    records = {name: record_intensity(m.accel_m_s2, m.dt_s, sa_period_s, periods,
                                      m.pair_accel_m_s2 if pairs else None) for name, m in motions.items()}
    _check_records(ida, records)
    played = [p.record for p in ida.played]  # each row's record, whatever its polarity
    covariates = {}
    for name, values in (("magnitude", ida.magnitude), ("distance_km", ida.distance_km)):
        if values is not None and np.sum(np.isfinite(values)) >= 3:
            covariates[name] = np.asarray(values, float)
        else:
            skipped[name] = "the rows do not give it"
    pulse, tp = record_pulses(ida, motions)
    if np.sum(np.isfinite(pulse)) >= 3:
        covariates["pulse"] = pulse
    else:
        skipped["pulse"] = "the records are not classified (only the FEMA P695 near-field sets are)"
    p = frequency_parameter_rad_s(ida)
    no_arch = "the file does not give the arch (r_ext_m, thickness_m): an HDF5 file does"
    if p is None:
        skipped["ln_frequency_ratio"] = no_arch
    else:
        omega = np.array([records[r].pga_m_s2 / records[r].pgv_m_s for r in played])
        covariates["ln_frequency_ratio"] = np.log(omega / p)
    if np.sum(np.isfinite(tp)) < 3:
        skipped["ln_pulse_frequency_ratio"] = ("fewer than 3 rows of a record with a pulse period (only the FEMA "
                                               "P695 near-field pulse records have one)")
    elif p is None:
        skipped["ln_pulse_frequency_ratio"] = no_arch
    else:
        covariates["ln_pulse_frequency_ratio"] = np.log(2.0 * math.pi / (tp * p))
    scale_low, scale_high = ida.scale_brackets()
    fits = []
    for name in measures:
        if name in skipped:
            continue
        if name == "pga_lambda_g":
            try:
                capacity = row_capacities_m_s2(ida)
            except InputError as exc:
                skipped[name] = str(exc)
                continue
            unit = np.array([records[r].pga_m_s2 for r in played]) / capacity
        else:
            unit = np.array([records[r].value(name) for r in played])
        try:
            fits.append(fit_measure(name, unit, scale_low, scale_high, covariates, ida.record))
        except FitError as exc:
            skipped[name] = str(exc)
    n_used = 0
    clusters, events, cluster_by = ida.bootstrap_clusters()
    if fits and n_bootstrap > 0:
        n_used = bootstrap_efficiency(fits, clusters, events, n_bootstrap, seed)
        if n_used < 10:
            skipped["beta_band"] = f"only {n_used} of {n_bootstrap} bootstrap resamples could be fitted"
    return MeasureComparison(fits, records, float(sa_period_s), tuple(float(t) for t in periods), skipped,
                             n_bootstrap=n_used, cluster_by=cluster_by)
