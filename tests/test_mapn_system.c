/* The defining systems of n-dimensional map iterates (mapn_system.h):
 * every Jacobian against central differences of its equations, the test
 * functions of the fixed-point branch against the trace and determinant,
 * and Newton onto ghenon's fold, flip and Neimark-Sacker points and a
 * neutral saddle against their closed forms, and onto the pitchfork of a
 * symmetric map.
 *
 * ghenon (x, y) -> (y, alpha - beta x - y^2 + R x y): fixed points x = y
 * = s with (1 - R) s^2 + (1 + beta) s - alpha = 0, Jacobian trace
 * tr = (R - 2) s, determinant det = beta - R s; fold where 1 - tr + det =
 * 0, i.e. s = -(1 + beta) / (2 (1 - R)); flip where 1 + tr + det = 0,
 * i.e. s = (1 + beta) / 2; NS where det = 1, |tr| < 2, i.e.
 * s = (beta - 1) / R, with kappa = cos theta = tr / 2. */
#include <math.h>
#include <string.h>

#include "slipcont/map.h"
#include "slipcont/mapn_system.h"
#include "test_util.h"

/* Central differences of the systems' equations with h = 1e-6: their
 * error is ~h^2 |F'''| + eps |F| / h ~ 1e-10 for these moderate maps. */
static const double FD_H = 1e-6;
static const double FD_TOL = 1e-7;
/* The located points' closed forms: Newton converges to the rounding of
 * the equations, a few ulps of O(1) numbers amplified by the bordered
 * systems' condition. */
static const double PT_TOL = 1e-12;

/* g = f^m of a model through the map layer. */
typedef struct {
  sc_map *m;
  sc_mapn_value *v;
  int period;
} model_map;

static int model_fn(const double *x, const double *p, int order,
                    sc_mapn_jet *jet, void *user) {
  model_map *mm = user;
  size_t n = sc_map_dim(mm->m), np = sc_map_nparam(mm->m);
  sc_msg msg;
  for (size_t q = 0; q < np; q++)
    if (sc_map_set_param(mm->m, q, p[q], &msg)) return 1;
  unsigned flags = order >= 2 ? SC_EVAL_DERIV2 : order == 1 ? SC_EVAL_DERIV : 0;
  if (sc_map_iterate_n(mm->m, x, mm->period, flags, mm->v, &msg)) return 1;
  memcpy(jet->g, mm->v->f, n * sizeof *jet->g);
  if (order >= 1) {
    memcpy(jet->gx, mm->v->J, n * n * sizeof *jet->gx);
    memcpy(jet->gp, mm->v->fp, np * n * sizeof *jet->gp);
  }
  if (order >= 2) {
    memcpy(jet->gxx, mm->v->H, n * n * n * sizeof *jet->gxx);
    memcpy(jet->gxp, mm->v->Jp, np * n * n * sizeof *jet->gxp);
  }
  return 0;
}

/* A map with a Z2 symmetry (x, y) -> (-x, -y): (x, y) -> (p x + y / 2 -
 * x^3, x / 4 + q y).  The origin is fixed for all p; det(J - I) =
 * (p - 1)(q - 1) - 1/8 vanishes at p = 1 + 1 / (8 (q - 1)), where the
 * symmetric pair x^2 = ... branches off: a pitchfork (BP). */
static int pitch_fn(const double *x, const double *p, int order,
                    sc_mapn_jet *jet, void *user) {
  (void)user;
  double a = p[0], q = p[1];
  jet->g[0] = a * x[0] + 0.5 * x[1] - x[0] * x[0] * x[0];
  jet->g[1] = 0.25 * x[0] + q * x[1];
  if (order >= 1) {
    double J[4] = {a - 3 * x[0] * x[0], 0.5, 0.25, q};
    double gp[4] = {x[0], 0, 0, x[1]};
    memcpy(jet->gx, J, sizeof J);
    memcpy(jet->gp, gp, sizeof gp);
  }
  if (order >= 2) {
    memset(jet->gxx, 0, 8 * sizeof *jet->gxx);
    memset(jet->gxp, 0, 8 * sizeof *jet->gxp);
    jet->gxx[0] = -6 * x[0];     /* d2 g_0 / dx0 dx0 */
    jet->gxp[0] = 1;             /* d g_x[0][0] / dp */
    jet->gxp[4 + 3] = 1;         /* d g_x[1][1] / dq */
  }
  return 0;
}

