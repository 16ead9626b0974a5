# A missing LP library stops the configuration with the package to install (issue 25).
# The probe project tests/glpk_missing/ runs cmake/glpk.cmake, the top CMakeLists.txt's
# search for GLPK: as it stands it finds GLPK; with every include and library folder
# re-rooted under an empty folder (CMAKE_FIND_ROOT_PATH, mode ONLY) it must stop and
# name the Debian package, libglpk-dev.
set(GLPK_PROBE_DIR ${CMAKE_CURRENT_BINARY_DIR}/glpk_missing)
file(MAKE_DIRECTORY ${GLPK_PROBE_DIR}/empty_root)
add_test(NAME glpk_found_by_the_probe
         COMMAND ${CMAKE_COMMAND} -S ${CMAKE_CURRENT_SOURCE_DIR}/glpk_missing -B ${GLPK_PROBE_DIR}/visible
                 -DVOUSSOIR_SOURCE_DIR=${CMAKE_SOURCE_DIR})
set_tests_properties(glpk_found_by_the_probe PROPERTIES PASS_REGULAR_EXPRESSION "GLPK found: [^\n]*glpk\\.h and [^\n]*glpk")
add_test(NAME glpk_missing_names_the_package
         COMMAND ${CMAKE_COMMAND} -S ${CMAKE_CURRENT_SOURCE_DIR}/glpk_missing -B ${GLPK_PROBE_DIR}/hidden
                 -DVOUSSOIR_SOURCE_DIR=${CMAKE_SOURCE_DIR} -DCMAKE_FIND_ROOT_PATH=${GLPK_PROBE_DIR}/empty_root
                 -DCMAKE_FIND_ROOT_PATH_MODE_INCLUDE=ONLY -DCMAKE_FIND_ROOT_PATH_MODE_LIBRARY=ONLY)
set_tests_properties(glpk_missing_names_the_package PROPERTIES
  PASS_REGULAR_EXPRESSION "GLPK not found.*apt-get[ \n]+install[ \n]+libglpk-dev"
  FAIL_REGULAR_EXPRESSION "GLPK found:")
