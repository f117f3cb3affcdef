/* Fold, flip and Neimark-Sacker curves of the period-m fixed points of an
 * n-dimensional map in two parameters: the minimally augmented systems of
 * mapn_system.h continued by pseudo-arclength (continuation/branch.c),
 * their bordering vectors updated at every point, and every
 * codimension-two point of sc_nf_curve_tests() located by Newton on the
 * extended system (sc_curve_locate; docs/maps.md, "Curves and
 * codimension two"). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/curve_impl.h"
#include "slipcont/mapn_system.h"
#include "slipcont/normal_form.h"

/* The map with its current parameters and the storage of one evaluation
 * of g = f^m with every derivative. */
typedef struct {
  sc_map *m;
  int period, ix, iy;
  size_t n, np;
  sc_mapn_value *v;
  sc_msg emsg; /* of the last failed evaluation */
} gctx;

/* g at (x, p): the free parameters set where they changed (a model's
 * setup runs at each change). */
static int g_eval(gctx *c, const double *x, double px, double py,
                  unsigned flags) {
  if ((sc_map_get_param(c->m, (size_t)c->ix) != px &&
       sc_map_set_param(c->m, (size_t)c->ix, px, &c->emsg)) ||
      (sc_map_get_param(c->m, (size_t)c->iy) != py &&
       sc_map_set_param(c->m, (size_t)c->iy, py, &c->emsg)))
    return 1; /* outside the parameters' range: shrink the step */
  return sc_map_iterate_n(c->m, x, c->period, flags, c->v, &c->emsg) ? 1 : 0;
}

/* sc_mapn_fn: g and its derivatives up to @p order into the system's
 * arrays. */
static int g_fn(const double *x, const double *p, int order, sc_mapn_jet *jet,
                void *user) {
  gctx *c = user;
  unsigned flags = order == 0   ? SC_EVAL_VALUE
                   : order == 1 ? SC_EVAL_DERIV
                                : SC_EVAL_DERIV | SC_EVAL_DERIV2;
  int rc = g_eval(c, x, p[c->ix], p[c->iy], flags);
  if (rc) return rc;
  size_t n = c->n, np = c->np;
  memcpy(jet->g, c->v->f, n * sizeof(double));
  if (order >= 1) {
    memcpy(jet->gx, c->v->J, n * n * sizeof(double));
    memcpy(jet->gp, c->v->fp, np * n * sizeof(double));
  }
  if (order >= 2) {
    memcpy(jet->gxx, c->v->H, n * n * n * sizeof(double));
    memcpy(jet->gxp, c->v->Jp, np * n * n * sizeof(double));
  }
  return 0;
}

typedef struct {
  const sc_curve_settings *set;
  const sc_curven_output *out;
  sc_curve_stats *stats;
  sc_accuracy acc;
  gctx g;
  sc_nf_curve kind;
  sc_mapn_system *sys;
  sc_curve_system cs; /* the curve's problem with its tests */
  const char *labels[SC_NF_MAXTEST];
  size_t ntest;
  size_t n, N; /* state dimension; unknowns */
  double qref[SC_DIM_TENSOR], qnext[SC_DIM_TENSOR]; /* the fold's q */
  int have_qref;
  double *u0, *prev, *cur, *u, *mid, *F; /* N each */
  double psi_prev[SC_NF_MAXTEST], psi[SC_NF_MAXTEST];
  int closed;
} ntrace;

#define UX(T, u) ((u)[(T)->N - 2])
#define UY(T, u) ((u)[(T)->N - 1])

static double kappa_of(const ntrace *T, const double *u) {
  return T->kind == SC_NF_NS ? u[T->n] : T->kind == SC_NF_FOLD ? 1 : -1;
}

/* The tests at u (sc_curve_system's callback): g's jet with its third
 * derivatives, then sc_nf_curve_tests(); the fold's q is oriented by the
 * last accepted point's and kept in qnext. */
static int tests_at(const double *u, double *psi, void *user) {
  ntrace *T = user;
  if (g_eval(&T->g, u, UX(T, u), UY(T, u), SC_EVAL_DERIV | SC_EVAL_DERIV2))
    return 1;
  sc_nf_jet jet = {T->n, T->g.v->J, T->g.v->H, T->g.v->T};
  sc_msg m;
  return sc_nf_curve_tests(T->kind, &jet, kappa_of(T, u),
                           T->have_qref ? T->qref : NULL, psi, T->qnext, &m)
             ? -1
             : 0;
}

