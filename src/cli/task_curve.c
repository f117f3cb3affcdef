/* Task `curve`: the fold or flip curve of a period-m orbit in two
 * parameters, its codimension-two points (CP, GPD, TP) and where it ends
 * (sc_curve_trace, curve.h; docs/curves.md). */
#define _XOPEN_SOURCE 700 /* realpath */

#include <glob.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/curve_impl.h"
#include "cli/progress.h"
#include "cli/tasks.h"
#include "slipcont/curve.h"

static const sc_key_info curve_keys[] = {
    {"type", SC_KEY_CHOICE, 1, NULL, 0, 0, 0, 0,
     "fold|flip|graze|cross|switch|both|touch|ns",
     "fold: multiplier +1 (f^m(d) = d, (f^m)' = 1); flip: (f^m)' = -1; "
     "ns (n-dimensional models): a pair of multipliers e^(+-i theta), the "
     "Neimark-Sacker curve; graze, cross, switch, both, touch: the orbit on "
     "its nearest border of that kind (GR, CS, SW, BR, TT), f^m(d) = d and "
     "m_k = 0"},
    {"x", SC_KEY_PARAM, 1, NULL, 0, 0, 0, 0, NULL,
     "the parameter the start was located in (horizontal axis)"},
    {"y", SC_KEY_PARAM, 1, NULL, 0, 0, 0, 0, NULL,
     "the second parameter (vertical axis); the start is corrected at the "
     "model's value of y"},
    {"x-from", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "the box: lower end of x"},
    {"x-to", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "the box: upper end of x (> x-from)"},
    {"y-from", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "the box: lower end of y"},
    {"y-to", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "the box: upper end of y (> y-from)"},
    {"period", SC_KEY_INT, 0, "1", 1, 4096, 0, 0, NULL,
     "m: the orbit is a fixed point of f^m (single shooting)"},
    {"d0", SC_KEY_STATE, 0, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "guess of an orbit point at the start (or give start)"},
    {"start", SC_KEY_TEXT, 0, NULL, 0, 0, 0, 0, NULL,
     "FILE:N, row N (1 = first after the header) of a branch task's "
     "points.csv: an LP (type = fold), PD (type = flip), NS (type = ns) or "
     "border point "
     "(GR for graze, CS cross, SW switch, BR both, TT touch) located in x; "
     "x, d0 and period are taken from it (instead of d0), and from a "
     "border point its border, followed by the curve"},
    {"shooting", SC_KEY_CHOICE, 0, "single", 0, 0, 0, 0, "single|multiple",
     "single: on f^m in (d, x, y); multiple: one equation per iterate in "
     "(d_0..d_{m-1}, x, y), for long periods"},
    {"h0", SC_KEY_REAL, 0, "0", 0, HUGE_VAL, 0, 1, NULL,
     "initial arclength step in (d, x, y) (0: hmax / 10)"},
    {"hmax", SC_KEY_REAL, 0, "0", 0, HUGE_VAL, 0, 1, NULL,
     "largest arclength step (0: the box's smaller side / 50)"},
    {"max-points", SC_KEY_INT, 0, "5000", 2, 10000000, 0, 0, NULL,
     "accepted points per direction"},
    {"marks", SC_KEY_TEXT, 0, NULL, 0, 0, 0, 0, NULL,
     "user points (UZ): values of x, separated by spaces, at which the "
     "curve records its point (located by Newton with x fixed; rows of "
     "points.csv)"},
    {"overlay", SC_KEY_TEXT, 0, NULL, 0, 0, 0, 0, NULL,
     "a chart.csv of the chart task over the same x and y, drawn under "
     "the curve (path relative to the working folder)"},
    {"also", SC_KEY_TEXT, 0, NULL, 0, 0, 0, 0, NULL,
     "output folders of other curve tasks (separated by spaces; shell "
     "patterns such as out/curve-fig58-* allowed), whose curves and "
     "labelled points are drawn in the same plot"},
};

/* The curve types in key order; border kinds of the border types. */
static const char *const type_names[] = {
    "fold", "flip", "graze", "cross", "switch", "both", "touch", "ns"};
static const char *const type_labels[] = {"LP", "PD", "GR", "CS",
                                          "SW", "BR", "TT", "NS"};
static const sc_border_kind type_kinds[] = {
    0, 0, SC_BORDER_GRAZING, SC_BORDER_CROSSING, SC_BORDER_SWITCHING,
    SC_BORDER_BOTH, SC_BORDER_TOUCH, 0};
/* type_names' index of ns: the n-dimensional curve */
#define TYPE_NS 7

static int type_index(const char *t) {
  for (int i = 0; i < 8; i++)
    if (strcmp(t, type_names[i]) == 0) return i;
  return 0; /* the key's choices are checked by the scene */
}

/* The overlay's header must start with "<x>,<y>,period": a chart of
 * these two parameters.  Returns 0 or a status with the reason. */
static int overlay_check(const sc_scene *s, const char *path, const char *xn,
                         const char *yn, sc_msg *msg) {
  char line[256], want[256];
  sc_msg why;
  if (sc_cli_read_head(path, "the overlay", line, sizeof line, &why))
    return sc_scene_fail_key(s, "task", "overlay", msg,
                             "overlay = %s cannot be read: %s (valid: a "
                             "chart.csv of the chart task)",
                             path, why.text);
  snprintf(want, sizeof want, "%s,%s,period,", xn, yn);
  if (strncmp(line, want, strlen(want)) != 0)
    return sc_scene_fail_key(s, "task", "overlay", msg,
                             "overlay = %s is not a chart of (%s, %s): its "
                             "header does not start with '%s' (valid: a "
                             "chart.csv with x = %s, y = %s)",
                             path, xn, yn, want, xn, yn);
  return SC_OK;
}

