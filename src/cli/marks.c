/* The `marks` key of the branch and curve tasks: parameter values at
 * which every branch (or curve) records a user point (UZ); and the word
 * reader that every key holding a list (marks, auto-d, auto-at, also)
 * shares. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/tasks.h"

size_t sc_cli_next_word(const char **q, char *buf, size_t len) {
  const char *w = *q + strspn(*q, " \t");
  size_t n = strcspn(w, " \t");
  if (n == 0) return 0;
  snprintf(buf, len, "%.*s", (int)(n < len ? n : len - 1), w);
  *q = w + n;
  return n;
}

int sc_cli_marks(const sc_scene *s, const char *pname, double lo, double hi,
                 double *out, size_t *n, sc_msg *msg) {
  const char *q = sc_scene_text(s, "marks");
  *n = 0;
  if (!q) return SC_OK;
  const sc_map *m = sc_scene_map(s);
  const sc_param_info *pi = &sc_map_type(m)->params[sc_map_param_index(m, pname)];
  sc_key_info range = {pi->name, SC_KEY_REAL, 0, NULL, pi->lo, pi->hi,
                       pi->lo_open, pi->hi_open, NULL, NULL};
  char rtext[128], w[80];
  sc_key_range_text(&range, rtext, sizeof rtext);
  size_t len;
  for (int k = 1; (len = sc_cli_next_word(&q, w, sizeof w)) > 0; k++) {
    double v;
    if (len >= sizeof w || sc_parse_double(w, &v) || !isfinite(v))
      return sc_scene_fail_key(s, "task", "marks", msg,
                               "marks: value %d, '%s', is not a finite "
                               "number (valid: values of %s separated by "
                               "spaces)",
                               k, w, pname);
    if (sc_param_check(pi, v, NULL))
      return sc_scene_fail_key(s, "task", "marks", msg,
                               "marks: value %d, %s, is out of range of %s "
                               "(valid: %s)",
                               k, w, pname, rtext);
    if ((lo - v) * (hi - v) > 0)
      return sc_scene_fail_key(s, "task", "marks", msg,
                               "marks: value %d, %s, is outside [%.17g, "
                               "%.17g], where %s is continued (valid: "
                               "inside it)",
                               k, w, fmin(lo, hi), fmax(lo, hi), pname);
    if (*n == SC_CLI_MAXMARKS)
      return sc_scene_fail_key(s, "task", "marks", msg,
                               "marks: more than %d values (valid: at most "
                               "%d)",
                               SC_CLI_MAXMARKS, SC_CLI_MAXMARKS);
    out[(*n)++] = v;
  }
  return SC_OK;
}
