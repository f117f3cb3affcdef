/* Orbit branches by multiple shooting: a segment whose orbit amplifies
 * the map's error beyond what single shooting resolves is continued in
 * u = (x_0, ..., x_{m-1}, p) on
 *
 *   F_k = f_k(x_k) - x_{k+1 mod m} = 0,   k < m,
 *
 * each f_k one iterate along the segment's code for it, as the shooting
 * of starts (src/map/shooting.c) and the curves' multiple shooting
 * (continuation/curve_ms.c) do; its Jacobian is block-cyclic (f_k' on the
 * diagonal, -1 next to it, f_p in the parameter's column).  Each equation
 * carries one iterate's error, not the product's.  Borders are watched
 * per iterate, each from its own point, and a border is located by
 * Newton on this system plus the border's own equation on the iterate
 * that meets it (for a border in the state, that iterate is put on it).
 * See docs/branches.md, "Multiple shooting". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/branch_orbit_impl.h"
#include "slipcont/linalg.h"

/* The switch: single shooting's residual f^m(d) - d carries the map's
 * error (sc_map_precision()) times the orbit's multiplier, and its
 * Newton step moves the late iterates of the orbit by as much.  Once that
 * exceeds MS_SWITCH_ORBIT_TOLS times the orbit tolerance (sc_orbit_tol(),
 * the distance within which two orbits are one), the point single
 * shooting returns is not known to be the orbit any more: the segment is
 * continued by multiple shooting.  1: at the very tolerance by which the
 * rest of the branch identifies orbits.  Closed forms (precision 0)
 * never switch. */
#define MS_SWITCH_ORBIT_TOLS 1.0

int sc_ob_ms_wanted(const sc_orbit_branch *b, int period, double d,
                    double mult) {
  double prec = sc_map_precision(b->m);
  if (!(prec > 0) || period < 2) return 0;
  return prec * fabs(mult) > MS_SWITCH_ORBIT_TOLS * sc_orbit_tol(&b->acc, d);
}

/* The per-iterate values at u into S->ms_val: f, f' and f_p of iterate
 * k at 3 k .. 3 k + 2; after them the point they were taken at (m + 1)
 * and 1 once valid.  The corrector asks F and then the Jacobian at one
 * point: evaluated once. */
static int ms_values(segment *S, const double *u) {
  sc_orbit_branch *b = S->ob;
  int m = S->period;
  double *val = S->ms_val, *at = val + 3 * m, *have = at + m + 1;
  if (*have > 0 && memcmp(at, u, (size_t)(m + 1) * sizeof *u) == 0) return 0;
  *have = 0;
  if (sc_ob_set_p(b->m, b->sp.param, u[m])) return 1;
  sc_map_value v;
  int st = sc_map_iterate_points(b->m, u, m, SC_EVAL_DERIV, b->codes, NULL,
                                 b->sp.param, NULL, val, &v, NULL);
  if (st)
    return st == SC_EUNDEF || st == SC_ENONFINITE || st == SC_ENOCONV ? 1 : -1;
  if (v.neutral) return 1;
  memcpy(at, u, (size_t)(m + 1) * sizeof *u);
  *have = 1;
  return 0;
}

static int ms_f(const double *u, double *F, void *user) {
  segment *S = user;
  int m = S->period;
  int rc = ms_values(S, u);
  if (rc) return rc;
  for (int k = 0; k < m; k++) F[k] = S->ms_val[3 * k] - u[(k + 1) % m];
  return 0;
}

/* Row-major m x (m + 1). */
static int ms_jac(const double *u, double *J, void *user) {
  segment *S = user;
  int m = S->period, N = m + 1;
  int rc = ms_values(S, u);
  if (rc) return rc;
  memset(J, 0, (size_t)m * (size_t)N * sizeof *J);
  for (int k = 0; k < m; k++) {
    J[k * N + k] += S->ms_val[3 * k + 1];
    J[k * N + (k + 1) % m] -= 1;
    J[k * N + m] = S->ms_val[3 * k + 2];
  }
  return 0;
}