/* The Jacobian of @p s at @p u against central differences of its F. */
static void check_jac(const char *what, sc_mapn_system *s, const double *u) {
  size_t ne = sc_mapn_system_nequations(s), nu = sc_mapn_system_nunknowns(s);
  double J[400], Fp[20], Fm[20], up[20], err = 0, scale = 1;
  tu_true(sc_mapn_system_jac(s, u, J) == 0, "%s: Jacobian evaluates", what);
  for (size_t j = 0; j < nu; j++) {
    memcpy(up, u, nu * sizeof *u);
    up[j] = u[j] + FD_H;
    sc_mapn_system_f(s, up, Fp);
    up[j] = u[j] - FD_H;
    sc_mapn_system_f(s, up, Fm);
    for (size_t i = 0; i < ne; i++) {
      double fd = (Fp[i] - Fm[i]) / (2 * FD_H);
      err = fmax(err, fabs(J[i * nu + j] - fd));
      scale = fmax(scale, fabs(fd));
    }
  }
  char buf[128];
  snprintf(buf, sizeof buf, "%s: Jacobian vs differences (relative)", what);
  tu_close(buf, err / scale, 0, FD_TOL);
}

static sc_mapn_system *make(sc_mapn_fn fn, void *user, sc_mapn_kind kind,
                            size_t np, const double *p, size_t nfree, int a,
                            int b) {
  sc_mapn_def d = {.fn = fn, .user = user, .kind = kind, .n = 2, .np = np,
                   .nfree = nfree, .ifree = {a, b}};
  memcpy(d.p, p, np * sizeof *p);
  sc_mapn_system *s = NULL;
  sc_msg msg;
  int st = sc_mapn_system_alloc(&d, &s, &msg);
  tu_true(st == SC_OK, "alloc kind %d: %s", (int)kind, msg.text);
  return s;
}

/* Every system's Jacobian at generic points (not on the special point:
 * the formulas hold everywhere). */
static void check_jacobians(model_map *mm) {
  double p[3] = {0.3, 0.4, 0.25};
  struct {
    sc_mapn_kind k;
    size_t nfree;
    const char *what;
  } c[] = {{SC_MAPN_FIXED, 1, "fixed"}, {SC_MAPN_FOLD, 1, "fold"},
           {SC_MAPN_FLIP, 1, "flip"},   {SC_MAPN_NS, 1, "ns"},
           {SC_MAPN_FOLD, 2, "fold curve"}, {SC_MAPN_FLIP, 2, "flip curve"},
           {SC_MAPN_NS, 2, "ns curve"}};
  for (size_t i = 0; i < sizeof c / sizeof *c; i++) {
    sc_mapn_system *s = make(model_fn, mm, c[i].k, 3, p, c[i].nfree, 0, 2);
    double u[6] = {0.21, 0.37, 0, 0, 0, 0};
    size_t at = 2;
    if (c[i].k == SC_MAPN_NS) u[at++] = -0.35; /* kappa */
    u[at++] = 0.3;
    if (c[i].nfree == 2) u[at++] = 0.25;
    sc_msg msg;
    tu_int("init", sc_mapn_system_init(s, u, &msg), SC_OK);
    check_jac(c[i].what, s, u);
    sc_mapn_system_free(s);
  }
  mm->period = 2;
  sc_mapn_system *s = make(model_fn, mm, SC_MAPN_FLIP, 3, p, 2, 1, 0);
  double u[4] = {0.11, 0.47, 0.41, 0.33};
  sc_msg msg;
  sc_mapn_system_init(s, u, &msg);
  check_jac("flip curve of f^2", s, u);
  sc_mapn_system_free(s);
  s = make(model_fn, mm, SC_MAPN_NS, 3, p, 1, 2, 0);
  double w[4] = {0.11, 0.47, 0.2, 0.33};
  sc_mapn_system_init(s, w, &msg);
  check_jac("ns of f^2", s, w);
  sc_mapn_system_free(s);
  mm->period = 1;
  double pq[2] = {0.8, 0.2};
  s = make(pitch_fn, NULL, SC_MAPN_BP, 2, pq, 1, 0, 0);
  double b[4] = {0.13, -0.21, 0.05, 0.8};
  sc_mapn_system_init(s, b, &msg);
  check_jac("branch point", s, b);
  sc_mapn_system_free(s);
}

/* The fixed-point branch's tests: for n = 2, det(J - I) = 1 - tr + det,
 * det(J + I) = 1 + tr + det, and the bialternate product is det J. */
