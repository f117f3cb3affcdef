/* Labelled points of the benchmarks' error-against-time plots (log-log):
 * the labels are placed by the library's sc_plot_place() in a fixed
 * frame, so that no two overlap (points under one marker share a label:
 * "exact fast, default, precise"). */
#ifndef SC_BENCH_PLOT_H
#define SC_BENCH_PLOT_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "slipcont/io.h"

/* A decade below the smallest and above the largest of v[0..n) (> 0):
 * room for the labels, ticks at powers of ten. */
static inline void bench_plot_decades(int n, const double *v, double *lo,
                                      double *hi) {
  double a = HUGE_VAL, b = 0;
  for (int i = 0; i < n; i++)
    if (v[i] > 0) a = fmin(a, v[i]), b = fmax(b, v[i]);
  if (!(a <= b)) a = 1e-3, b = 1;
  *lo = pow(10, floor(log10(a)) - (log10(a) - floor(log10(a)) < 0.3));
  *hi = pow(10, ceil(log10(b)) + (ceil(log10(b)) - log10(b) < 0.3));
}

/* Write the frame of a W x H picture whose plot area spans [left, right]
 * x [bottom, top] (fractions), log-log over the points, and their labels
 * text[i] at (x[i], y[i]); the key goes below the x label. */
static inline void bench_plot_labels(FILE *gp, int w, int h, double left,
                                     double right, double bottom, double top,
                                     int n, const double *x, const double *y,
                                     const char *const *text) {
  sc_plot_frame fr = {.width = w, .height = h, .left = left,
                      .right = right, .bottom = bottom, .top = top,
                      .xlog = 1, .ylog = 1, .font = 8, .marker = 5};
  bench_plot_decades(n, x, &fr.xmin, &fr.xmax);
  bench_plot_decades(n, y, &fr.ymin, &fr.ymax);
  sc_plot_spot *s = calloc((size_t)(n > 0 ? n : 1), sizeof *s);
  if (!s) return;
  for (int i = 0; i < n; i++) {
    s[i].x = x[i];
    s[i].y = y[i];
    snprintf(s[i].text, sizeof s[i].text, "%s", text[i]);
  }
  sc_plot_frame_write(gp, &fr);
  size_t out = sc_plot_place(&fr, s, (size_t)n);
  sc_plot_labels_write(gp, &fr, s, (size_t)n, "#333333");
  if (out)
    fprintf(gp, "# %zu labels left out: no free place\n", out);
  free(s);
}

#endif
