/* Numerical flows of the chain (docs/chain.md, "Velocity weakening"): one
 * slip phase integrated by GSL's odeiv2 (Prince-Dormand 8(9)), with the
 * variational equations alongside when derivatives are asked for.  It
 * carries velocity-weakening friction K_i = T_i / (1 + gamma |U_i - W|),
 * which has no closed form, and Coulomb friction under flows = numerical
 * (a check of the exact flows of chain_phase.c).
 *
 * Only slipping blocks obey a differential equation; a stuck block's
 * right-hand side is Y' = W, U' = 0, which every Runge-Kutta step
 * integrates exactly, so stuck blocks add no error and no step control.
 *
 * Events follow bk2's numerical flows (bk2_numerical.c): after every
 * accepted step each guard is interpolated by the cubic Hermite
 * polynomial through its values and slopes at both ends (the step's
 * dense output); its first rise through zero is isolated between the
 * cubic's critical points and found by GSL's Brent solver, then refined
 * on the true solution by Newton steps that integrate from the step's
 * start.  A step is never longer than a tenth of the fastest free
 * period, so a guard cannot turn twice inside one step unseen; a guard
 * that rises and falls back inside a step has its maximum located on the
 * true solution, and a maximum within rounding of zero is a root (a
 * grazing).  A block that has just come loose does not re-stick
 * (restick_arrives()). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_roots.h>

#include "chain_impl.h"

#define CHAIN_NUM_PI 3.14159265358979323846
/* Fraction of the fastest free period allowed as one step, as bk2's
 * numerical flows: a guard then turns at most once inside a step. */
#define STEP_FRACTION 0.1
/* Newton refinements of an event time on the true solution (quadratic
 * convergence from the interpolant's root: two or three suffice). */
#define EVENT_NEWTON_MAX 8
/* Rounding bound on a guard value, in ulps of its terms' size (bk2's). */
#define GUARD_ROUND_ULPS 16.0
/* Two roots within this many event tolerances are one instant, as the
 * exact flows tie them (chain_phase.c). */
#define TIE_TOLS 2.0
/* A phase's horizon in turns of the slowest free period (2 pi): the
 * exact flows' (chain_phase.c). */
#define HORIZON_TURNS 1000.0
/* The integration tolerance times the growth of an error over a slip (a
 * few oscillations): how well f is known, as bk2's numerical flows. */
#define PRECISION_FACTOR 10.0
/* Brent iterations on one piece of a cubic: it converges in ~log2 of
 * 1 / DBL_EPSILON bisections at worst. */
#define BRENT_MAX 100

struct chain_num {
  int N, P;
  double atol, rtol;
  size_t dim[2];               /* [0]: the state; [1]: with sensitivities */
  gsl_odeiv2_step *step[2];
  gsl_odeiv2_control *ctrl[2];
  gsl_odeiv2_evolve *evol[2];
  gsl_root_fsolver *brent;
  double *buf;                 /* the vectors below, dim[1] each */
  double *y, *y0, *dy0, *dy1, *yt, *dyt, *ys, *ym, *dym;
};

/* The right-hand side's context. */
typedef struct {
  const chain_inst *c;
  int nd; /* sensitivity columns carried (0 or c->P) */
} rhs_ctx;

/* A direction of the sensitivities: column col is d_(col+1) for col < N -
 * 1, else parameter q = col - (N - 1) (as chain_phase.c's). */
typedef struct {
  int q;
  double da, dphi, dW, dg;
} num_dir;

static num_dir dir_of(const chain_inst *c, int col) {
  int q = col - (c->N - 1);
  num_dir D = {q, q == P_ALPHA, q == P_PHI, 0, q == P_GAMMA};
  D.dW = !c->frozen && q == P_V;
  return D;
}

/* d T_b along D (thresholds of blocks 2..5 are parameters). */
static double dT_of(const num_dir *D, int b) {
  return b >= 1 && b < CHAIN_PARAM_BLOCKS && D->q == P_BETA2 + b - 1;
}

