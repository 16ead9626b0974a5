"""The record table of an IDA, as a figure for a report: one line per record (component),
with its event, the component's orientation (fault-normal or fault-parallel, for the
FEMA P695 near-field sets, read from the set), magnitude, distance, site Vs30 and pulse
period (where the file has them), its own PGA, the record scale at which the arch
collapsed on each model sample (or their median and range with more than
MAX_SAMPLE_COLUMNS samples) and the PGA at the collapse.
A scale beyond 4 or below 0.25 (fragility_plot.SCALE_WARN, the FEMA P695 practice) marks
its row. The cells are made by :func:`record_table` (plain text, testable without a
figure) and drawn as figure texts by :func:`plot_record_table`."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..earthquake.ida import FIT_BRACKET, FIT_LEFT_OUT, IdaResult, played_record
from ..earthquake.record_sets import AS_RECORDED, read_set
from ..errors import RecordsError
from .drawing import G_M_S2, new_figure, provenance, save_figure
from .fragility_plot import SCALE_WARN, arch_words, records_words, samples_words

__all__ = ["RecordTable", "record_table", "plot_record_table", "MAX_SAMPLE_COLUMNS", "FLAG_MARK", "LOWER_BOUND"]

#: Up to this many model samples the scale of each has its own column; beyond, the median and range.
MAX_SAMPLE_COLUMNS = 4
#: The mark of a row with a scale factor beyond SCALE_WARN.
FLAG_MARK = " †"
#: Before a value that is a lower bound (no collapse up to the largest scale tried, or a failed search).
LOWER_BOUND = "> "

_FONT_PT = 8.0
_ROW_PT = 1.45 * _FONT_PT  # the height of a line of the table
_PAD_IN = 0.12  # between two columns
_MARGIN_IN = 0.25
_FLAG_COLOUR = "tab:red"


@dataclass
class RecordTable:
    """What :func:`plot_record_table` drew: the column heads (lines of each), the cells
    (one list per record, text), which rows are flagged and which cells are (row, column)."""

    heads: list[list[str]]
    cells: list[list[str]]
    flagged: list[bool]
    flagged_cells: set[tuple[int, int]] = field(default_factory=set)
    title: str = ""
    footnote: str = ""
    png_path: str = ""

    def column(self, first_head_line: str) -> list[str]:
        """The cells of the column whose head begins with `first_head_line`."""
        k = [h[0] for h in self.heads].index(first_head_line)
        return [row[k] for row in self.cells]


#: How the numbers are written: magnitudes and distances to 0.1, Vs30 to 1 m/s, the rest
#: to two or three decimals (a column of them aligned on the point).
_SCALE_FMT = ".2f"
_PGA_FMT = ".3f"


def _number(value: float, fmt: str = _SCALE_FMT) -> str:
    return "-" if not math.isfinite(value) else format(value, fmt)


def _collapse_values(ida: IdaResult) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(scale, PGA [m/s2], lower bound?, flagged?) per row: at the collapse where it was
    found; where not (censored, failed), the lower bound; NaN for a row left out."""
    scale_low, scale_high = ida.scale_brackets()
    pga_low, pga_high = ida.intensity_brackets("pga")
    bound = np.isinf(scale_high)
    scale = np.where(bound, scale_low, scale_high)
    pga = np.where(bound, pga_low, pga_high)
    collapsed = np.array([how == FIT_BRACKET for how in ida.fit_as])
    low, high = SCALE_WARN
    flagged = collapsed & ((scale > high) | (scale < low))
    left_out = np.array([how == FIT_LEFT_OUT for how in ida.fit_as])
    scale[left_out] = pga[left_out] = np.nan
    return scale, pga, bound, flagged


def _median_cell(values: np.ndarray, bound: np.ndarray, fmt: str = _SCALE_FMT) -> str:
    """The median of `values` where those marked `bound` are lower bounds: exact when
    the bounds cannot move it, else shown as a lower bound ('> x')."""
    known = np.isfinite(values)
    values, bound = values[known], bound[known]
    if values.size == 0:
        return "-"
    low = float(np.median(values))
    high = float(np.median(np.where(bound, np.inf, values)))
    return _number(low, fmt) if high == low else LOWER_BOUND + _number(low, fmt)


