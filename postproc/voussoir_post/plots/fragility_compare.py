"""Two IDA fragilities in one figure (``voussoir-post fragility A.h5 --compare B.h5``),
e.g. the nominal model against the model the table tests revealed: for each file, its
lognormal fits against PGA (g, with m/s2 on the top axis) and PGV, their bootstrap
bands clustered by record (or event), the fits at the lower bound of the median
(one line style per measure: PGA fit solid and bound dashed, PGV dash-dot and dotted) and
the IDA points, on common axes, with the static capacity lambda g of the models where the
files give it (/results/static_capacity_m_s2); the text and JSON give both fits with the
split of beta and the ratio of the medians. The legend has one entry per model (its
colour, its numbers) and one per kind of mark (its style, in both colours): a dashed
bound belongs to the model of its colour."""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ..earthquake.fragility import fragility
from ..earthquake.ida import FIT_BRACKET, FIT_CENSORED, FIT_FAILED, IdaResult
from ..tables import ReportTable
from .drawing import new_figure, provenance, save_figure, wrap_text
from .fragility_plot import (BOUND_STYLES, FIT_STYLES, G_M_S2, LEGEND_PAD, POINTS_WORDS, TUPLE_HANDLER,
                             FragilityData, IntensityFragility, arch_words, confidence_words, draw_bracket_points,
                             fragility_data, points_handle, records_words, samples_words, scale_warning,
                             split_label, static_capacities_m_s2, top_intensity, two_line_title, warning_entry)

__all__ = ["FragilityComparison", "plot_fragility_compare", "COMPARE_COLORS", "FIT_STYLES", "POINT_MARKERS",
           "compare_title", "lower_bound_entries", "band_kind_words", "MODEL_WRAP_IN"]

#: One colour per file (the first, the second).
COMPARE_COLORS = ("tab:blue", "tab:orange")
#: One marker of the IDA points per file.
POINT_MARKERS = ("o", "s")
_WIDTH_IN = 12.5
#: Width [in] to which a model's legend entry is wrapped (wrap_text's estimate is generous:
#: 92 characters of 8-pt text take about 5.3 in).
MODEL_WRAP_IN = 5.6


@dataclass
class FragilityComparison:
    """What :func:`plot_fragility_compare` drew and printed."""

    labels: list[str]  #: the two files' names in the figure and the text
    paths: list[str]
    data: list[FragilityData]  #: the fits of each file (same seeds, bands on a common grid)
    png_path: str | None = None
    curve_table: ReportTable = field(default_factory=lambda: ReportTable([]))
    same_records: bool = True  #: the two IDAs ran the same record files

    def summary(self) -> dict:
        """Both fits (each as `fragility --json` gives it) and the ratios of the medians (for --json)."""
        fits = [d.summary() for d in self.data]
        return {
            "labels": list(self.labels), "files": list(self.paths), "fits": fits,
            "median_pga_ratio": fits[1]["median_pga_g"] / fits[0]["median_pga_g"],
            "median_pgv_ratio": fits[1]["median_pgv_m_s"] / fits[0]["median_pgv_m_s"],
            "same_records": self.same_records,
        }

    def report_lines(self) -> list[str]:
        """Each file's fit in words (as `fragility` prints it), then the two side by side."""
        lines = []
        for label, path, data in zip(self.labels, self.paths, self.data):
            lines.append(f"== {label}: {path}")
            lines += data.report_lines()
        summary = self.summary()
        a, b = self.data
        lines.append(f"== {self.labels[1]} against {self.labels[0]}"
                     + ("" if self.same_records else " (NOT the same records)"))
        for name, scale, unit in (("pga", G_M_S2, "g"), ("pgv", 1.0, "m/s")):
            fa, fb = getattr(a, name), getattr(b, name)
            lines.append(
                f"{name.upper()}: median {fa.fit.median / scale:.4g} -> {fb.fit.median / scale:.4g} {unit} "
                f"(x {summary[f'median_{name}_ratio']:.3f}); beta {fa.fit.beta:.3f} -> {fb.fit.beta:.3f}"
                f"{_split_change(fa, fb)}")
        return lines


