/* Period charts: the grid, refusals of bad charts, known classes on a
 * two-parameter logistic map, bit-identical results for 1 and 2 threads
 * and for rows divided among calls (as MPI ranks divide them), neighbour
 * seeding on the bistable cubic map, and cancellation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/chart.h"
#include "test_util.h"

/* x -> (r + e) x (1 - x), undefined (SC_EUNDEF) where r + e > 4: the
 * orbit would leave [0, 1].  Two parameters with the logistic's known
 * periods along r + e. */
typedef struct {
  double r, e;
} l2_inst;

static const sc_param_info l2_params[] = {
    {"r", 3, 0, 5, 1, 0, "growth rate", NULL, NULL},
    {"e", 0, -1, 1, 0, 0, "shift of the growth rate", NULL, NULL},
};

static int l2_setup(void *inst, const double *p, const int *opt,
                    const sc_accuracy *acc, sc_msg *msg) {
  (void)opt, (void)acc, (void)msg;
  l2_inst *l = inst;
  l->r = p[0];
  l->e = p[1];
  return SC_OK;
}

static int l2_eval(void *inst, double x, unsigned flags, sc_map_value *out,
                   sc_msg *msg) {
  (void)flags;
  const l2_inst *l = inst;
  double g = l->r + l->e;
  if (g > 4)
    return sc_fail(msg, SC_EUNDEF, "l2: r + e = %g > 4 leaves [0, 1]", g);
  out->f = g * x * (1 - x);
  return SC_OK;
}

static const sc_model_type l2_type = {
    .name = "l2",
    .doc = "logistic map with growth rate r + e",
    .state_name = "x",
    .nparam = 2,
    .params = l2_params,
    .inst_size = sizeof(l2_inst),
    .setup = l2_setup,
    .eval = l2_eval,
};

static sc_chart_spec l2_spec(void) {
  sc_chart_spec s;
  sc_chart_spec_default(&s);
  s.x = "r";
  s.x_from = 2.8;
  s.x_to = 4.2;
  s.x_steps = 29; /* r = 2.8, 2.85, ..., 4.2 */
  s.y = "e";
  s.y_from = -0.01;
  s.y_to = 0.01;
  s.y_steps = 5;
  s.d0 = 0.2385;
  s.transient = 5000;
  return s;
}

