/* Task `orbit`: iterate the map from d0 and, for models with continuous
 * motion (bk2), follow the motion itself (fig 5.4). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/tasks.h"
#include "slipcont/analysis.h"
#include "slipcont/linalg.h"
#include "slipcont/period.h"

static const sc_key_info orbit_keys[] = {
    {"d0", SC_KEY_STATE, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "initial state (bk2: d = Y2 - Y1 of the first global stick phase)"},
    {"iterations", SC_KEY_INT, 0, "300", 1, 10000000, 0, 0, NULL,
     "map iterates (as the sweep task's iterations)"},
    {"trajectory", SC_KEY_BOOL, 0, "no", 0, 0, 0, 0, NULL,
     "also write the continuous motion (models with one: bk2, chain)"},
    {"trajectory-iterates", SC_KEY_INT, 0, "0", 0, 10000000, 0, 0, NULL,
     "the trajectory follows the last this many iterates (0: all)"},
    {"dtau", SC_KEY_REAL, 0, "0.01", 0, 1000, 1, 0, NULL,
     "trajectory sampling step in dimensionless time (events are added)"},
};

/* Most rows of trajectory.csv (about 100 bytes each: 500 MB). */
#define TRAJ_MAX_ROWS 5000000L

/* Rows the trajectory will have at least: each iterate has a slip, and a
 * block that slips alone comes back to the driver's speed after about
 * half its period pi / sqrt(1 + alpha) (docs/model.md); so many samples
 * of dtau, whatever the stick phases add. */
static double traj_rows_estimate(const sc_scene *s) {
  const sc_map *m = sc_scene_map(s);
  long it = sc_scene_int(s, "trajectory-iterates");
  if (it == 0) it = sc_scene_int(s, "iterations");
  int ia = sc_map_param_index(m, "alpha");
  double alpha = ia >= 0 ? sc_map_get_param(m, (size_t)ia) : 0;
  const double pi = 3.14159265358979323846;
  return (double)it * (pi / sqrt(1 + alpha)) / sc_scene_real(s, "dtau");
}

/* Iterates summarised at the end: enough for a period up to 16 to repeat
 * several times. */
#define ORBIT_TAIL 128

static int orbit_check(const sc_scene *s, sc_msg *msg) {
  const sc_map *m = sc_scene_map(s);
  if (sc_scene_flag(s, "trajectory") && !sc_map_type(m)->trajectory &&
      !sc_map_type(m)->trajectory_n)
    return sc_scene_fail_key(s, "task", "trajectory", msg,
                             "trajectory = yes: model %s has no continuous "
                             "motion (valid: no)",
                             sc_map_type(m)->name);
  if (sc_scene_int(s, "trajectory-iterates") > sc_scene_int(s, "iterations"))
    return sc_scene_fail_key(s, "task", "trajectory-iterates", msg,
                             "trajectory-iterates = %ld is more than "
                             "iterations = %ld (valid: [0, iterations])",
                             sc_scene_int(s, "trajectory-iterates"),
                             sc_scene_int(s, "iterations"));
  if (sc_scene_flag(s, "trajectory")) {
    double rows = traj_rows_estimate(s);
    if (!(rows <= (double)TRAJ_MAX_ROWS))
      return sc_scene_fail_key(s, "task", "dtau", msg,
                               "dtau = %s: the trajectory would have at least "
                               "%.3g rows (limit %ld, about 500 MB): raise dtau "
                               "or lower trajectory-iterates",
                               sc_scene_text(s, "dtau"), rows, TRAJ_MAX_ROWS);
  }
  return SC_OK;
}

typedef struct {
  FILE *f;
  long rows;
  double y1lo, y1hi, y2lo, y2hi;
  int blocks; /* the number of blocks N (2 N values a sample) */
} traj_ctx;

/* A sample of the motion: tau, N positions, N velocities, the number of
 * blocks slipping; the extent of (Y1, Y2) for the phase plot. */
