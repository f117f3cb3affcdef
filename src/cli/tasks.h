/* The tasks of the `slipcont` program, the one run skeleton they share,
 * and what a task may use while it runs.
 *
 * Registration contract (how to add a task kind, e.g. `chart`):
 *
 * 1. Write src/cli/task_chart.c defining its job (a struct holding the
 *    settings read from the scene and what one step hands to the next)
 *    and one constant
 *
 *        const sc_cli_task sc_cli_task_chart = {
 *            .type = {.kind = "chart", .doc = "...", .keys = chart_keys,
 *                     .nkeys = sizeof chart_keys / sizeof chart_keys[0],
 *                     .check = chart_check},
 *            .outputs = "chart.csv (x,y,period), chart.gp/png",
 *            .job_size = sizeof(chart_job),
 *            .prepare = chart_prepare, .compute = chart_compute,
 *            .write = chart_write, .summary = chart_summary,
 *            .plots = chart_plots, .report = chart_report,
 *            .release = chart_release,
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
 *    - The steps (sc_cli_task below) do the work; sc_cli_task_run() is
 *      the one driver that runs them.  Every file is written through
 *      sc_cli_open()/sc_cli_commit() (atomic; the driver aborts what a
 *      failed step left open), gnuplot scripts through
 *      sc_cli_plot_begin()/sc_cli_plot_end() (main renders them
 *      afterwards when `[output] plot = yes`), stderr only through
 *      sc_cli_note() and a progress bar (progress.h).  Long loops stop
 *      when sc_cli_interrupted() says so (sc_cli_stop()); a step returns
 *      SC_OK or an error status with r->msg filled (the program then
 *      exits with status 1).
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
/** Most files one task may have open at a time. */
#define SC_CLI_MAXOPEN 8

/** Everything a task may use while it runs. */
typedef struct sc_cli_run {
  const sc_scene *scene; /**< the validated scene */
  sc_map *map;           /**< its model instance (sc_scene_map()) */
  const char *dir;       /**< output folder: exists and is writable */
  int quiet;             /**< 1: no progress or notes on stderr */
  sc_msg *msg;           /**< where a step explains a failure */
  size_t nplots;         /**< plots declared so far */
  char plot_script[SC_CLI_MAXPLOTS][64]; /**< "sweep.gp" */
  char plot_png[SC_CLI_MAXPLOTS][64];    /**< "sweep.png" */
  char written[1024];    /**< names of the files written, for the notes */
  sc_file *open[SC_CLI_MAXOPEN]; /**< files opened, not yet committed */
  size_t nopen;          /**< entries of open[] */
  int compute_only;      /**< set by prepare in a process that only helps
                              compute (an MPI rank other than 0): the
                              driver then runs only compute and release */
  long stop_after_rows;  /**< chart: stop with a checkpoint after this
                              many rows, as a kill would (0: never); the
                              option --stop-after-rows, for tests */
  const char *interrupt_before; /**< a step's name: the driver raises
                              SIGINT just before it (NULL: never); the
                              option --interrupt-before, for tests */
} sc_cli_run;

/**
 * A task kind of the program: its keys and the steps of its run.
 *
 * The one run skeleton.  sc_cli_task_run() allocates the job (job_size
 * bytes, zeroed) and calls the steps in this order, each at most once;
 * any step may be NULL:
 *
 *   prepare  read the scene's settings into the job, allocate; no file
 *   compute  the computation (a long one may stream its data files)
 *   write    the data files from what compute kept in the job
 *   summary  the findings under "results:" in summary.txt: the driver
 *            opens the file, writes its head (the scene, every setting),
 *            calls this with the stream, and commits
 *   plots    the gnuplot scripts (sc_cli_plot_begin()/sc_cli_plot_end())
 *   report   the closing notes on stderr, and the run's status: a
 *            failure found by compute whose files were still written
 *            (orbit: the map is undefined at an iterate) is returned here
 *   release  free the job's memory and restore the map; called exactly
 *            once whatever happened, also on a job that prepare filled
 *            only in part (pointers are NULL until set)
 *
 * Before each step the driver checks sc_cli_interrupted(): after a
 * SIGINT or SIGTERM no further step runs and the run fails with
 * "interrupted".  The first step that fails ends the run; the driver then
 * aborts every file still open (sc_file_abort(): no temporary is left)
 * and returns its status.
 */
typedef struct sc_cli_task {
  sc_task_type type;   /**< kind, doc, keys, check (io.h) */
  const char *outputs; /**< the files it writes, one line */
  size_t job_size;     /**< bytes of the task's job (0: none) */
  int (*prepare)(sc_cli_run *r, void *job);
  int (*compute)(sc_cli_run *r, void *job);
  int (*write)(sc_cli_run *r, void *job);
  int (*summary)(sc_cli_run *r, void *job, FILE *f);
  int (*plots)(sc_cli_run *r, void *job);
  int (*report)(sc_cli_run *r, void *job);
  void (*release)(sc_cli_run *r, void *job);
} sc_cli_task;

