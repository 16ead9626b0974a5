"""``voussoir-post dtcheck A.h5 B.h5``: the time-step check of an IDA
(:mod:`voussoir_post.earthquake.dt_check`), a subcommand of its own rather than an
option of ``fragility``: it takes two files in fixed roles (B the same IDA at a smaller
dt_s, on a subset of A's rows), refuses a pair that is not that, and reports a change
with its paired band instead of two fragilities (which ``fragility --compare`` draws)."""

from __future__ import annotations

import json

from ..errors import DONE, InputError

__all__ = ["add_dtcheck_parser", "cmd_dtcheck"]


def cmd_dtcheck(args) -> int:
    from ..earthquake.dt_check import dt_check  # scipy: imported when the command runs (cli/post.py)
    from ..earthquake.ida import read_ida

    if args.bootstrap < 10:
        raise InputError(f"--bootstrap {args.bootstrap}: at least 10 resamples")
    check = dt_check(read_ida(args.ida_a), read_ida(args.ida_b), n_bootstrap=args.bootstrap, seed=args.seed)
    if args.json:
        print(json.dumps(check.summary(), indent=1))
        return DONE
    for line in check.lines():
        print(line)
    return DONE


def add_dtcheck_parser(sub) -> None:
    """The subcommand's arguments, on ``voussoir-post``'s subparsers ``sub``."""
    p = sub.add_parser("dtcheck", help="time-step check of an IDA: the change of the PGA fragility's median and "
                                       "beta when the same IDA (or a sample of its rows) runs at a smaller dt_s, "
                                       "with a paired bootstrap band clustered by event")
    p.add_argument("ida_a", metavar="A.h5", help="the IDA (&sweep mode = 'ida') at its time step")
    p.add_argument("ida_b", metavar="B.h5", help="the same IDA at a smaller &solver dt_s: the same arch, search and "
                                                 "model samples, on all or some of A's records and samples")
    p.add_argument("--json", action="store_true", help="print the numbers as JSON (median_ratio, beta_change, ...)")
    p.add_argument("--bootstrap", type=int, default=400, metavar="N",
                   help="paired bootstrap resamples of the events (then records) of the common rows (default 400)")
    p.add_argument("--seed", type=int, default=20261124, help="seed of the bootstrap (default 20261124)")
    p.set_defaults(func=cmd_dtcheck)