/* The normal-form coefficient at u (NaN where it has none). */
static double coef_at(ntrace *T, const double *u) {
  double psi[SC_NF_MAXTEST];
  if (tests_at(u, psi, T)) return NAN;
  return T->kind == SC_NF_NS ? psi[4] : psi[0];
}

static int emit_special(ntrace *T, const char *label, const double *u,
                        double residual, double test, const char *note) {
  sc_curven_special s;
  memset(&s, 0, sizeof s);
  snprintf(s.label, sizeof s.label, "%s", label);
  s.x = UX(T, u), s.y = UY(T, u), s.n = T->n;
  memcpy(s.state, u, T->n * sizeof *u);
  s.kappa = kappa_of(T, u);
  s.coefficient = coef_at(T, u);
  s.residual = residual, s.test = test;
  snprintf(s.note, sizeof s.note, "%s", note);
  if (strcmp(label, "EP") && !strchr(label, '?')) T->stats->nspecial++;
  if (T->out && T->out->special && T->out->special(T->out->ctx, &s))
    return SC_ECALLBACK;
  return SC_OK;
}

static double norm_inf(const double *v, size_t n) {
  double m = 0;
  for (size_t i = 0; i < n; i++) m = fmax(m, fabs(v[i]));
  return m;
}

static int emit_point(ntrace *T, const double *u, int branch) {
  if (T->cs.pb.f(u, T->F, T->cs.pb.user)) return SC_OK;
  T->stats->max_residual =
      fmax(T->stats->max_residual, norm_inf(T->F, T->cs.pb.n));
  double coef = coef_at(T, u), re[SC_DIM_TENSOR], im[SC_DIM_TENSOR];
  sc_msg m;
  if (sc_nf_multipliers(T->n, T->g.v->J, re, im, &m)) /* J at u */
    for (size_t i = 0; i < T->n; i++) re[i] = im[i] = NAN;
  sc_curven_point p = {UX(T, u),      UY(T, u), T->n, u, kappa_of(T, u),
                       coef, branch, re,       im};
  T->stats->npoints++;
  if (T->out && T->out->point && T->out->point(T->out->ctx, &p))
    return SC_ECALLBACK;
  return SC_OK;
}

static double dist_inf(const ntrace *T, const double *a, const double *b) {
  double m = 0;
  for (size_t i = 0; i < T->N; i++) m = fmax(m, fabs(a[i] - b[i]));
  return m;
}

/* What a located point is, by its curve and test. */
static const char *what_of(sc_nf_curve kind, const char *label) {
  static const struct {
    const char *label, *fold, *flip, *ns;
  } w[] = {
      {"CP", "cusp: the fold's quadratic coefficient a vanishes", NULL, NULL},
      {"GPD", NULL, "generalized flip: the flip's cubic coefficient b "
                    "vanishes", NULL},
      {"CH", NULL, NULL, "Chenciner: the first Lyapunov coefficient d "
                         "vanishes"},
      {"R1", "1:1 resonance: a double multiplier 1 (the fold's left and "
             "right null vectors orthogonal)", NULL,
       "1:1 resonance: the pair meets at 1 (kappa = 1); beyond, a neutral "
       "saddle"},
      {"R2", NULL, "1:2 resonance: a double multiplier -1",
       "1:2 resonance: the pair meets at -1 (kappa = -1); beyond, a "
       "neutral saddle"},
      {"R3", NULL, NULL, "1:3 resonance: theta = 2 pi / 3 (kappa = -1/2)"},
      {"R4", NULL, NULL, "1:4 resonance: theta = pi / 2 (kappa = 0)"},
      {"LPPD", "fold-flip: a multiplier -1 beside the fold's 1",
       "fold-flip: a multiplier 1 beside the flip's -1", NULL},
      {"LPNS", "fold-Neimark-Sacker: a pair on the unit circle beside the "
               "fold's 1", NULL,
       "fold-Neimark-Sacker: a multiplier 1 beside the pair"},
      {"PDNS", NULL, "flip-Neimark-Sacker: a pair on the unit circle "
                     "beside the flip's -1",
       "flip-Neimark-Sacker: a multiplier -1 beside the pair"},
      {"NSNS", NULL, NULL, "double Neimark-Sacker: a second pair on the "
                           "unit circle"},
  };
  for (size_t i = 0; i < sizeof w / sizeof *w; i++)
    if (strcmp(w[i].label, label) == 0)
      return kind == SC_NF_FOLD   ? w[i].fold
             : kind == SC_NF_FLIP ? w[i].flip
                                  : w[i].ns;
  return NULL;
}

