/* The chain's borders (docs/chain.md, "Borders"): each border's gradient
 * in d and every parameter against central differences of its value along
 * the followed code; each border's zero against the event structure (on
 * its two sides the natural itinerary is the followed one and one that
 * differs first in the phase the border names); two blocks against bk2's
 * borders (the same kinds with their zeros at the same d). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/map.h"
#include "chain_ref.h"
#include "test_util.h"

#define MAXN 4
#define NBORD 64



/* One evaluation and its borders. */
typedef struct {
  sc_map *m;
  sc_mapn_value *v;
  sc_bordern_list *bl;
  size_t n, np;
} probe;

static int probe_init(probe *p, sc_map *m) {
  sc_msg msg;
  p->m = m;
  p->n = sc_map_dim(m);
  p->np = sc_map_nparam(m);
  return sc_mapn_value_alloc(m, SC_EVAL_DERIV, &p->v, &msg) ||
         sc_bordern_list_alloc(m, NBORD, &p->bl, &msg);
}

static void probe_free(probe *p) {
  sc_mapn_value_free(p->v);
  sc_bordern_list_free(p->bl);
}

/* The border named @p name of the evaluation at x along @p force (NULL:
 * natural; its code into @p code if not NULL), or NULL. */
static const sc_bordern *border_at(probe *p, const double *x,
                                   const sc_itin_code *force,
                                   sc_itin_code *code, const char *name) {
  sc_msg msg;
  p->bl->n = 0;
  if (sc_map_eval_n_ex(p->m, x, SC_EVAL_VALUE, force, code, p->bl, p->v, &msg))
    return NULL;
  for (size_t i = 0; i < p->bl->n && i < p->bl->cap; i++)
    if (!name || strcmp(p->bl->b[i].name, name) == 0) return &p->bl->b[i];
  return NULL;
}

/* A start on the attractor: three natural iterates from a random d. */
static int draw_point(probe *p, int N, double *x) {
  sc_msg msg;
  chain_ref_set(p->m, "alpha", tu_uni(1.5, 4));
  chain_ref_set(p->m, "phi", tu_uni(1.1, 2));
  chain_ref_set(p->m, "v", tu_uni(0.01, 0.1));
  for (int i = 2; i <= N && i <= 5; i++) {
    char nm[8];
    snprintf(nm, sizeof nm, "beta%d", i);
    chain_ref_set(p->m, nm, tu_uni(0.7, 3));
  }
  for (size_t i = 0; i < p->n; i++) x[i] = tu_uni(-0.3, 0.3);
  if (sc_map_iterate_n(p->m, x, 3, SC_EVAL_VALUE, p->v, &msg)) return 0;
  memcpy(x, p->v->f, p->n * sizeof *x);
  return 1;
}

/* ------------------------------------------------------------------ */
/* Gradients against central differences                                */

static const double FD_H = 1e-6;
static const double FD_TOL = 1e-6;

typedef struct {
  int count[SC_BORDER_NKINDS];
  double worst;
} grad_stats;

/* The central difference of the border @p name along the code, step
 * @p h0: in state component k (k < n), else in parameter k - n. */
static int fd_step(probe *p, const double *x, const sc_itin_code *code,
                   const char *name, size_t k, double h0, double *out) {
  double xs[MAXN], val[2];
  for (int s = 0; s < 2; s++) {
    double h = s ? -h0 : h0;
    memcpy(xs, x, p->n * sizeof *xs);
    double p0 = 0;
    if (k < p->n) xs[k] += h;
    else {
      p0 = sc_map_get_param(p->m, k - p->n);
      h *= 1 + fabs(p0);
      sc_map_set_param(p->m, k - p->n, p0 + h, NULL);
    }
    const sc_bordern *b = border_at(p, xs, code, NULL, name);
    if (k >= p->n) sc_map_set_param(p->m, k - p->n, p0, NULL);
    if (!b) return 0;
    val[s] = b->value;
    if (s) *out = (val[0] - val[1]) / (-2 * h);
  }
  return 1;
}

/* The derivative by Richardson's extrapolation of central differences at
 * FD_H and FD_H / 4, and their difference: the error of the plain one
 * (a crossing nearly tangent has a large curvature). */
static int fd(probe *p, const double *x, const sc_itin_code *code,
              const char *name, size_t k, double *out, double *err) {
  double d1, d4;
  if (!fd_step(p, x, code, name, k, FD_H, &d1) ||
      !fd_step(p, x, code, name, k, FD_H / 4, &d4))
    return 0;
  *out = (16 * d4 - d1) / 15;
  *err = fabs(d4 - d1);
  return 1;
}

