/* Two-parameter period charts: the grid, its checks, and the parallel
 * computation of rows (OpenMP; one map clone and one period detector per
 * thread, taken before the loops). */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <omp.h>
#include <stdint.h>
#include <string.h>

#include "slipcont/chart.h"

void sc_chart_spec_default(sc_chart_spec *s) {
  memset(s, 0, sizeof *s);
  s->transient = 1000;
  s->max_period = SC_PERIOD_DEFAULT_MAX;
  s->confirm = SC_PERIOD_DEFAULT_CONFIRM;
  s->seed = SC_CHART_SEED_FIXED;
  s->d0 = 0;
}

double sc_chart_x(const sc_chart_spec *s, long i) {
  return sc_grid(s->x_from, s->x_to, (size_t)s->x_steps, (size_t)i,
                 (sc_grid_scale)s->x_scale);
}

double sc_chart_y(const sc_chart_spec *s, long j) {
  return sc_grid(s->y_from, s->y_to, (size_t)s->y_steps, (size_t)j,
                 (sc_grid_scale)s->y_scale);
}

/* The name of an axis: a parameter of the model. */
static int check_name(const sc_map *m, const char *key, const char *name,
                      sc_msg *msg) {
  const sc_model_type *t = sc_map_type(m);
  if (!name || !*name)
    return sc_fail(msg, SC_EINVAL, "chart: %s is missing (valid: a parameter "
                   "of model %s)", key, t->name);
  if (sc_map_param_index(m, name) >= 0) return SC_OK;
  char list[256] = "";
  for (size_t k = 0; k < t->nparam; k++) {
    if (k) strncat(list, ", ", sizeof list - strlen(list) - 1);
    strncat(list, t->params[k].name, sizeof list - strlen(list) - 1);
  }
  return sc_fail(msg, SC_EINVAL,
                 "chart: %s = '%s' is not a parameter of model %s (valid: %s)",
                 key, name, t->name, list);
}

/* One axis: steps >= 2, both ends in the parameter's range. */
static int check_axis(const sc_map *m, const char *key, const char *name,
                      double from, double to, long steps, int scale,
                      sc_msg *msg) {
  const sc_model_type *t = sc_map_type(m);
  int i = sc_map_param_index(m, name);
  if (steps < 2)
    return sc_fail(msg, SC_EINVAL,
                   "chart: %s-steps = %ld (valid: >= 2; both ends are grid "
                   "points)",
                   key, steps);
  if (steps > SC_CHART_MAX_POINTS)
    return sc_fail(msg, SC_EINVAL, "chart: %s-steps = %ld (valid: <= %ld)",
                   key, steps, SC_CHART_MAX_POINTS);
  sc_msg sub;
  const double ends[2] = {from, to};
  const char *endname[2] = {"from", "to"};
  for (int e = 0; e < 2; e++)
    if (sc_param_check(&t->params[i], ends[e], &sub))
      return sc_fail(msg, SC_EINVAL, "chart: %s-%s: %s", key, endname[e],
                     sub.text);
  char axis[16];
  snprintf(axis, sizeof axis, "%s-scale", key);
  if (sc_grid_check(axis, from, to, (sc_grid_scale)scale, &sub))
    return sc_fail(msg, SC_EINVAL, "chart: %s", sub.text);
  return SC_OK;
}

