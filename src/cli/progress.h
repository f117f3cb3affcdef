/* A progress bar on stderr: percentage, rate and time left, redrawn at
 * most a few times a second, shown only when stderr is a terminal and the
 * user did not ask for --quiet. */
#ifndef SC_CLI_PROGRESS_H
#define SC_CLI_PROGRESS_H

#include <stdio.h>

typedef struct {
  FILE *out;         /* stderr, or NULL when the bar is off */
  const char *unit;  /* "points" */
  long total;        /* work items in all */
  long start_done;   /* items already done when the bar started (resume) */
  long done;         /* items done, start_done included */
  double t0;         /* monotonic seconds at the start */
  double last_draw;  /* monotonic seconds of the last redraw */
  int width;         /* characters of the bar itself */
} sc_progress;

/* 1 when a bar should be drawn: stderr is a terminal and not quiet. */
int sc_progress_wanted(int quiet);

/* Start a bar over @p total items of which @p done are already done
 * (a resumed run); @p enabled 0 makes every call a no-op. */
void sc_progress_start(sc_progress *p, const char *unit, long total,
                       long done, int enabled);

/* @p done items are now complete; redraws when enough time has passed.
 * Cheap enough to call after every item. */
void sc_progress_update(sc_progress *p, long done);

/* Draw the final state and end the line. */
void sc_progress_finish(sc_progress *p);

/* Seconds of a monotonic clock. */
double sc_progress_now(void);

#endif
