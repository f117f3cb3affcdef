/* Orbit branches: a border of a segment's orbit located by Newton's
 * method on its defining system, where it changed sign between two
 * accepted points (sc_ob_border_crossed) or lies just ahead of where the
 * corrector stopped (sc_ob_locate_ahead).  See branch_orbit_impl.h. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/branch_orbit_impl.h"


/* A border located by Newton must lie between the two accepted points
 * that bracket its sign change, up to this fraction of their distance
 * (the interpolated start is already inside). */
#define BRACKET_SLACK 0.5

/* Where the corrector stopped, a border is sought up to this many
 * largest steps ahead: the corrector stops when its step, shrunk from at
 * most hmax, falls below hmin, so the border that stopped it lies within
 * a step or two of the last point; 8 leaves room for the error of the
 * linear prediction of its zero. */
#define AHEAD_REACH_HMAX 8

/* A border crossed transversally and located behind the last accepted
 * point by more than this (relative to 1 + |p|) was passed already: the
 * margin is the location's rounding (Newton tolerances of 1e-13 in the
 * default preset, times the system's conditioning), so a zero at the
 * last point itself is kept. */
#define BEHIND_REL 1e-12

/* ------------------------------------------------------------------ */
/* Locating a border: Newton on its defining system                     */

/* Rounding level of a Newton step on a border's system, in ulps of the
 * unknown: f^m is computed to a few ulps and the system's Jacobian
 * amplifies that near a grazing or a switching; a tolerance below it
 * (the "precise" preset) is met at that floor. */
#define BORDER_NOISE_ULPS 256.0

int sc_ob_border_step_done(double dx, double x, const sc_accuracy *acc) {
  return sc_test_delta(dx, x, acc->newton_atol, acc->newton_rtol) == SC_OK ||
         fabs(dx) <= BORDER_NOISE_ULPS * DBL_EPSILON * (1 + fabs(x));
}

/* The border of `like` at (d, p) along the segment's codes. */
static int border_at(sc_orbit_branch *b, int period, double d, double p,
                     const sc_itin_code *codes, const sc_border *like,
                     sc_border *out, sc_map_value *v) {
  if (sc_ob_set_p(b->m, b->sp.param, p)) return SC_EINVAL;
  int st = sc_ob_orbit_borders(b, d, period, codes, NULL, &b->bl_tmp, v, NULL);
  if (st) return st;
  const sc_border *x = sc_border_list_find(&b->bl_tmp, like);
  if (!x) return SC_EUNDEF;
  *out = *x;
  return SC_OK;
}

/* A located border point is degenerate where the uncertainty of its
 * root, the noise of the system reduced to the parameter, G(p), over its
 * slope (eps / |G'|), exceeds DEGENERATE_RATIO times the distance over
 * which that slope itself vanishes (|G'| / |G''|): a double root (the
 * orbit touches the border and turns back), or an orbit that sits on the
 * border along an interval (G vanishes identically).  Newton then stops
 * anywhere within about sqrt(2 eps / |G''|) of the root, whatever the
 * preset, and a residual at rounding certifies nothing.  For a simple
 * root the ratio is eps |G''| / G'^2, many orders below 1. */
#define DEGENERATE_RATIO 1.0

static void mark_degenerate(border_fix *fx, double Gpp) {
  double s = fabs(fx->slope), e = fx->noise;
  if (!(e * fabs(Gpp) > DEGENERATE_RATIO * s * s) && s > 0) return;
  fx->degenerate = 1;
  double lin = s > 0 ? e / s : HUGE_VAL;
  double quad = fabs(Gpp) > 0 ? sqrt(2 * e / fabs(Gpp)) : HUGE_VAL;
  fx->step = fmax(fx->step, fmin(lin, quad));
}

/* Newton in (d0, p) on {f^m(d0) - d0 = 0, m_k(d0, p) = 0} from the
 * interpolation between (pa, da) and (pb, db); the codes are those of the
 * segment. */
