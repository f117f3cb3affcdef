/* Fold, flip and Neimark-Sacker curves of n-dimensional maps
 * (sc_curven_trace, src/analysis/curven.c) against closed forms
 * (docs/maps.md, "Curves and codimension two"):
 *  - ghenon (alpha, beta, R): the fixed points x = y = s with
 *    (1 - R) s^2 + (1 + beta) s - alpha = 0, trace (R - 2) s and
 *    determinant beta - R s; its fold, flip and NS curves, R1 to R4 and
 *    LPPD in (alpha, beta), GPD on the flip curve and CH on the NS curve
 *    in (beta, R), and the coefficients a, b, d along them;
 *  - a cusp map with a stable direction (CP);
 *  - ghenon times a one-dimensional fold or flip (3-d: LPNS, PDNS on the
 *    NS curve) and times a planar rotation (4-d: NSNS on the NS curve,
 *    LPNS on the fold curve, PDNS on the flip curve), whose multipliers
 *    are those of the factors, and times a saddle (a real pair with
 *    product 1: NSNS?, a neutral saddle, not NSNS);
 *  - henon's period-2 flip curve with its two R2 (a curve of f^2).
 * Every curve point is held to 1e-12 and every codimension-two point to
 * 1e-10 (the closed forms are evaluated in double, their own error a few
 * ulps). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/curve.h"
#include "slipcont/map.h"
#include "slipcont/normal_form.h"
#include "test_util.h"

static const double TOL_CURVE = 1e-12, TOL_POINT = 1e-10;

/* ---- the test models --------------------------------------------------- */

typedef struct {
  double p[6];
} inst6;

static int setup6(void *inst, const double *p, const int *opt,
                  const sc_accuracy *acc, sc_msg *msg) {
  (void)opt, (void)acc, (void)msg;
  memcpy(((inst6 *)inst)->p, p, 6 * sizeof *p);
  return SC_OK;
}

static void zero_derivs(sc_mapn_value *o, unsigned flags) {
  size_t n = o->n, np = o->np;
  if (flags & SC_EVAL_DERIV) {
    memset(o->J, 0, n * n * sizeof(double));
    memset(o->fp, 0, np * n * sizeof(double));
  }
  if (flags & SC_EVAL_DERIV2) {
    memset(o->H, 0, n * n * n * sizeof(double));
    memset(o->Jp, 0, np * n * n * sizeof(double));
    memset(o->T, 0, n * n * n * n * sizeof(double));
  }
}

#define J_(i, j) o->J[(i) * n + (j)]
#define FP_(q, i) o->fp[(q) * n + (i)]
#define H_(i, j, k) o->H[((i) * n + (j)) * n + (k)]
#define JP_(q, i, j) o->Jp[((q) * n + (i)) * n + (j)]
#define T_(i, j, k, l) o->T[(((i) * n + (j)) * n + (k)) * n + (l)]

/* ghenon's two components (the first two of every test map); alpha,
 * beta, R are parameters 0, 1, 2. */
static void ghenon_part(const double *p, const double *s, unsigned flags,
                        sc_mapn_value *o) {
  size_t n = o->n;
  double al = p[0], be = p[1], R = p[2], x = s[0], y = s[1];
  o->f[0] = y;
  o->f[1] = al - be * x - y * y + R * x * y;
  if (flags & SC_EVAL_DERIV) {
    J_(0, 1) = 1, J_(1, 0) = -be + R * y, J_(1, 1) = -2 * y + R * x;
    FP_(0, 1) = 1, FP_(1, 1) = -x, FP_(2, 1) = x * y;
  }
  if (flags & SC_EVAL_DERIV2) {
    H_(1, 0, 1) = H_(1, 1, 0) = R, H_(1, 1, 1) = -2;
    JP_(1, 1, 0) = -1, JP_(2, 1, 0) = y, JP_(2, 1, 1) = x;
  }
}

static const sc_param_info gh_params[6] = {
    {"alpha", 0.1, -1e6, 1e6, 0, 0, "constant term", NULL, NULL},
    {"beta", 0.5, -1e6, 1e6, 0, 0, "linear term in x", NULL, NULL},
    {"R", 0.5, -1e6, 1e6, 0, 0, "coefficient of x y", NULL, NULL},
    {"c", 0.3, -1e6, 1e6, 0, 0, "alpha of the third factor's bifurcation",
     NULL, NULL},
    {"sigma", 1, -1e6, 1e6, 0, 0, "third factor: +1 fold, -1 flip", NULL,
     NULL},
    {"phi", 1, -1e6, 1e6, 0, 0, "rotation of the planar factor", NULL, NULL},
};

/* gh3: ghenon x (z -> sigma z + (alpha - c) - z^2): fixed points
 * z^2 + (1 - sigma) z = alpha - c, multiplier sigma - 2 z; at alpha = c,
 * z = 0 and the multiplier is sigma (a fold for +1, a flip for -1). */
