# Scenes, outputs, sweeps and the slipcont program (src/io, src/cli,
# src/analysis/sweep.c).
sc_add_test(test_scene)
sc_add_test(test_scene_sweep)
sc_add_test(test_plot)

# The program itself, through small shell scripts: refusals of bad input,
# overrides, outputs, the examples, and the guide's key tables.
foreach(script cli_errors cli_refusals cli_signals cli_steps cli_outputs cli_examples cli_guide
               cli_messages cli_inputs cli_fixed_point cli_fixed_point_n cli_branch_n
               cli_mapn cli_bordern)
  add_test(NAME ${script}
    COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/${script}.sh
            $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
endforeach()
set_tests_properties(cli_examples cli_mapn PROPERTIES TIMEOUT 300)
# The Henon example searches periods 1..12 from 1441 starts each: about
# 3 s of processor time, 167 s of wall time under the sanitizers on the
# shared 2-core machine at load 19: the limit is for a hang.
set_tests_properties(cli_fixed_point_n PROPERTIES TIMEOUT 600)
# The ghenon atlas: its chart and curves against the closed forms
# (docs/maps.md, "The ghenon atlas").
add_test(NAME ghenon_atlas
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/ghenon_atlas.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
set_tests_properties(ghenon_atlas PROPERTIES TIMEOUT 300)
# Every example is run by some test (by name), so a new one cannot go
# unchecked.
add_test(NAME examples_covered
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/examples_covered.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
# A model that hangs must fail the suite, not stall it.
set_tests_properties(test_scene_sweep PROPERTIES TIMEOUT 300)
# The examples' figures: labels clear of each other, keys, tick formats.
add_test(NAME figures
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/figures.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
set_tests_properties(figures PROPERTIES TIMEOUT 600) # ~3 min under the sanitizers
# Added starts of a branch: the summary's counts equal the rows.
add_test(NAME branch_starts
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/branch_starts.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
# User points (UZ) on branches and curves.
add_test(NAME user_points
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/user_points.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
