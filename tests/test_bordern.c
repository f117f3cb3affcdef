/* Borders of n-dimensional maps (models.h sc_bordern, map.h
 * sc_map_iterate_n_ex, branchn.h) on the border-collision normal form
 * bcnf, (x, y) -> (tau x + y + mu, -delta x) with (tau_L, delta_L) for
 * x <= 0 and (tau_R, delta_R) for x > 0, whose answers are closed forms:
 *  - a fixed point on side S: x* = mu / (1 - tau_S + delta_S), y* =
 *    -delta_S x*, on the switching line x = 0 at mu = 0;
 *  - the period-2 orbit L R: (1 + delta_L) x_L - tau_R x_R = mu,
 *    (1 + delta_R) x_R - tau_L x_L = mu, so with D = (1 + delta_L)
 *    (1 + delta_R) - tau_L tau_R, x_L = mu (1 + delta_R + tau_R) / D,
 *    x_R = mu (1 + delta_L + tau_L) / D, y_L = -delta_R x_R: its L point
 *    reaches x = 0 at tau_R = -(1 + delta_R) for any mu != 0. */
#include <math.h>
#include <string.h>

#include "slipcont/branchn.h"
#include "slipcont/map.h"
#include "test_util.h"

/* Border points are Newton solutions of {g - x = 0, m = 0}; the map is
 * piecewise linear, so Newton lands on the root in one step up to the
 * rounding of a few products of numbers of order 1. */
static const double PT_TOL = 1e-12;

/* Central differences of a piecewise-linear map along a forced
 * itinerary are exact up to rounding (the pieces are affine in x and
 * in each parameter): the step's rounding, eps / h ~ 1e-10. */
static const double FD_TOL = 1e-8;
static const double FD_H = 1e-6;

static sc_map *bcnf(double mu, double tl, double dl, double tr, double dr) {
  sc_map *m;
  sc_msg msg;
  if (sc_map_alloc("bcnf", NULL, &m, &msg)) return NULL;
  const char *nm[] = {"mu", "tau_L", "delta_L", "tau_R", "delta_R"};
  double v[] = {mu, tl, dl, tr, dr};
  for (int i = 0; i < 5; i++) sc_map_set_param_by_name(m, nm[i], v[i], &msg);
  return m;
}

/* f^3 along forced codes L R L from a point: the borders of the three
 * iterates, their chained gradients against central differences of the
 * border values, and the codes followed. */
