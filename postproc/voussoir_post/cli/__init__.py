"""The command-line programs: ``voussoir-post`` (:mod:`.post`) and ``voussoir-diagnose``
(:mod:`.diagnose`), both through :func:`.entry.run_command`, the one exit-status policy
(0 done, 1 the work failed, 2 bad input; :mod:`voussoir_post.errors`)."""
