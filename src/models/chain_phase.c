/* One slip phase of the chain (docs/chain.md, "Exact flows" and
 * "Events"): the runs of slipping blocks, each solved in closed form in
 * the eigenbasis of its coupling matrix; every guard as a linear term
 * plus sinusoids of the runs' frequencies; the first events by the
 * certified search (sc_guard_long_first_root()); the state at the event
 * and, on request, its sensitivities to d and the parameters, carried
 * through the flow and the event time. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "chain_impl.h"
#include "slipcont/hybrid.h"

/* Rounding of a guard's value: a few ulps of its terms' size, as the
 * search's own bound (guard_long.c). */
#define CHAIN_ROUND_ULPS 8.0
/* Two roots within this many event tolerances (atol + rtol t) are one
 * instant, as bk2 ties them (twice its tie tolerance). */
#define CHAIN_TIE_TOLS 2.0
/* The side-by-side march's first round reaches an eighth of a turn of a
 * mode of frequency 1 (the slowest there is), each round after twice as
 * far: a phase that lasts T costs its guards their march to at most 2T
 * (in instructions on three blocks in chaos, an eighth and twice took 15%
 * fewer than one turn and four times, and within 1% of a quarter and
 * 1.5 times). */
#define CHAIN_FIRST_REACH (CHAIN_TWO_PI / 8)
#define CHAIN_REACH_GROWTH 2.0

/* --- runs and their modal data ------------------------------------- */

/* The shape of a run and whether its basis is read backwards. */
static int run_shape(const chain_inst *c, int start, int m, int *rev) {
  *rev = 0;
  if (m == c->N) return SHAPE_WHOLE;
  if (c->ring) return SHAPE_INNER;
  if (start == 0) return SHAPE_END;
  if (start + m == c->N) {
    *rev = 1;
    return SHAPE_END;
  }
  return SHAPE_INNER;
}

static int add_run(chain_inst *c, int start, int m, size_t *used, int *off,
                   sc_msg *msg) {
  chain_run *r = &c->runs[c->nruns++];
  r->start = start, r->m = m, r->off = *off;
  *off += m;
  return chain_basis_of(c, run_shape(c, start, m, &r->rev), m, used, &r->B,
                        msg);
}

/* The maximal runs of slipping blocks (a ring's may wrap around). */
int chain_find_runs(chain_inst *c, sc_msg *msg) {
  int N = c->N, off = 0, first = 0;
  size_t used = 0;
  c->nruns = 0;
  if (c->ring) {
    while (first < N && c->slip[first]) first++;
    if (first == N) return add_run(c, 0, N, &used, &off, msg);
  }
  /* from a stuck block (the ring) or block 1 (open), once around */
  for (int k = 0; k < N;) {
    int j = (first + k) % N;
    if (!c->slip[j]) {
      k++;
      continue;
    }
    int m = 0;
    while (k + m < N && c->slip[(first + k + m) % N]) m++;
    int st = add_run(c, j, m, &used, &off, msg);
    if (st) return st;
    k += m;
  }
  return SC_OK;
}

/* Block of element i of run r, and the row of its basis. */
#define run_block chain_run_block
#define run_row chain_run_row

/* The slipping block's forcing F0 + F1 s: its kinetic friction and its
 * stuck neighbours' springs, those neighbours moving at Vs. */
static void forcing(const chain_inst *c, int b, double *F0, double *F1) {
  int nb[2], k = chain_neighbours(c, b, nb);
  *F0 = c->K[b], *F1 = 0;
  for (int q = 0; q < k; q++)
    if (!c->slip[nb[q]]) {
      *F0 += c->alpha * c->Y0[nb[q]];
      *F1 += c->alpha * c->Vs;
    }
}

/* Modal data of run r from the phase's start state: z_k(s) = P0 + P1 s +
 * A cos(om s) + B sin(om s) solves z'' + lam z = Q^T (F0 + F1 s). */
