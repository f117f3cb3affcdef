/* Sweeps (analysis.h): the grid, period detection, the logistic map's
 * exact periods, thread-count independence, undefined points, seeding;
 * and the reference behaviours of the two-block model (docs/model.md, figs
 * 5.4 and 5.6). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "slipcont/analysis.h"
#include "slipcont/period.h"
#include "test_util.h"

static void test_grid(void) {
  tu_close("grid: first point", sc_grid_point(0.025, 0.015, 400, 0), 0.025, 0);
  tu_close("grid: last point exactly to", sc_grid_point(0.025, 0.015, 400, 399),
           0.015, 0);
  tu_close("grid: middle", sc_grid_point(0, 1, 5, 2), 0.5, 0);
  tu_close("grid: steps = 1 is from", sc_grid_point(2.385, 7, 1, 0), 2.385, 0);
  tu_true(isnan(sc_grid_point(0, 1, 0, 0)), "grid: steps = 0 is NaN");
  tu_true(isnan(sc_grid_point(0, 1, 3, 3)), "grid: i = steps is NaN");
  /* from + (to - from) (i/(steps - 1)) (sc_grid, common.h). */
  tu_close("grid: formula", sc_grid_point(0.1, 0.7, 7, 3),
           0.1 + (0.7 - 0.1) * (3.0 / 6.0), 0);
}

/* One period rule: a sweep's period at each value is the class the
 * chart's detector gives the same orbit (sc_period_find with
 * max_iter = iterations), here across the logistic map's flip at r = 3,
 * where slow convergence made the two disagree before. */
static void test_one_period_rule(void) {
  sc_msg msg;
  sc_map *m = NULL;
  tu_int("logistic map", sc_map_alloc("logistic", NULL, &m, &msg), SC_OK);
  sc_sweep_spec sp = {0};
  sp.param = (size_t)sc_map_param_index(m, "r");
  sp.from = 2.95;
  sp.to = 3.05;
  sp.steps = 41;
  sp.iterations = 600;
  sp.keep = 10;
  sp.d0 = 0.3;
  sp.direction = SC_SWEEP_UP;
  sp.seed = SC_SEED_FIXED;
  sc_sweep *sw = NULL;
  tu_int("sweep alloc", sc_sweep_alloc(m, &sp, &sw, &msg), SC_OK);
  tu_int("sweep run", sc_sweep_run(sw, &msg), SC_OK);
  sc_period *pd = NULL;
  tu_int("detector", sc_period_alloc(SC_SWEEP_PERIOD_MAX,
                                     SC_PERIOD_DEFAULT_CONFIRM,
                                     sc_map_accuracy(m)->period_rtol, &pd,
                                     &msg), SC_OK);
  int agree = 1, p1 = 0, p2 = 0;
  for (size_t i = 0; i < sc_sweep_npoints(sw); i++) {
    sc_sweep_point pt;
    sc_sweep_get_point(sw, i, &pt);
    sc_map_set_param(m, sp.param, pt.p, &msg);
    sc_period_result res;
    sc_period_find(pd, m, sp.d0, sp.iterations, &res, &msg);
    if (res.period != pt.period) {
      agree = 0;
      printf("  r = %.17g: sweep %d, chart %d\n", pt.p, pt.period, res.period);
    }
    p1 += pt.period == 1;
    p2 += pt.period == 2;
  }
  tu_true(agree, "sweep and chart classify every r in [2.95, 3.05] alike");
  tu_true(p1 > 0 && p2 > 0, "both sides of the flip seen (%d period 1, %d "
                            "period 2)", p1, p2);
  sc_period_free(pd);
  sc_sweep_free(sw);
  sc_map_free(m);
}

static void test_period(void) {
  double two[] = {0.3, 0.7, 0.3, 0.7, 0.3, 0.7};
  tu_int("period 2", sc_sweep_period(two, 6, 1e-6, 16), 2);
  double one[] = {0.5, 0.5, 0.5};
  tu_int("constant: period 1", sc_sweep_period(one, 3, 1e-6, 16), 1);
  /* A fixed point still converging: spread 1e-9 relative, far below the
   * tolerance of 1e-6 of the value. */
  double conv[] = {0.6 + 1e-9, 0.6 + 5e-10, 0.6 + 2.5e-10, 0.6 + 1.25e-10};
  tu_int("converging fixed point: period 1", sc_sweep_period(conv, 4, 1e-6, 16),
         1);
  double three[] = {0.1, 0.5, 0.9, 0.1, 0.5, 0.9, 0.1, 0.5, 0.9};
  tu_int("period 3", sc_sweep_period(three, 9, 1e-6, 16), 3);
  tu_int("period 3 but pmax 2: none", sc_sweep_period(three, 9, 1e-6, 2), 0);
  double noisy[] = {0.3, 0.7, 0.3 + 1e-3, 0.7, 0.3, 0.7 - 1e-3};
  tu_int("lag-2 differences 1e-3 of a spread 0.4: none",
         sc_sweep_period(noisy, 6, 1e-6, 16), 0);
  tu_int("same with rtol 1e-2: period 2", sc_sweep_period(noisy, 6, 1e-2, 16),
         2);
  double bad[] = {0.1, NAN};
  tu_int("NaN: -1", sc_sweep_period(bad, 2, 1e-6, 16), -1);
  tu_int("empty: -1", sc_sweep_period(bad, 0, 1e-6, 16), -1);
  /* At least two cycles must be seen: 4 values cannot show period 3. */
  tu_int("too short for period 3", sc_sweep_period(three, 4, 1e-6, 16), 0);
}

