/* Shooting for periodic orbits of maps of n dimensions: Newton on
 * f^m(x) - x (single) or on the block-cyclic system f(x_k) - x_(k+1)
 * (multiple), with the exact Jacobians of sc_map_iterate_n(), deflation
 * of known orbits, and the multipliers of the orbit.  See shooting.h. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/shooting.h"

/* A Newton step within this many ulps of the unknown cannot be improved
 * on: the residual is then at the rounding level of the map (as the
 * one-dimensional shooting). */
#define STAGNATION_ULPS 4.0

/* The residual tolerance of single shooting grows with ||J_g|| (the
 * rounding of f^m), but no further than this: beyond it f^m carries less
 * than half the digits of a double, f^m(x) - x can no longer certify an
 * orbit (it would accept residuals of order 1 for the chaotic orbits of
 * long period), and multiple shooting is the method. */
#define SINGLE_FTOL_GROWTH_MAX (1 / 1.4901161193847656e-08) /* 1 / sqrt(eps) */

/* A deflated step divides F's Newton step by 1 - tau; where |1 - tau| is
 * below this the deflated step is not defined (it would be longer than
 * 1 / DBL_EPSILON times F's step): reported as a singular matrix. */
#define DEFLATE_MIN_DENOM (16 * DBL_EPSILON)

struct sc_shootn {
  sc_map *map;
  int period;
  sc_shoot_method method;
  size_t n;   /* state dimension */
  size_t N;   /* unknowns: n (single) or period n (multiple) */
  const sc_linsolve_type *lstype;
  sc_linsolve *ls;
  sc_mapn_value *v;
  /* unknowns, residuals and Jacobians at the current point and the trial
   * one (J: n^2 of J_g for single shooting, m n^2 of J(x_k) for
   * multiple) */
  double *x, *xtry, *F, *Ftry, *J, *Jtry;
  double *dx, *val, *seed;
  double *orbit, *Jorb;       /* m n points, m n^2 Jacobians at them */
  sc_product_eigs_work *eig;  /* multipliers of m factors of order n */
  const double **factors;     /* m pointers into Jorb */
  double *re, *im;            /* n each */
  /* deflated orbits: their points one after another, their periods */
  double *defl;
  int *deflq;
  double *deflL;
  size_t ndefl, ndeflpts, capdefl, capdeflpts;
  unsigned long nnewton;
};

const char *sc_shootn_reason_text(sc_shootn_reason r) {
  switch (r) {
  case SC_SHOOTN_CONVERGED: return "converged";
  case SC_SHOOTN_MAXITER: return "no convergence in newton-maxiter iterations";
  case SC_SHOOTN_NO_DECREASE: return "no step decreases the residual";
  case SC_SHOOTN_SINGULAR: return "singular Jacobian";
  case SC_SHOOTN_UNDEFINED: return "map undefined or infinite";
  }
  return "?";
}

/* Block-cyclic pattern of multiple shooting over N = m n unknowns: column
 * j n + l holds J(x_j)[., l] in rows j n .. j n + n - 1 and the -1 of
 * dF_(j-1)/dx_j in row ((j - 1) mod m) n + l (sorted; m = 1: J - I). */
static int cyclic_pattern(const sc_shootn *s, sc_linsolve **out,
                          sc_msg *msg) {
  size_t n = s->n, m = (size_t)s->period, N = s->N;
  int *colptr = malloc((N + 1) * sizeof *colptr);
  int *rowind = malloc(N * (n + 1) * sizeof *rowind);
  int st = SC_ENOMEM;
  if (colptr && rowind) {
    int k = 0;
    for (size_t j = 0; j < m; j++)
      for (size_t l = 0; l < n; l++) {
        colptr[j * n + l] = k;
        int id = (int)(((j + m - 1) % m) * n + l);
        if (m > 1 && j > 0) rowind[k++] = id;
        for (size_t i = 0; i < n; i++) rowind[k++] = (int)(j * n + i);
        if (m > 1 && j == 0) rowind[k++] = id;
      }
    colptr[N] = k;
    st = sc_linsolve_alloc(s->lstype, (int)N, colptr, rowind, out, msg);
  } else {
    sc_fail(msg, st, "sc_shootn_alloc: out of memory");
  }
  free(colptr);
  free(rowind);
  return st;
}

