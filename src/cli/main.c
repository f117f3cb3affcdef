/* The `slipcont` program: run or check a scene, list models and keys.
 *
 * Exit status: 0 success; 1 a computation failed (or gnuplot is missing
 * or failed) after the scene was accepted; 2 bad input (usage, scene,
 * output folder).  Messages and progress go to stderr; stdout carries
 * only what was asked for (check results, models, keys, help). */
#define _POSIX_C_SOURCE 200809L

#include <gsl/gsl_errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "cli/help.h"
#include "cli/tasks.h"
#include "slipcont/chart.h"
#include "slipcont/io.h"

enum { EXIT_OK = 0, EXIT_COMPUTE = 1, EXIT_INPUT = 2 };

/* Most --set overrides on one command line. */
#define MAX_SETS 64

typedef struct {
  const char *scene;
  const char *sets[MAX_SETS];
  size_t nsets;
  const char *out;
  int quiet;
  long threads;
  long stop_after_rows;
  const char *interrupt_before;
  int help;
  int markdown;
} cli_args;

static void usage(FILE *f) {
  fputs(
      "usage: slipcont COMMAND [ARGS]\n"
      "\n"
      "Bifurcation analysis of stick-slip event maps (two-block "
      "Burridge-Knopoff model).\n"
      "\n"
      "commands:\n"
      "  run SCENE [OPTIONS]    validate SCENE, compute its task, write the "
      "outputs\n"
      "  check SCENE [OPTIONS]  validate SCENE only (nothing is written)\n"
      "  models                 list the models, their parameters, ranges "
      "and options\n"
      "  keys [--markdown]      list every scene key of every section\n"
      "  help [COMMAND|KIND]    this text, a command's options, or a task "
      "kind's keys\n"
      "\n"
      "run/check options:\n"
      "  --set SECTION.KEY=VALUE  override a scene key (as if appended to "
      "the file)\n"
      "  --out DIR                override [output] dir\n"
      "  --quiet                  no notes or progress on stderr\n"
      "  --threads N              OpenMP threads for parallel tasks (N >= "
      "1)\n"
      "  --stop-after-rows N      chart: stop after N rows with a checkpoint,"
      " as a kill\n"
      "                           would (to test resuming)\n"
      "  --interrupt-before STEP  raise SIGINT just before a step of the run"
      " (prepare,\n"
      "                           compute, write, summary, plots, report; to"
      " test stopping)\n"
      "\n"
      "exit status: 0 success, 1 computation failed or interrupted, 2 bad "
      "input (usage,\nscene, output folder); 130/143 when SIGINT/SIGTERM "
      "had to end a task that did\nnot stop within a second (no "
      "half-written file is left)\n"
      "see docs/guide.md; examples/*.ini show each task.\n",
      f);
}

static void run_usage(FILE *f, const char *cmd) {
  fprintf(f,
          "usage: slipcont %s SCENE [--set SECTION.KEY=VALUE]... [--out DIR]"
          "%s\n\n",
          cmd, strcmp(cmd, "run") == 0 ? " [--quiet] [--threads N]"
                                         " [--stop-after-rows N]"
                                         " [--interrupt-before STEP]" : "");
  if (strcmp(cmd, "run") == 0)
    fputs("Validate the scene, create the output folder, compute the task, "
          "write CSV files,\nsummary.txt and gnuplot scripts, and render "
          "them to PNG when [output] plot = yes.\n\n",
          f);
  else
    fputs("Validate the scene and the output folder without computing or "
          "writing anything;\nprint 'SCENE: ok ...' on stdout.\n\n",
          f);
  fputs("A scene has the sections [model] (name = bk2|logistic|cubic and "
        "its parameters),\n[task] (kind = ",
        f);
  for (size_t i = 0; i < sc_cli_task_count(); i++)
    fprintf(f, "%s%s", i ? "|" : "", sc_cli_task_get(i)->type.kind);
  fputs(" and its keys), [accuracy], [output].\n\n", f);
  for (size_t i = 0; i < sc_cli_task_count(); i++)
    sc_cli_print_task_keys(f, sc_cli_task_get(i), 0);
  fputs("`slipcont keys` lists every section; `slipcont models` every "
        "model.\n",
        f);
}

static int bad_usage(const char *fmt, const char *arg) {
  fputs("slipcont: ", stderr);
  fprintf(stderr, fmt, arg);
  fputs(" (see slipcont --help)\n", stderr);
  return EXIT_INPUT;
}

