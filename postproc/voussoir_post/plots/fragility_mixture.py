"""The calibrated fragility as a mixture of its model samples (issue 36, item 2): the figure,
table and words of :mod:`voussoir_post.earthquake.mixture` for an IDA of several model samples.

The samples' strata (model and weight of each param_set) come from the stratified samples
file the IDA played (`voussoir-post samples`; the HDF5 file's &sweep model_samples_file,
looked for beside it, or given), checked against the IDA's own parameter values; without one
every sample weighs the same and no model's curve is drawn.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ..diagnosis.strata import STRATUM_PREFIX, Strata, read_strata
from ..earthquake.ida import IdaResult
from ..earthquake.mixture import GOF_LEVEL, PERCENTILES, MixtureFragility, mixture_fragility
from ..errors import InputError
from ..tables import ReportTable
from ..units import G_M_S2
from .drawing import legend_pad, new_figure, provenance, save_figure, wrap_text
from .fragility_plot import arch_words, records_words, two_line_title

__all__ = ["MixtureData", "find_strata", "mixture_data", "plot_mixture"]

_MODEL_COLOURS = ("tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown", "tab:pink", "tab:olive",
                  "tab:cyan", "tab:gray")


def find_strata(ida: IdaResult, path: str | None = None) -> tuple[Strata | None, str]:
    """(the strata of the IDA's samples, a note): from ``path``, else from the IDA's
    &sweep model_samples_file beside its file; None (and why) when there is none or it has no
    stratum lines. InputError when a stratified file disagrees with the IDA's samples."""
    given = path is not None
    if not given:
        name = str(ida.config.get("sweep", {}).get("model_samples_file", "") or "").strip()
        if not name:
            return None, "the IDA's samples are not from a file: equal weights"
        path = name if os.path.isabs(name) else os.path.join(os.path.dirname(os.path.abspath(ida.path)), name)
        if not os.path.exists(path):
            return None, f"its samples file {name} is not beside the IDA: equal weights, no model curves"
        with open(path, encoding="utf-8-sig") as f:
            if not any(line.startswith(STRATUM_PREFIX) for line in f):
                return None, (f"its samples file {os.path.basename(path)} is not stratified (voussoir-post samples): "
                              f"equal weights")
    strata = read_strata(path)
    sets = sorted(set(ida.param_set.tolist()))
    if sets[-1] >= len(strata.models):
        raise InputError(f"{path}: {len(strata.models)} sample rows, but the IDA {ida.path} has param_set {sets[-1]}")
    for name, values in ida.parameters.items():
        if name in strata.values:
            want = strata.values[name][ida.param_set]
            if not np.allclose(values, want, rtol=1e-9, atol=1e-12):
                k = int(np.argmax(~np.isclose(values, want, rtol=1e-9, atol=1e-12)))
                raise InputError(f"{path}: sample {ida.param_set[k]} has {name} = {want[k]!r}, the IDA {ida.path} "
                                 f"played {values[k]!r}: not the samples of this IDA")
    return strata, f"strata from {os.path.basename(path)}"


@dataclass
class MixtureData:
    mixture: MixtureFragility
    note: str  #: where the weights came from
    png_path: str | None = None
    table: ReportTable | None = None

    def single_sample_models(self) -> list[str]:
        """The models with one sample (whose resampling adds nothing to the band)."""
        models = self.mixture.fits.models
        return [] if models is None else [m for m in dict.fromkeys(models) if models.count(m) == 1]

    def summary(self) -> dict:
        """For --json: the key 'mixture'."""
        mx, f = self.mixture, self.mixture.fits
        c = mx.check
        return {"mixture": {
            "median_pga_g": mx.median / G_M_S2,
            "median_pga_g_band": [mx.band.median_low / G_M_S2, mx.band.median_high / G_M_S2],
            "band_level": mx.band.level, "n_bootstrap": mx.band.n_resamples,
            "n_bootstrap_unfitted": mx.band.n_unfitted,
            "ln_median_sd": mx.band.ln_median_sd,
            "band": "two-stage bootstrap: the events with their records, and the model samples within their models",
            "models_with_one_sample": self.single_sample_models(),
            "weights_from": self.note,
            "sample_param_set": f.samples.tolist(), "sample_model": f.models,
            "sample_weight": f.weights.tolist(), "sample_median_pga_g": (f.medians / G_M_S2).tolist(),
            "sample_beta_pga": f.betas.tolist(),
            "model_median_pga_g": {m: v / G_M_S2 for m, v in mx.model_medians().items()},
            "p_collapse_percentiles_at_median": {f"{q:g}": float(np.interp(mx.median, mx.im, curve))
                                                  for q, curve in mx.percentiles.items()},
            "pooled_median_pga_g": mx.pooled.median / G_M_S2, "pooled_beta_pga": mx.pooled.beta,
            "pooled_gof_statistic": c.statistic, "pooled_gof_p_table": c.p_table, "pooled_gof_p_calibrated": c.p_value,
            "pooled_gof_n_simulations": c.n_simulations, "pooled_gof_rho_record": c.rho_record,
            "pooled_gof_rho_event": c.rho_event, "pooled_gof_rho_sample": c.rho_sample,
            "pooled_holds": c.holds, "gof_level": GOF_LEVEL,
            "to_use": "pooled lognormal" if c.holds else "mixture",
            "bootstrap_draws": [{"median_pga_g": (m / G_M_S2).tolist(), "beta_pga": b.tolist(), "weight": w.tolist()}
                                for m, b, w in mx.band.draws],
        }}

    def report_lines(self) -> list[str]:
        mx, f, c = self.mixture, self.mixture.fits, self.mixture.check
        pct = int(round(100 * mx.band.level))
        single = self.single_sample_models()
        lines = [f"mixture of the {f.samples.size} model samples ({self.note}): PGA median {mx.median / G_M_S2:.4g} g, "
                 f"{pct} % band [{mx.band.median_low / G_M_S2:.4g}, {mx.band.median_high / G_M_S2:.4g}] g "
                 f"(two-stage bootstrap, {mx.band.n_resamples} resamples of the {mx.band.n_clusters} "
                 f"{mx.band.cluster_by}s with their records, and of the samples within their models"
                 + (f", {mx.band.n_unfitted} more could not be fitted" if mx.band.n_unfitted else "")
                 + f"; sd of ln median {mx.band.ln_median_sd:.3f})"]
        if single:
            lines.append(f"  {len(single)} of the {len(set(f.models))} models have one sample ({', '.join(single)}): "
                         f"resampling it changes nothing, so the band carries none of their own samples' error (a "
                         f"model's parameters within it); more samples per model carry it")
        if f.models is not None:
            counts = {m: f.models.count(m) for m in dict.fromkeys(f.models)}
            lines.append("  each model's own curve, median: " + "; ".join(
                f"{m} {v / G_M_S2:.3g} g ({counts[m]} sample{'s' if counts[m] != 1 else ''}, weight "
                f"{f.weights[np.array(f.models) == m].sum():.3f})" for m, v in mx.model_medians().items()))
        lines.append(f"  the samples' medians {np.min(f.medians) / G_M_S2:.3g}-{np.max(f.medians) / G_M_S2:.3g} g, "
                     f"betas {np.min(f.betas):.3f}-{np.max(f.betas):.3f}; at the mixture's median the samples' "
                     + ", ".join(f"{100 * q:g} %" for q in mx.percentiles) + " percentiles of P(collapse) are "
                     + ", ".join(f"{float(np.interp(mx.median, mx.im, v)):.2f}" for v in mx.percentiles.values()))
        verdict = (f"holds (p >= {GOF_LEVEL:g}): it may stand for the mixture" if c.holds else
                   f"rejected (p < {GOF_LEVEL:g}): use the mixture, not the pooled lognormal")
        lines.append(f"pooled lognormal (median {mx.pooled.median / G_M_S2:.4g} g, beta {mx.pooled.beta:.3f}): "
                     f"goodness of fit KS D = {c.statistic:.3f}, p {c.p_value:.3g} calibrated by {c.n_simulations} "
                     f"simulations of the fitted lognormal clustered by event, record and sample as the rows "
                     f"(correlations: record {c.rho_record:.2f}, event {c.rho_event:.2f}, sample "
                     f"{c.rho_sample:.2f}), against {c.p_table:.3g} "
                     f"from the KS table; {verdict}")
        return lines


def mixture_data(ida: IdaResult, n_bootstrap: int = 400, seed: int = 20261124, strata_path: str | None = None,
                 n_simulations: int = 400, im_max: float | None = None) -> MixtureData:
    """The PGA mixture of ``ida``'s model samples (needs at least two)."""
    strata, note = find_strata(ida, strata_path)
    low, high = ida.intensity_brackets("pga")
    clusters, events, cluster_by = ida.bootstrap_clusters()
    finite = np.where(np.isfinite(high), high, low)
    top = im_max or 1.15 * float(np.nanmax(finite))
    grid = np.linspace(top / 400.0, top, 400)
    scale_max = ida.config.get("sweep", {}).get("scale_max")
    censor = (ida.unit_pga_m_s2 * float(scale_max) if isinstance(scale_max, (int, float))
              else np.full(ida.n_rows, np.inf))
    weights = models = None
    if strata is not None:
        weights = {s: float(strata.weights[s]) for s in set(ida.param_set.tolist())}
        models = {s: strata.models[s] for s in set(ida.param_set.tolist())}
    mixture = mixture_fragility(low, high, ida.param_set, grid, clusters, events, cluster_by, weights, models, censor,
                                n_bootstrap=n_bootstrap, n_simulations=n_simulations, seed=seed,
                                strata_source=strata.path if strata else "")
    rows = [(float(x / G_M_S2), float(x), float(p), float(lo), float(hi))
            + tuple(float(mixture.percentiles[q][k]) for q in mixture.percentiles)
            + tuple(float(c[k]) for c in mixture.models.values())
            for k, (x, p, lo, hi) in enumerate(zip(grid, mixture.curve, mixture.band.low, mixture.band.high))]
    table = ReportTable(["pga_g", "pga_m_s2", "p_mixture", "p_low", "p_high"]
                        + [f"p_samples_q{q:g}" for q in mixture.percentiles]
                        + [f"p_model_{m}" for m in mixture.models], rows,
                        title=f"the mixture of the model samples against PGA ({note}); p_low, p_high: its "
                              f"{int(round(100 * mixture.band.level))} % two-stage bootstrap band; p_samples_q: "
                              f"percentiles over the samples' curves; p_model_: each model's own curve")
    return MixtureData(mixture, note, None, table)


def plot_mixture(ida: IdaResult, out_png: str | os.PathLike, n_bootstrap: int = 400, seed: int = 20261124,
                 strata_path: str | None = None) -> MixtureData:
    """The mixture, its band, the samples' percentile curves, each model's curve, the
    samples' own curves (thin) and the pooled lognormal (dashed, said rejected when its
    calibrated fit fails), against PGA in g (m/s2 on the top axis)."""
    data = mixture_data(ida, n_bootstrap, seed, strata_path)
    mx, f, c = data.mixture, data.mixture.fits, data.mixture.check
    x = mx.im / G_M_S2
    fig = new_figure(10.0, 7.8)
    ax = fig.subplots(1, 1)
    # each sample's own curve, unless every model has one sample (its model's curve is the sample's)
    own = f.models is None or any(f.models.count(m) > 1 for m in set(f.models))
    if own:
        for m, b in zip(f.medians, f.betas):
            ax.plot(x, _lognormal(mx.im, m, b), color="0.75", linewidth=0.6, zorder=1)
    ax.fill_between(x, mx.band.low, mx.band.high, color="tab:blue", alpha=0.2, linewidth=0, zorder=2)
    q_low, q_high = (mx.percentiles[q] for q in PERCENTILES)
    ax.plot(x, q_low, ":", color="black", linewidth=1.4, zorder=6)
    ax.plot(x, q_high, ":", color="black", linewidth=1.4, zorder=6)
    handles = [Line2D([], [], color="tab:blue", linewidth=2.5,
                      label=f"mixture of the {f.samples.size} model samples (weighted mean of their curves): median "
                            f"{mx.median / G_M_S2:.3g} g ({mx.median:.3g} m/s²)"),
               Patch(color="tab:blue", alpha=0.2,
                     label=f"its {int(round(100 * mx.band.level))} % band: {mx.band.n_resamples} two-stage bootstrap "
                           f"resamples (the {mx.band.n_clusters} {mx.band.cluster_by}s with their records, and the "
                           f"samples within their models)"),
               Line2D([], [], color="black", linestyle=":", linewidth=1.4,
                      label=f"{100 * PERCENTILES[0]:g} % and {100 * PERCENTILES[1]:g} % of the samples' curves "
                            f"(weighted, at each PGA)")]
    if own:
        handles.append(Line2D([], [], color="0.75", linewidth=0.6,
                              label="each model sample's own lognormal (its rows alone)"))
    for k, (m, curve) in enumerate(mx.models.items()):
        colour = _MODEL_COLOURS[k % len(_MODEL_COLOURS)]
        ax.plot(x, curve, color=colour, linewidth=1.3, zorder=4)
        n_m = f.models.count(m)
        handles.append(Line2D([], [], color=colour, linewidth=1.3,
                              label=f"model {m}: {n_m} sample{'s' if n_m != 1 else ''}, weight "
                                    f"{f.weights[np.array(f.models) == m].sum():.2f}, median "
                                    f"{data.mixture.model_medians()[m] / G_M_S2:.3g} g"))
    ax.plot(x, mx.curve, color="tab:blue", linewidth=2.5, zorder=5)
    ax.plot(x, _lognormal(mx.im, mx.pooled.median, mx.pooled.beta), "--", color="black", linewidth=1.2, zorder=5)
    handles.append(Line2D([], [], color="black", linestyle="--", linewidth=1.2,
                          label=f"pooled lognormal of all rows: median {mx.pooled.median / G_M_S2:.3g} g, beta "
                                f"{mx.pooled.beta:.2f}; goodness of fit p {c.p_value:.2g} (calibrated) "
                                + ("holds" if c.holds else f"< {GOF_LEVEL:g}: rejected, not for use")))
    ax.set_xlim(0.0, x[-1])
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("PGA of the scaled record [g]")
    ax.set_ylabel("probability of collapse")
    top = ax.secondary_xaxis("top", functions=(lambda g: g * G_M_S2, lambda a: a / G_M_S2))
    top.set_xlabel("PGA [m/s²]")
    ax.grid(True, alpha=0.3)
    fig.legend(handles, [wrap_text(h.get_label(), 9.4, 8.0) for h in handles], fontsize=8,
               loc="outside lower center", ncol=1, borderaxespad=legend_pad(8.0))
    fig.suptitle(two_line_title(f"Probability of collapse of the {arch_words(ida)}: mixture of {f.samples.size} "
                                f"model samples", f"under {records_words(ida)}", 9.8,
                                second_short=f"under {len(ida.records)} ground-motion records"), fontsize=10)
    note = provenance(getattr(ida, "code_version", ""), os.path.basename(ida.path))
    data.png_path = save_figure(fig, out_png, note=f"{data.note} | {note}")
    return data


def _lognormal(im, median, beta):
    from ..earthquake.fragility import fragility
    return fragility(im, median, beta)

