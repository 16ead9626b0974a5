"""scripts/seed_2013_analysis.py rewrites docs/seed_2013, which git tracks, and draws its
figures as it goes: each figure is stamped with the commit and whether a tracked file
differs from it (plots/drawing.py, save_png). The output is made in an untracked folder
and only then put in place of the old one, so that the stamp tells the state of the code,
not that of the folder being written. Checked here on a throwaway git repository, with
the same `git status` that the stamp reads."""

from __future__ import annotations

import importlib.util
import shutil
import subprocess
import sys

import pytest

from conftest import REPO_ROOT


def _script():
    spec = importlib.util.spec_from_file_location("seed_2013_analysis", REPO_ROOT / "scripts" / "seed_2013_analysis.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def _git(repo, *args: str) -> str:
    return subprocess.run(["git", "-C", str(repo), *args], capture_output=True, text=True, check=True).stdout


def _tree(repo) -> str:
    """'clean' or 'modified', as save_png stamps a figure (tracked files only)."""
    return "modified" if _git(repo, "status", "--porcelain", "--untracked-files=no").strip() else "clean"


@pytest.fixture
def repo(tmp_path):
    """A repository with code and a committed output folder docs/out (a report and a figure)."""
    root = tmp_path / "repo"
    (root / "src").mkdir(parents=True)
    (root / "src" / "code.f90").write_text("program p\nend program p\n")
    (root / "docs" / "out").mkdir(parents=True)
    (root / "docs" / "out" / "report.md").write_text("old report\n")
    (root / "docs" / "out" / "old_figure.png").write_bytes(b"old")
    _git(root, "init", "-q")
    _git(root, "-c", "user.name=t", "-c", "user.email=t@t", "add", ".")
    _git(root, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "first")
    return root


def test_figures_made_for_a_tracked_folder_see_a_clean_tree(repo):
    out, staging = repo / "docs" / "out", repo / "build" / "out.new"
    seen = []

    def make(folder):
        (folder / "report.md").write_text("new report\n")
        seen.append(_tree(repo))  # what save_png would stamp on a figure drawn now
        (folder / "figure.png").write_bytes(b"new")
        return "made"

    assert _script().replace_when_made(out, staging, make) == "made"
    assert seen == ["clean"]
    assert sorted(p.name for p in out.iterdir()) == ["figure.png", "report.md"]
    assert (out / "report.md").read_text() == "new report\n"
    assert not staging.exists()
    assert _tree(repo) == "modified"  # the new output, to be committed


def test_deleting_the_tracked_folder_first_stamps_modified(repo):
    """The cause of 'modified tree' on the seed report's figures: the folder deleted first."""
    shutil.rmtree(repo / "docs" / "out")
    (repo / "docs" / "out").mkdir()
    assert _tree(repo) == "modified"


def test_a_change_of_the_code_is_still_stamped_modified(repo):
    (repo / "src" / "code.f90").write_text("program p\n  print *, 1\nend program p\n")
    seen = []
    _script().replace_when_made(repo / "docs" / "out", repo / "build" / "out.new",
                                lambda folder: seen.append(_tree(repo)))
    assert seen == ["modified"]


def test_a_failed_run_leaves_the_old_output(repo):
    def make(folder):
        (folder / "report.md").write_text("half a report\n")
        raise RuntimeError("the diagnosis failed")

    with pytest.raises(RuntimeError):
        _script().replace_when_made(repo / "docs" / "out", repo / "build" / "out.new", make)
    assert (repo / "docs" / "out" / "report.md").read_text() == "old report\n"
    assert _tree(repo) == "clean"
