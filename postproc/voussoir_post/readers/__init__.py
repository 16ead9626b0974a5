"""Readers of files: the result files of the Fortran drivers (:mod:`.results`,
:mod:`.limit_results`), shaking-table campaign folders (:mod:`.campaign` over
:mod:`.campaign_csv`, summarised by :mod:`.campaign_summary`) and the one CSV reader
they share (:mod:`.csv_table`)."""