/* Kinetic friction of slipping block b at velocity u, its derivative in u
 * (*dk_du) and, with D, along D at fixed u (*dk_dp). */
static double kinetic(const chain_inst *c, int b, double u, const num_dir *D,
                      double *dk_du, double *dk_dp) {
  double T = c->T[b];
  if (!c->vw) {
    *dk_du = 0;
    if (D) *dk_dp = dT_of(D, b) / c->phi - c->K[b] / c->phi * D->dphi;
    return c->K[b];
  }
  double rel = u - c->Vs, den = 1 + c->gamma * fabs(rel);
  double sgn = rel > 0 ? 1 : rel < 0 ? -1 : 0;
  *dk_du = -T * c->gamma * sgn / (den * den);
  if (D)
    *dk_dp = dT_of(D, b) / den +
             T * (c->gamma * sgn * D->dW - fabs(rel) * D->dg) / (den * den);
  return T / den;
}

/* sum over the neighbours of block j of v[n]. */
static double nb_sum(const chain_inst *c, int j, const double *v) {
  int nb[2], k = chain_neighbours(c, j, nb);
  double s = 0;
  for (int q = 0; q < k; q++) s += v[nb[q]];
  return s;
}

/* The spring force on block j from positions Y: S_j. */
static double spring(const chain_inst *c, int j, const double *Y) {
  return (1 + c->alpha * chain_degree(c, j)) * Y[j] - c->alpha * nb_sum(c, j, Y);
}

/* y = (Y, U), then per column (dY, dU), N each. */
static int rhs(double t, const double y[], double dy[], void *vp) {
  (void)t;
  const rhs_ctx *x = vp;
  const chain_inst *c = x->c;
  int N = c->N;
  const double *Y = y, *U = y + N;
  for (int i = 0; i < N; i++) {
    double dk;
    dy[i] = c->slip[i] ? U[i] : c->Vs;
    dy[N + i] = c->slip[i] ? kinetic(c, i, U[i], NULL, &dk, NULL) -
                                 spring(c, i, Y)
                           : 0;
  }
  for (int col = 0; col < x->nd; col++) {
    num_dir D = dir_of(c, col);
    const double *ty = y + 2 * (size_t)N * (col + 1), *tu = ty + N;
    double *dty = dy + 2 * (size_t)N * (col + 1), *dtu = dty + N;
    for (int i = 0; i < N; i++) {
      if (!c->slip[i]) {
        dty[i] = D.dW, dtu[i] = 0;
        continue;
      }
      double dk_du, dk_dp;
      kinetic(c, i, U[i], &D, &dk_du, &dk_dp);
      double dS = spring(c, i, ty) +
                  D.da * (chain_degree(c, i) * Y[i] - nb_sum(c, i, Y));
      dty[i] = tu[i];
      dtu[i] = dk_du * tu[i] + dk_dp - dS;
    }
  }
  return GSL_SUCCESS;
}

/* --- the workspace ----------------------------------------------------- */

void chain_num_release(chain_inst *c) {
  chain_num *n = c->num;
  if (!n) return;
  for (int i = 0; i < 2; i++) {
    if (n->evol[i]) gsl_odeiv2_evolve_free(n->evol[i]);
    if (n->ctrl[i]) gsl_odeiv2_control_free(n->ctrl[i]);
    if (n->step[i]) gsl_odeiv2_step_free(n->step[i]);
  }
  if (n->brent) gsl_root_fsolver_free(n->brent);
  free(n->buf);
  free(n);
  c->num = NULL;
}

