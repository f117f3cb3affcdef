/* The borders of an orbit in a growing list (border_list.h). */
#include <stdlib.h>
#include <string.h>

#include "analysis/border_list.h"

int sc_border_list_iterate(sc_map *m, double d, int period, unsigned flags,
                           const sc_itin_code *force, sc_itin_code *codes,
                           sc_border_list *bl, sc_map_value *v, sc_msg *msg) {
  for (;;) {
    bl->n = 0;
    int st =
        sc_map_iterate_ex(m, d, period, flags, force, codes, bl, v, msg);
    if (st || bl->n <= bl->cap) return st;
    size_t nc = 2 * bl->n;
    sc_border *q = realloc(bl->b, nc * sizeof *q);
    if (!q) return sc_fail(msg, SC_ENOMEM, "borders: out of memory");
    bl->b = q;
    bl->cap = nc;
  }
}

const sc_border *sc_border_list_find(const sc_border_list *l,
                                     const sc_border *like) {
  for (size_t i = 0; i < l->n && i < l->cap; i++)
    if (l->b[i].iterate == like->iterate && l->b[i].kind == like->kind &&
        strcmp(l->b[i].name, like->name) == 0)
      return &l->b[i];
  return NULL;
}
