"""The fragility figures read as a paper's figures: two title lines at most; one legend
entry per model (its numbers) and one per kind of mark, so that the dashed curves at the
median's lower bound read as bounds of their model and not as more models; the warning
about record scales in the legend, where it is read, not only in the small print. The
IDA tables are written by hand (test_fragility_ida.py, test_fragility_lambda_g.py); one
of them has rows scaled beyond 4."""

from __future__ import annotations

import numpy as np
import pytest

from test_fragility_ida import SCALES, csv_fixture
from test_fragility_lambda_g import CAPACITIES, ratio_fixture
from voussoir_post.cli import post

LABELS = ("nominal model", "as the tests revealed it")


def _legend_labels(fig) -> list[str]:
    (legend,) = fig.legends
    return [t.get_text().replace("\n", " ") for t in legend.get_texts() if t.get_text().strip()]


def _files(tmp_path, axis):
    if axis == "pga":
        # the second file's rows at 0.7 x the first's: 2 of its 6 collapse below a scale of 0.25
        return csv_fixture(tmp_path / "a.csv", SCALES), csv_fixture(tmp_path / "b.csv", np.asarray(SCALES) * 0.7)
    return ratio_fixture(tmp_path / "a.csv")[0], ratio_fixture(tmp_path / "b.csv", CAPACITIES * 0.6, seed=3)[0]


@pytest.mark.parametrize("axis", ["pga", "pga-lambda-g"])
def test_compare_one_entry_per_model_and_per_kind(tmp_path, drawn_figures, axis):
    a, b = _files(tmp_path, axis)
    assert post.main(["fragility", str(a), "--compare", str(b), "--labels", *LABELS, "--axis", axis,
                      "--bootstrap", "20", "--out", str(tmp_path)]) == 0
    (fig,) = drawn_figures
    assert fig._suptitle.get_text().count("\n") <= 1  # two title lines at most
    labels = _legend_labels(fig)
    for label in LABELS:
        mine = [t for t in labels if t.startswith(f"{label}:") and not t.startswith(f"{label}: warning: ")]
        assert len(mine) == 1, mine  # the model's one entry (a warning of its rows apart)
    bounds = [t for t in labels if "lower 5 % bound (95 % confident" in t]
    assert bounds and all("a bound of the model of its colour" in t for t in bounds)
    assert not any(t.startswith(LABELS) and "bound (95 %" in t for t in labels)
    assert sum("IDA points" in t for t in labels) == 1
    assert len(labels) <= 12


@pytest.mark.parametrize("axis", ["pga", "pga-lambda-g"])
def test_the_scale_warning_is_in_the_legend(tmp_path, drawn_figures, axis):
    """Rows collapsed at a record scale beyond 4 or below 0.25: said in the legend."""
    a, b = _files(tmp_path, axis)
    assert post.main(["fragility", str(b), "--axis", axis, "--bootstrap", "20", "--out", str(tmp_path)]) == 0
    fig = drawn_figures[0]  # the fragility, then the record table
    assert fig._suptitle.get_text().count("\n") <= 1
    warnings = [t for t in _legend_labels(fig) if t.startswith("warning: ")]
    assert len(warnings) == 1 and "rows collapsed at a record scale beyond 4 or below 0.25" in warnings[0]
    drawn_figures.clear()
    assert post.main(["fragility", str(b), "--compare", str(a), "--labels", *LABELS, "--axis", axis,
                      "--bootstrap", "20", "--out", str(tmp_path)]) == 0
    (fig,) = drawn_figures
    assert any(t.startswith(f"{LABELS[0]}: warning: ") for t in _legend_labels(fig))
