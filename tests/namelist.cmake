# tests/namelist/layouts.nml read by the project's namelist reader and by gfortran's own
# NAMELIST READ: every group found, every value the same to the bit (issue 34).
add_executable(test_namelist_layouts ${CMAKE_CURRENT_SOURCE_DIR}/namelist/test_namelist_layouts.f90)
target_link_libraries(test_namelist_layouts PRIVATE voussoir_assert)
add_test(NAME namelist_layouts
         COMMAND test_namelist_layouts ${CMAKE_CURRENT_SOURCE_DIR}/namelist/layouts.nml)
