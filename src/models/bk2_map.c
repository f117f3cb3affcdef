/* The two-block Burridge-Knopoff model (docs/model.md) as a map of the
 * library: its parameters and options, the event loop that follows the
 * motion from one global stick phase (GSP) to the next through the slip
 * phases its flows compute (bk2_flows: exact or numerical), the borders
 * and itinerary codes of a whole iterate, evaluation with derivatives
 * propagated in forward mode (src/hybrid/dual.h), and trajectories.
 * The derivation of every formula is in docs/derivations.md. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hybrid/dual.h"
#include "hybrid/hybrid_impl.h"
#include "models/bk2_impl.h"
#include "models/bk2_jet.h"
#include "models/bk2_quad.h"
#include "slipcont/hybrid.h"

static const sc_param_info bk2_params[] = {
    {"alpha", 3, 0, 1e6, 1, 0, "coupling spring / driver spring, k_c/k", NULL,
     NULL},
    {"beta", 1, 0, 1e6, 1, 0, "static friction of block 2 / block 1", NULL,
     NULL},
    {"phi", 1.25, 1, 1e6, 1, 0, "static / kinetic friction ratio, 1/mu", NULL,
     "friction=coulomb"},
    {"v", 0.025, 0, 1e3, 0, 0, "driver velocity V (dimensionless)", "V", NULL},
    {"gamma", 1, 0, 1e6, 0, 0,
     "velocity weakening: K_i = T_i / (1 + gamma |U_i - V_s|) (friction = "
     "velocity-weakening only)",
     NULL, "friction=velocity-weakening"},
};

static const sc_option_info bk2_options[] = {
    {"driver",
     {"moving", "frozen", NULL},
     "the driver keeps moving during slips, or stops (assumption 1)", 0, 0},
    {"friction",
     {"coulomb", "velocity-weakening", NULL},
     "kinetic friction: constant mu T_i (coulomb), or T_i / (1 + gamma "
     "|U_i - V_s|) (velocity-weakening)", 0, 0},
    {"flows",
     {"exact", "numerical", NULL},
     "closed-form flows, or GSL odeiv2 integration", 0, 0},
};

double sc_bk2_dstar(double alpha, double beta) {
  return (beta - 1) / (1 + 2 * alpha);
}


/* The kinetic force falls below the threshold by (1 - mu) T_i, and that
 * margin drives every slip: with the driver moving, a slip's velocities
 * swing by ~V_s about the belt and miss it by ~((1 - mu) T)^2 / V_s at
 * their closest, so when (1 - mu) min(1, beta) < sqrt(eps) V_s that miss
 * is below the rounding of V_s and double cannot tell a re-stick from a
 * touch (at phi = 1 + 1e-6, V = 100 double took touches for re-sticks
 * where quad slips on; docs/accuracy.md).  Such parameters are refused in
 * double, with the limit named; quad resolves them. */
static int bk2_unresolved(const bk2_inst *b) {
  if (b->acc.precision == SC_PRECISION_QUAD || !(b->vs > 0)) return 0;
  return (1 - b->mu) * fmin(1, b->beta) < sqrt(DBL_EPSILON) * b->vs;
}

