"""What every result reader shares: the error type (defined in :mod:`voussoir_post.errors`)
and the hinge side names."""

from __future__ import annotations

from ..errors import ResultsError

__all__ = ["SIDE_NAMES", "ResultsError"]

#: Hinge side codes of /hinges/side: 0 intrados, 1 extrados.
SIDE_NAMES = ("intrados", "extrados")

