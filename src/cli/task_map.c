/* Task `map`: f^n on a grid of states, with its derivative, itinerary
 * and, where it is undefined, the reason (fig 5.5). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/progress.h"
#include "cli/tasks.h"
#include "slipcont/analysis.h"

static const sc_key_info map_keys[] = {
    {"iterate", SC_KEY_INT, 0, "1", 1, 1000, 0, 0, NULL,
     "n: the map drawn is f^n, the n-th iterate"},
    {"from", SC_KEY_STATE, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "first state of the grid (bk2: d = Y2 - Y1; n > 1 components: the "
     "segment's first end, 0.1 -0.2)"},
    {"to", SC_KEY_STATE, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "last state of the grid (n > 1: the segment's other end)"},
    {"steps", SC_KEY_INT, 0, "1001", 1, 100000000, 0, 0, NULL,
     "grid points, both ends included (1: from only)"},
};

/* Pieces of constant itinerary listed in the summary. */
#define MAP_MAX_PIECES 64

/* Borders of one iterate held while the state borders are asked for
 * (bk2 reports some ten; more is refused by sc_map_state_borders), and
 * state borders drawn at most. */
#define MAP_MAX_BORDERS 64
#define MAP_MAX_STATE_BORDERS 4

typedef struct {
  double from, to;             /* first and last grid point of the piece */
  double flo, fhi;             /* range of f^n on it */
  size_t npts;
  char itinerary[SC_ITIN_LEN]; /* "undefined" where f^n is */
} map_piece;

typedef struct {
  map_piece p[MAP_MAX_PIECES];
  size_t n;      /* pieces stored */
  size_t extra;  /* pieces beyond MAP_MAX_PIECES */
} map_pieces;

static void add_point(map_pieces *ps, double d, double f, const char *itin) {
  map_piece *last = ps->n ? &ps->p[ps->n - 1] : NULL;
  if (last && !ps->extra && strcmp(last->itinerary, itin) == 0) {
    last->to = d;
    last->npts++;
    if (f < last->flo) last->flo = f;
    if (f > last->fhi) last->fhi = f;
    return;
  }
  if (ps->n == MAP_MAX_PIECES) {
    ps->extra++;
    return;
  }
  map_piece *p = &ps->p[ps->n++];
  p->from = p->to = d;
  p->flo = p->fhi = f;
  p->npts = 1;
  snprintf(p->itinerary, sizeof p->itinerary, "%s", itin);
}

/* One map run: the grid, and what the summary says about it. */
typedef struct {
  int n;                 /* the iterate drawn, f^n */
  size_t dim;            /* state components; > 1: a segment of states */
  double *xf, *xt;       /* dim > 1: the segment's ends */
  double *flo_n, *fhi_n; /* dim > 1: each component's range */
  double from, to;
  size_t steps;
  size_t nok, nundef, nfailed;
  double flo, fhi;       /* range of f^n where defined */
  char first_reason[SC_MSG_LEN];  /* first undefined point */
  char first_failure[SC_MSG_LEN]; /* first point the model refused */
  map_pieces *pieces;
  /* the model's borders in the state (sc_map_state_borders): drawn and
   * reported, whatever the model */
  size_t nsb;
  sc_border sb[MAP_MAX_STATE_BORDERS];
  sc_border scratch[MAP_MAX_BORDERS];
} map_job;

/* The model's borders in the state at the scene's parameters, as an
 * iterate from the grid's first, last or middle point reports them (one
 * where the map is defined suffices); equal points are one. */
static void state_borders(map_job *j, sc_map *m) {
  sc_border_list l = {.b = j->scratch, .cap = MAP_MAX_BORDERS};
  const double at[3] = {j->from, j->to, 0.5 * (j->from + j->to)};
  j->nsb = 0;
  for (int k = 0; k < 3; k++) {
    if (sc_map_state_borders(m, at[k], &l, NULL) != SC_OK) continue;
    for (size_t i = 0; i < l.n && j->nsb < MAP_MAX_STATE_BORDERS; i++) {
      int seen = 0;
      for (size_t q = 0; q < j->nsb; q++) seen |= j->sb[q].d_on == l.b[i].d_on;
      if (!seen) j->sb[j->nsb++] = l.b[i];
    }
    return;
  }
}

