/* An integration of the chain of its own (chain_ref.h). */
#define _POSIX_C_SOURCE 200809L
#include "chain_ref.h"

#include "slipcont/map.h"
#include "test_util.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static double ref_spring(const chain_ref *s, const double *Y, int i) {
  double f = Y[i];
  for (int k = -1; k <= 1; k += 2) {
    int n = i + k;
    if (s->ring) n = (n + s->N) % s->N;
    else if (n < 0 || n >= s->N) continue;
    f += s->alpha * (Y[i] - Y[n]);
  }
  return f;
}

static int ref_rhs(double t, const double y[], double dy[], void *p) {
  (void)t;
  const chain_ref *s = p;
  for (int i = 0; i < s->N; i++) {
    dy[i] = s->slip[i] ? y[s->N + i] : s->W;
    double K = s->T[i] / (s->phi * (1 + s->gamma * fabs(y[s->N + i] - s->W)));
    dy[s->N + i] = s->slip[i] ? K - ref_spring(s, y, i) : 0;
  }
  return GSL_SUCCESS;
}

/* The guard of block i: U_i - W slipping, S_i - T_i stuck. */
static double ref_guard(const chain_ref *s, const double *y, int i) {
  return s->slip[i] ? y[s->N + i] - s->W : ref_spring(s, y, i) - s->T[i];
}

/* The rk8pd tolerance, absolute and relative, on states of order 1: f
 * then agrees with the closed forms to ~1e-11 over the ~10
 * time units of a slip. */
static const double REF_EPS = 1e-13;
/* Steps no longer than this, so that no guard crosses zero twice inside
 * one step unseen (frequencies <= sqrt(1 + 4 alpha) ~ 4 here). */
static const double REF_HMAX = 0.01;

/* y at t0 + h from y0 at t0, integrated afresh (event location). */
static void ref_flow(chain_ref *s, const double *y0, double h, double *y) {
  gsl_odeiv2_system sys = {ref_rhs, NULL, (size_t)(2 * s->N), s};
  gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(
      &sys, gsl_odeiv2_step_rk8pd, fmin(h, REF_HMAX) / 4, REF_EPS, REF_EPS);
  double t = 0;
  memcpy(y, y0, (size_t)(2 * s->N) * sizeof *y);
  if (h > 0) gsl_odeiv2_driver_apply(d, &t, h, y);
  gsl_odeiv2_driver_free(d);
}

/* The time in (0, h] where guard i of the step from y0 reaches zero, by
 * bisection on re-integrations (to the rounding of the step). */
static double ref_locate(chain_ref *s, const double *y0, double h, int i) {
  double lo = 0, hi = h, y[2 * CHAIN_REF_MAXN];
  for (int it = 0; it < 60 && hi - lo > 1e-16 * (1 + hi); it++) {
    double mid = 0.5 * (lo + hi);
    ref_flow(s, y0, mid, y);
    if (ref_guard(s, y, i) >= 0) hi = mid;
    else lo = mid;
  }
  return hi;
}

int chain_ref_map(chain_ref *s, const double *d, double *f, char *itin) {
  int N = s->N;
  double y[2 * CHAIN_REF_MAXN], yo[2 * CHAIN_REF_MAXN], gap[CHAIN_REF_MAXN], gmin = HUGE_VAL;
  y[0] = 0;
  for (int i = 1; i < N; i++) y[i] = y[i - 1] + d[i - 1];
  for (int i = 0; i < N; i++) {
    gap[i] = s->T[i] - ref_spring(s, y, i);
    gmin = fmin(gmin, gap[i]);
  }
  int armed[CHAIN_REF_MAXN];
  for (int i = 0; i < N; i++) {
    y[i] += gmin; /* S_i grows with a common shift of the positions */
    y[N + i] = s->W;
    s->slip[i] = gap[i] == gmin;
    armed[i] = !s->slip[i];
  }
  itin[0] = '\0';
  gsl_odeiv2_system sys = {ref_rhs, NULL, (size_t)(2 * N), s};
  for (int phase = 0;; phase++) {
    if (phase == CHAIN_REF_MAX_PHASES) return -2;
    if (phase) strcat(itin, "-");
    for (int i = 0; i < N; i++)
      if (s->slip[i]) snprintf(itin + strlen(itin), 12, "%d", i + 1);
    gsl_odeiv2_evolve *ev = gsl_odeiv2_evolve_alloc((size_t)(2 * N));
    gsl_odeiv2_control *ct = gsl_odeiv2_control_y_new(REF_EPS, REF_EPS);
    gsl_odeiv2_step *st = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd,
                                                (size_t)(2 * N));
    double t = 0, h = 1e-3;
    int hit = -1;
    double th = 0;
    while (hit < 0 && t < 1000) {
      double t0 = t;
      memcpy(yo, y, sizeof y);
      gsl_odeiv2_evolve_apply(ev, ct, st, &sys, &t, t0 + REF_HMAX, &h, y);
      for (int i = 0; i < N; i++) {
        double g = ref_guard(s, y, i);
        if (!armed[i] && g < 0) armed[i] = 1;
        else if (armed[i] && g >= 0 && ref_guard(s, yo, i) < 0) {
          double tl = ref_locate(s, yo, t - t0, i);
          if (hit < 0 || tl < th) hit = i, th = tl;
        }
      }
      if (hit >= 0) ref_flow(s, yo, th, y);
    }
    gsl_odeiv2_evolve_free(ev);
    gsl_odeiv2_control_free(ct);
    gsl_odeiv2_step_free(st);
    if (hit < 0) return -1;
    if (s->slip[hit]) {
      s->slip[hit] = 0;
      y[N + hit] = s->W;
      int left = 0;
      for (int i = 0; i < N; i++) left += s->slip[i];
      if (!left) break;
    } else {
      s->slip[hit] = 1;
      armed[hit] = 0;
    }
  }
  for (int i = 0; i + 1 < N; i++) f[i] = y[i + 1] - y[i];
  return 0;
}


sc_map *chain_ref_new(int N, const char *topology, const char *driver) {
  sc_map *m = NULL;
  sc_msg msg;
  char nb[24];
  snprintf(nb, sizeof nb, "%d", N);
  if (sc_map_alloc("chain", NULL, &m, &msg) ||
      sc_map_set_option(m, "blocks", nb, &msg) ||
      sc_map_set_option(m, "topology", topology, &msg) ||
      sc_map_set_option(m, "driver", driver, &msg)) {
    tu_true(0, "chain_ref_new(%d, %s, %s): %s", N, topology, driver,
            msg.text);
    sc_map_free(m);
    return NULL;
  }
  return m;
}

void chain_ref_set(sc_map *m, const char *name, double x) {
  sc_msg msg;
  if (sc_map_set_param_by_name(m, name, x, &msg))
    tu_true(0, "set %s = %g: %s", name, x, msg.text);
}
