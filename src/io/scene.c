#define _POSIX_C_SOURCE 200809L
/* Scenes: INI files read with inih, collected into a list of entries
 * (section, key, value, where it was set), overridden by --set and
 * --out, then validated section by section against the key tables: the
 * model's parameter and option tables (models.h), the accuracy fields
 * (common.h), the task kind's keys (sc_task_type) and [output]'s.
 * Nothing is computed or written before the whole scene has passed. */
#include <errno.h>
#include <fcntl.h>
#include <ini.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "slipcont/io.h"

typedef struct {
  char *section, *key, *value;
  int line;     /* > 0: line of the file; 0: an override */
  char *origin; /* the override as given ("--set model.v=0.1", "--out") */
} entry;

/* The sections a scene may have, and the line of each header. */
static const char *const sections[] = {"model", "task", "accuracy", "output"};
#define NSECTIONS (sizeof sections / sizeof sections[0])

struct sc_scene {
  char *name;
  char *source;
  entry *e;
  size_t n, cap;
  int section_line[NSECTIONS];
  sc_accuracy acc;
  sc_map *map;
  const sc_task_type *task;
  char *outdir; /* derived default when [output] dir is absent */
};

static const sc_key_info output_keys[] = {
    {"dir", SC_KEY_TEXT, 0, NULL, 0, 0, 0, 0, NULL,
     "output folder, created if needed (default: out/STEM, STEM the scene "
     "file's name without extension), relative to the working folder"},
    {"plot", SC_KEY_BOOL, 0, "yes", 0, 0, 0, 0, NULL,
     "render the gnuplot scripts to PNG (the scripts are always written)"},
};

static const sc_key_info accuracy_keys[] = {
    {"preset", SC_KEY_CHOICE, 0, "default", 0, 0, 0, 0, "fast|default|precise",
     "applied first, whatever its place in the section; then each field"},
    {"precision", SC_KEY_CHOICE, 0, "double", 0, 0, 0, 0, "double|quad",
     "arithmetic of bk2's exact flows: quad is __float128, slow, the "
     "reference (docs/accuracy.md)"},
};

const sc_key_info *sc_scene_section_keys(const char *section, size_t *n) {
  if (section && strcmp(section, "output") == 0) {
    *n = sizeof output_keys / sizeof output_keys[0];
    return output_keys;
  }
  if (section && strcmp(section, "accuracy") == 0) {
    *n = sizeof accuracy_keys / sizeof accuracy_keys[0];
    return accuracy_keys;
  }
  *n = 0;
  return NULL;
}

/* ------------------------------------------------------------------ */
/* Key tables                                                          */

static void fmt_bound(char *buf, size_t len, double x, int is_int) {
  if (isinf(x)) snprintf(buf, len, x > 0 ? "inf" : "-inf");
  else if (is_int) snprintf(buf, len, "%.0f", x);
  else snprintf(buf, len, "%.17g", x);
}

char *sc_key_range_text(const sc_key_info *k, char *buf, size_t len) {
  char lo[40], hi[40];
  switch (k->type) {
  case SC_KEY_REAL:
  case SC_KEY_STATE:
  case SC_KEY_INT:
    fmt_bound(lo, sizeof lo, k->lo, k->type == SC_KEY_INT);
    fmt_bound(hi, sizeof hi, k->hi, k->type == SC_KEY_INT);
    snprintf(buf, len, "%c%s, %s%c",
             k->type != SC_KEY_INT && k->lo_open ? '(' : '[', lo, hi,
             k->type != SC_KEY_INT && k->hi_open ? ')' : ']');
    break;
  case SC_KEY_CHOICE: snprintf(buf, len, "%s", k->choices); break;
  case SC_KEY_BOOL: snprintf(buf, len, "yes|no"); break;
  case SC_KEY_PARAM: snprintf(buf, len, "a parameter of the model"); break;
  case SC_KEY_TEXT: snprintf(buf, len, "non-empty text"); break;
  }
  return buf;
}

/* 1 if @p word is one of the '|'-separated words of @p list. */
static int in_list(const char *list, const char *word) {
  size_t n = strlen(word);
  for (const char *p = list; p && *p;) {
    const char *bar = strchr(p, '|');
    size_t k = bar ? (size_t)(bar - p) : strlen(p);
    if (k == n && strncmp(p, word, n) == 0) return 1;
    p = bar ? bar + 1 : NULL;
  }
  return 0;
}

/* A number that is not one: say whether it is too large or malformed,
 * and the rule (sc_number_syntax()). */
static int bad_number(const char *name, const char *value, const char *range,
                      sc_msg *msg) {
  char *end;
  double x = strtod(value, &end);
  if (end != value && isnan(x) + isinf(x) && sc_number_syntax(value) == 0 &&
      !strchr(value, 'x') && !strchr(value, 'X'))
    return sc_fail(msg, SC_EINVAL, "%s = %s is not a finite number (valid: %s)",
                   name, value, range);
  if (sc_number_syntax(value) != SC_NUM_NONE)
    return sc_fail(msg, SC_EINVAL,
                   "%s = %s is too large for a double (valid: %s)", name,
                   value, range);
  return sc_fail(msg, SC_EINVAL,
                 "%s = '%s' is not a number: numbers are decimal, like 0.025, "
                 "-3 or 1e-3 (valid: %s)",
                 name, value, range);
}

