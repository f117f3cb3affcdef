/* Task `chart`: the period of the attractor on a grid over two model
 * parameters (fig 5.7), computed in blocks of rows with OpenMP (and MPI
 * ranks when built with SLIPCONT_MPI), checkpointed after blocks so that
 * an interrupted run resumes where it stopped.  docs/charts.md. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <omp.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/progress.h"
#include "cli/tasks.h"
#include "slipcont/chart.h"
#ifdef SLIPCONT_MPI
#include "cli/mpi_chart.h"
#endif

static const sc_key_info chart_keys[] = {
    {"x", SC_KEY_PARAM, 1, NULL, 0, 0, 0, 0, NULL,
     "parameter on the horizontal axis"},
    {"x-from", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "first x value (inside the parameter's valid range)"},
    {"x-to", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "last x value, exactly a grid point"},
    {"x-steps", SC_KEY_INT, 0, "200", 2, SC_CHART_MAX_POINTS, 0, 0, NULL,
     "grid points along x, both ends included"},
    {"y", SC_KEY_PARAM, 1, NULL, 0, 0, 0, 0, NULL,
     "parameter on the vertical axis (not x)"},
    {"y-from", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "first y value (inside the parameter's valid range)"},
    {"y-to", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "last y value, exactly a grid point"},
    {"y-steps", SC_KEY_INT, 0, "200", 2, SC_CHART_MAX_POINTS, 0, 0, NULL,
     "grid points along y (rows), both ends included"},
    {"x-scale", SC_KEY_CHOICE, 0, "linear", 0, 0, 0, 0, "linear|log",
     "x grid spacing: equal differences, or equal ratios (log; ends of one "
     "sign)"},
    {"y-scale", SC_KEY_CHOICE, 0, "linear", 0, 0, 0, 0, "linear|log",
     "y grid spacing: equal differences, or equal ratios (log; ends of one "
     "sign)"},
    {"d0", SC_KEY_STATE, 0, "0", -HUGE_VAL, HUGE_VAL, 1, 1, NULL,
     "initial state of every point (bk2: d = Y2 - Y1 of the first GSP)"},
    {"transient", SC_KEY_INT, 0, "1000", 1, INT32_MAX, 0, 0, NULL,
     "most map iterates per point; a point stops as soon as its period is "
     "confirmed"},
    {"max-period", SC_KEY_INT, 0, "16", 1, SC_PERIOD_MAX, 0, 0, NULL,
     "longest period told apart; longer ones, chaos and quasi-periodicity "
     "are 'high'"},
    {"confirm", SC_KEY_INT, 0, "4", 1, SC_PERIOD_MAX_CONFIRM, 0, 0, NULL,
     "full cycles a period must repeat before it is accepted"},
    {"seed", SC_KEY_CHOICE, 0, "fixed", 0, 0, 0, 0, "fixed|previous",
     "start every point from d0, or from the final state of the previous "
     "point of its row (rows are then sequential)"},
};

/* The chart of a scene (its names point into the scene; a state of n > 1
 * components into @p x0, SC_MAXDIM values). */
static sc_chart_spec spec_of(const sc_scene *s, double *x0) {
  sc_chart_spec c;
  sc_chart_spec_default(&c);
  c.x = sc_scene_text(s, "x");
  c.x_from = sc_scene_real(s, "x-from");
  c.x_to = sc_scene_real(s, "x-to");
  c.x_steps = sc_scene_int(s, "x-steps");
  c.y = sc_scene_text(s, "y");
  c.y_from = sc_scene_real(s, "y-from");
  c.y_to = sc_scene_real(s, "y-to");
  c.y_steps = sc_scene_int(s, "y-steps");
  const char *xs = sc_scene_text(s, "x-scale"), *ys = sc_scene_text(s, "y-scale");
  c.x_scale = xs && strcmp(xs, "log") == 0 ? SC_GRID_LOG : SC_GRID_LINEAR;
  c.y_scale = ys && strcmp(ys, "log") == 0 ? SC_GRID_LOG : SC_GRID_LINEAR;
  if (sc_map_dim(sc_scene_map(s)) > 1) {
    /* the default "0" is one number: every component */
    size_t n = sc_map_dim(sc_scene_map(s));
    if (sc_scene_state(s, "d0", x0, SC_MAXDIM) < n)
      for (size_t k = 1; k < n; k++) x0[k] = x0[0];
    c.x0 = x0;
    c.d0 = x0[0];
  } else {
    c.d0 = sc_scene_real(s, "d0");
  }
  c.transient = sc_scene_int(s, "transient");
  c.max_period = (int)sc_scene_int(s, "max-period");
  c.confirm = (int)sc_scene_int(s, "confirm");
  const char *seed = sc_scene_text(s, "seed");
  c.seed = seed && strcmp(seed, "previous") == 0 ? SC_CHART_SEED_NEIGHBOUR
                                                   : SC_CHART_SEED_FIXED;
  return c;
}