static void check_chain(void) {
  sc_map *m = bcnf(0.35, 0.45, 0.25, -1.7, 0.55);
  sc_msg msg;
  sc_mapn_value *v;
  sc_bordern_list *l, *l2;
  sc_mapn_value_alloc(m, SC_EVAL_DERIV, &v, &msg);
  sc_bordern_list_alloc(m, 8, &l, &msg);
  sc_bordern_list_alloc(m, 8, &l2, &msg);
  sc_itin_code force[3] = {{1, {'L'}}, {1, {'R'}}, {1, {'L'}}}, codes[3];
  double x[2] = {0.2385, -0.417};
  int st = sc_map_iterate_n_ex(m, x, 3, SC_EVAL_DERIV, force, codes, l, v,
                               &msg);
  tu_int("forced f^3 evaluates", st, SC_OK);
  tu_int("three borders, one per iterate", (long)l->n, 3);
  for (int k = 0; k < 3; k++)
    tu_true(codes[k].n == 1 && codes[k].c[0] == force[k].c[0],
            "iterate %d follows the forced code", k);
  /* x0 = 0.2385 > 0 followed as L: its border -x is negative there */
  tu_close("border of iterate 0 (forced L at x > 0)", l->b[0].value, -0.2385,
           1e-15);
  tu_true(l->b[0].kind == SC_BORDER_SWITCHING && l->b[0].on_state,
          "the switching line is a border in the state");
  for (size_t i = 0; i < l->n; i++) {
    char what[96];
    for (int j = 0; j < 2; j++) {
      double xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]};
      xp[j] += FD_H, xm[j] -= FD_H;
      l2->n = 0;
      sc_map_iterate_n_ex(m, xp, 3, SC_EVAL_VALUE, force, NULL, l2, v, &msg);
      double mp = l2->b[i].value;
      l2->n = 0;
      sc_map_iterate_n_ex(m, xm, 3, SC_EVAL_VALUE, force, NULL, l2, v, &msg);
      snprintf(what, sizeof what, "border %zu: dm/dx_%d", i, j);
      tu_close(what, l->b[i].dx[j], (mp - l2->b[i].value) / (2 * FD_H),
               FD_TOL);
    }
    for (size_t q = 0; q < 5; q++) {
      double p0 = sc_map_get_param(m, q), mv[2];
      for (int s = 0; s < 2; s++) {
        sc_map_set_param(m, q, p0 + (s ? -FD_H : FD_H), &msg);
        l2->n = 0;
        sc_map_iterate_n_ex(m, x, 3, SC_EVAL_VALUE, force, NULL, l2, v, &msg);
        mv[s] = l2->b[i].value;
      }
      sc_map_set_param(m, q, p0, &msg);
      snprintf(what, sizeof what, "border %zu: dm/dp_%zu", i, q);
      tu_close(what, l->b[i].dp[q], (mv[0] - mv[1]) / (2 * FD_H), FD_TOL);
    }
  }
  /* the natural itinerary and its codes: the values all positive */
  l->n = 0;
  sc_map_iterate_n_ex(m, x, 3, SC_EVAL_VALUE, NULL, codes, l, v, &msg);
  int pos = 1;
  for (size_t i = 0; i < l->n; i++) pos &= l->b[i].value >= 0;
  tu_true(pos && codes[0].c[0] == 'R', "natural: every border >= 0, x0 on R");
  /* refusals: a bad code, a list of another dimension, a 1-d model */
  sc_itin_code bad = {1, {'Q'}};
  tu_int("a code the model cannot follow",
         sc_map_eval_n_ex(m, x, 0, &bad, NULL, NULL, v, &msg), SC_EINVAL);
  sc_map *lg;
  sc_map_alloc("logistic", NULL, &lg, &msg);
  sc_mapn_value *v1;
  sc_mapn_value_alloc(lg, SC_EVAL_DERIV, &v1, &msg);
  tu_int("a list of dimension 2 for a 1-d model",
         sc_map_eval_n_ex(lg, x, 0, NULL, NULL, l, v1, &msg), SC_EINVAL);
  tu_true(!sc_map_has_borders_n(lg) && sc_map_has_borders_n(m) &&
              !sc_map_has_borders(m),
          "n-dimensional borders are bcnf's, one-dimensional ones not");
  sc_mapn_value_free(v1);
  sc_map_free(lg);
  sc_bordern_list_free(l);
  sc_bordern_list_free(l2);
  sc_mapn_value_free(v);
  sc_map_free(m);
}

static int special(const sc_branchn *b, sc_branchn_label label,
                   sc_branchn_special *s) {
  for (size_t i = 0; i < sc_branchn_nspecial(b); i++)
    if (sc_branchn_special_get(b, i, s) == SC_OK && s->label == label)
      return 1;
  return 0;
}

/* The worst distance of branch @p br's points from the fixed point of
 * side (tau, delta), and its direction in mu. */
static double off_line(const sc_branchn *b, int br, double tau, double delta,
                       int *dir, size_t *np) {
  double worst = 0, p0 = NAN, p1 = NAN;
  *np = 0;
  for (size_t i = 0; i < sc_branchn_npoints(b); i++) {
    sc_branchn_point pt;
    sc_branchn_point_get(b, i, &pt);
    if (pt.branch != br) continue;
    double xs = pt.p / (1 - tau + delta);
    worst = fmax(worst, fmax(fabs(pt.x[0] - xs), fabs(pt.x[1] + delta * xs)));
    if (isnan(p0)) p0 = pt.p;
    p1 = pt.p, (*np)++;
  }
  *dir = p1 > p0 ? 1 : -1;
  return worst;
}

/* A fixed point through the border in mu: the SW point at mu = 0 and
 * the hand-over onto the right side's fixed point, which goes on with mu
 * increasing where 1 - tau_R + delta_R > 0 (persistence) and turns back
 * where it is < 0 (the two fixed points meet at the border: a
 * border-collision fold). */
