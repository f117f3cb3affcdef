/* Task `branch` for maps of n > 1 dimensions: a fixed point or periodic
 * orbit continued in one parameter with its LP, PD, NS and BP points
 * (sc_branchn, branchn.h).  Called by task_branch.c for a model with
 * n > 1; the one-dimensional path is task_branch.c's own. */
#ifndef SLIPCONT_CLI_TASK_BRANCH_N_H
#define SLIPCONT_CLI_TASK_BRANCH_N_H

#include <stdio.h>

#include "cli/tasks.h"
#include "slipcont/branchn.h"

/** One n-dimensional branch run. */
typedef struct {
  const char *pname;
  size_t param;
  double x0[SC_MAXDIM];
  sc_branchn_spec sp;
  sc_branchn *b;
  int show;              /* sc_cli_show(): a component from 0, or
                            SC_CLI_SHOW_NORM */
  double elapsed;
  unsigned long nev;
} sc_brn_job;

/* The checks of the scene for n > 1: the keys of the one-dimensional
 * path that have no meaning here are refused, `show` is read. */
int sc_brn_check(const sc_scene *s, sc_msg *msg);
int sc_brn_prepare(sc_cli_run *r, sc_brn_job *j);
int sc_brn_compute(sc_cli_run *r, sc_brn_job *j);
int sc_brn_write(sc_cli_run *r, const sc_brn_job *j);
int sc_brn_summary(sc_cli_run *r, const sc_brn_job *j, FILE *f);
int sc_brn_plots(sc_cli_run *r, const sc_brn_job *j);
int sc_brn_report(sc_cli_run *r, const sc_brn_job *j);
void sc_brn_release(sc_brn_job *j);

#endif
