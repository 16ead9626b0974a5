"""The figures README.md and docs/ show are the ones scripts/readme_figures.py draws,
each drawn at a clean commit that already holds the last change of the code that draws
it: a figure drawn from a modified tree, or older than a change of its drawing code,
fails here (the commit is the one recorded inside the PNG, never a file time: a fresh
clone's file times are its checkout's). Redraw with scripts/readme_figures.py."""

from __future__ import annotations

import importlib.util
import re
import subprocess
import sys

from conftest import REPO_ROOT
from voussoir_post.plots.drawing import PNG_COMMIT_KEY, PNG_TREE_KEY, png_provenance

FIGURES_DIR = REPO_ROOT / "docs" / "figures"
REDRAW = "redraw with: .venv/bin/python scripts/readme_figures.py (on a clean tree, after scripts/main_job.sh)"


def _script():
    spec = importlib.util.spec_from_file_location("readme_figures", REPO_ROOT / "scripts" / "readme_figures.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


def _git(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(["git", "-C", str(REPO_ROOT), *args], capture_output=True, text=True)


def test_every_figure_the_docs_show_is_drawn_by_the_script_or_named():
    script = _script()
    drawn = {f.png for f in script.FIGURES} | set(script.OTHER_FIGURES)
    shown = set()
    for doc in [REPO_ROOT / "README.md", *sorted((REPO_ROOT / "docs").glob("*.md"))]:
        shown |= set(re.findall(r"figures/([\w.-]+\.png)", doc.read_text()))
    assert shown, "README.md and docs/ show no figure of docs/figures"
    assert shown <= drawn, f"figures shown but drawn by nobody known: {sorted(shown - drawn)}"
    assert {f.png for f in script.FIGURES} <= shown, "the script draws a figure no document shows"


def test_readme_figures_are_drawn_at_a_clean_commit_after_their_code():
    assert _git("rev-parse", "--is-inside-work-tree").stdout.strip() == "true", "not a git clone"
    stale = []
    for fig in _script().FIGURES:
        png = FIGURES_DIR / fig.png
        assert png.is_file(), f"{png} is missing; {REDRAW}"
        meta = png_provenance(png)
        commit, tree = meta.get(PNG_COMMIT_KEY), meta.get(PNG_TREE_KEY)
        if not commit or commit == "unknown":
            stale.append(f"{fig.png} records no drawing commit")
            continue
        if tree != "clean":
            stale.append(f"{fig.png} was drawn from a {tree} tree at {commit[:10]}")
        if _git("cat-file", "-e", f"{commit}^{{commit}}").returncode != 0:
            stale.append(f"{fig.png} was drawn at {commit[:10]}, a commit this clone does not have")
            continue
        for module in fig.modules:
            path = f"postproc/voussoir_post/{module}"
            last = _git("log", "-1", "--format=%H", "--", path).stdout.strip()
            assert last, f"{path}: no commit (a module named in scripts/readme_figures.py that git does not know)"
            if _git("merge-base", "--is-ancestor", last, commit).returncode != 0:
                stale.append(f"{fig.png} was drawn at {commit[:10]}, before {path} changed in {last[:10]}")
    assert not stale, "\n".join(stale + [REDRAW])
