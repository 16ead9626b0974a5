"""The fragility of an IDA on the dimensionless axis PGA / (lambda g) (``voussoir-post
fragility --axis pga-lambda-g``): each row's PGA bracket divided by the static capacity
lambda g of the row's own model sample (:func:`.im_fragility.pga_lambda_g_brackets`),
fitted by the same interval-censored maximum likelihood, band, goodness of fit and beta
split as the PGA fragility (:func:`.fragility_plot.fragility_of`). The static capacity is
then the vertical line at 1 for every model. With ``--compare`` both files' fits on the
one axis, each row divided by its own model's capacity.

Why: lambda g is where the arch first becomes a mechanism, so a stronger model and a
larger arch of the same shape fall at the same PGA / (lambda g) as far as the collapse
onset goes; the frequency dependence (the size of the arch against the period of the
shaking) is not taken out by it (docs/earthquakes.md, "The dimensionless axis")."""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ..earthquake.fragility import empirical_collapse_fraction, fragility
from ..earthquake.ida import FIT_BRACKET, FIT_CENSORED, FIT_FAILED, IdaResult
from ..earthquake.im_fragility import MEASURES, pga_lambda_g_brackets, row_capacities_m_s2
from ..tables import ReportTable
from .drawing import legend_pad, new_figure, provenance, save_figure, wrap_text
from .fragility_compare import COMPARE_COLORS, FragilityComparison, lower_bound_entries
from .fragility_plot import (G_M_S2, FragilityData, IntensityFragility, arch_words, band_words, confidence_words,
                             fragility_data, fragility_of, records_words, samples_words, scale_warning,
                             static_capacities_m_s2)

__all__ = ["LambdaGFragility", "LambdaGComparison", "lambda_g_fragility", "plot_lambda_g_fragility",
           "plot_lambda_g_compare", "RATIO_NAME", "AXIS_LABEL", "lambda_g_keys"]

#: The measure's name in text (as `--im pga_lambda_g` names it) and on the figures.
RATIO_NAME = MEASURES["pga_lambda_g"][0]
_FIGURE_NAME = "PGA / (λ g)"
AXIS_LABEL = "PGA / (λ g)   (static capacity = 1)"
_LEGEND_FONT = 8.0
_WIDTH_IN = 10.5  #: of both figures
_POINT_MARKERS = ("o", "s")


def lambda_g_fragility(ida: IdaResult, n_bootstrap: int = 400, seed: int = 20261124,
                       im_max: float | None = None) -> IntensityFragility:
    """The fit, band, check and beta split of ``ida`` against PGA / (lambda g); the band
    resamples the same clusters as the PGA band (same ``seed``); InputError when the rows
    do not give their static capacity."""
    low, high = pga_lambda_g_brackets(ida)
    clusters, events, cluster_by = ida.bootstrap_clusters()
    return fragility_of(RATIO_NAME, "-", low, high, clusters, events, cluster_by, n_bootstrap, seed, ida.fit_as,
                        ida.param_set, im_max)


def _capacities(ida: IdaResult) -> np.ndarray:
    """The distinct static capacities of the rows' models [m/s2], sorted
    (:func:`.fragility_plot.static_capacities_m_s2`); InputError first when a row does
    not give one > 0 (:func:`.im_fragility.row_capacities_m_s2`)."""
    row_capacities_m_s2(ida)
    return static_capacities_m_s2(ida)


def lambda_g_keys(ratio: IntensityFragility, capacities_m_s2: np.ndarray) -> dict:
    """The fit against PGA / (lambda g) for --json (new keys beside `fragility`'s)."""
    f, b, split = ratio.fit, ratio.band, ratio.split
    return {
        "axis": "pga_lambda_g",
        "median_pga_lambda_g": f.median, "beta_pga_lambda_g": f.beta,
        "median_pga_lambda_g_band": [b.median_low, b.median_high],
        "beta_pga_lambda_g_band": [b.beta_low, b.beta_high],
        "median_pga_lambda_g_conf": b.median_low,
        "ln_median_pga_lambda_g_sd": b.ln_median_sd, "beta_pga_lambda_g_sd": b.beta_sd,
        "gof_p_value_pga_lambda_g": ratio.check.p_value, "ks_d_pga_lambda_g": ratio.check.statistic,
        "beta_pga_lambda_g_rtr": None if split is None else split.beta_rtr,
        "beta_pga_lambda_g_model": None if split is None else split.beta_model,
        "median_pga_lambda_g_by_sample": None if split is None else split.medians.tolist(),
        "static_capacities_m_s2": [float(c) for c in capacities_m_s2],
        "pga_lambda_g_description": "each row's PGA bracket (stood, collapsed] divided by the static capacity "
                                    "lambda g of the row's own model sample (column static_capacity_m_s2); the "
                                    "same interval-censored fit, band clusters and seed as the PGA fit",
    }