int sc_shootn_alloc(sc_map *m, int period, sc_shoot_method method,
                    const sc_linsolve_type *ls, sc_shootn **out,
                    sc_msg *msg) {
  *out = NULL;
  if (!m) return sc_fail(msg, SC_EINVAL, "sc_shootn_alloc: no map");
  if (period < 1 || period > SC_SHOOTN_MAX_PERIOD)
    return sc_fail(msg, SC_EINVAL,
                   "sc_shootn_alloc: period = %d (valid: [1, %d])", period,
                   SC_SHOOTN_MAX_PERIOD);
  if (method != SC_SHOOT_SINGLE && method != SC_SHOOT_MULTIPLE)
    return sc_fail(msg, SC_EINVAL,
                   "sc_shootn_alloc: method = %d (valid: SC_SHOOT_SINGLE, "
                   "SC_SHOOT_MULTIPLE)",
                   (int)method);
  sc_shootn *s = calloc(1, sizeof *s);
  if (!s) return sc_fail(msg, SC_ENOMEM, "sc_shootn_alloc: out of memory");
  s->map = m;
  s->period = period;
  s->method = method;
  size_t n = s->n = sc_map_dim(m), mp = (size_t)period;
  s->N = method == SC_SHOOT_SINGLE ? n : mp * n;
  size_t nJ = method == SC_SHOOT_SINGLE ? n * n : mp * n * n;
  int st = sc_mapn_value_alloc(m, SC_EVAL_DERIV, &s->v, msg);
  if (st) goto fail;
  st = SC_ENOMEM;
  s->x = malloc(s->N * sizeof *s->x);
  s->xtry = malloc(s->N * sizeof *s->xtry);
  s->F = malloc(s->N * sizeof *s->F);
  s->Ftry = malloc(s->N * sizeof *s->Ftry);
  s->dx = malloc(s->N * sizeof *s->dx);
  s->J = malloc(nJ * sizeof *s->J);
  s->Jtry = malloc(nJ * sizeof *s->Jtry);
  s->val = malloc(s->N * (n + 1) * sizeof *s->val);
  s->seed = malloc(mp * n * sizeof *s->seed);
  s->orbit = malloc(mp * n * sizeof *s->orbit);
  s->Jorb = malloc(mp * n * n * sizeof *s->Jorb);
  s->factors = malloc(mp * sizeof *s->factors);
  s->re = calloc(n, sizeof *s->re);
  s->im = calloc(n, sizeof *s->im);
  if (!s->x || !s->xtry || !s->F || !s->Ftry || !s->dx || !s->J ||
      !s->Jtry || !s->val || !s->seed || !s->orbit || !s->Jorb ||
      !s->factors || !s->re || !s->im) {
    sc_fail(msg, st, "sc_shootn_alloc: out of memory");
    goto fail;
  }
  st = sc_product_eigs_work_alloc(n, mp, &s->eig, msg);
  if (st) goto fail;
  if (method == SC_SHOOT_SINGLE) {
    s->lstype = sc_linsolve_dense;
    st = sc_linsolve_alloc_full(s->lstype, (int)n, &s->ls, msg);
  } else {
    s->lstype = ls ? ls
                   : period <= SC_SHOOT_DENSE_MAX ? sc_linsolve_dense
                                                  : sc_linsolve_klu;
    st = cyclic_pattern(s, &s->ls, msg);
  }
  if (st) goto fail;
  *out = s;
  return SC_OK;
fail:
  sc_shootn_free(s);
  return st;
}

void sc_shootn_free(sc_shootn *s) {
  if (!s) return;
  sc_linsolve_free(s->ls);
  sc_mapn_value_free(s->v);
  free(s->x);
  free(s->xtry);
  free(s->F);
  free(s->Ftry);
  free(s->dx);
  free(s->J);
  free(s->Jtry);
  free(s->val);
  free(s->seed);
  free(s->orbit);
  free(s->Jorb);
  sc_product_eigs_work_free(s->eig);
  free(s->factors);
  free(s->re);
  free(s->im);
  free(s->defl);
  free(s->deflq);
  free(s->deflL);
  free(s);
}

const double *sc_shootn_orbit(const sc_shootn *s) { return s->orbit; }
void sc_shootn_multipliers(const sc_shootn *s, const double **re,
                           const double **im) {
  *re = s->re;
  *im = s->im;
}
int sc_shootn_period(const sc_shootn *s) { return s->period; }
size_t sc_shootn_dim(const sc_shootn *s) { return s->n; }
unsigned long sc_shootn_nnewton(const sc_shootn *s) { return s->nnewton; }

