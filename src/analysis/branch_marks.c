/* User points (AUTO's UZ) on orbit branches: where the step from one
 * accepted point to the next passes a value of the spec's marks, the
 * orbit there is located by Newton on g(d) = f^m(d) - d with the
 * parameter fixed at the mark, along the segment's itinerary codes, and
 * recorded as a UZ special point with its residual |g(d)|. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "analysis/branch_orbit_impl.h"

/* Whether the orbit through d at the mark is one recorded before (a mark
 * met again by another segment of the same branch). */
static int known(sc_orbit_branch *b, int period, double p, const double *orb) {
  for (size_t i = 0; i < b->nsp; i++) {
    const special_rec *r = &b->sps[i];
    if (r->label != SC_PT_UZ || r->period != period || r->p != p) continue;
    if (sc_ob_iterate_orbit_forced(b, r->d, period, NULL, b->seed) == SC_OK &&
        sc_ob_same_orbit(b, b->seed, orb, period))
      return 1;
  }
  return 0;
}

/* Locate and record the orbit at the mark p between (pa, da) and
 * (pb, db). */
static void record_mark(sc_orbit_branch *b, const segment *S, double p,
                        double pa, double da, double pb, double db) {
  sc_map *m = b->m;
  int period = S->period;
  double d = pb == pa ? db : da + (p - pa) * (db - da) / (pb - pa);
  double step = NAN, g = NAN, mult = NAN;
  int it = 0, st = sc_ob_set_p(m, b->sp.param, p), conv = 0;
  sc_map_value v;
  for (; !st && it < b->acc.newton_maxiter; it++) {
    st = sc_map_iterate_ex(m, d, period, SC_EVAL_DERIV | SC_EVAL_ITINERARY,
                           b->ctx.force, NULL, NULL, &v, NULL);
    if (st) break;
    g = v.f - d;
    mult = v.dfdd;
    if (!(fabs(mult - 1) > 0)) {
      st = SC_ENOCONV; /* a fold at the mark: g' = 0 */
      break;
    }
    step = g / (mult - 1);
    d -= step;
    /* the step and the residual within the map's Newton tolerances */
    if (sc_test_delta(step, d, b->acc.newton_atol, b->acc.newton_rtol) ==
            SC_OK &&
        sc_test_residual(g, b->acc.newton_ftol) == SC_OK) {
      conv = 1;
      it++;
      break;
    }
  }
  /* the certificate: the residual at the point returned */
  if (!st &&
      sc_map_iterate_ex(m, d, period, SC_EVAL_DERIV | SC_EVAL_ITINERARY,
                        b->ctx.force, NULL, NULL, &v, NULL) == SC_OK) {
    g = v.f - d;
    mult = v.dfdd;
  }
  if (!st && sc_ob_iterate_orbit_forced(b, d, period, b->ctx.force,
                                        b->orb_a) == SC_OK &&
      known(b, period, p, b->orb_a))
    return;
  special_rec *r =
      sc_ob_add_special(b, SC_PT_UZ, S->branch, period, p, d, mult, g);
  if (!r) return;
  r->residual = fabs(g);
  r->error = 0; /* the parameter is the mark itself */
  r->iterations = it;
  if (conv) {
    snprintf(r->note, sizeof r->note,
             "user point: orbit at %.17g located by Newton with the "
             "parameter fixed (%d iterations, last step %.3g in d)",
             p, it, fabs(step));
  } else {
    r->method = SC_LOC_FAILED;
    r->error = fabs(pb - pa);
    snprintf(r->note, sizeof r->note,
             "user point NOT LOCATED: Newton at the parameter fixed at "
             "%.17g %s (residual %.3g after %d iterations); d is "
             "interpolated between the branch points at %.17g and %.17g",
             p, st ? sc_strerror(st) : "did not converge", fabs(g), it, pa,
             pb);
    r->d = pb == pa ? db : da + (p - pa) * (db - da) / (pb - pa);
  }
}

void sc_ob_marks(sc_orbit_branch *b, const segment *S, const double *u) {
  double pa = S->last_p, da = S->last_d, pb = u[1], db = u[0];
  for (size_t i = 0; i < b->sp.nmarks; i++) {
    double p = b->sp.marks[i];
    /* passed on this step, or reached exactly (once: the step leaving a
     * point at the mark does not count it again) */
    if ((pa - p) * (pb - p) < 0 || pb == p)
      record_mark(b, S, p, pa, da, pb, db);
  }
  /* the map's parameter back at the accepted point */
  sc_ob_set_p(b->m, b->sp.param, pb);
}
