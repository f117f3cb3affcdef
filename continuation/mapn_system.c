/* Defining systems for fixed points of an n-dimensional map iterate
 * g = f^m(x, p): the fixed-point system and its test functions, and the
 * minimally augmented fold, flip, Neimark-Sacker and branch-point systems
 * with exact Jacobians (mapn_system.h; docs/maps.md, "Branches").
 *
 * The fold's (flip's) function s is the last component of the solution of
 * M (v; s) = (0; 1), M = [[A, b], [c^T, 0]], A = g_x -+ I.  With w from
 * M^T (w; s2) = (0; 1), differentiating M (v; s) = e_{n+1} and multiplying
 * by (w; s2)^T gives ds/dz = -w^T A_z v for every unknown z.  The NS
 * system does the same with two borders and B = g_x^2 - 2 kappa g_x + I:
 * dG/dz = -W^T B_z V, B_z = A_z A + A A_z - 2 kappa A_z, B_kappa = -2 A. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/mapn_system.h"

/* LAPACK's SVD (Fortran 77 interface, column-major). */
extern void dgesvd_(const char *jobu, const char *jobvt, const int *m,
                    const int *n, double *a, const int *lda, double *s,
                    double *u, const int *ldu, double *vt, const int *ldvt,
                    double *work, const int *lwork, int *info);

/* A pivot below this fraction of the matrix's largest entry is a rank
 * deficiency to working precision: LU's rounding is of that order. */
#define PIVOT_FLOOR DBL_EPSILON

/* Steps of Newton at the rounding level of u are noise (as the branch
 * corrector's NEWTON_NOISE_ULPS in branch.c): bordered systems at folds
 * amplify the rounding of g by their condition, a few hundred ulps. */
#define NOISE_ULPS 256.0

/* The branch point's row w^T g_p is differentiated in p by central
 * differences of the exact g_p (g_pp is not given): cbrt(eps) balances
 * truncation (h^2) against rounding (eps / h).  The row sets only the
 * rate of Newton's convergence, never the point. */
#define BP_FD_STEP 6.0554544523933395e-06

#define MAXN SC_MAPN_MAXDIM
#define MAXB (SC_MAPN_MAXDIM + 2)

struct sc_mapn_system {
  sc_mapn_def d;
  size_t n, ne, nu, neq;
  sc_mapn_jet jet;
  double *mem;              /* the jet's arrays */
  double b[MAXN], c[MAXN];  /* fold, flip, BP borders */
  double P[2 * MAXN], Q[2 * MAXN]; /* NS borders, column k at k n */
  int ga, gb;               /* NS: entries of G (row 2 + column) */
  double M[MAXB * MAXB];    /* bordered matrix, LU in place */
  double Mt[MAXB * MAXB];   /* its transpose, LU in place */
  int piv[MAXB], pivt[MAXB];
  double A[MAXN * MAXN], B[MAXN * MAXN];
  double V[2 * MAXB], W[2 * MAXB]; /* solutions, column k at k (n + 2) */
  double *det;              /* scratch for the tests' determinants */
  int *dpiv;
};

/* ------------------------------------------------------------------ */
/* Dense LU with partial pivoting (row-major), small systems           */
/* ------------------------------------------------------------------ */

/* Factor the N x N matrix a in place.  Returns SC_ESING for a pivot at
 * or below PIVOT_FLOOR times the largest entry (the factors are complete
 * even then, so the determinant is still the product of the pivots). */
static int lu_factor(size_t N, double *a, int *piv) {
  double amax = 0;
  for (size_t i = 0; i < N * N; i++) amax = fmax(amax, fabs(a[i]));
  int st = SC_OK;
  for (size_t c = 0; c < N; c++) {
    size_t p = c;
    for (size_t r = c + 1; r < N; r++)
      if (fabs(a[r * N + c]) > fabs(a[p * N + c])) p = r;
    piv[c] = (int)p;
    if (p != c)
      for (size_t j = 0; j < N; j++) {
        double t = a[c * N + j];
        a[c * N + j] = a[p * N + j];
        a[p * N + j] = t;
      }
    double d = a[c * N + c];
    if (!(fabs(d) > PIVOT_FLOOR * amax)) {
      st = SC_ESING;
      if (d == 0) continue;
    }
    for (size_t r = c + 1; r < N; r++) {
      double f = a[r * N + c] /= d;
      for (size_t j = c + 1; j < N; j++) a[r * N + j] -= f * a[c * N + j];
    }
  }
  return st;
}

/* Solve with the factors of lu_factor(): its interchanges moved whole
 * rows (the multipliers too, as LAPACK's dgetrf), so all of them apply to
 * x before the forward substitution. */
