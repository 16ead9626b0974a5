"""The collapse risk at a site (``voussoir-post risk``): the hazard curve with the
fragility, and the disaggregation of the mean annual frequency of collapse over PGA."""

from __future__ import annotations

import numpy as np

from .. import __version__
from ..units import G_M_S2
from .drawing import COLORS, new_figure, provenance, save_figure

__all__ = ["plot_risk"]


def plot_risk(path: str, hazard, median_g: float, beta: float, result) -> str:
    from ..earthquake.fragility import fragility

    fig = new_figure(11.0, 4.8)
    left, right = fig.subplots(1, 2)
    lo = min(hazard.pga_g[0], float(result.pga_g[0]))
    hi = max(hazard.pga_g[-1], median_g * np.exp(3.5 * beta))
    grid = np.geomspace(max(lo, 1e-3), hi, 400)
    left.loglog(grid, hazard.rate(grid), color=COLORS[0], lw=1.2, label="hazard: annual rate of exceedance "
                "(log-log between the file's points)")
    left.loglog(hazard.pga_g, hazard.annual_rate, "o", color=COLORS[0], ms=4, label="hazard file's points")
    left.set_xlabel("PGA [g]")
    left.set_ylabel("mean annual frequency of exceedance [1/yr]")
    twin = left.twinx()
    twin.plot(grid, fragility(grid, median_g, beta), color=COLORS[1], lw=1.5,
              label=f"fragility: lognormal, median {median_g:.3g} g, beta {beta:.3g}")
    twin.set_ylim(0, 1.02)
    twin.set_ylabel("probability of collapse")
    left.set_title("The site's hazard and the arch's fragility", fontsize=10)
    handles = left.get_legend_handles_labels()[0] + twin.get_legend_handles_labels()[0]
    left.legend(handles, [h.get_label() for h in handles], fontsize=7, loc="upper center",
                bbox_to_anchor=(0.5, -0.14))
    # Disaggregation: the density of lambda_c over ln PGA (its share per unit of ln PGA).
    share = result.density * result.pga_g / result.annual_rate
    right.plot(result.pga_g, share, color=COLORS[2], lw=1.5,
               label="share of the collapse rate per unit of ln PGA\n(fragility density x hazard rate)")
    right.axvline(median_g, color=COLORS[1], ls="--", lw=1, label=f"fragility median {median_g:.3g} g")
    mode = float(result.pga_g[int(np.argmax(share))])
    right.axvline(mode, color=COLORS[2], ls=":", lw=1, label=f"where collapses come from most: {mode:.3g} g")
    right.set_xscale("log")
    right.set_xlim(median_g * np.exp(-5 * beta), median_g * np.exp(5 * beta))
    right.set_xlabel("PGA [g]")
    right.set_ylabel("density of the collapse rate over ln PGA [-]")
    right.set_title(f"Disaggregation: {result.annual_rate:.3g} collapses per year, "
                    f"P(50 yr) = {result.p_50yr:.3g}", fontsize=10)
    secondary = right.secondary_xaxis("top", functions=(lambda g: g * G_M_S2, lambda a: a / G_M_S2))
    secondary.set_xlabel("PGA [m/s2]", fontsize=8)
    right.set_ylim(0, 1.5 * float(np.max(share)))  # room for the legend above the curve
    right.legend(fontsize=7, loc="upper left")
    fig.suptitle("Collapse risk at the site: the fragility integrated with the hazard curve", fontsize=11)
    save_figure(fig, path, note=provenance(f"voussoir-post {__version__}", hazard.source))
    return path
