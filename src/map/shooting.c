/* Shooting for periodic orbits of the event map: Newton on f^m(d) - d
 * (single) or on the cyclic system d_(i+1) - f(d_i) = 0 (multiple), with
 * the exact derivatives of map.h.  See shooting.h. */
#include "slipcont/shooting.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A Newton step within this many ulps of the unknown cannot be improved
 * on: the residual is then at the rounding level of the map. */
#define STAGNATION_ULPS 4.0

struct sc_shoot {
  sc_map *map;
  int period;
  sc_shoot_method method;
  int n;                  /* unknowns: 1 (single) or period (multiple) */
  const sc_linsolve_type *lstype;
  sc_linsolve *ls;        /* multiple shooting only */
  double *x, *xtry, *seed, *F, *Ftry, *dx, *fd, *fdtry, *val;
  int *neutral, *neutraltry;
  unsigned long nnewton;
};

int sc_shoot_alloc(sc_map *m, int period, sc_shoot_method method,
                   const sc_linsolve_type *ls, sc_shoot **out, sc_msg *msg) {
  *out = NULL;
  if (!m)
    return sc_fail(msg, SC_EINVAL, "sc_shoot_alloc: no map");
  if (period < 1 || period > 1000000)
    return sc_fail(msg, SC_EINVAL,
                   "sc_shoot_alloc: period = %d (valid: [1, 1000000])",
                   period);
  if (method != SC_SHOOT_SINGLE && method != SC_SHOOT_MULTIPLE)
    return sc_fail(msg, SC_EINVAL,
                   "sc_shoot_alloc: method = %d (valid: SC_SHOOT_SINGLE, "
                   "SC_SHOOT_MULTIPLE)",
                   (int)method);
  sc_shoot *s = calloc(1, sizeof *s);
  int *colptr = NULL, *rowind = NULL;
  int st = SC_ENOMEM;
  if (!s) goto fail;
  s->map = m;
  s->period = period;
  s->method = method;
  s->n = method == SC_SHOOT_SINGLE ? 1 : period;
  size_t n = (size_t)period; /* orbit storage is period long either way */
  s->x = calloc(n, sizeof *s->x);
  s->xtry = calloc(n, sizeof *s->xtry);
  s->seed = calloc(n, sizeof *s->seed);
  s->F = calloc(n, sizeof *s->F);
  s->Ftry = calloc(n, sizeof *s->Ftry);
  s->dx = calloc(n, sizeof *s->dx);
  s->fd = calloc(n, sizeof *s->fd);
  s->fdtry = calloc(n, sizeof *s->fdtry);
  s->val = calloc(2 * n, sizeof *s->val);
  s->neutral = calloc(n, sizeof *s->neutral);
  s->neutraltry = calloc(n, sizeof *s->neutraltry);
  if (!s->x || !s->xtry || !s->seed || !s->F || !s->Ftry || !s->dx || !s->fd ||
      !s->fdtry || !s->val || !s->neutral || !s->neutraltry)
    goto fail;
  if (method == SC_SHOOT_MULTIPLE) {
    s->lstype = ls ? ls
                   : period <= SC_SHOOT_DENSE_MAX ? sc_linsolve_dense
                                                  : sc_linsolve_klu;
    /* Cyclic bidiagonal pattern: column j holds dF_j/dd_j = -f'(d_j) and
     * dF_(j-1)/dd_j = 1 (rows sorted; for m = 1 one entry 1 - f'). */
    colptr = malloc((n + 1) * sizeof *colptr);
    rowind = malloc(2 * n * sizeof *rowind);
    if (!colptr || !rowind) goto fail;
    int k = 0;
    for (int j = 0; j < period; j++) {
      colptr[j] = k;
      if (period == 1) {
        rowind[k++] = 0;
      } else if (j == 0) {
        rowind[k++] = 0;
        rowind[k++] = period - 1;
      } else {
        rowind[k++] = j - 1;
        rowind[k++] = j;
      }
    }
    colptr[period] = k;
    st = sc_linsolve_alloc(s->lstype, period, colptr, rowind, &s->ls, msg);
    if (st) goto fail;
  }
  free(colptr);
  free(rowind);
  *out = s;
  return SC_OK;
fail:
  free(colptr);
  free(rowind);
  sc_shoot_free(s);
  if (st == SC_ENOMEM) sc_fail(msg, st, "sc_shoot_alloc: out of memory");
  return st;
}