int sc_shootn_deflate(sc_shootn *s, const double *orbit, int q, double scale,
                      sc_msg *msg) {
  if (q < 1 || s->period % q != 0)
    return sc_fail(msg, SC_EINVAL,
                   "sc_shootn_deflate: period %d does not divide %d", q,
                   s->period);
  if (!(scale > 0) || !isfinite(scale))
    return sc_fail(msg, SC_EINVAL,
                   "sc_shootn_deflate: scale = %g (valid: finite, > 0)",
                   scale);
  size_t n = s->n, need = s->ndeflpts + (size_t)q * n;
  if (s->ndefl == s->capdefl) {
    size_t cap = s->capdefl ? 2 * s->capdefl : 16;
    int *qq = realloc(s->deflq, cap * sizeof *qq);
    if (!qq) return sc_fail(msg, SC_ENOMEM, "sc_shootn_deflate: out of memory");
    s->deflq = qq;
    double *ll = realloc(s->deflL, cap * sizeof *ll);
    if (!ll) return sc_fail(msg, SC_ENOMEM, "sc_shootn_deflate: out of memory");
    s->deflL = ll;
    s->capdefl = cap;
  }
  if (need > s->capdeflpts) {
    size_t cap = 2 * need;
    double *d = realloc(s->defl, cap * sizeof *d);
    if (!d) return sc_fail(msg, SC_ENOMEM, "sc_shootn_deflate: out of memory");
    s->defl = d;
    s->capdeflpts = cap;
  }
  for (size_t i = 0; i < (size_t)q * n; i++)
    if (!isfinite(orbit[i]))
      return sc_fail(msg, SC_EINVAL,
                     "sc_shootn_deflate: orbit value %zu is not finite", i);
  memcpy(s->defl + s->ndeflpts, orbit, (size_t)q * n * sizeof *orbit);
  s->deflq[s->ndefl] = q;
  s->deflL[s->ndefl] = scale;
  s->ndefl++;
  s->ndeflpts = need;
  return SC_OK;
}

void sc_shootn_deflate_clear(sc_shootn *s) {
  s->ndefl = 0;
  s->ndeflpts = 0;
}

/* ln M(x) and tau = grad(ln M) . d for the deflated orbits (see
 * sc_shootn_deflate()); d may be NULL (then tau is not computed).  A
 * factor at distance exactly 0 is left out: x is then a known root, F
 * vanishes there and the caller's convergence test sees it. */
static void deflation(const sc_shootn *s, const double *x, const double *d,
                      double *lnM, double *tau) {
  *lnM = 0;
  if (tau) *tau = 0;
  size_t n = s->n, m = (size_t)s->period;
  const double p = SC_SHOOTN_DEFLATE_POWER, sigma = SC_SHOOTN_DEFLATE_SHIFT;
  const double *o = s->defl;
  for (size_t j = 0; j < s->ndefl; o += (size_t)s->deflq[j] * n, j++) {
    size_t q = (size_t)s->deflq[j];
    for (size_t r = 0; r < q; r++) {
      /* root r: point r (single), rotation from point r (multiple) */
      double d2 = 0, dot = 0;
      size_t np = s->method == SC_SHOOT_SINGLE ? 1 : m;
      for (size_t k = 0; k < np; k++)
        for (size_t c = 0; c < n; c++) {
          double e = x[k * n + c] - o[((r + k) % q) * n + c];
          d2 += e * e;
          if (d) dot += e * d[k * n + c];
        }
      if (d2 == 0) continue;
      double u = pow(s->deflL[j] * s->deflL[j] / d2, 0.5 * p);
      *lnM += log(u + sigma);
      if (tau) *tau += -p * dot / d2 * (u / (u + sigma));
    }
  }
}

static double maxabs(const double *v, size_t n) {
  double r = 0;
  for (size_t i = 0; i < n; i++) r = fmax(r, fabs(v[i]));
  return r;
}

/* ln of the merit M(x) ||F||_2 of damped Newton (-inf for F = 0). */
static double ln_merit(const sc_shootn *s, const double *x, const double *F) {
  double r = 0, lnM;
  for (size_t i = 0; i < s->N; i++) r = hypot(r, F[i]);
  deflation(s, x, NULL, &lnM, NULL);
  return log(r) + lnM;
}

