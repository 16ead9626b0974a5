"""The fragility figure and table of an IDA: collapse probability against PGA (in g,
with m/s2 on the top axis) and against PGV, each with its lognormal maximum-likelihood
fit on the rows' brackets, the bootstrap band clustered by record (or event), the fit
moved to the lower bound of its median (dashed), the goodness of fit, the split of beta
into record-to-record and model parts, and the IDA points (Kaplan-Meier fraction of
records collapsed, each at the middle of its bracket drawn as a bar; right-censored records
marked at their lower bound). Two title lines at most; what the title leaves out is in the
legend, and so is a warning about the record scales."""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np
from matplotlib.legend_handler import HandlerTuple
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ..earthquake.fragility import (BetaSplit, FitCheck, FitError, FragilityBand, FragilityFit, clustered_band,
                                    confidence_curve, empirical_collapse_fraction, fit_intervals, fragility,
                                    goodness_of_fit, split_beta)
from ..earthquake.ida import FIT_BRACKET, FIT_CENSORED, FIT_FAILED, FIT_LEFT_OUT, IdaResult
from ..tables import ReportTable
from ..units import G_M_S2
from .drawing import bridge_caption, legend_pad, new_figure, provenance, save_figure, wrap_text

__all__ = ["FragilityData", "IntensityFragility", "fragility_of", "fragility_data", "plot_fragility", "G_M_S2",
           "BETA_CONVENTION", "BETA_SPLIT", "LEGEND_PAD", "confidence_words", "split_words", "split_label",
           "band_words", "arch_words", "samples_words", "records_words", "top_intensity", "FIT_STYLES",
           "BOUND_STYLES", "POINTS_WORDS", "SCALE_WARN", "scale_warning", "static_capacities_m_s2", "bracket_points",
           "draw_bracket_points", "points_handle", "warning_entry", "two_line_title", "TUPLE_HANDLER"]

#: One line style per measure, in every fragility figure: the fit, and the fit at the
#: lower bound of its median.
FIT_STYLES = {"PGA": "-", "PGV": "-."}
BOUND_STYLES = {"PGA": "--", "PGV": ":"}
#: What an IDA point is: each row is one record on one model.
POINTS_WORDS = ("IDA points: fraction of the rows (record × model) collapsed at or below (Kaplan-Meier), each "
                "row's collapse at the geometric middle of its bracket; the bar spans the bracket (last stand, "
                "first collapse]")
#: A legend handle made of several (a bar and its point, or one mark in each colour).
TUPLE_HANDLER = {tuple: HandlerTuple(ndivide=None, pad=0.3)}
#: A row that collapsed at a record scale outside these is warned of (the record then
#: stands for another earthquake than the one recorded; voussoir-sweep warns too).
SCALE_WARN = (0.25, 4.0)
#: How beta and the bootstrap standard deviations are computed (said in every output).
BETA_CONVENTION = ("beta: maximum likelihood (divisor n, not n - 1); bootstrap standard deviations: "
                   "divisor n - 1 over the resamples")
#: Pad of a figure legend under the axes, in font sizes (8 pt): its 0.5 plus save_figure's 10-pt
#: strip for the small print, which the legend would otherwise cross.
LEGEND_PAD = legend_pad(8.0)
#: How beta is split (said in every output that gives the split).
BETA_SPLIT = ("beta split: the rows of each model sample fitted alone (the same interval-censored maximum "
              "likelihood); record-to-record beta_RTR = sqrt(mean over the samples of beta_s^2), model beta_model "
              "= standard deviation (divisor m - 1) of the samples' ln medians (it also holds the part of their "
              "sampling error that the records shared by the samples do not cancel); "
              "sqrt(beta_RTR^2 + beta_model^2) set beside the pooled beta as a check")


@dataclass
class IntensityFragility:
    """The fragility against one intensity measure."""

    name: str  #: 'PGA' or 'PGV'
    unit: str  #: 'm/s2' or 'm/s'
    im: np.ndarray  #: per row: intensity at the collapse (at the lower bound where right-censored; NaN: left out)
    censored: np.ndarray  #: per row: right-censored (no collapse up to scale_max, or a failed search)
    fit: FragilityFit
    band: FragilityBand
    check: FitCheck  #: PIT and Kolmogorov-Smirnov test of the rows under the fit
    low: np.ndarray  #: per row: the collapse intensity is in (low, high]
    high: np.ndarray
    fit_as: list[str] = field(default_factory=list)  #: per row: how it entered the fit (ida.FIT_*)
    split: BetaSplit | None = None  #: beta by record-to-record and model parts (None: see split_note)
    split_note: str = ""  #: why there is no split

    def confidence(self, im) -> np.ndarray:
        """The fit moved to the lower bound of its median (same beta): :func:`confidence_curve`."""
        return confidence_curve(im, self.fit, self.band)


