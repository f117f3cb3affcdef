/* The quad-precision path of bk2 (src/models/bk2_quad.c): the double path
 * against it on thousands of points across the parameters (both drivers,
 * beta = 1 and not, V = 0), and the quad path against identities of the
 * closed forms that hold exactly (docs/derivations.md): the beta = 1 symmetry
 * f(-d) = -f(d), f(d) = d + 2 (1 - mu) / (1 + alpha) for a lone slip of
 * block 1 with the driver frozen, the energy balance of an iterate with
 * the driver frozen, and its derivatives against quad differences.  The
 * tolerances are justified where they are used; docs/accuracy.md quotes
 * the same figures. */
#include <float.h>
#include <math.h>
#include <quadmath.h>
#include <stdio.h>
#include <string.h>

#include "models/bk2_quad.h"
#include "slipcont/map.h"
#include "test_util.h"

typedef sc_quad Q;

/* Quad's epsilon, 2^-112, without the GNU Q suffix. */
static Q qeps(void) { return __extension__ FLT128_EPSILON; }

/* A deterministic generator (the same points on every platform). */
static unsigned long long rng_state = 0x2385aa17ULL;
static double urand(void) {
  rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(rng_state >> 11) / 9007199254740992.0;
}
static double logu(double lo, double hi) {
  return exp(log(lo) + (log(hi) - log(lo)) * urand());
}

static sc_map *make(double alpha, double beta, double phi, double v, int frozen,
                    int precision) {
  sc_accuracy acc;
  sc_msg msg;
  sc_map *m;
  sc_accuracy_preset(&acc, "default", NULL);
  acc.precision = precision;
  if (sc_map_alloc("bk2", &acc, &m, &msg)) return NULL;
  if (sc_map_set_param_by_name(m, "alpha", alpha, &msg) ||
      sc_map_set_param_by_name(m, "beta", beta, &msg) ||
      sc_map_set_param_by_name(m, "phi", phi, &msg) ||
      sc_map_set_param_by_name(m, "v", v, &msg) ||
      sc_map_set_option(m, "driver", frozen ? "frozen" : "moving", &msg)) {
    printf("make: %s\n", msg.text);
    sc_map_free(m);
    return NULL;
  }
  return m;
}

/* Distance to the nearest border of the itinerary (grazing, crossing,
 * d*), from the quad evaluation. */
static double border_dist(double alpha, double beta, double phi, double v,
                          int frozen, double d) {
  sc_bk2q_params p = {alpha, beta, phi, v, frozen, 256};
  sc_bk2q_value q;
  if (sc_bk2q_eval(&p, d, 0, &q, NULL)) return HUGE_VAL;
  return fmin(fmin(q.graze_margin, fabs(q.gsp_gap)), q.dstar_dist);
}

/* Double against quad on n random points.  The double path's error on f
 * is rounding carried through the onset state Y = 1 + alpha d and the
 * flows, so it is measured in units of eps (1 + alpha)(1 + |d|); on f' in
 * units of eps (1 + alpha)(1 + |f'|) times the amplification 1/|g'| of
 * the event times, which is what makes f' large. */
