"""``voussoir-diagnose``: campaign diagnosis (shared/MEASURED_DATA.md).

Subcommands:

- ``check CAMPAIGN``: validate the folder and print a summary; exit 0 when valid,
  2 with ``file:line:column: message`` when not.
- ``run CAMPAIGN --out DIR [--np N]``: the full diagnosis (report.md + diagnosis.json),
  see diagnosis.py.

Each subcommand is a ``cmd_<name>(args) -> int`` function registered in
:func:`build_parser`; adding one means adding its parser and function.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import warnings

from ..readers.campaign import Campaign, CampaignError, CampaignWarning, measured_thresholds, read_campaign
from ..runner import RunError
from ..tables import Table, format_table

__all__ = ["main", "build_parser", "campaign_summary"]


def _mm(value_m: float | None) -> float | None:
    return None if value_m is None else 1e3 * value_m


def campaign_summary(campaign: Campaign) -> str:
    """A readable summary of a validated campaign: specimens with geometry, tests per
    specimen and frequency with the measured thresholds and brackets, records, hinges."""
    out = [f"Campaign '{campaign.name}' ({campaign.path}): valid",
           f"{len(campaign.specimens)} specimens, {len(campaign.tests)} tests, "
           f"{len(campaign.records)} records, {len(campaign.hinges)} hinge files", ""]

    out.append(format_table(Table(
        ["specimen", "embrace_deg", "n_voussoirs", "r_ext_mm", "thickness_mm", "t/R_mean", "width_mm",
         "density_kg_m3", "friction", "tests"],
        [(s.specimen_id, s.embrace_deg, s.n_voussoirs, 1e3 * s.r_ext_m, 1e3 * s.thickness_m,
          s.thickness_ratio_mean, 1e3 * s.width_m, s.density_kg_m3, s.friction, len(campaign.tests_of(s.specimen_id)))
         for s in campaign.specimens.values()],
        title="Specimens")))
    out.append("")

    thresholds = measured_thresholds(campaign)
    rows = []
    for m in thresholds:
        tests = [campaign.tests[t] for t in m.test_ids]
        amps = ", ".join(f"{1e3 * t.amplitude_m:g}{'c' if t.collapsed else 's'}"
                         for t in sorted(tests, key=lambda t: t.amplitude_m))
        bracket = f"({_fmt_mm(m.low_m)}, {_fmt_mm(m.high_m)}]"
        rows.append((m.specimen_id, m.frequency_hz, len(tests), m.n_stand, m.n_collapse, amps,
                     _mm(m.threshold_m), bracket, m.threshold_accel_m_s2, m.non_monotonic))
    out.append(format_table(Table(
        ["specimen", "frequency_hz", "tests", "stand", "collapse", "amplitudes_mm (s/c)", "threshold_mm",
         "bracket_mm", "threshold_accel_m_s2", "non_monotonic"],
        rows, title="Tests per specimen and frequency; measured threshold = midpoint of the bracket "
                    "(largest stand below, smallest collapse], or the smallest collapse when no "
                    "stand lies below ('-'); amplitudes: s = stand, c = collapse")))
    others = [t for t in campaign.tests.values() if t.frequency_hz is None or t.amplitude_m is None]
    if others:
        out.append("Tests without frequency and amplitude (not in a threshold pair): "
                   + ", ".join(f"{t.test_id} ({t.specimen_id}, {t.waveform}, {t.outcome})" for t in others))
    out.append("")

    if campaign.records:
        out.append(format_table(Table(
            ["test", "specimen", "waveform", "samples", "dt_s", "duration_s", "peak_table_x_mm", "crown"],
            [(tid, campaign.tests[tid].specimen_id, campaign.tests[tid].waveform, r.t_s.size, r.dt_s,
              r.duration_s, 1e3 * float(abs(r.table_x_m).max()),
              "dx,dy" if r.crown_dx_m is not None and r.crown_dy_m is not None
              else ("dx" if r.crown_dx_m is not None else ("dy" if r.crown_dy_m is not None else "-")))
             for tid, r in campaign.records.items()],
            title="Records (records/<test_id>.csv)")))
    else:
        out.append("Records: none")
    out.append("")
    if campaign.hinges:
        out.append(format_table(Table(
            ["test", "specimen", "hinges (t_s joint side)"],
            [(tid, campaign.tests[tid].specimen_id,
              "; ".join(f"{h.t_s:g} {h.joint}{h.side[0]}" for h in hs) or "-")
             for tid, hs in campaign.hinges.items()],
            title="Observed hinges (hinges/<test_id>.csv; i = intrados, e = extrados)")))
    else:
        out.append("Hinges: none")
    if campaign.warnings:
        out.append("")
        out.append("Warnings:")
        out.extend(f"  {w}" for w in campaign.warnings)
    return "\n".join(out)


def _fmt_mm(value_m: float) -> str:
    return "-" if value_m is None or math.isnan(value_m) else f"{1e3 * value_m:g}"


def cmd_check(args) -> int:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", CampaignWarning)  # they are printed in the summary
        campaign = read_campaign(args.campaign)
    print(campaign_summary(campaign))
    return 0


def _default_bin_dir() -> str:
    here = os.path.dirname(os.path.abspath(__file__))
    return os.environ.get("VOUSSOIR_BIN_DIR", os.path.join(here, "..", "..", "build", "drivers"))


def cmd_run(args) -> int:
    from pathlib import Path

    from ..diagnosis.pipeline import DiagnosisSettings, diagnose
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", CampaignWarning)
        read_campaign(args.campaign)  # refuse an invalid folder before anything else
    bin_dir = Path(args.bin_dir or _default_bin_dir()).resolve()
    for exe in ("voussoir-run", "voussoir-sweep"):
        if not (bin_dir / exe).is_file():
            print(f"voussoir-diagnose: error: {bin_dir / exe} not found: build the project or give --bin-dir",
                  file=sys.stderr)
            return 2
    if args.np < 1 or args.dt <= 0:
        print("voussoir-diagnose: error: --np must be >= 1 and --dt > 0", file=sys.stderr)
        return 2
    out = args.out or os.path.join(os.getcwd(), "diagnosis_" + os.path.basename(os.path.normpath(args.campaign)))
    settings = DiagnosisSettings(bin_dir=bin_dir, n_ranks=args.np, dt_s=args.dt,
                                 log=lambda m: print(m, flush=True))
    result = diagnose(args.campaign, out, settings)
    print(f"verdict: {result['verdict']}; threshold error {result['baseline']['threshold_error_pct']:.1f} % "
          f"(nominal) -> {result['extended']['threshold_error_pct']:.1f} % (extended, held out); "
          f"report: {os.path.join(out, 'report.md')}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="voussoir-diagnose",
                                     description="Diagnosis of a shaking-table campaign folder "
                                                 "(shared/MEASURED_DATA.md).")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    p = sub.add_parser("check", help="validate a campaign folder and print a summary")
    p.add_argument("campaign", metavar="CAMPAIGN")
    p.set_defaults(func=cmd_check)
    p = sub.add_parser("run", help="simulate every test, compare, name the cause, write report.md and "
                                   "diagnosis.json")
    p.add_argument("campaign", metavar="CAMPAIGN")
    p.add_argument("--out", metavar="DIR", help="output folder for report.md and diagnosis.json "
                                                "(default: ./diagnosis_<campaign>)")
    p.add_argument("--np", type=int, default=2, help="MPI ranks of the sweeps (default 2)")
    p.add_argument("--dt", type=float, default=1.0e-3, help="time step of the simulations [s] (default 1e-3)")
    p.add_argument("--bin-dir", help="folder of the Fortran executables (default $VOUSSOIR_BIN_DIR or "
                                     "<repo>/build/drivers)")
    p.set_defaults(func=cmd_run)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``voussoir-diagnose``; returns the exit status."""
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except BrokenPipeError:  # stdout closed early (piped into head): end quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except CampaignError as exc:
        print(str(exc), file=sys.stderr)
        return 2
    except RunError as exc:  # an executable failed: its own message says why
        print(f"voussoir-diagnose: error: a simulation failed: {exc}", file=sys.stderr)
        return 1
    except ValueError as exc:  # e.g. no pair with a collapse: nothing to compare
        print(f"voussoir-diagnose: error: {exc}", file=sys.stderr)
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