@dataclass
class FragilityData:
    """What :func:`plot_fragility` drew and printed."""

    pga: IntensityFragility
    pgv: IntensityFragility
    png_path: str | None = None
    table: ReportTable = field(default_factory=lambda: ReportTable([]))
    curve_table: ReportTable = field(default_factory=lambda: ReportTable([]))
    n_non_monotonic: int | None = None  #: rows flagged non_monotonic (None: the file does not say)
    #: the lowest static capacity lambda g of the models [m/s2] (None: the file has none):
    #: no rigid model moves below its own, so no collapse there, but a lognormal has a tail
    floor_m_s2: float | None = None

    def _count(self, how: str) -> int:
        return sum(1 for k in self.pga.fit_as if k == how)

    def summary(self) -> dict:
        """The numbers of the fits (for --json)."""
        f, b = self.pga.fit, self.pga.band
        v, vb = self.pgv.fit, self.pgv.band
        return {
            "median_pga_g": f.median / G_M_S2, "median_pga_m_s2": f.median, "beta": f.beta, "beta_pga": f.beta,
            "median_pga_g_band": [b.median_low / G_M_S2, b.median_high / G_M_S2],
            "beta_pga_band": [b.beta_low, b.beta_high],
            "median_pgv_m_s": v.median, "beta_pgv": v.beta, "median_pgv_m_s_band": [vb.median_low, vb.median_high],
            "beta_pgv_band": [vb.beta_low, vb.beta_high],
            "ln_median_pga_sd": b.ln_median_sd, "beta_pga_sd": b.beta_sd,
            "ln_median_pgv_sd": vb.ln_median_sd, "beta_pgv_sd": vb.beta_sd,
            "beta_convention": BETA_CONVENTION,
            # The interface keys (issue 24): fit 'interval' (the rows' brackets), the band of
            # the median clustered by `band_cluster`, the PGA goodness-of-fit p-value, and
            # PGA's beta split into record-to-record and model parts (None without a split).
            "fit": "interval",
            "fit_description": "interval-censored maximum likelihood: IM_c in (IM at scale_stood, IM at "
                               "scale_threshold]; right-censored at scale_max, and a failed search at its last stand",
            "band_cluster": b.cluster_by, "gof_p_value": self.pga.check.p_value,
            "gof_test": "Kolmogorov-Smirnov of the PGA fit's probability integral transform (randomised within "
                        "each row's bracket) against U(0, 1)",
            "beta_record": None if self.pga.split is None else self.pga.split.beta_rtr,
            "beta_model": None if self.pga.split is None else self.pga.split.beta_model,
            "band_level": b.level, "n_bootstrap": b.n_resamples, "n_bootstrap_unfitted": b.n_unfitted,
            "cluster_by": b.cluster_by, "n_clusters": b.n_clusters,
            "ks_d_pga": self.pga.check.statistic, "ks_p_pga": self.pga.check.p_value,
            "ks_d_pgv": self.pgv.check.statistic, "ks_p_pgv": self.pgv.check.p_value,
            "pit_seed": self.pga.check.seed,
            "pga_floor_m_s2": self.floor_m_s2, "p_collapse_at_floor": self.p_at_floor(),
            "n_rows": f.n, "n_interval": f.n_interval, "n_censored": self._count(FIT_CENSORED),
            "n_failed_censored": self._count(FIT_FAILED), "n_failed_left_out": self._count(FIT_LEFT_OUT),
            "n_non_monotonic": self.n_non_monotonic, "g_m_s2": G_M_S2,
            "median_pga_g_conf": b.median_low / G_M_S2, "median_pgv_m_s_conf": vb.median_low,
            "conf_level": 0.5 * (1.0 + b.level), "confidence_curve": confidence_words(b),
            **_split_keys("pga", self.pga, G_M_S2), **_split_keys("pgv", self.pgv, 1.0),
            "model_samples": None if self.pga.split is None else self.pga.split.samples,
            "beta_split": BETA_SPLIT if self.pga.split is not None else self.pga.split_note,
        }

    def p_at_floor(self) -> float | None:
        """The PGA fit's probability of collapse at the lowest static capacity (None
        without one): the mass the lognormal's tail puts where no rigid model collapses."""
        if self.floor_m_s2 is None:
            return None
        return float(fragility(np.array([self.floor_m_s2]), self.pga.fit.median, self.pga.fit.beta)[0])

    def floor_words(self) -> list[str]:
        """The line on the static capacity's floor (none without a capacity)."""
        if self.floor_m_s2 is None:
            return []
        return [f"floor: no rigid model moves below its static capacity (the lowest here {self.floor_m_s2 / G_M_S2:.3g} "
                f"g); the PGA lognormal gives P(collapse) = {self.p_at_floor():.2g} there, the mass its tail puts "
                f"below the floor"]

    def report_lines(self) -> list[str]:
        """The fits in words: the median and beta of PGA and PGV with their bands, the
        rows and how they entered the fit, the band's clusters, the goodness of fit."""
        summary = self.summary()
        pga, pgv = self.pga, self.pgv
        pct = int(round(100 * pga.band.level))
        left_out = summary["n_failed_left_out"]
        monotonic = ("non_monotonic not in the file" if self.n_non_monotonic is None else
                     f"{self.n_non_monotonic} non-monotonic (a scale above the threshold stood; column non_monotonic)")
        return [
            f"PGA: median {summary['median_pga_g']:.4g} g ({pga.fit.median:.4g} m/s2), {pct} % band "
            f"[{summary['median_pga_g_band'][0]:.4g}, {summary['median_pga_g_band'][1]:.4g}] g; "
            f"beta {pga.fit.beta:.3f} [{pga.band.beta_low:.3f}, {pga.band.beta_high:.3f}]",
            f"PGV: median {pgv.fit.median:.4g} m/s, {pct} % band [{pgv.band.median_low:.4g}, "
            f"{pgv.band.median_high:.4g}] m/s; beta {pgv.fit.beta:.3f} [{pgv.band.beta_low:.3f}, "
            f"{pgv.band.beta_high:.3f}]",
            f"{pga.fit.n} rows: {pga.fit.n_interval} bracketed (stood, collapsed], {summary['n_censored']} censored "
            f"(no collapse up to scale_max), {summary['n_failed_censored']} failed search(es) censored at the last "
            f"stand" + (f", {left_out} failed left out (no stand known)" if left_out else "") + f"; {monotonic}",
            f"band: {pct} % pointwise, {band_words(pga.band)}",
            BETA_CONVENTION + f" (PGA: sd of ln median {pga.band.ln_median_sd:.3f}, of beta {pga.band.beta_sd:.3f})",
            f"goodness of fit: Kolmogorov-Smirnov of the PIT (randomised within the brackets, seed "
            f"{pga.check.seed}) against U(0, 1): PGA D = {pga.check.statistic:.3f}, p = {pga.check.p_value:.3g}; "
            f"PGV D = {pgv.check.statistic:.3f}, p = {pgv.check.p_value:.3g}",
            split_words(pga, G_M_S2, "g"),
            split_words(pgv, 1.0, "m/s"),
        ] + ([BETA_SPLIT] if pga.split is not None else []) + [
            f"{confidence_words(pga.band)}: PGA {pga.band.median_low / G_M_S2:.4g} g, PGV {pgv.band.median_low:.4g} "
            f"m/s (the dashed PGA and dotted PGV curves)",
        ] + self.floor_words()