def _value_cell(value: float, bound: bool) -> str:
    return (LOWER_BOUND if bound and math.isfinite(value) else "") + _number(value)


def record_orientations(ida: IdaResult) -> dict[str, str] | None:
    """Each record's orientation in its packaged set (fault-normal, fault-parallel), None
    when no record of the rows has one other than 'as recorded' (record files, the
    far-field set) or the set cannot be read here (its package missing: the table is
    drawn without the column)."""
    if not ida.record_set:
        return None
    try:
        by_name = {r.record: r.orientation for r in read_set(ida.record_set)}
    except RecordsError:
        return None
    out = {name: by_name.get(played_record(name).record, "") for name in ida.records}
    return out if any(v not in ("", AS_RECORDED) for v in out.values()) else None


def record_table(ida: IdaResult) -> RecordTable:
    """The cells of the record table of `ida`: one row per record, sorted by event (when
    the file has events) then record name."""
    scale, pga, bound, flagged = _collapse_values(ida)
    sets = sorted(set(ida.param_set.tolist()))
    per_sample = len(sets) <= MAX_SAMPLE_COLUMNS
    events = ida.event or [""] * ida.n_rows
    first_row = {}
    for k, name in enumerate(ida.record):
        first_row.setdefault(name, k)
    order = sorted(first_row, key=lambda name: (events[first_row[name]], name))

    def per_record(values):
        return None if values is None else np.array([values[first_row[name]] for name in order], dtype=float)

    heads: list[list[str]] = [["record"]]
    columns: list[list[str]] = [list(order)]
    if ida.event is not None:
        heads.append(["event"])
        columns.append([events[first_row[name]] for name in order])
    orientation = record_orientations(ida)
    if orientation is not None:
        heads.append(["component"])
        columns.append([orientation[name] or "-" for name in order])
    for head, values, fmt in ((["M", "[Mw]"], ida.magnitude, ".1f"), (["R", "(Rrup)", "[km]"], ida.distance_km, ".1f"),
                              (["Vs30", "[m/s]"], ida.vs30_m_s, ".0f"),
                              (["Tp", "(pulse)", "[s]"], ida.pulse_period_s, ".2f"),
                              (["PGA", "(record)", "[g]"],
                               None if ida.unit_pga_m_s2 is None else ida.unit_pga_m_s2 / G_M_S2, _PGA_FMT)):
        values = per_record(values)
        if values is None or not np.any(np.isfinite(values)):
            continue  # a column nan for every record says nothing
        heads.append(head)
        columns.append([_number(v, fmt) for v in values])
    rows_of = {name: [k for k, r in enumerate(ida.record) if r == name] for name in order}
    scale_columns = []
    if per_sample:
        for s in sets:
            heads.append(["scale at", "collapse,", f"model {s} [-]"])
            cells = []
            for name in order:
                ks = [k for k in rows_of[name] if ida.param_set[k] == s]
                cells.append(_value_cell(scale[ks[0]], bool(bound[ks[0]])) if ks else "-")
            scale_columns.append(len(columns))
            columns.append(cells)
    else:
        heads.append(["scale at", "collapse,", "median [-]"])
        scale_columns.append(len(columns))
        columns.append([_median_cell(scale[rows_of[n]], bound[rows_of[n]]) for n in order])
        heads.append(["scale at", "collapse,", "range [-]"])
        columns.append([_range_cell(scale[rows_of[n]], bound[rows_of[n]]) for n in order])
    pga_head = "median" if len(sets) > 1 else ""
    heads.append(["PGA at", f"collapse{',' if pga_head else ''}", f"{pga_head} [g]".strip()])
    columns.append([_median_cell(pga[rows_of[n]] / G_M_S2, bound[rows_of[n]], _PGA_FMT) for n in order])

    row_flagged = [bool(np.any(flagged[rows_of[name]])) for name in order]
    flagged_cells = set()
    for i, name in enumerate(order):
        if not row_flagged[i]:
            continue
        columns[0][i] += FLAG_MARK
        if per_sample:
            for j, s in zip(scale_columns, sets):
                if any(flagged[k] and ida.param_set[k] == s for k in rows_of[name]):
                    flagged_cells.add((i, j))
        else:
            flagged_cells.add((i, scale_columns[0] + 1))  # the range holds the flagged value
    cells = [[column[i] for column in columns] for i in range(len(order))]
    return RecordTable(heads=heads, cells=cells, flagged=row_flagged, flagged_cells=flagged_cells,
                       title=_title(ida), footnote=_footnote(ida, per_sample, sum(row_flagged), bool(bound.any())))


