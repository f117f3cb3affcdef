/* The `show` key: which number of an n-component state a plot draws (a
 * component or the norm), read once for every task that has it
 * (tasks.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/tasks.h"

int sc_cli_show(const sc_scene *s, int *show, sc_msg *msg) {
  const sc_map *m = sc_scene_map(s);
  size_t n = sc_map_dim(m);
  const char *v = sc_scene_text(s, "show");
  *show = 0;
  if (!v) return SC_OK;
  if (strcmp(v, "norm") == 0) {
    *show = SC_CLI_SHOW_NORM;
    return SC_OK;
  }
  char *end;
  long k = strtol(v, &end, 10);
  if (end != v && !*end && k >= 1 && (size_t)k <= n) {
    *show = (int)(k - 1);
    return SC_OK;
  }
  char names[256] = "", c[32];
  for (size_t i = 0; i < n; i++) {
    const char *name = sc_map_state_component(m, i, c, sizeof c);
    if (strcmp(v, name) == 0) {
      *show = (int)i;
      return SC_OK;
    }
    if (strlen(names) + strlen(name) + 2 < sizeof names) {
      if (i) strcat(names, ", ");
      strcat(names, name);
    }
  }
  return sc_scene_fail_key(s, "task", "show", msg,
                           "show = %s: model %s has %zu state component%s "
                           "(valid: 1..%zu, a name (%s), or norm)",
                           v, sc_map_type(m)->name, n, n == 1 ? "" : "s", n,
                           names);
}

const char *sc_cli_show_label(const sc_map *m, int show, char *buf,
                              size_t len) {
  const char *state = sc_map_type(m)->state_name;
  if (show == SC_CLI_SHOW_NORM) {
    snprintf(buf, len, "|%s|", sc_plot_label(m, state));
  } else if (sc_map_dim(m) == 1) {
    snprintf(buf, len, "%s", sc_plot_label(m, state));
  } else {
    char c[32];
    snprintf(buf, len, "%s",
             sc_map_state_component(m, (size_t)show, c, sizeof c));
  }
  return buf;
}

const char *sc_cli_show_using(int show, size_t n, int col0, char *buf,
                              size_t len) {
  if (show != SC_CLI_SHOW_NORM) {
    snprintf(buf, len, "%d", col0 + show);
    return buf;
  }
  size_t u = (size_t)snprintf(buf, len, "(sqrt(");
  for (size_t i = 0; i < n && u < len; i++)
    u += (size_t)snprintf(buf + u, len - u, "%s$%d**2", i ? " + " : "",
                          col0 + (int)i);
  if (u < len) snprintf(buf + u, len - u, "))");
  return buf;
}

double sc_cli_show_value(int show, const double *x, size_t n) {
  if (show != SC_CLI_SHOW_NORM) return x[show];
  double s = 0;
  for (size_t i = 0; i < n; i++) s = hypot(s, x[i]);
  return s;
}
