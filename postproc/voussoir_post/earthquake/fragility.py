"""Lognormal fragility of collapse, fitted by maximum likelihood to the collapse
intensities of an incremental dynamic analysis.

Each record (on each sampled model) brings the arch down at an intensity IM_c (PGA or
PGV of the scaled record); the fragility is the distribution of IM_c:

    P(collapse | IM) = P(IM_c <= IM) = F(IM) = Phi(ln(IM / median) / beta).

An IDA does not measure IM_c itself: a search brackets it between the intensity of the
largest scale that stood and that of the smallest that collapsed, IM_c in (a, b]. With
ln IM_c normal (mu = ln median, sigma = beta) each row contributes to the
log-likelihood

    ln(Phi(z_b) - Phi(z_a)),  z = (ln IM - mu) / beta,

an *interval-censored* row; b = infinity for a row known only to exceed a (right-
censored: a record that never brought the arch down, or a search that failed after a
stand), and a row with a = b is an exact intensity, ln phi(z) - ln beta (the constant
-ln IM left out). The maximum is found by damped Newton on (mu, ln beta) with the
analytic gradient and Hessian (a few steps; BFGS of scipy.optimize where Newton
fails); with exact rows only it is the closed form, median = exp(mean ln x) and beta =
the standard deviation of ln x with divisor n (the maximum-likelihood estimate, not
the n - 1 one).

The band is a bootstrap refitted on resamples of *clusters* of rows (the rows of one
record over the model samples are not independent; records of one event neither), with
pointwise percentiles (:func:`clustered_resamples` draws them for any statistic of
the rows: two fits on the same resample make the paired bootstrap of voussoir-post
dtcheck). The goodness of fit is a Kolmogorov-Smirnov test of the
probability integral transform of the rows, randomised within each row's bracket.

With several model samples the spread splits into a record-to-record part and a model
part (FEMA P695 / P-58 practice; :func:`split_beta`): the same fit on the rows of each
model sample alone gives its median and beta; beta_RTR = sqrt(mean of the samples'
beta^2), beta_model = the standard deviation (divisor m - 1) of the m samples' ln
medians, and sqrt(beta_RTR^2 + beta_model^2) is set beside the pooled beta as a check.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize, stats
from scipy.special import log_ndtr, ndtr

from ..errors import FitError

__all__ = ["FitError", "FragilityFit", "FragilityBand", "FitCheck", "BetaSplit", "fit_lognormal", "fit_intervals",
           "max_likelihood", "max_likelihood_intervals", "log_likelihood", "interval_log_likelihood", "fragility",
           "bootstrap_band", "clustered_band", "refitted_band", "clustered_resamples", "resample_clusters",
           "goodness_of_fit", "normal_cdf", "empirical_collapse_fraction", "split_beta", "confidence_curve"]

_LOG_SQRT_2PI = 0.5 * math.log(2.0 * math.pi)


@dataclass
class FragilityFit:
    """A fitted lognormal fragility."""

    median: float  #: IM at 50 % probability of collapse (units of the IM)
    beta: float  #: logarithmic standard deviation (maximum likelihood: divisor n)
    n: int  #: rows used
    n_censored: int  #: rows known only to exceed an intensity (right-censored)
    log_likelihood: float
    n_interval: int = 0  #: rows known between two intensities (the rest are exact)


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
    cluster_by: str = "row"  #: what a resample draws: 'row', or the name of the clusters ('record', 'event')
    n_clusters: int = 0  #: clusters drawn from (rows when cluster_by is 'row'; events with two levels)
    ln_median_sd: float = math.nan  #: standard deviation of ln median over the resamples (divisor n - 1)
    beta_sd: float = math.nan  #: standard deviation of beta over the resamples (divisor n - 1)
    n_unfitted: int = 0  #: resamples left out because they could not be fitted
    #: the fitted median and beta of each resample (for what the band feeds: voussoir-post risk)
    medians: np.ndarray | None = None
    betas: np.ndarray | None = None


@dataclass
class FitCheck:
    """Goodness of fit: the probability integral transform (PIT) u = F(IM_c) of each row
    under the fitted law, randomised uniformly within F of its bracket, tested against
    U(0, 1) by Kolmogorov-Smirnov."""

    pit: np.ndarray  #: per row (NaN for a row left out of the fit)
    statistic: float  #: KS distance D
    p_value: float
    n: int  #: rows tested
    seed: int  #: of the randomisation within the brackets


@dataclass
class BetaSplit:
    """The spread of the pooled rows beside its record-to-record and model parts
    (:func:`split_beta`)."""

    beta_total: float  #: the pooled fit's beta (all the rows, every model sample)
    beta_rtr: float  #: record-to-record: sqrt(mean over the samples of beta_s^2)
    beta_model: float | None  #: standard deviation (divisor m - 1) of the samples' ln medians; None with one sample
    samples: list  #: the model samples' labels, sorted
    medians: np.ndarray  #: each sample's fitted median (units of the IM)
    betas: np.ndarray  #: each sample's fitted beta (maximum likelihood, divisor n)
    n_rows: np.ndarray  #: rows each sample's fit used

    @property
    def n_samples(self) -> int:
        return len(self.samples)

    @property
    def beta_srss(self) -> float | None:
        """sqrt(beta_RTR^2 + beta_model^2), to set beside beta_total (None with one sample)."""
        return None if self.beta_model is None else math.hypot(self.beta_rtr, self.beta_model)


def normal_cdf(z) -> np.ndarray:
    """Phi(z), accurate in both tails."""
    return ndtr(np.asarray(z, dtype=float))


def fragility(im, median: float, beta: float) -> np.ndarray:
    """P(collapse | IM) = Phi(ln(IM / median) / beta)."""
    with np.errstate(divide="ignore"):
        return normal_cdf(np.log(np.asarray(im, dtype=float) / median) / beta)


# ------------------------------------------------------------------ likelihood

def _log_phi_between(za: np.ndarray, zb: np.ndarray) -> np.ndarray:
    """ln(Phi(zb) - Phi(za)) for za < zb, from the tail nearer to the pair (no
    cancellation when both are far out)."""
    upper = za > 0.0  # both in the upper tail: Phi(zb) - Phi(za) = Phi(-za) - Phi(-zb)
    big = np.where(upper, log_ndtr(-za), log_ndtr(zb))
    small = np.where(upper, log_ndtr(-zb), log_ndtr(za))
    with np.errstate(divide="ignore", invalid="ignore"):
        return big + np.log1p(-np.exp(small - big))


def _split(ln_low: np.ndarray, ln_high: np.ndarray) -> np.ndarray:
    """Rows that are exact intensities (both ends equal)."""
    return ln_low == ln_high


def _log_pdf(z: np.ndarray) -> np.ndarray:
    """ln phi(z) (-inf at an infinite z)."""
    with np.errstate(invalid="ignore"):
        return -0.5 * z * z - _LOG_SQRT_2PI


def _derivatives(mu: float, beta: float, x: np.ndarray, ln_a: np.ndarray,
                 ln_b: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """:func:`interval_log_likelihood` of exact rows ``x`` and brackets (``ln_a``,
    ``ln_b``], its gradient and its Hessian with respect to (mu, s = ln beta).

    With z = (ln IM - mu) / beta, dz/dmu = -1 / beta and dz/ds = -z. An exact row adds
    (z / beta, z^2 - 1) to the gradient and [[-1, -2 z beta], [., -2 z^2 beta^2]] / beta^2
    to the Hessian. A bracket, P = Phi(zb) - Phi(za) and r = phi(z) / P at each end (0
    at an infinite end), adds g = ((ra - rb) / beta, za ra - zb rb) and, from
    d(phi(z) dz/di)/dj = phi(z) (d2z/didj - z dz/di dz/dj), the Hessian
    q(zb) - q(za) - g g^T, q(z) = r [[-z / beta^2, (1 - z^2) / beta], [., z (1 - z^2)]]."""
    z = (x - mu) / beta
    n, sum_z, sum_zz = z.size, float(z.sum()), float((z * z).sum())
    value = -0.5 * sum_zz - n * (_LOG_SQRT_2PI + math.log(beta))
    g_mu, g_s = sum_z / beta, sum_zz - n
    h_mu_mu, h_mu_s, h_s_s = -n / beta ** 2, -2.0 * sum_z / beta, -2.0 * sum_zz
    if ln_a.size:
        za, zb = (ln_a - mu) / beta, (ln_b - mu) / beta
        log_p = _log_phi_between(za, zb)
        if not np.all(np.isfinite(log_p)):  # a row the law cannot produce: stop before inf - inf
            return -math.inf, np.zeros(2), np.full((2, 2), math.nan)
        ra, rb = np.exp(_log_pdf(za) - log_p), np.exp(_log_pdf(zb) - log_p)
        za, zb = np.where(np.isfinite(za), za, 0.0), np.where(np.isfinite(zb), zb, 0.0)  # r = 0 there
        row_mu, row_s = (ra - rb) / beta, za * ra - zb * rb
        ra_1, rb_1 = ra * (1.0 - za * za), rb * (1.0 - zb * zb)
        sums = np.array([log_p, row_mu, row_s, (za * ra - zb * rb) / beta ** 2 - row_mu * row_mu,
                         (rb_1 - ra_1) / beta - row_mu * row_s, zb * rb_1 - za * ra_1 - row_s * row_s]).sum(axis=1)
        value += sums[0]
        g_mu, g_s = g_mu + sums[1], g_s + sums[2]
        h_mu_mu, h_mu_s, h_s_s = h_mu_mu + sums[3], h_mu_s + sums[4], h_s_s + sums[5]
    if not math.isfinite(value):
        return -math.inf, np.zeros(2), np.full((2, 2), math.nan)
    return float(value), np.array([g_mu, g_s]), np.array([[h_mu_mu, h_mu_s], [h_mu_s, h_s_s]])


def _value_and_score(mu: float, beta: float, ln_low: np.ndarray, ln_high: np.ndarray,
                     exact: np.ndarray) -> tuple[float, np.ndarray]:
    """:func:`interval_log_likelihood` and its gradient with respect to (mu, ln beta)."""
    return _derivatives(mu, beta, ln_low[exact], ln_low[~exact], ln_high[~exact])[:2]


def interval_log_likelihood(mu: float, beta: float, ln_low, ln_high) -> float:
    """Log-likelihood of (mu, beta) for ln IM_c in (ln_low, ln_high] (ln_high = inf:
    right-censored; ln_low = -inf: left-censored; equal: exact, its density in ln IM)."""
    ln_low, ln_high = np.asarray(ln_low, float), np.asarray(ln_high, float)
    return _value_and_score(mu, beta, ln_low, ln_high, _split(ln_low, ln_high))[0]


def log_likelihood(mu: float, beta: float, ln_x: np.ndarray, censored: np.ndarray) -> float:
    """Log-likelihood of (mu, beta) for exact ln intensities, right-censored where
    flagged (the constant -sum ln x of the exact rows left out)."""
    ln_x = np.asarray(ln_x, float)
    return interval_log_likelihood(mu, beta, ln_x, np.where(np.asarray(censored, bool), math.inf, ln_x))


def _newton(p: np.ndarray, rows: tuple, tol: float, max_steps: int = 50) -> tuple[np.ndarray, float] | None:
    """(mu, ln beta) and the log-likelihood after damped Newton steps from ``p`` on the
    analytic Hessian until a step is below ``tol`` (relative); None when the Hessian is
    not negative definite or no halving of the step climbs (the caller falls back)."""
    value, score, hess = _derivatives(p[0], math.exp(p[1]), *rows)
    for _ in range(max_steps):
        if not (math.isfinite(value) and hess[0, 0] < 0.0 and hess[0, 0] * hess[1, 1] - hess[0, 1] ** 2 > 0.0):
            return None  # not negative definite (or NaN)
        step = -np.linalg.solve(hess, score)
        for _ in range(30):  # halve until the likelihood does not fall (beyond rounding)
            trial = _derivatives(p[0] + step[0], math.exp(p[1] + step[1]), *rows)
            if trial[0] >= value - 1e-12 * (1.0 + abs(value)):
                break
            step = 0.5 * step
        else:
            return None
        p = p + step
        value, score, hess = trial
        if np.max(np.abs(step)) <= tol * (1.0 + np.max(np.abs(p))):
            return p, value
    return None


def max_likelihood_intervals(ln_low, ln_high, tol: float = 1e-12) -> tuple[float, float, float]:
    """(mu, beta, log-likelihood) maximising :func:`interval_log_likelihood`: damped
    Newton on (mu, ln beta) with the analytic Hessian until the step is below ``tol``
    (relative), from the mean and spread of one point per row (the exact value, the
    middle of a bracket, the finite end of a censored row). Where Newton fails (a
    Hessian not negative definite on the way, or no halving of a step that climbs),
    BFGS with the analytic gradient from the same start, then Newton from BFGS's
    answer (which stands if Newton fails again). The maximum is unique, so the path
    does not change the answer."""
    ln_low, ln_high = np.asarray(ln_low, float), np.asarray(ln_high, float)
    exact = _split(ln_low, ln_high)
    rows = (ln_low[exact], ln_low[~exact], ln_high[~exact])
    point = np.where(np.isfinite(ln_low) & np.isfinite(ln_high), 0.5 * (ln_low + ln_high),
                     np.where(np.isfinite(ln_low), ln_low, ln_high))
    start = np.array([point.mean(), math.log(max(float(np.std(point)), 0.05))])
    found = _newton(start, rows, tol)
    if found is None:
        def cost(p):
            value, score, _ = _derivatives(p[0], math.exp(p[1]), *rows)
            return -value, -score

        result = optimize.minimize(cost, start, jac=True, method="BFGS",
                                   options={"gtol": 1e-9 * max(1, ln_low.size)})
        p = np.asarray(result.x, float)
        found = _newton(p, rows, tol) or (p, -cost(p)[0])
    p, value = found
    if not (math.isfinite(value) and np.all(np.isfinite(p))):
        raise FitError("the maximum-likelihood fit did not converge")
    return float(p[0]), math.exp(p[1]), value


def max_likelihood(ln_x: np.ndarray, censored: np.ndarray, tol: float = 1e-12) -> tuple[float, float, float]:
    """(mu, beta, log-likelihood) maximising :func:`log_likelihood` (exact rows,
    right-censored where flagged), numerically."""
    ln_x = np.asarray(ln_x, dtype=float)
    return max_likelihood_intervals(ln_x, np.where(np.asarray(censored, bool), math.inf, ln_x), tol=tol)


# ------------------------------------------------------------------ the fit

def _check_brackets(low: np.ndarray, high: np.ndarray) -> None:
    """FitError unless the rows define a lognormal with 0 < beta < infinity."""
    if low.ndim != 1 or low.shape != high.shape or low.size == 0:
        raise FitError("the lower and upper intensities must be two 1-D arrays of one length")
    if not (np.all(np.isfinite(low) & (low >= 0.0)) and np.all(high >= low) and not np.any(np.isnan(high))):
        raise FitError("intensities must be finite, >= 0 and no upper intensity below its lower one")
    exact = low == high
    if np.any(low[exact] <= 0.0):
        raise FitError("an exact collapse intensity must be > 0")
    n_collapsed = int(np.sum(np.isfinite(high)))
    # A point in every row's bracket: a distribution concentrated there explains all
    # the rows, and the maximum likelihood is at beta = 0.
    if exact.any():
        common = float(low[exact][0]) if np.unique(low[exact]).size == 1 else None
        if common is not None and not np.all((low[~exact] < common) & (common <= high[~exact])):
            common = None
    else:
        a, b = float(np.max(low)), float(np.min(high))
        common = (b if math.isfinite(b) else 2.0 * a) if a < b else None
    if common is not None:
        raise FitError(f"{n_collapsed} of {low.size} rows collapsed and all of them allow one collapse intensity "
                       f"{common:.4g}: a fragility needs at least two different collapse intensities")
    if not np.any(exact | ((low > 0.0) & np.isfinite(high))):
        raise FitError("no row bounds its collapse intensity on both sides (a collapse above a stand): "
                       "the spread beta is not defined")


def fit_intervals(low, high, tol: float = 1e-12) -> FragilityFit:
    """Maximum-likelihood lognormal fragility of collapse intensities known to lie in
    (``low``, ``high``] (``high`` = inf: right-censored; ``low`` = 0 with a finite
    ``high``: left-censored; ``low`` = ``high``: exact). Exact rows only: the closed
    form; else :func:`max_likelihood_intervals` (``tol`` its relative step)."""
    low, high = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
    _check_brackets(low, high)
    exact = low == high
    with np.errstate(divide="ignore"):
        ln_low, ln_high = np.log(low), np.log(high)
    if exact.all():
        mu, beta = float(np.mean(ln_low)), float(np.std(ln_low))
        ll = interval_log_likelihood(mu, beta, ln_low, ln_high)
    else:
        mu, beta, ll = max_likelihood_intervals(ln_low, ln_high, tol=tol)
    censored = np.isinf(high)
    return FragilityFit(median=math.exp(mu), beta=beta, n=int(low.size), n_censored=int(censored.sum()),
                        log_likelihood=ll, n_interval=int(np.sum(~exact & ~censored)))


def fit_lognormal(im, censored=None, tol: float = 1e-12) -> FragilityFit:
    """Maximum-likelihood lognormal fragility of exact collapse intensities ``im`` (> 0),
    right-censored where ``censored`` (their ``im`` a lower bound); ``tol``: of the
    numerical maximisation (censored data only)."""
    im = np.asarray(im, dtype=float)
    censored = np.zeros(im.shape, bool) if censored is None else np.asarray(censored, dtype=bool)
    if im.ndim != 1 or im.shape != censored.shape or im.size == 0:
        raise FitError("intensities and censored flags must be two 1-D arrays of one length")
    if not np.all(np.isfinite(im) & (im > 0.0)):
        raise FitError("intensities must be finite and > 0")
    return fit_intervals(im, np.where(censored, math.inf, im), tol=tol)


# ------------------------------------------------------------------ beta split

def split_beta(low, high, samples, total: FragilityFit | None = None) -> BetaSplit:
    """The pooled beta of the rows (``low``, ``high``] (``total``: their fit, if made
    already) beside its parts, the rows grouped by ``samples`` (one model-sample label
    per row): each sample's rows fitted alone (:func:`fit_intervals`) give its median
    m_s and beta_s; beta_RTR = sqrt(mean_s beta_s^2) (unweighted over the samples),
    beta_model = the standard deviation of ln m_s with divisor m - 1, None with one
    sample. FitError, naming the sample, when a sample's rows cannot be fitted alone."""
    low, high = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
    samples = np.asarray(samples)
    if samples.shape != low.shape:
        raise FitError("one model sample label per row is needed")
    total = fit_intervals(low, high) if total is None else total
    names = np.unique(samples)
    fits = []
    for name in names.tolist():
        mine = samples == name
        try:
            fits.append(fit_intervals(low[mine], high[mine]))
        except FitError as exc:
            raise FitError(f"model sample {name} alone ({int(mine.sum())} rows): {exc}") from None
    medians = np.array([f.median for f in fits])
    betas = np.array([f.beta for f in fits])
    beta_model = float(np.std(np.log(medians), ddof=1)) if names.size > 1 else None
    return BetaSplit(beta_total=total.beta, beta_rtr=math.sqrt(float(np.mean(betas ** 2))), beta_model=beta_model,
                     samples=names.tolist(), medians=medians, betas=betas, n_rows=np.array([f.n for f in fits]))


