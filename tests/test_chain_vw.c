/* The chain's numerical flows (docs/chain.md, "Velocity weakening"): two
 * blocks under velocity weakening against bk2's velocity-weakening map;
 * Coulomb friction through the integrator against the exact flows; three
 * blocks against an integration of its own at a much tighter tolerance;
 * the derivatives against differences; the limit gamma -> 0; the
 * refusals; the three-block example's known answer. */
#define _POSIX_C_SOURCE 200809L
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/map.h"
#include "chain_ref.h"
#include "test_util.h"

#define MAXN 4

static sc_map *map_new(const char *model, const char *preset) {
  sc_map *m = NULL;
  sc_msg msg;
  sc_accuracy acc;
  sc_accuracy_preset(&acc, preset, &msg);
  if (sc_map_alloc(model, &acc, &m, &msg))
    tu_true(0, "%s: %s", model, msg.text);
  return m;
}

static void opt(sc_map *m, const char *name, const char *value) {
  sc_msg msg;
  if (sc_map_set_option(m, name, value, &msg))
    tu_true(0, "%s = %s: %s", name, value, msg.text);
}

static sc_map *chain_new(int N, const char *topology, const char *friction,
                         const char *flows, const char *preset) {
  sc_map *m = map_new("chain", preset);
  char nb[24];
  snprintf(nb, sizeof nb, "%d", N);
  opt(m, "blocks", nb);
  opt(m, "topology", topology);
  opt(m, "friction", friction);
  opt(m, "flows", flows);
  return m;
}


/* --- two blocks are bk2 ---------------------------------------------- */

/* Both integrate the same equations at the preset's tolerance (1e-13 at
 * precise) with different steps (bk2 limits them by the slip's own
 * fastest period, the chain by the chain's bound), so f agrees to the
 * maps' promise, 10 (atol + rtol) = 2e-12 at precise; 1e-9 leaves room
 * for a slip's growth of errors near grazing.  The derivatives carry the
 * event times' 1 / slope: 1e-6 relative. */
static const double BK2_F_TOL = 1e-9;
static const double BK2_D_TOL = 1e-6;

static void check_bk2(const char *friction, const char *driver, int npoints,
                      int near_dstar) {
  sc_map *b = map_new("bk2", "precise");
  sc_map *c = chain_new(2, "open", friction, "numerical", "precise");
  opt(b, "friction", friction);
  opt(b, "flows", "numerical");
  opt(b, "driver", driver);
  opt(c, "driver", driver);
  int vw = strcmp(friction, "coulomb") != 0;
  const char *bn[5] = {"alpha", "beta", "v", "gamma", "phi"};
  const char *cn[5] = {"alpha", "beta2", "v", "gamma", "phi"};
  int bi[5], ci[5];
  for (int k = 0; k < 5; k++) {
    bi[k] = sc_map_param_index(b, bn[k]);
    ci[k] = sc_map_param_index(c, cn[k]);
  }
  double ef = 0, ed = 0;
  int nitin = 0, nstatus = 0, ndone = 0;
  tu_seed(4711 + (unsigned)vw + 7 * (unsigned)near_dstar);
  sc_msg msg, m2;
  for (int k = 0; k < npoints; k++) {
    double p[5] = {tu_uni(0.5, 5), tu_uni(0.5, 3), tu_uni(0.01, 0.1), tu_uni(0.2, 3),
                   tu_uni(1.1, 2.1)};
    for (int q = 0; q < 5; q++) {
      chain_ref_set(b, bn[q], p[q]);
      chain_ref_set(c, cn[q], p[q]);
    }
    double ds = (p[1] - 1) / (1 + 2 * p[0]);
    double d = near_dstar ? ds + tu_uni(-1, 1) * pow(10, -tu_uni(6, 12))
                          : tu_uni(-1, 1);
    sc_map_value bv, cv;
    unsigned fl = SC_EVAL_DERIV | SC_EVAL_ITINERARY;
    int s1 = sc_map_eval(b, d, fl, &bv, &msg);
    int s2 = sc_map_eval(c, d, fl, &cv, &m2);
    if (s1 || s2) {
      if (s1 != s2 && nstatus++ < 3)
        tu_true(0, "bk2 %s %s d = %.17g: status %d (%s), chain %d (%s)",
                friction, driver, d, s1, s1 ? msg.text : "", s2,
                s2 ? m2.text : "");
      continue;
    }
    ndone++;
    if (strcmp(bv.itinerary, cv.itinerary)) {
      if (nitin++ < 3)
        tu_true(0, "bk2 %s %s d = %.17g: itinerary %s, chain %s", friction,
                driver, d, bv.itinerary, cv.itinerary);
      continue;
    }
    ef = fmax(ef, fabs(bv.f - cv.f));
    ed = fmax(ed, fabs(bv.dfdd - cv.dfdd) / fmax(1, fabs(bv.dfdd)));
    for (int q = 0; q < 5; q++)
      ed = fmax(ed, fabs(bv.dfdp[bi[q]] - cv.dfdp[ci[q]]) /
                        fmax(1, fabs(bv.dfdp[bi[q]])));
  }
  printf("bk2 against chain, %s, driver %s%s: %d points, max |df| %.3g, "
         "max derivative difference %.3g\n",
         friction, driver, near_dstar ? ", within 1e-6 of d*" : "", ndone, ef,
         ed);
  tu_true(ndone >= npoints * 9 / 10, "%d of %d points evaluated", ndone,
          npoints);
  tu_int("itineraries that differ from bk2's", nitin, 0);
  tu_int("statuses that differ from bk2's", nstatus, 0);
  tu_close("max |f_chain - f_bk2|", ef, 0, BK2_F_TOL);
  tu_close("max derivative difference (relative)", ed, 0, BK2_D_TOL);
  sc_map_free(b);
  sc_map_free(c);
}

