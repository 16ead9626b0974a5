"""The fragility figure and table of an IDA: collapse probability against PGA (in g,
with m/s2 on the top axis) and against PGV, each with its lognormal maximum-likelihood
fit, the bootstrap band and the IDA points (Kaplan-Meier fraction of records collapsed,
censored records marked at their lower bound)."""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ..earthquake.fragility import (FragilityBand, FragilityFit, bootstrap_band, empirical_collapse_fraction,
                                    fit_lognormal, fragility)
from ..earthquake.ida import IdaResult
from ..tables import ReportTable
from .drawing import new_figure, provenance, save_png

__all__ = ["FragilityData", "IntensityFragility", "fragility_of", "plot_fragility", "G_M_S2"]

G_M_S2 = 9.81  #: the kernel's gravity, also its g for PGA in g


@dataclass
class IntensityFragility:
    """The fragility against one intensity measure."""

    name: str  #: 'PGA' or 'PGV'
    unit: str  #: 'm/s2' or 'm/s'
    im: np.ndarray  #: per row: collapse intensity (lower bound where censored)
    censored: np.ndarray
    fit: FragilityFit
    band: FragilityBand


@dataclass
class FragilityData:
    """What :func:`plot_fragility` drew and printed."""

    pga: IntensityFragility
    pgv: IntensityFragility
    png_path: str | None = None
    table: ReportTable = field(default_factory=lambda: ReportTable([]))
    curve_table: ReportTable = field(default_factory=lambda: ReportTable([]))

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
            "band_level": b.level, "n_bootstrap": b.n_resamples,
            "n_rows": f.n, "n_censored": f.n_censored, "g_m_s2": G_M_S2,
        }

    def report_lines(self) -> list[str]:
        """The fits in words: the median and beta of PGA and PGV with their bands, the rows."""
        summary = self.summary()
        pga, pgv = self.pga, self.pgv
        pct = int(round(100 * pga.band.level))
        return [
            f"PGA: median {summary['median_pga_g']:.4g} g ({pga.fit.median:.4g} m/s2), {pct} % band "
            f"[{summary['median_pga_g_band'][0]:.4g}, {summary['median_pga_g_band'][1]:.4g}] g; "
            f"beta {pga.fit.beta:.3f} [{pga.band.beta_low:.3f}, {pga.band.beta_high:.3f}]",
            f"PGV: median {pgv.fit.median:.4g} m/s, {pct} % band [{pgv.band.median_low:.4g}, "
            f"{pgv.band.median_high:.4g}] m/s; beta {pgv.fit.beta:.3f} [{pgv.band.beta_low:.3f}, "
            f"{pgv.band.beta_high:.3f}]",
            f"{pga.fit.n} rows, {pga.fit.n_censored} censored (no collapse up to scale_max)",
        ]


def fragility_of(name: str, unit: str, im, censored, n_bootstrap: int, seed: int) -> IntensityFragility:
    fit = fit_lognormal(im, censored)
    grid = np.linspace(0.0, 1.15 * np.max(im), 300)[1:]
    band = bootstrap_band(im, censored, grid, n_resamples=n_bootstrap, seed=seed)
    return IntensityFragility(name, unit, np.asarray(im, float), np.asarray(censored, bool), fit, band)


def _title(ida: IdaResult) -> str:
    arch = ida.config.get("arch", {})
    if arch.get("embrace_deg") is not None:
        what = (f"{arch.get('embrace_deg'):g}-degree arch of {arch.get('n_voussoirs')} voussoirs "
                f"(r_ext {arch.get('r_ext_m')} m, t {arch.get('thickness_m')} m)")
    else:
        what = os.path.basename(ida.path)
    return (f"Probability of collapse of the {what}\nunder {len(ida.records)} scaled ground-motion records "
            f"x {ida.n_sets} model sample(s): {ida.n_rows} IDA rows, {int(ida.censored.sum())} without collapse "
            "up to scale_max")


