/* The curve task for n-dimensional models: fold, flip and Neimark-Sacker
 * curves of a period-m fixed point in two parameters with every
 * codimension-two point (sc_curven_trace, curve.h; docs/maps.md, "Curves
 * and codimension two").  task_curve.c keeps the keys, the box, the
 * figure and the one-dimensional path; this file reads an n-dimensional
 * start and writes the n-dimensional rows. */
#define _POSIX_C_SOURCE 200809L /* getline, open_memstream */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/curve_impl.h"

struct sc_cli_curve_n {
  size_t n;
  double x0[SC_DIM_TENSOR]; /* the start's state */
  double kappa0;            /* NS: the row's kappa, or NaN */
  sc_curven_special *sp;    /* the special rows, in order */
  size_t nsp, cap;
  long nns, nsaddle;        /* NS curve: points with |kappa| < 1, > 1 */
};

/* A row of an n-dimensional branch's points.csv. */
typedef struct {
  char label[16], param[64];
  double value, kappa;
  double x[SC_DIM_TENSOR];
  int period;
} nrow;

/* Most columns of a points.csv row read here. */
#define NCOLS 64

/* The columns label, parameter, value, the state (named as
 * sc_csv_state_header() names them) and period of a header line; kappa
 * optional.  col: 4 + n entries. */
static int find_cols(const sc_map *m, char *head, int *col, int *colk,
                     char *why, size_t len, const char *path) {
  size_t n = sc_map_dim(m);
  char *h[NCOLS], *names = NULL, *sn[SC_DIM_TENSOR];
  size_t nlen = 0;
  FILE *ms = open_memstream(&names, &nlen);
  if (!ms) return SC_ENOMEM;
  sc_csv_state_header(ms, m, "");
  fclose(ms);
  sc_cli_csv_split(names, sn, (int)n);
  static const char *const fixed[4] = {"label", "parameter", "value",
                                       "period"};
  int nh = sc_cli_csv_split(head, h, NCOLS), st = SC_OK;
  for (size_t k = 0; k < 4 + n; k++) col[k] = -1;
  *colk = -1;
  for (int i = 0; i < nh; i++) {
    for (size_t k = 0; k < 4 + n; k++)
      if (strcmp(h[i], k < 4 ? fixed[k] : sn[k - 4]) == 0) col[k] = i;
    if (strcmp(h[i], "kappa") == 0) *colk = i;
  }
  for (size_t k = 0; k < 4 + n && !st; k++)
    if (col[k] < 0) {
      snprintf(why, len,
               "%.300s has no column '%s' (a branch task's points.csv of "
               "model %s has label, parameter, value, its state and period)",
               path, k < 4 ? fixed[k] : sn[k - 4], sc_map_type(m)->name);
      st = SC_EINVAL;
    }
  free(names);
  return st;
}

/* Row N of the points.csv named by spec ("FILE:N"). */
static int read_row(const sc_map *m, const char *spec, nrow *row, char *why,
                    size_t len) {
  char path[4096];
  snprintf(path, sizeof path, "%s", spec);
  char *colon = strrchr(path, ':');
  long N = 0, per = 0;
  if (!colon || colon == path || sc_parse_long(colon + 1, 1, 100000000, &N)) {
    snprintf(why, len, "'%.300s' is not FILE:N with a row number N in [1, "
                       "100000000]", spec);
    return SC_EINVAL;
  }
  *colon = '\0';
  FILE *f;
  sc_msg msg;
  int st = sc_input_open(path, "a points file", SC_INPUT_MAXBYTES, &f, &msg);
  if (st) {
    snprintf(why, len, "%s", msg.text);
    return st;
  }
  size_t n = sc_map_dim(m), cap = 0;
  char *line = NULL, *v[NCOLS];
  int col[4 + SC_DIM_TENSOR], colk;
  st = getline(&line, &cap, f) > 0
           ? find_cols(m, line, col, &colk, why, len, path)
           : (snprintf(why, len, "%.300s is empty", path), SC_EINVAL);
  long rows = 0;
  while (!st && rows < N && getline(&line, &cap, f) > 0) rows++;
  if (!st && rows < N) {
    snprintf(why, len, "%.300s has no row %ld (%ld rows after the header)",
             path, N, rows);
    st = SC_EINVAL;
  }
  int nv = st ? 0 : sc_cli_csv_split(line, v, NCOLS);
  for (size_t k = 0; !st && k < 4 + n; k++)
    if (col[k] >= nv ||
        (k == 2 && (sc_parse_double(v[col[k]], &row->value) ||
                    !isfinite(row->value))) ||
        (k == 3 && sc_parse_long(v[col[k]], 1, 4096, &per)) ||
        (k >= 4 && (sc_parse_double(v[col[k]], &row->x[k - 4]) ||
                    !isfinite(row->x[k - 4])))) {
      snprintf(why, len, "row %ld of %.300s: column %zu unreadable (valid: "
                         "finite numbers, a period in [1, 4096])",
               N, path, k + 1);
      st = SC_EINVAL;
    }
  if (!st) {
    row->period = (int)per;
    snprintf(row->label, sizeof row->label, "%.15s", v[col[0]]);
    snprintf(row->param, sizeof row->param, "%.63s", v[col[1]]);
    row->kappa = NAN;
    if (colk >= 0 && colk < nv && sc_parse_double(v[colk], &row->kappa))
      row->kappa = NAN;
  }
  free(line);
  fclose(f);
  return st;
}