/* fold and flip: the multiplier, the product of the f_k', at -+ 1 */
static int ms_test(const double *u, const double *t, double *psi,
                   void *user) {
  segment *S = user;
  (void)t;
  int rc = ms_values(S, u);
  if (rc) return rc;
  double mult = 1;
  for (int k = 0; k < S->period; k++) mult *= S->ms_val[3 * k + 1];
  psi[0] = mult - 1;
  psi[1] = mult + 1;
  return 0;
}

static const char *const ms_test_names[] = {"fold", "flip"};

int sc_ob_ms_problem(sc_orbit_branch *b, segment *S, sc_cont_problem *pb,
                     sc_msg *msg) {
  size_t N = (size_t)S->period + 1;
  S->ob = b;
  S->ms_last = calloc(N, sizeof(double));
  S->ms_tan = calloc(N, sizeof(double));
  S->ms_try = calloc(N, sizeof(double));
  S->ms_best = calloc(N, sizeof(double));
  S->ms_start = calloc(N, sizeof(double));
  S->ms_rhs = calloc(N, sizeof(double));
  S->ms_mat = calloc(N * N, sizeof(double));
  S->ms_val = calloc(4 * N + 1, sizeof(double));
  if (!S->ms_last || !S->ms_tan || !S->ms_try || !S->ms_best || !S->ms_start ||
      !S->ms_rhs || !S->ms_mat || !S->ms_val)
    return sc_fail(msg, SC_ENOMEM, "branch: out of memory");
  int st = sc_linsolve_alloc_full(sc_linsolve_dense, (int)N, &S->ms_ls, msg);
  if (st) return st;
  S->ms = 1;
  memset(pb, 0, sizeof *pb);
  pb->n = N - 1;
  pb->f = ms_f;
  pb->jac = ms_jac;
  pb->ntest = 2;
  pb->test = ms_test;
  pb->test_names = ms_test_names;
  pb->user = S;
  return SC_OK;
}

void sc_ob_ms_free(segment *S) {
  free(S->ms_last);
  free(S->ms_tan);
  free(S->ms_try);
  free(S->ms_best);
  free(S->ms_start);
  free(S->ms_rhs);
  free(S->ms_mat);
  free(S->ms_val);
  sc_linsolve_free(S->ms_ls);
  S->ms_last = S->ms_tan = S->ms_try = S->ms_best = S->ms_start = NULL;
  S->ms_val = S->ms_rhs = S->ms_mat = NULL;
  S->ms_ls = NULL;
}

int sc_ob_ms_eval(sc_orbit_branch *b, const sc_itin_code *codes, int period,
                  const double *u, sc_border_list *bl, sc_map_value *v,
                  double *each, sc_itin_code *out) {
  if (sc_ob_set_p(b->m, b->sp.param, u[period])) return SC_EINVAL;
  unsigned fl = SC_EVAL_DERIV | SC_EVAL_ITINERARY;
  for (;;) {
    if (bl) bl->n = 0;
    int st = sc_map_iterate_points(b->m, u, period, fl, codes, out,
                                   b->sp.param, bl, each, v, NULL);
    if (st || !bl || bl->n <= bl->cap) return st;
    size_t nc = 2 * bl->n;
    sc_border *q = realloc(bl->b, nc * sizeof *q);
    if (!q) return SC_ENOMEM;
    bl->b = q;
    bl->cap = nc;
  }
}

/* One Newton iteration's matrix (column-major, N = m + 1) and right-hand
 * side at y: rows k < m the cyclic equations, row m the border's
 * (for a border in the state, x_j - d_on(p)). */
static void ms_border_system(int m, const double *val, const double *y,
                             int j, double mx, double mp, double mval,
                             double *A, double *r) {
  int N = m + 1;
  memset(A, 0, (size_t)N * (size_t)N * sizeof *A);
  for (int k = 0; k < m; k++) {
    A[k + N * k] += val[3 * k + 1];
    A[k + N * ((k + 1) % m)] -= 1;
    A[k + N * m] = val[3 * k + 2];
    r[k] = -(val[3 * k] - y[(k + 1) % m]);
  }
  A[m + N * j] = mx;
  A[m + N * m] = mp;
  r[m] = -mval;
}

