"""The record table of an IDA (plots/record_table.py) on IDA rows written here: each
cell against the value given to the rows (the scale at the collapse of one record on
one model sample, the median with more than four samples, the record's own data), the
order by event then record, the mark of a scale beyond 4 or below 0.25, the columns the
rows leave empty left out, a lower bound where no collapse was found, and the figure
written beside the fragility by `voussoir-post fragility`."""

from __future__ import annotations

import numpy as np
import pytest

from figure_text import text_clashes
from test_fragility_ida import csv_fixture
from voussoir_post.cli.post import main
from voussoir_post.earthquake.ida import IdaResult
from voussoir_post.plots.record_table import FLAG_MARK, LOWER_BOUND, plot_record_table, record_table

G = 9.81
# Four records of three events, given out of order: sorted by event then record they are
# A/r0, A/r1 (Alpha 1990), C/r3 (Mid 1995), B/r2 (Zeta 2000).
NAMES = ["B/r2", "A/r1", "C/r3", "A/r0"]
EVENTS = ["Zeta 2000", "Alpha 1990", "Mid 1995", "Alpha 1990"]
SORTED = ["A/r0", "A/r1", "C/r3", "B/r2"]
MAGNITUDE = [7.4, 6.1, 6.8, 6.1]
DISTANCE_KM = [31.5, 8.2, 14.0, 12.7]
UNIT_PGA = np.array([1.2, 3.3, 2.1, 4.9])  # m/s2, at scale 1
TP_S = [np.nan, 1.8, np.nan, np.nan]  # one pulse: the column shown
# The scale at the collapse, [model sample][record]: B/r2 on sample 1 beyond 4, A/r0 on
# sample 0 below 0.25; the others within.
SCALES = np.array([[2.5, 0.9, 1.3, 0.21], [4.6, 1.1, 1.7, 0.3]])


def _ida(scales, censored=None, names=NAMES, events=EVENTS) -> IdaResult:
    n_sets, n_records = scales.shape
    censored = np.zeros(scales.shape, bool) if censored is None else censored
    rep = lambda values: np.tile(np.asarray(values, float), n_sets)  # noqa: E731 (rows: sample-major)
    threshold = scales.reshape(-1)
    return IdaResult(path="synthetic.h5", record=list(names) * n_sets,
                     param_set=np.repeat(np.arange(n_sets), n_records), scale_stood=0.95 * threshold,
                     scale_threshold=threshold, pga_m_s2=threshold * rep(UNIT_PGA), pgv_m_s=threshold * 0.1,
                     censored=censored.reshape(-1), event=list(events) * n_sets, unit_pga_m_s2=rep(UNIT_PGA),
                     unit_pgv_m_s=rep([0.1] * n_records), magnitude=rep(MAGNITUDE), distance_km=rep(DISTANCE_KM),
                     vs30_m_s=rep([np.nan] * n_records), pulse=rep([np.nan, 1, 0, 0]), pulse_period_s=rep(TP_S))


def _value(cell: str) -> float:
    return float(cell.removesuffix(FLAG_MARK.strip()).strip().removeprefix(LOWER_BOUND.strip()))


def _heads(table) -> list[str]:
    return [" ".join(h) for h in table.heads]


def _column(table, head: str) -> list[str]:
    return [row[_heads(table).index(head)] for row in table.cells]


def test_cells_are_the_rows_values_sorted_by_event_then_record():
    table = record_table(_ida(SCALES))
    assert [c.removesuffix(FLAG_MARK) for c in _column(table, "record")] == SORTED
    original = [NAMES.index(name) for name in SORTED]
    assert _column(table, "event") == [EVENTS[k] for k in original]
    assert [_value(c) for c in _column(table, "M [Mw]")] == pytest.approx([MAGNITUDE[k] for k in original])
    assert [_value(c) for c in _column(table, "R (Rrup) [km]")] == pytest.approx([DISTANCE_KM[k] for k in original])
    assert [_value(c) for c in _column(table, "PGA (record) [g]")] == pytest.approx(UNIT_PGA[original] / G,
                                                                                     abs=5e-4)
    for s in range(2):
        cells = _column(table, f"scale at collapse, model {s} [-]")
        assert [_value(c) for c in cells] == pytest.approx(SCALES[s, original], abs=5e-3)
    # two samples: the PGA at the collapse is their median (the mean of two)
    collapse_g = SCALES[:, original].mean(axis=0) * UNIT_PGA[original] / G
    assert [_value(c) for c in _column(table, "PGA at collapse, median [g]")] == pytest.approx(collapse_g, abs=5e-4)


def test_columns_empty_for_every_record_are_left_out():
    heads = _heads(record_table(_ida(SCALES)))
    assert "Tp (pulse) [s]" in heads  # one record has a pulse period
    assert not any(h.startswith("Vs30") for h in heads)  # NaN for every record
    # no event, nor period: neither column; the records then sorted by name
    ida = _ida(SCALES)
    ida.event, ida.pulse_period_s = None, np.full(ida.n_rows, np.nan)
    table = record_table(ida)
    assert not any(h.startswith(("event", "Tp")) for h in _heads(table))
    assert _column(table, "record")[:2] == ["A/r0" + FLAG_MARK, "A/r1"]
    assert [c.removesuffix(FLAG_MARK) for c in _column(table, "record")] == sorted(NAMES)