def _split_keys(measure: str, frag: IntensityFragility, scale: float) -> dict:
    """The split of one measure's beta for --json (None where it is not defined)."""
    split = frag.split
    unit = "g" if measure == "pga" else "m_s"
    return {
        f"beta_{measure}_rtr": None if split is None else split.beta_rtr,
        f"beta_{measure}_model": None if split is None else split.beta_model,
        f"beta_{measure}_srss": None if split is None else split.beta_srss,
        f"median_{measure}_{unit}_by_sample": None if split is None else (split.medians / scale).tolist(),
        f"beta_{measure}_by_sample": None if split is None else split.betas.tolist(),
    }


def confidence_words(band: FragilityBand) -> str:
    """What the dashed curve is, in words."""
    tail = 50.0 * (1.0 - band.level)
    return (f"fit at the median's lower {tail:g} % bound (the {tail:g}th percentile of the bootstrap medians, the "
            f"low end of the {100 * band.level:g} % band: {100 - tail:g} % confident the median is above it; "
            f"same beta)")


def split_words(frag: IntensityFragility, scale: float, unit: str) -> str:
    """One measure's beta beside its parts, and each model sample's median and beta."""
    split = frag.split
    if split is None:
        return f"{frag.name} beta split: not made ({frag.split_note})"
    per_sample = (f"samples' medians {', '.join(f'{m / scale:.3g}' for m in split.medians)} {unit}, betas "
                  f"{', '.join(f'{b:.3f}' for b in split.betas)}")
    if split.beta_model is None:
        return (f"{frag.name} beta split: one model sample: record-to-record {split.beta_rtr:.3f} (= the pooled "
                f"beta); the model part is not defined ({per_sample})")
    return (f"{frag.name} beta split over {split.n_samples} model samples: record-to-record {split.beta_rtr:.3f}, "
            f"model {split.beta_model:.3f}; sqrt(RTR^2 + model^2) = {split.beta_srss:.3f} beside the pooled "
            f"{split.beta_total:.3f} ({per_sample})")


