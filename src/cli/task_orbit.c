/* Task `orbit`: iterate the map from d0 and, for models with continuous
 * motion (bk2), follow the motion itself (fig 5.4). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/tasks.h"
#include "slipcont/analysis.h"

static const sc_key_info orbit_keys[] = {
    {"d0", SC_KEY_STATE, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "initial state (bk2: d = Y2 - Y1 of the first global stick phase)"},
    {"iterations", SC_KEY_INT, 0, "300", 1, 10000000, 0, 0, NULL,
     "map iterates (as the sweep task's iterations)"},
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

/* One orbit run: the iterates, the tail of their multipliers and
 * itineraries (a ring), where the map failed, the trajectory's extent. */
typedef struct {
  long n;        /* iterations */
  double *d;     /* d[0..n]; d[0..k] are defined */
  long k;        /* iterates done */
  double dfdd[ORBIT_TAIL];
  int neutral[ORBIT_TAIL];
  char (*itin)[SC_ITIN_LEN];
  int fail;      /* the map's status at iterate k (SC_OK: all defined) */
  sc_msg em;     /* and its message */
  traj_ctx traj; /* rows and bounds of trajectory.csv */
} orbit_job;

static int orbit_prepare(sc_cli_run *r, void *job) {
  orbit_job *j = job;
  j->n = sc_scene_int(r->scene, "iterations");
  j->d = malloc((size_t)(j->n + 1) * sizeof *j->d);
  j->itin = calloc(ORBIT_TAIL, sizeof *j->itin);
  if (!j->d || !j->itin)
    return sc_fail(r->msg, SC_ENOMEM, "orbit: out of memory");
  j->d[0] = sc_scene_real(r->scene, "d0");
  return SC_OK;
}

/* The iterates into orbit.csv, up to the first where the map fails. */
static int orbit_iterate(sc_cli_run *r, orbit_job *j) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "orbit.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("k,d,itinerary\n", f);
  sc_map_value v;
  double *d = j->d;
  for (j->k = 0; j->k < j->n; j->k++) {
    long k = j->k;
    if ((st = sc_cli_stop(r))) return st;
    j->fail = sc_map_eval(r->map, d[k], SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v,
                          &j->em);
    if (j->fail == SC_ENONFINITE) {
      /* f' does not exist here (an event with zero slope, or d* with the
       * driver frozen): the iterate does; the multiplier is then unknown */
      j->fail = sc_map_eval(r->map, d[k], SC_EVAL_ITINERARY, &v, &j->em);
      v.dfdd = NAN;
    }
    fprintf(f, "%ld,", k);
    sc_csv_double(f, d[k]);
    if (j->fail) {
      fputs(",undefined\n", f);
      break;
    }
    fprintf(f, ",%s\n", sc_cli_csv_text(v.itinerary));
    size_t slot = (size_t)k % ORBIT_TAIL;
    j->dfdd[slot] = v.dfdd;
    j->neutral[slot] = v.neutral;
    memcpy(j->itin[slot], v.itinerary, SC_ITIN_LEN);
    d[k + 1] = v.f;
  }
  if (!j->fail) {
    fprintf(f, "%ld,", j->n);
    sc_csv_double(f, d[j->n]);
    fputs(",\n", f);
  }
  return sc_cli_commit(r, "orbit.csv", csv);
}

/* The continuous motion over the last trajectory-iterates iterates into
 * trajectory.csv. */
static int orbit_trajectory(sc_cli_run *r, orbit_job *j) {
  const sc_scene *s = r->scene;
  long mt = sc_scene_int(s, "trajectory-iterates");
  if (mt == 0) mt = j->n;
  traj_ctx *c = &j->traj;
  *c = (traj_ctx){NULL, 0, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL};
  sc_file *tr = NULL;
  int st = sc_cli_open(r, "trajectory.csv", &tr);
  if (st) return st;
  c->f = sc_file_stream(tr);
  fputs("tau,y1,y2,u1,u2,mode\n", c->f);
  double from = j->d[j->n - mt];
  sc_msg em;
  st = sc_map_trajectory(r->map, from, (int)mt, sc_scene_real(s, "dtau"),
                         on_sample, c, &em);
  if (!st) return sc_cli_commit(r, "trajectory.csv", tr);
  if (sc_cli_interrupted()) return sc_cli_stop(r);
  if (c->rows > TRAJ_MAX_ROWS)
    return sc_fail(r->msg, SC_EINVAL,
                   "trajectory longer than %ld rows (long stick phases: V "
                   "is small): raise dtau or lower trajectory-iterates",
                   TRAJ_MAX_ROWS);
  return sc_fail(r->msg, st, "trajectory from d = %.17g: %s", from, em.text);
}

