"""Fixtures: the real Fortran executables and the result files they write.

Executables are looked up in ``$VOUSSOIR_BIN_DIR`` (default ``<repo>/build/drivers``).
A missing executable fails the tests that need it (the project rule: plots are tested
on files made by the real executables, never on hand-made fakes), and no test is ever
skipped: a skip is counted as a failure at the end of the session.
"""

from __future__ import annotations

import os

# One BLAS thread per pytest worker: two workers on two cores, and the diagnosis's small
# matrix products are slower with threads fighting over the cores than with one each.
for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import shutil
import subprocess
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

POSTPROC_DIR = Path(__file__).resolve().parents[1]
REPO_ROOT = POSTPROC_DIR.parent
SEED_CAMPAIGN = REPO_ROOT / "data" / "seed_2013"

#: The short run every run-file test reads: the seed's 156-degree wooden arch, one
#: attack, one full and one decay cycle at 2.5 Hz and 50 mm (about 12 m/s2, far above
#: its capacity, so it collapses), 0.5 s of rest.
RUN_NML = """\
&arch
  embrace_deg = 156.0, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071,
  width_m = 0.145, density_kg_m3 = 700.0, friction = 0.5, contact_inset_m = 0.0
/
&motion
  waveform = 'afd', frequency_hz = 2.5, amplitude_m = 0.05,
  n_attack = 1, n_full = 1, n_decay = 1, rest_s = 0.5
/
&solver
  dt_s = 2.0e-3, theta = 0.5, tol = 1.0e-4, max_iter = 1000
/
&output
  file = '{file}', every = 5
/
"""


def bin_dir() -> Path:
    """Folder of the Fortran executables: $VOUSSOIR_BIN_DIR or <repo>/build/drivers."""
    return Path(os.environ.get("VOUSSOIR_BIN_DIR", REPO_ROOT / "build" / "drivers"))


def executable(name: str) -> Path | None:
    path = bin_dir() / name
    return path if path.is_file() and os.access(path, os.X_OK) else None


def run_executable(args: list, cwd: Path, timeout_s: float = 600.0,
                   env: dict | None = None) -> subprocess.CompletedProcess:
    """Run a Fortran executable; fail the test with its output when it fails."""
    proc = subprocess.run([str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout_s, env=env)
    if proc.returncode != 0:
        pytest.fail(f"{' '.join(map(str, args))} exited with {proc.returncode}\n"
                    f"stdout:\n{proc.stdout}\nstderr:\n{proc.stderr}")
    return proc


def required_executable(name: str) -> Path:
    """An executable of the project; fails (never skips) when it has not been built."""
    exe = executable(name)
    if exe is None:
        pytest.fail(f"{name} not found in {bin_dir()}: build the project "
                    "(cmake -S . -B build && cmake --build build) or set VOUSSOIR_BIN_DIR "
                    "to the folder that holds the executables")
    return exe


@pytest.fixture(scope="session")
def voussoir_run_exe() -> Path:
    return required_executable("voussoir-run")


@pytest.fixture(scope="session")
def voussoir_sweep_exe() -> Path:
    return required_executable("voussoir-sweep")


@pytest.fixture(scope="session")
def voussoir_limit_exe() -> Path:
    return required_executable("voussoir-limit")


#: Lines the diagnosis tests report (the verdict each campaign got), printed at the end
#: of the session whatever the output capture.
VERDICTS: list[str] = []


#: The longest tests (about 40 to 130 s each, by `pytest --durations`), started first so
#: that the two workers of `pytest -n 2` do not end with one of them running a long test
#: alone while the other waits.
LONGEST_FIRST = ("test_end_to_end_diagnosis_follows_the_contract_and_keeps_the_truth",
                 "test_a_bank_biased_by_5_percent_fails_the_judgement",
                 "test_lmgc90_truths_are_named_with_power_and_never_wrongly",
                 "test_a_transducer_off_by_1_5_percent_names_no_cause_and_is_flagged",
                 "test_a_tenth_of_the_uncertainty_moves_no_probability_by_more_than_005")


def pytest_collection_modifyitems(session, config, items):
    rank = {name: k for k, name in enumerate(LONGEST_FIRST)}
    items.sort(key=lambda item: rank.get(item.originalname, len(rank)))  # stable: the rest keep their order


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    """Under pytest-xdist (scripts/test.sh runs 2 workers), each worker's verdict lines
    come back to the controller, which prints them."""
    VERDICTS.extend(getattr(node, "workeroutput", {}).get("verdicts", []))


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    if VERDICTS:
        terminalreporter.section("diagnosis verdicts on the independent campaigns")
        for line in VERDICTS:
            terminalreporter.write_line(line)


def pytest_sessionfinish(session, exitstatus):
    """No test may be skipped: a skipped test fails the session (under pytest-xdist the
    controller sees every worker's reports)."""
    if hasattr(session.config, "workeroutput"):  # an xdist worker: hand its verdicts over
        session.config.workeroutput["verdicts"] = list(VERDICTS)
        return
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    skipped = len(reporter.stats.get("skipped", [])) if reporter else 0
    if skipped and exitstatus == 0:
        print(f"\n{skipped} test(s) skipped: every test must run (a missing dependency is a failure)")
        session.exitstatus = 1


@pytest.fixture(scope="session")
def run_file(voussoir_run_exe, tmp_path_factory) -> Path:
    """A short real run (see RUN_NML), written once per test session."""
    folder = tmp_path_factory.mktemp("run")
    h5 = folder / "arch156.h5"
    nml = folder / "arch156.nml"
    nml.write_text(RUN_NML.format(file=h5))
    run_executable([voussoir_run_exe, nml], folder)
    if not h5.is_file():
        pytest.fail(f"voussoir-run did not write {h5}")
    return h5


@pytest.fixture
def run_copy(run_file, tmp_path) -> Path:
    """A private copy of the session run file (for tests that write beside it or edit it)."""
    dest = tmp_path / run_file.name
    shutil.copy(run_file, dest)
    return dest


@pytest.fixture(scope="session")
def seed_campaign() -> Path:
    """<repo>/data/seed_2013 (the seed paper's campaign, in the repository)."""
    if not (SEED_CAMPAIGN / "tests.csv").is_file():
        pytest.fail(f"seed campaign not found at {SEED_CAMPAIGN}")
    return SEED_CAMPAIGN


@pytest.fixture
def drawn_figures(monkeypatch) -> list:
    """Every figure the plot modules make during a test (their ``new_figure`` recorded),
    to look at after the PNG is written (e.g. its text boxes)."""
    import importlib

    from voussoir_post.plots import drawing

    figures = []

    def recording(*args, **kwargs):
        fig = drawing.new_figure(*args, **kwargs)
        figures.append(fig)
        return fig

    plots = ("sequence", "envelope", "compare", "history", "mechanism", "mechanism_lp", "fragility_plot",
             "fragility_compare", "fragility_lambda_g", "record_table", "reactions", "thrust_line", "msa_plot",
             "load_position")
    for name in [f"plots.{p}" for p in plots] + ["diagnosis.figures"]:
        module = importlib.import_module(f"voussoir_post.{name}")
        if hasattr(module, "new_figure"):
            monkeypatch.setattr(module, "new_figure", recording)
    return figures