/* Split a state's text into numbers: their count (at most @p cap stored
 * in @p x), or -1 with the bad word copied to @p bad. */
static int state_words(const char *value, double *x, size_t cap, char *bad,
                       size_t badlen) {
  int n = 0;
  for (const char *p = value; *p;) {
    while (*p == ' ' || *p == '\t') p++;
    if (!*p) break;
    size_t k = strcspn(p, " \t");
    char word[128];
    snprintf(word, sizeof word, "%.*s", (int)(k < 127 ? k : 127), p);
    double v;
    if (sc_parse_double(word, &v)) {
      snprintf(bad, badlen, "%s", word);
      return -1;
    }
    if ((size_t)n < cap) x[n] = v;
    n++;
    p += k;
  }
  return n;
}

/* An SC_KEY_STATE value: the model's dimension of numbers, each finite
 * and in range.  A one-dimensional model reads it as one REAL. */
static int check_state(const sc_key_info *k, const char *value,
                       const sc_map *m, const char *range, sc_msg *msg) {
  size_t n = m ? sc_map_dim(m) : 0;
  sc_key_info one = *k;
  one.type = SC_KEY_REAL;
  if (n == 1) return sc_key_check(&one, value, m, msg);
  char bad[128] = "";
  double x[SC_MAXDIM];
  int got = state_words(value, x, SC_MAXDIM, bad, sizeof bad);
  if (got < 0) return sc_key_check(&one, bad, m, msg);
  char names[256] = "";
  for (size_t i = 0; m && i < n && strlen(names) < 200; i++) {
    char c[32];
    if (i) strcat(names, " ");
    strcat(names, sc_map_state_component(m, i, c, sizeof c));
  }
  if (got == 0 && !m)
    return sc_fail(msg, SC_EINVAL, "%s is empty (valid: numbers %s)", k->name,
                   range);
  if (got == 0 || (n && (size_t)got != n))
    return sc_fail(msg, SC_EINVAL,
                   "%s = '%s' holds %d number%s; model %s has %zu state "
                   "components: write %zu numbers (%s) separated by spaces",
                   k->name, value, got, got == 1 ? "" : "s",
                   sc_map_type(m)->name, n, n, names);
  for (int i = 0; i < got && i < SC_MAXDIM; i++)
    if (!((k->lo_open ? x[i] > k->lo : x[i] >= k->lo) &&
          (k->hi_open ? x[i] < k->hi : x[i] <= k->hi)))
      return sc_fail(msg, SC_EINVAL,
                     "%s = %s: component %d (%.17g) out of range (valid: %s)",
                     k->name, value, i + 1, x[i], range);
  return SC_OK;
}

int sc_key_check(const sc_key_info *k, const char *value, const sc_map *m,
                 sc_msg *msg) {
  char range[256];
  sc_key_range_text(k, range, sizeof range);
  switch (k->type) {
  case SC_KEY_REAL: {
    double x;
    if (sc_parse_double(value, &x)) return bad_number(k->name, value, range, msg);
    int ok = (k->lo_open ? x > k->lo : x >= k->lo) &&
             (k->hi_open ? x < k->hi : x <= k->hi);
    if (!ok)
      return sc_fail(msg, SC_EINVAL, "%s = %s out of range (valid: %s)",
                     k->name, value, range);
    return SC_OK;
  }
  case SC_KEY_INT: {
    double x;
    long l;
    (void)x;
    if (sc_parse_long(value, (long)k->lo, (long)k->hi, &l) == SC_OK)
      return SC_OK;
    int syn = sc_number_syntax(value);
    if (syn == SC_NUM_INT)
      return sc_fail(msg, SC_EINVAL, "%s = %s out of range (valid: %s)",
                     k->name, value, range);
    if (syn == SC_NUM_REAL)
      return sc_fail(msg, SC_EINVAL,
                     "%s = %s is not an integer: write integers in decimal "
                     "digits only, without a point or exponent (valid: %s)",
                     k->name, value, range);
    return sc_fail(msg, SC_EINVAL,
                   "%s = '%s' is not an integer: integers are decimal "
                   "digits, like 1000 (valid: %s)",
                   k->name, value, range);
  }
  case SC_KEY_CHOICE:
  case SC_KEY_BOOL:
    if (in_list(k->type == SC_KEY_BOOL ? "yes|no" : k->choices, value))
      return SC_OK;
    return sc_fail(msg, SC_EINVAL, "%s = '%s' is not valid (valid: %s)",
                   k->name, value, range);
  case SC_KEY_PARAM: {
    if (!m) return value[0] ? SC_OK : sc_fail(msg, SC_EINVAL, "%s is empty",
                                              k->name);
    if (sc_map_param_index(m, value) >= 0) return SC_OK;
    const sc_model_type *t = sc_map_type(m);
    char list[256] = "";
    for (size_t i = 0; i < t->nparam; i++) {
      if (i) strncat(list, "|", sizeof list - strlen(list) - 1);
      strncat(list, t->params[i].name, sizeof list - strlen(list) - 1);
    }
    return sc_fail(msg, SC_EINVAL,
                   "%s = '%s' is not a parameter of model %s (valid: %s)",
                   k->name, value, t->name, list);
  }
  case SC_KEY_STATE:
    return check_state(k, value, m, range, msg);
  case SC_KEY_TEXT:
    if (value[0]) return SC_OK;
    return sc_fail(msg, SC_EINVAL, "%s is empty (valid: %s)", k->name, range);
  }
  return sc_fail(msg, SC_EINVAL, "%s: unknown key type", k->name);
}

