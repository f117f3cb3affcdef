/* Slip events of the chain (docs/chain.md, "Event catalogue"): while
 * one iterate is evaluated through eval_event, the event loop of chain.c
 * calls these after the onset, after each phase and at the global stick
 * phase; they add up the slip's length, each block's slip relative to
 * the surface, the elastic energy released and the driver's work, from
 * the state at each phase's ends and the phase's closed-form modes
 * (chain_phase.c's P0, P1, A, B, om: exact flows only). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "chain_impl.h"

/* A trajectory's sink (chain_trajectory()): samples every dtau of each
 * phase and at its end, tau counted from the first slip's start. */
typedef struct {
  int (*fn)(void *, double, const double *, int);
  void *ctx;
  double dtau, tau;
  double *s; /* one sample: N positions, N velocities */
  int stop;  /* fn asked to stop */
} chain_traj;

struct chain_rec {
  sc_slip_event *ev;
  double t;    /* the slip's length so far */
  double ysum; /* integral of sum_i Y_i over it so far */
  double *Ys;  /* the positions at its start (N) */
  unsigned char slipped[CHAIN_MAXBLOCKS];
  chain_traj *traj; /* NULL: no samples */
};

void chain_rec_begin(chain_inst *c) {
  chain_rec *r = c->rec;
  r->t = r->ysum = 0;
  r->ev->first = 0;
  for (int i = 0; i < c->N; i++) {
    r->Ys[i] = c->Y[i];
    r->slipped[i] = 0;
    if (c->fresh[i]) r->ev->first = i + 1; /* the last of a tie, as onset */
  }
}

/* Integral over [0, t] of z(s) = P0 + P1 s + A cos(om s) + B sin(om s);
 * 1 - cos(om t) = 2 sin^2(om t / 2), which keeps its digits for short
 * phases. */
static double mode_integral(double P0, double P1, double A, double B, double om,
                            double t) {
  double h = sin(0.5 * om * t);
  return P0 * t + 0.5 * P1 * t * t + (A * sin(om * t) + B * 2 * h * h) / om;
}

/* Integral over the phase of sum_i Y_i: stuck blocks move at Vs, each run
 * of slipping blocks is the sum of its modes weighted by the sums of its
 * eigenvectors' components. */
static double phase_ysum(const chain_inst *c, double t) {
  double s = 0;
  for (int j = 0; j < c->N; j++)
    if (!c->slip[j]) s += c->Y0[j] * t + 0.5 * c->Vs * t * t;
  for (int r = 0; r < c->nruns; r++) {
    const chain_run *R = &c->runs[r];
    for (int k = 0; k < R->m; k++) {
      int o = R->off + k;
      double qsum = 0;
      for (int i = 0; i < R->m; i++)
        qsum += R->B.Q[i + (size_t)k * R->m];
      s += qsum *
           mode_integral(c->P0[o], c->P1[o], c->A[o], c->B[o], c->om[o], t);
    }
  }
  return s;
}

/* The state at time t of the phase into s (positions, then velocities)
 * from its modes, as chain_phase.c's state at its event. */
static void phase_state(const chain_inst *c, double t, double *s) {
  int N = c->N;
  for (int j = 0; j < N; j++)
    if (!c->slip[j]) s[j] = c->Y0[j] + c->Vs * t, s[N + j] = c->Vs;
  for (int r = 0; r < c->nruns; r++) {
    const chain_run *R = &c->runs[r];
    for (int i = 0; i < R->m; i++) {
      int b = (R->start + i) % N, row = R->rev ? R->m - 1 - i : i;
      double y = 0, u = 0;
      for (int k = 0; k < R->m; k++) {
        int o = R->off + k;
        double q = R->B.Q[row + (size_t)k * R->m], cs = cos(c->om[o] * t),
               sn = sin(c->om[o] * t);
        y += q * (c->P0[o] + c->P1[o] * t + c->A[o] * cs + c->B[o] * sn);
        u += q * (c->P1[o] + c->om[o] * (c->B[o] * cs - c->A[o] * sn));
      }
      s[b] = y, s[N + b] = u;
    }
  }
}

/* The samples of a phase of length t: every dtau from its start, then
 * its end (as bk2's trajectories). */
static void sample_phase(chain_inst *c, chain_traj *T, double t) {
  int N = c->N, mode = 0;
  for (int i = 0; i < N; i++)
    mode += c->slip[i];
  long n = (long)floor(t / T->dtau);
  for (long i = 0; i <= n + 1 && !T->stop; i++) {
    if (i <= n) {
      phase_state(c, i * T->dtau, T->s);
    } else {
      memcpy(T->s, c->Y, (size_t)N * sizeof(double));
      memcpy(T->s + N, c->U, (size_t)N * sizeof(double));
    }
    T->stop = T->fn(T->ctx, T->tau + (i <= n ? i * T->dtau : t), T->s, mode);
  }
  T->tau += t;
}