static int on_sample(void *ctx, double tau, const double *x, int mode) {
  traj_ctx *c = ctx;
  sc_csv_double(c->f, tau);
  for (int i = 0; i < 2 * c->blocks; i++) {
    fputc(',', c->f);
    sc_csv_double(c->f, x[i]);
  }
  fprintf(c->f, ",%d\n", mode);
  c->y1lo = fmin(c->y1lo, x[0]);
  c->y1hi = fmax(c->y1hi, x[0]);
  c->y2lo = fmin(c->y2lo, x[1]);
  c->y2hi = fmax(c->y2hi, x[1]);
  c->rows++;
  return ferror(c->f) || sc_cli_interrupted() || c->rows > TRAJ_MAX_ROWS ? 1
                                                                         : 0;
}

static double param(const sc_map *m, const char *name, double dflt) {
  int i = sc_map_param_index(m, name);
  return i < 0 ? dflt : sc_map_get_param(m, (size_t)i);
}

/* The stuck block's velocity during slips (docs/model.md: V with the driver
 * moving, 0 with it frozen). */
static double stuck_velocity(const sc_map *m) {
  const char *drv = sc_map_get_option(m, "driver");
  return drv && strcmp(drv, "frozen") == 0 ? 0 : param(m, "v", 0);
}

/* One orbit run: the iterates, the tail of their multipliers and
 * itineraries (a ring), where the map failed, the trajectory's extent. */
typedef struct {
  long n;        /* iterations */
  size_t dim;    /* state components (the map's n); > 1: d holds states */
  double *d;     /* d[0..n] (states d[k dim ..]); d[0..k] are defined */
  long k;        /* iterates done */
  double dfdd[ORBIT_TAIL];
  int neutral[ORBIT_TAIL];
  char (*itin)[SC_ITIN_LEN];
  int fail;      /* the map's status at iterate k (SC_OK: all defined) */
  sc_msg em;     /* and its message */
  traj_ctx traj; /* rows and bounds of trajectory.csv */
} orbit_job;

static int orbit_prepare(sc_cli_run *r, void *job) {
  orbit_job *j = job;
  j->n = sc_scene_int(r->scene, "iterations");
  j->dim = sc_map_dim(r->map);
  j->d = malloc((size_t)(j->n + 1) * j->dim * sizeof *j->d);
  j->itin = calloc(ORBIT_TAIL, sizeof *j->itin);
  if (!j->d || !j->itin)
    return sc_fail(r->msg, SC_ENOMEM, "orbit: out of memory");
  if (j->dim > 1) sc_scene_state(r->scene, "d0", j->d, j->dim);
  else j->d[0] = sc_scene_real(r->scene, "d0");
  return SC_OK;
}

/* The iterates of a map of n > 1 components into orbit.csv (k, the
 * components, itinerary), up to the first where the map fails. */
static int orbit_iterate_n(sc_cli_run *r, orbit_job *j) {
  const size_t n = j->dim;
  sc_mapn_value *v = NULL;
  int st = sc_mapn_value_alloc(r->map, SC_EVAL_VALUE, &v, r->msg);
  sc_file *csv = NULL;
  if (!st) st = sc_cli_open(r, "orbit.csv", &csv);
  if (st) {
    sc_mapn_value_free(v);
    return st;
  }
  FILE *f = sc_file_stream(csv);
  fputs("k,", f);
  sc_csv_state_header(f, r->map, "");
  fputs(",itinerary\n", f);
  for (j->k = 0; j->k < j->n; j->k++) {
    long k = j->k;
    const double *x = j->d + (size_t)k * n;
    if ((st = sc_cli_stop(r))) break;
    j->fail = sc_map_eval_n(r->map, x, SC_EVAL_ITINERARY, v, &j->em);
    fprintf(f, "%ld,", k);
    sc_csv_state(f, x, n);
    if (j->fail) {
      fputs(",undefined\n", f);
      break;
    }
    fprintf(f, ",%s\n", sc_cli_csv_text(v->itinerary));
    memcpy(j->d + (size_t)(k + 1) * n, v->f, n * sizeof *v->f);
  }
  sc_mapn_value_free(v);
  if (st) return st;
  if (!j->fail) {
    fprintf(f, "%ld,", j->n);
    sc_csv_state(f, j->d + (size_t)j->n * n, n);
    fputs(",\n", f);
  }
  return sc_cli_commit(r, "orbit.csv", csv);
}

