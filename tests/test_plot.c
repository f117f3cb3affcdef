/* Figures: label boxes against measured text, label placement (no two
 * labels overlap, none covers a marker, all inside the plot area), tick
 * formats on narrow ranges, shared colours and markers. */
#define _POSIX_C_SOURCE 200809L /* fmemopen */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "slipcont/io.h"
#include "test_util.h"

/* Widths in pixels of texts drawn by gnuplot 5.4's pngcairo in Sans,
 * measured on the rendered pictures (the extent of the dark pixels): a
 * box must hold each of them. */
static void test_text_box(void) {
  static const struct {
    const char *text;
    double font, width, height;
  } measured[] = {
      {"0123456789", 12, 98, 12},     {"MMMMMMMMMM", 12, 136, 12},
      {"exact default", 12, 104, 12}, {"numerical 1e-8", 12, 119, 12},
      {"Hg", 12, 19, 15},             {"0123456789", 8, 68, 8},
      {"numerical 1e-8", 8, 80, 8},   {"Hg", 9, 15, 12},
      {"numerical 1e-8", 9, 89, 10},  {"exact default", 9, 77, 10},
  };
  for (size_t i = 0; i < sizeof measured / sizeof *measured; i++) {
    double b[4];
    sc_plot_text_box(measured[i].font, measured[i].text, 100, 50, b);
    tu_true(b[2] - b[0] >= measured[i].width &&
                b[2] - b[0] <= 1.3 * measured[i].width + 4,
            "box of '%s' at %g pt is %g px wide; drawn %g px (the box holds "
            "it, at most 30%% more)",
            measured[i].text, measured[i].font, b[2] - b[0],
            measured[i].width);
    tu_true(b[3] - b[1] >= measured[i].height,
            "box of '%s' at %g pt is %g px high; drawn %g px",
            measured[i].text, measured[i].font, b[3] - b[1],
            measured[i].height);
  }
  double a[4] = {0, 0, 10, 10}, c[4] = {10, 0, 20, 10}, d[4] = {9, 9, 20, 20};
  tu_int("boxes that touch do not overlap", sc_plot_boxes_overlap(a, c), 0);
  tu_int("boxes that share a corner square overlap",
         sc_plot_boxes_overlap(a, d), 1);
}

/* Every placed label inside the area, clear of every other label and of
 * every marker; returns the number placed. */
static size_t check_layout(const char *what, const sc_plot_frame *fr,
                           const sc_plot_spot *s, size_t n) {
  double X0 = fr->width * fr->left, X1 = fr->width * fr->right;
  double Y0 = fr->height * fr->bottom, Y1 = fr->height * fr->top;
  size_t placed = 0, bad = 0;
  for (size_t i = 0; i < n; i++) {
    if (s[i].placed != 1) continue;
    placed++;
    /* the box recomputed from the anchor, not taken from the output */
    double b[4];
    sc_plot_text_box(fr->font, s[i].text, s[i].ax, s[i].ay, b);
    if (b[0] < X0 || b[2] > X1 || b[1] < Y0 || b[3] > Y1) bad++;
    for (size_t j = 0; j < n; j++) {
      double m[4] = {s[j].px - fr->marker, s[j].py - fr->marker,
                     s[j].px + fr->marker, s[j].py + fr->marker};
      if (sc_plot_boxes_overlap(b, m)) bad++;
      if (j > i && s[j].placed == 1) {
        double c[4];
        sc_plot_text_box(fr->font, s[j].text, s[j].ax, s[j].ay, c);
        if (sc_plot_boxes_overlap(b, c)) {
          bad++;
          printf("  overlap: '%s' and '%s'\n", s[i].text, s[j].text);
        }
      }
    }
  }
  tu_int(what, (long)bad, 0);
  return placed;
}

/* The map accuracy figure (docs/img/accuracy-map-f.png): the three exact
 * presets at one point, numerical 1e-6 and 1e-8 nearly at one point
 * beside 1e-4; these overprinted each other. */
