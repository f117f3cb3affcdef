/* Task `branch` for maps of n > 1 dimensions: the orbit through d0
 * continued in one parameter, its LP, PD, NS and BP points located by
 * Newton on their defining systems (sc_branchn, branchn.h), switching at
 * PD and BP with `switch = yes`.  See task_branch_n.h and docs/maps.md,
 * "Branches". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/progress.h"
#include "cli/task_branch_n.h"

/* Keys of the one-dimensional branch that mean nothing here, refused
 * when set apart from their defaults: its starts (found by the interval
 * scan of f^m - d; `at` serves), user points, the brute-force sweep's settings (no
 * sweep is drawn under an n-dimensional branch: `sweep` is ignored), the
 * map drawn at a special point, the sparse solver of long orbits. */
static const char *const one_d_keys[] = {
    "starts", "auto-at", "auto-period", "auto-d", "marks", "plot-at",
    "sweep-steps", "sweep-iterations", "sweep-keep", "linsolve"};

/* A key set to other than its default (a key without a default: set at
 * all). */
static int set_apart(const sc_scene *s, const char *key) {
  const char *v = sc_scene_value(s, "task", key);
  const sc_task_type *t = sc_scene_task(s);
  if (!v) return 0;
  for (size_t i = 0; t && i < t->nkeys; i++)
    if (strcmp(t->keys[i].name, key) == 0)
      return !t->keys[i].def || strcmp(t->keys[i].def, v) != 0;
  return 1;
}

int sc_brn_check(const sc_scene *s, sc_msg *msg) {
  const sc_map *m = sc_scene_map(s);
  size_t n = sc_map_dim(m);
  for (size_t k = 0; k < sizeof one_d_keys / sizeof *one_d_keys; k++)
    if (set_apart(s, one_d_keys[k]))
      return sc_scene_fail_key(s, "task", one_d_keys[k], msg,
                               "%s is a key of one-dimensional branches; "
                               "model %s has %zu state components (its "
                               "branch starts from d0 at from)",
                               one_d_keys[k], sc_map_type(m)->name, n);
  if (!sc_scene_text(s, "d0"))
    return sc_scene_fail_key(s, "task", "d0", msg,
                             "no start: give d0 (%zu numbers: a guess of an "
                             "orbit point at `at`, default from)",
                             n);
  if (sc_scene_text(s, "at")) {
    double at = sc_scene_real(s, "at");
    if ((sc_scene_real(s, "from") - at) * (sc_scene_real(s, "to") - at) > 0)
      return sc_scene_fail_key(s, "task", "at", msg,
                               "at = %s outside [from, to]",
                               sc_scene_text(s, "at"));
  }
  int show;
  return sc_cli_show(s, &show, msg);
}

static int on_progress(void *ctx, size_t n) {
  (void)ctx;
  (void)n;
  return sc_cli_interrupted();
}

int sc_brn_prepare(sc_cli_run *r, sc_brn_job *j) {
  const sc_scene *s = r->scene;
  j->pname = sc_scene_text(s, "parameter");
  j->param = (size_t)sc_map_param_index(r->map, j->pname);
  sc_scene_state(s, "d0", j->x0, SC_MAXDIM);
  int st = sc_cli_show(s, &j->show, r->msg);
  if (st) return st;
  int sw = sc_scene_flag(s, "switch");
  j->sp = (sc_branchn_spec){
      .param = j->param,
      .from = sc_scene_real(s, "from"),
      .to = sc_scene_real(s, "to"),
      .period = (int)sc_scene_int(s, "period"),
      .x0 = j->x0,
      .has_at = sc_scene_text(s, "at") != NULL,
      .at = sc_scene_text(s, "at") ? sc_scene_real(s, "at") : 0,
      .switch_pd = sw,
      .switch_bp = sw,
      .max_points = sc_scene_int(s, "max-points"),
      .max_branches = (int)sc_scene_int(s, "max-branches"),
      .max_period = (int)sc_scene_int(s, "max-period"),
      .h0 = sc_scene_real(s, "h0"),
      .hmax = sc_scene_real(s, "hmax"),
      .progress = on_progress,
      .progress_ctx = r,
  };
  return sc_branchn_alloc(r->map, &j->sp, &j->b, r->msg);
}

