"""The collapse risk at a site (``voussoir-post risk``): the hazard curve (and its fractile
curves) with the fragility, and the disaggregation of the mean annual frequency of
collapse over the intensity, with the rate's band in the title."""

from __future__ import annotations

import numpy as np

from .. import __version__
from ..units import G_M_S2
from .drawing import COLORS, new_figure, provenance, save_figure, wrap_text

__all__ = ["plot_risk"]


def _band_words(band) -> str:
    """'band 16-84 %: 1.2e-05 to 4.5e-05 /yr (hazard fractiles x bootstrap)', or ''."""
    if band is None:
        return ""
    if band.combined:
        lo, hi = band.combined.get(0.16), band.combined.get(0.84)
        return f"; 16-84 %: {lo:.2g} to {hi:.2g} /yr (hazard fractiles x {band.combined_with})"
    for kind in sorted(band.fragility, key=lambda k: k != "mixture bootstrap"):
        q = band.fragility[kind]["quantiles"]
        return f"; 16-84 %: {q[0.16]:.2g} to {q[0.84]:.2g} /yr ({kind} only)"
    if band.hazard_fractiles:
        qs = sorted(band.hazard_fractiles)
        return (f"; on the {qs[0]:g} and {qs[-1]:g} hazard fractiles: {band.hazard_fractiles[qs[0]]:.2g} and "
                f"{band.hazard_fractiles[qs[-1]]:.2g} /yr")
    return ""


def plot_risk(path: str, hazard, median_g: float, beta: float, result, band=None, mixture=None) -> str:
    """`hazard`: a HazardSet (or one HazardCurve); `beta`: the dispersion the rate was
    computed with (the model-form part included); `band`: the RiskBand, if made; `mixture`:
    the model samples' lognormals (FragilityDraws) when the rate is the mixture's (`median_g`
    then the mixture's median, `beta` the pooled one, for the axes' ranges)."""
    from ..earthquake.fragility import fragility
    from ..earthquake.hazard import measure_words

    fractiles = getattr(hazard, "fractiles", {})
    mean = getattr(hazard, "mean", hazard)
    measure = measure_words(getattr(mean, "measure", "PGA"))
    fig = new_figure(11.0, 5.2)
    left, right = fig.subplots(1, 2)
    lo = min(mean.pga_g[0], float(result.pga_g[0]))
    hi = max(mean.pga_g[-1], median_g * np.exp(3.5 * beta))
    grid = np.geomspace(max(lo, 1e-3), hi, 400)
    inside = (grid >= mean.pga_g[0]) & (grid <= mean.pga_g[-1])
    left.loglog(grid[inside], mean.rate(grid[inside]), color=COLORS[0], lw=1.4,
                label="hazard: mean annual frequency of exceedance (log-log between the file's points)")
    if not inside.all():
        outside = np.where(inside, np.nan, mean.rate(grid))
        left.loglog(grid, outside, color=COLORS[0], lw=0.8, alpha=0.5,
                    label="hazard beyond the file's range: its end power laws extended")
    left.loglog(mean.pga_g, mean.annual_rate, "o", color=COLORS[0], ms=3.5, label="hazard file's points")
    for k, (q, curve) in enumerate(fractiles.items()):
        left.loglog(grid, curve.rate(grid), color=COLORS[0], lw=0.9, ls=(0, (4, 2)) if q < 0.5 else (0, (1, 1.5)),
                    alpha=0.8, label=f"hazard, {q:g} fractile")
    left.set_xlabel(f"{measure} [g]")
    left.set_ylabel("mean annual frequency of exceedance [1/yr]")
    top = left.secondary_xaxis("top", functions=(lambda g: g * G_M_S2, lambda a: a / G_M_S2))
    top.set_xlabel(f"{measure} [m/s2]", fontsize=8)
    twin = left.twinx()
    raised = (f" (fitted {band.beta_fit:.3g}, model-form {band.model_form.beta:.3g}, SRSS)"
              if band is not None and band.model_form.rated else "")
    if mixture is None:
        twin.plot(grid, fragility(grid, median_g, beta), color=COLORS[1], lw=1.5,
                  label=f"fragility: lognormal, median {median_g:.3g} g, beta {beta:.3g}{raised}")
    else:
        from ..earthquake.mixture import mixture_cdf
        form = band.model_form if band is not None else None
        betas = mixture.betas if form is None else np.array([form.total(b) for b in mixture.betas])
        twin.plot(grid, mixture_cdf(grid, mixture.medians_g, betas, mixture.draw_weights()), color=COLORS[1], lw=1.5,
                  label=f"fragility: the mixture of {mixture.medians_g.size} model samples' lognormals (the pooled "
                        f"lognormal rejected), median {median_g:.3g} g"
                        + (f", each beta raised by the model-form {form.beta:.3g} (SRSS)" if form and form.rated
                           else ""))
    twin.set_ylim(0, 1.02)
    twin.set_ylabel("probability of collapse")
    left.set_title("The site's hazard and the arch's fragility", fontsize=10)
    handles = left.get_legend_handles_labels()[0] + twin.get_legend_handles_labels()[0]
    # Labels wrapped to the panel's width: a long one (the mixture's) would widen the legend
    # past the figure's left edge.
    left.legend(handles, [wrap_text(h.get_label(), 5.0, 7) for h in handles], fontsize=7, loc="upper center",
                bbox_to_anchor=(0.5, -0.17))
    # Disaggregation: the density of lambda_c over ln IM (its share per unit of ln IM).
    share = result.density * result.pga_g / result.annual_rate
    right.plot(result.pga_g, share, color=COLORS[2], lw=1.5,
               label=f"share of the collapse rate per unit of ln {measure}\n(fragility density x hazard rate)")
    right.axvline(median_g, color=COLORS[1], ls="--", lw=1, label=f"fragility median {median_g:.3g} g"
                  + (" (the mixture's)" if mixture is not None else ""))
    mode = float(result.pga_g[int(np.argmax(share))])
    right.axvline(mode, color=COLORS[2], ls=":", lw=1, label=f"where collapses come from most: {mode:.3g} g")
    right.set_xscale("log")
    right.set_xlim(median_g * np.exp(-5 * beta), median_g * np.exp(5 * beta))
    right.set_xlabel(f"{measure} [g]")
    right.set_ylabel(f"density of the collapse rate over ln {measure} [-]")
    right.set_title(f"Disaggregation: {result.annual_rate:.3g} collapses per year,\n"
                    f"P(collapse in 50 yr) = {result.p_50yr:.3g}", fontsize=10)
    secondary = right.secondary_xaxis("top", functions=(lambda g: g * G_M_S2, lambda a: a / G_M_S2))
    secondary.set_xlabel(f"{measure} [m/s2]", fontsize=8)
    right.set_ylim(0, 1.5 * float(np.max(share)))  # room for the legend above the curve
    right.legend(fontsize=7, loc="upper left")
    fig.suptitle(f"Collapse risk at the site: the fragility integrated with the mean hazard curve\n"
                 f"mean annual frequency of collapse {result.annual_rate:.3g} /yr{_band_words(band)}", fontsize=10.5)
    save_figure(fig, path, note=provenance(f"voussoir-post {__version__}", mean.source))
    return path