static void lu_solve(size_t N, const double *a, const int *piv, double *x) {
  for (size_t c = 0; c < N; c++) {
    size_t p = (size_t)piv[c];
    if (p != c) {
      double t = x[c];
      x[c] = x[p];
      x[p] = t;
    }
  }
  for (size_t c = 0; c < N; c++)
    for (size_t r = c + 1; r < N; r++) x[r] -= a[r * N + c] * x[c];
  for (size_t c = N; c-- > 0;) {
    for (size_t j = c + 1; j < N; j++) x[c] -= a[c * N + j] * x[j];
    x[c] /= a[c * N + c];
  }
}

/* Largest determinant of the tests: the bialternate product of
 * n = SC_MAPN_MAXDIM, n (n - 1) / 2 rows (the bordered ones have n + 1). */
#define MAXDET (SC_MAPN_MAXDIM * (SC_MAPN_MAXDIM - 1) / 2)

/* det(a) / prod_i max(1, |row_i|_2) for the N x N row-major a
 * (destroyed), N <= MAXDET: in [-1, 1] by Hadamard's inequality, zero
 * where det is.  Each pivot is divided by a row's norm as it is
 * multiplied in, so that neither product overflows. */
static double scaled_det(size_t N, double *a, int *piv) {
  double sc[MAXDET];
  for (size_t i = 0; i < N; i++) {
    double s = 0;
    for (size_t j = 0; j < N; j++) s += a[i * N + j] * a[i * N + j];
    sc[i] = fmax(1, sqrt(s));
  }
  lu_factor(N, a, piv);
  double r = 1;
  for (size_t c = 0; c < N; c++) {
    r *= a[c * N + c] / sc[c];
    if (piv[c] != (int)c) r = -r;
  }
  return r;
}

/* ------------------------------------------------------------------ */
/* Allocation and evaluation of g                                      */
/* ------------------------------------------------------------------ */

static size_t extra_of(sc_mapn_kind k) {
  return k == SC_MAPN_NS || k == SC_MAPN_BP;
}

static size_t neq_of(sc_mapn_kind k, size_t n) {
  switch (k) {
  case SC_MAPN_FIXED: return n;
  case SC_MAPN_FOLD:
  case SC_MAPN_FLIP: return n + 1;
  default: return n + 2;
  }
}

void sc_mapn_system_free(sc_mapn_system *s) {
  if (!s) return;
  free(s->mem);
  free(s->det);
  free(s->dpiv);
  free(s);
}

static int check_def(const sc_mapn_def *d, sc_msg *msg) {
  if (!d || !d->fn)
    return sc_fail(msg, SC_EINVAL, "sc_mapn_system_alloc: NULL map");
  if (d->n < 1 || d->n > SC_MAPN_MAXDIM)
    return sc_fail(msg, SC_EINVAL,
                   "sc_mapn_system_alloc: n = %zu (valid: [1, %d])", d->n,
                   SC_MAPN_MAXDIM);
  if (d->np < 1 || d->np > SC_MAPN_MAXPARAM)
    return sc_fail(msg, SC_EINVAL,
                   "sc_mapn_system_alloc: np = %zu (valid: [1, %d])", d->np,
                   SC_MAPN_MAXPARAM);
  if ((unsigned)d->kind > SC_MAPN_BP)
    return sc_fail(msg, SC_EINVAL, "sc_mapn_system_alloc: unknown kind %d",
                   (int)d->kind);
  if (d->kind == SC_MAPN_NS && d->n < 2)
    return sc_fail(msg, SC_EINVAL,
                   "sc_mapn_system_alloc: a Neimark-Sacker system needs n >= "
                   "2 (n = 1)");
  size_t maxfree = d->kind == SC_MAPN_FIXED || d->kind == SC_MAPN_BP ? 1 : 2;
  if (d->nfree < 1 || d->nfree > maxfree)
    return sc_fail(msg, SC_EINVAL,
                   "sc_mapn_system_alloc: nfree = %zu (valid: [1, %zu] for "
                   "this kind)",
                   d->nfree, maxfree);
  for (size_t i = 0; i < d->nfree; i++)
    if (d->ifree[i] < 0 || (size_t)d->ifree[i] >= d->np)
      return sc_fail(msg, SC_EINVAL,
                     "sc_mapn_system_alloc: free parameter index %d (valid: "
                     "[0, %zu))",
                     d->ifree[i], d->np);
  if (d->nfree == 2 && d->ifree[0] == d->ifree[1])
    return sc_fail(msg, SC_EINVAL,
                   "sc_mapn_system_alloc: both free parameters are index %d",
                   d->ifree[0]);
  return SC_OK;
}

