/* Special points of n-dimensional branches (branchn.h): at a zero of a
 * test function of the fixed-point system, Newton on the point's own
 * defining system (mapn_system.h), its multipliers and normal-form
 * coefficient (normal_form.h), and the switch onto the period-doubled
 * branch at a flip and onto the crossing branch at a branch point.
 * docs/maps.md, "Branches". */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "analysis/branchn_impl.h"
#include "dense_impl.h"

/* Displacements of a switched start, in units of the job's h (the
 * segment's first step), in the order tried: h first; a smaller one if
 * Newton fell elsewhere, a larger one if the new branch is nearly
 * degenerate so close to the point it is born at. */
static const double switch_scales[] = {1, 0.3, 3, 0.1};
#define NSWITCH_SCALES (sizeof switch_scales / sizeof switch_scales[0])

/* A pivot at the rounding level of the matrix's largest entry (a
 * bordered Jacobian) carries no digit of the solution: singular. */
#define BN_SING DBL_EPSILON

/* The N x N row-major A (destroyed) solved for b (overwritten); -1 when
 * A is singular by BN_SING. */
int sc_bn_gauss(size_t N, double *A, double *b) {
  int ipiv[BN_MAXN + 1];
  return sc_dense_solve(N, A, b, ipiv, BN_SING) ? -1 : 0;
}

/* ------------------------------------------------------------------ */
/* Switched starts                                                      */

/* Newton on {g(x, p) - x = 0, dvec . (u - u*) = h} from u* + h dvec;
 * with @p t non-NULL, also the tangent there with t . dvec > 0. */
static int displaced_newton(sc_branchn *b, sc_mapn_system *sys,
                            const bn_job *j, double h, double *u, double *t) {
  size_t n = b->n, N = n + 1;
  double F[BN_MAXN + 1], A[(BN_MAXN + 1) * (BN_MAXN + 1)];
  for (size_t i = 0; i < N; i++) u[i] = j->u[i] + h * j->dvec[i];
  for (int it = 0; it < b->acc.newton_maxiter; it++) {
    if (sc_mapn_system_f(sys, u, F) || sc_mapn_system_jac(sys, u, A))
      return -1;
    double res = 0, c = -h;
    for (size_t i = 0; i < n; i++) res = fmax(res, fabs(F[i]));
    for (size_t i = 0; i < N; i++) {
      A[n * N + i] = j->dvec[i];
      c += j->dvec[i] * (u[i] - j->u[i]);
    }
    for (size_t i = 0; i < n; i++) F[i] = -F[i];
    F[n] = -c;
    if (sc_bn_gauss(N, A, F)) return -1;
    int small = 1;
    for (size_t i = 0; i < N; i++) {
      u[i] += F[i];
      small &= sc_test_delta(F[i], u[i], b->acc.newton_atol,
                             b->acc.newton_rtol) == SC_OK;
    }
    if (small && res <= b->acc.newton_ftol) break;
    if (it == b->acc.newton_maxiter - 1) return -1;
  }
  if (!t) return 0;
  if (sc_mapn_system_jac(sys, u, A)) return -1;
  for (size_t i = 0; i < N; i++) {
    A[n * N + i] = j->dvec[i];
    t[i] = i == n;
  }
  return sc_bn_gauss(N, A, t);
}

/* The orbit through x has a period dividing m / 2 (a doubled start that
 * fell back onto the orbit it was born from). */
static int half_period(sc_branchn *b, int period, const double *u) {
  if (period % 2 || sc_map_set_param(b->m, b->param, u[b->n], NULL))
    return 0;
  if (sc_map_iterate_n(b->m, u, period / 2, 0, b->v1, NULL)) return 0;
  for (size_t i = 0; i < b->n; i++)
    if (fabs(b->v1->f[i] - u[i]) > sc_orbit_tol(&b->acc, u[i])) return 0;
  return 1;
}

