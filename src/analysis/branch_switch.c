/* Orbit branches: from a located point to the orbit on its other side
 * (hand-over), the bisection fallback where no border could be located,
 * and the period-doubled branch born at a flip.  Each queues a new job.
 * See branch_orbit_impl.h. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/branch_orbit_impl.h"

/* Parameter offset beyond a located bifurcation at which the orbit on
 * the other side is sought, relative to 1 + |p|: well above the location
 * tolerance (1e-13), small enough that the new orbit is still close to
 * the old one. */
#define CROSS_REL 1e-7

/* An orbit found beyond a bifurcation continues the old one if each of
 * its points lies within this many parameter offsets of an old point
 * (orbit points move with slopes dd/dp of order one to a hundred). */
#define CLOSE_FACTOR 1e3

/* The offsets tried grow by CROSS_GROWTH up to CROSS_REL_MAX (1e-4):
 * next to a switching with the driver frozen shooting needs the orbit a
 * little away from d*, and 1e-4 relative is still below the distance
 * between the special points of the chapter's branches. */
#define CROSS_GROWTH 10
#define CROSS_REL_MAX (1e3 * CROSS_REL)

/* The bisection fallback looks for the end of the piece first
 * BISECT_FIRST_HMIN smallest steps ahead (the corrector gave up within a
 * step of hmin), doubling that offset at most BISECT_DOUBLINGS times and
 * not beyond BISECT_REACH_REL of the parameter interval: a piece that
 * goes on further is not where the corrector stopped. */
#define BISECT_FIRST_HMIN 4
#define BISECT_DOUBLINGS 40
#define BISECT_REACH_REL 1e-2

/* Halvings of the bisection's bracket at most: 2^-200 of any interval
 * is far below the Newton tolerance, where it stops (or where the
 * midpoint rounds to an end). */
#define BISECT_HALVINGS 200

/* Added to a border's rate of change in the parameter, so that one that
 * does not move with it is infinitely far but still compares (the
 * nearest border ahead is sought). */
#define RATE_FLOOR 1e-300

/* Shooting fails next to a switching with the driver frozen, so the
 * bisection may stop short of the border by up to this many of its
 * brackets (at the Newton tolerance, 1e-13 relative: still 1e-10, far
 * below the distance between distinct special points). */
#define BISECT_SHORT_FACTOR 1e3

/* Parameter offsets from a flip at which the doubled orbit is sought,
 * relative to max(1, |p|) and scaled by range / (1 + range), in the order
 * tried: 1e-4 first; smaller ones leave the new orbit nearly degenerate
 * (its multiplier is +1 at the flip, so shooting may fall back onto the
 * old orbit), larger ones may pass the next bifurcation. */
static const double flip_offsets[] = {1e-4, 1e-5, 1e-3, 1e-6};
#define NFLIP_OFFSETS (sizeof flip_offsets / sizeof flip_offsets[0])

/* Displacements of the start from the flip's orbit point, of both signs,
 * in units of sqrt(dp) (1 + |d|) (the doubled orbit's amplitude grows
 * like the square root of the distance to the flip), in the order tried:
 * 0.3 first, about the amplitude of the normal form's coefficients of
 * order one; then the amplitude itself, then a smaller one. */
static const double flip_amplitudes[] = {0.3, 1, 0.1};
#define NFLIP_AMPLITUDES (sizeof flip_amplitudes / sizeof flip_amplitudes[0])

/* The doubled orbit found must lie within this many amplitudes
 * sqrt(dp) (1 + |d|) of the flip's orbit point: farther is another
 * orbit that shooting fell onto. */
#define FLIP_REACH 100

/* ------------------------------------------------------------------ */
/* Handing over to the other side of a located point                    */

/* The first iterate whose itinerary differs between the f^m itineraries
 * @p a and @p c ('|'-separated): "iterate K: A -> C", or "" if none. */
static void first_change(const char *a, const char *c, char *out,
                         size_t len) {
  char what[SC_ITIN_LEN * 2 + 8];
  int k = sc_first_change(a, c, '|', what, sizeof what);
  if (k) snprintf(out, len, "iterate %d: %.*s", k, (int)(len > 20 ? len - 20 : 0), what);
  else if (len) out[0] = '\0';
}

