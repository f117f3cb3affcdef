/* Numerical flows for bk2: the same equations of motion integrated with a
 * GSL odeiv2 embedded Runge-Kutta pair (Prince-Dormand 8(9)), with the
 * variational equations alongside when derivatives are asked for.  Used
 * to cross-check the closed forms (flows = numerical) and for friction
 * laws without closed forms (velocity weakening).
 *
 * Events: after every accepted step each guard g is interpolated by the
 * cubic Hermite polynomial through g and g' at both ends; its first root
 * in the step is isolated exactly (between the cubic's critical points)
 * and then refined on the true solution by Newton steps, each integrating
 * from the step's start.  A step is never longer than a tenth of the
 * fastest free period, so a guard cannot turn twice inside one step
 * unseen at the integration tolerance.  This is as far as the first-root
 * discipline of the exact flows carries over to numerical ones. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "hybrid/hybrid_impl.h"
#include "models/bk2_impl.h"

#define NSTATE 4
#define NDIR_BK2 6
#define DIM_MAX (NSTATE * (1 + NDIR_BK2))
/* Fraction of the fastest free period allowed as one step. */
#define STEP_FRACTION 0.1
/* Newton refinements of an event time on the true solution. */
#define EVENT_NEWTON_MAX 8
/* Rounding bound on a guard value, in ulps of the state's size. */
#define GUARD_ROUND_ULPS 16.0
/* Same horizon as the exact flows: slow periods without an event. */
#define PHASE_PERIODS 16

struct bk2_num {
  gsl_odeiv2_step *step[2];   /* [0]: state only; [1]: with sensitivities */
  gsl_odeiv2_control *ctrl[2];
  gsl_odeiv2_evolve *evol[2];
  double atol, rtol;
};

typedef struct {
  const bk2_inst *b;
  int mode, nd;
} rhs_ctx;

static int slipping(int mode, int i) {
  return mode == SC_BK2_SLIP12 || mode == i;
}

/* Kinetic force of block i at velocity u and its derivative in u and in
 * the parameters (directions 1..5 = alpha, beta, phi, v, gamma). */
static double kinetic(const bk2_inst *b, int i, double u, double *dk_du,
                      double dk_dp[NDIR_BK2]) {
  double t = i == 1 ? 1 : b->beta;
  for (int k = 0; k < NDIR_BK2; k++) dk_dp[k] = 0;
  if (!b->vw) {
    *dk_du = 0;
    dk_dp[3] = -t * b->mu * b->mu; /* d(mu)/d(phi) = -mu^2 */
    if (i == 2) dk_dp[2] = b->mu;
    return t * b->mu;
  }
  /* K = T / (1 + gamma |u - Vs|) */
  double g = b->gamma, rel = u - b->vs, den = 1 + g * fabs(rel);
  double sgn = rel > 0 ? 1 : rel < 0 ? -1 : 0;
  *dk_du = -t * g * sgn / (den * den);
  if (i == 2) dk_dp[2] = 1 / den;
  if (!b->frozen) dk_dp[4] = t * g * sgn / (den * den); /* through Vs = v */
  dk_dp[5] = -t * fabs(rel) / (den * den);
  return t / den;
}

static int rhs(double t, const double y[], double dy[], void *vp) {
  (void)t;
  const rhs_ctx *c = vp;
  const bk2_inst *b = c->b;
  double a = b->alpha;
  double s[2] = {(1 + a) * y[0] - a * y[1], (1 + a) * y[1] - a * y[0]};
  double dk_du[2] = {0, 0}, dk_dp[2][NDIR_BK2] = {{0}};
  dy[0] = y[2];
  dy[1] = y[3];
  for (int i = 0; i < 2; i++) {
    dy[2 + i] = 0;
    if (slipping(c->mode, i + 1))
      dy[2 + i] = kinetic(b, i + 1, y[2 + i], &dk_du[i], dk_dp[i]) - s[i];
  }
  /* Directions not carried (gamma with Coulomb friction) stay zero: the
   * system has room for all of them. */
  for (int k = c->nd; c->nd > 0 && k < NDIR_BK2; k++)
    for (int q = 0; q < NSTATE; q++) dy[NSTATE * (k + 1) + q] = 0;
  /* Variational equations s_k' = J s_k + df/dtheta_k. */
  for (int k = 0; k < c->nd; k++) {
    const double *z = y + NSTATE * (k + 1);
    double *dz = dy + NSTATE * (k + 1);
    dz[0] = z[2];
    dz[1] = z[3];
    for (int i = 0; i < 2; i++) {
      dz[2 + i] = 0;
      if (!slipping(c->mode, i + 1)) continue;
      int j = 1 - i;
      double ds = (1 + a) * z[i] - a * z[j];
      double fp = dk_dp[i][k];
      if (k == 1) fp -= y[i] - y[j]; /* dS_i/dalpha = Y_i - Y_j */
      dz[2 + i] = dk_du[i] * z[2 + i] - ds + fp;
    }
  }
  return GSL_SUCCESS;
}

static void num_release(bk2_inst *b) {
  bk2_num *n = b->num;
  if (!n) return;
  for (int i = 0; i < 2; i++) {
    if (n->evol[i]) gsl_odeiv2_evolve_free(n->evol[i]);
    if (n->ctrl[i]) gsl_odeiv2_control_free(n->ctrl[i]);
    if (n->step[i]) gsl_odeiv2_step_free(n->step[i]);
  }
  free(n);
  b->num = NULL;
}