int sc_bn_displaced_start(sc_branchn *b, const bn_job *j, double *u,
                          int *dir, sc_msg *msg) {
  sc_mapn_system *sys;
  int st = sc_bn_make_system(b, SC_MAPN_FIXED, &sys, msg);
  if (st) return st;
  st = SC_ENOCONV;
  for (size_t k = 0; k < NSWITCH_SCALES && st; k++) {
    double t[BN_MAXN + 1];
    if (displaced_newton(b, sys, j, j->h * switch_scales[k], u, t)) continue;
    if (j->doubled && half_period(b, j->period, u)) continue;
    *dir = t[b->n] >= 0 ? 1 : -1;
    st = SC_OK;
  }
  sc_mapn_system_free(sys);
  if (st)
    return sc_fail(msg, SC_ENOCONV,
                   "Newton from displacements %g to %g along the new "
                   "direction did not converge onto a new orbit",
                   j->h * 0.1, j->h * 3);
  return SC_OK;
}

/* ------------------------------------------------------------------ */
/* Location                                                             */

/* kappa = Re(mu_i + mu_j) / 2 of the pair of multipliers whose product
 * is nearest 1 (the pair the NS test's zero is about). */
static double kappa_guess(const double *re, const double *im, size_t n) {
  double best = HUGE_VAL, kappa = 0;
  for (size_t i = 0; i < n; i++)
    for (size_t k = i + 1; k < n; k++) {
      double pr = re[i] * re[k] - im[i] * im[k];
      double pi = re[i] * im[k] + im[i] * re[k];
      double d = hypot(pr - 1, pi);
      if (d < best) {
        best = d;
        kappa = (re[i] + re[k]) / 2;
      }
    }
  return kappa;
}

/* Another special point with the same label and period within the
 * orbit tolerance, or NULL. */
static const bn_special *seen(const sc_branchn *b, const bn_special *s) {
  for (size_t i = 0; i + 1 < b->nsp; i++) {
    const bn_special *o = &b->sps[i];
    if (o->label != s->label || o->period != s->period ||
        o->method != SC_LOC_NEWTON ||
        fabs(o->p - s->p) > sc_orbit_tol(&b->acc, s->p))
      continue;
    int same = 1;
    for (size_t k = 0; k < b->n; k++)
      same &= fabs(o->x[k] - s->x[k]) <= sc_orbit_tol(&b->acc, s->x[k]);
    if (same) return o;
  }
  return NULL;
}

/* The normal-form coefficient at the located point (its jet of g = f^m),
 * and for a flip its eigenvector q (n values) for the switch. */
static void coefficient(sc_branchn *b, bn_special *s, double *q) {
  if (sc_map_set_param(b->m, b->param, s->p, NULL) ||
      sc_map_iterate_n(b->m, s->x, s->period, SC_EVAL_DERIV2, b->v2, NULL))
    return;
  sc_nf_jet g = {.n = b->n, .A = b->v2->J, .H = b->v2->H, .T = b->v2->T};
  sc_nf nf;
  sc_msg m2 = {{0}};
  int st = SC_EINVAL;
  size_t len = strlen(s->note);
  const char *sign = "";
  if (s->label == SC_PTN_LP) {
    st = sc_nf_fold(&g, NULL, &nf, &m2);
  } else if (s->label == SC_PTN_PD) {
    st = sc_nf_flip(&g, &nf, &m2);
    if (!st) sign = nf.coef > 0 ? "supercritical (b > 0)" : "subcritical";
  } else if (s->label == SC_PTN_NS) {
    double mu[2] = {s->kappa, sqrt(fmax(0, 1 - s->kappa * s->kappa))};
    st = sc_nf_ns(&g, mu, &nf, &m2);
    if (!st) sign = nf.coef < 0 ? "supercritical (d < 0)" : "subcritical";
  }
  if (st) {
    snprintf(s->note + len, sizeof s->note - len, "%scoefficient: %s",
             len ? "; " : "", sc_msg_what(m2.text));
    return;
  }
  s->coef = nf.coef;
  if (q) memcpy(q, nf.q, b->n * sizeof *q);
  if (*sign)
    snprintf(s->note + len, sizeof s->note - len, "%s%s", len ? "; " : "",
             sign);
}