def _draw(ax, frag: IntensityFragility, scale: float, unit_label: str, unit: str) -> list:
    """One panel; `scale` turns the IM into the axis `unit`."""
    band, fit = frag.band, frag.fit
    x = band.im / scale
    ax.fill_between(x, band.low, band.high, color="tab:blue", alpha=0.2, linewidth=0)
    ax.plot(x, fragility(band.im, fit.median, fit.beta), "-", color="tab:blue", linewidth=2)
    xs, ps = empirical_collapse_fraction(frag.im, frag.censored)
    ax.plot(xs / scale, ps, "o", color="black", markersize=4)
    if frag.censored.any():
        ax.plot(frag.im[frag.censored] / scale, np.full(frag.censored.sum(), 0.02), ">", color="tab:red",
                markersize=7, linestyle="none")
    ax.axvline(fit.median / scale, color="tab:blue", linestyle=":", linewidth=1)
    ax.set_xlim(0.0, band.im[-1] / scale)
    ax.set_ylim(-0.02, 1.02)
    ax.set_ylabel("probability of collapse")
    ax.set_xlabel(unit_label)
    ax.grid(True, which="both", alpha=0.3)
    pct = int(round(100 * band.level))
    censored = [Line2D([], [], color="tab:red", marker=">", linestyle="none", markersize=7,
                       label="no collapse up to scale_max: lower bound of the collapse intensity")]
    return [
        Line2D([], [], color="tab:blue", linewidth=2,
               label=f"lognormal fit by maximum likelihood: median {fit.median / scale:.3g} {unit}, "
                     f"beta {fit.beta:.2f}"),
        Patch(color="tab:blue", alpha=0.2, label=f"{pct} % bootstrap band ({band.n_resamples} resamples of the rows)"),
        Line2D([], [], color="black", marker="o", linestyle="none", markersize=4,
               label="IDA points: fraction of records collapsed at or below (Kaplan-Meier)"),
        Line2D([], [], color="tab:blue", linestyle=":", label="median: 50 % probability of collapse"),
    ] + (censored if frag.censored.any() else [])


def plot_fragility(ida: IdaResult, out_png: str | os.PathLike, n_bootstrap: int = 400,
                   seed: int = 20261124) -> FragilityData:
    """Fit the PGA and PGV fragilities of ``ida`` and draw them to ``out_png``."""
    pga = fragility_of("PGA", "m/s2", ida.pga_m_s2, ida.censored, n_bootstrap, seed)
    pgv = fragility_of("PGV", "m/s", ida.pgv_m_s, ida.censored, n_bootstrap, seed + 1)

    fig = new_figure(12.0, 6.6)
    ax_a, ax_v = fig.subplots(1, 2)
    handles = _draw(ax_a, pga, G_M_S2, "PGA of the scaled record [g]", "g")
    top = ax_a.secondary_xaxis("top", functions=(lambda g: g * G_M_S2, lambda a: a / G_M_S2))
    top.set_xlabel("PGA [m/s²]")
    ax_a.set_title("against peak ground acceleration", fontsize=10)
    handles_v = _draw(ax_v, pgv, 1.0, "PGV of the scaled record [m/s]", "m/s")
    ax_v.set_title("against peak ground velocity", fontsize=10)
    handles[0].set_label("PGA: " + handles[0].get_label())
    handles_v[0].set_label("PGV: " + handles_v[0].get_label())
    fig.legend(handles=[handles[0], handles_v[0]] + handles[1:], fontsize=8, loc="outside lower center", ncol=2)
    fig.suptitle(_title(ida), fontsize=10)
    png = save_png(fig, out_png, note=provenance(getattr(ida, "code_version", ""), os.path.basename(ida.path)))

    rows = []
    for k in range(ida.n_rows):
        rows.append((ida.record[k] if len(ida.record[k]) < 48 else "..." + ida.record[k][-45:],
                     int(ida.param_set[k]), float(ida.scale_stood[k]), float(ida.scale_threshold[k]),
                     float(ida.pga_m_s2[k] / G_M_S2), float(ida.pga_m_s2[k]), float(ida.pgv_m_s[k]),
                     bool(ida.censored[k])))
    table = ReportTable(["record", "param_set", "scale_stood", "scale_threshold", "pga_threshold_g",
                         "pga_threshold_m_s2", "pgv_threshold_m_s", "censored"], rows,
                        title=f"IDA points of {ida.path}")
    curve = ReportTable(["pga_g", "pga_m_s2", "p_collapse", "p_low", "p_high"],
                        [(float(x / G_M_S2), float(x), float(p), float(lo), float(hi)) for x, p, lo, hi in
                         zip(pga.band.im, fragility(pga.band.im, pga.fit.median, pga.fit.beta), pga.band.low,
                             pga.band.high)],
                        title="fragility against PGA")
    return FragilityData(pga, pgv, png, table, curve)
