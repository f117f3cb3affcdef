/* The event map of the two-block model (docs/derivations.md) in quadruple
 * precision: closed-form flows, certified first-root location of every guard,
 * and forward-mode derivatives (d and the four parameters), all in __float128
 * (libquadmath).  It is written for clarity, not speed, and shares no code
 * with the double path (bk2.c, src/hybrid/guard.c), so that comparing the
 * two measures the double path's error rather than repeating it
 * (docs/accuracy.md).
 *
 * Event location follows the argument of docs/events.md: each guard is
 * c0 + c1 t + sum_k (a_k cos w_k t + b_k sin w_k t), so |g'''| <= M3 =
 * sum_k w_k^3 R_k, and (0, tmax] is covered by intervals each proved free
 * of roots (a Taylor quadratic with remainder M3 h^3/6 keeps its sign) or
 * holding at most one (g' keeps its sign with margin M3 h^2/2); a root is
 * then refined by safeguarded Newton.  No sample spacing is assumed. */
#include <float.h>
#include <math.h>
#if SC_HAVE_QUAD
#include <quadmath.h>
#include <string.h>

#include "models/bk2_quad.h"
#include "models/bk2_rules.h"

typedef sc_quad Q;

/* Rounding bound of one guard evaluation, in units of eps times the size
 * of its terms (sinusoid arguments w t included): generous, since a
 * tighter bound only moves the point where a touch is declared. */
#define QROUND_ULPS 16
/* Event-time tolerance in units of eps: the located time is within
 * QTIME_ULPS eps (1 + t) of the root, about 1e-32 for t ~ 1, so f is
 * exact to ~1e-31 wherever the guard's slope is not tiny. */
#define QTIME_ULPS 64
/* Newton/bisection steps: bisection alone needs ~115 to reach the
 * tolerance from a bracket of length 1; the cap is a safety net. */
#define QMAX_REFINE 400
/* Periods of the slow mode of SLIP12 without a re-stick before f is
 * declared undefined (as the double path: a slip cycle). */
#define QSLIP12_PERIODS 16

/* (__extension__: the Q suffix of libquadmath's constants is GNU C) */
static Q qeps(void) { return __extension__ FLT128_EPSILON; }
static Q qpi(void) { return __extension__ M_PIq; }

/* ---- duals in quad ---------------------------------------------------- */

typedef struct {
  Q v;
  Q d[SC_BK2Q_NDIR];
} qd;

static qd qc(Q v) {
  qd r;
  memset(&r, 0, sizeof r);
  r.v = v;
  return r;
}
static qd qvar(Q v, int dir, int nd) {
  qd r = qc(v);
  if (dir < nd) r.d[dir] = 1;
  return r;
}
static qd qadd(qd a, qd b, int nd) {
  a.v += b.v;
  for (int k = 0; k < nd; k++)
    a.d[k] += b.d[k];
  return a;
}
static qd qsub(qd a, qd b, int nd) {
  a.v -= b.v;
  for (int k = 0; k < nd; k++)
    a.d[k] -= b.d[k];
  return a;
}
static qd qscale(qd a, Q s, int nd) {
  a.v *= s;
  for (int k = 0; k < nd; k++)
    a.d[k] *= s;
  return a;
}
static qd qaddc(qd a, Q c) {
  a.v += c;
  return a;
}
static qd qmul(qd a, qd b, int nd) {
  qd r = qc(a.v * b.v);
  for (int k = 0; k < nd; k++)
    r.d[k] = a.d[k] * b.v + a.v * b.d[k];
  return r;
}
static qd qdiv(qd a, qd b, int nd) {
  qd r = qc(a.v / b.v);
  for (int k = 0; k < nd; k++)
    r.d[k] = (a.d[k] - r.v * b.d[k]) / b.v;
  return r;
}
static qd qsqrt(qd a, int nd) {
  qd r = qc(sqrtq(a.v));
  for (int k = 0; k < nd; k++)
    r.d[k] = a.d[k] / (2 * r.v);
  return r;
}
/* sin and cos of the dual w t at a plain time t (t carries no derivative:
 * the event-time sensitivity is applied separately at each event). */