/* Whether f^m is continuous across a border of this label: at d* (SW)
 * both sides start from the same positions and velocities, and where two
 * ending events coincide (CS, BR) the motion after them depends
 * continuously on the state; a grazing (GR) or a touching threshold (TT)
 * adds or removes a whole slip, so f jumps there (docs/model.md). */
static int continuous_at(sc_point_label l) {
  return l == SC_PT_SW || l == SC_PT_CS || l == SC_PT_BR;
}

/* How many points of orbit a (na) lie within tol of a point of orbit c
 * (nc); the largest of those distances and of the others' in *worst. */
static int near_points(const double *a, int na, const double *c, int nc,
                       double tol, double *worst) {
  int n = 0;
  *worst = 0;
  for (int i = 0; i < na; i++) {
    double e = HUGE_VAL;
    for (int k = 0; k < nc; k++) e = fmin(e, fabs(a[i] - c[k]));
    if (e <= tol) n++;
    *worst = fmax(*worst, e);
  }
  return n;
}

/* Seeds of a period-q orbit at pc from the border orbit orb (m points)
 * started at orb[k], into b->seed: for q = m its own points (where the map
 * is continuous the orbit beyond starts at them, and next to d* iterating
 * would multiply their error by f' ~ |d - d*|^(-1/2)); otherwise the
 * natural iterates, each replaced by the nearest orbit point when within
 * tol of one, so that an expanding orbit does not carry its error along. */
static int seed_from(sc_orbit_branch *b, const double *orb, int m, int k,
                     int q, int own, double tol) {
  if (own && q == m) {
    for (int i = 0; i < q; i++) b->seed[i] = orb[(k + i) % m];
    return SC_OK;
  }
  b->seed[0] = orb[k];
  for (int i = 1; i < q; i++) {
    sc_map_value v;
    int st = sc_map_eval(b->m, b->seed[i - 1], SC_EVAL_VALUE, &v, NULL);
    if (st) return st;
    double x = v.f, e = tol;
    for (int j = 0; own && j < m; j++)
      if (fabs(orb[j] - v.f) <= e) e = fabs(orb[j] - v.f), x = orb[j];
    b->seed[i] = x;
  }
  return SC_OK;
}

/* After a located point at p (orbit orb of period m on the segment's side,
 * codes cod, itinerary itin), look for the orbit on the other side (dir)
 * and queue it.  Writes what followed into the record's note.
 *
 * The orbit beyond continues the border orbit only if it starts within
 * the corrector's step (hmax) of it: min(q, m) of its points each that
 * close to a point of the border orbit (a crossing-sliding adds or
 * removes one).  An orbit found farther away is another orbit, not the
 * continuation: it is refused and the note says so, with its distance. */