static void check_tests(model_map *mm) {
  double al = 0.3, be = 0.4, R = 0.25, p[3] = {al, be, R};
  sc_mapn_system *s = make(model_fn, mm, SC_MAPN_FIXED, 3, p, 1, 0, 0);
  double x = 0.23, y = -0.41, u[3] = {x, y, al};
  double J[4] = {0, 1, -be + R * y, -2 * y + R * x};
  double tr = J[0] + J[3], det = J[0] * J[3] - J[1] * J[2];
  double t[3] = {0.6, 0, 0.8}, psi[SC_MAPN_NTEST];
  tu_int("tests evaluate", sc_mapn_system_tests(s, u, t, psi), 0);
  /* the scaled determinants: each row's norm (at least 1) divides */
  double r0 = fmax(1, hypot(J[0] - 1, J[1])), r1 = fmax(1, hypot(J[2], J[3] - 1));
  tu_close("LP test", psi[SC_MAPN_TEST_LP], (1 - tr + det) / (r0 * r1), 1e-15);
  r0 = fmax(1, hypot(J[0] + 1, J[1]));
  r1 = fmax(1, hypot(J[2], J[3] + 1));
  tu_close("PD test", psi[SC_MAPN_TEST_PD], (1 + tr + det) / (r0 * r1), 1e-15);
  tu_close("NS test", psi[SC_MAPN_TEST_NS],
           (det - 1) / fmax(1, fabs(det - 1)), 1e-15);
  /* BP: det [[J - I, g_alpha], [t^T]] with g_alpha = (0, 1) */
  double A[9] = {J[0] - 1, J[1], 0, J[2], J[3] - 1, 1, t[0], t[1], t[2]};
  double d3 = A[0] * (A[4] * A[8] - A[5] * A[7]) -
              A[1] * (A[3] * A[8] - A[5] * A[6]) +
              A[2] * (A[3] * A[7] - A[4] * A[6]);
  double n0 = fmax(1, sqrt(A[0] * A[0] + A[1] * A[1] + A[2] * A[2]));
  double n1 = fmax(1, sqrt(A[3] * A[3] + A[4] * A[4] + A[5] * A[5]));
  tu_close("BP test", psi[SC_MAPN_TEST_BP], d3 / (n0 * n1), 1e-15);
  sc_cont_problem pb;
  sc_msg msg;
  tu_int("fixed system is a continuation problem",
         sc_mapn_system_problem(s, &pb, &msg), SC_OK);
  tu_int("with four tests", (long)pb.ntest, 4);
  double uu[3];
  tu_int("a square system has no Newton of its own here",
         sc_mapn_system_solve(s, uu, NULL, &(sc_curve_cert){0}, &msg),
         SC_EINVAL);
  sc_mapn_system_free(s);
}

/* Newton from a perturbed start onto a special point, its closed form. */
static void locate(const char *what, model_map *mm, sc_mapn_kind k, int ifree,
                   const double *p, double *u, const double *want,
                   size_t nu) {
  sc_mapn_system *s = make(model_fn, mm, k, 3, p, 1, ifree, 0);
  sc_accuracy acc;
  sc_msg msg;
  sc_accuracy_preset(&acc, "default", &msg);
  acc.newton_atol = 1e-14;
  acc.newton_ftol = 1e-14;
  sc_curve_cert c;
  tu_int("init", sc_mapn_system_init(s, u, &msg), SC_OK);
  int st = sc_mapn_system_solve(s, u, &acc, &c, &msg);
  tu_true(st == SC_OK, "%s: Newton converges: %s", what, msg.text);
  char buf[128];
  for (size_t i = 0; i < nu; i++) {
    snprintf(buf, sizeof buf, "%s: u[%zu]", what, i);
    tu_close(buf, u[i], want[i], PT_TOL);
  }
  snprintf(buf, sizeof buf, "%s: residual certificate", what);
  tu_close(buf, c.residual, 0, 1e-14);
  snprintf(buf, sizeof buf, "%s: iterations (quadratic convergence)", what);
  tu_true(c.iterations <= 8, "%s: %d", buf, c.iterations);
  sc_mapn_system_free(s);
}