/* Every folder matched by `also` holds a curve.csv in (x, y). */
static int also_check(const sc_scene *s, const char *xn, const char *yn,
                      sc_msg *msg) {
  const char *also = sc_scene_text(s, "also");
  char dir[2048], path[2100];
  for (const char *p = also; p && sc_cli_next_word(&p, dir, sizeof dir);) {
    glob_t g;
    int gr = glob(dir, 0, NULL, &g);
    size_t ng = gr == 0 ? g.gl_pathc : 0;
    if (ng == 0) {
      if (gr == 0) globfree(&g);
      return sc_scene_fail_key(s, "task", "also", msg,
                               "also: %s matches no folder (valid: output "
                               "folders of curve tasks; run them first)",
                               dir);
    }
    for (size_t i = 0; i < ng; i++) {
      snprintf(path, sizeof path, "%s/curve.csv", g.gl_pathv[i]);
      char line[256], want[256];
      sc_msg why;
      snprintf(want, sizeof want, "%s,%s,", xn, yn);
      int bad = sc_cli_read_head(path, "a curve of also", line, sizeof line,
                                 &why);
      if (bad || strncmp(line, want, strlen(want)) != 0) {
        globfree(&g);
        if (bad)
          return sc_scene_fail_key(s, "task", "also", msg,
                                   "also: %s (valid: output folders of curve "
                                   "tasks in x = %s, y = %s; run them first)",
                                   why.text, xn, yn);
        return sc_scene_fail_key(s, "task", "also", msg,
                                 "also: %s is not a curve.csv in (%s, %s) "
                                 "(valid: output folders of curve tasks in x "
                                 "= %s, y = %s; run them first)",
                                 path, xn, yn, xn, yn);
      }
    }
    globfree(&g);
  }
  return SC_OK;
}

static int curve_check(const sc_scene *s, sc_msg *msg) {
  const sc_map *m = sc_scene_map(s);
  const char *xn = sc_scene_text(s, "x"), *yn = sc_scene_text(s, "y");
  if (strcmp(xn, yn) == 0)
    return sc_scene_fail_key(s, "task", "y", msg,
                             "y = %s is the same parameter as x (valid: "
                             "another parameter of the model)",
                             yn);
  int ti = type_index(sc_scene_text(s, "type"));
  double xstart = NAN;
  if (sc_map_dim(m) > 1) {
    int st = sc_cli_curve_n_check(s, sc_scene_text(s, "type"), type_labels[ti],
                                  &xstart, msg);
    if (st) return st;
  } else if (ti == TYPE_NS) {
    return sc_scene_fail_key(s, "task", "type", msg,
                             "type = ns: model %s is one-dimensional, with no "
                             "pair of multipliers (valid: fold, flip or a "
                             "border's kind)",
                             sc_map_type(m)->name);
  }
  if (ti >= 2 && ti != TYPE_NS && !sc_map_has_borders(m))
    return sc_scene_fail_key(s, "task", "type", msg,
                             "type = %s: model %s declares no borders "
                             "(valid: fold or flip)",
                             sc_scene_text(s, "type"), sc_map_type(m)->name);
  const char *spec = sc_scene_text(s, "start");
  int has_d0 = sc_map_dim(m) > 1 ? sc_scene_value(s, "task", "d0") != NULL
                                 : !isnan(sc_scene_real(s, "d0"));
  if (!spec == !has_d0)
    return sc_scene_fail_key(s, "task", spec ? "start" : "d0", msg,
                             "give either d0 or start (valid: exactly one "
                             "of them)");
  sc_cli_points_row row;
  if (spec && sc_map_dim(m) == 1) {
    char why[512];
    if (sc_cli_points_row_read(spec, &row, why, sizeof why))
      return sc_scene_fail_key(s, "task", "start", msg, "start: %s", why);
    const char *want = type_labels[type_index(sc_scene_text(s, "type"))];
    if (strcmp(row.param, xn) || strcmp(row.label, want))
      return sc_scene_fail_key(s, "task", "start", msg,
                               "start = %s is a %s in %s (valid: a %s in x "
                               "= %s for type = %s)",
                               spec, row.label, row.param, want, xn,
                               sc_scene_text(s, "type"));
  }
  const char *lo[2] = {"x-from", "y-from"}, *hi[2] = {"x-to", "y-to"};
  const char *nm[2] = {xn, yn};
  const char *const xends[] = {"x-from", "x-to"};
  const char *const yends[] = {"y-from", "y-to"};
  int st = sc_cli_check_param_keys(s, "x", xends, 2, msg);
  if (!st) st = sc_cli_check_param_keys(s, "y", yends, 2, msg);
  if (st) return st;
  for (int k = 0; k < 2; k++) {
    if (!(sc_scene_real(s, lo[k]) < sc_scene_real(s, hi[k])))
      return sc_scene_fail_key(s, "task", hi[k], msg,
                               "%s = %s is not above %s = %s (valid: > %s)",
                               hi[k], sc_scene_text(s, hi[k]), lo[k],
                               sc_scene_text(s, lo[k]), lo[k]);
    double v = sc_map_get_param(m, (size_t)sc_map_param_index(m, nm[k]));
    if (k == 0 && spec) v = sc_map_dim(m) > 1 ? xstart : row.value;
    if (v < sc_scene_real(s, lo[k]) || v > sc_scene_real(s, hi[k]))
      return sc_scene_fail_key(
          s, "task", lo[k], msg,
          "the start's %s = %.17g (%s) lies outside [%s, %s] (valid: "
          "inside the box)",
          nm[k], v, k == 0 && spec ? "its row of start" : "the [model] value",
          sc_scene_text(s, lo[k]), sc_scene_text(s, hi[k]));
  }
  st = also_check(s, xn, yn, msg);
  if (st) return st;
  double marks[SC_CLI_MAXMARKS];
  size_t nmarks;
  st = sc_cli_marks(s, xn, sc_scene_real(s, "x-from"),
                    sc_scene_real(s, "x-to"), marks, &nmarks, msg);
  if (st) return st;
  const char *ov = sc_scene_text(s, "overlay");
  if (ov) return overlay_check(s, ov, xn, yn, msg);
  return SC_OK;
}