static int gh3_eval(void *inst, const double *s, unsigned flags,
                    sc_mapn_value *o, sc_msg *msg) {
  (void)msg;
  const double *p = ((inst6 *)inst)->p;
  size_t n = o->n;
  zero_derivs(o, flags);
  ghenon_part(p, s, flags, o);
  double z = s[2], sg = p[4];
  o->f[2] = sg * z + (p[0] - p[3]) - z * z;
  if (flags & SC_EVAL_DERIV) {
    J_(2, 2) = sg - 2 * z;
    FP_(0, 2) = 1, FP_(3, 2) = -1, FP_(4, 2) = z;
  }
  if (flags & SC_EVAL_DERIV2) {
    H_(2, 2, 2) = -2;
    JP_(4, 2, 2) = 1;
  }
  return SC_OK;
}

/* gh4: ghenon x (w -> rho e^(i phi) w - w |w|^2), rho = 1 + alpha - c,
 * w = u + i v: w = 0 is fixed with the multipliers rho e^(+-i phi), on
 * the unit circle at alpha = c. */
static int gh4_eval(void *inst, const double *s, unsigned flags,
                    sc_mapn_value *o, sc_msg *msg) {
  (void)msg;
  const double *p = ((inst6 *)inst)->p;
  size_t n = o->n;
  zero_derivs(o, flags);
  ghenon_part(p, s, flags, o);
  double rho = 1 + p[0] - p[3], cs = cos(p[5]), sn = sin(p[5]);
  double u = s[2], v = s[3], r2 = u * u + v * v;
  double a = rho * cs, b = rho * sn;
  o->f[2] = a * u - b * v - u * r2;
  o->f[3] = b * u + a * v - v * r2;
  if (flags & SC_EVAL_DERIV) {
    J_(2, 2) = a - r2 - 2 * u * u, J_(2, 3) = -b - 2 * u * v;
    J_(3, 2) = b - 2 * u * v, J_(3, 3) = a - r2 - 2 * v * v;
    /* d/dalpha = -d/dc of rho; d/dphi */
    FP_(0, 2) = cs * u - sn * v, FP_(0, 3) = sn * u + cs * v;
    FP_(3, 2) = -FP_(0, 2), FP_(3, 3) = -FP_(0, 3);
    FP_(5, 2) = -b * u - a * v, FP_(5, 3) = a * u - b * v;
  }
  if (flags & SC_EVAL_DERIV2) {
    /* -w |w|^2: second and third derivatives of -u r2 and -v r2 */
    double x[2] = {u, v};
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++)
        for (int k = 0; k < 2; k++) {
          /* d2 (x_i r2) / dx_j dx_k = 2 (d_ij x_k + d_ik x_j + d_jk x_i) */
          H_(2 + i, 2 + j, 2 + k) =
              -2 * ((i == j) * x[k] + (i == k) * x[j] + (j == k) * x[i]);
          for (int l = 0; l < 2; l++)
            T_(2 + i, 2 + j, 2 + k, 2 + l) =
                -2 * ((i == j) * (k == l) + (i == k) * (j == l) +
                      (j == k) * (i == l));
        }
    JP_(0, 2, 2) = cs, JP_(0, 2, 3) = -sn, JP_(0, 3, 2) = sn, JP_(0, 3, 3) = cs;
    JP_(3, 2, 2) = -cs, JP_(3, 2, 3) = sn, JP_(3, 3, 2) = -sn, JP_(3, 3, 3) = -cs;
    JP_(5, 2, 2) = -b, JP_(5, 2, 3) = -a, JP_(5, 3, 2) = a, JP_(5, 3, 3) = -b;
  }
  return SC_OK;
}

/* gh4s: ghenon x (u, v) -> (2 rho u, v / 2), rho = 1 + alpha - c: the
 * multipliers 2 rho and 1/2, a real pair whose product is 1 at
 * alpha = c: a neutral saddle, not a second pair on the circle. */
static int gh4s_eval(void *inst, const double *s, unsigned flags,
                     sc_mapn_value *o, sc_msg *msg) {
  (void)msg;
  const double *p = ((inst6 *)inst)->p;
  size_t n = o->n;
  zero_derivs(o, flags);
  ghenon_part(p, s, flags, o);
  double rho = 1 + p[0] - p[3];
  o->f[2] = 2 * rho * s[2];
  o->f[3] = 0.5 * s[3];
  if (flags & SC_EVAL_DERIV) {
    J_(2, 2) = 2 * rho, J_(3, 3) = 0.5;
    FP_(0, 2) = 2 * s[2], FP_(3, 2) = -2 * s[2];
  }
  if (flags & SC_EVAL_DERIV2) JP_(0, 2, 2) = 2, JP_(3, 2, 2) = -2;
  return SC_OK;
}

/* cusp2: (x, y) -> (x + mu1 + mu2 x - x^3 + k x y, y / 2 + x^2): on the
 * fixed points y = 2 x^2 and mu1 + mu2 x - (1 - 2 k) x^3 = 0, so the
 * fold curve is mu2 = 3 (1 - 2 k) x^2, mu1 = -2 (1 - 2 k) x^3, with its
 * cusp at mu1 = mu2 = 0. */
