/* Scenes: a good scene, every kind of bad scene (each refused with a
 * message naming file, line, key and valid range), overrides, defaults,
 * the output folder checks and atomic files. */
#define _POSIX_C_SOURCE 200809L

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "slipcont/io.h"
#include "test_util.h"

/* A task kind of the test's own, shaped like the program's sweep. */
static const sc_key_info demo_keys[] = {
    {"parameter", SC_KEY_PARAM, 1, NULL, 0, 0, 0, 0, NULL, "swept"},
    {"from", SC_KEY_REAL, 1, NULL, -HUGE_VAL, HUGE_VAL, 1, 1, NULL, "start"},
    {"steps", SC_KEY_INT, 0, "200", 1, 1000000, 0, 0, NULL, "points"},
    {"seed", SC_KEY_CHOICE, 0, "fixed", 0, 0, 0, 0, "fixed|previous", "seed"},
    {"trajectory", SC_KEY_BOOL, 0, "no", 0, 0, 0, 0, NULL, "motion"},
    {"dtau", SC_KEY_REAL, 0, "0.01", 0, 1000, 1, 0, NULL, "step"},
};

static int demo_check(const sc_scene *s, sc_msg *msg) {
  if (sc_scene_int(s, "steps") == 13)
    return sc_scene_fail_key(s, "task", "steps", msg,
                             "steps = 13 is unlucky (valid: not 13)");
  return SC_OK;
}

static const sc_task_type demo = {"demo", "a test task", demo_keys,
                                  sizeof demo_keys / sizeof demo_keys[0],
                                  demo_check};
static const sc_task_type *const demo_tasks[] = {&demo};

static const char *good =
    "; a good scene\n"
    "[model]\n"
    "name = bk2\n"
    "driver = frozen     ; inline comment\n"
    "alpha = 2.385\n"
    "beta = 1.5\n"
    "\n"
    "[task]\n"
    "kind = demo\n"
    "parameter = v\n"
    "from = 0.025\n"
    "\n"
    "[accuracy]\n"
    "event-rtol = 3e-13\n"
    "preset = fast\n"
    "\n"
    "[output]\n"
    "dir = out/good\n"
    "plot = no\n";

static sc_scene *parse(const char *text, const char *const *sets,
                       size_t nsets, const char *out, sc_msg *msg, int *st) {
  sc_scene_options o = {sets, nsets, out, demo_tasks, 1};
  sc_scene *s = NULL;
  *st = sc_scene_parse("x.ini", text, &o, &s, msg);
  return s;
}

/* A scene with one line replaced or added must be refused with a message
 * containing each of @p want (NULL-terminated). */
static void refused(const char *what, const char *text, const char *want1,
                    const char *want2) {
  sc_msg msg = {""};
  int st;
  sc_scene *s = parse(text, NULL, 0, NULL, &msg, &st);
  tu_true(st == SC_EINVAL && !s, "%s: refused with SC_EINVAL (got %d)", what,
          st);
  tu_true(strstr(msg.text, want1) != NULL, "%s: message '%s' contains '%s'",
          what, msg.text, want1);
  if (want2)
    tu_true(strstr(msg.text, want2) != NULL, "%s: message '%s' contains '%s'",
            what, msg.text, want2);
  sc_scene_free(s);
}

/* @p good with the first occurrence of @p from replaced by @p to. */
static char *edit(const char *from, const char *to) {
  static char buf[4096];
  const char *p = strstr(good, from);
  if (!p) {
    snprintf(buf, sizeof buf, "%s", good);
    return buf;
  }
  snprintf(buf, sizeof buf, "%.*s%s%s", (int)(p - good), good, to,
           p + strlen(from));
  return buf;
}

