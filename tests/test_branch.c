/* Branches of periodic orbits (sc_orbit_branch, branch.h).
 *
 * - Logistic map: the fixed point continued in r with branch switching:
 *   flips at r = 3 and r = 1 + sqrt 6 (and the next two of the cascade
 *   against their 50-digit values); each PD's new branch has twice the
 *   period; the period-3 fold at r = 1 + 2 sqrt 2.
 * - bk2, driver frozen, beta = 2.5 (fig 5.8): the flip cascade from the
 *   period-2 orbit of alpha = 3; the period-6 window's two folds, a closed
 *   curve of orbits; multipliers -1 and +1 at the located points; every
 *   stable branch point is the orbit brute-force iteration converges to.
 * - bk2, driver frozen, beta = 3.2 (fig 5.12): a crossing-sliding after
 *   which the branch goes on with period 1, a grazing-sliding, the
 *   period-3 fold; each DIB's degeneracy recomputed at the located point.
 * - sc_map_iterate_points (branch segments by multiple shooting) against
 *   sc_map_iterate_ex at the iterates of one point.
 *
 * Tolerances: special points are located until the arclength step is
 * within 1e-13 (1 + |u|) and |test function| <= 1e-8 (the continuation
 * defaults); flips are located to rounding in the map (1e-13 for the
 * logistic map, as in test_continuation); the multipliers at LP and PD
 * are within test_atol = 1e-8 of +1 and -1.  DIBs are bracketed in the
 * parameter to 1e-13 (1 + |p|) and their margins are below
 * SC_DIB_MARGIN_TOL (branch.h explains the value). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/bk2.h"
#include "slipcont/orbits.h"
#include "slipcont/shooting.h"
#include "test_util.h"

static sc_orbit_branch_spec spec0(size_t param, double from, double to,
                                  int period, double d0) {
  sc_orbit_branch_spec sp = {.param = param, .from = from, .to = to,
                             .period = period, .d0 = d0, .switch_pd = 1,
                             .max_points = 2000, .max_branches = 40,
                             .max_period = 16};
  return sp;
}

/* Special points of a label, in the order found. */
static int collect(const sc_orbit_branch *b, sc_point_label l,
                   sc_orbit_special_info *out, int max) {
  int n = 0;
  for (size_t i = 0; i < sc_orbit_branch_nspecial(b) && n < max; i++) {
    sc_orbit_special_info sp;
    sc_orbit_branch_special(b, i, &sp);
    if (sp.label == l) out[n++] = sp;
  }
  return n;
}

/* Period of branch @p k (from its points), 0 if it has none. */
static int branch_period(const sc_orbit_branch *b, int k) {
  sc_orbit_point_info pt;
  for (size_t i = 0; i < sc_orbit_branch_npoints(b); i++) {
    sc_orbit_branch_point(b, i, &pt);
    if (pt.branch == k) return pt.period;
  }
  return 0;
}

/* A fold or flip test that changes sign by a jump is reported as not
 * located (SC_LOC_FAILED), not dropped.  The multiplier jumps only where
 * f^m is not smooth: at a border of the orbit (next to a switching, f'
 * grows like |d - d*|^(-1/2)), so such a report must sit at a border
 * point the branch located, within 1e-6 in the parameter (steps here are
 * up to 1e-2).  Every located fold and flip has multiplier +1 or -1. */