/* A multiplier is on the unit circle, or a pair's product is 1, within
 * this: the eigenvalues of g_x at a located point carry the point's
 * error (1e-10 and below) times their condition; 1e-6 tells a pair on
 * the circle from a real pair mu, 1/mu (a neutral saddle) far apart. */
#define ON_CIRCLE 1e-6

/* Whether the located bialternate zero at u is a pair on the unit circle
 * (a Neimark-Sacker pair) rather than a real pair mu1 mu2 = 1 (a neutral
 * saddle): among the multipliers other than the curve's critical ones,
 * the pair whose product is nearest 1 is complex. */
static int genuine_pair(ntrace *T, const double *u) {
  double re[SC_DIM_TENSOR], im[SC_DIM_TENSOR];
  sc_msg m;
  if (g_eval(&T->g, u, UX(T, u), UY(T, u), SC_EVAL_DERIV) ||
      sc_nf_multipliers(T->n, T->g.v->J, re, im, &m))
    return 0;
  size_t n = T->n;
  int used[SC_DIM_TENSOR] = {0};
  /* the critical ones: the real one nearest +-1, or the pair nearest
   * kappa +- i sqrt(1 - kappa^2) */
  double kap = kappa_of(T, u);
  for (int c = 0; c < (T->kind == SC_NF_NS ? 2 : 1); c++) {
    size_t best = n;
    double bd = HUGE_VAL;
    double tim = T->kind == SC_NF_NS ? (c ? -1 : 1) * sqrt(fmax(0, 1 - kap * kap)) : 0;
    for (size_t i = 0; i < n; i++) {
      double d = hypot(re[i] - kap, im[i] - tim);
      if (!used[i] && d < bd) bd = d, best = i;
    }
    if (best < n) used[best] = 1;
  }
  double bd = HUGE_VAL;
  int complex_pair = 0;
  for (size_t i = 0; i < n; i++)
    for (size_t j = i + 1; j < n; j++) {
      if (used[i] || used[j]) continue;
      double pr = re[i] * re[j] - im[i] * im[j];
      double pi = re[i] * im[j] + im[i] * re[j];
      double d = hypot(pr - 1, pi);
      if (d < bd)
        bd = d, complex_pair = im[i] != 0 && fabs(hypot(re[i], im[i]) - 1) <
                                                 ON_CIRCLE;
    }
  return complex_pair;
}

/* The label and note of the zero of test k located at u: a zero on the
 * neutral-saddle part of an NS curve (|kappa| > 1), or of a bialternate
 * test with a real pair, is not the codimension-two point: its label gets
 * a '?'. */
static void classify(ntrace *T, size_t k, const double *u, double pa,
                     char *label, size_t llen, char *note, size_t nlen) {
  const char *lab = T->labels[k];
  const char *what = what_of(T->kind, lab);
  double kap = kappa_of(T, u);
  int bialt = (T->kind == SC_NF_NS && k == 7) ||
              (T->kind != SC_NF_NS && k == 3);
  if (T->kind == SC_NF_NS && k >= 4 && !(fabs(kap) < 1)) {
    snprintf(label, llen, "%s?", lab);
    snprintf(note, nlen,
             "rejected: on the neutral-saddle part of the curve (kappa = "
             "%.6g, a real pair mu, 1/mu): not a Neimark-Sacker point",
             kap);
    return;
  }
  if (bialt && !genuine_pair(T, u)) {
    snprintf(label, llen, "%s?", lab);
    snprintf(note, nlen,
             "rejected: the multipliers with product 1 are a real pair mu, "
             "1/mu (a neutral saddle), not a pair on the unit circle");
    return;
  }
  snprintf(label, llen, "%s", lab);
  if ((T->kind == SC_NF_FLIP && k == 0) || (T->kind == SC_NF_NS && k == 4))
    snprintf(note, nlen, "%s; %s", what,
             (T->kind == SC_NF_FLIP ? pa > 0 : pa < 0)
                 ? "supercritical to subcritical"
                 : "subcritical to supercritical");
  else
    snprintf(note, nlen, "%s", what ? what : lab);
}

