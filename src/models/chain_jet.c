/* Exact second and third derivatives of the chain's event map
 * (docs/chain.md, "What is exact"): H = f_xx, Jp = f_xp and T = f_xxx.
 *
 * An evaluation with SC_EVAL_DERIV2 records each phase it met (its
 * slipping set, the blocks that re-stick at its end, the event that ends
 * it and its time; chain_log_phase()).  chain_jet_fill() then replays
 * those phases in truncated Taylor arithmetic along a line x + s u of
 * the state, with first-order tangents eps_r in every variable (the n
 * components of x and the parameters): a jet holds the coefficients of
 *   s^k        (k <= 3)  and  s^k eps_r  (k <= 2),
 * all other products dropped (eps_r eps_q = 0, s^3 eps_r = 0; the kept
 * monomials are closed under division, so the truncation is exact).
 * Along u = e_a one replay gives, of every component f_i,
 *   s^0 eps_r: df_i/dx_r and df_i/dp_q,
 *   s^1 eps_r: H[i][a][r] and Jp[q][i][a],
 *   s^2 eps_r: T[i][a][a][r] / 2;
 * the T[i][a][b][c] of three distinct indices come from the replay
 * along e_a + e_b (N >= 4).  So n + (n - 1)(n - 2)/2 replays give every
 * tensor, exactly, with no differences.
 *
 * Each phase is the closed-form flow of its runs (the modal formulas of
 * chain_phase.c) on jets, with the time a jet: the event time tau is
 * the root of the guard that ended the phase, g(tau) = 0, found by
 * Newton's method in jet arithmetic started at the recorded root, its
 * value held there; each step at least doubles the order to which the
 * jet is exact (1, 3), as in bk2_jet.c.  No search is needed. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "chain_impl.h"

/* Tangent directions a jet may carry: the state's components (tensors
 * are kept up to SC_DIM_TENSOR, models.h) and the parameters. */
#define CJ_MAXE (SC_DIM_TENSOR + CHAIN_NPARAM)

/* Newton steps in jet arithmetic per event time: two make the jet exact
 * to third order (the error's order doubles from 1 to 2 to 4); the third
 * costs little and absorbs the rounding of the first two (bk2_jet.c). */
#define CJ_NEWTON 3

typedef struct {
  double s[4];          /* s^k */
  double e[3][CJ_MAXE]; /* s^k eps_r */
} cjet;

/* --- the arithmetic ------------------------------------------------- */

static inline cjet cj_const(double v) {
  cjet r;
  memset(&r, 0, sizeof r);
  r.s[0] = v;
  return r;
}

/* A variable with tangent eps_r (r < 0: none) and slope w along s. */
static inline cjet cj_var(double v, int r, double w) {
  cjet a = cj_const(v);
  if (r >= 0) a.e[0][r] = 1;
  a.s[1] = w;
  return a;
}

/* a + w b */
static inline cjet cj_axpy(cjet a, double w, const cjet *b, int ne) {
  for (int k = 0; k < 4; k++) a.s[k] += w * b->s[k];
  for (int k = 0; k < 3; k++)
    for (int r = 0; r < ne; r++) a.e[k][r] += w * b->e[k][r];
  return a;
}

static inline cjet cj_add(cjet a, cjet b, int ne) {
  return cj_axpy(a, 1, &b, ne);
}
static inline cjet cj_sub(cjet a, cjet b, int ne) {
  return cj_axpy(a, -1, &b, ne);
}
static inline cjet cj_scale(cjet a, double w, int ne) {
  for (int k = 0; k < 4; k++) a.s[k] *= w;
  for (int k = 0; k < 3; k++)
    for (int r = 0; r < ne; r++) a.e[k][r] *= w;
  return a;
}
static inline cjet cj_addc(cjet a, double c) {
  a.s[0] += c;
  return a;
}

static inline cjet cj_mul(const cjet a, const cjet b, int ne) {
  cjet r;
  for (int k = 0; k < 4; k++) {
    double v = 0;
    for (int i = 0; i <= k; i++) v += a.s[i] * b.s[k - i];
    r.s[k] = v;
  }
  for (int k = 0; k < 3; k++)
    for (int q = 0; q < ne; q++) {
      double v = 0;
      for (int i = 0; i <= k; i++)
        v += a.s[i] * b.e[k - i][q] + a.e[i][q] * b.s[k - i];
      r.e[k][q] = v;
    }
  return r;
}

