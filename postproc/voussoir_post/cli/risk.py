"""``voussoir-post risk HAZARD.csv``: the collapse risk at a site, a lognormal fragility in
PGA integrated with the site's hazard curve (:mod:`voussoir_post.earthquake.risk`): the
mean annual frequency of collapse, the probability in 50 years (or --years), the collapse
margin ratio against an MCE, and the figure of the hazard, the fragility and the rate's
disaggregation over PGA. The fragility is given by its median and beta, or read from
``voussoir-post fragility --json`` (its PGA fit)."""

from __future__ import annotations

import json

from ..errors import DONE, InputError

__all__ = ["add_risk_parser", "cmd_risk"]


def _fragility(args) -> tuple[float, float, str]:
    if args.fragility_json:
        if args.median_g is not None or args.beta is not None:
            raise InputError("give the fragility either as --fragility-json or as --median-g and --beta")
        try:
            data = json.loads(open(args.fragility_json).read())
            return float(data["median_pga_g"]), float(data["beta_pga"]), args.fragility_json
        except (OSError, ValueError, KeyError) as e:
            raise InputError(f"{args.fragility_json}: not the JSON of voussoir-post fragility --json "
                             f"(median_pga_g, beta_pga): {e}") from None
    if args.median_g is None or args.beta is None:
        raise InputError("the fragility: give --median-g and --beta, or --fragility-json FILE")
    return args.median_g, args.beta, "given"


def cmd_risk(args) -> int:
    from ..earthquake.risk import collapse_risk, read_hazard

    median, beta, source = _fragility(args)
    hazard = read_hazard(args.hazard)
    r = collapse_risk(hazard, median, beta, years=args.years, mce_g=args.mce_g)
    summary = {"hazard": hazard.source, "fragility": source, "median_pga_g": median, "beta_pga": beta,
               "annual_rate_of_collapse": r.annual_rate, "return_period_yr": 1.0 / r.annual_rate,
               "p_collapse_50yr": r.p_50yr, "years": r.years, "p_collapse_years": r.p_years,
               "collapse_margin_ratio": r.margin_ratio, "share_beyond_hazard_file": r.beyond_fraction}
    if args.json:
        print(json.dumps(summary, indent=1))
    else:
        print(f"fragility: PGA median {median:.4g} g, beta {beta:.3g} ({source})")
        print(f"hazard: {hazard.source}, PGA {hazard.pga_g[0]:.3g} to {hazard.pga_g[-1]:.3g} g, annual rates "
              f"{hazard.annual_rate[0]:.3g} to {hazard.annual_rate[-1]:.3g} /yr (log-log interpolated)")
        print(f"mean annual frequency of collapse: {r.annual_rate:.4g} /yr (return period {1 / r.annual_rate:.4g} yr)")
        print(f"probability of collapse in 50 years: {r.p_50yr:.4g}" +
              (f"; in {r.years:g} years: {r.p_years:.4g}" if r.years != 50 else ""))
        if r.margin_ratio is not None:
            print(f"collapse margin ratio (median over the MCE's {args.mce_g:g} g): {r.margin_ratio:.3g}")
        print(f"share of the rate from PGAs beyond the hazard file's range (its end power laws extended): "
              f"{100 * r.beyond_fraction:.2g} %")
    from ..plots.risk_plot import plot_risk  # matplotlib when the command runs
    from .post import figure_path
    path = figure_path(args.hazard, "risk", args)
    plot_risk(path, hazard, median, beta, r)
    if not args.json:
        print(f"wrote {path}")
    return DONE


def add_risk_parser(sub, figure_format) -> None:
    p = sub.add_parser("risk", help="collapse risk at a site: a PGA fragility integrated with the site's hazard "
                                    "curve (mean annual frequency, probability in 50 years, margin ratio)")
    p.add_argument("hazard", metavar="HAZARD.csv",
                   help="the site's hazard curve: columns pga_g and annual_rate (mean annual frequency of "
                        "exceedance [1/yr])")
    p.add_argument("--median-g", type=float, help="the fragility's median PGA [g]")
    p.add_argument("--beta", type=float, help="the fragility's lognormal dispersion")
    p.add_argument("--fragility-json", metavar="FILE", help="the output of voussoir-post fragility --json")
    p.add_argument("--years", type=float, default=50.0, help="the period of the probability of collapse (default 50)")
    p.add_argument("--mce-g", type=float, help="the maximum considered earthquake's PGA [g], for the margin ratio")
    p.add_argument("--json", action="store_true", help="print the numbers as JSON")
    p.add_argument("--out", help="output figure file (.png, .pdf or .svg) or folder (default: beside the hazard file)")
    figure_format(p)
    p.set_defaults(func=cmd_risk)