static void check_lp_pd(const sc_orbit_branch *b) {
  sc_orbit_special_info sp[64];
  for (int lp = 0; lp < 2; lp++) {
    sc_point_label l = lp ? SC_PT_LP : SC_PT_PD;
    int n = collect(b, l, sp, 64);
    for (int i = 0; i < n; i++) {
      if (sp[i].method != SC_LOC_FAILED) {
        tu_close(lp ? "multiplier at a located LP"
                    : "multiplier at a located PD",
                 sp[i].multiplier, lp ? 1 : -1, 1e-8);
        continue;
      }
      double dist = HUGE_VAL;
      for (size_t k = 0; k < sc_orbit_branch_nspecial(b); k++) {
        sc_orbit_special_info x;
        sc_orbit_branch_special(b, k, &x);
        if (x.label >= SC_PT_GR && x.label <= SC_PT_TT &&
            x.method != SC_LOC_FAILED)
          dist = fmin(dist, fabs(x.p - sp[i].p));
      }
      tu_true(dist <= 1e-6,
              "%s not located at p = %.12g (a jump of its test, multiplier "
              "%.4g): %.3g from the nearest located border point",
              lp ? "LP" : "PD", sp[i].p, sp[i].multiplier, dist);
    }
  }
}

/* Each PD followed by a new branch: that branch has twice the period. */
static void check_doubling(const sc_orbit_branch *b) {
  int nb = sc_orbit_branch_nbranches(b), checked = 0;
  for (int k = 1; k < nb; k++) {
    /* A branch born at a flip starts within 1e-3 of that PD in p. */
    sc_orbit_point_info pt;
    for (size_t i = 0; i < sc_orbit_branch_npoints(b); i++) {
      sc_orbit_branch_point(b, i, &pt);
      if (pt.branch == k) break;
    }
    sc_orbit_special_info sp[64];
    int n = collect(b, SC_PT_PD, sp, 64);
    for (int j = 0; j < n; j++)
      if (fabs(sp[j].p - pt.p) < 2e-3 * (1 + fabs(pt.p)) &&
          strstr(sp[j].note, "period-doubled branch is followed") &&
          branch_period(b, sp[j].branch) * 2 == pt.period) {
        checked++;
        break;
      }
  }
  tu_true(checked >= 1, "%d branches start at a PD with twice its period",
          checked);
}

static void test_logistic(void) {
  printf("--- logistic: fixed point in r with branch switching\n");
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("logistic", NULL, &m, &msg);
  sc_orbit_branch_spec sp = spec0(0, 2.8, 3.6, 1, 0.6);
  sp.max_period = 8;
  sp.hmax = 0.01;
  sc_orbit_branch *b;
  int st = sc_orbit_branch_alloc(m, &sp, &b, &msg);
  if (!st) st = sc_orbit_branch_run(b, &msg);
  tu_int("run: SC_OK", st, SC_OK);
  sc_orbit_special_info pd[16];
  int n = collect(b, SC_PT_PD, pd, 16);
  tu_int("four flips (periods 1, 2, 4, 8)", n, 4);
  /* Sorted by period, they are the cascade r_1 .. r_4 (mpmath values,
   * as in test_continuation). */
  const double want[4] = {3.0, 1 + 2.449489742783178098197284,
                          3.54409035955192285361596598660,
                          3.56440726609543259777355758653};
  for (int k = 0; k < n && k < 4; k++) {
    int per = 1 << k;
    for (int i = 0; i < n; i++)
      if (pd[i].period == per) {
        char what[64];
        snprintf(what, sizeof what, "flip of the period-%d orbit", per);
        tu_close(what, pd[i].p, want[k], 1e-13);
      }
  }
  check_lp_pd(b);
  check_doubling(b);
  int nb = 0;
  for (int l = SC_PT_GR; l <= SC_PT_TT; l++)
    nb += collect(b, (sc_point_label)l, pd, 16);
  tu_int("no border point on a smooth map", nb, 0);
  sc_orbit_branch_free(b);

  printf("--- logistic: period-3 fold\n");
  sc_map_set_param(m, 0, 3.835, &msg);
  double x = 0.5;
  sc_map_value v;
  for (int k = 0; k < 3000; k++) {
    sc_map_eval(m, x, SC_EVAL_VALUE, &v, &msg);
    x = v.f;
  }
  sp = spec0(0, 3.835, 3.8, 3, x);
  sp.hmax = 2e-3;
  sp.switch_pd = 0;
  sc_orbit_branch_alloc(m, &sp, &b, &msg);
  st = sc_orbit_branch_run(b, &msg);
  tu_int("run: SC_OK", st, SC_OK);
  sc_orbit_special_info lp[4];
  n = collect(b, SC_PT_LP, lp, 4);
  tu_int("one fold", n, 1);
  if (n) tu_close("period-3 fold at r = 1 + 2 sqrt 2", lp[0].p, 1 + 2 * sqrt(2),
                  1e-13);
  check_lp_pd(b);
  sc_orbit_branch_free(b);
  sc_map_free(m);
}

