/* The chain model (docs/chain.md): two blocks against bk2 (the same
 * itineraries, f, J and f_p), three to five blocks against an integration
 * of its own (GSL's rk8pd at 1e-13 with events located by re-integration),
 * the symmetries of a ring and of a mirrored open chain, the derivatives
 * against differences, and the refusals. */
#define _POSIX_C_SOURCE 200809L
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/map.h"
#include "chain_ref.h"
#include "test_util.h"

#define MAXN 5



/* --- two blocks are bk2 ---------------------------------------------- */

/* f agrees to 1e-13: both are closed forms of the same motion, evaluated
 * in a different order (bk2 in the modes Sum and Dif, the chain in
 * dsyev's eigenbasis), so they differ by the rounding of a few dozen
 * operations on numbers of order 1.  The derivatives carry the event
 * times' 1 / slope, which amplifies that rounding: 1e-9 relative. */
static const double BK2_F_TOL = 1e-13;
static const double BK2_D_TOL = 1e-9;

static void check_bk2(const char *driver, int npoints) {
  sc_map *b = NULL, *c = chain_ref_new(2, "open", driver);
  sc_msg msg, m2;
  sc_map_alloc("bk2", NULL, &b, &msg);
  sc_map_set_option(b, "driver", driver, &msg);
  sc_mapn_value *v;
  sc_mapn_value_alloc(c, SC_EVAL_DERIV, &v, &msg);
  /* bk2's parameters alpha beta phi v against the chain's alpha beta2
   * phi v */
  const char *bn[4] = {"alpha", "beta", "phi", "v"};
  const char *cn[4] = {"alpha", "beta2", "phi", "v"};
  int bi[4], ci[4];
  for (int k = 0; k < 4; k++) {
    bi[k] = sc_map_param_index(b, bn[k]);
    ci[k] = sc_map_param_index(c, cn[k]);
  }
  double ef = 0, ed = 0;
  int nitin = 0, nstatus = 0, ndone = 0;
  tu_seed(2385);
  for (int k = 0; k < npoints; k++) {
    double p[4] = {tu_uni(0.5, 5), tu_uni(0.5, 3), tu_uni(1.1, 2.1), tu_uni(0.005, 0.1)};
    for (int q = 0; q < 4; q++) {
      chain_ref_set(b, bn[q], p[q]);
      chain_ref_set(c, cn[q], p[q]);
    }
    double d = tu_uni(-1, 1);
    sc_map_value bv;
    unsigned fl = SC_EVAL_DERIV | SC_EVAL_ITINERARY;
    int s1 = sc_map_eval(b, d, fl, &bv, &msg);
    int s2 = sc_map_eval_n(c, &d, fl, v, &m2);
    if (s1 || s2) {
      nstatus += s1 != s2;
      continue;
    }
    ndone++;
    ef = fmax(ef, fabs(bv.f - v->f[0]));
    ed = fmax(ed, fabs(bv.dfdd - v->J[0]) / fmax(1, fabs(bv.dfdd)));
    for (int q = 0; q < 4; q++)
      ed = fmax(ed, fabs(bv.dfdp[bi[q]] - v->fp[ci[q]]) /
                        fmax(1, fabs(bv.dfdp[bi[q]])));
    if (strcmp(bv.itinerary, v->itinerary) && nitin++ < 3)
      tu_true(0, "bk2 %s d = %.17g: itinerary %s, chain %s", driver, d,
              bv.itinerary, v->itinerary);
  }
  printf("bk2 against chain, driver %s: %d points, max |df| %.3g, max "
         "derivative difference %.3g\n",
         driver, ndone, ef, ed);
  tu_true(ndone >= npoints * 9 / 10, "bk2 %s: %d of %d points evaluated",
          driver, ndone, npoints);
  tu_int("itineraries that differ from bk2's", nitin, 0);
  tu_int("statuses that differ from bk2's", nstatus, 0);
  tu_close("max |f_chain - f_bk2|", ef, 0, BK2_F_TOL);
  tu_close("max derivative difference (relative)", ed, 0, BK2_D_TOL);
  sc_mapn_value_free(v);
  sc_map_free(b);
  sc_map_free(c);
}

