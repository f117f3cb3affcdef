/* Orbits forced along an itinerary code as curve systems in (d, x, y):
 * the fold / flip systems past a border (for locating where a curve
 * meets one) and the border curves {f^m(d) = d, m_k = 0} with their LP,
 * PD and border crossings (docs/curves.md). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/border_list.h"
#include "analysis/curve_impl.h"

void sc_curve_ftol(sc_accuracy *acc, double floor) {
  acc->newton_ftol = fmax(acc->newton_ftol, SC_CURVE_FTOL);
  if (floor > acc->newton_ftol && floor <= SC_CURVE_FLOOR_MAX) {
    acc->newton_ftol = SC_CURVE_FLOOR_MARGIN * floor;
    acc->newton_atol = fmax(acc->newton_atol, SC_CURVE_FLOOR_MARGIN * floor);
  }
}

void sc_curve_cont_settings(const sc_curve_settings *s, int dir,
                            sc_cont_settings *c) {
  sc_cont_settings_default(c);
  c->h0 = s->h0;
  c->hmax = s->hmax;
  c->hmin = fmin(c->hmin, s->h0);
  c->pmin = s->ylo;
  c->pmax = s->yhi;
  c->direction = dir;
  c->max_points = s->max_points;
}

int sc_forced_init(sc_forced_sys *s, sc_map *m, int period, int ix, int iy,
                   sc_curve_type type, double fd_step, sc_msg *msg) {
  memset(s, 0, sizeof *s);
  s->m = m, s->period = period, s->ix = ix, s->iy = iy, s->type = type;
  s->fd_step = fd_step;
  s->codes = calloc((size_t)period, sizeof *s->codes);
  s->bl.cap = 16;
  s->bl.b = calloc(s->bl.cap, sizeof *s->bl.b);
  if (!s->codes || !s->bl.b) {
    sc_forced_free(s);
    return sc_fail(msg, SC_ENOMEM, "curve: out of memory");
  }
  return SC_OK;
}

void sc_forced_free(sc_forced_sys *s) {
  free(s->codes);
  free(s->watch);
  free(s->labels);
  free(s->bl.b);
  memset(s, 0, sizeof *s);
}

int sc_forced_watch(sc_forced_sys *s, const sc_border *w, size_t n,
                    sc_msg *msg) {
  size_t off = s->type == SC_CURVE_BORDER ? 2 : 0;
  sc_border *nw = n ? malloc(n * sizeof *nw) : NULL;
  const char **nl = malloc((n + off) * sizeof *nl);
  if ((n && !nw) || !nl) {
    free(nw);
    free(nl);
    return sc_fail(msg, SC_ENOMEM, "curve: out of memory");
  }
  if (n) memcpy(nw, w, n * sizeof *nw);
  if (off) nl[0] = "LP", nl[1] = "PD";
  for (size_t j = 0; j < n; j++)
    nl[off + j] = sc_border_label(w[j].kind);
  free(s->watch);
  free(s->labels);
  s->watch = nw, s->labels = nl, s->nwatch = n;
  return SC_OK;
}

void sc_forced_use_alt(sc_forced_sys *s, const sc_border *b) {
  if (b->alt.n > 0 && b->iterate >= 0 && b->iterate < s->period)
    s->codes[b->iterate] = b->alt;
}

int sc_forced_eval(sc_forced_sys *s, const double *u,
                   const sc_itin_code *force, sc_itin_code *codes_out,
                   sc_map_value *v) {
  if (sc_map_set_param(s->m, (size_t)s->ix, u[1], &s->emsg) ||
      sc_map_set_param(s->m, (size_t)s->iy, u[2], &s->emsg))
    return 1; /* outside the parameters' range: shrink the step */
  int st = sc_border_list_iterate(s->m, u[0], s->period,
                                  SC_EVAL_DERIV | SC_EVAL_ITINERARY, force,
                                  codes_out, &s->bl, v, &s->emsg);
  if (st == SC_ENOMEM) return -1;
  if (st) return 1;
  return isfinite(v->f) && isfinite(v->dfdd) ? 0 : 1;
}

const sc_border *sc_forced_find(const sc_border_list *l,
                                const sc_border *like) {
  return sc_border_list_find(l, like);
}

static double sign_of(sc_curve_type t) { return t == SC_CURVE_FOLD ? 1 : -1; }

/* A border in the state itself (the key, on_state, rotated to iterate
 * 0: m = +-(d - d_on(p))): the map may be singular next to it (bk2, driver
 * frozen: f' ~ |d - d*|^(-1/2)), the orbit started on it is not.  So f^m
 * is evaluated at d_on(p) exactly, and the system is
 *   F = (f^m(d_on(p)) - d_on(p), d - d_on(p)),
 * whose first row does not depend on d: its Jacobian is
 *   (0, g_p + (g_d - 1) d_on_p) for p = x, y; the second (1, -d_on_p).
 * d_on(p) and its derivatives come from the border of one iterate. */
static int on_state_eval(sc_forced_sys *s, const double *u, sc_map_value *v,
                         double *don, double *dx, double *dy) {
  if (sc_map_set_param(s->m, (size_t)s->ix, u[1], &s->emsg) ||
      sc_map_set_param(s->m, (size_t)s->iy, u[2], &s->emsg))
    return 1;
  sc_map_value v1;
  int st = sc_border_list_iterate(s->m, u[0], 1, SC_EVAL_DERIV, s->codes,
                                  NULL, &s->bl, &v1, &s->emsg);
  if (st) return st == SC_ENOMEM ? -1 : 1;
  *don = NAN;
  for (size_t i = 0; i < s->bl.n && i < s->bl.cap; i++)
    if (s->bl.b[i].on_state && s->bl.b[i].iterate == 0)
      *don = s->bl.b[i].d_on, *dx = s->bl.b[i].d_on_dp[s->ix],
      *dy = s->bl.b[i].d_on_dp[s->iy];
  if (!isfinite(*don)) return 1;
  double w[3] = {*don, u[1], u[2]};
  return sc_forced_eval(s, w, s->codes, NULL, v);
}

