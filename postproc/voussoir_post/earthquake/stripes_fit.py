"""Lognormal fragility of collapse fitted to the stripes of a multiple-stripe analysis
(MSA), by the binomial maximum likelihood of Baker (2015, Earthquake Spectra 31(1),
"Efficient analytical fragility function fitting using dynamic structural analysis").

At each intensity level x_j (a stripe) n_j runs were made and z_j collapsed. With
P(collapse | x) = p(x) = Phi(ln(x / theta) / beta), the runs at x_j collapse
independently with probability p(x_j), and the likelihood of (theta, beta) is

    L = prod_j C(n_j, z_j) p_j^z_j (1 - p_j)^(n_j - z_j),

maximised here over (ln theta, ln beta) by BFGS (scipy.optimize) with the analytic
gradient; ln p and ln(1 - p) come from ``log_ndtr``, accurate far in both tails. The
constant C(n_j, z_j) is kept in the reported log-likelihood, as Baker writes it.

The maximum exists (beta > 0 finite) when some run stood at a level above one where a
run collapsed: otherwise the stripes are separated (every stand at or below every
collapse) and the likelihood grows as beta -> 0; that is refused with the levels named.
With two stripes of fractions f1 < f2, both strictly between 0 and 1, the fit passes
through both: beta = ln(x2 / x1) / (Phi^-1(f2) - Phi^-1(f1)).

The band is the clustered bootstrap of :func:`voussoir_post.earthquake.fragility.
refitted_band`: a resample draws records (all their runs, every level and model
sample: the runs of one record are not independent), or events then records.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize
from scipy.special import gammaln, log_ndtr

from ..errors import FitError
from .fragility import FragilityBand, FragilityFit, refitted_band

__all__ = ["stripes_of", "binomial_log_likelihood", "fit_stripes", "fit_runs", "stripes_band"]

#: beta beyond this is no fragility: the fraction collapsed does not grow with the level
BETA_MAX = 20.0


def stripes_of(levels, collapsed) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(x, n, z) of runs at ``levels`` (> 0) that ``collapsed`` (bool): the distinct
    levels, increasing, the runs at each and the collapses among them."""
    levels = np.asarray(levels, dtype=float)
    collapsed = np.asarray(collapsed, dtype=bool)
    if levels.ndim != 1 or levels.shape != collapsed.shape or levels.size == 0:
        raise FitError("the levels and the outcomes must be two 1-D arrays of one length, not empty")
    if not np.all(np.isfinite(levels) & (levels > 0.0)):
        raise FitError("the intensity levels must be finite and > 0")
    x, code = np.unique(levels, return_inverse=True)
    n = np.bincount(code, minlength=x.size)
    z = np.bincount(code, weights=collapsed.astype(float), minlength=x.size).astype(int)
    return x, n, z


def binomial_log_likelihood(mu: float, beta: float, x, n, z) -> float:
    """ln L of Baker's binomial likelihood (the binomial coefficients included) for
    stripes (x, n, z) under the lognormal of median exp(``mu``) and ``beta``."""
    x, n, z = np.asarray(x, float), np.asarray(n, float), np.asarray(z, float)
    u = (np.log(x) - mu) / beta
    log_choose = gammaln(n + 1.0) - gammaln(z + 1.0) - gammaln(n - z + 1.0)
    with np.errstate(invalid="ignore"):
        terms = np.where(z > 0, z * log_ndtr(u), 0.0) + np.where(n - z > 0, (n - z) * log_ndtr(-u), 0.0)
    return float(np.sum(log_choose + terms))


def _cost_and_gradient(p: np.ndarray, ln_x: np.ndarray, n: np.ndarray, z: np.ndarray) -> tuple[float, np.ndarray]:
    """-ln L (without the constant) and its gradient in (mu, ln beta)."""
    mu, beta = p[0], math.exp(p[1])
    u = (ln_x - mu) / beta
    log_p, log_q = log_ndtr(u), log_ndtr(-u)
    log_pdf = -0.5 * u * u - 0.5 * math.log(2.0 * math.pi)
    value = float(np.sum(z * log_p + (n - z) * log_q))
    # d ln L / du = z phi/Phi(u) - (n - z) phi/Phi(-u); du/dmu = -1/beta, du/dln beta = -u
    d_u = z * np.exp(log_pdf - log_p) - (n - z) * np.exp(log_pdf - log_q)
    gradient = np.array([float(np.sum(-d_u / beta)), float(np.sum(-d_u * u))])
    return -value, -gradient