static int num_setup(bk2_inst *b, sc_msg *msg) {
  if (b->num && b->num->atol == b->acc.ode_atol &&
      b->num->rtol == b->acc.ode_rtol)
    return SC_OK;
  num_release(b);
  bk2_num *n = calloc(1, sizeof *n);
  if (!n) goto fail;
  b->num = n;
  n->atol = b->acc.ode_atol;
  n->rtol = b->acc.ode_rtol;
  for (int i = 0; i < 2; i++) {
    size_t dim = i ? DIM_MAX : NSTATE;
    n->step[i] = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, dim);
    n->ctrl[i] = gsl_odeiv2_control_y_new(n->atol, n->rtol);
    n->evol[i] = gsl_odeiv2_evolve_alloc(dim);
    if (!n->step[i] || !n->ctrl[i] || !n->evol[i]) goto fail;
  }
  return SC_OK;
fail:
  num_release(b);
  return sc_fail(msg, SC_ENOMEM, "bk2: cannot allocate the ODE workspace");
}

/* Rounding bound on a guard value at state y. */
static double round_guard(const bk2_inst *b, const double *y) {
  double scale = fabs(y[0]) + fabs(y[1]) + fabs(y[2]) + fabs(y[3]) + 1;
  return GUARD_ROUND_ULPS * DBL_EPSILON * (1 + b->alpha) * scale;
}

/* Pack duals into the ODE vector and back. */
static void pack(const bk2_state *x, int nd, double *y) {
  const sc_dual *xs[4] = {&x->y1, &x->y2, &x->u1, &x->u2};
  for (int i = 0; i < NSTATE; i++) {
    y[i] = xs[i]->v;
    for (int k = 0; k < nd; k++) y[NSTATE * (k + 1) + i] = xs[i]->d[k];
  }
}

static void unpack(const double *y, int nd, bk2_state *x) {
  sc_dual *xs[4] = {&x->y1, &x->y2, &x->u1, &x->u2};
  for (int i = 0; i < NSTATE; i++) {
    *xs[i] = sc_dconst(y[i], nd);
    for (int k = 0; k < nd; k++) xs[i]->d[k] = y[NSTATE * (k + 1) + i];
  }
}

/* Guard kinds: 1, 2 re-stick of block i; 3 threshold of the stuck block. */
static double guard(const bk2_inst *b, int mode, int kind, const double *y,
                    const double *dy, double *slope) {
  double a = b->alpha;
  if (kind < 3) {
    *slope = dy[1 + kind];
    return y[1 + kind] - b->vs;
  }
  int j = mode == SC_BK2_SLIP1 ? 1 : 0; /* index of the stuck block */
  int i = 1 - j;
  double tj = j == 1 ? b->beta : 1;
  *slope = (1 + a) * dy[j] - a * dy[i];
  return (1 + a) * y[j] - a * y[i] - tj;
}

/* First root in (0, h] of the cubic Hermite interpolant of (g0, d0) at 0
 * and (g1, d1) at h where it crosses zero in direction dir (+1 rising,
 * -1 falling); skip a root at 0 if `skip0`.  Returns -1 if none. */
static double hermite_root(double g0, double d0, double g1, double d1,
                           double h, int skip0, int dir) {
  /* H(s) = c0 + c1 s + c2 s^2 + c3 s^3 */
  double c0 = g0, c1 = d0;
  double c2 = (3 * (g1 - g0) / h - 2 * d0 - d1) / h;
  double c3 = (d0 + d1 - 2 * (g1 - g0) / h) / (h * h);
  /* critical points: c1 + 2 c2 s + 3 c3 s^2 = 0 */
  double cuts[4] = {0}, nc = 1;
  double A = 3 * c3, B = 2 * c2, C = c1;
  if (A != 0) {
    double disc = B * B - 4 * A * C;
    if (disc >= 0) {
      double q = -0.5 * (B + copysign(sqrt(disc), B));
      double r1 = q / A, r2 = q != 0 ? C / q : r1;
      if (r1 > r2) {
        double tmp = r1;
        r1 = r2, r2 = tmp;
      }
      if (r1 > 0 && r1 < h) cuts[(int)nc++] = r1;
      if (r2 > 0 && r2 < h && r2 != r1) cuts[(int)nc++] = r2;
    }
  } else if (B != 0) {
    double r = -C / B;
    if (r > 0 && r < h) cuts[(int)nc++] = r;
  }
  cuts[(int)nc] = h;
  for (int p = 0; p < (int)nc; p++) {
    double lo = cuts[p], hi = cuts[p + 1];
    /* H is monotone on each piece: starting at the skipped root, the first
     * piece moves away from zero and holds no other root. */
    if (p == 0 && skip0) continue;
    double flo = c0 + lo * (c1 + lo * (c2 + lo * c3));
    double fhi = c0 + hi * (c1 + hi * (c2 + hi * c3));
    /* Events are guards rising through zero (docs/model.md), maxima are
     * g' falling through it: a piece crossing the other way is passed.
     * With velocity weakening a slip starts with U' = K - T = 0, so
     * rounding may make the guard rise first and then fall back through
     * zero: not a re-stick. */
    if (dir > 0 ? !(flo < 0 && fhi >= 0) : !(flo > 0 && fhi <= 0)) continue;
    if (fhi == 0) return hi;
    for (int it = 0; it < 200 && hi - lo > 4 * DBL_EPSILON * hi; it++) {
      double m = 0.5 * (lo + hi);
      double fm = c0 + m * (c1 + m * (c2 + m * c3));
      if ((fm > 0) == (flo > 0)) lo = m, flo = fm;
      else hi = m;
    }
    return 0.5 * (lo + hi);
  }
  return -1;
}

