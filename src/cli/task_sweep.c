/* Task `sweep`: a brute-force one-parameter bifurcation diagram
 * (figs 5.6, 5.8, 5.12), computed by sc_sweep (analysis.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/progress.h"
#include "cli/tasks.h"
#include "slipcont/analysis.h"
#include "slipcont/period.h"

static const sc_key_info sweep_keys[] = {
    {"parameter", SC_KEY_PARAM, 1, NULL, 0, 0, 0, 0, NULL,
     "the model parameter swept (bk2: alpha, beta, phi or v)"},
    {"from", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "first grid value (inside the parameter's range)"},
    {"to", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "last grid value (inside the parameter's range; may be below from)"},
    {"steps", SC_KEY_INT, 0, "1001", 1, 10000000, 0, 0, NULL,
     "grid points, both ends included (1: from only)"},
    {"x-scale", SC_KEY_CHOICE, 0, "linear", 0, 0, 0, 0, "linear|log",
     "grid spacing: equal differences, or equal ratios (log; from and to "
     "of one sign), drawn on a log axis"},
    {"iterations", SC_KEY_INT, 0, "300", 1, 100000000, 0, 0, NULL,
     "map iterates at each parameter value"},
    {"keep", SC_KEY_INT, 0, "100", 1, 100000000, 0, 0, NULL,
     "last iterates kept and drawn (<= iterations)"},
    {"d0", SC_KEY_STATE, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "initial state (bk2: d = Y2 - Y1 of the first global stick phase)"},
    {"direction", SC_KEY_CHOICE, 0, NULL, 0, 0, 0, 0, "up|down|both",
     "up: increasing parameter, down: decreasing, both: up then down "
     "(default: from towards to)"},
    {"seed", SC_KEY_CHOICE, 0, "fixed", 0, 0, 0, 0, "fixed|previous",
     "each value starts from d0 (fixed; parallel), or from the final state "
     "of the previous value (previous)"},
    SC_CLI_SHOW_KEY,
};

/* Most kept values held in memory (8 bytes each): 4 GiB. */
#define SWEEP_MAX_VALUES 536870912.0

static int sweep_check(const sc_scene *s, sc_msg *msg) {
  int st = sc_cli_check_param_ends(s, msg);
  if (st) return st;
  int show;
  if ((st = sc_cli_show(s, &show, msg))) return st;
  const char *xs = sc_scene_text(s, "x-scale");
  if (xs && strcmp(xs, "log") == 0 &&
      sc_grid_check("x-scale", sc_scene_real(s, "from"), sc_scene_real(s, "to"),
                    SC_GRID_LOG, NULL))
    return sc_scene_fail_key(s, "task", "x-scale", msg,
                             "x-scale = log needs from and to of one sign and "
                             "not 0 (from %s, to %s)",
                             sc_scene_text(s, "from"), sc_scene_text(s, "to"));
  long it = sc_scene_int(s, "iterations"), keep = sc_scene_int(s, "keep");
  if (keep > it)
    return sc_scene_fail_key(s, "task", "keep", msg,
                             "keep = %ld is more than iterations = %ld "
                             "(valid: [1, iterations])",
                             keep, it);
  const char *dir = sc_scene_text(s, "direction");
  double passes = dir && strcmp(dir, "both") == 0 ? 2 : 1;
  double values = passes * (double)sc_scene_int(s, "steps") * (double)keep;
  if (values > SWEEP_MAX_VALUES)
    return sc_scene_fail_key(s, "task", "steps", msg,
                             "steps x keep%s = %.0f values is too many "
                             "(valid: at most %.0f)",
                             passes > 1 ? " x 2" : "", values,
                             SWEEP_MAX_VALUES);
  return SC_OK;
}

static int on_progress(void *ctx, size_t done, size_t total) {
  (void)total;
  sc_progress_update(ctx, (long)done);
  return sc_cli_interrupted();
}