static int f_cb(const double *u, double *F, void *user) {
  sc_forced_sys *s = user;
  sc_map_value v;
  int rc;
  if (s->type == SC_CURVE_BORDER && s->key.on_state) {
    double don, dx, dy;
    if ((rc = on_state_eval(s, u, &v, &don, &dx, &dy))) return rc;
    F[0] = v.f - don;
    F[1] = u[0] - don;
    return isfinite(F[0]) && isfinite(F[1]) ? 0 : 1;
  }
  rc = sc_forced_eval(s, u, s->codes, NULL, &v);
  if (rc) return rc;
  F[0] = v.f - u[0];
  if (s->type == SC_CURVE_BORDER) {
    const sc_border *b = sc_forced_find(&s->bl, &s->key);
    if (!b) return 1;
    F[1] = b->value;
  } else {
    F[1] = v.dfdd - sign_of(s->type);
  }
  return isfinite(F[0]) && isfinite(F[1]) ? 0 : 1;
}

static int jac_cb(const double *u, double *J, void *user) {
  sc_forced_sys *s = user;
  sc_map_value v;
  int rc;
  if (s->type == SC_CURVE_BORDER && s->key.on_state) {
    double don, dx, dy;
    if ((rc = on_state_eval(s, u, &v, &don, &dx, &dy))) return rc;
    J[0] = 0;
    J[1] = v.dfdp[s->ix] + (v.dfdd - 1) * dx;
    J[2] = v.dfdp[s->iy] + (v.dfdd - 1) * dy;
    J[3] = 1, J[4] = -dx, J[5] = -dy;
    for (int i = 0; i < 6; i++)
      if (!isfinite(J[i])) return 1;
    return 0;
  }
  rc = sc_forced_eval(s, u, s->codes, NULL, &v);
  if (rc) return rc;
  J[0] = v.dfdd - 1, J[1] = v.dfdp[s->ix], J[2] = v.dfdp[s->iy];
  if (s->type == SC_CURVE_BORDER) {
    const sc_border *b = sc_forced_find(&s->bl, &s->key);
    if (!b) return 1;
    J[3] = b->dd, J[4] = b->dp[s->ix], J[5] = b->dp[s->iy];
  } else {
    /* d(g_d)/du_j by central differences of the exact g_d */
    for (int j = 0; j < 3; j++) {
      double w[3] = {u[0], u[1], u[2]}, h = s->fd_step * (1 + fabs(u[j]));
      double gd[2];
      for (int k = 0; k < 2; k++) {
        w[j] = u[j] + (k ? -h : h);
        if ((rc = sc_forced_eval(s, w, s->codes, NULL, &v))) return rc;
        gd[k] = v.dfdd;
      }
      J[3 + j] = (gd[0] - gd[1]) / (2 * h);
    }
  }
  for (int i = 0; i < 6; i++)
    if (!isfinite(J[i])) return 1;
  return 0;
}

static int test_cb(const double *u, double *psi, void *user) {
  sc_forced_sys *s = user;
  sc_map_value v;
  int rc;
  if (s->type == SC_CURVE_BORDER && s->key.on_state) {
    double don, dx, dy;
    rc = on_state_eval(s, u, &v, &don, &dx, &dy);
  } else {
    rc = sc_forced_eval(s, u, s->codes, NULL, &v);
  }
  if (rc) return rc;
  size_t off = 0;
  if (s->type == SC_CURVE_BORDER) {
    psi[0] = v.dfdd - 1, psi[1] = v.dfdd + 1;
    off = 2;
  }
  for (size_t j = 0; j < s->nwatch; j++) {
    const sc_border *b = sc_forced_find(&s->bl, &s->watch[j]);
    psi[off + j] = b ? b->value : NAN;
  }
  return 0;
}

void sc_forced_system(sc_forced_sys *s, sc_curve_system *cs) {
  memset(cs, 0, sizeof *cs);
  cs->pb.n = 2;
  cs->pb.f = f_cb;
  cs->pb.jac = jac_cb;
  cs->pb.user = s;
  cs->ntest = s->nwatch + (s->type == SC_CURVE_BORDER ? 2 : 0);
  cs->test = test_cb;
  cs->labels = s->labels;
  cs->user = s;
}

/* ------------------------------------------------------------------ */
/* Border curves                                                        */

typedef struct {
  sc_map *m;
  const sc_curve_settings *set;
  const sc_curve_output *out;
  sc_curve_stats *stats;
  sc_forced_sys fs;
  sc_curve_system cs;
  sc_accuracy acc;
  double u0[3];
  double *psa, *psb; /* ntest each */
  int closed;
} btrace;

static double norm2inf(const double *F) { return fmax(fabs(F[0]), fabs(F[1])); }

static double dist3(const double *a, const double *b) {
  return fmax(fabs(a[0] - b[0]), fmax(fabs(a[1] - b[1]), fabs(a[2] - b[2])));
}

/* The orbit point reported for u: u[0], or for a border in the state the
 * point on it, d_on(p) exactly (u[0] is within rounding of it, and a
 * rounding to the wrong side starts another itinerary). */