static int bk2_setup(void *vinst, const double *p, const int *opt,
                     const sc_accuracy *acc, sc_msg *msg) {
  bk2_inst *b = vinst;
  b->alpha = p[0];
  b->beta = p[1];
  b->phi = p[2];
  b->v = p[3];
  b->gamma = p[4];
  b->frozen = opt[0] == 1;
  b->vw = opt[1] == 1;
  b->numerical = opt[2] == 1 || b->vw;
  b->acc = *acc;
  b->mu = 1 / b->phi;
  b->w1 = sqrt(1 + b->alpha);
  b->w2 = sqrt(1 + 2 * b->alpha);
  b->vs = b->frozen ? 0 : b->v;
  b->dstar = sc_bk2_dstar(b->alpha, b->beta);
  bk2_load_params(b, 0, &b->p0);
  bk2v_load_params(b, 0, &b->pv); /* value-only evaluations start from it */
  b->search = sc_guard_first_root;
  b->search_pair = sc_guard_first_root_pair;
  if (b->v > 0 && b->v < DBL_MIN)
    return sc_fail(msg, SC_EINVAL,
                   "bk2: v = %g is subnormal: the event horizons divide by "
                   "it (valid: 0, or v >= %g)",
                   b->v, DBL_MIN);
  if (b->vw && b->frozen)
    return sc_fail(msg, SC_EINVAL,
                   "bk2: friction = velocity-weakening with driver = frozen "
                   "is ill posed (a slip cannot start): use "
                   "driver = moving");
  if (b->numerical && acc->precision == SC_PRECISION_QUAD)
    return sc_fail(msg, SC_EINVAL,
                   "bk2: precision = quad needs flows = exact (the numerical "
                   "flows are double only)");
  b->unresolved = bk2_unresolved(b);
  const bk2_flows *fl =
      b->numerical ? &sc_bk2_flows_numerical : &sc_bk2_flows_exact;
  if (b->flows && b->flows != fl) b->flows->release(b); /* set up again */
  b->flows = fl;
  return fl->setup(b, msg);
}

static void bk2_release(void *vinst) {
  bk2_inst *b = vinst;
  if (b->flows) b->flows->release(b);
}

/* The switching border of a GSP: the distance of d from d* on the side of
 * the onset mode, a surface in the state (d_on = d*). */
static void switch_border(const bk2_inst *b, const bk2_dpar *P, sc_dual d,
                          int mode, sc_border_list *l) {
  int nd = P->nd;
  sc_dual ds = sc_ddiv(sc_daddc(P->beta, -1),
                       sc_daddc(sc_dscale(P->alpha, 2, nd), 1), nd);
  ds.v = b->dstar; /* the same number as the onset's comparison */
  sc_dual m = mode == SC_BK2_SLIP1 ? sc_dsub(ds, d, nd) : sc_dsub(d, ds, nd);
  if (mode == SC_BK2_SLIP12) m.v = 0;
  sc_bk2_border_add(l, SC_BORDER_SWITCHING, &m,
                    mode == SC_BK2_SLIP1   ? "d* - d at the onset (block 1)"
                    : mode == SC_BK2_SLIP2 ? "d - d* at the onset (block 2)"
                                           : "d = d* at the onset (both)");
  if (l->n <= l->cap) {
    sc_border *bd = &l->b[l->n - 1];
    bd->on_state = 1;
    bd->d_on = b->dstar;
    for (int k = 0; k < BK2_NPARAM; k++) bd->d_on_dp[k] = ds.d[k + 1];
  }
}

/* The threshold gap of the block that stayed stuck through a one-block
 * phase that ended by a re-stick: the length of the next global stick
 * phase, times V (zero at crossing-sliding). */
static void gap_border(const bk2_dpar *P, int mode, const bk2_state *x,
                       int phase, sc_border_list *l) {
  int nd = P->nd;
  sc_dual m = mode == SC_BK2_SLIP1
                  ? sc_dsub(P->t2, bk2_spring(P, x->y2, x->y1), nd)
                  : sc_dsub(sc_dconst(1, nd), bk2_spring(P, x->y1, x->y2), nd);
  char name[2 * SC_BORDER_NAME];
  snprintf(name, sizeof name, "threshold gap of block %d, phase %d (slip %s)",
           mode == SC_BK2_SLIP1 ? 2 : 1, phase, bk2_mode_name(mode));
  sc_bk2_border_add(l, SC_BORDER_CROSSING, &m, name);
}

/* The borders' own codes, once the iterate's code is complete: a
 * grazing met from the side where the guard fires ends its phase at the
 * guard's maximum; a start at d* whose first phase ends at once at the
 * other block's threshold is a start of both blocks without that phase. */