static sc_map *bk2_frozen(double beta) {
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("bk2", NULL, &m, &msg);
  sc_map_set_option(m, "driver", "frozen", &msg);
  sc_map_set_param_by_name(m, "beta", beta, &msg);
  sc_map_set_param_by_name(m, "phi", 1.25, &msg);
  return m;
}

/* Stable points of the branches against brute force: iterate from a
 * point displaced by 1e-6 and compare with the orbit after 3000
 * iterates.  Points with |multiplier| > 0.9 (slow convergence) and
 * those within 1e-3 of a special point are skipped. */
static void check_brute_force(const sc_orbit_branch *b, sc_map *m,
                              size_t param) {
  int checked = 0, bad = 0;
  double worst = 0;
  for (size_t i = 0; i < sc_orbit_branch_npoints(b); i += 7) {
    sc_orbit_point_info pt;
    sc_orbit_branch_point(b, i, &pt);
    if (!pt.stable || fabs(pt.multiplier) > 0.9) continue;
    int near = 0;
    for (size_t j = 0; j < sc_orbit_branch_nspecial(b); j++) {
      sc_orbit_special_info sp;
      sc_orbit_branch_special(b, j, &sp);
      if (fabs(sp.p - pt.p) < 1e-3) near = 1;
    }
    if (near) continue;
    sc_map_set_param(m, param, pt.p, NULL);
    double x = pt.d + 1e-6;
    sc_map_value v;
    int st = 0;
    for (int k = 0; k < 3000 * pt.period && !st; k++) {
      st = sc_map_eval(m, x, SC_EVAL_VALUE, &v, NULL);
      x = v.f;
    }
    /* After a multiple of the period the iterate is back near d. */
    double err = st ? HUGE_VAL : fabs(x - pt.d);
    worst = fmax(worst, err);
    if (err > 1e-9) bad++;
    checked++;
  }
  printf("  %d stable points checked against brute force, worst %.3g\n",
         checked, worst);
  tu_true(checked >= 10, "at least 10 stable points checked (%d)", checked);
  /* |multiplier| <= 0.9: 3000 periods contract 1e-6 far below 1e-9. */
  tu_int("stable points not reached by brute force within 1e-9", bad, 0);
}

/* A border point's border recomputed independently of the branch code:
 * the orbit of the nearest accepted point of its segment is shot again
 * from that point, its natural codes taken there (starting at the orbit
 * point nearest s->d), and f^m evaluated from s->d at the located
 * parameter along those codes: the border named s->border of the first
 * iterate must vanish there, and the orbit must be periodic. */
