/* Recomputes every point of a fold or flip curve (a curve task's
 * curve.csv) from the map layer alone, for curve_examples.sh: at each
 * row's (x, y), f^m from the row's d by sc_map_iterate(), with nothing of
 * the continuation (no Newton, no forced itinerary, no border location).
 * Where the itinerary followed is the row's, the promise of the scene is
 * checked: |f^m(d) - d| <= 1e-10 and |(f^m)'(d) - M| <= 1e-10 (M = 1 for
 * a fold, -1 for a flip).  Rows past a border, where the curve follows
 * its start's itinerary by a forced evaluation (docs/curves.md), take
 * another itinerary here and are counted, not checked; at least half of
 * the rows must be checked.
 *
 *   curve_points SCENE CURVE.CSV fold|flip
 *
 * Prints the worst of each residual and the counts; exit status 0 if
 * every checked row holds, 1 otherwise, 2 on bad arguments.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/tasks.h"
#include "slipcont/io.h"
#include "slipcont/map.h"

/* The scenes' promise: every point on its defining system to 1e-10. */
#define PROMISE 1e-10

int main(int argc, char **argv) {
  if (argc != 4 || (strcmp(argv[3], "fold") && strcmp(argv[3], "flip"))) {
    fprintf(stderr, "usage: curve_points SCENE CURVE.CSV fold|flip\n");
    return 2;
  }
  const double target = strcmp(argv[3], "fold") == 0 ? 1 : -1;
  size_t ntypes;
  sc_scene_options o = {0};
  o.tasks = sc_cli_task_types(&ntypes);
  o.ntasks = ntypes;
  sc_scene *s = NULL;
  sc_msg msg;
  if (sc_scene_load(argv[1], &o, &s, &msg)) {
    fprintf(stderr, "curve_points: %s\n", msg.text);
    return 2;
  }
  sc_map *m = sc_scene_map(s);
  FILE *f = fopen(argv[2], "r");
  char line[4096], xname[64], yname[64];
  if (!f || !fgets(line, sizeof line, f) ||
      sscanf(line, "%63[^,],%63[^,],", xname, yname) != 2) {
    fprintf(stderr, "curve_points: cannot read the header of %s\n", argv[2]);
    sc_scene_free(s);
    if (f) fclose(f);
    return 2;
  }
  int ix = sc_map_param_index(m, xname), iy = sc_map_param_index(m, yname);
  if (ix < 0 || iy < 0) {
    fprintf(stderr, "curve_points: %s or %s is not a parameter\n", xname,
            yname);
    sc_scene_free(s);
    fclose(f);
    return 2;
  }
  long rows = 0, checked = 0, bad = 0;
  double worst_f = 0, worst_m = 0;
  while (fgets(line, sizeof line, f)) {
    double x, y, d;
    int period;
    char itin[SC_ITIN_LEN];
    if (sscanf(line, "%lf,%lf,%lf,%d,%*[^,],%*[^,],%255[^\n]", &x, &y, &d,
               &period, itin) != 5)
      continue; /* a blank line between pieces */
    rows++;
    sc_map_value v;
    if (sc_map_set_param_by_name(m, xname, x, &msg) ||
        sc_map_set_param_by_name(m, yname, y, &msg) ||
        sc_map_iterate(m, d, period, SC_EVAL_DERIV | SC_EVAL_ITINERARY, &v,
                       &msg) ||
        strcmp(v.itinerary, itin) != 0)
      continue; /* past a border: forced in the curve, not here */
    checked++;
    double ef = fabs(v.f - d), em = fabs(v.dfdd - target);
    worst_f = fmax(worst_f, ef);
    worst_m = fmax(worst_m, em);
    if (!(ef <= PROMISE && em <= PROMISE)) {
      bad++;
      printf("  %s = %.17g, %s = %.17g, d = %.17g: |f^%d(d) - d| = %.3g, "
             "|f' - (%g)| = %.3g\n", xname, x, yname, y, d, period, ef,
             target, em);
    }
  }
  fclose(f);
  sc_scene_free(s);
  printf("%ld rows, %ld on their own itinerary: worst |f^m(d) - d| = %.3g, "
         "worst |(f^m)' - (%g)| = %.3g (promise %g); %ld beyond it\n",
         rows, checked, worst_f, target, worst_m, PROMISE, bad);
  return bad || rows == 0 || 2 * checked < rows;
}