/* At d* both blocks start together (the tie rule): the same itinerary
 * "12..." as bk2, f to 1e-13 and the same one-sided derivative (the
 * positions placed from block 2, as bk2 places them).  beta = 1, d = 0:
 * the synchronous slip, f = 0 exactly. */
static void check_bk2_ties(const char *driver) {
  sc_map *b = NULL, *c = chain_ref_new(2, "open", driver);
  sc_msg msg;
  sc_map_alloc("bk2", NULL, &b, &msg);
  sc_map_set_option(b, "driver", driver, &msg);
  const double betas[] = {1, 1.7, 0.6, 2.385};
  for (int k = 0; k < 4; k++) {
    chain_ref_set(b, "beta", betas[k]);
    chain_ref_set(c, "beta2", betas[k]);
    double ds = (betas[k] - 1) / (1 + 2 * 3.0); /* alpha = 3, the default */
    sc_map_value v, w;
    unsigned fl = SC_EVAL_DERIV | SC_EVAL_ITINERARY;
    int s1 = sc_map_eval(b, ds, fl, &v, &msg);
    int s2 = sc_map_eval(c, ds, fl, &w, &msg);
    tu_true(s1 == SC_OK && s2 == SC_OK && strcmp(v.itinerary, w.itinerary) == 0
                && strncmp(w.itinerary, "12", 2) == 0,
            "d* with beta %g, %s: itineraries %s (bk2), %s (chain)", betas[k],
            driver, v.itinerary, w.itinerary);
    tu_close("f at d*", w.f, v.f, BK2_F_TOL);
    tu_close("f' at d* (relative)", (w.dfdd - v.dfdd) / fmax(1, fabs(v.dfdd)),
             0, BK2_D_TOL);
    if (betas[k] == 1) tu_true(w.f == 0, "synchronous slip: f = %g", w.f);
  }
  sc_map_free(b);
  sc_map_free(c);
}

/* --- against an integration of its own (chain_ref.h) ------------------ */

/* The reference integrates at 1e-13 and agrees with the closed forms to
 * ~1e-11 over the ~10 time units of a slip: the bound allows a hundred
 * times that. */
static const double REF_TOL = 1e-9;

static void check_integration(int N, int ring, int frozen, int npoints) {
  const char *topo = ring ? "ring" : "open", *drv = frozen ? "frozen" : "moving";
  sc_map *m = chain_ref_new(N, topo, drv);
  sc_mapn_value *v;
  sc_msg msg;
  sc_mapn_value_alloc(m, SC_EVAL_ITINERARY, &v, &msg);
  tu_seed(1000 * N + 10 * ring + frozen);
  double emax = 0;
  int ndone = 0, nitin = 0, nlong = 0;
  for (int k = 0; k < npoints; k++) {
    chain_ref s = {N, ring, 0, 0, 0, 0, {1}, {0}};
    s.alpha = tu_uni(0.5, 4);
    s.phi = tu_uni(1.1, 2);
    double V = tu_uni(0.005, 0.1);
    s.W = frozen ? 0 : V;
    chain_ref_set(m, "alpha", s.alpha);
    chain_ref_set(m, "phi", s.phi);
    chain_ref_set(m, "v", V);
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
      tu_true(s1 && s2, "N %d %s %s point %d: chain status %d (%s), "
              "integration %d (%s)", N, topo, drv, k, s1, s1 ? msg.text : "", s2, s2 ? "" : itin);
      continue;
    }
    ndone++;
    if (strcmp(itin, v->itinerary)) {
      if (nitin++ < 3)
        tu_true(0, "N %d %s %s point %d: itinerary %s, integration %s", N,
                topo, drv, k, v->itinerary, itin);
      continue;
    }
    for (int i = 0; i + 1 < N; i++) emax = fmax(emax, fabs(f[i] - v->f[i]));
  }
  printf("N = %d %s %s: %d points (%d left out: %d phases or more), max "
         "|f - f_integrated| %.3g\n",
         N, topo, drv, ndone, nlong, CHAIN_REF_MAX_PHASES, emax);
  tu_true(ndone >= npoints * 4 / 5, "%d of %d points compared", ndone,
          npoints);
  tu_int("itineraries that differ from the integration's", nitin, 0);
  tu_close("max |f - f_integrated|", emax, 0, REF_TOL);
  sc_mapn_value_free(v);
  sc_map_free(m);
}