/* Residual F and Jacobian(s) J at x (see struct sc_shootn). */
static int residual(sc_shootn *s, const double *x, double *F, double *J,
                    sc_msg *msg) {
  size_t n = s->n;
  if (s->method == SC_SHOOT_SINGLE) {
    int st = sc_map_iterate_n(s->map, x, s->period, SC_EVAL_DERIV, s->v, msg);
    if (st) return st;
    for (size_t i = 0; i < n; i++) F[i] = s->v->f[i] - x[i];
    memcpy(J, s->v->J, n * n * sizeof *J);
    return SC_OK;
  }
  size_t m = (size_t)s->period;
  for (size_t k = 0; k < m; k++) {
    int st = sc_map_eval_n(s->map, x + k * n, SC_EVAL_DERIV, s->v, msg);
    if (st) {
      if (msg) {
        char tail[SC_MSG_LEN];
        snprintf(tail, sizeof tail, "%s", msg->text);
        sc_fail(msg, st, "orbit point %zu of %zu: %.400s", k + 1, m, tail);
      }
      return st;
    }
    const double *next = x + ((k + 1) % m) * n;
    for (size_t i = 0; i < n; i++) F[k * n + i] = s->v->f[i] - next[i];
    memcpy(J + k * n * n, s->v->J, n * n * sizeof *J);
  }
  return SC_OK;
}

/* F's Newton step -Jac^-1 F into s->dx at the current point. */
static int newton_step(sc_shootn *s, sc_msg *msg) {
  size_t n = s->n, N = s->N;
  size_t k = 0;
  if (s->method == SC_SHOOT_SINGLE) {
    /* column-major J_g - I */
    for (size_t j = 0; j < n; j++)
      for (size_t i = 0; i < n; i++)
        s->val[k++] = s->J[i * n + j] - (i == j);
  } else {
    size_t m = (size_t)s->period;
    for (size_t j = 0; j < m; j++) {
      const double *Jj = s->J + j * n * n;
      for (size_t l = 0; l < n; l++) {
        if (m > 1 && j > 0) s->val[k++] = -1;
        for (size_t i = 0; i < n; i++)
          s->val[k++] = Jj[i * n + l] - (m == 1 && i == l);
        if (m > 1 && j == 0) s->val[k++] = -1;
      }
    }
  }
  int st = sc_linsolve_factor(s->ls, s->val, msg);
  if (st) return st;
  for (size_t i = 0; i < N; i++) s->dx[i] = -s->F[i];
  return sc_linsolve_solve(s->ls, s->dx, msg);
}

/* The multipliers of the orbit: eigenvalues of J(x_(m-1)) ... J(x_0)
 * from s->Jorb into s->re, s->im, by the periodic Schur decomposition
 * (sc_product_eigs_compute(), linalg.h), which does not form the product
 * and so keeps multipliers that are tiny against the largest one; its
 * order is decreasing modulus, ties by decreasing real part, a complex
 * pair with its positive imaginary part first. */
static int multipliers(sc_shootn *s, sc_msg *msg) {
  size_t n = s->n, m = (size_t)s->period;
  for (size_t k = 0; k < m; k++) s->factors[k] = s->Jorb + k * n * n;
  return sc_product_eigs_compute(s->eig, s->factors, s->re, s->im, NULL,
                                 NULL, msg);
}

/* The orbit points and the Jacobians at them, the multipliers, the
 * certificate: res filled at the converged point. */
static int finish(sc_shootn *s, sc_shootn_result *res, sc_msg *msg) {
  size_t n = s->n, m = (size_t)s->period;
  if (s->method == SC_SHOOT_SINGLE)
    memcpy(s->orbit, s->x, n * sizeof *s->x);
  else
    memcpy(s->orbit, s->x, m * n * sizeof *s->x);
  for (size_t k = 0; k < m; k++) {
    int st = sc_map_eval_n(s->map, s->orbit + k * n, SC_EVAL_DERIV, s->v, msg);
    if (st) return st;
    memcpy(s->Jorb + k * n * n, s->v->J, n * n * sizeof *s->Jorb);
    if (s->method == SC_SHOOT_SINGLE && k + 1 < m)
      memcpy(s->orbit + (k + 1) * n, s->v->f, n * sizeof *s->orbit);
  }
  int st = multipliers(s, msg);
  if (st) return st;
  res->reason = SC_SHOOTN_CONVERGED;
  res->residual = maxabs(s->F, s->N);
  res->multiplier = s->im[0] == 0 ? s->re[0] : hypot(s->re[0], s->im[0]);
  res->stable = hypot(s->re[0], s->im[0]) < 1;
  return SC_OK;
}