/* --- Coulomb friction through the integrator ---------------------------- */

/* The same equations in closed form and integrated at the precise
 * preset's 1e-13: f within the numerical map's promise (2e-12) and some
 * room for the growth of errors over several phases (1e-9, as against
 * bk2); the derivatives within 1e-6 of their scale. */
static void check_exact(int N, int ring, const char *driver, int npoints) {
  const char *topo = ring ? "ring" : "open";
  sc_map *e = chain_new(N, topo, "coulomb", "exact", "precise");
  sc_map *m = chain_new(N, topo, "coulomb", "numerical", "precise");
  opt(e, "driver", driver);
  opt(m, "driver", driver);
  sc_mapn_value *a, *b;
  sc_msg msg;
  unsigned fl = SC_EVAL_DERIV | SC_EVAL_ITINERARY;
  sc_mapn_value_alloc(e, fl, &a, &msg);
  sc_mapn_value_alloc(m, fl, &b, &msg);
  size_t n = (size_t)N - 1, np = sc_map_nparam(m);
  tu_seed(99 + 10 * (unsigned)N + (unsigned)ring);
  double ef = 0, ed = 0;
  int ndone = 0, nitin = 0, nstatus = 0;
  for (int k = 0; k < npoints; k++) {
    double p[3] = {tu_uni(0.5, 4), tu_uni(1.1, 2), tu_uni(0.005, 0.1)};
    const char *pn[3] = {"alpha", "phi", "v"};
    for (int q = 0; q < 3; q++) {
      chain_ref_set(e, pn[q], p[q]);
      chain_ref_set(m, pn[q], p[q]);
    }
    for (int i = 1; i < N; i++) {
      char nm[24];
      snprintf(nm, sizeof nm, "beta%d", i + 1);
      double t = tu_uni(0.6, 2);
      chain_ref_set(e, nm, t);
      chain_ref_set(m, nm, t);
    }
    double d[MAXN];
    for (size_t i = 0; i < n; i++) d[i] = tu_uni(-0.5, 0.5);
    int s1 = sc_map_eval_n(e, d, fl, a, &msg);
    int s2 = sc_map_eval_n(m, d, fl, b, &msg);
    if (s1 || s2) {
      nstatus += s1 != s2;
      continue;
    }
    if (strcmp(a->itinerary, b->itinerary)) {
      if (nitin++ < 3)
        tu_true(0, "N %d %s %s point %d: itinerary %s exact, %s numerical",
                N, topo, driver, k, a->itinerary, b->itinerary);
      continue;
    }
    ndone++;
    double scale = 1;
    for (size_t i = 0; i < n * n; i++) scale = fmax(scale, fabs(a->J[i]));
    for (size_t i = 0; i < n * np; i++) scale = fmax(scale, fabs(a->fp[i]));
    for (size_t i = 0; i < n; i++) ef = fmax(ef, fabs(a->f[i] - b->f[i]));
    for (size_t i = 0; i < n * n; i++)
      ed = fmax(ed, fabs(a->J[i] - b->J[i]) / scale);
    for (size_t i = 0; i < n * np; i++)
      ed = fmax(ed, fabs(a->fp[i] - b->fp[i]) / scale);
  }
  printf("N = %d %s %s, Coulomb: numerical against exact flows, %d points, "
         "max |df| %.3g, max derivative difference %.3g\n",
         N, topo, driver, ndone, ef, ed);
  tu_true(ndone >= npoints * 4 / 5, "%d of %d points compared", ndone,
          npoints);
  tu_int("itineraries that differ", nitin, 0);
  tu_int("statuses that differ", nstatus, 0);
  tu_close("max |f_numerical - f_exact|", ef, 0, BK2_F_TOL);
  tu_close("max derivative difference / scale", ed, 0, BK2_D_TOL);
  sc_mapn_value_free(a);
  sc_mapn_value_free(b);
  sc_map_free(e);
  sc_map_free(m);
}