int sc_brn_compute(sc_cli_run *r, sc_brn_job *j) {
  double t0 = sc_progress_now();
  unsigned long ev0 = sc_map_nevals(r->map);
  int st = sc_branchn_run(j->b, r->msg);
  j->elapsed = sc_progress_now() - t0;
  j->nev = sc_map_nevals(r->map) - ev0;
  if (st == SC_ENOCONV || st == SC_EINVAL) {
    const sc_scene *s = r->scene;
    const char *at = sc_scene_text(s, sc_scene_text(s, "at") ? "at" : "from");
    char why[SC_MSG_LEN];
    snprintf(why, sizeof why, "%s", sc_msg_what(r->msg->text));
    return sc_scene_fail_key(
        s, "task", "d0", r->msg,
        "d0 = %s at %s = %s: %s; to find starts, run the fixed-point task "
        "there (kind = fixed-point, period = %d, [model] %s = %s)",
        sc_scene_text(s, "d0"), j->pname, at, why, j->sp.period, j->pname,
        at);
  }
  return st;
}

/* ------------------------------------------------------------------ */
/* Files                                                                */

static int write_branch(sc_cli_run *r, const sc_brn_job *j) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "branch.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  size_t n = sc_map_dim(r->map);
  fprintf(f, "%s,", j->pname);
  sc_csv_state_header(f, r->map, "");
  fputs(",multiplier,multipliers,stable,period,branch\n", f);
  sc_branchn_point pt;
  for (size_t i = 0; i < sc_branchn_npoints(j->b); i++) {
    sc_branchn_point_get(j->b, i, &pt);
    sc_csv_double(f, pt.p);
    fputc(',', f);
    sc_csv_state(f, pt.x, n);
    fputc(',', f);
    sc_csv_double(f, pt.multiplier);
    fputc(',', f);
    sc_csv_multipliers(f, pt.re, pt.im, n);
    fprintf(f, ",%s,%d,%d\n", pt.stable ? "yes" : "no", pt.period,
            pt.branch);
  }
  return sc_cli_commit(r, "branch.csv", csv);
}

static int write_points(sc_cli_run *r, const sc_brn_job *j) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "points.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  size_t n = sc_map_dim(r->map);
  fputs("label,parameter,value,", f);
  sc_csv_state_header(f, r->map, "");
  fputs(",period,multiplier,multipliers,coefficient,kappa,theta,residual,"
        "error,iterations,method,note\n",
        f);
  sc_branchn_special sp;
  for (size_t i = 0; i < sc_branchn_nspecial(j->b); i++) {
    sc_branchn_special_get(j->b, i, &sp);
    fprintf(f, "%s,%s,", sc_branchn_label_text(sp.label), j->pname);
    sc_csv_double(f, sp.p);
    fputc(',', f);
    sc_csv_state(f, sp.x, n);
    fprintf(f, ",%d,", sp.period);
    double mult = sp.im[0] == 0 ? sp.re[0] : hypot(sp.re[0], sp.im[0]);
    sc_csv_double(f, mult);
    fputc(',', f);
    sc_csv_multipliers(f, sp.re, sp.im, n);
    fputc(',', f);
    sc_csv_double(f, sp.coef);
    fputc(',', f);
    sc_csv_double(f, sp.kappa);
    fputc(',', f);
    sc_csv_double(f, sp.theta);
    fputc(',', f);
    sc_csv_double(f, sp.residual);
    fputc(',', f);
    sc_csv_double(f, sp.error);
    char note[512];
    if (sp.branch < 0) snprintf(note, sizeof note, "%s", sp.note);
    else snprintf(note, sizeof note, "branch %d%s%s", sp.branch,
                  *sp.note ? ": " : "", sp.note);
    fprintf(f, ",%d,%s,%s\n", sp.iterations, sc_location_method_text(sp.method),
            sc_cli_csv_text(note));
  }
  return sc_cli_commit(r, "points.csv", csv);
}

/* The value drawn of a state (`show`: a component or the norm). */
static double shown(const sc_brn_job *j, const double *x, size_t n) {
  return sc_cli_show_value(j->show, x, n);
}

/* The k-th iterate of the orbit through x at parameter p (k < period). */
static int iterate_to(sc_cli_run *r, const sc_brn_job *j, const double *x,
                      double p, int k, sc_mapn_value *v, double *out) {
  size_t n = sc_map_dim(r->map);
  memcpy(out, x, n * sizeof *x);
  if (k == 0) return SC_OK;
  if (sc_map_set_param(r->map, j->param, p, NULL) ||
      sc_map_iterate_n(r->map, x, k, 0, v, NULL))
    return SC_EUNDEF;
  memcpy(out, v->f, n * sizeof *out);
  return SC_OK;
}