static void double_vs_quad(int n) {
  double worst_f = 0, worst_df = 0, worst_dp = 0;
  int compared = 0, itin_near = 0, itin_far = 0, undef = 0, status_far = 0;
  for (int i = 0; i < n; i++) {
    double alpha = logu(0.3, 30);
    double beta = i % 3 == 0 ? 1 : logu(0.2, 5);
    double phi = i % 4 == 0 ? 1.25 : 1.05 + 2 * urand();
    double v = i % 10 == 0 ? 0 : 0.1 * urand();
    int frozen = i % 2;
    double d = -0.5 + urand();
    sc_map *md = make(alpha, beta, phi, v, frozen, SC_PRECISION_DOUBLE);
    sc_map *mq = make(alpha, beta, phi, v, frozen, SC_PRECISION_QUAD);
    if (!tu_true(md && mq, "map allocation")) goto next;
    sc_map_value rd, rq;
    sc_msg m1, m2;
    unsigned fl = SC_EVAL_ITINERARY | SC_EVAL_DERIV;
    int s1 = sc_map_eval(md, d, fl, &rd, &m1);
    int s2 = sc_map_eval(mq, d, fl, &rq, &m2);
    if (s1 || s2) {
      if (s1 == s2)
        undef++;
      else {
        status_far++;
        printf("status differs: double %d quad %d at alpha=%.17g beta=%.17g "
               "phi=%.17g v=%.17g %s d=%.17g\n",
               s1, s2, alpha, beta, phi, v, frozen ? "frozen" : "moving", d);
      }
      goto next;
    }
    if (strcmp(rd.itinerary, rq.itinerary) != 0) {
      /* Allowed only within rounding of a border, where the side taken
       * is decided by the last bits. */
      if (border_dist(alpha, beta, phi, v, frozen, d) <= 1e-9)
        itin_near++;
      else {
        itin_far++;
        printf("itinerary differs far from a border: %s vs %s at "
               "alpha=%.17g beta=%.17g phi=%.17g v=%.17g %s d=%.17g\n",
               rd.itinerary, rq.itinerary, alpha, beta, phi, v,
               frozen ? "frozen" : "moving", d);
      }
      goto next;
    }
    compared++;
    double scale = DBL_EPSILON * (1 + alpha) * (1 + fabs(d));
    worst_f = fmax(worst_f, fabs(rd.f - rq.f) / scale);
    /* derivatives: a relative error, compared with the event-time
     * amplification the border distance stands for */
    double amp = 1 + 1 / sqrt(fmax(border_dist(alpha, beta, phi, v, frozen, d), DBL_EPSILON));
    double sd = DBL_EPSILON * (1 + alpha) * (1 + fabs(rq.dfdd)) * amp;
    worst_df = fmax(worst_df, fabs(rd.dfdd - rq.dfdd) / sd);
    for (int k = 0; k < 4; k++) {
      double sp = DBL_EPSILON * (1 + alpha) * (1 + fabs(rq.dfdp[k])) * amp;
      worst_dp = fmax(worst_dp, fabs(rd.dfdp[k] - rq.dfdp[k]) / sp);
    }
  next:
    sc_map_free(md);
    sc_map_free(mq);
  }
  printf("double vs quad: %d points, %d compared, %d undefined in both, %d "
         "itineraries differ within 1e-9 of a border\n",
         n, compared, undef, itin_near);
  tu_true(compared >= n * 9 / 10,
          "at least 90%% of the points compared "
          "(%d of %d)",
          compared, n);
  tu_int("status differs (one path undefined, the other not)", status_far, 0);
  tu_int("itineraries that differ away from a border", itin_far, 0);
  tu_true(itin_near <= n / 100,
          "itineraries differing next to a border: "
          "%d (at most 1%%)",
          itin_near);
  /* Measured worst (docs/accuracy.md): ~1 for f, ~10 for f'.  The bound
   * 16 leaves room for other libm's sin/cos (1 ulp each, a few per
   * iterate); a wrong closed form would be off by 1e10 units or more. */
  tu_close("double vs quad: max |df| / (eps (1+alpha)(1+|d|))", worst_f, 0, 16);
  tu_close("double vs quad: max f' error in units", worst_df, 0, 64);
  tu_close("double vs quad: max df/dp error in units", worst_dp, 0, 64);
}

static sc_bk2q_params qparams(double alpha, double beta, double phi, double v,
                              int frozen) {
  sc_bk2q_params p = {alpha, beta, phi, v, frozen, 256};
  return p;
}

/* beta = 1: swapping the blocks maps d to -d, so f(-d) = -f(d) and
 * f'(-d) = f'(d), exactly; in quad to the event-time tolerance. */
static void symmetry(void) {
  Q worst = 0, worst_d = 0;
  int n = 0;
  for (int i = 0; i < 400; i++) {
    double alpha = logu(0.5, 20), v = i % 5 ? 0.05 * urand() : 0;
    double phi = 1.1 + urand();
    sc_bk2q_params p = qparams(alpha, 1, phi, v, i % 2);
    Q d = (Q)(0.4 * urand()) + (Q)1e-3;
    sc_bk2q_value a, b;
    if (sc_bk2q_eval(&p, d, SC_BK2Q_NDIR, &a, NULL) ||
        sc_bk2q_eval(&p, -d, SC_BK2Q_NDIR, &b, NULL))
      continue;
    if (strcmp(a.itinerary, b.itinerary) != 0 && a.graze_margin > 1e-20) {
      /* the mirror image of "1-12-2" is "2-12-1": compare the lengths */
      tu_int("mirrored itineraries have the same length",
             (long)strlen(a.itinerary), (long)strlen(b.itinerary));
    }
    n++;
    worst = fmaxq(worst, fabsq(a.f + b.f));
    worst_d = fmaxq(worst_d, fabsq(a.df[0] - b.df[0]) / (1 + fabsq(a.df[0])));
  }
  tu_true(n >= 350, "symmetry: %d of 400 points defined", n);
  /* 1e4 eps_quad ~ 2e-30: the event times are exact to 64 eps (1 + t) and
   * the states to a few eps times their size (<= 1 + 2 alpha |d| ~ 20). */
  tu_close("beta = 1: max |f(d) + f(-d)| / eps_quad", (double)(worst / qeps()),
           0, 1e4);
  tu_close("beta = 1: max |f'(d) - f'(-d)| / (1+|f'|) / eps_quad",
           (double)(worst_d / qeps()), 0, 1e6);
}