def _range_cell(values: np.ndarray, bound: np.ndarray) -> str:
    known = np.isfinite(values)
    if not known.any():
        return "-"
    top = _number(float(values[known].max()))
    return f"{_number(float(values[known].min()))}-{top}" + ("+" if bound[known].any() else "")


def _title(ida: IdaResult) -> str:
    return (f"Ground-motion records of the IDA of the {arch_words(ida)}\n"
            f"{records_words(ida)}, each on {samples_words(ida)}: the record scale and the PGA at the collapse")


def _footnote(ida: IdaResult, per_sample: bool, n_flagged: int, any_bound: bool) -> str:
    low, high = SCALE_WARN
    lines = ["Scale at collapse: the smallest factor on the record's accelerogram (as recorded = 1) that brought "
             "the arch down in the IDA's search (scale_threshold; the last factor that stood is within the search's "
             "tolerance below it); PGA at collapse = the record's PGA x that factor"
             + ("." if ida.n_sets == 1 else ", its median over the model samples." if per_sample
                else "; the scale's median and range and the PGA's median over the model samples.")]
    if any_bound:
        lines.append(f"'{LOWER_BOUND.strip()} x': no collapse up to the largest scale tried, or a search that ended "
                     f"in a failed run: a lower bound" + ("; '+' after a range: it holds such a bound" if not per_sample
                                                          else "") + ".")
    lines.append(f"{FLAG_MARK.strip()} a scale factor beyond {high:g} or below {low:g}"
                 + ("" if per_sample else " on at least one model sample") + f" (in red; {n_flagged or 'none'} of "
                 f"the {len(ida.records)} records here): FEMA P695 practice keeps the factors within these, a record scaled "
                 f"further standing for another earthquake than the one recorded.")
    return " ".join(lines)


def _wrap(fig, text: str, width_in: float, fontsize: float) -> str:
    """`text` broken at spaces into lines that the renderer draws within `width_in`."""
    from matplotlib.font_manager import FontProperties

    renderer, font = fig.canvas.get_renderer(), FontProperties(size=fontsize)

    def fits(line: str) -> bool:
        return renderer.get_text_width_height_descent(line, font, ismath=False)[0] / fig.dpi <= width_in

    lines: list[str] = []
    for word in text.split(" "):
        if lines and fits(f"{lines[-1]} {word}"):
            lines[-1] += f" {word}"
        else:
            lines.append(word)
    return "\n".join(lines)


def _text_widths_in(fig, texts) -> list[float]:
    renderer = fig.canvas.get_renderer()
    return [t.get_window_extent(renderer).width / fig.dpi for t in texts]


