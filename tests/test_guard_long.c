/* The certified first-root search for long guards
 * (sc_guard_long_first_root(), hybrid.h): roots in closed form, a start
 * on zero skipped, a touch found and a near miss passed, a guard of five
 * incommensurate frequencies against a dense scan, and the refusals. */
#include <float.h>
#include <math.h>

#include "slipcont/hybrid.h"
#include "test_util.h"

#define PI 3.14159265358979323846

/* Simple roots come out within a few ulps of their guard's rounding over
 * the slope (~1e-16 here); a touch only to sqrt(rounding / g'') ~ 1e-8. */
static const double ROOT_TOL = 1e-14;
static const double TOUCH_TOL = 1e-6;

static sc_root_long search(double c0, double c1, int n, const double *w,
                           const double *a, const double *b, double tmax,
                           int skip) {
  sc_guard_long g = {c0, c1, n, w, a, b};
  sc_root_long r;
  int st = sc_guard_long_first_root(&g, tmax, skip, &r);
  tu_int("search status", st, SC_OK);
  return r;
}

static void closed_forms(void) {
  double w1[1] = {1}, a0[1] = {0}, b1[1] = {1}, bm[1] = {-1}, a1[1] = {1};
  /* -1 + 0.5 t: t = 2 */
  sc_root_long r = search(-1, 0.5, 0, NULL, NULL, NULL, 10, 0);
  tu_close("linear guard: root", r.t, 2, ROOT_TOL);
  /* sin t - 0.5: pi / 6 */
  r = search(-0.5, 0, 1, w1, a0, b1, 10, 0);
  tu_close("sin t - 1/2: root pi/6", r.t, PI / 6, ROOT_TOL);
  tu_close("sin t - 1/2: slope cos(pi/6)", r.slope, sqrt(3) / 2, ROOT_TOL);
  /* -sin t starts on zero and falls: the root at 0 is skipped, pi next */
  r = search(0, 0, 1, w1, a0, bm, 10, 1);
  tu_close("-sin t from zero: root pi", r.t, PI, ROOT_TOL);
  /* without skip, a start on zero that falls is no root either */
  r = search(0, 0, 1, w1, a0, bm, 10, 0);
  tu_close("-sin t, no skip: root pi", r.t, PI, ROOT_TOL);
  /* sin t starts on zero and rises: a root at 0 unless skipped */
  r = search(0, 0, 1, w1, a0, b1, 10, 0);
  tu_true(r.found && r.t == 0, "sin t: root at 0 (t = %g)", r.t);
  /* cos t - 1 touches zero at 2 pi (and starts on it with g' = 0 > g'') */
  r = search(-1, 0, 1, w1, a1, a0, 10, 1);
  tu_true(r.found && r.tangent, "cos t - 1: a touch found (found %d, "
          "tangent %d)", r.found, r.tangent);
  tu_close("cos t - 1: the touch at 2 pi", r.t, 2 * PI, TOUCH_TOL);
  /* 1e-10 below: a near miss, far above rounding */
  r = search(-1 - 1e-10, 0, 1, w1, a1, a0, 10, 1);
  tu_true(!r.found, "cos t - 1 - 1e-10: no root (found at %.17g)", r.t);
  /* 0.5 + sin t starts above zero, past its event: the root at 0 */
  r = search(0.5, 0, 1, w1, a0, b1, 10, 0);
  tu_true(r.found && r.t == 0, "0.5 + sin t: root at 0 (t = %g)", r.t);
  /* -2 + 0.1 t + cos 3t - 1: beyond tmax */
  double w3[1] = {3};
  r = search(-2, 0.1, 1, w3, a1, a0, 5, 0);
  tu_true(!r.found && r.t == 5, "no root up to tmax = 5");
}

/* g at t, directly. */
static double g_at(double c0, double c1, int n, const double *w,
                   const double *a, const double *b, double t) {
  double v = c0 + c1 * t;
  for (int k = 0; k < n; k++) v += a[k] * cos(w[k] * t) + b[k] * sin(w[k] * t);
  return v;
}