/* ------------------------------------------------------------------ */
/* Entries                                                             */

static int section_index(const char *name) {
  for (size_t i = 0; i < NSECTIONS; i++)
    if (strcmp(sections[i], name) == 0) return (int)i;
  return -1;
}

static const char *section_list(void) { return "model, task, accuracy, output"; }

static entry *find_entry(const sc_scene *s, const char *section,
                         const char *key) {
  for (size_t i = 0; i < s->n; i++)
    if (strcmp(s->e[i].section, section) == 0 && strcmp(s->e[i].key, key) == 0)
      return &s->e[i];
  return NULL;
}

static char *dup_text(const char *t) {
  size_t n = strlen(t) + 1;
  char *c = malloc(n);
  if (c) memcpy(c, t, n);
  return c;
}

static void entry_clear(entry *e) {
  free(e->section);
  free(e->key);
  free(e->value);
  free(e->origin);
}

static int add_entry(sc_scene *s, const char *section, const char *key,
                     const char *value, int line, const char *origin) {
  if (s->n == s->cap) {
    size_t cap = s->cap ? 2 * s->cap : 32;
    entry *e = realloc(s->e, cap * sizeof *e);
    if (!e) return SC_ENOMEM;
    s->e = e;
    s->cap = cap;
  }
  entry *e = &s->e[s->n];
  memset(e, 0, sizeof *e);
  e->section = dup_text(section);
  e->key = dup_text(key);
  e->value = dup_text(value);
  e->origin = origin ? dup_text(origin) : NULL;
  e->line = line;
  if (!e->section || !e->key || !e->value || (origin && !e->origin)) {
    entry_clear(e);
    return SC_ENOMEM;
  }
  s->n++;
  return SC_OK;
}

static void remove_entry(sc_scene *s, entry *e) {
  size_t i = (size_t)(e - s->e);
  entry_clear(e);
  memmove(&s->e[i], &s->e[i + 1], (s->n - i - 1) * sizeof *e);
  s->n--;
}

static char *origin_text(const sc_scene *s, const entry *e, char *buf,
                         size_t len) {
  if (e && e->origin) snprintf(buf, len, "%s", e->origin);
  else if (e) snprintf(buf, len, "%s:%d", s->name, e->line);
  else snprintf(buf, len, "%s", s->name);
  return buf;
}

/* Message for a problem with entry @p e: "ORIGIN: [section] detail". */
static int fail_entry(const sc_scene *s, const entry *e, sc_msg *msg,
                      const char *detail) {
  char where[SC_MSG_LEN];
  origin_text(s, e, where, sizeof where);
  return sc_fail(msg, SC_EINVAL, "%s: [%s] %s", where, e->section, detail);
}

/* Message for a missing required key of a section. */
static int fail_missing(const sc_scene *s, const char *section,
                        const char *key, const char *valid, sc_msg *msg) {
  int si = section_index(section);
  int line = si >= 0 ? s->section_line[si] : 0;
  char where[SC_MSG_LEN];
  if (line > 0) snprintf(where, sizeof where, "%s:%d", s->name, line);
  else snprintf(where, sizeof where, "%s", s->name);
  return sc_fail(msg, SC_EINVAL, "%s: [%s] missing required key '%s' (valid: %s)",
                 where, section, key, valid);
}

/* ------------------------------------------------------------------ */
/* Reading with inih                                                   */

typedef struct {
  sc_scene *s;
  const char *pos; /* next unread character of the source */
  int line;        /* line number of the line last handed to inih */
  int indented;    /* that line starts with blanks */
  int err_line;    /* line of the first problem, 0 if none */
  int status;      /* its status */
  sc_msg msg;      /* its message */
  const char *prev_section, *prev_key; /* last key seen, for continuations */
} reader_state;

/* The first control character of @p v (a byte below ' ' other than a
 * tab, or DEL), or -1: a value is printable text on one line, and what
 * is not would garble the messages and files that repeat it. */
static long control_at(const char *v) {
  for (long i = 0; v[i]; i++) {
    unsigned char c = (unsigned char)v[i];
    if ((c < 0x20 && c != '\t') || c == 0x7f) return i;
  }
  return -1;
}

