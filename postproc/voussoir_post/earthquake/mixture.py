"""The fragility of a model known only by its posterior: a mixture of the model samples'
fragilities, its spread over the samples, and when a pooled lognormal may stand for it
(issue 36, item 2).

Each model sample s (an IDA's ``param_set``) has its own lognormal fragility F_s, fitted to
its rows alone (the interval-censored maximum likelihood of :mod:`.fragility`), and a
weight w_s in the mixture (the strata of :mod:`voussoir_post.diagnosis.strata`: its model's
posterior share over that model's samples; equal weights without strata). The calibrated
fragility is the mixture

    F(IM) = sum_s w_s F_s(IM),

the probability of collapse of the arch whose model is uncertain as the posterior says;
its median solves F(IM) = 1/2 (a root in ln IM between the samples' extreme medians). Beside
it: the percentile curves over the samples (at each IM, the weighted q-quantile of the
F_s(IM): the smallest value whose cumulated weight reaches q), and each model's own curve
(the mixture of its samples alone).

The band resamples both sources in two stages (:func:`mixture_band`): the events with their
records (:func:`.fragility.resample_clusters`, as the pooled fit's band), and the model
samples, within each model (n_m of its n_m samples drawn with replacement, each keeping the
weight w_s; without strata, all the samples drawn as one stratum). Each resample refits every
sample it drew on the rows of the records it drew and makes its mixture.

The pooled lognormal (one fit on every row) is the mixture's stand-in only where its goodness
of fit holds. Its Kolmogorov-Smirnov p-value taken from the KS table is wrong twice over: the
parameters were fitted to the same rows (too large a p), and rows sharing a record or an event
are not independent (too small). :func:`calibrated_fit_check` calibrates it by a parametric
bootstrap that keeps the clustering of the rows: rows simulated from the fitted lognormal with
a random effect per event, per record and per model sample (ln IM_c = mu + beta (sqrt(rho_e)
a_event + sqrt(rho_r - rho_e) b_record + sqrt(rho_s) c_sample + sqrt(1 - rho_r - rho_s) e_row),
the correlations rho_r of two rows of one record, rho_e of two records of one event and rho_s
of two rows of one sample estimated from the rows' standardised residuals, records and samples
crossed), bracketed and censored as the IDA's rows were, refitted, and the statistic
recomputed; the p-value is the share of simulated statistics at least the observed one
((1 + count) / (1 + n)). Under that null the samples' spread is itself lognormal, which is
what a pooled lognormal assumes: the test asks whether the samples' medians (and the
records) look like draws of a normal in ln IM. A posterior split between rival models of
distinct capacities fails it once each model has a few samples; with very few samples in
all, draws of a normal can look like anything, and the test cannot tell (the mixture is made
either way).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import optimize, stats

from ..errors import FitError
from .fragility import (FragilityFit, _cluster_layout, _draw_clusters, fit_intervals, fragility,
                        goodness_of_fit)

__all__ = ["SampleFits", "fit_samples", "mixture_cdf", "mixture_quantile", "weighted_quantile",
           "percentile_curves", "model_curves", "MixtureBand", "mixture_band", "CalibratedCheck",
           "calibrated_fit_check", "cluster_correlations", "MixtureFragility", "mixture_fragility",
           "GOF_LEVEL", "PERCENTILES"]

#: The pooled lognormal stands for the mixture only when its calibrated p-value is at least this.
GOF_LEVEL = 0.05
#: The percentile curves over the samples drawn and tabulated.
PERCENTILES = (0.16, 0.84)


@dataclass
class SampleFits:
    """Each model sample's own lognormal, and its weight."""

    samples: np.ndarray  #: the param_set of each sample
    medians: np.ndarray
    betas: np.ndarray
    weights: np.ndarray  #: sum 1
    models: list[str] | None = None  #: the model of each sample (None: not stratified)
    n_rows: np.ndarray | None = None

    def cdf(self, im) -> np.ndarray:
        return mixture_cdf(im, self.medians, self.betas, self.weights)

    def median(self) -> float:
        return mixture_quantile(0.5, self.medians, self.betas, self.weights)


