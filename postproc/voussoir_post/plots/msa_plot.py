"""The fragility figure and table of a multiple-stripe analysis (MSA): collapse
probability against the PGA level [g] (m/s2 on the top axis), Baker's binomial
maximum-likelihood fit (:mod:`voussoir_post.earthquake.stripes_fit`), its bootstrap
band clustered by record (or event), and each stripe's observed fraction collapsed as a
point with its count (z / n)."""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ..earthquake.fragility import FitError, FragilityBand, FragilityFit, fragility
from ..earthquake.msa import MsaResult
from ..earthquake.stripes_fit import fit_stripes, stripes_band, stripes_of
from ..tables import ReportTable
from .drawing import new_figure, provenance, save_figure
from .fragility_plot import BETA_CONVENTION, G_M_S2, LEGEND_PAD, SCALE_WARN, band_words, warning_entry

__all__ = ["MsaFragilityData", "msa_fragility_data", "plot_msa_fragility", "FIT_WORDS"]

#: The fit, in words (said in every output).
FIT_WORDS = ("fit: binomial maximum likelihood of the stripes (Baker 2015), P(limit state exceeded | PGA) = "
             "Phi(ln(PGA / median) / beta)")


@dataclass
class MsaFragilityData:
    """The MSA fragility: the stripes, the fit and its band."""

    levels_g: np.ndarray  #: the stripes' PGA levels [g], increasing
    n_runs: np.ndarray  #: runs with an outcome at each level
    n_exceeded: np.ndarray  #: runs that exceeded the limit state at each level
    fit: FragilityFit  #: median in g
    band: FragilityBand  #: over PGA in g
    n_failed: int = 0  #: runs that stopped with an error, left out
    n_scale_warned: int = 0  #: runs whose scale is outside SCALE_WARN
    limit_state: str = "collapse"  #: the key of msa.LIMIT_STATES fitted
    limit_state_words: str = "collapse"  #: what exceeding it means
    threshold_mm: float | None = None  #: of hinge-onset or residual-drift
    png_path: str = ""
    table: ReportTable = field(default_factory=lambda: ReportTable([]))
    curve_table: ReportTable = field(default_factory=lambda: ReportTable([]))

    def summary(self) -> dict:
        """The --json keys, those of the IDA's where they apply."""
        f, b = self.fit, self.band
        return {
            "fit": "binomial", "fit_description": FIT_WORDS, "limit_state": self.limit_state,
            "limit_state_description": self.limit_state_words, "threshold_mm": self.threshold_mm,
            "median_pga_g": f.median,
            "median_pga_m_s2": f.median * G_M_S2, "beta": f.beta, "beta_pga": f.beta,
            "median_pga_g_band": [b.median_low, b.median_high], "beta_pga_band": [b.beta_low, b.beta_high],
            "ln_median_pga_sd": b.ln_median_sd, "beta_pga_sd": b.beta_sd, "beta_convention": BETA_CONVENTION,
            "band_level": b.level, "band_cluster": b.cluster_by, "cluster_by": b.cluster_by,
            "n_clusters": b.n_clusters, "n_bootstrap": b.n_resamples, "n_bootstrap_unfitted": b.n_unfitted,
            "log_likelihood": f.log_likelihood, "n_rows": int(f.n), "n_failed": self.n_failed,
            "n_scale_warned": self.n_scale_warned, "g_m_s2": G_M_S2,
            "stripes": [{"level_g": float(x), "n_runs": int(n), "n_exceeded": int(z)}
                        for x, n, z in zip(self.levels_g, self.n_runs, self.n_exceeded)],
        }

    def report_lines(self) -> list[str]:
        f, b = self.fit, self.band
        pct = f"{100 * b.level:g} %"
        lines = [f"limit state: {self.limit_state_words}",
                 f"{FIT_WORDS}: median PGA {f.median:.4g} g ({f.median * G_M_S2:.4g} m/s2), beta {f.beta:.3f} "
                 f"({f.n} runs at {self.levels_g.size} levels)",
                 f"{pct} band of the median: {b.median_low:.4g} to {b.median_high:.4g} g; of beta: {b.beta_low:.3f} "
                 f"to {b.beta_high:.3f} ({band_words(b)})",
                 "stripes (exceeded / runs): " + ", ".join(f"{x:.4g} g {z}/{n}" for x, n, z in
                                                            zip(self.levels_g, self.n_runs, self.n_exceeded)),
                 BETA_CONVENTION]
        if self.n_failed:
            lines.append(f"warning: {self.n_failed} runs stopped with an error (column failed = 1): left out")
        if self.n_scale_warned:
            lines.append(f"warning: {self.n_scale_warned} runs scaled their record beyond {SCALE_WARN[1]:g} or below "
                         f"{SCALE_WARN[0]:g} (the record then stands for another earthquake than the one recorded)")
        return lines