/* Bisections of a chord in pole_on_chord(): 2^-40 of a step. */
#define POLE_BISECTIONS 40

/* Whether test k changes sign between the points a and b through a pole
 * or a jump rather than a zero: a coefficient does so at a resonance
 * where its vectors or resolvents are singular (the fold's a at R1, the
 * flip's b at R2 and LPPD; off the curve next to them, which of two
 * nearby multipliers is the critical one can change).  Bisection of the
 * sign change along the chord from a to b: at a zero |psi| falls to
 * rounding on both sides of the final bracket; at a pole or a jump it
 * stays of the size of its ends (or is not a number).  *pv: the value
 * left of the final bracket. */
static int pole_on_chord(ntrace *T, size_t k, const double *a,
                         const double *b, double pa, double pb, double *pv) {
  double lo = 0, hi = 1, plo = pa, phi = pb, psi[SC_NF_MAXTEST];
  for (int it = 0; it < POLE_BISECTIONS; it++) {
    double t = 0.5 * (lo + hi);
    for (size_t i = 0; i < T->N; i++) T->mid[i] = a[i] + t * (b[i] - a[i]);
    if (tests_at(T->mid, psi, T)) return 0;
    if (!isfinite(psi[k])) { /* singular there: no zero */
      *pv = psi[k];
      return 1;
    }
    if ((plo > 0) == (psi[k] > 0)) lo = t, plo = psi[k];
    else hi = t, phi = psi[k];
  }
  *pv = plo;
  return fmin(fabs(plo), fabs(phi)) > SC_SQRT_EPS * fmax(fabs(pa), fabs(pb));
}

/* Locate the zero of test k between the points a and b (values pa, pb
 * of opposite signs) and report it. */
static int locate(ntrace *T, size_t k, const double *a, const double *b,
                  double pa, double pb) {
  double w = pa / (pa - pb), *u = T->u, *mid = T->mid;
  for (size_t i = 0; i < T->N; i++) mid[i] = u[i] = a[i] + w * (b[i] - a[i]);
  sc_curve_cert cert;
  sc_msg msg;
  char label[8], note[256];
  int st = sc_curve_locate(&T->cs, k, u, &T->acc, &cert, &msg);
  double pv;
  /* a sign change through a pole or a jump is no candidate point: not
   * reported */
  if ((st || !(fabs(cert.psi) <= SC_SQRT_EPS * fmax(fabs(pa), fabs(pb)))) &&
      pole_on_chord(T, k, a, b, pa, pb, &pv))
    return SC_OK;
  if (st) {
    snprintf(label, sizeof label, "%s?", T->labels[k]);
    snprintf(note, sizeof note, "not located: %.200s", sc_msg_what(msg.text));
    return emit_special(T, label, mid, cert.residual, NAN, note);
  }
  /* a sign change across a pole of the test (a coefficient through a
   * resonance) is no zero; nor is a zero far from the bracket */
  double scale = fmax(fabs(pa), fabs(pb));
  if (!(fabs(cert.psi) <= SC_SQRT_EPS * scale) ||
      dist_inf(T, u, mid) > SC_CURVE_BRACKET_REACH * dist_inf(T, a, b)) {
    snprintf(label, sizeof label, "%s?", T->labels[k]);
    snprintf(note, sizeof note,
             "rejected: the sign change is not a zero (test = %.3g, ends "
             "%.3g, %.3g)",
             cert.psi, pa, pb);
    return emit_special(T, label, mid, cert.residual, cert.psi, note);
  }
  classify(T, k, u, pa, label, sizeof label, note, sizeof note);
  return emit_special(T, label, u, cert.residual, cert.psi, note);
}

static int end_point(ntrace *T, const double *u, const char *why) {
  return emit_special(T, "EP", u, NAN, NAN, why);
}

/* The itinerary of g at u into buf ("" if the map fails there); the
 * return value: the evaluation's slip phases (0 for a smooth map, whose
 * itinerary is symbolic only), as the n-dimensional branch watches it. */
static int itinerary_at(ntrace *T, const double *u, char *buf, size_t len) {
  buf[0] = '\0';
  if (g_eval(&T->g, u, UX(T, u), UY(T, u), SC_EVAL_ITINERARY)) return 0;
  snprintf(buf, len, "%s", T->g.v->itinerary);
  return T->g.v->nphases;
}