/* Relations between keys: sc_chart_check() says which key is wrong in
 * the first word after "chart: "; name that key's line. */
static int chart_check(const sc_scene *s, sc_msg *msg) {
  double x0[SC_MAXDIM];
  sc_chart_spec c = spec_of(s, x0);
  sc_msg m;
  if (sc_chart_check(sc_scene_map(s), &c, &m) == SC_OK) return SC_OK;
  const char *text = strncmp(m.text, "chart: ", 7) == 0 ? m.text + 7 : m.text;
  const char *key = "x-steps";
  for (size_t i = 0; i < sizeof chart_keys / sizeof chart_keys[0]; i++) {
    size_t n = strlen(chart_keys[i].name);
    if (strncmp(text, chart_keys[i].name, n) == 0 &&
        (text[n] == ' ' || text[n] == ':' || text[n] == '-')) {
      key = chart_keys[i].name;
      if (text[n] != '-') break; /* "x-from" beats "x" */
    }
  }
  if (strncmp(text, "x and y", 7) == 0) key = "y";
  return sc_scene_fail_key(s, "task", key, msg, "%s", text);
}

/* ------------------------------------------------------------------ */
/* The scene's effective values, for the checkpoint                      */

/* Every value the results depend on, one "name = value" line each: the
 * model, its parameters and options, the accuracy, the chart.  [output]
 * is left out: the folder and plotting do not change the results. */
static int scene_text(const sc_cli_run *r, const sc_chart_spec *c, char *buf,
                      size_t len) {
  const sc_map *m = r->map;
  const sc_model_type *t = sc_map_type(m);
  size_t u = 0;
#define ADD_(...)                                                      \
  do {                                                                 \
    int k_ = snprintf(buf + u, u < len ? len - u : 0, __VA_ARGS__);    \
    if (k_ > 0) u += (size_t)k_;                                       \
  } while (0)
  ADD_("model = %s\n", t->name);
  for (size_t i = 0; i < t->nparam; i++)
    ADD_("model.%s = %.17g\n", t->params[i].name, sc_map_get_param(m, i));
  for (size_t i = 0; i < t->noption; i++)
    ADD_("model.%s = %s\n", t->options[i].name,
         sc_map_get_option(m, t->options[i].name));
  for (size_t i = 0; i < t->ndata; i++)
    ADD_("model.%s = %s\n", t->data[i].name,
         sc_map_get_data(m, t->data[i].name));
  const sc_accuracy *acc = sc_map_accuracy(m);
  for (size_t i = 0; i < sc_accuracy_nfields(); i++)
    ADD_("accuracy.%s = %.17g\n", sc_accuracy_field_name(i),
         sc_accuracy_field_value(acc, i));
  ADD_("task.x = %s\ntask.x-from = %.17g\ntask.x-to = %.17g\n"
       "task.x-steps = %ld\n",
       c->x, c->x_from, c->x_to, c->x_steps);
  ADD_("task.y = %s\ntask.y-from = %.17g\ntask.y-to = %.17g\n"
       "task.y-steps = %ld\n",
       c->y, c->y_from, c->y_to, c->y_steps);
  if (c->x_scale || c->y_scale) /* absent when linear: old checkpoints hold */
    ADD_("task.x-scale = %s\ntask.y-scale = %s\n",
         c->x_scale ? "log" : "linear", c->y_scale ? "log" : "linear");
  if (sc_map_dim(m) > 1) {
    ADD_("task.d0 =");
    for (size_t k = 0; k < sc_map_dim(m); k++) ADD_(" %.17g", c->x0[k]);
    ADD_("\n");
  } else {
    ADD_("task.d0 = %.17g\n", c->d0);
  }
  ADD_("task.transient = %ld\ntask.max-period = %d\n"
       "task.confirm = %d\ntask.seed = %s\n",
       c->transient, c->max_period, c->confirm,
       c->seed == SC_CHART_SEED_NEIGHBOUR ? "previous" : "fixed");
  ADD_("point-bytes = %zu\n", sizeof(sc_chart_point));
#undef ADD_
  return u < len ? SC_OK : SC_EINTERNAL;
}

/* FNV-1a, 64 bits: a fingerprint, not a defence against tampering. */
static uint64_t fnv1a(const char *s) {
  uint64_t h = 1469598103934665603ULL;
  for (; *s; s++) {
    h ^= (unsigned char)*s;
    h *= 1099511628211ULL;
  }
  return h;
}

/* ------------------------------------------------------------------ */
/* Checkpoint: `chart.checkpoint` in the output folder                   */

#define CKPT_NAME "chart.checkpoint"
#define CKPT_MAGIC "slipcont chart checkpoint 2\n"
#define SCENE_TEXT_LEN 8192
/* Bytes per point on disk: d (IEEE 754 binary64), period, iterations
 * (two's-complement int32), each little-endian whatever the host. */
