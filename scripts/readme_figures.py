#!/usr/bin/env python3
"""Redraw the figures that README.md and docs/ show (docs/figures/) from the main job's
results, with the drawing code of this clone, at a clean commit.

    .venv/bin/python scripts/readme_figures.py [--results results] [--campaign DIR] [--out docs/figures]

Run it after `bash scripts/main_job.sh` (which fills results/) on a tree whose tracked
files are all committed: every PNG records the commit that drew it and whether the tree
was modified (plots/drawing.py, save_png), and postproc/tests/test_readme_figures.py
fails when a figure was drawn from a modified tree or before the last commit of the code
that draws it (FIGURES below). Then commit docs/figures/.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "postproc"))  # this clone's postprocessor, whatever is installed


@dataclass(frozen=True)
class ReadmeFigure:
    """A figure of docs/figures: the voussoir-post command that draws it ({results},
    {campaign} filled in) and the modules of postproc/voussoir_post whose code draws it."""

    png: str
    command: tuple[str, ...]
    modules: tuple[str, ...]


_DRAWING = "plots/drawing.py"
FIGURES = (
    ReadmeFigure("sweep_envelope_156_envelope.png",
                 ("envelope", "{results}/sweep_envelope_156.h5", "--campaign", "{campaign}", "--specimen", "A156",
                  "--limit", "{results}/limit_seed_156.json"),
                 ("plots/envelope.py", _DRAWING, "analysis/afd.py")),
    ReadmeFigure("ida_156_compare_fragility.png",
                 ("fragility", "{results}/ida_156.h5", "--compare", "{results}/ida_156_calibrated.h5",
                  "--labels", "nominal model", "as the tests revealed it"),
                 ("plots/fragility_compare.py", "plots/fragility_plot.py", _DRAWING)),
    ReadmeFigure("ida_156_compare_fragility_pga_lambda_g.png",
                 ("fragility", "{results}/ida_156.h5", "--compare", "{results}/ida_156_calibrated.h5",
                  "--axis", "pga-lambda-g", "--labels", "nominal model", "as the tests revealed it"),
                 ("plots/fragility_lambda_g.py", "plots/fragility_compare.py", "plots/fragility_plot.py",
                  "earthquake/im_fragility.py", _DRAWING)),
    ReadmeFigure("seed_156_A66mm_sequence.png", ("sequence", "{results}/seed_156_A66mm.h5"),
                 ("plots/sequence.py", _DRAWING, "analysis/kinematics.py", "analysis/afd.py")),
    ReadmeFigure("sweep_seed_tests_compare.png", ("compare", "{results}/sweep_seed_tests.h5", "{campaign}"),
                 ("plots/compare.py", "plots/envelope.py", _DRAWING)),
    ReadmeFigure("limit_seed_156_mechanism.png", ("mechanism", "{results}/limit_seed_156.json"),
                 ("plots/mechanism.py", _DRAWING)),
    ReadmeFigure("seed_156_A66mm_history.png", ("history", "{results}/seed_156_A66mm.h5"),
                 ("plots/history.py", _DRAWING, "analysis/afd.py")),
)

#: Figures the docs show that other programs draw (not from results/), and which.
OTHER_FIGURES = {
    "diagnosis_reliability.png": "bench/diagnosis_calibration.sh (the calibration study)",
    "bridge_two_spans_ida_fragility.png": "voussoir-post fragility on the IDA of the two-span bridge "
                                          "(docs/bridges.md, \"The bridge under earthquakes\")",
    "bridge_backing_mechanism.png": "voussoir-post mechanism on voussoir-limit --json of input/bridge_backing.nml "
                                    "(docs/bridges.md, \"Backing\")",
}


def tree_state() -> tuple[str, bool]:
    """(HEAD commit, whether tracked files differ from it)."""
    head = subprocess.run(["git", "-C", ROOT, "rev-parse", "HEAD"], capture_output=True, text=True, check=True)
    status = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                            capture_output=True, text=True, check=True)
    return head.stdout.strip(), bool(status.stdout.strip())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--results", default=os.path.join(ROOT, "results"), help="the main job's results (results/)")
    parser.add_argument("--campaign", default=os.path.join(ROOT, "data", "seed_2013"),
                        help="the seed campaign folder (data/seed_2013)")
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "figures"), help="where the PNGs go")
    args = parser.parse_args(argv)
    head, modified = tree_state()
    if modified:
        print("readme_figures: error: the tree has uncommitted changes to tracked files; commit them first "
              "(each figure records the commit that drew it, and a figure drawn from a modified tree fails "
              "postproc/tests/test_readme_figures.py)", file=sys.stderr)
        return 2
    from voussoir_post.cli import post

    os.makedirs(args.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        for fig in FIGURES:
            command = [part.format(results=os.path.abspath(args.results), campaign=os.path.abspath(args.campaign))
                       for part in fig.command]
            status = post.main(command + ["--out", work + os.sep])
            drawn = os.path.join(work, fig.png)
            if status != 0 or not os.path.isfile(drawn):
                print(f"readme_figures: error: voussoir-post {' '.join(command)} did not draw {fig.png}",
                      file=sys.stderr)
                return 1
            shutil.copyfile(drawn, os.path.join(args.out, fig.png))
            print(f"readme_figures: {os.path.join(args.out, fig.png)} (drawn at {head[:10]})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