/* Every component of the step within newton_atol + newton_rtol |x|. */
static int step_within_tol(const sc_shootn *s, const sc_accuracy *acc) {
  for (size_t i = 0; i < s->N; i++)
    if (sc_test_delta(s->dx[i], s->x[i], acc->newton_atol,
                      acc->newton_rtol) != SC_OK)
      return 0;
  return 1;
}

/* Converged after the last step (see sc_shootn_solve()). */
static int converged(const sc_shootn *s, const sc_accuracy *acc, double fnorm,
                     double ftol, double last, double before_last) {
  if (!(fnorm <= ftol)) return 0;
  int stagnant = 1;
  for (size_t i = 0; i < s->N; i++)
    if (fabs(s->dx[i]) > STAGNATION_ULPS * DBL_EPSILON * fabs(s->x[i]))
      stagnant = 0;
  return step_within_tol(s, acc) || stagnant || last >= 0.5 * before_last;
}

/* The residual tolerance at the current point: single shooting scales it
 * by max(1, ||J_g||_inf), the growth of the rounding of f^m. */
static double residual_tol(const sc_shootn *s, const sc_accuracy *acc) {
  double ftol = acc->newton_ftol;
  if (s->method != SC_SHOOT_SINGLE) return ftol;
  double norm = 0;
  for (size_t i = 0; i < s->n; i++) {
    double row = 0;
    for (size_t j = 0; j < s->n; j++) row += fabs(s->J[i * s->n + j]);
    norm = fmax(norm, row);
  }
  return isfinite(norm) ? ftol * fmin(fmax(1, norm), SINGLE_FTOL_GROWTH_MAX)
                        : ftol;
}

/* A failed solve: reason and status, the message with the point. */
static int give_up(sc_shootn *s, sc_shootn_result *res, sc_shootn_reason why,
                   int st, double fnorm, sc_msg *msg) {
  res->reason = why;
  res->residual = fnorm;
  if (msg && why != SC_SHOOTN_UNDEFINED && why != SC_SHOOTN_SINGULAR)
    sc_fail(msg, st,
            "sc_shootn_solve: %s (period %d, %s shooting, %d iterations; "
            "residual %.3g, last step %.3g, x_0 = (%.17g%s))",
            sc_shootn_reason_text(why), s->period,
            s->method == SC_SHOOT_SINGLE ? "single" : "multiple",
            res->iterations, fnorm, res->step, s->x[0], s->n > 1 ? ", ..." : "");
  return st;
}

/* One damped step from s->x along s->dx (already deflated): the trial
 * point is accepted into s->x, s->F, s->J; *lambda is the factor taken. */
static int damped_step(sc_shootn *s, const sc_accuracy *acc, double ftol,
                       double *lambda, sc_shootn_reason *why, sc_msg *msg) {
  size_t N = s->N;
  int tiny = step_within_tol(s, acc);
  double merit = ln_merit(s, s->x, s->F);
  *lambda = 1;
  for (int h = 0;; h++) {
    for (size_t i = 0; i < N; i++) s->xtry[i] = s->x[i] + *lambda * s->dx[i];
    int st = residual(s, s->xtry, s->Ftry, s->Jtry, msg);
    if (st == SC_OK) {
      if (tiny || maxabs(s->Ftry, N) <= ftol ||
          ln_merit(s, s->xtry, s->Ftry) < merit)
        break;
      if (h >= SC_SHOOT_MAX_HALVINGS) {
        *why = SC_SHOOTN_NO_DECREASE;
        return SC_ENOCONV;
      }
    } else if ((st != SC_EUNDEF && st != SC_ENONFINITE && st != SC_ENOCONV) ||
               h >= SC_SHOOT_MAX_HALVINGS) {
      *why = SC_SHOOTN_UNDEFINED;
      return st;
    }
    *lambda *= 0.5;
  }
  for (size_t i = 0; i < N; i++) s->dx[i] *= *lambda;
  double *t = s->x;
  s->x = s->xtry;
  s->xtry = t;
  t = s->F;
  s->F = s->Ftry;
  s->Ftry = t;
  t = s->J;
  s->J = s->Jtry;
  s->Jtry = t;
  return SC_OK;
}

