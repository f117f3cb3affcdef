/* The one run skeleton (sc_cli_task_run: the steps of every task in
 * order), and what a task may use while it runs: atomic files named in
 * the notes, the head of summary.txt, plot scripts, notes, signals. */
#define _POSIX_C_SOURCE 200809L

#include <ctype.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli/tasks.h"

/* ------------------------------------------------------------------ */
/* Signals: the one mechanism of the program (see tasks.h).              */

/* Only flags of type volatile sig_atomic_t may be written by a handler. */
static volatile sig_atomic_t interrupted;
static volatile sig_atomic_t exit_code = 1;

/* The temporaries opened through sc_cli_open(), newest last (a ring):
 * when the process must end before the task returns, they are unlinked
 * so that no half-written file is left.  A slot whose file was committed
 * or aborted names a path that no longer exists; unlinking it again is
 * harmless. */
#define TRACKED 64
static char tracked[TRACKED][4096];
static volatile sig_atomic_t ntracked;

static void track(const sc_file *f) {
  const char *p = sc_file_temp_path(f);
  size_t n = strlen(p);
  if (n >= sizeof tracked[0]) return; /* longer paths are refused earlier */
  int k = ntracked % TRACKED;
  tracked[k][0] = '\0';
  memcpy(tracked[k], p, n + 1);
  ntracked = ntracked + 1;
}

/* Async-signal-safe: unlink(), write() and _exit() only. */
static void end_now(void) {
  int n = ntracked < TRACKED ? ntracked : TRACKED;
  for (int k = 0; k < n; k++)
    if (tracked[k][0]) unlink(tracked[k]);
  static const char note[] = "slipcont: stopped by a signal (unfinished "
                             "files removed; the files written are "
                             "complete)\n";
  ssize_t w = write(STDERR_FILENO, note, sizeof note - 1);
  (void)w;
  _exit(exit_code);
}

static void on_signal(int sig) {
  if (interrupted) end_now(); /* a second signal: at once */
  interrupted = 1;
  exit_code = 128 + sig;
  alarm(SC_CLI_STOP_GRACE_S);
}

static void on_alarm(int sig) {
  (void)sig;
  if (interrupted) end_now();
}

int sc_cli_interrupted(void) { return interrupted != 0; }

void sc_cli_catch_signals(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  sa.sa_handler = on_alarm;
  sigaction(SIGALRM, &sa, NULL);
}

void sc_cli_signals_done(void) {
  /* The task has returned: its files are complete or removed. */
  alarm(0);
}

/* ------------------------------------------------------------------ */

int sc_cli_stop(sc_cli_run *r) {
  return sc_cli_interrupted() ? sc_fail(r->msg, SC_ECALLBACK, "interrupted")
                              : SC_OK;
}

/* ------------------------------------------------------------------ */
/* Files: every one open is listed in r->open until committed or aborted. */

int sc_cli_open(sc_cli_run *r, const char *name, sc_file **f) {
  *f = NULL;
  if (r->nopen == SC_CLI_MAXOPEN)
    return sc_fail(r->msg, SC_EINTERNAL, "%s: more than %d files open",
                   name, SC_CLI_MAXOPEN);
  int st = sc_file_open(r->dir, name, f, r->msg);
  if (st) return st;
  track(*f);
  r->open[r->nopen++] = *f;
  return SC_OK;
}

/* Take @p f off the list of open files. */
static void forget(sc_cli_run *r, const sc_file *f) {
  for (size_t i = 0; i < r->nopen; i++)
    if (r->open[i] == f) {
      r->open[i] = r->open[--r->nopen];
      return;
    }
}

int sc_cli_commit(sc_cli_run *r, const char *name, sc_file *f) {
  forget(r, f);
  int st = sc_file_commit(f, r->msg);
  if (st == SC_OK && name) {
    size_t n = strlen(r->written);
    snprintf(r->written + n, sizeof r->written - n, "%s%s", n ? ", " : "",
             name);
  }
  return st;
}

void sc_cli_abort(sc_cli_run *r, sc_file *f) {
  if (!f) return;
  forget(r, f);
  sc_file_abort(f);
}

