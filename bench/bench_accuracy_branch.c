/* Located special points against time (docs/accuracy.md, "Special
 * points"), through the public branch API only (branch.h), so that it
 * reads whatever labels and values the branch code reports:
 *
 *   build/bench/bench_accuracy_branch OUTDIR
 *   build/bench/bench_accuracy_branch --smooth OUTDIR REPEATS
 *
 * Fig 5.8's orbits (driver frozen, beta = 2.5, alpha in [2.8, 4]) are
 * continued from three starts without branch switching (period 2 from
 * alpha = 3 over [3, 4], period 6 from 3.3, period 4 from 3.75), once per
 * setting: each preset with arclength steps hmax = 0.02, 0.01, 0.005.  The
 * reference is the same run with the quad path, preset precise, hmax =
 * 0.005.  Every special point of the reference other than an end point
 * is matched with the point of the same label and period nearest in the
 * parameter; the table gives each point's error |p - p_ref| (or "-"
 * where none is found within 1e-3), the plot the largest over the folds
 * and flips and over the borders.  Writes
 * OUTDIR/branch.csv, branch.gp, branch.png (if gnuplot runs) and appends
 * a table to OUTDIR/tables.md, then one each for the logistic and cubic
 * maps, whose special points are known exactly (smooth_all(): median of
 * 11 runs per setting, OUTDIR/smooth.csv, smooth.gp, smooth.png).  With
 * --smooth only the latter, REPEATS runs per setting, tables to
 * OUTDIR/smooth.md: bench/auto/run_auto.sh runs it next to AUTO-07p on the
 * same maps and adds AUTO's rows to smooth.csv and smooth.md. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "slipcont/orbits.h"
#include "slipcont/map.h"
#include "bench_plot.h"
#include "bench_util.h"

#define MAXPTS 256

typedef struct {
  char label[8];
  int period;
  double p, d;
} spt;

typedef struct {
  const char *preset;
  double hmax;
  int quad;
} bsetting;

/* One run; returns its time and fills pts (special points, no EP). */
static double run(const bsetting *s, spt *pts, int *npts, unsigned long *nev) {
  sc_accuracy acc;
  sc_msg msg;
  sc_map *m;
  sc_accuracy_preset(&acc, s->preset, NULL);
  acc.precision = s->quad ? SC_PRECISION_QUAD : SC_PRECISION_DOUBLE;
  if (sc_map_alloc("bk2", &acc, &m, &msg) ||
      sc_map_set_param_by_name(m, "alpha", 3.0, &msg) ||
      sc_map_set_param_by_name(m, "beta", 2.5, &msg) ||
      sc_map_set_option(m, "driver", "frozen", &msg)) {
    fprintf(stderr, "bench_accuracy_branch: %s\n", msg.text);
    exit(1);
  }
  sc_orbit_branch_spec sp = {
      .param = (size_t)sc_map_param_index(m, "alpha"),
      .from = 3.0,
      .to = 4.0,
      .period = 2,
      .d0 = 0.2253,
      .switch_pd = 0,
      .max_points = 4000,
      .max_branches = 8,
      .max_period = 16,
      .h0 = 0,
      .hmax = s->hmax,
  };
  sc_orbit_branch *ob;
  double t0 = bench_wall();
  unsigned long e0 = sc_map_nevals(m);
  int st = sc_orbit_branch_alloc(m, &sp, &ob, &msg);
  if (!st) st = sc_orbit_branch_add_start(ob, 3.3, 0.0991, 6, &msg);
  if (!st) st = sc_orbit_branch_add_start(ob, 3.75, 0.2075, 4, &msg);
  if (!st) st = sc_orbit_branch_run(ob, &msg);
  double t = bench_wall() - t0;
  if (st) {
    fprintf(stderr, "bench_accuracy_branch: %s (%s)\n", msg.text,
            sc_strerror(st));
    exit(1);
  }
  *nev = sc_map_nevals(m) - e0;
  *npts = 0;
  for (size_t i = 0; i < sc_orbit_branch_nspecial(ob) && *npts < MAXPTS; i++) {
    sc_orbit_special_info sp_i;
    if (sc_orbit_branch_special(ob, i, &sp_i)) continue;
    const char *lab = sc_point_label_text(sp_i.label);
    if (strcmp(lab, "EP") == 0) continue;
    spt *q = &pts[(*npts)++];
    snprintf(q->label, sizeof q->label, "%s", lab);
    q->period = sp_i.period;
    q->p = sp_i.p;
    q->d = sp_i.d;
  }
  sc_orbit_branch_free(ob);
  sc_map_free(m);
  return t;
}

