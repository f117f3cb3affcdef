/* Task `fixed-point` for maps of n > 1 dimensions: Newton from a grid of
 * a box and from points of the attractor, period after period, with the
 * orbits found deflated (sc_fixed_points_n_find(), orbits.h); or Newton
 * from the one start d0.  See task_fixed_point_n.h. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/progress.h"
#include "cli/task_fixed_point_n.h"

/* Defaults of the keys that have none in the shared table (the
 * one-dimensional search reads `steps` otherwise): 21 points per axis
 * (441 starts in 2-d), 1000 attractor points after 1000 iterates: on the
 * Henon map at a = 1.4, b = 0.3 they find all orbits of periods 1..12
 * (docs/maps.md) in a few seconds. */
#define FPN_STEPS 21
#define FPN_ATTRACTOR 1000
#define FPN_TRANSIENT 1000

int sc_fpn_check(const sc_scene *s, long lo, long hi, sc_msg *msg) {
  const sc_map *m = sc_scene_map(s);
  size_t n = sc_map_dim(m);
  if (lo < 1 || hi > SC_FIXED_POINTS_N_MAX_PERIOD)
    return sc_scene_fail_key(s, "task", "period", msg,
                             "period = %s (valid for n > 1: m in [1, %d], or "
                             "m1..m2 with 1 <= m1 <= m2 <= %d)",
                             sc_scene_text(s, "period"),
                             SC_FIXED_POINTS_N_MAX_PERIOD,
                             SC_FIXED_POINTS_N_MAX_PERIOD);
  if (sc_scene_value(s, "task", "d0")) return SC_OK;
  static const char *const box[] = {"from", "to"};
  for (int k = 0; k < 2; k++)
    if (!sc_scene_value(s, "task", box[k]))
      return sc_scene_fail_key(s, "task", box[k], msg,
                               "missing key '%s': the search needs a box "
                               "(from, to: %zu numbers each) or a start "
                               "(d0 = %zu numbers)",
                               box[k], n, n);
  double from[SC_MAXDIM], to[SC_MAXDIM];
  sc_scene_state(s, "from", from, SC_MAXDIM);
  sc_scene_state(s, "to", to, SC_MAXDIM);
  for (size_t c = 0; c < n; c++)
    if (!(from[c] < to[c])) {
      char name[32];
      return sc_scene_fail_key(s, "task", "to", msg,
                               "to = %s is not above from = %s in component "
                               "%zu (%s) (valid: every component of to > "
                               "from's)",
                               sc_scene_text(s, "to"), sc_scene_text(s, "from"),
                               c + 1,
                               sc_map_state_component(m, c, name, sizeof name));
    }
  double steps = sc_scene_value(s, "task", "steps")
                     ? (double)sc_scene_int(s, "steps")
                     : FPN_STEPS;
  double attr = sc_scene_value(s, "task", "attractor")
                    ? (double)sc_scene_int(s, "attractor")
                    : FPN_ATTRACTOR;
  double total = pow(steps, (double)n) + attr;
  if (!(total <= SC_FIXED_POINTS_N_MAX_STARTS))
    return sc_scene_fail_key(s, "task", "steps", msg,
                             "steps = %.0f per axis in %zu dimensions with %.0f "
                             "attractor points: %.3g starts (valid: steps^%zu "
                             "+ attractor <= %d)",
                             steps, n, attr, total, n,
                             SC_FIXED_POINTS_N_MAX_STARTS);
  return SC_OK;
}

int sc_fpn_prepare(sc_cli_run *r, long lo, long hi, sc_fpn_job *j) {
  const sc_scene *s = r->scene;
  size_t n = sc_map_dim(r->map);
  sc_fixed_points_n_spec *sp = &j->sp;
  *sp = (sc_fixed_points_n_spec){
      .period_lo = (int)lo, .period_hi = (int)hi, .steps = FPN_STEPS,
      .attractor = FPN_ATTRACTOR, .transient = FPN_TRANSIENT,
      .method = SC_SHOOT_MULTIPLE};
  if (sc_scene_value(s, "task", "d0")) {
    sc_scene_state(s, "d0", j->start, n);
    sp->start = j->start;
  } else {
    sc_scene_state(s, "from", j->from, n);
    sc_scene_state(s, "to", j->to, n);
    sp->from = j->from;
    sp->to = j->to;
  }
  if (sc_scene_value(s, "task", "steps"))
    sp->steps = (size_t)sc_scene_int(s, "steps");
  if (sc_scene_value(s, "task", "attractor"))
    sp->attractor = (size_t)sc_scene_int(s, "attractor");
  if (sc_scene_value(s, "task", "transient"))
    sp->transient = sc_scene_int(s, "transient");
  const char *sh = sc_scene_text(s, "shooting");
  if (sh && strcmp(sh, "single") == 0) sp->method = SC_SHOOT_SINGLE;
  return SC_OK;
}

/* The search cannot be stopped from outside: a signal during it ends the
 * process after SC_CLI_STOP_GRACE_S (tasks.h), before any file is
 * opened. */
