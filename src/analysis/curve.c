/* Fold and flip curves of a model's period-m orbits in two parameters:
 * the defining system of continuation/curve.c on g = f^m with exact
 * second and third derivatives (SC_EVAL_DERIV2), continued both ways by
 * pseudo-arclength (continuation/branch.c), with CP / GPD / TP located by
 * Newton on the extended system (docs/curves.md). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/curve_impl.h"

/* The default steps of a curve in (d, x, y): a first step of 1e-3, small
 * against the chapter's parameters (order one) so that the corrector
 * converges from the start's tangent, and a largest of 2e-2, which draws
 * the chapter's curves (spans of order one) smoothly in some hundred
 * points, well within the default max_points (2000). */
#define CURVE_H0_DEFAULT 1e-3
#define CURVE_HMAX_DEFAULT 2e-2
#define CURVE_MAX_POINTS_DEFAULT 2000

/* A normal-form coefficient vanishes within this many residual
 * tolerances: the accuracy to which a located point meets its system,
 * through the coefficient's conditioning. */
#define COEF_ZERO_FTOLS 100

/* After crossing a border, the new side's curve must start within this
 * many first steps of the border point: a few of the small steps taken
 * across (a multiplier that jumps across the border leaves the new
 * itinerary's fold or flip elsewhere). */
#define CROSS_START_H0 4

void sc_curve_settings_default(sc_curve_settings *s) {
  memset(s, 0, sizeof *s);
  s->type = SC_CURVE_FOLD;
  s->period = 1;
  s->ix = 0;
  s->iy = 1;
  s->xlo = s->ylo = -HUGE_VAL;
  s->xhi = s->yhi = HUGE_VAL;
  s->h0 = CURVE_H0_DEFAULT;
  s->hmax = CURVE_HMAX_DEFAULT;
  s->max_points = CURVE_MAX_POINTS_DEFAULT;
}

typedef struct {
  sc_map *m;
  int period, ix, iy;
  char itin[SC_ITIN_LEN]; /* of the last evaluation (natural) */
  sc_msg emsg;            /* of the last failed evaluation */
  /* single shooting along the start's code: where the natural itinerary
   * is not itin0 (past a border), the orbit is evaluated along fs's codes
   * instead; NULL: natural only */
  sc_forced_sys *fs;
  const char *itin0;
} map_ctx;

/* g's jet along c->fs's codes: g, g_x, g_p exact (first derivatives of
 * the forced evaluation), the second and third ones by central
 * differences of the exact g_x with step fd_step (1 + |u|): they enter
 * only the continuation's Jacobian and tests past a border, where the
 * curve ends at the located border point. */
static int forced_jet(map_ctx *c, double x, const double *p, sc_curve_jet *j) {
  sc_forced_sys *fs = c->fs;
  sc_map_value v;
  double u[3] = {x, p[c->ix], p[c->iy]};
  int rc = sc_forced_eval(fs, u, fs->codes, NULL, &v);
  if (rc) {
    c->emsg = fs->emsg;
    return rc;
  }
  size_t np = sc_map_nparam(c->m);
  j->g = v.f, j->gx = v.dfdd;
  for (size_t i = 0; i < np; i++)
    j->gp[i] = v.dfdp[i], j->gxp[i] = j->gxxp[i] = 0;
  double gx0 = v.dfdd;
  for (int k = 0; k < 3; k++) {
    double w[3] = {u[0], u[1], u[2]}, h = fs->fd_step * (1 + fabs(u[k]));
    double gd[2];
    for (int e = 0; e < 2; e++) {
      w[k] = u[k] + (e ? -h : h);
      if ((rc = sc_forced_eval(fs, w, fs->codes, NULL, &v))) return rc;
      gd[e] = v.dfdd;
    }
    double dk = (gd[0] - gd[1]) / (2 * h);
    if (k == 0) {
      j->gxx = dk;
      j->gxxx = (gd[0] - 2 * gx0 + gd[1]) / (h * h);
    } else {
      j->gxp[k == 1 ? c->ix : c->iy] = dk;
    }
  }
  /* the parameters back at p (the differences moved them) */
  if (sc_map_set_param(c->m, (size_t)c->ix, p[c->ix], &c->emsg) ||
      sc_map_set_param(c->m, (size_t)c->iy, p[c->iy], &c->emsg))
    return 1;
  return isfinite(j->gxx) && isfinite(j->gxxx) ? 0 : 1;
}

static int jet_fn(double x, const double *p, sc_curve_jet *j, void *user) {
  map_ctx *c = user;
  if (sc_map_set_param(c->m, (size_t)c->ix, p[c->ix], &c->emsg) ||
      sc_map_set_param(c->m, (size_t)c->iy, p[c->iy], &c->emsg))
    return 1; /* outside the parameters' range: shrink the step */
  sc_map_value v;
  if (sc_map_iterate(c->m, x, c->period, SC_EVAL_DERIV2 | SC_EVAL_ITINERARY, &v,
                     &c->emsg)) {
    c->itin[0] = '\0';
    return c->fs ? forced_jet(c, x, p, j) : 1;
  }
  snprintf(c->itin, sizeof c->itin, "%s", v.itinerary);
  if (c->fs && strcmp(c->itin, c->itin0)) return forced_jet(c, x, p, j);
  j->g = v.f;
  j->gx = v.dfdd;
  j->gxx = v.d2fdd2;
  j->gxxx = v.d3fdd3;
  size_t np = sc_map_nparam(c->m);
  for (size_t i = 0; i < np; i++) {
    j->gp[i] = v.dfdp[i];
    j->gxp[i] = v.d2fddp[i];
    j->gxxp[i] = v.d3fdd2p[i];
  }
  /* NaN: an event with zero slope, f not twice differentiable */
  return isfinite(j->gx) && isfinite(j->gxx) && isfinite(j->gxxx) ? 0 : 1;
}