static void newton_2d(sc_orbit_branch *b, int period, const sc_itin_code *codes,
                      const sc_border *like, double pa, double da, double ma,
                      double pb, double db, double mb, border_fix *fx) {
  const sc_accuracy *acc = &b->acc;
  size_t ip = b->sp.param;
  double t = ma / (ma - mb);
  if (!(t >= 0 && t <= 1)) t = 0.5;
  double p = pa + t * (pb - pa), d = da + t * (db - da);
  sc_map_value v;
  sc_border bd;
  for (int it = 0; it < BORDER_NEWTON_MAX; it++) {
    int st = border_at(b, period, d, p, codes, like, &bd, &v);
    if (st) {
      snprintf(fx->why, sizeof fx->why,
               "the defining system cannot be evaluated at %s = %.17g, "
               "d = %.17g (%s)",
               sc_map_type(b->m)->params[ip].name, p, d, sc_strerror(st));
      return;
    }
    double F = v.f - d;
    double J11 = v.dfdd - 1, J12 = v.dfdp[ip], J21 = bd.dd, J22 = bd.dp[ip];
    double det = J11 * J22 - J12 * J21;
    fx->m = bd.value, fx->F = F, fx->mult = v.dfdd, fx->iterations = it;
    if (!isfinite(det) || det == 0) {
      snprintf(fx->why, sizeof fx->why,
               "singular Jacobian of the defining system (det %.3g)", det);
      return;
    }
    double dd = (F * J22 - J12 * bd.value) / det;
    double dpp = (J11 * bd.value - F * J21) / det;
    d -= dd;
    p -= dpp;
    fx->step = fabs(dpp);
    if (sc_ob_border_step_done(dpp, p, acc) &&
        sc_ob_border_step_done(dd, d, acc)) {
      /* the certificate: the system at the returned point */
      if (border_at(b, period, d, p, codes, like, &bd, &v)) {
        snprintf(fx->why, sizeof fx->why,
                 "the last Newton point cannot be evaluated");
        return;
      }
      fx->ok = 1;
      fx->p = p, fx->d0 = d, fx->m = bd.value, fx->F = v.f - d;
      fx->mult = v.dfdd, fx->iterations = it + 1;
      /* reduced to p along the fixed point d(p), d' = -J12 / J11:
       * G = m_k(d(p), p), G' = det / J11; G' a difference step either
       * side says where it vanishes */
      double s = J11 != 0 ? -J12 / J11 : NAN;
      fx->slope = J11 != 0 ? det / J11 : NAN;
      fx->noise = (BORDER_NOISE_ULPS * DBL_EPSILON * (1 + fabs(d)) +
                   sc_map_precision(b->m)) *
                  (1 + fabs(J21 / J11));
      double h = acc->fd_step * (1 + fabs(p)), g[2] = {NAN, NAN};
      for (int k = 0; k < 2 && isfinite(s); k++) {
        double hk = k ? -h : h;
        if (border_at(b, period, d + s * hk, p + hk, codes, like, &bd, &v))
          continue;
        double a11 = v.dfdd - 1, a12 = v.dfdp[ip];
        g[k] = (a11 * bd.dp[ip] - a12 * bd.dd) / a11;
      }
      if (isfinite(fx->slope)) mark_degenerate(fx, (g[0] - g[1]) / (2 * h));
      sc_ob_set_p(b->m, ip, p);
      return;
    }
  }
  snprintf(fx->why, sizeof fx->why,
           "Newton did not converge in %d iterations (last step %.3g in "
           "the parameter)",
           BORDER_NEWTON_MAX, fx->step);
}

/* G(p) = f^m(d_on(p)) - d_on(p) and G'(p) of a border in the state, the
 * orbit started on it along codes3 (the codes rotated to its iterate),
 * or along its natural codes where `natural`; its point d_on(p) into
 * *don. */
int sc_ob_d_on(sc_orbit_branch *b, const sc_border *like, double p,
               double *don, double *don_p) {
  size_t ip = b->sp.param;
  /* d_on(p): the border of any one iterate at p says where it is */
  sc_border_list *l = &b->bl_tmp;
  sc_map_value v;
  if (sc_ob_set_p(b->m, ip, p) ||
      sc_map_eval_ex(b->m, like->d_on, SC_EVAL_VALUE, NULL, NULL,
                     (l->n = 0, l), &v, NULL))
    return SC_EUNDEF;
  *don_p = NAN;
  *don = NAN;
  for (size_t i = 0; i < l->n && i < l->cap; i++)
    if (l->b[i].on_state) *don = l->b[i].d_on, *don_p = l->b[i].d_on_dp[ip];
  return isfinite(*don) ? SC_OK : SC_EUNDEF;
}

