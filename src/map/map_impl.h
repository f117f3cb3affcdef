/* The model instance, shared by the one- and n-dimensional evaluations
 * of the map layer (map.c, mapn.c). */
#ifndef SC_MAP_IMPL_H
#define SC_MAP_IMPL_H

#include "slipcont/map.h"

struct sc_map {
  const sc_model_type *type;
  double p[SC_MAXPARAM];
  int opt[SC_MAXOPTION];
  /* a whole-number option's value as text (sc_map_get_option()) */
  char opt_text[SC_MAXOPTION][16];
  /* data keys' texts (sc_map_set_data()); parameters set explicitly,
   * which the data's parameter values do not override */
  char data[SC_MAXDATA][SC_DATA_LEN];
  unsigned char p_set[SC_MAXPARAM];
  size_t dim;             /* state dimension, read after every setup */
  sc_accuracy acc;
  void *inst;             /* type->inst_size bytes, owned */
  unsigned long nevals;   /* evaluations of one iterate */
  /* n-dimensional iterates (mapn.c): one step's value and the scratch of
   * the chain rule, sized at allocation so evaluation never allocates */
  sc_mapn_value *step;    /* f and its derivatives at one point */
  double *scratch;        /* the chain rule's intermediate products */
  /* the borders of a one-component state read through eval_n_ex (the
   * chain of two blocks; map.c), taken at the first such evaluation */
  sc_bordern_list *blist;
};

/* Take / release the n-dimensional workspace of @p m (its type set);
 * return 0 or -1 when out of memory. */
int sc_mapn_work_alloc(sc_map *m);
void sc_mapn_work_free(sc_map *m);

/* Append @p s to the itinerary text @p dst (SC_ITIN_LEN bytes), cutting
 * with "..." when full. */
void sc_map_itin_append(char *dst, const char *s);

#endif
