/* Task `fixed-point`: every period-m orbit in an interval of d at fixed
 * parameters, without a start guess (sc_fixed_points_find, orbits.h),
 * and the graph of f^m against d with the diagonal. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/progress.h"
#include "cli/tasks.h"
#include "slipcont/orbits.h"

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

/* One search: its spec, the orbits found, counts for the notes. */
typedef struct {
  sc_fixed_points_spec sp;
  sc_orbit_set *set;
  size_t n, nstable, nfam; /* orbits, stable ones, neutral families */
  unsigned long nev;       /* map evaluations of the search */
  double elapsed;          /* its seconds */
} fp_job;

static int fp_prepare(sc_cli_run *r, void *job) {
  fp_job *j = job;
  const sc_scene *s = r->scene;
  j->sp = (sc_fixed_points_spec){.period = (int)sc_scene_int(s, "period"),
                                 .from = sc_scene_real(s, "from"),
                                 .to = sc_scene_real(s, "to"),
                                 .steps = (size_t)sc_scene_int(s, "steps")};
  return SC_OK;
}

/* The search cannot be stopped from outside: a signal during it ends the
 * process after SC_CLI_STOP_GRACE_S (tasks.h), before any file is
 * opened; one that arrived by the time it returns stops the driver. */
static int fp_compute(sc_cli_run *r, void *job) {
  fp_job *j = job;
  unsigned long ev0 = sc_map_nevals(r->map);
  double t0 = sc_progress_now();
  int st = sc_fixed_points_find(r->map, &j->sp, &j->set, r->msg);
  if (st) return st;
  j->elapsed = sc_progress_now() - t0;
  j->nev = sc_map_nevals(r->map) - ev0;
  j->n = sc_orbit_set_count(j->set);
  sc_orbit_info o;
  for (size_t i = 0; i < j->n; i++) {
    sc_orbit_set_get(j->set, i, &o);
    j->nfam += (size_t)o.neutral;
    j->nstable += (size_t)(!o.neutral && o.stable);
  }
  return SC_OK;
}

/* orbits.csv: one row an orbit (a family: its piece's d-interval). */
static int write_orbits(sc_cli_run *r, const fp_job *j) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "orbits.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("period,multiplier,stable,d,itinerary\n", f);
  sc_orbit_info o;
  for (size_t i = 0; i < j->n; i++) {
    sc_orbit_set_get(j->set, i, &o);
    fprintf(f, "%d,", o.period);
    sc_csv_double(f, o.multiplier);
    if (o.neutral) {
      fputs(",family,", f);
      sc_csv_double(f, o.lo);
      fputs("..", f);
      sc_csv_double(f, o.hi);
    } else {
      fprintf(f, ",%s,", o.stable ? "yes" : "no");
      for (int k = 0; k < o.period; k++) {
        if (k) fputc(';', f);
        sc_csv_double(f, o.d[k]);
      }
    }
    char itin[4096];
    snprintf(itin, sizeof itin, "%s", o.itinerary);
    fprintf(f, ",%s\n", sc_cli_csv_text(itin));
  }
  return sc_cli_commit(r, "orbits.csv", csv);
}

/* The orbit points on the diagonal, for the plot. */
static int write_diagonal(sc_cli_run *r, const fp_job *j) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "fixed-point-orbits.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("d,d,stable,orbit\n", f);
  sc_orbit_info o;
  for (size_t i = 0; i < j->n; i++) {
    sc_orbit_set_get(j->set, i, &o);
    if (o.neutral) continue;
    for (int k = 0; k < o.period; k++) {
      sc_csv_double(f, o.d[k]);
      fputc(',', f);
      sc_csv_double(f, o.d[k]);
      fprintf(f, ",%d,%zu\n", o.stable, i + 1);
    }
  }
  return sc_cli_commit(r, "fixed-point-orbits.csv", csv);
}

static int fp_write(sc_cli_run *r, void *job) {
  const fp_job *j = job;
  const sc_fixed_points_spec *sp = &j->sp;
  int st = write_orbits(r, j);
  if (!st) st = write_diagonal(r, j);
  /* The graph of f^m over the interval, with the diagonal. */
  size_t gsteps = sp->steps < 2001    ? 2001
                  : sp->steps > 20001 ? 20001
                                      : sp->steps;
  if (!st)
    st = sc_cli_write_map_graph(r, "fixed-point-map.csv", sp->period,
                                sp->from, sp->to, gsteps);
  return st;
}

