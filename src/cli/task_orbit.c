/* Task `orbit`: iterate the map from d0 and, for models with continuous
 * motion (bk2), follow the motion itself (fig 5.4). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/tasks.h"
#include "slipcont/analysis.h"

static const sc_key_info orbit_keys[] = {
    {"d0", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "initial state (bk2: d = Y2 - Y1 of the first global stick phase)"},
    {"iterations", SC_KEY_INT, 0, "100", 1, 10000000, 0, 0, NULL,
     "map iterates"},
    {"trajectory", SC_KEY_BOOL, 0, "no", 0, 0, 0, 0, NULL,
     "also write the continuous motion (models with one: bk2)"},
    {"trajectory-iterates", SC_KEY_INT, 0, "0", 0, 10000000, 0, 0, NULL,
     "the trajectory follows the last this many iterates (0: all)"},
    {"dtau", SC_KEY_REAL, 0, "0.01", 0, 1000, 1, 0, NULL,
     "trajectory sampling step in dimensionless time (events are added)"},
};

/* Most rows of trajectory.csv (about 100 bytes each: 500 MB). */
#define TRAJ_MAX_ROWS 5000000L

/* Rows the trajectory will have at least: each iterate has a slip, and a
 * block that slips alone comes back to the driver's speed after about
 * half its period pi / sqrt(1 + alpha) (docs/model.md); so many samples
 * of dtau, whatever the stick phases add. */
static double traj_rows_estimate(const sc_scene *s) {
  const sc_map *m = sc_scene_map(s);
  long it = sc_scene_int(s, "trajectory-iterates");
  if (it == 0) it = sc_scene_int(s, "iterations");
  int ia = sc_map_param_index(m, "alpha");
  double alpha = ia >= 0 ? sc_map_get_param(m, (size_t)ia) : 0;
  const double pi = 3.14159265358979323846;
  return (double)it * (pi / sqrt(1 + alpha)) / sc_scene_real(s, "dtau");
}

/* Iterates summarised at the end: enough for a period up to 16 to repeat
 * several times. */
#define ORBIT_TAIL 128

static int orbit_check(const sc_scene *s, sc_msg *msg) {
  const sc_map *m = sc_scene_map(s);
  if (sc_scene_flag(s, "trajectory") && !sc_map_type(m)->trajectory)
    return sc_scene_fail_key(s, "task", "trajectory", msg,
                             "trajectory = yes: model %s has no continuous "
                             "motion (valid: no)",
                             sc_map_type(m)->name);
  if (sc_scene_int(s, "trajectory-iterates") > sc_scene_int(s, "iterations"))
    return sc_scene_fail_key(s, "task", "trajectory-iterates", msg,
                             "trajectory-iterates = %ld is more than "
                             "iterations = %ld (valid: [0, iterations])",
                             sc_scene_int(s, "trajectory-iterates"),
                             sc_scene_int(s, "iterations"));
  if (sc_scene_flag(s, "trajectory")) {
    double rows = traj_rows_estimate(s);
    if (!(rows <= (double)TRAJ_MAX_ROWS))
      return sc_scene_fail_key(s, "task", "dtau", msg,
                               "dtau = %s: the trajectory would have at least "
                               "%.3g rows (limit %ld, about 500 MB): raise dtau "
                               "or lower trajectory-iterates",
                               sc_scene_text(s, "dtau"), rows, TRAJ_MAX_ROWS);
  }
  return SC_OK;
}

typedef struct {
  FILE *f;
  long rows;
  double y1lo, y1hi, y2lo, y2hi;
} traj_ctx;

static int on_sample(void *ctx, double tau, const double *x, int mode) {
  traj_ctx *c = ctx;
  sc_csv_double(c->f, tau);
  for (int i = 0; i < 4; i++) {
    fputc(',', c->f);
    sc_csv_double(c->f, x[i]);
  }
  fprintf(c->f, ",%d\n", mode);
  c->y1lo = fmin(c->y1lo, x[0]);
  c->y1hi = fmax(c->y1hi, x[0]);
  c->y2lo = fmin(c->y2lo, x[1]);
  c->y2hi = fmax(c->y2hi, x[1]);
  c->rows++;
  return ferror(c->f) || sc_cli_interrupted() || c->rows > TRAJ_MAX_ROWS ? 1
                                                                         : 0;
}