void chain_rec_phase(chain_inst *c, double t) {
  chain_rec *r = c->rec;
  if (r->traj && !r->traj->stop) sample_phase(c, r->traj, t);
  r->t += t;
  r->ysum += phase_ysum(c, t);
  for (int i = 0; i < c->N; i++)
    r->slipped[i] |= (unsigned char)c->slip[i];
}

/* Spring force on block i from positions y (docs/chain.md, "Equations"). */
static double spring(const chain_inst *c, const double *y, int i) {
  int nb[2], k = chain_neighbours(c, i, nb);
  double s = y[i];
  for (int q = 0; q < k; q++)
    s += c->alpha * (y[i] - y[nb[q]]);
  return s;
}

void chain_rec_end(chain_inst *c) {
  chain_rec *r = c->rec;
  sc_slip_event *ev = r->ev;
  int N = c->N;
  double *dY = c->NY; /* scratch: the displacements, Y_end - Y_start */
  for (int i = 0; i < N; i++)
    dY[i] = c->Y[i] - r->Ys[i];
  /* E quadratic: E(Ys + dY) - E(Ys) = S(Ys) . dY + dY . S(dY) / 2, free
   * of the cancellation of two large energies */
  double rel = 0, gap = HUGE_VAL;
  ev->nblocks = N;
  ev->nslipped = 0;
  ev->slip = ev->friction = 0;
  for (int i = 0; i < N; i++) {
    rel -= dY[i] * (spring(c, r->Ys, i) + 0.5 * spring(c, dY, i));
    double b = r->slipped[i] ? c->Vs * r->t - dY[i] : 0;
    ev->bslip[i] = b;
    ev->slipped[i] = r->slipped[i];
    ev->nslipped += r->slipped[i];
    ev->slip += b;
    ev->friction += c->K[i] * b;
    gap = fmin(gap, c->T[i] - spring(c, c->Y, i));
  }
  ev->released = rel;
  /* sum_i S_i = sum_i Y_i: the coupling springs' forces cancel */
  ev->driver = c->Vs * r->ysum;
  ev->duration = r->t;
  ev->stick = c->v > 0 ? fmax(0, gap) / c->v : HUGE_VAL;
}

int chain_eval_event(void *inst, const double *x, unsigned flags,
                     sc_mapn_value *out, sc_slip_event *ev, sc_msg *msg) {
  chain_inst *c = inst;
  if (c->numerical)
    return sc_fail(msg, SC_EINVAL,
                   "chain: slip events are recorded with flows = exact "
                   "(Coulomb friction) only");
  double ys[CHAIN_MAXBLOCKS];
  chain_rec rec = {ev, 0, 0, ys, {0}, NULL};
  c->rec = &rec;
  int st = chain_eval_n(inst, x, flags, out, msg);
  c->rec = NULL;
  return st;
}

/* The model's trajectory_n (models.h): each iterate recorded with its
 * phases sampled, then its global stick phase, every block moving at V
 * until the smallest gap closes (passed at once with V = 0, as bk2). */
int chain_trajectory(void *inst, const double *x, int iterations, double dtau,
                     int (*fn)(void *, double, const double *, int), void *ctx,
                     sc_msg *msg) {
  chain_inst *c = inst;
  if (c->numerical)
    return sc_fail(msg, SC_EINVAL,
                   "chain: trajectories are sampled with flows = exact "
                   "(Coulomb friction) only");
  int N = c->N;
  double ys[CHAIN_MAXBLOCKS], s[2 * CHAIN_MAXBLOCKS], d[CHAIN_MAXBLOCKS];
  double f[CHAIN_MAXBLOCKS];
  sc_slip_event *ev = malloc(sizeof *ev);
  if (!ev) return sc_fail(msg, SC_ENOMEM, "chain: out of memory");
  chain_traj T = {fn, ctx, dtau, 0, s, 0};
  chain_rec rec = {ev, 0, 0, ys, {0}, &T};
  sc_mapn_value out = {.n = (size_t)N - 1, .f = f};
  memcpy(d, x, (size_t)(N - 1) * sizeof *d);
  int st = SC_OK;
  for (int k = 0; k < iterations && !st; k++) {
    c->rec = &rec;
    st = chain_eval_n(inst, d, SC_EVAL_VALUE, &out, msg);
    c->rec = NULL;
    if (!st && T.stop) st = SC_ECALLBACK;
    if (st) break;
    double tstick = c->v > 0 ? ev->stick : 0;
    long n = (long)floor(tstick / dtau);
    for (long i = 0; i <= n && !st; i++) {
      for (int b = 0; b < N; b++)
        s[b] = c->Y[b] + c->v * i * dtau, s[N + b] = c->v;
      if (fn(ctx, T.tau + i * dtau, s, 0)) st = SC_ECALLBACK;
    }
    T.tau += tstick;
    memcpy(d, f, (size_t)(N - 1) * sizeof *d);
  }
  free(ev);
  if (st == SC_ECALLBACK)
    return sc_fail(msg, st, "chain: the trajectory was stopped");
  return st;
}