# ------------------------------------------------------------------ the band

def resample_clusters(rng: np.random.Generator, clusters, events=None) -> np.ndarray:
    """Row indices of one bootstrap resample. Without ``events``: k clusters drawn with
    replacement from the k (``rng.integers(0, k, k)``, clusters numbered in sorted order
    of their labels), all the rows of each; with ``events`` (one per row, the same for
    every row of a cluster): the events drawn with replacement, then within each drawn
    event its clusters with replacement (two-stage)."""
    return _draw_clusters(rng, *_cluster_layout(clusters, events))


def _cluster_layout(clusters, events=None) -> tuple[list, list | None]:
    """(the rows of each cluster, the clusters of each event or None), in sorted order of
    the labels: what :func:`resample_clusters` draws from, worked out once."""
    names, code = np.unique(np.asarray(clusters), return_inverse=True)
    members = [np.flatnonzero(code == k) for k in range(names.size)]
    if events is None:
        return members, None
    event_names, event_code = np.unique(np.asarray(events), return_inverse=True)
    return members, [np.unique(code[event_code == e]) for e in range(event_names.size)]


def _draw_clusters(rng: np.random.Generator, members: list, inside: list | None) -> np.ndarray:
    """One resample of :func:`resample_clusters` from its :func:`_cluster_layout`."""
    if inside is None:
        pick = rng.integers(0, len(members), len(members))
        return np.concatenate([members[k] for k in pick])
    rows = []
    for e in rng.integers(0, len(inside), len(inside)):
        for k in inside[e][rng.integers(0, inside[e].size, inside[e].size)]:
            rows.append(members[k])
    return np.concatenate(rows)