/* Driver frozen, block 1 slips alone from a GSP: Y1 oscillates about
 * P = (mu + alpha Y2)/(1 + alpha) and re-sticks after half a period at
 * 2 P - Y1(0); since S1(0) = 1, f(d) = d + 2 (1 - mu)/(1 + alpha),
 * block 2 likewise: f(d) = d - 2 beta (1 - mu)/(1 + alpha). */
static void lone_slips(void) {
  int n1 = 0, n2 = 0;
  Q worst = 0;
  for (int i = 0; i < 400; i++) {
    double alpha = logu(0.5, 20), beta = logu(0.3, 4), phi = 1.1 + urand();
    sc_bk2q_params p = qparams(alpha, beta, phi, 0.05, 1);
    Q mu = 1 / (Q)phi, d = (Q)(-0.6 + 1.2 * urand());
    sc_bk2q_value r;
    if (sc_bk2q_eval(&p, d, 0, &r, NULL)) continue;
    Q c;
    if (strcmp(r.itinerary, "1") == 0)
      c = 2 * (1 - mu) / (1 + (Q)alpha), n1++;
    else if (strcmp(r.itinerary, "2") == 0)
      c = -2 * (Q)beta * (1 - mu) / (1 + (Q)alpha), n2++;
    else
      continue;
    worst = fmaxq(worst, fabsq(r.f - d - c) / (1 + (Q)alpha * fabsq(d)));
  }
  tu_true(n1 >= 50 && n2 >= 50, "lone slips sampled: block 1 %d, block 2 %d",
          n1, n2);
  /* rounding of the onset Y1 = 1 + alpha d and of the flow: ~100 eps */
  tu_close("frozen lone slip: max |f - d - c| / (1 + alpha |d|) / eps_quad",
           (double)(worst / qeps()), 0, 1e3);
}

/* Driver frozen: H = (U1^2 + U2^2)/2 + (Y1^2 + Y2^2)/2 + alpha (Y1 -
 * Y2)^2 / 2 - mu Y1 - beta mu Y2 is constant along the motion (a slipping
 * block's friction mu T_i is constant, a stuck block does not move), and
 * U1 = U2 = 0 at both GSPs: H(onset) = H(next GSP) on every itinerary. */
static void energy(void) {
  int n = 0, multi = 0;
  Q worst = 0;
  for (int i = 0; i < 400; i++) {
    double alpha = logu(0.5, 20), beta = logu(0.3, 4), phi = 1.1 + urand();
    sc_bk2q_params p = qparams(alpha, beta, phi, 0, 1);
    Q a = alpha, b = beta, mu = 1 / (Q)phi;
    Q d = (Q)(-0.6 + 1.2 * urand());
    Q dstar = (b - 1) / (1 + 2 * a), y1, y2;
    if (d < dstar)
      y1 = 1 + a * d, y2 = y1 + d;
    else
      y2 = b - a * d, y1 = y2 - d;
    sc_bk2q_value r;
    if (sc_bk2q_eval(&p, d, 0, &r, NULL)) continue;
    Q h0 = (y1 * y1 + y2 * y2 + a * (y1 - y2) * (y1 - y2)) / 2 - mu * y1 -
           b * mu * y2;
    Q h1 = (r.y1 * r.y1 + r.y2 * r.y2 + a * (r.y1 - r.y2) * (r.y1 - r.y2)) / 2 -
           mu * r.y1 - b * mu * r.y2;
    Q size = 1 + (1 + a) * (y1 * y1 + y2 * y2);
    worst = fmaxq(worst, fabsq(h1 - h0) / size);
    n++;
    multi += r.nphases > 1;
  }
  tu_true(n >= 350 && multi >= 50,
          "energy: %d points, %d with several "
          "phases",
          n, multi);
  tu_close("frozen: max |H(end) - H(onset)| / size / eps_quad",
           (double)(worst / qeps()), 0, 1e4);
}