static void border_codes(const sc_itin_code *code, size_t border0,
                         const bk2_events *ev, sc_border_list *l) {
  for (int k = 0; k < ev->npatch; k++) {
    sc_border *bd = &l->b[ev->patch[k].idx];
    int at = 1 + 2 * (ev->patch[k].phase - 1);
    if (at + 1 >= code->n) continue;
    if (ev->patch[k].drop_next) {
      /* only when the next phase is the other block alone, ended by its
       * re-stick (then it ends the iterate too) */
      if (at + 3 >= code->n || code->c[at + 2] == BK2_EV_THRESHOLD) continue;
    }
    bd->alt = *code;
    bd->alt.c[at] = ev->patch[k].c0;
    bd->alt.c[at + 1] = ev->patch[k].c1;
    if (ev->patch[k].drop_next) {
      memmove(bd->alt.c + at + 2, bd->alt.c + at + 4,
              (size_t)(code->n - at - 4));
      bd->alt.n -= 2;
    }
  }
  if (border0 < l->n && border0 < l->cap && code->n >= 3 &&
      code->c[0] != SC_BK2_SLIP12 && code->c[1] == BK2_EV_THRESHOLD) {
    sc_border *bd = &l->b[border0];
    bd->alt.n = code->n - 2;
    bd->alt.c[0] = SC_BK2_SLIP12;
    memcpy(bd->alt.c + 1, code->c + 3, (size_t)(code->n - 3));
  }
}

/* The start of an iterate that follows the code `force`: the mode of its
 * onset state (the code's first byte) and of its first phase, and where
 * the first phase's bytes are.  Exactly on the switching surface a forced
 * one-block start whose first phase ends at once at the other block's
 * threshold is the start of both (the tie rule), and that phase has
 * length zero. */
static int loop_force_start(const bk2_inst *b, double d,
                            const sc_itin_code *force, int *onset, int *mode,
                            int *fpos, sc_msg *msg) {
  const unsigned char *fc = force->c;
  *onset = *mode = fc[0];
  if (*mode < SC_BK2_SLIP1 || *mode > SC_BK2_SLIP12 || force->n % 2 == 0)
    return sc_fail(msg, SC_EINVAL, "bk2: malformed itinerary code");
  if (*mode != SC_BK2_SLIP12 && d == b->dstar && force->n >= 3 &&
      fc[1] == BK2_EV_THRESHOLD)
    *mode = SC_BK2_SLIP12, *fpos = 3;
  return SC_OK;
}

/* Append a phase's two code bytes; a code too long to force is dropped
 * (the caller is told by n = 0). */
static void code_add(sc_itin_code *code, const unsigned char rec[2]) {
  if (code->n + 2 <= SC_CODE_LEN) {
    code->c[code->n++] = rec[0];
    code->c[code->n++] = rec[1];
  } else {
    code->n = 0;
  }
}

/* The derivatives of f = Y2 - Y1 at the iterate's end x; f' = 1 exactly
 * where the iterate is neutral (docs/model.md), whatever rounding says. */
static void loop_derivatives(const bk2_dpar *P, const bk2_state *x,
                             sc_map_value *out) {
  int nd = P->nd;
  if (!nd) return;
  sc_dual dn = sc_dsub(x->y2, x->y1, nd);
  out->dfdd = dn.d[0];
  for (int k = 0; k + 1 < nd; k++) out->dfdp[k] = dn.d[k + 1];
  if (out->neutral) out->dfdd = 1;
}

/* The event loop on duals (bk2_loop.h), through the flows' phases. */
#define BK2_LOOP_NAME dual_loop
#define BK2_LOOP_FULL 1
#define BK2_LOOP_NUM sc_dual
#define BK2_LOOP_PAR bk2_dpar
#define BK2_LOOP_STATE bk2_state
#define BK2_LOOP_VAL(a) ((a).v)
#define BK2_LOOP_ONSET(P, d, mode, x) bk2_onset_state(P, d, mode, x)
#define BK2_LOOP_PHASE b->flows->phase(b, P, mode, fresh, x, &dur, &ev, msg)
#include "models/bk2_loop.h"