static const sc_param_info cusp_params[3] = {
    {"mu1", 0, -1e6, 1e6, 0, 0, "constant term", NULL, NULL},
    {"mu2", 0, -1e6, 1e6, 0, 0, "linear term", NULL, NULL},
    {"k", 0.3, -1e6, 1e6, 0, 0, "coupling to the stable direction", NULL,
     NULL},
};

static int cusp_eval(void *inst, const double *s, unsigned flags,
                     sc_mapn_value *o, sc_msg *msg) {
  (void)msg;
  const double *p = ((inst6 *)inst)->p;
  size_t n = o->n;
  zero_derivs(o, flags);
  double x = s[0], y = s[1], k = p[2];
  o->f[0] = x + p[0] + p[1] * x - x * x * x + k * x * y;
  o->f[1] = 0.5 * y + x * x;
  if (flags & SC_EVAL_DERIV) {
    J_(0, 0) = 1 + p[1] - 3 * x * x + k * y, J_(0, 1) = k * x;
    J_(1, 0) = 2 * x, J_(1, 1) = 0.5;
    FP_(0, 0) = 1, FP_(1, 0) = x, FP_(2, 0) = x * y;
  }
  if (flags & SC_EVAL_DERIV2) {
    H_(0, 0, 0) = -6 * x, H_(0, 0, 1) = H_(0, 1, 0) = k, H_(1, 0, 0) = 2;
    T_(0, 0, 0, 0) = -6;
    JP_(1, 0, 0) = 1, JP_(2, 0, 0) = y, JP_(2, 0, 1) = x;
  }
  return SC_OK;
}

static const char *const xyz[] = {"x", "y", "z", "w"};

static const sc_model_type gh3_type = {
    .name = "gh3", .doc = "ghenon x a fold or flip", .state_name = "x",
    .dim = 3, .state_names = xyz, .nparam = 5, .params = gh_params,
    .inst_size = sizeof(inst6), .setup = setup6, .eval_n = gh3_eval};
static const sc_model_type gh4_type = {
    .name = "gh4", .doc = "ghenon x a rotation", .state_name = "x",
    .dim = 4, .state_names = xyz, .nparam = 6, .params = gh_params,
    .inst_size = sizeof(inst6), .setup = setup6, .eval_n = gh4_eval};
static const sc_model_type gh4s_type = {
    .name = "gh4s", .doc = "ghenon x a saddle", .state_name = "x",
    .dim = 4, .state_names = xyz, .nparam = 6, .params = gh_params,
    .inst_size = sizeof(inst6), .setup = setup6, .eval_n = gh4s_eval};
static const sc_model_type cusp_type = {
    .name = "cusp2", .doc = "cusp with a stable direction",
    .state_name = "x", .dim = 2, .state_names = xyz, .nparam = 3,
    .params = cusp_params, .inst_size = sizeof(inst6), .setup = setup6,
    .eval_n = cusp_eval};

/* ---- tracing and collecting -------------------------------------------- */

#define MAXPTS 20000
#define MAXSP 64

typedef struct {
  long np;
  double x[MAXPTS], y[MAXPTS], s[MAXPTS][4], kappa[MAXPTS], coef[MAXPTS];
  size_t nsp;
  sc_curven_special sp[MAXSP];
} trace_out;

static int on_pt(void *ctx, const sc_curven_point *p) {
  trace_out *t = ctx;
  if (t->np >= MAXPTS) return 1;
  t->x[t->np] = p->x, t->y[t->np] = p->y;
  for (size_t i = 0; i < p->n && i < 4; i++) t->s[t->np][i] = p->state[i];
  t->kappa[t->np] = p->kappa, t->coef[t->np] = p->coefficient;
  t->np++;
  return 0;
}

static int on_sp(void *ctx, const sc_curven_special *s) {
  trace_out *t = ctx;
  if (t->nsp < MAXSP) t->sp[t->nsp++] = *s;
  return 0;
}

static trace_out T; /* large: static */

/* Trace a curve of @p m through the guess x0 at the map's parameters. */
static int trace(sc_map *m, sc_curve_type type, int ix, int iy,
                 const double *box, const double *x0) {
  sc_curve_settings set;
  sc_curve_settings_default(&set);
  set.type = type, set.ix = ix, set.iy = iy;
  set.xlo = box[0], set.xhi = box[1], set.ylo = box[2], set.yhi = box[3];
  set.hmax = 0.02, set.h0 = 0.002, set.max_points = 5000;
  memset(&T, 0, sizeof T);
  sc_curven_output out = {on_pt, on_sp, &T};
  sc_curve_stats st;
  sc_msg msg;
  int rc = sc_curven_trace(m, &set, x0, NAN, &out, &st, &msg);
  tu_true(rc == SC_OK, "trace: %s", rc ? msg.text : "");
  return rc;
}

/* The located special point labelled @p label nearest (x, y), or NULL. */
static const sc_curven_special *find(const char *label, double x, double y) {
  const sc_curven_special *best = NULL;
  double bd = HUGE_VAL;
  for (size_t i = 0; i < T.nsp; i++) {
    double d = hypot(T.sp[i].x - x, T.sp[i].y - y);
    if (strcmp(T.sp[i].label, label) == 0 && d < bd) bd = d, best = &T.sp[i];
  }
  return best;
}

