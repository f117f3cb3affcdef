/* Task `curve`: the fold or flip curve of a period-m orbit in two
 * parameters, its codimension-two points (CP, GPD, TP) and where it ends
 * (sc_curve_trace, curve.h; docs/curves.md). */
#define _XOPEN_SOURCE 700 /* realpath */

#include <glob.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/progress.h"
#include "cli/tasks.h"
#include "slipcont/curve.h"

static const sc_key_info curve_keys[] = {
    {"type", SC_KEY_CHOICE, 1, NULL, 0, 0, 0, 0,
     "fold|flip|graze|cross|switch|both|touch",
     "fold: multiplier +1 (f^m(d) = d, (f^m)' = 1); flip: (f^m)' = -1; "
     "graze, cross, switch, both, touch: the orbit on its nearest border of "
     "that kind (GR, CS, SW, BR, TT), f^m(d) = d and m_k = 0"},
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
    {"d0", SC_KEY_REAL, 0, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "guess of an orbit point at the start (or give start)"},
    {"start", SC_KEY_TEXT, 0, NULL, 0, 0, 0, 0, NULL,
     "FILE:N, row N (1 = first after the header) of a branch task's "
     "points.csv: an LP (type = fold), PD (type = flip) or border point "
     "(GR for graze, CS cross, SW switch, BR both, TT touch) located in x; "
     "x, d0 and period are taken from it (instead of d0)"},
    {"shooting", SC_KEY_CHOICE, 0, "single", 0, 0, 0, 0, "single|multiple",
     "single: on f^m in (d, x, y); multiple: one equation per iterate in "
     "(d_0..d_{m-1}, x, y), for long periods"},
    {"h0", SC_KEY_REAL, 0, "0", 0, HUGE_VAL, 0, 1, NULL,
     "initial arclength step in (d, x, y) (0: hmax / 10)"},
    {"hmax", SC_KEY_REAL, 0, "0", 0, HUGE_VAL, 0, 1, NULL,
     "largest arclength step (0: the box's smaller side / 50)"},
    {"max-points", SC_KEY_INT, 0, "5000", 2, 10000000, 0, 0, NULL,
     "accepted points per direction"},
    {"overlay", SC_KEY_TEXT, 0, NULL, 0, 0, 0, 0, NULL,
     "a chart.csv of the chart task over the same x and y, drawn under "
     "the curve (path relative to the working folder)"},
    {"also", SC_KEY_TEXT, 0, NULL, 0, 0, 0, 0, NULL,
     "output folders of other curve tasks (separated by spaces; shell "
     "patterns such as out/curve-fig58-* allowed), whose curves and "
     "labelled points are drawn in the same plot"},
};

/* The folders of `also`, one at a time: copies the next word of *p into
 * buf and advances; 0 at the end. */
static int next_word(const char **p, char *buf, size_t len) {
  const char *s = *p + strspn(*p, " \t");
  size_t n = strcspn(s, " \t");
  if (n == 0) return 0;
  snprintf(buf, len, "%.*s", (int)n, s);
  *p = s + n;
  return 1;
}

/* The curve types in key order; border kinds of the border types. */
static const char *const type_names[] = {"fold",  "flip", "graze", "cross",
                                         "switch", "both", "touch"};
static const char *const type_labels[] = {"LP", "PD", "GR", "CS",
                                          "SW", "BR", "TT"};
static const sc_border_kind type_kinds[] = {
    0, 0, SC_BORDER_GRAZING, SC_BORDER_CROSSING, SC_BORDER_SWITCHING,
    SC_BORDER_BOTH, SC_BORDER_TOUCH};