static double border_recomputed(sc_map *m, size_t ia,
                                const sc_orbit_branch *b,
                                const sc_orbit_special_info *sp,
                                double *orbit_res) {
  *orbit_res = HUGE_VAL;
  const int q = sp->period;
  sc_orbit_point_info near = {0}, pt;
  double dist = HUGE_VAL;
  for (size_t i = 0; i < sc_orbit_branch_npoints(b); i++) {
    sc_orbit_branch_point(b, i, &pt);
    if (pt.branch == sp->branch && pt.period == q &&
        fabs(pt.p - sp->p) < dist)
      dist = fabs(pt.p - sp->p), near = pt;
  }
  if (!isfinite(dist) || q > 64) return HUGE_VAL;
  sc_map_set_param(m, ia, near.p, NULL);
  double o[64];
  o[0] = near.d;
  for (int k = 1; k < q; k++) {
    sc_map_value w;
    if (sc_map_eval(m, o[k - 1], SC_EVAL_VALUE, &w, NULL)) return HUGE_VAL;
    o[k] = w.f;
  }
  int k0 = 0;
  for (int k = 1; k < q; k++)
    if (fabs(o[k] - sp->d) < fabs(o[k0] - sp->d)) k0 = k;
  sc_itin_code codes[64];
  sc_border bl[512];
  sc_border_list l = {bl, 512, 0};
  sc_map_value v;
  if (sc_map_iterate_ex(m, o[k0], q, SC_EVAL_DERIV, NULL, codes, &l, &v,
                        NULL))
    return HUGE_VAL;
  /* the border's own code for its iterate, where it has one (a grazing
   * from the side where the guard fires: the event at the maximum) */
  for (size_t i = 0; i < l.n && i < l.cap; i++)
    if (bl[i].iterate == 0 && strcmp(bl[i].name, sp->border) == 0 &&
        bl[i].alt.n > 0)
      codes[0] = bl[i].alt;
  sc_map_set_param(m, ia, sp->p, NULL);
  l.n = 0;
  if (sc_map_iterate_ex(m, sp->d, q, SC_EVAL_DERIV, codes, NULL, &l, &v,
                        NULL))
    return HUGE_VAL;
  for (size_t i = 0; i < l.n && i < l.cap; i++)
    if (bl[i].iterate == 0 && strcmp(bl[i].name, sp->border) == 0) {
      *orbit_res = fabs(v.f - sp->d);
      return fabs(bl[i].value);
    }
  return HUGE_VAL;
}

/* Every border point (GR, CS, SW, BR, TT): located by Newton with a
 * residual certificate, its border recomputed to zero, and for SW the
 * point at d* itself. */
static int check_borders(const sc_orbit_branch *b, sc_map *m, size_t ia,
                         double beta) {
  int n = 0;
  for (size_t i = 0; i < sc_orbit_branch_nspecial(b); i++) {
    sc_orbit_special_info s;
    sc_orbit_branch_special(b, i, &s);
    if (s.label == SC_PT_LP || s.label == SC_PT_PD || s.label == SC_PT_EP)
      continue;
    const char *l = sc_point_label_text(s.label);
    n++;
    tu_true(s.method == SC_LOC_NEWTON, "%s at %.12g located by Newton (%s)",
            l, s.p, s.note);
    if (s.method != SC_LOC_NEWTON) continue;
    /* the defining system is scaled by the map (displacements of order
     * 0.1): 1e-10 leaves room for f^m's conditioning */
    tu_true(s.residual <= 1e-10, "%s at %.12g: residual %.3g <= 1e-10", l,
            s.p, s.residual);
    if (s.label == SC_PT_SW) {
      /* the orbit through d* at the located parameter, with the model's
       * own tie rule there (both blocks start): periodic */
      double a = s.p; /* alpha is the continued parameter here */
      tu_close("SW: the orbit point sits at d*", s.d, sc_bk2_dstar(a, beta),
               1e-12);
      sc_map_value v;
      sc_map_set_param(m, ia, s.p, NULL);
      int st = sc_map_iterate(m, s.d, s.period, SC_EVAL_VALUE, &v, NULL);
      tu_true(!st && fabs(v.f - s.d) <= 1e-9,
              "SW at %.12g: the orbit through d* is periodic there (%.3g)",
              s.p, st ? HUGE_VAL : fabs(v.f - s.d));
      continue;
    }
    double ores, mb = border_recomputed(m, ia, b, &s, &ores);
    char what[128];
    snprintf(what, sizeof what, "%s at %.12g: border '%s' recomputed", l,
             s.p, s.border);
    tu_close(what, mb, 0, 1e-9);
    tu_true(ores <= 1e-9, "%s at %.12g: the orbit through d = %.12g is "
                          "periodic there (%.3g)",
            l, s.p, s.d, ores);
  }
  return n;
}