static void record(reader_state *st, int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static void record(reader_state *st, int status, const char *fmt, ...) {
  if (st->err_line) return;
  char detail[SC_MSG_LEN];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(detail, sizeof detail, fmt, ap);
  va_end(ap);
  st->err_line = st->line;
  st->status = status;
  sc_fail(&st->msg, status, "%s:%d: %s", st->s->name, st->line, detail);
}

/* Section headers are seen here, in the raw lines, because inih only
 * reports keys: an empty unknown or repeated section is refused too. */
static void scan_header(reader_state *st, const char *line, size_t n) {
  size_t i = 0;
  while (i < n && (line[i] == ' ' || line[i] == '\t')) i++;
  if (i == n || line[i] != '[') return;
  size_t j = i + 1;
  while (j < n && line[j] != ']') j++;
  if (j == n) return; /* inih reports the syntax error */
  size_t t = j + 1;
  while (t < n && (line[t] == ' ' || line[t] == '\t')) t++;
  if (t < n && line[t] != ';' && line[t] != '#') {
    record(st, SC_EINVAL,
           "text after the section header: '%.*s' (a header is [name] "
           "alone on its line, or followed by a comment)",
           (int)(n - t), line + t);
    st->prev_key = NULL;
    return;
  }
  char name[128];
  size_t k = j - i - 1 < sizeof name - 1 ? j - i - 1 : sizeof name - 1;
  memcpy(name, line + i + 1, k);
  name[k] = '\0';
  int si = section_index(name);
  if (si < 0) {
    record(st, SC_EINVAL, "unknown section [%s] (valid: %s)", name,
           section_list());
  } else if (st->s->section_line[si]) {
    record(st, SC_EINVAL, "section [%s] repeated (first at line %d)", name,
           st->s->section_line[si]);
  } else {
    st->s->section_line[si] = st->line;
  }
  st->prev_key = NULL;
}

/* inih's line reader: one source line per call, so that the line number
 * of every key is known (this build of inih does not pass it).  Lines
 * too long for inih's buffer are refused rather than cut. */
static char *read_line(char *str, int num, void *stream) {
  reader_state *st = stream;
  if (!*st->pos) return NULL;
  /* A line ends at LF, CR LF or a lone CR (old Mac files). */
  size_t body0 = strcspn(st->pos, "\r\n");
  size_t n = body0;
  if (st->pos[n] == '\r') n++;
  if (st->pos[n] == '\n' && (n == body0 || st->pos[n - 1] == '\r')) n++;
  st->line++;
  st->indented = st->pos[0] == ' ' || st->pos[0] == '\t';
  size_t cap = num > 2 ? (size_t)num - 2 : 0; /* room for "\n\0" */
  size_t body = body0;
  if (body > cap) {
    record(st, SC_EINVAL, "line too long (%zu characters; limit %zu)", body,
           cap);
    body = 0;
  } else {
    scan_header(st, st->pos, body);
  }
  memcpy(str, st->pos, body);
  str[body] = '\n';
  str[body + 1] = '\0';
  st->pos += n;
  return str;
}

static int on_key(void *user, const char *section, const char *name,
                  const char *value) {
  reader_state *st = user;
  sc_scene *s = st->s;
  if (!section[0]) {
    record(st, SC_EINVAL, "key '%s' outside any section (valid sections: %s)",
           name, section_list());
    return 1;
  }
  if (section_index(section) < 0) return 1; /* reported by scan_header */
  if (st->indented && st->prev_key && strcmp(st->prev_key, name) == 0 &&
      strcmp(st->prev_section, section) == 0) {
    record(st, SC_EINVAL,
           "[%s] line starts with blanks: continuation lines are not "
           "supported (remove the leading blanks)",
           section);
    return 1;
  }
  long bad = control_at(value);
  if (bad >= 0) {
    record(st, SC_EINVAL,
           "[%s] %s: control character 0x%02x at position %ld of the value "
           "(valid: printable text)",
           section, name, (unsigned char)value[bad], bad + 1);
    return 1;
  }
  entry *old = find_entry(s, section, name);
  if (old) {
    record(st, SC_EINVAL, "[%s] duplicate key '%s' (first at line %d)",
           section, name, old->line);
    return 1;
  }
  if (add_entry(s, section, name, value, st->line, NULL)) {
    record(st, SC_ENOMEM, "out of memory");
    return 0;
  }
  st->prev_section = s->e[s->n - 1].section;
  st->prev_key = s->e[s->n - 1].key;
  return 1;
}

/* ------------------------------------------------------------------ */
/* Overrides                                                           */

static int apply_override(sc_scene *s, const char *section, const char *key,
                          const char *value, const char *origin,
                          sc_msg *msg) {
  if (section_index(section) < 0)
    return sc_fail(msg, SC_EINVAL, "%s: unknown section [%s] (valid: %s)",
                   origin, section, section_list());
  if (!key[0])
    return sc_fail(msg, SC_EINVAL, "%s: expected section.key=value", origin);
  entry *old = find_entry(s, section, key);
  if (old) remove_entry(s, old); /* as if set again at the end */
  if (add_entry(s, section, key, value, 0, origin))
    return sc_fail(msg, SC_ENOMEM, "%s: out of memory", origin);
  return SC_OK;
}

static void trim(char *t) {
  size_t n = strlen(t);
  while (n && (t[n - 1] == ' ' || t[n - 1] == '\t')) t[--n] = '\0';
  size_t i = 0;
  while (t[i] == ' ' || t[i] == '\t') i++;
  memmove(t, t + i, n - i + 1);
}

static int apply_set(sc_scene *s, const char *set, sc_msg *msg) {
  char origin[SC_MSG_LEN], buf[SC_MSG_LEN];
  long bad = control_at(set);
  if (bad >= 0) {
    snprintf(buf, sizeof buf, "%s", set);
    for (char *p = buf; *p; p++)
      if (control_at(p) == 0) *p = '?';
    const char *eq = strchr(set, '=');
    long at = eq && eq - set < bad ? bad - (eq + 1 - set) : bad;
    return sc_fail(msg, SC_EINVAL,
                   "--set %s: control character 0x%02x at position %ld of "
                   "the %s (shown as '?'; valid: printable text)",
                   buf, (unsigned char)set[bad], at + 1,
                   eq && eq - set < bad ? "value" : "override");
  }
  snprintf(origin, sizeof origin, "--set %s", set);
  if (strlen(set) >= sizeof buf)
    return sc_fail(msg, SC_EINVAL, "--set: override too long");
  memcpy(buf, set, strlen(set) + 1);
  char *eq = strchr(buf, '=');
  char *dot = strchr(buf, '.');
  if (!eq || !dot || dot > eq)
    return sc_fail(msg, SC_EINVAL, "%s: expected section.key=value", origin);
  *eq = '\0';
  *dot = '\0';
  char *section = buf, *key = dot + 1, *value = eq + 1;
  trim(section);
  trim(key);
  trim(value);
  return apply_override(s, section, key, value, origin, msg);
}

/* ------------------------------------------------------------------ */
/* Validation                                                          */

static int check_accuracy(sc_scene *s, sc_msg *msg) {
  sc_msg m;
  char detail[SC_MSG_LEN];
  sc_accuracy_preset(&s->acc, "default", NULL);
  entry *p = find_entry(s, "accuracy", "preset");
  if (p) {
    if (sc_key_check(&accuracy_keys[0], p->value, NULL, &m))
      return fail_entry(s, p, msg, m.text);
    sc_accuracy_preset(&s->acc, p->value, NULL);
  }
  for (size_t i = 0; i < s->n; i++) {
    entry *e = &s->e[i];
    if (strcmp(e->section, "accuracy") != 0 || e == p) continue;
    if (sc_accuracy_set(&s->acc, e->key, e->value, &m)) {
      snprintf(detail, sizeof detail, "%s", m.text);
      return fail_entry(s, e, msg, detail);
    }
  }
  if (sc_accuracy_check(&s->acc, &m)) {
    /* Only reachable if a preset itself were bad: name the section. */
    return sc_fail(msg, SC_EINVAL, "%s: [accuracy] %s", s->name, m.text);
  }
  return SC_OK;
}

static void model_keys_text(const sc_model_type *t, char *buf, size_t len) {
  snprintf(buf, len, "name");
  for (size_t i = 0; i < t->nparam; i++) {
    strncat(buf, ", ", len - strlen(buf) - 1);
    strncat(buf, t->params[i].name, len - strlen(buf) - 1);
  }
  for (size_t i = 0; i < t->noption; i++) {
    strncat(buf, ", ", len - strlen(buf) - 1);
    strncat(buf, t->options[i].name, len - strlen(buf) - 1);
  }
  for (size_t i = 0; i < t->ndata; i++) {
    strncat(buf, ", ", len - strlen(buf) - 1);
    strncat(buf, t->data[i].name, len - strlen(buf) - 1);
  }
}

static int is_data_key(const sc_model_type *t, const char *key) {
  for (size_t i = 0; i < t->ndata; i++)
    if (strcmp(t->data[i].name, key) == 0) return 1;
  return 0;
}

/* The model's data keys (the chain's thresholds), after its parameters
 * and options and in the model's table order, whatever the file's: a
 * list's length is checked against the options, and a key's relations
 * with the data keys before it in the table. */
static int set_model_data(sc_scene *s, const sc_model_type *t, sc_msg *msg) {
  sc_msg m;
  for (size_t k = 0; k < t->ndata; k++) {
    entry *e = find_entry(s, "model", t->data[k].name);
    if (e && sc_map_set_data(s->map, e->key, e->value, &m))
      return fail_entry(s, e, msg, m.text);
  }
  return SC_OK;
}

static void model_names_text(char *buf, size_t len) {
  buf[0] = '\0';
  for (size_t i = 0; i < sc_model_count(); i++) {
    if (i) strncat(buf, "|", len - strlen(buf) - 1);
    strncat(buf, sc_model_get(i)->name, len - strlen(buf) - 1);
  }
}

static int check_model(sc_scene *s, sc_msg *msg) {
  char list[512], detail[SC_MSG_LEN];
  sc_msg m;
  model_names_text(list, sizeof list);
  entry *ne = find_entry(s, "model", "name");
  if (!ne) return fail_missing(s, "model", "name", list, msg);
  const sc_model_type *t = sc_model_find(ne->value);
  if (!t) {
    snprintf(detail, sizeof detail, "name = '%.64s' is not a model (valid: %.300s)",
             ne->value, list);
    return fail_entry(s, ne, msg, detail);
  }
  int st = sc_map_alloc_type(t, &s->acc, &s->map, &m);
  if (st) return fail_entry(s, ne, msg, m.text);
  for (size_t i = 0; i < s->n; i++) {
    entry *e = &s->e[i];
    if (strcmp(e->section, "model") != 0 || e == ne || is_data_key(t, e->key))
      continue;
    int pi = sc_map_param_index(s->map, e->key);
    if (pi >= 0) {
      /* Range from the model's table; the message quotes the value as
       * written rather than its binary rounding. */
      const sc_param_info *p = &t->params[pi];
      sc_key_info k = {p->name, SC_KEY_REAL, 0, NULL, p->lo, p->hi,
                       p->lo_open, p->hi_open, NULL, p->doc};
      if (sc_key_check(&k, e->value, NULL, &m))
        return fail_entry(s, e, msg, m.text);
      double x;
      sc_parse_double(e->value, &x);
      if (sc_map_set_param(s->map, (size_t)pi, x, &m))
        return fail_entry(s, e, msg, m.text);
      continue;
    }
    if (sc_map_get_option(s->map, e->key)) {
      if (sc_map_set_option(s->map, e->key, e->value, &m))
        return fail_entry(s, e, msg, m.text);
      continue;
    }
    model_keys_text(t, list, sizeof list);
    snprintf(detail, sizeof detail, "unknown key '%.64s' for model %s (valid: %.300s)",
             e->key, t->name, list);
    return fail_entry(s, e, msg, detail);
  }
  return set_model_data(s, t, msg);
}

static const sc_key_info *find_key(const sc_key_info *keys, size_t n,
                                   const char *name) {
  for (size_t i = 0; i < n; i++)
    if (strcmp(keys[i].name, name) == 0) return &keys[i];
  return NULL;
}

static void keys_text(const char *first, const sc_key_info *keys, size_t n,
                      char *buf, size_t len) {
  snprintf(buf, len, "%s", first ? first : "");
  for (size_t i = 0; i < n; i++) {
    if (buf[0]) strncat(buf, ", ", len - strlen(buf) - 1);
    strncat(buf, keys[i].name, len - strlen(buf) - 1);
  }
}

/* Check every key of @p section against @p keys (and required ones). */
static int check_keys(sc_scene *s, const char *section, const char *skip,
                      const sc_key_info *keys, size_t nkeys, sc_msg *msg) {
  char list[512], detail[SC_MSG_LEN];
  sc_msg m;
  for (size_t i = 0; i < s->n; i++) {
    entry *e = &s->e[i];
    if (strcmp(e->section, section) != 0) continue;
    if (skip && strcmp(e->key, skip) == 0) continue;
    const sc_key_info *k = find_key(keys, nkeys, e->key);
    if (!k) {
      keys_text(skip, keys, nkeys, list, sizeof list);
      if (s->task && strcmp(section, "task") == 0)
        snprintf(detail, sizeof detail,
                 "unknown key '%.64s' for kind %.64s (valid: %.300s)", e->key,
                 s->task->kind, list);
      else
        snprintf(detail, sizeof detail, "unknown key '%.64s' (valid: %.300s)", e->key,
                 list);
      return fail_entry(s, e, msg, detail);
    }
    if (sc_key_check(k, e->value, s->map, &m))
      return fail_entry(s, e, msg, m.text);
  }
  for (size_t i = 0; i < nkeys; i++) {
    if (!keys[i].required || find_entry(s, section, keys[i].name)) continue;
    char range[256];
    sc_key_range_text(&keys[i], range, sizeof range);
    if (keys[i].type == SC_KEY_PARAM && s->map) {
      const sc_model_type *t = sc_map_type(s->map);
      range[0] = '\0';
      for (size_t j = 0; j < t->nparam; j++) {
        if (j) strncat(range, "|", sizeof range - strlen(range) - 1);
        strncat(range, t->params[j].name, sizeof range - strlen(range) - 1);
      }
    }
    return fail_missing(s, section, keys[i].name, range, msg);
  }
  return SC_OK;
}

static int check_task(sc_scene *s, const sc_scene_options *o, sc_msg *msg) {
  char list[512] = "", detail[SC_MSG_LEN];
  size_t ntasks = o ? o->ntasks : 0;
  for (size_t i = 0; i < ntasks; i++) {
    if (i) strncat(list, "|", sizeof list - strlen(list) - 1);
    strncat(list, o->tasks[i]->kind, sizeof list - strlen(list) - 1);
  }
  entry *ke = find_entry(s, "task", "kind");
  if (!ke) return fail_missing(s, "task", "kind", list, msg);
  for (size_t i = 0; i < ntasks; i++)
    if (strcmp(o->tasks[i]->kind, ke->value) == 0) s->task = o->tasks[i];
  if (!s->task) {
    snprintf(detail, sizeof detail, "kind = '%.64s' is not a task (valid: %.300s)",
             ke->value, list);
    return fail_entry(s, ke, msg, detail);
  }
  int st = check_keys(s, "task", "kind", s->task->keys, s->task->nkeys, msg);
  if (st) return st;
  return s->task->check ? s->task->check(s, msg) : SC_OK;
}

static int check_output(sc_scene *s, sc_msg *msg) {
  int st = check_keys(s, "output", NULL, output_keys,
                      sizeof output_keys / sizeof output_keys[0], msg);
  if (st) return st;
  if (find_entry(s, "output", "dir")) return SC_OK;
  /* out/STEM */
  const char *base = strrchr(s->name, '/');
  base = base ? base + 1 : s->name;
  size_t n = strlen(base);
  const char *dot = strrchr(base, '.');
  if (dot && dot != base) n = (size_t)(dot - base);
  s->outdir = malloc(n + 5);
  if (!s->outdir) return sc_fail(msg, SC_ENOMEM, "%s: out of memory", s->name);
  memcpy(s->outdir, "out/", 4);
  memcpy(s->outdir + 4, base, n);
  s->outdir[n + 4] = '\0';
  if (n == 0) s->outdir[3] = '\0'; /* "out" */
  return SC_OK;
}

/* ------------------------------------------------------------------ */
/* Construction                                                        */

int sc_scene_parse(const char *name, const char *text,
                   const sc_scene_options *opts, sc_scene **out,
                   sc_msg *msg) {
  *out = NULL;
  sc_scene *s = calloc(1, sizeof *s);
  if (!s) return sc_fail(msg, SC_ENOMEM, "%s: out of memory", name);
  s->name = dup_text(name);
  s->source = dup_text(text);
  if (!s->name || !s->source) {
    sc_scene_free(s);
    return sc_fail(msg, SC_ENOMEM, "%s: out of memory", name);
  }
  if (strlen(text) > SC_SCENE_MAXBYTES) {
    sc_scene_free(s);
    return sc_fail(msg, SC_EINVAL, "%s: scene too large (limit %d bytes)",
                   name, SC_SCENE_MAXBYTES);
  }
  reader_state st = {.s = s, .pos = s->source};
  int rc = ini_parse_stream(read_line, &st, on_key, &st);
  int status = SC_OK;
  if (rc > 0 && (!st.err_line || rc < st.err_line)) {
    status = sc_fail(msg, SC_EINVAL,
                     "%s:%d: syntax error (expected [section], key = value, "
                     "or a comment starting with ; or #)",
                     name, rc);
  } else if (st.err_line) {
    status = st.status;
    if (msg) *msg = st.msg;
  } else if (rc < 0) {
    status = sc_fail(msg, SC_ENOMEM, "%s: out of memory while parsing", name);
  }
  for (size_t i = 0; !status && opts && i < opts->nsets; i++)
    status = apply_set(s, opts->sets[i], msg);
  if (!status && opts && opts->out_dir)
    status = apply_override(s, "output", "dir", opts->out_dir, "--out", msg);
  if (!status) status = check_accuracy(s, msg);
  if (!status) status = check_model(s, msg);
  if (!status) status = check_task(s, opts, msg);
  if (!status) status = check_output(s, msg);
  if (status) {
    sc_scene_free(s);
    return status;
  }
  *out = s;
  return SC_OK;
}

/* What a file that is not a regular one is, for a message. */
static const char *file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a pipe (FIFO)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "neither a file nor a folder";
}