static void check_gradients(int N, const char *topo, const char *driver,
                            int npoints, grad_stats *S) {
  sc_map *m = chain_ref_new(N, topo, driver);
  probe p;
  if (!m || probe_init(&p, m)) return;
  tu_seed((unsigned long long)(N * 100 + (topo[0] == 'r') * 10 +
                            (driver[0] == 'f')));
  for (int it = 0; it < npoints; it++) {
    double x[MAXN];
    sc_itin_code code;
    if (!draw_point(&p, N, x) || !border_at(&p, x, NULL, &code, NULL) ||
        code.n == 0)
      continue;
    size_t nb = p.bl->n < p.bl->cap ? p.bl->n : p.bl->cap;
    sc_bordern B[NBORD];
    double G[NBORD][MAXN];
    for (size_t i = 0; i < nb; i++) {
      B[i] = p.bl->b[i];
      memcpy(G[i], B[i].dx, p.n * sizeof(double));
    }
    for (size_t i = 0; i < nb; i++) {
      double scale = 1, d, e, worst = 0;
      for (size_t k = 0; k < p.n; k++) scale = fmax(scale, fabs(G[i][k]));
      for (size_t q = 0; q < p.np; q++) scale = fmax(scale, fabs(B[i].dp[q]));
      int ok = 1;
      for (size_t k = 0; k < p.n + p.np && ok; k++) {
        if (!fd(&p, x, &code, B[i].name, k, &d, &e)) ok = 0;
        else /* off by more than the differences' own error */
          worst = fmax(worst,
                       fabs(d - (k < p.n ? G[i][k] : B[i].dp[k - p.n])) - e);
      }
      if (!ok) continue; /* the border is not there on both sides */
      S->count[B[i].kind]++;
      S->worst = fmax(S->worst, worst / scale);
      tu_true(worst <= FD_TOL * scale,
              "N = %d %s %s: border %s (%s): gradient against differences, "
              "%.3g beyond their error (scale %.3g)",
              N, topo, driver, B[i].name, sc_border_label(B[i].kind), worst,
              scale);
    }
  }
  probe_free(&p);
  sc_map_free(m);
}

/* ------------------------------------------------------------------ */
/* Zeros against the event structure                                     */

/* The group index where two codes first differ (-1: equal). */
static int first_diff(const sc_itin_code *a, const sc_itin_code *b) {
  int ia = 0, ib = 0, g = 0;
  while (ia < a->n && ib < b->n) {
    int ka = a->c[ia], kb = b->c[ib];
    if (ka != kb || memcmp(a->c + ia + 1, b->c + ib + 1, (size_t)ka)) return g;
    ia += 1 + ka, ib += 1 + kb, g++;
  }
  return ia == a->n && ib == b->n ? -1 : g;
}

/* The phase a border's name gives (0: the onset). */
static int phase_of(const char *name) {
  const char *s = strstr(name, "phase ");
  return s ? atoi(s + 6) : 0;
}

/* Newton along the gradient to the border's zero, following the code. */
static int to_zero(probe *p, double *x, const sc_itin_code *code,
                   const char *name) {
  for (int it = 0; it < 12; it++) {
    const sc_bordern *b = border_at(p, x, code, NULL, name);
    if (!b) return 0;
    double g2 = 0;
    for (size_t k = 0; k < p->n; k++) g2 += b->dx[k] * b->dx[k];
    if (!(g2 > 0)) return 0;
    if (fabs(b->value) <= 1e-13 * sqrt(g2)) return 1;
    double s = b->value / g2, dx[MAXN];
    for (size_t k = 0; k < p->n; k++) dx[k] = b->dx[k];
    for (size_t k = 0; k < p->n; k++) x[k] -= s * dx[k];
  }
  return 0;
}

typedef struct {
  int checked[SC_BORDER_NKINDS], skipped;
} zero_stats;

/* Across a border's zero, a step of ZERO_STEP in its value either way. */
static const double ZERO_STEP = 1e-9;