def clustered_band(low, high, im_grid, clusters=None, events=None, cluster_by: str = "",
                   n_resamples: int = 400, level: float = 0.90, seed: int = 20261124) -> FragilityBand:
    """Pointwise ``level`` band of the fragility at ``im_grid`` from ``n_resamples``
    bootstrap resamples of the bracketed rows (``low``, ``high``] (see
    :func:`fit_intervals`), each refitted. ``clusters`` (one label per row): a resample
    draws clusters, not rows (:func:`resample_clusters`; ``events``: two stages);
    ``None``: each row its own cluster, the plain row bootstrap. ``cluster_by`` names
    the clusters in the result ('record', 'event'). Resamples that cannot be fitted
    (e.g. with fewer than two collapses) are left out, and counted."""
    low, high = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
    return refitted_band(lambda pick: fit_intervals(low[pick], high[pick], tol=1e-9), low.size, im_grid, clusters,
                         events, cluster_by, n_resamples, level, seed)


def refitted_band(fit_rows, n_rows: int, im_grid, clusters=None, events=None, cluster_by: str = "",
                  n_resamples: int = 400, level: float = 0.90, seed: int = 20261124) -> FragilityBand:
    """The band of :func:`clustered_band` for any fit of rows: ``fit_rows(pick)`` fits
    the rows of the index array ``pick`` (a resample of the ``n_rows`` rows, drawn by
    :func:`resample_clusters`) and returns a :class:`FragilityFit`, or raises FitError
    (the resample is then left out, and counted)."""
    rows = clusters is None
    fits, n_clusters = clustered_resamples(fit_rows, n_rows, clusters, events, n_resamples, seed)
    curves = [fragility(im_grid, fit.median, fit.beta) for fit in fits]
    ln_medians = [math.log(fit.median) for fit in fits]
    betas = [fit.beta for fit in fits]
    tails = [50.0 * (1.0 - level), 50.0 * (1.0 + level)]
    p_low, p_high = np.percentile(np.array(curves), tails, axis=0)
    m_low, m_high = np.exp(np.percentile(ln_medians, tails))
    b_low, b_high = np.percentile(betas, tails)
    return FragilityBand(np.asarray(im_grid, float), p_low, p_high, level, float(m_low), float(m_high),
                         float(b_low), float(b_high), len(curves),
                         cluster_by="row" if rows else (cluster_by or "cluster"), n_clusters=n_clusters,
                         ln_median_sd=float(np.std(ln_medians, ddof=1)), beta_sd=float(np.std(betas, ddof=1)),
                         n_unfitted=n_resamples - len(curves), medians=np.exp(np.array(ln_medians)),
                         betas=np.array(betas))


