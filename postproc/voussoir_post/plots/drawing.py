"""Figure helpers: Agg figures without pyplot (no global figure state), and the one
function that writes a figure (:func:`save_figure`: PNG at 200 dpi, PDF or SVG, chosen by
the file's suffix)."""

from __future__ import annotations

import functools
import math
import os
import subprocess

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ..analysis.afd import afd_peak_accel_per_m
from ..analysis.bridge_report import numbered_setting, vehicle_words
from ..units import G_M_S2

__all__ = ["new_figure", "save_figure", "save_png", "FIGURE_FORMATS", "RASTER_DPI", "figure_format", "MARKERS",
           "COLORS", "G_M_S2", "provenance", "add_g_axis", "run_caption", "arch_caption", "bridge_caption", "vehicle_words", "legend_pad", "NOTE_STRIP_PT",
           "HINGE_COLOURS", "COLLAPSE_COLOUR", "wrap_text", "parameters_in_words", "drawing_tree", "PNG_COMMIT_KEY", "PNG_TREE_KEY", "png_provenance"]

#: Marker style per specimen or parameter set, in order.
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "<", ">", "h")
#: What a colour means in every figure of a structure (sequence, mechanism): a hinge
#: pivoting on the intrados green, on the extrados blue, a separated or sliding joint
#: purple. Red is kept for the collapse (its time, collapsing runs).
HINGE_COLOURS = {"intrados": "tab:green", "extrados": "tab:blue", "separated": "tab:purple"}
COLLAPSE_COLOUR = "tab:red"

#: Colour cycle of data series (matplotlib's tab10 without red, which is the collapse's).
COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:brown",
          "tab:pink", "tab:gray", "tab:olive", "tab:cyan")