int chain_num_setup(chain_inst *c, sc_msg *msg) {
  chain_num *n = c->num;
  if (n && n->N == c->N && n->atol == c->acc.ode_atol &&
      n->rtol == c->acc.ode_rtol)
    return SC_OK;
  chain_num_release(c);
  n = c->num = calloc(1, sizeof *n);
  if (!n) goto fail;
  n->N = c->N, n->P = c->P;
  n->atol = c->acc.ode_atol, n->rtol = c->acc.ode_rtol;
  n->dim[0] = 2 * (size_t)c->N;
  n->dim[1] = n->dim[0] * (1 + (size_t)c->P);
  for (int i = 0; i < 2; i++) {
    n->step[i] = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, n->dim[i]);
    n->ctrl[i] = gsl_odeiv2_control_y_new(n->atol, n->rtol);
    n->evol[i] = gsl_odeiv2_evolve_alloc(n->dim[i]);
    if (!n->step[i] || !n->ctrl[i] || !n->evol[i]) goto fail;
  }
  n->brent = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  double **v[] = {&n->y,  &n->y0, &n->dy0, &n->dy1, &n->yt,
                  &n->dyt, &n->ys, &n->ym,  &n->dym};
  size_t nv = sizeof v / sizeof v[0];
  n->buf = calloc(nv * n->dim[1], sizeof(double));
  if (!n->brent || !n->buf) goto fail;
  for (size_t i = 0; i < nv; i++) *v[i] = n->buf + i * n->dim[1];
  return SC_OK;
fail:
  chain_num_release(c);
  return sc_fail(msg, SC_ENOMEM,
                 "chain: cannot allocate the ODE workspace of %d blocks",
                 c->N);
}

double chain_num_precision(const chain_inst *c) {
  return PRECISION_FACTOR * (c->acc.ode_atol + c->acc.ode_rtol);
}

/* --- guards ------------------------------------------------------------ */

/* Rounding bound on guard j's value (and on U_j' = K_j - S_j, rounded
 * like S_j) at state y. */
static double round_guard(const chain_inst *c, int j, const double *y) {
  int nb[2], k = chain_neighbours(c, j, nb), N = c->N;
  double size = fabs(y[j]) + fabs(y[N + j]) + c->T[j] + c->Vs;
  for (int q = 0; q < k; q++) size += fabs(y[nb[q]]);
  return GUARD_ROUND_ULPS * DBL_EPSILON * (1 + c->alpha * chain_degree(c, j)) *
         size;
}

/* Guard j at state y with derivative dy: U_j - W while j slips (a
 * re-stick), S_j - T_j while it sticks (a threshold); its slope. */
static double guard(const chain_inst *c, int j, const double *y,
                    const double *dy, double *slope) {
  int N = c->N;
  if (c->slip[j]) {
    *slope = dy[N + j];
    return y[N + j] - c->Vs;
  }
  *slope = spring(c, j, dy);
  return spring(c, j, y) - c->T[j];
}

/* Guard j's slope and second derivative (*g2) at y, dy: U_j'' = dK/dU
 * U_j' - S_j' while it slips, S_j'' = -alpha (sum of the slipping
 * neighbours' accelerations) while it sticks. */
static double guard_prime(const chain_inst *c, int j, const double *y,
                          const double *dy, double *g2) {
  int N = c->N;
  if (c->slip[j]) {
    double dk_du;
    kinetic(c, j, y[N + j], NULL, &dk_du, NULL);
    *g2 = dk_du * dy[N + j] - spring(c, j, dy);
    return dy[N + j];
  }
  *g2 = spring(c, j, dy + N);
  return spring(c, j, dy);
}

/* Whether the re-stick guard of slipping block j, within rounding of zero
 * at y, arrives at zero (a re-stick) rather than leaves it: g' > 0, or g'
 * within rounding and g'' > 0.  A block that has just come loose leaves:
 * U' = K - T is < 0 with Coulomb friction and 0 with velocity weakening
 * (K(W) = T), and U'' = -S' < 0, so for a while only g'' tells the way; a
 * maximum that touches zero (g'' < 0) is no re-stick (bk2's rule,
 * docs/model.md). */
static int restick_arrives(const chain_inst *c, int j, const double *y,
                           const double *dy) {
  double g2, g1 = guard_prime(c, j, y, dy, &g2);
  double E = round_guard(c, j, y);
  return g1 > E || (g1 >= -E && g2 > 0);
}

/* Whether guard j at y (within the margin of its rounding) is on its way
 * up through zero: a re-stick that arrives, a threshold rising. */
