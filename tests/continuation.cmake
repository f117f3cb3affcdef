# Tests of the generic continuation layer (continuation/).
sc_add_test(test_linalg)
sc_add_test(test_continuation)
sc_add_test(test_curve)
sc_add_test(test_normal_form)
sc_add_test(test_curven)
sc_add_test(test_curve_border)
sc_add_test(test_mapn_system)
add_test(NAME test_curve_cli
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_curve_cli.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
# Every bk2 curve scene of examples/ and fig 5.7(b), held to the promise
# of its opening comment; curve_points recomputes the fold and flip
# curves' points from the map layer alone.
add_executable(curve_points curve_points.c ${SC_TEST_CLI_SOURCES})
target_include_directories(curve_points PRIVATE ${PROJECT_SOURCE_DIR}/src)
target_compile_options(curve_points PRIVATE ${SC_WARNINGS})
target_link_libraries(curve_points PRIVATE slipcont_io_static slipcont_static
                                           GSL::gsl OpenMP::OpenMP_C)
add_test(NAME curve_examples
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/curve_examples.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR}
          $<TARGET_FILE:curve_points>)
set_tests_properties(curve_examples PROPERTIES TIMEOUT 300)
# Multipliers of a product without forming it (continuation/product_eigs.c).
sc_add_test(test_product_eigs)
# The curve task on n-dimensional models: ghenon's examples against their
# closed forms, a start from a branch row, the refusals.
add_test(NAME curve_n_cli
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/curve_n_cli.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