/* The iterates into orbit.csv, up to the first where the map fails. */
static int orbit_iterate(sc_cli_run *r, orbit_job *j) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "orbit.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("k,d,itinerary\n", f);
  sc_map_value v;
  double *d = j->d;
  for (j->k = 0; j->k < j->n; j->k++) {
    long k = j->k;
    if ((st = sc_cli_stop(r))) return st;
    j->fail = sc_map_eval(r->map, d[k], SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v,
                          &j->em);
    if (j->fail == SC_ENONFINITE) {
      /* f' does not exist here (an event with zero slope, or d* with the
       * driver frozen): the iterate does; the multiplier is then unknown */
      j->fail = sc_map_eval(r->map, d[k], SC_EVAL_ITINERARY, &v, &j->em);
      v.dfdd = NAN;
    }
    fprintf(f, "%ld,", k);
    sc_csv_double(f, d[k]);
    if (j->fail) {
      fputs(",undefined\n", f);
      break;
    }
    fprintf(f, ",%s\n", sc_cli_csv_text(v.itinerary));
    size_t slot = (size_t)k % ORBIT_TAIL;
    j->dfdd[slot] = v.dfdd;
    j->neutral[slot] = v.neutral;
    memcpy(j->itin[slot], v.itinerary, SC_ITIN_LEN);
    d[k + 1] = v.f;
  }
  if (!j->fail) {
    fprintf(f, "%ld,", j->n);
    sc_csv_double(f, d[j->n]);
    fputs(",\n", f);
  }
  return sc_cli_commit(r, "orbit.csv", csv);
}

/* The continuous motion over the last trajectory-iterates iterates into
 * trajectory.csv: Y and U of each of the N blocks (bk2 through
 * sc_map_trajectory() from d, N = 2; a model of N = n + 1 blocks, the
 * chain, through sc_map_trajectory_n() from its state). */
static int orbit_trajectory(sc_cli_run *r, orbit_job *j) {
  const sc_scene *s = r->scene;
  long mt = sc_scene_int(s, "trajectory-iterates");
  if (mt == 0) mt = j->n;
  int scalar = sc_map_type(r->map)->trajectory != NULL;
  traj_ctx *c = &j->traj;
  *c = (traj_ctx){NULL, 0, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL,
                  scalar ? 2 : (int)j->dim + 1};
  sc_file *tr = NULL;
  int st = sc_cli_open(r, "trajectory.csv", &tr);
  if (st) return st;
  c->f = sc_file_stream(tr);
  fputs("tau", c->f);
  for (int k = 0; k < 2; k++)
    for (int i = 1; i <= c->blocks; i++) fprintf(c->f, ",%c%d", "yu"[k], i);
  fputs(",mode\n", c->f);
  sc_msg em;
  double dtau = sc_scene_real(s, "dtau");
  const double *from = j->d + (size_t)(j->n - mt) * j->dim;
  st = scalar ? sc_map_trajectory(r->map, *from, (int)mt, dtau, on_sample, c,
                                  &em)
              : sc_map_trajectory_n(r->map, from, (int)mt, dtau, on_sample, c,
                                    &em);
  if (!st) return sc_cli_commit(r, "trajectory.csv", tr);
  if (sc_cli_interrupted()) return sc_cli_stop(r);
  if (c->rows > TRAJ_MAX_ROWS)
    return sc_fail(r->msg, SC_EINVAL,
                   "trajectory longer than %ld rows%s: raise dtau or lower "
                   "trajectory-iterates",
                   TRAJ_MAX_ROWS,
                   scalar ? " (long stick phases: V is small)" : "");
  if (scalar)
    return sc_fail(r->msg, st, "trajectory from d = %.17g: %s", *from,
                   em.text);
  return sc_fail(r->msg, st, "trajectory from iterate %ld: %s", j->n - mt,
                 em.text);
}