/* Newton on the system of @p kind from the located point u (x, p) of
 * the branch, into a new special point. */
static bn_special *solve_point(sc_branchn *b, sc_mapn_kind kind, int branch,
                               int period, const double *u, sc_msg *msg,
                               int *status) {
  size_t n = b->n;
  sc_mapn_system *sys = NULL;
  *status = sc_bn_make_system(b, kind, &sys, msg);
  if (*status) return NULL;
  bn_special *s = sc_bn_new_special(b);
  if (!s) {
    sc_mapn_system_free(sys);
    *status = sc_fail(msg, SC_ENOMEM, "branch: out of memory");
    return NULL;
  }
  s->branch = branch;
  s->period = period;
  s->label = kind == SC_MAPN_FOLD   ? SC_PTN_LP
             : kind == SC_MAPN_FLIP ? SC_PTN_PD
             : kind == SC_MAPN_NS   ? SC_PTN_NS
                                    : SC_PTN_BP;
  double w[BN_MAXN + 2], re[BN_MAXN], im[BN_MAXN];
  size_t ne = sc_mapn_system_nextra(sys);
  memcpy(w, u, n * sizeof *w);
  w[n + ne] = u[n];
  if (kind == SC_MAPN_BP) w[n] = 0;
  if (kind == SC_MAPN_NS) {
    if (sc_bn_multipliers(b, period, u, u[n], re, im, msg)) w[n] = 0;
    else w[n] = kappa_guess(re, im, n);
  }
  sc_curve_cert c = {0};
  sc_msg m2 = {{0}};
  int st = sc_mapn_system_init(sys, w, &m2);
  if (!st) st = sc_mapn_system_solve(sys, w, &b->acc, &c, &m2);
  if (st) {
    memcpy(s->x, u, n * sizeof *u);
    s->p = u[n];
    s->method = SC_LOC_FAILED;
    s->error = c.step;
    snprintf(s->note, sizeof s->note, "not located: %s",
             sc_msg_what(m2.text));
  } else {
    memcpy(s->x, w, n * sizeof *w);
    s->p = w[n + ne];
    s->method = SC_LOC_NEWTON;
    s->residual = c.residual;
    s->error = c.step;
    s->iterations = c.iterations;
    if (kind == SC_MAPN_NS) {
      s->kappa = w[n];
      if (fabs(s->kappa) < 1) s->theta = acos(s->kappa);
      else s->label = SC_PTN_NN;
      if (s->label == SC_PTN_NN)
        snprintf(s->note, sizeof s->note,
                 "neutral saddle (real multipliers mu, 1/mu): not a "
                 "bifurcation");
    }
  }
  if (sc_bn_multipliers(b, period, s->x, s->p, s->re, s->im, &m2))
    for (size_t i = 0; i < n; i++) s->re[i] = s->im[i] = NAN;
  sc_mapn_system_free(sys);
  return s;
}

/* ------------------------------------------------------------------ */
/* Switching                                                            */

static int push_switch(sc_branchn *b, bn_special *s, int period,
                       const double *dvec, int doubled, const char *what) {
  bn_job j = {.period = period, .displaced = 1, .doubled = doubled,
              .h = b->set.h0, .dir = 1};
  memcpy(j.u, s->x, b->n * sizeof *j.u);
  j.u[b->n] = s->p;
  memcpy(j.dvec, dvec, (b->n + 1) * sizeof *dvec);
  snprintf(j.why, sizeof j.why, "%.40s of the %s at %.10g: ", what,
           sc_branchn_label_text(s->label), s->p);
  int st = sc_bn_push_job(b, &j);
  if (st) return st;
  size_t len = strlen(s->note);
  snprintf(s->note + len, sizeof s->note - len, "%s%s: segment queued",
           len ? "; " : "", what);
  return SC_OK;
}

/* The crossing branch's direction at a branch point: the null vector of
 * F_u = [g_x - I, g_p] orthogonal to the branch's tangent t, from the
 * right null vector v of g_x - I (F_u (v, 0) = 0). */