static void qsincos_wt(qd w, Q t, int nd, qd *s, qd *c) {
  Q sv = sinq(w.v * t), cv = cosq(w.v * t);
  *s = qc(sv);
  *c = qc(cv);
  for (int k = 0; k < nd; k++) {
    s->d[k] = cv * w.d[k] * t;
    c->d[k] = -sv * w.d[k] * t;
  }
}

/* ---- parameters, state ------------------------------------------------ */

typedef struct {
  int nd, frozen, max_events;
  qd alpha, beta, mu, k1, k2, v, vs, w1, w2;
  Q dstar;
} qpar;

typedef struct {
  qd y1, y2, u1, u2;
} qstate;

static void qpar_make(const sc_bk2q_params *p, int nd, qpar *P) {
  P->nd = nd;
  P->frozen = p->frozen;
  P->max_events = p->max_events;
  P->alpha = qvar(p->alpha, 1, nd);
  P->beta = qvar(p->beta, 2, nd);
  P->mu = qdiv(qc(1), qvar(p->phi, 3, nd), nd);
  P->k1 = P->mu;
  P->k2 = qmul(P->beta, P->mu, nd);
  P->v = qvar(p->v, 4, nd);
  P->vs = p->frozen ? qc(0) : P->v;
  P->w1 = qsqrt(qaddc(P->alpha, 1), nd);
  P->w2 = qsqrt(qaddc(qscale(P->alpha, 2, nd), 1), nd);
  P->dstar = (p->beta - 1) / (1 + 2 * p->alpha);
}

/* S_a = (1+alpha) Y_a - alpha Y_b */
static qd qspring(const qpar *P, qd ya, qd yb) {
  return qadd(ya, qmul(P->alpha, qsub(ya, yb, P->nd), P->nd), P->nd);
}

/* q'' + w^2 q = F0 + F1 t: q = s0 + s1 t + A cos wt + B sin wt. */
typedef struct {
  qd s0, s1, A, B, w;
} qosc;

static qosc qosc_make(qd q0, qd p0, qd F0, qd F1, qd w, int nd) {
  qosc o;
  qd w2 = qmul(w, w, nd);
  o.s0 = qdiv(F0, w2, nd);
  o.s1 = qdiv(F1, w2, nd);
  o.A = qsub(q0, o.s0, nd);
  o.B = qdiv(qsub(p0, o.s1, nd), w, nd);
  o.w = w;
  return o;
}

static void qosc_at(const qosc *o, Q t, int nd, qd *q, qd *p, Q *acc) {
  qd s, c;
  qsincos_wt(o->w, t, nd, &s, &c);
  qd Ac = qmul(o->A, c, nd), Bs = qmul(o->B, s, nd);
  *q = qadd(qadd(o->s0, qscale(o->s1, t, nd), nd), qadd(Ac, Bs, nd), nd);
  *p = qadd(o->s1,
            qmul(o->w, qsub(qmul(o->B, c, nd), qmul(o->A, s, nd), nd), nd), nd);
  *acc = -o->w.v * o->w.v * (Ac.v + Bs.v);
}

/* ---- guards and their certified first root ----------------------------- */

typedef struct {
  Q c0, c1;
  int n;
  Q w[2], a[2], b[2];
} qguard;

static void qg_eval(const qguard *g, Q t, Q *g0, Q *g1, Q *g2) {
  Q v = g->c0 + g->c1 * t, d1 = g->c1, d2 = 0;
  for (int k = 0; k < g->n; k++) {
    Q w = g->w[k], s = sinq(w * t), c = cosq(w * t);
    Q cv = g->a[k] * c + g->b[k] * s;
    v += cv;
    d1 += w * (g->b[k] * c - g->a[k] * s);
    d2 -= w * w * cv;
  }
  *g0 = v;
  if (g1) *g1 = d1;
  if (g2) *g2 = d2;
}

typedef struct {
  int found, tangent;
  Q t, slope;
} qroot;

typedef struct {
  Q c0, c1, amp, wamp, m3;
} qsize;

static Q qround_at(const qsize *z, Q t) {
  return QROUND_ULPS * qeps() * (z->c0 + z->amp + (z->c1 + z->wamp) * t);
}
static Q qtol_at(Q t) { return QTIME_ULPS * qeps() * (1 + fabsq(t)); }