/* The default preset integrates at 1e-10 and promises f to 10 (atol +
 * rtol) = 2e-9 (sc_map_precision()); the reference is a thousand times
 * tighter. */
static void check_integration(int N, int ring, int npoints) {
  const char *topo = ring ? "ring" : "open";
  sc_map *m = chain_new(N, topo, "velocity-weakening", "numerical", "default");
  sc_mapn_value *v;
  sc_msg msg;
  sc_mapn_value_alloc(m, SC_EVAL_ITINERARY, &v, &msg);
  tu_seed(1000 * (unsigned)N + 10 * (unsigned)ring);
  double emax = 0, prec = sc_map_precision(m);
  int ndone = 0, nitin = 0, nlong = 0;
  for (int k = 0; k < npoints; k++) {
    chain_ref s = {N, ring, 0, 1, 0, 0, {1}, {0}};
    s.alpha = tu_uni(0.5, 4);
    s.gamma = tu_uni(0.2, 3);
    s.W = tu_uni(0.005, 0.1);
    chain_ref_set(m, "alpha", s.alpha);
    chain_ref_set(m, "gamma", s.gamma);
    chain_ref_set(m, "v", s.W);
    for (int i = 1; i < N; i++) {
      char nm[24];
      snprintf(nm, sizeof nm, "beta%d", i + 1);
      s.T[i] = tu_uni(0.6, 2);
      chain_ref_set(m, nm, s.T[i]);
    }
    double d[MAXN], f[MAXN];
    char itin[512];
    for (int i = 0; i + 1 < N; i++) d[i] = tu_uni(-0.5, 0.5);
    int s1 = sc_map_eval_n(m, d, SC_EVAL_ITINERARY, v, &msg);
    int s2 = chain_ref_map(&s, d, f, itin);
    if (s2 == -2 || (!s1 && v->nphases >= CHAIN_REF_MAX_PHASES)) {
      nlong++;
      continue;
    }
    if (s1 || s2) {
      tu_true(s1 && s2, "N %d %s point %d: chain status %d (%s), integration "
              "%d (%s)", N, topo, k, s1, s1 ? msg.text : "", s2,
              s2 ? "" : itin);
      continue;
    }
    ndone++;
    if (strcmp(itin, v->itinerary)) {
      if (nitin++ < 3)
        tu_true(0, "N %d %s point %d: itinerary %s, integration %s", N, topo,
                k, v->itinerary, itin);
      continue;
    }
    for (int i = 0; i + 1 < N; i++) emax = fmax(emax, fabs(f[i] - v->f[i]));
  }
  printf("N = %d %s, velocity weakening, default preset: %d points (%d left "
         "out: %d phases or more), max |f - f_integrated| %.3g (promise "
         "%.3g)\n",
         N, topo, ndone, nlong, CHAIN_REF_MAX_PHASES, emax, prec);
  tu_true(ndone >= npoints * 4 / 5, "%d of %d points compared", ndone,
          npoints);
  tu_int("itineraries that differ from the integration's", nitin, 0);
  tu_close("max |f - f_integrated|", emax, 0, prec);
  sc_mapn_value_free(v);
  sc_map_free(m);
}

