/* libFuzzer target: a scene file's bytes through parsing and validation
 * with every task kind of the program, then a short run of the model the
 * scene describes (a few map evaluations from the scene's state).  Any
 * crash, sanitizer report, leak or hang is a defect; a refused scene is
 * an ordinary outcome.
 *
 *   CC=clang cmake -S . -B build-fuzz -DSLIPCONT_FUZZ=ON
 *   cmake --build build-fuzz --target fuzz_scene
 *   build-fuzz/fuzz_scene -max_total_time=60 NEW_CORPUS fuzz/corpus
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cli/tasks.h"
#include "slipcont/io.h"
#include "slipcont/map.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > 1 << 16) return 0; /* the parser's own limit is tested elsewhere */
  char *text = malloc(size + 1);
  if (!text) return 0;
  memcpy(text, data, size);
  text[size] = '\0';
  size_t ntypes;
  const sc_task_type *const *types = sc_cli_task_types(&ntypes);
  sc_scene_options o = {0};
  o.tasks = types;
  o.ntasks = ntypes;
  sc_scene *s = NULL;
  sc_msg msg;
  if (sc_scene_parse("fuzz.ini", text, &o, &s, &msg) == SC_OK) {
    sc_map *m = sc_scene_map(s);
    sc_map_value v;
    double d = 0.01;
    for (int k = 0; k < 4; k++) {
      if (sc_map_eval(m, d, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v, &msg))
        break;
      d = v.f;
    }
    sc_scene_free(s);
  }
  free(text);
  return 0;
}