int sc_chart_check(const sc_map *m, const sc_chart_spec *s, sc_msg *msg) {
  int st = check_name(m, "x", s->x, msg);
  if (!st) st = check_name(m, "y", s->y, msg);
  if (st) return st;
  if (strcmp(s->x, s->y) == 0)
    return sc_fail(msg, SC_EINVAL,
                   "chart: x and y are both '%s' (valid: two different "
                   "parameters)",
                   s->x);
  st = check_axis(m, "x", s->x, s->x_from, s->x_to, s->x_steps, s->x_scale,
                  msg);
  if (!st)
    st = check_axis(m, "y", s->y, s->y_from, s->y_to, s->y_steps, s->y_scale,
                    msg);
  if (st) return st;
  double npts = (double)s->x_steps * (double)s->y_steps;
  if (npts > (double)SC_CHART_MAX_POINTS)
    return sc_fail(msg, SC_EINVAL,
                   "chart: %ld x %ld = %.0f grid points (valid: at most %ld)",
                   s->x_steps, s->y_steps, npts, SC_CHART_MAX_POINTS);
  double bytes = npts * (double)sizeof(sc_chart_point);
  if (bytes > SC_CHART_MAX_BYTES)
    return sc_fail(msg, SC_EINVAL,
                   "chart: %.0f grid points need %.0f MiB (valid: at most "
                   "%.0f MiB)",
                   npts, bytes / 1048576, SC_CHART_MAX_BYTES / 1048576);
  if (!isfinite(s->d0))
    return sc_fail(msg, SC_EINVAL, "chart: d0 = %g (valid: finite)", s->d0);
  for (size_t k = 0; s->x0 && sc_map_dim(m) > 1 && k < sc_map_dim(m); k++)
    if (!isfinite(s->x0[k]))
      return sc_fail(msg, SC_EINVAL,
                     "chart: d0 component %zu = %g (valid: finite)", k + 1,
                     s->x0[k]);
  if (s->transient < 1 || s->transient > INT32_MAX)
    return sc_fail(msg, SC_EINVAL, "chart: transient = %ld (valid: 1..%ld)",
                   s->transient, (long)INT32_MAX);
  if (s->max_period < 1 || s->max_period > SC_PERIOD_MAX)
    return sc_fail(msg, SC_EINVAL, "chart: max-period = %d (valid: 1..%d)",
                   s->max_period, SC_PERIOD_MAX);
  if (s->confirm < 1 || s->confirm > SC_PERIOD_MAX_CONFIRM)
    return sc_fail(msg, SC_EINVAL, "chart: confirm = %d (valid: 1..%d)",
                   s->confirm, SC_PERIOD_MAX_CONFIRM);
  if (s->seed != SC_CHART_SEED_FIXED && s->seed != SC_CHART_SEED_NEIGHBOUR)
    return sc_fail(msg, SC_EINVAL, "chart: seed = %d (valid: fixed, "
                   "neighbour)", s->seed);
  return SC_OK;
}

/* Per-thread workspace and the state shared by the threads of one call. */
typedef struct {
  const sc_chart_spec *s;
  int ix, iy;                 /* parameter indices */
  long first, stride, nx;
  sc_chart_progress_fn progress;
  void *ctx;
  sc_chart_point *out;
  long done;                  /* points completed (atomic) */
  int stop;                   /* set to cancel (atomic) */
  long err_index;             /* lowest failing point index (-1: a
                                 thread's workspace), LONG_MAX if none */
  int err_status;
  sc_msg err_msg;
} shared_state;

/* Record a failure, keeping the one of lowest point index so that the
 * message does not depend on the thread count. */
static void record_error(shared_state *sh, long index, int status,
                         const sc_msg *msg) {
/* Unnamed: a named critical section is a global lock symbol
 * (.gomp_critical_user_NAME) exported from the shared library. */
#pragma omp critical
  {
    if (index < sh->err_index) {
      sh->err_index = index;
      sh->err_status = status;
      sh->err_msg = *msg;
    }
  }
#pragma omp atomic write
  sh->stop = 1;
}

static int stopped(shared_state *sh) {
  int v;
#pragma omp atomic read
  v = sh->stop;
  return v;
}

/* After a point: count it, and let thread 0 report progress. */
static void point_done(shared_state *sh) {
  long d;
#pragma omp atomic capture
  d = ++sh->done;
  if (sh->progress && omp_get_thread_num() == 0 && sh->progress(sh->ctx, d)) {
#pragma omp atomic write
    sh->stop = 1;
  }
}