static void test_fig58(void) {
  printf("--- bk2 frozen, beta = 2.5 (fig 5.8)\n");
  sc_map *m = bk2_frozen(2.5);
  size_t ia = (size_t)sc_map_param_index(m, "alpha");
  sc_msg msg = {""};
  sc_orbit_branch_spec sp = spec0(ia, 3.0, 3.45, 2, 0.2253);
  sp.hmax = 0.01;
  sp.max_period = 8;
  sc_orbit_branch *b;
  int st = sc_orbit_branch_alloc(m, &sp, &b, &msg);
  if (!st) st = sc_orbit_branch_add_start(b, 3.3, 0.0991, 6, &msg);
  if (!st) st = sc_orbit_branch_run(b, &msg);
  tu_int("run: SC_OK", st, SC_OK);
  sc_orbit_special_info s[64];
  int n = collect(b, SC_PT_PD, s, 64);
  tu_true(n >= 3, "the flip cascade: %d PDs", n);
  int first = 0;
  for (int i = 0; i < n; i++)
    if (s[i].period == 2 && fabs(s[i].p - 3.0568) < 1e-3) first = 1;
  tu_true(first, "first flip of the cascade near alpha = 3.0568");
  n = collect(b, SC_PT_LP, s, 64);
  int lo = 0, hi = 0;
  for (int i = 0; i < n; i++) {
    if (s[i].period != 6) continue;
    if (fabs(s[i].p - 3.2196) < 1e-3) lo++;
    if (fabs(s[i].p - 3.3878) < 1e-3) hi++;
  }
  tu_true(lo >= 1 && hi >= 1, "the period-6 window's folds near 3.2196 and "
                              "3.3878 (%d, %d)",
          lo, hi);
  n = collect(b, SC_PT_EP, s, 64);
  int closed = 0;
  for (int i = 0; i < n; i++)
    if (strstr(s[i].note, "closes on itself")) closed = 1;
  tu_true(closed, "the period-6 branch is a closed curve");
  int ndib = check_borders(b, m, ia, 2.5);
  tu_true(ndib >= 1, "%d border points located and checked", ndib);
  check_lp_pd(b);
  check_doubling(b);
  check_brute_force(b, m, ia);
  sc_orbit_branch_free(b);
  sc_map_free(m);
}

static void test_fig512(void) {
  printf("--- bk2 frozen, beta = 3.2 (fig 5.12)\n");
  sc_map *m = bk2_frozen(3.2);
  size_t ia = (size_t)sc_map_param_index(m, "alpha");
  sc_msg msg = {""};
  sc_orbit_branch_spec sp = spec0(ia, 5.0, 6.5, 2, 0.2157);
  sp.hmax = 0.01;
  sc_orbit_branch *b;
  int st = sc_orbit_branch_alloc(m, &sp, &b, &msg);
  if (!st) st = sc_orbit_branch_add_start(b, 6.0, 0.1223, 3, &msg);
  if (!st) st = sc_orbit_branch_run(b, &msg);
  tu_int("run: SC_OK", st, SC_OK);
  sc_orbit_special_info cs[8], gr[8], lp[8];
  int ncs = collect(b, SC_PT_CS, cs, 8), ngr = collect(b, SC_PT_GR, gr, 8),
      nlp = collect(b, SC_PT_LP, lp, 8);
  tu_true(ncs >= 1 && fabs(cs[0].p - 5.6488) < 1e-3,
          "crossing-sliding near alpha = 5.6488 (%d found)", ncs);
  int g1 = 0;
  for (int i = 0; i < ngr; i++)
    if (gr[i].period == 1 && fabs(gr[i].p - 5.7494) < 1e-3) g1++;
  tu_true(g1 == 1, "grazing-sliding of the period-1 orbit near alpha = "
                   "5.7494 (%d of %d GR)",
          g1, ngr);
  int p3 = 0;
  for (int i = 0; i < nlp; i++)
    if (lp[i].period == 3 && fabs(lp[i].p - 5.6357) < 1e-3) p3 = 1;
  tu_true(p3, "the period-3 fold near alpha = 5.6357");
  if (ncs) {
    tu_int("CS on the period-2 orbit", cs[0].period, 2);
    tu_true(strstr(cs[0].note, "continues with period 1") != NULL,
            "after the CS the branch goes on with period 1: %s", cs[0].note);
  }
  check_borders(b, m, ia, 3.2);
  check_lp_pd(b);
  check_brute_force(b, m, ia);
  sc_orbit_branch_free(b);
  sc_map_free(m);
}

