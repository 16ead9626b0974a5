"""The fragility of an IDA on the dimensionless axis PGA / (lambda g) (``voussoir-post
fragility --axis pga-lambda-g``): each row's PGA bracket divided by the static capacity
lambda g of the row's own model sample (:func:`.im_fragility.pga_lambda_g_brackets`),
fitted by the same interval-censored maximum likelihood, band, goodness of fit and beta
split as the PGA fragility (:func:`.fragility_plot.fragility_of`). The static capacity is
then the vertical line at 1 for every model. With ``--compare`` both files' fits on the
one axis, each row divided by its own model's capacity. The x-range runs from just below
the static capacity (or the lowest bracket) to the end of the fits; each IDA point sits
at the geometric middle of its brackets, a bar over them.

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

from ..earthquake.fragility import fragility
from ..earthquake.ida import FIT_BRACKET, FIT_CENSORED, FIT_FAILED, IdaResult
from ..earthquake.im_fragility import MEASURES, pga_lambda_g_brackets, row_capacities_m_s2
from ..tables import ReportTable
from .drawing import legend_pad, new_figure, provenance, save_figure, wrap_text
from .fragility_compare import (COMPARE_COLORS, MODEL_WRAP_IN, POINT_MARKERS, FragilityComparison, band_kind_words,
                                compare_title, lower_bound_entries, model_and_kind_legend)
from .fragility_plot import (G_M_S2, POINTS_WORDS, TUPLE_HANDLER, FragilityData, IntensityFragility, arch_words,
                             band_words, bracket_points, confidence_words, draw_bracket_points, fragility_data,
                             fragility_of, points_handle, records_words, samples_words, scale_warning,
                             static_capacities_m_s2, two_line_title, warning_entry)

__all__ = ["LambdaGFragility", "LambdaGComparison", "lambda_g_fragility", "plot_lambda_g_fragility",
           "plot_lambda_g_compare", "RATIO_NAME", "AXIS_LABEL", "lambda_g_keys"]

#: The measure's name in text (as `--im pga_lambda_g` names it) and on the figures.
RATIO_NAME = MEASURES["pga_lambda_g"][0]
_FIGURE_NAME = "PGA / (λ g)"
AXIS_LABEL = "PGA / (λ g)   (static capacity = 1)"
_LEGEND_FONT = 8.0
_WIDTH_IN = 12.5  #: of both figures (as wide as the comparison against PGA and PGV)


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


def x_range(frags: list[IntensityFragility]) -> tuple[float, float]:
    """The x-range of the data: from a little below the static capacity 1 (or the lowest
    bracket, if lower) to a little beyond the highest bracket or the point where every
    fit reaches 0.995, whichever is further (within the fits' grid)."""
    points = [bracket_points(f) for f in frags]
    lowest = min([1.0] + [float(p[2].min()) for p in points if p[2].size])
    highest = max([float(f.fit.median * np.exp(2.576 * f.fit.beta)) for f in frags]
                  + [float(np.nanmax(f.im)) for f in frags])
    right = min(float(frags[0].band.im[-1]), highest + 0.05 * (highest - lowest))
    return max(0.0, lowest - 0.08 * (right - lowest)), right


def _panel(ax, frags: list[IntensityFragility], colors, markers) -> None:
    """The fits of `frags` on one dimensionless axis, and the static capacity at 1."""
    ax.axvline(1.0, color="tab:red", linewidth=1.5, alpha=0.8)
    edge = "black" if len(frags) > 1 else None
    for k, (frag, color, marker) in enumerate(zip(frags, colors, markers)):
        band, fit = frag.band, frag.fit
        ax.fill_between(band.im, band.low, band.high, color=color, alpha=0.18, linewidth=0)
        ax.plot(band.im, fragility(band.im, fit.median, fit.beta), "-", color=color, linewidth=2)
        ax.plot(band.im, frag.confidence(band.im), "--", color=color, linewidth=1.2)
        ax.axvline(fit.median, color=color, linestyle=":", linewidth=1.0)
        draw_bracket_points(ax, frag, 1.0, color, marker, edge=edge)
        kinds = np.array(frag.fit_as if frag.fit_as else [FIT_CENSORED if c else FIT_BRACKET for c in frag.censored])
        for kind, y, face in ((FIT_CENSORED, 0.02 + 0.04 * k, color), (FIT_FAILED, 0.10 + 0.04 * k, "none")):
            mine = kinds == kind
            if mine.any():
                ax.plot(frag.im[mine], np.full(mine.sum(), y), ">", color=color, markerfacecolor=face,
                        markersize=7, linestyle="none")
    ax.set_xlim(*x_range(frags))
    ax.set_ylim(-0.02, 1.02)
    ax.set_ylabel("probability of collapse")
    ax.set_xlabel(AXIS_LABEL)
    ax.grid(True, which="both", alpha=0.3)


def _fit_words(frag: IntensityFragility) -> str:
    """'median 1.49, β 0.14 (record-to-record 0.13, model 0.05), goodness of fit p 0.24'."""
    fit, split = frag.fit, frag.split
    parts = (f" (record-to-record {split.beta_rtr:.2f}, model {split.beta_model:.2f})"
             if split is not None and split.beta_model is not None else "")
    return f"median {fit.median:.3g}, β {fit.beta:.2f}{parts}, goodness of fit p {frag.check.p_value:.2g}"


def _legend(frag: IntensityFragility, color: str, marker: str) -> list[tuple[object, str]]:
    """The one model's legend entries: fit, band, bound, median, points, censored rows."""
    band, fit = frag.band, frag.fit
    tail = 50.0 * (1.0 - band.level)
    entries = [
        (Line2D([], [], color=color, linewidth=2), f"lognormal fit in {_FIGURE_NAME} by interval-censored maximum "
                                                   f"likelihood on each row's bracket: {_fit_words(frag)}"),
        (Patch(color=color, alpha=0.18), band_kind_words(band)),
        (Line2D([], [], color=color, linestyle="--", linewidth=1.2),
         f"fit at the median's lower {tail:g} % bound ({band.median_low:.3g}; {100 - tail:g} % confident the median "
         f"is higher), same β"),
        (Line2D([], [], color=color, linestyle=":", linewidth=1.0),
         f"median: 50 % probability of collapse at {fit.median:.3g} times the static capacity"),
        (points_handle([(color, marker)]), POINTS_WORDS + ", all over λ g"),
    ]
    return entries + [(h, h.get_label()) for h in lower_bound_entries(color, "", frag.fit_as)]


def _capacity_entry(words: str) -> tuple[Line2D, str]:
    return (Line2D([], [], color="tab:red", linewidth=1.5, alpha=0.8),
            f"static capacity: PGA = λ g of the row's own model (limit analysis; {words}); the IDA searches start "
            f"there")


def _wrapped(entries: list[tuple[object, str]], width_in: float) -> tuple[list, list[str]]:
    """The legend's handles and labels, each label wrapped to `width_in` (the handle
    and the frame take about an inch more)."""
    return [h for h, _ in entries], [wrap_text(t, width_in, _LEGEND_FONT) for _, t in entries]


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

    fig = new_figure(_WIDTH_IN, 7.2)
    ax = fig.subplots()
    _panel(ax, [ratio], ["tab:blue"], ["o"])
    entries = _legend(ratio, "tab:blue", "o")
    entries.append(_capacity_entry(f"{_g_list(capacities)} for the {ida.n_sets} model"
                                   f"{'s' if ida.n_sets != 1 else ''}"))
    warning = scale_warning(ida)
    if warning:
        entries.append((warning_entry(""), f"{warning} (the record then stands for another earthquake)"))
    handles, labels = _wrapped(entries, _WIDTH_IN - 1.2)
    fig.legend(handles, labels, fontsize=_LEGEND_FONT, loc="outside lower center", ncol=1,
               borderaxespad=legend_pad(_LEGEND_FONT), handler_map=TUPLE_HANDLER)
    scale_max = ida.config.get("sweep", {}).get("scale_max")
    top = f" (up to x {scale_max:g})" if isinstance(scale_max, (int, float)) else ""
    fig.suptitle(two_line_title(
        f"Probability of collapse against {_FIGURE_NAME} of the {arch_words(ida)}, {samples_words(ida)}",
        f"under {records_words(ida)}, scaled{top}: each row's PGA over the static capacity λ g of its own model",
        _WIDTH_IN - 0.2, second_short=f"under {len(ida.records)} ground-motion records, scaled{top}: each row's PGA "
                                      f"over the static capacity λ g of its own model"), fontsize=10)
    note = provenance(getattr(ida, "code_version", ""), os.path.basename(ida.path))
    png = save_figure(fig, out_png, note=f"{warning} | {note}" if warning else note)

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


def _kinds(ratios: list[IntensityFragility]) -> list[tuple[object, str]]:
    """One legend entry per kind of mark of the comparison, its handle in both colours."""
    def both(**style):
        return tuple(Line2D([], [], color=c, **style) for c in COMPARE_COLORS)

    tail = 50.0 * (1.0 - ratios[0].band.level)
    entries = [
        (both(linewidth=2), f"lognormal fit in {_FIGURE_NAME} by interval-censored maximum likelihood on each "
                            f"row's bracket"),
        (both(linestyle="--", linewidth=1.2), f"fit at its median's lower {tail:g} % bound ({100 - tail:g} % "
                                              f"confident the median is above it), same β: a bound of the model of "
                                              f"its colour, not a model"),
        (both(linestyle=":", linewidth=1.0), "median: 50 % probability of collapse"),
        (tuple(Patch(color=c, alpha=0.18) for c in COMPARE_COLORS), band_kind_words(ratios[0].band)),
        (points_handle(zip(COMPARE_COLORS, POINT_MARKERS), edge="black"), POINTS_WORDS + ", all over λ g"),
        (Line2D([], [], color="tab:red", linewidth=1.5, alpha=0.8),
         "static capacity: PGA = λ g of the row's own model (limit analysis): 1 for every model; the IDA searches "
         "start there"),
    ]
    kinds = set().union(*(r.fit_as for r in ratios))
    return entries + [(both(marker=h.get_marker(), linestyle="none", markersize=7,
                            markerfacecolor="none" if h.get_markerfacecolor() == "none" else None), h.get_label())
                      for h in lower_bound_entries("black", "", kinds)]


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

    fig = new_figure(_WIDTH_IN, 7.8)
    ax = fig.subplots()
    _panel(ax, ratios, COMPARE_COLORS, POINT_MARKERS)
    models = []
    for k, (label, ratio, ida, c) in enumerate(zip(labels, ratios, idas, capacities)):
        handle = (Line2D([], [], color=COMPARE_COLORS[k], linewidth=6, alpha=0.35),
                  Line2D([], [], color=COMPARE_COLORS[k], marker=POINT_MARKERS[k], markeredgecolor="black",
                         markeredgewidth=0.4, linestyle="none", markersize=5))
        tail = 50.0 * (1.0 - ratio.band.level)
        models.append((handle, "\n".join(wrap_text(w, MODEL_WRAP_IN, _LEGEND_FONT) for w in (
            f"{label}: {samples_words(ida)}", _fit_words(ratio),
            f"lower {tail:g} % bound of the median {ratio.band.median_low:.3g}; static capacity λ g {_g_list(c)}"))))
    warnings = [f"{label}: {w}" for label, w in zip(labels, map(scale_warning, idas)) if w]
    model_and_kind_legend(fig, models, _kinds(ratios), [f"{w} (the record then stands for another earthquake)"
                                                         for w in warnings])
    fig.suptitle(compare_title(idas, labels, same_records, _WIDTH_IN - 0.2, f" against {_FIGURE_NAME}"),
                 fontsize=10)
    note = provenance(ida_a.code_version or ida_b.code_version, os.path.basename(ida_a.path),
                      os.path.basename(ida_b.path))
    png = save_figure(fig, out_png, note=" | ".join(warnings + [note]))

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
