/* Error against time for what users compute (docs/accuracy.md):
 *
 *   build/bench/bench_accuracy OUTDIR [repeats] [chart-steps]
 *
 * 1. The map.  A sample of d (attractor points of four parameter sets of
 *    the reference chapter and a uniform grid of d over [-0.3, 0.3] for
 *    each) is evaluated by every setting: exact flows under each preset,
 *    numerical flows at ODE tolerances 1e-4 .. 1e-12, and the quad path.
 *    The error of a setting is measured against the quad path (f and
 *    f'), over the points whose itineraries agree; the points whose
 *    itineraries differ are counted.  The time is the median over
 *    `repeats` passes of the time per value-only evaluation on one core.
 * 2. Charts.  Fig 5.7(a) (driver frozen, alpha and beta over [1, 20],
 *    d0 = 0) on a chart-steps^2 grid: each setting of the transient, the
 *    confirmation cycles, the period tolerance and the preset against a
 *    long-transient reference chart; the error is the fraction of cells
 *    classified differently, the time that of the whole chart on one
 *    thread.  Cells of the reference are then re-run with the quad path
 *    (those where the default chart disagrees, and a random few): the
 *    count that quad confirms is printed.
 *
 * Writes OUTDIR/map.csv, chart.csv, tables.md, the gnuplot scripts and
 * (if gnuplot runs) map-f.png, map-df.png, chart.png, each with the
 * Pareto front (settings no other setting beats in both time and error)
 * drawn as a line.  Also prints tables.md. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "slipcont/chart.h"
#include "slipcont/map.h"
#include "bench_plot.h"
#include "bench_util.h"

#define NPERSET 400 /* points per parameter set: 200 attractor, 200 grid */
#define NSETS 4
#define NPTS (NPERSET * NSETS)
#define MAXSET 32

typedef struct {
  const char *name;
  double alpha, beta, v;
  const char *driver;
} pset;

static const pset sets[NSETS] = {
    {"fig 5.6", 2.9, 1, 0.019, "moving"},
    {"fig 5.8", 3.5, 2.5, 0.025, "frozen"},
    {"fig 5.12", 5.7, 3.2, 0.025, "frozen"},
    {"alpha 8", 8, 1.7, 0.01, "moving"},
};

/* One setting of the map: flows, preset, ODE tolerance, precision. */
typedef struct {
  char label[48];
  const char *flows, *preset;
  double ode_tol;
  int quad;
} msetting;

typedef struct {
  double time;    /* seconds per evaluation (median) */
  double err_f;   /* max |f - f_quad| */
  double med_f;   /* median |f - f_quad| */
  double err_df;  /* max |f' - f'_quad| / (1 + |f'_quad|) */
  int itin_diff;  /* points whose itinerary differs from quad's */
  int undef_diff; /* points defined in one and not the other */
} mresult;

static sc_map *make_map(const pset *p, const char *flows, const char *preset,
                        double ode_tol, int quad) {
  sc_accuracy acc;
  sc_msg msg;
  sc_map *m;
  sc_accuracy_preset(&acc, preset, NULL);
  if (ode_tol > 0) acc.ode_atol = acc.ode_rtol = ode_tol;
  acc.precision = quad ? SC_PRECISION_QUAD : SC_PRECISION_DOUBLE;
  if (sc_map_alloc("bk2", &acc, &m, &msg) ||
      sc_map_set_param_by_name(m, "alpha", p->alpha, &msg) ||
      sc_map_set_param_by_name(m, "beta", p->beta, &msg) ||
      sc_map_set_param_by_name(m, "v", p->v, &msg) ||
      sc_map_set_option(m, "driver", p->driver, &msg) ||
      sc_map_set_option(m, "flows", flows, &msg)) {
    fprintf(stderr, "bench_accuracy: %s\n", msg.text);
    exit(1);
  }
  return m;
}

static double pts[NSETS][NPERSET];
static sc_map_value ref[NSETS][NPERSET];
static int ref_st[NSETS][NPERSET];

static void make_sample(void) {
  for (int s = 0; s < NSETS; s++) {
    sc_map *m = make_map(&sets[s], "exact", "precise", 0, 0);
    sc_map_value r;
    double d = 0.02;
    for (int k = 0; k < 300 + NPERSET / 2; k++) {
      if (sc_map_eval(m, d, 0, &r, NULL))
        d = 0.02;
      else
        d = r.f;
      if (k >= 300) pts[s][k - 300] = d;
    }
    for (int i = 0; i < NPERSET / 2; i++)
      pts[s][NPERSET / 2 + i] = -0.3 + 0.6 * (i + 0.5) / (NPERSET / 2);
    sc_map_free(m);
  }
}