def _ratio_lines(ratio: IntensityFragility, capacities_m_s2: np.ndarray) -> list[str]:
    f, b, split = ratio.fit, ratio.band, ratio.split
    pct = int(round(100 * b.level))
    lines = [f"{RATIO_NAME}: each row's PGA over the static capacity lambda g of its own model sample "
             f"({', '.join(f'{c:.4g}' for c in capacities_m_s2)} m/s2 = "
             f"{', '.join(f'{c / G_M_S2:.4g}' for c in capacities_m_s2)} g); the static capacity is 1",
             f"{RATIO_NAME}: median {f.median:.4g}, {pct} % band [{b.median_low:.4g}, {b.median_high:.4g}]; beta "
             f"{f.beta:.3f} [{b.beta_low:.3f}, {b.beta_high:.3f}]; goodness of fit p = {ratio.check.p_value:.3g}; "
             f"{confidence_words(b)}: {b.median_low:.4g}"]
    if split is not None and split.beta_model is not None:
        lines.append(f"{RATIO_NAME} beta split over {split.n_samples} model samples: record-to-record "
                     f"{split.beta_rtr:.3f}, model {split.beta_model:.3f} (samples' medians "
                     f"{', '.join(f'{m:.3g}' for m in split.medians)})")
    return lines


@dataclass
class LambdaGFragility:
    """What :func:`plot_lambda_g_fragility` drew and printed."""

    data: FragilityData  #: the PGA and PGV fits, as `fragility` gives them (no figure of them)
    ratio: IntensityFragility  #: the fit against PGA / (lambda g)
    capacities_m_s2: np.ndarray  #: the models' distinct static capacities
    png_path: str | None = None
    table: ReportTable = field(default_factory=lambda: ReportTable([]))
    curve_table: ReportTable = field(default_factory=lambda: ReportTable([]))

    def summary(self) -> dict:
        """`fragility --json`'s keys, and the dimensionless fit's (:func:`lambda_g_keys`)."""
        return {**self.data.summary(), **lambda_g_keys(self.ratio, self.capacities_m_s2)}

    def report_lines(self) -> list[str]:
        return self.data.report_lines() + _ratio_lines(self.ratio, self.capacities_m_s2)


def _panel(ax, frags: list[IntensityFragility], colors, markers) -> None:
    """The fits of `frags` on one dimensionless axis, and the static capacity at 1."""
    ax.axvline(1.0, color="tab:red", linewidth=1.5, alpha=0.8)
    for k, (frag, color, marker) in enumerate(zip(frags, colors, markers)):
        band, fit = frag.band, frag.fit
        ax.fill_between(band.im, band.low, band.high, color=color, alpha=0.18, linewidth=0)
        ax.plot(band.im, fragility(band.im, fit.median, fit.beta), "-", color=color, linewidth=2)
        ax.plot(band.im, frag.confidence(band.im), "--", color=color, linewidth=1.2)
        ax.axvline(fit.median, color=color, linestyle=":", linewidth=1.0)
        used = np.isfinite(frag.im)
        xs, ps = empirical_collapse_fraction(frag.im[used], frag.censored[used])
        ax.plot(xs, ps, marker, color=color, markersize=4, markeredgecolor="black", markeredgewidth=0.4,
                linestyle="none")
        kinds = np.array(frag.fit_as if frag.fit_as else [FIT_CENSORED if c else FIT_BRACKET for c in frag.censored])
        for kind, y, face in ((FIT_CENSORED, 0.02 + 0.04 * k, color), (FIT_FAILED, 0.10 + 0.04 * k, "none")):
            mine = kinds == kind
            if mine.any():
                ax.plot(frag.im[mine], np.full(mine.sum(), y), ">", color=color, markerfacecolor=face,
                        markersize=7, linestyle="none")
    ax.set_xlim(0.0, frags[0].band.im[-1])
    ax.set_ylim(-0.02, 1.02)
    ax.set_ylabel("probability of collapse")
    ax.set_xlabel(AXIS_LABEL)
    ax.grid(True, which="both", alpha=0.3)


