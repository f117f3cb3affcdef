# Tests of the generic continuation layer (continuation/).
sc_add_test(test_linalg)
sc_add_test(test_continuation)
sc_add_test(test_curve)
sc_add_test(test_curve_border)
add_test(NAME test_curve_cli
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_curve_cli.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
