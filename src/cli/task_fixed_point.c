/* Task `fixed-point`: every period-m orbit in an interval of d at fixed
 * parameters, without a start guess (sc_fixed_points_find, orbits.h),
 * and the graph of f^m against d with the diagonal. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/progress.h"
#include "cli/tasks.h"
#include "cli/task_fixed_point_n.h"
#include "slipcont/orbits.h"

/* Highest period searched (the library's limit, sc_fixed_points_find). */
#define FP_MAX_PERIOD 100000

static const sc_key_info fp_keys[] = {
    {"period", SC_KEY_TEXT, 0, "1", 0, 0, 0, 0, NULL,
     "m, or a range m1..m2 (1 <= m1 <= m2 <= 100000; n > 1: <= 1000): "
     "orbits of minimal period m (fixed points of f^m); over a range every "
     "orbit once, at its minimal period, with a count per period"},
    {"from", SC_KEY_STATE, 0, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "lower end of the d interval searched; n > 1: the box's lower corner "
     "(n numbers).  Required, but for n > 1 with d0"},
    {"to", SC_KEY_STATE, 0, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "upper end of the d interval searched (> from); n > 1: the box's upper "
     "corner (each component > from's).  Required, but for n > 1 with d0"},
    {"steps", SC_KEY_INT, 0, NULL, 2, 100000000, 0, 0, NULL,
     "initial scan grid, both ends included (1001); itinerary changes "
     "between grid points are located by bisection.  n > 1: grid points per "
     "axis of the box (21), every one a Newton start"},
    {"d0", SC_KEY_STATE, 0, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "n > 1 only: a start guess; Newton from it alone (no box, grid or "
     "attractor starts)"},
    {"attractor", SC_KEY_INT, 0, NULL, 0, 10000000, 0, 0, NULL,
     "n > 1 only: starts on the attractor, the iterates of a few grid "
     "points after the transient (1000)"},
    {"transient", SC_KEY_INT, 0, NULL, 0, 100000000, 0, 0, NULL,
     "n > 1 only: iterates before the attractor starts are taken (1000)"},
    {"shooting", SC_KEY_CHOICE, 0, NULL, 0, 0, 0, 0, "single|multiple",
     "n > 1 only: Newton on f^m(x) - x (single) or on the m orbit points "
     "(multiple, block-sparse; the default)"},
};

/* Default of `steps` for a one-dimensional model (the key has no
 * default of its own since n > 1 reads it per axis). */
#define FP_STEPS_1D 1001

/* `period`: "m" or "m1..m2" into [*lo, *hi]; SC_OK or SC_EINVAL. */
static int parse_periods(const char *text, long *lo, long *hi) {
  const char *dots = strstr(text, "..");
  char a[32];
  if (!dots) {
    if (sc_parse_long(text, 1, FP_MAX_PERIOD, lo)) return SC_EINVAL;
    *hi = *lo;
    return SC_OK;
  }
  size_t n = (size_t)(dots - text);
  if (n == 0 || n >= sizeof a) return SC_EINVAL;
  memcpy(a, text, n);
  a[n] = '\0';
  if (sc_parse_long(a, 1, FP_MAX_PERIOD, lo) ||
      sc_parse_long(dots + 2, 1, FP_MAX_PERIOD, hi) || *hi < *lo)
    return SC_EINVAL;
  return SC_OK;
}

/* A required key left out: the message of a missing required key. */
static int fp_missing(const sc_scene *s, const char *key, sc_msg *msg) {
  sc_key_info one = {key, SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL,
                     1, 1, NULL, NULL};
  char range[128];
  sc_key_range_text(&one, range, sizeof range);
  return sc_scene_fail_key(s, "task", key, msg,
                           "missing required key '%s' (valid: %s)", key,
                           range);
}

