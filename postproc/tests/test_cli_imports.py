"""What the programs import: each ``voussoir-post`` subcommand starts a fresh process, so
building the parsers must not pay for matplotlib, scipy or h5py, and a figure of a run
must not pay for scipy (cli/post.py imports a command's modules when it runs)."""

from __future__ import annotations

import json
import subprocess
import sys

HEAVY = ("matplotlib", "scipy", "h5py")


def loaded_after(code: str) -> set[str]:
    """The top-level packages of HEAVY that a fresh interpreter has imported after ``code``."""
    script = code + "\nimport json, sys\nprint(json.dumps(sorted({m.split('.')[0] for m in sys.modules})))\n"
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    return set(json.loads(proc.stdout.splitlines()[-1])) & set(HEAVY)


def test_building_the_parsers_imports_no_plotting_fitting_or_hdf5():
    loaded = loaded_after("from voussoir_post.cli import diagnose, dtcheck, post\n"
                          "post.build_parser().parse_args(['history', 'run.h5'])\n"
                          "diagnose.build_parser().parse_args(['check', 'campaign'])")
    assert loaded == set()


def test_figures_of_a_run_import_no_scipy(run_copy, tmp_path):
    commands = [["history", str(run_copy)], ["reactions", str(run_copy)], ["xdmf", str(run_copy)],
                ["vtk", str(run_copy)]]
    loaded = loaded_after("from voussoir_post.cli import post\n"
                          f"for command in {commands!r}:\n"
                          f"    assert post.main(command + ['--out', {str(tmp_path) + '/'!r}]) == 0")
    assert loaded == {"matplotlib", "h5py"}
