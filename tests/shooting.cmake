# Shooting, the fixed-point search and branches of periodic orbits.
sc_add_test(test_shooting)
sc_add_test(test_shootn)
sc_add_test(test_fixed_points)
sc_add_test(test_fixed_points_n)
sc_add_test(test_branch)
sc_add_test(test_branchn)
sc_add_test(test_bordern)
# The fixed-point and branch example scenes through the program.
add_test(NAME branch_examples
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/branch_examples.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
# About 33 s of processor time under the sanitizers, which ran 268 s on
# a shared 2-core machine with 15 jobs waiting: the limit is for a hang.
set_tests_properties(branch_examples PROPERTIES TIMEOUT 600)
add_test(NAME branch_presets
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/branch_presets.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
# fig 5.8 to period 16 under three presets: about 45 s of processor time
# under the sanitizers, 202 s of wall time at load average 15 on a shared
# 2-core machine: the limit is for a hang.
set_tests_properties(branch_presets PROPERTIES TIMEOUT 600)
# Hand-overs, degenerate border points and curves from branch rows.
add_test(NAME branch_edges
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/branch_edges.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
set_tests_properties(branch_edges PROPERTIES TIMEOUT 300)
