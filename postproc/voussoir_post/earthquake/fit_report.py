"""What `voussoir-post fragility` adds to an IDA's fit beyond its figure (issue 36): how much
the failed searches matter, and each bootstrap resample's fit (for ``voussoir-post risk``).

The failed searches are read two ways (:meth:`voussoir_post.earthquake.ida.IdaResult.intensity_brackets`):
the fit's reading (a search that had collapsed before it failed bracketed by that collapse,
(last stand, collapse seen]; one that had not, censored at its last stand), and a second one
in which every failed search whose failed run is known collapses at or below that run. The
second fit is the same interval-censored maximum likelihood on the second reading's PGA
brackets; the distance between the two fits is how much the failures matter.
"""

from __future__ import annotations

import numpy as np

from ..units import G_M_S2
from .fragility import FragilityBand, FragilityFit, fit_intervals
from .ida import FIT_FAILED_COLLAPSED, IdaResult

__all__ = ["FailureReading", "failure_reading", "bootstrap_keys"]


class FailureReading:
    """The failed searches of an IDA, and the PGA fit that counts them as collapses."""

    def __init__(self, ida: IdaResult, fit: FragilityFit):
        self.fit = fit  #: the fit's own reading (PGA, m/s2)
        self.n_failed = ida.n_failed
        self.n_after_collapse = sum(1 for k in ida.fit_as if k == FIT_FAILED_COLLAPSED)
        self.n_counted = ida.n_failures_as_collapses() if self.n_failed else 0
        self.second: FragilityFit | None = None
        if self.n_counted:
            low, high = ida.intensity_brackets("pga", failures_as_collapses=True)
            used = np.isfinite(low)
            self.second = fit_intervals(low[used], high[used])

    def keys(self) -> dict:
        """For --json: n_failed, n_failed_after_collapse, failures_as_collapses (None without a second fit)."""
        f = self.second
        return {"n_failed": self.n_failed, "n_failed_after_collapse": self.n_after_collapse,
                "failures_as_collapses": None if f is None else {
                    "median_pga_g": f.median / G_M_S2, "beta_pga": f.beta, "n_counted": self.n_counted,
                    "median_ratio": f.median / self.fit.median, "beta_difference": f.beta - self.fit.beta,
                    "how": "each failed search whose failed run's scale is known: its collapse in (last stand, the "
                           "lower of the failed run and its collapse seen]"}}

    def words(self) -> str:
        """How much the failed searches matter, in one line."""
        if self.n_failed == 0:
            return "failed searches: none (the fit does not depend on how failures are read)"
        f = self.second
        if f is None:
            return (f"failed searches: {self.n_failed}; none has its failed run's scale in the file (a CSV): the "
                    f"reading that counts failures as collapses could not be made (read the HDF5 file)")
        return (f"failed searches: {self.n_failed} ({self.n_after_collapse} had collapsed before failing: in (last "
                f"stand, collapse seen]); counting {self.n_counted} of them as collapses at their failed run: PGA "
                f"median {f.median / G_M_S2:.4g} g ({100 * (f.median / self.fit.median - 1):+.2g} %), beta "
                f"{f.beta:.3f} "
                f"({f.beta - self.fit.beta:+.3f}): how much the failures matter")


def failure_reading(ida: IdaResult, fit: FragilityFit) -> FailureReading:
    return FailureReading(ida, fit)


def bootstrap_keys(band: FragilityBand) -> dict:
    """Each bootstrap resample's PGA fit, for --json (what `voussoir-post risk` carries into its band)."""
    return {"bootstrap_median_pga_g": None if band.medians is None else (band.medians / G_M_S2).tolist(),
            "bootstrap_beta_pga": None if band.betas is None else band.betas.tolist()}
