"""CSV files of a campaign read with the physical line of every row, and typed cells
whose errors name the file, the line and the column (shared/MEASURED_DATA.md's rules:
UTF-8 with an optional byte order mark, comma separated, quoted fields, LF or CRLF,
`#` comment lines anywhere outside a quoted field, blank lines skipped, cells stripped).
"""

from __future__ import annotations

import csv
import io
import math
import os
import re
import warnings
from dataclasses import dataclass

__all__ = ["CampaignError", "CampaignWarning", "Row", "Table", "read_table", "check_columns", "Cells"]

NUMBER = re.compile(r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?")  #: a number as a campaign may write it


class CampaignError(Exception):
    """An invalid campaign: names the file, the 1-based line and the column."""

    def __init__(self, path, message: str, line: int | None = None,
                 column_name: str | None = None, column_index: int | None = None):
        self.path = os.fspath(path)
        self.message = message
        self.line = line
        self.column_name = column_name
        self.column_index = column_index
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


class CampaignWarning(UserWarning):
    """Something a valid campaign may contain but that is ignored (e.g. an unknown column)."""


@dataclass
class Row:
    line: int
    cells: dict[str, str]


@dataclass
class Table:
    path: str
    header_line: int
    columns: list[str]
    rows: list[Row]

    def index(self, name: str) -> int | None:
        """1-based column index of ``name`` or None when absent."""
        return self.columns.index(name) + 1 if name in self.columns else None

    def has(self, name: str) -> bool:
        return name in self.columns


def read_table(path: str) -> Table:
    """Read one campaign CSV file keeping the physical line of every row."""
    try:
        with open(path, "rb") as f:
            raw = f.read()
    except OSError as exc:
        raise CampaignError(path, f"cannot read file: {exc.strerror}") from exc
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        raise CampaignError(path, f"not UTF-8 text (byte 0x{raw[exc.start]:02x})", line) from exc

    state = {"line": 0, "start": 0, "at_record_start": True}

    def physical_lines():
        for physical in io.StringIO(text, newline=""):
            state["line"] += 1
            if state["at_record_start"]:
                if physical.startswith("#") or not physical.strip():
                    continue
                state["start"] = state["line"]
                state["at_record_start"] = False
            yield physical

    reader = csv.reader(physical_lines(), strict=True)
    header: list[str] | None = None
    header_line = 0
    rows: list[Row] = []
    while True:
        state["at_record_start"] = True
        try:
            record = next(reader)
        except StopIteration:
            break
        except csv.Error as exc:
            raise CampaignError(path, f"malformed CSV: {exc}", state["line"]) from exc
        line = state["start"]
        cells = [c.strip() for c in record]
        if header is None:
            header, header_line = cells, line
            for k, name in enumerate(header):
                if not name:  # e.g. a trailing comma: an unknown column, ignored with a warning
                    header[k] = name = f"<unnamed column {k + 1}>"
                if name in header[:k]:
                    raise CampaignError(path, f"duplicate column (also column {header.index(name) + 1})",
                                        line, name, k + 1)
            continue
        if len(cells) > len(header) and any(cells[len(header):]):
            extra = len(header) + next(k for k, c in enumerate(cells[len(header):]) if c) + 1
            raise CampaignError(path, f"row has {len(cells)} fields but the header has {len(header)}",
                                line, None, extra)
        cells += [""] * (len(header) - len(cells))
        rows.append(Row(line, dict(zip(header, cells))))
    if header is None:
        raise CampaignError(path, "no header row (the file is empty or only comments)", max(state["line"], 1))
    return Table(path, header_line, header, rows)


def check_columns(table: Table, required: tuple[str, ...], known: tuple[str, ...],
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

    def __init__(self, table: Table, row: Row):
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
