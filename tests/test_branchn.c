/* Branches of n-dimensional maps (branchn.h) against closed forms:
 *  - ghenon (beta = 0.6, R = -1) in alpha: fixed points x = y = s,
 *    alpha = (1 - R) s^2 + (1 + beta) s; fold at s = -(1 + beta) /
 *    (2 (1 - R)) = -0.4 (alpha = -0.32), NS where det = beta - R s = 1,
 *    s = 0.4 (alpha = 0.96, kappa = tr / 2 = (R - 2) s / 2 = -0.6), flip
 *    where 1 + tr + det = 0, s = (1 + beta) / 2 = 0.8 (alpha = 2.56);
 *  - henon (b = 0.3) in a with switching: the fixed point flips at
 *    a1 = 3 (1 - b)^2 / 4, the period-2 orbit at a2 = (1 + b)^2 / 4 +
 *    (1 - b)^2 (its points x1 + x2 = (1 - b) / a, x1 x2 = (1 - b)^2 / a^2
 *    - 1 / a give f^2 the trace 4 a^2 x1 x2 + 2 b and determinant b^2);
 *  - a map with the symmetry (x, y) -> (-x, -y), (x, y) -> (p x + y / 2 -
 *    x^3, x / 4 + q y): the origin's pitchfork at p* = 1 + 1 / (8 (q - 1))
 *    and the crossing branch x^2 = p - p*, y = x / (4 (1 - q)). */
#include <math.h>
#include <string.h>

#include "slipcont/branchn.h"
#include "slipcont/map.h"
#include "test_util.h"

/* Special points are Newton solutions of their systems, certified to
 * the solver's tolerances (newton_atol 1e-10 by default, with quadratic
 * convergence the last step leaves them at the rounding level). */
static const double PT_TOL = 1e-10;

/* The special point of @p b with @p label, period @p period nearest p. */
static int find(const sc_branchn *b, sc_branchn_label label, int period,
                double p, sc_branchn_special *out) {
  int found = 0;
  for (size_t i = 0; i < sc_branchn_nspecial(b); i++) {
    sc_branchn_special s;
    sc_branchn_special_get(b, i, &s);
    if (s.label != label || s.period != period) continue;
    if (!found || fabs(s.p - p) < fabs(out->p - p)) *out = s;
    found = 1;
  }
  return found;
}

static void expect(const sc_branchn *b, const char *what,
                   sc_branchn_label label, int period, double p,
                   const double *x, sc_branchn_special *s) {
  char buf[160];
  if (!tu_true(find(b, label, period, p, s), "%s found", what)) return;
  snprintf(buf, sizeof buf, "%s: parameter", what);
  tu_close(buf, s->p, p, PT_TOL);
  for (size_t i = 0; x && i < sc_branchn_dim(b); i++) {
    snprintf(buf, sizeof buf, "%s: x[%zu]", what, i);
    tu_close(buf, s->x[i], x[i], PT_TOL);
  }
  tu_true(s->method == SC_LOC_NEWTON && s->residual <= 1e-12,
          "%s: located by Newton, residual %g", what, s->residual);
}