/* Rows with a '?': located zeros that are not the point, or not located. */
static int count_rejected(void) {
  int c = 0;
  for (size_t i = 0; i < T.nsp; i++) c += strchr(T.sp[i].label, '?') != NULL;
  return c;
}

static int count(const char *label) {
  int c = 0;
  for (size_t i = 0; i < T.nsp; i++) c += strcmp(T.sp[i].label, label) == 0;
  return c;
}

/* A located point against its closed form (x, y, state s0 in every
 * component up to n, kappa where finite). */
static void check_point(const char *what, const char *label, double x,
                        double y, const double *s0, size_t n, double kappa) {
  const sc_curven_special *p = find(label, x, y);
  char w[160];
  snprintf(w, sizeof w, "%s: %s located", what, label);
  if (!tu_true(p != NULL, "%s", w)) return;
  double e = fmax(fabs(p->x - x), fabs(p->y - y));
  for (size_t i = 0; i < n; i++) e = fmax(e, fabs(p->state[i] - s0[i]));
  if (!isnan(kappa)) e = fmax(e, fabs(p->kappa - kappa));
  snprintf(w, sizeof w, "%s: %s against its closed form (max error)", what,
           label);
  tu_close(w, e, 0, TOL_POINT);
  snprintf(w, sizeof w, "%s: %s residual", what, label);
  tu_close(w, p->residual, 0, TOL_POINT);
}

/* ---- ghenon in (alpha, beta) -------------------------------------------- */

static const double R0 = 0.5;

static sc_map *ghenon_at(double al, double be, double R) {
  sc_map *m;
  sc_msg msg;
  if (sc_map_alloc("ghenon", NULL, &m, &msg)) return NULL;
  sc_map_set_param(m, 0, al, &msg);
  sc_map_set_param(m, 1, be, &msg);
  sc_map_set_param(m, 2, R, &msg);
  return m;
}

/* The point of ghenon's NS curve (det = 1) at s: beta = 1 + R s,
 * alpha = s^2 + 2 s (the fixed-point equation with beta - R s = 1). */
static void ns_at(double s, double R, double *al, double *be) {
  *be = 1 + R * s;
  *al = s * s + 2 * s;
}

static void test_ghenon_ns(void) {
  double R = R0, s0 = 0.4, al, be;
  ns_at(s0, R, &al, &be);
  sc_map *m = ghenon_at(al, be, R);
  double box[4] = {-2, 6, -1, 3}, x0[2] = {s0 + 0.01, s0 - 0.02};
  if (trace(m, SC_CURVE_NS, 0, 1, box, x0)) goto out;
  double e = 0, ed = 0;
  for (long i = 0; i < T.np; i++) {
    double s = (T.y[i] - 1) / R, a2, b2;
    ns_at(s, R, &a2, &b2);
    e = fmax(e, fmax(fabs(T.x[i] - a2), fabs(T.s[i][0] - s)));
    e = fmax(e, fmax(fabs(T.s[i][1] - s), fabs(T.kappa[i] - (R - 2) * s / 2)));
    /* d = -R (R - 1) / (16 (1 - kappa)) (docs/maps.md) */
    double k = T.kappa[i], d = -R * (R - 1) / (16 * (1 - k));
    if (fabs(k) < 0.95) ed = fmax(ed, fabs(T.coef[i] - d) / fabs(d));
  }
  tu_true(T.np > 100, "ns: %ld points", T.np);
  tu_close("ns (alpha, beta): points on det = 1, alpha = s^2 + 2 s", e, 0,
           TOL_CURVE);
  tu_close("ns: d = -R (R - 1) / (16 (1 - kappa)), relative", ed, 0, 1e-10);
  const struct {
    const char *label;
    double s, kappa;
  } want[] = {{"R1", 2 / (R - 2), 1},
              {"R2", -2 / (R - 2), -1},
              {"R3", -1 / (R - 2), -0.5},
              {"R4", 0, 0}};
  for (int k = 0; k < 4; k++) {
    double s = want[k].s, st[2] = {s, s};
    ns_at(s, R, &al, &be);
    check_point("ns (alpha, beta)", want[k].label, al, be, st, 2,
                want[k].kappa);
    tu_int("ns: located once", count(want[k].label), 1);
  }
  tu_int("ns: no Chenciner point in (alpha, beta) (d has no zero)",
         count("CH"), 0);
  tu_int("ns: nothing rejected", count_rejected(), 0);
out:
  sc_map_free(m);
}

