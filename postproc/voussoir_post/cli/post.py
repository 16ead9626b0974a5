"""``voussoir-post``: plots of Voussoir result files.

Every figure subcommand writes its figure(s) beside the input (``<input stem>_<kind>.png``)
or to ``--out`` (a file, written exactly there, or a folder), as PNG (200 dpi), PDF or SVG:
``--format``, or the suffix of ``--out`` (the two must agree; :func:`figure_path`). It
prints the plotted numbers as a table and, with ``--csv``, writes them as CSV beside the
figure (same stem, ``.csv``). Errors and exit statuses are :func:`.entry.run_command`'s:
0 done, 1 the work failed, 2 bad input (the message on stderr names the file).

Each command imports its readers and plots when it runs, not at the top: the program
starts once per subcommand, and matplotlib, scipy.stats and h5py cost seconds that a
command which does not draw or fit should not pay (tests/test_cli_imports.py).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys

from ..earthquake.record_sets import SET_NAMES
from ..errors import DONE, InputError, RecordsError
from ..tables import ReportTable, format_table, write_csv
from .bridge_report import add_bridge_report_parser
from .dtcheck import add_dtcheck_parser
from .risk import add_risk_parser
from .samples import add_samples_parser
from .entry import run_command

__all__ = ["main", "build_parser", "output_path", "figure_path", "FIGURE_FORMATS"]

#: The formats of every figure command (--format; the suffix of an --out file).
FIGURE_FORMATS = ("png", "pdf", "svg")
#: Suffixes of image formats that voussoir-post does not write: an --out ending so is
#: refused rather than made a folder of that name.
_OTHER_IMAGE_SUFFIXES = (".jpg", ".jpeg", ".eps", ".ps", ".tif", ".tiff", ".gif", ".webp", ".bmp")


def output_path(input_path: str, kind: str, out: str | None, ext: str = ".png") -> str:
    """Where a subcommand writes: ``--out`` when it names a file with extension ``ext``,
    ``<out>/<stem>_<kind><ext>`` when it names a folder, else beside the input."""
    stem = os.path.splitext(os.path.basename(input_path))[0]
    name = f"{stem}_{kind}{ext}"
    if out is None:
        return os.path.join(os.path.dirname(os.path.abspath(input_path)), name)
    if out.lower().endswith(ext):
        return out
    return os.path.join(out, name)


def figure_path(input_path: str, kind: str, args) -> str:
    """Where a figure command writes (:func:`output_path` with the figure's suffix): an
    ``--out`` ending in .png, .pdf or .svg is that file, in that format; otherwise
    ``--format`` (default png) names the suffix. InputError when the suffix of ``--out``
    contradicts ``--format``, or names an image format that is not written."""
    out, fmt = args.out, args.format
    suffix = os.path.splitext(out)[1].lower() if out is not None else ""
    if suffix in tuple(f".{f}" for f in FIGURE_FORMATS):
        if fmt is not None and suffix != f".{fmt}":
            raise InputError(f"--out {out} names a {suffix[1:].upper()} file but --format is {fmt}: give one of "
                             f"them, or make them agree (--out {os.path.splitext(out)[0]}.{fmt})")
        return out
    if suffix in _OTHER_IMAGE_SUFFIXES:
        raise InputError(f"--out {out}: voussoir-post writes figures as {', '.join(FIGURE_FORMATS)}; name a "
                         f".png, .pdf or .svg file, or a folder")
    return output_path(input_path, kind, out, f".{fmt or 'png'}")


def _emit(table: ReportTable, png_path: str, csv_wanted: bool, extra: list[tuple[ReportTable, str]] = ()) -> None:
    """Print the table and the written files; write CSV(s) when asked."""
    print(format_table(table))
    print(f"wrote {png_path}")
    if csv_wanted:
        print(f"wrote {write_csv(table, os.path.splitext(png_path)[0] + '.csv')}")
        for tab, suffix in extra:
            print(f"wrote {write_csv(tab, os.path.splitext(png_path)[0] + suffix)}")


def _parse_times(text: str) -> list[float]:
    try:
        times = [float(t) for t in text.split(",") if t.strip()]
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"--times expects comma-separated seconds, got '{text}'") from exc
    if not times:
        raise argparse.ArgumentTypeError("--times is empty")
    return times


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expects a whole number >= 1, got '{text}'") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"expects a whole number >= 1, got {value}")
    return value


def cmd_envelope(args) -> int:
    from ..plots.envelope import plot_envelope
    from ..readers.campaign import read_campaign
    from ..readers.results import read_limit_json, read_sweep

    sweep = read_sweep(args.sweep)
    campaign = read_campaign(args.campaign) if args.campaign else None
    if args.specimen and campaign is None:
        raise InputError("--specimen needs --campaign")
    if campaign is not None and args.specimen:
        for sid in args.specimen:
            if sid not in campaign.specimens:
                raise InputError(f"{campaign.path}: no specimen '{sid}' (has: {', '.join(campaign.specimens)})")
    capacity, source = None, ""
    if args.limit:
        limit = read_limit_json(args.limit)
        capacity = limit.static_capacity_m_s2()
        source = os.path.basename(args.limit)
    png = figure_path(args.sweep, "envelope", args)
    data = plot_envelope(sweep, png, campaign, args.specimen, capacity_m_s2=capacity, capacity_source=source)
    _emit(data.table, data.png_path, args.csv)
    return DONE


def cmd_sequence(args) -> int:
    from ..plots.sequence import default_frame_times, plot_sequence, write_sequence_gif
    from ..readers.results import read_run

    run = read_run(args.run)
    png = figure_path(args.run, "sequence", args)
    open_tol = None if args.open_tol_mm is None else 1e-3 * args.open_tol_mm
    data = plot_sequence(run, png, times_s=args.times, n_frames=args.n_frames, amplify=args.amplify,
                         open_tol_m=open_tol)
    _emit(data.table, data.png_path, args.csv)
    if args.gif:
        t_end = max(f.time_s for f in data.frames) if args.times else float(default_frame_times(run, 2)[-1])
        gif, samples = write_sequence_gif(run, os.path.splitext(png)[0] + ".gif", t_end_s=t_end,
                                          amplify=args.amplify, open_tol_m=open_tol, max_frames=args.gif_frames)
        print(f"wrote {gif} ({len(samples)} frames)")
    return DONE


def cmd_history(args) -> int:
    from ..plots.history import plot_history
    from ..readers.results import read_run

    run = read_run(args.run)
    png = figure_path(args.run, "history", args)
    data = plot_history(run, png)
    print(format_table(data.summary))
    print(f"wrote {data.png_path}")
    if args.csv:
        stem = os.path.splitext(data.png_path)[0]
        print(f"wrote {write_csv(data.samples_table(), stem + '.csv')}")
        print(f"wrote {write_csv(data.steps_table(), stem + '_steps.csv')}")
    return DONE


def cmd_compare(args) -> int:
    from ..plots.compare import mean_error_lines, plot_compare
    from ..readers.campaign import read_campaign
    from ..readers.results import read_sweep

    sweep = read_sweep(args.sweep)
    campaign = read_campaign(args.campaign)
    png = figure_path(args.sweep, "compare", args)
    data = plot_compare(sweep, campaign, png, args.specimen)
    for note in data.notes:
        print(note)
    _emit(data.table, data.png_path, args.csv)
    for line in mean_error_lines(data, sweep):
        print(line)
    return DONE


def cmd_xdmf(args) -> int:
    from ..plots.xdmf import check_xdmf, write_xdmf
    from ..readers.results import read_run

    run = read_run(args.run)
    xmf = None
    if args.out is not None:
        xmf = args.out if args.out.lower().endswith(".xmf") else os.path.join(
            args.out, os.path.splitext(os.path.basename(args.run))[0] + ".xmf")
    data = write_xdmf(run, xmf, every=args.every)
    items = check_xdmf(data.xmf_path)
    print(format_table(data.table(run.path, len(items))))
    print(f"wrote {data.h5_path}")
    print(f"wrote {data.xmf_path}")
    return DONE


def cmd_vtk(args) -> int:
    from ..plots.vtu import write_vtu
    from ..readers.results import read_run

    if args.open_tol_mm is not None and not args.open_tol_mm > 0.0:
        raise InputError(f"--open-tol-mm {args.open_tol_mm:g}: the opening tolerance must be > 0 mm")
    run = read_run(args.run)
    if args.out is not None and os.path.exists(args.out) and not os.path.isdir(args.out):
        raise InputError(f"--out {args.out}: is a file, expected a folder")
    tol = None if args.open_tol_mm is None else 1e-3 * args.open_tol_mm
    data = write_vtu(run, args.out, every=args.every, open_tol_m=tol)
    print(format_table(data.table(run.path)))
    if "contacts" not in data.part_pvd_paths:
        print(f"note: {run.path} has no /contacts (written before runs recorded them): no contact forces")
    print(f"wrote {len(data.samples)} samples x {len(data.files)} parts of .vtu into {data.vtu_folder}")
    for path in [data.pvd_path, *data.part_pvd_paths.values()]:
        print(f"wrote {path}")
    return DONE


def _statics_figure(args, kind: str, plot) -> int:
    """A figure of a run's contact forces over time (reactions, thrust): its summary
    printed, its samples as CSV with --csv."""
    from ..readers.results import read_run

    run = read_run(args.run)
    data = plot(run, figure_path(args.run, kind, args))
    print(format_table(data.summary))
    print(f"wrote {data.png_path}")
    if args.csv:
        print(f"wrote {write_csv(data.samples_table(), os.path.splitext(data.png_path)[0] + '.csv')}")
    return DONE


def cmd_reactions(args) -> int:
    from ..plots.reactions import plot_reactions

    return _statics_figure(args, "reactions", plot_reactions)


def cmd_thrust(args) -> int:
    from ..plots.thrust_line import plot_thrust_line

    return _statics_figure(args, "thrust", plot_thrust_line)


def cmd_mechanism(args) -> int:
    from ..plots.mechanism import plot_mechanism
    from ..readers.results import read_limit_json

    limit = read_limit_json(args.limit)
    png = figure_path(args.limit, "mechanism", args)
    data = plot_mechanism(limit, png)
    _emit(data.table, data.png_path, args.csv)
    return DONE


def _read_ida_warned(path: str):
    """read_ida, and a warning on stderr about the searches that failed."""
    from ..earthquake.ida import FIT_FAILED, read_ida

    ida = read_ida(path)
    if ida.n_failed:
        kept = sum(1 for how in ida.fit_as if how == FIT_FAILED)
        left_out = ida.n_failed - kept
        print(f"warning: {path}: {ida.n_failed} searches ended by a run that failed (column failed = 1; "
              f"voussoir-sweep printed why): {kept} fitted as right-censored at their last stand"
              + (f", {left_out} rows left out: the file does not say their last stand (a CSV does not; the "
                 "HDF5 file's /runs does)" if left_out else ""), file=sys.stderr)
    return ida


def _fragility_compare(args) -> int:
    """`fragility A --compare B`: both fits in one figure."""
    from ..plots.fragility_compare import plot_fragility_compare

    ida_a, ida_b = _read_ida_warned(args.ida), _read_ida_warned(args.compare)
    labels = args.labels or [os.path.splitext(os.path.basename(p))[0] for p in (args.ida, args.compare)]
    if args.axis == "pga-lambda-g":
        from ..plots.fragility_lambda_g import plot_lambda_g_compare
        png = figure_path(args.ida, "compare_fragility_pga_lambda_g", args)
        data = plot_lambda_g_compare(ida_a, ida_b, labels, png, n_bootstrap=args.bootstrap, seed=args.seed)
    else:
        png = figure_path(args.ida, "compare_fragility", args)
        data = plot_fragility_compare(ida_a, ida_b, labels, png, n_bootstrap=args.bootstrap, seed=args.seed)
    curve_csv = write_csv(data.curve_table, os.path.splitext(data.png_path)[0] + ".csv")
    if args.json:
        print(json.dumps(data.summary(), indent=1))
        return DONE
    for line in data.report_lines():
        print(line)
    print(f"wrote {data.png_path}")
    print(f"wrote {curve_csv}")
    return DONE


def _fragility_msa(args) -> int:
    """`fragility MSA.h5`: Baker's binomial fit to the stripes."""
    from ..earthquake.msa import read_msa
    from ..plots.msa_plot import plot_msa_fragility

    msa = read_msa(args.ida)
    if msa.n_failed:
        print(f"warning: {args.ida}: {msa.n_failed} runs stopped with an error (column failed = 1; voussoir-sweep "
              "printed why): left out of the stripes", file=sys.stderr)
    threshold_mm = {"hinge-onset": args.opening_mm, "residual-drift": args.drift_mm}.get(args.limit_state)
    if args.limit_state == "residual-drift" and args.drift_mm is None:
        raise InputError("--limit-state residual-drift needs --drift-mm X (the residual crown drift in mm beyond "
                         "which the limit state is exceeded)")
    if threshold_mm is not None and not (math.isfinite(threshold_mm) and threshold_mm > 0.0):
        raise InputError(f"--opening-mm / --drift-mm = {threshold_mm:g}: a threshold > 0 mm is needed")
    kind = "fragility" if args.limit_state == "collapse" else f"fragility_{args.limit_state.replace('-', '_')}"
    png = figure_path(args.ida, kind, args)
    data = plot_msa_fragility(msa, png, n_bootstrap=args.bootstrap, seed=args.seed, limit_state=args.limit_state,
                              threshold_mm=threshold_mm)
    stem = os.path.splitext(data.png_path)[0]
    curve_csv = write_csv(data.curve_table, stem + ".csv")
    points_csv = write_csv(data.table, stem + "_points.csv")
    if args.json:
        print(json.dumps(data.summary(), indent=1))
        return DONE
    print(format_table(data.table))
    for line in data.report_lines():
        print(line)
    print(f"wrote {data.png_path}")
    print(f"wrote {curve_csv}")
    print(f"wrote {points_csv}")
    return DONE


def cmd_fragility(args) -> int:
    from ..earthquake.msa import is_msa

    if args.labels and not args.compare:
        raise InputError("--labels names the two files of --compare: give --compare B.h5 too")
    if args.labels and any(not label.strip() for label in args.labels):
        raise InputError("--labels: a label is empty")
    measures = _measures(args)
    if args.compare:
        if measures:
            raise InputError("--im fits one IDA file: give it without --compare")
        if is_msa(args.ida) or is_msa(args.compare):
            raise InputError("--compare draws two IDA fits; an MSA file (&sweep mode = 'msa') is fitted alone")
        return _fragility_compare(args)
    if is_msa(args.ida):
        if measures:
            raise InputError("--im fits the rows of an IDA file; an MSA file (&sweep mode = 'msa') has stripes")
        if args.axis != "pga":
            raise InputError(f"--axis {args.axis} fits the rows of an IDA file, each over its model's static "
                             f"capacity; an MSA file (&sweep mode = 'msa') is fitted against PGA")
        return _fragility_msa(args)
    if args.limit_state != "collapse":
        raise InputError(f"--limit-state {args.limit_state} reads the runs of an MSA file (&sweep mode = 'msa'); "
                         f"{args.ida} is an IDA, whose rows are collapse intensities")
    from ..plots.fragility_plot import plot_fragility
    from ..plots.record_table import plot_record_table

    ida = _read_ida_warned(args.ida)
    motions = None
    if measures:  # the records read, and RotD50 asked for by name refused, before anything is fitted
        from ..earthquake.im_fragility import record_motions, rotd50_refusal, unpaired_records

        motions = record_motions(ida)
        unpaired = unpaired_records(ida, motions)
        if "rotd50" in measures and unpaired and args.im.strip().lower() != "all":
            raise RecordsError(f"--im rotd50: {rotd50_refusal(ida, unpaired)}")
    if args.axis == "pga-lambda-g":
        from ..plots.fragility_lambda_g import plot_lambda_g_fragility
        png = figure_path(args.ida, "fragility_pga_lambda_g", args)
        data = plot_lambda_g_fragility(ida, png, n_bootstrap=args.bootstrap, seed=args.seed)
    else:
        png = figure_path(args.ida, "fragility", args)
        data = plot_fragility(ida, png, n_bootstrap=args.bootstrap, seed=args.seed)
    stem = os.path.splitext(data.png_path)[0]
    curve_csv = write_csv(data.curve_table, stem + ".csv")
    points_csv = write_csv(data.table, stem + "_points.csv")
    # the table of the records, in the figure's format
    records_png = plot_record_table(ida, stem + "_records" + os.path.splitext(data.png_path)[1]).png_path
    by_measure = None
    if measures:
        from ..earthquake.im_fragility import compare_measures

        by_measure = compare_measures(ida, measures, args.sa_period, tuple(args.avgsa_periods or (0.2, 3.0)),
                                      motions=motions, n_bootstrap=args.bootstrap, seed=args.seed)
    from ..earthquake.fit_report import bootstrap_keys, failure_reading

    pga = data.data.pga if hasattr(data, "data") else data.pga
    failures = failure_reading(ida, pga.fit)
    mixture, mixture_note = None, "one model sample: no mixture"
    if ida.n_sets > 1 and args.axis == "pga":
        from ..errors import FitError
        from ..plots.fragility_mixture import plot_mixture

        try:
            mixture = plot_mixture(ida, stem + "_mixture" + os.path.splitext(data.png_path)[1],
                                   n_bootstrap=args.bootstrap, seed=args.seed,
                                   strata_path=getattr(args, "strata", None))
            mixture_csv = write_csv(mixture.table, stem + "_mixture.csv")
        except FitError as exc:  # a sample whose rows cannot be fitted alone: the pooled fit only
            mixture_note = f"the mixture of the model samples could not be made: {exc}"
    elif getattr(args, "strata", None):
        raise InputError("--strata weighs the model samples of the mixture: it needs an IDA of two samples or more "
                         "and --axis pga")
    if args.json:
        print(json.dumps({**data.summary(), **failures.keys(), **bootstrap_keys(pga.band),
                          **(mixture.summary() if mixture else {"mixture": None, "mixture_note": mixture_note}),
                          **(by_measure.summary() if by_measure else {})}, indent=1))
        return DONE
    print(format_table(data.table))
    for line in data.report_lines():
        print(line)
    print(failures.words())
    if mixture:
        for line in mixture.report_lines():
            print(line)
    elif ida.n_sets > 1 and args.axis == "pga":
        print(mixture_note)
    print(f"wrote {data.png_path}")
    print(f"wrote {curve_csv}")
    print(f"wrote {points_csv}")
    print(f"wrote {records_png} (the records: event, M, R, PGA, scale and PGA at the collapse)")
    if mixture:
        print(f"wrote {mixture.png_path} (the mixture of the model samples, each model, the pooled lognormal)")
        print(f"wrote {mixture_csv}")
    if by_measure:
        print()
        print(format_table(by_measure.table()))
        print("efficiency (smallest beta / power first; beta / power compares a measure that grows with the "
              "scale squared, Arias, with the others): " + ", ".join(by_measure.ranking()))
        print(f"beta band and P(best): {by_measure.n_bootstrap} bootstrap resamples of the {by_measure.cluster_by}s "
              f"(--bootstrap, --seed), the same rows for every measure, each refitted; P(best): the fraction in "
              f"which the measure's beta / power is the smallest")
        print("sufficiency: slope of ln IM_c - ln median (rows that collapsed, IM_c the geometric middle of the "
              "bracket) on each covariate alone; a p-value below 0.05 says the measure leaves that covariate's "
              "effect in the residuals (rows sharing a record make the p-values optimistic)")
        for what, why in by_measure.skipped.items():
            print(f"not available: {what}: {why}")
    return DONE


def _measures(args) -> list[str]:
    """The measures of --im (empty without it); InputError for a bad --im, --sa-period or
    --avgsa-periods."""
    if args.im is None:
        if args.sa_period is not None or args.avgsa_periods:
            raise InputError("--sa-period and --avgsa-periods set the spectra of --im: give --im too")
        return []
    from ..earthquake.im_fragility import parse_measures

    measures = parse_measures(args.im)
    if args.sa_period is None:
        args.sa_period = 1.0
    if not (math.isfinite(args.sa_period) and args.sa_period > 0.0):
        raise InputError(f"--sa-period {args.sa_period!r}: a period > 0 s")
    if args.avgsa_periods and not (all(math.isfinite(t) for t in args.avgsa_periods)
                                   and 0.0 < args.avgsa_periods[0] < args.avgsa_periods[1]):
        raise InputError(f"--avgsa-periods {args.avgsa_periods[0]!r} {args.avgsa_periods[1]!r}: two periods "
                         f"0 < T_LOW < T_HIGH [s]")
    return measures


def record_sets_dir() -> str:
    """Where voussoir-sweep looks for the exported record sets without $VOUSSOIR_RECORD_SETS:
    record_sets/ beside the folder of the executables (build/record_sets for build/drivers)."""
    from ..runner import find_bin_dir

    if os.environ.get("VOUSSOIR_RECORD_SETS"):
        return os.environ["VOUSSOIR_RECORD_SETS"]
    return str(find_bin_dir(programs=("voussoir-sweep",)).parent / "record_sets")


def cmd_records(args) -> int:
    from ..earthquake.record_sets import export_sets, read_set, set_table
    from ..earthquake.records import record_files_line, select_records, suite, suite_table

    if args.export is not None:
        root = args.export or record_sets_dir()
        for index in export_sets(root, args.set or SET_NAMES):
            print(f"wrote {index}")
        return DONE
    if args.set:
        for name in args.set:
            print(format_table(set_table(name, read_set(name))))
        return DONE
    records = select_records(suite(), args.keys)
    print(record_files_line(records) if args.namelist else format_table(suite_table(records)))
    return DONE


def cmd_joints(args) -> int:
    from ..analysis.assembly_joints import joints_table, run_joints
    from ..readers.results import read_run

    if not args.tol_mm > 0.0:
        raise InputError(f"--tol-mm {args.tol_mm:g}: the touching tolerance must be > 0 mm (default 0.1)")
    run = read_run(args.run)
    motions = run_joints(run, args.tol_mm * 1e-3)
    if not motions:
        raise InputError(f"{args.run}: no two blocks touch in the reference configuration (within {args.tol_mm:g} mm)")
    table = joints_table(motions, os.path.basename(args.run))
    shown = table if args.top <= 0 else ReportTable(table.columns, table.rows[: args.top], table.title)
    print(format_table(shown))
    if args.csv:
        print(f"wrote {write_csv(table, output_path(args.run, 'joints', args.out, '.csv'))}")
    return DONE


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="voussoir-post",
        description="Plots of Voussoir result files (HDF5 from voussoir-run / voussoir-sweep, "
                    "JSON from voussoir-limit --json).")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    def figure_format(p):
        p.add_argument("--format", choices=FIGURE_FORMATS, default=None,
                       help="figure format: png (200 dpi), pdf or svg (default png, or the suffix of an --out file, "
                            "which must agree)")

    def common(p, csv=True):
        p.add_argument("--out", help="output figure file (.png, .pdf or .svg: its suffix is the format), or a "
                                     "folder (default: beside the input)")
        figure_format(p)
        if csv:
            p.add_argument("--csv", action="store_true", help="also write the plotted numbers as CSV")

    p = sub.add_parser("envelope", help="collapse envelope of a sweep (threshold or grid mode)")
    p.add_argument("sweep", metavar="SWEEP.h5")
    p.add_argument("--campaign", metavar="DIR", help="overlay the measured points of this campaign folder")
    p.add_argument("--specimen", metavar="ID", action="append",
                   help="overlay only this specimen (repeatable; default: all)")
    p.add_argument("--limit", metavar="LIMIT.json",
                   help="draw the static capacity lambda g of this voussoir-limit --json result (the weaker "
                        "direction)")
    common(p)
    p.set_defaults(func=cmd_envelope)

    p = sub.add_parser("sequence", help="frames of the blocks with open hinges")
    p.add_argument("run", metavar="RUN.h5")
    p.add_argument("--times", type=_parse_times, metavar="T1,T2,...", help="frame times [s] (nearest samples)")
    p.add_argument("--n-frames", type=int, default=6, metavar="N",
                   help="frames evenly spread up to the collapse time + 15%% or the end (default 6)")
    p.add_argument("--amplify", type=float, default=1.0, metavar="K",
                   help="exaggerate displacements and rotations relative to the table-carried "
                        "reference K times until the collapse (default 1: true scale; the title says K)")
    p.add_argument("--open-tol-mm", type=float, metavar="MM",
                   help="joint opening counted as open [mm] (default: the run's &output hinge_gap_m, "
                        "else 1%% of the ring thickness)")
    p.add_argument("--gif", action="store_true", help="also write an animated GIF")
    p.add_argument("--gif-frames", type=_positive_int, default=120, metavar="N",
                   help="at most N frames in the GIF, evenly spread over the samples (default 120)")
    common(p)
    p.set_defaults(func=cmd_sequence)

    p = sub.add_parser("history", help="time histories: table, crown, NLGS iterations, contacts")
    p.add_argument("run", metavar="RUN.h5")
    common(p)
    p.set_defaults(func=cmd_history)

    p = sub.add_parser("reactions", help="the reactions of the supports (springings) over time, from the "
                                         "run's contact forces")
    p.add_argument("run", metavar="RUN.h5")
    common(p)
    p.set_defaults(func=cmd_reactions)

    p = sub.add_parser("thrust", help="the thrust line of an arch over time: where each joint's force crosses "
                                      "it, from the run's contact forces")
    p.add_argument("run", metavar="RUN.h5")
    common(p)
    p.set_defaults(func=cmd_thrust)

    p = sub.add_parser("compare", help="simulated vs measured thresholds per specimen and frequency")
    p.add_argument("sweep", metavar="SWEEP.h5")
    p.add_argument("campaign", metavar="CAMPAIGN")
    p.add_argument("--specimen", metavar="ID",
                   help="the specimen the sweep simulates (default: matched by the &arch geometry)")
    common(p)
    p.set_defaults(func=cmd_compare)

    p = sub.add_parser("xdmf", help="write RUN.xmf + RUN.vtk.h5 for ParaView")
    p.add_argument("run", metavar="RUN.h5")
    p.add_argument("--every", type=int, default=1, metavar="N", help="export every N-th sample (default 1)")
    p.add_argument("--out", help="output .xmf file or folder (default: beside the run)")
    p.set_defaults(func=cmd_xdmf)

    p = sub.add_parser("vtk", help="write RUN.pvd + .vtu files for ParaView (meshio): blocks, joints with their "
                                   "opening and hinge state, contact forces; bodies numbered from 1")
    p.add_argument("run", metavar="RUN.h5")
    p.add_argument("--every", type=_positive_int, default=1, metavar="N",
                   help="export every N-th sample and the last (default 1)")
    p.add_argument("--open-tol-mm", type=float, metavar="MM",
                   help="joint opening counted as open for the hinge field [mm] (default: the run's &output "
                        "hinge_gap_m, else 1%% of the ring thickness)")
    p.add_argument("--out", metavar="DIR", help="folder of the .pvd files and of <stem>_vtu/ (default: beside "
                                                "the run)")
    p.set_defaults(func=cmd_vtk)

    p = sub.add_parser("fragility", help="lognormal fragility of collapse from an IDA sweep (&sweep mode = 'ida', "
                                         "interval-censored fit) or an MSA sweep (mode = 'msa', binomial fit of "
                                         "the stripes)")
    p.add_argument("ida", metavar="SWEEP.h5|SWEEP.csv", help="the IDA or MSA sweep's HDF5 file, or its CSV summary")
    p.add_argument("--out", help="output figure file (.png, .pdf or .svg), or a folder (default: beside the "
                                 "input); the fit's "
                                 "curve and points are written beside it as <stem>.csv and <stem>_points.csv "
                                 "(with --compare: <IDA stem>_compare_fragility.png and the curves' .csv)")
    figure_format(p)
    p.add_argument("--compare", metavar="B.h5|B.csv",
                   help="a second IDA (e.g. of the calibrated model) drawn with the first in one figure; the "
                        "text and --json give both fits and the ratio of the medians")
    p.add_argument("--labels", nargs=2, metavar=("LABEL_A", "LABEL_B"),
                   help="the names of the two files in the figure and the text (default: their stems)")
    p.add_argument("--json", action="store_true",
                   help="print the fit as JSON (median_pga_g, beta, ...) instead of the tables")
    p.add_argument("--bootstrap", type=int, default=400, metavar="N",
                   help="bootstrap resamples of the band, each drawing records (or events), not rows "
                        "(default 400)")
    p.add_argument("--seed", type=int, default=20261124,
                   help="seed of the bootstrap and of the PIT within the brackets (default 20261124)")
    p.add_argument("--im", metavar="LIST",
                   help="also fit the fragility in each intensity measure and compare them (efficiency: beta; "
                        "sufficiency: the residuals' slope on magnitude, distance, pulse, frequency ratio, pulse "
                        "frequency ratio): 'all' or a comma-separated list of pga, pgv, pgd, arias, cav, sa, avgsa, "
                        "rotd50 (of the record's pair of components, a packaged set's), pga_lambda_g "
                        "(docs/earthquakes.md); the records are read again")
    p.add_argument("--sa-period", type=float, default=None, metavar="T_S",
                   help="period of Sa(T) and RotD50 with --im, 5 %% damping (default 1 s)")
    p.add_argument("--avgsa-periods", type=float, nargs=2, metavar=("T_LOW", "T_HIGH"),
                   help="periods of AvgSa with --im: the geometric mean of Sa at 10 periods spread in ln T over "
                        "T_LOW..T_HIGH s (default 0.2 3.0)")
    p.add_argument("--axis", choices=["pga", "pga-lambda-g"], default="pga",
                   help="IDA only: pga (default), the fragility against PGA and PGV; pga-lambda-g, against the "
                        "dimensionless PGA / (lambda g), each row's PGA over the static capacity of its own model "
                        "sample (the static capacity is then 1; with --compare both files on that one axis; "
                        "written as <stem>_fragility_pga_lambda_g.png; --json adds median_pga_lambda_g, "
                        "beta_pga_lambda_g, median_pga_lambda_g_band); the file must give static_capacity_m_s2")
    p.add_argument("--strata", metavar="SAMPLES.csv",
                   help="IDA of several model samples: the stratified samples file it played (voussoir-post "
                        "samples), whose models and weights make the mixture (default: the IDA's "
                        "model_samples_file beside its file when stratified, else equal weights); the mixture is "
                        "drawn as <stem>_fragility_mixture.png, its curves in <stem>_fragility_mixture.csv")
    p.add_argument("--limit-state", choices=["collapse", "hinge-onset", "residual-drift"], default="collapse",
                   help="MSA only: the limit state fitted: collapse (default); hinge-onset, a joint opened by more "
                        "than --opening-mm; residual-drift, a residual crown drift above --drift-mm (a collapse "
                        "exceeds both)")
    p.add_argument("--opening-mm", type=float, default=1.0, metavar="MM",
                   help="hinge-onset: the joint opening [mm] beyond which a hinge has formed (default 1)")
    p.add_argument("--drift-mm", type=float, default=None, metavar="MM",
                   help="residual-drift: the residual crown drift [mm] beyond which the limit state is exceeded")
    p.set_defaults(func=cmd_fragility)

    add_dtcheck_parser(sub)
    add_risk_parser(sub, figure_format)
    add_samples_parser(sub)

    p = sub.add_parser("records", help="the suite of real ground-motion records and where they are installed")
    p.add_argument("keys", nargs="*", metavar="KEY", help="only these records (e.g. ELC180 CLS000)")
    p.add_argument("--namelist", action="store_true", help="print them as a &sweep record_files line")
    p.add_argument("--set", action="append", choices=SET_NAMES, metavar="NAME",
                   help=f"a packaged record set ({', '.join(SET_NAMES)}; repeatable): print its records and "
                        "their metadata, or with --export export only it")
    p.add_argument("--export", nargs="?", const="", metavar="DIR",
                   help="write the packaged record sets as .AT2 files and an index.csv each into DIR/<set>/, "
                        "where &sweep record_set finds them (default: $VOUSSOIR_RECORD_SETS, else record_sets/ "
                        "beside the folder of the executables, e.g. build/record_sets; scripts/setup.sh runs it)")
    p.set_defaults(func=cmd_records)

    p = sub.add_parser("joints", help="every joint of any assembly (a wall, polygon blocks): opening and sliding "
                                      "over the run and at its end")
    p.add_argument("run", metavar="RUN.h5")
    p.add_argument("--top", type=int, default=20, metavar="N", help="print the N joints that slid most (0: all; "
                                                                    "default 20)")
    p.add_argument("--tol-mm", type=float, default=0.1, metavar="MM",
                   help="two faces closer than this at t = 0 touch (default 0.1 mm)")
    p.add_argument("--out", help="CSV file or folder for --csv (default: beside the run)")
    p.add_argument("--csv", action="store_true", help="also write the table as CSV (<stem>_joints.csv)")
    p.set_defaults(func=cmd_joints)

    p = sub.add_parser("mechanism", help="limit-analysis mechanisms (voussoir-limit --json)")
    p.add_argument("limit", metavar="LIMIT.json")
    common(p)
    p.set_defaults(func=cmd_mechanism)

    add_bridge_report_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``voussoir-post``; returns the exit status."""
    return run_command(build_parser(), argv)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
