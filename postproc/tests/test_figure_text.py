"""No text box of a figure the main job draws overlaps another or is cut by the
figure's edge (titles, axis labels, tick labels, legends, the provenance strip), by
matplotlib's renderer extents (figure_text.py). The envelope and compare figures are
checked on their sweep in test_sweep.py, the sequence and the history in
test_run_plots.py; here the mechanism (a real voussoir-limit JSON), the reactions and the
thrust line (the short real run of conftest.py), and the fragility
figures (IDA tables written by hand, as test_fragility_ida.py writes them), the IDA's
record table (rows written as test_record_table.py writes them), and the
diagnosis's figures (report.md's and the calibration's reliability figure) from a few
numbers written here. Each figure is drawn once, small inputs: seconds in all."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from conftest import run_executable
from figure_text import text_boxes, text_clashes
from voussoir_post.cli import post
from voussoir_post.analysis.afd import afd_command
from voussoir_post.diagnosis import figures
from voussoir_post.diagnosis.observations import PairObservation
from voussoir_post.plots.drawing import new_figure, provenance, save_png
from voussoir_post.readers.campaign import Record, Test as CampaignTest
from test_fragility_ida import SCALES, csv_fixture
from test_fragility_lambda_g import CAPACITIES, ratio_fixture
from test_record_table import SCALES as RECORD_SCALES, _ida as record_rows
from voussoir_post.plots.record_table import plot_record_table


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


@pytest.mark.parametrize("command", ["reactions", "thrust"])
def test_reactions_and_thrust_text(run_copy, tmp_path, drawn_figures, command):
    """The figures of a run's contact forces: their titles (the run's caption is long) not
    cut by the figure's edge, and clear of it by a tenth of an inch (the reactions' caption
    line ran the figure's full width and lost its first character in the PNG)."""
    assert post.main([command, str(run_copy), "--out", str(tmp_path)]) == 0
    (fig,) = drawn_figures
    assert text_clashes(fig) == []
    (title,) = [box for name, box in text_boxes(fig) if name.startswith("suptitle")]
    margin = 0.1 * fig.dpi
    assert margin <= title.x0 and title.x1 <= fig.bbox.width - margin


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


@pytest.mark.parametrize("compare", [False, True])
def test_fragility_lambda_g_text(tmp_path, drawn_figures, compare):
    """The dimensionless figure (--axis pga-lambda-g), alone and with --compare."""
    a, _ = ratio_fixture(tmp_path / "a.csv")
    args = ["fragility", str(a), "--axis", "pga-lambda-g", "--bootstrap", "20", "--out", str(tmp_path)]
    if compare:
        b, _ = ratio_fixture(tmp_path / "b.csv", CAPACITIES * 0.6, seed=3)
        args += ["--compare", str(b), "--labels", "nominal model", "as the tests revealed it"]
    assert post.main(args) == 0
    assert len(drawn_figures) == (1 if compare else 2)  # alone, the record table too
    for fig in drawn_figures:
        assert text_clashes(fig) == []


@pytest.mark.parametrize("n_samples", [2, 6])
def test_record_table_text(tmp_path, drawn_figures, n_samples):
    """The record table, with flagged and bounded cells: a column per model sample, and
    the median and range of six."""
    scales = np.vstack([RECORD_SCALES] * (n_samples // 2))
    censored = np.zeros(scales.shape, bool)
    censored[0, 2] = True
    plot_record_table(record_rows(scales, censored), str(tmp_path / "a_fragility_records.png"))
    (fig,) = drawn_figures
    assert text_clashes(fig) == []


# The diagnosis's figures (report.md's and the calibration's reliability figure), each from
# a few numbers written here: no simulation, no campaign folder.
_PAIRS = [PairObservation("A156", 1.25, 0.0, 0.046), PairObservation("A132", 1.6, 0.0, 0.056),
          PairObservation("A118", 2.0, 0.031, 0.038)]  # two open below (as the seed's), one closed


@pytest.mark.parametrize("shown", [None, "contact_edges+friction"])
def test_diagnosis_thresholds_text(tmp_path, drawn_figures, shown):
    name = figures.thresholds_figure(tmp_path, _PAIRS, [0.064, 0.072, 0.041], shown, 0.41,
                                     [0.030, 0.045, 0.036] if shown else None, provenance("v", "campaign test"))
    assert (tmp_path / name).is_file()
    (fig,) = drawn_figures
    assert text_clashes(fig) == []


@pytest.mark.parametrize("n_models", [1, 12])
def test_diagnosis_probabilities_text(tmp_path, drawn_figures, n_models):
    names = ["none", "friction", "contact_edges", "geometry", "base_restraint", "table_motion",
             "contact_edges+friction", "contact_edges+geometry", "friction+geometry", "base_restraint+friction",
             "base_restraint+table_motion", "geometry+table_motion"][:n_models]
    weights = np.arange(n_models, 0, -1, dtype=float)
    figures.probabilities_figure(tmp_path, dict(zip(names, weights / weights.sum())), provenance("v", "test"))
    (fig,) = drawn_figures
    assert text_clashes(fig) == []


def test_diagnosis_table_text(tmp_path, drawn_figures):
    t = np.arange(0.0, 3.2, 0.005)
    tests = {tid: CampaignTest(tid, "A156", "afd", "stand", 1.25, a) for tid, a in (("T1", 0.020), ("T2", 0.040))}
    # The measured motion: the command of T2 a little late and 5 % short (no fit made here).
    measured = 0.95 * afd_command(t - 0.012, 1.25, 0.040, 1, 1, 1)
    records = {"T2": Record("T2", "records/T2.csv", t, measured)}
    table = SimpleNamespace(source="records", per_test=[("T1", 0.97, 0.010, 1e-4), ("T2", 0.95, 0.012, 1e-4)])
    campaign = SimpleNamespace(tests=tests, records=records)
    assert figures.table_figure(tmp_path, campaign, table, provenance("v", "test")) == "table_records.png"
    (fig,) = drawn_figures
    assert text_clashes(fig) == []


def test_diagnosis_reliability_text(tmp_path, drawn_figures):
    # (bin low, high, draws, mean stated, fraction right, 95 % interval): points near both
    # corners, as the calibration's (docs/figures/diagnosis_reliability.png).
    bins = [(0.2, 0.4, 60, 0.32, 0.32, 0.21, 0.44), (0.4, 0.6, 120, 0.50, 0.53, 0.44, 0.61),
            (0.8, 0.9, 15, 0.87, 1.0, 0.80, 1.0), (0.9, 1.0, 40, 0.94, 1.0, 0.91, 1.0)]
    figures.reliability_figure(tmp_path, bins, provenance("bench/diagnosis_calibration.sh", "40 truths x 10"))
    (fig,) = drawn_figures
    assert text_clashes(fig) == []