/** The names of the steps in their order, "prepare" to "report" (the
 * names --interrupt-before accepts; release always runs and is not
 * listed); sets @p n. */
const char *const *sc_cli_step_names(size_t *n);

/**
 * The one driver: run task @p t on @p r (see sc_cli_task).  Returns
 * SC_OK, the status of the step that failed (message in r->msg),
 * SC_ECALLBACK "interrupted" after a signal, SC_ENOMEM for the job, or
 * SC_EINTERNAL when a task ends with a file still open.
 */
int sc_cli_task_run(const sc_cli_task *t, sc_cli_run *r);

/** For a task's check: `[task] from` and `to` inside the range of the
 * model parameter named by `[task] parameter` (the model's table, with
 * sc_param_check()); the message names the key's line. */
int sc_cli_check_param_ends(const sc_scene *s, sc_msg *msg);
/** The same for the @p n `[task]` keys @p ends (a curve's box: "x-from",
 * "x-to") and the parameter named by the key @p param ("x"). */
int sc_cli_check_param_keys(const sc_scene *s, const char *param,
                            const char *const *ends, int n, sc_msg *msg);

/** The next blank-separated word of a key's list at *q, copied into
 * buf[0..len) (cut to fit) with *q moved past it.  Returns the word's
 * full length, so that a caller can refuse one that did not fit; 0 at
 * the end of the list. */
size_t sc_cli_next_word(const char **q, char *buf, size_t len);

/** The most values `marks` may list. */
#define SC_CLI_MAXMARKS 100

/** For the branch and curve tasks: `[task] marks`, values of parameter
 * @p pname separated by blanks, into out[0..*n) (at most
 * SC_CLI_MAXMARKS; *n = 0 without the key); each a finite number in the
 * parameter's range (the model's table) and inside [lo, hi] (the
 * interval continued), else a message naming the value and the key's
 * line. */
int sc_cli_marks(const sc_scene *s, const char *pname, double lo, double hi,
                 double *out, size_t *n, sc_msg *msg);

/**
 * The graph of f^n over [from, to] on @p steps points into the CSV file
 * @p name (columns d,f,itinerary), with an empty line wherever the
 * itinerary changes so that gnuplot does not join the pieces across a
 * jump.  Points where f^n is undefined are left out (and break the line).
 * Used by the fixed-point and branch tasks (figs 5.9-5.11).
 */
int sc_cli_write_map_graph(sc_cli_run *r, const char *name, int n,
                           double from, double to, size_t steps);

/* ------------------------------------------------------------------ */
/* `show`: which number of an n-component state a plot draws (show.c)   */

/** sc_cli_show()'s value for `show = norm`: the Euclidean norm. */
#define SC_CLI_SHOW_NORM (-1)

/** The `show` key as a task's key table lists it (sweep, branch): put
 * SC_CLI_SHOW_KEY in the table, read it with sc_cli_show() in the task's
 * check (which refuses a bad value naming the key's line) and in
 * prepare. */
#define SC_CLI_SHOW_KEY                                                     \
  {"show", SC_KEY_TEXT, 0, "1", 0, 0, 0, 0, NULL,                           \
   "what a plot draws of a state of n > 1 components: a component, by "    \
   "its index 1..n or its name (y), or norm (the Euclidean norm); CSV "     \
   "files keep every component"}

/** `[task] show` of @p s for the model of @p s: *show = the component's
 * index from 0, or SC_CLI_SHOW_NORM.  Returns SC_OK, or SC_EINVAL with a
 * message naming the key's line and the valid values. */
int sc_cli_show(const sc_scene *s, int *show, sc_msg *msg);

/** The axis label of what @p show draws of a state of @p m: the
 * component's plot label ("y"), or "|x|" (the state name between bars)
 * for the norm; a one-dimensional model's state label.  Returns @p buf. */
const char *sc_cli_show_label(const sc_map *m, int show, char *buf,
                              size_t len);

/** The gnuplot `using` expression of what @p show draws when the @p n
 * components of a state are the CSV columns col0 .. col0 + n - 1: the
 * column's number ("3"), or "(sqrt($2**2 + $3**2))" for the norm; either
 * goes after "using 1:".  Returns @p buf. */
const char *sc_cli_show_using(int show, size_t n, int col0, char *buf,
                              size_t len);

/** The value @p show draws of the state @p x (n values). */
double sc_cli_show_value(int show, const double *x, size_t n);

/** Number of registered tasks; sc_cli_task_get(i) lists them. */
size_t sc_cli_task_count(void);
/** Registered task @p i, or NULL. */
const sc_cli_task *sc_cli_task_get(size_t i);
/** Registered task by kind, or NULL. */
const sc_cli_task *sc_cli_task_find(const char *kind);
/** The scene-level descriptions of all tasks, for sc_scene_options. */
const sc_task_type *const *sc_cli_task_types(size_t *n);

