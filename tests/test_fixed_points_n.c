/* The search for periodic orbits of n-dimensional maps without a start
 * guess (sc_fixed_points_n_find): the Henon map at a = 1.4, b = 0.3 against
 * closed forms (periods 1 and 2) and against an independent brute-force
 * count (periods 1..6); the generalized Henon map's fixed points and
 * multipliers against their closed forms; a start alone; single and
 * multiple shooting alike; the refusals. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/orbits.h"
#include "test_util.h"

/* Newton converges to the solver accuracy (1e-12 and below); the closed
 * forms are a few ulps off: 1e-12 bounds both. */
static const double TOL = 1e-12;

#define MAXP 6
static const double FROM[2] = {-1.5, -0.5}, TO[2] = {1.5, 0.5};

static sc_map *henon(void) {
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("henon", NULL, &m, &msg);
  sc_map_set_param_by_name(m, "a", 1.4, &msg);
  sc_map_set_param_by_name(m, "b", 0.3, &msg);
  return m;
}

static sc_orbitn_set *search(sc_map *m, int lo, int hi, sc_shoot_method meth) {
  sc_fixed_points_n_spec sp = {.period_lo = lo, .period_hi = hi,
                               .from = FROM, .to = TO, .steps = 21,
                               .attractor = 300, .transient = 1000,
                               .method = meth};
  sc_orbitn_set *set = NULL;
  sc_msg msg;
  int st = sc_fixed_points_n_find(m, &sp, &set, &msg);
  tu_true(st == SC_OK, "search %d..%d: %s", lo, hi, st ? msg.text : "");
  return set;
}

static int count_period(const sc_orbitn_set *set, int p) {
  int c = 0;
  sc_orbitn_info o;
  for (size_t i = 0; set && i < sc_orbitn_set_count(set); i++) {
    sc_orbitn_set_get(set, i, &o);
    c += o.period == p;
  }
  return c;
}

/* Periods 1 and 2 exactly: the fixed points
 * x = (-(1 - b) +- sqrt((1 - b)^2 + 4 a)) / (2 a), y = b x, and the
 * period-2 orbit x = ((1 - b) +- sqrt(4 a - 3 (1 - b)^2)) / (2 a) with
 * y1 = b x2, y2 = b x1 (a > 3 (1 - b)^2 / 4), listed from the
 * lexicographically smallest point. */
static void closed_forms(const sc_orbitn_set *set) {
  const double a = 1.4, b = 0.3;
  double r1 = sqrt((1 - b) * (1 - b) + 4 * a);
  double fx[2] = {(-(1 - b) - r1) / (2 * a), (-(1 - b) + r1) / (2 * a)};
  double r2 = sqrt(4 * a - 3 * (1 - b) * (1 - b));
  double x1 = ((1 - b) - r2) / (2 * a), x2 = ((1 - b) + r2) / (2 * a);
  double p2[4] = {x1, b * x2, x2, b * x1};
  tu_int("henon: fixed points", count_period(set, 1), 2);
  tu_int("henon: period-2 orbits", count_period(set, 2), 1);
  sc_orbitn_info o;
  int k = 0;
  for (size_t i = 0; i < sc_orbitn_set_count(set); i++) {
    sc_orbitn_set_get(set, i, &o);
    if (o.period == 1 && k < 2) {
      tu_close("henon fixed point x", o.x[0], fx[k], TOL);
      tu_close("henon fixed point y", o.x[1], b * fx[k], TOL);
      /* trace -2 a x, determinant -b */
      double t = -2 * a * fx[k], d = -b, s = sqrt(t * t - 4 * d);
      double big = fabs(t + s) > fabs(t - s) ? 0.5 * (t + s) : 0.5 * (t - s);
      tu_close("henon fixed point: leading multiplier", o.multiplier, big,
               TOL);
      tu_close("henon fixed point: product of multipliers",
               o.mult_re[0] * o.mult_re[1], d, TOL);
      tu_true(o.residual <= TOL, "fixed point residual %g", o.residual);
      k++;
    }
    if (o.period == 2)
      for (int c = 0; c < 4; c++)
        tu_close("henon period-2 orbit point", o.x[c], p2[c], TOL);
  }
}

