# Tests of the voussoir-limit executable (issue 3). Each test runs the real program on a
# namelist and checks its JSON (and table) with tests/limit/check_limit.py. Expected
# numbers are derived independently of the module: symmetry of
# the arch, the geometry conventions of docs/measured_data.md, published values
# (t/R_ext = 0.10188 for 20 chord-faced voussoirs), an independent static LP
# (tests/test_limit_analysis.f90) and statics (a 180-degree arch whose friction is below
# lambda must slide at a springing: the springings carry the whole horizontal load
# lambda W with a total normal force W).
if(NOT TARGET voussoir-limit)
  return()
endif()

set(LIMIT_TEST_DIR ${CMAKE_CURRENT_BINARY_DIR}/limit_driver)
file(MAKE_DIRECTORY ${LIMIT_TEST_DIR})
# The input files input/limit_<case>.nml.
foreach(case seed_156 seed_180 seed_118 min_thickness_20)
  add_test(NAME limit_driver_${case}
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                   ${case} ${CMAKE_SOURCE_DIR}/input/limit_${case}.nml
           WORKING_DIRECTORY ${LIMIT_TEST_DIR})
endforeach()
add_test(NAME limit_driver_low_friction
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit> low_friction
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
add_test(NAME limit_driver_bad_inputs
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit> bad_inputs
                 ${CMAKE_SOURCE_DIR}/input/limit_seed_156.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# The limit analysis by linear programming: the seed arch at friction 0.395 (sliding
# governs), a polygon file (a block tipping at b/h) and a wall (sliding at mu).
add_test(NAME limit_driver_friction_0395
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 friction_0395 ${CMAKE_SOURCE_DIR}/input/limit_seed_156.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
add_test(NAME limit_driver_polygon_block
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 polygon_block ${CMAKE_SOURCE_DIR}/input/rocking_block.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
add_test(NAME limit_driver_wall_sliding
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 wall_sliding ${CMAKE_SOURCE_DIR}/input/wall_sliding.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# &arch joint_friction (issue 25): the friction of each joint as the dynamics takes it.
add_test(NAME limit_driver_joint_friction
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 joint_friction ${CMAKE_SOURCE_DIR}/input/limit_seed_156.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# &limit compressive_strength_pa (issue 25): a block tipping about a point set in by the
# stress block (closed form) and the seed arch's forces at their crushing offsets.
add_test(NAME limit_driver_crushing
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 crushing ${CMAKE_SOURCE_DIR}/input/rocking_block.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# Restraint brackets (issue 25): the LP against the least four-hinge mechanism with no
# hinge at a restrained springing, computed in the check itself.
add_test(NAME limit_driver_restrained
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 restrained
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# &load (issue 25): a vertical live point load on a semicircular arch at quarter span and
# along a path, against the least four-hinge mechanism computed in the check itself.
add_test(NAME limit_driver_arch_point_load
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 arch_point_load
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# &bridge (issue 37): a semicircle built by &bridge against the arch builder's on the same
# geometry (the same load factors to 1e-10), and the two-span bridge of input/ in statics.
add_test(NAME limit_driver_bridge
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 bridge ${CMAKE_SOURCE_DIR}/input/bridge_two_spans.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# The fill of &bridge (issue 37): its weight and the spread of a live load through it,
# checked from the JSON's blocks (closed-form columns, the spread lines, statics).
add_test(NAME limit_driver_bridge_fill
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 bridge_fill ${CMAKE_SOURCE_DIR}/input/bridge_fill.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# The fill as particles (issue 37, item 2(b)): the particles tile the fill (convex, no
# overlap, the region's shoelace area), statics, and the lower bound against the columns.
add_test(NAME limit_driver_bridge_particles
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 bridge_particles ${CMAKE_SOURCE_DIR}/input/bridge_fill_particles.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# Masonry backing over the haunches (&bridge backing_level_m, issue 37): the courses tile the
# backed region, the fill stands on them, statics, and weightless backing lowers no load factor.
add_test(NAME limit_driver_bridge_backing
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 bridge_backing ${CMAKE_SOURCE_DIR}/input/bridge_backing.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# Multi-ring arches (&bridge n_rings, issue 37): the rings' load factor at most the single
# ring's and non-decreasing in the friction between them, the single ring's under vertical
# loads at friction 10, ring separation at friction 0, the fill on the outer ring alone.
add_test(NAME limit_driver_bridge_rings
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 bridge_rings
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# The parts' compressive strengths (&bridge ring_/pier_compressive_strength_pa, issue 37):
# a single span's ring at S is &limit's S on every interface, each interface of two spans
# at the lesser of its blocks' strengths.
add_test(NAME limit_driver_bridge_strength
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 bridge_strength ${CMAKE_SOURCE_DIR}/input/bridge_fill.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# Vehicles (&vehicle, issue 37) on the span of input/bridge_fill.nml: a one-axle vehicle is
# the point load, two half axles 0 m apart are one, the axles where they stand, the
# harmonic bound of the axles alone (convexity), the named LM1 tandem against its axles.
add_test(NAME limit_driver_bridge_vehicle
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 bridge_vehicle ${CMAKE_SOURCE_DIR}/input/bridge_fill.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# Boussinesq's dispersion (&bridge dispersion = 'boussinesq', issue 37) on the span of
# input/bridge_fill.nml: each strip against Flamant's stress integrated in the check, the
# spread's ends, symmetry over the crown, statics, and the bound by the undispersed load.
add_test(NAME limit_driver_bridge_boussinesq
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 bridge_boussinesq ${CMAKE_SOURCE_DIR}/input/bridge_fill.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# Patches, load cases and partial factors (&load point_load_patch_m, &load_cases, issue 37):
# a vanishing patch is the point load, gamma_q divides the load factor, gamma_g multiplies
# it (the LP is homogeneous in the loads) with statics under the factored loads, and each
# case of input/bridge_load_cases.nml equals that case alone in its own file.
add_test(NAME limit_driver_load_cases
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/limit/check_limit.py $<TARGET_FILE:voussoir-limit>
                 load_cases ${CMAKE_SOURCE_DIR}/input/bridge_load_cases.nml
         WORKING_DIRECTORY ${LIMIT_TEST_DIR})
# The longest tests start first (CTest runs the highest COST first; a fresh clone has no
# timings of its own): about 20-30 s each, where most take a second or two.
set_tests_properties(limit_driver_bridge_particles PROPERTIES COST 30)