typedef struct {
  const sc_curve_settings *set;
  const sc_curve_output *out;
  sc_curve_stats *stats;
  sc_curve_system cs; /* the system continued: single or multiple */
  sc_curve_system ss; /* single shooting, for the start's correction */
  sc_curve_map1d sys;
  sc_curve_map1d_ms msys;
  map_ctx mc;  /* g = f^m */
  map_ctx mc1; /* f, for multiple shooting */
  const sc_accuracy *acc;
  char itin0[SC_ITIN_LEN];
  /* the start's itinerary code and the orbit's borders there, watched
   * along the curve (fs.nwatch = 0: none, a model without borders) */
  sc_forced_sys fs;
  double *bpa, *bpb, *bpc; /* border values at prev, cur; prev's copy */
  double start3[3];         /* the corrected start (d, x, y) */
  size_t N;   /* unknowns: 3, or m + 2 with multiple shooting */
  double *u0; /* N: the corrected start */
  double *prev, *cur, *u, *mid, *F; /* N each: work */
  int closed;
} trace;

/* x and y of a point u (its last two entries) */
#define UX(T, u) ((u)[(T)->N - 2])
#define UY(T, u) ((u)[(T)->N - 1])

/* g = f^m's jet at the orbit point u[0], parameters from u; fills
 * T->mc.itin.  Returns the callback's status. */
static int g_at(trace *T, const double *u, sc_curve_jet *j) {
  double p[SC_MAP1D_MAXPARAM];
  memcpy(p, T->sys.p, sizeof p);
  p[T->set->ix] = UX(T, u);
  p[T->set->iy] = UY(T, u);
  memset(j, 0, sizeof *j);
  return jet_fn(u[0], p, j, &T->mc);
}

static int emit_special(trace *T, const char *label, const double *u,
                        double coef, double residual, const char *note) {
  sc_curve_special s;
  memset(&s, 0, sizeof s);
  snprintf(s.label, sizeof s.label, "%s", label);
  s.d = u[0], s.x = UX(T, u), s.y = UY(T, u);
  s.coefficient = coef;
  s.residual = residual;
  snprintf(s.note, sizeof s.note, "%s", note);
  if (strcmp(label, "EP") && strcmp(label, "UZ") && !strchr(label, '?'))
    T->stats->nspecial++; /* codimension two: not ends, user points */
  if (T->out && T->out->special && T->out->special(T->out->ctx, &s))
    return SC_ECALLBACK;
  return SC_OK;
}

static double norm_inf(const double *v, size_t n) {
  double m = 0;
  for (size_t i = 0; i < n; i++)
    m = fmax(m, fabs(v[i]));
  return m;
}

static int emit_point(trace *T, const double *u, int branch) {
  sc_curve_jet j;
  if (T->cs.pb.f(u, T->F, T->cs.pb.user) || g_at(T, u, &j))
    return SC_OK; /* cannot happen at an accepted point */
  T->stats->max_residual =
      fmax(T->stats->max_residual, norm_inf(T->F, T->cs.pb.n));
  sc_curve_point pt = {
      UX(T, u), UY(T, u),  u[0], j.gx, sc_curve_coefficient(T->set->type, &j),
      branch,   T->mc.itin};
  T->stats->npoints++;
  if (T->out && T->out->point && T->out->point(T->out->ctx, &pt))
    return SC_ECALLBACK;
  return SC_OK;
}

static double dist_inf(const trace *T, const double *a, const double *b) {
  double m = 0;
  for (size_t i = 0; i < T->N; i++)
    m = fmax(m, fabs(a[i] - b[i]));
  return m;
}

/* Locate the zero of test k between the points a and b (psi values pa,
 * pb of opposite signs) and report it. */
static int locate(trace *T, size_t k, const double *a, const double *b,
                  double pa, double pb) {
  double w = pa / (pa - pb), *u = T->u, *mid = T->mid;
  for (size_t i = 0; i < T->N; i++)
    mid[i] = u[i] = a[i] + w * (b[i] - a[i]);
  sc_curve_cert cert;
  sc_msg msg;
  int st = sc_curve_locate(&T->cs, k, u, T->acc, &cert, &msg);
  char note[128];
  const char *label = T->cs.labels[k];
  char rej[8];
  snprintf(rej, sizeof rej, "%s?", label);
  if (st) {
    snprintf(note, sizeof note, "not located: %.100s", sc_msg_what(msg.text));
    return emit_special(T, rej, mid, NAN, cert.residual, note);
  }
  /* A sign change across a pole or a jump of psi (near d* or a grazing,
   * where f'' grows without bound) is no zero: the located psi must be
   * small against its values at the bracket's ends (sqrt(eps): what a
   * difference-row Newton reaches on a well-scaled zero), and the point
   * must lie near the bracket. */
  double scale = fmax(fabs(pa), fabs(pb));
  double span = dist_inf(T, a, b);
  if (!(fabs(cert.psi) <= SC_SQRT_EPS * scale) ||
      dist_inf(T, u, mid) > SC_CURVE_BRACKET_REACH * span) {
    snprintf(note, sizeof note,
             "rejected: the sign change is not a zero (%s = %.3g, ends "
             "%.3g, %.3g)",
             k == 0 ? "coefficient" : "test", cert.psi, pa, pb);
    return emit_special(T, rej, mid, NAN, cert.residual, note);
  }
  sc_curve_jet j;
  if (g_at(T, u, &j)) return SC_OK;
  double coef = sc_curve_coefficient(T->set->type, &j);
  const char *xn = sc_map_type(T->mc.m)->params[T->set->ix].name;
  const char *yn = sc_map_type(T->mc.m)->params[T->set->iy].name;
  if (k == 0) {
    if (T->set->type == SC_CURVE_FOLD)
      snprintf(note, sizeof note,
               "cusp: the fold's quadratic coefficient changes sign");
    else
      snprintf(note, sizeof note, "generalized flip: %s",
               pa > 0 ? "supercritical to subcritical"
                      : "subcritical to supercritical");
    return emit_special(T, label, u, coef, cert.residual, note);
  }
  /* A turning point where the normal-form coefficient also vanishes is
   * the cusp (reported by its own test): the coefficient tells them
   * apart. */
  if (fabs(coef) <= COEF_ZERO_FTOLS * T->acc->newton_ftol) return SC_OK;
  size_t ip = k == 1 ? T->N - 2 : T->N - 1;
  int max = u[ip] >= a[ip] && u[ip] >= b[ip];
  snprintf(note, sizeof note, "%s %s", k == 1 ? xn : yn, max ? "max" : "min");
  return emit_special(T, label, u, coef, cert.residual, note);
}