def band_words(band: FragilityBand) -> str:
    """'400 bootstrap resamples of the 8 records (clustered by record: ...)'."""
    what = {"record": f"the {band.n_clusters} records (clustered by record: the rows carry no event; a record's "
                      "rows over the model samples go together)",
            "event": f"the {band.n_clusters} events, then the records within each (clustered by event)",
            "row": f"the {band.n_clusters} rows"}.get(band.cluster_by, f"{band.n_clusters} {band.cluster_by}s")
    unfitted = f", {band.n_unfitted} more could not be fitted" if band.n_unfitted else ""
    return f"{band.n_resamples} bootstrap resamples of {what}{unfitted}"


def fragility_of(name: str, unit: str, low, high, clusters, events, cluster_by: str, n_bootstrap: int,
                 seed: int, fit_as: list[str] | None = None, samples=None,
                 im_max: float | None = None) -> IntensityFragility:
    """The fit, band, check and beta split of one intensity measure from the rows'
    brackets (low, high] (NaN: a row left out); ``clusters``/``events``: see
    :func:`voussoir_post.earthquake.fragility.clustered_band`; ``samples``: each row's
    model sample, for :func:`voussoir_post.earthquake.fragility.split_beta` (None: no
    split); the band's grid runs to ``im_max`` (default 1.15 x the largest intensity)."""
    low, high = np.asarray(low, float), np.asarray(high, float)
    used = np.isfinite(low)
    fit = fit_intervals(low[used], high[used])
    im = np.where(np.isfinite(high), high, low)
    grid = np.linspace(0.0, im_max if im_max is not None else 1.15 * np.nanmax(im), 300)[1:]
    band = clustered_band(low[used], high[used], grid, np.asarray(clusters)[used],
                          None if events is None else np.asarray(events)[used], cluster_by,
                          n_resamples=n_bootstrap, seed=seed)
    check = goodness_of_fit(low, high, fit.median, fit.beta, seed=seed)
    split, note = None, "no model samples given"
    if samples is not None:
        try:
            split = split_beta(low[used], high[used], np.asarray(samples)[used], fit)
        except FitError as exc:
            note = str(exc)
    return IntensityFragility(name, unit, im, np.isinf(high), fit, band, check, low, high,
                              list(fit_as) if fit_as is not None else [], split, "" if split else note)


def top_intensity(ida: IdaResult, measure: str) -> float:
    """The largest intensity of the rows ('pga' in m/s2, 'pgv' in m/s): the top of a
    bracket, the lower bound of a censored row."""
    low, high = ida.intensity_brackets(measure)
    return float(np.nanmax(np.where(np.isfinite(high), high, low)))


def arch_words(ida: IdaResult) -> str:
    """The arch of an IDA in words ('156-degree arch of 13 voussoirs (r_ext ..., t ...)'),
    or its &bridge, short enough for a title ('bridge of 2 segmental spans of 10, 10 m
    (rise 2.5, 2.5 m), ring 450 mm of 20 voussoirs, with fill': its &arch then holds only
    the ring's values)."""
    if "bridge" in ida.config:
        bridge = ida.config["bridge"]
        words = bridge_caption(bridge).split(";")[0]
        if float(bridge.get("fill_density_kg_m3", 0.0)) > 0:
            words += ", with fill"
        return words + (", a standing vehicle" if ida.config.get("vehicle") else "")
    arch = ida.config.get("arch", {})
    if arch.get("embrace_deg") is not None:
        return (f"{arch.get('embrace_deg'):g}-degree arch of {arch.get('n_voussoirs')} voussoirs "
                f"(r_ext {arch.get('r_ext_m')} m, t {arch.get('thickness_m')} m)")
    return os.path.basename(ida.path)


