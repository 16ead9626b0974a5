"""Site hazard curves for ``voussoir-post risk``: an intensity measure [g] against the mean
annual frequency of its exceedance [1/yr], read from three kinds of file.

1. **A plain CSV** (Voussoir's own): a header row with ``pga_g`` and ``annual_rate``, ``#``
   comments; fractile curves may ride along as columns ``annual_rate_q<fraction>`` (e.g.
   ``annual_rate_q0.16``, ``annual_rate_q0.84``). PGA only.

2. **The JSON of the USGS hazard web service** (nshmp-haz-ws, behind the Unified Hazard
   Tool; format as written by ``gov.usgs.earthquake.nshmp.www.HazardService`` of
   github.com/usgs/nshmp-haz-ws, its GSON serialisers in ``www/meta/Util.java``)::

       {"status": "success", "date": ..., "url": ..., "server": {...},
        "response": [
          {"metadata": {"edition": {...}, "region": {...}, "latitude": ..., "longitude": ...,
                        "imt": {"id": 0, "value": "PGA", "display": "Peak Ground Acceleration",
                                "displayorder": 0},
                        "vs30": {"value": "760", ...},
                        "xlabel": "Ground Motion (g)", "ylabel": "Annual Frequency of Exceedence",
                        "xvalues": [...]},
           "data": [{"component": "Total", "yvalues": [...]},
                    {"component": "Fault", "yvalues": [...]}, ...]},
          ...one entry per intensity measure...]}

   The intensity measures are nshmp-haz's ``Imt`` names: ``PGA``, ``PGV``, ``SA0P2`` (Sa at
   0.2 s), ``SA1P0``, ...; the x values are in g for PGA and Sa, the y values are annual
   frequencies of exceedance. The curve read is the component ``Total`` of the entry whose
   ``imt.value`` is the measure asked for. The service gives no fractiles.

3. **OpenQuake's hazard-curve CSV** (``oq engine --export-outputs``; files
   ``hazard_curve-mean-PGA_<calc>.csv``, ``quantile_curve-0.16-PGA_<calc>.csv``,
   ``quantile_curve-0.84-SA(1.0)_<calc>.csv``; format as in the OpenQuake manual, "Outputs
   from Classical PSHA", and the engine's QA expected files)::

       #,,,,,"generated_by='OpenQuake engine 3.18.0', start_date='...', checksum=...,
              kind='mean', investigation_time=1.0, imt='PGA'"          (one line)
       lon,lat,depth,poe-0.1000000,poe-0.4000000,poe-0.6000000
       0.00000,0.00000,-0.10000,4.553860E-01,5.754042E-02,6.354511E-03

   One row per site, one column per intensity level: the probability that the level is
   exceeded in ``investigation_time`` T years. With Poisson occurrence the annual rate is
   lambda = -ln(1 - PoE) / T. The kind (``mean``, ``quantile-0.16``, ``rlz-000``) and the
   measure are read from the comment line (older engines wrote
   ``# ..., investigation_time=1.0,imt="PGA"`` without a kind: the kind is then read from the
   file name, ``quantile_curve-0.16-...`` or ``hazard_curve-mean-...``).

What every reader refuses, naming the file: a measure other than the one asked for (the
file's measures listed), negative values, an exceedance rate or probability that rises
with the intensity, a probability above 1, fewer than two usable points. What it drops,
and counts in :attr:`HazardCurve.notes`: the points of rate 0 at the top (the curve has
ended: a power law cannot pass through 0) and, in an OpenQuake file, the points of PoE 1
at the bottom (an infinite rate).
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError

__all__ = ["HazardCurve", "HazardSet", "read_hazard", "read_hazard_set", "normalise_measure", "measure_words"]


@dataclass(frozen=True)
class HazardCurve:
    """A site's hazard: the intensity [g] and the mean annual frequency of its exceedance [1/yr]."""

    pga_g: np.ndarray  #: the intensity levels [g] (PGA, or Sa(T) when `measure` says so)
    annual_rate: np.ndarray
    source: str = ""
    measure: str = "PGA"  #: 'PGA' or 'SA(T)' (:func:`normalise_measure`)
    kind: str = "mean"  #: 'mean', 'quantile-0.16', ... ; '' when the file does not say
    fractile: float | None = None  #: the fractile of a quantile curve (0.16), None for the mean
    notes: tuple = ()  #: what was dropped or converted on reading, in words

    @property
    def im_g(self) -> np.ndarray:
        return self.pga_g

    def rate(self, pga_g) -> np.ndarray:
        """lambda(im), log-log interpolated, the end intervals' power laws beyond the ends."""
        x, y = np.log(self.pga_g), np.log(self.annual_rate)
        q = np.log(np.asarray(pga_g, float))
        k = np.clip(np.searchsorted(x, q) - 1, 0, x.size - 2)
        slope = (y[k + 1] - y[k]) / (x[k + 1] - x[k])
        return np.exp(y[k] + slope * (q - x[k]))