static double bpoint_d(btrace *B, const double *u) {
  double don, dx, dy;
  sc_map_value v;
  if (B->fs.key.on_state && on_state_eval(&B->fs, u, &v, &don, &dx, &dy) == 0)
    return don;
  return u[0];
}

static int bemit(btrace *B, const char *label, const double *u, double res,
                 const char *note) {
  sc_curve_special s;
  memset(&s, 0, sizeof s);
  snprintf(s.label, sizeof s.label, "%s", label);
  s.d = bpoint_d(B, u), s.x = u[1], s.y = u[2];
  double F[2];
  s.coefficient = f_cb(u, F, &B->fs) ? NAN : F[1];
  s.residual = res;
  snprintf(s.note, sizeof s.note, "%.255s", note);
  if (strcmp(label, "EP") && strcmp(label, "UZ") && !strchr(label, '?'))
    B->stats->nspecial++; /* codimension two: not ends, user points */
  if (B->out && B->out->special && B->out->special(B->out->ctx, &s))
    return SC_ECALLBACK;
  return SC_OK;
}

static int bpoint(btrace *B, const double *u, int branch) {
  double F[2];
  sc_map_value v;
  if (f_cb(u, F, &B->fs) || sc_forced_eval(&B->fs, u, B->fs.codes, NULL, &v))
    return SC_OK; /* cannot happen at an accepted point */
  B->stats->max_residual = fmax(B->stats->max_residual, norm2inf(F));
  double d = bpoint_d(B, u);
  if (B->fs.key.on_state && sc_forced_eval(&B->fs, (double[3]){d, u[1], u[2]},
                                           B->fs.codes, NULL, &v))
    return SC_OK;
  sc_curve_point pt = {u[1], u[2], d, v.dfdd, F[1], branch, v.itinerary};
  B->stats->npoints++;
  if (B->out && B->out->point && B->out->point(B->out->ctx, &pt))
    return SC_ECALLBACK;
  return SC_OK;
}

/* Locate the zero of test k between a and b; 1 in *ends if the curve
 * ends there (a crossing of another border). */
static int blocate(btrace *B, size_t k, const double *a, const double *b,
                   double pa, double pb, int *ends) {
  double w = pa / (pa - pb), u[3], mid[3];
  for (int i = 0; i < 3; i++)
    mid[i] = u[i] = a[i] + w * (b[i] - a[i]);
  sc_curve_cert cert;
  sc_msg msg;
  char note[256], rej[8];
  const char *label = B->cs.labels[k];
  const char *bn = sc_border_label(B->fs.key.kind);
  snprintf(rej, sizeof rej, "%s?", label);
  *ends = k >= 2;
  int st = sc_curve_locate(&B->cs, k, u, &B->acc, &cert, &msg);
  if (st && k >= 2) {
    /* a border that is not smooth at its zero: bisection along the
     * curve, the point known to the bracket's width */
    double m, width;
    int bs = sc_curve_bisect(&B->cs, k, a, b, pa, pb, &B->acc, u, &m,
                             &width);
    if (bs == SC_ENOMEM) return sc_fail(&msg, SC_ENOMEM, "out of memory");
    if (bs == SC_OK) {
      double F[2];
      double res = f_cb(u, F, &B->fs) ? NAN : norm2inf(F);
      snprintf(note, sizeof note,
               "%s curve meets %s (%.40s, it. %d; bisection: Newton fails, "
               "m = %.2g, width %.2g): ends",
               bn, label, B->fs.watch[k - 2].name,
               B->fs.watch[k - 2].iterate + 1, m, width);
      return bemit(B, label, u, fmax(res, fabs(m)), note);
    }
    /* a border that jumps is no crossing: the curve goes on */
    if (bs == SC_EUNDEF) *ends = 0;
    snprintf(note, sizeof note, "not located: %.50s; bisection: %s",
             sc_msg_what(msg.text),
             bs == SC_EUNDEF ? "the border jumps (not a zero), the curve goes on"
                             : "failed, the curve ends here");
    return bemit(B, rej, mid, cert.residual, note);
  }
  if (st) {
    snprintf(note, sizeof note, "not located: %.100s", sc_msg_what(msg.text));
    return bemit(B, rej, mid, cert.residual, note);
  }
  if (!(fabs(cert.psi) <= SC_SQRT_EPS * fmax(fabs(pa), fabs(pb))) ||
      dist3(u, mid) > SC_CURVE_BRACKET_REACH * dist3(a, b)) {
    snprintf(note, sizeof note,
             "rejected: the sign change is not a zero (test %.3g, ends %.3g, "
             "%.3g)",
             cert.psi, pa, pb);
    return bemit(B, rej, mid, cert.residual, note);
  }
  double res = fmax(cert.residual, k >= 2 ? fabs(cert.psi) : 0);
  if (k == 0)
    snprintf(note, sizeof note, "fold of the orbit on the %s border", bn);
  else if (k == 1)
    snprintf(note, sizeof note, "flip of the orbit on the %s border", bn);
  else
    snprintf(note, sizeof note,
             "%s border curve meets %s (%.50s, iterate %d): ends here", bn,
             label, B->fs.watch[k - 2].name, B->fs.watch[k - 2].iterate + 1);
  return bemit(B, label, u, res, note);
}

/* Halvings of a damped Newton step at most: a step of 2^-30 (1e-9) of
 * the full one that still does not decrease the residual means the
 * residual is at its rounding floor. */
#define DAMP_HALVINGS 30