int sc_bk2_iterate(const bk2_inst *b, const bk2_dpar *P, sc_dual d,
                   unsigned flags, bk2_state *x, sc_map_value *out,
                   bk2_phase_fn fn, void *ctx, sc_msg *msg) {
  return dual_loop(b, P, d, flags, NULL, NULL, NULL, x, out, fn, ctx, msg);
}

int sc_bk2_iterate_ex(const bk2_inst *b, const bk2_dpar *P, sc_dual d,
                      unsigned flags, const sc_itin_code *force,
                      sc_itin_code *code, sc_border_list *borders,
                      bk2_state *x, sc_map_value *out, bk2_phase_fn fn,
                      void *ctx, sc_msg *msg) {
  return dual_loop(b, P, d, flags, force, code, borders, x, out, fn, ctx,
                   msg);
}


_Static_assert(1 + 4 <= SC_NDIR, "bk2 needs d and four parameters");

/* ---- second derivatives ------------------------------------------------- */

/* Keep each phase's mode and duration (the event loop's phase callback)
 * for the replay in jets. */
static int record_phase(void *ctx, int mode, const bk2_state *x0,
                        double dur) {
  bk2_phase_log *L = ctx;
  (void)x0;
  if (L->n >= SC_BK2_JET_MAXPHASES) return SC_EINVAL;
  L->mode[L->n] = mode;
  L->dur[L->n] = dur;
  L->n++;
  return SC_OK;
}

int sc_bk2_eval_jet(const bk2_inst *b, double d, unsigned flags,
                    sc_map_value *out, double *grad, sc_msg *msg) {
  return sc_bk2_eval_jet_ex(b, d, flags, NULL, NULL, NULL, out, grad, msg);
}

int sc_bk2_eval_jet_ex(const bk2_inst *b, double d, unsigned flags,
                       const sc_itin_code *force, sc_itin_code *code,
                       sc_border_list *borders, sc_map_value *out,
                       double *grad, sc_msg *msg) {
  /* The replay solves each event as a root of its guard: a code that
   * ends a phase at a guard's maximum (a grazing's own system) is not
   * one it can follow. */
  for (int i = 2; force && i < force->n; i += 2)
    if (force->c[i - 1] & BK2_EV_ATMAX)
      return sc_fail(msg, SC_EINVAL,
                     "bk2: second derivatives along a code that ends a slip "
                     "at a guard's maximum are not available");
  if (b->numerical)
    return sc_fail(msg, SC_EINVAL,
                   "bk2: second derivatives (SC_EVAL_DERIV2) need the "
                   "closed-form flows (valid: flows = exact)");
  bk2_dpar P;
  bk2_load_params(b, 5, &P);
  bk2_state x;
  bk2_phase_log L;
  L.n = 0;
  int st = sc_bk2_iterate_ex(b, &P, sc_dvar(d, 0, 5), flags | SC_EVAL_DERIV,
                             force, code, borders, &x, out, record_phase, &L,
                             msg);
  if (st == SC_EINVAL && L.n >= SC_BK2_JET_MAXPHASES)
    return sc_fail(msg, SC_EINVAL,
                   "bk2: %d slip phases in one iterate: too many for second "
                   "derivatives (valid: at most %d)",
                   L.n, SC_BK2_JET_MAXPHASES);
  if (st) return st;
  sc_bk2_jet_replay(b, d, &L, out, grad);
  return SC_OK;
}

/* f' is not finite: an event with zero slope.  Next to d* with the
 * driver frozen that is rounding (the other block starts at its threshold
 * with zero speed, so f' grows like |d - d*|^(-1/2), beyond what double
 * resolves): say so rather than return NaN with SC_OK. */