def plot_record_table(ida: IdaResult, png_path: str) -> RecordTable:
    """Draw :func:`record_table` of `ida` at `png_path`; returns it, with the path."""
    table = record_table(ida)
    n_head = max(len(h) for h in table.heads)
    n_cols = len(table.heads)
    fig = new_figure(8.0, 6.0)
    numeric = [j > 1 or (j == 1 and ida.event is None) for j in range(n_cols)]  # record and event read as words
    head_texts = [[fig.text(0, 0, line, fontsize=_FONT_PT, fontweight="bold", ha="right" if numeric[j] else "left",
                            va="baseline") for line in head] for j, head in enumerate(table.heads)]
    cell_texts = [[fig.text(0, 0, cell, fontsize=_FONT_PT, ha="right" if numeric[j] else "left", va="baseline",
                            color=_FLAG_COLOUR if (i, j) in table.flagged_cells else "black")
                   for j, cell in enumerate(row)] for i, row in enumerate(table.cells)]
    widths = []
    for j in range(n_cols):
        column = head_texts[j] + [row[j] for row in cell_texts]
        widths.append(max(_text_widths_in(fig, column)))
    table_in = sum(widths) + _PAD_IN * (n_cols - 1)
    # wide enough for the title's first line (the arch) up to 10 in, which then wraps
    probe = fig.text(0, 0, table.title.split("\n")[0], fontsize=10.0)
    arch_in = _text_widths_in(fig, [probe])[0]
    probe.remove()
    width_in = max(table_in, min(arch_in + 0.05, 10.0), 7.0) + 2 * _MARGIN_IN
    text_in = width_in - 2 * _MARGIN_IN
    title = "\n".join(_wrap(fig, line, text_in, 10.0) for line in table.title.split("\n"))
    footnote = _wrap(fig, table.footnote, text_in, 7.0)
    row_in = _ROW_PT / 72.0
    title_in = (title.count("\n") + 1) * 10.0 * 1.3 / 72.0
    foot_in = (footnote.count("\n") + 1) * 7.0 * 1.3 / 72.0
    body_in = (n_head + len(table.cells)) * row_in + 0.15
    height_in = _MARGIN_IN + title_in + 0.15 + body_in + 0.1 + foot_in + 0.3  # 0.3: the provenance strip
    fig.set_size_inches(width_in, height_in)
    fig.set_layout_engine("none")  # the texts are placed here, in inches
    W, H = width_in, height_in

    def at(x_in, y_in):  # from the top left, in figure fractions
        return x_in / W, 1.0 - y_in / H

    fig.text(*at(_MARGIN_IN, _MARGIN_IN), title, fontsize=10.0, ha="left", va="top")
    left = _MARGIN_IN + (width_in - 2 * _MARGIN_IN - table_in) / 2
    x_left, x = [], left
    for w in widths:
        x_left.append(x)
        x += w + _PAD_IN
    top = _MARGIN_IN + title_in + 0.15
    for j, texts in enumerate(head_texts):
        x_j = x_left[j] + (widths[j] if numeric[j] else 0.0)
        first = n_head - len(texts)  # the heads aligned on their last line (the unit)
        for k, text in enumerate(texts):
            text.set_position(at(x_j, top + (first + k + 0.8) * row_in))
    rule = top + n_head * row_in + 0.05
    _rule(fig, at(left, rule), at(left + table_in, rule), 0.8)
    y_prev_event = None
    for i, texts in enumerate(cell_texts):
        y = rule + (i + 0.8) * row_in + 0.03
        event = table.cells[i][1] if ida.event is not None else None
        if event is not None and y_prev_event is not None and event != y_prev_event:
            y_line = rule + i * row_in + 0.03
            _rule(fig, at(left, y_line), at(left + table_in, y_line), 0.3)  # a thin line between two events
        y_prev_event = event
        for j, text in enumerate(texts):
            text.set_position(at(x_left[j] + (widths[j] if numeric[j] else 0.0), y))
    bottom = rule + len(table.cells) * row_in + 0.08
    _rule(fig, at(left, bottom), at(left + table_in, bottom), 0.8)
    fig.text(*at(_MARGIN_IN, bottom + 0.08), footnote, fontsize=7.0, ha="left", va="top")
    note = provenance(ida.code_version, ida.path.rsplit("/", 1)[-1])
    table.png_path = save_figure(fig, png_path, note=note)
    return table


def _rule(fig, start, end, linewidth: float) -> None:
    from matplotlib.lines import Line2D

    fig.add_artist(Line2D([start[0], end[0]], [start[1], end[1]], transform=fig.transFigure, color="black",
                          linewidth=linewidth))