static void check_ghenon(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("ghenon", NULL, &m, &msg);
  double be = 0.6, R = -1;
  sc_map_set_param_by_name(m, "beta", be, &msg);
  sc_map_set_param_by_name(m, "R", R, &msg);
  /* the start: the root s < -0.4 at alpha = 3 */
  double s0 = (-(1 + be) - sqrt((1 + be) * (1 + be) + 4 * (1 - R) * 3)) /
              (2 * (1 - R));
  double x0[2] = {s0 + 0.01, s0 - 0.02};
  sc_branchn_spec sp = {.param = 0, .from = 3, .to = -1, .period = 1,
                        .x0 = x0, .max_points = 5000, .max_branches = 4,
                        .max_period = 4};
  sc_branchn *b;
  tu_int("ghenon branch alloc", sc_branchn_alloc(m, &sp, &b, &msg), SC_OK);
  int st = sc_branchn_run(b, &msg);
  tu_true(st == SC_OK, "ghenon branch runs: %s", msg.text);
  sc_branchn_special s;
  double xl[2] = {-0.4, -0.4}, xn[2] = {0.4, 0.4}, xp[2] = {0.8, 0.8};
  expect(b, "ghenon LP", SC_PTN_LP, 1, -0.32, xl, &s);
  expect(b, "ghenon NS", SC_PTN_NS, 1, 0.96, xn, &s);
  tu_close("ghenon NS: kappa = tr / 2", s.kappa, -0.6, PT_TOL);
  tu_close("ghenon NS: theta", s.theta, acos(-0.6), PT_TOL);
  tu_true(isfinite(s.coef), "ghenon NS: coefficient d = %g", s.coef);
  expect(b, "ghenon PD", SC_PTN_PD, 1, 2.56, xp, &s);
  tu_true(isfinite(s.coef), "ghenon PD: coefficient b = %g", s.coef);
  /* nothing else: one LP, one NS, one PD and the end */
  size_t nlab[SC_PTN_EP + 1] = {0};
  for (size_t i = 0; i < sc_branchn_nspecial(b); i++) {
    sc_branchn_special_get(b, i, &s);
    nlab[s.label]++;
  }
  tu_int("ghenon: one LP", (long)nlab[SC_PTN_LP], 1);
  tu_int("ghenon: one NS", (long)nlab[SC_PTN_NS], 1);
  tu_int("ghenon: one PD", (long)nlab[SC_PTN_PD], 1);
  tu_int("ghenon: no BP", (long)nlab[SC_PTN_BP], 0);
  tu_int("ghenon: one EP", (long)nlab[SC_PTN_EP], 1);
  /* stability: the branch's points between the NS and the flip (s in
   * (0.4, 0.8)) are stable, det = 0.6 + s < 1 */
  sc_branchn_point pt;
  int ok = 1;
  for (size_t i = 0; i < sc_branchn_npoints(b); i++) {
    sc_branchn_point_get(b, i, &pt);
    double sx = pt.x[0], det = be - R * sx, tr = (R - 2) * sx;
    int stab = det < 1 && 1 - tr + det > 0 && 1 + tr + det > 0;
    /* the multipliers' product and sum are det and tr */
    double pr = pt.re[0] * pt.re[1] - pt.im[0] * pt.im[1];
    /* on a boundary (the special points are branch points too) the
     * rounding decides: compared off them only */
    int edge = fabs(det - 1) < 1e-9 || fabs(1 - tr + det) < 1e-9 ||
               fabs(1 + tr + det) < 1e-9;
    int good = (edge || pt.stable == stab) && fabs(pr - det) < 1e-12 &&
               fabs(pt.re[0] + pt.re[1] - tr) < 1e-12;
    if (!good && ok)
      printf("point %zu: s %.17g stable %d (%d) mu %g%+gi %g%+gi det %g tr %g\n",
             i, sx, pt.stable, stab, pt.re[0], pt.im[0], pt.re[1], pt.im[1],
             det, tr);
    ok &= good;
  }
  tu_true(ok, "ghenon: multipliers and stability of every point");
  tu_close("ghenon: parameters restored", sc_map_get_param(m, 0), 0.1, 0);
  sc_branchn_free(b);
  sc_map_free(m);
}

static void check_henon(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("henon", NULL, &m, &msg);
  double bb = 0.3, a0 = 0.1;
  sc_map_set_param_by_name(m, "b", bb, &msg);
  double x = (-(1 - bb) + sqrt((1 - bb) * (1 - bb) + 4 * a0)) / (2 * a0);
  double x0[2] = {x, bb * x};
  sc_branchn_spec sp = {.param = 0, .from = a0, .to = 1.2, .period = 1,
                        .x0 = x0, .switch_pd = 1, .max_points = 5000,
                        .max_branches = 8, .max_period = 8};
  sc_branchn *b;
  tu_int("henon branch alloc", sc_branchn_alloc(m, &sp, &b, &msg), SC_OK);
  int st = sc_branchn_run(b, &msg);
  tu_true(st == SC_OK, "henon branch runs: %s", msg.text);
  double a1 = 3 * (1 - bb) * (1 - bb) / 4, x1 = (1 - bb) / (2 * a1);
  double xf[2] = {x1, bb * x1};
  sc_branchn_special s;
  expect(b, "henon PD period 1", SC_PTN_PD, 1, a1, xf, &s);
  double a2 = (1 + bb) * (1 + bb) / 4 + (1 - bb) * (1 - bb);
  expect(b, "henon PD period 2", SC_PTN_PD, 2, a2, NULL, &s);
  /* the period-2 orbit point is a root of z^2 - S z + P */
  double S = (1 - bb) / a2, P = S * S - 1 / a2;
  tu_close("henon PD period 2: x on the orbit", s.x[0] * s.x[0] - S * s.x[0] + P,
           0, PT_TOL);
  tu_close("henon PD period 2: y = b x_other", s.x[1], bb * (S - s.x[0]),
           PT_TOL);
  tu_true(find(b, SC_PTN_PD, 4, 1.0, &s), "henon: the period-4 flip found");
  tu_true(sc_branchn_nbranches(b) >= 3, "henon: %d segments",
          sc_branchn_nbranches(b));
  sc_branchn_free(b);
  sc_map_free(m);
}