int sc_cli_plot_begin(sc_cli_run *r, const char *stem, const char *title,
                      const char *xlabel, const char *ylabel,
                      sc_file **gp) {
  char script[64], png[64];
  snprintf(script, sizeof script, "%s.gp", stem);
  snprintf(png, sizeof png, "%s.png", stem);
  int st = sc_cli_open(r, script, gp);
  if (st == SC_OK)
    sc_plot_head(sc_file_stream(*gp), png, title, xlabel, ylabel);
  return st;
}

int sc_cli_plot_end(sc_cli_run *r, const char *stem, sc_file *gp) {
  char script[64], png[64];
  snprintf(script, sizeof script, "%s.gp", stem);
  snprintf(png, sizeof png, "%s.png", stem);
  int st = sc_cli_commit(r, script, gp);
  return st ? st : sc_cli_add_plot(r, script, png);
}

/* ------------------------------------------------------------------ */
/* The one run skeleton (tasks.h).                                       */

enum { STEP_PREPARE, STEP_COMPUTE, STEP_WRITE, STEP_SUMMARY, STEP_PLOTS,
       STEP_REPORT, NSTEPS };

static const char *const step_names[NSTEPS] = {
    "prepare", "compute", "write", "summary", "plots", "report"};

const char *const *sc_cli_step_names(size_t *n) {
  *n = NSTEPS;
  return step_names;
}

/* The summary step: head by the driver, findings by the task. */
static int summary_step(const sc_cli_task *t, sc_cli_run *r, void *job) {
  sc_file *f = NULL;
  int st = sc_cli_summary_begin(r, &f);
  if (st) return st;
  /* The findings pass through sc_cli_user_text() as every text shown. */
  char *text = NULL;
  size_t len = 0;
  FILE *mem = open_memstream(&text, &len);
  if (!mem) return sc_fail(r->msg, SC_ENOMEM, "summary: out of memory");
  st = t->summary(r, job, mem);
  if (fclose(mem) && !st)
    st = sc_fail(r->msg, SC_ENOMEM, "summary: out of memory");
  if (!st) fputs(sc_cli_user_text(text), sc_file_stream(f));
  free(text);
  return st ? st : sc_cli_commit(r, "summary.txt", f);
}

static int run_step(const sc_cli_task *t, sc_cli_run *r, void *job, int k) {
  switch (k) {
  case STEP_PREPARE: return t->prepare ? t->prepare(r, job) : SC_OK;
  case STEP_COMPUTE: return t->compute ? t->compute(r, job) : SC_OK;
  case STEP_WRITE: return t->write ? t->write(r, job) : SC_OK;
  case STEP_SUMMARY: return t->summary ? summary_step(t, r, job) : SC_OK;
  case STEP_PLOTS: return t->plots ? t->plots(r, job) : SC_OK;
  default: return t->report ? t->report(r, job) : SC_OK;
  }
}

int sc_cli_task_run(const sc_cli_task *t, sc_cli_run *r) {
  void *job = calloc(1, t->job_size ? t->job_size : 1);
  if (!job) return sc_fail(r->msg, SC_ENOMEM, "%s: out of memory", t->type.kind);
  int st = SC_OK;
  for (int k = 0; k < NSTEPS && !st; k++) {
    if (r->interrupt_before && strcmp(r->interrupt_before, step_names[k]) == 0)
      raise(SIGINT); /* the test hook: as if the user pressed ^C now */
    if (k > STEP_COMPUTE && r->compute_only) break;
    st = sc_cli_stop(r);
    if (!st) st = run_step(t, r, job, k);
  }
  if (!st && r->nopen) /* a task's bug: say which file */
    st = sc_fail(r->msg, SC_EINTERNAL, "%s: %s was left open",
                 t->type.kind, sc_file_temp_path(r->open[0]));
  while (r->nopen) sc_cli_abort(r, r->open[r->nopen - 1]);
  if (t->release) t->release(r, job);
  free(job);
  return st;
}

/* ------------------------------------------------------------------ */

int sc_cli_add_plot(sc_cli_run *r, const char *script, const char *png) {
  if (r->nplots == SC_CLI_MAXPLOTS)
    return sc_fail(r->msg, SC_EINTERNAL, "too many plots (limit %d)",
                   SC_CLI_MAXPLOTS);
  snprintf(r->plot_script[r->nplots], sizeof r->plot_script[0], "%s", script);
  snprintf(r->plot_png[r->nplots], sizeof r->plot_png[0], "%s", png);
  r->nplots++;
  return SC_OK;
}