static int arrives(const chain_inst *c, int j, const double *y,
                   const double *dy) {
  double s;
  if (c->slip[j]) return restick_arrives(c, j, y, dy);
  guard(c, j, y, dy, &s);
  return s > 0;
}

/* --- the dense output: cubic Hermite pieces ----------------------------- */

typedef struct {
  double c0, c1, c2, c3;
} cubic;

static double cubic_at(double s, void *p) {
  const cubic *q = p;
  return q->c0 + s * (q->c1 + s * (q->c2 + s * q->c3));
}

/* The root in [lo, hi] of the cubic, which changes sign there, by Brent. */
static double brent_root(gsl_root_fsolver *br, cubic *q, double lo,
                         double hi) {
  gsl_function F = {cubic_at, q};
  if (gsl_root_fsolver_set(br, &F, lo, hi)) return 0.5 * (lo + hi);
  for (int it = 0; it < BRENT_MAX; it++) {
    if (gsl_root_fsolver_iterate(br)) break;
    double a = gsl_root_fsolver_x_lower(br), b = gsl_root_fsolver_x_upper(br);
    /* the interval to a few ulps of the step */
    if (gsl_root_test_interval(a, b, 0, 4 * DBL_EPSILON) != GSL_CONTINUE)
      break;
  }
  return gsl_root_fsolver_root(br);
}

/* First root in (0, h] of the cubic Hermite interpolant of (g0, d0) at 0
 * and (g1, d1) at h crossing zero in direction dir (+1 rising, -1
 * falling); with skip0, the first monotone piece (which holds a start on
 * zero) is passed.  Returns -1 if none. */
static double hermite_root(gsl_root_fsolver *br, double g0, double d0,
                           double g1, double d1, double h, int skip0,
                           int dir) {
  cubic q = {g0, d0, (3 * (g1 - g0) / h - 2 * d0 - d1) / h,
             (d0 + d1 - 2 * (g1 - g0) / h) / (h * h)};
  double cuts[4] = {0};
  int nc = 1;
  double A = 3 * q.c3, B = 2 * q.c2, C = q.c1;
  if (A != 0) {
    double disc = B * B - 4 * A * C;
    if (disc >= 0) {
      double r = -0.5 * (B + copysign(sqrt(disc), B));
      double r1 = r / A, r2 = r != 0 ? C / r : r1;
      if (r1 > r2) {
        double tmp = r1;
        r1 = r2, r2 = tmp;
      }
      if (r1 > 0 && r1 < h) cuts[nc++] = r1;
      if (r2 > 0 && r2 < h && r2 != r1) cuts[nc++] = r2;
    }
  } else if (B != 0) {
    double r = -C / B;
    if (r > 0 && r < h) cuts[nc++] = r;
  }
  cuts[nc] = h;
  for (int p = 0; p < nc; p++) {
    if (p == 0 && skip0) continue;
    double lo = cuts[p], hi = cuts[p + 1];
    double flo = cubic_at(lo, &q), fhi = cubic_at(hi, &q);
    if (dir > 0 ? !(flo < 0 && fhi >= 0) : !(flo > 0 && fhi <= 0)) continue;
    if (fhi == 0) return hi;
    return brent_root(br, &q, lo, hi);
  }
  return -1;
}

/* --- integration -------------------------------------------------------- */

typedef struct {
  chain_inst *c;
  chain_num *n;
  int w;              /* 1: with sensitivities */
  gsl_odeiv2_system sys;
  double hmax;
} num_run;

/* Integrate y from t0 to t1 (the evolve object restarted). */
static int advance_to(num_run *R, double t0, double t1, double *y) {
  chain_num *n = R->n;
  gsl_odeiv2_evolve_reset(n->evol[R->w]);
  gsl_odeiv2_step_reset(n->step[R->w]);
  double t = t0, h = fmin(R->hmax, t1 - t0);
  while (t < t1) {
    double hc = fmin(h, R->hmax);
    int st = gsl_odeiv2_evolve_apply(n->evol[R->w], n->ctrl[R->w],
                                     n->step[R->w], &R->sys, &t, t1, &hc, y);
    if (st != GSL_SUCCESS) return st;
    h = hc;
  }
  return GSL_SUCCESS;
}

