"""``voussoir-post risk HAZARD [FRACTILES ...]``: the collapse risk at a site, a lognormal
fragility integrated with the site's hazard curve (:mod:`voussoir_post.earthquake.risk`):
the mean annual frequency of collapse, the probability in 50 years (or --years), the
collapse margin ratio against an MCE, each with its band (hazard fractiles, the
fragility's bootstrap, its model samples; FEMA P695's model-form dispersions added when
rated), and the figure of the hazard, the fragility and the rate's disaggregation. The
hazard: a plain CSV, the JSON of the USGS hazard service, or OpenQuake's hazard-curve CSVs
(:mod:`voussoir_post.earthquake.hazard`). The fragility: its median and beta, or
``voussoir-post fragility --json`` (its PGA fit, bootstrap resamples and model samples)."""

from __future__ import annotations

import json

from ..errors import DONE, InputError

__all__ = ["add_risk_parser", "cmd_risk"]

RATINGS = ("superior", "good", "fair", "poor")


def _fragility(args):
    """(median [g], beta, source, draws) of the fragility the command was given."""
    from ..earthquake.risk import FragilityDraws

    if args.fragility_json:
        if args.median_g is not None or args.beta is not None:
            raise InputError("give the fragility either as --fragility-json or as --median-g and --beta")
        try:
            data = json.loads(open(args.fragility_json).read())
            median, beta = float(data["median_pga_g"]), float(data["beta_pga"])
        except (OSError, ValueError, KeyError, TypeError) as e:
            raise InputError(f"{args.fragility_json}: not the JSON of voussoir-post fragility --json "
                             f"(median_pga_g, beta_pga): {e}") from None
        draws = []
        mixture = data.get("mixture")
        for kind, m_key, b_key in (("bootstrap", "bootstrap_median_pga_g", "bootstrap_beta_pga"),
                                   ("model samples", "median_pga_g_by_sample", "beta_pga_by_sample")):
            if kind == "model samples" and mixture:
                continue  # the mixture's samples, with their weights, below
            medians, betas = data.get(m_key), data.get(b_key)
            if medians and betas and len(medians) > 1:
                draws.append(FragilityDraws(kind, medians, betas))
        point_mixture = None
        if mixture:
            try:
                samples = FragilityDraws("model samples", mixture["sample_median_pga_g"], mixture["sample_beta_pga"],
                                         weights=mixture["sample_weight"])
                resamples = mixture.get("bootstrap_draws") or []
                if resamples:
                    draws.append(FragilityDraws(
                        "mixture bootstrap", [m for r in resamples for m in r["median_pga_g"]],
                        [b for r in resamples for b in r["beta_pga"]],
                        weights=[w for r in resamples for w in r["weight"]],
                        groups=[k for k, r in enumerate(resamples) for _ in r["weight"]]))
                draws.append(samples)
                if not mixture["pooled_holds"]:
                    point_mixture = samples
                    median = float(mixture["median_pga_g"])
                    # the pooled fit's own bootstrap is of the rejected fit: the mixture's replaces it
                    draws = [d for d in draws if d.kind != "bootstrap"]
            except (KeyError, TypeError, ValueError) as e:
                raise InputError(f"{args.fragility_json}: its 'mixture' is not that of voussoir-post fragility --json: "
                                 f"{e}") from None
        source = args.fragility_json
        if point_mixture is not None:
            source += (f"; the mixture of its {point_mixture.medians_g.size} model samples (the pooled lognormal's "
                       f"goodness of fit failed: p {mixture['pooled_gof_p_calibrated']:.2g}, calibrated)")
        elif mixture:
            source += (f"; the pooled lognormal (its goodness of fit holds: p "
                       f"{mixture['pooled_gof_p_calibrated']:.2g}, calibrated)")
        return median, beta, source, draws, point_mixture
    if args.median_g is None or args.beta is None:
        raise InputError("the fragility: give --median-g and --beta, or --fragility-json FILE")
    return args.median_g, args.beta, "given", [], None


def _fmt_band(quantiles: dict, fmt: str = ".3g") -> str:
    return ", ".join(f"{100 * q:g} %: {v:{fmt}}" for q, v in quantiles.items())