/* The point at y, with iterate j put on a border in the state: its
 * values into S->ms_val and the border row's entries (mx, mp, mval). */
static int ms_border_eval(sc_orbit_branch *b, segment *S,
                          const sc_itin_code *codes, const sc_border *like,
                          double *y, double *mx, double *mp, double *mval,
                          sc_map_value *v) {
  int m = S->period, j = like->iterate;
  size_t ip = b->sp.param;
  if (like->on_state) {
    double don, don_p;
    int st = sc_ob_d_on(b, like, y[m], &don, &don_p);
    if (st) return st;
    y[j] = don;
    *mx = 1, *mp = -don_p, *mval = 0;
  }
  int st = sc_ob_ms_eval(b, codes, m, y, &b->bl_tmp, v, S->ms_val, NULL);
  if (st) return st;
  if (like->on_state) return SC_OK;
  const sc_border *bd = sc_border_list_find(&b->bl_tmp, like);
  if (!bd) return SC_EUNDEF;
  *mx = bd->dd, *mp = bd->dp[ip], *mval = bd->value;
  return SC_OK;
}

/* Newton from y = S->ms_try in place. */
static void ms_newton(sc_orbit_branch *b, segment *S, const sc_itin_code *codes,
                      const sc_border *like, border_fix *fx) {
  int m = S->period, N = m + 1, j = like->iterate;
  double *y = S->ms_try;
  double *mat = S->ms_mat, *rhs = S->ms_rhs;
  sc_map_value v;
  double mx, mp, mval;
  for (int it = 0; it < BORDER_NEWTON_MAX; it++) {
    int st = ms_border_eval(b, S, codes, like, y, &mx, &mp, &mval, &v);
    if (st) {
      snprintf(fx->why, sizeof fx->why,
               "the multiple-shooting system cannot be evaluated at %s = "
               "%.17g (%s)",
               sc_map_type(b->m)->params[b->sp.param].name, y[m],
               sc_strerror(st));
      return;
    }
    ms_border_system(m, S->ms_val, y, j, mx, mp, mval, mat, rhs);
    double res = fabs(mval);
    for (int k = 0; k < m; k++) res = fmax(res, fabs(rhs[k]));
    fx->F = res, fx->m = mval, fx->mult = v.dfdd, fx->iterations = it;
    if (sc_linsolve_factor(S->ms_ls, mat, NULL) ||
        sc_linsolve_solve(S->ms_ls, rhs, NULL)) {
      snprintf(fx->why, sizeof fx->why,
               "singular Jacobian of the multiple-shooting system");
      return;
    }
    int small = 1;
    for (int i = 0; i < N; i++) {
      y[i] += rhs[i];
      if (!sc_ob_border_step_done(rhs[i], y[i], &b->acc)) small = 0;
    }
    fx->step = fabs(rhs[m]);
    if (!small) continue;
    /* the certificate: the system at the returned point */
    if (ms_border_eval(b, S, codes, like, y, &mx, &mp, &mval, &v)) {
      snprintf(fx->why, sizeof fx->why,
               "the last Newton point cannot be evaluated");
      return;
    }
    res = fabs(mval);
    for (int k = 0; k < m; k++)
      res = fmax(res, fabs(S->ms_val[3 * k] - y[(k + 1) % m]));
    fx->ok = 1;
    fx->p = y[m], fx->d0 = y[0], fx->dk = y[j];
    fx->F = res, fx->m = mval, fx->mult = v.dfdd;
    fx->iterations = it + 1;
    fx->orb = y;
    return;
  }
  snprintf(fx->why, sizeof fx->why,
           "Newton did not converge in %d iterations (last step %.3g in "
           "the parameter)",
           BORDER_NEWTON_MAX, fx->step);
}

void sc_ob_ms_locate(sc_orbit_branch *b, segment *S, const sc_itin_code *codes,
                     const sc_border *like, const double *ua, border_fix *fx) {
  int m = S->period;
  memcpy(S->ms_try, ua, (size_t)(m + 1) * sizeof *ua);
  ms_newton(b, S, codes, like, fx);
  sc_ob_set_p(b->m, b->sp.param, fx->ok ? fx->p : S->ms_try[m]);
}
