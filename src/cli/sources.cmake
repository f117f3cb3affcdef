# sources of the slipcont program: one line per task (see src/cli/tasks.h)
set(SC_CLI_SOURCES
  src/cli/main.c
  src/cli/help.c
  src/cli/run.c
  src/cli/inputs.c
  src/cli/marks.c
  src/cli/tasks.c
  src/cli/show.c)
list(APPEND SC_CLI_SOURCES src/cli/task_orbit.c)
list(APPEND SC_CLI_SOURCES src/cli/task_map.c)
list(APPEND SC_CLI_SOURCES src/cli/task_sweep.c)
list(APPEND SC_CLI_SOURCES src/cli/task_chart.c src/cli/progress.c $<$<BOOL:${SLIPCONT_MPI}>:src/cli/mpi_chart.c>)
list(APPEND SC_CLI_SOURCES src/cli/task_fixed_point.c src/cli/task_branch.c
  src/cli/task_fixed_point_n.c src/cli/task_branch_n.c)
list(APPEND SC_CLI_SOURCES src/cli/task_curve.c src/cli/task_curve_n.c)
list(APPEND SC_CLI_SOURCES src/cli/task_catalogue.c src/cli/catalogue_mf.c
  $<$<BOOL:${SLIPCONT_MPI}>:src/cli/mpi_catalogue.c>)
