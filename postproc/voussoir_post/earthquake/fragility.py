"""Lognormal fragility of collapse, fitted by maximum likelihood to the collapse
intensities of an incremental dynamic analysis.

Each record (on each sampled model) brings the arch down at an intensity IM_c (PGA or
PGV of the scaled record); the fragility is the distribution of IM_c:

    P(collapse | IM) = P(IM_c <= IM) = Phi(ln(IM / median) / beta).

With ln IM_c normal (mu = ln median, sigma = beta), the log-likelihood of n exact
intensities x_i and m censored ones (records that never brought the arch down, known
only to exceed c_j, their intensity at the largest scale tried) is

    sum_i [ln phi((ln x_i - mu) / beta) - ln beta - ln x_i] + sum_j ln(1 - Phi((ln c_j - mu) / beta)).

Without censoring its maximum is closed-form, median = exp(mean ln x) and beta = the
standard deviation of ln x (ddof 0); with censoring it is found numerically
(Nelder-Mead on (mu, ln beta), from the closed form of all intensities). The band is a
bootstrap over the rows (records x models), refitted, pointwise percentiles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import FitError

__all__ = ["FitError", "FragilityFit", "FragilityBand", "fit_lognormal", "max_likelihood", "log_likelihood",
           "fragility", "bootstrap_band", "normal_cdf", "empirical_collapse_fraction"]

_SQRT2 = math.sqrt(2.0)
_LOG_SQRT_2PI = 0.5 * math.log(2.0 * math.pi)
_erfc = np.vectorize(math.erfc, otypes=[float])


@dataclass
class FragilityFit:
    """A fitted lognormal fragility."""

    median: float  #: IM at 50 % probability of collapse (units of the IM)
    beta: float  #: logarithmic standard deviation
    n: int  #: rows used
    n_censored: int  #: rows that never collapsed (lower bounds)
    log_likelihood: float


@dataclass
class FragilityBand:
    """Pointwise bootstrap percentiles of the fragility curve."""

    im: np.ndarray
    low: np.ndarray  #: lower percentile of P(collapse) at im
    high: np.ndarray
    level: float  #: e.g. 0.90 for the 5 %-95 % band
    median_low: float  #: percentiles of the fitted median
    median_high: float
    beta_low: float
    beta_high: float
    n_resamples: int  #: bootstrap resamples that could be fitted


def normal_cdf(z) -> np.ndarray:
    """Phi(z), accurate in both tails (erfc)."""
    return 0.5 * _erfc(-np.asarray(z, dtype=float) / _SQRT2)


def fragility(im, median: float, beta: float) -> np.ndarray:
    """P(collapse | IM) = Phi(ln(IM / median) / beta)."""
    return normal_cdf(np.log(np.asarray(im, dtype=float) / median) / beta)


def log_likelihood(mu: float, beta: float, ln_x: np.ndarray, censored: np.ndarray) -> float:
    """Log-likelihood of (mu, beta) for ln intensities, right-censored where flagged
    (the constant -sum ln x of the exact rows left out)."""
    z = (ln_x - mu) / beta
    exact = z[~censored]
    value = float(np.sum(-0.5 * exact * exact - _LOG_SQRT_2PI) - exact.size * math.log(beta))
    if censored.any():
        survival = 0.5 * _erfc(z[censored] / _SQRT2)
        if np.any(survival <= 0.0):
            return -math.inf
        value += float(np.sum(np.log(survival)))
    return value


def max_likelihood(ln_x: np.ndarray, censored: np.ndarray, tol: float = 1e-12,
                   max_iter: int = 5000) -> tuple[float, float, float]:
    """(mu, beta, log-likelihood) maximising :func:`log_likelihood`, by Nelder-Mead on
    (mu, ln beta) started from the mean and spread of all ln x."""
    ln_x = np.asarray(ln_x, dtype=float)
    censored = np.asarray(censored, dtype=bool)

    def cost(p):
        return -log_likelihood(p[0], math.exp(p[1]), ln_x, censored)

    spread = max(float(np.std(ln_x)), 0.05)
    simplex = np.array([[ln_x.mean(), math.log(spread)],
                        [ln_x.mean() + 0.5 * spread, math.log(spread)],
                        [ln_x.mean(), math.log(spread) + 0.5]])
    values = np.array([cost(p) for p in simplex])
    for _ in range(max_iter):
        order = np.argsort(values)
        simplex, values = simplex[order], values[order]
        if np.abs(simplex[1:] - simplex[0]).max() < tol and values[-1] - values[0] <= tol * (1 + abs(values[0])):
            break
        centroid = simplex[:-1].mean(axis=0)
        reflected = centroid + (centroid - simplex[-1])
        f_r = cost(reflected)
        if f_r < values[0]:
            expanded = centroid + 2.0 * (centroid - simplex[-1])
            f_e = cost(expanded)
            simplex[-1], values[-1] = (expanded, f_e) if f_e < f_r else (reflected, f_r)
        elif f_r < values[-2]:
            simplex[-1], values[-1] = reflected, f_r
        else:
            contracted = centroid + 0.5 * (simplex[-1] - centroid)
            f_c = cost(contracted)
            if f_c < values[-1]:
                simplex[-1], values[-1] = contracted, f_c
            else:  # shrink towards the best point
                simplex[1:] = simplex[0] + 0.5 * (simplex[1:] - simplex[0])
                values[1:] = [cost(p) for p in simplex[1:]]
    best = int(np.argmin(values))
    return float(simplex[best, 0]), math.exp(simplex[best, 1]), -float(values[best])


def fit_lognormal(im, censored=None, tol: float = 1e-12) -> FragilityFit:
    """Maximum-likelihood lognormal fragility of collapse intensities ``im`` (> 0),
    right-censored where ``censored`` (their ``im`` a lower bound); ``tol``: of the
    numerical maximisation (censored data only)."""
    im = np.asarray(im, dtype=float)
    censored = np.zeros(im.shape, bool) if censored is None else np.asarray(censored, dtype=bool)
    if im.ndim != 1 or im.shape != censored.shape or im.size == 0:
        raise FitError("intensities and censored flags must be two 1-D arrays of one length")
    if not np.all(np.isfinite(im) & (im > 0.0)):
        raise FitError("intensities must be finite and > 0")
    exact = im[~censored]
    if np.unique(exact).size < 2:
        raise FitError(f"{exact.size} of {im.size} rows collapsed (with {np.unique(exact).size} distinct "
                       "intensities): a fragility needs at least two different collapse intensities")
    ln_x = np.log(im)
    if not censored.any():
        mu, beta = float(np.mean(ln_x)), float(np.std(ln_x))
        ll = log_likelihood(mu, beta, ln_x, censored)
    else:
        mu, beta, ll = max_likelihood(ln_x, censored, tol=tol)
    return FragilityFit(median=math.exp(mu), beta=beta, n=int(im.size), n_censored=int(censored.sum()),
                        log_likelihood=ll)


def bootstrap_band(im, censored, im_grid, n_resamples: int = 400, level: float = 0.90,
                   seed: int = 20261124) -> FragilityBand:
    """Pointwise ``level`` band of the fragility at ``im_grid`` from ``n_resamples``
    resamples of the rows with replacement (resamples that cannot be fitted, e.g.
    with fewer than two collapses, are left out and not counted)."""
    im = np.asarray(im, dtype=float)
    censored = np.asarray(censored, dtype=bool)
    rng = np.random.default_rng(seed)
    curves, medians, betas = [], [], []
    for _ in range(n_resamples):
        pick = rng.integers(0, im.size, im.size)
        try:
            fit = fit_lognormal(im[pick], censored[pick], tol=1e-7)
        except FitError:
            continue
        curves.append(fragility(im_grid, fit.median, fit.beta))
        medians.append(fit.median)
        betas.append(fit.beta)
    if len(curves) < 10:
        raise FitError(f"only {len(curves)} of {n_resamples} bootstrap resamples could be fitted")
    tails = [50.0 * (1.0 - level), 50.0 * (1.0 + level)]
    low, high = np.percentile(np.array(curves), tails, axis=0)
    m_low, m_high = np.percentile(medians, tails)
    b_low, b_high = np.percentile(betas, tails)
    return FragilityBand(np.asarray(im_grid, float), low, high, level, float(m_low), float(m_high),
                         float(b_low), float(b_high), len(curves))


def empirical_collapse_fraction(im, censored) -> tuple[np.ndarray, np.ndarray]:
    """Kaplan-Meier estimate of P(IM_c <= x) at each exact collapse intensity x (sorted):
    the fraction of records collapsed at or below x, censored rows counted as at risk
    until their lower bound."""
    im = np.asarray(im, dtype=float)
    censored = np.asarray(censored, dtype=bool)
    order = np.lexsort((censored, im))  # at equal IM, collapses before censorings
    im, censored = im[order], censored[order]
    survival, at_risk = 1.0, im.size
    xs, ps = [], []
    for x, c in zip(im, censored):
        if not c:
            survival *= 1.0 - 1.0 / at_risk
            xs.append(x)
            ps.append(1.0 - survival)
        at_risk -= 1
    return np.array(xs), np.array(ps)