/* The user points (marks: values of x) passed on the step from a to b
 * (sc_curve_mark(), on the single-shooting system), reported as UZ, or
 * UZ? with the reason where Newton fails. */
static int user_points(trace *T, const double *a, const double *b,
                       int start) {
  const sc_curve_settings *s = T->set;
  double a3[3] = {a[0], UX(T, a), UY(T, a)}, b3[3] = {b[0], UX(T, b), UY(T, b)};
  for (size_t i = 0; i < s->nmarks; i++) {
    double u3[3], res;
    char note[200];
    int ok = sc_curve_mark(&T->ss.pb, T->acc, sc_map_type(T->mc.m)->params[s->ix].name,
                           s->marks[i], a3, b3, start, u3, &res, note,
                           sizeof note);
    if (ok < 0) continue;
    double *u = T->u;
    u[0] = u3[0], UX(T, u) = u3[1], UY(T, u) = u3[2];
    sc_curve_jet j;
    double coef = g_at(T, u, &j) ? NAN : sc_curve_coefficient(s->type, &j);
    int st = emit_special(T, ok ? "UZ" : "UZ?", u, coef, res, note);
    if (st) return st;
  }
  return SC_OK;
}

static int end_point(trace *T, const double *u, const char *why) {
  sc_curve_jet j;
  double coef = g_at(T, u, &j) ? NAN : sc_curve_coefficient(T->set->type, &j);
  return emit_special(T, "EP", u, coef, NAN, why);
}

/* A curve leaving the box in x ends on the box's edge: the point where
 * the step from prev to cur crosses x = edge, interpolated and corrected
 * onto the system at that x (single shooting: unknowns d and y; multiple
 * shooting: the orbit points and y, on its own system), into T->mid;
 * 0 unless located within EDGE_FTOLS residual tolerances, the step's own
 * acceptance level. */
#define EDGE_FTOLS 10.0
static int edge_point(trace *T, const double *prev, const double *cur,
                      double edge) {
  double t = (edge - UX(T, prev)) / (UX(T, cur) - UX(T, prev)), floor;
  if (!(t >= 0 && t <= 1)) return 0;
  for (size_t i = 0; i < T->N; i++)
    T->mid[i] = prev[i] + t * (cur[i] - prev[i]);
  UX(T, T->mid) = edge;
  int st = T->N == 3
               ? sc_curve_correct_fixed(&T->ss.pb, T->mid, 1, T->acc, &floor)
               : sc_curve_correct_fixed_n(&T->cs.pb, T->mid, T->N - 2, T->acc,
                                          &floor);
  return st == SC_OK && floor <= EDGE_FTOLS * T->acc->newton_ftol &&
         UY(T, T->mid) >= T->set->ylo && UY(T, T->mid) <= T->set->yhi;
}

/* Damped Newton for the start at fixed y on the single-shooting system,
 * unknowns (d, x): the orbits of f^m can sit close to d*, where
 * f' ~ |d - d*|^(-1/2) (docs/derivations.md), and a full step from a guess
 * overshoots; halving the step until the residual decreases brings the
 * guess in, and the branch's own corrector then polishes it.  u holds
 * (d, x, y) in and out. */
static int correct_start(trace *T, double *u, double *floor_out, sc_msg *msg) {
  if (sc_curve_correct_fixed(&T->ss.pb, u, 2, T->acc, floor_out))
    return sc_fail(msg, SC_ENOCONV,
                   "curve: the map fails at the start (%.200s)",
                   sc_msg_what(T->mc.emsg.text));
  return SC_OK; /* the branch corrector decides */
}

/* ---- the borders of the orbit along the curve ------------------------ */

/* The watched borders' values at the point u (trace layout), along the
 * start's code; NaN where one cannot be evaluated. */
static void border_values(trace *T, const double *u, double *bv) {
  double w[3] = {u[0], UX(T, u), UY(T, u)};
  sc_map_value v;
  int rc = sc_forced_eval(&T->fs, w, T->fs.codes, NULL, &v);
  for (size_t j = 0; j < T->fs.nwatch; j++) {
    const sc_border *b = rc ? NULL : sc_forced_find(&T->fs.bl, &T->fs.watch[j]);
    bv[j] = b ? b->value : NAN;
  }
}

/* Locate where the curve meets watched border j: Newton on {f^m(d) = d,
 * (f^m)' = +-1, m_j = 0} in (d, x, y) from w (overwritten), along the
 * start's code with the border's own code for its iterate.  Reported
 * with the border's kind as label, or as "KIND?" with the reason; *found
 * says whether it was.  `pa`, `pb`: m_j at
 * the bracket's ends; `reach`: how far from w the point may lie. */
static int cross_border(trace *T, const double *w, const double *dir3,
                        double *v, int *ok, sc_msg *msg);

