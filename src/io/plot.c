/* Plots: readable gnuplot scripts written beside the data, rendered to
 * PNG by running gnuplot without a shell. */
#define _XOPEN_SOURCE 700 /* realpath() */

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "slipcont/io.h"

void sc_plot_quote(FILE *f, const char *text) {
  fputc('\'', f);
  for (const char *p = text; *p; p++) {
    if (*p == '\'') fputc('\'', f); /* '' is a quote inside '...' */
    if (*p != '\n') fputc(*p, f);
  }
  fputc('\'', f);
}

/* Characters of a title line: at the 1200-pixel terminal's 12-point font
 * (about 7 pixels a character) a line is centred over a plot that the key
 * outside leaves about 900 pixels wide, so a longer line is cut at both
 * ends of the picture; titles are broken before that. */
#define PLOT_TITLE_LINE 110

/* A title quoted for gnuplot, broken into lines after ", " where a line
 * would pass PLOT_TITLE_LINE characters: 'a, b' . "\n" . 'c' (one gnuplot
 * line; the pieces are joined by the string operator). */
static void quote_title(FILE *f, const char *title) {
  size_t n = strlen(title);
  if (n <= PLOT_TITLE_LINE) {
    sc_plot_quote(f, title);
    return;
  }
  char line[PLOT_TITLE_LINE + 1];
  const char *p = title;
  while (strlen(p) > PLOT_TITLE_LINE) {
    /* the last ", " that keeps the line within bounds */
    const char *cut = NULL;
    for (const char *q = p; q + 1 < p + PLOT_TITLE_LINE; q++)
      if (q[0] == ',' && q[1] == ' ') cut = q;
    if (!cut) break;
    size_t k = (size_t)(cut - p) + 1;
    memcpy(line, p, k);
    line[k] = '\0';
    sc_plot_quote(f, line);
    fputs(" . \"\\n\" . ", f);
    p = cut + 2;
  }
  sc_plot_quote(f, p);
}

void sc_plot_head(FILE *f, const char *png, const char *title,
                  const char *xlabel, const char *ylabel) {
  fputs("# Written by slipcont; edit freely and run `gnuplot THIS.gp`.\n", f);
  fputs("set terminal pngcairo size 1200,800 enhanced font 'Sans,12'\n", f);
  fputs("if (!exists(\"outfile\")) outfile = ", f);
  sc_plot_quote(f, png);
  fputs("\nset output outfile\n", f);
  fputs("set datafile separator ','\n", f);
  fputs("set key outside right top\n", f);
  fputs("set grid lc rgb '#dddddd'\n", f);
  fputs("set title ", f);
  quote_title(f, title);
  fputs("\nset xlabel ", f);
  sc_plot_quote(f, xlabel);
  fputs("\nset ylabel ", f);
  sc_plot_quote(f, ylabel);
  fputc('\n', f);
}

/* Whether parameter p acts with the map's options (only_with
 * "option=value", or "option>=N" for a whole-number option). */
static int param_acts(const sc_map *m, const sc_param_info *p) {
  if (!p->only_with) return 1;
  const char *eq = strchr(p->only_with, '=');
  if (!eq) return 1;
  int at_least = eq > p->only_with && eq[-1] == '>';
  char opt[64];
  size_t n = (size_t)(eq - p->only_with) - (size_t)at_least;
  if (n >= sizeof opt) return 1;
  memcpy(opt, p->only_with, n);
  opt[n] = '\0';
  const char *v = sc_map_get_option(m, opt);
  if (!v) return 1;
  if (at_least) return atol(v) >= atol(eq + 1);
  return strcmp(v, eq + 1) == 0;
}

char *sc_plot_title_except(const sc_map *m, const char *skip1,
                           const char *skip2, char *buf, size_t len) {
  const sc_model_type *t = sc_map_type(m);
  buf[0] = '\0';
  size_t used = 0;
  for (size_t i = 0; i < t->nparam && used < len; i++) {
    const char *n = t->params[i].name;
    if ((skip1 && strcmp(skip1, n) == 0) || (skip2 && strcmp(skip2, n) == 0) ||
        !param_acts(m, &t->params[i]))
      continue;
    int k = snprintf(buf + used, len - used, "%s%s = %.10g", used ? ", " : "",
                     n, sc_map_get_param(m, i));
    if (k > 0) used += (size_t)k;
  }
  /* The first option (bk2: driver) always, the others when changed. */
  for (size_t i = 0; i < t->noption && used < len; i++) {
    const char *v = sc_map_get_option(m, t->options[i].name);
    if (i && strcmp(v, t->options[i].values[0]) == 0) continue;
    int k = snprintf(buf + used, len - used, "%s%s %s", used ? ", " : "",
                     t->options[i].name, v);
    if (k > 0) used += (size_t)k;
  }
  if (!buf[0]) snprintf(buf, len, "%s", t->doc);
  return buf;
}

char *sc_plot_title(const sc_map *m, const char *skip, char *buf,
                    size_t len) {
  return sc_plot_title_except(m, skip, NULL, buf, len);
}

const char *sc_plot_label(const sc_map *m, const char *name) {
  /* The model tables carry the symbols of docs/model.md where they differ
   * from the names in code. */
  const sc_model_type *t = sc_map_type(m);
  if (strcmp(name, t->state_name) == 0)
    return t->state_label ? t->state_label : name;
  int i = sc_map_param_index(m, name);
  if (i >= 0 && t->params[i].symbol) return t->params[i].symbol;
  return name;
}