static const char *dir_name(int d) { return d == SC_SWEEP_DOWN ? "down" : "up"; }

/* Runs of equal period along each pass, for the summary. */
static void write_findings(FILE *f, const sc_sweep *sw, const char *pname) {
  size_t n = sc_sweep_npoints(sw);
  /* seen[period + 2]: -2 not settled, -1 undefined, 0 none, 1..max */
  int seen[SC_SWEEP_PERIOD_MAX + 3] = {0};
  sc_sweep_point a, b;
  fprintf(f, "  parameter values: %zu points; map undefined at %zu\n", n,
          sc_sweep_nundefined(sw));
  if (sc_sweep_nundefined(sw))
    fprintf(f, "  first undefined: %s\n", sc_sweep_undefined_reason(sw));
  fputs("  period by parameter range (0: none found up to 16, i.e. chaos "
        "or a longer period; -1: map undefined; -2: not settled, still "
        "converging after the iterations):\n",
        f);
  size_t i = 0;
  while (i < n) {
    sc_sweep_get_point(sw, i, &a);
    size_t j = i;
    while (j + 1 < n) {
      sc_sweep_get_point(sw, j + 1, &b);
      if (b.direction != a.direction || b.period != a.period) break;
      j++;
    }
    sc_sweep_get_point(sw, j, &b);
    fprintf(f, "    %-4s %s from %.10g to %.10g (%zu values): period %d\n",
            dir_name(a.direction), pname, a.p, b.p, j - i + 1, a.period);
    if (a.period >= SC_PERIOD_UNSETTLED && a.period <= SC_SWEEP_PERIOD_MAX)
      seen[a.period + 2] = 1;
    i = j + 1;
  }
  fputs("  periods seen:", f);
  for (int p = SC_PERIOD_UNSETTLED; p <= SC_SWEEP_PERIOD_MAX; p++)
    if (seen[p + 2]) fprintf(f, " %d", p);
  fputc('\n', f);
}

/* One sweep run: its spec, the sweep, its progress bar. */
typedef struct {
  const char *pname; /* the parameter swept */
  size_t n;          /* state components */
  int show;          /* what the plot draws (sc_cli_show()) */
  double x0[SC_MAXDIM]; /* d0 of a map of n > 1 components */
  sc_sweep_spec sp;
  sc_sweep *sw;
  sc_progress bar;
} sweep_job;

static int sweep_prepare(sc_cli_run *r, void *job) {
  sweep_job *j = job;
  const sc_scene *s = r->scene;
  sc_sweep_spec *sp = &j->sp;
  j->pname = sc_scene_text(s, "parameter");
  sp->param = (size_t)sc_map_param_index(r->map, j->pname);
  sp->from = sc_scene_real(s, "from");
  sp->to = sc_scene_real(s, "to");
  sp->steps = (size_t)sc_scene_int(s, "steps");
  sp->x_scale = strcmp(sc_scene_text(s, "x-scale"), "log") == 0
                    ? SC_GRID_LOG
                    : SC_GRID_LINEAR;
  sp->iterations = (int)sc_scene_int(s, "iterations");
  sp->keep = (int)sc_scene_int(s, "keep");
  j->n = sc_map_dim(r->map);
  if (j->n > 1) {
    sc_scene_state(s, "d0", j->x0, SC_MAXDIM);
    sp->x0 = j->x0;
    sp->d0 = j->x0[0];
  } else {
    sp->d0 = sc_scene_real(s, "d0");
  }
  int st = sc_cli_show(s, &j->show, r->msg);
  if (st) return st;
  const char *dir = sc_scene_text(s, "direction");
  if (!dir) sp->direction = sp->to >= sp->from ? SC_SWEEP_UP : SC_SWEEP_DOWN;
  else if (strcmp(dir, "both") == 0) sp->direction = SC_SWEEP_BOTH;
  else if (strcmp(dir, "down") == 0) sp->direction = SC_SWEEP_DOWN;
  else sp->direction = SC_SWEEP_UP;
  sp->seed = strcmp(sc_scene_text(s, "seed"), "previous") == 0
                 ? SC_SEED_PREVIOUS
                 : SC_SEED_FIXED;
  sp->progress = on_progress;
  sp->progress_ctx = &j->bar;
  return sc_sweep_alloc(r->map, sp, &j->sw, r->msg);
}