static int locate_border_pt(trace *T, size_t j, double *w, double pa,
                            double pb, double reach, int fallback,
                            int *found, const double *dir3, double *next,
                            int *crossed, const double *a3, const double *b3,
                            int *jump) {
  const sc_border bwc = T->fs.watch[j]; /* the watch may be replaced */
  const sc_border *bw = &bwc;
  *crossed = 0;
  if (jump) *jump = 0;
  const char *kl = sc_border_label(bw->kind);
  const char *tn = T->set->type == SC_CURVE_FOLD ? "fold" : "flip";
  char rej[8], note[512];
  snprintf(rej, sizeof rej, "%s?", kl);
  *found = 0;
  sc_forced_sys L;
  sc_msg lm;
  int st = sc_forced_init(&L, T->mc.m, T->set->period, T->set->ix,
                          T->set->iy, T->set->type, T->acc->fd_step, &lm);
  if (st) return st;
  memcpy(L.codes, T->fs.codes, (size_t)T->set->period * sizeof *L.codes);
  sc_forced_use_alt(&L, bw);
  if ((st = sc_forced_watch(&L, bw, 1, &lm))) {
    sc_forced_free(&L);
    return st;
  }
  sc_curve_system cs;
  sc_forced_system(&L, &cs);
  double mid[3] = {w[0], w[1], w[2]};
  sc_curve_cert cert;
  int rc = sc_curve_locate(&cs, 0, w, T->acc, &cert, &lm);
  double dist = fmax(fabs(w[0] - mid[0]),
                     fmax(fabs(w[1] - mid[1]), fabs(w[2] - mid[2])));
  if (rc == SC_OK &&
      !(fabs(cert.psi) <= fmax(SC_SQRT_EPS * fmax(fabs(pa), fabs(pb)),
                               T->acc->newton_ftol) &&
        dist <= reach)) {
    rc = SC_ENOCONV;
    snprintf(lm.text, sizeof lm.text,
             "converged to a point %.3g away (reach %.3g), m = %.3g", dist,
             reach, cert.psi);
  }
  double *u = T->u;
  if (rc == SC_OK) lm.text[0] = '\0';
  if (rc && a3 && b3) {
    /* a border that is not smooth at its zero: bisection along the curve
     * (the point known to the bracket's width); or a border that jumps */
    double m, width;
    int bs = sc_curve_bisect(&cs, 0, a3, b3, pa, pb, T->acc, w, &m, &width);
    if (bs == SC_ENOMEM) {
      sc_forced_free(&L);
      return SC_ENOMEM;
    }
    if (bs == SC_OK) {
      rc = SC_OK;
      cert.psi = m;
      double F[2];
      cert.residual = cs.pb.f(w, F, cs.pb.user) ? NAN
                                                : fmax(fabs(F[0]), fabs(F[1]));
      snprintf(lm.text, sizeof lm.text, "bisection (Newton fails), width %.2g",
               width);
    } else if (bs == SC_EUNDEF) {
      if (jump) *jump = 1;
      char nt[SC_MSG_LEN];
      snprintf(nt, sizeof nt, "%.60s", sc_msg_what(lm.text));
      snprintf(lm.text, sizeof lm.text,
               "the border jumps (not a zero); Newton: %.60s", nt);
    }
  }
  if (rc) {
    sc_forced_free(&L);
    u[0] = mid[0], UX(T, u) = mid[1], UY(T, u) = mid[2];
    if (bw->on_state)
      /* f' may be unbounded on a border in the state (bk2, driver
       * frozen: |d - d*|^(-1/2)), so (f^m)' = +-1 cannot hold there */
      snprintf(note, sizeof note,
               "%s ends next to %s: not located (the multiplier is singular "
               "on this border: %.80s); %.60s",
               tn, kl, sc_msg_what(lm.text), bw->name);
    else
      snprintf(note, sizeof note, "%s meets %s%s: not located: %.90s; %.40s",
               tn, kl,
               fallback ? " (the nearest when the corrector stopped)" : "",
               sc_msg_what(lm.text), bw->name);
    return emit_special(T, rej, u, NAN, cert.residual, note);
  }
  *found = 1;
  sc_forced_free(&L);
  u[0] = w[0], UX(T, u) = w[1], UY(T, u) = w[2];
  sc_curve_jet j2;
  double coef =
      g_at(T, u, &j2) ? NAN : sc_curve_coefficient(T->set->type, &j2);
  char old[SC_ITIN_LEN];
  snprintf(old, sizeof old, "%s", T->itin0);
  char how[SC_MSG_LEN];
  snprintf(how, sizeof how, "%s", sc_msg_what(lm.text));
  if (dir3 && (st = cross_border(T, w, dir3, next, crossed, &lm))) return st;
  if (*crossed)
    snprintf(note, sizeof note,
             "%s meets %s at iterate %d%s%.40s: continued across, itinerary "
             "%.50s -> %.50s; %.50s",
             tn, kl, bw->iterate + 1, how[0] ? ", " : "", how, old, T->itin0,
             bw->name);
  else
    snprintf(note, sizeof note,
             "%s meets %s at iterate %d%s%s%.40s: the curve ends here (%s); "
             "%.50s",
             tn, kl, bw->iterate + 1,
             fallback ? ", found after the corrector stopped" : "",
             how[0] ? ", " : "", how,
             T->set->multiple ? "not continued across with multiple shooting"
             : !dir3          ? "not continued across"
                              : "no such point on the other side",
             bw->name);
  return emit_special(T, kl, u, coef, fmax(cert.residual, fabs(cert.psi)),
                      note);
}

/* Where the curve cannot go on from u (the corrector stopped, or the
 * residual's floor rose above the tolerance): a border past which the
 * orbit cannot be followed (a forced event that does not occur) shows no
 * sign change, so the nearest watched border is located from u. */