def risk_summary(args, hazard, median, beta, source, band) -> dict:
    """The numbers of the command (for --json)."""
    from ..earthquake.risk import P695_SOURCE, RiskBand

    r = band.point
    years = r.years
    frag = {kind: {"n_draws": d["n"], "annual_rate_quantiles": {f"{q:g}": v for q, v in d["quantiles"].items()},
                   "p_collapse_50yr_quantiles": {f"{q:g}": RiskBand.p_in(v, 50.0) for q, v in d["quantiles"].items()},
                   "mean_annual_rate": d["mean"],
                   "median_quantiles_g": {f"{q:g}": v for q, v in d["median_quantiles_g"].items()},
                   "collapse_margin_ratio_quantiles": None if d["margin_quantiles"] is None else
                   {f"{q:g}": v for q, v in d["margin_quantiles"].items()}}
            for kind, d in band.fragility.items()}
    return {
        "hazard": hazard.mean.source,
        "hazard_fractile_files": {f"{q:g}": c.source for q, c in hazard.fractiles.items()},
        "hazard_notes": list(hazard.mean.notes), "measure": hazard.measure,
        "fragility": source, "median_g": median, "median_pga_g": median if hazard.measure == "PGA" else None,
        "beta_fit": beta, "beta_pga": beta if hazard.measure == "PGA" else None,
        "model_form": {"rating_dr": band.model_form.rating_dr, "rating_td": band.model_form.rating_td,
                       "rating_mdl": band.model_form.rating_mdl, "beta_dr": band.model_form.beta_dr,
                       "beta_td": band.model_form.beta_td, "beta_mdl": band.model_form.beta_mdl,
                       "beta_model_form": band.model_form.beta, "source": P695_SOURCE},
        "beta_total": band.beta_total,
        "annual_rate_of_collapse": r.annual_rate, "return_period_yr": 1.0 / r.annual_rate,
        "p_collapse_50yr": r.p_50yr, "years": years, "p_collapse_years": r.p_years,
        "annual_rate_without_model_form": (None if band.point_without_model_form is None
                                           else band.point_without_model_form.annual_rate),
        "collapse_margin_ratio": r.margin_ratio, "mce_g": args.mce_g, "share_beyond_hazard_file": r.beyond_fraction,
        "band_levels": list(band.levels),
        "annual_rate_on_hazard_fractiles": {f"{q:g}": v for q, v in band.hazard_fractiles.items()},
        "p_collapse_50yr_on_hazard_fractiles": {f"{q:g}": RiskBand.p_in(v, 50.0)
                                                for q, v in band.hazard_fractiles.items()},
        "fragility_bands": frag,
        "combined_band_with": band.combined_with or None, "beta_hazard": band.beta_hazard,
        "annual_rate_combined_quantiles": {f"{q:g}": v for q, v in band.combined.items()},
        "p_collapse_50yr_combined_quantiles": {f"{q:g}": RiskBand.p_in(v, 50.0) for q, v in band.combined.items()},
        "band_method": band.method,
    }


def report_lines(args, hazard, median, beta, source, band) -> list[str]:
    """The command's text output."""
    from ..earthquake.hazard import measure_words
    from ..earthquake.risk import P695_SOURCE, RiskBand

    r, m = band.point, measure_words(hazard.measure)
    c = hazard.mean
    mixed = "the mixture of its" in source
    lines = [f"fragility: {m} median {median:.4g} g, " + ("a mixture of lognormals" if mixed else f"beta {beta:.3g}")
             + f" ({source})",
             f"hazard: {c.source}, {m} {c.pga_g[0]:.3g} to {c.pga_g[-1]:.3g} g, annual rates {c.annual_rate[0]:.3g} to "
             f"{c.annual_rate[-1]:.3g} /yr (log-log interpolated)"
             + (f"; fractiles {', '.join(f'{q:g}' for q in hazard.fractiles)}" if hazard.fractiles else "")]
    lines += [f"  {note}" for note in c.notes]
    lines.append(band.model_form.words() + (f"; beta {beta:.3f} -> {band.beta_total:.3f} (SRSS)"
                                            if band.model_form.rated else ""))
    if band.model_form.rated:
        lines.append(f"  source: {P695_SOURCE}")
    lines.append(f"mean annual frequency of collapse: {r.annual_rate:.4g} /yr (return period "
                 f"{1 / r.annual_rate:.4g} yr)"
                 + (f"; {band.point_without_model_form.annual_rate:.4g} /yr without the model-form part"
                    if band.point_without_model_form is not None else ""))
    lines.append(f"probability of collapse in 50 years: {r.p_50yr:.4g}"
                 + (f"; in {r.years:g} years: {r.p_years:.4g}" if r.years != 50 else ""))
    if r.margin_ratio is not None:
        lines.append(f"collapse margin ratio (median over the MCE's {args.mce_g:g} g): {r.margin_ratio:.3g}")
    lines.append(f"share of the rate from intensities beyond the hazard file's range (its end power laws extended): "
                 f"{100 * r.beyond_fraction:.2g} %")
    if band.hazard_fractiles:
        lines.append("on the hazard fractiles: " + "; ".join(
            f"{q:g}: {v:.3g} /yr, P(50 yr) {RiskBand.p_in(v, 50):.3g}" for q, v in band.hazard_fractiles.items()))
    for kind, d in band.fragility.items():
        few = " (few draws: the quantiles interpolate between them)" if d["n"] < 10 else ""
        lines.append(f"{kind} ({d['n']} fragilities{few}): annual rate {_fmt_band(d['quantiles'])} /yr; P(50 yr) "
                     + _fmt_band({q: RiskBand.p_in(v, 50) for q, v in d["quantiles"].items()})
                     + (f"; mixture (weighted mean of the samples' curves) {d['mean']:.3g} /yr"
                        if kind == "model samples" else "")
                     + ("" if d["margin_quantiles"] is None else
                        f"; margin ratio {_fmt_band(d['margin_quantiles'])}"))
    if band.combined:
        lines.append(f"combined (hazard fractiles x {band.combined_with}): annual rate {_fmt_band(band.combined)} /yr; "
                     f"P(50 yr) " + _fmt_band({q: RiskBand.p_in(v, 50) for q, v in band.combined.items()}))
    elif band.hazard_fractiles or band.fragility:
        lines.append("combined band: not made (it needs a pair of hazard fractiles q, 1 - q and fragility draws)")
    lines += [f"  how: {text}" for text in band.method]
    return lines


