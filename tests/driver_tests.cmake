# Every input file runs with its driver, and bad inputs are refused cleanly.
file(GLOB INPUT_FILES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/input/*.nml)
foreach(input ${INPUT_FILES})
  get_filename_component(name ${input} NAME_WE)
  add_test(NAME input_${name}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/run_input.sh ${input}
                   ${CMAKE_BINARY_DIR}/drivers ${CMAKE_CURRENT_BINARY_DIR}/inputs/${name} ${Python3_EXECUTABLE})
  if(name MATCHES "^sweep_")
    set_tests_properties(input_${name} PROPERTIES PROCESSORS 2)
  endif()
endforeach()
add_test(NAME bad_inputs
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bad_inputs.sh ${CMAKE_BINARY_DIR}/drivers
                 ${CMAKE_CURRENT_BINARY_DIR}/bad_inputs)
# A full disk (a small tmpfs) while voussoir-run and voussoir-sweep write: a clear
# error, no half-written file, the previous result byte for byte intact.
add_test(NAME disk_full
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/disk_full.sh ${CMAKE_BINARY_DIR}/drivers
                 ${CMAKE_CURRENT_BINARY_DIR}/disk_full)
set_tests_properties(disk_full PROPERTIES PROCESSORS 2)
# Ctrl-C or SIGTERM of a long run: what was computed is written, marked interrupted.
add_test(NAME interrupt
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/interrupt.sh ${CMAKE_BINARY_DIR}/drivers
                 ${CMAKE_CURRENT_BINARY_DIR}/interrupt ${Python3_EXECUTABLE})
# The longest input file (about 30 s: the LP of a fill of particles) starts first.
set_tests_properties(input_bridge_fill_particles PROPERTIES COST 30)
# Multi-ring arches in voussoir-run (&bridge n_rings, issue 37): at rest the abutments hold
# up every ring (weight by hand); where the LP finds the rings cannot carry their weight,
# the run sees them fall.
add_test(NAME bridge_rings_at_rest
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/bridge_rings_at_rest.py
                 ${CMAKE_BINARY_DIR}/drivers/voussoir-run ${CMAKE_BINARY_DIR}/drivers/voussoir-limit
                 ${CMAKE_CURRENT_BINARY_DIR}/bridge_rings_at_rest)
