"""Collapse risk at a site: a lognormal fragility integrated with the site's hazard curve.

The hazard curve gives the mean annual frequency lambda(im) with which the intensity
measure (here PGA, in g) is exceeded at the site. The mean annual frequency of collapse
is the total probability over intensity,

    lambda_c = integral P(C | im) |d lambda / d im| d im = integral f(im) lambda(im) d im,

f the fragility's lognormal density (the second form by parts: P(C | 0) = 0 and lambda
vanishes at large im). Between the hazard file's points lambda is interpolated linearly in
log-log (a power law on each interval, as hazard curves are drawn); beyond its ends the
end intervals' power laws are extended (the report says how much of lambda_c comes from
there). The probability of collapse in T years is 1 - exp(-lambda_c T) (Poisson), and the
collapse margin ratio of FEMA P695 is the fragility's median over the maximum considered
earthquake's intensity.

Checked against the closed form for a power-law hazard lambda(im) = k0 im^-k and a
lognormal fragility of median m and dispersion beta (Cornell et al. 2002):
lambda_c = k0 m^-k exp(k^2 beta^2 / 2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .hazard import HazardCurve, HazardSet, read_hazard, read_hazard_set

__all__ = ["HazardCurve", "HazardSet", "read_hazard", "read_hazard_set", "RiskResult", "collapse_risk",
           "power_law_rate"]


@dataclass
class RiskResult:
    """The collapse risk of a lognormal fragility at a site."""

    annual_rate: float  #: mean annual frequency of collapse [1/yr]
    p_50yr: float  #: probability of collapse in 50 years
    years: float
    p_years: float  #: probability of collapse in `years`
    margin_ratio: float | None  #: median / the MCE's PGA (FEMA P695's CMR), None without one
    beyond_fraction: float  #: share of the rate from intensities outside the hazard file's range
    pga_g: np.ndarray  #: the integration grid [g]
    density: np.ndarray  #: the rate's density over PGA [1/yr per g]: its disaggregation


def collapse_risk(hazard: HazardCurve, median_g: float, beta: float, years: float = 50.0,
                  mce_g: float | None = None, points: int = 4001) -> RiskResult:
    """lambda_c, the probability in `years` (and in 50) and the margin ratio."""
    if not (median_g > 0 and beta > 0):
        raise InputError(f"a lognormal fragility needs median > 0 and beta > 0 (median {median_g}, beta {beta})")
    if years <= 0:
        raise InputError(f"--years must be > 0 (got {years})")
    z = np.linspace(-8.0, 8.0, points)
    ln_im = math.log(median_g) + beta * z
    im = np.exp(ln_im)
    pdf_ln = np.exp(-0.5 * z * z) / (beta * math.sqrt(2.0 * math.pi))  # density over ln im
    integrand = pdf_ln * hazard.rate(im)
    total = float(np.trapezoid(integrand, ln_im))
    outside = (im < hazard.pga_g[0]) | (im > hazard.pga_g[-1])
    beyond = float(np.trapezoid(np.where(outside, integrand, 0.0), ln_im)) / total if total > 0 else 0.0
    p = lambda t: -math.expm1(-total * t)
    return RiskResult(total, p(50.0), years, p(years), None if mce_g is None else median_g / mce_g, beyond,
                      im, integrand / im)


def power_law_rate(k0: float, k: float, median_g: float, beta: float) -> float:
    """The closed form lambda_c = k0 m^-k exp(k^2 beta^2 / 2) for lambda(im) = k0 im^-k."""
    return k0 * median_g ** (-k) * math.exp(0.5 * (k * beta) ** 2)

