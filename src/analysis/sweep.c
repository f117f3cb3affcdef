/* One-parameter brute-force sweeps: iterate the map at each value of a
 * parameter grid, keep the tail, detect its period.  All memory is taken
 * in sc_sweep_alloc(); the loop itself only evaluates the map. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "slipcont/analysis.h"
#include "slipcont/period.h"

double sc_grid_point(double from, double to, size_t steps, size_t i) {
  return sc_grid(from, to, steps, i, SC_GRID_LINEAR);
}


int sc_sweep_period(const double *x, size_t n, double rtol, int pmax) {
  if (n == 0) return -1;
  double lo = x[0], hi = x[0], amax = 0;
  for (size_t k = 0; k < n; k++) {
    if (!isfinite(x[k])) return -1;
    lo = fmin(lo, x[k]);
    hi = fmax(hi, x[k]);
    amax = fmax(amax, fabs(x[k]));
  }
  /* A tail at rest to rtol of its size is a fixed point (possibly still
   * converging: seen alone, its small spread would make the detector's
   * tolerance too strict to accept it). */
  if (hi - lo <= rtol * amax + SC_PERIOD_FLOOR_ULPS * DBL_EPSILON * amax)
    return 1;
  if (rtol < DBL_EPSILON) rtol = DBL_EPSILON;
  if (rtol > SC_PERIOD_MAX_RTOL) rtol = SC_PERIOD_MAX_RTOL;
  size_t pm = (size_t)(pmax > 0 ? pmax : 0);
  if (pm > n / 2) pm = n / 2;
  if (pm > SC_PERIOD_MAX) pm = SC_PERIOD_MAX;
  if (pm == 0) return 0;
  sc_period *pd;
  if (sc_period_alloc((int)pm, 1, rtol, &pd, NULL)) return -1;
  sc_period_reset(pd, x[0]);
  int p = 0;
  for (size_t k = 1; k < n && !p; k++) p = sc_period_push(pd, x[k]);
  sc_period_free(pd);
  return p;
}

struct sc_sweep {
  sc_sweep_spec spec;
  size_t npoints;
  int npasses;
  int pass_dir[2];
  sc_map **maps;
  sc_period **pds;      /* per map: the period detector (period.h) */
  size_t dim;           /* state components; n > 1 uses the next ones */
  sc_periodn **pdns;    /* per map: the detector of states */
  sc_mapn_value **vals; /* per map: an evaluation's storage */
  double *x0n;          /* the initial state (dim) */
  double *xs;           /* per map: a state and the next seed (2 dim) */
  int nmaps;
  unsigned long evals0; /* map evaluations of the clones before the run */
  double *d;            /* npoints * keep */
  int *status;          /* npoints */
  int *period;          /* npoints */
  size_t *first_undef;  /* per map: first undefined point seen, or npoints */
  sc_msg *undef_msg;    /* per map: its message */
  size_t nundef;
  char reason[SC_MSG_LEN];
  int stop;             /* a fatal error or a cancel: shared flag */
  int fatal;            /* its status */
  sc_msg fatal_msg;
  size_t done;
};

void sc_sweep_free(sc_sweep *s) {
  if (!s) return;
  for (int i = 0; s->maps && i < s->nmaps; i++) sc_map_free(s->maps[i]);
  for (int i = 0; s->pds && i < s->nmaps; i++) sc_period_free(s->pds[i]);
  for (int i = 0; s->pdns && i < s->nmaps; i++) sc_periodn_free(s->pdns[i]);
  for (int i = 0; s->vals && i < s->nmaps; i++) sc_mapn_value_free(s->vals[i]);
  free(s->maps);
  free(s->pds);
  free(s->pdns);
  free(s->vals);
  free(s->x0n);
  free(s->xs);
  free(s->d);
  free(s->status);
  free(s->period);
  free(s->first_undef);
  free(s->undef_msg);
  free(s);
}