static void run_map(const msetting *st, int repeats, mresult *res) {
  double times[101];
  static double errs[NPTS];
  int ne = 0;
  memset(res, 0, sizeof *res);
  for (int rep = 0; rep < repeats; rep++)
    times[rep] = 0;
  for (int s = 0; s < NSETS; s++) {
    sc_map *m =
        make_map(&sets[s], st->flows, st->preset, st->ode_tol, st->quad);
    sc_map_value r;
    double sink = 0;
    for (int rep = 0; rep < repeats; rep++) {
      double t0 = bench_wall();
      for (int i = 0; i < NPERSET; i++)
        if (!sc_map_eval(m, pts[s][i], 0, &r, NULL)) sink += r.f;
      times[rep] += bench_wall() - t0;
    }
    if (sink == 42) printf(" ");
    for (int i = 0; i < NPERSET; i++) {
      int rs = sc_map_eval(m, pts[s][i], SC_EVAL_DERIV | SC_EVAL_ITINERARY, &r,
                           NULL);
      if (rs || ref_st[s][i]) {
        res->undef_diff += (rs != 0) != (ref_st[s][i] != 0);
        continue;
      }
      if (strcmp(r.itinerary, ref[s][i].itinerary) != 0) {
        res->itin_diff++;
        continue;
      }
      double e = fabs(r.f - ref[s][i].f);
      errs[ne++] = e;
      res->err_f = fmax(res->err_f, e);
      double q = ref[s][i].dfdd;
      if (isfinite(q))
        res->err_df = fmax(res->err_df, fabs(r.dfdd - q) / (1 + fabs(q)));
    }
    sc_map_free(m);
  }
  qsort(times, (size_t)repeats, sizeof times[0], bench_cmp_double);
  res->time = times[repeats / 2] / NPTS;
  qsort(errs, (size_t)ne, sizeof errs[0], bench_cmp_double);
  res->med_f = ne ? errs[ne / 2] : NAN;
}

/* Pareto front of (x, y), both smaller-is-better: marks front[i]. */
static void pareto(int n, const double *x, const double *y, int *front) {
  for (int i = 0; i < n; i++) {
    front[i] = 1;
    for (int j = 0; j < n; j++)
      if (j != i && x[j] <= x[i] && y[j] <= y[i] &&
          (x[j] < x[i] || y[j] < y[i]))
        front[i] = 0;
  }
}

/* The gnuplot script of one error-against-time plot: all settings as
 * labelled points (labels placed so that none overlaps another,
 * bench_plot.h), the front as a line through its points by time. */
static void write_plot(const char *dir, const char *stem, const char *csv,
                       int xcol, int ycol, const char *xlabel,
                       const char *ylabel, const char *title, double floor,
                       int n, const double *x, const double *y,
                       const char *const *text) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s.gp", dir, stem);
  FILE *f = fopen(path, "w");
  if (!f) return;
  fprintf(f,
          "set terminal pngcairo size 900,600\nset output '%s/%s.png'\n"
          "set datafile separator ','\nset grid\n"
          "set format xy \"10^{%%L}\"\n"
          "set key at screen 0.5, screen 0.01 center bottom horizontal\n"
          "set title \"%s\"\nset xlabel \"%s\"\n"
          "set ylabel \"%s\"\nfloor = %g\n",
          dir, stem, title, xlabel, ylabel, floor);
  bench_plot_labels(f, 900, 600, 0.12, 0.96, 0.2, 0.9, n, x, y, text);
  fprintf(f,
          "plot '%s/%s' every ::1 using %d:(column(%d) > floor ? "
          "column(%d) : floor) with points pt 7 ps 1.2 title 'setting', \\\n"
          "     '%s/%s-front.csv' using 1:(column(2) > floor ? column(2) : "
          "floor) with linespoints lw 2 pt 6 ps 2 title 'Pareto front'\n",
          dir, csv, xcol, ycol, ycol, dir, stem);
  fclose(f);
}