/* The state at te from (t0, y0) into yt, dyt. */
static void state_at(num_run *R, double t0, const double *y0, double te,
                     double *yt, double *dyt) {
  memcpy(yt, y0, R->n->dim[R->w] * sizeof *yt);
  if (te > t0) advance_to(R, t0, te, yt);
  rhs(te, yt, dyt, R->sys.params);
}

/* Refine a zero near *te in [t0, t1] of guard j (order 0) or of its
 * slope (order 1) by Newton's method on the true solution; the state
 * there into yt, dyt. */
static void refine(num_run *R, int j, int order, double t0, const double *y0,
                   double t1, double *te, double *yt, double *dyt) {
  const chain_inst *c = R->c;
  double t = *te;
  for (int it = 0; it < EVENT_NEWTON_MAX; it++) {
    state_at(R, t0, y0, t, yt, dyt);
    double s, v = order ? guard_prime(c, j, yt, dyt, &s) : guard(c, j, yt, dyt, &s);
    if (s == 0) break;
    double dt = -v / s, tol = c->acc.event_atol + c->acc.event_rtol * t;
    t = fmin(fmax(t + dt, t0), t1);
    if (fabs(dt) <= tol) break;
  }
  state_at(R, t0, y0, t, yt, dyt);
  *te = t;
}

/* The first rise through zero of guard j in the step [t0, t1], as an
 * offset from t0, or -1.  At the phase's start the start root of a
 * guard that leaves zero (a fresh block's, or one within rounding that
 * did not fire at once) is skipped.  A guard that rises and falls back
 * inside the step, below zero at both ends, has its maximum located on
 * the true solution: within rounding of zero, it is a root (a grazing
 * the interpolant may hide). */
static double step_root(num_run *R, int j, double t0, const double *y0,
                        const double *dy0, double t1, const double *y1,
                        const double *dy1) {
  const chain_inst *c = R->c;
  chain_num *n = R->n;
  double s0, s1, h = t1 - t0;
  double g0 = guard(c, j, y0, dy0, &s0), g1 = guard(c, j, y1, dy1, &s1);
  int skip = t0 == 0 && ((c->slip[j] && c->fresh[j]) ||
                         fabs(g0) <= round_guard(c, j, y0));
  double r = hermite_root(n->brent, g0, s0, g1, s1, h, skip, 1);
  if (r >= 0 || !(g0 < 0 && g1 < 0 && s0 > 0 && s1 < 0)) return r;
  double a0, a1;
  guard_prime(c, j, y0, dy0, &a0);
  guard_prime(c, j, y1, dy1, &a1);
  double rm = hermite_root(n->brent, s0, a0, s1, a1, h, skip, -1);
  if (rm < 0) return -1;
  double tm = t0 + rm, sm;
  refine(R, j, 1, t0, y0, t1, &tm, n->ym, n->dym);
  double gm = guard(c, j, n->ym, n->dym, &sm);
  if (gm < -round_guard(c, j, n->ym)) return -1;
  double rr = hermite_root(n->brent, g0, s0, gm, 0, tm - t0, 0, 1);
  return rr >= 0 ? rr : tm - t0;
}

/* The event margin of guard j at te: the tie window's value (its slope
 * times twice the event tolerance) plus its rounding. */
static double margin(const chain_inst *c, int j, double te, const double *yt,
                     double slope) {
  double tol = c->acc.event_atol + c->acc.event_rtol * te;
  return TIE_TOLS * tol * fabs(slope) + round_guard(c, j, yt);
}

/* The roots of a step are picked from its interpolants, whose error can
 * exceed the time between two events: after the event of guard *which is
 * located at te, a guard already past zero there beyond its margin rose
 * through zero before it; that one is located instead, on [t0, te], until
 * none is earlier (at most once per block).  Returns the event time. */
