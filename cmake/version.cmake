# Writes the Fortran version module from src/core/version.f90.in with the project version and
# `git describe` of the source tree; run at every build, so that the version recorded in
# result files follows the commit (configure_file rewrites only when the text changes).
#   cmake -DSRC=<source dir> -DOUT=<file> -DVERSION=<x.y.z> -P version.cmake
set(GIT_DESCRIBE "unknown")
find_program(GIT_EXECUTABLE git)
if(GIT_EXECUTABLE AND EXISTS "${SRC}/.git")
  execute_process(COMMAND "${GIT_EXECUTABLE}" describe --always --dirty --tags
                  WORKING_DIRECTORY "${SRC}" OUTPUT_VARIABLE GIT_DESCRIBE
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0 OR GIT_DESCRIBE STREQUAL "")
    set(GIT_DESCRIBE "unknown")
  endif()
endif()
set(VOUSSOIR_VERSION_STRING "${VERSION}+${GIT_DESCRIBE}")
configure_file("${SRC}/src/core/version.f90.in" "${OUT}" @ONLY)
