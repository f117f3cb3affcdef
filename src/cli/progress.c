/* Progress bar on stderr (see progress.h). */
#define _POSIX_C_SOURCE 200809L

#include "cli/progress.h"

#include <time.h>
#include <unistd.h>

/* Redraw interval in seconds: often enough to look alive, rarely enough
 * to cost nothing next to the work. */
#define REDRAW_S 0.2

double sc_progress_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int sc_progress_wanted(int quiet) {
  return !quiet && isatty(STDERR_FILENO);
}

/* h:mm:ss, or mm:ss under an hour. */
static void clock_text(char *buf, size_t len, double s) {
  if (!(s >= 0) || s > 1e7) {
    snprintf(buf, len, "--:--");
    return;
  }
  long t = (long)(s + 0.5);
  if (t >= 3600)
    snprintf(buf, len, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
  else
    snprintf(buf, len, "%02ld:%02ld", t / 60, t % 60);
}

static void draw(sc_progress *p, double now, int final) {
  double frac = p->total > 0 ? (double)p->done / (double)p->total : 1;
  if (frac > 1) frac = 1;
  int fill = (int)(frac * p->width);
  double el = now - p->t0;
  long run = p->done - p->start_done; /* items of this run */
  double rate = el > 0 ? (double)run / el : 0;
  char left[32], spent[32];
  clock_text(spent, sizeof spent, el);
  if (final)
    clock_text(left, sizeof left, 0);
  else
    clock_text(left, sizeof left,
               rate > 0 ? (double)(p->total - p->done) / rate : -1);
  fputc('\r', p->out);
  fputc('[', p->out);
  for (int i = 0; i < p->width; i++) fputc(i < fill ? '#' : '.', p->out);
  fprintf(p->out, "] %5.1f%% %ld/%ld %s, %.3g %s/s, %s spent, %s left\033[K",
          100 * frac, p->done, p->total, p->unit, rate, p->unit, spent, left);
  if (final) fputc('\n', p->out);
  fflush(p->out);
  p->last_draw = now;
}

void sc_progress_start(sc_progress *p, const char *unit, long total,
                       long done, int enabled) {
  p->out = enabled ? stderr : NULL;
  p->unit = unit;
  p->total = total;
  p->start_done = p->done = done;
  p->t0 = p->last_draw = sc_progress_now();
  p->width = 30;
  if (p->out) draw(p, p->t0, 0);
}

void sc_progress_update(sc_progress *p, long done) {
  if (!p->out) return;
  p->done = done;
  double now = sc_progress_now();
  if (now - p->last_draw >= REDRAW_S) draw(p, now, 0);
}

void sc_progress_finish(sc_progress *p) {
  if (!p->out) return;
  draw(p, sc_progress_now(), 1);
  p->out = NULL;
}