int sc_shootn_solve_orbit(sc_shootn *s, const double *x0,
                          sc_shootn_result *res, sc_msg *msg) {
  memset(res, 0, sizeof *res);
  res->step = HUGE_VAL;
  sc_accuracy acc; /* no tighter than the map's precision */
  sc_map_solver_accuracy(s->map, &acc);
  for (size_t i = 0; i < s->N; i++) {
    if (!isfinite(x0[i]))
      return sc_fail(msg, SC_EINVAL,
                     "sc_shootn_solve: guess value %zu = %g is not finite",
                     i + 1, x0[i]);
    s->x[i] = x0[i];
  }
  int st = residual(s, s->x, s->F, s->J, msg);
  if (st) {
    res->reason = SC_SHOOTN_UNDEFINED;
    return st;
  }
  double last = HUGE_VAL, before_last = HUGE_VAL;
  for (int it = 0;; it++) {
    res->iterations = it;
    double fnorm = maxabs(s->F, s->N), ftol = residual_tol(s, &acc);
    if (it > 0 && converged(s, &acc, fnorm, ftol, last, before_last)) {
      res->step = last;
      return finish(s, res, msg);
    }
    if (it >= acc.newton_maxiter)
      return give_up(s, res, SC_SHOOTN_MAXITER, SC_ENOCONV, fnorm, msg);
    st = newton_step(s, msg);
    if (st == SC_ESING && fnorm <= acc.newton_ftol) {
      /* within the unscaled tolerance where the matrix is singular (a
       * start at a fold); the scaled one would accept any point where
       * J_g is huge, and J_g - I then singular in rounding */
      res->step = it == 0 ? 0 : last;
      return finish(s, res, msg);
    }
    if (st == SC_ESING || st == SC_ENONFINITE)
      return give_up(s, res, SC_SHOOTN_SINGULAR, SC_ESING, fnorm, msg);
    if (st) return st;
    s->nnewton++;
    if (s->ndefl) {
      double lnM, tau;
      deflation(s, s->x, s->dx, &lnM, &tau);
      if (!(fabs(1 - tau) > DEFLATE_MIN_DENOM)) {
        sc_fail(msg, SC_ESING,
                "sc_shootn_solve: the deflated Newton step is not defined "
                "(1 - grad(ln M) . d = %.3g) at x_0 = (%.17g, ...)",
                1 - tau, s->x[0]);
        return give_up(s, res, SC_SHOOTN_SINGULAR, SC_ESING, fnorm, msg);
      }
      for (size_t i = 0; i < s->N; i++) s->dx[i] /= 1 - tau;
    }
    double lambda;
    sc_shootn_reason why;
    st = damped_step(s, &acc, ftol, &lambda, &why, msg);
    if (st) return give_up(s, res, why, st, fnorm, msg);
    before_last = last;
    last = res->step = maxabs(s->dx, s->N);
  }
}

int sc_shootn_solve(sc_shootn *s, const double *x0, sc_shootn_result *res,
                    sc_msg *msg) {
  size_t n = s->n;
  for (size_t i = 0; i < n; i++)
    if (!isfinite(x0[i])) {
      memset(res, 0, sizeof *res);
      return sc_fail(msg, SC_EINVAL,
                     "sc_shootn_solve: guess component %zu = %g is not "
                     "finite",
                     i + 1, x0[i]);
    }
  memcpy(s->seed, x0, n * sizeof *x0);
  if (s->method == SC_SHOOT_MULTIPLE)
    for (int k = 1; k < s->period; k++) {
      int st = sc_map_eval_n(s->map, s->seed + (size_t)(k - 1) * n,
                             SC_EVAL_VALUE, s->v, msg);
      if (st) {
        memset(res, 0, sizeof *res);
        res->reason = SC_SHOOTN_UNDEFINED;
        return st;
      }
      memcpy(s->seed + (size_t)k * n, s->v->f, n * sizeof *x0);
    }
  return sc_shootn_solve_orbit(s, s->seed, res, msg);
}
