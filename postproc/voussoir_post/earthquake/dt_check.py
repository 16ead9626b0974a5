"""The time-step check of an IDA (``voussoir-post dtcheck A.h5 B.h5``): B is the same
IDA as A (same arch, motion settings, search, model samples) run at a smaller
``&solver dt_s``, on all of A's rows or a subset (a few records, or one model sample).

On the rows common to both, paired by record and ``param_set``, each file's rows are
fitted by the IDA's fragility fit (:func:`.fragility.fit_intervals` on the PGA
brackets of :meth:`.ida.IdaResult.intensity_brackets`), and the change is reported as
the ratio of the medians B / A and the difference of the betas B - A, each with a
90 % band from a *paired* bootstrap: every resample draws the events, then the records
within them (:func:`.fragility.clustered_resamples`, as the fragility's band), and
refits both files on the same drawn rows, so what the two share (the records' own
spread) cancels in the ratio and only the time step's effect and its scatter remain.
A row whose bracket moved is counted, with its shift in scale steps, ln(threshold_B /
threshold_A) / ln(threshold_A / stood_A), A's own final bracket the step (ln(1 / (1 -
scale_tol)) for a row of no width): -1 is B's threshold at A's stand.

What may differ between A and B: ``&solver dt_s`` (B's smaller), the records chosen
(``record_files``, ``record_set``, ``record_components``), how the model samples are
given (``n_samples`` and the ranges or lists, ``model_samples_file``: the samples'
values themselves are compared per ``param_set``), ``dt_check_rows``,
``progress_every_s``, ``max_runs`` and the output file. Anything else is refused,
naming the variable.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..units import G_M_S2
from .fragility import FragilityFit, clustered_resamples, fit_intervals
from .ida import FIT_BRACKET, IdaResult

__all__ = ["DtCheck", "MovedRow", "dt_check", "pair_rows", "check_same_ida", "G_M_S2"]


#: Variables that may differ between the IDA and its check, by namelist group.
_MAY_DIFFER = {
    "solver": {"dt_s"},
    "output": {"file", "every"},
    "sweep": {"record_files", "record_set", "record_components", "dt_check_rows", "progress_every_s",
              "max_runs", "n_samples", "model_samples_file"},
}


def _sampling(name: str) -> bool:
    """A variable that says how the model samples are drawn (their values are compared)."""
    return name.endswith(("_range", "_range_m", "_list", "_list_m", "_list_deg"))


@dataclass
class MovedRow:
    """A row whose bracket at dt_B differs from that at dt_A."""

    record: str
    param_set: int
    bracket_a: tuple[float, float]  #: (scale_stood, scale_threshold) at dt_A (censored: (scale_max, inf))
    bracket_b: tuple[float, float]
    #: ln(threshold_B / threshold_A) / ln(threshold_A / stood_A); None if one is censored or failed
    steps: float | None


@dataclass
class DtCheck:
    """The fits of A and B on their common rows and the change between them."""

    path_a: str
    path_b: str
    dt_s_a: float
    dt_s_b: float
    fit_a: FragilityFit  #: PGA [m/s2]
    fit_b: FragilityFit
    median_ratio_band: tuple[float, float]
    beta_change_band: tuple[float, float]
    n_rows: int  #: rows fitted (common to both, known in both)
    n_left_out: int  #: common rows left out: a failed search with no stand known, in A or B
    band_cluster: str  #: what a resample draws: 'event' (then records) or 'record'
    n_clusters: int
    n_resamples: int  #: resamples in which both files could be fitted
    level: float
    scale_tol: float
    moved: list[MovedRow] = field(default_factory=list)
    n_rows_a: int = 0  #: rows of A (the common ones and the rest)
    notes: list[str] = field(default_factory=list)  #: what could not be compared (check_same_ida)

    @property
    def median_ratio(self) -> float:
        return self.fit_b.median / self.fit_a.median

    @property
    def beta_change(self) -> float:
        return self.fit_b.beta - self.fit_a.beta

    def summary(self) -> dict:
        """The numbers (for --json)."""
        return {
            "file_a": self.path_a, "file_b": self.path_b, "dt_s_a": self.dt_s_a, "dt_s_b": self.dt_s_b,
            "median_pga_g_a": self.fit_a.median / G_M_S2, "median_pga_g_b": self.fit_b.median / G_M_S2,
            "median_ratio": self.median_ratio, "median_ratio_band": list(self.median_ratio_band),
            "beta_a": self.fit_a.beta, "beta_b": self.fit_b.beta, "beta_change": self.beta_change,
            "beta_change_band": list(self.beta_change_band), "band_level": self.level,
            "band_cluster": self.band_cluster, "n_clusters": self.n_clusters, "n_bootstrap": self.n_resamples,
            "n_rows": self.n_rows, "n_rows_a": self.n_rows_a, "n_left_out": self.n_left_out,
            "rows_moved": len(self.moved), "scale_tol": self.scale_tol,
            "rows_moved_detail": [{"record": m.record, "param_set": m.param_set, "bracket_a": list(m.bracket_a),
                                   "bracket_b": list(m.bracket_b), "steps": m.steps} for m in self.moved],
            "g_m_s2": G_M_S2, "notes": list(self.notes),
            "beta_convention": "maximum likelihood (divisor n), interval-censored on (scale_stood, scale_threshold]",
        }

    def lines(self) -> list[str]:
        """A short table and what it says."""
        pct = int(round(100 * self.level))
        ra, rb = self.median_ratio_band
        ba, bb = self.beta_change_band
        what = {"event": f"the {self.n_clusters} events, then the records within each",
                "record": f"the {self.n_clusters} records"}.get(self.band_cluster, f"{self.n_clusters} clusters")
        out = [f"dt check: {self.path_b} (dt_s = {self.dt_s_b:g} s) against {self.path_a} (dt_s = {self.dt_s_a:g} s), "
               f"{self.n_rows} common rows (record x model sample) of A's {self.n_rows_a}"
               + (f", {self.n_left_out} left out (a failed search with no stand)" if self.n_left_out else ""),
               f"{'':24s}{'dt_A':>10s}{'dt_B':>10s}{'B/A or B-A':>12s}   {pct} % band (paired)",
               f"{'median PGA [g]':24s}{self.fit_a.median / G_M_S2:10.4f}{self.fit_b.median / G_M_S2:10.4f}"
               f"{self.median_ratio:12.4f}   {ra:.4f} - {rb:.4f}",
               f"{'beta [-]':24s}{self.fit_a.beta:10.4f}{self.fit_b.beta:10.4f}{self.beta_change:+12.4f}   "
               f"{ba:+.4f} - {bb:+.4f}",
               f"band: {self.n_resamples} paired bootstrap resamples of {what} (each refits both files on the "
               f"same rows)"]
        steps = [round(m.steps, 1) for m in self.moved if m.steps is not None]
        by_steps = ", ".join(f"{s:+.1f} scale steps ({steps.count(s)} row{'s' if steps.count(s) > 1 else ''})"
                             for s in sorted(set(steps)))
        out.append(f"brackets moved: {len(self.moved)} of {self.n_rows} rows"
                   + (f", by {by_steps}; a step: the row's final bracket at dt_A" if steps else "")
                   + (f"; {len(self.moved) - len(steps)} changed between censored, failed and collapsed"
                      if len(steps) < len(self.moved) else ""))
        return out + [f"note: {n}" for n in self.notes]


def _differences(group: str, a: dict, b: dict) -> tuple[list[str], list[str]]:
    """(each variable of &group that differs and may not: 'var: A value / B value', each
    stated by one file only: a note). A variable one file does not state comes from a
    version of voussoir-sweep that did not have it, and ran as its default does."""
    allowed = _MAY_DIFFER.get(group, set())
    differ, notes = [], []
    for name in sorted(set(a) | set(b)):
        if name in allowed or (group == "sweep" and _sampling(name)):
            continue
        if (name in a) != (name in b):
            which, value = ("A", a[name]) if name in a else ("B", b[name])
            notes.append(f"&{group} {name} = {value!r} is stated by {which} only (the other file's version of "
                         f"voussoir-sweep did not write it): taken as the same")
        elif a[name] != b[name]:
            differ.append(f"&{group} {name}: {a[name]!r} in A, {b[name]!r} in B")
    return differ, notes


def check_same_ida(a: IdaResult, b: IdaResult) -> tuple[float, float, list[str]]:
    """(dt_s of A, dt_s of B [s], notes) when B is A's IDA at a smaller time step;
    InputError naming what differs otherwise (the configuration, the sampled
    parameters). The notes say what could not be compared (a variable one file's
    version did not write, different code versions)."""
    for ida in (a, b):
        if not ida.config:
            raise InputError(f"{ida.path}: the file does not carry its configuration (a CSV, or an older "
                             f"version): give the IDA's HDF5 file, whose config_nml says its dt_s, arch and "
                             f"samples")
    dt_a, dt_b = (float(ida.config.get("solver", {}).get("dt_s", math.nan)) for ida in (a, b))
    if not (math.isfinite(dt_a) and math.isfinite(dt_b)):
        raise InputError(f"{a.path if not math.isfinite(dt_a) else b.path}: no &solver dt_s in its configuration")
    if not dt_b < dt_a:
        raise InputError(f"B ({b.path}) runs at dt_s = {dt_b:g} s, not below A's ({a.path}) {dt_a:g} s: give the "
                         f"IDA at the larger time step first")
    diffs, notes = [], []
    for group in sorted(set(a.config) | set(b.config)):
        differ, note = _differences(group, a.config.get(group, {}), b.config.get(group, {}))
        diffs += differ
        notes += note
    if diffs:
        raise InputError(f"{b.path} is not the IDA of {a.path} at another time step: " + "; ".join(diffs))
    if sorted(a.parameters) != sorted(b.parameters):
        raise InputError(f"different model samples: A ({a.path}) samples {', '.join(sorted(a.parameters)) or 'none'}, "
                         f"B ({b.path}) {', '.join(sorted(b.parameters)) or 'none'}")
    if a.code_version != b.code_version:
        notes.append(f"written by different versions: A by {a.code_version or 'an unknown version'}, B by "
                     f"{b.code_version or 'an unknown version'}")
    return dt_a, dt_b, notes


def pair_rows(a: IdaResult, b: IdaResult) -> tuple[np.ndarray, np.ndarray]:
    """(rows of A, rows of B) paired by record and param_set: every row of B must be in A,
    with the same record (its PGA at scale 1) and the same sampled parameters;
    InputError naming the row otherwise."""
    where = {}
    for k, key in enumerate(zip(a.record, a.param_set.tolist())):
        if key in where:
            raise InputError(f"{a.path}: two rows of record {key[0]}, param_set {key[1]}")
        where[key] = k
    rows_a, rows_b = [], []
    for k, key in enumerate(zip(b.record, b.param_set.tolist())):
        if key not in where:
            known = ", ".join(a.records)
            raise InputError(f"different records or samples: row {k + 1} of B ({b.path}), record {key[0]}, "
                             f"param_set {key[1]}, is not in A ({a.path}; its records: {known}; param_set 0 to "
                             f"{int(a.param_set.max())})")
        j = where[key]
        if j in rows_a:
            raise InputError(f"{b.path}: two rows of record {key[0]}, param_set {key[1]}")
        for name, column in a.parameters.items():
            va, vb = float(column[j]), float(b.parameters[name][k])
            if va != vb:
                raise InputError(f"different model samples: param_set {key[1]} has {name} = {va!r} in A "
                                 f"({a.path}) and {vb!r} in B ({b.path})")
        pa, pb = float(a.unit_pga_m_s2[j]), float(b.unit_pga_m_s2[k])
        if math.isfinite(pa) and math.isfinite(pb) and not math.isclose(pa, pb, rel_tol=1e-9):
            raise InputError(f"different records: {key[0]} has a PGA of {pa:.6g} m/s2 in A ({a.path}) and "
                             f"{pb:.6g} m/s2 in B ({b.path})")
        rows_a.append(j)
        rows_b.append(k)
    return np.array(rows_a, int), np.array(rows_b, int)


def _bracket(ida: IdaResult, k: int, how: str) -> tuple[float, float]:
    if how == FIT_BRACKET:
        return float(ida.scale_stood[k]), float(ida.scale_threshold[k])
    return float(ida.scale_stood[k] if ida.failed[k] else ida.scale_threshold[k]), math.inf


def _moved(a: IdaResult, b: IdaResult, rows_a, rows_b, scale_tol: float) -> list[MovedRow]:
    """The common rows whose brackets differ (more than 1e-9 relative), with the shift."""
    fit_a, fit_b = a.fit_as, b.fit_as
    out = []
    for j, k in zip(rows_a.tolist(), rows_b.tolist()):
        ba, bb = _bracket(a, j, fit_a[j]), _bracket(b, k, fit_b[k])
        same = fit_a[j] == fit_b[k] and all(
            (x == y) or (math.isfinite(x) and math.isfinite(y) and math.isclose(x, y, rel_tol=1e-9))
            for x, y in zip(ba, bb))
        if same:
            continue
        both = fit_a[j] == FIT_BRACKET and fit_b[k] == FIT_BRACKET
        width = math.log(ba[1] / ba[0]) if both and ba[0] > 0.0 else 0.0
        step = width if width > 0.0 else -math.log1p(-scale_tol)
        steps = math.log(bb[1] / ba[1]) / step if both else None
        out.append(MovedRow(a.record[j], int(a.param_set[j]), ba, bb, steps))
    return out


def dt_check(a: IdaResult, b: IdaResult, n_bootstrap: int = 400, seed: int = 20261124,
             level: float = 0.90) -> DtCheck:
    """The check of B (A's IDA at a smaller dt_s, see the module) against A on their
    common rows; InputError when B is not A's IDA, FitError when the rows cannot be
    fitted."""
    dt_a, dt_b, notes = check_same_ida(a, b)
    rows_a, rows_b = pair_rows(a, b)
    low_a, high_a = (x[rows_a] for x in a.intensity_brackets("pga"))
    low_b, high_b = (x[rows_b] for x in b.intensity_brackets("pga"))
    used = np.isfinite(low_a) & np.isfinite(low_b)
    low_a, high_a, low_b, high_b = low_a[used], high_a[used], low_b[used], high_b[used]
    fit_a, fit_b = fit_intervals(low_a, high_a), fit_intervals(low_b, high_b)
    clusters, events, cluster_by = a.bootstrap_clusters()
    clusters = np.asarray(clusters)[rows_a][used]
    events = None if events is None else np.asarray(events)[rows_a][used]

    def change(pick):
        fa = fit_intervals(low_a[pick], high_a[pick], tol=1e-9)
        fb = fit_intervals(low_b[pick], high_b[pick], tol=1e-9)
        return math.log(fb.median / fa.median), fb.beta - fa.beta

    values, n_clusters = clustered_resamples(change, int(used.sum()), clusters, events, n_bootstrap, seed)
    values = np.array(values)
    tails = [50.0 * (1.0 - level), 50.0 * (1.0 + level)]
    ratio_band = np.exp(np.percentile(values[:, 0], tails))
    beta_band = np.percentile(values[:, 1], tails)
    scale_tol = float(a.config.get("sweep", {}).get("scale_tol", 0.05))
    return DtCheck(os.fspath(a.path), os.fspath(b.path), dt_a, dt_b, fit_a, fit_b,
                   (float(ratio_band[0]), float(ratio_band[1])), (float(beta_band[0]), float(beta_band[1])),
                   int(used.sum()), int((~used).sum()), cluster_by, n_clusters, len(values), level, scale_tol,
                   _moved(a, b, rows_a, rows_b, scale_tol), a.n_rows, notes)