int sc_curve_correct_fixed(const sc_cont_problem *pb, double *u, int fix,
                           const sc_accuracy *acc, double *floor_out) {
  int c1 = fix == 2 ? 1 : 2; /* the other parameter's column */
  double F[2], J[6], Ft[2], ut[3];
  *floor_out = HUGE_VAL;
  if (pb->f(u, F, pb->user)) return SC_ECALLBACK;
  for (int it = 0; it < acc->newton_maxiter; it++) {
    double r = fmax(fabs(F[0]), fabs(F[1]));
    *floor_out = r;
    if (r <= acc->newton_ftol) return SC_OK;
    if (pb->jac(u, J, pb->user)) break;
    /* columns d (0) and c1 of the 2 x 3 Jacobian */
    double a = J[0], b = J[c1], c = J[3], e = J[3 + c1], det = a * e - b * c;
    if (det == 0 || !isfinite(det)) break;
    double dd = -(e * F[0] - b * F[1]) / det;
    double dx = -(a * F[1] - c * F[0]) / det;
    double lam = 1;
    int ok = 0;
    for (int h = 0; h < DAMP_HALVINGS && !ok; h++, lam *= 0.5) {
      ut[0] = u[0] + lam * dd, ut[c1] = u[c1] + lam * dx, ut[fix] = u[fix];
      ok = pb->f(ut, Ft, pb->user) == 0 && fmax(fabs(Ft[0]), fabs(Ft[1])) < r;
    }
    if (!ok) break; /* no step decreases the residual: its rounding floor */
    memcpy(u, ut, sizeof ut);
    memcpy(F, Ft, sizeof Ft);
  }
  return SC_OK;
}

static double norm_max(const double *F, size_t n) {
  double r = 0;
  for (size_t i = 0; i < n; i++) r = fmax(r, fabs(F[i]));
  return r;
}

/* One damped Newton step of sc_curve_correct_fixed_n(): the n x n
 * matrix of pb's Jacobian without column `fix` factored by `ls`, the
 * step halved until the residual (r at u) decreases; u and F updated.
 * 1 when a step was taken. */
static int fixed_n_step(const sc_cont_problem *pb, sc_linsolve *ls, double *u,
                        double *F, size_t fix, double r, double *work) {
  size_t n = pb->n, N = n + 1;
  double *J = work, *A = J + n * N, *dx = A + n * n, *ut = dx + n,
         *Ft = ut + N;
  if (pb->jac(u, J, pb->user)) return 0;
  for (size_t j = 0, c = 0; j < N; j++) {
    if (j == fix) continue;
    for (size_t i = 0; i < n; i++) A[i + n * c] = J[i * N + j];
    c++;
  }
  for (size_t i = 0; i < n; i++) dx[i] = -F[i];
  if (sc_linsolve_factor(ls, A, NULL) || sc_linsolve_solve(ls, dx, NULL))
    return 0;
  double lam = 1;
  for (int h = 0; h < DAMP_HALVINGS; h++, lam *= 0.5) {
    for (size_t j = 0, c = 0; j < N; j++)
      ut[j] = j == fix ? u[j] : u[j] + lam * dx[c++];
    if (pb->f(ut, Ft, pb->user) || !(norm_max(Ft, n) < r)) continue;
    memcpy(u, ut, N * sizeof *u);
    memcpy(F, Ft, n * sizeof *F);
    return 1;
  }
  return 0; /* no step decreases the residual: its rounding floor */
}

int sc_curve_correct_fixed_n(const sc_cont_problem *pb, double *u, size_t fix,
                             const sc_accuracy *acc, double *floor_out) {
  size_t n = pb->n, N = n + 1;
  *floor_out = HUGE_VAL;
  if (pb->jac_colptr || fix >= N) return SC_EINVAL;
  double *work = malloc((n * N + n * n + n + N + n + n) * sizeof *work);
  sc_linsolve *ls = NULL;
  if (!work || sc_linsolve_alloc_full(sc_linsolve_dense, (int)n, &ls, NULL)) {
    free(work);
    return SC_ENOMEM;
  }
  double *F = work + n * N + n * n + n + N + n;
  int st = pb->f(u, F, pb->user) ? SC_ECALLBACK : SC_OK;
  for (int it = 0; st == SC_OK && it < acc->newton_maxiter; it++) {
    double r = norm_max(F, n);
    *floor_out = r;
    if (r <= acc->newton_ftol || !fixed_n_step(pb, ls, u, F, fix, r, work))
      break;
    *floor_out = norm_max(F, n);
  }
  sc_linsolve_free(ls);
  free(work);
  return st;
}

int sc_curve_mark(const sc_cont_problem *pb, const sc_accuracy *acc,
                  const char *xname, double c, const double *a,
                  const double *b, int start, double *u3, double *res,
                  char *note, size_t len) {
  double xa = a[1], xb = b[1];
  if (!((xa - c) * (xb - c) < 0 || xb == c || (start && xa == c))) return -1;
  double w = xb == xa ? (xa == c ? 0 : 1) : (c - xa) / (xb - xa);
  double guess[3] = {a[0] + w * (b[0] - a[0]), c, a[2] + w * (b[2] - a[2])};
  memcpy(u3, guess, sizeof guess);
  /* down to the residual's rounding floor (no step decreases it): a user
   * point is a reference value, not a step of the trace */
  sc_accuracy polish = *acc;
  polish.newton_ftol = 0;
  double floor, F[2];
  int st = sc_curve_correct_fixed(pb, u3, 1, &polish, &floor);
  *res = pb->f(u3, F, pb->user) ? NAN : norm2inf(F);
  /* located: the corrector's own acceptance, SC_CURVE_FLOOR_FTOLS
   * residual tolerances (as the trace's points) */
  int ok = st == SC_OK && u3[1] == c &&
           *res <= SC_CURVE_FLOOR_FTOLS * acc->newton_ftol;
  if (ok)
    snprintf(note, len, "user point: %s = %.17g, located by Newton with %s "
                        "fixed",
             xname, c, xname);
  else {
    snprintf(note, len,
             "user point NOT LOCATED at %s = %.17g (%s; residual %.3g): "
             "interpolated between curve points",
             xname, c, st ? sc_strerror(st) : "residual above tolerance",
             *res);
    memcpy(u3, guess, sizeof guess);
  }
  return ok;
}