/* --- next to a tie --------------------------------------------------------- */

/* Blocks 1 and 3 of an open chain of three at their thresholds at once:
 * gap_1 = 1 + alpha d1 equals gap_3 = T_3 - d1 - (1 + alpha) d2 on the
 * line d2 = (T_3 - 1 - (1 + alpha) d1) / (1 + alpha).  Within 1e-6 to
 * 1e-12 of it one block comes loose first and the other a moment later,
 * while the first is still slower than the surface by ~1e-14 or less:
 * it must not be taken as re-sticking (bk2's rule).  Against the
 * integration of its own, as check_integration(). */
static void check_near_ties(int npoints) {
  sc_map *m = chain_new(3, "open", "velocity-weakening", "numerical",
                        "default");
  sc_mapn_value *v;
  sc_msg msg;
  sc_mapn_value_alloc(m, SC_EVAL_ITINERARY, &v, &msg);
  tu_seed(2718);
  double emax = 0, prec = sc_map_precision(m);
  int ndone = 0, nitin = 0, nlong = 0, nsame = 0;
  for (int k = 0; k < npoints; k++) {
    chain_ref s = {3, 0, 0, 1, 0, 0, {1}, {0}};
    s.alpha = tu_uni(0.5, 4);
    s.gamma = tu_uni(0.2, 3);
    s.W = tu_uni(0.005, 0.1);
    s.T[1] = tu_uni(1.5, 2), s.T[2] = tu_uni(0.8, 1.4);
    chain_ref_set(m, "alpha", s.alpha);
    chain_ref_set(m, "gamma", s.gamma);
    chain_ref_set(m, "v", s.W);
    chain_ref_set(m, "beta2", s.T[1]);
    chain_ref_set(m, "beta3", s.T[2]);
    double d[2], f[2], a = s.alpha;
    char itin[512];
    d[0] = tu_uni(-0.1, 0.1);
    double delta = (k % 2 ? 1 : -1) * pow(10, -6 - 2 * ((k / 2) % 4));
    d[1] = (s.T[2] - 1 - (1 + a) * d[0]) / (1 + a) + delta;
    int s1 = sc_map_eval_n(m, d, SC_EVAL_ITINERARY, v, &msg);
    int s2 = chain_ref_map(&s, d, f, itin);
    if (s2 == -2 || (!s1 && v->nphases >= CHAIN_REF_MAX_PHASES)) {
      nlong++;
      continue;
    }
    if (s1 || s2) {
      tu_true(s1 && s2, "near a tie, point %d: chain status %d (%s), "
              "integration %d", k, s1, s1 ? msg.text : "", s2);
      continue;
    }
    ndone++;
    nsame += strchr(v->itinerary, '-') != NULL &&
             (strncmp(v->itinerary, "1-13", 4) == 0 ||
              strncmp(v->itinerary, "3-13", 4) == 0);
    if (strcmp(itin, v->itinerary)) {
      if (nitin++ < 3)
        tu_true(0, "near a tie, point %d (delta %g): itinerary %s, "
                "integration %s", k, delta, v->itinerary, itin);
      continue;
    }
    for (int i = 0; i < 2; i++) emax = fmax(emax, fabs(f[i] - v->f[i]));
  }
  printf("N = 3 open, velocity weakening, within 1e-6 to 1e-12 of blocks 1 "
         "and 3 at their thresholds together: %d points (%d left out, %d "
         "starting 1-13 or 3-13), max |f - f_integrated| %.3g\n",
         ndone, nlong, nsame, emax);
  tu_true(ndone >= npoints * 4 / 5, "%d of %d points compared", ndone,
          npoints);
  tu_true(nsame >= ndone / 2, "%d of %d slips start with both blocks",
          nsame, ndone);
  tu_int("itineraries that differ from the integration's", nitin, 0);
  tu_close("max |f - f_integrated|", emax, 0, prec);
  sc_mapn_value_free(v);
  sc_map_free(m);
}