static int on_state_G(sc_orbit_branch *b, int period, const sc_border *like,
                      double p, int natural, double *G, double *Gp,
                      double *don, sc_map_value *v) {
  size_t ip = b->sp.param;
  double don_p;
  if (sc_ob_d_on(b, like, p, don, &don_p)) return SC_EUNDEF;
  int st = sc_map_iterate_ex(b->m, *don, period, SC_EVAL_DERIV,
                             natural ? NULL : b->codes3, NULL, NULL, v, NULL);
  if (st) return st;
  *G = v->f - *don;
  *Gp = v->dfdp[ip] + (v->dfdd - 1) * don_p;
  return isfinite(*G) && isfinite(*Gp) ? SC_OK : SC_ENONFINITE;
}

/* The certificate of a root p of the on-state system (its last Newton
 * step dp, point don): the orbit's first point, the noise and whether
 * the root is degenerate. */
static void on_state_done(sc_orbit_branch *b, int period, const sc_border *like,
                          double p, double dp, double don, int it,
                          border_fix *fx) {
  const sc_accuracy *acc = &b->acc;
  int k = like->iterate;
  sc_map_value v;
  fx->ok = 1;
  fx->p = p, fx->dk = don, fx->step = fabs(dp);
  fx->iterations = it + 1;
  fx->noise = BORDER_NOISE_ULPS * DBL_EPSILON * (1 + fabs(don)) +
              sc_map_precision(b->m);
  /* the orbit's first point: iterate back is not possible; report
   * the continued point by iterating forward the remaining steps */
  double *o = b->seed;
  if (sc_ob_iterate_orbit_forced(b, don, period, b->codes3, o) == SC_OK)
    fx->d0 = o[(period - k) % period];
  else
    fx->d0 = NAN;
  /* G' a difference step either side: where it vanishes */
  double h = acc->fd_step * (1 + fabs(p)), g[2] = {NAN, NAN}, Gh, dh;
  for (int s = 0; s < 2; s++)
    if (on_state_G(b, period, like, p + (s ? -h : h), 0, &Gh, &g[s], &dh, &v))
      g[s] = NAN;
  mark_degenerate(fx, (g[0] - g[1]) / (2 * h));
  sc_ob_set_p(b->m, b->sp.param, p);
}

/* A border in the state itself (m = +-(d_k - d_on(p))): Newton in p on
 * G(p) = f^m(d_on(p)) - d_on(p) with the orbit started on the border at
 * iterate k (the codes rotated to start there).  The map may be singular
 * next to such a border, the orbit through it is not.
 *
 * The branch meets such a border tangentially (its point approaches d_on
 * like the square of the distance in p), so where another point of the
 * orbit also lies next to d_on (a period-16 orbit that shadows a
 * period-4 one passes d* twice), the corrector stops far from the root,
 * where the orbit started on the border no longer follows the segment's
 * codes (G is not defined there).  Then G along the natural codes steers
 * Newton, whose step is kept inside the bracket of G's sign changes met
 * (bisected where it would leave it); the root is accepted only where
 * the orbit follows the segment's codes, as their system's certificate. */