static void check_mu(double tr, int dir_expected) {
  double tl = 0.5, dl = 0.3, dr = 0.3;
  sc_map *m = bcnf(-1, tl, dl, tr, dr);
  sc_msg msg;
  double x0[2] = {-1 / (1 - tl + dl), dl / (1 - tl + dl)};
  sc_branchn_spec sp = {.param = 0, .from = -1, .to = 1, .period = 1,
                        .x0 = x0, .max_points = 500, .max_branches = 4,
                        .max_period = 4};
  sc_branchn *b;
  tu_int("alloc", sc_branchn_alloc(m, &sp, &b, &msg), SC_OK);
  tu_int("run", sc_branchn_run(b, &msg), SC_OK);
  sc_branchn_special s;
  if (tu_true(special(b, SC_PTN_SW, &s), "SW found (tau_R = %g)", tr)) {
    tu_close("SW: mu", s.p, 0, PT_TOL);
    tu_close("SW: x", s.x[0], 0, PT_TOL);
    tu_close("SW: y", s.x[1], 0, PT_TOL);
    tu_true(s.method == SC_LOC_NEWTON && s.residual <= PT_TOL,
            "SW: Newton, residual %g", s.residual);
    tu_true(strcmp(s.border, "x = 0") == 0, "SW: the border named");
  }
  int dir;
  size_t np;
  tu_close("branch 0 on the left fixed point", off_line(b, 0, tl, dl, &dir,
                                                         &np), 0, PT_TOL);
  double w = off_line(b, 1, tr, dr, &dir, &np);
  tu_true(np >= 2, "the hand-over branch has %zu points", np);
  tu_close("branch 1 on the right fixed point", w, 0, PT_TOL);
  tu_int("branch 1's direction in mu", dir, dir_expected);
  sc_branchn_free(b);
  sc_map_free(m);
}

/* The period-2 orbit L R at mu = 0.5 continued in tau_R: its L point
 * reaches x = 0 at tau_R = -(1 + delta_R) = -1.3. */
static void check_period2(void) {
  double mu = 0.5, tl = 0.5, dl = 0.3, dr = 0.3, tr0 = -1.5;
  sc_map *m = bcnf(mu, tl, dl, tr0, dr);
  sc_msg msg;
  double D = (1 + dl) * (1 + dr) - tl * tr0;
  double xl = mu * (1 + dr + tr0) / D, xr = mu * (1 + dl + tl) / D;
  double x0[2] = {xl, -dr * xr};
  sc_branchn_spec sp = {.param = 3, .from = tr0, .to = -1, .period = 2,
                        .x0 = x0, .max_points = 500, .max_branches = 4,
                        .max_period = 4};
  sc_branchn *b;
  tu_int("alloc", sc_branchn_alloc(m, &sp, &b, &msg), SC_OK);
  tu_int("run", sc_branchn_run(b, &msg), SC_OK);
  sc_branchn_special s;
  double trs = -(1 + dr), Ds = (1 + dl) * (1 + dr) - tl * trs;
  if (tu_true(special(b, SC_PTN_SW, &s), "period-2 SW found")) {
    tu_close("period-2 SW: tau_R", s.p, trs, PT_TOL);
    tu_close("period-2 SW: x_L", s.x[0], 0, PT_TOL);
    tu_close("period-2 SW: y_L", s.x[1], -dr * mu * (1 + dl + tl) / Ds,
             PT_TOL);
    tu_int("period-2 SW: period", s.period, 2);
    tu_true(s.residual <= PT_TOL, "period-2 SW: residual %g", s.residual);
  }
  sc_branchn_free(b);
  sc_map_free(m);
}

/* The period-2 orbit L R at tau_R = -1.5 continued in mu from 0.5 to
 * -0.5: both its points reach x = 0 at mu = 0, where it shrinks onto the
 * fixed point x = y = 0: a SW of an orbit of minimal period 1, with no
 * hand-over (the other side has no period-2 orbit from there). */
static void check_period2_born(void) {
  double mu = 0.5, tl = 0.5, dl = 0.3, dr = 0.3, tr = -1.5;
  sc_map *m = bcnf(mu, tl, dl, tr, dr);
  sc_msg msg;
  double D = (1 + dl) * (1 + dr) - tl * tr;
  double x0[2] = {mu * (1 + dr + tr) / D, -dr * mu * (1 + dl + tl) / D};
  sc_branchn_spec sp = {.param = 0, .from = mu, .to = -0.5, .period = 2,
                        .x0 = x0, .max_points = 500, .max_branches = 4,
                        .max_period = 4};
  sc_branchn *b;
  tu_int("alloc", sc_branchn_alloc(m, &sp, &b, &msg), SC_OK);
  tu_int("run", sc_branchn_run(b, &msg), SC_OK);
  sc_branchn_special s;
  if (tu_true(special(b, SC_PTN_SW, &s), "SW of the period-2 orbit found")) {
    tu_close("its mu", s.p, 0, PT_TOL);
    tu_close("its x", s.x[0], 0, PT_TOL);
    tu_true(strstr(s.note, "minimal period 1") != NULL,
            "the note says the orbit has minimal period 1: %s", s.note);
  }
  tu_int("no hand-over onto the fixed point traversed twice",
         sc_branchn_nbranches(b), 1);
  sc_branchn_free(b);
  sc_map_free(m);
}

int main(void) {
  check_chain();
  check_mu(-1.5, 1);
  check_mu(2.5, -1);
  check_period2();
  check_period2_born();
  return tu_finish();
}
