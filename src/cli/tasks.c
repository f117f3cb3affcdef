/* The registry of task kinds.  To add one, add a line X(name) below
 * (the constant sc_cli_task_name is defined in src/cli/task_name.c);
 * see the contract in tasks.h. */
#include "cli/tasks.h"

#include <string.h>

#define SC_CLI_TASK_LIST(X) \
  X(orbit)                  \
  X(map)                    \
  X(chart)                  \
  X(fixed_point) X(branch)  \
  X(sweep)                  \
  X(curve)                  \
  X(catalogue)

#define SC_CLI_TASK_DECLARE_(name) extern const sc_cli_task sc_cli_task_##name;
SC_CLI_TASK_LIST(SC_CLI_TASK_DECLARE_)
#undef SC_CLI_TASK_DECLARE_

static const sc_cli_task *const tasks[] = {
#define SC_CLI_TASK_ENTRY_(name) &sc_cli_task_##name,
    SC_CLI_TASK_LIST(SC_CLI_TASK_ENTRY_)
#undef SC_CLI_TASK_ENTRY_
};

static const sc_task_type *const types[] = {
#define SC_CLI_TASK_TYPE_(name) &sc_cli_task_##name.type,
    SC_CLI_TASK_LIST(SC_CLI_TASK_TYPE_)
#undef SC_CLI_TASK_TYPE_
};

#define NTASKS (sizeof tasks / sizeof tasks[0])

size_t sc_cli_task_count(void) { return NTASKS; }

const sc_cli_task *sc_cli_task_get(size_t i) {
  return i < NTASKS ? tasks[i] : NULL;
}

const sc_cli_task *sc_cli_task_find(const char *kind) {
  for (size_t i = 0; kind && i < NTASKS; i++)
    if (strcmp(tasks[i]->type.kind, kind) == 0) return tasks[i];
  return NULL;
}

const sc_task_type *const *sc_cli_task_types(size_t *n) {
  *n = NTASKS;
  return types;
}