int sc_fpn_compute(sc_cli_run *r, sc_fpn_job *j) {
  unsigned long ev0 = sc_map_nevals(r->map);
  double t0 = sc_progress_now();
  int st = sc_cli_stop(r);
  if (!st) st = sc_fixed_points_n_find(r->map, &j->sp, &j->set, r->msg);
  j->elapsed = sc_progress_now() - t0;
  j->nev = sc_map_nevals(r->map) - ev0;
  return st;
}

/* orbits.csv: one row an orbit, by period then first point. */
static int write_orbits(sc_cli_run *r, const sc_fpn_job *j) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "orbits.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  size_t n = sc_map_dim(r->map);
  fputs("period,multiplier,multipliers,stable,residual,", f);
  sc_csv_state_header(f, r->map, "start_");
  fputs(",points\n", f);
  sc_orbitn_info o;
  for (size_t i = 0; i < sc_orbitn_set_count(j->set); i++) {
    sc_orbitn_set_get(j->set, i, &o);
    fprintf(f, "%d,", o.period);
    sc_csv_double(f, o.multiplier);
    fputc(',', f);
    sc_csv_multipliers(f, o.mult_re, o.mult_im, n);
    fprintf(f, ",%s,", o.stable ? "yes" : "no");
    sc_csv_double(f, o.residual);
    fputc(',', f);
    sc_csv_state(f, o.start, n);
    fputc(',', f);
    sc_csv_points(f, o.x, (size_t)o.period, n);
    fputc('\n', f);
  }
  return sc_cli_commit(r, "orbits.csv", csv);
}

/* periods.csv: per period, the orbits and what the starts gave. */
static int write_counts(sc_cli_run *r, const sc_fpn_job *j) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "periods.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("period,orbits,stable,unstable,starts,known,lower_period,"
        "outside_box,failed\n",
        f);
  sc_orbitn_info o;
  for (int m = j->sp.period_lo; m <= j->sp.period_hi; m++) {
    size_t no = 0, ns = 0, nf = 0;
    for (size_t i = 0; i < sc_orbitn_set_count(j->set); i++) {
      sc_orbitn_set_get(j->set, i, &o);
      no += o.period == m;
      ns += o.period == m && o.stable;
    }
    sc_orbitn_stats s;
    sc_orbitn_set_stats(j->set, m, &s);
    for (int k = 1; k < SC_SHOOTN_NREASONS; k++) nf += s.failed[k];
    fprintf(f, "%d,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu\n", m, no, ns, no - ns,
            s.starts, s.known, s.lower, s.outside, nf);
  }
  return sc_cli_commit(r, "periods.csv", csv);
}

/* fixed-point-orbits.csv: every orbit point, for the plot. */
static int write_points(sc_cli_run *r, const sc_fpn_job *j) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "fixed-point-orbits.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  size_t n = sc_map_dim(r->map);
  sc_csv_state_header(f, r->map, "");
  fputs(",stable,orbit,period\n", f);
  sc_orbitn_info o;
  for (size_t i = 0; i < sc_orbitn_set_count(j->set); i++) {
    sc_orbitn_set_get(j->set, i, &o);
    for (int k = 0; k < o.period; k++) {
      sc_csv_state(f, o.x + (size_t)k * n, n);
      fprintf(f, ",%d,%zu,%d\n", o.stable, i + 1, o.period);
    }
  }
  return sc_cli_commit(r, "fixed-point-orbits.csv", csv);
}

int sc_fpn_write(sc_cli_run *r, const sc_fpn_job *j) {
  int st = write_orbits(r, j);
  if (!st) st = write_counts(r, j);
  if (!st) st = write_points(r, j);
  return st;
}

/* What the starts of period m gave, failures grouped by reason. */
static void starts_line(FILE *f, const sc_orbitn_stats *s) {
  size_t nf = 0;
  for (int k = 1; k < SC_SHOOTN_NREASONS; k++) nf += s->failed[k];
  fprintf(f, "    starts %zu: new orbits %zu, known orbits %zu, lower period "
             "%zu, outside the box %zu, failed %zu",
          s->starts, s->found, s->known, s->lower, s->outside, nf);
  const char *sep = " (";
  for (int k = 1; k < SC_SHOOTN_NREASONS; k++)
    if (s->failed[k]) {
      fprintf(f, "%s%s: %zu", sep, sc_shootn_reason_text((sc_shootn_reason)k),
              s->failed[k]);
      sep = "; ";
    }
  fputs(*sep == ';' ? ")\n" : "\n", f);
}