static int bp_switch(sc_branchn *b, bn_special *s, const double *t,
                     sc_msg *msg) {
  size_t n = b->n, N = n + 1;
  sc_mapn_system *sys;
  int st = sc_bn_make_system(b, SC_MAPN_BP, &sys, msg);
  if (st) return st;
  double w[BN_MAXN + 2], v[BN_MAXN], d[BN_MAXN + 1], dm[BN_MAXN + 1];
  memcpy(w, s->x, n * sizeof *w);
  w[n] = 0;
  w[n + 1] = s->p;
  sc_msg m2;
  st = sc_mapn_system_init(sys, w, &m2);
  if (!st) st = sc_mapn_system_vectors(sys, w, v, NULL, &m2);
  sc_mapn_system_free(sys);
  if (st) return SC_OK; /* no switch: the note keeps the point */
  double dt = 0, nr = 0;
  for (size_t i = 0; i < n; i++) dt += v[i] * t[i];
  for (size_t i = 0; i < N; i++) {
    d[i] = (i < n ? v[i] : 0) - dt * t[i];
    nr += d[i] * d[i];
  }
  for (size_t i = 0; i < N; i++) {
    d[i] /= sqrt(nr);
    dm[i] = -d[i];
  }
  st = push_switch(b, s, s->period, d, 0, "crossing branch");
  if (!st) st = push_switch(b, s, s->period, dm, 0, "its other half");
  return st;
}

int sc_bn_special(sc_branchn *b, int branch, int period, const double *u,
                  const double *t, int test, sc_msg *msg) {
  size_t n = b->n;
  /* det(g_x - I) vanishes at a branch point too, where the branch does
   * not turn: a fold is where the tangent's parameter component is of
   * the order of the located test (at most test_atol), a branch point
   * where it is of order one; the geometric mean tells them apart.  Both
   * tests change sign there, one step locates one of them, and the other
   * is found again next to it: each is located as the branch point, once
   * (the second is the first met again on the same segment). */
  if (test == SC_MAPN_TEST_LP && fabs(t[n]) > sqrt(b->set.test_atol))
    test = SC_MAPN_TEST_BP;
  static const sc_mapn_kind kinds[] = {SC_MAPN_FOLD, SC_MAPN_FLIP,
                                       SC_MAPN_NS, SC_MAPN_BP};
  if (test < 0 || test >= SC_MAPN_NTEST) return SC_OK;
  if (test == SC_MAPN_TEST_NS && n < 2) return SC_OK;
  int st;
  bn_special *s = solve_point(b, kinds[test], branch, period, u, msg, &st);
  if (!s) return st;
  const bn_special *o = s->method == SC_LOC_NEWTON ? seen(b, s) : NULL;
  if (o) {
    b->ndup += o->branch != branch;
    b->nsp--;
    return SC_OK;
  }
  if (s->method != SC_LOC_NEWTON) return SC_OK;
  double q[BN_MAXN], dvec[BN_MAXN + 1];
  coefficient(b, s, q);
  if (s->label == SC_PTN_PD && b->sp.switch_pd &&
      2 * period <= b->sp.max_period) {
    if (!isfinite(s->coef)) { /* no normal form: the null vector serves */
      sc_mapn_system *sys;
      if ((st = sc_bn_make_system(b, SC_MAPN_FLIP, &sys, msg))) return st;
      double w[BN_MAXN + 1];
      memcpy(w, s->x, n * sizeof *w);
      w[n] = s->p;
      sc_msg m2;
      int bad = sc_mapn_system_init(sys, w, &m2) ||
                sc_mapn_system_vectors(sys, w, q, NULL, &m2);
      sc_mapn_system_free(sys);
      if (bad) return SC_OK;
    }
    memcpy(dvec, q, n * sizeof *q);
    dvec[n] = 0;
    return push_switch(b, s, 2 * period, dvec, 1, "doubled branch");
  }
  if (s->label == SC_PTN_BP && b->sp.switch_bp) return bp_switch(b, s, t, msg);
  return SC_OK;
}
