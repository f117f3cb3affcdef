/* Figures' shared looks and label placement: colours and markers that
 * mean the same in every figure, tick formats for narrow ranges, and
 * text labels placed in pixels so that none overlaps another. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "slipcont/io.h"

/* Period classes of charts (a categorical table; black, grey and white
 * stay free for high, undefined and not settled). */
static const unsigned period_rgb[16] = {
    0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd, 0x8c564b,
    0xe377c2, 0x17becf, 0xbcbd22, 0x7f7f7f, 0x393b79, 0xfdd0a2,
    0x98df8a, 0xff9896, 0xc5b0d5, 0x00ffff};

unsigned sc_plot_period_rgb(int period) {
  if (period == -3) return 0xffd700u; /* invariant circle: gold */
  if (period == -2) return 0xffffffu; /* not settled: unlike every period */
  if (period == -1) return 0xd9d9d9u; /* undefined */
  if (period <= 0) return 0x000000u;  /* higher than max-period, or chaos */
  return period_rgb[(period - 1) % 16];
}

static const struct {
  const char *label, *what;
  int pt;
  const char *rgb;
} point_style[] = {
    {"LP", "fold", 9, "#2ca02c"},
    {"PD", "flip", 7, "#000000"},
    {"GR", "grazing-sliding", 5, "#9467bd"},
    {"CS", "crossing-sliding", 13, "#ff7f0e"},
    {"SW", "switching (d = d*)", 11, "#17becf"},
    {"BR", "both re-stick", 15, "#8c564b"},
    {"TT", "threshold touched", 3, "#e377c2"},
    {"IC", "itinerary change (border unknown)", 1, "#555555"},
    {"CP", "cusp", 8, "#d62728"},
    {"GPD", "generalized flip", 12, "#1f77b4"},
    {"TP", "turning point", 10, "#2ca02c"},
    {"CH", "Chenciner", 4, "#9467bd"},
    {"R1", "1:1 resonance", 5, "#d62728"},
    {"R2", "1:2 resonance", 13, "#ff7f0e"},
    {"R3", "1:3 resonance", 11, "#17becf"},
    {"R4", "1:4 resonance", 15, "#8c564b"},
    {"LPPD", "fold-flip", 3, "#e377c2"},
    {"LPNS", "fold-Neimark-Sacker", 14, "#2ca02c"},
    {"PDNS", "flip-Neimark-Sacker", 12, "#000000"},
    {"NSNS", "double Neimark-Sacker", 10, "#1f77b4"},
    {"UZ", "user point", 2, "#bcbd22"},
    {"EP", "end", 6, "#777777"},
};

void sc_plot_point_style(const char *label, int *pt, const char **rgb,
                         const char **what) {
  size_t n = sizeof point_style / sizeof point_style[0];
  /* A label may carry a suffix ("BR?": located by bisection only). */
  for (size_t k = 0; label && k < n; k++) {
    size_t len = strlen(point_style[k].label);
    if (strncmp(label, point_style[k].label, len) == 0 &&
        (label[len] == '\0' || label[len] == '?')) {
      if (pt) *pt = point_style[k].pt;
      if (rgb) *rgb = point_style[k].rgb;
      if (what) *what = point_style[k].what;
      return;
    }
  }
  if (pt) *pt = 1;
  if (rgb) *rgb = "#555555";
  if (what) *what = label ? label : "";
}

const char *sc_plot_curve_rgb(int k) {
  /* No blue: the figure's own curve is dark blue. */
  static const char *const rgb[12] = {
      "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#17becf",
      "#e377c2", "#7f7f7f", "#bcbd22", "#222222", "#637939", "#ad494a"};
  return rgb[(k < 0 ? -k : k) % 12];
}

void sc_plot_axis_format(FILE *f, const char *axis, double lo, double hi) {
  if (!isfinite(lo) || !isfinite(hi) || !(hi > lo)) return;
  double mag = fmax(fabs(lo), fabs(hi));
  /* gnuplot puts 4 to 10 ticks on a range; a twentieth is the finest
   * step it may choose, and tick labels differ when they carry one digit
   * of that step beyond the magnitude's leading one. */
  double step = (hi - lo) / 20;
  int digits = (int)ceil(log10(mag / step)) + 1;
  if (digits <= 6) return; /* gnuplot's default "% h" shows six */
  if (digits > 17) digits = 17;
  fprintf(f, "set format %s '%%.%dg'\n", axis, digits);
}

