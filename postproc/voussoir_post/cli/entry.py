"""The one entry layer of the command-line programs: parse the arguments, run the
subcommand, and map the package's errors (:mod:`voussoir_post.errors`) to the exit
status with the message on stderr: 0 done, 1 the work failed, 2 bad input (argparse's
own usage errors exit 2 as well). Any other exception is a bug and is let through with
its traceback (Python then exits 1)."""

from __future__ import annotations

import argparse
import os
import sys

from ..errors import DONE, VoussoirError

__all__ = ["run_command"]


def run_command(parser: argparse.ArgumentParser, argv: list[str] | None = None) -> int:
    """Run the subcommand ``argv`` names (each sets ``func(args) -> int`` as its default);
    returns the exit status."""
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except BrokenPipeError:  # stdout closed early (piped into head): end quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return DONE
    except VoussoirError as exc:
        print(exc.describe(parser.prog), file=sys.stderr)
        return exc.exit_code
