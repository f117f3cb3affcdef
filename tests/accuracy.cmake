# Accuracy: the quad-precision reference path, the presets'
# promises held against it, and the extremes of the parameter ranges.
sc_add_test(test_quad)
sc_add_test(test_extremes)
set_tests_properties(test_extremes PROPERTIES TIMEOUT 300)
# The precision key through the program, with its example scene.
add_test(NAME accuracy_cli
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/accuracy_cli.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
set_tests_properties(accuracy_cli PROPERTIES TIMEOUT 300)
# The fig 5.8 flip cascade to its period-4096 orbit, certified against
# quad (bench_cascade in bench/ runs it to period 8192).
sc_add_test(test_cascade)
