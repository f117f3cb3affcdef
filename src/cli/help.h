/* Help texts and key tables of the `slipcont` program, generated from
 * the tables of models, accuracy, scene sections and tasks.  @p md
 * selects Markdown (docs/guide.md) over plain text. */
#ifndef SC_CLI_HELP_H
#define SC_CLI_HELP_H

#include <stdio.h>

#include "cli/tasks.h"
#include "slipcont/models.h"

/** The keys of one task kind. */
void sc_cli_print_task_keys(FILE *f, const sc_cli_task *t, int md);
/** One model: parameters with ranges and defaults, options with values. */
void sc_cli_print_model(FILE *f, const sc_model_type *t, int md);
/** Every built-in model. */
void sc_cli_print_models(FILE *f, int md);
/** Every key of every section. */
void sc_cli_print_keys(FILE *f, int md);

#endif