/* 1 if @p name is a step of the run skeleton (tasks.h). */
static int is_step(const char *name) {
  size_t n;
  const char *const *steps = sc_cli_step_names(&n);
  for (size_t i = 0; i < n; i++)
    if (strcmp(name, steps[i]) == 0) return 1;
  return 0;
}

/* Options of run and check, before or after the scene. */
static int parse_run_args(int argc, char **argv, cli_args *a) {
  for (int i = 0; i < argc; i++) {
    const char *s = argv[i];
    const char *val = NULL;
    if (strcmp(s, "--help") == 0 || strcmp(s, "-h") == 0) {
      a->help = 1;
    } else if (strcmp(s, "--quiet") == 0 || strcmp(s, "-q") == 0) {
      a->quiet = 1;
    } else if (strncmp(s, "--set", 5) == 0 && (s[5] == '\0' || s[5] == '=')) {
      val = s[5] ? s + 6 : (i + 1 < argc ? argv[++i] : NULL);
      if (!val) return bad_usage("%s needs SECTION.KEY=VALUE", s);
      if (a->nsets == MAX_SETS) return bad_usage("too many %s", "--set");
      a->sets[a->nsets++] = val;
    } else if (strncmp(s, "--out", 5) == 0 && (s[5] == '\0' || s[5] == '=')) {
      val = s[5] ? s + 6 : (i + 1 < argc ? argv[++i] : NULL);
      if (!val || !val[0]) return bad_usage("%s needs a folder", s);
      a->out = val;
    } else if (strncmp(s, "--threads", 9) == 0 &&
               (s[9] == '\0' || s[9] == '=')) {
      val = s[9] ? s + 10 : (i + 1 < argc ? argv[++i] : NULL);
      if (!val || sc_parse_long(val, 1, 4096, &a->threads))
        return bad_usage("--threads needs a count in [1, 4096], not '%s'",
                         val ? val : "");
    } else if (strncmp(s, "--stop-after-rows", 17) == 0 &&
               (s[17] == '\0' || s[17] == '=')) {
      val = s[17] ? s + 18 : (i + 1 < argc ? argv[++i] : NULL);
      if (!val || sc_parse_long(val, 1, SC_CHART_MAX_POINTS,
                                &a->stop_after_rows))
        return bad_usage("--stop-after-rows needs a row count >= 1, not "
                         "'%s'", val ? val : "");
    } else if (strncmp(s, "--interrupt-before", 18) == 0 &&
               (s[18] == '\0' || s[18] == '=')) {
      val = s[18] ? s + 19 : (i + 1 < argc ? argv[++i] : NULL);
      if (!val || !is_step(val))
        return bad_usage("--interrupt-before needs a step (prepare, compute, "
                         "write, summary, plots or report), not '%s'",
                         val ? val : "");
      a->interrupt_before = val;
    } else if (s[0] == '-' && s[1]) {
      return bad_usage("unknown option '%s'", s);
    } else if (!a->scene) {
      a->scene = s;
    } else {
      return bad_usage("one scene at a time ('%s' is extra)", s);
    }
  }
  return EXIT_OK;
}

static int load(const cli_args *a, sc_scene **scene) {
  size_t ntypes;
  const sc_task_type *const *types = sc_cli_task_types(&ntypes);
  sc_scene_options o = {a->sets, a->nsets, a->out, types, ntypes};
  sc_msg msg;
  if (sc_scene_load(a->scene, &o, scene, &msg)) {
    fprintf(stderr, "slipcont: %s\n", sc_cli_user_text(msg.text));
    return EXIT_INPUT;
  }
  return EXIT_OK;
}

/* A long path shown in a message: its first and last characters. */
static const char *shown(const char *dir, char *buf, size_t len) {
  size_t n = strlen(dir);
  if (n <= 80) return dir;
  snprintf(buf, len, "%.40s...%s (%zu characters)", dir, dir + n - 30, n);
  return buf;
}

/* The results a task writes, named in its `outputs` line: every word
 * ending in .csv, .txt, .gp, .png or .checkpoint.  Calls fn on each. */