#define CKPT_POINT_BYTES 16

/* The layout, version 2: the magic line, then the text lines
 *   hash H       FNV-1a of the scene text (16 hex digits)
 *   rows R       rows done, columns C, bytes B of the scene text
 *   columns C
 *   bytes B
 *   checksum S   FNV-1a of the R*C points as stored
 * then the scene text and R*C points of CKPT_POINT_BYTES.  Every value
 * read back is checked (ckpt_read()); anything off starts the chart over. */

static void put_le(unsigned char *p, uint64_t v, int n) {
  for (int i = 0; i < n; i++) p[i] = (unsigned char)(v >> (8 * i));
}

static uint64_t get_le(const unsigned char *p, int n) {
  uint64_t v = 0;
  for (int i = n - 1; i >= 0; i--) v = v << 8 | p[i];
  return v;
}

static void point_encode(const sc_chart_point *pt, unsigned char *b) {
  uint64_t bits;
  memcpy(&bits, &pt->d, sizeof bits);
  put_le(b, bits, 8);
  put_le(b + 8, (uint32_t)pt->period, 4);
  put_le(b + 12, (uint32_t)pt->iterations, 4);
}

static void point_decode(const unsigned char *b, sc_chart_point *pt) {
  uint64_t bits = get_le(b, 8);
  memcpy(&pt->d, &bits, sizeof bits);
  uint32_t p = (uint32_t)get_le(b + 8, 4), it = (uint32_t)get_le(b + 12, 4);
  pt->period = p > INT32_MAX ? -(int32_t)(UINT32_MAX - p) - 1 : (int32_t)p;
  pt->iterations = it > INT32_MAX ? -1 : (int32_t)it;
}

static uint64_t fnv1a_bytes(uint64_t h, const unsigned char *p, size_t n) {
  for (size_t i = 0; i < n; i++) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
  return h;
}
#define FNV_OFFSET 1469598103934665603ULL

/* Write the rows done so far, atomically (temporary name + rename). */
static int ckpt_write(sc_cli_run *r, const char *text, uint64_t hash,
                      long nx, long rows, const sc_chart_point *grid) {
  const char *dir = r->dir;
  sc_msg *msg = r->msg;
  const size_t n = (size_t)(rows * nx);
  unsigned char b[CKPT_POINT_BYTES];
  uint64_t sum = FNV_OFFSET;
  for (size_t k = 0; k < n; k++) {
    point_encode(&grid[k], b);
    sum = fnv1a_bytes(sum, b, sizeof b);
  }
  sc_file *f = NULL;
  int st = sc_cli_open(r, CKPT_NAME, &f);
  if (st) return st;
  FILE *o = sc_file_stream(f);
  fputs(CKPT_MAGIC, o);
  fprintf(o, "hash %016llx\nrows %ld\ncolumns %ld\nbytes %zu\n"
             "checksum %016llx\n",
          (unsigned long long)hash, rows, nx, strlen(text),
          (unsigned long long)sum);
  fputs(text, o);
  for (size_t k = 0; k < n; k++) {
    point_encode(&grid[k], b);
    if (fwrite(b, 1, sizeof b, o) != sizeof b) {
      sc_cli_abort(r, f);
      return sc_fail(msg, SC_EIO, "%s/%s: write failed", dir, CKPT_NAME);
    }
  }
  return sc_cli_commit(r, NULL, f); /* not named: removed at the end */
}


/* A point as the chart can have computed it: a period class in range,
 * iterations within the transient, d finite (or NaN where undefined). */
static int point_valid(const sc_chart_point *p, const sc_chart_spec *c) {
  if (p->period != SC_PERIOD_UNDEFINED && p->period != SC_PERIOD_HIGH &&
      p->period != SC_PERIOD_UNSETTLED && p->period != SC_PERIOD_CIRCLE &&
      (p->period < 1 || p->period > c->max_period))
    return 0;
  if (p->iterations < 0 || p->iterations > c->transient) return 0;
  if (p->period != SC_PERIOD_UNDEFINED && !isfinite(p->d)) return 0;
  return 1;
}

/* Read a checkpoint into grid; returns the rows it holds (0 when there is
 * none, it is unreadable, corrupt, or it belongs to another scene: then a
 * note says so and the chart starts over). */