/** Open `dir/name` atomically (sc_file_open()); message into r->msg.
 * The file is open until sc_cli_commit() or sc_cli_abort(); the driver
 * aborts it if a step fails.  The temporary is unlinked if a signal ends
 * the process early. */
int sc_cli_open(sc_cli_run *r, const char *name, sc_file **f);
/** Commit a file opened with sc_cli_open() (freed in every case) and
 * add @p name to the files named in the closing note (NULL: not named,
 * e.g. a checkpoint that is removed at the end). */
int sc_cli_commit(sc_cli_run *r, const char *name, sc_file *f);
/** Abort a file opened with sc_cli_open(); NULL is accepted. */
void sc_cli_abort(sc_cli_run *r, sc_file *f);

/**
 * Open summary.txt and write its head: the scene, the overrides, and
 * every effective setting of every section (defaults included).  The
 * driver calls it for the summary step; the task's summary step writes
 * its findings under "results:".
 */
int sc_cli_summary_begin(sc_cli_run *r, sc_file **f);

/** Open the gnuplot script STEM.gp and write its head (sc_plot_head())
 * for STEM.png with @p title and the axis labels. */
int sc_cli_plot_begin(sc_cli_run *r, const char *stem, const char *title,
                      const char *xlabel, const char *ylabel, sc_file **gp);
/** Commit STEM.gp opened by sc_cli_plot_begin() and declare it with
 * STEM.png (sc_cli_add_plot()). */
int sc_cli_plot_end(sc_cli_run *r, const char *stem, sc_file *gp);

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
 * sc_cli_catch_signals() before calling sc_cli_task_run()).  The driver
 * checks it between steps; a step checks it in its loops (sc_cli_stop();
 * progress callbacks return it, so that library loops stop) and returns
 * SC_ECALLBACK with "interrupted" in r->msg; the driver aborts the files
 * still open (no temporary is left).  A task that has not returned
 * SC_CLI_STOP_GRACE_S seconds after the signal (a library call that
 * cannot be stopped), or a second signal, ends the process at once with
 * status 128 + the signal number, after unlinking the temporaries opened
 * with sc_cli_open(): files are left complete or not at all.  Progress
 * bars: src/cli/progress.h.
 */
int sc_cli_interrupted(void);
/** SC_OK, or SC_ECALLBACK with "interrupted" in r->msg once a signal has
 * arrived: `if ((st = sc_cli_stop(r))) return st;` in a step's loop. */
int sc_cli_stop(sc_cli_run *r);
/** Install the SIGINT/SIGTERM handler behind sc_cli_interrupted(). */
void sc_cli_catch_signals(void);
/** The task has returned: no more forced end (main calls it). */
void sc_cli_signals_done(void);

/* ------------------------------------------------------------------ */
/* The files a scene names besides itself (inputs.c), each opened with
 * sc_input_open() (a regular file of bounded size, never blocking), in a
 * task's check so that bad ones are refused before anything is made. */

/** Split the CSV line @p line in place (its line end cut) into at most
 * @p max fields @p f; returns their number. */
int sc_cli_csv_split(char *line, char **f, int max);

/** A row of a branch task's points.csv. */
typedef struct {
  char label[16];  /**< LP, PD, GR, ..., EP */
  char param[64];  /**< the parameter continued */
  double value, d; /**< its value and the orbit point (finite) */
  int period;      /**< in [1, 4096] */
  char border[64]; /**< the border of a border point ("" if none, or no
                        such column) */
  char method[16]; /**< how it was located ("newton", "degenerate", ...;
                        "" if none, or no such column) */
} sc_cli_points_row;

/** The row named by @p spec, "FILE:N" (N = 1 is the first row after the
 * header), its columns found by the header's names.  Returns SC_OK, or
 * an error status with the reason, naming the file, in @p why. */
int sc_cli_points_row_read(const char *spec, sc_cli_points_row *row,
                           char *why, size_t len);

/** The first line of the file @p path (what: "the overlay", for
 * messages), without its line end, into @p line.  Returns SC_OK, or an
 * error status with `PATH: reason` in @p msg. */
int sc_cli_read_head(const char *path, const char *what, char *line,
                     size_t len, sc_msg *msg);

/**
 * The one rule for every text the program shows (messages and notes on
 * stderr, summary.txt, CSV notes): the library's messages start with the
 * function that failed ("sc_shoot_solve: ...", for programmers); a user
 * is told what and where in the terms of the scene.  This removes every
 * such function name ("sc_NAME: ") from @p text in place and returns it.
 * main, sc_cli_note(), the summary step and sc_cli_csv_text() apply it,
 * so a task need not.
 */
/** Write the state @p x of @p n components as "(a, b, ...)" in full
 * precision, as the n-dimensional tasks' summaries show it. */
void sc_cli_put_state(FILE *f, const double *x, size_t n);

char *sc_cli_user_text(char *text);

/** Replace ',' by ';' and control characters by ' ' so that @p text can
 * be one CSV field (after sc_cli_user_text()); returns @p text. */
char *sc_cli_csv_text(char *text);

#endif
