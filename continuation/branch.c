/* Pseudo-arclength continuation of F(u) = 0, u in R^(n+1): tangent
 * predictor, Newton corrector on the bordered system, adaptive steps, test
 * functions and the location of their zeros.  See docs/continuation.md
 * for the formulas. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/continuation.h"

/* A point of the branch with what is known there. */
typedef struct {
  double *u;     /* N = n + 1 */
  double *t;     /* unit tangent, N */
  double *psi;   /* test functions, ntest */
  int det_sign;  /* bordered Jacobian [F_u; t_prev^T] at u */
  double det_log;
  int newton_iter; /* iterations its corrector took */
} point;

struct sc_branch {
  sc_cont_problem pb;
  sc_cont_settings set;
  sc_accuracy acc;
  size_t n, N;
  /* Jacobian values as the callback writes them, and where each goes in
   * the bordered matrix B = [F_u; border^T] (CSC, N x N). */
  int nnz_j;
  int *jac_cp, *jac_ri; /* copies of the user pattern (sparse case) */
  double *jval;         /* nnz_j */
  int *jmap;            /* nnz_j: slot in bval */
  int *bslot;           /* N: slot of B(n, j) */
  int nnz_b;
  double *bval;         /* nnz_b */
  sc_linsolve *ls;
  double *F, *dx, *border;
  point cur, trial, loc, best;
  int *sign;            /* ntest: sign of psi_k on the current side */
  double h;
  int ready, ended;
  sc_corr_reason reason;
  sc_cont_location location, best_location;
  unsigned long npoints, nspecial, nrej_special, nrejected, nnewton, nfeval,
      njac, nlocate;
};

const char *sc_corr_reason_text(sc_corr_reason r) {
  switch (r) {
  case SC_CORR_NONE: return "no corrector run";
  case SC_CORR_CONVERGED: return "converged";
  case SC_CORR_MAXITER: return "maximum Newton iterations reached";
  case SC_CORR_DIVERGING: return "diverging (Newton step grew)";
  case SC_CORR_SINGULAR: return "singular bordered Jacobian";
  case SC_CORR_CALLBACK: return "callback failed or returned a non-finite "
                                "value";
  }
  return "unknown reason";
}

void sc_cont_settings_default(sc_cont_settings *s) {
  s->h0 = 1e-2;
  s->hmin = 1e-10;
  s->hmax = 0.1;
  s->grow = 1.5;
  s->shrink = 0.5;
  s->fast_iter = 3;
  s->pmin = -HUGE_VAL;
  s->pmax = HUGE_VAL;
  s->direction = 1;
  s->max_points = 1000;
  s->test_atol = 1e-8;
  s->max_locate_iter = 60;
  s->linsolve = NULL;
  s->start_free = 0;
}

int sc_cont_settings_check(const sc_cont_settings *s, sc_msg *msg) {
  if (!s) return sc_fail(msg, SC_EINVAL, "sc_cont_settings_check: NULL");
  if (!(isfinite(s->h0) && s->h0 > 0))
    return sc_fail(msg, SC_EINVAL, "settings: h0 = %.17g (valid: finite, > 0)",
                   s->h0);
  if (!(s->hmin > 0 && s->hmin <= s->h0))
    return sc_fail(msg, SC_EINVAL,
                   "settings: hmin = %.17g (valid: (0, h0 = %.17g])", s->hmin,
                   s->h0);
  if (!(isfinite(s->hmax) && s->hmax >= s->h0))
    return sc_fail(msg, SC_EINVAL,
                   "settings: hmax = %.17g (valid: finite, >= h0 = %.17g)",
                   s->hmax, s->h0);
  if (!(isfinite(s->grow) && s->grow >= 1))
    return sc_fail(msg, SC_EINVAL, "settings: grow = %.17g (valid: [1, inf))",
                   s->grow);
  if (!(s->shrink > 0 && s->shrink < 1))
    return sc_fail(msg, SC_EINVAL, "settings: shrink = %.17g (valid: (0, 1))",
                   s->shrink);
  if (s->fast_iter < 1)
    return sc_fail(msg, SC_EINVAL, "settings: fast_iter = %d (valid: >= 1)",
                   s->fast_iter);
  if (isnan(s->pmin) || isnan(s->pmax) || !(s->pmin < s->pmax))
    return sc_fail(msg, SC_EINVAL,
                   "settings: [pmin, pmax] = [%.17g, %.17g] (valid: pmin < "
                   "pmax)",
                   s->pmin, s->pmax);
  if (s->direction != 1 && s->direction != -1)
    return sc_fail(msg, SC_EINVAL, "settings: direction = %d (valid: +1, -1)",
                   s->direction);
  if (s->max_points < 1)
    return sc_fail(msg, SC_EINVAL, "settings: max_points = %ld (valid: >= 1)",
                   s->max_points);
  if (!(isfinite(s->test_atol) && s->test_atol > 0))
    return sc_fail(msg, SC_EINVAL,
                   "settings: test_atol = %.17g (valid: finite, > 0)",
                   s->test_atol);
  if (s->max_locate_iter < 1)
    return sc_fail(msg, SC_EINVAL,
                   "settings: max_locate_iter = %d (valid: >= 1)",
                   s->max_locate_iter);
  return SC_OK;
}

