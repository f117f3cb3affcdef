/* slipcont's side of the ghenon comparison with AUTO-07p
 * (docs/performance.md, "Beside AUTO-07p: ghenon"): the branch of fixed
 * points of the generalized Henon map in alpha at beta = 1.2, R = 0.5,
 * from x = y = -5.64 (alpha = 3.5) through LP, NS and PD back to
 * alpha = 3.5 (sc_branchn_run), then the fold, flip and NS curves in
 * (alpha, beta), each from its point on the branch (sc_curven_trace, both
 * ways), in the box alpha in [-3, 5], beta in [-1.5, 2]; every value
 * against the closed forms (docs/maps.md, "The ghenon atlas").
 *
 *   ghenon_bench once       one computation in a fresh process, its time
 *   ghenon_bench repeat N   the median of N computations in this process
 *
 * The time includes the map's allocation.  Built and run by
 * run_ghenon.sh; prints one line a result ("key value ...") that
 * run_ghenon.py reads. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/slipcont.h"
#include "bench_util.h" /* bench/ */

static const double R = 0.5, BETA0 = 1.2, FROM = 3.5, TO = -3;
static const double ALO = -3, AHI = 5, BLO = -1.5, BHI = 2;
/* The largest steps: AUTO's DSMAX (c.ghenon, run_ghenon.py), so that
 * both compute about as many points. */
static const double HMAX_BRANCH = 0.08, HMAX_CURVE = 0.08;

enum { NCURVE = 3, MAXSP = 32 };

typedef struct {
  char label[8];
  double alpha, beta, residual;
} special_t;

typedef struct {
  long branch_points;
  sc_branchn_special sp[3];  /* LP, NS, PD of the branch */
  double sp_x[3][2];
  int found[3];
  long points[NCURVE];
  double worst[NCURVE];      /* max |alpha - closed form(beta)| */
  special_t special[NCURVE][MAXSP];
  int nspecial[NCURVE];
  int status[NCURVE];
  int curve;                 /* the one being traced */
} result_t;

static double alpha_fold(double b) { return (1 + b) * (1 + b) / (4 * (R - 1)); }
static double alpha_flip(double b) { return (3 - R) * (1 + b) * (1 + b) / 4; }
static double alpha_ns(double b) {
  double s = (b - 1) / R;
  return (1 - R) * s * s + (1 + b) * s;
}
static double (*const CLOSED[NCURVE])(double) = {alpha_fold, alpha_flip,
                                                 alpha_ns};

static int on_point(void *ctx, const sc_curven_point *p) {
  result_t *r = ctx;
  int c = r->curve;
  r->points[c]++;
  r->worst[c] = fmax(r->worst[c], fabs(p->x - CLOSED[c](p->y)));
  return 0;
}

static int on_special(void *ctx, const sc_curven_special *s) {
  result_t *r = ctx;
  int c = r->curve;
  if (!strcmp(s->label, "EP") || r->nspecial[c] >= MAXSP) return 0;
  special_t *o = &r->special[c][r->nspecial[c]++];
  snprintf(o->label, sizeof o->label, "%s", s->label);
  o->alpha = s->x, o->beta = s->y, o->residual = s->residual;
  return 0;
}

/* The branch; its LP, NS, PD into r.  Returns the branch's status. */
static int branch(sc_map *m, result_t *r) {
  double s = (-(1 + BETA0) - sqrt((1 + BETA0) * (1 + BETA0) +
                                  4 * (1 - R) * FROM)) / (2 * (1 - R));
  double x0[2] = {s, s};
  sc_branchn_spec sp = {.param = 0, .from = FROM, .to = TO, .period = 1,
                        .x0 = x0, .max_points = 5000, .max_branches = 1,
                        .max_period = 1, .hmax = HMAX_BRANCH};
  sc_branchn *b;
  sc_msg msg;
  int st = sc_branchn_alloc(m, &sp, &b, &msg);
  if (st == SC_OK) st = sc_branchn_run(b, &msg);
  if (st != SC_OK) {
    fprintf(stderr, "ghenon_bench: branch: %s\n", msg.text);
    sc_branchn_free(b);
    return st;
  }
  r->branch_points = (long)sc_branchn_npoints(b);
  static const sc_branchn_label want[3] = {SC_PTN_LP, SC_PTN_NS, SC_PTN_PD};
  for (size_t i = 0; i < sc_branchn_nspecial(b); i++) {
    sc_branchn_special q;
    sc_branchn_special_get(b, i, &q);
    for (int k = 0; k < 3; k++)
      if (q.label == want[k] && !r->found[k]) {
        r->sp[k] = q, r->found[k] = 1;
        r->sp_x[k][0] = q.x[0], r->sp_x[k][1] = q.x[1];
        r->sp[k].x = r->sp_x[k];
        r->sp[k].re = r->sp[k].im = NULL;
      }
  }
  sc_branchn_free(b);
  return SC_OK;
}