static int orbit_compute(sc_cli_run *r, void *job) {
  orbit_job *j = job;
  if (j->dim > 1) {
    int st = orbit_iterate_n(r, j);
    if (!st && !j->fail && sc_scene_flag(r->scene, "trajectory"))
      st = orbit_trajectory(r, j);
    return st;
  }
  int st = orbit_iterate(r, j);
  if (!st && !j->fail && sc_scene_flag(r->scene, "trajectory"))
    st = orbit_trajectory(r, j);
  return st;
}

/* The period of the @p nt states x[0..nt-1] of n components: period.h's
 * rule on states (sc_periodn) with one confirmation cycle, as
 * sc_sweep_period() does for one component; states at rest to rtol of
 * their size are period 1.  0: none up to SC_SWEEP_PERIOD_MAX; -1: no
 * detector. */
static int tail_period_n(const double *x, size_t nt, size_t n, double rtol) {
  double ext = 0, amax = 0;
  for (size_t i = 0; i < n; i++) {
    double lo = x[i], hi = x[i];
    for (size_t k = 0; k < nt; k++) {
      lo = fmin(lo, x[k * n + i]);
      hi = fmax(hi, x[k * n + i]);
      amax = fmax(amax, fabs(x[k * n + i]));
    }
    ext = fmax(ext, hi - lo);
  }
  if (ext <= rtol * amax + SC_PERIOD_FLOOR_ULPS * DBL_EPSILON * amax) return 1;
  int pm = SC_SWEEP_PERIOD_MAX < (int)(nt / 2) ? SC_SWEEP_PERIOD_MAX
                                                : (int)(nt / 2);
  if (pm < 1) return 0;
  sc_periodn *pd;
  if (sc_periodn_alloc(n, pm, 1, rtol, &pd, NULL)) return -1;
  sc_periodn_reset(pd, x);
  int p = 0;
  for (size_t k = 1; k < nt && !p; k++) p = sc_periodn_push(pd, x + k * n);
  sc_periodn_free(pd);
  return p;
}

/* The multipliers of the period-p orbit through the states pts[0..p-1]:
 * the eigenvalues of the product of the p Jacobians (sc_product_eigs(),
 * without forming the product), by decreasing modulus, into re, im. */
static int orbit_multipliers(sc_map *m, const double *pts, int p, size_t n,
                             double *re, double *im, sc_msg *msg) {
  sc_mapn_value *v = NULL;
  double *J = malloc((size_t)p * n * n * sizeof *J);
  const double **A = malloc((size_t)p * sizeof *A);
  int st = J && A ? sc_mapn_value_alloc(m, SC_EVAL_DERIV, &v, msg)
                  : sc_fail(msg, SC_ENOMEM, "orbit: out of memory");
  for (int k = 0; k < p && !st; k++) {
    st = sc_map_eval_n(m, pts + (size_t)k * n, SC_EVAL_DERIV, v, msg);
    if (!st) memcpy(J + (size_t)k * n * n, v->J, n * n * sizeof *J);
    A[k] = J + (size_t)k * n * n;
  }
  if (!st) st = sc_product_eigs(n, (size_t)p, A, re, im, msg);
  sc_mapn_value_free(v);
  free(J);
  free(A);
  return st;
}

/* Points of the tail the invariant-circle test looks at, at most. */
#define ORBIT_CIRCLE_TAIL SC_CIRCLE_POINTS