static int each_output(const sc_cli_task *t, const char *dir,
                       int (*fn)(const char *dir, const char *name)) {
  const char *p = t->outputs;
  while (*p) {
    size_t k = strcspn(p, " ,;()");
    if (k > 0 && k < 64) {
      char name[64];
      memcpy(name, p, k);
      name[k] = '\0';
      const char *dot = strrchr(name, '.');
      if (dot && (!strcmp(dot, ".csv") || !strcmp(dot, ".txt") ||
                  !strcmp(dot, ".gp") || !strcmp(dot, ".png") ||
                  !strcmp(dot, ".checkpoint"))) {
        int rc = fn(dir, name);
        if (rc) return rc;
      }
    }
    p += k;
    if (*p) p++;
  }
  return 0;
}

/* A result name taken by something that is not a file (a folder, a
 * FIFO): found now, not after computing. */
static int output_blocked(const char *dir, const char *name) {
  char path[PATH_MAX];
  struct stat sb;
  snprintf(path, sizeof path, "%s/%s", dir, name);
  if (lstat(path, &sb) == 0 && !S_ISREG(sb.st_mode)) {
    char buf[160];
    fprintf(stderr,
            "slipcont: %s/%s exists and is not a file: the result %s cannot "
            "be written there (remove it or choose another --out)\n",
            shown(dir, buf, sizeof buf), name, name);
    return EXIT_INPUT;
  }
  return 0;
}

/* The output folder: checked (check) or created and proved writable
 * (run); the message names where dir was set.  Result names blocked by
 * folders are refused in both. */
static int prepare_output(const sc_scene *s, int create) {
  sc_msg msg;
  const char *dir = sc_scene_output_dir(s);
  const sc_cli_task *task = sc_cli_task_find(sc_scene_task(s)->kind);
  if (sc_output_prepare(dir, create, &msg) == SC_OK)
    return each_output(task, dir, output_blocked);
  char where[SC_MSG_LEN], buf[160];
  const char *reason = sc_cli_user_text(msg.text);
  size_t n = strlen(dir);
  if (strncmp(reason, dir, n) == 0 && strncmp(reason + n, ": ", 2) == 0)
    reason += n + 2; /* the path is already in the message */
  else if (strncmp(reason, "output folder: ", 15) == 0)
    reason += 15;
  sc_scene_origin(s, "output", "dir", where, sizeof where);
  fprintf(stderr, "slipcont: %s: [output] dir = %s: %s\n", where,
          shown(dir, buf, sizeof buf), reason);
  return EXIT_INPUT;
}

static int cmd_check(const cli_args *a) {
  sc_scene *s;
  int rc = load(a, &s);
  if (rc) return rc;
  rc = prepare_output(s, 0);
  if (!rc)
    printf("%s: ok (model %s, task %s, output %s)\n", sc_scene_name(s),
           sc_map_type(sc_scene_map(s))->name, sc_scene_task(s)->kind,
           sc_scene_output_dir(s));
  if (!rc && !a->quiet && sc_scene_plot(s) && !sc_plot_available())
    fputs("slipcont: note: gnuplot not found on PATH: a run would write the "
          "data and exit with status 1 (or set [output] plot = no)\n",
          stderr);
  sc_scene_free(s);
  return rc;
}