/* min over s in [0, h] of sigma (p0 + p1 s + p2 s^2 / 2) */
static Q qquad_min(Q sigma, Q p0, Q p1, Q p2, Q h) {
  p0 *= sigma, p1 *= sigma, p2 *= sigma;
  Q m = fminq(p0, p0 + p1 * h + p2 * h * h / 2);
  if (p2 > 0) {
    Q s = -p1 / p2;
    if (s > 0 && s < h) m = fminq(m, p0 + p1 * s / 2);
  }
  return m;
}

/* Safeguarded Newton in [lo, hi], g(lo) and g(hi) of opposite signs, g
 * monotone there. */
static void qrefine(const qguard *g, const qsize *z, Q lo, Q glo, Q hi, Q ghi,
                    qroot *r) {
  Q t = lo - glo * (hi - lo) / (ghi - glo);
  if (!(t > lo && t < hi)) t = (lo + hi) / 2;
  Q v, d;
  for (int it = 0; it < QMAX_REFINE; it++) {
    qg_eval(g, t, &v, &d, NULL);
    if (fabsq(v) <= qround_at(z, t)) break;
    if ((v > 0) == (glo > 0))
      lo = t, glo = v;
    else
      hi = t;
    Q tn = t - v / d;
    if (d != 0 && tn > lo && tn < hi) {
      Q step = fabsq(tn - t);
      t = tn;
      if (step <= qtol_at(t)) break;
    } else {
      t = (lo + hi) / 2;
    }
    if (hi - lo <= qtol_at(hi)) break;
  }
  qg_eval(g, t, &v, &r->slope, NULL);
  r->t = t;
  r->found = 1;
}

/* The first root of g in (0, tmax].  skip_start: g(0) = 0 by construction
 * (a block that just started slipping); that root is not an event.  A g(0)
 * within rounding of zero is otherwise an event only if g moves up through
 * zero (every event of the model is a guard reaching zero from below). */
static void qfirst_root(const qguard *g, Q tmax, int skip_start, qroot *r) {
  r->found = r->tangent = 0;
  r->t = tmax;
  r->slope = 0;
  qsize z = {fabsq(g->c0), fabsq(g->c1), 0, 0, 0};
  Q wmax = 0;
  for (int k = 0; k < g->n; k++) {
    Q R = hypotq(g->a[k], g->b[k]), w = g->w[k];
    z.amp += R;
    z.wamp += R * w;
    z.m3 += R * w * w * w;
    wmax = fmaxq(wmax, w);
  }
  Q t = 0, g0, g1, g2;
  qg_eval(g, 0, &g0, &g1, &g2);
  if (fabsq(g0) <= qround_at(&z, 0)) {
    int upward = g1 > 0 || (g1 == 0 && g2 > 0);
    if (!skip_start && upward) {
      r->found = 1;
      r->t = 0;
      r->slope = g1;
      return;
    }
    skip_start = 1;
  }
  Q h = wmax > 0 ? fminq(tmax, qpi() / (2 * wmax)) : tmax;
  int at_start = skip_start;
  while (t < tmax) {
    h = fminq(h, tmax - t);
    Q E = qround_at(&z, t + h), sigma;
    if (at_start) {
      sigma = g1 != 0 ? (g1 > 0 ? 1 : -1) : (g2 > 0 ? 1 : -1);
    } else {
      if (fabsq(g0) <= E) {
        r->found = 1;
        r->t = t;
        r->slope = g1;
        r->tangent = fabsq(g1) * qtol_at(t) <= E;
        return;
      }
      sigma = g0 > 0 ? 1 : -1;
      /* no root in [t, t + h]: the Taylor quadratic with its remainder
       * keeps the sign of g, or the line c0 + c1 t does, with a margin
       * larger than the sum of the sinusoids' amplitudes (which lets a
       * slow line, V ~ 1e-12, be followed in doubling steps) */
      Q l0 = sigma * (g->c0 + g->c1 * t),
        l1 = sigma * (g->c0 + g->c1 * (t + h));
      if (qquad_min(sigma, g0, g1, g2, h) - z.m3 * h * h * h / 6 > E ||
          fminq(l0, l1) - z.amp > E) {
        t += h;
        qg_eval(g, t, &g0, &g1, &g2);
        h *= 2;
        continue;
      }
    }
    /* g strictly monotone on [t, t + h] */
    Q d0 = g1, dh = g1 + g2 * h;
    if ((d0 > 0) == (dh > 0) &&
        fminq(fabsq(d0), fabsq(dh)) > z.m3 * h * h / 2) {
      Q e0, e1, e2;
      qg_eval(g, t + h, &e0, &e1, &e2);
      if (!at_start && (e0 * sigma <= 0 || fabsq(e0) <= E)) {
        if (fabsq(e0) <= E) {
          r->found = 1;
          r->t = t + h;
          r->slope = e1;
        } else {
          qrefine(g, &z, t, g0, t + h, e0, r);
        }
        return;
      }
      at_start = 0;
      t += h;
      g0 = e0, g1 = e1, g2 = e2;
      h *= 2;
      continue;
    }
    h /= 2;
    if (h <= qtol_at(t)) {
      if (at_start) { /* a degenerate start (g' = 0 too): step past it */
        at_start = 0;
        t += h;
        qg_eval(g, t, &g0, &g1, &g2);
        continue;
      }
      /* g and g' both within rounding of zero over an interval below the
       * tolerance: a tangential touch */
      r->found = r->tangent = 1;
      r->t = t + h / 2;
      qg_eval(g, r->t, &g0, &r->slope, NULL);
      return;
    }
  }
}