/* --- derivatives against differences ----------------------------------- */

/* Central differences with h = 1e-6 of f integrated at the precise
 * preset, whose promise is 2e-12: its error over 2h is ~1e-6; truncation
 * h^2 |f'''| / 6 reaches ~1e-6 on slips of twenty phases (h = 1e-5 gave
 * 1.4e-3 there, falling as h^2).  1e-5 relative to the derivatives'
 * scale. */
static const double FD_H = 1e-6;
static const double FD_TOL = 1e-5;

static void check_derivatives(int N, int ring) {
  sc_map *m = chain_new(N, ring ? "ring" : "open", "velocity-weakening",
                        "numerical", "precise");
  size_t n = (size_t)N - 1, np = sc_map_nparam(m);
  sc_mapn_value *v, *a, *b;
  sc_msg msg;
  sc_mapn_value_alloc(m, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v, &msg);
  sc_mapn_value_alloc(m, SC_EVAL_ITINERARY, &a, &msg);
  sc_mapn_value_alloc(m, SC_EVAL_ITINERARY, &b, &msg);
  tu_seed(31 + (unsigned)N + (unsigned)ring);
  double p0[8];
  chain_ref_set(m, "alpha", 2.385);
  chain_ref_set(m, "gamma", 1.37);
  chain_ref_set(m, "v", 0.037);
  for (int i = 1; i < N; i++) {
    char nm[24];
    snprintf(nm, sizeof nm, "beta%d", i + 1);
    chain_ref_set(m, nm, tu_uni(0.8, 1.6));
  }
  for (size_t q = 0; q < np; q++) p0[q] = sc_map_get_param(m, q);
  double emax = 0, gmax = 0;
  int ndone = 0, pg = sc_map_param_index(m, "gamma");
  for (int k = 0; k < 20; k++) {
    double d[MAXN], x[MAXN];
    for (size_t i = 0; i < n; i++) d[i] = tu_uni(-0.4, 0.4);
    if (sc_map_eval_n(m, d, SC_EVAL_DERIV | SC_EVAL_ITINERARY, v, &msg))
      continue;
    double fd[(MAXN + 8) * MAXN], ex[(MAXN + 8) * MAXN], scale = 1;
    int smooth = 1;
    for (size_t c = 0; c < n + np && smooth; c++) {
      for (int sgn = -1; sgn <= 1; sgn += 2) {
        sc_mapn_value *w = sgn < 0 ? b : a;
        memcpy(x, d, n * sizeof *d);
        if (c < n) x[c] += sgn * FD_H;
        else sc_map_set_param(m, c - n, p0[c - n] + sgn * FD_H, &msg);
        int st = sc_map_eval_n(m, x, SC_EVAL_ITINERARY, w, &msg);
        if (c >= n) sc_map_set_param(m, c - n, p0[c - n], &msg);
        /* a difference across a border is no test of the derivative */
        if (st || strcmp(w->itinerary, v->itinerary)) smooth = 0;
      }
      for (size_t i = 0; i < n && smooth; i++) {
        fd[c * n + i] = (a->f[i] - b->f[i]) / (2 * FD_H);
        ex[c * n + i] = c < n ? v->J[i * n + c] : v->fp[(c - n) * n + i];
        scale = fmax(scale, fabs(ex[c * n + i]));
      }
    }
    if (!smooth) continue;
    ndone++;
    for (size_t i = 0; i < (n + np) * n; i++)
      emax = fmax(emax, fabs(fd[i] - ex[i]) / scale);
    for (size_t i = 0; i < n; i++)
      gmax = fmax(gmax, fabs(ex[(n + (size_t)pg) * n + i]));
  }
  printf("N = %d %s, velocity weakening: %d points, max relative |J, f_p - "
         "differences| %.3g (largest |df/dgamma| %.3g)\n",
         N, ring ? "ring" : "open", ndone, emax, gmax);
  tu_true(ndone >= 10, "derivatives N %d: %d smooth points of 20", N, ndone);
  tu_true(gmax > 1e-3, "f depends on gamma (|df/dgamma| up to %g)", gmax);
  tu_close("max |exact - differences| / scale", emax, 0, FD_TOL);
  sc_mapn_value_free(v);
  sc_mapn_value_free(a);
  sc_mapn_value_free(b);
  sc_map_free(m);
}