/* Smooth maps whose special points are known exactly, the same problems
 * as bench/auto/ gives AUTO-07p (run_auto.sh puts both on one plot). */
typedef struct {
  const char *label;
  int period;
  double p;
} exact_pt;

typedef struct {
  const char *name;  /* model */
  const char *param; /* continued parameter */
  const char *fixed; /* another parameter held fixed, or NULL */
  double fixed_value;
  double from, to, d0;
  int switch_pd, max_period;
  int extra_period; /* a second start (0: none) */
  double extra_p, extra_d;
  const char *doc;
  int nexact;
  exact_pt exact[4];
} smooth_case;

static const smooth_case smooth_cases[] = {
    /* Flips at r = 3, 1 + sqrt(6) and r_3 = 3.5440903595519228536
     * (period 4 -> 8, a published constant), the period-3 fold at
     * 1 + 2 sqrt(2).  Period 1 from r = 2.8 with branch switching up to
     * period 8, and period 3 from r = 3.84. */
    {"logistic",
     "r",
     NULL,
     0,
     2.8,
     3.9,
     0.6,
     1,
     8,
     3,
     3.84,
     0.1494,
     "flips at 3, 1 + sqrt(6), 3.5440903595519229, the period-3 fold at "
     "1 + 2 sqrt(2): period 1 from r = 2.8 with branch switching to "
     "period 8, period 3 from r = 3.84",
     4,
     {{"PD", 1, 3.0},
      {"PD", 2, 3.4494897427831781}, /* 1 + sqrt(6) */
      {"PD", 4, 3.5440903595519229},
      {"LP", 3, 3.8284271247461901}}}, /* 1 + 2 sqrt(2) */
    /* x -> x + mu1 + mu2 x - x^3 at mu2 = 1/2, mu1 from -1 to 1 along the
     * S-shaped branch mu1 = x^3 - x/2: flips where f' = -1 (x = -+
     * sqrt(5/6), mu1 = -+sqrt(5/6)/3), folds where f' = 1 (x = -+1/sqrt
     * 6, mu1 = +-1/(3 sqrt 6)).  No branch switching. */
    {"cubic",
     "mu1",
     "mu2",
     0.5,
     -1.0,
     1.0,
     -1.165,
     0,
     1,
     0,
     0,
     0,
     "mu2 = 1/2, mu1 from -1 to 1: flips at mu1 = -+sqrt(5/6)/3, folds at "
     "mu1 = +-1/(3 sqrt 6)",
     4,
     {{"PD", 1, -0.30429030972509228}, /* -sqrt(5/6)/3 */
      {"LP", 1, 0.13608276348795434},  /* 1/(3 sqrt 6) */
      {"LP", 1, -0.13608276348795434},
      {"PD", 1, 0.30429030972509228}}},
};

/* A located point farther than this from the exact one counts as not
 * found; the exact points of one map are at least 0.09 apart (and run_auto.py
 * uses the same window for AUTO's points). */
#define SMOOTH_MATCH 1e-2

/* One smooth case under one setting, run `repeats` times: returns the
 * median time and the largest |p - exact| over the exact points found
 * (a point of that label and period within SMOOTH_MATCH; the others are
 * counted in *missing).  Every repeat gives the same points (deterministic). */
