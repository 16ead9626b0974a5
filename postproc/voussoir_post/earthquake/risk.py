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
from pathlib import Path

import numpy as np

from ..errors import InputError

__all__ = ["HazardCurve", "read_hazard", "RiskResult", "collapse_risk", "power_law_rate"]


@dataclass(frozen=True)
class HazardCurve:
    """A site's hazard: PGA [g] and the mean annual frequency of its exceedance [1/yr]."""

    pga_g: np.ndarray
    annual_rate: np.ndarray
    source: str = ""

    def rate(self, pga_g) -> np.ndarray:
        """lambda(im), log-log interpolated, the end intervals' power laws beyond the ends."""
        x, y = np.log(self.pga_g), np.log(self.annual_rate)
        q = np.log(np.asarray(pga_g, float))
        k = np.clip(np.searchsorted(x, q) - 1, 0, x.size - 2)
        slope = (y[k + 1] - y[k]) / (x[k + 1] - x[k])
        return np.exp(y[k] + slope * (q - x[k]))


def read_hazard(path: str | Path) -> HazardCurve:
    """A hazard curve as CSV: columns `pga_g` and `annual_rate` (mean annual frequency of
    exceedance, 1/yr), one header row, `#` comments; at least two rows, PGA increasing and
    positive, rates positive and decreasing."""
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: no such hazard file")
    lines = [(n, line.strip()) for n, line in enumerate(path.read_text().splitlines(), 1)
             if line.strip() and not line.lstrip().startswith("#")]
    if not lines:
        raise InputError(f"{path}: empty hazard file")
    header = [c.strip() for c in lines[0][1].split(",")]
    for name in ("pga_g", "annual_rate"):
        if name not in header:
            raise InputError(f"{path}:{lines[0][0]}: missing column '{name}' (header has: {', '.join(header)})")
    ia, ir = header.index("pga_g"), header.index("annual_rate")
    pga, rate = [], []
    for n, line in lines[1:]:
        cells = [c.strip() for c in line.split(",")]
        try:
            a, r = float(cells[ia]), float(cells[ir])
        except (ValueError, IndexError):
            raise InputError(f"{path}:{n}: pga_g and annual_rate must be numbers: '{line}'") from None
        if not (a > 0 and r > 0 and math.isfinite(a) and math.isfinite(r)):
            raise InputError(f"{path}:{n}: pga_g and annual_rate must be positive: '{line}'")
        pga.append(a)
        rate.append(r)
    if len(pga) < 2:
        raise InputError(f"{path}: a hazard curve needs at least two rows")
    pga_a, rate_a = np.array(pga), np.array(rate)
    if np.any(np.diff(pga_a) <= 0) or np.any(np.diff(rate_a) >= 0):
        raise InputError(f"{path}: pga_g must increase and annual_rate decrease from row to row")
    return HazardCurve(pga_a, rate_a, str(path))


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