def _split_change(fa: IntensityFragility, fb: IntensityFragility) -> str:
    if fa.split is None or fb.split is None or fa.split.beta_model is None or fb.split.beta_model is None:
        return ""
    return (f", record-to-record {fa.split.beta_rtr:.3f} -> {fb.split.beta_rtr:.3f}, model "
            f"{fa.split.beta_model:.3f} -> {fb.split.beta_model:.3f}")


def compare_title(idas: list[IdaResult], labels: list[str], same_records: bool, width_in: float,
                  what: str = "") -> str:
    """Two lines: the arch (or both), `what` after it, and the records."""
    arches = [arch_words(ida) for ida in idas]
    arch = (f"the {arches[0]}" if arches[0] == arches[1] and idas[0].config.get("arch")
            else f"{arches[0]} ({labels[0]}) and {arches[1]} ({labels[1]})")
    records = (f"under the same {records_words(idas[0])}, scaled" if same_records else
               f"under {len(idas[0].records)} and {len(idas[1].records)} scaled records (NOT the same)")
    short = (f"under the same {len(idas[0].records)} ground-motion records, scaled" if same_records else None)
    return two_line_title(f"Probability of collapse of {arch}{what}", records, width_in, second_short=short)


def band_kind_words(band) -> str:
    """'90 % bootstrap band of the fit (400 resamples of the 14 events, clustered by event)'."""
    what = {"record": f"the {band.n_clusters} records, clustered by record",
            "event": f"the {band.n_clusters} events, clustered by event"}.get(band.cluster_by, "the rows")
    return f"{int(round(100 * band.level))} % bootstrap band of the fit ({band.n_resamples} resamples of {what})"


def _panel(ax, frags: list[IntensityFragility], scale: float, unit_label: str,
           capacities: list[np.ndarray] = ()) -> None:
    """One measure of both files on one axis; `scale` turns the IM into the axis unit;
    `capacities`: each file's static capacities in the IM's unit (vertical lines)."""
    for k, values in enumerate(capacities):
        for c in values:
            ax.axvline(c / scale, color=COMPARE_COLORS[k], linewidth=3, alpha=0.35)
    for k, frag in enumerate(frags):
        color, band, fit = COMPARE_COLORS[k], frag.band, frag.fit
        x = band.im / scale
        ax.fill_between(x, band.low, band.high, color=color, alpha=0.18, linewidth=0)
        ax.plot(x, fragility(band.im, fit.median, fit.beta), FIT_STYLES[frag.name], color=color, linewidth=2)
        ax.plot(x, frag.confidence(band.im), BOUND_STYLES[frag.name], color=color, linewidth=1.1)
        draw_bracket_points(ax, frag, scale, color, POINT_MARKERS[k], edge="black")
        kinds = np.array(frag.fit_as if frag.fit_as else [FIT_CENSORED if c else FIT_BRACKET for c in frag.censored])
        for kind, y, face in ((FIT_CENSORED, 0.02 + 0.04 * k, color), (FIT_FAILED, 0.10 + 0.04 * k, "none")):
            mine = kinds == kind
            if mine.any():
                ax.plot(frag.im[mine] / scale, np.full(mine.sum(), y), ">", color=color, markerfacecolor=face,
                        markersize=7, linestyle="none")
    ax.set_xlim(0.0, frags[0].band.im[-1] / scale)
    ax.set_ylim(-0.02, 1.02)
    ax.set_ylabel("probability of collapse")
    ax.set_xlabel(unit_label)
    ax.grid(True, which="both", alpha=0.3)