int sc_sweep_alloc(const sc_map *m, const sc_sweep_spec *sp, sc_sweep **out,
                   sc_msg *msg) {
  *out = NULL;
  if (!m || !sp) return sc_fail(msg, SC_EINVAL, "sc_sweep_alloc: NULL argument");
  const sc_model_type *t = sc_map_type(m);
  if (sp->param >= t->nparam)
    return sc_fail(msg, SC_EINVAL,
                   "sc_sweep_alloc: param = %zu (valid: 0 <= param < %zu)",
                   sp->param, t->nparam);
  const sc_param_info *pi = &t->params[sp->param];
  sc_msg m2;
  if (sc_param_check(pi, sp->from, &m2) || sc_param_check(pi, sp->to, &m2))
    return sc_fail(msg, SC_EINVAL, "sc_sweep_alloc: %s", m2.text);
  if (sc_grid_check("sc_sweep_alloc: x-scale", sp->from, sp->to,
                    (sc_grid_scale)sp->x_scale, &m2))
    return sc_fail(msg, SC_EINVAL, "%s", m2.text);
  if (sp->steps < 1)
    return sc_fail(msg, SC_EINVAL, "sc_sweep_alloc: steps = 0 (valid: >= 1)");
  if (sp->iterations < 1 || sp->keep < 1 || sp->keep > sp->iterations)
    return sc_fail(msg, SC_EINVAL,
                   "sc_sweep_alloc: iterations = %d, keep = %d (valid: "
                   "1 <= keep <= iterations)",
                   sp->iterations, sp->keep);
  if (!isfinite(sp->d0))
    return sc_fail(msg, SC_EINVAL, "sc_sweep_alloc: d0 = %g is not finite",
                   sp->d0);
  if (sp->direction < SC_SWEEP_UP || sp->direction > SC_SWEEP_BOTH)
    return sc_fail(msg, SC_EINVAL,
                   "sc_sweep_alloc: direction = %d (valid: 1, 2, 3)",
                   sp->direction);
  if (sp->seed != SC_SEED_FIXED && sp->seed != SC_SEED_PREVIOUS)
    return sc_fail(msg, SC_EINVAL, "sc_sweep_alloc: seed = %d (valid: 0, 1)",
                   sp->seed);
  sc_sweep *s = calloc(1, sizeof *s);
  if (!s) goto nomem;
  s->spec = *sp;
  s->npasses = sp->direction == SC_SWEEP_BOTH ? 2 : 1;
  s->pass_dir[0] = sp->direction == SC_SWEEP_DOWN ? SC_SWEEP_DOWN : SC_SWEEP_UP;
  s->pass_dir[1] = SC_SWEEP_DOWN;
  s->npoints = sp->steps * (size_t)s->npasses;
  s->dim = sc_map_dim(m);
  if (s->npoints / (size_t)s->npasses != sp->steps ||
      s->npoints > ((size_t)-1) / sizeof(double) / (size_t)sp->keep / s->dim)
    goto nomem;
  s->nmaps = 1;
#ifdef _OPENMP
  if (sp->seed == SC_SEED_FIXED) s->nmaps = omp_get_max_threads();
  if (s->nmaps < 1) s->nmaps = 1;
#endif
  s->maps = calloc((size_t)s->nmaps, sizeof *s->maps);
  s->pds = calloc((size_t)s->nmaps, sizeof *s->pds);
  s->first_undef = calloc((size_t)s->nmaps, sizeof *s->first_undef);
  s->undef_msg = calloc((size_t)s->nmaps, sizeof *s->undef_msg);
  s->d = malloc(s->npoints * (size_t)sp->keep * s->dim * sizeof *s->d);
  s->status = calloc(s->npoints, sizeof *s->status);
  s->period = calloc(s->npoints, sizeof *s->period);
  if (!s->maps || !s->pds || !s->first_undef || !s->undef_msg || !s->d ||
      !s->status || !s->period)
    goto nomem;
  if (s->dim > 1) {
    s->pdns = calloc((size_t)s->nmaps, sizeof *s->pdns);
    s->vals = calloc((size_t)s->nmaps, sizeof *s->vals);
    s->x0n = malloc(s->dim * sizeof *s->x0n);
    s->xs = malloc(2 * (size_t)s->nmaps * s->dim * sizeof *s->xs);
    if (!s->pdns || !s->vals || !s->x0n || !s->xs) goto nomem;
    for (size_t k = 0; k < s->dim; k++) {
      s->x0n[k] = sp->x0 ? sp->x0[k] : sp->d0;
      if (!isfinite(s->x0n[k])) {
        sc_sweep_free(s);
        return sc_fail(msg, SC_EINVAL,
                       "sc_sweep_alloc: d0 component %zu = %g is not finite",
                       k + 1, sp->x0 ? sp->x0[k] : sp->d0);
      }
    }
  }
  for (int i = 0; i < s->nmaps; i++) {
    int st = sc_map_clone(m, &s->maps[i], msg);
    if (!st && s->dim == 1)
      st = sc_period_alloc(SC_SWEEP_PERIOD_MAX, SC_PERIOD_DEFAULT_CONFIRM,
                           sc_map_accuracy(m)->period_rtol, &s->pds[i], msg);
    if (!st && s->dim > 1)
      st = sc_periodn_alloc(s->dim, SC_SWEEP_PERIOD_MAX,
                            SC_PERIOD_DEFAULT_CONFIRM,
                            sc_map_accuracy(m)->period_rtol, &s->pdns[i], msg);
    if (!st && s->dim > 1)
      st = sc_mapn_value_alloc(m, SC_EVAL_VALUE, &s->vals[i], msg);
    if (st) {
      sc_sweep_free(s);
      return st;
    }
    s->evals0 += sc_map_nevals(s->maps[i]);
  }
  *out = s;
  return SC_OK;
nomem:
  sc_sweep_free(s);
  return sc_fail(msg, SC_ENOMEM, "sc_sweep_alloc: out of memory (%zu points)",
                 sp->steps);
}