static long ckpt_read(const sc_cli_run *r, const sc_chart_spec *c,
                      const char *text, uint64_t hash, sc_chart_point *grid) {
  const long nx = c->x_steps, ny = c->y_steps;
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", r->dir, CKPT_NAME);
  FILE *in = fopen(path, "rb");
  if (!in) return 0;
  char magic[sizeof CKPT_MAGIC] = "";
  unsigned long long h = 0, sum = 0;
  long rows = -1, cols = -1;
  size_t bytes = 0;
  long got = 0;
  char *old = NULL;
  if (fread(magic, 1, sizeof magic - 1, in) != sizeof magic - 1 ||
      strcmp(magic, CKPT_MAGIC) != 0 ||
      fscanf(in, "hash %16llx\nrows %9ld\ncolumns %9ld\nbytes %5zu\n"
                 "checksum %16llx",
             &h, &rows, &cols, &bytes, &sum) != 5 ||
      fgetc(in) != '\n') {
    sc_cli_note(r, "%s is not a chart checkpoint of this version: starting "
                   "over", path);
    goto done;
  }
  if (rows < 0 || rows > ny || cols != nx || bytes >= SCENE_TEXT_LEN) {
    sc_cli_note(r, "%s is corrupt (rows %ld of %ld, columns %ld of %ld, "
                   "%zu bytes of scene): starting over",
                path, rows, ny, cols, nx, bytes);
    goto done;
  }
  old = calloc(1, bytes + 1);
  if (!old || fread(old, 1, bytes, in) != bytes) {
    sc_cli_note(r, "%s is truncated: starting over", path);
    goto done;
  }
  if (h != hash || strcmp(old, text) != 0) {
    char change[256];
    if (!sc_first_change(old, text, '\n', change, sizeof change))
      snprintf(change, sizeof change, "the scene");
    sc_cli_note(r,
                "the checkpoint %s was made for another scene (%s): "
                "starting over",
                path, change);
    goto done;
  }
  uint64_t s = FNV_OFFSET;
  for (long k = 0; k < rows * nx; k++) {
    unsigned char b[CKPT_POINT_BYTES];
    if (fread(b, 1, sizeof b, in) != sizeof b) {
      sc_cli_note(r, "%s is truncated: starting over", path);
      goto done;
    }
    s = fnv1a_bytes(s, b, sizeof b);
    point_decode(b, &grid[k]);
    if (!point_valid(&grid[k], c)) {
      sc_cli_note(r, "%s is corrupt (point %ld: period %d, %d iterations): "
                     "starting over", path, k, (int)grid[k].period,
                  (int)grid[k].iterations);
      goto done;
    }
  }
  if (s != sum || fgetc(in) != EOF) {
    sc_cli_note(r, "%s is corrupt (checksum or length differs): starting "
                   "over", path);
    goto done;
  }
  got = rows;
done:
  free(old);
  fclose(in);
  return got;
}

/* ------------------------------------------------------------------ */
/* Output files                                                          */

/* Index of a period class in the counts: 0 invariant circle,
 * 1 unsettled, 2 undefined, 3 high, 3 + p period p. */
#define CLASS(p) ((p) + 3)
#define NCLASSES(maxp) ((size_t)(maxp) + 4)

/* Classes present, counted at CLASS(period). */
static void count_classes(const sc_chart_point *g, long n, int maxp,
                          long *count, double *iterations) {
  memset(count, 0, NCLASSES(maxp) * sizeof *count);
  *iterations = 0;
  for (long k = 0; k < n; k++) {
    count[CLASS(g[k].period)]++;
    *iterations += g[k].iterations;
  }
}

static int write_csv(sc_cli_run *r, const sc_chart_spec *c,
                     const sc_chart_point *g) {
  sc_file *f = NULL;
  int st = sc_cli_open(r, "chart.csv", &f);
  if (st) return st;
  FILE *o = sc_file_stream(f);
  /* a state of n > 1 components: its first one (sc_chart_point) */
  fprintf(o, "%s,%s,period,%s%s,iterations\n", c->x, c->y,
          sc_map_type(r->map)->state_name, sc_map_dim(r->map) > 1 ? "1" : "");
  for (long j = 0; j < c->y_steps; j++) {
    double y = sc_chart_y(c, j);
    for (long i = 0; i < c->x_steps; i++) {
      const sc_chart_point *p = &g[j * c->x_steps + i];
      sc_csv_double(o, sc_chart_x(c, i));
      fputc(',', o);
      sc_csv_double(o, y);
      fprintf(o, ",%d,", (int)p->period);
      sc_csv_double(o, p->d);
      fprintf(o, ",%d\n", (int)p->iterations);
    }
  }
  return sc_cli_commit(r, "chart.csv", f);
}

/* The colours of the period classes: sc_plot_period_rgb(), shared with
 * the chart drawn under a curve. */
#define HIGH_RGB sc_plot_period_rgb(SC_PERIOD_HIGH)
#define UNDEF_RGB sc_plot_period_rgb(SC_PERIOD_UNDEFINED)
#define UNSETTLED_RGB sc_plot_period_rgb(SC_PERIOD_UNSETTLED)
#define CIRCLE_RGB sc_plot_period_rgb(SC_PERIOD_CIRCLE)

static unsigned class_rgb(int period) { return sc_plot_period_rgb(period); }

/* The title: every parameter except the two on the axes, the options,
 * the start and the iterates. */