int sc_cli_curve_n_check(const sc_scene *s, const char *type,
                         const char *want_label, double *xstart,
                         sc_msg *msg) {
  const sc_map *m = sc_scene_map(s);
  if (strcmp(type, "fold") && strcmp(type, "flip") && strcmp(type, "ns"))
    return sc_scene_fail_key(s, "task", "type", msg,
                             "type = %s: model %s is %zu-dimensional and "
                             "declares no borders (valid: fold, flip or ns)",
                             type, sc_map_type(m)->name, sc_map_dim(m));
  if (sc_map_dim(m) > SC_DIM_TENSOR)
    return sc_scene_fail_key(s, "task", "type", msg,
                             "model %s has %zu state components: curves need "
                             "second and third derivatives, kept up to %d "
                             "(valid: a model of at most %d components)",
                             sc_map_type(m)->name, sc_map_dim(m),
                             SC_DIM_TENSOR, SC_DIM_TENSOR);
  if (strcmp(sc_scene_text(s, "shooting"), "single"))
    return sc_scene_fail_key(s, "task", "shooting", msg,
                             "shooting = %s: the curves of an n-dimensional "
                             "model are traced on f^m (valid: single)",
                             sc_scene_text(s, "shooting"));
  if (sc_scene_text(s, "marks"))
    return sc_scene_fail_key(s, "task", "marks", msg,
                             "marks: user points are not located on the "
                             "curves of an n-dimensional model (valid: leave "
                             "marks out)");
  const char *spec = sc_scene_text(s, "start");
  if (!spec) return SC_OK;
  nrow row;
  char why[600];
  if (read_row(m, spec, &row, why, sizeof why))
    return sc_scene_fail_key(s, "task", "start", msg, "start: %s", why);
  const char *xn = sc_scene_text(s, "x");
  if (strcmp(row.param, xn) || strcmp(row.label, want_label))
    return sc_scene_fail_key(s, "task", "start", msg,
                             "start = %s is a %s in %s (valid: a %s in x = %s "
                             "for type = %s)",
                             spec, row.label, row.param, want_label, xn, type);
  *xstart = row.value;
  return SC_OK;
}

int sc_cli_curve_n_prepare(sc_cli_run *r, sc_curve_settings *set,
                           sc_cli_curve_n **out) {
  sc_cli_curve_n *c = calloc(1, sizeof *c);
  if (!c) return sc_fail(r->msg, SC_ENOMEM, "curve: out of memory");
  *out = c;
  c->n = sc_map_dim(r->map);
  c->kappa0 = NAN;
  const char *spec = sc_scene_text(r->scene, "start");
  if (!spec) {
    sc_scene_state(r->scene, "d0", c->x0, c->n);
    return SC_OK;
  }
  nrow row; /* checked by sc_cli_curve_n_check() */
  char why[600];
  if (read_row(r->map, spec, &row, why, sizeof why))
    return sc_fail(r->msg, SC_EIO, "curve: start = %s: %s", spec, why);
  memcpy(c->x0, row.x, c->n * sizeof *c->x0);
  c->kappa0 = row.kappa;
  set->period = row.period;
  return sc_map_set_param(r->map, (size_t)set->ix, row.value, r->msg);
}

long sc_cli_curve_n_saddles(const sc_cli_curve_n *c) {
  return c ? c->nsaddle : 0;
}

void sc_cli_curve_n_free(sc_cli_curve_n *c) {
  if (!c) return;
  free(c->sp);
  free(c);
}

typedef struct {
  out_ctx *c;
  sc_cli_curve_n *nd;
} nctx;

static int on_point(void *vc, const sc_curven_point *p) {
  nctx *x = vc;
  out_ctx *c = x->c;
  if (!c->have_start)
    c->have_start = 1, c->start_x = p->x, c->start_y = p->y;
  if (p->branch != c->last_branch) fputc('\n', c->curve);
  c->last_branch = p->branch;
  if (!isnan(p->kappa) && p->kappa != 1 && p->kappa != -1) {
    if (fabs(p->kappa) < 1) x->nd->nns++;
    else x->nd->nsaddle++;
  }
  sc_csv_double(c->curve, p->x);
  fputc(',', c->curve);
  sc_csv_double(c->curve, p->y);
  fputc(',', c->curve);
  sc_csv_state(c->curve, p->state, p->n);
  fprintf(c->curve, ",%d,", c->period);
  sc_csv_double(c->curve, p->kappa);
  fputc(',', c->curve);
  sc_csv_double(c->curve, p->coefficient);
  fputc(',', c->curve);
  sc_csv_multipliers(c->curve, p->mre, p->mim, p->n);
  fputc('\n', c->curve);
  return sc_cli_interrupted();
}