/* Brute force, independent of the search: plain Newton on f^p(x) - x
 * (no deflation, no line search) from 4000 random points of the box and
 * 4000 points of a long trajectory on the attractor, every converged
 * orbit kept once at its minimal period if a point lies in the box.  The
 * trajectory comes arbitrarily close to every periodic orbit embedded in
 * the chaotic attractor (they are dense in it), so Newton from its points
 * meets each of them; the random starts reach those off the attractor
 * (the fixed point near x = -1.13).  Counts per period of the Henon
 * attractor published from exhaustive searches are 1, 1, 0, 1, 0, 2 for
 * periods 1..6 plus the fixed point off the attractor: 2, 1, 0, 1, 0, 2. */
#define BF_STARTS 4000
#define BF_MAXORB 64

typedef struct {
  int n[MAXP + 1];
  double x[MAXP + 1][BF_MAXORB][2 * MAXP];
} bf_set;

static int newton(sc_map *m, sc_mapn_value *v, double *x, int p) {
  for (int it = 0; it < 60; it++) {
    if (sc_map_iterate_n(m, x, p, SC_EVAL_DERIV, v, NULL)) return 0;
    double F0 = v->f[0] - x[0], F1 = v->f[1] - x[1];
    double A = v->J[0] - 1, B = v->J[1], C = v->J[2], D = v->J[3] - 1;
    double det = A * D - B * C;
    if (det == 0 || !isfinite(det)) return 0;
    double d0 = -(D * F0 - B * F1) / det, d1 = -(-C * F0 + A * F1) / det;
    x[0] += d0;
    x[1] += d1;
    if (fabs(x[0]) > 10 || fabs(x[1]) > 10) return 0;
    if (fabs(d0) + fabs(d1) < 1e-13) return 1;
  }
  return 0;
}

static void bf_add(bf_set *bf, sc_map *m, sc_mapn_value *v, const double *x0,
                   int p) {
  double pts[2 * MAXP];
  memcpy(pts, x0, 2 * sizeof *x0);
  for (int k = 1; k < p; k++) {
    sc_map_eval_n(m, pts + 2 * (k - 1), SC_EVAL_VALUE, v, NULL);
    memcpy(pts + 2 * k, v->f, 2 * sizeof *pts);
  }
  /* minimal period and equality: 1e-8, far above Newton's 1e-13 and far
   * below the distance between distinct orbits of low period */
  int q = sc_orbit_minimal_period_n(pts, p, 2, 1e-8);
  if (q != p) return;
  int inside = 0;
  for (int k = 0; k < p; k++)
    inside |= pts[2 * k] >= FROM[0] && pts[2 * k] <= TO[0] &&
              pts[2 * k + 1] >= FROM[1] && pts[2 * k + 1] <= TO[1];
  if (!inside) return;
  for (int i = 0; i < bf->n[p]; i++)
    if (sc_orbit_same_n(bf->x[p][i], pts, p, 2, 1e-8)) return;
  if (bf->n[p] < BF_MAXORB) memcpy(bf->x[p][bf->n[p]++], pts, sizeof pts);
}

static void brute_force(sc_map *m, bf_set *bf) {
  sc_mapn_value *v;
  sc_msg msg;
  sc_mapn_value_alloc(m, SC_EVAL_DERIV, &v, &msg);
  memset(bf, 0, sizeof *bf);
  unsigned long seed = 2385;
  double traj[2] = {0.1, 0.1};
  for (int i = 0; i < 1000; i++) {
    sc_map_eval_n(m, traj, SC_EVAL_VALUE, v, NULL);
    memcpy(traj, v->f, sizeof traj);
  }
  for (int s = 0; s < 2 * BF_STARTS; s++) {
    double x0[2];
    if (s < BF_STARTS) { /* a linear congruential generator, reproducible */
      for (int c = 0; c < 2; c++) {
        seed = seed * 6364136223846793005UL + 1442695040888963407UL;
        double u = (double)(seed >> 11) / 9007199254740992.0;
        x0[c] = FROM[c] + u * (TO[c] - FROM[c]);
      }
    } else {
      sc_map_eval_n(m, traj, SC_EVAL_VALUE, v, NULL);
      memcpy(traj, v->f, sizeof traj);
      memcpy(x0, traj, sizeof x0);
    }
    for (int p = 1; p <= MAXP; p++) {
      double x[2] = {x0[0], x0[1]};
      if (newton(m, v, x, p)) bf_add(bf, m, v, x, p);
    }
  }
  sc_mapn_value_free(v);
}