/* --- refusals ----------------------------------------------------------- */

static void check_refusals(void) {
  sc_map *m = chain_new(3, "open", "coulomb", "exact", "default");
  sc_msg msg;
  opt(m, "driver", "frozen");
  tu_true(sc_map_set_option(m, "friction", "velocity-weakening", &msg) ==
                  SC_EINVAL &&
              strstr(msg.text, "driver = moving"),
          "velocity weakening with the driver frozen refused: %s", msg.text);
  tu_true(strcmp(sc_map_get_option(m, "friction"), "coulomb") == 0,
          "refused: friction stays coulomb (%s)",
          sc_map_get_option(m, "friction"));
  sc_accuracy acc;
  sc_accuracy_preset(&acc, "default", &msg);
  acc.precision = SC_PRECISION_QUAD;
  opt(m, "flows", "numerical");
  tu_true(sc_map_set_accuracy(m, &acc, &msg) == SC_EINVAL &&
              strstr(msg.text, "flows = exact"),
          "quad with numerical flows refused: %s", msg.text);
  tu_true(sc_map_precision(m) > 0, "numerical flows: precision %g > 0",
          sc_map_precision(m));
  opt(m, "flows", "exact");
  tu_true(sc_map_precision(m) == 0, "exact flows: precision %g",
          sc_map_precision(m));
  sc_map_free(m);
}

/* --- gamma -> 0 ---------------------------------------------------------- */

/* K_i = T_i / (1 + gamma |U_i - W|) tends to T_i as gamma -> 0: Coulomb's
 * law with kinetic force equal to the threshold, the exact map's limit
 * phi -> 1, where f depends on phi - 1 to second order (a block that
 * comes loose starts at its moving equilibrium).  Against the exact
 * Coulomb map at phi = 1 + 1e-8 (precise), on a line of d: gamma = 0
 * within the numerical map's promise (2e-12), gamma = 1e-4 and 1e-5 with
 * an error that falls with gamma (like gamma^1.5, as bk2's in
 * tests/test_bk2.c), all with the same itineraries. */