def _model_entry(k: int, label: str, data: FragilityData, ida: IdaResult) -> tuple[object, str]:
    """File k's one legend entry: its colour, and its fits' numbers in words."""
    color = COMPARE_COLORS[k]
    tail = 50.0 * (1.0 - data.pga.band.level)
    words = [f"{label}: {samples_words(ida)}"]
    for frag, scale, unit in ((data.pga, G_M_S2, "g"), (data.pgv, 1.0, "m/s")):
        words.append(f"{frag.name} median {frag.fit.median / scale:.3g} {unit} (lower {tail:g} % bound "
                     f"{frag.band.median_low / scale:.3g}), beta {frag.fit.beta:.2f}{split_label(frag.split)}")
    capacities = static_capacities_m_s2(ida)
    if capacities.size:
        words.append("static capacity λ g " + ", ".join(f"{c / G_M_S2:.3g}" for c in capacities) + " g")
    handle = (Line2D([], [], color=color, linewidth=6, alpha=0.35),
              Line2D([], [], color=color, marker=POINT_MARKERS[k], markeredgecolor="black", markeredgewidth=0.4,
                     linestyle="none", markersize=5))
    return handle, "\n".join(wrap_text(w, MODEL_WRAP_IN, 8.0) for w in words)


def _kind_entries(data: list[FragilityData], idas: list[IdaResult]) -> list[tuple[object, str]]:
    """One legend entry per kind of mark, its handle in both files' colours."""
    def both(**style):
        return tuple(Line2D([], [], color=c, **style) for c in COMPARE_COLORS)

    band = data[0].pga.band
    tail = 50.0 * (1.0 - band.level)
    entries = []
    for name, measure in (("PGA", "peak ground acceleration"), ("PGV", "peak ground velocity")):
        entries.append((both(linewidth=2, linestyle=FIT_STYLES[name]),
                        f"{name} fit: lognormal, interval-censored maximum likelihood on each row's bracket"))
    for name in ("PGA", "PGV"):
        entries.append((both(linewidth=1.1, linestyle=BOUND_STYLES[name]),
                        f"{name} fit at its median's lower {tail:g} % bound ({100 - tail:g} % confident the median is "
                        f"above it), same beta: a bound of the model of its colour, not a model"))
    entries.append((tuple(Patch(color=c, alpha=0.18) for c in COMPARE_COLORS), band_kind_words(band)))
    entries.append((points_handle(zip(COMPARE_COLORS, POINT_MARKERS), edge="black"), POINTS_WORDS))
    if any(static_capacities_m_s2(ida).size for ida in idas):
        entries.append((both(linewidth=3, alpha=0.35),
                        "static capacity λ g of each model sample (limit analysis): the IDA searches start there"))
    kinds = set().union(*(d.pga.fit_as for d in data))
    entries += [(both(marker=h.get_marker(), linestyle="none", markersize=7,
                      markerfacecolor="none" if h.get_markerfacecolor() == "none" else None),
                 h.get_label()) for h in lower_bound_entries("black", "", kinds)]
    return entries


def model_and_kind_legend(fig, models: list[tuple[object, str]], kinds: list[tuple[object, str]],
                          warnings: list[str]) -> None:
    """The figure's legend under the axes: the models in the left column, the kinds of
    mark (and the warnings) in the right."""
    kinds = kinds + [(warning_entry(w), w) for w in warnings]
    right = [(h, "\n".join(wrap_text(line, 5.2, 8.0) for line in text.split("\n"))) for h, text in kinds]
    blank = (Line2D([], [], linestyle="none"), " ")
    # equal columns, so that the models stay in the left one (a legend fills columns first)
    lines = lambda entries: sum(text.count("\n") + 1 for _, text in entries)  # noqa: E731
    left = list(models)
    while lines(left) + 1 <= lines(right) and len(left) < len(right):
        left.append(blank)
    left += [blank] * (len(right) - len(left))
    right += [blank] * (len(left) - len(right))
    entries = left + right
    fig.legend([h for h, _ in entries], [t for _, t in entries], fontsize=8, loc="outside lower center", ncol=2,
               handlelength=4.0, borderaxespad=LEGEND_PAD, handler_map=TUPLE_HANDLER)