static int fp_summary(sc_cli_run *r, void *job, FILE *f) {
  const fp_job *j = job;
  (void)r;
  fprintf(f, "  period-%d orbits in [%.17g, %.17g]: %zu isolated (%zu "
             "stable), %zu neutral families\n",
          j->sp.period, j->sp.from, j->sp.to, j->n - j->nfam, j->nstable,
          j->nfam);
  sc_orbit_info o;
  for (size_t i = 0; i < j->n; i++) {
    sc_orbit_set_get(j->set, i, &o);
    if (o.neutral)
      fprintf(f, "    family: d in [%.17g, %.17g], multiplier exactly 1\n",
              o.lo, o.hi);
    else
      fprintf(f, "    d = %.17g, multiplier %.17g (%s), residual %.3g\n",
              o.d[0], o.multiplier, o.stable ? "stable" : "unstable",
              o.residual);
  }
  fprintf(f, "  pieces of constant itinerary: %zu\n",
          sc_orbit_set_npieces(j->set));
  fprintf(f, "  roots of lower period skipped: %zu\n",
          sc_orbit_set_nlower(j->set));
  fprintf(f, "  points where the map is undefined: %zu\n",
          sc_orbit_set_nundefined(j->set));
  fprintf(f, "  map evaluations: %lu; time %.3f s\n", j->nev, j->elapsed);
  return SC_OK;
}

static int fp_plots(sc_cli_run *r, void *job) {
  const fp_job *j = job;
  sc_map *m = r->map;
  int per = j->sp.period;
  char title[512], full[640], ylab[64];
  sc_plot_title(m, NULL, title, sizeof title);
  snprintf(full, sizeof full, "f^{%d}: %zu period-%d orbits (%s)", per, j->n,
           per, title);
  snprintf(ylab, sizeof ylab, "f^{%d}(%s)", per, sc_map_type(m)->state_name);
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "fixed-point", full,
                             sc_plot_label(m, sc_map_type(m)->state_name),
                             ylab, &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fprintf(f, "set xrange [%.17g:%.17g]\n", j->sp.from, j->sp.to);
  sc_plot_axis_format(f, "x", j->sp.from, j->sp.to);
  fputs("stab(c) = column(3) == 1 ? column(c) : NaN\n", f);
  fputs("unst(c) = column(3) == 0 ? column(c) : NaN\n", f);
  fprintf(f, "plot 'fixed-point-map.csv' skip 1 using 1:2 with lines lw 1.5 "
             "lc rgb '#1f4e9e' title 'f^{%d}', \\\n",
          per);
  fputs("     x with lines dt 2 lc rgb '#777777' title 'diagonal', \\\n", f);
  /* the key lists the kinds of orbit present */
  fprintf(f, "     'fixed-point-orbits.csv' skip 1 using 1:(stab(2)) with "
             "points pt 7 ps 1.6 lc rgb '#2ca02c' %s, \\\n",
          j->nstable ? "title 'stable orbit points'" : "notitle");
  fprintf(f, "     'fixed-point-orbits.csv' skip 1 using 1:(unst(2)) with "
             "points pt 6 ps 1.6 lw 2 lc rgb '#d62728' %s\n",
          j->n > j->nstable ? "title 'unstable orbit points'" : "notitle");
  return sc_cli_plot_end(r, "fixed-point", gp);
}

static int fp_report(sc_cli_run *r, void *job) {
  const fp_job *j = job;
  sc_cli_note(r, "%zu period-%d orbits (%zu stable, %zu families) in %.3f s",
              j->n - j->nfam, j->sp.period, j->nstable, j->nfam, j->elapsed);
  return SC_OK;
}

static void fp_release(sc_cli_run *r, void *job) {
  fp_job *j = job;
  (void)r;
  sc_orbit_set_free(j->set);
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
               "fixed-point-map.csv, fixed-point-orbits.csv, summary.txt, "
               "fixed-point.gp, fixed-point.png",
    .job_size = sizeof(fp_job),
    .prepare = fp_prepare,
    .compute = fp_compute,
    .write = fp_write,
    .summary = fp_summary,
    .plots = fp_plots,
    .report = fp_report,
    .release = fp_release,
};