/* A border that is not smooth at its zero (a square root: its derivative
 * grows without bound there) keeps |m| ~ sqrt(bracket) at the end of a
 * bisection, ~1e-7 of its size for a bracket at rounding; a jump keeps its
 * size.  Below this fraction of the values at the ends it is a zero. */
#define SC_BISECT_ZERO 1e-3

int sc_curve_bisect(const sc_curve_system *cs, size_t k, const double *a,
                    const double *b, double pa, double pb,
                    const sc_accuracy *acc, double *u, double *m,
                    double *width) {
  double lo[3], hi[3], psi_lo = pa;
  memcpy(lo, a, sizeof lo);
  memcpy(hi, b, sizeof hi);
  int fix = fabs(b[1] - a[1]) >= fabs(b[2] - a[2]) ? 1 : 2;
  double *psi = malloc((cs->ntest ? cs->ntest : 1) * sizeof *psi);
  if (!psi) return SC_ENOMEM;
  int st = SC_ENOCONV;
  *m = pa;
  memcpy(u, a, 3 * sizeof *u);
  for (int it = 0; it < SC_CURVE_BISECTIONS; it++) {
    *width = fabs(hi[fix] - lo[fix]);
    if (sc_test_delta(*width, lo[fix], acc->newton_atol, acc->newton_rtol) ==
        SC_OK) {
      st = SC_OK;
      break;
    }
    double w[3], floor;
    for (int i = 0; i < 3; i++)
      w[i] = 0.5 * (lo[i] + hi[i]);
    if (sc_curve_correct_fixed(&cs->pb, w, fix, acc, &floor) ||
        !(floor <= SC_CURVE_FLOOR_FTOLS * acc->newton_ftol) || cs->test(w, psi, cs->user) ||
        !isfinite(psi[k]))
      break;
    if ((psi[k] > 0) == (psi_lo > 0))
      memcpy(lo, w, sizeof lo), psi_lo = psi[k];
    else
      memcpy(hi, w, sizeof hi);
    if (fabs(psi[k]) < fabs(*m)) *m = psi[k], memcpy(u, w, 3 * sizeof *u);
  }
  free(psi);
  if (st == SC_OK && !(fabs(*m) <= SC_BISECT_ZERO * fmax(fabs(pa), fabs(pb))))
    st = SC_EUNDEF; /* a jump, not a zero */
  return st;
}

/* The watched border nearest to u (|m_j| over its gradient's size), or
 * -1; its distance estimate in *dist. */
long sc_forced_nearest(sc_forced_sys *s, const double *u, double *dist) {
  sc_map_value v;
  long best = -1;
  *dist = HUGE_VAL;
  if (sc_forced_eval(s, u, s->codes, NULL, &v)) return -1;
  for (size_t j = 0; j < s->nwatch; j++) {
    const sc_border *b = sc_forced_find(&s->bl, &s->watch[j]);
    if (!b) continue;
    double g = fmax(fabs(b->dd), fmax(fabs(b->dp[s->ix]), fabs(b->dp[s->iy])));
    double e = fabs(b->value) / g;
    if (g > 0 && e < *dist) *dist = e, best = (long)j;
  }
  return best;
}

/* After the corrector stopped at u: the nearest watched border located
 * from u (the fallback: a border past which the forced orbit cannot be
 * evaluated shows no sign change).  1 if reported. */
static int bfallback(btrace *B, const double *u, int *st) {
  double dist, w[3] = {u[0], u[1], u[2]};
  long j = sc_forced_nearest(&B->fs, u, &dist);
  if (j < 0 || !(dist <= SC_CURVE_NEAR_HMAX * B->set->hmax)) return 0;
  size_t k = 2 + (size_t)j;
  sc_curve_cert cert;
  sc_msg msg;
  char note[256];
  int rc = sc_curve_locate(&B->cs, k, w, &B->acc, &cert, &msg);
  if (rc == SC_OK && dist3(w, u) > SC_CURVE_LOCATE_HMAX * B->set->hmax) {
    rc = SC_ENOCONV;
    snprintf(msg.text, sizeof msg.text, "converged %.3g away",
             dist3(w, u));
  }
  if (rc) {
    char rej[8];
    snprintf(rej, sizeof rej, "%s?", B->cs.labels[k]);
    snprintf(note, sizeof note,
             "meets %s (the nearest when the corrector stopped): not "
             "located: %.80s; %.30s",
             B->cs.labels[k], sc_msg_what(msg.text), B->fs.watch[j].name);
    *st = bemit(B, rej, u, NAN, note);
    return 0;
  }
  snprintf(note, sizeof note,
           "%s curve meets %s (%.30s, iterate %d; found after the corrector "
           "stopped): ends",
           sc_border_label(B->fs.key.kind), B->cs.labels[k],
           B->fs.watch[j].name, B->fs.watch[j].iterate + 1);
  *st = bemit(B, B->cs.labels[k], w, fmax(cert.residual, fabs(cert.psi)),
              note);
  return 1;
}