static double first_event(num_run *R, double t0, const double *y0,
                          const double *dy0, double te, int *which) {
  const chain_inst *c = R->c;
  chain_num *n = R->n;
  for (int pass = 0; pass < c->N; pass++) {
    int earlier = -1;
    double s0, si;
    for (int i = 0; i < c->N && earlier < 0; i++) {
      if (i == *which) continue;
      double gi = guard(c, i, n->yt, n->dyt, &si);
      if (gi > margin(c, i, te, n->yt, si)) earlier = i;
    }
    if (earlier < 0) return te;
    double g0 = guard(c, earlier, y0, dy0, &s0);
    double gi = guard(c, earlier, n->yt, n->dyt, &si);
    int skip = t0 == 0 && c->slip[earlier] && c->fresh[earlier];
    double r = hermite_root(n->brent, g0, s0, gi, si, te - t0, skip, 1);
    double t1 = te;
    te = t0 + (r >= 0 ? r : 0.5 * (te - t0));
    refine(R, earlier, 0, t0, y0, t1, &te, n->yt, n->dyt);
    *which = earlier;
  }
  return te;
}

/* --- the end of a phase -------------------------------------------------- */

/* The events at the instant te of guard `which` into ev (it first), the
 * others tied to it: within their margin and arriving (a block that has
 * only just come loose does not re-stick). */
static int collect(const chain_inst *c, int which, double te,
                   const double *yt, const double *dyt, chain_event *ev) {
  int nev = 0;
  for (int pass = 0; pass < 2; pass++)
    for (int i = 0; i < c->N; i++) {
      if ((i == which) != (pass == 0)) continue;
      double s, g = guard(c, i, yt, dyt, &s);
      if (i != which && !(fabs(g) <= margin(c, i, te, yt, s) &&
                          arrives(c, i, yt, dyt)))
        continue;
      int kind = c->slip[i] ? CHAIN_RESTICK : CHAIN_THRESHOLD;
      double u = fabs(s) > 0 ? round_guard(c, i, yt) / fabs(s) : HUGE_VAL;
      ev[nev++] = (chain_event){kind, i, te, s, u};
    }
  return nev;
}

/* The state at the event into c->Y, c->U and, with deriv, the
 * sensitivities: those of the flow at fixed time (integrated) plus the
 * state's rate times the event time's, -(d guard) / (guard's rate). */
static void finish(chain_inst *c, int deriv, const chain_event *e,
                   const double *yt, const double *dyt) {
  int N = c->N, j = e->block;
  memcpy(c->Y, yt, (size_t)N * sizeof *yt);
  memcpy(c->U, yt + N, (size_t)N * sizeof *yt);
  if (!deriv) return;
  int deg = chain_degree(c, j);
  for (int col = 0; col < c->P; col++) {
    num_dir D = dir_of(c, col);
    const double *ny = yt + 2 * (size_t)N * (col + 1), *nu = ny + N;
    double dg;
    if (e->kind == CHAIN_RESTICK) dg = nu[j] - D.dW;
    else
      dg = D.da * (deg * yt[j] - nb_sum(c, j, yt)) + spring(c, j, ny) -
           dT_of(&D, j);
    double ds = -dg / e->slope;
    double *ty = c->TY + (size_t)col * N, *tu = c->TU + (size_t)col * N;
    for (int b = 0; b < N; b++) {
      ty[b] = ny[b] + dyt[b] * ds;
      tu[b] = nu[b] + dyt[N + b] * ds;
    }
  }
}

/* --- one phase ------------------------------------------------------------ */

/* Pack the state (and the sensitivities) into y. */
static void pack(const chain_inst *c, int deriv, double *y) {
  int N = c->N;
  memcpy(y, c->Y, (size_t)N * sizeof *y);
  memcpy(y + N, c->U, (size_t)N * sizeof *y);
  for (int col = 0; deriv && col < c->P; col++) {
    double *ty = y + 2 * (size_t)N * (col + 1);
    memcpy(ty, c->TY + (size_t)col * N, (size_t)N * sizeof *y);
    memcpy(ty + N, c->TU + (size_t)col * N, (size_t)N * sizeof *y);
  }
}