/* Five incommensurate frequencies: the first root against a scan at
 * steps of 1e-4 (far below the spacing of the guard's roots, ~0.1) and
 * bisection of the first sign change. */
static void against_scan(void) {
  const double w[5] = {1, sqrt(2), sqrt(3), sqrt(5), sqrt(7)};
  const double a[5] = {0.21, -0.13, 0.08, 0.11, -0.05};
  const double b[5] = {-0.17, 0.09, -0.12, 0.04, 0.1};
  /* g(0) = c0 + 0.22 < 0 for every c0 below */
  for (int k = 0; k < 6; k++) {
    double c0 = -0.45 + 0.04 * k, c1 = 0.002 * k;
    double h = 1e-4, t = 0, lo = -1, hi = -1;
    for (; t < 40; t += h)
      if (g_at(c0, c1, 5, w, a, b, t) < 0 && g_at(c0, c1, 5, w, a, b, t + h) >= 0) {
        lo = t, hi = t + h;
        break;
      }
    for (int it = 0; hi > 0 && it < 100; it++) {
      double mid = 0.5 * (lo + hi);
      if (g_at(c0, c1, 5, w, a, b, mid) >= 0) hi = mid;
      else lo = mid;
    }
    sc_root_long r = search(c0, c1, 5, w, a, b, 40, 0);
    if (hi < 0) {
      tu_true(!r.found, "c0 = %g: no root in [0, 40] by the scan, search "
              "found %d at %g", c0, r.found, r.t);
      continue;
    }
    tu_true(r.found, "c0 = %g: a root", c0);
    tu_close("five frequencies: first root as the scan's", r.t, hi, 1e-12);
    printf("c0 = %g, c1 = %g: root %.17g in %ld steps\n", c0, c1, r.t,
           r.steps);
  }
}

/* A march stopped at several tmax and resumed (sc_guard_long_advance())
 * takes the same steps to the same root as one search: the five
 * frequencies of against_scan, and a start on zero that is skipped. */
static void resumed(void) {
  const double w[5] = {1, sqrt(2), sqrt(3), sqrt(5), sqrt(7)};
  const double a[5] = {0.21, -0.13, 0.08, 0.11, -0.05};
  const double b[5] = {-0.17, 0.09, -0.12, 0.04, 0.1};
  const double ws[1] = {1}, as[1] = {0}, bs[1] = {-1};
  for (int k = 0; k < 7; k++) {
    /* k < 6: the scan's guards; k = 6: -sin t from zero, root pi */
    sc_guard_long g = {-0.45 + 0.04 * k, 0.002 * k, 5, w, a, b};
    int skip = k == 6;
    if (skip) g = (sc_guard_long){0, 0, 1, ws, as, bs};
    sc_root_long one, r = {0};
    tu_int("one search", sc_guard_long_first_root(&g, 40, skip, &one), SC_OK);
    sc_guard_long_march m = {.stage = SC_MARCH_NEW};
    double lims[6] = {0, 1e-3, 0.7, 3, 3, 40};
    for (int i = 0; i < 6; i++) {
      tu_int("a stage", sc_guard_long_advance(&g, lims[i], skip, &m, &r),
             SC_OK);
      if (!r.found) tu_true(r.t == lims[i], "stage %d: none up to %g", i, lims[i]);
      else tu_true(r.t <= lims[i], "stage %d: root %g within %g", i, r.t, lims[i]);
    }
    tu_true(r.found == one.found && r.t == one.t && r.slope == one.slope &&
                r.tangent == one.tangent && r.steps == one.steps,
            "guard %d: resumed march = one search (found %d/%d, t %.17g/%.17g, "
            "steps %ld/%ld)", k, r.found, one.found, r.t, one.t, r.steps,
            one.steps);
  }
}

