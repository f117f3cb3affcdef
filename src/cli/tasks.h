/* The tasks of the `slipcont` program, and what a task may use while it
 * runs.
 *
 * Registration contract (how to add a task kind, e.g. `chart`):
 *
 * 1. Write src/cli/task_chart.c defining one constant
 *
 *        const sc_cli_task sc_cli_task_chart = {
 *            .type = {.kind = "chart", .doc = "...", .keys = chart_keys,
 *                     .nkeys = sizeof chart_keys / sizeof chart_keys[0],
 *                     .check = chart_check},
 *            .outputs = "chart.csv (x,y,period), chart.gp/png",
 *            .run = chart_run,
 *        };
 *
 *    - `.type.kind` is the value of `[task] kind` (it may contain '-',
 *      e.g. "fixed-point"; the C name uses '_').
 *    - `.type.keys` is the one table of the task's `[task]` keys (name,
 *      type, required or default, range, doc; io.h sc_key_info).  Scene
 *      validation, `slipcont help KIND`, `slipcont keys --markdown` and
 *      docs/guide.md are all generated from it, so a key exists nowhere
 *      else.  Do not list `kind` itself.
 *    - `.type.check` (may be NULL) checks relations between keys once
 *      each key has passed its own check (`keep <= iterations`, `from`
 *      inside the range of the swept parameter: take ranges from the
 *      model's table with sc_param_check(), never hard-code them) and
 *      reports with sc_scene_fail_key() so that the message names the
 *      file, line and key.  It must not compute or write anything.
 *    - `.run` does the work (see sc_cli_run below): it writes every file
 *      through sc_cli_open()/sc_cli_commit() (atomic), writes
 *      summary.txt with sc_cli_summary_begin(), declares each gnuplot
 *      script with sc_cli_add_plot() (main renders them afterwards when
 *      `[output] plot = yes`), prints to stderr only through
 *      sc_cli_note() and a progress bar (progress.h), stops cleanly when
 *      sc_cli_interrupted() says so, and returns SC_OK or an error
 *      status with r->msg filled (the program then exits with status 1).
 * 2. Add one line `X(chart)` to SC_CLI_TASK_LIST in src/cli/tasks.c.
 * 3. Add src/cli/task_chart.c to src/cli/sources.cmake.
 * 4. Regenerate the key tables of docs/guide.md
 *    (`slipcont keys --markdown`, between the markers) and describe the
 *    task's outputs there; the test `cli_guide_keys` compares them.
 */
#ifndef SC_CLI_TASKS_H
#define SC_CLI_TASKS_H

#include <stddef.h>
#include <stdio.h>

#include "slipcont/io.h"
#include "slipcont/map.h"

/** Most plots one task may declare. */
#define SC_CLI_MAXPLOTS 8

/** Everything a task may use while it runs. */
typedef struct sc_cli_run {
  const sc_scene *scene; /**< the validated scene */
  sc_map *map;           /**< its model instance (sc_scene_map()) */
  const char *dir;       /**< output folder: exists and is writable */
  int quiet;             /**< 1: no progress or notes on stderr */
  sc_msg *msg;           /**< where run() explains a failure */
  size_t nplots;         /**< plots declared so far */
  char plot_script[SC_CLI_MAXPLOTS][64]; /**< "sweep.gp" */
  char plot_png[SC_CLI_MAXPLOTS][64];    /**< "sweep.png" */
  char written[1024];    /**< names of the files written, for the notes */
  long stop_after_rows;  /**< chart: stop with a checkpoint after this
                              many rows, as a kill would (0: never); the
                              option --stop-after-rows, for tests */
} sc_cli_run;

/** A task kind of the program: see the contract above. */
typedef struct sc_cli_task {
  sc_task_type type;   /**< kind, doc, keys, check (io.h) */
  const char *outputs; /**< the files it writes, one line */
  int (*run)(sc_cli_run *r);
} sc_cli_task;

/**
 * The graph of f^n over [from, to] on @p steps points into the CSV file
 * @p name (columns d,f,itinerary), with an empty line wherever the
 * itinerary changes so that gnuplot does not join the pieces across a
 * jump.  Points where f^n is undefined are left out (and break the line).
 * Used by the fixed-point and branch tasks (figs 5.9-5.11).
 */
int sc_cli_write_map_graph(sc_cli_run *r, const char *name, int n,
                           double from, double to, size_t steps);

/** Number of registered tasks; sc_cli_task_get(i) lists them. */
size_t sc_cli_task_count(void);
/** Registered task @p i, or NULL. */
const sc_cli_task *sc_cli_task_get(size_t i);
/** Registered task by kind, or NULL. */
const sc_cli_task *sc_cli_task_find(const char *kind);
/** The scene-level descriptions of all tasks, for sc_scene_options. */
const sc_task_type *const *sc_cli_task_types(size_t *n);

/** Open `dir/name` atomically (sc_file_open()); message into r->msg.
 * The temporary is unlinked if a signal ends the process early. */
int sc_cli_open(sc_cli_run *r, const char *name, sc_file **f);
/** Commit a file opened with sc_cli_open() and remember its name. */
int sc_cli_commit(sc_cli_run *r, const char *name, sc_file *f);

/**
 * Open summary.txt and write its head: the scene, the overrides, and
 * every effective setting of every section (defaults included).  The task
 * then writes its findings under "results:" and commits with
 * sc_cli_commit(r, "summary.txt", f).
 */
int sc_cli_summary_begin(sc_cli_run *r, sc_file **f);

/** Declare a gnuplot script (already written) and the PNG it makes. */
int sc_cli_add_plot(sc_cli_run *r, const char *script, const char *png);

/** A note on stderr ("slipcont: ...") unless r->quiet. */
void sc_cli_note(const sc_cli_run *r, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/** Seconds a task has, after SIGINT/SIGTERM, to return by itself. */
#define SC_CLI_STOP_GRACE_S 1

/**
 * The one signal mechanism of the program.  1 once SIGINT or SIGTERM has
 * arrived during a run (main installs the handler with
 * sc_cli_catch_signals() before calling run()).  A task checks it in its
 * loops (and progress callbacks return it, so that library loops stop);
 * when set it aborts the files it was writing (sc_file_abort(): no
 * temporary is left) and returns SC_ECALLBACK with "interrupted" in
 * r->msg.  A task that has not returned SC_CLI_STOP_GRACE_S seconds
 * after the signal (a library call that cannot be stopped), or a second
 * signal, ends the process at once with status 128 + the signal number,
 * after unlinking the temporaries opened with sc_cli_open(): files are
 * left complete or not at all.  Progress bars: src/cli/progress.h.
 */
int sc_cli_interrupted(void);
/** Install the SIGINT/SIGTERM handler behind sc_cli_interrupted(). */
void sc_cli_catch_signals(void);
/** The task has returned: no more forced end (main calls it). */
void sc_cli_signals_done(void);

/** Replace ',' by ';' and control characters by ' ' so that @p text can
 * be one CSV field; returns @p text. */
char *sc_cli_csv_text(char *text);

#endif