static void counts(sc_map *m, const sc_orbitn_set *set) {
  static bf_set bf;
  brute_force(m, &bf);
  static const int published[MAXP + 1] = {0, 2, 1, 0, 1, 0, 2};
  for (int p = 1; p <= MAXP; p++) {
    char w[96];
    snprintf(w, sizeof w, "henon period %d: brute force vs published", p);
    tu_int(w, bf.n[p], published[p]);
    snprintf(w, sizeof w, "henon period %d: search vs brute force", p);
    tu_int(w, count_period(set, p), bf.n[p]);
  }
  /* every orbit of the search is one of the brute force's */
  sc_orbitn_info o;
  for (size_t i = 0; i < sc_orbitn_set_count(set); i++) {
    sc_orbitn_set_get(set, i, &o);
    int found = 0;
    for (int k = 0; k < bf.n[o.period]; k++)
      found |= sc_orbit_same_n(bf.x[o.period][k], o.x, o.period, 2, 1e-8);
    tu_true(found, "search orbit %zu (period %d) is a brute-force orbit", i,
            o.period);
  }
}

/* ghenon: x = y = s, (1 - R) s^2 + (1 + beta) s - alpha = 0; multipliers
 * from trace (R - 2) s and determinant beta - R s. */
static void ghenon(void) {
  const double al = 0.3, be = 0.6, R = 0.4;
  sc_map *m;
  sc_msg msg;
  sc_map_alloc("ghenon", NULL, &m, &msg);
  sc_map_set_param_by_name(m, "alpha", al, &msg);
  sc_map_set_param_by_name(m, "beta", be, &msg);
  sc_map_set_param_by_name(m, "R", R, &msg);
  double A = 1 - R, B = 1 + be, disc = sqrt(B * B + 4 * A * al);
  double s[2] = {(-B - disc) / (2 * A), (-B + disc) / (2 * A)};
  double from[2] = {-4, -4}, to[2] = {2, 2};
  sc_fixed_points_n_spec sp = {.period_lo = 1, .period_hi = 1, .from = from,
                               .to = to, .steps = 11, .attractor = 50,
                               .transient = 500, .method = SC_SHOOT_SINGLE};
  sc_orbitn_set *set;
  if (!tu_true(sc_fixed_points_n_find(m, &sp, &set, &msg) == SC_OK,
               "ghenon search: %s", msg.text))
    return;
  tu_int("ghenon: two fixed points", (long)sc_orbitn_set_count(set), 2);
  sc_orbitn_info o;
  for (size_t i = 0; i < sc_orbitn_set_count(set) && i < 2; i++) {
    sc_orbitn_set_get(set, i, &o);
    tu_close("ghenon fixed point x", o.x[0], s[i], TOL);
    tu_close("ghenon fixed point y", o.x[1], s[i], TOL);
    double t = (R - 2) * s[i], d = be - R * s[i], q = t * t - 4 * d;
    if (q < 0) { /* a complex pair, positive imaginary part first */
      tu_close("ghenon: pair real part", o.mult_re[0], 0.5 * t, TOL);
      tu_close("ghenon: pair imaginary part", o.mult_im[0], 0.5 * sqrt(-q),
               TOL);
      tu_close("ghenon: conjugate", o.mult_im[1], -0.5 * sqrt(-q), TOL);
      tu_int("ghenon: stability from |mu|^2 = det", o.stable, d < 1);
    } else {
      double big = fabs(t + sqrt(q)) > fabs(t - sqrt(q)) ? 0.5 * (t + sqrt(q))
                                                           : 0.5 * (t - sqrt(q));
      tu_close("ghenon: leading multiplier", o.mult_re[0], big, TOL);
      tu_close("ghenon: product = det", o.mult_re[0] * o.mult_re[1], d, TOL);
    }
  }
  sc_orbitn_set_free(set);
  sc_map_free(m);
}