static void chart_title(const sc_map *m, const sc_chart_spec *c, char *buf,
                        size_t len) {
  const sc_model_type *t = sc_map_type(m);
  sc_plot_title_except(m, c->x, c->y, buf, len);
  size_t u = strlen(buf);
  if (sc_map_dim(m) > 1) {
    int k = snprintf(buf + u, u < len ? len - u : 0, "%s%s_0 = (",
                     u ? ", " : "", t->state_name);
    u += k > 0 ? (size_t)k : 0;
    for (size_t i = 0; i < sc_map_dim(m) && u < len; i++) {
      k = snprintf(buf + u, len - u, "%s%.6g", i ? ", " : "", c->x0[i]);
      u += k > 0 ? (size_t)k : 0;
    }
    if (u < len)
      snprintf(buf + u, len - u, "), %ld iterates at most", c->transient);
    return;
  }
  if (u < len)
    snprintf(buf + u, len - u, "%s%s_0 = %.10g, %ld iterates at most",
             u ? ", " : "", t->state_name, c->d0, c->transient);
}

static int write_plot(sc_cli_run *r, const sc_chart_spec *c,
                      const long *count) {
  char title[512], xl[128], yl[128];
  chart_title(r->map, c, title, sizeof title);
  /* A log axis is drawn as log10 of the values: the cells are then
   * equal, as rgbimage needs. */
  snprintf(xl, sizeof xl, c->x_scale ? "log10 %s" : "%s",
           sc_plot_label(r->map, c->x));
  snprintf(yl, sizeof yl, c->y_scale ? "log10 %s" : "%s",
           sc_plot_label(r->map, c->y));
  sc_file *f = NULL;
  int st = sc_cli_plot_begin(r, "chart", title, xl, yl, &f);
  if (st) return st;
  FILE *o = sc_file_stream(f);
  double x0 = c->x_scale ? log10(fabs(c->x_from)) : c->x_from;
  double x1 = c->x_scale ? log10(fabs(c->x_to)) : c->x_to;
  double y0 = c->y_scale ? log10(fabs(c->y_from)) : c->y_from;
  double y1 = c->y_scale ? log10(fabs(c->y_to)) : c->y_to;
  double hx = (x1 - x0) / (double)(c->x_steps - 1) / 2;
  double hy = (y1 - y0) / (double)(c->y_steps - 1) / 2;
  fprintf(o, "set xrange [%.17g:%.17g]\n", fmin(x0, x1) - fabs(hx),
          fmax(x0, x1) + fabs(hx));
  fprintf(o, "set yrange [%.17g:%.17g]\n", fmin(y0, y1) - fabs(hy),
          fmax(y0, y1) + fabs(hy));
  fputs("set size square\nunset grid\nset tics out\n"
        "set key outside right top title 'period' box\n",
        o);
  if (sc_map_dim(r->map) > 1)
    fputs("# colour of a period class (column 3): -3 invariant circle, -2 "
          "not settled, -1 undefined, 0 high\n", o);
  else
    fputs("# colour of a period class (column 3): -2 not settled, -1 "
          "undefined, 0 high\n", o);
  fputs("array C[16] = [", o);
  for (int k = 0; k < 16; k++)
    fprintf(o, "%s0x%06x", k ? ", " : "", sc_plot_period_rgb(k + 1));
  fputs("]\n", o);
  if (sc_map_dim(r->map) > 1)
    fprintf(o, "rgb(p) = p == -3 ? 0x%06x : p == -2 ? 0x%06x : p < 0 ? "
               "0x%06x : p == 0 ? 0x%06x : C[int(p - 1) %% 16 + 1]\n",
            CIRCLE_RGB, UNSETTLED_RGB, UNDEF_RGB, HIGH_RGB);
  else
    fprintf(o,
            "rgb(p) = p == -2 ? 0x%06x : p < 0 ? 0x%06x : p == 0 ? 0x%06x : "
            "C[int(p - 1) %% 16 + 1]\n",
            UNSETTLED_RGB, UNDEF_RGB, HIGH_RGB);
  fprintf(o, "plot 'chart.csv' skip 1 using %s:%s:(int(rgb($3)) >> 16 & "
             "255):",
          c->x_scale ? "(log10(abs($1)))" : "1",
          c->y_scale ? "(log10(abs($2)))" : "2");
  fputs("(int(rgb($3)) >> 8 & 255):(int(rgb($3)) & 255) with rgbimage "
        "notitle",
        o);
  /* A key entry for each class present. */
  for (int p = 1; p <= c->max_period; p++)
    if (count[CLASS(p)])
      fprintf(o, ", \\\n  keyentry with boxes fs solid fc rgb '#%06x' "
              "title '%d'",
              class_rgb(p), p);
  if (count[CLASS(SC_PERIOD_CIRCLE)])
    fprintf(o, ", \\\n  keyentry with boxes fs solid fc rgb '#%06x' "
            "title 'invariant circle'",
            CIRCLE_RGB);
  if (count[CLASS(SC_PERIOD_HIGH)])
    fprintf(o, ", \\\n  keyentry with boxes fs solid fc rgb '#%06x' "
            "title '> %d or chaos'",
            HIGH_RGB, c->max_period);
  if (count[CLASS(SC_PERIOD_UNSETTLED)])
    fprintf(o, ", \\\n  keyentry with boxes fs solid border lc rgb "
            "'#000000' fc rgb '#%06x' title 'not settled'",
            UNSETTLED_RGB);
  if (count[CLASS(SC_PERIOD_UNDEFINED)])
    fprintf(o, ", \\\n  keyentry with boxes fs solid border lc rgb "
            "'#000000' fc rgb '#%06x' title 'undefined'",
            UNDEF_RGB);
  fputc('\n', o);
  return sc_cli_plot_end(r, "chart", f);
}

