/* Codimension-two points of a curve: Newton on the extended system
 * {F(u) = 0, psi_k(u) = 0}, and the fold / flip curve systems of a 1-D
 * map iterate g = f^m(x, p) with their normal-form tests.  Generic: only
 * vectors, Jacobians and callbacks (docs/continuation.md). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/curve_system.h"

/* Gaussian elimination with partial pivoting on the N x N row-major A;
 * b is overwritten with the solution.  Returns SC_ESING for a zero pivot
 * (or one below DBL_EPSILON times the largest entry: rank deficient to
 * working precision).  It stays here rather than LAPACK's LU
 * (dense_impl.h) because the one-dimensional curves keep their outputs bit
 * for bit: with dgetrf every curve point and located special point of the
 * curve examples is the same, but the Newton of a point left unlocated at
 * a degenerate row (curve-fig58-flip2's GPD?) fails another way and
 * writes another reason and residual. */
static int solve(int N, double *A, double *b) {
  double amax = 0;
  for (int i = 0; i < N * N; i++)
    amax = fmax(amax, fabs(A[i]));
  for (int c = 0; c < N; c++) {
    int p = c;
    for (int r = c + 1; r < N; r++)
      if (fabs(A[r * N + c]) > fabs(A[p * N + c])) p = r;
    if (!(fabs(A[p * N + c]) > DBL_EPSILON * amax)) return SC_ESING;
    if (p != c) {
      for (int j = 0; j < N; j++) {
        double t = A[c * N + j];
        A[c * N + j] = A[p * N + j];
        A[p * N + j] = t;
      }
      double t = b[c];
      b[c] = b[p];
      b[p] = t;
    }
    for (int r = c + 1; r < N; r++) {
      double f = A[r * N + c] / A[c * N + c];
      for (int j = c; j < N; j++)
        A[r * N + j] -= f * A[c * N + j];
      b[r] -= f * b[c];
    }
  }
  for (int c = N - 1; c >= 0; c--) {
    double s = b[c];
    for (int j = c + 1; j < N; j++)
      s -= A[c * N + j] * b[j];
    b[c] = s / A[c * N + c];
  }
  return SC_OK;
}

static int finite_all(const double *v, size_t n) {
  for (size_t i = 0; i < n; i++)
    if (!isfinite(v[i])) return 0;
  return 1;
}

/* G(u) = (F(u), psi_k(u)); psi has room for ntest values */
static int ext_eval(const sc_curve_system *cs, size_t k, const double *u,
                    double *G, double *psi) {
  int rc = cs->pb.f(u, G, cs->pb.user);
  if (rc) return rc;
  rc = cs->test(u, psi, cs->user);
  if (rc) return rc;
  G[cs->pb.n] = psi[k];
  return finite_all(G, cs->pb.n + 1) ? 0 : 1;
}

static int locate_run(const sc_curve_system *cs, size_t k, double *u,
                      const sc_accuracy *acc, sc_curve_cert *cert, sc_msg *msg,
                      double *G, double *up, double *Gp, double *Gm,
                      double *psi, double *A, double *J);

int sc_curve_locate(const sc_curve_system *cs, size_t k, double *u,
                    const sc_accuracy *acc, sc_curve_cert *cert, sc_msg *msg) {
  size_t n = cs->pb.n, N = n + 1;
  memset(cert, 0, sizeof *cert);
  cert->residual = cert->step = HUGE_VAL;
  if (k >= cs->ntest || !cs->test)
    return sc_fail(msg, SC_EINVAL,
                   "sc_curve_locate: test %zu of %zu (valid: k < ntest)", k,
                   cs->ntest);
  /* One block: G, up, Gp, Gm (N each), psi (ntest), A, J (N^2 each). */
  double *mem = malloc((4 * N + cs->ntest + 2 * N * N) * sizeof *mem);
  if (!mem) return sc_fail(msg, SC_ENOMEM, "sc_curve_locate: out of memory");
  double *G = mem, *up = G + N, *Gp = up + N, *Gm = Gp + N, *psi = Gm + N;
  double *A = psi + cs->ntest, *J = A + N * N;
  int st = locate_run(cs, k, u, acc, cert, msg, G, up, Gp, Gm, psi, A, J);
  free(mem);
  return st;
}