size_t sc_sweep_npoints(const sc_sweep *s) { return s->npoints; }
size_t sc_sweep_nundefined(const sc_sweep *s) { return s->nundef; }
const char *sc_sweep_undefined_reason(const sc_sweep *s) { return s->reason; }

unsigned long sc_sweep_nevals(const sc_sweep *s) {
  unsigned long n = 0;
  for (int i = 0; i < s->nmaps; i++) n += sc_map_nevals(s->maps[i]);
  return n - s->evals0;
}

/* Parameter value of point @p i and the direction of its pass. */
static double point_value(const sc_sweep *s, size_t i, int *dir) {
  const sc_sweep_spec *sp = &s->spec;
  size_t pass = i / sp->steps, j = i % sp->steps;
  *dir = s->pass_dir[pass];
  int ascending_grid = sp->to >= sp->from;
  int want_up = *dir == SC_SWEEP_UP;
  size_t g = ascending_grid == want_up ? j : sp->steps - 1 - j;
  return sc_grid(sp->from, sp->to, sp->steps, g, (sc_grid_scale)sp->x_scale);
}

int sc_sweep_get_point(const sc_sweep *s, size_t i, sc_sweep_point *pt) {
  if (i >= s->npoints) return SC_EINVAL;
  pt->p = point_value(s, i, &pt->direction);
  pt->status = s->status[i];
  pt->period = s->period[i];
  pt->nd = s->status[i] ? 0 : s->spec.keep;
  pt->d = s->status[i] ? NULL : s->d + i * (size_t)s->spec.keep * s->dim;
  pt->dim = s->dim;
  return SC_OK;
}

/* Failures of the map at one parameter value that the sweep records and
 * passes over; every other status stops it. */
static int recoverable(int st) {
  return st == SC_EUNDEF || st == SC_ENOCONV || st == SC_ENONFINITE;
}

/* Compute point @p i on map @p t from @p x0; the final state goes to
 * *xend.  Returns SC_OK, a recoverable status (recorded), or a fatal
 * one. */