def _check_overlap(x: np.ndarray, n: np.ndarray, z: np.ndarray, unit: str, verbs: tuple[str, str]) -> None:
    """FitError unless some run stood at a level above a level where one collapsed
    (``verbs``: the words of an outcome and of its absence, ('collapsed', 'stood'))."""
    yes, no = verbs
    if not np.any(z > 0):
        raise FitError(f"no run {yes} at any of the {x.size} levels (up to {x.max():.4g} {unit}): "
                       "the fragility's median lies above every level; add higher levels")
    if not np.any(z < n):
        raise FitError(f"every run {yes}, at each of the {x.size} levels (from {x.min():.4g} {unit}): "
                       "the fragility's median lies below every level; add lower levels")
    lowest_yes = float(x[z > 0].min())
    highest_no = float(x[z < n].max())
    if highest_no <= lowest_yes:
        raise FitError(f"the stripes are separated: every run {no} at or below {highest_no:.4g} {unit} and every "
                       f"one {yes} at or above {lowest_yes:.4g} {unit}, so the likelihood grows without "
                       f"bound as beta -> 0; a fragility needs a run that {no} at a level above one where a run "
                       f"{yes} (more records, or levels between these)")


def fit_stripes(x, n, z, unit: str = "g", verbs: tuple[str, str] = ("collapsed", "stood")) -> FragilityFit:
    """Baker's binomial maximum-likelihood fit to stripes (x, n, z): ``n`` runs at level
    ``x`` (> 0, in ``unit``), ``z`` of them collapsed (``verbs``: the words of the
    outcome and of its absence in the messages). FitError, with the levels named, when
    the maximum is not a fragility (no collapse, no stand, separated stripes, or a
    fraction collapsed that does not grow with the level)."""
    x, n, z = np.asarray(x, float), np.asarray(n, float), np.asarray(z, float)
    if not (x.ndim == 1 and x.shape == n.shape == z.shape and x.size > 0):
        raise FitError("levels, runs and collapses must be three 1-D arrays of one length, not empty")
    if not (np.all(np.isfinite(x) & (x > 0.0)) and np.all((n >= 1) & (z >= 0) & (z <= n))):
        raise FitError("levels must be finite and > 0, each with at least one run and 0 <= collapses <= runs")
    _check_overlap(x, n, z, unit, verbs)
    ln_x = np.log(x)
    # Start: the median at the weighted mean of the levels' logarithms, beta 0.5.
    start = np.array([float(np.sum(n * ln_x) / np.sum(n)), math.log(0.5)])
    result = optimize.minimize(_cost_and_gradient, start, args=(ln_x, n, z), jac=True, method="BFGS",
                               options={"gtol": 1e-10 * float(np.sum(n))})
    mu, beta = float(result.x[0]), math.exp(float(result.x[1]))
    if not (math.isfinite(mu) and math.isfinite(beta)) or beta > BETA_MAX:
        raise FitError(f"the binomial fit has no finite maximum with beta <= {BETA_MAX:g} (beta -> {beta:.3g}): "
                       "the fraction collapsed does not grow with the level")
    return FragilityFit(median=math.exp(mu), beta=beta, n=int(np.sum(n)), n_censored=0,
                        log_likelihood=binomial_log_likelihood(mu, beta, x, n, z))


def fit_runs(levels, collapsed, unit: str = "g") -> FragilityFit:
    """:func:`fit_stripes` of single runs: ``levels`` (> 0) and whether each ``collapsed``."""
    return fit_stripes(*stripes_of(levels, collapsed), unit=unit)


def stripes_band(levels, collapsed, im_grid, clusters=None, events=None, cluster_by: str = "",
                 n_resamples: int = 400, level: float = 0.90, seed: int = 20261124) -> FragilityBand:
    """Pointwise ``level`` band of the fragility at ``im_grid`` from ``n_resamples``
    bootstrap resamples of the runs, each refitted by :func:`fit_runs`; ``clusters``
    (one label per run, e.g. its record) and ``events`` as in
    :func:`voussoir_post.earthquake.fragility.clustered_band` (its resampling, reused)."""
    levels = np.asarray(levels, dtype=float)
    collapsed = np.asarray(collapsed, dtype=bool)
    return refitted_band(lambda pick: fit_runs(levels[pick], collapsed[pick]), levels.size, im_grid, clusters,
                         events, cluster_by, n_resamples, level, seed)