static void run_modes(chain_inst *c, const chain_run *r) {
  int m = r->m;
  for (int k = 0; k < m; k++) {
    const double *q = r->B.Q + (size_t)k * m;
    double f0 = 0, f1 = 0, z0 = 0, zp0 = 0;
    for (int i = 0; i < m; i++) {
      int b = run_block(c, r, i);
      double qi = q[run_row(r, i)], F0, F1;
      forcing(c, b, &F0, &F1);
      f0 += qi * F0, f1 += qi * F1;
      z0 += qi * c->Y0[b], zp0 += qi * c->U0[b];
    }
    int o = r->off + k;
    c->lam[o] = 1 + c->alpha * r->B.mu[k];
    c->om[o] = sqrt(c->lam[o]);
    c->P0[o] = f0 / c->lam[o];
    c->P1[o] = f1 / c->lam[o];
    c->A[o] = z0 - c->P0[o];
    c->B[o] = (zp0 - c->P1[o]) / c->om[o];
  }
}

/* --- guards ---------------------------------------------------------- */

/* The run a slipping block belongs to, and its element there. */
static const chain_run *run_of(const chain_inst *c, int b, int *elem) {
  for (int r = 0; r < c->nruns; r++) {
    const chain_run *R = &c->runs[r];
    int i = (b - R->start + c->N) % c->N;
    if (i < R->m) {
      *elem = i;
      return R;
    }
  }
  return NULL;
}

/* Re-stick guard of slipping block b: U_b - Vs, its terms at offset
 * `at` of the phase's guard storage (c->ga, c->gb). */
static void restick_guard(chain_inst *c, int b, sc_guard_long *g, size_t at) {
  int i;
  const chain_run *r = run_of(c, b, &i);
  double *ga = c->ga + at, *gb = c->gb + at;
  *g = (sc_guard_long){-c->Vs, 0, r->m, c->om + r->off, ga, gb};
  for (int k = 0; k < r->m; k++) {
    int o = r->off + k;
    double q = r->B.Q[run_row(r, i) + (size_t)k * r->m];
    g->c0 += q * c->P1[o];
    ga[k] = q * c->B[o] * c->om[o];
    gb[k] = -q * c->A[o] * c->om[o];
  }
}

/* Threshold guard of stuck block j: S_j - T_j, S_j = (1 + alpha deg) Y_j
 * - alpha (sum of the neighbours' Y); a slipping neighbour brings its
 * run's modes (a ring's run of N - 1 blocks has j on both sides and
 * brings them twice: the terms stay apart, which only loosens the
 * search's bound a little).  Its terms at offset `at` of the phase's
 * guard storage.  Returns 1 if j has a slipping neighbour. */
static int threshold_guard(chain_inst *c, int j, sc_guard_long *g,
                           size_t at) {
  int nb[2], nn = chain_neighbours(c, j, nb), osc = 0;
  double al = c->alpha, gain = 1 + al * chain_degree(c, j);
  double *gw = c->gw + at, *ga = c->ga + at, *gb = c->gb + at;
  *g = (sc_guard_long){gain * c->Y0[j] - c->T[j], gain * c->Vs, 0, gw, ga,
                       gb};
  for (int q = 0; q < nn; q++) {
    int n = nb[q], i;
    if (!c->slip[n]) {
      g->c0 -= al * c->Y0[n];
      g->c1 -= al * c->Vs;
      continue;
    }
    osc = 1;
    const chain_run *r = run_of(c, n, &i);
    for (int k = 0; k < r->m; k++) {
      int o = r->off + k;
      double w = -al * r->B.Q[run_row(r, i) + (size_t)k * r->m];
      g->c0 += w * c->P0[o];
      g->c1 += w * c->P1[o];
      gw[g->n] = c->om[o];
      ga[g->n] = w * c->A[o];
      gb[g->n] = w * c->B[o];
      g->n++;
    }
  }
  return osc;
}

/* --- the first events ------------------------------------------------ */

typedef struct {
  chain_event *ev;
  int n;
  double best;   /* earliest root so far (HUGE_VAL: none) */
  double best_u; /* how well it is known (root_spread()) */
  double H;      /* the horizon of guards with sinusoids */
} chain_search;

/* Two roots this close to t are one instant, when both are known exactly
 * (add each root's own spread, root_spread()). */
static double tie_window(const chain_inst *c, double t) {
  return CHAIN_TIE_TOLS * (c->acc.event_atol + c->acc.event_rtol * t);
}

/* How well the root t of g is known: the rounding of g there over its
 * slope, and no more than sqrt(2 rounding / M2) (a root where g only
 * touches zero).  Roots of guards that are equal by a symmetry (the two
 * ends of a mirrored chain) differ by about this much: a slope of 0.02
 * turns a rounding of 4e-16 into 2e-14, past the event tolerance. */