static void test_accuracy_figure(void) {
  static const struct {
    const char *text;
    double t, e;
  } pts[] = {
      {"exact fast", 1.08e-6, 1.36e-15},
      {"exact default", 1.09e-6, 1.36e-15},
      {"exact precise", 1.10e-6, 1.36e-15},
      {"numerical 1e-4", 9.3e-6, 1.5e-10},
      {"numerical 1e-6", 1.29e-5, 1.47e-10},
      {"numerical 1e-8", 1.30e-5, 1.45e-10},
      {"numerical 1e-10", 1.30e-5, 2.3e-12},
      {"numerical 1e-12", 2.1e-5, 1.5e-14},
      {"quad", 1.35e-4, 1e-18},
  };
  size_t n = sizeof pts / sizeof *pts;
  sc_plot_frame fr = {.width = 900, .height = 600, .left = 0.12,
                      .right = 0.96, .bottom = 0.2, .top = 0.9,
                      .xmin = 1e-7, .xmax = 1e-3, .ymin = 1e-19,
                      .ymax = 1e-9, .xlog = 1, .ylog = 1, .font = 8,
                      .marker = 5};
  sc_plot_spot s[16];
  memset(s, 0, sizeof s);
  for (size_t i = 0; i < n; i++) {
    s[i].x = pts[i].t;
    s[i].y = pts[i].e;
    snprintf(s[i].text, sizeof s[i].text, "%s", pts[i].text);
  }
  size_t out = sc_plot_place(&fr, s, n);
  tu_int("accuracy figure: labels left out", (long)out, 0);
  check_layout("accuracy figure: overlaps", &fr, s, n);
  tu_true(strcmp(s[0].text, "exact fast, default, precise") == 0,
          "the presets at one point share the label '%s' (expected 'exact "
          "fast, default, precise')",
          s[0].text);
  tu_int("exact default merged into exact fast", s[1].into, 0);
  tu_int("exact precise merged into exact fast", s[2].into, 0);
  tu_true(s[4].placed == 1 && s[5].placed == 0 &&
              strcmp(s[4].text, "numerical 1e-6, 1e-8") == 0,
          "1e-6 and 1e-8 under one marker share '%s'", s[4].text);
}

/* A crowded figure: 300 points in three tight clusters and a line, as on
 * a branch plot near an accumulation of flips.  Whatever is placed does
 * not overlap; what has no room is counted, not drawn. */
static void test_crowded(void) {
  enum { N = 300 };
  sc_plot_spot *s = calloc(N, sizeof *s);
  sc_plot_frame fr = {.width = 1200, .height = 800, .left = 0.08,
                      .right = 0.8, .bottom = 0.2, .top = 0.93, .xmin = 0,
                      .xmax = 1, .ymin = 0, .ymax = 1, .font = 9,
                      .marker = 6};
  unsigned long seed = 12345;
  for (int i = 0; i < N; i++) {
    seed = seed * 6364136223846793005UL + 1442695040888963407UL;
    double u = (double)(seed >> 11) / 9007199254740992.0;
    seed = seed * 6364136223846793005UL + 1442695040888963407UL;
    double v = (double)(seed >> 11) / 9007199254740992.0;
    int c = i % 4;
    s[i].x = c == 3 ? u : 0.2 + 0.3 * c + 0.03 * u;
    s[i].y = c == 3 ? 0.5 + 0.1 * u : 0.3 + 0.05 * v;
    snprintf(s[i].text, sizeof s[i].text, "%d", i + 1);
  }
  size_t out = sc_plot_place(&fr, s, N);
  size_t placed = check_layout("crowded figure: overlaps", &fr, s, N);
  size_t merged = 0;
  for (int i = 0; i < N; i++) merged += s[i].placed == 0;
  tu_int("crowded figure: placed + merged + left out = all",
         (long)(placed + merged + out), N);
  tu_true(placed > 30, "crowded figure: %zu labels placed (> 30)", placed);
  free(s);
}

/* A marker only (empty text) is never labelled and keeps labels off. */
static void test_marker_only(void) {
  sc_plot_frame fr = {.width = 400, .height = 300, .left = 0.1,
                      .right = 0.9, .bottom = 0.1, .top = 0.9, .xmin = 0,
                      .xmax = 1, .ymin = 0, .ymax = 1, .font = 10,
                      .marker = 6};
  sc_plot_spot s[2];
  memset(s, 0, sizeof s);
  s[0].x = 0.5, s[0].y = 0.5;
  snprintf(s[0].text, sizeof s[0].text, "LP");
  s[1].x = 0.51, s[1].y = 0.5; /* under the first marker */
  sc_plot_place(&fr, s, 2);
  tu_int("a marker only is not merged", s[1].into, -1);
  tu_true(strcmp(s[0].text, "LP") == 0, "label kept as 'LP': '%s'",
          s[0].text);
  check_layout("marker only: overlaps", &fr, s, 2);
}

/* Tick labels at the finest step gnuplot may choose differ with the
 * format written; wide ranges keep gnuplot's own. */