/* Past this time a guard keeps one sign or repeats (as the double path):
 * one period of a pure sinusoid, the time a linear term needs to
 * dominate, or QSLIP12_PERIODS slow periods of two sinusoids. */
static Q qhorizon(const qguard *g) {
  Q amp = 0, wmin = 0;
  for (int k = 0; k < g->n; k++) {
    amp += fabsq(g->a[k]) + fabsq(g->b[k]);
    wmin = k == 0 ? g->w[k] : fminq(wmin, g->w[k]);
  }
  Q period = 2 * qpi() / wmin;
  if (g->c1 != 0) return (fabsq(g->c0) + amp) / fabsq(g->c1) + period;
  if (g->n == 1) return period * 101 / 100;
  return QSLIP12_PERIODS * period;
}

/* ---- one slip phase ---------------------------------------------------- */

typedef struct {
  int mode;
  qosc o1, o2; /* SLIP1/2: the slipping block; SLIP12: Sum and Dif */
  qstate x0;
} qflow;

static qflow qflow_make(const qpar *P, int mode, const qstate *x0) {
  int nd = P->nd;
  qflow f;
  f.mode = mode;
  f.x0 = *x0;
  qd F1 = qmul(P->alpha, P->vs, nd);
  if (mode == SC_BK2_SLIP1) {
    f.o1 =
        qosc_make(x0->y1, x0->u1, qadd(P->k1, qmul(P->alpha, x0->y2, nd), nd),
                  F1, P->w1, nd);
  } else if (mode == SC_BK2_SLIP2) {
    f.o1 =
        qosc_make(x0->y2, x0->u2, qadd(P->k2, qmul(P->alpha, x0->y1, nd), nd),
                  F1, P->w1, nd);
  } else {
    f.o1 = qosc_make(qadd(x0->y1, x0->y2, nd), qadd(x0->u1, x0->u2, nd),
                     qadd(P->k1, P->k2, nd), qc(0), qc(1), nd);
    f.o2 = qosc_make(qsub(x0->y1, x0->y2, nd), qsub(x0->u1, x0->u2, nd),
                     qsub(P->k1, P->k2, nd), qc(0), P->w2, nd);
  }
  return f;
}

static void qflow_at(const qpar *P, const qflow *f, Q t, qstate *x, Q acc[2]) {
  int nd = P->nd;
  qd q, p, q2, p2;
  Q a, a2;
  qosc_at(&f->o1, t, nd, &q, &p, &a);
  if (f->mode == SC_BK2_SLIP1) {
    x->y1 = q, x->u1 = p;
    x->y2 = qadd(f->x0.y2, qscale(P->vs, t, nd), nd);
    x->u2 = P->vs;
    acc[0] = a, acc[1] = 0;
  } else if (f->mode == SC_BK2_SLIP2) {
    x->y2 = q, x->u2 = p;
    x->y1 = qadd(f->x0.y1, qscale(P->vs, t, nd), nd);
    x->u1 = P->vs;
    acc[0] = 0, acc[1] = a;
  } else {
    qosc_at(&f->o2, t, nd, &q2, &p2, &a2);
    x->y1 = qscale(qadd(q, q2, nd), (Q)0.5, nd);
    x->y2 = qscale(qsub(q, q2, nd), (Q)0.5, nd);
    x->u1 = qscale(qadd(p, p2, nd), (Q)0.5, nd);
    x->u2 = qscale(qsub(p, p2, nd), (Q)0.5, nd);
    acc[0] = (a + a2) / 2, acc[1] = (a - a2) / 2;
  }
}

