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
sc_add_test(test_mapn)
sc_add_test(test_map_equiv)
target_sources(test_map_equiv PRIVATE ref/guard_v0.c)
# bk2's value-only path against its dual path, bit for bit.
sc_add_test(test_bk2_value)

# The searches have no state: recorded inside the map and replayed alone
# they return the same roots bit for bit (bench_searches checks it and
# exits 1 otherwise; its timings are printed, never asserted).
add_executable(search_replay ${PROJECT_SOURCE_DIR}/bench/bench_searches.c)
target_include_directories(search_replay PRIVATE ${PROJECT_SOURCE_DIR}/src
                                                 ${PROJECT_SOURCE_DIR}/bench)
target_compile_options(search_replay PRIVATE ${SC_WARNINGS})
target_link_libraries(search_replay PRIVATE slipcont_static)
add_test(NAME search_replay_chart COMMAND search_replay chart 20)
add_test(NAME search_replay_fig56 COMMAND search_replay fig56 3000)
set_tests_properties(search_replay_chart search_replay_fig56 PROPERTIES
  ENVIRONMENT SLIPCONT_BENCH_REPEAT=1)
# Velocity weakening next to d* and the crossing-sliding borders against
# a long-double Taylor integration of the test's own.
sc_add_test(test_vw_edges)
# Branch starts with velocity weakening: mirror images alike.
sc_add_test(test_vw_starts)
# An integration of the chain of its own and the model's set-up, for the
# chain's tests.
add_library(sc_chain_ref STATIC chain_ref.c)
target_compile_options(sc_chain_ref PRIVATE ${SC_WARNINGS})
target_include_directories(sc_chain_ref PRIVATE ${PROJECT_SOURCE_DIR}/include)
target_link_libraries(sc_chain_ref PRIVATE sc_test_util slipcont_static GSL::gsl m)
sc_add_test(test_chain)
target_link_libraries(test_chain PRIVATE sc_chain_ref)
# The chain's borders: gradients against differences, zeros against the
# itineraries on both sides, two blocks against bk2's (a few seconds).
sc_add_test(test_chain_border)
target_link_libraries(test_chain_border PRIVATE sc_chain_ref)
# The chain's numerical flows: velocity weakening against bk2 and an
# integration of its own, Coulomb through the integrator (a few seconds).
sc_add_test(test_chain_vw)
target_link_libraries(test_chain_vw PRIVATE sc_chain_ref)
# Thresholds per block: betas, the seeded draw, their refusals.
sc_add_test(test_chain_data)
# The chain's second and third derivatives against differences and bk2.
sc_add_test(test_chain_jet)
target_link_libraries(test_chain_jet PRIVATE sc_chain_ref)
sc_add_test(test_guard_long)
# The event catalogue: two blocks against bk2, the energy balance, seeds,
# the example of 100 blocks, the refusals (about 3 s of processor time;
# the limit is for a hang on a loaded machine).
add_test(NAME chain_catalogue
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/chain_catalogue.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
set_tests_properties(chain_catalogue PROPERTIES TIMEOUT 300)
if(SLIPCONT_MPI)
  # Seeds dealt to 2 MPI ranks give the serial files byte for byte.
  add_test(NAME chain_catalogue_mpi
    COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/chain_catalogue_mpi.sh
            $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR}
            ${MPIEXEC_EXECUTABLE})
endif()
# The chain through the program: two blocks give bk2's orbits.
add_test(NAME chain_cli
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/chain_cli.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
# The three-block chain's examples, each claim against a computation of
# its own (docs/chain.md, "Three blocks"): about 4 s of processor time,
# the limit is for a hang on a loaded machine.
add_test(NAME chain3
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/chain3.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
set_tests_properties(chain3 PROPERTIES TIMEOUT 300)
# The three-block chain under velocity weakening: the example's cascade
# against the orbit and flip of tests/test_chain_vw.c (about 3 s).
add_test(NAME chain3_vw
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/chain3_vw.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
set_tests_properties(chain3_vw PROPERTIES TIMEOUT 300)