def cmd_risk(args) -> int:
    from ..earthquake.hazard import normalise_measure, read_hazard_set
    from ..earthquake.risk import model_form, risk_band

    median, beta, source, draws, point_mixture = _fragility(args)
    measure = normalise_measure(getattr(args, "measure", None) or "PGA")
    if args.fragility_json and measure != "PGA":
        raise InputError(f"--fragility-json gives the PGA fit; for {measure} give --median-g and --beta")
    files = [args.hazard] if isinstance(args.hazard, str) else list(args.hazard)
    hazard = read_hazard_set(files, measure=measure, site=getattr(args, "site", None))
    form = model_form(getattr(args, "rating_dr", None), getattr(args, "rating_td", None),
                      getattr(args, "rating_mdl", None))
    if args.years <= 0:
        raise InputError(f"--years must be > 0 (got {args.years})")
    band = risk_band(hazard, median, beta, draws, form, years=args.years, mce_g=args.mce_g,
                     combine={"samples": "model samples", "mixture": "mixture bootstrap"}.get(
                         getattr(args, "combine", None), getattr(args, "combine", None)), mixture=point_mixture)
    summary = risk_summary(args, hazard, median, beta, source, band)
    if args.json:
        print(json.dumps(summary, indent=1))
    else:
        print("\n".join(report_lines(args, hazard, median, beta, source, band)))
    from ..plots.risk_plot import plot_risk  # matplotlib when the command runs
    from .post import figure_path
    path = figure_path(files[0], "risk", args)
    plot_risk(path, hazard, median, band.beta_total, band.point, band=band, mixture=point_mixture)
    if not args.json:
        print(f"wrote {path}")
    return DONE


def add_risk_parser(sub, figure_format) -> None:
    p = sub.add_parser(
        "risk", help="collapse risk at a site: a fragility integrated with the site's hazard curve (mean annual "
                     "frequency, probability in 50 years, margin ratio, with their bands)",
        description="The mean annual frequency of collapse, its probability in 50 years and the collapse margin "
                    "ratio of a lognormal fragility at a site, with bands from the hazard's fractiles, the "
                    "fragility's bootstrap and its model samples, and FEMA P695's model-form dispersions when rated "
                    "(docs/earthquakes.md, 'Collapse risk at a site').")
    p.add_argument("hazard", metavar="HAZARD", nargs="+",
                   help="the site's hazard curve and, after it or in any order, its fractile curves: a CSV with "
                        "columns pga_g and annual_rate (mean annual frequency of exceedance [1/yr]) and optionally "
                        "annual_rate_q0.16 ...; the JSON of the USGS hazard service (its component Total); or "
                        "OpenQuake's hazard_curve-mean-<IMT>_<id>.csv and quantile_curve-<q>-<IMT>_<id>.csv "
                        "(PoE in investigation_time turned into annual rates)")
    p.add_argument("--measure", default="PGA",
                   help="the intensity measure of the fragility and the hazard: PGA (default) or SA(T), e.g. SA(1.0) "
                        "(then give --median-g and --beta in g of Sa)")
    p.add_argument("--site", type=int, help="the site of an OpenQuake file of several, 0 for its first row")
    p.add_argument("--median-g", type=float, help="the fragility's median [g]")
    p.add_argument("--beta", type=float, help="the fragility's lognormal dispersion (record-to-record, as fitted)")
    p.add_argument("--fragility-json", metavar="FILE",
                   help="the output of voussoir-post fragility --json: its PGA fit, and the band from its bootstrap "
                        "resamples and its model samples' own fits when it gives them")
    for flag, what in (("--rating-dr", "design requirements"), ("--rating-td", "test data"),
                       ("--rating-mdl", "model (its validity under recorded motion included)")):
        p.add_argument(flag, choices=RATINGS, type=str.lower,
                       help=f"FEMA P695 quality rating of the {what}: superior 0.10, good 0.20, fair 0.35, poor 0.50, "
                            f"added to beta by the square root of the sum of squares (not rated: 0)")
    p.add_argument("--combine", choices=("bootstrap", "samples", "mixture"),
                   help="the fragility draws combined with the hazard fractiles into one band (default: the "
                        "mixture's two-stage bootstrap when the JSON has a mixture, else the bootstrap when given, "
                        "else the model samples)")
    p.add_argument("--years", type=float, default=50.0, help="the period of the probability of collapse (default 50)")
    p.add_argument("--mce-g", type=float,
                   help="the maximum considered earthquake's intensity [g], for the margin ratio")
    p.add_argument("--json", action="store_true", help="print the numbers as JSON")
    p.add_argument("--out", help="output figure file (.png, .pdf or .svg) or folder (default: beside the hazard file)")
    figure_format(p)
    p.set_defaults(func=cmd_risk)