static int near_border(trace *T, const double *u, int *found) {
  double dist, w[3] = {u[0], UX(T, u), UY(T, u)};
  long jn = sc_forced_nearest(&T->fs, w, &dist);
  *found = 0;
  if (jn < 0 || !(dist <= SC_CURVE_NEAR_HMAX * T->set->hmax)) return SC_OK;
  int crossed;
  return locate_border_pt(T, (size_t)jn, w, T->bpa[jn], T->bpa[jn],
                          SC_CURVE_LOCATE_HMAX * T->set->hmax, 1, found, NULL, NULL, &crossed,
                          NULL, NULL, NULL);
}

/* The start's itinerary code and the orbit's borders, at the corrected
 * start (d, x, y): the borders are watched along the curve, and single
 * shooting follows the code past a border. */
static int watch_setup(trace *T, const double *start, sc_msg *msg) {
  int st = sc_forced_init(&T->fs, T->mc.m, T->set->period, T->set->ix,
                          T->set->iy, T->set->type, T->acc->fd_step, msg);
  if (st) return st;
  sc_map_value v;
  double w[3] = {start[0], start[1], start[2]};
  if (sc_forced_eval(&T->fs, w, NULL, T->fs.codes, &v)) return SC_OK;
  for (int k = 0; k < T->set->period; k++)
    if (T->fs.codes[k].n == 0) return SC_OK; /* no code to follow */
  size_t nb = T->fs.bl.n;
  if ((st = sc_forced_watch(&T->fs, T->fs.bl.b, nb, msg))) return st;
  T->bpa = calloc(3 * (nb ? nb : 1), sizeof *T->bpa);
  if (!T->bpa) return sc_fail(msg, SC_ENOMEM, "curve: out of memory");
  T->bpb = T->bpa + nb, T->bpc = T->bpb + nb;
  snprintf(T->itin0, sizeof T->itin0, "%s", v.itinerary);
  if (!T->set->multiple) {
    T->mc.fs = &T->fs;
    T->mc.itin0 = T->itin0;
  }
  return SC_OK;
}

/* Most border crossings per direction of a curve: a guard against
 * crossing the same border back and forth. */
#define SC_CURVE_MAX_CROSSINGS 16

/* The watch of the start again (a direction that crossed borders
 * replaced it). */
static int watch_reset(trace *T, const double *start, sc_msg *msg) {
  sc_forced_free(&T->fs);
  free(T->bpa);
  T->bpa = T->bpb = T->bpc = NULL;
  T->mc.fs = NULL;
  T->mc.itin0 = NULL;
  return watch_setup(T, start, msg);
}

/* After the border point w (d, x, y), met going along dir3: does the
 * fold or flip persist on the other side with the orbit's new itinerary?
 * From w one small step (h0) along dir3, the new itinerary's code is
 * taken and the point corrected onto the curve's system at fixed y along
 * it; it persists when that converges within one largest step of w with
 * the natural itinerary the new one (*ok = 1, the start in v).  The watch
 * is then the new itinerary's borders.  Single shooting only. */
static int cross_border(trace *T, const double *w, const double *dir3,
                        double *v, int *ok, sc_msg *msg) {
  *ok = 0;
  if (T->set->multiple) return SC_OK;
  double nt = fmax(fabs(dir3[0]), fmax(fabs(dir3[1]), fabs(dir3[2])));
  if (!(nt > 0)) return SC_OK;
  for (int i = 0; i < 3; i++)
    v[i] = w[i] + T->set->h0 * dir3[i] / nt;
  char old[SC_ITIN_LEN];
  snprintf(old, sizeof old, "%s", T->itin0);
  int st = watch_reset(T, v, msg);
  if (st) return st;
  if (!T->mc.fs || strcmp(old, T->itin0) == 0) return SC_OK;
  double floor;
  if (correct_start(T, v, &floor, msg) != SC_OK ||
      !(floor <= SC_CURVE_FLOOR_FTOLS * T->acc->newton_ftol))
    return SC_OK;
  sc_map_value val;
  if (sc_forced_eval(&T->fs, v, NULL, NULL, &val) ||
      strcmp(val.itinerary, T->itin0) != 0)
    return SC_OK;
  double dist = fmax(fabs(v[0] - w[0]),
                     fmax(fabs(v[1] - w[1]), fabs(v[2] - w[2])));
  /* the new side's curve must start at the border point */
  *ok = dist <= CROSS_START_H0 * T->set->h0;
  return SC_OK;
}

/* One direction of a curve being traced: run() and its steps. */
typedef struct {
  int branch;             /* 0: the first direction, 1: the other */
  sc_cont_problem pb;     /* the system (multiple shooting: sparse) */
  sc_cont_settings cset;  /* its continuation settings */
  sc_branch *b;           /* the pseudo-arclength branch */
  double psi_prev[3];     /* the tests at the last point */
  size_t nw;              /* borders watched */
  double far;             /* farthest distance from the start so far */
  int ncross;             /* borders crossed */
} walk;

/* What a step of run() says about the loop. */
enum { WALK_ON, WALK_NEXT, WALK_STOP };

/* The branch and its first point: the corrected start, emitted (and, in
 * the first direction, taken as the start with its itinerary). */