/* On an event map, whether the accepted point cur has another itinerary
 * of g than the start's: the map is not smooth between prev and cur (a
 * border the curve does not locate), so the direction ends at prev with
 * a row that says so, and no test's sign change across it is located
 * (a coefficient may jump there). */
static int itinerary_changed(ntrace *T, const char *itin0, int *st) {
  char itin[SC_ITIN_LEN], why[256]; /* the notes' length */
  if (!*itin0) return 0; /* a smooth map: nothing to watch */
  itinerary_at(T, T->cur, itin, sizeof itin);
  if (!strcmp(itin, itin0)) return 0;
  size_t k = 0; /* from the phase where they part */
  while (itin[k] && itin[k] == itin0[k]) k++;
  while (k > 0 && itin0[k - 1] != '|') k--; /* its iterate */
  snprintf(why, sizeof why,
           "the itinerary changes between (%.8g, %.8g) and (%.8g, %.8g) "
           "(%s%.32s to %s%.32s): not passed",
           UX(T, T->prev), UY(T, T->prev), UX(T, T->cur), UY(T, T->cur),
           k ? "..." : "", itin0 + k, k ? "..." : "", itin + k);
  *st = end_point(T, T->prev, why);
  return 1;
}

/* The tests at the accepted point cur that changed sign since prev, each
 * located; the point's tests become the next step's (and the fold's q
 * the next reference). */
static int step_tests(ntrace *T) {
  if (tests_at(T->cur, T->psi, T)) return SC_OK;
  double psi[SC_NF_MAXTEST], q[SC_DIM_TENSOR];
  memcpy(psi, T->psi, sizeof psi);
  memcpy(q, T->qnext, sizeof q);
  for (size_t k = 0; k < T->ntest; k++) {
    double a = T->psi_prev[k], b = psi[k];
    if ((a > 0 && b < 0) || (a < 0 && b > 0)) {
      int st = locate(T, k, T->prev, T->cur, a, b);
      if (st) return st;
    }
  }
  memcpy(T->psi_prev, psi, sizeof psi);
  memcpy(T->qref, q, sizeof q);
  T->have_qref = 1;
  return SC_OK;
}

/* The accepted point cur: the box in x, emitted, the curve's ends (the
 * box in y, max points, closing).  1 when the direction ends. */
static int step_accept(ntrace *T, sc_branch *b, int bs, int branch,
                       double far, int *st) {
  const sc_curve_settings *s = T->set;
  double *prev = T->prev, *cur = T->cur;
  if (UX(T, cur) < s->xlo || UX(T, cur) > s->xhi) {
    /* the end on the box's edge: the step's crossing, interpolated and
     * corrected at that x (the state, kappa and y free) */
    double edge = UX(T, cur) < s->xlo ? s->xlo : s->xhi, floor = HUGE_VAL;
    double t = (edge - UX(T, prev)) / (UX(T, cur) - UX(T, prev));
    for (size_t i = 0; i < T->N; i++)
      T->mid[i] = prev[i] + t * (cur[i] - prev[i]);
    UX(T, T->mid) = edge;
    if (sc_curve_correct_fixed_n(&T->cs.pb, T->mid, T->N - 2, &T->acc,
                                 &floor) == SC_OK &&
        floor <= T->acc.newton_ftol) {
      if ((*st = emit_point(T, T->mid, branch))) return 1;
      *st = end_point(T, T->mid, "the box's edge in x (located on it)");
    } else {
      *st = end_point(T, prev, "the box's edge in x (the last point inside)");
    }
    return 1;
  }
  if ((*st = emit_point(T, cur, branch))) return 1;
  memcpy(prev, cur, T->N * sizeof *prev);
  if (bs == SC_END) {
    *st = end_point(T, cur,
                    UY(T, cur) <= s->ylo || UY(T, cur) >= s->yhi
                        ? "the box's edge in y"
                        : "max-points reached");
    return 1;
  }
  /* closed: back within one step of the start after going away */
  if (far > SC_CURVE_CLOSE_HMAX * s->hmax &&
      dist_inf(T, cur, T->u0) < SC_CURVE_CLOSE_STEPS * sc_branch_step_size(b)) {
    T->closed = 1;
    *st = end_point(T, cur, "the curve closes on itself");
    return 1;
  }
  return 0;
}

