"""The diagnosis of a measured campaign, as stages that hand their result to the next:
observations (:mod:`.observations`), the simulation bank (:mod:`.bank`, through
:mod:`.simulator`), each model's predictions and likelihood (:mod:`.models`,
:mod:`.likelihood`), the posterior (:mod:`.posterior`), the verdict (:mod:`.decision`) and
the report (:mod:`.report`, with :mod:`.single_runs` and :mod:`.screen`), tied together by
:mod:`.pipeline`."""