int sc_input_open(const char *path, const char *what, long long max_bytes,
                  FILE **f, sc_msg *msg) {
  *f = NULL;
  /* Opened without blocking (a FIFO would wait for a writer forever),
   * then refused unless it is a regular file. */
  int fd = open(path, O_RDONLY | O_NONBLOCK);
  if (fd < 0)
    return sc_fail(msg, SC_EIO, "%s: cannot open %s (%s)", path, what,
                   strerror(errno));
  struct stat sb;
  if (fstat(fd, &sb) != 0) {
    int err = errno;
    close(fd);
    return sc_fail(msg, SC_EIO, "%s: cannot read %s (%s)", path, what,
                   strerror(err));
  }
  if (!S_ISREG(sb.st_mode)) {
    close(fd);
    return sc_fail(msg, SC_EINVAL,
                   "%s: not a regular file: it is %s (%s must be a "
                   "regular file)",
                   path, file_kind(sb.st_mode), what);
  }
  if ((long long)sb.st_size > max_bytes) {
    close(fd);
    return sc_fail(msg, SC_EINVAL,
                   "%s: %s is too large (%lld bytes; limit %lld bytes)", path,
                   what, (long long)sb.st_size, max_bytes);
  }
  *f = fdopen(fd, "rb");
  if (!*f) {
    close(fd);
    return sc_fail(msg, SC_ENOMEM, "%s: out of memory", path);
  }
  return SC_OK;
}

