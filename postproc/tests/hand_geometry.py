"""A segmental ring's geometry by hand, for the tests that check a bridge's weights and
regions against the builder (written here from the circle, never from the code)."""

from __future__ import annotations

import numpy as np


def segmental_ring(span: float, rise: float, t: float, n: int):
    """A segmental ring of n voussoirs (intrados span and rise, depth t): the ring's area,
    n quadrilaterals of (R_e^2 - R_i^2) sin(dphi)/2 with R = (L^2/4 + r^2)/(2r), and the
    extrados ends of its joints (x, y) from the left springing, on the circle of radius
    R + t about the intrados' centre (L/2, r - R)."""
    radius = (span ** 2 / 4 + rise ** 2) / (2 * rise)
    half = np.arcsin(span / 2 / radius)
    phi = np.linspace(-half, half, n + 1)
    ring_area = n * 0.5 * ((radius + t) ** 2 - radius ** 2) * np.sin(2 * half / n)
    ex = span / 2 + (radius + t) * np.sin(phi)
    ey = rise - radius + (radius + t) * np.cos(phi)
    return ring_area, ex, ey


def backed_area(bottom, level: float) -> float:
    """The trapezoids between `level` and every piece of the x-ascending polyline `bottom`
    wholly at or below it (a backing's region: docs/bridges.md, "Backing")."""
    return sum((x1 - x0) * (level - (y0 + y1) / 2) for (x0, y0), (x1, y1) in zip(bottom, bottom[1:])
               if max(y0, y1) <= level)
