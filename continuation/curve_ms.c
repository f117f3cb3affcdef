/* Fold and flip curves of a period-m orbit by multiple shooting:
 * u = (x_0, ..., x_{m-1}, p_a, p_b) and
 *
 *   F_k = f(x_k) - x_{k+1 mod m},   k < m,
 *   F_m = prod_k f'(x_k) -+ 1,
 *
 * each equation involving one iterate of f, so that long periods stay
 * well conditioned (the product's factors are bounded where f^m's chain
 * rule would multiply errors).  The last row's derivatives use the
 * prefix and suffix products of the f'(x_j):
 *   dF_m/dx_k = f''(x_k) prod_{j != k} f'(x_j),
 *   dF_m/dp   = sum_k f'_p(x_k) prod_{j != k} f'(x_j).
 * Tests as for single shooting (curve.c): the normal-form coefficient
 * of g = f^m at x_0 (from a g-jet callback), and the turning points in
 * p_a, p_b as determinants of F's Jacobian without that column. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/curve_system.h"

struct sc_curve_ms_work {
  size_t m;
  sc_curve_jet *jets;   /* m */
  double *pre, *suf;    /* m + 1 each */
  double *J, *A;        /* (m + 1) x (m + 2), (m + 1)^2 */
  int *colptr, *rowind; /* the CSC pattern: m + 3, at most 5 m + 2 */
};

int sc_curve_ms_work_alloc(size_t period, sc_curve_ms_work **out, sc_msg *msg) {
  *out = NULL;
  if (period < 1)
    return sc_fail(msg, SC_EINVAL,
                   "sc_curve_ms_work_alloc: period = %zu (valid: >= 1)",
                   period);
  sc_curve_ms_work *w = calloc(1, sizeof *w);
  if (!w) goto fail;
  size_t n = period + 1;
  w->m = period;
  w->jets = calloc(period, sizeof *w->jets);
  w->pre = calloc(n, sizeof *w->pre);
  w->suf = calloc(n, sizeof *w->suf);
  w->J = calloc(n * (n + 1), sizeof *w->J);
  w->A = calloc(n * n, sizeof *w->A);
  w->colptr = calloc(period + 3, sizeof *w->colptr);
  w->rowind = calloc(5 * period + 2, sizeof *w->rowind);
  if (!w->jets || !w->pre || !w->suf || !w->J || !w->A || !w->colptr ||
      !w->rowind)
    goto fail;
  /* Column j < m holds rows j (f'(d_j)), j - 1 mod m (the -1 of
   * F_{j-1}) and m (the product row); columns m, m + 1 (the parameters)
   * are full.  Rows increase within each column. */
  int nz = 0, mm = (int)period;
  for (int j = 0; j < mm; j++) {
    w->colptr[j] = nz;
    int a = j, b = (j + mm - 1) % mm;
    int lo = a < b ? a : b, hi = a < b ? b : a;
    w->rowind[nz++] = lo;
    if (hi != lo) w->rowind[nz++] = hi;
    w->rowind[nz++] = mm;
  }
  for (int j = mm; j < mm + 2; j++) {
    w->colptr[j] = nz;
    for (int i = 0; i <= mm; i++)
      w->rowind[nz++] = i;
  }
  w->colptr[mm + 2] = nz;
  *out = w;
  return SC_OK;
fail:
  sc_curve_ms_work_free(w);
  return sc_fail(msg, SC_ENOMEM, "sc_curve_ms_work_alloc: out of memory");
}

void sc_curve_ms_work_free(sc_curve_ms_work *w) {
  if (!w) return;
  free(w->jets);
  free(w->pre);
  free(w->suf);
  free(w->J);
  free(w->A);
  free(w->colptr);
  free(w->rowind);
  free(w);
}

