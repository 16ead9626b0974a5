"""Two IDA fragilities in one figure (``voussoir-post fragility A.h5 --compare B.h5``),
e.g. the nominal model against the model the table tests revealed: for each file, its
lognormal fits against PGA (g, with m/s2 on the top axis) and PGV, their bootstrap
bands clustered by record (or event), the fits at the lower bound of the median
(one line style per measure: PGA fit solid and bound dashed, PGV dash-dot and dotted) and
the IDA points, on common axes, with the static capacity lambda g of the models where the
files give it (/results/static_capacity_m_s2); the text and JSON give both fits with the
split of beta and the ratio of the medians."""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ..earthquake.fragility import empirical_collapse_fraction, fragility
from ..earthquake.ida import FIT_BRACKET, FIT_CENSORED, FIT_FAILED, IdaResult
from ..tables import ReportTable
from .drawing import new_figure, provenance, save_figure
from .fragility_plot import (BOUND_STYLES, FIT_STYLES, G_M_S2, LEGEND_PAD, FragilityData,
                             IntensityFragility, arch_words, confidence_words, fragility_data, records_words,
                             samples_words, scale_warning, split_label, static_capacities_m_s2, top_intensity)

__all__ = ["FragilityComparison", "plot_fragility_compare", "COMPARE_COLORS", "FIT_STYLES"]

#: One colour per file (the first, the second).
COMPARE_COLORS = ("tab:blue", "tab:orange")
_POINT_MARKERS = ("o", "s")


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


def _title(idas: list[IdaResult], labels: list[str], same_records: bool, data: list[FragilityData]) -> str:
    arches = [arch_words(ida) for ida in idas]
    arch = (f"the {arches[0]}" if arches[0] == arches[1] and idas[0].config.get("arch")
            else f"{arches[0]} ({labels[0]}) and {arches[1]} ({labels[1]})")
    records = (f"the same {records_words(idas[0])}, scaled" if same_records else
               f"{len(idas[0].records)} and {len(idas[1].records)} scaled records (NOT the same)")
    band = data[0].pga.band
    clustered = {"record": "clustered by record", "event": "clustered by event"}.get(band.cluster_by, "of the rows")
    colours = [c.removeprefix("tab:") for c in COMPARE_COLORS]
    return (f"Probability of collapse of {arch}\nunder {records}\n"
            f"{colours[0]}: {labels[0]}, {samples_words(idas[0])}; {colours[1]}: {labels[1]}, "
            f"{samples_words(idas[1])}\n"
            f"lognormal fits by interval-censored maximum likelihood; bands: {int(round(100 * band.level))} % "
            f"bootstrap {clustered} ({band.n_resamples} resamples)")


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
        used = np.isfinite(frag.im)
        xs, ps = empirical_collapse_fraction(frag.im[used], frag.censored[used])
        ax.plot(xs / scale, ps, _POINT_MARKERS[k], color=color, markersize=4, markeredgecolor="black",
                markeredgewidth=0.4, linestyle="none")
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


def _legend_entries(k: int, label: str, data: FragilityData, ida: IdaResult) -> list:
    """The legend of file k: its two fits, band, dashed curve, points, censored rows."""
    color = COMPARE_COLORS[k]
    entries = []
    for frag, scale, unit in ((data.pga, G_M_S2, "g"), (data.pgv, 1.0, "m/s")):
        entries.append(Line2D([], [], color=color, linewidth=2, linestyle=FIT_STYLES[frag.name],
                              label=f"{label}: {frag.name} fit, median {frag.fit.median / scale:.3g} {unit}, "
                                    f"beta {frag.fit.beta:.2f}{split_label(frag.split)}"))
    band = data.pga.band
    tail = 50.0 * (1.0 - band.level)
    what = {"record": f"the {band.n_clusters} records", "event": f"the {band.n_clusters} events"}.get(
        band.cluster_by, "the rows")
    entries += [
        Patch(color=color, alpha=0.18, label=f"{label}: {int(round(100 * band.level))} % band, clustered by "
                                             f"{band.cluster_by} (resamples of {what})"),
    ]
    for frag, scale, unit in ((data.pga, G_M_S2, "g"), (data.pgv, 1.0, "m/s")):
        entries.append(Line2D([], [], color=color, linestyle=BOUND_STYLES[frag.name], linewidth=1.1,
                              label=f"{label}: {frag.name} fit at the median's lower {tail:g} % bound "
                                    f"({frag.band.median_low / scale:.3g} {unit}), same beta"))
    entries.append(Line2D([], [], color=color, marker=_POINT_MARKERS[k], markeredgecolor="black",
                          markeredgewidth=0.4, linestyle="none", markersize=4,
                          label=f"{label}: IDA points, fraction of the rows (record x model) collapsed at or below"))
    capacities = static_capacities_m_s2(ida)
    if capacities.size:
        entries.append(Line2D([], [], color=color, linewidth=3, alpha=0.35,
                              label=f"{label}: static capacity lambda g (limit analysis): "
                                    + ", ".join(f"{c / G_M_S2:.3g}" for c in capacities) + " g"))
    return entries + lower_bound_entries(color, f"{label}: ", data.pga.fit_as)


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

    fig = new_figure(12.5, 7.8)
    ax_a, ax_v = fig.subplots(1, 2)
    _panel(ax_a, [d.pga for d in data], G_M_S2, "PGA of the scaled record [g]",
           [static_capacities_m_s2(ida) for ida in idas])
    top = ax_a.secondary_xaxis("top", functions=(lambda g: g * G_M_S2, lambda a: a / G_M_S2))
    top.set_xlabel("PGA [m/s²]")
    ax_a.set_title("against peak ground acceleration", fontsize=10)
    _panel(ax_v, [d.pgv for d in data], 1.0, "PGV of the scaled record [m/s]")
    ax_v.set_title("against peak ground velocity", fontsize=10)
    columns = [_legend_entries(k, labels[k], d, idas[k]) for k, d in enumerate(data)]
    rows = max(len(c) for c in columns)
    for c in columns:  # equal columns, so that each file's entries stay in its own column
        c += [Line2D([], [], linestyle="none", label=" ")] * (rows - len(c))
    fig.legend(handles=columns[0] + columns[1], fontsize=8, loc="outside lower center", ncol=2, handlelength=3.5,
               borderaxespad=LEGEND_PAD)
    fig.suptitle(_title(idas, labels, same_records, data), fontsize=10)
    note = provenance(ida_a.code_version or ida_b.code_version, os.path.basename(ida_a.path),
                      os.path.basename(ida_b.path))
    warnings = [f"{label}: {w}" for label, w in zip(labels, (scale_warning(ida) for ida in idas)) if w]
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
