/* The rules of the bk2 model that every flow obeys (bk2_impl.h): what an
 * event does to the state and to its sensitivities, and how borders are
 * recorded.  The derivations are in docs/derivations.md. */
#include <math.h>
#include <string.h>

#include "hybrid/dual.h"
#include "models/bk2_impl.h"

/* ---- events ------------------------------------------------------------ */

/* Apply the event-time sensitivity: the guard gval (a dual evaluated at
 * fixed time) vanishes at the event, so dt = -dg / g' and the state moves
 * along its velocity: x += xdot dt. */
void sc_bk2_event_shift(const bk2_dpar *P, sc_dual gval, double slope,
                        const double acc[2], bk2_state *x) {
  int nd = P->nd;
  if (nd == 0) return;
  double dt[SC_NDIR];
  /* g' = 0: the event time is not differentiable (f' is infinite there,
   * docs/model.md: |d - d*|^(-1/2) at d* with V_s = 0): say so with NaN. */
  for (int k = 0; k < nd; k++) dt[k] = slope != 0 ? -gval.d[k] / slope : NAN;
  double xdot[4] = {x->u1.v, x->u2.v, acc[0], acc[1]};
  sc_dual *xs[4] = {&x->y1, &x->y2, &x->u1, &x->u2};
  for (int i = 0; i < 4; i++)
    for (int k = 0; k < nd; k++) xs[i]->d[k] += xdot[i] * dt[k];
}

int sc_bk2_take_event(const bk2_dpar *P, int mode, int kind, double slope,
                      const double acc[2], bk2_state *x) {
  /* the guard on duals at fixed time: its sensitivity moves the event */
  if (P->nd)
    sc_bk2_event_shift(P, bk2_guard_value(P, mode, kind, x), slope, acc, x);
  return bk2_stick(P, mode, kind, x);
}

int sc_bk2_take_event_at_max(const bk2_dpar *P, int mode, int kind,
                             double g2, const double acc[2], bk2_state *x) {
  /* the event time solves g' = 0: dt = -dg'/g'' at fixed time, with
   * g' = U_i' = K_i - S_i of the slipping block */
  int nd = P->nd;
  sc_dual gp = kind == BK2_EV_RESTICK1
                   ? sc_dsub(P->k1, bk2_spring(P, x->y1, x->y2), nd)
                   : sc_dsub(P->k2, bk2_spring(P, x->y2, x->y1), nd);
  sc_bk2_event_shift(P, gp, g2, acc, x);
  return bk2_stick(P, mode, kind, x);
}

void sc_bk2_patch(bk2_events *ev, int c0, int c1, int drop_next) {
  if (ev->borders->n > ev->borders->cap || ev->npatch >= 8) return;
  ev->patch[ev->npatch].idx = ev->borders->n - 1;
  ev->patch[ev->npatch].phase = ev->phase;
  ev->patch[ev->npatch].c0 = (unsigned char)c0;
  ev->patch[ev->npatch].c1 = (unsigned char)c1;
  ev->patch[ev->npatch].drop_next = drop_next;
  ev->npatch++;
}

/* ---- borders ------------------------------------------------------------ */

void sc_bk2_border_add(sc_border_list *l, sc_border_kind kind,
                       const sc_dual *m, const char *name) {
  if (l->n++ >= l->cap) return; /* counted: the caller grows and repeats */
  sc_border *bd = &l->b[l->n - 1];
  memset(bd, 0, sizeof *bd);
  bd->kind = kind;
  bd->value = m->v;
  bd->dd = m->d[0];
  for (int k = 0; k < BK2_NPARAM; k++) bd->dp[k] = m->d[k + 1];
  size_t len = strlen(name);
  if (len >= sizeof bd->name) len = sizeof bd->name - 1; /* cut */
  memcpy(bd->name, name, len);
  bd->name[len] = '\0';
}



/* ---- the end of an iterate ---------------------------------------------- */

int sc_bk2_slip_cycle(const bk2_inst *b, sc_msg *msg) {
  return sc_fail(msg, SC_EUNDEF,
                 "no return to a global stick phase after %d slip phases "
                 "(max-events): the motion settles on a slip cycle",
                 b->acc.max_events);
}
