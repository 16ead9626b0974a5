"""The diagnosis of a shaking-table campaign (docs/diagnosis.md): the whole in
:mod:`.pipeline` (``diagnose``), its report in :mod:`.report`, its settings in
:mod:`.settings`; the table evidence (:mod:`.actuator`), the effects (:mod:`.effects`),
their simulations (:mod:`.simulator`), the fits (:mod:`.selection`), pairs of effects
(:mod:`.combined`), nested cross-validation (:mod:`.nested`), the verdict
(:mod:`.decision`) and the set-up screen (:mod:`.setup_screen`)."""
