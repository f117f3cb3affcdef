/* Help texts, the model list and the key tables, all generated from the
 * tables of the models (models.h), the accuracy object (common.h), the
 * scene sections (io.h) and the tasks (tasks.h). */
#include "cli/help.h"

#include <math.h>
#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/tasks.h"

/* The shortest %.Ng text that reads back as exactly @p x. */
static const char *exact(double x, char *buf, size_t len) {
  if (x == floor(x) && fabs(x) < 1e15) {
    snprintf(buf, len, "%.0f", x);
    return buf;
  }
  for (int prec = 1; prec <= 17; prec++) {
    snprintf(buf, len, "%.*g", prec, x);
    if (strtod(buf, NULL) == x) break;
  }
  return buf;
}

static void key_default(const sc_key_info *k, char *buf, size_t len) {
  if (k->required) snprintf(buf, len, "required");
  else if (k->def) snprintf(buf, len, "%s", k->def);
  else snprintf(buf, len, "derived");
}

static void param_range(const sc_param_info *p, char *buf, size_t len) {
  sc_key_info k = {p->name, SC_KEY_REAL, 0, NULL, p->lo, p->hi,
                   p->lo_open, p->hi_open, NULL, NULL};
  sc_key_range_text(&k, buf, len);
}

/* Markdown table cells must not contain '|': write choices with ", ". */
static void md_cell(FILE *f, const char *text) {
  for (const char *p = text; *p; p++) {
    if (*p == '|') fputs("\\|", f);
    else fputc(*p, f);
  }
}

static void key_rows(FILE *f, const sc_key_info *keys, size_t n, int md) {
  char range[256], def[128];
  for (size_t i = 0; i < n; i++) {
    sc_key_range_text(&keys[i], range, sizeof range);
    key_default(&keys[i], def, sizeof def);
    if (md) {
      fprintf(f, "| `%s` | ", keys[i].name);
      md_cell(f, range);
      fputs(" | ", f);
      md_cell(f, def);
      fputs(" | ", f);
      md_cell(f, keys[i].doc);
      fputs(" |\n", f);
    } else {
      fprintf(f, "  %-20s %-24s default %-10s %s\n", keys[i].name, range, def,
              keys[i].doc);
    }
  }
}

static void table_head(FILE *f, int md) {
  if (md) fputs("| key | valid values | default | meaning |\n|---|---|---|---|\n", f);
}

void sc_cli_print_task_keys(FILE *f, const sc_cli_task *t, int md) {
  if (md) {
    fprintf(f, "#### `kind = %s`\n\n", t->type.kind);
    md_cell(f, t->type.doc);
    fputs(".\n\nWrites: ", f);
    md_cell(f, t->outputs);
    fputs(".\n\n", f);
    table_head(f, 1);
  } else {
    fprintf(f, "[task] kind = %s: %s\n  writes: %s\n", t->type.kind,
            t->type.doc, t->outputs);
  }
  key_rows(f, t->type.keys, t->type.nkeys, md);
  fputc('\n', f);
}

/* The state a model's map acts on: "d", or "(x, y)" for n > 1. */
static char *state_text(const sc_model_type *t, char *buf, size_t len) {
  if (t->dim <= 1) {
    snprintf(buf, len, "%s", t->state_name);
    return buf;
  }
  size_t used = (size_t)snprintf(buf, len, "(");
  for (size_t i = 0; i < t->dim && used < len; i++) {
    if (t->state_names)
      used += (size_t)snprintf(buf + used, len - used, "%s%s", i ? ", " : "",
                               t->state_names[i]);
    else
      used += (size_t)snprintf(buf + used, len - used, "%s%s%zu",
                               i ? ", " : "", t->state_name, i + 1);
  }
  if (used < len) snprintf(buf + used, len - used, ")");
  return buf;
}

