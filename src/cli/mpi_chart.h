/* The MPI side of the chart task (compiled only with -DSLIPCONT_MPI=ON):
 * rows of each block are dealt to ranks round-robin, rank 0 gathers them
 * and writes every file.  Only the calling (OpenMP master) thread uses
 * MPI (MPI_THREAD_FUNNELED).  The library never depends on MPI. */
#ifndef SC_CLI_MPI_CHART_H
#define SC_CLI_MPI_CHART_H

#include "slipcont/chart.h"

/* Initialise MPI unless it already is (a process started without mpirun
 * is a singleton of one rank); fills this process's rank and the number
 * of ranks.  Returns SC_OK or SC_EINTERNAL with a message. */
int sc_mpi_chart_begin(int *rank, int *size, sc_msg *msg);

/* Finalise MPI if sc_mpi_chart_begin() initialised it. */
void sc_mpi_chart_end(void);

/* Broadcast @p v from rank 0. */
void sc_mpi_chart_bcast_long(long *v);

/* Smallest status over the ranks (errors are negative, SC_OK is 0). */
int sc_mpi_chart_min_status(int status);

/* Gather the rows of block [r0, r0 + nb): rank k computed rows
 * r0 + k, r0 + k + size, ... into @p mine (row-major, nx points a row);
 * rank 0 receives them into @p grid (the whole chart, row-major) through
 * @p stage (nb * nx points).  Returns SC_OK or SC_EINTERNAL. */
int sc_mpi_chart_gather(const sc_chart_point *mine, long nx, long r0,
                        long nb, int rank, int size, sc_chart_point *stage,
                        sc_chart_point *grid, sc_msg *msg);

#endif