static int on_special(void *vc, const sc_curven_special *s) {
  nctx *x = vc;
  out_ctx *c = x->c;
  sc_cli_curve_n *nd = x->nd;
  fprintf(c->points, "%s,", s->label);
  sc_csv_double(c->points, s->x);
  fputc(',', c->points);
  sc_csv_double(c->points, s->y);
  fputc(',', c->points);
  sc_csv_state(c->points, s->state, s->n);
  char note[sizeof s->note];
  snprintf(note, sizeof note, "%s", s->note);
  fprintf(c->points, ",%d,%s,", c->period, sc_cli_csv_text(note));
  sc_csv_double(c->points, s->coefficient);
  fputc(',', c->points);
  sc_csv_double(c->points, s->residual);
  fputc(',', c->points);
  sc_csv_double(c->points, s->kappa);
  fputc('\n', c->points);
  if (nd->nsp == nd->cap) {
    size_t cap = nd->cap ? 2 * nd->cap : 16;
    sc_curven_special *p = realloc(nd->sp, cap * sizeof *p);
    if (!p) return c->oom = 1;
    nd->sp = p, nd->cap = cap;
  }
  nd->sp[nd->nsp++] = *s;
  /* the figure's rows: label and parameters */
  sc_curve_special t;
  memset(&t, 0, sizeof t);
  snprintf(t.label, sizeof t.label, "%s", s->label);
  t.x = s->x, t.y = s->y, t.d = s->state[0];
  t.coefficient = s->coefficient, t.residual = s->residual;
  snprintf(t.note, sizeof t.note, "%s", s->note);
  return sc_cli_curve_keep(c, &t);
}

int sc_cli_curve_n_compute(sc_cli_run *r, sc_cli_curve_n *nd,
                           const sc_curve_settings *set, out_ctx *c,
                           sc_curve_stats *stats) {
  sc_map *m = r->map;
  sc_file *cf = NULL, *pf = NULL;
  int st = sc_cli_open(r, "curve.csv", &cf);
  if (!st) st = sc_cli_open(r, "points.csv", &pf);
  if (st) return st;
  c->curve = sc_file_stream(cf);
  c->points = sc_file_stream(pf);
  const char *xn = sc_map_type(m)->params[set->ix].name;
  const char *yn = sc_map_type(m)->params[set->iy].name;
  fprintf(c->curve, "%s,%s,", xn, yn);
  sc_csv_state_header(c->curve, m, "");
  fputs(",period,kappa,coefficient,multipliers\n", c->curve);
  fprintf(c->points, "label,%s,%s,", xn, yn);
  sc_csv_state_header(c->points, m, "");
  fputs(",period,note,coefficient,residual,kappa\n", c->points);
  nctx x = {c, nd};
  sc_curven_output out = {on_point, on_special, &x};
  st = sc_curven_trace(m, set, nd->x0, nd->kappa0, &out, stats, r->msg);
  if (st == SC_ECALLBACK && (c->oom || sc_cli_interrupted()))
    sc_fail(r->msg, st, "curve: %s", c->oom ? "out of memory" : "interrupted");
  if (!st) st = sc_cli_commit(r, "curve.csv", cf);
  return st ? st : sc_cli_commit(r, "points.csv", pf);
}

void sc_cli_curve_n_summary(FILE *f, const sc_cli_run *r,
                            const sc_cli_curve_n *nd) {
  const sc_map *m = r->map;
  if (nd->nns || nd->nsaddle)
    fprintf(f,
            "  Neimark-Sacker points (|kappa| < 1): %ld; neutral saddles "
            "(a real pair mu, 1/mu, |kappa| > 1): %ld\n",
            nd->nns, nd->nsaddle);
  for (size_t i = 0; i < nd->nsp; i++) {
    const sc_curven_special *p = &nd->sp[i];
    const char *xn = sc_scene_text(r->scene, "x");
    const char *yn = sc_scene_text(r->scene, "y");
    fprintf(f, "    %-5s %s = %.17g, %s = %.17g, state", p->label, xn, p->x,
            yn, p->y);
    for (size_t k = 0; k < p->n; k++) fprintf(f, " %.17g", p->state[k]);
    fprintf(f, ", kappa %.12g, coefficient %.6g, residual %.3g: %s\n",
            p->kappa, p->coefficient, p->residual, p->note);
  }
  (void)m;
}