int sc_scene_load(const char *path, const sc_scene_options *opts,
                  sc_scene **out, sc_msg *msg) {
  *out = NULL;
  FILE *f;
  int ost = sc_input_open(path, "the scene file", SC_SCENE_MAXBYTES, &f, msg);
  if (ost) return ost;
  char *text = malloc(SC_SCENE_MAXBYTES + 2);
  if (!text) {
    fclose(f);
    return sc_fail(msg, SC_ENOMEM, "%s: out of memory", path);
  }
  size_t n = fread(text, 1, SC_SCENE_MAXBYTES + 1, f);
  int err = ferror(f);
  fclose(f);
  if (err) {
    free(text);
    return sc_fail(msg, SC_EIO, "%s: cannot read the scene file", path);
  }
  if (n > SC_SCENE_MAXBYTES) {
    free(text);
    return sc_fail(msg, SC_EINVAL, "%s: scene too large (limit %d bytes)",
                   path, SC_SCENE_MAXBYTES);
  }
  text[n] = '\0';
  if (strlen(text) != n) {
    free(text);
    return sc_fail(msg, SC_EINVAL, "%s: not a text file (contains NUL bytes)",
                   path);
  }
  int st = sc_scene_parse(path, text, opts, out, msg);
  free(text);
  return st;
}