def new_figure(width_in: float, height_in: float) -> Figure:
    """A figure drawn by the Agg canvas (independent of pyplot and its global state)."""
    fig = Figure(figsize=(width_in, height_in), layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def wrap_text(text: str, width_in: float, fontsize: float) -> str:
    """``text`` broken into lines that fit ``width_in`` inches at ``fontsize`` points
    (a character taken as 0.52 em: DejaVu Sans averages about 0.5 on prose)."""
    import textwrap
    chars = max(20, int(width_in * 72.0 / (0.52 * fontsize)))
    return "\n".join(textwrap.wrap(text, chars, break_on_hyphens=False)) if len(text) > chars else text


_PARAMETER_WORDS = {
    "embrace_deg": lambda v: f"{v:g}°",
    "n_voussoirs": lambda v: f"{int(round(v))} voussoirs",
    "thickness_m": lambda v: f"t = {1e3 * v:g} mm",
    "r_ext_m": lambda v: f"R_ext = {1e3 * v:g} mm",
    "width_m": lambda v: f"width {1e3 * v:g} mm",
    "friction": lambda v: f"friction {v:g}",
    "contact_inset_m": lambda v: f"contact inset {1e3 * v:g} mm",
    "density_kg_m3": lambda v: f"density {v:g} kg/m³",
    "size_imperfection": lambda v: f"size imperfection {v:g}",
}


def parameters_in_words(parameters: dict) -> str:
    """A parameter set in words ('156°, 13 voussoirs', 't = 65 mm, friction 0.45'),
    the names a sweep swept (with or without their group) turned into engineering text."""
    words = []
    for name, value in parameters.items():
        key = name.replace("%", ".").split(".")[-1].strip().lower()
        say = _PARAMETER_WORDS.get(key)
        words.append(say(float(value)) if say else f"{key} = {float(value):.6g}")
    return ", ".join(words)


def provenance(code_version: str, *sources: str) -> str:
    """The small print of a figure: the code version and what it was made from."""
    made_from = "; ".join(s for s in sources if s)
    return f"{code_version or 'voussoir (version unknown)'}" + (f" | from {made_from}" if made_from else "")


def add_g_axis(ax, label: str = "[g]") -> None:
    """A right-hand axis reading the left one's m/s2 in g (engineers read g)."""
    right = ax.secondary_yaxis("right", functions=(lambda a: a / G_M_S2, lambda g: g * G_M_S2))
    right.set_ylabel(label)


def arch_caption(arch: dict, n_blocks: int | None = None) -> str:
    """The structure of an &arch group, in words."""
    if arch.get("polygon_file"):
        blocks = f"{n_blocks} blocks" if n_blocks else "blocks"
        return f"assembly of {blocks} ({os.path.basename(str(arch['polygon_file']))})"
    return (f"{float(arch.get('embrace_deg', math.nan)):g}° arch of {arch.get('n_voussoirs', '?')} voussoirs "
            f"(t = {1e3 * float(arch.get('thickness_m', math.nan)):g} mm, "
            f"R_ext = {1e3 * float(arch.get('r_ext_m', math.nan)):g} mm)")


def bridge_caption(bridge: dict, vehicle: dict | None = None) -> str:
    """A &bridge group (and a standing &vehicle) in words: 'bridge of 2 segmental spans of
    10 m (rise 2.5 m), ring 450 mm of 20 voussoirs; fill to 3.45 m (2000 kg/m³) as mass the
    ring carries;
    vehicle ... standing from x = 2 m'."""
    spans = [v for v in numbered_setting(bridge, "span_m") if v > 0]
    rises = [v for v in numbered_setting(bridge, "rise_m") if v > 0]
    span_words = ", ".join(f"{s:g}" for s in spans)
    rise_words = ", ".join(f"{r:g}" for r in rises[:len(spans)])
    rings = int(bridge.get("n_rings", 1))
    text = (f"bridge of {len(spans)} {bridge.get('shape', '')} span{'s' if len(spans) > 1 else ''} of {span_words} m "
            f"(rise {rise_words} m), ring {1e3 * float(bridge.get('ring_thickness_m', math.nan)):g} mm"
            f"{f' in {rings} rings' if rings > 1 else ''} of {bridge.get('n_voussoirs', '?')} voussoirs")
    if float(bridge.get("fill_density_kg_m3", 0.0)) > 0:
        pressure = ", its active pressure as forces" if float(bridge.get("fill_friction_deg", 0.0)) > 0 else ""
        text += (f"; fill to {float(bridge.get('fill_level_m', math.nan)):g} m "
                 f"({float(bridge['fill_density_kg_m3']):g} kg/m³) as mass the ring carries{pressure}")
    if vehicle:
        text += f"; {vehicle_words(vehicle)} standing from x = {float(vehicle.get('first_axle_x_m', 0.0)):g} m"
    return text


def run_caption(run, sep: str = ", ") -> str:
    """What a run simulated, in words: the structure and the shaking (joined by `sep`)."""
    arch = run.config.get("arch", {})
    motion = run.config.get("motion", {})
    if "bridge" in run.config:
        what = bridge_caption(run.config["bridge"], run.config.get("vehicle"))
    else:
        what = arch_caption(arch, len(run.body_role))
    wave = motion.get("waveform", "")
    if wave == "afd":
        f, a = float(motion.get("frequency_hz", math.nan)), float(motion.get("amplitude_m", math.nan))
        # The true peak of the commanded motion (its envelopes add to A (2 pi f)^2).
        cycles = (int(motion.get(k, 1)) for k in ("n_attack", "n_full", "n_decay"))
        peak = a * afd_peak_accel_per_m(f, *cycles)
        shake = f"sinusoid {f:g} Hz, A = {1e3 * a:g} mm (peak acceleration {peak:.2f} m/s² = {peak / G_M_S2:.3f} g)"
    elif wave == "accelerogram":
        shake = (f"record {os.path.basename(str(motion.get('record_file', '')))} x "
                 f"{float(motion.get('record_scale', 1.0)):g}")
    else:
        shake = f"{wave} motion" if wave else ""
    return what + (f"{sep}{shake}" if shake else "")


#: Height [pt] of the strip save_png keeps at the bottom for the provenance note.
NOTE_STRIP_PT = 10.0


def legend_pad(fontsize: float) -> float:
    """Pad [font sizes] of a figure legend placed "outside lower center" at `fontsize`,
    so that it clears save_png's strip for the small print: the usual 0.5 plus the strip."""
    return 0.5 + NOTE_STRIP_PT / fontsize


#: PNG text keys of every figure: the commit of the code that drew it, and whether that
#: code's tree had changes ("clean" or "modified"); read back by :func:`png_provenance`.
PNG_COMMIT_KEY = "Voussoir drawing commit"
PNG_TREE_KEY = "Voussoir drawing tree"


@functools.lru_cache(maxsize=1)
def drawing_tree() -> tuple[str, str]:
    """(commit, 'clean' | 'modified') of the git tree this package runs from (tracked
    files only), or ('unknown', 'unknown') outside a git checkout."""
    here = os.path.dirname(os.path.abspath(__file__))

    def git(*args: str) -> str | None:
        try:
            proc = subprocess.run(["git", "-C", here, *args], capture_output=True, text=True, timeout=30)
        except (OSError, subprocess.SubprocessError):
            return None
        return proc.stdout.strip() if proc.returncode == 0 else None

    commit = git("rev-parse", "HEAD")
    status = git("status", "--porcelain", "--untracked-files=no")
    if not commit or status is None:
        return "unknown", "unknown"
    return commit, "modified" if status else "clean"


def png_provenance(path: str | os.PathLike) -> dict[str, str]:
    """The drawing commit and tree that :func:`save_png` wrote into a PNG ({} if none)."""
    from PIL import Image

    with Image.open(path) as im:
        text = dict(getattr(im, "text", {}) or {})
    return {k: text[k] for k in (PNG_COMMIT_KEY, PNG_TREE_KEY) if k in text}


#: The formats :func:`save_figure` writes, by the suffix of the file's name.
FIGURE_FORMATS = ("png", "pdf", "svg")
#: Resolution of the raster format (PNG) [dots per inch]: print quality for a paper.
RASTER_DPI = 200


def figure_format(path: str | os.PathLike) -> str:
    """'png', 'pdf' or 'svg' from the suffix of ``path`` (any case); ValueError for any
    other suffix."""
    suffix = os.path.splitext(os.fspath(path))[1].lower().lstrip(".")
    if suffix not in FIGURE_FORMATS:
        raise ValueError(f"{os.fspath(path)}: a figure is written as .png, .pdf or .svg (the suffix chooses), "
                         f"not {'.' + suffix if suffix else 'without a suffix'}")
    return suffix


def save_figure(fig: Figure, path: str | os.PathLike, note: str | None = None, dpi: int = RASTER_DPI) -> str:
    """Save ``fig`` at ``path`` in the format its suffix names (:func:`figure_format`:
    PNG at ``dpi``, or the vector PDF or SVG), parent folders created; returns the path.
    ``note`` (see :func:`provenance`) is printed small in the bottom right corner,
    followed by the commit of the code that drew the figure ('+modified' when its tree
    had changes), which the file's metadata also records (a PNG's text chunks, read by
    :func:`png_provenance`; a PDF's or SVG's keywords)."""
    fmt = figure_format(path)
    commit, tree = drawing_tree()
    if note:
        note += f" | drawn by {commit[:10]}" + ("" if tree == "clean" else f" ({tree} tree)")
        # A strip of its own at the bottom, so that the note never overlaps an axis label.
        engine = fig.get_layout_engine()
        if engine is not None and hasattr(engine, "set") and "rect" in engine.get():
            strip = NOTE_STRIP_PT / 72.0 / fig.get_figheight()
            engine.set(rect=(0.0, strip, 1.0, 1.0 - strip))
        fig.text(0.995, 0.002, note, ha="right", va="bottom", fontsize=6, color="#777777")
    path = os.fspath(path)
    parent = os.path.dirname(os.path.abspath(path))
    os.makedirs(parent, exist_ok=True)
    stamp = {PNG_COMMIT_KEY: commit, PNG_TREE_KEY: tree}
    metadata = (stamp if fmt == "png" else
                {"Creator": "voussoir-post", "Keywords": "; ".join(f"{k}: {v}" for k, v in stamp.items())})
    fig.savefig(path, dpi=dpi, format=fmt, metadata=metadata)
    return path


#: The name the diagnosis's figures (diagnosis/figures.py) call :func:`save_figure` by.
save_png = save_figure
