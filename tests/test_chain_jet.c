/* The chain's second and third derivatives (docs/chain.md, "What is
 * exact"; src/models/chain_jet.c): H, Jp and T against central
 * differences of the exact J, f_p and H on random states of three and
 * four blocks (open and ring, both drivers), and two blocks against
 * bk2's own jets through the n-dimensional interface. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/map.h"
#include "chain_ref.h"
#include "test_util.h"

#define MAXN 3 /* state components: four blocks */
#define NP 8   /* the chain's parameters */



/* --- against differences ----------------------------------------------- */

/* Central differences at h and h / 2, extrapolated (Richardson:
 * (4 D(h/2) - D(h)) / 3, truncation ~h^4 f^(6)), for h = 1e-4, 2.5e-5 and
 * 6e-6, the best of the three kept: the tensors reach 1e7 at states
 * whose slips nearly graze, where the truncation needs the smallest h,
 * and the differences' rounding (eps times the size of the terms that
 * cancel in H, over h) needs the largest where f is nearly affine.
 * Observed: the error falls as h^4 (5e-6, then 4e-8 of the scale from h
 * = 1e-4 to 3e-5) until rounding takes over (3.5e-7 of a scale of 1 at
 * h = 3e-5, 1.6e-6 at 1e-5).  A wrong tensor is wrong at every h. */
static const double FD_HS[3] = {1e-4, 2.5e-5, 6e-6};
static const double FD_TOL = 1e-6;

typedef struct {
  sc_map *m;
  size_t n, np;
  double h; /* the differences' step */
  double p0[NP];
  sc_mapn_value *v, *w[4]; /* at x; at x + h, x - h, x + h/2, x - h/2 */
} fd_ctx;

/* Evaluate w[] in variable c (state component, or parameter c - n); 0
 * if one crosses a border (its itinerary is not v's) or fails. */
static int pair(fd_ctx *F, const double *x, size_t c) {
  sc_msg msg;
  static const double step[4] = {1, -1, 0.5, -0.5};
  for (int k = 0; k < 4; k++) {
    double y[MAXN], h = step[k] * F->h;
    memcpy(y, x, F->n * sizeof *x);
    const char *name = c >= F->n ? sc_model_chain.params[c - F->n].name : NULL;
    if (c < F->n) y[c] += h;
    else chain_ref_set(F->m, name, F->p0[c - F->n] + h);
    /* T from differences of H in the state; Jp from J's in p */
    unsigned fl = (c < F->n ? SC_EVAL_DERIV2 : SC_EVAL_DERIV) |
                  SC_EVAL_ITINERARY;
    int st = sc_map_eval_n(F->m, y, fl, F->w[k], &msg);
    if (name) chain_ref_set(F->m, name, F->p0[c - F->n]);
    if (st || strcmp(F->w[k]->itinerary, F->v->itinerary)) return 0;
  }
  return 1;
}

#define FD(field, k)                                                          \
  ((4 * (F->w[2]->field[k] - F->w[3]->field[k]) / F->h -                      \
    (F->w[0]->field[k] - F->w[1]->field[k]) / (2 * F->h)) /                   \
   3)

/* max |exact - differences| / scale at x over H (from J), Jp (from J in
 * the parameters), T (from H); -1 where a difference crosses a border. */
static double fd_error(fd_ctx *F, const double *x, double *scale) {
  size_t n = F->n, np = F->np;
  sc_mapn_value *v = F->v;
  double e[3] = {0}, s[3] = {1, 1, 1};
  for (size_t c = 0; c < n + np; c++) {
    if (!pair(F, x, c)) return -1;
    for (size_t i = 0; i < n; i++)
      for (size_t j = 0; j < n; j++) {
        if (c >= n) {
          size_t k = ((c - n) * n + i) * n + j;
          e[1] = fmax(e[1], fabs(v->Jp[k] - FD(J, i * n + j)));
          s[1] = fmax(s[1], fabs(v->Jp[k]));
          continue;
        }
        size_t k = (i * n + j) * n + c;
        e[0] = fmax(e[0], fabs(v->H[k] - FD(J, i * n + j)));
        s[0] = fmax(s[0], fabs(v->H[k]));
        for (size_t l = 0; l < n; l++) {
          size_t t = ((i * n + j) * n + l) * n + c;
          e[2] = fmax(e[2], fabs(v->T[t] - FD(H, (i * n + j) * n + l)));
          s[2] = fmax(s[2], fabs(v->T[t]));
        }
      }
  }
  *scale = fmax(s[0], fmax(s[1], s[2]));
  return fmax(e[0] / s[0], fmax(e[1] / s[1], e[2] / s[2]));
}