def _legend(frag: IntensityFragility, color: str, marker: str, label: str = "") -> list:
    """One file's legend entries: fit, band, bound, median, points, censored rows."""
    band, fit, split = frag.band, frag.fit, frag.split
    who = f"{label}: " if label else ""
    tail = 50.0 * (1.0 - band.level)
    parts = (f" (record-to-record {split.beta_rtr:.2f}, model {split.beta_model:.2f})"
             if split is not None and split.beta_model is not None else "")
    clusters = {"record": f"{band.n_clusters} records, clustered by record",
                "event": f"{band.n_clusters} events, clustered by event"}.get(band.cluster_by, "the rows")
    entries = [
        Line2D([], [], color=color, linewidth=2,
               label=f"{who}lognormal fit in {_FIGURE_NAME}: median {fit.median:.3g}, β {fit.beta:.2f}{parts}, "
                     f"goodness of fit p {frag.check.p_value:.2g}"),
        Patch(color=color, alpha=0.18,
              label=f"{who}{int(round(100 * band.level))} % bootstrap band of the fit ({band.n_resamples} "
                    f"resamples of the {clusters})"),
        Line2D([], [], color=color, linestyle="--", linewidth=1.2,
               label=f"{who}fit at the median's lower {tail:g} % bound ({band.median_low:.3g}; {100 - tail:g} % "
                     f"confident the median is higher), same β"),
        Line2D([], [], color=color, linestyle=":", linewidth=1.0,
               label=f"{who}median: 50 % probability of collapse at {fit.median:.3g} times the static capacity"),
        Line2D([], [], color=color, marker=marker, markeredgecolor="black", markeredgewidth=0.4, linestyle="none",
               markersize=4, label=f"{who}IDA points: fraction of the rows (record × model) collapsed at or below "
                                   f"(Kaplan-Meier, top of each bracket / λ g)"),
    ]
    return entries + lower_bound_entries(color, who, frag.fit_as)


def _capacity_entry(words: str) -> Line2D:
    return Line2D([], [], color="tab:red", linewidth=1.5, alpha=0.8,
                  label=f"static capacity: PGA = λ g of the row's own model (limit analysis; {words}); the IDA "
                        f"searches start there")


def _title_lines(lines: list[str], width_in: float) -> str:
    """The title's lines, each wrapped to the figure's width (10-pt text)."""
    return "\n".join(wrap_text(line, width_in - 0.2, 10.0) for line in lines)


def _wrapped(handles: list) -> list:
    """The legend's entries, each label wrapped to the width of the figure (the handle
    and the frame take about an inch)."""
    for handle in handles:
        handle.set_label(wrap_text(handle.get_label(), _WIDTH_IN - 1.2, _LEGEND_FONT))
    return handles


def _g_list(capacities_m_s2: np.ndarray) -> str:
    return ", ".join(f"{c / G_M_S2:.3g}" for c in capacities_m_s2) + " g"