/* ------------------------------------------------------------------ */
/* Allocation                                                          */
/* ------------------------------------------------------------------ */

static int point_alloc(point *p, size_t N, size_t ntest) {
  p->u = calloc(N, sizeof *p->u);
  p->t = calloc(N, sizeof *p->t);
  p->psi = calloc(ntest ? ntest : 1, sizeof *p->psi);
  return p->u && p->t && p->psi;
}

static void point_free(point *p) {
  free(p->u);
  free(p->t);
  free(p->psi);
}

static void point_copy(point *dst, const point *src, size_t N, size_t ntest) {
  memcpy(dst->u, src->u, N * sizeof *dst->u);
  memcpy(dst->t, src->t, N * sizeof *dst->t);
  memcpy(dst->psi, src->psi, ntest * sizeof *dst->psi);
  dst->det_sign = src->det_sign;
  dst->det_log = src->det_log;
  dst->newton_iter = src->newton_iter;
}

void sc_branch_free(sc_branch *b) {
  if (!b) return;
  free(b->jac_cp);
  free(b->jac_ri);
  free(b->jval);
  free(b->jmap);
  free(b->bslot);
  free(b->bval);
  sc_linsolve_free(b->ls);
  free(b->F);
  free(b->dx);
  free(b->border);
  point_free(&b->cur);
  point_free(&b->trial);
  point_free(&b->loc);
  point_free(&b->best);
  free(b->sign);
  free(b);
}

/* Check the user's Jacobian pattern: n rows, N columns, rows strictly
 * increasing in each column. */
static int check_jac_pattern(const sc_cont_problem *pb, sc_msg *msg) {
  const int *cp = pb->jac_colptr, *ri = pb->jac_rowind;
  int n = (int)pb->n, N = n + 1;
  if (cp[0] != 0)
    return sc_fail(msg, SC_EINVAL, "sc_branch_alloc: jac_colptr[0] = %d "
                                   "(valid: 0)", cp[0]);
  for (int j = 0; j < N; j++) {
    if (cp[j + 1] < cp[j])
      return sc_fail(msg, SC_EINVAL,
                     "sc_branch_alloc: jac_colptr decreases at column %d", j);
    for (int k = cp[j]; k < cp[j + 1]; k++)
      if (ri[k] < 0 || ri[k] >= n || (k > cp[j] && ri[k] <= ri[k - 1]))
        return sc_fail(msg, SC_EINVAL,
                       "sc_branch_alloc: Jacobian pattern row %d in column %d "
                       "(valid: [0, %d), strictly increasing)",
                       ri[k], j, n);
  }
  return SC_OK;
}