/* f's jets at every orbit point, with the free parameters from u. */
static int jets_at(const sc_curve_map1d_ms *s, const double *u) {
  size_t m = s->period;
  double p[SC_MAP1D_MAXPARAM];
  memcpy(p, s->p, sizeof p);
  p[s->ifree[0]] = u[m];
  p[s->ifree[1]] = u[m + 1];
  for (size_t k = 0; k < m; k++) {
    memset(&s->work->jets[k], 0, sizeof s->work->jets[k]);
    int rc = s->fn(u[k], p, &s->work->jets[k], s->user);
    if (rc) return rc;
  }
  /* pre[k] = prod_{j < k} f'(x_j), suf[k] = prod_{j >= k} f'(x_j) */
  sc_curve_ms_work *w = s->work;
  w->pre[0] = 1;
  for (size_t k = 0; k < m; k++)
    w->pre[k + 1] = w->pre[k] * w->jets[k].gx;
  w->suf[m] = 1;
  for (size_t k = m; k-- > 0;)
    w->suf[k] = w->suf[k + 1] * w->jets[k].gx;
  return 0;
}

static double target(const sc_curve_map1d_ms *s) {
  return s->type == SC_CURVE_FOLD ? 1 : -1;
}

static int ms_f(const double *u, double *F, void *user) {
  const sc_curve_map1d_ms *s = user;
  size_t m = s->period;
  int rc = jets_at(s, u);
  if (rc) return rc;
  for (size_t k = 0; k < m; k++)
    F[k] = s->work->jets[k].g - u[(k + 1) % m];
  F[m] = s->work->pre[m] - target(s);
  return 0;
}

/* The dense (m + 1) x (m + 2) Jacobian into J (row-major). */
static void ms_jac_fill(const sc_curve_map1d_ms *s, double *J) {
  size_t m = s->period, N = m + 2;
  const sc_curve_ms_work *w = s->work;
  int a = s->ifree[0], b = s->ifree[1];
  memset(J, 0, (m + 1) * N * sizeof *J);
  for (size_t k = 0; k < m; k++) {
    const sc_curve_jet *j = &w->jets[k];
    J[k * N + k] += j->gx;
    J[k * N + (k + 1) % m] -= 1;
    J[k * N + m] = j->gp[a];
    J[k * N + m + 1] = j->gp[b];
  }
  double *row = J + m * N;
  for (size_t k = 0; k < m; k++) {
    double others = w->pre[k] * w->suf[k + 1]; /* prod_{j != k} f'(x_j) */
    row[k] = w->jets[k].gxx * others;
    row[m] += w->jets[k].gxp[a] * others;
    row[m + 1] += w->jets[k].gxp[b] * others;
  }
}

static int ms_jac(const double *u, double *J, void *user) {
  const sc_curve_map1d_ms *s = user;
  int rc = jets_at(s, u);
  if (rc) return rc;
  ms_jac_fill(s, J);
  return 0;
}

/* The Jacobian's nonzeros in the CSC pattern's order (for KLU). */
static int ms_jac_sparse(const double *u, double *J, void *user) {
  const sc_curve_map1d_ms *s = user;
  int rc = jets_at(s, u);
  if (rc) return rc;
  size_t N = s->period + 2;
  double *D = s->work->J;
  ms_jac_fill(s, D);
  const int *cp = s->work->colptr, *ri = s->work->rowind;
  for (size_t j = 0; j < N; j++)
    for (int k = cp[j]; k < cp[j + 1]; k++)
      J[k] = D[(size_t)ri[k] * N + j];
  return 0;
}

int sc_curve_map1d_ms_sparse(const sc_curve_map1d_ms *sys, sc_cont_problem *pb,
                             sc_msg *msg) {
  sc_curve_system cs;
  int st = sc_curve_map1d_ms_system(sys, &cs, msg);
  if (st) return st;
  *pb = cs.pb;
  pb->jac = ms_jac_sparse;
  pb->jac_colptr = sys->work->colptr;
  pb->jac_rowind = sys->work->rowind;
  return SC_OK;
}

/* Sign-faithful determinant of the n x n row-major A by elimination with
 * partial pivoting (A is destroyed).  Each row is first scaled by the
 * inverse of its largest entry (a positive factor: the sign is kept) so
 * that products of m derivatives neither overflow nor underflow. */