static int orbit_compute(sc_cli_run *r, void *job) {
  orbit_job *j = job;
  int st = orbit_iterate(r, j);
  if (!st && !j->fail && sc_scene_flag(r->scene, "trajectory"))
    st = orbit_trajectory(r, j);
  return st;
}

/* Findings: the period of the tail and, for a periodic orbit, its
 * points, itineraries and multiplier (product of f' over one period). */
static int orbit_summary(sc_cli_run *r, void *job, FILE *f) {
  const orbit_job *j = job;
  const double *d = j->d;
  long n = j->n, last = j->k; /* d[0..last] are defined */
  if (j->fail) {
    fprintf(f, "  the map is undefined at iterate %ld (d = %.17g): %s\n",
            last, d[last], j->em.text);
  } else {
    /* The second half of the orbit at most: the first is transient. */
    long nt = (last + 1) / 2 < ORBIT_TAIL ? (last + 1) / 2 : ORBIT_TAIL;
    if (nt < 1) nt = 1;
    int p = sc_sweep_period(d + last + 1 - nt, (size_t)nt,
                            sc_map_accuracy(r->map)->period_rtol,
                            SC_SWEEP_PERIOD_MAX);
    fprintf(f, "  final state after %ld iterates: %.17g\n", n, d[n]);
    if (p > 0) {
      double mult = 1;
      int neut = 1;
      fprintf(f, "  period of the last %ld iterates: %d\n", nt, p);
      for (long k = n - p; k < n; k++) {
        size_t slot = (size_t)k % ORBIT_TAIL;
        mult *= j->dfdd[slot];
        neut = neut && j->neutral[slot];
        fprintf(f, "    d = %.17g  itinerary %s  f' = %.17g\n", d[k],
                j->itin[slot], j->dfdd[slot]);
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
  fprintf(f, "  map evaluations: %lu\n", sc_map_nevals(r->map));
  return SC_OK;
}

/* Motion in the plane (Y1, Y2) over the global stick region. */
static int phase_plot(sc_cli_run *r, const traj_ctx *c, const char *title) {
  sc_map *m = r->map;
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "phase", title, "Y_1", "Y_2", &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
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
  return sc_cli_plot_end(r, "phase", gp);
}

/* The blocks' velocities relative to a stuck block's. */
static int velocity_plot(sc_cli_run *r, const char *title) {
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "velocity", title, "tau", "U_i - V_s", &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fputs("# V_s: velocity of a stuck block during a slip (V with the "
        "driver moving, 0 frozen);\n# in a global stick phase both blocks "
        "move with V.\n",
        f);
  fprintf(f, "Vs = %.17g\n", stuck_velocity(r->map));
  fputs("plot 'trajectory.csv' skip 1 using 1:($4 - Vs) with lines lw 1.5 "
        "lc rgb '#d62728' title 'U_1 - V_s', \\\n"
        "     '' skip 1 using 1:($5 - Vs) with lines lw 1.5 lc rgb '#1f4e9e' "
        "title 'U_2 - V_s'\n",
        f);
  return sc_cli_plot_end(r, "velocity", gp);
}

/* The orbit d_k against k; the trajectory's plots when it has rows. */
static int orbit_plots(sc_cli_run *r, void *job) {
  const orbit_job *j = job;
  sc_map *m = r->map;
  char title[512];
  sc_plot_title(m, NULL, title, sizeof title);
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "orbit", title, "k (iterate)",
                             sc_plot_label(m, sc_map_type(m)->state_name),
                             &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fputs("plot 'orbit.csv' skip 1 using 1:2 with linespoints pt 7 ps 0.6 "
        "lw 0.5 lc rgb '#1f4e9e' title 'orbit'\n",
        f);
  if ((st = sc_cli_plot_end(r, "orbit", gp))) return st;
  if (!j->traj.rows) return SC_OK;
  if ((st = phase_plot(r, &j->traj, title))) return st;
  return velocity_plot(r, title);
}

/* The files are written: an orbit that left the map's domain fails now. */
static int orbit_report(sc_cli_run *r, void *job) {
  const orbit_job *j = job;
  if (!j->fail) return SC_OK;
  return sc_fail(r->msg, j->fail, "orbit: map undefined at iterate %ld from "
                                  "%.17g: %s",
                 j->k, j->d[j->k], j->em.text);
}

static void orbit_release(sc_cli_run *r, void *job) {
  orbit_job *j = job;
  (void)r;
  free(j->itin);
  free(j->d);
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
    .job_size = sizeof(orbit_job),
    .prepare = orbit_prepare,
    .compute = orbit_compute,
    .summary = orbit_summary,
    .plots = orbit_plots,
    .report = orbit_report,
    .release = orbit_release,
};
