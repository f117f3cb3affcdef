/* The event catalogue task's parts (task_catalogue.c): one seed's run,
 * the magnitude-frequency distribution of the events' sizes
 * (catalogue_mf.c) and the MPI side (mpi_catalogue.c, or nothing without
 * MPI). */
#ifndef SC_CLI_CATALOGUE_H
#define SC_CLI_CATALOGUE_H

#include <stdio.h>

#include "cli/tasks.h"

/* One seed's run: its rows of catalogue.csv (in memory), its events'
 * sizes, how it ended. */
typedef struct {
  long seed;  /* the threshold seed, -1: the model's thresholds */
  char *rows; /* CSV rows (open_memstream) */
  size_t nbytes;
  double *size;   /* total slip of each event written */
  long n;         /* events written */
  double t_end;   /* start time of the last event written */
  double balance; /* largest |released - (friction - driver)| */
  double scale;   /* largest |released| + |friction| + |driver| */
  double top;     /* the largest event's slip */
  long top_n;     /* and its number of blocks */
  int fail;       /* the map's status (SC_OK: the run is complete) */
  long fail_at;   /* the iterate where it failed */
  sc_msg em;
} sc_cli_cat_run;

/* The magnitude-frequency distribution: events per bin of log10 of their
 * size (total slip, the moment in the model's units), bins of 1 / bpd
 * decade from lo10, and the least-squares line through log10 counts. */
typedef struct {
  int bpd;
  long nbins;
  double lo10; /* log10 of the first bin's lower edge */
  long *count; /* events per bin */
  long total;  /* events counted (size > 0) */
  int fit;     /* 1: the slope is meaningful */
  double slope, slope_se, icpt, r2;
  long fit_bins; /* bins fitted */
  char why[160]; /* fit = 0: why not */
} sc_cli_mf;

int sc_cli_mf_build(const sc_cli_cat_run *runs, long nruns, int bpd,
                    sc_cli_mf *mf, sc_msg *msg);
int sc_cli_mf_write(sc_cli_run *r, const sc_cli_mf *mf);
void sc_cli_mf_summary(FILE *f, const sc_cli_mf *mf);
int sc_cli_mf_plot(sc_cli_run *r, const sc_cli_mf *mf, const char *title);
void sc_cli_mf_free(sc_cli_mf *mf);

/* MPI: this process's rank among size ranks (0 of 1 without MPI); rank
 * 0 alone writes (r->compute_only is set on the others). */
int sc_cli_catalogue_mpi_begin(sc_cli_run *r, int *rank, int *size);
/* Rank 0 receives every other rank's runs (seed i ran on rank i mod
 * size) and every rank learns the worst status. */
int sc_cli_catalogue_mpi_gather(sc_cli_run *r, sc_cli_cat_run *runs, long nruns,
                                int rank, int size, int status);
void sc_cli_catalogue_mpi_end(void);

#endif