static int on_point(void *vc, const sc_curve_point *p) {
  out_ctx *c = vc;
  if (!c->have_start)
    c->have_start = 1, c->start_x = p->x, c->start_y = p->y;
  if (p->branch != c->last_branch) fputc('\n', c->curve);
  c->last_branch = p->branch;
  sc_csv_double(c->curve, p->x);
  fputc(',', c->curve);
  sc_csv_double(c->curve, p->y);
  fputc(',', c->curve);
  sc_csv_double(c->curve, p->d);
  fprintf(c->curve, ",%d,", c->period);
  sc_csv_double(c->curve, p->multiplier);
  fputc(',', c->curve);
  sc_csv_double(c->curve, p->coefficient);
  char itin[SC_ITIN_LEN];
  snprintf(itin, sizeof itin, "%s", p->itinerary);
  fprintf(c->curve, ",%s\n", sc_cli_csv_text(itin));
  return sc_cli_interrupted();
}

static int on_special(void *vc, const sc_curve_special *s) {
  out_ctx *c = vc;
  fprintf(c->points, "%s,", s->label);
  sc_csv_double(c->points, s->x);
  fputc(',', c->points);
  sc_csv_double(c->points, s->y);
  fputc(',', c->points);
  sc_csv_double(c->points, s->d);
  char note[sizeof s->note];
  snprintf(note, sizeof note, "%s", s->note);
  fprintf(c->points, ",%d,%s,", c->period, sc_cli_csv_text(note));
  sc_csv_double(c->points, s->coefficient);
  fputc(',', c->points);
  sc_csv_double(c->points, s->residual);
  fputc('\n', c->points);
  return sc_cli_curve_keep(c, s);
}

int sc_cli_curve_keep(out_ctx *c, const sc_curve_special *s) {
  if (c->nsp == c->cap) {
    size_t cap = c->cap ? 2 * c->cap : 16;
    sc_curve_special *n = realloc(c->sp, cap * sizeof *n);
    if (!n) {
      c->oom = 1;
      return 1;
    }
    c->sp = n, c->cap = cap;
  }
  c->sp[c->nsp++] = *s;
  return 0;
}

/* One curve run: the settings, where it starts, the special points. */
typedef struct {
  sc_curve_settings set;
  int ti;        /* index of the type in type_names */
  const char *xn, *yn;
  double d0;
  out_ctx c;     /* the streams while tracing; the special points */
  sc_curve_stats stats;
  double x0, y0; /* the start given: the scene's or the row's x, y */
  unsigned long nev;
  double elapsed;
  double marks[SC_CLI_MAXMARKS]; /* user points: values of x */
  sc_cli_curve_n *nd; /* an n-dimensional model's path; NULL for n = 1 */
  int degenerate; /* the start row's point is degenerate (no certificate) */
} curve_job;

static int curve_prepare(sc_cli_run *r, void *job) {
  curve_job *j = job;
  const sc_scene *s = r->scene;
  sc_map *m = r->map;
  sc_curve_settings *set = &j->set;
  j->xn = sc_scene_text(s, "x");
  j->yn = sc_scene_text(s, "y");
  sc_curve_settings_default(set);
  j->ti = type_index(sc_scene_text(s, "type"));
  set->type = j->ti == 0        ? SC_CURVE_FOLD
              : j->ti == 1      ? SC_CURVE_FLIP
              : j->ti == TYPE_NS ? SC_CURVE_NS
                                : SC_CURVE_BORDER;
  set->border = type_kinds[j->ti];
  set->period = (int)sc_scene_int(s, "period");
  set->multiple = strcmp(sc_scene_text(s, "shooting"), "multiple") == 0;
  set->ix = sc_map_param_index(m, j->xn);
  set->iy = sc_map_param_index(m, j->yn);
  set->xlo = sc_scene_real(s, "x-from"), set->xhi = sc_scene_real(s, "x-to");
  set->ylo = sc_scene_real(s, "y-from"), set->yhi = sc_scene_real(s, "y-to");
  set->hmax = sc_scene_real(s, "hmax");
  if (set->hmax == 0)
    set->hmax = fmin(set->xhi - set->xlo, set->yhi - set->ylo) / 50;
  set->h0 = sc_scene_real(s, "h0");
  if (set->h0 == 0) set->h0 = set->hmax / 10;
  if (set->h0 > set->hmax) set->hmax = set->h0;
  set->max_points = sc_scene_int(s, "max-points");
  if (sc_map_dim(m) > 1) return sc_cli_curve_n_prepare(r, set, &j->nd);
  int st = sc_cli_marks(s, j->xn, set->xlo, set->xhi, j->marks,
                        &set->nmarks, r->msg);
  if (st) return st;
  set->marks = j->marks;
  j->d0 = sc_scene_real(s, "d0");
  const char *spec = sc_scene_text(s, "start");
  if (!spec) return SC_OK;
  /* checked by curve_check(): the row exists and fits */
  sc_cli_points_row row;
  char why[512];
  if (sc_cli_points_row_read(spec, &row, why, sizeof why))
    return sc_fail(r->msg, SC_EIO, "curve: start = %s: %s", spec, why);
  j->d0 = row.d;
  j->degenerate = strcmp(row.method, "degenerate") == 0;
  set->period = row.period;
  /* a border row starts the curve on its own border */
  if (set->type == SC_CURVE_BORDER)
    snprintf(set->border_name, sizeof set->border_name, "%s", row.border);
  return sc_map_set_param(m, (size_t)set->ix, row.value, r->msg);
}