/* phi(a) for phi with derivatives f0..f3 at a's value: with a = a0 +
 * delta, phi(a) = f0 + f1 delta + f2 delta^2 / 2 + f3 delta^3 / 6 (delta^4
 * vanishes), written out coefficient by coefficient. */
static inline cjet cj_compose(const cjet *a, double f0, double f1, double f2,
                              double f3, int ne) {
  cjet r;
  double d1 = a->s[1], d2 = a->s[2], d3 = a->s[3];
  r.s[0] = f0;
  r.s[1] = f1 * d1;
  r.s[2] = f1 * d2 + 0.5 * f2 * d1 * d1;
  r.s[3] = f1 * d3 + f2 * d1 * d2 + f3 * d1 * d1 * d1 / 6;
  for (int q = 0; q < ne; q++) {
    double e0 = a->e[0][q], e1 = a->e[1][q], e2 = a->e[2][q];
    r.e[0][q] = f1 * e0;
    r.e[1][q] = f1 * e1 + f2 * d1 * e0;
    r.e[2][q] = f1 * e2 + f2 * (d1 * e1 + d2 * e0) + 0.5 * f3 * d1 * d1 * e0;
  }
  return r;
}

static inline cjet cj_inv(const cjet a, int ne) {
  double y = 1 / a.s[0];
  return cj_compose(&a, y, -y * y, 2 * y * y * y, -6 * y * y * y * y, ne);
}
static inline cjet cj_div(const cjet a, const cjet b, int ne) {
  return cj_mul(a, cj_inv(b, ne), ne);
}
static inline cjet cj_sqrt(const cjet a, int ne) {
  double s = sqrt(a.s[0]), x = a.s[0];
  return cj_compose(&a, s, 0.5 / s, -0.25 / (s * x), 0.375 / (s * x * x),
                    ne);
}
static inline void cj_sincos(const cjet a, int ne, cjet *s, cjet *c) {
  double sv = sin(a.s[0]), cv = cos(a.s[0]);
  *s = cj_compose(&a, sv, cv, -sv, -cv, ne);
  *c = cj_compose(&a, cv, -sv, -cv, sv, ne);
}

/* --- the record of one evaluation ------------------------------------ */

/* Per phase: its slipping set and the blocks re-sticking at its end
 * (bits of the flags below, one byte per block), the event that ends
 * it and its time. */
enum { LOG_SLIP = 1, LOG_RESTICK = 2 };

struct chain_log {
  int N, cap;           /* blocks and phases the buffers hold */
  int onset;            /* the block the onset placed the others from */
  int nph;              /* phases recorded */
  unsigned char *set;   /* [phase N + block] */
  double *t;            /* event times */
  int *kind, *block;    /* the events that end the phases */
  cjet *jets;           /* the replay's: 19 N */
};

void chain_log_free(chain_inst *c) {
  chain_log *L = c->log;
  if (!L) return;
  free(L->set);
  free(L->t);
  free(L->kind);
  free(L->jets);
  free(L);
  c->log = NULL;
}

/* Buffers for c->N blocks and max_events phases (taken once, and again
 * only when the chain or max_events grows). */
int chain_log_start(chain_inst *c, sc_msg *msg) {
  int N = c->N, cap = c->acc.max_events > 0 ? c->acc.max_events : 1;
  chain_log *L = c->log;
  if (!L || L->N != N || L->cap < cap) {
    chain_log_free(c);
    L = c->log = calloc(1, sizeof *L);
    if (L) {
      L->N = N, L->cap = cap;
      L->set = malloc((size_t)cap * N);
      L->t = malloc((size_t)cap * sizeof *L->t);
      L->kind = malloc(2 * (size_t)cap * sizeof *L->kind);
      L->jets = malloc(19 * (size_t)N * sizeof *L->jets);
    }
    if (!L || !L->set || !L->t || !L->kind || !L->jets) {
      chain_log_free(c);
      return sc_fail(msg, SC_ENOMEM,
                     "chain: out of memory for second derivatives (%d blocks)",
                     N);
    }
    L->block = L->kind + cap;
  }
  L->onset = c->onset_block;
  L->nph = 0;
  return SC_OK;
}