/* the velocity q'(t) of an oscillator, scaled, added to a guard */
static void qguard_add_qdot(qguard *g, const qosc *o, Q scale) {
  Q w = o->w.v;
  g->c0 += scale * o->s1.v;
  g->w[g->n] = w;
  g->a[g->n] = scale * w * o->B.v;
  g->b[g->n] = -scale * w * o->A.v;
  g->n++;
}

/* re-stick guard U_i - V_s of slipping block i */
static qguard qguard_restick(const qpar *P, const qflow *f, int i) {
  qguard g;
  memset(&g, 0, sizeof g);
  g.c0 = -P->vs.v;
  if (f->mode != SC_BK2_SLIP12) {
    qguard_add_qdot(&g, &f->o1, 1);
  } else {
    qguard_add_qdot(&g, &f->o1, (Q)0.5);
    qguard_add_qdot(&g, &f->o2, i == 1 ? (Q)0.5 : (Q)-0.5);
  }
  return g;
}

/* threshold guard S_j - T_j of the stuck block j (the other slips) */
static qguard qguard_threshold(const qpar *P, const qflow *f) {
  qguard g;
  memset(&g, 0, sizeof g);
  Q a = P->alpha.v;
  int j = f->mode == SC_BK2_SLIP1 ? 2 : 1;
  Q yj0 = j == 2 ? f->x0.y2.v : f->x0.y1.v;
  Q tj = j == 2 ? P->beta.v : 1;
  g.c0 = (1 + a) * yj0 - a * f->o1.s0.v - tj;
  g.c1 = (1 + a) * P->vs.v - a * f->o1.s1.v;
  g.n = 1;
  g.w[0] = f->o1.w.v;
  g.a[0] = -a * f->o1.A.v;
  g.b[0] = -a * f->o1.B.v;
  return g;
}

/* Take the event `kind` (1, 2: re-stick of block i; 3: threshold of the
 * stuck block) at state x (duals at fixed time): the guard's dual part
 * moves the event time by dt = -dg / g', and the state along its velocity.
 * Returns the next mode. */
static int qtake_event(const qpar *P, int mode, int kind, Q slope,
                       const Q acc[2], qstate *x) {
  int nd = P->nd;
  if (nd) {
    qd gv;
    int gk = BK2_GUARD_OF(kind);
    if (gk == BK2_EV_RESTICK1)
      gv = qsub(x->u1, P->vs, nd);
    else if (gk == BK2_EV_RESTICK2)
      gv = qsub(x->u2, P->vs, nd);
    else if (mode == SC_BK2_SLIP1)
      gv = qsub(qspring(P, x->y2, x->y1), P->beta, nd);
    else
      gv = qaddc(qspring(P, x->y1, x->y2), -1);
    Q xdot[4] = {x->u1.v, x->u2.v, acc[0], acc[1]};
    qd *xs[4] = {&x->y1, &x->y2, &x->u1, &x->u2};
    for (int k = 0; k < nd; k++) {
      /* g' = 0: the event time is not differentiable: NaN says so */
      Q dt = slope != 0 ? -gv.d[k] / slope : (Q)NAN;
      for (int i = 0; i < 4; i++)
        xs[i]->d[k] += xdot[i] * dt;
    }
  }
  int next = bk2_next_mode(mode, kind), stuck = bk2_stuck_blocks(mode, next);
  if (stuck & 1) x->u1 = P->vs;
  if (stuck & 2) x->u2 = P->vs;
  return next;
}

typedef struct {
  double graze_margin;
  int graze_block, graze_mode, tangent;
} qevents;

/* One slip phase: its end, the next mode (or a negative status), and the
 * state there.  fresh bit i-1: block i started slipping at this phase's
 * start, so its re-stick guard starts at zero. */
