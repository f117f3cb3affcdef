/* Task `branch`: continuation of a periodic orbit in one parameter. */
#include <math.h>

#include "cli/tasks.h"
#include "slipcont/branch.h"

static const sc_key_info branch_keys[] = {
    {"parameter", SC_KEY_PARAM, 1, NULL, 0, 0, 0, 0, NULL,
     "the model parameter continued"},
};

static int branch_run(sc_cli_run *r) {
  return sc_fail(r->msg, SC_EINTERNAL, "branch: not yet");
}

const sc_cli_task sc_cli_task_branch = {
    .type = {.kind = "branch",
             .doc = "continuation of a periodic orbit in one parameter",
             .keys = branch_keys,
             .nkeys = sizeof branch_keys / sizeof branch_keys[0],
             .check = NULL},
    .outputs = "branch.csv, points.csv",
    .run = branch_run,
};
