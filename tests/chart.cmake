# Period detection and two-parameter charts.
sc_add_test(test_period)
sc_add_test(test_chart)
# Through the program: threads, resume, signals, bad scenes, examples.
add_test(NAME chart_cli
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/chart_cli.sh
          $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR})
if(SLIPCONT_MPI)
  add_test(NAME chart_mpi
    COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/chart_mpi.sh
            $<TARGET_FILE:slipcont_cli> ${PROJECT_SOURCE_DIR}
            ${MPIEXEC_EXECUTABLE})
endif()
