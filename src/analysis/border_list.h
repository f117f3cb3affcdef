/* Private to src/analysis: the borders of an orbit of f^m in a list that
 * grows as needed, and a border found again by name (branch_*.c,
 * curve.c, curve_border.c). */
#ifndef SC_ANALYSIS_BORDER_LIST_H
#define SC_ANALYSIS_BORDER_LIST_H

#include "slipcont/map.h"

/* f^m at d (sc_map_iterate_ex with flags, along force or natural, codes
 * into codes) with every border: the list bl is grown (realloc) and the
 * evaluation repeated until it holds them all.  Returns the map's
 * status, or SC_ENOMEM. */
int sc_border_list_iterate(sc_map *m, double d, int period, unsigned flags,
                           const sc_itin_code *force, sc_itin_code *codes,
                           sc_border_list *bl, sc_map_value *v, sc_msg *msg);

/* The border of l that is `like` (same iterate, kind and name: equal
 * names on equal codes are the same border, models.h), or NULL. */
const sc_border *sc_border_list_find(const sc_border_list *l,
                                     const sc_border *like);

#endif
