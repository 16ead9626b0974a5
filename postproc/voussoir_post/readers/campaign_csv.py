"""CSV files of a campaign: read by :func:`.csv_table.read_csv_table` (which keeps the
physical line of every row), their columns checked, and typed cells whose errors name
the file, the line and the column (:class:`~voussoir_post.errors.CampaignError`).
"""

from __future__ import annotations

import math
import re
import warnings

from ..errors import CampaignError, CampaignWarning
from .csv_table import CsvRow, CsvTable, read_csv_table

__all__ = ["CampaignError", "CampaignWarning", "read_table", "check_columns", "Cells"]

NUMBER = re.compile(r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?")  #: a number as a campaign may write it


def read_table(path: str) -> CsvTable:
    """Read one campaign CSV file keeping the physical line of every row; CampaignError
    when it is not a readable CSV table."""
    return read_csv_table(path, CampaignError)


def check_columns(table: CsvTable, required: tuple[str, ...], known: tuple[str, ...],
                   warn_list: list[str]) -> None:
    """Error on a missing required column; warn on an unknown one."""
    for name in required:
        if not table.has(name):
            raise CampaignError(table.path, f"missing required column (header has: {', '.join(table.columns)})",
                                table.header_line, name)
    for k, name in enumerate(table.columns):
        if name not in known:
            message = (f"{table.path}:{table.header_line}:{k + 1}: column '{name}': "
                       "unknown column, ignored")
            warn_list.append(message)
            warnings.warn(message, CampaignWarning, stacklevel=3)


class Cells:
    """Typed access to the cells of one row; errors are collected and the leftmost raised."""

    def __init__(self, table: CsvTable, row: CsvRow):
        self.table = table
        self.row = row
        self.errors: list[CampaignError] = []

    def error(self, name: str, message: str) -> CampaignError:
        err = CampaignError(self.table.path, message, self.row.line, name, self.table.index(name))
        self.errors.append(err)
        return err

    def raise_first(self) -> None:
        if self.errors:
            raise min(self.errors, key=lambda e: e.column_index or 10**9)

    def raw(self, name: str, required: bool) -> str | None:
        """Cell text, None when empty or the column is absent (an error if required)."""
        text = self.row.cells.get(name, "")
        if text:
            return text
        if required:
            if self.table.has(name):
                self.error(name, "empty required cell")
            else:
                self.error(name, "required here, but the file has no such column")
        return None

    def text(self, name: str, required: bool = True) -> str | None:
        return self.raw(name, required)

    def number(self, name: str, required: bool = True, *, length: bool = False,
               low: float | None = None, low_inclusive: bool = True,
               high: float | None = None, high_inclusive: bool = True,
               rule: str = "") -> float | None:
        """A finite number; ``length`` makes a negative value an error of its own."""
        text = self.raw(name, required)
        if text is None:
            return None
        if not NUMBER.fullmatch(text):
            self.error(name, f"'{text}' is not a number")
            return None
        value = float(text)
        if not math.isfinite(value):
            self.error(name, f"'{text}' is not a finite number")
            return None
        if length and value < 0:
            self.error(name, f"negative length {text} m")
            return None
        bad_low = low is not None and (value < low or (value == low and not low_inclusive))
        bad_high = high is not None and (value > high or (value == high and not high_inclusive))
        if bad_low or bad_high:
            self.error(name, f"{text} is out of range: {rule}")
            return None
        return value

    def integer(self, name: str, required: bool = True, *, low: int | None = None,
                high: int | None = None, rule: str = "") -> int | None:
        value = self.number(name, required)
        if value is None:
            return None
        if value != int(value):
            self.error(name, f"'{self.row.cells[name]}' is not an integer")
            return None
        if (low is not None and value < low) or (high is not None and value > high):
            self.error(name, f"{self.row.cells[name]} is out of range: {rule}")
            return None
        return int(value)

    def enum(self, name: str, allowed: tuple[str, ...], required: bool = True) -> str | None:
        text = self.raw(name, required)
        if text is None:
            return None
        if text not in allowed:
            self.error(name, f"'{text}' is not one of {', '.join(allowed)}")
            return None
        return text