static int cmd_run(const cli_args *a) {
  sc_scene *s;
  int rc = load(a, &s);
  if (rc) return rc;
  struct stat sb;
  int existed = stat(sc_scene_output_dir(s), &sb) == 0;
  if ((rc = prepare_output(s, 1))) {
    sc_scene_free(s);
    return rc;
  }
#ifdef _OPENMP
  if (a->threads > 0) omp_set_num_threads((int)a->threads);
#endif
  const sc_cli_task *task = sc_cli_task_find(sc_scene_task(s)->kind);
  sc_msg msg;
  sc_cli_run r;
  memset(&r, 0, sizeof r);
  r.scene = s;
  r.map = sc_scene_map(s);
  r.dir = sc_scene_output_dir(s);
  r.quiet = a->quiet;
  r.msg = &msg;
  int plot = sc_scene_plot(s);
  if (plot && !sc_plot_available())
    fputs("slipcont: gnuplot not found on PATH: the data will be written "
          "but no PNG (set [output] plot = no to silence this)\n",
          stderr);
  sc_cli_catch_signals();
  r.stop_after_rows = a->stop_after_rows;
  r.interrupt_before = a->interrupt_before;
  int st = sc_cli_task_run(task, &r);
  sc_cli_signals_done();
  if (st) {
    /* a message that names the scene's file (a key's line) already says
     * where */
    const char *name = sc_scene_name(s);
    size_t n = strlen(name);
    int named = strncmp(msg.text, name, n) == 0 && msg.text[n] == ':';
    fprintf(stderr, "slipcont: %s%s%s\n", named ? "" : name,
            named ? "" : ": ", sc_cli_user_text(msg.text));
    rc = EXIT_COMPUTE;
  } else if (sc_cli_interrupted()) {
    /* The task finished its files, but the user asked to stop: no plots. */
    fprintf(stderr, "slipcont: %s: interrupted (the files written are "
                    "complete; no plot was rendered)\n",
            sc_scene_name(s));
    rc = EXIT_COMPUTE;
  }
  for (size_t i = 0; plot && !sc_cli_interrupted() && i < r.nplots; i++) {
    if (sc_plot_render(r.dir, r.plot_script[i], r.plot_png[i], &msg)) {
      fprintf(stderr, "slipcont: %s\n", sc_cli_user_text(msg.text));
      rc = EXIT_COMPUTE;
      if (!sc_plot_available()) break;
    } else {
      size_t n = strlen(r.written);
      snprintf(r.written + n, sizeof r.written - n, "%s%s", n ? ", " : "",
               r.plot_png[i]);
    }
  }
  if (r.written[0]) sc_cli_note(&r, "wrote %s/{%s}", r.dir, r.written);
  /* A run that failed before writing anything leaves no folder it made
   * (rmdir removes only an empty one). */
  if (rc && !existed) rmdir(r.dir);
  sc_scene_free(s);
  return rc;
}

static int cmd_help(int argc, char **argv) {
  if (argc == 0) {
    usage(stdout);
    return EXIT_OK;
  }
  const char *topic = argv[0];
  if (strcmp(topic, "run") == 0 || strcmp(topic, "check") == 0) {
    run_usage(stdout, topic);
    return EXIT_OK;
  }
  if (strcmp(topic, "models") == 0) {
    sc_cli_print_models(stdout, 0);
    return EXIT_OK;
  }
  if (strcmp(topic, "keys") == 0 || strcmp(topic, "scene") == 0) {
    sc_cli_print_keys(stdout, 0);
    return EXIT_OK;
  }
  const sc_cli_task *t = sc_cli_task_find(topic);
  if (t) {
    sc_cli_print_task_keys(stdout, t, 0);
    return EXIT_OK;
  }
  const sc_model_type *m = sc_model_find(topic);
  if (m) {
    sc_cli_print_model(stdout, m, 0);
    return EXIT_OK;
  }
  return bad_usage("no help on '%s' (try a command, a task kind or a model)",
                   topic);
}

int main(int argc, char **argv) {
  gsl_set_error_handler_off();
  if (argc < 2) {
    usage(stderr);
    return EXIT_INPUT;
  }
  const char *cmd = argv[1];
  if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0)
    return cmd_help(0, NULL);
  if (strcmp(cmd, "--version") == 0) {
    puts("slipcont 0.1.0");
    return EXIT_OK;
  }
  if (strcmp(cmd, "help") == 0) return cmd_help(argc - 2, argv + 2);
  if (strcmp(cmd, "run") == 0 || strcmp(cmd, "check") == 0) {
    cli_args a;
    memset(&a, 0, sizeof a);
    int rc = parse_run_args(argc - 2, argv + 2, &a);
    if (rc) return rc;
    if (a.help) {
      run_usage(stdout, cmd);
      return EXIT_OK;
    }
    if (!a.scene) return bad_usage("%s needs a scene file", cmd);
    return strcmp(cmd, "run") == 0 ? cmd_run(&a) : cmd_check(&a);
  }
  if (strcmp(cmd, "models") == 0 || strcmp(cmd, "keys") == 0) {
    int md = 0;
    for (int i = 2; i < argc; i++) {
      if (strcmp(argv[i], "--markdown") == 0) md = 1;
      else if (strcmp(argv[i], "--help") == 0) return cmd_help(1, argv + 1);
      else return bad_usage("unknown argument '%s'", argv[i]);
    }
    if (strcmp(cmd, "models") == 0) sc_cli_print_models(stdout, md);
    else sc_cli_print_keys(stdout, md);
    return EXIT_OK;
  }
  return bad_usage("unknown command '%s'", cmd);
}