/* The tensors' symmetry in the state indices (exact by construction of
 * H, by the fill of T: checked to rounding). */
static double asymmetry(const sc_mapn_value *v) {
  size_t n = v->n;
  double e = 0, s = 1;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      for (size_t k = 0; k < n; k++) {
        s = fmax(s, fabs(v->H[(i * n + j) * n + k]));
        e = fmax(e, fabs(v->H[(i * n + j) * n + k] - v->H[(i * n + k) * n + j]));
        for (size_t l = 0; l < n; l++) {
          double t = v->T[((i * n + j) * n + k) * n + l];
          e = fmax(e, fabs(t - v->T[((i * n + k) * n + l) * n + j]));
          e = fmax(e, fabs(t - v->T[((i * n + l) * n + j) * n + k]));
        }
      }
  return e / s;
}

static void check_differences(int N, int ring, const char *driver) {
  fd_ctx F = {.m = chain_ref_new(N, ring ? "ring" : "open", driver)};
  sc_msg msg;
  unsigned fl = SC_EVAL_DERIV2 | SC_EVAL_ITINERARY;
  F.n = (size_t)N - 1, F.np = sc_map_nparam(F.m);
  sc_mapn_value_alloc(F.m, fl, &F.v, &msg);
  for (int k = 0; k < 4; k++) sc_mapn_value_alloc(F.m, fl, &F.w[k], &msg);
  tu_seed(77 + 2 * N + ring);
  chain_ref_set(F.m, "alpha", 2.385);
  chain_ref_set(F.m, "phi", 1.3);
  chain_ref_set(F.m, "v", 0.037);
  for (int i = 1; i < N; i++) {
    char nm[24];
    snprintf(nm, sizeof nm, "beta%d", i + 1);
    chain_ref_set(F.m, nm, tu_uni(0.9, 1.3));
  }
  for (size_t q = 0; q < F.np; q++) F.p0[q] = sc_map_get_param(F.m, q);
  double emax = 0, smax = 0, asym = 0;
  int ndone = 0, nnan = 0, nslips = 0;
  for (int k = 0; k < 30; k++) {
    double x[MAXN], scale;
    for (size_t i = 0; i < F.n; i++) x[i] = tu_uni(-0.1, 0.1);
    if (sc_map_eval_n(F.m, x, fl, F.v, &msg)) continue;
    if (!isfinite(F.v->H[0]) || !isfinite(F.v->T[0])) {
      nnan++;
      continue;
    }
    double e = HUGE_VAL;
    for (int hk = 0; hk < 3; hk++) {
      F.h = FD_HS[hk];
      double ek = fd_error(&F, x, &scale);
      if (ek >= 0) e = fmin(e, ek);
    }
    if (e == HUGE_VAL) continue;
    ndone++;
    nslips += strchr(F.v->itinerary, '-') != NULL;
    emax = fmax(emax, e);
    smax = fmax(smax, scale);
    asym = fmax(asym, asymmetry(F.v));
  }
  printf("N = %d %s %s: %d points (%d of several phases), max relative |H, "
         "Jp, T - differences| %.3g (tensors up to %.3g), asymmetry %.3g\n",
         N, ring ? "ring" : "open", driver, ndone, nslips, emax, smax, asym);
  tu_true(ndone >= 15, "N %d: %d smooth points of 30", N, ndone);
  tu_true(nslips >= 5, "N %d: %d points of several phases", N, nslips);
  tu_int("points without second derivatives", nnan, 0);
  tu_close("max |exact - differences| / scale", emax, 0, FD_TOL);
  tu_close("asymmetry of H and T / scale", asym, 0, 1e-12);
  sc_mapn_value_free(F.v);
  for (int k = 0; k < 4; k++) sc_mapn_value_free(F.w[k]);
  sc_map_free(F.m);
}

