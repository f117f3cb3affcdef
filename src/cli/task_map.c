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
    {"from", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "first state of the grid (bk2: d = Y2 - Y1)"},
    {"to", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "last state of the grid"},
    {"steps", SC_KEY_INT, 0, "1001", 1, 100000000, 0, 0, NULL,
     "grid points, both ends included (1: from only)"},
};

/* Pieces of constant itinerary listed in the summary. */
#define MAP_MAX_PIECES 64

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

/* Short reasons are enough in the CSV: the first failure's full message
 * goes to the summary. */
static int map_run(sc_cli_run *r) {
  const sc_scene *s = r->scene;
  sc_map *m = r->map;
  int n = (int)sc_scene_int(s, "iterate");
  double from = sc_scene_real(s, "from"), to = sc_scene_real(s, "to");
  size_t steps = (size_t)sc_scene_int(s, "steps");
  sc_file *csv = NULL, *sum = NULL, *gp = NULL;
  int st = sc_cli_open(r, "map.csv", &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("d,f,df,itinerary,status\n", f);
  size_t nundef = 0, nok = 0;
  double flo = HUGE_VAL, fhi = -HUGE_VAL;
  char first_reason[SC_MSG_LEN] = "";
  char first_failure[SC_MSG_LEN] = "";
  size_t nfailed = 0;
  sc_map_value v;
  sc_msg em;
  map_pieces *pieces = calloc(1, sizeof *pieces);
  if (!pieces) {
    sc_file_abort(csv);
    return sc_fail(r->msg, SC_ENOMEM, "map: out of memory");
  }
  sc_progress bar;
  sc_progress_start(&bar, "points", (long)steps, 0,
                    sc_progress_wanted(r->quiet));
  for (size_t i = 0; i < steps; i++) {
    if (sc_cli_interrupted()) {
      sc_progress_finish(&bar);
      sc_file_abort(csv);
      free(pieces);
      return sc_fail(r->msg, SC_ECALLBACK, "interrupted");
    }
    double d = sc_grid_point(from, to, steps, i);
    st = sc_map_iterate(m, d, n, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v, &em);
    sc_csv_double(f, d);
    fputc(',', f);
    if (st == SC_OK) {
      sc_csv_double(f, v.f);
      fputc(',', f);
      sc_csv_double(f, v.dfdd);
      fprintf(f, ",%s,ok\n", sc_cli_csv_text(v.itinerary));
      add_point(pieces, d, v.f, v.itinerary);
      flo = flo < v.f ? flo : v.f;
      fhi = fhi > v.f ? fhi : v.f;
      nok++;
    } else if (st == SC_EUNDEF || st == SC_ENOCONV || st == SC_ENONFINITE) {
      if (!nundef)
        snprintf(first_reason, sizeof first_reason, "at %.17g: %.400s", d,
                 em.text);
      nundef++;
      fprintf(f, "nan,nan,,%s\n", sc_cli_csv_text(em.text));
      add_point(pieces, d, NAN, "undefined");
    } else if (st == SC_ENOMEM) {
      sc_progress_finish(&bar);
      sc_file_abort(csv);
      free(pieces);
      return sc_fail(r->msg, st, "map at %s = %.17g: %s",
                     sc_map_type(m)->state_name, d, em.text);
    } else {
      /* The model refused this point (an extreme d, parameters it cannot
       * handle): one point is lost, not the run; the row says why, the
       * summary and a note count them. */
      if (!nfailed)
        snprintf(first_failure, sizeof first_failure, "at %.17g: %s: %.400s",
                 d, sc_strerror(st), em.text);
      nfailed++;
      fprintf(f, "nan,nan,,%s\n", sc_cli_csv_text(em.text));
      add_point(pieces, d, NAN, "failed");
    }
    sc_progress_update(&bar, (long)i + 1);
  }
  sc_progress_finish(&bar);
  if ((st = sc_cli_commit(r, "map.csv", csv)) ||
      (st = sc_cli_summary_begin(r, &sum))) {
    free(pieces);
    return st;
  }
  f = sc_file_stream(sum);
  fprintf(f, "  f^%d evaluated at %zu points: %zu defined, %zu undefined\n", n,
          steps, nok, nundef);
  if (nok) fprintf(f, "  range of f^%d: [%.17g, %.17g]\n", n, flo, fhi);
  if (nundef) fprintf(f, "  first undefined point %s\n", first_reason);
  if (nfailed) {
    fprintf(f, "  %zu points refused by the model; first %s\n", nfailed,
            first_failure);
    sc_cli_note(r, "map: %zu of %zu points refused by the model; first %s",
                nfailed, steps, first_failure);
  }
  fputs("  pieces of constant itinerary (grid points; f^n on them):\n", f);
  for (size_t i = 0; i < pieces->n; i++) {
    const map_piece *p = &pieces->p[i];
    fprintf(f, "    %s from %.10g to %.10g (%zu points): %s", sc_map_type(m)->state_name,
            p->from, p->to, p->npts, p->itinerary);
    if (!isnan(p->flo)) fprintf(f, "; f^%d in [%.10g, %.10g]", n, p->flo, p->fhi);
    fputc('\n', f);
  }
  if (pieces->extra)
    fprintf(f, "    ... and %zu more pieces\n", pieces->extra);
  free(pieces);
  if (strcmp(sc_map_type(m)->name, "bk2") == 0) {
    double a = sc_map_get_param(m, (size_t)sc_map_param_index(m, "alpha"));
    double b = sc_map_get_param(m, (size_t)sc_map_param_index(m, "beta"));
    fprintf(f, "  d* = (beta - 1)/(1 + 2 alpha) = %.17g\n", sc_bk2_dstar(a, b));
  }
  if ((st = sc_cli_commit(r, "summary.txt", sum))) return st;

  if ((st = sc_cli_open(r, "map.gp", &gp))) return st;
  f = sc_file_stream(gp);
  char title[512], ylabel[64], xlabel[128];
  const char *state = sc_map_type(m)->state_name;
  snprintf(xlabel, sizeof xlabel, "%s", sc_plot_label(m, state));
  if (n == 1) snprintf(ylabel, sizeof ylabel, "f(%s)", state);
  else snprintf(ylabel, sizeof ylabel, "f^{%d}(%s)", n, state);
  sc_plot_title(m, NULL, title, sizeof title);
  sc_plot_head(f, "map.png", title, xlabel, ylabel);
  fputs("set key inside left top box opaque\n", f);
  if (from != to)
    fprintf(f, "set xrange [%.17g:%.17g]\n", fmin(from, to), fmax(from, to));
  if (strcmp(sc_map_type(m)->name, "bk2") == 0) {
    double a = sc_map_get_param(m, (size_t)sc_map_param_index(m, "alpha"));
    double b = sc_map_get_param(m, (size_t)sc_map_param_index(m, "beta"));
    fputs("# d*: both blocks reach their threshold together\n", f);
    fprintf(f, "dstar = %.17g\n", sc_bk2_dstar(a, b));
    fputs("set arrow 1 from dstar, graph 0 to dstar, graph 1 nohead "
          "dt 2 lc rgb '#888888'\n",
          f);
    fputs("set label 1 'd*' at dstar, graph 0.97 offset 0.5,0 tc rgb "
          "'#666666'\n",
          f);
  }
  fputs("# points, not lines, so that jumps of the map stay open\n", f);
  if (strcmp(sc_map_type(m)->name, "bk2") == 0) {
    fputs("# column 4 is the itinerary: without '12' only one block slips at "
          "a time\n# (single-block slips: f' = 1, docs/model.md)\n"
          "single(s) = strstrt(s, '12') == 0\n",
          f);
    fputs("plot 'map.csv' skip 1 using 1:(single(strcol(4)) ? $2 : NaN) "
          "with points pt 7 ps 0.35 lc rgb '#2ca02c' notitle, \\\n"
          "     '' skip 1 using 1:(single(strcol(4)) ? NaN : $2) with points "
          "pt 7 ps 0.35 lc rgb '#1f4e9e' notitle, \\\n"
          "     keyentry with points pt 7 ps 1.5 lc rgb '#2ca02c' "
          "title 'one block slips at a time', \\\n"
          "     keyentry with points pt 7 ps 1.5 lc rgb '#1f4e9e' "
          "title 'both blocks slip', \\\n"
          "     x with lines dt 2 lc rgb '#999999' title 'diagonal'\n",
          f);
  } else {
    fprintf(f,
            "plot 'map.csv' using 1:2 skip 1 with points pt 7 ps 0.35 "
            "lc rgb '#1f4e9e' title '%s', \\\n"
            "     x with lines dt 2 lc rgb '#999999' title 'diagonal'\n",
            n == 1 ? "f" : "f^n");
  }
  if ((st = sc_cli_commit(r, "map.gp", gp))) return st;
  if ((st = sc_cli_add_plot(r, "map.gp", "map.png"))) return st;
  if (nundef)
    sc_cli_note(r, "map undefined at %zu of %zu points (first %s)", nundef,
                steps, first_reason);
  return SC_OK;
}

const sc_cli_task sc_cli_task_map = {
    .type = {.kind = "map",
             .doc = "the event map f^n on a grid of states, with f', "
                    "itineraries and undefined points",
             .keys = map_keys,
             .nkeys = sizeof map_keys / sizeof map_keys[0],
             .check = NULL},
    .outputs = "map.csv (d,f,df,itinerary,status), summary.txt, map.gp, "
               "map.png",
    .run = map_run,
};
