/* Borders on n-dimensional branches (branchn.h): each segment follows
 * the itinerary codes of its first point; a border of its orbit that
 * changes sign between two accepted points is located by Newton on
 * {g(x, p) - x = 0, m(x, p) = 0} with the exact gradient of m, certified
 * by the residual, and the branch is handed over to the orbit on the
 * other side, started at the border orbit's own points.  docs/maps.md,
 * "Borders in n dimensions". */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/branchn_impl.h"

/* Borders stored per iterate before a list is grown: a piecewise map has
 * a few switching surfaces; the list grows (and the evaluation is
 * repeated) where an orbit has more. */
#define BORDERS_PER_ITERATE 4

/* Rounding level of a Newton step on a border's system, in ulps of the
 * unknown (as the one-dimensional branch, branch_border.c): g is computed
 * to a few ulps and the system's Jacobian amplifies that; a tolerance
 * below it is met at that floor. */
#define BORDER_NOISE_ULPS 256.0

/* A located border point must lie between the two accepted points that
 * bracket its sign change, up to this fraction of their distance (the
 * interpolated start is already inside). */
#define BRACKET_SLACK 0.5
/* ... or this many of their distances for a border with its own code: a
 * switching whose phase lasts as the square root of the distance to it
 * (sc_bordern.alt), where the segment's Jacobian grows without bound and
 * its steps shrink: the sign change is seen a few such steps off the
 * border, which its own smooth system locates. */
#define BRACKET_SLACK_OWN 4.0

/* The side beyond a border is probed at this distance from the border
 * orbit's point, relative to 1 + |x|: far above the rounding of the
 * point (the border's value there is 0 to a few ulps), far below any
 * scale of the map, so the probe is on the other side of this border and
 * of no other. */
#define HANDOVER_REL 1e-7

int sc_bn_border_alloc(sc_branchn *b, sc_msg *msg) {
  b->borders = sc_map_has_borders_n(b->m);
  if (!b->borders) return SC_OK;
  size_t mp = (size_t)b->sp.max_period, cap = BORDERS_PER_ITERATE * mp;
  b->codes = calloc(mp, sizeof *b->codes);
  b->codes2 = calloc(mp, sizeof *b->codes2);
  if (!b->codes || !b->codes2)
    return sc_fail(msg, SC_ENOMEM, "branch: out of memory");
  int st;
  if ((st = sc_bordern_list_alloc(b->m, cap, &b->bl_prev, msg)) ||
      (st = sc_bordern_list_alloc(b->m, cap, &b->bl_cur, msg)) ||
      (st = sc_bordern_list_alloc(b->m, cap, &b->bl_tmp, msg)))
    return st;
  return SC_OK;
}

void sc_bn_border_free(sc_branchn *b) {
  free(b->codes);
  free(b->codes2);
  free(b->codes_pool);
  sc_bordern_list_free(b->bl_prev);
  sc_bordern_list_free(b->bl_cur);
  sc_bordern_list_free(b->bl_tmp);
}

/* g = f^period at (x, p) along @p codes with every border into *@p l
 * (grown and evaluated again where the orbit has more than it holds). */
static int borders_at(sc_branchn *b, int period, const double *x, double p,
                      const sc_itin_code *codes, sc_itin_code *out_codes,
                      sc_bordern_list **l, sc_msg *msg) {
  int st = sc_map_set_param(b->m, b->param, p, msg);
  if (st) return st;
  for (;;) {
    (*l)->n = 0;
    st = sc_map_iterate_n_ex(b->m, x, period, SC_EVAL_DERIV, codes,
                             out_codes, *l, b->v1, msg);
    if (st || (*l)->n <= (*l)->cap) return st;
    sc_bordern_list *g = NULL;
    if ((st = sc_bordern_list_alloc(b->m, 2 * (*l)->n, &g, msg))) return st;
    sc_bordern_list_free(*l);
    *l = g;
  }
}

/* The border of @p l that is @p like (same iterate and name), or NULL. */
static const sc_bordern *find(const sc_bordern_list *l, const sc_bordern *like) {
  for (size_t i = 0; i < l->n && i < l->cap; i++)
    if (l->b[i].iterate == like->iterate &&
        strcmp(l->b[i].name, like->name) == 0)
      return &l->b[i];
  return NULL;
}