def clustered_resamples(statistic, n_rows: int, clusters=None, events=None, n_resamples: int = 400,
                        seed: int = 20261124) -> tuple[list, int]:
    """(the values of ``statistic(pick)`` over ``n_resamples`` bootstrap resamples of the
    ``n_rows`` rows, the number of clusters drawn from): each ``pick`` an index array
    drawn by :func:`resample_clusters` (``clusters`` None: each row its own cluster;
    ``events``: two stages) from ``numpy.random.default_rng(seed)``. A statistic of
    several fits on the same ``pick`` (e.g. two IDAs of paired rows) gets a paired
    bootstrap. Resamples whose statistic raises FitError are left out; FitError when
    fewer than 10 remain."""
    if clusters is None:
        clusters = np.arange(n_rows)
    if len(clusters) != n_rows or (events is not None and len(events) != n_rows):
        raise FitError("one cluster (and event) label per row is needed")
    if events is not None:
        label = {}
        for c, e in zip(np.asarray(clusters).tolist(), np.asarray(events).tolist()):
            if label.setdefault(c, e) != e:
                raise FitError(f"cluster '{c}' belongs to two events, '{label[c]}' and '{e}'")
    rng = np.random.default_rng(seed)
    layout = _cluster_layout(clusters, events)
    values = []
    for _ in range(n_resamples):
        pick = _draw_clusters(rng, *layout)
        try:
            values.append(statistic(pick))
        except FitError:
            continue
    if len(values) < 10:
        raise FitError(f"only {len(values)} of {n_resamples} bootstrap resamples could be fitted")
    n_clusters = np.unique(np.asarray(events if events is not None else clusters)).size
    return values, int(n_clusters)