static void test_good(void) {
  sc_msg msg = {""};
  int st;
  sc_scene *s = parse(good, NULL, 0, NULL, &msg, &st);
  tu_int("good scene accepted", st, SC_OK);
  if (!s) {
    printf("  message: %s\n", msg.text);
    return;
  }
  sc_map *m = sc_scene_map(s);
  tu_close("alpha set", sc_map_get_param(m, (size_t)sc_map_param_index(m, "alpha")),
           2.385, 0);
  tu_close("phi default", sc_map_get_param(m, (size_t)sc_map_param_index(m, "phi")),
           1.25, 0);
  tu_true(strcmp(sc_map_get_option(m, "driver"), "frozen") == 0,
          "driver = frozen (inline comment stripped)");
  /* The preset comes first wherever it is written; fields then override. */
  tu_close("event-rtol after preset", sc_scene_accuracy(s)->event_rtol, 3e-13,
           0);
  sc_accuracy fast;
  sc_accuracy_preset(&fast, "fast", NULL);
  tu_close("newton-atol from the fast preset",
           sc_scene_accuracy(s)->newton_atol, fast.newton_atol, 0);
  tu_close("map got the accuracy", sc_map_accuracy(m)->event_rtol, 3e-13, 0);
  tu_true(strcmp(sc_scene_task(s)->kind, "demo") == 0, "task kind demo");
  tu_int("steps default", sc_scene_int(s, "steps"), 200);
  tu_true(strcmp(sc_scene_text(s, "seed"), "fixed") == 0, "seed default");
  tu_int("trajectory default no", sc_scene_flag(s, "trajectory"), 0);
  tu_close("from", sc_scene_real(s, "from"), 0.025, 0);
  tu_true(strcmp(sc_scene_output_dir(s), "out/good") == 0, "output dir");
  tu_int("plot = no", sc_scene_plot(s), 0);
  char where[256];
  sc_scene_origin(s, "task", "from", where, sizeof where);
  tu_true(strcmp(where, "x.ini:11") == 0, "origin of from is x.ini:11 (%s)",
          where);
  sc_scene_free(s);
}

static void test_overrides(void) {
  sc_msg msg = {""};
  int st;
  const char *sets[] = {"model.alpha=3.1", "task.steps = 17",
                        "model.v=0.0125", "output.plot=yes"};
  sc_scene *s = parse(good, sets, 4, "elsewhere/x", &msg, &st);
  tu_int("overrides accepted", st, SC_OK);
  if (!s) {
    printf("  message: %s\n", msg.text);
    return;
  }
  sc_map *m = sc_scene_map(s);
  tu_close("--set model.alpha", sc_map_get_param(m, (size_t)sc_map_param_index(m, "alpha")),
           3.1, 0);
  tu_close("--set model.v (not in the file)",
           sc_map_get_param(m, (size_t)sc_map_param_index(m, "v")), 0.0125, 0);
  tu_int("--set task.steps", sc_scene_int(s, "steps"), 17);
  tu_int("--set output.plot", sc_scene_plot(s), 1);
  tu_true(strcmp(sc_scene_output_dir(s), "elsewhere/x") == 0,
          "--out replaces [output] dir");
  char where[256];
  sc_scene_origin(s, "model", "alpha", where, sizeof where);
  tu_true(strcmp(where, "--set model.alpha=3.1") == 0,
          "origin of an override (%s)", where);
  sc_scene_free(s);

  /* An override is checked like the file: same message shape. */
  const char *bad[] = {"model.alpha=-1"};
  s = parse(good, bad, 1, NULL, &msg, &st);
  tu_true(st == SC_EINVAL && strstr(msg.text, "--set model.alpha=-1: [model] "
                                              "alpha = -1 out of range "
                                              "(valid: (0, 1000000])"),
          "bad override refused: %s", msg.text);
  sc_scene_free(s);
  const char *malformed[] = {"alpha=3"};
  s = parse(good, malformed, 1, NULL, &msg, &st);
  tu_true(st == SC_EINVAL && strstr(msg.text, "expected section.key=value"),
          "override without a section refused: %s", msg.text);
  sc_scene_free(s);
  const char *badsec[] = {"modle.alpha=3"};
  s = parse(good, badsec, 1, NULL, &msg, &st);
  tu_true(st == SC_EINVAL && strstr(msg.text, "unknown section [modle]"),
          "override with an unknown section refused: %s", msg.text);
  sc_scene_free(s);
}