void sc_scene_free(sc_scene *s) {
  if (!s) return;
  for (size_t i = 0; i < s->n; i++) entry_clear(&s->e[i]);
  free(s->e);
  sc_map_free(s->map);
  free(s->outdir);
  free(s->name);
  free(s->source);
  free(s);
}

/* ------------------------------------------------------------------ */
/* Getters                                                             */

const char *sc_scene_name(const sc_scene *s) { return s->name; }
const char *sc_scene_source(const sc_scene *s) { return s->source; }
sc_map *sc_scene_map(const sc_scene *s) { return s->map; }
const sc_accuracy *sc_scene_accuracy(const sc_scene *s) { return &s->acc; }
const sc_task_type *sc_scene_task(const sc_scene *s) { return s->task; }

const char *sc_scene_output_dir(const sc_scene *s) {
  entry *e = find_entry(s, "output", "dir");
  return e ? e->value : s->outdir;
}

int sc_scene_plot(const sc_scene *s) {
  const char *v = sc_scene_value(s, "output", "plot");
  return v && strcmp(v, "yes") == 0;
}

const char *sc_scene_value(const sc_scene *s, const char *section,
                           const char *key) {
  entry *e = find_entry(s, section, key);
  if (e) return e->value;
  const sc_key_info *k = NULL;
  size_t n;
  const sc_key_info *keys = sc_scene_section_keys(section, &n);
  if (keys) k = find_key(keys, n, key);
  else if (strcmp(section, "task") == 0 && s->task)
    k = find_key(s->task->keys, s->task->nkeys, key);
  return k ? k->def : NULL;
}