static double param(const sc_map *m, const char *name, double dflt) {
  int i = sc_map_param_index(m, name);
  return i < 0 ? dflt : sc_map_get_param(m, (size_t)i);
}

/* The stuck block's velocity during slips (docs/model.md: V with the driver
 * moving, 0 with it frozen). */
static double stuck_velocity(const sc_map *m) {
  const char *drv = sc_map_get_option(m, "driver");
  return drv && strcmp(drv, "frozen") == 0 ? 0 : param(m, "v", 0);
}

static int write_trajectory_plots(sc_cli_run *r, const traj_ctx *c) {
  sc_map *m = r->map;
  char title[512];
  sc_plot_title(m, NULL, title, sizeof title);
  sc_file *gp = NULL;
  int st = sc_cli_open(r, "phase.gp", &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  sc_plot_head(f, "phase.png", title, "Y_1", "Y_2");
  double a = param(m, "alpha", 1), b = param(m, "beta", 1);
  double dx = fmax(c->y1hi - c->y1lo, c->y2hi - c->y2lo);
  dx = dx > 0 ? 0.08 * dx : 0.1;
  fprintf(f, "set xrange [%.17g:%.17g]\nset yrange [%.17g:%.17g]\n",
          c->y1lo - dx, c->y1hi + dx, c->y2lo - dx, c->y2hi + dx);
  fputs("set size ratio -1\nset key outside right top\n", f);
  fprintf(f, "alpha = %.17g\nbeta = %.17g\n", a, b);
  fputs("# The global stick region: S1 = (1+alpha) Y1 - alpha Y2 <= 1 and\n"
        "# S2 = (1+alpha) Y2 - alpha Y1 <= beta, i.e. s1(Y1) <= Y2 <= s2(Y1)\n"
        "s1(x) = ((1 + alpha)*x - 1)/alpha\n"
        "s2(x) = (beta + alpha*x)/(1 + alpha)\n"
        "top(x) = s2(x) > s1(x) ? s2(x) : s1(x)\n"
        "# column 6 is the mode: 0 STICK, 1 SLIP1, 2 SLIP2, 3 SLIP12\n"
        "mode(m, c) = column(6) == m ? column(c) : NaN\n"
        "set samples 400\n",
        f);
  fputs("plot '+' using 1:(s1($1)):(top($1)) with filledcurves "
        "fc rgb '#e8e8e8' title 'global stick region', \\\n"
        "     s1(x) with lines lc rgb '#666666' dt 2 title 'S_1 = 1', \\\n"
        "     s2(x) with lines lc rgb '#666666' dt 4 title 'S_2 = beta', \\\n"
        "     'trajectory.csv' skip 1 using (mode(0,2)):(mode(0,3)) with "
        "points pt 7 ps 0.35 lc rgb '#444444' notitle, \\\n"
        "     '' skip 1 using (mode(1,2)):(mode(1,3)) with points pt 7 "
        "ps 0.35 lc rgb '#d62728' notitle, \\\n"
        "     '' skip 1 using (mode(2,2)):(mode(2,3)) with points pt 7 "
        "ps 0.35 lc rgb '#1f4e9e' notitle, \\\n"
        "     '' skip 1 using (mode(3,2)):(mode(3,3)) with points pt 7 "
        "ps 0.35 lc rgb '#2ca02c' notitle, \\\n"
        "     keyentry with points pt 7 ps 1.5 lc rgb '#444444' "
        "title 'stick (GSP)', \\\n"
        "     keyentry with points pt 7 ps 1.5 lc rgb '#d62728' "
        "title 'block 1 slips', \\\n"
        "     keyentry with points pt 7 ps 1.5 lc rgb '#1f4e9e' "
        "title 'block 2 slips', \\\n"
        "     keyentry with points pt 7 ps 1.5 lc rgb '#2ca02c' "
        "title 'both slip'\n",
        f);
  if ((st = sc_cli_commit(r, "phase.gp", gp))) return st;
  if ((st = sc_cli_add_plot(r, "phase.gp", "phase.png"))) return st;

  if ((st = sc_cli_open(r, "velocity.gp", &gp))) return st;
  f = sc_file_stream(gp);
  sc_plot_head(f, "velocity.png", title, "tau", "U_i - V_s");
  fputs("set key inside right top box opaque\n", f);
  fputs("# V_s: velocity of a stuck block during a slip (V with the "
        "driver moving, 0 frozen);\n# in a global stick phase both blocks "
        "move with V.\n",
        f);
  fprintf(f, "Vs = %.17g\n", stuck_velocity(m));
  fputs("plot 'trajectory.csv' skip 1 using 1:($4 - Vs) with lines lw 1.5 "
        "lc rgb '#d62728' title 'U_1 - V_s', \\\n"
        "     '' skip 1 using 1:($5 - Vs) with lines lw 1.5 lc rgb '#1f4e9e' "
        "title 'U_2 - V_s'\n",
        f);
  if ((st = sc_cli_commit(r, "velocity.gp", gp))) return st;
  return sc_cli_add_plot(r, "velocity.gp", "velocity.png");
}

static int orbit_run(sc_cli_run *r) {
  const sc_scene *s = r->scene;
  sc_map *m = r->map;
  long n = sc_scene_int(s, "iterations");
  double *d = malloc((size_t)(n + 1) * sizeof *d);
  if (!d) return sc_fail(r->msg, SC_ENOMEM, "orbit: out of memory");
  static const size_t tail_cap = ORBIT_TAIL;
  double dfdd[ORBIT_TAIL];
  int neutral[ORBIT_TAIL];
  char (*itin)[SC_ITIN_LEN] = calloc(tail_cap, sizeof *itin);
  if (!itin) {
    free(d);
    return sc_fail(r->msg, SC_ENOMEM, "orbit: out of memory");
  }
  sc_file *csv = NULL, *sum = NULL, *gp = NULL, *tr = NULL;
  int fail = SC_OK;
  sc_msg em;
  int st = sc_cli_open(r, "orbit.csv", &csv);
  if (st) goto done;
  FILE *f = sc_file_stream(csv);
  fputs("k,d,itinerary\n", f);
  d[0] = sc_scene_real(s, "d0");
  long k;
  sc_map_value v;
  for (k = 0; k < n; k++) {
    if (sc_cli_interrupted()) {
      st = sc_fail(r->msg, SC_ECALLBACK, "interrupted");
      goto done;
    }
    fail = sc_map_eval(m, d[k], SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v, &em);
    if (fail == SC_ENONFINITE) {
      /* f' does not exist here (an event with zero slope, or d* with the
       * driver frozen): the iterate does; the multiplier is then unknown */
      fail = sc_map_eval(m, d[k], SC_EVAL_ITINERARY, &v, &em);
      v.dfdd = NAN;
    }
    fprintf(f, "%ld,", k);
    sc_csv_double(f, d[k]);
    if (fail) {
      fputs(",undefined\n", f);
      break;
    }
    fprintf(f, ",%s\n", sc_cli_csv_text(v.itinerary));
    size_t slot = (size_t)k % tail_cap;
    dfdd[slot] = v.dfdd;
    neutral[slot] = v.neutral;
    memcpy(itin[slot], v.itinerary, SC_ITIN_LEN);
    d[k + 1] = v.f;
  }
  if (!fail) {
    fprintf(f, "%ld,", n);
    sc_csv_double(f, d[n]);
    fputs(",\n", f);
  }
  st = sc_cli_commit(r, "orbit.csv", csv);
  csv = NULL;
  if (st) goto done;

  /* Findings: the period of the tail and, for a periodic orbit, its
   * points, itineraries and multiplier (product of f' over one period). */
  if ((st = sc_cli_summary_begin(r, &sum))) goto done;
  f = sc_file_stream(sum);
  long last = k; /* d[0..last] are defined */
  if (fail) {
    fprintf(f, "  the map is undefined at iterate %ld (d = %.17g): %s\n", k,
            d[k], em.text);
  } else {
    /* The second half of the orbit at most: the first is transient. */
    long nt = (last + 1) / 2 < ORBIT_TAIL ? (last + 1) / 2 : ORBIT_TAIL;
    if (nt < 1) nt = 1;
    const double *tail = d + last + 1 - nt;
    int p = sc_sweep_period(tail, (size_t)nt,
                            sc_map_accuracy(m)->period_rtol,
                            SC_SWEEP_PERIOD_MAX);
    fprintf(f, "  final state after %ld iterates: %.17g\n", n, d[n]);
    if (p > 0) {
      double mult = 1;
      int neut = 1;
      fprintf(f, "  period of the last %ld iterates: %d\n", nt, p);
      for (long j = n - p; j < n; j++) {
        size_t slot = (size_t)j % tail_cap;
        mult *= dfdd[slot];
        neut = neut && neutral[slot];
        fprintf(f, "    d = %.17g  itinerary %s  f' = %.17g\n", d[j],
                itin[slot], dfdd[slot]);
      }
      fprintf(f, "  multiplier (product of f' over one period): %.17g%s\n",
              neut ? 1.0 : mult,
              neut ? " (neutral: single-block slips only)"
                   : fabs(mult) < 1 ? " (stable)" : " (unstable)");
    } else {
      fprintf(f, "  no period up to %d found in the last %ld iterates "
                 "(chaos, a longer period, or a transient)\n",
              SC_SWEEP_PERIOD_MAX, nt);
    }
  }
  fprintf(f, "  map evaluations: %lu\n", sc_map_nevals(m));
  st = sc_cli_commit(r, "summary.txt", sum);
  sum = NULL;
  if (st) goto done;

  /* The orbit d_k against k. */
  if ((st = sc_cli_open(r, "orbit.gp", &gp))) goto done;
  f = sc_file_stream(gp);
  char title[512];
  sc_plot_title(m, NULL, title, sizeof title);
  sc_plot_head(f, "orbit.png", title, "k (iterate)",
               sc_plot_label(m, sc_map_type(m)->state_name));
  fputs("set key inside right top box opaque\n", f);
  fputs("plot 'orbit.csv' skip 1 using 1:2 with linespoints pt 7 ps 0.6 "
        "lw 0.5 lc rgb '#1f4e9e' title 'orbit'\n",
        f);
  st = sc_cli_commit(r, "orbit.gp", gp);
  gp = NULL;
  if (st) goto done;
  if ((st = sc_cli_add_plot(r, "orbit.gp", "orbit.png"))) goto done;

  if (fail) {
    st = sc_fail(r->msg, fail, "orbit: map undefined at iterate %ld from "
                               "%.17g: %s",
                 k, d[k], em.text);
    goto done;
  }
  if (sc_scene_flag(s, "trajectory")) {
    long mt = sc_scene_int(s, "trajectory-iterates");
    if (mt == 0) mt = n;
    traj_ctx c = {NULL, 0, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL};
    if ((st = sc_cli_open(r, "trajectory.csv", &tr))) goto done;
    c.f = sc_file_stream(tr);
    fputs("tau,y1,y2,u1,u2,mode\n", c.f);
    st = sc_map_trajectory(m, d[n - mt], (int)mt, sc_scene_real(s, "dtau"),
                           on_sample, &c, &em);
    if (st) {
      if (sc_cli_interrupted()) sc_fail(r->msg, SC_ECALLBACK, "interrupted");
      else if (c.rows > TRAJ_MAX_ROWS)
        sc_fail(r->msg, SC_EINVAL,
                "trajectory longer than %ld rows (long stick phases: V is "
                "small): raise dtau or lower trajectory-iterates",
                TRAJ_MAX_ROWS);
      else sc_fail(r->msg, st, "trajectory from d = %.17g: %s", d[n - mt],
                   em.text);
      goto done;
    }
    st = sc_cli_commit(r, "trajectory.csv", tr);
    tr = NULL;
    if (st) goto done;
    if (c.rows) st = write_trajectory_plots(r, &c);
  }
done:
  sc_file_abort(csv);
  sc_file_abort(sum);
  sc_file_abort(gp);
  sc_file_abort(tr);
  free(itin);
  free(d);
  return st;
}

const sc_cli_task sc_cli_task_orbit = {
    .type = {.kind = "orbit",
             .doc = "iterate the map from d0; optionally the continuous "
                    "motion (trajectory)",
             .keys = orbit_keys,
             .nkeys = sizeof orbit_keys / sizeof orbit_keys[0],
             .check = orbit_check},
    .outputs = "orbit.csv (k,d,itinerary), summary.txt, orbit.gp/png; with "
               "trajectory = yes also trajectory.csv "
               "(tau,y1,y2,u1,u2,mode), phase.gp/png, velocity.gp/png",
    .run = orbit_run,
};