static int sweep_compute(sc_cli_run *r, void *job) {
  sweep_job *j = job;
  sc_progress_start(&j->bar, "values", (long)sc_sweep_npoints(j->sw), 0,
                    sc_progress_wanted(r->quiet));
  int st = sc_sweep_run(j->sw, r->msg);
  sc_progress_finish(&j->bar);
  if (st == SC_ECALLBACK) sc_fail(r->msg, st, "interrupted");
  return st;
}

static int sweep_write(sc_cli_run *r, void *job) {
  const sweep_job *j = job;
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "sweep.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  if (j->n > 1) {
    fprintf(f, "%s,", j->pname);
    sc_csv_state_header(f, r->map, "");
    fputs(",period,direction\n", f);
  } else {
    fprintf(f, "%s,d,period,direction\n", j->pname);
  }
  size_t n = sc_sweep_npoints(j->sw);
  sc_sweep_point pt;
  for (size_t i = 0; i < n; i++) {
    if ((st = sc_cli_stop(r))) return st;
    sc_sweep_get_point(j->sw, i, &pt);
    if (pt.status != SC_OK) {
      sc_csv_double(f, pt.p);
      for (size_t c = 0; c < j->n; c++) fputs(",nan", f);
      fprintf(f, ",%d,%s\n", SC_SWEEP_UNDEFINED, dir_name(pt.direction));
      continue;
    }
    for (int k = 0; k < pt.nd; k++) {
      sc_csv_double(f, pt.p);
      fputc(',', f);
      sc_csv_state(f, pt.d + (size_t)k * pt.dim, pt.dim);
      fprintf(f, ",%d,%s\n", pt.period, dir_name(pt.direction));
    }
  }
  return sc_cli_commit(r, "sweep.csv", csv);
}

static int sweep_summary(sc_cli_run *r, void *job, FILE *f) {
  const sweep_job *j = job;
  (void)r;
  fprintf(f, "  passes: %s; seed: %s\n",
          j->sp.direction == SC_SWEEP_BOTH ? "up then down"
                                           : dir_name(j->sp.direction),
          j->sp.seed == SC_SEED_PREVIOUS ? "previous" : "fixed");
  write_findings(f, j->sw, j->pname);
  fprintf(f, "  map evaluations: %lu\n", sc_sweep_nevals(j->sw));
  return SC_OK;
}