int sc_ob_hand_over(sc_orbit_branch *b, special_rec *r, int m,
                    const sc_itin_code *cod, const char *itin, double p,
                    double *orb, int dir) {
  char base[NOTE_LEN];
  snprintf(base, sizeof base, "%s", r ? r->note : "");
  /* A degenerate point is a touch, not a crossing: the orbit turns back
   * at the border (or stays on it), so no orbit lies beyond it. */
  if (r && r->method == SC_LOC_DEGENERATE) {
    snprintf(r->note, sizeof r->note,
             "%.400s; the orbit touches the border there: the branch ends "
             "here",
             base);
    return SC_END;
  }
  int own = r && continuous_at(r->label);
  double step = sc_ob_hmax(b);
  double far_d = HUGE_VAL, far_p = NAN;
  int far_q = 0;
  /* Offsets from CROSS_REL up: next to a switching with the driver
   * frozen f' grows like |d - d*|^(-1/2), and shooting needs the orbit a
   * little away from d*. */
  for (double off = CROSS_REL; off <= CROSS_REL_MAX; off *= CROSS_GROWTH) {
  double pc = p + dir * off * (1 + fabs(p));
  if (pc < fmin(b->sp.from, b->sp.to) || pc > fmax(b->sp.from, b->sp.to))
    break;
  /* a crossing-sliding removes or adds a global stick phase; at a
   * switching or two events at once the map is continuous, so the orbit
   * beyond keeps the period */
  const int qs[3] = {m, m - 1, m + 1};
  int nq = r && (r->label == SC_PT_SW || r->label == SC_PT_BR) ? 1 : 3;
  for (int iq = 0; iq < nq; iq++) {
    int q = qs[iq];
    if (q < 1 || q > b->sp.max_period) continue;
    for (int k = 0; k < m; k++) {
      if (sc_ob_set_p(b->m, b->sp.param, pc)) break;
      if (seed_from(b, orb, m, k, q, own, step)) continue;
      sc_shoot_result res;
      if (sc_ob_shoot_at(b, q, pc, b->seed, &res) != SC_OK) continue;
      if (q == m) {
        /* the same orbit still: not the other side */
        int same = strcmp(res.itinerary, itin) == 0;
        if (same && cod && sc_map_has_borders(b->m)) {
          sc_map_value v;
          same = sc_ob_orbit_borders(b, b->orbit[0], q, NULL, b->codes2,
                                     &b->bl_tmp, &v, NULL) == SC_OK &&
                 sc_ob_same_codes(b->codes2, cod, q, k);
        }
        if (same) continue;
      }
      if (sc_ob_minimal_period(b, b->orbit, q, NULL) != q) continue;
      double worst;
      int near = near_points(b->orbit, q, orb, m, step, &worst);
      if (near < (q < m ? q : m)) {
        if (worst < far_d) far_d = worst, far_p = pc, far_q = q;
        continue;
      }
      /* the job starts at the new orbit's point nearest the border orbit */
      int i0 = 0;
      double e0 = HUGE_VAL;
      for (int i = 0; i < q; i++)
        for (int j = 0; j < m; j++)
          if (fabs(b->orbit[i] - orb[j]) < e0)
            e0 = fabs(b->orbit[i] - orb[j]), i0 = i;
      char origin[96];
      snprintf(origin, sizeof origin, "%s at %.10g",
               r ? sc_point_label_text(r->label) : "point", p);
      int queued =
          sc_ob_push_job(b, q, pc, b->orbit[i0], dir, fabs(pc - p), origin);
      char change[160] = "";
      first_change(itin, res.itinerary, change, sizeof change);
      if (r)
        snprintf(r->note, sizeof r->note,
                 "%.360s; %sthe branch continues with period %d%s%.150s",
                 base, queued ? "" : "not followed (max-branches): ", q,
                 change[0] ? " (" : "", change);
      if (r && change[0]) strncat(r->note, ")", sizeof r->note - strlen(r->note) - 1);
      return SC_OK;
    }
  }
  }
  if (r && isfinite(far_d))
    snprintf(r->note, sizeof r->note,
             "%.330s; hand-over refused: the period-%d orbit found beyond "
             "(at %.10g) lies %.3g from the border orbit, more than the "
             "corrector's step %.3g: the branch ends here",
             base, far_q, far_p, far_d, step);
  else if (r)
    snprintf(r->note, sizeof r->note,
             "%.400s; no orbit on the other side: the branch ends here",
             base);
  return SC_END;
}

/* ------------------------------------------------------------------ */
/* Fallback: bisection on a change of itinerary code                     */

/* Whether the natural orbit found by shooting at p from orb_a still has
 * the segment's codes (or itinerary, for a model without codes). */
static int on_piece(sc_orbit_branch *b, int m, double p, double *orb_a,
                    const sc_shoot_result *res) {
  (void)p;
  (void)orb_a;
  if (strcmp(res->itinerary, b->ctx.itin) != 0) return 0;
  if (!b->ctx.force) return 1;
  sc_map_value v;
  return sc_ob_orbit_borders(b, b->orbit[0], m, NULL, b->codes2, &b->bl_tmp, &v,
                             NULL) == SC_OK &&
         sc_ob_same_codes(b->codes2, b->codes, m, 0);
}