static void newton_on_state(sc_orbit_branch *b, int period,
                            const sc_itin_code *codes, const sc_border *like,
                            double pa, double ma, double pb, double mb,
                            border_fix *fx) {
  const sc_accuracy *acc = &b->acc;
  int k = like->iterate;
  for (int i = 0; i < period; i++) b->codes3[i] = codes[(i + k) % period];
  double t = ma / (ma - mb);
  if (!(t >= 0 && t <= 1)) t = 0.5;
  double p = pa + t * (pb - pa), lo = NAN, hi = NAN, Glo = NAN;
  sc_map_value v;
  for (int it = 0; it < BORDER_NEWTON_MAX; it++) {
    double G, Gp, don;
    int st = on_state_G(b, period, like, p, 0, &G, &Gp, &don, &v);
    int forced = st == SC_OK;
    if (!forced) st = on_state_G(b, period, like, p, 1, &G, &Gp, &don, &v);
    if (st) {
      snprintf(fx->why, sizeof fx->why,
               "the orbit from the border cannot be evaluated at %.17g (%s)",
               p, sc_strerror(st));
      return;
    }
    fx->F = G, fx->m = 0, fx->mult = v.dfdd, fx->iterations = it;
    fx->slope = Gp;
    /* the bracket: the last points with G of either sign */
    if (isnan(lo) || (G > 0) == (Glo > 0)) lo = p, Glo = G;
    else hi = p;
    double dp = Gp != 0 ? G / Gp : HUGE_VAL;
    if (forced && it > 0 && sc_ob_border_step_done(dp, p, acc)) {
      on_state_done(b, period, like, p, dp, don, it, fx);
      return;
    }
    double pn = p - dp;
    if (!isnan(hi) && !(pn > fmin(lo, hi) && pn < fmax(lo, hi)))
      pn = 0.5 * (lo + hi);
    if (!isfinite(pn)) {
      snprintf(fx->why, sizeof fx->why, "singular derivative (%.3g)", Gp);
      return;
    }
    fx->step = fabs(pn - p);
    p = pn;
  }
  snprintf(fx->why, sizeof fx->why,
           "Newton did not converge in %d iterations (last step %.3g)",
           BORDER_NEWTON_MAX, fx->step);
}

/* The codes of a border's defining system: the segment's, with the
 * border's own code for its iterate where it has one (into codes4). */
static const sc_itin_code *defining_codes(sc_orbit_branch *b, int period,
                                          const sc_itin_code *codes,
                                          const sc_border *like) {
  if (like->alt.n <= 0) return codes;
  sc_itin_code *c = b->codes4;
  for (int i = 0; i < period; i++) c[i] = codes[i];
  c[like->iterate] = like->alt;
  return c;
}

static void check_located(sc_orbit_branch *b, int period,
                          const sc_itin_code *codes, const sc_border *like,
                          double pa, double pb, border_fix *fx);

void sc_ob_locate_border(sc_orbit_branch *b, int period,
                         const sc_itin_code *codes, const sc_border *like,
                         double pa, double da, double ma, double pb,
                         double db, double mb, border_fix *fx) {
  memset(fx, 0, sizeof *fx);
  codes = defining_codes(b, period, codes, like);
  if (like->on_state)
    newton_on_state(b, period, codes, like, pa, ma, pb, mb, fx);
  else
    newton_2d(b, period, codes, like, pa, da, ma, pb, db, mb, fx);
  if (fx->ok) check_located(b, period, codes, like, pa, pb, fx);
}

/* A border of the segment located from the point ua (multiple shooting:
 * m + 1 entries, S->ms_start) or from the interpolation between (pa, da,
 * ma) and (pb, db, mb) (single shooting). */
static void locate_seg(sc_orbit_branch *b, segment *S, const sc_border *like,
                       double pa, double da, double ma, double pb, double db,
                       double mb, border_fix *fx) {
  if (!S->ms) {
    sc_ob_locate_border(b, S->period, b->codes, like, pa, da, ma, pb, db, mb,
                        fx);
    return;
  }
  memset(fx, 0, sizeof *fx);
  const sc_itin_code *codes = defining_codes(b, S->period, b->codes, like);
  sc_ob_ms_locate(b, S, codes, like, S->ms_start, fx);
  if (fx->ok) check_located(b, S->period, codes, like, pa, pb, fx);
}

/* The checks of a located border point: inside the bracket [pa, pb] and
 * the task's interval, of the segment's minimal period. */