static void write_front(const char *dir, const char *stem, int n,
                        const double *x, const double *y) {
  int front[MAXSET], idx[MAXSET], k = 0;
  pareto(n, x, y, front);
  for (int i = 0; i < n; i++)
    if (front[i]) idx[k++] = i;
  for (int a = 1; a < k; a++)
    for (int b = a; b > 0 && x[idx[b]] < x[idx[b - 1]]; b--) {
      int t = idx[b];
      idx[b] = idx[b - 1], idx[b - 1] = t;
    }
  char path[512];
  snprintf(path, sizeof path, "%s/%s-front.csv", dir, stem);
  FILE *f = fopen(path, "w");
  if (!f) return;
  for (int i = 0; i < k; i++)
    fprintf(f, "%.17g,%.17g\n", x[idx[i]], y[idx[i]]);
  fclose(f);
}

/* ---- charts ------------------------------------------------------------ */

typedef struct {
  char label[48];
  const char *preset;
  long transient;
  int confirm;
  double period_rtol; /* 0: the preset's */
} csetting;

static sc_map *chart_map(const char *preset, double prtol, int quad) {
  static const pset fig57 = {"fig 5.7(a)", 1, 1, 0.025, "frozen"};
  sc_map *m = make_map(&fig57, "exact", preset, 0, quad);
  if (prtol > 0) {
    sc_accuracy acc = *sc_map_accuracy(m);
    acc.period_rtol = prtol;
    sc_map_set_accuracy(m, &acc, NULL);
  }
  return m;
}