/* Findings of a map of n > 1 components: the period of the tail and, for
 * a periodic orbit, its points and multipliers; with no period, whether
 * the tail lies on an invariant circle. */
static void orbit_summary_n(sc_cli_run *r, const orbit_job *j, FILE *f) {
  const size_t n = j->dim;
  const double *d = j->d;
  long last = j->k;
  long nt = (last + 1) / 2 < ORBIT_TAIL ? (last + 1) / 2 : ORBIT_TAIL;
  if (nt < 1) nt = 1;
  const double *tail = d + (size_t)(last + 1 - nt) * n;
  double rtol = sc_map_accuracy(r->map)->period_rtol;
  int p = tail_period_n(tail, (size_t)nt, n, rtol);
  fputs("  final state: ", f);
  sc_csv_points(f, d + (size_t)last * n, 1, n);
  fprintf(f, " after %ld iterates\n", last);
  if (p > 0) {
    double re[SC_MAXDIM], im[SC_MAXDIM];
    sc_msg em;
    fprintf(f, "  period of the last %ld iterates: %d\n", nt, p);
    for (long k = last - p; k < last; k++) {
      fputs("    ", f);
      sc_csv_points(f, d + (size_t)k * n, 1, n);
      fputc('\n', f);
    }
    if (orbit_multipliers(r->map, d + (size_t)(last - p) * n, p, n, re, im,
                          &em)) {
      fprintf(f, "  multipliers: not computed (%s)\n", sc_cli_user_text(em.text));
      return;
    }
    fprintf(f, "  multipliers (eigenvalues of the product of the %d "
               "Jacobians, by decreasing modulus): ", p);
    sc_csv_multipliers(f, re, im, n);
    fprintf(f, " (%s)\n", hypot(re[0], im[0]) < 1 ? "stable" : "unstable");
    return;
  }
  long nc = (last + 1) / 2 < ORBIT_CIRCLE_TAIL ? (last + 1) / 2
                                               : ORBIT_CIRCLE_TAIL;
  double *work = malloc(3 * (size_t)nc * sizeof *work), ratio = NAN;
  int circle = work && sc_orbit_on_circle(d + (size_t)(last + 1 - nc) * n,
                                          (size_t)nc, n, rtol, work, &ratio);
  free(work);
  if (circle)
    fprintf(f, "  no period up to %d; the last %ld iterates lie on a closed "
               "curve that the map turns in order: an invariant circle "
               "(quasi-periodic)\n",
            SC_SWEEP_PERIOD_MAX, nc);
  else
    fprintf(f, "  no period up to %d found in the last %ld iterates (chaos, "
               "a longer period, or a transient)\n",
            SC_SWEEP_PERIOD_MAX, nt);
}

/* Findings: the period of the tail and, for a periodic orbit, its
 * points, itineraries and multiplier (product of f' over one period). */