static void check_located(sc_orbit_branch *b, int period,
                          const sc_itin_code *codes, const sc_border *like,
                          double pa, double pb, border_fix *fx) {
  /* It must lie between the two points that bracket the sign change. */
  double lo = fmin(pa, pb), hi = fmax(pa, pb);
  double w = BRACKET_SLACK * (hi - lo) + BISECTION_REACH * (1 + fabs(pa));
  if (fx->p < lo - w || fx->p > hi + w) {
    fx->ok = 0;
    snprintf(fx->why, sizeof fx->why,
             "Newton converged to %.17g, outside the bracket [%.17g, %.17g]",
             fx->p, lo, hi);
    return;
  }
  /* Points are reported only inside the task's interval: a degenerate
   * one known to fx->step only is put on the interval's end when within
   * that of it (where Newton stops within its uncertainty is rounding). */
  double plo = fmin(b->sp.from, b->sp.to), phi = fmax(b->sp.from, b->sp.to);
  if (fx->degenerate && fx->p < plo && plo - fx->p <= fx->step) fx->p = plo;
  if (fx->degenerate && fx->p > phi && fx->p - phi <= fx->step) fx->p = phi;
  if (fx->p < plo || fx->p > phi) {
    fx->ok = 0;
    snprintf(fx->why, sizeof fx->why,
             "Newton converged to %.17g, outside the interval [%.17g, %.17g]",
             fx->p, fmin(b->sp.from, b->sp.to), fmax(b->sp.from, b->sp.to));
    return;
  }
  double *o = fx->orb ? fx->orb : b->seed;
  if (!like->on_state && !fx->orb) {
    if (sc_ob_set_p(b->m, b->sp.param, fx->p) ||
        sc_ob_iterate_orbit_forced(b, fx->d0, period, codes, o)) {
      fx->ok = 0;
      snprintf(fx->why, sizeof fx->why, "the located orbit cannot be "
                                        "iterated");
      return;
    }
    fx->dk = o[like->iterate];
  }
  /* The orbit located must be the segment's, not one of lower period
   * through the same border (bk2 with beta = 1: the synchronous orbit
   * d = d* = 0 is a fixed point of every f^m). */
  int q = sc_ob_minimal_period(b, o, period, codes);
  if (q < period) {
    fx->ok = 0;
    snprintf(fx->why, sizeof fx->why,
             "Newton converged to an orbit of minimal period %d, not %d", q,
             period);
  }
}

/* Record a located (or not located) border point. */
special_rec *sc_ob_record_border(sc_orbit_branch *b, int branch, int period,
                                 const sc_border *bd, const border_fix *fx,
                                 double p_est, double d_est, double width) {
  sc_point_label l = sc_point_label_of_border(bd->kind);
  special_rec *r;
  if (fx->ok) {
    r = sc_ob_add_special(b, l, branch, period, fx->p, fx->dk, fx->mult, fx->m);
    if (!r) return NULL;
    r->residual = fmax(fabs(fx->F), fabs(fx->m));
    /* degenerate: no certificate, the residual is at the system's noise
     * anywhere within the uncertainty */
    if (fx->degenerate) r->residual = fmax(r->residual, fx->noise);
    r->error = fx->step;
    r->iterations = fx->iterations;
    if (fx->orb)
      snprintf(r->note, sizeof r->note,
               "%s of iterate %d: %s; Newton on {x_(k+1) = f(x_k), k < %d "
               "(multiple shooting); border = 0}, %d iterations, residual "
               "%.2g",
               sc_point_label_text(l), bd->iterate + 1, bd->name, period,
               fx->iterations, r->residual);
    else
      snprintf(r->note, sizeof r->note,
               "%s of iterate %d: %s; Newton on {f^%d(d) = d, border = 0}, "
               "%d iterations, residual %.2g",
               sc_point_label_text(l), bd->iterate + 1, bd->name, period,
               fx->iterations, r->residual);
    if (fx->degenerate) {
      r->method = SC_LOC_DEGENERATE;
      size_t n = strlen(r->note);
      snprintf(r->note + n, sizeof r->note - n,
               "; DEGENERATE: the system's slope in the parameter %.2g is "
               "at its noise %.2g (a double root, or the orbit on the border "
               "along an interval): known to %.2g only, no certificate",
               fx->slope, fx->noise, r->error);
    }
  } else {
    r = sc_ob_add_special(b, l, branch, period, p_est, d_est, NAN, bd->value);
    if (!r) return NULL;
    r->method = SC_LOC_FAILED;
    r->error = width;
    snprintf(r->note, sizeof r->note,
             "NOT LOCATED: %s of iterate %d (%s) changed sign here but %s",
             sc_point_label_text(l), bd->iterate + 1, bd->name, fx->why);
  }
  snprintf(r->border, sizeof r->border, "%s", bd->name);
  return r;
}

/* The orbit located at fx on border `like` into orb, aligned with the
 * segment's start: along the border's defining codes, and for a border
 * in the state from the point on it (the map may be singular next to it,
 * so iterating from d0 would not land on it).  The codes are rebuilt
 * here: locating the other borders of a step reuses their scratch. */
