"""The postprocessor's gravity is the Fortran kernel's: read from src/core/kinds.f90,
not from the package, so a change on either side fails here."""

from __future__ import annotations

import re
from pathlib import Path

from voussoir_post.units import G_M_S2

KINDS = Path(__file__).resolve().parents[2] / "src" / "core" / "kinds.f90"


def test_gravity_is_the_kernels():
    match = re.search(r"g_m_s2\s*=\s*([0-9.eEdD+-]+)_dp", KINDS.read_text())
    assert match, f"{KINDS}: no 'g_m_s2 = ..._dp' parameter"
    assert G_M_S2 == float(match.group(1).lower().replace("d", "e"))