@dataclass
class HazardSet:
    """The mean hazard curve of a site and its fractile curves (fractile -> curve), as read."""

    mean: HazardCurve
    fractiles: dict = field(default_factory=dict)

    @property
    def measure(self) -> str:
        return self.mean.measure


# ------------------------------------------------------------------ measures

def normalise_measure(text: str) -> str:
    """'PGA', or 'SA(T)' with T as %g: from 'PGA', 'pga', 'SA(1.0)', 'Sa(1)', or nshmp-haz's
    'SA1P0' / 'SA0P2'; InputError otherwise."""
    s = str(text).strip().upper().replace(" ", "")
    if s == "PGA":
        return "PGA"
    m = re.fullmatch(r"SA\(([0-9.]+)\)", s) or re.fullmatch(r"SA([0-9]+P[0-9]+)", s)
    if m:
        try:
            period = float(m.group(1).replace("P", "."))
        except ValueError:
            period = math.nan
        if period > 0:
            return f"SA({period:g})"
    if s in ("PGV", "PGD"):
        return s
    raise InputError(f"'{text}' is not an intensity measure the risk takes (PGA, or SA(T) with T in s)")


def measure_words(measure: str) -> str:
    """'PGA' or 'Sa(1 s)'."""
    return measure if not measure.startswith("SA(") else f"Sa({measure[3:-1]} s)"


# ------------------------------------------------------------------ checks

