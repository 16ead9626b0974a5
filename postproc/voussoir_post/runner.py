"""The one way Python runs the Fortran executables: a namelist from a mapping
(:mod:`voussoir_post.namelist`), the executable on it, the result read back through
:mod:`voussoir_post.readers.results`.

    groups = {"arch": {"embrace_deg": 156.0, "n_voussoirs": 13},
              "motion": {"waveform": "afd", "frequency_hz": 1.25, "amplitude_m": 0.046}}
    run = Runner(bin_dir, work_dir).run_single(groups, "A156_f1.25")   # -> RunResult

Every run writes ``<name>.nml`` in the work folder and its result beside it, so a failed
run can be repeated by hand from what is left there. A failure raises :class:`RunError`
with the command, the namelist and the program's own words. Sweeps run under MPI when
``n_ranks > 1`` (with the variables Open MPI needs as root).
"""

from __future__ import annotations

import hashlib
import os
import re
import shutil
import subprocess
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from .errors import BinDirError, RunError
from .namelist import format_namelist
from .readers.csv_table import read_csv_table

if TYPE_CHECKING:  # h5py, through the readers: imported when a run is read, not by voussoir-diagnose's parser
    from .readers.results import LimitResult, RunResult, SweepResult

__all__ = ["RunError", "Runner", "read_csv_rows", "find_bin_dir", "BIN_DIR_ENV", "installed_bin_dir_file", "code_hash"]

BIN_DIR_ENV = "VOUSSOIR_BIN_DIR"  #: the environment variable naming the folder of the executables


def installed_bin_dir_file() -> Path:
    """The file the project's set-up (scripts/setup.sh) writes with the build's drivers
    folder: ``<sys.prefix>/etc/voussoir/bin_dir``."""
    return Path(sys.prefix) / "etc" / "voussoir" / "bin_dir"


def find_bin_dir(given: str | os.PathLike | None = None,
                 programs: Sequence[str] = ("voussoir-run", "voussoir-sweep")) -> Path:
    """The folder of the Fortran executables: ``given`` (a --bin-dir option) when set,
    else ``$VOUSSOIR_BIN_DIR``, else the folder written at install time in
    :func:`installed_bin_dir_file`, else the folder of ``programs[0]`` on PATH. The first
    of these that is set must hold every one of ``programs``; BinDirError otherwise, or
    naming all three places when none is set."""
    found = None
    if given:
        found = Path(given), "--bin-dir"
    elif os.environ.get(BIN_DIR_ENV):
        found = Path(os.environ[BIN_DIR_ENV]), f"${BIN_DIR_ENV}"
    elif installed_bin_dir_file().is_file() and installed_bin_dir_file().read_text().strip():
        found = Path(installed_bin_dir_file().read_text().strip()), str(installed_bin_dir_file())
    elif shutil.which(programs[0]):
        found = Path(shutil.which(programs[0])).parent, "PATH"
    if found is None:
        raise BinDirError(f"the Fortran executables ({', '.join(programs)}) were not found: set ${BIN_DIR_ENV} to "
                          f"their folder, or run bash scripts/setup.sh (it builds them and writes their folder "
                          f"into {installed_bin_dir_file()}), or put them on PATH")
    folder, source = found
    folder = folder.resolve()
    for program in programs:
        if not (folder / program).is_file():
            raise BinDirError(f"{folder / program} not found (the folder comes from {source}): build the project "
                              f"(bash scripts/setup.sh) or name the folder of the executables")
    return folder


def code_hash(bin_dir: str | os.PathLike, names: Sequence[str]) -> str:
    """A hash of the executables `names` in `bin_dir` that ignores the version string they
    embed (`<program> --version` prints it in brackets: project version + git commit) and
    the linker's build id (a hash of the whole file, so of that string too). A commit that
    changes only Python or docs then keeps the caches keyed by this hash (the diagnosis's
    bank and single runs); any change of the compiled code still changes it."""
    h = hashlib.sha256()
    for name in names:
        exe = Path(bin_dir) / name
        data = exe.read_bytes()
        out = subprocess.run([str(exe), "--version"], capture_output=True, text=True).stdout
        version = re.search(r"\((voussoir [^()]+)\)\s*$", out)
        if version:
            data = data.replace(version.group(1).encode(), b"voussoir <version>")
        h.update(_without_build_id(data))
    return h.hexdigest()[:16]


#: An ELF note of the GNU build id (little-endian): name size 4, id size 20 (SHA-1), type 3.
_BUILD_ID_NOTE = b"\x04\x00\x00\x00\x14\x00\x00\x00\x03\x00\x00\x00GNU\x00"


def _without_build_id(data: bytes) -> bytes:
    """The bytes with the 20 bytes of every GNU build-id note zeroed."""
    out = bytearray(data)
    k = out.find(_BUILD_ID_NOTE)
    while k >= 0:
        start = k + len(_BUILD_ID_NOTE)
        out[start:start + 20] = bytes(20)
        k = out.find(_BUILD_ID_NOTE, start + 20)
    return bytes(out)


def read_csv_rows(path: str | os.PathLike) -> list[dict[str, str]]:
    """Rows of a CSV written by the executables (``#`` comment lines skipped)."""
    return [row.cells for row in read_csv_table(path).rows]