static void check_points(model_map *mm) {
  double be = 0.3, R = 0.2;
  /* fold in alpha */
  double s = -(1 + be) / (2 * (1 - R));
  double al = (1 - R) * s * s + (1 + be) * s;
  double p[3] = {0, be, R};
  double u[3] = {s + 0.02, s - 0.03, al + 0.01}, want[3] = {s, s, al};
  locate("ghenon fold (alpha)", mm, SC_MAPN_FOLD, 0, p, u, want, 3);
  /* flip in alpha */
  s = (1 + be) / 2;
  al = (1 - R) * s * s + (1 + be) * s;
  double u2[3] = {s - 0.02, s + 0.01, al - 0.03}, w2[3] = {s, s, al};
  locate("ghenon flip (alpha)", mm, SC_MAPN_FLIP, 0, p, u2, w2, 3);
  /* NS in alpha: beta = 0.6, R = -1: s = 0.4, tr = -1.2, kappa = -0.6 */
  be = 0.6, R = -1;
  s = (be - 1) / R;
  al = (1 - R) * s * s + (1 + be) * s;
  double kap = (R - 2) * s / 2;
  double pn[3] = {0, be, R};
  double u3[4] = {s + 0.01, s - 0.02, kap + 0.03, al + 0.02};
  double w3[4] = {s, s, kap, al};
  locate("ghenon NS (alpha)", mm, SC_MAPN_NS, 0, pn, u3, w3, 4);
  /* NS in beta at alpha fixed: det = 1 gives beta = 1 + R s, and the
   * fixed point (1 - R) s^2 + (2 + R s) s = alpha, i.e. s^2 + 2 s =
   * alpha: s = -1 + sqrt(1 + alpha) */
  al = 0.5, R = -0.8;
  s = -1 + sqrt(1 + al);
  be = 1 + R * s;
  kap = (R - 2) * s / 2;
  double pb[3] = {al, 0, R};
  double u4[4] = {s - 0.01, s + 0.01, kap - 0.02, be + 0.02};
  double w4[4] = {s, s, kap, be};
  locate("ghenon NS (beta)", mm, SC_MAPN_NS, 1, pb, u4, w4, 4);
  /* a neutral saddle: det = 1 with |tr| > 2 (R = -3, beta = -0.5: s =
   * 0.5, tr = -2.5, kappa = -1.25) */
  be = -0.5, R = -3;
  s = (be - 1) / R;
  al = (1 - R) * s * s + (1 + be) * s;
  kap = (R - 2) * s / 2;
  double pq[3] = {0, be, R};
  double u5[4] = {s + 0.01, s + 0.01, kap + 0.02, al - 0.01};
  double w5[4] = {s, s, kap, al};
  locate("ghenon neutral saddle (alpha)", mm, SC_MAPN_NS, 0, pq, u5, w5, 4);
  tu_true(fabs(w5[2]) > 1, "neutral saddle has |kappa| > 1: %g", w5[2]);
}

/* The pitchfork of the symmetric map: x = y = 0, mu = 0, p = 1 + 1 / (8
 * (q - 1)). */
static void check_bp(void) {
  double q = 0.2, pq[2] = {0.8, q}, pstar = 1 + 1 / (8 * (q - 1));
  sc_mapn_system *s = make(pitch_fn, NULL, SC_MAPN_BP, 2, pq, 1, 0, 0);
  double u[4] = {0.01, -0.02, 0.01, pstar + 0.03};
  sc_accuracy acc;
  sc_msg msg;
  sc_accuracy_preset(&acc, "default", &msg);
  acc.newton_atol = 1e-14;
  acc.newton_ftol = 1e-14;
  sc_curve_cert c;
  tu_int("BP init", sc_mapn_system_init(s, u, &msg), SC_OK);
  int st = sc_mapn_system_solve(s, u, &acc, &c, &msg);
  tu_true(st == SC_OK, "BP: Newton converges: %s", msg.text);
  tu_close("BP x", u[0], 0, PT_TOL);
  tu_close("BP y", u[1], 0, PT_TOL);
  tu_close("BP mu", u[2], 0, PT_TOL);
  tu_close("BP p", u[3], pstar, PT_TOL);
  sc_mapn_system_free(s);
}


/* The fold curve of ghenon in (alpha, beta) at R fixed, by continuation
 * of the minimally augmented system with its borders updated at every
 * point: each point on (1 + beta)^2 + 4 (1 - R) alpha = 0 and x = y = s
 * = -(1 + beta) / (2 (1 - R)); and the null vectors at the last one. */