/* Width of one character in em (the font size in pixels), measured on
 * pngcairo's Sans and rounded up: see sc_plot_text_box(). */
static double char_em(unsigned char c) {
  if (c >= '0' && c <= '9') return 0.84;
  if (c == 'M' || c == 'W' || c == 'm' || c == 'w') return 1.2;
  if (c >= 'A' && c <= 'Z') return 1.0;
  if (strchr("iljtfr", c) && c) return 0.45;
  if (c >= 'a' && c <= 'z') return 0.8;
  if (c == ' ' || c == '.' || c == ',' || c == ':' || c == ';' ||
      c == '\'' || c == '(' || c == ')' || c == '[' || c == ']' ||
      c == '-' || c == '|')
    return 0.45;
  return 0.9; /* other symbols and any byte of a multibyte character */
}

#define TEXT_HEIGHT_EM 1.4 /* ascender to descender of "Hg" plus leading */
#define TEXT_PAD_PX 1.0    /* antialiasing spills about a pixel */

void sc_plot_text_box(double font, const char *text, double ax, double ay,
                      double box[4]) {
  double w = 0;
  for (const unsigned char *p = (const unsigned char *)text; *p; p++)
    w += char_em(*p);
  w *= font;
  double h = TEXT_HEIGHT_EM * font;
  box[0] = ax - TEXT_PAD_PX;
  box[1] = ay - h / 2 - TEXT_PAD_PX;
  box[2] = ax + w + TEXT_PAD_PX;
  box[3] = ay + h / 2 + TEXT_PAD_PX;
}

int sc_plot_boxes_overlap(const double a[4], const double b[4]) {
  return a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
}

/* A point's place on the picture, pixels from the bottom left. */
static double frac(double v, double lo, double hi, int lg) {
  if (lg) return (log10(v) - log10(lo)) / (log10(hi) - log10(lo));
  return (v - lo) / (hi - lo);
}

static void to_pixels(const sc_plot_frame *fr, double x, double y,
                      double *px, double *py) {
  double w = fr->width, h = fr->height;
  *px = w * (fr->left + (fr->right - fr->left) *
                            frac(x, fr->xmin, fr->xmax, fr->xlog));
  *py = h * (fr->bottom + (fr->top - fr->bottom) *
                              frac(y, fr->ymin, fr->ymax, fr->ylog));
}

/* Append @p add to the joined text @p dst: a first word equal to dst's
 * first word is written once; a text already there is not repeated. */
static void join_text(char *dst, size_t len, const char *add) {
  const char *s = strstr(dst, add);
  size_t al = strlen(add);
  if (s && (s == dst || s[-1] == ' ') && (s[al] == '\0' || s[al] == ','))
    return;
  const char *sp = strchr(dst, ' '), *asp = strchr(add, ' ');
  if (sp && asp && sp - dst == asp - add &&
      strncmp(dst, add, (size_t)(sp - dst)) == 0)
    add = asp + 1;
  size_t u = strlen(dst);
  if (u + 2 + strlen(add) < len)
    snprintf(dst + u, len - u, ", %s", add);
  else if (u + 4 < len && strcmp(dst + u - 3, "...") != 0)
    snprintf(dst + u, len - u, "...");
}

/* Far places are tried up to this many text heights away: beyond, a
 * label would be read as belonging to another point. */
#define MAX_RINGS 8

