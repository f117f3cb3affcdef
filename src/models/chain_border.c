/* The chain's borders and itinerary codes (docs/chain.md, "Borders"):
 * an evaluation that follows a forced code or records the natural one,
 * and lists the iterate's borders with their exact gradients in d and
 * every parameter, for the n-dimensional branch (docs/maps.md, "Borders
 * in n dimensions").  The evaluation without codes or borders never comes
 * here: chain.c and chain_phase.c call the hooks below only when c->bx is
 * set, by chain_eval_n_ex(). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chain_impl.h"

/* An itinerary code (models.h, sc_itin_code) is a sequence of groups:
 * the blocks that start at the onset, then the events that end each
 * phase; a group is its count, then one byte per event, the block (from
 * 0) plus CODE_THRESHOLD for a threshold.  Longer chains have no code. */
#define CODE_THRESHOLD 0x80
#define CODE_BLOCKS 128

/* Most local maxima of one guard walked through in a phase: a phase lasts
 * a few turns of its modes; past this the walk stops (the border of the
 * highest maximum so far is given). */
#define WALK_MAX 512

/* A crossing border looks for the other guard's rise this far past the
 * phase's event, in time units (one turn of the slowest possible mode,
 * or the phase's own length if longer): a rise further on is no border
 * of this iterate's neighbourhood. */
#define AHEAD_MIN CHAIN_TWO_PI

typedef struct chain_bx {
  const sc_itin_code *force; /* NULL: the natural itinerary */
  int fpos;                  /* bytes of force read */
  sc_itin_code rec;          /* the code followed */
  int rec_ok;                /* 0: it did not fit */
  sc_bordern_list *bl;       /* NULL: no borders */
  int phase;                 /* phases of this iterate so far */
  int st;                    /* an onset's failure, reported by the phase */
  char why[SC_MSG_LEN];
  double *dT, *dA, *dm;      /* P values each: the event time's, a guard's,
                                a border's derivatives */
  double *w, *a, *b, *ha, *hb; /* a guard's terms, and a transformed one */
  int nsw;                   /* the onset's switching borders: */
  size_t sw_at[CHAIN_MAXBLOCKS]; /* their places in the list */
  int sw_k[CHAIN_MAXBLOCKS];     /* the other block of each */
} chain_bx;

int chain_bx_deriv(const chain_inst *c) { return c->bx->bl != NULL; }

/* --- codes -------------------------------------------------------------- */

static void rec_group(chain_bx *x, const unsigned char *bytes, int k) {
  if (!x->rec_ok) return;
  if (x->rec.n + 1 + k > SC_CODE_LEN) {
    x->rec_ok = 0;
    return;
  }
  x->rec.c[x->rec.n++] = (unsigned char)k;
  memcpy(x->rec.c + x->rec.n, bytes, (size_t)k);
  x->rec.n += k;
}

static int cmp_byte(const void *p, const void *q) {
  return *(const unsigned char *)p - *(const unsigned char *)q;
}

/* The next group of the forced code into bytes; its size, or -1. */
static int next_group(chain_bx *x, unsigned char *bytes) {
  const sc_itin_code *f = x->force;
  if (x->fpos >= f->n) return -1;
  int k = f->c[x->fpos];
  if (k < 1 || x->fpos + 1 + k > f->n) return -1;
  memcpy(bytes, f->c + x->fpos + 1, (size_t)k);
  x->fpos += 1 + k;
  return k;
}

/* The slipping set's name, as the itinerary writes it. */
static void slip_name(const chain_inst *c, char *s, size_t len) {
  size_t k = 0;
  s[0] = '\0';
  for (int i = 0; i < c->N && k + 5 < len; i++)
    if (c->slip[i])
      k += (size_t)snprintf(s + k, len - k, "%s%d",
                            c->N >= 10 && k ? "." : "", i + 1);
}

/* --- borders ------------------------------------------------------------ */

/* Append a border: m, its derivatives dm in the columns (d, then the
 * parameters), its kind and name. */
static void add_border(const chain_inst *c, sc_border_kind kind, double m,
                       const double *dm, int on_state, const char *name) {
  sc_bordern_list *l = c->bx->bl;
  size_t i = l->n++;
  if (i >= l->cap) return;
  sc_bordern *b = &l->b[i];
  double *dx = b->dx;
  int n = c->N - 1;
  memset(b, 0, sizeof *b);
  b->dx = dx;
  b->kind = kind;
  b->value = m;
  for (int k = 0; k < n; k++) dx[k] = dm[k];
  for (int q = 0; q < CHAIN_NPARAM; q++) b->dp[q] = dm[n + q];
  b->on_state = on_state;
  size_t len = strlen(name);
  if (len >= SC_BORDER_NAME) len = SC_BORDER_NAME - 1;
  memcpy(b->name, name, len);
  b->name[len] = '\0';
}