static int walk_start(trace *T, walk *W, sc_msg *msg) {
  size_t N = T->N;
  int st;
  if (W->branch == 1 && T->bpa && (st = watch_reset(T, T->start3, msg)))
    return st;
  st = sc_branch_alloc(&W->pb, &W->cset, T->acc, &W->b, msg);
  if (st) return st;
  st = sc_branch_set(W->b, T->u0, msg);
  if (st) return st;
  double *prev = T->prev;
  memcpy(prev, sc_branch_point(W->b), N * sizeof *prev);
  sc_curve_jet j;
  if (W->branch == 0) {
    memcpy(T->u0, prev, N * sizeof *prev);
    /* the start's itinerary: the curve follows this one */
    sc_forced_sys *keep = T->mc.fs;
    T->mc.fs = NULL;
    g_at(T, prev, &j);
    T->mc.fs = keep;
    snprintf(T->itin0, sizeof T->itin0, "%s", T->mc.itin);
    if ((st = emit_point(T, prev, 0))) return st;
    if ((st = user_points(T, prev, prev, 1))) return st;
  } else if ((st = emit_point(T, prev, 1))) {
    /* the start again, so that each direction's polyline begins there */
    return st;
  }
  if (T->cs.test(prev, W->psi_prev, T->cs.user))
    return sc_fail(msg, SC_ENOCONV, "curve: test functions fail at the start");
  W->nw = T->fs.nwatch;
  if (W->nw) border_values(T, prev, T->bpa);
  return SC_OK;
}

/* The borders at the new point: the first to change sign along the step
 * (its index, or nw, into *jb; the fraction of the step, 2 for none,
 * into *wb); the values before the step are kept in T->bpc. */
static void step_borders(trace *T, walk *W, size_t *jb, double *wb) {
  size_t nw = W->nw;
  *jb = nw;
  *wb = 2;
  if (!nw) return;
  border_values(T, T->cur, T->bpb);
  for (size_t k = 0; k < nw; k++) {
    double ba = T->bpa[k], bb = T->bpb[k];
    if (((ba > 0 && bb < 0) || (ba < 0 && bb > 0)) && ba / (ba - bb) < *wb)
      *wb = ba / (ba - bb), *jb = k;
  }
  memcpy(T->bpc, T->bpa, nw * sizeof *T->bpa);
  memcpy(T->bpa, T->bpb, nw * sizeof *T->bpa);
}

/* The codimension-two tests that changed sign along the step before the
 * first border (fraction wb), each located. */
static int step_tests(trace *T, walk *W, double wb) {
  double psi[3];
  if (T->cs.test(T->cur, psi, T->cs.user) != 0) return SC_OK;
  int st;
  for (size_t k = 0; k < 3; k++)
    if (((W->psi_prev[k] > 0 && psi[k] < 0) ||
         (W->psi_prev[k] < 0 && psi[k] > 0)) &&
        W->psi_prev[k] / (W->psi_prev[k] - psi[k]) < wb)
      if ((st = locate(T, k, T->prev, T->cur, W->psi_prev[k], psi[k])))
        return st;
  memcpy(W->psi_prev, psi, sizeof psi);
  return SC_OK;
}

/* Across a located border: a new branch from the other side, going on
 * the same way in y, from next (d, x, y); WALK_NEXT, or WALK_STOP where
 * the new side cannot start. */
static int walk_cross(trace *T, walk *W, const double *dir3,
                      const double *next, int *st, sc_msg *msg) {
  size_t N = T->N;
  sc_msg bm;
  W->ncross++;
  sc_branch_free(W->b);
  W->b = NULL;
  W->cset.direction = dir3[2] >= 0 ? 1 : -1;
  double *u = T->mid;
  u[0] = next[0], UX(T, u) = next[1], UY(T, u) = next[2];
  for (size_t k = 1; k + 2 < N; k++) /* multiple: not crossed */
    u[k] = next[0];
  if ((*st = sc_branch_alloc(&W->pb, &W->cset, T->acc, &W->b, msg)))
    return WALK_STOP;
  if (sc_branch_set(W->b, u, &bm)) {
    char why[128];
    snprintf(why, sizeof why, "across the border the start fails: %.90s",
             sc_msg_what(bm.text));
    *st = end_point(T, u, why);
    return WALK_STOP;
  }
  double *prev = T->prev;
  memcpy(prev, sc_branch_point(W->b), N * sizeof *prev);
  if ((*st = emit_point(T, prev, W->branch))) return WALK_STOP;
  if (T->cs.test(prev, W->psi_prev, T->cs.user)) {
    *st = end_point(T, prev, "across the border the tests fail");
    return WALK_STOP;
  }
  W->nw = T->fs.nwatch;
  if (W->nw) border_values(T, prev, T->bpa);
  return WALK_NEXT;
}

/* Every border that changed sign along the step, in the order met (a
 * border may jump rather than cross: its location fails and is
 * reported, and the next one is tried), from the first, jb.  The first
 * located ends the curve, or is crossed (walk_cross()).  WALK_ON where
 * only borders that jump changed sign (the itinerary check still watches
 * the orbit). */
static int step_cross(trace *T, walk *W, size_t jb, int *st, sc_msg *msg) {
  const double *prev = T->prev, *cur = T->cur;
  size_t nw = W->nw;
  double a3[3], b3[3];
  a3[0] = prev[0], a3[1] = UX(T, prev), a3[2] = UY(T, prev);
  b3[0] = cur[0], b3[1] = UX(T, cur), b3[2] = UY(T, cur);
  double span = fmax(fabs(b3[0] - a3[0]),
                     fmax(fabs(b3[1] - a3[1]), fabs(b3[2] - a3[2])));
  /* the point may lie off the chord: where the steps shrank (near d*,
   * the orbit moves fast in d) the bracket is short, so at least one
   * largest step */
  double reach = fmax(SC_CURVE_BRACKET_REACH * span, T->set->hmax);
  int found = 0, crossed = 0, njump = 0, ntried = 0;
  double wlast = -1, dir3[3], next[3];
  for (int i = 0; i < 3; i++)
    dir3[i] = b3[i] - a3[i];
  for (;;) {
    size_t jn = nw;
    double wn = 2;
    for (size_t k = 0; k < nw; k++) {
      double ba = T->bpc[k], bb = T->bpb[k];
      if (((ba > 0 && bb < 0) || (ba < 0 && bb > 0))) {
        double wk = ba / (ba - bb);
        if ((wk > wlast || (wk == wlast && k > jb)) && wk < wn)
          wn = wk, jn = k;
      }
    }
    if (jn == nw) break;
    jb = jn, wlast = wn;
    double w[3];
    for (int i = 0; i < 3; i++)
      w[i] = a3[i] + wn * (b3[i] - a3[i]);
    int jump = 0;
    if ((*st = locate_border_pt(
             T, jn, w, T->bpc[jn], T->bpb[jn], reach, 0, &found,
             W->ncross < SC_CURVE_MAX_CROSSINGS ? dir3 : NULL, next,
             &crossed, a3, b3, &jump)))
      return WALK_STOP;
    if (found) break;
    njump += jump, ntried++;
  }
  if (found && crossed) return walk_cross(T, W, dir3, next, st, msg);
  if (found) return WALK_STOP;
  if (njump < ntried) {
    *st = end_point(T, prev, "borders changed sign, none located (rows "
                             "above)");
    return WALK_STOP;
  }
  return WALK_ON;
}