/* Period 4 alone: Newton on f^4 also meets the fixed points and the
 * period-2 orbit (roots of f^4 - x too); they are recognised by their
 * minimal period, counted as lower, deflated, and not listed. */
static void lower_periods(sc_map *m) {
  sc_orbitn_set *set = search(m, 4, 4, SC_SHOOT_MULTIPLE);
  if (!set) return;
  sc_orbitn_stats st;
  sc_orbitn_set_stats(set, 4, &st);
  tu_int("period 4 alone: one orbit listed", (long)sc_orbitn_set_count(set),
         1);
  tu_int("period 4 alone: 2 fixed points and 1 period-2 orbit met, each "
         "once",
         (long)st.lower, 3);
  tu_int("period 4 alone: none met twice", (long)st.known, 0);
  sc_orbitn_set_free(set);
}

/* A start alone: one Newton run, no box. */
static void one_start(sc_map *m) {
  double x0[2] = {0.6, 0.2};
  sc_fixed_points_n_spec sp = {.period_lo = 1, .period_hi = 2,
                               .start = x0, .method = SC_SHOOT_MULTIPLE};
  sc_orbitn_set *set;
  sc_msg msg;
  if (!tu_true(sc_fixed_points_n_find(m, &sp, &set, &msg) == SC_OK,
               "start: %s", msg.text))
    return;
  sc_orbitn_stats st;
  sc_orbitn_set_stats(set, 1, &st);
  tu_int("start: one Newton run for period 1", (long)st.starts, 1);
  tu_true(count_period(set, 1) == 1, "start: the fixed point near it");
  sc_orbitn_info o;
  sc_orbitn_set_get(set, 0, &o);
  tu_close("start: x", o.x[0], (-(0.7) + sqrt(0.49 + 5.6)) / 2.8, TOL);
  sc_orbitn_set_free(set);
}

static void refusals(sc_map *m) {
  sc_orbitn_set *set;
  sc_msg msg;
  double lo[2] = {0, 0}, hi[2] = {1, 0};
  sc_fixed_points_n_spec sp = {.period_lo = 2, .period_hi = 1, .from = lo,
                               .to = hi, .steps = 3, .method = SC_SHOOT_SINGLE};
  tu_int("periods reversed", sc_fixed_points_n_find(m, &sp, &set, &msg),
         SC_EINVAL);
  sp.period_lo = 1;
  tu_int("to not above from in y", sc_fixed_points_n_find(m, &sp, &set, &msg),
         SC_EINVAL);
  tu_true(strstr(msg.text, "component 2") != NULL, "names the component: %s",
          msg.text);
  hi[1] = 1;
  sp.steps = 100000;
  tu_int("too many starts", sc_fixed_points_n_find(m, &sp, &set, &msg),
         SC_EINVAL);
}

int main(void) {
  sc_map *m = henon();
  sc_orbitn_set *multi = search(m, 1, MAXP, SC_SHOOT_MULTIPLE);
  sc_orbitn_set *single = search(m, 1, MAXP, SC_SHOOT_SINGLE);
  if (multi) {
    closed_forms(multi);
    counts(m, multi);
  }
  for (int p = 1; p <= MAXP; p++)
    tu_int("single and multiple shooting find as many",
           count_period(single, p), count_period(multi, p));
  sc_orbitn_set_free(multi);
  sc_orbitn_set_free(single);
  ghenon();
  one_start(m);
  lower_periods(m);
  refusals(m);
  sc_map_free(m);
  return tu_finish();
}