static int type_index(const char *t) {
  for (int i = 0; i < 7; i++)
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
  for (const char *p = also; p && next_word(&p, dir, sizeof dir);) {
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
  if (type_index(sc_scene_text(s, "type")) >= 2 && !sc_map_has_borders(m))
    return sc_scene_fail_key(s, "task", "type", msg,
                             "type = %s: model %s declares no borders "
                             "(valid: fold or flip)",
                             sc_scene_text(s, "type"), sc_map_type(m)->name);
  const char *spec = sc_scene_text(s, "start");
  int has_d0 = !isnan(sc_scene_real(s, "d0"));
  if (!spec == !has_d0)
    return sc_scene_fail_key(s, "task", spec ? "start" : "d0", msg,
                             "give either d0 or start (valid: exactly one "
                             "of them)");
  sc_cli_points_row row;
  if (spec) {
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
    if (k == 0 && spec) v = row.value;
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
  const char *ov = sc_scene_text(s, "overlay");
  if (ov) return overlay_check(s, ov, xn, yn, msg);
  return SC_OK;
}

typedef struct {
  FILE *curve, *points;
  int period;
  int last_branch;
  sc_curve_special *sp;
  size_t nsp, cap;
  int oom;
} out_ctx;

static int on_point(void *vc, const sc_curve_point *p) {
  out_ctx *c = vc;
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
  unsigned long nev;
  double elapsed;
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
  set->type = j->ti == 0   ? SC_CURVE_FOLD
              : j->ti == 1 ? SC_CURVE_FLIP
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
  j->d0 = sc_scene_real(s, "d0");
  const char *spec = sc_scene_text(s, "start");
  if (!spec) return SC_OK;
  /* checked by curve_check(): the row exists and fits */
  sc_cli_points_row row;
  char why[512];
  if (sc_cli_points_row_read(spec, &row, why, sizeof why))
    return sc_fail(r->msg, SC_EIO, "curve: start = %s: %s", spec, why);
  j->d0 = row.d;
  set->period = row.period;
  return sc_map_set_param(m, (size_t)set->ix, row.value, r->msg);
}

/* The trace, streamed into curve.csv and points.csv. */
static int curve_compute(sc_cli_run *r, void *job) {
  curve_job *j = job;
  sc_map *m = r->map;
  out_ctx *c = &j->c;
  c->period = j->set.period;
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
  unsigned long ev0 = sc_map_nevals(m);
  double t0 = sc_progress_now();
  st = sc_curve_trace(m, &j->set, j->d0, &out, &j->stats, r->msg);
  j->elapsed = sc_progress_now() - t0;
  j->nev = sc_map_nevals(m) - ev0;
  if (st == SC_ECALLBACK && (c->oom || sc_cli_interrupted()))
    sc_fail(r->msg, st, "curve: %s", c->oom ? "out of memory" : "interrupted");
  if (!st) st = sc_cli_commit(r, "curve.csv", cf);
  return st ? st : sc_cli_commit(r, "points.csv", pf);
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
  if (stats->border_iterate >= 0)
    fprintf(f, "  border followed: %s, %s, iterate %d of %d\n",
            type_labels[j->ti], stats->border, stats->border_iterate + 1,
            j->set.period);
  fprintf(f, "  shooting: %s\n", j->set.multiple ? "multiple" : "single");
  fprintf(f, "  codimension-two points: %ld\n", stats->nspecial);
  for (size_t i = 0; i < j->c.nsp; i++) {
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

/* The chart of `overlay` in light colours under the curve (undefined
 * points, period -1, left out); 1 if drawn. */
static int plot_overlay(FILE *f, const char *ov) {
  char path[4096];
  if (!ov || !realpath(ov, path)) return 0;
  fputs("set palette defined (0 '#f2f2f2', 1 '#cfe3f7', 4 '#d9f2d0', "
        "8 '#fbe3c8', 16 '#f6cfd6')\n"
        "set cbrange [0:16]\nset cblabel 'period of the chart'\n",
        f);
  fputs("plot ", f);
  sc_plot_quote(f, path);
  fputs(" skip 1 using 1:2:($3 < 0 ? NaN : $3) with image notitle, \\\n"
        "     ",
        f);
  return 1;
}

/* The other curves (also): thin lines, their points labelled. */
static void plot_also(FILE *f, const char *also) {
  static const char *const acol[6] = {"#b2182b", "#2166ac", "#1b7837",
                                      "#762a83", "#e08214", "#4d4d4d"};
  char dir[2048], apath[4096], q[4200];
  int ia = 0;
  for (const char *p = also; p && next_word(&p, dir, sizeof dir);) {
    glob_t g;
    if (glob(dir, 0, NULL, &g) != 0) continue; /* checked before the run */
    for (size_t gi = 0; gi < g.gl_pathc; gi++) {
      if (!realpath(g.gl_pathv[gi], apath)) continue;
      const char *base = strrchr(apath, '/');
      base = base ? base + 1 : apath;
      const char *col = acol[ia++ % 6];
      snprintf(q, sizeof q, "%s/curve.csv", apath);
      sc_plot_quote(f, q);
      fprintf(f,
              " skip 1 using 1:2 with lines lw 1.5 lc rgb '%s' title '%s', "
              "\\\n     ",
              col, base);
      snprintf(q, sizeof q, "%s/points.csv", apath);
      sc_plot_quote(f, q);
      fprintf(f,
              " skip 1 using 2:(strcol(1) eq 'EP' ? NaN : column(3)):1 with "
              "labels point pt 7 ps 0.8 lc rgb '%s' offset 0.6,0.6 font ',8' "
              "tc rgb '%s' notitle, \\\n     ",
              col, col);
    }
    globfree(&g);
  }
}

/* This curve's special points: each label present once in the key. */
static void plot_labels(FILE *f, const out_ctx *c) {
  static const char *const labels[11] = {"CP", "GPD", "TP", "LP", "PD", "GR",
                                         "CS", "SW",  "BR", "TT", "EP"};
  static const char *const colors[11] = {
      "#d62728", "#9467bd", "#2ca02c", "#ff7f0e", "#8c564b", "#e377c2",
      "#17becf", "#bcbd22", "#1f77b4", "#7f7f7f", "#777777"};
  static const int pts[11] = {7, 5, 9, 11, 13, 4, 8, 10, 12, 3, 6};
  int nk = 0, shown[11];
  for (int k = 0; k < 11; k++) {
    shown[k] = k == 10;
    for (size_t i = 0; i < c->nsp && !shown[k]; i++)
      shown[k] = strcmp(c->sp[i].label, labels[k]) == 0;
    nk += shown[k];
  }
  for (int k = 0; k < 11; k++)
    if (shown[k])
      fprintf(f,
              "     'points.csv' skip 1 using 2:(lab('%s')) with points pt "
              "%d ps 2 lc rgb '%s' title '%s'%s\n",
              labels[k], pts[k], colors[k], labels[k], --nk ? ", \\" : "");
}

static int curve_plots(sc_cli_run *r, void *job) {
  const curve_job *j = job;
  const sc_scene *s = r->scene;
  sc_map *m = r->map;
  char title[512], full[640];
  sc_plot_title(m, NULL, title, sizeof title);
  snprintf(full, sizeof full, "%s curve, period %d (%s)", type_names[j->ti],
           j->set.period, title);
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "curve", full, sc_plot_label(m, j->xn),
                             sc_plot_label(m, j->yn), &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fprintf(f, "set xrange [%.17g:%.17g]\nset yrange [%.17g:%.17g]\n",
          j->set.xlo, j->set.xhi, j->set.ylo, j->set.yhi);
  fputs("set datafile separator ','\n", f);
  /* with other curves drawn the key goes under the plot */
  fputs(sc_scene_text(s, "also") ? "set key below horizontal font ',9'\n"
                                 : "set key inside right top box opaque\n",
        f);
  fputs("lab(l) = strcol(1) eq l ? column(3) : NaN\n", f);
  if (!plot_overlay(f, sc_scene_text(s, "overlay"))) fputs("plot ", f);
  plot_also(f, sc_scene_text(s, "also"));
  fprintf(f,
          "'curve.csv' skip 1 using 1:2 with lines lw 2 lc rgb "
          "'#1f4e9e' title '%s curve', \\\n",
          type_names[j->ti]);
  plot_labels(f, &j->c);
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