int sc_mapn_system_alloc(const sc_mapn_def *def, sc_mapn_system **out,
                         sc_msg *msg) {
  *out = NULL;
  int st = check_def(def, msg);
  if (st) return st;
  sc_mapn_system *s = calloc(1, sizeof *s);
  if (!s) return sc_fail(msg, SC_ENOMEM, "sc_mapn_system_alloc: out of memory");
  s->d = *def;
  size_t n = def->n, np = def->np;
  s->n = n;
  s->ne = extra_of(def->kind);
  s->nu = n + s->ne + def->nfree;
  s->neq = neq_of(def->kind, n);
  size_t len = n + n * n + np * n + n * n * n + np * n * n;
  /* the largest determinant of the tests: the bialternate product's
   * n (n - 1) / 2, or the bordered n + 1 */
  size_t nd = n * (n - 1) / 2 > n + 1 ? n * (n - 1) / 2 : n + 1;
  s->mem = calloc(len, sizeof *s->mem);
  s->det = calloc(nd * nd, sizeof *s->det);
  s->dpiv = calloc(nd, sizeof *s->dpiv);
  if (!s->mem || !s->det || !s->dpiv) {
    sc_mapn_system_free(s);
    return sc_fail(msg, SC_ENOMEM, "sc_mapn_system_alloc: out of memory");
  }
  s->jet.g = s->mem;
  s->jet.gx = s->jet.g + n;
  s->jet.gp = s->jet.gx + n * n;
  s->jet.gxx = s->jet.gp + np * n;
  s->jet.gxp = s->jet.gxx + n * n * n;
  s->b[0] = s->c[0] = 1;
  s->P[0] = s->Q[0] = 1;
  s->P[n + 1] = s->Q[n + 1] = 1;
  s->ga = 0; /* G_11 and G_22 until a point chooses */
  s->gb = 3;
  *out = s;
  return SC_OK;
}

size_t sc_mapn_system_nunknowns(const sc_mapn_system *s) { return s->nu; }
size_t sc_mapn_system_nequations(const sc_mapn_system *s) { return s->neq; }
size_t sc_mapn_system_nextra(const sc_mapn_system *s) { return s->ne; }

int sc_mapn_system_set_param(sc_mapn_system *s, size_t q, double value) {
  if (q >= s->d.np) return SC_EINVAL;
  s->d.p[q] = value;
  return SC_OK;
}

/* g at u up to @p order into s->jet; non-finite values are recoverable
 * failures. */
static int jet_at(sc_mapn_system *s, const double *u, int order) {
  double p[SC_MAPN_MAXPARAM];
  memcpy(p, s->d.p, sizeof p);
  for (size_t i = 0; i < s->d.nfree; i++)
    p[s->d.ifree[i]] = u[s->n + s->ne + i];
  int rc = s->d.fn(u, p, order, &s->jet, s->d.user);
  if (rc) return rc;
  size_t n = s->n, np = s->d.np;
  size_t len = order == 0   ? n
               : order == 1 ? n + n * n + np * n
                            : n + n * n + np * n + n * n * n + np * n * n;
  for (size_t i = 0; i < len; i++)
    if (!isfinite(s->mem[i])) return 1;
  return 0;
}

/* ------------------------------------------------------------------ */
/* The bordered systems                                                */
/* ------------------------------------------------------------------ */

/* A = g_x + sigma I into s->A (sigma = -1 fold and BP, +1 flip). */
static void shifted(sc_mapn_system *s) {
  size_t n = s->n;
  double sigma = s->d.kind == SC_MAPN_FLIP ? 1 : -1;
  memcpy(s->A, s->jet.gx, n * n * sizeof *s->A);
  for (size_t i = 0; i < n; i++) s->A[i * n + i] += sigma;
}

/* B = A^2 - 2 kappa A + I with A = g_x, into s->B. */
static void ns_matrix(sc_mapn_system *s, double kappa) {
  size_t n = s->n;
  const double *A = s->jet.gx;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) {
      double v = 0;
      for (size_t k = 0; k < n; k++) v += A[i * n + k] * A[k * n + j];
      s->B[i * n + j] = v - 2 * kappa * A[i * n + j] + (i == j);
    }
}

/* Factor M = [[X, borders], [borders'^T, 0]] and its transpose, X the
 * n x n s->A (nb = 1: b, c) or s->B (nb = 2: P, Q); solve for (v; s)
 * and (w; s2) with right sides (0; I): into s->V, s->W. */
static int bordered(sc_mapn_system *s, size_t nb) {
  size_t n = s->n, N = n + nb;
  const double *X = nb == 1 ? s->A : s->B;
  const double *L = nb == 1 ? s->b : s->P, *R = nb == 1 ? s->c : s->Q;
  memset(s->M, 0, N * N * sizeof *s->M);
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) s->M[i * N + j] = X[i * n + j];
  for (size_t k = 0; k < nb; k++)
    for (size_t i = 0; i < n; i++) {
      s->M[i * N + n + k] = L[k * n + i];
      s->M[(n + k) * N + i] = R[k * n + i];
    }
  for (size_t i = 0; i < N; i++)
    for (size_t j = 0; j < N; j++) s->Mt[j * N + i] = s->M[i * N + j];
  if (lu_factor(N, s->M, s->piv) || lu_factor(N, s->Mt, s->pivt))
    return SC_ESING;
  for (size_t k = 0; k < nb; k++) {
    double *v = s->V + k * N, *w = s->W + k * N;
    for (size_t i = 0; i < N; i++) v[i] = w[i] = i == n + k;
    lu_solve(N, s->M, s->piv, v);
    lu_solve(N, s->Mt, s->pivt, w);
  }
  return SC_OK;
}

