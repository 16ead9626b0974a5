"""`&motion waveform = 'accelerogram'` on the real executable: the table plays the scaled
record, linearly interpolated, with its exact integrals; the result file carries the
record's intensity measures; bad records are refused with the file and the line and
nothing is written.

Every expected value is computed here from the record file by other means than the
program's: an AT2 parser of this test, and dense numerical quadrature of the
interpolated acceleration (instead of the closed-form integrals the program uses).
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import numpy as np
import pytest

from conftest import run_executable
from voussoir_post.earthquake.records import record_path
from voussoir_post.readers.results import read_run

G = 9.81  # the kernel's gravity, also its g for records in units of g
BLOCK = """\
# A 0.2 m x 1.0 m block on a table slab (coordinates in m).
block free
-0.1 0.0
 0.1 0.0
 0.1 1.0
-0.1 1.0
block driven
-1.0 -0.2
 1.0 -0.2
 1.0  0.0
-1.0  0.0
"""


def block_nml(folder: Path, record: Path, out: str, scale=1.0, lead_s=0.0, rest_s=0.0, duration_s=0.0,
              dt_s=1.0e-3, every=1) -> Path:
    (folder / "block.txt").write_text(BLOCK)
    nml = folder / (Path(out).stem + ".nml")
    duration = f", duration_s = {duration_s!r}" if duration_s else ""
    nml.write_text(f"""&arch
  polygon_file = 'block.txt', thickness_m = 0.2, width_m = 0.2, density_kg_m3 = 2000, friction = 0.7
/
&motion
  waveform = 'accelerogram', record_file = '{record}', record_scale = {scale!r}, lead_s = {lead_s!r},
  rest_s = {rest_s!r}{duration}
/
&solver
  dt_s = {dt_s!r}
/
&output
  file = '{out}', every = {every}, stop_after_collapse_s = -1.0