static int locate_run(const sc_curve_system *cs, size_t k, double *u,
                      const sc_accuracy *acc, sc_curve_cert *cert, sc_msg *msg,
                      double *G, double *up, double *Gp, double *Gm,
                      double *psi, double *A, double *J) {
  size_t n = cs->pb.n, N = n + 1;
  for (int it = 1; it <= acc->newton_maxiter; it++) {
    int rc = ext_eval(cs, k, u, G, psi);
    if (rc == 0) rc = cs->pb.jac(u, J, cs->pb.user);
    if (rc)
      return sc_fail(msg, SC_ECALLBACK,
                     "sc_curve_locate: callback failed (%d) at iteration %d",
                     rc, it);
    for (size_t i = 0; i < n; i++)
      for (size_t j = 0; j < N; j++)
        A[i * N + j] = J[i * N + j];
    /* psi_k's row: central differences of a function computed from exact
     * derivatives; the step is relative, fd_step (u's scale: 1 + |u_j|) */
    for (size_t j = 0; j < N; j++) {
      double h = acc->fd_step * (1 + fabs(u[j]));
      memcpy(up, u, N * sizeof *u);
      up[j] = u[j] + h;
      rc = ext_eval(cs, k, up, Gp, psi);
      up[j] = u[j] - h;
      if (rc == 0) rc = ext_eval(cs, k, up, Gm, psi);
      if (rc)
        return sc_fail(msg, SC_ECALLBACK,
                       "sc_curve_locate: test %s failed near the point",
                       cs->labels ? cs->labels[k] : "?");
      A[n * N + j] = (Gp[n] - Gm[n]) / (2 * h);
    }
    for (size_t i = 0; i < N; i++)
      G[i] = -G[i];
    if (solve((int)N, A, G))
      return sc_fail(msg, SC_ESING,
                     "sc_curve_locate: singular extended Jacobian at "
                     "iteration %d (the %s test is degenerate here)",
                     it, cs->labels ? cs->labels[k] : "?");
    double step = 0;
    int conv = 1;
    for (size_t i = 0; i < N; i++) {
      step = fmax(step, fabs(G[i]));
      if (sc_test_delta(G[i], u[i], acc->newton_atol, acc->newton_rtol))
        conv = 0;
      u[i] += G[i];
    }
    cert->iterations = it;
    cert->step = step;
    /* the certificate is the residual at the returned point */
    rc = ext_eval(cs, k, u, Gp, psi);
    if (rc)
      return sc_fail(msg, SC_ECALLBACK,
                     "sc_curve_locate: callback failed after a step");
    double res = 0;
    for (size_t i = 0; i < n; i++)
      res = fmax(res, fabs(Gp[i]));
    cert->residual = res;
    cert->psi = Gp[n];
    /* the test function is not scaled (a normal-form coefficient may be
     * 1e4 where F is 1e-13): its zero is certified by the Newton step,
     * F's by the residual */
    if (conv && res <= acc->newton_ftol) return SC_OK;
  }
  return sc_fail(msg, SC_ENOCONV,
                 "sc_curve_locate: no convergence in %d iterations "
                 "(residual %.3g, step %.3g)",
                 acc->newton_maxiter, cert->residual, cert->step);
}

/* ---- fold and flip curves of a map iterate ---------------------------- */

static int jet_at(const sc_curve_map1d *s, const double *u, sc_curve_jet *j) {
  double p[SC_MAP1D_MAXPARAM];
  memcpy(p, s->p, sizeof p);
  p[s->ifree[0]] = u[1];
  p[s->ifree[1]] = u[2];
  memset(j, 0, sizeof *j);
  return s->fn(u[0], p, j, s->user);
}