static int nonfinite_derivative(const bk2_inst *b, double d, int st,
                                const sc_map_value *out, sc_msg *msg) {
  /* (At d* itself the derivative is that of the start of both blocks:
   * the switching's own system, which the curve and branch tasks solve;
   * f' of the map is unbounded on both sides there, docs/accuracy.md D4.) */
  if (st || isfinite(out->dfdd)) return st;
  return sc_fail(msg, SC_ENONFINITE,
                 "bk2: f'(%.17g) is not finite: an event with zero slope "
                 "(d - d* = %.3g; next to d* f' grows like |d - d*|^(-1/2))",
                 d, d - b->dstar);
}

/* The largest |d| the model resolves: the onset state is ~ alpha d and
 * the guards combine it with terms of size 1; beyond this their sums and
 * event horizons overflow or lose every digit of the slip (1e100 leaves
 * alpha up to 1e6 and its squares far from overflow). */
#define BK2_D_MAX 1e100

static int out_of_reach(const bk2_inst *b, double d, sc_msg *msg) {
  if (b->unresolved)
    return sc_fail(msg, SC_EUNDEF,
                   "bk2: phi = %.17g with v = %g is beyond what double "
                   "resolves: the slip's force margin (1 - 1/phi) "
                   "min(1, beta) = %.3g is below sqrt(eps) v = %.3g, so a "
                   "re-stick cannot be told from a touch (use "
                   "precision = quad, a larger phi or a smaller v)",
                   b->phi, b->v, (1 - b->mu) * fmin(1, b->beta),
                   sqrt(DBL_EPSILON) * b->vs);
  if (fabs(d) <= BK2_D_MAX) return SC_OK;
  return sc_fail(msg, SC_EUNDEF,
                 "bk2: d = %g is beyond what the model resolves (valid: "
                 "|d| <= %g)",
                 d, BK2_D_MAX);
}

static int bk2_eval(void *vinst, double d, unsigned flags, sc_map_value *out,
                    sc_msg *msg) {
  const bk2_inst *b = vinst;
  if (out_of_reach(b, d, msg)) return SC_EUNDEF;
  if (b->acc.precision == SC_PRECISION_QUAD) { /* bk2_quad.c */
    if (flags & SC_EVAL_DERIV2)
      return sc_fail(msg, SC_EINVAL,
                     "bk2: second derivatives are computed in double only "
                     "(valid with SC_EVAL_DERIV2: precision = double)");
    return sc_bk2_quad_eval(b->alpha, b->beta, b->phi, b->v, b->frozen,
                            b->acc.max_events, d, flags, out, msg);
  }
  if (flags & SC_EVAL_DERIV2)
    return sc_bk2_eval_jet(b, d, flags, out, NULL, msg);
  bk2_dpar P;
  int nd = (flags & SC_EVAL_DERIV) ? bk2_nd(b) : 0;
  if (!nd && b->flows->value && !b->dual_only)
    return b->flows->value(b, d, flags, out, msg);
  if (nd) bk2_load_params(b, nd, &P);
  else P = b->p0;
  bk2_state x;
  int st = sc_bk2_iterate(b, &P, sc_dvar(d, 0, nd), flags, &x, out, NULL,
                          NULL, msg);
  return nd ? nonfinite_derivative(b, d, st, out, msg) : st;
}

static double bk2_precision(const void *vinst) {
  const bk2_inst *b = vinst;
  return b->flows->precision(b);
}