def _curve(x, y, source: str, measure: str, kind: str, notes: list, what: str = "annual rate") -> HazardCurve:
    """A checked curve from intensities `x` [g] and annual rates `y` (zeros at the top dropped)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    if x.size != y.size:
        raise InputError(f"{source}: {x.size} intensity levels but {y.size} {what}s")
    if not (np.all(np.isfinite(x)) and np.all(x > 0)):
        raise InputError(f"{source}: the intensity levels must be finite and > 0")
    if np.any(np.diff(x) <= 0):
        raise InputError(f"{source}: the intensity levels must increase")
    if np.any(np.isnan(y)) or np.any(y < 0):
        k = int(np.argmax(np.isnan(y) | (y < 0)))
        raise InputError(f"{source}: a negative or missing {what} ({y[k]!r} at {x[k]:g} g)")
    rising = np.flatnonzero(np.diff(y) > 0)
    if rising.size:
        k = int(rising[0])
        raise InputError(f"{source}: the {what} rises with the intensity ({y[k]:.4g} at {x[k]:g} g, {y[k + 1]:.4g} "
                         f"at {x[k + 1]:g} g): a hazard curve's exceedance falls as the intensity grows")
    keep = y > 0
    if not keep.all():
        notes.append(f"{int((~keep).sum())} point(s) of zero {what} at the top dropped (from {x[~keep][0]:g} g)")
    x, y = x[keep], y[keep]
    if x.size < 2:
        raise InputError(f"{source}: a hazard curve needs at least two points of positive {what}")
    fractile = None
    if kind.startswith("quantile-"):
        try:
            fractile = float(kind.split("-", 1)[1])
        except ValueError:
            raise InputError(f"{source}: kind '{kind}' is not quantile-<fraction>") from None
        if not 0 < fractile < 1:
            raise InputError(f"{source}: kind '{kind}': a fractile must lie between 0 and 1")
    return HazardCurve(x, y, source, measure, kind, fractile, tuple(notes))


def _check_measure(found: str, wanted: str, source: str, available=None) -> None:
    if normalise_measure(found) != wanted:
        listed = f" (the file has: {', '.join(available)})" if available else ""
        raise InputError(f"{source}: the hazard is for {found}, but the fragility is in {measure_words(wanted)}"
                         f"{listed}: give the hazard of the fragility's measure")


# ------------------------------------------------------------------ readers

def _read_plain_csv(path: Path, text: str, measure: str) -> list[HazardCurve]:
    lines = [(n, line.strip()) for n, line in enumerate(text.splitlines(), 1)
             if line.strip() and not line.lstrip().startswith("#")]
    if not lines:
        raise InputError(f"{path}: empty hazard file")
    header = [c.strip() for c in lines[0][1].split(",")]
    for name in ("pga_g", "annual_rate"):
        if name not in header:
            raise InputError(f"{path}:{lines[0][0]}: missing column '{name}' (header has: {', '.join(header)})")
    if measure != "PGA":
        raise InputError(f"{path}: a plain hazard CSV gives PGA (column pga_g), but the fragility is in "
                         f"{measure_words(measure)}")
    columns = {"annual_rate": "mean"}
    for name in header:
        m = re.fullmatch(r"annual_rate_q([0-9.]+)", name)
        if m:
            columns[name] = f"quantile-{float(m.group(1)):g}"
    index = {name: header.index(name) for name in ["pga_g", *columns]}
    values: dict[str, list[float]] = {name: [] for name in index}
    for n, line in lines[1:]:
        cells = [c.strip() for c in line.split(",")]
        for name, i in index.items():
            try:
                v = float(cells[i])
            except (ValueError, IndexError):
                raise InputError(f"{path}:{n}: {name} must be a number: '{line}'") from None
            if not (v > 0 and math.isfinite(v)):
                raise InputError(f"{path}:{n}: {name} must be positive: '{line}'")
            values[name].append(v)
    if len(values["pga_g"]) < 2:
        raise InputError(f"{path}: a hazard curve needs at least two rows")
    curves = []
    for name, kind in columns.items():
        source = str(path) if name == "annual_rate" else f"{path} ({name})"
        curves.append(_curve(values["pga_g"], values[name], source, "PGA", kind, []))
    return curves


def _read_nshmp_json(path: Path, text: str, measure: str) -> list[HazardCurve]:
    try:
        data = json.loads(text)
    except ValueError as exc:
        raise InputError(f"{path}: not JSON: {exc}") from None
    if not isinstance(data, dict) or not isinstance(data.get("response"), list):
        raise InputError(f"{path}: not the JSON of the USGS hazard service (no 'response' list)")
    if data.get("status") not in (None, "success"):
        raise InputError(f"{path}: the service answered status '{data.get('status')}', not 'success'")
    found = []
    for entry in data["response"]:
        try:
            meta = entry["metadata"]
            imt = meta["imt"]["value"] if isinstance(meta["imt"], dict) else str(meta["imt"])
        except (KeyError, TypeError):
            raise InputError(f"{path}: a response without metadata.imt") from None
        found.append(imt)
        try:
            if normalise_measure(imt) != measure:
                continue
        except InputError:
            continue
        totals = [c for c in entry.get("data", []) if c.get("component") == "Total"]
        if len(totals) != 1:
            raise InputError(f"{path}: {imt}: {len(totals)} curves of component 'Total' (one expected; components: "
                             f"{', '.join(str(c.get('component')) for c in entry.get('data', []))})")
        ylabel = str(meta.get("ylabel", ""))
        if ylabel and "annual" not in ylabel.lower():
            raise InputError(f"{path}: {imt}: y values are '{ylabel}', not annual frequencies of exceedance")
        xlabel = str(meta.get("xlabel", ""))
        if xlabel and "(g)" not in xlabel:
            raise InputError(f"{path}: {imt}: x values are '{xlabel}', not in g")
        site = f"{meta.get('longitude')}, {meta.get('latitude')}"
        vs30 = meta.get("vs30", {})
        vs30 = vs30.get("value") if isinstance(vs30, dict) else vs30
        notes = [f"USGS hazard service, {imt}, component Total, site (lon, lat) = ({site}), Vs30 {vs30} m/s"]
        return [_curve(meta.get("xvalues", []), totals[0].get("yvalues", []), f"{path} ({imt}, Total)",
                       measure, "mean", notes)]
    _check_measure(found[0] if found else "no measure", measure, str(path), found)
    raise InputError(f"{path}: no curve for {measure_words(measure)} (the file has: {', '.join(found) or 'none'})")


_OQ_NAME = re.compile(r"(hazard_curve|quantile_curve)-(?P<kind>mean|[0-9.]+|rlz-[0-9]+)-?(?P<imt>[^_]*)")


def _read_openquake_csv(path: Path, text: str, measure: str, site: int | None) -> list[HazardCurve]:
    first, _, rest = text.partition("\n")
    meta = {}
    for key in ("kind", "imt", "investigation_time"):
        m = re.search(key + r"""\s*=\s*(?:'([^']*)'|"([^"]*)"|([^,\s"']+))""", first)
        if m:
            meta[key] = next(g for g in m.groups() if g is not None)
    if "investigation_time" not in meta:
        raise InputError(f"{path}:1: OpenQuake's comment line gives no investigation_time")
    try:
        years = float(meta["investigation_time"])
    except ValueError:
        raise InputError(f"{path}:1: investigation_time '{meta['investigation_time']}' is not a number") from None
    if not years > 0:
        raise InputError(f"{path}:1: investigation_time must be > 0 (got {years:g})")
    name = _OQ_NAME.match(os.path.basename(path))
    kind = meta.get("kind", "")
    if not kind and name:
        kind = "mean" if name["kind"] == "mean" else (f"quantile-{name['kind']}" if name[1] == "quantile_curve"
                                                      else name["kind"])
    imt = meta.get("imt") or (name["imt"] if name and name["imt"] else "")
    if not imt:
        raise InputError(f"{path}:1: the file does not say its intensity measure (imt)")
    _check_measure(imt, measure, str(path))
    rows = list(csv.reader(io.StringIO(rest)))
    rows = [(n, r) for n, r in enumerate(rows, 2) if r and not r[0].lstrip().startswith("#")]
    if not rows:
        raise InputError(f"{path}: no header row after the comment line")
    header_line, header = rows[0]
    header = [h.strip() for h in header]
    poe_columns = [(k, h) for k, h in enumerate(header) if h.startswith("poe-")]
    if not poe_columns:
        raise InputError(f"{path}:{header_line}: no poe-<level> columns (header: {', '.join(header)})")
    try:
        levels = [float(h[4:]) for _, h in poe_columns]
    except ValueError:
        raise InputError(f"{path}:{header_line}: a poe- column without a number") from None
    sites = rows[1:]
    if not sites:
        raise InputError(f"{path}: no site row")
    if site is None:
        if len(sites) > 1:
            raise InputError(f"{path}: {len(sites)} sites; choose one with --site K (0 to {len(sites) - 1}, in the "
                             f"file's order)")
        site = 0
    if not 0 <= site < len(sites):
        raise InputError(f"{path}: --site {site}: the file has sites 0 to {len(sites) - 1}")
    line, row = sites[site]
    try:
        poe = np.array([float(row[k]) for k, _ in poe_columns])
    except (ValueError, IndexError):
        raise InputError(f"{path}:{line}: the poe- cells must be numbers") from None
    if np.any(np.isnan(poe)) or np.any(poe < 0) or np.any(poe > 1):
        k = int(np.argmax(np.isnan(poe) | (poe < 0) | (poe > 1)))
        raise InputError(f"{path}:{line}: a probability of exceedance {poe[k]!r} outside [0, 1] (at {levels[k]:g} g)")
    where = {h: row[k].strip() for k, h in enumerate(header[:3]) if k < len(row)}
    notes = [f"OpenQuake {kind or 'curve (kind not stated)'} of {imt}, site {site} "
             f"({', '.join(f'{k} {v}' for k, v in where.items() if not k.startswith('poe-'))}); "
             f"PoE in {years:g} yr -> annual rate -ln(1 - PoE) / {years:g}"]
    certain = poe >= 1.0
    if certain.any():
        if np.any(np.diff(certain.astype(int)) > 0):
            raise InputError(f"{path}:{line}: a probability of exceedance rises to 1 with the intensity")
        notes.append(f"{int(certain.sum())} point(s) of PoE 1 at the bottom dropped (an infinite rate)")
    x = np.array(levels)[~certain]
    with np.errstate(divide="ignore"):
        rate = -np.log1p(-poe[~certain]) / years
    if np.any(np.diff(poe) > 0):
        k = int(np.flatnonzero(np.diff(poe) > 0)[0])
        raise InputError(f"{path}:{line}: the probability of exceedance rises with the intensity ({poe[k]:.4g} at "
                         f"{levels[k]:g} g, {poe[k + 1]:.4g} at {levels[k + 1]:g} g)")
    source = f"{path} (site {site})" if len(sites) > 1 else str(path)
    return [_curve(x, rate, source, measure, kind, notes)]


def _kind_of(path: Path, text: str) -> str:
    stripped = text.lstrip("\ufeff").lstrip()
    if stripped.startswith("{"):
        return "nshmp"
    first = stripped.split("\n", 1)[0]
    if first.startswith("#") and "investigation_time" in first:
        return "openquake"
    return "csv"


def _read_curves(path: str | os.PathLike, measure: str = "PGA", site: int | None = None) -> list[HazardCurve]:
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: no such hazard file")
    text = path.read_text(encoding="utf-8-sig")
    measure = normalise_measure(measure)
    kind = _kind_of(path, text)
    if kind == "nshmp":
        return _read_nshmp_json(path, text, measure)
    if kind == "openquake":
        return _read_openquake_csv(path, text, measure, site)
    return _read_plain_csv(path, text, measure)


def read_hazard(path: str | os.PathLike, measure: str = "PGA", site: int | None = None) -> HazardCurve:
    """The mean hazard curve of one file (plain CSV, USGS JSON or OpenQuake CSV, told apart
    by their content). InputError as the module says."""
    curves = _read_curves(path, measure, site)
    return curves[0]


def read_hazard_set(paths, measure: str = "PGA", site: int | None = None) -> HazardSet:
    """The mean curve and the fractile curves of one or more files of one site: exactly one
    mean (an OpenQuake ``rlz-`` curve or a curve of unstated kind counts as the mean only
    alone), any number of fractiles, each fractile once, all of `measure`."""
    curves = [c for p in ([paths] if isinstance(paths, (str, os.PathLike)) else paths)
              for c in _read_curves(p, measure, site)]
    means = [c for c in curves if c.fractile is None]
    if len(means) != 1:
        listed = "; ".join(f"{c.source} ({c.kind or 'kind not stated'})" for c in means) or "none"
        raise InputError(f"one mean hazard curve is needed beside the fractiles, {len(means)} given: {listed}")
    fractiles: dict[float, HazardCurve] = {}
    for c in curves:
        if c.fractile is None:
            continue
        if c.fractile in fractiles:
            raise InputError(f"the {c.fractile:g} fractile given twice: {fractiles[c.fractile].source} and {c.source}")
        fractiles[c.fractile] = c
    return HazardSet(means[0], dict(sorted(fractiles.items())))