/* --- two blocks are bk2 ------------------------------------------------ */

/* bk2's jets replay its own closed forms in the modes Sum and Dif; the
 * chain's replay dsyev's eigenbasis: the same derivatives up to rounding
 * amplified by the event times' slopes, as for the first derivatives
 * (test_chain.c: 1e-9 relative; observed ~1e-12). */
static const double BK2_TOL = 1e-9;

static void check_bk2(const char *driver, int npoints) {
  sc_map *b = NULL, *c = chain_ref_new(2, "open", driver);
  sc_msg msg, m2;
  sc_map_alloc("bk2", NULL, &b, &msg);
  sc_map_set_option(b, "driver", driver, &msg);
  unsigned fl = SC_EVAL_DERIV2 | SC_EVAL_ITINERARY;
  sc_mapn_value *bv, *cv;
  sc_mapn_value_alloc(b, fl, &bv, &msg);
  sc_mapn_value_alloc(c, fl, &cv, &msg);
  const char *bn[4] = {"alpha", "beta", "phi", "v"};
  const char *cn[4] = {"alpha", "beta2", "phi", "v"};
  int bi[4], ci[4];
  for (int k = 0; k < 4; k++) {
    bi[k] = sc_map_param_index(b, bn[k]);
    ci[k] = sc_map_param_index(c, cn[k]);
  }
  double e = 0;
  int ndone = 0, nitin = 0, iters = 0;
  tu_seed(4242);
  for (int k = 0; k < npoints; k++) {
    double p[4] = {tu_uni(0.5, 5), tu_uni(0.5, 3), tu_uni(1.1, 2.1), tu_uni(0.005, 0.1)};
    for (int q = 0; q < 4; q++) {
      chain_ref_set(b, bn[q], p[q]);
      chain_ref_set(c, cn[q], p[q]);
    }
    double d = tu_uni(-1, 1);
    int it = 1 + k % 2; /* one iterate, and two by the chain rule */
    if (sc_map_iterate_n(b, &d, it, fl, bv, &msg) ||
        sc_map_iterate_n(c, &d, it, fl, cv, &m2))
      continue;
    if (!isfinite(bv->H[0]) || !isfinite(bv->T[0])) continue;
    if (strcmp(bv->itinerary, cv->itinerary)) {
      nitin++;
      continue;
    }
    double s2 = fmax(1, fabs(bv->H[0])), s3 = fmax(1, fabs(bv->T[0]));
    double ek = fmax(fabs(bv->H[0] - cv->H[0]) / s2,
                     fabs(bv->T[0] - cv->T[0]) / s3);
    for (int q = 0; q < 4; q++)
      ek = fmax(ek, fabs(bv->Jp[bi[q]] - cv->Jp[ci[q]]) /
                        fmax(1, fabs(bv->Jp[bi[q]])));
    if (ek > BK2_TOL && e <= BK2_TOL)
      printf("  worst so far: alpha %.17g beta %.17g phi %.17g v %.17g d "
             "%.17g (%d iterates): H %.17g / %.17g, T %.17g / %.17g\n",
             p[0], p[1], p[2], p[3], d, it, bv->H[0], cv->H[0], bv->T[0],
             cv->T[0]);
    e = fmax(e, ek);
    ndone++;
    iters += it == 2;
  }
  printf("bk2 against chain, driver %s: %d points (%d of two iterates), max "
         "relative difference of H, Jp, T %.3g\n",
         driver, ndone, iters, e);
  tu_true(ndone >= npoints * 8 / 10, "bk2 %s: %d of %d points compared",
          driver, ndone, npoints);
  tu_int("itineraries that differ from bk2's", nitin, 0);
  tu_close("max |chain - bk2| (relative)", e, 0, BK2_TOL);
  sc_mapn_value_free(bv);
  sc_mapn_value_free(cv);
  sc_map_free(b);
  sc_map_free(c);
}

int main(void) {
  check_bk2("moving", 1000);
  check_bk2("frozen", 1000);
  for (int N = 3; N <= 4; N++)
    for (int ring = 0; ring <= 1; ring++) {
      check_differences(N, ring, "moving");
      check_differences(N, ring, "frozen");
    }
  return tu_finish();
}