/* A branch point whose multiplier of largest modulus is within this of
 * modulus 1 is a zero of a stability test located on the branch (an LP,
 * PD or NS point, to the continuation's tolerance, ~1e-12): the boundary
 * between the stable and unstable parts, whichever side rounding put it
 * on.  An ordinary point is a step away, its multipliers typically 1e-3
 * or more from modulus 1, so 1e-8 separates the two. */
#define BN_PLOT_NEUTRAL 1e-8

/* branch-orbits.csv: for each segment and each k < m the k-th orbit point,
 * drawn: one block per (segment, k); branch-points.csv: the special
 * points as drawn. */
static int write_plot_data(sc_cli_run *r, const sc_brn_job *j) {
  sc_file *orb = NULL, *pts = NULL;
  int st = sc_cli_open(r, "branch-orbits.csv", &orb);
  if (!st) st = sc_cli_open(r, "branch-points.csv", &pts);
  if (st) return st;
  FILE *g = sc_file_stream(orb), *h = sc_file_stream(pts);
  size_t n = sc_map_dim(r->map), np = sc_branchn_npoints(j->b);
  double saved = sc_map_get_param(r->map, j->param), y[SC_MAXDIM];
  sc_mapn_value *v = NULL;
  if ((st = sc_mapn_value_alloc(r->map, 0, &v, r->msg))) return st;
  fprintf(g, "# every orbit point along each branch: one block per branch "
             "and point index k\n%s,shown_stable,shown_unstable,k,branch\n",
          j->pname);
  sc_branchn_point pt;
  for (int b = 0; b < sc_branchn_nbranches(j->b); b++) {
    int q = 0;
    for (size_t i = 0; i < np && !q; i++)
      if (sc_branchn_point_get(j->b, i, &pt) == SC_OK && pt.branch == b)
        q = pt.period;
    for (int k = 0; k < q; k++) {
      int prev = -1; /* the previous point's stability: a point where it
                        changes is drawn in both columns, so the lines
                        meet; a located test zero (neutral, 2) is drawn
                        in both, so the part past it has its own style */
      for (size_t i = 0; i < np; i++) {
        sc_branchn_point_get(j->b, i, &pt);
        if (pt.branch != b || iterate_to(r, j, pt.x, pt.p, k, v, y)) continue;
        double s = shown(j, y, n);
        int neutral = fabs(fabs(pt.multiplier) - 1) <= BN_PLOT_NEUTRAL;
        sc_csv_double(g, pt.p);
        fputc(',', g);
        sc_csv_double(g, pt.stable || neutral || prev == 1 ? s : NAN);
        fputc(',', g);
        sc_csv_double(g, !pt.stable || neutral || prev == 0 ? s : NAN);
        fprintf(g, ",%d,%d\n", k, b);
        prev = neutral ? 2 : pt.stable;
      }
      fputs("\n\n", g);
    }
  }
  fputs("number,label,parameter,shown\n", h);
  sc_branchn_special sp;
  for (size_t i = 0, num = 0; i < sc_branchn_nspecial(j->b); i++) {
    sc_branchn_special_get(j->b, i, &sp);
    if (sp.label == SC_PTN_EP) continue;
    fprintf(h, "%zu,%s,", ++num, sc_branchn_label_text(sp.label));
    sc_csv_double(h, sp.p);
    fputc(',', h);
    sc_csv_double(h, shown(j, sp.x, n));
    fputc('\n', h);
  }
  sc_mapn_value_free(v);
  sc_map_set_param(r->map, j->param, saved, NULL);
  st = sc_cli_commit(r, "branch-orbits.csv", orb);
  return st ? st : sc_cli_commit(r, "branch-points.csv", pts);
}

int sc_brn_write(sc_cli_run *r, const sc_brn_job *j) {
  int st = write_branch(r, j);
  if (!st) st = write_points(r, j);
  if (!st) st = write_plot_data(r, j);
  return st;
}

/* ------------------------------------------------------------------ */
/* Summary, plot, report                                                */

static const char *coef_name(sc_branchn_label l) {
  return l == SC_PTN_LP ? "a" : l == SC_PTN_PD ? "b" : "d";
}