void chain_log_phase(chain_inst *c, const chain_event *ev, int nev) {
  chain_log *L = c->log;
  if (L->nph >= L->cap) return; /* the loop stops at max_events first */
  int N = c->N, p = L->nph++;
  unsigned char *s = L->set + (size_t)p * N;
  for (int i = 0; i < N; i++) s[i] = c->slip[i] ? LOG_SLIP : 0;
  for (int e = 0; e < nev; e++)
    if (ev[e].kind == CHAIN_RESTICK) s[ev[e].block] |= LOG_RESTICK;
  L->t[p] = ev[0].t;
  L->kind[p] = ev[0].kind;
  L->block[p] = ev[0].block;
}

/* --- the replay -------------------------------------------------------- */

typedef struct {
  chain_inst *c;
  const chain_log *L;
  int ne;                /* tangents: the n state components, then the
                            parameters that act */
  int pe[CHAIN_NPARAM];  /* parameter q's tangent, -1 if it does not act */
  cjet al, Vs;           /* alpha, the surface speed during slips */
  cjet *T, *K, *Y, *U, *Y0, *U0, *Ac, *F0, *F1;    /* per block */
  cjet *lam, *om, *P0, *P1, *A, *B, *z, *zp, *zpp; /* per mode */
  cjet *f;                                          /* the map's value */
} jreplay;

/* Whether parameter q acts on the map (its other derivatives are 0):
 * gamma never under Coulomb friction, v not with the driver frozen, the
 * thresholds of blocks the chain does not have. */
static int acts(const chain_inst *c, int q) {
  if (q == P_GAMMA) return 0;
  if (q == P_V) return !c->frozen;
  if (q >= P_BETA2) return q - P_BETA2 + 1 < c->N;
  return 1;
}

static void j_bind(jreplay *R, chain_inst *c) {
  int N = c->N, n = N - 1, ne = n;
  for (int q = 0; q < CHAIN_NPARAM; q++) R->pe[q] = acts(c, q) ? ne++ : -1;
  cjet **v[] = {&R->T,  &R->K,  &R->Y,  &R->U,  &R->Y0, &R->U0, &R->Ac,
                &R->F0, &R->F1, &R->lam, &R->om, &R->P0, &R->P1, &R->A,
                &R->B,  &R->z,  &R->zp, &R->zpp, &R->f};
  for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
    *v[i] = c->log->jets + i * (size_t)N;
  R->c = c, R->L = c->log, R->ne = ne;
  R->al = cj_var(c->alpha, R->pe[P_ALPHA], 0);
  R->Vs = c->frozen ? cj_const(0) : cj_var(c->v, R->pe[P_V], 0);
  cjet phi = cj_var(c->phi, R->pe[P_PHI], 0), iphi = cj_inv(phi, ne);
  for (int i = 0; i < N; i++) {
    R->T[i] = i > 0 && i < CHAIN_PARAM_BLOCKS
                  ? cj_var(c->T[i], R->pe[P_BETA2 + i - 1], 0)
                  : cj_const(c->T[i]);
    R->K[i] = cj_mul(R->T[i], iphi, ne);
  }
}

/* The onset (chain.c's onset()) on jets, the state x + s u: the blocks
 * placed from the recorded block at its threshold. */
static void j_onset(jreplay *R, const double *x, const double *u) {
  chain_inst *c = R->c;
  int N = c->N, ne = R->ne, j = R->L->onset;
  cjet *D = R->Y0, *cc = R->U0;
  D[0] = cj_const(0);
  for (int i = 1; i < N; i++)
    D[i] = cj_add(D[i - 1], cj_var(x[i - 1], i - 1, u[i - 1]), ne);
  for (int i = 0; i < N; i++) {
    int nb[2], nn = chain_neighbours(c, i, nb);
    cc[i] = cj_const(0);
    for (int s = 0; s < nn; s++)
      cc[i] = cj_add(cc[i], cj_sub(D[i], D[nb[s]], ne), ne);
  }
  cjet yj = cj_sub(R->T[j], cj_mul(R->al, cc[j], ne), ne);
  for (int i = 0; i < N; i++) {
    R->Y[i] = cj_add(yj, cj_sub(D[i], D[j], ne), ne);
    R->U[i] = R->Vs;
  }
}

/* Modal data of run r from the phase's start (chain_phase.c's
 * run_modes()), the blocks' forcing F0 + F1 s in R->F0, R->F1. */
