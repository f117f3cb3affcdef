/* A downstream program that uses the scene layer (libslipcont_io) with a
 * task kind of its own, "iterate" (one key, `d0`): it parses a scene held
 * in memory, reads the model it describes and the task's key, and
 * evaluates the event map once.  Expected: the values come back as
 * written and f(d0) is finite; a d0 outside its range is refused. */
#include <math.h>
#include <stdio.h>

#include <slipcont/io.h>

static const sc_key_info iterate_keys[] = {
    {"d0", SC_KEY_REAL, 1, NULL, -1, 1, 0, 0, NULL, "starting point"},
};
static const sc_task_type iterate = {"iterate", "iterate the map once",
                                     iterate_keys, 1, NULL};

int main(void) {
  const char *text = "[model]\nname = bk2\nalpha = 3\nv = 0.025\n"
                     "[task]\nkind = iterate\nd0 = 0.02\n";
  const sc_task_type *tasks[] = {&iterate};
  sc_msg msg;
  sc_scene *s;
  sc_scene_options opts = {0};
  opts.tasks = tasks;
  opts.ntasks = 1;
  /* Out of range: refused with the key and its range in the message. */
  if (sc_scene_parse("bad", "[model]\nname = bk2\n[task]\nkind = iterate\n"
                     "d0 = 7\n", &opts, &s, &msg) != SC_EINVAL) {
    fprintf(stderr, "d0 = 7 was accepted\n");
    return 1;
  }
  printf("refused: %s\n", msg.text);
  if (sc_scene_parse("inline", text, &opts, &s, &msg)) {
    fprintf(stderr, "%s\n", msg.text);
    return 1;
  }
  sc_map *m = sc_scene_map(s);
  int ia = sc_map_param_index(m, "alpha");
  double alpha = ia >= 0 ? sc_map_get_param(m, (size_t)ia) : NAN;
  sc_map_value r;
  if (sc_map_eval(m, sc_scene_real(s, "d0"), 0, &r, &msg)) {
    fprintf(stderr, "%s\n", msg.text);
    sc_scene_free(s);
    return 1;
  }
  double d0 = sc_scene_real(s, "d0");
  printf("scene %s: alpha = %g, f(%g) = %.13f\n", sc_scene_name(s), alpha,
         d0, r.f);
  sc_scene_free(s);
  return alpha == 3 && d0 == 0.02 && isfinite(r.f) ? 0 : 1;
}