static double root_spread(const sc_guard_long *g, double t, double slope) {
  double size = fabs(g->c0) + fabs(g->c1) * t, M2 = 0;
  for (int k = 0; k < g->n; k++) {
    double amp = sqrt(g->a[k] * g->a[k] + g->b[k] * g->b[k]);
    size += amp * (1 + g->w[k] * t);
    M2 += g->w[k] * g->w[k] * amp;
  }
  double r = CHAIN_ROUND_ULPS * DBL_EPSILON * size;
  double u = fabs(slope) > 0 ? r / fabs(slope) : HUGE_VAL;
  return M2 > 0 ? fmin(u, sqrt(2 * r / M2)) : fmin(u, r);
}

/* Whether a root at t known to u is at the instant of the earliest one. */
static int at_best(const chain_inst *c, const chain_search *S, double t,
                   double u) {
  return t <= S->best + tie_window(c, S->best) + S->best_u + u;
}

/* Whether g can never reach zero: no positive drift, and its constant
 * plus every amplitude below minus its rounding. */
static int never_zero(const sc_guard_long *g) {
  if (g->c1 > 0) return 0;
  double top = g->c0, size = fabs(g->c0);
  for (int k = 0; k < g->n; k++) {
    double amp = sqrt(g->a[k] * g->a[k] + g->b[k] * g->b[k]);
    top += amp, size += amp;
  }
  return top < -CHAIN_ROUND_ULPS * DBL_EPSILON * size;
}

static void record(chain_search *S, int kind, int block, double t,
                   double slope, double u) {
  S->ev[S->n++] = (chain_event){kind, block, t, slope, u};
  if (t < S->best) S->best = t, S->best_u = u;
}

/* A stuck block whose neighbours are stuck too: S_j - T_j = c0 + Vs t. */
static void linear_threshold(const sc_guard_long *g, int j, chain_search *S) {
  double r = CHAIN_ROUND_ULPS * DBL_EPSILON * (fabs(g->c0) + fabs(g->c1));
  if (!(g->c1 > 0)) return;
  record(S, CHAIN_THRESHOLD, j, g->c0 >= -r ? 0 : -g->c0 / g->c1, g->c1,
         r / g->c1);
}

/* How far the guards are marched: the earliest root so far plus a tie
 * window (where a root known as well as that one is at its instant), or
 * the round's reach L while there is none; never past the horizon. */
static double search_lim(const chain_inst *c, const chain_search *S,
                         double L) {
  if (S->best < HUGE_VAL)
    return fmin(S->H, S->best + tie_window(c, S->best) + 2 * S->best_u);
  return fmin(S->H, L);
}

/* The guards marched in a phase: block, guard (its terms in the phase's
 * guard storage), march, and how far it has been marched. */
typedef struct {
  int n;
  int block[CHAIN_MAXBLOCKS];
  sc_guard_long g[CHAIN_MAXBLOCKS];
  sc_guard_long_march m[CHAIN_MAXBLOCKS];
  double reached[CHAIN_MAXBLOCKS];
} chain_marches;

/* March guard i from where it stands up to lim, and record its root. */
static int advance_guard(chain_inst *c, chain_marches *M, int i, double lim,
                         chain_search *S, sc_msg *msg) {
  int b = M->block[i], kind = c->slip[b] ? CHAIN_RESTICK : CHAIN_THRESHOLD;
  sc_root_long r;
  int st = sc_guard_long_advance(&M->g[i], lim,
                                 kind == CHAIN_RESTICK && c->fresh[b], &M->m[i],
                                 &r);
  M->reached[i] = lim;
  /* the guards are built from finite parameters, so a refused one has
   * overflowed: a state far too large (Newton's steps can go there) */
  if (st)
    return sc_fail(msg, st == SC_EINVAL ? SC_ENONFINITE : st,
                   "chain: the %s guard of block %d could not be searched "
                   "(%s)",
                   kind == CHAIN_RESTICK ? "re-stick" : "threshold", b + 1,
                   st == SC_EINVAL ? "its terms overflow: a state too large"
                                   : "a start on zero, or too many steps");
  /* found once: a march over is not advanced again */
  if (r.found)
    record(S, kind, b, r.t, r.slope, root_spread(&M->g[i], r.t, r.slope));
  return SC_OK;
}