/* y^T X_z x with X_z the derivative of g_x in unknown z = x_k
 * (k < n) or parameter q (z = n + q): rows i, columns j. */
static double form(const sc_mapn_system *s, size_t z, const double *y,
                   const double *x) {
  size_t n = s->n;
  double r = 0;
  for (size_t i = 0; i < n; i++) {
    double ri = 0;
    if (z < n)
      for (size_t j = 0; j < n; j++) ri += s->jet.gxx[(i * n + j) * n + z] * x[j];
    else
      for (size_t j = 0; j < n; j++)
        ri += s->jet.gxp[((z - n) * n + i) * n + j] * x[j];
    r += y[i] * ri;
  }
  return r;
}

/* out = X_z x (n values), X_z as in form(). */
static void dmat_vec(const sc_mapn_system *s, size_t z, const double *x,
                     double *out) {
  size_t n = s->n;
  for (size_t i = 0; i < n; i++) {
    double ri = 0;
    if (z < n)
      for (size_t j = 0; j < n; j++) ri += s->jet.gxx[(i * n + j) * n + z] * x[j];
    else
      for (size_t j = 0; j < n; j++)
        ri += s->jet.gxp[((z - n) * n + i) * n + j] * x[j];
    out[i] = ri;
  }
}

static void mat_vec(size_t n, const double *A, const double *x, double *out) {
  for (size_t i = 0; i < n; i++) {
    double r = 0;
    for (size_t j = 0; j < n; j++) r += A[i * n + j] * x[j];
    out[i] = r;
  }
}

/* dG_ab/dz = -W_a^T B_z V_b for z = x_k or a parameter (as form()):
 * the four entries (row a, column b) into g4. */
static void ns_dG(const sc_mapn_system *s, size_t z, double kappa,
                  double *g4) {
  size_t n = s->n, N = n + 2;
  for (size_t bcol = 0; bcol < 2; bcol++) {
    const double *v = s->V + bcol * N;
    double Av[MAXN], Azv[MAXN], AzAv[MAXN], AAzv[MAXN];
    mat_vec(n, s->jet.gx, v, Av);
    dmat_vec(s, z, v, Azv);
    dmat_vec(s, z, Av, AzAv);
    mat_vec(n, s->jet.gx, Azv, AAzv);
    for (size_t a = 0; a < 2; a++) {
      const double *w = s->W + a * N;
      double r = 0;
      for (size_t i = 0; i < n; i++)
        r += w[i] * (AzAv[i] + AAzv[i] - 2 * kappa * Azv[i]);
      g4[a * 2 + bcol] = -r;
    }
  }
}

/* dG/dkappa = -W^T (-2 A) V = 2 W_a^T A V_b. */
static void ns_dG_kappa(const sc_mapn_system *s, double *g4) {
  size_t n = s->n, N = n + 2;
  for (size_t bcol = 0; bcol < 2; bcol++) {
    double Av[MAXN];
    mat_vec(n, s->jet.gx, s->V + bcol * N, Av);
    for (size_t a = 0; a < 2; a++) {
      double r = 0;
      for (size_t i = 0; i < n; i++) r += s->W[a * N + i] * Av[i];
      g4[a * 2 + bcol] = 2 * r;
    }
  }
}

/* Evaluate g at u (order) and solve the kind's bordered system there. */
static int bordered_at(sc_mapn_system *s, const double *u, int order) {
  int rc = jet_at(s, u, order);
  if (rc) return rc;
  if (s->d.kind == SC_MAPN_NS) {
    ns_matrix(s, u[s->n]);
    return bordered(s, 2) ? 1 : 0;
  }
  shifted(s);
  return bordered(s, 1) ? 1 : 0;
}

/* ------------------------------------------------------------------ */
/* Equations and Jacobians                                             */
/* ------------------------------------------------------------------ */

int sc_mapn_system_f(sc_mapn_system *s, const double *u, double *F) {
  size_t n = s->n;
  sc_mapn_kind k = s->d.kind;
  int rc = k == SC_MAPN_FIXED ? jet_at(s, u, 0) : bordered_at(s, u, 1);
  if (rc) return rc;
  for (size_t i = 0; i < n; i++) F[i] = s->jet.g[i] - u[i];
  switch (k) {
  case SC_MAPN_FIXED: break;
  case SC_MAPN_FOLD:
  case SC_MAPN_FLIP: F[n] = s->V[n]; break;
  case SC_MAPN_NS:
    F[n] = s->V[(s->ga % 2) * (n + 2) + n + s->ga / 2];
    F[n + 1] = s->V[(s->gb % 2) * (n + 2) + n + s->gb / 2];
    break;
  case SC_MAPN_BP: {
    double mu = u[n], wgp = 0;
    const double *gp = s->jet.gp + (size_t)s->d.ifree[0] * n;
    for (size_t i = 0; i < n; i++) {
      F[i] += mu * s->b[i];
      wgp += s->W[i] * gp[i];
    }
    F[n] = s->V[n];
    F[n + 1] = wgp;
    break;
  }
  }
  return 0;
}