/* Integrate y from t0 to t1 (the evolve object restarted). */
static int advance_to(bk2_num *n, int w, gsl_odeiv2_system *sys, double t0,
                      double t1, double hmax, double *y) {
  gsl_odeiv2_evolve_reset(n->evol[w]);
  gsl_odeiv2_step_reset(n->step[w]);
  double t = t0, h = fmin(hmax, t1 - t0);
  while (t < t1) {
    double hc = fmin(h, hmax);
    int st = gsl_odeiv2_evolve_apply(n->evol[w], n->ctrl[w], n->step[w], sys,
                                     &t, t1, &hc, y);
    if (st != GSL_SUCCESS) return st;
    h = hc;
  }
  return GSL_SUCCESS;
}

/* One accepted step of at most hmax towards tend (h: the step to try,
 * updated). */
static int num_step(bk2_num *n, int w, gsl_odeiv2_system *sys, double *t,
                    double tend, double *h, double hmax, double *y, int mode,
                    sc_msg *msg) {
  double hc = fmin(*h, hmax);
  int st = gsl_odeiv2_evolve_apply(n->evol[w], n->ctrl[w], n->step[w], sys,
                                   t, tend, &hc, y);
  if (st != GSL_SUCCESS)
    return sc_fail(msg, SC_ENOCONV,
                   "bk2: ODE integration failed in mode %d at tau = %.6g "
                   "(GSL: %s)",
                   mode, *t, gsl_strerror(st));
  *h = hc;
  return SC_OK;
}

static double fastest_period(const bk2_inst *b, int mode) {
  return 2 * SC_PI / (mode == SC_BK2_SLIP12 ? b->w2 : b->w1);
}

/* The state at an event, its sensitivities shifted by the event time's,
 * and the mode that follows (the same rule as the exact flows). */
static int finish_event(const bk2_dpar *P, int mode, int kind,
                        const double *yt, const double *dyt, double slope,
                        bk2_state *x) {
  unpack(yt, P->nd, x);
  double acc2[2] = {dyt[2], dyt[3]};
  return sc_bk2_take_event(P, mode, kind, slope, acc2, x);
}

/* ---- borders along a numerical phase ---------------------------------- */

/* g' and g'' of guard `kind` at state y with derivative dy (Coulomb
 * friction: K_i does not depend on U_i, so U_i'' = -S_i'). */
static double guard_prime(const bk2_inst *b, int mode, int kind,
                          const double *y, const double *dy, double *g2) {
  double a = b->alpha;
  if (kind < 3) {
    int i = kind - 1, j = 1 - i;
    /* U_i'' = dK_i/dU_i U_i' - S_i' (velocity weakening: K_i depends on
     * U_i; Coulomb: dK/dU = 0) */
    double dk_du, dk_dp[NDIR_BK2];
    kinetic(b, kind, y[2 + i], &dk_du, dk_dp);
    *g2 = dk_du * dy[2 + i] - ((1 + a) * y[2 + i] - a * y[2 + j]);
    return dy[2 + i];
  }
  int j = mode == SC_BK2_SLIP1 ? 1 : 0, i = 1 - j;
  *g2 = (1 + a) * dy[2 + j] - a * dy[2 + i];
  return (1 + a) * dy[j] - a * dy[i];
}

/* The guard of `kind` on duals at a state y (sensitivities at fixed
 * time), as the exact flows' guard_dual(). */
static sc_dual guard_at(const bk2_dpar *P, int mode, int kind,
                        const double *y) {
  int nd = P->nd;
  bk2_state xs;
  unpack(y, nd, &xs);
  kind = BK2_GUARD_OF(kind);
  if (kind == BK2_EV_RESTICK1) return sc_dsub(xs.u1, P->vs, nd);
  if (kind == BK2_EV_RESTICK2) return sc_dsub(xs.u2, P->vs, nd);
  double a = P->alpha.v;
  (void)a;
  sc_dual s1 = sc_dadd(xs.y1, sc_dmul(P->alpha, sc_dsub(xs.y1, xs.y2, nd), nd),
                       nd);
  sc_dual s2 = sc_dadd(xs.y2, sc_dmul(P->alpha, sc_dsub(xs.y2, xs.y1, nd), nd),
                       nd);
  return mode == SC_BK2_SLIP1 ? sc_dsub(s2, P->t2, nd) : sc_daddc(s1, -1);
}

/* Refine a zero of w = g (order 0) or g' (order 1) of guard `kind` near
 * tg in [t0, t1] by Newton's method on the true solution, integrating
 * from (t0, y0) each time; the state there into yt, dyt. */
static void refine(const bk2_inst *b, int w, gsl_odeiv2_system *sys,
                   int mode, int kind, int order, double t0, const double *y0,
                   double t1, double hmax, double *tg, double *yt,
                   double *dyt) {
  double te = *tg;
  for (int it = 0; it < EVENT_NEWTON_MAX; it++) {
    memcpy(yt, y0, DIM_MAX * sizeof *yt);
    if (te > t0 && advance_to(b->num, w, sys, t0, te, hmax, yt)) break;
    rhs(te, yt, dyt, sys->params);
    double d1, d2, v = order ? guard_prime(b, mode, kind, yt, dyt, &d2)
                             : guard(b, mode, kind, yt, dyt, &d1);
    double slope = order ? d2 : d1;
    if (slope == 0) break;
    double dt = -v / slope, tn = fmin(fmax(te + dt, t0), t1);
    double tol = b->acc.event_atol + b->acc.event_rtol * te;
    te = tn;
    if (fabs(dt) <= tol) break;
  }
  memcpy(yt, y0, DIM_MAX * sizeof *yt);
  if (te > t0) advance_to(b->num, w, sys, t0, te, hmax, yt);
  rhs(te, yt, dyt, sys->params);
  *tg = te;
}