def fit_samples(low, high, param_set, weights: dict | None = None, models: dict | None = None) -> SampleFits:
    """Each sample's lognormal on its own rows (``low``, ``high``]; ``weights`` {param_set:
    w} (default equal; renormalised to sum 1), ``models`` {param_set: model}. FitError,
    naming the sample, when one cannot be fitted."""
    low, high, param_set = np.asarray(low, float), np.asarray(high, float), np.asarray(param_set)
    used = np.isfinite(low)
    names = np.unique(param_set[used])
    medians, betas, n = [], [], []
    for s in names.tolist():
        mine = used & (param_set == s)
        try:
            fit = fit_intervals(low[mine], high[mine])
        except FitError as exc:
            raise FitError(f"model sample {s} alone ({int(mine.sum())} rows): {exc}") from None
        medians.append(fit.median)
        betas.append(fit.beta)
        n.append(fit.n)
    w = np.array([1.0 if weights is None else float(weights[s]) for s in names.tolist()])
    return SampleFits(names, np.array(medians), np.array(betas), w / w.sum(),
                      None if models is None else [models[s] for s in names.tolist()], np.array(n))


def mixture_cdf(im, medians, betas, weights) -> np.ndarray:
    """sum_s w_s Phi(ln(IM / m_s) / beta_s) at each IM."""
    im = np.atleast_1d(np.asarray(im, float))
    medians, betas, weights = (np.asarray(v, float) for v in (medians, betas, weights))
    with np.errstate(divide="ignore"):
        z = (np.log(im)[:, None] - np.log(medians)[None, :]) / betas[None, :]
    return stats.norm.cdf(z) @ (weights / weights.sum())


def mixture_quantile(p: float, medians, betas, weights) -> float:
    """The IM at which the mixture reaches ``p``: a root in ln IM (brentq to 1e-12) between
    the samples' own p-quantiles, which bracket it."""
    medians, betas = np.asarray(medians, float), np.asarray(betas, float)
    own = np.log(medians) + betas * stats.norm.ppf(p)
    lo, hi = float(own.min()), float(own.max())
    if hi - lo < 1e-12:
        return math.exp(lo)
    f = lambda x: float(mixture_cdf(math.exp(x), medians, betas, weights)[0]) - p
    return math.exp(optimize.brentq(f, lo - 1e-9, hi + 1e-9, xtol=1e-13, rtol=1e-13))


def weighted_quantile(values, weights, q: float) -> float:
    """The smallest value whose cumulated weight (values sorted) reaches ``q`` of the total."""
    values, weights = np.asarray(values, float), np.asarray(weights, float)
    order = np.argsort(values, kind="stable")
    cum = np.cumsum(weights[order]) / weights.sum()
    return float(values[order][np.searchsorted(cum, q - 1e-12)])


def percentile_curves(im, fits: SampleFits, levels=PERCENTILES) -> dict[float, np.ndarray]:
    """At each IM, the weighted ``level`` quantiles of the samples' P(collapse)."""
    curves = np.array([fragility(im, m, b) for m, b in zip(fits.medians, fits.betas)])
    return {q: np.array([weighted_quantile(curves[:, k], fits.weights, q) for k in range(curves.shape[1])])
            for q in levels}


def model_curves(im, fits: SampleFits) -> dict[str, np.ndarray]:
    """Each model's own curve: the mixture of its samples alone (their weights renormalised)."""
    if fits.models is None:
        return {}
    out = {}
    models = np.array(fits.models)
    for m in dict.fromkeys(fits.models):
        mine = models == m
        out[m] = mixture_cdf(im, fits.medians[mine], fits.betas[mine], fits.weights[mine])
    return out


# ------------------------------------------------------------------ the two-stage band

@dataclass
class MixtureBand:
    """The mixture's band from resamples of the events (with their records) and of the samples."""

    im: np.ndarray
    low: np.ndarray
    high: np.ndarray
    level: float
    median_low: float
    median_high: float
    medians: np.ndarray  #: each resample's mixture median
    n_resamples: int  #: resamples fitted
    n_unfitted: int
    resample_samples: bool  #: the samples were resampled (False: held fixed, the events only)
    n_clusters: int
    cluster_by: str
    #: each resample's drawn samples: (medians, betas, weights) of its mixture, for the risk's band
    draws: list = field(default_factory=list)

    @property
    def ln_median_sd(self) -> float:
        return float(np.std(np.log(self.medians), ddof=1))


def _sample_strata(fits: SampleFits) -> list[np.ndarray]:
    """The indices (into fits.samples) of each stratum: one per model, or all in one."""
    if fits.models is None:
        return [np.arange(fits.samples.size)]
    models = np.array(fits.models)
    return [np.flatnonzero(models == m) for m in dict.fromkeys(fits.models)]