/* Period of the logistic map at r from a one-point sweep. */
static int logistic_period(double r) {
  sc_map *m;
  sc_msg msg;
  if (sc_map_alloc("logistic", NULL, &m, &msg)) return -99;
  sc_sweep_spec sp = {0};
  sp.param = 0;
  sp.from = sp.to = r;
  sp.steps = 1;
  sp.iterations = 2000;
  sp.keep = 200;
  sp.d0 = 0.3;
  sp.direction = SC_SWEEP_UP;
  sp.seed = SC_SEED_FIXED;
  sc_sweep *sw;
  int p = -98;
  if (sc_sweep_alloc(m, &sp, &sw, &msg) == SC_OK) {
    sc_sweep_point pt;
    if (sc_sweep_run(sw, &msg) == SC_OK && sc_sweep_get_point(sw, 0, &pt) == 0)
      p = pt.period;
    sc_sweep_free(sw);
  }
  sc_map_free(m);
  return p;
}

static void test_logistic(void) {
  tu_int("logistic r = 2.8: period 1", logistic_period(2.8), 1);
  tu_int("logistic r = 3.2: period 2", logistic_period(3.2), 2);
  tu_int("logistic r = 3.5: period 4", logistic_period(3.5), 4);
  tu_int("logistic r = 3.83: period 3", logistic_period(3.83), 3);
  tu_int("logistic r = 3.9: none (chaos)", logistic_period(3.9), 0);
}

/* A sweep of the logistic map with every option, for the checks below. */
static int sweep(sc_map *m, int direction, int seed, double d0,
                 sc_sweep **out) {
  sc_sweep_spec sp = {0};
  sp.param = 0;
  sp.from = 4;
  sp.to = 2.5;
  sp.steps = 151;
  sp.iterations = 300;
  sp.keep = 50;
  sp.d0 = d0;
  sp.direction = direction;
  sp.seed = seed;
  sc_msg msg;
  int st = sc_sweep_alloc(m, &sp, out, &msg);
  if (st == SC_OK) st = sc_sweep_run(*out, &msg);
  if (st) printf("  sweep: %s\n", msg.text);
  return st;
}

static int same_results(const sc_sweep *a, const sc_sweep *b) {
  if (sc_sweep_npoints(a) != sc_sweep_npoints(b)) return 0;
  for (size_t i = 0; i < sc_sweep_npoints(a); i++) {
    sc_sweep_point p, q;
    sc_sweep_get_point(a, i, &p);
    sc_sweep_get_point(b, i, &q);
    if (p.p != q.p || p.period != q.period || p.nd != q.nd ||
        p.status != q.status || p.direction != q.direction)
      return 0;
    if (p.nd && memcmp(p.d, q.d, (size_t)p.nd * sizeof *p.d) != 0) return 0;
  }
  return 1;
}