static void test_bad(void) {
  refused("unknown section", edit("[accuracy]", "[accuracy]\n[extra]"),
          "x.ini:14: unknown section [extra]", "valid: model, task");
  refused("unknown model key", edit("beta = 1.5", "delta = 1.5"),
          "x.ini:6: [model] unknown key 'delta' for model bk2",
          "alpha, beta, phi, v, gamma, driver");
  refused("unknown task key", edit("from = 0.025", "form = 0.025"),
          "x.ini:11: [task] unknown key 'form' for kind demo", "from");
  refused("unknown accuracy key", edit("event-rtol", "event_tol"),
          "x.ini:14: [accuracy] unknown accuracy key 'event_tol'", NULL);
  refused("unknown output key", edit("plot = no", "plots = no"),
          "x.ini:19: [output] unknown key 'plots'", "dir, plot");
  refused("duplicate key", edit("beta = 1.5", "beta = 1.5\nbeta = 2"),
          "x.ini:7: [model] duplicate key 'beta' (first at line 6)", NULL);
  refused("repeated section", edit("[output]", "[model]\n[output]"),
          "x.ini:17: section [model] repeated (first at line 2)", NULL);
  refused("bad number", edit("alpha = 2.385", "alpha = 2.3.85"),
          "x.ini:5: [model] alpha = '2.3.85' is not a number", "(0, 1000000]");
  refused("NaN", edit("alpha = 2.385", "alpha = nan"),
          "x.ini:5: [model] alpha = nan is not a finite number", NULL);
  refused("infinity", edit("from = 0.025", "from = -inf"),
          "x.ini:11: [task] from = -inf is not a finite number", NULL);
  refused("out of range (table)", edit("alpha = 2.385", "alpha = -1"),
          "x.ini:5: [model] alpha = -1 out of range (valid: (0, 1000000])",
          NULL);
  refused("open end excluded", edit("alpha = 2.385", "alpha = 0"),
          "x.ini:5: [model] alpha = 0 out of range (valid: (0, 1000000])",
          NULL);
  refused("bad option value", edit("driver = frozen", "driver = stopped"),
          "x.ini:4: [model] driver = 'stopped' is not valid",
          "moving|frozen");
  refused("bad model", edit("name = bk2", "name = bk3"),
          "x.ini:3: [model] name = 'bk3' is not a model", "bk2|logistic|cubic");
  refused("missing model name", edit("name = bk2\n", ""),
          "x.ini:2: [model] missing required key 'name'", "bk2|logistic");
  refused("missing kind", edit("kind = demo\n", ""),
          "x.ini:8: [task] missing required key 'kind'", "demo");
  refused("missing required task key", edit("from = 0.025\n", ""),
          "x.ini:8: [task] missing required key 'from'", NULL);
  refused("bad kind", edit("kind = demo", "kind = sweeep"),
          "x.ini:9: [task] kind = 'sweeep' is not a task", "valid: demo");
  refused("steps = 0", edit("from = 0.025", "from = 0.025\nsteps = 0"),
          "x.ini:12: [task] steps = 0 out of range (valid: [1, 1000000])",
          NULL);
  refused("steps not an integer", edit("from = 0.025", "from = 0.025\nsteps = 2.5"),
          "x.ini:12: [task] steps = 2.5 is not an integer", NULL);
  refused("bad choice", edit("from = 0.025", "from = 0.025\nseed = random"),
          "x.ini:12: [task] seed = 'random' is not valid",
          "(valid: fixed|previous)");
  refused("bad bool", edit("plot = no", "plot = maybe"),
          "x.ini:19: [output] plot = 'maybe' is not valid", "yes|no");
  refused("parameter of another model", edit("parameter = v", "parameter = r"),
          "x.ini:10: [task] parameter = 'r' is not a parameter of model bk2",
          "alpha|beta|phi|v");
  refused("dtau open lower end", edit("from = 0.025", "from = 0.025\ndtau = 0"),
          "x.ini:12: [task] dtau = 0 out of range (valid: (0, 1000])", NULL);
  refused("task check", edit("from = 0.025", "from = 0.025\nsteps = 13"),
          "x.ini:12: [task] steps = 13 is unlucky", NULL);
  refused("bad preset", edit("preset = fast", "preset = quick"),
          "x.ini:15: [accuracy] preset = 'quick' is not valid",
          "fast|default|precise");
  refused("accuracy out of range", edit("event-rtol = 3e-13", "event-rtol = 1"),
          "x.ini:14: [accuracy] event-rtol = 1 out of range", NULL);
  refused("key outside a section", "alpha = 3\n[model]\nname = bk2\n",
          "x.ini:1: key 'alpha' outside any section", NULL);
  refused("syntax error", edit("beta = 1.5", "beta 1.5"),
          "x.ini:6: syntax error", NULL);
  refused("continuation line", edit("beta = 1.5", "beta = 1.5\n  2"),
          "x.ini:7: [model] line starts with blanks", NULL);
  refused("empty value", edit("beta = 1.5", "beta ="),
          "x.ini:6: [model] beta = '' is not a number", NULL);
  refused("velocity weakening with the driver frozen",
          edit("beta = 1.5", "beta = 1.5\nfriction = velocity-weakening"),
          "x.ini:7: [model]", NULL);
  char longline[400];
  memset(longline, 'x', sizeof longline);
  memcpy(longline, "; ", 2);
  longline[sizeof longline - 1] = '\0';
  char text[1024];
  snprintf(text, sizeof text, "%s\n%s", longline, good);
  refused("line too long", text, "x.ini:1: line too long", NULL);

  sc_msg msg;
  sc_scene *s = NULL;
  int st = sc_scene_load("/nonexistent/scene.ini", NULL, &s, &msg);
  tu_true(st == SC_EIO && !s &&
              strstr(msg.text, "/nonexistent/scene.ini: cannot open"),
          "missing file: %s", msg.text);
}