/* ------------------------------------------------------------------ */
/* The run                                                               */

typedef struct {
  sc_progress *bar;
  long base;  /* points done before this block (all ranks) */
  long mult;  /* ranks: this rank's points stand for that many */
} progress_ctx;

static int on_progress(void *ctx, long done) {
  progress_ctx *p = ctx;
  sc_progress_update(p->bar, p->base + done * p->mult);
  return sc_cli_interrupted();
}

/* Seconds between checkpoints: often enough that a kill loses little,
 * rarely enough that rewriting the rows done costs nothing. */
#define CKPT_INTERVAL_S 2.0
/* Points a block should hold at least: enough that the threads' wait
 * for the block's last point stays small next to the block, few enough
 * (a second or so of bk2) that a kill loses little. */
#define BLOCK_POINTS 2048

/* One chart run: the spec, this process's place among the ranks, and
 * the buffers (rank 0 holds the whole grid). */
typedef struct {
  sc_chart_spec c;
  long nx, ny;
  int rank, size, threads;
  double t0;
  long block;      /* rows per block */
  long stop_after; /* --stop-after-rows (rank 0's, broadcast) */
  long start;      /* rows read back from a checkpoint */
  char *text;      /* the scene's effective values (checkpoint) */
  uint64_t hash;   /* and their fingerprint */
  sc_chart_point *grid, *mine, *stage;
  int mpi;           /* sc_mpi_chart_begin() succeeded */
  long *count;       /* points of each class (rank 0, once complete) */
  double iterations; /* map iterates in all */
  double x0[SC_MAXDIM]; /* the initial state of a map of n > 1 components */
} chart_job;

/* Rows per block: enough points to keep the threads busy (whole rows per
 * thread with seed = previous), a multiple of the ranks. */
static long block_rows(const chart_job *j) {
  long block = (BLOCK_POINTS + j->nx - 1) / j->nx;
  if (j->c.seed == SC_CHART_SEED_NEIGHBOUR && block < 2L * j->threads)
    block = 2L * j->threads;
  if (j->size > 1 && block < 4L * j->size) block = 4L * j->size;
  block = (block + j->size - 1) / j->size * j->size;
  return block > j->ny ? j->ny : block;
}

/* All ranks learn the worst status; a rank that was fine says which
 * failed. */
static int agree(sc_cli_run *r, int st, const char *who) {
#ifdef SLIPCONT_MPI
  int all = sc_mpi_chart_min_status(st);
  if (all && !st)
    st = sc_fail(r->msg, all, "chart: %s failed (%s)", who, sc_strerror(all));
#else
  (void)r;
  (void)who;
#endif
  return st;
}

/* This process among the ranks, the spec, the block size. */
static int chart_setup(sc_cli_run *r, chart_job *j) {
  j->c = spec_of(r->scene, j->x0);
  j->nx = j->c.x_steps;
  j->ny = j->c.y_steps;
  j->size = 1;
  int st = sc_chart_check(r->map, &j->c, r->msg);
  if (st) return st;
#ifdef SLIPCONT_MPI
  if ((st = sc_mpi_chart_begin(&j->rank, &j->size, r->msg))) return st;
  j->mpi = 1;
  /* rank 0 writes every file; the others only compute */
  r->compute_only = j->rank != 0;
#endif
  j->threads = omp_get_max_threads();
  j->t0 = sc_progress_now();
  j->block = block_rows(j);
  j->stop_after = j->rank == 0 ? r->stop_after_rows : 0;
  return SC_OK;
}

/* The ranks, the scene text and its hash, the buffers, the checkpoint.
 * Failures after sc_mpi_chart_begin() fall through to the first
 * collective call, so that every rank learns of them. */
