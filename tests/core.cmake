sc_add_test(test_common)
sc_add_test(test_guard)
# the searches once more without the pair march's lanes, to compare
target_sources(test_guard PRIVATE guard_scalar.c)
sc_add_test(test_bk2)
# The 1:n resonance of a slip of both blocks: BR = 0 at alpha = (n^2-1)/2.
sc_add_test(test_bk2_resonance)
# The API example prints the period-2 orbit of fig 5.4.
add_test(NAME example_api COMMAND example_api)
set_tests_properties(example_api PROPERTIES PASS_REGULAR_EXPRESSION
  "d = -0.0153337753869[0-9]* -> f\\(d\\) = 0.0153337753869[0-9]*  f' = 0.634677  itinerary 1-12-2")
sc_add_test(test_jet)
# The map with the current root search against the frozen earlier one.
sc_add_test(test_map_equiv)
target_sources(test_map_equiv PRIVATE ref/guard_v0.c)
# bk2's value-only path against its dual path, bit for bit.
sc_add_test(test_bk2_value)

# bench/side_by_side.sh's refusals (the benchmark itself is not a test).
add_test(NAME bench_args
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/bench_args.sh ${PROJECT_SOURCE_DIR})