static int bk2_eval_ex(void *vinst, double d, unsigned flags,
                       const sc_itin_code *force, sc_itin_code *code,
                       sc_border_list *borders, sc_map_value *out,
                       sc_msg *msg) {
  const bk2_inst *b = vinst;
  if (out_of_reach(b, d, msg)) return SC_EUNDEF;
  if (flags & SC_EVAL_DERIV2)
    return sc_bk2_eval_jet_ex(b, d, flags, force, code, borders, out, NULL,
                              msg);
  bk2_dpar P;
  int nd = (flags & SC_EVAL_DERIV) || borders ? bk2_nd(b) : 0;
  if (!nd && b->flows->value && !b->dual_only && !(force && force->n > 0) &&
      !code)
    return b->flows->value(b, d, flags, out, msg);
  if (nd) bk2_load_params(b, nd, &P);
  else P = b->p0;
  bk2_state x;
  int st = sc_bk2_iterate_ex(b, &P, sc_dvar(d, 0, nd), flags, force, code,
                             borders, &x, out, NULL, NULL, msg);
  if (st || !(flags & SC_EVAL_DERIV)) return st;
  /* a forced code at d* (a switching's own system) has the derivative of
   * that system: only a NaN is refused there */
  if (force && force->n > 0)
    return isfinite(out->dfdd)
               ? SC_OK
               : sc_fail(msg, SC_ENONFINITE,
                         "bk2: f'(%.17g) along the forced code is not "
                         "finite: an event with zero slope",
                         d);
  return nonfinite_derivative(b, d, st, out, msg);
}

/* ---- trajectories --------------------------------------------------- */

typedef struct {
  const bk2_inst *b;
  const bk2_dpar *P;
  bk2_traj t;
} traj_ctx;

/* Sample one finished slip phase (the event loop's phase callback). */
static int traj_phase(void *vc, int mode, const bk2_state *x0, double dur) {
  traj_ctx *c = vc;
  return c->b->flows->sample(c->b, c->P, mode, x0, dur, &c->t);
}

static int bk2_trajectory(void *vinst, double d, int iterations, double dtau,
                          int (*fn)(void *, double, const double *, int),
                          void *ctx, sc_msg *msg) {
  const bk2_inst *b = vinst;
  if (out_of_reach(b, d, msg)) return SC_EUNDEF;
  bk2_dpar P;
  bk2_load_params(b, 0, &P);
  traj_ctx c = {b, &P, {0, dtau, fn, ctx}};
  sc_map_value out;
  for (int k = 0; k < iterations; k++) {
    memset(&out, 0, sizeof out);
    bk2_state x;
    int st = sc_bk2_iterate(b, &P, sc_dconst(d, 0), 0, &x, &out, traj_phase,
                            &c, msg);
    if (st) return st;
    /* The global stick phase: both blocks move with V until the first
     * threshold; S_i grows at rate V.  With V = 0 it is passed at once
     * (quasi-static loading). */
    double s1 = bk2_spring(&P, x.y1, x.y2).v, s2 = bk2_spring(&P, x.y2, x.y1).v;
    double gap = fmax(0, fmin(1 - s1, b->beta - s2));
    double tstick = b->v > 0 ? gap / b->v : 0;
    x.u1 = x.u2 = sc_dconst(b->v, 0);
    long n = (long)floor(tstick / dtau);
    for (long i = 0; i <= n; i++) {
      bk2_state xs = x;
      xs.y1.v += b->v * i * dtau;
      xs.y2.v += b->v * i * dtau;
      double st4[4] = {xs.y1.v, xs.y2.v, xs.u1.v, xs.u2.v};
      if (bk2_traj_emit(&c.t, i * dtau, st4, SC_BK2_STICK))
        return SC_ECALLBACK;
    }
    c.t.tau += tstick;
    d = out.f;
  }
  return SC_OK;
}

const sc_model_type sc_model_bk2 = {
    .name = "bk2",
    .doc = "two-block Burridge-Knopoff stick-slip model (docs/model.md)",
    .state_name = "d",
    .state_label = "Y_2 - Y_1",
    .state_point_name = "d*",
    .nparam = BK2_NPARAM,
    .params = bk2_params,
    .noption = 3,
    .options = bk2_options,
    .inst_size = sizeof(bk2_inst),
    .setup = bk2_setup,
    .release = bk2_release,
    .eval = bk2_eval,
    .eval_ex = bk2_eval_ex,
    .precision = bk2_precision,
    .trajectory = bk2_trajectory,
};