void sc_shoot_free(sc_shoot *s) {
  if (!s) return;
  sc_linsolve_free(s->ls);
  free(s->x);
  free(s->xtry);
  free(s->seed);
  free(s->F);
  free(s->Ftry);
  free(s->dx);
  free(s->fd);
  free(s->fdtry);
  free(s->val);
  free(s->neutral);
  free(s->neutraltry);
  free(s);
}

const double *sc_shoot_orbit(const sc_shoot *s) { return s->x; }
int sc_shoot_period(const sc_shoot *s) { return s->period; }
sc_shoot_method sc_shoot_get_method(const sc_shoot *s) { return s->method; }
const sc_linsolve_type *sc_shoot_linsolve_type(const sc_shoot *s) {
  return s->method == SC_SHOOT_MULTIPLE ? s->lstype : NULL;
}
unsigned long sc_shoot_nnewton(const sc_shoot *s) { return s->nnewton; }

/* Residual F and slopes at x (n unknowns): single F = f^m(x) - x with
 * fd = (f^m)'; multiple F_i = x_(i+1) - f(x_i) with fd_i = f'(x_i). */
static int residual(sc_shoot *s, const double *x, double *F, double *fd,
                    int *neutral, sc_msg *msg) {
  sc_map_value v;
  if (s->method == SC_SHOOT_SINGLE) {
    int st = sc_map_iterate(s->map, x[0], s->period, SC_EVAL_DERIV, &v, msg);
    if (st) return st;
    F[0] = v.f - x[0];
    fd[0] = v.dfdd;
    neutral[0] = v.neutral;
    return SC_OK;
  }
  int m = s->period;
  for (int i = 0; i < m; i++) {
    int st = sc_map_eval(s->map, x[i], SC_EVAL_DERIV, &v, msg);
    if (st) {
      if (msg) {
        char tail[SC_MSG_LEN];
        snprintf(tail, sizeof tail, "%s", msg->text);
        sc_fail(msg, st, "orbit point %d of %d (%.17g): %.400s", i + 1, m,
                x[i], tail);
      }
      return st;
    }
    F[i] = x[(i + 1) % m] - v.f;
    fd[i] = v.dfdd;
    neutral[i] = v.neutral;
  }
  return SC_OK;
}

static double maxabs(const double *v, int n) {
  double r = 0;
  for (int i = 0; i < n; i++) r = fmax(r, fabs(v[i]));
  return r;
}

/* The merit of damped Newton: the Newton direction is a descent
 * direction of the Euclidean norm (not of the max-norm). */
static double norm2(const double *v, int n) {
  double r = 0;
  for (int i = 0; i < n; i++) r = hypot(r, v[i]);
  return r;
}

/* Newton step dx solving J dx = -F at the current point. */
static int newton_step(sc_shoot *s, sc_msg *msg) {
  int n = s->n;
  if (s->method == SC_SHOOT_SINGLE) {
    double J = s->fd[0] - 1;
    if (J == 0 || !isfinite(J))
      return sc_fail(msg, SC_ESING,
                     "sc_shoot_solve: (f^%d)'(d) - 1 = %g at d = %.17g: "
                     "singular (a fold of the orbit?)",
                     s->period, J, s->x[0]);
    s->dx[0] = -s->F[0] / J;
    return SC_OK;
  }
  /* Values in pattern order (see sc_shoot_alloc). */
  int k = 0;
  for (int j = 0; j < n; j++) {
    if (n == 1) {
      s->val[k++] = 1 - s->fd[0];
    } else if (j == 0) {
      s->val[k++] = -s->fd[0];
      s->val[k++] = 1;
    } else {
      s->val[k++] = 1;
      s->val[k++] = -s->fd[j];
    }
  }
  int st = sc_linsolve_factor(s->ls, s->val, msg);
  if (st) return st;
  for (int i = 0; i < n; i++) s->dx[i] = -s->F[i];
  return sc_linsolve_solve(s->ls, s->dx, msg);
}

static int all_set(const int *v, int n) {
  for (int i = 0; i < n; i++)
    if (!v[i]) return 0;
  return 1;
}