/* The user points passed on the step from a to b (sc_curve_mark()). */
static int buser_points(btrace *B, const double *a, const double *b,
                        int start) {
  const sc_curve_settings *s = B->set;
  for (size_t i = 0; i < s->nmarks; i++) {
    double u3[3], res;
    char note[200];
    int ok = sc_curve_mark(&B->cs.pb, &B->acc,
                           sc_map_type(B->m)->params[s->ix].name, s->marks[i],
                           a, b, start, u3, &res, note, sizeof note);
    if (ok < 0) continue;
    int st = bemit(B, ok ? "UZ" : "UZ?", u3, res, note);
    if (st) return st;
  }
  return SC_OK;
}

static int brun(btrace *B, int dir, int branch, sc_msg *msg) {
  const sc_curve_settings *s = B->set;
  sc_cont_settings cset;
  sc_curve_cont_settings(s, dir, &cset);
  sc_branch *b;
  int st = sc_branch_alloc(&B->cs.pb, &cset, &B->acc, &b, msg);
  if (st) return st;
  if ((st = sc_branch_set(b, B->u0, msg))) {
    sc_branch_free(b);
    return st;
  }
  double prev[3], cur[3];
  size_t nt = B->cs.ntest;
  memcpy(prev, sc_branch_point(b), sizeof prev);
  if (branch == 0) memcpy(B->u0, prev, sizeof prev);
  if ((st = bpoint(B, prev, branch))) goto done;
  if (branch == 0 && (st = buser_points(B, prev, prev, 1))) goto done;
  if (B->cs.test(prev, B->psa, B->cs.user)) {
    st = sc_fail(msg, SC_ENOCONV, "curve: test functions fail at the start");
    goto done;
  }
  double far = 0;
  for (;;) {
    sc_msg bm;
    int bs = sc_branch_step(b, &bm);
    if (bs < 0 && bfallback(B, prev, &st)) break;
    if (st) goto done;
    if (bs < 0) {
      char why[128];
      if (strstr(bm.text, "callback failed") && B->fs.emsg.text[0])
        snprintf(why, sizeof why, "stopped: the forced orbit fails: %.90s",
                 sc_msg_what(B->fs.emsg.text));
      else
        snprintf(why, sizeof why, "stopped: %.110s", sc_msg_what(bm.text));
      st = bemit(B, "EP", prev, NAN, why);
      break;
    }
    memcpy(cur, sc_branch_point(b), sizeof cur);
    int ends = 0;
    if (B->cs.test(cur, B->psb, B->cs.user) == 0) {
      /* the tests in the order they are met along the step */
      for (;;) {
        size_t kmin = nt;
        double wmin = 2;
        for (size_t k = 0; k < nt; k++) {
          double pa = B->psa[k], pb = B->psb[k];
          if ((pa > 0 && pb < 0) || (pa < 0 && pb > 0)) {
            double w = pa / (pa - pb);
            if (w < wmin) wmin = w, kmin = k;
          }
        }
        if (kmin == nt) break;
        if ((st = blocate(B, kmin, prev, cur, B->psa[kmin], B->psb[kmin],
                          &ends)))
          goto done;
        B->psa[kmin] = B->psb[kmin]; /* done with this one */
        if (ends) break;
      }
      memcpy(B->psa, B->psb, nt * sizeof *B->psa);
    }
    if (ends) break;
    /* accepted at the corrector's rounding floor far above the tolerance
     * (next to d*, where f' is unbounded): the curve ends where its
     * points stop meeting their system, as fold and flip curves do */
    double F[2];
    if (f_cb(cur, F, &B->fs) == 0 && norm2inf(F) > SC_CURVE_FLOOR_FTOLS * B->acc.newton_ftol) {
      if (bfallback(B, prev, &st)) break;
      if (st) goto done;
      char why[128];
      snprintf(why, sizeof why,
               "the residual's rounding floor (%.3g) exceeds the tolerance "
               "(%.3g)",
               norm2inf(F), B->acc.newton_ftol);
      st = bemit(B, "EP", prev, NAN, why);
      break;
    }
    if (cur[1] < s->xlo || cur[1] > s->xhi) {
      /* located on the edge: the step's crossing of it, corrected onto
       * the system at that x (unknowns d and y) */
      double edge = cur[1] < s->xlo ? s->xlo : s->xhi, w[3], fl;
      double t = (edge - prev[1]) / (cur[1] - prev[1]);
      for (int i = 0; i < 3; i++) w[i] = prev[i] + t * (cur[i] - prev[i]);
      w[1] = edge;
      if (sc_curve_correct_fixed(&B->cs.pb, w, 1, &B->acc, &fl) == SC_OK &&
          fl <= 10 * B->acc.newton_ftol && w[2] >= s->ylo && w[2] <= s->yhi) {
        if ((st = bpoint(B, w, branch))) goto done;
        st = bemit(B, "EP", w, NAN, "the box's edge in x (located on it)");
      } else {
        st = bemit(B, "EP", prev, NAN,
                   "the box's edge in x (the last point inside)");
      }
      break;
    }
    if ((st = bpoint(B, cur, branch))) goto done;
    if ((st = buser_points(B, prev, cur, 0))) goto done;
    memcpy(prev, cur, sizeof prev);
    if (bs == SC_END) {
      st = bemit(B, "EP", cur, NAN,
                 cur[2] <= s->ylo || cur[2] >= s->yhi ? "the box's edge in y"
                                                      : "max-points reached");
      break;
    }
    double dist = dist3(cur, B->u0);
    far = fmax(far, dist);
    if (far > SC_CURVE_CLOSE_HMAX * s->hmax &&
        dist < SC_CURVE_CLOSE_STEPS * sc_branch_step_size(b)) {
      B->closed = 1;
      st = bemit(B, "EP", cur, NAN, "the curve closes on itself");
      break;
    }
  }
done:
  sc_branch_free(b);
  return st;
}