def mixture_band(low, high, param_set, fits: SampleFits, im_grid, clusters=None, events=None, cluster_by: str = "",
                 n_resamples: int = 400, level: float = 0.90, seed: int = 20261124,
                 resample_samples: bool = True) -> MixtureBand:
    """Pointwise ``level`` band of the mixture at ``im_grid`` and of its median: each of
    ``n_resamples`` resamples draws the rows' clusters (``clusters``, ``events``: as
    :func:`.fragility.clustered_band`) and, with ``resample_samples``, the samples within
    their strata; every drawn sample is refitted on its rows of the drawn records. A resample
    in which a drawn sample cannot be fitted is left out, and counted."""
    low, high, param_set = np.asarray(low, float), np.asarray(high, float), np.asarray(param_set)
    n_rows = low.size
    if clusters is None:
        clusters = np.arange(n_rows)
    layout = _cluster_layout(clusters, events)
    strata = _sample_strata(fits)
    rng = np.random.default_rng(seed)
    curves, medians, draws = [], [], []
    unfitted = 0
    for _ in range(n_resamples):
        pick = _draw_clusters(rng, *layout)
        if resample_samples:
            chosen = np.concatenate([idx[rng.integers(0, idx.size, idx.size)] for idx in strata])
        else:
            chosen = np.arange(fits.samples.size)
        picked_sets = param_set[pick]
        cache = {}
        try:
            for k in np.unique(chosen).tolist():
                rows = pick[(picked_sets == fits.samples[k]) & np.isfinite(low[pick])]
                fit = fit_intervals(low[rows], high[rows], tol=1e-9)
                cache[k] = (fit.median, fit.beta)
        except FitError:
            unfitted += 1
            continue
        m = np.array([cache[k][0] for k in chosen.tolist()])
        b = np.array([cache[k][1] for k in chosen.tolist()])
        w = fits.weights[chosen] / fits.weights[chosen].sum()
        curves.append(mixture_cdf(im_grid, m, b, w))
        medians.append(mixture_quantile(0.5, m, b, w))
        draws.append((m, b, w))
    if len(curves) < 10:
        raise FitError(f"only {len(curves)} of {n_resamples} two-stage resamples could be fitted")
    tails = [50.0 * (1.0 - level), 50.0 * (1.0 + level)]
    p_low, p_high = np.percentile(np.array(curves), tails, axis=0)
    m_low, m_high = np.exp(np.percentile(np.log(medians), tails))
    n_clusters = np.unique(np.asarray(events if events is not None else clusters)).size
    return MixtureBand(np.asarray(im_grid, float), p_low, p_high, level, float(m_low), float(m_high),
                       np.array(medians), len(curves), unfitted, resample_samples, int(n_clusters),
                       cluster_by or ("row" if clusters is None else "cluster"), draws)


# ------------------------------------------------------------------ calibrated goodness of fit

@dataclass
class CalibratedCheck:
    """The pooled lognormal's goodness of fit, its p-value calibrated by a parametric
    clustered bootstrap."""

    statistic: float  #: KS distance D of the rows' randomised PIT under the pooled fit
    p_table: float  #: the KS table's p-value (fitted parameters and clustering ignored)
    p_value: float  #: calibrated: (1 + #(D_sim >= D)) / (1 + n_simulations)
    n_simulations: int  #: simulated data sets that could be fitted
    rho_record: float  #: correlation of two rows of one record, used in the simulation
    rho_event: float  #: of two rows of different records of one event
    seed: int
    rho_sample: float = 0.0  #: of two rows of one model sample in different records (simulated with
    #: ``sample_effect``)

    @property
    def holds(self) -> bool:
        return self.p_value >= GOF_LEVEL