/* The accepted point cur: whether it still meets its system and keeps
 * its itinerary and the box; then emitted, and the curve's ends (the
 * box in y, max points, closing). */
static int step_accept(trace *T, walk *W, int bs, int *st) {
  const sc_curve_settings *s = T->set;
  double *prev = T->prev, *cur = T->cur;
  sc_curve_jet j;
  /* A point accepted at the corrector's rounding floor with a residual
   * far above the tolerance: next to d* (f'' unbounded,
   * docs/derivations.md) the multiplier's rounding error grows without
   * bound; the curve ends where its points stop meeting their system
   * (SC_CURVE_FLOOR_FTOLS). */
  if (T->cs.pb.f(cur, T->F, T->cs.pb.user) == 0 &&
      norm_inf(T->F, T->cs.pb.n) >
          SC_CURVE_FLOOR_FTOLS * T->acc->newton_ftol) {
    char why[128];
    snprintf(why, sizeof why,
             "the residual's rounding floor (%.3g) exceeds the tolerance "
             "(%.3g): f'' grows without bound here",
             norm_inf(T->F, T->cs.pb.n), T->acc->newton_ftol);
    int found = 0;
    if (W->nw && (*st = near_border(T, prev, &found))) return WALK_STOP;
    if (!found) *st = end_point(T, prev, why);
    return WALK_STOP;
  }
  /* the orbit must keep its itinerary: a change without a border of
   * the orbit changing sign is reported as such */
  if (g_at(T, cur, &j) == 0 && T->mc.itin[0] && strcmp(T->mc.itin, T->itin0)) {
    char why[128];
    snprintf(why, sizeof why, "border: itinerary %.40s -> %.40s", T->itin0,
             T->mc.itin);
    *st = end_point(T, prev, why);
    return WALK_STOP;
  }
  if (UX(T, cur) < s->xlo || UX(T, cur) > s->xhi) {
    double edge = UX(T, cur) < s->xlo ? s->xlo : s->xhi;
    if (edge_point(T, prev, cur, edge)) {
      if ((*st = emit_point(T, T->mid, W->branch))) return WALK_STOP;
      *st = end_point(T, T->mid, "the box's edge in x (located on it)");
    } else {
      *st = end_point(T, prev, "the box's edge in x (the last point "
                               "inside)");
    }
    return WALK_STOP;
  }
  if ((*st = emit_point(T, cur, W->branch))) return WALK_STOP;
  if ((*st = user_points(T, prev, cur, 0))) return WALK_STOP;
  memcpy(prev, cur, T->N * sizeof *prev);
  if (bs == SC_END) {
    *st = end_point(T, cur,
                    UY(T, cur) <= s->ylo || UY(T, cur) >= s->yhi
                        ? "the box's edge in y"
                        : "max-points reached");
    return WALK_STOP;
  }
  /* closed: back within one step of the start after going away */
  double dist = dist_inf(T, cur, T->u0);
  W->far = fmax(W->far, dist);
  if (W->far > SC_CURVE_CLOSE_HMAX * s->hmax &&
      dist < SC_CURVE_CLOSE_STEPS * sc_branch_step_size(W->b)) {
    T->closed = 1;
    *st = end_point(T, cur, "the curve closes on itself");
    return WALK_STOP;
  }
  return WALK_ON;
}

/* One direction from the corrected start: each step's borders and tests,
 * a border crossed or ending the curve, then the point accepted. */
static int run(trace *T, int dir, int branch, sc_msg *msg) {
  const sc_curve_settings *s = T->set;
  walk W = {.branch = branch, .pb = T->cs.pb};
  sc_curve_cont_settings(s, dir, &W.cset);
  /* multiple shooting: the sparse pattern and KLU (about 5 m nonzeros
   * in an (m + 2)^2 bordered matrix) */
  if (s->multiple) {
    int rc = sc_curve_map1d_ms_sparse(&T->msys, &W.pb, msg);
    if (rc) return rc;
    W.cset.linsolve = sc_linsolve_klu;
  }
  int st = walk_start(T, &W, msg);
  while (!st) {
    sc_msg bm;
    int bs = sc_branch_step(W.b, &bm);
    if (bs < 0 && W.nw) {
      int found = 0;
      if ((st = near_border(T, T->prev, &found)) || found) break;
    }
    if (bs < 0) {
      char why[128];
      snprintf(why, sizeof why, "stopped: %.110s", sc_msg_what(bm.text));
      st = end_point(T, T->prev, why);
      break;
    }
    memcpy(T->cur, sc_branch_point(W.b), T->N * sizeof *T->cur);
    size_t jb;
    double wb;
    step_borders(T, &W, &jb, &wb);
    if ((st = step_tests(T, &W, wb))) break;
    if (jb < W.nw) {
      int w = step_cross(T, &W, jb, &st, msg);
      if (w == WALK_STOP) break;
      if (w == WALK_NEXT) continue;
    }
    if (step_accept(T, &W, bs, &st) == WALK_STOP) break;
  }
  sc_branch_free(W.b);
  return st;
}