/* The switching borders of the onset: gap_k - gap_j for every block k
 * that does not start (the gaps T_i - S_i at the end of the GSP, linear
 * in d: hyperplanes), j the block the positions are placed from; cc
 * (in c->U0) the onset's coupling sums (chain.c). */
static void onset_borders(chain_inst *c, const double *gap, int j) {
  const double *cc = c->U0;
  int N = c->N, n = N - 1;
  double *dm = c->bx->dm;
  char name[4 * SC_BORDER_NAME];
  for (int k = 0; k < N; k++) {
    if (k == j || (c->slip[k] && !c->bx->force)) continue;
    for (int col = 0; col < c->P; col++) {
      int q = col - n, blk[2] = {k, j};
      double v = 0;
      for (int s = 0; s < 2; s++) {
        int i = blk[s], nb[2], nn = chain_neighbours(c, i, nb);
        double dgap;
        if (q < 0) {
          double dc = 0;
          for (int t = 0; t < nn; t++) dc += (i > col) - (nb[t] > col);
          dgap = -(i > col) - c->alpha * dc;
        } else {
          dgap = (q == P_ALPHA) ? -cc[i] : 0;
          dgap += i >= 1 && i < CHAIN_PARAM_BLOCKS && q == P_BETA2 + i - 1;
        }
        v += s ? -dgap : dgap;
      }
      dm[col] = v;
    }
    /* the blocks in their order: the same name where k starts instead */
    snprintf(name, sizeof name, "gaps %d, %d equal at the onset",
             (k < j ? k : j) + 1, (k < j ? j : k) + 1);
    /* (a block that starts with j, as a forced code may ask: the same
     * function, its zero where they tie) */
    c->bx->sw_at[c->bx->nsw] = c->bx->bl->n;
    c->bx->sw_k[c->bx->nsw++] = k;
    add_border(c, SC_BORDER_SWITCHING, gap[k] - gap[j], dm, 1, name);
  }
}

/* The own code of each switching border of the onset (c->bx->rec, the
 * iterate's code, complete): block k starts at the end of the phase that
 * begins when its guard, at zero on the border, starts to rise (the first
 * phase with the driver moving; the first in which a neighbour slips with
 * it frozen: then the guard starts flat, the phase lasts as the square
 * root of the distance to the border, and f is not differentiable across
 * it).  That phase has length zero on the border: its own code starts k
 * with the group before (the onset's, or the previous phase's events)
 * and drops the phase, so that the system on it stays smooth. */
static void switching_codes(chain_inst *c) {
  chain_bx *x = c->bx;
  const sc_itin_code *r = &x->rec;
  if (!x->rec_ok) return;
  for (int i = 0; i < x->nsw; i++) {
    if (x->sw_at[i] >= x->bl->cap) continue;
    unsigned char kb = (unsigned char)(x->sw_k[i] | CODE_THRESHOLD);
    int prev = -1, at = 0;
    while (at < r->n && !(r->c[at] == 1 && at + 1 < r->n &&
                          r->c[at + 1] == kb && prev >= 0)) {
      prev = at;
      at += 1 + r->c[at];
    }
    if (at >= r->n) continue;
    sc_itin_code *alt = &x->bl->b[x->sw_at[i]].alt;
    int kp = r->c[prev];
    memcpy(alt->c, r->c, (size_t)prev);
    alt->c[prev] = (unsigned char)(kp + 1);
    memcpy(alt->c + prev + 1, r->c + prev + 1, (size_t)kp);
    alt->c[prev + 1 + kp] = kb;
    qsort(alt->c + prev + 1, (size_t)kp + 1, 1, cmp_byte);
    memcpy(alt->c + prev + 2 + kp, r->c + at + 2, (size_t)(r->n - at - 2));
    alt->n = r->n - 1;
  }
}

/* h(s) = sign g^(deriv)(t0 + dir s) as a guard in s (deriv 0 or 1, dir
 * +-1), its terms in x->ha, x->hb. */