def cluster_correlations(z, clusters=None, events=None, samples=None) -> tuple[float, float, float]:
    """(rho_r, rho_e, rho_s): moment estimates of the shares of var(z) of the random effects
    of the module docstring, from the standardised residuals ``z`` = (ln IM_c - mu) / beta.
    Records and model samples are crossed (every sample plays every record), so each effect
    is read with the other taken out: rho_r is the mean product over pairs of rows of one
    record (``clusters``), rho_e over pairs of one event in different records, both of z less
    its sample's mean; rho_s the mean product over pairs of one sample in different records
    of z less its record's mean, times S / (S - 1) (S samples: the centring takes 1/S of it);
    each over the mean z^2. Clipped to 0 <= rho_e <= rho_r <= 0.95 and 0 <= rho_s <= 0.95; 0
    where there is no pair (or no labels)."""
    z = np.asarray(z, float)
    scale = float(np.mean(z * z)) or 1.0

    def centred(labels):
        if labels is None:
            return z
        code = np.unique(np.asarray(labels), return_inverse=True)[1]
        return z - (np.bincount(code, z) / np.bincount(code))[code]

    def pairs(v, *labels):
        """(sum of v_i v_j, number of pairs) over the pairs i < j alike in every label."""
        if any(lab is None for lab in labels):
            return 0.0, 0
        keys = np.unique(np.stack([np.unique(np.asarray(lab), return_inverse=True)[1] for lab in labels]), axis=1,
                         return_inverse=True)[1].reshape(-1)
        sums, squares, counts = np.bincount(keys, v), np.bincount(keys, v * v), np.bincount(keys)
        return float(np.sum(0.5 * (sums * sums - squares))), int(np.sum(counts * (counts - 1) // 2))

    def ratio(total, count):
        return total / count / scale if count > 0 else 0.0

    by_sample = centred(samples)
    r = pairs(by_sample, clusters)
    rho_r = max(ratio(*r), 0.0) if clusters is not None else 0.0
    rho_e = 0.0
    if events is not None and clusters is not None:
        e = pairs(by_sample, events)
        rho_e = max(ratio(e[0] - r[0], e[1] - r[1]), 0.0)
    rho_s = 0.0
    if samples is not None and clusters is not None:
        n_samples = np.unique(np.asarray(samples)).size
        by_record = centred(clusters)
        s, sr = pairs(by_record, samples), pairs(by_record, samples, clusters)
        if n_samples > 1:
            rho_s = max(ratio(s[0] - sr[0], s[1] - sr[1]) * n_samples / (n_samples - 1), 0.0)
    rho_r = min(rho_r, 0.95)
    rho_s = min(rho_s, 0.95)
    rho_e = min(rho_e, rho_r)
    return rho_r, rho_e, rho_s


def _representative(low: np.ndarray, high: np.ndarray) -> np.ndarray:
    """One ln IM per row: the geometric middle of a bracket, the lower end of a censored row."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(np.isfinite(high) & (low > 0), 0.5 * (np.log(low) + np.log(high)),
                        np.where(np.isfinite(high), np.log(high), np.log(low)))


def calibrated_fit_check(low, high, fit: FragilityFit | None = None, clusters=None, events=None, censor_at=None,
                         n_simulations: int = 200, seed: int = 20261124, samples=None,
                         sample_effect: bool = True) -> CalibratedCheck:
    """The pooled lognormal's KS statistic (:func:`.fragility.goodness_of_fit`, seed
    ``seed``) and its p-value by a parametric bootstrap that keeps the rows' clustering
    (module docstring). Each simulated row is bracketed as its row was: censored at
    ``censor_at`` (per row, the intensity at scale_max or the failed search's last stand;
    default: a censored row's lower end, inf for the others) when it lies above, else in a
    bracket of the row's own width ratio high/low (the median ratio for rows without one;
    an exact row stays exact) at a uniform offset. ``samples`` (each row's model sample): its
    mean is taken out of the record correlations, and with ``sample_effect`` the samples are a
    random effect of the simulation. Rows with a NaN ``low`` are left out."""
    low, high = np.asarray(low, float), np.asarray(high, float)
    used = np.isfinite(low)
    low, high = low[used], high[used]
    clusters = None if clusters is None else np.asarray(clusters)[used]
    events = None if events is None else np.asarray(events)[used]
    samples = None if samples is None else np.asarray(samples)[used]
    if censor_at is None:
        censor = np.where(np.isinf(high), low, np.inf)
    else:
        censor = np.asarray(censor_at, float)[used]
        censor = np.where(np.isinf(high), low, np.where(np.isfinite(censor), censor, np.inf))
    fit = fit_intervals(low, high) if fit is None else fit
    observed = goodness_of_fit(low, high, fit.median, fit.beta, seed=seed)
    mu, beta = math.log(fit.median), fit.beta
    z = (_representative(low, high) - mu) / beta
    rho_r, rho_e, rho_s = cluster_correlations(z, clusters, events, samples)
    exact = low == high
    bracketed = np.isfinite(high) & (low > 0) & ~exact
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(bracketed, high / low, np.nan)
    typical = float(np.nanmedian(ratio)) if np.any(bracketed) else 1.05
    ratio = np.where(exact, 1.0, np.where(bracketed, ratio, typical))
    n = low.size
    c_code = np.unique(clusters if clusters is not None else np.arange(n), return_inverse=True)[1]
    e_code = np.unique(events, return_inverse=True)[1] if events is not None else None
    s_code = np.unique(samples, return_inverse=True)[1] if samples is not None and sample_effect else None
    rho_s_sim = rho_s if s_code is not None else 0.0
    rng = np.random.default_rng(seed + 1)
    stats_sim = []
    for j in range(n_simulations):
        zz = math.sqrt(max(1.0 - rho_r - rho_s_sim, 0.0)) * rng.standard_normal(n)
        if s_code is not None:
            zz += math.sqrt(rho_s_sim) * rng.standard_normal(s_code.max() + 1)[s_code]
        zz += math.sqrt(rho_r - rho_e) * rng.standard_normal(c_code.max() + 1)[c_code]
        if e_code is not None:
            zz += math.sqrt(rho_e) * rng.standard_normal(e_code.max() + 1)[e_code]
        x = np.exp(mu + beta * zz)
        top = x * ratio ** rng.uniform(0.0, 1.0, n)
        s_low, s_high = top / ratio, top
        over = x > censor
        s_low, s_high = np.where(over, censor, s_low), np.where(over, np.inf, s_high)
        try:
            f = fit_intervals(s_low, s_high, tol=1e-9)
            stats_sim.append(goodness_of_fit(s_low, s_high, f.median, f.beta, seed=seed + 2 + j).statistic)
        except FitError:
            continue
    if len(stats_sim) < 10:
        raise FitError(f"only {len(stats_sim)} of {n_simulations} simulated data sets could be fitted")
    stats_sim = np.array(stats_sim)
    p = (1.0 + np.sum(stats_sim >= observed.statistic)) / (1.0 + stats_sim.size)
    return CalibratedCheck(observed.statistic, observed.p_value, float(p), int(stats_sim.size), rho_r, rho_e, seed,
                           rho_s)


# ------------------------------------------------------------------ all of it

@dataclass
class MixtureFragility:
    """The calibrated fragility as a mixture of its model samples (:func:`mixture_fragility`)."""

    fits: SampleFits
    im: np.ndarray  #: grid
    curve: np.ndarray  #: the mixture at im
    median: float
    percentiles: dict  #: level -> curve over the samples
    models: dict  #: model -> its own curve
    band: MixtureBand
    pooled: FragilityFit
    check: CalibratedCheck
    strata_source: str = ""  #: the stratified samples file ('' : equal weights)

    @property
    def pooled_holds(self) -> bool:
        return self.check.holds

    def model_medians(self) -> dict[str, float]:
        if self.fits.models is None:
            return {}
        models = np.array(self.fits.models)
        return {m: mixture_quantile(0.5, self.fits.medians[models == m], self.fits.betas[models == m],
                                    self.fits.weights[models == m]) for m in dict.fromkeys(self.fits.models)}


def mixture_fragility(low, high, param_set, im_grid, clusters=None, events=None, cluster_by: str = "",
                      weights: dict | None = None, models: dict | None = None, censor_at=None,
                      n_bootstrap: int = 400, n_simulations: int = 200, level: float = 0.90,
                      seed: int = 20261124, strata_source: str = "") -> MixtureFragility:
    """Fits, mixture, percentile and model curves, the two-stage band, the pooled fit and its
    calibrated check, from the rows' brackets (``low``, ``high``] (NaN: left out) and each
    row's ``param_set``."""
    low, high = np.asarray(low, float), np.asarray(high, float)
    fits = fit_samples(low, high, param_set, weights, models)
    im_grid = np.asarray(im_grid, float)
    band = mixture_band(low, high, param_set, fits, im_grid, clusters, events, cluster_by, n_bootstrap, level, seed)
    used = np.isfinite(low)
    pooled = fit_intervals(low[used], high[used])
    check = calibrated_fit_check(low, high, pooled, clusters, events, censor_at, n_simulations, seed, param_set)
    return MixtureFragility(fits, im_grid, fits.cdf(im_grid), fits.median(), percentile_curves(im_grid, fits),
                            model_curves(im_grid, fits), band, pooled, check, strata_source)