/* --- symmetries ------------------------------------------------------- */

/* The images of d under a symmetry agree to this: the two evaluations
 * number the blocks differently, so their sums round differently. */
static const double SYM_TOL = 1e-12;

/* Ring: block i -> i + 1; d_i -> d_(i-1), d_0 = d_N = -(d_1 + ... ). */
static void rotate(int N, const double *d, double *r) {
  double s = 0;
  for (int i = 0; i + 1 < N; i++) s += d[i];
  r[0] = -s;
  for (int i = 1; i + 1 < N; i++) r[i] = d[i - 1];
}
/* Open chain: block i -> N + 1 - i; d_i -> -d_(N-i). */
static void mirror(int N, const double *d, double *r) {
  for (int i = 0; i + 1 < N; i++) r[i] = -d[N - 2 - i];
}

static void check_symmetry(int N, int ring, const char *driver, int npoints) {
  sc_map *m = chain_ref_new(N, ring ? "ring" : "open", driver);
  sc_mapn_value *a, *b;
  sc_msg msg;
  sc_mapn_value_alloc(m, SC_EVAL_VALUE, &a, &msg);
  sc_mapn_value_alloc(m, SC_EVAL_VALUE, &b, &msg);
  void (*sym)(int, const double *, double *) = ring ? rotate : mirror;
  tu_seed(77 + N + ring);
  double emax = 0;
  int ndone = 0;
  for (int k = 0; k < npoints; k++) {
    chain_ref_set(m, "alpha", tu_uni(0.5, 4));
    chain_ref_set(m, "v", tu_uni(0.005, 0.1));
    /* ring: equal thresholds; open: T_i = T_(N+1-i) */
    double beta[MAXN] = {1};
    for (int i = 1; i < N; i++) {
      char nm[24];
      snprintf(nm, sizeof nm, "beta%d", i + 1);
      beta[i] = ring ? 1 : i > N - 1 - i ? beta[N - 1 - i] : tu_uni(0.6, 2);
      chain_ref_set(m, nm, beta[i]);
    }
    double d[MAXN], sd[MAXN], sf[MAXN];
    for (int i = 0; i + 1 < N; i++) d[i] = tu_uni(-0.5, 0.5);
    sym(N, d, sd);
    int s1 = sc_map_eval_n(m, d, 0, a, &msg);
    int s2 = sc_map_eval_n(m, sd, 0, b, &msg);
    if (s1 != s2) tu_true(0, "symmetry N %d: statuses %d, %d", N, s1, s2);
    if (s1 || s2) continue;
    ndone++;
    sym(N, a->f, sf);
    for (int i = 0; i + 1 < N; i++) emax = fmax(emax, fabs(sf[i] - b->f[i]));
  }
  printf("N = %d %s %s: %d points, max |S f(d) - f(S d)| %.3g\n", N,
         ring ? "ring, equal thresholds, rotated"
              : "open, mirrored thresholds, mirrored",
         driver, ndone, emax);
  tu_close("symmetry: max |S f(d) - f(S d)|", emax, 0, SYM_TOL);
  sc_mapn_value_free(a);
  sc_mapn_value_free(b);
  sc_map_free(m);
}

/* Whether an itinerary of N <= 9 blocks is its own mirror image: every
 * slipping set holds block N + 1 - i with block i. */
static int itin_mirrored(const char *it, int N) {
  int in[10] = {0};
  for (const char *p = it;; p++) {
    if (*p >= '1' && *p <= '9') {
      in[*p - '0'] = 1;
      continue;
    }
    for (int i = 1; i <= N; i++)
      if (in[i] != in[N + 1 - i]) return 0;
    memset(in, 0, sizeof in);
    if (!*p) return 1;
  }
}

/* States fixed by the symmetry: their blocks re-stick in pairs at one
 * instant (roots equal up to rounding, taken together by the tie rule),
 * and f is fixed by the symmetry too.  A ring with equal thresholds at
 * d = 0 slips all together and returns to d = 0. */