static int fp_check(const sc_scene *s, sc_msg *msg) {
  long lo, hi;
  int bad = parse_periods(sc_scene_text(s, "period"), &lo, &hi);
  if (sc_map_dim(sc_scene_map(s)) > 1)
    return sc_fpn_check(s, bad ? -1 : lo, bad ? -1 : hi, msg);
  static const char *const nd_only[] = {"d0", "attractor", "transient",
                                        "shooting"};
  for (size_t i = 0; i < sizeof nd_only / sizeof nd_only[0]; i++)
    if (sc_scene_value(s, "task", nd_only[i]))
      return sc_scene_fail_key(s, "task", nd_only[i], msg,
                               "%s is a key of models of n > 1 dimensions; "
                               "model %s is one-dimensional and searched "
                               "by pieces of itinerary (valid: leave it out)",
                               nd_only[i], sc_map_type(sc_scene_map(s))->name);
  if (!sc_scene_value(s, "task", "from")) return fp_missing(s, "from", msg);
  if (!sc_scene_value(s, "task", "to")) return fp_missing(s, "to", msg);
  if (bad)
    return sc_scene_fail_key(s, "task", "period", msg,
                             "period = %s (valid: m in [1, %d], or m1..m2 "
                             "with 1 <= m1 <= m2 <= %d)",
                             sc_scene_text(s, "period"), FP_MAX_PERIOD,
                             FP_MAX_PERIOD);
  if (!(sc_scene_real(s, "from") < sc_scene_real(s, "to")))
    return sc_scene_fail_key(s, "task", "to", msg,
                             "to = %s is not above from = %s (valid: to > "
                             "from)",
                             sc_scene_text(s, "to"), sc_scene_text(s, "from"));
  return SC_OK;
}

/* What one period's search found. */
typedef struct {
  sc_orbit_set *set;
  size_t n, nstable, nfam; /* orbits, stable ones, neutral families */
} fp_period;

/* One search over the periods lo..hi: the orbits found, the counts. */
typedef struct {
  sc_fixed_points_spec sp; /* sp.period: the one being searched */
  long lo, hi;             /* the periods */
  fp_period *per;          /* hi - lo + 1 */
  size_t n, nstable, nfam; /* totals */
  unsigned long nev;       /* map evaluations of the search */
  double elapsed;          /* its seconds */
  sc_fpn_job nd;           /* n > 1: the n-dimensional search */
} fp_job;

static int fp_prepare(sc_cli_run *r, void *job) {
  fp_job *j = job;
  const sc_scene *s = r->scene;
  parse_periods(sc_scene_text(s, "period"), &j->lo, &j->hi); /* checked */
  if (sc_map_dim(r->map) > 1) return sc_fpn_prepare(r, j->lo, j->hi, &j->nd);
  j->sp = (sc_fixed_points_spec){.period = (int)j->lo,
                                 .from = sc_scene_real(s, "from"),
                                 .to = sc_scene_real(s, "to"),
                                 .steps = FP_STEPS_1D};
  if (sc_scene_value(s, "task", "steps"))
    j->sp.steps = (size_t)sc_scene_int(s, "steps");
  j->per = calloc((size_t)(j->hi - j->lo + 1), sizeof *j->per);
  if (!j->per) return sc_fail(r->msg, SC_ENOMEM, "fixed-point: out of memory");
  return SC_OK;
}

/* The search cannot be stopped from outside within one period: a signal
 * during it ends the process after SC_CLI_STOP_GRACE_S (tasks.h), before
 * any file is opened; between periods the run stops by itself. */
static int fp_compute(sc_cli_run *r, void *job) {
  fp_job *j = job;
  if (sc_map_dim(r->map) > 1) return sc_fpn_compute(r, &j->nd);
  unsigned long ev0 = sc_map_nevals(r->map);
  double t0 = sc_progress_now();
  for (long m = j->lo; m <= j->hi; m++) {
    int st = sc_cli_stop(r);
    fp_period *P = &j->per[m - j->lo];
    j->sp.period = (int)m;
    if (!st) st = sc_fixed_points_find(r->map, &j->sp, &P->set, r->msg);
    if (st) return st;
    /* The search reports an orbit only at its minimal period (families
     * too), so over a range each orbit is listed once. */
    size_t n = sc_orbit_set_count(P->set);
    sc_orbit_info o;
    for (size_t i = 0; i < n; i++) {
      sc_orbit_set_get(P->set, i, &o);
      P->n++;
      P->nfam += (size_t)o.neutral;
      P->nstable += (size_t)(!o.neutral && o.stable);
    }
    j->n += P->n;
    j->nfam += P->nfam;
    j->nstable += P->nstable;
  }
  j->sp.period = (int)j->lo;
  j->elapsed = sc_progress_now() - t0;
  j->nev = sc_map_nevals(r->map) - ev0;
  return SC_OK;
}

/* orbits.csv: one row an orbit (a family: its piece's d-interval), by
 * period, then by smallest point. */
static int write_orbits(sc_cli_run *r, const fp_job *j) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "orbits.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("period,multiplier,stable,d,itinerary\n", f);
  sc_orbit_info o;
  for (long m = j->lo; m <= j->hi; m++) {
    const fp_period *P = &j->per[m - j->lo];
    for (size_t i = 0; i < sc_orbit_set_count(P->set); i++) {
      sc_orbit_set_get(P->set, i, &o);
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
  }
  return sc_cli_commit(r, "orbits.csv", csv);
}