/* The rows of g - x: [g_x - I | extra columns | g_p of the free ones]
 * (BP: the extra column is b). */
static void fixed_rows(const sc_mapn_system *s, double *J) {
  size_t n = s->n, nu = s->nu;
  for (size_t i = 0; i < n; i++) {
    double *row = J + i * nu;
    for (size_t j = 0; j < n; j++) row[j] = s->jet.gx[i * n + j] - (i == j);
    for (size_t e = 0; e < s->ne; e++)
      row[n + e] = s->d.kind == SC_MAPN_BP ? s->b[i] : 0;
    for (size_t f = 0; f < s->d.nfree; f++)
      row[n + s->ne + f] = s->jet.gp[(size_t)s->d.ifree[f] * n + i];
  }
}

/* Row of s: ds/dz = -w^T A_z v (A_z = dg_x/dz; A's shift is constant). */
static void fold_row(const sc_mapn_system *s, double *row) {
  size_t n = s->n;
  const double *v = s->V, *w = s->W;
  for (size_t k = 0; k < n; k++) row[k] = -form(s, k, w, v);
  for (size_t e = 0; e < s->ne; e++) row[n + e] = 0;
  for (size_t f = 0; f < s->d.nfree; f++)
    row[n + s->ne + f] = -form(s, n + (size_t)s->d.ifree[f], w, v);
}

static void ns_rows(const sc_mapn_system *s, double kappa, double *J) {
  size_t n = s->n, nu = s->nu;
  double *ra = J + n * nu, *rb = J + (n + 1) * nu, g4[4];
  for (size_t k = 0; k < n; k++) {
    ns_dG(s, k, kappa, g4);
    ra[k] = g4[s->ga];
    rb[k] = g4[s->gb];
  }
  ns_dG_kappa(s, g4);
  ra[n] = g4[s->ga];
  rb[n] = g4[s->gb];
  for (size_t f = 0; f < s->d.nfree; f++) {
    ns_dG(s, n + (size_t)s->d.ifree[f], kappa, g4);
    ra[n + 1 + f] = g4[s->ga];
    rb[n + 1 + f] = g4[s->gb];
  }
}

static int bp_row(sc_mapn_system *s, const double *u, double *row);

int sc_mapn_system_jac(sc_mapn_system *s, const double *u, double *J) {
  size_t n = s->n, nu = s->nu;
  sc_mapn_kind k = s->d.kind;
  int rc = k == SC_MAPN_FIXED ? jet_at(s, u, 1) : bordered_at(s, u, 2);
  if (rc) return rc;
  fixed_rows(s, J);
  switch (k) {
  case SC_MAPN_FIXED: break;
  case SC_MAPN_FOLD:
  case SC_MAPN_FLIP: fold_row(s, J + n * nu); break;
  case SC_MAPN_NS: ns_rows(s, u[n], J); break;
  case SC_MAPN_BP:
    fold_row(s, J + n * nu);
    return bp_row(s, u, J + (n + 1) * nu);
  }
  return 0;
}

/* Row of w^T g_p (p = p_a): d/dx_k = w^T (dg_p/dx_k) - w^T A_k y, with
 * M (y; y2) = (g_p; 0) (w's own derivative: w_z^T g_p = -w^T A_z y);
 * d/dp = w^T g_pp - w^T A_p y, g_pp by central differences of g_p.
 * Needs the jet (order 2) and s->W at u; leaves them as they were. */
static int bp_row(sc_mapn_system *s, const double *u, double *row) {
  size_t n = s->n, N = n + 1, q = (size_t)s->d.ifree[0];
  double y[MAXB], w[MAXN];
  memcpy(w, s->W, n * sizeof *w);
  for (size_t i = 0; i < n; i++) y[i] = s->jet.gp[q * n + i];
  y[n] = 0;
  lu_solve(N, s->M, s->piv, y);
  for (size_t k = 0; k < n; k++) {
    double r = 0;
    for (size_t i = 0; i < n; i++) r += w[i] * s->jet.gxp[(q * n + i) * n + k];
    row[k] = r - form(s, k, w, y);
  }
  row[n] = 0;
  double apy = form(s, n + q, w, y);
  double up[MAXB + 1], h = BP_FD_STEP * (1 + fabs(u[n + 1])), gpp = 0;
  memcpy(up, u, s->nu * sizeof *up);
  for (int sgn = 1; sgn >= -1; sgn -= 2) {
    up[n + 1] = u[n + 1] + sgn * h;
    int rc = jet_at(s, up, 1);
    if (rc) return rc;
    for (size_t i = 0; i < n; i++) gpp += sgn * w[i] * s->jet.gp[q * n + i];
  }
  row[n + 1] = gpp / (2 * h) - apy;
  return 0;
}