static double compute(result_t *r) {
  static const sc_curve_type type[NCURVE] = {SC_CURVE_FOLD, SC_CURVE_FLIP,
                                             SC_CURVE_NS};
  memset(r, 0, sizeof *r);
  double t0 = bench_wall();
  sc_map *m;
  if (sc_map_alloc("ghenon", NULL, &m, NULL) != SC_OK) exit(1);
  sc_map_set_param(m, 1, BETA0, NULL);
  sc_map_set_param(m, 2, R, NULL);
  if (branch(m, r) != SC_OK) exit(1);
  for (int c = 0; c < NCURVE; c++) {
    if (!r->found[c]) {
      fprintf(stderr, "ghenon_bench: no %s on the branch\n", c == 0 ? "LP"
              : c == 1 ? "NS" : "PD");
      exit(1);
    }
    /* the curves in the order fold, flip, NS; the branch's LP, NS, PD */
    int k = c == 0 ? 0 : c == 1 ? 2 : 1;
    sc_curve_settings set;
    sc_curve_settings_default(&set);
    set.type = type[c];
    set.ix = 0, set.iy = 1;
    set.xlo = ALO, set.xhi = AHI, set.ylo = BLO, set.yhi = BHI;
    set.hmax = HMAX_CURVE, set.h0 = HMAX_CURVE / 10;
    sc_map_set_param(m, 0, r->sp[k].p, NULL);
    sc_map_set_param(m, 1, BETA0, NULL);
    r->curve = c;
    sc_curven_output out = {on_point, on_special, r};
    sc_curve_stats st;
    sc_msg msg;
    r->status[c] = sc_curven_trace(m, &set, r->sp[k].x,
                                   c == 2 ? r->sp[k].kappa : NAN, &out, &st,
                                   &msg);
    if (r->status[c] != SC_OK) {
      fprintf(stderr, "ghenon_bench: curve %d: %s\n", c, msg.text);
      exit(1);
    }
  }
  sc_map_free(m);
  return bench_wall() - t0;
}

static void print(const result_t *r, const char *timekey, double t) {
  static const char *bname[3] = {"LP", "NS", "PD"};
  double exact[3] = {alpha_fold(BETA0), alpha_ns(BETA0), alpha_flip(BETA0)};
  static const char *cname[NCURVE] = {"fold", "flip", "NS"};
  printf("branch_points %ld\n", r->branch_points);
  for (int k = 0; k < 3; k++) {
    const sc_branchn_special *q = &r->sp[k];
    printf("branch %s %.17g err %.3g residual %.3g coef %.6g\n", bname[k],
           q->p, fabs(q->p - exact[k]), q->residual, q->coef);
  }
  for (int c = 0; c < NCURVE; c++) {
    printf("curve %s points %ld worst %.3g\n", cname[c], r->points[c],
           r->worst[c]);
    for (int i = 0; i < r->nspecial[c]; i++) {
      const special_t *s = &r->special[c][i];
      printf("special %s %s %.17g %.17g residual %.3g\n", cname[c], s->label,
             s->alpha, s->beta, s->residual);
    }
  }
  printf("%s %.6g\n", timekey, t);
}

int main(int argc, char **argv) {
  static result_t r;
  if (argc == 2 && !strcmp(argv[1], "once")) {
    double t = compute(&r);
    print(&r, "time", t);
    return 0;
  }
  long n = argc == 3 && !strcmp(argv[1], "repeat") ? strtol(argv[2], NULL, 10) : 0;
  if (n < 1 || n > 100000) {
    fprintf(stderr, "usage: ghenon_bench once | ghenon_bench repeat N (1..100000)\n");
    return 2;
  }
  double *t = malloc((size_t)n * sizeof *t);
  if (!t) return 1;
  for (long i = 0; i < n; i++) t[i] = compute(&r);
  print(&r, "median", bench_median(t, (int)n));
  free(t);
  return 0;
}