static void j_modes(jreplay *R, const chain_run *r) {
  chain_inst *c = R->c;
  int m = r->m, ne = R->ne;
  for (int i = 0; i < m; i++) {
    int b = chain_run_block(c, r, i), nb[2], k = chain_neighbours(c, b, nb);
    R->F0[b] = R->K[b];
    R->F1[b] = cj_const(0);
    for (int q = 0; q < k; q++)
      if (!c->slip[nb[q]]) {
        R->F0[b] = cj_add(R->F0[b], cj_mul(R->al, R->Y0[nb[q]], ne), ne);
        R->F1[b] = cj_add(R->F1[b], cj_mul(R->al, R->Vs, ne), ne);
      }
  }
  for (int k = 0; k < m; k++) {
    const double *q = r->B.Q + (size_t)k * m;
    cjet f0 = cj_const(0), f1 = f0, z0 = f0, zp0 = f0;
    for (int i = 0; i < m; i++) {
      int b = chain_run_block(c, r, i);
      double qi = q[chain_run_row(r, i)];
      f0 = cj_axpy(f0, qi, &R->F0[b], ne);
      f1 = cj_axpy(f1, qi, &R->F1[b], ne);
      z0 = cj_axpy(z0, qi, &R->Y0[b], ne);
      zp0 = cj_axpy(zp0, qi, &R->U0[b], ne);
    }
    int o = r->off + k;
    R->lam[o] = cj_addc(cj_scale(R->al, r->B.mu[k], ne), 1);
    R->om[o] = cj_sqrt(R->lam[o], ne);
    cjet il = cj_inv(R->lam[o], ne);
    R->P0[o] = cj_mul(f0, il, ne);
    R->P1[o] = cj_mul(f1, il, ne);
    R->A[o] = cj_sub(z0, R->P0[o], ne);
    R->B[o] = cj_div(cj_sub(zp0, R->P1[o], ne), R->om[o], ne);
  }
}

/* Mode o at time tau of the phase: z, z' and z'' into R->z, R->zp,
 * R->zpp. */
static void j_mode_at(jreplay *R, int o, const cjet *tau) {
  int ne = R->ne;
  cjet sn, cs;
  cj_sincos(cj_mul(R->om[o], *tau, ne), ne, &sn, &cs);
  cjet osc = cj_add(cj_mul(R->A[o], cs, ne), cj_mul(R->B[o], sn, ne), ne);
  cjet rot = cj_sub(cj_mul(R->B[o], cs, ne), cj_mul(R->A[o], sn, ne), ne);
  R->z[o] = cj_add(cj_add(R->P0[o], cj_mul(R->P1[o], *tau, ne), ne), osc, ne);
  R->zp[o] = cj_add(R->P1[o], cj_mul(R->om[o], rot, ne), ne);
  R->zpp[o] = cj_scale(cj_mul(R->lam[o], osc, ne), -1, ne);
}

/* Element i (block b) of run r from its modes' z, z', z''. */
static void j_project(jreplay *R, const chain_run *r, int i, int b) {
  int m = r->m, ne = R->ne;
  cjet y = cj_const(0), v = y, a = y;
  for (int k = 0; k < m; k++) {
    double q = r->B.Q[chain_run_row(r, i) + (size_t)k * m];
    y = cj_axpy(y, q, &R->z[r->off + k], ne);
    v = cj_axpy(v, q, &R->zp[r->off + k], ne);
    a = cj_axpy(a, q, &R->zpp[r->off + k], ne);
  }
  R->Y[b] = y, R->U[b] = v, R->Ac[b] = a;
}

static void j_stuck_at(jreplay *R, int j, const cjet *tau) {
  R->Y[j] = cj_add(R->Y0[j], cj_mul(R->Vs, *tau, R->ne), R->ne);
  R->U[j] = R->Vs;
  R->Ac[j] = cj_const(0);
}

/* Positions, velocities and accelerations of every block at time tau of
 * the phase. */
static void j_state(jreplay *R, const cjet *tau) {
  chain_inst *c = R->c;
  for (int j = 0; j < c->N; j++)
    if (!c->slip[j]) j_stuck_at(R, j, tau);
  for (int ri = 0; ri < c->nruns; ri++) {
    const chain_run *r = &c->runs[ri];
    for (int k = 0; k < r->m; k++) j_mode_at(R, r->off + k, tau);
    for (int i = 0; i < r->m; i++) j_project(R, r, i, chain_run_block(c, r, i));
  }
}