int sc_bn_segment_codes(sc_branchn *b, const bn_job *j, sc_msg *msg) {
  size_t n = b->n;
  b->jc.force = NULL;
  if (j->handover) {
    memcpy(b->codes, b->codes_pool + (j->handover - 1),
           (size_t)j->period * sizeof *b->codes);
  } else {
    int st = borders_at(b, j->period, j->u, j->u[n], NULL, b->codes,
                        &b->bl_tmp, msg);
    if (st) return st;
  }
  b->jc.force = b->codes;
  return SC_OK;
}

int sc_bn_border_start(sc_branchn *b, int period, const double *u,
                       sc_msg *msg) {
  return borders_at(b, period, u, u[b->n], b->codes, NULL, &b->bl_prev, msg);
}

/* ------------------------------------------------------------------ */
/* Newton on {g(x, p) - x = 0, m(x, p) = 0}                             */

typedef struct {
  int ok, iterations;
  double u[BN_MAXN + 1], residual, step;
  char why[BN_NOTE];
} border_fix;

static int step_done(double dx, double x, const sc_accuracy *acc) {
  return sc_test_delta(dx, x, acc->newton_atol, acc->newton_rtol) == SC_OK ||
         fabs(dx) <= BORDER_NOISE_ULPS * DBL_EPSILON * (1 + fabs(x));
}

/* The codes a border's system follows: the segment's, with the border's
 * own code in its iterate where it has one (sc_bordern.alt: a switching
 * whose first phase has length zero on it, dropped there, so that the
 * system stays smooth); in codes2, free until the hand-over. */
static const sc_itin_code *system_codes(sc_branchn *b, int period,
                                        const sc_bordern *like) {
  if (!like->alt.n) return b->codes;
  memcpy(b->codes2, b->codes, (size_t)period * sizeof *b->codes2);
  b->codes2[like->iterate] = like->alt;
  return b->codes2;
}

/* The system and its Jacobian at u into F (N) and A (N x N, row-major):
 * rows of g - x, [g_x - I, g_p]; the border's row, [m_x, m_p]. */
static int border_system(sc_branchn *b, int period, const sc_bordern *like,
                         const double *u, double *F, double *A) {
  size_t n = b->n, N = n + 1, ip = b->param;
  if (borders_at(b, period, u, u[n], system_codes(b, period, like), NULL,
                 &b->bl_tmp, NULL))
    return SC_EUNDEF;
  const sc_bordern *bd = find(b->bl_tmp, like);
  if (!bd) return SC_EUNDEF;
  const sc_mapn_value *v = b->v1;
  for (size_t i = 0; i < n; i++) {
    F[i] = v->f[i] - u[i];
    for (size_t k = 0; k < n; k++)
      A[i * N + k] = v->J[i * n + k] - (i == k);
    A[i * N + n] = v->fp[ip * n + i];
  }
  F[n] = bd->value;
  for (size_t k = 0; k < n; k++) A[n * N + k] = bd->dx[k];
  A[n * N + n] = bd->dp[ip];
  return SC_OK;
}

static double max_abs(const double *F, size_t N) {
  double r = 0;
  for (size_t i = 0; i < N; i++) r = fmax(r, fabs(F[i]));
  return r;
}

/* Newton from the linear interpolation between ua (border value ma > 0)
 * and ub (mb <= 0). */