def test_scales_beyond_4_or_below_quarter_are_marked():
    table = record_table(_ida(SCALES))
    marked = [row[0].endswith(FLAG_MARK) for row in table.cells]
    assert marked == [True, False, False, True]  # A/r0 (0.21 on sample 0), B/r2 (4.6 on sample 1)
    assert table.flagged == marked
    head = _heads(table)
    assert (0, head.index("scale at collapse, model 0 [-]")) in table.flagged_cells
    assert (3, head.index("scale at collapse, model 1 [-]")) in table.flagged_cells
    assert (3, head.index("scale at collapse, model 0 [-]")) not in table.flagged_cells  # 2.5 is within
    assert "beyond 4 or below 0.25" in table.footnote and "2 of the 4 records" in table.footnote
    # a scale exactly at the limits is within them
    within = record_table(_ida(np.array([[4.0, 0.25, 1.0, 1.0]])))
    assert not any(within.flagged)


def test_many_samples_give_median_and_range():
    rng = np.random.default_rng(7)
    scales = rng.uniform(0.5, 3.0, (6, 4))
    table = record_table(_ida(scales))
    heads = _heads(table)
    assert not any("model" in h for h in heads)
    original = [NAMES.index(name) for name in SORTED]
    medians = [_value(c) for c in _column(table, "scale at collapse, median [-]")]
    assert medians == pytest.approx(np.median(scales[:, original], axis=0), abs=5e-3)
    for cell, k in zip(_column(table, "scale at collapse, range [-]"), original):
        low, high = (float(v) for v in cell.split("-"))
        assert (low, high) == pytest.approx((scales[:, k].min(), scales[:, k].max()), abs=5e-3)
    pga = [_value(c) for c in _column(table, "PGA at collapse, median [g]")]
    assert pga == pytest.approx(np.median(scales[:, original] * UNIT_PGA[original], axis=0) / G, abs=5e-4)


def test_a_record_without_collapse_is_a_lower_bound():
    censored = np.zeros(SCALES.shape, bool)
    censored[0, NAMES.index("C/r3")] = True  # C/r3 stood on sample 0 up to scale_max 1.3
    table = record_table(_ida(SCALES, censored))
    cell = _column(table, "scale at collapse, model 0 [-]")[SORTED.index("C/r3")]
    assert cell.startswith(LOWER_BOUND) and _value(cell) == pytest.approx(1.3)
    assert "lower bound" in table.footnote
    # the median of two with one bounded below is itself a lower bound
    assert _column(table, "PGA at collapse, median [g]")[SORTED.index("C/r3")].startswith(LOWER_BOUND)


def test_figure_draws_the_cells_without_clashes(tmp_path, drawn_figures):
    long_events = ["Superstition Hills (California) 1987", "Chi-Chi (Taiwan) 1999", "Kocaeli (Turkey) 1999",
                   "Chi-Chi (Taiwan) 1999"]
    table = plot_record_table(_ida(SCALES, events=long_events), str(tmp_path / "t_fragility_records.png"))
    assert (tmp_path / "t_fragility_records.png").is_file()
    (fig,) = drawn_figures
    texts = [t.get_text() for t in fig.texts]
    for row in table.cells:
        for cell in row:
            assert cell in texts
    assert text_clashes(fig) == []


def test_fragility_writes_the_record_table(tmp_path, capsys):
    events = ["Imperial Valley 1940", "Loma Prieta 1989", "San Fernando 1971"]
    path = csv_fixture(tmp_path / "ida.csv", np.array([[1.2, 0.61, 0.33], [1.5, 0.55, 0.29]]), events=events)
    assert main(["fragility", str(path), "--bootstrap", "20"]) == 0
    png = tmp_path / "ida_fragility_records.png"
    assert png.is_file()
    assert f"wrote {png}" in capsys.readouterr().out


def test_near_field_components_are_named_fault_normal_and_fault_parallel():
    """An IDA of the FEMA P695 near-field set names each record's component as the ATC-63
    record files do (NORTHR/RRS_032 fault-normal, NORTHR/RRS_122 fault-parallel; a
    reversed row is its record's); the far-field set's, as recorded, get no column."""
    names = ["NORTHR/RRS_032", "NORTHR/RRS_122", "NORTHR/RRS_122 (reversed)", "LOMAP/CLS_128"]
    ida = _ida(SCALES, names=names, events=["Northridge-01 1994"] * 3 + ["Loma Prieta 1989"])
    ida.record_set = "fema_p695_near_field"
    component = dict(zip(_column(record_table(ida), "record"), _column(record_table(ida), "component")))
    assert {name.removesuffix(FLAG_MARK): c for name, c in component.items()} == {
        "NORTHR/RRS_032": "fault-normal", "NORTHR/RRS_122": "fault-parallel",
        "NORTHR/RRS_122 (reversed)": "fault-parallel", "LOMAP/CLS_128": "fault-parallel"}
    far = _ida(SCALES, names=["NORTHR/MUL009", "NORTHR/MUL279", "NORTHR/LOS000", "NORTHR/LOS270"])
    far.record_set = "fema_p695_far_field"
    assert "component" not in _heads(record_table(far))