static void check_coulomb_limit(int ring) {
  const char *topo = ring ? "ring" : "open";
  const double gam[3] = {0, 1e-4, 1e-5};
  sc_map *all[4];
  all[0] = chain_new(3, topo, "coulomb", "exact", "precise");
  chain_ref_set(all[0], "phi", 1 + 1e-8);
  for (int k = 1; k < 4; k++) {
    all[k] = chain_new(3, topo, "velocity-weakening", "numerical", "precise");
    chain_ref_set(all[k], "gamma", gam[k - 1]);
  }
  sc_mapn_value *v[4];
  sc_msg msg;
  for (int k = 0; k < 4; k++) {
    chain_ref_set(all[k], "alpha", 2.9);
    chain_ref_set(all[k], "v", 0.025);
    chain_ref_set(all[k], "beta2", 1.3);
    chain_ref_set(all[k], "beta3", 1.7);
    sc_mapn_value_alloc(all[k], SC_EVAL_ITINERARY, &v[k], &msg);
  }
  double e[3] = {0, 0, 0};
  int n = 0, differ = 0;
  for (int i = 0; i <= 24; i++) {
    double d[2] = {-0.4 + 0.8 * i / 24 + 1e-3, 0.3 - 0.5 * i / 24};
    int st = 0;
    for (int k = 0; k < 4; k++)
      st |= sc_map_eval_n(all[k], d, SC_EVAL_ITINERARY, v[k], &msg);
    if (st) continue;
    n++;
    int same = 1;
    for (int k = 1; k < 4; k++) same &= !strcmp(v[0]->itinerary, v[k]->itinerary);
    if (!same) {
      differ++;
      continue;
    }
    for (int k = 0; k < 3; k++)
      for (int q = 0; q < 2; q++)
        e[k] = fmax(e[k], fabs(v[k + 1]->f[q] - v[0]->f[q]));
  }
  printf("N = 3 %s, velocity weakening against Coulomb at phi = 1 + 1e-8: "
         "%d points, max |df| %.3g at gamma 0, %.3g at 1e-4, %.3g at 1e-5\n",
         topo, n, e[0], e[1], e[2]);
  tu_true(n >= 20 && differ == 0, "gamma -> 0, %s: %d points, %d "
          "itineraries differ", topo, n, differ);
  tu_close("|f(gamma 0) - f(Coulomb, phi -> 1)|", e[0], 0,
           sc_map_precision(all[1]));
  tu_close("|f(gamma 1e-5) - f(Coulomb, phi -> 1)|", e[2], 0, 2e-9);
  tu_true(e[1] >= 10 * e[2], "the error falls with gamma (%.3g -> %.3g)",
          e[1], e[2]);
  for (int k = 0; k < 4; k++) {
    sc_mapn_value_free(v[k]);
    sc_map_free(all[k]);
  }
}

/* --- the three-block example's flip --------------------------------------- */

/* examples/chain3-vw-sweep.ini: the open chain of three blocks, alpha =
 * 3.5, beta3 = 3, V = 0.025, gamma swept.  Its period-1 orbit loses
 * stability in a flip at gamma = CHAIN3_VW_FLIP (docs/chain.md, "Velocity
 * weakening"; tests/chain3_vw.sh holds the sweep's periods to it): the
 * fixed point solved by Newton with the map's J (residual <= 1e-11), and
 * det(J + I) = 0 by the secant method in gamma, each step on the fixed
 * point of its gamma; there J has the multiplier -1 (to 1e-8), its other
 * inside the unit circle; the orbit's slip at gamma = 0.2 is a full
 * one from block 3 to block 1. */
#define CHAIN3_VW_FLIP 0.21446
/* The period-1 orbit at gamma = 0.2 (d1, to ten digits: the sweep's d1
 * there, tests/chain3_vw.sh). */
#define CHAIN3_VW_D1 0.1355455871
/* How far from the documented value (five digits) the flip may be. */
static const double FLIP_DOC_TOL = 1e-5;

/* The fixed point near d by Newton on f(d) - d with J; its J into J. */
static double fixed_point(sc_map *m, sc_mapn_value *v, double *d, double *J) {
  sc_msg msg;
  double res = HUGE_VAL;
  for (int it = 0; it < 20; it++) {
    if (sc_map_eval_n(m, d, SC_EVAL_DERIV, v, &msg)) return HUGE_VAL;
    double r0 = v->f[0] - d[0], r1 = v->f[1] - d[1];
    res = fmax(fabs(r0), fabs(r1));
    double a = v->J[0] - 1, b = v->J[1], c = v->J[2], e = v->J[3] - 1;
    memcpy(J, v->J, 4 * sizeof *J);
    if (res < 1e-13) break;
    double det = a * e - b * c;
    d[0] -= (e * r0 - b * r1) / det;
    d[1] -= (a * r1 - c * r0) / det;
  }
  return res;
}