/* Set a parameter only when it changes (setup runs on every set). */
static int set_param(sc_map *m, int i, double v, sc_msg *msg) {
  if (sc_map_get_param(m, (size_t)i) == v) return SC_OK;
  return sc_map_set_param(m, (size_t)i, v, msg);
}

/* Point (row k of this call, column i) from state d; writes out[]. */
static int one_point(shared_state *sh, sc_map *m, sc_period *pd, long k,
                     long i, double d, sc_msg *msg) {
  const sc_chart_spec *s = sh->s;
  long row = sh->first + k * sh->stride;
  double x = sc_chart_x(s, i), y = sc_chart_y(s, row);
  int st = set_param(m, sh->iy, y, msg);
  if (!st) st = set_param(m, sh->ix, x, msg);
  sc_period_result res;
  if (!st) st = sc_period_find(pd, m, d, s->transient, &res, msg);
  if (st) {
    sc_msg inner = *msg;
    sc_fail(msg, st, "chart: at %s = %.17g, %s = %.17g: %s", s->x, x, s->y,
            y, inner.text);
    return st;
  }
  sc_chart_point *pt = &sh->out[k * sh->nx + i];
  pt->d = res.d;
  pt->period = res.period;
  pt->iterations = (int32_t)res.iterations;
  return SC_OK;
}

/* A thread's workspace for a map of n > 1 components: the detector, the
 * evaluation, the last SC_CIRCLE_POINTS states (a ring), the circle
 * test's work, the state and a row's seed. */
typedef struct {
  size_t n;
  sc_periodn *pd;
  sc_mapn_value *v;
  double *tail, *chron, *work, *x, *seed;
} nd_work;

static void nd_free(nd_work *w) {
  sc_periodn_free(w->pd);
  sc_mapn_value_free(w->v);
  free(w->tail);
  free(w->chron);
  free(w->work);
  free(w->x);
  free(w->seed);
}

static int nd_alloc(const sc_map *m, const sc_chart_spec *s, double rtol,
                    nd_work *w, sc_msg *msg) {
  memset(w, 0, sizeof *w);
  w->n = sc_map_dim(m);
  int st = sc_periodn_alloc(w->n, s->max_period, s->confirm, rtol, &w->pd,
                            msg);
  if (!st) st = sc_mapn_value_alloc(m, SC_EVAL_VALUE, &w->v, msg);
  if (st) return st;
  w->tail = malloc(SC_CIRCLE_POINTS * w->n * sizeof *w->tail);
  w->chron = malloc(SC_CIRCLE_POINTS * w->n * sizeof *w->chron);
  w->work = malloc(3 * SC_CIRCLE_POINTS * sizeof *w->work);
  w->x = malloc(w->n * sizeof *w->x);
  w->seed = malloc(w->n * sizeof *w->seed);
  if (!w->tail || !w->chron || !w->work || !w->x || !w->seed)
    return sc_fail(msg, SC_ENOMEM, "chart: out of memory");
  return SC_OK;
}

/* The initial state of a chart of an n-dimensional map into @p x. */
static void nd_start(const sc_chart_spec *s, size_t n, double *x) {
  for (size_t k = 0; k < n; k++) x[k] = s->x0 ? s->x0[k] : s->d0;
}

/* The class of the orbit from w->seed (period.h's rule on states, then
 * the invariant-circle test on the last SC_CIRCLE_POINTS states, when the
 * transient made so many); the final state stays in w->seed. */