/* ------------------------------------------------------------------ */
/* Test functions of the fixed-point branch                            */
/* ------------------------------------------------------------------ */

/* det(C2(g_x) - I), scaled: C2 the second compound (the bialternate
 * product g_x (.) g_x), entries the 2 x 2 minors of rows (p, q) and
 * columns (r, t), p < q, r < t; its eigenvalues are mu_i mu_j, i < j. */
static double ns_test(sc_mapn_system *s) {
  size_t n = s->n, m = n * (n - 1) / 2, row = 0;
  const double *a = s->jet.gx;
  for (size_t p = 0; p < n; p++)
    for (size_t q = p + 1; q < n; q++, row++) {
      size_t col = 0;
      for (size_t r = 0; r < n; r++)
        for (size_t t = r + 1; t < n; t++, col++)
          s->det[row * m + col] = a[p * n + r] * a[q * n + t] -
                                  a[p * n + t] * a[q * n + r] - (row == col);
    }
  return scaled_det(m, s->det, s->dpiv);
}

int sc_mapn_system_tests(sc_mapn_system *s, const double *u, const double *t,
                         double *psi) {
  if (s->d.kind != SC_MAPN_FIXED) return -1;
  size_t n = s->n, N = n + 1;
  int rc = jet_at(s, u, 1);
  if (rc) return rc;
  for (int sigma = -1; sigma <= 1; sigma += 2) {
    memcpy(s->det, s->jet.gx, n * n * sizeof *s->det);
    for (size_t i = 0; i < n; i++) s->det[i * n + i] += sigma;
    psi[sigma < 0 ? SC_MAPN_TEST_LP : SC_MAPN_TEST_PD] =
        scaled_det(n, s->det, s->dpiv);
  }
  psi[SC_MAPN_TEST_NS] = n >= 2 ? ns_test(s) : 1;
  const double *gp = s->jet.gp + (size_t)s->d.ifree[0] * n;
  for (size_t i = 0; i < n; i++) {
    for (size_t j = 0; j < n; j++)
      s->det[i * N + j] = s->jet.gx[i * n + j] - (i == j);
    s->det[i * N + n] = gp[i];
  }
  for (size_t j = 0; j < N; j++) s->det[n * N + j] = t[j];
  psi[SC_MAPN_TEST_BP] = scaled_det(N, s->det, s->dpiv);
  return 0;
}

/* ------------------------------------------------------------------ */
/* Bordering vectors                                                   */
/* ------------------------------------------------------------------ */

static void normalize(double *v, size_t n) {
  double r = 0;
  for (size_t i = 0; i < n; i++) r += v[i] * v[i];
  r = sqrt(r);
  if (r > 0)
    for (size_t i = 0; i < n; i++) v[i] /= r;
}

/* Gram-Schmidt on the two columns of X (column k at k n). */
static void orthonormalize(double *X, size_t n) {
  normalize(X, n);
  double d = 0;
  for (size_t i = 0; i < n; i++) d += X[i] * X[n + i];
  for (size_t i = 0; i < n; i++) X[n + i] -= d * X[i];
  normalize(X + n, n);
}

/* NS: of the six pairs of G's entries, the one whose gradients, reduced
 * to the directions (kappa, free parameters) along which g = x holds,
 * span the largest area: the best conditioned pair of equations.  Needs
 * the jet (order 2) and the solutions V, W at u; keeps the pair when
 * g_x - I is singular. */
static void choose_pair(sc_mapn_system *s, const double *u) {
  size_t n = s->n, nf = s->d.nfree;
  double a[MAXN * MAXN], dx[2][MAXN], r[4][3], g4[4];
  int piv[MAXN];
  memcpy(a, s->jet.gx, n * n * sizeof *a);
  for (size_t i = 0; i < n; i++) a[i * n + i] -= 1;
  if (lu_factor(n, a, piv)) return;
  for (size_t f = 0; f < nf; f++) {
    for (size_t i = 0; i < n; i++)
      dx[f][i] = -s->jet.gp[(size_t)s->d.ifree[f] * n + i];
    lu_solve(n, a, piv, dx[f]);
  }
  ns_dG_kappa(s, g4);
  for (int e = 0; e < 4; e++) r[e][0] = g4[e];
  for (size_t f = 0; f < nf; f++) {
    ns_dG(s, n + (size_t)s->d.ifree[f], u[n], g4);
    for (int e = 0; e < 4; e++) r[e][1 + f] = g4[e];
  }
  for (size_t k = 0; k < n; k++) {
    ns_dG(s, k, u[n], g4);
    for (int e = 0; e < 4; e++)
      for (size_t f = 0; f < nf; f++) r[e][1 + f] += g4[e] * dx[f][k];
  }
  double best = -1;
  for (int e1 = 0; e1 < 4; e1++)
    for (int e2 = e1 + 1; e2 < 4; e2++) {
      double aa = 0, bb = 0, ab = 0;
      for (size_t c = 0; c <= nf; c++) {
        aa += r[e1][c] * r[e1][c];
        bb += r[e2][c] * r[e2][c];
        ab += r[e1][c] * r[e2][c];
      }
      double area = aa * bb - ab * ab;
      if (area > best) {
        best = area;
        s->ga = e1;
        s->gb = e2;
      }
    }
}