@dataclass
class Runner:
    """Runs voussoir-run, voussoir-sweep and voussoir-limit in one work folder."""

    bin_dir: Path
    work_dir: Path
    n_ranks: int = 1  #: MPI ranks of a sweep (1: no mpirun)
    mpiexec: str = "mpirun"
    timeout_s: float | None = None

    def __post_init__(self):
        self.bin_dir = Path(self.bin_dir).resolve()  # the programs run in the work folder
        self.work_dir = Path(self.work_dir).resolve()
        self.work_dir.mkdir(parents=True, exist_ok=True)
        self.n_runs = 0  #: executables started
        self.reused = 0  #: results found already made from the same input

    def exe(self, name: str) -> Path:
        path = self.bin_dir / name
        if not path.is_file():
            raise BinDirError(f"{path} does not exist: build the project (bash scripts/setup.sh)")
        return path

    def _env(self) -> dict:
        env = dict(os.environ)
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        return env

    def write(self, groups: Mapping[str, Mapping[str, object]], name: str) -> Path:
        """Write ``<name>.nml``; returns its path."""
        path = self.work_dir / f"{name}.nml"
        path.write_text(format_namelist(groups))
        return path

    def execute(self, program: str, nml: Path, *args: str, mpi: bool = False) -> subprocess.CompletedProcess:
        """Run one program on one namelist in the work folder; RunError when it fails."""
        cmd = [str(self.exe(program)), nml.name, *args]
        if mpi and self.n_ranks > 1:
            cmd = [self.mpiexec, "--oversubscribe", "-np", str(self.n_ranks), *cmd]
        try:
            proc = subprocess.run(cmd, cwd=self.work_dir, capture_output=True, text=True, env=self._env(),
                                  timeout=self.timeout_s)
        except subprocess.TimeoutExpired as exc:
            raise RunError(f"{' '.join(cmd)} (in {self.work_dir}) did not finish in {self.timeout_s} s") from exc
        self.n_runs += 1
        if proc.returncode != 0:
            raise RunError(f"{' '.join(cmd)} (in {self.work_dir}) exited with {proc.returncode}\n"
                           f"input {nml}:\n{nml.read_text()}\nstdout:\n{proc.stdout}\nstderr:\n{proc.stderr}")
        return proc

    def _fresh(self, groups, name: str, outputs: Sequence[str]) -> tuple[Path, bool]:
        """Write the namelist unless the same one and all its outputs are already there."""
        path = self.work_dir / f"{name}.nml"
        text = format_namelist(groups)
        done = path.is_file() and path.read_text() == text and all((self.work_dir / o).is_file() for o in outputs)
        if not done:
            path.write_text(text)
        return path, done

    @staticmethod
    def _with_output(groups, file: str) -> dict:
        out = {g: dict(v) for g, v in groups.items()}
        out.setdefault("output", {})["file"] = file
        return out

    def run_single(self, groups: Mapping[str, Mapping[str, object]], name: str, keep: bool = True) -> RunResult:
        """voussoir-run on the groups (``&output file`` is set to ``<name>.h5``)."""
        groups = self._with_output(groups, f"{name}.h5")
        nml = self.write(groups, name)
        self.execute("voussoir-run", nml)
        from .readers.results import read_run

        h5 = self.work_dir / f"{name}.h5"
        result = read_run(h5)
        if not keep:
            h5.unlink()
        return result

    def collapses(self, groups: Mapping[str, Mapping[str, object]], name: str) -> bool:
        """voussoir-run on the groups, for its outcome only: whether the arch fell (its
        summary line says "collapsed at"); the result file is removed."""
        groups = self._with_output(groups, f"{name}.h5")
        out = self.execute("voussoir-run", self.write(groups, name)).stdout
        (self.work_dir / f"{name}.h5").unlink(missing_ok=True)
        return "collapsed at" in out

    def run_sweep(self, groups: Mapping[str, Mapping[str, object]], name: str, reuse: bool = True
                  ) -> tuple[SweepResult, list[dict[str, str]]]:
        """voussoir-sweep of threshold or grid mode (`run_sweep_file`): the HDF5 result and
        the CSV rows."""
        from .readers.results import read_sweep

        h5 = self.run_sweep_file(groups, name, reuse)
        return read_sweep(h5), read_csv_rows(h5.with_suffix(".csv"))

    def run_sweep_file(self, groups: Mapping[str, Mapping[str, object]], name: str, reuse: bool = True) -> Path:
        """voussoir-sweep of any mode (under MPI when n_ranks > 1): the path of its HDF5
        file ``<name>.h5`` (its CSV beside it). A finished sweep of the same input in the
        work folder is reused when ``reuse``."""
        groups = self._with_output(groups, f"{name}.h5")
        nml, done = self._fresh(groups, name, [f"{name}.h5", f"{name}.csv"])
        if done and reuse:
            self.reused += 1
        else:
            self.execute("voussoir-sweep", nml, mpi=True)
        return self.work_dir / f"{name}.h5"

    def run_limit(self, groups: Mapping[str, Mapping[str, object]], name: str) -> LimitResult:
        """voussoir-limit --json on the groups."""
        from .readers.limit_results import read_limit_json

        nml = self.write(groups, name)
        proc = self.execute("voussoir-limit", nml, "--json")
        path = self.work_dir / f"{name}.json"
        path.write_text(proc.stdout)
        return read_limit_json(path)