static void check_fold_curve(model_map *mm) {
  double R = 0.2, be = 0.3, s = -(1 + be) / (2 * (1 - R));
  double p[3] = {(1 - R) * s * s + (1 + be) * s, be, R};
  sc_mapn_system *sys = make(model_fn, mm, SC_MAPN_FOLD, 3, p, 2, 0, 1);
  sc_cont_problem pb;
  sc_msg msg;
  tu_int("fold curve problem", sc_mapn_system_problem(sys, &pb, &msg), SC_OK);
  double u[4] = {s, s, p[0], be};
  tu_int("fold curve init", sc_mapn_system_init(sys, u, &msg), SC_OK);
  sc_cont_settings set;
  sc_cont_settings_default(&set);
  set.pmax = 1.5;
  set.hmax = 0.05;
  sc_accuracy acc;
  sc_accuracy_preset(&acc, "default", &msg);
  sc_branch *b;
  tu_int("branch alloc", sc_branch_alloc(&pb, &set, &acc, &b, &msg), SC_OK);
  tu_int("branch set", sc_branch_set(b, u, &msg), SC_OK);
  double worst = 0;
  int st, npts = 0;
  while ((st = sc_branch_step(b, &msg)) == SC_CONTINUE && npts < 200) {
    const double *q = sc_branch_point(b);
    double ss = -(1 + q[3]) / (2 * (1 - R));
    worst = fmax(worst, fabs((1 + q[3]) * (1 + q[3]) + 4 * (1 - R) * q[2]));
    worst = fmax(worst, fmax(fabs(q[0] - ss), fabs(q[1] - ss)));
    sc_mapn_system_update(sys, q, &msg);
    npts++;
  }
  tu_true(st == SC_END, "fold curve reaches beta = 1.5: %d %s", st, msg.text);
  tu_true(npts > 10, "fold curve: %d points", npts);
  /* the tolerance of the corrector (newton_atol 1e-10 by default) */
  tu_close("fold curve: points on the closed form", worst, 0, 1e-9);
  const double *q = sc_branch_point(b);
  double v[2], w[2], J[4] = {0, 1, -q[3] + R * q[1], -2 * q[1] + R * q[0]};
  tu_int("null vectors", sc_mapn_system_vectors(sys, q, v, w, &msg), SC_OK);
  double r = fmax(fabs((J[0] - 1) * v[0] + J[1] * v[1]),
                  fabs(J[2] * v[0] + (J[3] - 1) * v[1]));
  double l = fmax(fabs((J[0] - 1) * w[0] + J[2] * w[1]),
                  fabs(J[1] * w[0] + (J[3] - 1) * w[1]));
  tu_close("v spans the kernel of g_x - I", r, 0, 1e-9);
  tu_close("w spans the kernel of (g_x - I)^T", l, 0, 1e-9);
  tu_close("|v| = 1", hypot(v[0], v[1]), 1, 1e-15);
  sc_branch_free(b);
  sc_mapn_system_free(sys);
}

static void check_refusals(void) {
  double p[3] = {0.1, 0.2, 0.3};
  sc_mapn_def d = {.fn = pitch_fn, .kind = SC_MAPN_NS, .n = 1, .np = 2,
                   .nfree = 1};
  sc_mapn_system *s;
  sc_msg msg;
  memcpy(d.p, p, sizeof p);
  tu_int("NS with n = 1 refused", sc_mapn_system_alloc(&d, &s, &msg),
         SC_EINVAL);
  d.kind = SC_MAPN_BP, d.n = 2, d.nfree = 2, d.ifree[1] = 1;
  tu_int("BP with two free parameters refused",
         sc_mapn_system_alloc(&d, &s, &msg), SC_EINVAL);
  d.kind = SC_MAPN_FOLD, d.ifree[1] = 0;
  tu_int("equal free parameters refused", sc_mapn_system_alloc(&d, &s, &msg),
         SC_EINVAL);
  d.nfree = 1, d.ifree[0] = 2;
  tu_int("free index out of range refused",
         sc_mapn_system_alloc(&d, &s, &msg), SC_EINVAL);
  d.ifree[0] = 0, d.n = 17;
  tu_int("n above SC_MAPN_MAXDIM refused", sc_mapn_system_alloc(&d, &s, &msg),
         SC_EINVAL);
  d.n = 2;
  tu_int("fold point allocates", sc_mapn_system_alloc(&d, &s, &msg), SC_OK);
  sc_cont_problem pb;
  tu_int("a square system is not a continuation problem",
         sc_mapn_system_problem(s, &pb, &msg), SC_EINVAL);
  sc_mapn_system_free(s);
}

int main(void) {
  model_map mm = {.period = 1};
  sc_msg msg;
  sc_map_alloc("ghenon", NULL, &mm.m, &msg);
  sc_mapn_value_alloc(mm.m, SC_EVAL_DERIV2, &mm.v, &msg);
  check_jacobians(&mm);
  check_tests(&mm);
  check_points(&mm);
  check_bp();
  check_fold_curve(&mm);
  check_refusals();
  sc_mapn_value_free(mm.v);
  sc_map_free(mm.m);
  return tu_finish();
}