int sc_mapn_system_init(sc_mapn_system *s, const double *u, sc_msg *msg) {
  if (s->d.kind == SC_MAPN_FIXED) return SC_OK;
  int n = (int)s->n, rc = jet_at(s, u, 2);
  if (rc)
    return sc_fail(msg, SC_ECALLBACK,
                   "sc_mapn_system_init: the map or its first or second "
                   "derivatives could not be evaluated there (%s)",
                   rc > 0 ? "a non-finite value: a model without second "
                            "derivatives, or a point where the map is not "
                            "smooth"
                          : "the evaluation failed");
  const double *X = s->B;
  if (s->d.kind == SC_MAPN_NS) ns_matrix(s, u[n]);
  else {
    shifted(s);
    X = s->A;
  }
  double a[MAXN * MAXN], sv[MAXN], U[MAXN * MAXN], VT[MAXN * MAXN];
  double work[8 * MAXN * MAXN];
  int lwork = 8 * MAXN * MAXN, info = 0;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) a[j * n + i] = X[i * n + j];
  dgesvd_("A", "A", &n, &n, a, &n, sv, U, &n, VT, &n, work, &lwork, &info);
  if (info != 0)
    return sc_fail(msg, SC_EINTERNAL, "sc_mapn_system_init: dgesvd info %d",
                   info);
  int nb = s->d.kind == SC_MAPN_NS ? 2 : 1;
  double *L = nb == 1 ? s->b : s->P, *R = nb == 1 ? s->c : s->Q;
  for (int k = 0; k < nb; k++) {
    int col = n - nb + k;
    for (int i = 0; i < n; i++) {
      L[k * n + i] = U[col * n + i];
      R[k * n + i] = VT[i * n + col];
    }
  }
  if (s->d.kind == SC_MAPN_NS) {
    if (bordered(s, 2))
      return sc_fail(msg, SC_ESING, "sc_mapn_system_init: singular "
                                    "bordered matrix");
    choose_pair(s, u);
  }
  return SC_OK;
}

int sc_mapn_system_update(sc_mapn_system *s, const double *u, sc_msg *msg) {
  if (s->d.kind == SC_MAPN_FIXED) return SC_OK;
  size_t n = s->n;
  int rc = jet_at(s, u, 2);
  if (rc)
    return sc_fail(msg, SC_ECALLBACK,
                   "sc_mapn_system_update: the map or its first or second "
                   "derivatives could not be evaluated there (%s)",
                   rc > 0 ? "a non-finite value: a model without second "
                            "derivatives, or a point where the map is not "
                            "smooth"
                          : "the evaluation failed");
  if (s->d.kind == SC_MAPN_NS) {
    ns_matrix(s, u[n]);
    if (bordered(s, 2)) goto sing;
    for (size_t k = 0; k < 2; k++)
      for (size_t i = 0; i < n; i++) {
        s->Q[k * n + i] = s->V[k * (n + 2) + i];
        s->P[k * n + i] = s->W[k * (n + 2) + i];
      }
    orthonormalize(s->Q, n);
    orthonormalize(s->P, n);
    if (bordered(s, 2)) goto sing;
    choose_pair(s, u);
    return SC_OK;
  }
  shifted(s);
  if (bordered(s, 1)) goto sing;
  memcpy(s->c, s->V, n * sizeof *s->c);
  memcpy(s->b, s->W, n * sizeof *s->b);
  normalize(s->c, n);
  normalize(s->b, n);
  return SC_OK;
sing:
  return sc_fail(msg, SC_ESING,
                 "sc_mapn_system_update: singular bordered matrix (start "
                 "again with sc_mapn_system_init)");
}

int sc_mapn_system_vectors(sc_mapn_system *s, const double *u, double *v,
                           double *w, sc_msg *msg) {
  if (s->d.kind == SC_MAPN_FIXED)
    return sc_fail(msg, SC_EINVAL,
                   "sc_mapn_system_vectors: a fixed-point system has none");
  size_t n = s->n;
  int rc = bordered_at(s, u, 1);
  if (rc)
    return sc_fail(msg, rc < 0 ? SC_ECALLBACK : SC_ESING,
                   "sc_mapn_system_vectors: %s at the point",
                   rc < 0 ? "the map failed" : "singular bordered matrix");
  size_t nb = s->d.kind == SC_MAPN_NS ? 2 : 1;
  for (size_t k = 0; k < nb; k++)
    for (size_t i = 0; i < n; i++) {
      if (v) v[k * n + i] = s->V[k * (n + nb) + i];
      if (w) w[k * n + i] = s->W[k * (n + nb) + i];
    }
  if (nb == 1) {
    if (v) normalize(v, n);
    if (w) normalize(w, n);
  }
  return SC_OK;
}

