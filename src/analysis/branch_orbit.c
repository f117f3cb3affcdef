/* Branches of periodic orbits in one parameter. */
#include "slipcont/branch.h"

const char *sc_point_label_text(sc_point_label l) {
  static const char *t[] = {"LP", "PD", "GR", "CS", "SW", "DI", "EP"};
  return (unsigned)l < sizeof t / sizeof t[0] ? t[l] : "??";
}