/* --- the symmetric test map, as a model of its own --------------------- */

typedef struct {
  double p, q;
} pitch_inst;

static int pitch_setup(void *inst, const double *p, const int *opt,
                       const sc_accuracy *acc, sc_msg *msg) {
  (void)opt, (void)acc, (void)msg;
  pitch_inst *c = inst;
  c->p = p[0];
  c->q = p[1];
  return SC_OK;
}

static int pitch_eval(void *inst, const double *s, unsigned flags,
                      sc_mapn_value *out, sc_msg *msg) {
  (void)msg;
  const pitch_inst *c = inst;
  double x = s[0], y = s[1];
  out->f[0] = c->p * x + 0.5 * y - x * x * x;
  out->f[1] = 0.25 * x + c->q * y;
  if (flags & SC_EVAL_DERIV) {
    double J[4] = {c->p - 3 * x * x, 0.5, 0.25, c->q}, fp[4] = {x, 0, 0, y};
    memcpy(out->J, J, sizeof J);
    memcpy(out->fp, fp, sizeof fp);
  }
  if (flags & SC_EVAL_DERIV2) {
    memset(out->H, 0, 8 * sizeof *out->H);
    memset(out->Jp, 0, 8 * sizeof *out->Jp);
    memset(out->T, 0, 16 * sizeof *out->T);
    out->H[0] = -6 * x;
    out->T[0] = -6;
    out->Jp[0] = 1;
    out->Jp[4 + 3] = 1;
  }
  return SC_OK;
}

static const sc_param_info pitch_params[] = {
    {"p", 0.5, -10, 10, 0, 0, "linear term in x", NULL, NULL},
    {"q", 0.2, -10, 10, 0, 0, "linear term in y", NULL, NULL},
};

static const sc_model_type pitch_model = {
    .name = "pitch",
    .doc = "(x, y) -> (p x + y/2 - x^3, x/4 + q y)",
    .state_name = "x",
    .dim = 2,
    .nparam = 2,
    .params = pitch_params,
    .inst_size = sizeof(pitch_inst),
    .setup = pitch_setup,
    .eval_n = pitch_eval,
};

/* --- a piecewise-smooth map (an event map's stand-in) ----------------- */

/* (x, y) -> (p - x / 2 + 2 max(x - 0.3, 0), y / 5), one slip phase an
 * iterate, itinerary "A" left of x = 0.3 and "B" right of it: the fixed
 * point x = p / 1.5 meets the kink at p = 0.45, where the branch must
 * stop rather than pass a point where the map is not smooth. */
static int kink_eval(void *inst, const double *s, unsigned flags,
                     sc_mapn_value *out, sc_msg *msg) {
  (void)msg;
  const pitch_inst *c = inst;
  double x = s[0], right = x > 0.3;
  out->f[0] = c->p - 0.5 * x + (right ? 2 * (x - 0.3) : 0);
  out->f[1] = 0.2 * s[1];
  if (flags & SC_EVAL_DERIV) {
    double J[4] = {right ? 1.5 : -0.5, 0, 0, 0.2}, fp[4] = {1, 0, 0, 0};
    memcpy(out->J, J, sizeof J);
    memcpy(out->fp, fp, sizeof fp);
  }
  if (flags & SC_EVAL_DERIV2) {
    memset(out->H, 0, 8 * sizeof *out->H);
    memset(out->Jp, 0, 8 * sizeof *out->Jp);
    memset(out->T, 0, 16 * sizeof *out->T);
  }
  out->nphases = 1;
  if (flags & SC_EVAL_ITINERARY) strcpy(out->itinerary, right ? "B" : "A");
  return SC_OK;
}