/* The full path of `gnuplot` on PATH into @p buf; 0 if there is none.
 * Resolved before fork() so that the child needs only execv(), which is
 * async-signal-safe (execvp() is not). */
static int find_gnuplot(char *buf, size_t len) {
  const char *path = getenv("PATH");
  if (!path) return 0;
  for (const char *p = path; *p;) {
    const char *colon = strchr(p, ':');
    size_t n = colon ? (size_t)(colon - p) : strlen(p);
    int k = n == 0 ? snprintf(buf, len, "./gnuplot")
                   : snprintf(buf, len, "%.*s/gnuplot", (int)n, p);
    struct stat sb;
    if (k > 0 && (size_t)k < len && stat(buf, &sb) == 0 &&
        S_ISREG(sb.st_mode) && access(buf, X_OK) == 0)
      return 1;
    if (!colon) break;
    p = colon + 1;
  }
  return 0;
}

int sc_plot_available(void) {
  char buf[4096];
  return find_gnuplot(buf, sizeof buf);
}

/* The last non-empty line of @p path into @p buf. */
static void last_line(const char *path, char *buf, size_t len) {
  buf[0] = '\0';
  FILE *f = fopen(path, "r");
  if (!f) return;
  char line[512];
  while (fgets(line, sizeof line, f)) {
    size_t n = strlen(line);
    while (n && (line[n - 1] == '\n' || line[n - 1] == '\r' ||
                 line[n - 1] == ' '))
      line[--n] = '\0';
    if (n) snprintf(buf, len, "%s", line);
  }
  fclose(f);
}

int sc_plot_render(const char *dir, const char *script, const char *png,
                   sc_msg *msg) {
  char exe[4096];
  if (!find_gnuplot(exe, sizeof exe))
    return sc_fail(msg, SC_EIO,
                   "gnuplot not found on PATH: %s/%s was written but not "
                   "rendered (install gnuplot, or set [output] plot = no)",
                   dir, script);
  if (exe[0] != '/') { /* a relative PATH entry: the child changes folder */
    char *abs = realpath(exe, NULL);
    if (abs && strlen(abs) < sizeof exe) memcpy(exe, abs, strlen(abs) + 1);
    free(abs);
  }
  /* Everything the child needs is prepared before fork(): after it only
   * async-signal-safe calls are made. */
  char tmp[512], arg[600], log[512], full[1024];
  snprintf(tmp, sizeof tmp, ".%s.%ld.tmp", png, (long)getpid());
  snprintf(arg, sizeof arg, "outfile='%s'", tmp);
  snprintf(log, sizeof log, "%s.log", script);
  char *argv[] = {"gnuplot", "-e", arg, (char *)script, NULL};
  int pfd[2];
  if (pipe(pfd) != 0)
    return sc_fail(msg, SC_EIO, "gnuplot: pipe failed (%s)", strerror(errno));
  fcntl(pfd[1], F_SETFD, FD_CLOEXEC);
  pid_t pid = fork();
  if (pid < 0) {
    close(pfd[0]);
    close(pfd[1]);
    return sc_fail(msg, SC_EIO, "gnuplot: fork failed (%s)", strerror(errno));
  }
  if (pid == 0) {
    close(pfd[0]);
    int e = 0;
    if (chdir(dir) != 0) e = errno;
    int fd = e ? -1 : open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (!e && fd < 0) e = errno;
    if (!e) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
      execv(exe, argv);
      e = errno;
    }
    ssize_t wr = write(pfd[1], &e, sizeof e);
    (void)wr;
    _exit(127);
  }
  close(pfd[1]);
  int child_err = 0;
  ssize_t got;
  do got = read(pfd[0], &child_err, sizeof child_err);
  while (got < 0 && errno == EINTR);
  close(pfd[0]);
  int wst;
  while (waitpid(pid, &wst, 0) < 0 && errno == EINTR) {
  }
  snprintf(full, sizeof full, "%s/%s", dir, log);
  if (got == (ssize_t)sizeof child_err && child_err)
    return sc_fail(msg, SC_EIO, "gnuplot could not be started for %s/%s (%s)",
                   dir, script, strerror(child_err));
  if (!WIFEXITED(wst) || WEXITSTATUS(wst) != 0) {
    char last[400];
    last_line(full, last, sizeof last);
    snprintf(full, sizeof full, "%s/%s", dir, tmp);
    unlink(full);
    return sc_fail(msg, SC_EIO, "gnuplot failed on %s/%s (%s %d; see %s): %s",
                   dir, script, WIFEXITED(wst) ? "exit status" : "signal",
                   WIFEXITED(wst) ? WEXITSTATUS(wst) : WTERMSIG(wst), log,
                   last);
  }
  unlink(full);
  char from[1024], to[1024];
  snprintf(from, sizeof from, "%s/%s", dir, tmp);
  snprintf(to, sizeof to, "%s/%s", dir, png);
  if (rename(from, to) != 0)
    return sc_fail(msg, SC_EIO, "gnuplot wrote no picture %s (%s)", to,
                   strerror(errno));
  return SC_OK;
}