static void grid_and_checks(void) {
  sc_msg msg;
  sc_map *m = NULL;
  sc_map_alloc_type(&l2_type, NULL, &m, &msg);
  sc_chart_spec s = l2_spec();
  tu_int("good chart passes", sc_chart_check(m, &s, &msg), SC_OK);
  tu_close("x_0 = from", sc_chart_x(&s, 0), 2.8, 0);
  tu_close("x_last = to exactly", sc_chart_x(&s, 28), 4.2, 0);
  tu_close("x_2 = from + (to - from) 2/28", sc_chart_x(&s, 2),
           2.8 + (4.2 - 2.8) * (2.0 / 28), 0);
  tu_close("y_last = to exactly", sc_chart_y(&s, 4), 0.01, 0);
  /* A log x axis: equal ratios, the ends exact. */
  sc_chart_spec g = s;
  g.x_scale = SC_GRID_LOG;
  tu_int("log x chart passes", sc_chart_check(m, &g, &msg), SC_OK);
  tu_close("log x_0 = from", sc_chart_x(&g, 0), 2.8, 0);
  tu_close("log x_last = to", sc_chart_x(&g, 28), 4.2, 0);
  tu_rel("log x_14 = sqrt(from to)", sc_chart_x(&g, 14), sqrt(2.8 * 4.2),
         1e-15);
  tu_rel("log: equal ratios", sc_chart_x(&g, 2) / sc_chart_x(&g, 1),
         sc_chart_x(&g, 1) / sc_chart_x(&g, 0), 1e-15);
  g.x_scale = 7;
  tu_int("unknown scale refused", sc_chart_check(m, &g, &msg), SC_EINVAL);

  sc_chart_spec t;
#define REFUSE(stmt, needle)                                              \
  do {                                                                    \
    t = l2_spec();                                                        \
    stmt;                                                                 \
    int st_ = sc_chart_check(m, &t, &msg);                                \
    tu_true(st_ == SC_EINVAL && strstr(msg.text, needle) != NULL,         \
            "refused (%s): %s -> %s", #stmt, sc_strerror(st_), msg.text); \
  } while (0)
  REFUSE(t.x_steps = 0, "x-steps = 0");
  REFUSE(t.y_steps = -3, "y-steps = -3");
  REFUSE(t.x_steps = 1, "x-steps = 1");
  REFUSE(t.y = "r", "both 'r'");
  REFUSE(t.x = "gamma", "'gamma' is not a parameter of model l2");
  REFUSE(t.y = NULL, "y is missing");
  REFUSE((t.x_steps = 20000, t.y_steps = 20000), "grid points");
  REFUSE(t.x_steps = 200000000, "x-steps = 200000000");
  REFUSE(t.x_from = -1, "x-from: r = -1 out of range");
  REFUSE(t.y_to = 1.5, "y-to: e = 1.5 out of range");
  REFUSE(t.transient = 0, "transient = 0");
  REFUSE(t.max_period = 0, "max-period = 0");
  REFUSE(t.max_period = SC_PERIOD_MAX + 1, "max-period");
  REFUSE(t.d0 = NAN, "d0");
  REFUSE(t.seed = 7, "seed = 7");
#undef REFUSE
  sc_chart_point pt[29];
  tu_int("rows outside the grid refused",
         sc_chart_rows(m, &s, 4, 2, 1, 1, NULL, NULL, pt, &msg), SC_EINVAL);
  tu_int("stride 0 refused",
         sc_chart_rows(m, &s, 0, 1, 0, 1, NULL, NULL, pt, &msg), SC_EINVAL);
  sc_map_free(m);
}

/* Period class of logistic growth rate g (the test_period cases). */
static int expected_class(double g) {
  if (g > 4) return SC_PERIOD_UNDEFINED;
  if (g < 2.99) return 1;
  if (g > 3.01 && g < 3.44) return 2;
  if (g > 3.46 && g < 3.54) return 4;
  if (g > 3.832 && g < 3.84) return 3;
  return -2; /* not asserted: near a bifurcation or in the cascade */
}

static void classes_and_threads(int seed) {
  sc_msg msg;
  sc_map *m = NULL;
  sc_map_alloc_type(&l2_type, NULL, &m, &msg);
  sc_chart_spec s = l2_spec();
  s.seed = seed;
  size_t n = (size_t)(s.x_steps * s.y_steps);
  sc_chart_point *a = calloc(n, sizeof *a), *b = calloc(n, sizeof *b),
                 *c = calloc(n, sizeof *c);
  const char *sn = seed ? "neighbour" : "fixed";
  int st = sc_chart_rows(m, &s, 0, s.y_steps, 1, 1, NULL, NULL, a, &msg);
  tu_int("1 thread: status", st, SC_OK);
  int checked = 0, wrong = 0;
  for (long j = 0; j < s.y_steps; j++)
    for (long i = 0; i < s.x_steps; i++) {
      double g = sc_chart_x(&s, i) + sc_chart_y(&s, j);
      int want = expected_class(g);
      int got = a[j * s.x_steps + i].period;
      if (want == -2) continue;
      checked++;
      if (got != want) {
        wrong++;
        printf("  r + e = %.17g: period %d, expected %d\n", g, got, want);
      }
    }
  tu_true(wrong == 0 && checked > 40, "%s: %d points of known class, %d wrong",
          sn, checked, wrong);
  /* Chaos at r + e = 3.7 (row e = 0, column r = 3.7). */
  tu_int("r = 3.7, e = 0: high", a[2 * s.x_steps + 18].period,
         SC_PERIOD_HIGH);
  tu_int("r = 4.2: undefined", a[2 * s.x_steps + 28].period,
         SC_PERIOD_UNDEFINED);
  tu_int("undefined at the first iterate", a[2 * s.x_steps + 28].iterations,
         1);

  st = sc_chart_rows(m, &s, 0, s.y_steps, 1, 2, NULL, NULL, b, &msg);
  tu_int("2 threads: status", st, SC_OK);
  tu_true(memcmp(a, b, n * sizeof *a) == 0,
          "%s: 1 and 2 threads give byte-identical results", sn);
  /* Rows divided as 2 MPI ranks divide them: even rows, then odd ones. */
  long ne = (s.y_steps + 1) / 2, no = s.y_steps / 2;
  sc_chart_point *even = calloc((size_t)(ne * s.x_steps), sizeof *even);
  sc_chart_point *odd = calloc((size_t)(no * s.x_steps), sizeof *odd);
  sc_chart_rows(m, &s, 0, ne, 2, 2, NULL, NULL, even, &msg);
  sc_chart_rows(m, &s, 1, no, 2, 1, NULL, NULL, odd, &msg);
  for (long j = 0; j < s.y_steps; j++)
    memcpy(c + j * s.x_steps,
           (j % 2 ? odd + (j / 2) * s.x_steps : even + (j / 2) * s.x_steps),
           (size_t)s.x_steps * sizeof *c);
  tu_true(memcmp(a, c, n * sizeof *a) == 0,
          "%s: rows split into two strided calls give byte-identical "
          "results",
          sn);
  free(even);
  free(odd);
  free(a);
  free(b);
  free(c);
  sc_map_free(m);
}

/* Cubic map x -> x + mu1 + mu2 x - x^3 with mu2 = 0.5: two stable fixed
 * points +-sqrt(mu2) at mu1 = 0, the lower one lost in a fold at
 * mu1 = 2 (mu2/3)^(3/2) = 0.136.  Sweeping mu1 down from 0.2 with
 * neighbour seeding stays on the upper branch; each point from d0 = -0.9
 * lands on the lower one wherever it exists. */
static void neighbour_hysteresis(void) {
  sc_msg msg;
  sc_map *m = NULL;
  sc_map_alloc("cubic", NULL, &m, &msg);
  sc_chart_spec s;
  sc_chart_spec_default(&s);
  s.x = "mu1";
  s.x_from = 0.2;
  s.x_to = -0.05;
  s.x_steps = 15;
  s.y = "mu2";
  s.y_from = 0.5;
  s.y_to = 0.6;
  s.y_steps = 3;
  s.d0 = -0.9;
  sc_chart_point fixed[45], neigh[45];
  s.seed = SC_CHART_SEED_FIXED;
  tu_int("cubic fixed", sc_chart_rows(m, &s, 0, 3, 1, 2, NULL, NULL, fixed,
                                      &msg), SC_OK);
  s.seed = SC_CHART_SEED_NEIGHBOUR;
  tu_int("cubic neighbour", sc_chart_rows(m, &s, 0, 3, 1, 2, NULL, NULL,
                                          neigh, &msg), SC_OK);
  int all_period1 = 1, upper = 1;
  for (int k = 0; k < 45; k++) {
    if (fixed[k].period != 1 || neigh[k].period != 1)
      printf("  mu1 = %g, mu2 = %g: periods %d (fixed), %d (neighbour)\n",
             sc_chart_x(&s, k % 15), sc_chart_y(&s, k / 15), fixed[k].period,
             neigh[k].period);
    all_period1 &= fixed[k].period == 1 && neigh[k].period == 1;
    upper &= neigh[k].d > 0;
  }
  tu_true(all_period1, "every point settles on a fixed point");
  tu_true(upper, "neighbour seeding follows the upper branch to mu1 < 0");
  tu_true(fixed[14].d < 0 && neigh[14].d > 0,
          "at mu1 = -0.05, mu2 = 0.5: fixed seed %.6g (lower), neighbour "
          "%.6g (upper)",
          fixed[14].d, neigh[14].d);
  tu_true(memcmp(&fixed[0], &neigh[0], sizeof fixed[0]) == 0,
          "first point of a row is the same with both seeds");
  sc_map_free(m);
}

/* Cancel from the progress callback after 10 points. */
static int cancel_after_10(void *ctx, long done) {
  *(long *)ctx = done;
  return done >= 10;
}

static void cancel(void) {
  sc_msg msg;
  sc_map *m = NULL;
  sc_map_alloc_type(&l2_type, NULL, &m, &msg);
  sc_chart_spec s = l2_spec();
  sc_chart_point pt[29 * 5];
  long seen = 0;
  int st = sc_chart_rows(m, &s, 0, 5, 1, 1, cancel_after_10, &seen, pt, &msg);
  tu_int("cancelled: SC_ECALLBACK", st, SC_ECALLBACK);
  tu_int("callback saw 10 points", seen, 10);
  sc_map_free(m);
}

/* Charts of two-dimensional maps: the class of known points, and the
 * same results for 1 and 2 threads and both seeds.  ghenon with R = -1
 * has its fixed point x = y = s, (1 - R) s^2 + (1 + beta) s = alpha, with
 * Jacobian determinant beta - R s; at beta = 0.9 the determinant is 1 at
 * s = 0.1, alpha = 0.21 (a supercritical Neimark-Sacker point: below it
 * the fixed point attracts, above it an invariant circle does).  henon at
 * a = 1.4, b = 0.3 is the classic chaotic attractor. */
static void two_dimensional(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("ghenon", NULL, &m, &msg);
  sc_map_set_param_by_name(m, "R", -1, &msg);
  sc_chart_spec s;
  sc_chart_spec_default(&s);
  const double x0[2] = {0.1, 0.1};
  s.x = "alpha", s.x_from = 0.05, s.x_to = 0.3, s.x_steps = 3;
  s.y = "beta", s.y_from = 0.9, s.y_to = 0.95, s.y_steps = 2;
  s.x0 = x0;
  s.transient = 3000;
  sc_chart_point a[6], b[6];
  tu_int("ghenon chart", sc_chart_rows(m, &s, 0, 2, 1, 1, NULL, NULL, a, &msg),
         SC_OK);
  tu_int("alpha = 0.05, beta = 0.9: the fixed point", a[0].period, 1);
  /* 2 s^2 + 1.9 s - 0.05 = 0; the orbit settles to the period rule's
   * tolerance (period-rtol 1e-6 of its extent, about 0.1) */
  tu_true(fabs(a[0].d - (-1.9 + sqrt(1.9 * 1.9 + 8 * 0.05)) / 4) < 1e-7,
          "at x = s = %.12g", a[0].d);
  tu_int("alpha = 0.3, beta = 0.9: an invariant circle", a[2].period,
         SC_PERIOD_CIRCLE);
  for (int seed = 0; seed < 2; seed++) {
    s.seed = seed ? SC_CHART_SEED_NEIGHBOUR : SC_CHART_SEED_FIXED;
    sc_chart_rows(m, &s, 0, 2, 1, 1, NULL, NULL, a, &msg);
    sc_chart_rows(m, &s, 0, 2, 1, 2, NULL, NULL, b, &msg);
    tu_true(memcmp(a, b, sizeof a) == 0, "seed %d: 1 and 2 threads agree bit "
            "for bit", seed);
  }
  sc_map_free(m);
  sc_map_alloc("henon", NULL, &m, &msg);
  sc_chart_spec_default(&s);
  s.x = "a", s.x_from = 1.4, s.x_to = 1.45, s.x_steps = 2;
  s.y = "b", s.y_from = 0.3, s.y_to = 0.31, s.y_steps = 2;
  tu_int("henon chart", sc_chart_rows(m, &s, 0, 1, 1, 1, NULL, NULL, a, &msg),
         SC_OK);
  tu_int("henon a = 1.4, b = 0.3: chaos (high)", a[0].period, SC_PERIOD_HIGH);
  double bad[2] = {0.1, NAN};
  s.x0 = bad;
  tu_int("a non-finite component refused", sc_chart_check(m, &s, &msg),
         SC_EINVAL);
  tu_true(strstr(msg.text, "d0 component 2") != NULL, "message: %s", msg.text);
  sc_map_free(m);
}

int main(void) {
  two_dimensional();
  grid_and_checks();
  classes_and_threads(SC_CHART_SEED_FIXED);
  classes_and_threads(SC_CHART_SEED_NEIGHBOUR);
  neighbour_hysteresis();
  cancel();
  return tu_finish();
}