static int compute_point(sc_sweep *s, int t, size_t i, double x0,
                         double *xend, sc_msg *msg) {
  const sc_sweep_spec *sp = &s->spec;
  sc_map *m = s->maps[t];
  int dir;
  int st = sc_map_set_param(m, sp->param, point_value(s, i, &dir), msg);
  if (st) return st;
  double *keep = s->d + i * (size_t)sp->keep;
  int first_kept = sp->iterations - sp->keep;
  double x = x0;
  sc_map_value v;
  int k, period = 0;
  /* The one period rule (period.h), over every iterate from x0, as a
   * chart with transient = iterations would classify this point. */
  sc_period_reset(s->pds[t], x0);
  for (k = 0; k < sp->iterations; k++) {
    st = sc_map_eval(m, x, SC_EVAL_VALUE, &v, msg);
    if (st) break;
    x = v.f;
    period = sc_period_push(s->pds[t], x);
    if (k >= first_kept) keep[k - first_kept] = x;
  }
  if (st) {
    s->status[i] = st;
    s->period[i] = SC_SWEEP_UNDEFINED;
    if (!recoverable(st)) return st;
    if (i < s->first_undef[t]) {
      s->first_undef[t] = i;
      sc_fail(&s->undef_msg[t], st, "%s = %.17g, iterate %d from %.17g: %.400s",
              sc_map_type(m)->params[sp->param].name, sc_map_get_param(m, sp->param),
              k + 1, x0, msg->text);
    }
    *xend = NAN;
    return SC_OK;
  }
  s->status[i] = SC_OK;
  if (!period && sc_period_settling(s->pds[t])) period = SC_PERIOD_UNSETTLED;
  s->period[i] = period; /* 0: SC_PERIOD_HIGH */
  *xend = x;
  return SC_OK;
}

/* compute_point() for a map of n > 1 components: from the state @p x0,
 * the final state into @p xend (NaN where the map failed). */
static int compute_point_n(sc_sweep *s, int t, size_t i, const double *x0,
                           double *xend, sc_msg *msg) {
  const sc_sweep_spec *sp = &s->spec;
  const size_t n = s->dim;
  sc_map *m = s->maps[t];
  sc_mapn_value *v = s->vals[t];
  int dir;
  int st = sc_map_set_param(m, sp->param, point_value(s, i, &dir), msg);
  if (st) return st;
  double *keep = s->d + i * (size_t)sp->keep * n;
  int first_kept = sp->iterations - sp->keep;
  const double *x = x0;
  int k, period = 0;
  sc_periodn_reset(s->pdns[t], x0);
  for (k = 0; k < sp->iterations; k++) {
    st = sc_map_eval_n(m, x, SC_EVAL_VALUE, v, msg);
    if (st) break;
    x = v->f;
    period = sc_periodn_push(s->pdns[t], x);
    if (k >= first_kept)
      memcpy(keep + (size_t)(k - first_kept) * n, x, n * sizeof *x);
  }
  if (st) {
    s->status[i] = st;
    s->period[i] = SC_SWEEP_UNDEFINED;
    if (!recoverable(st)) return st;
    if (i < s->first_undef[t]) {
      s->first_undef[t] = i;
      sc_fail(&s->undef_msg[t], st, "%s = %.17g, iterate %d from (%.17g, "
              "...): %.400s",
              sc_map_type(m)->params[sp->param].name,
              sc_map_get_param(m, sp->param), k + 1, x0[0], msg->text);
    }
    for (size_t c = 0; c < n; c++) xend[c] = NAN;
    return SC_OK;
  }
  s->status[i] = SC_OK;
  if (!period && sc_periodn_settling(s->pdns[t])) period = SC_PERIOD_UNSETTLED;
  s->period[i] = period;
  memcpy(xend, x, n * sizeof *x);
  return SC_OK;
}

/* Point @p i on map @p t from the state @p x0 (dim values; the map's
 * own path for n = 1), the final state into @p xend. */
static int compute_any(sc_sweep *s, int t, size_t i, const double *x0,
                       double *xend, sc_msg *msg) {
  if (s->dim > 1) return compute_point_n(s, t, i, x0, xend, msg);
  return compute_point(s, t, i, x0[0], xend, msg);
}