static int qphase(const qpar *P, int mode, int fresh, qstate *x, qevents *ev,
                  sc_msg *msg) {
  qflow f = qflow_make(P, mode, x);
  qguard g[2];
  int kind[2], ng = 0;
  for (int i = 1; i <= 2; i++)
    if (mode == i || mode == SC_BK2_SLIP12) {
      g[ng] = qguard_restick(P, &f, i);
      kind[ng++] = i;
    }
  if (mode != SC_BK2_SLIP12) {
    g[ng] = qguard_threshold(P, &f);
    kind[ng++] = BK2_EV_THRESHOLD;
  }
  Q tmax = 0;
  for (int i = 0; i < ng; i++)
    tmax = fmaxq(tmax, qhorizon(&g[i]));
  qroot r[2];
  int first = -1;
  for (int i = 0; i < ng; i++) {
    int skip = kind[i] != BK2_EV_THRESHOLD && (fresh & kind[i]);
    /* a later guard matters only up to the earliest root so far (plus
     * the tie tolerance) */
    Q lim = first < 0 ? tmax : r[first].t + qtol_at(r[first].t);
    qfirst_root(&g[i], lim, skip, &r[i]);
    if (r[i].found && (first < 0 || r[i].t < r[first].t)) first = i;
  }
  if (first < 0)
    return sc_fail(msg, SC_EUNDEF,
                   "bk2 (quad): no event within %.6g time units of slip "
                   "mode %s: the slip does not end",
                   (double)tmax, bk2_mode_name(mode));
  /* ties within the time tolerance: re-sticks first (docs/events.md); two
   * re-sticks at once end both slips */
  int both = 0;
  for (int i = 0; i < ng; i++) {
    if (i == first || !r[i].found) continue;
    if (fabsq(r[i].t - r[first].t) <= qtol_at(r[first].t)) {
      if (kind[first] == BK2_EV_THRESHOLD)
        first = i;
      else if (kind[i] != BK2_EV_THRESHOLD)
        both = 1;
    }
  }
  Q t = r[first].t, acc[2];
  qflow_at(P, &f, t, x, acc);
  if (r[first].tangent) ev->tangent = 1;
  if (kind[first] != BK2_EV_THRESHOLD) {
    Q g0, g2;
    qg_eval(&g[first], t, &g0, NULL, &g2);
    double h = g2 < 0 ? (double)(r[first].slope * r[first].slope / (2 * -g2))
                      : HUGE_VAL;
    if (h < ev->graze_margin) {
      ev->graze_margin = h;
      ev->graze_block = kind[first];
      ev->graze_mode = mode;
    }
  }
  return qtake_event(P, mode,
                     !both ? kind[first]
                     : kind[first] == BK2_EV_RESTICK1 ? BK2_EV_BOTH
                                                      : BK2_EV_BOTH2,
                     r[first].slope, acc, x);
}