/* Locate where the piece of the period-m orbit ends, between pa (orbit
 * points orb_a, on the piece) and beyond in direction dir.  Returns SC_OK
 * with the bracket [pa, pb] and orb_a updated, or SC_ENOCONV if the piece
 * does not end within the offsets tried. */
static int locate_by_bisection(sc_orbit_branch *b, int m, double *pa,
                               double *pb, double *orb_a, double hmin,
                               int dir) {
  const sc_accuracy *acc = &b->acc;
  double p0 = *pa, pmin = fmin(b->sp.from, b->sp.to),
         pmax = fmax(b->sp.from, b->sp.to);
  sc_shoot_result res;
  /* An offset beyond which the piece has ended: grow from hmin. */
  double w = BISECT_FIRST_HMIN * hmin, lo = p0, hi = NAN;
  for (int k = 0; k < BISECT_DOUBLINGS; k++, w *= 2) {
    double p = p0 + dir * w;
    if (p < pmin || p > pmax) p = dir > 0 ? pmax : pmin;
    int st = sc_ob_shoot_at(b, m, p, orb_a, &res);
    if (st != SC_OK || !on_piece(b, m, p, orb_a, &res)) {
      hi = p;
      break;
    }
    lo = p;
    memcpy(orb_a, b->orbit, (size_t)m * sizeof *orb_a);
    if (p == pmin || p == pmax || w > BISECT_REACH_REL * (pmax - pmin)) break;
  }
  if (isnan(hi)) return SC_ENOCONV;
  for (int it = 0; it < BISECT_HALVINGS; it++) {
    if (fabs(hi - lo) <= acc->newton_atol + acc->newton_rtol * fabs(lo))
      break;
    double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    int st = sc_ob_shoot_at(b, m, mid, orb_a, &res);
    if (st == SC_OK && on_piece(b, m, mid, orb_a, &res)) {
      lo = mid;
      memcpy(orb_a, b->orbit, (size_t)m * sizeof *orb_a);
    } else {
      hi = mid;
    }
  }
  *pa = lo;
  *pb = hi;
  return SC_OK;
}

/* After a bisection bracket [pa, pb] (orbit orb on the segment's side):
 * the orbit just beyond, its borders, and the one that vanishes at the
 * bracket located by Newton from that side (where it is smooth).  Records
 * the point, hands over, and returns. */