static void test_errors(void) {
  printf("--- error paths\n");
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("logistic", NULL, &m, &msg);
  sc_orbit_branch *b = (sc_orbit_branch *)&msg;
  sc_orbit_branch_spec sp = spec0(0, 3, 3, 1, 0.5);
  tu_int("from = to: SC_EINVAL", sc_orbit_branch_alloc(m, &sp, &b, &msg),
         SC_EINVAL);
  tu_true(b == NULL, "no object on failure");
  printf("  message: %s\n", msg.text);
  sp = spec0(5, 2, 3, 1, 0.5);
  tu_int("bad parameter index: SC_EINVAL",
         sc_orbit_branch_alloc(m, &sp, &b, &msg), SC_EINVAL);
  sp = spec0(0, 2, 3, 1, 0.5);
  sp.max_period = 0;
  tu_int("max_period < period: SC_EINVAL",
         sc_orbit_branch_alloc(m, &sp, &b, &msg), SC_EINVAL);
  sp = spec0(0, 2, 3, 1, 0.5);
  sc_orbit_branch_alloc(m, &sp, &b, &msg);
  tu_int("start outside the interval: SC_EINVAL",
         sc_orbit_branch_add_start(b, 4, 0.5, 1, &msg), SC_EINVAL);
  sc_orbit_branch_free(b);
  sc_orbit_branch_free(NULL);
  sc_map_free(m);
}

/* A period-2 segment that runs into the flip it was born in must not go
 * on along the period-1 orbit traversed twice (same itinerary, also a
 * fixed point of f^2): it ends there and the period-1 branch is followed
 * with its own period.  fig 5.8 below alpha = 3: the period-1 orbit
 * flips near alpha = 2.825 and folds near 2.9925 (brute force: period 2
 * below ~2.83, period 1 up to ~2.99). */
static void test_collapse(void) {
  printf("--- bk2 frozen, beta = 2.5, alpha in [2.8, 3]: period 2 -> 1\n");
  sc_map *m = bk2_frozen(2.5);
  size_t ia = (size_t)sc_map_param_index(m, "alpha");
  sc_msg msg = {""};
  sc_orbit_branch_spec sp = spec0(ia, 2.8, 3.0, 2, 0.2197);
  sp.hmax = 0.01;
  sc_orbit_branch *b;
  int st = sc_orbit_branch_alloc(m, &sp, &b, &msg);
  if (!st) st = sc_orbit_branch_run(b, &msg);
  tu_int("run: SC_OK", st, SC_OK);
  int pd1 = 0, lp1 = 0, lp2 = 0;
  for (size_t i = 0; i < sc_orbit_branch_nspecial(b); i++) {
    sc_orbit_special_info x;
    sc_orbit_branch_special(b, i, &x);
    if (x.label == SC_PT_PD && x.period == 1 && fabs(x.p - 2.8252) < 1e-3)
      pd1++;
    if (x.label == SC_PT_LP && x.period == 1 && fabs(x.p - 2.9925) < 1e-3)
      lp1++;
    if (x.label == SC_PT_LP && x.period == 2) lp2++;
  }
  tu_true(pd1 >= 1, "the period-1 flip near alpha = 2.8252 (%d)", pd1);
  tu_true(lp1 >= 1, "the period-1 fold near alpha = 2.9925 (%d)", lp1);
  tu_int("no fold reported as period 2 (the doubled period-1 orbit)", lp2, 0);
  sc_orbit_branch_free(b);
  sc_map_free(m);
}