/* periods.csv: the count of each period searched. */
static int write_counts(sc_cli_run *r, const fp_job *j) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "periods.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("period,orbits,stable,unstable,families,lower_period_roots\n", f);
  for (long m = j->lo; m <= j->hi; m++) {
    const fp_period *P = &j->per[m - j->lo];
    size_t iso = P->n - P->nfam;
    fprintf(f, "%ld,%zu,%zu,%zu,%zu,%zu\n", m, iso, P->nstable,
            iso - P->nstable, P->nfam,
            sc_orbit_set_nlower(P->set));
  }
  return sc_cli_commit(r, "periods.csv", csv);
}

/* The orbit points on the diagonal, for the plot. */
static int write_diagonal(sc_cli_run *r, const fp_job *j) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "fixed-point-orbits.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("d,d,stable,orbit,period\n", f);
  sc_orbit_info o;
  size_t num = 0;
  for (long m = j->lo; m <= j->hi; m++) {
    const fp_period *P = &j->per[m - j->lo];
    for (size_t i = 0; i < sc_orbit_set_count(P->set); i++) {
      num++;
      sc_orbit_set_get(P->set, i, &o);
      if (o.neutral) continue;
      for (int k = 0; k < o.period; k++) {
        sc_csv_double(f, o.d[k]);
        fputc(',', f);
        sc_csv_double(f, o.d[k]);
        fprintf(f, ",%d,%zu,%d\n", o.stable, num, o.period);
      }
    }
  }
  return sc_cli_commit(r, "fixed-point-orbits.csv", csv);
}

static int fp_write(sc_cli_run *r, void *job) {
  const fp_job *j = job;
  if (sc_map_dim(r->map) > 1) return sc_fpn_write(r, &j->nd);
  const sc_fixed_points_spec *sp = &j->sp;
  int st = write_orbits(r, j);
  if (!st) st = write_counts(r, j);
  if (!st) st = write_diagonal(r, j);
  /* The graph of f^m over the interval, with the diagonal (one period). */
  size_t gsteps = sp->steps < 2001    ? 2001
                  : sp->steps > 20001 ? 20001
                                      : sp->steps;
  if (!st && j->lo == j->hi)
    st = sc_cli_write_map_graph(r, "fixed-point-map.csv", sp->period,
                                sp->from, sp->to, gsteps);
  return st;
}

static int fp_summary(sc_cli_run *r, void *job, FILE *f) {
  const fp_job *j = job;
  if (sc_map_dim(r->map) > 1) return sc_fpn_summary(r, &j->nd, f);
  if (j->lo == j->hi)
    fprintf(f, "  period-%ld orbits in [%.17g, %.17g]: %zu isolated (%zu "
               "stable), %zu neutral families\n",
            j->lo, j->sp.from, j->sp.to, j->n - j->nfam, j->nstable, j->nfam);
  else
    fprintf(f, "  orbits of minimal periods %ld..%ld in [%.17g, %.17g], each "
               "once: %zu isolated (%zu stable), %zu neutral families\n",
            j->lo, j->hi, j->sp.from, j->sp.to, j->n - j->nfam, j->nstable,
            j->nfam);
  size_t npieces = 0, nlower = 0, nundef = 0;
  sc_orbit_info o;
  for (long m = j->lo; m <= j->hi; m++) {
    const fp_period *P = &j->per[m - j->lo];
    if (j->lo != j->hi)
      fprintf(f, "  period %ld: %zu orbits (%zu stable), %zu neutral "
                 "families\n",
              m, P->n - P->nfam, P->nstable, P->nfam);
    for (size_t i = 0; i < sc_orbit_set_count(P->set); i++) {
      sc_orbit_set_get(P->set, i, &o);
      if (o.neutral)
        fprintf(f, "    family: d in [%.17g, %.17g], multiplier exactly 1\n",
                o.lo, o.hi);
      else
        fprintf(f, "    d = %.17g, multiplier %.17g (%s), residual %.3g\n",
                o.d[0], o.multiplier, o.stable ? "stable" : "unstable",
                o.residual);
    }
    npieces += sc_orbit_set_npieces(P->set);
    nlower += sc_orbit_set_nlower(P->set);
    nundef += sc_orbit_set_nundefined(P->set);
  }
  fprintf(f, "  pieces of constant itinerary: %zu\n", npieces);
  fprintf(f, "  roots of lower period skipped: %zu\n", nlower);
  fprintf(f, "  points where the map is undefined: %zu\n", nundef);
  fprintf(f, "  map evaluations: %lu; time %.3f s\n", j->nev, j->elapsed);
  return SC_OK;
}