/* One direction from the start. */
static int run(ntrace *T, int dir, int branch, sc_msg *msg) {
  sc_cont_settings cset;
  sc_curve_cont_settings(T->set, dir, &cset);
  cset.start_free = 1;
  sc_branch *b = NULL;
  int st = sc_mapn_system_init(T->sys, T->u0, msg);
  if (!st) st = sc_branch_alloc(&T->cs.pb, &cset, &T->acc, &b, msg);
  if (!st && (st = sc_branch_set(b, T->u0, msg)))
    st = sc_fail(msg, SC_ENOCONV, "curve: the start is not corrected onto "
                                  "the curve: %.200s",
                 sc_msg_what(msg->text));
  if (st) {
    sc_branch_free(b);
    return st;
  }
  memcpy(T->prev, sc_branch_point(b), T->N * sizeof *T->prev);
  memcpy(T->u0, T->prev, T->N * sizeof *T->prev);
  T->have_qref = 0;
  sc_mapn_system_update(T->sys, T->prev, msg);
  if ((st = emit_point(T, T->prev, branch))) goto done;
  if (tests_at(T->prev, T->psi_prev, T)) {
    st = sc_fail(msg, SC_ENOCONV, "curve: the tests fail at the start");
    goto done;
  }
  memcpy(T->qref, T->qnext, sizeof T->qref);
  T->have_qref = 1;
  char itin0[SC_ITIN_LEN];
  if (!itinerary_at(T, T->prev, itin0, sizeof itin0)) itin0[0] = '\0';
  double far = 0;
  for (;;) {
    sc_msg bm;
    int bs = sc_branch_step(b, &bm);
    if (bs < 0) {
      char why[160];
      snprintf(why, sizeof why, "stopped: %.140s", sc_msg_what(bm.text));
      st = end_point(T, T->prev, why);
      break;
    }
    memcpy(T->cur, sc_branch_point(b), T->N * sizeof *T->cur);
    if (itinerary_changed(T, itin0, &st)) break;
    if (sc_mapn_system_update(T->sys, T->cur, &bm))
      sc_mapn_system_init(T->sys, T->cur, &bm);
    if ((st = step_tests(T))) break;
    far = fmax(far, dist_inf(T, T->cur, T->u0));
    if (step_accept(T, b, bs, branch, far, &st)) break;
  }
done:
  sc_branch_free(b);
  return st;
}

/* kappa at the guess: the complex pair of g_x nearest the unit circle,
 * its real part over its modulus (cos theta). */
static int kappa_guess(ntrace *T, const double *x0, double *kappa,
                       sc_msg *msg) {
  double re[SC_DIM_TENSOR], im[SC_DIM_TENSOR];
  if (g_eval(&T->g, x0, sc_map_get_param(T->g.m, (size_t)T->g.ix),
             sc_map_get_param(T->g.m, (size_t)T->g.iy), SC_EVAL_DERIV))
    return sc_fail(msg, SC_ENOCONV, "curve: the map fails at the start "
                                    "(%.200s)",
                   sc_msg_what(T->g.emsg.text));
  int st = sc_nf_multipliers(T->n, T->g.v->J, re, im, msg);
  if (st) return st;
  double bd = HUGE_VAL;
  for (size_t i = 0; i < T->n; i++) {
    double r = hypot(re[i], im[i]);
    if (im[i] > 0 && fabs(r - 1) < bd) bd = fabs(r - 1), *kappa = re[i] / r;
  }
  if (bd == HUGE_VAL)
    return sc_fail(msg, SC_EINVAL,
                   "curve: no complex pair of multipliers at the start (type "
                   "= ns needs one near the unit circle)");
  return SC_OK;
}