/* One sinusoid without drift has its root in closed form; the same
 * guard written as two halves of the same frequency is marched: both give
 * the same root (simple roots to 1e-12 of the period plus rounding over
 * the slope; touches found alike), on random guards, starts on zero
 * (skipped) included. */
static void closed_form_vs_march(void) {
  unsigned long s = 99;
  int touches = 0, found = 0;
  for (int k = 0; k < 2000; k++) {
    double u[5];
    for (int i = 0; i < 5; i++) {
      s = s * 6364136223846793005UL + 1442695040888963407UL;
      u[i] = (double)(s >> 11) / 9007199254740992.0;
    }
    double w[2] = {0.5 + 3 * u[0], 0}, a[2] = {u[1] - 0.5, 0},
           b[2] = {u[2] - 0.5, 0}, R = sqrt(a[0] * a[0] + b[0] * b[0]);
    double c0 = -R * (0.2 + 1.1 * u[3]);
    int skip = 0;
    if (k % 4 == 1) c0 = -a[0], skip = 1;  /* a start on zero */
    if (k % 4 == 2) c0 = -R * (1 - 1e-17); /* tops within rounding */
    w[1] = w[0], a[1] = a[0] / 2, b[1] = b[0] / 2;
    double ah[1] = {a[0] / 2}, bh[1] = {b[0] / 2};
    sc_guard_long one = {c0, 0, 1, w, a, b};
    double a2[2] = {ah[0], ah[0]}, b2[2] = {bh[0], bh[0]};
    sc_guard_long two = {c0, 0, 2, w, a2, b2};
    sc_root_long r1, r2;
    int s1 = sc_guard_long_first_root(&one, 50, skip, &r1);
    int s2 = sc_guard_long_first_root(&two, 50, skip, &r2);
    tu_int("closed form: status as the march's", s1, s2);
    if (s1 || s2) continue;
    tu_true(r1.found == r2.found, "guard %d: found %d, marched %d", k,
            r1.found, r2.found);
    if (!r1.found || !r2.found) continue;
    found++;
    /* a root near a top is known to rounding over the slope */
    double tol = r1.tangent || r2.tangent
                     ? 1e-6
                     : 1e-12 * 6.3 / w[0] + 64 * DBL_EPSILON * R / fabs(r2.slope);
    touches += r2.tangent;
    tu_true(fabs(r1.t - r2.t) <= tol,
            "guard %d (c0 %g, R %g, w %g, skip %d): root %.17g, marched "
            "%.17g", k, c0, R, w[0], skip, r1.t, r2.t);
    tu_true(r1.tangent == r2.tangent, "guard %d: tangent %d, marched %d", k,
            r1.tangent, r2.tangent);
  }
  printf("closed form vs march: %d roots, %d touches\n", found, touches);
  tu_true(found > 1000 && touches > 100, "the cases are exercised");
}

static void refusals(void) {
  double w0[1] = {0}, a1[1] = {1}, wn[1] = {1}, an[1] = {NAN};
  sc_guard_long g = {-1, 0, 1, w0, a1, a1};
  sc_root_long r;
  tu_int("w = 0 refused", sc_guard_long_first_root(&g, 1, 0, &r), SC_EINVAL);
  g = (sc_guard_long){-1, 0, 1, wn, an, a1};
  tu_int("a NaN coefficient refused", sc_guard_long_first_root(&g, 1, 0, &r),
         SC_EINVAL);
  g = (sc_guard_long){-1, 0, 1, wn, a1, a1};
  tu_int("tmax = inf refused", sc_guard_long_first_root(&g, INFINITY, 0, &r),
         SC_EINVAL);
  g = (sc_guard_long){-1, 0, -1, wn, a1, a1};
  tu_int("n < 0 refused", sc_guard_long_first_root(&g, 1, 0, &r), SC_EINVAL);
}

int main(void) {
  closed_forms();
  against_scan();
  resumed();
  closed_form_vs_march();
  refusals();
  return tu_finish();
}
