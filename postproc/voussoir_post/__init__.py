"""Postprocessor of the Voussoir NSCD solver.

Readers (:mod:`.results` for the HDF5/JSON files of the Fortran drivers,
:mod:`.campaign` for shaking-table campaign folders), plain plotting functions over
numpy arrays that return the numbers they draw (:mod:`.envelope`, :mod:`.sequence`,
:mod:`.history`, :mod:`.compare`, :mod:`.mechanism`), the ParaView export
(:mod:`.xdmf`) and two command-line programs (:mod:`.cli`, :mod:`.diagnose_cli`).
"""

__version__ = "0.1.0"