static void test_ghenon_fold(void) {
  double R = R0, be = 0.5, s = -(1 + be) / (2 * (1 - R));
  double al = (1 - R) * s * s + (1 + be) * s;
  sc_map *m = ghenon_at(al, be, R);
  double box[4] = {-3, 6, -3, 3}, x0[2] = {s, s};
  if (trace(m, SC_CURVE_FOLD, 0, 1, box, x0)) goto out;
  double e = 0, ea = 0;
  for (long i = 0; i < T.np; i++) {
    double b = T.y[i], si = -(1 + b) / (2 * (1 - R));
    e = fmax(e, fabs((1 + b) * (1 + b) + 4 * (1 - R) * T.x[i]));
    e = fmax(e, fmax(fabs(T.s[i][0] - si), fabs(T.s[i][1] - si)));
    /* a = (R - 1) / (sqrt 2 (2 - trace)), q = (1, 1) / sqrt 2 */
    double t = (R - 2) * si, a = (R - 1) / (sqrt(2) * (2 - t));
    if (fabs(2 - t) > 0.01) ea = fmax(ea, fabs(T.coef[i] - a) / fabs(a));
  }
  tu_close("fold (alpha, beta): (1 + beta)^2 + 4 (1 - R) alpha = 0", e, 0,
           TOL_CURVE);
  tu_close("fold: a = (R - 1) / (sqrt 2 (2 - tr)), relative", ea, 0, 1e-10);
  double s1 = 2 / (R - 2), b1 = 1 + R * s1, st1[2] = {s1, s1};
  double a1 = (1 - R) * s1 * s1 + (1 + b1) * s1;
  check_point("fold", "R1", a1, b1, st1, 2, NAN);
  double st0[2] = {0, 0};
  check_point("fold", "LPPD", 0, -1, st0, 2, NAN);
  tu_int("fold: no cusp (a vanishes only at R = 1)", count("CP"), 0);
  tu_int("fold: nothing rejected (a's pole at R1 is no candidate)",
         count_rejected(), 0);
out:
  sc_map_free(m);
}

static void test_ghenon_flip(void) {
  double R = R0, be = 0.5, s = (1 + be) / 2;
  double al = (3 - R) * s * s;
  sc_map *m = ghenon_at(al, be, R);
  double box[4] = {-3, 6, -3, 3}, x0[2] = {s, s};
  if (trace(m, SC_CURVE_FLIP, 0, 1, box, x0)) goto out;
  double e = 0, eb = 0;
  for (long i = 0; i < T.np; i++) {
    double b = T.y[i], si = (1 + b) / 2;
    e = fmax(e, fabs(T.x[i] - (3 - R) * si * si));
    e = fmax(e, fmax(fabs(T.s[i][0] - si), fabs(T.s[i][1] - si)));
    double den = (R - 2) * (b + 1) * (R * b + R - 2 * b + 2);
    double bb = -2 * (R + 1) / den;
    if (fabs(den) > 0.05) eb = fmax(eb, fabs(T.coef[i] - bb) / fabs(bb));
  }
  tu_close("flip (alpha, beta): alpha = (3 - R) s^2, s = (1 + beta) / 2", e,
           0, TOL_CURVE);
  tu_close("flip: b = -2 (R + 1) / ((R - 2)(beta + 1)(R beta + R - 2 beta + "
           "2)), relative",
           eb, 0, 1e-10);
  double s2 = -2 / (R - 2), b2 = 1 + R * s2, st2[2] = {s2, s2};
  check_point("flip", "R2", (3 - R) * s2 * s2, b2, st2, 2, NAN);
  double st0[2] = {0, 0};
  check_point("flip", "LPPD", 0, -1, st0, 2, NAN);
  tu_int("flip: no GPD in (alpha, beta) (b vanishes only at R = -1)",
         count("GPD"), 0);
  tu_int("flip: nothing rejected (b's poles at R2, LPPD are no candidates)",
         count_rejected(), 0);
out:
  sc_map_free(m);
}

/* GPD: the flip curve in (beta, R) at alpha = 0.5 crosses R = -1 at
 * beta = -1 + sqrt(alpha), s = sqrt(alpha) / 2. */
static void test_ghenon_gpd(void) {
  double al = 0.5, R = -0.5, s = sqrt(al / (3 - R)), be = 2 * s - 1;
  sc_map *m = ghenon_at(al, be, R);
  double box[4] = {-3, 2, -2, 1.5}, x0[2] = {s, s};
  if (trace(m, SC_CURVE_FLIP, 1, 2, box, x0)) goto out;
  double e = 0;
  for (long i = 0; i < T.np; i++) {
    double si = (1 + T.x[i]) / 2;
    e = fmax(e, fabs(al - (3 - T.y[i]) * si * si));
  }
  tu_close("flip (beta, R): alpha = (3 - R) s^2", e, 0, TOL_CURVE);
  double sg = sqrt(al) / 2, st[2] = {sg, sg};
  check_point("flip (beta, R)", "GPD", sqrt(al) - 1, -1, st, 2, NAN);
  tu_int("flip (beta, R): one GPD", count("GPD"), 1);
out:
  sc_map_free(m);
}

/* CH: the NS curve in (beta, R) at alpha = 0.5 is s = -1 + sqrt(1 +
 * alpha), beta = 1 + R s, and d = -R (R - 1) / (16 (1 - kappa)) vanishes
 * at R = 0 and R = 1. */