/* Keep guard g of block b for the march unless it can never fire. */
static void keep(chain_marches *M, int b, const sc_guard_long *g,
                 size_t *at) {
  if (never_zero(g)) return;
  M->block[M->n] = b;
  M->g[M->n] = *g;
  M->m[M->n].stage = SC_MARCH_NEW;
  M->reached[M->n++] = -1;
  *at += (size_t)g->n;
}

/* Every guard of the phase.  Thresholds of blocks between stuck ones are
 * linear: their roots come first, in closed form.  The others are built
 * once and marched side by side (sc_guard_long_advance()) in rounds
 * reaching CHAIN_FIRST_REACH, then CHAIN_REACH_GROWTH times further each
 * round, until a root is found; then every guard only up to that root's
 * instant.  A guard that never fires before the phase ends is so marched
 * not much further than the phase's end, not to the horizon.  Each
 * guard's root is the one a search of it alone finds. */
static int search_all(chain_inst *c, chain_search *S, sc_msg *msg) {
  chain_marches M;
  sc_guard_long g;
  int N = c->N, st = SC_OK;
  size_t at = 0;
  M.n = 0;
  /* thresholds (linear ones recorded), then re-sticks of blocks that
   * slipped before, then fresh blocks' (their start on zero skipped) */
  for (int j = 0; j < N; j++)
    if (!c->slip[j]) {
      if (!threshold_guard(c, j, &g, at)) linear_threshold(&g, j, S);
      else keep(&M, j, &g, &at);
    }
  for (int pass = 0; pass < 2; pass++)
    for (int b = 0; b < N; b++)
      if (c->slip[b] && c->fresh[b] == pass) {
        restick_guard(c, b, &g, at);
        keep(&M, b, &g, &at);
      }
  for (double L = CHAIN_FIRST_REACH;; L *= CHAIN_REACH_GROWTH) {
    int final = S->best < HUGE_VAL;
    for (int i = 0; i < M.n && !st; i++) {
      double lim = search_lim(c, S, L);
      if (M.m[i].stage != SC_MARCH_DONE && M.reached[i] < lim)
        st = advance_guard(c, &M, i, lim, S, msg);
    }
    /* with a root found in this round: one more, up to its instant */
    if (st || final || (S->best == HUGE_VAL && L >= S->H)) return st;
  }
}

/* --- the state at the event and its sensitivities -------------------- */

/* Positions, velocities and accelerations (c->mzp holds them per block
 * for the sensitivities) at time t of the phase.  (inline: called from
 * chain_phase() and from the borders' chain_guard_sens(), it stays in
 * the first, as before the second came: 0.3% of a three-block iterate.) */
static inline void state_at(chain_inst *c, double t) {
  for (int j = 0; j < c->N; j++)
    if (!c->slip[j]) {
      c->Y[j] = c->Y0[j] + c->Vs * t;
      c->U[j] = c->Vs;
    }
  for (int r = 0; r < c->nruns; r++) {
    const chain_run *R = &c->runs[r];
    for (int k = 0; k < R->m; k++) {
      int o = R->off + k;
      c->cs[o] = cos(c->om[o] * t);
      c->sn[o] = sin(c->om[o] * t);
    }
    for (int i = 0; i < R->m; i++) {
      int b = run_block(c, R, i);
      double y = 0, u = 0;
      for (int k = 0; k < R->m; k++) {
        int o = R->off + k;
        double q = R->B.Q[run_row(R, i) + (size_t)k * R->m];
        y += q * (c->P0[o] + c->P1[o] * t + c->A[o] * c->cs[o] +
                  c->B[o] * c->sn[o]);
        u += q * (c->P1[o] +
                  c->om[o] * (c->B[o] * c->cs[o] - c->A[o] * c->sn[o]));
      }
      c->Y[b] = y, c->U[b] = u;
    }
  }
}

/* Acceleration of block b at the event (0 when stuck). */
static double accel_at(const chain_inst *c, int b) {
  int i;
  if (!c->slip[b]) return 0;
  const chain_run *R = run_of(c, b, &i);
  double a = 0;
  for (int k = 0; k < R->m; k++) {
    int o = R->off + k;
    a -= R->B.Q[run_row(R, i) + (size_t)k * R->m] * c->lam[o] *
         (c->A[o] * c->cs[o] + c->B[o] * c->sn[o]);
  }
  return a;
}