/* What a scan of a numerical phase finds for one guard. */
typedef struct {
  int kind;
  int nmax;            /* maxima passed so far */
  double gbest;        /* the highest maximum before the event */
  double ybest[DIM_MAX];
  double tnth;         /* the n-th maximum (ATMAX) */
  double ynth[DIM_MAX], dynth[DIM_MAX];
  int have_root;       /* its first rise through zero */
  double troot, sroot;
  double yroot[DIM_MAX];
  int have_after;      /* its first maximum after the event */
  double yafter[DIM_MAX];
} scan_guard;

/* Integrate a phase again from its start y0 and watch every guard:
 * maxima (before tevent; the nth one, when nth > 0, ends the scan),
 * first rises through zero, the first maximum after tevent.  The scan
 * goes past tevent until what the borders need is found, or the horizon
 * tmax. */
static int num_scan(const bk2_inst *b, const bk2_dpar *P, int mode,
                    int fresh, const double *ystart, double tevent,
                    int ekind, double tmax, int nth, scan_guard *sg, int ng,
                    sc_msg *msg) {
  bk2_num *n = b->num;
  int nd = P->nd, w = nd > 0;
  rhs_ctx ctx = {b, mode, nd};
  gsl_odeiv2_system sys = {rhs, NULL, w ? DIM_MAX : NSTATE, &ctx};
  double y[DIM_MAX] = {0}, y0[DIM_MAX], dy0[DIM_MAX], dy1[DIM_MAX];
  double yt[DIM_MAX], dyt[DIM_MAX];
  memcpy(y, ystart, sizeof y);
  double hmax = STEP_FRACTION * fastest_period(b, mode);
  double t = 0, h = hmax * 0.1, tol = b->acc.event_atol;
  gsl_odeiv2_evolve_reset(n->evol[w]);
  gsl_odeiv2_step_reset(n->step[w]);
  rhs(0, y, dy0, &ctx);
  for (int k = 0; k < ng; k++) sg[k].gbest = -HUGE_VAL;
  while (t < tmax) {
    double t0 = t;
    memcpy(y0, y, sizeof y);
    int st = num_step(n, w, &sys, &t, tmax, &h, hmax, y, mode, msg);
    if (st) return st;
    rhs(t, y, dy1, &ctx);
    int done = t > tevent;
    for (int k = 0; k < ng; k++) {
      scan_guard *q = &sg[k];
      int ending = q->kind == BK2_GUARD_OF(ekind);
      /* a maximum: g' falls through zero in this step */
      double a0, a1, p0 = guard_prime(b, mode, q->kind, y0, dy0, &a0);
      double p1 = guard_prime(b, mode, q->kind, y, dy1, &a1);
      double r = hermite_root(p0, a0, p1, a1, t - t0, t0 == 0, -1);
      if (r >= 0 && p0 > 0 && !(p1 > 0)) {
        double tm = t0 + r;
        refine(b, w, &sys, mode, q->kind, 1, t0, y0, t, hmax, &tm, yt, dyt);
        double s1, gv = guard(b, mode, q->kind, yt, dyt, &s1);
        if (tm < tevent - tol) {
          q->nmax++;
          if (nth > 0 && ending && q->nmax == nth) {
            q->tnth = tm;
            memcpy(q->ynth, yt, sizeof yt);
            memcpy(q->dynth, dyt, sizeof dyt);
            return SC_OK;
          }
          if (gv > q->gbest) q->gbest = gv, memcpy(q->ybest, yt, sizeof yt);
        } else if (ending && !q->have_after && tm > tevent + tol) {
          q->have_after = 1;
          memcpy(q->yafter, yt, sizeof yt);
        }
      }
      /* its first rise through zero */
      if (!ending && !q->have_root && q->kind < 3) {
        double s0, s1, g0 = guard(b, mode, q->kind, y0, dy0, &s0);
        double g1 = guard(b, mode, q->kind, y, dy1, &s1);
        int skip = t0 == 0 && (fresh & q->kind);
        double rr = hermite_root(g0, s0, g1, s1, t - t0, skip, 1);
        if (rr >= 0 && g1 > g0) {
          double tr = t0 + rr;
          refine(b, w, &sys, mode, q->kind, 0, t0, y0, t, hmax, &tr, yt, dyt);
          double sl;
          guard(b, mode, q->kind, yt, dyt, &sl);
          q->have_root = 1, q->troot = tr, q->sroot = sl;
          memcpy(q->yroot, yt, sizeof yt);
        }
      }
      if (!ending && q->kind < 3 && !q->have_root) done = 0;
      if (ending && q->kind < 3 && !q->have_after) done = 0;
    }
    /* the refinements restarted the integrator: go on from the step */
    gsl_odeiv2_evolve_reset(n->evol[w]);
    gsl_odeiv2_step_reset(n->step[w]);
    memcpy(dy0, dy1, sizeof dy1);
    if (done) break;
  }
  return SC_OK;
}

/* The borders of a numerical phase, named and signed as the exact
 * flows' (phase_borders() in bk2.c). */