/* The name a state border's point has in plots and the summary: the
 * model's (bk2: "d*"), or the border kind's label. */
static const char *state_point_name(const sc_map *m, const sc_border *b) {
  const char *s = sc_map_type(m)->state_point_name;
  return s ? s : sc_border_label(b->kind);
}

static int map_prepare(sc_cli_run *r, void *job) {
  map_job *j = job;
  const sc_scene *s = r->scene;
  sc_map *m = r->map;
  j->n = (int)sc_scene_int(s, "iterate");
  j->dim = sc_map_dim(m);
  if (j->dim > 1) {
    j->xf = malloc(4 * j->dim * sizeof *j->xf);
    if (!j->xf) return sc_fail(r->msg, SC_ENOMEM, "map: out of memory");
    j->xt = j->xf + j->dim;
    j->flo_n = j->xt + j->dim;
    j->fhi_n = j->flo_n + j->dim;
    sc_scene_state(s, "from", j->xf, j->dim);
    sc_scene_state(s, "to", j->xt, j->dim);
    for (size_t i = 0; i < j->dim; i++)
      j->flo_n[i] = HUGE_VAL, j->fhi_n[i] = -HUGE_VAL;
    j->steps = (size_t)sc_scene_int(s, "steps");
    return SC_OK;
  }
  j->from = sc_scene_real(s, "from");
  j->to = sc_scene_real(s, "to");
  j->steps = (size_t)sc_scene_int(s, "steps");
  j->flo = HUGE_VAL;
  j->fhi = -HUGE_VAL;
  state_borders(j, m);
  j->pieces = calloc(1, sizeof *j->pieces);
  return j->pieces ? SC_OK : sc_fail(r->msg, SC_ENOMEM, "map: out of memory");
}

/* One grid point into map.csv.  Short reasons are enough in the CSV: the
 * first failure's full message goes to the summary. */
static int map_point(sc_cli_run *r, map_job *j, FILE *f, double d) {
  sc_map_value v;
  sc_msg em;
  int st = sc_map_iterate(r->map, d, j->n, SC_EVAL_DERIV | SC_EVAL_ITINERARY,
                          &v, &em);
  sc_csv_double(f, d);
  fputc(',', f);
  if (st == SC_OK) {
    sc_csv_double(f, v.f);
    fputc(',', f);
    sc_csv_double(f, v.dfdd);
    fprintf(f, ",%s,ok\n", sc_cli_csv_text(v.itinerary));
    add_point(j->pieces, d, v.f, v.itinerary);
    j->flo = j->flo < v.f ? j->flo : v.f;
    j->fhi = j->fhi > v.f ? j->fhi : v.f;
    j->nok++;
  } else if (st == SC_EUNDEF || st == SC_ENOCONV || st == SC_ENONFINITE) {
    if (!j->nundef)
      snprintf(j->first_reason, sizeof j->first_reason, "at %.17g: %.400s", d,
               em.text);
    j->nundef++;
    fprintf(f, "nan,nan,,%s\n", sc_cli_csv_text(em.text));
    add_point(j->pieces, d, NAN, "undefined");
  } else if (st == SC_ENOMEM) {
    return sc_fail(r->msg, st, "map at %s = %.17g: %s",
                   sc_map_type(r->map)->state_name, d, em.text);
  } else {
    /* The model refused this point (an extreme d, parameters it cannot
     * handle): one point is lost, not the run; the row says why, the
     * summary and a note count them. */
    if (!j->nfailed)
      snprintf(j->first_failure, sizeof j->first_failure,
               "at %.17g: %s: %.400s", d, sc_strerror(st), em.text);
    j->nfailed++;
    fprintf(f, "nan,nan,,%s\n", sc_cli_csv_text(em.text));
    add_point(j->pieces, d, NAN, "failed");
  }
  return SC_OK;
}

/* A map of n > 1 components: f^n at the states x(t) = from + t (to -
 * from), t on steps points of [0, 1], into map.csv (t, the state, f^n's
 * components, itinerary, status). */