/* A direction of the sensitivities: column col is d_(col+1) for col < N -
 * 1, else parameter q = col - (N - 1). */
typedef struct {
  int q;
  double da, dphi, dW;
} chain_dir;

static chain_dir dir_of(const chain_inst *c, int col) {
  int q = col - (c->N - 1);
  chain_dir D = {q, q == P_ALPHA, q == P_PHI, 0};
  D.dW = !c->frozen && q == P_V;
  return D;
}

/* d T_b along D (thresholds of blocks 2..5 are parameters). */
static double dT_of(const chain_dir *D, int b) {
  return b >= 1 && b < CHAIN_PARAM_BLOCKS && D->q == P_BETA2 + b - 1;
}

/* d of run R's positions and velocities at time t of the phase, t held
 * fixed, along D, from the start's (ty, tu) into c->NY, c->NU. */
static void run_sens(chain_inst *c, const chain_run *R, const chain_dir *D,
                     const double *ty, const double *tu, double t) {
  int m = R->m;
  double al = c->alpha;
  for (int k = 0; k < m; k++) {
    const double *q = R->B.Q + (size_t)k * m;
    double df0 = 0, df1 = 0, dz0 = 0, dzp0 = 0;
    for (int i = 0; i < m; i++) {
      int b = run_block(c, R, i), nb[2], nn = chain_neighbours(c, b, nb);
      double qi = q[run_row(R, i)];
      double dF0 = dT_of(D, b) / c->phi - c->K[b] / c->phi * D->dphi, dF1 = 0;
      for (int s = 0; s < nn; s++)
        if (!c->slip[nb[s]]) {
          dF0 += D->da * c->Y0[nb[s]] + al * ty[nb[s]];
          dF1 += D->da * c->Vs + al * D->dW;
        }
      df0 += qi * dF0, df1 += qi * dF1;
      dz0 += qi * ty[b], dzp0 += qi * tu[b];
    }
    int o = R->off + k;
    double lam = c->lam[o], om = c->om[o], A = c->A[o], B = c->B[o];
    double dlam = R->B.mu[k] * D->da, dom = dlam / (2 * om);
    double dP0 = (df0 - c->P0[o] * dlam) / lam;
    double dP1 = (df1 - c->P1[o] * dlam) / lam;
    double dA = dz0 - dP0, dB = (dzp0 - dP1) / om - B * dom / om;
    double cs = c->cs[o], sn = c->sn[o], dth = t * dom;
    c->mz[o] = dP0 + dP1 * t + dA * cs + dB * sn + (B * cs - A * sn) * dth;
    c->mzp[o] = dP1 - (dA * om + A * dom) * sn + (dB * om + B * dom) * cs -
                (A * cs + B * sn) * om * dth;
  }
  for (int i = 0; i < m; i++) {
    int b = run_block(c, R, i);
    double y = 0, u = 0;
    for (int k = 0; k < m; k++) {
      double qk = R->B.Q[run_row(R, i) + (size_t)k * m];
      y += qk * c->mz[R->off + k];
      u += qk * c->mzp[R->off + k];
    }
    c->NY[b] = y, c->NU[b] = u;
  }
}

/* d of the guard that ended the phase, the event time held fixed (from
 * c->NY, c->NU), and its rate of change. */
static void event_sens(const chain_inst *c, const chain_event *e,
                       const chain_dir *D, double *dg, double *gdot) {
  int j = e->block;
  if (e->kind == CHAIN_RESTICK) {
    *dg = c->NU[j] - D->dW;
    *gdot = c->Ad[j];
    return;
  }
  int nb[2], nn = chain_neighbours(c, j, nb), deg = chain_degree(c, j);
  double gain = 1 + c->alpha * deg, ysum = 0, dysum = 0, usum = 0;
  for (int s = 0; s < nn; s++) {
    ysum += c->Y[nb[s]];
    dysum += c->NY[nb[s]];
    usum += c->U[nb[s]];
  }
  *dg = D->da * (deg * c->Y[j] - ysum) + gain * c->NY[j] -
        c->alpha * dysum - dT_of(D, j);
  *gdot = gain * c->Vs - c->alpha * usum;
}