static int border_orbit(sc_orbit_branch *b, int period, const sc_border *like,
                        const border_fix *fx, double *orb) {
  if (fx->orb) {
    memcpy(orb, fx->orb, (size_t)period * sizeof *orb);
    return sc_ob_set_p(b->m, b->sp.param, fx->p);
  }
  const sc_itin_code *codes = defining_codes(b, period, b->codes, like);
  if (sc_ob_set_p(b->m, b->sp.param, fx->p)) return SC_EINVAL;
  if (!like->on_state)
    return sc_ob_iterate_orbit_forced(b, fx->d0, period, codes, orb);
  int k = like->iterate;
  for (int i = 0; i < period; i++) b->codes3[i] = codes[(i + k) % period];
  int st = sc_ob_iterate_orbit_forced(b, fx->dk, period, b->codes3, b->seed);
  if (st) return st;
  for (int i = 0; i < period; i++) orb[(i + k) % period] = b->seed[i];
  return SC_OK;
}

/* Detect: a border of the orbit at (u) that changed sign since the last
 * accepted point (whose borders are in bl_prev).  Locates every such
 * border, records the one met first, hands over, and returns 1; 0 when
 * none changed sign.  The borders at u are left in bl_cur. */
int sc_ob_border_crossed(sc_orbit_branch *b, segment *S, const double *u) {
  if (!b->ctx.force) return 0;
  int period = S->period;
  sc_map_value v;
  const double *uf = S->ms ? sc_branch_point(S->br) : NULL;
  if (S->ms ? sc_ob_ms_eval(b, b->codes, period, uf, &b->bl_cur, &v, NULL, NULL)
            : sc_ob_set_p(b->m, b->sp.param, u[1]) ||
                  sc_ob_orbit_borders(b, u[0], period, b->codes, NULL,
                                      &b->bl_cur, &v, NULL))
    return 0; /* the corrector accepted it, so this does not happen */
  int dir = u[1] > S->last_p ? 1 : -1;
  border_fix best = {0}, fx;
  sc_border bbest, bfail;
  int nfail = 0, nchanged = 0;
  char whyfail[200] = "";
  double dist_best = HUGE_VAL;
  for (size_t i = 0; i < b->bl_cur.n && i < b->bl_cur.cap; i++) {
    const sc_border *c = &b->bl_cur.b[i];
    if (c->value > 0) continue;
    const sc_border *a = sc_border_list_find(&b->bl_prev, c);
    if (!a || !(a->value > 0)) continue;
    nchanged++;
    sc_border like = *c;
    if (S->ms) { /* the start: the interpolation at the border's zero */
      double t = a->value / (a->value - c->value);
      if (!(t >= 0 && t <= 1)) t = 0.5;
      for (int k = 0; k <= period; k++)
        S->ms_start[k] = S->ms_last[k] + t * (uf[k] - S->ms_last[k]);
    }
    locate_seg(b, S, &like, S->last_p, S->last_d, a->value, u[1], u[0],
               c->value, &fx);
    if (!fx.ok) {
      if (!nfail) bfail = like, snprintf(whyfail, sizeof whyfail, "%s", fx.why);
      nfail++;
      continue;
    }
    double dist = fabs(fx.p - S->last_p);
    if (dist < dist_best) {
      dist_best = dist, best = fx, bbest = like;
      if (fx.orb) {
        memcpy(S->ms_best, fx.orb, (size_t)(period + 1) * sizeof *fx.orb);
        best.orb = S->ms_best;
      }
    }
  }
  if (!nchanged) return 0;
  special_rec *r;
  double *orb = b->orb_a;
  if (best.ok) {
    r = sc_ob_record_border(b, S->branch, period, &bbest, &best, 0, 0, 0);
    if (r && nchanged > 1) {
      size_t n = strlen(r->note);
      snprintf(r->note + n, sizeof r->note - n,
               "; %d other border(s) changed sign in the same step, beyond "
               "it (the orbit there is not real)",
               nchanged - 1);
    }
    if (border_orbit(b, period, &bbest, &best, orb))
      memcpy(orb, b->orb_c, (size_t)period * sizeof *orb);
    sc_ob_hand_over(b, r, period, b->codes, b->ctx.itin, best.p, orb, dir);
    return 1;
  }
  /* None located: say so (the row is replaced if the fallback below
   * locates the point), and let the caller fall back to a bisection from
   * the last point. */
  fx = (border_fix){0};
  snprintf(fx.why, sizeof fx.why, "%s", whyfail);
  r = sc_ob_record_border(b, S->branch, period, &bfail, &fx, S->last_p,
                          S->last_d, fabs(u[1] - S->last_p));
  if (r && nfail > 1) {
    size_t n = strlen(r->note);
    snprintf(r->note + n, sizeof r->note - n,
             "; %d border(s) changed sign in this step, none located",
             nfail);
  }
  return 2;
}