static double run_chart(const csetting *c, long steps, sc_chart_point *out) {
  sc_chart_spec s;
  sc_chart_spec_default(&s);
  s.x = "alpha", s.x_from = 1, s.x_to = 20, s.x_steps = steps;
  s.y = "beta", s.y_from = 1, s.y_to = 20, s.y_steps = steps;
  s.d0 = 0;
  s.transient = c->transient;
  s.confirm = c->confirm;
  sc_map *m = chart_map(c->preset, c->period_rtol, 0);
  sc_msg msg;
  if (sc_chart_check(m, &s, &msg)) {
    fprintf(stderr, "bench_accuracy: %s\n", msg.text);
    exit(1);
  }
  double t0 = bench_wall();
  if (sc_chart_rows(m, &s, 0, steps, 1, 1, NULL, NULL, out, &msg)) {
    fprintf(stderr, "bench_accuracy: %s\n", msg.text);
    exit(1);
  }
  double t = bench_wall() - t0;
  sc_map_free(m);
  return t;
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: bench_accuracy OUTDIR [repeats] [chart-steps]\n");
    return 2;
  }
  const char *dir = argv[1];
  int repeats = argc > 2 ? atoi(argv[2]) : 5;
  long steps = argc > 3 ? atol(argv[3]) : 40;
  if (repeats < 1 || repeats > 101 || steps < 2 || steps > 400) {
    fprintf(stderr, "bench_accuracy: repeats in 1..101, chart-steps in "
                    "2..400\n");
    return 2;
  }
  char path[512];
  snprintf(path, sizeof path, "%s/tables.md", dir);
  FILE *md = fopen(path, "w");
  if (!md) {
    fprintf(stderr, "bench_accuracy: cannot write %s (does %s exist?)\n", path,
            dir);
    return 1;
  }

  /* ---- 1. the map ---- */
  make_sample();
  for (int s = 0; s < NSETS; s++) {
    sc_map *q = make_map(&sets[s], "exact", "default", 0, 1);
    for (int i = 0; i < NPERSET; i++)
      ref_st[s][i] = sc_map_eval(
          q, pts[s][i], SC_EVAL_DERIV | SC_EVAL_ITINERARY, &ref[s][i], NULL);
    sc_map_free(q);
  }
  msetting ms[MAXSET];
  int nm = 0;
  const char *presets[] = {"fast", "default", "precise"};
  for (int p = 0; p < 3; p++) {
    msetting x = {"", "exact", presets[p], 0, 0};
    snprintf(x.label, sizeof x.label, "exact %s", presets[p]);
    ms[nm++] = x;
  }
  for (int e = 4; e <= 12; e += 2) {
    msetting x = {"", "numerical", "default", pow(10, -e), 0};
    snprintf(x.label, sizeof x.label, "numerical 1e-%d", e);
    ms[nm++] = x;
  }
  {
    msetting x = {"quad", "exact", "default", 0, 1};
    ms[nm++] = x;
  }
  mresult mr[MAXSET];
  snprintf(path, sizeof path, "%s/map.csv", dir);
  FILE *csv = fopen(path, "w");
  if (!csv) return 1;
  fprintf(csv, "setting,seconds_per_eval,max_err_f,median_err_f,"
               "max_rel_err_df,itinerary_differs,undefined_differs\n");
  fprintf(md,
          "Map: %d points (%d per parameter set: fig 5.6, fig 5.8, fig "
          "5.12, alpha 8), errors against the quad path, time per "
          "value-only evaluation (median of %d passes, one core).\n\n"
          "| setting | time per f (us) | max abs err f | median abs err f "
          "| max rel err f' | itinerary differs | defined differs |\n"
          "|---|---|---|---|---|---|---|\n",
          NPTS, NPERSET, repeats);
  double xs[MAXSET], yf[MAXSET], yd[MAXSET];
  for (int i = 0; i < nm; i++) {
    run_map(&ms[i], ms[i].quad ? (repeats + 1) / 2 : repeats, &mr[i]);
    fprintf(csv, "%s,%.6g,%.6g,%.6g,%.6g,%d,%d\n", ms[i].label, mr[i].time,
            mr[i].err_f, mr[i].med_f, mr[i].err_df, mr[i].itin_diff,
            mr[i].undef_diff);
    fprintf(md, "| %s | %.4g | %.3g | %.3g | %.3g | %d | %d |\n", ms[i].label,
            1e6 * mr[i].time, mr[i].err_f, mr[i].med_f, mr[i].err_df,
            mr[i].itin_diff, mr[i].undef_diff);
    fflush(md);
    xs[i] = mr[i].time;
    /* quad against itself is 0: plotted at the floor */
    yf[i] = fmax(mr[i].err_f, 1e-18);
    yd[i] = fmax(mr[i].err_df, 1e-18);
  }
  fclose(csv);
  write_front(dir, "map-f", nm, xs, yf);
  write_front(dir, "map-df", nm, xs, yd);
  const char *mlab[MAXSET];
  for (int i = 0; i < nm; i++) mlab[i] = ms[i].label;
  write_plot(dir, "map-f", "map.csv", 2, 3, "seconds per evaluation of f",
             "max |f - f_{quad}|",
             "bk2 map: error against time (quad at the floor 1e-18)", 1e-18,
             nm, xs, yf, mlab);
  write_plot(dir, "map-df", "map.csv", 2, 5, "seconds per evaluation of f",
             "max |f' - f'_{quad}| / (1 + |f'_{quad}|)",
             "bk2 map derivative: error against time", 1e-18, nm, xs, yd,
             mlab);

  /* ---- 2. charts ---- */
  long np = steps * steps;
  sc_chart_point *refc = malloc((size_t)np * sizeof *refc);
  sc_chart_point *cur = malloc((size_t)np * sizeof *cur);
  sc_chart_point *def = malloc((size_t)np * sizeof *def);
  if (!refc || !cur || !def) return 1;
  const csetting reference = {"reference", "precise", 8000, 8, 1e-8};
  double tref = run_chart(&reference, steps, refc);
  csetting cs[MAXSET];
  int nc = 0;
  long trans[] = {100, 250, 500, 1000, 2000, 4000};
  for (int i = 0; i < 6; i++) {
    csetting x = {"", "default", trans[i], 4, 0};
    snprintf(x.label, sizeof x.label, "transient %ld", trans[i]);
    cs[nc++] = x;
  }
  int confs[] = {1, 2, 8};
  for (int i = 0; i < 3; i++) {
    csetting x = {"", "default", 1000, confs[i], 0};
    snprintf(x.label, sizeof x.label, "confirm %d", confs[i]);
    cs[nc++] = x;
  }
  double rt[] = {1e-3, 1e-4, 1e-5, 1e-7, 1e-8};
  for (int i = 0; i < 5; i++) {
    csetting x = {"", "default", 1000, 4, rt[i]};
    snprintf(x.label, sizeof x.label, "period-rtol %.0e", rt[i]);
    cs[nc++] = x;
  }
  for (int p = 0; p < 3; p += 2) {
    csetting x = {"", presets[p], 1000, 4, 0};
    snprintf(x.label, sizeof x.label, "preset %s", presets[p]);
    cs[nc++] = x;
  }
  snprintf(path, sizeof path, "%s/chart.csv", dir);
  csv = fopen(path, "w");
  if (!csv) return 1;
  fprintf(csv, "setting,seconds,fraction_differs\n");
  fprintf(md,
          "\nCharts: fig 5.7(a) (driver frozen, d0 = 0), alpha and beta "
          "over [1, 20] on %ld x %ld cells, max period 16; reference: "
          "preset precise, transient %ld, confirm %d, period-rtol %g "
          "(%.3g s).  Unless named, a setting is transient 1000, "
          "confirm 4, preset default (period-rtol 1e-6).  One thread.\n\n"
          "| setting | time (s) | cells classified differently |\n"
          "|---|---|---|\n",
          steps, steps, reference.transient, reference.confirm,
          reference.period_rtol, tref);
  double cx[MAXSET], cy[MAXSET];
  for (int i = 0; i < nc; i++) {
    double t = run_chart(&cs[i], steps, cur);
    long diff = 0;
    for (long k = 0; k < np; k++)
      diff += cur[k].period != refc[k].period;
    double frac = (double)diff / (double)np;
    if (strcmp(cs[i].label, "transient 1000") == 0)
      memcpy(def, cur, (size_t)np * sizeof *cur);
    fprintf(csv, "%s,%.6g,%.6g\n", cs[i].label, t, frac);
    fprintf(md, "| %s | %.3g | %.4f (%ld) |\n", cs[i].label, t, frac, diff);
    fflush(md);
    cx[i] = t;
    cy[i] = fmax(frac, 0.5 / (double)np);
  }
  fclose(csv);
  write_front(dir, "chart", nc, cx, cy);
  const char *clab[MAXSET];
  for (int i = 0; i < nc; i++) clab[i] = cs[i].label;
  write_plot(dir, "chart", "chart.csv", 2, 3, "seconds per chart (one thread)",
             "fraction of cells classified differently from the reference",
             "fig 5.7(a) chart: error against time (0 plotted at half a cell)",
             0.5 / (double)np, nc, cx, cy, clab);

  /* ---- quad check of the reference ---- */
  sc_map *q = chart_map("precise", reference.period_rtol, 1);
  sc_period *pd;
  sc_msg msg;
  if (sc_period_alloc(16, reference.confirm, reference.period_rtol, &pd, &msg))
    return 1;
  int checked = 0, agree = 0, ndis = 0, nrand = 0;
  unsigned long long rs = 12345;
  for (long k = 0; k < np && (ndis < 8 || nrand < 8); k++) {
    int pick = 0;
    if (def[k].period != refc[k].period && ndis < 8) pick = 1, ndis++;
    rs = rs * 6364136223846793005ULL + 1442695040888963407ULL;
    if (!pick && (rs >> 40) % (unsigned long long)(np / 8 + 1) == 0 &&
        nrand < 8)
      pick = 1, nrand++;
    if (!pick) continue;
    sc_chart_spec s;
    sc_chart_spec_default(&s);
    s.x_from = 1, s.x_to = 20, s.x_steps = steps;
    s.y_from = 1, s.y_to = 20, s.y_steps = steps;
    sc_map_set_param_by_name(q, "alpha", sc_chart_x(&s, k % steps), NULL);
    sc_map_set_param_by_name(q, "beta", sc_chart_y(&s, k / steps), NULL);
    sc_period_result pr;
    if (sc_period_find(pd, q, 0, reference.transient, &pr, &msg)) continue;
    checked++;
    agree += pr.period == refc[k].period;
    if (pr.period != refc[k].period)
      fprintf(md,
              "\nquad disagrees with the reference at alpha = %.17g, "
              "beta = %.17g: %d vs %d\n",
              sc_chart_x(&s, k % steps), sc_chart_y(&s, k / steps), pr.period,
              refc[k].period);
  }
  fprintf(md,
          "\nQuad check of the reference chart: %d of %d cells (%d where "
          "the default setting disagrees, %d at random) get the same "
          "class with the quad path.\n",
          agree, checked, ndis, nrand);
  sc_period_free(pd);
  sc_map_free(q);
  fclose(md);
  free(refc), free(cur), free(def);

  /* render, if gnuplot is there */
  const char *stems[] = {"map-f", "map-df", "chart"};
  for (int i = 0; i < 3; i++) {
    char cmd[1100];
    snprintf(cmd, sizeof cmd, "gnuplot '%s/%s.gp' 2>/dev/null", dir, stems[i]);
    if (system(cmd) != 0)
      fprintf(stderr, "bench_accuracy: gnuplot failed on %s.gp\n", stems[i]);
  }
  snprintf(path, sizeof path, "cat '%s/tables.md'", dir);
  return system(path) == 0 ? 0 : 1;
}