static int orbit_summary(sc_cli_run *r, void *job, FILE *f) {
  const orbit_job *j = job;
  if (j->dim > 1) {
    if (j->fail) {
      fprintf(f, "  the map is undefined at iterate %ld (", j->k);
      sc_csv_points(f, j->d + (size_t)j->k * j->dim, 1, j->dim);
      fprintf(f, "): %s\n", j->em.text);
    } else {
      orbit_summary_n(r, j, f);
    }
    fprintf(f, "  map evaluations: %lu\n", sc_map_nevals(r->map));
    return SC_OK;
  }
  const double *d = j->d;
  long n = j->n, last = j->k; /* d[0..last] are defined */
  if (j->fail) {
    fprintf(f, "  the map is undefined at iterate %ld (d = %.17g): %s\n",
            last, d[last], j->em.text);
  } else {
    /* The second half of the orbit at most: the first is transient. */
    long nt = (last + 1) / 2 < ORBIT_TAIL ? (last + 1) / 2 : ORBIT_TAIL;
    if (nt < 1) nt = 1;
    int p = sc_sweep_period(d + last + 1 - nt, (size_t)nt,
                            sc_map_accuracy(r->map)->period_rtol,
                            SC_SWEEP_PERIOD_MAX);
    fprintf(f, "  final state after %ld iterates: %.17g\n", n, d[n]);
    if (p > 0) {
      double mult = 1;
      int neut = 1;
      fprintf(f, "  period of the last %ld iterates: %d\n", nt, p);
      for (long k = n - p; k < n; k++) {
        size_t slot = (size_t)k % ORBIT_TAIL;
        mult *= j->dfdd[slot];
        neut = neut && j->neutral[slot];
        fprintf(f, "    d = %.17g  itinerary %s  f' = %.17g\n", d[k],
                j->itin[slot], j->dfdd[slot]);
      }
      fprintf(f, "  multiplier (product of f' over one period): %.17g%s\n",
              neut ? 1.0 : mult,
              neut ? " (neutral: single-block slips only)"
                   : fabs(mult) < 1 ? " (stable)" : " (unstable)");
    } else {
      fprintf(f, "  no period up to %d found in the last %ld iterates "
                 "(chaos, a longer period, or a transient)\n",
              SC_SWEEP_PERIOD_MAX, nt);
    }
  }
  fprintf(f, "  map evaluations: %lu\n", sc_map_nevals(r->map));
  return SC_OK;
}

/* Motion in the plane (Y1, Y2) over the global stick region. */
static int phase_plot(sc_cli_run *r, const traj_ctx *c, const char *title) {
  sc_map *m = r->map;
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "phase", title, "Y_1", "Y_2", &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  double a = param(m, "alpha", 1), b = param(m, "beta", 1);
  double dx = fmax(c->y1hi - c->y1lo, c->y2hi - c->y2lo);
  dx = dx > 0 ? 0.08 * dx : 0.1;
  fprintf(f, "set xrange [%.17g:%.17g]\nset yrange [%.17g:%.17g]\n",
          c->y1lo - dx, c->y1hi + dx, c->y2lo - dx, c->y2hi + dx);
  fputs("set size ratio -1\nset key outside right top\n", f);
  fprintf(f, "alpha = %.17g\nbeta = %.17g\n", a, b);
  fputs("# The global stick region: S1 = (1+alpha) Y1 - alpha Y2 <= 1 and\n"
        "# S2 = (1+alpha) Y2 - alpha Y1 <= beta, i.e. s1(Y1) <= Y2 <= s2(Y1)\n"
        "s1(x) = ((1 + alpha)*x - 1)/alpha\n"
        "s2(x) = (beta + alpha*x)/(1 + alpha)\n"
        "top(x) = s2(x) > s1(x) ? s2(x) : s1(x)\n"
        "# column 6 is the mode: 0 STICK, 1 SLIP1, 2 SLIP2, 3 SLIP12\n"
        "mode(m, c) = column(6) == m ? column(c) : NaN\n"
        "set samples 400\n",
        f);
  fputs("plot '+' using 1:(s1($1)):(top($1)) with filledcurves "
        "fc rgb '#e8e8e8' title 'global stick region', \\\n"
        "     s1(x) with lines lc rgb '#666666' dt 2 title 'S_1 = 1', \\\n"
        "     s2(x) with lines lc rgb '#666666' dt 4 title 'S_2 = beta', \\\n"
        "     'trajectory.csv' skip 1 using (mode(0,2)):(mode(0,3)) with "
        "points pt 7 ps 0.35 lc rgb '#444444' notitle, \\\n"
        "     '' skip 1 using (mode(1,2)):(mode(1,3)) with points pt 7 "
        "ps 0.35 lc rgb '#d62728' notitle, \\\n"
        "     '' skip 1 using (mode(2,2)):(mode(2,3)) with points pt 7 "
        "ps 0.35 lc rgb '#1f4e9e' notitle, \\\n"
        "     '' skip 1 using (mode(3,2)):(mode(3,3)) with points pt 7 "
        "ps 0.35 lc rgb '#2ca02c' notitle, \\\n"
        "     keyentry with points pt 7 ps 1.5 lc rgb '#444444' "
        "title 'stick (GSP)', \\\n"
        "     keyentry with points pt 7 ps 1.5 lc rgb '#d62728' "
        "title 'block 1 slips', \\\n"
        "     keyentry with points pt 7 ps 1.5 lc rgb '#1f4e9e' "
        "title 'block 2 slips', \\\n"
        "     keyentry with points pt 7 ps 1.5 lc rgb '#2ca02c' "
        "title 'both slip'\n",
        f);
  return sc_cli_plot_end(r, "phase", gp);
}