/* The quad derivatives against central differences in quad: with step
 * h = 1e-12 the truncation error is ~ f''' h^2 ~ 1e-24 and rounding
 * ~ eps_quad / h ~ 1e-22, so a relative agreement of 1e-15 holds wherever
 * the itinerary is the same at d - h and d + h. */
static void derivatives(void) {
  Q worst = 0;
  int n = 0;
  const Q h = (Q)1e-12;
  for (int i = 0; i < 200; i++) {
    double alpha = logu(0.5, 20), beta = i % 3 ? logu(0.3, 4) : 1;
    double phi = 1.1 + urand(), v = 0.05 * urand();
    int frozen = i % 2;
    double dd = -0.4 + 0.8 * urand();
    double par[4] = {alpha, beta, phi, v};
    sc_bk2q_params p = qparams(alpha, beta, phi, v, frozen);
    sc_bk2q_value r, lo, hi;
    if (sc_bk2q_eval(&p, dd, SC_BK2Q_NDIR, &r, NULL)) continue;
    for (int k = 0; k < SC_BK2Q_NDIR; k++) {
      if (k == 4 && frozen) continue; /* f does not depend on V */
      sc_bk2q_params pl = p, ph = p;
      Q dl = dd, dh = dd, step = h;
      if (k == 0)
        dl -= h, dh += h;
      else {
        Q *ql = k == 1   ? &pl.alpha
                : k == 2 ? &pl.beta
                : k == 3 ? &pl.phi
                         : &pl.v;
        Q *qh = k == 1   ? &ph.alpha
                : k == 2 ? &ph.beta
                : k == 3 ? &ph.phi
                         : &ph.v;
        step = h * (1 + (Q)par[k - 1]);
        *ql -= step, *qh += step;
      }
      if (sc_bk2q_eval(&pl, dl, 0, &lo, NULL) ||
          sc_bk2q_eval(&ph, dh, 0, &hi, NULL) ||
          strcmp(lo.itinerary, r.itinerary) ||
          strcmp(hi.itinerary, r.itinerary))
        continue;
      Q fd = (hi.f - lo.f) / (2 * step);
      worst = fmaxq(worst, fabsq(fd - r.df[k]) / (1 + fabsq(r.df[k])));
      n++;
    }
  }
  tu_true(n >= 600, "derivative checks: %d", n);
  tu_close("quad derivatives vs quad central differences (relative)",
           (double)worst, 0, 1e-15);
}

/* Each preset held to its promise (docs/accuracy.md, "Promises") against
 * the quad path, on random points away from borders (the itineraries
 * agree; within rounding of a border either side may be taken), with
 * S = 1 + beta + (1 + alpha)|d| the size of the onset state, g = 1 + |f'|
 * the gain, n the number of slip phases, and r = min(1, |d - d*|, graze
 * margin, threshold gap) the distance to the nearest border:
 *   exact flows:     |df| <= 64 eps S g n,    |df'| <= E' S g / r,
 *   numerical flows: |df| <= 10 tol S g n,    |df'| <= 1e3 tol S g / r,
 * eps = DBL_EPSILON, tol = the preset's ode tolerance, and E' = 1024 eps
 * for default and precise, 1e-8 for fast (its events stop at a relative
 * 1e-9, and f' takes the event time's error at first order). */
typedef struct {
  const char *preset, *flows;
  double f_unit, df_unit; /* the bounds' constants, as above */
} promise;

