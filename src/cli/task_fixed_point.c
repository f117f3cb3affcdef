/* Task `fixed-point`: every period-m orbit in an interval of d at fixed
 * parameters, without a start guess (sc_fixed_points_find, branch.h),
 * and the graph of f^m against d with the diagonal. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "cli/tasks.h"
#include "slipcont/branch.h"

static const sc_key_info fp_keys[] = {
    {"period", SC_KEY_INT, 0, "1", 1, 100000, 0, 0, NULL,
     "m: orbits of minimal period m (fixed points of f^m)"},
    {"from", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "lower end of the d interval searched"},
    {"to", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "upper end of the d interval searched (> from)"},
    {"steps", SC_KEY_INT, 0, "1001", 2, 100000000, 0, 0, NULL,
     "initial scan grid, both ends included; itinerary changes between "
     "grid points are located by bisection"},
};

static int fp_check(const sc_scene *s, sc_msg *msg) {
  if (!(sc_scene_real(s, "from") < sc_scene_real(s, "to")))
    return sc_scene_fail_key(s, "task", "to", msg,
                             "to = %s is not above from = %s (valid: to > "
                             "from)",
                             sc_scene_text(s, "to"), sc_scene_text(s, "from"));
  return SC_OK;
}

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int fp_run(sc_cli_run *r) {
  const sc_scene *s = r->scene;
  sc_map *m = r->map;
  sc_fixed_points_spec sp = {.period = (int)sc_scene_int(s, "period"),
                             .from = sc_scene_real(s, "from"),
                             .to = sc_scene_real(s, "to"),
                             .steps = (size_t)sc_scene_int(s, "steps")};
  unsigned long ev0 = sc_map_nevals(m);
  double t0 = now();
  sc_orbit_set *set = NULL;
  /* The search cannot be stopped from outside: a signal during it ends
   * the process after SC_CLI_STOP_GRACE_S (tasks.h), before any file is
   * opened; one that arrived by the time it returns stops here. */
  int st = sc_fixed_points_find(m, &sp, &set, r->msg);
  if (!st && sc_cli_interrupted()) {
    sc_orbit_set_free(set);
    return sc_fail(r->msg, SC_ECALLBACK, "interrupted");
  }
  if (st) return st;
  double elapsed = now() - t0;
  unsigned long nev = sc_map_nevals(m) - ev0;
  size_t n = sc_orbit_set_count(set), nstable = 0, nfam = 0;
  sc_file *csv = NULL, *sum = NULL, *gp = NULL;
  if ((st = sc_cli_open(r, "orbits.csv", &csv))) goto done;
  FILE *f = sc_file_stream(csv);
  fputs("period,multiplier,stable,d,itinerary\n", f);
  sc_orbit_info o;
  for (size_t i = 0; i < n; i++) {
    sc_orbit_set_get(set, i, &o);
    fprintf(f, "%d,", o.period);
    sc_csv_double(f, o.multiplier);
    if (o.neutral) {
      /* A family: the d-interval of the piece holding it. */
      fputs(",family,", f);
      sc_csv_double(f, o.lo);
      fputs("..", f);
      sc_csv_double(f, o.hi);
      nfam++;
    } else {
      fprintf(f, ",%s,", o.stable ? "yes" : "no");
      for (int k = 0; k < o.period; k++) {
        if (k) fputc(';', f);
        sc_csv_double(f, o.d[k]);
      }
      nstable += (size_t)o.stable;
    }
    char itin[4096];
    snprintf(itin, sizeof itin, "%s", o.itinerary);
    fprintf(f, ",%s\n", sc_cli_csv_text(itin));
  }
  st = sc_cli_commit(r, "orbits.csv", csv);
  csv = NULL;
  if (st) goto done;

  /* The orbit points on the diagonal, for the plot. */
  if ((st = sc_cli_open(r, "fixed-point-orbits.csv", &csv))) goto done;
  f = sc_file_stream(csv);
  fputs("d,d,stable,orbit\n", f);
  for (size_t i = 0; i < n; i++) {
    sc_orbit_set_get(set, i, &o);
    if (o.neutral) continue;
    for (int k = 0; k < o.period; k++) {
      sc_csv_double(f, o.d[k]);
      fputc(',', f);
      sc_csv_double(f, o.d[k]);
      fprintf(f, ",%d,%zu\n", o.stable, i + 1);
    }
  }
  st = sc_cli_commit(r, "fixed-point-orbits.csv", csv);
  csv = NULL;
  if (st) goto done;

  /* The graph of f^m over the interval, with the diagonal. */
  size_t gsteps = sp.steps < 2001 ? 2001 : sp.steps > 20001 ? 20001 : sp.steps;
  if ((st = sc_cli_write_map_graph(r, "fixed-point-map.csv", sp.period,
                                   sp.from, sp.to, gsteps)))
    goto done;

  if ((st = sc_cli_summary_begin(r, &sum))) goto done;
  f = sc_file_stream(sum);
  fprintf(f, "  period-%d orbits in [%.17g, %.17g]: %zu isolated (%zu "
             "stable), %zu neutral families\n",
          sp.period, sp.from, sp.to, n - nfam, nstable, nfam);
  for (size_t i = 0; i < n; i++) {
    sc_orbit_set_get(set, i, &o);
    if (o.neutral)
      fprintf(f, "    family: d in [%.17g, %.17g], multiplier exactly 1\n",
              o.lo, o.hi);
    else
      fprintf(f, "    d = %.17g, multiplier %.17g (%s), residual %.3g\n",
              o.d[0], o.multiplier, o.stable ? "stable" : "unstable",
              o.residual);
  }
  fprintf(f, "  pieces of constant itinerary: %zu\n",
          sc_orbit_set_npieces(set));
  fprintf(f, "  roots of lower period skipped: %zu\n",
          sc_orbit_set_nlower(set));
  fprintf(f, "  points where the map is undefined: %zu\n",
          sc_orbit_set_nundefined(set));
  fprintf(f, "  map evaluations: %lu; time %.3f s\n", nev, elapsed);
  st = sc_cli_commit(r, "summary.txt", sum);
  sum = NULL;
  if (st) goto done;

  if ((st = sc_cli_open(r, "fixed-point.gp", &gp))) goto done;
  f = sc_file_stream(gp);
  char title[512], full[640], ylab[64];
  sc_plot_title(m, NULL, title, sizeof title);
  snprintf(full, sizeof full, "f^{%d}: %zu period-%d orbits (%s)", sp.period,
           n, sp.period, title);
  const char *xl = sc_plot_label(m, sc_map_type(m)->state_name);
  snprintf(ylab, sizeof ylab, "f^{%d}(%s)", sp.period,
           sc_map_type(m)->state_name);
  sc_plot_head(f, "fixed-point.png", full, xl, ylab);
  fprintf(f, "set xrange [%.17g:%.17g]\n", sp.from, sp.to);
  fputs("set key inside left top box opaque\n", f);
  fputs("stab(c) = column(3) == 1 ? column(c) : NaN\n", f);
  fputs("unst(c) = column(3) == 0 ? column(c) : NaN\n", f);
  fprintf(f, "plot 'fixed-point-map.csv' skip 1 using 1:2 with lines lw 1.5 "
             "lc rgb '#1f4e9e' title 'f^{%d}', \\\n",
          sp.period);
  fputs("     x with lines dt 2 lc rgb '#777777' title 'diagonal', \\\n", f);
  fputs("     'fixed-point-orbits.csv' skip 1 using 1:(stab(2)) with points "
        "pt 7 ps 1.6 lc rgb '#2ca02c' title 'stable orbit points', \\\n",
        f);
  fputs("     'fixed-point-orbits.csv' skip 1 using 1:(unst(2)) with points "
        "pt 6 ps 1.6 lw 2 lc rgb '#d62728' title 'unstable orbit points'\n",
        f);
  st = sc_cli_commit(r, "fixed-point.gp", gp);
  gp = NULL;
  if (st) goto done;
  st = sc_cli_add_plot(r, "fixed-point.gp", "fixed-point.png");
  sc_cli_note(r, "%zu period-%d orbits (%zu stable, %zu families) in %.3f s",
              n - nfam, sp.period, nstable, nfam, elapsed);
done:
  sc_file_abort(csv);
  sc_file_abort(sum);
  sc_file_abort(gp);
  sc_orbit_set_free(set);
  return st;
}

const sc_cli_task sc_cli_task_fixed_point = {
    .type = {.kind = "fixed-point",
             .doc = "every period-m orbit in an interval of d, without a "
                    "start guess: pieces of constant itinerary, brackets, "
                    "Newton",
             .keys = fp_keys,
             .nkeys = sizeof fp_keys / sizeof fp_keys[0],
             .check = fp_check},
    .outputs = "orbits.csv (period,multiplier,stable,d,itinerary), "
               "fixed-point-map.csv, fixed-point-orbits.csv, summary.txt, fixed-point.gp, "
               "fixed-point.png",
    .run = fp_run,
};