def samples_words(ida: IdaResult) -> str:
    """'4 models (friction, thickness varied)', or '4 models from <file>', or '1 model'."""
    n = ida.n_sets
    models = f"{n} model{'s' if n != 1 else ''}"
    samples_file = str(ida.config.get("sweep", {}).get("model_samples_file", "") or "")
    if samples_file:
        return f"{models} from {os.path.basename(samples_file)}"
    if ida.parameters and n > 1:
        return f"{models} ({', '.join(name.removesuffix('_m').replace('_', ' ') for name in ida.parameters)} varied)"
    return models


def records_words(ida: IdaResult) -> str:
    """'22 ground-motion records (set fema_p695_far_field, first components: 14 events, M 6.5-7.6,
    Rrup 7.1-26 km)', as far as the file tells."""
    n = len(ida.records)
    text = f"{n} ground-motion record{'s' if n != 1 else ''}"
    sweep = ida.config.get("sweep", {})
    facts = []
    if ida.record_set:
        facts.append(f"set {ida.record_set}" + (", first components" if sweep.get("record_components") == "first"
                                                else ""))
    if ida.event is not None:
        facts.append(f"{len(set(ida.event))} events")
    for name, values, unit in (("M", ida.magnitude, ""), ("Rrup", ida.distance_km, " km")):
        if values is not None and np.any(np.isfinite(values)):
            facts.append(f"{name} {np.nanmin(values):.3g}-{np.nanmax(values):.3g}{unit}")
    return text + (f" ({', '.join(facts)})" if facts else "")


def scale_warning(ida: IdaResult) -> str:
    """'3 of 44 rows collapsed at a record scale beyond 4 or below 0.25', or ''."""
    collapsed = ~ida.censored & ~ida.failed
    low, high = SCALE_WARN
    n = int(np.sum(collapsed & ((ida.scale_threshold > high) | (ida.scale_threshold < low))))
    return (f"warning: {n} of {ida.n_rows} rows collapsed at a record scale beyond {high:g} or below {low:g}"
            if n else "")


def static_capacities_m_s2(ida: IdaResult) -> np.ndarray:
    """The distinct static capacities lambda g of the models [m/s2] (empty when the file
    does not give them)."""
    if ida.static_capacity_m_s2 is None:
        return np.array([])
    values = ida.static_capacity_m_s2[np.isfinite(ida.static_capacity_m_s2)]
    return np.unique(np.round(values, 9))