static void check_example_flip(void) {
  sc_map *m = chain_new(3, "open", "velocity-weakening", "numerical",
                        "precise");
  sc_mapn_value *v;
  sc_msg msg;
  sc_mapn_value_alloc(m, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v, &msg);
  chain_ref_set(m, "alpha", 3.5);
  chain_ref_set(m, "beta3", 3);
  chain_ref_set(m, "v", 0.025);
  chain_ref_set(m, "gamma", 0.2);
  double d[2] = {0.1, 0.2}, J[4], res = 0;
  for (int k = 0; k < 600; k++) {
    sc_map_eval_n(m, d, 0, v, &msg);
    d[0] = v->f[0], d[1] = v->f[1];
  }
  res = fixed_point(m, v, d, J);
  printf("three blocks, alpha 3.5, beta3 3, gamma 0.2: the period-1 orbit "
         "at d = (%.12f, %.12f), residual %.3g\n", d[0], d[1], res);
  tu_close("period-1 orbit at gamma 0.2: d1 (docs/chain.md)", d[0],
           CHAIN3_VW_D1, 1e-10);
  sc_map_eval_n(m, d, SC_EVAL_ITINERARY, v, &msg);
  tu_true(strcmp(v->itinerary, "3-23-123-12-1") == 0,
          "period-1 orbit at gamma 0.2: its slip %s (3-23-123-12-1)",
          v->itinerary);
  /* secant on h(gamma) = det(J + I) */
  double g[2] = {0.21, 0.22}, h[2];
  for (int k = 0; k < 2; k++) {
    chain_ref_set(m, "gamma", g[k]);
    res = fmax(res, fixed_point(m, v, d, J));
    h[k] = (J[0] + 1) * (J[3] + 1) - J[1] * J[2];
  }
  for (int it = 0; it < 30 && fabs(g[1] - g[0]) > 1e-12; it++) {
    double gn = g[1] - h[1] * (g[1] - g[0]) / (h[1] - h[0]);
    g[0] = g[1], h[0] = h[1], g[1] = gn;
    chain_ref_set(m, "gamma", gn);
    res = fmax(res, fixed_point(m, v, d, J));
    h[1] = (J[0] + 1) * (J[3] + 1) - J[1] * J[2];
  }
  double tr = J[0] + J[3], det = J[0] * J[3] - J[1] * J[2];
  double disc = sqrt(fmax(0, tr * tr - 4 * det));
  double l1 = 0.5 * (tr - disc), l2 = 0.5 * (tr + disc);
  printf("three blocks, alpha 3.5, beta3 3: flip of the period-1 orbit at "
         "gamma = %.10f, d = (%.10f, %.10f), multipliers %.10f, %.10f, "
         "Newton residual <= %.3g\n",
         g[1], d[0], d[1], l1, l2, res);
  tu_close("fixed points: max Newton residual", res, 0, 1e-11);
  tu_close("flip: multiplier", l1, -1, 1e-8);
  tu_true(fabs(l2) < 1, "flip: the other multiplier %g inside", l2);
  tu_close("flip's gamma (docs/chain.md)", g[1], CHAIN3_VW_FLIP,
           FLIP_DOC_TOL);
  sc_mapn_value_free(v);
  sc_map_free(m);
}

int main(void) {
  gsl_set_error_handler_off();
  check_refusals();
  check_bk2("velocity-weakening", "moving", 300, 0);
  check_bk2("velocity-weakening", "moving", 100, 1);
  check_bk2("coulomb", "moving", 100, 0);
  check_bk2("coulomb", "frozen", 100, 0);
  for (int N = 3; N <= MAXN; N++)
    for (int ring = 0; ring <= 1; ring++) {
      check_exact(N, ring, "moving", 40);
      check_exact(N, ring, "frozen", 40);
    }
  for (int ring = 0; ring <= 1; ring++) check_integration(3, ring, 40);
  check_integration(4, 0, 20);
  check_near_ties(40);
  check_derivatives(3, 0);
  check_derivatives(3, 1);
  check_coulomb_limit(0);
  check_coulomb_limit(1);
  check_example_flip();
  return tu_finish();
}