static int num_borders(const bk2_inst *b, const bk2_dpar *P, int mode,
                       int fresh, const double *ystart, double te,
                       int ekind, const sc_dual *Td, const double *yatmax,
                       bk2_events *ev, sc_msg *msg) {
  int nd = P->nd;
  scan_guard sg[3];
  int ng = 0;
  memset(sg, 0, sizeof sg);
  if (slipping(mode, 1)) sg[ng++].kind = 1;
  if (slipping(mode, 2)) sg[ng++].kind = 2;
  if (mode != SC_BK2_SLIP12) sg[ng++].kind = 3;
  double tmax = te + PHASE_PERIODS * 2 * SC_PI;
  int st = num_scan(b, P, mode, fresh, ystart, te, ekind, tmax, 0, sg, ng,
                    msg);
  if (st) return st;
  char name[2 * SC_BORDER_NAME];
  const char *mn = bk2_mode_name(mode);
  int eg = BK2_GUARD_OF(ekind);
  for (int k = 0; k < ng; k++) {
    scan_guard *q = &sg[k];
    if (q->kind == eg && eg < 3 && (q->have_after || yatmax) &&
        !BK2_IS_BOTH(ekind)) {
      sc_dual m = guard_at(P, mode, q->kind, yatmax ? yatmax : q->yafter);
      snprintf(name, sizeof name, "%s max after the event, phase %d (slip %s)",
               bk2_guard_text(q->kind), ev->phase, mn);
      sc_bk2_border_add(ev->borders, SC_BORDER_GRAZING, &m, name);
      sc_bk2_patch(ev, ekind | BK2_EV_ATMAX, q->nmax, 0);
    }
    if (q->gbest > -HUGE_VAL) {
      sc_dual m = sc_dscale(guard_at(P, mode, q->kind, q->ybest), -1, nd);
      snprintf(name, sizeof name, "%s max, phase %d (slip %s)",
               bk2_guard_text(q->kind), ev->phase, mn);
      sc_bk2_border_add(ev->borders,
                        q->kind < 3 ? SC_BORDER_GRAZING : SC_BORDER_TOUCH, &m,
                        name);
    }
    if (q->kind == eg || q->kind >= 3 || !q->have_root) continue;
    sc_dual g = guard_at(P, mode, q->kind, q->yroot);
    sc_dual m = sc_dconst(q->troot - te, nd);
    for (int j = 0; j < nd; j++) m.d[j] = -g.d[j] / q->sroot - Td->d[j];
    snprintf(name, sizeof name, "%s rise after the event, phase %d (slip %s)",
             bk2_guard_text(q->kind), ev->phase, mn);
    sc_bk2_border_add(ev->borders,
                      ekind == BK2_EV_THRESHOLD ? SC_BORDER_CROSSING
                                                : SC_BORDER_BOTH,
                      &m, name);
    if (ekind != BK2_EV_THRESHOLD && !BK2_IS_BOTH(ekind))
      sc_bk2_patch(ev, eg == BK2_EV_RESTICK1 ? BK2_EV_BOTH : BK2_EV_BOTH2, 0,
                   1);
  }
  return SC_OK;
}

/* A phase forced to end at the (skip + 1)-th local maximum of re-stick
 * guard `kind` (a grazing's own code). */
static int num_phase_at_max(const bk2_inst *b, const bk2_dpar *P, int mode,
                            int fresh, const double *ystart, int kind,
                            int skip, bk2_state *x, double *duration,
                            bk2_events *ev, sc_msg *msg) {
  if (kind >= 3)
    return sc_fail(msg, SC_EINVAL,
                   "bk2: a code that ends a slip at a threshold's maximum");
  scan_guard sg;
  memset(&sg, 0, sizeof sg);
  sg.kind = kind;
  double tmax = PHASE_PERIODS * 2 * SC_PI;
  int st = num_scan(b, P, mode, fresh, ystart, tmax, kind, tmax, skip + 1,
                    &sg, 1, msg);
  if (st) return st;
  if (sg.nmax < skip + 1)
    return sc_fail(msg, SC_EUNDEF,
                   "bk2: the forced grazing event of slip mode %d needs %d "
                   "maxima of its guard, found %d",
                   mode, skip + 1, sg.nmax);
  double g2;
  guard_prime(b, mode, kind, sg.ynth, sg.dynth, &g2);
  *duration = sg.tnth;
  ev->rec[0] = (unsigned char)(kind | BK2_EV_ATMAX);
  ev->rec[1] = (unsigned char)skip;
  if (ev->borders) {
    sc_dual Td = sc_dconst(sg.tnth, P->nd); /* dt = -dg'/g'' */
    bk2_state xs;
    unpack(sg.ynth, P->nd, &xs);
    sc_dual K = kind == 1 ? P->k1 : P->k2;
    sc_dual yi = kind == 1 ? xs.y1 : xs.y2, yj = kind == 1 ? xs.y2 : xs.y1;
    sc_dual S = sc_dadd(yi, sc_dmul(P->alpha, sc_dsub(yi, yj, P->nd), P->nd),
                        P->nd);
    sc_dual gp = sc_dsub(K, S, P->nd);
    for (int j = 0; j < P->nd; j++) Td.d[j] = -gp.d[j] / g2;
    st = num_borders(b, P, mode, fresh, ystart, sg.tnth, kind, &Td, sg.ynth,
                     ev, msg);
    if (st) return st;
  }
  unpack(sg.ynth, P->nd, x);
  double acc2[2] = {sg.dynth[2], sg.dynth[3]};
  return sc_bk2_take_event_at_max(P, mode, kind, g2, acc2, x);
}

/* ---- one slip phase ------------------------------------------------------
 * num_phase() in named steps: the candidate guards (phase_guards()), an
 * event at the phase's very start (start_event()), the march with the
 * first root in each step (step_root()), the event time on the true
 * solution (locate_event()), the tie rules (resolve_ties()) and the state
 * after it (end_phase()). */