int sc_branch_alloc(const sc_cont_problem *pb, const sc_cont_settings *set,
                    const sc_accuracy *acc, sc_branch **out, sc_msg *msg) {
  *out = NULL;
  if (!pb || pb->n < 1 || !pb->f || !pb->jac || (pb->ntest && !pb->test) ||
      !pb->jac_colptr != !pb->jac_rowind || pb->n > 46339)
    return sc_fail(msg, SC_EINVAL,
                   "sc_branch_alloc: malformed problem (need n in [1, 46339], "
                   "f, jac, test if ntest > 0, both or neither of the "
                   "Jacobian pattern arrays)");
  sc_cont_settings s;
  if (set) {
    int st = sc_cont_settings_check(set, msg);
    if (st) return st;
    s = *set;
  } else {
    sc_cont_settings_default(&s);
  }
  sc_accuracy a;
  if (acc) {
    int st = sc_accuracy_check(acc, msg);
    if (st) return st;
    a = *acc;
  } else {
    sc_accuracy_preset(&a, "default", NULL);
  }
  if (pb->jac_colptr) {
    int st = check_jac_pattern(pb, msg);
    if (st) return st;
  }

  sc_branch *b = calloc(1, sizeof *b);
  if (!b) return sc_fail(msg, SC_ENOMEM, "sc_branch_alloc: out of memory");
  b->pb = *pb;
  b->set = s;
  b->acc = a;
  b->n = pb->n;
  b->N = pb->n + 1;
  size_t n = b->n, N = b->N, nt = pb->ntest;
  int *bcp = NULL, *bri = NULL;
  int st = SC_ENOMEM;

  /* The bordered pattern: column j holds the Jacobian's rows of column j
   * and then row n (the border). */
  if (pb->jac_colptr) {
    b->nnz_j = pb->jac_colptr[N];
    b->jac_cp = malloc(sizeof(int) * (N + 1));
    b->jac_ri = malloc(sizeof(int) * (size_t)(b->nnz_j ? b->nnz_j : 1));
    if (!b->jac_cp || !b->jac_ri) goto fail;
    memcpy(b->jac_cp, pb->jac_colptr, sizeof(int) * (N + 1));
    memcpy(b->jac_ri, pb->jac_rowind, sizeof(int) * (size_t)b->nnz_j);
    b->pb.jac_colptr = b->jac_cp;
    b->pb.jac_rowind = b->jac_ri;
  } else {
    b->nnz_j = (int)(n * N);
  }
  b->nnz_b = b->nnz_j + (int)N;
  b->jval = malloc(sizeof(double) * (size_t)b->nnz_j);
  b->jmap = malloc(sizeof(int) * (size_t)b->nnz_j);
  b->bslot = malloc(sizeof(int) * N);
  b->bval = malloc(sizeof(double) * (size_t)b->nnz_b);
  bcp = malloc(sizeof(int) * (N + 1));
  bri = malloc(sizeof(int) * (size_t)b->nnz_b);
  if (!b->jval || !b->jmap || !b->bslot || !b->bval || !bcp || !bri)
    goto fail;
  int k = 0;
  for (size_t j = 0; j < N; j++) {
    bcp[j] = k;
    if (pb->jac_colptr) {
      for (int q = b->jac_cp[j]; q < b->jac_cp[j + 1]; q++) {
        b->jmap[q] = k;
        bri[k++] = b->jac_ri[q];
      }
    } else {
      for (size_t i = 0; i < n; i++) {
        b->jmap[i * N + j] = k; /* row-major J[i][j] */
        bri[k++] = (int)i;
      }
    }
    b->bslot[j] = k;
    bri[k++] = (int)n;
  }
  bcp[N] = k;
  st = sc_linsolve_alloc(s.linsolve ? s.linsolve : sc_linsolve_dense, (int)N,
                         bcp, bri, &b->ls, msg);
  if (st) {
    free(bcp);
    free(bri);
    sc_branch_free(b);
    return st;
  }
  st = SC_ENOMEM;
  b->F = malloc(sizeof(double) * N);
  b->dx = malloc(sizeof(double) * N);
  b->border = malloc(sizeof(double) * N);
  b->sign = calloc(nt ? nt : 1, sizeof *b->sign);
  if (!b->F || !b->dx || !b->border || !b->sign) goto fail;
  if (!point_alloc(&b->cur, N, nt) || !point_alloc(&b->trial, N, nt) ||
      !point_alloc(&b->loc, N, nt) || !point_alloc(&b->best, N, nt))
    goto fail;
  free(bcp);
  free(bri);
  b->location.test = -1;
  *out = b;
  return SC_OK;
fail:
  free(bcp);
  free(bri);
  sc_branch_free(b);
  return sc_fail(msg, SC_ENOMEM, "sc_branch_alloc: out of memory (n = %zu)",
                 n);
}