static void check_zeros(int N, const char *topo, const char *driver,
                        int npoints, zero_stats *S) {
  sc_map *m = chain_ref_new(N, topo, driver);
  probe p;
  if (!m || probe_init(&p, m)) return;
  tu_seed((unsigned long long)(7 + N * 100 + (topo[0] == 'r') * 10 +
                            (driver[0] == 'f')));
  for (int it = 0; it < npoints; it++) {
    double x[MAXN];
    sc_itin_code code;
    /* (an iterate whose code does not fit has none: nothing to follow) */
    if (!draw_point(&p, N, x) || !border_at(&p, x, NULL, &code, NULL) ||
        code.n == 0)
      continue;
    size_t nb = p.bl->n < p.bl->cap ? p.bl->n : p.bl->cap;
    char names[NBORD][SC_BORDER_NAME];
    int kinds[NBORD];
    for (size_t i = 0; i < nb; i++) {
      snprintf(names[i], sizeof names[i], "%s", p.bl->b[i].name);
      kinds[i] = p.bl->b[i].kind;
    }
    for (size_t i = 0; i < nb; i++) {
      double xz[MAXN], xs[MAXN], f0[MAXN];
      memcpy(xz, x, p.n * sizeof *xz);
      const sc_bordern *b;
      if (!to_zero(&p, xz, &code, names[i]) ||
          !(b = border_at(&p, xz, &code, NULL, names[i]))) {
        S->skipped++;
        continue;
      }
      double g2 = 0, grad[MAXN];
      for (size_t k = 0; k < p.n; k++) g2 += b->dx[k] * b->dx[k];
      memcpy(grad, b->dx, p.n * sizeof *grad);
      sc_itin_code cs[2];
      double ms = 0;
      int ok = 1;
      for (int s = 0; s < 2 && ok; s++) {
        for (size_t k = 0; k < p.n; k++)
          xs[k] = xz[k] + (s ? -1 : 1) * ZERO_STEP * grad[k] / g2;
        ok = border_at(&p, xs, NULL, &cs[s], NULL) != NULL;
        if (s && ok) {
          memcpy(f0, p.v->f, p.n * sizeof *f0);
          const sc_bordern *bf = border_at(&p, xs, &code, NULL, names[i]);
          ok = bf != NULL;
          if (ok) ms = bf->value;
        }
      }
      /* another border between the point and this zero: not this one's */
      if (!ok || first_diff(&cs[0], &code) != -1) {
        S->skipped++;
        continue;
      }
      int g = first_diff(&cs[1], &code), ph = phase_of(names[i]);
      double jump = 0;
      for (size_t k = 0; k < p.n; k++)
        jump = fmax(jump, fabs(f0[k] - p.v->f[k]));
      /* a grazing of the guard that ends the phase, before its root,
       * keeps the code and moves the event: f jumps */
      int changed = g == ph || (g == -1 && jump > 1e-6);
      S->checked[kinds[i]]++;
      tu_true(changed && ms < 0,
              "N = %d %s %s: across %s (%s): itineraries differ from group "
              "%d (the name's phase %d; -1: none), f jumps %.3g, beyond m = "
              "%.3g",
              N, topo, driver, names[i], sc_border_label(kinds[i]), g, ph,
              jump, ms);
    }
  }
  probe_free(&p);
  sc_map_free(m);
}

/* ------------------------------------------------------------------ */
/* Two blocks against bk2                                               */

/* bk2's border named @p name at d along @p force: its value and slope. */
static int bk2_border(sc_map *mb, double d, const sc_itin_code *force,
                      const char *name, double *m, double *dm) {
  sc_border b[NBORD];
  sc_border_list l = {b, NBORD, 0};
  sc_map_value v;
  sc_msg msg;
  if (sc_map_eval_ex(mb, d, SC_EVAL_VALUE, force, NULL, &l, &v, &msg))
    return 0;
  for (size_t i = 0; i < l.n && i < l.cap; i++)
    if (strcmp(b[i].name, name) == 0) {
      *m = b[i].value, *dm = b[i].dd;
      return 1;
    }
  return 0;
}

/* Whether a border of bk2 of @p kind, listed at d along its natural
 * code, has its zero at z (within tol): its point d_on in the state, or
 * Newton along that code started at z. */
static int bk2_zero_at(sc_map *mb, double d, int kind, double z, double tol) {
  sc_border b[NBORD];
  sc_border_list l = {b, NBORD, 0};
  sc_map_value v;
  sc_itin_code code;
  sc_msg msg;
  if (sc_map_eval_ex(mb, d, SC_EVAL_VALUE, NULL, &code, &l, &v, &msg))
    return 0;
  size_t nb = l.n < l.cap ? l.n : l.cap;
  sc_border B[NBORD];
  memcpy(B, b, nb * sizeof *B);
  for (size_t i = 0; i < nb; i++) {
    if ((int)B[i].kind != kind) continue;
    if (B[i].on_state) {
      if (fabs(B[i].d_on - z) <= tol) return 1;
      continue;
    }
    double x = z, m, dm;
    for (int it = 0; it < 12; it++) {
      if (!bk2_border(mb, x, &code, B[i].name, &m, &dm) || !(dm != 0)) break;
      if (fabs(m) <= 1e-14 * fabs(dm)) {
        if (fabs(x - z) <= tol) return 1;
        break;
      }
      x -= m / dm;
    }
  }
  return 0;
}