/* Newton for the periodic orbit at fixed parameters (natural itinerary),
 * damped: a guess d0 of an orbit point made good enough for the border
 * system.  Leaves *d unchanged if it does not converge. */
static void orbit_at(sc_map *m, int period, const sc_accuracy *acc,
                     double *d) {
  double x = *d;
  for (int it = 0; it < acc->newton_maxiter; it++) {
    sc_map_value v;
    if (sc_map_iterate(m, x, period, SC_EVAL_DERIV, &v, NULL)) return;
    double F = v.f - x, J = v.dfdd - 1;
    if (fabs(F) <= acc->newton_ftol) {
      *d = x;
      return;
    }
    if (!(J != 0) || !isfinite(J)) return;
    x -= F / J;
  }
}

/* Border names equal, ',' and ';' alike (a CSV field has ';'). */
static int same_name(const char *a, const char *c) {
  for (;; a++, c++) {
    char x = *a == ',' ? ';' : *a, y = *c == ',' ? ';' : *c;
    if (x != y) return 0;
    if (!x) return 1;
  }
}

/* The start d is tried, then nudged by NUDGE_ULPS * NUDGE_GROWTH^k ulps
 * either way, k < NUDGES (up to about 1e-9 relative): a located border
 * point lies on the border to rounding, and the natural map there may
 * take either side of it (past a grazing the event fires); a nudge of
 * that size is far below the corrector's tolerance. */
#define NUDGE_ULPS 1.0
#define NUDGE_GROWTH 4.0
#define NUDGES 13

/* The start of a curve on the border named set->border_name: the codes
 * (into B->fs.codes) of the natural orbit at u[0], or at the nearest
 * nudge of it, that has that border, first at iterate 0 (a branch row's
 * d is the point where its border is met), else at any iterate; the
 * border into *key.  u[0] is kept. */
static int named_start(btrace *B, const double *u, sc_border *key,
                       sc_msg *msg) {
  const sc_curve_settings *set = B->set;
  double ulp = DBL_EPSILON * (1 + fabs(u[0]));
  sc_itin_code *codes = B->fs.codes;
  int fails = 0;
  for (int any = 0; any < 2; any++)
    for (int k = 0; k <= 2 * NUDGES; k++) {
      double w[3] = {u[0], u[1], u[2]};
      if (k > 0)
        w[0] += (k % 2 ? 1 : -1) * NUDGE_ULPS * ulp *
                pow(NUDGE_GROWTH, (k - 1) / 2);
      sc_map_value v;
      if (sc_forced_eval(&B->fs, w, NULL, codes, &v)) {
        fails++;
        continue;
      }
      const sc_border *best = NULL;
      for (size_t i = 0; i < B->fs.bl.n && i < B->fs.bl.cap; i++) {
        const sc_border *x = &B->fs.bl.b[i];
        if (x->kind == set->border && (any || x->iterate == 0) &&
            same_name(x->name, set->border_name) &&
            (!best || fabs(x->value) < fabs(best->value)))
          best = x;
      }
      if (best) {
        *key = *best;
        return SC_OK;
      }
    }
  if (fails == 2 * (2 * NUDGES + 1))
    return sc_fail(msg, SC_ENOCONV,
                   "curve: the map fails at the start (%.200s)",
                   sc_msg_what(B->fs.emsg.text));
  return sc_fail(msg, SC_EINVAL,
                 "curve: the period-%d orbit through d = %.17g has no %s "
                 "border '%.64s' on either side of d (valid: a start row "
                 "of that border)",
                 set->period, u[0], sc_border_label(set->border),
                 set->border_name);
}

/* Damped Newton in (d, x) at fixed y on the border system: converged
 * when at its rounding floor within the fast preset's reach
 * (SC_CURVE_FLOOR_MAX, as sc_curve_ftol()). */
static int bcorrect(btrace *B, double *u, double *floor_out) {
  if (sc_curve_correct_fixed(&B->cs.pb, u, 2, &B->acc, floor_out))
    return SC_ENOCONV;
  return *floor_out <= SC_CURVE_FLOOR_MAX ? SC_OK : SC_ENOCONV;
}

/* The start of a border curve: the orbit through d0 (polished unless a
 * border is named), its codes, and the border followed (the named one,
 * or the nearest of the kind), into B->fs.key; the orbit rotated to
 * start on a border in the state.  u: (d, x0, y0) of the start. */
