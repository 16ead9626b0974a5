"""What `voussoir-post fragility` adds to an IDA's fit beyond its figure (issue 36): each
bootstrap resample's fit (for ``voussoir-post risk``)."""

from __future__ import annotations

from ..units import G_M_S2
from .fragility import FragilityBand

__all__ = ["bootstrap_keys"]


def bootstrap_keys(band: FragilityBand) -> dict:
    """Each bootstrap resample's PGA fit, for --json (what `voussoir-post risk` carries into its band)."""
    return {"bootstrap_median_pga_g": None if band.medians is None else (band.medians / G_M_S2).tolist(),
            "bootstrap_beta_pga": None if band.betas is None else band.betas.tolist()}
