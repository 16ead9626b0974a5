"""Postprocessor of the Voussoir NSCD solver, a subpackage per concept:

- :mod:`.readers`: the HDF5/JSON files of the Fortran drivers, campaign folders, the one
  CSV reader;
- :mod:`.analysis`: block polygons, joint openings and hinges of a run;
- :mod:`.plots`: plain plotting functions that return the numbers they draw, and the
  ParaView export;
- :mod:`.earthquake`: the suite of real records, incremental dynamic analyses and their
  lognormal fragility;
- :mod:`.diagnosis`: the diagnosis of a shaking-table campaign;
- :mod:`.cli`: the programs ``voussoir-post`` and ``voussoir-diagnose``;

and at the top :mod:`.errors` (every error and its exit status), :mod:`.namelist`
(namelists both ways), :mod:`.runner` (the one way Python runs an executable) and
:mod:`.tables` (what the commands print and write as CSV).
"""

__version__ = "0.1.0"