static void transform(const chain_bx *x, const sc_guard_long *g, double t0,
                      int deriv, double sign, int dir, sc_guard_long *h) {
  double c0 = g->c0 + g->c1 * t0, c1 = g->c1;
  if (deriv) c0 = g->c1, c1 = 0;
  *h = (sc_guard_long){sign * c0, sign * dir * c1, g->n, g->w, x->ha, x->hb};
  for (int k = 0; k < g->n; k++) {
    double w = g->w[k], a = g->a[k], b = g->b[k];
    if (deriv) {
      double a1 = b * w;
      b = -a * w, a = a1;
    }
    double cs = cos(w * t0), sn = sin(w * t0);
    x->ha[k] = sign * (a * cs + b * sn);
    x->hb[k] = sign * dir * (b * cs - a * sn);
  }
}

/* The highest local maximum of g in (0, tend): its time and value; 0 if
 * none. */
static int highest_max(const chain_bx *x, const sc_guard_long *g, double tend,
                       double *tm, double *gm) {
  double t = 0, g1, g2;
  int found = 0, skip = 0;
  sc_guard_long_eval(g, 0, NULL, &g1, &g2);
  int rising = g1 > 0 || (g1 == 0 && g2 > 0);
  if (g1 == 0) skip = 1;
  for (int it = 0; it < 2 * WALK_MAX && t < tend; it++) {
    sc_guard_long h;
    sc_root_long r;
    /* a maximum: -g' rises to zero; a minimum: g' does */
    transform(x, g, t, 1, rising ? -1 : 1, 1, &h);
    if (sc_guard_long_first_root(&h, tend - t, skip, &r) || !r.found) break;
    t += r.t;
    skip = 1;
    if (rising && t < tend) {
      double v;
      sc_guard_long_eval(g, t, &v, NULL, NULL);
      if (!found || v > *gm) *gm = v, *tm = t;
      found = 1;
    }
    rising = !rising;
  }
  return found;
}

/* The rise through zero of g nearest to the phase's event at T: the
 * first after T where g(T) < 0 (within `ahead`), else the last before
 * it; its time into *tg.  0 if none. */
static int rise_near(const chain_bx *x, const sc_guard_long *g, double T,
                     double ahead, double *tg) {
  double gT;
  sc_guard_long h;
  sc_root_long r;
  sc_guard_long_eval(g, T, &gT, NULL, NULL);
  if (gT < 0) {
    transform(x, g, T, 0, 1, 1, &h);
    if (sc_guard_long_first_root(&h, ahead, 0, &r) || !r.found) return 0;
    *tg = T + r.t;
    return 1;
  }
  transform(x, g, T, 0, -1, -1, &h);
  if (sc_guard_long_first_root(&h, T, 0, &r) || !r.found) return 0;
  *tg = T - r.t;
  return 1;
}

/* Guard names in borders: "U2 - W", "S3 - T3". */
static void guard_name(int kind, int b, char *s, size_t len) {
  if (kind == CHAIN_RESTICK) snprintf(s, len, "U%d - W", b + 1);
  else snprintf(s, len, "S%d - T%d", b + 1, b + 1);
}

/* The crossing border of guard (kind, b) against the phase's event: m =
 * t_G - T, the time from the event to the guard's own rise through zero
 * (> 0 where the event comes first), dm from dt = -dg / g'. */
static void crossing_border(chain_inst *c, const sc_guard_long *g, int kind,
                            int b, const chain_event *e0, double T,
                            const char *gname, const char *slip) {
  chain_bx *x = c->bx;
  double tg, gdot, ahead = fmax(T, AHEAD_MIN);
  if (!rise_near(x, g, T, ahead, &tg)) return;
  chain_guard_sens(c, kind, b, tg, x->dA, &gdot);
  if (!(gdot > 0)) return; /* a touch: the grazing border's */
  for (int col = 0; col < c->P; col++)
    x->dm[col] = -x->dA[col] / gdot - x->dT[col];
  sc_border_kind k =
      e0->kind == CHAIN_RESTICK
          ? (kind == CHAIN_RESTICK ? SC_BORDER_BOTH : SC_BORDER_CROSSING)
          : (kind == CHAIN_RESTICK ? SC_BORDER_CROSSING : SC_BORDER_SWITCHING);
  /* named by the two guards in block order, so that the other side's
   * border, where the other guard ends the phase, has the same name */
  char ename[32], name[4 * SC_BORDER_NAME];
  guard_name(e0->kind, e0->block, ename, sizeof ename);
  int first = b < e0->block || (b == e0->block && kind < e0->kind);
  snprintf(name, sizeof name, "%s, %s at once, phase %d (slip %.40s)",
           first ? gname : ename, first ? ename : gname, x->phase, slip);
  add_border(c, k, tg - T, x->dm, 0, name);
}