static void locate(sc_branchn *b, int period, const sc_bordern *like,
                   const double *ua, double ma, const double *ub, double mb,
                   border_fix *fx) {
  size_t n = b->n, N = n + 1;
  double F[BN_MAXN + 1], A[(BN_MAXN + 1) * (BN_MAXN + 1)];
  double t = ma / (ma - mb);
  if (!(t >= 0 && t <= 1)) t = 0.5;
  memset(fx, 0, sizeof *fx);
  for (size_t i = 0; i < N; i++) fx->u[i] = ua[i] + t * (ub[i] - ua[i]);
  for (int it = 0; it < b->acc.newton_maxiter; it++) {
    if (border_system(b, period, like, fx->u, F, A)) {
      snprintf(fx->why, sizeof fx->why,
               "the defining system cannot be evaluated at p = %.17g",
               fx->u[n]);
      return;
    }
    for (size_t i = 0; i < N; i++) F[i] = -F[i];
    if (sc_bn_gauss(N, A, F)) {
      snprintf(fx->why, sizeof fx->why,
               "singular Jacobian of the defining system");
      return;
    }
    int small = 1;
    for (size_t i = 0; i < N; i++) {
      fx->u[i] += F[i];
      small &= step_done(F[i], fx->u[i], &b->acc);
    }
    fx->step = fabs(F[n]);
    fx->iterations = it + 1;
    if (!small) continue;
    /* the certificate: the system at the returned point */
    if (border_system(b, period, like, fx->u, F, A)) {
      snprintf(fx->why, sizeof fx->why,
               "the last Newton point cannot be evaluated");
      return;
    }
    fx->residual = max_abs(F, N);
    double lo = fmin(ua[n], ub[n]), hi = fmax(ua[n], ub[n]);
    double w = (like->alt.n ? BRACKET_SLACK_OWN : BRACKET_SLACK) * (hi - lo);
    if (fx->u[n] < lo - w || fx->u[n] > hi + w) {
      snprintf(fx->why, sizeof fx->why,
               "Newton converged to %.17g, outside the bracket [%.17g, "
               "%.17g]", fx->u[n], lo, hi);
      return;
    }
    fx->ok = 1;
    return;
  }
  snprintf(fx->why, sizeof fx->why,
           "Newton did not converge in %d iterations (last step %.3g)",
           b->acc.newton_maxiter, fx->step);
}

/* ------------------------------------------------------------------ */
/* The hand-over                                                        */

/* A code as text: its bytes where printable, else in hex. */
static void code_text(const sc_itin_code *c, char *buf, size_t len) {
  size_t k = 0;
  buf[0] = '\0';
  for (int i = 0; i < c->n && k + 4 < len; i++) {
    unsigned char ch = c->c[i];
    int w = ch >= 0x21 && ch < 0x7f ? snprintf(buf + k, len - k, "%c", ch)
                                    : snprintf(buf + k, len - k, "\\x%02x", ch);
    k += (size_t)w;
  }
}

static int same_code(const sc_itin_code *a, const sc_itin_code *c) {
  return a->n == c->n && memcmp(a->c, c->c, (size_t)a->n) == 0;
}

/* The code of the border's iterate on its other side: the natural code
 * at the border orbit's point x_k moved HANDOVER_REL across the border,
 * along minus the border's gradient in x_k (its normal). */
static int other_side(sc_branchn *b, const sc_bordern *like,
                      const double *u, sc_itin_code *c) {
  size_t n = b->n;
  int k = like->iterate;
  double xk[BN_MAXN];
  if (sc_map_set_param(b->m, b->param, u[n], NULL)) return SC_EINVAL;
  memcpy(xk, u, n * sizeof *xk);
  if (k > 0 && sc_map_iterate_n_ex(b->m, u, k, SC_EVAL_VALUE, b->codes, NULL,
                                   NULL, b->v1, NULL))
    return SC_EUNDEF;
  if (k > 0) memcpy(xk, b->v1->f, n * sizeof *xk);
  b->bl_tmp->n = 0;
  if (sc_map_eval_n_ex(b->m, xk, SC_EVAL_VALUE, &b->codes[k], NULL, b->bl_tmp,
                       b->v1, NULL))
    return SC_EUNDEF;
  sc_bordern one = *like;
  one.iterate = 0;
  const sc_bordern *bd = find(b->bl_tmp, &one);
  if (!bd) return SC_EUNDEF;
  double g2 = 0, xm = 0;
  for (size_t i = 0; i < n; i++) g2 += bd->dx[i] * bd->dx[i];
  for (size_t i = 0; i < n; i++) xm = fmax(xm, fabs(xk[i]));
  if (!(g2 > 0)) return SC_EUNDEF;
  double h = HANDOVER_REL * (1 + xm) / sqrt(g2), probe[BN_MAXN];
  for (size_t i = 0; i < n; i++) probe[i] = xk[i] - h * bd->dx[i];
  return sc_map_eval_n_ex(b->m, probe, SC_EVAL_VALUE, NULL, c, NULL, b->v1,
                          NULL);
}

/* The direction in p of the branch on the other side (codes2) from the
 * border point u: its tangent (x', 1), (g_x - I) x' = -g_p, taken where
 * the border grows (into the side it follows).  0: none. */