static const double BK2_ZERO_TOL = 1e-12;

static void check_bk2(const char *driver, int npoints, int *matched) {
  sc_map *mc = chain_ref_new(2, "open", driver), *mb = NULL;
  sc_msg msg;
  probe p;
  if (!mc || sc_map_alloc("bk2", NULL, &mb, &msg) ||
      sc_map_set_option(mb, "driver", driver, &msg) || probe_init(&p, mc)) {
    tu_true(0, "bk2 against chain: setup");
    return;
  }
  tu_seed(driver[0] == 'f' ? 51 : 52);
  for (int it = 0; it < npoints; it++) {
    double al = tu_uni(1.5, 4), be = tu_uni(0.8, 3), ph = tu_uni(1.1, 2),
           V = tu_uni(0.01, 0.1);
    chain_ref_set(mc, "alpha", al), chain_ref_set(mb, "alpha", al);
    chain_ref_set(mc, "beta2", be), chain_ref_set(mb, "beta", be);
    chain_ref_set(mc, "phi", ph), chain_ref_set(mb, "phi", ph);
    chain_ref_set(mc, "v", V), chain_ref_set(mb, "v", V);
    double x = tu_uni(-0.3, 0.3);
    if (sc_map_iterate_n(mc, &x, 3, SC_EVAL_VALUE, p.v, &msg)) continue;
    x = p.v->f[0];
    sc_itin_code code;
    if (!border_at(&p, &x, NULL, &code, NULL)) continue;
    size_t nb = p.bl->n < p.bl->cap ? p.bl->n : p.bl->cap;
    char names[NBORD][SC_BORDER_NAME];
    int kinds[NBORD];
    for (size_t i = 0; i < nb; i++) {
      snprintf(names[i], sizeof names[i], "%s", p.bl->b[i].name);
      kinds[i] = p.bl->b[i].kind;
    }
    for (size_t i = 0; i < nb; i++) {
      double z = x;
      /* (a zero far off is past other borders: another code's) */
      if (!to_zero(&p, &z, &code, names[i]) || fabs(z - x) > 0.05) continue;
      int found =
          bk2_zero_at(mb, x, kinds[i], z, BK2_ZERO_TOL * (1 + fabs(z)));
      (*matched)++;
      tu_true(found,
              "two blocks, driver %s, alpha %.6g beta %.6g phi %.6g V %.6g "
              "d %.10g: the chain's %s (%s) at d = %.15g, a zero of bk2's "
              "borders of that kind",
              driver, al, be, ph, V, x, names[i], sc_border_label(kinds[i]),
              z);
    }
  }
  probe_free(&p);
  sc_map_free(mc);
  sc_map_free(mb);
}

int main(void) {
  grad_stats G = {{0}, 0};
  zero_stats Z = {{0}, 0};
  const char *topo[] = {"open", "ring"}, *drv[] = {"frozen", "moving"};
  for (int N = 3; N <= 4; N++)
    for (int t = 0; t < 2; t++)
      for (int d = 0; d < 2; d++) {
        check_gradients(N, topo[t], drv[d], 3, &G);
        check_zeros(N, topo[t], drv[d], 6, &Z);
      }
  printf("gradients: GR %d CS %d SW %d BR %d TT %d borders, worst %.3g of "
         "scale\n",
         G.count[0], G.count[1], G.count[2], G.count[3], G.count[4], G.worst);
  printf("zeros: GR %d CS %d SW %d BR %d TT %d checked, %d skipped\n",
         Z.checked[0], Z.checked[1], Z.checked[2], Z.checked[3], Z.checked[4],
         Z.skipped);
  for (int k = 0; k < 4; k++)
    tu_true(G.count[k] > 0 && Z.checked[k] > 0,
            "borders of kind %s checked (gradients %d, zeros %d)",
            sc_border_label((sc_border_kind)k), G.count[k], Z.checked[k]);
  int matched = 0;
  check_bk2("frozen", 40, &matched);
  check_bk2("moving", 40, &matched);
  printf("two blocks: %d zeros of the chain's borders matched in bk2's\n",
         matched);
  tu_true(matched >= 20, "two blocks: %d zeros compared", matched);
  return tu_finish();
}