/* The borders of the phase that ends at ev[0].t by the events ev: for
 * every guard, its highest local maximum before the end (GR for a
 * re-stick, TT for a threshold: m = -max), and for every guard that does
 * not end the phase, its crossing border against the event. */
static void phase_borders(chain_inst *c, const chain_event *ev, int nev) {
  chain_bx *x = c->bx;
  int N = c->N;
  double T = ev[0].t, gdot;
  double tol = 2 * (c->acc.event_atol + c->acc.event_rtol * T);
  char slip[4 * CHAIN_MAXBLOCKS], gname[32], name[4 * SC_BORDER_NAME];
  slip_name(c, slip, sizeof slip);
  chain_guard_sens(c, ev[0].kind, ev[0].block, T, x->dA, &gdot);
  for (int col = 0; col < c->P; col++) x->dT[col] = -x->dA[col] / gdot;
  for (int b = 0; b < N; b++) {
    int kind = c->slip[b] ? CHAIN_RESTICK : CHAIN_THRESHOLD, ending = 0;
    for (int e = 0; e < nev; e++) ending |= ev[e].block == b;
    sc_guard_long g0, g;
    chain_guard_of(c, kind, b, &g0);
    g = (sc_guard_long){g0.c0, g0.c1, g0.n, x->w, x->a, x->b};
    memcpy(x->w, g0.w, (size_t)g0.n * sizeof(double));
    memcpy(x->a, g0.a, (size_t)g0.n * sizeof(double));
    memcpy(x->b, g0.b, (size_t)g0.n * sizeof(double));
    guard_name(kind, b, gname, sizeof gname);
    double tm = 0, gm = 0;
    if (g.n > 0 && highest_max(x, &g, T - tol, &tm, &gm)) {
      chain_guard_sens(c, kind, b, tm, x->dA, &gdot);
      for (int col = 0; col < c->P; col++) x->dm[col] = -x->dA[col];
      snprintf(name, sizeof name, "%s max, phase %d (slip %.40s)", gname,
               x->phase, slip);
      add_border(c,
                 kind == CHAIN_RESTICK ? SC_BORDER_GRAZING : SC_BORDER_TOUCH,
                 -gm, x->dm, 0, name);
    }
    if (!ending) crossing_border(c, &g, kind, b, &ev[0], T, gname, slip);
  }
}

/* --- the hooks ------------------------------------------------------------ */

int chain_bx_onset(chain_inst *c, const double *gap, int j) {
  chain_bx *x = c->bx;
  int N = c->N;
  if (x->force) {
    unsigned char by[SC_CODE_LEN];
    int k = next_group(x, by), bad = k < 1;
    for (int i = 0; i < k && !bad; i++)
      bad = !(by[i] & CODE_THRESHOLD) || (by[i] & ~CODE_THRESHOLD) >= N;
    if (bad) {
      x->st = SC_EINVAL;
      snprintf(x->why, sizeof x->why,
               "chain: the forced itinerary code does not start with the "
               "blocks that start slipping");
      return j;
    }
    for (int i = 0; i < N; i++) c->slip[i] = c->fresh[i] = 0;
    j = 0;
    for (int i = 0; i < k; i++) {
      int b = by[i] & ~CODE_THRESHOLD;
      c->slip[b] = c->fresh[b] = 1;
      if (b > j) j = b; /* the last of them, as the natural tie */
    }
  }
  unsigned char rec[CHAIN_MAXBLOCKS];
  int k = 0;
  for (int i = 0; i < N && k < SC_CODE_LEN; i++)
    if (c->slip[i]) rec[k++] = (unsigned char)(i | CODE_THRESHOLD);
  rec_group(x, rec, k);
  if (x->bl) onset_borders(c, gap, j);
  return j;
}

/* The forced events of a phase (their group of the code) into ev: each
 * its guard's first rise through zero; the earliest first. */