static double target(const sc_curve_map1d *s) {
  return s->type == SC_CURVE_FOLD ? 1 : -1;
}

static int c_f(const double *u, double *F, void *user) {
  const sc_curve_map1d *s = user;
  sc_curve_jet j;
  int rc = jet_at(s, u, &j);
  if (rc) return rc;
  F[0] = j.g - u[0];
  F[1] = j.gx - target(s);
  return 0;
}

static int c_jac(const double *u, double *J, void *user) {
  const sc_curve_map1d *s = user;
  sc_curve_jet j;
  int rc = jet_at(s, u, &j);
  if (rc) return rc;
  int a = s->ifree[0], b = s->ifree[1];
  J[0] = j.gx - 1, J[1] = j.gp[a], J[2] = j.gp[b];
  J[3] = j.gxx, J[4] = j.gxp[a], J[5] = j.gxp[b];
  return 0;
}

double sc_curve_coefficient(sc_curve_type type, const sc_curve_jet *j) {
  /* fold: g = x + a (x - x0)^2 + ...; flip: the second iterate is
   * x - 2 c (x - x0)^3 + ... with c = a2^2 + a3, a2 = g_xx/2, a3 = g_xxx/6
   * (docs/curves.md) */
  if (type == SC_CURVE_FOLD) return 0.5 * j->gxx;
  return 0.25 * j->gxx * j->gxx + j->gxxx / 6;
}

static int c_test(const double *u, double *psi, void *user) {
  const sc_curve_map1d *s = user;
  sc_curve_jet j;
  int rc = jet_at(s, u, &j);
  if (rc) return rc;
  int a = s->ifree[0], b = s->ifree[1];
  psi[0] = sc_curve_coefficient(s->type, &j);
  /* The tangent's p_a component is proportional to the determinant of
   * F's Jacobian without the p_a column, columns (x, p_b); p_b's to the
   * one with columns (x, p_a) (Cramer). */
  psi[1] = (j.gx - 1) * j.gxp[b] - j.gp[b] * j.gxx;
  psi[2] = (j.gx - 1) * j.gxp[a] - j.gp[a] * j.gxx;
  return 0;
}

static const char *const fold_labels[] = {"CP", "TP", "TP"};
static const char *const flip_labels[] = {"GPD", "TP", "TP"};

int sc_curve_map1d_system(const sc_curve_map1d *sys, sc_curve_system *cs,
                          sc_msg *msg) {
  if (!sys || !sys->fn || sys->np < 2 || sys->np > SC_MAP1D_MAXPARAM)
    return sc_fail(msg, SC_EINVAL,
                   "sc_curve_map1d_system: NULL map or np = %zu (valid: "
                   "[2, %d])",
                   sys ? sys->np : 0, SC_MAP1D_MAXPARAM);
  if (sys->type != SC_CURVE_FOLD && sys->type != SC_CURVE_FLIP)
    return sc_fail(msg, SC_EINVAL, "sc_curve_map1d_system: unknown type %d",
                   (int)sys->type);
  for (int i = 0; i < 2; i++)
    if (sys->ifree[i] < 0 || (size_t)sys->ifree[i] >= sys->np)
      return sc_fail(msg, SC_EINVAL,
                     "sc_curve_map1d_system: free parameter index %d "
                     "(valid: [0, %zu))",
                     sys->ifree[i], sys->np);
  if (sys->ifree[0] == sys->ifree[1])
    return sc_fail(msg, SC_EINVAL,
                   "sc_curve_map1d_system: both free parameters are index %d",
                   sys->ifree[0]);
  memset(cs, 0, sizeof *cs);
  cs->pb.n = 2;
  cs->pb.f = c_f;
  cs->pb.jac = c_jac;
  cs->pb.user = (void *)sys; /* only read */
  cs->ntest = 3;
  cs->test = c_test;
  cs->labels = sys->type == SC_CURVE_FOLD ? fold_labels : flip_labels;
  cs->user = (void *)sys;
  return SC_OK;
}