/* ------------------------------------------------------------------ */
/* Corrector                                                           */
/* ------------------------------------------------------------------ */

static double norm_inf(const double *v, size_t n) {
  double m = 0;
  for (size_t i = 0; i < n; i++) m = fmax(m, fabs(v[i]));
  return m;
}

static double dot(const double *a, const double *b, size_t n) {
  double s = 0;
  for (size_t i = 0; i < n; i++) s += a[i] * b[i];
  return s;
}

static int all_finite(const double *v, size_t n) {
  for (size_t i = 0; i < n; i++)
    if (!isfinite(v[i])) return 0;
  return 1;
}

/* Outcome of a callback: SC_OK, SC_CONTINUE (recoverable: reason
 * CALLBACK) or SC_ECALLBACK (fatal). */
static int callback_status(sc_branch *b, int rc, const double *v, size_t len,
                           const char *what, sc_msg *msg) {
  if (rc < 0)
    return sc_fail(msg, SC_ECALLBACK, "continuation: %s callback failed "
                                      "(returned %d)", what, rc);
  if (rc > 0 || !all_finite(v, len)) {
    b->reason = SC_CORR_CALLBACK;
    sc_fail(msg, SC_CONTINUE, "continuation: %s callback %s", what,
            rc > 0 ? "failed recoverably" : "returned a non-finite value");
    return SC_CONTINUE;
  }
  return SC_OK;
}

/* Evaluate F at u into b->F. */
static int eval_f(sc_branch *b, const double *u, sc_msg *msg) {
  b->nfeval++;
  int rc = b->pb.f(u, b->F, b->pb.user);
  return callback_status(b, rc, b->F, b->n, "F", msg);
}

/* Evaluate the Jacobian at u and factor B = [F_u(u); border^T]. */
static int factor_bordered(sc_branch *b, const double *u,
                           const double *border, sc_msg *msg) {
  b->njac++;
  int rc = b->pb.jac(u, b->jval, b->pb.user);
  int st = callback_status(b, rc, b->jval, (size_t)b->nnz_j, "Jacobian", msg);
  if (st) return st;
  for (int q = 0; q < b->nnz_j; q++) b->bval[b->jmap[q]] = b->jval[q];
  for (size_t j = 0; j < b->N; j++) b->bval[b->bslot[j]] = border[j];
  st = sc_linsolve_factor(b->ls, b->bval, msg);
  if (st == SC_ESING || st == SC_ENONFINITE) {
    b->reason = SC_CORR_SINGULAR;
    return SC_CONTINUE;
  }
  return st;
}

/* Rounding level of a Newton step, in ulps of the size of u: steps of
 * f^m-based systems stop shrinking at a few hundred ulps near folds and
 * flips, where the bordered Jacobian amplifies the rounding of F. */
#define NEWTON_NOISE_ULPS 256.0

/* Newton on G(u) = [F(u); border.u - target] = 0 from u (in place).
 * Converged when |dx_i| <= newton_atol + newton_rtol |u_i| for every i
 * and |F|_inf <= newton_ftol at the point the last step started from.
 * Returns SC_OK (b->reason = CONVERGED), SC_CONTINUE (a recoverable
 * failure, b->reason says which) or a negative error. */