static double det(size_t n, double *A) {
  double d = 1;
  for (size_t i = 0; i < n; i++) {
    double mx = 0;
    for (size_t j = 0; j < n; j++)
      mx = fmax(mx, fabs(A[i * n + j]));
    if (mx == 0) return 0;
    for (size_t j = 0; j < n; j++)
      A[i * n + j] /= mx;
  }
  for (size_t c = 0; c < n; c++) {
    size_t p = c;
    for (size_t r = c + 1; r < n; r++)
      if (fabs(A[r * n + c]) > fabs(A[p * n + c])) p = r;
    if (A[p * n + c] == 0) return 0;
    if (p != c) {
      for (size_t j = 0; j < n; j++) {
        double t = A[c * n + j];
        A[c * n + j] = A[p * n + j];
        A[p * n + j] = t;
      }
      d = -d;
    }
    d *= A[c * n + c];
    for (size_t r = c + 1; r < n; r++) {
      double f = A[r * n + c] / A[c * n + c];
      for (size_t j = c; j < n; j++)
        A[r * n + j] -= f * A[c * n + j];
    }
  }
  return d;
}

/* det of J without column `skip` */
static double minor_det(const sc_curve_map1d_ms *s, size_t skip) {
  size_t n = s->period + 1, N = n + 1;
  sc_curve_ms_work *w = s->work;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0, c = 0; j < N; j++)
      if (j != skip) w->A[i * n + c++] = w->J[i * N + j];
  return det(n, w->A);
}

static int ms_test(const double *u, double *psi, void *user) {
  const sc_curve_map1d_ms *s = user;
  size_t m = s->period;
  double p[SC_MAP1D_MAXPARAM];
  memcpy(p, s->p, sizeof p);
  p[s->ifree[0]] = u[m];
  p[s->ifree[1]] = u[m + 1];
  sc_curve_jet g;
  memset(&g, 0, sizeof g);
  int rc = s->gfn(u[0], p, &g, s->guser);
  if (rc) return rc;
  psi[0] = sc_curve_coefficient(s->type, &g);
  rc = jets_at(s, u);
  if (rc) return rc;
  ms_jac_fill(s, s->work->J);
  /* The tangent's p_a component is the minor without p_a's column (up to
   * a common factor and sign, Cramer), as in curve.c. */
  psi[1] = minor_det(s, m);
  psi[2] = minor_det(s, m + 1);
  return 0;
}

static const char *const fold_labels[] = {"CP", "TP", "TP"};
static const char *const flip_labels[] = {"GPD", "TP", "TP"};

int sc_curve_map1d_ms_system(const sc_curve_map1d_ms *sys, sc_curve_system *cs,
                             sc_msg *msg) {
  if (!sys || !sys->fn || !sys->gfn || !sys->work ||
      sys->work->m != sys->period || sys->np < 2 || sys->np > SC_MAP1D_MAXPARAM)
    return sc_fail(msg, SC_EINVAL,
                   "sc_curve_map1d_ms_system: NULL callback or workspace, a "
                   "workspace for another period, or np out of [2, %d]",
                   SC_MAP1D_MAXPARAM);
  if (sys->type != SC_CURVE_FOLD && sys->type != SC_CURVE_FLIP)
    return sc_fail(msg, SC_EINVAL, "sc_curve_map1d_ms_system: unknown type %d",
                   (int)sys->type);
  for (int i = 0; i < 2; i++)
    if (sys->ifree[i] < 0 || (size_t)sys->ifree[i] >= sys->np)
      return sc_fail(msg, SC_EINVAL,
                     "sc_curve_map1d_ms_system: free parameter index %d "
                     "(valid: [0, %zu))",
                     sys->ifree[i], sys->np);
  if (sys->ifree[0] == sys->ifree[1])
    return sc_fail(msg, SC_EINVAL,
                   "sc_curve_map1d_ms_system: both free parameters are "
                   "index %d",
                   sys->ifree[0]);
  memset(cs, 0, sizeof *cs);
  cs->pb.n = sys->period + 1;
  cs->pb.f = ms_f;
  cs->pb.jac = ms_jac;
  cs->pb.user = (void *)sys;
  cs->ntest = 3;
  cs->test = ms_test;
  cs->labels = sys->type == SC_CURVE_FOLD ? fold_labels : flip_labels;
  cs->user = (void *)sys;
  return SC_OK;
}