int sc_bk2q_eval(const sc_bk2q_params *p, Q d, int nd, sc_bk2q_value *out,
                 sc_msg *msg) {
  memset(out, 0, sizeof *out);
  if (!(nd == 0 || nd == SC_BK2Q_NDIR))
    return sc_fail(msg, SC_EINVAL, "sc_bk2q_eval: nd = %d (valid: 0, %d)", nd,
                   SC_BK2Q_NDIR);
  if (!finiteq(d))
    return sc_fail(msg, SC_EINVAL, "sc_bk2q_eval: d is not finite");
  if (!(p->alpha > 0 && p->beta > 0 && p->phi > 1 && p->v >= 0 &&
        finiteq(p->alpha) && finiteq(p->beta) && finiteq(p->phi) &&
        finiteq(p->v) && p->max_events >= 1))
    return sc_fail(msg, SC_EINVAL,
                   "sc_bk2q_eval: parameters out of range (valid: alpha > 0, "
                   "beta > 0, phi > 1, v >= 0, max-events >= 1)");
  qpar P;
  qpar_make(p, nd, &P);
  qd dd = qvar(d, 0, nd);
  qstate x;
  int mode;
  /* the onset (docs/derivations.md, section 3) */
  mode = BK2_ONSET_MODE(d, P.dstar);
  if (bk2_onset_block(mode) == 1) {
    x.y1 = qaddc(qmul(P.alpha, dd, nd), 1);
    x.y2 = qadd(x.y1, dd, nd);
  } else {
    x.y2 = qsub(P.beta, qmul(P.alpha, dd, nd), nd);
    x.y1 = qsub(x.y2, dd, nd);
  }
  x.u1 = x.u2 = P.vs;
  out->dstar_dist = (double)fabsq(d - P.dstar);
  int first_mode = mode, fresh = bk2_fresh_blocks(SC_BK2_STICK, mode);
  qevents ev = {HUGE_VAL, 0, 0, 0};
  size_t ilen = 0;
  for (int n = 0; n < P.max_events; n++) {
    bk2_itin_add(out->itinerary, &ilen, mode);
    int next = qphase(&P, mode, fresh, &x, &ev, msg);
    if (next < 0) return next;
    out->nphases++;
    if (next == SC_BK2_STICK) {
      qd f = qsub(x.y2, x.y1, nd);
      out->f = f.v;
      out->y1 = x.y1.v;
      out->y2 = x.y2.v;
      for (int k = 0; k < nd; k++)
        out->df[k] = f.d[k];
      /* single-block slip from a GSP: f(d) = d + c exactly
       * (docs/derivations.md) */
      out->neutral = out->nphases == 1 && first_mode != SC_BK2_SLIP12;
      if (out->neutral && nd) out->df[0] = 1;
      Q s1 = qspring(&P, x.y1, x.y2).v, s2 = qspring(&P, x.y2, x.y1).v;
      Q gap1 = 1 - s1, gap2 = p->beta - s2;
      out->gsp_gap = (double)fminq(gap1, gap2);
      out->gap_block = gap1 <= gap2 ? 1 : 2;
      out->graze_margin = ev.graze_margin;
      out->graze_block = ev.graze_block;
      out->graze_mode = ev.graze_mode;
      out->tangent = ev.tangent;
      return SC_OK;
    }
    fresh = bk2_fresh_blocks(mode, next);
    mode = next;
  }
  return sc_fail(msg, SC_EUNDEF,
                 "bk2 (quad): no return to a global stick phase after %d "
                 "slip phases (max-events): the motion settles on a slip "
                 "cycle",
                 P.max_events);
}

int sc_bk2_quad_eval(double alpha, double beta, double phi, double v,
                     int frozen, int max_events, double d, unsigned flags,
                     sc_map_value *out, sc_msg *msg) {
  sc_bk2q_params p = {alpha, beta, phi, v, frozen, max_events};
  sc_bk2q_value q;
  int nd = (flags & SC_EVAL_DERIV) ? SC_BK2Q_NDIR : 0;
  int st = sc_bk2q_eval(&p, d, nd, &q, msg);
  if (st) return st;
  out->f = (double)q.f;
  if (nd) {
    out->dfdd = (double)q.df[0];
    for (int k = 0; k < 4; k++)
      out->dfdp[k] = (double)q.df[k + 1];
  }
  out->neutral = q.neutral;
  out->nphases = q.nphases;
  if (flags & SC_EVAL_ITINERARY)
    memcpy(out->itinerary, q.itinerary, sizeof out->itinerary);
  else
    out->itinerary[0] = '\0';
  return SC_OK;
}

#else /* no __float128 arithmetic in this build (libquadmath not found) */

#include "models/bk2_quad.h"

static int no_quad(sc_msg *msg) {
  return sc_fail(msg, SC_EINVAL,
                 "precision = quad: this build has no quad precision (it "
                 "needs GCC's libquadmath; valid here: precision = double)");
}

int sc_bk2q_eval(const sc_bk2q_params *p, sc_quad d, int nd,
                 sc_bk2q_value *out, sc_msg *msg) {
  (void)p, (void)d, (void)nd, (void)out;
  return no_quad(msg);
}

int sc_bk2_quad_eval(double alpha, double beta, double phi, double v,
                     int frozen, int max_events, double d, unsigned flags,
                     sc_map_value *out, sc_msg *msg) {
  (void)alpha, (void)beta, (void)phi, (void)v, (void)frozen;
  (void)max_events, (void)d, (void)flags, (void)out;
  return no_quad(msg);
}

#endif