/* A guard that ends the phase at its very start, or -1: one past zero,
 * or within rounding of zero and arriving; a fresh block's re-stick guard
 * starts on zero by construction and never does. */
static int start_event(const chain_inst *c, const double *y,
                       const double *dy) {
  for (int i = 0; i < c->N; i++) {
    if (c->slip[i] && c->fresh[i]) continue;
    double s, g = guard(c, i, y, dy, &s), E = round_guard(c, i, y);
    if (g > E || (g >= -E && arrives(c, i, y, dy))) return i;
  }
  return -1;
}

/* The phase's horizon: the exact flows' turns, and with stuck blocks on
 * a moving surface time for their springs to reach any threshold (bk2's
 * numerical flows). */
static double horizon(const chain_inst *c) {
  double H = HORIZON_TURNS * 2 * CHAIN_NUM_PI, tmax = 0;
  int stuck = 0;
  for (int i = 0; i < c->N; i++) {
    stuck |= !c->slip[i];
    tmax = fmax(tmax, c->T[i]);
  }
  return stuck && c->Vs > 0 ? fmax(H, 4 * (tmax + 1) / c->Vs) : H;
}

int chain_phase_num(chain_inst *c, int deriv, chain_event *ev, int *nev,
                    sc_msg *msg) {
  chain_num *n = c->num;
  int w = deriv != 0;
  rhs_ctx ctx = {c, w ? c->P : 0};
  /* frequencies sqrt(1 + alpha mu) with mu <= 4 (twice the largest degree) */
  num_run R = {c, n, w, {rhs, NULL, n->dim[w], &ctx},
               STEP_FRACTION * 2 * CHAIN_NUM_PI / sqrt(1 + 4 * c->alpha)};
  double *y = n->y;
  pack(c, w, y);
  rhs(0, y, n->dy0, &ctx);
  int which = start_event(c, y, n->dy0);
  if (which >= 0) {
    *nev = collect(c, which, 0, y, n->dy0, ev);
    finish(c, deriv, &ev[0], y, n->dy0);
    return SC_OK;
  }
  gsl_odeiv2_evolve_reset(n->evol[w]);
  gsl_odeiv2_step_reset(n->step[w]);
  double t = 0, h = 0.1 * R.hmax, tend = horizon(c);
  while (t < tend) {
    double t0 = t, hc = fmin(h, R.hmax);
    memcpy(n->y0, y, n->dim[w] * sizeof *y);
    int st = gsl_odeiv2_evolve_apply(n->evol[w], n->ctrl[w], n->step[w],
                                     &R.sys, &t, tend, &hc, y);
    if (st != GSL_SUCCESS)
      return sc_fail(msg, SC_ENOCONV,
                     "chain: the ODE integration of a slip phase failed at "
                     "tau = %.6g (GSL: %s)",
                     t, gsl_strerror(st));
    h = hc;
    rhs(t, y, n->dy1, &ctx);
    double troot = -1;
    for (int i = 0; i < c->N; i++) {
      double r = step_root(&R, i, t0, n->y0, n->dy0, t, y, n->dy1);
      if (r >= 0 && (troot < 0 || r < troot)) troot = r, which = i;
    }
    /* the grazing checks restarted the integrator: go on from the step */
    gsl_odeiv2_evolve_reset(n->evol[w]);
    gsl_odeiv2_step_reset(n->step[w]);
    if (which >= 0) {
      double te = t0 + troot;
      refine(&R, which, 0, t0, n->y0, t, &te, n->yt, n->dyt);
      te = first_event(&R, t0, n->y0, n->dy0, te, &which);
      *nev = collect(c, which, te, n->yt, n->dyt, ev);
      finish(c, deriv, &ev[0], n->yt, n->dyt);
      return SC_OK;
    }
    memcpy(n->dy0, n->dy1, n->dim[w] * sizeof *y);
  }
  return sc_fail(msg, SC_EUNDEF,
                 "chain: no event within %g time units of a slip phase (a "
                 "slip cycle that never returns to a global stick phase?)",
                 tend);
}
