"""``voussoir-post bridge-report LIMIT.json [--without-passive LIMIT2.json] --out DIR``: a
bridge assessed by ``voussoir-limit --json`` as a report for an assessor, DIR/report.md
and its figures (the mechanism at the critical position, of each file; the load factor
against the vehicle's position, both cases in one figure) (docs/bridges.md, "The bridge
report")."""

from __future__ import annotations

import math
import os

from ..errors import DONE

__all__ = ["add_bridge_report_parser", "cmd_bridge_report"]

#: The report's files in DIR.
REPORT_NAME = "report.md"
FIGURE_NAMES = {"mechanism": "mechanism.png", "mechanism_without_passive": "mechanism_without_passive.png",
                "load_position": "load_position.png"}


def _curve_case(label: str, summary):
    import numpy as np

    from ..plots.load_position import CurveCase

    lim = summary.limit
    return CurveCase(label, np.array([x for x, _ in lim.load_factor_curve]),
                     np.array([v for _, v in lim.load_factor_curve]), np.array(lim.curve_at_joint, dtype=bool),
                     lim.critical_x_m, lim.load_factor)


def cmd_bridge_report(args) -> int:
    from ..analysis.bridge_report import bridge_summary, check_pair, report_markdown
    from ..plots.drawing import provenance
    from ..plots.load_position import plot_load_position
    from ..plots.mechanism import plot_mechanism
    from ..readers.limit_results import read_limit_json

    main = bridge_summary(read_limit_json(args.limit))
    without = None
    if args.without_passive:
        without = bridge_summary(read_limit_json(args.without_passive))
        check_pair(main, without)
    out = args.out or os.path.splitext(args.limit)[0] + "_report"
    os.makedirs(out, exist_ok=True)
    figures = {}
    for key, summary in (("mechanism", main), ("mechanism_without_passive", without)):
        if summary is not None:
            plot_mechanism(summary.limit, os.path.join(out, FIGURE_NAMES[key]))
            figures[key] = FIGURE_NAMES[key]
    rows = []
    if main.limit.load_factor_curve:
        labels = ("as given", None) if without is None else (
            f"with the fill's passive pressure (mobilisation {main.passive_mobilisation:g})",
            "without the passive pressure (active only)")
        cases = [_curve_case(labels[0], main)] + ([_curve_case(labels[1], without)] if without else [])
        spans = ", ".join(f"{s.span_m:g} m" for s in main.spans)
        title = (f"Collapse load factor against the vehicle's position: the bridge of "
                 f"{os.path.basename(main.limit.input_file)} "
                 f"(span{'s' if len(main.spans) > 1 else ''} {spans}),\n"
                 + (f"the {main.vehicle}, " if main.vehicle else "")
                 + f"live load {main.live_total_n / 1e3:.4g} kN on the strip "
                 + ("on the extrados" if main.fill_density_kg_m3 <= 0 else
                    "spread through the fill by Boussinesq" if main.dispersion == "boussinesq" else
                    f"spread through the fill at {main.dispersion_angle_deg:g}°"))
        data = plot_load_position(cases, main.live_total_n, os.path.join(out, FIGURE_NAMES["load_position"]), title,
                                  provenance(main.limit.code_version, os.path.basename(main.limit.path),
                                             os.path.basename(without.limit.path) if without else ""))
        figures["load_position"] = FIGURE_NAMES["load_position"]
        rows = data.table.rows
    report = os.path.join(out, REPORT_NAME)
    with open(report, "w", encoding="utf-8") as f:
        f.write(report_markdown(main, without, figures, rows))
    print(f"load factor {main.load_factor:.6g}" + (f" at x = {main.limit.critical_x_m:.4g} m"
                                                  if math.isfinite(main.limit.critical_x_m) else ""))
    if without is not None:
        print(f"without the passive pressure {without.load_factor:.6g}")
    for name in [REPORT_NAME, *figures.values()]:
        print(f"wrote {os.path.join(out, name)}")
    return DONE


def add_bridge_report_parser(sub) -> None:
    p = sub.add_parser("bridge-report", help="a bridge's limit analysis (voussoir-limit --json on &bridge) as a "
                                             "report: geometry, loads, load factor, mechanism, load-position curve",
                       description="Write DIR/report.md and its figures (mechanism.png, load_position.png; with "
                                   "--without-passive also mechanism_without_passive.png) from voussoir-limit --json "
                                   "of a &bridge input with a live load of &load (docs/bridges.md, 'The bridge "
                                   "report').")
    p.add_argument("limit", metavar="LIMIT.json", help="voussoir-limit --json of the bridge (with the fill's passive "
                                                       "pressure, when --without-passive is given)")
    p.add_argument("--without-passive", metavar="LIMIT2.json",
                   help="the same bridge and load with passive_mobilisation = 0: its load factor, mechanism and "
                        "curve beside the first's")
    p.add_argument("--out", metavar="DIR", help="the report's folder (default: <LIMIT stem>_report beside it)")
    p.set_defaults(func=cmd_bridge_report)
