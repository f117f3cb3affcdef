/* Private to the curve task (task_curve.c, task_curve_n.c): the streams a
 * trace writes into, the special points kept for the summary and the
 * figure, and the n-dimensional path (docs/maps.md, "Curves and
 * codimension two"). */
#ifndef SC_CLI_CURVE_IMPL_H
#define SC_CLI_CURVE_IMPL_H

#include <stdio.h>

#include "cli/tasks.h"
#include "slipcont/curve.h"

typedef struct {
  FILE *curve, *points;
  int period;
  int last_branch;
  sc_curve_special *sp; /* every special row, in order (n-d: the state's
                           first component as d) */
  size_t nsp, cap;
  int oom;
  int have_start;          /* the first point: the corrected start */
  double start_x, start_y;
} out_ctx;

/* Keep @p s in c->sp; 1 when out of memory. */
int sc_cli_curve_keep(out_ctx *c, const sc_curve_special *s);

/* The n-dimensional path of a curve run (opaque). */
typedef struct sc_cli_curve_n sc_cli_curve_n;

/* The checks of an n-dimensional model's curve scene: the type (fold,
 * flip or ns), no multiple shooting, no marks, and a start row (if
 * `start` is given) that is an LP, PD or NS in x with a state of the
 * model's dimension; its x value into *xstart (unchanged without). */
int sc_cli_curve_n_check(const sc_scene *s, const char *type,
                         const char *want_label, double *xstart,
                         sc_msg *msg);

/* The start (d0 or the row of `start`, which also sets x and the
 * period in @p set) into a new path object. */
int sc_cli_curve_n_prepare(sc_cli_run *r, sc_curve_settings *set,
                           sc_cli_curve_n **out);
void sc_cli_curve_n_free(sc_cli_curve_n *c);
/* Points of an NS curve traced with |kappa| > 1 (neutral saddles); 0 for
 * other curves. */
long sc_cli_curve_n_saddles(const sc_cli_curve_n *c);

/* The trace, streamed into curve.csv and points.csv of @p c's run. */
int sc_cli_curve_n_compute(sc_cli_run *r, sc_cli_curve_n *nd,
                           const sc_curve_settings *set, out_ctx *c,
                           sc_curve_stats *stats);

/* The summary's list of codimension-two and end points, and the NS
 * curve's Neimark-Sacker and neutral-saddle parts. */
void sc_cli_curve_n_summary(FILE *f, const sc_cli_run *r,
                            const sc_cli_curve_n *nd);

#endif