static int other_direction(sc_branchn *b, int period, const sc_bordern *like,
                           const double *u) {
  size_t n = b->n, ip = b->param;
  double A[BN_MAXN * BN_MAXN], r[BN_MAXN];
  if (borders_at(b, period, u, u[n], b->codes2, NULL, &b->bl_tmp, NULL))
    return 0;
  const sc_bordern *bd = find(b->bl_tmp, like);
  if (!bd) return 0;
  for (size_t i = 0; i < n; i++) {
    for (size_t k = 0; k < n; k++)
      A[i * n + k] = b->v1->J[i * n + k] - (i == k);
    r[i] = -b->v1->fp[ip * n + i];
  }
  if (sc_bn_gauss(n, A, r)) return 0;
  double rate = bd->dp[ip];
  for (size_t i = 0; i < n; i++) rate += bd->dx[i] * r[i];
  return rate > 0 ? 1 : rate < 0 ? -1 : 0;
}

/* Hand the branch over at the located border point @p u: the segment on
 * the other side, started at u, follows the codes with the border's
 * iterate changed to that side's.  Its outcome into @p note. */
static int hand_over(sc_branchn *b, int period, const sc_bordern *like,
                     const double *u, char *note, size_t len) {
  int k = like->iterate;
  sc_itin_code c;
  char ta[3 * SC_CODE_LEN], tb[3 * SC_CODE_LEN];
  if (other_side(b, like, u, &c)) {
    snprintf(note, len, "; the other side cannot be evaluated: the branch "
                        "ends here");
    return SC_OK;
  }
  if (same_code(&c, &b->codes[k])) {
    snprintf(note, len, "; the itinerary does not change across it: the "
                        "branch ends here");
    return SC_OK;
  }
  memcpy(b->codes2, b->codes, (size_t)period * sizeof *b->codes2);
  b->codes2[k] = c;
  code_text(&b->codes[k], ta, sizeof ta);
  code_text(&c, tb, sizeof tb);
  int dir = other_direction(b, period, like, u);
  if (!dir) {
    snprintf(note, len, "; no orbit of period %d leaves it on the other "
                        "side (iterate %d: %s -> %s): the branch ends here",
             period, k + 1, ta, tb);
    return SC_OK;
  }
  if (sc_bn_grow((void **)&b->codes_pool, &b->poolcap,
                 b->npool + (size_t)period, sizeof *b->codes_pool))
    return SC_ENOMEM;
  memcpy(b->codes_pool + b->npool, b->codes2,
         (size_t)period * sizeof *b->codes_pool);
  bn_job j = {.period = period, .dir = dir, .handover = b->npool + 1};
  b->npool += (size_t)period;
  memcpy(j.u, u, (b->n + 1) * sizeof *u);
  snprintf(j.why, sizeof j.why, "hand-over at %.40s: ", like->name);
  snprintf(note, len, "; the branch continues on the other side (iterate "
                      "%d: %s -> %s), %s %s",
           k + 1, ta, tb, sc_map_type(b->m)->params[b->param].name,
           dir > 0 ? "increasing" : "decreasing");
  return sc_bn_push_job(b, &j);
}

/* Two points of a located orbit are the same where they differ by less
 * than this many times the Newton tolerances to which it is located: a
 * period-m orbit that shrinks onto one of lower period at the border
 * coincides with it there to rounding, while distinct points of an orbit
 * lie far apart on the scale of those tolerances. */
#define SAME_POINT_TOLS 1e3

/* The minimal period of the orbit of u along the segment's codes: the
 * least divisor q of the period with f^q(x) = x. */
static int minimal_period(sc_branchn *b, int period, const double *u) {
  size_t n = b->n;
  const sc_accuracy *acc = &b->acc;
  if (sc_map_set_param(b->m, b->param, u[n], NULL)) return period;
  for (int q = 1; q < period; q++) {
    if (period % q) continue;
    if (sc_map_iterate_n_ex(b->m, u, q, SC_EVAL_VALUE, b->codes, NULL, NULL,
                            b->v1, NULL))
      continue;
    int same = 1;
    for (size_t i = 0; i < n; i++)
      same &= fabs(b->v1->f[i] - u[i]) <=
              SAME_POINT_TOLS * (acc->newton_atol + acc->newton_rtol *
                                 fabs(u[i]));
    if (same) return q;
  }
  return period;
}

