/* Classification of a located itinerary change of a periodic orbit
 * (a discontinuity-induced bifurcation) by the degeneracy found there:
 * MODEL.md, "What the bifurcations look like on the map". */
#include <math.h>
#include <stdio.h>

#include "slipcont/branch.h"

static const char *mode_text(int mode) {
  switch (mode) {
  case SC_BK2_SLIP1: return "1 (block 1 slips alone)";
  case SC_BK2_SLIP2: return "2 (block 2 slips alone)";
  case SC_BK2_SLIP12: return "12 (both blocks slip)";
  default: return "?";
  }
}

sc_point_label sc_dib_classify(const sc_map_value *a, const sc_map_value *b,
                               double *degeneracy, char *note, size_t len) {
  const sc_map_value *side[2] = {a, b};
  double best = HUGE_VAL;
  int kind = -1;
  const sc_map_value *at = a;
  for (int k = 0; k < 2; k++) {
    const sc_map_value *v = side[k];
    if (!v) continue;
    double m[3] = {v->graze_margin, v->gsp_gap, v->dstar_dist};
    for (int i = 0; i < 3; i++)
      if (fabs(m[i]) < best) best = fabs(m[i]), kind = i, at = v;
  }
  *degeneracy = best;
  if (kind < 0 || !(best <= SC_DIB_MARGIN_TOL)) {
    snprintf(note, len,
             "itinerary change without a degeneracy (smallest margin %.3g)",
             best);
    return SC_PT_DI;
  }
  switch (kind) {
  case 0:
    snprintf(note, len,
             "grazing-sliding: the re-stick of block %d ending slip mode %s "
             "is tangent (graze_margin %.3g)",
             at->graze_block, mode_text(at->graze_mode), best);
    return SC_PT_GR;
  case 1:
    snprintf(note, len,
             "crossing-sliding: a global stick phase of length 0 (block %d "
             "at its threshold when the other re-sticks; gsp_gap %.3g)",
             at->gap_block, best);
    return SC_PT_CS;
  default:
    snprintf(note, len,
             "switching: a global stick phase at d* (both blocks at their "
             "thresholds; |d - d*| = %.3g)",
             best);
    return SC_PT_SW;
  }
}
