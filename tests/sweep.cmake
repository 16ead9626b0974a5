# MPI and driver tests of voussoir-sweep (issue 4): tests/sweep/sweep_test.py runs the
# real executables under MPIEXEC_EXECUTABLE and checks the result files with h5py.
#   sweep_ranks             same file on 1, 2 and 3 (oversubscribed) ranks; thresholds
#                           consistent with their own runs
#   sweep_grid              grid mode on 1 and 3 ranks; a grid row equals a single run
#   sweep_resume            kill -9 of mpirun mid-sweep, rerun: nothing redone, same file
#   sweep_refuse            another sweep's file, or a run's file, is refused untouched
#   sweep_threshold_vs_run  voussoir-run stands at threshold - amp_tol, falls at threshold
#   sweep_bad_inputs        bad &sweep values: clear errors, no result file
#   sweep_failing_job       a job whose run fails is recorded as failed, the others finish
#   sweep_lock              a second sweep on the same file is refused while the first runs
#   sweep_ida_samples       an IDA over the model samples of a file: the file's values in
#                           the rows and in the runs (voussoir-limit, voussoir-run), the
#                           samples in the sweep definition, bad files refused
#   sweep_ida_replay        --write-rows: voussoir-run on a row's inputs gives the row's
#                           outcome (collapse time; steps at rest, ended at rest)
#   sweep_bridge            a &bridge semicircle without fill: the &arch builder's thresholds,
#                           onsets, IDA scale and capacity; its --write-rows input replayed;
#                           with fill, the onset against a ramp in voussoir-run; the refusals
# The input files input/sweep_*.nml are run by driver_tests.cmake.
if(NOT TARGET voussoir-sweep)
  return()
endif()
if(NOT MPIEXEC_EXECUTABLE)
  message(FATAL_ERROR "voussoir-sweep is built but no mpiexec was found: its MPI tests cannot run")
endif()

foreach(case ranks grid resume refuse threshold_vs_run bad_inputs failing_job lock ida_samples ida_replay bridge)
  add_test(NAME sweep_${case}
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/sweep/sweep_test.py ${case}
                   --mpiexec ${MPIEXEC_EXECUTABLE} --bin $<TARGET_FILE_DIR:voussoir-sweep>
                   --work ${CMAKE_CURRENT_BINARY_DIR}/sweep/${case})
  # Open MPI refuses to run as root unless told; only for these tests, never globally.
  set_tests_properties(sweep_${case} PROPERTIES
                       ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1"
                       PROCESSORS 2 TIMEOUT 600)
endforeach()