static int report_progress(sc_sweep *s) {
  if (!s->spec.progress) return 0;
  return s->spec.progress(s->spec.progress_ctx, s->done, s->npoints);
}

static int run_previous(sc_sweep *s, sc_msg *msg) {
  const size_t n = s->dim;
  double x1 = s->spec.d0, xe1;
  /* the state and the next seed: scalars for n = 1 */
  double *x = n > 1 ? s->xs : &x1, *xend = n > 1 ? s->xs + n : &xe1;
  const double *x0 = n > 1 ? s->x0n : &s->spec.d0;
  memcpy(x, x0, n * sizeof *x);
  sc_msg m;
  for (size_t i = 0; i < s->npoints; i++) {
    int st = compute_any(s, 0, i, isfinite(x[0]) ? x : x0, xend, &m);
    if (st) {
      int dir;
      return sc_fail(msg, st, "sweep at %s = %.17g: %s",
                     sc_map_type(s->maps[0])->params[s->spec.param].name,
                     point_value(s, i, &dir), m.text);
    }
    memcpy(x, xend, n * sizeof *x);
    s->done = i + 1;
    if (report_progress(s))
      return sc_fail(msg, SC_ECALLBACK, "sweep stopped by its progress callback");
  }
  return SC_OK;
}

static int run_fixed(sc_sweep *s, sc_msg *msg) {
  long n = (long)s->npoints;
#ifdef _OPENMP
#pragma omp parallel num_threads(s->nmaps)
#endif
  {
    int t = 0;
#ifdef _OPENMP
    t = omp_get_thread_num();
#endif
    sc_msg m;
#ifdef _OPENMP
#pragma omp for schedule(dynamic, 1)
#endif
    for (long i = 0; i < n; i++) {
      int stop;
#ifdef _OPENMP
#pragma omp atomic read
#endif
      stop = s->stop;
      if (stop) continue;
      double xe1;
      double *xend = s->dim > 1 ? s->xs + 2 * (size_t)t * s->dim : &xe1;
      int st = compute_any(s, t, (size_t)i, s->dim > 1 ? s->x0n : &s->spec.d0,
                           xend, &m);
#ifdef _OPENMP
#pragma omp critical /* unnamed: no exported lock symbol */
#endif
      {
        if (st && !s->stop) {
          int dir;
#ifdef _OPENMP
#pragma omp atomic write
#endif
          s->stop = 1;
          s->fatal = st;
          sc_fail(&s->fatal_msg, st, "sweep at %s = %.17g: %s",
                  sc_map_type(s->maps[t])->params[s->spec.param].name,
                  point_value(s, (size_t)i, &dir), m.text);
        }
        s->done++;
        if (!s->stop && report_progress(s)) {
#ifdef _OPENMP
#pragma omp atomic write
#endif
          s->stop = 1;
          s->fatal = SC_ECALLBACK;
          sc_fail(&s->fatal_msg, SC_ECALLBACK,
                  "sweep stopped by its progress callback");
        }
      }
    }
  }
  if (s->stop) {
    if (msg) *msg = s->fatal_msg;
    return s->fatal;
  }
  return SC_OK;
}

int sc_sweep_run(sc_sweep *s, sc_msg *msg) {
  s->nundef = 0;
  s->reason[0] = '\0';
  s->stop = 0;
  s->done = 0;
  for (int t = 0; t < s->nmaps; t++) s->first_undef[t] = s->npoints;
  int st = s->spec.seed == SC_SEED_PREVIOUS ? run_previous(s, msg)
                                            : run_fixed(s, msg);
  if (st) return st;
  size_t first = s->npoints;
  for (int t = 0; t < s->nmaps; t++)
    if (s->first_undef[t] < first) {
      first = s->first_undef[t];
      snprintf(s->reason, sizeof s->reason, "%s", s->undef_msg[t].text);
    }
  for (size_t i = 0; i < s->npoints; i++) s->nundef += s->status[i] != SC_OK;
  return SC_OK;
}
