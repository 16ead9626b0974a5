"""Earthquakes: the suite of real records (:mod:`.records`), the reader of incremental
dynamic analyses (:mod:`.ida`) and their lognormal fragility fit (:mod:`.fragility`)."""