/* ------------------------------------------------------------------ */
/* Detection along a segment                                            */

/* Record the border point of @p fx (or, not located, the estimate
 * @p uest with the reason). */
static int record(sc_branchn *b, int branch, int period,
                  const sc_bordern *like, const border_fix *fx,
                  const double *uest, double width) {
  bn_special *s = sc_bn_new_special(b);
  if (!s) return SC_ENOMEM;
  size_t n = b->n;
  const double *u = fx->ok ? fx->u : uest;
  s->label = (sc_branchn_label)(SC_PTN_GR + like->kind);
  s->branch = branch;
  s->period = period;
  s->p = u[n];
  memcpy(s->x, u, n * sizeof *u);
  snprintf(s->border, sizeof s->border, "%s", like->name);
  sc_msg m2;
  if (sc_bn_multipliers(b, period, s->x, s->p, s->re, s->im, &m2))
    for (size_t i = 0; i < n; i++) s->re[i] = s->im[i] = NAN;
  if (!fx->ok) {
    s->method = SC_LOC_FAILED;
    s->error = width;
    snprintf(s->note, sizeof s->note, "NOT LOCATED: %s of iterate %d "
             "(%.30s) changed sign here but %.90s",
             sc_border_label(like->kind), like->iterate + 1, like->name,
             fx->why);
    return SC_OK;
  }
  s->method = SC_LOC_NEWTON;
  s->residual = fx->residual;
  s->error = fx->step;
  s->iterations = fx->iterations;
  size_t k = (size_t)snprintf(s->note, sizeof s->note,
                              "%s of iterate %d: %.40s; Newton on {g = x, "
                              "border = 0}",
                              sc_border_label(like->kind), like->iterate + 1,
                              like->name);
  if (k >= sizeof s->note) return SC_OK;
  int q = minimal_period(b, period, fx->u);
  if (q < period) {
    /* the period-m orbit is born from (or dies into) the period-q orbit
     * at the border: the other side has no period-m orbit from here */
    snprintf(s->note + k, sizeof s->note - k,
             "; the orbit has minimal period %d here (born at the border): "
             "the branch ends here", q);
    return SC_OK;
  }
  return hand_over(b, period, like, fx->u, s->note + k, sizeof s->note - k);
}

int sc_bn_border_step(sc_branchn *b, int branch, int period,
                      const double *uprev, const double *u, int *crossed,
                      double *ub, sc_msg *msg) {
  size_t n = b->n;
  *crossed = 0;
  if (borders_at(b, period, u, u[n], b->codes, NULL, &b->bl_cur, NULL))
    return SC_OK; /* the corrector accepted it: this does not happen */
  border_fix best = {0}, fx;
  sc_bordern bbest = {0}, bfail = {0};
  char whyfail[BN_NOTE] = "";
  int nchanged = 0;
  for (size_t i = 0; i < b->bl_cur->n && i < b->bl_cur->cap; i++) {
    const sc_bordern *c = &b->bl_cur->b[i];
    const sc_bordern *a = c->value > 0 ? NULL : find(b->bl_prev, c);
    if (!a || !(a->value > 0)) continue;
    nchanged++;
    locate(b, period, c, uprev, a->value, u, c->value, &fx);
    if (!fx.ok) {
      if (!whyfail[0]) bfail = *c, snprintf(whyfail, sizeof whyfail, "%s",
                                            fx.why);
      continue;
    }
    if (!best.ok || fabs(fx.u[n] - uprev[n]) < fabs(best.u[n] - uprev[n]))
      best = fx, bbest = *c;
  }
  if (!nchanged) {
    sc_bordern_list *t = b->bl_prev;
    b->bl_prev = b->bl_cur;
    b->bl_cur = t;
    return SC_OK;
  }
  int st;
  if (best.ok) {
    *crossed = 1;
    memcpy(ub, best.u, (n + 1) * sizeof *ub);
    st = record(b, branch, period, &bbest, &best, NULL, 0);
  } else {
    *crossed = 2;
    snprintf(best.why, sizeof best.why, "%s", whyfail);
    st = record(b, branch, period, &bfail, &best, u, fabs(u[n] - uprev[n]));
  }
  sc_map_set_param(b->m, b->param, u[n], NULL);
  return st == SC_ENOMEM ? sc_fail(msg, st, "branch: out of memory") : st;
}