static void test_ghenon_ch(void) {
  double al = 0.5, s = sqrt(1 + al) - 1, R = 0.5, be = 1 + R * s;
  sc_map *m = ghenon_at(al, be, R);
  double box[4] = {-1, 3, -0.5, 1.5}, x0[2] = {s, s};
  if (trace(m, SC_CURVE_NS, 1, 2, box, x0)) goto out;
  double e = 0;
  for (long i = 0; i < T.np; i++)
    e = fmax(e, fmax(fabs(T.x[i] - (1 + T.y[i] * s)), fabs(T.s[i][0] - s)));
  tu_close("ns (beta, R): s = sqrt(1 + alpha) - 1, beta = 1 + R s", e, 0,
           TOL_CURVE);
  double st[2] = {s, s};
  check_point("ns (beta, R)", "CH", 1 + s, 1, st, 2, -s / 2);
  check_point("ns (beta, R)", "CH", 1, 0, st, 2, -s);
  tu_int("ns (beta, R): two CH", count("CH"), 2);
out:
  sc_map_free(m);
}

/* ---- the test maps ------------------------------------------------------ */

static sc_map *model_at(const sc_model_type *t, const double *p) {
  sc_map *m;
  sc_msg msg;
  if (sc_map_alloc_type(t, NULL, &m, &msg)) return NULL;
  for (size_t i = 0; i < t->nparam; i++) sc_map_set_param(m, i, p[i], &msg);
  return m;
}

/* The test models' J, f_p against central differences of f, and H, J_p,
 * T against differences of J and H (h = 1e-6: errors ~1e-10 on these
 * polynomials of moderate size). */
static void check_model(const sc_model_type *t, const double *p,
                        const double *x) {
  sc_map *m = model_at(t, p);
  sc_mapn_value *v, *a, *b;
  sc_msg msg;
  size_t n = t->dim, np = t->nparam;
  sc_mapn_value_alloc(m, SC_EVAL_DERIV2, &v, &msg);
  sc_mapn_value_alloc(m, SC_EVAL_DERIV2, &a, &msg);
  sc_mapn_value_alloc(m, SC_EVAL_DERIV2, &b, &msg);
  const double h = 1e-6;
  double e = 0;
  unsigned fl = SC_EVAL_DERIV | SC_EVAL_DERIV2;
  sc_map_eval_n(m, x, fl, v, &msg);
  for (size_t j = 0; j < n; j++) {
    double xp[4], xm[4];
    memcpy(xp, x, n * sizeof *x), memcpy(xm, x, n * sizeof *x);
    xp[j] += h, xm[j] -= h;
    sc_map_eval_n(m, xp, fl, a, &msg), sc_map_eval_n(m, xm, fl, b, &msg);
    for (size_t i = 0; i < n; i++) {
      e = fmax(e, fabs(v->J[i * n + j] - (a->f[i] - b->f[i]) / (2 * h)));
      for (size_t k = 0; k < n; k++) {
        e = fmax(e, fabs(v->H[(i * n + k) * n + j] -
                         (a->J[i * n + k] - b->J[i * n + k]) / (2 * h)));
        for (size_t l = 0; l < n; l++)
          e = fmax(e, fabs(v->T[((i * n + k) * n + l) * n + j] -
                           (a->H[(i * n + k) * n + l] -
                            b->H[(i * n + k) * n + l]) / (2 * h)));
      }
    }
  }
  for (size_t q = 0; q < np; q++) {
    sc_map_set_param(m, q, p[q] + h, &msg), sc_map_eval_n(m, x, fl, a, &msg);
    sc_map_set_param(m, q, p[q] - h, &msg), sc_map_eval_n(m, x, fl, b, &msg);
    sc_map_set_param(m, q, p[q], &msg);
    for (size_t i = 0; i < n; i++) {
      e = fmax(e, fabs(v->fp[q * n + i] - (a->f[i] - b->f[i]) / (2 * h)));
      for (size_t j = 0; j < n; j++)
        e = fmax(e, fabs(v->Jp[(q * n + i) * n + j] -
                         (a->J[i * n + j] - b->J[i * n + j]) / (2 * h)));
    }
  }
  char w[96];
  snprintf(w, sizeof w, "model %s: derivatives against differences", t->name);
  tu_close(w, e, 0, 1e-8);
  sc_mapn_value_free(v), sc_mapn_value_free(a), sc_mapn_value_free(b);
  sc_map_free(m);
}