/* Carry the sensitivities c->TY, c->TU from the phase's start to its
 * event e at time t (c->Y, c->U hold the state there): through the
 * closed-form flow, and through the event time, whose derivative is
 * -(d guard) / (guard's rate). */
static void sens_at(chain_inst *c, const chain_event *e, double t) {
  int N = c->N;
  for (int b = 0; b < N; b++) c->Ad[b] = accel_at(c, b);
  for (int col = 0; col < c->P; col++) {
    chain_dir D = dir_of(c, col);
    double *ty = c->TY + (size_t)col * N, *tu = c->TU + (size_t)col * N;
    for (int j = 0; j < N; j++)
      if (!c->slip[j]) {
        c->NY[j] = ty[j] + D.dW * t;
        c->NU[j] = D.dW;
      }
    for (int r = 0; r < c->nruns; r++) run_sens(c, &c->runs[r], &D, ty, tu, t);
    double dg, gdot;
    event_sens(c, e, &D, &dg, &gdot);
    double ds = -dg / gdot;
    for (int b = 0; b < N; b++) {
      ty[b] = c->NY[b] + (c->slip[b] ? c->U[b] : c->Vs) * ds;
      tu[b] = c->NU[b] + c->Ad[b] * ds;
    }
  }
}

/* --- one phase -------------------------------------------------------- */

int chain_phase(chain_inst *c, int deriv, chain_event *ev, int *nev,
                sc_msg *msg) {
  memcpy(c->Y0, c->Y, (size_t)c->N * sizeof(double));
  memcpy(c->U0, c->U, (size_t)c->N * sizeof(double));
  int st = chain_find_runs(c, msg);
  if (st) return st;
  for (int r = 0; r < c->nruns; r++) run_modes(c, &c->runs[r]);
  chain_search S = {ev, 0, HUGE_VAL, 0, CHAIN_HORIZON_TURNS * CHAIN_TWO_PI};
  st = search_all(c, &S, msg);
  if (st) return st;
  if (S.n == 0)
    return sc_fail(msg, SC_EUNDEF,
                   "chain: no event within %g time units of a slip phase "
                   "(a slip cycle that never returns to a global stick "
                   "phase?)",
                   S.H);
  /* the events at the earliest instant, the earliest first */
  int n = 0, first = 0;
  for (int i = 0; i < S.n; i++)
    if (at_best(c, &S, ev[i].t, ev[i].u)) {
      ev[n] = ev[i];
      if (ev[n].t < ev[first].t) first = n;
      n++;
    }
  chain_event e0 = ev[first];
  ev[first] = ev[0];
  ev[0] = e0;
  *nev = n;
  if (c->bx) { /* forced events, codes, borders: chain_border.c */
    st = chain_bx_phase(c, ev, nev, msg);
    if (st) return st;
    e0 = ev[0];
  }
  state_at(c, e0.t);
  if (deriv) sens_at(c, &e0, e0.t);
  return SC_OK;
}

/* --- for the borders (chain_border.c) --------------------------------- */

void chain_guard_of(chain_inst *c, int kind, int block, sc_guard_long *g) {
  /* at the start of the phase's guard storage: the search is over */
  if (kind == CHAIN_RESTICK) restick_guard(c, block, g, 0);
  else threshold_guard(c, block, g, 0);
}

void chain_guard_sens(chain_inst *c, int kind, int block, double t,
                      double *dg, double *gdot) {
  int N = c->N;
  chain_event e = {kind, block, t, 0, 0};
  state_at(c, t);
  for (int b = 0; b < N; b++) c->Ad[b] = accel_at(c, b);
  for (int col = 0; col < c->P; col++) {
    chain_dir D = dir_of(c, col);
    const double *ty = c->TY + (size_t)col * N, *tu = c->TU + (size_t)col * N;
    for (int j = 0; j < N; j++)
      if (!c->slip[j]) {
        c->NY[j] = ty[j] + D.dW * t;
        c->NU[j] = D.dW;
      }
    for (int r = 0; r < c->nruns; r++) run_sens(c, &c->runs[r], &D, ty, tu, t);
    event_sens(c, &e, &D, &dg[col], gdot);
  }
}