def lower_bound_entries(color: str, who: str, fit_as) -> list:
    """The legend entries of the rows fitted as lower bounds (``fit_as``: each row's
    kind), ``who`` the words before each ("nominal model: ")."""
    kinds = set(fit_as)
    entries = []
    if FIT_CENSORED in kinds:
        entries.append(Line2D([], [], color=color, marker=">", linestyle="none", markersize=7,
                              label=f"{who}no collapse up to the largest scale tried (lower bound)"))
    if FIT_FAILED in kinds:
        entries.append(Line2D([], [], color=color, marker=">", markerfacecolor="none", linestyle="none",
                              markersize=7, label=f"{who}search failed (lower bound at its last stand)"))
    return entries


def plot_fragility_compare(ida_a: IdaResult, ida_b: IdaResult, labels: list[str], out_png: str | os.PathLike,
                           n_bootstrap: int = 400, seed: int = 20261124) -> FragilityComparison:
    """Fit both IDAs (:func:`.fragility_plot.fragility_data`, the same seeds, the bands
    on one grid per measure up to 1.15 x the largest intensity of either) and draw them
    in one figure at ``out_png``: colour by file, line style by measure."""
    idas = [ida_a, ida_b]
    im_max = {m: 1.15 * max(top_intensity(ida, m) for ida in idas) for m in ("pga", "pgv")}
    data = [fragility_data(ida, n_bootstrap, seed, im_max) for ida in idas]
    same_records = ida_a.records == ida_b.records

    fig = new_figure(_WIDTH_IN, 7.8)
    ax_a, ax_v = fig.subplots(1, 2)
    _panel(ax_a, [d.pga for d in data], G_M_S2, "PGA of the scaled record [g]",
           [static_capacities_m_s2(ida) for ida in idas])
    top = ax_a.secondary_xaxis("top", functions=(lambda g: g * G_M_S2, lambda a: a / G_M_S2))
    top.set_xlabel("PGA [m/s²]")
    ax_a.set_title("against peak ground acceleration", fontsize=10)
    _panel(ax_v, [d.pgv for d in data], 1.0, "PGV of the scaled record [m/s]")
    ax_v.set_title("against peak ground velocity", fontsize=10)
    warnings = [f"{label}: {w}" for label, w in zip(labels, (scale_warning(ida) for ida in idas)) if w]
    model_and_kind_legend(fig, [_model_entry(k, labels[k], d, idas[k]) for k, d in enumerate(data)],
                          _kind_entries(data, idas),
                          [f"{w} (the record then stands for another earthquake)" for w in warnings])
    fig.suptitle(compare_title(idas, labels, same_records, _WIDTH_IN - 0.2), fontsize=10)
    note = provenance(ida_a.code_version or ida_b.code_version, os.path.basename(ida_a.path),
                      os.path.basename(ida_b.path))
    png = save_figure(fig, out_png, note=" | ".join(warnings + [note]))

    a, b = data[0].pga, data[1].pga
    assert np.array_equal(a.band.im, b.band.im)  # one grid
    columns_csv = ["pga_g", "pga_m_s2"]
    for tag in ("a", "b"):
        columns_csv += [f"p_collapse_{tag}", f"p_low_{tag}", f"p_high_{tag}", f"p_conf_{tag}"]
    curves = [np.column_stack([fragility(f.band.im, f.fit.median, f.fit.beta), f.band.low, f.band.high,
                               f.confidence(f.band.im)]) for f in (a, b)]
    table = ReportTable(columns_csv,
                        [(float(x / G_M_S2), float(x), *map(float, ca), *map(float, cb))
                         for x, ca, cb in zip(a.band.im, *curves)],
                        title=f"fragility against PGA of a: {labels[0]} ({ida_a.path}) and b: {labels[1]} "
                              f"({ida_b.path}); p_low, p_high: the {int(round(100 * a.band.level))} % band; p_conf: "
                              f"the {confidence_words(a.band)}")
    return FragilityComparison(list(labels), [ida_a.path, ida_b.path], data, png, table, same_records)