/* ------------------------------------------------------------------ */
/* Continuation problem and Newton                                     */
/* ------------------------------------------------------------------ */

static int pb_f(const double *u, double *F, void *user) {
  return sc_mapn_system_f(user, u, F);
}
static int pb_jac(const double *u, double *J, void *user) {
  return sc_mapn_system_jac(user, u, J);
}
static int pb_test(const double *u, const double *t, double *psi,
                   void *user) {
  return sc_mapn_system_tests(user, u, t, psi);
}

static const char *const fixed_names[] = {"LP", "PD", "NS", "BP"};

int sc_mapn_system_problem(sc_mapn_system *s, sc_cont_problem *pb,
                           sc_msg *msg) {
  if (s->nu != s->neq + 1)
    return sc_fail(msg, SC_EINVAL,
                   "sc_mapn_system_problem: %zu equations in %zu unknowns "
                   "(valid: one more unknown than equations)",
                   s->neq, s->nu);
  memset(pb, 0, sizeof *pb);
  pb->n = s->neq;
  pb->f = pb_f;
  pb->jac = pb_jac;
  pb->user = s;
  if (s->d.kind == SC_MAPN_FIXED) {
    pb->ntest = SC_MAPN_NTEST;
    pb->test = pb_test;
    pb->test_names = fixed_names;
  }
  return SC_OK;
}

static double max_abs(const double *v, size_t n) {
  double m = 0;
  for (size_t i = 0; i < n; i++) m = fmax(m, fabs(v[i]));
  return m;
}

int sc_mapn_system_solve(sc_mapn_system *s, double *u, const sc_accuracy *acc,
                         sc_curve_cert *cert, sc_msg *msg) {
  size_t N = s->nu;
  memset(cert, 0, sizeof *cert);
  cert->residual = cert->step = HUGE_VAL;
  if (s->nu != s->neq)
    return sc_fail(msg, SC_EINVAL,
                   "sc_mapn_system_solve: %zu equations in %zu unknowns "
                   "(valid: a square system)",
                   s->neq, s->nu);
  double F[MAXB + 1], J[(MAXB + 1) * (MAXB + 1)];
  int piv[MAXB + 1];
  double prev = HUGE_VAL;
  for (int it = 1; it <= acc->newton_maxiter; it++) {
    int rc = sc_mapn_system_f(s, u, F);
    if (rc == 0) rc = sc_mapn_system_jac(s, u, J);
    if (rc == 0 && !isfinite(max_abs(F, N) + max_abs(J, N * N))) rc = 1;
    if (rc)
      return sc_fail(msg, SC_ECALLBACK,
                     "sc_mapn_system_solve: the map or the bordered system "
                     "failed (%d) at iteration %d",
                     rc, it);
    cert->residual = max_abs(F, N);
    if (lu_factor(N, J, piv))
      return sc_fail(msg, SC_ESING,
                     "sc_mapn_system_solve: singular Jacobian at iteration %d "
                     "(residual %.3g)",
                     it, cert->residual);
    for (size_t i = 0; i < N; i++) F[i] = -F[i];
    lu_solve(N, J, piv, F);
    double step = max_abs(F, N), noise = NOISE_ULPS * DBL_EPSILON *
                                          (1 + max_abs(u, N));
    int small = 1;
    for (size_t i = 0; i < N; i++) {
      u[i] += F[i];
      if (sc_test_delta(F[i], u[i], acc->newton_atol, acc->newton_rtol) !=
              SC_OK &&
          !(fabs(F[i]) <= noise))
        small = 0;
    }
    cert->step = step;
    cert->iterations = it;
    if (small && (cert->residual <= acc->newton_ftol || step <= noise)) {
      rc = sc_mapn_system_f(s, u, F); /* the certificate at the answer */
      if (rc)
        return sc_fail(msg, SC_ECALLBACK,
                       "sc_mapn_system_solve: the map failed at the solution");
      cert->residual = max_abs(F, N);
      return SC_OK;
    }
    if (step > prev && step > noise)
      return sc_fail(msg, SC_ENOCONV,
                     "sc_mapn_system_solve: Newton diverging at iteration %d "
                     "(step %.3g > previous %.3g; residual %.3g)",
                     it, step, prev, cert->residual);
    prev = step;
  }
  return sc_fail(msg, SC_ENOCONV,
                 "sc_mapn_system_solve: not converged in %d iterations "
                 "(residual %.3g, step %.3g)",
                 acc->newton_maxiter, cert->residual, cert->step);
}