static int sweep_plots(sc_cli_run *r, void *job) {
  const sweep_job *j = job;
  const sc_sweep_spec *sp = &j->sp;
  sc_map *m = r->map;
  char title[512], key[2][96], yl[96];
  const char *xl = sc_plot_label(m, j->pname);
  sc_plot_title(m, j->pname, title, sizeof title);
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "sweep", title, xl,
                             j->n > 1 ? sc_cli_show_label(m, j->show, yl,
                                                          sizeof yl)
                                      : sc_plot_label(m, sc_map_type(m)->state_name),
                             &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fprintf(f, "set xrange [%.17g:%.17g]\n", fmin(sp->from, sp->to),
          fmax(sp->from, sp->to));
  if (sp->x_scale == SC_GRID_LOG) fputs("set logscale x\n", f);
  else sc_plot_axis_format(f, "x", fmin(sp->from, sp->to), fmax(sp->from, sp->to));
  snprintf(key[0], sizeof key[0], "increasing %s", xl);
  snprintf(key[1], sizeof key[1], "decreasing %s", xl);
  if (j->n > 1) {
    /* columns: the parameter, the n components, period, direction */
    char use[512];
    sc_cli_show_using(j->show, j->n, 2, use, sizeof use);
    fprintf(f, "# column %zu is the direction of the pass: up or down; the up "
               "pass is drawn\n# first with larger points so that both stay "
               "visible where they agree\n",
            j->n + 3);
    fprintf(f, "# what is drawn of the state (show): %s\n", use);
    fprintf(f, "shown(c) = %s%s%s\n", j->show == SC_CLI_SHOW_NORM ? "" : "column(",
            use, j->show == SC_CLI_SHOW_NORM ? "" : ")");
    fprintf(f, "up(c)   = strcol(%zu) eq 'up'   ? shown(c) : NaN\n", j->n + 3);
    fprintf(f, "down(c) = strcol(%zu) eq 'down' ? shown(c) : NaN\n", j->n + 3);
  } else {
    fputs("# column 4 is the direction of the pass: up or down; the up pass "
          "is drawn\n# first with larger points so that both stay visible "
          "where they agree\n",
          f);
    fputs("up(c)   = strcol(4) eq 'up'   ? column(c) : NaN\n", f);
    fputs("down(c) = strcol(4) eq 'down' ? column(c) : NaN\n", f);
  }
  /* The dots are tiny: the key shows large ones (keyentry). */
  const char *upc = sp->direction == SC_SWEEP_BOTH ? "#6fa8dc" : "#1f4e9e";
  fputs("plot ", f);
  if (sp->direction != SC_SWEEP_DOWN) {
    fprintf(f,
            "'sweep.csv' skip 1 using 1:(up(2)) with points pt 7 ps %s "
            "lc rgb '%s' notitle, \\\n"
            "     keyentry with points pt 7 ps 1.5 lc rgb '%s' title ",
            sp->direction == SC_SWEEP_BOTH ? "0.5" : "0.25", upc, upc);
    sc_plot_quote(f, key[0]);
  }
  if (sp->direction != SC_SWEEP_UP) {
    if (sp->direction != SC_SWEEP_DOWN) fputs(", \\\n     ", f);
    fputs("'sweep.csv' skip 1 using 1:(down(2)) with points pt 7 ps 0.22 "
          "lc rgb '#c00000' notitle, \\\n"
          "     keyentry with points pt 7 ps 1.5 lc rgb '#c00000' title ",
          f);
    sc_plot_quote(f, key[1]);
  }
  fputc('\n', f);
  return sc_cli_plot_end(r, "sweep", gp);
}

static int sweep_report(sc_cli_run *r, void *job) {
  const sweep_job *j = job;
  if (sc_sweep_nundefined(j->sw))
    sc_cli_note(r, "map undefined at %zu parameter values (first: %s)",
                sc_sweep_nundefined(j->sw), sc_sweep_undefined_reason(j->sw));
  return SC_OK;
}

static void sweep_release(sc_cli_run *r, void *job) {
  sweep_job *j = job;
  (void)r;
  sc_sweep_free(j->sw);
}

const sc_cli_task sc_cli_task_sweep = {
    .type = {.kind = "sweep",
             .doc = "brute-force one-parameter bifurcation diagram: iterate "
                    "at each parameter value, keep the tail, find its period",
             .keys = sweep_keys,
             .nkeys = sizeof sweep_keys / sizeof sweep_keys[0],
             .check = sweep_check},
    .outputs = "sweep.csv (PARAMETER,d,period,direction; n > 1: "
               "PARAMETER,d1..dn,period,direction), summary.txt, sweep.gp, "
               "sweep.png",
    .job_size = sizeof(sweep_job),
    .prepare = sweep_prepare,
    .compute = sweep_compute,
    .write = sweep_write,
    .summary = sweep_summary,
    .plots = sweep_plots,
    .report = sweep_report,
    .release = sweep_release,
};
