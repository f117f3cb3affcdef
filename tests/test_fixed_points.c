/* All period-m orbits in an interval (sc_fixed_points_find, branch.h).
 *
 * - Logistic map: at r = 3.2 one 2-cycle, at
 *   (r + 1 -+ sqrt((r + 1)(r - 3)))/(2r); the fixed points 0 and 1 - 1/r
 *   are roots of f^2(x) - x too and are not reported as 2-cycles.  At
 *   r = 3.835 (inside the period-3 window, past the fold at
 *   1 + 2 sqrt 2) exactly two 3-cycles, one stable, one unstable, and the
 *   products of their slopes against a long double check.  At r = 3.9 the
 *   count of period-4 orbits is known: (2^4 - 2^2)/4 = 3 (every orbit of
 *   the full shift exists for r = 4; at 3.9 fewer, but at least the
 *   ones found by multiple shooting in test_shooting).
 * - bk2 with the driver frozen, beta = 2.5, alpha = 3.3 (inside the
 *   period-6 window of fig 5.8): the stable period-6 orbit found by the
 *   search agrees with brute-force iteration.
 * - A family of neutral orbits (driver moving, alpha = 2.9, beta = 1,
 *   V = 0.0165) reported as a family with a d-interval.
 *
 * Tolerances: roots are polished to the shooting tolerances (steps within
 * 1e-13 (1 + |d|)) and are exact to rounding; 1e-14 for the logistic map
 * where the answer is known in closed form. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/orbits.h"
#include "test_util.h"

static void test_logistic_period2(void) {
  printf("--- logistic r = 3.2, period 2\n");
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("logistic", NULL, &m, &msg);
  double r = 3.2;
  sc_map_set_param_by_name(m, "r", r, &msg);
  sc_fixed_points_spec sp = {.period = 2, .from = 0, .to = 1, .steps = 101};
  sc_orbit_set *set;
  int st = sc_fixed_points_find(m, &sp, &set, &msg);
  tu_int("search: SC_OK", st, SC_OK);
  tu_int("one 2-cycle", (long)sc_orbit_set_count(set), 1);
  sc_orbit_info o;
  sc_orbit_set_get(set, 0, &o);
  double lo = (r + 1 - sqrt((r + 1) * (r - 3))) / (2 * r);
  double hi = (r + 1 + sqrt((r + 1) * (r - 3))) / (2 * r);
  tu_int("period", o.period, 2);
  tu_close("low point (r+1-sqrt((r+1)(r-3)))/(2r)", o.d[0], lo, 1e-14);
  tu_close("high point (r+1+sqrt((r+1)(r-3)))/(2r)", o.d[1], hi, 1e-14);
  tu_close("multiplier 4 + 2r - r^2", o.multiplier, 4 + 2 * r - r * r,
           1e-13);
  tu_int("stable", o.stable, 1);
  tu_true(sc_orbit_set_nlower(set) >= 2,
          "fixed points 0 and 1 - 1/r skipped as lower periods (%zu)",
          sc_orbit_set_nlower(set));
  printf("  itinerary %s, pieces %zu\n", o.itinerary,
         sc_orbit_set_npieces(set));
  sc_orbit_set_free(set);
  sc_map_free(m);
}

static void test_logistic_period3(void) {
  printf("--- logistic r = 3.835, period 3\n");
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("logistic", NULL, &m, &msg);
  double r = 3.835;
  sc_map_set_param_by_name(m, "r", r, &msg);
  sc_fixed_points_spec sp = {.period = 3, .from = 0, .to = 1, .steps = 1001};
  sc_orbit_set *set;
  int st = sc_fixed_points_find(m, &sp, &set, &msg);
  tu_int("search: SC_OK", st, SC_OK);
  tu_int("exactly two 3-cycles", (long)sc_orbit_set_count(set), 2);
  int nstable = 0;
  for (size_t i = 0; i < sc_orbit_set_count(set); i++) {
    sc_orbit_info o;
    sc_orbit_set_get(set, i, &o);
    long double y = o.d[0], mult = 1;
    for (int k = 0; k < 3; k++) {
      mult *= r * (1 - 2 * y);
      y = r * y * (1 - y);
    }
    printf("  3-cycle %zu: %.17g %.17g %.17g multiplier %.17g\n", i, o.d[0],
           o.d[1], o.d[2], o.multiplier);
    tu_close("f^3(d) - d in long double", (double)(y - o.d[0]), 0, 1e-14);
    tu_rel("multiplier against long double", o.multiplier, (double)mult,
           1e-12);
    tu_true(o.d[0] < o.d[1] || o.d[0] < o.d[2],
            "points listed from the smallest");
    nstable += o.stable;
  }
  tu_int("one stable, one unstable", nstable, 1);
  sc_orbit_set_free(set);
  sc_map_free(m);
}

static void test_bk2_period6(void) {
  printf("--- bk2 frozen, beta = 2.5, alpha = 3.3, period 6\n");
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("bk2", NULL, &m, &msg);
  sc_map_set_option(m, "driver", "frozen", &msg);
  sc_map_set_param_by_name(m, "alpha", 3.3, &msg);
  sc_map_set_param_by_name(m, "beta", 2.5, &msg);
  sc_map_set_param_by_name(m, "phi", 1.25, &msg);
  double x = 0;
  sc_map_value v;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (int k = 0; k < 600; k++) {
    sc_map_eval(m, x, SC_EVAL_VALUE, &v, &msg);
    x = v.f;
    if (k >= 594) lo = fmin(lo, x), hi = fmax(hi, x);
  }
  double att_min = lo;
  sc_fixed_points_spec sp = {.period = 6, .from = lo - 0.01, .to = hi + 0.01,
                             .steps = 400};
  sc_orbit_set *set;
  int st = sc_fixed_points_find(m, &sp, &set, &msg);
  tu_int("search: SC_OK", st, SC_OK);
  int found = 0;
  for (size_t i = 0; i < sc_orbit_set_count(set); i++) {
    sc_orbit_info o;
    sc_orbit_set_get(set, i, &o);
    printf("  orbit %zu: period %d multiplier %.6g stable %d d0 %.17g %s\n",
           i, o.period, o.multiplier, o.stable, o.d[0], o.itinerary);
    if (o.stable && fabs(o.d[0] - att_min) < 1e-9) found = 1;
  }
  tu_true(found, "the stable period-6 orbit of brute force (smallest point "
                 "%.17g) is found",
          att_min);
  printf("  pieces %zu, lower periods %zu, undefined %zu, evaluations %lu\n",
         sc_orbit_set_npieces(set), sc_orbit_set_nlower(set),
         sc_orbit_set_nundefined(set), sc_map_nevals(m));
  sc_orbit_set_free(set);
  sc_map_free(m);
}

static void test_family(void) {
  printf("--- neutral family, driver moving, beta = 1, V = 0.0165\n");
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("bk2", NULL, &m, &msg);
  sc_map_set_option(m, "driver", "moving", &msg);
  sc_map_set_param_by_name(m, "alpha", 2.9, &msg);
  sc_map_set_param_by_name(m, "beta", 1, &msg);
  sc_map_set_param_by_name(m, "phi", 1.25, &msg);
  sc_map_set_param_by_name(m, "v", 0.0165, &msg);
  double x = 0.02;
  sc_map_value v;
  for (int k = 0; k < 2000; k++) {
    sc_map_eval(m, x, SC_EVAL_VALUE, &v, &msg);
    x = v.f;
  }
  double a = fabs(x);
  sc_fixed_points_spec sp = {.period = 2, .from = -a - 0.01, .to = a + 0.01,
                             .steps = 200};
  sc_orbit_set *set;
  int st = sc_fixed_points_find(m, &sp, &set, &msg);
  tu_int("search: SC_OK", st, SC_OK);
  int fam = 0;
  for (size_t i = 0; i < sc_orbit_set_count(set); i++) {
    sc_orbit_info o;
    sc_orbit_set_get(set, i, &o);
    printf("  orbit %zu: neutral %d [%.17g, %.17g] multiplier %g %s\n", i,
           o.neutral, o.lo, o.hi, o.multiplier, o.itinerary);
    if (o.neutral) {
      fam++;
      tu_true(o.lo < o.hi, "family interval has a length (%.3g)",
              o.hi - o.lo);
      sc_map_eval(m, x, SC_EVAL_VALUE, &v, &msg);
      tu_true((x >= o.lo && x <= o.hi) || (v.f >= o.lo && v.f <= o.hi),
              "the attractor's orbit {%.6g, %.6g} is on the family", x, v.f);
      tu_close("family multiplier exactly 1", o.multiplier, 1, 0);
    }
  }
  tu_int("one family (reported once, not once per shift)", fam, 1);
  sc_orbit_set_free(set);
  sc_map_free(m);
}

static void test_errors(void) {
  printf("--- error paths\n");
  sc_map *m;
  sc_msg msg = {""};
  sc_map_alloc("logistic", NULL, &m, &msg);
  sc_orbit_set *set = (sc_orbit_set *)&msg;
  sc_fixed_points_spec sp = {.period = 2, .from = 1, .to = 0, .steps = 10};
  tu_int("from > to: SC_EINVAL", sc_fixed_points_find(m, &sp, &set, &msg),
         SC_EINVAL);
  tu_true(set == NULL, "no set on failure");
  printf("  message: %s\n", msg.text);
  sp = (sc_fixed_points_spec){.period = 0, .from = 0, .to = 1, .steps = 10};
  tu_int("period 0: SC_EINVAL", sc_fixed_points_find(m, &sp, &set, &msg),
         SC_EINVAL);
  sp = (sc_fixed_points_spec){.period = 1, .from = 0, .to = 1, .steps = 1};
  tu_int("steps 1: SC_EINVAL", sc_fixed_points_find(m, &sp, &set, &msg),
         SC_EINVAL);
  sc_orbit_set_free(NULL);
  sc_map_free(m);
}

int main(void) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  test_logistic_period2();
  test_logistic_period3();
  test_bk2_period6();
  test_family();
  test_errors();
  return tu_finish();
}