/* The system, its problem and tests, and the work arrays. */
static int setup(ntrace *T, sc_map *m, const sc_curve_settings *set,
                 sc_msg *msg) {
  static const sc_mapn_kind kinds[] = {SC_MAPN_FOLD, SC_MAPN_FLIP, 0,
                                       SC_MAPN_NS};
  sc_mapn_def def;
  memset(&def, 0, sizeof def);
  def.fn = g_fn, def.user = &T->g, def.kind = kinds[set->type];
  def.n = T->n, def.np = T->g.np, def.nfree = 2;
  def.ifree[0] = set->ix, def.ifree[1] = set->iy;
  for (size_t i = 0; i < T->g.np; i++) def.p[i] = sc_map_get_param(m, i);
  int st = sc_mapn_value_alloc(m, SC_EVAL_DERIV | SC_EVAL_DERIV2, &T->g.v, msg);
  if (!st) st = sc_mapn_system_alloc(&def, &T->sys, msg);
  if (!st) st = sc_mapn_system_problem(T->sys, &T->cs.pb, msg);
  if (st) return st;
  T->ntest = sc_nf_curve_ntest(T->kind);
  for (size_t k = 0; k < T->ntest; k++)
    T->labels[k] = sc_nf_curve_label(T->kind, k, NULL);
  T->cs.ntest = T->ntest;
  T->cs.test = tests_at;
  T->cs.labels = T->labels;
  T->cs.user = T;
  T->N = sc_mapn_system_nunknowns(T->sys);
  double *mem = calloc(6 * T->N, sizeof *mem);
  if (!mem) return sc_fail(msg, SC_ENOMEM, "sc_curven_trace: out of memory");
  T->u0 = mem, T->prev = mem + T->N, T->cur = mem + 2 * T->N;
  T->u = mem + 3 * T->N, T->mid = mem + 4 * T->N, T->F = mem + 5 * T->N;
  return SC_OK;
}

int sc_curven_trace(sc_map *m, const sc_curve_settings *set, const double *x0,
                    double kappa0, const sc_curven_output *out,
                    sc_curve_stats *stats, sc_msg *msg) {
  size_t np = sc_map_nparam(m), n = sc_map_dim(m);
  memset(stats, 0, sizeof *stats);
  stats->border_iterate = -1;
  if (set->period < 1 || set->ix < 0 || set->iy < 0 || (size_t)set->ix >= np ||
      (size_t)set->iy >= np || set->ix == set->iy || !(set->h0 > 0) ||
      !(set->hmax >= set->h0) || set->max_points < 1 ||
      !(set->xlo < set->xhi) || !(set->ylo < set->yhi) ||
      (set->type != SC_CURVE_FOLD && set->type != SC_CURVE_FLIP &&
       set->type != SC_CURVE_NS))
    return sc_fail(msg, SC_EINVAL,
                   "sc_curven_trace: bad settings (type fold, flip or ns; "
                   "period %d >= 1, x, y distinct parameters, 0 < h0 <= "
                   "hmax, lo < hi)",
                   set->period);
  if (n < 2 || n > SC_DIM_TENSOR)
    return sc_fail(msg, SC_EINVAL,
                   "sc_curven_trace: model %s has dimension %zu (valid: [2, "
                   "%d]; a one-dimensional map's curves are sc_curve_trace())",
                   sc_map_type(m)->name, n, SC_DIM_TENSOR);
  ntrace T;
  memset(&T, 0, sizeof T);
  T.set = set, T.out = out, T.stats = stats;
  /* a smooth map's iterates carry rounding only: the map's own accuracy
   * (bk2's curves raise it to their rounding floor, sc_curve_ftol()) */
  T.acc = *sc_map_accuracy(m);
  stats->ftol = T.acc.newton_ftol;
  T.n = n;
  T.kind = set->type == SC_CURVE_FOLD   ? SC_NF_FOLD
           : set->type == SC_CURVE_FLIP ? SC_NF_FLIP
                                        : SC_NF_NS;
  T.g.m = m, T.g.period = set->period, T.g.ix = set->ix, T.g.iy = set->iy;
  T.g.n = n, T.g.np = np;
  double xs = sc_map_get_param(m, (size_t)set->ix);
  double ys = sc_map_get_param(m, (size_t)set->iy);
  int st = setup(&T, m, set, msg);
  if (!st) {
    memcpy(T.u0, x0, n * sizeof *x0);
    if (T.kind == SC_NF_NS)
      st = isnan(kappa0) ? kappa_guess(&T, x0, &T.u0[n], msg)
                         : (T.u0[n] = kappa0, SC_OK);
    UX(&T, T.u0) = xs, UY(&T, T.u0) = ys;
  }
  if (!st) st = run(&T, +1, 0, msg);
  if (!st && !T.closed) st = run(&T, -1, 1, msg);
  stats->closed = T.closed;
  sc_map_set_param(m, (size_t)set->ix, xs, NULL);
  sc_map_set_param(m, (size_t)set->iy, ys, NULL);
  sc_mapn_system_free(T.sys);
  sc_mapn_value_free(T.g.v);
  free(T.u0);
  return st;
}