static int nd_classify(nd_work *w, sc_map *m, long transient,
                       sc_chart_point *pt, sc_msg *msg) {
  const size_t n = w->n;
  double *x = w->x;
  memcpy(x, w->seed, n * sizeof *x);
  memcpy(w->tail, x, n * sizeof *x);
  sc_periodn_reset(w->pd, x);
  int period = 0;
  long k;
  for (k = 1; k <= transient && !period; k++) {
    int st = sc_map_eval_n(m, x, SC_EVAL_VALUE, w->v, msg);
    if (st == SC_EUNDEF || st == SC_ENONFINITE) {
      pt->period = SC_PERIOD_UNDEFINED;
      pt->iterations = (int32_t)k;
      pt->d = x[0];
      return SC_OK;
    }
    if (st) return st;
    memcpy(x, w->v->f, n * sizeof *x);
    memcpy(w->tail + (size_t)(k % SC_CIRCLE_POINTS) * n, x, n * sizeof *x);
    period = sc_periodn_push(w->pd, x);
  }
  k--;
  if (!period && sc_periodn_settling(w->pd)) period = SC_PERIOD_UNSETTLED;
  if (!period && k + 1 >= SC_CIRCLE_POINTS) {
    /* the last SC_CIRCLE_POINTS states in their order: x_k is at slot
     * k % SC_CIRCLE_POINTS of the ring */
    const size_t M = SC_CIRCLE_POINTS, s0 = (size_t)(k + 1) % M;
    memcpy(w->chron, w->tail + s0 * n, (M - s0) * n * sizeof *x);
    memcpy(w->chron + (M - s0) * n, w->tail, s0 * n * sizeof *x);
    if (sc_orbit_on_circle(w->chron, M, n, sc_periodn_tol(w->pd), w->work,
                           NULL))
      period = SC_PERIOD_CIRCLE;
  }
  pt->period = period;
  pt->iterations = (int32_t)k;
  pt->d = x[0];
  memcpy(w->seed, x, n * sizeof *x);
  return SC_OK;
}

/* Point (row k of this call, column i) of an n-dimensional map from the
 * state w->seed. */
static int one_point_n(shared_state *sh, sc_map *m, nd_work *w, long k,
                       long i, sc_msg *msg) {
  const sc_chart_spec *s = sh->s;
  long row = sh->first + k * sh->stride;
  double x = sc_chart_x(s, i), y = sc_chart_y(s, row);
  int st = set_param(m, sh->iy, y, msg);
  if (!st) st = set_param(m, sh->ix, x, msg);
  if (!st) st = nd_classify(w, m, s->transient, &sh->out[k * sh->nx + i], msg);
  if (st) {
    sc_msg inner = *msg;
    sc_fail(msg, st, "chart: at %s = %.17g, %s = %.17g: %s", s->x, x, s->y,
            y, inner.text);
  }
  return st;
}

/* The rows of a map of n > 1 components, as sc_chart_rows() does them
 * for n = 1 (the one-dimensional loop stays as it was). */
static void rows_n(shared_state *sh, const sc_map *proto, long count,
                   int nth) {
  const sc_chart_spec *s = sh->s;
  const double rtol = sc_map_accuracy(proto)->period_rtol;
  const long nx = s->x_steps;
  const int neighbour = s->seed == SC_CHART_SEED_NEIGHBOUR;
#pragma omp parallel num_threads(nth)
  {
    sc_map *m = NULL;
    nd_work w;
    sc_msg lmsg;
    int lst = sc_map_clone(proto, &m, &lmsg);
    if (!lst) lst = nd_alloc(proto, s, rtol, &w, &lmsg);
    else memset(&w, 0, sizeof w);
    if (lst) record_error(sh, -1, lst, &lmsg);
    if (!neighbour) {
#pragma omp for schedule(dynamic, 4)
      for (long p = 0; p < count * nx; p++) {
        if (lst || stopped(sh)) continue;
        nd_start(s, w.n, w.seed);
        int e = one_point_n(sh, m, &w, p / nx, p % nx, &lmsg);
        if (e) record_error(sh, p, e, &lmsg);
        else point_done(sh);
      }
    } else {
#pragma omp for schedule(dynamic, 1)
      for (long k = 0; k < count; k++) {
        if (!lst) nd_start(s, w.n, w.seed);
        for (long i = 0; i < nx && !lst && !stopped(sh); i++) {
          int e = one_point_n(sh, m, &w, k, i, &lmsg);
          if (e) {
            record_error(sh, k * nx + i, e, &lmsg);
            break;
          }
          if (sh->out[k * nx + i].period == SC_PERIOD_UNDEFINED)
            nd_start(s, w.n, w.seed);
          point_done(sh);
        }
      }
    }
    nd_free(&w);
    sc_map_free(m);
  }
}

