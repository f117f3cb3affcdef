# Tests of the generic continuation layer (continuation/).
sc_add_test(test_linalg)
sc_add_test(test_continuation)
sc_add_test(test_curve)
sc_add_test(test_curve_border)
add_test(NAME test_curve_cli
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_curve_cli.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
# Every bk2 curve scene of examples/ and fig 5.7(b), held to the promise
# of its opening comment.
add_test(NAME curve_examples
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/curve_examples.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
set_tests_properties(curve_examples PROPERTIES TIMEOUT 300)