static void test_default_dir(void) {
  sc_msg msg;
  sc_scene_options o = {NULL, 0, NULL, demo_tasks, 1};
  sc_scene *s = NULL;
  char *text = edit("dir = out/good\n", "");
  int st = sc_scene_parse("examples/fig.v2.ini", text, &o, &s, &msg);
  tu_int("scene without dir", st, SC_OK);
  if (s)
    tu_true(strcmp(sc_scene_output_dir(s), "out/fig.v2") == 0,
            "default dir out/STEM (%s)", sc_scene_output_dir(s));
  sc_scene_free(s);
}

static int count_entries(const char *dir) {
  DIR *d = opendir(dir);
  if (!d) return -1;
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d)))
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
  closedir(d);
  return n;
}

static void test_output(void) {
  char base[] = "/tmp/sc-test-scene-XXXXXX";
  if (!mkdtemp(base)) {
    tu_true(0, "mkdtemp");
    return;
  }
  char dir[512], file[600], sub[700];
  sc_msg msg;
  snprintf(dir, sizeof dir, "%s/a/b/c", base);
  tu_int("check only: creatable", sc_output_prepare(dir, 0, &msg), SC_OK);
  struct stat sb;
  tu_true(stat(dir, &sb) != 0, "check only created nothing");
  tu_int("mkdir -p", sc_output_prepare(dir, 1, &msg), SC_OK);
  tu_true(stat(dir, &sb) == 0 && S_ISDIR(sb.st_mode), "folder created");
  tu_int("no probe left", count_entries(dir), 0);

  /* A path under a regular file cannot be created, even by root. */
  snprintf(file, sizeof file, "%s/plain", base);
  FILE *f = fopen(file, "w");
  fputs("x\n", f);
  fclose(f);
  snprintf(sub, sizeof sub, "%s/out", file);
  tu_true(sc_output_prepare(sub, 0, &msg) == SC_EIO &&
              strstr(msg.text, "is not a folder"),
          "under a file (check): %s", msg.text);
  tu_true(sc_output_prepare(sub, 1, &msg) == SC_EIO &&
              strstr(msg.text, "cannot create"),
          "under a file (create): %s", msg.text);

  /* Atomic files: nothing under the final name until commit; no
   * temporary left after commit or abort. */
  sc_file *w;
  tu_int("open", sc_file_open(dir, "data.csv", &w, &msg), SC_OK);
  fputs("a,b\n", sc_file_stream(w));
  sc_csv_double(sc_file_stream(w), 0.1);
  fputc(',', sc_file_stream(w));
  sc_csv_double(sc_file_stream(w), NAN);
  fputc('\n', sc_file_stream(w));
  snprintf(file, sizeof file, "%s/data.csv", dir);
  tu_true(stat(file, &sb) != 0, "final name absent before commit");
  tu_int("one temporary while writing", count_entries(dir), 1);
  tu_int("commit", sc_file_commit(w, &msg), SC_OK);
  tu_int("only the final file after commit", count_entries(dir), 1);
  f = fopen(file, "r");
  char line[2][64] = {"", ""};
  if (f) {
    if (!fgets(line[0], 64, f) || !fgets(line[1], 64, f)) line[1][0] = '\0';
    fclose(f);
  }
  tu_true(strcmp(line[1], "0.10000000000000001,nan\n") == 0,
          "%%.17g and nan written: %s", line[1]);
  tu_int("open again", sc_file_open(dir, "other.csv", &w, &msg), SC_OK);
  fputs("half", sc_file_stream(w));
  sc_file_abort(w);
  tu_int("abort leaves nothing", count_entries(dir), 1);
  char cmd[700];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", base);
  tu_int("cleanup", system(cmd), 0);
}

