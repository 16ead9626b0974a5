"""What every result reader shares: the error type and the hinge side names."""

from __future__ import annotations

import os

__all__ = ["SIDE_NAMES", "ResultsError"]

#: Hinge side codes of /hinges/side: 0 intrados, 1 extrados.
SIDE_NAMES = ("intrados", "extrados")


class ResultsError(Exception):
    """A result file cannot be read; the message names the file and the problem."""

    def __init__(self, path: str | os.PathLike, message: str):
        self.path = os.fspath(path)
        self.message = message
        super().__init__(f"{self.path}: {message}")