double sc_scene_real(const sc_scene *s, const char *key) {
  const char *v = sc_scene_value(s, "task", key);
  double x;
  return v && sc_parse_double(v, &x) == SC_OK ? x : NAN;
}

size_t sc_scene_state(const sc_scene *s, const char *key, double *x,
                      size_t n) {
  const char *v = sc_scene_value(s, "task", key);
  char bad[128];
  int got = v ? state_words(v, x, n, bad, sizeof bad) : 0;
  return got > 0 ? (size_t)got : 0;
}

long sc_scene_int(const sc_scene *s, const char *key) {
  const char *v = sc_scene_value(s, "task", key);
  long l;
  return v && sc_parse_long(v, LONG_MIN, LONG_MAX, &l) == SC_OK ? l : 0;
}

const char *sc_scene_text(const sc_scene *s, const char *key) {
  return sc_scene_value(s, "task", key);
}

int sc_scene_flag(const sc_scene *s, const char *key) {
  const char *v = sc_scene_value(s, "task", key);
  return v && strcmp(v, "yes") == 0;
}

char *sc_scene_origin(const sc_scene *s, const char *section,
                      const char *key, char *buf, size_t len) {
  return origin_text(s, find_entry(s, section, key), buf, len);
}

int sc_scene_fail_key(const sc_scene *s, const char *section,
                      const char *key, sc_msg *msg, const char *fmt, ...) {
  char where[SC_MSG_LEN], detail[SC_MSG_LEN];
  sc_scene_origin(s, section, key, where, sizeof where);
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(detail, sizeof detail, fmt, ap);
  va_end(ap);
  return sc_fail(msg, SC_EINVAL, "%s: [%s] %s", where, section, detail);
}