static int map_compute_n(sc_cli_run *r, map_job *j) {
  const size_t n = j->dim;
  sc_mapn_value *v = NULL;
  double x[SC_MAXDIM];
  int st = sc_mapn_value_alloc(r->map, SC_EVAL_VALUE, &v, r->msg);
  sc_file *csv = NULL;
  if (!st) st = sc_cli_open(r, "map.csv", &csv);
  if (st) {
    sc_mapn_value_free(v);
    return st;
  }
  FILE *f = sc_file_stream(csv);
  fputs("t,", f);
  sc_csv_state_header(f, r->map, "");
  fputc(',', f);
  sc_csv_state_header(f, r->map, "f_");
  fputs(",itinerary,status\n", f);
  for (size_t i = 0; i < j->steps && !st; i++) {
    if ((st = sc_cli_stop(r))) break;
    double t = j->steps > 1 ? sc_grid_point(0, 1, j->steps, i) : 0;
    for (size_t c = 0; c < n; c++) x[c] = j->xf[c] + t * (j->xt[c] - j->xf[c]);
    sc_msg em;
    int e = sc_map_iterate_n(r->map, x, j->n, SC_EVAL_ITINERARY, v, &em);
    sc_csv_double(f, t);
    fputc(',', f);
    sc_csv_state(f, x, n);
    if (e == SC_ENOMEM) {
      st = sc_fail(r->msg, e, "map at t = %.17g: %s", t, em.text);
      break;
    }
    if (e) {
      if (!j->nundef)
        snprintf(j->first_reason, sizeof j->first_reason, "at t = %.17g: %.400s",
                 t, em.text);
      j->nundef++;
      for (size_t c = 0; c < n; c++) fputs(",nan", f);
      fprintf(f, ",,%s\n", sc_cli_csv_text(em.text));
      continue;
    }
    fputc(',', f);
    sc_csv_state(f, v->f, n);
    fprintf(f, ",%s,ok\n", sc_cli_csv_text(v->itinerary));
    for (size_t c = 0; c < n; c++) {
      j->flo_n[c] = fmin(j->flo_n[c], v->f[c]);
      j->fhi_n[c] = fmax(j->fhi_n[c], v->f[c]);
    }
    j->nok++;
  }
  sc_mapn_value_free(v);
  return st ? st : sc_cli_commit(r, "map.csv", csv);
}