/* CP of cusp2: the fold curve mu2 = 3 (1 - 2k) x^2, mu1 = -2 (1 - 2k) x^3. */
static void test_cusp(void) {
  double k = 0.3, c = 1 - 2 * k, x = 0.5;
  double p[3] = {-2 * c * x * x * x, 3 * c * x * x, k};
  sc_map *m = model_at(&cusp_type, p);
  double box[4] = {-1, 1, -0.5, 1.5}, x0[2] = {x, 2 * x * x};
  if (trace(m, SC_CURVE_FOLD, 0, 1, box, x0)) goto out;
  double e = 0;
  for (long i = 0; i < T.np; i++) {
    double xi = T.s[i][0];
    e = fmax(e, fabs(T.y[i] - 3 * c * xi * xi));
    e = fmax(e, fabs(T.x[i] + 2 * c * xi * xi * xi));
    e = fmax(e, fabs(T.s[i][1] - 2 * xi * xi));
  }
  tu_close("cusp2 fold: mu2 = 3 (1 - 2k) x^2, mu1 = -2 (1 - 2k) x^3", e, 0,
           TOL_CURVE);
  double st[2] = {0, 0};
  check_point("cusp2", "CP", 0, 0, st, 2, NAN);
  tu_int("cusp2: one CP", count("CP"), 1);
out:
  sc_map_free(m);
}

/* gh3 and gh4 at alpha = c on ghenon's NS curve: LPNS (gh3, sigma = 1),
 * PDNS (gh3, sigma = -1), NSNS (gh4). */
static void test_product_ns(const sc_model_type *t, double sigma,
                            const char *label) {
  double R = R0, c = 0.3, al = 0.6, s = sqrt(1 + al) - 1, be;
  ns_at(s, R, &al, &be);
  double p[6] = {al, be, R, c, sigma, 1};
  double z = sigma > 0 ? sqrt(al - c) : sqrt(1 + al - c) - 1;
  double x0[4] = {s, s, t->dim == 3 ? z : 0, 0};
  sc_map *m = model_at(t, p);
  double box[4] = {-2, 6, -1, 3};
  char what[64];
  snprintf(what, sizeof what, "%s on the NS curve", t->name);
  if (trace(m, SC_CURVE_NS, 0, 1, box, x0)) goto out;
  double e = 0;
  for (long i = 0; i < T.np; i++) {
    double si = (T.y[i] - 1) / R, a2, b2;
    ns_at(si, R, &a2, &b2);
    e = fmax(e, fmax(fabs(T.x[i] - a2), fabs(T.s[i][0] - si)));
  }
  tu_close(what, e, 0, TOL_CURVE);
  double sl = sqrt(1 + c) - 1, al2, be2, st[4] = {sl, sl, 0, 0};
  ns_at(sl, R, &al2, &be2);
  check_point(what, label, al2, be2, st, t->dim, (R - 2) * sl / 2);
out:
  sc_map_free(m);
}

/* gh4s on ghenon's NS curve: the bialternate test vanishes at alpha = c
 * through a real pair (2, 1/2): located, and written as NSNS? (a neutral
 * saddle), not as NSNS. */
static void test_neutral_pair(void) {
  double R = R0, c = 0.3, al = 0.6, s = sqrt(1 + al) - 1, be;
  ns_at(s, R, &al, &be);
  double p[6] = {al, be, R, c, 1, 1}, x0[4] = {s, s, 0, 0};
  sc_map *m = model_at(&gh4s_type, p);
  double box[4] = {-2, 6, -1, 3};
  if (trace(m, SC_CURVE_NS, 0, 1, box, x0) == SC_OK) {
    double sl = sqrt(1 + c) - 1, al2, be2;
    ns_at(sl, R, &al2, &be2);
    tu_int("gh4s: no NSNS (the pair is real)", count("NSNS"), 0);
    const sc_curven_special *q = find("NSNS?", al2, be2);
    tu_true(q && fabs(q->x - al2) + fabs(q->y - be2) <= TOL_POINT &&
                strstr(q->note, "neutral saddle"),
            "gh4s: NSNS? at alpha = c, a neutral saddle (%s)",
            q ? q->note : "none");
  }
  sc_map_free(m);
}

/* gh4 at alpha = c on ghenon's fold curve (LPNS) and flip curve (PDNS). */
static void test_product_lp_pd(void) {
  double R = R0;
  { /* fold: c = -0.5, (1 + beta)^2 = -4 (1 - R) alpha */
    double c = -0.5, al = -0.3, be = -1 + sqrt(-4 * (1 - R) * al);
    double s = -(1 + be) / (2 * (1 - R));
    double p[6] = {al, be, R, c, 1, 1}, x0[4] = {s, s, 0, 0};
    sc_map *m = model_at(&gh4_type, p);
    double box[4] = {-3, 1, -1.5, 3};
    if (trace(m, SC_CURVE_FOLD, 0, 1, box, x0) == SC_OK) {
      double bl = -1 + sqrt(-4 * (1 - R) * c), sl = -(1 + bl) / (2 * (1 - R));
      double st[4] = {sl, sl, 0, 0};
      check_point("gh4 on the fold curve", "LPNS", c, bl, st, 4, NAN);
    }
    sc_map_free(m);
  }
  { /* flip: c = 0.5, alpha = (3 - R) (1 + beta)^2 / 4 */
    double c = 0.5, al = 0.8, s = sqrt(al / (3 - R)), be = 2 * s - 1;
    double p[6] = {al, be, R, c, 1, 1}, x0[4] = {s, s, 0, 0};
    sc_map *m = model_at(&gh4_type, p);
    double box[4] = {-1, 3, -1.5, 3};
    if (trace(m, SC_CURVE_FLIP, 0, 1, box, x0) == SC_OK) {
      double sl = sqrt(c / (3 - R)), st[4] = {sl, sl, 0, 0};
      check_point("gh4 on the flip curve", "PDNS", c, 2 * sl - 1, st, 4, NAN);
    }
    sc_map_free(m);
  }
}


