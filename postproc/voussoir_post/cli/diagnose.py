"""``voussoir-diagnose``: campaign diagnosis (docs/measured_data.md).

Subcommands:

- ``check CAMPAIGN``: validate the folder and print a summary; exit 0 when valid,
  2 with ``file:line:column: message`` when not.
- ``run CAMPAIGN --out DIR [--np N]``: the full diagnosis (report.md + diagnosis.json),
  see :mod:`voussoir_post.diagnosis.pipeline`.

Each subcommand is a ``cmd_<name>(args) -> int`` function registered in
:func:`build_parser`; adding one means adding its parser and function. Errors and exit
statuses are :func:`.entry.run_command`'s (0 done, 1 the work failed, 2 bad input).
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings
from pathlib import Path

from ..errors import DONE, InputError
from ..readers.campaign import CampaignWarning, read_campaign
from ..readers.campaign_summary import campaign_summary
from ..runner import BIN_DIR_ENV, find_bin_dir, installed_bin_dir_file
from .entry import run_command

__all__ = ["main", "build_parser"]


def cmd_check(args) -> int:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", CampaignWarning)  # they are printed in the summary
        campaign = read_campaign(args.campaign)
    print(campaign_summary(campaign))
    from ..diagnosis.report import METHOD_CHECK, prior_text
    from ..diagnosis.settings import DiagnosisSettings
    frictions = {s.friction for s in campaign.specimens.values()}
    print("\nHow `voussoir-diagnose run` would weigh it (docs/measured_data.md version 4): posterior "
          "probabilities of the nominal model, of each effect and of each pair, a cause named at 0.9.\n"
          + prior_text(DiagnosisSettings(bin_dir=Path(".")), frictions.pop() if len(frictions) == 1 else None
                       ).replace("`", "") + "\n" + METHOD_CHECK)
    return DONE


def cmd_run(args) -> int:
    from ..diagnosis.pipeline import DiagnosisSettings, diagnose
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", CampaignWarning)
        read_campaign(args.campaign)  # refuse an invalid folder before anything else
    bin_dir = find_bin_dir(args.bin_dir, ("voussoir-run", "voussoir-sweep"))
    if args.np < 1 or args.dt <= 0:
        raise InputError("--np must be >= 1 and --dt > 0")
    if not 0.0 <= args.build_tolerance <= 0.2:
        raise InputError(f"--build-tolerance {args.build_tolerance:g}: a relative standard deviation between 0 "
                         "and 0.2 (0.015 is 1.5 %)")
    out = args.out or os.path.join(os.getcwd(), "diagnosis_" + os.path.basename(os.path.normpath(args.campaign)))
    settings = DiagnosisSettings(bin_dir=bin_dir, n_ranks=args.np, dt_s=args.dt, figure_format=args.format,
                                 build_tolerance=args.build_tolerance, crown_records=args.crown_records,
                                 log=lambda m: print(m, flush=True))
    result = diagnose(args.campaign, out, settings)
    top = sorted(result["probabilities"].items(), key=lambda kv: -kv[1])[:3]
    print(f"verdict: {result['verdict']} (" + ", ".join(f"{m} {p:.2f}" for m, p in top) + "); threshold error "
          f"{result['baseline']['threshold_error_pct']:.1f} % (nominal) -> "
          f"{result['extended']['threshold_error_pct']:.1f} % (reported model, held out); "
          f"report: {os.path.join(out, 'report.md')}")
    return DONE


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="voussoir-diagnose",
                                     description="Diagnosis of a shaking-table campaign folder "
                                                 "(docs/measured_data.md).")
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
    p.add_argument("--format", choices=("png", "pdf", "svg"), default="png",
                   help="format of report.md's figures (default png, 200 dpi)")
    p.add_argument("--build-tolerance", type=float, default=0.015, metavar="FRACTION",
                   help="how far the specimens as built may lie from their stated ring thickness, a relative "
                        "standard deviation (default 0.015; 0 for specimens made exactly)")
    p.add_argument("--crown-records", action="store_true",
                   help="weigh the crown records (crown_dx_m) of tests that stood near their threshold, and advise "
                        "tests held below it with the crown recorded (not yet calibrated across codes: "
                        "docs/diagnosis.md)")
    p.add_argument("--bin-dir", help=f"folder of the Fortran executables (default: ${BIN_DIR_ENV}, else the "
                                     f"folder scripts/setup.sh wrote into {installed_bin_dir_file()}, else PATH)")
    p.set_defaults(func=cmd_run)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``voussoir-diagnose``; returns the exit status."""
    return run_command(build_parser(), argv)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
