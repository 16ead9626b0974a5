"""The one CSV reader of the package: a file read with the physical line of every row,
so that every error names the file, the line and the column.

The rules (docs/measured_data.md's, and what the executables write): UTF-8 with an
optional byte order mark, comma separated, quoted fields, LF or CRLF, ``#`` comment
lines anywhere outside a quoted field, blank lines skipped, cells stripped. Campaign
files (:mod:`.campaign_csv`), IDA summaries (:mod:`voussoir_post.earthquake.ida`) and
the sweep CSVs the runner reads back all go through :func:`read_csv_table`.
"""

from __future__ import annotations

import csv
import io
import os
from dataclasses import dataclass

from ..errors import CsvError

__all__ = ["CsvRow", "CsvTable", "read_csv_table"]


@dataclass
class CsvRow:
    """One record of a CSV file: its first physical line and its cells by column name
    (missing trailing cells are empty)."""

    line: int
    cells: dict[str, str]
    n_fields: int = 0  #: the fields the record had, before the missing ones were filled in


@dataclass
class CsvTable:
    """A CSV file read as a header and rows, each row with its physical line."""

    path: str
    header_line: int
    columns: list[str]
    rows: list[CsvRow]

    def index(self, name: str) -> int | None:
        """1-based column index of ``name`` or None when absent."""
        return self.columns.index(name) + 1 if name in self.columns else None

    def has(self, name: str) -> bool:
        return name in self.columns


def read_csv_table(path: str | os.PathLike, error: type[CsvError] = CsvError, expected: str = "") -> CsvTable:
    """Read one CSV file keeping the physical line of every row. A file that is not a
    CSV table raises ``error`` (a :class:`~voussoir_post.errors.CsvError`, e.g. a
    CampaignError) with the line and column; ``expected`` says what the header should
    hold when there is none."""
    path = os.fspath(path)
    try:
        with open(path, "rb") as f:
            raw = f.read()
    except OSError as exc:
        raise error(path, f"cannot read file: {exc.strerror}") from exc
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        raise error(path, f"not UTF-8 text (byte 0x{raw[exc.start]:02x})", line) from exc

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
    rows: list[CsvRow] = []
    while True:
        state["at_record_start"] = True
        try:
            record = next(reader)
        except StopIteration:
            break
        except csv.Error as exc:
            raise error(path, f"malformed CSV: {exc}", state["line"]) from exc
        line = state["start"]
        cells = [c.strip() for c in record]
        if header is None:
            header, header_line = cells, line
            for k, name in enumerate(header):
                if not name:  # e.g. a trailing comma: an unknown column, ignored with a warning
                    header[k] = name = f"<unnamed column {k + 1}>"
                if name in header[:k]:
                    raise error(path, f"duplicate column (also column {header.index(name) + 1})", line, name, k + 1)
            continue
        if len(cells) > len(header) and any(cells[len(header):]):
            extra = len(header) + next(k for k, c in enumerate(cells[len(header):]) if c) + 1
            raise error(path, f"row has {len(cells)} fields but the header has {len(header)}", line, None, extra)
        n_fields = len(cells)
        cells += [""] * (len(header) - len(cells))
        rows.append(CsvRow(line, dict(zip(header, cells)), n_fields))
    if header is None:
        hint = f"; expected {expected}" if expected else ""
        raise error(path, f"no header row (the file is empty or only comments){hint}", max(state["line"], 1))
    return CsvTable(path, header_line, header, rows)