static void test_keys(void) {
  char buf[128];
  sc_key_info k = {"x", SC_KEY_REAL, 0, NULL, 0, HUGE_VAL, 1, 1, NULL, ""};
  tu_true(strcmp(sc_key_range_text(&k, buf, sizeof buf), "(0, inf)") == 0,
          "range text (0, inf): %s", buf);
  sc_msg msg;
  tu_int("1e300 accepted", sc_key_check(&k, "1e300", NULL, &msg), SC_OK);
  tu_int("1e999 refused", sc_key_check(&k, "1e999", NULL, &msg), SC_EINVAL);
  tu_int("0x10 refused (decimal only)", sc_key_check(&k, "0x10", NULL, &msg),
         SC_EINVAL);
  tu_true(strstr(msg.text, "x = '0x10' is not a number: numbers are decimal") !=
              NULL,
          "hex message: %s", msg.text);
  sc_key_info ki = {"n", SC_KEY_INT, 0, NULL, 1, 1000000, 0, 0, NULL, ""};
  tu_int("1e3 is not an integer", sc_key_check(&ki, "1e3", NULL, &msg),
         SC_EINVAL);
  tu_true(strstr(msg.text, "n = 1e3 is not an integer: write integers in "
                           "decimal digits only") != NULL,
          "1e3 message: %s", msg.text);
  tu_int("99999999999 out of range", sc_key_check(&ki, "99999999999", NULL,
                                                  &msg), SC_EINVAL);
  tu_true(strstr(msg.text, "n = 99999999999 out of range (valid: [1, "
                           "1000000])") != NULL,
          "overflow message: %s", msg.text);
  tu_int("blank refused", sc_key_check(&k, " ", NULL, &msg), SC_EINVAL);
}

/* Mutations of the good scene and random bytes: every input is either
 * accepted or refused with a message; nothing crashes (the sanitizer
 * build checks memory).  A fixed LCG keeps the inputs reproducible. */
static void test_fuzz(void) {
  unsigned long long seed = 2385;
  const char alphabet[] = "[]=;#. \t\r\nabcdefgmnoprstuvxyz0123456789-+eE";
  char buf[2048];
  int refused_n = 0, accepted = 0, bad_msg = 0;
  for (int iter = 0; iter < 3000; iter++) {
    size_t n = strlen(good);
    memcpy(buf, good, n + 1);
    int edits = 1 + iter % 8;
    for (int k = 0; k < edits; k++) {
      seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
      size_t pos = (size_t)(seed >> 33) % (n ? n : 1);
      char c = alphabet[(seed >> 17) % (sizeof alphabet - 1)];
      if (iter % 3 == 0 && n + 1 < sizeof buf) { /* insert */
        memmove(buf + pos + 1, buf + pos, n - pos + 1);
        buf[pos] = c;
        n++;
      } else if (iter % 3 == 1 && n > 1) { /* delete */
        memmove(buf + pos, buf + pos + 1, n - pos);
        n--;
      } else {
        buf[pos] = c;
      }
    }
    if (iter % 10 == 9) { /* random bytes 1..255, lines of any length */
      size_t len = 1 + (size_t)(seed >> 40) % 600;
      for (size_t k = 0; k < len; k++) {
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        buf[k] = (char)(1 + (seed >> 33) % 255);
      }
      buf[len] = '\0';
    }
    sc_msg msg = {""};
    int st;
    sc_scene *sc = parse(buf, NULL, 0, NULL, &msg, &st);
    if (st == SC_OK) accepted++;
    else {
      refused_n++;
      if (!msg.text[0] || !strstr(msg.text, "x.ini")) bad_msg++;
    }
    sc_scene_free(sc);
  }
  printf("fuzz: %d accepted, %d refused\n", accepted, refused_n);
  tu_int("fuzz: every refusal names the file", bad_msg, 0);
  tu_true(refused_n > 1000 && accepted > 10,
          "fuzz: both outcomes seen (%d accepted, %d refused)", accepted,
          refused_n);
}

int main(void) {
  test_good();
  test_overrides();
  test_bad();
  test_default_dir();
  test_output();
  test_keys();
  test_fuzz();
  return tu_finish();
}