/* The blocks the guard of (kind, j) reads (j, and a threshold's
 * neighbours) at time tau, their runs' modes computed once: what the
 * Newton steps need, without the whole state. */
static void j_guard_blocks(jreplay *R, int kind, int j, const cjet *tau) {
  chain_inst *c = R->c;
  int b[3] = {j, -1, -1}, nb = 1, done[3] = {-1, -1, -1};
  if (kind == CHAIN_THRESHOLD) nb += chain_neighbours(c, j, b + 1);
  for (int k = 0; k < nb; k++) {
    if (!c->slip[b[k]]) {
      j_stuck_at(R, b[k], tau);
      continue;
    }
    for (int ri = 0; ri < c->nruns; ri++) {
      const chain_run *r = &c->runs[ri];
      int i = (b[k] - r->start + c->N) % c->N;
      if (i >= r->m) continue;
      if (done[0] != ri && done[1] != ri && done[2] != ri)
        for (int q = 0; q < r->m; q++) j_mode_at(R, r->off + q, tau);
      done[k] = ri;
      j_project(R, r, i, b[k]);
      break;
    }
  }
}

/* The guard of the event that ended the phase, and its rate, from the
 * state at tau (a re-stick: U_b - Vs; a threshold: S_j - T_j). */
static void j_guard(jreplay *R, int kind, int j, cjet *g, cjet *rate) {
  int ne = R->ne;
  if (kind == CHAIN_RESTICK) {
    *g = cj_sub(R->U[j], R->Vs, ne);
    *rate = R->Ac[j];
    return;
  }
  chain_inst *c = R->c;
  int nb[2], nn = chain_neighbours(c, j, nb);
  cjet gain = cj_addc(cj_scale(R->al, chain_degree(c, j), ne), 1);
  cjet ys = cj_const(0), us = ys;
  for (int s = 0; s < nn; s++) {
    ys = cj_add(ys, R->Y[nb[s]], ne);
    us = cj_add(us, R->U[nb[s]], ne);
  }
  *g = cj_sub(cj_sub(cj_mul(gain, R->Y[j], ne), cj_mul(R->al, ys, ne), ne),
              R->T[j], ne);
  *rate = cj_sub(cj_mul(gain, R->U[j], ne), cj_mul(R->al, us, ne), ne);
}

/* Phase p of the record: its flow on jets to its event time, a jet found
 * by Newton's method on the guard, then the re-sticks at that instant
 * (their velocity is Vs whatever the direction).  Returns SC_OK, 1 where
 * the guard's slope is zero (f is not twice differentiable there), or a
 * negative status. */
static int j_phase(jreplay *R, int p, sc_msg *msg) {
  chain_inst *c = R->c;
  int N = c->N, ne = R->ne;
  const unsigned char *set = R->L->set + (size_t)p * N;
  for (int i = 0; i < N; i++) c->slip[i] = (set[i] & LOG_SLIP) != 0;
  memcpy(R->Y0, R->Y, (size_t)N * sizeof *R->Y);
  memcpy(R->U0, R->U, (size_t)N * sizeof *R->U);
  int st = chain_find_runs(c, msg);
  if (st) return st;
  for (int r = 0; r < c->nruns; r++) j_modes(R, &c->runs[r]);
  double t = R->L->t[p];
  cjet tau = cj_const(t);
  for (int it = 0; it < CJ_NEWTON; it++) {
    cjet g, rate;
    j_guard_blocks(R, R->L->kind[p], R->L->block[p], &tau);
    j_guard(R, R->L->kind[p], R->L->block[p], &g, &rate);
    if (rate.s[0] == 0 || !isfinite(rate.s[0])) return 1;
    tau = cj_sub(tau, cj_div(g, rate, ne), ne);
    tau.s[0] = t; /* the root of the ordinary evaluation */
  }
  j_state(R, &tau);
  for (int i = 0; i < N; i++)
    if (set[i] & LOG_RESTICK) R->U[i] = R->Vs;
  return SC_OK;
}