/* The blocks' velocities relative to a stuck block's. */
static int velocity_plot(sc_cli_run *r, const char *title) {
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "velocity", title, "tau", "U_i - V_s", &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fputs("# V_s: velocity of a stuck block during a slip (V with the "
        "driver moving, 0 frozen);\n# in a global stick phase both blocks "
        "move with V.\n",
        f);
  fprintf(f, "Vs = %.17g\n", stuck_velocity(r->map));
  fputs("plot 'trajectory.csv' skip 1 using 1:($4 - Vs) with lines lw 1.5 "
        "lc rgb '#d62728' title 'U_1 - V_s', \\\n"
        "     '' skip 1 using 1:($5 - Vs) with lines lw 1.5 lc rgb '#1f4e9e' "
        "title 'U_2 - V_s'\n",
        f);
  return sc_cli_plot_end(r, "velocity", gp);
}

/* The blocks' slip history of a model of N blocks: each block's row in
 * time, coloured by its slip velocity V_s - U_i (0 when stuck). */
static int spacetime_plot(sc_cli_run *r, const traj_ctx *c,
                          const char *title) {
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "spacetime", title, "tau", "block", &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fputs("# column 1 + i: Y_i, column 1 + N + i: U_i; slip velocity V_s - "
        "U_i\n",
        f);
  fprintf(f, "N = %d\nVs = %.17g\n", c->blocks, stuck_velocity(r->map));
  fprintf(f, "set yrange [0.5:%d.5]\nset cblabel 'slip velocity V_s - "
             "U_i'\nset palette defined (0 '#f4f4f4', 1 '#fdae61', 2 "
             "'#d7191c', 3 '#2b0000')\nset cbrange [0:*]\n",
          c->blocks);
  fputs("plot for [i=1:N] 'trajectory.csv' skip 1 using 1:(i):(Vs - "
        "column(1 + N + i)) with points pt 5 ps 0.5 lc palette notitle\n",
        f);
  return sc_cli_plot_end(r, "spacetime", gp);
}

/* A map of n > 1 components: every component against k, and for n = 2
 * the phase plane (the second component against the first). */
static int orbit_plots_n(sc_cli_run *r, const orbit_job *j,
                         const char *title) {
  static const char *const rgb[] = {"#1f4e9e", "#d62728", "#2ca02c",
                                    "#9467bd", "#ff7f0e", "#17becf"};
  sc_map *m = r->map;
  char c0[32], c1[32];
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "orbit", title, "k (iterate)", "state", &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fputs("plot ", f);
  for (size_t i = 0; i < j->dim; i++) {
    fprintf(f, "%s'orbit.csv' skip 1 using 1:%zu with linespoints pt 7 "
               "ps 0.5 lw 0.5 lc rgb '%s' title ",
            i ? ", \\\n     " : "", i + 2, rgb[i % 6]);
    sc_plot_quote(f, sc_map_state_component(m, i, c0, sizeof c0));
  }
  fputc('\n', f);
  if ((st = sc_cli_plot_end(r, "orbit", gp))) return st;
  if (j->traj.rows && (st = spacetime_plot(r, &j->traj, title))) return st;
  if (j->dim != 2) return st;
  sc_map_state_component(m, 0, c0, sizeof c0);
  sc_map_state_component(m, 1, c1, sizeof c1);
  if ((st = sc_cli_plot_begin(r, "phase", title, c0, c1, &gp))) return st;
  f = sc_file_stream(gp);
  fputs("# the orbit in the plane: the first iterates (the transient) "
        "light, the rest dark\n",
        f);
  fprintf(f, "half = %ld\n", j->k / 2);
  fputs("plot 'orbit.csv' skip 1 using ($1 < half ? $2 : NaN):3 with points "
        "pt 7 ps 0.35 lc rgb '#9ecae1' title 'first half', \\\n"
        "     '' skip 1 using ($1 >= half ? $2 : NaN):3 with points pt 7 "
        "ps 0.5 lc rgb '#1f4e9e' title 'second half'\n",
        f);
  return sc_cli_plot_end(r, "phase", gp);
}