def bracket_points(frag: IntensityFragility) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The IDA points where a reader of an interval-censored fit expects them: each row's
    collapse taken at the geometric middle of its bracket (low, high] (at its top when
    the bracket starts at 0; a censored row at its lower bound, at risk until there), the
    Kaplan-Meier fraction of the rows collapsed at or below, one point per distinct
    middle. Returns (x, p, x_low, x_high): the point, and the span of its brackets."""
    used = np.isfinite(frag.im)
    low, high, censored = frag.low[used], frag.high[used], frag.censored[used]
    top = np.where(np.isfinite(high), high, low)
    middle = np.where(censored, low, np.where(low > 0.0, np.sqrt(np.clip(low, 0.0, None) * top), top))
    xs, ps = empirical_collapse_fraction(middle, censored)
    x_out, p_out, lo_out, hi_out = [], [], [], []
    for x, p in zip(xs, ps):
        if x_out and np.isclose(x, x_out[-1], rtol=1e-9, atol=0.0):
            p_out[-1] = p  # a tie: the fraction after all of its rows
            continue
        same = ~censored & np.isclose(middle, x, rtol=1e-9, atol=0.0)
        x_out.append(x)
        p_out.append(p)
        lo_out.append(float(low[same].min()))
        hi_out.append(float(top[same].max()))
    return np.array(x_out), np.array(p_out), np.array(lo_out), np.array(hi_out)


def draw_bracket_points(ax, frag: IntensityFragility, scale: float, color: str, marker: str = "o",
                        edge: str | None = None) -> None:
    """The IDA points of :func:`bracket_points` (x divided by `scale`), each with a bar
    over its bracket."""
    x, p, lo, hi = bracket_points(frag)
    ax.hlines(p, lo / scale, hi / scale, color=color, linewidth=1.0, alpha=0.8)
    ax.plot(x / scale, p, marker, color=color, markersize=4, linestyle="none",
            **({"markeredgecolor": edge, "markeredgewidth": 0.4} if edge else {}))


def points_handle(colors_markers, edge: str | None = None) -> tuple:
    """The legend handle of the bracket points: a bar with its point, one per colour."""
    return tuple(h for color, marker in colors_markers for h in (
        (Line2D([], [], color=color, linewidth=1.0), Line2D([], [], color=color, marker=marker, linestyle="none",
                                                            markersize=4,
                                                            **({"markeredgecolor": edge, "markeredgewidth": 0.4}
                                                               if edge else {})))))


def warning_entry(text: str) -> Line2D:
    """A warning as a legend entry (a red '!'), where the reader reads the figure."""
    return Line2D([], [], color="tab:red", marker="$!$", markersize=8, linestyle="none", label=text)


def two_line_title(first: str, second: str, width_in: float, fontsize: float = 10.0,
                   second_short: str | None = None) -> str:
    """A figure's title in two lines at most: `first` and `second` each on one line at
    `fontsize` in `width_in` inches (:func:`.drawing.wrap_text`); `second_short` replaces a
    `second` that does not fit, and what still does not fit is cut at a word with '...'."""
    lines = []
    for text, short in ((first, None), (second, second_short)):
        if short is not None and "\n" in wrap_text(text, width_in, fontsize):
            text = short
        wrapped = wrap_text(text, width_in, fontsize).split("\n")
        lines.append(wrapped[0] + (" ..." if len(wrapped) > 1 else ""))
    return "\n".join(lines)


def _title(ida: IdaResult, width_in: float) -> str:
    scale_max = ida.config.get("sweep", {}).get("scale_max")
    top = f" (up to x {scale_max:g})" if isinstance(scale_max, (int, float)) else ""
    return two_line_title(f"Probability of collapse of the {arch_words(ida)}, {samples_words(ida)}",
                          f"under {records_words(ida)}, scaled{top}", width_in,
                          second_short=f"under {len(ida.records)} ground-motion records, scaled{top}")


def rows_words(ida: IdaResult) -> str:
    """'44 analyses (record × model), 2 without collapse up to the largest scale tried, 1 failed search'."""
    failed = f", {ida.n_failed} failed search{'es' if ida.n_failed != 1 else ''}" if ida.n_failed else ""
    return (f"{ida.n_rows} analyses (record × model), {int(ida.censored.sum())} without collapse up to the largest "
            f"scale tried{failed}")


def _draw(ax, frag: IntensityFragility, scale: float, unit_label: str, unit: str,
          capacities: np.ndarray = np.array([])) -> list:
    """One panel; `scale` turns the IM into the axis `unit`; `capacities`: static
    capacities in the IM's unit, drawn as vertical lines."""
    band, fit = frag.band, frag.fit
    fit_style, bound_style = FIT_STYLES[frag.name], BOUND_STYLES[frag.name]
    x = band.im / scale
    ax.fill_between(x, band.low, band.high, color="tab:blue", alpha=0.2, linewidth=0)
    ax.plot(x, fragility(band.im, fit.median, fit.beta), fit_style, color="tab:blue", linewidth=2)
    ax.plot(x, frag.confidence(band.im), bound_style, color="tab:blue", linewidth=1.2)
    for c in capacities:
        ax.axvline(c / scale, color="tab:red", linewidth=1.2, alpha=0.7)
    draw_bracket_points(ax, frag, scale, "black")
    kinds = np.array(frag.fit_as if frag.fit_as else [FIT_CENSORED if c else FIT_BRACKET for c in frag.censored])
    at_max, failed = kinds == FIT_CENSORED, kinds == FIT_FAILED
    if at_max.any():
        ax.plot(frag.im[at_max] / scale, np.full(at_max.sum(), 0.02), ">", color="tab:red", markersize=7,
                linestyle="none")
    if failed.any():
        ax.plot(frag.im[failed] / scale, np.full(failed.sum(), 0.06), ">", color="tab:orange", markersize=7,
                markerfacecolor="none", linestyle="none")
    ax.axvline(fit.median / scale, color="0.45", linestyle=fit_style, linewidth=0.8)
    ax.set_xlim(0.0, band.im[-1] / scale)
    ax.set_ylim(-0.02, 1.02)
    ax.set_ylabel("probability of collapse")
    ax.set_xlabel(unit_label)
    ax.grid(True, which="both", alpha=0.3)
    pct = int(round(100 * band.level))
    clustered = {"record": f"{band.n_clusters} records, clustered by record",
                 "event": f"{band.n_clusters} events, clustered by event"}.get(band.cluster_by, "the rows")
    extra = []
    if at_max.any():
        extra.append(Line2D([], [], color="tab:red", marker=">", linestyle="none", markersize=7,
                            label="no collapse up to the largest scale tried: lower bound of the collapse intensity"))
    if capacities.size:
        extra.append(Line2D([], [], color="tab:red", linewidth=1.2, alpha=0.7,
                            label="static capacity lambda g of the model" + ("s" if capacities.size > 1 else "") +
                                  " (limit analysis): " + ", ".join(f"{c / scale:.3g}" for c in capacities) +
                                  f" {unit}; the searches start there"))
    if failed.any():
        extra.append(Line2D([], [], color="tab:orange", marker=">", markerfacecolor="none", linestyle="none",
                            markersize=7, label="search failed: lower bound at its last stand"))
    tail = 50.0 * (1.0 - band.level)
    return [
        Line2D([], [], color="tab:blue", linewidth=2, linestyle=fit_style,
               label=f"fit: median {fit.median / scale:.3g} {unit}, beta {fit.beta:.2f}{split_label(frag.split)}, "
                     f"goodness of fit p {frag.check.p_value:.2g}"),
        Patch(color="tab:blue", alpha=0.2,
              label=f"{pct} % bootstrap band ({band.n_resamples} resamples of the {clustered})"),
        Line2D([], [], color="tab:blue", linestyle=bound_style, linewidth=1.2,
               label=f"{frag.name} fit at the median's lower {tail:g} % bound ({100 - tail:g} % confident the "
                     f"median is higher), same beta"),
        points_handle([("black", "o")]),
        Line2D([], [], color="0.45", linestyle=fit_style, linewidth=0.8,
               label=f"{frag.name} median: 50 % probability of collapse"),
    ] + extra