/* Whether the re-stick guard g = U_i - Vs of slipping block `kind`, within
 * rounding of zero at state y, arrives at zero from the slipping side (a
 * re-stick) rather than leaves it.  A block slips slower than the surface,
 * U_i < Vs, from the moment it comes loose until U_i climbs back to Vs
 * (docs/model.md), so a re-stick is U_i returning to Vs after having left it:
 * g' > 0, or g' within rounding and g'' > 0.  A block that has just come
 * loose leaves: U_i' = K_i - S_i is K_i - T_i < 0 at its start with
 * Coulomb friction and 0 with velocity weakening (K_i(Vs) = T_i), and then
 * U_i'' = -S_i' < 0, so for a while both g and g' lie below their rounding
 * and only g'' tells the way (the other block triggered 1e-6 after it next
 * to d*, g ~ -1e-14: not a re-stick).  A maximum of g that touches zero
 * (g' ~ 0, g'' < 0) counts as no re-stick: it is a grazing's border, where
 * the map takes either side.  U_i' = K_i - S_i is rounded like S_i, so
 * like the guards (round_guard()). */
static int restick_arrives(const bk2_inst *b, int mode, int kind,
                           const double *y, const double *dy) {
  double g2, g1 = guard_prime(b, mode, kind, y, dy, &g2);
  double E = round_guard(b, y);
  return g1 > E || (g1 >= -E && g2 > 0);
}

/* The guards that may end a phase of `mode` (kinds: 1, 2 re-stick of
 * block i; 3 threshold of the stuck block), or with a forced code the
 * forced one alone (*both: it ends the slip of both blocks).  Returns
 * their number, or a negative status. */
static int phase_guards(const bk2_events *ev, int mode, int kinds[3],
                        int *both, sc_msg *msg) {
  int ng = 0;
  *both = 0;
  if (slipping(mode, 1)) kinds[ng++] = 1;
  if (slipping(mode, 2)) kinds[ng++] = 2;
  if (mode != SC_BK2_SLIP12) kinds[ng++] = 3;
  if (!ev->force) return ng;
  /* Follow the code: only the forced guard ends the phase. */
  /* the guard is the code's event without the flag "at its maximum" (a
   * grazing's own system), as in the exact flows */
  int want = ev->force[0], kind = want & ~BK2_EV_ATMAX;
  int gk = BK2_GUARD_OF(kind), ok = 0;
  for (int i = 0; i < ng; i++) ok |= kinds[i] == gk;
  if (!ok || (BK2_IS_BOTH(kind) && mode != SC_BK2_SLIP12))
    return sc_fail(msg, SC_EINVAL,
                   "bk2: the forced itinerary code does not fit slip mode "
                   "%d (event %d)",
                   mode, want);
  if (!(want & BK2_EV_ATMAX) && ev->force[1] > 0)
    return sc_fail(msg, SC_EINVAL,
                   "bk2: a forced root with a count of maxima: not a code "
                   "of this version");
  kinds[0] = gk;
  *both = BK2_IS_BOTH(kind);
  return 1;
}

/* The guard that ends a phase at its very start, or -1.  Every guard
 * approaches zero from below; one past zero fires at once, as in the exact
 * flows, and so does one within rounding of zero that is on its way up: a
 * threshold (S_j' > 0) or a re-stick that arrives (restick_arrives()); a
 * fresh block's re-stick guard starts at zero by construction and never
 * does. */
static int start_event(const bk2_inst *b, int mode, int fresh,
                       const int *kinds, int ng, const double *y,
                       const double *dy, double *slope) {
  double E = round_guard(b, y);
  for (int i = 0; i < ng; i++) {
    int k = kinds[i];
    if (k < 3 && (fresh & k)) continue;
    double sl, g = guard(b, mode, k, y, dy, &sl);
    int up = k < 3 ? restick_arrives(b, mode, k, y, dy) : sl > 0;
    if (g > E || (g >= -E && up)) {
      *slope = sl;
      return i;
    }
  }
  return -1;
}

/* The first root in the step [t0, t] of guard `kind` rising through zero,
 * as an offset from t0, or -1.  At the phase's start the start root of a
 * guard that leaves zero (a fresh block's, or one within rounding that
 * start_event() did not take) is skipped: such a guard cannot re-stick
 * before it has left zero (restick_arrives()). */
static double step_root(const bk2_inst *b, int w, gsl_odeiv2_system *sys,
                        int mode, int fresh, int kind, double t0,
                        const double *y0, const double *dy0, double t,
                        const double *y1, const double *dy1, double hmax) {
  double s0, s1, step = t - t0;
  double g0 = guard(b, mode, kind, y0, dy0, &s0);
  double g1 = guard(b, mode, kind, y1, dy1, &s1);
  int skip = t0 == 0 && ((kind < 3 && (fresh & kind)) ||
                         fabs(g0) <= round_guard(b, y0));
  double r = hermite_root(g0, s0, g1, s1, step, skip, 1);
  /* A guard that rises and falls back inside the step, negative at both
   * ends: its maximum, refined on the true solution, decides whether it
   * touched zero (a grazing the interpolant may hide when the hump is
   * lower than its error).  A leaving guard's start is no maximum: its
   * first piece is skipped as its start root is. */
  if (r < 0 && g0 < 0 && g1 < 0 && s0 > 0 && s1 < 0) {
    double a0, a1, ym[DIM_MAX], dym[DIM_MAX];
    guard_prime(b, mode, kind, y0, dy0, &a0);
    guard_prime(b, mode, kind, y1, dy1, &a1);
    double rm = hermite_root(s0, a0, s1, a1, step, skip, -1);
    if (rm >= 0) {
      double tm = t0 + rm, sm;
      refine(b, w, sys, mode, kind, 1, t0, y0, t, hmax, &tm, ym, dym);
      double gm = guard(b, mode, kind, ym, dym, &sm);
      if (gm >= -round_guard(b, ym)) {
        /* the root: on [t0, tm], where g rises from g0 < 0 */
        double rr = hermite_root(g0, s0, gm, 0, tm - t0, 0, 1);
        r = rr >= 0 ? rr : tm - t0;
      }
    }
  }
  return r;
}