/* Fill res from the converged (or neutral) point. */
static int finish(sc_shoot *s, sc_shoot_result *res, int neutral,
                  sc_msg *msg) {
  int m = s->period;
  sc_map_value v;
  /* Orbit points: single shooting iterates from x[0]. */
  if (s->method == SC_SHOOT_SINGLE) {
    for (int i = 1; i < m; i++) {
      int st = sc_map_eval(s->map, s->x[i - 1], SC_EVAL_VALUE, &v, msg);
      if (st) return st;
      s->x[i] = v.f;
    }
  }
  int st = sc_map_iterate(s->map, s->x[0], m,
                          SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v, msg);
  if (st) return st;
  res->d = s->x[0];
  snprintf(res->itinerary, sizeof res->itinerary, "%s", v.itinerary);
  res->neutral = neutral;
  if (neutral) {
    res->multiplier = 1;
    double gap = 0;
    for (int i = 0; i < s->n; i++) gap -= s->F[i];
    res->family_gap = s->method == SC_SHOOT_SINGLE ? s->F[0] : gap;
  } else {
    /* The product of the slopes at the orbit points. */
    double mult = 1;
    if (s->method == SC_SHOOT_MULTIPLE)
      for (int i = 0; i < m; i++) mult *= s->fd[i];
    else
      mult = v.dfdd;
    res->multiplier = mult;
    res->family_gap = 0;
  }
  res->stable = fabs(res->multiplier) < 1;
  res->residual = maxabs(s->F, s->n);
  return SC_OK;
}

/* Whether every one of x[0..n-1] is finite. */
static int finite_all(const double *x, int n) {
  for (int i = 0; i < n; i++)
    if (!isfinite(x[i])) return 0;
  return 1;
}

/* Every component of the last Newton step s->dx within the step
 * tolerance at s->x. */
static int step_within_tol(const sc_shoot *s, const sc_accuracy *acc) {
  for (int i = 0; i < s->n; i++)
    if (sc_test_delta(s->dx[i], s->x[i], acc->newton_atol,
                      acc->newton_rtol) != SC_OK)
      return 0;
  return 1;
}

/* Newton has converged after its last step (residual fnorm, tolerance
 * ftol, the last two step sizes): step and residual within tolerance,
 * or steps stagnant at rounding, or the noise floor. */
static int converged(const sc_shoot *s, const sc_accuracy *acc, double fnorm,
                     double ftol, double last, double before) {
  int stagnant = 1;
  for (int i = 0; i < s->n; i++)
    if (fabs(s->dx[i]) > STAGNATION_ULPS * DBL_EPSILON * fabs(s->x[i]))
      stagnant = 0;
  /* At the noise floor of an ill-conditioned Jacobian (near a fold or
   * flip) the residual is within tolerance but the steps, the rounding
   * of F amplified by the condition number, stop shrinking: that is
   * convergence too. */
  int at_floor = fnorm <= ftol && last >= 0.5 * before;
  return (step_within_tol(s, acc) && fnorm <= ftol) || stagnant || at_floor;
}