static void test_sweep_logistic(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("logistic", NULL, &m, &msg);
  sc_sweep *a = NULL, *b = NULL;
#ifdef _OPENMP
  int nt = omp_get_max_threads();
  omp_set_num_threads(1);
#endif
  tu_int("fixed seed, 1 thread", sweep(m, SC_SWEEP_BOTH, SC_SEED_FIXED, 0.3, &a),
         SC_OK);
#ifdef _OPENMP
  omp_set_num_threads(4);
#endif
  tu_int("fixed seed, 4 threads", sweep(m, SC_SWEEP_BOTH, SC_SEED_FIXED, 0.3, &b),
         SC_OK);
#ifdef _OPENMP
  omp_set_num_threads(nt);
#endif
  if (a && b)
    tu_true(same_results(a, b), "results identical bit for bit for 1 and 4 "
                                "threads");
  sc_sweep_point pt;
  tu_int("both: 2 x steps points", (long)sc_sweep_npoints(a), 302);
  sc_sweep_get_point(a, 0, &pt);
  tu_true(pt.p == 2.5 && pt.direction == SC_SWEEP_UP,
          "up pass starts at the lowest value (%g)", pt.p);
  sc_sweep_get_point(a, 150, &pt);
  tu_true(pt.p == 4 && pt.direction == SC_SWEEP_UP, "up pass ends at 4 (%g)",
          pt.p);
  sc_sweep_get_point(a, 151, &pt);
  tu_true(pt.p == 4 && pt.direction == SC_SWEEP_DOWN,
          "down pass starts at 4 (%g)", pt.p);
  sc_sweep_get_point(a, 301, &pt);
  tu_true(pt.p == 2.5 && pt.direction == SC_SWEEP_DOWN,
          "down pass ends at 2.5 (%g)", pt.p);
  tu_int("caller's map untouched", sc_map_get_param(m, 0) == 2.8, 1);
  sc_sweep_free(a);
  sc_sweep_free(b);

  /* seed = previous: each value starts from the final state of the one
   * before, so the first kept value at point i+1 is f(last of point i)
   * iterated; check the chain on a period-1 stretch directly. */
  tu_int("previous seed", sweep(m, SC_SWEEP_UP, SC_SEED_PREVIOUS, 0.3, &a),
         SC_OK);
  sc_sweep_point p0, p1;
  sc_sweep_get_point(a, 10, &p0);
  sc_sweep_get_point(a, 11, &p1);
  sc_map *c;
  sc_map_clone(m, &c, &msg);
  sc_map_set_param(c, 0, p1.p, &msg);
  double x = p0.d[p0.nd - 1];
  sc_map_value v;
  for (int k = 0; k < 300; k++) {
    sc_map_eval(c, x, 0, &v, &msg);
    x = v.f;
  }
  tu_close("previous: point 11 continues from point 10", p1.d[p1.nd - 1], x, 0);
  sc_map_free(c);
  sc_sweep_free(a);

  /* Undefined points: from x = 1.5 the logistic orbit runs to -inf, so
   * every value is undefined (non-finite), recorded, and the sweep goes
   * on. */
  tu_int("diverging orbits", sweep(m, SC_SWEEP_DOWN, SC_SEED_PREVIOUS, 1.5, &a),
         SC_OK);
  tu_int("every point undefined", (long)sc_sweep_nundefined(a), 151);
  sc_sweep_get_point(a, 0, &pt);
  tu_true(pt.period == SC_SWEEP_UNDEFINED && pt.nd == 0 && !pt.d &&
              pt.status == SC_ENONFINITE && pt.p == 4,
          "undefined point: period -1, no values, status %d", pt.status);
  tu_true(strstr(sc_sweep_undefined_reason(a), "r = 4") != NULL,
          "reason names the parameter: %s", sc_sweep_undefined_reason(a));
  sc_sweep_free(a);

  sc_sweep_spec sp = {0};
  sp.steps = 10;
  sp.iterations = 5;
  sp.keep = 6;
  sp.from = sp.to = 3;
  sp.direction = SC_SWEEP_UP;
  tu_int("keep > iterations refused", sc_sweep_alloc(m, &sp, &a, &msg),
         SC_EINVAL);
  sp.keep = 5;
  sp.to = 4.5;
  tu_int("to outside the range of r refused", sc_sweep_alloc(m, &sp, &a, &msg),
         SC_EINVAL);
  tu_true(strstr(msg.text, "r = 4.5 out of range") != NULL, "message: %s",
          msg.text);
  sp.to = 4;
  sp.steps = 0;
  tu_int("steps = 0 refused", sc_sweep_alloc(m, &sp, &a, &msg), SC_EINVAL);
  sc_map_free(m);
}

/* bk2 ------------------------------------------------------------------ */

static sc_map *bk2(const char *driver, double alpha, double beta, double v) {
  sc_map *m;
  sc_msg msg;
  if (sc_map_alloc("bk2", NULL, &m, &msg)) {
    printf("  bk2: %s\n", msg.text);
    return NULL;
  }
  if (sc_map_set_option(m, "driver", driver, &msg) ||
      sc_map_set_param_by_name(m, "alpha", alpha, &msg) ||
      sc_map_set_param_by_name(m, "beta", beta, &msg) ||
      sc_map_set_param_by_name(m, "phi", 1.25, &msg) ||
      sc_map_set_param_by_name(m, "v", v, &msg)) {
    printf("  bk2: %s\n", msg.text);
    sc_map_free(m);
    return NULL;
  }
  return m;
}

/* Period of the orbit from d0 after n iterates (tail of 100). */
static int orbit_period(sc_map *m, double d0, int n, double *dlast) {
  double tail[100];
  double x = d0;
  sc_map_value v;
  sc_msg msg;
  for (int k = 0; k < n; k++) {
    if (sc_map_eval(m, x, 0, &v, &msg)) {
      printf("  orbit: %s\n", msg.text);
      return -1;
    }
    x = v.f;
    if (k >= n - 100) tail[k - (n - 100)] = x;
  }
  if (dlast) *dlast = x;
  return sc_sweep_period(tail, 100, sc_map_accuracy(m)->period_rtol, 16);
}