static void check_symmetric_states(void) {
  const char *drv[2] = {"moving", "frozen"};
  for (int k = 0; k < 2; k++) {
    sc_map *m = chain_ref_new(5, "open", drv[k]);
    sc_mapn_value *v;
    sc_msg msg;
    sc_mapn_value_alloc(m, SC_EVAL_ITINERARY, &v, &msg);
    chain_ref_set(m, "beta2", 1.4);
    chain_ref_set(m, "beta3", 1.9);
    chain_ref_set(m, "beta4", 1.4);
    const double ds[2][4] = {{0.05, 0.02, -0.02, -0.05},
                             {0.05, -0.02, 0.02, -0.05}};
    for (int j = 0; j < 2; j++) {
      double mf[4];
      int st = sc_map_eval_n(m, ds[j], SC_EVAL_ITINERARY, v, &msg);
      tu_true(st == SC_OK, "symmetric state %d, %s: %s", j, drv[k], msg.text);
      mirror(5, v->f, mf);
      double e = 0;
      for (int i = 0; i < 4; i++) e = fmax(e, fabs(mf[i] - v->f[i]));
      tu_true(itin_mirrored(v->itinerary, 5),
              "open, 5 blocks, %s, symmetric d: itinerary %s mirrored",
              drv[k], v->itinerary);
      tu_close("symmetric d: |M f - f|", e, 0, SYM_TOL);
    }
    sc_mapn_value_free(v);
    sc_map_free(m);
    m = chain_ref_new(4 + k, "ring", drv[k]);
    sc_mapn_value_alloc(m, SC_EVAL_ITINERARY, &v, &msg);
    double z[4] = {0, 0, 0, 0};
    tu_true(sc_map_eval_n(m, z, SC_EVAL_ITINERARY, v, &msg) == SC_OK &&
                strcmp(v->itinerary, k ? "12345" : "1234") == 0,
            "ring of %d at d = 0, %s: one synchronous slip (%s)", 4 + k,
            drv[k], v->itinerary);
    double e = 0;
    for (int i = 0; i < 3 + k; i++) e = fmax(e, fabs(v->f[i]));
    tu_close("ring at d = 0: |f|", e, 0, SYM_TOL);
    sc_mapn_value_free(v);
    sc_map_free(m);
  }
}

/* --- derivatives against differences --------------------------------- */

/* Central differences with h = 1e-6 on f of order 1 with derivatives of
 * order 10: truncation ~h^2 f''' ~ 1e-10, rounding ~eps / h ~ 1e-10;
 * 1e-6 relative to the derivatives' scale leaves room for the event
 * times' larger third derivatives. */
static const double FD_H = 1e-6;
static const double FD_TOL = 1e-6;

static void check_derivatives(int N, int ring, const char *driver) {
  sc_map *m = chain_ref_new(N, ring ? "ring" : "open", driver);
  size_t n = (size_t)N - 1, np = sc_map_nparam(m);
  sc_mapn_value *v, *a, *b;
  sc_msg msg;
  sc_mapn_value_alloc(m, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v, &msg);
  sc_mapn_value_alloc(m, SC_EVAL_ITINERARY, &a, &msg);
  sc_mapn_value_alloc(m, SC_EVAL_ITINERARY, &b, &msg);
  tu_seed(31 + N + ring);
  double p0[8];
  chain_ref_set(m, "alpha", 2.385);
  chain_ref_set(m, "phi", 1.3);
  chain_ref_set(m, "v", 0.037);
  for (int i = 1; i < N; i++) {
    char nm[24];
    snprintf(nm, sizeof nm, "beta%d", i + 1);
    chain_ref_set(m, nm, tu_uni(0.8, 1.6));
  }
  for (size_t q = 0; q < np; q++) p0[q] = sc_map_get_param(m, q);
  double emax = 0;
  int ndone = 0;
  for (int k = 0; k < 40; k++) {
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
        else chain_ref_set(m, sc_model_chain.params[c - n].name,
                 p0[c - n] + sgn * FD_H);
        int st = sc_map_eval_n(m, x, SC_EVAL_ITINERARY, w, &msg);
        if (c >= n) chain_ref_set(m, sc_model_chain.params[c - n].name, p0[c - n]);
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
  }
  printf("N = %d %s %s: %d points, max relative |J, f_p - differences| "
         "%.3g\n",
         N, ring ? "ring" : "open", driver, ndone, emax);
  tu_true(ndone >= 20, "derivatives N %d: %d smooth points of 40", N, ndone);
  tu_close("max |exact - differences| / scale", emax, 0, FD_TOL);
  sc_mapn_value_free(v);
  sc_mapn_value_free(a);
  sc_mapn_value_free(b);
  sc_map_free(m);
}

