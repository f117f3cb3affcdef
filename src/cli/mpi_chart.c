/* MPI for the chart task: see mpi_chart.h. */
#include "cli/mpi_chart.h"

#include <mpi.h>
#include <stdlib.h>
#include <string.h>

/* Set when this process called MPI_Init_thread, so that only it
 * finalises: the one piece of process state the distributed run needs. */
static int we_initialised;

int sc_mpi_chart_begin(int *rank, int *size, sc_msg *msg) {
  int inited = 0;
  MPI_Initialized(&inited);
  if (!inited) {
    int provided = 0;
    if (MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided) !=
        MPI_SUCCESS)
      return sc_fail(msg, SC_EINTERNAL, "chart: MPI_Init_thread failed");
    we_initialised = 1;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  return SC_OK;
}

void sc_mpi_chart_end(void) {
  if (!we_initialised) return;
  int done = 0;
  MPI_Finalized(&done);
  if (!done) MPI_Finalize();
  we_initialised = 0;
}

void sc_mpi_chart_bcast_long(long *v) {
  MPI_Bcast(v, 1, MPI_LONG, 0, MPI_COMM_WORLD);
}

int sc_mpi_chart_min_status(int status) {
  int out = status;
  MPI_Allreduce(&status, &out, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return out;
}

/* Rows of a block of nb rows that rank k computes. */
static long rows_of(long nb, int k, int size) {
  return k < nb ? (nb - k + size - 1) / size : 0;
}

int sc_mpi_chart_gather(const sc_chart_point *mine, long nx, long r0,
                        long nb, int rank, int size, sc_chart_point *stage,
                        sc_chart_point *grid, sc_msg *msg) {
  /* Byte counts: the points are plain data and the ranks run the same
   * binary on machines of one architecture. */
  const long row_bytes = nx * (long)sizeof(sc_chart_point);
  int *counts = NULL, *displs = NULL;
  if (rank == 0) {
    counts = malloc((size_t)size * sizeof *counts);
    displs = malloc((size_t)size * sizeof *displs);
    if (!counts || !displs) {
      free(counts);
      free(displs);
      MPI_Abort(MPI_COMM_WORLD, 1);
      return sc_fail(msg, SC_ENOMEM, "chart: out of memory (MPI gather)");
    }
    long off = 0;
    for (int k = 0; k < size; k++) {
      counts[k] = (int)(rows_of(nb, k, size) * row_bytes);
      displs[k] = (int)off;
      off += counts[k];
    }
  }
  int st = MPI_Gatherv(mine, (int)(rows_of(nb, rank, size) * row_bytes),
                       MPI_BYTE, stage, counts, displs, MPI_BYTE, 0,
                       MPI_COMM_WORLD);
  if (rank == 0 && st == MPI_SUCCESS) {
    for (int k = 0; k < size; k++) {
      const sc_chart_point *src = stage + displs[k] / (long)sizeof *stage;
      for (long t = 0; t < rows_of(nb, k, size); t++)
        memcpy(grid + (r0 + k + t * size) * nx, src + t * nx,
               (size_t)row_bytes);
    }
  }
  free(counts);
  free(displs);
  if (st != MPI_SUCCESS)
    return sc_fail(msg, SC_EINTERNAL, "chart: MPI_Gatherv failed");
  return SC_OK;
}