static const sc_model_type kink_model = {
    .name = "kink",
    .doc = "(x, y) -> (p - x/2 + 2 max(x - 0.3, 0), y/5)",
    .state_name = "x",
    .dim = 2,
    .nparam = 2,
    .params = pitch_params,
    .inst_size = sizeof(pitch_inst),
    .setup = pitch_setup,
    .eval_n = kink_eval,
};

static void check_kink(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc_type(&kink_model, NULL, &m, &msg);
  double x0[2] = {0.1 / 1.5, 0};
  sc_branchn_spec sp = {.param = 0, .from = 0.1, .to = 1, .period = 1,
                        .x0 = x0, .max_points = 5000, .max_branches = 1,
                        .max_period = 1};
  sc_branchn *b;
  tu_int("kink: alloc", sc_branchn_alloc(m, &sp, &b, &msg), SC_OK);
  tu_int("kink: run", sc_branchn_run(b, &msg), SC_OK);
  sc_branchn_special s;
  int n = (int)sc_branchn_nspecial(b);
  tu_int("kink: one row", n, 1);
  sc_branchn_special_get(b, 0, &s);
  tu_true(s.label == SC_PTN_EP && s.p < 0.45 &&
              strstr(s.note, "the itinerary changes") != NULL,
          "kink: the segment ends before the kink at 0.45: %s at %g (%s)",
          sc_branchn_label_text(s.label), s.p, s.note);
  double pmax = 0;
  for (size_t i = 0; i < sc_branchn_npoints(b); i++) {
    sc_branchn_point pt;
    sc_branchn_point_get(b, i, &pt);
    pmax = fmax(pmax, pt.p);
  }
  tu_true(pmax < 0.45, "kink: no point beyond it (%g)", pmax);
  sc_branchn_free(b);
  sc_map_free(m);
}

static void check_pitchfork(void) {
  sc_map *m;
  sc_msg msg;
  tu_int("pitch model", sc_map_alloc_type(&pitch_model, NULL, &m, &msg),
         SC_OK);
  double q = 0.2, pstar = 1 + 1 / (8 * (q - 1)), x0[2] = {0.01, -0.01};
  sc_branchn_spec sp = {.param = 0, .from = 0.5, .to = 1.2, .period = 1,
                        .x0 = x0, .switch_bp = 1, .max_points = 5000,
                        .max_branches = 4, .max_period = 4};
  sc_branchn *b;
  tu_int("pitch branch alloc", sc_branchn_alloc(m, &sp, &b, &msg), SC_OK);
  int st = sc_branchn_run(b, &msg);
  tu_true(st == SC_OK, "pitch branch runs: %s", msg.text);
  sc_branchn_special s;
  double xo[2] = {0, 0};
  expect(b, "pitchfork BP", SC_PTN_BP, 1, pstar, xo, &s);
  tu_int("pitch: three segments (the trivial one and both halves)",
         sc_branchn_nbranches(b), 3);
  /* the crossing branch's points: x^2 = p - p*, y = x / (4 (1 - q)) */
  double worst = 0;
  int nonzero = 0, pos = 0, neg = 0;
  for (size_t i = 0; i < sc_branchn_npoints(b); i++) {
    sc_branchn_point pt;
    sc_branchn_point_get(b, i, &pt);
    if (pt.branch == 0) continue;
    nonzero++;
    pos += pt.x[0] > 0;
    neg += pt.x[0] < 0;
    worst = fmax(worst, fabs(pt.x[0] * pt.x[0] - (pt.p - pstar)));
    worst = fmax(worst, fabs(pt.x[1] - pt.x[0] / (4 * (1 - q))));
  }
  tu_true(nonzero > 10 && pos > 0 && neg > 0,
          "pitch: crossing branch points %d (x > 0: %d, x < 0: %d)", nonzero,
          pos, neg);
  /* the corrector's tolerance (newton_atol 1e-10) */
  tu_close("pitch: crossing branch on x^2 = p - p*", worst, 0, 1e-9);
  sc_branchn_free(b);
  sc_map_free(m);
}