/* One replay of the recorded iterate along x + s u: f's jets in R->f. */
static int j_replay(jreplay *R, const double *x, const double *u,
                    sc_msg *msg) {
  j_onset(R, x, u);
  for (int p = 0; p < R->L->nph; p++) {
    int st = j_phase(R, p, msg);
    if (st) return st;
  }
  for (int i = 0; i + 1 < R->c->N; i++)
    R->f[i] = cj_sub(R->Y[i + 1], R->Y[i], R->ne);
  return SC_OK;
}

/* --- the tensors ------------------------------------------------------- */

static void fill_nan(sc_mapn_value *out) {
  size_t n = out->n, np = out->np;
  for (size_t i = 0; i < n * n * n; i++) out->H[i] = NAN;
  for (size_t i = 0; i < np * n * n; i++) out->Jp[i] = NAN;
  for (size_t i = 0; i < n * n * n * n; i++) out->T[i] = NAN;
}

/* T[i][a][b][c] and its permutations in (a, b, c). */
static void put_t(double *T, size_t n, size_t i, size_t a, size_t b,
                  size_t c, double v) {
  size_t p[6][3] = {{a, b, c}, {a, c, b}, {b, a, c},
                    {b, c, a}, {c, a, b}, {c, b, a}};
  for (int k = 0; k < 6; k++)
    T[((i * n + p[k][0]) * n + p[k][1]) * n + p[k][2]] = v;
}

/* Along u = e_a: H[i][a][.] (half of each symmetric pair, the other half
 * from the replay along that index), Jp[.][i][a], T[i][a][a][.]. */
static void take_axis(const jreplay *R, size_t a, sc_mapn_value *out) {
  size_t n = out->n, np = out->np;
  for (size_t i = 0; i < n; i++) {
    const cjet *f = &R->f[i];
    for (size_t r = 0; r < n; r++) {
      out->H[(i * n + a) * n + r] += 0.5 * f->e[1][r];
      out->H[(i * n + r) * n + a] += 0.5 * f->e[1][r];
      put_t(out->T, n, i, a, a, r, 2 * f->e[2][r]);
    }
    for (size_t q = 0; q < np; q++)
      out->Jp[(q * n + i) * n + a] = R->pe[q] < 0 ? 0 : f->e[1][R->pe[q]];
  }
}

int chain_jet_fill(chain_inst *c, const double *x, sc_mapn_value *out,
                   sc_msg *msg) {
  size_t n = out->n;
  if (n + CHAIN_NPARAM > CJ_MAXE || out->np != CHAIN_NPARAM)
    return sc_fail(msg, SC_EINVAL,
                   "chain: second derivatives are kept up to %d blocks "
                   "(blocks = %d)",
                   SC_DIM_TENSOR + 1, c->N);
  if (c->vw) {
    /* velocity weakening's flows are integrated (chain_vw.c), with no
     * closed form to replay: no second derivatives (docs/chain.md) */
    fill_nan(out);
    return SC_OK;
  }
  jreplay R;
  j_bind(&R, c);
  memset(out->H, 0, n * n * n * sizeof *out->H);
  double u[SC_DIM_TENSOR] = {0};
  for (size_t a = 0; a < n; a++) {
    u[a] = 1;
    int st = j_replay(&R, x, u, msg);
    u[a] = 0;
    if (st < 0) return st;
    if (st) {
      fill_nan(out);
      return SC_OK;
    }
    take_axis(&R, a, out);
  }
  /* three distinct indices a < b < c: along e_a + e_b, the coefficient of
   * s^2 eps_c is (T_aac + 2 T_abc + T_bbc) / 2 */
  for (size_t a = 0; a + 2 < n; a++)
    for (size_t b = a + 1; b + 1 < n; b++) {
      u[a] = u[b] = 1;
      int st = j_replay(&R, x, u, msg);
      u[a] = u[b] = 0;
      if (st < 0) return st;
      if (st) {
        fill_nan(out);
        return SC_OK;
      }
      for (size_t i = 0; i < n; i++)
        for (size_t cc = b + 1; cc < n; cc++) {
          const double *T = out->T;
          double taac = T[((i * n + a) * n + a) * n + cc];
          double tbbc = T[((i * n + b) * n + b) * n + cc];
          put_t(out->T, n, i, a, b, cc,
                R.f[i].e[2][cc] - 0.5 * (taac + tbbc));
        }
    }
  return SC_OK;
}
