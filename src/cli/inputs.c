/* The files a scene names besides itself, read the one way every such
 * file is read (sc_input_open(): a regular file of bounded size, opened
 * without blocking): rows of a branch task's points.csv (`starts` of a
 * branch, `start` of a curve) and the header lines of an overlay or of
 * the curves of `also`. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/tasks.h"

int sc_cli_read_head(const char *path, const char *what, char *line,
                     size_t len, sc_msg *msg) {
  FILE *f;
  line[0] = '\0';
  int st = sc_input_open(path, what, SC_INPUT_MAXBYTES, &f, msg);
  if (st) return st;
  if (!fgets(line, (int)len, f)) line[0] = '\0';
  fclose(f);
  line[strcspn(line, "\r\n")] = '\0';
  return SC_OK;
}

int sc_cli_csv_split(char *line, char **f, int max) {
  int n = 0;
  line[strcspn(line, "\r\n")] = '\0';
  for (char *p = line; n < max;) {
    f[n++] = p;
    char *c = strchr(p, ',');
    if (!c) break;
    *c = '\0';
    p = c + 1;
  }
  return n;
}

/* Row n of the open points.csv f, its columns found by the header's
 * names. */
static int read_row(FILE *f, const char *path, long n, sc_cli_points_row *row,
                    char *why, size_t len) {
  static const char *const names[5] = {"label", "parameter", "value", "d",
                                       "period"};
  char *line = NULL, *h[16], *v[16];
  size_t cap = 0;
  int col[5] = {-1, -1, -1, -1, -1}, colb = -1, colm = -1;
  int nh =
      getline(&line, &cap, f) > 0 ? sc_cli_csv_split(line, h, 16) : 0;
  for (int i = 0; i < nh; i++) {
    for (int k = 0; k < 5; k++)
      if (strcmp(h[i], names[k]) == 0) col[k] = i;
    if (strcmp(h[i], "border") == 0) colb = i; /* optional */
    if (strcmp(h[i], "method") == 0) colm = i; /* optional */
  }
  for (int k = 0; k < 5; k++)
    if (col[k] < 0) {
      snprintf(why, len,
               "%.300s has no column '%s' (a branch task's points.csv has "
               "label,parameter,value,d,period)",
               path, names[k]);
      free(line);
      return SC_EINVAL;
    }
  long rows = 0;
  while (rows < n && getline(&line, &cap, f) > 0) rows++;
  if (rows < n) {
    snprintf(why, len,
             "%.300s has no row %ld (it has fewer than %ld rows: %ld after "
             "the header)",
             path, n, n, rows);
    free(line);
    return SC_EINVAL;
  }
  int nv = sc_cli_csv_split(line, v, 16), st = SC_OK;
  long per = 0;
  for (int k = 0; k < 5; k++)
    if (col[k] >= nv) st = SC_EINVAL;
  if (st)
    snprintf(why, len, "row %ld of %.300s has too few columns", n, path);
  else if (sc_parse_double(v[col[2]], &row->value) || !isfinite(row->value) ||
           sc_parse_double(v[col[3]], &row->d) || !isfinite(row->d) ||
           sc_parse_long(v[col[4]], 1, 4096, &per)) {
    st = SC_EINVAL;
    snprintf(why, len,
             "row %ld of %.300s: value, d or period unreadable (valid: "
             "finite numbers, a period in [1, 4096])",
             n, path);
  } else {
    row->period = (int)per;
    snprintf(row->label, sizeof row->label, "%.15s", v[col[0]]);
    snprintf(row->param, sizeof row->param, "%.63s", v[col[1]]);
    snprintf(row->border, sizeof row->border, "%.63s",
             colb >= 0 && colb < nv ? v[colb] : "");
    snprintf(row->method, sizeof row->method, "%.15s",
             colm >= 0 && colm < nv ? v[colm] : "");
  }
  free(line);
  return st;
}

int sc_cli_points_row_read(const char *spec, sc_cli_points_row *row,
                           char *why, size_t len) {
  char path[4096];
  snprintf(path, sizeof path, "%s", spec);
  char *colon = strrchr(path, ':');
  long n = 0;
  if (!colon || colon == path || sc_parse_long(colon + 1, 1, 100000000, &n)) {
    snprintf(why, len, "'%.300s' is not FILE:N with a row number N in [1, "
                       "100000000]",
             spec);
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
  st = read_row(f, path, n, row, why, len);
  fclose(f);
  return st;
}

void sc_cli_put_state(FILE *f, const double *x, size_t n) {
  fputc('(', f);
  for (size_t c = 0; c < n; c++) fprintf(f, "%s%.17g", c ? ", " : "", x[c]);
  fputc(')', f);
}
