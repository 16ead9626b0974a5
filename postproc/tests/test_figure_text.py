"""No text box of a figure the main job draws overlaps another or is cut by the
figure's edge (titles, axis labels, tick labels, legends, the provenance strip), by
matplotlib's renderer extents (figure_text.py). The envelope and compare figures are
checked on their sweep in test_sweep.py, the sequence and the history in
test_run_plots.py; here the mechanism (a real voussoir-limit JSON), and the fragility
figures (IDA tables written by hand, as test_fragility_ida.py writes them). Each
figure is drawn once, small inputs: seconds in all."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import run_executable
from figure_text import text_boxes, text_clashes
from voussoir_post.cli import post
from voussoir_post.plots.drawing import new_figure, save_png
from test_fragility_ida import SCALES, csv_fixture


def test_the_check_sees_an_overlap_and_a_cut(tmp_path):
    """The check itself: a title struck by a legend and a label pushed off the figure."""
    fig = new_figure(5.0, 3.0)
    ax = fig.subplots()
    ax.plot([0, 1], [0, 1], label="a curve with a long label")
    ax.set_title("a title")
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0))  # on top of the title
    ax.set_xlabel("x [m]")
    ax.xaxis.set_label_coords(1.3, -0.1)  # beyond the right edge
    save_png(fig, tmp_path / "bad.png", note="voussoir test | from nothing")
    clashes = text_clashes(fig)
    assert any("title 'a title'" in c and "legend" in c for c in clashes)
    assert any("x label" in c and "cut by the figure's edge" in c for c in clashes)
    names = [name for name, _ in text_boxes(fig)]
    assert any(name.startswith("figure text") and "voussoir test" in name for name in names)


def test_mechanism_text(voussoir_limit_exe, tmp_path, drawn_figures):
    nml = tmp_path / "limit.nml"
    nml.write_text("&arch embrace_deg = 156, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071,\n"
                   "  width_m = 0.145, density_kg_m3 = 700, friction = 0.5 /\n")
    path = tmp_path / "limit.json"
    path.write_text(run_executable([voussoir_limit_exe, nml, "--json"], tmp_path).stdout)
    assert post.main(["mechanism", str(path), "--out", str(tmp_path / "m.png")]) == 0
    (fig,) = drawn_figures
    assert text_clashes(fig) == []


@pytest.mark.parametrize("compare", [False, True])
def test_fragility_text(tmp_path, drawn_figures, compare):
    a = csv_fixture(tmp_path / "a.csv", SCALES)
    args = ["fragility", str(a), "--bootstrap", "20", "--out", str(tmp_path)]
    if compare:
        b = csv_fixture(tmp_path / "b.csv", np.asarray(SCALES) * 0.7)
        args += ["--compare", str(b), "--labels", "nominal model", "as the tests revealed it"]
    assert post.main(args) == 0
    assert drawn_figures
    for fig in drawn_figures:
        assert text_clashes(fig) == []