/* The orbit d_k against k; the trajectory's plots when it has rows. */
static int orbit_plots(sc_cli_run *r, void *job) {
  const orbit_job *j = job;
  sc_map *m = r->map;
  char title[512];
  sc_plot_title(m, NULL, title, sizeof title);
  if (j->dim > 1) return orbit_plots_n(r, j, title);
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "orbit", title, "k (iterate)",
                             sc_plot_label(m, sc_map_type(m)->state_name),
                             &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fputs("plot 'orbit.csv' skip 1 using 1:2 with linespoints pt 7 ps 0.6 "
        "lw 0.5 lc rgb '#1f4e9e' title 'orbit'\n",
        f);
  if ((st = sc_cli_plot_end(r, "orbit", gp))) return st;
  if (!j->traj.rows) return SC_OK;
  if (!sc_map_type(m)->trajectory) return spacetime_plot(r, &j->traj, title);
  if ((st = phase_plot(r, &j->traj, title))) return st;
  return velocity_plot(r, title);
}

/* The files are written: an orbit that left the map's domain fails now. */
static int orbit_report(sc_cli_run *r, void *job) {
  const orbit_job *j = job;
  if (!j->fail) return SC_OK;
  if (j->dim > 1)
    return sc_fail(r->msg, j->fail, "orbit: map undefined at iterate %ld "
                                    "from (%.17g, %.17g%s): %s",
                   j->k, j->d[j->k * (long)j->dim], j->d[j->k * (long)j->dim + 1],
                   j->dim > 2 ? ", ..." : "", j->em.text);
  return sc_fail(r->msg, j->fail, "orbit: map undefined at iterate %ld from "
                                  "%.17g: %s",
                 j->k, j->d[j->k], j->em.text);
}

static void orbit_release(sc_cli_run *r, void *job) {
  orbit_job *j = job;
  (void)r;
  free(j->itin);
  free(j->d);
}

const sc_cli_task sc_cli_task_orbit = {
    .type = {.kind = "orbit",
             .doc = "iterate the map from d0; optionally the continuous "
                    "motion (trajectory)",
             .keys = orbit_keys,
             .nkeys = sizeof orbit_keys / sizeof orbit_keys[0],
             .check = orbit_check},
    .outputs = "orbit.csv (k,d,itinerary; n > 1: k,d1..dn,itinerary), "
               "summary.txt, orbit.gp/png, for n = 2 phase.gp/png; with "
               "trajectory = yes also trajectory.csv "
               "(tau,y1,y2,u1,u2,mode), phase.gp/png, velocity.gp/png (bk2), "
               "or (tau,y1..yN,u1..uN,mode), spacetime.gp/png (chain)",
    .job_size = sizeof(orbit_job),
    .prepare = orbit_prepare,
    .compute = orbit_compute,
    .summary = orbit_summary,
    .plots = orbit_plots,
    .report = orbit_report,
    .release = orbit_release,
};