/* The event time of guard `kind` by Newton's method on the true solution
 * from the step's start (t0, y0), starting at te within [t0, t1]: the
 * time, and the state, its derivative, the guard's value and slope there
 * (yt, dyt, *slope). */
static double locate_event(const bk2_inst *b, int w, gsl_odeiv2_system *sys,
                           int mode, int kind, double t0, const double *y0,
                           double t1, double te, double hmax, double *yt,
                           double *dyt, double *slope) {
  for (int it = 0; it < EVENT_NEWTON_MAX; it++) {
    memcpy(yt, y0, DIM_MAX * sizeof *yt);
    if (te > t0 && advance_to(b->num, w, sys, t0, te, hmax, yt)) break;
    rhs(te, yt, dyt, sys->params);
    double g = guard(b, mode, kind, yt, dyt, slope);
    if (*slope == 0) return te;
    double dt = -g / *slope;
    double tol = b->acc.event_atol + b->acc.event_rtol * te;
    te = fmin(fmax(te + dt, t0), t1);
    if (fabs(dt) <= tol) break;
  }
  memcpy(yt, y0, DIM_MAX * sizeof *yt);
  if (te > t0) advance_to(b->num, w, sys, t0, te, hmax, yt);
  rhs(te, yt, dyt, sys->params);
  guard(b, mode, kind, yt, dyt, slope);
  return te;
}

/* The tie rules at an event of guard kinds[*which] at time te, state yt
 * (docs/model.md): another re-stick within the event's bracket (the event
 * tolerance over its slope, plus rounding) that arrives at zero
 * (restick_arrives(); a block that has only just come loose does not)
 * goes first when the event is a threshold, a re-stick that coincides
 * with the other block's threshold giving a GSP of zero length; two such
 * re-sticks end the slip of both blocks.  Updates *which and *slope;
 * returns whether both blocks re-stick. */
static int resolve_ties(const bk2_inst *b, int mode, const int *kinds,
                        int ng, int *which, double te, const double *yt,
                        const double *dyt, double *slope) {
  double tol = b->acc.event_atol + b->acc.event_rtol * te;
  for (int i = 0; i < ng; i++) {
    if (i == *which || kinds[i] >= 3) continue;
    double si, gi = guard(b, mode, kinds[i], yt, dyt, &si);
    if (!(fabs(gi) <= tol * fabs(si) + round_guard(b, yt)) ||
        !restick_arrives(b, mode, kinds[i], yt, dyt))
      continue;
    if (kinds[*which] < 3) return 1;
    *which = i, *slope = si;
  }
  return 0;
}

/* The end of a phase at the event of guard `kind` at te (both: of both
 * blocks): its code bytes, its borders when asked for, the state after
 * it; returns the next mode. */
static int end_phase(const bk2_inst *b, const bk2_dpar *P, int mode,
                     int fresh, const double *ystart, int kind, int both,
                     double te, const double *yt, const double *dyt,
                     double slope, bk2_state *x, bk2_events *ev,
                     sc_msg *msg) {
  int nd = P->nd;
  ev->rec[0] = (unsigned char)(!both ? kind
                               : kind == BK2_EV_RESTICK1 ? BK2_EV_BOTH
                                                         : BK2_EV_BOTH2);
  ev->rec[1] = 0;
  if (ev->borders) {
    /* the event time's sensitivity, dt = -dg / g' */
    sc_dual gd = guard_at(P, mode, kind, yt), Td = sc_dconst(te, nd);
    for (int j = 0; j < nd; j++) Td.d[j] = slope != 0 ? -gd.d[j] / slope : NAN;
    int sb = num_borders(b, P, mode, fresh, ystart, te, ev->rec[0], &Td, NULL,
                         ev, msg);
    if (sb) return sb;
  }
  int next = finish_event(P, mode, kind, yt, dyt, slope, x);
  if (both) {
    x->u1 = x->u2 = P->vs;
    return SC_BK2_STICK;
  }
  return next;
}

/* The roots of a step are picked from its Hermite interpolants, whose
 * error can exceed the time between two re-sticks (next to a BR, where
 * both blocks re-stick at once, 1e-7 apart and less): after the chosen
 * event is located at te, a re-stick guard already past zero there,
 * beyond the tie margin of resolve_ties(), rose through zero before it.
 * That event is located instead, on [t0, te]; repeated until none is
 * earlier (at most once per guard).  Returns the event time, `which`,
 * the state and slope updated. */
static double first_event(const bk2_inst *b, int w, gsl_odeiv2_system *sys,
                          int mode, int fresh, const int *kinds, int ng,
                          double t0, const double *y0, const double *dy0,
                          double te, double hmax, int *which, double *yt,
                          double *dyt, double *slope) {
  for (int pass = 0; pass < ng; pass++) {
    int earlier = -1;
    double tol = b->acc.event_atol + b->acc.event_rtol * te, s0, si;
    for (int i = 0; i < ng && earlier < 0; i++) {
      if (i == *which || kinds[i] >= 3) continue;
      double gi = guard(b, mode, kinds[i], yt, dyt, &si);
      if (gi > tol * fabs(si) + round_guard(b, yt)) earlier = i;
    }
    if (earlier < 0) return te;
    double g0 = guard(b, mode, kinds[earlier], y0, dy0, &s0);
    double gi = guard(b, mode, kinds[earlier], yt, dyt, &si);
    int skip = t0 == 0 && (fresh & kinds[earlier]);
    double r = hermite_root(g0, s0, gi, si, te - t0, skip, 1);
    double guess = t0 + (r >= 0 ? r : 0.5 * (te - t0));
    double t1 = te;
    te = locate_event(b, w, sys, mode, kinds[earlier], t0, y0, t1, guess,
                      hmax, yt, dyt, slope);
    *which = earlier;
  }
  return te;
}