static int chart_prepare(sc_cli_run *r, void *job) {
  chart_job *j = job;
  int st = chart_setup(r, j);
  if (st) return st;
  j->text = malloc(SCENE_TEXT_LEN);
  if (!j->text)
    st = sc_fail(r->msg, SC_ENOMEM, "chart: out of memory");
  else if (scene_text(r, &j->c, j->text, SCENE_TEXT_LEN))
    st = sc_fail(r->msg, SC_EINTERNAL,
                 "chart: scene text longer than %d bytes", SCENE_TEXT_LEN);
  else
    j->hash = fnv1a(j->text);
  const long nx = j->nx, ny = j->ny;
  if (!st && j->rank == 0) {
    j->grid = malloc((size_t)(nx * ny) * sizeof *j->grid);
    if (j->size > 1)
      j->stage = malloc((size_t)(j->block * nx) * sizeof *j->stage);
    if (!j->grid || (j->size > 1 && !j->stage)) {
      st = sc_fail(r->msg, SC_ENOMEM,
                   "chart: out of memory for %ld x %ld points (%.0f MiB)", nx,
                   ny, (double)(nx * ny) * sizeof *j->grid / 1048576);
    } else {
      j->start = ckpt_read(r, &j->c, j->text, j->hash, j->grid);
      if (j->start)
        sc_cli_note(r, "resuming from %s/%s: %ld of %ld rows done", r->dir,
                    CKPT_NAME, j->start, ny);
    }
  }
  if (!st && j->size > 1) {
    j->mine = malloc((size_t)((j->block + j->size - 1) / j->size * nx) *
                     sizeof *j->mine);
    if (!j->mine)
      st = sc_fail(r->msg, SC_ENOMEM, "chart: out of memory (rank %d)",
                   j->rank);
  }
  st = agree(r, st, "another rank");
#ifdef SLIPCONT_MPI
  sc_mpi_chart_bcast_long(&j->start);
  sc_mpi_chart_bcast_long(&j->stop_after);
#endif
  return st;
}

/* The rows from the checkpoint's end to the last, block by block, with a
 * checkpoint every CKPT_INTERVAL_S, on a signal (then SC_ECALLBACK) and
 * at --stop-after-rows. */
static int chart_compute(sc_cli_run *r, void *job) {
  chart_job *j = job;
  const long nx = j->nx, ny = j->ny;
  int st = SC_OK;
  sc_progress bar;
  sc_progress_start(&bar, "points", nx * ny, j->start * nx,
                    j->rank == 0 && sc_progress_wanted(r->quiet));
  double last_ckpt = sc_progress_now();
  long done_rows = j->start;
  while (done_rows < ny) {
    long r0 = done_rows, r1 = r0 + j->block < ny ? r0 + j->block : ny;
    if (j->stop_after > r0 && j->stop_after < r1) r1 = j->stop_after;
    long nb = r1 - r0;
    progress_ctx pc = {&bar, r0 * nx, j->size};
    sc_chart_point *dst = j->size > 1 ? j->mine : j->grid + r0 * nx;
    long count = j->rank < nb ? (nb - j->rank + j->size - 1) / j->size : 0;
    st = sc_chart_rows(r->map, &j->c, r0 + j->rank, count, j->size, 0,
                       on_progress, &pc, dst, r->msg);
    st = agree(r, st, "another rank");
#ifdef SLIPCONT_MPI
    if (!st && j->size > 1)
      st = sc_mpi_chart_gather(j->mine, nx, r0, nb, j->rank, j->size,
                               j->stage, j->grid, r->msg);
#endif
    if (st == SC_ECALLBACK && sc_cli_interrupted()) {
      sc_progress_finish(&bar);
      int e = j->rank == 0
                  ? ckpt_write(r, j->text, j->hash, nx, done_rows, j->grid)
                  : SC_OK;
      return e ? e
               : sc_fail(r->msg, SC_ECALLBACK,
                         "chart: interrupted after %ld of %ld rows; the "
                         "checkpoint %s/%s is saved: run the same command "
                         "to resume",
                         done_rows, ny, r->dir, CKPT_NAME);
    }
    if (st) break;
    done_rows = r1;
    sc_progress_update(&bar, done_rows * nx); /* all ranks' points */
    int hooked = j->stop_after > 0 && done_rows == j->stop_after &&
                 done_rows < ny;
    if (j->rank == 0 && done_rows < ny &&
        (hooked || sc_progress_now() - last_ckpt >= CKPT_INTERVAL_S)) {
      st = ckpt_write(r, j->text, j->hash, nx, done_rows, j->grid);
      last_ckpt = sc_progress_now();
    }
    st = agree(r, st, "rank 0"); /* rank 0's checkpoint */
    if (st) break;
    if (hooked) {
      sc_progress_finish(&bar);
      return sc_fail(r->msg, SC_ECALLBACK,
                     "chart: stopped after %ld of %ld rows by "
                     "--stop-after-rows; checkpoint saved",
                     done_rows, ny);
    }
  }
  sc_progress_finish(&bar);
  return st;
}

/* The files (rank 0): the grid is complete.  A long chart first leaves
 * a complete checkpoint, so that a rerun after a kill while writing only
 * writes the files. */