static void test_axis_format(void) {
  static const double ranges[][2] = {
      {0.19736742105263158, 0.19736942105263158}, /* accuracy-dstar.ini */
      {3.41884855, 3.41884856},
      {-1e-9, 1e-9},
      {1234.5, 1234.5001},
  };
  for (size_t r = 0; r < sizeof ranges / sizeof *ranges; r++) {
    char buf[256] = "";
    FILE *f = fmemopen(buf, sizeof buf, "w");
    sc_plot_axis_format(f, "x", ranges[r][0], ranges[r][1]);
    fclose(f);
    char fmt[32] = "%g"; /* gnuplot's default shows six digits */
    int digits;
    if (sscanf(buf, "set format x '%%.%dg'", &digits) == 1)
      snprintf(fmt, sizeof fmt, "%%.%dg", digits);
    double lo = ranges[r][0], hi = ranges[r][1], step = (hi - lo) / 20;
    /* ticks at multiples of a 1-2-5 step near a twentieth of the range */
    double p10 = pow(10, floor(log10(step)));
    double st = step / p10 >= 5 ? 5 * p10 : step / p10 >= 2 ? 2 * p10 : p10;
    char prev[64] = "", cur[64];
    int same = 0, nt = 0;
    for (double t = ceil(lo / st) * st; t <= hi; t += st, nt++) {
      snprintf(cur, sizeof cur, fmt, fabs(t) < st / 2 ? 0.0 : t);
      same += strcmp(cur, prev) == 0;
      snprintf(prev, sizeof prev, "%s", cur);
    }
    tu_true(nt >= 4 && same == 0,
            "range [%.17g, %.17g]: %d ticks with format %s, %d equal to "
            "their neighbour",
            lo, hi, nt, fmt, same);
  }
  char buf[256] = "";
  FILE *f = fmemopen(buf, sizeof buf, "w");
  sc_plot_axis_format(f, "y", 2.8, 4);
  fclose(f);
  tu_true(buf[0] == '\0', "range [2.8, 4] keeps gnuplot's format: '%s'",
          buf);
}

/* Colours and markers: the chart's period colours; each kind's own
 * marker; neighbouring curves in different colours. */
static void test_styles(void) {
  tu_int("period 1 colour", (long)sc_plot_period_rgb(1), 0x1f77b4);
  tu_int("period 17 repeats period 1", (long)sc_plot_period_rgb(17),
         (long)sc_plot_period_rgb(1));
  tu_int("high: black", (long)sc_plot_period_rgb(0), 0);
  tu_int("not settled: white", (long)sc_plot_period_rgb(-2), 0xffffff);
  const char *kinds[] = {"LP", "PD", "GR", "CS", "SW", "BR",
                         "TT", "CP", "GPD", "TP", "UZ", "EP"};
  size_t nk = sizeof kinds / sizeof *kinds;
  for (size_t i = 0; i < nk; i++)
    for (size_t j = i + 1; j < nk; j++) {
      int pi, pj;
      const char *ci, *cj;
      sc_plot_point_style(kinds[i], &pi, &ci, NULL);
      sc_plot_point_style(kinds[j], &pj, &cj, NULL);
      tu_true(pi != pj || strcmp(ci, cj) != 0,
              "%s and %s differ in marker or colour", kinds[i], kinds[j]);
    }
  int pt, pq;
  sc_plot_point_style("BR?", &pq, NULL, NULL);
  sc_plot_point_style("BR", &pt, NULL, NULL);
  tu_int("BR? (not located) has BR's marker", pq, pt);
  for (int k = 0; k < 24; k++)
    tu_true(strcmp(sc_plot_curve_rgb(k), sc_plot_curve_rgb(k + 1)) != 0,
            "curves %d and %d differ in colour", k, k + 1);
}

/* A title names the parameters that act: the chain's thresholds of the
 * blocks it has, bk2's phi with Coulomb friction and not gamma. */
static void test_title_params(void) {
  sc_map *m;
  sc_msg msg;
  char t[512];
  sc_map_alloc("chain", NULL, &m, &msg);
  sc_map_set_option(m, "blocks", "3", &msg);
  sc_plot_title(m, NULL, t, sizeof t);
  tu_true(strstr(t, "beta3 =") && !strstr(t, "beta4") && !strstr(t, "beta5"),
          "three blocks: beta3, not beta4 or beta5: '%s'", t);
  sc_map_set_option(m, "blocks", "5", &msg);
  sc_plot_title(m, NULL, t, sizeof t);
  tu_true(strstr(t, "beta4 =") && strstr(t, "beta5 ="),
          "five blocks: beta4 and beta5: '%s'", t);
  sc_map_free(m);
  sc_map_alloc("bk2", NULL, &m, &msg);
  sc_plot_title(m, NULL, t, sizeof t);
  tu_true(strstr(t, "phi =") && !strstr(t, "gamma"),
          "bk2, Coulomb: phi, not gamma: '%s'", t);
  sc_map_free(m);
}

int main(void) {
  test_title_params();
  test_text_box();
  test_accuracy_figure();
  test_crowded();
  test_marker_only();
  test_axis_format();
  test_styles();
  return tu_finish();
}