static double run_smooth(const smooth_case *c, const char *preset, double hmax,
                         int repeats, double *err, int *missing,
                         unsigned long *nev) {
  double times[64];
  if (repeats > 64) repeats = 64;
  for (int rep = 0; rep < repeats; rep++) {
    sc_accuracy acc;
    sc_msg msg;
    sc_map *m;
    sc_accuracy_preset(&acc, preset, NULL);
    if (sc_map_alloc(c->name, &acc, &m, &msg) ||
        sc_map_set_param_by_name(m, c->param, c->from, &msg) ||
        (c->fixed &&
         sc_map_set_param_by_name(m, c->fixed, c->fixed_value, &msg))) {
      fprintf(stderr, "bench_accuracy_branch: %s\n", msg.text);
      exit(1);
    }
    sc_orbit_branch_spec sp = {
        .param = (size_t)sc_map_param_index(m, c->param),
        .from = c->from,
        .to = c->to,
        .period = 1,
        .d0 = c->d0,
        .switch_pd = c->switch_pd,
        .max_points = 4000,
        .max_branches = 16,
        .max_period = c->max_period,
        .hmax = hmax,
    };
    sc_orbit_branch *ob;
    double t0 = bench_wall();
    unsigned long e0 = sc_map_nevals(m);
    int st = sc_orbit_branch_alloc(m, &sp, &ob, &msg);
    if (!st && c->extra_period)
      st = sc_orbit_branch_add_start(ob, c->extra_p, c->extra_d,
                                     c->extra_period, &msg);
    if (!st) st = sc_orbit_branch_run(ob, &msg);
    times[rep] = bench_wall() - t0;
    if (st) {
      fprintf(stderr, "bench_accuracy_branch: %s: %s\n", c->name, msg.text);
      exit(1);
    }
    *nev = sc_map_nevals(m) - e0;
    *err = 0;
    *missing = 0;
    for (int k = 0; k < c->nexact; k++) {
      double best = HUGE_VAL;
      for (size_t i = 0; i < sc_orbit_branch_nspecial(ob); i++) {
        sc_orbit_special_info q;
        if (sc_orbit_branch_special(ob, i, &q)) continue;
        if (strcmp(sc_point_label_text(q.label), c->exact[k].label) == 0 &&
            q.period == c->exact[k].period)
          best = fmin(best, fabs(q.p - c->exact[k].p));
      }
      if (best > SMOOTH_MATCH)
        (*missing)++;
      else
        *err = fmax(*err, best);
    }
    sc_orbit_branch_free(ob);
    sc_map_free(m);
  }
  qsort(times, (size_t)repeats, sizeof times[0], bench_cmp_double);
  return times[repeats / 2];
}

/* The smooth maps under each preset and hmax: a table in md, rows in
 * OUTDIR/smooth.csv (run_auto.sh appends AUTO-07p's) and the plot
 * OUTDIR/smooth.gp -> smooth.png. */