int sc_curve_trace(sc_map *m, const sc_curve_settings *set, double d0,
                   const sc_curve_output *out, sc_curve_stats *stats,
                   sc_msg *msg) {
  size_t np = sc_map_nparam(m);
  memset(stats, 0, sizeof *stats);
  stats->border_iterate = -1;
  if (set->period < 1 || set->ix < 0 || set->iy < 0 || (size_t)set->ix >= np ||
      (size_t)set->iy >= np || set->ix == set->iy || !(set->h0 > 0) ||
      !(set->hmax >= set->h0) || set->max_points < 1 ||
      !(set->xlo < set->xhi) || !(set->ylo < set->yhi))
    return sc_fail(msg, SC_EINVAL,
                   "sc_curve_trace: bad settings (period %d >= 1, x, y "
                   "distinct parameters, 0 < h0 <= hmax, lo < hi)",
                   set->period);
  if (set->type == SC_CURVE_BORDER)
    return sc_curve_trace_border(m, set, d0, out, stats, msg);
  trace T;
  memset(&T, 0, sizeof T);
  T.set = set;
  T.out = out;
  T.stats = stats;
  T.acc = sc_map_accuracy(m);
  T.mc.m = T.mc1.m = m;
  T.mc.period = set->period;
  T.mc1.period = 1;
  T.mc.ix = T.mc1.ix = set->ix;
  T.mc.iy = T.mc1.iy = set->iy;
  T.sys.fn = jet_fn;
  T.sys.user = &T.mc;
  T.sys.type = set->type;
  T.sys.np = np;
  for (size_t i = 0; i < np; i++)
    T.sys.p[i] = sc_map_get_param(m, i);
  T.sys.ifree[0] = set->ix;
  T.sys.ifree[1] = set->iy;
  double x0 = T.sys.p[set->ix], y0 = T.sys.p[set->iy];
  int st = sc_curve_map1d_system(&T.sys, &T.ss, msg);
  if (st) return st;
  size_t mper = (size_t)set->period;
  T.N = set->multiple ? mper + 2 : 3;
  double *mem = calloc(6 * T.N, sizeof *mem);
  if (!mem) return sc_fail(msg, SC_ENOMEM, "sc_curve_trace: out of memory");
  T.u0 = mem, T.prev = mem + T.N, T.cur = mem + 2 * T.N;
  T.u = mem + 3 * T.N, T.mid = mem + 4 * T.N, T.F = mem + 5 * T.N;
  if (set->multiple) {
    T.msys.fn = jet_fn;
    T.msys.gfn = jet_fn;
    T.msys.user = &T.mc1; /* f */
    T.msys.guser = &T.mc; /* f^m, for the normal-form test */
    T.msys.type = set->type;
    T.msys.period = mper;
    T.msys.np = np;
    memcpy(T.msys.p, T.sys.p, sizeof T.msys.p);
    T.msys.ifree[0] = set->ix;
    T.msys.ifree[1] = set->iy;
    st = sc_curve_ms_work_alloc(mper, &T.msys.work, msg);
    if (st == SC_OK) st = sc_curve_map1d_ms_system(&T.msys, &T.cs, msg);
  } else {
    T.cs = T.ss;
  }
  double floor = HUGE_VAL, start[3] = {d0, x0, y0};
  if (st == SC_OK) st = correct_start(&T, start, &floor, msg);
  if (st == SC_OK) {
    /* the orbit from the corrected single-shooting start */
    T.u0[0] = start[0];
    UX(&T, T.u0) = start[1];
    UY(&T, T.u0) = start[2];
    for (size_t k = 1; set->multiple && k < mper && st == SC_OK; k++) {
      sc_curve_jet j;
      double p[SC_MAP1D_MAXPARAM];
      memcpy(p, T.sys.p, sizeof p);
      p[set->ix] = start[1], p[set->iy] = start[2];
      if (jet_fn(T.u0[k - 1], p, &j, &T.mc1))
        st = sc_fail(msg, SC_ENOCONV,
                     "curve: the map fails along the start "
                     "orbit (%.200s)",
                     sc_msg_what(T.mc1.emsg.text));
      T.u0[k] = j.g;
    }
  }
  /* The residual of f^m's system has a rounding floor that grows with m
   * and with |f'| along the orbit (near d*, f' ~ |d - d*|^(-1/2)), and
   * varies along the curve; a residual tolerance below it can never be
   * met.  Use at least SC_CURVE_FTOL, and 4 times the floor met at the
   * start where that is larger (reported), never beyond 1e-9 (the fast
   * preset's). */
  sc_accuracy acc = *T.acc;
  sc_curve_ftol(&acc, floor);
  stats->ftol = acc.newton_ftol;
  T.acc = &acc;
  memcpy(T.start3, start, sizeof T.start3);
  if (st == SC_OK && sc_map_has_borders(m)) st = watch_setup(&T, start, msg);
  if (st == SC_OK) st = run(&T, +1, 0, msg);
  if (st == SC_OK && !T.closed) st = run(&T, -1, 1, msg);
  stats->closed = T.closed;
  sc_map_set_param(m, (size_t)set->ix, x0, NULL);
  sc_map_set_param(m, (size_t)set->iy, y0, NULL);
  sc_curve_ms_work_free(T.msys.work);
  sc_forced_free(&T.fs);
  free(T.bpa);
  free(mem);
  return st;
}