/* Over a range of periods: the orbit points against their period. */
static int fp_range_plot(sc_cli_run *r, const fp_job *j) {
  sc_map *m = r->map;
  char title[512], full[700];
  sc_plot_title(m, NULL, title, sizeof title);
  snprintf(full, sizeof full, "%zu orbits of periods %ld..%ld (%s)",
           j->n - j->nfam, j->lo, j->hi, title);
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "fixed-point", full,
                             sc_plot_label(m, sc_map_type(m)->state_name),
                             "minimal period", &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fprintf(f, "set xrange [%.17g:%.17g]\nset yrange [%g:%g]\n", j->sp.from,
          j->sp.to, j->lo - 0.5, j->hi + 0.5);
  /* one tic a period while they can be read */
  if (j->hi - j->lo <= 24) fputs("set ytics 1\n", f);
  fputs("set grid ytics\nset key outside right top box opaque\n", f);
  fputs("stab(c) = column(3) == 1 ? column(c) : NaN\n", f);
  fputs("unst(c) = column(3) == 0 ? column(c) : NaN\n", f);
  fputs("plot 'fixed-point-orbits.csv' skip 1 using 1:(stab(5)) with points "
        "pt 7 ps 1.4 lc rgb '#2ca02c' title 'stable orbit points', \\\n",
        f);
  fputs("     'fixed-point-orbits.csv' skip 1 using 1:(unst(5)) with points "
        "pt 6 ps 1.4 lw 2 lc rgb '#d62728' title 'unstable orbit points'\n",
        f);
  return sc_cli_plot_end(r, "fixed-point", gp);
}

static int fp_plots(sc_cli_run *r, void *job) {
  const fp_job *j = job;
  if (sc_map_dim(r->map) > 1) return sc_fpn_plots(r, &j->nd);
  if (j->lo != j->hi) return fp_range_plot(r, j);
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
  if (sc_map_dim(r->map) > 1) return sc_fpn_report(r, &j->nd);
  if (j->lo == j->hi)
    sc_cli_note(r, "%zu period-%ld orbits (%zu stable, %zu families) in "
                   "%.3f s",
                j->n - j->nfam, j->lo, j->nstable, j->nfam, j->elapsed);
  else
    sc_cli_note(r, "%zu orbits of periods %ld..%ld (%zu stable, %zu "
                   "families) in %.3f s",
                j->n - j->nfam, j->lo, j->hi, j->nstable, j->nfam,
                j->elapsed);
  return SC_OK;
}

static void fp_release(sc_cli_run *r, void *job) {
  fp_job *j = job;
  (void)r;
  sc_fpn_release(&j->nd);
  for (long m = j->lo; j->per && m <= j->hi; m++) {
    sc_orbit_set_free(j->per[m - j->lo].set);
  }
  free(j->per);
}

const sc_cli_task sc_cli_task_fixed_point = {
    .type = {.kind = "fixed-point",
             .doc = "every orbit of period m (or of each period of a range "
                    "m1..m2) in an interval of d, without a start guess: "
                    "pieces of constant itinerary, brackets, Newton; n > 1: "
                    "Newton from a grid of a box and from the attractor "
                    "with the orbits found deflated, or from d0",
             .keys = fp_keys,
             .nkeys = sizeof fp_keys / sizeof fp_keys[0],
             .check = fp_check},
    .outputs = "orbits.csv (period,multiplier,stable,d,itinerary), "
               "periods.csv (period,orbits,stable,unstable,families,"
               "lower_period_roots), fixed-point-map.csv (one period: the "
               "graph of f^m), fixed-point-orbits.csv, summary.txt, "
               "fixed-point.gp, fixed-point.png; n > 1: orbits.csv "
               "(period,multiplier,multipliers,stable,residual,start_*,"
               "points), periods.csv (period,orbits,stable,unstable,starts,"
               "known,lower_period,outside_box,failed), "
               "fixed-point-orbits.csv, summary.txt, fixed-point.gp/png "
               "(n = 2: the orbit points in the plane)",
    .job_size = sizeof(fp_job),
    .prepare = fp_prepare,
    .compute = fp_compute,
    .write = fp_write,
    .summary = fp_summary,
    .plots = fp_plots,
    .report = fp_report,
    .release = fp_release,
};
