"""The tables a command reports (the numbers a figure drew, a summary): printed as
aligned text and written as CSV. Not to be confused with
:class:`voussoir_post.readers.csv_table.CsvTable`, a CSV file read in."""

from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass, field

__all__ = ["ReportTable", "format_table", "write_csv"]


@dataclass
class ReportTable:
    """Rows of reported numbers (or words) with named columns (units in the names)."""

    columns: list[str]
    rows: list[tuple] = field(default_factory=list)
    title: str = ""

    def column(self, name: str) -> list:
        k = self.columns.index(name)
        return [row[k] for row in self.rows]


def _cell(value, digits: int = 6) -> str:
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        if math.isnan(value):
            return "-"
        return f"{value:.{digits}g}"
    return str(value)


def format_table(table: ReportTable, digits: int = 5) -> str:
    """The table as aligned text (NaN and None shown as '-')."""
    cells = [[_cell(v, digits) for v in row] for row in table.rows]
    widths = [max([len(c)] + [len(r[k]) for r in cells]) for k, c in enumerate(table.columns)]
    lines = []
    if table.title:
        lines.append(table.title)
    lines.append("  ".join(c.rjust(w) for c, w in zip(table.columns, widths)))
    lines.append("  ".join("-" * w for w in widths))
    for r in cells:
        lines.append("  ".join(c.rjust(w) for c, w in zip(r, widths)))
    return "\n".join(lines)


def write_csv(table: ReportTable, path: str | os.PathLike) -> str:
    """Write the table as CSV (full precision, NaN/None as empty cells); returns the path."""
    path = os.fspath(path)
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(table.columns)
        for row in table.rows:
            out = []
            for v in row:
                if v is None or (isinstance(v, float) and math.isnan(v)):
                    out.append("")
                elif isinstance(v, bool):
                    out.append(int(v))
                elif isinstance(v, float):
                    out.append(repr(v))
                else:
                    out.append(v)
            writer.writerow(out)
    return path