/* sc_map_iterate_points (multiple shooting's evaluation) against
 * sc_map_iterate_ex: at the iterates of one point it chains to the same
 * f^8 bit for bit (the same products in the same order), and its
 * borders, whose derivatives are in their own iterate's point, chained
 * by hand give sc_map_iterate_ex's within rounding (1e-12 relative). */
static void test_iterate_points(void) {
  printf("--- sc_map_iterate_points: f^8 iterate by iterate (fig 5.8)\n");
  sc_map *m = bk2_frozen(2.5);
  size_t ia = (size_t)sc_map_param_index(m, "alpha");
  sc_map_set_param(m, ia, 3.25, NULL);
  enum { N = 8 };
  double x[N], each[3 * N], pre[N], prep[N];
  x[0] = 0.2;
  for (int k = 1; k < N; k++) {
    sc_map_value w;
    sc_map_eval(m, x[k - 1], SC_EVAL_VALUE, &w, NULL);
    x[k] = w.f;
  }
  sc_itin_code codes[N];
  sc_border b1[256], b2[256];
  sc_border_list l1 = {b1, 256, 0}, l2 = {b2, 256, 0};
  sc_map_value v1, v2;
  unsigned fl = SC_EVAL_DERIV | SC_EVAL_ITINERARY;
  int st = sc_map_iterate_ex(m, x[0], N, fl, NULL, codes, &l1, &v1, NULL);
  if (!st)
    st = sc_map_iterate_points(m, x, N, fl, codes, NULL, ia, &l2, each, &v2,
                               NULL);
  tu_int("both evaluate", st, SC_OK);
  if (st) {
    sc_map_free(m);
    return;
  }
  tu_true(v1.f == v2.f && v1.dfdd == v2.dfdd && v1.dfdp[ia] == v2.dfdp[ia] &&
              strcmp(v1.itinerary, v2.itinerary) == 0,
          "f^8, (f^8)', d f^8/d alpha and itinerary bit for bit (%.17g %.17g)",
          v2.f, v2.dfdd);
  double prod = 1, dp = 0;
  for (int k = 0; k < N; k++) {
    pre[k] = prod, prep[k] = dp; /* d x_k / d x_0 and d x_k / d alpha */
    dp = each[3 * k + 1] * dp + each[3 * k + 2];
    prod *= each[3 * k + 1];
  }
  tu_true(prod == v2.dfdd && each[3 * (N - 1)] == v2.f,
          "each iterate's f and f' chain to the same value");
  tu_int("the same borders", (long)l2.n, (long)l1.n);
  double worst = 0;
  int same = 0;
  for (size_t i = 0; i < l1.n && i < l1.cap && i < l2.n; i++) {
    const sc_border *a = &b1[i], *c = &b2[i];
    int k = c->iterate;
    same += a->iterate == k && a->value == c->value &&
            strcmp(a->name, c->name) == 0;
    double dd = c->dd * pre[k], dpa = c->dp[ia] + c->dd * prep[k];
    worst = fmax(worst, fabs(dd - a->dd) / (1 + fabs(a->dd)));
    worst = fmax(worst, fabs(dpa - a->dp[ia]) / (1 + fabs(a->dp[ia])));
  }
  tu_int("borders of the same iterate, name and value", same, (long)l1.n);
  tu_close("borders' derivatives chained by hand (worst relative)", worst, 0,
           1e-12);
  sc_map_free(m);
}

int main(void) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  test_logistic();
  test_fig58();
  test_collapse();
  test_fig512();
  test_errors();
  test_iterate_points();
  return tu_finish();
}