/* The message of a start that could not be put on the curve: where it
 * was set, why, and how to get a start that is on it. */
static int start_failed(sc_cli_run *r, const curve_job *j) {
  const sc_scene *s = r->scene;
  const sc_map *m = r->map;
  char why[SC_MSG_LEN];
  snprintf(why, sizeof why, "%s", r->msg->text);
  sc_cli_user_text(why);
  const char *spec = sc_scene_text(s, "start");
  char key[600];
  if (spec)
    snprintf(key, sizeof key, "start = %.500s", spec);
  else
    snprintf(key, sizeof key, "d0 = %.500s", sc_scene_text(s, "d0"));
  /* a degenerate row is a touch of its border, or an orbit on it along
   * an interval: its own label is no help */
  if (j->degenerate)
    return sc_scene_fail_key(
        s, "task", "start", r->msg,
        "%s (period %d at %s = %.12g, %s = %.12g): the row's point is "
        "degenerate (its method column: the orbit touches its border or "
        "sits on it along an interval, so its defining system has no "
        "isolated root), and no %s curve could be started there (%s); "
        "start from a row located by Newton",
        key, j->set.period, j->xn, sc_map_get_param(m, (size_t)j->set.ix),
        j->yn, sc_map_get_param(m, (size_t)j->set.iy), type_names[j->ti],
        why);
  return sc_scene_fail_key(
      s, "task", spec ? "start" : "d0", r->msg,
      "%s (period %d at %s = %.12g, %s = %.12g): the start is not on a %s "
      "curve (%s); start from a row labelled %s, located by the branch "
      "task in %s (start = FILE:N, a row of its points.csv)",
      key, j->set.period, j->xn,
      sc_map_get_param(m, (size_t)j->set.ix), j->yn,
      sc_map_get_param(m, (size_t)j->set.iy), type_names[j->ti], why,
      type_labels[j->ti], j->xn);
}

/* The trace, streamed into curve.csv and points.csv. */
static int curve_compute(sc_cli_run *r, void *job) {
  curve_job *j = job;
  sc_map *m = r->map;
  out_ctx *c = &j->c;
  c->period = j->set.period;
  if (j->nd) {
    j->x0 = sc_map_get_param(m, (size_t)j->set.ix);
    j->y0 = sc_map_get_param(m, (size_t)j->set.iy);
    unsigned long ev0 = sc_map_nevals(m);
    double t0 = sc_progress_now();
    int st = sc_cli_curve_n_compute(r, j->nd, &j->set, c, &j->stats);
    j->elapsed = sc_progress_now() - t0;
    j->nev = sc_map_nevals(m) - ev0;
    if (st && st != SC_ENOMEM && st != SC_ECALLBACK && j->stats.npoints == 0)
      st = start_failed(r, j);
    return st;
  }
  sc_file *cf = NULL, *pf = NULL;
  int st = sc_cli_open(r, "curve.csv", &cf);
  if (!st) st = sc_cli_open(r, "points.csv", &pf);
  if (st) return st;
  c->curve = sc_file_stream(cf);
  c->points = sc_file_stream(pf);
  const char *state = sc_map_type(m)->state_name;
  fprintf(c->curve, "%s,%s,%s,period,multiplier,coefficient,itinerary\n",
          j->xn, j->yn, state);
  fprintf(c->points, "label,%s,%s,%s,period,note,coefficient,residual\n",
          j->xn, j->yn, state);
  sc_curve_output out = {on_point, on_special, c};
  j->x0 = sc_map_get_param(m, (size_t)j->set.ix);
  j->y0 = sc_map_get_param(m, (size_t)j->set.iy);
  unsigned long ev0 = sc_map_nevals(m);
  double t0 = sc_progress_now();
  st = sc_curve_trace(m, &j->set, j->d0, &out, &j->stats, r->msg);
  j->elapsed = sc_progress_now() - t0;
  j->nev = sc_map_nevals(m) - ev0;
  if (st == SC_ECALLBACK && (c->oom || sc_cli_interrupted()))
    sc_fail(r->msg, st, "curve: %s", c->oom ? "out of memory" : "interrupted");
  else if (st && st != SC_ENOMEM && j->stats.npoints == 0)
    st = start_failed(r, j);
  if (!st) st = sc_cli_commit(r, "curve.csv", cf);
  return st ? st : sc_cli_commit(r, "points.csv", pf);
}


