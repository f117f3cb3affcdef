/* Slip events of a map of many blocks (map.h sc_map_eval_event()): one
 * iterate with the record of what its slip did, for event catalogues
 * (docs/chain.md, "Event catalogue"); and the blocks' continuous motion
 * (sc_map_trajectory_n()).  The plain evaluation is untouched:
 * a model records only when called through eval_event. */
#include <math.h>

#include "map_impl.h"

int sc_map_has_events(const sc_map *m) { return m->type->eval_event != NULL; }

int sc_map_eval_event(sc_map *m, const double *x, unsigned flags,
                      sc_mapn_value *out, sc_slip_event *ev, sc_msg *msg) {
  if (!m->type->eval_event)
    return sc_fail(msg, SC_EINVAL,
                   "sc_map_eval_event: model %s records no slip events",
                   m->type->name);
  if (flags & ~(unsigned)SC_EVAL_ITINERARY)
    return sc_fail(msg, SC_EINVAL,
                   "sc_map_eval_event: flags %u (valid: SC_EVAL_VALUE or "
                   "SC_EVAL_ITINERARY)",
                   flags);
  if (!out || out->n != m->dim || !out->f)
    return sc_fail(msg, SC_EINVAL,
                   "sc_map_eval_event: storage for dimension %zu (the map "
                   "has %zu)",
                   out ? out->n : 0, m->dim);
  char name[32];
  for (size_t i = 0; i < m->dim; i++)
    if (!isfinite(x[i]))
      return sc_fail(msg, SC_EINVAL, "%s = %g is not finite",
                     sc_map_state_component(m, i, name, sizeof name), x[i]);
  out->nphases = 0;
  out->itinerary[0] = '\0';
  m->nevals++;
  int st = m->type->eval_event(m->inst, x, flags, out, ev, msg);
  if (st) return st;
  for (size_t i = 0; i < m->dim; i++)
    if (!isfinite(out->f[i]))
      return sc_fail(msg, SC_ENONFINITE, "f is not finite at the state given");
  return SC_OK;
}

int sc_map_trajectory_n(sc_map *m, const double *x, int iterations, double dtau,
                        sc_traj_fn fn, void *ctx, sc_msg *msg) {
  if (!m->type->trajectory_n)
    return sc_fail(msg, SC_EINVAL,
                   "sc_map_trajectory_n: model %s has no continuous motion "
                   "of its blocks",
                   m->type->name);
  int ok = dtau > 0 && isfinite(dtau) && iterations >= 1;
  for (size_t i = 0; ok && i < m->dim; i++)
    ok = isfinite(x[i]);
  if (!ok)
    return sc_fail(msg, SC_EINVAL,
                   "sc_map_trajectory_n: dtau = %g, iterations = %d (valid: "
                   "dtau > 0, iterations >= 1, a finite state)",
                   dtau, iterations);
  return m->type->trajectory_n(m->inst, x, iterations, dtau, fn, ctx, msg);
}