/* Where the corrector cannot go on from the last point A: the borders of
 * A whose zero lies just ahead along the tangent, each located by Newton
 * on its own defining system (a grazing met from the side where the
 * guard fires: with the event at the guard's maximum; a switching: with
 * the orbit started on d*).  Records the nearest certified one ahead,
 * hands over, and returns 1; 0 when none is found. */
int sc_ob_locate_ahead(sc_orbit_branch *b, segment *S, int dir) {
  if (!b->ctx.force) return 0;
  int period = S->period;
  size_t ip = b->sp.param;
  border_fix best = {0}, fx;
  sc_border bbest;
  double reach = AHEAD_REACH_HMAX * S->set.hmax;
  for (size_t i = 0; i < b->bl_prev.n && i < b->bl_prev.cap; i++) {
    const sc_border *x = &b->bl_prev.b[i];
    sc_border like = *x;
    if (x->on_state) {
      /* a border in the state is met tangentially by the branch (the
       * orbit point approaches d* like the square of the distance in the
       * parameter), so no rate predicts it: Newton from A itself, within
       * the reach ahead */
      if (!(x->value > 0)) continue;
      if (S->ms)
        memcpy(S->ms_start, S->ms_last, (size_t)(period + 1) * sizeof(double));
      locate_seg(b, S, &like, S->last_p, S->last_d, 0,
                 S->last_p + dir * reach, S->last_d, -1, &fx);
    } else {
      /* multiple shooting: x->dd is with respect to its own iterate */
      double xt = S->ms ? S->ms_tan[x->iterate] : S->last_td;
      double rate = x->dd * xt + x->dp[ip] * S->last_t;
      double ds = x->value > 0 && rate < 0 ? -x->value / rate : HUGE_VAL;
      if (!(ds <= reach)) continue;
      /* the far end mirrored at twice the predicted zero: the linear
       * interpolation starts Newton at the prediction */
      double dpar = S->last_t * ds, dd = S->last_td * ds;
      for (int k = 0; S->ms && k <= period; k++)
        S->ms_start[k] = S->ms_last[k] + ds * S->ms_tan[k];
      locate_seg(b, S, &like, S->last_p, S->last_d, x->value,
                 S->last_p + 2 * dpar, S->last_d + 2 * dd, -x->value, &fx);
    }
    /* A border in the state is met tangentially: the orbit point sits
     * within rounding of it over a stretch of the parameter (its
     * distance grows like the square of the parameter's), so the last
     * accepted point may lie a little past the solution. */
    double behind = (x->on_state ? BISECTION_REACH : BEHIND_REL) *
                    (1 + fabs(S->last_p));
    if (!fx.ok || (fx.p - S->last_p) * dir < -behind) continue;
    if (!best.ok || fabs(fx.p - S->last_p) < fabs(best.p - S->last_p)) {
      best = fx, bbest = like;
      if (fx.orb) {
        memcpy(S->ms_best, fx.orb, (size_t)(period + 1) * sizeof *fx.orb);
        best.orb = S->ms_best;
      }
    }
  }
  if (!best.ok) return 0;
  special_rec *r =
      sc_ob_record_border(b, S->branch, period, &bbest, &best, 0, 0, 0);
  if (r) {
    size_t n = strlen(r->note);
    snprintf(r->note + n, sizeof r->note - n,
             "; met where the corrector stopped (the segment's smooth "
             "extension ends at it)");
  }
  double *orb = b->orb_a;
  if (border_orbit(b, period, &bbest, &best, orb))
    for (int i = 0; i < period; i++) orb[i] = NAN;
  sc_ob_hand_over(b, r, period, b->codes, b->ctx.itin, best.p, orb, dir);
  return 1;
}