/* --- the model's table and its refusals ------------------------------- */

static void check_interface(void) {
  sc_map *m = chain_ref_new(3, "open", "moving");
  sc_msg msg;
  tu_int("blocks = 3: dimension", (long)sc_map_dim(m), 2);
  tu_true(strcmp(sc_map_get_option(m, "blocks"), "3") == 0,
          "blocks reads back as '%s'", sc_map_get_option(m, "blocks"));
  tu_true(sc_map_set_option(m, "blocks", "7", &msg) == SC_OK, "blocks = 7");
  tu_int("blocks = 7: dimension", (long)sc_map_dim(m), 6);
  tu_true(sc_map_set_option(m, "blocks", "257", &msg) == SC_EINVAL &&
              strstr(msg.text, "2..256"),
          "blocks = 257 refused: %s", msg.text);
  tu_true(sc_map_set_option(m, "blocks", "2.5", &msg) == SC_EINVAL,
          "blocks = 2.5 refused");
  tu_int("refused: dimension kept", (long)sc_map_dim(m), 6);
  sc_map_set_option(m, "blocks", "2", &msg);
  tu_true(sc_map_set_option(m, "topology", "ring", &msg) == SC_EINVAL &&
              strstr(msg.text, "blocks >= 3"),
          "a ring of 2 refused: %s", msg.text);
  /* two blocks: the one-dimensional interface reads it too */
  sc_map_value v;
  double d = 0.0123;
  tu_true(sc_map_eval(m, d, SC_EVAL_DERIV, &v, &msg) == SC_OK,
          "sc_map_eval on two blocks: %s", msg.text);
  sc_map *c2 = NULL;
  tu_true(sc_map_clone(m, &c2, &msg) == SC_OK && sc_map_dim(c2) == 1,
          "clone keeps blocks = 2");
  sc_map_value w;
  sc_map_eval(c2, d, 0, &w, &msg);
  tu_true(w.f == v.f, "clone: the same f (%.17g, %.17g)", w.f, v.f);
  /* a long chain: bases per phase (beyond the setup's table) */
  tu_true(sc_map_set_option(m, "blocks", "100", &msg) == SC_OK, "blocks = 100");
  sc_mapn_value *nv;
  sc_mapn_value_alloc(m, SC_EVAL_ITINERARY, &nv, &msg);
  double x[99];
  for (int i = 0; i < 99; i++) x[i] = 0.01 * sin(i);
  tu_true(sc_map_eval_n(m, x, SC_EVAL_ITINERARY, nv, &msg) == SC_OK,
          "100 blocks: %s", msg.text);
  printf("100 blocks: %d phases, itinerary %.60s\n", nv->nphases,
         nv->itinerary);
  sc_mapn_value_free(nv);
  sc_map_free(c2);
  sc_map_free(m);
}

int main(void) {
  gsl_set_error_handler_off();
  check_interface();
  check_bk2("moving", 10000);
  check_bk2("frozen", 10000);
  check_bk2_ties("moving");
  check_bk2_ties("frozen");
  for (int N = 3; N <= MAXN; N++)
    for (int ring = 0; ring <= 1; ring++)
      for (int frozen = 0; frozen <= 1; frozen++)
        check_integration(N, ring, frozen, 25);
  for (int N = 3; N <= MAXN; N++) {
    check_symmetry(N, 1, "moving", 200);
    check_symmetry(N, 0, "frozen", 200);
    check_symmetry(N, 0, "moving", 200);
  }
  check_symmetric_states();
  for (int N = 3; N <= 4; N++)
    for (int ring = 0; ring <= 1; ring++) {
      check_derivatives(N, ring, "moving");
      check_derivatives(N, ring, "frozen");
    }
  return tu_finish();
}