static int chart_write(sc_cli_run *r, void *job) {
  chart_job *j = job;
  int st;
  if (j->start < j->ny && sc_progress_now() - j->t0 >= CKPT_INTERVAL_S &&
      (st = ckpt_write(r, j->text, j->hash, j->nx, j->ny, j->grid)))
    return st;
  j->count = calloc(NCLASSES(j->c.max_period), sizeof *j->count);
  if (!j->count) return sc_fail(r->msg, SC_ENOMEM, "chart: out of memory");
  count_classes(j->grid, j->nx * j->ny, j->c.max_period, j->count,
                &j->iterations);
  return write_csv(r, &j->c, j->grid);
}

static int chart_summary(sc_cli_run *r, void *job, FILE *o) {
  const chart_job *j = job;
  const sc_chart_spec *c = &j->c;
  const long *count = j->count;
  long n = c->x_steps * c->y_steps;
  fprintf(o, "  %ld x %ld = %ld points, %.0f map iterates (%.1f a point)\n",
          c->x_steps, c->y_steps, n, j->iterations,
          j->iterations / (double)n);
  fprintf(o, "  %.3f s on %d rank(s) x %d thread(s)",
          sc_progress_now() - j->t0, j->size, j->threads);
  if (j->start) fprintf(o, ", resumed after %ld rows", j->start);
  fputc('\n', o);
  for (int p = 1; p <= c->max_period; p++)
    if (count[CLASS(p)])
      fprintf(o, "  period %-3d %10ld points (%.2f%%)\n", p, count[CLASS(p)],
              100.0 * (double)count[CLASS(p)] / (double)n);
  long high = count[CLASS(SC_PERIOD_HIGH)];
  long unset = count[CLASS(SC_PERIOD_UNSETTLED)];
  long undef = count[CLASS(SC_PERIOD_UNDEFINED)];
  if (sc_map_dim(r->map) > 1) {
    long circ = count[CLASS(SC_PERIOD_CIRCLE)];
    fprintf(o, "  invariant circle %4ld points (%.2f%%): no period, the last "
               "%d points on a closed curve\n",
            circ, 100.0 * (double)circ / (double)n, SC_CIRCLE_POINTS);
  }
  fprintf(o, "  high       %10ld points (%.2f%%): period > %d or chaos\n",
          high, 100.0 * (double)high / (double)n, c->max_period);
  fprintf(o, "  not settled %9ld points (%.2f%%): still converging after %ld "
          "iterates (raise transient)\n",
          unset, 100.0 * (double)unset / (double)n, c->transient);
  fprintf(o, "  undefined  %10ld points (%.2f%%)\n", undef,
          100.0 * (double)undef / (double)n);
  return SC_OK;
}

static int chart_plots(sc_cli_run *r, void *job) {
  const chart_job *j = job;
  return write_plot(r, &j->c, j->count);
}

/* Every file is written: the checkpoint goes. */
static int chart_report(sc_cli_run *r, void *job) {
  const chart_job *j = job;
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", r->dir, CKPT_NAME);
  if (remove(path) != 0 && errno != ENOENT)
    sc_cli_note(r, "could not remove %s: %s", path, strerror(errno));
  char circ[64] = "";
  if (sc_map_dim(r->map) > 1)
    snprintf(circ, sizeof circ, "%ld invariant circle, ",
             j->count[CLASS(SC_PERIOD_CIRCLE)]);
  sc_cli_note(r,
              "chart: %ld points in %.2f s (%d rank(s) x %d thread(s)); "
              "%s%ld high, %ld not settled, %ld undefined",
              j->nx * j->ny, sc_progress_now() - j->t0, j->size, j->threads,
              circ, j->count[CLASS(SC_PERIOD_HIGH)],
              j->count[CLASS(SC_PERIOD_UNSETTLED)],
              j->count[CLASS(SC_PERIOD_UNDEFINED)]);
  return SC_OK;
}

static void chart_release(sc_cli_run *r, void *job) {
  chart_job *j = job;
  (void)r;
  free(j->grid);
  free(j->mine);
  free(j->stage);
  free(j->text);
  free(j->count);
#ifdef SLIPCONT_MPI
  if (j->mpi) sc_mpi_chart_end();
#endif
}

const sc_cli_task sc_cli_task_chart = {
    .type = {.kind = "chart",
             .doc = "period of the attractor on a grid over two parameters "
                    "(fig 5.7): OpenMP, MPI, resumable",
             .keys = chart_keys,
             .nkeys = sizeof chart_keys / sizeof chart_keys[0],
             .check = chart_check},
    .outputs = "chart.csv (x,y,period,d,iterations; n > 1: d1, the first "
               "component), summary.txt, chart.gp, chart.png; "
               "chart.checkpoint while unfinished",
    .job_size = sizeof(chart_job),
    .prepare = chart_prepare,
    .compute = chart_compute,
    .write = chart_write,
    .summary = chart_summary,
    .plots = chart_plots,
    .report = chart_report,
    .release = chart_release,
};