/* A neutral saddle: ghenon at beta = -0.5, R = -3 has det = beta - R s =
 * 1 at s = 0.5 with tr = (R - 2) s = -2.5: real multipliers mu, 1/mu
 * (kappa = tr / 2 = -1.25), a zero of the NS test that is no
 * bifurcation: reported NN at alpha = 4 s^2 + 0.5 s = 1.25, no NS. */
static void check_neutral_saddle(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("ghenon", NULL, &m, &msg);
  sc_map_set_param_by_name(m, "beta", -0.5, &msg);
  sc_map_set_param_by_name(m, "R", -3, &msg);
  double s0 = (-0.5 + sqrt(0.25 + 32)) / 8, x0[2] = {s0, s0};
  sc_branchn_spec sp = {.param = 0, .from = 2, .to = 0.5, .period = 1,
                        .x0 = x0, .max_points = 5000, .max_branches = 1,
                        .max_period = 1};
  sc_branchn *b;
  tu_int("neutral saddle: alloc", sc_branchn_alloc(m, &sp, &b, &msg), SC_OK);
  tu_int("neutral saddle: run", sc_branchn_run(b, &msg), SC_OK);
  sc_branchn_special s;
  double xs[2] = {0.5, 0.5};
  expect(b, "neutral saddle NN", SC_PTN_NN, 1, 1.25, xs, &s);
  tu_close("neutral saddle: kappa", s.kappa, -1.25, PT_TOL);
  tu_true(isnan(s.theta) && isnan(s.coef), "neutral saddle: no angle, no "
          "coefficient (%g, %g)", s.theta, s.coef);
  tu_true(!find(b, SC_PTN_NS, 1, 1.25, &s), "neutral saddle: no NS");
  sc_branchn_free(b);
  sc_map_free(m);
}

/* n = 1 through the same code: the logistic map's flips at r = 3
 * (x = 2/3) and, on the doubled branch, at r = 1 + sqrt(6), the values
 * the one-dimensional branch (orbits.h) is tested on. */
static void check_logistic(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("logistic", NULL, &m, &msg);
  double x0[1] = {0.6};
  sc_branchn_spec sp = {.param = 0, .from = 2.5, .to = 3.5, .period = 1,
                        .x0 = x0, .switch_pd = 1, .max_points = 5000,
                        .max_branches = 4, .max_period = 2};
  sc_branchn *b;
  tu_int("logistic: alloc", sc_branchn_alloc(m, &sp, &b, &msg), SC_OK);
  tu_int("logistic: run", sc_branchn_run(b, &msg), SC_OK);
  sc_branchn_special s;
  double xf[1] = {2.0 / 3};
  expect(b, "logistic PD period 1", SC_PTN_PD, 1, 3, xf, &s);
  expect(b, "logistic PD period 2", SC_PTN_PD, 2, 1 + sqrt(6), NULL, &s);
  sc_branchn_free(b);
  sc_map_free(m);
}

static void check_refusals(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("henon", NULL, &m, &msg);
  double x0[2] = {0.1, NAN};
  sc_branchn_spec sp = {.param = 0, .from = 0.1, .to = 1, .period = 1,
                        .x0 = x0, .max_points = 100, .max_branches = 1,
                        .max_period = 1};
  sc_branchn *b;
  tu_int("non-finite x0 refused", sc_branchn_alloc(m, &sp, &b, &msg),
         SC_EINVAL);
  x0[1] = 0;
  sp.to = sp.from;
  tu_int("to = from refused", sc_branchn_alloc(m, &sp, &b, &msg), SC_EINVAL);
  sp.to = 1, sp.period = 2;
  tu_int("period above max_period refused",
         sc_branchn_alloc(m, &sp, &b, &msg), SC_EINVAL);
  sp.period = 1;
  /* no fixed point of henon at a = -1 (a < -(1 - b)^2 / 4) */
  sp.from = -1;
  tu_int("alloc", sc_branchn_alloc(m, &sp, &b, &msg), SC_OK);
  int st = sc_branchn_run(b, &msg);
  tu_true(st == SC_ENOCONV, "a start on no orbit fails: %d %s", st, msg.text);
  sc_branchn_free(b);
  sc_map_free(m);
}

int main(void) {
  check_ghenon();
  check_henon();
  check_pitchfork();
  check_neutral_saddle();
  check_logistic();
  check_kink();
  check_refusals();
  return tu_finish();
}