def split_label(split: BetaSplit | None) -> str:
    """' (record-to-record 0.14, model 0.07)' for a legend; '' without a model part."""
    if split is None or split.beta_model is None:
        return ""
    return f" (record-to-record {split.beta_rtr:.2f}, model {split.beta_model:.2f})"


def fragility_data(ida: IdaResult, n_bootstrap: int = 400, seed: int = 20261124,
                   im_max: dict[str, float] | None = None) -> FragilityData:
    """The PGA and PGV fragilities of ``ida`` (fits, bands, checks, beta splits by
    ``param_set``) and their tables, without a figure; ``seed``: of the PGA bootstrap
    and PIT (PGV: seed + 1); ``im_max``: the end of the bands' grids by measure
    ('pga' in m/s2, 'pgv' in m/s; default 1.15 x the largest intensity)."""
    clusters, events, cluster_by = ida.bootstrap_clusters()
    fit_as = ida.fit_as
    im_max = im_max or {}
    pga = fragility_of("PGA", "m/s2", *ida.intensity_brackets("pga"), clusters, events, cluster_by, n_bootstrap,
                       seed, fit_as, ida.param_set, im_max.get("pga"))
    pgv = fragility_of("PGV", "m/s", *ida.intensity_brackets("pgv"), clusters, events, cluster_by, n_bootstrap,
                       seed + 1, fit_as, ida.param_set, im_max.get("pgv"))
    non_monotonic = ida.non_monotonic
    # the records' own numbers, when the file has them (a packaged set: magnitude, distance,
    # the site's Vs30, the pulse period of a pulse record)
    metadata = {name: values for name, values in (("magnitude", ida.magnitude), ("distance_km", ida.distance_km),
                                                  ("vs30_m_s", ida.vs30_m_s), ("pulse_period_s", ida.pulse_period_s))
                if values is not None and np.any(np.isfinite(values))}
    rows = []
    for k in range(ida.n_rows):
        rows.append((ida.record[k] if len(ida.record[k]) < 48 else "..." + ida.record[k][-45:],
                     int(ida.param_set[k]), float(ida.scale_stood[k]), float(ida.scale_threshold[k]),
                     float(ida.pga_m_s2[k] / G_M_S2), float(ida.pga_m_s2[k]), float(ida.pgv_m_s[k]),
                     bool(ida.censored[k]), float(pga.low[k] / G_M_S2), float(pgv.low[k]), bool(ida.failed[k]),
                     None if non_monotonic is None else bool(non_monotonic[k]), fit_as[k],
                     float(pga.check.pit[k]), float(pgv.check.pit[k]))
                    + ((ida.event[k],) if ida.event is not None else ())
                    + tuple(float(v[k]) for v in metadata.values()))
    table = ReportTable(["record", "param_set", "scale_stood", "scale_threshold", "pga_threshold_g",
                         "pga_threshold_m_s2", "pgv_threshold_m_s", "censored", "pga_stood_g", "pgv_stood_m_s",
                         "failed", "non_monotonic", "fit_as", "pit_pga", "pit_pgv"]
                        + (["event"] if ida.event is not None else []) + list(metadata), rows,
                        title=f"IDA points of {ida.path}")
    curve = ReportTable(["pga_g", "pga_m_s2", "p_collapse", "p_low", "p_high", "p_conf"],
                        [(float(x / G_M_S2), float(x), float(p), float(lo), float(hi), float(c)) for x, p, lo, hi, c in
                         zip(pga.band.im, fragility(pga.band.im, pga.fit.median, pga.fit.beta), pga.band.low,
                             pga.band.high, pga.confidence(pga.band.im))],
                        title=f"fragility against PGA; p_low, p_high: {int(round(100 * pga.band.level))} % band "
                              f"of {band_words(pga.band)}; p_conf: the {confidence_words(pga.band)}")
    capacities = static_capacities_m_s2(ida)
    return FragilityData(pga, pgv, None, table, curve, None if non_monotonic is None else int(np.sum(non_monotonic)),
                         float(capacities.min()) if capacities.size else None)