static void after_bisection(sc_orbit_branch *b, int branch, int m, double pa,
                            double pb, double *orb, int dir) {
  const char *pname = sc_map_type(b->m)->params[b->sp.param].name;
  char itin[SC_ITIN_LEN];
  snprintf(itin, sizeof itin, "%s", b->ctx.itin);
  /* the orbit beyond the bracket, by shooting from the old one */
  sc_shoot_result res;
  int have = 0;
  double pc = pb + dir * CROSS_REL * (1 + fabs(pb));
  for (int k = 0; k < m && !have; k++) {
    if (sc_ob_set_p(b->m, b->sp.param, pc) ||
        sc_ob_iterate_orbit(b, orb[k], m, b->seed))
      continue;
    have = sc_ob_shoot_at(b, m, pc, b->seed, &res) == SC_OK &&
           sc_ob_close_orbits(b->orbit, m, orb, m,
                              CLOSE_FACTOR * CROSS_REL * (1 + fabs(pb)));
  }
  border_fix best = {0};
  sc_border bbest;
  memset(&bbest, 0, sizeof bbest);
  if (have && sc_map_has_borders(b->m)) {
    sc_map_value v;
    double dc = b->orbit[0];
    if (sc_ob_orbit_borders(b, dc, m, NULL, b->codes2, &b->bl_cur, &v, NULL) ==
        SC_OK) {
      /* the border nearest to zero ahead (backwards from this side) */
      double tbest = HUGE_VAL;
      for (size_t i = 0; i < b->bl_cur.n && i < b->bl_cur.cap; i++) {
        const sc_border *x = &b->bl_cur.b[i];
        double rate = fabs(x->dp[b->sp.param]) + RATE_FLOOR;
        double t = x->value / rate;
        if (x->value >= 0 && t < tbest) tbest = t, bbest = *x;
      }
      if (isfinite(tbest)) {
        double mb = -bbest.value; /* mirror: a bracket for the interpolation */
        sc_ob_locate_border(b, m, b->codes2, &bbest, pc, dc, bbest.value, pa,
                            orb[0], mb, &best);
        /* Shooting fails next to a switching with the driver frozen (f'
         * grows like |d - d*|^(-1/2)), so the bisection can stop short of
         * the border by far more than its bracket: a certified solution
         * of the border's system this close is that border. */
        if (best.ok && fabs(best.p - pa) > BISECT_SHORT_FACTOR * fabs(pb - pa) +
                                               BISECTION_REACH *
                                                   (1 + fabs(pa))) {
          best.ok = 0;
          snprintf(best.why, sizeof best.why,
                   "Newton from the other side converged to %s = %.17g, "
                   "away from the bisection bracket",
                   pname, best.p);
        }
      }
    }
  }
  special_rec *r;
  if (best.ok) {
    r = sc_ob_record_border(b, branch, m, &bbest, &best, pa, orb[0], pb - pa);
    if (r) {
      size_t n = strlen(r->note);
      snprintf(r->note + n, sizeof r->note - n,
               " (found where the corrector stopped; located from the side "
               "where it is smooth, bisection bracket %.2g)",
               fabs(pb - pa));
    }
  } else {
    /* No border known beyond: the border of this side's orbit (at pa,
     * along the segment's codes) nearest to its zero in the parameter is
     * what is known; with none, the label says only that the itinerary
     * changes here (IC), not which border. */
    const char *side = "beyond";
    if (!bbest.name[0] && b->ctx.force && sc_map_has_borders(b->m)) {
      sc_map_value v;
      if (sc_ob_set_p(b->m, b->sp.param, pa) == SC_OK &&
          sc_ob_orbit_borders(b, orb[0], m, b->codes, NULL, &b->bl_cur, &v,
                              NULL) == SC_OK) {
        double tbest = HUGE_VAL;
        for (size_t i = 0; i < b->bl_cur.n && i < b->bl_cur.cap; i++) {
          const sc_border *x = &b->bl_cur.b[i];
          double rate = fabs(x->dp[b->sp.param]);
          double t = rate > 0 ? x->value / rate : HUGE_VAL;
          if (x->value >= 0 && t < tbest) tbest = t, bbest = *x;
        }
        /* it must vanish within the bisection's reach of pa */
        if (!(tbest <= BISECTION_REACH * (1 + fabs(pa))))
          memset(&bbest, 0, sizeof bbest);
        side = "on this side, vanishing at the bracket";
      }
    }
    sc_point_label l = bbest.name[0] ? sc_point_label_of_border(bbest.kind)
                                     : SC_PT_IC;
    sc_map_value va;
    double mult = NAN;
    if (!sc_ob_set_p(b->m, b->sp.param, pa) &&
        !sc_map_iterate(b->m, orb[0], m, SC_EVAL_DERIV, &va, NULL))
      mult = va.dfdd;
    r = sc_ob_add_special(b, l, branch, m, pa, orb[0], mult,
                          bbest.name[0] ? bbest.value : NAN);
    if (r) {
      r->method = SC_LOC_BISECTION;
      r->error = fabs(pb - pa);
      snprintf(r->border, sizeof r->border, "%s", bbest.name);
      snprintf(r->note, sizeof r->note,
               "located by BISECTION (fallback) on a change of itinerary, "
               "bracket %.2g; %s%s%s%s%s",
               fabs(pb - pa),
               bbest.name[0] ? "nearest border " : "no border known (IC: "
                                                   "the itinerary changes, "
                                                   "its kind is unknown)",
               bbest.name[0] ? side : "", bbest.name[0] ? ": " : "",
               bbest.name, best.why[0] ? "; Newton: " : "");
      if (best.why[0])
        strncat(r->note, best.why, sizeof r->note - strlen(r->note) - 1);
    }
  }
  sc_ob_hand_over(b, r, m, b->ctx.force ? b->codes : NULL, itin, pa, orb, dir);
}

/* ------------------------------------------------------------------ */
/* Flips                                                                */