static int newton(sc_branch *b, double *u, const double *border,
                  double target, int *iters, sc_msg *msg) {
  size_t N = b->N, n = b->n;
  double prev = HUGE_VAL;
  *iters = 0;
  for (int k = 0; k < b->acc.newton_maxiter; k++) {
    int st = eval_f(b, u, msg);
    if (st) return st;
    st = factor_bordered(b, u, border, msg);
    if (st) return st;
    for (size_t i = 0; i < n; i++) b->dx[i] = -b->F[i];
    b->dx[n] = target - dot(border, u, N);
    st = sc_linsolve_solve(b->ls, b->dx, msg);
    if (st == SC_ENONFINITE) {
      b->reason = SC_CORR_SINGULAR;
      return SC_CONTINUE;
    }
    if (st) return st;
    b->nnewton++;
    (*iters)++;
    double step = norm_inf(b->dx, N);
    double res = norm_inf(b->F, n);
    int small = 1;
    /* A step at the rounding level of u is noise: Newton can do no
     * better there, so a tolerance below what the arithmetic resolves
     * (the "precise" preset) is met at that floor, and steps that wander
     * within it are not a divergence. */
    double noise = NEWTON_NOISE_ULPS * DBL_EPSILON * (1 + norm_inf(u, N));
    for (size_t i = 0; i < N; i++) {
      u[i] += b->dx[i];
      if (sc_test_delta(b->dx[i], u[i], b->acc.newton_atol,
                        b->acc.newton_rtol) != SC_OK &&
          !(fabs(b->dx[i]) <= noise))
        small = 0;
    }
    if (small && (res <= b->acc.newton_ftol || step <= noise)) {
      b->reason = SC_CORR_CONVERGED;
      return SC_OK;
    }
    /* Newton's steps shrink (quadratically) inside its basin: a step
     * longer than the previous one means we are not in it. */
    if (step > prev && step > noise) {
      b->reason = SC_CORR_DIVERGING;
      sc_fail(msg, SC_CONTINUE,
              "continuation: Newton diverging at iteration %d (step %.3g > "
              "previous %.3g)",
              k + 1, step, prev);
      return SC_CONTINUE;
    }
    prev = step;
  }
  b->reason = SC_CORR_MAXITER;
  sc_fail(msg, SC_CONTINUE,
          "continuation: Newton not converged in %d iterations (newton-atol "
          "%.3g, newton-rtol %.3g, newton-ftol %.3g)",
          b->acc.newton_maxiter, b->acc.newton_atol, b->acc.newton_rtol,
          b->acc.newton_ftol);
  return SC_CONTINUE;
}

/* The unit tangent at p->u from B = [F_u; border^T] t = e_N (so that
 * border.t > 0 after normalisation), the determinant of B, and the test
 * functions.  SC_OK, SC_CONTINUE (recoverable) or an error. */
static int finish_point(sc_branch *b, point *p, const double *border,
                        sc_msg *msg) {
  size_t N = b->N;
  int st = factor_bordered(b, p->u, border, msg);
  if (st) return st;
  for (size_t i = 0; i < N; i++) p->t[i] = 0;
  p->t[N - 1] = 1;
  st = sc_linsolve_solve(b->ls, p->t, msg);
  if (st == SC_ENONFINITE) {
    b->reason = SC_CORR_SINGULAR;
    return SC_CONTINUE;
  }
  if (st) return st;
  double nrm = sqrt(dot(p->t, p->t, N));
  for (size_t i = 0; i < N; i++) p->t[i] /= nrm;
  sc_linsolve_det(b->ls, &p->det_sign, &p->det_log);
  if (b->pb.ntest) {
    int rc = b->pb.test(p->u, p->t, p->psi, b->pb.user);
    st = callback_status(b, rc, p->psi, b->pb.ntest, "test function", msg);
    if (st) return st;
  }
  return SC_OK;
}

/* The point of the branch at arclength s from the current point: Newton
 * from cur.u + s cur.t on t.(u - cur.u) = s, then tangent and tests. */
static int point_at(sc_branch *b, double s, point *p, sc_msg *msg) {
  size_t N = b->N;
  for (size_t i = 0; i < N; i++) p->u[i] = b->cur.u[i] + s * b->cur.t[i];
  double target = dot(b->cur.t, b->cur.u, N) + s;
  int st = newton(b, p->u, b->cur.t, target, &p->newton_iter, msg);
  if (st) return st;
  return finish_point(b, p, b->cur.t, msg);
}

/* ------------------------------------------------------------------ */
/* Start                                                               */
/* ------------------------------------------------------------------ */

static int sgn(double x) { return (x > 0) - (x < 0); }

