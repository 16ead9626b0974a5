# The layers of src/ are enforced by the build: a module may use only the modules of the
# libraries its target links. The probe uses voussoir_setup (run layer) from a target
# that links the input layer only: its compilation must fail on that module; the same
# source linked to the run layer must compile.
add_library(layering_probe_wrong_way STATIC EXCLUDE_FROM_ALL ${CMAKE_CURRENT_SOURCE_DIR}/layering/input_uses_nothing_above.f90)
set_target_properties(layering_probe_wrong_way PROPERTIES Fortran_MODULE_DIRECTORY ${CMAKE_BINARY_DIR}/modules/probe_wrong)
target_link_libraries(layering_probe_wrong_way PRIVATE voussoir_input)
add_library(layering_probe_right_way STATIC EXCLUDE_FROM_ALL ${CMAKE_CURRENT_SOURCE_DIR}/layering/input_uses_nothing_above.f90)
set_target_properties(layering_probe_right_way PROPERTIES Fortran_MODULE_DIRECTORY ${CMAKE_BINARY_DIR}/modules/probe_right)
target_link_libraries(layering_probe_right_way PRIVATE voussoir_run)
add_test(NAME layering_wrong_way_use_does_not_build
         COMMAND ${CMAKE_COMMAND} --build ${CMAKE_BINARY_DIR} --target layering_probe_wrong_way)
set_tests_properties(layering_wrong_way_use_does_not_build PROPERTIES
  PASS_REGULAR_EXPRESSION "voussoir_setup\\.mod" FAIL_REGULAR_EXPRESSION "Built target layering_probe_wrong_way"
  RESOURCE_LOCK build_tree)
add_test(NAME layering_right_way_use_builds
         COMMAND ${CMAKE_COMMAND} --build ${CMAKE_BINARY_DIR} --target layering_probe_right_way)
set_tests_properties(layering_right_way_use_builds PROPERTIES RESOURCE_LOCK build_tree)