int sc_shoot_solve_orbit(sc_shoot *s, const double *d0, sc_shoot_result *res,
                         sc_msg *msg) {
  memset(res, 0, sizeof *res);
  res->step = HUGE_VAL;
  /* no tighter than the map's precision, as every Newton method on it */
  sc_accuracy sacc;
  sc_map_solver_accuracy(s->map, &sacc);
  const sc_accuracy *acc = &sacc;
  int n = s->n;
  for (int i = 0; i < n; i++) {
    if (!isfinite(d0[i]))
      return sc_fail(msg, SC_EINVAL,
                     "sc_shoot_solve: guess %d = %g is not finite", i + 1,
                     d0[i]);
    s->x[i] = d0[i];
  }
  int st = residual(s, s->x, s->F, s->fd, s->neutral, msg);
  if (st) return st;
  double last = HUGE_VAL, before = HUGE_VAL;
  for (int it = 0;; it++) {
    res->iterations = it;
    if (all_set(s->neutral, n)) {
      st = finish(s, res, 1, msg);
      if (st) return st;
      int on = fabs(res->family_gap) <= acc->newton_ftol;
      if (on)
        return sc_fail(msg, SC_ENEUTRAL,
                       "sc_shoot_solve: d = %.17g is on a continuous family "
                       "of period-%d orbits (every iterate a single-block "
                       "slip, multiplier exactly 1, f^%d(d) - d = %.3g): no "
                       "isolated orbit",
                       s->x[0], s->period, s->period, res->family_gap);
      return sc_fail(msg, SC_ENEUTRAL,
                     "sc_shoot_solve: no period-%d orbit through d = %.17g: "
                     "every iterate is a single-block slip there, so f^%d(d) "
                     "- d = %.17g is the same for all d nearby, and not 0",
                     s->period, s->x[0], s->period, res->family_gap);
    }
    /* Single shooting: f^m(d) - d carries the rounding of f^m, which
     * grows with (f^m)'; its tolerance scales with max(1, |(f^m)'|). */
    double fnorm = maxabs(s->F, n);
    double ftol = acc->newton_ftol;
    if (s->method == SC_SHOOT_SINGLE && isfinite(s->fd[0]))
      ftol *= fmax(1, fabs(s->fd[0]));
    if (it > 0 && converged(s, acc, fnorm, ftol, last, before)) {
      res->step = last;
      return finish(s, res, 0, msg);
    }
    if (it >= acc->newton_maxiter)
      return sc_fail(msg, SC_ENOCONV,
                     "sc_shoot_solve: no convergence in %d Newton iterations "
                     "(period %d, %s shooting; residual %.3g, last step %.3g, "
                     "d = %.17g)",
                     it, s->period,
                     s->method == SC_SHOOT_SINGLE ? "single" : "multiple",
                     fnorm, last, s->x[0]);
    st = newton_step(s, msg);
    if (st == SC_ESING && fnorm <= ftol && finite_all(s->fd, n)) {
      /* within tolerance where the Jacobian is exactly singular: a start
       * at a fold itself (below) */
      res->step = it == 0 ? 0 : last;
      return finish(s, res, 0, msg);
    }
    if (st) return st;
    s->nnewton++;
    /* Damped Newton: halve a step that lands where the map is undefined
     * or that does not decrease the Euclidean norm of the residual
     * (across a jump of f the full step can land on another piece, far
     * away). */
    /* a step within tolerance is taken whatever it does */
    int tiny = step_within_tol(s, acc);
    double lambda = 1, merit = norm2(s->F, n);
    for (int h = 0;; h++) {
      for (int i = 0; i < n; i++) s->xtry[i] = s->x[i] + lambda * s->dx[i];
      st = residual(s, s->xtry, s->Ftry, s->fdtry, s->neutraltry, msg);
      if (st == SC_OK) {
        if (tiny || norm2(s->Ftry, n) < merit || maxabs(s->Ftry, n) <= ftol)
          break;
        if (h >= SC_SHOOT_MAX_HALVINGS && fnorm <= ftol) {
          /* Already within tolerance, and no step decreases the residual:
           * the noise floor, reached before any step was tested against
           * it (a start at a fold itself, from a points.csv row: the
           * Jacobian is singular there and its step goes far) */
          res->step = it == 0 ? 0 : last;
          return finish(s, res, 0, msg);
        }
        if (h >= SC_SHOOT_MAX_HALVINGS)
          return sc_fail(msg, SC_ENOCONV,
                         "sc_shoot_solve: no Newton step decreases the "
                         "residual %.3g after %d halvings (period %d, d = "
                         "%.17g): a jump of the map?",
                         fnorm, h, s->period, s->x[0]);
      } else if ((st != SC_EUNDEF && st != SC_ENONFINITE &&
                  st != SC_ENOCONV) ||
                 h >= SC_SHOOT_MAX_HALVINGS) {
        return st;
      }
      lambda *= 0.5;
    }
    for (int i = 0; i < n; i++) s->dx[i] *= lambda;
    before = last;
    last = maxabs(s->dx, n);
    memcpy(s->x, s->xtry, (size_t)n * sizeof *s->x);
    memcpy(s->F, s->Ftry, (size_t)n * sizeof *s->F);
    memcpy(s->fd, s->fdtry, (size_t)n * sizeof *s->fd);
    memcpy(s->neutral, s->neutraltry, (size_t)n * sizeof *s->neutral);
  }
}

int sc_shoot_solve(sc_shoot *s, double d0, sc_shoot_result *res,
                   sc_msg *msg) {
  if (!isfinite(d0)) {
    memset(res, 0, sizeof *res);
    return sc_fail(msg, SC_EINVAL, "sc_shoot_solve: guess %g is not finite",
                   d0);
  }
  /* Seed the unknowns with the iterates of d0. */
  s->seed[0] = d0;
  if (s->method == SC_SHOOT_MULTIPLE) {
    sc_map_value v;
    for (int i = 1; i < s->period; i++) {
      int st = sc_map_eval(s->map, s->seed[i - 1], SC_EVAL_VALUE, &v, msg);
      if (st) {
        memset(res, 0, sizeof *res);
        return st;
      }
      s->seed[i] = v.f;
    }
  }
  return sc_shoot_solve_orbit(s, s->seed, res, msg);
}