def plot_fragility(ida: IdaResult, out_png: str | os.PathLike, n_bootstrap: int = 400,
                   seed: int = 20261124) -> FragilityData:
    """Fit the PGA and PGV fragilities of ``ida`` (:func:`fragility_data`) and draw them
    to ``out_png``."""
    data = fragility_data(ida, n_bootstrap, seed)
    pga, pgv = data.pga, data.pgv
    fig = new_figure(12.0, 7.2)
    ax_a, ax_v = fig.subplots(1, 2)
    handles = _draw(ax_a, pga, G_M_S2, "PGA of the scaled record [g]", "g", static_capacities_m_s2(ida))
    top = ax_a.secondary_xaxis("top", functions=(lambda g: g * G_M_S2, lambda a: a / G_M_S2))
    top.set_xlabel("PGA [m/s²]")
    ax_a.set_title("against peak ground acceleration", fontsize=10)
    handles_v = _draw(ax_v, pgv, 1.0, "PGV of the scaled record [m/s]", "m/s")
    ax_v.set_title("against peak ground velocity", fontsize=10)
    handles[0].set_label("PGA " + handles[0].get_label())
    handles_v[0].set_label("PGV " + handles_v[0].get_label())
    # PGA's and PGV's own lines (fit, bound, median), then the marks both panels share
    entries = [handles[0], handles_v[0], handles[2], handles_v[2], handles[4], handles_v[4], handles[1],
               handles[3]] + handles[5:]
    labels = [h.get_label() if not isinstance(h, tuple) else f"{POINTS_WORDS}; {rows_words(ida)}" for h in entries]
    warning = scale_warning(ida)
    if warning:
        entries.append(warning_entry(warning + " (the record then stands for another earthquake)"))
        labels.append(entries[-1].get_label())
    fig.legend(entries, [wrap_text(label, 5.0, 8.0) for label in labels], fontsize=8, loc="outside lower center",
               ncol=2, borderaxespad=LEGEND_PAD, handler_map=TUPLE_HANDLER)
    fig.suptitle(_title(ida, 12.0 - 0.2), fontsize=10)
    note = provenance(getattr(ida, "code_version", ""), os.path.basename(ida.path))
    data.png_path = save_figure(fig, out_png, note=f"{warning} | {note}" if warning else note)
    return data