/* Whether the corrected start moved from the given x by more than the
 * corrector's own tolerance (newton_atol + newton_rtol |x|): a move at
 * the rounding level is no news for the title or the summary. */
static int start_moved(const curve_job *j, const sc_map *m) {
  sc_accuracy acc;
  sc_map_solver_accuracy(m, &acc);
  double tol = acc.newton_atol + acc.newton_rtol * fabs(j->x0);
  return fabs(j->c.start_x - j->x0) > tol;
}

static int curve_summary(sc_cli_run *r, void *job, FILE *f) {
  const curve_job *j = job;
  const sc_curve_stats *stats = &j->stats;
  fprintf(f, "  %s curve of the period-%d orbit in (%s, %s): %ld points%s\n",
          type_names[j->ti], j->set.period, j->xn, j->yn, stats->npoints,
          stats->closed ? ", closed" : "");
  fprintf(f,
          "  largest residual of the defining system over the points: "
          "%.3g\n",
          stats->max_residual);
  fprintf(f, "  residual tolerance used: %.3g\n", stats->ftol);
  /* the corrector keeps a point whose residual stays at its rounding
   * floor, up to 10 tolerances (docs/curves.md): say so when it did */
  if (stats->max_residual > stats->ftol && !j->nd)
    fprintf(f,
            "  the largest residual is above the tolerance: a point whose "
            "residual stays at its rounding floor (f^m's rounding times "
            "|f'| along the orbit, large next to d*) is kept up to 10 "
            "tolerances, and the curve ends where the floor rises beyond "
            "(EP)\n");
  /* the start is corrected onto the curve at fixed y: where it landed */
  if (j->c.have_start && start_moved(j, r->map))
    fprintf(f,
            "  start: %s = %.17g, %s = %.17g, corrected from the given %s = "
            "%.17g (moved by %.3g)\n",
            j->xn, j->c.start_x, j->yn, j->c.start_y, j->xn, j->x0,
            j->c.start_x - j->x0);
  else if (j->c.have_start)
    fprintf(f, "  start: %s = %.17g, %s = %.17g, as given (within the "
               "corrector's tolerance)\n", j->xn,
            j->c.start_x, j->yn, j->c.start_y);
  if (stats->border_iterate >= 0)
    fprintf(f, "  border followed: %s, %s, iterate %d of %d\n",
            type_labels[j->ti], stats->border, stats->border_iterate + 1,
            j->set.period);
  fprintf(f, "  shooting: %s\n", j->set.multiple ? "multiple" : "single");
  fprintf(f, "  codimension-two points: %ld\n", stats->nspecial);
  if (j->nd) sc_cli_curve_n_summary(f, r, j->nd);
  for (size_t i = 0; !j->nd && i < j->c.nsp; i++) {
    const sc_curve_special *p = &j->c.sp[i];
    fprintf(f,
            "    %-3s %s = %.17g, %s = %.17g, %s = %.17g, coefficient "
            "%.6g, residual %.3g: %s\n",
            p->label, j->xn, p->x, j->yn, p->y,
            sc_map_type(r->map)->state_name, p->d, p->coefficient,
            p->residual, p->note);
  }
  fprintf(f, "  map evaluations: %lu; time %.3f s\n", j->nev, j->elapsed);
  return SC_OK;
}

/* A file another run wrote, opened as every input a scene names is
 * (sc_input_open(): a bounded regular file, never blocking); NULL
 * otherwise (the figure then goes without what it would have added). */
static FILE *open_regular(const char *path) {
  FILE *f = NULL;
  return sc_input_open(path, "a file drawn", SC_INPUT_MAXBYTES, &f, NULL)
             ? NULL
             : f;
}

/* Rows read from another run's file for a figure: enough for any chart or
 * curve a figure can show (a 3000 x 3000 chart), bounded for any file. */
#define FIGURE_MAX_ROWS 10000000L

/* The chart of `overlay` under the curves, in the chart's own colours
 * (sc_plot_period_rgb) made pale so that the curves stand out: each
 * class present gets a key entry, as in the chart's own figure. */
#define OVERLAY_PALE 0.7 /* share of white mixed into a period's colour */

static unsigned pale(unsigned rgb) {
  unsigned out = 0;
  for (int sh = 16; sh >= 0; sh -= 8) {
    double c = (rgb >> sh) & 255u;
    out |= (unsigned)lround(c + (255 - c) * OVERLAY_PALE) << sh;
  }
  return out;
}