/* At a located flip (p, d) of the period-m branch: the period-2m orbit
 * born there, sought on either side from d displaced along the
 * eigendirection (in one dimension: d itself). */
int sc_ob_switch_flip(sc_orbit_branch *b, int m, double p, double d) {
  if (2 * m > b->sp.max_period) return 0;
  for (size_t i = 0; i < NFLIP_OFFSETS; i++) {
    double dp = flip_offsets[i] * fmax(1, fabs(p)) * fabs(b->sp.to - b->sp.from) /
                (1 + fabs(b->sp.to - b->sp.from));
    for (int side = -1; side <= 1; side += 2) {
      double ps = p + side * dp;
      if (ps < fmin(b->sp.from, b->sp.to) || ps > fmax(b->sp.from, b->sp.to))
        continue;
      for (size_t ia = 0; ia < 2 * NFLIP_AMPLITUDES; ia++) {
        double eps = (ia % 2 ? -1 : 1) * sqrt(dp) * flip_amplitudes[ia / 2] *
                     (1 + fabs(d));
        if (sc_ob_set_p(b->m, b->sp.param, ps)) continue;
        if (sc_ob_iterate_orbit(b, d + eps, 2 * m, b->seed)) continue;
        sc_shoot_result res;
        if (sc_ob_shoot_at(b, 2 * m, ps, b->seed, &res) != SC_OK) continue;
        if (sc_ob_minimal_period(b, b->orbit, 2 * m, NULL) != 2 * m) continue;
        if (fabs(b->orbit[0] - d) > FLIP_REACH * sqrt(dp) * (1 + fabs(d)))
          continue;
        char origin[96];
        snprintf(origin, sizeof origin, "PD at %.10g", p);
        return sc_ob_push_job(b, 2 * m, ps, b->orbit[0], side, dp, origin);
      }
    }
  }
  return 0;
}

/* The fallback from the last point: bisection on a change of itinerary
 * code, then the border that vanishes there located from the far side.
 * A "not located" row just written for this segment is replaced when the
 * fallback finds the point. */
void sc_ob_fall_back(sc_orbit_branch *b, segment *S, const job *jb,
                     sc_msg *msg) {
  int period = S->period, branch = S->branch;
  int dir = S->last_t > 0 ? 1 : S->last_t < 0 ? -1 : jb->direction;
  double pa = S->last_p, pbnd = S->last_p + dir;
  sc_ob_set_p(b->m, b->sp.param, pa);
  double *orb = b->orb_a;
  char why[SC_MSG_LEN];
  snprintf(why, sizeof why, "%s", msg ? msg->text : "");
  size_t nsp0 = b->nsp;
  int failed_row = nsp0 > 0 && b->sps[nsp0 - 1].branch == branch &&
                   b->sps[nsp0 - 1].method == SC_LOC_FAILED;
  if (sc_ob_iterate_orbit_forced(b, S->last_d, period, b->ctx.force, orb) ||
      locate_by_bisection(b, period, &pa, &pbnd, orb, S->set.hmin, dir) !=
          SC_OK) {
    if (!failed_row)
      sc_ob_add_end(b, branch, period, S->last_p, S->last_d, S->last_mult,
                    "the corrector failed and no itinerary change was found "
                    "ahead: %.300s%s",
                    why, NULL);
    else
      sc_ob_add_end(b, branch, period, S->last_p, S->last_d, S->last_mult,
                    "the segment ends at the border it could not locate%s%s",
                    NULL, NULL);
    return;
  }
  char keep[NOTE_LEN] = "";
  if (failed_row) {
    snprintf(keep, sizeof keep, "%s", b->sps[nsp0 - 1].note);
    b->nsp--; /* the bisection's row takes its place */
  }
  after_bisection(b, branch, period, pa, pbnd, orb, dir);
  if (failed_row && b->nsp > 0) {
    special_rec *r = &b->sps[b->nsp - 1];
    size_t n = strlen(r->note);
    snprintf(r->note + n, sizeof r->note - n, "; Newton at the sign change: "
             "%.200s", strstr(keep, "but ") ? strstr(keep, "but ") + 4 : keep);
  }
}