int sc_chart_rows(const sc_map *proto, const sc_chart_spec *s, long first,
                  long count, long stride, int threads,
                  sc_chart_progress_fn progress, void *ctx,
                  sc_chart_point *out, sc_msg *msg) {
  int st = sc_chart_check(proto, s, msg);
  if (st) return st;
  if (first < 0 || count < 0 || stride < 1 || threads < 0 ||
      (count > 0 && first + (count - 1) * stride >= s->y_steps))
    return sc_fail(msg, SC_EINVAL,
                   "sc_chart_rows: first = %ld, count = %ld, stride = %ld, "
                   "threads = %d (valid: rows inside 0..%ld, stride >= 1, "
                   "threads >= 0)",
                   first, count, stride, threads, s->y_steps - 1);
  if (count == 0) return SC_OK;
  shared_state sh = {.s = s,
                     .ix = sc_map_param_index(proto, s->x),
                     .iy = sc_map_param_index(proto, s->y),
                     .first = first,
                     .stride = stride,
                     .nx = s->x_steps,
                     .progress = progress,
                     .ctx = ctx,
                     .out = out,
                     .err_index = LONG_MAX};
  const double rtol = sc_map_accuracy(proto)->period_rtol;
  const long nx = s->x_steps;
  const int neighbour = s->seed == SC_CHART_SEED_NEIGHBOUR;
  int nth = threads > 0 ? threads : omp_get_max_threads();

  if (sc_map_dim(proto) > 1) rows_n(&sh, proto, count, nth);
  else
#pragma omp parallel num_threads(nth)
  {
    sc_map *m = NULL;
    sc_period *pd = NULL;
    sc_msg lmsg;
    int lst = sc_map_clone(proto, &m, &lmsg);
    if (!lst) lst = sc_period_alloc(s->max_period, s->confirm, rtol, &pd,
                                    &lmsg);
    if (lst) record_error(&sh, -1, lst, &lmsg);
    if (!neighbour) {
#pragma omp for schedule(dynamic, 4)
      for (long p = 0; p < count * nx; p++) {
        if (lst || stopped(&sh)) continue;
        int e = one_point(&sh, m, pd, p / nx, p % nx, s->d0, &lmsg);
        if (e) record_error(&sh, p, e, &lmsg);
        else point_done(&sh);
      }
    } else {
#pragma omp for schedule(dynamic, 1)
      for (long k = 0; k < count; k++) {
        double d = s->d0;
        for (long i = 0; i < nx && !lst && !stopped(&sh); i++) {
          int e = one_point(&sh, m, pd, k, i, d, &lmsg);
          if (e) {
            record_error(&sh, k * nx + i, e, &lmsg);
            break;
          }
          const sc_chart_point *pt = &out[k * nx + i];
          d = pt->period == SC_PERIOD_UNDEFINED ? s->d0 : pt->d;
          point_done(&sh);
        }
      }
    }
    sc_period_free(pd);
    sc_map_free(m);
  }

  if (sh.err_index != LONG_MAX) {
    if (msg) *msg = sh.err_msg;
    return sh.err_status;
  }
  if (sh.stop)
    return sc_fail(msg, SC_ECALLBACK,
                   "sc_chart_rows: cancelled by the progress callback after "
                   "%ld points",
                   sh.done);
  return SC_OK;
}