void sc_cli_print_model(FILE *f, const sc_model_type *t, int md) {
  char range[256], vals[256], state[256];
  state_text(t, state, sizeof state);
  if (md) {
    fprintf(f, "#### `name = %s`\n\n", t->name);
    md_cell(f, t->doc);
    fprintf(f, "; the map acts on `%s`.\n\n", state);
    table_head(f, 1);
  } else {
    fprintf(f, "%s: %s (state %s)\n", t->name, t->doc, state);
  }
  /* One width for the column of valid values, so that the defaults and
   * docs line up below the longest ("coulomb|velocity-weakening"). */
  int w = 24;
  for (size_t i = 0; i < t->nparam; i++) {
    param_range(&t->params[i], range, sizeof range);
    if ((int)strlen(range) > w) w = (int)strlen(range);
  }
  for (size_t i = 0; i < t->noption; i++) {
    sc_option_values_text(&t->options[i], vals, sizeof vals);
    if ((int)strlen(vals) > w) w = (int)strlen(vals);
  }
  for (size_t i = 0; i < t->nparam; i++) {
    param_range(&t->params[i], range, sizeof range);
    char num[40];
    exact(t->params[i].def, num, sizeof num);
    if (md) {
      fprintf(f, "| `%s` | %s | %s | ", t->params[i].name, range, num);
      md_cell(f, t->params[i].doc);
      fputs(" |\n", f);
    } else {
      fprintf(f, "  %-10s %-*s default %-8s %s\n", t->params[i].name, w,
              range, num, t->params[i].doc);
    }
  }
  for (size_t i = 0; i < t->noption; i++) {
    sc_option_values_text(&t->options[i], vals, sizeof vals);
    if (md) {
      fprintf(f, "| `%s` | ", t->options[i].name);
      md_cell(f, vals);
      fprintf(f, " | %s | ", t->options[i].values[0]);
      md_cell(f, t->options[i].doc);
      fputs(" |\n", f);
    } else {
      fprintf(f, "  %-10s %-*s default %-8s %s\n", t->options[i].name, w,
              vals, t->options[i].values[0], t->options[i].doc);
    }
  }
  for (size_t i = 0; i < t->ndata; i++) {
    const char *def = t->data[i].def[0] ? t->data[i].def : "-";
    if (md) {
      fprintf(f, "| `%s` | data | %s | ", t->data[i].name, def);
      md_cell(f, t->data[i].doc);
      fputs(" |\n", f);
    } else {
      fprintf(f, "  %-10s %-*s default %-8s %s\n", t->data[i].name, w,
              "data", def, t->data[i].doc);
    }
  }
  fputc('\n', f);
}

void sc_cli_print_models(FILE *f, int md) {
  for (size_t i = 0; i < sc_model_count(); i++)
    sc_cli_print_model(f, sc_model_get(i), md);
}

static void accuracy_rows(FILE *f, int md) {
  size_t n;
  const sc_key_info *k = sc_scene_section_keys("accuracy", &n);
  key_rows(f, k, n, md);
  sc_accuracy p[3];
  sc_accuracy_preset(&p[0], "fast", NULL);
  sc_accuracy_preset(&p[1], "default", NULL);
  sc_accuracy_preset(&p[2], "precise", NULL);
  if (!md)
    fprintf(f, "  %-20s %-24s %-24s %-24s\n", "field", "fast", "default",
            "precise");
  for (size_t i = 0; i < sc_accuracy_nfields(); i++) {
    const char *name = sc_accuracy_field_name(i);
    char v[3][40];
    for (int j = 0; j < 3; j++)
      exact(sc_accuracy_field_value(&p[j], i), v[j], sizeof v[j]);
    double lo, hi;
    char range[96];
    int is_count = sc_accuracy_field_range(i, &lo, &hi);
    if (is_count) snprintf(range, sizeof range, "%.0f .. %.0f", lo, hi);
    else if (lo == DBL_MIN) snprintf(range, sizeof range, "(0, %g]", hi);
    else snprintf(range, sizeof range, "[%.3g, %g]", lo, hi);
    if (md)
      fprintf(f, "| `%s` | %s | %s (fast: %s, precise: %s) | %s |\n", name,
              range, v[1], v[0], v[2], sc_accuracy_field_doc(i));
    else
      fprintf(f, "  %-20s %-24s %-24s %-24s\n", name, v[0], v[1], v[2]);
  }
}

void sc_cli_print_keys(FILE *f, int md) {
  size_t n;
  if (md) {
    fputs("<!-- Generated by `slipcont keys --markdown`: do not edit by "
          "hand. -->\n\n",
          f);
    fputs("### `[model]`\n\n`name` (required) picks the model; the other "
          "keys are its parameters and options.\n\n",
          f);
  } else {
    fputs("[model]: name = MODEL (required), then its parameters and "
          "options:\n\n",
          f);
  }
  sc_cli_print_models(f, md);
  if (md)
    fputs("### `[task]`\n\n`kind` (required) picks the task; the other keys "
          "depend on it.\n\n",
          f);
  for (size_t i = 0; i < sc_cli_task_count(); i++)
    sc_cli_print_task_keys(f, sc_cli_task_get(i), md);
  if (md) {
    fputs("### `[accuracy]`\n\n", f);
    table_head(f, 1);
  } else {
    fputs("[accuracy]: preset, then any field:\n", f);
  }
  accuracy_rows(f, md);
  fputc('\n', f);
  if (md) {
    fputs("### `[output]`\n\n", f);
    table_head(f, 1);
  } else {
    fputs("[output]:\n", f);
  }
  const sc_key_info *ok = sc_scene_section_keys("output", &n);
  key_rows(f, ok, n, md);
}