static int plot_overlay(FILE *f, const char *ov) {
  char path[4096];
  if (!ov || !realpath(ov, path)) return 0;
  /* the classes present: periods 1..64, then high, undefined, unsettled,
   * invariant circle (charts of n-dimensional maps) */
  enum { NPER = 64 };
  int present[NPER + 4] = {0};
  FILE *in = open_regular(path);
  if (in) {
    char line[512];
    long rows = 0;
    if (fgets(line, sizeof line, in))
      while (rows++ < FIGURE_MAX_ROWS && fgets(line, sizeof line, in)) {
        const char *c = strchr(line, ',');
        c = c ? strchr(c + 1, ',') : NULL;
        if (!c) continue;
        long per = strtol(c + 1, NULL, 10);
        if (per >= 1 && per <= NPER) present[per - 1] = 1;
        else if (per == 0) present[NPER] = 1;
        else if (per == -1) present[NPER + 1] = 1;
        else if (per == -2) present[NPER + 2] = 1;
        else if (per == -3) present[NPER + 3] = 1;
      }
    fclose(in);
  }
  fputs("# the chart's period colours (sc_plot_period_rgb), pale\n"
        "array C[16] = [",
        f);
  for (int k = 0; k < 16; k++)
    fprintf(f, "%s0x%06x", k ? ", " : "", pale(sc_plot_period_rgb(k + 1)));
  fputs("]\nrgb(p) = ", f);
  if (present[NPER + 3]) /* only then: other charts' scripts unchanged */
    fprintf(f, "p == -3 ? 0x%06x : ", pale(sc_plot_period_rgb(-3)));
  fprintf(f, "p == -2 ? 0x%06x : p == -1 ? 0x%06x : p == 0 ? "
             "0x%06x : C[int(p - 1) %% 16 + 1]\n",
          pale(sc_plot_period_rgb(-2)), pale(sc_plot_period_rgb(-1)),
          pale(sc_plot_period_rgb(0)));
  fputs("plot ", f);
  sc_plot_quote(f, path);
  fputs(" skip 1 using 1:2:(int(rgb($3)) >> 16 & 255):(int(rgb($3)) >> 8 "
        "& 255):(int(rgb($3)) & 255) with rgbimage notitle, \\\n",
        f);
  for (int p = 1; p <= NPER + 4; p++) {
    if (!present[p - 1]) continue;
    int per = p <= NPER ? p : NPER + 1 - p; /* 0, -1, -2, -3 */
    char title[64];
    if (per >= 1) snprintf(title, sizeof title, "chart: period %d", per);
    else
      snprintf(title, sizeof title, "chart: %s",
               per == 0    ? "higher or chaos"
               : per == -1 ? "undefined"
               : per == -2 ? "not settled"
                           : "invariant circle");
    fprintf(f, "     keyentry with boxes fs solid border lc rgb '#bbbbbb' "
               "fc rgb '#%06x' title '%s', \\\n",
            pale(sc_plot_period_rgb(per)), title);
  }
  fputs("     ", f);
  return 1;
}

/* The kinds of points a curve figure marks, in the key's order. */
static const char *const point_kinds[] = {
    "CP", "GPD", "TP",   "LP",   "PD",   "GR",   "CS", "SW", "BR",
    "TT", "CH",  "R1",   "R2",   "R3",   "R4",   "LPPD", "LPNS", "PDNS",
    "NSNS", "UZ", "EP"};
#define NKINDS (sizeof point_kinds / sizeof *point_kinds)

/* The kind of a points.csv label ("BR?" is a BR not located): its index
 * in point_kinds, or -1. */
static int kind_of(const char *label, size_t len) {
  for (size_t k = 0; k < NKINDS; k++) {
    size_t n = strlen(point_kinds[k]);
    if (len >= n && strncmp(label, point_kinds[k], n) == 0 &&
        (len == n || label[n] == '?'))
      return (int)k;
  }
  return -1;
}

/* The kinds present in a points.csv (first column). */
static void kinds_in(const char *path, int *present) {
  FILE *in = open_regular(path);
  if (!in) return;
  char line[1024];
  long rows = 0;
  if (fgets(line, sizeof line, in))
    while (rows++ < FIGURE_MAX_ROWS && fgets(line, sizeof line, in)) {
      int k = kind_of(line, strcspn(line, ",\n"));
      if (k >= 0) present[k] = 1;
    }
  fclose(in);
}

/* An also folder's curve: type and period from the first line of its
 * summary's results ("  fold curve of the period-6 orbit in ..."); the
 * folder's name and period 0 when it has none. */
static void also_describe(const char *dir, char *type, size_t len,
                          int *period) {
  char path[4200], line[512], t[32];
  snprintf(path, sizeof path, "%s/summary.txt", dir);
  const char *base = strrchr(dir, '/');
  snprintf(type, len, "%.100s", base ? base + 1 : dir);
  *period = 0;
  FILE *in = open_regular(path);
  if (!in) return;
  for (int n = 0; n < 1000 && fgets(line, sizeof line, in); n++)
    if (sscanf(line, "  %31s curve of the period-%d orbit", t, period) == 2) {
      snprintf(type, len, "%s", t);
      break;
    }
  fclose(in);
}

/* Add "TYPE PERIOD" to the title's list, grouped by type: "flip 1, 2;
 * fold 4". */
static void names_add(char *names, size_t len, const char *type, int period) {
  char key[160], tmp[4096];
  snprintf(key, sizeof key, "%s ", type);
  char *at = strstr(names, key);
  while (at && at != names && !(at[-1] == ' ' && at[-2] == ';'))
    at = strstr(at + 1, key);
  if (!at) {
    size_t u = strlen(names);
    if (period > 0)
      snprintf(names + u, len - u, "%s%s %d", u ? "; " : "", type, period);
    else
      snprintf(names + u, len - u, "%s%s", u ? "; " : "", type);
    return;
  }
  char *end = strchr(at, ';');
  size_t head = (size_t)((end ? end : at + strlen(at)) - names);
  snprintf(tmp, sizeof tmp, "%.*s, %d%s", (int)head, names, period,
           end ? end : "");
  snprintf(names, len, "%s", tmp);
}