static int map_compute(sc_cli_run *r, void *job) {
  map_job *j = job;
  if (j->dim > 1) return map_compute_n(r, j);
  sc_file *csv = NULL;
  int st = sc_cli_open(r, "map.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("d,f,df,itinerary,status\n", f);
  sc_progress bar;
  sc_progress_start(&bar, "points", (long)j->steps, 0,
                    sc_progress_wanted(r->quiet));
  for (size_t i = 0; i < j->steps && !st; i++) {
    if ((st = sc_cli_stop(r))) break;
    st = map_point(r, j, f, sc_grid_point(j->from, j->to, j->steps, i));
    sc_progress_update(&bar, (long)i + 1);
  }
  sc_progress_finish(&bar);
  return st ? st : sc_cli_commit(r, "map.csv", csv);
}

/* The summary of a segment of states. */
static void map_summary_n(sc_cli_run *r, const map_job *j, FILE *f) {
  char c[32];
  fprintf(f, "  f^%d evaluated at %zu states from (", j->n, j->steps);
  sc_csv_points(f, j->xf, 1, j->dim);
  fputs(") to (", f);
  sc_csv_points(f, j->xt, 1, j->dim);
  fprintf(f, "): %zu defined, %zu undefined\n", j->nok, j->nundef);
  for (size_t i = 0; j->nok && i < j->dim; i++)
    fprintf(f, "  range of component %s of f^%d: [%.17g, %.17g]\n",
            sc_map_state_component(r->map, i, c, sizeof c), j->n,
            j->flo_n[i], j->fhi_n[i]);
  if (j->nundef) fprintf(f, "  first undefined point %s\n", j->first_reason);
}

static int map_summary(sc_cli_run *r, void *job, FILE *f) {
  const map_job *j = job;
  int n = j->n;
  if (j->dim > 1) {
    map_summary_n(r, j, f);
    return SC_OK;
  }
  fprintf(f, "  f^%d evaluated at %zu points: %zu defined, %zu undefined\n", n,
          j->steps, j->nok, j->nundef);
  if (j->nok) fprintf(f, "  range of f^%d: [%.17g, %.17g]\n", n, j->flo, j->fhi);
  if (j->nundef) fprintf(f, "  first undefined point %s\n", j->first_reason);
  if (j->nfailed)
    fprintf(f, "  %zu points refused by the model; first %s\n", j->nfailed,
            j->first_failure);
  fputs("  pieces of constant itinerary (grid points; f^n on them):\n", f);
  for (size_t i = 0; i < j->pieces->n; i++) {
    const map_piece *p = &j->pieces->p[i];
    fprintf(f, "    %s from %.10g to %.10g (%zu points): %s",
            sc_map_type(r->map)->state_name, p->from, p->to, p->npts,
            p->itinerary);
    if (!isnan(p->flo)) fprintf(f, "; f^%d in [%.10g, %.10g]", n, p->flo, p->fhi);
    fputc('\n', f);
  }
  if (j->pieces->extra)
    fprintf(f, "    ... and %zu more pieces\n", j->pieces->extra);
  for (size_t i = 0; i < j->nsb; i++)
    fprintf(f, "  %s = %.17g: a border in the state (%s: %s)\n",
            state_point_name(r->map, &j->sb[i]), j->sb[i].d_on,
            sc_border_label(j->sb[i].kind), j->sb[i].name);
  return SC_OK;
}

/* The components of f^n along the segment, against t. */
static int map_plots_n(sc_cli_run *r, const map_job *j) {
  static const char *const rgb[] = {"#1f4e9e", "#d62728", "#2ca02c",
                                    "#9467bd", "#ff7f0e", "#17becf"};
  sc_map *m = r->map;
  char title[512], c[32], key[64];
  sc_plot_title(m, NULL, title, sizeof title);
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "map", title,
                             "t (the state from + t (to - from))",
                             j->n == 1 ? "f" : "f^n", &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  fputs("set xrange [0:1]\nplot ", f);
  for (size_t i = 0; i < j->dim; i++) {
    /* columns: t, the n components of the state, those of f^n */
    fprintf(f, "%s'map.csv' skip 1 using 1:%zu with points pt 7 ps 0.35 "
               "lc rgb '%s' title ",
            i ? ", \\\n     " : "", 2 + j->dim + i, rgb[i % 6]);
    snprintf(key, sizeof key, "component %s",
             sc_map_state_component(m, i, c, sizeof c));
    sc_plot_quote(f, key);
  }
  fputc('\n', f);
  return sc_cli_plot_end(r, "map", gp);
}

static int map_plots(sc_cli_run *r, void *job) {
  const map_job *j = job;
  sc_map *m = r->map;
  char title[512], ylabel[64];
  if (j->dim > 1) return map_plots_n(r, j);
  const char *state = sc_map_type(m)->state_name;
  if (j->n == 1) snprintf(ylabel, sizeof ylabel, "f(%s)", state);
  else snprintf(ylabel, sizeof ylabel, "f^{%d}(%s)", j->n, state);
  sc_plot_title(m, NULL, title, sizeof title);
  sc_file *gp = NULL;
  int st = sc_cli_plot_begin(r, "map", title, sc_plot_label(m, state), ylabel,
                             &gp);
  if (st) return st;
  FILE *f = sc_file_stream(gp);
  double xlo = fmin(j->from, j->to), xhi = fmax(j->from, j->to);
  if (j->from != j->to) {
    fprintf(f, "set xrange [%.17g:%.17g]\n", xlo, xhi);
    sc_plot_axis_format(f, "x", xlo, xhi);
  }
  /* the y axis shows f^n and the diagonal over the grid */
  if (j->flo <= j->fhi)
    sc_plot_axis_format(f, "y", fmin(j->flo, xlo), fmax(j->fhi, xhi));
  for (size_t i = 0; i < j->nsb; i++) {
    const sc_border *b = &j->sb[i];
    fprintf(f, "# %s: a border in the state (%s: %s)\n",
            state_point_name(m, b), sc_border_label(b->kind), b->name);
    fprintf(f, "sb%zu = %.17g\n", i + 1, b->d_on);
    fprintf(f, "set arrow %zu from sb%zu, graph 0 to sb%zu, graph 1 nohead "
               "dt 2 lc rgb '#888888'\n",
            i + 1, i + 1, i + 1);
    fprintf(f, "set label %zu '%s' at sb%zu, graph 0.97 offset 0.5,0 tc rgb "
               "'#666666'\n",
            i + 1, state_point_name(m, b), i + 1);
  }
  fputs("# points, not lines, so that jumps of the map stay open\n", f);
  /* the key lists the kinds of motion present */
  int single = 0, both = 0;
  for (size_t i = 0; i < j->pieces->n; i++) {
    const char *it = j->pieces->p[i].itinerary;
    if (strcmp(it, "undefined") == 0) continue;
    if (strstr(it, "12")) both = 1;
    else single = 1;
  }
  if (j->pieces->extra) single = both = 1; /* not all pieces kept */
  if (sc_map_has_borders(m)) {
    /* a piecewise-smooth model: its itineraries name the parts that slip
     * (bk2, the only one: '12' both blocks) */
    fputs("# column 4 is the itinerary: without '12' only one block slips at "
          "a time\n# (single-block slips: f' = 1, docs/model.md)\n"
          "single(s) = strstrt(s, '12') == 0\n",
          f);
    fputs("plot 'map.csv' skip 1 using 1:(single(strcol(4)) ? $2 : NaN) "
          "with points pt 7 ps 0.35 lc rgb '#2ca02c' notitle, \\\n"
          "     '' skip 1 using 1:(single(strcol(4)) ? NaN : $2) with points "
          "pt 7 ps 0.35 lc rgb '#1f4e9e' notitle, \\\n",
          f);
    if (single)
      fputs("     keyentry with points pt 7 ps 1.5 lc rgb '#2ca02c' "
            "title 'one block slips at a time', \\\n",
            f);
    if (both)
      fputs("     keyentry with points pt 7 ps 1.5 lc rgb '#1f4e9e' "
            "title 'both blocks slip', \\\n",
            f);
    fputs("     x with lines dt 2 lc rgb '#999999' title 'diagonal'\n", f);
  } else {
    fprintf(f,
            "plot 'map.csv' using 1:2 skip 1 with points pt 7 ps 0.35 "
            "lc rgb '#1f4e9e' title '%s', \\\n"
            "     x with lines dt 2 lc rgb '#999999' title 'diagonal'\n",
            j->n == 1 ? "f" : "f^n");
  }
  return sc_cli_plot_end(r, "map", gp);
}

static int map_report(sc_cli_run *r, void *job) {
  const map_job *j = job;
  if (j->nfailed)
    sc_cli_note(r, "map: %zu of %zu points refused by the model; first %s",
                j->nfailed, j->steps, j->first_failure);
  if (j->nundef)
    sc_cli_note(r, "map undefined at %zu of %zu points (first %s)", j->nundef,
                j->steps, j->first_reason);
  return SC_OK;
}

static void map_release(sc_cli_run *r, void *job) {
  map_job *j = job;
  (void)r;
  free(j->pieces);
  free(j->xf);
}

const sc_cli_task sc_cli_task_map = {
    .type = {.kind = "map",
             .doc = "the event map f^n on a grid of states, with f', "
                    "itineraries and undefined points",
             .keys = map_keys,
             .nkeys = sizeof map_keys / sizeof map_keys[0],
             .check = NULL},
    .outputs = "map.csv (d,f,df,itinerary,status; n > 1: t,d1..dn,"
               "f_d1..f_dn,itinerary,status along the segment from-to), "
               "summary.txt, map.gp, map.png",
    .job_size = sizeof(map_job),
    .prepare = map_prepare,
    .compute = map_compute,
    .summary = map_summary,
    .plots = map_plots,
    .report = map_report,
    .release = map_release,
};