def plot_lambda_g_fragility(ida: IdaResult, out_png: str | os.PathLike, n_bootstrap: int = 400,
                            seed: int = 20261124) -> LambdaGFragility:
    """Fit ``ida`` against PGA / (lambda g) (and against PGA and PGV, for the text and
    JSON: :func:`.fragility_plot.fragility_data`) and draw the dimensionless fit to
    ``out_png``; InputError, before any fit, when the rows do not give their capacity."""
    capacities = _capacities(ida)
    ratio = lambda_g_fragility(ida, n_bootstrap, seed)
    data = fragility_data(ida, n_bootstrap, seed)

    fig = new_figure(_WIDTH_IN, 8.0)
    ax = fig.subplots()
    _panel(ax, [ratio], ["tab:blue"], ["o"])
    handles = _legend(ratio, "tab:blue", "o")
    handles.append(_capacity_entry(f"{_g_list(capacities)} for the {ida.n_sets} model"
                                   f"{'s' if ida.n_sets != 1 else ''}"))
    fig.legend(handles=_wrapped(handles), fontsize=_LEGEND_FONT, loc="outside lower center", ncol=1,
               borderaxespad=legend_pad(_LEGEND_FONT))
    scale_max = ida.config.get("sweep", {}).get("scale_max")
    top = f" (x {scale_max:g})" if isinstance(scale_max, (int, float)) else ""
    fig.suptitle(_title_lines([
        f"Probability of collapse of the {arch_words(ida)} against {_FIGURE_NAME}",
        f"under {records_words(ida)}, scaled",
        f"on {samples_words(ida)}: {ida.n_rows} analyses (record × model), {int(ida.censored.sum())} without "
        f"collapse up to the largest scale tried{top}",
        "each row's PGA divided by the static capacity λ g of its own model sample",
        "lognormal fit by interval-censored maximum likelihood on each row's bracket (last scale that stood, first "
        "that collapsed] / λ g"] + [w for w in [scale_warning(ida)] if w], _WIDTH_IN), fontsize=10)
    png = save_figure(fig, out_png, note=provenance(getattr(ida, "code_version", ""), os.path.basename(ida.path)))

    capacity = row_capacities_m_s2(ida)
    pit = ratio.check.pit
    table = ReportTable(data.table.columns + ["static_capacity_m_s2", "pga_lambda_g_stood", "pga_lambda_g_threshold",
                                              "pit_pga_lambda_g"],
                        [tuple(row) + (float(capacity[k]), float(ratio.low[k]), float(ratio.high[k]), float(pit[k]))
                         for k, row in enumerate(data.table.rows)],
                        title=f"IDA points of {ida.path}, with each row's PGA bracket over its model's static capacity")
    curve = ReportTable(["pga_lambda_g", "p_collapse", "p_low", "p_high", "p_conf"],
                        [(float(x), float(p), float(lo), float(hi), float(c)) for x, p, lo, hi, c in
                         zip(ratio.band.im, fragility(ratio.band.im, ratio.fit.median, ratio.fit.beta),
                             ratio.band.low, ratio.band.high, ratio.confidence(ratio.band.im))],
                        title=f"fragility against {RATIO_NAME}; p_low, p_high: {int(round(100 * ratio.band.level))} "
                              f"% band of {band_words(ratio.band)}; p_conf: the {confidence_words(ratio.band)}")
    return LambdaGFragility(data, ratio, capacities, png, table, curve)


@dataclass
class LambdaGComparison(FragilityComparison):
    """What :func:`plot_lambda_g_compare` drew and printed: the two files' fits (as
    --compare gives them) and their fits against PGA / (lambda g)."""

    ratios: list[IntensityFragility] = field(default_factory=list)
    capacities_m_s2: list[np.ndarray] = field(default_factory=list)

    def summary(self) -> dict:
        out = super().summary()
        for fit, ratio, capacities in zip(out["fits"], self.ratios, self.capacities_m_s2):
            fit.update(lambda_g_keys(ratio, capacities))
        out["median_pga_lambda_g_ratio"] = self.ratios[1].fit.median / self.ratios[0].fit.median
        return out

    def report_lines(self) -> list[str]:
        lines = []
        for label, path, data, ratio, capacities in zip(self.labels, self.paths, self.data, self.ratios,
                                                        self.capacities_m_s2):
            lines += [f"== {label}: {path}"] + data.report_lines() + _ratio_lines(ratio, capacities)
        a, b = self.ratios
        lines.append(f"== {self.labels[1]} against {self.labels[0]}"
                     + ("" if self.same_records else " (NOT the same records)"))
        summary = self.summary()
        lines.append(f"{RATIO_NAME}: median {a.fit.median:.4g} -> {b.fit.median:.4g} (x "
                     f"{summary['median_pga_lambda_g_ratio']:.3f}); beta {a.fit.beta:.3f} -> {b.fit.beta:.3f}; "
                     f"PGA: median x {summary['median_pga_ratio']:.3f}")
        return lines