static int smooth_all(const char *dir, FILE *md, int repeats) {
  const char *presets[] = {"fast", "default", "precise"};
  const double hs[] = {0.02, 0.01, 0.005};
  char path[512];
  snprintf(path, sizeof path, "%s/smooth.csv", dir);
  FILE *csv = fopen(path, "w");
  if (!csv) {
    fprintf(stderr, "bench_accuracy_branch: cannot write %s\n", path);
    return 1;
  }
  fprintf(csv, "map,tool,setting,seconds,max_err,missing,process_seconds\n");
  /* each case's points and labels, for the plot */
  double px[2][9], py[2][9];
  char ptext[2][9][96];
  const char *plab[2][9];
  for (size_t ic = 0; ic < sizeof smooth_cases / sizeof smooth_cases[0]; ic++) {
    const smooth_case *c = &smooth_cases[ic];
    fprintf(md,
            "\nThe %s map against its exact special points (%s); slipcont, "
            "median of %d runs in one process:\n\n"
            "| setting | time (s) | map evaluations | max abs p - exact "
            "| missing (none within 1e-2) |\n|---|---|---|---|---|\n",
            c->name, c->doc, repeats);
    for (int ip = 0; ip < 3; ip++)
      for (int ih = 0; ih < 3; ih++) {
        double err;
        int missing;
        unsigned long nev;
        double t =
            run_smooth(c, presets[ip], hs[ih], repeats, &err, &missing, &nev);
        fprintf(md, "| %s hmax %g | %.3g | %lu | %.3g | %d |\n", presets[ip],
                hs[ih], t, nev, err, missing);
        fprintf(csv, "%s,slipcont,%s hmax %g,%.6g,%.6g,%d,\n", c->name,
                presets[ip], hs[ih], t, err, missing);
        if (ic < 2) {
          int k = 3 * ip + ih;
          px[ic][k] = t;
          py[ic][k] = err > 1e-17 ? err : 1e-17;
          if (missing)
            snprintf(ptext[ic][k], sizeof ptext[ic][k],
                     "%s hmax %g (%d not found)", presets[ip], hs[ih],
                     missing);
          else
            snprintf(ptext[ic][k], sizeof ptext[ic][k], "%s hmax %g",
                     presets[ip], hs[ih]);
          plab[ic][k] = ptext[ic][k];
        }
      }
  }
  fclose(csv);
  snprintf(path, sizeof path, "%s/smooth.gp", dir);
  FILE *gp = fopen(path, "w");
  if (!gp) return 1;
  fprintf(gp,
          "# slipcont and (where run_auto.sh added its rows) AUTO-07p\n"
          "set terminal pngcairo size 1200,560\n"
          "set output '%s/smooth.png'\n"
          "set datafile separator ','\nset logscale xy\nset grid\n"
          "set format y \"10^{%%L}\"\nset format x \"10^{%%L}\"\n"
          "set key at screen 0.5, screen 0.01 center bottom horizontal "
          "maxrows 1 font ',10'\n"
          "set xlabel \"seconds per run (median)\"\n"
          "set ylabel \"max |p - p_{exact}| over the points found\"\n"
          "f = '%s/smooth.csv'\n"
          "y(e) = e > 1e-17 ? e : 1e-17\n"
          "is(m, t) = strcol(1) eq m && strcol(2) eq t\n"
          "set multiplot\n",
          dir, dir);
  const char *titles[] = {"logistic map: flips at 3, 1+sqrt 6, r_3; fold "
                          "of period 3",
                          "cubic map (mu2 = 1/2): two flips, two folds"};
  for (size_t ic = 0; ic < 2; ic++) {
    const char *n = smooth_cases[ic].name;
    /* slipcont's settings labelled (placed: none overlaps another); the
     * x range leaves two decades on the right for AUTO-07p's rows */
    double xr[2] = {px[ic][0], px[ic][0] * 100};
    for (int k = 1; k < 9; k++)
      xr[0] = fmin(xr[0], px[ic][k]), xr[1] = fmax(xr[1], 100 * px[ic][k]);
    /* the key once, under both panels */
    fprintf(gp, "unset label\nunset arrow\nset format x \"10^{%%L}\"\n%s",
            ic ? "unset key\n" : "");
    double left = ic ? 0.57 : 0.07;
    sc_plot_frame fr = {.width = 1200, .height = 560, .left = left,
                        .right = left + 0.41, .bottom = 0.22, .top = 0.9,
                        .xlog = 1, .ylog = 1, .font = 7, .marker = 5};
    bench_plot_decades(2, xr, &fr.xmin, &fr.xmax);
    fr.ymin = 1e-17, fr.ymax = 1;
    sc_plot_spot sp[9];
    for (int k = 0; k < 9; k++) {
      memset(&sp[k], 0, sizeof sp[k]);
      sp[k].x = px[ic][k], sp[k].y = py[ic][k];
      snprintf(sp[k].text, sizeof sp[k].text, "%s", plab[ic][k]);
    }
    sc_plot_frame_write(gp, &fr);
    sc_plot_place(&fr, sp, 9);
    sc_plot_labels_write(gp, &fr, sp, 9, "#666666");
    fprintf(gp,
            "set title \"%s\"\n"
            "plot f every ::1 using (is('%s','slipcont') ? $4 : NaN):(y($5)) "
            "with points pt 7 ps 1.2 lc 1 title 'slipcont (in process)', \\\n"
            "     f every ::1 using (is('%s','auto') ? $4 : NaN):(y($5)) "
            "with points pt 5 ps 1.2 lc 2 title 'AUTO-07p (its Total Time)', "
            "\\\n"
            "     f every ::1 using (is('%s','auto') ? $7 : NaN):(y($5)) "
            "with points pt 4 ps 1.2 lc 2 title 'AUTO-07p (wall, with "
            "process start and files)'\n",
            titles[ic], n, n, n);
  }
  fprintf(gp, "unset multiplot\n");
  fclose(gp);
  char cmd[1100];
  snprintf(cmd, sizeof cmd, "gnuplot '%s/smooth.gp' 2>/dev/null", dir);
  if (system(cmd) != 0)
    fprintf(stderr, "bench_accuracy_branch: gnuplot failed (smooth.gp)\n");
  return 0;
}