static int num_phase(const bk2_inst *b, const bk2_dpar *P, int mode,
                     int fresh, bk2_state *x, double *duration,
                     bk2_events *ev, sc_msg *msg) {
  bk2_num *n = b->num;
  int nd = P->nd, w = nd > 0;
  rhs_ctx ctx = {b, mode, nd};
  gsl_odeiv2_system sys = {rhs, NULL, w ? DIM_MAX : NSTATE, &ctx};
  double y[DIM_MAX] = {0}, y0[DIM_MAX], dy0[DIM_MAX], dy1[DIM_MAX];
  double yt[DIM_MAX], dyt[DIM_MAX], ystart[DIM_MAX], slope = 0;
  pack(x, nd, y);
  memcpy(ystart, y, sizeof y);
  int kinds[3], both_forced;
  int ng = phase_guards(ev, mode, kinds, &both_forced, msg);
  if (ng < 0) return ng;
  if (ev->force && (ev->force[0] & BK2_EV_ATMAX))
    return num_phase_at_max(b, P, mode, fresh, ystart, kinds[0],
                            ev->force[1], x, duration, ev, msg);
  double hmax = STEP_FRACTION * fastest_period(b, mode);
  double tend = PHASE_PERIODS * 2 * SC_PI; /* slow period is 2 pi */
  if (mode != SC_BK2_SLIP12 && b->vs > 0)
    tend = fmax(tend, 4 * (b->beta + 1) / b->vs); /* thresholds are reached */
  gsl_odeiv2_evolve_reset(n->evol[w]);
  gsl_odeiv2_step_reset(n->step[w]);
  rhs(0, y, dy0, &ctx);
  int which = start_event(b, mode, fresh, kinds, ng, y, dy0, &slope);
  if (which >= 0) {
    /* zero-length phase: the state is unchanged, no time shift needed
     * beyond the guard's own sensitivity */
    *duration = 0;
    ev->rec[0] = (unsigned char)kinds[which];
    ev->rec[1] = 0;
    return finish_event(P, mode, kinds[which], y, dy0, slope, x);
  }
  double t = 0, h = hmax * 0.1;
  while (t < tend) {
    double t0 = t;
    memcpy(y0, y, sizeof y);
    int st = num_step(n, w, &sys, &t, tend, &h, hmax, y, mode, msg);
    if (st) return st;
    ev->steps++;
    rhs(t, y, dy1, &ctx);
    double troot = -1;
    for (int i = 0; i < ng; i++) {
      double r = step_root(b, w, &sys, mode, fresh, kinds[i], t0, y0, dy0, t,
                           y, dy1, hmax);
      if (r >= 0 && (troot < 0 || r < troot)) troot = r, which = i;
    }
    if (which >= 0) {
      double te = locate_event(b, w, &sys, mode, kinds[which], t0, y0, t,
                               t0 + troot, hmax, yt, dyt, &slope);
      te = first_event(b, w, &sys, mode, fresh, kinds, ng, t0, y0, dy0, te,
                       hmax, &which, yt, dyt, &slope);
      *duration = te;
      int both = both_forced || resolve_ties(b, mode, kinds, ng, &which, te,
                                             yt, dyt, &slope);
      return end_phase(b, P, mode, fresh, ystart, kinds[which], both, te, yt,
                       dyt, slope, x, ev, msg);
    }
    memcpy(dy0, dy1, sizeof dy1);
  }
  return sc_fail(msg, SC_EUNDEF,
                 "no event within %.6g time units of slip mode %d: the slip "
                 "does not end",
                 tend, mode);
}

static int num_sample(const bk2_inst *b, const bk2_dpar *P, int mode,
                      const bk2_state *x0, double duration, bk2_traj *traj) {
  (void)P;
  bk2_num *n = b->num;
  rhs_ctx ctx = {b, mode, 0};
  gsl_odeiv2_system sys = {rhs, NULL, NSTATE, &ctx};
  double y[NSTATE] = {x0->y1.v, x0->y2.v, x0->u1.v, x0->u2.v};
  double hmax = STEP_FRACTION * fastest_period(b, mode);
  double t = 0, dtau = traj->dtau;
  int st = bk2_traj_emit(traj, 0, y, mode);
  long nsamp = (long)ceil(duration / dtau);
  for (long i = 1; i <= nsamp && !st; i++) {
    double t1 = i == nsamp ? duration : i * dtau;
    if (advance_to(n, 0, &sys, t, t1, hmax, y)) return SC_ENOCONV;
    t = t1;
    st = bk2_traj_emit(traj, t, y, mode);
  }
  traj->tau += duration;
  return st;
}

/* The integration tolerance, times the growth of an error over a slip
 * phase (a few oscillations). */
#define PRECISION_FACTOR 10.0

static double num_precision(const bk2_inst *b) {
  return PRECISION_FACTOR * (b->acc.ode_atol + b->acc.ode_rtol);
}

const bk2_flows sc_bk2_flows_numerical = {
    .name = "numerical",
    .setup = num_setup,
    .release = num_release,
    .phase = num_phase,
    .sample = num_sample,
    .precision = num_precision,
    .value = NULL,
};