int sc_branch_set(sc_branch *b, const double *u0, sc_msg *msg) {
  size_t N = b->N, n = b->n;
  b->ready = 0;
  b->ended = 0;
  if (!all_finite(u0, N))
    return sc_fail(msg, SC_EINVAL, "sc_branch_set: initial point not finite");
  if (!(u0[n] >= b->set.pmin && u0[n] <= b->set.pmax))
    return sc_fail(msg, SC_EINVAL,
                   "sc_branch_set: parameter u[%zu] = %.17g outside [%.17g, "
                   "%.17g]",
                   n, u0[n], b->set.pmin, b->set.pmax);
  point *p = &b->cur;
  /* Correct with the parameter fixed: border e_n.  Where F_x is nearly
   * singular (close to a fold in u[n], or to a flip of the orbit a
   * period-doubled branch starts from) that correction is ill
   * conditioned; with start_free, fix another coordinate instead, as the
   * tangent below does. */
  int st = SC_CONTINUE;
  size_t naxes = b->set.start_free ? N : 1;
  for (size_t k = 0; k < naxes && st == SC_CONTINUE; k++) {
    size_t axis = k == 0 ? n : k - 1;
    memcpy(p->u, u0, N * sizeof *u0);
    for (size_t i = 0; i < N; i++) b->border[i] = i == axis;
    st = newton(b, p->u, b->border, u0[axis], &p->newton_iter, msg);
    if (st == SC_ESING) st = SC_CONTINUE; /* singular with this border */
    if (st < 0) return st;
    if (st == SC_OK && !(p->u[n] >= b->set.pmin && p->u[n] <= b->set.pmax))
      st = SC_CONTINUE;
  }
  if (st == SC_CONTINUE)
    return sc_fail(msg, SC_ENOCONV,
                   "sc_branch_set: initial point not corrected (%s)",
                   sc_corr_reason_text(b->reason));
  /* Tangent from [F_u; e_j^T] t = e_N, with j = n first; at a turning
   * point in u[n] that matrix is singular, so try the other axes. */
  st = SC_CONTINUE;
  for (size_t j = N; j-- > 0 && st == SC_CONTINUE;) {
    for (size_t i = 0; i < N; i++) b->border[i] = i == j;
    st = finish_point(b, p, b->border, msg);
    if (st < 0) return st;
  }
  if (st)
    return sc_fail(msg, SC_ENOCONV,
                   "sc_branch_set: no tangent at the initial point (%s)",
                   sc_corr_reason_text(b->reason));
  if (sgn(p->t[n]) == -b->set.direction) {
    for (size_t i = 0; i < N; i++) p->t[i] = -p->t[i];
    if (b->pb.ntest) { /* the tests may depend on the orientation */
      int rc = b->pb.test(p->u, p->t, p->psi, b->pb.user);
      st = callback_status(b, rc, p->psi, b->pb.ntest, "test function", msg);
      if (st == SC_CONTINUE) st = SC_ENOCONV;
      if (st) return st;
    }
  }
  for (size_t k = 0; k < b->pb.ntest; k++) b->sign[k] = sgn(p->psi[k]);
  b->location = (sc_cont_location){.test = -1};
  b->h = b->set.h0;
  b->ready = 1;
  b->npoints++;
  return SC_OK;
}

/* ------------------------------------------------------------------ */
/* Location of a zero of test k between cur (s = 0) and trial (s = h)   */
/* ------------------------------------------------------------------ */

/* Illinois-modified regula falsi in arclength, with bisection when the
 * secant point leaves the bracket.  Stops when (the last step in s is
 * within tolerance and |psi| <= test_atol) or the bracket is within
 * tolerance; accepts only the first.  The located point is in b->loc.
 * Returns SC_OK (see b->location.accepted) or a negative error. */