def msa_fragility_data(msa: MsaResult, n_bootstrap: int = 400, seed: int = 20261124, limit_state: str = "collapse",
                       threshold_mm: float | None = None) -> MsaFragilityData:
    """The stripes of ``msa`` for ``limit_state`` (:meth:`MsaResult.exceeded`), Baker's
    fit and its band clustered by record (or event); FitError when the stripes cannot be
    fitted (its message names the levels)."""
    used = msa.used
    exceeded, words = msa.exceeded(limit_state, threshold_mm)
    x, n, z = stripes_of(msa.level_g[used], exceeded[used])
    verbs = ("collapsed", "stood") if limit_state == "collapse" else ("exceeded it", "stayed short of it")
    try:
        fit = fit_stripes(x, n, z, unit="g", verbs=verbs)
    except FitError as exc:
        raise FitError(f"limit state {words}: {exc}") from None
    grid = np.linspace(0.0, 1.15 * max(float(x.max()), fit.median), 300)[1:]
    clusters, events, cluster_by = msa.bootstrap_clusters()
    band = stripes_band(msa.level_g[used], exceeded[used], grid, np.asarray(clusters)[used],
                        None if events is None else np.asarray(events)[used], cluster_by,
                        n_resamples=n_bootstrap, seed=seed)
    warned = int(np.sum((msa.scale > SCALE_WARN[1]) | (msa.scale < SCALE_WARN[0])))
    table = ReportTable(["level_g", "level_m_s2", "n_runs", "n_exceeded", "fraction_exceeded", "p_fit"],
                        [(float(xj), float(xj * G_M_S2), int(nj), int(zj), float(zj / nj),
                          float(fragility(xj, fit.median, fit.beta))) for xj, nj, zj in zip(x, n, z)],
                        title="stripes")
    curve = ReportTable(["pga_g", "pga_m_s2", "p_collapse", "p_low", "p_high"],
                        [(float(g), float(g * G_M_S2), float(p), float(lo), float(hi)) for g, p, lo, hi in
                         zip(grid, fragility(grid, fit.median, fit.beta), band.low, band.high)])
    return MsaFragilityData(x, n, z, fit, band, msa.n_failed, warned, limit_state, words,
                            None if limit_state == "collapse" else threshold_mm, table=table, curve_table=curve)


def plot_msa_fragility(msa: MsaResult, out_png: str | os.PathLike, n_bootstrap: int = 400, seed: int = 20261124,
                       limit_state: str = "collapse", threshold_mm: float | None = None) -> MsaFragilityData:
    """Fit the stripes of ``msa`` (:func:`msa_fragility_data`) and draw them to ``out_png``."""
    data = msa_fragility_data(msa, n_bootstrap, seed, limit_state, threshold_mm)
    fit, band = data.fit, data.band
    fig = new_figure(8.0, 6.4)
    ax = fig.subplots()
    ax.fill_between(band.im, band.low, band.high, color="tab:blue", alpha=0.2, linewidth=0)
    ax.plot(band.im, fragility(band.im, fit.median, fit.beta), "-", color="tab:blue", linewidth=2)
    ax.plot(data.levels_g, data.n_exceeded / data.n_runs, "o", color="black", markersize=6)
    for x, n, z in zip(data.levels_g, data.n_runs, data.n_exceeded):
        ax.annotate(f"{z}/{n}", (x, z / n), textcoords="offset points", xytext=(6, -10), fontsize=8)
    ax.axvline(fit.median, color="0.45", linewidth=0.8)
    ax.set_xlim(0.0, band.im[-1])
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("PGA level of the scaled records [g]")
    ax.set_ylabel("probability of collapse" if limit_state == "collapse" else f"probability of {limit_state}")
    top = ax.secondary_xaxis("top", functions=(lambda g: g * G_M_S2, lambda a: a / G_M_S2))
    top.set_xlabel("PGA [m/s²]")
    ax.grid(True, alpha=0.3)
    pct = int(round(100 * band.level))
    clustered = {"record": f"{band.n_clusters} records, clustered by record",
                 "event": f"{band.n_clusters} events, clustered by event"}.get(band.cluster_by, "runs")
    handles = [
        Line2D([], [], color="tab:blue", linewidth=2,
               label=f"binomial fit (Baker 2015): median {fit.median:.3g} g, beta {fit.beta:.2f}"),
        Patch(color="tab:blue", alpha=0.2, label=f"{pct} % bootstrap band ({band.n_resamples} resamples of the "
                                                  f"{clustered})"),
        Line2D([], [], color="black", marker="o", linestyle="none", markersize=6,
               label="stripes: fraction of the runs exceeding the limit state at each level (exceeded/runs beside)"),
        Line2D([], [], color="0.45", linewidth=0.8, label="median: 50 % probability"),
    ]
    if data.n_scale_warned:  # where the figure is read, not only in its small print
        handles.append(warning_entry(f"warning: {data.n_scale_warned} of {int(data.n_runs.sum())} runs scaled their "
                                     f"record beyond {SCALE_WARN[1]:g} or below {SCALE_WARN[0]:g} (the record then "
                                     f"stands for another earthquake)"))
    fig.legend(handles=handles, fontsize=8, loc="outside lower center", ncol=1, borderaxespad=LEGEND_PAD)
    fig.suptitle(f"MSA fragility, {data.limit_state_words}: {len(msa.records)} records x {msa.n_sets} model samples x "
                 f"{data.levels_g.size} levels", fontsize=10)
    note = provenance(msa.code_version, os.path.basename(msa.path))
    if data.n_scale_warned:
        note = f"{data.n_scale_warned} runs scaled beyond {SCALE_WARN[1]:g} or below {SCALE_WARN[0]:g} | {note}"
    data.png_path = save_figure(fig, out_png, note=note)
    return data