def confidence_curve(im, fit: FragilityFit, band: FragilityBand) -> np.ndarray:
    """The fragility at the lower bound of the median: the lognormal of median
    ``band.median_low`` (the 50 (1 - level) th percentile of the bootstrap medians: the
    5th for the 90 % band; the median is above it with confidence (1 + level) / 2) and
    the fitted beta (the uncertainty of beta is not carried)."""
    return fragility(im, band.median_low, fit.beta)


def bootstrap_band(im, censored, im_grid, n_resamples: int = 400, level: float = 0.90,
                   seed: int = 20261124, clusters=None, events=None, cluster_by: str = "") -> FragilityBand:
    """:func:`clustered_band` of exact intensities ``im``, right-censored where
    ``censored``."""
    im = np.asarray(im, dtype=float)
    high = np.where(np.asarray(censored, dtype=bool), math.inf, im)
    return clustered_band(im, high, im_grid, clusters, events, cluster_by, n_resamples, level, seed)


# ------------------------------------------------------------------ goodness of fit

def goodness_of_fit(low, high, median: float, beta: float, seed: int = 20261124) -> FitCheck:
    """The PIT of each row (``low``, ``high``] under the lognormal (median, beta): F(x)
    for an exact row, else F(low) + v (F(high) - F(low)) with v uniform on (0, 1)
    (drawn for every row in order from ``seed``): uniform on (0, 1) when the rows come
    from that law. Rows with a NaN ``low`` are left out. The KS p-value takes (median,
    beta) as given: fitted to the same rows it is conservative (too large), and rows
    that share a record are not independent, which makes it optimistic the other way."""
    low, high = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
    v = np.random.default_rng(seed).uniform(0.0, 1.0, low.size)
    f_low, f_high = fragility(low, median, beta), fragility(high, median, beta)
    pit = np.where(low == high, f_low, f_low + v * (f_high - f_low))
    used = np.isfinite(pit)
    if used.sum() < 2:
        raise FitError("the goodness of fit needs at least two rows")
    test = stats.kstest(pit[used], "uniform")
    return FitCheck(pit, float(test.statistic), float(test.pvalue), int(used.sum()), seed)


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
