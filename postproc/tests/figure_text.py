"""The text boxes of a drawn figure, by matplotlib's renderer extents: titles, axis
labels, tick labels (of the ticks in view), legends and the figure's own texts (the
suptitle, the provenance strip), secondary axes included. Notes drawn inside an axes
(annotations, a hinge label) belong to the drawing and are left out.

``text_clashes(fig)`` names every pair of boxes that overlap and every box that the
figure's edge clips: a figure fit for a report has neither."""

from __future__ import annotations

from matplotlib.figure import Figure

from voussoir_post.plots.drawing import RASTER_DPI


def _all_axes(fig: Figure):
    out = []
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        out.append(ax)
        out.extend(c for c in getattr(ax, "child_axes", []) if c.get_visible())
    return out


def text_boxes(fig: Figure) -> list[tuple[str, object]]:
    """(name, window extent) of every text box of the figure, drawn at save_figure's dpi."""
    fig.set_dpi(RASTER_DPI)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    boxes = []

    def add(name, artist):
        if artist is None or not artist.get_visible():
            return
        if hasattr(artist, "get_text") and not artist.get_text().strip():
            return
        boxes.append((name, artist.get_window_extent(renderer)))

    for k, t in enumerate(fig.texts):
        if t is not fig._suptitle:
            add(f"figure text {k} {t.get_text()[:40]!r}", t)
    if fig._suptitle is not None:
        add(f"suptitle {fig._suptitle.get_text()[:40]!r}", fig._suptitle)
    for k, leg in enumerate(fig.legends):
        add(f"figure legend {k}", leg)
    for a, ax in enumerate(_all_axes(fig)):
        for where in ("left", "center", "right"):
            title = ax._left_title if where == "left" else ax.title if where == "center" else ax._right_title
            add(f"axes {a} title {title.get_text()[:40]!r}", title)
        for axis_name, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
            if not axis.get_visible():
                continue
            add(f"axes {a} {axis_name} label {axis.label.get_text()[:30]!r}", axis.label)
            for tick in axis._update_ticks():  # the ticks in view, as drawn
                for t in (tick.label1, tick.label2):
                    add(f"axes {a} {axis_name} tick {t.get_text()!r}", t)
            add(f"axes {a} {axis_name} offset", axis.get_offset_text())
        if ax.get_legend() is not None:
            add(f"axes {a} legend", ax.get_legend())
    return boxes


def _overlap(a, b, slack_px: float = 0.5) -> bool:
    return (a.x0 + slack_px < b.x1 and b.x0 + slack_px < a.x1 and
            a.y0 + slack_px < b.y1 and b.y0 + slack_px < a.y1)


def text_clashes(fig: Figure) -> list[str]:
    """Every overlapping pair of text boxes, and every box the figure's edge cuts."""
    boxes = text_boxes(fig)
    width, height = fig.bbox.width, fig.bbox.height
    clashes = []
    for name, box in boxes:
        if box.x0 < -0.5 or box.y0 < -0.5 or box.x1 > width + 0.5 or box.y1 > height + 0.5:
            clashes.append(f"{name} is cut by the figure's edge ({box} in {width:.0f} x {height:.0f})")
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            if _overlap(boxes[i][1], boxes[j][1]):
                clashes.append(f"{boxes[i][0]} overlaps {boxes[j][0]}")
    return clashes