static int bstart(btrace *B, double d0, double x0, double y0, double *u,
                  sc_msg *msg) {
  sc_map *m = B->m;
  const sc_curve_settings *set = B->set;
  sc_curve_stats *stats = B->stats;
  int st;
  const char *kl = sc_border_label(set->border);
  /* the orbit at the start, its codes and its border: the named one on
   * the side of d0 where the orbit has it, or the nearest of the kind */
  double d = d0;
  if (!set->border_name[0]) orbit_at(m, set->period, &B->acc, &d);
  u[0] = d, u[1] = x0, u[2] = y0;
  sc_map_value v;
  sc_border keyb;
  const sc_border *key = NULL;
  if (set->border_name[0]) {
    if ((st = named_start(B, u, &keyb, msg))) return st;
    key = &keyb;
  } else if (sc_forced_eval(&B->fs, u, NULL, B->fs.codes, &v)) {
    st = sc_fail(msg, SC_ENOCONV, "curve: the map fails at the start (%.200s)",
                 sc_msg_what(B->fs.emsg.text));
    return st;
  }
  for (int k = 0; k < set->period; k++)
    if (B->fs.codes[k].n == 0) {
      st = sc_fail(msg, SC_EINVAL,
                   "curve: iterate %d of the start has no itinerary code "
                   "(too many phases to force)",
                   k + 1);
      return st;
    }
  for (size_t i = 0; !set->border_name[0] && i < B->fs.bl.n; i++)
    if (B->fs.bl.b[i].kind == set->border &&
        (!key || fabs(B->fs.bl.b[i].value) < fabs(key->value)))
      key = &B->fs.bl.b[i];
  if (!key) {
    st = sc_fail(msg, SC_EINVAL,
                 "curve: the period-%d orbit through d = %.17g has no %s "
                 "border (valid: a start on an orbit with one, e.g. a %s row "
                 "of a branch task's points.csv)",
                 set->period, d, kl, kl);
    return st;
  }
  B->fs.key = *key;
  if (key->on_state && key->iterate > 0) {
    /* the orbit from the iterate on the border: codes rotated, d its
     * point there */
    int k = key->iterate, per = set->period;
    sc_itin_code *rot = malloc((size_t)per * sizeof *rot);
    if (!rot) {
      st = sc_fail(msg, SC_ENOMEM, "curve: out of memory");
      return st;
    }
    for (int i = 0; i < per; i++)
      rot[i] = B->fs.codes[(i + k) % per];
    memcpy(B->fs.codes, rot, (size_t)per * sizeof *rot);
    free(rot);
    for (int i = 0; i < k; i++) {
      sc_map_value vi;
      if (sc_map_eval(m, u[0], SC_EVAL_VALUE, &vi, NULL)) break;
      u[0] = vi.f;
    }
    B->fs.key.iterate = 0;
  }
  stats->border_iterate = key->iterate;
  snprintf(stats->border, sizeof stats->border, "%s", key->name);
  B->fs.emsg.text[0] = '\0';
  sc_forced_use_alt(&B->fs, key);
  return SC_OK;
}

/* Every other border of the start's orbit watched, the system made
 * again with them, and the tests' storage. */
static int bwatch(btrace *B, const double *u, sc_msg *msg) {
  sc_map_value v;
  int st;
  /* every other border of the orbit is watched */
  if (sc_forced_eval(&B->fs, u, B->fs.codes, NULL, &v))
    return sc_fail(msg, SC_ENOCONV, "curve: the map fails at the start");
  size_t nb = B->fs.bl.n, nw = 0;
  sc_border *w = malloc((nb ? nb : 1) * sizeof *w);
  if (!w) {
    st = sc_fail(msg, SC_ENOMEM, "curve: out of memory");
    return st;
  }
  for (size_t i = 0; i < nb; i++) {
    const sc_border *bi = &B->fs.bl.b[i];
    if (!(bi->iterate == B->fs.key.iterate && bi->kind == B->fs.key.kind &&
          strcmp(bi->name, B->fs.key.name) == 0))
      w[nw++] = *bi;
  }
  st = sc_forced_watch(&B->fs, w, nw, msg);
  free(w);
  if (st) return st;
  sc_forced_system(&B->fs, &B->cs);
  B->psa = calloc(2 * B->cs.ntest, sizeof *B->psa);
  if (!B->psa) {
    st = sc_fail(msg, SC_ENOMEM, "curve: out of memory");
    return st;
  }
  B->psb = B->psa + B->cs.ntest;
  return SC_OK;
}

int sc_curve_trace_border(sc_map *m, const sc_curve_settings *set, double d0,
                          const sc_curve_output *out, sc_curve_stats *stats,
                          sc_msg *msg) {
  if (!sc_map_has_borders(m))
    return sc_fail(msg, SC_EINVAL,
                   "curve: model %s declares no borders (valid: type = fold "
                   "or flip)",
                   sc_map_type(m)->name);
  if ((int)set->border < 0 || (int)set->border >= SC_BORDER_NKINDS)
    return sc_fail(msg, SC_EINVAL, "curve: border kind %d (valid: 0..%d)",
                   (int)set->border, SC_BORDER_NKINDS - 1);
  btrace B;
  memset(&B, 0, sizeof B);
  B.m = m, B.set = set, B.out = out, B.stats = stats;
  B.acc = *sc_map_accuracy(m);
  double x0 = sc_map_get_param(m, (size_t)set->ix);
  double y0 = sc_map_get_param(m, (size_t)set->iy);
  int st = sc_forced_init(&B.fs, m, set->period, set->ix, set->iy,
                          SC_CURVE_BORDER, B.acc.fd_step, msg);
  if (st) return st;
  double u[3], floor = HUGE_VAL;
  const char *kl = sc_border_label(set->border);
  if ((st = bstart(&B, d0, x0, y0, u, msg))) goto done;
  sc_forced_system(&B.fs, &B.cs); /* again once the watch is known */
  st = bcorrect(&B, u, &floor);
  if (st) {
    st = sc_fail(msg, SC_ENOCONV,
                 "curve: the start could not be corrected onto the %s border "
                 "(%.60s) at %s = %.17g (residual %.3g)",
                 kl, B.fs.key.name, sc_map_type(m)->params[set->iy].name, y0,
                 floor);
    goto done;
  }
  sc_curve_ftol(&B.acc, floor);
  stats->ftol = B.acc.newton_ftol;
  if ((st = bwatch(&B, u, msg))) goto done;
  memcpy(B.u0, u, sizeof u);
  st = brun(&B, +1, 0, msg);
  if (st == SC_OK && !B.closed) st = brun(&B, -1, 1, msg);
  stats->closed = B.closed;
done:
  sc_map_set_param(m, (size_t)set->ix, x0, NULL);
  sc_map_set_param(m, (size_t)set->iy, y0, NULL);
  free(B.psa);
  sc_forced_free(&B.fs);
  return st;
}