def plot_lambda_g_compare(ida_a: IdaResult, ida_b: IdaResult, labels: list[str], out_png: str | os.PathLike,
                          n_bootstrap: int = 400, seed: int = 20261124) -> LambdaGComparison:
    """Both IDAs against PGA / (lambda g) on one axis (each row over its own model's
    capacity; the bands on one grid up to 1.15 x the largest ratio of either), colour
    by file; the text and JSON also give each file's PGA and PGV fits."""
    idas = [ida_a, ida_b]
    capacities = [_capacities(ida) for ida in idas]
    tops = [np.nanmax(np.where(np.isfinite(h), h, lo)) for lo, h in (pga_lambda_g_brackets(ida) for ida in idas)]
    ratios = [lambda_g_fragility(ida, n_bootstrap, seed, 1.15 * max(tops)) for ida in idas]
    data = [fragility_data(ida, n_bootstrap, seed) for ida in idas]
    same_records = ida_a.records == ida_b.records

    fig = new_figure(_WIDTH_IN, 9.2)
    ax = fig.subplots()
    _panel(ax, ratios, COMPARE_COLORS, _POINT_MARKERS)
    # one column, the files one after the other (two columns would halve each entry's width)
    handles = [h for k, r in enumerate(ratios) for h in _legend(r, COMPARE_COLORS[k], _POINT_MARKERS[k], labels[k])]
    handles.append(_capacity_entry("; ".join(f"{label}: {_g_list(c)}" for label, c in zip(labels, capacities))))
    fig.legend(handles=_wrapped(handles), fontsize=_LEGEND_FONT,
               loc="outside lower center", ncol=1, borderaxespad=legend_pad(_LEGEND_FONT))
    arches = [arch_words(ida) for ida in idas]
    arch = (f"the {arches[0]}" if arches[0] == arches[1] and ida_a.config.get("arch")
            else f"{arches[0]} ({labels[0]}) and {arches[1]} ({labels[1]})")
    records = (f"the same {records_words(ida_a)}, scaled" if same_records else
               f"{len(ida_a.records)} and {len(ida_b.records)} scaled records (NOT the same)")
    colours = [c.removeprefix("tab:") for c in COMPARE_COLORS]
    fig.suptitle(_title_lines([
        f"Probability of collapse of {arch} against {_FIGURE_NAME}", f"under {records}",
        f"{colours[0]}: {labels[0]}, {samples_words(ida_a)}; {colours[1]}: {labels[1]}, {samples_words(ida_b)}",
        "each row's PGA divided by the static capacity λ g of its own model sample",
        "lognormal fits by interval-censored maximum likelihood on each row's bracket (last scale that stood, first "
        "that collapsed] / λ g"] + [f"{label}: {w}" for label, w in zip(labels, map(scale_warning, idas)) if w],
        _WIDTH_IN), fontsize=10)
    png = save_figure(fig, out_png, note=provenance(ida_a.code_version or ida_b.code_version,
                                                 os.path.basename(ida_a.path), os.path.basename(ida_b.path)))

    a, b = ratios
    curves = [np.column_stack([fragility(f.band.im, f.fit.median, f.fit.beta), f.band.low, f.band.high,
                               f.confidence(f.band.im)]) for f in ratios]
    columns_csv = ["pga_lambda_g"] + [f"{name}_{tag}" for tag in ("a", "b")
                                      for name in ("p_collapse", "p_low", "p_high", "p_conf")]
    table = ReportTable(columns_csv, [(float(x), *map(float, ca), *map(float, cb))
                                      for x, ca, cb in zip(a.band.im, *curves)],
                        title=f"fragility against {RATIO_NAME} of a: {labels[0]} ({ida_a.path}) and b: {labels[1]} "
                              f"({ida_b.path}); p_low, p_high: the {int(round(100 * a.band.level))} % band; p_conf: "
                              f"the {confidence_words(a.band)}")
    return LambdaGComparison(list(labels), [ida_a.path, ida_b.path], data, png, table, same_records, ratios,
                             capacities)
