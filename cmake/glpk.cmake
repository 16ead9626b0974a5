# GLPK, the LP library of the limit analysis (src/limit/glpk.f90): its header and its C
# library, or a stop that names the Debian package to install. Included by the top
# CMakeLists.txt and by the probe of tests/glpk_missing.cmake, which hides GLPK from it.
find_path(GLPK_INCLUDE_DIR glpk.h)
find_library(GLPK_LIBRARY glpk)
if(NOT GLPK_INCLUDE_DIR OR NOT GLPK_LIBRARY OR NOT EXISTS "${GLPK_INCLUDE_DIR}/glpk.h")
  message(FATAL_ERROR "GLPK not found (glpk.h and libglpk): the limit analysis solves its linear "
                      "programmes with GLPK. On Debian or Ubuntu: apt-get install libglpk-dev "
                      "(scripts/setup.sh installs it), or set GLPK_INCLUDE_DIR (the folder of glpk.h) "
                      "and GLPK_LIBRARY.")
endif()