int main(int argc, char **argv) {
  const int smooth_repeats = 11;
  if (argc == 4 && strcmp(argv[1], "--smooth") == 0) {
    /* Only the smooth maps, for run_auto.sh: tables to OUTDIR/smooth.md. */
    char *end;
    long reps = strtol(argv[3], &end, 10);
    if (*end || reps < 1 || reps > 64) {
      fprintf(stderr, "bench_accuracy_branch: REPEATS must be 1..64 (%s)\n",
              argv[3]);
      return 2;
    }
    char path[512];
    snprintf(path, sizeof path, "%s/smooth.md", argv[2]);
    FILE *md = fopen(path, "w");
    if (!md) {
      fprintf(stderr, "bench_accuracy_branch: cannot write %s\n", path);
      return 1;
    }
    int st = smooth_all(argv[2], md, (int)reps);
    fclose(md);
    return st;
  }
  if (argc != 2) {
    fprintf(stderr, "usage: bench_accuracy_branch OUTDIR\n"
                    "       bench_accuracy_branch --smooth OUTDIR REPEATS\n");
    return 2;
  }
  const char *dir = argv[1];
  static spt ref[MAXPTS], cur[MAXPTS];
  int nref, ncur;
  unsigned long nev;
  const bsetting refs = {"precise", 0.005, 1};
  double tref = run(&refs, ref, &nref, &nev);
  char path[512];
  snprintf(path, sizeof path, "%s/tables.md", dir);
  FILE *md = fopen(path, "a");
  snprintf(path, sizeof path, "%s/branch.csv", dir);
  FILE *csv = fopen(path, "w");
  if (!md || !csv) {
    fprintf(stderr, "bench_accuracy_branch: cannot write into %s\n", dir);
    return 1;
  }
  fprintf(md,
          "\nSpecial points: fig 5.8's orbits (driver frozen, beta = "
          "2.5) from three starts, no branch switching; reference: "
          "quad, preset precise, hmax 0.005 (%.3g s, %lu map "
          "evaluations, %d special points:",
          tref, nev, nref);
  for (int i = 0; i < nref; i++)
    fprintf(md, " %s(m=%d) %.15g%s", ref[i].label, ref[i].period, ref[i].p,
            i + 1 < nref ? "," : "");
  fprintf(md, ").\n\nError |p - p_ref| of each reference point (\"-\": "
              "no point of that label and period within 1e-3), and the "
              "largest over the folds and flips (LP, PD) and over the "
              "others (borders):\n\n| setting | time (s) | map evaluations "
              "| max LP/PD | max others |");
  for (int i = 0; i < nref; i++)
    fprintf(md, " %s%d %.4f |", ref[i].label, ref[i].period, ref[i].p);
  fprintf(md, "\n|---|---|---|---|---|");
  for (int i = 0; i < nref; i++)
    fprintf(md, "---|");
  fprintf(md, "\n");
  fprintf(csv, "setting,seconds,max_err_lp_pd,max_err_other,missing\n");
  /* the plot's points: folds and flips labelled, borders as markers */
  double gx[36], gy[36]; /* folds and flips, then borders */
  char gtext[18][64];
  const char *glab[18];
  int ng = 0;
  const char *presets[] = {"fast", "default", "precise"};
  const double hs[] = {0.02, 0.01, 0.005};
  for (int ip = 0; ip < 3; ip++)
    for (int ih = 0; ih < 3; ih++) {
      bsetting s = {presets[ip], hs[ih], 0};
      double t = run(&s, cur, &ncur, &nev);
      double e_lp = 0, e_other = 0, errs[MAXPTS];
      int missing = 0;
      for (int i = 0; i < nref; i++) {
        double best = HUGE_VAL;
        for (int j = 0; j < ncur; j++)
          if (strcmp(cur[j].label, ref[i].label) == 0 &&
              cur[j].period == ref[i].period)
            best = fmin(best, fabs(cur[j].p - ref[i].p));
        errs[i] = best;
        if (best > 1e-3) { /* not the same point */
          missing++;
          continue;
        }
        int fold_flip =
            strcmp(ref[i].label, "LP") == 0 || strcmp(ref[i].label, "PD") == 0;
        if (fold_flip)
          e_lp = fmax(e_lp, best);
        else
          e_other = fmax(e_other, best);
      }
      char label[64];
      snprintf(label, sizeof label, "%s hmax %g", presets[ip], hs[ih]);
      fprintf(md, "| %s | %.3g | %lu | %.3g | %.3g |", label, t, nev, e_lp,
              e_other);
      for (int i = 0; i < nref; i++)
        if (errs[i] > 1e-3)
          fprintf(md, " - |");
        else
          fprintf(md, " %.2g |", errs[i]);
      fprintf(md, "\n");
      fprintf(csv, "%s,%.6g,%.6g,%.6g,%d\n", label, t, e_lp, e_other, missing);
      gx[ng] = t, gy[ng] = e_lp > 1e-17 ? e_lp : 1e-17;
      gy[9 + ng] = e_other > 1e-17 ? e_other : 1e-17; /* 9 settings */
      snprintf(gtext[ng], sizeof gtext[ng], "%s", label);
      glab[ng] = gtext[ng];
      ng++;
    }
  fclose(csv);
  if (smooth_all(dir, md, smooth_repeats)) return 1;
  fclose(md);
  snprintf(path, sizeof path, "%s/branch.gp", dir);
  FILE *gp = fopen(path, "w");
  if (!gp) return 1;
  fprintf(gp,
          "set terminal pngcairo size 900,600\nset output '%s/branch.png'\n"
          "set datafile separator ','\nset grid\n"
          "set format y \"10^{%%L}\"\n"
          "set key at screen 0.5, screen 0.01 center bottom horizontal\n"
          "set title \"fig 5.8 special points: error against time "
          "(reference: quad)\"\nset xlabel \"seconds per run\"\n"
          "set ylabel \"max |p - p_{quad}| over matched points\"\n",
          dir);
  /* the settings' labels by their fold and flip points; the border
   * points' markers (empty texts) are kept clear of them */
  const char *alab[36];
  for (int i = 0; i < ng; i++) {
    gx[ng + i] = gx[i];
    alab[i] = glab[i];
    alab[ng + i] = "";
  }
  bench_plot_labels(gp, 900, 600, 0.12, 0.96, 0.2, 0.9, 2 * ng, gx, gy, alab);
  fprintf(gp,
          "plot '%s/branch.csv' every ::1 using 2:($3 > 1e-17 ? $3 : 1e-17) "
          "with points pt 7 ps 1.2 title 'folds and flips (LP, PD)', \\\n"
          "     '' every ::1 using 2:($4 > 1e-17 ? $4 : 1e-17) with points "
          "pt 5 ps 1.2 title 'borders (GR, CS, SW, DI)'\n",
          dir);
  fclose(gp);
  char cmd[1100];
  snprintf(cmd, sizeof cmd, "gnuplot '%s/branch.gp' 2>/dev/null", dir);
  if (system(cmd) != 0)
    fprintf(stderr, "bench_accuracy_branch: gnuplot failed\n");
  return 0;
}
