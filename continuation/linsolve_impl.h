/* Private: the backend table behind sc_linsolve_type and the generic
 * solver object.  Only continuation/linsolve*.c include this. */
#ifndef SC_LINSOLVE_IMPL_H
#define SC_LINSOLVE_IMPL_H

#include <float.h>

#include "slipcont/linalg.h"

/* A factorization whose pivot ratio min |U_kk| / max |U_kk| is at or below
 * the unit roundoff carries no significant digit in its smallest pivot:
 * such a matrix is reported as numerically singular. */
#define SC_LINSOLVE_SING_RATIO DBL_EPSILON

/* The pattern, shared by every backend (owned copies). */
typedef struct {
  int n, nnz;
  int *colptr; /* n + 1 */
  int *rowind; /* nnz */
} sc_pattern;

struct sc_linsolve_type {
  const char *name;
  size_t state_size;
  /* Prepare the zeroed @p state for pattern @p p (kept alive by the
   * caller until release). */
  int (*init)(void *state, const sc_pattern *p, sc_msg *msg);
  void (*release)(void *state);
  /* Factor; set *refactored = 1 when the pivot order was reused. */
  int (*factor)(void *state, const sc_pattern *p, const double *val,
                int *refactored, sc_msg *msg);
  int (*solve)(void *state, double *b, sc_msg *msg);
  void (*det)(const void *state, int *sign, double *logabs);
  int (*rcond)(void *state, const sc_pattern *p, double *rcond,
               sc_msg *msg);
  double (*pivot_ratio)(const void *state);
};

/* Sign of a permutation perm[0..n-1] (a bijection of 0..n-1), using
 * @p mark (n chars) as workspace: (-1)^(n - number of cycles). */
int sc_perm_sign(int n, const int *perm, unsigned char *mark);

extern const sc_linsolve_type sc_linsolve_dense_type;
extern const sc_linsolve_type sc_linsolve_klu_type;

#endif
