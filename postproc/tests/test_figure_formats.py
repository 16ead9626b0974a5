"""Figures for papers: every figure command of voussoir-post writes PNG (at 200 dpi or
more), PDF or SVG, by --format or by the suffix of an --out file, and --out naming a
file writes exactly that file (never a folder of that name); a suffix that contradicts
--format, or names an image format that is not written, is refused before any work."""

from __future__ import annotations

import argparse

import pytest
from PIL import Image

from conftest import run_executable
from test_fragility_ida import SCALES, csv_fixture
from voussoir_post.cli import post
from voussoir_post.plots import drawing

#: The subcommands that draw a figure.
FIGURE_COMMANDS = ("envelope", "sequence", "history", "reactions", "thrust", "compare", "fragility", "mechanism")


def _kind(path) -> str:
    """What a file is, by its first bytes."""
    head = path.read_bytes()[:400]
    if head.startswith(b"%PDF"):
        return "pdf"
    if head.startswith(b"\x89PNG"):
        return "png"
    if b"<svg" in head:
        return "svg"
    return "unknown"


def test_every_figure_command_takes_format():
    parser = post.build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for name in FIGURE_COMMANDS:
        options = {o: a for a in sub.choices[name]._actions for o in a.option_strings}
        assert "--format" in options, name
        assert tuple(options["--format"].choices) == ("png", "pdf", "svg"), name


def test_out_naming_a_pdf_writes_exactly_that_pdf(run_copy, tmp_path, capsys):
    out = tmp_path / "figs" / "hist.pdf"
    assert post.main(["history", str(run_copy), "--out", str(out)]) == 0
    assert out.is_file() and _kind(out) == "pdf"  # a file, not a folder hist.pdf/
    assert f"wrote {out}" in capsys.readouterr().out
    assert sorted(p.name for p in out.parent.iterdir()) == ["hist.pdf"]
    # the drawing commit is in the PDF's metadata, as in a PNG's text chunks
    assert drawing.PNG_COMMIT_KEY.encode() in out.read_bytes()


@pytest.mark.parametrize("command", ["history", "sequence", "reactions", "thrust"])
def test_format_svg_into_a_folder(run_copy, tmp_path, command):
    assert post.main([command, str(run_copy), "--format", "svg", "--out", str(tmp_path / "figs")]) == 0
    svg = tmp_path / "figs" / f"{run_copy.stem}_{command}.svg"
    assert svg.is_file() and _kind(svg) == "svg"


def test_the_default_is_a_png_at_200_dpi_or_more(run_copy):
    assert post.main(["reactions", str(run_copy)]) == 0
    png = run_copy.parent / f"{run_copy.stem}_reactions.png"
    assert _kind(png) == "png"
    with Image.open(png) as im:
        assert min(im.info["dpi"]) >= 199.5  # 200 dpi, as pixels per metre rounded
        assert im.size[0] >= 200 * 6  # the figure is several inches wide


def test_mechanism_pdf_by_suffix_and_by_format(voussoir_limit_exe, tmp_path):
    nml = tmp_path / "limit.nml"
    nml.write_text("&arch embrace_deg = 156, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071 /\n")
    limit = tmp_path / "limit.json"
    limit.write_text(run_executable([voussoir_limit_exe, nml, "--json"], tmp_path).stdout)
    assert post.main(["mechanism", str(limit), "--out", str(tmp_path / "m.PDF")]) == 0
    assert _kind(tmp_path / "m.PDF") == "pdf"
    assert post.main(["mechanism", str(limit), "--format", "pdf"]) == 0
    assert _kind(tmp_path / "limit_mechanism.pdf") == "pdf"


def test_fragility_writes_its_figure_and_record_table_in_the_format(tmp_path):
    ida = csv_fixture(tmp_path / "ida.csv", SCALES)
    assert post.main(["fragility", str(ida), "--bootstrap", "20", "--out", str(tmp_path / "f.svg")]) == 0
    assert _kind(tmp_path / "f.svg") == "svg" and _kind(tmp_path / "f_records.svg") == "svg"
    assert (tmp_path / "f.csv").is_file() and (tmp_path / "f_points.csv").is_file()
    assert not list(tmp_path.glob("*.png"))


@pytest.mark.parametrize("out, fmt, words", [
    ("hist.png", "pdf", "--out {out} names a PNG file but --format is pdf"),
    ("hist.pdf", "svg", "--out {out} names a PDF file but --format is svg"),
    ("hist.jpg", None, "--out {out}: voussoir-post writes figures as png, pdf, svg"),
])
def test_a_contradicting_or_unwritten_suffix_is_refused(run_copy, tmp_path, capsys, out, fmt, words):
    path = tmp_path / out
    args = ["history", str(run_copy), "--out", str(path)] + (["--format", fmt] if fmt else [])
    assert post.main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith("voussoir-post: error: ") and words.format(out=path) in err
    assert not path.exists()  # neither a file nor a folder
    assert list(tmp_path.iterdir()) == [run_copy]


def test_figure_path_rules():
    def args(out=None, fmt=None):
        return argparse.Namespace(out=out, format=fmt)

    assert post.figure_path("/a/run.h5", "history", args()) == "/a/run_history.png"
    assert post.figure_path("/a/run.h5", "history", args(fmt="svg")) == "/a/run_history.svg"
    assert post.figure_path("/a/run.h5", "history", args("/c", "pdf")) == "/c/run_history.pdf"
    assert post.figure_path("/a/run.h5", "history", args("/c/x.pdf")) == "/c/x.pdf"
    assert post.figure_path("/a/run.h5", "history", args("/c/x.svg", "svg")) == "/c/x.svg"
    assert post.figure_path("/a/run.h5", "history", args("/c/v1.2")) == "/c/v1.2/run_history.png"  # a folder
