/* Task `fixed-point` for maps of n > 1 dimensions: periodic orbits
 * without a start guess (sc_fixed_points_n_find(), orbits.h) or from the
 * start d0.  Called by task_fixed_point.c for a model with n > 1. */
#ifndef SLIPCONT_CLI_TASK_FIXED_POINT_N_H
#define SLIPCONT_CLI_TASK_FIXED_POINT_N_H

#include <stdio.h>

#include "cli/tasks.h"
#include "slipcont/orbits.h"

/** One n-dimensional search: its spec, its box or start, its result. */
typedef struct {
  sc_fixed_points_n_spec sp;
  double from[SC_MAXDIM], to[SC_MAXDIM], start[SC_MAXDIM];
  sc_orbitn_set *set;
  unsigned long nev; /* map evaluations of the search */
  double elapsed;    /* its seconds */
} sc_fpn_job;

/* The checks of the scene for n > 1 (lo, hi: the periods read, -1 if the
 * text is not a period or range). */
int sc_fpn_check(const sc_scene *s, long lo, long hi, sc_msg *msg);
int sc_fpn_prepare(sc_cli_run *r, long lo, long hi, sc_fpn_job *j);
int sc_fpn_compute(sc_cli_run *r, sc_fpn_job *j);
int sc_fpn_write(sc_cli_run *r, const sc_fpn_job *j);
int sc_fpn_summary(sc_cli_run *r, const sc_fpn_job *j, FILE *f);
int sc_fpn_plots(sc_cli_run *r, const sc_fpn_job *j);
int sc_fpn_report(sc_cli_run *r, const sc_fpn_job *j);
void sc_fpn_release(sc_fpn_job *j);

#endif
