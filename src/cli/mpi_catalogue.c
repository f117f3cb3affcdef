/* MPI for the catalogue task (compiled only with -DSLIPCONT_MPI=ON; see
 * catalogue.h): seed i runs on rank i mod size, rank 0 receives every
 * other rank's runs in seed order and writes every file, so the files are
 * those of one process.  Only the master thread calls MPI. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "cli/catalogue.h"
#include "cli/mpi_chart.h"

int sc_cli_catalogue_mpi_begin(sc_cli_run *r, int *rank, int *size) {
  int st = sc_mpi_chart_begin(rank, size, r->msg);
  if (!st) r->compute_only = *rank != 0;
  return st;
}

void sc_cli_catalogue_mpi_end(void) { sc_mpi_chart_end(); }

/* A run's numbers, as doubles (counts are below 2^53). */
enum {
  H_N,
  H_BYTES,
  H_TEND,
  H_BAL,
  H_SCALE,
  H_TOP,
  H_TOPN,
  H_FAIL,
  H_AT,
  H_COUNT
};

static void pack(const sc_cli_cat_run *c, double *h) {
  h[H_N] = (double)c->n, h[H_BYTES] = (double)c->nbytes;
  h[H_TEND] = c->t_end, h[H_BAL] = c->balance, h[H_SCALE] = c->scale;
  h[H_TOP] = c->top, h[H_TOPN] = (double)c->top_n;
  h[H_FAIL] = c->fail, h[H_AT] = (double)c->fail_at;
}

static void unpack(sc_cli_cat_run *c, const double *h) {
  c->n = (long)h[H_N], c->nbytes = (size_t)h[H_BYTES];
  c->t_end = h[H_TEND], c->balance = h[H_BAL], c->scale = h[H_SCALE];
  c->top = h[H_TOP], c->top_n = (long)h[H_TOPN];
  c->fail = (int)h[H_FAIL], c->fail_at = (long)h[H_AT];
}

/* Rank k sends the runs of its seeds; rank 0 takes them in seed order.
 * A run's text is sent in pieces of at most INT_MAX bytes' worth (one
 * seed's rows are far below it). */
static int move_run(sc_cli_cat_run *c, int from, int rank, sc_msg *msg) {
  double h[H_COUNT];
  if (rank == from) {
    pack(c, h);
    MPI_Send(h, H_COUNT, MPI_DOUBLE, 0, 1, MPI_COMM_WORLD);
    MPI_Send(c->em.text, SC_MSG_LEN, MPI_CHAR, 0, 2, MPI_COMM_WORLD);
    MPI_Send(c->rows, (int)c->nbytes, MPI_CHAR, 0, 3, MPI_COMM_WORLD);
    MPI_Send(c->size, (int)c->n, MPI_DOUBLE, 0, 4, MPI_COMM_WORLD);
    return SC_OK;
  }
  MPI_Recv(h, H_COUNT, MPI_DOUBLE, from, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  unpack(c, h);
  MPI_Recv(c->em.text, SC_MSG_LEN, MPI_CHAR, from, 2, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  free(c->rows);
  free(c->size);
  c->rows = malloc(c->nbytes + 1);
  c->size = malloc(((size_t)c->n + 1) * sizeof *c->size);
  int ok = c->rows && c->size;
  /* receive anyway, so that the sender is not left waiting */
  char dump;
  MPI_Recv(ok ? c->rows : &dump, ok ? (int)c->nbytes : 0, MPI_CHAR, from, 3,
           MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Recv(ok ? c->size : NULL, ok ? (int)c->n : 0, MPI_DOUBLE, from, 4,
           MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return ok ? SC_OK
            : sc_fail(msg, SC_ENOMEM, "catalogue: out of memory (rank 0)");
}

int sc_cli_catalogue_mpi_gather(sc_cli_run *r, sc_cli_cat_run *runs, long nruns,
                                int rank, int size, int status) {
  int all = sc_mpi_chart_min_status(status);
  if (all) {
    if (!status)
      status = sc_fail(r->msg, all, "catalogue: another rank failed (%s)",
                       sc_strerror(all));
    return status;
  }
  int st = SC_OK;
  for (long i = 0; i < nruns; i++) {
    int from = (int)(i % size);
    if (from == 0 || (rank != 0 && rank != from)) continue;
    int s = move_run(&runs[i], from, rank, r->msg);
    if (!st) st = s;
  }
  return sc_mpi_chart_min_status(st);
}