static void presets(int n) {
  const promise pr[] = {
      {"fast", "exact", 64 * DBL_EPSILON, 1e-8},
      {"default", "exact", 64 * DBL_EPSILON, 1024 * DBL_EPSILON},
      {"precise", "exact", 64 * DBL_EPSILON, 1024 * DBL_EPSILON},
      {"fast", "numerical", 10 * 1e-7, 1e3 * 1e-7},
      {"default", "numerical", 10 * 1e-10, 1e3 * 1e-10},
      {"precise", "numerical", 10 * 1e-13, 1e3 * 1e-13},
  };
  for (size_t k = 0; k < sizeof pr / sizeof pr[0]; k++) {
    double wf = 0, wdf = 0;
    int compared = 0;
    rng_state = 0x51ed2385ULL; /* the same sample for every preset */
    for (int i = 0; i < n; i++) {
      double alpha = logu(0.3, 30);
      double beta = i % 3 == 0 ? 1 : logu(0.2, 5);
      double phi = i % 4 == 0 ? 1.25 : 1.05 + 2 * urand();
      double v = i % 10 == 0 ? 0 : 0.1 * urand();
      int frozen = i % 2;
      double d = -0.5 + urand();
      sc_map *mq = make(alpha, beta, phi, v, frozen, SC_PRECISION_QUAD);
      sc_map *md = make(alpha, beta, phi, v, frozen, SC_PRECISION_DOUBLE);
      sc_accuracy acc;
      sc_accuracy_preset(&acc, pr[k].preset, NULL);
      sc_map_value rd, rq;
      if (md && mq && !sc_map_set_accuracy(md, &acc, NULL) &&
          !sc_map_set_option(md, "flows", pr[k].flows, NULL) &&
          !sc_map_eval(mq, d, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &rq, NULL) &&
          !sc_map_eval(md, d, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &rd, NULL) &&
          strcmp(rd.itinerary, rq.itinerary) == 0 && isfinite(rq.dfdd)) {
        double S = 1 + beta + (1 + alpha) * fabs(d), g = 1 + fabs(rq.dfdd);
        double r = fmin(1, border_dist(alpha, beta, phi, v, frozen, d));
        wf = fmax(wf, fabs(rd.f - rq.f) / (S * g * rq.nphases));
        wdf = fmax(wdf, fabs(rd.dfdd - rq.dfdd) * r / (S * g));
        compared++;
      }
      sc_map_free(md);
      sc_map_free(mq);
    }
    char what[160];
    tu_true(compared >= n * 9 / 10, "%s, %s flows: %d of %d points compared",
            pr[k].preset, pr[k].flows, compared, n);
    snprintf(what, sizeof what, "%s, %s flows: max |df| / (S g n) within %g",
             pr[k].preset, pr[k].flows, pr[k].f_unit);
    tu_close(what, wf, 0, pr[k].f_unit);
    snprintf(what, sizeof what, "%s, %s flows: max |df'| r / (S g) within %g",
             pr[k].preset, pr[k].flows, pr[k].df_unit);
    tu_close(what, wdf, 0, pr[k].df_unit);
  }
}

/* The switch: scene key, accuracy check, refusal with numerical flows. */
static void selection(void) {
  sc_accuracy acc;
  sc_msg msg;
  sc_accuracy_preset(&acc, "precise", NULL);
  tu_int("presets use double", acc.precision, SC_PRECISION_DOUBLE);
  tu_int("precision = quad accepted",
         sc_accuracy_set(&acc, "precision", "quad", &msg), SC_OK);
  tu_int("precision = quad set", acc.precision, SC_PRECISION_QUAD);
  tu_int("precision = single refused",
         sc_accuracy_set(&acc, "precision", "single", &msg), SC_EINVAL);
  tu_true(strstr(msg.text, "double|quad") != NULL,
          "message names the valid "
          "values: %s",
          msg.text);
  acc.precision = 7;
  tu_int("precision = 7 refused by the check", sc_accuracy_check(&acc, &msg),
         SC_EINVAL);
  sc_map *m = make(3, 1, 1.25, 0.025, 0, SC_PRECISION_QUAD);
  tu_true(m != NULL, "quad map");
  if (!m) return;
  tu_int("quad with numerical flows refused",
         sc_map_set_option(m, "flows", "numerical", &msg), SC_EINVAL);
  tu_true(strstr(msg.text, "quad") != NULL, "message: %s", msg.text);
  /* the period-2 orbit of fig 5.4 (examples/api.c): f(f(d0)) = d0 */
  sc_map_value r;
  double d0 = -0.015333775386934;
  tu_int("quad eval", sc_map_iterate(m, d0, 2, SC_EVAL_DERIV, &r, &msg), SC_OK);
  tu_close("period-2 orbit of fig 5.4 in quad", r.f, d0, 1e-13);
  sc_map_free(m);
}

int main(void) {
  selection();
  double_vs_quad(3000);
  symmetry();
  lone_slips();
  energy();
  derivatives();
  presets(300);
  return tu_finish();
}