/* The other curves (also): each in its own colour (sc_plot_curve_rgb,
 * dashed after the twelfth), named by type and period, its points marked
 * by kind in the curve's colour; their kinds are added to @p present.
 * Writes the names, "; "-separated, into @p names. */
static int plot_also(FILE *f, const char *also, int *present, char *names,
                     size_t nlen) {
  char dir[2048], apath[4096], q[4200], what[160], type[128];
  int period;
  int ia = 0;
  names[0] = '\0';
  for (const char *p = also; p && sc_cli_next_word(&p, dir, sizeof dir);) {
    glob_t g;
    if (glob(dir, 0, NULL, &g) != 0) continue; /* checked before the run */
    for (size_t gi = 0; gi < g.gl_pathc; gi++) {
      if (!realpath(g.gl_pathv[gi], apath)) continue;
      also_describe(apath, type, sizeof type, &period);
      if (period > 0)
        snprintf(what, sizeof what, "%s, period %d", type, period);
      else
        snprintf(what, sizeof what, "%s", type);
      names_add(names, nlen, type, period);
      const char *col = sc_plot_curve_rgb(ia);
      int dash = ia / 12 + 1;
      ia++;
      snprintf(q, sizeof q, "%s/curve.csv", apath);
      sc_plot_quote(f, q);
      fprintf(f,
              " skip 1 using 1:2 with lines lw 1.5 dt %d lc rgb '%s' title ",
              dash, col);
      sc_plot_quote(f, what);
      fputs(", \\\n", f);
      int here[NKINDS] = {0};
      snprintf(q, sizeof q, "%s/points.csv", apath);
      kinds_in(q, here);
      for (size_t k = 0; k < NKINDS; k++) {
        if (!here[k]) continue;
        present[k] = 1;
        int pt;
        sc_plot_point_style(point_kinds[k], &pt, NULL, NULL);
        fputs("     ", f);
        sc_plot_quote(f, q);
        fprintf(f, " skip 1 using 2:(lab('%s')) with points pt %d ps 1.2 "
                   "lc rgb '%s' notitle, \\\n",
                point_kinds[k], pt, col);
      }
      fputs("     ", f);
    }
    globfree(&g);
  }
  return ia;
}

/* The plot command's entries for this curve's points, and with other
 * curves (@p nalso of them) the key's markers of every kind in
 * @p present, which gains this curve's kinds. */
static void plot_own_points(FILE *body, const curve_job *j, int nalso,
                            int *present) {
  /* this curve's points: the kinds' own colours without other curves,
   * the curve's colour with them (then the colour tells the curve) */
  int mine[NKINDS] = {0};
  for (size_t i = 0; i < j->c.nsp; i++) {
    int k = kind_of(j->c.sp[i].label, strlen(j->c.sp[i].label));
    if (k >= 0) mine[k] = 1;
  }
  mine[NKINDS - 1] = 1; /* EP: the curve's ends */
  for (size_t k = 0; k < NKINDS; k++) {
    if (!mine[k]) continue;
    present[k] = 1;
    int pt;
    const char *rgb, *what;
    sc_plot_point_style(point_kinds[k], &pt, &rgb, &what);
    char key[96] = "notitle";
    if (!nalso) snprintf(key, sizeof key, "title '%s %s'", point_kinds[k], what);
    fprintf(body,
            "     'points.csv' skip 1 using 2:(lab('%s')) with points pt %d "
            "ps %s lc rgb '%s' %s, \\\n",
            point_kinds[k], pt, nalso ? "1.6" : "2", nalso ? "#1f4e9e" : rgb,
            key);
  }
  /* with several curves the key tells the kinds by marker alone */
  for (size_t k = 0; nalso && k < NKINDS; k++) {
    if (!present[k]) continue;
    int pt;
    const char *what;
    sc_plot_point_style(point_kinds[k], &pt, NULL, &what);
    fprintf(body, "     keyentry with points pt %d ps 1.4 lc rgb '#333333' "
                  "title '%s %s', \\\n",
            pt, point_kinds[k], what);
  }
}

