"""Every error the package raises on purpose, under one base class, each with the exit
status of the command-line programs it means (:mod:`voussoir_post.cli.entry`):

- ``BAD_INPUT`` (2): nothing was done; what the command was given is wrong (an argument,
  a file, a campaign folder, the folder of the executables) and the message says what
  to change.
- ``WORK_FAILED`` (1): the input was accepted but the work failed on the way (an
  executable exited with an error, a written file failed its check).

Anything else that escapes a command (KeyError, a ValueError from numpy, ...) is a bug:
the programs let it through with its traceback rather than call it bad input.
"""

from __future__ import annotations

import os

__all__ = ["DONE", "WORK_FAILED", "BAD_INPUT", "VoussoirError", "InputError", "LocatedError", "CsvError",
           "CampaignError", "CampaignWarning", "ResultsError", "MatchError", "RecordsError", "FitError",
           "BinDirError", "RunError", "CheckError"]

DONE = 0  #: exit status: done
WORK_FAILED = 1  #: exit status: the work failed
BAD_INPUT = 2  #: exit status: bad input, nothing was done


class VoussoirError(Exception):
    """Base of the package's errors; ``exit_code`` is the status a program exits with."""

    exit_code = WORK_FAILED

    def describe(self, program: str) -> str:
        """The line a program prints on stderr."""
        return f"{program}: error: {self}"


class InputError(VoussoirError, ValueError):
    """Bad input: an argument or a file the command cannot use (exit 2)."""

    exit_code = BAD_INPUT


class LocatedError(InputError):
    """Bad input at a place in a text file: ``file:line:column: column 'name': message``
    (printed as it is, the way compilers print, so that editors can jump to it)."""

    exit_code = BAD_INPUT

    def __init__(self, path, message: str, line: int | None = None,
                 column_name: str | None = None, column_index: int | None = None):
        self.path = os.fspath(path)
        self.message = message
        self.line = line  #: 1-based physical line
        self.column_name = column_name
        self.column_index = column_index  #: 1-based
        super().__init__(self.format())

    @property
    def location(self) -> str:
        """``file:line:column`` (the parts that are known)."""
        loc = self.path
        if self.line is not None:
            loc += f":{self.line}"
            if self.column_index is not None:
                loc += f":{self.column_index}"
        return loc

    def format(self) -> str:
        column = f"column '{self.column_name}': " if self.column_name else ""
        return f"{self.location}: {column}{self.message}"

    def describe(self, program: str) -> str:
        return str(self)


class CsvError(LocatedError):
    """A CSV file that cannot be read as a table (exit 2)."""

    exit_code = BAD_INPUT


class CampaignError(CsvError):
    """An invalid campaign folder: names the file, the 1-based line and the column (exit 2)."""

    exit_code = BAD_INPUT


class CampaignWarning(UserWarning):
    """Something a valid campaign may contain but that is ignored (e.g. an unknown column)."""


class ResultsError(InputError):
    """A result file cannot be read; the message names the file and the problem (exit 2)."""

    exit_code = BAD_INPUT

    def __init__(self, path: str | os.PathLike, message: str):
        self.path = os.fspath(path)
        self.message = message
        super().__init__(f"{self.path}: {message}")


class MatchError(InputError):
    """The sweep cannot be matched to campaign specimens (exit 2)."""

    exit_code = BAD_INPUT


class RecordsError(InputError):
    """The record suite cannot be found, or has no such record; the message says how to
    install it or which records it has (exit 2)."""

    exit_code = BAD_INPUT


class FitError(InputError):
    """The data cannot define a fragility (e.g. no collapse at all) (exit 2)."""

    exit_code = BAD_INPUT


class BinDirError(InputError):
    """The folder of the Fortran executables is not found, or lacks a program (exit 2)."""

    exit_code = BAD_INPUT


class RunError(VoussoirError, RuntimeError):
    """An executable failed: the message has the command, the input and its output (exit 1)."""

    exit_code = WORK_FAILED

    def describe(self, program: str) -> str:
        return f"{program}: error: a simulation failed: {self}"


class CheckError(VoussoirError, ValueError):
    """A file the package wrote fails its own check (exit 1)."""

    exit_code = WORK_FAILED