int sc_fpn_summary(sc_cli_run *r, const sc_fpn_job *j, FILE *f) {
  const sc_fixed_points_n_spec *sp = &j->sp;
  size_t n = sc_map_dim(r->map), total = sc_orbitn_set_count(j->set);
  size_t ngrid, nattr, nstable = 0;
  sc_orbitn_set_starts(j->set, &ngrid, &nattr);
  sc_orbitn_info o;
  for (size_t i = 0; i < total; i++) {
    sc_orbitn_set_get(j->set, i, &o);
    nstable += (size_t)o.stable;
  }
  fprintf(f, "  orbits of minimal periods %d..%d (%s shooting, orbits already "
             "found deflated): %zu, each once (%zu stable)\n",
          sp->period_lo, sp->period_hi,
          sp->method == SC_SHOOT_SINGLE ? "single" : "multiple", total,
          nstable);
  if (sp->start) {
    fputs("  start: d0 = ", f);
    sc_cli_put_state(f, sp->start, n);
    fputs(" alone\n", f);
  } else {
    fprintf(f, "  starts a period: %zu grid points (%zu per axis) of the box ",
            ngrid, sp->steps);
    sc_cli_put_state(f, sp->from, n);
    fputs(" .. ", f);
    sc_cli_put_state(f, sp->to, n);
    fprintf(f, ", %zu attractor points (after %ld iterates)\n", nattr,
            sp->transient);
  }
  for (int m = sp->period_lo; m <= sp->period_hi; m++) {
    size_t no = 0, ns = 0;
    for (size_t i = 0; i < total; i++) {
      sc_orbitn_set_get(j->set, i, &o);
      no += o.period == m;
      ns += o.period == m && o.stable;
    }
    fprintf(f, "  period %d: %zu orbits (%zu stable)\n", m, no, ns);
    sc_orbitn_stats s;
    sc_orbitn_set_stats(j->set, m, &s);
    starts_line(f, &s);
    for (size_t i = 0; i < total; i++) {
      sc_orbitn_set_get(j->set, i, &o);
      if (o.period != m) continue;
      fputs("    x = ", f);
      sc_cli_put_state(f, o.x, n);
      fprintf(f, ", multiplier %.17g (%s), residual %.3g\n", o.multiplier,
              o.stable ? "stable" : "unstable", o.residual);
    }
  }
  fprintf(f, "  map evaluations: %lu; time %.3f s\n", j->nev, j->elapsed);
  return SC_OK;
}

/* n = 2: the orbit points in the plane, coloured by period, stable ones
 * filled, unstable ones open. */
int sc_fpn_plots(sc_cli_run *r, const sc_fpn_job *j) {
  sc_map *m = r->map;
  if (sc_map_dim(m) != 2) return SC_OK; /* a plane only for n = 2 */
  char title[512], full[700], xn[32], yn[32];
  sc_plot_title(m, NULL, title, sizeof title);
  snprintf(full, sizeof full, "%zu orbits of periods %d..%d (%s)",
           sc_orbitn_set_count(j->set), j->sp.period_lo, j->sp.period_hi,
           title);
  sc_map_state_component(m, 0, xn, sizeof xn);
  sc_map_state_component(m, 1, yn, sizeof yn);
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "fixed-point", full, xn, yn, &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  if (j->sp.from)
    fprintf(f, "set xrange [%.17g:%.17g]\nset yrange [%.17g:%.17g]\n",
            j->sp.from[0], j->sp.to[0], j->sp.from[1], j->sp.to[1]);
  fprintf(f, "set cbrange [%g:%g]\nset cblabel 'minimal period'\n",
          j->sp.period_lo - 0.5, j->sp.period_hi + 0.5);
  if (j->sp.period_hi - j->sp.period_lo <= 24) fputs("set cbtics 1\n", f);
  fprintf(f, "set palette maxcolors %d\n",
          j->sp.period_hi - j->sp.period_lo + 1);
  fputs("set key outside right top box opaque\n", f);
  fputs("stab(c) = column(3) == 1 ? column(c) : NaN\n", f);
  fputs("unst(c) = column(3) == 0 ? column(c) : NaN\n", f);
  /* the few orbits of low period drawn larger, not hidden by the many of
   * high period drawn after them */
  fputs("size(p) = 1 + 1.5 / p\n", f);
  fputs("plot 'fixed-point-orbits.csv' skip 1 using 1:(stab(2)):(size($5)):5 "
        "with points pt 7 ps variable lc palette title 'stable (filled)', "
        "\\\n",
        f);
  fputs("     'fixed-point-orbits.csv' skip 1 using 1:(unst(2)):(size($5)):5 "
        "with points pt 6 ps variable lw 2 lc palette title 'unstable "
        "(open)'\n",
        f);
  return sc_cli_plot_end(r, "fixed-point", gp);
}

int sc_fpn_report(sc_cli_run *r, const sc_fpn_job *j) {
  size_t ngrid, nattr;
  sc_orbitn_set_starts(j->set, &ngrid, &nattr);
  sc_cli_note(r, "%zu orbits of periods %d..%d from %zu starts a period in "
                 "%.3f s",
              sc_orbitn_set_count(j->set), j->sp.period_lo, j->sp.period_hi,
              j->sp.start ? (size_t)1 : ngrid + nattr, j->elapsed);
  return SC_OK;
}

void sc_fpn_release(sc_fpn_job *j) {
  sc_orbitn_set_free(j->set);
  j->set = NULL;
}