static int curve_plots(sc_cli_run *r, void *job) {
  const curve_job *j = job;
  const sc_scene *s = r->scene;
  sc_map *m = r->map;
  const char *also = sc_scene_text(s, "also");
  char title[512], full[640];
  sc_file *gp = NULL;
  int st;
  if (!also) {
    /* the parameters where the curve starts: the corrected start */
    size_t ix = (size_t)j->set.ix;
    double xs = sc_map_get_param(m, ix);
    if (j->c.have_start) sc_map_set_param(m, ix, j->c.start_x, NULL);
    sc_plot_title(m, NULL, title, sizeof title);
    sc_map_set_param(m, ix, xs, NULL);
    char moved[160] = "";
    if (j->c.have_start && start_moved(j, m))
      snprintf(moved, sizeof moved, "; start moved %.3g from %s = %.10g",
               j->c.start_x - j->x0, j->xn, j->x0);
    snprintf(full, sizeof full, "%s curve, period %d (%.440s%s)",
             type_names[j->ti], j->set.period, title, moved);
    st = sc_cli_plot_begin(r, "curve", full, sc_plot_label(m, j->xn),
                           sc_plot_label(m, j->yn), &gp);
  } else {
    /* Several curves: the title names them all (below) and the values of
     * the parameters that are not on the axes. */
    sc_plot_title_except(m, j->xn, j->yn, title, sizeof title);
    st = sc_cli_plot_begin(r, "curve", title, sc_plot_label(m, j->xn),
                           sc_plot_label(m, j->yn), &gp);
  }
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fprintf(f, "set xrange [%.17g:%.17g]\nset yrange [%.17g:%.17g]\n",
          j->set.xlo, j->set.xhi, j->set.ylo, j->set.yhi);
  sc_plot_axis_format(f, "x", j->set.xlo, j->set.xhi);
  sc_plot_axis_format(f, "y", j->set.ylo, j->set.yhi);
  fputs("set datafile separator ','\n", f);
  const char *ov = sc_scene_text(s, "overlay");
  /* With other curves or a chart the key goes to the right of the plot,
   * one entry a line: clear of the x label however many there are. */
  if (also || ov)
    fputs("set rmargin at screen 0.74\nset key at screen 0.99, screen 0.93 "
          "right top vertical Left reverse font ',9' spacing 1.1 "
          "samplen 2\n",
          f);
  else
    fputs("set key inside right top box opaque\n", f);
  fputs("lab(l) = (strcol(1) eq l || strcol(1) eq l.'?') ? column(3) : "
        "NaN\n",
        f);
  /* the rest of the script is the plot command; the title is set first */
  char body_names[4096];
  int present[NKINDS] = {0};
  char *buf = NULL;
  size_t blen = 0;
  FILE *body = open_memstream(&buf, &blen);
  if (!body) {
    sc_file_abort(gp);
    return sc_fail(r->msg, SC_ENOMEM, "curve: out of memory");
  }
  if (!plot_overlay(body, ov)) fputs("plot ", body);
  int nalso = plot_also(body, also, present, body_names, sizeof body_names);
  if (j->ti == TYPE_NS && sc_cli_curve_n_saddles(j->nd) > 0) {
    /* An NS curve goes on past R1 and R2 as the curve of neutral saddles
     * (kappa outside [-1, 1]: a real pair mu, 1/mu), not a bifurcation:
     * drawn dashed.  curve.csv: x, y, the n components, period, kappa. */
    int kc = 2 + (int)sc_map_dim(r->map) + 2;
    fprintf(body,
            "'curve.csv' skip 1 using 1:(abs($%d) <= 1 ? $2 : NaN) with "
            "lines lw 2.5 lc rgb '#1f4e9e' title 'ns, period %d%s', \\\n"
            "     'curve.csv' skip 1 using 1:(abs($%d) > 1 ? $2 : NaN) with "
            "lines lw 1.5 dt 2 lc rgb '#1f4e9e' title 'neutral saddle "
            "(not NS)', \\\n",
            kc, j->set.period, also ? " (this run)" : "", kc);
  } else {
    fprintf(body,
            "'curve.csv' skip 1 using 1:2 with lines lw 2.5 lc rgb "
            "'#1f4e9e' title '%s, period %d%s', \\\n",
            type_names[j->ti], j->set.period, also ? " (this run)" : "");
  }
  plot_own_points(body, j, nalso, present);
  fputs("     NaN notitle\n", body);
  fclose(body);
  if (nalso) {
    fputs("set title ", f);
    char head[256];
    snprintf(head, sizeof head, "%d curves in (%s, %s): %s %d (this run, "
             "thick) and, by type and period, ",
             nalso + 1, j->xn, j->yn, type_names[j->ti], j->set.period);
    sc_plot_quote(f, head);
    fputs(" . ", f);
    sc_plot_quote(f, body_names);
    fputs(" . \"\\n\" . ", f);
    sc_plot_quote(f, title);
    fputs(" font ',10'\n", f);
  }
  fwrite(buf, 1, blen, f);
  free(buf);
  return sc_cli_plot_end(r, "curve", gp);
}

static int curve_report(sc_cli_run *r, void *job) {
  const curve_job *j = job;
  sc_cli_note(r, "%ld curve points, %ld codimension-two points in %.3f s",
              j->stats.npoints, j->stats.nspecial, j->elapsed);
  return SC_OK;
}

static void curve_release(sc_cli_run *r, void *job) {
  curve_job *j = job;
  (void)r;
  free(j->c.sp);
  sc_cli_curve_n_free(j->nd);
}

const sc_cli_task sc_cli_task_curve = {
    .type = {.kind = "curve",
             .doc = "fold, flip or border curve of a period-m orbit in "
                    "two parameters, with its cusps (CP), generalized flips "
                    "(GPD), turning points (TP), the borders it meets (GR, "
                    "CS, SW, BR, TT) and, on a border curve, folds (LP) and "
                    "flips (PD)",
             .keys = curve_keys,
             .nkeys = sizeof curve_keys / sizeof curve_keys[0],
             .check = curve_check},
    .outputs = "curve.csv (x,y,d,period,multiplier,coefficient,itinerary), "
               "points.csv (label,x,y,d,period,note,coefficient,residual), "
               "summary.txt, curve.gp, curve.png",
    .job_size = sizeof(curve_job),
    .prepare = curve_prepare,
    .compute = curve_compute,
    .summary = curve_summary,
    .plots = curve_plots,
    .report = curve_report,
    .release = curve_release,
};