size_t sc_plot_place(const sc_plot_frame *fr, sc_plot_spot *s, size_t n) {
  double X0 = fr->width * fr->left, X1 = fr->width * fr->right;
  double Y0 = fr->height * fr->bottom, Y1 = fr->height * fr->top;
  double m = fr->marker;
  for (size_t i = 0; i < n; i++) {
    to_pixels(fr, s[i].x, s[i].y, &s[i].px, &s[i].py);
    s[i].placed = 1;
    s[i].into = (int)i;
    s[i].leader = 0;
    s[i].ax = s[i].ay = NAN;
    for (int k = 0; k < 4; k++) s[i].box[k] = NAN;
  }
  /* Points under one marker share a label: the first one's. */
  for (size_t i = 0; i < n; i++) {
    if (!s[i].text[0]) { /* a marker only */
      s[i].placed = 0;
      s[i].into = -1;
      continue;
    }
    for (size_t j = 0; j < i; j++)
      if (s[j].placed == 1 && fabs(s[i].px - s[j].px) <= 2 * m &&
          fabs(s[i].py - s[j].py) <= 2 * m) {
        join_text(s[j].text, sizeof s[j].text, s[i].text);
        s[i].placed = 0;
        s[i].into = (int)j;
        break;
      }
  }
  static const int dir[8][2] = {{1, 1}, {-1, 1}, {1, -1}, {-1, -1},
                                {1, 0}, {-1, 0}, {0, 1},  {0, -1}};
  size_t left_out = 0;
  for (size_t i = 0; i < n; i++) {
    if (s[i].placed != 1) continue;
    double b0[4];
    sc_plot_text_box(fr->font, s[i].text, 0, 0, b0);
    double w = b0[2] - b0[0], h = b0[3] - b0[1];
    int found = 0;
    for (int ring = 0; ring < MAX_RINGS && !found; ring++) {
      double r = m + 2 + ring * h;
      for (int d = 0; d < 8 && !found; d++) {
        double bx = dir[d][0] > 0   ? s[i].px + r
                    : dir[d][0] < 0 ? s[i].px - r - w
                                    : s[i].px - w / 2;
        double by = dir[d][1] > 0   ? s[i].py + (dir[d][0] ? r / 2 : r)
                    : dir[d][1] < 0 ? s[i].py - (dir[d][0] ? r / 2 : r) - h
                                    : s[i].py - h / 2;
        double box[4];
        sc_plot_text_box(fr->font, s[i].text, bx - b0[0], by - b0[1], box);
        if (box[0] < X0 || box[2] > X1 || box[1] < Y0 || box[3] > Y1)
          continue;
        int free = 1;
        for (size_t j = 0; j < n && free; j++) {
          double mk[4] = {s[j].px - m, s[j].py - m, s[j].px + m,
                          s[j].py + m};
          if (sc_plot_boxes_overlap(box, mk)) free = 0;
          if (j < i && s[j].placed == 1 && sc_plot_boxes_overlap(box, s[j].box))
            free = 0;
        }
        if (!free) continue;
        found = 1;
        s[i].ax = bx - b0[0];
        s[i].ay = by - b0[1];
        memcpy(s[i].box, box, sizeof box);
        s[i].leader = ring > 0;
      }
    }
    if (!found) {
      s[i].placed = -1;
      left_out++;
    }
  }
  return left_out;
}

void sc_plot_frame_write(FILE *f, const sc_plot_frame *fr) {
  fprintf(f, "set lmargin at screen %.6f\nset rmargin at screen %.6f\n",
          fr->left, fr->right);
  fprintf(f, "set bmargin at screen %.6f\nset tmargin at screen %.6f\n",
          fr->bottom, fr->top);
  fprintf(f, "set xrange [%.17g:%.17g]\nset yrange [%.17g:%.17g]\n",
          fr->xmin, fr->xmax, fr->ymin, fr->ymax);
  if (fr->xlog) fputs("set logscale x\n", f);
  else sc_plot_axis_format(f, "x", fr->xmin, fr->xmax);
  if (fr->ylog) fputs("set logscale y\n", f);
  else sc_plot_axis_format(f, "y", fr->ymin, fr->ymax);
}

/* Tags of placed labels and leaders: above those a script sets itself. */
#define LABEL_TAG0 1000

void sc_plot_labels_write(FILE *f, const sc_plot_frame *fr,
                          const sc_plot_spot *s, size_t n, const char *rgb) {
  double W = fr->width, H = fr->height;
  for (size_t i = 0; i < n; i++) {
    if (s[i].placed != 1) continue;
    fprintf(f, "set label %zu ", LABEL_TAG0 + i);
    sc_plot_quote(f, s[i].text);
    fprintf(f,
            " at screen %.6f, screen %.6f left font 'Sans,%g' tc rgb '%s' "
            "noenhanced front\n# box %.1f %.1f %.1f %.1f\n",
            s[i].ax / W, s[i].ay / H, fr->font, rgb, s[i].box[0],
            s[i].box[1], s[i].box[2], s[i].box[3]);
    if (s[i].leader) {
      /* to the nearest point of the box */
      double tx = fmin(fmax(s[i].px, s[i].box[0]), s[i].box[2]);
      double ty = fmin(fmax(s[i].py, s[i].box[1]), s[i].box[3]);
      fprintf(f,
              "set arrow %zu from screen %.6f, screen %.6f to screen %.6f, "
              "screen %.6f nohead lw 0.6 lc rgb '#888888' back\n",
              LABEL_TAG0 + i, s[i].px / W, s[i].py / H, tx / W, ty / H);
    }
  }
}