static int forced_events(chain_inst *c, chain_event *ev, int *nev,
                         sc_msg *msg) {
  chain_bx *x = c->bx;
  unsigned char by[SC_CODE_LEN];
  int k = next_group(x, by);
  if (k < 1)
    return sc_fail(msg, SC_EINVAL,
                   "chain: the forced itinerary code ends before the slip "
                   "does (phase %d)",
                   x->phase);
  for (int i = 0; i < k; i++) {
    int kind = by[i] & CODE_THRESHOLD ? CHAIN_THRESHOLD : CHAIN_RESTICK;
    int b = by[i] & ~CODE_THRESHOLD;
    if (b >= c->N || c->slip[b] != (kind == CHAIN_RESTICK))
      return sc_fail(msg, SC_EINVAL,
                     "chain: the forced itinerary code does not fit phase "
                     "%d (a %s of block %d)",
                     x->phase, kind == CHAIN_RESTICK ? "re-stick" : "threshold",
                     b + 1);
    sc_guard_long g;
    sc_root_long r;
    chain_guard_of(c, kind, b, &g);
    int skip = kind == CHAIN_RESTICK && c->fresh[b];
    /* an event of a group whose guard has no root, or a flat one (a
     * switching's own code: a block started with the others at its zero
     * guard, which does not rise with the driver frozen), is taken at the
     * group's first root */
    if (sc_guard_long_first_root(&g, CHAIN_HORIZON_TURNS * CHAIN_TWO_PI, skip,
                                 &r) ||
        (k > 1 && !(r.slope > 0)))
      r.found = 0;
    ev[i] = (chain_event){kind, b, r.found ? r.t : HUGE_VAL, r.slope, 0};
    if (ev[i].t < ev[0].t) {
      chain_event t = ev[0];
      ev[0] = ev[i];
      ev[i] = t;
    }
  }
  if (!(ev[0].t < HUGE_VAL))
    return sc_fail(msg, SC_EUNDEF,
                   "chain: the forced event (the %s of block %d) does not "
                   "occur in phase %d",
                   ev[0].kind == CHAIN_RESTICK ? "re-stick" : "threshold",
                   ev[0].block + 1, x->phase);
  *nev = k;
  return SC_OK;
}

int chain_bx_phase(chain_inst *c, chain_event *ev, int *nev, sc_msg *msg) {
  chain_bx *x = c->bx;
  if (x->st) return sc_fail(msg, x->st, "%s", x->why);
  x->phase++;
  if (x->force) {
    int st = forced_events(c, ev, nev, msg);
    if (st) return st;
  }
  unsigned char rec[CHAIN_MAXBLOCKS];
  int k = 0;
  for (int e = 0; e < *nev && k < SC_CODE_LEN; e++)
    rec[k++] = (unsigned char)(ev[e].block |
                               (ev[e].kind == CHAIN_THRESHOLD ? CODE_THRESHOLD
                                                              : 0));
  qsort(rec, (size_t)k, 1, cmp_byte);
  rec_group(x, rec, k);
  if (x->bl) phase_borders(c, ev, *nev);
  return SC_OK;
}

/* --- the evaluation --------------------------------------------------- */

int chain_eval_n_ex(void *inst, const double *d, unsigned flags,
                    const sc_itin_code *force, sc_itin_code *code,
                    sc_bordern_list *borders, sc_mapn_value *out,
                    sc_msg *msg) {
  chain_inst *c = inst;
  if (force && force->n == 0) force = NULL;
  if (code) code->n = 0;
  if (c->N > CODE_BLOCKS || c->numerical) {
    if (force)
      return sc_fail(msg, SC_EINVAL,
                     "chain: itinerary codes are for exact flows and chains "
                     "of up to %d blocks (blocks = %d%s)",
                     CODE_BLOCKS, c->N,
                     c->numerical ? ", numerical flows" : "");
    return chain_eval_n(inst, d, flags, out, msg); /* no code, no borders */
  }
  if (!force && !code && !borders) return chain_eval_n(inst, d, flags, out, msg);
  chain_bx x = {.force = force, .rec_ok = 1, .bl = borders};
  double *buf = NULL;
  if (borders) {
    size_t P = (size_t)c->P, N = (size_t)c->N;
    buf = malloc((3 * P + 10 * N) * sizeof *buf);
    if (!buf) return sc_fail(msg, SC_ENOMEM, "chain: out of memory");
    x.dT = buf, x.dA = buf + P, x.dm = buf + 2 * P;
    x.w = buf + 3 * P, x.a = x.w + 2 * N, x.b = x.a + 2 * N;
    x.ha = x.b + 2 * N, x.hb = x.ha + 2 * N;
  }
  c->bx = &x;
  int st = chain_eval_n(inst, d, flags, out, msg);
  if (!st && borders) switching_codes(c);
  c->bx = NULL;
  free(buf);
  if (!st && force && x.fpos != force->n)
    st = sc_fail(msg, SC_EINVAL,
                 "chain: the forced itinerary code goes on after the slip "
                 "ends (%d of its %d bytes followed)",
                 x.fpos, force->n);
  if (!st && code && x.rec_ok) *code = x.rec;
  return st;
}
