/* The starts of branches with velocity-weakening friction (numerical
 * flows, default preset): the symmetric model (beta = 1), where swapping
 * the blocks maps an orbit through d to its mirror image through -d, with
 * the same multiplier.  Known answer (alpha 2.8, gamma 0.5, V 0.03, d in
 * [-0.5, 0.5]): seven period-1 orbits, three mirror pairs (d about
 * 0.00885, 0.01613, 0.01979) and d = 0, and three period-2 orbits, one
 * pair and one its own mirror (-0.01426; 0.01426).
 *  - The fixed-point search finds an orbit iff it finds its mirror, with
 *    the same multiplier.
 *  - Multiple shooting from an orbit's point and from its mirror image
 *    both converge, or both fail, to mirror images: Newton asks no more
 *    than the flows' precision (sc_map_solver_accuracy()), as the branch
 *    corrector does; before, one of a pair stopped at the noise floor
 *    with "no convergence in 30 Newton iterations (residual 9.8e-13)". */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "slipcont/slipcont.h"
#include "test_util.h"

static sc_map *vw_map(void) {
  sc_map *m;
  sc_msg msg;
  if (sc_map_alloc("bk2", NULL, &m, &msg)) return NULL;
  sc_map_set_param_by_name(m, "alpha", 2.8, &msg);
  sc_map_set_param_by_name(m, "beta", 1, &msg);
  sc_map_set_param_by_name(m, "v", 0.03, &msg);
  sc_map_set_option(m, "driver", "moving", &msg);
  sc_map_set_option(m, "friction", "velocity-weakening", &msg);
  sc_map_set_param_by_name(m, "gamma", 0.5, &msg);
  return m;
}

/* Mirror images agree to the flows' precision over an orbit, amplified
 * by the orbit's condition (|multiplier - 1| up to ~20 here): MIRROR_D
 * times the precision on points, MIRROR_REL relative on multipliers
 * (their derivatives carry the error of the variational equations). */
#define MIRROR_D 10.0
#define MIRROR_REL 1e-6

/* Whether the orbit set holds the mirror image of orbit o. */
static int has_mirror(const sc_orbit_set *set, const sc_orbit_info *o,
                      double tol) {
  for (size_t j = 0; j < sc_orbit_set_count(set); j++) {
    sc_orbit_info q;
    sc_orbit_set_get(set, j, &q);
    if (q.period != o->period) continue;
    if (fabs(q.multiplier - o->multiplier) >
        MIRROR_REL * fabs(o->multiplier))
      continue;
    for (int r = 0; r < o->period; r++) {
      int all = 1;
      for (int i = 0; i < o->period && all; i++)
        all = fabs(q.d[(i + r) % o->period] + o->d[i]) <= tol;
      if (all) return 1;
    }
  }
  return 0;
}

static void test_fixed_points(sc_map *m, double tol) {
  const size_t want[3] = {0, 7, 3};
  for (int per = 1; per <= 2; per++) {
    sc_fixed_points_spec fs = {.period = per, .from = -0.5, .to = 0.5,
                               .steps = 2000};
    sc_orbit_set *set = NULL;
    sc_msg msg;
    int st = sc_fixed_points_find(m, &fs, &set, &msg);
    if (!tu_true(st == SC_OK, "period %d: fixed points: %s", per,
                 st ? msg.text : "ok"))
      continue;
    char what[96];
    snprintf(what, sizeof what, "period %d: orbits found", per);
    tu_int(what, (long)sc_orbit_set_count(set), (long)want[per]);
    for (size_t i = 0; i < sc_orbit_set_count(set); i++) {
      sc_orbit_info o;
      sc_orbit_set_get(set, i, &o);
      tu_true(has_mirror(set, &o, tol),
              "period %d: the orbit through %.17g (multiplier %.10g) and "
              "its mirror image both found",
              per, o.d[0], o.multiplier);
    }
    sc_orbit_set_free(set);
  }
}

/* Multiple shooting of period `per` from d and from -d. */
static void test_shoot_pair(sc_map *m, int per, double d, double tol) {
  sc_shoot *s = NULL;
  sc_msg msg;
  if (!tu_true(sc_shoot_alloc(m, per, SC_SHOOT_MULTIPLE, NULL, &s, &msg) ==
                   SC_OK,
               "shooting alloc"))
    return;
  sc_shoot_result r[2];
  int st[2];
  char why[2][SC_MSG_LEN];
  for (int k = 0; k < 2; k++) {
    st[k] = sc_shoot_solve(s, k ? -d : d, &r[k], &msg);
    snprintf(why[k], sizeof why[k], "%s", st[k] ? msg.text : "converged");
  }
  sc_shoot_free(s);
  tu_true(st[0] == SC_OK && st[1] == SC_OK,
          "period %d from %.17g: %s; from its mirror image: %s", per, d,
          why[0], why[1]);
  if (st[0] || st[1]) return;
  char what[128];
  snprintf(what, sizeof what, "period %d from +-%.6g: d + d(mirror)", per, d);
  tu_close(what, r[0].d + r[1].d, 0, tol);
  snprintf(what, sizeof what, "period %d from +-%.6g: multipliers", per, d);
  tu_rel(what, r[1].multiplier, r[0].multiplier, MIRROR_REL);
}

int main(void) {
  gsl_set_error_handler_off();
  sc_map *m = vw_map();
  double tol = MIRROR_D * sc_map_precision(m);
  printf("tolerance on mirrored points: %.3g\n", tol);
  test_fixed_points(m, tol);
  /* the period-1 orbits, also as period 2 (the branch's period-2 start
   * that stopped at the noise floor), and the period-2 pair */
  const double p1[] = {0.0088549239058688285, 0.016127957017738715,
                       0.019788450127336921};
  for (size_t i = 0; i < sizeof p1 / sizeof *p1; i++) {
    test_shoot_pair(m, 1, p1[i], tol);
    test_shoot_pair(m, 2, p1[i], tol);
  }
  test_shoot_pair(m, 2, 0.0035770073296531005, tol);
  sc_map_free(m);
  return tu_finish();
}
