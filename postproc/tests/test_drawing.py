"""The small print of every figure (its provenance note) never covers what the figure
shows: it gets a strip of its own below the axes, their labels and tick labels."""

from __future__ import annotations

import numpy as np

from voussoir_post.plots.drawing import new_figure, save_png


def _overlaps(a, b) -> bool:
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def test_the_provenance_note_overlaps_no_axis_and_no_label(tmp_path):
    note = "voussoir 1.0 (a long provenance note) | from a file with a long path, to reach the labels"
    for width, height, n_axes in ((7.5, 2.2, 1), (5.0, 4.0, 2), (11.0, 3.6, 2)):
        fig = new_figure(width, height)
        axes = np.atleast_1d(fig.subplots(1, n_axes))
        for ax in axes:
            ax.plot([0, 1], [0, 1], label="a curve")
            ax.set_xlabel("a long x label that runs the whole width of the axis [m/s2]")
            ax.set_ylabel("y [mm]")
            ax.set_xticks([0, 0.5, 1])
            ax.set_xticklabels(["first\ntwo lines", "middle", "last\ntwo lines"])
        save_png(fig, tmp_path / "f.png", note=note)
        renderer = fig.canvas.get_renderer()
        text = [t for t in fig.texts if t.get_text().startswith(note)][0].get_window_extent(renderer)
        for ax in axes:
            assert not _overlaps(text, ax.get_tightbbox(renderer)), (width, height, n_axes)


def test_every_png_records_the_commit_and_tree_that_drew_it(tmp_path):
    """The PNG's text chunks and its small print name the commit of the drawing code, as
    git itself reports it for this package's folder."""
    import subprocess

    from voussoir_post.plots import drawing

    here = drawing.__file__
    folder = __import__("os").path.dirname(here)
    head = subprocess.run(["git", "-C", folder, "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "-C", folder, "status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True).stdout.strip()
    fig = new_figure(4.0, 3.0)
    fig.subplots().plot([0, 1], [0, 1])
    path = save_png(fig, tmp_path / "f.png", note="a note")
    meta = drawing.png_provenance(path)
    assert meta[drawing.PNG_COMMIT_KEY] == head and len(head) == 40
    assert meta[drawing.PNG_TREE_KEY] == ("modified" if dirty else "clean")
    (strip,) = [t.get_text() for t in fig.texts if t.get_text().startswith("a note")]
    assert f"drawn by {head[:10]}" in strip and (("modified tree" in strip) == bool(dirty))