static void test_fig54(void) {
  const char *drivers[] = {"moving", "frozen"};
  for (int i = 0; i < 2; i++) {
    sc_map *m = bk2(drivers[i], 3, 1, 0.025);
    if (!m) {
      tu_true(0, "bk2 map for fig 5.4");
      continue;
    }
    char what[96];
    snprintf(what, sizeof what, "fig 5.4 (driver %s): period 2 from d0 = 0.02",
             drivers[i]);
    tu_int(what, orbit_period(m, 0.02, 300, NULL), 2);
    sc_map_free(m);
  }
}

/* The fig 5.6 sweep (driver moving, alpha 2.9, beta 1, phi 1.25): V down
 * from 0.025 to 0.015, 400 values, 350 iterates, 100 kept, d0 0.02, each
 * from the previous. */
static void test_fig56(void) {
  sc_map *m = bk2("moving", 2.9, 1, 0.025);
  if (!m) {
    tu_true(0, "bk2 map for fig 5.6");
    return;
  }
  sc_sweep_spec sp = {0};
  sp.param = (size_t)sc_map_param_index(m, "v");
  sp.from = 0.025;
  sp.to = 0.015;
  sp.steps = 400;
  sp.iterations = 350;
  sp.keep = 100;
  sp.d0 = 0.02;
  sp.direction = SC_SWEEP_DOWN;
  sp.seed = SC_SEED_PREVIOUS;
  sc_sweep *sw;
  sc_msg msg;
  int st = sc_sweep_alloc(m, &sp, &sw, &msg);
  if (st == SC_OK) st = sc_sweep_run(sw, &msg);
  tu_int("fig 5.6 sweep runs", st, SC_OK);
  if (st) {
    printf("  %s\n", msg.text);
    sc_map_free(m);
    return;
  }
  tu_int("fig 5.6: no undefined point", (long)sc_sweep_nundefined(sw), 0);
  sc_sweep_point pt;
  int n2_top = 0, n2_total = 0, n4 = 0, n4_total = 0, nchaos = 0, nchaos_total = 0;
  double d016 = NAN, v016 = NAN;
  for (size_t i = 0; i < sc_sweep_npoints(sw); i++) {
    sc_sweep_get_point(sw, i, &pt);
    if (pt.p >= 0.0235) {
      n2_total++;
      n2_top += pt.period == 2;
    }
    if (pt.p <= 0.0205 && pt.p >= 0.0197) {
      n4_total++;
      n4 += pt.period == 4;
    }
    if (pt.p <= 0.0194 && pt.p >= 0.0175) {
      nchaos_total++;
      nchaos += pt.period == 0;
    }
    if (fabs(pt.p - 0.016) < 1.3e-5 && pt.nd) {
      v016 = pt.p;
      d016 = pt.d[pt.nd - 1];
    }
    if (i == 0) tu_int("period 2 at V = 0.025", pt.period, 2);
  }
  tu_true(n2_top == n2_total && n2_total > 50,
          "period 2 everywhere in [0.0235, 0.025]: %d of %d", n2_top,
          n2_total);
  tu_true(n4 == n4_total,
          "period 4 just below V = 0.0207 (in [0.0197, 0.0205]): %d of %d",
          n4, n4_total);
  /* Chaos with windows: most values below 0.0194 have no period. */
  tu_true(nchaos * 10 >= nchaos_total * 6,
          "chaos below V = 0.0195: %d of %d values in [0.0175, 0.0194] with "
          "no period",
          nchaos, nchaos_total);
  /* Near V = 0.016: a period-2 orbit of single-block slips. */
  if (isfinite(d016)) {
    sc_map_set_param(m, sp.param, v016, &msg);
    sc_map_value v;
    st = sc_map_iterate(m, d016, 4, SC_EVAL_ITINERARY, &v, &msg);
    int single = st == SC_OK;
    for (const char *p = v.itinerary; single && *p; p++)
      single = *p == '1' || *p == '2' || *p == '|';
    tu_true(single, "V = %.6g: itineraries of 4 iterates \"%s\" are single "
                    "block slips only",
            v016, v.itinerary);
    tu_int("V = 0.016: period 2", orbit_period(m, d016, 200, NULL), 2);
  } else {
    tu_true(0, "a kept value near V = 0.016");
  }
  sc_sweep_free(sw);
  sc_map_free(m);
}

int main(void) {
  test_grid();
  test_period();
  test_one_period_rule();
  test_logistic();
  test_sweep_logistic();
  test_fig54();
  test_fig56();
  return tu_finish();
}
