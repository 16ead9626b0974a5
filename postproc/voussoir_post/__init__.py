"""Postprocessor of the Voussoir NSCD solver.

Readers (:mod:`.results` for the HDF5/JSON files of the Fortran drivers,
:mod:`.campaign` for shaking-table campaign folders, :mod:`.ida` for incremental
dynamic analyses, :mod:`.records` for the suite of real ground-motion records), the
lognormal fragility fit (:mod:`.fragility`), plain plotting functions over
numpy arrays that return the numbers they draw (:mod:`.envelope`, :mod:`.sequence`,
:mod:`.history`, :mod:`.compare`, :mod:`.mechanism`, :mod:`.fragility_plot`), the ParaView export
(:mod:`.xdmf`) and two command-line programs (:mod:`.cli`, :mod:`.diagnose_cli`).
"""

__version__ = "0.1.0"