int sc_brn_summary(sc_cli_run *r, const sc_brn_job *j, FILE *f) {
  const sc_branchn *b = j->b;
  size_t n = sc_map_dim(r->map), ns = sc_branchn_nspecial(b);
  fprintf(f, "  branches: %d, points: %zu, special points: %zu\n",
          sc_branchn_nbranches(b), sc_branchn_npoints(b), ns);
  int count[SC_PTN_NLABELS] = {0}, newton = 0, failed = 0;
  sc_branchn_special sp;
  for (size_t i = 0; i < ns; i++) {
    sc_branchn_special_get(b, i, &sp);
    count[sp.label]++;
    newton += sp.method == SC_LOC_NEWTON;
    failed += sp.method == SC_LOC_FAILED;
  }
  fputs("  by label:", f);
  for (int l = 0; l < SC_PTN_NLABELS; l++)
    if (count[l]) fprintf(f, " %s %d", sc_branchn_label_text(l), count[l]);
  fprintf(f, "\n  located by Newton on their defining systems with a residual "
             "certificate: %d; detected but NOT located: %d\n",
          newton, failed);
  fprintf(f, "  met again by another segment (reported once): %zu\n",
          sc_branchn_nduplicate(b));
  for (size_t i = 0; i < ns; i++) {
    sc_branchn_special_get(b, i, &sp);
    fprintf(f, "  %s  %s = %.17g  x = ", sc_branchn_label_text(sp.label),
            j->pname, sp.p);
    sc_cli_put_state(f, sp.x, n);
    fprintf(f, "  period %d\n      ", sp.period);
    if (sp.method != SC_LOC_NONE)
      fprintf(f, "%s: residual %.3g, error %.3g; ",
              sc_location_method_text(sp.method), sp.residual, sp.error);
    if (isfinite(sp.coef))
      fprintf(f, "%s = %.10g; ", coef_name(sp.label), sp.coef);
    if (isfinite(sp.theta)) fprintf(f, "theta = %.10g; ", sp.theta);
    if (sp.branch >= 0) fprintf(f, "branch %d%s", sp.branch, *sp.note ? ": " : "");
    fprintf(f, "%s\n", sp.note);
  }
  fprintf(f, "  continuation: %.3f s, %lu map evaluations\n", j->elapsed,
          j->nev);
  return SC_OK;
}

int sc_brn_plots(sc_cli_run *r, const sc_brn_job *j) {
  sc_map *m = r->map;
  char title[512], yl[64];
  sc_plot_title(m, j->pname, title, sizeof title);
  sc_cli_show_label(m, j->show, yl, sizeof yl);
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "branch", title, sc_plot_label(m, j->pname),
                             yl, &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fprintf(f, "set xrange [%.17g:%.17g]\n", fmin(j->sp.from, j->sp.to),
          fmax(j->sp.from, j->sp.to));
  fputs("set key outside right top box opaque\n", f);
  fputs("plot 'branch-orbits.csv' skip 2 using 1:2 with lines lw 2 "
        "lc rgb '#1f4e9e' title 'stable', \\\n",
        f);
  fputs("     'branch-orbits.csv' skip 2 using 1:3 with lines lw 1.5 dt 2 "
        "lc rgb '#d62728' title 'unstable'",
        f);
  static const char *const kinds[] = {"LP", "PD", "NS", "NN", "BP",
                                      "GR", "CS", "SW", "BR", "TT"};
  for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++) {
    int present = 0;
    sc_branchn_special sp;
    for (size_t i = 0; i < sc_branchn_nspecial(j->b) && !present; i++)
      present = sc_branchn_special_get(j->b, i, &sp) == SC_OK &&
                strcmp(sc_branchn_label_text(sp.label), kinds[k]) == 0;
    if (!present) continue;
    int pt;
    const char *rgb, *what;
    sc_plot_point_style(kinds[k], &pt, &rgb, &what);
    fprintf(f, ", \\\n     'branch-points.csv' skip 1 using 3:(strcol(2) eq "
               "'%s' ? $4 : NaN) with points pt %d ps 1.6 lc rgb '%s' "
               "title '%s'",
            kinds[k], pt, rgb, kinds[k]);
  }
  fputs(", \\\n     'branch-points.csv' skip 1 using 3:4:(sprintf('%d', $1)) "
        "with labels offset 0.8,0.8 font 'Sans,9' notitle\n",
        f);
  return sc_cli_plot_end(r, "branch", gp);
}

int sc_brn_report(sc_cli_run *r, const sc_brn_job *j) {
  sc_cli_note(r, "%d branches, %zu points, %zu special points in %.2f s",
              sc_branchn_nbranches(j->b), sc_branchn_npoints(j->b),
              sc_branchn_nspecial(j->b), j->elapsed);
  return SC_OK;
}

void sc_brn_release(sc_brn_job *j) {
  sc_branchn_free(j->b);
  j->b = NULL;
}