static int locate(sc_branch *b, size_t k, double h, sc_msg *msg) {
  double sa = 0, sb = h, fa = b->cur.psi[k], fb = b->trial.psi[k];
  double slast = h;
  int side = 0;
  sc_cont_location *L = &b->location;
  L->test = (int)k;
  L->accepted = 0;
  L->psi = fb;
  L->ds = h;
  L->width = h;
  L->iterations = 0;
  for (int it = 1; it <= b->set.max_locate_iter; it++) {
    double s = (sa * fb - sb * fa) / (fb - fa);
    if (!(s > sa && s < sb)) s = 0.5 * (sa + sb);
    int st = point_at(b, s, &b->loc, msg);
    b->nlocate++;
    L->iterations = it;
    if (st < 0) return st;
    if (st) return SC_OK; /* the corrector failed inside: not accepted */
    double f = b->loc.psi[k];
    L->psi = f;
    L->ds = s - slast;
    slast = s;
    if (sgn(f) == sgn(fa)) {
      sa = s;
      fa = f;
      if (side == -1) fb *= 0.5; /* Illinois: the other end is stuck */
      side = -1;
    } else {
      sb = s;
      fb = f;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
    L->width = sb - sa;
    double tol = b->acc.newton_atol +
                 b->acc.newton_rtol * norm_inf(b->loc.u, b->N);
    int small_f = fabs(f) <= b->set.test_atol;
    if ((fabs(L->ds) <= tol && small_f) || f == 0) {
      L->accepted = 1;
      return SC_OK;
    }
    if (L->width <= tol) {
      L->accepted = small_f;
      return SC_OK;
    }
  }
  return SC_OK;
}

/* ------------------------------------------------------------------ */
/* Step                                                                */
/* ------------------------------------------------------------------ */

/* The point where the branch crosses u[n] = pe, between cur and trial:
 * Newton with the parameter fixed, from the secant guess; into trial.
 * Returns the arclength coordinate t.(u - cur.u) in *s. */
static int end_point(sc_branch *b, double pe, double *s, sc_msg *msg) {
  size_t N = b->N, n = b->n;
  double lam = (pe - b->cur.u[n]) / (b->trial.u[n] - b->cur.u[n]);
  for (size_t i = 0; i < N; i++) {
    b->trial.u[i] = b->cur.u[i] + lam * (b->trial.u[i] - b->cur.u[i]);
    b->border[i] = i == n;
  }
  b->trial.u[n] = pe;
  int st = newton(b, b->trial.u, b->border, pe, &b->trial.newton_iter, msg);
  if (st) return st;
  st = finish_point(b, &b->trial, b->cur.t, msg);
  if (st) return st;
  double d = 0;
  for (size_t i = 0; i < N; i++) d += b->cur.t[i] * (b->trial.u[i] - b->cur.u[i]);
  *s = d;
  return SC_OK;
}

int sc_branch_step(sc_branch *b, sc_msg *msg) {
  if (!b->ready)
    return sc_fail(msg, SC_EINVAL,
                   "sc_branch_step: no current point (call sc_branch_set)");
  if (b->ended) return SC_END;
  size_t N = b->N, n = b->n, nt = b->pb.ntest;
  double h;
  int at_end = 0;
  for (;;) {
    h = b->h;
    int st = point_at(b, h, &b->trial, msg);
    if (st < 0) return st;
    if (st == SC_OK) {
      /* Past the end of the parameter interval: replace the trial point
       * by the branch point on the boundary. */
      double p = b->trial.u[n];
      if (p > b->set.pmax || p < b->set.pmin) {
        double pe = p > b->set.pmax ? b->set.pmax : b->set.pmin;
        st = end_point(b, pe, &h, msg);
        if (st < 0) return st;
        at_end = st == SC_OK;
      }
    }
    if (st == SC_OK) break;
    b->nrejected++;
    b->h *= b->set.shrink;
    if (b->h < b->set.hmin)
      return sc_fail(msg, SC_ENOCONV,
                     "sc_branch_step: step %.3g below hmin = %.3g at "
                     "u[%zu] = %.17g (last corrector: %s)",
                     b->h, b->set.hmin, n, b->cur.u[n],
                     sc_corr_reason_text(b->reason));
  }
  if (b->trial.newton_iter <= b->set.fast_iter && !at_end)
    b->h = fmin(b->h * b->set.grow, b->set.hmax);

  /* Sign changes of the test functions between cur and trial. */
  int found = -1;
  double sbest = HUGE_VAL;
  for (size_t k = 0; k < nt; k++) {
    int s1 = sgn(b->trial.psi[k]);
    if (b->sign[k] == 0) {
      b->sign[k] = s1;
      continue;
    }
    if (s1 == 0 || s1 == b->sign[k]) continue;
    int st = locate(b, k, h, msg);
    if (st) return st;
    if (!b->location.accepted) {
      b->sign[k] = s1; /* a jump, not a zero: pass it */
      b->nrej_special++;
      continue;
    }
    double sl = dot(b->cur.t, b->loc.u, N) - dot(b->cur.t, b->cur.u, N);
    if (sl < sbest) {
      sbest = sl;
      found = (int)k;
      point_copy(&b->best, &b->loc, N, nt);
      b->best_location = b->location;
    }
  }
  if (found >= 0) {
    /* The located point becomes the current one; tests located further
     * along keep their sign and are found again by the next step. */
    b->sign[found] = sgn(b->trial.psi[found]);
    point_copy(&b->cur, &b->best, N, nt);
    b->location = b->best_location; /* the last locate() may be another */
    b->npoints++;
    b->nspecial++;
    return SC_SPECIAL;
  }
  point_copy(&b->cur, &b->trial, N, nt);
  b->npoints++;
  if (at_end || (long)b->npoints >= b->set.max_points) {
    b->ended = 1;
    return SC_END;
  }
  return SC_CONTINUE;
}

int sc_branch_solve(sc_branch *b, const double *u0, sc_branch_fn fn,
                    void *ctx, sc_msg *msg) {
  int st = sc_branch_set(b, u0, msg);
  if (st) return st;
  if (fn && fn(ctx, b, SC_POINT_START))
    return sc_fail(msg, SC_ECALLBACK, "sc_branch_solve: stopped by the "
                                      "caller at the start");
  for (;;) {
    st = sc_branch_step(b, msg);
    if (st < 0) return st;
    sc_point_kind kind = st == SC_SPECIAL ? SC_POINT_SPECIAL
                         : st == SC_END   ? SC_POINT_END
                                          : SC_POINT_REGULAR;
    if (fn && fn(ctx, b, kind))
      return sc_fail(msg, SC_ECALLBACK,
                     "sc_branch_solve: stopped by the caller at point %lu",
                     b->npoints);
    if (st == SC_END) return SC_OK;
  }
}

/* ------------------------------------------------------------------ */
/* Getters                                                             */
/* ------------------------------------------------------------------ */

size_t sc_branch_dim(const sc_branch *b) { return b->N; }
const double *sc_branch_point(const sc_branch *b) { return b->cur.u; }
const double *sc_branch_tangent(const sc_branch *b) { return b->cur.t; }
const double *sc_branch_test_values(const sc_branch *b) { return b->cur.psi; }
double sc_branch_step_size(const sc_branch *b) { return b->h; }
sc_corr_reason sc_branch_reason(const sc_branch *b) { return b->reason; }
const sc_cont_location *sc_branch_location(const sc_branch *b) {
  return &b->location;
}
int sc_branch_bordered_det(const sc_branch *b, int *sign, double *logabs) {
  if (!b->ready) return SC_EINVAL;
  *sign = b->cur.det_sign;
  *logabs = b->cur.det_log;
  return SC_OK;
}
unsigned long sc_branch_npoints(const sc_branch *b) { return b->npoints; }
unsigned long sc_branch_nspecial(const sc_branch *b) { return b->nspecial; }
unsigned long sc_branch_nrejected_special(const sc_branch *b) {
  return b->nrej_special;
}
unsigned long sc_branch_nrejected(const sc_branch *b) { return b->nrejected; }
unsigned long sc_branch_nnewton(const sc_branch *b) { return b->nnewton; }
unsigned long sc_branch_nfeval(const sc_branch *b) { return b->nfeval; }
unsigned long sc_branch_njac(const sc_branch *b) { return b->njac; }
unsigned long sc_branch_nlocate(const sc_branch *b) { return b->nlocate; }
const sc_linsolve *sc_branch_linsolve(const sc_branch *b) { return b->ls; }