/
""")
    return nml


def read_at2_here(path: Path) -> tuple[np.ndarray, float]:
    """Samples [g] and DT of a NGA-West2 .AT2 file, parsed here (not by the program)."""
    lines = path.read_text().splitlines()
    m = re.search(r"NPTS=\s*(\d+),\s*DT=\s*([.\d]+)", lines[3])
    values = np.array([float(v) for line in lines[4:] for v in line.split()])
    assert values.size == int(m.group(1))
    return values, float(m.group(2))


def dense(accel: np.ndarray, dt: float, sub: int = 64):
    """The interpolated acceleration on a grid `sub` times finer, and its velocity and
    displacement by cumulative trapezoids (second-order quadrature, not the closed form)."""
    t = np.arange((accel.size - 1) * sub + 1) * (dt / sub)
    a = np.interp(t, np.arange(accel.size) * dt, accel)
    h = dt / sub
    v = np.concatenate([[0.0], np.cumsum(0.5 * h * (a[1:] + a[:-1]))])
    x = np.concatenate([[0.0], np.cumsum(0.5 * h * (v[1:] + v[:-1]))])
    return t, a, v, x


@pytest.fixture(scope="module")
def elcentro():
    path = record_path("ELC180")
    accel_g, dt = read_at2_here(path)
    return path, accel_g, dt


def test_table_is_the_scaled_record_and_its_exact_integrals(voussoir_run_exe, tmp_path, elcentro):
    path, accel_g, dt = elcentro
    scale, lead_s = 1.7, 0.2537  # the lead ends off the output grid
    nml = block_nml(tmp_path, path, "table.h5", scale=scale, lead_s=lead_s, duration_s=6.0, every=7)
    run_executable([voussoir_run_exe, nml], tmp_path)
    run = read_run(tmp_path / "table.h5")
    accel = scale * G * accel_g
    t = run.time_s
    before = t < lead_s
    # At rest before the first sample, then the scaled record, linear between samples.
    assert np.all(run.table_a_m_s2[before] == 0.0) and np.all(run.table_v_m_s[before] == 0.0)
    expected_a = np.interp(t - lead_s, np.arange(accel.size) * dt, accel)
    np.testing.assert_allclose(run.table_a_m_s2[~before], expected_a[~before], rtol=0, atol=1e-9 * accel.max())
    # Velocity and displacement: the integrals of that acceleration (dense quadrature here).
    td, _, vd, xd = dense(accel, dt)
    np.testing.assert_allclose(run.table_v_m_s[~before], np.interp(t[~before] - lead_s, td, vd),
                               rtol=0, atol=1e-6 * np.abs(vd).max())
    np.testing.assert_allclose(run.table_x_m[~before], np.interp(t[~before] - lead_s, td, xd),
                               rtol=0, atol=1e-6 * np.abs(xd[td <= 6.0]).max())


def test_intensity_measures_of_the_record(voussoir_run_exe, tmp_path, elcentro):
    path, accel_g, dt = elcentro
    scale = 0.5
    nml = block_nml(tmp_path, path, "im.h5", scale=scale, lead_s=0.5, duration_s=0.6, every=100)
    run_executable([voussoir_run_exe, nml], tmp_path)
    rec = read_run(tmp_path / "im.h5").record
    assert rec is not None
    accel = scale * G * accel_g
    td, ad, vd, _ = dense(accel, dt)
    h = td[1] - td[0]
    cum = np.concatenate([[0.0], np.cumsum(0.5 * h * (ad[1:] ** 2 + ad[:-1] ** 2))])
    arias = np.pi / (2 * G) * cum[-1]
    t5, t95 = np.interp([0.05 * cum[-1], 0.95 * cum[-1]], cum, td)
    assert rec.name == "RSN6_IMPVALL.I_I-ELC180-hor1"
    assert "El Centro" in rec.description and rec.scale == scale
    assert rec.n_samples == accel.size and rec.dt_s == pytest.approx(dt, rel=1e-12)
    assert rec.start_s == 0.5
    assert rec.pga_m_s2 == pytest.approx(np.abs(accel).max(), rel=1e-12)
    assert rec.pga_g == pytest.approx(scale * np.abs(accel_g).max(), rel=1e-12)
    assert rec.pgv_m_s == pytest.approx(np.abs(vd).max(), rel=1e-5)
    assert rec.arias_m_s == pytest.approx(arias, rel=1e-4)
    assert rec.t5_s == pytest.approx(t5, abs=2e-3) and rec.t95_s == pytest.approx(t95, abs=2e-3)
    assert rec.significant_duration_s == pytest.approx(t95 - t5, abs=4e-3)
    # The published El Centro 1940 (180) values, as a sanity check of the units:
    # PGA 0.28 g, PGV 31 cm/s, D5-95 about 24 s.
    assert rec.pga_g / scale == pytest.approx(0.28, abs=0.01)
    assert rec.pgv_m_s / scale == pytest.approx(0.31, abs=0.01)
    assert 23.0 < rec.significant_duration_s < 25.5


def write_records(folder: Path, accel_g: np.ndarray, dt: float) -> dict[str, Path]:
    """The same samples as a NGA-West2 AT2, an older-PEER AT2 and a CSV in m/s2."""
    body = "\n".join("".join(f"{v:15.7E}" for v in accel_g[k:k + 5]) for k in range(0, accel_g.size, 5))
    new = folder / "new.AT2"
    new.write_text("PEER NGA STRONG MOTION DATABASE RECORD\nTest event, 1/1/2000, station, 0\n"
                   f"ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   {accel_g.size}, DT=   {dt:.4f} SEC,\n"
                   f"{body}\n")
    old = folder / "old.at2"
    old.write_text("PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.\n"
                   "TEST EVENT 1/1/00, STATION, 000\nACCELERATION TIME HISTORY IN UNITS OF G\n"
                   f"   {accel_g.size}   {dt:.5f}    NPTS, DT\n{body}\n")
    csv = folder / "same.csv"  # columns in another order, one of them ignored, a comment
    rows = [f"{G * float(f'{v:.7E}')!r},x,{k * dt!r}" for k, v in enumerate(accel_g)]
    csv.write_text("# the same record in m/s2\naccel_m_s2,comment,t_s\n" + "\n".join(rows) + "\n")
    return {"new": new, "old": old, "csv": csv}


def test_both_at2_header_variants_and_csv_drive_the_same_table(voussoir_run_exe, tmp_path, elcentro):
    _, accel_g, dt = elcentro
    accel_g = 2.0 * accel_g[150:450]  # 3 s of strong motion
    files = write_records(tmp_path, accel_g, dt)
    tables = {}
    for key, path in files.items():
        nml = block_nml(tmp_path, path, f"{key}.h5", lead_s=0.1, every=5)
        run_executable([voussoir_run_exe, nml], tmp_path)
        run = read_run(tmp_path / f"{key}.h5")
        tables[key] = run.table_a_m_s2
        assert run.record.n_samples == accel_g.size and run.record.dt_s == pytest.approx(dt, rel=1e-9)
    np.testing.assert_array_equal(tables["new"], tables["old"])
    np.testing.assert_allclose(tables["csv"], tables["new"], rtol=0, atol=1e-9)
    assert read_run(tmp_path / "new.h5").record.description == "Test event, 1/1/2000, station, 0"


HEADER = ("PEER NGA STRONG MOTION DATABASE RECORD\nbad record\nACCELERATION TIME SERIES IN UNITS OF G\n")
DATA = "  .1000000E-01  .2000000E-01  .3000000E-01\n  .2000000E-01  .1000000E-01\n"
BAD_RECORDS = [
    # name, file name, text, expected line, expected words
    ("no_npts", "r.AT2", HEADER + "DT=   .0100 SEC\n" + DATA, 4, "no NPTS"),
    ("no_dt", "r.AT2", HEADER + "NPTS=   5,\n" + DATA, 4, "no 'DT='"),
    ("old_no_dt", "r.AT2", HEADER + "   5    NPTS\n" + DATA, 4, "no DT"),
    ("bad_npts", "r.AT2", HEADER + "NPTS=   five, DT=   .0100 SEC\n" + DATA, 4, "NPTS = 'FIVE' is not an integer"),
    ("zero_dt", "r.AT2", HEADER + "NPTS=   5, DT=   .0000 SEC\n" + DATA, 4, "DT = '.0000' is not a time step > 0"),
    ("short_header", "r.AT2", "PEER NGA STRONG MOTION DATABASE RECORD\nbad\n", 3, "ends inside the four header"),
    ("units", "r.AT2", HEADER.replace("OF G", "OF CM/S/S") + "NPTS= 5, DT= .01 SEC\n" + DATA, 3, "units of g"),
    ("npts_too_many", "r.AT2", HEADER + "NPTS=   6, DT=   .0100 SEC\n" + DATA, 6, "ends after 5 samples, but NPTS = 6"),
    ("npts_too_few", "r.AT2", HEADER + "NPTS=   4, DT=   .0100 SEC\n" + DATA, 6, "more samples than NPTS = 4"),
    ("text", "r.AT2", HEADER + "NPTS=   5, DT=   .0100 SEC\n  .1E-01  abc  .3E-01\n .2E-01 .1E-01\n", 5,
     "'abc' is not a number"),
    ("nan", "r.AT2", HEADER + "NPTS=   5, DT=   .0100 SEC\n  .1E-01  .2E-01  .3E-01\n NaN .1E-01\n", 6,
     "'NaN' is not a finite number"),
    ("slash", "r.AT2", HEADER + "NPTS=   5, DT=   .0100 SEC\n  .1E-01  1/2  .3E-01\n .2E-01 .1E-01\n", 5,
     "'1/2' is not a number"),
    ("csv_no_column", "r.csv", "t_s,accel_g\n0.0,0.1\n0.01,0.2\n", 1, "no column accel_m_s2"),
    ("csv_text", "r.csv", "t_s,accel_m_s2\n0.0,0.1\n0.01,big\n", 3, "accel_m_s2 = 'big' is not a number"),
    ("csv_nan", "r.csv", "t_s,accel_m_s2\n0.0,0.1\n0.01,nan\n", 3, "accel_m_s2 = 'nan' is not a finite number"),
    ("csv_short_row", "r.csv", "t_s,accel_m_s2\n0.0,0.1\n0.01\n", 3, "the row has 1 cells"),
    ("csv_not_increasing", "r.csv", "t_s,accel_m_s2\n0.0,0.1\n0.01,0.2\n# note\n0.01,0.3\n", 5,
     "t_s = 0.01 does not increase"),
    ("csv_non_uniform", "r.csv", "t_s,accel_m_s2\n0.0,0.1\n0.01,0.2\n0.025,0.3\n", 4,
     "differs from the first one"),
    ("csv_one_sample", "r.csv", "t_s,accel_m_s2\n0.0,0.1\n", None, "at least 2 samples"),
]


@pytest.mark.parametrize("name, file_name, text, line, words", BAD_RECORDS, ids=[b[0] for b in BAD_RECORDS])
def test_bad_records_are_refused_with_file_and_line(voussoir_run_exe, tmp_path, name, file_name, text, line, words):
    record = tmp_path / file_name
    record.write_text(text)
    nml = block_nml(tmp_path, record, "out.h5", duration_s=0.1)
    proc = subprocess.run([str(voussoir_run_exe), str(nml)], cwd=tmp_path, capture_output=True,
                                        text=True)
    message = proc.stderr
    assert proc.returncode == 1, (proc.stdout, message)
    where = f"{record}:{line}:" if line is not None else f"{record}:"
    assert where in message and words in message, message
    assert str(nml) in message and "record_file" in message, message
    assert not (tmp_path / "out.h5").exists() and not (tmp_path / "out.h5.part").exists()


def test_unknown_record_format_is_refused(voussoir_run_exe, tmp_path):
    record = tmp_path / "r.txt"
    record.write_text("0.1 0.2\n")
    nml = block_nml(tmp_path, record, "out.h5", duration_s=0.1)
    proc = subprocess.run([str(voussoir_run_exe), str(nml)], cwd=tmp_path, capture_output=True,
                                        text=True)
    assert proc.returncode == 1 and "unknown record format '.txt'" in proc.stderr, proc.stderr
    assert not (tmp_path / "out.h5").exists()


def test_suite_lists_the_eight_horizontal_records():
    from voussoir_post.earthquake.records import suite

    records = suite()
    assert [r.key for r in records] == ["ELC180", "ELC270", "CLS000", "CLS090", "SYL090", "SYL360",
                                        "PUL164", "PUL254"]
    for rec in records:
        lines = rec.path.read_text().splitlines()
        assert rec.path.suffix == ".AT2" and "UNITS OF G" in lines[2]
        assert not re.search(r"(UP|DWN|up)\.AT2$", rec.path.name)  # horizontal components only
        npts = int(re.search(r"NPTS=\s*(\d+)", lines[3]).group(1))
        assert sum(len(line.split()) for line in lines[4:]) == npts


def test_records_command_prints_the_suite_as_a_namelist_line(capsys):
    from voussoir_post.cli.post import main

    assert main(["records", "--namelist"]) == 0
    line = capsys.readouterr().out.strip()
    paths = re.findall(r"'([^']+)'", line)
    assert line.startswith("record_files = ") and len(paths) == 8
    assert all(Path(p).is_file() and p.endswith(".AT2") for p in paths)
    assert main(["records", "NOPE"]) == 2
    assert "no record NOPE in the suite" in capsys.readouterr().err