char *sc_cli_user_text(char *text) {
  char *w = text;
  for (const char *p = text; *p;) {
    /* a name starts a word: not inside a path or another name */
    int start = p == text || !(isalnum((unsigned char)p[-1]) ||
                               p[-1] == '_' || p[-1] == '/' || p[-1] == '.' ||
                               p[-1] == '-');
    const char *q = start ? sc_msg_what(p) : p;
    if (q != p) {
      p = q;
      continue;
    }
    *w++ = *p++;
  }
  *w = '\0';
  return text;
}

void sc_cli_note(const sc_cli_run *r, const char *fmt, ...) {
  if (r->quiet) return;
  char text[4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(text, sizeof text, fmt, ap);
  va_end(ap);
  fprintf(stderr, "slipcont: %s\n", sc_cli_user_text(text));
}

char *sc_cli_csv_text(char *text) {
  sc_cli_user_text(text);
  for (char *p = text; *p; p++) {
    if (*p == ',') *p = ';';
    else if ((unsigned char)*p < 32 || *p == '"') *p = ' ';
  }
  return text;
}

/* The shortest %.Ng text that reads back as exactly @p x. */
static const char *exact(double x, char *buf, size_t len) {
  for (int prec = 15; prec <= 17; prec++) {
    snprintf(buf, len, "%.*g", prec, x);
    if (strtod(buf, NULL) == x) break;
  }
  return buf;
}

/* Every key of a section with its effective value and where it was set. */
static void section_settings(FILE *f, const sc_scene *s, const char *section,
                             const char *first, const sc_key_info *keys,
                             size_t n) {
  char where[SC_MSG_LEN];
  fprintf(f, "[%s]\n", section);
  if (first) {
    const char *v = sc_scene_value(s, section, first);
    fprintf(f, "  %-16s = %-24s ; %s\n", first, v ? v : "",
            sc_scene_origin(s, section, first, where, sizeof where));
  }
  for (size_t i = 0; i < n; i++) {
    const char *v = sc_scene_value(s, section, keys[i].name);
    sc_scene_origin(s, section, keys[i].name, where, sizeof where);
    int given = strcmp(where, sc_scene_name(s)) != 0;
    fprintf(f, "  %-16s = %-24s ; %s\n", keys[i].name,
            v ? v : "(derived)", given ? where : "default");
  }
}

int sc_cli_summary_begin(sc_cli_run *r, sc_file **out) {
  int st = sc_cli_open(r, "summary.txt", out);
  if (st) return st;
  FILE *f = sc_file_stream(*out);
  const sc_scene *s = r->scene;
  const sc_map *m = r->map;
  const sc_model_type *t = sc_map_type(m);
  char where[SC_MSG_LEN];
  time_t now = time(NULL);
  struct tm tm;
  char stamp[64] = "";
  if (gmtime_r(&now, &tm)) strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", &tm);
  fprintf(f, "slipcont %s: %s\n", sc_scene_task(s)->kind, sc_scene_name(s));
  fprintf(f, "written %s into %s\n\n", stamp, r->dir);
  fputs("settings (value ; where it was set):\n", f);
  fprintf(f, "[model]\n  %-16s = %-24s ; %s\n", "name", t->name,
          sc_scene_origin(s, "model", "name", where, sizeof where));
  for (size_t i = 0; i < t->nparam; i++) {
    sc_scene_origin(s, "model", t->params[i].name, where, sizeof where);
    char num[40];
    /* not in the scene: the table's default, or the model's data's value
     * (the chain's beta2..beta5 from betas or a draw) */
    int from_data = !sc_map_param_is_set(m, i) &&
                    sc_map_get_param(m, i) != t->params[i].def;
    fprintf(f, "  %-16s = %-24s ; %s\n", t->params[i].name,
            exact(sc_map_get_param(m, i), num, sizeof num),
            strcmp(where, sc_scene_name(s)) ? where
            : from_data                      ? "model data"
                                             : "default");
  }
  for (size_t i = 0; i < t->noption; i++) {
    sc_scene_origin(s, "model", t->options[i].name, where, sizeof where);
    fprintf(f, "  %-16s = %-24s ; %s\n", t->options[i].name,
            sc_map_get_option(m, t->options[i].name),
            strcmp(where, sc_scene_name(s)) ? where : "default");
  }
  for (size_t i = 0; i < t->ndata; i++) {
    sc_scene_origin(s, "model", t->data[i].name, where, sizeof where);
    const char *v = sc_map_get_data(m, t->data[i].name);
    fprintf(f, "  %-16s = %-24s ; %s\n", t->data[i].name, v[0] ? v : "-",
            strcmp(where, sc_scene_name(s)) ? where : "default");
  }
  /* what runs, where the options alone do not say it: velocity weakening
   * is integrated numerically whatever flows reads */
  if (sc_map_precision(m) > 0)
    fprintf(f, "  (the flows are integrated numerically here: f to about "
               "%.1e, the model's precision)\n", sc_map_precision(m));
  const sc_task_type *tt = sc_scene_task(s);
  section_settings(f, s, "task", "kind", tt->keys, tt->nkeys);
  size_t n;
  const sc_key_info *ak = sc_scene_section_keys("accuracy", &n);
  section_settings(f, s, "accuracy", NULL, ak, n);
  const sc_accuracy *acc = sc_scene_accuracy(s);
  for (size_t i = 0; i < sc_accuracy_nfields(); i++) {
    char num[40];
    fprintf(f, "  %-16s = %s\n", sc_accuracy_field_name(i),
            exact(sc_accuracy_field_value(acc, i), num, sizeof num));
  }
  fprintf(f, "[output]\n  %-16s = %s\n  %-16s = %s\n", "dir", r->dir,
          "plot", sc_scene_plot(s) ? "yes" : "no");
  fputs("\nresults:\n", f);
  return SC_OK;
}

/* See tasks.h. */
int sc_cli_check_param_keys(const sc_scene *s, const char *param,
                            const char *const *ends, int n, sc_msg *msg) {
  const sc_map *m = sc_scene_map(s);
  const char *name = sc_scene_text(s, param);
  const sc_param_info *pi =
      &sc_map_type(m)->params[sc_map_param_index(m, name)];
  /* The range is the model table's (never a copy of it). */
  sc_key_info range = {pi->name, SC_KEY_REAL, 0, NULL, pi->lo, pi->hi,
                       pi->lo_open, pi->hi_open, NULL, NULL};
  char text[128];
  sc_key_range_text(&range, text, sizeof text);
  for (int k = 0; k < n; k++)
    if (sc_param_check(pi, sc_scene_real(s, ends[k]), NULL))
      return sc_scene_fail_key(s, "task", ends[k], msg,
                               "%s = %s out of range of %s (valid: %s)",
                               ends[k], sc_scene_text(s, ends[k]), name, text);
  return SC_OK;
}

int sc_cli_check_param_ends(const sc_scene *s, sc_msg *msg) {
  static const char *const ends[] = {"from", "to"};
  return sc_cli_check_param_keys(s, "parameter", ends, 2, msg);
}

/* See tasks.h. */
int sc_cli_write_map_graph(sc_cli_run *r, const char *name, int n,
                           double from, double to, size_t steps) {
  sc_file *csv = NULL;
  int st = sc_cli_open(r, name, &csv);
  if (st) return st;
  FILE *f = sc_file_stream(csv);
  fputs("d,f,itinerary\n", f);
  char last[SC_ITIN_LEN] = "";
  int have = 0;
  sc_map_value v;
  for (size_t i = 0; i < steps; i++) {
    if ((st = sc_cli_stop(r))) return st; /* the driver aborts csv */
    double d = sc_grid(from, to, steps, i, SC_GRID_LINEAR);
    int e = sc_map_iterate(r->map, d, n, SC_EVAL_ITINERARY, &v, NULL);
    if (e == SC_EUNDEF || e == SC_ENONFINITE || e == SC_ENOCONV) {
      if (have) fputc('\n', f);
      have = 0;
      continue;
    }
    if (e) return sc_fail(r->msg, e, "graph of f^%d at d = %.17g failed", n, d);
    if (have && strcmp(last, v.itinerary) != 0) fputc('\n', f);
    snprintf(last, sizeof last, "%s", v.itinerary);
    have = 1;
    sc_csv_double(f, d);
    fputc(',', f);
    sc_csv_double(f, v.f);
    fprintf(f, ",%s\n", sc_cli_csv_text(v.itinerary));
  }
  return sc_cli_commit(r, name, csv);
}