/* A period-2 curve: henon's flip of its period-2 orbit,
 * a = (1 + b)^2 / 4 + (1 - b)^2 (the orbit points x1 + x2 = (1 - b) / a,
 * x1 x2 = (1 - b)^2 / a^2 - 1 / a give f^2 the trace 4 a^2 x1 x2 + 2 b
 * and the determinant b^2, and 1 + tr + det = 0); its other multiplier
 * is -b^2, so R2 at b = 1 (a = 1) and b = -1 (a = 4). */
static void test_henon_period2(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("henon", NULL, &m, &msg);
  double b = 0.3, a = (1 + b) * (1 + b) / 4 + (1 - b) * (1 - b);
  sc_map_set_param(m, 0, a, &msg);
  sc_map_set_param(m, 1, b, &msg);
  double S = (1 - b) / a, P = (1 - b) * (1 - b) / (a * a) - 1 / a;
  double x1 = (S + sqrt(S * S - 4 * P)) / 2, x0[2] = {x1, b * (S - x1)};
  sc_curve_settings set;
  sc_curve_settings_default(&set);
  set.type = SC_CURVE_FLIP, set.period = 2, set.ix = 0, set.iy = 1;
  set.xlo = -1, set.xhi = 5, set.ylo = -1.2, set.yhi = 1.2;
  set.hmax = 0.03, set.h0 = 0.003;
  memset(&T, 0, sizeof T);
  sc_curven_output out = {on_pt, on_sp, &T};
  sc_curve_stats st;
  int rc = sc_curven_trace(m, &set, x0, NAN, &out, &st, &msg);
  if (tu_true(rc == SC_OK, "henon period 2: %s", rc ? msg.text : "")) {
    double e = 0;
    for (long i = 0; i < T.np; i++) {
      double bi = T.y[i];
      e = fmax(e, fabs(T.x[i] - (1 + bi) * (1 + bi) / 4 - (1 - bi) * (1 - bi)));
    }
    tu_close("henon period-2 flip: a = (1 + b)^2 / 4 + (1 - b)^2", e, 0,
             TOL_CURVE);
    const sc_curven_special *r = find("R2", 1, 1);
    tu_true(r && fabs(r->x - 1) + fabs(r->y - 1) <= TOL_POINT,
            "henon period 2: R2 at (1, 1)");
    r = find("R2", 4, -1);
    tu_true(r && fabs(r->x - 4) + fabs(r->y + 1) <= TOL_POINT,
            "henon period 2: R2 at (4, -1)");
    tu_int("henon period 2: two R2", count("R2"), 2);
    tu_int("henon period 2: nothing else but the two ends", (int)T.nsp, 4);
    tu_int("henon period 2: nothing rejected (b's poles at R2)",
           count_rejected(), 0);
  }
  sc_map_free(m);
}

static void test_refusals(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("logistic", NULL, &m, &msg);
  sc_curve_settings set;
  sc_curve_settings_default(&set);
  set.xlo = set.ylo = -1, set.xhi = set.yhi = 1;
  sc_curve_stats st;
  double x0 = 0.5;
  tu_int("refuse: a one-dimensional map",
         sc_curven_trace(m, &set, &x0, NAN, NULL, &st, &msg), SC_EINVAL);
  sc_map_free(m);
  m = ghenon_at(0.5, 0.3, 0.5); /* no complex pair at (0.1, 0.1)? */
  double x2[2] = {3, 3};
  set.type = SC_CURVE_NS;
  int rc = sc_curven_trace(m, &set, x2, NAN, NULL, &st, &msg);
  tu_true(rc == SC_EINVAL || rc == SC_ENOCONV,
          "refuse: ns start far from any NS point (%d: %s)", rc, msg.text);
  sc_map_free(m);
}

int main(void) {
  double pg[6] = {0.4, 0.7, 0.5, 0.3, 1, 1}, xs[4] = {0.3, -0.2, 0.4, 0.25};
  check_model(&gh3_type, pg, xs);
  pg[4] = -1;
  check_model(&gh3_type, pg, xs);
  check_model(&gh4_type, pg, xs);
  check_model(&gh4s_type, pg, xs);
  double pc[3] = {0.1, 0.2, 0.3};
  check_model(&cusp_type, pc, xs);
  test_ghenon_ns();
  test_ghenon_fold();
  test_ghenon_flip();
  test_ghenon_gpd();
  test_ghenon_ch();
  test_cusp();
  test_product_ns(&gh3_type, 1, "LPNS");
  test_product_ns(&gh3_type, -1, "PDNS");
  test_product_ns(&gh4_type, 1, "NSNS");
  test_product_lp_pd();
  test_henon_period2();
  test_neutral_pair();
  test_refusals();
  return tu_finish();
}
